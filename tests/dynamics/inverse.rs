//! Inverse dynamics: the driving torque `M = J eps + 1/2 J' omega^2 - Q` that the library
//! computes from the analogs, against
//!
//! * Lagrange's equation evaluated independently on the rhombic drive (five bodies, gravity, a
//!   gas force on the piston, a speed that varies over the turn): `d/dt dT/dphi' - dT/dphi - Q`
//!   with the kinetic energy `T` and the virtual work of the loads built from finite
//!   differences of solved positions only, and `d/dt` a finite difference along the trajectory;
//! * the classical closed form for the offset slider-crank with a reciprocating mass `m` and a
//!   gas force `F` on the piston and a balanced crank at constant speed (the crank torque from
//!   the piston force through the connecting-rod angle `beta`, as in the engine force analysis of
//!   Shigley and Uicker, *Theory of Machines and Mechanisms*, or Norton, *Design of Machinery*,
//!   chapter "Engine dynamics"):
//!
//! ```text
//! x = r cos phi + S,  S = sqrt(l^2 - (r sin phi - e)^2),  sin beta = (r sin phi - e) / l,
//! M = -(m x'' - F) r sin(phi + beta) / cos beta
//! ```

use crate::fixtures::{
    RhombicDrive, SliderCrank, configuration, derivative, gas_force, index, reduced_inertia_fd, rhombic_model,
};
use kinloop::Mechanism;
use kinloop::dynamics::{Body, Coord, InverseCycle, MassModel, Rotation, SpeedLaw};
use std::f64::consts::TAU;

use crate::support::tol;

/// `dT/dphi'`, `dT/dphi` and `Q` at `(phi, omega)` from positions only.
fn lagrange_terms(drive: &RhombicDrive, gravity: [f64; 2], phi: f64, omega: f64, guess: &[f64; 4]) -> (f64, f64, f64) {
    let model = rhombic_model(gravity);
    let bodies = model.bodies();
    // T is a quadratic form in phi': dT/dphi' = J(phi) phi' exactly.
    let momentum = reduced_inertia_fd(drive, bodies, phi, guess) * omega;
    let j_slope = derivative(|x| vec![reduced_inertia_fd(drive, bodies, x, guess)], phi, 1e-3)[0];
    let v = derivative(|x| configuration(drive, bodies, x, guess), phi, 1e-3);
    // Virtual work of gravity on each body and of the gas force on the piston (body 3, x).
    let mut q: f64 =
        bodies.iter().enumerate().map(|(i, b)| b.mass * (gravity[0] * v[3 * i] + gravity[1] * v[3 * i + 1])).sum();
    let x_c = configuration(drive, bodies, phi, guess)[9];
    q += gas_force(x_c) * v[9];
    (momentum, 0.5 * j_slope * omega * omega, q)
}

#[test]
fn rhombic_driving_torque_satisfies_lagrange_equation() {
    let drive = RhombicDrive::default();
    let gravity = [0.0, -9.81];
    let model = rhombic_model(gravity);
    let law = |phi: f64| (1.3 * (1.0 + 0.2 * phi.sin()), 1.3 * 0.2 * phi.cos());
    let cycle = InverseCycle::new(&drive, &model, SpeedLaw::Varying(&law))
        .samples(36)
        .guess(drive.guess_flat(&[0.0]))
        .run()
        .unwrap();
    let scale = cycle.points.iter().map(|p| p.torque.abs()).fold(0.0, f64::max);
    let mut guess = drive.guess_flat(&[0.0]);
    for p in &cycle.points {
        guess = drive.position_flat(&[p.phi], &guess, &Default::default()).unwrap().0;
        // The trajectory through this point: phi(t) = phi + omega t + eps t^2 / 2.
        let momentum = |t: f64| {
            let (phi, omega) = (p.phi + p.omega * t + 0.5 * p.eps * t * t, p.omega + p.eps * t);
            vec![lagrange_terms(&drive, gravity, phi, omega, &guess).0]
        };
        let dp_dt = derivative(momentum, 0.0, 2e-3)[0];
        let (_, dt_dphi, q) = lagrange_terms(&drive, gravity, p.phi, p.omega, &guess);
        let reference = dp_dt - dt_dphi - q;
        // Nested differences: J to ~1e-12, its derivative in t to ~1e-12 / 1e-3 ~ 1e-9.
        assert_close!(p.torque, reference, <= 1e-7 * scale, "phi {}: {} vs {reference}", p.phi, p.torque);
        // The cycle's own fields are consistent with the formula.
        let direct = p.inertia * p.eps + 0.5 * p.inertia_slope * p.omega * p.omega - p.load;
        assert_close!(p.torque, direct, <= tol::ULPS * scale);
    }
}

/// Gas force on the piston along x (towards the crank), a function of its position.
fn piston_gas(x: f64) -> f64 {
    -3.0 / (x - 1.5).powi(2)
}

#[test]
fn slider_crank_torque_matches_classical_closed_form() {
    let sc = SliderCrank::default();
    let (r, l, e, m, omega) = (sc.r, sc.l, sc.e, 2.5, 40.0);
    let x_col = index(&<SliderCrank as Mechanism<2, 1, 2>>::UNKNOWNS, "x");
    let piston = [Coord::Unknown(x_col), Coord::Fixed(e)];
    // A massless rod: the classical reciprocating-mass model.
    let model = MassModel::new()
        .with_body(Body {
            name: "crank".into(),
            mass: 4.0,
            com: [Coord::Fixed(0.0); 2],
            inertia: 0.3,
            rotation: Rotation::Input(0),
        })
        .and_then(|md| {
            md.with_body(Body { name: "piston".into(), mass: m, com: piston, inertia: 0.0, rotation: Rotation::None })
        })
        .and_then(|md| md.with_force("gas", piston, move |k, _| [piston_gas(k.q[x_col]), 0.0]))
        .unwrap();
    let cycle = InverseCycle::new(&sc, &model, SpeedLaw::Constant(omega))
        .start(0.1)
        .samples(720)
        .guess(sc.guess_flat(&[0.1]))
        .run()
        .unwrap();
    let closed = |phi: f64| {
        let (u, du, d2u) = (r * phi.sin() - e, r * phi.cos(), -r * phi.sin());
        let s = (l * l - u * u).sqrt();
        let d2s = -(du * du + u * d2u) / s - (u * du).powi(2) / s.powi(3);
        let x = r * phi.cos() + s;
        let accel = omega * omega * (-r * phi.cos() + d2s);
        let beta = (u / l).asin();
        -(m * accel - piston_gas(x)) * r * (phi + beta).sin() / beta.cos()
    };
    let scale = cycle.points.iter().map(|p| closed(p.phi).abs()).fold(0.0, f64::max);
    for p in &cycle.points {
        assert_close!(p.torque, closed(p.phi), <= tol::SOLVE * scale, "phi {}: {} vs {}", p.phi, p.torque, closed(p.phi));
    }
    // The phase of the samples: one turn from 0.1, equally spaced.
    assert_close!(cycle.points[1].phi - cycle.points[0].phi, TAU / 720.0, tol::SOLVE);
}

kinloop::mechanism! {
    /// A crank pushed round by its piston: the piston's position `x` is the input, a length.
    pub struct PistonDriven {
        params r = 0.05, l = 0.2, m = 2.0;
        input x;
        unknowns phi = 0.3, beta = -0.1;
        loop abc: r @ phi + l @ beta == (x, 0);
        point pin = r @ phi;
        body crank: mass m, com pin;
    }
}

/// A cycle turns its input through 2 pi: of a length input that is 2 pi of the unit of length,
/// and no period of the machine. It is refused, naming the input and what it is, in every unit:
/// in metres the 6.28 m stroke ran into a limit position (an error that blamed the branch), in
/// millimetres the 6.28 mm from x = 200 mm came out as a cycle, its driving torque's mean
/// -0.002 with no load at all (the inertia term over a stretch that is no period).
#[test]
fn a_cycle_of_an_input_that_is_a_length_is_refused_in_every_unit() {
    use kinloop::dynamics::{DynamicsError, turn_states};
    use kinloop::{Compiled, QuantityKind};
    assert_eq!(PistonDriven::INPUT_KINDS, [QuantityKind::Length]);
    for unit in [1.0, 1e3, 1e6] {
        let m = PistonDriven { r: 0.05 * unit, l: 0.2 * unit, m: 2.0 };
        let model = m.mass_model().unwrap();
        let x0 = 0.2 * unit;
        let run = InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0)).start(x0).guess(m.guess_flat(&[x0])).run();
        let err = run.expect_err("a cycle over a length");
        assert!(
            matches!(&err, DynamicsError::InputNotAngle { input, kind: QuantityKind::Length } if input == "x"),
            "unit {unit}: {err}"
        );
        let said = err.to_string();
        assert!(said.contains("`x` is a length, not an angle") && said.contains("crank angle"), "{said}");
        let states = turn_states(Compiled(&m), x0, 64, m.guess_flat(&[x0]));
        assert!(matches!(states, Err(DynamicsError::InputNotAngle { .. })), "unit {unit}: {states:?}");
    }
}
