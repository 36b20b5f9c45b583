//! Every error variant, triggered on purpose: bad input gets a typed error naming what and where,
//! never a panic, a hang or a silent NaN.

use kinloop::{Error, EventKind, NewtonConfig, Quantity};
use kinloop_fixtures::FourBar;
use std::f64::consts::PI;

kinloop::mechanism! {
    /// Slider-crank driven by its slider: `x` is the input, the crank and rod angles unknown.
    /// Solved by Newton (its dyad has a closed form): the iteration errors below are Newton's.
    #[kinloop(newton)]
    pub struct SliderDriven {
        params r, l;
        input x;
        unknowns phi = 0.5, psi = 2.5;
        loop oab: r @ phi - l @ psi == (x, 0);
        output reach = sqrt(x - 3);
    }
}

kinloop::mechanism! {
    /// A slider whose position jumps (floor) at phi = 1: no step, however small, follows it.
    /// (A corner, as `abs` makes, is swept through: `tests/sweeps/sweep_kinks.rs`.)
    pub struct Stepped {
        params k;
        input phi;
        unknowns s = 0;
        eq jump: s == k * floor(phi);
    }
}

const M: SliderDriven = SliderDriven { r: 1.0, l: 3.0 };

#[test]
fn non_finite_parameter_input_guess_and_motion() {
    let bad = SliderDriven { r: f64::NAN, ..M };
    match bad.solve(3.0) {
        Err(Error::NonFinite { what: Quantity::Parameter, name, .. }) if name == "r" => {}
        other => panic!("{other:?}"),
    }
    assert!(bad.check().is_err());
    assert!(M.check().is_ok());
    match M.solve(f64::INFINITY) {
        Err(Error::NonFinite { what: Quantity::Input, name, .. }) if name == "x" => {}
        other => panic!("{other:?}"),
    }
    let g = SliderDrivenUnknowns { phi: f64::NAN, psi: 2.0 };
    match M.kinematics(3.0, &g) {
        Err(Error::NonFinite { what: Quantity::Guess, name, .. }) if name == "phi" => {}
        other => panic!("{other:?}"),
    }
    let s = M.solve(3.5).unwrap();
    assert!(matches!(s.motion(f64::NAN, 0.0), Err(Error::NonFinite { what: Quantity::Motion, .. })));
    assert!(matches!(M.sweep(0.0, f64::NAN, 3, &M.guess(0.0)), Err(Error::NonFinite { what: Quantity::Range, .. })));
}

/// A position given to `kinematics_at` (the caller's, not a solve's) with an unknown not
/// finite names that unknown: the step alone would call it a singular Jacobian or an equation
/// not finite. A parameter not finite is still named first.
#[test]
fn a_given_position_not_finite_is_named() {
    let four_bar = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let sens = kinloop_fixtures::FourBarSens { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let q = four_bar.solve(0.5).unwrap().q;
    let expect = |r: Result<(), Error>, unknown: &str| match r {
        Err(Error::NonFinite { what: Quantity::Position, ref name, .. }) if name == unknown => {
            let message = r.unwrap_err().to_string();
            assert!(message.starts_with(&format!("given position of `{unknown}` is not finite")), "{message}");
        }
        other => panic!("{unknown}: {other:?}"),
    };
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        // Closed forms (the four-bar's dyad) and Newton (the slider-driven crank), each unknown.
        let g = kinloop_fixtures::FourBarUnknowns { beta: bad, ..q };
        expect(four_bar.kinematics_at(0.5, &g).map(drop), "beta");
        expect(
            sens.sensitivities_at(0.5, &kinloop_fixtures::FourBarSensUnknowns { beta: bad, gamma: q.gamma }).map(drop),
            "beta",
        );
        let g = kinloop_fixtures::FourBarUnknowns { gamma: bad, ..q };
        expect(four_bar.kinematics_at(0.5, &g).map(drop), "gamma");
        let p = M.solve(3.5).unwrap().q;
        expect(M.kinematics_at(3.5, &SliderDrivenUnknowns { psi: bad, ..p }).map(drop), "psi");
        expect(M.kinematics_at(3.5, &SliderDrivenUnknowns { phi: bad, ..p }).map(drop), "phi");
        let nan_param = SliderDriven { l: f64::NAN, ..M };
        match nan_param.kinematics_at(3.5, &SliderDrivenUnknowns { phi: bad, ..p }) {
            Err(Error::NonFinite { what: Quantity::Parameter, name, .. }) if name == "l" => {}
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn impossible_assembly_is_no_assembly() {
    // The slider beyond the reach of crank and rod: the loop cannot close.
    let e = M.solve(4.5).unwrap_err();
    assert!(matches!(e, Error::NoAssembly { .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("cannot be assembled") && msg.contains("x = 4.5") && msg.contains("block 0"), "{msg}");
}

#[test]
fn iteration_cap_is_no_convergence() {
    let cfg = NewtonConfig::default().with_max_iterations(1);
    let e = M.kinematics_with(2.5, &SliderDrivenUnknowns { phi: 2.0, psi: 1.0 }, &cfg).unwrap_err();
    assert!(matches!(e, Error::NoConvergence { iterations: 1, .. }), "{e}");
    // One iteration is one, not "1 iterations".
    assert!(e.to_string().contains("did not converge in 1 iteration in `SliderDriven`"), "{e}");
}

#[test]
fn dead_centre_is_singular() {
    // Fully stretched (x = r + l): the positions exist but the velocity analogs do not.
    let e = M.kinematics(4.0, &SliderDrivenUnknowns { phi: 0.0, psi: PI }).unwrap_err();
    match &e {
        Error::Singular { pivot_ratio, .. } => assert!(*pivot_ratio < 1e-10),
        other => panic!("{other:?}"),
    }
    // Positions alone are fine there.
    assert!(M.position(4.0, &SliderDrivenUnknowns { phi: 0.0, psi: PI }).is_ok());
}

#[test]
fn expression_outside_its_domain_is_domain_error() {
    // `reach = sqrt(x - 3)` is NaN for x < 3 although the loop closes (2 <= x <= 4).
    let e = M.solve(2.5).unwrap_err();
    match &e {
        Error::Domain { what: kinloop::Computed::Output, name, .. } if name == "reach" => {}
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().contains("reach"));
    // At x = 3 the value exists but its derivative (1 / (2 sqrt(0))) does not.
    match M.solve(3.0) {
        Err(Error::Domain { what: kinloop::Computed::OutputVelocityAnalog, name, .. }) if name == "reach" => {}
        other => panic!("{other:?}"),
    }
}

#[test]
fn limit_position_stops_a_sweep() {
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let r: Result<Vec<_>, _> = m.sweep(0.0, PI, 19, &g).unwrap().collect();
    assert!(matches!(r, Err(Error::SweepStopped { kind: EventKind::LimitPosition, .. })));
}

#[test]
fn a_jump_in_the_solution_is_a_branch_error() {
    let m = Stepped { k: 2.0 };
    let r: Result<Vec<_>, _> = m.sweep(0.0, 2.0, 9, &m.guess(0.0)).unwrap().collect();
    match r {
        Err(Error::Branch { at, .. }) => assert!((at.inputs[0].1 - 1.0).abs() < 1e-6, "{at}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn zero_samples_is_invalid_argument() {
    assert!(matches!(M.sweep(2.0, 3.0, 0, &M.guess(2.0)), Err(Error::InvalidArgument(_))));
}

/// A configuration out of range is named with the range it must lie in, through every way a
/// program meets it: its `validate`, a point solve, a sweep, a trace and the optimisers.
#[test]
fn a_configuration_out_of_range_states_the_range() {
    use kinloop::analysis::optimize::{LevenbergMarquardt, NelderMead};
    use kinloop::{SweepConfig, TraceConfig};
    let g = M.guess(2.0);
    let said = |e: Error| e.to_string();
    let newton = NewtonConfig::default().with_singular_tol(2.0);
    let point = M.position_with(2.0, &g, &newton).unwrap_err();
    assert!(said(point).contains("NewtonConfig::singular_tol is out of its valid range, [0, 1)"));
    let sweep = SweepConfig::default().with_max_halvings(0);
    let first = M.sweep(2.0, 3.0, 3, &g).unwrap().with_config(sweep).next().unwrap().unwrap_err();
    assert!(said(first).contains("SweepConfig::max_halvings is out of its valid range, 1..=60"));
    let sweep = SweepConfig::default().with_newton(newton);
    let e = sweep.validate().unwrap_err();
    assert!(said(e).contains("SweepConfig::newton.singular_tol is out of its valid range, [0, 1)"));
    let e = M.trace_curve(2.0, 3.0, &g, &TraceConfig::default().with_ds(2.0)).unwrap_err();
    assert!(said(e).contains("TraceConfig::ds is out of its valid range, [1e-9, 1]"));
    let e = TraceConfig::default().with_newton(NewtonConfig::default().with_max_iterations(20_000)).validate();
    assert!(
        said(e.unwrap_err()).contains("TraceConfig::newton.max_iterations is out of its valid range, at most 10000")
    );
    let e = LevenbergMarquardt::default().with_lambda(0.0).validate().unwrap_err();
    assert!(said(e).contains("LevenbergMarquardt::lambda is out of its valid range, positive and finite"));
    let e = NelderMead::default().with_max_evaluations(0).validate().unwrap_err();
    assert!(said(e).contains("NelderMead::max_evaluations is out of its valid range, at least 1"));
}

/// Levenberg-Marquardt's steps are the same relative to the problem's size in any unit, its stop
/// is not: `tol` is a residual norm in the residuals' unit. The documentation said any magnitude
/// gave the same relative answer; the default `tol` takes the start of the same problem in
/// micrometres (residuals in square micrometres, 1e-12 of the metres' ones) as converged. A
/// `tol` scaled with the residuals, or `0`, gives the same relative answer in every unit.
#[test]
fn levenberg_marquardt_stops_at_a_tolerance_in_the_residuals_unit() {
    use kinloop::analysis::optimize::LevenbergMarquardt;
    // x^2 + y^2 = 4 s^2, x y = s^2: the root (1.9319 s, 0.5176 s), from (2 s, 0.1 s).
    let solve = |s: f64, lm: LevenbergMarquardt| {
        let f = move |v: &[f64; 2]| {
            let [x, y] = *v;
            Ok(([x * x + y * y - 4.0 * s * s, x * y - s * s], [[2.0 * x, 2.0 * y], [y, x]]))
        };
        let m = lm.minimize(f, [2.0 * s, 0.1 * s]).unwrap();
        (m.converged(), m.x.map(|v| v / s), m.evaluations)
    };
    let root = (2.0 + 3f64.sqrt()).sqrt();
    let exact = [root, 1.0 / root];
    let (ok, metres, _) = solve(1.0, LevenbergMarquardt::default());
    assert!(ok && (0..2).all(|i| (metres[i] - exact[i]).abs() < 1e-9), "{metres:?}");
    for s in [1e-6, 1e-150, 1e6, 1e150] {
        // The default `tol` is absolute: in micrometres the start is already below it.
        let (ok, x, evaluations) = solve(s, LevenbergMarquardt::default());
        if s < 1.0 {
            assert!(ok && evaluations == 1 && x == [2.0, 0.1], "{s:e}: {x:?} in {evaluations}");
        }
        // Scaled as the residuals are, the same relative answer; to the rounding with `tol` 0.
        for (tol, within) in [(1e-10 * s * s, 1e-9), (0.0, 1e-15)] {
            let (ok, x, _) = solve(s, LevenbergMarquardt::default().with_tol(tol));
            let within = (0..2).all(|i| (x[i] - exact[i]).abs() < within * exact[i]);
            assert!(within && (ok || tol == 0.0), "{s:e}, tol {tol:e}: {x:?}");
        }
    }
}

kinloop::mechanism! {
    /// A slider-crank and a lift on its slider, compiled: the rod angle's closed form reads its
    /// guess (the branch), and the slider's and the lift's linear solves read none.
    pub struct Lifted {
        params r, l, h;
        input phi;
        unknowns beta = 0.3, s = 3, y = 1;
        loop rod: r @ phi + l @ beta == (s, 0);
        eq lift: y == h * s;
    }
}

kinloop::mechanism! {
    /// `Lifted` solved by dense Newton, which reads every guess.
    #[kinloop(newton)]
    pub struct LiftedNewton {
        params r, l, h;
        input phi;
        unknowns beta = 0.3, s = 3, y = 1;
        loop rod: r @ phi + l @ beta == (s, 0);
        eq lift: y == h * s;
    }
}

/// A guess not finite is refused, naming the unknown, whether or not the solve reads it, by the
/// point solves and by a sweep's and a trace's start, as a Newton block that reads it refuses
/// it. A NaN guess of the slider or the lift (solved linearly, from no guess) was accepted, by
/// the compiled mechanism and by its Newton twin, whose blocks are linear there too.
#[test]
fn a_guess_not_finite_is_refused_whether_or_not_the_solve_reads_it() {
    let (m, twin) = (Lifted { r: 1.0, l: 3.0, h: 0.5 }, LiftedNewton { r: 1.0, l: 3.0, h: 0.5 });
    let good = m.solve(0.4).unwrap().q;
    let guesses = |bad: f64| {
        let mut all = Vec::new();
        for u in ["beta", "s", "y"] {
            let mut g = good;
            *match u {
                "beta" => &mut g.beta,
                "s" => &mut g.s,
                _ => &mut g.y,
            } = bad;
            all.push((u, g));
        }
        all
    };
    let refused = |r: Result<(), Error>, u: &str, how: &str| match r {
        Err(Error::NonFinite { what: Quantity::Guess, name, .. }) if name == u => {}
        other => panic!("{how}, guess of `{u}`: {other:?}"),
    };
    for bad in [f64::NAN, f64::INFINITY] {
        for (u, g) in guesses(bad) {
            let twin_g = LiftedNewtonUnknowns { beta: g.beta, s: g.s, y: g.y };
            refused(m.kinematics(0.4, &g).map(drop), u, "kinematics");
            refused(twin.kinematics(0.4, &twin_g).map(drop), u, "the twin's kinematics");
            refused(m.position(0.4, &g).map(drop), u, "position");
            refused(m.sweep(0.4, 0.6, 3, &g).unwrap().next().unwrap().map(drop), u, "a sweep's first state");
            refused(m.trace_curve(0.4, 0.6, &g, &kinloop::TraceConfig::default()).map(drop), u, "a trace");
        }
    }
    // A finite guess far from the solution still solves (the linear solves read none of it).
    let far = LiftedUnknowns { s: 1e9, y: -1e9, ..good };
    assert_eq!(m.kinematics(0.4, &far).unwrap().q.y, good.y);
}
