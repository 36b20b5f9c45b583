//! `Sampled::unbalance` and `Sampled::fourier` across singular crossings (change points), with
//! samples between the crossings and at them: the Grashof-equal four-bar
//! of `limits_crossing` (`a + d = b + c`), whose links lie stretched along the frame at
//! `phi = pi`, where the sweep passes from one assembly mode to the other, and back at
//! `3 pi`: two crank turns are one period. The joint's `x` has its minimum at the crossing
//! itself, where its analog changes sign, and so has the residual after the first harmonic its
//! largest magnitude: the search refining that root stepped into the crossing's band and the
//! whole call failed with `NearSingular`. Checked against the joint by construction (circle
//! intersection on the branch the sweep follows), its harmonics summed from the same sample
//! points, the residual's largest magnitude by brute force, at three length scales.

use crate::support::{circle_point, tol};
use kinloop::analysis::Sampled;
use kinloop::{AtSingular, SweepConfig};
use kinloop_fixtures::FourBar;
use std::f64::consts::{PI, TAU};

/// Two crank turns: the period of a mechanism that changes mode at each pass through `pi`.
const PERIOD: f64 = 2.0 * TAU;

/// 74 intervals: the crossings at `pi` and `3 pi` lie between samples, not on them.
const SAMPLES: usize = 75;

/// 72 intervals (every 10 degrees): the crossings are samples, which the sweep cannot land on.
const ON_CROSSINGS: usize = 73;

/// The joint C of the four-bar (1, 2, 2.5, 3.5) times `s` at `phi`, in units of `s`: from the
/// circles (B, b) and (D, c), on the left of B -> D before the first crossing and after the
/// second, on its right between them (where the sweep's continuation through each change point
/// puts it).
fn joint(s: f64, phi: f64) -> (f64, f64) {
    let (bx, by) = (s * phi.cos(), s * phi.sin());
    let side = if (PI..3.0 * PI).contains(&phi) { -1.0 } else { 1.0 };
    let (cx, cy) = circle_point(bx, by, 2.0 * s, 3.5 * s, 0.0, 2.5 * s, side);
    (cx / s, cy / s)
}

/// The trapezoidal sum of harmonic `k` of `v` over the period from `samples` equally spaced
/// points (the last repeating the first): the mean for `k = 0`, the sine's coefficient where
/// `sine`, the cosine's otherwise.
fn harmonic(samples: usize, v: impl Fn(f64) -> f64, k: usize, sine: bool) -> f64 {
    let n = samples - 1;
    let weight = |x: f64| {
        let t = k as f64 * TAU * x / PERIOD;
        if k == 0 {
            0.5
        } else if sine {
            t.sin()
        } else {
            t.cos()
        }
    };
    let xs = (0..n).map(|j| PERIOD * j as f64 / n as f64);
    2.0 * xs.map(|x| v(x) * weight(x)).sum::<f64>() / n as f64
}

/// The largest magnitude of the residual of `v` after its mean and first harmonic over the
/// period, the harmonics from `v` at the samples' points (trapezoidal sums, as the library's
/// definition has them), by brute force: a scan of 2^17 intervals (the crossings at `pi` and
/// `3 pi` among its points), its best refined by golden sections over its two intervals.
fn reference_residual(samples: usize, v: impl Fn(f64) -> f64) -> (f64, f64) {
    let theta = |x: f64| TAU * x / PERIOD;
    let [a0, a1, b1] =
        [harmonic(samples, &v, 0, false), harmonic(samples, &v, 1, false), harmonic(samples, &v, 1, true)];
    let r = |x: f64| (v(x) - a0 - a1 * theta(x).cos() - b1 * theta(x).sin()).abs();
    let m = 1 << 17;
    let h = PERIOD / m as f64;
    let best = (0..=m).map(|i| i as f64 * h).fold((0.0, -1.0), |b, x| if r(x) > b.1 { (x, r(x)) } else { b });
    let (mut lo, mut hi) = (best.0 - h, best.0 + h);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if r(c) >= r(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    let x = 0.5 * (lo + hi);
    if r(x) > best.1 { (x, r(x)) } else { best }
}

#[test]
fn the_residual_of_a_column_at_a_change_point_is_located_there() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    for s in [1.0, 1e-3, 1e-6] {
        let m = FourBar { a: s, b: 2.0 * s, c: 2.5 * s, d: 3.5 * s };
        let run = Sampled::sweep_with(&m, 0.0, PERIOD, SAMPLES, [0.6, 1.7], cfg).unwrap();
        for (name, v) in [("pc.x", 0), ("pc.y", 1)] {
            let col = |phi: f64| if v == 0 { joint(s, phi).0 } else { joint(s, phi).1 };
            let u = run.unbalance(name, 1).unwrap_or_else(|e| panic!("{name} at scale {s}: {e}"));
            let (_, d) = reference_residual(SAMPLES, col);
            // The residual at the crossing is the joint's value at the located crossing: a
            // slope of order one times the crossing's location (`tol::LOCATED`), in units of s.
            assert_close!(u.max_abs / s, d, tol::LOCATED, "{name} at scale {s}: {u:?}");
            if name == "pc.x" {
                // At the crossing itself: C at (d - c, 0), the links along the frame.
                assert_close!(u.at.x, PI, tol::LOCATED, "{name} at scale {s}: {u:?}");
            }
        }
    }
}

/// Samples at the crossings themselves: the sweep gives the first well-conditioned state past
/// each (a thousandth of a radian on) in its place, which the Fourier sums weighed as if at
/// `pi`: the joint's mean `x` came out 1.3e-8 off, and `unbalance` refused the samples as not
/// equally spaced. The column at the crossing is now what the sums weigh.
#[test]
fn samples_at_the_change_points_are_summed_there() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    for s in [1.0, 1e-3, 1e-6] {
        let m = FourBar { a: s, b: 2.0 * s, c: 2.5 * s, d: 3.5 * s };
        let run = Sampled::sweep_with(&m, 0.0, PERIOD, ON_CROSSINGS, [0.6, 1.7], cfg).unwrap();
        for (name, v) in [("pc.x", 0), ("pc.y", 1)] {
            let col = |phi: f64| if v == 0 { joint(s, phi).0 } else { joint(s, phi).1 };
            let f = run.fourier(name, 3).unwrap_or_else(|e| panic!("{name} at scale {s}: {e}"));
            // The samples are solved to rounding, the one at each crossing is the column at the
            // located crossing (within rounding of pi and 3 pi here, measured 5e-15 off).
            assert_close!(f.a0 / s, harmonic(ON_CROSSINGS, col, 0, false), tol::SOLVE, "{name} at scale {s}: {f:?}");
            for k in 1..=3 {
                assert_close!(f.a[k - 1] / s, harmonic(ON_CROSSINGS, col, k, false), tol::SOLVE, "{name} a{k} at {s}");
                assert_close!(f.b[k - 1] / s, harmonic(ON_CROSSINGS, col, k, true), tol::SOLVE, "{name} b{k} at {s}");
            }
            let u = run.unbalance(name, 1).unwrap_or_else(|e| panic!("{name} at scale {s}: {e}"));
            let (_, d) = reference_residual(ON_CROSSINGS, col);
            assert_close!(u.max_abs / s, d, tol::SOLVE, "{name} at scale {s}: {u:?}");
        }
    }
}
