//! The check that `@` has its length first: `length @ angle`. A polar term whose length is a
//! bare name of an angle (`th @ s` for `s @ th`) compiles as a link of `th` radians turned by
//! `s`, a mechanism that solves to wrong angles, or not at all, and whose results change with
//! the unit of length; it is refused at the term, with the swap to write.
//!
//! A coordinate of a Cartesian vector that is a bare name of an angle (`(x, phi)`) is refused
//! too where the vector is a position: in a loop, which adds lengths, a point, the point a
//! force acts at, a centre of mass, and a vector `let` that one of these uses. A vector scaled
//! by a quantity that varies (`l * (phi, 0)`) has coordinates of its kind, and is not judged.
//!
//! Only a name that is an angle by the mechanism itself is refused (the test of a body's
//! `turns`: it enters a sine, cosine or `@` as a whole multiple of itself elsewhere, or an `eq`
//! sets it to an angle), or one whose value is written in degrees. A length times an angle
//! (`(r * phi) @ 0`), a constant, or a name of no known kind stays the length it is written as.

use super::dynamics::is_angle;
use super::lower::{Lowerer, Place};
use crate::graph::dag::{Leaf, NodeId};
use crate::graph::multiples;
use std::collections::{HashMap, HashSet};

/// Reports every polar term noted in `lw` whose length is an angle, and every coordinate of a
/// loop's Cartesian vector that is one. `residuals` and `columns` are the mechanism's equations
/// and outputs (where an angle is seen to be one); `degrees` the parameters and unknowns whose
/// values are written in degrees.
pub(super) fn check(lw: &mut Lowerer, residuals: &[NodeId], columns: &[NodeId], degrees: &[Leaf]) {
    let terms = std::mem::take(&mut lw.named_lengths);
    let coordinates = std::mem::take(&mut lw.named_coordinates);
    if terms.is_empty() && coordinates.is_empty() {
        return;
    }
    let roots: Vec<NodeId> = residuals.iter().chain(columns).copied().collect();
    let arguments = multiples::trig_arguments(&lw.graph, &roots);
    // One verdict per name, however many terms have it as their length.
    let mut angles: HashMap<Leaf, bool> = HashMap::new();
    for t in terms {
        let (length, angle) = (&t.length, &t.angle);
        let known = *angles.entry(t.leaf).or_insert_with(|| is_angle(&lw.graph, t.leaf, &arguments, residuals));
        let Some(why) = why_an_angle(degrees.contains(&t.leaf), known, length) else { continue };
        let fix = if t.constant_angle {
            // `th @ 0`: no length to swap with; an arc rolled by `th` is a radius times it.
            format!("write a length there, such as `r * {length}` for the arc a radius `r` rolls")
        } else {
            format!("the two are swapped; write `{angle} @ {length}`")
        };
        lw.errors.push(t.term.error(format!(
            "`{length}` is an angle ({why}), but here it is the length of `@`, which takes `length @ angle`: {fix}"
        )));
    }
    // A loop adds lengths, and a point is a position: an angle as a coordinate of one of their
    // vectors (`(x, phi)`) makes a mechanism whose results change with the unit of length.
    let positions = lets_taken_as_lengths(&std::mem::take(&mut lw.let_uses));
    for c in coordinates {
        if let Place::Let(l) = &c.place
            && !positions.contains(l)
        {
            continue;
        }
        if let (Place::Dynamics(_), Some(Leaf::Unknown(_))) = (&c.place, c.leaf) {
            // An angle unknown at a body's or a force's point: refused by the dynamics' check.
            continue;
        }
        let name = &c.name;
        let why = match c.leaf {
            Some(leaf) => {
                let known = *angles.entry(leaf).or_insert_with(|| is_angle(&lw.graph, leaf, &arguments, residuals));
                why_an_angle(degrees.contains(&leaf), known, name)
            }
            // Written in degrees there: `(x, deg(5))`.
            None => why_an_angle(true, false, name),
        };
        let Some(why) = why else { continue };
        lw.errors.push(c.range.error(format!(
            "`{name}` is an angle ({why}), but here it is a coordinate of {}: write a length there, such as \
             `r * {}` for the arc a radius `r` rolls",
            c.place.describe(),
            c.factor
        )));
    }
}

/// The `let`s that a loop, a point or a position of the dynamics uses, directly or through
/// other such `let`s (`uses`: each `let` named, with the item that names it): their vectors
/// are positions too.
fn lets_taken_as_lengths(uses: &[(Place, String)]) -> HashSet<String> {
    let mut found: HashSet<String> =
        uses.iter().filter(|(p, _)| !matches!(p, Place::Let(_))).map(|(_, l)| l.clone()).collect();
    // A `let` uses only those above it: one pass from the bottom up reaches them all.
    for (place, used) in uses.iter().rev() {
        if let Place::Let(user) = place
            && found.contains(user)
        {
            found.insert(used.clone());
        }
    }
    found
}

/// Why the name `name` is an angle: its value is in `degrees`, or it is `known` as one from the
/// mechanism; `None` when it is neither.
fn why_an_angle(degrees: bool, known: bool, name: &str) -> Option<String> {
    if degrees {
        Some("its value is written in degrees".to_string())
    } else if known {
        Some(format!(
            "elsewhere it turns a link, as in `l @ {name}`, or is the argument of a sine or cosine, \
             or an `eq` sets it to an angle"
        ))
    } else {
        None
    }
}
