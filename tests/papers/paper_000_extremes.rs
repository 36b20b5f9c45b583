//! Paper 000, Fig. 1 (`docs/papers.md`), the drive of `examples/rhombic_drive.rs`: extreme
//! positions of the working piston and the displacer located as roots of their velocity analogs,
//! against the paper's `X_F0 = sqrt((L_B + R_B)^2 - e_B^2)`, `X_Fmin = sqrt((L_B - R_B)^2 -
//! e_B^2)` and the same construction for the piston (crank and rod collinear); the crank angles
//! there from the same triangles; strokes and phase shifts. The closed forms themselves are
//! checked against the stationary points of the explicit slider-crank positions.

use kinloop::analysis::Extreme;
use std::f64::consts::TAU;

use kinloop_fixtures::RhombicDrive;

use crate::support::{dead_centres, stationary, tol, wrap};

#[test]
fn extreme_positions_strokes_and_phase_shift_match_the_closed_forms() {
    let m = RhombicDrive::default();
    let turn = m.sampled(0.0, TAU, 361, &m.guess(0.0)).unwrap();
    let xc = turn.range(RhombicDrive::COL.x_c).unwrap();
    let xf = turn.range(RhombicDrive::COL.x_f).unwrap();

    let e_b = m.e_p - m.de;
    let (x_f0, x_fmin) = dead_centres(m.l_b, m.r_b, e_b);
    let (c_outer, c_inner) = dead_centres(m.l_p, m.r_p, m.e_p);
    let (c_outer, c_inner) = (-c_outer, -c_inner);
    // The positions carry the Newton tolerance (1e-12 on the loop residual, well conditioned).
    assert_close!(xf.max.value, x_f0, tol::SOLVE, "X_F0");
    assert_close!(xf.min.value, x_fmin, tol::SOLVE, "X_Fmin");
    assert_close!(xc.min.value, c_outer, tol::SOLVE, "X_C outer");
    assert_close!(xc.max.value, c_inner, tol::SOLVE, "X_C inner");
    assert_close!(xf.span(), x_f0 - x_fmin, tol::SOLVE, "displacer stroke");
    assert_close!(xc.span(), c_inner - c_outer, tol::SOLVE, "piston stroke");

    // Crank angles: the arm points along (outer) or against (inner) the line from A to the pin.
    let at = [
        (xc.min.x, f64::atan2(-m.e_p, c_outer)),
        (xc.max.x, f64::atan2(m.e_p, -c_inner)),
        (xf.max.x, f64::atan2(-e_b, x_f0) - m.gamma),
        (xf.min.x, f64::atan2(e_b, -x_fmin) - m.gamma),
    ];
    // A root of the analog (~1e-13 accurate analogs, curvature ~1) is located to ~1e-12; the
    // independent angle is exact to rounding.
    for (got, want) in at {
        assert!(wrap(got - want).abs() < 1e-10, "{got} vs {want}");
    }
    // The velocity analogs vanish there, and they are the only interior extremes of a turn.
    let e = turn.extremes(RhombicDrive::COL.x_f).unwrap();
    assert_eq!(e.len(), 2);
    assert!(e.iter().all(|e| e.at.d1.abs() < 1e-12));
    assert_eq!(e.iter().filter(|e| e.kind == Extreme::Max).count(), 1);

    // Phase shift between corresponding extremes, in degrees modulo a turn.
    let shift = |a: f64, b: f64| (a - b).to_degrees().rem_euclid(360.0);
    let outer = shift(xf.max.x, xc.min.x);
    let inner = shift(xf.min.x, xc.max.x);
    assert_close!(outer, shift(at[2].1, at[0].1), 1e-8);
    assert_close!(inner, shift(at[3].1, at[1].1), 1e-8);

    // The closed forms the example prints, against the stationary points of the explicit
    // positions (each slider-crank's triangle solved for the slider): values exact to rounding,
    // locations to ~1e-13 (see `stationary`).
    let x_c = |a: f64| m.r_p * a.cos() - (m.l_p.powi(2) - (m.e_p + m.r_p * a.sin()).powi(2)).sqrt();
    let x_f =
        |a: f64| m.r_b * (a + m.gamma).cos() + (m.l_b.powi(2) - (e_b + m.r_b * (a + m.gamma).sin()).powi(2)).sqrt();
    let position = |k: usize, a: f64| if k < 2 { x_c(a) } else { x_f(a) };
    let mut found = [0.0; 4];
    for (k, ((_, want_at), want)) in at.into_iter().zip([c_outer, c_inner, x_f0, x_fmin]).enumerate() {
        let f = |a: f64| position(k, a);
        found[k] = stationary(f, want_at - 0.3, want_at + 0.3);
        assert_close!(f(found[k]), want, tol::SOLVE, "extreme {k}: {} vs {want}", f(found[k]));
        assert!(wrap(found[k] - want_at).abs() < 1e-10, "extreme {k} at {} vs {want_at}", found[k]);
    }
    // Strokes and phase shifts from the explicit positions alone.
    assert_close!(xc.span(), x_c(found[1]) - x_c(found[0]), tol::SOLVE);
    assert_close!(xf.span(), x_f(found[2]) - x_f(found[3]), tol::SOLVE);
    assert_close!(outer, shift(found[2], found[0]), 1e-8);
    assert_close!(inner, shift(found[3], found[1]), 1e-8);
}

#[test]
fn extremes_follow_the_drive_when_its_dimensions_change() {
    // A second, more eccentric drive: the helpers and the closed forms still agree.
    let m = RhombicDrive { r_b: 0.8, l_b: 2.6, e_p: 0.9, de: -0.3, gamma: 2.1, ..RhombicDrive::default() };
    let turn = m.sampled(0.0, TAU, 181, &m.guess(0.0)).unwrap();
    let xf = turn.range(RhombicDrive::COL.x_f).unwrap();
    let e_b = m.e_p - m.de;
    let (x_f0, x_fmin) = dead_centres(m.l_b, m.r_b, e_b);
    assert_close!(xf.max.value, x_f0, tol::SOLVE, "X_F0");
    assert_close!(xf.min.value, x_fmin, tol::SOLVE, "X_Fmin");
    assert!(wrap(xf.max.x - (f64::atan2(-e_b, xf.max.value) - m.gamma)).abs() < 1e-10);
}
