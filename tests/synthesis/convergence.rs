//! How the local solve stops with few targets and with many: `Converged` where the design meets
//! its targets exactly, whatever their number, and on the step where a least-squares fit ends.
//!
//! Tolerances: the targets are sampled from the closed form of the design (rounding, about
//! `3e-16` of their size per target at 5 targets as at 5000, measured), and `LocalConfig::tol`
//! is compared with the residuals' root mean square over the targets (a candidate's
//! `rms_error`); their norm grows with the square root of their number, and at 5000 targets an
//! exact fit's (about 2e-14 of the size, measured) passed the default `1e-14`.

use super::mechanisms::{CouplerFourBar, coupler_point};
use kinloop::analysis::OptimizerStop;
use kinloop::synthesis::{Candidate, Design, LocalConfig, Problem, Search, Task};

/// The design the targets are sampled from: `a` and `b` vary, the other dimensions are fixed.
const TRUTH: [f64; 6] = [1.1, 2.8, 2.5, 3.0, 1.5, 0.6];

/// `n` points of the truth's coupler curve at prescribed crank angles over most of a turn, each
/// moved by `nudge` (`(+nudge, 0)` at even targets, `(-nudge, 0)` at odd ones), and the local
/// solve's candidate from `a`, `b` 5 % off the truth; with the targets' size (their largest
/// distance from their centroid).
fn fit(n: usize, nudge: f64) -> (Candidate, f64) {
    let phis: Vec<f64> = (0..n).map(|k| 0.1 + 6.0 * k as f64 / n as f64).collect();
    let targets: Vec<[f64; 2]> = phis
        .iter()
        .enumerate()
        .map(|(k, &p)| {
            let [x, y] = coupler_point(TRUTH, p);
            [x + if k % 2 == 0 { nudge } else { -nudge }, y]
        })
        .collect();
    let mean = targets.iter().fold([0.0, 0.0], |m, t| [m[0] + t[0] / n as f64, m[1] + t[1] / n as f64]);
    let size = targets.iter().map(|t| (t[0] - mean[0]).hypot(t[1] - mean[1])).fold(0.0, f64::max);
    let task = Task::path("p", targets).timed(phis);
    let [_, _, c, d, e, alpha] = TRUTH;
    let m = CouplerFourBar { c, d, e, alpha, ..CouplerFourBar::default() };
    let problem = Problem::new(m, &Design::new().var("a", 0.8, 1.4).var("b", 2.0, 3.5), &task).unwrap();
    let candidate = Search::default().refine(&problem, &[1.05 * TRUTH[0], 0.95 * TRUTH[1]]).unwrap();
    (candidate, size)
}

/// An exact fit is `Converged` at 5 targets and at 5000 alike, its residuals' root mean square
/// within `tol` of the targets' size (at 5000 the norm over every residual was compared, which
/// the rounding of so many targets passes: the solve was reported stopped on the step).
#[test]
fn an_exact_fit_of_any_number_of_targets_converges() {
    let tol = LocalConfig::default().tol;
    for n in [5, 5000] {
        let (best, size) = fit(n, 0.0);
        assert_eq!(best.local.stop, OptimizerStop::Converged, "{n} targets: {:?}", best.local);
        assert!(best.rms_error <= tol * size, "{n} targets: rms {:e} of a size {size}", best.rms_error);
        for (got, want) in best.values.iter().zip(&TRUTH) {
            assert!((got - want).abs() <= 1e-12 * want, "{n} targets: {got} vs {want}");
        }
    }
}

/// The same 5000 targets moved off the curve by a millionth of their size, alternately to
/// either side: no design meets them, and the least-squares fit stops on the step with its
/// residuals' root mean square far above `tol`, not `Converged`.
#[test]
fn a_least_squares_fit_of_many_targets_stops_on_the_step() {
    let (exact, size) = fit(5000, 0.0);
    let nudge = 1e-6 * size;
    let (best, _) = fit(5000, nudge);
    assert_eq!(best.local.stop, OptimizerStop::StepTolerance, "{:?}", best.local);
    // Alternate nudges are nearly orthogonal to every change of `a` and `b`: the fit leaves
    // about all of them.
    assert!(best.rms_error > 0.9 * nudge && best.rms_error <= nudge, "rms {:e}", best.rms_error);
    assert!(best.rms_error > 1e6 * LocalConfig::default().tol * size, "rms {:e}", best.rms_error);
    for (got, want) in best.values.iter().zip(&exact.values) {
        assert!((got - want).abs() <= 1e-6 * want, "{got} vs {want}");
    }
}

/// An exact fit is `Converged` wherever the mechanism stands: the five timed points of a
/// four-bar whose crank pivot is `(s, s)`, the targets moved alike, from 8 starts and the
/// truth. Each residual is then computed from values of magnitude `s` whose rounding alone
/// (about `2e-16 s`) passes `tol` times the targets' spread (about 2) from `s = 1e2` on: at
/// `1e4` five of the nine solves, exact to rounding, were reported stopped on the step. The
/// tolerance is now relative to the residuals' resolution too (each target's magnitude, each
/// unknown's share in the residual), and every solve that meets the points converges.
///
/// Tolerances: the points are met to a few roundings of `s` (`1e-13 s`); the dimensions, found
/// from points known to about `2e-16 s`, to `1e-12 s` relative (the Jacobian's smallest
/// singular value, about 0.03, costs at most a factor of 30 over that).
#[test]
fn an_exact_fit_far_from_the_origin_converges() {
    use super::mechanisms::{FOUR_BAR, PlacedFourBar};
    let phis: Vec<f64> = (0..5).map(|k| 0.3 + 1.1 * k as f64).collect();
    let truth @ [a, b, c, d, e, alpha] = FOUR_BAR;
    for s in [1e4, 1e6] {
        let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(truth, p).map(|v| v + s)).collect();
        let task = Task::path("p", targets).timed(phis.clone());
        let design = ["a", "b", "c", "g", "e", "alpha"]
            .iter()
            .zip(truth)
            .fold(Design::new(), |design, (name, v)| design.var(*name, 0.8 * v, 1.2 * v));
        let m = PlacedFourBar { ax: s, ay: s, ..PlacedFourBar::default() };
        let problem = Problem::new(m, &design, &task).unwrap();
        let seed = vec![a, b, c, d, e, alpha];
        let report = Search::default().with_seeds(vec![seed]).with_starts(0..8).run(&problem).unwrap();
        assert_eq!(report.step_tolerance, 0, "at {s:e}: {report:#?}");
        let met: Vec<&Candidate> = report.candidates.iter().filter(|c| c.max_error <= 1e-13 * s).collect();
        assert!(!met.is_empty(), "at {s:e}: {report:#?}");
        for c in met {
            assert_eq!(c.local.stop, OptimizerStop::Converged, "at {s:e}: {:?}", c.local);
            for (got, want) in c.values.iter().zip(truth) {
                assert!((got - want).abs() <= 1e-12 * s * want, "at {s:e}: {got} vs {want}");
            }
        }
    }
}
