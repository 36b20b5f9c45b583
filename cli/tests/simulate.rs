//! `kinloop simulate` end to end: the built binary on the shipped engine, its CSV parsed and
//! compared with the compiled mechanism of the same declaration (the fixtures' `EngineMachine`,
//! its `mass_model` and the compiled `Simulation`), its units, options and exit codes.

mod common;

use common::{csv, kinloop, shipped};
use kinloop::dynamics::{RunConfig, Simulation};
use kinloop_fixtures as fx;

/// Agreement demanded with the compiled simulation, of each column's largest magnitude: both
/// integrate by the same code with the same operations (the library's test finds no
/// difference at all), and the CSV writes each value with the digits that read back exactly.
const REL: f64 = 1e-14;

/// The engine driven by a constant torque with a flywheel: the command's times, angles and
/// speeds are the compiled simulation's dense output at those times; in degrees they are the
/// same values converted.
#[test]
fn simulate_writes_the_compiled_engine_s_motion() {
    let engine = fx::EngineMachine::default();
    let mass = engine.mass_model().unwrap();
    let cfg = RunConfig::default().with_flywheel(0.05);
    let compiled = Simulation::new(&engine, &mass).start(0.3, 150.0).drive(|_, _, _| 2.5).config(cfg).run(0.2).unwrap();
    let args = ["simulate", &shipped("engine.kl"), "--start", "0.3", "--speed", "150", "--torque", "2.5"];
    let out = kinloop(&[&args[..], &["--flywheel", "0.05", "--time", "0.2", "--samples", "41"]].concat());
    let (header, rows) = csv(&out);
    assert_eq!(header, ["t [time unit]", "phi [rad]", "omega [rad/time unit]"]);
    assert_eq!(rows.len(), 41);
    let want: Vec<[f64; 3]> = rows
        .iter()
        .map(|r| {
            let [phi, omega] = compiled.at(r[0]);
            [r[0], phi, omega]
        })
        .collect();
    assert_eq!((rows[0][0], rows[40][0]), (0.0, 0.2));
    for c in 0..3 {
        let scale = want.iter().fold(0.0f64, |m, w| m.max(w[c].abs()));
        for (r, w) in rows.iter().zip(&want) {
            assert!((r[c] - w[c]).abs() <= REL * scale, "column {c}: {r:?} against {w:?}");
        }
    }
    // The machine turns: more than four turns in 0.2 time units.
    assert!(rows[40][1] > 0.3 + 4.0 * std::f64::consts::TAU, "{:?}", rows[40]);
    let deg = ["simulate", &shipped("engine.kl"), "--start", "17.188733853924695", "--speed", "8594.366926962348"];
    let out = kinloop(
        &[&deg[..], &["--torque", "2.5", "--flywheel", "0.05", "--time", "0.2", "--samples", "41", "--deg"]].concat(),
    );
    let (header, deg_rows) = csv(&out);
    assert_eq!(header, ["t [time unit]", "phi [deg]", "omega [deg/time unit]"]);
    for (d, r) in deg_rows.iter().zip(&rows) {
        assert!((d[1].to_radians() - r[1]).abs() <= 1e-12 * r[1].abs(), "{d:?} against {r:?}");
        assert!((d[2].to_radians() - r[2]).abs() <= 1e-12 * r[2].abs(), "{d:?} against {r:?}");
    }
}

/// Arguments that cannot be used are usage errors (exit 2), parameters that make a body's mass
/// negative among them; a machine that cannot move on
/// (a rocker driven into its limit position) fails with exit 1 and says where.
#[test]
fn simulate_s_bad_arguments_and_failures_have_their_exit_codes() {
    let engine = shipped("engine.kl");
    for bad in [
        vec!["--time", "0"],
        vec!["--time", "1", "--samples", "1"],
        vec!["--time", "1", "--flywheel", "-1"],
        vec!["--time", "1", "--speed", "inf"],
    ] {
        let out = kinloop(&[&["simulate", engine.as_str()][..], &bad].concat());
        assert_eq!(out.status.code(), Some(2), "{bad:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
    // A body's mass or inertia made negative by the parameters given.
    for param in ["m_rod=-2", "j_crank=-1e-3"] {
        let out = kinloop(&["simulate", engine.as_str(), "--time", "1", "--params", param]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{param}: {stderr}");
        assert!(stderr.contains("of body `") && stderr.contains("--params"), "{param}: {stderr}");
    }
    let out = kinloop(&["simulate", &shipped("four_bar.kl"), "--time", "1", "--params", "a=1,b=3,c=2.5,d=3.2"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("declares no bodies"));
    // A crank longer than the rod: the engine rocks to a limit position.
    let out = kinloop(&["simulate", &engine, "--time", "1", "--speed", "100", "--params", "r=0.3,l=0.2"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("EngineMachine"), "{stderr}");
}

/// The step budget is an option: `--max-steps` that is no count of at least 1 is a usage
/// error; a `--time` that needs more steps than the budget stops when the budget is spent (not
/// after millions of steps) and says which option to raise; a budget that suffices changes
/// nothing in the output.
#[test]
fn simulate_s_step_budget_is_an_option_that_bounds_the_run() {
    let engine = shipped("engine.kl");
    let run = |extra: &[&str]| {
        let args = ["simulate", engine.as_str(), "--speed", "150", "--torque", "2.5", "--flywheel", "0.05"];
        kinloop(&[&args[..], extra].concat())
    };
    let stderr = |o: &std::process::Output| String::from_utf8_lossy(&o.stderr).to_string();
    for bad in ["0", "many", "-3", "1.5"] {
        let out = run(&["--time", "0.2", "--max-steps", bad]);
        assert_eq!(out.status.code(), Some(2), "--max-steps {bad}: {}", stderr(&out));
        assert!(stderr(&out).contains("--max-steps"), "--max-steps {bad}: {}", stderr(&out));
        assert!(out.stdout.is_empty());
    }
    let out = run(&["--time", "0.2", "--max-steps", "0"]);
    assert!(stderr(&out).contains("at least 1"), "{}", stderr(&out));
    // A span of a million million time units: the budget of 1000 steps is spent long before
    // its end, and the run stops there (the message names the budget it spent).
    let out = run(&["--time", "1e12", "--max-steps", "1000"]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty(), "no table of a simulation that did not reach its time");
    for what in ["EngineMachine", "budget of 1000 steps", "raise --max-steps", "--time"] {
        assert!(err.contains(what), "`{what}` missing: {err}");
    }
    assert!(!err.contains("OdeConfig"), "the library's setting named to a command-line user: {err}");
    // A budget of one step is named in the singular.
    let err = stderr(&run(&["--time", "1e12", "--max-steps", "1"]));
    assert!(err.contains("budget of 1 step (--max-steps)"), "{err}");
    // From rest, where the first step is a millionth of the span: over 1e10 (and 1e200) its
    // stages put the crank far beyond any f64 angle, a step rejected for a shorter one, not a
    // failure of the machine ("input accelerations ... beyond the range of f64").
    // The time is written back as every number in kinloop is, not in two hundred digits.
    for (time, written) in [("1e10", "10000000000"), ("1e200", "1e200")] {
        let out = kinloop(&["simulate", engine.as_str(), "--time", time, "--max-steps", "1000"]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "--time {time}: {err}");
        assert!(err.contains("budget of 1000 steps") && err.contains(&format!("of --time {written}")), "{err}");
    }
    // A speed that makes the span more steps than any budget: the message names the turns the
    // speed and the time imply (1e30 rad per unit for 1 unit: 1e30 / 2 pi = 1.59e29 turns,
    // closed form) as the cause, and both remedies, not raising the budget.
    let out = kinloop(&["simulate", engine.as_str(), "--speed", "1e30", "--time", "1", "--max-steps", "1000"]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    let cause = "--speed 1e30 over --time 1 is about 1.59e29 turns of the input";
    for what in [cause, "more than any --max-steps", "lower --speed", "shorter --time"] {
        assert!(err.contains(what), "`{what}` missing: {err}");
    }
    assert!(!err.contains("raise --max-steps"), "{err}");
    // A long time at an ordinary speed: the turns named too, and every remedy.
    let err = stderr(&run(&["--time", "1e12", "--max-steps", "1000"]));
    for what in ["--speed 150 over --time 1000000000000 is about 2.39e13 turns", "raise --max-steps, lower --speed"] {
        assert!(err.contains(what), "`{what}` missing: {err}");
    }
    // A budget the run fits in: the same table as the default's.
    let fits = run(&["--time", "0.2", "--samples", "11"]);
    assert!(fits.status.success(), "{}", stderr(&fits));
    let budget = run(&["--time", "0.2", "--samples", "11", "--max-steps", "100000"]);
    assert!(budget.status.success(), "{}", stderr(&budget));
    assert_eq!(fits.stdout, budget.stdout);
}

/// The table the command streams (each row read from a step's dense output as the steps pass
/// its time) is, bit for bit, the one sampled from the whole recorded trajectory of the same
/// run-time model: every time and value of the CSV, read back, is the trajectory's
/// `Trajectory::at` at that time, the times those from the time reached, in radians and in
/// degrees, with more rows than the run has steps.
#[test]
fn simulate_s_streamed_table_is_the_recorded_trajectory_s() {
    let mut model = kinloop_model::Model::read("engine.kl", &std::fs::read_to_string(shipped("engine.kl")).unwrap())
        .expect("the shipped engine");
    for (deg, angle) in [(false, 1.0), (true, 180.0 / std::f64::consts::PI)] {
        // The start as the command reads it: the value written, converted to radians.
        let (start, speed) = (0.3 * angle, 150.0 * angle);
        let run = model
            .simulation()
            .start(start / angle, speed / angle)
            .drive(|_, _, _| 2.5)
            .config(RunConfig::default().with_flywheel(0.05))
            .run(0.2)
            .unwrap();
        let samples = 3 * run.steps.len() + 1;
        let n = samples.to_string();
        let (start, speed) = (start.to_string(), speed.to_string());
        let args = ["simulate", &shipped("engine.kl"), "--start", &start, "--speed", &speed, "--torque", "2.5"];
        let more: &[&str] = if deg { &["--deg"] } else { &[] };
        let out = kinloop(&[&args[..], &["--flywheel", "0.05", "--time", "0.2", "--samples", &n], more].concat());
        let (_, rows) = csv(&out);
        assert_eq!(rows.len(), samples);
        let last = samples - 1;
        for (k, r) in rows.iter().enumerate() {
            // The time written is the decimal `0.2 k / last` (its nearest double), the product
            // to its rounding.
            let (time, product) = (r[0], if k == last { run.t_end } else { run.t_end * k as f64 / last as f64 });
            assert!((time - product).abs() <= 2.0 * f64::EPSILON * product, "row {k}: {time} vs {product}");
            let [phi, omega] = run.at(time);
            let want = [time, phi * angle, omega * angle];
            assert_eq!(r.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), want.map(f64::to_bits), "row {k}: {r:?}");
        }
    }
}

/// The times between the start and `--time` are the decimals they stand for, as `sweep` writes
/// its inputs: `--time 0.3 --samples 4` wrote `0.09999999999999999` and `0.19999999999999998`
/// (the products `0.3 k / 3`), and `--time 0.7 --samples 8` `0.30000000000000004`.
#[test]
fn the_times_between_are_the_decimals() {
    let engine = shipped("engine.kl");
    for (time, samples, want) in [
        ("0.3", "4", &["0", "0.1", "0.2", "0.3"][..]),
        ("0.7", "8", &["0", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7"][..]),
    ] {
        let args = ["simulate", &engine, "--speed", "150", "--time", time, "--samples", samples];
        let out = kinloop(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let text = String::from_utf8_lossy(&out.stdout);
        let times: Vec<&str> = text.lines().skip(1).map(|l| l.split(',').next().unwrap_or_default()).collect();
        assert_eq!(times, want, "--time {time} --samples {samples}");
    }
}

/// A start angle so large that no step can move it is named as the input angle in the units
/// given (without `--deg` it named "state component 0"). In degrees such a start is refused
/// before, as given: that far out degrees do not convert to radians precisely (where they do,
/// up to 2.6e8 degrees, a step moves the angle).
#[test]
fn a_start_no_step_can_move_is_named_as_given() {
    let engine = shipped("engine.kl");
    let base = ["simulate", engine.as_str(), "--speed", "150", "--torque", "2.5", "--flywheel", "0.05"];
    let run = |start: &str, deg: bool| {
        let mut args = [&base[..], &["--time", "0.1", "--start", start]].concat();
        if deg {
            args.push("--deg");
        }
        let out = kinloop(&args);
        (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (code, err) = run("1e300", false);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("(= 1e300)") && err.contains("cannot advance"), "{err}");
    assert!(err.contains("changes the input angle") && !err.contains("component"), "{err}");
    for start in ["1e300", "1e17"] {
        let (code, err) = run(start, true);
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains(&format!("--start: {start} degrees are too many turns out")), "{err}");
        // In degrees as given, not in radians (1e300 degrees are 1.745...e298 rad).
        assert!(!err.contains("e298") && !err.contains("e15"), "{err}");
    }
    assert_eq!(run("2.5e8", true).0, Some(0));
}

/// A `--time` too short for any step (a few subnormals: below 8 units in the last place of the
/// smallest normal double, about 3.9e-323, the time's rounding is as large as the span) is a
/// usage error naming `--time`, as `--time 0` is: it failed as a solve (exit 1) with the
/// library's "invalid end time". A tiny time that a step spans (1e-300) is simulated: the
/// crank has turned by the speed times the time (its acceleration adds `t^2`, 1e-600: nothing).
#[test]
fn a_time_too_short_for_a_step_is_a_usage_error() {
    let engine = shipped("engine.kl");
    let run = |time: &str| kinloop(&["simulate", &engine, "--speed", "150", "--time", time, "--samples", "2"]);
    for time in ["5e-324", "2e-323", "3.5e-323"] {
        let out = run(time);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "--time {time}: {err}");
        assert!(err.contains("--time") && err.contains("EngineMachine"), "--time {time}: {err}");
        assert!(out.stdout.is_empty(), "--time {time}");
    }
    let (_, rows) = csv(&run("1e-300"));
    let [t, phi, omega] = rows[1][..] else { panic!("three columns: {rows:?}") };
    assert_eq!(t, 1e-300);
    // To a few roundings of the integrator's sums (1e-15 relative).
    assert!((phi / 1.5e-298 - 1.0).abs() <= 1e-15, "{phi}");
    assert!((omega / 150.0 - 1.0).abs() <= 1e-15, "{omega}");
}

/// A machine started at rest over a tiny `--time` a step does span (subnormal times, above the
/// time's rounding of 3.9e-323) is simulated: its first step, a millionth of the span, was below
/// that rounding or 0, and the run failed as "the motion is singular at phi = 0, speed 0 (t =
/// 0) ... is this a limit position?" (exit code 1), of a machine with nothing singular about it.
#[test]
fn a_tiny_time_from_rest_is_simulated() {
    let engine = shipped("engine.kl");
    for time in ["1e-317", "1e-320", "1e-322"] {
        let out = kinloop(&["simulate", &engine, "--time", time, "--samples", "2"]);
        let (_, rows) = csv(&out);
        let [t, phi, _] = rows[1][..] else { panic!("three columns: {rows:?}") };
        // From rest the crank has not moved: half its acceleration times the square of `t`.
        assert_eq!((t, phi), (time.parse().expect("a number"), 0.0), "--time {time}");
    }
}

/// The first row is the start at time 0, its angle and speed in degrees as given: `--start 30`
/// was written `29.999999999999996` (its radians times `180/pi`). The same state as the run in
/// radians from the same start, to a rounding of the conversion.
#[test]
fn the_start_in_degrees_is_written_as_given() {
    let engine = shipped("engine.kl");
    let run = |start: &str, speed: &str, deg: &[&str]| {
        let args = ["simulate", &engine, "--start", start, "--speed", speed, "--time", "0.01", "--samples", "2"];
        csv(&kinloop(&[&args[..], deg].concat())).1
    };
    for start in ["30", "70", "-0.1"] {
        let rows = run(start, "8594.366926962348", &["--deg"]);
        let given: f64 = start.parse().expect("a number");
        assert_eq!(rows[0], [0.0, given, 8594.366926962348], "--start {start}");
        let radians = run(&given.to_radians().to_string(), "150", &[]);
        assert!((radians[0][1].to_degrees() - given).abs() <= 4.0 * f64::EPSILON * given.abs(), "{start}");
    }
}

/// The input angle in a failure's message, `phi = VALUE`.
fn angle_in(err: &str) -> f64 {
    let tail = err.split("at phi = ").nth(1).unwrap_or_else(|| panic!("no angle in: {err}"));
    let value = tail.split([' ', ',', '\n']).next().unwrap_or_default();
    value.parse().unwrap_or_else(|_| panic!("`{value}` in: {err}"))
}

/// With `--deg` a failed simulation names the input in degrees, as its table, `--start` and
/// `--speed` are; it was written in radians. The engine whose crank is longer than its rod
/// (r = 0.3, l = 0.2, offset e = 0.01) locks where `r sin(phi) = l + e`, at asin(0.7) =
/// 44.427 degrees (0.7754 rad): the run stops at a trial state there, within the reach of the
/// last steps, which the speed falling to zero at the limit keeps short (measured: 1e-11 deg).
/// A brake torque `sqrt(1 - phi)` is not finite past 1 rad = 57.296 degrees, where the run
/// stops within a step of it (measured: 0.03 deg at 150 rad per time unit). Half a degree
/// tells either from its value in radians.
#[test]
fn a_failure_names_the_input_in_degrees_with_deg() {
    let engine = shipped("engine.kl");
    let speed = 150f64.to_degrees().to_string();
    let args = ["simulate", &engine, "--deg", "--speed", &speed, "--time", "0.01", "--samples", "3"];
    let out = kinloop(&[&args[..], &["--params", "r=0.3,l=0.2"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let limit = 0.7f64.asin().to_degrees();
    assert!((angle_in(&err) - limit).abs() < 0.5, "limit at {limit} deg: {err}");
    let path = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("engine_sqrt_brake_sim.kl");
    let brake = "-t_load * (1 + 0.5 * cos(phi))";
    let text = std::fs::read_to_string(shipped("engine.kl")).expect("the shipped engine");
    assert!(text.contains(brake), "the shipped engine's brake law changed");
    std::fs::write(&path, text.replacen(brake, "-t_load * sqrt(1 - phi)", 1)).unwrap();
    let args = ["simulate", path.to_str().unwrap(), "--deg", "--speed", &speed, "--time", "0.01", "--samples", "3"];
    let out = kinloop(&args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("the load `brake` is not finite"), "{err}");
    assert!((angle_in(&err) - 1f64.to_degrees()).abs() < 0.5, "not finite past 57.3 deg: {err}");
}

/// The shipped engine with its input `phi` named `input`, written to a file of its own.
fn engine_with_input(input: &str) -> String {
    let text = std::fs::read_to_string(shipped("engine.kl")).expect("the shipped engine");
    let file = std::env::temp_dir().join(format!("kinloop-simulate-input-{input}-{}.kl", std::process::id()));
    std::fs::write(&file, text.replace("phi", input)).expect("written");
    file.display().to_string()
}

/// An input named as a column the command writes of its own (the time `t`, the speed
/// `omega`) is a usage error naming it, before the run: the table named two columns alike
/// (`t [time unit],t [time unit],omega`, the angle's column in the time's unit), which read
/// back as neither. Another name is written as the input's column.
#[test]
fn an_input_named_as_the_command_s_own_column_is_a_usage_error() {
    for input in ["t", "omega"] {
        let file = engine_with_input(input);
        let out = kinloop(&["simulate", &file, "--speed", "150", "--time", "0.01", "--samples", "3"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{input}: {stderr}");
        assert!(out.stdout.is_empty(), "{input}: {}", String::from_utf8_lossy(&out.stdout));
        assert!(stderr.contains(&format!("rename the input `{input}` of EngineMachine")), "{stderr}");
        let _ = std::fs::remove_file(&file);
    }
    let file = engine_with_input("theta");
    let (header, rows) = csv(&kinloop(&["simulate", &file, "--speed", "150", "--time", "0.01", "--samples", "3"]));
    assert_eq!(header, ["t [time unit]", "theta [rad]", "omega [rad/time unit]"]);
    assert_eq!(rows.len(), 3);
    let _ = std::fs::remove_file(&file);
}
