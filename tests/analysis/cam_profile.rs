//! A disc cam's profile by kinematic inversion (`analysis::cam::cam_profile`) against what is
//! known of two cams without it: the eccentric disc of the cam-linkage drive, whose pitch curve
//! is a circle of the disc's radius plus the roller's about the disc's centre and whose pressure
//! angle the declaration states as an output; and the double-harmonic law moving a radial
//! translating follower, whose pitch curve is the polar curve `R = y0 + s(phi)` with the
//! textbook closed forms of its radius of curvature and pressure angle.

use kinloop::Error;
use kinloop::analysis::cam::{CamProfile, FollowerSample, cam_extremes, cam_profile};
use kinloop_fixtures::cam_linkage::{CamLinkage, HarmonicCamRocker};
use std::f64::consts::TAU;

/// The roller centre of the cam-linkage drive over one turn, every 5 degrees, as follower
/// samples (the direction square to the rocker's arm), and the declared pressure angle.
fn eccentric_samples(m: &CamLinkage) -> Result<(Vec<FollowerSample>, Vec<f64>), Error> {
    let start = m.solve(0.0)?;
    let (mut samples, mut pressure) = (Vec::new(), Vec::new());
    for s in m.sweep(0.0, TAU, 73, &start.q)? {
        let s = s?;
        let p = [s.out.roller.x, s.out.roller.y];
        samples.push(FollowerSample {
            cam: [s.input.phi, 1.0, 0.0],
            point: [p, [s.dout.roller.x, s.dout.roller.y], [s.d2out.roller.x, s.d2out.roller.y]],
            direction: [-(p[1] - m.a_y), p[0] - m.a_x],
        });
        pressure.push(s.out.pressure);
    }
    Ok((samples, pressure))
}

#[test]
fn the_eccentric_disc_is_recovered_with_the_declared_pressure_angle() -> Result<(), Error> {
    let m = CamLinkage::default();
    let (samples, declared) = eccentric_samples(&m)?;
    let cam = cam_profile(&samples, [0.0, 0.0], m.r_roller)?;
    // In the cam's frame the disc's centre stays at (e, 0).
    let from_centre = |p: [f64; 2]| (p[0] - m.e).hypot(p[1]);
    let pitch = m.r_cam + m.r_roller;
    for (k, &declared) in declared.iter().enumerate() {
        assert!((from_centre(cam.pitch[k]) - pitch).abs() <= 1e-13 * pitch, "{k}: {:?}", cam.pitch[k]);
        assert!((from_centre(cam.profile[k]) - m.r_cam).abs() <= 1e-13 * pitch, "{k}: {:?}", cam.profile[k]);
        // A circle's radius of curvature, from the analogs' second derivatives.
        assert!((cam.pitch_radius[k] - pitch).abs() <= 1e-11 * pitch, "{k}: {}", cam.pitch_radius[k]);
        assert!((cam.profile_radius(k) - m.r_cam).abs() <= 1e-11 * pitch);
        // The declared pressure angle is signed, between the line C -> P and the roller's motion.
        let (s, c) = declared.sin_cos();
        let expected = s.abs().atan2(c.abs());
        assert!((cam.pressure_angle[k] - expected).abs() <= 1e-13, "{k}: {} vs {expected}", cam.pressure_angle[k]);
    }
    assert!(cam.undercut().is_empty());
    assert!((cam.min_convex_radius().map(|(_, r)| r).unwrap() - pitch).abs() <= 1e-11 * pitch);
    let (k, worst) = cam.max_pressure_angle();
    assert_eq!(worst, cam.pressure_angle.iter().copied().fold(0.0, f64::max));
    assert_eq!(cam.pressure_angle[k], worst);
    // A roller larger than the pitch circle folds the offset over everywhere.
    let too_big = cam_profile(&samples, [0.0, 0.0], 1.01 * pitch)?;
    assert_eq!(too_big.undercut().len(), samples.len());
    Ok(())
}

#[test]
fn the_same_cam_in_micrometres_has_the_same_angles_and_a_scaled_profile() -> Result<(), Error> {
    let mm = CamLinkage::default();
    let k = 1000.0;
    let um = CamLinkage {
        e: k * mm.e,
        r_cam: k * mm.r_cam,
        r_roller: k * mm.r_roller,
        a_x: k * mm.a_x,
        a_y: k * mm.a_y,
        l_arm: k * mm.l_arm,
        l_out: k * mm.l_out,
        l_rod: k * mm.l_rod,
        h: k * mm.h,
        ..mm
    };
    let (a, b) = (eccentric_samples(&mm)?.0, eccentric_samples(&um)?.0);
    let (a, b) = (cam_profile(&a, [0.0, 0.0], mm.r_roller)?, cam_profile(&b, [0.0, 0.0], um.r_roller)?);
    for j in 0..a.pitch.len() {
        assert!((a.pressure_angle[j] - b.pressure_angle[j]).abs() <= 1e-14, "{j}");
        assert!((k * a.pitch_radius[j] - b.pitch_radius[j]).abs() <= 1e-12 * b.pitch_radius[j], "{j}");
        for c in 0..2 {
            assert!((k * a.profile[j][c] - b.profile[j][c]).abs() <= 1e-12 * k * mm.r_cam, "{j}");
        }
    }
    Ok(())
}

/// The law of `HarmonicCamRocker` and its first two derivatives, by hand.
fn harmonic(m: &HarmonicCamRocker, phi: f64) -> [f64; 3] {
    let h = m.lift / 2.0;
    [
        h * ((1.0 - phi.cos()) - (1.0 - (2.0 * phi).cos()) / 4.0),
        h * (phi.sin() - (2.0 * phi).sin() / 2.0),
        h * (phi.cos() - (2.0 * phi).cos()),
    ]
}

/// The follower pin of the double-harmonic cam every `360 / (n - 1)` degrees, from the
/// mechanism's solution (positions and analogs of its `follower` point).
fn harmonic_samples(m: &HarmonicCamRocker, n: usize) -> Result<Vec<FollowerSample>, Error> {
    let start = m.solve(0.0)?;
    let mut out = Vec::new();
    for s in m.sweep(0.0, TAU, n, &start.q)? {
        let s = s?;
        out.push(FollowerSample {
            cam: [s.input.phi, 1.0, 0.0],
            point: [
                [s.out.follower.x, s.out.follower.y],
                [s.dout.follower.x, s.dout.follower.y],
                [s.d2out.follower.x, s.d2out.follower.y],
            ],
            direction: [0.0, 1.0],
        });
    }
    Ok(out)
}

#[test]
fn a_radial_translating_follower_matches_the_polar_closed_forms() -> Result<(), Error> {
    let m = HarmonicCamRocker::default();
    let samples = harmonic_samples(&m, 361)?;
    let roller = 5.0;
    let cam: CamProfile = cam_profile(&samples, [0.0, 0.0], roller)?;
    for (k, s) in samples.iter().enumerate() {
        let phi = s.cam[0];
        let [sv, ds, d2s] = harmonic(&m, phi);
        let r = m.y0 + sv;
        // The cam turns counter-clockwise, so the pin's place on it is (0, R) turned back by phi.
        let pitch = [r * phi.sin(), r * phi.cos()];
        for c in 0..2 {
            assert!((cam.pitch[k][c] - pitch[c]).abs() <= 1e-13 * r, "{k}: {:?} vs {pitch:?}", cam.pitch[k]);
        }
        // A polar curve's radius of curvature, and the radial follower's pressure angle.
        let rho = (r * r + ds * ds).powf(1.5) / (r * r + 2.0 * ds * ds - r * d2s);
        assert!((cam.pitch_radius[k] - rho).abs() <= 1e-12 * rho.abs(), "{k}: {} vs {rho}", cam.pitch_radius[k]);
        let alpha = ds.abs().atan2(r);
        assert!((cam.pressure_angle[k] - alpha).abs() <= 1e-14, "{k}: {} vs {alpha}", cam.pressure_angle[k]);
        // The contact lies a roller's radius inside, along the pitch curve's normal.
        let (dx, dy) = (cam.profile[k][0] - pitch[0], cam.profile[k][1] - pitch[1]);
        assert!((dx.hypot(dy) - roller).abs() <= 1e-12 * r);
        assert!(cam.profile[k][0].hypot(cam.profile[k][1]) < r);
    }
    // The sharpest convex point of the pitch curve: a roller just under it rolls everywhere,
    // one just over it undercuts the profile there.
    let (at, sharpest) = cam.min_convex_radius().expect("a disc cam is convex somewhere");
    let closed_min = (0..samples.len())
        .map(|k| {
            let [sv, ds, d2s] = harmonic(&m, samples[k].cam[0]);
            let r = m.y0 + sv;
            (r * r + ds * ds).powf(1.5) / (r * r + 2.0 * ds * ds - r * d2s)
        })
        .filter(|rho| *rho > 0.0)
        .fold(f64::INFINITY, f64::min);
    assert!((sharpest - closed_min).abs() <= 1e-12 * closed_min, "{sharpest} vs {closed_min}");
    assert!(cam_profile(&samples, [0.0, 0.0], 0.999 * sharpest)?.undercut().is_empty());
    assert!(cam_profile(&samples, [0.0, 0.0], 1.001 * sharpest)?.undercut().contains(&at));
    // The same law on a cam turning clockwise: the pitch curve mirrored, winding the other way,
    // with the same curvature and pressure angles.
    let mut clockwise = samples.clone();
    for s in &mut clockwise {
        s.cam = [-s.cam[0], -1.0, 0.0];
    }
    let mirrored = cam_profile(&clockwise, [0.0, 0.0], roller)?;
    for k in 0..samples.len() {
        assert!(
            (mirrored.pitch[k][0] + cam.pitch[k][0]).abs() <= 1e-13 * m.y0 && mirrored.pitch[k][1] == cam.pitch[k][1]
        );
        assert!((mirrored.profile[k][0] + cam.profile[k][0]).abs() <= 1e-13 * m.y0);
        assert!((mirrored.profile[k][1] - cam.profile[k][1]).abs() <= 1e-13 * m.y0);
        assert!((mirrored.pitch_radius[k] - cam.pitch_radius[k]).abs() <= 1e-13 * cam.pitch_radius[k].abs());
        assert_eq!(mirrored.pressure_angle[k], cam.pressure_angle[k]);
    }
    // A knife edge: the profile is the pitch curve.
    let knife = cam_profile(&samples, [0.0, 0.0], 0.0)?;
    assert_eq!(knife.profile, knife.pitch);
    Ok(())
}

#[test]
fn bad_samples_are_refused_naming_what_is_wrong() -> Result<(), Error> {
    let m = HarmonicCamRocker::default();
    let good = harmonic_samples(&m, 13)?;
    let refused = |samples: &[FollowerSample], roller: f64, says: &str| {
        let e = cam_profile(samples, [0.0, 0.0], roller).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument(_)) && e.to_string().contains(says), "{says}: {e}");
    };
    refused(&[], 1.0, "no samples");
    refused(&good, -1.0, "roller's radius");
    refused(&good, f64::NAN, "roller's radius");
    let mut nan = good.clone();
    nan[4].point[1][0] = f64::NAN;
    refused(&nan, 1.0, "sample 4 has a value that is not finite");
    let mut still = good.clone();
    still[2].direction = [0.0, 0.0];
    refused(&still, 1.0, "sample 2's direction");
    // A cam that does not turn under a follower that does not move.
    let mut parked = good.clone();
    parked[3].cam = [parked[3].cam[0], 0.0, 0.0];
    parked[3].point[1] = [0.0, 0.0];
    refused(&parked, 1.0, "at sample 3 the follower's point does not move around the cam's centre");
    // One sample of a cam turning the other way.
    let mut reversed = good.clone();
    reversed[5].cam[1] = -1.0;
    reversed[5].point[1] = [-reversed[5].point[1][0], -reversed[5].point[1][1]];
    refused(&reversed, 1.0, "at sample 5 the follower's point turns around the cam's centre the other way");
    Ok(())
}

/// The same cam at 1e300 and at 1e-300 of its size: the same pressure angles and the radii scaled
/// (computed in units of a power of two near each sample's lengths, no cube overflows).
#[test]
fn a_cam_at_the_ends_of_the_f64_range_has_the_same_angles() -> Result<(), Error> {
    let m = CamLinkage::default();
    let (samples, _) = eccentric_samples(&m)?;
    let plain = cam_profile(&samples, [0.0, 0.0], m.r_roller)?;
    for k in [1e300, 1e-300] {
        let scaled: Vec<FollowerSample> = samples
            .iter()
            .map(|s| FollowerSample {
                point: s.point.map(|p| p.map(|v| v * k)),
                direction: s.direction.map(|v| v * k),
                ..*s
            })
            .collect();
        let cam = cam_profile(&scaled, [0.0, 0.0], m.r_roller * k)?;
        for j in 0..samples.len() {
            assert!((cam.pressure_angle[j] - plain.pressure_angle[j]).abs() <= 1e-14, "{k:e} {j}");
            let want = plain.pitch_radius[j] * k;
            assert!((cam.pitch_radius[j] - want).abs() <= 1e-13 * want.abs(), "{k:e} {j}: {}", cam.pitch_radius[j]);
            for c in 0..2 {
                let want = plain.profile[j][c] * k;
                assert!((cam.profile[j][c] - want).abs() <= 1e-13 * m.r_cam * k, "{k:e} {j}");
            }
        }
        assert!(cam.undercut().is_empty());
    }
    Ok(())
}

/// The double-harmonic law's largest pressure angle and sharpest point located between samples
/// a quarter turn apart ([`cam_extremes`]): the textbook closed forms' extremes, found by a
/// fine search here, where the samples' own checks miss them by degrees.
#[test]
fn the_checks_are_located_between_the_samples() -> Result<(), Error> {
    let m = HarmonicCamRocker::default();
    let follower = |phi: f64| -> Result<FollowerSample, Error> {
        let s = m.solve(phi)?;
        let p = [s.out.follower.x, s.out.follower.y];
        Ok(FollowerSample {
            cam: [phi, 1.0, 0.0],
            point: [p, [s.dout.follower.x, s.dout.follower.y], [s.d2out.follower.x, s.d2out.follower.y]],
            direction: [0.0, 1.0],
        })
    };
    let inputs: Vec<f64> = (0..=4).map(|k| k as f64 * TAU / 4.0).collect();
    let samples: Vec<FollowerSample> = inputs.iter().map(|&phi| follower(phi)).collect::<Result<_, _>>()?;
    let located = cam_extremes(&inputs, &samples, [0.0, 0.0], 0.0, follower)?;
    // The pressure angle and the curvature of the polar curve R = y0 + s (where convex), by
    // hand, their largest on a fine grid refined by golden section.
    let alpha = |phi: f64| {
        let [s, ds, _] = harmonic(&m, phi);
        ds.abs().atan2(m.y0 + s)
    };
    let curvature = |phi: f64| {
        let [s, ds, d2s] = harmonic(&m, phi);
        let r = m.y0 + s;
        let rho = (r * r + ds * ds).powf(1.5) / (r * r + 2.0 * ds * ds - r * d2s);
        if rho > 0.0 { 1.0 / rho } else { 0.0 }
    };
    let best = |f: &dyn Fn(f64) -> f64| {
        let k = (0..3600).max_by(|&a, &b| f(a as f64 * TAU / 3600.0).total_cmp(&f(b as f64 * TAU / 3600.0))).unwrap();
        let (mut a, mut b) = ((k as f64 - 1.0) * TAU / 3600.0, (k as f64 + 1.0) * TAU / 3600.0);
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if f(c) > f(d) { b = d } else { a = c }
        }
        (0.5 * (a + b), f(0.5 * (a + b)))
    };
    let (x, worst) = best(&alpha);
    assert!((located.max_pressure_angle.value - worst).abs() <= 1e-13, "{located:?} vs {worst}");
    assert!((located.max_pressure_angle.x - x).abs() <= 1e-6, "{located:?} vs {x}");
    let (x, curvature) = best(&curvature);
    let sharpest = located.min_convex_radius.expect("convex somewhere");
    assert!((sharpest.value - 1.0 / curvature).abs() <= 1e-11 * m.y0, "{located:?} vs {}", 1.0 / curvature);
    assert!((sharpest.x - x).abs() <= 1e-6, "{located:?} vs {x}");
    // The samples' own checks, a quarter turn apart, are off.
    let cam = cam_profile(&samples, [0.0, 0.0], 0.0)?;
    assert!(cam.max_pressure_angle().1 < worst - 1e-3, "{:?}", cam.max_pressure_angle());
    // A roller as large as the sharpest point undercuts it.
    let big = cam_extremes(&inputs, &samples, [0.0, 0.0], sharpest.value, follower)?;
    assert!(big.undercut() && !located.undercut());
    Ok(())
}
