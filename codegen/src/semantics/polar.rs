//! The check that `@` has its length first: `length @ angle`. A polar term whose length is a
//! bare name of an angle (`th @ s` for `s @ th`) compiles as a link of `th` radians turned by
//! `s`, a mechanism that solves to wrong angles, or not at all, and whose results change with
//! the unit of length; it is refused at the term, with the swap to write.
//!
//! A coordinate of a loop's Cartesian vector that is a bare name of an angle (`(x, phi)`) is
//! refused too: a loop adds lengths.
//!
//! Only a name that is an angle by the mechanism itself is refused (the test of a body's
//! `turns`: it enters a sine, cosine or `@` as a whole multiple of itself elsewhere, or an `eq`
//! sets it to an angle), or one whose value is written in degrees. A length times an angle
//! (`(r * phi) @ 0`), a constant, or a name of no known kind stays the length it is written as.

use super::dynamics::is_angle;
use super::lower::Lowerer;
use crate::graph::dag::{Leaf, NodeId};
use crate::graph::multiples;
use std::collections::HashMap;

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
    // A loop adds lengths: an angle as a coordinate of one of its vectors (`(x, phi)`) makes a
    // mechanism whose results change with the unit of length.
    for c in coordinates {
        let name = &c.name;
        let known = *angles.entry(c.leaf).or_insert_with(|| is_angle(&lw.graph, c.leaf, &arguments, residuals));
        let Some(why) = why_an_angle(degrees.contains(&c.leaf), known, name) else { continue };
        lw.errors.push(c.range.error(format!(
            "`{name}` is an angle ({why}), but here it is a coordinate of a vector in a loop, which adds \
             lengths: write a length there, such as `r * {name}` for the arc a radius `r` rolls"
        )));
    }
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
