//! What is an angle: the one test every check of the macro asks of a name, so that a name is of
//! one kind for them all. The unit check ([`super::polar`]: coordinates of positions, sums, the
//! length of `@`) asks it over the whole mechanism; the same check asks it with the terms in
//! question set aside to tell whether a term whose length is an angle is swapped (`psi @ l`) or
//! needs a length (`psi @ phi`), and which of two terms that take two names in opposite orders
//! is wrong; a body's `turns` and a torque's `on` ([`super::dynamics`]) take what it finds over
//! the whole mechanism.
//!
//! A name is an angle when its value is written in degrees, when it enters a sine, cosine or
//! tangent as a multiple of itself by a constant (`l @ q`, `l @ (q + gamma)`, `sin(2 * q)`,
//! `l @ (q / 2)`; a length scaled into one, `sin(x / l)`, is not), or when an `eq` sets it to an
//! angle: to inverse trigonometric functions (`q == atan2(dy, dx)`, `asin`, `acos`, `atan`,
//! `angle(v)`), or, for an unknown, to an expression of angles (`y == 2 * psi`, a gear's angle,
//! `y == psi + gamma`), plus terms free of the state. The last is the kind the plan labels its
//! column with (`y [rad]`), and turns a body as `psi` does: in radians, `2 * psi` of them.
//!
//! A name written as a length elsewhere (`placed`: a coordinate of a position, the length of
//! `@`) is held to more: a sine that takes only a fraction of it (`sin(x / 2)`, the 2 perhaps a
//! radius written as a number) makes it no angle, and neither does an `eq` that sets it to an
//! expression of angles, which is the mistake then (it equates an angle and a length).

use crate::graph::dag::{Func, Graph, Leaf, NodeId, Op};
use crate::graph::dims::{self, Dim};
use crate::graph::multiples;
use std::collections::{HashMap, HashSet};

/// What the mechanism says of its names, for [`Evidence::is_angle`].
pub(super) struct Evidence<'a> {
    pub g: &'a Graph,
    /// The mechanism's equations, where an `eq` sets a name to an angle.
    pub residuals: &'a [NodeId],
    /// The arguments of the sines, cosines and tangents that count: the whole mechanism's, or
    /// those found with the terms in question set aside.
    pub arguments: &'a [NodeId],
    /// The parameters and unknowns whose values are written in degrees.
    pub degrees: &'a [Leaf],
    /// The names written bare as a coordinate of a position or as the length of `@`.
    pub placed: &'a HashSet<Leaf>,
    /// The angles of polar terms found swapped (`l` in `psi @ l`): lengths written in the wrong
    /// place, which make no expression of them an angle.
    pub swapped: &'a HashSet<Leaf>,
}

/// The verdicts found over one [`Evidence`], each once.
#[derive(Default)]
pub(super) struct Verdicts {
    /// Whether each name is an angle by itself: in degrees, in a sine or cosine, or set by an
    /// `eq` to inverse trigonometric functions.
    by_itself: HashMap<Leaf, bool>,
    /// The unknowns that `eq`s set to expressions of angles (`y == 2 * psi`), found together at
    /// the first verdict that asks ([`Evidence::set_by_eqs`]).
    set_by_eqs: Option<HashSet<Leaf>>,
    /// The names an equation sets to inverse trigonometric functions, and the trigonometric
    /// arguments each name is in: found together at the first verdict that asks, so that a
    /// verdict reads the equations and arguments of its own name (a name's own search through
    /// all of them made the verdicts quadratic in the mechanism's size: a declaration of 600
    /// loops took seconds to be refused for its number of unknowns).
    index: Option<Index>,
}

/// What [`Evidence::by_itself`] reads of each name, found in one pass over the equations and
/// the trigonometric arguments.
struct Index {
    /// The names an equation sets to inverse trigonometric functions (`q == atan2(y, x)`).
    set_by_trig: HashSet<Leaf>,
    /// The trigonometric arguments each name is in.
    arguments_of: HashMap<Leaf, Vec<NodeId>>,
}

impl Index {
    fn of(e: &Evidence) -> Self {
        let g = e.g;
        let mut set_by_trig = HashSet::new();
        for &r in e.residuals {
            // Only a name that is a whole term of the equation can be set by it.
            let own = terms(g, r).into_iter().flatten().filter_map(|t| match g.op(t) {
                Op::Leaf(l) => Some(l),
                _ => None,
            });
            for leaf in own.collect::<HashSet<_>>() {
                if !set_by_trig.contains(&leaf) && sets_to_angle(g, leaf, r, &mut |_| false) {
                    set_by_trig.insert(leaf);
                }
            }
        }
        let mut arguments_of: HashMap<Leaf, Vec<NodeId>> = HashMap::new();
        for &a in e.arguments {
            for leaf in g.leaves_of(&[a]) {
                arguments_of.entry(leaf).or_default().push(a);
            }
        }
        Index { set_by_trig, arguments_of }
    }
}

impl Evidence<'_> {
    /// Whether `leaf` is an angle (see the module's documentation). The unknowns that `eq`s set
    /// to expressions of angles are found once, together ([`Evidence::set_by_eqs`]); a circle of
    /// equations that nothing else makes angles makes none.
    pub fn is_angle(&self, leaf: Leaf, verdicts: &mut Verdicts) -> bool {
        if self.by_itself(leaf, verdicts) {
            return true;
        }
        // A name placed as a length (`(x, s)` in a loop) stays one: an `eq` that sets it to an
        // expression of angles is the mistake, told there as one that equates the two.
        if !matches!(leaf, Leaf::Unknown(_)) || self.placed.contains(&leaf) {
            return false;
        }
        if verdicts.set_by_eqs.is_none() {
            let set = self.set_by_eqs(verdicts);
            verdicts.set_by_eqs = Some(set);
        }
        verdicts.set_by_eqs.as_ref().is_some_and(|set| set.contains(&leaf))
    }

    /// Whether `leaf` is an angle by itself, once per name: written in degrees, a multiple of
    /// itself in a sine or cosine, or set by an `eq` to inverse trigonometric functions.
    fn by_itself(&self, leaf: Leaf, verdicts: &mut Verdicts) -> bool {
        if let Some(&known) = verdicts.by_itself.get(&leaf) {
            return known;
        }
        let g = self.g;
        let index = verdicts.index.get_or_insert_with(|| Index::of(self));
        // The arguments `leaf` is not in classify it as free of it: its own are the same verdict.
        let arguments = index.arguments_of.get(&leaf).map_or(&[][..], Vec::as_slice);
        let in_trig = match self.placed.contains(&leaf) {
            true => multiples::in_whole_multiple(g, leaf, arguments),
            false => multiples::in_whole_angle(g, leaf, arguments),
        };
        let known = self.degrees.contains(&leaf) || in_trig || index.set_by_trig.contains(&leaf);
        verdicts.by_itself.insert(leaf, known);
        known
    }

    /// The unknowns, not placed as lengths, that `eq`s set to expressions of angles, those
    /// judged in turn: the least set closed under "an `eq` sets it to angles by themselves or
    /// of the set". A circle of equations that nothing else makes angles (`y == 2 * z` beside
    /// `z == y / 2`) makes none. Found from the angles outwards, each equation judged again only
    /// where one of its names became an angle, so the work is about linear in the equations: a
    /// search from each unknown through the equations that set it, its circles' verdicts not
    /// kept, took exponential time (eight unknowns each set to the sum of two others held
    /// `mechanism!` and the reader for minutes).
    fn set_by_eqs(&self, verdicts: &mut Verdicts) -> HashSet<Leaf> {
        let g = self.g;
        let leaves: Vec<Vec<Leaf>> = self.residuals.iter().map(|&r| g.leaves_of(&[r])).collect();
        // The equations each name is in, to judge again where it becomes an angle.
        let mut users: HashMap<Leaf, Vec<usize>> = HashMap::new();
        for (i, of) in leaves.iter().enumerate() {
            for &leaf in of {
                users.entry(leaf).or_default().push(i);
            }
        }
        let mut set = HashSet::new();
        let mut queue: Vec<usize> = (0..self.residuals.len()).rev().collect();
        while let Some(i) = queue.pop() {
            let r = self.residuals[i];
            for &leaf in &leaves[i] {
                let candidate = matches!(leaf, Leaf::Unknown(_))
                    && !set.contains(&leaf)
                    && !self.placed.contains(&leaf)
                    && !self.by_itself(leaf, verdicts);
                if candidate && sets_to_angle(g, leaf, r, &mut |t| self.made_angle(t, &set, verdicts)) {
                    set.insert(leaf);
                    queue.extend(users.get(&leaf).into_iter().flatten().copied());
                }
            }
        }
        set
    }

    /// Whether the expression `t` is an angle by the names it is made from: some are angles,
    /// by themselves or in `set` (set to angles by `eq`s), but those of terms found swapped,
    /// and the operations keep it one (`2 * psi`, `psi + gamma`; not `r * psi`).
    fn made_angle(&self, t: NodeId, set: &HashSet<Leaf>, verdicts: &mut Verdicts) -> bool {
        let mut found = HashSet::new();
        for leaf in self.g.leaves_of(&[t]) {
            if !self.swapped.contains(&leaf) && (set.contains(&leaf) || self.by_itself(leaf, verdicts)) {
                found.insert(leaf);
            }
        }
        !found.is_empty() && dims::is_angle(self.g, t, &|l| if found.contains(&l) { Dim::Angle } else { Dim::Other })
    }
}

/// Whether residual `r` sets `leaf` to an angle: `leaf == f + c`, either side and either sign,
/// with `f` one or more inverse trigonometric functions (`atan2`, `asin`, `acos`, `atan`,
/// `angle(v)`, which is an `atan2`) or terms that `made_angle` finds to be angles by what they
/// are made of (`2 * psi`), and `c` terms free of the state (an offset such as `pi / 2`). The
/// leaf must be a whole side: `x == l * atan(s)` makes `x` a length; a term that holds `leaf`
/// itself sets it to nothing.
fn sets_to_angle(g: &Graph, leaf: Leaf, r: NodeId, made_angle: &mut dyn FnMut(NodeId) -> bool) -> bool {
    let Some(terms) = terms(g, r) else { return false };
    let (mut own, mut angles) = (0, 0);
    for t in terms {
        match g.op(t) {
            Op::Leaf(l) if l == leaf => own += 1,
            Op::Func(Func::Asin | Func::Acos | Func::Atan, _) | Op::Atan2(..) => angles += 1,
            _ if g.leaves_of(&[t]).contains(&leaf) => return false,
            _ if made_angle(t) => angles += 1,
            _ if !depends_on_state(g, t) => {}
            _ => return false,
        }
    }
    own == 1 && angles > 0
}

fn depends_on_state(g: &Graph, n: NodeId) -> bool {
    g.leaves_of(&[n]).iter().any(|l| matches!(l, Leaf::Input(_) | Leaf::Unknown(_)))
}

/// More terms than an equation setting an angle has (see [`terms`]).
const MAX_TERMS: usize = 16;

/// The terms of `r` read as a sum through `+`, `-` and negation, their signs dropped; `None`
/// beyond [`MAX_TERMS`] (an equation that sets an angle has a few, and a sum that shares its
/// terms would otherwise be walked once per path).
fn terms(g: &Graph, r: NodeId) -> Option<Vec<NodeId>> {
    let (mut stack, mut out) = (vec![r], Vec::new());
    while let Some(n) = stack.pop() {
        match g.op(n) {
            Op::Add(a, b) | Op::Sub(a, b) => stack.extend([a, b]),
            Op::Neg(a) => stack.push(a),
            _ => out.push(n),
        }
        if stack.len() + out.len() > MAX_TERMS {
            return None;
        }
    }
    Some(out)
}
