//! `Sampled::fourier`, `unbalance`, `dwells` and `extremes` of columns that stand still in
//! exact arithmetic: a parallelogram four-bar's coupler angle (0 at every crank angle) and a
//! centred slider's height (0). Computed, each is rounding alone, some 1e-16 of what it is solved from; judged
//! against its own size, that noise at the start and end of a turn made a turn "not periodic"
//! (and its travel progressive, the sign changes of its analog extremes).
//! The references are exact: the coupler angle and the slider's height are zero, the coupler
//! joint's height of the parallelogram `a sin(phi)`.

use kinloop::analysis::{Rest, Sampled};
use kinloop::{AtSingular, Error, SweepConfig};
use kinloop_fixtures::FourBar;
use kinloop_fixtures::cam_linkage::DwellCamRocker;
use std::f64::consts::{PI, TAU};

kinloop::mechanism! {
    /// The fixtures' slider-crank with the slider's pin as a point: `c = (x, e)`.
    pub struct SliderPin {
        params r, l, e;
        input phi;
        unknowns psi = 0, x = -l;
        loop oabo: r @ phi == (x, e) + l @ psi;
        point c = r @ phi - l @ psi;
    }
}

/// Scales of length the checks run at: the library is scale-free.
const SCALES: [f64; 3] = [1.0, 1e-3, 1e-6];

/// The open parallelogram (crank and rocker `a`, coupler and frame `3 a`): the coupler stays
/// parallel to the frame, `beta = 0`, and the rocker turns with the crank, `gamma = phi`. It
/// has change points where all four links lie on the frame (`phi = 0, pi`), which the sweep
/// passes on the parallelogram's branch.
fn parallelogram_turn(m: &FourBar) -> Sampled<'_, FourBar, 2, 2> {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    Sampled::sweep_with(m, 0.3, 0.3 + TAU, 73, [0.0, 0.3], cfg).unwrap()
}

#[test]
fn a_parallelogram_coupler_angle_that_stands_still_is_periodic() {
    for s in SCALES {
        let m = FourBar { a: s, b: 3.0 * s, c: s, d: 3.0 * s };
        let turn = parallelogram_turn(&m);
        // Its coefficients are the samples' rounding: every one of them zero within a solve's
        // rounding of an angle (1e-12 rad).
        let f = turn.fourier(FourBar::COL.beta, 4).unwrap_or_else(|e| panic!("scale {s}: {e}"));
        assert!(f.a0.abs() < 1e-12, "scale {s}: {f:?}");
        assert!(f.a.iter().chain(&f.b).all(|c| c.abs() < 1e-12), "scale {s}: {f:?}");
        // Nothing is left after any harmonic but rounding; at the change points the positions
        // are pinned less tightly (the corners there measured 1e-10 rad), so 1e-9 rad.
        let u = turn.unbalance(FourBar::COL.beta, 1).unwrap_or_else(|e| panic!("scale {s}: {e}"));
        assert!(u.max_abs < 1e-9, "scale {s}: {u:?}");
        // The rocker turns a whole turn with the crank: not periodic, as before.
        assert!(turn.fourier(FourBar::COL.gamma, 1).is_err(), "scale {s}");
        // The joint's height `a sin(phi)`: one sine harmonic of amplitude `a` from 0.3 on.
        let f = turn.fourier(FourBar::COL.pc.y, 3).unwrap();
        let (a1, b1) = (s * 0.3f64.sin(), s * 0.3f64.cos());
        assert!((f.a[0] - a1).abs() < 1e-12 * s && (f.b[0] - b1).abs() < 1e-12 * s, "scale {s}: {f:?}");
    }
}

#[test]
fn a_centred_slider_height_that_stands_still_is_periodic() {
    for s in SCALES {
        let m = SliderPin { r: s, l: 3.0 * s, e: 0.0 };
        // From 0.1: the height rounds to a different tiny value at the start and the end.
        let turn = Sampled::sweep(&m, 0.1, 0.1 + TAU, 73, [0.0, -3.9 * s]).unwrap();
        let f = turn.fourier(SliderPin::COL.c.y, 3).unwrap_or_else(|e| panic!("scale {s}: {e}"));
        // Rounding of lengths of about 4 s: 1e-12 of the mechanism's size.
        assert!(f.a0.abs() < 1e-12 * s && f.a.iter().chain(&f.b).all(|c| c.abs() < 1e-12 * s), "scale {s}: {f:?}");
        let u = turn.unbalance(SliderPin::COL.c.y, 1).unwrap_or_else(|e| panic!("scale {s}: {e}"));
        assert!(u.max_abs < 1e-12 * s, "scale {s}: {u:?}");
        // The slider's own position over half a turn is still not one period.
        let half = Sampled::sweep(&m, 0.1, 0.1 + TAU / 2.0, 37, [0.0, -3.9 * s]).unwrap();
        assert!(half.fourier(SliderPin::COL.x, 1).is_err(), "scale {s}");
    }
}

/// The dwells of a column that stands still: it has no net travel, at every scale. Its
/// rounding's travel was judged against its range, rounding too: the parallelogram's coupler
/// angle passed as progressive, with no dwell at one scale and a search stepping into a change
/// point's band (`NearSingular`) at another.
#[test]
fn a_column_that_stands_still_has_no_net_travel_for_dwells() {
    for s in SCALES {
        let m = FourBar { a: s, b: 3.0 * s, c: s, d: 3.0 * s };
        let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
        let run = Sampled::sweep_with(&m, 0.3, 0.3 + 0.9 * TAU, 65, [0.0, 0.3], cfg).unwrap();
        let r = run.dwells(FourBar::COL.beta);
        assert!(matches!(&r, Err(Error::InvalidArgument(e)) if e.contains("no net travel")), "scale {s}: {r:?}");
        // The rocker, turning with the crank, is progressive: no reversal, no dwell.
        assert_eq!(run.dwells(FourBar::COL.gamma).unwrap(), [], "scale {s}");
        let m = SliderPin { r: s, l: 3.0 * s, e: 0.0 };
        let run = Sampled::sweep(&m, 0.1, 0.1 + 0.9 * TAU, 65, [0.0, -3.9 * s]).unwrap();
        let r = run.dwells(SliderPin::COL.c.y);
        assert!(matches!(&r, Err(Error::InvalidArgument(e)) if e.contains("no net travel")), "scale {s}: {r:?}");
    }
}

/// The extremes of a column that stands still: none, at every scale. The sign changes of its
/// analog, rounding, were reported as some thirty maxima and minima a turn, at crank angles the
/// rounding chose. Its range is its rounding; a column that moves keeps its extremes.
#[test]
fn a_column_that_stands_still_has_no_extremes() {
    for s in SCALES {
        let m = FourBar { a: s, b: 3.0 * s, c: s, d: 3.0 * s };
        let turn = parallelogram_turn(&m);
        assert_eq!(turn.extremes(FourBar::COL.beta).unwrap(), [], "scale {s}");
        let r = turn.range(FourBar::COL.beta).unwrap();
        assert!(r.extremes.is_empty(), "scale {s}: {r:?}");
        // Rounding, and beside the change points the positions pinned to about 1e-10 rad.
        assert!(r.min.value.abs() < 1e-9 && r.max.value.abs() < 1e-9, "scale {s}: {r:?}");
        // The joint's height `a sin(phi)` keeps its two extremes, at pi/2 and 3 pi/2.
        let e = turn.extremes(FourBar::COL.pc.y).unwrap();
        assert_eq!(e.len(), 2, "scale {s}: {e:?}");
        assert!((e[0].x() - PI / 2.0).abs() < 1e-9 && (e[1].x() - 1.5 * PI).abs() < 1e-9, "scale {s}: {e:?}");
        let m = SliderPin { r: s, l: 3.0 * s, e: 0.0 };
        let turn = Sampled::sweep(&m, 0.1, 0.1 + TAU, 73, [0.0, -3.9 * s]).unwrap();
        assert_eq!(turn.extremes(SliderPin::COL.c.y).unwrap(), [], "scale {s}");
        // The slider's dead centres at 180 degrees and a full turn: x = -(l + r) and -(l - r).
        let e = turn.extremes(SliderPin::COL.x).unwrap();
        assert_eq!(e.len(), 2, "scale {s}: {e:?}");
        assert!((e[0].value() + 4.0 * s).abs() < 1e-12 * s && (e[1].value() + 2.0 * s).abs() < 1e-12 * s, "{e:?}");
    }
}

kinloop::mechanism! {
    /// The centred slider-crank of [`SliderPin`] with the pin's height over the rod's length as
    /// a ratio: `r sin(phi) - l sin(psi)` is zero in exact arithmetic (the pin stays on the
    /// line of the slider), so the ratio is rounding alone, some 1e-16 of the sines summed.
    pub struct SliderRatio {
        params r, l;
        input phi;
        unknowns psi = 0, x = -l;
        loop oabo: r @ phi == (x, 0) + l @ psi;
        output h = (r * sin(phi) - l * sin(psi)) / l;
    }
}

/// A dimensionless column that stands still in exact arithmetic (a ratio of lengths that is
/// zero) is periodic, has no extremes and no net travel, at every scale: judged against its
/// own size, rounding, the noise at the start and the end of a turn made it "not periodic",
/// and the sign changes of its analog extremes. A pure number's rounding is absolute (a few
/// ulps of the sines and ratios it is computed from, of size one), as an angle's is.
#[test]
fn a_ratio_that_stands_still_is_periodic() {
    for s in SCALES {
        let m = SliderRatio { r: s, l: 3.0 * s };
        let turn = Sampled::sweep(&m, 0.1, 0.1 + TAU, 73, [0.0, -3.9 * s]).unwrap();
        let jets = turn.jets(SliderRatio::COL.h).unwrap();
        // The exact value is zero: the samples are rounding, a solve's 1e-12 at most.
        assert!(jets.iter().all(|j| j.value.abs() < 1e-12), "scale {s}: {jets:?}");
        let f = turn.fourier(SliderRatio::COL.h, 3).unwrap_or_else(|e| panic!("scale {s}: {e}"));
        assert!(f.a0.abs() < 1e-12 && f.a.iter().chain(&f.b).all(|c| c.abs() < 1e-12), "scale {s}: {f:?}");
        let u = turn.unbalance(SliderRatio::COL.h, 1).unwrap_or_else(|e| panic!("scale {s}: {e}"));
        assert!(u.max_abs < 1e-12, "scale {s}: {u:?}");
        assert_eq!(turn.extremes(SliderRatio::COL.h).unwrap(), [], "scale {s}");
        let run = Sampled::sweep(&m, 0.1, 0.1 + 0.9 * TAU, 65, [0.0, -3.9 * s]).unwrap();
        let r = run.dwells(SliderRatio::COL.h);
        assert!(matches!(&r, Err(Error::InvalidArgument(e)) if e.contains("no net travel")), "scale {s}: {r:?}");
    }
}

kinloop::mechanism! {
    /// The centred slider-crank of [`SliderPin`] with the squared length of its rod from the
    /// crank pin `r @ phi` to the slider's pin `(x, 0)`: an area (length squared), whose kind
    /// kinloop does not infer, equal to `l^2` in exact arithmetic at every crank angle.
    pub struct SliderRodSquared {
        params r, l;
        input phi;
        unknowns psi = 0, x = -l;
        loop oabo: r @ phi == (x, 0) + l @ psi;
        output ll = (x - r * cos(phi)) * (x - r * cos(phi)) + r * sin(phi) * r * sin(phi);
    }
}

/// A column of a kind not inferred (an area) that is constant in exact arithmetic has no
/// extremes and no net travel, at every scale: its rounding, some 1e-16 of its own size, was
/// judged against nothing (exactly equal values only), and the sign changes of its analog were
/// 28 "extremes" a turn (at scale 1) at crank angles the rounding chose, as
/// [`a_column_that_stands_still_has_no_extremes`] saw of an angle's. Judged against its own
/// size (as `fourier` judges its return to its start), it stands still.
#[test]
fn a_column_of_unknown_kind_that_stands_still_has_no_extremes() {
    for s in SCALES {
        let m = SliderRodSquared { r: s, l: 3.0 * s };
        let turn = Sampled::sweep(&m, 0.1, 0.1 + TAU, 73, [0.0, -3.9 * s]).unwrap();
        let jets = turn.jets(SliderRodSquared::COL.ll).unwrap();
        // The exact value is l^2 = 9 s^2: the samples are within a solve's rounding (1e-12 of
        // the lengths squared) of it.
        assert!(jets.iter().all(|j| (j.value - 9.0 * s * s).abs() < 1e-12 * s * s), "scale {s}: {jets:?}");
        assert_eq!(turn.extremes(SliderRodSquared::COL.ll).unwrap(), [], "scale {s}");
        let r = turn.range(SliderRodSquared::COL.ll).unwrap();
        assert!(r.extremes.is_empty() && r.span() < 1e-12 * s * s, "scale {s}: {r:?}");
        let run = Sampled::sweep(&m, 0.1, 0.1 + 0.9 * TAU, 65, [0.0, -3.9 * s]).unwrap();
        let r = run.dwells(SliderRodSquared::COL.ll);
        assert!(matches!(&r, Err(Error::InvalidArgument(e)) if e.contains("no net travel")), "scale {s}: {r:?}");
        // The slider's own position keeps its dead centres.
        assert_eq!(turn.extremes(SliderRodSquared::COL.x).unwrap().len(), 2, "scale {s}");
    }
}

/// The rests of a column that stands still (its values within its rounding over the range, as
/// `extremes` judges it): one, the whole range, at every scale. Its velocity analog, exactly
/// zero over some stretches and rounding over others, made rests of those stretches at values
/// apart by their rounding: the slider's height "stood still" over several stretches of a turn, and
/// `kinloop extremes` noted them one by one. A column that moves keeps its rests: the dwell
/// cam's follower rests at the top and the bottom of its lift, its height moving between.
#[test]
fn a_column_that_stands_still_rests_over_the_whole_range() {
    // One rest, from the first sample's input to the last's.
    let whole =
        |path: &[f64], r: &[Rest]| r.len() == 1 && r[0].start.x == path[0] && r[0].end.x == path[path.len() - 1];
    for s in SCALES {
        let m = SliderPin { r: s, l: 3.0 * s, e: 0.0 };
        let turn = Sampled::sweep(&m, 0.1, 0.1 + TAU, 73, [0.0, -3.9 * s]).unwrap();
        let r = turn.rests(SliderPin::COL.c.y).unwrap();
        assert!(whole(turn.path_values(), &r), "scale {s}: {r:?}");
        // At its value, zero to the rounding of lengths of about 4 s.
        assert!(r[0].value().abs() < 1e-12 * s, "scale {s}: {r:?}");
        // The slider moves: no rest.
        assert_eq!(turn.rests(SliderPin::COL.x).unwrap(), [], "scale {s}");
        let m = SliderRatio { r: s, l: 3.0 * s };
        let turn = Sampled::sweep(&m, 0.1, 0.1 + TAU, 73, [0.0, -3.9 * s]).unwrap();
        let r = turn.rests(SliderRatio::COL.h).unwrap();
        assert!(whole(turn.path_values(), &r), "scale {s}: {r:?}");
        let m = SliderRodSquared { r: s, l: 3.0 * s };
        let turn = Sampled::sweep(&m, 0.1, 0.1 + TAU, 73, [0.0, -3.9 * s]).unwrap();
        let r = turn.rests(SliderRodSquared::COL.ll).unwrap();
        assert!(whole(turn.path_values(), &r), "scale {s}: {r:?}");
        let m = FourBar { a: s, b: 3.0 * s, c: s, d: 3.0 * s };
        let turn = parallelogram_turn(&m);
        let r = turn.rests(FourBar::COL.beta).unwrap();
        assert!(whole(turn.path_values(), &r), "scale {s}: {r:?}");
        assert_eq!(turn.rests(FourBar::COL.pc.y).unwrap(), [], "scale {s}");
    }
    let m = DwellCamRocker::default();
    let from = m.phi0 + 0.5 * m.rise;
    let turn = Sampled::sweep(&m, from, from + TAU, 73, m.guess(from)).unwrap();
    let r = turn.rests(DwellCamRocker::COL.follower.y).unwrap();
    // At the top from the end of the rise to `phi1`, at the bottom from the end of the return
    // to `phi0` a turn on; located as `rests.rs` checks them (within 1e-7 rad).
    let ends: Vec<(f64, f64, f64)> = r.iter().map(|r| (r.start.x, r.end.x, r.value())).collect();
    let want = [(m.phi0 + m.rise, m.phi1, m.y0 + m.lift), (m.phi1 + m.fall, TAU + m.phi0, m.y0)];
    assert_eq!(ends.len(), 2, "{r:?}");
    for (got, want) in ends.iter().zip(want) {
        assert!((got.0 - want.0).abs() < 1e-7 && (got.1 - want.1).abs() < 1e-7, "{got:?} vs {want:?}");
        assert!((got.2 - want.2).abs() <= 4.0 * f64::EPSILON * want.2, "{got:?} vs {want:?}");
    }
}
