//! `kinloop trace` end to end: the built binary on the shipped four-bar, its CSV and its events
//! compared with closed forms (the limit positions of a linkage whose input rocks, by the law of
//! cosines; every point on the loop), the closure of a crank-rocker driven by its rocker, its
//! usage errors and exit codes.
//!
//! Tolerances: a limit position is located to the rounding of the arclength (`1e-9` rad is far
//! above it); every point is a corrected Newton solution, on the loop to the solver's tolerance
//! relative to the links' size (`1e-10`). Degrees add one conversion (a relative rounding).

mod common;

use common::{csv, kinloop, shipped};
use std::f64::consts::TAU;

/// The crank angles `+-phi` of the limit positions of the four-bar `a, b, c, d` where coupler
/// and rocker lie in line, stretched (`|BD| = b + c`).
fn stretched_limit(a: f64, b: f64, c: f64, d: f64) -> f64 {
    ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos()
}

/// The events file: per event its kind and its numbers (`tau`, the inputs, the unknowns).
fn events(path: &std::path::Path) -> Vec<(String, Vec<f64>)> {
    let text = std::fs::read_to_string(path).expect("the events file");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("kind,tau [1],phi [deg],beta [deg],gamma [deg]"));
    lines
        .map(|l| {
            let (kind, rest) = l.split_once(',').expect("a kind");
            (kind.to_string(), rest.split(',').map(|v| v.parse().expect("a number")).collect())
        })
        .collect()
}

/// A triple rocker (`a + d > b + c`): its input rocks between two limit positions, which a sweep
/// stops at and the trace passes, closing its curve. In degrees, with the events in a file.
#[test]
fn a_rocking_inputs_closed_curve_with_its_limit_positions_in_degrees() {
    let (a, b, c, d): (f64, f64, f64, f64) = (3.0, 2.0, 2.5, 4.0);
    let dir = std::env::temp_dir().join(format!("kinloop-trace-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let events_path = dir.join("events.csv");
    let params = format!("a={a},b={b},c={c},d={d}");
    let args = ["trace", &shipped("four_bar.kl"), "--from", "0", "--to", "180", "--deg", "--params", &params];
    let out = kinloop(&[&args[..], &["--events", events_path.to_str().unwrap()]].concat());
    let (header, rows) = csv(&out);
    assert_eq!(header, ["phi [deg]", "beta [deg]", "gamma [deg]", "pc.x [length unit]", "pc.y [length unit]"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("the curve closed on itself"), "{stderr}");
    assert!(rows.len() > 100, "{} points", rows.len());
    for r in &rows {
        let [phi, beta, gamma] = [r[0], r[1], r[2]].map(f64::to_radians);
        let loop_x = a * phi.cos() + b * beta.cos() - d - c * gamma.cos();
        let loop_y = a * phi.sin() + b * beta.sin() - c * gamma.sin();
        assert!(loop_x.abs().max(loop_y.abs()) <= 1e-10 * d, "off the loop at {r:?}");
        let pc = [a * phi.cos() + b * beta.cos(), a * phi.sin() + b * beta.sin()];
        assert!((pc[0] - r[3]).abs().max((pc[1] - r[4]).abs()) <= 1e-12 * d, "the coupler point at {r:?}");
    }
    let lim = stretched_limit(a, b, c, d).to_degrees();
    let found = events(&events_path);
    assert_eq!(found.len(), 2, "{found:?}");
    // First the one the trace meets moving towards `--to`, then the other.
    for ((kind, v), expected) in found.iter().zip([lim, -lim]) {
        assert_eq!(kind, "limit position");
        assert!((v[1] - expected).abs() <= 1e-9_f64.to_degrees(), "{v:?} against {expected}");
        // Coupler and rocker in line: `gamma - beta` a whole number of half turns.
        let half_turns = (v[3] - v[2]) / 180.0;
        assert!((half_turns - half_turns.round()).abs() <= 1e-8, "{v:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A crank-rocker driven by its rocker (the output link `c` the shortest, `c + d <= a + b`):
/// the input rocks (between `|BD| = b - c` and `b + c`: 0.64 to 1.71 rad) while the crank turns
/// fully. The curve closes after one rocking with the crank a turn on, its angle compared to
/// within whole turns; events on standard error.
#[test]
fn a_crank_driven_by_its_rocker_closes_a_turn_on() {
    let params = "a=2,b=3,c=1,d=3.2";
    let out = kinloop(&["trace", &shipped("four_bar.kl"), "--from", "1.2", "--to", "2", "--params", params]);
    let (_, rows) = csv(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.matches("event: limit position").count(), 2, "{stderr}");
    assert!(stderr.contains("the curve closed on itself"), "{stderr}");
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    // The last point is within a step (0.01 in the scaled coordinates) of the first.
    assert!((last[0] - first[0]).abs() < 0.05, "{first:?} .. {last:?}");
    let turned = (last[2] - first[2]) / TAU;
    assert!((turned.abs() - 1.0).abs() < 0.01, "the crank turned {turned} turns");
}

/// Where a sweep stops at a limit position it says that `trace_curve` goes on, and notes that
/// it is `kinloop trace`; a sweep started at the input it names (copied from its message, in
/// degrees) says that it starts at a singular position, and a trace started there starts there:
/// it lists that limit position first, the other where the law of cosines puts it, and closes
/// its curve.
#[test]
fn a_trace_starts_where_a_sweep_stopped_at_a_limit_position() {
    let (a, b, c, d): (f64, f64, f64, f64) = (3.0, 2.0, 2.5, 4.0);
    let params = format!("a={a},b={b},c={c},d={d}");
    let four_bar = shipped("four_bar.kl");
    let common = ["--deg", "--params", params.as_str()];
    let swept = kinloop(&[&["sweep", four_bar.as_str(), "--from", "0", "--to", "180"][..], &common].concat());
    let stderr = String::from_utf8_lossy(&swept.stderr);
    assert_eq!(swept.status.code(), Some(1), "{stderr}");
    // The error says what goes on in the library's names, the note the command line's, once each.
    assert!(stderr.contains("the input cannot go on past a limit position on this branch; `trace_curve`"), "{stderr}");
    assert!(stderr.contains("\nnote: `trace_curve` is `kinloop trace` on the command line\n"), "{stderr}");
    assert_eq!(stderr.matches("cannot go on past a limit position").count(), 1, "{stderr}");
    let stop = stderr.lines().find(|l| l.starts_with("error: the sweep stopped at a limit position")).expect(&stderr);
    let at = stop.split("phi = ").nth(1).and_then(|r| r.split(' ').next()).expect(stop);
    let lim = stretched_limit(a, b, c, d).to_degrees();
    assert!((at.parse::<f64>().unwrap() - lim).abs() <= 1e-9_f64.to_degrees(), "{at} against {lim}");
    // A sweep from there cannot leave it on one branch: it says that it starts at a singular
    // position, and names `trace`.
    let again = kinloop(&[&["sweep", four_bar.as_str(), "--from", at, "--to", "0"][..], &common].concat());
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert_eq!(again.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("error: the sweep starts at a singular position"), "{stderr}");
    assert!(stderr.contains("note: `kinloop trace` traces the curve from a limit position"), "{stderr}");
    let traced = kinloop(&[&["trace", four_bar.as_str(), "--from", at, "--to", "-180"][..], &common].concat());
    let stderr = String::from_utf8_lossy(&traced.stderr);
    assert_eq!(traced.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("the curve closed on itself"), "{stderr}");
    let limits: Vec<&str> = stderr.lines().filter(|l| l.starts_with("event: limit position at phi = ")).collect();
    assert_eq!(limits.len(), 2, "{stderr}");
    assert!(limits[0].starts_with(&format!("event: limit position at phi = {at} (fraction 0 ")), "{stderr}");
    let other: f64 = limits[1]["event: limit position at phi = ".len()..].split(' ').next().unwrap().parse().unwrap();
    assert!((other + lim).abs() <= 1e-9_f64.to_degrees(), "{other} against {}", -lim);
    let (_, rows) = csv(&traced);
    assert_eq!(rows[0][0], at.parse::<f64>().unwrap());
    for r in &rows {
        let [phi, beta, gamma] = [r[0], r[1], r[2]].map(f64::to_radians);
        let loop_x = a * phi.cos() + b * beta.cos() - d - c * gamma.cos();
        let loop_y = a * phi.sin() + b * beta.sin() - c * gamma.sin();
        assert!(loop_x.abs().max(loop_y.abs()) <= 1e-10 * d, "off the loop at {r:?}");
    }
}

/// A sweep that stops at a change point (a parallelogram four-bar's links in line) says that
/// two branches cross there, that `AtSingular::Continue` goes on and that `trace_curve` keeps to
/// the curve it is on, and notes that these are `--through-crossings` and `kinloop trace`: the
/// sweep told to go on passes both change points (two of its samples lie on them), and the
/// trace over the same range passes both and closes its curve.
#[test]
fn a_sweep_stopped_at_a_change_point_names_trace() {
    let args = ["--from", "10", "--to", "370", "--deg", "--params", "a=1,b=3,c=1,d=3"];
    let four_bar = shipped("four_bar.kl");
    let swept = kinloop(&[&["sweep", four_bar.as_str(), "--samples", "37"][..], &args].concat());
    let stderr = String::from_utf8_lossy(&swept.stderr);
    assert_eq!(swept.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("error: the sweep stopped at a singular crossing"), "{stderr}");
    // The error says what goes on in the library's names, the note the command line's, once each.
    assert!(stderr.contains(": two branches of the motion cross there (a change point)"), "{stderr}");
    assert!(
        stderr.contains("`AtSingular::Continue` (`SweepConfig::with_at_singular`) goes on along the smooth"),
        "{stderr}"
    );
    assert!(stderr.contains("`trace_curve` keeps to the curve it is on"), "{stderr}");
    assert!(
        stderr.contains("`AtSingular::Continue` is `--through-crossings`, `trace_curve` is `kinloop trace`"),
        "{stderr}"
    );
    assert_eq!(stderr.matches("two branches of the motion cross there").count(), 1, "{stderr}");
    // Told to go on, the sweep passes both; its samples at 180 and 360 degrees, on the change
    // points, are the first well-conditioned states past them, each written at its own input.
    let through =
        kinloop(&[&["sweep", four_bar.as_str(), "--samples", "37", "--through-crossings"][..], &args].concat());
    let stderr = String::from_utf8_lossy(&through.stderr);
    assert_eq!(through.status.code(), Some(0), "{stderr}");
    assert_eq!(stderr.lines().filter(|l| l.starts_with("event: singular crossing at phi = ")).count(), 2, "{stderr}");
    let (_, rows) = csv(&through);
    assert_eq!(rows.len(), 37);
    for (n, r) in rows.iter().enumerate() {
        let sample = 10.0 + 10.0 * n as f64;
        let past = r[0] - sample;
        if n == 17 || n == 35 {
            assert!(past > 0.0 && past < 0.1, "{r:?}");
        } else {
            assert_eq!(r[0], sample, "{r:?}");
        }
        // The parallelogram's branch: the coupler parallel to the frame, the rocker with the crank.
        assert!(r[1].abs() < 1e-9 && (r[2] - r[0]).abs() < 1e-9, "{r:?}");
    }
    let traced = kinloop(&[&["trace", four_bar.as_str()][..], &args].concat());
    let stderr = String::from_utf8_lossy(&traced.stderr);
    assert_eq!(traced.status.code(), Some(0), "{stderr}");
    assert_eq!(stderr.lines().filter(|l| l.starts_with("event: singular crossing at phi = ")).count(), 2, "{stderr}");
    assert!(stderr.contains("the curve closed on itself"), "{stderr}");
}

/// At a change point two curves cross: no trace starts there (which would it follow?). The
/// error says where the start is singular and the note where a trace can start instead.
#[test]
fn no_trace_starts_at_a_change_point() {
    // A parallelogram four-bar: at phi = 0 its links lie in line, a change point.
    let out = kinloop(&["trace", &shipped("four_bar.kl"), "--from", "0", "--to", "1", "--params", "a=1,b=3,c=1,d=3"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("error: singular position in `FourBar` at phi = 0"), "{stderr}");
    assert!(
        stderr.contains("note: a trace starts at a limit position") && stderr.contains("start it beside"),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn bad_options_are_usage_errors_naming_them() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=3,b=2,c=2.5,d=4";
    for (extra, says) in [
        (&["--from", "0", "--to", "1", "--ds", "0"][..], "--ds 0 must be from 1e-9 to 1"),
        (&["--from", "0", "--to", "1", "--ds", "-1"][..], "--ds -1 must be from"),
        (&["--from", "0", "--to", "1", "--ds", "inf"][..], "--ds inf must be from"),
        (&["--from", "0", "--to", "1", "--ds", "3"][..], "longer steps pass over the curve's limit positions"),
        (&["--from", "0", "--to", "1", "--max-points", "0"][..], "--max-points 0 is out of range"),
        (&["--from", "0", "--to", "1", "--max-points", "10000001"][..], "at most 10000000"),
        (&["--from", "1", "--to", "1"][..], "--from 1 --to 1: the trace needs a direction"),
        (&["--from", "1", "--to", "1.0", "--deg"][..], "give --to different from --from"),
        (&["--from", "0,1", "--to", "1"][..], "gives 2 inputs"),
        (&["--from", "0", "--to", "1e12"][..], "turns a sweep or a trace follows"),
        // From 694,444 turns back (where this rocker assembles, as at 0): 1.39e6 turns
        // in degrees that still convert to radians precisely; 1e12 degrees do not.
        (
            &["--from", "-249999840", "--to", "2.5e8", "--deg"][..],
            "at most 360000000 apart in the units given (degrees for an angle) (--to 110000160)",
        ),
        (&["--from", "0", "--to", "1e12", "--deg"][..], "--to 1e12: 1000000000000 degrees are too many turns out"),
    ] {
        let out = kinloop(&[&["trace", four_bar.as_str(), "--params", params][..], extra].concat());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {stderr}");
        assert!(stderr.contains(says), "{extra:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{extra:?}");
    }
}

/// A trace that leaves the inputs' segment says where the segment is, in numbers in the units
/// given (for each input, as far behind `--from` as `--to` lies ahead): it said "the path from
/// `from - (to - from)` to `to`", the library's arguments, for the reader to work out. The
/// crank of a Grashof four-bar turns on past `--to`, so its curve leaves the segment there.
#[test]
fn a_trace_that_leaves_the_segment_says_where_it_is() {
    let four_bar = shipped("four_bar.kl");
    let runs: [(&[&str], &str); 2] = [
        (&["--from", "30", "--to", "60", "--deg"], "from 0 to 60 (as far behind --from 30"),
        (&["--from", "1", "--to", "1.5"], "from 0.5 to 1.5 (as far behind --from 1"),
    ];
    for (range, said) in runs {
        let args = [&["trace", &four_bar, "--params", "a=1,b=3,c=2.5,d=3.2"][..], range].concat();
        let out = kinloop(&args);
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "{range:?}: {stderr}");
        assert!(stderr.contains(&format!("FourBar: the curve left the inputs' segment {said}")), "{range:?}: {stderr}");
        assert!(!stderr.contains("from - (to - from)"), "{range:?}: {stderr}");
    }
}

/// `--max-points` stops the trace there, and says so.
#[test]
fn the_most_points_stop_the_trace_and_it_says_so() {
    let out = kinloop(&[
        "trace",
        &shipped("four_bar.kl"),
        "--params",
        "a=3,b=2,c=2.5,d=4",
        "--from",
        "0",
        "--to",
        "1",
        "--max-points",
        "7",
    ]);
    let (_, rows) = csv(&out);
    assert_eq!(rows.len(), 7);
    assert!(String::from_utf8_lossy(&out.stderr).contains("stopped at --max-points 7"));
}

/// A trace keeps every point, and the runtime refuses a `--max-points` whose points would take
/// more than the 1 GiB a collector keeps at most; the command says so in its own option's terms,
/// with the most that fit for this model, not in the library's field's. A run-time model's point
/// holds its positions and inputs on the heap: of a chain of five four-bars (ten unknowns) fewer
/// than the option's own bound of 10^7 fit. The most that fit are traced.
#[test]
fn more_points_than_fit_in_memory_are_refused_naming_the_option() {
    let mut text = String::from("pub struct Chain {\n    params a = 1, b = 3, c = 2.5, d = 3.2;\n    input phi;\n");
    text += "    unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9, u4 = 0.6, v4 = 1.9;\n";
    for (i, driver) in ["phi", "v0", "v1", "v2", "v3"].iter().enumerate() {
        text += &format!("    loop l{i}: a @ {driver} + b @ u{i} == (d, 0) + c @ v{i};\n");
    }
    text += "}\n";
    let path = std::env::temp_dir().join(format!("kinloop-trace-chain-{}.kl", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let chain = path.display().to_string();
    let run = |n: &str| kinloop(&["trace", chain.as_str(), "--from", "0", "--to", "1", "--max-points", n]);
    let out = run("10000000");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--max-points 10000000: more points of Chain than fit in the 1 GiB"), "{stderr}");
    assert!(!stderr.contains("TraceConfig"), "{stderr}");
    let most: usize = stderr
        .split("give at most ")
        .nth(1)
        .and_then(|rest| rest.split(',').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("the most that fit: {stderr}"));
    assert!((1_000_000..10_000_000).contains(&most), "{most}");
    let over = run(&(most + 1).to_string());
    assert_eq!(over.status.code(), Some(2), "{}", String::from_utf8_lossy(&over.stderr));
    let at = run(&most.to_string());
    std::fs::remove_file(&path).ok();
    assert!(at.status.success(), "{}", String::from_utf8_lossy(&at.stderr));
}

/// The help of `--max-points` says what the most points cost: every point is kept until the
/// trace ends, as `extremes` says of its samples; it gave the bound alone, which takes about a
/// gigabyte.
#[test]
fn the_help_states_what_the_points_kept_take() {
    let out = kinloop(&["trace", "--help"]);
    let help = String::from_utf8_lossy(&out.stdout);
    // The option's own entry: from its name to the next option's.
    let entry = help.split("\n      --max-points <").nth(1).and_then(|rest| rest.split("\n      --").next());
    let states =
        |e: &str| e.contains("every point is kept until the trace ends") && e.contains("some 1 GB at the most");
    assert!(entry.is_some_and(states), "{help}");
}

/// A declaration without unknowns (a point and an output of the input alone) traces its input
/// from `--from` to past `--to`, every point the closed form's: the SVD of its empty Jacobian
/// panicked ("Cannot compute the SVD of an empty matrix", exit code 101).
#[test]
fn a_declaration_without_unknowns_is_traced() {
    let dir = std::env::temp_dir().join(format!("kinloop-trace-no-unknowns-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("no_unknowns.kl");
    std::fs::write(
        &file,
        "pub struct X {\n    params a = 2.0;\n    input phi;\n    output y = a * phi;\n    point p = a @ phi;\n}\n",
    )
    .expect("the declaration");
    let out = kinloop(&["trace", file.to_str().unwrap(), "--from", "0", "--to", "1", "--ds", "0.1"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let (header, rows) = csv(&out);
    assert_eq!(header, ["phi [rad]", "p.x [length unit]", "p.y [length unit]", "y [length unit]"]);
    assert!(rows.len() >= 10, "{} points", rows.len());
    for row in &rows {
        let phi = row[0];
        assert!((-1.0..=1.0 + 1e-9).contains(&phi), "{phi}");
        assert!((row[1] - 2.0 * phi.cos()).abs() < 1e-12 && (row[2] - 2.0 * phi.sin()).abs() < 1e-12, "{row:?}");
        assert!((row[3] - 2.0 * phi).abs() < 1e-12, "{row:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// An output that is not finite at a traced point (`sqrt(sin(phi))` past `phi = pi`, by hand)
/// fails the trace there, exit code 1, naming the output and the input, as `solve` and `sweep`
/// fail: the trace wrote it `NaN` and succeeded. The points before it are written, each with
/// the output of the closed form.
#[test]
fn an_output_that_is_not_finite_fails_the_trace() {
    let file = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("trace_not_finite.kl");
    let text = "pub struct Rooted {
        params r = 1, l = 3;
        input phi;
        unknowns psi = 0, x = -2;
        loop oabo: r @ phi == (x, 0) + l @ psi;
        point q = (sqrt(sin(phi)), 0);
    }";
    std::fs::write(&file, text).expect("write the declaration");
    let f = file.display().to_string();
    let out = kinloop(&["trace", &f, "--from", "3", "--to", "4", "--ds", "0.05"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("the output `q.x` is not finite in `Rooted` at phi = "), "{err}");
    let at: f64 = err.split("at phi = ").nth(1).and_then(|s| s.split(':').next()).expect("phi").parse().expect("phi");
    assert!(at > std::f64::consts::PI && at <= 4.0, "{err}");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let rows: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect()).collect();
    assert!(!rows.is_empty(), "{text}");
    for r in &rows {
        // The output's own expression, evaluated the same way: to the rounding.
        assert!(r[3].is_finite() && (r[3] - r[0].sin().sqrt()).abs() <= 1e-15, "{r:?}");
    }
    let _ = std::fs::remove_file(&file);
}

/// A four-bar's input or unknown named as a column the events' file writes of its own (`kind`,
/// `tau`) is a usage error naming it, before `sweep` or `trace` runs, where `--events` is
/// given: the file's header named two columns alike (`kind,tau,tau [rad],beta [rad],...`),
/// which a CSV reader finds by name. Without `--events` the events name no columns, and the
/// run is as before; another name is written beside `kind,tau`.
#[test]
fn an_input_or_unknown_named_as_an_events_column_is_a_usage_error() {
    let text = std::fs::read_to_string(shipped("four_bar.kl")).expect("the shipped four-bar");
    let dir = std::env::temp_dir();
    let events = dir.join(format!("kinloop-events-columns-{}.csv", std::process::id()));
    let events_arg = events.display().to_string();
    let params = ["--params", "a=1,b=3,c=2.5,d=3.2", "--from", "0", "--to", "1"];
    let run = |command: &str, file: &str, with_events: bool| {
        let mut args = vec![command, file];
        args.extend(params);
        if with_events {
            args.extend(["--events", events_arg.as_str()]);
        }
        kinloop(&args)
    };
    for (from, to, what) in [("phi", "tau", "input"), ("gamma", "kind", "unknown")] {
        let file = dir.join(format!("kinloop-events-columns-{to}-{}.kl", std::process::id()));
        std::fs::write(&file, text.replace(from, to)).expect("written");
        let file = file.display().to_string();
        for command in ["sweep", "trace"] {
            let out = run(command, &file, true);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{command} {to}: {stderr}");
            assert!(out.stdout.is_empty(), "{command} {to}: {}", String::from_utf8_lossy(&out.stdout));
            assert!(stderr.contains(&format!("kinloop {command} --events writes a column `{to}`")), "{stderr}");
            assert!(stderr.contains(&format!("rename the {what} `{to}` of FourBar")), "{stderr}");
            assert!(!events.exists(), "{command} {to}: the events file was created");
            let out = run(command, &file, false);
            assert!(out.status.success(), "{command} {to}: {}", String::from_utf8_lossy(&out.stderr));
        }
        let _ = std::fs::remove_file(&file);
    }
    for command in ["sweep", "trace"] {
        assert!(run(command, &shipped("four_bar.kl"), true).status.success(), "{command}");
        let written = std::fs::read_to_string(&events).expect("the events file");
        assert!(written.starts_with("kind,tau [1],phi [rad],beta [rad],gamma [rad]\n"), "{command}: {written}");
        let _ = std::fs::remove_file(&events);
    }
}
