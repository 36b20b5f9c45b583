//! Known answers: targets sampled from closed forms of a design (`mechanisms.rs`, plain
//! trigonometry), its dimensions hidden, found again by the search.
//!
//! Tolerances: the targets are exact to rounding (~1e-16 of their size), and the problems are
//! overdetermined or square with a Jacobian of full rank at the truth, so the residual of the
//! recovered design is at rounding (`RESIDUAL`, 1e-13 of the targets' size, a few hundred
//! roundings) and the dimensions agree to the residual times the condition number of the
//! Jacobian: `DIMENSION`, 1e-12 relative (of a value, absolute below 1: `assert_close!`). Measured
//! when it was set: 3.0e-14 at worst (the fit with a placement), 1.4e-14 the six-bar's, 6.7e-15
//! or less the others' (the evolution's 3.2e-15); the margin, 30, is for the rounding of other
//! platforms' sines and cosines in the targets and the solves (a few ulps each, multiplied by
//! the same condition numbers). README.md states this tolerance.

use super::mechanisms::{
    CouplerFourBar, FOUR_BAR, SLIDER, STEPHENSON, Slider, Stephenson, coupler_point, four_bar_pose, slider_x,
    stephenson_point,
};
use kinloop::synthesis::{Design, PlacementBounds, Problem, Search, SynthesisReport, Task, chebyshev};

const RESIDUAL: f64 = 1e-13;
const DIMENSION: f64 = 1e-12;

/// Design variables `names` with the truth `values`, each within `spread` of its value.
pub fn design(names: &[&str], values: &[f64], spread: f64) -> Design {
    names.iter().zip(values).fold(Design::new(), |d, (n, v)| d.var(*n, v * (1.0 - spread), v * (1.0 + spread)))
}

/// The best valid candidate meets the targets to rounding and has the true dimensions.
pub fn check_recovered(report: &SynthesisReport, truth: &[f64], size: f64) {
    let best = report.best().unwrap_or_else(|| panic!("no valid candidate: {report:#?}"));
    assert!(best.max_error <= RESIDUAL * size, "max error {:e}", best.max_error);
    // With the exact Jacobian the best start converges in few steps (measured: 6 to 18
    // evaluations, 40 for the 22 unknowns of the fitting case, from starts up to 40 % off); a
    // wrong derivative would need far more, or stall.
    assert!(best.local.evaluations <= 60, "{:?}", best.local);
    for (name, (got, want)) in report.variables.iter().zip(best.values.iter().zip(truth)) {
        assert_close!(*got, *want, rel = DIMENSION, "{name}: {got} vs {want}");
    }
}

pub const FOUR_BAR_NAMES: [&str; 6] = ["a", "b", "c", "d", "e", "alpha"];

#[test]
fn four_bar_path_with_timing() {
    // Five points at prescribed crank angles: ten equations for the six dimensions.
    let phis: Vec<f64> = (0..5).map(|k| 0.3 + 1.1 * k as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(FOUR_BAR, p)).collect();
    let task = Task::path("p", targets).timed(phis);
    let problem = Problem::new(CouplerFourBar::default(), &design(&FOUR_BAR_NAMES, &FOUR_BAR, 0.3), &task).unwrap();
    let report = Search::default().with_starts(0..24).run(&problem).unwrap();
    check_recovered(&report, &FOUR_BAR, 1.0);
    assert!(report.valid >= 1 && report.evaluations > 0);
}

/// A channel's weight only scales the residuals: the same design, to the bit, with weights
/// from 1e-200 to 1e200 (powers of two apart from one: the residuals exactly scaled). At 1e-200
/// the normal equations underflowed to zero and every start "converged" where it began, one
/// with a crank 11 % off reported as meeting the targets.
#[test]
fn a_uniform_weight_finds_the_same_design() {
    let phis: Vec<f64> = (0..5).map(|k| 0.3 + 1.1 * k as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(FOUR_BAR, p)).collect();
    let run = |w: f64| {
        let task = Task::path("p", targets.clone()).timed(phis.clone()).with_weights(vec![w]);
        let problem = Problem::new(CouplerFourBar::default(), &design(&FOUR_BAR_NAMES, &FOUR_BAR, 0.3), &task).unwrap();
        Search::default().with_starts(0..24).run(&problem).unwrap()
    };
    let one = run(1.0);
    check_recovered(&one, &FOUR_BAR, 1.0);
    for e in [-664, -100, 100, 664] {
        let w = 2f64.powi(e);
        let report = run(w);
        check_recovered(&report, &FOUR_BAR, w);
        let (a, b) = (one.best().unwrap(), report.best().unwrap());
        assert_eq!(a.values, b.values, "weight 2^{e}");
        assert_eq!((report.valid, report.evaluations), (one.valid, one.evaluations), "weight 2^{e}");
    }
}

#[test]
fn four_bar_path_without_timing() {
    // Eight points, their crank angles unknown: sixteen equations for six dimensions and eight
    // input values, met in order along one turn of the crank.
    let phis: Vec<f64> = (0..8).map(|k| 0.2 + 0.7 * k as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(FOUR_BAR, p)).collect();
    let task = Task::path("p", targets).untimed(0.0, std::f64::consts::TAU);
    let problem = Problem::new(CouplerFourBar::default(), &design(&FOUR_BAR_NAMES, &FOUR_BAR, 0.2), &task).unwrap();
    assert_eq!(problem.dims(), 14);
    let report = Search::default().with_starts(0..48).run(&problem).unwrap();
    check_recovered(&report, &FOUR_BAR, 1.0);
    let best = report.best().unwrap();
    for (x, want) in best.inputs.iter().zip(&phis) {
        assert_close!(x[0], *want, rel = DIMENSION, "crank angle");
    }
}

#[test]
fn slider_crank_function_with_chebyshev_spacing() {
    // The slider's position at five crank angles at Chebyshev spacing over half a turn.
    let phis = chebyshev(0.2, 3.0, 5).unwrap();
    let task = Task::function("x", phis.iter().map(|&p| (p, slider_x(SLIDER, p))));
    let problem = Problem::new(Slider::default(), &design(&["r", "l", "e"], &SLIDER, 0.4), &task).unwrap();
    let report = Search::default().with_starts(0..16).run(&problem).unwrap();
    check_recovered(&report, &SLIDER, 1.0);
}

#[test]
fn four_bar_angle_function() {
    // The rocker angle gamma as a function of the crank angle (an angle column: compared modulo
    // a turn): its proportions a, b, c with the frame d fixed, as the function is scale-free.
    let [a, b, c, d, ..] = FOUR_BAR;
    let gamma = |phi: f64| {
        // The rocker angle from the coupler point construction with e = b, alpha = 0 (the point
        // is the joint C itself).
        let [x, y] = coupler_point([a, b, c, d, b, 0.0], phi);
        y.atan2(x - d)
    };
    let phis: Vec<f64> = (0..6).map(|k| 0.5 + 0.8 * k as f64).collect();
    let task = Task::function("gamma", phis.iter().map(|&p| (p, gamma(p))));
    let m = CouplerFourBar { d, ..CouplerFourBar::default() };
    let problem = Problem::new(m, &design(&["a", "b", "c"], &[a, b, c], 0.3), &task).unwrap();
    let report = Search::default().with_starts(0..16).run(&problem).unwrap();
    check_recovered(&report, &[a, b, c], 1.0);
}

#[test]
fn stephenson_six_bar_path_with_timing() {
    // Eleven dimensions from eight points at prescribed crank angles (sixteen equations): a path
    // no four-bar declaration can be asked for.
    let phis: Vec<f64> = (0..8).map(|k| 0.2 + 0.75 * k as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| stephenson_point(STEPHENSON, p)).collect();
    let task = Task::path("r", targets).timed(phis);
    let names = ["a", "b", "c", "d", "e", "alpha", "f", "g", "gx", "gy", "h"];
    let problem = Problem::new(Stephenson::default(), &design(&names, &STEPHENSON, 0.1), &task).unwrap();
    let report = Search::default().with_starts(0..32).run(&problem).unwrap();
    check_recovered(&report, &STEPHENSON, 1.0);
}

#[test]
fn four_bar_path_fitting_with_a_placement() {
    // Twelve samples of the coupler curve moved by (dx, dy) = (2, -1) and turned by 0.7 rad,
    // crank angles free: the dimensions, the crank angles and the placement are found again.
    let (dx, dy, turn) = (2.0, -1.0, 0.7f64);
    let (s, c) = turn.sin_cos();
    let phis: Vec<f64> = (0..12).map(|k| 0.1 + 0.5 * k as f64).collect();
    let samples: Vec<[f64; 2]> = phis
        .iter()
        .map(|&p| {
            let [x, y] = coupler_point(FOUR_BAR, p);
            [dx + c * x - s * y, dy + s * x + c * y]
        })
        .collect();
    let bounds = PlacementBounds::translation((1.0, 3.0), (-2.0, 0.0)).with_rotation((0.4, 1.0));
    let task = Task::fit("p", samples).untimed(0.0, std::f64::consts::TAU).with_placement(bounds);
    let problem = Problem::new(CouplerFourBar::default(), &design(&FOUR_BAR_NAMES, &FOUR_BAR, 0.2), &task).unwrap();
    assert_eq!(problem.dims(), 6 + 12 + 4);
    let report = Search::default().with_starts(0..8).run(&problem).unwrap();
    check_recovered(&report, &FOUR_BAR, 1.0);
    let placement = report.best().unwrap().placement.unwrap();
    for (got, want) in placement.iter().zip([dx, dy, turn, 1.0]) {
        assert_close!(*got, want, rel = DIMENSION, "placement");
    }
}

#[test]
fn four_bar_motion_generation() {
    // Four poses of the coupler (its point and its angle theta) at prescribed crank angles:
    // twelve equations for the six dimensions.
    let phis = [0.3, 1.2, 2.4, 3.9];
    let poses: Vec<[f64; 3]> = phis
        .iter()
        .map(|&p| {
            let ([x, y], [beta, _]) = four_bar_pose(FOUR_BAR, p, 1.0);
            [x, y, beta + FOUR_BAR[5]]
        })
        .collect();
    let task = Task::motion("p", "theta", poses).timed(phis);
    let problem = Problem::new(CouplerFourBar::default(), &design(&FOUR_BAR_NAMES, &FOUR_BAR, 0.3), &task).unwrap();
    let report = Search::default().with_starts(0..16).run(&problem).unwrap();
    check_recovered(&report, &FOUR_BAR, 1.0);
}

#[test]
fn four_bar_path_on_the_other_assembly_mode() {
    // The same five timed points, sampled with the coupler joint on the right of AD (the mode
    // the declared guess does not pick): found when the first position is given on that mode.
    let phis: Vec<f64> = (0..5).map(|k| 0.3 + 1.1 * k as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| four_bar_pose(FOUR_BAR, p, -1.0).0).collect();
    let (_, [beta, gamma]) = four_bar_pose(FOUR_BAR, phis[0], -1.0);
    let task = Task::path("p", targets).timed(phis);
    let design = design(&FOUR_BAR_NAMES, &FOUR_BAR, 0.3);
    let problem = Problem::new(CouplerFourBar::default(), &design, &task).unwrap();
    // On the declared guess's mode no design of the box meets them (measured: the best valid
    // candidate misses by 1.7, the size of the curve) ...
    let declared = Search::default().with_starts(0..8).run(&problem).unwrap();
    assert!(declared.best().is_none_or(|b| b.max_error > 1e-6), "{:?}", declared.best());
    // ... on the given mode they are.
    let report = Search::default().with_starts(0..24).run(&problem.with_guess([beta, gamma]).unwrap()).unwrap();
    check_recovered(&report, &FOUR_BAR, 1.0);
}

#[test]
fn an_optimum_beyond_a_bound_stops_on_it() {
    // The slider's crank is at most 1.0 here, the truth's 1.1: the local solves end on the
    // bound (held there while the others move), at a local minimum of non-zero residual.
    let phis = chebyshev(0.2, 3.0, 5).unwrap();
    let task = Task::function("x", phis.iter().map(|&p| (p, slider_x(SLIDER, p))));
    let design = Design::new().var("r", 0.5, 1.0).var("l", 2.0, 5.0).var("e", -1.0, 1.0);
    let problem = Problem::new(Slider::default(), &design, &task).unwrap();
    let report = Search::default().with_starts(0..8).run(&problem).unwrap();
    let best = report.best().unwrap();
    assert_eq!(best.values[0], 1.0, "{best:?}");
    assert!(best.max_error > 1e-3 && best.max_error.is_finite(), "{best:?}");
    // A local minimum of non-zero residual: stopped on the step, the residual not within `tol`.
    assert_eq!(best.local.stop, kinloop::analysis::OptimizerStop::StepTolerance, "{best:?}");
}

/// A length (`e`) and an angle (`alpha`) recovered together in any unit of length, from 1e-100
/// to 1e100: the angle's column of the Jacobian grows with the unit and the length's does not.
/// The local solve's damping floor, relative to the largest column, swamped the length's at
/// 1e100: its steps came out too small to change it, and the solve stopped "converged" with
/// the length where it started and errors the size of the mechanism.
#[test]
fn a_length_and_an_angle_are_recovered_in_any_unit() {
    let phis: Vec<f64> = (0..5).map(|k| 0.3 + 1.1 * k as f64).collect();
    for s in [1e-100, 1e-9, 1.0, 1e12, 1e100] {
        let [a, b, c, d, e, alpha] = FOUR_BAR;
        let truth = [a * s, b * s, c * s, d * s, e * s, alpha];
        let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(truth, p)).collect();
        let task = Task::path("p", targets).timed(phis.clone());
        let m = CouplerFourBar { a: truth[0], b: truth[1], c: truth[2], d: truth[3], e: truth[4], alpha };
        let vars = Design::new().var("e", 0.5 * truth[4], 2.0 * truth[4]).var("alpha", 0.0, 1.0);
        let problem = Problem::new(m, &vars, &task).unwrap();
        let cand = Search::default().refine(&problem, &[1.1 * truth[4], 0.5]).unwrap();
        assert!(cand.local.stop == kinloop::analysis::OptimizerStop::Converged, "{s:e}: {:?}", cand.local);
        assert!(cand.max_error <= RESIDUAL * s, "{s:e}: max error {:e}", cand.max_error);
        // In units of `s`: `assert_close!` is absolute below 1, and 1e-12 of nothing at 1e-100.
        assert_close!(cand.values[0] / s, truth[4] / s, rel = DIMENSION, "{s:e}: e");
        assert_close!(cand.values[1], alpha, rel = DIMENSION, "{s:e}: alpha");
    }
}

/// The search is free of the unit of length: the same prescribed-input problem (the crank and
/// coupler of a four-bar from eight exact coupler points, its other lengths fixed), every length
/// scaled by `s`, finds the same design relative to `s`. With lengths near 1e-30 a step test
/// with an absolute floor (in units of length) took the first step for convergence (a crank
/// 1.4e-4 off after two evaluations). The compiled mechanism's position solve assembles it
/// from 1e-150 to 1e150 (beyond, its loop's products of lengths leave the doubles); the command
/// line's run-time model is tested to 1e-300 (`cli/tests/synth.rs`).
#[test]
fn prescribed_inputs_at_any_unit_of_length() {
    let truth = [1.1, 2.8, 2.5, 3.0, 1.5, 0.6];
    let phis: Vec<f64> = (0..8).map(|k| k as f64 * std::f64::consts::FRAC_PI_4).collect();
    let run = |s: f64| {
        let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(truth, p).map(|v| v * s)).collect();
        let task = Task::path("p", targets).timed(phis.clone());
        let m = CouplerFourBar { c: 2.5 * s, d: 3.0 * s, e: 1.5 * s, ..CouplerFourBar::default() };
        let design = Design::new().var("a", 0.8 * s, 1.4 * s).var("b", 2.0 * s, 3.5 * s);
        let problem = Problem::new(m, &design, &task).unwrap();
        Search::default().with_starts(0..16).run(&problem).unwrap()
    };
    let one = run(1.0);
    check_recovered(&one, &truth[..2], 1.0);
    for s in [1e-150, 1e-100, 1e-30, 1e30, 1e100, 1e150] {
        let report = run(s);
        let best = report.best().unwrap_or_else(|| panic!("no valid candidate at {s:e}: {report:#?}"));
        assert!(best.max_error <= RESIDUAL * s, "{s:e}: max error {:e}", best.max_error);
        for (name, (got, want)) in report.variables.iter().zip(best.values.iter().zip(&truth)) {
            assert_close!(*got / s, *want, rel = 1e-10, "{name} at {s:e}: {got:e}");
        }
        assert!(best.local.evaluations > 2, "{s:e}: {:?}", best.local);
        assert_eq!(report.valid, one.valid, "{s:e}");
    }
}

/// A digitised curve of thousands of points with free inputs: each target's input moves only
/// its own residuals, so the search's normal equations are an arrow and cost linearly in the
/// targets (dense, a start at 1600 targets took one to two minutes, 2000 about twice that). The 2000
/// targets and their 2002 unknowns are solved from one start to the known design.
#[test]
fn a_curve_of_two_thousand_points_with_free_inputs() {
    let truth = [1.1, 2.8, 2.5, 3.0, 1.5, 0.6];
    let n = 2000;
    let phis: Vec<f64> = (0..n).map(|k| 0.1 + 6.0 * k as f64 / n as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(truth, p)).collect();
    let task = Task::path("p", targets).untimed(0.0, std::f64::consts::TAU);
    let m = CouplerFourBar { c: 2.5, d: 3.0, e: 1.5, alpha: 0.6, ..CouplerFourBar::default() };
    let design = Design::new().var("a", 0.8, 1.4).var("b", 2.0, 3.5);
    let problem = Problem::new(m, &design, &task).unwrap();
    assert_eq!(problem.dims(), n + 2);
    let report = Search::default().with_starts(0..1).run(&problem).unwrap();
    check_recovered(&report, &truth[..2], 1.0);
    let best = report.best().unwrap();
    for (x, want) in best.inputs.iter().zip(&phis) {
        assert_close!(x[0], *want, rel = DIMENSION, "crank angle");
    }
}
