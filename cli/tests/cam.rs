//! `kinloop cam` end to end: the built binary on the shipped dwell cam, its CSV against the
//! radial follower's closed forms of the 3-4-5 law by hand (`law_by_hand`: the pitch curve as the
//! polar curve `R = y0 + s`, its radius of curvature, the pressure angle `atan(|s'| / R)`), a
//! rocking follower on the cam-linkage drive's eccentric disc (its pitch circle about the disc's
//! centre, the pressure angle the declaration states), flat-faced followers (the dwell cam's
//! radial face against `R_b + s + s''` and `s'` by hand, the eccentric disc given back under a
//! rocking face), and the usage errors.
//!
//! Tolerances: the lift and its analogs are the law's to rounding (the declaration's polynomial
//! and the one here are evaluated in different orders): 1e-12 of the pitch radius for lengths,
//! 1e-11 of it for the radius of curvature (a quotient of analogs), 1e-10 degrees for angles.

mod common;

use common::{csv, kinloop, shipped};
use kinloop_fixtures as fx;

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).to_string()
}

/// The number in `err` after `after`, up to `until`.
fn number_in(err: &str, after: &str, until: char) -> f64 {
    err.split(after)
        .nth(1)
        .and_then(|t| t.split(until).next())
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no `{after}` in: {err}"))
}

/// The largest value of `f` on `[a, b]` where it has one peak, by golden-section search to
/// the doubles' resolution: `(x, f(x))`.
fn golden(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> (f64, f64) {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..200 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if f(c) > f(d) { b = d } else { a = c }
    }
    let x = 0.5 * (a + b);
    (x, f(x))
}

#[test]
fn the_dwell_cam_has_the_radial_follower_s_closed_forms() {
    let m = fx::cam_linkage::DwellCamRocker::default();
    let file = shipped("dwell_cam.kl");
    let out = kinloop(&[
        "cam",
        &file,
        "--point",
        "follower",
        "--guide",
        "0,1",
        "--roller",
        "10",
        "--deg",
        "--samples",
        "721",
    ]);
    let (header, rows) = csv(&out);
    assert_eq!(
        header,
        [
            "phi [deg]",
            "pitch.x [length unit]",
            "pitch.y [length unit]",
            "profile.x [length unit]",
            "profile.y [length unit]",
            "pitch_radius [length unit]",
            "pressure_angle [deg]"
        ]
    );
    assert_eq!(rows.len(), 721);
    let mut largest = 0.0f64;
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row[0], k as f64 / 2.0, "the samples every half degree");
        let phi = row[0].to_radians();
        let [s, ds, d2s] = m.law_by_hand(phi);
        let r = m.y0 + s;
        let pitch = [r * phi.sin(), r * phi.cos()];
        let rho = (r * r + ds * ds).powf(1.5) / (r * r + 2.0 * ds * ds - r * d2s);
        let alpha = ds.abs().atan2(r).to_degrees();
        let at = format!("at {} deg", row[0]);
        assert!((row[1] - pitch[0]).abs() <= 1e-12 * r && (row[2] - pitch[1]).abs() <= 1e-12 * r, "{at}: {row:?}");
        assert!(((row[3] - row[1]).hypot(row[4] - row[2]) - 10.0).abs() <= 1e-12 * r, "{at}: {row:?}");
        assert!(row[3].hypot(row[4]) < r, "{at}: the profile inside the pitch curve");
        assert!((row[5] - rho).abs() <= 1e-11 * rho.abs(), "{at}: {} vs {rho}", row[5]);
        assert!((row[6] - alpha).abs() <= 1e-10, "{at}: {} vs {alpha}", row[6]);
        largest = largest.max(alpha);
    }
    let err = stderr(&out);
    assert!(err.contains("no undercut with a roller of radius 10"), "{err}");
    // The largest pressure angle is located between the samples: the law's own, beside the
    // largest sample's.
    let said = number_in(&err, "largest pressure angle ", '°');
    let top = (0..rows.len()).max_by(|&a, &b| rows[a][6].total_cmp(&rows[b][6])).unwrap();
    let at = rows[top][0].to_radians();
    let alpha = |phi: f64| {
        let [s, ds, _] = m.law_by_hand(phi);
        ds.abs().atan2(m.y0 + s).to_degrees()
    };
    let (_, peak) = golden(alpha, at - 0.5f64.to_radians(), at + 0.5f64.to_radians());
    assert!(peak >= largest && (said - peak).abs() <= 1e-10, "{said} vs {peak} (the samples' {largest})");
    // Clockwise: the pitch curve mirrored, the same pressure angles.
    let cw =
        kinloop(&["cam", &file, "--point", "follower", "--guide", "0,1", "--roller", "10", "--deg", "--clockwise"]);
    let (_, mirrored) = csv(&cw);
    let (_, plain) = csv(&kinloop(&["cam", &file, "--point", "follower", "--guide", "0,1", "--roller", "10", "--deg"]));
    for (a, b) in mirrored.iter().zip(&plain) {
        assert!((a[1] + b[1]).abs() <= 1e-12 * m.y0 && a[2] == b[2] && (a[6] - b[6]).abs() <= 1e-12, "{a:?} {b:?}");
    }
    // A roller larger than the base circle of the pitch curve undercuts the dwells.
    let big = kinloop(&["cam", &file, "--point", "follower", "--guide", "0,1", "--roller", "61"]);
    assert!(big.status.success() && stderr(&big).contains("UNDERCUT"), "{}", stderr(&big));
}

#[test]
fn a_rocking_follower_on_the_eccentric_disc() {
    let m = fx::cam_linkage::CamLinkage::default();
    let file = std::env::temp_dir().join(format!("kinloop-cam-linkage-{}.kl", std::process::id()));
    std::fs::write(&file, fx::cam_linkage::CAM_LINKAGE_TEXT).unwrap();
    let rocker = format!("{},{}", m.a_x, m.a_y);
    let out = kinloop(&["cam", file.to_str().unwrap(), "--point", "roller", "--rocker", &rocker, "--roller", "12"]);
    let _ = std::fs::remove_file(&file);
    let (_, rows) = csv(&out);
    let pitch = m.r_cam + m.r_roller;
    let mut q = m.solve(0.0).unwrap().q;
    for row in &rows {
        // The disc's centre stays at (e, 0) in the cam's frame: the pitch circle and the disc.
        assert!(((row[1] - m.e).hypot(row[2]) - pitch).abs() <= 1e-12 * pitch, "{row:?}");
        assert!(((row[3] - m.e).hypot(row[4]) - m.r_cam).abs() <= 1e-12 * pitch, "{row:?}");
        assert!((row[5] - pitch).abs() <= 1e-10 * pitch, "{row:?}");
        let s = m.kinematics(row[0], &q).unwrap();
        q = s.q;
        let (sin, cos) = s.out.pressure.sin_cos();
        assert!((row[6] - sin.abs().atan2(cos.abs())).abs() <= 1e-12, "{row:?} vs {}", s.out.pressure);
    }
}

/// The radial translating flat face on the dwell cam against the closed forms by hand: the cam
/// turning counter-clockwise under the face square to the +y guide, the contact in the cam's
/// frame is `((y0 + s) sin phi + s' cos phi, (y0 + s) cos phi - s' sin phi)` (the face's
/// envelope `h n + dh/dpsi J n`, `h = y0 + s`, its normal at `psi = pi/2 - phi`), its radius
/// of curvature `y0 + s + s''`, `s'` along the face from the follower's axis, the pressure
/// angle 0.
#[test]
fn a_flat_face_on_the_dwell_cam_has_the_closed_forms() {
    let m = fx::cam_linkage::DwellCamRocker::default();
    let file = shipped("dwell_cam.kl");
    let args = ["cam", &file, "--point", "follower", "--guide", "0,1", "--flat", "--deg", "--samples", "721"];
    let out = kinloop(&args);
    let (header, rows) = csv(&out);
    assert_eq!(
        header,
        [
            "phi [deg]",
            "profile.x [length unit]",
            "profile.y [length unit]",
            "radius [length unit]",
            "offset [length unit]",
            "pressure_angle [deg]"
        ]
    );
    assert_eq!(rows.len(), 721);
    let (mut lo, mut hi, mut sharpest) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
    for row in &rows {
        let phi = row[0].to_radians();
        let [s, ds, d2s] = m.law_by_hand(phi);
        let r = m.y0 + s;
        let (sin, cos) = phi.sin_cos();
        let at = format!("at {} deg: {row:?}", row[0]);
        assert!((row[1] - (r * sin + ds * cos)).abs() <= 1e-12 * r, "{at}");
        assert!((row[2] - (r * cos - ds * sin)).abs() <= 1e-12 * r, "{at}");
        assert!((row[3] - (r + d2s)).abs() <= 1e-12 * r, "{at}");
        assert!((row[4] - ds).abs() <= 1e-12 * r, "{at}");
        assert_eq!(row[5], 0.0, "{at}");
        (lo, hi, sharpest) = (lo.min(ds), hi.max(ds), sharpest.min(r + d2s));
    }
    // The summary: the face spans the extremes of s' (the rise's 1.875 h / beta, the return's),
    // the smallest radius where s'' is most negative.
    // (Both extremes of s' fall on samples, mid-rise and mid-return; the smallest radius is
    // located between them, where y0 + s + s'' is least, early in the return.)
    let err = stderr(&out);
    let number = |after: &str, until: char| number_in(&err, after, until);
    assert!((number("face width at least ", '(') - (hi - lo)).abs() <= 1e-12 * m.y0, "{err}");
    assert!((hi - 1.875 * m.lift / m.rise).abs() <= 1e-6 * m.lift, "{hi}");
    let radius = |phi: f64| {
        let [s, _, d2s] = m.law_by_hand(phi);
        -(m.y0 + s + d2s)
    };
    let (_, least) = golden(radius, m.phi1, m.phi1 + m.fall / 2.0);
    assert!(-least <= sharpest, "{least} {sharpest}");
    assert!((number("smallest radius of curvature of the profile ", 'a') + least).abs() <= 1e-12 * m.y0, "{err}");
    assert!(err.contains("the profile is convex at every sample"), "{err}");
    // On a base circle of 10 (the rod lengthened to reach the rocker) the face's envelope folds
    // early in the return: 10 + s + s'' = 10 + 18.7 - 37.9 < 0 where its deceleration peaks.
    let params = ["--params", "y0=10,l_rod=120"];
    let small = kinloop(&[&["cam", &file, "--point", "follower", "--guide", "0,1", "--flat"], &params[..]].concat());
    assert!(small.status.success() && stderr(&small).contains("NOT CONVEX at"), "{}", stderr(&small));
    // A tilted face: the pressure angle is the tilt.
    let (_, tilted) = csv(&kinloop(&["cam", &file, "--point", "follower", "--guide", "0,1", "--flat", "-20", "--deg"]));
    assert!(tilted.iter().all(|row| (row[5] - 20.0).abs() <= 1e-12), "{:?}", tilted[0]);
}

/// The dwell cam's checks are located between the samples, whatever their number. Its rise
/// shortened to 2 degrees (the 361 samples every degree land at its start, its middle and its
/// end) or to half a degree (no sample in it), the radial follower's checks are those of the
/// polar curve `R = y0 + s(phi)`, `s = lift p(u)`, `u = (phi - phi0) / rise`,
/// `p = 10 u^3 - 15 u^4 + 6 u^5` (lift 20, y0 60, phi0 30 degrees): the pressure angle
/// `atan(|s'| / R)` and the pitch curve's radius of curvature
/// `(R^2 + R'^2)^1.5 / (R^2 + 2 R'^2 - R R'')`; under a flat face square to the guide the
/// profile's radius of curvature `R + s''`. Their extremes by golden-section search in python3
/// (mpmath, 40 digits), the rise given in radians as here:
///
/// * rise 2 degrees: the sharpest convex point of the pitch curve at 31.907459 degrees, radius
///   of curvature 0.206069 (a roller of 10 undercuts it; at the samples the sharpest was the
///   return's 53.03 at 224 degrees, "no undercut"); under a flat face the least radius
///   -94687.715 at 31.577341 degrees (the samples said convex, 40.66 at 223 degrees);
/// * rise half a degree: the largest pressure angle 89.075161 degrees at 30.233183 degrees (the
///   samples said 17.2 at 253 degrees, the return's).
#[test]
fn the_checks_are_located_between_the_samples() {
    let file = shipped("dwell_cam.kl");
    let cam = |rise: &str, follower: &[&str], samples: &str| {
        let params = format!("rise={rise}");
        let args =
            [&["cam", &file, "--point", "follower", "--guide", "0,1", "--deg", "--params", &params][..], follower]
                .concat();
        let out = kinloop(&[&args[..], &["--samples", samples]].concat());
        assert!(out.status.success(), "{}", stderr(&out));
        stderr(&out)
    };
    let (two, half, roller) = ("0.0349066", "0.00872665", ["--roller", "10"]);
    // The reported numbers agree to rounding whatever the samples (the default 361 among them).
    let reference = number_in(&cam(half, &roller, "361"), "largest pressure angle ", '°');
    let agree = |a: f64, b: f64, what: &str| assert!((a - b).abs() <= 1e-9 * a.abs().max(1.0), "{what}: {a} vs {b}");
    for samples in ["361", "37", "1001", "100001"] {
        let err = cam(two, &roller, samples);
        assert!(err.contains("UNDERCUT"), "{samples} samples: {err}");
        let sharpest = number_in(&err, "radius of curvature ", ',');
        let at = number_in(&err, "sharpest convex point of the pitch curve at ", '°');
        assert!((sharpest - 0.206069).abs() <= 1e-5 && (at - 31.907459).abs() <= 1e-4, "{samples} samples: {err}");
        let err = cam(half, &roller, samples);
        let alpha = number_in(&err, "largest pressure angle ", '°');
        let at = number_in(&err, "° at ", '°');
        assert!((alpha - 89.075161).abs() <= 0.05 && (at - 30.233183).abs() <= 0.05, "{samples} samples: {err}");
        assert!((alpha - 89.075161).abs() <= 1e-5 && (at - 30.233183).abs() <= 1e-4, "{samples} samples: {err}");
        agree(alpha, reference, "the largest pressure angle against the default samples'");
        let err = cam(two, &["--flat"], samples);
        assert!(err.contains("NOT CONVEX"), "{samples} samples: {err}");
        let least = number_in(&err, "smallest radius of curvature of the profile ", 'a');
        let at = number_in(&err, &format!("{least} at "), '°');
        assert!((least + 94687.715).abs() <= 1e-3 && (at - 31.577341).abs() <= 1e-4, "{samples} samples: {err}");
    }
    // At the default samples no sample falls where the half-degree rise undercuts the roller.
    let err = cam(half, &roller, "361");
    assert!(err.contains("UNDERCUT between the samples, at 30.48"), "{err}");
}

/// The eccentric disc (radius 40, its centre 10 from the shaft) under a flat face on a rocker
/// pivoted at (-60, 60), the face 5 below the arm: the loop keeps the disc tangent to the face.
const DISC_FLAT_ROCKER: &str = "
pub struct DiscFlatRocker {
    params e = 10.0, r = 40.0, a_x = -60.0, a_y = 60.0, d = 5.0, l = 100.0;
    input phi;
    unknowns gamma = -0.25, w = 62;
    loop contact: e @ phi + r @ (gamma + pi / 2) == (a_x, a_y) + d @ (gamma - pi / 2) + w @ gamma;
    point arm = (a_x, a_y) + l @ gamma;
}
";

#[test]
fn a_rocking_flat_face_on_the_eccentric_disc() {
    let file = std::env::temp_dir().join(format!("kinloop-disc-flat-rocker-{}.kl", std::process::id()));
    std::fs::write(&file, DISC_FLAT_ROCKER).unwrap();
    let path = file.to_str().unwrap();
    let args =
        ["cam", path, "--point", "arm", "--rocker", "-60,60", "--flat", "--face-offset", "-5", "--samples", "73"];
    let out = kinloop(&args);
    // The same with the unknown w written out, to compare the offset with (the sweep's columns).
    let sweep = kinloop(&["sweep", path, "--from", "0", "--to", "6.283185307179586", "--samples", "73"]);
    let _ = std::fs::remove_file(&file);
    let (_, rows) = csv(&out);
    let (header, states) = csv(&sweep);
    let w = header.iter().position(|h| h.starts_with("w")).expect("the unknown w");
    assert_eq!(rows.len(), 73);
    for (row, state) in rows.iter().zip(&states) {
        // The disc given back (its centre at (10, 0) in the cam's frame), its radius the radius
        // of curvature; the contact where the loop puts it; tan(pressure angle) = 5 / w.
        assert!(((row[1] - 10.0).hypot(row[2]) - 40.0).abs() <= 1e-12 * 40.0, "{row:?}");
        assert!((row[3] - 40.0).abs() <= 1e-11 * 40.0, "{row:?}");
        assert!((row[4] - state[w]).abs() <= 1e-12 * 40.0, "{row:?} vs {state:?}");
        assert!((row[5] - 5.0f64.atan2(state[w].abs())).abs() <= 1e-13, "{row:?}");
    }
}

/// The table's first column is the input under its name, as every command's table has it (it
/// was `input [deg]` where a sweep of the same declaration wrote `phi [deg]`); an input named as
/// one of the table's own columns is refused before the sweep, naming it, as `dynamics` refuses
/// one named as its own.
#[test]
fn the_first_column_is_the_input_by_its_name() {
    let args = ["--point", "follower", "--guide", "0,1", "--samples", "5", "--deg"];
    for flat in [false, true] {
        let mut cam = vec!["cam", &shipped("dwell_cam.kl")].into_iter().map(String::from).collect::<Vec<_>>();
        cam.extend(args.iter().map(|a| a.to_string()));
        if flat {
            cam.push("--flat".into());
        }
        let cam: Vec<&str> = cam.iter().map(String::as_str).collect();
        let (header, rows) = csv(&kinloop(&cam));
        assert_eq!(header[0], "phi [deg]", "{header:?}");
        assert_eq!(rows.iter().map(|r| r[0]).collect::<Vec<_>>(), [0.0, 90.0, 180.0, 270.0, 360.0]);
    }
    let renamed = std::fs::read_to_string(shipped("dwell_cam.kl")).unwrap().replace("phi", "offset");
    let file = std::env::temp_dir().join(format!("kinloop-cam-input-offset-{}.kl", std::process::id()));
    std::fs::write(&file, renamed).unwrap();
    let out = kinloop(&[&["cam", file.to_str().unwrap()], &args[..]].concat());
    let _ = std::fs::remove_file(&file);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("kinloop cam writes a column `offset` of its own") && err.contains("rename the input"),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn bad_requests_are_usage_errors() {
    let (cam, five_bar, slider) = (shipped("dwell_cam.kl"), shipped("five_bar.kl"), shipped("slider_crank.kl"));
    // A folder where a file is: the plot cannot be created.
    let plot = std::path::Path::new(&cam).join("cam.svg");
    // A folder that does not exist is not created (as for `animate --out`).
    let missing = std::env::temp_dir().join(format!("kinloop-no-such-dir-{}", std::process::id())).join("cam.svg");
    let base = ["cam", cam.as_str(), "--point", "follower"];
    let cases: Vec<(Vec<&str>, &str, i32)> = vec![
        (base.to_vec(), "--guide X,Y", 2),
        ([&base[..], &["--guide", "0,1", "--rocker", "0,0"]].concat(), "not both", 2),
        ([&base[..], &["--guide", "0,0"]].concat(), "has no direction", 2),
        ([&base[..], &["--guide", "1"]].concat(), "not a point", 2),
        ([&base[..], &["--guide", "0,1", "--roller", "-1"]].concat(), "--roller -1", 2),
        ([&base[..], &["--guide", "0,1", "--samples", "2"]].concat(), "--samples 2", 2),
        ([&base[..], &["--guide", "0,1", "--pivot", "a,b"]].concat(), "--pivot", 2),
        ([&base[..], &["--guide", "0,1", "--flat", "--roller", "10"]].concat(), "not both", 2),
        ([&base[..], &["--guide", "0,1", "--flat", "90", "--deg"]].concat(), "less than a quarter turn", 2),
        ([&base[..], &["--guide", "0,1", "--flat", "--face-offset", "3"]].concat(), "translating", 2),
        ([&base[..], &["--guide", "0,1", "--face-offset", "3"]].concat(), "give it with --flat", 2),
        ([&base[..], &["--rocker", "0,0", "--flat", "inf"]].concat(), "--flat inf: the face's tilt must be", 2),
        // A tilt that is no number is said to be one, not to be tilted less than a quarter turn.
        ([&base[..], &["--guide", "0,1", "--flat", "nan"]].concat(), "--flat NaN: the face's tilt must be a finite", 2),
        ([&base[..], &["--rocker", "0,0", "--flat", "--face-offset", "-inf"]].concat(), "--face-offset -inf must", 2),
        ([&base[..], &["--guide", "0,1", "--flat", "x"]].concat(), "--flat", 2),
        // A rocking face's tilt in degrees so many turns out that their radians are rounding
        // (the face was tilted by it without a word), as `--start` is refused.
        (
            [&base[..], &["--rocker", "0,0", "--flat", "1e300", "--deg"]].concat(),
            "--flat: 1e300 degrees are too many turns out to convert to radians",
            2,
        ),
        ([&base[..], &["--guide", "0,1", "--start", "1e300"]].concat(), "a turn of the cam from 1e300 is lost", 2),
        // Degrees so many turns out that their radians round by more than a solve's precision
        // are refused as `sweep --deg` and `dynamics --deg` refuse them (the cam was found at the
        // rounded inputs without a word): the doubles there are `math.ulp(math.radians(3e8))`,
        // 9.313225746154785e-10 rad, apart, 5.336085289072462e-8 degrees (Python).
        (
            [&base[..], &["--guide", "0,1", "--deg", "--start", "3e8"]].concat(),
            "--start: 300000000 degrees are too many turns out to convert to radians to a solve's precision (the \
             doubles of the radians there are 5.336085289072462e-8 degrees apart",
            2,
        ),
        (vec!["cam", cam.as_str(), "--point", "nope", "--guide", "0,1"], "its points: follower, rocker_pin", 2),
        // A mechanism of no point says to declare one (it said "its points: none").
        (
            vec!["cam", slider.as_str(), "--params", "r=1,l=3,e=0", "--point", "x", "--guide", "1,0"],
            "--point x: SliderCrank declares no point: declare it in the declaration, `point x = ...;`",
            2,
        ),
        (vec!["cam", five_bar.as_str(), "--point", "p", "--guide", "0,1"], "must have one input, an angle", 2),
        ([&base[..], &["--guide", "0,1", "--plot", plot.to_str().unwrap()]].concat(), "cannot create the plot", 73),
        ([&base[..], &["--guide", "0,1", "--plot", missing.to_str().unwrap()]].concat(), "cannot create the plot", 73),
    ];
    for (args, says, code) in cases {
        let out = kinloop(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: `{says}` missing: {err}");
        // Refused before anything is written: a plot that cannot be created too.
        assert!(out.stdout.is_empty(), "{args:?}: {err}");
    }
    assert!(!missing.parent().unwrap().exists());
}

/// A follower that is not the point's motion (a guide across it, a pivot it does not turn
/// about) is a usage error saying how the point moves and what to give; so is a pivot (the
/// rocker's or the cam's) at the point, naming the sample. The point moves along y (its pin) or
/// on an arc about (-40, 140) (the rocker's pin). Nothing is written, no plot left.
#[test]
fn a_follower_that_is_not_the_points_motion_is_a_usage_error() {
    let cam = shipped("dwell_cam.kl");
    let plot = std::env::temp_dir().join(format!("kinloop-refused-cam-{}.svg", std::process::id()));
    let follower = ["cam", cam.as_str(), "--point", "follower", "--deg", "--plot", plot.to_str().unwrap()];
    let pin = ["cam", cam.as_str(), "--point", "rocker_pin", "--pivot", "-10,60"];
    let cases: [(Vec<&str>, &str); 7] = [
        (
            [&follower[..], &["--guide", "1,0"]].concat(),
            "--guide 1,0: the follower's point `follower` does not move along this guide: it leaves the guide's line \
             by 20 over a stroke of 20: it moves along the line of direction 0,1; give --guide 0,1",
        ),
        ([&follower[..], &["--rocker", "100,0"]].concat(), "does not turn about this pivot"),
        ([&follower[..], &["--rocker", "100,0"]].concat(), "give --guide 0,1 (a translating follower)"),
        ([&pin[..], &["--guide", "0,1"]].concat(), "moves on an arc about -40,140 of radius 40; give --rocker -40,140"),
        (
            [&follower[..], &["--rocker", "0,60"]].concat(),
            "--rocker 0,60 is at the follower's point `follower` at sample 0 (input 0 deg)",
        ),
        ([&follower[..], &["--guide", "0,1", "--pivot", "0,60"]].concat(), "--pivot 0,60 is at the follower's point"),
        ([&follower[..], &["--guide", "0,1", "--pivot", "0,70", "--flat"]].concat(), "at sample 90 (input 90 deg)"),
    ];
    for (args, says) in &cases {
        let out = kinloop(args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: `{says}` missing: {err}");
        assert!(out.stdout.is_empty() && !plot.exists(), "{args:?}: {err}");
    }
    // A plot file that was there before is the user's: a failed command leaves it as it was.
    std::fs::write(&plot, "kept").unwrap();
    let out = kinloop(&cases[0].0);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert_eq!(std::fs::read_to_string(&plot).ok().as_deref(), Some("kept"), "the plot there before was touched");
    std::fs::remove_file(&plot).unwrap();
    // The same at any size: the rocker's pin moves on an arc in a mechanism of 1e151 or 1e-109
    // units too (the circumcentre's squares overflowed and underflowed: "neither a line nor an
    // arc"), the pivot is written short (not a hundred digits), and given back it is taken.
    for (params, pivot) in [
        ("lift=2e151,y0=6e151,l_rod=7e151,c=4e151,d_x=-4e151,d_y=1.4e152", "-4e151,1.4e152"),
        ("lift=2e-109,y0=6e-109,l_rod=7e-109,c=4e-109,d_x=-4e-109,d_y=1.4e-108", "-4e-109,1.4e-108"),
    ] {
        let out = kinloop(&[&pin[..], &["--guide", "0,1", "--params", params]].concat());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{pivot}: {err}");
        assert!(err.contains(&format!("give --rocker {pivot} (a rocking follower)")), "{pivot}: {err}");
        let out = kinloop(&[&pin[..], &["--rocker", pivot, "--params", params]].concat());
        assert!(out.status.success(), "{pivot}: {}", stderr(&out));
    }
    // What the messages say to give is taken, and so is a follower given to a few digits (a
    // guide half a milliradian off, a pivot 0.01 off on an arm of 40).
    let near = [
        [&pin[..], &["--rocker", "-40,140"]].concat(),
        [&follower[..], &["--guide", "0,1"]].concat(),
        [&pin[..], &["--rocker", "-40.01,140"]].concat(),
        [&follower[..], &["--guide", "0.0005,1"]].concat(),
    ];
    for args in near {
        let out = kinloop(&args);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    }
    std::fs::remove_file(&plot).expect("the plot written");
}

/// A flat face whose options make no cam for the motion (a rocking face offset so that it
/// passes through the cam's pivot, an offset beyond what f64 relates to the arm) is a usage
/// error naming the options and the sample's input, as the other follower checks are: it was
/// exit code 1 with "invalid argument: flat_face_profile: at sample 77 ...", the offset 1e308
/// written in three hundred digits. Nothing is written, no plot left.
#[test]
fn a_flat_face_that_makes_no_cam_is_a_usage_error_naming_the_options() {
    let cam = shipped("dwell_cam.kl");
    let plot = std::env::temp_dir().join(format!("kinloop-no-cam-{}.svg", std::process::id()));
    let pin = ["cam", cam.as_str(), "--point", "rocker_pin", "--rocker", "-40,140", "--flat", "--deg"];
    for (offset, says) in [
        (
            "-135",
            "DwellCamRocker: no cam for the follower given (--rocker -40,140, --flat 0, --face-offset -135, the \
             cam's pivot 0,0): at sample 77 (input 77 deg) the face passes through the cam's pivot",
        ),
        ("1e308", "at sample 0 (input 0 deg) the arm from the rocker's pivot"),
        ("-1e308", "beside the face's offset -1e308 and the pivots' distance"),
    ] {
        let out = kinloop(&[&pin[..], &["--face-offset", offset, "--plot", plot.to_str().unwrap()]].concat());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{offset}: {err}");
        assert!(err.contains(says), "{offset}: `{says}` missing: {err}");
        assert!(!err.contains("flat_face_profile") && !err.contains("0000000000"), "{offset}: {err}");
        assert!(out.stdout.is_empty() && !plot.exists(), "{offset}: {err}");
    }
}

/// A guide is a direction whatever its size: `1e308,0` or `1e-320,0` is `1,0`, refused saying
/// the point leaves it by the whole stroke of 20 (its products with the size overflowed to
/// "by inf", and the subnormal lost digits of it), and `0,1e308`, `0,1e-320` are taken and give
/// the table of `0,1` to the bit.
#[test]
fn a_guide_is_its_direction_whatever_its_size() {
    let cam = shipped("dwell_cam.kl");
    let follower = ["cam", cam.as_str(), "--point", "follower", "--roller", "10"];
    for guide in ["1e308,0", "-1e308,1e-300", "1e-320,0"] {
        let out = kinloop(&[&follower[..], &["--guide", guide]].concat());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{guide}: {err}");
        let says = format!(
            "--guide {guide}: the follower's point `follower` does not move along this guide: it leaves the guide's \
             line by 20 over a stroke of 20"
        );
        assert!(err.contains(&says), "{guide}: `{says}` missing: {err}");
    }
    let unit = kinloop(&[&follower[..], &["--guide", "0,1"]].concat());
    assert!(unit.status.success(), "{}", stderr(&unit));
    for guide in ["0,1e308", "1e-300,1e308", "0,1e-320"] {
        let out = kinloop(&[&follower[..], &["--guide", guide]].concat());
        assert!(out.status.success(), "{guide}: {}", stderr(&out));
        assert_eq!(out.stdout, unit.stdout, "{guide}");
    }
}

#[test]
fn the_plot_draws_the_pitch_curve_and_the_profile() {
    let path = std::env::temp_dir().join(format!("kinloop-cam-{}.svg", std::process::id()));
    let out = kinloop(&[
        "cam",
        &shipped("dwell_cam.kl"),
        "--point",
        "follower",
        "--guide",
        "0,1",
        "--roller",
        "10",
        "--plot",
        path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let svg = std::fs::read_to_string(&path).expect("the plot");
    let _ = std::fs::remove_file(&path);
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"), "{}", &svg[..60.min(svg.len())]);
    assert!(svg.contains("pitch curve") && svg.contains("cam profile"));
}

/// The plot is SVG: a name with another format's extension is a usage error, nothing created
/// (`--plot cam.png` held SVG, exit 0); `.SVG` is SVG too.
#[test]
fn a_plot_named_for_another_format_is_refused() {
    let dir = std::env::temp_dir();
    let cam = |name: &str| {
        let path = dir.join(format!("kinloop-cam-{}-{name}", std::process::id()));
        let _ = std::fs::remove_file(&path);
        let args = ["cam", &shipped("dwell_cam.kl"), "--point", "follower", "--guide", "0,1", "--roller", "10"];
        let out = kinloop(&args.into_iter().chain(["--plot", path.to_str().unwrap()]).collect::<Vec<_>>());
        let created = path.exists();
        let _ = std::fs::remove_file(&path);
        (out, created)
    };
    let (out, created) = cam("plot.png");
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("the drawing is SVG, not .png: name it .svg"), "{}", stderr(&out));
    assert!(out.stdout.is_empty() && !created);
    let (out, created) = cam("plot.SVG");
    assert!(out.status.success() && created, "{}", stderr(&out));
}

/// The cam's inputs in degrees are the decimals from `--start` as given, as a sweep writes its
/// samples: from `--start 0.1` over 101 samples, 3.6 degrees apart, 21.7 was written
/// `21.700000000000003` and 28.9 `28.900000000000002` (the start plus the turn's share, rounded
/// twice). Each is the double of the decimal it stands for (written with one decimal, read back).
#[test]
fn the_cam_s_inputs_in_degrees_are_the_decimals_from_the_start() {
    let cam = shipped("dwell_cam.kl");
    let args = ["cam", &cam, "--point", "follower", "--guide", "0,1", "--roller", "10", "--deg"];
    let (_, rows) = csv(&kinloop(&[&args[..], &["--start", "0.1", "--samples", "101"]].concat()));
    assert_eq!(rows.len(), 101);
    for (k, row) in rows.iter().enumerate() {
        let want: f64 = format!("{:.1}", 0.1 + 3.6 * k as f64).parse().expect("a number");
        assert_eq!(row[0], want, "sample {k}");
    }
}

/// A follower's point that turns with the cam (a point on the input's crank, its rocker's pivot
/// the cam's) does not move relative to the cam: refused naming its velocity there as the
/// command writes its other numbers, `(0, 0)`, not in Rust's debug format, `[0.0, 0.0]`.
#[test]
fn a_point_turning_with_the_cam_names_its_velocity_as_numbers_are_written() {
    let file = std::env::temp_dir().join(format!("kinloop-cam-spin-{}.kl", std::process::id()));
    std::fs::write(&file, "pub struct Spin {\n    params r = 1;\n    input phi;\n    point p = r @ phi;\n}\n")
        .expect("write the declaration");
    let out = kinloop(&["cam", &file.display().to_string(), "--point", "p", "--rocker", "0,0"]);
    let err = stderr(&out);
    let _ = std::fs::remove_file(&file);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("does not move around the cam's centre (r' = (0, 0) relative to the cam)"), "{err}");
    assert!(!err.contains("[0.0") && out.stdout.is_empty(), "{err}");
}
