//! Objectives over a sweep with exact gradients: extremes of the rhombic drive's displacer
//! against the paper's closed forms, their gradients and locations against finite differences,
//! and the integral of an output.

use kinloop::Extreme;
use kinloop_fixtures::RhombicDrive;
use std::f64::consts::PI;

use crate::support::{dead_centres, tol};

/// The gallery drive (its centres of mass do not enter the objectives).
const M: RhombicDrive = kinloop_fixtures::rhombic::GALLERY_DRIVE;

/// `docs/papers.md`, paper 000: X_F0 = sqrt((L_B + R_B)^2 - e_B^2), X_Fmin = sqrt((L_B - R_B)^2 - e_B^2).
fn closed_extremes(m: &RhombicDrive) -> (f64, f64) {
    dead_centres(m.l_b, m.r_b, m.e_p - m.de)
}

#[test]
fn displacer_extremes_match_the_paper_with_gradients() {
    let g = M.guess(0.0);
    let max =
        M.sampled(0.0, 2.0 * PI, 73, &g).unwrap().extremum_with_gradient(RhombicDrive::COL.x_f, Extreme::Max).unwrap();
    let min =
        M.sampled(0.0, 2.0 * PI, 73, &g).unwrap().extremum_with_gradient(RhombicDrive::COL.x_f, Extreme::Min).unwrap();
    let (x0, x1) = closed_extremes(&M);
    assert_close!(max.value, x0, tol::SOLVE, "X_F0");
    assert_close!(min.value, x1, tol::SOLVE, "X_Fmin");
    // Gradients of the closed forms, e.g. d X_F0 / d L_B = (L_B + R_B) / X_F0.
    let e_b = M.e_p - M.de;
    let l = RhombicDrive::PARAMS.iter().position(|p| *p == "l_b").unwrap();
    assert_close!(max.grad[l], (M.l_b + M.r_b) / x0, 1e-9);
    assert_close!(min.grad[l], (M.l_b - M.r_b) / x1, 1e-9);
    let e = RhombicDrive::PARAMS.iter().position(|p| *p == "e_p").unwrap();
    assert_close!(max.grad[e], -e_b / x0, 1e-9);
    // The extremum's location moves as finite differences say (the centres of mass, the last
    // four parameters, do not move it: their gradients vanish).
    for p in 0..RhombicDrive::PARAMS.len() {
        let h = 1e-5;
        let at = |s: f64| {
            let mut v = M.param_values();
            v[p] += s;
            let m = RhombicDrive::from_param_values(v);
            m.sampled(0.0, 2.0 * PI, 73, &m.guess(0.0))
                .unwrap()
                .extremum_with_gradient(RhombicDrive::COL.x_f, Extreme::Max)
                .unwrap()
        };
        let (a, b) = (at(h), at(-h));
        let fd_x = (a.x - b.x) / (2.0 * h);
        let fd_v = (a.value - b.value) / (2.0 * h);
        assert_close!(
            max.x_grad[p],
            fd_x,
            1e-6 * (1.0 + fd_x.abs()),
            "{}: {} vs {fd_x}",
            RhombicDrive::PARAMS[p],
            max.x_grad[p]
        );
        assert_close!(max.grad[p], fd_v, 1e-7 * (1.0 + fd_v.abs()));
    }
}

#[test]
fn integral_of_an_output_and_its_gradient() {
    let (v, g) =
        M.sampled(0.0, 2.0 * PI, 181, &M.guess(0.0)).unwrap().integral_with_gradient(RhombicDrive::COL.gap).unwrap();
    // Independent: trapezoid over the closed-form gap X_F - X_C.
    let e_b = M.e_p - M.de;
    let gap = |m: &RhombicDrive, phi: f64| {
        let s4 = (e_b + m.r_b * (phi + m.gamma).sin()) / m.l_b;
        let s2 = (m.e_p + m.r_p * phi.sin()) / m.l_p;
        let x_f = m.r_b * (phi + m.gamma).cos() + m.l_b * (1.0 - s4 * s4).sqrt();
        x_f - (m.r_p * phi.cos() - m.l_p * (1.0 - s2 * s2).sqrt())
    };
    let h = 2.0 * PI / 180.0;
    let trapezoid = |m: &RhombicDrive| -> f64 {
        (0..=180).map(|k| if k == 0 || k == 180 { 0.5 } else { 1.0 } * h * gap(m, k as f64 * h)).sum()
    };
    let reference = trapezoid(&M);
    assert_close!(v, reference, 1e-10, "{v} vs {reference}");
    let l = RhombicDrive::PARAMS.iter().position(|p| *p == "l_b").unwrap();
    let dh = 1e-6;
    let mut mp = M;
    mp.l_b += dh;
    let mut mm = M;
    mm.l_b -= dh;
    // The gradient against finite differences of the independent closed-form quadrature.
    let fd = (trapezoid(&mp) - trapezoid(&mm)) / (2.0 * dh);
    assert_close!(g[l], fd, 1e-6 * fd.abs(), "{} vs {fd}", g[l]);
}

/// The integral is over the input whatever parametrises the range: over a range given as a path
/// (whose parameter is the fraction of the path, `0 ..= 1`) it is the same integral over the
/// input as over the sweep of the same samples, not that divided by the path's length.
#[test]
fn the_integral_over_a_path_is_over_the_input() {
    use kinloop::analysis::Sampled;
    let col = RhombicDrive::COL.gap;
    let by_sweep = M.sampled(0.0, 2.0 * PI, 181, &M.guess(0.0)).unwrap().integral_with_gradient(col).unwrap();
    let path = Sampled::path(&M, [0.0], [2.0 * PI], 181, M.guess(0.0)).unwrap();
    let (v, g) = path.integral_with_gradient(col).unwrap();
    // The same samples, their inputs made the same way up to rounding: the sums agree to a few
    // ulps of the integral's magnitude (about 2 pi times the gap's), far from a factor 2 pi.
    assert_close!(v, by_sweep.0, 1e-12 * by_sweep.0.abs(), "{v} vs {}", by_sweep.0);
    for (a, b) in g.iter().zip(&by_sweep.1) {
        assert_close!(*a, *b, 1e-12 * (1.0 + b.abs()), "{a} vs {b}");
    }
}

/// An extremum at a singular crossing the sweep passed has no gradient, and says so at every
/// scale and sample count. The change-point four-bar (1, 2, 2.5, 3.5: `a + d = b + c`) has the
/// joint's `x` at its minimum `d - c` exactly at the crossing `phi = pi` (C on the frame, the
/// nearest the rocker's circle comes to the crank's pivot), a corner; off `a + d = b + c` the
/// crossing is gone (limit positions, or no change of mode), so the minimum is not
/// differentiable in the parameters. The state asked for at the crossing was a pivot band past
/// it: the minimum came back at `phi` 7e-4 from `pi`, its value 2.2e-7 of the crank above
/// `d - c`, with a gradient of that point, or as `NearSingular`, as the sample count chose.
/// The smooth maximum is still given (its gradients are checked on smooth extremes above).
#[test]
fn an_extremum_at_a_singular_crossing_has_no_gradient() {
    use kinloop::analysis::Sampled;
    use kinloop::{AtSingular, Error, SweepConfig};
    use kinloop_fixtures::FourBarSens;
    for s in [1.0, 1e-3, 1e-6] {
        let m = FourBarSens { a: s, b: 2.0 * s, c: 2.5 * s, d: 3.5 * s };
        let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
        for n in [64, 73, 100] {
            let run = Sampled::sweep_with(&m, 0.0, 6.2, n, [0.5, 1.5], cfg).unwrap();
            let min = run.range(FourBarSens::COL.pc.x).unwrap().min;
            // The closed form: C at (d - c, 0) at phi = pi.
            assert!((min.value - s).abs() < 1e-12 * s && (min.x - PI).abs() < 1e-9, "scale {s}, {n}: {min:?}");
            let r = run.extremum_with_gradient(FourBarSens::COL.pc.x, Extreme::Min);
            assert!(
                matches!(&r, Err(Error::InvalidArgument(e)) if e.contains("minimum of `pc.x` lies at a singular crossing")),
                "scale {s}, {n} samples: {r:?}"
            );
            assert!(run.extremum_with_gradient(FourBarSens::COL.pc.x, Extreme::Max).is_ok(), "scale {s}, {n}");
        }
    }
}

kinloop::mechanism! {
    /// A cam law rising at uniform velocity to `h` at `phi = p0` and returning to 0 at a full
    /// turn: its peak is a corner of the motion (a kink) at `p0`, of value `h`, whatever `p0`.
    #[kinloop(sensitivities)]
    pub struct PeakedLaw {
        params h, p0;
        input phi;
        unknowns s = 0;
        eq law: s == h * min(phi / p0, (6.283185307179586 - phi) / (6.283185307179586 - p0));
    }
}

/// A peak at a corner of the motion that falls on a sample has the corner's gradients, as one
/// between samples has: `d h / d (h, p0) = (1, 0)`, and the corner `phi = p0` moves by `(0, 1)`.
/// The sample, one side's value, was the largest candidate but no located extreme, and was
/// taken for an end of the range: one side's `d s / d p0 = -phi h / p0^2` (-0.5 h) came back,
/// and `x_grad = 0`.
#[test]
fn a_peak_at_a_kink_on_a_sample_has_the_corners_gradients() {
    // (from, to, samples): the corner at 2 is the 21st of 41 samples, the middle one of 3.
    for (from, to, n) in [(0.0, 4.0, 41), (1.0, 3.0, 3)] {
        for h in [1e-6, 1.0, 1e6] {
            let m = PeakedLaw { h, p0: 2.0 };
            let run = kinloop::analysis::Sampled::sweep(&m, from, to, n, [0.0]).unwrap();
            assert!(run.path_values().contains(&2.0), "the corner is a sample");
            let top = run.extremum_with_gradient::<2>(PeakedLaw::COL.s, Extreme::Max).unwrap();
            assert!(top.x == 2.0 && (top.value - h).abs() < 1e-15 * h, "{n}, h {h}: {top:?}");
            // The sides are taken a few units of rounding from the corner: their derivatives are
            // the branches' to about 1e-14 (measured 1e-14), in the units of each derivative.
            assert!((top.grad[0] - 1.0).abs() < 1e-12 && top.grad[1].abs() < 1e-12 * h, "{n}, h {h}: {top:?}");
            assert!(top.x_grad[0].abs() < 1e-12 / h && (top.x_grad[1] - 1.0).abs() < 1e-12, "{n}, h {h}: {top:?}");
        }
    }
}
