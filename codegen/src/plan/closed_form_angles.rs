//! The unknowns that closed-form blocks give as angles.

use super::finished::Plan;

/// Per unknown, whether a closed-form block gives it as an angle: the runtime's
/// `CLOSED_FORM_ANGLES`, written by the emitter and read by a run-time model, from one place
/// (see also [`followers::followers`](super::followers::followers)).
pub fn closed_form_angles(plan: &Plan) -> Vec<bool> {
    let mut out = vec![false; plan.n];
    for u in plan.blocks.iter().filter_map(|bp| bp.solve.closed_form()).flat_map(|r| r.form.angles()) {
        out[u] = true;
    }
    out
}
