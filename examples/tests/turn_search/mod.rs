//! A brute-force search over one turn of an input, written independently of kinloop, which the
//! examples' tests hold what the examples print against.

use std::f64::consts::TAU;

/// The input angle (degrees in `[0, 360)`) and value of the smallest of `f` over a turn: the best
/// of 36,000 samples, refined by golden sections between its neighbours down to 1e-13 rad.
pub fn smallest(f: impl Fn(f64) -> f64) -> (f64, f64) {
    let n = 36_000;
    let step = TAU / n as f64;
    let best = (0..n).map(|k| k as f64 * step).min_by(|a, b| f(*a).total_cmp(&f(*b))).expect("samples");
    let (mut a, mut b) = (best - step, best + step);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    while b - a > 1e-13 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if f(x1) < f(x2) { b = x2 } else { a = x1 }
    }
    let x = 0.5 * (a + b);
    (x.to_degrees().rem_euclid(360.0), f(x))
}

/// The difference of two angles in degrees, across the turn's seam.
#[allow(dead_code)] // not every test binary compares angles
pub fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    d.min(360.0 - d)
}
