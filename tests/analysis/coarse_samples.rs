//! `Sampled` with samples a turn or more apart: every sample has the same state, and no analog
//! changes sign between them, yet the quantities move through their whole range in between. The
//! extremes, ranges and peaks are looked for at the points a sweep steps to, and found: the
//! offset slider-crank's dead centres and the rod's swing against their closed forms.

use crate::support::{argmax, dead_centres, richardson_first};
use kinloop::analysis::{Extreme, Jet, Sampled};
use kinloop_fixtures::SliderCrank;
use std::f64::consts::TAU;

const M: SliderCrank = SliderCrank { r: 1.0, l: 3.0, e: 0.4 };

/// The slider's position and the rod's angle by construction, the slider on the crank's -x
/// side (the fixture's guess): `l sin psi = r sin phi - e`, `x = r cos phi - l cos psi`.
fn construction(phi: f64) -> (f64, f64) {
    let psi = ((M.r * phi.sin() - M.e) / M.l).asin();
    (psi, M.r * phi.cos() - M.l * psi.cos())
}

/// Ranges from samples a whole turn apart (two and three turns), and from a spacing of 500
/// degrees: the slider's stroke between its dead centres and the rod's swing, each to the
/// rounding, with every dead centre of the range an interior extreme.
#[test]
fn samples_a_turn_apart_still_find_the_stroke_and_swing() {
    let (stretched, folded) = dead_centres(M.l, M.r, M.e);
    let swing = (((-M.r - M.e) / M.l).asin(), ((M.r - M.e) / M.l).asin());
    for (to, samples, dead) in [(2.0 * TAU, 3, 4), (3.0 * TAU, 4, 6), (1000f64.to_radians(), 3, 5)] {
        let run = Sampled::sweep(&M, 0.0, to, samples, M.guess(0.0)).unwrap();
        let x = run.range(SliderCrank::COL.x).unwrap();
        assert!((x.min.value + stretched).abs() < 1e-13 && (x.max.value + folded).abs() < 1e-13, "{to}: {x:?}");
        let psi = run.range(SliderCrank::COL.psi).unwrap();
        assert!((psi.min.value - swing.0).abs() < 1e-13 && (psi.max.value - swing.1).abs() < 1e-13, "{to}: {psi:?}");
        let extremes = run.extremes(SliderCrank::COL.x).unwrap();
        assert_eq!(extremes.len(), dead, "{to}: {extremes:?}");
        for e in &extremes {
            // At a dead centre, where the construction's slider stops.
            let (_, at) = construction(e.x());
            assert!((e.value() - at).abs() < 1e-13, "{to}: {e:?} against {at}");
            let expected = if e.kind == Extreme::Min { -stretched } else { -folded };
            assert!((e.value() - expected).abs() < 1e-13, "{to}: {e:?}");
        }
    }
}

/// The largest velocity analog of the slider over two turns sampled a turn apart: the same as
/// over one turn densely sampled.
#[test]
fn a_peak_between_samples_a_turn_apart() {
    let coarse = Sampled::sweep(&M, 0.0, 2.0 * TAU, 3, M.guess(0.0)).unwrap();
    let (s, v) = coarse.peak_of(SliderCrank::COL.x, |j: Jet| j.d1.abs()).unwrap();
    // The slider's velocity analog by Richardson-extrapolated central differences of the
    // construction (truncation and rounding about 1e-13), its largest magnitude by a dense scan.
    let speed = |phi: f64| richardson_first(|p| construction(p).1, phi, 1e-3).abs();
    let best = speed(argmax(speed, TAU, 10_000));
    assert!((v - best).abs() < 1e-10, "{v} at {s} against {best}");
}

/// The largest acceleration analog of the offset slider over one turn, with few samples: its
/// peak lies just after the first sample, which ties with the last (the turn closes), and the
/// peak is found whichever of the two the samples rank first. It was the last sample's
/// neighbourhood that was refined, and the peak came out 0.2 % low, at 2 pi.
#[test]
fn a_peak_beside_a_sample_that_ties_with_another() {
    let accel = |phi: f64| {
        let h = 1e-3;
        let x = |p: f64| construction(p).1;
        // Richardson-extrapolated second differences (truncation about h^4, rounding 1e-10).
        let d2 = |h: f64| (x(phi + h) - 2.0 * x(phi) + x(phi - h)) / (h * h);
        ((16.0 * d2(h / 2.0) - d2(h)) / 15.0).abs()
    };
    let best_at = argmax(accel, TAU, 20_000);
    let best = accel(best_at);
    // The turn starts just before the peak.
    let from = best_at - 0.05;
    for samples in [5, 13, 19, 25, 37, 49, 73] {
        let turn = Sampled::sweep(&M, from, from + TAU, samples, M.guess(from)).unwrap();
        let (s, v) = turn.peak_of(SliderCrank::COL.x, |j: Jet| j.d2.abs()).unwrap();
        assert!((v - best).abs() < 1e-7 * best, "{samples} samples: {v} at {s} against {best} at {best_at}");
    }
}

/// Samples so far apart that the points between them would not fit a search (20,000 turns
/// in three samples): refused, saying how many samples would do, not a search that fills the
/// memory.
#[test]
fn samples_too_far_apart_to_search_between_are_refused() {
    let run = Sampled::sweep(&M, 0.0, 2e4 * TAU, 3, M.guess(0.0)).unwrap();
    let e = run.range(SliderCrank::COL.x).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("too far apart to search between") && text.contains("give at least"), "{text}");
    assert!(text.contains(&kinloop::analysis::MAX_SEARCH_POINTS.to_string()), "{text}");
}

/// The Fourier series of a column needs the sweep to be one period: a range a milliradian short
/// of a turn, or half a turn, is refused at every size of the mechanism, and a whole turn
/// accepted with the same first harmonic relative to the size. The check's floor of one unit
/// let both pass once the mechanism was a micrometre across.
#[test]
fn fourier_refuses_a_range_short_of_a_turn_at_every_scale() {
    for k in [1.0, 1e-6, 1e-12, 1e6] {
        let m = SliderCrank { r: M.r * k, l: M.l * k, e: M.e * k };
        for to in [TAU - 1e-3, TAU / 2.0] {
            let run = Sampled::sweep(&m, 0.0, to, 73, m.guess(0.0)).unwrap();
            assert!(run.fourier(SliderCrank::COL.x, 2).is_err(), "{k}: 0 to {to} taken for a period");
        }
        let turn = Sampled::sweep(&m, 0.0, TAU, 73, m.guess(0.0)).unwrap();
        let f = turn.fourier(SliderCrank::COL.x, 2).unwrap();
        let unit = Sampled::sweep(&M, 0.0, TAU, 73, M.guess(0.0)).unwrap().fourier(SliderCrank::COL.x, 2).unwrap();
        assert!((f.amplitude(1) / k - unit.amplitude(1)).abs() < 1e-12 * unit.amplitude(1), "{k}: {f:?}");
    }
    // The unit mechanism's coefficients against the construction's own: the trapezoidal rule over
    // a period, exact to the rounding for a smooth periodic function (the slider's harmonics fall
    // as (r / l)^k: those that alias onto the first two from 72 samples or 4096 weigh nothing).
    let unit = Sampled::sweep(&M, 0.0, TAU, 73, M.guess(0.0)).unwrap().fourier(SliderCrank::COL.x, 2).unwrap();
    let n = 4096;
    let coefficient = |k: usize, of: fn(f64) -> f64| {
        2.0 / n as f64
            * (0..n).map(|j| TAU * j as f64 / n as f64).map(|p| construction(p).1 * of(k as f64 * p)).sum::<f64>()
    };
    for k in 1..=2 {
        let (a, b) = (coefficient(k, f64::cos), coefficient(k, f64::sin));
        assert!(
            (unit.a[k - 1] - a).abs() < 1e-13 * M.l && (unit.b[k - 1] - b).abs() < 1e-13 * M.l,
            "{k}: {unit:?} against ({a}, {b})"
        );
    }
    let mean = (0..n).map(|j| construction(TAU * j as f64 / n as f64).1).sum::<f64>() / n as f64;
    assert!((unit.a0 - mean).abs() < 1e-13 * M.l, "{unit:?} against {mean}");
}

/// A range of half a turn starting a ten-millionth of a radian before the slider's stretched dead
/// centre: its minimum, at the dead centre, is an extreme inside the range at every sampling. A millionth of
/// the samples' spacing (1.6 rad) from the start, it was taken for the start itself and dropped
/// with 3 and 5 samples (found with 73).
#[test]
fn an_extreme_just_inside_the_range_is_kept_at_any_spacing() {
    let (stretched, folded) = dead_centres(M.l, M.r, M.e);
    // Crank and rod in line towards the slider at (-stretched, e).
    let at = M.e.atan2(-stretched);
    let from = at - 1e-7;
    for samples in [3, 5, 73] {
        let run = Sampled::sweep(&M, from, from + std::f64::consts::PI, samples, M.guess(from)).unwrap();
        let extremes = run.extremes(SliderCrank::COL.x).unwrap();
        // The minimum just inside the start, and the folded dead centre's maximum half a turn on.
        let [min, max] = extremes.as_slice() else { panic!("{samples} samples: {extremes:?}") };
        assert_eq!((min.kind, max.kind), (Extreme::Min, Extreme::Max), "{samples} samples");
        assert!((min.x() - at).abs() < 1e-9 && (min.value() + stretched).abs() < 1e-13, "{samples}: {min:?}");
        assert!((max.value() + folded).abs() < 1e-13, "{samples}: {max:?}");
    }
}

/// The quick-return ratio of an offset slider-crank from a turn of three and four samples: both
/// dead centres lie between two samples, and are looked for there as `extremes` looks (the
/// samples alone found "0 maxima and 0 minima" with three). Against the closed form: the crank
/// turns `pi + theta` for one stroke and `pi - theta` for the other, `theta = asin(e / (l - r))
/// - asin(e / (l + r))` (the angle between the two collinear positions of crank and rod).
#[test]
fn a_time_ratio_from_a_turn_of_few_samples() {
    let m = SliderCrank { r: 1.0, l: 3.0, e: 0.8 };
    let theta = (m.e / (m.l - m.r)).asin() - (m.e / (m.l + m.r)).asin();
    let ratio = (std::f64::consts::PI + theta) / (std::f64::consts::PI - theta);
    for samples in [3, 4, 181] {
        let turn = Sampled::sweep(&m, 2.8, 2.8 + TAU, samples, m.guess(2.8)).unwrap();
        let t = turn.time_ratio(SliderCrank::COL.x).unwrap();
        // The dead centres are roots of the velocity analog located to rounding; the ratio
        // carries a few ulps of the crank's angle over the strokes' (about 3 rad).
        assert!((t.ratio() - ratio).abs() < 1e-12, "{samples} samples: {} against {ratio}", t.ratio());
    }
}

/// The transmission angle of a crank-rocker from a turn of three and four samples: its largest,
/// a right angle where `cos mu` changes sign between two samples, and its smallest at
/// `phi = 0` (law of cosines: `cos mu = (b^2 + c^2 - a^2 - d^2 + 2 a d cos phi) / (2 b c)`,
/// from -0.16 to 0.69 over the turn). The samples alone gave 1.534 and 1.551 for pi / 2.
#[test]
fn a_transmission_angle_from_a_turn_of_few_samples() {
    use kinloop_fixtures::FourBar;
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let cos_mu =
        |phi: f64| (m.b * m.b + m.c * m.c - m.a * m.a - m.d * m.d + 2.0 * m.a * m.d * phi.cos()) / (2.0 * m.b * m.c);
    // From 2.1: `cos mu` vanishes at 2.248 and 4.035, both within the first sample spacing
    // of three or four samples a turn, where its sign does not change.
    let guess = m.position(2.1, &m.guess(2.1)).unwrap().0;
    for samples in [3, 4, 181] {
        let turn = Sampled::sweep(&m, 2.1, 2.1 + TAU, samples, guess).unwrap();
        let mu = turn.transmission(FourBar::COL.beta, FourBar::COL.gamma).unwrap();
        assert!((mu.max.angle - std::f64::consts::FRAC_PI_2).abs() < 1e-14, "{samples} samples: {mu:?}");
        assert!((cos_mu(mu.max.x)).abs() < 1e-13, "{samples} samples: {mu:?}");
        // The smallest at phi = 0, one turn on (2 pi); compared in cosines (acos is
        // ill-conditioned near its ends).
        assert!((mu.min.angle.cos() - cos_mu(0.0)).abs() < 1e-13, "{samples} samples: {mu:?}");
        assert!((mu.min.x - TAU).abs() < 1e-7, "{samples} samples: {mu:?}");
    }
}
