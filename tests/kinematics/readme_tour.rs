//! README.md's "A short tour" as written: its two Rust blocks are here line for line (the
//! statements in a function, the dynamics items in a declaration of their own) and run against
//! paper 000's closed forms (`docs/papers.md`), and `the_readme_shows_this_code` fails when a
//! line of those blocks is not here in the same order, so that the README cannot go on showing
//! code that no longer compiles.

use crate::support::doc_snippets::{assert_written_in, rust_blocks};
use crate::support::tol;

kinloop::mechanism! {
    /// Asymmetric rhombic drive with a developed crank (paper 000, Fig. 1).
    pub struct RhombicDrive {
        params r_p, r_b, l_p, l_b, e_p, de, gamma, l_cs2;
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;   // guesses pick the branch
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
        point s2 = (x_c, 0) + l_cs2 @ phi2;                    // centre of mass of rod 2
    }
}

kinloop::mechanism! {
    /// The tour's drive with the README's dynamics items.
    pub struct RhombicMachine {
        params r_p, r_b, l_p, l_b, e_p, de, gamma, l_cs2;
        params m1, j1, l_as1, psi_s1, m2, j2, m_c, p_gas, area, g;   // ... next to the kinematic ones
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
        point s2 = (x_c, 0) + l_cs2 @ phi2;
        point s1 = (0, e_p) + l_as1 @ (phi1 + psi_s1);         // centre of mass of the crank
        body crank: mass m1, com s1, inertia j1, turns phi1;   // com: a declared point
        body rod: mass m2, com s2, inertia j2, turns phi2;
        body piston: mass m_c, com (x_c, 0);                   // a slider: no `turns`
        force gas at (x_c, 0) = (p_gas * area, 0);             // expressions of the state
        torque friction on phi2 = -0.01 * sin(phi2);           // on an input or an angle unknown
        gravity (0, -g);
    }
}

/// The tour's statements, then what each names checked against the paper's closed forms:
/// `sin phi2 = lambda_P (k_P + sin phi1)` with `cos phi2 > 0`, `X_C`, `U21`, `V_qC`, `eps_q2`.
fn tour(omega1: f64, eps1: f64) -> Result<(), kinloop::Error> {
    let drive = RhombicDrive { r_p: 1.0, r_b: 1.2, l_p: 3.0, l_b: 3.5, e_p: 0.5, de: 0.9, gamma: 0.7, l_cs2: 1.2 };
    let s = drive.solve(0.5)?; // or drive.kinematics(phi1, &previous.q) along a sweep
    let x_c = s.q.x_c; // piston position X_C
    let v_qc = s.dq.x_c; // velocity analog dX_C/dphi1
    let eps_q2 = s.d2q.phi2; // acceleration analog of the rod angle
    let v_qs2 = s.dout.s2.norm(); // |v_qS2|
    let m = s.motion(omega1, eps1)?; // true velocities and accelerations (crank: omega1, eps1)

    let (lambda, k, phi1) = (drive.r_p / drive.l_p, drive.e_p / drive.r_p, 0.5_f64);
    let phi2 = (lambda * (k + phi1.sin())).asin();
    let u21 = lambda * phi1.cos() / phi2.cos();
    let expected_v_qc = drive.l_p * (u21 * phi2.sin() - lambda * phi1.sin());
    assert_close!(x_c, drive.l_p * (lambda * phi1.cos() - phi2.cos()), rel = tol::SOLVE);
    assert_close!(v_qc, expected_v_qc, rel = tol::SOLVE);
    let expected_eps_q2 = (u21 * u21 * phi2.sin() - lambda * phi1.sin()) / phi2.cos();
    assert_close!(eps_q2, expected_eps_q2, rel = tol::SOLVE);
    // S2 = (X_C, 0) + l_CS2 (cos phi2, sin phi2), differentiated by hand.
    let v_s2 = [expected_v_qc - drive.l_cs2 * phi2.sin() * u21, drive.l_cs2 * phi2.cos() * u21];
    assert_close!(v_qs2, v_s2[0].hypot(v_s2[1]), rel = tol::SOLVE);
    // v = v_q omega1, a = a_q omega1^2 + v_q eps1.
    assert_close!(m.qdot.x_c, expected_v_qc * omega1, rel = tol::SOLVE);
    assert_close!(m.qddot.phi2, expected_eps_q2 * omega1 * omega1 + u21 * eps1, rel = tol::SOLVE);
    Ok(())
}

#[test]
fn the_tour_runs_and_means_what_it_says() {
    tour(10.0, 0.0).unwrap();
    tour(-3.0, 2.5).unwrap();
}

#[test]
fn the_tours_mass_model_is_its_bodies() -> Result<(), kinloop::Error> {
    // The tour's drive; then m1, j1, l_as1, psi_s1, m2, j2, m_c, p_gas, area, g.
    let drive = RhombicMachine::from_param_values([
        1.0, 1.2, 3.0, 3.5, 0.5, 0.9, 0.7, 1.2, //
        2.0, 0.05, 0.3, 0.35, 0.8, 0.6, 1.5, 2.0, 0.5, 9.81,
    ]);
    let model = drive.mass_model()?;
    let s = drive.solve(0.5)?;
    let d = model.dynamics(&s.flat, &[1.0])?;
    // Reduced inertia: each body's mass times its centre's squared velocity analog, plus its
    // moment of inertia times its angle's squared analog (the crank turns with phi1 itself).
    let (v_s1, v_s2) = (s.dout.s1, s.dout.s2);
    let expected = drive.m1 * v_s1.norm().powi(2)
        + drive.j1
        + drive.m2 * v_s2.norm().powi(2)
        + drive.j2 * s.dq.phi2.powi(2)
        + drive.m_c * s.dq.x_c.powi(2);
    assert_close!(d.reduced_inertia(), expected, rel = tol::SOLVE);
    assert_close!(v_s1.norm(), drive.l_as1, rel = tol::SOLVE);
    Ok(())
}

#[test]
fn the_readme_shows_this_code() {
    let blocks = rust_blocks("README.md", "## A short tour");
    assert_eq!(blocks.len(), 2, "the tour's two Rust blocks");
    for (i, block) in blocks.iter().enumerate() {
        assert_written_in(
            include_str!("readme_tour.rs"),
            block,
            &format!("README.md, the tour's Rust block {}", i + 1),
        );
    }
}
