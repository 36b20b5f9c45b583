//! `kinloop sweep`: a branch-safe sweep of the inputs from `--from` to `--to` as CSV with units,
//! the runtime's own sweep over the model (the events it meets listed on standard error, or
//! written to `--events`).

use crate::solve::{factors, parse_inputs, units};
use crate::{Failed, exit};
use kinloop_model::Model;
use kinloop_runtime::dims::KinState;
use kinloop_runtime::{Event, QuantityKind, Table};
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
    let kinds: Vec<QuantityKind> = model.quantities().iter().map(|(_, k)| *k).collect();
    let ni = model.inputs().len();
    let to_rad = |spec: &str| -> Result<Vec<f64>, Failed> {
        let mut x = parse_inputs(spec, ni, "--from/--to")?;
        for (v, k) in x.iter_mut().zip(&kinds[..ni]) {
            if req.deg && *k == QuantityKind::Angle {
                *v = v.to_radians();
            }
        }
        Ok(x)
    };
    let (from, to) = (to_rad(req.from)?, to_rad(req.to)?);
    if req.samples == 0 {
        eprintln!("error: --samples must be at least 1");
        return Err(Failed(exit::USAGE));
    }
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
    let mut sweep = model.sweep(&from, &to, req.samples, &guess).map_err(|e| failed(&e))?;
    let mut table = Table::new(columns);
    let mut stop = None;
    while let Some(k) = sweep.next_ref() {
        match k {
            Ok(k) => table.push(k.table_row().iter().zip(&factors).map(|(v, f)| v * f).collect()),
            Err(e) => {
                stop = Some(e);
                break;
            }
        }
    }
    let events = sweep.events().to_vec();
    drop(sweep);
    let table = table.with_units(&base.iter().map(|(n, u)| (n.as_str(), *u)).collect::<Vec<_>>());
    let stdout = std::io::stdout();
    table.write_csv(stdout.lock()).map_err(|e| failed(&format!("cannot write the table: {e}")))?;
    write_events(model, &events, req).map_err(|e| failed(&format!("cannot write the events: {e}")))?;
    match stop {
        Some(e) => Err(failed(&e)),
        None => Ok(()),
    }
}

/// The events as CSV (`kind,tau,` the inputs and the unknowns, in the sweep's units) into
/// `--events`, or one line each on standard error.
fn write_events(model: &Model, events: &[Event], req: &Request) -> std::io::Result<()> {
    let kinds: Vec<QuantityKind> = model.quantities().iter().map(|(_, k)| *k).collect();
    let angle = |k: QuantityKind, v: f64| if req.deg && k == QuantityKind::Angle { v.to_degrees() } else { v };
    let ni = model.inputs().len();
    let Some(path) = req.events else {
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
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    let names: Vec<&str> = model.inputs().iter().chain(model.unknowns()).map(String::as_str).collect();
    writeln!(w, "kind,tau,{}", names.join(","))?;
    for e in events {
        let values: Vec<String> =
            e.x.iter().chain(&e.q).zip(&kinds[..ni + e.q.len()]).map(|(v, k)| angle(*k, *v).to_string()).collect();
        writeln!(w, "{},{},{}", e.kind, e.tau, values.join(","))?;
    }
    w.flush()
}
