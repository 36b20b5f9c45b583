//! Regression tests of the point solver: every `Ok` is accurate, every error names what
//! happened. Each test is named after the defect it guards. References are independent of the
//! solver: circle-intersection closed forms computed here, and loop magnitudes (sums of link
//! lengths) for residuals.

use kinloop::{Error, Mechanism, NewtonConfig, Sensitivities};
use kinloop_fixtures::{FourBar, FourBarSens, FourBarUnknowns, SlottedLever};
use std::f64::consts::PI;

use crate::support::{angle_apart, four_bar_angles, four_bar_limit, tol};

kinloop::mechanism! {
    /// The same four-bar solved by Newton (`FourBar`'s dyad is solved in closed form): for the
    /// tests of Newton's own acceptance.
    #[kinloop(newton)]
    pub struct FourBarNewton {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

/// Largest residual relative to the loop's magnitude (the sum of its link lengths): the
/// rounding floor of the loop equation is a few ulps of it.
fn scaled_residual(m: &FourBar, phi: f64, q: &[f64; 2]) -> f64 {
    let r = m.residual_flat(&[phi], q);
    r[0].abs().max(r[1].abs()) / (m.a + m.b + m.c + m.d)
}

const CRANK_ROCKER: FourBar = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };

#[test]
fn ok_with_a_large_residual_is_impossible() {
    // A guess 1e15 radians out: the Newton step test alone used to end the iteration with a
    // residual of several length units and return Ok. There doubles are 1/8 rad apart: no angle
    // meets the tolerance on that turn, and the error says so.
    match CRANK_ROCKER.kinematics_flat(&[0.3], &[1e15, 1.5], &NewtonConfig::default()) {
        Ok(k) => assert!(scaled_residual(&CRANK_ROCKER, 0.3, &k.q) <= tol::SOLVE, "{k:?}"),
        Err(e) => assert!(matches!(e, Error::TooManyTurns { ref name, .. } if name == "beta"), "{e}"),
    }
}

/// The slotted lever (size 3: crank 1, rocker pivot 2 below it) from guesses whose angle is
/// too many turns out (beyond `largest_precise_angle`, 4.5e6 rad by default) and whose length
/// is ordinary or far beyond the mechanism's size. Whatever the length's guess, no solve can
/// give the angle on its turn to the tolerance: the error names it. A length guessed at `1e150`
/// or more made the magnitudes at the guess those of a mechanism beyond the closed forms'
/// sizes, and the whole-system Newton solve that answers there returned the far angle with a
/// length of `1e168`, `1e276` or `0` (the loop open by its whole size) and no error; a sum of
/// the two guesses that overflows (`1e308` each) was reported as an equation not finite.
#[test]
fn an_angle_too_many_turns_out_is_named_whatever_the_lengths_guess() {
    let m = SlottedLever::default();
    let cfg = NewtonConfig::default();
    assert!(cfg.largest_precise_angle() < 1e7);
    let guesses = [(3.0, 1e7), (1e150, 1e7), (1e200, 1e7), (1e308, 1e307), (1e308, 1e308), (1e308, -1e308)];
    for (s, theta) in guesses.into_iter().chain([(f64::MAX, 3e292), (-f64::MAX, -3e292)]) {
        let guess = [s, theta];
        let results = [
            m.position_flat(&[0.3], &guess, &cfg).map(|(q, _)| q),
            m.kinematics_flat(&[0.3], &guess, &cfg).map(|k| k.q),
        ];
        for result in results {
            match result {
                Err(Error::TooManyTurns { ref name, value, .. }) => {
                    assert!(name == "theta" && value.abs() > cfg.largest_precise_angle(), "{s:e}, {theta:e}: {value:e}")
                }
                other => panic!("guess {s:e}, {theta:e}: {other:?}"),
            }
        }
    }
}

/// The slotted lever with its crank as long as its pivot's offset (`r = d = 1`) at `phi = -pi/2`:
/// the crank pin sits on the rocker's pivot (the lever `s`, `|r (cos phi, sin phi) + (0, d)|`,
/// is `6.1e-17`), a singular position at which no rocker angle is determined. From a length's
/// guess of the mechanism's size the solve says so; from one of `1e150` the magnitudes at the
/// guess were beyond the closed forms' sizes, and the whole-system Newton solve that answers
/// there, its residual judged in those magnitudes, returned `s = 1.2e118` (and `0` from `1e200`)
/// with no error, the loop open by all of it. Every `Ok` must close the loop, in the lever's own
/// lengths computed here; every guess gives the error the mechanism's size gives.
#[test]
fn a_length_guessed_far_out_never_opens_the_loop() {
    let m = SlottedLever { r: 1.0, d: 1.0, l: 4.0 };
    let cfg = NewtonConfig::default();
    let phi = -PI / 2.0;
    let (px, py) = (m.r * phi.cos(), m.r * phi.sin() + m.d);
    let lever = px.hypot(py);
    assert!(lever < 1e-16, "{lever}");
    for s in [1.0, 1e150, 1e200, 1e300] {
        let guess = [s, 0.3];
        let results = [
            m.position_flat(&[phi], &guess, &cfg).map(|(q, _)| q),
            m.kinematics_flat(&[phi], &guess, &cfg).map(|k| k.q),
        ];
        for result in results {
            match result {
                Ok([s_q, theta]) => {
                    let open = (px - s_q * theta.cos()).hypot(py - s_q * theta.sin());
                    assert!(
                        open <= tol::SOLVE * (m.r + m.d),
                        "guess {s:e}: s {s_q:e}, theta {theta}, open by {open:e}"
                    );
                }
                Err(e) => assert!(matches!(e, Error::Singular { .. }), "guess {s:e}: {e}"),
            }
        }
    }
}

#[test]
fn a_guess_within_tolerance_is_still_corrected() {
    // A guess off by 1e-13 rad has a residual below 1e-12 (the old absolute stop): it used to
    // come back unchanged. Corrected once, it is exact to rounding.
    let m = CRANK_ROCKER;
    for phi in [0.0, 0.7, 2.0, 4.0] {
        let exact = four_bar_angles(m.a, m.b, m.c, m.d, phi, 1.0).unwrap();
        let guess = [exact[0] + 1e-13, exact[1] - 1e-13];
        let k = m.kinematics_flat(&[phi], &guess, &NewtonConfig::default()).unwrap();
        for u in 0..2 {
            // Rounding of the closed form and of the solver: a few ulps of the angles (~3).
            assert!(angle_apart(k.q[u], exact[u]) <= 4e-15, "phi {phi}: {:?} vs {exact:?}", k.q);
        }
    }
}

#[test]
fn a_change_point_reached_slowly_is_singular_not_inaccurate() {
    // (1, 2, 1, 2) at phi = 0 lies folded on the ground line: the Jacobian is singular at the
    // root, Newton converges linearly and stopped 1.5e-6 rad short, returning Ok.
    let m = FourBar { a: 1.0, b: 2.0, c: 1.0, d: 2.0 };
    match m.kinematics_flat(&[0.0], &[0.5, 1.5], &NewtonConfig::default()) {
        Err(Error::Singular { .. }) => {}
        Ok(k) => panic!("a singular position returned as Ok: {:?}", k.q),
        Err(e) => panic!("wrong error kind: {e}"),
    }
}

#[test]
fn an_exact_solution_near_a_singular_position_is_not_no_assembly() {
    // Coupler and rocker a million times the crank: nearly parallel, pivot ratio ~1e-6.
    let m = FourBar { a: 1.0, b: 1e6, c: 1e6, d: 1.0 };
    let phi = 1.0;
    let exact = four_bar_angles(m.a, m.b, m.c, m.d, phi, 1.0).unwrap();
    match m.kinematics_flat(&[phi], &exact, &NewtonConfig::default()) {
        Ok(k) => {
            // Condition ~1e6: the angles are determined to ~1e6 ulps of the residual floor.
            for u in 0..2 {
                assert!(angle_apart(k.q[u], exact[u]) <= 1e-9, "{:?} vs {exact:?}", k.q);
            }
        }
        Err(e) => assert!(matches!(e, Error::Singular { .. }), "{e}"),
    }
}

#[test]
fn near_a_limit_from_the_limit_configuration_is_not_no_assembly() {
    // Non-Grashof: coupler and rocker stretch (|BD| = b + c) at phi_lim; the input 1e-9 rad
    // before it, from the stretched configuration as guess, used to report NoAssembly.
    let m = FourBar { a: 3.0, b: 1.0, c: 1.5, d: 3.0 };
    let phi_lim = four_bar_limit(m.a, m.d, m.b + m.c);
    let (bx, by) = (m.a * phi_lim.cos(), m.a * phi_lim.sin());
    let dir = (-by).atan2(m.d - bx);
    let phi = phi_lim - 1e-9;
    match m.kinematics_flat(&[phi], &[dir, dir + PI], &NewtonConfig::default()) {
        Ok(k) => {
            assert!(scaled_residual(&m, phi, &k.q) <= tol::SOLVE, "{k:?}");
            let want = [1.0, -1.0].map(|s| four_bar_angles(m.a, m.b, m.c, m.d, phi, s).unwrap());
            // Within sqrt(1e-9) of the fold the solution is known to ~1e-16 / 1e-4.5.
            assert!(want.iter().any(|w| (0..2).all(|u| angle_apart(k.q[u], w[u]) <= 1e-9)), "{:?} vs {want:?}", k.q);
        }
        Err(e) => assert!(matches!(e, Error::Singular { .. } | Error::NoConvergence { .. }), "{e}"),
    }
}

#[test]
fn unreachable_input_is_still_no_assembly() {
    // The same four-bar 0.1 rad beyond its limit cannot close.
    let m = FourBar { a: 3.0, b: 1.0, c: 1.5, d: 3.0 };
    let phi_lim = four_bar_limit(m.a, m.d, m.b + m.c);
    let e = m.kinematics_flat(&[phi_lim + 0.1], &[-0.5, 2.0], &NewtonConfig::default()).unwrap_err();
    assert!(matches!(e, Error::NoAssembly { .. }), "{e}");
}

#[test]
fn far_guesses_at_reachable_inputs_never_claim_no_assembly() {
    // A deterministic grid of far guesses (the issue measured 11 NoAssembly in 9,000).
    let m = CRANK_ROCKER;
    let mut counts = [0usize; 3];
    for i in 0..30 {
        let phi = i as f64 * 2.0 * PI / 30.0;
        for j in 0..30 {
            let g = [-20.0 + 40.0 * ((j * 7) % 30) as f64 / 29.0, -20.0 + 40.0 * j as f64 / 29.0];
            match m.kinematics_flat(&[phi], &g, &NewtonConfig::default()) {
                Ok(k) => {
                    assert!(scaled_residual(&m, phi, &k.q) <= tol::SOLVE, "{k:?}");
                    let want = [1.0, -1.0].map(|s| four_bar_angles(m.a, m.b, m.c, m.d, phi, s).unwrap());
                    // Angles come back modulo turns: their rounding grows with their magnitude.
                    let tol = |v: f64| 8.0 * f64::EPSILON * v.abs().max(PI);
                    assert!(want.iter().any(|w| (0..2).all(|u| angle_apart(k.q[u], w[u]) <= tol(k.q[u]))), "{:?}", k.q);
                    counts[0] += 1;
                }
                Err(Error::NoAssembly { .. }) => panic!("NoAssembly at a reachable input {phi} from {g:?}"),
                Err(_) => counts[1] += 1,
            }
        }
    }
    assert!(counts[0] >= 850, "{counts:?}");
}

#[test]
fn unit_free_acceptance() {
    // The same crank-rocker in metres and in picometres: a guess 0.1 rad off is never
    // accepted as it is, and the angles agree to rounding.
    for k in [1.0, 1e-12, 1e6] {
        let m = FourBar { a: CRANK_ROCKER.a * k, b: CRANK_ROCKER.b * k, c: CRANK_ROCKER.c * k, d: CRANK_ROCKER.d * k };
        let exact = four_bar_angles(CRANK_ROCKER.a, CRANK_ROCKER.b, CRANK_ROCKER.c, CRANK_ROCKER.d, 0.7, 1.0).unwrap();
        let guess = [exact[0] + 0.1, exact[1] + 0.1];
        let s = m.kinematics_flat(&[0.7], &guess, &NewtonConfig::default()).unwrap();
        let n = FourBarNewton { a: m.a, b: m.b, c: m.c, d: m.d };
        let sn = n.kinematics_flat(&[0.7], &guess, &NewtonConfig::default()).unwrap();
        assert!(sn.report.iterations > 0, "scale {k}: guess accepted as it is");
        for u in 0..2 {
            assert!(angle_apart(s.q[u], exact[u]) <= 4e-15, "scale {k}: {:?} vs {exact:?}", s.q);
            assert!(angle_apart(sn.q[u], exact[u]) <= 4e-15, "scale {k}, Newton: {:?} vs {exact:?}", sn.q);
        }
    }
}

#[test]
fn invalid_newton_configurations_are_named() {
    let s = CRANK_ROCKER.guess(0.3);
    for (cfg, field) in [
        (NewtonConfig::default().with_residual_tol(f64::INFINITY), "residual_tol"),
        (NewtonConfig::default().with_residual_tol(f64::NAN), "residual_tol"),
        (NewtonConfig::default().with_min_damping(0.0), "min_damping"),
    ] {
        match CRANK_ROCKER.kinematics_with(0.3, &s, &cfg) {
            Err(Error::InvalidArgument(msg)) => assert!(msg.contains(field), "{msg}"),
            other => panic!("{other:?}"),
        }
    }
}

/// The analogs at a position the caller solved read the configuration's `singular_tol`: one out
/// of range is named there as it is by a solve, not taken. A NaN tolerance made a regular
/// position (pivot ratio 0.5) "singular, reached only linearly", a negative one was accepted.
#[test]
fn invalid_newton_configurations_are_named_at_a_given_position() {
    let (x, sens) = ([0.3], FourBarSens { a: CRANK_ROCKER.a, b: CRANK_ROCKER.b, c: CRANK_ROCKER.c, d: CRANK_ROCKER.d });
    let newton = FourBarNewton { a: CRANK_ROCKER.a, b: CRANK_ROCKER.b, c: CRANK_ROCKER.c, d: CRANK_ROCKER.d };
    let q = CRANK_ROCKER.kinematics_flat(&x, &CRANK_ROCKER.guess(0.3).into(), &NewtonConfig::default()).unwrap().q;
    for (cfg, field) in [
        (NewtonConfig::default().with_singular_tol(f64::NAN), "singular_tol"),
        (NewtonConfig::default().with_singular_tol(-1.0), "singular_tol"),
        (NewtonConfig::default().with_residual_tol(f64::NAN), "residual_tol"),
        (NewtonConfig::default().with_max_iterations(u32::MAX), "max_iterations"),
    ] {
        for (what, r) in [
            ("closed form", CRANK_ROCKER.kinematics_at_flat(&x, &q, &cfg).map(drop)),
            ("Newton", newton.kinematics_at_flat(&x, &q, &cfg).map(drop)),
            ("sensitivities", sens.sensitivities_at_flat(&x, &q, &cfg).map(drop)),
        ] {
            match r {
                Err(Error::InvalidArgument(msg)) => {
                    assert!(msg.contains(&format!("NewtonConfig::{field} is out of its valid range")), "{what}: {msg}")
                }
                other => panic!("{what}, {field}: {other:?}"),
            }
        }
    }
    // The same position with a valid configuration: regular, far from the tolerance.
    let k = CRANK_ROCKER.kinematics_at_flat(&x, &q, &NewtonConfig::default()).unwrap();
    assert!(k.health.min_pivot > 0.1, "{:?}", k.health);
}

#[test]
fn limit_positions_are_located_alike_at_every_scale() {
    // Non-Grashof four-bar: the crank stops where coupler and rocker stretch (law of cosines).
    let base = FourBar { a: 3.0, b: 1.0, c: 1.5, d: 3.0 };
    let phi_lim = ((base.a * base.a + base.d * base.d - (base.b + base.c).powi(2)) / (2.0 * base.a * base.d)).acos();
    for k in [1e-3, 1.0, 1e6] {
        let m = FourBar { a: base.a * k, b: base.b * k, c: base.c * k, d: base.d * k };
        let exact = four_bar_angles(base.a, base.b, base.c, base.d, 0.2, 1.0).unwrap();
        let mut s = m.sweep(0.2, 1.5, 14, &FourBarUnknowns { beta: exact[0], gamma: exact[1] }).unwrap();
        let stop = s.by_ref().find_map(|r| r.err()).expect("the limit stops the sweep");
        assert!(
            matches!(stop, Error::SweepStopped { kind: kinloop::EventKind::LimitPosition, .. }),
            "scale {k}: {stop}"
        );
        let at = s.events()[0].x[0];
        // The fold is located to about sqrt(eps) in the input (the curve is flat there in phi).
        assert_close!(at, phi_lim, tol::LOCATED, "scale {k}: limit at {at}, law of cosines {phi_lim}");
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]
    /// Whatever the guess (near or tens of radians away) every `Ok` satisfies the loop to a few
    /// ulps of its magnitude, and is one of the two closed-form assemblies.
    #[test]
    fn every_ok_has_a_small_scaled_residual(
        phi in 0.0..6.3f64,
        g0 in -60.0..60.0f64,
        g1 in -60.0..60.0f64,
        scale in proptest::sample::select(vec![1e-6, 1.0, 1e4]),
    ) {
        let m = FourBar { a: CRANK_ROCKER.a * scale, b: CRANK_ROCKER.b * scale, c: CRANK_ROCKER.c * scale, d: CRANK_ROCKER.d * scale };
        if let Ok(k) = m.kinematics_flat(&[phi], &[g0, g1], &NewtonConfig::default()) {
            proptest::prop_assert!(scaled_residual(&m, phi, &k.q) <= tol::SOLVE, "{:?}", k.q);
            let want = [1.0, -1.0].map(|s| four_bar_angles(CRANK_ROCKER.a, CRANK_ROCKER.b, CRANK_ROCKER.c, CRANK_ROCKER.d, phi, s).unwrap());
            let tol = |v: f64| 8.0 * f64::EPSILON * v.abs().max(PI);
            proptest::prop_assert!(want.iter().any(|w| (0..2).all(|u| angle_apart(k.q[u], w[u]) <= tol(k.q[u]))), "{:?} vs {want:?}", k.q);
        }
    }
}

#[test]
fn a_limit_position_assembles_in_every_unit() {
    // At the non-Grashof four-bar's limit input (and an ulp or two beside it) the dyad's circles
    // touch: their discriminant is zero up to rounding, which in some units falls below zero.
    // That rounding used to decide between a position and "cannot be assembled" (28 of these 52
    // solves failed). Now every one is the limit position: the loop closes to rounding, with
    // coupler and rocker stretched into one line from B through C to D (`beta = gamma + pi` up
    // to the angles' sensitivity there, about the square root of the rounding).
    let base = FourBar { a: 3.0, b: 1.0, c: 1.5, d: 3.0 };
    let phi_lim = ((base.a * base.a + base.d * base.d - (base.b + base.c).powi(2)) / (2.0 * base.a * base.d)).acos();
    for k in [1e-6, 1e-3, 0.1, 0.3, 0.7, 1.0, 1.1, 3.0, 1e3, 1e6, 25.4, 0.0254, 1.0 / 3.0] {
        let m = FourBar { a: base.a * k, b: base.b * k, c: base.c * k, d: base.d * k };
        for dphi in [-2e-16, 0.0, 2e-16, 4e-16] {
            let phi = phi_lim + dphi;
            let (q, _) = m
                .position_flat(&[phi], &[0.5, 1.5], &NewtonConfig::default())
                .unwrap_or_else(|e| panic!("scale {k}, {dphi:e} past the limit: {e}"));
            assert!(scaled_residual(&m, phi, &q) <= 1e-15, "scale {k}: {q:?}");
            assert!(angle_apart(q[0], q[1] + PI) <= 1e-7, "scale {k}, {dphi:e}: {q:?}");
        }
    }
}

kinloop::mechanism! {
    /// A four-bar whose ground link `d` is tilted by `g0`.
    pub struct TiltedFourBar {
        params a, b, c, d, g0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == d @ g0 + c @ gamma;
    }
}

kinloop::mechanism! {
    /// The same, solved by Newton.
    #[kinloop(newton)]
    pub struct TiltedFourBarNewton {
        params a, b, c, d, g0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == d @ g0 + c @ gamma;
    }
}

#[test]
fn a_dyad_on_coincident_centres_is_singular_in_a_position_solve_too() {
    // `a = d`, `b = c`: at `phi = g0` the crank pin B sits on the rocker pivot D and the folded
    // coupler and rocker turn freely about it. Near there their orientation is known only to the
    // rounding of the loop's lengths over `|BD| = 2 a sin((phi - g0) / 2)`: with the ground
    // tilted, both components of BD cancel, and closer than the rounding the orientation is
    // anything. The kinematics report the pivot ratio `|BD| / b` and refuse below the tolerance;
    // a position-only solve must not answer there either, on either path. The reference: C on
    // the perpendicular bisector of BD, at `h = sqrt(b^2 - (|BD| / 2)^2)` from its midpoint, in
    // half angles (no cancellation).
    let eps = f64::EPSILON;
    let g0 = 0.3;
    for scale in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
        let (a, b) = (scale, 2.0 * scale);
        let m = TiltedFourBar { a, b, c: b, d: a, g0 };
        let mn = TiltedFourBarNewton { a, b, c: b, d: a, g0 };
        for k in 1..=16 {
            let phi = g0 + 10f64.powi(-k);
            // The offset as represented (exact: the two are within a factor two).
            let t = phi - g0;
            let s = (0.5 * t).sin();
            let (sm, cm) = (g0 + 0.5 * t).sin_cos();
            let bd = 2.0 * a * s;
            let h = (b * b - 0.25 * bd * bd).sqrt();
            // C - B = BD / 2 + side h n, BD along (sm, -cm), n = (cm, sm).
            let betas = [1.0, -1.0].map(|side| (-a * s * cm + side * h * sm).atan2(a * s * sm + side * h * cm));
            let guess = [1.0, 1.0 + PI - 0.1];
            let closed = m.position_flat(&[phi], &guess, &NewtonConfig::default()).map(|(q, _)| q[0]);
            let newton = mn.position_flat(&[phi], &guess, &NewtonConfig::default()).map(|(q, _)| q[0]);
            for (path, got) in [("closed form", closed), ("Newton", newton)] {
                let at = format!("{path}, scale {scale:e}, phi - g0 = 1e-{k}");
                match got {
                    Ok(beta) => {
                        let err = betas.iter().map(|&b| angle_apart(beta, b)).fold(f64::INFINITY, f64::min);
                        assert!(err <= 4.0 * eps * (a + b) / bd, "{at}: beta {beta} vs {betas:?}");
                        assert!(k <= 9, "{at}: Ok, beta {beta}");
                    }
                    Err(e) => assert!(matches!(e, Error::Singular { .. }) && k >= 8, "{at}: {e}"),
                }
            }
        }
    }
}
