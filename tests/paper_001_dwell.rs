//! Paper 001 (SEEDS.md), the numbers printed by `examples/gear_lever.rs`: dwell duration, dwell
//! quality (rocker swing) and peak acceleration analog for k = 1.1 ... 1.5, from the analysis
//! helpers on the generated kinematics, against an independent computation from the paper's
//! explicit formulas (rocker angle `atan2(x, y)`, `omega_r`, `eps_r`) with bisection and
//! golden-section search, using the symmetry of the stop about alpha = 0.

use kinloop::analysis::{ExtremeKind, Sampled};
use std::f64::consts::{PI, TAU};

kinloop::mechanism! {
    /// Gear-lever drive (as in the example).
    pub struct GearLever {
        params l_c = 2.0, l_p = 1.3, u = 3.0;
        input alpha;
        unknowns s = l_c + l_p, phi = 0;
        let pin = (l_c * sin(alpha), l_c * cos(alpha))
                + (l_p * sin((1 - u) * alpha), l_p * cos((1 - u) * alpha));
        loop oab: pin == s * (sin(phi), cos(phi));
    }
}

/// The paper's explicit formulas for u = 3, L = 2, l = k: rocker angle, omega_r / omega,
/// eps_r / omega^2.
fn explicit(k: f64, a: f64) -> (f64, f64, f64) {
    let x = 2.0 * a.sin() - k * (2.0 * a).sin();
    let y = 2.0 * a.cos() + k * (2.0 * a).cos();
    let xd = 2.0 * a.cos() - 2.0 * k * (2.0 * a).cos();
    let yd = -2.0 * a.sin() - 2.0 * k * (2.0 * a).sin();
    let xdd = -2.0 * a.sin() + 4.0 * k * (2.0 * a).sin();
    let ydd = -2.0 * a.cos() - 4.0 * k * (2.0 * a).cos();
    let r2 = x * x + y * y;
    let w = (xd * y - yd * x) / r2;
    let e = ((xdd * y - ydd * x) * r2 - 2.0 * (xd * y - yd * x) * (xd * x + yd * y)) / (r2 * r2);
    (x.atan2(y), w, e)
}

fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let flo = f(lo);
    assert!(flo * f(hi) < 0.0, "no sign change on [{lo}, {hi}]");
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (f(mid) < 0.0) == (flo < 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Independent stop characteristics: (duration, swing, peak acceleration analog) in radians.
fn independent(k: f64) -> (f64, f64, f64) {
    // The rocker angle is odd in alpha: phi(-a) = -phi(a). Near alpha = 0 the rocker runs
    // backwards; the reversal is from the maximum at -a1 to the minimum at +a1, where omega_r
    // vanishes (a1 in (0, 60 deg)); the swing is 2 |phi(a1)|. The rocker leaves the band where
    // phi(a2) = phi(-a1) = -phi(a1) with a2 > a1; by symmetry it entered at -a2.
    let a1 = bisect(|a| explicit(k, a).1, 1e-9, PI / 3.0);
    let phi1 = explicit(k, a1).0;
    let a2 = bisect(|a| explicit(k, a).0 + phi1, a1, PI / 3.0);
    // The peak acceleration analog: a dense scan over one stop cycle, refined by golden sections.
    let acc = |a: f64| explicit(k, a).2;
    let n = 12_000;
    let best = (0..n).map(|i| 2.0 * PI / 3.0 * i as f64 / n as f64).max_by(|a, b| acc(*a).total_cmp(&acc(*b))).unwrap();
    let h = 2.0 * PI / 3.0 / n as f64;
    let (mut lo, mut hi) = (best - h, best + h);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if acc(c) > acc(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    (2.0 * a2, -2.0 * phi1, acc(0.5 * (lo + hi)))
}

/// The example's computation (same calls).
fn with_helpers(k: f64) -> (Vec<kinloop::analysis::Dwell>, (f64, f64)) {
    let m = GearLever { l_p: k, ..GearLever::default() };
    let from = -PI / 3.0;
    let turn = Sampled::sweep(&m, from, from + TAU, 721, m.guess(from).into()).unwrap();
    let dwells = turn.dwells("phi").unwrap();
    let peak = turn.peak(|s| s.d2q[1][0][0]).unwrap();
    (dwells, peak)
}

#[test]
fn dwell_duration_quality_and_peak_acceleration_match_the_explicit_formulas() {
    // The example prints these (degrees, 6 decimals): duration, swing, max acceleration analog.
    let printed = [
        (1.1, 55.945290, 1.286465, 16.340509),
        (1.2, 75.095631, 3.581077, 22.390975),
        (1.3, 87.586130, 6.513532, 31.492545),
        (1.4, 96.581801, 9.991301, 45.944919),
        (1.5, 103.363357, 14.009886, 70.629620),
    ];
    let mut previous = (0.0, 0.0, 0.0);
    for (k, p_duration, p_swing, p_acc) in printed {
        let (dwells, (x_peak, acc)) = with_helpers(k);
        let (duration, swing, peak) = independent(k);
        assert_eq!(dwells.len(), 3, "k = {k}: three stops per carrier turn");
        for (i, d) in dwells.iter().enumerate() {
            // Each stop is centred on alpha = 0, 120, 240 degrees and has the same duration and
            // swing (three-fold symmetry). Root tolerances: the helpers locate roots of the
            // generated analogs to rounding; bisection is exact to rounding too; the positions
            // themselves carry the Newton tolerance (~1e-12).
            let centre = 2.0 * PI / 3.0 * i as f64;
            assert_eq!(d.first.kind, ExtremeKind::Max);
            assert!(((d.start.x + d.end.x) / 2.0 - centre).abs() < 1e-10, "k = {k}, stop {i}");
            assert!((d.duration() - duration).abs() < 1e-10, "k = {k}: {} vs {duration}", d.duration());
            assert!((d.swing() - swing).abs() < 1e-10, "k = {k}: {} vs {swing}", d.swing());
            // The located extremes are where omega_r = 0 in the explicit formula.
            assert!(explicit(k, d.first.x()).1.abs() < 1e-10 && explicit(k, d.second.x()).1.abs() < 1e-10);
        }
        // Brent locates the peak to ~1e-8 rad; the value is then exact to ~1e-15 relative.
        assert!((acc - peak).abs() < 1e-9 * peak, "k = {k}: {acc} vs {peak}");
        assert!((explicit(k, x_peak).2 - acc).abs() < 1e-9 * peak);
        // The printed numbers (degrees, rounded to 6 decimals).
        assert!((duration.to_degrees() - p_duration).abs() < 6e-7, "k = {k}: {}", duration.to_degrees());
        assert!((swing.to_degrees() - p_swing).abs() < 6e-7, "k = {k}: {}", swing.to_degrees());
        assert!((peak - p_acc).abs() < 6e-7, "k = {k}: {peak}");
        // The paper's finding: the farther the pin from the planet centre, the longer the dwell
        // and the worse its quality (and the harder the acceleration).
        assert!(duration > previous.0 && swing > previous.1 && peak > previous.2, "k = {k}");
        previous = (duration, swing, peak);
    }
}

#[test]
fn the_stops_do_not_depend_on_size() {
    // Angular results depend on the ratios only: scale every length by 2.5.
    let (a, _) = with_helpers(1.3);
    let m = GearLever { l_c: 5.0, l_p: 1.3 * 2.5, u: 3.0 };
    let from = -PI / 3.0;
    let turn = Sampled::sweep(&m, from, from + TAU, 721, m.guess(from).into()).unwrap();
    let b = turn.dwells("phi").unwrap();
    assert!((a[0].duration() - b[0].duration()).abs() < 1e-10 && (a[0].swing() - b[0].swing()).abs() < 1e-10);
}
