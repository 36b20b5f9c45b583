//! Hostile magnitudes in the dynamics: results beyond the range of f64 are typed errors (or
//! computed scaled where representable), never infinity or NaN inside an `Ok`.

use super::*;
use crate::kin::{Health, Kin};
use crate::{NewtonStop, SolveReport};
use ode::norm;

/// A crank of radius `r` turning with input 0, its centre of mass at the crank pin (the
/// columns of a point `r @ phi` at phi = 0), as a hand-made state.
fn crank(r: f64) -> Kin<0, 1, 2> {
    Kin {
        x: [0.0],
        q: [],
        dq: [],
        d2q: [],
        out: [r, 0.0],
        dout: [[0.0], [r]],
        d2out: [[[-r]], [[0.0]]],
        report: SolveReport { iterations: 0, evaluations: 0, residual: 0.0, termination: NewtonStop::Direct },
        health: Health::default(),
    }
}

fn body(mass: f64, inertia: f64) -> Body {
    Body {
        name: "crank".into(),
        mass,
        com: [Coord::Output(0), Coord::Output(1)],
        inertia,
        rotation: Rotation::Input(0),
    }
}

#[test]
fn a_total_mass_beyond_f64_is_refused_when_the_body_is_added() {
    let one = MassModel::<0, 1, 2>::new().with_body(body(1e308, 0.0)).unwrap();
    assert_eq!(one.total_mass(), 1e308);
    let err = one.with_body(body(1e308, 0.0)).expect_err("two bodies of 1e308 overflow");
    assert!(matches!(err, DynamicsError::Overflow { what: "total mass", .. }), "{err}");
    assert!(err.to_string().contains("total mass is beyond the range of f64"), "{err}");
    assert!(!err.to_string().contains("at input"), "{err}");
}

#[test]
fn dynamics_results_beyond_f64_are_overflow_errors() {
    // m r^2 overflows: the mass matrix is not representable.
    let model = MassModel::<0, 1, 2>::new().with_body(body(1e308, 0.0)).unwrap();
    let err = model.dynamics(&crank(10.0), &[1.0]).unwrap_err();
    assert!(matches!(&err, DynamicsError::Overflow { x, .. } if x == &[0.0]), "{err}");
    // Gravity on a huge mass: the generalised force overflows.
    let model = MassModel::<0, 1, 2>::new().with_body(body(1e308, 0.0)).unwrap().with_gravity([0.0, -10.0]).unwrap();
    let err = model.dynamics(&crank(1.0), &[1.0]).unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { what: "generalised forces", .. }), "{err}");
    // A representable model, driven at speeds and accelerations whose torque overflows.
    // J = 200.01: J eps overflows.
    let model = MassModel::<0, 1, 2>::new().with_body(body(2.0, 0.01)).unwrap();
    let d = model.dynamics(&crank(10.0), &[1.0]).unwrap();
    let err = d.checked_drive(&[0.0], &[1.0], &[1e308]).unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { what: "driving force", .. }), "{err}");
    assert_eq!(d.checked_drive(&[0.0], &[1.0], &[2.0]).unwrap(), d.drive(&[1.0], &[2.0]));
    assert!(matches!(d.checked_drive(&[0.0], &[f64::NAN], &[0.0]), Err(DynamicsError::BadValue { .. })));
    // J = 0.01: tau / J overflows.
    let d = model.dynamics(&crank(0.001), &[1.0]).unwrap();
    let err = d.accelerations(&[0.0], &[1.0], &[1e308]).unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { what: "input accelerations", .. }), "{err}");
    assert!(matches!(d.accelerations(&[0.0], &[1.0], &[f64::INFINITY]), Err(DynamicsError::BadValue { .. })));
    // A hand-made state holding NaN is a bad value, not an overflow.
    let mut k = crank(0.1);
    k.dout[1][0] = f64::NAN;
    let err = model.dynamics(&k, &[1.0]).unwrap_err();
    assert!(matches!(err, DynamicsError::BadValue { what: "kinematic state value", .. }), "{err}");
}

fn point(phi: f64, torque: f64, load: f64, omega: f64, inertia: f64) -> CyclePoint {
    CyclePoint {
        phi,
        omega,
        eps: 0.0,
        inertia,
        inertia_slope: 0.0,
        load,
        torque,
        shaking: Shaking { force: [torque, -torque], moment: torque },
    }
}

/// A cycle of `n` points with torque `scale * (1 + cos phi)`.
fn cycle(n: usize, scale: f64) -> Cycle {
    let points = (0..n)
        .map(|j| {
            let phi = std::f64::consts::TAU * j as f64 / n as f64;
            point(phi, scale * (1.0 + phi.cos()), 0.0, 1.0, 1.0)
        })
        .collect();
    Cycle { points }
}

#[test]
fn too_many_harmonics_say_so_with_the_numbers() {
    let c = cycle(16, 1.0);
    let err = c.torque_harmonics(8).unwrap_err();
    assert_eq!(err, DynamicsError::TooManyHarmonics { harmonics: 8, samples: 16 });
    let text = err.to_string();
    assert!(text.contains("8 harmonics asked of 16 samples per period: they resolve at most 7"), "{text}");
    assert!(!text.contains("kinematics") && !text.contains("NaN"), "{text}");
    assert!(c.torque_harmonics(7).is_ok());
    // One harmonic of one sample is one of each, not "1 harmonics asked of 1 samples".
    let one = DynamicsError::TooManyHarmonics { harmonics: 1, samples: 1 }.to_string();
    assert!(one.starts_with("1 harmonic asked of 1 sample per period: they resolve at most 0"), "{one}");
    assert!(matches!(c.shaking_harmonics(100), Err(DynamicsError::TooManyHarmonics { harmonics: 100, .. })));
    for harmonics in [usize::MAX, usize::MAX / 2 + 1] {
        assert!(matches!(c.torque_harmonics(harmonics), Err(DynamicsError::TooManyHarmonics { .. })));
        assert!(matches!(c.shaking_harmonics(harmonics), Err(DynamicsError::TooManyHarmonics { .. })));
    }
    assert!(matches!(Cycle { points: Vec::new() }.torque_harmonics(0), Err(DynamicsError::TooManyHarmonics { .. })));
    // Outside a simulation a kinematic failure names no time.
    let kin = DynamicsError::kin(crate::Error::InvalidArgument("x".into())).to_string();
    assert!(kin.starts_with("kinematics failed: "), "{kin}");
}

#[test]
fn harmonics_and_means_of_huge_values_are_computed_scaled() {
    // Torques near the top of the f64 range: the plain sums overflow, the scaled ones do not.
    let c = cycle(16, 8e307);
    let f = c.torque_harmonics(3).unwrap();
    assert!((f.a0 / 8e307 - 1.0).abs() < 1e-12 && (f.a[0] / 8e307 - 1.0).abs() < 1e-12, "{f:?}");
    assert!(f.a[1].abs() < 1e-12 * 8e307 && f.b[0].abs() < 1e-12 * 8e307, "{f:?}");
    let mean = c.mean_torque().unwrap();
    assert!((mean / 8e307 - 1.0).abs() < 1e-12, "{mean}");
    assert!(c.shaking_harmonics(3).is_ok());
    // The same at ordinary magnitudes, bit for bit as before the scaling (a power of two).
    let small = cycle(16, 3.0);
    let scaled = cycle(16, 3.0 * 2f64.powi(600));
    let (a, b) = (small.torque_harmonics(3).unwrap(), scaled.torque_harmonics(3).unwrap());
    assert_eq!(a.a0 * 2f64.powi(600), b.a0);
    assert_eq!(a.b.iter().map(|v| v * 2f64.powi(600)).collect::<Vec<_>>(), b.b);
}

#[test]
fn a_flywheel_beyond_f64_is_an_error() {
    // Loads whose work over the cycle overflows.
    let n = 16;
    let points: Vec<CyclePoint> = (0..n)
        .map(|j| {
            let phi = std::f64::consts::TAU * j as f64 / n as f64;
            point(phi, 0.0, 1.5e308 * phi.sin(), 1.0, 1.0)
        })
        .collect();
    let err = Cycle { points }.flywheel(0.01).unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { .. }), "{err}");
    // A work swing so large that the flywheel for the smallest fluctuation is beyond f64.
    let n = 16;
    let points: Vec<CyclePoint> = (0..n)
        .map(|j| {
            let phi = std::f64::consts::TAU * j as f64 / n as f64;
            point(phi, 0.0, 1e303 * phi.sin(), 1.0, 1.0)
        })
        .collect();
    let err = Cycle { points: points.clone() }.flywheel(super::MIN_DELTA).unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { .. }), "{err}");
    // Hand-made points that are not finite, or none.
    let mut bad = points;
    bad[3].omega = f64::NAN;
    assert!(matches!(Cycle { points: bad }.flywheel(0.1), Err(DynamicsError::BadValue { .. })));
    assert!(matches!(Cycle { points: Vec::new() }.flywheel(0.1), Err(DynamicsError::BadValue { .. })));
}

/// A cycle of `n` points whose speed law is `omega(phi)`, loads `load(phi)`, inertia `j`.
fn law_cycle(n: usize, omega: impl Fn(f64) -> f64, load: impl Fn(f64) -> f64, j: f64) -> Cycle {
    let points = (0..n)
        .map(|k| {
            let phi = std::f64::consts::TAU * k as f64 / n as f64;
            point(phi, 0.0, load(phi), omega(phi), j)
        })
        .collect();
    Cycle { points }
}

#[test]
fn a_speed_law_that_stops_or_turns_back_has_no_flywheel() {
    // A mean speed of zero (its rounding either sign, by the samples and the units): an error
    // every time, not a flywheel of 1e35 for one sign.
    for n in [360, 720, 1000] {
        for k in [1.0, 1e3, 1e-3] {
            let c = law_cycle(n, |phi| phi.sin() / k, |phi| phi.cos(), 1.0);
            let err = c.flywheel(0.05).unwrap_err();
            assert!(matches!(err, DynamicsError::BadValue { what: "cycle speed", .. }), "{n} {k}: {err}");
        }
    }
    // A positive mean of a law that turns back.
    let c = law_cycle(360, |phi| 1.0 + 2.0 * phi.sin(), |phi| phi.cos(), 1.0);
    assert!(matches!(c.flywheel(0.05), Err(DynamicsError::BadValue { what: "cycle speed", .. })));
    // Every speed positive: sized.
    let c = law_cycle(360, |phi| 10.0 + phi.sin(), |phi| phi.cos(), 1.0);
    assert!(c.flywheel(0.05).is_ok());
}

/// A crank turning clockwise (every speed negative) has a flywheel: the energy equation
/// `1/2 J omega^2 = E_0 + E(phi)` holds along the angle whichever way the input runs and is even
/// in the speed, so its flywheel is the counter-clockwise law's, bit for bit, its start speed
/// negative. It was refused as a speed "not positive at every angle". Against the closed form at
/// constant inertia, where the energy method is exact: a load `50 cos phi` swings the work by
/// `dE = 100`, so `J_total = dE / (delta omega_m^2) = 100 / (0.05 * 100) = 20`, the flywheel 19
/// beside the mechanism's 1, and the speed at phi = 0 (`E = 0`, midway) `sqrt(2 E_0 / 20)` with
/// `E_0 + 50 = 10 * 10.25^2`: 10.0031. The samples' trapezoidal work is `sin phi` to `h^2 / 12`
/// of it (2.5e-5 at a degree), hence 1e-4.
#[test]
fn a_clockwise_crank_has_the_flywheel_of_the_counter_clockwise_one() {
    let clockwise = law_cycle(360, |_| -10.0, |phi| 50.0 * phi.cos(), 1.0).flywheel(0.05).unwrap();
    let close = |got: f64, want: f64| (got - want).abs() <= 1e-4 * want.abs();
    assert!(close(clockwise.total_inertia, 20.0) && close(clockwise.flywheel, 19.0), "{clockwise:?}");
    assert!(close(clockwise.exact, 19.0), "{clockwise:?}");
    let e0 = 10.0 * 10.25f64.powi(2) - 50.0;
    assert!(close(clockwise.start_speed, -(e0 / 10.0).sqrt()), "{clockwise:?}");
    // A varying inertia and speed: the mirror image of the counter-clockwise law, bit for bit.
    let points = |sign: f64| {
        let points = (0..360)
            .map(|k| {
                let phi = std::f64::consts::TAU * k as f64 / 360.0;
                let law = sign * (10.0 + 0.3 * phi.sin());
                point(phi, 0.0, 40.0 * phi.cos() + 15.0 * (2.0 * phi).sin(), law, 2.0 + (2.0 * phi).cos())
            })
            .collect();
        Cycle { points }
    };
    let forward = points(1.0).flywheel(0.02).unwrap();
    let backward = points(-1.0).flywheel(0.02).unwrap();
    assert!(forward.exact > 0.0 && forward.start_speed > 0.0, "{forward:?}");
    assert_eq!(backward, Flywheel { start_speed: -forward.start_speed, ..forward });
}

#[test]
fn a_machine_without_inertia_is_a_singular_mass_unless_a_flywheel_gives_it_one() {
    // No work over the cycle and no inertia: no flywheel is needed, and the speed does not follow
    // from the energy: a singular mass at the first angle, not an overflow of the sizing.
    let err = law_cycle(36, |_| 10.0, |_| 0.0, 0.0).flywheel(0.05).unwrap_err();
    assert!(matches!(&err, DynamicsError::SingularMass { x, .. } if x == &[0.0]), "{err}");
    // Loads without inertia: the flywheel carries the whole swing, at a finite start speed.
    let f = law_cycle(36, |_| 10.0, |phi| phi.cos(), 0.0).flywheel(0.05).unwrap();
    assert!(f.exact > 0.0 && f.start_speed > 0.0 && f.start_speed.is_finite(), "{f:?}");
}

#[test]
fn an_integration_that_cannot_move_a_huge_coordinate_is_an_error() {
    // y' = 1 from y = 1e300: every step's change is far below the spacing of f64 there
    // (about 1e284), so y would stay at 1e300 and an Ok would report a frozen state.
    let cfg = OdeConfig::default();
    let err = dopri5(|_, _| Ok([1.0]), 0.0, [1e300], 1.0, &cfg, |_, _| Ok(false)).unwrap_err();
    let DynamicsError::CannotAdvance { component: 0, value, change, .. } = err else { panic!("{err}") };
    assert_eq!(value, 1e300);
    assert!(change > cfg.atol && change < 1.0, "{change}");
    assert!(err.to_string().contains("spacing of f64 numbers there (1.4"), "{err}");
    // A change below the absolute tolerance may be lost (a machine coming to rest), and a
    // large value that does register its change integrates as before.
    let (_, y) = dopri5(|_, _| Ok([1e-20]), 0.0, [1.0], 1.0, &cfg, |_, _| Ok(false)).unwrap();
    assert_eq!(y, [1.0]);
    let (_, y) = dopri5(|_, _| Ok([1.0]), 0.0, [1e6], 1.0, &cfg, |_, _| Ok(false)).unwrap();
    assert_eq!(y, [1e6 + 1.0]);
    // A state that overflows is never accepted: y' = y^2 from 1 blows up at t = 1, and
    // y' = 1e308 from 1e308 leaves the f64 range at t = 0.8 with a finite derivative (so the
    // error estimate, relative to an infinite state, would not see it).
    let r = dopri5(|_, y| Ok([y[0] * y[0]]), 0.0, [1.0], 2.0, &cfg, |_, _| Ok(false));
    assert!(matches!(r, Err(DynamicsError::StepTooSmall { .. })), "{r:?}");
    let r = dopri5(|_, _| Ok([1e308]), 0.0, [1e308], 2.0, &cfg, |_, y| Ok(!y[0].is_finite()));
    assert!(matches!(r, Err(DynamicsError::StepTooSmall { t, .. }) if t < 0.8), "{r:?}");
}

/// From rest the first step is not a millionth of the span: over a span of 1e12 under a unit
/// acceleration that was a step of 1e6, whose stages reach 1e11, beyond a domain of 1e6 where
/// the motion itself stays until t = 1414 (as a simulation from rest over a long time asked its
/// kinematics for the crank a million turns on, and failed). A motion that truly leaves the
/// domain still ends with `f`'s error.
#[test]
fn a_first_step_from_rest_stays_near_the_start_whatever_the_span() {
    let cfg = OdeConfig::default();
    let out = |y: &[f64; 2]| DynamicsError::Overflow { what: "positions", x: vec![y[0]], names: Vec::new() };
    let f = |_: f64, y: &[f64; 2]| if y[0].abs() <= 1e6 { Ok([y[1], 1.0]) } else { Err(out(y)) };
    let (t, y) = dopri5(f, 0.0, [0.0, 0.0], 1e12, &cfg, |s, _| Ok(s.t1() >= 1.0)).unwrap();
    assert!((1.0..1e3).contains(&t), "{t}");
    assert!((y[0] - t * t / 2.0).abs() <= 1e-9 * t * t && (y[1] - t).abs() <= 1e-9 * t, "{y:?} at {t}");
    // Beyond the domain at t = sqrt(2e6): `f`'s error.
    let r = dopri5(f, 0.0, [0.0, 0.0], 1e12, &cfg, |_, _| Ok(false));
    assert!(matches!(r, Err(DynamicsError::Overflow { what: "positions", .. })), "{r:?}");
}

/// A start not finite is a bad value, not a motion singular at t = 0 (every step was
/// rejected down to the time's resolution).
#[test]
fn an_integration_from_a_start_not_finite_is_a_bad_value() {
    let cfg = OdeConfig::default();
    let decay = |_: f64, y: &[f64; 1]| Ok([-y[0]]);
    let r = dopri5(decay, 0.0, [f64::NAN], 1.0, &cfg, |_, _| Ok(false));
    assert!(matches!(r, Err(DynamicsError::BadValue { what: "initial state", .. })), "{r:?}");
    let r = dopri5(|_, _| Ok([f64::NAN]), 0.0, [1.0], 1.0, &cfg, |_, _| Ok(false));
    assert!(matches!(r, Err(DynamicsError::BadValue { what: "derivative at the start", .. })), "{r:?}");
}

#[test]
fn shaking_and_centre_of_mass_are_typed_errors_or_finite() {
    let model = MassModel::<0, 1, 2>::new().with_body(body(2.0, 0.01)).unwrap();
    let k = crank(0.1);
    let s = model.shaking(&k, &[10.0], &[0.0], [0.0; 2]).unwrap();
    // The crank pin's centripetal acceleration: -m a = m r w^2 outwards, along +x.
    assert!((s.force[0] - 2.0 * 0.1 * 100.0).abs() < 1e-12 && s.force[1].abs() < 1e-12, "{s:?}");
    // Speeds whose square overflows, a moment centre at the end of the f64 range.
    let err = model.shaking(&k, &[1e200], &[0.0], [0.0; 2]).unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { what: "shaking force or moment", .. }), "{err}");
    let err = model.shaking(&k, &[1e150], &[0.0], [0.0, f64::MAX]).unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { .. }), "{err}");
    assert!(matches!(model.shaking(&k, &[f64::NAN], &[0.0], [0.0; 2]), Err(DynamicsError::BadValue { .. })));
    assert!(matches!(model.shaking(&k, &[1.0], &[0.0], [f64::INFINITY, 0.0]), Err(DynamicsError::BadValue { .. })));
    // The centre of mass: none without mass; the mean of huge coordinates computed weighted.
    assert_eq!(model.centre_of_mass(&k).unwrap(), [0.1, 0.0]);
    let none = MassModel::<0, 1, 2>::new();
    assert!(matches!(none.centre_of_mass(&k), Err(DynamicsError::BadValue { what: "total mass", .. })));
    let heavy = MassModel::<0, 1, 2>::new().with_body(body(1e300, 0.0)).unwrap();
    let far = crank(1e300);
    assert_eq!(heavy.centre_of_mass(&far).unwrap(), [1e300, 0.0]);
    // Coefficients set by hand to NaN are named, not reported as an overflow.
    let mut d = model.dynamics(&k, &[1.0]).unwrap();
    d.mass[0][0] = f64::NAN;
    assert!(matches!(d.accelerations(&[0.0], &[1.0], &[1.0]), Err(DynamicsError::BadValue { .. })));
    assert!(matches!(d.checked_drive(&[0.0], &[1.0], &[1.0]), Err(DynamicsError::BadValue { .. })));
}

/// A turn of the largest sample count whose states the memory budget holds is not reserved up
/// front: the sweep starts and fails at its first solve (a guess that is not a number) instead
/// of the process aborting on an allocation of that many states. The largest count an analysis
/// takes is beyond the budget, and refused before anything is allocated, as is a larger one.
#[test]
fn a_huge_turn_is_not_reserved_up_front() {
    let m = crate::analysis::demo::SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
    let most = crate::paths::collected::MAX_COLLECTED_BYTES / size_of::<crate::Kin<1, 1, 1>>();
    let r = turn_states(crate::Compiled(&m), 0.0, most, [f64::NAN]);
    assert!(matches!(r, Err(DynamicsError::Kinematics { .. })), "{r:?}");
    let r = turn_states(crate::Compiled(&m), 0.0, crate::analysis::MAX_SAMPLES, [f64::NAN]);
    assert!(matches!(r, Err(DynamicsError::BadValue { what: "samples", .. })), "{r:?}");
    let r = turn_states(crate::Compiled(&m), 0.0, 1 << 40, [f64::NAN]);
    assert!(matches!(r, Err(DynamicsError::BadValue { what: "samples", .. })), "{r:?}");
}

/// `y'' = -w^2 y` from `y = 1, y' = 0`, as `[y, y' / w]`: `y = cos(w t)`, `y' / w = -sin(w t)`.
fn oscillator(w: f64) -> impl FnMut(f64, &[f64; 2]) -> Result<[f64; 2], DynamicsError> {
    move |_, y| Ok([w * y[1], -w * y[0]])
}

#[test]
fn a_long_span_steps_as_finely_as_a_short_one() {
    // A fast oscillator's steps (about 1e-5 at these tolerances) are far below the span's
    // rounding (8 eps 1e12 = 1.8e-3): the steps are fine at t = 0 all the same, where the time
    // resolves any step, and the motion is that of a short run.
    let w = 1000.0;
    let cfg = OdeConfig::default();
    let mut first = None;
    let (t, y) = dopri5(oscillator(w), 0.0, [1.0, 0.0], 1e12, &cfg, |s, _| {
        first.get_or_insert(s.h);
        Ok(s.t1() >= 0.01)
    })
    .unwrap();
    assert!(first.is_some_and(|h| h < 1e-3), "first step {first:?}");
    assert!((0.01..0.011).contains(&t), "{t}");
    assert!((y[0] - (w * t).cos()).abs() < 1e-8 && (y[1] + (w * t).sin()).abs() < 1e-8, "{y:?} at t = {t}");
    // The same run to 0.01 exactly, over a short span: the same steps, the same state.
    let short = dopri5(oscillator(w), 0.0, [1.0, 0.0], 0.01, &cfg, |_, _| Ok(false)).unwrap().1;
    assert!((short[0] - (w * 0.01f64).cos()).abs() < 1e-8, "{short:?}");
    // A start far out in time resolves steps only as its time does: 8 eps 1e12 there.
    let far = dopri5(oscillator(w), 1e12, [1.0, 0.0], 2e12, &cfg, |_, _| Ok(false)).unwrap_err();
    assert!(matches!(far, DynamicsError::StepTooSmall { t: 1e12, .. }), "{far}");
}

#[test]
fn a_span_beyond_the_step_budget_says_what_to_do() {
    let cfg = OdeConfig::default().with_max_steps(500);
    let err = dopri5(oscillator(1000.0), 0.0, [1.0, 0.0], 1e12, &cfg, |_, _| Ok(false)).unwrap_err();
    let DynamicsError::TooManySteps { steps: 500, t, t_end } = err else { panic!("{err}") };
    assert!(t > 0.0 && t < 1.0 && t_end == 1e12, "{err}");
    let message = err.to_string();
    for what in ["budget of 500 steps", " of 1000000000000:", "`--time`", "`OdeConfig::max_steps`"] {
        assert!(message.contains(what), "`{what}` missing: {message}");
    }
    // A budget of one step is one, not "1 steps".
    let cfg = OdeConfig::default().with_max_steps(1);
    let err = dopri5(oscillator(1000.0), 0.0, [1.0, 0.0], 1e12, &cfg, |_, _| Ok(false)).unwrap_err();
    assert!(matches!(err, DynamicsError::TooManySteps { steps: 1, .. }), "{err}");
    assert!(err.to_string().contains("made its budget of 1 step and reached"), "{err}");
}

/// A derivative beyond 1e154 of its tolerance's scale overflowed the squares of the error norm:
/// the first step was `0.01 / inf = 0`, reported as a singular motion at the start. The norm is
/// finite wherever it is: the motion is integrated (`y = 1e170 t` at t = 1e-160 here, exactly
/// linear) or, where the state itself leaves f64, ends as before.
#[test]
fn a_fast_motion_is_not_singular_at_its_start() {
    let cfg = OdeConfig::default();
    let (t, y) = dopri5(|_, _| Ok([1e170]), 0.0, [0.0], 1e-160, &cfg, |_, _| Ok(false)).unwrap();
    assert_eq!(t, 1e-160);
    assert!((y[0] - 1e10).abs() <= 1e-12 * 1e10, "{y:?}");
    // Two components of 1e200 and 1e-300 of their scales: the norm of the first.
    let v = [1e200 * cfg.atol, 1e-300 * cfg.atol];
    let n = norm(&v, &[0.0; 2], &[0.0; 2], &cfg);
    assert!((n - 1e200 / 2f64.sqrt()).abs() <= 1e-15 * n, "{n:e}");
    // Squares that underflow: 1e-170 of the scale is a norm of 1e-170, not 0.
    let n = norm(&[1e-170 * cfg.atol], &[0.0], &[0.0], &cfg);
    assert!((n - 1e-170).abs() <= 1e-15 * 1e-170, "{n:e}");
    assert!(norm(&[f64::NAN, 1.0], &[0.0; 2], &[0.0; 2], &cfg).is_nan());
    assert_eq!(norm(&[f64::INFINITY, 1.0], &[0.0; 2], &[0.0; 2], &cfg), f64::INFINITY);
    assert_eq!(norm(&[0.0, 0.0], &[0.0; 2], &[0.0; 2], &cfg), 0.0);
    // A derivative whose ratio to the absolute tolerance is beyond f64 has no first step.
    let r = dopri5(|_, _| Ok([1e305]), 0.0, [0.0], 1.0, &cfg, |_, _| Ok(false));
    assert!(matches!(r, Err(DynamicsError::BadValue { what: "derivative at the start", value: 1e305, .. })), "{r:?}");
}

/// A span shorter than the time's rounding (`--time 5e-324`) is refused as such, not reported
/// as a singular motion at the start.
#[test]
fn a_span_below_the_time_s_rounding_is_refused() {
    let cfg = OdeConfig::default();
    for (t0, t_end) in [(0.0, 5e-324), (1.0, 1.0 + f64::EPSILON), (1e12, 1e12 + 1e-3)] {
        let r = dopri5(oscillator(1.0), t0, [1.0, 0.0], t_end, &cfg, |_, _| Ok(false));
        assert!(matches!(r, Err(DynamicsError::BadValue { what: "end time", .. })), "{t0} {t_end}: {r:?}");
    }
    // Beyond the floor a step is taken, over a span of subnormal times too. From rest (a
    // machine started at speed 0, `kinloop simulate --time 1e-320`) the first step is a
    // millionth of the span, below the floor there or 0: such spans, from ten units of the last
    // place to 1e-317, were reported singular motions at their start.
    let from_rest = |_: f64, y: &[f64; 2]| Ok([y[1], 1.0]);
    for t_end in [1e-300, 1e-310, 1e-317, 1e-320, 5e-323] {
        let r = dopri5(oscillator(1.0), 0.0, [1.0, 0.0], t_end, &cfg, |_, _| Ok(false));
        let (t, y) = r.unwrap_or_else(|e| panic!("{t_end:e}: {e}"));
        // `-sin t` is `-t` there, to the few units of the last place a subnormal end holds.
        assert!(t == t_end && y[0] == 1.0 && (y[1] + t_end).abs() <= 0.2 * t_end, "{t_end:e}: {y:?}");
        let r = dopri5(from_rest, 0.0, [0.0, 0.0], t_end, &cfg, |_, _| Ok(false));
        let (t, y) = r.unwrap_or_else(|e| panic!("from rest, {t_end:e}: {e}"));
        // The speed `t`; the position `t^2 / 2`, 0 or a few units of the last place.
        assert!(t == t_end && y[0] <= t_end && (y[1] - t_end).abs() <= 0.2 * t_end, "{t_end:e}: {y:?}");
    }
}

/// A step that ends a few units in the last place short of the span's end leaves a sliver no
/// step can take (below the time's rounding there): the step ends the span instead. The steps
/// of a plain oscillator capped by `h_max = 1e-3` reach 1.0069999999999997, and the sliver left
/// to 1.007, 2.2e-16, ended its run as a singular motion there; so for the ends 1.008 to 1.011
/// (of those below 1.1: 16 of 12000 runs to `n h_max` failed, `h_max` from 1e-3 to 0.3).
/// Every such run reaches its end, where
/// the oscillator is `(cos t, -sin t)`: its steps, 1e-3 at a tolerance of 1e-10, err by about
/// 1e-16 each, 1e-13 over a thousand of them; 1e-10 is the tolerance itself.
#[test]
fn a_step_ending_within_the_time_s_rounding_of_the_end_ends_the_span() {
    let cfg = OdeConfig::default().with_h_max(1e-3);
    for n in 1000..1100 {
        let t_end = n as f64 * 1e-3;
        let r = dopri5(oscillator(1.0), 0.0, [1.0, 0.0], t_end, &cfg, |_, _| Ok(false));
        let (t, y) = r.unwrap_or_else(|e| panic!("to {t_end}: {e}"));
        assert_eq!(t, t_end);
        assert!((y[0] - t_end.cos()).abs() < 1e-10 && (y[1] + t_end.sin()).abs() < 1e-10, "{y:?} at {t_end}");
    }
}
