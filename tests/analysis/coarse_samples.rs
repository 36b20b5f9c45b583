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
