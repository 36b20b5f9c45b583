//! The numbers the `dwell_cam` example prints: the peaks of the follower's analogs in the rise
//! and the return agree with the 3-4-5 law's closed form, and the follower and the rocker stand
//! exactly still in every dwell; the cam found by inversion has the radial follower's pressure
//! angle and the pitch curve's radius of curvature as a polar curve. The closed forms are worked
//! out by hand from the law's polynomial, here and in the fixtures' `law_by_hand` (never read
//! from the example or the library), for the default cam and for a second one with other lift,
//! segment angles and dwells.

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../dwell_cam.rs"]
mod dwell_cam;

use dwell_cam::{ROLLER, Segment, cam, check_dwell, dwells, peak_pressure, segment_peaks, segments, turn};
use kinloop_fixtures::cam_linkage::DwellCamRocker;
use std::f64::consts::TAU;

/// The two cams checked: the default, and one with a shorter lift, a quicker rise and a slower
/// return (so that no number of the default is built into the check).
fn cams() -> [DwellCamRocker; 2] {
    [
        DwellCamRocker::default(),
        DwellCamRocker {
            lift: 12.0,
            phi0: 10f64.to_radians(),
            rise: 90f64.to_radians(),
            phi1: 150f64.to_radians(),
            fall: 140f64.to_radians(),
            ..DwellCamRocker::default()
        },
    ]
}

/// The law's polynomial in the normalised cam angle `u`, `p = 10 u^3 - 15 u^4 + 6 u^5`, and its
/// first two derivatives, multiplied out by hand: `p' = 30 u^2 (1 - u)^2`,
/// `p'' = 60 u (1 - u) (1 - 2 u)`.
fn law(u: f64) -> [f64; 3] {
    [
        10.0 * u.powi(3) - 15.0 * u.powi(4) + 6.0 * u.powi(5),
        30.0 * (u * (1.0 - u)).powi(2),
        60.0 * u * (1.0 - u) * (1.0 - 2.0 * u),
    ]
}

/// The closed-form peaks of a segment: `(cam angle, value)` of the velocity analog of largest
/// magnitude and of the largest and the smallest acceleration analog. `p'` is largest where
/// `p'' = 0` inside, at `u = 1/2`; `p''` is extreme where `p''' = 60 (1 - 6 u + 6 u^2) = 0`, at
/// `u = (3 -+ sqrt 3) / 6`. The return runs the polynomial backwards (`s = h (1 - p(w))`), so
/// its analogs are the rise's negated.
fn closed_form(m: &DwellCamRocker, seg: &Segment) -> [(f64, f64); 3] {
    let (h, beta, sign) = (m.lift, seg.span, seg.sign);
    let (u_up, u_down) = ((3.0 - 3f64.sqrt()) / 6.0, (3.0 + 3f64.sqrt()) / 6.0);
    let at = |u: f64| seg.start + u * beta;
    let velocity = (at(0.5), sign * h / beta * law(0.5)[1]);
    let up = (at(u_up), sign * h / (beta * beta) * law(u_up)[2]);
    let down = (at(u_down), sign * h / (beta * beta) * law(u_down)[2]);
    if sign > 0.0 { [velocity, up, down] } else { [velocity, down, up] }
}

#[test]
fn the_closed_form_is_the_known_one() {
    // 15/8 at the middle, 10 / sqrt 3 at the inflection points of p'.
    assert_eq!(law(0.5)[1], 1.875);
    let u = (3.0 - 3f64.sqrt()) / 6.0;
    assert!((law(u)[2] - 10.0 / 3f64.sqrt()).abs() < 1e-13);
    assert!((law(1.0 - u)[2] + 10.0 / 3f64.sqrt()).abs() < 1e-13);
    // The polynomial rises from rest to rest: p(0) = 0, p(1) = 1, p' and p'' zero at both ends.
    assert_eq!([law(0.0), law(1.0)], [[0.0; 3], [1.0, 0.0, 0.0]]);
}

/// The located peaks' values agree with the closed form to 1e-12 of the peak (they are
/// evaluated at the located angle, where the analog is flat, so the location's error enters
/// only squared); their cam angles to 1e-6 rad (Brent's search stops within about
/// `sqrt(eps)` of the angle).
#[test]
fn the_printed_peaks_agree_with_the_closed_form() -> Result<(), Box<dyn std::error::Error>> {
    for m in cams() {
        for seg in segments(&m) {
            let p = segment_peaks(&m, &seg)?;
            let located = [p.velocity, p.acceleration_max, p.acceleration_min];
            let names = ["velocity analog", "largest acceleration analog", "smallest acceleration analog"];
            for ((name, got), (at, value)) in names.iter().zip(located).zip(closed_form(&m, &seg)) {
                let what = format!("{} {name} (lift {}, span {})", seg.name, m.lift, seg.span);
                assert!((got.value - value).abs() <= 1e-12 * value.abs(), "{what}: {} vs {value}", got.value);
                assert!((got.at - at).abs() <= 1e-6, "{what}: at {} vs {at}", got.at);
            }
        }
    }
    Ok(())
}

/// In every dwell the follower and the rocker are exactly still (analogs zero, positions equal
/// at every sample), the follower at the bottom or at the full lift; the dwells and the moving
/// segments tile the turn.
#[test]
fn the_dwells_are_exactly_still() -> Result<(), Box<dyn std::error::Error>> {
    for m in cams() {
        let [d0, d1, d2] = dwells(&m);
        let [rise, ret] = segments(&m);
        let ends = [d0.from, d0.to, rise.start + rise.span, d1.to, ret.start + ret.span, d2.to];
        assert_eq!(ends, [0.0, rise.start, d1.from, ret.start, d2.from, TAU], "the turn's pieces");
        let mut bottom_psi = Vec::new();
        for (d, lift) in [(d0, 0.0), (d1, m.lift), (d2, 0.0)] {
            let c = check_dwell(&m, &d)?;
            assert!(c.still && c.analogs == [0.0; 4], "{} dwell of the lift {}: {c:?}", d.name, m.lift);
            assert_eq!(c.lift, lift, "{} dwell", d.name);
            if lift == 0.0 {
                bottom_psi.push(c.psi);
            }
        }
        // One position at the bottom, before the rise and after the return.
        assert!((bottom_psi[0] - bottom_psi[1]).abs() <= 1e-12, "{bottom_psi:?}");
    }
    Ok(())
}

/// The check of a dwell sees motion: over the rise it reports the follower moving.
#[test]
fn the_dwell_check_sees_a_moving_follower() -> Result<(), Box<dyn std::error::Error>> {
    let m = DwellCamRocker::default();
    let rise = dwell_cam::Dwell { name: "rise", from: m.phi0, to: m.phi0 + m.rise };
    let c = check_dwell(&m, &rise)?;
    assert!(!c.still && c.analogs.iter().all(|&a| a > 0.0), "{c:?}");
    Ok(())
}

/// The cam the example prints, at every half degree: its follower's line passes through the
/// cam's centre, so the pitch curve is the polar curve `R = y0 + s` and the pressure angle
/// `atan(|s'| / R)`; the radius of curvature of a polar curve is
/// `(R^2 + R'^2)^(3/2) / (R^2 + 2 R'^2 - R R'')`.
#[test]
fn the_cam_has_the_radial_follower_s_pressure_angle_and_curvature() -> Result<(), Box<dyn std::error::Error>> {
    for m in cams() {
        let states = turn(&m, 720)?;
        let disc = cam(&states)?;
        let mut sharpest = f64::INFINITY;
        for (k, st) in states.iter().enumerate() {
            let phi = st.input.phi;
            let [sv, ds, d2s] = m.law_by_hand(phi);
            let r = m.y0 + sv;
            let alpha = ds.abs().atan2(r);
            let rho = (r * r + ds * ds).powf(1.5) / (r * r + 2.0 * ds * ds - r * d2s);
            let what = format!("lift {} at {:.2} deg", m.lift, phi.to_degrees());
            assert!((disc.pressure_angle[k] - alpha).abs() <= 1e-13, "{what}: {} vs {alpha}", disc.pressure_angle[k]);
            assert!(
                (disc.pitch_radius[k] - rho).abs() <= 1e-11 * rho.abs(),
                "{what}: {} vs {rho}",
                disc.pitch_radius[k]
            );
            assert!((disc.pitch[k][0].hypot(disc.pitch[k][1]) - r).abs() <= 1e-13 * r, "{what}");
            if rho > 0.0 {
                sharpest = sharpest.min(rho);
            }
        }
        let (_, printed) = disc.min_convex_radius().expect("convex somewhere");
        assert!((printed - sharpest).abs() <= 1e-11 * sharpest);
        assert_eq!(disc.undercut().is_empty(), sharpest > ROLLER);
        // The largest pressure angle of the rise and of the return, as printed (located between
        // the samples), against the closed form's scanned every 1e-5 rad: there its value is
        // off by at most about `|alpha''| h^2 / 8`, below 1e-10 rad.
        for seg in segments(&m) {
            let (at, alpha) = peak_pressure(&m, &states, &disc, seg.start, seg.start + seg.span)?;
            let steps = (seg.span / 1e-5) as usize;
            let (closed_at, closed) = (0..=steps)
                .map(|j| {
                    let phi = seg.start + seg.span * j as f64 / steps as f64;
                    let [sv, ds, _] = m.law_by_hand(phi);
                    (phi, ds.abs().atan2(m.y0 + sv))
                })
                .fold((0.0, 0.0), |best, x| if x.1 > best.1 { x } else { best });
            let what = format!("{} of lift {}", seg.name, m.lift);
            assert!((alpha - closed).abs() <= 1e-9, "{what}: {alpha} vs {closed}");
            assert!((at - closed_at).abs() <= 1e-4, "{what}: at {at} vs {closed_at}");
        }
    }
    Ok(())
}
