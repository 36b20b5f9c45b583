//! Machine dynamics declared in `mechanism!` (`body`, `force`, `torque`, `gravity`), checked
//! against references that use no analog of kinloop:
//!
//! * a slider-crank engine whose positions have a closed form: the reduced moment of inertia,
//!   its slope and the generalised force of a gas force, a friction torque and gravity, from
//!   Richardson-extrapolated central differences of the closed-form positions;
//! * the rhombic drive of the fixtures: the declared mass model against the same model built by
//!   hand, body by body;
//! * the engine's rod turning with an angle that an `eq` sets through `atan2`, its dynamics
//!   those of the engine whose rod turns with a loop angle; a flywheel geared to its crank,
//!   turning with an angle an `eq` sets to `-2 * phi`, adding its inertia and torque by the ratio;
//! * bad parameter values at run time: typed errors.

use crate::fixtures::{RhombicDrive, derivative};
use kinloop::dynamics::{Body, Coord, DynamicsError, MassModel, Rotation};
use kinloop::{Mechanism, NewtonConfig};

kinloop::mechanism! {
    /// Slider-crank engine: crank `r` about the origin, rod `l` to the piston on the X axis;
    /// the rod's centre of mass `l_s` from the crank pin.
    pub struct Engine {
        params r = 0.05, l = 0.2, l_s = 0.06, m_rod = 2.0, j_rod = 0.01, m_p = 0.5, j_crank = 0.02,
               area = 3e-3, p0 = 1e5, c = 0.4, g = 9.81;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        point s2 = r @ phi + l_s @ beta;
        body crank: mass 0, com (0, 0), inertia j_crank, turns phi;
        body rod: mass m_rod, com s2, inertia j_rod, turns beta;
        body piston: mass m_p, com (x, 0);
        // Gas pressure falling as the piston moves out (isothermal), on the piston crown.
        force gas at (x, 0) = (p0 * area * (r + l) / x, 0);
        torque friction on beta = -c * sin(beta);
        gravity (0, -g);
    }
}

/// Closed-form positions `[beta, x, s2x, s2y]` of the engine (`r sin phi + l sin beta = 0`).
fn positions(e: &Engine, phi: f64) -> Vec<f64> {
    let beta = (-e.r * phi.sin() / e.l).asin();
    let x = e.r * phi.cos() + e.l * beta.cos();
    vec![beta, x, e.r * phi.cos() + e.l_s * beta.cos(), e.r * phi.sin() + e.l_s * beta.sin()]
}

/// Reduced moment of inertia and generalised force from the closed-form positions.
fn reference(e: &Engine, phi: f64) -> (f64, f64) {
    let p = positions(e, phi);
    let v = derivative(|t| positions(e, t), phi, 1e-3);
    let (beta, x) = (p[0], p[1]);
    let j = e.j_crank + e.m_rod * (v[2] * v[2] + v[3] * v[3]) + e.j_rod * v[0] * v[0] + e.m_p * v[1] * v[1];
    let gas = e.p0 * e.area * (e.r + e.l) / x;
    let q = gas * v[1] - e.c * beta.sin() * v[0] - e.g * e.m_rod * v[3];
    (j, q)
}

#[test]
fn declared_engine_agrees_with_closed_form_positions() {
    let e = Engine::default();
    let model = e.mass_model().unwrap();
    let mut guess = e.guess_flat(&[0.0]);
    let (mut worst_j, mut worst_dj, mut worst_q): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for step in 0..72 {
        let phi = step as f64 * 5f64.to_radians();
        let k = e.kinematics_flat(&[phi], &guess, &NewtonConfig::default()).unwrap();
        guess = k.q;
        let d = model.dynamics(&k, &[30.0]).unwrap();
        let (j, q) = reference(&e, phi);
        let dj = derivative(|t| vec![reference(&e, t).0], phi, 1e-3)[0];
        worst_j = worst_j.max((d.reduced_inertia() - j).abs() / j);
        worst_dj = worst_dj.max((d.reduced_inertia_slope() - dj).abs() / j);
        worst_q = worst_q.max((d.forces[0] - q).abs() / (e.p0 * e.area * e.r));
    }
    eprintln!("relative errors: J {worst_j:e}, dJ/dphi {worst_dj:e}, Q {worst_q:e}");
    // Richardson-extrapolated central differences at h = 1e-3: truncation ~ h^4 = 1e-12 times
    // the fifth derivative (of the order of the value here), rounding ~ eps / h ~ 2e-13 for a
    // first difference and ~ eps / h^2 ~ 2e-10 for the slope (a difference of differences).
    assert!(worst_j < 1e-10, "J: {worst_j:e}");
    assert!(worst_dj < 1e-8, "dJ/dphi: {worst_dj:e}");
    assert!(worst_q < 1e-10, "Q: {worst_q:e}");
}

kinloop::mechanism! {
    /// The engine of [`Engine`] (no gravity, no gas) with the rod's angle set by an `eq` through
    /// `atan2`, not by a loop: `beta` is in no sine or cosine, and the rod still turns with it.
    pub struct EngineByAtan2 {
        params r = 0.05, l = 0.2, l_s = 0.06, m_rod = 2.0, j_rod = 0.01, m_p = 0.5, c = 0.4;
        input phi;
        unknowns beta = 0, x = 0.25;
        eq piston: x == r * cos(phi) + sqrt(l^2 - (r * sin(phi))^2);
        eq rod: beta == atan2(-r * sin(phi), x - r * cos(phi));
        point s2 = (r * cos(phi) + l_s / l * (x - r * cos(phi)), r * sin(phi) - l_s / l * r * sin(phi));
        body rod: mass m_rod, com s2, inertia j_rod, turns beta;
        body piston: mass m_p, com (x, 0);
        torque friction on beta = -c * beta;
    }
}

kinloop::mechanism! {
    /// [`EngineByAtan2`] with the rod's angle a loop angle.
    pub struct EngineByLoop {
        params r = 0.05, l = 0.2, l_s = 0.06, m_rod = 2.0, j_rod = 0.01, m_p = 0.5, c = 0.4;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        point s2 = r @ phi + l_s @ beta;
        body rod: mass m_rod, com s2, inertia j_rod, turns beta;
        body piston: mass m_p, com (x, 0);
        torque friction on beta = -c * beta;
    }
}

/// A rod that turns with an angle set by `eq beta == atan2(..)` (no loop angle) has the reduced
/// inertia, its slope and the generalised force of the same rod turning with a loop angle.
#[test]
fn a_body_turns_with_an_angle_an_equation_sets() {
    let (by_atan2, by_loop) = (EngineByAtan2::default(), EngineByLoop::default());
    let (model_atan2, model_loop) = (by_atan2.mass_model().unwrap(), by_loop.mass_model().unwrap());
    assert_eq!(model_atan2.bodies()[0].rotation, Rotation::Unknown(0));
    let (mut guess_atan2, mut guess_loop) = (by_atan2.guess_flat(&[0.0]), by_loop.guess_flat(&[0.0]));
    let mut worst: f64 = 0.0;
    for step in 0..36 {
        let phi = step as f64 * 10f64.to_radians();
        let k_atan2 = by_atan2.kinematics_flat(&[phi], &guess_atan2, &NewtonConfig::default()).unwrap();
        let k_loop = by_loop.kinematics_flat(&[phi], &guess_loop, &NewtonConfig::default()).unwrap();
        (guess_atan2, guess_loop) = (k_atan2.q, k_loop.q);
        let a = model_atan2.dynamics(&k_atan2, &[30.0]).unwrap();
        let b = model_loop.dynamics(&k_loop, &[30.0]).unwrap();
        // The rod's own rotation is a sizeable part of J: without it the two would differ by
        // j_rod (dbeta/dphi)^2, up to j_rod (r / l)^2 = 6.25e-4 against J = 3.1e-3 to 6.4e-3.
        let j = b.reduced_inertia();
        worst = worst
            .max((a.reduced_inertia() - j).abs() / j)
            .max((a.reduced_inertia_slope() - b.reduced_inertia_slope()).abs() / j)
            .max((a.forces[0] - b.forces[0]).abs() / (by_loop.c * std::f64::consts::PI));
    }
    // The same positions and analogs from two sets of equations, each solved to rounding: a
    // few ulps (4e-16 measured), far below the rod's share.
    assert!(worst < 1e-12, "relative difference {worst:e}");
}

kinloop::mechanism! {
    /// [`EngineByLoop`] with a flywheel geared to the crank at twice its speed, the other way
    /// round: its angle `g` is set by an `eq` to an expression of the crank's angle, an angle
    /// in no sine or cosine and set by no inverse trigonometric function, and the flywheel
    /// turns with it, pushed by a constant torque.
    pub struct EngineWithGear {
        params r = 0.05, l = 0.2, l_s = 0.06, m_rod = 2.0, j_rod = 0.01, m_p = 0.5, c = 0.4, j_g = 0.003, k = 0.7;
        input phi;
        unknowns beta = 0, x = 0.25, g = 0;
        loop abc: r @ phi + l @ beta == (x, 0);
        eq gear: g == -2 * phi;
        point s2 = r @ phi + l_s @ beta;
        body rod: mass m_rod, com s2, inertia j_rod, turns beta;
        body piston: mass m_p, com (x, 0);
        body flywheel: mass 0, com (0, 0), inertia j_g, turns g;
        torque friction on beta = -c * beta;
        torque push on g = -k;
    }
}

/// A flywheel that turns with an angle an `eq` sets to `-2 * phi` adds `4 j_g` to the reduced
/// inertia and `2 k` to the generalised force of its torque `-k` (through the ratio -2), and
/// nothing to the slope: its angle turns it by so many radians. Such an angle was refused as "not an angle".
#[test]
fn a_body_turns_with_an_angle_an_equation_sets_to_an_expression_of_angles() {
    let (geared, plain) = (EngineWithGear::default(), EngineByLoop::default());
    let (model_geared, model_plain) = (geared.mass_model().unwrap(), plain.mass_model().unwrap());
    assert_eq!(model_geared.bodies()[2].rotation, Rotation::Unknown(2));
    let (mut guess_geared, mut guess_plain) = (geared.guess_flat(&[0.0]), plain.guess_flat(&[0.0]));
    let (gear_inertia, push) = (4.0 * geared.j_g, 2.0 * geared.k);
    let mut worst: f64 = 0.0;
    for step in 0..36 {
        let phi = step as f64 * 10f64.to_radians();
        let k_geared = geared.kinematics_flat(&[phi], &guess_geared, &NewtonConfig::default()).unwrap();
        let k_plain = plain.kinematics_flat(&[phi], &guess_plain, &NewtonConfig::default()).unwrap();
        (guess_geared, guess_plain) = (k_geared.q, k_plain.q);
        let a = model_geared.dynamics(&k_geared, &[30.0]).unwrap();
        let b = model_plain.dynamics(&k_plain, &[30.0]).unwrap();
        let j = a.reduced_inertia();
        worst = worst
            .max((a.reduced_inertia() - b.reduced_inertia() - gear_inertia).abs() / j)
            .max((a.reduced_inertia_slope() - b.reduced_inertia_slope()).abs() / j)
            .max((a.forces[0] - b.forces[0] - push).abs() / push);
    }
    // The same loop solved alike in both, the gear's analogs exact (-2 and 0): a few roundings
    // of J and Q, far below the flywheel's share (4 j_g = 0.012 of J = 0.015 to 0.019).
    assert!(worst < 1e-12, "relative difference {worst:e}");
}

#[test]
fn declared_rhombic_model_is_the_hand_built_one() {
    let declared = crate::fixtures::rhombic_bodies([0.0, -9.81]);
    let hand = crate::fixtures::rhombic_bodies_by_hand([0.0, -9.81]);
    assert_eq!(declared.bodies().len(), hand.bodies().len());
    for (a, b) in declared.bodies().iter().zip(hand.bodies()) {
        assert_eq!((a.mass, a.com, a.inertia, a.rotation), (b.mass, b.com, b.inertia, b.rotation), "{}", a.name);
    }
    assert_eq!(declared.gravity_vector(), hand.gravity_vector());
    // The declared gas force is off by default (no gas): its generalised force is zero, so both
    // models give the same dynamics everywhere.
    let drive = RhombicDrive::default();
    let mut guess = drive.guess_flat(&[0.0]);
    for step in 0..36 {
        let phi = step as f64 * 10f64.to_radians();
        let k = drive.kinematics_flat(&[phi], &guess, &NewtonConfig::default()).unwrap();
        guess = k.q;
        assert_eq!(declared.dynamics(&k, &[7.0]).unwrap(), hand.dynamics(&k, &[7.0]).unwrap(), "phi = {phi}");
    }
}

#[test]
fn bad_declared_values_are_typed_errors() {
    let bad_mass = Engine { m_rod: -1.0, ..Engine::default() };
    assert!(
        matches!(bad_mass.mass_model(), Err(DynamicsError::BadMass { body, quantity: "mass", .. }) if body == "rod")
    );
    let bad_inertia = Engine { j_rod: f64::NAN, ..Engine::default() };
    assert!(matches!(bad_inertia.mass_model(), Err(DynamicsError::BadMass { quantity: "moment of inertia", .. })));
    let bad_gravity = Engine { g: f64::INFINITY, ..Engine::default() };
    assert!(matches!(bad_gravity.mass_model(), Err(DynamicsError::BadValue { what: "gravity", .. })));
    // A load that is not finite shows when it is evaluated, with the input where it happened.
    let bad_gas = Engine { p0: f64::NAN, ..Engine::default() };
    let model = bad_gas.mass_model().unwrap();
    let k = bad_gas.kinematics_flat(&[0.5], &bad_gas.guess_flat(&[0.5]), &NewtonConfig::default()).unwrap();
    match model.dynamics(&k, &[1.0]) {
        Err(DynamicsError::NonFiniteLoad { name, x, .. }) if name == "gas" => assert_eq!(x, vec![0.5]),
        other => panic!("expected a non-finite gas force, got {other:?}"),
    }
}

/// The declared coordinates and angles are the ones a hand-built model names.
#[test]
fn declared_points_and_angles_map_to_the_state() {
    let model = Engine::default().mass_model().unwrap();
    let col = |n: &str| <Engine as Mechanism<2, 1, 2>>::OUTPUTS.iter().position(|o| *o == n).unwrap();
    let expected = [
        Body {
            name: "crank".into(),
            mass: 0.0,
            com: [Coord::Fixed(0.0); 2],
            inertia: 0.02,
            rotation: Rotation::Input(0),
        },
        Body {
            name: "rod".into(),
            mass: 2.0,
            com: [Coord::Output(col("s2.x")), Coord::Output(col("s2.y"))],
            inertia: 0.01,
            rotation: Rotation::Unknown(0),
        },
        Body {
            name: "piston".into(),
            mass: 0.5,
            com: [Coord::Unknown(1), Coord::Fixed(0.0)],
            inertia: 0.0,
            rotation: Rotation::None,
        },
    ];
    assert_eq!(model.bodies(), &expected);
    assert_eq!(model.gravity_vector(), [0.0, -9.81]);
    let names: Vec<_> = model.loads().iter().map(|l| l.name()).collect();
    assert_eq!(names, ["gas", "friction"]);
    let _: &MassModel<2, 1, 2> = &model;
}

/// Scale-free: the engine in millimetres (consistent units kg, mm, s: lengths times 1e3,
/// moments of inertia, pressures times areas and torques rescaled accordingly) gives the same
/// dynamics times the unit's factor: J, dJ/dphi and Q (energies per radian) times 1e6.
#[test]
fn declared_dynamics_are_scale_free() {
    let m = Engine::default();
    let mm = Engine {
        r: m.r * 1e3,
        l: m.l * 1e3,
        l_s: m.l_s * 1e3,
        j_rod: m.j_rod * 1e6,
        j_crank: m.j_crank * 1e6,
        area: m.area * 1e6,
        p0: m.p0 * 1e-3,
        c: m.c * 1e6,
        g: m.g * 1e3,
        ..m
    };
    let (model_m, model_mm) = (m.mass_model().unwrap(), mm.mass_model().unwrap());
    let (mut guess_m, mut guess_mm) = (m.guess_flat(&[0.0]), mm.guess_flat(&[0.0]));
    let mut worst: f64 = 0.0;
    for step in 0..36 {
        let phi = step as f64 * 10f64.to_radians();
        let k_m = m.kinematics_flat(&[phi], &guess_m, &NewtonConfig::default()).unwrap();
        let k_mm = mm.kinematics_flat(&[phi], &guess_mm, &NewtonConfig::default()).unwrap();
        (guess_m, guess_mm) = (k_m.q, k_mm.q);
        let (a, b) = (model_m.dynamics(&k_m, &[30.0]).unwrap(), model_mm.dynamics(&k_mm, &[30.0]).unwrap());
        let rel = |x: f64, y: f64, scale: f64| (y / 1e6 - x).abs() / scale;
        worst = worst
            .max(rel(a.reduced_inertia(), b.reduced_inertia(), a.reduced_inertia()))
            .max(rel(a.reduced_inertia_slope(), b.reduced_inertia_slope(), a.reduced_inertia()))
            .max(rel(a.forces[0], b.forces[0], m.p0 * m.area * m.r));
    }
    // Each quantity is a short sum of products of f64 values that differ by exact powers of ten
    // only up to rounding (1e3 and 1e-3 are not exact binary scalings): a few ulps.
    assert!(worst < 1e-13, "relative difference {worst:e}");
}

kinloop::mechanism! {
    #[doc(hidden)]
    #[doc = concat!("A crank drawn ", "at half its angle: `q` turns as the input does.")]
    pub struct HalfAngleCrank {
        params r = 1.5;
        input phi;
        unknowns q = 0.5, x = 0.1;
        loop l: r @ (q / 2) == (x, 0) + r @ (phi / 2);
        body disc: mass 2, com (x, 0), inertia 3, turns q;
    }
}

/// An angle that enters its loop as a half angle (`r @ (q / 2)`) is an angle for a body's
/// `turns`, as a whole one is; and the struct takes Rust's other documentation attributes
/// (`#[doc(hidden)]`, `#[doc = concat!(..)]`). Here `q = phi` and `x = 0`: the reduced inertia is
/// the disc's own, 3, its mass not moving.
#[test]
fn a_body_turns_with_a_half_angle() {
    let m = HalfAngleCrank::default();
    let model = m.mass_model().unwrap();
    assert_eq!(model.bodies()[0].rotation, Rotation::Unknown(0));
    for phi in [0.3, 1.0, 2.5] {
        let k = m.kinematics_flat(&[phi], &[phi + 0.01, 0.01], &NewtonConfig::default()).unwrap();
        assert!((k.q[0] - phi).abs() < 1e-14 && k.q[1].abs() < 1e-14, "{:?}", k.q);
        let d = model.dynamics(&k, &[1.0]).unwrap();
        assert!((d.reduced_inertia() - 3.0).abs() < 1e-13, "{}", d.reduced_inertia());
    }
}
