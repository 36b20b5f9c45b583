//! Classical closed forms as seeds of the general search (`Search::with_seeds`): Freudenstein's
//! three-point `y = log10 x` generator and a pair of Burmester dyads of five poses, mapped by
//! `classical::FourBar` onto declared four-bars. Checked against the 50-digit mpmath references
//! of `runtime/src/synthesis/classical/reference/` (independent of the library).

use super::mechanisms::{FunctionFourBar, PlacedFourBar};
use kinloop::Vec2;
use kinloop::analysis::OptimizerStop;
use kinloop::deg;
use kinloop::synthesis::classical::{
    BurmesterConfig, FourBar, FunctionMap, Pose, PrecisionPoint, burmester_points, chebyshev_points, freudenstein,
};
use kinloop::synthesis::{Design, LocalConfig, Origin, Problem, Search, Task};

/// The targets are met to rounding: a few hundred roundings of the targets' size.
const RESIDUAL: f64 = 1e-13;

/// `name,value` rows of the `exact` case of `freudenstein_log10.csv`.
fn log10_reference(name: &str) -> f64 {
    include_str!("../../runtime/src/synthesis/classical/reference/freudenstein_log10.csv")
        .lines()
        .find_map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0] == "exact" && f[1] == name).then(|| f[2].parse().unwrap())
        })
        .unwrap()
}

/// The declared four-bar with the ground `d = 1` over `points` (its output angle `psi` a
/// function of `phi`), its links `a`, `b`, `c` varied from 0.5 to 8, from the positions of
/// `four_bar` (a closed form's): the problem and the closed form's links as a seed.
fn function_problem(points: &[PrecisionPoint], four_bar: &FourBar) -> (Problem<FunctionFourBar, 2, 1, 0, 4>, Vec<f64>) {
    let task = Task::function("psi", points.iter().map(|p| (p.phi, p.psi)));
    let design = Design::new().var("a", 0.5, 8.0).var("b", 0.5, 8.0).var("c", 0.5, 8.0);
    let problem = Problem::new(FunctionFourBar::default(), &design, &task)
        .unwrap()
        .with_guess([four_bar.couplers[0], four_bar.outputs[0]])
        .unwrap();
    (problem, vec![four_bar.links.input, four_bar.links.coupler, four_bar.links.output])
}

#[test]
fn freudenstein_s_log10_generator_seeds_a_function_generation_problem() {
    // y = log10 x on [1, 2]: input from 60 degrees through 90, output from 90 through 90;
    // three Chebyshev precision points (the textbook three-point case).
    let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0)).unwrap();
    let points = map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0).unwrap()).unwrap();
    let g = freudenstein(&points).unwrap();
    let four_bar = FourBar::from_function_generator(&g, &points).unwrap();
    let (problem, seed) = function_problem(&points, &four_bar);
    // The seed alone: already at the answer, the local solve stops at once.
    let report = Search::default().with_seeds(vec![seed.clone()]).with_starts(0..0).run(&problem).unwrap();
    assert_eq!(report.seeds, 1);
    let best = report.best().unwrap();
    assert_eq!((best.origin, best.start), (Origin::Seed, 0), "{best:?}");
    assert!(best.local.evaluations <= 2, "{:?}", best.local);
    assert!(best.max_error <= RESIDUAL, "output angle error {:e} rad", best.max_error);
    // The link ratios (ground 1) are the 50-digit closed form's: the system's reciprocal
    // condition number is 0.052, so rounding of the angles costs about 20x in the lengths.
    for (got, name) in best.values.iter().zip(["input", "coupler", "output"]) {
        let want = log10_reference(name);
        assert!((got - want).abs() <= 1e-13 * want, "{name}: {got} vs {want}");
    }
    // With Halton starts beside it, the seed's design is the best (one design, whichever start
    // reached it with the smaller rounding error is kept).
    let report = Search::default().with_seeds(vec![seed]).with_starts(0..8).run(&problem).unwrap();
    let best = report.best().unwrap();
    assert!(best.max_error <= RESIDUAL);
    for (got, name) in best.values.iter().zip(["input", "coupler", "output"]) {
        let want = log10_reference(name);
        assert!((got - want).abs() <= 1e-13 * want, "{name}: {got} vs {want}");
    }
}

/// Freudenstein's `log10` generator over seven evenly spaced points (x = 1, 7/6, ..., 2) has no
/// exact design: a least-squares problem, whose optimum was never checked against another
/// solver. The reference is Gauss-Newton at 40 digits on the output angle in closed form
/// (`psi = arg(P) + acos((|P|^2 + c^2 - b^2) / 2c|P|)`, `P = a e^{i phi} - 1`, the assembly
/// mode of the seed), to a step below 1e-32 (`log10_least_squares.py` beside this file):
/// links `a`, `b`, `c` and the residual norm below.
///
/// Tolerances: the optimum is flat, `f(z + dz) - f = |J dz|^2 / 2f` to second order, and the
/// local solve accepts a step only where the computed `f` falls, which it resolves to about
/// `df = 1e-16` (each target's angle is solved to a rounding or so of a radian): the lengths
/// are determined to about `sqrt(2 f df) / s_min` (singular values of `J` 1.2, 0.26 and 0.030
/// at the optimum: 5.6e-8 along the flattest direction, 3e-8 of the coupler), so `1e-7`
/// relative (found: 1.0e-8 from these starts, 4e-11 from others). The residual norm is second
/// order in that error and its angles are solved to about `df`: `1e-12` relative (found:
/// 4e-14).
#[test]
fn a_least_squares_function_generator_reaches_the_40_digit_optimum() {
    // 3.3947470270661315735373, 1.9011648362775403751904, 4.7138245604493715994914 and
    // 0.014462568964236584068715 to 23 digits, here to the nearest double.
    const OPTIMUM: [f64; 3] = [3.3947470270661316, 1.9011648362775404, 4.713824560449372];
    const NORM: f64 = 0.014462568964236584;
    let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0)).unwrap();
    let seeds = map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0).unwrap()).unwrap();
    let four_bar = FourBar::from_function_generator(&freudenstein(&seeds).unwrap(), &seeds).unwrap();
    let xs: Vec<f64> = (0..7).map(|k| 1.0 + k as f64 / 6.0).collect();
    let points = map.precision_points(f64::log10, &xs).unwrap();
    let (problem, seed) = function_problem(&points, &four_bar);
    let report = Search::default().with_seeds(vec![seed]).with_starts(0..8).run(&problem).unwrap();
    let best = report.best().unwrap();
    // Seven points, three lengths: the optimum's residual is not zero, so the solve stops on
    // the step there, not converged (no residual within `tol`); it was reported `Converged`.
    assert_eq!(best.local.stop, OptimizerStop::StepTolerance, "{:?}", best.local);
    assert_eq!(report.converged, 0, "{report:?}");
    assert!(report.step_tolerance >= 1, "{report:?}");
    assert!((best.local.residual - NORM).abs() <= 1e-12 * NORM, "residual norm {:e}", best.local.residual);
    for ((got, want), name) in best.values.iter().zip(OPTIMUM).zip(["a", "b", "c"]) {
        assert!((got - want).abs() <= 1e-7 * want, "{name}: {got} vs {want}");
    }
    // The stop is reported as it happened: out of evaluations, after as many as allowed.
    let short = Search::default().with_local(LocalConfig::default().with_max_evaluations(3));
    let start: Vec<f64> = OPTIMUM.iter().zip([1.2, 0.9, 1.1]).map(|(v, f)| v * f).collect();
    let stopped = short.refine(&problem, &start).unwrap();
    assert_eq!((stopped.local.stop, stopped.local.evaluations), (OptimizerStop::MaxEvaluations, 3));
    assert!(stopped.local.residual > NORM, "{:?}", stopped.local);
}

/// A weight on the output angle of an angle-only task only scales its residuals: the same
/// design, to the bit, with weights from 2^-600 to 2^100 (powers of two: the residuals exactly
/// scaled), and it is the 50-digit closed form's. The residual tolerance was a radian times
/// `1e-14` whatever the weight: at 2^-600 every start counted as converged where it began, the
/// best 0.56 rad off the points.
#[test]
fn a_uniform_weight_on_an_output_angle_finds_the_same_design() {
    let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0)).unwrap();
    let points = map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0).unwrap()).unwrap();
    let four_bar = FourBar::from_function_generator(&freudenstein(&points).unwrap(), &points).unwrap();
    let design = Design::new().var("a", 0.5, 8.0).var("b", 0.5, 8.0).var("c", 0.5, 8.0);
    let run = |w: f64| {
        let task = Task::function("psi", points.iter().map(|p| (p.phi, p.psi))).with_weights(vec![w]);
        let problem = Problem::new(FunctionFourBar::default(), &design, &task)
            .unwrap()
            .with_guess([four_bar.couplers[0], four_bar.outputs[0]])
            .unwrap();
        Search::default().with_starts(0..8).run(&problem).unwrap()
    };
    let one = run(1.0);
    for e in [-600, -40, 100] {
        let w = 2f64.powi(e);
        let report = run(w);
        let best = report.best().unwrap();
        // The error of a target is its weighted residual: an angle's difference times `w`.
        assert!(best.max_error <= RESIDUAL * w, "weight 2^{e}: output angle error {:e} rad", best.max_error / w);
        for (got, name) in best.values.iter().zip(["input", "coupler", "output"]) {
            let want = log10_reference(name);
            assert!((got - want).abs() <= 1e-13 * want, "weight 2^{e}, {name}: {got} vs {want}");
        }
        assert_eq!(best.values, one.best().unwrap().values, "weight 2^{e}");
        assert_eq!((report.valid, report.evaluations), (one.valid, one.evaluations), "weight 2^{e}");
    }
}

/// `burmester_five_poses.csv`: five poses of a four-bar's coupler and mpmath's Burmester pairs
/// (center point, circle point in the first pose), sorted by the center's x.
fn five_poses() -> (Vec<Pose>, Vec<(Vec2, Vec2)>) {
    let (mut poses, mut pairs) = (vec![], vec![]);
    for line in include_str!("../../runtime/src/synthesis/classical/reference/burmester_five_poses.csv").lines().skip(1)
    {
        let f: Vec<&str> = line.split(',').collect();
        let v = |i: usize| f[i].parse::<f64>().unwrap();
        match f[0] {
            "pose" => poses.push(Pose::new(v(1), v(2), v(3))),
            _ => pairs.push((Vec2::new(v(1), v(2)), Vec2::new(v(3), v(4)))),
        }
    }
    (poses, pairs)
}

/// The problem of the five poses for the declared `PlacedFourBar` with the four-bar of two
/// dyads as its seed: design variables in a box of +-0.5 (or +-50 % of a larger value) around
/// the seed's, crank angles free (motion generation prescribes no timing: fifteen equations for
/// ten dimensions and five inputs), each target's position started from the four-bar's own.
fn seeded(four_bar: &FourBar, poses: &[Pose]) -> (Problem<PlacedFourBar, 2, 1, 3, 10>, Vec<f64>) {
    let (e, alpha) = four_bar.coupler_point.unwrap();
    let l = four_bar.links;
    let names = ["ax", "ay", "g", "th", "a", "b", "c", "e", "alpha", "tau"];
    let dims = [
        four_bar.input_pivot.x,
        four_bar.input_pivot.y,
        l.ground,
        four_bar.ground_angle,
        l.input,
        l.coupler,
        l.output,
        e,
        alpha,
        four_bar.body_angle,
    ];
    let design = names.iter().zip(dims).fold(Design::new(), |d, (n, v)| {
        let w = 0.5 * v.abs().max(1.0);
        d.var(*n, v - w, v + w)
    });
    let x = &four_bar.inputs;
    let (lo, hi) =
        (x.iter().copied().fold(f64::INFINITY, f64::min), x.iter().copied().fold(f64::NEG_INFINITY, f64::max));
    let task =
        Task::motion("p", "theta", poses.iter().map(|p| [p.point.x, p.point.y, p.angle])).untimed(lo - 0.5, hi + 0.5);
    let th = four_bar.ground_angle;
    // Each target's position from the four-bar's own link angles: from the previous target's
    // a Newton solve can land on the other assembly mode where the output turns far between
    // poses.
    let guesses = four_bar.couplers.iter().zip(&four_bar.outputs).map(|(b, c)| [b + th, c + th]).collect();
    let problem = Problem::new(PlacedFourBar::default(), &design, &task).unwrap().with_guesses(guesses).unwrap();
    let mut seed = dims.to_vec();
    seed.extend(x);
    (problem, seed)
}

#[test]
fn two_burmester_dyads_seed_a_five_pose_motion_generation_problem() {
    let (poses, pairs) = five_poses();
    let found = burmester_points(&poses, &BurmesterConfig::default()).unwrap();
    assert_eq!(found.dyads.len(), 4);
    // The first two pairs: their cranks are the input and the output of the four-bar the poses
    // were made with.
    let four_bar = FourBar::from_dyads(&found.dyads[0], &found.dyads[1], &poses).unwrap();
    let (problem, seed) = seeded(&four_bar, &poses);
    let report = Search::default().with_seeds(vec![seed]).with_starts(0..0).run(&problem).unwrap();
    let best = report.best().unwrap_or_else(|| panic!("{report:#?}"));
    assert_eq!(best.origin, Origin::Seed);
    // Measured: 2.0e-15 for poses 2.1 apart (`found.size`), 9.7e-16 of their size, in one
    // evaluation (the seed is already there); docs/synthesis.md and synthesis-classical.md quote it.
    assert!(best.max_error <= RESIDUAL * found.size, "pose error {:e}", best.max_error);
    // At the crank angles the poses were made at (30, 55, 80, 110, 140 degrees from the ground
    // line: `generate.py`).
    for (x, want) in best.inputs.iter().zip([30.0, 55.0, 80.0, 110.0, 140.0]) {
        assert!((x[0] - deg(want)).abs() < 1e-12, "{x:?} vs {want} degrees");
    }
    // Its pivots and lengths are the 50-digit reference's Burmester pairs.
    let [ax, ay, g, _, a, b, c, ..] = best.values[..] else { unreachable!() };
    let ((m1, k1), (m2, k2)) = (pairs[0], pairs[1]);
    for (got, want) in [
        (ax, m1.x),
        (ay, m1.y),
        (g, (m2 - m1).norm()),
        (a, (k1 - m1).norm()),
        (b, (k2 - k1).norm()),
        (c, (k2 - m2).norm()),
    ] {
        assert!((got - want).abs() <= 1e-11 * found.size, "{got} vs {want}");
    }
}

#[test]
fn every_pair_of_burmester_dyads_meets_the_five_poses() {
    // Each ordered pair of the four dyads is a four-bar through the five poses (to rounding of
    // the problem's size, or of a far crank's length: up to 31 times the size here), which the
    // verification may still reject for a branch or order defect, the classical defects of
    // Burmester synthesis. The crank of the third dyad driving the first's is one no linkage
    // made, and valid.
    let (poses, _) = five_poses();
    let found = burmester_points(&poses, &BurmesterConfig::default()).unwrap();
    let mut valid = Vec::new();
    for i in 0..4 {
        for j in (0..4).filter(|&j| j != i) {
            let four_bar = FourBar::from_dyads(&found.dyads[i], &found.dyads[j], &poses).unwrap();
            let (problem, seed) = seeded(&four_bar, &poses);
            let report = Search::default().with_seeds(vec![seed]).with_starts(0..0).run(&problem).unwrap();
            let c = &report.candidates[0];
            let size = found.size.max(found.dyads[i].radius()).max(found.dyads[j].radius());
            assert!(c.max_error <= 1e-13 * size, "pair {i}, {j}: {:e}", c.max_error);
            // Exact to the rounding of the 66-long crank too: converged, not stopped on the
            // step (the three pairs it drives were, their residuals' rounding above `tol` of
            // the poses' size).
            assert_eq!(c.local.stop, OptimizerStop::Converged, "pair {i}, {j}: {:?}", c.local);
            if c.is_valid() {
                valid.push((i, j));
            }
        }
    }
    assert!(valid.contains(&(0, 1)) && valid.contains(&(2, 0)), "{valid:?}");
}
