//! `kinloop sweep`: a branch-safe sweep of the inputs from `--from` to `--to` as CSV with units,
//! the runtime's own sweep over the model (the events it meets listed on standard error, or
//! written to `--events`).

use crate::csv_rows::CsvRows;
use crate::numbers::between;
use crate::own_columns::{self, Own};
use crate::solve::{degrees, factors, model_inputs, parse_inputs, solve_failed, start_failed, units};
use crate::{Failed, exit, output, progress, samples};
use kinloop_model::Model;
use kinloop_runtime::dims::KinState;
use kinloop_runtime::{Error, Event, Number, QuantityKind, Table};
use std::io::Write;
use std::path::Path;

/// What `kinloop sweep` was asked.
pub struct Request<'a> {
    /// The inputs at the start, one per input.
    pub from: &'a str,
    /// The inputs at the end.
    pub to: &'a str,
    /// Samples, both ends included.
    pub samples: usize,
    /// Angles in degrees.
    pub deg: bool,
    /// Where to write the events (standard error otherwise).
    pub events: Option<&'a Path>,
}

/// Sweeps from the declared guess at `from` and writes the table to standard output, each
/// state's row as soon as it is solved. A sweep that stops (a limit position, no assembly) has
/// written the states before the stop; it writes the events and the reason on standard error,
/// and fails. One whose start cannot be solved writes no table, not even its header.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    samples::check(req.samples)?;
    events_columns(model, "sweep", req.events)?;
    let kinds: Vec<QuantityKind> = model.quantities().iter().map(|(_, k)| *k).collect();
    let ni = model.inputs().len();
    let from = model_inputs(req.from, &kinds[..ni], req.deg, "--from")?;
    let to = model_inputs(req.to, &kinds[..ni], req.deg, "--to")?;
    too_few_samples(req, from != to)?;
    // Every input's ends as given (an angle's in degrees with `--deg`, else in the model's
    // units), whose samples the table writes.
    let (a, b) = (parse_inputs(req.from, ni, "--from")?, parse_inputs(req.to, ni, "--to")?);
    let given: Vec<(f64, f64)> = a.into_iter().zip(b).collect();
    let name = model.name().to_string();
    let factors = factors(model, &kinds, req.deg);
    let columns = model.columns();
    let base = units(model, &kinds, req.deg);
    let failed = |e: &dyn std::fmt::Display| {
        eprintln!("error: {name}: {e}");
        Failed(exit::SOLVE_FAILED)
    };
    if let Some(usage) = samples_too_fine(model, req, &from, &to, &kinds[..ni]) {
        return Err(usage);
    }
    let mut guess = vec![0.0; model.unknowns().len()];
    model.guess(&from, &mut guess).map_err(|e| failed(&e))?;
    // The runtime checks the arguments (at least one sample, `to` apart from `from` for
    // several): its refusal is a usage error, not a failed solve.
    let mut sweep = model.sweep(&from, &to, req.samples, &guess).map_err(|e| match e {
        Error::InvalidArgument(_) => exit::usage(format!("{name}: {e}")),
        e => solve_failed(&name, e, &kinds[..ni], req.deg),
    })?;
    let units = Units { factors, given, last: req.samples.saturating_sub(1).max(1) };
    // The first sample, before anything is created: a range longer than a sweep follows is
    // refused there, a usage error.
    // A start that cannot be solved (no assembly, a singular position) fails there too, as
    // `trace`, `extremes` and `solve` fail: no state was solved, so no table is written (it
    // wrote the header alone, a table of no rows, before the error).
    let first = match sweep.next_ref().map(|r| r.map(|k| k.table_row())) {
        Some(Err(e)) => match range_too_long(&name, &e, req.from, req.to, req.deg) {
            Some(usage) => return Err(usage),
            None => {
                // The sweep lends the model: given back for the note on where it assembles.
                drop(sweep);
                return Err(start_failed(model, &name, e, (&from, Some(&to)), req.deg));
            }
        },
        first => first,
    };
    // The second sample too, where the first solved: a sweep whose input's doubles are too
    // coarse for its steps (`--from 1e17`) fails at its first step, a usage error said before
    // anything is written (it wrote the header and the first row, then failed with exit code 2).
    let second = match &first {
        Some(Ok(_)) if req.samples > 1 => match sweep.next_ref() {
            Some(Err(e @ Error::InputTooCoarse { .. })) => {
                return Err(solve_failed(&name, e, &kinds[..ni], req.deg));
            }
            state => Some(state.map(|r| r.map(|k| k.table_row()))),
        },
        _ => None,
    };
    // Created before the rest of the sweep runs: a path that cannot be written stops before
    // any output.
    let events_file = output::created(req.events, "the events file")?;
    let bar = progress::bar(&format!("{name}: sweeping"), req.samples, req.samples);
    let header = Table::new(columns).with_units(&base.iter().map(|(n, u)| (n.as_str(), *u)).collect::<Vec<_>>());
    // Buffered: a row is a write of its own, where standard output would pass each line on by
    // itself.
    let out = std::io::BufWriter::new(std::io::stdout().lock());
    // The states solved already, the first last (taken first).
    let mut pending: Vec<_> = second.into_iter().chain([first]).collect();
    let next = || {
        let state = match pending.pop() {
            Some(solved) => solved,
            None => sweep.next_ref().map(|r| r.map(|k| k.table_row())),
        };
        bar.inc(1);
        state
    };
    let streamed = CsvRows::new(out, &header)
        .and_then(|mut rows| stream(&mut rows, &units, next).and_then(|stop| rows.finish().map(|()| stop)));
    bar.finish_and_clear();
    let stop = match streamed {
        Ok(stop) => stop,
        // A table that cannot be written (standard output full, its reader gone) fails the
        // command before the events are: the events file it made is removed again (it was
        // left empty).
        Err(e) => {
            if let Some(file) = events_file {
                file.abandon();
            }
            return Err(output::failed("the table", e));
        }
    };
    let events = sweep.events().to_vec();
    drop(sweep);
    output::write_into(events_file, "the events", |file| write_events(model, &events, req.deg, file))?;
    match stop {
        Some(e) => Err(solve_failed(&name, e, &kinds[..ni], req.deg)),
        None => Ok(()),
    }
}

/// How a sweep's states are written: each state's row (in the order of `table_row`) times
/// the factors of the units written, its inputs the samples' own values.
struct Units {
    /// Per column, the factor from the model's units to those written.
    factors: Vec<f64>,
    /// Per input, its ends as given, in the units written.
    given: Vec<(f64, f64)>,
    /// The index of the last sample (1 for a sweep of one sample).
    last: usize,
}

impl Units {
    /// The row written for the state `state` of sample `s`.
    fn row(&self, s: usize, state: &[f64]) -> Vec<f64> {
        let mut row: Vec<f64> = state.iter().zip(&self.factors).map(|(v, f)| v * f).collect();
        // Each input: the sample's value between the ends given, as `solve` writes the input
        // given. Not an angle's radians times `180/π` with `--deg` (`59.99999999999999` for the
        // sample at 60), nor the doubles' own steps in the model's units (`0.44999999999999996`
        // between 0.3 and 0.6, `0.9000000000000001` for `--to 0.9` itself). Exact where the
        // samples fall on round numbers.
        for (i, &(a, b)) in self.given.iter().enumerate() {
            row[i] = sample_as_given(a, b, s, self.last, row[i]);
        }
        row
    }
}

/// The value written for sample `s` of the equally spaced samples from `a` (sample 0) to `b`
/// (sample `last`), given in the units written (an angle's degrees with `--deg`, else the
/// model's units), whose state is at `written` (in those units: an angle's radians times
/// `180/π`, a length or radians as solved): the sample's value between the ends given
/// ([`between`]: `60`, where the product is `59.99999999999999`; `0.45` between 0.3 and 0.6,
/// where the solved input is `0.44999999999999996`; the ends themselves). Only where the state
/// is at the sample to the rounding: a sample at a singular crossing passed
/// (`--through-crossings`) is the first well-conditioned state past it, whose own input is
/// written.
pub(crate) fn sample_as_given(a: f64, b: f64, s: usize, last: usize, written: f64) -> f64 {
    let given = between(a, b, s, last);
    let rounding = 1e-9 * ((b - a) / last as f64).abs() + 8.0 * f64::EPSILON * given.abs();
    // Ends near the largest `f64`: the products overflow, the product stays.
    if given.is_finite() && (given - written).abs() <= rounding { given } else { written }
}

/// Writes the row of each state `next` solves (in `units`) to `rows` as soon as it is solved,
/// keeping none: the memory of a sweep does not grow with its samples, and a reader that is
/// gone (`kinloop sweep ... | head`) stops the sweep at the next row, not at its end. Returns
/// the error that stopped the sweep (`None`: it ran to its end); a failed write is the `Err`.
fn stream<W: Write, E>(
    rows: &mut CsvRows<W>,
    units: &Units,
    mut next: impl FnMut() -> Option<Result<Vec<f64>, E>>,
) -> std::io::Result<Option<E>> {
    let mut s = 0;
    while let Some(state) = next() {
        match state {
            Ok(state) => rows.row(&units.row(s, &state))?,
            Err(e) => return Ok(Some(e)),
        }
        s += 1;
    }
    Ok(None)
}

/// The usage error of too few `--samples` for the range, in the command line's terms. Both ends
/// are rows: one sample cannot be two different inputs (it wrote the row at `--from` alone,
/// `--to` unread), and none writes nothing. `--samples 0` was refused by the library's own
/// message, "a sweep needs at least one sample", which sent a reader with two different ends to
/// a second refusal at 1. Several samples at one input (`--to` equal to `--from`) are refused
/// too, saying to give another `--to` or a single sample.
fn too_few_samples(req: &Request, two_ends: bool) -> Result<(), Failed> {
    // Several samples at one input: the runtime's refusal said it in its own terms ("a sweep with
    // several samples needs `to` different from `from`"), naming no option and no way out.
    if !two_ends && req.samples > 1 {
        return Err(exit::usage(format!(
            "--samples {} from --from {} to --to {}, the same inputs: give --to different from --from, or --samples 1 \
             for the state at --from alone",
            req.samples, req.from, req.to
        )));
    }
    let least = if two_ends { 2 } else { 1 };
    if req.samples >= least {
        return Ok(());
    }
    let rows = if req.samples == 0 { "no row" } else { "one row" };
    Err(exit::usage(match two_ends {
        true => format!(
            "--samples {} writes {rows}, and the table's rows include both ends (--from {} and --to {}): give at \
             least 2 samples, or --to equal to --from",
            req.samples, req.from, req.to
        ),
        false => format!("--samples 0 writes no row: give at least 1 (the state at --from {})", req.from),
    }))
}

/// The usage error of samples closer together than the inputs' doubles can place them: where
/// even the input that resolves them best (of those that move) has doubles more than half its
/// change between samples apart, at the end of the range farther from zero. There samples round
/// to one input and the table repeats rows (100,000 samples over `1e12 .. 1e12 + 1`, doubles
/// `1.2e-4` apart, were 8,193 distinct inputs), and the samples asked for cannot be written.
/// Closer, each sample rounds by at most a quarter of the spacing: distinct, in order, and solved
/// at the input its row writes. `None` for a single sample or inputs fine for the spacing.
fn samples_too_fine(model: &Model, req: &Request, from: &[f64], to: &[f64], kinds: &[QuantityKind]) -> Option<Failed> {
    let intervals = req.samples.checked_sub(1).filter(|&n| n > 0)? as f64;
    let (i, apart, change) = from
        .iter()
        .zip(to)
        .enumerate()
        .filter_map(|(i, (&a, &b))| {
            let far = a.abs().max(b.abs());
            let change = ((b - a) / intervals).abs();
            (change > 0.0 && change.is_finite()).then(|| (i, far.next_up() - far, change))
        })
        .min_by(|x, y| (x.1 / x.2).total_cmp(&(y.1 / y.2)))?;
    if apart <= 0.5 * change {
        return None;
    }
    let (apart, change, unit) = match (req.deg, kinds[i]) {
        (true, QuantityKind::Angle) => (apart.to_degrees(), change.to_degrees(), " deg"),
        _ => (apart, change, ""),
    };
    Some(exit::usage(format!(
        "--from {} --to {}: {} samples are closer together than input `{}` can tell apart there (its doubles are \
         {apart:e}{unit} apart, the samples {change:e}{unit}): samples would repeat; give fewer --samples or a longer \
         range, or reduce a periodic input by whole turns",
        req.from,
        req.to,
        req.samples,
        model.inputs()[i]
    )))
}

/// The usage error of a range longer than a sweep follows ([`Error::RangeTooLong`], which a
/// sweep or a trace finds before its first step): how far apart `--from` and `--to` may be, in the units
/// given. `None` for any other error.
///
/// The sweep counts the turns in the unit its steps are measured in (a radian for an input that
/// the equations turn through sines and cosines; for another, even an angle taken within its
/// turn by `wrap`, the unit the equations give it), so the span allowed is said in the units
/// given, from the turns counted: they grow in proportion to the span. It was said as `2 pi 1e6`
/// radians whatever the input, and a dwell cam's `--to 6283185` was refused with the advice to
/// give at most 6283185.3.
pub(crate) fn range_too_long(name: &str, e: &Error, from: &str, to: &str, deg: bool) -> Option<Failed> {
    let &Error::RangeTooLong { turns, max_turns, .. } = e else { return None };
    let numbers = |s: &str| s.split(',').map(|v| v.trim().parse::<f64>().ok()).collect::<Option<Vec<f64>>>();
    let unit = if deg { " in the units given (degrees for an angle)" } else { " in the units given" };
    let allowed = match (numbers(from), numbers(to)) {
        (Some(a), Some(b)) if a.len() == b.len() && turns.is_finite() && turns > 0.0 => {
            let fraction = max_turns / turns;
            let spans: Vec<f64> =
                a.iter().zip(&b).map(|(a, b)| eight_digits((b - a).abs() * fraction, true, 1e-11)).collect();
            // Each end on its own side of `--from`, rounded towards it: the span it makes is
            // within the one allowed.
            let ends: Vec<String> = a
                .iter()
                .zip(&b)
                .zip(&spans)
                .map(|((a, b), span)| match b < a {
                    true => format!("{}", eight_digits(a - span, false, 0.0)),
                    false => format!("{}", eight_digits(a + span, true, 0.0)),
                })
                .collect();
            match spans.as_slice() {
                [span] => format!("at most {span} apart{unit} (--to {})", ends[0]),
                _ => format!("at most --to {}{unit}", ends.join(",")),
            }
        }
        _ => format!("at most {max_turns:e} turns apart"),
    };
    Some(exit::usage(format!(
        "{name}: --from {from} --to {to} spans {turns:.3e} turns of the inputs as a sweep counts them (a turn: 2 pi \
         of the unit its steps are measured in, a radian for an input in sines and cosines), more than the \
         {max_turns:e} turns a sweep or a trace follows: give --from and --to {allowed}; split a longer range, or \
         reduce a periodic input by whole turns"
    )))
}

/// `v` to eight significant digits: the decimal nearest `v`, unless it lies beyond `v` (above it
/// where `not_above`, else below) by more than `slack` of `v`, then the next on the other side.
/// So a span said as allowed (`slack` `1e-11`, within what the range's check allows for the
/// rounding of the inputs given), or an end that keeps the span within it (`slack` 0), is
/// allowed, and prints as written (`6283185.3`, `360000000`): the decimal is made by a division
/// (or a product) by an exact power of ten, not by a product by `1e-1`, which gave
/// `6283185.300000001`.
fn eight_digits(v: f64, not_above: bool, slack: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let k = 7 - v.abs().log10().floor() as i32;
    let pow = 10f64.powi(k.abs());
    let scaled = if k >= 0 { v * pow } else { v / pow };
    let (near, slack) = (scaled.round(), slack * scaled.abs());
    let within = if not_above { near <= scaled + slack } else { near >= scaled - slack };
    let d = match (within, not_above) {
        (true, _) => near,
        (false, true) => scaled.floor(),
        (false, false) => scaled.ceil(),
    };
    let r = if k >= 0 { d / pow } else { d * pow };
    if r.is_finite() && pow.is_finite() { r } else { v }
}

/// The columns the events' file writes before the inputs and the unknowns.
const EVENT_COLUMNS: [&str; 2] = ["kind", "tau"];

/// Refuses an input or unknown named as one of the events' file's own columns where `kinloop
/// COMMAND` (`sweep`, `trace`) is to write one (`events`): its header would name two columns
/// alike (`kind,tau,tau [rad]`). Written on standard error, the events name no columns.
pub(crate) fn events_columns(model: &Model, command: &str, events: Option<&Path>) -> Result<(), Failed> {
    if events.is_none() {
        return Ok(());
    }
    let command = format!("kinloop {command} --events");
    let own = Own {
        command: &command,
        columns: &EVENT_COLUMNS,
        beside: "inputs' and unknowns'",
        rename_to: "",
        written: "the events file",
    };
    let inputs = model.inputs().iter().map(|n| ("input", n.as_str()));
    let unknowns = model.unknowns().iter().map(|n| ("unknown", n.as_str()));
    own_columns::check(&own, model.name(), inputs.chain(unknowns))
}

/// The events as CSV (`kind,tau [1],` the inputs and the unknowns, in the sweep's units, named
/// `name [unit]` as the table's columns) into `file` (`--events`), or one line each on
/// standard error.
pub(crate) fn write_events(
    model: &Model,
    events: &[Event],
    deg: bool,
    file: Option<std::fs::File>,
) -> std::io::Result<()> {
    let kinds: Vec<QuantityKind> = model.quantities().iter().map(|(_, k)| *k).collect();
    // Written as the table writes its numbers (a zero without a sign), an angle in degrees as
    // the trace's rows and the error that stops a sweep at the event write it: the shortest
    // decimal that reads back to its radians (`v.to_degrees()` may end a unit in the last
    // place off, and wrote the same limit position as 81.90928802268786 here and
    // 81.90928802268785 in the error).
    let angle = |k: QuantityKind, v: f64| {
        Number(crate::csv_rows::unsigned_zero(if deg && k == QuantityKind::Angle { degrees(v) } else { v }))
    };
    let ni = model.inputs().len();
    let Some(file) = file else {
        for e in events {
            let at: Vec<String> = model
                .inputs()
                .iter()
                .zip(&e.x)
                .zip(&kinds)
                .map(|((n, v), k)| format!("{n} = {}", angle(*k, *v)))
                .collect();
            eprintln!("event: {} at {} (fraction {} of the path)", e.kind, at.join(", "), Number(e.tau));
        }
        return Ok(());
    };
    let mut w = std::io::BufWriter::new(file);
    let columns = ni + model.unknowns().len();
    // The header the table writes for the same columns (`name [unit]`, the name alone where
    // the unit is empty), ended by its newline.
    let base = &units(model, &kinds, deg)[..columns];
    let header = Table::new(base.iter().map(|(n, _)| n.clone()).collect());
    let header = header.with_units(&base.iter().map(|(n, u)| (n.as_str(), *u)).collect::<Vec<_>>());
    let mut line = Vec::new();
    header.write_csv(&mut line)?;
    // `tau`, the fraction of the path, is a pure number: `[1]`, as the table writes one.
    let [kind, tau] = EVENT_COLUMNS;
    write!(w, "{kind},{tau} [{}],{}", QuantityKind::Dimensionless.unit(), String::from_utf8_lossy(&line))?;
    for e in events {
        let values: Vec<String> =
            e.x.iter().chain(&e.q).zip(&kinds[..ni + e.q.len()]).map(|(v, k)| angle(*k, *v).to_string()).collect();
        writeln!(w, "{},{},{}", e.kind, Number(e.tau), values.join(","))?;
    }
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::{CsvRows, Units, stream, write_events};
    use kinloop_model::Model;
    use kinloop_runtime::dims::KinState;
    use kinloop_runtime::{Event, EventKind, Table};
    use std::cell::Cell;
    use std::io::{self, Write};
    use std::rc::Rc;

    const FOUR_BAR: &str = "pub struct FourBar {
        params a = 1, b = 3, c = 2.5, d = 3.2;
        input phi;
        unknowns psi = 0.6, theta = 1.9;
        loop abcd: a @ phi + b @ psi == (d, 0) + c @ theta;
    }";

    /// A standard output that notes, at each write, how many states the sweep had solved; and
    /// fails the write that would take it past `capacity` bytes (a full disk, a reader gone).
    struct Recorder {
        solved: Rc<Cell<usize>>,
        bytes: Vec<u8>,
        /// Per write: the states solved then, and the bytes written once it is done.
        writes: Vec<(usize, usize)>,
        capacity: usize,
    }

    impl Write for Recorder {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            if self.bytes.len() + buf.len() > self.capacity {
                return Err(io::Error::new(io::ErrorKind::BrokenPipe, "the reader is gone"));
            }
            self.bytes.extend_from_slice(buf);
            self.writes.push((self.solved.get(), self.bytes.len()));
            Ok(buf.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    /// Streams a sweep of the four-bar over `samples` samples into a [`Recorder`] of
    /// `capacity` bytes: what it recorded, the states solved in all, and the result.
    fn sweep_into(samples: usize, capacity: usize) -> (Recorder, usize, io::Result<bool>) {
        let mut model = Model::read("four_bar.kl", FOUR_BAR).expect("the declaration reads");
        let columns = model.columns();
        let units = Units { factors: vec![1.0; columns.len()], given: vec![(0.0, 1.0)], last: samples - 1 };
        let mut sweep = model.sweep(&[0.0], &[1.0], samples, &[0.6, 1.9]).expect("a sweep");
        let solved = Rc::new(Cell::new(0));
        let mut sink = Recorder { solved: solved.clone(), bytes: Vec::new(), writes: Vec::new(), capacity };
        let mut rows = CsvRows::new(&mut sink, &Table::new(columns)).expect("the header fits");
        let next = || {
            let state = sweep.next_ref()?.map(|k| k.table_row());
            solved.set(solved.get() + 1);
            Some(state)
        };
        let result = stream(&mut rows, &units, next).map(|stop: Option<kinloop_runtime::Error>| stop.is_none());
        drop(rows);
        (sink, solved.get(), result)
    }

    /// Each row reaches the output when its state is solved, before the next one is: a sweep
    /// that kept its rows to write them at the end would write them all after the last state.
    #[test]
    fn each_row_is_written_before_the_next_state_is_solved() {
        let samples = 6;
        let (recorder, solved, result) = sweep_into(samples, usize::MAX);
        assert!(matches!(result, Ok(true)), "the sweep runs to its end");
        assert_eq!(solved, samples);
        let text = String::from_utf8(recorder.bytes.clone()).expect("utf-8");
        let ends: Vec<usize> = text.match_indices('\n').map(|(i, _)| i + 1).collect();
        assert_eq!(ends.len(), samples + 1, "a header and a row per sample: {text}");
        for (line, &end) in ends.iter().enumerate() {
            // The write that completed the line, and the states solved when it was made.
            let &(when, _) = recorder.writes.iter().find(|(_, len)| *len >= end).expect("written");
            assert_eq!(when, line, "line {line} (the header is line 0) written after {when} states: {text}");
        }
    }

    /// A write that fails stops the sweep there: no state is solved past the row that could
    /// not be written, and the failure is the result.
    #[test]
    fn a_failed_write_stops_the_sweep_at_once() {
        let (full, _, _) = sweep_into(3, usize::MAX);
        // The bytes of the header and the first row: the second row is the write that fails.
        let lines: Vec<usize> =
            full.bytes.iter().enumerate().filter(|(_, b)| **b == b'\n').map(|(i, _)| i + 1).collect();
        let header_and_one_row = lines[1];
        let (recorder, solved, result) = sweep_into(1000, header_and_one_row);
        assert_eq!(result.expect_err("the second row does not fit").kind(), io::ErrorKind::BrokenPipe);
        assert_eq!(solved, 2, "the sweep went on past the row that failed");
        assert_eq!(recorder.bytes.len(), header_and_one_row);
    }

    /// The events' file writes its numbers as the table does: in exponent notation far from
    /// ordinary magnitudes (not 300 zeros), `tau` too, angles in degrees with `--deg`.
    #[test]
    fn events_write_numbers_as_the_table_does() {
        let model = Model::read("four_bar.kl", FOUR_BAR).expect("the declaration reads");
        let event =
            Event { kind: EventKind::LimitPosition, x: vec![1e-300], tau: 2.5e-17, q: vec![0.5, 1e300], block: None };
        let path = std::env::temp_dir().join(format!("kinloop-events-{}.csv", std::process::id()));
        for (deg, row) in [
            (false, "limit position,2.5e-17,1e-300,0.5,1e300"),
            (true, "limit position,2.5e-17,5.729577951308232e-299,28.64788975654116,5.729577951308233e301"),
        ] {
            write_events(
                &model,
                std::slice::from_ref(&event),
                deg,
                Some(std::fs::File::create(&path).expect("a file")),
            )
            .expect("written");
            let text = std::fs::read_to_string(&path).expect("read back");
            assert_eq!(text.lines().nth(1), Some(row), "{text}");
        }
        let _ = std::fs::remove_file(&path);
    }

    /// The events' file holds a column of text, `kind`, which `Table::read_csv` refuses naming
    /// it (as its documentation says); the columns after it are written as a table's, and
    /// without `kind` the file reads back as one: names, units and every value to the bit.
    #[test]
    fn events_are_a_table_but_for_their_kind() {
        let model = Model::read("four_bar.kl", FOUR_BAR).expect("the declaration reads");
        let events = [
            Event { kind: EventKind::LimitPosition, x: vec![1.9446], tau: 0.125, q: vec![-0.0, 5e-324], block: None },
            Event {
                kind: EventKind::SingularCrossing,
                x: vec![1e300],
                tau: 1.0,
                q: vec![0.1 + 0.2, -1e-7],
                block: None,
            },
        ];
        let path = std::env::temp_dir().join(format!("kinloop-events-table-{}.csv", std::process::id()));
        write_events(&model, &events, false, Some(std::fs::File::create(&path).expect("a file"))).expect("written");
        let text = std::fs::read_to_string(&path).expect("read back");
        let _ = std::fs::remove_file(&path);
        let err = Table::read_csv(text.as_bytes()).expect_err("a column of text").to_string();
        assert!(err.contains("column `kind` holds `limit position`"), "{err}");
        let numbers: String = text.lines().map(|l| l.split_once(',').expect("a kind").1.to_string() + "\n").collect();
        let table = Table::read_csv(numbers.as_bytes()).unwrap_or_else(|e| panic!("{e}: {numbers}"));
        assert_eq!(table.columns, ["tau", "phi", "psi", "theta"]);
        assert_eq!(table.units, ["1", "rad", "rad", "rad"]);
        // A zero is written without its sign, as the table's rows write it.
        let want = [[0.125, 1.9446, 0.0, 5e-324], [1.0, 1e300, 0.1 + 0.2, -1e-7]];
        for (row, want) in table.rows.iter().zip(want) {
            assert_eq!(row.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), want.map(f64::to_bits), "{text}");
        }
    }
}
