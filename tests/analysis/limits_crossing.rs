//! The limit report and the sampled extremes across a singular crossing (change point): a
//! Grashof-equal four-bar (`a + d = b + c`) whose coupler and rocker lie stretched along the
//! frame at `phi = pi`, where the sweep passes from one assembly mode to the other. The joint's
//! `x` has its minimum exactly there (C at `(d - c, 0)`, the nearest the rocker's circle comes
//! to the crank's pivot), its analog changing sign at the crossing: a search refining that root
//! stepped into the crossing's singular band and failed the whole report, for `pc.x` alone and
//! at some sample counts only. Checked against the closed form on the branch the sweep follows,
//! by brute force, at three length scales.

use crate::support::{circle_point, tol};
use kinloop::analysis::{Column, Extreme, LocalExtreme, Sampled};
use kinloop::events::EventKind;
use kinloop::metrics::Limits;
use kinloop::{AtSingular, Mechanism, SweepConfig};
use kinloop_fixtures::FourBar;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The sweep's range: short of a full turn (as the report that found the failure swept it), the
/// crossing inside it; not `TAU`.
#[allow(clippy::approx_constant)]
const TO: f64 = 6.28;
const COLUMNS: [&str; 4] = ["beta", "gamma", "pc.x", "pc.y"];

kinloop::mechanism! {
    /// The fixtures' four-bar with two progressive outputs (advancing over the range, with one
    /// reversal each, whose dwells lie across the change point): `dip`, the joint's `x` in units
    /// of the crank (scale-free) plus `0.05 (phi - pi)^3`, whose reversal ends at the joint's
    /// minimum at the crossing itself (the cubic's slope vanishes there); and `lag`, the
    /// coupler's angle plus `0.3 phi`, whose reversal runs from before the crossing to after it.
    /// And two outputs of the crank's angle alone that stand still over stretches: `still` from
    /// 0 to 2, from 3 to 4 (across the change point at `pi`) and from 5 on; `until` up to the
    /// crossing itself, moving after it.
    pub struct FourBarDip {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point pc = a @ phi + b @ beta;
        output dip = (a * cos(phi) + b * cos(beta)) / a + 0.05 * (phi - pi) * (phi - pi) * (phi - pi);
        output lag = beta + 0.3 * phi;
        output still = clamp(phi - 2, 0, 1) + clamp(phi - 4, 0, 1);
        output until = clamp(phi - pi, 0, 1);
    }
}

/// The four-bar (1, 2, 2.5, 3.5) at scale `s`: `a + d = b + c`.
fn four_bar(s: f64) -> FourBar {
    FourBar { a: s, b: 2.0 * s, c: 2.5 * s, d: 3.5 * s }
}

/// The column `name` at `phi` by construction, independent of the library: C from the circles
/// (B, b) and (D, c), B the crank's tip, on the left of B -> D before the crossing (the fixture's
/// guess, C above the frame at `phi = 0`) and on its right after it: the sweep's smooth
/// continuation through the change point, where the two modes meet (`|BD| = b + c`, C on the
/// line B -> D), changes mode; with the outputs of [`FourBarDip`]. Angles are wrapped to
/// (-pi, pi]; see [`unwrap_near`].
fn construction(m: &FourBar, phi: f64, name: &str) -> f64 {
    let (bx, by) = (m.a * phi.cos(), m.a * phi.sin());
    let side = if phi < PI { 1.0 } else { -1.0 };
    // `circle_point` clamps the height to zero where rounding puts |BD| a hair beyond b + c.
    let (cx, cy) = circle_point(bx, by, m.b, m.d, 0.0, m.c, side);
    match name {
        "beta" => (cy - by).atan2(cx - bx),
        "gamma" => cy.atan2(cx - m.d),
        "pc.x" => cx,
        "pc.y" => cy,
        "dip" => cx / m.a + 0.05 * (phi - PI).powi(3),
        "lag" => (cy - by).atan2(cx - bx) + 0.3 * phi,
        _ => unreachable!("{name}"),
    }
}

/// `v` moved by whole turns to lie within half a turn of `near` (angles only).
fn unwrap_near(name: &str, v: f64, near: f64) -> f64 {
    if matches!(name, "beta" | "gamma" | "lag") { v + TAU * ((near - v) / TAU).round() } else { v }
}

/// The interior local extremes of the column over `[0, TO]`, by brute force: the closed form on
/// a grid of 2^18 intervals (spacing 2.4e-5, far below the distance between extremes), every
/// interior local extreme of the grid refined by a golden-section search over its two
/// intervals. The search locates an extreme to about `sqrt(eps |f / f''|)` (some 2e-8 here:
/// the values compared are equal within rounding over a wider interval than that), and its
/// value to rounding.
fn reference_extremes(m: &FourBar, name: &str) -> Vec<(Extreme, f64, f64)> {
    let values = grid_values(m, name);
    let n = values.len() - 1;
    let phi = |i: usize| TO * i as f64 / n as f64;
    let mut found = Vec::new();
    for i in 1..n {
        let (l, v, r) = (values[i - 1], values[i], values[i + 1]);
        let kind = if v > l && v >= r {
            Extreme::Max
        } else if v < l && v <= r {
            Extreme::Min
        } else {
            continue;
        };
        let sign = if kind == Extreme::Max { -1.0 } else { 1.0 };
        let f = |x: f64| sign * unwrap_near(name, construction(m, x, name), v);
        let (mut a, mut b) = (phi(i - 1), phi(i + 1));
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if f(c) <= f(d) {
                b = d;
            } else {
                a = c;
            }
        }
        let x = 0.5 * (a + b);
        found.push((kind, x, sign * f(x)));
    }
    found
}

/// The column by construction on the grid of [`reference_extremes`] (2^18 intervals over
/// `[0, TO]`), angles unwrapped along it: continuous, as the library's columns are.
fn grid_values(m: &FourBar, name: &str) -> Vec<f64> {
    let n = 1usize << 18;
    let mut values: Vec<f64> = Vec::with_capacity(n + 1);
    for i in 0..=n {
        let v = construction(m, TO * i as f64 / n as f64, name);
        let v = values.last().map_or(v, |&prev| unwrap_near(name, v, prev));
        values.push(v);
    }
    values
}

/// The dwells of the column over `[0, TO]` by the definition (`kinloop::analysis::dwell`),
/// from the brute-force extremes and the construction: the output advances overall in the sign
/// of `v(TO) - v(0)`; each pair of consecutive extremes moving against it (a maximum then a
/// minimum for an advancing output) is a reversal, whose dwell runs from where the output
/// enters the band, reaching the second extreme's value before the first extreme (after the
/// extreme before it, or from 0), to where it leaves it, reaching the first extreme's value
/// after the second (before the next, or by `TO`); a reversal whose band is not entered or
/// left so is no dwell. Each end by bisection on the construction, to rounding.
/// `(start, first extreme, second extreme, end)`, as inputs.
fn reference_dwells(m: &FourBar, name: &str) -> Vec<[f64; 4]> {
    let values = grid_values(m, name);
    let (first, last) = (values[0], values[values.len() - 1]);
    let reversal = if last > first { Extreme::Max } else { Extreme::Min };
    let ext = reference_extremes(m, name);
    // Where the column, monotonic on `[lo, hi]`, takes `level`, if it does.
    let reach = |lo: f64, hi: f64, level: f64| {
        let f = |x: f64| unwrap_near(name, construction(m, x, name), level) - level;
        let (mut a, mut b) = (lo, hi);
        if (f(a) >= 0.0) == (f(b) >= 0.0) {
            return None;
        }
        for _ in 0..200 {
            let mid = 0.5 * (a + b);
            if (f(mid) >= 0.0) == (f(a) >= 0.0) { a = mid } else { b = mid }
        }
        Some(0.5 * (a + b))
    };
    let mut dwells = Vec::new();
    for i in 0..ext.len().saturating_sub(1) {
        let ((kind, x1, v1), (_, x2, v2)) = (ext[i], ext[i + 1]);
        if kind != reversal {
            continue;
        }
        let before = if i > 0 { ext[i - 1].1 } else { 0.0 };
        let after = ext.get(i + 2).map_or(TO, |e| e.1);
        if let (Some(start), Some(end)) = (reach(before, x1, v2), reach(x2, after, v1)) {
            dwells.push([start, x1, x2, end]);
        }
    }
    dwells
}

/// What a length or an angle of the column is compared with: the link size for a length.
fn size(m: &FourBar, name: &str) -> f64 {
    if name.starts_with("pc") { m.a } else { 1.0 }
}

/// The located extremes against the brute-force ones: the same count and kinds, the values to a
/// solve's rounding (`tol::SOLVE` of the column's size: an extreme's value is insensitive to its
/// location, to second order), the locations to 1e-6 (the reference's golden-section resolution
/// above, with a margin; the crossing's own location is checked to `tol::LOCATED` by the caller).
fn check_extremes(what: &str, m: &FourBar, name: &str, found: &[LocalExtreme], reference: &[(Extreme, f64, f64)]) {
    assert_eq!(found.len(), reference.len(), "{what}: {found:?} against {reference:?}");
    for (e, &(kind, x, value)) in found.iter().zip(reference) {
        assert_eq!(e.kind, kind, "{what}: {e:?} against {x} {value}");
        assert!((e.x() - x).abs() < 1e-6, "{what}: {e:?} against {x} {value}");
        // An angle column's extreme value is compared up to whole turns (the reference unwraps
        // from its own start); the library's angles are continuous along the sweep.
        let v = unwrap_near(name, value, e.value());
        assert!((e.value() - v).abs() < tol::SOLVE * size(m, name), "{what}: {e:?} against {x} {value}");
    }
}

/// The crossing: the sweep's events are the one singular crossing, located at `pi` to the
/// event's documented precision (`tol::LOCATED`, 1e-9 of the input's unit).
fn check_crossing(what: &str, events: &[kinloop::Event]) {
    assert_eq!(events.len(), 1, "{what}: {events:?}");
    assert_eq!(events[0].kind, EventKind::SingularCrossing, "{what}: {events:?}");
    assert!((events[0].x[0] - PI).abs() < tol::LOCATED, "{what}: {events:?}");
}

/// The limit report of every column, at every sample count and length scale, succeeds: it lists
/// the crossing at `pi`, and the extremes of each column as the construction has them, `pc.x`'s
/// minimum `d - c` at the crossing among them (at 73 samples the report failed with a stop at a
/// singular crossing 1e-6 before it, at 10 with a pivot-ratio branch error, for `pc.x` alone).
#[test]
fn limits_pass_a_change_point_for_every_column_and_sample_count() {
    for scale in [1.0, 1e-3, 1e3] {
        let m = four_bar(scale);
        let guess = m.guess_flat(&[0.0]);
        for name in COLUMNS {
            let reference = reference_extremes(&m, name);
            if name == "pc.x" {
                // The reference has the minimum at the crossing (to its own resolution).
                let (kind, x, value) = reference[1];
                assert!(kind == Extreme::Min && (x - PI).abs() < 1e-7, "{reference:?}");
                assert!((value - (m.d - m.c)).abs() < tol::ULPS * scale, "{reference:?}");
            }
            let columns = [Column::<FourBar>::named(name).unwrap()];
            for samples in [5, 10, 73, 360] {
                let what = format!("scale {scale}, {name}, {samples} samples");
                let r = Limits::new(&m, 0.0, TO).samples(samples).guess(guess).columns(&columns).run();
                let r = r.unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(r.reached, (0.0, TO), "{what}: {r}");
                check_crossing(&what, &r.events);
                check_extremes(&what, &m, name, &r.outputs[0].extremes, &reference);
                if name == "pc.x" {
                    // At the crossing's input, its value from the state there.
                    let at = r.outputs[0].extremes[1];
                    assert_eq!(at.x(), r.events[0].x[0], "{what}: {r}");
                    assert!((at.value() - (m.d - m.c)).abs() < tol::SOLVE * scale, "{what}: {r}");
                }
            }
        }
    }
}

/// The sampled analyses behind the report find the same across the crossing: `extremes` and
/// `range` of `pc.x` (the stroke of the joint from `d - c` at the crossing to its maxima), over a
/// sweep configured to pass crossings.
#[test]
fn sampled_extremes_and_range_across_a_change_point() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    for scale in [1.0, 1e-3, 1e3] {
        let m = four_bar(scale);
        let reference = reference_extremes(&m, "pc.x");
        for samples in [5, 10, 73, 360] {
            let what = format!("scale {scale}, {samples} samples");
            let run = Sampled::sweep_with(&m, 0.0, TO, samples, m.guess_flat(&[0.0]), cfg).unwrap();
            let found = run.extremes(FourBar::COL.pc.x).unwrap_or_else(|e| panic!("{what}: {e}"));
            check_extremes(&what, &m, "pc.x", &found, &reference);
            assert!((found[1].x() - PI).abs() < tol::LOCATED, "{what}: {found:?}");
            let range = run.range(FourBar::COL.pc.x).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!((range.min.value - (m.d - m.c)).abs() < tol::SOLVE * scale, "{what}: {range:?}");
            assert!((range.min.x - PI).abs() < tol::LOCATED, "{what}: {range:?}");
            assert!((range.max.value - reference[0].2).abs() < tol::SOLVE * scale, "{what}: {range:?}");
        }
    }
}

/// The transmission angle across the change point, against the law of cosines: coupler and
/// rocker lie stretched on one line at the crossing, a dead point (angle 0) there, and the
/// angle is largest, pi/2, where `cos mu = (b^2 + c^2 - a^2 - d^2 + 2 a d cos phi) / (2 b c)`
/// vanishes, `cos phi = 3/7`. The search located the dead point by stepping into the crossing's
/// singular band, and failed the whole analysis at every sample count and scale.
#[test]
fn transmission_angle_across_a_change_point() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let peak = (3.0f64 / 7.0).acos();
    for scale in [1.0, 1e-3, 1e3] {
        let m = four_bar(scale);
        for samples in [10, 73, 360] {
            let what = format!("scale {scale}, {samples} samples");
            let run = Sampled::sweep_with(&m, 0.0, TO, samples, m.guess_flat(&[0.0]), cfg).unwrap();
            let mu = run.transmission(FourBar::COL.beta, FourBar::COL.gamma).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(mu.dead_points.len() == 1 && (mu.dead_points[0] - PI).abs() < tol::LOCATED, "{what}: {mu:?}");
            assert!(mu.min.angle < tol::SOLVE && (mu.min.x - PI).abs() < tol::LOCATED, "{what}: {mu:?}");
            assert!((mu.max.angle - FRAC_PI_2).abs() < tol::SOLVE, "{what}: {mu:?}");
            assert!(
                (mu.max.x - peak).abs() < tol::LOCATED || (mu.max.x - (TAU - peak)).abs() < tol::LOCATED,
                "{what}: {mu:?}"
            );
        }
    }
}

/// The rests of outputs standing still across the change point and up to it: `still` rests
/// from 0 to 2, 3 to 4 and 5 to the end, the switches of its clamps located to the doubles;
/// `until` up to the crossing at `pi`, located there to the width of the crossing's band (the
/// search steps no closer), and from `pi + 1`. The search for a rest across the crossing evaluated the output
/// inside that band, and failed (at 10 and 73 samples).
#[test]
fn rests_across_a_change_point() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    for scale in [1.0, 1e-3, 1e3] {
        let m = FourBarDip { a: scale, b: 2.0 * scale, c: 2.5 * scale, d: 3.5 * scale };
        for samples in [5, 10, 73, 360] {
            let what = format!("scale {scale}, {samples} samples");
            let run = Sampled::sweep_with(&m, 0.0, TO, samples, m.guess_flat(&[0.0]), cfg).unwrap();
            let still = run.rests(FourBarDip::COL.still).unwrap_or_else(|e| panic!("{what}: {e}"));
            let ends: Vec<(f64, f64)> = still.iter().map(|r| (r.start.x, r.end.x)).collect();
            assert_eq!(ends.len(), 3, "{what}: {ends:?}");
            for ((start, end), (a, b)) in ends.iter().zip([(0.0, 2.0), (3.0, 4.0), (5.0, TO)]) {
                assert!((start - a).abs() < tol::ULPS && (end - b).abs() < tol::ULPS, "{what}: {ends:?}");
            }
            let until = run.rests(FourBarDip::COL.until).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(until.len() == 2 && until[0].start.x == 0.0, "{what}: {until:?}");
            assert!(until[0].end.x <= PI && PI - until[0].end.x < 1e-5, "{what}: {until:?}");
            assert!((until[1].start.x - (PI + 1.0)).abs() < tol::ULPS && until[1].end.x == TO, "{what}: {until:?}");
        }
    }
}

/// The peaks of the joint's `x` across the change point: its least value, `d - c` at the
/// crossing itself (as `-x`'s peak, located to the width of the crossing's band, where nothing
/// is solved), and its largest acceleration analog `|x''|`, against a brute force on the
/// construction (central differences on a grid of 2^15 intervals: its peak to some 1e-8). The
/// refinement between a sample and its neighbour beyond the crossing stepped into the band and
/// failed: for the least `x` at every sample count, for `|x''|` at 10.
#[test]
fn peaks_across_a_change_point() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    for scale in [1.0, 1e-3, 1e3] {
        let m = four_bar(scale);
        let x = |phi: f64| construction(&m, phi, "pc.x");
        let (n, h) = (1 << 15, 1e-4);
        let brute = (0..=n)
            .map(|i| TO * f64::from(i) / f64::from(n))
            .filter(|phi| (phi - PI).abs() > 1e-2 && *phi > h && *phi < TO - h)
            .map(|phi| ((x(phi + h) - 2.0 * x(phi) + x(phi - h)) / (h * h)).abs())
            .fold(0.0, f64::max);
        for samples in [5, 10, 73, 360] {
            let what = format!("scale {scale}, {samples} samples");
            let run = Sampled::sweep_with(&m, 0.0, TO, samples, m.guess_flat(&[0.0]), cfg).unwrap();
            let (at, least) = run.peak_of(FourBar::COL.pc.x, |j| -j.value).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!((at - PI).abs() < 1e-5 && (-least - (m.d - m.c)).abs() < 1e-9 * scale, "{what}: {at} {least}");
            let (_, peak) = run.peak_of(FourBar::COL.pc.x, |j| j.d2.abs()).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!((peak - brute).abs() < 1e-6 * scale, "{what}: {peak} against {brute}");
        }
    }
}

/// A state asked for between the crossing and the point where the sweep resumes past it is the
/// state at that input: it was the resumed state, 7e-4 rad past the crossing, whatever input
/// within that was asked for (and the extremes' refinement there compared the wrong states).
#[test]
fn a_state_just_past_a_change_point_is_at_its_own_input() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let m = four_bar(1.0);
    let run = Sampled::sweep_with(&m, 0.0, TO, 73, m.guess_flat(&[0.0]), cfg).unwrap();
    for off in [1e-3, 1e-4, 1e-5] {
        let phi = PI + off;
        let k = run.at(phi).unwrap();
        assert_eq!(k.x[0], phi);
        let x = construction(&m, phi, "pc.x");
        assert!((FourBar::COL.pc.x.jet(&k).value - x).abs() < tol::SOLVE, "{off}: {k:?} against {x}");
    }
}

/// The dwells of every column across the change point: the search behind them is the extremes'
/// (`pc.x`'s at the crossing itself), which failed the whole analysis for `pc.x` at every sample
/// count. Each column's dwells, at every count and scale, are the definition's from the
/// construction ([`reference_dwells`]). The four columns of the four-bar have none: each
/// swings and comes back (mirrored across the crossing) without a reversal entered from below
/// it and left above it within the range. The progressive `dip` and `lag` have one each, over
/// `[0.39, 4.39]` and `[0.88, 5.40]` (the brute force's, to the hundredth), `dip`'s second
/// extreme the crossing itself: an analysis finding no dwell fails here. Compared: the same
/// count; each extreme within 1e-6 (as in [`check_extremes`]); the ends, where the output enters
/// and leaves the band, within `tol::LOCATED`: each a root of `v - level`, the level an
/// extreme's value (to `tol::SOLVE` of the size), so placed within that over the slope there,
/// which is checked to be at least a tenth of the size per radian.
#[test]
fn sampled_dwells_across_a_change_point() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let expected = |name: &str| match name {
        "dip" => vec![[0.39, 1.27, PI, 4.39]],
        "lag" => vec![[0.88, 1.98, 4.31, 5.40]],
        _ => vec![],
    };
    for name in COLUMNS.into_iter().chain(["dip", "lag"]) {
        for scale in [1.0, 1e-3, 1e3] {
            let m = four_bar(scale);
            let reference = reference_dwells(&m, name);
            // The brute force against the figures written above.
            let rough = expected(name);
            assert_eq!(reference.len(), rough.len(), "{name}: {reference:?}");
            for (r, e) in reference.iter().zip(&rough) {
                assert!(r.iter().zip(e).all(|(r, e)| (r - e).abs() < 0.01), "{name}: {reference:?}");
            }
            let dip = FourBarDip { a: m.a, b: m.b, c: m.c, d: m.d };
            for samples in [5, 10, 73, 360] {
                let what = format!("{name}, scale {scale}, {samples} samples");
                let run = Sampled::sweep_with(&dip, 0.0, TO, samples, dip.guess_flat(&[0.0]), cfg).unwrap();
                let c = Column::<FourBarDip>::named(name).unwrap();
                let found = run.dwells(c).unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(found.len(), reference.len(), "{what}: {found:?} against {reference:?}");
                for (d, want) in found.iter().zip(&reference) {
                    let size = size(&m, name);
                    for (got, want) in [(d.first.x(), want[1]), (d.second.x(), want[2])] {
                        assert!((got - want).abs() < 1e-6, "{what}: an extreme at {got} against {want}: {d:?}");
                    }
                    for (end, want) in [(d.start, want[0]), (d.end, want[3])] {
                        assert!(end.d1.abs() > 0.1 * size, "{what}: slope at {end:?}");
                        assert!(
                            (end.x - want).abs() < tol::LOCATED,
                            "{what}: an end at {} against {want}: {d:?}",
                            end.x
                        );
                    }
                }
            }
        }
    }
}
