//! Shaking force and moment on the frame against independent references from solved
//! positions only: the force equals `-M a_G`, the total moving mass times the acceleration of
//! the overall centre of mass (differenced twice along the input); the moment equals `-dH/dt`,
//! the rate of the angular momentum about the frame point (differenced along the trajectory). A
//! crank counterweighted onto its axis shakes nothing; the slider-crank's harmonics against the
//! closed form.

use crate::fixtures::{RhombicDrive, configuration, derivative, rhombic_model, second_derivative};
use kinloop::Mechanism;
use kinloop::dynamics::{Body, Coord, InverseCycle, MassModel, Rotation, SpeedLaw};
use std::f64::consts::TAU;

use crate::support::tol;

#[test]
fn shaking_force_is_mass_times_centre_of_mass_acceleration() {
    let drive = RhombicDrive::default();
    let model = rhombic_model([0.0, -9.81]);
    let bodies = model.bodies();
    let total = model.total_mass();
    let law = |phi: f64| (2.0 * (1.0 + 0.3 * phi.cos()), -2.0 * 0.3 * phi.sin());
    let about = [0.4, -0.2];
    let cycle = InverseCycle::new(&drive, &model, SpeedLaw::Varying(&law))
        .start(0.05)
        .samples(36)
        .guess(drive.guess_flat(&[0.05]))
        .about(about)
        .run()
        .unwrap();
    let mut guess = drive.guess_flat(&[0.05]);
    let scale = cycle.points.iter().map(|p| p.shaking.force[0].hypot(p.shaking.force[1])).fold(0.0, f64::max);
    for p in &cycle.points {
        guess = drive.position_flat(&[p.phi], &guess, &Default::default()).unwrap().0;
        let centre = |x: f64| {
            let c = configuration(&drive, bodies, x, &guess);
            let g = |k: usize| bodies.iter().enumerate().map(|(i, b)| b.mass * c[3 * i + k]).sum::<f64>() / total;
            vec![g(0), g(1)]
        };
        let d1 = derivative(centre, p.phi, 1e-3);
        let d2 = second_derivative(centre, p.phi, 1e-3);
        for k in 0..2 {
            let a = d2[k] * p.omega * p.omega + d1[k] * p.eps;
            // Second differences: rounding ~ eps / h^2 ~ 2e-10 relative.
            assert!(
                (p.shaking.force[k] + total * a).abs() <= 1e-8 * scale,
                "phi {}: {:?} vs {} (scale {scale})",
                p.phi,
                p.shaking.force[k],
                -total * a
            );
        }
    }
    // The moment: -dH/dt with H = sum m (r - O) x v + J theta' along phi(t).
    for p in cycle.points.iter().step_by(3) {
        guess = drive.position_flat(&[p.phi], &guess, &Default::default()).unwrap().0;
        let momentum = |t: f64| {
            let (phi, omega) = (p.phi + p.omega * t + 0.5 * p.eps * t * t, p.omega + p.eps * t);
            let c = configuration(&drive, bodies, phi, &guess);
            let v = derivative(|x| configuration(&drive, bodies, x, &guess), phi, 1e-3);
            let h: f64 = bodies
                .iter()
                .enumerate()
                .map(|(i, b)| {
                    let (rx, ry) = (c[3 * i] - about[0], c[3 * i + 1] - about[1]);
                    omega * (b.mass * (rx * v[3 * i + 1] - ry * v[3 * i]) + b.inertia * v[3 * i + 2])
                })
                .sum();
            vec![h]
        };
        let dh_dt = derivative(momentum, 0.0, 2e-3)[0];
        let moment_scale = cycle.points.iter().map(|p| p.shaking.moment.abs()).fold(0.0, f64::max);
        assert!(
            (p.shaking.moment + dh_dt).abs() <= 1e-7 * moment_scale,
            "phi {}: {} vs {}",
            p.phi,
            p.shaking.moment,
            -dh_dt
        );
    }
}

kinloop::mechanism! {
    /// Slider-crank with a crank arm's centre of mass at `a` and a counterweight at `b` opposite.
    pub struct Counterweighted {
        params r = 1.0, l = 4.0, e = 0.0, a = 0.6, b = 0.45;
        input phi;
        unknowns psi = pi, x = r + l;
        loop oabo: r @ phi == (x, e) + l @ psi;
        point arm = a @ phi;
        point weight = b @ (phi + pi);
    }
}

#[test]
fn counterweighted_crank_does_not_shake() {
    let m = Counterweighted::default();
    let (m_arm, omega) = (3.0, 150.0);
    let m_weight = m_arm * m.a / m.b;
    let body = |name: &'static str, mass, c: usize| Body {
        name: name.into(),
        mass,
        com: [Coord::Output(2 * c), Coord::Output(2 * c + 1)],
        inertia: 0.01,
        rotation: Rotation::Input(0),
    };
    let model = MassModel::new()
        .with_body(body("arm", m_arm, 0))
        .and_then(|md| md.with_body(body("counterweight", m_weight, 1)))
        .unwrap();
    let cycle = InverseCycle::new(&m, &model, SpeedLaw::Constant(omega))
        .samples(360)
        .guess(m.guess_flat(&[0.0]))
        .run()
        .unwrap();
    let unbalanced = m_arm * m.a * omega * omega;
    for p in &cycle.points {
        let f = p.shaking.force[0].hypot(p.shaking.force[1]);
        assert!(f <= 1e-12 * unbalanced, "phi {}: {f:e}", p.phi);
        // A crank at constant speed needs no torque and shakes no moment about its axis.
        assert_close!(p.torque, 0.0, <= tol::SOLVE * unbalanced);
        assert_close!(p.shaking.moment, 0.0, <= tol::SOLVE * unbalanced);
    }
    // Without the counterweight the crank shakes with m a omega^2 in every direction.
    let bare = MassModel::new().with_body(body("arm", m_arm, 0)).unwrap();
    let cycle =
        InverseCycle::new(&m, &bare, SpeedLaw::Constant(omega)).samples(360).guess(m.guess_flat(&[0.0])).run().unwrap();
    for p in &cycle.points {
        let f = p.shaking.force[0].hypot(p.shaking.force[1]);
        assert_close!(f, unbalanced, <= tol::SOLVE * unbalanced);
    }
}

/// The reciprocating mass of a centred slider-crank: `F_x = -m x''` with
/// `x = r cos phi + sqrt(l^2 - r^2 sin^2 phi)`. The first harmonic is exactly `m r omega^2`
/// (the square root holds only even harmonics); the second is checked against a hand-written
/// discrete Fourier sum of the closed form.
#[test]
fn slider_crank_shaking_harmonics_match_closed_form() {
    let m = Counterweighted { e: 0.0, ..Default::default() };
    let (mass, omega, n) = (1.7, 80.0, 256);
    let x = index_of_x();
    let model = MassModel::new()
        .with_body(Body {
            name: "piston".into(),
            mass,
            com: [Coord::Unknown(x), Coord::Fixed(0.0)],
            inertia: 0.0,
            rotation: Rotation::None,
        })
        .unwrap();
    let cycle =
        InverseCycle::new(&m, &model, SpeedLaw::Constant(omega)).samples(n).guess(m.guess_flat(&[0.0])).run().unwrap();
    let [fx, fy, _] = cycle.shaking_harmonics(4).unwrap();
    let scale = mass * m.r * omega * omega;
    let closed = |phi: f64| {
        let (u, du, d2u) = (m.r * phi.sin(), m.r * phi.cos(), -m.r * phi.sin());
        let s = (m.l * m.l - u * u).sqrt();
        let d2s = -(du * du + u * d2u) / s - (u * du).powi(2) / s.powi(3);
        -mass * omega * omega * (-m.r * phi.cos() + d2s)
    };
    let coefficient = |k: usize, trig: fn(f64) -> f64| {
        (0..n).map(|j| closed(TAU * j as f64 / n as f64) * trig(TAU * (k * j) as f64 / n as f64)).sum::<f64>() * 2.0
            / n as f64
    };
    assert_close!(fx.a[0], scale, <= tol::SOLVE * scale, "{} vs {scale}", fx.a[0]);
    assert_close!(fx.a[1], coefficient(2, f64::cos), <= tol::SOLVE * scale);
    // Second harmonic ~ lambda = r / l of the first (the classical approximation).
    assert_close!(fx.amplitude(2) / scale, m.r / m.l, (m.r / m.l).powi(3));
    for k in 1..=4 {
        assert!(fx.b[k - 1].abs() <= 1e-12 * scale && fy.amplitude(k) <= 1e-12 * scale);
    }
}

fn index_of_x() -> usize {
    <Counterweighted as Mechanism<2, 1, 4>>::UNKNOWNS.iter().position(|u| *u == "x").unwrap()
}
