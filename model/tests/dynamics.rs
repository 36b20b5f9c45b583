//! The dynamics of run-time models: the declared bodies, loads and gravity evaluated at run
//! time against the compiled mechanism's `mass_model` (the same declarations, compiled by the
//! macro), and against closed forms.
//!
//! The compiled reference is independent of the tape: straight-line Rust the macro emitted for
//! the kinematics, the masses and the load laws. Both evaluate the same plan with the same
//! operations, so the values agree to a few roundings; the tolerance is 1e-14 of each
//! quantity's largest magnitude over the cycle (a torque crosses zero: a relative difference at
//! each point would measure the rounding of the larger terms against a vanishing sum).

use kinloop::Mechanism;
use kinloop::NewtonConfig;
use kinloop::dynamics::{
    Cycle, CyclePoint, DenseStep, DynamicsBuf, DynamicsError, InverseCycle, OdeConfig, RunConfig, Simulation, SpeedLaw,
    Trajectory, turn_states,
};
use kinloop_fixtures as fx;
use kinloop_model::Model;
use kinloop_runtime::Error;
use kinloop_runtime::SweepConfig;
use kinloop_runtime::dims::Heap;
use std::f64::consts::TAU;

/// Agreement demanded of the run-time dynamics with the compiled, of each quantity's largest
/// magnitude.
const REL: f64 = 1e-14;

/// The largest difference of `a` and `b`, relative to the largest magnitude of either.
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    a.iter().zip(b).map(|(x, y)| (x - y).abs() / scale).fold(0.0, f64::max)
}

/// The columns of a cycle: angle, speed, acceleration, inertia, its slope, load, torque, shaking.
fn columns(c: &Cycle) -> Vec<(&'static str, Vec<f64>)> {
    let col = |f: fn(&CyclePoint) -> f64| c.points.iter().map(f).collect::<Vec<f64>>();
    vec![
        ("phi", col(|p| p.phi)),
        ("omega", col(|p| p.omega)),
        ("eps", col(|p| p.eps)),
        ("inertia", col(|p| p.inertia)),
        ("inertia slope", col(|p| p.inertia_slope)),
        ("load", col(|p| p.load)),
        ("torque", col(|p| p.torque)),
        ("shaking x", col(|p| p.shaking.force[0])),
        ("shaking y", col(|p| p.shaking.force[1])),
        ("shaking moment", col(|p| p.shaking.moment)),
    ]
}

/// Compares two cycles column by column; returns the largest relative difference.
fn cycles_agree(compiled: &Cycle, run_time: &Cycle) -> f64 {
    assert_eq!(compiled.points.len(), run_time.points.len());
    let mut worst = 0.0f64;
    for ((name, c), (_, r)) in columns(compiled).into_iter().zip(columns(run_time)) {
        let d = rel_diff(&c, &r);
        assert!(d <= REL, "{name}: relative difference {d:e}");
        worst = worst.max(d);
    }
    worst
}

#[test]
fn the_engine_s_inverse_cycle_equals_the_compiled_one() {
    let engine = fx::EngineMachine::default();
    let mass = engine.mass_model().unwrap();
    let mut model = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).unwrap();
    assert!(model.has_dynamics());
    let about = [0.01, -0.02];
    let omega = |phi: f64| (150.0 * (1.0 + 0.1 * phi.sin()), 15.0 * phi.cos());
    for law in [SpeedLaw::Constant(150.0), SpeedLaw::Varying(&omega)] {
        let compiled = InverseCycle::new(&engine, &mass, law).samples(360).start(0.3).about(about).run().unwrap();
        let run_time = model.inverse_cycle(law).samples(360).start(0.3).about(about).run().unwrap();
        let worst = cycles_agree(&compiled, &run_time);
        eprintln!("engine cycle: largest relative difference {worst:e}");
        // Every quantity is exercised: the loads and the shaking do not vanish.
        assert!(compiled.points.iter().all(|p| p.load != 0.0 && p.shaking.moment != 0.0));
        let (fc, fr) = (compiled.flywheel(0.02).unwrap(), run_time.flywheel(0.02).unwrap());
        let pairs = [
            (fc.mean_torque, fr.mean_torque),
            (fc.energy_swing, fr.energy_swing),
            (fc.total_inertia, fr.total_inertia),
            (fc.mechanism_inertia, fr.mechanism_inertia),
            (fc.flywheel, fr.flywheel),
            (fc.exact, fr.exact),
            (fc.start_speed, fr.start_speed),
        ];
        for (c, r) in pairs {
            assert!((c - r).abs() <= REL * c.abs().max(r.abs()), "flywheel {fc:?} against {fr:?}");
        }
        let (hc, hr) = (compiled.torque_harmonics(4).unwrap(), run_time.torque_harmonics(4).unwrap());
        let scale = hc.a.iter().chain(&hc.b).fold(hc.a0.abs(), |m, v| m.max(v.abs()));
        for (c, r) in hc.a.iter().chain(&hc.b).zip(hr.a.iter().chain(&hr.b)) {
            assert!((c - r).abs() <= REL * scale, "harmonics {hc:?} against {hr:?}");
        }
    }
}

#[test]
fn the_five_bar_s_mass_matrix_and_forces_equal_the_compiled_ones() {
    let five = fx::FiveBarMachine::default();
    let mass = five.mass_model().unwrap();
    let mut model = Model::read("five_bar.kl", fx::FIVE_BAR_MACHINE_TEXT).unwrap();
    let cfg = NewtonConfig::default();
    let (w, eps) = ([3.0, -2.0], [1.0, 0.5]);
    let mut compared = 0;
    for k in 0..24 {
        let x = [0.9 + 0.05 * k as f64, 2.0 - 0.03 * k as f64];
        let Ok(c) = five.kinematics_flat(&x, &five.guess_flat(&x), &cfg) else { continue };
        let r = model.kinematics(&x, &five.guess_flat(&x), &cfg).unwrap().clone();
        let (dc, dr) = (mass.dynamics(&c, &w).unwrap(), model.dynamics(&r, &w).unwrap());
        assert!(rel_diff(dc.mass.as_flattened(), &dr.mass) <= REL, "{dc:?} against {dr:?}");
        assert!(rel_diff(dc.gamma.as_flattened().as_flattened(), &dr.gamma) <= REL, "{dc:?} against {dr:?}");
        assert!(rel_diff(&dc.forces, &dr.forces) <= REL, "{dc:?} against {dr:?}");
        let (sc, sr) =
            (mass.shaking(&c, &w, &eps, [0.5, 0.1]).unwrap(), model.shaking(&r, &w, &eps, [0.5, 0.1]).unwrap());
        let flat = |s: kinloop::dynamics::Shaking| [s.force[0], s.force[1], s.moment];
        assert!(rel_diff(&flat(sc), &flat(sr)) <= REL, "{sc:?} against {sr:?}");
        let mut tau = [0.0; 2];
        dr.checked_drive_into(&x, &w, &eps, &mut tau).unwrap();
        let want = dc.checked_drive(&x, &w, &eps).unwrap();
        assert!(rel_diff(&want, &tau) <= REL, "{want:?} against {tau:?}");
        // The mass matrix is symmetric (to rounding: `(m v_i) v_j` and `(m v_j) v_i` round
        // differently) and positive definite.
        assert!((dr.mass[1] - dr.mass[2]).abs() <= 1e-15 * dr.mass[0].max(dr.mass[3]), "{dr:?}");
        assert!(dr.mass[0] > 0.0 && dr.mass[0] * dr.mass[3] > dr.mass[1] * dr.mass[2]);
        compared += 1;
    }
    assert!(compared >= 20, "only {compared} states assemble");
}

/// A centred slider-crank (crank `r`, rod `l`, piston at `x` on the X axis): the piston's
/// position and its first two derivatives in the crank angle, in closed form.
fn piston(r: f64, l: f64, phi: f64) -> (f64, f64, f64) {
    let (s, c) = phi.sin_cos();
    let root = (l * l - r * r * s * s).sqrt();
    let x = r * c + root;
    let x1 = -r * s - r * r * s * c / root;
    let x2 = -r * c - r * r * (c * c - s * s) / root - r.powi(4) * s * s * c * c / root.powi(3);
    (x, x1, x2)
}

const CENTRED: &str = "pub struct Centred {
    params r = 0.05, l = 0.2, m_c = 1.2, j_c = 0.004, m_p = 0.5, f = 300.0;
    input phi;
    unknowns beta = 0, x = 0.25;
    loop abc: r @ phi + l @ beta == (x, 0);
    point pin = r @ phi;
    body crank: mass m_c, com pin, inertia j_c, turns phi;
    body piston: mass m_p, com (x, 0);
    force gas at (x, 0) = (-f, 0);
}";

/// The driving torque, reduced inertia and shaking force of a slider-crank whose rod is
/// massless, from the closed form of the piston's motion: `J = j_c + m_c r^2 + m_p x'^2`,
/// `J' = 2 m_p x' x''`, `Q = -f x'`, the torque `J eps + J' omega^2 / 2 - Q`, the shaking force
/// `m_c r (omega^2 cos + eps sin, omega^2 sin - eps cos) - m_p (x' eps + x'' omega^2, 0)`.
#[test]
fn a_slider_crank_s_torque_and_shaking_force_match_the_closed_form() {
    let (r, l, m_c, j_c, m_p, f) = (0.05, 0.2, 1.2, 0.004, 0.5, 300.0);
    let mut model = Model::read("centred.kl", CENTRED).unwrap();
    let speed = |phi: f64| (120.0 + 20.0 * phi.sin(), 20.0 * phi.cos());
    let cycle = model.inverse_cycle(SpeedLaw::Varying(&speed)).samples(180).run().unwrap();
    let mut want = vec![Vec::new(); 5];
    let mut got = vec![Vec::new(); 5];
    for p in &cycle.points {
        let (_, x1, x2) = piston(r, l, p.phi);
        let (w, eps) = (p.omega, p.eps);
        let j = j_c + m_c * r * r + m_p * x1 * x1;
        let torque = j * eps + m_p * x1 * x2 * w * w + f * x1;
        let (s, c) = p.phi.sin_cos();
        let fx = m_c * r * (w * w * c + eps * s) - m_p * (x1 * eps + x2 * w * w);
        let fy = m_c * r * (w * w * s - eps * c);
        for (v, value) in want.iter_mut().zip([j, 2.0 * m_p * x1 * x2, torque, fx, fy]) {
            v.push(value);
        }
        for (v, value) in
            got.iter_mut().zip([p.inertia, p.inertia_slope, p.torque, p.shaking.force[0], p.shaking.force[1]])
        {
            v.push(value);
        }
    }
    // The closed forms round differently from the analogs (a square root and its cube, about
    // ten operations each): a few units of rounding of the largest magnitude (measured: below
    // 5e-16); 1e-14 leaves room for a libm of other roundings.
    for (name, (w, g)) in
        ["inertia", "inertia slope", "torque", "shaking x", "shaking y"].iter().zip(want.iter().zip(&got))
    {
        let d = rel_diff(w, g);
        eprintln!("slider-crank {name}: relative difference from the closed form {d:e}");
        assert!(d < 1e-14, "{name}: {d:e}");
    }
}

/// The centred slider-crank of [`CENTRED`] with a flywheel geared to the crank at twice its
/// speed, the other way round: its angle `g`, set by an `eq` to `-2 * phi`, is an angle a body
/// turns with and a torque acts on, at run time as in `mechanism!`.
const GEARED: &str = "pub struct Geared {
    params r = 0.05, l = 0.2, m_c = 1.2, j_c = 0.004, m_p = 0.5, f = 300.0, j_g = 0.003, k = 0.7;
    input phi;
    unknowns beta = 0, x = 0.25, g = 0;
    loop abc: r @ phi + l @ beta == (x, 0);
    eq gear: g == -2 * phi;
    point pin = r @ phi;
    body crank: mass m_c, com pin, inertia j_c, turns phi;
    body piston: mass m_p, com (x, 0);
    body flywheel: mass 0, com (0, 0), inertia j_g, turns g;
    force gas at (x, 0) = (-f, 0);
    torque push on g = -k;
}";

/// The geared flywheel adds `4 j_g` to the reduced inertia, nothing to its slope, and
/// `4 j_g eps - 2 k` to the driving torque (its torque `-k` drives the crank by `2 k` through
/// the ratio -2): the run-time reader takes `g` for the angle the macro does. Both were
/// refused as "not an angle".
#[test]
fn a_flywheel_turning_with_an_angle_an_eq_sets_adds_its_inertia_by_the_ratio() {
    let (j_g, k) = (0.003, 0.7);
    let mut geared = Model::read("geared.kl", GEARED).unwrap();
    let mut centred = Model::read("centred.kl", CENTRED).unwrap();
    let speed = |phi: f64| (120.0 + 20.0 * phi.sin(), 20.0 * phi.cos());
    let a = geared.inverse_cycle(SpeedLaw::Varying(&speed)).samples(180).run().unwrap();
    let b = centred.inverse_cycle(SpeedLaw::Varying(&speed)).samples(180).run().unwrap();
    assert_eq!(a.points.len(), b.points.len());
    let mut want = vec![Vec::new(); 3];
    let mut got = vec![Vec::new(); 3];
    for (p, q) in a.points.iter().zip(&b.points) {
        let values = [q.inertia + 4.0 * j_g, q.inertia_slope, q.torque + 4.0 * j_g * q.eps - 2.0 * k];
        for (v, value) in want.iter_mut().zip(values) {
            v.push(value);
        }
        for (v, value) in got.iter_mut().zip([p.inertia, p.inertia_slope, p.torque]) {
            v.push(value);
        }
    }
    // The same loop solved alike, the gear's analogs exact (-2 and 0): a few roundings of each
    // quantity's largest magnitude.
    for (name, (w, g)) in ["inertia", "inertia slope", "torque"].iter().zip(want.iter().zip(&got)) {
        let d = rel_diff(w, g);
        assert!(d < 1e-12, "{name}: {d:e}");
    }
}

#[test]
fn bad_values_and_missing_items_are_typed_errors() {
    let mut model = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).unwrap();
    assert!(model.set_param("m_rod", -2.0));
    match model.mass_model() {
        Err(Error::Dynamics(source)) => {
            let e = source.downcast_ref::<DynamicsError>().expect("a dynamics error");
            assert!(matches!(e, DynamicsError::BadMass { body, quantity: "mass", .. } if body == "rod"), "{e:?}");
        }
        other => panic!("{other:?}"),
    }
    let mut plain = Model::read(
        "four_bar.kl",
        "pub struct FourBar {
            params a = 1, b = 3, c = 2.5, d = 3.2;
            input phi;
            unknowns psi = 0.6, theta = 1.9;
            loop abcd: a @ phi + b @ psi == (d, 0) + c @ theta;
        }",
    )
    .unwrap();
    assert!(!plain.has_dynamics());
    let e = plain.inverse_cycle(SpeedLaw::Constant(1.0)).run().unwrap_err();
    assert!(matches!(&e, Error::InvalidArgument(m) if m.contains("declares no bodies")), "{e}");
    // A load that is not finite names the load.
    let mut engine = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).unwrap();
    engine.set_param("p0", f64::INFINITY);
    let e = engine.inverse_cycle(SpeedLaw::Constant(1.0)).run().unwrap_err();
    assert!(e.to_string().contains("gas"), "{e}");
    // And where: by the input's name, as the compiled cycle says it.
    assert!(e.to_string().contains("is not finite (inf) at phi = "), "{e}");
    // A two-input model has no one-input cycle.
    let mut five = Model::read("five_bar.kl", fx::FIVE_BAR_MACHINE_TEXT).unwrap();
    let e = five.inverse_cycle(SpeedLaw::Constant(1.0)).guess(&[1.2, 2.0]).run().unwrap_err();
    assert!(e.to_string().contains("1 expected"), "{e}");
}

/// The gallery's Stirling engine (the rhombic drive's five bodies and its Schmidt-type gas
/// force, an expression of both sliders through `let` bindings) with gas: its inverse cycle at
/// a varying speed, run time against compiled.
/// The run-time cycle evaluates each state as the sweep makes it (the loads computed on the
/// model the sweep's kernel lends between two of its steps) and keeps none: its points are, bit
/// for bit, those of the turn's states kept and evaluated after the sweep.
#[test]
fn the_engine_s_streamed_cycle_is_the_cycle_of_its_kept_states() {
    let mut model = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).unwrap();
    let omega = |phi: f64| (150.0 * (1.0 + 0.1 * phi.sin()), 15.0 * phi.cos());
    let law = SpeedLaw::Varying(&omega);
    let about = [0.01, -0.02];
    let streamed = model.inverse_cycle(law).samples(120).start(0.3).about(about).run().unwrap();
    let mass = model.mass_model().unwrap();
    let mut guess = vec![0.0; model.unknowns().len()];
    model.guess(&[0.3], &mut guess).unwrap();
    let kernel = model.kernel(SweepConfig::default()).unwrap();
    let states = turn_states(kernel, 0.3, 120, Heap(guess.into())).unwrap();
    let mut d = DynamicsBuf::zeros(1);
    let kept = Cycle::over_states(&states, law, |k, omega, eps| {
        let loads = model.load_values(k).unwrap();
        mass.dynamics_into(k, &[omega], loads, &mut d)?;
        let shaking = mass.shaking(k, &[omega], &[eps], about)?;
        CyclePoint::of(k.x[0], omega, eps, &d.mass, &d.gamma, &d.forces, shaking)
    })
    .unwrap();
    assert!(streamed.points.iter().all(|p| p.load != 0.0 && p.shaking.moment != 0.0));
    let bits = |c: &Cycle| columns(c).into_iter().flat_map(|(_, v)| v).map(f64::to_bits).collect::<Vec<u64>>();
    assert_eq!(bits(&streamed), bits(&kept));
}

#[test]
fn the_stirling_engine_s_inverse_cycle_equals_the_compiled_one() {
    let gas = [
        ("area", 0.2),
        ("t_hot", 3.0),
        ("t_cold", 1.0),
        ("dead", 1.0),
        ("x_c_min", -4.5),
        ("x_f_max", 5.0),
        ("x_f_min", 2.0),
        ("mass_r", 2.0),
        ("buffer", 0.4),
    ];
    let mut engine = fx::StirlingEngine::default();
    let mut model = Model::read("stirling.kl", fx::STIRLING_ENGINE_TEXT).unwrap();
    for (name, value) in gas {
        let k = fx::StirlingEngine::PARAMS.iter().position(|p| *p == name).unwrap();
        let mut values = engine.param_values();
        values[k] = value;
        engine = fx::StirlingEngine::from_param_values(values);
        assert!(model.set_param(name, value));
    }
    let mass = engine.mass_model().unwrap();
    let speed = |phi: f64| (20.0 + 2.0 * (2.0 * phi).cos(), -4.0 * (2.0 * phi).sin());
    let law = SpeedLaw::Varying(&speed);
    let about = [0.0, engine.e_p];
    let compiled = InverseCycle::new(&engine, &mass, law).samples(240).about(about).run().unwrap();
    let run_time = model.inverse_cycle(law).samples(240).about(about).run().unwrap();
    assert!(compiled.points.iter().any(|p| p.load.abs() > 0.1), "the gas force acts");
    let worst = cycles_agree(&compiled, &run_time);
    eprintln!("Stirling engine cycle: largest relative difference {worst:e}");
}

// ---------------------------------------------------------------------------------------------
// Forward simulation

/// The largest difference of two trajectories' states at the ends of their steps and at three
/// points inside each (the dense output), relative to the largest magnitude of each of `phi`
/// and `omega`; the steps must be the same in number and in time.
fn trajectories_differ(c: &Trajectory, r: &Trajectory) -> f64 {
    assert_eq!(c.steps.len(), r.steps.len(), "the same number of steps");
    let (mut a, mut b) = ([Vec::new(), Vec::new()], [Vec::new(), Vec::new()]);
    for (sc, sr) in c.steps.iter().zip(&r.steps) {
        assert!(rel_diff(&[sc.t0, sc.h], &[sr.t0, sr.h]) <= REL, "steps {sc:?} and {sr:?}");
        for k in 0..4 {
            let t = sc.t0 + sc.h * k as f64 / 4.0;
            for (i, (yc, yr)) in sc.at(t).into_iter().zip(sr.at(t)).enumerate() {
                a[i].push(yc);
                b[i].push(yr);
            }
        }
    }
    assert_eq!((c.t_end.to_bits(), c.end.map(f64::to_bits)), (r.t_end.to_bits(), r.end.map(f64::to_bits)));
    rel_diff(&a[0], &b[0]).max(rel_diff(&a[1], &b[1]))
}

/// The engine under a motor characteristic with a flywheel, from a given speed: the run-time
/// model's trajectory is the compiled mechanism's. Both integrate by the same code
/// (`simulate_of`) with the same right-hand side: the model's step computes the compiled
/// kinematics with the same operations in the same order (libm's sines in both: a point solve
/// takes them), its load expressions are the emitted closures' operations and its mass model's
/// formulas are the compiled one's. So every evaluation, every step size the controller
/// chooses and every state are the same to the last bit (measured: no difference at all);
/// the assertion allows 1e-14 of each quantity's magnitude, the bound the inverse cycle above
/// holds to, should a platform's libm round the two differently at a point.
#[test]
fn the_engine_s_simulation_equals_the_compiled_one() {
    let engine = fx::EngineMachine::default();
    let mass = engine.mass_model().unwrap();
    let mut model = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).unwrap();
    let motor = |_: f64, _: f64, omega: f64| 4.0 - 0.01 * omega;
    let cfg = RunConfig::default().with_flywheel(0.05).with_ode(OdeConfig::default().with_tolerances(1e-11, 1e-11));
    let stop = |_: f64, y: &[f64; 2]| y[0] > 6.0 * TAU;
    let compiled = Simulation::new(&engine, &mass).start(0.3, 150.0).drive(motor).config(cfg).stop_when(stop).run(5.0);
    let run_time = model.simulation().start(0.3, 150.0).drive(motor).config(cfg).stop_when(stop).run(5.0);
    let (compiled, run_time) = (compiled.unwrap(), run_time.unwrap());
    assert!(compiled.end[0] > 6.0 * TAU, "six turns: {:?}", compiled.end);
    let worst = trajectories_differ(&compiled, &run_time);
    eprintln!("engine simulation: {} steps, largest relative difference {worst:e}", compiled.steps.len());
    assert!(worst <= REL, "{worst:e}");
    // The same from an explicit guess, through the Stirling engine's gas force (an expression of
    // both sliders through `let` bindings) and its five bodies.
    let stirling = fx::StirlingEngine::default();
    let mut values = stirling.param_values();
    let mut model = Model::read("stirling.kl", fx::STIRLING_ENGINE_TEXT).unwrap();
    for (name, value) in [("area", 0.2), ("t_hot", 3.0), ("t_cold", 1.0), ("dead", 1.0), ("x_c_min", -4.5)]
        .into_iter()
        .chain([("x_f_max", 5.0), ("x_f_min", 2.0), ("mass_r", 2.0), ("buffer", 0.4)])
    {
        values[fx::StirlingEngine::PARAMS.iter().position(|p| *p == name).unwrap()] = value;
        assert!(model.set_param(name, value));
    }
    let stirling = fx::StirlingEngine::from_param_values(values);
    let mass = stirling.mass_model().unwrap();
    let guess = stirling.guess_flat(&[0.0]);
    let compiled = Simulation::new(&stirling, &mass).start(0.0, 20.0).guess(guess).run(1.0).unwrap();
    let run_time = model.simulation().start(0.0, 20.0).guess(&guess).run(1.0).unwrap();
    let worst = trajectories_differ(&compiled, &run_time);
    eprintln!("Stirling engine simulation: {} steps, largest relative difference {worst:e}", compiled.steps.len());
    assert!(worst <= REL, "{worst:e}");
}

/// Each step's start, size and dense output at five points (its ends and three inside), as
/// bits: equal only if the steps are the same to the last bit.
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

/// A run-time model's recorded run keeps room for no more steps than its budget allows, as the
/// compiled one's: 300 steps of a run of 400 at most, where the doubling of its storage made
/// room for 512.
#[test]
fn the_engine_s_recorded_run_reserves_no_more_than_its_step_budget() {
    let mut model = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).unwrap();
    let cfg = RunConfig::default().with_flywheel(0.05).with_ode(OdeConfig::default().with_max_steps(400));
    let mut made = 0;
    let stop = move |_: f64, _: &[f64; 2]| {
        made += 1;
        made == 300
    };
    let run = model.simulation().start(0.3, 150.0).drive(|_, _, _| 4.0).config(cfg).stop_when(stop).run(50.0).unwrap();
    assert_eq!(run.steps.len(), 300);
    assert!(run.steps.capacity() <= 400, "room for {} steps of a budget of 400", run.steps.capacity());
}

/// A run-time model's streamed steps (`run_steps`) are its recorded trajectory's, bit for bit,
/// with the state at each one's end, and the compiled mechanism streams the same steps as it
/// records; the consumer ends the run where it says (with the stop predicate still asked), and
/// an error ends the streamed run as it ends the recorded one, where it happened.
#[test]
fn the_engine_s_streamed_steps_are_its_trajectory_s() {
    let engine = fx::EngineMachine::default();
    let mass = engine.mass_model().unwrap();
    let mut model = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).unwrap();
    let motor = |_: f64, _: f64, omega: f64| 4.0 - 0.01 * omega;
    let cfg = RunConfig::default().with_flywheel(0.05);
    let stop = |_: f64, y: &[f64; 2]| y[0] > 4.0 * TAU;
    let stored = model.simulation().start(0.3, 150.0).drive(motor).config(cfg).stop_when(stop).run(5.0).unwrap();
    assert!(stored.end[0] > 4.0 * TAU && stored.steps.len() > 100, "{} steps", stored.steps.len());
    let mut steps = Vec::new();
    let (t, end) = model
        .simulation()
        .start(0.3, 150.0)
        .drive(motor)
        .config(cfg)
        .stop_when(stop)
        .run_steps(5.0, |s, y| {
            steps.push((*s, *y));
            false
        })
        .unwrap();
    let (only, ends): (Vec<DenseStep<2>>, Vec<[f64; 2]>) = steps.iter().copied().unzip();
    assert_eq!(step_bits(&only), step_bits(&stored.steps));
    assert_eq!((t.to_bits(), end.map(f64::to_bits)), (stored.t_end.to_bits(), stored.end.map(f64::to_bits)));
    assert_eq!(ends.last().map(|y| y.map(f64::to_bits)), Some(end.map(f64::to_bits)));
    // The compiled mechanism streams what it records.
    let compiled = || Simulation::new(&engine, &mass).start(0.3, 150.0).drive(motor).config(cfg).stop_when(stop);
    let recorded = compiled().run(5.0).unwrap();
    let mut streamed = Vec::new();
    compiled()
        .run_steps(5.0, |s, _| {
            streamed.push(*s);
            false
        })
        .unwrap();
    assert_eq!(step_bits(&streamed), step_bits(&recorded.steps));
    // Ended by the consumer after 25 steps: the recorded run's first 25, the 25th's end reached.
    let mut count = 0;
    let (t, end) = model
        .simulation()
        .start(0.3, 150.0)
        .drive(motor)
        .config(cfg)
        .stop_when(stop)
        .run_steps(5.0, |_, _| {
            count += 1;
            count == 25
        })
        .unwrap();
    assert_eq!(count, 25);
    assert_eq!((t.to_bits(), end.map(f64::to_bits)), (stored.steps[24].t1().to_bits(), ends[24].map(f64::to_bits)));
    // A rocker driven into its limit position: the recorded run's error, with its time, after
    // the steps before it.
    let mut rocker = Model::read("rocker.kl", &FREE.replace("l = 0.2", "l = 0.03")).unwrap();
    let recorded = rocker.simulation().guess(&[0.0, 0.08]).start(0.0, 1.0).run(1.0).unwrap_err();
    let mut last = None;
    let e = rocker
        .simulation()
        .guess(&[0.0, 0.08])
        .start(0.0, 1.0)
        .run_steps(1.0, |s, _| {
            last = Some(s.t1());
            false
        })
        .unwrap_err();
    assert_eq!(e.to_string(), recorded.to_string());
    match dynamics_error(&e) {
        DynamicsError::Kinematics { t: Some(t), .. } => {
            let last = last.expect("steps before the failure");
            assert!(last <= *t && *t < 1.0, "the last step ends at {last}, the failure at {t}");
        }
        d => panic!("{d:?}"),
    }
}

const FREE: &str = "pub struct Free {
    params r = 0.05, l = 0.2, m_c = 1.2, j_c = 0.004, m_p = 0.5;
    input phi;
    unknowns beta = 0, x = 0.25;
    loop abc: r @ phi + l @ beta == (x, 0);
    point pin = r @ phi;
    body crank: mass m_c, com pin, inertia j_c, turns phi;
    body piston: mass m_p, com (x, 0);
}";

/// A free slider-crank (massless rod, no loads, no gravity) against its hand-derived reduced
/// inertia `J(phi) = j_c + m_c r^2 + m_p x'(phi)^2` (`x'` from the closed form of the piston's
/// motion): the kinetic energy `1/2 J omega^2` stays what it was at the start at every step, and
/// the time of a turn is the quadrature `T = int_0^2pi sqrt(J(phi) / 2E) dphi` (the energy
/// equation solved for `dt / dphi`; the trapezoidal rule converges geometrically on this smooth
/// periodic integrand).
#[test]
fn a_free_slider_crank_keeps_its_energy_and_turns_in_the_closed_form_time() {
    let (r, l, m_c, j_c, m_p) = (0.05, 0.2, 1.2, 0.004, 0.5);
    let inertia = |phi: f64| {
        let (_, x1, _) = piston(r, l, phi);
        j_c + m_c * r * r + m_p * x1 * x1
    };
    let mut model = Model::read("free.kl", FREE).unwrap();
    let omega0 = 30.0;
    let energy = 0.5 * inertia(0.0) * omega0 * omega0;
    let cfg = RunConfig::default().with_ode(OdeConfig::default().with_tolerances(1e-12, 1e-12));
    let run = model.simulation().start(0.0, omega0).config(cfg).stop_when(|_, y| y[0] > 2.2 * TAU).run(10.0).unwrap();
    let mut drift = 0.0f64;
    for s in &run.steps {
        let [phi, omega] = s.at(s.t1());
        drift = drift.max((0.5 * inertia(phi) * omega * omega - energy).abs() / energy);
    }
    // The integrator's tolerance 1e-12 per step over about four hundred steps (measured:
    // 1.2e-12).
    eprintln!("free slider-crank: {} steps, largest relative energy drift {drift:e}", run.steps.len());
    assert!(drift < 1e-10, "{drift:e}");
    // The time the input reaches 2 pi and 4 pi, by bisection on the dense output.
    let time_at = |angle: f64| {
        let (mut lo, mut hi) = (0.0, run.t_end);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if run.at(mid)[0] < angle { lo = mid } else { hi = mid }
        }
        0.5 * (lo + hi)
    };
    let samples = 4000;
    let period = (0..samples).map(|k| (inertia(TAU * k as f64 / samples as f64) / (2.0 * energy)).sqrt()).sum::<f64>()
        * TAU
        / samples as f64;
    for turns in [1.0, 2.0] {
        let t = time_at(turns * TAU);
        eprintln!("free slider-crank: {turns} turns in {t}, closed form {}", turns * period);
        // The integrator's global error, as the energy's (measured: 3e-13 of a turn's time).
        assert!((t - turns * period).abs() < 1e-10 * period, "{t} against {}", turns * period);
    }
}

/// A simulation's arguments that cannot be used are typed errors, never a panic.
#[test]
fn a_simulation_s_bad_arguments_are_typed_errors() {
    let mut engine = Model::read("engine.kl", fx::ENGINE_MACHINE_TEXT).unwrap();
    let e = engine.simulation().guess(&[0.0]).run(1.0).unwrap_err();
    assert!(matches!(&e, Error::InvalidArgument(m) if m.contains("2 expected")), "{e}");
    let e = engine.simulation().config(RunConfig::default().with_flywheel(-1.0)).run(1.0).unwrap_err();
    assert!(e.to_string().contains("flywheel"), "{e}");
    let e = engine.simulation().start(f64::NAN, 0.0).run(1.0).unwrap_err();
    assert!(
        matches!(dynamics_error(&e), DynamicsError::BadValue { what: "initial state", value, .. } if value.is_nan()),
        "{e}"
    );
    let e = engine.simulation().drive(|_, _, _| f64::NAN).run(1.0).unwrap_err();
    assert!(e.to_string().contains("drive"), "{e}");
    let mut five = Model::read("five_bar.kl", fx::FIVE_BAR_MACHINE_TEXT).unwrap();
    let e = five.simulation().guess(&[1.2, 2.0]).run(1.0).unwrap_err();
    assert!(e.to_string().contains("one-input"), "{e}");
    // Without a guess too: the size, not the declared guess asked at one input.
    let e = five.simulation().run(1.0).unwrap_err();
    let sizes = dynamics_error(&e);
    assert!(
        matches!(
            sizes,
            DynamicsError::SizeMismatch { what: "inputs of a one-input simulation", expected: 1, given: 2 }
        ),
        "{e}"
    );
    let mut plain = Model::read("free.kl", &FREE.replace("body", "// body")).unwrap();
    let e = plain.simulation().run(1.0).unwrap_err();
    assert!(matches!(&e, Error::InvalidArgument(m) if m.contains("declares no bodies")), "{e}");
    // A rocker driven into its limit position: the kinematic error with the model's name.
    let mut rocker = Model::read("rocker.kl", &FREE.replace("l = 0.2", "l = 0.03")).unwrap();
    let e = rocker.simulation().guess(&[0.0, 0.08]).start(0.0, 1.0).run(1.0).unwrap_err();
    eprintln!("rocker: {e}");
    assert!(e.to_string().contains("Free"), "{e}");
    // With the time it happened at, as the compiled simulation reports it.
    match dynamics_error(&e) {
        DynamicsError::Kinematics { t: Some(t), source } => {
            assert!(*t > 0.0 && *t < 1.0, "{t}");
            assert!(source.to_string().contains("Free"), "{source}");
            assert!(e.to_string().contains(&format!("at t = {t}")), "{e}");
        }
        d => panic!("{d:?}"),
    }
}

/// The dynamics error inside `e` (any other error fails the test).
fn dynamics_error(e: &Error) -> &DynamicsError {
    match e {
        Error::Dynamics(source) => source.downcast_ref::<DynamicsError>().expect("a dynamics error"),
        e => panic!("not a dynamics error: {e:?}"),
    }
}
