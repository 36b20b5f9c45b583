//! The verification on hand-made designs with a known defect: each design meets its targets
//! exactly (targets sampled from its closed form), so only the verification can reject it.

use super::mechanisms::{CouplerFourBar, FOUR_BAR, four_bar_pose};
use kinloop::synthesis::{Constraints, Defect, Design, Problem, Search, Task};
use std::f64::consts::{PI, TAU};

/// A non-Grashof four-bar (s + l = 1 + 2 > p + q = 1.5 + 1.3): the crank rocks within
/// `|phi| <= theta`, `cos theta = (a^2 + d^2 - (b + c)^2) / (2 a d)` (A, B and D in line).
const TRIPLE_ROCKER: [f64; 6] = [1.0, 1.5, 1.3, 2.0, 0.8, 0.3];

/// The problem of the targets at `phis` on sides `sides` of `p` (only `e` varies, within a
/// box around its value), each target's position given.
fn exact(p: [f64; 6], phis: &[f64], sides: &[f64], timed: bool) -> Problem<CouplerFourBar, 2, 1, 3, 6> {
    let poses: Vec<([f64; 2], [f64; 2])> = phis.iter().zip(sides).map(|(&x, &s)| four_bar_pose(p, x, s)).collect();
    let task = Task::path("p", poses.iter().map(|(t, _)| *t));
    let task = if timed { task.timed(phis.to_vec()) } else { task.untimed(-TAU, TAU) };
    let [a, b, c, d, e, alpha] = p;
    let m = CouplerFourBar { a, b, c, d, e, alpha };
    Problem::new(m, &Design::new().var("e", 0.5 * e, 2.0 * e), &task)
        .unwrap()
        .with_guesses(poses.iter().map(|(_, q)| *q).collect())
        .unwrap()
}

/// The design's own values (`e`, then the inputs where free), refined and verified.
fn verify(problem: &Problem<CouplerFourBar, 2, 1, 3, 6>, z: &[f64]) -> kinloop::synthesis::Candidate {
    let c = Search::default().refine(problem, z).unwrap();
    assert!(c.max_error < 1e-13, "the design meets its targets: {c:?}");
    c
}

/// A refinement reads only the local solve's settings: it is not refused for a start range,
/// `keep` or `distinct` it never uses (it was, as a search with them is), and gives the same
/// candidate; a local setting out of range still is refused.
#[test]
fn a_refinement_reads_only_the_local_settings() {
    use kinloop::synthesis::{LocalConfig, SynthesisError};
    let problem = exact(FOUR_BAR, &[0.0, 1.0, 2.0, 3.0], &[1.0; 4], true);
    let z = [1.1 * FOUR_BAR[4]];
    let plain = Search::default().refine(&problem, &z).unwrap();
    #[allow(clippy::reversed_empty_ranges)]
    let unused = [
        Search::default().with_starts(10..2),
        Search::default().with_keep(0),
        Search::default().with_distinct(f64::NAN),
    ];
    for search in unused {
        let c = search.refine(&problem, &z).unwrap_or_else(|e| panic!("{search:?}: {e}"));
        assert_eq!((&c.values, &c.errors), (&plain.values, &plain.errors));
    }
    let e = Search::default().with_local(LocalConfig::default().with_tol(-1.0)).refine(&problem, &z).unwrap_err();
    assert!(matches!(&e, SynthesisError::InvalidConfig(m) if m.starts_with("local.tol")), "{e:?}");
}

#[test]
fn a_valid_design_has_no_defect() {
    let problem = exact(FOUR_BAR, &[0.0, 1.0, 2.0, 3.0], &[1.0; 4], true);
    let c = verify(&problem, &[FOUR_BAR[4]]);
    assert!(c.is_valid(), "{c:?}");
}

#[test]
fn targets_on_two_assembly_modes_are_a_branch_defect() {
    // The Grashof crank-rocker with its second target on the other assembly mode (C on the
    // right of AD): met exactly, but the sweep from the first target reaches the second on the
    // first's mode.
    let problem = exact(FOUR_BAR, &[0.5, 1.0, 1.5], &[1.0, -1.0, -1.0], true);
    let c = verify(&problem, &[FOUR_BAR[4]]);
    assert_eq!(c.defects, [Defect::Branch { target: 1 }]);
}

/// Two targets at one crank angle, met on the two assembly modes: no sweep between them, and
/// their positions tell. It was valid (each target met on its own mode, nothing compared); on
/// one mode, valid.
#[test]
fn targets_at_one_input_on_two_assembly_modes_are_a_branch_defect() {
    let problem = exact(FOUR_BAR, &[0.3, 0.3, 1.2, 2.0, 2.8], &[1.0, -1.0, -1.0, -1.0, -1.0], true);
    let c = verify(&problem, &[FOUR_BAR[4]]);
    assert_eq!(c.defects, [Defect::Branch { target: 1 }]);
    let problem = exact(FOUR_BAR, &[0.3, 0.3, 1.2, 2.0, 2.8], &[-1.0; 5], true);
    let c = verify(&problem, &[FOUR_BAR[4]]);
    assert!(c.is_valid(), "{c:?}");
}

#[test]
fn a_limit_position_between_targets_is_a_circuit_defect() {
    // The crank must pass its limit position theta to go from 2.0 to 2 pi - 2.0 upwards.
    let [a, b, c, d, ..] = TRIPLE_ROCKER;
    let theta = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    assert!(2.0 < theta && theta < PI);
    let problem = exact(TRIPLE_ROCKER, &[2.0, TAU - 2.0], &[1.0, 1.0], true);
    let cand = verify(&problem, &[TRIPLE_ROCKER[4]]);
    match cand.defects.as_slice() {
        // The sweep locates the limit position to its event tolerance (`tol::LOCATED`).
        [Defect::Circuit { target: 1, at }] => assert_close!(*at, theta, crate::support::tol::LOCATED),
        other => panic!("{other:?}"),
    }
}

#[test]
fn targets_met_out_of_order_are_an_order_defect() {
    // Free crank angles, met exactly at 0.5, 1.5, 1.0, 2.0: not monotone.
    let phis = [0.5, 1.5, 1.0, 2.0];
    let problem = exact(FOUR_BAR, &phis, &[1.0; 4], false);
    let mut z = vec![FOUR_BAR[4]];
    z.extend(phis);
    let c = verify(&problem, &z);
    assert_eq!(c.defects.first(), Some(&Defect::Order));
}

#[test]
fn crank_angles_in_cyclic_order_are_one_motion() {
    // Free crank angles 5.5, 6.0, 0.3, 0.9: in order once the crank passes its zero, the
    // candidate meets them at 5.5, 6.0, 0.3 + 2 pi, 0.9 + 2 pi, on one sweep.
    let phis = [5.5, 6.0, 0.3, 0.9];
    let problem = exact(FOUR_BAR, &phis, &[1.0; 4], false);
    let mut z = vec![FOUR_BAR[4]];
    z.extend(phis);
    let c = verify(&problem, &z);
    assert!(c.is_valid(), "{c:?}");
    let unwrapped: Vec<f64> = c.inputs.iter().map(|x| x[0]).collect();
    for (got, want) in unwrapped.iter().zip([5.5, 6.0, 0.3 + TAU, 0.9 + TAU]) {
        assert_close!(*got, want, crate::support::tol::ULPS * 10.0);
    }
}

/// Over a range of crank angles shorter than a turn, the motion stays in it: targets met at
/// 2.0, 2.8 and 0.2 within `[0, 3]` are out of order (forward from 2.8 to 0.2 the crank turns
/// through 3 to 2 pi, which the range leaves out; backward it passes 2.0 again). The candidate
/// was valid, its last input reported as 0.2 + 2 pi, outside the range. Over a whole turn the
/// same targets are one motion passing the zero.
#[test]
fn cyclic_order_needs_a_range_of_a_whole_turn() {
    let phis = [2.0, 2.8, 0.2];
    let poses: Vec<([f64; 2], [f64; 2])> = phis.iter().map(|&x| four_bar_pose(FOUR_BAR, x, 1.0)).collect();
    let [a, b, c, d, e, alpha] = FOUR_BAR;
    // The targets' inputs whole turns from those they were made at (`shift`).
    let candidate = |lo: f64, hi: f64, shift: f64| {
        let task = Task::path("p", poses.iter().map(|(t, _)| *t)).untimed(lo, hi);
        let problem = Problem::new(CouplerFourBar { a, b, c, d, e, alpha }, &Design::new().var("e", 1.5, 1.9), &task)
            .unwrap()
            .with_guesses(poses.iter().map(|(_, q)| *q).collect())
            .unwrap();
        verify(&problem, &[e, phis[0] + shift, phis[1] + shift, phis[2] + shift])
    };
    let short = candidate(0.0, 3.0, 0.0);
    assert_eq!(short.defects.first(), Some(&Defect::Order), "{short:?}");
    let turn = candidate(0.0, TAU, 0.0);
    assert!(turn.is_valid(), "{turn:?}");
    assert_close!(turn.inputs[2][0], 0.2 + TAU, crate::support::tol::ULPS * 10.0);
    // A turn written from another start, whose width rounds to below 2 pi: a turn still.
    let (lo, hi) = (-6.0 * TAU + 0.2, -5.0 * TAU + 0.2);
    assert!(hi - lo < TAU);
    let shifted = candidate(lo, hi, -6.0 * TAU);
    assert!(shifted.is_valid(), "{shifted:?}");
}

#[test]
fn constraints_full_rotation_transmission_and_link_ratio() {
    // The crank-rocker turns fully; its transmission angle is extreme with crank and frame in
    // line (phi = 0 and pi, both sampled when the motion starts at 0): from the triangle of
    // coupler, rocker and |AD| = d -+ a, cos mu = (b^2 + c^2 - AD^2) / (2 b c).
    let [a, b, c, d, ..] = FOUR_BAR;
    let mu = |ad: f64| {
        let m = ((b * b + c * c - ad * ad) / (2.0 * b * c)).acos();
        m.min(PI - m)
    };
    let expected = mu(d - a).min(mu(d + a));
    let constraints = Constraints::default()
        .with_full_rotation()
        .with_transmission("beta", "gamma", expected + 0.01)
        .with_link_ratio(&["a", "b", "c", "d"], 3.0);
    let problem = exact(FOUR_BAR, &[0.0, 1.0, 2.0], &[1.0; 3], true).with_constraints(&constraints).unwrap();
    let cand = verify(&problem, &[FOUR_BAR[4]]);
    let min = cand.min_transmission.unwrap();
    assert_close!(min, expected, crate::support::tol::SOLVE);
    assert_eq!(cand.defects, [Defect::Transmission { min }, Defect::LinkRatio { ratio: b / a }]);

    // The triple rocker cannot turn fully.
    let problem = exact(TRIPLE_ROCKER, &[0.0, 1.0], &[1.0; 2], true)
        .with_constraints(&Constraints::default().with_full_rotation())
        .unwrap();
    assert_eq!(verify(&problem, &[TRIPLE_ROCKER[4]]).defects, [Defect::NoFullRotation]);
}

#[test]
fn the_smallest_transmission_angle_is_located_between_samples() {
    // The crank-rocker's transmission angle is smallest with crank and frame in line (phi = 0 or
    // pi). Here no sample lies there: the targets start 2.5 degrees past phi = 0, so the turn
    // checked for full rotation (samples every 5 degrees from the first target) passes both
    // extremes 2.5 degrees away, and the stretch from 3.0 to 3.3 passes phi = pi between
    // its samples. The verification reports the located minimum, the closed form's.
    let [a, b, c, d, ..] = FOUR_BAR;
    let mu = |ad: f64| {
        let m = ((b * b + c * c - ad * ad) / (2.0 * b * c)).acos();
        m.min(PI - m)
    };
    let expected = mu(d - a).min(mu(d + a));
    let start = 2.5f64.to_radians();
    let turn = Constraints::default().with_full_rotation().with_transmission("beta", "gamma", 0.0);
    let problem = exact(FOUR_BAR, &[start, 1.0, 2.0], &[1.0; 3], true).with_constraints(&turn).unwrap();
    let cand = verify(&problem, &[FOUR_BAR[4]]);
    assert_close!(cand.min_transmission.unwrap(), expected, crate::support::tol::SOLVE);
    assert!(cand.is_valid(), "{cand:?}");

    let stretch = Constraints::default().with_transmission("beta", "gamma", 0.0);
    let problem = exact(FOUR_BAR, &[3.0, 3.3], &[1.0; 2], true).with_constraints(&stretch).unwrap();
    let cand = verify(&problem, &[FOUR_BAR[4]]);
    assert_close!(cand.min_transmission.unwrap(), mu(d + a), crate::support::tol::SOLVE);

    // A bound just below the located minimum holds; one just above it (below every sample's
    // angle) is violated.
    for (bound, valid) in [(expected - 1e-9, true), (expected + 1e-9, false)] {
        let c = Constraints::default().with_full_rotation().with_transmission("beta", "gamma", bound);
        let problem = exact(FOUR_BAR, &[start, 1.0, 2.0], &[1.0; 3], true).with_constraints(&c).unwrap();
        assert_eq!(verify(&problem, &[FOUR_BAR[4]]).is_valid(), valid, "bound {bound}");
    }
}

/// Targets far beyond the design's reach, near the largest `f64` (`1e300` and `8e307` from it): the
/// errors are the distances, about `1e300`, not infinite, though their squares leave the range
/// of `f64` (the residual norm, the errors and the scale the tolerances are relative to
/// overflowed).
#[test]
fn targets_near_the_largest_f64_have_finite_errors() {
    let phis = [0.0, 1.0, 2.0];
    for far in [1e300, 8e307, -8e307] {
        // Targets spread by `far`, far apart too: their centroid and spread overflowed.
        let targets = [[far, 0.0], [0.0, far], [far, far]];
        let task = Task::path("p", targets).timed(phis.to_vec());
        let [a, b, c, d, e, alpha] = FOUR_BAR;
        let m = CouplerFourBar { a, b, c, d, e, alpha };
        let problem = Problem::new(m, &Design::new().var("e", 0.5 * e, 2.0 * e), &task).unwrap();
        // The design's points lie within `a + e` of the origin, 1e-290 of `far`: each error is
        // the target's distance from the origin to that relative rounding, `|far|` or
        // `sqrt(2) |far|`.
        let norm = problem.residual_norm(&[e]).unwrap();
        let want = far.abs() * 2f64.sqrt() * 2f64.sqrt();
        assert!((norm / want - 1.0).abs() < 1e-15, "{far:e}: {norm:e} vs {want:e}");
        let cand = Search::default()
            .with_local(kinloop::synthesis::LocalConfig::default().with_max_evaluations(1))
            .refine(&problem, &[e])
            .unwrap();
        for (got, want) in cand.errors.iter().zip([1.0, 1.0, 2f64.sqrt()]) {
            assert!((got / (want * far.abs()) - 1.0).abs() < 1e-15, "{far:e}: {cand:?}");
        }
        assert!((cand.max_error / (2f64.sqrt() * far.abs()) - 1.0).abs() < 1e-15, "{cand:?}");
        assert!((cand.rms_error / (far.abs() * (4.0f64 / 3.0).sqrt()) - 1.0).abs() < 1e-15, "{cand:?}");
    }
}

/// A target moved off the design's coupler curve: the best fit misses it, valid without a
/// bound (the motion has no defect); with `max_error` below its error the first target missed
/// by more is a `Miss` (after the motion's defects), counted in the rejections; a bound that
/// is not finite and positive is refused.
#[test]
fn a_target_missed_by_more_than_max_error_is_a_miss() {
    let phis = [0.0, 1.0, 2.0, 3.0];
    let mut poses: Vec<([f64; 2], [f64; 2])> = phis.iter().map(|&x| four_bar_pose(FOUR_BAR, x, 1.0)).collect();
    poses[2].0[0] += 0.1;
    let task = Task::path("p", poses.iter().map(|(t, _)| *t)).timed(phis.to_vec());
    let [a, b, c, d, e, alpha] = FOUR_BAR;
    let m = CouplerFourBar { a, b, c, d, e, alpha };
    let problem = Problem::new(m, &Design::new().var("e", 0.5 * e, 2.0 * e), &task)
        .unwrap()
        .with_guesses(poses.iter().map(|(_, q)| *q).collect())
        .unwrap();
    let free = Search::default().refine(&problem, &[e]).unwrap();
    assert!(free.is_valid() && free.max_error > 0.01, "{free:?}");

    let bound = 0.5 * free.max_error;
    let bounded = problem.clone().with_constraints(&Constraints::default().with_max_error(bound)).unwrap();
    let cand = Search::default().refine(&bounded, &[e]).unwrap();
    // The same fit, judged against the bound.
    assert_eq!((&cand.values, &cand.errors), (&free.values, &free.errors));
    let target = cand.errors.iter().position(|&x| x > bound).unwrap();
    assert_eq!(cand.defects, [Defect::Miss { target, error: cand.errors[target] }]);
    let report = Search::default().with_starts(0..4).run(&bounded).unwrap();
    assert_eq!(report.valid, 0);
    // Every local solve ends at the least-squares fit, on the step (its residual is not zero).
    assert_eq!((report.converged, report.step_tolerance), (0, report.rejected.miss));
    assert_eq!(report.rejected.total(), report.rejected.miss);

    let loose = problem.clone().with_constraints(&Constraints::default().with_max_error(2.0 * free.max_error)).unwrap();
    assert!(Search::default().refine(&loose, &[e]).unwrap().is_valid());

    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let r = problem.clone().with_constraints(&Constraints::default().with_max_error(bad));
        assert!(
            matches!(&r, Err(kinloop::synthesis::SynthesisError::InvalidConfig(m)) if m.starts_with("max_error is")),
            "{bad}: {:?}",
            r.err()
        );
    }
}

kinloop::mechanism! {
    /// A dyad driven by a slider: the slider's joint at `(u, 0)` (a length input), coupler `b`,
    /// rocker `c` pivoted at `(d, h)`; the point `p` at `e` from the slider's joint, `alpha` off
    /// the coupler.
    #[kinloop(sensitivities)]
    pub struct SlideDyad {
        params b = 3.0, c = 2.5, d = 1.0, h = 2.0, e = 1.5, alpha = 0.6;
        input u;
        unknowns beta = 1.0, gamma = 2.5;
        loop abcd: (u, 0) + b @ beta == (d, h) + c @ gamma;
        point p = (u, 0) + e @ (beta + alpha);
    }
}

/// The smallest transmission angle over the motion checked is located between the samples in
/// any unit, for a length input too. The joint's distance to the rocker's pivot,
/// `L^2 = (u - d)^2 + h^2`, is least at `u = d`, where by the law of cosines
/// `cos mu = (b^2 + c^2 - h^2) / (2 b c) = 11.25 / 15`: the smallest transmission angle is
/// `acos(0.75)`, between the samples of the stretch from the target at 0.3 to the one at 1.45
/// (the nearest 0.019 away, 3.5e-5 rad larger). The path's direction was normalised by the sum
/// of the squares of its components, the input's range: at lengths of `2^600` (`4e180`) that
/// overflowed, and the angle fell back to the samples' smallest. (Far below the unit a length
/// input's acceleration analogs, `1 / length^2`, leave the range of `f64` themselves.)
///
/// Tolerance: the located minimum is the closed form's to the solves' accuracy (`tol::SOLVE`).
#[test]
fn the_smallest_transmission_angle_over_a_length_input_is_located_in_any_unit() {
    let us = [-0.7, 0.3, 1.45, 2.0];
    let want = 0.75f64.acos();
    for k in [1.0, 2f64.powi(600)] {
        let m = SlideDyad { b: 3.0 * k, c: 2.5 * k, d: k, h: 2.0 * k, e: 1.5 * k, alpha: 0.6 };
        let inputs: Vec<f64> = us.iter().map(|u| u * k).collect();
        let mut q = m.guess(inputs[0]);
        let mut targets = Vec::new();
        let mut guesses = Vec::new();
        for &u in &inputs {
            let s = m.kinematics(u, &q).unwrap();
            q = s.q;
            targets.push([s.out.p.x, s.out.p.y]);
            guesses.push(<[f64; 2]>::from(s.q));
        }
        let task = Task::path("p", targets).timed(inputs.clone());
        let transmission = Constraints::default().with_transmission("beta", "gamma", 0.0);
        let problem = Problem::new(m, &Design::new().var("e", 0.75 * k, 3.0 * k), &task)
            .unwrap()
            .with_guesses(guesses)
            .unwrap()
            .with_constraints(&transmission)
            .unwrap();
        let cand = Search::default().refine(&problem, &[m.e]).unwrap();
        let min = cand.min_transmission.unwrap();
        assert!((min - want).abs() < crate::support::tol::SOLVE, "size {k:e}: {min} against {want}: {cand:?}");
    }
}
