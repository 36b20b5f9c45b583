//! `Sampled::fourier`, `unbalance` and `dwells` of a mechanism a millimetre across, in metres,
//! translated far from the origin (6.4e6 m out: Earth-centred coordinates). The same mechanism
//! at the origin is the reference: the same periods, the same coefficients but the mean (moved
//! by the offset), the same residual and the same dwells, to the rounding of the positions
//! there. Whether the samples were one period, and whether a column travelled, was judged
//! against 1e-9 of the values' magnitude, 6.4 mm out there: half a turn of the slider (2 mm
//! stroke) passed for a period, and a point travelling 6.3 mm a turn had "no net travel".

use kinloop::Error;
use kinloop::analysis::Sampled;
use std::f64::consts::{FRAC_PI_2, TAU};

kinloop::mechanism! {
    /// The fixtures' offset slider-crank with its crank pivoted at `(ox, oy)`: crank `r` at
    /// angle `phi`, rod `l` at `psi`, the slider's pin at `(x, oy + e)`; and a point `roll`
    /// rolling along, `r phi` on from the pivot and `1.5 r` out at `phi` (a prolate cycloid,
    /// advancing `2 pi r` a turn with one reversal).
    pub struct FarSlider {
        params r, l, e, ox, oy;
        input phi;
        unknowns psi = 0, x = 0;
        loop rod: (ox, oy) + r @ phi == (x, oy + e) + l @ psi;
        point pin = (x, oy + e);
        point roll = (ox + r * phi, oy) + 1.5 * r @ phi;
    }
}

/// The rounding of a position `offset` out: what the same mechanism's results may differ by.
fn rounding(offset: f64) -> f64 {
    16.0 * f64::EPSILON * offset
}

#[test]
fn a_mechanism_far_from_the_origin_has_the_same_periods_harmonics_and_dwells() {
    let r = 1e-3;
    let at = |ox: f64, oy: f64| FarSlider { r, l: 3.0 * r, e: 0.5 * r, ox, oy };
    let guess = |m: &FarSlider| [0.0, m.ox + 3.5 * r];
    let near = at(0.0, 0.0);
    let turn = Sampled::sweep(&near, 0.1, 0.1 + TAU, 73, guess(&near)).unwrap();
    let f0 = turn.fourier(FarSlider::COL.x, 2).unwrap();
    let u0 = turn.unbalance(FarSlider::COL.x, 1).unwrap();
    // One period of the roll, from where it moves forward fastest: one whole dwell, from its
    // maximum where sin(phi) = 2/3 to its minimum, a swing of r (2 asin(2/3) - pi + 3 cos(asin(2/3))).
    let run = Sampled::sweep(&near, -FRAC_PI_2, -FRAC_PI_2 + TAU, 73, guess(&near)).unwrap();
    let d0 = run.dwells(FarSlider::COL.roll.x).unwrap();
    let t = (2.0f64 / 3.0).asin();
    let swing = r * (2.0 * t - std::f64::consts::PI + 3.0 * t.cos());
    assert_eq!(d0.len(), 1, "{d0:?}");
    assert!((d0[0].swing() - swing).abs() < 1e-12 * r, "{} against {swing}", d0[0].swing());
    for (ox, oy) in [(6.4e6, 6.4e6), (-1e7, 1e7)] {
        let far = at(ox, oy);
        let tol = rounding(ox.abs().max(oy.abs()));
        let half = Sampled::sweep(&far, 0.1, 0.1 + TAU / 2.0, 37, guess(&far)).unwrap();
        let r1 = half.fourier(FarSlider::COL.x, 2);
        assert!(matches!(&r1, Err(Error::InvalidArgument(m)) if m.contains("not periodic")), "{ox:e}: {r1:?}");
        let r1 = half.unbalance(FarSlider::COL.x, 1);
        assert!(matches!(&r1, Err(Error::InvalidArgument(m)) if m.contains("not periodic")), "{ox:e}: {r1:?}");
        let turn = Sampled::sweep(&far, 0.1, 0.1 + TAU, 73, guess(&far)).unwrap();
        let f = turn.fourier(FarSlider::COL.x, 2).unwrap();
        assert!((f.a0 - ox - f0.a0).abs() < tol, "{ox:e}: {f:?} against {f0:?}");
        for (c, c0) in f.a.iter().chain(&f.b).zip(f0.a.iter().chain(&f0.b)) {
            assert!((c - c0).abs() < tol, "{ox:e}: {f:?} against {f0:?}");
        }
        let u = turn.unbalance(FarSlider::COL.x, 1).unwrap();
        assert!((u.max_abs - u0.max_abs).abs() < tol, "{ox:e}: {} against {}", u.max_abs, u0.max_abs);
        let run = Sampled::sweep(&far, -FRAC_PI_2, -FRAC_PI_2 + TAU, 73, guess(&far)).unwrap();
        let d = run.dwells(FarSlider::COL.roll.x).unwrap_or_else(|e| panic!("{ox:e}: {e}"));
        assert_eq!(d.len(), 1, "{ox:e}: {d:?}");
        // The ends are crossings of a band edge by a value resolved to `tol`, moving at about r
        // per radian.
        assert!((d[0].swing() - swing).abs() < tol, "{ox:e}: {} against {swing}", d[0].swing());
        assert!((d[0].start.x - d0[0].start.x).abs() < tol / r, "{ox:e}: {d:?} against {d0:?}");
        assert!((d[0].end.x - d0[0].end.x).abs() < tol / r, "{ox:e}: {d:?} against {d0:?}");
    }
}
