//! `kinloop extremes` end to end: the built binary on the shipped `.kl` files, its CSV and its
//! table parsed and compared with closed forms (the limit positions of a crank-rocker and the
//! dead centres of an offset slider-crank), its usage errors and exit codes.
//!
//! Tolerances: an extreme is located as a root of the velocity analog, to the analog's rounding
//! over the curvature (of order one for these links): within 1e-10 rad of the closed form's
//! input; its value, where the analog vanishes, moves to second order only: within 1e-12 of the
//! links' size. Degrees add one conversion (a relative rounding).

mod common;

use common::{kinloop, shipped};
use kinloop_fixtures as fx;
use std::f64::consts::TAU;
use std::process::Output;

/// A row of the output: the column's name, its unit and the numbers.
type Row = (String, String, Vec<f64>);

/// The CSV's header and rows.
fn csv(out: &Output) -> (Vec<String>, Vec<Row>) {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // No progress bar, nor anything else, where standard error is not a terminal.
    assert!(out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout.clone()).expect("utf-8");
    let mut lines = text.lines();
    let header = lines.next().expect("header").split(',').map(str::to_string).collect();
    let rows = lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            let numbers = cells[2..].iter().map(|v| v.parse().expect("a number")).collect();
            (cells[0].to_string(), cells[1].to_string(), numbers)
        })
        .collect();
    (header, rows)
}

/// The row of column `name`: `[min, input at min, max, input at max]` for one input.
fn row<'a>(rows: &'a [Row], name: &str) -> (&'a str, &'a [f64]) {
    let r = rows.iter().find(|r| r.0 == name).unwrap_or_else(|| panic!("no row {name}"));
    (&r.1, &r.2)
}

/// The shipped slider-crank is the fixture's declaration: the same tokens.
#[test]
fn the_shipped_slider_crank_is_the_fixtures() {
    let tokens = |t: &str| t.parse::<proc_macro2::TokenStream>().expect("tokens").to_string().replace("= r\"", "= \"");
    let shipped = std::fs::read_to_string(shipped("slider_crank.kl")).expect("shipped file");
    assert_eq!(tokens(&shipped), tokens(fx::SLIDER_CRANK_TEXT));
}

/// A crank-rocker's rocker swings between the positions where crank and coupler line up
/// (`|AC| = b + a` stretched, `b - a` folded); the triangle A-D-C gives the rocker angle,
/// `|AC|^2 = d^2 + c^2 + 2 d c cos gamma`, and the crank lies along A-C or against it.
#[test]
fn a_rockers_swing_from_the_limit_position_geometry_in_degrees() {
    let (a, b, c, d): (f64, f64, f64, f64) = (1.0, 3.0, 2.5, 3.2);
    let params = format!("a={a},b={b},c={c},d={d}");
    let out =
        kinloop(&["extremes", &shipped("four_bar.kl"), "--from", "0", "--to", "360", "--deg", "--params", &params]);
    let (header, rows) = csv(&out);
    assert_eq!(header, ["column", "unit", "min", "phi at min [deg]", "max", "phi at max [deg]"]);
    assert_eq!(rows.iter().map(|r| r.0.as_str()).collect::<Vec<_>>(), ["beta", "gamma", "pc.x", "pc.y"]);
    let limit = |ac: f64, stretched: bool| {
        let gamma = ((ac * ac - d * d - c * c) / (2.0 * d * c)).acos();
        let (cx, cy) = (d + c * gamma.cos(), c * gamma.sin());
        let phi = if stretched { cy.atan2(cx) } else { (-cy).atan2(-cx) };
        (gamma.to_degrees(), phi.rem_euclid(TAU).to_degrees())
    };
    let (stretched, folded) = (limit(b + a, true), limit(b - a, false));
    let (min, max) = if stretched.0 < folded.0 { (stretched, folded) } else { (folded, stretched) };
    let (unit, g) = row(&rows, "gamma");
    assert_eq!(unit, "deg");
    let deg = |rad: f64| rad.to_degrees();
    assert!((g[0] - min.0).abs() < deg(1e-12) && (g[2] - max.0).abs() < deg(1e-12), "{g:?} vs {min:?} {max:?}");
    assert!((g[1] - min.1).abs() < deg(1e-10) && (g[3] - max.1).abs() < deg(1e-10), "{g:?} vs {min:?} {max:?}");
    // The joint C at the rocker's limits lies on the circle about D: its x is d + c cos gamma at
    // its extremes only where C is leftmost or rightmost, which the rocker's swing, within
    // (0, pi), does not contain: x is extreme where gamma is.
    let (unit, x) = row(&rows, "pc.x");
    assert_eq!(unit, "length unit");
    let cx = |gamma_deg: f64| d + c * gamma_deg.to_radians().cos();
    assert!((x[0] - cx(max.0)).abs() < 1e-12 && (x[2] - cx(min.0)).abs() < 1e-12, "{x:?}");
    assert!((x[1] - max.1).abs() < deg(1e-10) && (x[3] - min.1).abs() < deg(1e-10), "{x:?}");
}

/// An offset slider-crank (the slider on the crank's -x side): nearest the crank pivot with
/// crank and rod folded, `|x| = sqrt((l - r)^2 - e^2)`, the crank pointing away from the slider;
/// farthest with them stretched, `|x| = sqrt((l + r)^2 - e^2)`, the crank pointing at it. The
/// stroke is the difference; in radians, from a start that is no extreme.
#[test]
fn a_sliders_stroke_and_dead_centres_from_the_closed_form() {
    let (r, l, e): (f64, f64, f64) = (1.0, 3.0, 0.4);
    let params = format!("r={r},l={l},e={e}");
    let to = format!("{}", TAU);
    let out = kinloop(&[
        "extremes",
        &shipped("slider_crank.kl"),
        "--from",
        "0",
        "--to",
        &to,
        "--samples",
        "73",
        "--params",
        &params,
        "--columns",
        "x",
    ]);
    let (header, rows) = csv(&out);
    assert_eq!(header, ["column", "unit", "min", "phi at min [rad]", "max", "phi at max [rad]"]);
    assert_eq!(rows.len(), 1);
    let near = ((l - r) * (l - r) - e * e).sqrt();
    let far = ((l + r) * (l + r) - e * e).sqrt();
    let (unit, x) = row(&rows, "x");
    assert_eq!(unit, "length unit");
    assert!((x[0] - -far).abs() < 1e-12 && (x[2] - -near).abs() < 1e-12, "{x:?}");
    assert!((x[1] - f64::atan2(e, -far).rem_euclid(TAU)).abs() < 1e-10, "{x:?}");
    assert!((x[3] - f64::atan2(-e, near).rem_euclid(TAU)).abs() < 1e-10, "{x:?}");
    assert!(((x[2] - x[0]) - (far - near)).abs() < 1e-12, "the stroke: {x:?}");
}

/// The table holds the CSV's numbers to ten significant digits, aligned under a header.
#[test]
fn the_table_is_the_csv_readable() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    // In degrees, and in radians (magnitudes below one, where a fixed count of decimals would
    // write fewer digits).
    let deg = ["extremes", &four_bar, "--from", "0", "--to", "360", "--deg", "--params", params];
    let rad = ["extremes", &four_bar, "--from", "0", "--to", "6.2", "--params", params, "--columns", "beta"];
    let mut below_one = 0;
    for (args, unit) in [(&deg[..], "[deg]"), (&rad[..], "[rad]")] {
        below_one += table_matches_csv(args, unit);
    }
    assert!(below_one > 0, "no number below one: the case that needs it is not tested");
}

/// A value that rounds up to the next power of ten at ten digits keeps ten: the in-line
/// slider-crank's slider at its outer dead centre, `x = -(r + l) = -9.99999999996` (by hand, the
/// crank and the rod in line), is `-10.00000000` in the table; it was `-10.000000000`, eleven
/// digits counted from the value's leading digit before rounding.
#[test]
fn a_value_that_rounds_up_to_a_power_of_ten_has_ten_digits() {
    let slider = shipped("slider_crank.kl");
    let (r, l) = (1.0, 8.99999999996);
    let params = format!("r={r},l={l},e=0");
    let args = ["extremes", &slider, "--params", &params, "--from", "0", "--to", "360", "--deg", "--columns", "x"];
    let (_, rows) = csv(&kinloop(&args));
    let (_, x) = row(&rows, "x");
    // The extreme's value moves to second order only where the analog vanishes (see above).
    assert!((x[0] - -(r + l)).abs() <= 1e-12, "{x:?}");
    table_matches_csv(&args, "[deg]");
    let text = String::from_utf8(kinloop(&[&args[..], &["--table"]].concat()).stdout).expect("utf-8");
    assert!(text.contains(" -10.00000000 "), "{text}");
}

/// The table of `args` holds the CSV's numbers to ten significant digits; the count of those
/// below one in magnitude.
fn table_matches_csv(args: &[&str], unit: &str) -> usize {
    let (_, rows) = csv(&kinloop(args));
    let mut with_table = args.to_vec();
    with_table.push("--table");
    let out = kinloop(&with_table);
    assert!(out.status.success() && out.stderr.is_empty());
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let mut lines = text.lines();
    let header = lines.next().expect("header");
    assert!(header.starts_with("column") && header.contains(&format!("phi at max {unit}")), "{header}");
    let mut below_one = 0;
    for (line, (name, unit, numbers)) in lines.zip(&rows) {
        let cells: Vec<&str> = line.split_whitespace().collect();
        // Units of several words (`length unit`) split: the numbers are the last four cells.
        assert_eq!(cells[0], name);
        assert_eq!(cells[1..cells.len() - 4].join(" "), *unit);
        for (cell, v) in cells[cells.len() - 4..].iter().zip(numbers) {
            let t: f64 = cell.parse().expect("a number");
            // Ten significant digits: within half a unit of the tenth, of the value itself
            // (whatever its magnitude), and ten digits written (zero written exactly).
            assert!((t - v).abs() <= 5e-10 * v.abs(), "{line}: {t} vs {v}");
            let mantissa = cell.trim_start_matches('-').split('e').next().unwrap();
            let digits = mantissa.chars().filter(char::is_ascii_digit).skip_while(|&c| c == '0').count();
            assert!(digits == 10 || *v == 0.0, "{line}: {cell} has {digits} significant digits");
            below_one += usize::from(v.abs() < 1.0 && *v != 0.0);
        }
    }
    below_one
}

/// Usage errors (exit 2) name what is wrong; a sweep that stops at a limit position fails
/// (exit 1) and says so; nothing is written on standard output then.
#[test]
fn errors_and_exit_codes() {
    let four_bar = shipped("four_bar.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    let code = |args: &[&str], code: i32, says: &str| {
        let out = kinloop(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    };
    code(
        &["extremes", &four_bar, "--from", "0", "--to", "1", "--params", params, "--columns", "beta,nope"],
        2,
        "`nope`",
    );
    code(&["extremes", &four_bar, "--from", "1", "--to", "0", "--params", params], 2, "from < to");
    code(
        &["extremes", &four_bar, "--from", "0", "--to", "1", "--samples", "2", "--params", params],
        2,
        "at least 3 samples",
    );
    code(&["extremes", &four_bar, "--from", "0", "--to", "x", "--params", params], 2, "--to x");
    code(&["extremes", &four_bar, "--from", "0", "--to", "1"], 2, "have no value");
    // A non-Grashof rocker cannot turn through: its limit position, where coupler and rocker
    // stretch in line, stops the sweep.
    code(
        &["extremes", &four_bar, "--from", "1.2", "--to", "7.4", "--params", "a=1.5,b=3,c=1,d=3.2"],
        1,
        "limit position",
    );
}

/// Two inputs moving together along the straight path (`--from th1,th2 --to th1,th2`): each
/// extreme with both inputs where it happens, against the compiled mechanism of the same
/// declaration (kinloop's fixture, its own sweep with the rotated sines): the values to the
/// sweeps' agreement (1e-13 of the links' size, see `kinloop-model`'s `sweeps.rs`), an extreme's
/// value to second order in its location, the inputs to the analog's rounding over the
/// curvature (1e-10).
#[test]
fn a_path_of_two_inputs_gives_both_inputs_at_each_extreme() {
    use kinloop::Mechanism;
    use kinloop::analysis::{Column, Sampled};
    let dir = std::env::temp_dir().join(format!("kinloop-cli-extremes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("five_bar.kl");
    std::fs::write(&file, fx::FIVE_BAR_TEXT).expect("write");
    let (from, to) = ([0.0, 1.0], [std::f64::consts::PI, 1.0 + std::f64::consts::FRAC_PI_2]);
    let list = |x: [f64; 2]| format!("{},{}", x[0], x[1]);
    let out = kinloop(&[
        "extremes",
        &file.display().to_string(),
        "--from",
        &list(from),
        "--to",
        &list(to),
        "--samples",
        "91",
    ]);
    let (header, rows) = csv(&out);
    let want = [
        "column",
        "unit",
        "min",
        "th1 at min [rad]",
        "th2 at min [rad]",
        "max",
        "th1 at max [rad]",
        "th2 at max [rad]",
    ];
    assert_eq!(header, want);
    let m = fx::FiveBar::default();
    let compiled = Sampled::path(&m, from, to, 91, m.guess_flat(&from)).expect("compiled sweep");
    assert_eq!(rows.len(), fx::FiveBar::UNKNOWNS.len() + fx::FiveBar::OUTPUTS.len());
    for (name, _, v) in &rows {
        let r = compiled.range(Column::named(name).expect("a column")).expect("range");
        let (at_min, at_max) = (compiled.inputs_at(r.min.x), compiled.inputs_at(r.max.x));
        assert!((v[0] - r.min.value).abs() < 1e-12 && (v[3] - r.max.value).abs() < 1e-12, "{name}: {v:?} {r:?}");
        for (got, want) in v[1..3].iter().zip(at_min).chain(v[4..6].iter().zip(at_max)) {
            assert!((got - want).abs() < 1e-10, "{name}: {v:?} {r:?}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `--columns` that names no column (an empty list, commas only) is a usage error, not an
/// empty table written with success.
#[test]
fn columns_naming_nothing_is_a_usage_error() {
    for list in ["", ",", " , "] {
        let args = ["extremes", &shipped("rhombic_drive.kl"), "--from", "0", "--to", "1", "--columns", list];
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{list:?}: {err}");
        assert!(err.contains("--columns"), "{err}");
        assert!(out.stdout.is_empty());
    }
}

/// `--columns` that names a column twice is a usage error naming it, not a table with the row
/// written twice.
#[test]
fn columns_named_twice_are_a_usage_error() {
    let args = ["extremes", &shipped("rhombic_drive.kl"), "--from", "0", "--to", "1", "--columns", "x_c, phi2,x_c"];
    let out = kinloop(&args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("names `x_c` twice"), "{err}");
    assert!(out.stdout.is_empty());
    // A name of nothing given twice is refused as a name of nothing, the mistake to mend
    // first: it was refused as named twice, and named once next as unknown.
    let args = ["extremes", &shipped("rhombic_drive.kl"), "--from", "0", "--to", "1", "--columns", "p.x,p.x"];
    let out = kinloop(&args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("has no unknown or output `p.x`"), "{err}");
    assert!(!err.contains("twice"), "{err}");
}

/// `--from` and `--to` too close together for the samples' inputs to be told apart (a range of
/// a few units in the last place) are a usage error saying so and what to change, not a failed
/// solve reporting the samples' inputs out of order (`found NaN then NaN` for two inputs).
#[test]
fn a_range_too_short_for_its_samples_is_a_usage_error() {
    let params = "a=1,b=3,c=2.5,d=3.2";
    let four_bar = shipped("four_bar.kl");
    let five_bar = shipped("five_bar.kl");
    for args in [
        vec!["extremes", four_bar.as_str(), "--from", "1", "--to", "1.0000000000000002", "--params", params],
        vec!["extremes", four_bar.as_str(), "--from", "0", "--to", "5e-324", "--params", params],
        vec!["extremes", five_bar.as_str(), "--from", "0,0", "--to", "5e-324,0"],
    ] {
        let out = kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        for what in [&format!("--from {} --to {}", args[3], args[5]), "361 samples", "--samples"] {
            assert!(err.contains(what), "{args:?}: `{what}` missing: {err}");
        }
        assert!(!err.contains("NaN") && !err.contains("increasing"), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// Samples too far apart for the points between them to be searched (20,000 turns in three)
/// are a usage error saying how many samples would do.
#[test]
fn samples_too_far_apart_are_a_usage_error() {
    let slider = shipped("slider_crank.kl");
    let args = ["extremes", &slider, "--params", "r=1,l=3,e=0.4", "--from", "0", "--to", "7200000", "--deg"];
    let out = kinloop(&[&args[..], &["--samples", "3"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("--samples 3: the samples are too far apart") && err.contains("give at least"), "{err}");
    assert!(out.stdout.is_empty());
}

/// The CSV writes its numbers as the other commands do: a slider-crank a hundred orders of
/// magnitude small in `e` notation (Rust's own formatting wrote a hundred zeros), and an end of
/// the range in degrees as given (`60`, not `59.99999999999999`: the crank's 60 degrees in
/// radians and back).
#[test]
fn numbers_are_written_short_and_degrees_as_given() {
    let slider = shipped("slider_crank.kl");
    let out = kinloop(&[
        "extremes",
        &slider,
        "--params",
        "r=1e-100,l=3e-100,e=0.4e-100",
        "--from",
        "0",
        "--to",
        "60",
        "--deg",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!text.contains("0.0000"), "{text}");
    // Over 0..60 degrees the slider only moves inwards: its extremes are the range's ends.
    let x = text.lines().find(|l| l.starts_with("x,")).unwrap_or_else(|| panic!("{text}"));
    let cells: Vec<&str> = x.split(',').collect();
    assert!(cells[2].ends_with("e-100") && cells[4].ends_with("e-100"), "{x}");
    assert_eq!((cells[3], cells[5]), ("60", "0"), "{x}");
}

/// The dwell cam's follower stands still over each dwell of its law, where its extremes are
/// reached over the whole stretch: the table writes one point of it (the lowest position "at
/// 344 degrees", inside the dwell from 300 to 390), and a note names the stretches, at the
/// law's ends (the rise's end located within 1e-8 rad, written to 6 digits).
#[test]
fn a_column_standing_still_has_its_rests_noted() {
    let out = kinloop(&["extremes", &shipped("dwell_cam.kl"), "--from", "90", "--to", "450", "--deg"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let err = String::from_utf8_lossy(&out.stderr);
    let follower = "note: follower.y stands still at 80 length unit from phi = 150 deg to phi = 200 deg, and at 60 \
                    length unit from phi = 300 deg to phi = 390 deg (6 significant digits)";
    assert!(err.contains(follower), "{err}");
    // Every column the cam moves rests with it; `follower.x`, constant, has no note.
    assert!(err.lines().filter(|l| l.starts_with("note: ")).count() == 5 && !err.contains("follower.x"), "{err}");
}

/// Columns that stand still in exact arithmetic, their values rounding (a centred slider's pin
/// height `c.y`, zero; its ratio to the rod `h`, zero; the rod's squared length `ll`, a quantity
/// of no inferred kind, `l^2`), have no note: each stood still "at 0 length unit from phi = 0.1
/// rad to phi = 0.191677 rad, and at 0 ... and 1 more stretches, and at -1.11022e-16 length unit
/// from ...", stretches where their velocity analog happened to round to zero exactly, at values
/// apart by their rounding. The dwell cam's follower, which moves and rests, keeps its note
/// ([`a_column_standing_still_has_its_rests_noted`]).
#[test]
fn a_column_still_to_its_rounding_has_no_rests_noted() {
    let file = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("extremes_still.kl");
    let text = "pub struct SliderStill {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 0, x = -3.0;
        loop oabo: r @ phi == (x, 0) + l @ psi;
        point c = r @ phi - l @ psi;
        output h = (r * sin(phi) - l * sin(psi)) / l;
        output ll = (x - r * cos(phi)) * (x - r * cos(phi)) + r * sin(phi) * r * sin(phi);
    }";
    std::fs::write(&file, text).expect("write the declaration");
    let f = file.display().to_string();
    let (_, rows) = csv(&kinloop(&["extremes", &f, "--from", "0.1", "--to", "6.3", "--samples", "73"]));
    // Rounding: zero within 1e-15 of the mechanism's size (4), `ll` within 1e-15 of its 9.
    for (name, value) in [("c.y", 0.0), ("h", 0.0), ("ll", 9.0)] {
        let (_, v) = row(&rows, name);
        assert!((v[0] - value).abs() <= 1e-14 && (v[2] - value).abs() <= 1e-14, "{name}: {v:?}");
    }
    let _ = std::fs::remove_file(&file);
}

/// Over many turns the note names the first stretches at rest and the last, and counts the
/// others: over a thousand turns it named every one, 655 KB of notes.
#[test]
fn rests_over_many_turns_are_counted_past_the_first() {
    let out = kinloop(&["extremes", &shipped("dwell_cam.kl"), "--from", "90", "--to", "3690", "--deg"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let err = String::from_utf8_lossy(&out.stderr);
    let follower = err.lines().find(|l| l.starts_with("note: follower.y")).unwrap_or_else(|| panic!("{err}"));
    // Two rests a turn over ten turns: four named, 15 counted, the last named.
    let start = "note: follower.y stands still at 80 length unit from phi = 150 deg to phi = 200 deg, and at 60 \
                 length unit from phi = 300 deg to phi = 390 deg, and at 80 length unit from phi = 510 deg";
    assert!(follower.starts_with(start), "{follower}");
    assert!(follower.contains(", and 15 more stretches, and at 60 length unit from phi = 3540 deg to phi = 3630 deg"));
    assert!(follower.len() < 600, "{follower}");
}

/// A time input (`t`, of no inferred kind) has its unit in the header as the sweep's table and
/// `check` write it, `t at min [unit of t]`: it had none (`t at min`), where the sweep wrote
/// `t [unit of t]` and `check` listed `t` alone. The slider of a crank turned at `w` per unit of
/// `t` is farthest out, by hand, at `w t = pi`, `x = -(r + l)`.
#[test]
fn a_time_input_has_its_unit() {
    let file = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("extremes_timed.kl");
    let text = "pub struct Timed {
        params r = 1, l = 3, w = 2;
        input t;
        unknowns psi = 0, x = -2;
        loop oabo: r @ (w * t) == (x, 0) + l @ psi;
    }";
    std::fs::write(&file, text).expect("write the declaration");
    let f = file.display().to_string();
    let (header, rows) = csv(&kinloop(&["extremes", &f, "--from", "0", "--to", "3", "--columns", "x"]));
    assert_eq!(header, ["column", "unit", "min", "t at min [unit of t]", "max", "t at max [unit of t]"]);
    let (_, x) = row(&rows, "x");
    assert!((x[0] - -4.0).abs() <= 1e-12 && (x[1] - std::f64::consts::FRAC_PI_2).abs() <= 1e-10, "{x:?}");
    let table = String::from_utf8(kinloop(&["extremes", &f, "--from", "0", "--to", "3", "--table"]).stdout);
    assert!(table.expect("utf-8").lines().next().is_some_and(|h| h.contains("t at max [unit of t]")));
    let sweep = String::from_utf8(kinloop(&["sweep", &f, "--from", "0", "--to", "1", "--samples", "2"]).stdout);
    assert!(sweep.expect("utf-8").starts_with("t [unit of t],"));
    let check = String::from_utf8(kinloop(&["check", &f]).stdout).expect("utf-8");
    assert!(check.contains("inputs: t [unit of t]\n"), "{check}");
    let _ = std::fs::remove_file(&file);
}

/// A range too long for the points searched between samples is refused before the sweep: with
/// the fewest samples that do, where `--samples` takes that many, otherwise with the `--to` the
/// most samples search. A million turns in three samples swept for ten seconds, then asked for
/// 25,132,741 samples, beyond the 10,000,000 `--samples` takes.
#[test]
fn a_range_too_long_to_search_is_refused_with_advice_that_can_be_followed() {
    let coupler = shipped("coupler_four_bar.kl");
    let out = kinloop(&["extremes", &coupler, "--from", "0", "--to", "6283185", "--samples", "3"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("too long a range for extremes") && err.contains("more than the 10000000"), "{err}");
    let to: f64 =
        err.split("give --to at most ").nth(1).and_then(|r| r.split([' ', '\n']).next()).unwrap().parse().unwrap();
    // About 400,000 turns.
    assert!(to > 2.4e6 && to < 2.6e6, "{err}");
    assert!(!err.contains("give at least"), "{err}");
    assert!(out.stdout.is_empty());
    // 20,000 turns in the default 361 samples: a count that `--samples` takes.
    let out = kinloop(&["extremes", &coupler, "--from", "0", "--to", "125664", "--samples", "361"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    let least: usize = err.split("give at least ").nth(1).and_then(|r| r.split(' ').next()).unwrap().parse().unwrap();
    assert!(least > 361 && least <= 10_000_000, "{err}");
}
