//! Plain numerics for the tests' independent checks (closed forms solved without kinloop).

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
