//! `kinloop dynamics` end to end: the built binary on the shipped engine, its CSV (the cycle
//! and the flywheel) parsed and compared with the compiled mechanism of the same declaration
//! (the fixtures' `EngineMachine` and its `mass_model`), its units, options and exit codes.

mod common;

use common::{kinloop, shipped};
use kinloop::Number;
use kinloop::dynamics::{InverseCycle, SpeedLaw};
use kinloop_fixtures as fx;
use std::process::Output;

/// Agreement demanded with the compiled mechanism, of each column's largest magnitude: both
/// evaluate the same plan with the same operations (a few roundings apart), and the CSV
/// writes each value with the digits that read back exactly.
const REL: f64 = 1e-14;

/// A CSV's header and rows.
fn parse(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines.next().expect("header").split(',').map(str::to_string).collect();
    let rows = lines.map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect()).collect();
    (header, rows)
}

fn csv(out: &Output) -> (Vec<String>, Vec<Vec<f64>>) {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    parse(&String::from_utf8(out.stdout.clone()).expect("utf-8"))
}

fn column(header: &[String], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let k = header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    rows.iter().map(|r| r[k]).collect()
}

/// `a` and `b` equal to `REL` of their largest magnitude.
fn assert_close(what: &str, a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len(), "{what}");
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() <= REL * scale, "{what}: {x} against {y}");
    }
}

/// The shipped engine holds the fixture's declaration: the same tokens.
#[test]
fn the_shipped_engine_is_the_fixture_s_declaration() {
    let tokens = |t: &str| t.parse::<proc_macro2::TokenStream>().expect("tokens").to_string().replace("= r\"", "= \"");
    let shipped = std::fs::read_to_string(shipped("engine.kl")).expect("shipped file");
    assert_eq!(tokens(&shipped), tokens(fx::ENGINE_MACHINE_TEXT));
}

#[test]
fn dynamics_writes_the_compiled_engine_s_cycle_and_flywheel() {
    let dir = std::env::temp_dir().join(format!("kinloop-dynamics-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fly = dir.join("flywheel.csv");
    let (header, rows) = csv(&kinloop(&[
        "dynamics",
        &shipped("engine.kl"),
        "--speed",
        "150",
        "--samples",
        "72",
        "--start",
        "0.3",
        "--about",
        "0.01,-0.02",
        "--delta",
        "0.05",
        "--flywheel",
        fly.to_str().unwrap(),
    ]));
    let torque_unit = "mass unit length unit^2/time unit^2";
    let want_header = [
        "phi [rad]".to_string(),
        "omega [rad/time unit]".to_string(),
        "eps [rad/time unit^2]".to_string(),
        "J [mass unit length unit^2]".to_string(),
        "d(J)/d(phi) [mass unit length unit^2/rad]".to_string(),
        format!("load [{torque_unit}]"),
        format!("torque [{torque_unit}]"),
        "shaking_x [mass unit length unit/time unit^2]".to_string(),
        "shaking_y [mass unit length unit/time unit^2]".to_string(),
        format!("shaking_moment [{torque_unit}]"),
    ];
    assert_eq!(header, want_header);
    assert_eq!(rows.len(), 72);

    let engine = fx::EngineMachine::default();
    let mass = engine.mass_model().unwrap();
    let cycle = InverseCycle::new(&engine, &mass, SpeedLaw::Constant(150.0))
        .samples(72)
        .start(0.3)
        .about([0.01, -0.02])
        .run()
        .unwrap();
    let compiled: [(&str, Vec<f64>); 10] = [
        ("phi", cycle.points.iter().map(|p| p.phi).collect()),
        ("omega", cycle.points.iter().map(|p| p.omega).collect()),
        ("eps", cycle.points.iter().map(|p| p.eps).collect()),
        ("J", cycle.points.iter().map(|p| p.inertia).collect()),
        ("d(J)/d(phi)", cycle.points.iter().map(|p| p.inertia_slope).collect()),
        ("load", cycle.points.iter().map(|p| p.load).collect()),
        ("torque", cycle.points.iter().map(|p| p.torque).collect()),
        ("shaking_x", cycle.points.iter().map(|p| p.shaking.force[0]).collect()),
        ("shaking_y", cycle.points.iter().map(|p| p.shaking.force[1]).collect()),
        ("shaking_moment", cycle.points.iter().map(|p| p.shaking.moment).collect()),
    ];
    for ((name, want), h) in compiled.iter().zip(&want_header) {
        assert_close(name, &column(&header, &rows, h), want);
    }

    let f = cycle.flywheel(0.05).unwrap();
    let (fh, frows) = parse(&std::fs::read_to_string(&fly).expect("the flywheel file"));
    assert_eq!(frows.len(), 1);
    let inertia = "mass unit length unit^2";
    for (name, want) in [
        ("delta".to_string(), 0.05),
        (format!("mean_torque [{torque_unit}]"), f.mean_torque),
        (format!("energy_swing [{torque_unit}]"), f.energy_swing),
        (format!("total_inertia [{inertia}]"), f.total_inertia),
        (format!("mechanism_inertia [{inertia}]"), f.mechanism_inertia),
        (format!("flywheel [{inertia}]"), f.flywheel),
        (format!("exact_flywheel [{inertia}]"), f.exact),
        ("start_speed [rad/time unit]".to_string(), f.start_speed),
    ] {
        assert_close(&name, &column(&fh, &frows, &name), &[want]);
    }
    // The brake's mean is what a constant driving torque must overcome: the flywheel is needed.
    assert!(f.mean_torque > 0.0 && f.flywheel > 0.0, "{f:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A crank turning clockwise (`--speed -150`) has the same cycle as the one turning
/// counter-clockwise at the same angles but for the speed's sign: the engine's loads depend on
/// positions only, and its inertia torques on the square of the speed. Its flywheel is the same,
/// its start speed negative (as the library's `Cycle::flywheel` sizes it). Refused before as
/// "not a positive number".
#[test]
fn a_crank_turning_clockwise_has_its_cycle_and_flywheel() {
    let dir = std::env::temp_dir().join(format!("kinloop-dynamics-cw-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |speed: &str| {
        let fly = dir.join(format!("flywheel{speed}.csv"));
        let args = ["--samples", "72", "--start", "0.3", "--delta", "0.05", "--flywheel", fly.to_str().unwrap()];
        let table = csv(&kinloop(&[&["dynamics", &shipped("engine.kl"), "--speed", speed], &args[..]].concat()));
        let flywheel = parse(&std::fs::read_to_string(&fly).expect("the flywheel file"));
        (table, flywheel)
    };
    let ((header, ccw), (fh, ccw_fly)) = run("150");
    let ((header_cw, cw), (fh_cw, cw_fly)) = run("-150");
    assert_eq!((&header, &fh), (&header_cw, &fh_cw));
    assert_eq!(cw.len(), 72);
    for (name, sign) in [("omega [rad/time unit]", -1.0), ("phi [rad]", 1.0), ("J [mass unit length unit^2]", 1.0)]
        .into_iter()
        .chain(header.iter().skip(3).map(|h| (h.as_str(), 1.0)))
    {
        let want: Vec<f64> = column(&header, &ccw, name).iter().map(|v| sign * v).collect();
        assert_close(name, &column(&header, &cw, name), &want);
    }
    for name in &fh {
        let sign = if name.starts_with("start_speed") { -1.0 } else { 1.0 };
        let want: Vec<f64> = column(&fh, &ccw_fly, name).iter().map(|v| sign * v).collect();
        assert_close(name, &column(&fh, &cw_fly, name), &want);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn degrees_and_parameters() {
    let out = kinloop(&[
        "dynamics",
        &shipped("engine.kl"),
        "--speed",
        "9000",
        "--deg",
        "--samples",
        "36",
        "--params",
        "m_p=0.8,p0=0",
    ]);
    let (header, rows) = csv(&out);
    let phi = column(&header, &rows, "phi [deg]");
    for (k, p) in phi.iter().enumerate() {
        assert!((p - 10.0 * k as f64).abs() < 1e-12, "{phi:?}");
    }
    let omega = column(&header, &rows, "omega [deg/time unit]");
    assert!(omega.iter().all(|&w| (w - 9000.0).abs() < 1e-9), "{omega:?}");
    // 9000 degrees per time unit is 50 pi rad per time unit.
    let engine = fx::EngineMachine { m_p: 0.8, p0: 0.0, ..Default::default() };
    let mass = engine.mass_model().unwrap();
    let w = 9000f64.to_radians();
    let cycle = InverseCycle::new(&engine, &mass, SpeedLaw::Constant(w)).samples(36).run().unwrap();
    let torque = column(&header, &rows, "torque [mass unit length unit^2/time unit^2]");
    assert_close("torque", &torque, &cycle.points.iter().map(|p| p.torque).collect::<Vec<f64>>());
    let slope = column(&header, &rows, "d(J)/d(phi) [mass unit length unit^2/deg]");
    let per_deg: Vec<f64> = cycle.points.iter().map(|p| p.inertia_slope.to_radians()).collect();
    assert_close("slope", &slope, &per_deg);
    // Without a file, the flywheel is listed on standard error.
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("flywheel: exact_flywheel = "), "{err}");
}

#[test]
fn bad_requests_and_bad_values_are_usage_errors() {
    let engine = shipped("engine.kl");
    let code = |args: &[&str]| {
        let out = kinloop(args);
        (out.status.code(), String::from_utf8_lossy(&out.stderr).to_string())
    };
    let (c, e) = code(&["dynamics", &shipped("four_bar.kl"), "--speed", "1", "--params", "a=1,b=3,c=2.5,d=3.2"]);
    assert_eq!(c, Some(2), "{e}");
    assert!(e.contains("declares no bodies"), "{e}");
    for args in [["--samples", "4"], ["--delta", "2.5"], ["--delta", "1e-300"], ["--about", "1"]] {
        let mut all = vec!["dynamics", engine.as_str(), "--speed", "10"];
        all.extend(args);
        let (c, e) = code(&all);
        assert_eq!(c, Some(2), "{args:?}: {e}");
        assert!(e.contains(args[0]), "{args:?}: {e}");
    }
    // The bound said as the help says it: 2 itself is refused, and was told "between 1e-6 and 2".
    for delta in ["2", "2.5"] {
        let (c, e) = code(&["dynamics", engine.as_str(), "--speed", "10", "--delta", delta]);
        assert_eq!(c, Some(2), "{e}");
        assert!(e.contains(&format!("--delta {delta} must be from 1e-6 to below 2")), "{e}");
    }
    // A flywheel file that cannot be created stops the command before the cycle is computed
    // (here a start angle the cycle would refuse); one that can is removed again when the
    // cycle fails.
    let missing = std::env::temp_dir().join(format!("kinloop-no-such-dir-{}", std::process::id())).join("f.csv");
    let (c, e) = code(&[
        "dynamics",
        engine.as_str(),
        "--speed",
        "10",
        "--start",
        "1e20",
        "--flywheel",
        missing.to_str().unwrap(),
    ]);
    assert_eq!(c, Some(73), "{e}");
    assert!(e.contains("cannot create the flywheel file") && !e.contains("start"), "{e}");
    let left = std::env::temp_dir().join(format!("kinloop-flywheel-{}.csv", std::process::id()));
    let (c, e) =
        code(&["dynamics", engine.as_str(), "--speed", "10", "--start", "1e20", "--flywheel", left.to_str().unwrap()]);
    assert_eq!(c, Some(2), "{e}");
    assert!(!left.exists(), "an empty flywheel file was left behind");
    // A file that was there before is the user's: kept as it was, neither emptied nor removed
    // (removing the path given deleted it, and as root a device given as the path).
    std::fs::write(&left, "kept\n").unwrap();
    let (c, e) =
        code(&["dynamics", engine.as_str(), "--speed", "10", "--start", "1e20", "--flywheel", left.to_str().unwrap()]);
    assert_eq!(c, Some(2), "{e}");
    assert_eq!(std::fs::read_to_string(&left).ok().as_deref(), Some("kept\n"), "the file there before was touched");
    // Written over where the command succeeds.
    let (c, e) = code(&["dynamics", engine.as_str(), "--speed", "10", "--flywheel", left.to_str().unwrap()]);
    assert_eq!(c, Some(0), "{e}");
    let text = std::fs::read_to_string(&left).unwrap();
    assert!(!text.contains("kept") && text.contains("exact_flywheel"), "{text}");
    std::fs::remove_file(&left).unwrap();
    // The speed on its own (given twice, clap refuses the repetition before the check).
    for speed in ["0", "-0", "inf", "-inf", "NaN"] {
        let (c, e) = code(&["dynamics", engine.as_str(), "--speed", speed]);
        assert_eq!(c, Some(2), "{speed}: {e}");
        let given = speed.parse::<f64>().unwrap();
        assert!(e.contains(&format!("--speed {} must be a finite number, not zero", Number(given))), "{e}");
    }
    // A start angle: not finite (checked here) or too large for the samples of a turn to be
    // told apart (checked by the runtime): both bad arguments.
    for (start, says) in
        [("inf", "--start inf must be a finite number"), ("1e20", "--start 1e20: the start angle must be finite")]
    {
        let (c, e) = code(&["dynamics", engine.as_str(), "--speed", "10", "--start", start]);
        assert_eq!(c, Some(2), "{start}: {e}");
        assert!(e.contains(says), "{start}: {e}");
    }
    // A parameter without a value: a usage error naming it.
    let dir = std::env::temp_dir().join(format!("kinloop-dynamics-unset-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let unset = dir.join("unset.kl");
    std::fs::write(&unset, fx::ENGINE_MACHINE_TEXT.replacen("m_p = 0.5", "m_p", 1)).unwrap();
    let (c, e) = code(&["dynamics", unset.to_str().unwrap(), "--speed", "10"]);
    assert_eq!(c, Some(2), "{e}");
    assert!(e.contains("`m_p` has no value"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
    // A negative mass or moment of inertia from the parameters given: a bad argument, as a
    // parameter that is not finite is, the runtime's error naming the body and the option.
    for (param, body) in [("m_rod=-2", "the mass of body `rod` is -2"), ("j_crank=-1e-3", "inertia of body `crank`")] {
        let (c, e) = code(&["dynamics", &engine, "--speed", "10", "--params", param]);
        assert_eq!(c, Some(2), "{e}");
        assert!(e.contains(body) && e.contains("--params"), "{e}");
    }
}

/// A start angle too large for the samples of a turn to be told apart is named as given, in
/// degrees with `--deg`, not in the radians the cycle is computed in (in degrees, refused
/// before: so far out they do not convert to radians precisely).
#[test]
fn a_start_too_large_is_named_as_given() {
    let engine = shipped("engine.kl");
    let in_degrees = "--start: 1e300 degrees are too many turns out to convert to radians";
    for (deg, given) in [(true, in_degrees), (false, "--start 1e300")] {
        let mut args = vec!["dynamics", engine.as_str(), "--speed", "10", "--start", "1e300"];
        if deg {
            args.push("--deg");
        }
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(given) && (deg || err.contains("told apart")), "{err}");
        // 1e300 degrees are 1.745...e298 rad.
        assert!(!err.contains("e298"), "{err}");
    }
}

/// A machine whose crank cannot turn (the engine with a rod shorter than its crank: at the
/// start the rod stands at `asin(1)`, a limit position) fails, and a note says so in the
/// machine's terms: the error speaks of sweeps (start inside the range, trace the curve), the
/// note that a turning crank meets a position the linkage cannot pass; from another start
/// angle the same; `simulate` says it too.
#[test]
fn a_crank_that_cannot_turn_says_so() {
    let engine = shipped("engine.kl");
    let note = "note: a crank turning this machine meets a singular position";
    for start in ["0", "0.1"] {
        let out = kinloop(&["dynamics", &engine, "--speed", "1", "--params", "l=0.01", "--start", start]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(err.contains(note) && err.contains("kinloop trace"), "--start {start}: {err}");
    }
    let args = ["simulate", &engine, "--speed", "150", "--torque", "2.5", "--flywheel", "0.05", "--time", "0.5"];
    let out = kinloop(&[&args[..], &["--params", "l=0.01"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains(note), "{err}");
    // The shipped engine turns: no note.
    let out = kinloop(&["dynamics", &engine, "--speed", "150"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(!String::from_utf8_lossy(&out.stderr).contains(note));
}

/// Where the turn stops at a limit position or a change point, the error says what goes on in
/// the library's names (`trace_curve`, `AtSingular::Continue`), and the notes say what those
/// are on the command line, as under `sweep`'s: `dynamics` wrote the library's names alone,
/// `--through-crossings` (which it takes) nowhere. The engine with a crank longer than its rod
/// and offset (r = 0.3 > l + e = 0.26) locks at asin(0.26 / 0.3); a parallelogram machine meets
/// its change point at half a turn.
#[test]
fn a_turn_stopped_at_a_singular_position_notes_the_command_line_s_names() {
    let engine = shipped("engine.kl");
    let out = kinloop(&["dynamics", &engine, "--speed", "150", "--params", "r=0.3,l=0.25"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("`trace_curve` follows the curve through it"), "{err}");
    assert!(err.contains("\nnote: `trace_curve` is `kinloop trace` on the command line\n"), "{err}");
    assert!(err.contains("note: a crank turning this machine meets a singular position"), "{err}");
    let path = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("parallelogram_dyn.kl");
    let text = "pub struct Par { params a = 1, b = 3, c = 1, d = 3, m = 1; input phi; unknowns beta = 0.1, \
                gamma = 1.2; loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma; point p = a @ phi; \
                point q = (d, 0) + c @ gamma; body crank: mass m, com p, inertia m, turns phi; \
                body rocker: mass m, com q, inertia m, turns gamma; }";
    std::fs::write(&path, text).expect("write the declaration");
    let out = kinloop(&["dynamics", path.to_str().unwrap(), "--speed", "10", "--start", "0.1"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("the sweep stopped at a singular crossing"), "{err}");
    assert!(err.contains("`AtSingular::Continue` is `--through-crossings`, `trace_curve` is `kinloop trace`"), "{err}");
}

/// A slider-crank machine (the crank's moment of inertia `j_c`, the piston's mass `m_p`, no
/// loads) written to `name` in the tests' directory.
fn slider_crank_machine(name: &str) -> std::path::PathBuf {
    let path = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let text = "pub struct ScDyn { params r=1.0, l=3.0, m_p=2.0, j_c=0.5; input phi; unknowns beta=0, x=4; \
                loop abc: r@phi + l@beta == (x,0); body crank: mass 1.0, com (0,0), inertia j_c, turns phi; \
                body piston: mass m_p, com (x,0); }";
    std::fs::write(&path, text).expect("write the declaration");
    path
}

/// A machine without inertia about its input (a crank whose mass is at its pivot and has no
/// moment of inertia, a massless piston) is told as such, as `simulate` tells it: the sizing
/// said it was "beyond the range of f64" and to change the units.
#[test]
fn a_machine_without_inertia_says_so() {
    let path = slider_crank_machine("sc_dyn.kl");
    let out = kinloop(&["dynamics", path.to_str().unwrap(), "--params", "j_c=0,m_p=0", "--speed", "10", "--deg"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("the machine has no inertia about its input at phi = 0 deg"), "{err}");
    assert!(err.contains("give the bodies that move with the input mass or inertia"), "{err}");
    assert!(!err.contains("range of f64"), "{err}");
}

/// Where the energy method's flywheel and the exact one differ by more than a tenth, a note
/// says which to size by: with no loads, the piston's varying inertia alone makes the speed
/// fluctuate, the energy swing is 0 and the energy method asks for no flywheel. The shipped
/// engine, whose loads dominate, gets no note where its two sizings agree.
#[test]
fn a_note_where_the_energy_method_neglects_what_matters() {
    let path = slider_crank_machine("sc_dyn_note.kl");
    let value = |err: &str, name: &str| -> f64 {
        let line = err.lines().find(|l| l.starts_with(&format!("flywheel: {name} = "))).expect(name);
        line.split(" = ").nth(1).and_then(|v| v.split(' ').next()).and_then(|v| v.parse().ok()).expect(name)
    };
    for (file, params) in [(path.to_str().unwrap().to_string(), "j_c=0"), (shipped("engine.kl"), "m_p=0.8")] {
        let out = kinloop(&["dynamics", &file, "--params", params, "--speed", "10"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{err}");
        let (energy, exact) = (value(&err, "flywheel"), value(&err, "exact_flywheel"));
        let differ = (energy - exact).abs() > 0.1 * energy.max(exact);
        assert_eq!(err.contains("size the flywheel by exact_flywheel"), differ, "{energy} {exact}: {err}");
        if params == "j_c=0" {
            assert!(differ && energy == 0.0 && exact > 0.0, "{err}");
            // No loads: the mean torque, a sum of zeros, is written `0`, not Rust's `-0`.
            assert!(err.contains("flywheel: mean_torque = 0 "), "{err}");
        }
    }
}

/// A moment centre `--about` so far out that the shaking moment about it is beyond the range
/// of f64 (the engine's shaking force is about 3.7e3, so 1e305 away the moment is 4e308) is the
/// argument's error, named: it failed as a solve (exit code 1) advising other units for the
/// model. 1e300 away it is within range and the moment transfers as statics says, `M_A = M_O -
/// (A x F)`: `-x_A F_y` for a centre on the x axis, against the moments about the origin.
#[test]
fn a_moment_centre_too_far_out_is_a_usage_error() {
    let engine = shipped("engine.kl");
    let run = |about: &str| kinloop(&["dynamics", &engine, "--speed", "150", "--samples", "8", "--about", about]);
    for about in ["1e305,0", "1e308,1e308"] {
        let out = run(about);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "--about {about}: {err}");
        assert!(err.contains(&format!("--about {about}")) && err.contains("nearer"), "{err}");
        assert!(out.stdout.is_empty(), "--about {about}");
    }
    let (header, origin) = csv(&run("0,0"));
    let (_, far) = csv(&run("1e300,0"));
    let col = |name: &str| header.iter().position(|h| h.starts_with(name)).expect(name);
    let (fy, m) = (col("shaking_y"), col("shaking_moment"));
    for (o, f) in origin.iter().zip(&far) {
        let want = o[m] - 1e300 * o[fy];
        // The rounding of the products (the origin's moment is lost against 1e300 F_y).
        assert!((f[m] - want).abs() <= 4.0 * f64::EPSILON * want.abs(), "{} against {want}", f[m]);
    }
}

/// The turn's angles in degrees are the decimals from the start as given, as a sweep writes
/// its samples: 93 of the default 360 were their radians times `180/pi` (`5.000000000000001`,
/// `20.000000000000004`), and from `--start 0.1` the start itself `0.10000000000000002`. Each
/// is the double of the decimal it stands for (written with one decimal, read back).
#[test]
fn the_turn_s_angles_in_degrees_are_the_decimals_from_the_start() {
    let engine = shipped("engine.kl");
    // 150 rad per time unit in degrees.
    let speed = "8594.366926962348";
    for (start, samples) in [("0", 360), ("0.1", 12), ("-33.3", 100)] {
        let args = ["dynamics", &engine, "--speed", speed, "--deg", "--start", start];
        let (_, rows) = csv(&kinloop(&[&args[..], &["--samples", &samples.to_string()]].concat()));
        assert_eq!(rows.len(), samples);
        let first: f64 = start.parse().expect("a number");
        for (k, row) in rows.iter().enumerate() {
            let want: f64 = format!("{:.1}", first + 360.0 * k as f64 / samples as f64).parse().expect("a number");
            assert_eq!(row[0], want, "--start {start}, sample {k}");
        }
    }
}

/// With `--deg` the angle a dynamics error names is in degrees, as the table's and `--start`'s
/// are: the engine whose brake torque is `sqrt(1 - phi)`, not finite beyond 1 rad, fails at the
/// first of 8 samples a turn past it, 90 degrees. It was written in radians, `phi =
/// 1.5707963267948966`, where a kinematic failure's angle was already in degrees.
#[test]
fn a_load_not_finite_names_its_angle_in_degrees_with_deg() {
    let path = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("engine_sqrt_brake.kl");
    let brake = "-t_load * (1 + 0.5 * cos(phi))";
    let text = std::fs::read_to_string(shipped("engine.kl")).expect("the shipped engine");
    assert!(text.contains(brake), "the shipped engine's brake law changed");
    std::fs::write(&path, text.replacen(brake, "-t_load * sqrt(1 - phi)", 1)).unwrap();
    let file = path.to_str().unwrap();
    let out = kinloop(&["dynamics", file, "--speed", "8594", "--samples", "8", "--deg"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("the load `brake` is not finite (NaN) at phi = 90"), "{err}");
    // In radians without `--deg`.
    let out = kinloop(&["dynamics", file, "--speed", "150", "--samples", "8"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("at phi = 1.5707963267948966"), "{err}");
}

/// An input named as a column the command writes of its own (`omega`, `J`, `shaking_moment`)
/// is a usage error naming it, before the turn is computed: the table named two columns alike
/// (`omega [rad],omega [rad]`, the speed's column in the angle's unit), which read back as
/// neither. Another name is written as the input's column, with its slope's.
#[test]
fn an_input_named_as_the_command_s_own_column_is_a_usage_error() {
    let text = std::fs::read_to_string(shipped("engine.kl")).expect("the shipped engine");
    let with_input = |input: &str| {
        let file = std::env::temp_dir().join(format!("kinloop-dynamics-input-{input}-{}.kl", std::process::id()));
        std::fs::write(&file, text.replace("phi", input)).expect("written");
        file
    };
    for input in ["omega", "J", "shaking_moment"] {
        let file = with_input(input);
        let out = kinloop(&["dynamics", &file.display().to_string(), "--speed", "150", "--samples", "8"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{input}: {stderr}");
        assert!(out.stdout.is_empty(), "{input}: {}", String::from_utf8_lossy(&out.stdout));
        assert!(stderr.contains(&format!("rename the input `{input}` of EngineMachine")), "{stderr}");
        let _ = std::fs::remove_file(&file);
    }
    let file = with_input("theta");
    let (header, rows) = csv(&kinloop(&["dynamics", &file.display().to_string(), "--speed", "150", "--samples", "8"]));
    assert_eq!((header[0].as_str(), header[1].as_str()), ("theta [rad]", "omega [rad/time unit]"));
    assert!(header[4].starts_with("d(J)/d(theta) ["), "{header:?}");
    assert_eq!(rows.len(), 8);
    let _ = std::fs::remove_file(&file);
}

/// A crank that cannot turn (the engine's crank 2 against its rod 1: the rod's end leaves the
/// line of the piston's offset 0.01 once `|0.01 - 2 sin phi| > 1`) is told the stretch it rocks
/// over, between the limit positions `sin phi = (0.01 -+ 1) / 2`, in the units given.
#[test]
fn a_crank_that_cannot_turn_is_told_the_stretch_it_rocks_over() {
    let engine = shipped("engine.kl");
    let out = kinloop(&["dynamics", &engine, "--params", "r=2,l=1", "--speed", "10", "--deg"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let note = err.lines().find(|l| l.starts_with("note: from phi = 0 deg")).unwrap_or_else(|| panic!("{err}"));
    let number = |after: &str| -> f64 {
        let rest = &note[note.find(after).unwrap_or_else(|| panic!("{note}")) + after.len()..];
        rest[..rest.find(' ').unwrap_or(rest.len())].parse().unwrap_or_else(|e| panic!("{e}: {note}"))
    };
    let (lo, hi) = (((0.01f64 - 1.0) / 2.0).asin().to_degrees(), ((0.01f64 + 1.0) / 2.0).asin().to_degrees());
    assert!((number("between ") - lo).abs() < 1e-7 && (number(") and ") - hi).abs() < 1e-7, "{note}");
    assert!(note.contains("it rocks"), "{note}");
    // A crank that turns: no such note.
    let out = kinloop(&["dynamics", &engine, "--speed", "10"]);
    assert!(out.status.success() && !String::from_utf8_lossy(&out.stderr).contains("rocks"));
}
