//! Forward dynamics: the Dormand–Prince integrator against closed-form solutions, energy
//! conservation of the free rhombic drive over 100 turns, the flywheel's speed fluctuation
//! reproduced by simulation, the run-up from rest under a motor characteristic, and a typed
//! stop at a limit position (but not at one a step's trial state was only thrown past); the
//! steps handed over as they are made (`run_steps`) are the recorded trajectory's, bit for bit.

use crate::fixtures::{FourBar, RhombicDrive, SliderCrank, rhombic_bodies, rhombic_model};
use kinloop::Mechanism;
use kinloop::dynamics::{
    Body, Coord, DenseStep, DynamicsError, InverseCycle, MassModel, OdeConfig, Rotation, RunConfig, Simulation,
    SpeedLaw, Trajectory, dopri5,
};
use std::f64::consts::TAU;

use crate::support::{bisect, tol};

#[test]
fn dopri5_matches_closed_forms() {
    let cfg = OdeConfig::default().with_tolerances(1e-11, 1e-11);
    // Harmonic oscillator over ten periods: y = (cos t, -sin t).
    let mut worst_dense: f64 = 0.0;
    let (t, y) = dopri5(
        |_, y| Ok([y[1], -y[0]]),
        0.0,
        [1.0, 0.0],
        10.0 * TAU,
        &cfg,
        |s, _| {
            for k in 1..4 {
                let t = s.t0 + s.h * k as f64 / 4.0;
                let y = s.at(t);
                worst_dense = worst_dense.max((y[0] - t.cos()).abs()).max((y[1] + t.sin()).abs());
            }
            Ok(false)
        },
    )
    .unwrap();
    assert_eq!(t, 10.0 * TAU);
    // Global error: ~ tolerance times the number of steps (a few hundred).
    assert_close!(y[0], 1.0, 1e-8, "{y:?}");
    assert_close!(y[1], 0.0, 1e-8, "{y:?}");
    assert!(worst_dense < 1e-8, "dense output error {worst_dense:e}");
    // Non-autonomous: y' = -2 t y, y = exp(-t^2).
    let (_, y) = dopri5(|t, y| Ok([-2.0 * t * y[0]]), 0.0, [1.0], 3.0, &cfg, |_, _| Ok(false)).unwrap();
    assert_close!(y[0], (-9f64).exp(), 1e-10);
    // A failing right-hand side stops the integration with its error.
    let err = dopri5(
        |t, y| if t > 1.0 { Err(DynamicsError::StepTooSmall { t, h: 0.0 }) } else { Ok([y[0]]) },
        0.0,
        [1.0],
        2.0,
        &cfg,
        |_, _| Ok(false),
    );
    assert!(matches!(err, Err(DynamicsError::StepTooSmall { h: 0.0, .. })));
}

/// Each step's dense output gives, to the last bit, the state the step started from at `t0`
/// and the state it reached at `t1()` (which the integrator hands over with the step): the
/// interpolant is exact at both ends, as `DenseStep::at` says. Harmonic oscillators from
/// starts whose components differ in magnitude and change sign along the way, where `y0 +
/// (y1 - y0)` rounds off `y1`; and a recorded trajectory read at its end time gives its end.
#[test]
fn dense_output_is_exact_at_both_ends_of_every_step() {
    let cfg = OdeConfig::default().with_tolerances(1e-9, 1e-9);
    for (y0, t_end) in [([1.0, 0.0], 20.0), ([0.1, 3.0], 7.3), ([1e-3, 2.0], 50.0)] {
        let mut from = y0;
        let mut steps = Vec::new();
        let (t, end) = dopri5(
            |_, y| Ok([y[1], -y[0]]),
            0.0,
            y0,
            t_end,
            &cfg,
            |s, y| {
                assert_eq!(s.at(s.t0).map(f64::to_bits), from.map(f64::to_bits), "start of the step at {}", s.t0);
                assert_eq!(s.at(s.t1()).map(f64::to_bits), y.map(f64::to_bits), "end of the step at {}", s.t0);
                from = *y;
                steps.push(*s);
                Ok(false)
            },
        )
        .unwrap();
        assert!(steps.len() > 100, "{y0:?}: {} steps", steps.len());
        let run = Trajectory { steps, t_end: t, end };
        assert_eq!(run.at(t).map(f64::to_bits), end.map(f64::to_bits), "{y0:?}: the trajectory's end");
    }
}

/// The kinetic energy at `(phi, omega)`: it needs the solved positions there, on the branch of
/// the run, reached by a sweep from 0 over one turn plus the final angle modulo a turn (the
/// drive repeats every turn).
fn energy_at(drive: &RhombicDrive, model: &MassModel<4, 1, 7>, phi: f64, omega: f64) -> f64 {
    let sweep = drive.sampled(0.0, TAU + phi.rem_euclid(TAU), 721, &drive.guess(0.0)).unwrap();
    let k = sweep.states().last().unwrap();
    model.kinetic_energy(k, &[omega])
}

#[test]
fn free_rhombic_drive_conserves_energy_over_100_turns() {
    let drive = RhombicDrive::default();
    let model = rhombic_bodies([0.0, 0.0]);
    let cfg = RunConfig::default().with_ode(OdeConfig::default().with_tolerances(1e-13, 1e-13));
    let omega0 = 12.0;
    let e0 = energy_at(&drive, &model, 0.0, omega0);
    let run = Simulation::new(&drive, &model)
        .start(0.0, omega0)
        .guess(drive.guess_flat(&[0.0]))
        .config(cfg)
        .stop_when(|_, y| y[0] >= 100.0 * TAU)
        .run(1e3)
        .unwrap();
    let [phi, omega] = run.end;
    assert!(phi >= 100.0 * TAU, "reached only {} turns", phi / TAU);
    let drift = (energy_at(&drive, &model, phi, omega) - e0).abs() / e0;
    eprintln!("relative energy drift {drift:e} over 100 turns, {} steps", run.steps.len());
    assert!(drift < 1e-8, "relative energy drift {drift:e} over {} steps", run.steps.len());
}

/// Largest and smallest speed over one turn from `phi_from`, from the dense output.
fn speed_range(run: &Trajectory, phi_from: f64) -> (f64, f64) {
    let (mut hi, mut lo) = (f64::NEG_INFINITY, f64::INFINITY);
    for s in &run.steps {
        for k in 0..=20 {
            let [phi, omega] = s.at(s.t0 + s.h * k as f64 / 20.0);
            if phi >= phi_from && phi < phi_from + TAU {
                hi = hi.max(omega);
                lo = lo.min(omega);
            }
        }
    }
    (hi, lo)
}

#[test]
fn flywheel_gives_the_required_speed_fluctuation() {
    let drive = RhombicDrive::default();
    let model = rhombic_model([0.0, 0.0]);
    let (omega_m, delta) = (10.0, 1.0 / 50.0);
    let cycle = InverseCycle::new(&drive, &model, SpeedLaw::Constant(omega_m))
        .samples(3600)
        .guess(drive.guess_flat(&[0.0]))
        .run()
        .unwrap();
    let fw = cycle.flywheel(delta).unwrap();
    assert!(fw.exact > 0.0 && fw.flywheel > 0.0);
    let cfg = RunConfig::default().with_flywheel(fw.exact);
    let run = Simulation::new(&drive, &model)
        .start(0.0, fw.start_speed)
        .guess(drive.guess_flat(&[0.0]))
        .drive(|_, _, _| fw.mean_torque)
        .config(cfg)
        .stop_when(|_, y| y[0] >= 2.5 * TAU)
        .run(1e3)
        .unwrap();
    let (hi, lo) = speed_range(&run, TAU);
    eprintln!(
        "flywheel for delta = 1/50: energy method {:.6}, exact {:.6}; simulated delta {:.8}, mean speed {:.8}",
        fw.flywheel,
        fw.exact,
        (hi - lo) / omega_m,
        (hi + lo) / 2.0
    );
    // The steady cycle is reproduced: sampling of the extremes (0.1 degree, ~1e-7) and the
    // trapezoidal work (~1e-7) limit the agreement.
    assert_close!((hi + lo) / 2.0, omega_m, 1e-5 * omega_m, "mean {}", (hi + lo) / 2.0);
    assert_close!((hi - lo) / omega_m, delta, 1e-4 * delta, "delta {}", (hi - lo) / omega_m);
}

/// The same drive turning clockwise: the flywheel of the law `-omega_m` (refused before, its
/// speeds "not positive") is the counter-clockwise one's, its start speed negative, and the
/// machine with it, driven backwards by the mean torque, runs a steady cycle whose speed
/// fluctuates by `delta` about `-omega_m` (over its second turn backwards; the tolerances of the
/// counter-clockwise run above).
#[test]
fn a_clockwise_flywheel_gives_the_required_speed_fluctuation() {
    let drive = RhombicDrive::default();
    let model = rhombic_model([0.0, 0.0]);
    let (omega_m, delta) = (10.0, 1.0 / 50.0);
    let cycle = |omega| {
        let run = InverseCycle::new(&drive, &model, SpeedLaw::Constant(omega)).samples(3600);
        run.guess(drive.guess_flat(&[0.0])).run().unwrap()
    };
    let fw = cycle(-omega_m).flywheel(delta).unwrap();
    let forward = cycle(omega_m).flywheel(delta).unwrap();
    assert!(fw.start_speed < 0.0 && fw.exact > 0.0, "{fw:?}");
    assert_close!(fw.exact, forward.exact, 1e-12 * forward.exact);
    let run = Simulation::new(&drive, &model)
        .start(0.0, fw.start_speed)
        .guess(drive.guess_flat(&[0.0]))
        .drive(|_, _, _| fw.mean_torque)
        .config(RunConfig::default().with_flywheel(fw.exact))
        .stop_when(|_, y| y[0] <= -2.5 * TAU)
        .run(1e3)
        .unwrap();
    let (mut hi, mut lo) = (f64::NEG_INFINITY, f64::INFINITY);
    for s in &run.steps {
        for k in 0..=20 {
            let [phi, omega] = s.at(s.t0 + s.h * k as f64 / 20.0);
            if phi <= -TAU && phi > -2.0 * TAU {
                hi = hi.max(omega);
                lo = lo.min(omega);
            }
        }
    }
    assert!(hi < 0.0, "{hi}");
    assert_close!((hi + lo) / 2.0, -omega_m, 1e-5 * omega_m, "mean {}", (hi + lo) / 2.0);
    assert_close!((hi - lo) / omega_m, delta, 1e-4 * delta, "delta {}", (hi - lo) / omega_m);
}

/// With a constant reduced inertia the energy method is exact: `1/2 J (omega_max^2 -
/// omega_min^2) = dE_max` is `J delta omega_m^2 = dE_max` when `omega_m` is the mid-range
/// speed. A crank of constant inertia under a load torque `3 sin phi + sin 2 phi`.
#[test]
fn energy_method_is_exact_for_constant_inertia() {
    let sc = SliderCrank::default();
    let model = crank_model(0.5)
        .and_then(|m| m.with_torque("load", Rotation::Input(0), |k, _| 3.0 * k.x[0].sin() + (2.0 * k.x[0]).sin()))
        .unwrap();
    let cycle = InverseCycle::new(&sc, &model, SpeedLaw::Constant(20.0))
        .samples(3600)
        .guess(sc.guess_flat(&[0.0]))
        .run()
        .unwrap();
    let fw = cycle.flywheel(0.02).unwrap();
    // Work of the load from its closed-form integral, E = 3 (1 - cos phi) + (1 - cos 2 phi) / 2,
    // its swing taken over the same angles (the trapezoidal work is accurate to ~1e-7).
    let energy = |phi: f64| 3.0 * (1.0 - phi.cos()) + 0.5 * (1.0 - (2.0 * phi).cos());
    let samples: Vec<f64> = (0..3600).map(|j| energy(TAU * j as f64 / 3600.0)).collect();
    let swing = samples.iter().copied().fold(f64::MIN, f64::max) - samples.iter().copied().fold(f64::MAX, f64::min);
    assert_close!(fw.energy_swing, swing, 1e-6 * swing, "{} vs {swing}", fw.energy_swing);
    assert_close!(fw.mean_torque, 0.0, tol::SOLVE);
    assert_close!(fw.flywheel / fw.exact, 1.0, 1e-6, "{} vs {}", fw.flywheel, fw.exact);
    assert_close!(fw.total_inertia, swing / (0.02 * 400.0), 1e-6 * fw.total_inertia);
}

/// From rest under `M = M_s (1 - omega / omega_s)` and viscous friction nowhere: on the
/// periodic steady state the motor does no net work over a turn, so the angle-averaged speed
/// `int omega dphi / 2 pi = int omega^2 dt / int omega dt` equals `omega_s`.
#[test]
fn run_up_from_rest_reaches_the_synchronous_speed_on_average() {
    let sc = SliderCrank::default();
    let model = crank_and_piston(2.0);
    let (m_s, omega_s) = (40.0, 6.0);
    let motor = move |_: f64, _: f64, omega: f64| m_s * (1.0 - omega / omega_s);
    let run = Simulation::new(&sc, &model).start(0.0, 0.0).guess(sc.guess_flat(&[0.0])).drive(motor).run(60.0).unwrap();
    let last = run.end[0] - TAU;
    // Gauss–Legendre with 5 nodes is exact for polynomials of degree 9: each step's dense
    // output is a quartic in time, so `omega` (degree 4) and `omega^2` (degree 8) are integrated
    // exactly over any interval of a step, to rounding.
    let nodes = [
        (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
        (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
        (0.0, 128.0 / 225.0),
        (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
        (0.906_179_845_938_664, 0.236_926_885_056_189_1),
    ];
    let (mut num, mut den) = (0.0, 0.0);
    for s in &run.steps {
        if s.at(s.t1())[0] <= last {
            continue;
        }
        // The last turn starts inside this step or before it: from where the angle passes
        // `last` (bisected on the dense output; the crank turns forward all along), or from the
        // step's start.
        let from = if s.at(s.t0)[0] < last { bisect(|t| s.at(t)[0] - last, s.t0, s.t1()) } else { s.t0 };
        let half = 0.5 * (s.t1() - from);
        for (x, w) in nodes {
            let [_, omega] = s.at(from + half * (1.0 + x));
            num += half * w * omega * omega;
            den += half * w * omega;
        }
    }
    // Left is the integration's own error: the transient decays with the time constant `J
    // omega_s / M_s`, under a second for these inertias, so after 60 s the motion is periodic to
    // rounding, and the average follows the integrator's tolerance (measured: off by 1.8e-6,
    // 2.3e-9, 2.0e-11 and 2.4e-13 at tolerances 1e-6, 1e-8, 1e-10 and 1e-12). At the default
    // 1e-10, ten times the tolerance; a motor that read the speed a relative 1e-7 off is caught.
    assert_close!(num / den / omega_s, 1.0, <= 1e-9, "angle-averaged speed {}", num / den);
    assert!(run.end[1] > 0.5 * omega_s);
}

kinloop::mechanism! {
    /// Non-Grashof four-bar: the input can only rock between two limit positions.
    pub struct Rocker {
        params a = 3.0, b = 2.0, c = 2.5, d = 4.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point sb = a @ phi + 0.5 * b @ beta;
    }
}

/// The input link and the coupler of [`Rocker`] (its centre of mass at the coupler's middle).
fn rocker_model() -> MassModel<2, 1, 2> {
    MassModel::new()
        .with_body(Body {
            name: "input".into(),
            mass: 0.0,
            com: [Coord::Fixed(0.0); 2],
            inertia: 1.0,
            rotation: Rotation::Input(0),
        })
        .and_then(|md| {
            md.with_body(Body {
                name: "coupler".into(),
                mass: 1.0,
                com: [Coord::Output(0), Coord::Output(1)],
                inertia: 0.3,
                rotation: Rotation::Unknown(0),
            })
        })
        .unwrap()
}

/// [`Rocker`]'s limit position at positive input: where |BD| = b + c (law of cosines).
fn rocker_limit() -> f64 {
    ((9.0 + 16.0 - 4.5f64 * 4.5) / 24.0).acos()
}

#[test]
fn running_into_a_limit_position_is_a_typed_error() {
    let m = Rocker::default();
    let model = rocker_model();
    let g = m.position_flat(&[0.0], &m.guess_flat(&[0.0]), &Default::default()).unwrap().0;
    let err = Simulation::new(&m, &model).start(0.0, 1.0).guess(g).drive(|_, _, _| 1.0).run(100.0).unwrap_err();
    let limit = rocker_limit();
    // Approaching it, J grows like K / (limit - phi) (the rod's angle analog like
    // 1 / sqrt(limit - phi)): with the energy E bounded (E ~ 2 here: the start's 1/2 J w^2 plus
    // the drive's work over 1.4 rad), the speed falls like sqrt(2 E (limit - phi) / K) and
    // reaches zero in finite time, where the input stops being a coordinate of the motion. The
    // step collapses there, unless a kinematic solve fails first, so the error is the singular
    // motion or the singular position, located. Where it stops: (1) limit - phi ~ K w^2 / (2 E) with the speed w at the
    // last step (~1e-6, measured), ~1e-12 for K / E of order one; (2) a kinematic solve accepts
    // residuals up to its tolerance (1e-12) and may sit that far (divided by the links' lengths,
    // 2 to 4) beyond the fold. Both are ~1e-12; 1e-9 leaves three orders for the constants.
    match &err {
        DynamicsError::SingularMotion { t, x, speed, .. } => {
            eprintln!("stopped at phi = {}, limit - phi = {:e}, speed {:e}", x[0], limit - x[0], speed[0]);
            assert!(t.is_finite() && (limit - x[0]).abs() < 1e-9, "{err}");
            assert_close!(speed[0], 0.0, 1e-3, "the speed must fall to zero at the limit: {err}");
            // The input by its name and the speed as numbers read, not as Rust's debug text.
            let message = err.to_string();
            assert!(message.starts_with(&format!("the motion is singular at phi = {}, speed ", x[0])), "{err}");
            assert!(!message.contains('['), "{err}");
        }
        // With the rocker's dyad solved in closed form, the kinematic solve may meet the fold
        // first (its discriminant vanishes there): a typed singular position, located as
        // precisely.
        DynamicsError::Kinematics { t, source } => {
            let at = source.location().map(|l| l.inputs[0].1).unwrap_or(f64::NAN);
            assert!(t.is_some_and(f64::is_finite) && (limit - at).abs() < 1e-9, "{err}");
            assert!(matches!(source, kinloop::Error::Singular { .. } | kinloop::Error::NoAssembly { .. }), "{err}");
        }
        other => panic!("expected a singular motion or position, got {other}"),
    }
}

/// A crank on a unit torsion spring (drive `-phi`) swinging well inside the limit positions of
/// a non-Grashof four-bar (±1.3716 rad). Its speed at 0 puts the kinetic energy there,
/// `1/2 J(0) omega0^2`, at the spring's `1/2 0.5^2`: energy conservation bounds the swing to
/// 0.5 rad (tolerances of 1e-6 and 1e-10 keep it within 0.5000).
fn spring_four_bar() -> (FourBar, MassModel<2, 1, 2>, f64) {
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let body =
        |name: &str, mass, com, inertia, rotation| Body { name: name.to_owned().into(), mass, com, inertia, rotation };
    let model = MassModel::new()
        .with_body(body("crank", 0.0, [Coord::Fixed(0.0); 2], 0.1, Rotation::Input(0)))
        .and_then(|md| {
            md.with_body(body("coupler", 2.0, [Coord::Output(0), Coord::Output(1)], 0.5, Rotation::Unknown(0)))
        })
        .and_then(|md| {
            md.with_body(body("rocker", 0.0, [Coord::Fixed(4.0), Coord::Fixed(0.0)], 0.7, Rotation::Unknown(1)))
        })
        .unwrap();
    let k = m.kinematics_flat(&[0.0], &m.guess_flat(&[0.0]), &Default::default()).unwrap();
    let j0 = model.dynamics(&k, &[0.0]).unwrap().reduced_inertia();
    (m, model, 0.5 / j0.sqrt())
}

/// The spring four-bar's swing (the largest `|phi|`, its steps sampled at eighths) over `t_end`
/// time units, from `phi = 0` at its start speed, at tolerances `tol`; the run must reach
/// `t_end`.
fn spring_swing(tol: f64, t_end: f64) -> f64 {
    let (m, model, omega0) = spring_four_bar();
    let cfg = RunConfig::default().with_ode(OdeConfig::default().with_tolerances(tol, tol));
    let run = Simulation::new(&m, &model)
        .start(0.0, omega0)
        .guess(m.guess_flat(&[0.0]))
        .drive(|_, phi, _| -phi)
        .config(cfg)
        .run(t_end)
        .unwrap();
    assert_eq!(run.t_end, t_end);
    let swing = run.steps.iter().flat_map(|s| (0..=8).map(move |k| s.at(s.t0 + s.h * k as f64 / 8.0)[0].abs()));
    swing.fold(0.0, f64::max)
}

/// A step too large for the motion throws its trial states past the limit positions: a
/// rejected step, not an error. At tolerances of 1e-3 the steps of the spring four-bar grow to
/// several time units, and the end of one from phi = 0.19 landed at phi = 3.63: the run ended at
/// t = 9.85 with the mechanism said not to assemble there, a position the motion never nears.
#[test]
fn a_step_thrown_past_a_limit_position_is_retried_not_an_error() {
    let swing = spring_swing(1e-3, 60.0);
    // Two periods (about 28 time units each), through the steps that threw their trials past
    // the limits. What bounds the swing is the energy, `1/2 phi^2` at the swing's ends: 1/8 at
    // the start, but at this tolerance the integration gains some with each swing (measured:
    // swings of 0.500, 0.532, 0.556 and 0.576, the last an energy a third above the start's).
    // 0.7 allows an energy of 0.245, twice the start's, and stays 0.67 rad short of the limits;
    // below 0.45 a fifth of the energy would be lost, which this integration does not do.
    assert!(swing > 0.45 && swing < 0.7, "swing {swing}");
}

/// A kinematic solve depends on the input's angle alone: a trial whose angle was thrown far
/// from its tangent was thrown off the motion, whatever its speed. Judged on the speed as well,
/// at a tolerance of 3e-4 the swing ran for 291 time units, ten periods, and a step then threw
/// its trial angle to -1.3742, just past the limit: the run failed there, the mechanism said
/// not to assemble at an angle the swing (0.71 rad at most) never nears.
#[test]
fn a_trial_angle_thrown_off_is_retried_whatever_its_speed() {
    let swing = spring_swing(3e-4, 300.0);
    // The energy bounds the swing to 0.5 rad; at this tolerance the integration gains some over
    // ten periods (measured: 0.71), far short of the limits at 1.37.
    assert!(swing > 0.45 && swing < 0.8, "swing {swing}");
}

/// A step longer than the last accepted one is the error control's guess from that step's
/// estimate: where its trial fails the kinematic solve, it is retried at the last accepted
/// length before the failure is believed. At a tolerance of 3e-3 a step grown from 3.3 to
/// about 4.2 time units threw its trial angle to -1.80 at t = 71.9, not far enough from its
/// tangent (-1.08) to count as thrown off: the run ended there, the mechanism said not to
/// assemble, where the swing (0.54 rad at most) never goes.
#[test]
fn a_grown_step_whose_trial_fails_is_retried_at_the_last_accepted_length() {
    let swing = spring_swing(3e-3, 200.0);
    // The energy bounds the swing to 0.5 rad (measured: 0.54 at this tolerance).
    assert!(swing > 0.45 && swing < 0.8, "swing {swing}");
}

/// A step's trial state that fails where the motion is heading is no step too large: the
/// motion arrives there. Without a drive the kinetic energy `1/2 J w^2` of the coasting rocker
/// stays what it was at the start, so its input's speed `w` cannot fall to zero before `J`
/// grows without bound, at the limit position: the input turns one way up to the limit, and the
/// run ends there with a typed error. At a loose tolerance the steps near the limit throw their
/// trials past it; retried with smaller steps whatever they were, those trials let the
/// integration turn the input round within its tolerance of the limit, on the branch it came on,
/// and coast back (measured: turned round 1e-4 short of the limit at t = 16.4, the run Ok at
/// t = 100).
#[test]
fn a_loose_tolerance_does_not_carry_a_rocker_back_from_its_limit_position() {
    let m = Rocker::default();
    let model = rocker_model();
    let g = m.position_flat(&[0.0], &m.guess_flat(&[0.0]), &Default::default()).unwrap().0;
    let cfg = RunConfig::default().with_ode(OdeConfig::default().with_tolerances(1e-3, 1e-3));
    let mut speeds = Vec::new();
    let err = Simulation::new(&m, &model)
        .start(0.0, 0.05)
        .guess(g)
        .config(cfg)
        .run_steps(100.0, |_, &[_, omega]| {
            speeds.push(omega);
            false
        })
        .unwrap_err();
    assert!(speeds.iter().all(|&omega| omega > 0.0), "the input turned round: {speeds:?}");
    // Where the mechanism cannot be assembled: at or past the limit (the located input is the
    // failing trial's, which this tolerance puts up to a step's turn of the crank beyond it).
    let limit = rocker_limit();
    let at = match &err {
        DynamicsError::SingularMotion { x, .. } => x[0],
        DynamicsError::Kinematics { source, .. } => source.location().map(|l| l.inputs[0].1).unwrap_or(f64::NAN),
        other => panic!("expected a singular motion or position, got {other}"),
    };
    assert!(at > limit - 1e-9, "{err}");
}

/// A simulation over a span far longer than it can step through: it starts as a short one
/// would (the steps of a fast crank, ~1e-4, are finer than the span's rounding, 8 eps 1e12 =
/// 1.8e-3, but not than the time's at t = 0) and ends on its step budget, saying so, not as a
/// singular motion at t = 0.
#[test]
fn a_long_simulation_ends_on_its_step_budget_not_as_a_singular_motion() {
    let sc = SliderCrank::default();
    // A piston makes the reduced inertia vary over a turn, so the steps stay short (a constant
    // one would make the motion a parabola, which the method integrates exactly in any step).
    let model = crank_and_piston(0.5);
    let cfg = RunConfig::default().with_flywheel(0.05).with_ode(OdeConfig::default().with_max_steps(2000));
    let sim = || Simulation::new(&sc, &model).start(0.0, 1000.0).guess(sc.guess_flat(&[0.0])).config(cfg);
    let err = sim().drive(|_, _, _| 2.5).run(1e12).unwrap_err();
    let DynamicsError::TooManySteps { steps: 2000, t, t_end } = err else { panic!("{err}") };
    assert!(t > 0.0 && t_end == 1e12, "{err}");
    assert!(err.to_string().contains("`--time`") && err.to_string().contains("`OdeConfig::max_steps`"), "{err}");
    // Its first steps are those of a short run: the same motion to the same time.
    let long = sim().drive(|_, _, _| 2.5).stop_when(|t, _| t >= 0.05).run(1e12).unwrap();
    let short = sim().drive(|_, _, _| 2.5).run(long.t_end).unwrap();
    assert!(long.steps[0].h < 1.8e-3, "first step {}", long.steps[0].h);
    assert_close!(long.end[0], short.end[0], 1e-8, "{:?} vs {:?}", long.end, short.end);
    assert_close!(long.end[1], short.end[1], 1e-6, "{:?} vs {:?}", long.end, short.end);
}

/// A recorded run keeps room for no more steps than its budget allows: the trajectory of 1500
/// steps of a run of 2000 at most holds at most 2000, where the doubling of its storage made
/// room for 2048 (at the default budget of ten million, for 16.8 million: 1.6 GB reserved for
/// the 0.96 GB a run can use). The steps are those the run hands over, bit for bit, and a span
/// beyond the budget still ends on it.
#[test]
fn a_recorded_run_reserves_no_more_than_its_step_budget() {
    let sc = SliderCrank::default();
    let model = crank_and_piston(0.5);
    let budget = 2000;
    let cfg = RunConfig::default().with_flywheel(0.05).with_ode(OdeConfig::default().with_max_steps(budget));
    let sim = || Simulation::new(&sc, &model).start(0.0, 1000.0).guess(sc.guess_flat(&[0.0])).config(cfg);
    let mut made = 0;
    let run = sim()
        .drive(|_, _, _| 2.5)
        .stop_when(move |_, _| {
            made += 1;
            made == 1500
        })
        .run(1e12)
        .unwrap();
    assert_eq!(run.steps.len(), 1500);
    assert!(run.steps.capacity() <= budget, "room for {} steps of a budget of {budget}", run.steps.capacity());
    let mut handed = Vec::new();
    let (t, end) = sim()
        .drive(|_, _, _| 2.5)
        .run_steps(1e12, |s, _| {
            handed.push(*s);
            handed.len() == 1500
        })
        .unwrap();
    assert_eq!(step_bits(&handed), step_bits(&run.steps));
    assert_eq!((t.to_bits(), end.map(f64::to_bits)), (run.t_end.to_bits(), run.end.map(f64::to_bits)));
    let err = sim().drive(|_, _, _| 2.5).run(1e12).unwrap_err();
    assert!(matches!(err, DynamicsError::TooManySteps { steps: 2000, .. }), "{err}");
}

/// A drive that grows without bound at t = 1/2 drives the speed to infinity there (`omega` like
/// `1 / (1/2 - t)`): the step collapses, and the error says where, the input by its name.
#[test]
fn a_collapsing_step_names_the_input_and_its_speed() {
    let sc = SliderCrank::default();
    let model = crank_model(1.0).unwrap();
    let drive = |t: f64, _: f64, _: f64| if t < 0.5 { (0.5 - t).powi(-2) } else { 0.0 };
    let err =
        Simulation::new(&sc, &model).start(0.0, 2.0).guess(sc.guess_flat(&[0.0])).drive(drive).run(1.0).unwrap_err();
    let DynamicsError::SingularMotion { t, x, speed, names, .. } = &err else { panic!("{err}") };
    assert!((t - 0.5).abs() < 1e-6 && speed[0] > 1e6, "{err}");
    assert_eq!(names, &["phi"]);
    let message = err.to_string();
    let expected = format!("the motion is singular at phi = {}, speed {} (t = {t}): ", x[0], speed[0]);
    assert!(message.starts_with(&expected), "{message}\nexpected {expected}");
}

/// A crank of moment of inertia `inertia` about its axis (centre of mass on the axis), turning
/// with the input.
fn crank_model(inertia: f64) -> Result<MassModel<2, 1, 2>, DynamicsError> {
    MassModel::new().with_body(Body {
        name: "crank".into(),
        mass: 1.0,
        com: [Coord::Fixed(0.0); 2],
        inertia,
        rotation: Rotation::Input(0),
    })
}

/// [`crank_model`] with a piston of 0.8 on the slider (its centre of mass at the slider's
/// coordinate, 0.3 above the line), whose motion makes the reduced inertia vary over a turn.
fn crank_and_piston(inertia: f64) -> MassModel<2, 1, 2> {
    crank_model(inertia)
        .and_then(|m| {
            m.with_body(Body {
                name: "piston".into(),
                mass: 0.8,
                com: [Coord::Unknown(1), Coord::Fixed(0.3)],
                inertia: 0.0,
                rotation: Rotation::None,
            })
        })
        .unwrap()
}

/// The steps a run hands over (`run_steps`) and the state at each one's end, recorded by the
/// caller.
type Handed = (Vec<DenseStep<2>>, Vec<[f64; 2]>);

/// Each step's start, size and dense output at five points (its ends and three inside), and
/// the state at its end, as bits: equal only if the steps are the same to the last bit.
fn step_bits(steps: &[DenseStep<2>]) -> Vec<u64> {
    let mut bits = Vec::new();
    for s in steps {
        bits.extend([s.t0.to_bits(), s.h.to_bits()]);
        for k in 0..=4 {
            bits.extend(s.at(s.t0 + s.h * k as f64 / 4.0).map(f64::to_bits));
        }
    }
    bits
}

/// The compiled mechanism's streamed steps are its recorded trajectory's, bit for bit: the
/// rhombic drive under a motor characteristic with a flywheel and a stop predicate; the state
/// handed with each step is the state at its end, and the run reaches the trajectory's end.
#[test]
fn the_streamed_steps_are_the_trajectory_s_bit_for_bit() {
    let drive = RhombicDrive::default();
    let model = rhombic_model([0.0, 0.0]);
    let cfg = RunConfig::default().with_flywheel(0.02);
    let sim = || {
        Simulation::new(&drive, &model)
            .start(0.0, 8.0)
            .guess(drive.guess_flat(&[0.0]))
            .drive(|_, _, omega| 3.0 - 0.2 * omega)
            .config(cfg)
            .stop_when(|_, y| y[0] >= 3.0 * TAU)
    };
    let stored = sim().run(50.0).unwrap();
    assert!(stored.end[0] >= 3.0 * TAU && stored.steps.len() > 50, "{} steps", stored.steps.len());
    let (mut steps, mut ends): Handed = (Vec::new(), Vec::new());
    let (t, end) = sim()
        .run_steps(50.0, |s, y| {
            steps.push(*s);
            ends.push(*y);
            false
        })
        .unwrap();
    assert_eq!(step_bits(&steps), step_bits(&stored.steps));
    assert_eq!((t.to_bits(), end.map(f64::to_bits)), (stored.t_end.to_bits(), stored.end.map(f64::to_bits)));
    assert_eq!(ends.last().map(|y| y.map(f64::to_bits)), Some(end.map(f64::to_bits)));
    // The state handed with a step is where the next one starts.
    for (y, next) in ends.iter().zip(&steps[1..]) {
        assert_eq!(y.map(f64::to_bits), next.at(next.t0).map(f64::to_bits));
    }
}

/// A consumer ends the run where it says: after the tenth step the run returns that step's
/// end, having made the recorded trajectory's first ten steps (and no more).
#[test]
fn the_consumer_of_the_steps_ends_the_run_early() {
    let sc = SliderCrank::default();
    let model = crank_and_piston(0.5);
    let sim = || Simulation::new(&sc, &model).start(0.0, 20.0).guess(sc.guess_flat(&[0.0])).drive(|_, _, _| 1.0);
    let stored = sim().run(2.0).unwrap();
    assert!(stored.steps.len() > 20, "{} steps", stored.steps.len());
    let (mut steps, mut ends): Handed = (Vec::new(), Vec::new());
    let (t, end) = sim()
        .run_steps(2.0, |s, y| {
            steps.push(*s);
            ends.push(*y);
            steps.len() == 10
        })
        .unwrap();
    assert_eq!(step_bits(&steps), step_bits(&stored.steps[..10]));
    assert_eq!(t.to_bits(), stored.steps[9].t1().to_bits());
    assert_eq!(end.map(f64::to_bits), ends[9].map(f64::to_bits));
    assert!(t < 2.0);
}

/// An error ends a streamed run as it ends the recorded one, with the same location (the time,
/// the input and its speed reached), after the steps before it were handed over: the last of
/// them ends where the error says the motion was.
#[test]
fn an_error_ends_the_streamed_run_where_it_happens() {
    let sc = SliderCrank::default();
    let model = crank_model(1.0).unwrap();
    let drive = |t: f64, _: f64, _: f64| if t < 0.5 { (0.5 - t).powi(-2) } else { 0.0 };
    let sim = || Simulation::new(&sc, &model).start(0.0, 2.0).guess(sc.guess_flat(&[0.0])).drive(drive);
    let stored = sim().run(1.0).unwrap_err();
    let (mut count, mut last) = (0, None);
    let streamed = sim()
        .run_steps(1.0, |s, y| {
            count += 1;
            last = Some((s.t1(), *y));
            false
        })
        .unwrap_err();
    assert_eq!(format!("{streamed:?}"), format!("{stored:?}"));
    let DynamicsError::SingularMotion { t, x, speed, .. } = &streamed else { panic!("{streamed}") };
    let (t1, y) = last.expect("steps before the error");
    assert!(count > 10, "{count} steps");
    assert_eq!((t1.to_bits(), y.map(f64::to_bits)), (t.to_bits(), [x[0].to_bits(), speed[0].to_bits()]));
}

/// A tiny absolute tolerance (pure relative error control) makes the first step from a state
/// with a zero component (an oscillator at its turning point, a machine at rest) many orders
/// of magnitude shorter than the tolerances allow: the step grows at the largest rate, and
/// the changes of the other components its first steps lose are not a state stuck at a huge
/// value. Such runs stopped with `CannotAdvance` (the oscillator at t = 3e-11 at `atol` 1e-20,
/// a machine from rest at t = 9e-12), telling the user to start from a smaller value.
#[test]
fn a_tiny_absolute_tolerance_integrates_from_a_zero_component() {
    for atol in [1e-20, 1e-30, 1e-300] {
        let cfg = OdeConfig::default().with_tolerances(1e-10, atol);
        // y = (cos t, -sin t) over 10 time units: a global error of the tolerance times the
        // steps (a few hundred) at most.
        let (t, y) = dopri5(|_, y| Ok([y[1], -y[0]]), 0.0, [1.0, 0.0], 10.0, &cfg, |_, _| Ok(false)).unwrap();
        assert_eq!(t, 10.0);
        assert_close!(y[0], 10f64.cos(), 1e-8, "atol {atol:e}: {y:?}");
        assert_close!(y[1], -10f64.sin(), 1e-8, "atol {atol:e}: {y:?}");
        // A crank of constant reduced inertia J = 0.5 from rest at 0.3 under a torque of 1:
        // phi = 0.3 + t^2, omega = 2 t (a quadratic, which the order-5 steps integrate to
        // rounding; the tolerance bounds the rest).
        let sc = SliderCrank::default();
        let model = crank_model(0.5).unwrap();
        let run = Simulation::new(&sc, &model)
            .start(0.3, 0.0)
            .guess(sc.guess_flat(&[0.3]))
            .drive(|_, _, _| 1.0)
            .config(RunConfig::default().with_ode(cfg))
            .run(1.0)
            .unwrap();
        assert_eq!(run.t_end, 1.0);
        assert_close!(run.end[0], 1.3, 1e-9, "atol {atol:e}: {:?}", run.end);
        assert_close!(run.end[1], 2.0, 1e-9, "atol {atol:e}: {:?}", run.end);
    }
}
