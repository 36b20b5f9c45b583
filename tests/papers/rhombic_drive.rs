//! The asymmetric rhombic drive of paper 000 (`docs/papers.md`, Fig. 1), as declared in
//! `examples/rhombic_drive.rs`, against the paper's closed forms, over 3600 crank angles: positions, velocity analogs, acceleration analogs, and the
//! centres of mass S1, S2, S4 against formulas derived here by hand.

use std::f64::consts::PI;

use kinloop_fixtures::RhombicDrive;
use kinloop_fixtures::rhombic::GALLERY_DRIVE;

use crate::support::tol;

/// The example's drive, with centres of mass of its own.
const DRIVE: RhombicDrive = RhombicDrive { l_as1: 0.4, psi_s1: 0.3, l_cs2: 1.1, l_fs4: 1.6, ..GALLERY_DRIVE };

/// The published closed form (paper 000) plus derived centre-of-mass formulas.
struct Closed {
    q: [f64; 4],
    dq: [f64; 4],
    d2q: [f64; 4],
    /// s1, s2, s4 as [x, y] with their first and second analogs.
    s: [[f64; 2]; 3],
    ds: [[f64; 2]; 3],
    d2s: [[f64; 2]; 3],
}

fn closed(m: &RhombicDrive, phi1: f64) -> Closed {
    let lam_p = m.r_p / m.l_p;
    let k_p = m.e_p / m.r_p;
    let e_b = m.e_p - m.de;
    let lam_b = m.r_b / m.l_b;
    let k_b = e_b / m.r_b;
    let a = phi1 + m.gamma;
    let s2 = lam_p * (k_p + phi1.sin());
    let phi2 = s2.asin();
    let s4 = lam_b * (k_b + a.sin());
    let phi4 = PI - s4.asin(); // continuous branch with cos(phi4) < 0
    let (c2, c4) = (phi2.cos(), phi4.cos());
    let x_c = m.l_p * (lam_p * phi1.cos() - c2);
    let x_f = m.l_b * (lam_b * a.cos() - c4);
    let u21 = lam_p * phi1.cos() / c2;
    let u41 = lam_b * a.cos() / c4;
    let v_c = m.l_p * (u21 * phi2.sin() - lam_p * phi1.sin());
    let v_f = m.l_b * (u41 * phi4.sin() - lam_b * a.sin());
    let e2 = (u21 * u21 * phi2.sin() - lam_p * phi1.sin()) / c2;
    let e4 = (u41 * u41 * phi4.sin() - lam_b * a.sin()) / c4;
    let a_c = m.l_p * (e2 * phi2.sin() + u21 * u21 * c2 - lam_p * phi1.cos());
    let a_f = m.l_b * (e4 * phi4.sin() + u41 * u41 * c4 - lam_b * a.cos());

    // Centres of mass, differentiated by hand (chain rule on the position formulas).
    let b = phi1 + m.psi_s1;
    let l1 = m.l_as1;
    let s1 = [l1 * b.cos(), m.e_p + l1 * b.sin()];
    let ds1 = [-l1 * b.sin(), l1 * b.cos()];
    let d2s1 = [-l1 * b.cos(), -l1 * b.sin()];
    let l2 = m.l_cs2;
    let s2p = [x_c + l2 * c2, l2 * phi2.sin()];
    let ds2 = [v_c - l2 * phi2.sin() * u21, l2 * c2 * u21];
    let d2s2 = [a_c - l2 * c2 * u21 * u21 - l2 * phi2.sin() * e2, -l2 * phi2.sin() * u21 * u21 + l2 * c2 * e2];
    let l4 = m.l_fs4;
    let s4p = [x_f + l4 * c4, m.de + l4 * phi4.sin()];
    let ds4 = [v_f - l4 * phi4.sin() * u41, l4 * c4 * u41];
    let d2s4 = [a_f - l4 * c4 * u41 * u41 - l4 * phi4.sin() * e4, -l4 * phi4.sin() * u41 * u41 + l4 * c4 * e4];
    Closed {
        q: [phi2, phi4, x_c, x_f],
        dq: [u21, u41, v_c, v_f],
        d2q: [e2, e4, a_c, a_f],
        s: [s1, s2p, s4p],
        ds: [ds1, ds2, ds4],
        d2s: [d2s1, d2s2, d2s4],
    }
}

#[test]
fn rhombic_drive_matches_published_closed_form_over_a_full_turn() {
    let m = DRIVE;
    let mut guess = m.guess(0.0);
    let (mut phi2_min, mut phi2_max, mut phi4_min, mut phi4_max) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for k in 0..3600 {
        let phi1 = 2.0 * PI * k as f64 / 3600.0;
        let st = m.kinematics(phi1, &guess).unwrap_or_else(|e| panic!("phi1 = {phi1}: {e}"));
        guess = st.q;
        let c = closed(&m, phi1);
        let q: [f64; 4] = st.q.into();
        let dq: [f64; 4] = st.dq.into();
        let d2q: [f64; 4] = st.d2q.into();
        for u in 0..4 {
            let name = RhombicDrive::UNKNOWNS[u];
            assert_close!(q[u], c.q[u], <= tol::SOLVE, "{name} at {phi1}: {} vs {}", q[u], c.q[u]);
            assert_close!(dq[u], c.dq[u], rel = 1e-9, "d{name} at {phi1}: {} vs {}", dq[u], c.dq[u]);
            assert_close!(d2q[u], c.d2q[u], rel = 1e-9, "d2{name} at {phi1}: {} vs {}", d2q[u], c.d2q[u]);
        }
        let pts = [
            (st.out.s1, st.dout.s1, st.d2out.s1),
            (st.out.s2, st.dout.s2, st.d2out.s2),
            (st.out.s4, st.dout.s4, st.d2out.s4),
        ];
        for (p, (s, ds, d2s)) in pts.iter().enumerate() {
            let got = [[s.x, s.y], [ds.x, ds.y], [d2s.x, d2s.y]];
            let want = [c.s[p], c.ds[p], c.d2s[p]];
            for o in 0..3 {
                for xy in 0..2 {
                    let tol = if o == 0 { tol::SOLVE } else { 1e-9 };
                    assert_close!(
                        got[o][xy],
                        want[o][xy],
                        rel = tol,
                        "point {p} order {o} comp {xy} at {phi1}: {} vs {}",
                        got[o][xy],
                        want[o][xy]
                    );
                }
            }
        }
        phi2_min = phi2_min.min(q[0]);
        phi2_max = phi2_max.max(q[0]);
        phi4_min = phi4_min.min(q[1]);
        phi4_max = phi4_max.max(q[1]);
    }
    // The paper: phi4 runs over 2.911..3.616 rad (partly in the 3rd quadrant, no 2 pi jump) and
    // phi2 over -0.167..0.524 for these dimensions.
    assert_close!(phi4_min, 2.911, 1e-3, "{phi4_min}..{phi4_max}");
    assert_close!(phi4_max, 3.616, 1e-3, "{phi4_min}..{phi4_max}");
    assert_close!(phi2_min, -0.167, 1e-3, "{phi2_min}..{phi2_max}");
    assert_close!(phi2_max, 0.524, 1e-3, "{phi2_min}..{phi2_max}");
}

#[test]
fn paper_s1_velocity_sign_is_derived_not_copied() {
    // d/dphi1 of S1.x = l cos(phi1 + psi) is -l sin(phi1 + psi): negative in the first quadrant.
    let m = DRIVE;
    let st = m.solve(0.2).unwrap();
    let expected = -m.l_as1 * (0.2 + m.psi_s1).sin();
    assert_close!(st.dout.s1.x, expected, tol::ULPS);
    assert!(st.dout.s1.x < 0.0);
}

#[test]
fn true_motion_from_analogs() {
    let m = DRIVE;
    let st = m.solve(1.0).unwrap();
    let (w, e) = (12.0, -3.0);
    let mo = st.motion(w, e).unwrap();
    assert_close!(mo.qdot.x_c, st.dq.x_c * w, tol::SOLVE);
    assert_close!(mo.qddot.x_c, st.d2q.x_c * w * w + st.dq.x_c * e, 1e-10);
    assert_close!(mo.out_ddot.s2.y, st.d2out.s2.y * w * w + st.dout.s2.y * e, 1e-10);
    assert!(st.motion(f64::NAN, 0.0).is_err());
}

#[test]
fn decomposition_separates_the_two_groups() {
    // Working group (phi2 then x_c) and displacer group (phi4 then x_f) are independent; the
    // slider coordinates appear linearly and are solved in closed form.
    let blocks = RhombicDrive::BLOCKS;
    assert_eq!(blocks.len(), 4, "{blocks:?}");
    for b in blocks {
        assert_eq!(b.unknowns.len(), 1);
        let u = &b.unknowns[0];
        assert_eq!(b.linear, u.starts_with("x_"), "{b:?}");
    }
    let pos = |n: &str| blocks.iter().position(|b| b.unknowns[0] == n).unwrap();
    assert!(pos("phi2") < pos("x_c"));
    assert!(pos("phi4") < pos("x_f"));
}
