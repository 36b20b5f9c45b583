//! The reduced moment of inertia `J(phi)` and its slope, computed by the library exactly from
//! the analogs, against an independent computation: the kinetic energy from
//! finite-difference velocities of the solved positions (central differences at h = 1e-3 and
//! 5e-4, one Richardson step), on the rhombic drive with five bodies; and the mass matrix of the
//! two-input five-bar against the same construction per input.

use crate::fixtures::{RhombicDrive, derivative, reduced_inertia_fd, rhombic_model};
use crate::support::{newton_to_fine_step, tol};
use kinloop::Mechanism;
use kinloop::dynamics::{Body, Coord, MassModel, Rotation};

/// Relative agreement of the finite-difference reference: truncation ~h^4 |r^(5)| ~ 1e-12 and
/// rounding ~1e-16 / 5e-4 ~ 2e-13 per velocity, on lengths and velocities of order 1.
const FD_REL: f64 = 1e-9;

#[test]
fn reduced_inertia_matches_kinetic_energy_of_differenced_positions() {
    let drive = RhombicDrive::default();
    let model = rhombic_model([0.0, 0.0]);
    let mut guess = drive.guess_flat(&[0.0]);
    let mut worst: f64 = 0.0;
    for j in 0..72 {
        let phi = j as f64 * 5f64.to_radians() + 0.01;
        let k = drive.kinematics_flat(&[phi], &guess, &Default::default()).unwrap();
        guess = k.q;
        let d = model.dynamics(&k, &[1.0]).unwrap();
        let reference = reduced_inertia_fd(&drive, model.bodies(), phi, &k.q);
        worst = worst.max((d.reduced_inertia() - reference).abs() / reference);
        // The kinetic energy at any speed is 1/2 J omega^2.
        let t = model.kinetic_energy(&k, &[7.0]);
        assert_close!(t, 0.5 * reference * 49.0, <= FD_REL * t);
    }
    assert!(worst <= FD_REL, "worst relative deviation {worst:e}");
}

#[test]
fn inertia_slope_matches_differenced_inertia() {
    let drive = RhombicDrive::default();
    let model = rhombic_model([0.0, 0.0]);
    let mut guess = drive.guess_flat(&[0.0]);
    for j in 0..36 {
        let phi = j as f64 * 10f64.to_radians() + 0.02;
        let k = drive.kinematics_flat(&[phi], &guess, &Default::default()).unwrap();
        guess = k.q;
        let slope = model.dynamics(&k, &[1.0]).unwrap().reduced_inertia_slope();
        // J at neighbouring angles (itself checked above), differenced: h = 1e-3, Richardson.
        let j_at = |x: f64| {
            let kx = drive.kinematics_flat(&[x], &k.q, &Default::default()).unwrap();
            vec![model.dynamics(&kx, &[1.0]).unwrap().reduced_inertia()]
        };
        let reference = derivative(j_at, phi, 1e-3)[0];
        let scale = model.dynamics(&k, &[1.0]).unwrap().reduced_inertia();
        assert_close!(slope, reference, <= 1e-9 * scale, "phi {phi}: {slope} vs {reference}");
    }
}

kinloop::mechanism! {
    /// Five-bar linkage driven by two cranks (as in tests/kinematics/five_bar.rs), with the centres of
    /// mass of its two links.
    pub struct FiveBar {
        params a = 1.0, b = 2.5, c = 2.2, d = 1.5, e = 1.2;
        inputs th1, th2;
        unknowns phi2 = 1.0, phi3 = 2.0;
        loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3;
        point s2 = a @ th1 + 0.4 * b @ phi2;
        point s3 = (d, 0) + e @ th2 + 0.6 * c @ phi3;
        point s1 = 0.5 * a @ th1;
        point s4 = (d, 0) + 0.5 * e @ th2;
    }
}

fn five_bar_model() -> MassModel<2, 2, 8> {
    let body = |name: &'static str, mass, c: usize, inertia, rotation| Body {
        name: name.into(),
        mass,
        com: [Coord::Output(2 * c), Coord::Output(2 * c + 1)],
        inertia,
        rotation,
    };
    MassModel::new()
        .with_body(body("link b", 1.3, 0, 0.7, Rotation::Unknown(0)))
        .and_then(|m| m.with_body(body("link c", 1.1, 1, 0.5, Rotation::Unknown(1))))
        .and_then(|m| m.with_body(body("crank a", 0.6, 2, 0.08, Rotation::Input(0))))
        .and_then(|m| m.with_body(body("crank e", 0.5, 3, 0.06, Rotation::Input(1))))
        .unwrap()
}

/// `M_ij = sum m v_Si . v_Sj + J w_i w_j` with the partial velocities `v_Si` differenced from
/// position solves along input `i` with the other input fixed.
#[test]
fn five_bar_mass_matrix_matches_differenced_partial_velocities() {
    let m = FiveBar::default();
    let model = five_bar_model();
    let cfg = newton_to_fine_step();
    for (th1, th2) in [(1.3, 0.9), (1.5, 1.1), (1.7, 1.3), (1.25, 1.35)] {
        let k = m.kinematics_flat(&[th1, th2], &m.guess_flat(&[th1, th2]), &cfg).unwrap();
        let config = |x: [f64; 2]| -> Vec<f64> {
            let (q, _) = m.position_flat(&x, &k.q, &cfg).unwrap();
            let out = m.outputs_flat(&x, &q);
            let angles = [q[0], q[1], x[0], x[1]];
            (0..4).flat_map(|b| [out[2 * b], out[2 * b + 1], angles[b]]).collect()
        };
        let v1 = derivative(|t| config([t, th2]), th1, 1e-3);
        let v2 = derivative(|t| config([th1, t]), th2, 1e-3);
        let v = [v1, v2];
        let (mass, _) = model.inertia(&k);
        for i in 0..2 {
            for j in 0..2 {
                let reference: f64 = model
                    .bodies()
                    .iter()
                    .enumerate()
                    .map(|(b, body)| {
                        let (x, y, r) = (3 * b, 3 * b + 1, 3 * b + 2);
                        body.mass * (v[i][x] * v[j][x] + v[i][y] * v[j][y]) + body.inertia * v[i][r] * v[j][r]
                    })
                    .sum();
                assert_close!(mass[i][j], reference, <= FD_REL * mass[0][0].max(mass[1][1]), "M[{i}][{j}]");
            }
        }
    }
}

/// The velocity-product terms satisfy Lagrange's identity `h_i(w) = d/dt (M w)_i -
/// 1/2 w^T (dM/dx_i) w` at zero input acceleration: `dM/dt` along `w` and `dM/dx_i` from the
/// library's mass matrix (checked above) differenced at neighbouring positions.
#[test]
fn five_bar_velocity_terms_satisfy_lagrange() {
    let m = FiveBar::default();
    let model = five_bar_model();
    let cfg = newton_to_fine_step();
    let w = [1.7, -0.9];
    for (th1, th2) in [(1.3, 0.9), (1.5, 1.1), (1.7, 1.3)] {
        let k = m.kinematics_flat(&[th1, th2], &m.guess_flat(&[th1, th2]), &cfg).unwrap();
        let mass_at = |x: [f64; 2]| -> Vec<f64> {
            let kx = m.kinematics_flat(&x, &k.q, &cfg).unwrap();
            model.inertia(&kx).0.iter().flatten().copied().collect()
        };
        let dm_dt = derivative(|t| mass_at([th1 + w[0] * t, th2 + w[1] * t]), 0.0, 1e-3);
        let dm_d1 = derivative(|t| mass_at([t, th2]), th1, 1e-3);
        let dm_d2 = derivative(|t| mass_at([th1, t]), th2, 1e-3);
        let quad = |d: &[f64]| 0.5 * (d[0] * w[0] * w[0] + (d[1] + d[2]) * w[0] * w[1] + d[3] * w[1] * w[1]);
        let reference =
            [dm_dt[0] * w[0] + dm_dt[1] * w[1] - quad(&dm_d1), dm_dt[2] * w[0] + dm_dt[3] * w[1] - quad(&dm_d2)];
        let d = model.dynamics(&k, &w).unwrap();
        let h = d.velocity_terms(&w);
        for i in 0..2 {
            assert_close!(h[i], reference[i], <= 1e-8, "h[{i}] = {} vs {}", h[i], reference[i]);
        }
    }
}

/// Forward dynamics inverts inverse dynamics: the accelerations from `M eps = tau + Q - h`
/// (Cholesky) reproduce the `eps` whose driving forces `tau` inverse dynamics gave, to the
/// conditioning of `M` times rounding.
#[test]
fn five_bar_forward_dynamics_inverts_inverse_dynamics() {
    let m = FiveBar::default();
    let model = five_bar_model().with_gravity([0.0, -9.81]).unwrap();
    let cfg = newton_to_fine_step();
    for (th1, th2) in [(1.3, 0.9), (1.5, 1.1), (1.7, 1.3)] {
        let k = m.kinematics_flat(&[th1, th2], &m.guess_flat(&[th1, th2]), &cfg).unwrap();
        let (w, eps) = ([1.7, -0.9], [0.4, 2.5]);
        let d = model.dynamics(&k, &w).unwrap();
        let tau = d.drive(&w, &eps);
        let back = d.accelerations(&k.x, &w, &tau).unwrap();
        for i in 0..2 {
            assert_close!(back[i], eps[i], <= tol::SOLVE * eps[0].abs().max(eps[1].abs()), "{back:?} vs {eps:?}");
        }
    }
    // A model without mass has a singular mass matrix: a typed error, not a NaN.
    let k = m.kinematics_flat(&[1.3, 0.9], &m.guess_flat(&[1.3, 0.9]), &cfg).unwrap();
    let d = MassModel::<2, 2, 8>::new().dynamics(&k, &[0.0; 2]).unwrap();
    assert!(matches!(
        d.accelerations(&k.x, &[0.0; 2], &[1.0; 2]),
        Err(kinloop::dynamics::DynamicsError::SingularMass { .. })
    ));
}

/// Scale-free: the same drive in metres and in micrometres (lengths times 1e6, the fixed
/// displacer line too) has `J` and `dJ/dphi` times 1e12, gravity's generalised force times
/// 1e6, to rounding.
#[test]
fn reduced_inertia_scales_with_length_squared() {
    let d = RhombicDrive::default();
    let s = 1e6;
    let big = RhombicDrive {
        r_p: s * d.r_p,
        r_b: s * d.r_b,
        l_p: s * d.l_p,
        l_b: s * d.l_b,
        e_p: s * d.e_p,
        de: s * d.de,
        l_as1: s * d.l_as1,
        l_cs2: s * d.l_cs2,
        l_fs4: s * d.l_fs4,
        ..d
    };
    let small_model = crate::fixtures::rhombic_bodies([0.0, -9.81]);
    let big_model = scaled_bodies(&small_model, s);
    let (mut g_small, mut g_big) = (d.guess_flat(&[0.0]), big.guess_flat(&[0.0]));
    for j in 0..36 {
        let phi = j as f64 * 10f64.to_radians() + 0.03;
        let ks = d.kinematics_flat(&[phi], &g_small, &newton_to_fine_step()).unwrap();
        let kb = big.kinematics_flat(&[phi], &g_big, &newton_to_fine_step()).unwrap();
        (g_small, g_big) = (ks.q, kb.q);
        let (a, b) = (small_model.dynamics(&ks, &[1.0]).unwrap(), big_model.dynamics(&kb, &[1.0]).unwrap());
        assert_close!(b.reduced_inertia() / (s * s), a.reduced_inertia(), <= tol::SOLVE * a.reduced_inertia());
        let slope_scale = a.reduced_inertia();
        assert_close!(b.reduced_inertia_slope() / (s * s), a.reduced_inertia_slope(), <= tol::SOLVE * slope_scale);
        assert_close!(b.forces[0] / s, a.forces[0], <= tol::SOLVE * a.forces[0].abs().max(1.0));
    }
}

/// The bodies of `model` for lengths times `s`: inertias times `s^2`, fixed coordinates times
/// `s`.
fn scaled_bodies(model: &MassModel<4, 1, 7>, s: f64) -> MassModel<4, 1, 7> {
    let scale = |c: Coord| if let Coord::Fixed(v) = c { Coord::Fixed(s * v) } else { c };
    let mut m = MassModel::new().with_gravity(model.gravity_vector()).unwrap();
    for b in model.bodies() {
        m = m.with_body(Body { inertia: b.inertia * s * s, com: b.com.map(scale), ..b.clone() }).unwrap();
    }
    m
}
