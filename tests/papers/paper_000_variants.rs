//! Paper 000, Figs. 2 and 3 (`docs/papers.md`; equations not published), the variants of
//! `examples/rhombic_variants.rs`: the loops close along a sweep; the analogs agree with finite
//! differences; positions agree with an independent triangle-by-triangle construction; with the
//! third joint on the crank pin both reduce to Fig. 1 and match its published closed form
//! (positions, velocity and acceleration analogs); the strokes the example prints.

use kinloop::Kin;
use std::f64::consts::{PI, TAU};

use kinloop_fixtures::{DisplacerRodDrive, WorkingRodDrive};

use crate::support::{argmax, dead_centres, newton_to_default_step, richardson, stationary, tol, wrap};

/// Fig. 1's published closed form (paper 000) with one crank pin (R_P = R_B = r,
/// gamma = 0): (positions, velocity analogs, acceleration analogs) of [phi2, phi4, X_C, X_F].
fn fig1(r: f64, l_p: f64, l_b: f64, e_p: f64, de: f64, phi1: f64) -> [[f64; 4]; 3] {
    let (lam_p, lam_b) = (r / l_p, r / l_b);
    let (k_p, k_b) = (e_p / r, (e_p - de) / r);
    let phi2 = (lam_p * (k_p + phi1.sin())).asin();
    let phi4 = PI - (lam_b * (k_b + phi1.sin())).asin();
    let (c2, c4) = (phi2.cos(), phi4.cos());
    let x_c = l_p * (lam_p * phi1.cos() - c2);
    let x_f = l_b * (lam_b * phi1.cos() - c4);
    let u21 = lam_p * phi1.cos() / c2;
    let u41 = lam_b * phi1.cos() / c4;
    let v_c = l_p * (u21 * phi2.sin() - lam_p * phi1.sin());
    let v_f = l_b * (u41 * phi4.sin() - lam_b * phi1.sin());
    let e2 = (u21 * u21 * phi2.sin() - lam_p * phi1.sin()) / c2;
    let e4 = (u41 * u41 * phi4.sin() - lam_b * phi1.sin()) / c4;
    let a_c = l_p * (e2 * phi2.sin() + u21 * u21 * c2 - lam_p * phi1.cos());
    let a_f = l_b * (e4 * phi4.sin() + u41 * u41 * c4 - lam_b * phi1.cos());
    [[phi2, phi4, x_c, x_f], [u21, u41, v_c, v_f], [e2, e4, a_c, a_f]]
}

#[test]
fn loops_close_and_positions_match_a_triangle_construction() {
    let m2 = DisplacerRodDrive::default();
    for s in m2.sweep(0.0, TAU, 721, &m2.guess(0.0)).unwrap() {
        let s = s.unwrap();
        let phi1 = s.input.phi1;
        assert!(m2.residual(phi1, &s.q).iter().all(|r| r.abs() <= tol::SOLVE), "Fig. 2 at {phi1}");
        // Independent: the displacer group as in Fig. 1, then D, then the working rod from D.
        let phi4 = PI - ((m2.e_p + m2.r * phi1.sin() - m2.de) / m2.l_b).asin();
        let x_f = m2.r * phi1.cos() - m2.l_b * phi4.cos();
        let (dx, dy) = (x_f + m2.l_fd * (phi4 + m2.gamma_b).cos(), m2.de + m2.l_fd * (phi4 + m2.gamma_b).sin());
        let phi2 = (dy / m2.l_p).asin();
        let x_c = dx - m2.l_p * phi2.cos();
        for (got, want) in [(s.q.phi4, phi4), (s.q.x_f, x_f), (s.q.phi2, phi2), (s.q.x_c, x_c), (s.out.d.x, dx)] {
            assert_close!(got, want, tol::SOLVE, "Fig. 2 at {phi1}: {got} vs {want}");
        }
    }
    let m3 = WorkingRodDrive::default();
    for s in m3.sweep(0.0, TAU, 721, &m3.guess(0.0)).unwrap() {
        let s = s.unwrap();
        let phi1 = s.input.phi1;
        assert!(m3.residual(phi1, &s.q).iter().all(|r| r.abs() <= tol::SOLVE), "Fig. 3 at {phi1}");
        let phi2 = ((m3.e_p + m3.r * phi1.sin()) / m3.l_p).asin();
        let x_c = m3.r * phi1.cos() - m3.l_p * phi2.cos();
        let (dx, dy) = (x_c + m3.l_cd * (phi2 + m3.gamma_p).cos(), m3.l_cd * (phi2 + m3.gamma_p).sin());
        let phi4 = PI - ((dy - m3.de) / m3.l_b).asin();
        let x_f = dx - m3.l_b * phi4.cos();
        for (got, want) in [(s.q.phi2, phi2), (s.q.x_c, x_c), (s.q.phi4, phi4), (s.q.x_f, x_f), (s.out.d.y, dy)] {
            assert_close!(got, want, tol::SOLVE, "Fig. 3 at {phi1}: {got} vs {want}");
        }
    }
}

#[test]
fn analogs_match_finite_differences() {
    let h = 1e-2;
    let m2 = DisplacerRodDrive::default();
    let m3 = WorkingRodDrive::default();
    for i in 0..24 {
        let phi1 = 0.1 + TAU * i as f64 / 24.0;
        let s2 = m2.solve(phi1).unwrap();
        let q2 = |x: f64| -> [f64; 4] { m2.position_with(x, &s2.q, &newton_to_default_step()).unwrap().0.into() };
        let s3 = m3.solve(phi1).unwrap();
        let q3 = |x: f64| -> [f64; 4] { m3.position_with(x, &s3.q, &newton_to_default_step()).unwrap().0.into() };
        let (dq2, d2q2): ([f64; 4], [f64; 4]) = (s2.dq.into(), s2.d2q.into());
        let (dq3, d2q3): ([f64; 4], [f64; 4]) = (s3.dq.into(), s3.d2q.into());
        for u in 0..4 {
            // With h = 1e-2: truncation ~1e-10, position errors 5e-13 give ~5e-11 and ~3e-8.
            let (f1, f2) = richardson(|x| q2(x)[u], phi1, h);
            assert_close!(
                dq2[u],
                f1,
                rel = tol::FD_FIRST,
                "Fig. 2 d{} at {phi1}: {} vs {f1}",
                DisplacerRodDrive::UNKNOWNS[u],
                dq2[u]
            );
            assert_close!(
                d2q2[u],
                f2,
                rel = tol::FD_SECOND,
                "Fig. 2 d2{} at {phi1}: {} vs {f2}",
                DisplacerRodDrive::UNKNOWNS[u],
                d2q2[u]
            );
            let (f1, f2) = richardson(|x| q3(x)[u], phi1, h);
            assert_close!(
                dq3[u],
                f1,
                rel = tol::FD_FIRST,
                "Fig. 3 d{} at {phi1}: {} vs {f1}",
                WorkingRodDrive::UNKNOWNS[u],
                dq3[u]
            );
            assert_close!(
                d2q3[u],
                f2,
                rel = tol::FD_SECOND,
                "Fig. 3 d2{} at {phi1}: {} vs {f2}",
                WorkingRodDrive::UNKNOWNS[u],
                d2q3[u]
            );
        }
    }
}

/// Positions, velocity and acceleration analogs of `[phi2, phi4, X_C, X_F]` in a state (flat, its
/// unknowns in the declared order `unknowns`) against Fig. 1's closed form.
fn assert_fig1<const NO: usize>(fig: &str, unknowns: [&str; 4], s: &Kin<4, 1, NO>, want: [[f64; 4]; 3]) {
    let at = ["phi2", "phi4", "x_c", "x_f"].map(|name| unknowns.iter().position(|u| *u == name).unwrap());
    let got = [at.map(|u| s.q[u]), at.map(|u| s.dq[u][0]), at.map(|u| s.d2q[u][0][0])];
    for o in 0..3 {
        for u in 0..4 {
            let tol = if o == 0 { tol::SOLVE } else { 1e-9 };
            assert_close!(got[o][u], want[o][u], rel = tol, "{fig} order {o} #{u} at {}", s.x[0]);
        }
    }
}

#[test]
fn third_joint_on_the_crank_pin_reduces_to_fig_1() {
    let d2 = DisplacerRodDrive { l_fd: 3.5, gamma_b: 0.0, ..DisplacerRodDrive::default() };
    let d3 = WorkingRodDrive { l_cd: 3.0, gamma_p: 0.0, ..WorkingRodDrive::default() };
    for s in d2.sweep(0.0, TAU, 721, &d2.guess(0.0)).unwrap() {
        let s = s.unwrap();
        let c = fig1(d2.r, d2.l_p, d2.l_b, d2.e_p, d2.de, s.input.phi1);
        assert_fig1("Fig. 2", DisplacerRodDrive::UNKNOWNS, &s.flat, c);
    }
    for s in d3.sweep(0.0, TAU, 721, &d3.guess(0.0)).unwrap() {
        let s = s.unwrap();
        let c = fig1(d3.r, d3.l_p, d3.l_b, d3.e_p, d3.de, s.input.phi1);
        assert_fig1("Fig. 3", WorkingRodDrive::UNKNOWNS, &s.flat, c);
    }
}

/// The extremes of `f` over a turn, `[(at min, min), (at max, max)]`: a scan of 3600 samples,
/// refined to the stationary points (located to ~1e-13, values exact to rounding).
fn extremes(f: impl Fn(f64) -> f64) -> [(f64, f64); 2] {
    let at_max = argmax(&f, TAU, 3600);
    let at_min = argmax(|x| -f(x), TAU, 3600);
    [at_min, at_max].map(|a| {
        let x = stationary(&f, a - 0.01, a + 0.01);
        (x, f(x))
    })
}

#[test]
fn strokes_and_extremes_printed_by_the_example() {
    let m2 = DisplacerRodDrive::default();
    let t2 = m2.sampled(0.0, TAU, 361, &m2.guess(0.0)).unwrap();
    let (c, f) = (t2.range(DisplacerRodDrive::COL.x_c).unwrap(), t2.range(DisplacerRodDrive::COL.x_f).unwrap());
    let e_b = m2.e_p - m2.de;
    // The displacer group of Fig. 2 is Fig. 1's: the paper's X_F0 and X_Fmin.
    let (x_f0, x_fmin) = dead_centres(m2.l_b, m2.r, e_b);
    assert_close!(f.max.value, x_f0, tol::SOLVE);
    assert_close!(f.min.value, x_fmin, tol::SOLVE);
    assert_close!(f.span(), x_f0 - x_fmin, tol::SOLVE);
    // The piston's extremes of Fig. 2 are where its analog vanishes: against the stationary
    // points of the triangle construction (independent of the helpers).
    let x_c = |phi1: f64| {
        let phi4 = PI - ((m2.e_p + m2.r * phi1.sin() - m2.de) / m2.l_b).asin();
        let x_f = m2.r * phi1.cos() - m2.l_b * phi4.cos();
        let (dx, dy) = (x_f + m2.l_fd * (phi4 + m2.gamma_b).cos(), m2.de + m2.l_fd * (phi4 + m2.gamma_b).sin());
        dx - m2.l_p * (dy / m2.l_p).asin().cos()
    };
    let [lo, hi] = extremes(x_c);
    assert_close!(c.min.value, lo.1, tol::SOLVE);
    assert_close!(c.max.value, hi.1, tol::SOLVE);
    assert_close!(c.span(), hi.1 - lo.1, tol::SOLVE);
    assert!(wrap(c.min.x - lo.0).abs() < 1e-9 && wrap(c.max.x - hi.0).abs() < 1e-9);

    let m3 = WorkingRodDrive::default();
    let t3 = m3.sampled(0.0, TAU, 361, &m3.guess(0.0)).unwrap();
    let (c, f) = (t3.range(WorkingRodDrive::COL.x_c).unwrap(), t3.range(WorkingRodDrive::COL.x_f).unwrap());
    let (c_outer, c_inner) =
        (-((m3.l_p + m3.r).powi(2) - m3.e_p * m3.e_p).sqrt(), -((m3.l_p - m3.r).powi(2) - m3.e_p * m3.e_p).sqrt());
    assert_close!(c.min.value, c_outer, tol::SOLVE);
    assert_close!(c.span(), c_inner - c_outer, tol::SOLVE);
    // The displacer of Fig. 3 from the triangle construction; the phase shifts the example
    // prints from the stationary points of both constructions.
    let (x_c, x_f) = (
        |phi1: f64| m3.r * phi1.cos() - m3.l_p * ((m3.e_p + m3.r * phi1.sin()) / m3.l_p).asin().cos(),
        |phi1: f64| {
            let phi2 = ((m3.e_p + m3.r * phi1.sin()) / m3.l_p).asin();
            let x_c = m3.r * phi1.cos() - m3.l_p * phi2.cos();
            let (dx, dy) = (x_c + m3.l_cd * (phi2 + m3.gamma_p).cos(), m3.l_cd * (phi2 + m3.gamma_p).sin());
            dx - m3.l_b * (PI - ((dy - m3.de) / m3.l_b).asin()).cos()
        },
    );
    let ([c_lo, c_hi], [f_lo, f_hi]) = (extremes(x_c), extremes(x_f));
    assert_close!(f.span(), f_hi.1 - f_lo.1, tol::SOLVE);
    let shift = |a: f64, b: f64| (a - b).to_degrees().rem_euclid(360.0);
    assert_close!(shift(f.max.x, c.min.x), shift(f_hi.0, c_lo.0), 1e-6);
    assert_close!(shift(f.min.x, c.max.x), shift(f_lo.0, c_hi.0), 1e-6);
}
