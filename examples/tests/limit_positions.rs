//! The numbers the `limit_positions` example prints about its non-Grashof four-bar: where the
//! sweep stops, the law of cosines it sets beside it, the reachable range and the limit
//! positions of the traced curve, against the limit found independently by bisection on where
//! the four-bar closes: the pins B = a (cos phi, sin phi) and D = (d, 0) must be at most
//! `b + c` apart. Checked for the example's four-bar and for another non-Grashof one.

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../limit_positions.rs"]
mod limit_positions;

use kinloop::EventKind;
use kinloop_fixtures::FourBar;
use limit_positions::limits;
use std::f64::consts::PI;

/// The example's four-bar and one of other proportions, both non-Grashof (`s + l > p + q`:
/// 2 + 4 > 2.5 + 3, and 1.5 + 3.3 > 2.5 + 2.2) and both closing at `phi = 0`.
fn four_bars() -> [FourBar; 2] {
    [FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 }, FourBar { a: 2.5, b: 1.5, c: 2.2, d: 3.3 }]
}

/// The largest input in `[0, pi]` at which the four-bar closes, by bisection on `|BD| - (b + c)`
/// to the last bit.
fn limit_by_bisection(m: &FourBar) -> f64 {
    let gap = |phi: f64| (m.a * phi.cos() - m.d).hypot(m.a * phi.sin()) - (m.b + m.c);
    let (mut lo, mut hi) = (0.0, PI);
    assert!(gap(lo) < 0.0 && gap(hi) > 0.0, "{m:?} closes at 0 and not at pi");
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return lo;
        }
        if gap(mid) <= 0.0 { lo = mid } else { hi = mid }
    }
}

/// The located limit position and the law of cosines to 1e-12 rad: at the limit `|BD|` grows
/// at the rate `a d sin(phi) / |BD|`, about 1 here, so the bisection's last bit of `phi` (4e-16)
/// and the rounding of `|BD|` (1e-15) put it within about 1e-15 rad; the sweep locates the limit
/// to its tolerance (the example prints differences of about 1e-16). The traced curve's folds
/// are located by continuation to 1e-9 rad.
#[test]
fn the_printed_limit_positions_are_where_the_four_bar_stops_closing() -> Result<(), Box<dyn std::error::Error>> {
    for m in four_bars() {
        let want = limit_by_bisection(&m);
        let found = limits(&m)?;
        assert!(found.stopped.is_some(), "{m:?}: the sweep stops");
        assert!(found.last < want, "{m:?}: the last sample {} is before the limit {want}", found.last);
        assert!((found.law - want).abs() <= 1e-12, "{m:?}: law of cosines {} vs {want}", found.law);
        let [(kind, x, _)] = found.events[..] else { panic!("{m:?}: one event, {:?}", found.events) };
        assert_eq!(kind, EventKind::LimitPosition, "{m:?}");
        assert!((x - want).abs() <= 1e-12, "{m:?}: located {x} vs {want}");
        // Symmetric about phi = 0 (the four-bar's mirror image in the frame line).
        let [lo, hi] = found.reach;
        assert!((lo + want).abs() <= 1e-12 && (hi - want).abs() <= 1e-12, "{m:?}: [{lo}, {hi}] vs {want}");
        let mut folds: Vec<f64> = found.traced.folds.iter().map(|f| f.x[0]).collect();
        folds.sort_by(f64::total_cmp);
        assert!(found.traced.closed, "{m:?}: the curve closes");
        assert!(
            folds.len() == 2 && (folds[0] + want).abs() <= 1e-9 && (folds[1] - want).abs() <= 1e-9,
            "{m:?}: folds {folds:?} vs ±{want}"
        );
    }
    Ok(())
}
