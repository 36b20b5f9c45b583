//! The rhombic drive's phase shift and stroke ratio the `synthesis` example prints (its third
//! part), with the gradients its Levenberg–Marquardt solve runs on, against the drive's
//! positions written from its loops (`docs/papers.md`, paper 000), never solved by kinloop:
//! `sin phi2 = (e_p + r_p sin phi1) / l_p`, `X_C = r_p cos phi1 - l_p cos phi2` (`phi2` near 0),
//! `sin phi4 = (e_p + r_b sin(phi1 + gamma) - de) / l_b`,
//! `X_F = r_b cos(phi1 + gamma) - l_b cos phi4` (`phi4` near pi); the extremes where the slopes
//! `X_C' = r_p (cos phi1 tan phi2 - sin phi1)` and
//! `X_F' = r_b (cos(phi1 + gamma) tan phi4 - sin(phi1 + gamma))`, differentiated by hand,
//! change sign, bisected to adjacent doubles; the gradients by central differences of those.

// The example's own functions, so that what is checked is what it prints (its `main`, its
// searches and its drawing are not called here).
#[allow(dead_code)]
#[path = "../synthesis.rs"]
mod synthesis;

use std::f64::consts::{PI, TAU};
use synthesis::{START, characteristics, phase_shift_design, rhombic};

/// `[X_C, X_F]` and their slopes by the crank angle, for `x = [r_b, gamma]`.
fn drive(x: [f64; 2], phi1: f64) -> ([f64; 2], [f64; 2]) {
    let m = rhombic(&x);
    let s2 = (m.e_p + m.r_p * phi1.sin()) / m.l_p;
    let c2 = (1.0 - s2 * s2).sqrt();
    let t = phi1 + m.gamma;
    let s4 = (m.e_p + m.r_b * t.sin() - m.de) / m.l_b;
    let c4 = -(1.0 - s4 * s4).sqrt();
    let values = [m.r_p * phi1.cos() - m.l_p * c2, m.r_b * t.cos() - m.l_b * c4];
    let slopes = [m.r_p * (phi1.cos() * s2 / c2 - phi1.sin()), m.r_b * (t.cos() * s4 / c4 - t.sin())];
    (values, slopes)
}

/// The crank angle in `[0, 2 pi)` and the value of the largest (`sign` 1) or smallest (`sign`
/// -1) of `X_C` (`u` 0) or `X_F` (`u` 1): the sample of 3,600 nearest it, then the sign change of
/// the slope beside it bisected to adjacent doubles.
fn extreme(x: [f64; 2], u: usize, sign: f64) -> (f64, f64) {
    let n = 3600;
    let at = |k: usize| TAU * k as f64 / n as f64;
    let best = (0..n).max_by(|&a, &b| (sign * drive(x, at(a)).0[u]).total_cmp(&(sign * drive(x, at(b)).0[u])));
    let k = best.expect("samples");
    // The slope times `sign` falls through zero at the extreme: positive before, negative after.
    let (mut lo, mut hi) = (at(k) - TAU / n as f64, at(k) + TAU / n as f64);
    let rising = |p: f64| sign * drive(x, p).1[u] > 0.0;
    assert!(rising(lo) && !rising(hi), "u {u}, sign {sign}: a single extreme about {}", at(k));
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if rising(mid) { lo = mid } else { hi = mid }
    }
    let p = 0.5 * (lo + hi);
    (p.rem_euclid(TAU), drive(x, p).0[u])
}

/// Phase shift (from the piston's outer dead centre, its smallest `X_C`, to the displacer's,
/// its largest `X_F`, in `(-pi, pi]`) and stroke ratio, from the positions written out.
fn written_out(x: [f64; 2]) -> [f64; 2] {
    let ((c_min_at, c_min), (_, c_max)) = (extreme(x, 0, -1.0), extreme(x, 0, 1.0));
    let ((f_max_at, f_max), (_, f_min)) = (extreme(x, 1, 1.0), extreme(x, 1, -1.0));
    [(f_max_at - c_min_at + PI).rem_euclid(TAU) - PI, (f_max - f_min) / (c_max - c_min)]
}

/// Phase shift and ratio to 1e-9 (the located extremes are within a few ulps of the crank angle
/// on both sides, and kinloop's, located by Newton on the velocity analog, within its residual
/// tolerance); gradients to 1e-6 of their size: central differences with steps of 1e-5, whose
/// truncation error is `h^2 / 6` times the third derivative (1e-10 for third derivatives up to
/// 10) and whose rounding error is about `1e-15 / h` = 1e-10.
#[test]
fn the_printed_phase_shift_and_stroke_ratio_agree_with_the_loops_written_out() -> Result<(), kinloop::Error> {
    for x in [START, [1.0, 1.1], [1.5, 0.4]] {
        let (got, jac) = characteristics(&x)?;
        let want = written_out(x);
        for i in 0..2 {
            assert!((got[i] - want[i]).abs() <= 1e-9, "{x:?}, characteristic {i}: {} vs {}", got[i], want[i]);
        }
        let h = 1e-5;
        for k in 0..2 {
            let (mut up, mut down) = (x, x);
            up[k] += h;
            down[k] -= h;
            let (a, b) = (written_out(up), written_out(down));
            for i in 0..2 {
                let fd = (a[i] - b[i]) / (2.0 * h);
                let size = fd.abs().max(1e-3);
                assert!((jac[i][k] - fd).abs() <= 1e-6 * size, "{x:?}: d{i}/d{k} {} vs {fd}", jac[i][k]);
            }
        }
    }
    // The design the example prints reaches its target, as the positions written out say.
    let (start, target, lm) = phase_shift_design()?;
    assert_eq!(start, characteristics(&START)?.0);
    let reached = written_out(lm.x);
    assert!(
        (reached[0] - target[0]).abs() <= 1e-8 && (reached[1] - target[1]).abs() <= 1e-8,
        "{reached:?} vs {target:?}"
    );
    Ok(())
}
