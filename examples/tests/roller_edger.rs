//! The turn-back of cylinder 1 the `roller_edger` example prints (the time located along the
//! stroke, the closed form it sets beside it, and the cylinder's angle there) against a
//! brute-force search of the law of cosines in the triangle O1 A O3,
//! `phi1 = alpha + acos((s^2 + l5^2 - l3^2) / (2 l5 s))` with `s = l1 + V1 t` (the branch that
//! closes with the declared assembly mode, `docs/papers.md`, paper 002), for the example's
//! edger and one of other dimensions.

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../roller_edger.rs"]
mod roller_edger;

use kinloop_fixtures::roller_edger::RollerEdger;
use roller_edger::turn_back;

/// The example's edger and one whose cylinder turns back later in the stroke (at about 3.9 s).
fn edgers() -> [RollerEdger; 2] {
    [RollerEdger::default(), RollerEdger { l1: 0.8, l3: 0.7, l5: 1.25, v1: 0.06, ..RollerEdger::default() }]
}

/// The time in `[0, 6]` s and the value of the largest `phi1`: the best of 60,000 samples,
/// refined by golden sections between its neighbours down to 1e-13 s.
fn latest_top(m: &RollerEdger) -> (f64, f64) {
    let phi1 = |t: f64| {
        let s = m.l1 + m.v1 * t;
        m.alpha + ((s * s + m.l5 * m.l5 - m.l3 * m.l3) / (2.0 * m.l5 * s)).acos()
    };
    let (n, step) = (60_000, 6.0 / 60_000.0);
    let best = (0..=n).map(|k| k as f64 * step).max_by(|a, b| phi1(*a).total_cmp(&phi1(*b))).expect("samples");
    let (mut a, mut b) = ((best - step).max(0.0), (best + step).min(6.0));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    while b - a > 1e-13 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if phi1(x1) > phi1(x2) { b = x2 } else { a = x1 }
    }
    let t = 0.5 * (a + b);
    (t, phi1(t))
}

/// The angle to 1e-12 rad: at the top `phi1` is flat, so the search's location error (about
/// `sqrt(eps)` of its scale, golden sections on a flat maximum: 1e-7 s) enters it only
/// squared, times `phi1'' ~ 1e-2 rad/s^2`. The times to 1e-6 s, ten times that location error.
#[test]
fn the_printed_turn_back_agrees_with_the_law_of_cosines() -> Result<(), Box<dyn std::error::Error>> {
    for m in edgers() {
        let [t, closed_t, phi1] = turn_back(&m)?;
        let (want_t, want_phi1) = latest_top(&m);
        assert!(want_t > 0.5 && want_t < 5.5, "{m:?}: turns back inside the stroke, at {want_t} s");
        assert!((phi1 - want_phi1).abs() <= 1e-12, "{m:?}: phi1 {phi1} vs {want_phi1}");
        assert!((t - want_t).abs() <= 1e-6, "{m:?}: located at {t} s vs {want_t} s");
        assert!((closed_t - want_t).abs() <= 1e-6, "{m:?}: closed form {closed_t} s vs {want_t} s");
    }
    Ok(())
}
