//! `kinloop sweep`: a branch-safe sweep of the inputs from `--from` to `--to` as CSV with units,
//! the runtime's own sweep over the model (the events it meets listed on standard error, or
//! written to `--events`).

use crate::solve::{factors, in_units, model_inputs, parse_inputs, units};
use crate::{Failed, exit, progress, samples};
use kinloop_model::Model;
use kinloop_runtime::dims::KinState;
use kinloop_runtime::{Error, Event, QuantityKind, Table};
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

/// Sweeps from the declared guess at `from` and writes the table to standard output. A sweep
/// that stops (a limit position, no assembly) writes the states before the stop, the events,
/// and the reason on standard error, and fails.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    samples::check(req.samples)?;
    let kinds: Vec<QuantityKind> = model.quantities().iter().map(|(_, k)| *k).collect();
    let ni = model.inputs().len();
    let from = model_inputs(req.from, &kinds[..ni], req.deg, "--from")?;
    let to = model_inputs(req.to, &kinds[..ni], req.deg, "--to")?;
    // The angle inputs in degrees as given, whose samples the table writes.
    let degrees: Vec<Option<(f64, f64)>> = match req.deg {
        true => {
            let (a, b) = (parse_inputs(req.from, ni, "--from")?, parse_inputs(req.to, ni, "--to")?);
            (0..ni).map(|i| (kinds[i] == QuantityKind::Angle).then_some((a[i], b[i]))).collect()
        }
        false => vec![None; ni],
    };
    let name = model.name().to_string();
    let factors = factors(model, &kinds, req.deg);
    let columns = model.columns();
    let base = units(model, &kinds, req.deg);
    let failed = |e: &dyn std::fmt::Display| {
        eprintln!("error: {name}: {e}");
        Failed(exit::SOLVE_FAILED)
    };
    let mut guess = vec![0.0; model.unknowns().len()];
    model.guess(&from, &mut guess).map_err(|e| failed(&e))?;
    // The runtime checks the arguments (at least one sample, `to` apart from `from` for
    // several): its refusal is a usage error, not a failed solve.
    let mut sweep = model.sweep(&from, &to, req.samples, &guess).map_err(|e| match e {
        Error::InvalidArgument(_) => exit::usage(format!("{name}: {e}")),
        e => failed(&in_units(e, &kinds[..ni], req.deg)),
    })?;
    let mut table = Table::new(columns);
    let mut stop = None;
    let last = req.samples.saturating_sub(1).max(1) as f64;
    // A state's row (`table_row`) in the units written, appended to the table.
    let push = |table: &mut Table, state: Vec<f64>| {
        let mut row: Vec<f64> = state.iter().zip(&factors).map(|(v, f)| v * f).collect();
        // An angle input in degrees: the sample's value between the ends given, not its
        // radians times `180/π` (`59.99999999999999` for the sample at 60), as `solve` writes
        // the input given. Exact where the samples fall on round numbers.
        let s = table.rows.len() as f64;
        for (i, ends) in degrees.iter().enumerate() {
            let Some((a, b)) = ends else { continue };
            let given = (a * (last - s) + b * s) / last;
            // Ends near the largest `f64`: the products overflow, the product stays.
            if given.is_finite() {
                row[i] = given;
            }
        }
        table.push(row);
    };
    // The first sample, before anything is created: a range longer than a sweep follows is
    // refused there, a usage error.
    match sweep.next_ref() {
        Some(Ok(k)) => push(&mut table, k.table_row()),
        Some(Err(e)) => match range_too_long(&name, &e, req.from, req.to, req.deg) {
            Some(usage) => return Err(usage),
            None => stop = Some(e),
        },
        None => {}
    }
    // Created before the rest of the sweep runs: a path that cannot be written stops before
    // any output.
    let events_file = match req.events {
        Some(path) => Some(std::fs::File::create(path).map_err(|e| {
            eprintln!("error: cannot create the events file {}: {e}", path.display());
            Failed(exit::CANT_CREATE)
        })?),
        None => None,
    };
    let bar = progress::bar(&format!("{name}: sweeping"), req.samples, req.samples);
    bar.inc(table.rows.len() as u64);
    while stop.is_none() {
        match sweep.next_ref() {
            Some(Ok(k)) => push(&mut table, k.table_row()),
            Some(Err(e)) => stop = Some(e),
            None => break,
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    let events = sweep.events().to_vec();
    drop(sweep);
    let table = table.with_units(&base.iter().map(|(n, u)| (n.as_str(), *u)).collect::<Vec<_>>());
    let stdout = std::io::stdout();
    let io_error = |what: &str, e: std::io::Error| {
        eprintln!("error: cannot write {what}: {e}");
        Failed(exit::IO_ERR)
    };
    table.write_csv(stdout.lock()).map_err(|e| io_error("the table", e))?;
    write_events(model, &events, req.deg, events_file).map_err(|e| io_error("the events", e))?;
    match stop {
        Some(e) => Err(failed(&in_units(e, &kinds[..ni], req.deg))),
        None => Ok(()),
    }
}

/// The usage error of a range longer than a sweep follows ([`Error::RangeTooLong`], which a
/// sweep finds before its first step): how far apart `--from` and `--to` may be, in the units
/// given. `None` for any other error.
pub(crate) fn range_too_long(name: &str, e: &Error, from: &str, to: &str, deg: bool) -> Option<Failed> {
    let &Error::RangeTooLong { turns, max_turns, .. } = e else { return None };
    let span = match deg {
        true => format!("{:.0} deg", 360.0 * max_turns),
        false => format!("{:.1} rad", std::f64::consts::TAU * max_turns),
    };
    Some(exit::usage(format!(
        "{name}: --from {from} --to {to} spans {turns:.3e} turns of the inputs, more than the {max_turns:e} turns a \
         sweep follows: give --from and --to at most {max_turns:e} turns apart ({span} of an angle input); split a \
         longer range into several sweeps, or reduce a periodic input by whole turns"
    )))
}

/// The events as CSV (`kind,tau,` the inputs and the unknowns, in the sweep's units, named
/// `name [unit]` as the table's columns) into `file` (`--events`), or one line each on
/// standard error.
fn write_events(model: &Model, events: &[Event], deg: bool, file: Option<std::fs::File>) -> std::io::Result<()> {
    let kinds: Vec<QuantityKind> = model.quantities().iter().map(|(_, k)| *k).collect();
    let angle = |k: QuantityKind, v: f64| if deg && k == QuantityKind::Angle { v.to_degrees() } else { v };
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
            eprintln!("event: {} at {} (fraction {} of the sweep)", e.kind, at.join(", "), e.tau);
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
    write!(w, "kind,tau,{}", String::from_utf8_lossy(&line))?;
    for e in events {
        let values: Vec<String> =
            e.x.iter().chain(&e.q).zip(&kinds[..ni + e.q.len()]).map(|(v, k)| angle(*k, *v).to_string()).collect();
        writeln!(w, "{},{},{}", e.kind, e.tau, values.join(","))?;
    }
    w.flush()
}
