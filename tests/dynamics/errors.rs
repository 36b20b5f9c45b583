//! Bad input to the dynamics layer gives typed errors, never a panic or a silent NaN: bad
//! masses and inertias, indices out of range, torques on sliders, loads that return NaN, a
//! machine without inertia, and bad arguments; each converts into `kinloop::Error`.

use kinloop::Mechanism;
use kinloop::dynamics::{
    Body, Coord, DynamicsError, InverseCycle, MassModel, Rotation, RunConfig, Simulation, SpeedLaw,
};

kinloop::mechanism! {
    /// Slider-crank with the rod's midpoint as a point (columns 0 and 1).
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = pi, x = r + l;
        loop oabo: r @ phi == (x, 0) + l @ psi;
        point mid = r @ phi - 0.5 * l @ psi;
    }
}

type Model = MassModel<2, 1, 2>;

fn body(mass: f64, inertia: f64) -> Body {
    Body {
        name: "rod".into(),
        mass,
        com: [Coord::Output(0), Coord::Output(1)],
        inertia,
        rotation: Rotation::Unknown(0),
    }
}

#[test]
fn bad_masses_and_inertias() {
    for (mass, inertia, quantity) in [
        (-1.0, 0.1, "mass"),
        (f64::NAN, 0.1, "mass"),
        (f64::INFINITY, 0.1, "mass"),
        (1.0, -0.1, "moment of inertia"),
        (1.0, f64::NAN, "moment of inertia"),
    ] {
        let err = Model::new().with_body(body(mass, inertia)).err().unwrap();
        assert!(
            matches!(&err, DynamicsError::BadMass { body, quantity: q, .. } if body == "rod" && *q == quantity),
            "{err}"
        );
        // Into the crate's error, whole: the message kept, and the error itself.
        let e: kinloop::Error = err.into();
        assert!(e.to_string().contains("rod"), "{e}");
        let kinloop::Error::Dynamics(source) = &e else { panic!("{e:?}") };
        let back = source.downcast_ref::<DynamicsError>();
        assert!(
            matches!(back, Some(DynamicsError::BadMass { body, quantity: q, .. }) if body == "rod" && *q == quantity),
            "{e}"
        );
    }
}

#[test]
fn indices_out_of_range() {
    let cases: [(Body, &str, usize); 4] = [
        (Body { com: [Coord::Output(2), Coord::Output(1)], ..body(1.0, 0.1) }, "output column", 2),
        (Body { com: [Coord::Unknown(0), Coord::Unknown(5)], ..body(1.0, 0.1) }, "unknown", 5),
        (Body { rotation: Rotation::Unknown(2), ..body(1.0, 0.1) }, "unknown", 2),
        (Body { rotation: Rotation::Input(1), ..body(1.0, 0.1) }, "input", 1),
    ];
    for (b, what, index) in cases {
        let err = Model::new().with_body(b).err().unwrap();
        assert!(
            matches!(err, DynamicsError::IndexOutOfRange { owner: "body", what: w, index: i, .. } if w == what && i == index),
            "{err}"
        );
    }
    let err =
        Model::new().with_constant_force("push", [Coord::Output(9), Coord::Fixed(0.0)], [1.0, 0.0]).err().unwrap();
    assert!(
        matches!(&err, DynamicsError::IndexOutOfRange { owner: "load", name, index: 9, len: 2, .. } if name == "push")
    );
    let err = Model::new().with_constant_torque("twist", Rotation::Input(3), 1.0).err().unwrap();
    assert!(matches!(err, DynamicsError::IndexOutOfRange { owner: "load", what: "input", .. }));
    let err = Model::new()
        .with_body(Body { com: [Coord::Fixed(f64::NAN), Coord::Output(0)], ..body(1.0, 0.0) })
        .err()
        .unwrap();
    assert!(matches!(err, DynamicsError::BadValue { what: "fixed coordinate", .. }));
}

#[test]
fn bad_loads_and_gravity() {
    assert!(matches!(
        Model::new().with_constant_torque("twist", Rotation::None, 1.0),
        Err(DynamicsError::TorqueOnSlider { name }) if name == "twist"
    ));
    assert!(matches!(Model::new().with_gravity([0.0, f64::NAN]), Err(DynamicsError::BadValue { what: "gravity", .. })));
    assert!(matches!(
        Model::new().with_constant_force("push", [Coord::Output(0); 2], [f64::INFINITY, 0.0]),
        Err(DynamicsError::BadValue { what: "force", .. })
    ));
    // A force law returning NaN at some positions: caught where it happens.
    let m = SliderCrank::default();
    let model = Model::new()
        .with_body(body(1.0, 0.1))
        .and_then(|md| {
            md.with_force("gas", [Coord::Unknown(1), Coord::Fixed(0.0)], |k, _| [(k.q[1] - 3.5).sqrt(), 0.0])
        })
        .unwrap();
    let err = InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0))
        .samples(36)
        .guess(m.guess_flat(&[0.0]))
        .run()
        .unwrap_err();
    assert!(matches!(&err, DynamicsError::NonFiniteLoad { name, x, .. } if name == "gas" && x.len() == 1), "{err}");
    // The cycle names the input the mass model saw only the value of.
    assert!(err.to_string().starts_with("the load `gas` is not finite (NaN) at phi = "), "{err}");
}

#[test]
fn bad_arguments_and_a_machine_without_inertia() {
    let m = SliderCrank::default();
    let model = Model::new().with_body(body(1.0, 0.1)).unwrap();
    let g = m.guess_flat(&[0.0]);
    assert!(matches!(
        InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0)).samples(3).guess(g).run(),
        Err(DynamicsError::BadValue { .. })
    ));
    let nan = |_: f64| (f64::NAN, 0.0);
    assert!(matches!(
        InverseCycle::new(&m, &model, SpeedLaw::Varying(&nan)).samples(36).guess(g).run(),
        Err(DynamicsError::BadValue { what: "speed law", .. })
    ));
    let cycle = InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0)).samples(36).guess(g).run().unwrap();
    // Below MIN_DELTA the speeds' fluctuation nears their rounding: the exact flywheel would be
    // noise (at 1e-300 it came out 13 orders of magnitude below the energy method's).
    for delta in [0.0, -0.1, f64::NAN, 2.5, 1e-300, 0.99 * kinloop::dynamics::MIN_DELTA] {
        let e = cycle.flywheel(delta).unwrap_err();
        assert!(matches!(e, DynamicsError::BadValue { .. }) && e.to_string().contains("1e-6"), "{delta}: {e}");
    }
    assert!(cycle.flywheel(kinloop::dynamics::MIN_DELTA).is_ok());
    let run = |model: &Model, cfg: &RunConfig, start: [f64; 2], t_end: f64| {
        Simulation::new(&m, model).start(start[0], start[1]).guess(g).drive(|_, _, _| 1.0).config(*cfg).run(t_end)
    };
    let cfg = RunConfig::default();
    assert!(matches!(run(&model, &cfg.with_flywheel(-1.0), [0.0, 1.0], 1.0), Err(DynamicsError::BadValue { .. })));
    assert!(matches!(run(&model, &cfg, [f64::NAN, 1.0], 1.0), Err(DynamicsError::BadValue { .. })));
    assert!(matches!(run(&model, &cfg, [0.0, 1.0], -1.0), Err(DynamicsError::BadValue { what: "end time", .. })));
    let bad_tol = cfg.with_ode(cfg.ode.with_tolerances(0.0, cfg.ode.atol));
    assert!(matches!(run(&model, &bad_tol, [0.0, 1.0], 1.0), Err(DynamicsError::BadValue { .. })));
    // A relative tolerance within rounding, with an absolute one as small, no step can meet: the
    // run stopped at its start as a singular motion ("is this a limit position?") or as a state
    // too large to change ("start from a smaller value"). It is refused as a bad value, and one
    // just above the bound runs.
    for rtol in [1e-300, 1e-20, kinloop::dynamics::MIN_RTOL] {
        let tiny = cfg.with_ode(cfg.ode.with_tolerances(rtol, 1e-300));
        let err = run(&model, &tiny, [0.0, 1.0], 1.0).unwrap_err();
        assert!(matches!(err, DynamicsError::BadValue { what: "relative tolerance", .. }), "{rtol:e}: {err}");
        assert!(err.to_string().contains("2.2e-15"), "{rtol:e}: {err}");
    }
    let fine = cfg.with_ode(cfg.ode.with_tolerances(1.01 * kinloop::dynamics::MIN_RTOL, 1e-300));
    assert!(run(&model, &fine, [0.0, 1.0], 0.1).is_ok());
    // No mass at all: the reduced inertia is zero, the motion undefined.
    let empty = Model::new();
    let err = run(&empty, &cfg, [0.0, 1.0], 1.0).unwrap_err();
    assert!(matches!(err, DynamicsError::SingularMass { .. }), "{err}");
    assert!(err.to_string().starts_with("the mass matrix is not positive definite at phi = 0 (pivot "), "{err}");
    // A drive that is not finite.
    let err = Simulation::new(&m, &model)
        .start(0.0, 1.0)
        .guess(g)
        .drive(|_, _, _| f64::NAN)
        .config(cfg)
        .run(1.0)
        .unwrap_err();
    assert!(matches!(&err, DynamicsError::NonFiniteLoad { name, .. } if name == "drive"));
    assert_eq!(err.to_string(), "the load `drive` is not finite (NaN) at phi = 0");
    // Too few steps allowed.
    let short = cfg.with_ode(cfg.ode.with_max_steps(3));
    assert!(matches!(run(&model, &short, [0.0, 1.0], 100.0), Err(DynamicsError::TooManySteps { steps: 3, .. })));
}
