//! The table the `gear_lever` example prints for each `k`: the rocker's swing during a stop and
//! the peak acceleration analog with the carrier angle where it occurs, against paper 001's
//! explicit formulas (`docs/papers.md`) for `u = 3`, `L = 2`, `l = k`:
//! `x = 2 sin a - k sin 2a`, `y = 2 cos a + k cos 2a`, the rocker angle `atan(x / y)` and
//! `eps_r = [(x'' y - y'' x)(x^2 + y^2) - 2 (x' y - y' x)(x' x + y' y)] / (x^2 + y^2)^2`,
//! differentiated by hand and searched by brute force, never solved by kinloop.

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../gear_lever.rs"]
mod gear_lever;

use gear_lever::stop;
use std::f64::consts::PI;

/// The pin and its first two derivatives by the carrier angle: `[[x, x', x''], [y, y', y'']]`.
fn pin(k: f64, a: f64) -> [[f64; 3]; 2] {
    let (s1, c1, s2, c2) = (a.sin(), a.cos(), (2.0 * a).sin(), (2.0 * a).cos());
    [
        [2.0 * s1 - k * s2, 2.0 * c1 - 2.0 * k * c2, -2.0 * s1 + 4.0 * k * s2],
        [2.0 * c1 + k * c2, -2.0 * s1 - 2.0 * k * s2, -2.0 * c1 - 4.0 * k * c2],
    ]
}

/// The rocker's angle (continuous near the stop around `a = 0`, where `y > 0`) and its
/// acceleration analog, by the paper's formulas.
fn rocker(k: f64, a: f64) -> (f64, f64) {
    let [[x, dx, ddx], [y, dy, ddy]] = pin(k, a);
    let r2 = x * x + y * y;
    let eps = ((ddx * y - ddy * x) * r2 - 2.0 * (dx * y - dy * x) * (dx * x + dy * y)) / (r2 * r2);
    ((x / y).atan(), eps)
}

/// The argument in `[lo, hi]` and value of the largest of `f`: the best of 100,000 samples,
/// refined by golden sections between its neighbours down to 1e-13.
fn largest(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let n = 100_000;
    let step = (hi - lo) / n as f64;
    let best = (0..=n).map(|j| lo + j as f64 * step).max_by(|a, b| f(*a).total_cmp(&f(*b))).expect("samples");
    let (mut a, mut b) = (best - step, best + step);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    while b - a > 1e-13 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if f(x1) > f(x2) { b = x2 } else { a = x1 }
    }
    let x = 0.5 * (a + b);
    (x, f(x))
}

/// Swing to 1e-9 degrees and peak to 1e-9 of itself: at an extreme the searched quantity is
/// flat, so the search's location error (about 1e-8 rad) enters it only squared; the peak's
/// carrier angle to 1e-5 degrees (that location error, 6e-7°, with margin). In the stop around
/// `a = 0` the rocker swings back from a local maximum before it to the local minimum after it
/// (the hypocycloid's loop), all within `|a| < 60°`, where `y > 0`.
#[test]
fn the_printed_swing_and_peak_agree_with_the_paper_s_formulas() -> Result<(), Box<dyn std::error::Error>> {
    for k in [1.1, 1.3, 1.5] {
        let printed = stop(k)?;
        let (at_max, top) = largest(-PI / 3.0, 0.0, |a| rocker(k, a).0);
        let (at_min, bottom) = largest(0.0, PI / 3.0, |a| -rocker(k, a).0);
        assert!(at_max < 0.0 && at_min > 0.0 && top > -bottom, "k = {k}: a loop around 0");
        let swing = (top + bottom).to_degrees();
        assert!((printed.swing - swing).abs() <= 1e-9, "k = {k}: swing {} vs {swing}", printed.swing);
        // The peak over a whole turn: the three stops are alike, so over one 120° cycle.
        let (at, peak) = largest(-PI / 3.0, PI / 3.0, |a| rocker(k, a).1);
        let at = at.to_degrees().rem_euclid(120.0);
        assert!((printed.peak_acc - peak).abs() <= 1e-9 * peak, "k = {k}: peak {} vs {peak}", printed.peak_acc);
        let gap = (printed.peak_at - at).rem_euclid(120.0);
        assert!(gap.min(120.0 - gap) <= 1e-5, "k = {k}: peak at {}° vs {at}°", printed.peak_at);
    }
    Ok(())
}
