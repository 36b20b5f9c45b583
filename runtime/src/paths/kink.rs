//! Telling a corner of the solution curve from a jump to another solution.
//!
//! A declaration may hold functions with corners on purpose: a uniform-velocity cam law written
//! with `clamp`, a slider's stroke through `abs`, a `min` or `max` of two laws. At such a corner
//! the velocity analogs jump however small the step, so the sweep's slope test fails at every
//! step size and the step is halved to its floor, exactly as it is where a step lands on another
//! solution. What tells them apart is the positions: across a corner they are continuous, each
//! unknown moving by no more than its steeper one-sided slope times the (vanishingly small)
//! step; another solution lies a finite distance away. Both states must also be regular, with
//! the same determinant signs: a singular position in between is a limit position or a
//! crossing, which the sweep locates by continuation instead.
//!
//! Near a limit position the slopes grow without bound, and over the sweep's smallest step
//! they change by a finite amount as well, with the positions continuous and the pivots still
//! above the sweep's threshold. What tells a corner from that is the inside of the step: on
//! either side of a corner the slope is constant to within the curvature over the step (far
//! below the jump), so a state solved inside the step has the slope of one side or the other;
//! approaching a fold the slope varies smoothly, and a state inside has one between them.
//!
//! Pseudo-arclength continuation asks the same question of its curve (`trace_kink`), in the
//! same parameterisation by the input: where the Jacobian is regular the curve is a function of
//! it.

/// The largest distance, in an unknown's unit (a radian, or its loop's size), between the two
/// sides of a corner beyond what their slopes explain: the Newton tolerance's order, far below
/// the distance of any other solution where the Jacobian is regular (two solutions this close
/// would put a singular position between them, which the pivot test excludes).
pub(crate) const KINK_GAP: f64 = 1e-8;

/// The smallest pivot ratio at which a corner is told from a jump to another solution, whatever
/// the configuration's `singular_pivot`: [`KINK_GAP`]'s argument (two solutions this close put
/// a singular position between them) holds where positions below it are excluded. A
/// configuration that lowers `singular_pivot` to pass near a singular position (a slide
/// brushing its pivot) does not lower this: with it at `1e-9`, a sweep into a parallelogram
/// four-bar's change point hopped between the two branches there and recorded each hop as a
/// kink (three within `4e-9` degrees of it) before it located the crossing.
pub(crate) const KINK_PIVOT: f64 = 1e-6;

/// One judged unknown on the two sides of the smallest step the sweep can take, each in the
/// unknown's unit: its change over the step and its slope before and after.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Side {
    /// `q_after - q_before`.
    pub change: f64,
    /// The slope (per unit of the step's parameter) at the last accepted state.
    pub slope_before: f64,
    /// The slope at the state past the step.
    pub slope_after: f64,
}

/// Whether every judged unknown moved continuously over a step of length `step` (in the slopes'
/// parameter): by no more than twice its steeper one-sided slope times the step, plus
/// [`KINK_GAP`]. The factor two covers the curvature on either side over a step at the sweep's
/// smallest, where it is far below the slopes' term. A NaN change is not continuous (the
/// states are finite: a sweep checks them).
pub(crate) fn continuous(sides: impl IntoIterator<Item = Side>, step: f64) -> bool {
    sides.into_iter().all(|s| {
        let steeper = s.slope_before.abs().max(s.slope_after.abs());
        s.change.abs() <= 2.0 * step.abs() * steeper + KINK_GAP
    })
}

/// The smallest jump, against the steeper slope, that makes a corner: a smaller change of
/// slope passes the sweep's slope test (a quarter of a tenth of the slope) and never comes here.
pub(crate) const MIN_JUMP: f64 = 1e-2;

/// The largest distance of a slope inside the step from the nearer side's, against the jump.
pub(crate) const ONE_SIDED: f64 = 1e-3;

/// The slopes of one judged unknown before the step, after it, and at a state solved inside it,
/// each in the unknown's unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Slopes {
    /// At the last accepted state.
    pub before: f64,
    /// At the state past the step.
    pub after: f64,
    /// At a state solved inside the step.
    pub inside: f64,
}

/// Whether the step holds a corner by the slopes of its unknowns: some unknown's slope jumps by
/// at least [`MIN_JUMP`] of the steeper side, and every unknown's slope inside the step is that
/// of one side or the other, within [`ONE_SIDED`] of the largest jump. NaN is not a corner.
pub(crate) fn one_sided(slopes: &[Slopes]) -> bool {
    let jump = slopes.iter().fold(0.0f64, |j, s| j.max((s.after - s.before).abs()));
    let steeper = slopes.iter().fold(0.0f64, |m, s| m.max(s.before.abs()).max(s.after.abs()));
    let jumps = jump >= MIN_JUMP * steeper && jump > 0.0;
    jumps
        && slopes.iter().all(|s| {
            let nearer = (s.inside - s.before).abs().min((s.inside - s.after).abs());
            nearer <= ONE_SIDED * jump
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn side(change: f64, before: f64, after: f64) -> Side {
        Side { change, slope_before: before, slope_after: after }
    }

    #[test]
    fn a_corner_moves_by_its_slopes() {
        // |x - 1| over [1 - 1e-12, 1 + 1e-12]: slopes -1 and 1, change 0.
        assert!(continuous([side(0.0, -1.0, 1.0)], 2e-12));
        // Up a ramp and onto a dwell: 0.5e-12 of change at slope 1 then 0.
        assert!(continuous([side(0.5e-12, 1.0, 0.0), side(0.0, 0.0, 0.0)], 1e-12));
    }

    #[test]
    fn another_solution_is_not_a_corner() {
        // The elbow's other assembly: a finite distance at a vanishing step.
        assert!(!continuous([side(0.0, 1.0, 1.0), side(0.3, 2.0, 2.0)], 1e-12));
        assert!(!continuous([side(2e-8, 1.0, 1.0)], 1e-12));
        assert!(!continuous([side(f64::NAN, 1.0, 1.0)], 1e-12));
    }

    fn slopes(before: f64, after: f64, inside: f64) -> Slopes {
        Slopes { before, after, inside }
    }

    #[test]
    fn a_corner_has_one_sided_slopes_inside() {
        assert!(one_sided(&[slopes(-2.0, 2.0, -2.0)]));
        assert!(one_sided(&[slopes(-2.0, 2.0, 2.0 + 1e-6), slopes(0.5, 0.5, 0.5)]));
        // A follower's slope jumps with its ramp's.
        assert!(one_sided(&[slopes(10.0, 0.0, 0.0), slopes(3.0, 0.0, 0.0)]));
    }

    #[test]
    fn a_fold_or_a_smooth_step_is_not_a_corner() {
        // Approaching a limit position: 1 / sqrt(distance) at 3, 2 and 1 units from it.
        let fold = |d: f64| 1.0 / d.sqrt();
        assert!(!one_sided(&[slopes(fold(3.0), fold(1.0), fold(2.0))]));
        // No jump at all: the step failed for another reason.
        assert!(!one_sided(&[slopes(1.0, 1.0, 1.0)]));
        assert!(!one_sided(&[slopes(1.0, 1.001, 1.0)]));
        assert!(!one_sided(&[slopes(0.0, 0.0, 0.0)]));
        assert!(!one_sided(&[slopes(-2.0, 2.0, f64::NAN)]));
        assert!(!one_sided(&[slopes(f64::NAN, 2.0, 2.0)]));
    }
}
