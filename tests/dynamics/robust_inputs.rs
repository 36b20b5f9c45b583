//! Hostile inputs to the dynamics of a machine declared with `mechanism!`: masses, speeds,
//! angles and settings at the ends of the f64 range, NaN and infinities. Every entry returns a
//! typed error or an `Ok` whose every number is finite; none panics.

use kinloop::Mechanism;
use kinloop::dynamics::{
    Coord, Cycle, CyclePoint, DynamicsError, InverseCycle, MassModel, OdeConfig, Rotation, RunConfig, Shaking,
    Simulation, SpeedLaw, dopri5,
};
use proptest::prelude::*;

kinloop::mechanism! {
    /// Slider-crank machine: crank `r` at the origin turning with `phi`, rod `l`, slider on
    /// the X axis; masses and moments of inertia as parameters, gravity along -Y.
    pub struct Machine {
        params r = 1.0, l = 3.0, m1 = 1.0, j1 = 0.1, m2 = 2.0, j2 = 0.5, m3 = 1.5, g = 9.81;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oabc: r @ phi == (x, 0) + l @ psi;
        point s1 = (0.5 * r) @ phi;
        point s2 = (x, 0) + (0.5 * l) @ psi;
        body crank: mass m1, com s1, inertia j1, turns phi;
        body rod: mass m2, com s2, inertia j2, turns psi;
        body slider: mass m3, com (x, 0);
        gravity (0, -g);
    }
}

type Model = MassModel<2, 1, 4>;

#[test]
fn masses_whose_sum_overflows_are_a_typed_error() {
    let m = Machine { m1: 1e308, m2: 1e308, ..Machine::default() };
    let err = m.mass_model().err().expect("the total mass overflows");
    assert!(matches!(err, DynamicsError::Overflow { what: "total mass", .. }), "{err}");
    // Each mass representable and their sum too, but m v^2 not: the dynamics say so.
    let m = Machine { m1: 1e308, m2: 0.0, m3: 0.0, j1: 0.0, ..Machine::default() };
    let model = m.mass_model().unwrap();
    assert!(model.total_mass().is_finite());
    let k = m.kinematics_flat(&[0.3], &m.guess_flat(&[0.3]), &Default::default()).unwrap();
    let err = model.dynamics(&k, &[1.0]).unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { .. }), "{err}");
    let err = InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0))
        .samples(16)
        .guess(m.guess_flat(&[0.0]))
        .run()
        .unwrap_err();
    assert!(matches!(err, DynamicsError::Overflow { .. }), "{err}");
}

#[test]
fn a_simulation_that_cannot_move_its_input_is_a_typed_error() {
    let m = Machine::default();
    let model = m.mass_model().unwrap();
    let run = |phi0: f64| {
        let guess = m.guess_flat(&[phi0]);
        Simulation::new(&m, &model).start(phi0, 10.0).guess(guess).run(1.0)
    };
    // At 1e300 rad the spacing of f64 numbers is about 1e284 rad: the input cannot move.
    let err = run(1e300).unwrap_err();
    let DynamicsError::CannotAdvance { component: 0, value, .. } = err else { panic!("{err}") };
    assert_eq!(value, 1e300);
    assert!(err.to_string().contains("start from a smaller value"), "{err}");
    // The same machine started at 1e300 modulo a turn runs.
    let ok = run(1e300 % std::f64::consts::TAU).unwrap();
    assert!(ok.end[0] > 1e300 % std::f64::consts::TAU + 5.0, "{:?}", ok.end);
    // An inverse cycle from such an angle could not tell its samples apart either.
    let err = InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0))
        .start(1e300)
        .samples(16)
        .guess(m.guess_flat(&[0.0]))
        .run();
    assert!(matches!(err, Err(DynamicsError::BadValue { what: "start angle", .. })), "{err:?}");
}

#[test]
fn too_many_harmonics_name_the_samples_not_a_kinematic_failure() {
    let m = Machine::default();
    let model = m.mass_model().unwrap();
    let cycle =
        InverseCycle::new(&m, &model, SpeedLaw::Constant(10.0)).samples(24).guess(m.guess_flat(&[0.0])).run().unwrap();
    let err = cycle.torque_harmonics(12).unwrap_err();
    assert_eq!(err, DynamicsError::TooManyHarmonics { harmonics: 12, samples: 24 });
    let text = err.to_string();
    assert!(text.contains("12 harmonics asked of 24 samples per period: they resolve at most 11"), "{text}");
    assert!(!text.contains("kinematics") && !text.contains("NaN"), "{text}");
    assert_eq!(cycle.torque_harmonics(11).unwrap().a.len(), 11);
    // A sample count beyond what an analysis takes is refused before anything is allocated
    // (2^40 grew the turn's states until the process was killed).
    for samples in [usize::MAX, usize::MAX / 8, 1 << 40, kinloop::analysis::MAX_SAMPLES + 1] {
        let err =
            InverseCycle::new(&m, &model, SpeedLaw::Constant(10.0)).samples(samples).guess(m.guess_flat(&[0.0])).run();
        assert!(matches!(err, Err(DynamicsError::BadValue { what: "samples", .. })), "{err:?}");
    }
}

/// A hostile number: NaN, infinities, zeros, the ends of the f64 range, or an ordinary one.
fn hostile() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(f64::MAX),
        Just(-f64::MAX),
        Just(f64::MIN_POSITIVE),
        Just(5e-324),
        Just(1e300),
        Just(-1e300),
        Just(1e-300),
        -10.0..10.0f64,
        any::<f64>(),
    ]
}

/// Mostly an ordinary number (so that models are built and cycles run, to be exercised
/// further), else a hostile one.
fn mostly(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    prop_oneof![4 => lo..hi, 1 => hostile()]
}

fn finite(values: impl IntoIterator<Item = f64>) -> bool {
    values.into_iter().all(f64::is_finite)
}

/// Runs every public dynamics entry on `m` with hostile settings; panics only on an `Ok`
/// holding a number that is not finite.
fn exercise(m: &Machine, model: &Model, v: &[f64; 6], samples: usize, harmonics: usize) {
    let [omega, phi0, about, delta, t_end, flywheel] = *v;
    // A coefficient of speed fluctuation is in (0, 2): mostly give one.
    let delta = 0.1 * delta;
    assert!(model.total_mass().is_finite());
    let guess = m.guess_flat(&[0.0]);
    let solved = m.kinematics_flat(&[phi0], &m.guess_flat(&[phi0]), &Default::default());
    if let Ok(k) = solved
        && let Ok(d) = model.dynamics(&k, &[omega])
    {
        let gamma = d.gamma.iter().flatten().flatten().copied();
        assert!(finite(d.mass.iter().flatten().copied().chain(gamma).chain(d.forces)), "{d:?}");
        if let Ok(tau) = d.checked_drive(&k.x, &[omega], &[delta]) {
            assert!(finite(tau), "{tau:?}");
        }
        if let Ok(eps) = d.accelerations(&k.x, &[omega], &[delta]) {
            assert!(finite(eps), "{eps:?}");
        }
        if let Ok(s) = model.shaking(&k, &[omega], &[delta], [about, -about]) {
            assert!(finite(s.force.into_iter().chain([s.moment])), "{s:?}");
        }
        if let Ok(c) = model.centre_of_mass(&k) {
            assert!(finite(c), "{c:?}");
        }
    }
    if let Ok(c) = InverseCycle::new(m, model, SpeedLaw::Constant(omega))
        .start(phi0)
        .samples(samples)
        .guess(guess)
        .about([about, -about])
        .run()
    {
        for p in &c.points {
            let s = p.shaking;
            let values = [p.phi, p.omega, p.eps, p.inertia, p.inertia_slope, p.load, p.torque, s.moment];
            assert!(finite(values.into_iter().chain(s.force)), "{p:?}");
        }
        assert!(c.mean_torque().is_finite());
        if let Ok(f) = c.torque_harmonics(harmonics) {
            assert!(finite(f.a.iter().chain(&f.b).copied().chain([f.a0])), "{f:?}");
        }
        if let Ok(all) = c.shaking_harmonics(harmonics) {
            assert!(all.iter().all(|f| finite(f.a.iter().chain(&f.b).copied().chain([f.a0]))), "{all:?}");
        }
        if let Ok(f) = c.flywheel(delta) {
            let values = [f.mean_torque, f.energy_swing, f.total_inertia, f.mechanism_inertia, f.flywheel];
            assert!(finite(values.into_iter().chain([f.exact, f.start_speed])), "{f:?}");
        }
    }
    let cfg = RunConfig::default()
        .with_flywheel(flywheel)
        .with_ode(OdeConfig::default().with_tolerances(1e-6, 1e-6).with_max_steps(400));
    let drive = move |_: f64, _: f64, _: f64| delta;
    let start_guess = m.guess_flat(&[phi0]);
    if let Ok(run) = Simulation::new(m, model).start(phi0, omega).guess(start_guess).drive(drive).config(cfg).run(t_end)
    {
        assert!(finite(run.end.into_iter().chain([run.t_end])), "{:?} at {}", run.end, run.t_end);
        for s in &run.steps {
            assert!(finite([s.t0, s.h]) && finite(s.at(s.t0 + 0.5 * s.h)), "{s:?}");
        }
        assert!(finite(run.at(0.5 * run.t_end)));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn hostile_dynamics_inputs_give_errors_or_finite_results(
        masses in proptest::array::uniform6(mostly(0.0, 10.0)),
        gravity in mostly(-20.0, 20.0),
        v in proptest::array::uniform6(mostly(0.0, 20.0)),
        samples in 4usize..24,
        harmonics in 0usize..12,
    ) {
        let [m1, j1, m2, j2, m3, r] = masses;
        let m = Machine { m1, j1, m2, j2, m3, g: gravity, r: r.abs().min(2.5), ..Machine::default() };
        // A model is refused (a typed error) or holds a finite total mass.
        if let Ok(model) = m.mass_model() {
            exercise(&m, &model, &v, samples, harmonics);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn hostile_integrations_cycles_and_loads_give_errors_or_finite_results(
        y0 in proptest::array::uniform2(hostile()),
        rate in hostile(),
        t_end in mostly(0.0, 5.0),
        tolerances in proptest::array::uniform3(mostly(1e-9, 1e-3)),
        cycle in proptest::collection::vec(proptest::array::uniform4(mostly(-5.0, 5.0)), 0..12),
        harmonics in 0usize..8,
        delta in mostly(0.0, 2.0),
        load in proptest::array::uniform2(hostile()),
    ) {
        // The integrator alone: y' = (y1, -rate y0), any start, tolerances and horizon.
        let cfg = OdeConfig::default()
            .with_tolerances(tolerances[0], tolerances[1])
            .with_h_max(tolerances[2])
            .with_max_steps(2000);
        let f = |_: f64, y: &[f64; 2]| Ok([y[1], -rate * y[0]]);
        let each = |s: &kinloop::dynamics::DenseStep<2>, y: &[f64; 2]| {
            assert!(finite([s.t0, s.h]) && finite(*y), "{s:?} {y:?}");
            Ok(false)
        };
        if let Ok((t, y)) = dopri5(f, 0.0, y0, t_end, &cfg, each) {
            prop_assert!(finite(y.into_iter().chain([t])), "{y:?} at {t}");
        }
        // A cycle made by hand, with any values.
        let n = cycle.len().max(1) as f64;
        let points: Vec<CyclePoint> = cycle
            .iter()
            .enumerate()
            .map(|(j, [torque, load, omega, inertia])| CyclePoint {
                phi: std::f64::consts::TAU * j as f64 / n,
                omega: *omega,
                eps: 0.0,
                inertia: *inertia,
                inertia_slope: 0.0,
                load: *load,
                torque: *torque,
                shaking: Shaking { force: [*torque, *load], moment: *omega },
            })
            .collect();
        let c = Cycle { points };
        if let Ok(f) = c.torque_harmonics(harmonics) {
            prop_assert!(finite(f.a.iter().chain(&f.b).copied().chain([f.a0])), "{f:?}");
        }
        if let Ok(all) = c.shaking_harmonics(harmonics) {
            prop_assert!(all.iter().all(|f| finite(f.a.iter().chain(&f.b).copied().chain([f.a0]))));
        }
        if let Ok(f) = c.flywheel(delta) {
            let values = [f.mean_torque, f.energy_swing, f.total_inertia, f.mechanism_inertia, f.flywheel];
            prop_assert!(finite(values.into_iter().chain([f.exact, f.start_speed])), "{f:?}");
        }
        // Constant loads of any size on a declared machine: refused when not finite, else a
        // typed error or finite forces.
        let m = Machine::default();
        let model = m.mass_model().unwrap();
        let at = [Coord::Unknown(1), Coord::Fixed(0.0)];
        if let Ok(model) = model.with_constant_force("push", at, load).and_then(|m| m.with_constant_torque("twist", Rotation::Input(0), load[0])) {
            let k = m.kinematics_flat(&[0.4], &m.guess_flat(&[0.4]), &Default::default()).unwrap();
            if let Ok(d) = model.dynamics(&k, &[1.0]) {
                prop_assert!(finite(d.forces), "{:?}", d.forces);
            }
        }
    }
}

/// Between the start angles whose turns sweep and those refused, no kinematic failure: the
/// cycle refuses every start angle at which the sweep's steps would round (doubles more than a
/// millionth of the samples' spacing apart) as a bad start angle, before sweeping.
#[test]
fn a_large_start_angle_runs_or_is_a_bad_value_never_a_kinematic_failure() {
    let m = Machine::default();
    let model = m.mass_model().unwrap();
    let (mut ran, mut refused) = (0, 0);
    for e in [6.0, 8.0, 9.0, 10.0, 12.0, 13.0, 14.0, 15.0, 15.5, 16.0] {
        for samples in [8, 360, 10_000] {
            let phi0 = 10f64.powf(e);
            let cycle = InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0))
                .start(phi0)
                .samples(samples)
                .guess(m.guess_flat(&[phi0]))
                .run();
            match cycle {
                Ok(c) => {
                    ran += 1;
                    assert!(c.points.iter().all(|p| p.torque.is_finite()), "{phi0} {samples}");
                }
                Err(DynamicsError::BadValue { what: "start angle", .. }) => refused += 1,
                Err(e) => panic!("start {phi0}, {samples} samples: {e}"),
            }
        }
    }
    // The bound falls between 1e6 (every count runs) and 1e16 (none does).
    assert!(ran >= 3 && refused >= 3, "{ran} ran, {refused} refused");
}
