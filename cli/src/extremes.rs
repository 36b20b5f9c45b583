//! `kinloop extremes`: the smallest and largest value of every unknown and output over a sweep
//! of the inputs, with the inputs where each happens, located as the library's analyses locate
//! them (the runtime's sampled sweep over the model: an interior extreme is a root of the
//! velocity analog, refined between samples on the sweep's branch; otherwise an end of the
//! range). Written as CSV with units, or as a readable table.

use crate::csv_rows::unsigned_zero;
use crate::output::unit_suffix;
use crate::solve::{degrees, in_units, led_by, model_inputs, start_failed, text_in_units};
use crate::sweep::range_too_long;
use crate::{Failed, exit, progress, samples};
use kinloop_model::Model;
use kinloop_runtime::analysis::MAX_SEARCH_POINTS;
use kinloop_runtime::paths::sweep::{MAX_INPUT_STEP, MAX_TURNS};
use kinloop_runtime::{Error, Number, QuantityKind};

/// What `kinloop extremes` was asked.
pub struct Request<'a> {
    /// The inputs at the start, one per input.
    pub from: &'a str,
    /// The inputs at the end.
    pub to: &'a str,
    /// Samples, both ends included.
    pub samples: usize,
    /// Angles in degrees.
    pub deg: bool,
    /// The columns to report (names separated by commas); every unknown and output otherwise.
    pub columns: Option<&'a str>,
    /// A readable table instead of CSV.
    pub table: bool,
}

/// One column's extremes, in the units written.
struct Row {
    name: String,
    unit: &'static str,
    min: f64,
    at_min: Vec<f64>,
    max: f64,
    at_max: Vec<f64>,
}

/// The unit a quantity of kind `k` is written in.
fn unit(k: QuantityKind, deg: bool) -> &'static str {
    if deg && k == QuantityKind::Angle { "deg" } else { k.unit() }
}

/// The unit the input `name` of kind `k` is written in: as [`unit`], but `unit of t` for an
/// input of no inferred kind (a time `t`), as `sweep` writes it: such an input had no unit
/// here (`t at min`) where the sweep's table wrote `t [unit of t]`.
fn input_unit(name: &str, k: QuantityKind, deg: bool) -> String {
    if deg && k == QuantityKind::Angle { "deg".to_string() } else { k.input_unit(name).into_owned() }
}

/// A value of kind `k` in the units written (degrees for an angle with `deg`).
fn written(k: QuantityKind, deg: bool, v: f64) -> f64 {
    if deg && k == QuantityKind::Angle { degrees(v) } else { v }
}

/// Samples the range from the declared guess at `from`, locates each column's extremes and
/// writes them to standard output.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    samples::check(req.samples)?;
    let name = model.name().to_string();
    let input_names = model.inputs().to_vec();
    let input_kinds = model.input_kinds().to_vec();
    let from = model_inputs(req.from, &input_kinds, req.deg, "--from")?;
    let to = model_inputs(req.to, &input_kinds, req.deg, "--to")?;
    // Checked here in the units given (the runtime checks them too, in radians).
    if req.samples < 3 {
        return Err(exit::usage(format!("--samples {}: extremes needs at least 3 samples", req.samples)));
    }
    if from.len() == 1 && to[0] <= from[0] {
        return Err(exit::usage(format!(
            "--from {} --to {}: extremes of one input need from < to (the input increasing)",
            req.from, req.to
        )));
    }
    if from == to {
        return Err(exit::usage(format!("--from {} --to {}: the path between them is empty", req.from, req.to)));
    }
    let quantities: Vec<(String, QuantityKind)> = model
        .unknowns()
        .iter()
        .zip(model.unknown_kinds())
        .chain(model.outputs().iter().zip(model.output_kinds()))
        .map(|(n, k)| (n.clone(), *k))
        .collect();
    let columns = match req.columns {
        None => quantities,
        Some(list) => select(&quantities, list, &name)?,
    };
    let failed = |e: &dyn std::fmt::Display| {
        eprintln!("error: {name}: {e}");
        Failed(exit::SOLVE_FAILED)
    };
    let mut guess = vec![0.0; model.unknowns().len()];
    model.guess(&from, &mut guess).map_err(|e| failed(&e))?;
    // The search between samples farther apart than a sweep's step keeps at most
    // `MAX_SEARCH_POINTS` points: a range too long for the samples asked for is refused here,
    // before the sweep (it was refused after sweeping the whole range, ten seconds over a
    // million turns, with a count of samples beyond those `--samples` takes). A range longer
    // than a sweep follows is left to the sweep's own refusal, which says so.
    let least = model.samples_to_search(&from, &to, &guess).map_err(|e| failed(&e))?;
    if least > req.samples && (least - 1) as f64 <= STEPS_IN_RANGE_LIMIT {
        return Err(too_few_to_search(req, least, &from, &to, &input_kinds));
    }
    let bar = progress::bar(&format!("{name}: sampling"), req.samples.saturating_add(columns.len()), req.samples);
    let sampled =
        model.sampled_reporting(&from, &to, req.samples, &guess, model.sweep_config(), |n| bar.set_position(n as u64));
    // The runtime checks the arguments (at least three samples, `to` apart from `from`, and
    // past it for one input; a range of at most the turns a sweep follows): its refusal is a
    // usage error, not a failed solve.
    let sampled = match sampled {
        Ok(sampled) => sampled,
        Err(e) => {
            bar.finish_and_clear();
            if let Some(usage) = range_too_long(&name, &e, req.from, req.to, req.deg) {
                return Err(usage);
            }
            if let Error::InvalidArgument(_) = e {
                // The start's (a loop whose lengths are all zero) where it was solved, in the
                // units given.
                return Err(exit::usage(led_by(&name, &name, &text_in_units(model, e, &from, req.deg))));
            }
            return Err(start_failed(model, &name, e, (&from, Some(&to)), req.deg));
        }
    };
    // Ends a few units in the last place apart: the samples' inputs round to the same numbers
    // (or, the path's length underflowing, to NaN), and no extreme can be located between them.
    // The runtime refuses them per column, in words about its samples: said here, once.
    if !sampled.path_values().windows(2).all(|w| w[0] < w[1]) {
        bar.finish_and_clear();
        return Err(exit::usage(format!(
            "--from {} --to {}: the ends are too close together for {} samples to be told apart (their inputs \
             round to the same numbers): give a longer range, or fewer --samples",
            req.from, req.to, req.samples
        )));
    }
    bar.set_message(format!("{name}: locating extremes"));
    let mut rows = Vec::with_capacity(columns.len());
    let mut notes = Vec::new();
    for (column, kind) in &columns {
        let range = sampled.range(column.as_str()).map_err(|e| {
            bar.finish_and_clear();
            match e {
                // The samples too far apart to search between: more `--samples`.
                Error::InvalidArgument(m) => exit::usage(format!("--samples {}: {m}", req.samples)),
                e => failed(&format!("the extremes of {column}: {}", in_units(e, &input_kinds, req.deg))),
            }
        })?;
        let inputs = |s: f64| -> Vec<f64> {
            let x = sampled.inputs_at(s);
            x.0.iter().zip(&input_kinds).map(|(v, k)| written(*k, req.deg, *v)).collect()
        };
        if let Some(note) = rests_note(&sampled, column, *kind, &input_names, &input_kinds, req.deg) {
            notes.push(note);
        }
        rows.push(Row {
            name: column.clone(),
            unit: unit(*kind, req.deg),
            min: written(*kind, req.deg, range.min.value),
            at_min: inputs(range.min.x),
            max: written(*kind, req.deg, range.max.value),
            at_max: inputs(range.max.x),
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    let input_units: Vec<String> =
        input_names.iter().zip(&input_kinds).map(|(n, k)| input_unit(n, *k, req.deg)).collect();
    let input_units: Vec<&str> = input_units.iter().map(String::as_str).collect();
    let text =
        if req.table { table(&rows, &input_names, &input_units) } else { csv(&rows, &input_names, &input_units) };
    crate::output::text(&text, "the extremes")?;
    for note in notes {
        eprintln!("{note}");
    }
    Ok(())
}

/// The natural steps ([`MAX_INPUT_STEP`]) over the most turns a sweep follows ([`MAX_TURNS`]),
/// with the search's allowance for rounding: a range needing more samples than this is longer
/// than a sweep follows, refused by the sweep itself in those words.
const STEPS_IN_RANGE_LIMIT: f64 = MAX_TURNS * std::f64::consts::TAU / MAX_INPUT_STEP * (1.0 + 1e-5);

/// The usage error of `--samples` too few for the search between them ([`MAX_SEARCH_POINTS`]
/// points at most, a sweep's step apart), `least` the fewest that would do: that count where
/// `--samples` takes it, otherwise the longest range the most samples search, as a `--to`.
fn too_few_to_search(req: &Request, least: usize, from: &[f64], to: &[f64], kinds: &[QuantityKind]) -> Failed {
    let why = format!(
        "extremes searches between samples farther apart than a sweep's step (a quarter radian of an angle \
         input) at points that far apart, and keeps at most {MAX_SEARCH_POINTS} of them"
    );
    if least <= samples::MAX_SAMPLES {
        return exit::usage(format!(
            "--samples {}: the samples are too far apart over --from {} --to {}: {why}; give at least {least} \
             samples, or a shorter range",
            req.samples, req.from, req.to
        ));
    }
    // Beyond the samples taken, the search needs about one sample per step (`least - 1` steps):
    // the most samples cover that fraction of the range, less a thousandth.
    let fraction = 0.999 * (samples::MAX_SAMPLES - 1) as f64 / (least - 1) as f64;
    let ends: Vec<String> = from
        .iter()
        .zip(to)
        .zip(kinds)
        .map(|((a, b), k)| format!("{}", six_digits(written(*k, req.deg, a + (b - a) * fraction))))
        .collect();
    exit::usage(format!(
        "--from {} --to {}: too long a range for extremes: {why}, which over this range needs {least} samples, \
         more than the {} --samples takes; give --to at most {} (or split the range)",
        req.from,
        req.to,
        samples::MAX_SAMPLES,
        ends.join(",")
    ))
}

/// `v` rounded to 6 significant digits, for a note: a rest's ends are located where the
/// velocity analog rounds to zero, which a law leaving the rest smoothly does a little before it
/// switches (a 3-4-5 law's end at 149.9999995 degrees, not 150).
fn six_digits(v: f64) -> f64 {
    crate::numbers::significant(v, 6)
}

/// The stretches at rest a note names one by one before it counts the others (and names the
/// last).
const NOTED_RESTS: usize = 4;

/// Where `column` stands exactly still over stretches of the range (a cam follower's dwells),
/// a note naming them: an extreme reached over a whole stretch is written at one point of it
/// (the follower's lowest position "at 344 degrees", inside a dwell from 300 to 390), which
/// reads as if it were reached there alone. `None` where it has no rest, or rests over the
/// whole range (a constant, or constant to its rounding), or the rests cannot be located.
fn rests_note(
    sampled: &kinloop_model::ModelSampled<'_>,
    column: &str,
    kind: QuantityKind,
    input_names: &[String],
    input_kinds: &[QuantityKind],
    deg: bool,
) -> Option<String> {
    let rests = sampled.rests(column).ok()?;
    let s = sampled.path_values();
    let whole = |r: &kinloop_runtime::analysis::Rest| r.start.x == s[0] && r.end.x == s[s.len() - 1];
    if rests.is_empty() || rests.iter().any(whole) {
        return None;
    }
    let at = |x: f64| -> String {
        let inputs = sampled.inputs_at(x);
        let parts: Vec<String> = input_names
            .iter()
            .zip(input_kinds)
            .zip(inputs.0.iter())
            .map(|((n, k), v)| {
                format!("{n} = {}{}", Number(six_digits(written(*k, deg, *v))), unit_suffix(&input_unit(n, *k, deg)))
            })
            .collect();
        parts.join(", ")
    };
    let u = unit_suffix(unit(kind, deg));
    let stretch = |r: &kinloop_runtime::analysis::Rest| {
        let value = Number(six_digits(written(kind, deg, r.value())));
        format!("at {value}{u} from {} to {}", at(r.start.x), at(r.end.x))
    };
    // Over many turns a cam's follower rests once or twice a turn: the first few stretches and
    // the last say the pattern, a count the others (every one written made a note of 655 KB
    // for a thousand turns).
    let stretches: Vec<String> = if rests.len() > NOTED_RESTS + 1 {
        let mut shown: Vec<String> = rests[..NOTED_RESTS].iter().map(stretch).collect();
        shown.push(format!("{} more stretches", rests.len() - NOTED_RESTS - 1));
        shown.push(stretch(&rests[rests.len() - 1]));
        shown
    } else {
        rests.iter().map(stretch).collect()
    };
    Some(format!(
        "note: {column} stands still {} (6 significant digits); an extreme reached over such a stretch is written \
         at one point of it",
        stretches.join(", and ")
    ))
}

/// The columns named in `list` (unknowns or outputs), in its order; at least one.
fn select(
    quantities: &[(String, QuantityKind)],
    list: &str,
    name: &str,
) -> Result<Vec<(String, QuantityKind)>, Failed> {
    // An empty list (an unset shell variable) would write an empty table with success.
    if list.split(',').all(|c| c.trim().is_empty()) {
        let known: Vec<&str> = quantities.iter().map(|(n, _)| n.as_str()).collect();
        return Err(exit::usage(format!("--columns `{list}` names no column (they are: {})", known.join(", "))));
    }
    let names: Vec<&str> = list.split(',').map(str::trim).filter(|c| !c.is_empty()).collect();
    // A name of nothing is refused before a name given twice: `p.x,p.x` of a mechanism without
    // `p` was "named twice", and naming it once was refused next.
    let columns = names
        .iter()
        .map(|&c| {
            quantities.iter().find(|(n, _)| n == c).cloned().ok_or_else(|| {
                let known: Vec<&str> = quantities.iter().map(|(n, _)| n.as_str()).collect();
                let look = crate::names::look_alike(c, &known);
                exit::usage(format!("{name} has no unknown or output `{c}`{look} (they are: {})", known.join(", ")))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    // A column named twice would be a row written twice.
    if let Some(c) = names.iter().enumerate().find(|(k, c)| names[..*k].contains(c)).map(|(_, c)| c) {
        return Err(exit::usage(format!("--columns `{list}` names `{c}` twice: name each column once")));
    }
    Ok(columns)
}

/// The header's cells: the column, its unit, the minimum and the inputs there, the maximum and
/// the inputs there (`phi at min [deg]`).
fn header(inputs: &[String], units: &[&str]) -> Vec<String> {
    let at = |which: &str| -> Vec<String> {
        inputs
            .iter()
            .zip(units)
            .map(|(n, u)| if u.is_empty() { format!("{n} at {which}") } else { format!("{n} at {which} [{u}]") })
            .collect()
    };
    let mut h = vec!["column".to_string(), "unit".to_string(), "min".to_string()];
    h.extend(at("min"));
    h.push("max".to_string());
    h.extend(at("max"));
    h
}

/// A row's cells, numbers as given by `number`.
fn cells(r: &Row, number: impl Fn(f64) -> String) -> Vec<String> {
    let mut c = vec![r.name.clone(), r.unit.to_string(), number(r.min)];
    c.extend(r.at_min.iter().map(|&v| number(v)));
    c.push(number(r.max));
    c.extend(r.at_max.iter().map(|&v| number(v)));
    c
}

/// CSV: numbers in their shortest form that reads back exactly, as the other commands write
/// them (`1e-100`, where `f64`'s own formatting writes a hundred zeros; a zero without a sign).
fn csv(rows: &[Row], inputs: &[String], units: &[&str]) -> String {
    let mut s = header(inputs, units).join(",") + "\n";
    for r in rows {
        s += &(cells(r, |v| Number(unsigned_zero(v)).to_string()).join(",") + "\n");
    }
    s
}

/// `v` to ten significant digits: in positional notation from 1e-3 to 1e6 (and zero), in
/// scientific notation otherwise (subnormal, tiny, huge, not finite). The notation and the
/// decimals follow the leading digit of `v` rounded to ten digits, not of `v`: a value just
/// below a power of ten that rounds up to it (`9.99999999996`) has its leading digit one place
/// higher, and counting from `v`'s own wrote eleven digits (`10.000000000`). Zero is written
/// without a sign (`-0.0`, as `-0`, read as a value below zero).
fn ten_digits(v: f64) -> String {
    // `+ 0.0` turns a negative zero into zero and leaves every other value as it is.
    let v = v + 0.0;
    let scientific = format!("{v:.9e}");
    // The exponent of the value rounded to ten digits (none: not finite, written as it is).
    let Some(exponent) = scientific.split_once('e').and_then(|(_, e)| e.parse::<i32>().ok()) else {
        return scientific;
    };
    if v == 0.0 || (-3..6).contains(&exponent) {
        // The leading digit's place is `exponent`, from -3 to 5 here (0 for zero): nine more
        // after it.
        let digits = (9 - exponent).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        scientific
    }
}

/// A table aligned in columns, numbers to ten significant digits.
fn table(rows: &[Row], inputs: &[String], units: &[&str]) -> String {
    let lines: Vec<Vec<String>> =
        std::iter::once(header(inputs, units)).chain(rows.iter().map(|r| cells(r, ten_digits))).collect();
    let widths: Vec<usize> =
        (0..lines[0].len()).map(|c| lines.iter().map(|l| l[c].chars().count()).max().unwrap_or(0)).collect();
    let mut s = String::new();
    for l in &lines {
        let padded: Vec<String> = l
            .iter()
            .zip(&widths)
            .enumerate()
            // Names and units to the left, numbers to the right.
            .map(|(c, (v, w))| if c < 2 { format!("{v:<w$}") } else { format!("{v:>w$}") })
            .collect();
        s += padded.join("  ").trim_end();
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::ten_digits;

    /// The significant digits of a number as written (without sign, point, exponent and
    /// leading zeros).
    fn significant(s: &str) -> usize {
        let mantissa = s.split('e').next().unwrap();
        mantissa.chars().filter(char::is_ascii_digit).skip_while(|&c| c == '0').count()
    }

    #[test]
    fn ten_significant_digits_at_every_magnitude() {
        for v in [1e-3, 0.0012345678901, 0.5, 0.123456789012, -0.987654321098, 1.0, 4.56789012345, 99999.5, 123456.789]
        {
            let s = ten_digits(v);
            assert_eq!(significant(&s), 10, "{v}: {s}");
            let back: f64 = s.parse().unwrap();
            assert!((back - v).abs() <= 5e-10 * v.abs(), "{v}: {s}");
        }
        assert_eq!(ten_digits(0.5), "0.5000000000");
        assert_eq!(ten_digits(0.001), "0.001000000000");
        assert_eq!(ten_digits(0.0), "0.000000000");
        // Subnormal, tiny and huge magnitudes: scientific, ten digits still.
        assert_eq!(ten_digits(5e-324), "4.940656458e-324");
        assert_eq!(ten_digits(1.5e-4), "1.500000000e-4");
        assert_eq!(ten_digits(1e6), "1.000000000e6");
        assert_eq!(ten_digits(-2.5e10), "-2.500000000e10");
        assert_eq!(ten_digits(f64::INFINITY), "inf");
    }

    /// A value that rounds up to the next power of ten has ten digits counted from that power:
    /// `9.99999999996` is `10.00000000` (eleven digits, `10.000000000`, before), and the notation
    /// changes where the rounded value crosses 1e6 or 1e-3, not the value.
    #[test]
    fn ten_digits_where_rounding_carries_to_the_next_power_of_ten() {
        for (v, written) in [
            (9.99999999996, "10.00000000"),
            (-9.99999999996, "-10.00000000"),
            (99999.9999999, "100000.0000"),
            (0.0999999999996, "0.1000000000"),
            (999999.99999, "1.000000000e6"),
            (0.00099999999996, "0.001000000000"),
            (9.999999999e-4, "9.999999999e-4"),
        ] {
            let s = ten_digits(v);
            assert_eq!(s, written, "{v}");
            assert_eq!(significant(&s), 10, "{v}: {s}");
        }
    }

    /// A zero is written without a sign: `-0.000000000` read as a value below zero.
    #[test]
    fn a_negative_zero_is_written_as_zero() {
        assert_eq!(ten_digits(-0.0), "0.000000000");
        assert_eq!(ten_digits(-1e-300), "-1.000000000e-300");
    }
}
