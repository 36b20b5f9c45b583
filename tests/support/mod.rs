//! Plain numerics for the tests' independent checks (closed forms solved without kinloop).

use std::f64::consts::{PI, TAU};

/// A root of `f` in `[lo, hi]` by bisection; `f` must change sign there.
pub fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let flo = f(lo);
    assert!(flo * f(hi) < 0.0, "no sign change on [{lo}, {hi}]");
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (f(mid) < 0.0) == (flo < 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Where `f` is largest on `[0, span)`: the best of `n` equally spaced samples, refined by golden
/// sections within one spacing on either side.
pub fn argmax(f: impl Fn(f64) -> f64, span: f64, n: usize) -> f64 {
    let best = (0..n).map(|i| span * i as f64 / n as f64).max_by(|a, b| f(*a).total_cmp(&f(*b))).unwrap();
    let h = span / n as f64;
    let (mut lo, mut hi) = (best - h, best + h);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(c) > f(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    0.5 * (lo + hi)
}

/// Where `f` is stationary in `[lo, hi]`: a root of its Richardson-extrapolated central
/// difference (step 1e-3, truncation ~1e-15 |f^(5)|, rounding ~1e-13 |f|) by bisection; the
/// derivative must change sign there. Located to ~1e-13 / |f''|.
pub fn stationary(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    bisect(|x| richardson_first(&f, x, 1e-3), lo, hi)
}

/// `|a - b| <= rel * max(1, |b|)`: relative tolerance, absolute near zero.
pub fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1.0)
}

/// An angle wrapped into `[-pi, pi)`.
pub fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(TAU) - PI
}

/// Central differences with one Richardson step (h and h/2): (first, second) derivative with
/// truncation error O(h^4) (~h^4/480 |q^(5)| and less for the second); position errors e
/// contribute ~e/h and ~5e/h^2.
pub fn richardson(f: impl Fn(f64) -> f64, x: f64, h: f64) -> (f64, f64) {
    let d2 = |h: f64| (f(x + h) - 2.0 * f(x) + f(x - h)) / (h * h);
    (richardson_first(&f, x, h), (4.0 * d2(h / 2.0) - d2(h)) / 3.0)
}

/// The first derivative of `f` at `x` by central differences with one Richardson step (h and
/// h/2): truncation error ~h^4/480 |f^(5)|; errors e in the values contribute ~e/h.
pub fn richardson_first(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    let d1 = |h: f64| (f(x + h) - f(x - h)) / (2.0 * h);
    (4.0 * d1(h / 2.0) - d1(h)) / 3.0
}

/// C from the circles (B, rb) and (D, rd), on side `side` of B -> D (+1 left, -1 right).
pub fn circle_point(bx: f64, by: f64, rb: f64, dx: f64, dy: f64, rd: f64, side: f64) -> (f64, f64) {
    let (ux, uy) = (dx - bx, dy - by);
    let dist = ux.hypot(uy);
    let along = (rb * rb - rd * rd + dist * dist) / (2.0 * dist);
    let h = (rb * rb - along * along).max(0.0).sqrt();
    (bx + (along * ux - side * h * uy) / dist, by + (along * uy + side * h * ux) / dist)
}
