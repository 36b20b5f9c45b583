//! The rests of the dwell cam's follower and rocker, against its law: with a rise-dwell-
//! return-dwell law the follower stands exactly still at the top from `phi0 + rise` to `phi1`
//! and at the bottom from `phi1 + fall` to `phi0` a turn on, and the rocker it drives with it.
//! An oscillating output has no dwell as `Sampled::dwells` defines it (no net travel); its
//! rests are what a cam designer reads. Across sizes 1e-6 to 1e6, 37 to 361 samples and the
//! three columns, the ends lie within 8.3e-9 rad of the law's switches (measured when the test
//! was written; see `ENDS`).

use kinloop::analysis::Sampled;
use kinloop_fixtures::cam_linkage::DwellCamRocker;
use std::f64::consts::TAU;

/// How far from the law's switch a rest's end may be located. The 3-4-5 law leaves a rest
/// smoothly: its velocity analog `30 h u^2 (1 - u)^2 / rise` vanishes as the square of the
/// distance `d` from the switch, and computed as the law's declaration writes it (`3 u^2 (10 -
/// 15 u + 6 u^2) + u^3 (-15 + 12 u)`, two terms of about 3 cancelling) it rounds to exactly zero
/// where `30 (d / rise)^2` is below their rounding, `3 eps`: within `rise sqrt(eps / 10)`, about
/// 1e-8 rad, of the switch, where the follower moves by `h (d / rise)^3`, 1e-24 of its lift, far
/// below the rounding of its value. Ten times that.
const ENDS: f64 = 1e-7;

#[test]
fn the_dwell_cams_follower_and_rocker_rest_where_its_law_dwells() {
    for k in [1e-6, 1.0, 1e6] {
        let base = DwellCamRocker::default();
        let m = DwellCamRocker {
            lift: base.lift * k,
            y0: base.y0 * k,
            l_rod: base.l_rod * k,
            c: base.c * k,
            d_x: base.d_x * k,
            d_y: base.d_y * k,
            ..base
        };
        // From the middle of the rise, where the follower moves: both rests of the turn whole.
        let from = m.phi0 + 0.5 * m.rise;
        let top = (m.phi0 + m.rise, m.phi1);
        let bottom = (m.phi1 + m.fall, TAU + m.phi0);
        for samples in [37, 73, 361] {
            let turn = Sampled::sweep(&m, from, from + TAU, samples, m.guess(from)).unwrap();
            // The rod's angle too, whose velocity analog also crosses zero at the first sample
            // (rounded to exactly zero there, over a few units in the last place): an instant,
            // not a rest.
            let columns = [
                (DwellCamRocker::COL.follower.y, "follower"),
                (DwellCamRocker::COL.psi, "psi"),
                (DwellCamRocker::COL.gamma, "gamma"),
            ];
            for (column, name) in columns {
                let r = turn.rests(column).unwrap();
                assert_eq!(r.len(), 2, "size {k:e}, {samples} samples, {name}: {r:?}");
                for (rest, (start, end)) in r.iter().zip([top, bottom]) {
                    assert!(
                        (rest.start.x - start).abs() < ENDS && (rest.end.x - end).abs() < ENDS,
                        "size {k:e}, {samples} samples, {name}: {rest:?} against {start}..{end}"
                    );
                    assert_eq!((rest.start.d1, rest.end.d1), (0.0, 0.0));
                    // Still, up to the rounding of the value near an end (see `ENDS`).
                    let ulps = 4.0 * f64::EPSILON * rest.start.value.abs();
                    assert!((rest.start.value - rest.end.value).abs() <= ulps, "{name} stands still: {rest:?}");
                }
            }
            // The follower at the top and the bottom of its lift.
            let r = turn.rests(DwellCamRocker::COL.follower.y).unwrap();
            for (got, want) in [(r[0].value(), m.y0 + m.lift), (r[1].value(), m.y0)] {
                assert!((got - want).abs() <= 4.0 * f64::EPSILON * want, "size {k:e}: {got} against {want}");
            }
            // A dwell needs net travel: the follower has none.
            assert!(turn.dwells(DwellCamRocker::COL.follower.y).is_err());
        }
    }
}
