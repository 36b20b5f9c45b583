//! The check that `@` has its length first: `length @ angle`. A polar term whose length is a
//! bare name of an angle (`th @ s` for `s @ th`) compiles as a link of `th` radians turned by
//! `s`, a mechanism that solves to wrong angles, or not at all, and whose results change with
//! the unit of length; it is refused at the term, with the swap to write, unless the angle of
//! `@` is an angle too by the rest of the mechanism (`psi @ phi`, `phi` the crank's angle):
//! swapping cannot help there, and a length is to be written. A length that is an expression
//! is judged by its kind, as a coordinate is (below): `(2 * phi) @ th` and
//! `norm((phi, psi)) @ th` are refused, with a length to write and, unless `th` is an angle
//! too, the swap. The angle of a term found swapped (`l` in `psi @ l`) is an angle only by
//! that mistake: it is the length it is everywhere else, so one mistake is told once; so is
//! the angle of a term whose length is an expression of an angle (`l` in `(2 * psi) @ l`). A
//! term whose length is written in degrees says nothing of its angle either. An angle of `@`
//! that holds an angle offset by names of no known kind (`psi @ (phi + e)`) is an angle if they
//! are angles, a mix of an angle and a length if not, a length in neither case: no swap is
//! told, but a length to write and, if they are lengths, an angle for them. A length that is
//! an angle only by such terms (`l` by `psi @ l`) where its own angle is one (`l @ psi`, with
//! `0.5 * l @ psi` elsewhere) is right as written: the other term is told, and only it; so is
//! one whose length is an angle only by a term found swapped (`psi @ l` beside `th @ psi`, `th`
//! an angle elsewhere: the one swap of `th @ psi` mends both).
//!
//! Two terms that take two names in opposite roles, bare or expressions alike (`l @ psi`
//! beside `psi @ l`, `(2 * psi) @ l` or `0.5 * l @ psi` beside either), are judged together
//! by one evidence, the two set aside: a name that the test of an angle finds one without
//! them (in a sine or cosine elsewhere, set by an `eq` to an angle, `atan2(dy, dx)` or
//! `2 * phi`) is an angle; one in a coordinate of a position, or in a sum beside a length, a
//! length. Where it tells which name is the length, the term that takes it as its angle is told,
//! and only it, in whichever order they are written; where nothing tells (or what tells
//! contradicts itself), the first written is one error that says so, naming both readings.
//!
//! A coordinate of a Cartesian vector that is an angle (`(x, phi)`) is refused too where the
//! vector is a position: in a loop, which adds lengths, a point, the point a force acts at, a
//! centre of mass, and a vector `let` that one of these uses. A coordinate that is no bare name
//! is judged by the dimension of its expression ([`crate::graph::dims`]): `phi + 0.0`, `2 * phi`,
//! a scalar `let` of an angle and `dot((phi, 0), (1, 0))` are angles, `r * phi` and `sin(phi)`
//! are not. A vector scaled by a quantity that varies (`l * (phi, 0)`) has coordinates of its
//! kind, and is not judged; a direction scaled so (`phi * (0, 1)`) has the quantity for a
//! coordinate. The vectors a function takes are no positions (`dot`, `cross`, `norm`, `angle`;
//! `rot` gives its vector back turned, a position still).
//!
//! A scalar sum, difference or `eq` that puts an angle beside a length (`s == phi`, `x + psi`,
//! with `s` and `x` written elsewhere as coordinates of positions or lengths of `@`) is refused
//! at the operation, in an equation, a `let`, a `point` or an `output` alike: its value too
//! changes with the unit of length. A sum that is the angle of a polar term already told to mix
//! the two (`psi @ (phi + e)`) is not told again. So is a vector of an angle and a length built
//! where it is no position (`(x, psi)` given to `norm`, `dot`, `cross`, `angle` or `rot`,
//! `(x, 0) + (0, psi)`): its magnitude, products and direction change so too. It is told where
//! it is built, once (`2 * (x, psi)` is that vector's mistake); a position's vector is told at
//! its coordinate.
//!
//! Only a name that is an angle by the one test of [`super::angles`] is refused, the test a
//! body's `turns` takes too: it enters a sine, cosine or `@` as a whole multiple of itself
//! elsewhere, an `eq` sets it to an angle (`atan2(dy, dx)`, or for an unknown an expression of
//! angles, `y == 2 * psi`, the kind the plan labels its column with, `y [rad]`), or its value
//! is written in degrees (a scalar `let` of such a value too). A name written as a length
//! elsewhere (a coordinate of a position, the length of `@`) that a sine takes only as a
//! fraction of itself (`sin(x / 2)`, the 2 perhaps a radius written as a number) is of no
//! certain kind, and one that an `eq` sets to an expression of angles a length, the `eq` the
//! mistake told. A length times an angle (`(r * phi) @ 0`), a constant, or a name of no known
//! kind stays the length it is written as.

use super::angles::{Evidence, Verdicts};
use super::lower::{Coordinate, Lowerer, NamedCoordinate, NamedLength, Place, ScalarPair, VectorPair};
use super::scope::leaf_name;
use crate::graph::dag::{Graph, Leaf, NodeId, Op};
use crate::graph::dims::{self, Dim};
use crate::graph::multiples;
use std::collections::{HashMap, HashSet};

/// The verdicts on which names are angles, shared by the checks of coordinates and of polar
/// terms: one per name, however many places write it.
pub(super) struct Angles {
    /// The mechanism's equations and outputs, where an angle is seen to be one.
    roots: Vec<NodeId>,
    residuals: Vec<NodeId>,
    /// The arguments of the sines and cosines below `roots`, found at the first verdict, but
    /// those of the terms `set_aside`.
    arguments: Option<Vec<NodeId>>,
    /// The coordinates of the polar terms whose length is written in degrees (`deg(3) @ e`,
    /// `th @ s` with `th = deg(20)`): such a term is a mistake whichever way it is mended, and
    /// makes its angle no angle (in `th @ s`, `s` is as likely the length).
    set_aside: Vec<NodeId>,
    /// The parameters and unknowns whose values are written in degrees.
    degrees: Vec<Leaf>,
    /// The verdicts of [`Angles::is_angle`], found over the whole mechanism.
    verdicts: Verdicts,
    /// The names written bare as a coordinate of a position or as the length of `@` that are
    /// not angles: lengths, beside which an angle is a unit mix.
    lengths: HashSet<Leaf>,
    /// The names written bare as a coordinate of a position or as the length of `@`: lengths
    /// by their place, against which a name is an angle only if it enters a sine or cosine
    /// whole (`l @ q`, `sin(2 * q)`), not only as a fraction (`sin(x / 2)`, where the divisor
    /// may be a length written as a number), or an `eq` sets it to one.
    placed_as_lengths: HashSet<Leaf>,
    /// The angles of polar terms found swapped (`l` in `psi @ l`): lengths written in the
    /// wrong place, angles only by that mistake, so no angle anywhere else.
    swapped: HashSet<Leaf>,
    /// The angles of polar terms told to mix an angle and a length (`phi + e` in
    /// `psi @ (phi + e)`): a sum within one is that mistake, told once.
    told_mixed: Vec<NodeId>,
}

impl Angles {
    /// `residuals` and `columns` are the mechanism's equations and outputs; `degrees` the
    /// parameters and unknowns whose values are written in degrees.
    pub(super) fn new(residuals: &[NodeId], columns: &[NodeId], degrees: Vec<Leaf>) -> Self {
        let roots = residuals.iter().chain(columns).copied().collect();
        Angles {
            roots,
            residuals: residuals.to_vec(),
            arguments: None,
            set_aside: Vec::new(),
            degrees,
            verdicts: Verdicts::default(),
            lengths: HashSet::new(),
            placed_as_lengths: HashSet::new(),
            swapped: HashSet::new(),
            told_mixed: Vec::new(),
        }
    }

    /// Why `leaf` (written `name`) is an angle: its value is in degrees, or the mechanism
    /// makes it one; `None` when it is neither, or is the angle of a term found swapped.
    pub(super) fn why(&mut self, g: &Graph, leaf: Leaf, name: &str) -> Option<String> {
        if self.swapped.contains(&leaf) {
            return None;
        }
        let degrees = self.degrees.contains(&leaf);
        let known = self.is_angle(g, leaf);
        why_an_angle(degrees, known, name)
    }

    /// Whether `leaf` is an angle by the whole mechanism ([`Evidence::is_angle`], over the
    /// trigonometric arguments of all but the terms `set_aside`), each verdict found once. The
    /// angle of a term found swapped is one here still, as it is there: a body's `turns` takes
    /// it as written, and only [`Angles::why`] makes it the length it is elsewhere.
    pub(super) fn is_angle(&mut self, g: &Graph, leaf: Leaf) -> bool {
        let (roots, set_aside) = (&self.roots, &self.set_aside);
        let arguments = self.arguments.get_or_insert_with(|| multiples::trig_arguments_avoiding(g, roots, set_aside));
        let evidence = Evidence {
            g,
            residuals: &self.residuals,
            arguments,
            degrees: &self.degrees,
            placed: &self.placed_as_lengths,
            swapped: &self.swapped,
        };
        evidence.is_angle(leaf, &mut self.verdicts)
    }

    /// Whether `leaf`, written bare as a coordinate of a position or as the length of `@`, is
    /// no angle by that place alone: a sine takes only a fraction of it (`sin(x / 2)`), or an
    /// `eq` sets it to an expression of angles. For the message that refuses it as an angle.
    pub(super) fn angle_but_for_its_place(&mut self, g: &Graph, leaf: Leaf) -> bool {
        if !self.placed_as_lengths.contains(&leaf) || self.is_angle(g, leaf) {
            return false;
        }
        let placed: HashSet<Leaf> = self.placed_as_lengths.iter().copied().filter(|&l| l != leaf).collect();
        let evidence = Evidence {
            g,
            residuals: &self.residuals,
            arguments: self.arguments.as_deref().unwrap_or_default(),
            degrees: &self.degrees,
            placed: &placed,
            swapped: &self.swapped,
        };
        evidence.is_angle(leaf, &mut Verdicts::default())
    }

    /// Whether `leaf` is an angle because its value is written in degrees.
    pub(super) fn in_degrees(&self, leaf: Leaf) -> bool {
        self.degrees.contains(&leaf) && !self.swapped.contains(&leaf)
    }

    /// Whether `leaf` is an angle by what the rest of the mechanism says of it, the terms in
    /// question set aside: [`Evidence::is_angle`] over `arguments` (the trigonometric arguments
    /// found without those terms), as [`Angles::why`] judges over the whole mechanism (an
    /// unknown an `eq` sets to `2 * psi` is one where `psi` is one apart from them), but not the
    /// angle of a term found swapped.
    fn apart(&self, g: &Graph, leaf: Leaf, arguments: &[NodeId]) -> bool {
        let evidence = Evidence {
            g,
            residuals: &self.residuals,
            arguments,
            degrees: &self.degrees,
            placed: &self.placed_as_lengths,
            swapped: &self.swapped,
        };
        !self.swapped.contains(&leaf) && evidence.is_angle(leaf, &mut Verdicts::default())
    }
}

/// Notes what the places of names say before any is judged: the names that `lw` writes as
/// lengths (a coordinate of a position, the length of `@`), and the polar terms whose length
/// is written in degrees, which make their angle no angle.
pub(super) fn note_places(lw: &Lowerer, angles: &mut Angles) {
    let degrees = |t: &&NamedLength| t.degrees || t.leaf.is_some_and(|l| angles.degrees.contains(&l));
    let set_aside: Vec<NodeId> = lw.named_lengths.iter().filter(degrees).flat_map(|t| t.products).collect();
    angles.set_aside = set_aside;
    let coordinates = lw.named_coordinates.iter().filter(|c| !matches!(c.place, Place::Let(_)));
    let names = coordinates.filter_map(|c| match c.what {
        Coordinate::Name(leaf) => Some(leaf),
        _ => None,
    });
    let lengths = lw.named_lengths.iter().filter_map(|t| t.leaf);
    angles.placed_as_lengths.extend(names.chain(lengths));
}

/// The errors for every polar term noted in `lw` whose length is an angle, in the order they are
/// written: a name that is one, a value in degrees, or an expression of one (`(2 * phi) @ th`,
/// `(phi + 0.0) @ th`, `norm((phi, psi)) @ th`) judged by its kind, as a coordinate is
/// (`(r * phi) @ th` is a length). Each says to swap the two only where the angle of `@` is no
/// angle by the rest of the mechanism (in `psi @ phi`, with `phi` an angle elsewhere, swapping
/// cannot help). Pairs of terms of two names in opposite roles first ([`opposite_orders`]),
/// then names and degrees: the angle of a term they find swapped (`l` in `psi @ l`) is an angle
/// only by that mistake, and makes nothing else one (`0.5 * l @ psi`, `(x, 2 * l)` and `x + l`
/// are told nothing more). Run before the checks of coordinates and sums, which take those
/// angles for lengths.
pub(super) fn terms(lw: &Lowerer, angles: &mut Angles) -> Vec<syn::Error> {
    let suspects = suspects(lw, angles);
    // The terms told with another one, as the other order of its two names.
    let mut told: HashSet<usize> = HashSet::new();
    let mut found = opposite_orders(lw, angles, &mut told);
    found.extend(direct_terms(lw, angles, &suspects, &told));
    found.extend(expression_terms(lw, angles, &suspects, &told));
    // Each error is kept with its term's index, so that they read in the order written.
    found.sort_by_key(|(i, _)| *i);
    found.into_iter().map(|(_, e)| e).collect()
}

/// Whether the length of `t` is a bare name or written in degrees: such a term is judged by
/// that name (or unit) alone, an expression by the kind of what it is made from.
fn is_direct(t: &NamedLength) -> bool {
    t.leaf.is_some() || t.degrees
}

/// The coordinates of the terms whose length is an angle by its name or its degrees. Such a
/// term says nothing of its angle (in `th @ l` and `psi @ l`, `l` is a length), so they are
/// set aside whenever the rest of the mechanism is asked what a term's names are.
fn suspects(lw: &Lowerer, angles: &mut Angles) -> Vec<NodeId> {
    let mut suspects = angles.set_aside.clone();
    for t in lw.named_lengths.iter().filter(|t| is_direct(t)) {
        if t.leaf.is_some_and(|leaf| angles.why(&lw.graph, leaf, &t.length).is_some()) {
            suspects.extend(t.products);
        }
    }
    suspects
}

/// The verdict on one term whose length is a bare name or written in degrees.
enum Direct {
    /// Nothing to tell: its length is a length, or it is right as written and another term is
    /// the one told.
    Fine,
    /// Its length is an angle: the error, with the fix.
    Error(syn::Error),
}

/// The errors for the terms whose length is a bare name or written in degrees, each with the
/// index of its term, but those `told` already. They are judged before the expressions: the
/// angle of a term found swapped (`l` in `psi @ l`) is an angle only by that mistake, and
/// makes nothing else one. Those whose length is an angle by the rest of the mechanism go
/// first: the angle of such a term found swapped is then a length for a term whose length is
/// an angle only by it (`psi` in `psi @ l` beside `th @ psi`, `th` an angle elsewhere: one swap
/// mends both), which is right as written.
fn direct_terms(
    lw: &Lowerer,
    angles: &mut Angles,
    suspects: &[NodeId],
    told: &HashSet<usize>,
) -> Vec<(usize, syn::Error)> {
    // Found at the first term with an angle to judge: most mechanisms have none.
    let mut arguments = None;
    let direct = lw.named_lengths.iter().enumerate().filter(|(i, t)| is_direct(t) && !told.contains(i));
    let (later, first): (Vec<_>, Vec<_>) =
        direct.partition(|&(_, t)| angle_only_by_suspects(lw, angles, t, suspects, &mut arguments));
    let mut found = Vec::new();
    for (i, t) in first.into_iter().chain(later) {
        if let Direct::Error(e) = direct_verdict(lw, angles, t, suspects, &mut arguments) {
            found.push((i, e));
        }
    }
    found
}

/// Whether the length of `t` is a name that is an angle only by the `suspects`, the terms whose
/// length is an angle (`psi` in `psi @ l`, by `th @ psi`). `arguments` is as for
/// [`direct_verdict`].
fn angle_only_by_suspects(
    lw: &Lowerer,
    angles: &Angles,
    t: &NamedLength,
    suspects: &[NodeId],
    arguments: &mut Option<Vec<NodeId>>,
) -> bool {
    let Some(leaf) = t.leaf.filter(|_| !t.degrees && suspects.contains(&t.products[0])) else { return false };
    let arguments =
        arguments.get_or_insert_with(|| multiples::trig_arguments_avoiding(&lw.graph, &angles.roots, suspects));
    !angles.apart(&lw.graph, leaf, arguments)
}

/// The verdict on the term `t`, of a bare name or degrees. `arguments` holds the
/// trigonometric arguments found without the `suspects`, computed here the first time a term
/// needs them. A term found right or swapped marks the names it shows to be lengths.
fn direct_verdict(
    lw: &Lowerer,
    angles: &mut Angles,
    t: &NamedLength,
    suspects: &[NodeId],
    arguments: &mut Option<Vec<NodeId>>,
) -> Direct {
    let Some(why) = why_direct(lw, angles, t) else {
        angles.lengths.extend(t.leaf);
        return Direct::Fine;
    };
    if t.constant_angle {
        return Direct::Error(length_error(t, &why, &arc(t)));
    }
    let arguments =
        arguments.get_or_insert_with(|| multiples::trig_arguments_avoiding(&lw.graph, &angles.roots, suspects));
    if let Some(leaf) = right_apart(lw, angles, t, arguments) {
        angles.swapped.insert(leaf);
        angles.lengths.insert(leaf);
        return Direct::Fine;
    }
    let fix = fix_by_angle(lw, angles, t, arguments, swap);
    Direct::Error(length_error(t, &why, &fix))
}

/// Why the length of `t`, a bare name or written in degrees, is an angle; `None` if it is not.
fn why_direct(lw: &Lowerer, angles: &mut Angles, t: &NamedLength) -> Option<String> {
    match t.leaf {
        Some(leaf) if !t.degrees => angles.why(&lw.graph, leaf, &t.length),
        _ => why_an_angle(true, false, &t.length),
    }
}

/// The errors for the terms whose length is an expression of an angle, each with the index of
/// its term.
fn expression_terms(
    lw: &Lowerer,
    angles: &mut Angles,
    suspects: &[NodeId],
    told: &HashSet<usize>,
) -> Vec<(usize, syn::Error)> {
    let mut found = Vec::new();
    for (i, t) in lw.named_lengths.iter().enumerate().filter(|(_, t)| !is_direct(t)) {
        if !told.contains(&i)
            && let Direct::Error(e) = expression_verdict(lw, angles, t, suspects)
        {
            found.push((i, e));
        }
    }
    found
}

/// The verdict on the term `t`, whose length is an expression: an error if its kind is
/// an angle.
fn expression_verdict(lw: &Lowerer, angles: &mut Angles, t: &NamedLength, suspects: &[NodeId]) -> Direct {
    let Some(why) = why_expression(lw, angles, t.node) else { return Direct::Fine };
    if t.constant_angle {
        return Direct::Error(length_error(t, &why, &arc(t)));
    }
    // An expression is seldom a swapped angle (`(2 * phi) @ psi` turns by `psi`, and the
    // angle of `@` is an angle by that term alone): both ways are told, where both could be.
    // Either way the angle is an angle only by this mistake (`l` in `(2 * psi) @ l`), as a
    // swapped term's is: a length for every later check, so that one mistake is told once.
    let avoided: Vec<NodeId> = suspects.iter().chain(&t.products).copied().collect();
    let arguments = multiples::trig_arguments_avoiding(&lw.graph, &angles.roots, &avoided);
    Direct::Error(length_error(t, &why, &fix_by_angle(lw, angles, t, &arguments, arc_or_swap)))
}

/// The fix for the term `t`, whose length is an angle, by what its angle is apart from it
/// (`arguments`: the trigonometric arguments found without it): `if_length` where the angle is
/// no angle, whose leaves are then lengths written in the wrong place.
fn fix_by_angle(
    lw: &Lowerer,
    angles: &mut Angles,
    t: &NamedLength,
    arguments: &[NodeId],
    if_length: fn(&NamedLength) -> String,
) -> String {
    // `beta @ beta`, `(2 * beta) @ beta`: the swap keeps the name in both places, whatever
    // it is elsewhere.
    if let Op::Leaf(angle) = lw.graph.op(t.angle_node)
        && lw.graph.leaves_of(&[t.node]).contains(&angle)
    {
        return both_angles(t);
    }
    match angle_of(lw, angles, t, arguments) {
        AngleOf::Angle => both_angles(t),
        AngleOf::Mixed { angle, others } => mixed(lw, angles, t, angle, others),
        AngleOf::Length(leaves) => {
            angles.swapped.extend(leaves);
            if_length(t)
        }
    }
}

/// The fix for the term `t` whose length is an expression of an angle and whose angle is no
/// angle: a length, or the swap.
fn arc_or_swap(t: &NamedLength) -> String {
    format!("{}, or if the two are swapped, write `{} @ {}`", arc(t), t.angle, t.factor)
}

/// The name that is the length of the term `t` (of a bare name, an angle) where it is an angle
/// only by the terms set aside, whose own length is an angle, and the angle of `t` is an angle
/// by the rest of the mechanism (`arguments`: the trigonometric arguments found without those
/// terms): `t` is right as written, and the other terms are to be swapped (`l @ psi`, with
/// `psi @ l` and `0.5 * l @ psi` elsewhere). `None` where `t` is judged by its angle.
fn right_apart(lw: &Lowerer, angles: &Angles, t: &NamedLength, arguments: &[NodeId]) -> Option<Leaf> {
    let length = t.leaf.filter(|&l| !t.degrees && !angles.apart(&lw.graph, l, arguments))?;
    matches!(angle_of(lw, angles, t, arguments), AngleOf::Angle).then_some(length)
}

/// The error for the term `t` whose two names (`length`, the one it takes as the length, and
/// `angle`) the term `m`, written after it, takes in the other order, with nothing else to tell
/// which is the length.
fn tie(t: &NamedLength, m: &NamedLength, [length, angle]: [&str; 2]) -> syn::Error {
    let (this, other) = (written(t), written(m));
    t.term.error(format!(
        "`{this}` and `{other}`, written after it, take `{length}` and `{angle}` in opposite orders, and nothing else in the \
         mechanism tells which is the length: `@` takes `length @ angle`, so write the two terms alike, `{this}` \
         if `{length}` is the length, `{other}` if `{angle}` is"
    ))
}

/// The term `t` as written: an expression length keeps the parentheses that make it one operand.
fn written(t: &NamedLength) -> String {
    let length = if is_direct(t) { &t.length } else { &t.factor };
    format!("{length} @ {}", t.angle)
}

/// The errors for the pairs of terms that take two names crosswise (`l @ psi` beside `psi @ l`,
/// `(2 * psi) @ l` or `0.5 * l @ psi`: a name of one's length in the other's angle, and one
/// of its angle in the other's length), bare or expressions alike, each length an angle by the
/// other term. Either term makes the other's names angles, so the verdict of either alone
/// would follow the order they are written in. Each pair is judged by the rest of the
/// mechanism ([`settle`]): where it tells which name is the length, the other name is a
/// length written in the wrong place, and the terms are left to their own verdicts, which then
/// tell the wrong one alone; where nothing tells, the first of the two gets one error naming
/// both readings, the two are `told`, and both names are lengths for every later check. A term
/// is in one pair at most, the first it makes whose lengths are still angles when it is judged:
/// a pair whose names an earlier one marked lengths is left to the terms' own verdicts.
fn opposite_orders(lw: &Lowerer, angles: &mut Angles, told: &mut HashSet<usize>) -> Vec<(usize, syn::Error)> {
    let mut found = Vec::new();
    let mut paired: HashSet<usize> = HashSet::new();
    for (i, j, names) in crosswise_pairs(lw) {
        let judged = paired.contains(&i) || paired.contains(&j);
        if judged || !length_is_angle(lw, angles, i) || !length_is_angle(lw, angles, j) {
            continue;
        }
        paired.extend([i, j]);
        match settle(lw, angles, [i, j], names) {
            Reading::Length(leaf) => {
                angles.swapped.insert(leaf);
                angles.lengths.insert(leaf);
            }
            Reading::Tie => {
                angles.swapped.extend(names);
                told.extend([i, j]);
                found.extend(pair_tie(lw, [i, j], names).map(|e| (i, e)));
            }
            Reading::Neither => {}
        }
    }
    found
}

/// The pairs `(i, j)`, `i < j`, of terms that take two names crosswise, with those names: the
/// first the `i`th term takes as its length. Terms of a constant angle (no length swapped with
/// a name) or a length in degrees (a mistake whichever way it is mended) are in none.
fn crosswise_pairs(lw: &Lowerer) -> Vec<(usize, usize, [Leaf; 2])> {
    let g = &lw.graph;
    let candidate = |t: &NamedLength| !t.degrees && !t.constant_angle;
    let sides: Vec<Option<[Vec<Leaf>; 2]>> = lw
        .named_lengths
        .iter()
        .map(|t| candidate(t).then(|| [g.leaves_of(&[t.node]), g.leaves_of(&[t.angle_node])]))
        .collect();
    let pair = |i: usize, j: usize| {
        let (Some(Some(t)), Some(Some(m))) = (sides.get(i), sides.get(j)) else { return None };
        crosswise(t, m).map(|names| (i, j, names))
    };
    (0..sides.len()).flat_map(|i| (i + 1..sides.len()).filter_map(move |j| pair(i, j))).collect()
}

/// A name of `t`'s length in `m`'s angle and one of `t`'s angle in `m`'s length, each side
/// given as its leaves `[length, angle]`.
fn crosswise([t_length, t_angle]: &[Vec<Leaf>; 2], [m_length, m_angle]: &[Vec<Leaf>; 2]) -> Option<[Leaf; 2]> {
    let length = t_length.iter().copied().find(|l| m_angle.contains(l))?;
    let angle = t_angle.iter().copied().find(|l| m_length.contains(l) && *l != length)?;
    Some([length, angle])
}

/// Whether the length of the `i`th term is an angle: a bare name that is one, or an expression
/// whose kind is one.
fn length_is_angle(lw: &Lowerer, angles: &mut Angles, i: usize) -> bool {
    let Some(t) = lw.named_lengths.get(i) else { return false };
    match t.leaf {
        Some(leaf) => angles.why(&lw.graph, leaf, &t.length).is_some(),
        None => why_expression(lw, angles, t.node).is_some(),
    }
}

/// What the rest of the mechanism says of a pair of terms that take two names crosswise.
enum Reading {
    /// This name is the length: the term that takes it as its angle is the wrong one.
    Length(Leaf),
    /// Nothing tells which is the length, or what tells contradicts itself.
    Tie,
    /// Both names are angles: each term's length is to be a length, told at each.
    Neither,
}

/// What the rest of the mechanism, the two terms `pair` set aside, says of their `names` (the
/// first the length of the first term, the angle of the other): which is the length, if
/// anything tells, by one and the same evidence whether the terms are bare or expressions.
fn settle(lw: &Lowerer, angles: &Angles, pair: [usize; 2], [a, b]: [Leaf; 2]) -> Reading {
    let products = pair.iter().filter_map(|&k| lw.named_lengths.get(k)).flat_map(|t| t.products);
    let avoided: Vec<NodeId> = angles.set_aside.iter().copied().chain(products).collect();
    let arguments = multiples::trig_arguments_avoiding(&lw.graph, &angles.roots, &avoided);
    let (ka, kb) = (kind_apart(lw, angles, a, &arguments), kind_apart(lw, angles, b, &arguments));
    let first_right = ka == Some(Kind::Length) || kb == Some(Kind::Angle);
    let second_right = ka == Some(Kind::Angle) || kb == Some(Kind::Length);
    match (first_right, second_right) {
        (true, false) => Reading::Length(a),
        (false, true) => Reading::Length(b),
        _ if ka == Some(Kind::Angle) && kb == Some(Kind::Angle) => Reading::Neither,
        _ => Reading::Tie,
    }
}

/// The kind of a name by the rest of the mechanism.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Angle,
    Length,
}

/// What the rest of the mechanism says `leaf` is (`arguments`: the trigonometric arguments
/// found with the terms in question set aside): an angle as [`Angles::apart`] finds one, a
/// length if written in a coordinate of a position or in a sum beside a length; `None` where
/// nothing tells, or both are told.
fn kind_apart(lw: &Lowerer, angles: &Angles, leaf: Leaf, arguments: &[NodeId]) -> Option<Kind> {
    let angle = angles.apart(&lw.graph, leaf, arguments);
    let length = in_a_position(lw, leaf) || beside_a_length(lw, angles, leaf);
    match (angle, length) {
        (true, false) => Some(Kind::Angle),
        (false, true) => Some(Kind::Length),
        _ => None,
    }
}

/// The tie of the terms `[i, j]`, `i < j`, that take `names` crosswise, told at the first.
fn pair_tie(lw: &Lowerer, [i, j]: [usize; 2], [a, b]: [Leaf; 2]) -> Option<syn::Error> {
    let name = |l: Leaf| leaf_name(lw, l).unwrap_or_default();
    let (t, m) = (lw.named_lengths.get(i)?, lw.named_lengths.get(j)?);
    Some(tie(t, m, [&name(a), &name(b)]))
}

/// Whether `leaf` is in a sum, difference or `eq` whose other side holds a name placed as a
/// length (`x + l`, `x == l + e`, `x` a coordinate of a position): a length by that sum.
fn beside_a_length(lw: &Lowerer, angles: &Angles, leaf: Leaf) -> bool {
    let holds = |n: NodeId, l: Leaf| lw.graph.leaves_of(&[n]).contains(&l);
    let placed =
        |n: NodeId| lw.graph.leaves_of(&[n]).iter().any(|l| *l != leaf && angles.placed_as_lengths.contains(l));
    lw.scalar_pairs.iter().any(|p| {
        let [(a, _), (b, _)] = p.sides;
        (holds(a, leaf) && placed(b)) || (holds(b, leaf) && placed(a))
    })
}

/// Whether `leaf` is written in a coordinate of a position (not a vector `let`, which may be
/// no position): a length by its place.
fn in_a_position(lw: &Lowerer, leaf: Leaf) -> bool {
    let positions = lw.named_coordinates.iter().filter(|c| !matches!(c.place, Place::Let(_)));
    positions.into_iter().any(|c| lw.graph.leaves_of(&[c.node]).contains(&leaf))
}

/// What the angle (not a constant) of a polar term whose length is an angle is, by the rest
/// of the mechanism.
enum AngleOf {
    /// An angle by the rest of the mechanism: swapping cannot help.
    Angle,
    /// An `angle` by the rest of the mechanism offset by `others`, of no known kind
    /// (`phi + e`): an angle if they are angles, a mix of an angle and a length if not, and a
    /// length in neither case, so swapping cannot help.
    Mixed { angle: Leaf, others: Vec<Leaf> },
    /// No angle but by this term: the two are swapped, and these leaves of it are lengths.
    Length(Vec<Leaf>),
}

/// What the angle of the term `t` is by the rest of the mechanism (`arguments`: the
/// trigonometric arguments found without `t` and the other terms whose length is an angle): a
/// name that only such terms make an angle (`l` in `psi @ l`) is a length written in the wrong
/// place.
fn angle_of(lw: &Lowerer, angles: &Angles, t: &NamedLength, arguments: &[NodeId]) -> AngleOf {
    let g = &lw.graph;
    let leaves = g.leaves_of(&[t.angle_node]);
    let apart: HashSet<Leaf> = leaves.iter().copied().filter(|&l| angles.apart(g, l, arguments)).collect();
    let of = |l: Leaf| if apart.contains(&l) { Dim::Angle } else { Dim::Other };
    if dims::is_angle(g, t.angle_node, &of) {
        return AngleOf::Angle;
    }
    // An angle that is none only for leaves of no known kind, and would be one were they
    // angles, is offset by them (`phi + e`), as it is not in a product (`r * phi`, an arc).
    let first = leaves.iter().copied().find(|l| apart.contains(l));
    if let Some(angle) = first
        && dims::is_angle(g, t.angle_node, &|_| Dim::Angle)
    {
        let others = leaves.into_iter().filter(|l| !apart.contains(l)).collect();
        return AngleOf::Mixed { angle, others };
    }
    AngleOf::Length(leaves.into_iter().filter(|l| !apart.contains(l)).collect())
}

/// The fix for the term `t` whose angle is an angle too: a length where the length belongs.
fn both_angles(t: &NamedLength) -> String {
    format!("`{}` is an angle too, so swapping the two cannot help; {}", bare_angle(t), arc(t))
}

/// The fix for the term `t` whose angle holds `angle`, an angle, offset by `others` of no known
/// kind (`phi + e`): a length where the length belongs, and an angle for the others if they are
/// lengths. They are angles only by this term, as a swapped term's angle is: lengths elsewhere.
fn mixed(lw: &Lowerer, angles: &mut Angles, t: &NamedLength, angle: Leaf, others: Vec<Leaf>) -> String {
    let name = |l: Leaf| format!("`{}`", leaf_name(lw, l).unwrap_or_default());
    let (shown, angle) = (bare_angle(t), name(angle));
    let (names, n) = (others.iter().map(|&l| name(l)).collect::<Vec<_>>().join(" or "), others.len());
    angles.swapped.extend(others);
    angles.told_mixed.push(t.angle_node);
    let (verb, pronoun) = if n == 1 { ("is a length", "it") } else { ("are lengths", "them") };
    format!(
        "`{shown}` holds {angle}, an angle, so swapping the two cannot help; {}, and if {names} {verb}, `{shown}` \
         mixes an angle and a length: write an angle for {pronoun}",
        arc(t)
    )
}

/// The angle of `t` as written, without the parentheses that make it one operand.
fn bare_angle(t: &NamedLength) -> &str {
    let a = t.angle.as_str();
    a.strip_prefix('(').and_then(|a| a.strip_suffix(')')).unwrap_or(a)
}

/// A length to write for the length `t` has: an arc rolled by it.
fn arc(t: &NamedLength) -> String {
    format!("write a length there, such as `r * {}` for the arc a radius `r` rolls", t.factor)
}

/// The swap of the term `t`.
fn swap(t: &NamedLength) -> String {
    format!("the two are swapped; write `{} @ {}`", t.angle, t.factor)
}

/// The error for the polar term `t` whose length is an angle (`why`), with the `fix` to write.
fn length_error(t: &NamedLength, why: &str, fix: &str) -> syn::Error {
    t.term.error(format!(
        "`{}` is an angle ({why}), but here it is the length of `@`, which takes `length @ angle`: {fix}",
        t.length
    ))
}

/// The errors for every coordinate noted in `lw` that is an angle where a position is written
/// (`(x, phi)`, `(x, 2 * phi)`): a mechanism whose results change with the unit of length. The
/// nodes refused are noted in `lw.refused_positions`, for the dynamics, which runs before the
/// errors are reported.
pub(super) fn coordinates(lw: &mut Lowerer, angles: &mut Angles) -> Vec<syn::Error> {
    let coordinates = std::mem::take(&mut lw.named_coordinates);
    let positions = lets_taken_as_lengths(&lw.let_uses);
    let mut errors = Vec::new();
    for c in coordinates {
        if let Place::Let(l) = &c.place
            && !positions.contains_key(l)
        {
            continue;
        }
        if let (Place::Dynamics(_, at), Coordinate::Name(Leaf::Unknown(_))) = (&c.place, c.what) {
            // An angle unknown at a body's or a force's point: refused by the dynamics' check.
            lw.left_to_dynamics.insert((*at, c.node));
            continue;
        }
        let Some((why, node)) = why_coordinate(lw, angles, &c) else {
            if let Coordinate::Name(leaf) = c.what {
                angles.lengths.insert(leaf);
            }
            continue;
        };
        lw.refused_positions.extend(node);
        errors.push(c.range.error(format!(
            "`{}` is an angle ({why}), but here it is a coordinate of {}: write a length there, such as \
             `r * {}` for the arc a radius `r` rolls",
            c.name,
            describe(&c.place, &positions),
            c.factor
        )));
    }
    errors
}

/// Why the coordinate `c` is an angle, with its node; `None` when it is not one.
fn why_coordinate(lw: &Lowerer, angles: &mut Angles, c: &NamedCoordinate) -> Option<(String, Option<NodeId>)> {
    let g = &lw.graph;
    match c.what {
        Coordinate::Name(leaf) => Some((angles.why(g, leaf, &c.name)?, Some(c.node))),
        // Written in degrees there: `(x, deg(5))`.
        Coordinate::Degrees => Some((why_an_angle(true, false, &c.name)?, None)),
        Coordinate::Expr(n) => Some((why_expression(lw, angles, n)?, Some(n))),
    }
}

/// Why the expression `n` is an angle, named by the first leaf that is one; `None` when the
/// kinds of its operations do not make it one (`2 * phi` is, `r * phi` and `sin(phi)` are not).
fn why_expression(lw: &Lowerer, angles: &mut Angles, n: NodeId) -> Option<String> {
    let g = &lw.graph;
    let mut why = None;
    let mut found = HashSet::new();
    for leaf in g.leaves_of(&[n]) {
        let name = leaf_name(lw, leaf).unwrap_or_default();
        if let Some(w) = angles.why(g, leaf, &name) {
            why.get_or_insert_with(|| format!("made from `{name}`, an angle: {w}"));
            found.insert(leaf);
        }
    }
    let of = |l: Leaf| if found.contains(&l) { Dim::Angle } else { Dim::Other };
    if found.is_empty() || !dims::is_angle(g, n, &of) {
        return None;
    }
    why
}

/// Reports every scalar sum, difference, `eq`, and call of `min`, `max`, `clamp`, `atan2`,
/// `hypot` or `wrap` noted in `lw` that puts an angle beside a length (`eq e: s == phi;` with
/// `s` a slider's travel): its value changes with the unit of length; then every vector of the
/// two ([`vectors_of_two_kinds`]). Run after [`coordinates`] and [`terms`], which find the
/// lengths.
pub(super) fn sums(lw: &mut Lowerer, angles: &mut Angles) {
    let pairs = std::mem::take(&mut lw.scalar_pairs);
    let vectors = std::mem::take(&mut lw.vector_pairs);
    if angles.lengths.is_empty() {
        return;
    }
    // The pairs of one call (`clamp(psi, lo, hi)`: `psi` with each bound) are one mistake,
    // told once.
    let mut told: Vec<(String, String)> = Vec::new();
    for p in pairs {
        if within_told_mixed(lw, angles, &p) {
            continue;
        }
        let at = (p.shown.clone(), format!("{:?}", p.range.start));
        if p.verb == "compares" && told.contains(&at) {
            continue;
        }
        if let Some(e) = angle_beside_length(lw, angles, &p) {
            lw.errors.push(e);
            told.push(at);
        }
    }
    vectors_of_two_kinds(lw, angles, vectors);
}

/// Reports every vector noted in `lw` whose coordinates are an angle and a length (`(x, psi)`
/// given to `norm`, `dot`, `cross`, `angle` or `rot`, `(x, 0) + (0, psi)`): its magnitude,
/// direction and products change with the unit of length, as the sum of the two does; and every
/// sum of vectors one of whose coordinates adds the two (`(x, 0) + (psi, 0)`), told once. A vector
/// built from one told (`2 * (x, psi)`, `(x, psi) + (0, x)`) is that mistake, and one in a vector
/// `let` that a loop or point takes is told as a coordinate of a position by [`coordinates`].
fn vectors_of_two_kinds(lw: &mut Lowerer, angles: &mut Angles, vectors: Vec<VectorPair>) {
    let positions = lets_taken_as_lengths(&lw.let_uses);
    let mut mixed: HashSet<[NodeId; 2]> = HashSet::new();
    for v in vectors {
        let [(x, _), (y, _)] = v.pair.sides;
        // A coordinate of a sum of vectors stands for the sum: told as the sum, once.
        let vector = v.sum.unwrap_or([x, y]);
        if v.parts.iter().any(|p| mixed.contains(p)) {
            mixed.insert(vector);
            continue;
        }
        if v.sum.is_some() && mixed.contains(&vector) {
            continue;
        }
        let Some(e) = angle_beside_length(lw, angles, &v.pair) else { continue };
        mixed.insert(vector);
        if !v.within.is_some_and(|l| positions.contains_key(&l)) {
            lw.errors.push(e);
        }
    }
}

/// Whether the pair `p` is made of the leaves of a polar term's angle already told to mix an
/// angle and a length (`phi + e` of a point's `psi @ (phi + e)`): one mistake, told once.
fn within_told_mixed(lw: &Lowerer, angles: &Angles, p: &ScalarPair) -> bool {
    if angles.told_mixed.is_empty() {
        return false;
    }
    let [(a, _), (b, _)] = p.sides;
    let leaves = lw.graph.leaves_of(&[a, b]);
    angles.told_mixed.iter().any(|&n| {
        let of_term = lw.graph.leaves_of(&[n]);
        leaves.iter().all(|l| of_term.contains(l))
    })
}

/// The error for the pair `p` if one side is an angle and the other a length.
fn angle_beside_length(lw: &Lowerer, angles: &mut Angles, p: &ScalarPair) -> Option<syn::Error> {
    let g = &lw.graph;
    let [(a, _), (b, _)] = p.sides;
    // Why each angle among the leaves is one, named for the message.
    let mut reasons: Vec<(Leaf, String, String)> = Vec::new();
    for leaf in g.leaves_of(&[a, b]) {
        let name = leaf_name(lw, leaf).unwrap_or_default();
        if let Some(why) = angles.why(g, leaf, &name) {
            reasons.push((leaf, name, why));
        }
    }
    let of = |l: Leaf| match () {
        _ if reasons.iter().any(|r| r.0 == l) => Dim::Angle,
        _ if angles.lengths.contains(&l) => Dim::L(1),
        _ => Dim::Other,
    };
    let d = dims::judged(g, &[a, b], &of);
    let dim = |n: NodeId| d.get(&n).copied().unwrap_or(Dim::Other);
    let (angle, length) = match (dim(a), dim(b)) {
        (Dim::Angle, Dim::L(1)) => (0, 1),
        (Dim::L(1), Dim::Angle) => (1, 0),
        _ => return None,
    };
    let (node, shown) = &p.sides[angle];
    // Why the angle is one: its own reason where it is that name, else the first angle it is
    // made from.
    let leaves = g.leaves_of(&[*node]);
    let (_, name, why) = reasons.iter().find(|r| leaves.contains(&r.0))?;
    let why = if name == shown { why.clone() } else { format!("made from `{name}`, an angle: {why}") };
    // A side not written as such (a coordinate of a sum of vectors) gets the angle's name.
    let factor = if p.factors[angle].is_empty() { name } else { &p.factors[angle] };
    Some(p.range.error(format!(
        "`{}` {} an angle and a length, so its value would change with the unit of length: `{shown}` is an \
         angle ({why}), and `{}` a length (a coordinate of a position or the length of `@`); write a length \
         for the angle, such as `r * {}` for the arc a radius `r` rolls",
        p.shown, p.verb, p.sides[length].1, factor
    )))
}

/// What takes a vector `let` as a position, directly or through other `let`s.
#[derive(Clone, Default)]
struct Takers {
    /// A loop or a point.
    loop_or_point: bool,
    /// The positions of the dynamics, as they are described (`a centre of mass`).
    dynamics: Vec<&'static str>,
}

impl Takers {
    fn add(&mut self, other: &Takers) {
        self.loop_or_point |= other.loop_or_point;
        for what in &other.dynamics {
            if !self.dynamics.contains(what) {
                self.dynamics.push(what);
            }
        }
    }
}

/// The `let`s that a loop, a point or a position of the dynamics uses, directly or through
/// other such `let`s (`uses`: each `let` named, with the item that names it), with what takes
/// each: their vectors are positions too.
fn lets_taken_as_lengths(uses: &[(Place, String)]) -> HashMap<String, Takers> {
    let mut found: HashMap<String, Takers> = HashMap::new();
    for (place, used) in uses {
        let taker = match place {
            Place::Let(_) => continue,
            Place::Loop | Place::Point => Takers { loop_or_point: true, dynamics: Vec::new() },
            Place::Dynamics(what, _) => Takers { loop_or_point: false, dynamics: vec![*what] },
        };
        found.entry(used.clone()).or_default().add(&taker);
    }
    // A `let` uses only those above it: one pass from the bottom up reaches them all.
    for (place, used) in uses.iter().rev() {
        if let Place::Let(user) = place
            && let Some(takers) = found.get(user).cloned()
        {
            found.entry(used.clone()).or_default().add(&takers);
        }
    }
    found
}

/// What a coordinate at `place` is, for the message: "a coordinate of ...". A `let` is named
/// with what takes it (`positions`): a centre of mass or a force's point by name, as a
/// loop's or point's `let` is "a vector that a loop or point takes".
fn describe(place: &Place, positions: &HashMap<String, Takers>) -> String {
    let Place::Let(name) = place else { return place.describe() };
    match positions.get(name) {
        Some(t) if !t.loop_or_point && !t.dynamics.is_empty() => {
            let verb = if t.dynamics.len() == 1 { "takes" } else { "take" };
            format!("`{name}`, a vector that {} {verb} as lengths", t.dynamics.join(" and "))
        }
        _ => place.describe(),
    }
}

/// Why the name `name` is an angle: its value is in `degrees`, or it is `known` as one from the
/// mechanism; `None` when it is neither.
fn why_an_angle(degrees: bool, known: bool, name: &str) -> Option<String> {
    if degrees {
        Some("its value is written in degrees".to_string())
    } else if known {
        // The example's link is named apart from the angle: `l @ l` would read as a length.
        let link = if name == "l" { "r" } else { "l" };
        Some(format!(
            "elsewhere it turns a link, as in `{link} @ {name}`, or is the argument of a sine or cosine, \
             or an `eq` sets it to an angle"
        ))
    } else {
        None
    }
}
