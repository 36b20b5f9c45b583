//! `kinloop trace`: the whole solution curve through the declared guess at `--from`, by the
//! runtime's pseudo-arclength continuation over the model, as CSV with units (the inputs, the
//! unknowns and the outputs at each point); the limit positions, kinks and crossings it passes
//! listed on standard error, or written to `--events`.

use crate::csv_rows::CsvRows;
use crate::solve::{degrees, led_by, located_in_units, model_inputs, parse_inputs, solve_failed, start_failed, units};
use crate::sweep::{events_columns, range_too_long, write_events};
use crate::{Failed, exit, output, samples};
use kinloop_model::Model;
use kinloop_runtime::dims::Heap;
use kinloop_runtime::{
    Computed, Error, Event, Kernel, Number, QuantityKind, SweepConfig, Table, TraceConfig, TracedOf, TracedPointOf,
};
use std::path::Path;

/// What `kinloop trace` was asked.
pub struct Request<'a> {
    /// The inputs at the start, one per input.
    pub from: &'a str,
    /// The inputs the trace moves towards first.
    pub to: &'a str,
    /// Arclength between points (scaled coordinates).
    pub ds: f64,
    /// The most points.
    pub max_points: usize,
    /// Angles in degrees.
    pub deg: bool,
    /// Where to write the events (standard error otherwise).
    pub events: Option<&'a Path>,
}

/// Traces from the declared guess at `from` and writes the points to standard output, then the
/// events; says on standard error why the trace ended where it did not close.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    if !(TraceConfig::MIN_DS..=TraceConfig::MAX_DS).contains(&req.ds) {
        return Err(exit::usage(format!(
            "--ds {} must be from {} to {} (a radian of the scaled coordinates: longer steps pass over the \
             curve's limit positions)",
            Number(req.ds),
            Number(TraceConfig::MIN_DS),
            Number(TraceConfig::MAX_DS)
        )));
    }
    if !(1..=samples::MAX_SAMPLES).contains(&req.max_points) {
        let n = req.max_points;
        return Err(exit::usage(format!(
            "--max-points {n} is out of range: at least 1, at most {}",
            samples::MAX_SAMPLES
        )));
    }
    events_columns(model, "trace", req.events)?;
    let kinds: Vec<QuantityKind> = model.quantities().iter().map(|(_, k)| *k).collect();
    let ni = model.inputs().len();
    let from = model_inputs(req.from, &kinds[..ni], req.deg, "--from")?;
    let to = model_inputs(req.to, &kinds[..ni], req.deg, "--to")?;
    if from == to {
        return Err(exit::usage(format!(
            "--from {} --to {}: the trace needs a direction to move in first: give --to different from --from",
            req.from, req.to
        )));
    }
    let name = model.name().to_string();
    let failed = |e: &dyn std::fmt::Display| {
        eprintln!("error: {name}: {e}");
        Failed(exit::SOLVE_FAILED)
    };
    // Every point is kept: more than fit in the memory budget are refused in the option's terms
    // (the runtime's refusal names its own field).
    let most = model.max_trace_points().map_err(|e| failed(&e))?;
    if req.max_points > most {
        return Err(exit::usage(format!(
            "--max-points {}: more points of {name} than fit in the 1 GiB a trace keeps at most; give at most {most}, \
             and trace a long curve in parts, each from the last point of the one before",
            req.max_points
        )));
    }
    let opts = TraceConfig::default().with_ds(req.ds).with_max_points(req.max_points);
    let mut guess = vec![0.0; model.unknowns().len()];
    model.guess(&from, &mut guess).map_err(|e| failed(&e))?;
    // The runtime checks the path (`to` apart from `from`, at most the turns a sweep follows)
    // and the options (again, as the checks above): its refusal is a usage error, not a failed
    // trace.
    let traced = match model.trace_curve(&from, &to, &guess, &opts) {
        Ok(traced) => traced,
        // The start's invalid argument (a loop whose lengths are all zero) where it was solved, in
        // the units given.
        Err(Error::InvalidArgument(m)) => {
            return Err(exit::usage(led_by(&name, &name, &located_in_units(model, &m, &from, req.deg))));
        }
        Err(e) => {
            if let Some(usage) = range_too_long(&name, &e, req.from, req.to, req.deg) {
                return Err(usage);
            }
            // Only the start is solved as a point: the trace passes singular positions after it.
            let singular_start = matches!(e, Error::Singular { .. });
            let failed = start_failed(model, &name, e, (&from, Some(&to)), req.deg);
            if singular_start {
                eprintln!(
                    "note: a trace starts at a limit position, but not where two curves cross (a change point): \
                     start it beside, on the curve to follow"
                );
            }
            return Err(failed);
        }
    };
    // Created before anything is written: a path that cannot be written stops before any output.
    let events_file = output::created(req.events, "the events file")?;
    // The points, then the events: a table that cannot be written (standard output full, its
    // reader gone) fails the command before the events are, and the events file it made is
    // removed again (it was left empty).
    let written = write_points(model, &traced, &kinds, req, &failed);
    if let Err(e) = written {
        if let Some(file) = events_file {
            file.abandon();
        }
        return Err(e);
    }
    // In the order met along the curve: by the point nearest each (a limit position is located
    // between two points; a kink and a crossing are points).
    let mut events: Vec<Event> = traced.folds.iter().chain(&traced.kinks).chain(&traced.crossings).cloned().collect();
    let nearest = |e: &Event| {
        let gap = |p: &TracedPointOf<Heap, Heap>| -> f64 {
            let (x, q): (&[f64], &[f64]) = (p.x.as_ref(), p.q.as_ref());
            x.iter().chain(q).zip(e.x.iter().chain(&e.q)).map(|(a, b)| (a - b) * (a - b)).sum()
        };
        (0..traced.points.len()).min_by(|&i, &j| gap(&traced.points[i]).total_cmp(&gap(&traced.points[j])))
    };
    events.sort_by_key(|e| nearest(e).unwrap_or(usize::MAX));
    output::write_into(events_file, "the events", |file| write_events(model, &events, req.deg, file))?;
    let points = traced.points.len();
    if traced.closed {
        eprintln!("{name}: the curve closed on itself after {points} points");
    } else if traced.truncated {
        eprintln!("{name}: stopped at --max-points {} before the curve closed or left the path", req.max_points);
    } else {
        // The segment's ends as numbers in the units given: `from - (to - from)` named the
        // library's arguments, for the reader to work out.
        let (a, b) = (parse_inputs(req.from, ni, "--from")?, parse_inputs(req.to, ni, "--to")?);
        let back: Vec<String> = a.iter().zip(&b).map(|(f, t)| Number(f - (t - f)).to_string()).collect();
        eprintln!(
            "{name}: the curve left the inputs' segment from {} to {} (as far behind --from {} as --to lies ahead) \
             after {points} points",
            back.join(","),
            req.to,
            req.from
        );
    }
    Ok(())
}

/// Writes the points of `traced` to standard output as CSV with units (the inputs, the
/// unknowns and the outputs), row by row; `failed` reports an output that cannot be computed.
fn write_points(
    model: &mut Model,
    traced: &TracedOf<Heap, Heap>,
    kinds: &[QuantityKind],
    req: &Request,
    failed: &dyn Fn(&dyn std::fmt::Display) -> Failed,
) -> Result<(), Failed> {
    let base = units(model, kinds, req.deg);
    let header = Table::new(base.iter().map(|(n, _)| n.clone()).collect())
        .with_units(&base.iter().map(|(n, u)| (n.as_str(), *u)).collect::<Vec<_>>());
    // Angles in degrees as `solve` writes its inputs: the shortest decimal that reads back.
    let angle = |k: QuantityKind, v: f64| if req.deg && k == QuantityKind::Angle { degrees(v) } else { v };
    let mut outputs = vec![0.0; model.outputs().len()];
    // Written row by row (buffered), as a sweep's: the curve's points are not copied into a
    // table first (at `--max-points` 10^7 that copy was a gigabyte).
    let mut rows = CsvRows::new(std::io::BufWriter::new(std::io::stdout().lock()), &header)
        .map_err(|e| output::failed("the table", e))?;
    let mut row = Vec::with_capacity(kinds.len());
    for p in &traced.points {
        let (x, q): (&[f64], &[f64]) = (p.x.as_ref(), p.q.as_ref());
        model.outputs_at(x, q, &mut outputs).map_err(|e| failed(&e))?;
        // An output that is not finite (the declaration's expression out of its domain there:
        // `sqrt(sin(phi))` past `phi = pi`) fails the trace at that point, the points before it
        // written, as a sweep fails at its state: it was written `NaN` with success.
        if let Some(k) = outputs.iter().position(|v| !v.is_finite()) {
            rows.finish().map_err(|e| output::failed("the table", e))?;
            return Err(output_not_finite(model, x, k, &kinds[..x.len()], req.deg));
        }
        row.clear();
        row.extend(x.iter().chain(q).chain(&outputs).zip(kinds).map(|(v, k)| angle(*k, *v)));
        rows.row(&row).map_err(|e| output::failed("the table", e))?;
    }
    rows.finish().map_err(|e| output::failed("the table", e))?;
    Ok(())
}

/// The failure of the output `k` of `model`, not finite at the inputs `x` (of kinds `kinds`) of
/// a traced point: the error a solve there reports ([`Error::Domain`] of the output, at the
/// model's location of the inputs, in degrees with `deg`), exit code 1.
fn output_not_finite(model: &mut Model, x: &[f64], k: usize, kinds: &[QuantityKind], deg: bool) -> Failed {
    let (mechanism, name) = (model.name().to_string(), std::borrow::Cow::Owned(model.outputs()[k].clone()));
    // The location is the model's as a kernel (the one its solves report), whatever the
    // configuration: the trace already ran, so every parameter has a value.
    let e = match model.kernel(SweepConfig::default()) {
        Ok(kernel) => Error::Domain { what: Computed::Output, name, at: kernel.location(x, None) },
        Err(e) => e,
    };
    solve_failed(&mechanism, e, kinds, deg)
}
