//! `kinloop` end to end: the built binary on the shipped `.kl` files, its CSV parsed and
//! compared with the compiled mechanisms of the same declarations (kinloop's fixtures), its
//! diagnostics and exit codes.

mod common;

use common::{csv, kinloop, shipped};
use kinloop::Mechanism;
use kinloop_fixtures as fx;
use std::path::PathBuf;

fn column(header: &[String], name: &str) -> usize {
    header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

/// The shipped files hold the fixtures' declarations: the same tokens.
#[test]
fn shipped_files_are_the_fixtures_declarations() {
    // `stringify!` writes doc comments as raw strings, the lexer as plain ones: the same text.
    let tokens = |t: &str| t.parse::<proc_macro2::TokenStream>().expect("tokens").to_string().replace("= r\"", "= \"");
    let rhombic = fx::RHOMBIC_DRIVE_TEXT.to_string();
    let shipped_files = [
        ("four_bar.kl", fx::FOUR_BAR_TEXT),
        ("rhombic_drive.kl", rhombic.as_str()),
        ("five_bar.kl", fx::FIVE_BAR_TEXT),
        ("dwell_cam.kl", fx::cam_linkage::DWELL_CAM_ROCKER_TEXT),
    ];
    for (file, text) in shipped_files {
        let shipped = std::fs::read_to_string(shipped(file)).expect("shipped file");
        assert_eq!(tokens(&shipped), tokens(text), "{file}");
    }
}

/// The documentation of each shipped file is true where it is read: a link to a Rust type
/// (`[`RhombicDriveDense`]`, `[`HarmonicCamRocker`]`, which the fixtures' text linked) names
/// the mechanism the file declares or none, since a `.kl` file declares that one alone.
#[test]
fn shipped_files_link_no_type_they_do_not_declare() {
    let dir = PathBuf::from(shipped("four_bar.kl")).parent().expect("the shipped files' folder").to_path_buf();
    for entry in std::fs::read_dir(&dir).expect("the shipped files") {
        let path = entry.expect("a shipped file").path();
        if path.extension().is_none_or(|e| e != "kl") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("a shipped file");
        let declared = text.split("pub struct ").nth(1).and_then(|r| r.split([' ', '{', '\n']).next()).unwrap_or("");
        for line in text.lines().filter_map(|l| l.trim_start().strip_prefix("///")) {
            for linked in line.split("[`").skip(1).filter_map(|r| r.split_once("`]").map(|(name, _)| name)) {
                assert_eq!(linked, declared, "{}: {line}", path.display());
            }
        }
    }
}

#[test]
fn solve_writes_the_compiled_mechanisms_state() {
    let drive = fx::RhombicDrive::default();
    let inputs = [0.0, 0.7, -2.0, 3.0];
    let mut args = vec!["solve".to_string(), shipped("rhombic_drive.kl")];
    for x in inputs {
        args.extend(["--at".to_string(), x.to_string()]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (header, rows) = csv(&kinloop(&args));
    assert_eq!(header[0], "phi1 [rad]");
    assert_eq!(rows.len(), inputs.len());
    let cfg = kinloop::NewtonConfig::default();
    for (x, row) in inputs.iter().zip(&rows) {
        let k = drive.kinematics_flat(&[*x], &drive.guess_flat(&[*x]), &cfg).expect("compiled solve");
        // Written with the shortest representation that reads back exactly: equal bits.
        assert_eq!(row[column(&header, "x_c [length unit]")], k.q[2]);
        assert_eq!(row[column(&header, "d(phi2)/d(phi1) [rad/rad]")], k.dq[0][0]);
        assert_eq!(row[column(&header, "d2(x_f)/d(phi1)^2 [length unit/rad^2]")], k.d2q[3][0][0]);
        assert_eq!(row[column(&header, "gap [length unit]")], k.out[6]);
    }
}

#[test]
fn degrees_and_parameters() {
    let (a, b, c, d) = (1.2, 3.0, 2.5, 3.2);
    let four_bar = fx::FourBar { a, b, c, d };
    let params = format!("a={a},b={b},c={c},d={d}");
    let (header, rows) = csv(&kinloop(&["solve", &shipped("four_bar.kl"), "--at", "30", "--deg", "--params", &params]));
    let x = 30f64.to_radians();
    let k = four_bar.kinematics_flat(&[x], &four_bar.guess_flat(&[x]), &Default::default()).expect("solve");
    // Degrees: one conversion and one rounding each.
    let close = |got: f64, want: f64| assert!((got - want).abs() <= 4.0 * f64::EPSILON * want.abs(), "{got} vs {want}");
    close(row_of(&header, &rows, "beta [deg]"), k.q[0].to_degrees());
    close(
        row_of(&header, &rows, "d2(gamma)/d(phi)^2 [deg/deg^2]"),
        k.d2q[1][0][0].to_degrees() / 180f64.to_degrees() * std::f64::consts::PI,
    );
    close(row_of(&header, &rows, "d(pc.y)/d(phi) [length unit/deg]"), k.dout[1][0].to_radians());
}

fn row_of(header: &[String], rows: &[Vec<f64>], name: &str) -> f64 {
    rows[0][column(header, name)]
}

#[test]
fn check_reports_the_structure() {
    let out = kinloop(&["check", &shipped("rhombic_drive.kl")]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with(fx::RhombicDrive::DECOMPOSITION), "{text}");
    assert!(text.contains("x_c [length unit]"), "{text}");
}

/// `check` tells how far a one-input linkage's input moves from 0 on the declared guess's
/// assembly mode, by its motion: a crank-rocker's crank turns fully; a four-bar whose coupler
/// and rocker (2.5 + 1.5) fall short of frame and crank in line rocks between the angles where
/// they stretch out, by the law of cosines; links that close nowhere are said so.
#[test]
fn check_tells_how_far_the_input_moves() {
    let four_bar = shipped("four_bar.kl");
    let motion = |params: &str| {
        let out = kinloop(&["check", &four_bar, "--params", params]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        text.lines().find_map(|l| l.strip_prefix("motion: ")).unwrap_or_else(|| panic!("{text}")).to_string()
    };
    assert!(motion("a=1,b=3,c=2.5,d=3.2").starts_with("phi turns fully from 0"));
    let rocks = motion("a=1,b=2.5,c=1.5,d=3.2");
    let limit = ((1.0f64 + 3.2 * 3.2 - 16.0) / (2.0 * 3.2)).acos();
    let number = |after: &str| -> f64 {
        let rest = &rocks[rocks.find(after).unwrap_or_else(|| panic!("{rocks}")) + after.len()..];
        rest[..rest.find(' ').unwrap_or(rest.len())].parse().unwrap_or_else(|e| panic!("{e}: {rocks}"))
    };
    assert!(rocks.starts_with("from 0 on the assembly mode of the declared guess, phi moves between"), "{rocks}");
    assert!((number("between ") + limit).abs() < 1e-9 && (number(") and ") - limit).abs() < 1e-9, "{rocks}");
    assert!(motion("a=1,b=3,c=2.5,d=10").contains("assembles at none of 360 values of phi"));
    // A parallelogram: at 0 its links lie in line, a change point.
    assert!(motion("a=1,b=3,c=1,d=3").starts_with("phi meets a change point at phi = "));
    // No values for the parameters: nothing to move.
    let out = kinloop(&["check", &four_bar]);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("motion:"));
}

#[test]
fn errors_have_carets_and_exit_codes() {
    let dir = std::env::temp_dir().join(format!("kinloop-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bad = dir.join("bad.kl");
    std::fs::write(
        &bad,
        "pub struct S {\n    params r = 1;\n    input phi;\n    unknowns x = 1;\n    eq e: x == r * phy;\n}\n",
    )
    .expect("write");
    let out = kinloop(&["check", &bad.display().to_string()]);
    assert_eq!(out.status.code(), Some(65));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("error: unknown name `phy`"), "{err}");
    assert!(err.contains("bad.kl:5:20"), "{err}");
    assert!(err.contains("^^^"), "{err}");

    let missing = kinloop(&["check", &dir.join("missing.kl").display().to_string()]);
    assert_eq!(missing.status.code(), Some(66));
    let unset = kinloop(&["solve", &shipped("four_bar.kl"), "--at", "0"]);
    assert_eq!(unset.status.code(), Some(2), "{}", String::from_utf8_lossy(&unset.stderr));
    let wrong_param = kinloop(&["solve", &shipped("rhombic_drive.kl"), "--at", "0", "--params", "nope=1"]);
    assert_eq!(wrong_param.status.code(), Some(2));
    let wrong_inputs = kinloop(&["solve", &shipped("rhombic_drive.kl"), "--at", "0,1"]);
    assert_eq!(wrong_inputs.status.code(), Some(2));
    // A number too small for a double is refused as in --params, not read as 0.
    let underflow = kinloop(&["solve", &shipped("rhombic_drive.kl"), "--at", "1e-400"]);
    let err = String::from_utf8_lossy(&underflow.stderr);
    assert_eq!(underflow.status.code(), Some(2), "{err}");
    assert!(err.contains("`1e-400` is too small for a 64-bit float"), "{err}");
    assert!(kinloop(&["solve", &shipped("rhombic_drive.kl"), "--at", "0e-400"]).status.success());
    // So in an option of one number or a point: a roller of radius 1e-400 was a knife edge, a
    // speed of 1e-400 a machine at rest, without a word.
    let cam = shipped("dwell_cam.kl");
    let engine = shipped("engine.kl");
    for (args, says) in [
        (vec!["cam", &cam, "--point", "follower", "--guide", "0,1", "--roller", "1e-400"], "'--roller <ROLLER>'"),
        (vec!["cam", &cam, "--point", "follower", "--guide", "0,1", "--roller", " 2e-999 "], "'--roller <ROLLER>'"),
        (vec!["dynamics", &engine, "--speed", "1e-400"], "'--speed <SPEED>'"),
        (vec!["dynamics", &engine, "--speed", "150", "--about", "1e-400,0"], "--about 1e-400,0 is not a point"),
    ] {
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says) && err.contains("too small for a 64-bit float and would be 0"), "{args:?}: {err}");
    }
    let spaced =
        kinloop(&["cam", &cam, "--point", "follower", "--guide", "0,1", "--roller", " 10 ", "--samples", "37"]);
    assert!(spaced.status.success(), "{}", String::from_utf8_lossy(&spaced.stderr));
    // Out of reach: a crank longer than the rod leaves no assembly at some angle.
    let out_of_reach = kinloop(&["solve", &shipped("rhombic_drive.kl"), "--at", "1.5", "--params", "r_p=5"]);
    assert_eq!(out_of_reach.status.code(), Some(1), "{}", String::from_utf8_lossy(&out_of_reach.stdout));
    std::fs::remove_dir_all(&dir).ok();
}

/// An option of inputs, of a point or of a point's name given nothing (an unset shell variable,
/// `--at "$X"`) is a usage error saying so and what it takes, where `{option} {value}` read
/// `--at  is not a list of finite numbers: `` is not a number`, two spaces and an empty number,
/// and `--point : DwellCamRocker has no point of that name`.
#[test]
fn an_option_given_nothing_says_so_and_what_it_takes() {
    let (rhombic, four_bar, engine) = (shipped("rhombic_drive.kl"), shipped("four_bar.kl"), shipped("engine.kl"));
    let params = "a=1,b=3,c=2.5,d=3.2";
    for (args, option, takes) in [
        (vec!["solve", &rhombic, "--at", ""], "--at", "a finite number, the mechanism's input"),
        (vec!["solve", &rhombic, "--at", " "], "--at", "a finite number, the mechanism's input"),
        (vec!["sweep", &four_bar, "--params", params, "--from", "", "--to", "1"], "--from", "a finite number"),
        (vec!["extremes", &four_bar, "--params", params, "--from", "0", "--to", ""], "--to", "a finite number"),
        (vec!["dynamics", &engine, "--speed", "150", "--about", ""], "--about", "a point `x,y` of two finite numbers"),
        (
            vec!["cam", &shipped("dwell_cam.kl"), "--point", "", "--guide", "0,1"],
            "--point",
            "the name of a point of DwellCamRocker (its points: follower, rocker_pin)",
        ),
    ] {
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(&format!("{option} is given nothing: give {takes}")), "{args:?}: {err}");
        assert!(!err.contains("  ") && !err.contains("``"), "{args:?}: {err}");
    }
}

/// Samples closer together than the input's doubles can place them (100,000 over
/// `1e12 .. 1e12 + 1`, doubles `1.2e-4` apart: the table repeated rows, 8,193 distinct inputs)
/// are a usage error naming the input and both spacings, before any row; 10,000 over
/// `1e9 .. 1e9 + 1` (doubles `1.2e-7` apart against `1e-4`) are swept, every input distinct.
#[test]
fn samples_finer_than_the_inputs_doubles_are_a_usage_error() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    let sweep = |from: &str, to: &str, samples: &str| {
        kinloop(&["sweep", &four_bar, "--params", params, "--from", from, "--to", to, "--samples", samples])
    };
    let out = sweep("1e12", "1000000000001", "100000");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty());
    assert!(
        err.contains("input `phi`") && err.contains("1.220703125e-4 apart") && err.contains("fewer --samples"),
        "{err}"
    );
    let (_, rows) = csv(&sweep("1e9", "1000000001", "10000"));
    assert_eq!(rows.len(), 10_000);
    assert!(rows.windows(2).all(|w| w[1][0] > w[0][0]), "repeated inputs");
}

/// `sweep` writes the compiled mechanism's sweep: the runtime's one sweep over the model, the
/// same states to the kernels' agreement (1e-15 of a column's magnitude in `kinloop-model`'s
/// parity tests; 1e-13 here for the compiled sweep's rotated sines, a few ulps off libm's), in
/// degrees where asked.
#[test]
fn sweep_writes_the_compiled_mechanisms_sweep() {
    let (a, b, c, d) = (1.0, 3.0, 2.5, 3.2);
    let four_bar = fx::FourBar { a, b, c, d };
    let params = format!("a={a},b={b},c={c},d={d}");
    let out = kinloop(&[
        "sweep",
        &shipped("four_bar.kl"),
        "--from",
        "0",
        "--to",
        "360",
        "--samples",
        "73",
        "--deg",
        "--params",
        &params,
    ]);
    let (header, rows) = csv(&out);
    assert_eq!(rows.len(), 73);
    assert_eq!(header[0], "phi [deg]");
    let g = four_bar.guess_flat(&[0.0]);
    let compiled: Vec<kinloop::Kin<2, 1, 2>> =
        kinloop::Sweep::<_, kinloop::Kin<2, 1, 2>, 2, 1, 2>::new(&four_bar, [0.0], [std::f64::consts::TAU], 73, g)
            .expect("sweep")
            .map(|k| k.expect("compiled state"))
            .collect();
    let close = |got: f64, want: f64, scale: f64| assert!((got - want).abs() <= 1e-13 * scale, "{got} vs {want}");
    for (k, row) in compiled.iter().zip(&rows) {
        close(row[column(&header, "phi [deg]")], k.x[0].to_degrees(), 360.0);
        close(row[column(&header, "beta [deg]")], k.q[0].to_degrees(), 360.0);
        close(row[column(&header, "d(gamma)/d(phi) [deg/deg]")], k.dq[1][0], 1.0 + k.dq[1][0].abs());
        close(row[column(&header, "pc.x [length unit]")], k.out[0], 4.0);
    }
    assert!(out.stderr.is_empty(), "no event: {}", String::from_utf8_lossy(&out.stderr));
}

/// A rocker's sweep stops at its limit position: the states before it are written, the event
/// (in `--events`) is where the coupler and the output stretch in line (closed form), and the
/// command fails.
#[test]
fn sweep_lists_the_limit_position_and_fails() {
    let (a, b, c, d): (f64, f64, f64, f64) = (1.5, 3.0, 1.0, 3.2);
    let dir = std::env::temp_dir().join(format!("kinloop-cli-sweep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let events = dir.join("events.csv");
    let params = format!("a={a},b={b},c={c},d={d}");
    let args = ["sweep", &shipped("four_bar.kl"), "--from", "1.2", "--to", "7.4", "--samples", "100", "--params"];
    let mut args: Vec<&str> = args.to_vec();
    let events_arg = events.display().to_string();
    args.extend([params.as_str(), "--events", &events_arg]);
    let out = kinloop(&args);
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("limit position"), "{err}");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let rows = text.lines().count() - 1;
    // |AD| = b + c: cos(phi) = (a^2 + d^2 - (b + c)^2) / (2 a d), about 1.945; samples 0.0626
    // apart from 1.2 reach it after the twelfth.
    let phi = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    assert_eq!(rows, ((phi - 1.2) / (6.2 / 99.0)).floor() as usize + 1, "{text}");
    let events = std::fs::read_to_string(&events).expect("events file");
    let mut lines = events.lines();
    // The table's headers of the same columns, with their units.
    assert_eq!(lines.next(), Some("kind,tau [1],phi [rad],beta [rad],gamma [rad]"));
    let event: Vec<&str> = lines.next().expect("one event").split(',').collect();
    assert_eq!(event[0], "limit position");
    let at: f64 = event[2].parse().expect("a number");
    assert!((at - phi).abs() < 1e-9, "event at {at}, closed form {phi}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Arguments the runtime's sweep refuses (no sample; several samples over an empty range) are
/// usage errors (exit 2), named on standard error, not failed solves; an `--events` file that
/// cannot be created is exit 73, before anything is written.
#[test]
fn sweep_arguments_the_runtime_refuses_are_usage_errors() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    let empty = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "0", "--params", params]);
    let err = String::from_utf8_lossy(&empty.stderr);
    assert_eq!(empty.status.code(), Some(2), "{err}");
    assert!(err.contains("give --to different from --from"), "{err}");
    assert!(empty.stdout.is_empty());
    let none = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "1", "--samples", "0", "--params", params]);
    let err = String::from_utf8_lossy(&none.stderr);
    assert_eq!(none.status.code(), Some(2), "{err}");
    // The bound of this range, not the library's "at least one sample", which one sample then
    // failed too.
    assert!(err.contains("--samples 0 writes no row") && err.contains("give at least 2 samples"), "{err}");
    assert!(!err.contains("at least one sample"), "{err}");
    assert!(none.stdout.is_empty());
    // Without a range one sample is enough, and none is still too few.
    let none = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "0", "--samples", "0", "--params", params]);
    let err = String::from_utf8_lossy(&none.stderr);
    assert_eq!(none.status.code(), Some(2), "{err}");
    assert!(err.contains("--samples 0 writes no row: give at least 1"), "{err}");
    // One sample needs no range: the state at `from`.
    let one = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "0", "--samples", "1", "--params", params]);
    assert_eq!(csv(&one).1.len(), 1);
    // One sample over a range cannot include both ends: it wrote the row at `from` alone.
    let one = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "1", "--samples", "1", "--params", params]);
    let err = String::from_utf8_lossy(&one.stderr);
    assert_eq!(one.status.code(), Some(2), "{err}");
    assert!(err.contains("--samples 1 writes one row") && err.contains("--to 1"), "{err}");
    assert!(one.stdout.is_empty());
    // A count that is none says what to write (Rust's parser said `invalid digit found in string`).
    for (samples, says) in
        [("-3", "a count cannot be negative"), ("2.5", "a count is a whole number written in digits")]
    {
        let out = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "1", "--samples", samples, "--params", params]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(&format!("'{samples}' for '--samples <SAMPLES>': {says}")), "{err}");
    }
    let bad_to = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "x", "--params", params]);
    let err = String::from_utf8_lossy(&bad_to.stderr);
    assert_eq!(bad_to.status.code(), Some(2), "{err}");
    assert!(err.contains("--to x") && !err.contains("--from"), "{err}");
    let nowhere = std::env::temp_dir().join(format!("kinloop-cli-no-dir-{}", std::process::id())).join("events.csv");
    let nowhere = nowhere.display().to_string();
    let out = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "1", "--params", params, "--events", &nowhere]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(73), "{err}");
    assert!(err.contains("cannot create the events file"), "{err}");
    assert!(out.stdout.is_empty());
}

/// A state solved within a hair of a limit position (a non-Grashof four-bar's, where coupler
/// and rocker stretch in line at phi = 78.58484225726951 deg; here a few ulps before it) is
/// written with a note that its analogs are the rounding's (they are some 3e7 there); a state
/// away from it gets none.
#[test]
fn a_state_near_a_singular_position_is_noted() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=3,b=2,c=2.5,d=4";
    let out = kinloop(&["solve", &four_bar, "--at", "78.5848422572695", "--at", "30", "--deg", "--params", params]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    let notes: Vec<&str> = err.lines().filter(|l| l.starts_with("note: ")).collect();
    assert_eq!(notes.len(), 1, "{err}");
    assert!(notes[0].starts_with("note: FourBar at 78.5848422572695: the smallest pivot ratio is "), "{err}");
    assert!(notes[0].contains("below the 1e-6 a sweep accepts"), "{err}");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert_eq!(text.lines().count(), 3, "{text}");
}

/// A solve that fails says why as a sweep's failure does (no assembly, a singular position,
/// with the block's unknowns and equations), not as the evaluator's internal record of it.
#[test]
fn solve_failures_are_explained() {
    let four_bar = shipped("four_bar.kl");
    // The frame longer than the other three links together: no assembly at any angle.
    let out = kinloop(&["solve", &four_bar, "--at", "0", "--params", "a=1,b=3,c=2.5,d=10"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot be assembled") && err.contains("unknowns beta, gamma"), "{err}");
    assert!(!err.contains("NoAssembly {"), "{err}");
    // d - a = b - c: at phi = 0 the coupler folds onto the rocker, a change point.
    let out = kinloop(&["solve", &four_bar, "--at", "0", "--params", "a=1,b=3,c=2.5,d=1.5"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("singular position") && err.contains("dead centre"), "{err}");
    assert!(err.contains("note: at a limit position `kinloop trace --from 0` starts there"), "{err}");
    assert!(!err.contains("Singular {"), "{err}");
    assert!(out.stdout.is_empty());
    // A non-Grashof four-bar (limit positions at phi = ±2.3186): of three states, the one beyond
    // its reach is explained, the two others written, in their order; exit code 1.
    let params = "a=2,b=2.2,c=2.4,d=3";
    let out = kinloop(&["solve", &four_bar, "--params", params, "--at", "0", "--at", "3.14159", "--at", "1"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("phi = 3.14159") && err.contains("cannot be assembled"), "{err}");
    let text = String::from_utf8_lossy(&out.stdout);
    let inputs: Vec<&str> = text.lines().skip(1).map(|l| l.split(',').next().unwrap_or("")).collect();
    assert_eq!(inputs, ["0", "1"], "{text}");
}

/// The two numbers of "for phi from X ... to Y ..." in a note on where a mechanism assembles.
fn stretch(err: &str, unit: &str) -> (f64, f64) {
    let note = err.lines().find(|l| l.starts_with("note: nearest")).unwrap_or_else(|| panic!("no note: {err}"));
    let after = |key: &str| -> f64 {
        let rest = &note[note.find(key).unwrap_or_else(|| panic!("{key}: {note}")) + key.len()..];
        let end = rest.find([' ']).unwrap_or(rest.len());
        rest[..end].parse().unwrap_or_else(|e| panic!("{e}: {note}"))
    };
    assert!(note.contains("(a limit position) to"), "{note}");
    assert!(unit.is_empty() || note.matches(unit).count() >= 3, "{note}");
    (after(" from "), after(" to "))
}

/// A mechanism that cannot be assembled at the input asked for is told where it does, nearest
/// it: the stretch between the limit positions, here of a four-bar whose coupler and rocker
/// (2.5 + 1.5) fall short of frame and crank in line (3.2 + 1), by the law of cosines; or that
/// its loops close nowhere. The same note after `solve`, `sweep`, `trace` and `extremes`.
/// The dwell cam with a rise of no width: its follower steps by the lift at `phi0` (30
/// degrees) between two samples, the analogs zero on both sides. The run-time model's sweep
/// stops there, as the compiled one does, saying that a piecewise function may step, where it
/// wrote the rocker half a radian away at the next sample as if nothing had happened; with the
/// declared rise it sweeps on.
#[test]
fn a_cam_law_that_steps_stops_the_sweep_there() {
    let cam = shipped("dwell_cam.kl");
    let args = ["sweep", &cam, "--from", "1", "--to", "61", "--samples", "7", "--deg"];
    let out = kinloop(&[&args[..], &["--params", "rise=0"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("the equations hold a piecewise function"), "{err}");
    assert!(err.contains("at phi = 30.0000000"), "{err}");
    // The samples before it were written: a header and 1 to 21 degrees.
    assert_eq!(String::from_utf8_lossy(&out.stdout).lines().count(), 4, "{err}");
    assert_eq!(csv(&kinloop(&args)).1.len(), 7);
}

#[test]
fn a_mechanism_that_cannot_be_assembled_is_told_where_it_does() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=2.5,c=1.5,d=3.2";
    let limit = ((1.0f64 + 3.2 * 3.2 - 16.0) / (2.0 * 3.2)).acos();
    let drawing = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("unassembled.svg");
    let _ = std::fs::remove_file(&drawing);
    let drawn = drawing.display().to_string();
    let runs: [&[&str]; 5] = [
        &["solve", &four_bar, "--params", params, "--at", "3.14"],
        &["sweep", &four_bar, "--params", params, "--from", "3.14", "--to", "4", "--samples", "5"],
        &["trace", &four_bar, "--params", params, "--from", "3.14", "--to", "4"],
        &["extremes", &four_bar, "--params", params, "--from", "3.14", "--to", "4"],
        &["animate", &four_bar, "--params", params, "--from", "3.14", "--to", "4", "--out", &drawn],
    ];
    for args in runs {
        let out = kinloop(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains("cannot be assembled"), "{err}");
        assert!(err.contains("note: nearest phi = 3.14, the mechanism assembles on the assembly mode"), "{err}");
        let (from, to) = stretch(&err, "");
        assert!((from + limit).abs() < 1e-9 && (to - limit).abs() < 1e-9, "{args:?}: {from} {to} against {limit}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    assert!(!drawing.exists());
    // In degrees, as the inputs were given.
    let out = kinloop(&["solve", &four_bar, "--params", params, "--at", "180", "--deg"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("note: nearest phi = 180 deg,"), "{err}");
    // 180 is as far from this turn's stretch as from the next one's: either is the nearest.
    let (from, to) = stretch(&err, " deg");
    let turn = if from > 0.0 { 360.0 } else { 0.0 };
    let l = limit.to_degrees();
    assert!((from - turn + l).abs() < 1e-7 && (to - turn - l).abs() < 1e-7, "{err}");
    // The frame longer than the other three links together: no angle closes the loop.
    let out = kinloop(&["solve", &four_bar, "--at", "0", "--params", "a=1,b=3,c=2.5,d=10"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("the mechanism assembles at none of 360 values of phi over the turn about 0"), "{err}");
    // The cam's turn too: a rod of 10 between the follower and the rocker 40 long, 140 up.
    let cam = ["cam", &shipped("dwell_cam.kl"), "--point", "follower", "--guide", "0,1", "--roller", "10"];
    let out = kinloop(&[&cam[..], &["--params", "l_rod=10"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("note: from the declared guess, the mechanism assembles at none of 360"), "{err}");
    // A five-bar (two inputs, base 5): where along the sweep's path its links first reach, the
    // cranks' pins 4.7 apart (plain geometry, by bisection), in degrees as given.
    let five_bar = shipped("five_bar.kl");
    let path = ["--params", "d=5", "--from", "180,0", "--to", "0,180", "--deg", "--samples", "5"];
    let out = kinloop(&[&["sweep", five_bar.as_str()][..], &path[..]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let gap = |t: f64| {
        let (t1, t2) = (std::f64::consts::PI * (1.0 - t), std::f64::consts::PI * t);
        (5.0 + 1.2 * t2.cos() - t1.cos()).hypot(1.2 * t2.sin() - t1.sin()) - 4.7
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) > 0.0 { lo = mid } else { hi = mid }
    }
    let note = err.lines().find(|l| l.starts_with("note: along the path to --to")).unwrap_or_else(|| panic!("{err}"));
    let th1 = |key: &str| -> f64 {
        let rest = &note[note.find(key).unwrap_or_else(|| panic!("{note}")) + key.len()..];
        rest[..rest.find(' ').unwrap_or(rest.len())].parse().unwrap_or_else(|e| panic!("{e}: {note}"))
    };
    assert!((th1("first assembles at th1 = ") - 180.0 * (1.0 - hi)).abs() < 1e-7, "{note} against {hi}");
    // The sweep's start, the first of the path's 360 samples past the entry: a whole degree
    // (the samples are half a degree apart), written as such, not with the rounding of its
    // conversion from radians in a 16th digit.
    let start = th1("a sweep can start at th1 = ");
    assert!(start == (start * 2.0).round() / 2.0 && (start - 180.0 * (1.0 - hi)).abs() <= 0.5, "{note}");
    assert!(note.contains(&format!("a sweep can start at th1 = {start} deg, th2 = {} deg,", 180.0 - start)), "{note}");
    let out = kinloop(&["sweep", &five_bar, "--params", "d=50", "--from", "180,0", "--to", "0,180", "--deg"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("assembles at none of 360 inputs equally spaced along the path to --to"), "{err}");
    // Where it assembles, or fails otherwise, no note.
    let out = kinloop(&["solve", &four_bar, "--at", "0", "--params", "a=1,b=3,c=2.5,d=1.5"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("singular position") && !err.contains("assembles"), "{err}");
}

/// Standard output that cannot be written (a full disk) is exit 74 with a message, for every
/// command that writes there (the help and the version too), never a panic; and so is an
/// output file that cannot be written.
#[test]
fn standard_output_that_cannot_be_written_is_exit_74() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return;
    };
    let targets = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("full_targets.csv");
    std::fs::write(&targets, "0.97,1.49\n1.12,2.34\n0.15,2.28\n-0.61,1.42\n").expect("write the targets");
    let targets = targets.display().to_string();
    let coupler = shipped("coupler_four_bar.kl");
    let synth = ["synth", &coupler, "--targets", &targets, "--path", "p", "--vary", "a=0.8..1.4", "--starts", "2"];
    let engine = shipped("engine.kl");
    let runs: [&[&str]; 14] = [
        &["check", &shipped("rhombic_drive.kl")],
        &["solve", &shipped("rhombic_drive.kl"), "--at", "0"],
        &["sweep", &shipped("rhombic_drive.kl"), "--from", "0", "--to", "1"],
        &["extremes", &shipped("rhombic_drive.kl"), "--from", "0", "--to", "1"],
        &synth,
        &["cam", &shipped("dwell_cam.kl"), "--point", "follower", "--guide", "0,1", "--samples", "37"],
        &["dynamics", &engine, "--speed", "150", "--samples", "8"],
        &["simulate", &engine, "--speed", "150", "--time", "0.01", "--samples", "3"],
        &["--help"],
        &["--version"],
        &["help"],
        &["help", "sweep"],
        &["sweep", "--help"],
        &["-h"],
    ];
    for args in runs {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_kinloop"))
            .args(args)
            .stdout(full.try_clone().expect("/dev/full"))
            .output()
            .expect("the kinloop binary runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(74), "{args:?}: {err}");
        assert!(err.contains("error: cannot write") && !err.contains("panicked"), "{args:?}: {err}");
    }
    // Files that cannot be written: the events of a sweep, the flywheel, an animation.
    let sweep = ["sweep", &shipped("four_bar.kl"), "--params", "a=1,b=3,c=2.5,d=3.2", "--from", "0", "--to", "1"];
    let files: [&[&str]; 3] = [
        &[&sweep[..], &["--events", "/dev/full"]].concat(),
        &["dynamics", &engine, "--speed", "150", "--samples", "8", "--flywheel", "/dev/full"],
        &["animate", &shipped("four_bar.kl"), "--params", "a=1,b=3,c=2.5,d=3.2", "--from", "0", "--to", "1"],
    ];
    for (k, args) in files.into_iter().enumerate() {
        let args = if k == 2 { [args, &["--format", "svg", "--out", "/dev/full"]].concat() } else { args.to_vec() };
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(74), "{args:?}: {err}");
        assert!(err.contains("error: cannot write") && !err.contains("panicked"), "{args:?}: {err}");
    }
}

/// A file named by `--events`, `--flywheel` or `--plot` whose write fails part way (here a
/// file size limit, its signal ignored so that the write fails with `EFBIG`) is removed rather
/// than left cut short, whether the command made it or it was there before (its content was
/// replaced when the writing began): exit code 74, the failure named, no file.
#[cfg(target_os = "linux")]
#[test]
fn a_file_written_part_way_is_removed() {
    let dir = std::env::temp_dir().join(format!("kinloop-cli-cut-short-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = |name: &str| dir.join(name).display().to_string();
    let (events, flywheel, there, plot) =
        (path("events.csv"), path("flywheel.csv"), path("there.csv"), path("cam.svg"));
    std::fs::write(&there, "what was there\n").expect("a file to replace");
    // Blocks of the shell's `ulimit -f`: none for the short files, one for the drawing, so that
    // it is cut inside its text.
    let (engine, four_bar, cam) = (shipped("engine.kl"), shipped("four_bar.kl"), shipped("dwell_cam.kl"));
    let sweep = ["sweep", &four_bar, "--params", "a=1.5,b=3,c=1,d=3.2", "--from", "1.2", "--to", "7.4"];
    let runs: [(Vec<&str>, &str, &str, u32); 4] = [
        ([&sweep[..], &["--events", &events]].concat(), &events, "the events", 0),
        (
            vec!["dynamics", &engine, "--speed", "150", "--samples", "8", "--flywheel", &flywheel],
            &flywheel,
            "the flywheel",
            0,
        ),
        (
            vec!["dynamics", &engine, "--speed", "150", "--samples", "8", "--flywheel", &there],
            &there,
            "the flywheel",
            0,
        ),
        (vec!["cam", &cam, "--point", "follower", "--guide", "0,1", "--plot", &plot], &plot, "the plot", 1),
    ];
    for (args, file, what, blocks) in runs {
        let script = format!(r#"trap '' XFSZ; ulimit -f {blocks}; exec "$0" "$@""#);
        let o = std::process::Command::new("sh")
            .args(["-c", &script, env!("CARGO_BIN_EXE_kinloop")])
            .args(&args)
            .output()
            .expect("sh runs");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(74), "{args:?}: {err}");
        assert!(err.contains(&format!("error: cannot write {what}")) && !err.contains("panicked"), "{args:?}: {err}");
        let left = std::fs::metadata(file).map(|m| m.len());
        assert!(left.is_err(), "{args:?}: a file of {left:?} bytes was left");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A sweep or a trace whose table cannot be written (standard output full) fails before its
/// events are written: the `--events` file it made is removed, not left empty (dynamics and cam
/// removed theirs already); a file that was there before is left as it was.
#[test]
fn an_events_file_made_is_removed_when_the_table_cannot_be_written() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("kinloop-cli-events-full-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let four_bar = shipped("four_bar.kl");
    for command in ["sweep", "trace"] {
        let (made, there) = (dir.join(format!("{command}.csv")), dir.join(format!("{command}-there.csv")));
        std::fs::write(&there, "kept\n").expect("a file there before");
        for events in [&made, &there] {
            let args = [command, &four_bar, "--params", "a=1,b=3,c=2.5,d=3.2", "--from", "0", "--to", "1"];
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_kinloop"))
                .args(args)
                .args(["--events", &events.display().to_string()])
                .stdout(full.try_clone().expect("/dev/full"))
                .output()
                .expect("the kinloop binary runs");
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(74), "{command}: {err}");
            assert!(err.contains("error: cannot write the table"), "{command}: {err}");
        }
        assert!(!made.exists(), "{command}: the events file it made was left");
        assert_eq!(std::fs::read_to_string(&there).expect("kept"), "kept\n", "{command}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `-` given to an option that writes a file (`--events`, `--flywheel`, `--plot`) is a usage
/// error naming the option and how to name a file of that name: it made a file named `-` in the
/// working directory without a word, where `animate --out -` (and the usual convention) is
/// standard output, which holds the table here. `./-` is still that file.
#[test]
fn a_dash_for_a_file_written_is_refused() {
    let dir = std::env::temp_dir().join(format!("kinloop-cli-dash-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (four_bar, engine, cam) = (shipped("four_bar.kl"), shipped("engine.kl"), shipped("dwell_cam.kl"));
    let sweep = ["sweep", &four_bar, "--params", "a=1,b=3,c=2.5,d=3.2", "--from", "0", "--to", "1", "--samples", "3"];
    let trace = ["trace", &four_bar, "--params", "a=1,b=3,c=2.5,d=3.2", "--from", "0", "--to", "1"];
    let runs: [(&[&str], &str); 4] = [
        (&sweep, "--events"),
        (&trace, "--events"),
        (&["dynamics", &engine, "--speed", "150", "--samples", "8"], "--flywheel"),
        (&["cam", &cam, "--point", "follower", "--guide", "0,1", "--samples", "8"], "--plot"),
    ];
    let run = |args: &[&str], option: &str, file: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_kinloop"))
            .args(args)
            .args([option, file])
            .current_dir(&dir)
            .output()
            .expect("the kinloop binary runs")
    };
    for (args, option) in runs {
        let out = run(args, option, "-");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?} {option} -: {err}");
        assert!(err.contains(&format!("{option} -")) && err.contains("`./-`"), "{args:?} {option} -: {err}");
        assert!(out.stdout.is_empty(), "{args:?} {option} -: nothing is written");
        assert!(!dir.join("-").exists(), "{args:?} {option} -: a file named `-` was made");
        // A file of that name, named so, is written.
        let out = run(args, option, "./-");
        assert!(out.status.success(), "{args:?} {option} ./-: {}", String::from_utf8_lossy(&out.stderr));
        assert!(std::fs::metadata(dir.join("-")).is_ok_and(|m| m.len() > 0), "{args:?} {option} ./-");
        std::fs::remove_file(dir.join("-")).expect("the file named `-`");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `sweep` of several samples and `animate` from one input to the same are usage errors said in
/// the command line's terms, naming `--from`, `--to` and what to give instead: both passed on
/// the runtime's "invalid argument: a sweep with several samples needs `to` different from
/// `from`", which names no option. `sweep --samples 1` there still writes that one state.
#[test]
fn a_sweep_or_an_animation_to_where_it_starts_says_to_give_another_to() {
    let four_bar = shipped("four_bar.kl");
    let svg = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("same_ends.svg").display().to_string();
    let params = ["--params", "a=1,b=3,c=2.5,d=3.2"];
    let runs: [(Vec<&str>, &str); 4] = [
        ([&["sweep", &four_bar], &params[..], &["--from", "1", "--to", "1"]].concat(), "--samples 1"),
        (
            [&["sweep", &four_bar], &params[..], &["--from", "60", "--to", "60.0", "--deg", "--samples", "5"]].concat(),
            "--samples 1",
        ),
        (
            [&["animate", &four_bar], &params[..], &["--from", "1", "--to", "1", "--out", &svg]].concat(),
            "--to different",
        ),
        (
            [&["animate", &four_bar], &params[..], &["--from", "60", "--to", "60", "--deg", "--out", &svg]].concat(),
            "--to different",
        ),
    ];
    for (args, instead) in runs {
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("--from") && err.contains("--to") && err.contains(instead), "{args:?}: {err}");
        assert!(!err.contains("invalid argument") && !err.contains("`to`"), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    let (_, rows) =
        csv(&kinloop(&[&["sweep", &four_bar], &params[..], &["--from", "1", "--to", "1", "--samples", "1"]].concat()));
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0][0], 1.0);
}

/// A file to read named `-` (the declaration, `--targets`), where there is none of that name, is
/// said not to be standard input, with what to give instead: it was "No such file or directory"
/// alone, for a name that by the usual convention reads standard input. `/dev/stdin` reads it.
#[test]
fn a_dash_for_a_file_read_says_it_is_not_standard_input() {
    let dir = std::env::temp_dir().join(format!("kinloop-cli-dash-read-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let coupler = shipped("coupler_four_bar.kl");
    let points = dir.join("points.csv");
    std::fs::write(&points, "0.9661,1.4940\n1.2330,2.2071\n0.6814,2.4363\n-0.0985,2.1152\n").expect("targets");
    let synth = |targets: &str| {
        ["synth", coupler.as_str(), "--targets", targets, "--path", "p", "--vary", "a=0.8..1.4,b=2..3.5", "--jobs", "1"]
            .map(str::to_string)
            .to_vec()
    };
    let run = |args: &[String], stdin: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_kinloop"))
            .args(args)
            .current_dir(&dir)
            .stdin(std::fs::File::open(stdin).expect("standard input"))
            .output()
            .expect("the kinloop binary runs")
    };
    let check = |file: &str| vec!["check".to_string(), file.to_string()];
    for (args, stdin) in [(check("-"), PathBuf::from(shipped("four_bar.kl"))), (synth("-"), points.clone())] {
        let out = run(&args, &stdin);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(66), "{args:?}: {err}");
        assert!(err.contains("not standard input") && err.contains("/dev/stdin"), "{args:?}: {err}");
    }
    for (args, stdin) in [(check("/dev/stdin"), PathBuf::from(shipped("four_bar.kl"))), (synth("/dev/stdin"), points)] {
        let out = run(&args, &stdin);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A count of one is named in the singular: one input given where a mechanism has two.
#[test]
fn one_input_is_named_in_the_singular() {
    let out = kinloop(&["solve", &shipped("five_bar.kl"), "--at", "0.5"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("--at 0.5 gives 1 input, the mechanism has 2"), "{err}");
}

/// With `--deg`, inputs are named in degrees everywhere: the input written by `solve` is the
/// one given (`30`, the angle whose radians were solved at), and the arguments refused and
/// the places of failures are named as given, not in the radians the model computes in.
#[test]
fn with_deg_inputs_are_named_in_degrees() {
    let four_bar = shipped("four_bar.kl");
    let (header, rows) = csv(&kinloop(&["solve", &four_bar, "--params", "a=1,b=3,c=2.5,d=3.2", "--at", "30", "--deg"]));
    assert_eq!(header[0], "phi [deg]");
    assert_eq!(rows[0][0], 30.0);
    // A sweep's inputs: the equally spaced values from `--from` to `--to` as given (each
    // sample's radians within a rounding of them).
    let args = ["sweep", &four_bar, "--params", "a=1,b=3,c=2.5,d=3.2", "--from", "0", "--to", "360", "--samples", "73"];
    let (_, rows) = csv(&kinloop(&[&args[..], &["--deg"]].concat()));
    let phis: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(phis, (0..73).map(|k| 5.0 * k as f64).collect::<Vec<f64>>());
    let err = |args: &[&str], code: i32| {
        let out = kinloop(args);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        err
    };
    let unreachable = "a=1,b=3,c=2.5,d=10";
    // Said once: the mechanism and the input are the error's own location (not also a prefix).
    let once = |e: &str| e.matches("FourBar").count() == 1 && e.matches("phi = 30").count() == 1;
    let e = err(&["solve", &four_bar, "--params", unreachable, "--at", "30", "--deg"], 1);
    assert!(e.contains("cannot be assembled") && e.contains("at phi = 30 ") && once(&e), "{e}");
    let e = err(&["sweep", &four_bar, "--params", unreachable, "--from", "30", "--to", "60", "--deg"], 1);
    assert!(e.contains("cannot be assembled") && e.contains("at phi = 30 ") && once(&e), "{e}");
    let e = err(&["extremes", &four_bar, "--params", unreachable, "--from", "30", "--to", "60", "--deg"], 1);
    assert!(e.contains("cannot be assembled") && e.contains("at phi = 30 ") && once(&e), "{e}");
    let svg = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("unreachable.svg");
    let svg = svg.display().to_string();
    let e =
        err(&["animate", &four_bar, "--params", unreachable, "--from", "30", "--to", "60", "--deg", "--out", &svg], 1);
    assert!(e.contains("cannot be assembled") && e.contains("at phi = 30 ") && once(&e), "{e}");
    let e = err(&["extremes", &four_bar, "--params", "a=1,b=3,c=2.5,d=3.2", "--from", "90", "--to", "30", "--deg"], 2);
    assert!(e.contains("from < to") && e.contains("90") && !e.contains("1.57"), "{e}");
}

/// An angle in degrees so many turns out that its radians are rounded by more than a solve's
/// precision is refused as given (`1e17` degrees, 280 on its turn, was solved at 275.6 and
/// written without a word): by `solve`, `sweep` and `extremes`. Within the bound, the angle a
/// turn's multiple out is solved as its turn's (to the conversion's rounding, `|x| eps`).
#[test]
fn degrees_too_many_turns_out_to_convert_are_refused() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    for args in [
        vec!["solve", &four_bar, "--params", params, "--at", "1e17", "--deg"],
        vec!["sweep", &four_bar, "--params", params, "--from", "1e17", "--to", "1.0000000000000001e17", "--deg"],
        vec!["extremes", &four_bar, "--params", params, "--from", "0", "--to", "-3e8", "--deg"],
    ] {
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("degrees are too many turns out to convert to radians"), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    let out = kinloop(&["solve", &four_bar, "--params", params, "--at", "1e17", "--deg"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("e.g. 280 for a mechanism that repeats every turn"));
    // 2.5e8 degrees is 694,444 turns and 160 degrees: within the bound (4.4e6 rad), solved there
    // to the conversion's rounding (4.4e6 eps, 1e-9 rad), amplified by the rocker's analog.
    let (_, far) = csv(&kinloop(&["solve", &four_bar, "--params", params, "--at", "2.5e8", "--deg"]));
    let (_, near) = csv(&kinloop(&["solve", &four_bar, "--params", params, "--at", "160", "--deg"]));
    assert_eq!(far[0][0], 2.5e8);
    for (a, b) in far[0][1..].iter().zip(&near[0][1..]) {
        assert!((a - b).abs() < 1e-6 * (1.0 + b.abs()), "{far:?} against {near:?}");
    }
}

/// A parameter given twice in `--params` is a usage error naming it, not the last value
/// silently.
#[test]
fn a_parameter_given_twice_is_a_usage_error() {
    let out = kinloop(&["solve", &shipped("four_bar.kl"), "--at", "0", "--params", "a=1,b=3,c=2.5,d=3.2,a=1.5"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("`a`") && err.contains("twice"), "{err}");
    assert!(out.stdout.is_empty());
}

/// A value that underflows to 0 (`1e-400`) is refused as one that overflows is, not taken for
/// 0 without a word; 0 written as such is taken.
#[test]
fn a_parameter_that_underflows_is_a_usage_error() {
    let run =
        |a: &str| kinloop(&["solve", &shipped("slider_crank.kl"), "--at", "0", "--params", &format!("r=1,l=3,e={a}")]);
    let out = run("1e-400");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("`e` in --params: `1e-400` is too small for a 64-bit float and would be 0"), "{err}");
    assert!(run("0e-400").status.success());
}

/// A file far larger than a declaration (a table or a log named by mistake) is refused after
/// the most a declaration may have, with a short message: not read whole, and not echoed.
#[test]
fn a_file_too_large_for_a_declaration_is_refused_briefly() {
    let big = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("too_large.kl");
    std::fs::write(&big, " ".repeat(3 << 20)).expect("write");
    let out = kinloop(&["check", &big.display().to_string()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(65), "{}", &err[..err.len().min(500)]);
    assert!(err.len() < 1000, "{} bytes on standard error", err.len());
    assert!(err.contains("more than 1048576 bytes"), "{err}");
}

/// A file that is not text (a binary, a file in another encoding) is named as such, with the
/// place of its first byte that is not UTF-8.
#[test]
fn a_file_that_is_not_text_says_where() {
    let bin = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("latin1.kl");
    // `°` in Latin-1 on the second line.
    std::fs::write(&bin, b"pub struct S {\n    params a = 90\xb0;\n}\n").expect("write");
    let out = kinloop(&["check", &bin.display().to_string()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(66), "{err}");
    assert!(err.contains("not UTF-8 text") && err.contains("line 2, column 18"), "{err}");
}

/// A range longer than the turns a sweep follows is a mistake of the arguments, found before
/// any step: a usage error (exit 2) of `sweep`, `extremes` and `animate` alike, saying how far
/// apart `--from` and `--to` may be, with nothing written.
#[test]
fn a_range_of_too_many_turns_is_a_usage_error() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    let out_file = std::env::temp_dir().join(format!("kinloop-cli-turns-{}.svg", std::process::id()));
    let out_file = out_file.display().to_string();
    // In degrees, from a turn's multiple to its opposite: a range from 0 this long is beyond
    // the degrees that convert to radians precisely (`degrees_too_many_turns_out_to_convert_are_refused`).
    for (command, from, to, deg, span) in [
        ("sweep", "0", "1e7", false, "at most 6283185.3 apart in the units given (--to 6283185.3)"),
        ("sweep", "-2.5e8", "2.5e8", true, "at most 360000000 apart in the units given (degrees for an angle)"),
        ("extremes", "0", "1e7", false, "at most 6283185.3 apart"),
        ("animate", "0", "1e7", false, "at most 6283185.3 apart"),
    ] {
        let mut args = vec![command, four_bar.as_str(), "--from", from, "--to", to, "--params", params];
        if deg {
            args.push("--deg");
        }
        if command == "animate" {
            args.extend(["--out", out_file.as_str()]);
        }
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command} --to {to}: {err}");
        for what in [&format!("--from {from} --to {to}"), "turns", "the 1e6 turns a sweep", span] {
            assert!(err.contains(what), "{command} --to {to}: `{what}` missing: {err}");
        }
        assert!(out.stdout.is_empty(), "{command}: {}", String::from_utf8_lossy(&out.stdout));
    }
    assert!(!std::path::Path::new(&out_file).exists());
}

/// The span allowed is said in the units given, and is allowed: the dwell cam's cam angle, taken
/// within its turn by `wrap` (no sine or cosine), has its turns counted in the unit its equations
/// give it, so that `--to 6283185` is more than a sweep follows. It was refused with "give --from
/// and --to at most 1e6 turns apart (6283185.3 rad of an angle input)", exactly what was given.
#[test]
fn a_range_too_long_says_the_span_allowed_in_the_units_given() {
    let dwell = shipped("dwell_cam.kl");
    let out = kinloop(&["sweep", &dwell, "--from", "0", "--to", "6283185", "--samples", "2"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(!err.contains("6283185.3"), "{err}");
    let to = err.split("(--to ").nth(1).and_then(|r| r.split(')').next()).expect("a --to allowed");
    let allowed: f64 = to.parse().unwrap_or_else(|e| panic!("{to}: {e}: {err}"));
    assert!(allowed > 4e6 && allowed < 6283185.0, "{err}");
    assert!(err.contains(&format!("at most {to} apart in the units given")), "{err}");
    // That range is followed: a trace of a few points from its start is not refused.
    let out = kinloop(&["trace", &dwell, "--from", "0", "--to", to, "--max-points", "5"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("turns a sweep or a trace follows"), "{err}");
    assert_eq!(out.status.code(), Some(0), "{err}");
}

/// The `--to` advised for a range that does not start at 0 keeps the span within the one
/// allowed: from 0.06, the end 6283185.36 was written to eight digits as 6283185.4, a span
/// beyond the 6283185.3 allowed, which the sweep refused in turn. It is rounded towards `--from`.
#[test]
fn the_to_advised_for_a_range_too_long_is_followed() {
    let four_bar = shipped("four_bar.kl");
    let params = ["--params", "a=1,b=3,c=2.5,d=3.2"];
    let out = kinloop(&[&["sweep", four_bar.as_str(), "--from", "0.06", "--to", "1e7"][..], &params].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    let to = err.split("(--to ").nth(1).and_then(|r| r.split(')').next()).expect("a --to allowed");
    assert_eq!(to, "6283185.3", "{err}");
    let args = ["trace", four_bar.as_str(), "--from", "0.06", "--to", to, "--max-points", "5"];
    let out = kinloop(&[&args[..], &params].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("turns a sweep or a trace follows"), "{err}");
    assert_eq!(out.status.code(), Some(0), "{err}");
}

/// An opening bracket never closed before the brace that ends the block is reported where it
/// is, not at the brace (which closes the block and is no mistake of its own).
#[test]
fn an_unclosed_parenthesis_is_reported_where_it_opens() {
    let dir = std::env::temp_dir().join(format!("kinloop-cli-unclosed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let cases = [
        // In a loop's equation, the block's `}` after it.
        (
            "paren.kl",
            "pub struct S {\n    params a = 1;\n    input phi;\n    unknowns x = 0;\n    loop l: a @ phi == (x, 0;\n}\n",
            "(",
            "paren.kl:5:24",
            "line 6, column 1",
        ),
        // A bracket inside a parenthesis inside the block: the innermost one is never closed.
        (
            "bracket.kl",
            "pub struct S {\n    params a = 1;\n    input phi;\n    unknowns x = (0, [1;\n}\n",
            "[",
            "bracket.kl:4:22",
            "line 5, column 1",
        ),
    ];
    for (name, text, open, place, brace) in cases {
        let file = dir.join(name);
        std::fs::write(&file, text).expect("write");
        let out = kinloop(&["check", &file.display().to_string()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(65), "{err}");
        assert!(err.contains(&format!("unclosed delimiter: this `{open}` is never closed")), "{err}");
        assert!(err.contains(place), "{err}");
        assert!(err.contains(&format!("the `}}` at {brace}")), "the brace that met it is named: {err}");
        assert!(!err.contains("unexpected closing delimiter"), "{err}");
    }
    // A closing parenthesis that closes nothing open around it: the mistake is where it is.
    let stray = dir.join("stray.kl");
    let text = "pub struct S {\n    params a = 1;\n    input phi;\n    unknowns x = 0;\n    loop l: a @ phi == (x, 0);\n    )\n}\n";
    std::fs::write(&stray, text).expect("write");
    let out = kinloop(&["check", &stray.display().to_string()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(65), "{err}");
    assert!(err.contains("unexpected closing delimiter: `)`") && err.contains("stray.kl:6:5"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A negative number given to an option that takes a number is read as the option's value and
/// refused by the option's own check, naming it: not taken for an unknown argument, with clap's
/// tip to write `-- -1` (which makes it a file name, not the option's value).
#[test]
fn a_negative_number_is_the_options_value() {
    let (engine, four_bar) = (shipped("engine.kl"), shipped("four_bar.kl"));
    let coupler = shipped("coupler_four_bar.kl");
    let svg = std::env::temp_dir().join(format!("kinloop-cli-negative-{}.svg", std::process::id()));
    let svg = svg.display().to_string();
    let fb = ["--from", "0", "--to", "1", "--params", "a=1,b=3,c=2.5,d=3.2"];
    let (sweep, extremes) = (["sweep", four_bar.as_str()], ["extremes", four_bar.as_str()]);
    let animate = ["animate", four_bar.as_str(), "--out", svg.as_str()];
    let synth = ["synth", coupler.as_str(), "--targets", "t.csv", "--path", "p", "--vary", "a=1..2"];
    let mut cases: Vec<(Vec<&str>, &str)> = vec![
        ([&sweep[..], &fb, &["--samples", "-1"]].concat(), "--samples"),
        ([&extremes[..], &fb, &["--samples", "-1"]].concat(), "--samples"),
        ([&animate[..], &fb, &["--samples", "-3"]].concat(), "--samples -3"),
        ([&animate[..], &fb, &["--frames", "-3"]].concat(), "--frames"),
        (vec!["dynamics", engine.as_str(), "--speed", "150", "--samples", "-8"], "--samples"),
        (vec!["dynamics", engine.as_str(), "--speed", "150", "--delta", "-0.02"], "--delta -0.02"),
        (vec!["simulate", engine.as_str(), "--time", "-1"], "--time -1"),
        (vec!["simulate", engine.as_str(), "--time", "1", "--flywheel", "-1"], "--flywheel -1"),
        (vec!["simulate", engine.as_str(), "--time", "1", "--samples", "-1"], "--samples"),
    ];
    for option in ["--starts", "--keep", "--jobs", "--seed"] {
        cases.push(([&synth[..], &[option, "-1"]].concat(), option));
    }
    for (args, option) in cases {
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(option), "{args:?}: `{option}` missing: {err}");
        assert!(!err.contains("unexpected argument") && !err.contains("-- -"), "{args:?}: {err}");
    }
    assert!(!std::path::Path::new(&svg).exists());
}

/// A parameter that has no value (no default in the declaration, none in `--params`) is a
/// mistake of the arguments, found before any solve: exit 2 for every command that solves,
/// naming every parameter missing and how to give it, with nothing written. `check` reports
/// the structure without values; `synth` needs none for the parameters it varies.
#[test]
fn a_parameter_without_a_value_is_a_usage_error() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("unset_params");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let four_bar = shipped("four_bar.kl");
    let svg = dir.join("unset.svg").display().to_string();
    let engine = dir.join("engine.kl");
    std::fs::write(&engine, fx::ENGINE_MACHINE_TEXT.replacen("m_p = 0.5", "m_p", 1)).expect("write");
    let engine = engine.display().to_string();
    let range = ["--from", "0", "--to", "1"];
    let runs: [(Vec<&str>, &str); 7] = [
        (vec!["solve", &four_bar, "--at", "0", "--params", "a=1,d=3.2"], "parameters `b`, `c` have no value"),
        ([&["sweep", four_bar.as_str()][..], &range].concat(), "parameters `a`, `b`, `c`, `d` have no value"),
        ([&["extremes", four_bar.as_str()][..], &range].concat(), "parameters `a`, `b`, `c`, `d` have no value"),
        ([&["animate", four_bar.as_str(), "--out", &svg][..], &range].concat(), "`a`, `b`, `c`, `d` have no value"),
        (vec!["dynamics", &engine, "--speed", "10"], "parameter `m_p` has no value"),
        (vec!["simulate", &engine, "--speed", "10", "--time", "0.1"], "parameter `m_p` has no value"),
        (vec!["solve", &four_bar, "--at", "0", "--params", "a=1,b=3,c=2.5"], "give it with --params d="),
    ];
    for (args, says) in runs {
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says) && err.contains("--params"), "{args:?}: `{says}` missing: {err}");
        assert!(out.stdout.is_empty(), "{args:?}: {}", String::from_utf8_lossy(&out.stdout));
    }
    assert!(!std::path::Path::new(&svg).exists());
    let out = kinloop(&["check", &four_bar]);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains("a [length unit] (no value)"));
    // Synthesis: the varied parameters take the values of the search, the others need one.
    let coupler = dir.join("coupler.kl");
    let text = std::fs::read_to_string(shipped("coupler_four_bar.kl")).expect("read");
    std::fs::write(&coupler, text.replacen("a = 1.0, b = 3.0, c = 2.5", "a, b, c", 1)).expect("write");
    let targets = dir.join("points.csv");
    let points = "0.9661,1.4940\n1.2330,2.2071\n0.6814,2.4363\n-0.0985,2.1152\n-0.6145,1.4192\n-0.6820,0.7191\n";
    std::fs::write(&targets, points).expect("write");
    let (coupler, targets) = (coupler.display().to_string(), targets.display().to_string());
    let synth = ["synth", &coupler, "--targets", &targets, "--path", "p", "--starts", "2", "--jobs", "1"];
    let out = kinloop(&[&synth[..], &["--vary", "a=0.8..1.4,b=2..3.5"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("parameter `c` has no value") && err.contains("--params c="), "{err}");
    assert!(!err.contains("`a`") && !err.contains("`b`"), "the varied ones need no value: {err}");
    let out = kinloop(&[&synth[..], &["--vary", "a=0.8..1.4,b=2..3.5", "--params", "c=2.5"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(matches!(out.status.code(), Some(0 | 1)), "{err}");
    assert!(err.contains("2 starts"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Standard error that cannot be written (`kinloop ... 2>&1 | head -1`, the reader gone) does
/// not panic: the exit code is the command's own, here a usage error (2) and a success whose
/// notes go to standard error (0).
#[test]
fn standard_error_that_cannot_be_written_is_no_panic() {
    let runs: [(&[&str], i32); 3] = [
        (&["sweep", &shipped("four_bar.kl"), "--from", "0", "--to", "1", "--params", "a=1,zz=2"], 2),
        (&["dynamics", &shipped("engine.kl"), "--speed", "150", "--samples", "8"], 0),
        (&["check", &shipped("nonexistent.kl")], 66),
    ];
    for (args, code) in runs {
        // A pipe whose reader is closed before the command starts: every write to it fails.
        let (reader, writer) = std::io::pipe().expect("a pipe");
        drop(reader);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_kinloop"))
            .args(args)
            .stderr(writer)
            .output()
            .expect("the kinloop binary runs");
        assert_eq!(out.status.code(), Some(code), "{args:?}");
    }
}

/// Every command is described in `kinloop --help` by its own words: `extremes` by its
/// extremes, `cam` by its cam alone.
#[test]
fn each_command_has_its_own_description() {
    let out = kinloop(&["--help"]);
    let help = String::from_utf8_lossy(&out.stdout);
    let line = |command: &str| {
        help.lines()
            .find(|l| l.trim_start().starts_with(&format!("{command} ")))
            .unwrap_or_else(|| panic!("no {command} in {help}"))
            .to_string()
    };
    assert!(line("extremes").contains("smallest and largest value"), "{help}");
    let cam = line("cam");
    assert!(cam.contains("disc cam") && !cam.contains("smallest and largest"), "{cam}");
    for command in ["check", "solve", "sweep", "trace", "dynamics", "simulate", "animate", "synth"] {
        assert!(line(command).len() > command.len() + 20, "{command} has no description: {help}");
    }
    // A summary a line each, as a terminal shows it (the whole description is under `kinloop
    // help COMMAND`): each command's first paragraph was its summary, up to 900 characters on
    // one line (`trace`).
    for command in ["check", "solve", "sweep", "trace", "dynamics", "simulate", "cam", "extremes", "animate", "synth"] {
        assert!(line(command).chars().count() <= 100, "{command}'s summary is longer than a line: {}", line(command));
    }
    let long = kinloop(&["help", "trace"]);
    assert!(String::from_utf8_lossy(&long.stdout).contains("pseudo-arclength continuation"), "the whole description");
}

/// A closed standard output (`kinloop ... >&-`) is exit 74 with a message, for every command
/// that writes there and for the help and the version: std's writes to it succeed and write
/// nothing, so without the check at start-up the whole output is lost with exit code 0. A
/// command that writes to a file alone (`animate`) runs.
#[cfg(unix)]
#[test]
fn a_closed_standard_output_is_exit_74() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    let targets = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("closed_targets.csv");
    std::fs::write(&targets, "0,90\n90,80\n180,100\n").expect("write the targets");
    let targets = targets.display().to_string();
    let coupler = shipped("coupler_four_bar.kl");
    let engine = shipped("engine.kl");
    let sweep = ["sweep", &four_bar, "--params", params, "--from", "0", "--to", "360", "--deg"];
    let runs: [&[&str]; 13] = [
        &sweep,
        &["check", &four_bar],
        &["solve", &four_bar, "--params", params, "--at", "0"],
        &["trace", &four_bar, "--params", params, "--from", "0", "--to", "1"],
        &["extremes", &four_bar, "--params", params, "--from", "0", "--to", "1"],
        &["synth", &coupler, "--targets", &targets, "--function", "phi:gamma", "--vary", "a=0.8..1.4", "--deg"],
        &["cam", &shipped("dwell_cam.kl"), "--point", "follower", "--guide", "0,1", "--samples", "37"],
        &["dynamics", &engine, "--speed", "150", "--samples", "8"],
        &["simulate", &engine, "--speed", "150", "--time", "0.01", "--samples", "3"],
        &["--help"],
        &["--version"],
        &["help", "sweep"],
        &["sweep", "--help"],
    ];
    // Through the shell, which closes descriptor 1 before it starts the binary.
    let closed = |args: &[&str]| {
        std::process::Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$0" "$@" >&-"#)
            .arg(env!("CARGO_BIN_EXE_kinloop"))
            .args(args)
            .output()
            .expect("sh runs")
    };
    for args in runs {
        let out = closed(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(74), "{args:?}: {err}");
        assert!(err.contains("error: cannot write") && err.contains("standard output is closed"), "{args:?}: {err}");
    }
    let svg = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("closed_animate.svg");
    let svg = svg.display().to_string();
    let out = closed(&["animate", &four_bar, "--params", params, "--from", "0", "--to", "1", "--out", &svg]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(std::fs::read_to_string(&svg).expect("the animation").contains("<svg"));
}

/// The analogs by an input whose kind is not inferred (a time) say the unit of their quantity,
/// per the input's unit: with `--deg` an angle's are 57.3 times its radians', and the headers
/// tell the two apart (they were both `d(psi)/d(t)`), in `solve` and in `sweep`.
#[test]
fn analogs_by_an_input_without_a_unit_say_their_quantitys() {
    let path = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("time_input.kl");
    let text = "pub struct TimeDriven { params v=2.0, r=1.0, l=3.0; input t; unknowns psi=0, phi=0; let s = v*t; \
                loop a: (s,0) + l@psi == r@phi; point p = r@phi; }";
    std::fs::write(&path, text).expect("write the declaration");
    let file = path.display().to_string();
    let (rad, rows_rad) = csv(&kinloop(&["solve", &file, "--at", "-1.5"]));
    let (deg, rows_deg) = csv(&kinloop(&["solve", &file, "--at", "-1.5", "--deg"]));
    let at = |header: &[String], name: &str| header.iter().position(|h| h.starts_with(&format!("{name} ["))).unwrap();
    let named = |header: &[String], name: &str| header[at(header, name)].clone();
    assert_eq!(named(&rad, "t"), "t [unit of t]");
    assert_eq!(named(&rad, "d(psi)/d(t)"), "d(psi)/d(t) [rad/unit of t]");
    assert_eq!(named(&deg, "d(psi)/d(t)"), "d(psi)/d(t) [deg/unit of t]");
    assert_eq!(named(&rad, "d2(phi)/d(t)^2"), "d2(phi)/d(t)^2 [rad/(unit of t)^2]");
    assert_eq!(named(&deg, "d2(phi)/d(t)^2"), "d2(phi)/d(t)^2 [deg/(unit of t)^2]");
    assert_eq!(named(&deg, "d(p.x)/d(t)"), "d(p.x)/d(t) [length unit/unit of t]");
    let k = at(&rad, "d(psi)/d(t)");
    assert!((rows_deg[0][k] - rows_rad[0][k].to_degrees()).abs() < 1e-12);
    let (sweep, _) = csv(&kinloop(&["sweep", &file, "--from", "-1.5", "--to", "-1.25", "--samples", "3", "--deg"]));
    assert_eq!(sweep, deg);
}

/// The macro's messages that speak of its invocation or of the Rust it generates are said for
/// a declaration read from a file, and a block too large for the run-time evaluator says what
/// to write instead.
#[test]
fn messages_about_the_macro_are_said_for_a_file() {
    let write = |name: &str, text: &str| {
        let path = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
        std::fs::write(&path, text).expect("write the declaration");
        path.display().to_string()
    };
    let one = |name: &str| format!("pub struct {name} {{ input phi; unknowns x=0; eq e: x == phi; }}\n");
    let check = |file: &str, code: i32| {
        let out = kinloop(&["check", file]);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(code), "{err}");
        err
    };
    let err = check(&write("two_structs.kl", &format!("{}{}", one("A"), one("B"))), 65);
    assert!(err.contains("a `.kl` file) holds one mechanism: put each in a file of its own"), "{err}");
    assert!(!err.contains("per `mechanism!`"), "{err}");
    let err = check(&write("named_t.kl", &one("T")), 65);
    assert!(err.contains("`mechanism!` uses it for the type parameter of the Rust types it generates"), "{err}");
    assert!(!err.contains("NameInputs"), "{err}");
    for (name, says) in [("f64", "a primitive type that the Rust code"), ("kinloop", "a crate that the Rust code")] {
        let err = check(&write(&format!("named_{name}.kl"), &one(name)), 65);
        assert!(err.contains(says) && err.contains("would not compile there"), "{err}");
        assert!(!err.contains("the generated code"), "{err}");
    }
    // Seventeen unknowns in one block (`dense` puts them there): one more than the evaluator's.
    let unknowns: Vec<String> = (1..=17).map(|i| format!("x{i}=0")).collect();
    let eqs: Vec<String> = (2..=17).map(|i| format!("eq e{i}: x{i} == x{} * x{} + phi;", i - 1, i - 1)).collect();
    let big = format!(
        "#[kinloop(dense)]\npub struct Big {{ input phi; unknowns {}; eq e1: x1 == phi; {} }}\n",
        unknowns.join(", "),
        eqs.join(" ")
    );
    let err = check(&write("seventeen.kl", &big), 69);
    assert!(err.contains("block 0 has 17 unknowns") && err.contains("leave out `#[kinloop(dense)]`"), "{err}");
    // `check` still reports the structure that shows the block.
    let out = kinloop(&["check", &write("seventeen.kl", &big)]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("block 0 (Newton, 17x17)"), "{out:?}");
    assert!(err.contains("17 unknowns solved together by dense Newton"), "{err}");
    assert!(err.contains("compile the declaration with `kinloop::mechanism!`"), "{err}");
    // A linear block of as many is named as `check` names it, one linear system (it was said
    // to be solved by dense Newton).
    let eqs: Vec<String> = (2..=17).map(|i| format!("eq e{i}: x{i} == x{} + phi;", i - 1)).collect();
    let linear = format!(
        "#[kinloop(dense)]\npub struct Big {{ input phi; unknowns {}; eq e1: x1 == phi; {} }}\n",
        unknowns.join(", "),
        eqs.join(" ")
    );
    let err = check(&write("seventeen_linear.kl", &linear), 69);
    assert!(err.contains("block 0 has 17 unknowns solved together as one linear system"), "{err}");
    let out = kinloop(&["check", &write("seventeen_linear.kl", &linear)]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("block 0 (linear, 17x17)"), "{out:?}");
}

/// A sweep far out, where the input's doubles are coarser than its steps, is the arguments'
/// mistake (exit code 2, as a range too long). With `--deg` the degrees as given are refused
/// before: so far out they do not convert to radians to a solve's precision.
#[test]
fn an_input_too_coarse_is_a_usage_error_in_the_units_given() {
    let four_bar = shipped("four_bar.kl");
    let args = ["sweep", &four_bar, "--params", "a=1,b=3,c=2.5,d=3.2", "--from", "1e17", "--to", "1.00000000001e17"];
    let out = kinloop(&[&args[..], &["--samples", "3", "--deg"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("--from 1e17: 1e17 degrees are too many turns out") && !err.contains("e15"), "{err}");
    let out = kinloop(&[&args[..], &["--samples", "3"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    // In radians the range lies farther out (1e17 rad): doubles 16 apart.
    assert!(err.contains("is a double 16 apart"), "{err}");
    // A usage error before anything is written: the header and the first row were, and an
    // `--events` file was made.
    assert!(out.stdout.is_empty(), "{}", String::from_utf8_lossy(&out.stdout));
    let events = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("coarse-events-{}.csv", std::process::id()));
    let out = kinloop(&[&args[..], &["--samples", "3", "--events", events.to_str().unwrap()]].concat());
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stdout.is_empty() && !events.exists());
}

/// A file to write that is the declaration read (by its own path, a symbolic link or a hard
/// link) is refused as a usage error before anything is written: `--flywheel engine.kl`
/// replaced the declaration with the flywheel's CSV, and `--out`, `--plot` and `--events` did
/// the same with their output.
#[cfg(unix)]
#[test]
fn an_output_that_is_the_declaration_read_is_refused() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("own-output-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    const FOUR_BAR: &str = "a=1,b=3,c=2.5,d=3.2";
    let cases: [(&str, &[&str], &str); 5] = [
        ("engine.kl", &["dynamics", "--speed", "150"], "--flywheel"),
        ("dwell_cam.kl", &["cam", "--point", "follower", "--guide", "0,1"], "--plot"),
        ("four_bar.kl", &["animate", "--from", "0", "--to", "1", "--samples", "5", "--params", FOUR_BAR], "--out"),
        ("four_bar.kl", &["sweep", "--from", "0", "--to", "1", "--params", FOUR_BAR], "--events"),
        ("four_bar.kl", &["trace", "--from", "0", "--to", "1", "--params", FOUR_BAR], "--events"),
    ];
    for (name, args, option) in cases {
        let decl = dir.join(name);
        std::fs::copy(shipped(name), &decl).unwrap();
        let text = std::fs::read_to_string(&decl).unwrap();
        let (soft, hard) = (dir.join(format!("soft-{name}")), dir.join(format!("hard-{name}")));
        let _ = (std::fs::remove_file(&soft), std::fs::remove_file(&hard));
        std::os::unix::fs::symlink(&decl, &soft).unwrap();
        std::fs::hard_link(&decl, &hard).unwrap();
        for target in [&decl, &soft, &hard] {
            let mut full = vec![args[0], decl.to_str().unwrap()];
            full.extend(&args[1..]);
            full.extend([option, target.to_str().unwrap()]);
            let out = kinloop(&full);
            let e = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{full:?}: {e}");
            assert!(e.contains(&format!("{option} {} is the file read", target.display())), "{e}");
            assert!(out.stdout.is_empty(), "{full:?} wrote output");
            assert_eq!(std::fs::read_to_string(&decl).unwrap(), text, "{full:?} changed the declaration");
        }
        // Another file is written as before.
        let other = dir.join(format!("out{option}.svg"));
        let mut full = vec![args[0], decl.to_str().unwrap()];
        full.extend(&args[1..]);
        full.extend([option, other.to_str().unwrap()]);
        let out = kinloop(&full);
        assert_eq!(out.status.code(), Some(0), "{full:?}: {}", String::from_utf8_lossy(&out.stderr));
        assert!(std::fs::metadata(&other).unwrap().len() > 0, "{full:?} wrote nothing");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A file to write that standard output is redirected to (`--events out.csv > out.csv`, or the
/// same file by a link) is refused as a usage error before anything is written: the table went
/// to standard output and the events over it, from the file's start, and the command succeeded
/// with three lines of events left of a table of 1321 rows.
#[cfg(unix)]
#[test]
fn an_output_that_is_the_redirected_standard_output_is_refused() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("stdout-output-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    const FOUR_BAR: &str = "a=3,b=2,c=2.5,d=4";
    let four_bar = shipped("four_bar.kl");
    let cases: [(&[&str], &str, &str); 3] = [
        (&["trace", &four_bar, "--from", "0", "--to", "180", "--deg", "--params", FOUR_BAR], "--events", "csv"),
        (&["sweep", &four_bar, "--from", "0", "--to", "1", "--params", FOUR_BAR], "--events", "csv"),
        (&["cam", &shipped("dwell_cam.kl"), "--point", "follower", "--guide", "0,1"], "--plot", "svg"),
    ];
    for (args, option, ext) in cases {
        let same = dir.join(format!("same.{ext}"));
        let link = dir.join(format!("link.{ext}"));
        for target in [&same, &link] {
            let _ = (std::fs::remove_file(&same), std::fs::remove_file(&link));
            let stdout = std::fs::File::create(&same).unwrap();
            std::os::unix::fs::symlink(&same, &link).unwrap();
            let mut full = args.to_vec();
            full.extend([option, target.to_str().unwrap()]);
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_kinloop"))
                .args(&full)
                .stdout(stdout)
                .output()
                .expect("the kinloop binary runs");
            let e = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{full:?}: {e}");
            let said = format!("{option} {} is the file standard output is redirected to", target.display());
            assert!(e.contains(&said), "{e}");
            assert_eq!(std::fs::metadata(&same).unwrap().len(), 0, "{full:?} wrote into the file");
        }
        // Standard output redirected to another file: both are written, whole.
        let (table, side) = (dir.join("table.out"), dir.join(format!("side.{ext}")));
        let mut full = args.to_vec();
        full.extend([option, side.to_str().unwrap()]);
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_kinloop"))
            .args(&full)
            .stdout(std::fs::File::create(&table).unwrap())
            .output()
            .expect("the kinloop binary runs");
        assert_eq!(out.status.code(), Some(0), "{full:?}: {}", String::from_utf8_lossy(&out.stderr));
        assert!(std::fs::metadata(&side).unwrap().len() > 0, "{full:?} wrote no {option} file");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--singular-pivot` sets the smallest pivot ratio the commands that sweep accept: a slotted
/// rocker whose slide passes 1e-8 of the crank's radius from the pivot stops a default sweep
/// with the advice to lower it (and the option that does), and lowered, the sweep completes and
/// `extremes` finds the slide's shortest length, `h - r`, where the crank points away from the
/// pivot (`phi = 3 pi / 2`).
#[test]
fn singular_pivot_lets_a_slide_brush_its_pivot() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let file = dir.join(format!("rocker-{}.kl", std::process::id()));
    std::fs::write(
        &file,
        "pub struct SlottedRocker {
            params h = 1.00000001, r = 1;
            input phi;
            unknowns s = 2, theta = 1.5;
            loop slot: (0, h) + r @ phi == s @ theta;
        }",
    )
    .unwrap();
    let f = file.to_str().unwrap();
    let sweep = ["sweep", f, "--from", "0", "--to", "6.283", "--samples", "73"];
    let stopped = kinloop(&sweep);
    let e = String::from_utf8_lossy(&stopped.stderr);
    assert_eq!(stopped.status.code(), Some(1), "{e}");
    assert!(e.contains("lower `singular_pivot`") && e.contains("`--singular-pivot RATIO` lowers it"), "{e}");
    let (_, rows) = csv(&kinloop(&[&sweep[..], &["--singular-pivot", "1e-12"]].concat()));
    assert_eq!(rows.len(), 73);
    let out = kinloop(&["extremes", f, "--from", "0", "--to", "6.283", "--columns", "s", "--singular-pivot", "1e-12"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let row: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
    let (min, at): (f64, f64) = (row[2].parse().unwrap(), row[3].parse().unwrap());
    assert!((min - 1e-8).abs() <= 1e-15, "{text}");
    assert!((at - 1.5 * std::f64::consts::PI).abs() <= 1e-6, "{text}");
    // Each written as numbers are elsewhere (1e308 was written in 309 digits, -1e-9 as
    // -0.000000001).
    for (bad, written) in [("1", "1"), ("-1e-9", "-1e-9"), ("NaN", "NaN"), ("1e308", "1e308"), ("-1e300", "-1e300")] {
        let out = kinloop(&[&sweep[..], &["--singular-pivot", bad]].concat());
        let e = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{bad}: {e}");
        assert!(e.contains(&format!("--singular-pivot {written} must be at least 0 and below 1")), "{e}");
    }
    // Commands that do not sweep take no such option.
    let out = kinloop(&["solve", f, "--at", "1", "--singular-pivot", "1e-12"]);
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_file(&file).unwrap();
}

/// A sweep from a change point (a parallelogram four-bar at 0) with `--singular-pivot 0`: the
/// solve of its first state finds it singular, and the message says so, not that a pivot ratio
/// of 0 is "below `SweepConfig::singular_pivot`, 0e0".
#[test]
fn a_singular_start_below_no_threshold_says_what_found_it() {
    let four_bar = shipped("four_bar.kl");
    let sweep = ["sweep", &four_bar, "--params", "a=1,b=3,c=1,d=3", "--from", "0", "--to", "90", "--deg"];
    for (pivot, says) in [
        ("0", "(a pivot ratio of 0.00e0, where the solve of its first state finds the Jacobian singular"),
        ("1e-6", "(a pivot ratio of 0.00e0, below `SweepConfig::singular_pivot`, 1e-6)"),
    ] {
        let out = kinloop(&[&sweep[..], &["--singular-pivot", pivot]].concat());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{pivot}: {err}");
        assert!(err.contains("error: the sweep starts at a singular position"), "{pivot}: {err}");
        assert!(err.contains(says), "{pivot}: `{says}` missing: {err}");
        // The library's setting named in the first case is mapped to the option, once.
        let mapped = "note: `SweepConfig::singular_pivot` is `--singular-pivot RATIO` on the command line";
        assert_eq!(err.matches(mapped).count(), usize::from(pivot == "1e-6"), "{pivot}: {err}");
    }
}

/// `check` writes the parameters' values as numbers are written elsewhere: `--params
/// r=1e-300,l=1e308` were written in some three hundred digits each.
#[test]
fn check_writes_huge_and_tiny_parameters_briefly() {
    let out =
        kinloop(&["check", &shipped("engine.kl"), "--params", "r=1e-300,l=1e308,e=123456789012345678901234567890"]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let written = "parameters: r [length unit] = 1e-300, l [length unit] = 1e308, e [length unit] = 1.2345678901234568e29, \
                   m_crank = 1.2";
    assert!(report.contains(written), "{report}");
}

/// `check` writes each parameter with its unit, as it writes the inputs, unknowns and outputs
/// (`phi1 [rad]`): an angle parameter in radians, a length in the unit of length, and a
/// parameter of no kind the names infer (a mass) bare. It wrote the names alone, so that
/// `gamma = 0.7` could be read as degrees beside `--deg` commands.
#[test]
fn check_writes_each_parameter_with_its_unit() {
    let out = kinloop(&["check", &shipped("rhombic_drive.kl")]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(report.contains("parameters: r_p [length unit] = 1, r_b [length unit] = 1.2,"), "{report}");
    assert!(report.contains(", gamma [rad] = 0.7,"), "{report}");
}

/// A guess too many turns out says how many in a few digits: `beta = 1e308` was "159154943...
/// turns out" in 308 digits; a billion radians keeps its whole count.
#[test]
fn a_guess_too_many_turns_out_counts_them_briefly() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("far-guess-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a directory");
    let text = std::fs::read_to_string(shipped("four_bar.kl")).expect("the four-bar");
    for (guess, says) in [("1e308", "is 1e308 rad, 1.592e307 turns out,"), ("1e10", ", 1591549431 turns out,")] {
        let file = dir.join(format!("guess_{guess}.kl"));
        std::fs::write(&file, text.replacen("beta = 0.5", &format!("beta = {guess}"), 1)).expect("write");
        let out = kinloop(&["solve", file.to_str().unwrap(), "--params", "a=1,b=3,c=2.5,d=3.2", "--at", "1"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(err.contains(says) && !err.contains("0000000000"), "{guess}: `{says}` missing: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A name given with spaces around it (`--point " follower"`, pasted with its space) is the
/// name, as a number with spaces around it is the number (`--roller " 10"`): it was "no point
/// of that name" while the message listed `follower` among the points.
#[test]
fn names_with_spaces_around_them_are_the_names() {
    let cam = shipped("dwell_cam.kl");
    let four_bar = shipped("four_bar.kl");
    let page = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("spaced_names.html");
    let page = page.display().to_string();
    let svg = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("spaced_names.svg");
    let svg = svg.display().to_string();
    let targets = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("spaced_names.csv");
    std::fs::write(&targets, "0.97,1.49\n1.12,2.34\n0.15,2.28\n-0.61,1.42\n").expect("write the targets");
    let targets = targets.display().to_string();
    let coupler = shipped("coupler_four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    let runs: [&[&str]; 4] = [
        &["cam", &cam, "--point", " follower ", "--guide", " 0, 1", "--roller", " 10", "--samples", "37"],
        &["animate", &four_bar, "--params", params, "--from", "0", "--to", "1", "--out", &page, "--show", " beta"],
        &["animate", &cam, "--from", "0", "--to", "6.3", "--cam", "follower\t", "--guide", "0,1", "--out", &svg],
        &["synth", &coupler, "--targets", &targets, "--path", " p", "--vary", "a=0.8..1.4", "--starts", "2"],
    ];
    for args in runs {
        let out = kinloop(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {err}");
    }
    // The same name twice, once with spaces, is named twice.
    let out = kinloop(&[
        "animate", &four_bar, "--params", params, "--from", "0", "--to", "1", "--out", &page, "--show", "beta",
        "--show", "beta ",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("--show beta is given twice"), "{err}");
    for file in [&page, &svg, &targets] {
        let _ = std::fs::remove_file(file);
    }
}

/// A value that is zero is written `0` in every CSV, whatever sign the arithmetic left on it:
/// the in-line slider-crank at its inner dead centre (`e = 0`, `phi = 0`) has by hand
/// `x' = -r sin(phi) (1 + r cos(phi) / sqrt(l^2 - r^2 sin^2(phi))) = 0` and
/// `psi'' = 0` (`sin(psi) = r sin(phi) / l`, whose second derivative carries `sin(phi)`), which
/// were written `-0`; and an engine without loads has a mean torque of 0, written `0` on
/// standard error and `-0` into `--flywheel`.
#[test]
fn a_zero_is_written_without_a_sign() {
    let slider = shipped("slider_crank.kl");
    let params = "r=1,l=3,e=0";
    let tmp = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let flywheel = tmp.join("unsigned_zero_flywheel.csv").display().to_string();
    let events = tmp.join("unsigned_zero_events.csv").display().to_string();
    let engine = shipped("engine.kl");
    let unloaded = "p0=0,c=0,t_load=0,g=0,e=0";
    let runs: [&[&str]; 5] = [
        &[
            "sweep",
            &slider,
            "--params",
            params,
            "--from",
            "0",
            "--to",
            "360",
            "--deg",
            "--samples",
            "9",
            "--events",
            &events,
        ],
        &["solve", &slider, "--params", params, "--at", "0", "--deg"],
        &["trace", &slider, "--params", params, "--from", "0", "--to", "90", "--deg", "--max-points", "3"],
        &["extremes", &slider, "--params", params, "--from", "-90", "--to", "90", "--deg", "--columns", "psi"],
        &["dynamics", &engine, "--params", unloaded, "--speed", "150", "--samples", "8", "--flywheel", &flywheel],
    ];
    for args in runs {
        let out = kinloop(args);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        let signed =
            |text: &str| text.lines().flat_map(|l| l.split(',')).any(|f| f.parse() == Ok(0.0) && f.starts_with('-'));
        assert!(!signed(&text), "{args:?}: {text}");
        let _ = std::fs::remove_file(&events);
    }
    // The zeros by hand are there, written `0`.
    let out = kinloop(runs[1]);
    let (header, rows) = csv(&out);
    let at = |name: &str| header.iter().position(|h| h.starts_with(name)).expect(name);
    let line = String::from_utf8_lossy(&out.stdout).lines().nth(1).expect("a row").to_string();
    let fields: Vec<&str> = line.split(',').collect();
    for column in ["d(x)/d(phi)", "d2(psi)/d(phi)^2"] {
        assert_eq!(rows[0][at(column)], 0.0, "{line}");
        assert_eq!(fields[at(column)], "0", "{column}: {line}");
    }
    let written = std::fs::read_to_string(&flywheel).expect("the flywheel file");
    let _ = std::fs::remove_file(&flywheel);
    let values: Vec<&str> = written.lines().nth(1).expect("a row").split(',').collect();
    assert_eq!(values[1], "0", "mean_torque: {written}");
}

/// A sweep whose start cannot be solved (the frame longer than the other three links together:
/// no assembly at any angle) writes no table, as `trace` and `extremes` write none: it wrote
/// the header of a table of no rows, then failed. The reason is on standard error, and no
/// `--events` file is left behind.
#[test]
fn a_sweep_that_cannot_start_writes_no_table() {
    let four_bar = shipped("four_bar.kl");
    let events = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("no-start-events.csv");
    std::fs::remove_file(&events).ok();
    let events = events.display().to_string();
    let unreachable = ["--params", "a=1,b=3,c=2.5,d=10", "--from", "0", "--to", "90", "--deg"];
    for extra in [&["sweep", "--samples", "3", "--events", &events][..], &["trace", "--events", &events], &["extremes"]]
    {
        let out = kinloop(&[&extra[..1], &[four_bar.as_str()], &unreachable, &extra[1..]].concat());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{extra:?}: {err}");
        assert!(err.contains("cannot be assembled") && err.contains("at phi = 0 "), "{extra:?}: {err}");
        assert_eq!(String::from_utf8_lossy(&out.stdout), "", "{extra:?}: a table of no rows");
        assert!(!std::path::Path::new(&events).exists(), "{extra:?}: an events file was left");
    }
}

/// An event's angles in degrees are written as the error that stops the sweep there writes
/// them, and as `solve` and `trace` write angles: the shortest decimal that reads back to the
/// radians. The limit position of the four-bar `a=2.7, b=2, c=2.5, d=4` (crank and frame
/// closing the triangle of side `b + c`: `cos phi = (a^2 + d^2 - (b + c)^2) / (2 a d)`,
/// `phi = 81.909288022687850198 deg` to 20 digits) was listed as `81.90928802268786` (its
/// radians times `180/pi`, a unit in the last place up) and stopped the sweep "at phi =
/// 81.90928802268785": one position, two numbers.
#[test]
fn an_event_is_written_in_degrees_as_the_error_at_it_is() {
    let four_bar = shipped("four_bar.kl");
    let file = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("limit-events.csv");
    let file_arg = file.display().to_string();
    let args = ["sweep", &four_bar, "--params", "a=2.7,b=2,c=2.5,d=4", "--from", "0", "--to", "180", "--deg"];
    let number_after = |text: &str, key: &str| -> String {
        let at = text.find(key).unwrap_or_else(|| panic!("`{key}` in {text}")) + key.len();
        text[at..].chars().take_while(|c| c.is_ascii_digit() || *c == '.').collect()
    };
    let out = kinloop(&args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let listed = number_after(&err, "event: limit position at phi = ");
    let stopped = number_after(&err, "stopped at a limit position in `FourBar` at phi = ");
    assert_eq!(listed, stopped, "{err}");
    let out = kinloop(&[&args[..], &["--events", &file_arg]].concat());
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    let events = std::fs::read_to_string(&file).expect("the events file");
    let row = events.lines().nth(1).expect("one event");
    let written = row.split(',').nth(2).expect("phi");
    assert_eq!(written, listed, "{events}");
    // The position itself, to well within the sweep's location of a limit position (to the
    // rounding of the input, about 1e-14 deg here; 1e-9 deg leaves room for another path to it).
    let phi: f64 = listed.parse().expect("a number");
    assert!((phi - 81.909_288_022_687_85).abs() <= 1e-9, "{phi}");
    std::fs::remove_file(&file).ok();
}

/// A sweep's inputs in degrees are the decimals between the ends as given, the ends
/// themselves among them: `--from 0.7` was written `0.6999999999999998`, `--to 360.1`
/// `360.1000000000001`, the sample at 30.1 `30.100000000000005` (the doubles' interpolation,
/// rounded four times). Each is the double of the decimal it stands for (written with one
/// decimal, read back: an independent parse).
#[test]
fn a_sweep_writes_the_decimals_between_its_ends() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    for (from, to, samples, step) in [("0.7", "1.3", 7, 0.1), ("0.1", "360.1", 13, 30.0), ("-33.3", "77.7", 112, 1.0)] {
        let args = ["sweep", &four_bar, "--params", params, "--from", from, "--to", to, "--deg"];
        let (_, rows) = csv(&kinloop(&[&args[..], &["--samples", &samples.to_string()]].concat()));
        let start: f64 = from.parse().expect("a number");
        for (k, row) in rows.iter().enumerate() {
            let want: f64 = format!("{:.1}", start + step * k as f64).parse().expect("a number");
            assert_eq!(row[0], want, "{from}..{to}, sample {k}");
        }
        assert_eq!(rows.len(), samples);
    }
}

/// So are its inputs in the model's units, radians or lengths, of one input or several: they
/// were written as solved, the doubles' own steps (`0.44999999999999996` between 0.3 and 0.6,
/// `0.6000000000000001`, `--to 0.9` itself as `0.9000000000000001`), where the same sweep in
/// degrees wrote its decimals.
#[test]
fn a_sweep_in_radians_writes_the_decimals_between_its_ends() {
    let (five_bar, four_bar) = (shipped("five_bar.kl"), shipped("four_bar.kl"));
    let params = ["--params", "a=1,b=3,c=2.5,d=3.2"];
    let runs: [(&[&str], &str, &str, &[f64]); 2] = [
        (&[&five_bar], "0.3,0.3", "0.6,0.9", &[0.075, 0.15]),
        (&[&four_bar, params[0], params[1]], "0.3", "0.9", &[0.15]),
    ];
    for (file, from, to, steps) in runs {
        let args = [&["sweep"], file, &["--from", from, "--to", to, "--samples", "5"]].concat();
        let (_, rows) = csv(&kinloop(&args));
        assert_eq!(rows.len(), 5);
        let starts: Vec<f64> = from.split(',').map(|v| v.parse().expect("a number")).collect();
        for (k, row) in rows.iter().enumerate() {
            for (i, (start, step)) in starts.iter().zip(steps).enumerate() {
                // The decimal the sample stands for, read back: an independent parse.
                let want: f64 = format!("{:.3}", start + step * k as f64).parse().expect("a number");
                assert_eq!(row[i], want, "{from}..{to}, sample {k}, input {i}");
            }
        }
    }
}

/// Every subcommand that solves the mechanism, run where the loops' lengths are all zero (the
/// shipped mechanisms with their lengths given as 0, as a parameter left unset is) from the
/// input `at` (`30` for the four-bar's and the engine's, and the five-bar's `10,20` for
/// `animate --grid`; in degrees where `deg` is set), with the input's location as the error
/// names it: `phi = 30` (or `th1 = 10, th2 = 20` for the five-bar).
fn on_zero_loops(at: [&str; 2], deg: bool) -> Vec<(Vec<String>, String)> {
    let (four_bar, five_bar, engine, cam) =
        (shipped("four_bar.kl"), shipped("five_bar.kl"), shipped("engine.kl"), shipped("dwell_cam.kl"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let (svg, html) =
        (out.join("zero_loop.svg").display().to_string(), out.join("zero_loop.html").display().to_string());
    let [at, next] = at;
    let zero = ["--params", "a=0,b=0,c=0,d=0"];
    let engine_zero = ["--params", "r=0,l=0,e=0"];
    let runs: Vec<Vec<&str>> = vec![
        [&["solve", &four_bar], &zero[..], &["--at", at]].concat(),
        [&["sweep", &four_bar], &zero[..], &["--from", at, "--to", next]].concat(),
        [&["trace", &four_bar], &zero[..], &["--from", at, "--to", next]].concat(),
        [&["extremes", &four_bar], &zero[..], &["--from", at, "--to", next]].concat(),
        [&["animate", &four_bar], &zero[..], &["--from", at, "--to", next, "--out", &svg]].concat(),
        [&["dynamics", &engine], &engine_zero[..], &["--speed", "150", "--start", at]].concat(),
        [&["simulate", &engine], &engine_zero[..], &["--speed", "150", "--time", "0.01", "--start", at]].concat(),
        vec!["cam", &cam, "--point", "follower", "--guide", "0,1", "--roller", "10", "--start", at, "--params"],
    ];
    let mut runs: Vec<(Vec<String>, String)> =
        runs.into_iter().map(|run| (run.into_iter().map(str::to_string).collect(), format!("phi = {at} "))).collect();
    // The cam's rod and rocker of length zero on a pivot at the origin.
    runs.last_mut().expect("the cam's run").0.push("l_rod=0,c=0,d_x=0,d_y=0".into());
    let (from, to) = if deg { ("10,20", "30,40") } else { ("0.1,0.2", "0.3,0.4") };
    let grid = ["animate", &five_bar, "--grid", "--from", from, "--to", to, "--samples", "3,3", "--out", &html];
    let grid = [&grid[..], &["--params", "a=0,b=0,c=0,d=0,e=0"]].concat();
    let (th1, th2) = from.split_once(',').expect("two inputs");
    runs.push((grid.into_iter().map(str::to_string).collect(), format!("th1 = {th1}, th2 = {th2} ")));
    if deg {
        for (args, _) in &mut runs {
            args.push("--deg".into());
        }
    }
    runs
}

/// The error of a loop whose lengths are all zero (`Error::InvalidArgument`, whose text names
/// where it was found: it carries no location to convert) names the input as given, in degrees
/// with `--deg`, under every subcommand: it was written in the radians solved at (`phi =
/// 0.5235987755982988` of the 30 typed), where every other error's location is converted.
#[test]
fn a_loop_whose_lengths_are_all_zero_is_located_in_the_units_given() {
    for (deg, at) in [(true, ["30", "60"]), (false, ["0.5", "1"])] {
        for (args, located) in on_zero_loops(at, deg) {
            let out = kinloop(&args.iter().map(String::as_str).collect::<Vec<_>>());
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{args:?}: {err}");
            assert!(err.contains("all have length zero"), "{args:?}: {err}");
            assert!(err.contains(&format!("at {located}")), "{args:?}: {err}");
            // Not the radians of 30, 10 or 20 degrees.
            for radians in ["0.5235987755982988", "0.17453292519943295", "0.3490658503988659"] {
                assert!(!err.contains(radians), "{args:?}: {err}");
            }
        }
    }
}

/// The error of a loop whose lengths are all zero names the mechanism, and where it was solved,
/// once under every subcommand: the runtime writes the location into the error's text, and the
/// command line led the text with the mechanism again (`solve` with the inputs as given too:
/// "FourBar at 30: ... in `FourBar` at phi = 30").
#[test]
fn a_loop_whose_lengths_are_all_zero_names_the_mechanism_once() {
    for (deg, at) in [(true, ["30", "60"]), (false, ["0.5", "1"])] {
        for (args, located) in on_zero_loops(at, deg) {
            let out = kinloop(&args.iter().map(String::as_str).collect::<Vec<_>>());
            let err = String::from_utf8_lossy(&out.stderr);
            let line = err.lines().find(|l| l.starts_with("error:")).expect("an error line");
            let mechanism = line.split("in `").nth(1).and_then(|r| r.split('`').next()).expect("the location");
            assert_eq!(line.matches(mechanism).count(), 1, "{args:?}: {line}");
            assert_eq!(line.matches(&format!("at {located}")).count(), 1, "{args:?}: {line}");
        }
    }
}

/// A loop whose lengths are all zero is a usage error (exit code 2: the parameters are at
/// fault, as a parameter without a value is) under every subcommand that solves, in degrees
/// or not: `solve`, `dynamics` and `simulate` exited 1 (a failed solve) where `sweep`, `trace`,
/// `extremes`, `animate` and `cam` exited 2. `solve` of several `--at` too; a solve that fails
/// for the mechanism (no assembly) stays 1.
#[test]
fn a_loop_whose_lengths_are_all_zero_is_a_usage_error_under_every_subcommand() {
    for (deg, at) in [(true, ["30", "60"]), (false, ["0.5", "1"])] {
        for (args, _) in on_zero_loops(at, deg) {
            let out = kinloop(&args.iter().map(String::as_str).collect::<Vec<_>>());
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(err.contains("all have length zero"), "{args:?}: {err}");
            assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        }
    }
    let four_bar = shipped("four_bar.kl");
    let code =
        |params: &str| kinloop(&["solve", &four_bar, "--params", params, "--at", "0.5", "--at", "1"]).status.code();
    assert_eq!(code("a=0,b=0,c=0,d=0"), Some(2));
    assert_eq!(code("a=1,b=3,c=2.5,d=10"), Some(1));
}
