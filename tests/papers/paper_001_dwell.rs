//! Paper 001 (`docs/papers.md`), the mechanism and numbers of `examples/gear_lever.rs`: dwell duration,
//! dwell quality (rocker swing) and peak acceleration analog for k = 1.1 ... 1.5, from the analysis
//! helpers on the generated kinematics, against an independent computation from the paper's
//! explicit formulas (rocker angle `atan2(x, y)`, `omega_r`, `eps_r`) with bisection and
//! golden-section search, using the symmetry of the stop about alpha = 0.

use kinloop::analysis::Extreme;
use std::f64::consts::PI;

use kinloop_fixtures::gear_lever::{GearLever, stops};

use crate::support::{argmax, bisect, gear_lever_explicit};

/// The paper's explicit formulas for u = 3, L = 2, l = k: rocker angle, omega_r / omega,
/// eps_r / omega^2.
fn explicit(k: f64, a: f64) -> (f64, f64, f64) {
    let [phi, omega_r, eps_r, ..] = gear_lever_explicit(2.0, k, 3.0, a);
    (phi, omega_r, eps_r)
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
    (2.0 * a2, -2.0 * phi1, acc(argmax(acc, 2.0 * PI / 3.0, 12_000)))
}

/// The example's computation for `k` (its `stops`).
fn with_helpers(k: f64) -> (Vec<kinloop::analysis::Dwell>, (f64, f64)) {
    stops(&GearLever { l_p: k, ..GearLever::default() }).unwrap()
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
            assert_eq!(d.first.kind, Extreme::Max);
            assert_close!((d.start.x + d.end.x) / 2.0, centre, 1e-10, "k = {k}, stop {i}");
            assert_close!(d.duration(), duration, 1e-10, "k = {k}: {} vs {duration}", d.duration());
            assert_close!(d.swing(), swing, 1e-10, "k = {k}: {} vs {swing}", d.swing());
            // The located extremes are where omega_r = 0 in the explicit formula.
            assert!(explicit(k, d.first.x()).1.abs() < 1e-10 && explicit(k, d.second.x()).1.abs() < 1e-10);
        }
        // Brent locates the peak to ~1e-8 rad; the value is then exact to ~1e-15 relative.
        assert_close!(acc, peak, 1e-9 * peak, "k = {k}: {acc} vs {peak}");
        assert_close!(explicit(k, x_peak).2, acc, 1e-9 * peak);
        // The printed numbers (degrees, rounded to 6 decimals).
        assert_close!(duration.to_degrees(), p_duration, 6e-7, "k = {k}: {}", duration.to_degrees());
        assert_close!(swing.to_degrees(), p_swing, 6e-7, "k = {k}: {}", swing.to_degrees());
        assert_close!(peak, p_acc, 6e-7, "k = {k}: {peak}");
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
    let (b, _) = stops(&GearLever { l_c: 5.0, l_p: 1.3 * 2.5, u: 3.0 }).unwrap();
    assert_close!(a[0].duration(), b[0].duration(), 1e-10);
    assert_close!(a[0].swing(), b[0].swing(), 1e-10);
}
