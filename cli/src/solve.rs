//! `kinloop solve`: states at given inputs as CSV, with units in the header.

use crate::numbers::number;
use crate::{Failed, exit};
use kinloop_model::{Count, Model, StepError};
use kinloop_runtime::dynamics::DynamicsError;
use kinloop_runtime::{Error, EventKind, Location, NewtonConfig, Number, QuantityKind, Source, Table};
use std::borrow::Cow;

/// Solves at every `--at` and writes the table of the states solved to standard output: a
/// failed one is explained on standard error and left out, the others written (each is solved
/// on its own from the declared guess), and the exit code is the failures' ([`exit_code`]): a
/// usage error where any is one (the arguments are to be changed whatever else failed), else
/// [`exit::SOLVE_FAILED`].
pub fn run(model: &mut Model, at: &[String], deg: bool) -> Result<(), Failed> {
    let kinds: Vec<QuantityKind> = model.quantities().iter().map(|(_, k)| *k).collect();
    let ni = model.inputs().len();
    let factors = factors(model, &kinds, deg);
    let name = model.name().to_string();
    let mut table = Table::new(model.columns());
    // Every `--at` read before any is solved: a mistyped one is the arguments' error, found
    // before states are written.
    let xs = at.iter().map(|spec| model_inputs(spec, &kinds[..ni], deg, "--at")).collect::<Result<Vec<_>, _>>()?;
    let mut failed = None;
    // A state nearer a singular position than a sweep accepts is written with a note: its
    // analogs are large and carry the rounding (a sweep would locate the position there).
    let near = model.sweep_config().singular_pivot;
    for (spec, x) in at.iter().zip(xs) {
        let row = match model.solve(&x) {
            Ok(state) => {
                let pivot = state.health.min_pivot;
                if pivot < near {
                    eprintln!(
                        "note: {name} at {spec}: the smallest pivot ratio is {pivot:.2e}, below the {near:e} a sweep \
                         accepts: a singular position (a limit position or a change point) is this near, and the \
                         analogs there are large and carry the rounding"
                    );
                }
                state.row()
            }
            Err(e) => {
                let (why, e) = explain(model, &x, e, &kinds[..ni], deg, &format!("{name} at {spec}"));
                let singular = matches!(e, Some(Error::Singular { .. }));
                // The code of the error as `sweep` and every other subcommand give it (a loop whose
                // lengths are all zero was 1 here, 2 there).
                let code = e.as_ref().map_or(exit::SOLVE_FAILED, exit_code);
                failed = Some(if failed == Some(exit::USAGE) { exit::USAGE } else { code });
                eprintln!("error: {why}");
                if let Some(e) = &e {
                    crate::assembles::note(model, e, &x, None, deg);
                }
                // The positions of a limit position exist where its analogs do not.
                if singular {
                    let unit = if deg { " --deg" } else { "" };
                    eprintln!(
                        "note: at a limit position `kinloop trace --from {spec}{unit}` starts there and writes the \
                         positions (not at a change point, where two branches cross)"
                    );
                }
                continue;
            }
        };
        let mut row: Vec<f64> = row.iter().zip(&factors).map(|(v, f)| v * f).collect();
        // The inputs as given: the product with `180/π` may end a unit in the last place off.
        for (i, k) in kinds[..ni].iter().enumerate() {
            if deg && *k == QuantityKind::Angle {
                row[i] = degrees(x[i]);
            }
        }
        table.push(row);
    }
    if !table.rows.is_empty() {
        let base = units(model, &kinds, deg);
        let table = table.with_units(&base.iter().map(|(n, u)| (n.as_str(), *u)).collect::<Vec<_>>());
        crate::output::table(&table, "the table")?;
    }
    match failed {
        Some(code) => Err(Failed(code)),
        None => Ok(()),
    }
}

/// Why the solve of `model` at `x` from the declared guess failed with `e`, as the runtime says
/// it ([`Model::explain`]), the inputs of kinds `kinds` in degrees where `deg` is set; `whence`
/// (the mechanism and the inputs as given) leads it where the explanation does not name them.
/// With it, the runtime's error (in radians), where the failure is one.
fn explain(
    model: &mut Model,
    x: &[f64],
    e: StepError,
    kinds: &[QuantityKind],
    deg: bool,
    whence: &str,
) -> (String, Option<Error>) {
    let mut guess = vec![0.0; model.unknowns().len()];
    if model.guess(x, &mut guess).is_err() {
        return (format!("{whence}: {e}"), None);
    }
    let e = model.explain(x, &guess, &NewtonConfig::default(), e);
    let said = in_units(text_in_units(model, e.clone(), x, deg), kinds, deg);
    let said = match said.location() {
        Some(_) => said.to_string(),
        None => led_by(whence, model.name(), &said),
    };
    (said, Some(e))
}

/// `e`, an error of a solve of `model` at the inputs `x` (in the model's units), with the
/// location written into its text in the units written: angles in degrees where `deg` is set.
/// The runtime writes the location of a loop whose lengths are all zero into the text of an
/// [`Error::InvalidArgument`] (``... all have length zero in `FourBar` at phi =
/// 0.5235987755982988 (block 0: ...)``), which carries no location for [`in_units`] to convert:
/// where the text names the location of `x` exactly as the runtime writes it, its inputs are
/// written as [`in_units`] writes every other error's (`phi = 30`); a text that names none, or
/// another location (of a failure after the first solve), is left as it is. A kinematic failure
/// inside a dynamics error is converted inside it. Other errors are returned as they are: their
/// locations are [`in_units`]' to convert, once.
pub fn text_in_units(model: &Model, e: Error, x: &[f64], deg: bool) -> Error {
    if !deg {
        return e;
    }
    match e {
        Error::InvalidArgument(text) => Error::InvalidArgument(located_in_units(model, &text, x, deg)),
        Error::Dynamics(source) => match source.downcast_ref::<DynamicsError>() {
            Some(DynamicsError::Kinematics { t, source: inner @ Error::InvalidArgument(_) }) => {
                let source = text_in_units(model, inner.clone(), x, deg);
                // Wrapped as it came (not through `From`, which unwraps a kinematic failure and
                // drops the time it happened at).
                Error::Dynamics(Source::new(DynamicsError::Kinematics { t: *t, source }))
            }
            _ => Error::Dynamics(source),
        },
        e => e,
    }
}

/// `text` (of an [`Error::InvalidArgument`]: see [`text_in_units`]) with the location of `model`
/// at the inputs `x` (as [`Location`] writes it, without a block) written with its angles in
/// degrees where `deg` is set, wherever it stands whole: not followed by what would go on with
/// its last number (the location at `0.5` is not the start of the one at `0.55`).
pub fn located_in_units(model: &Model, text: &str, x: &[f64], deg: bool) -> String {
    if !deg {
        return text.to_owned();
    }
    let location = |values: Vec<f64>| {
        let names = model.inputs().iter().map(|n| Cow::Owned(n.clone()));
        Location { mechanism: Cow::Owned(model.name().to_owned()), inputs: names.zip(values).collect(), block: None }
            .to_string()
    };
    let angles = model.input_kinds().iter().map(|k| *k == QuantityKind::Angle);
    let computed = location(x.to_vec());
    let written = location(x.iter().zip(angles).map(|(&v, angle)| if angle { degrees(v) } else { v }).collect());
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find(&computed) {
        let end = i + computed.len();
        let whole = !rest[end..].starts_with(|c: char| c.is_ascii_alphanumeric() || c == '.');
        out.push_str(&rest[..i]);
        out.push_str(if whole { &written } else { &computed });
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// The error `e` of the model `name` as a line says it: the error alone where its location
/// names the mechanism and the inputs (``in `FourBar` at phi = 30``), `name: e` otherwise
/// ([`led_by`]).
pub fn named(name: &str, e: &Error) -> String {
    match e.location() {
        Some(_) => e.to_string(),
        None => led_by(name, name, e),
    }
}

/// `what` (an error of the mechanism `mechanism`) led by `whence` (the mechanism, and the inputs
/// as given: `FourBar at 30`), unless its text names the mechanism's location itself (``in
/// `FourBar` at phi = 30``), as the runtime writes it into the text of an error that carries no
/// location (a loop whose lengths are all zero): led anyway, the line named the mechanism twice
/// and its inputs twice ("FourBar at 30: ... in `FourBar` at phi = 30").
pub fn led_by(whence: &str, mechanism: &str, what: &impl std::fmt::Display) -> String {
    let text = what.to_string();
    let location = Location { mechanism: Cow::Owned(mechanism.to_owned()), inputs: Vec::new(), block: None };
    match text.contains(&location.to_string()) {
        true => text,
        false => format!("{whence}: {text}"),
    }
}

/// The base quantities with their units: `deg` for angles where angles are written in
/// degrees, the inferred unit otherwise, and `unit of NAME` for an input whose kind is not
/// inferred (a time).
pub fn units(model: &Model, kinds: &[QuantityKind], deg: bool) -> Vec<(String, &'static str)> {
    let ni = model.inputs().len();
    let unit = |k: usize, name: &str, kind: QuantityKind| match kind {
        QuantityKind::Angle if deg => "deg",
        // The library's unit for an input of no inferred kind (`unit of t`): without it the
        // analogs by it would have none, and an angle's in radians and in degrees would be
        // written alike. Leaked: one short text per input, for the whole run.
        QuantityKind::Other if k < ni => Box::leak(kind.input_unit(name).into_owned().into_boxed_str()),
        kind => kind.unit(),
    };
    model
        .quantities()
        .iter()
        .zip(kinds)
        .enumerate()
        .map(|(k, ((n, _), kind))| (n.to_string(), unit(k, n, *kind)))
        .collect()
}

/// An angle `v` in radians in degrees as `--deg` reads them: of `v.to_degrees()` and the
/// numbers next to it, the shortest in decimal that turns back into exactly `v` (`30` for
/// `30f64.to_radians()`, whose product with `180/π` is `29.999999999999996`).
pub fn degrees(v: f64) -> f64 {
    let d = v.to_degrees();
    let near = [d, d.next_up(), d.next_down(), d.next_up().next_up(), d.next_down().next_down()];
    near.into_iter().filter(|c| c.to_radians() == v).min_by_key(|c| c.to_string().len()).unwrap_or(d)
}

/// `e` with the inputs of its location (of kinds `kinds`) in the units written: angles in
/// degrees where `deg` is set, as they were given and as the table writes them. A dynamics
/// error (`dynamics`, `simulate`) carries its inputs, and a simulation's speeds, apart from a
/// location: they are converted too ([`dynamics_in_units`]).
pub fn in_units(mut e: Error, kinds: &[QuantityKind], deg: bool) -> Error {
    if let (true, Error::Dynamics(source)) = (deg, &e)
        && let Some(d) = source.downcast_ref::<DynamicsError>()
    {
        // Wrapped as it came (not through `From`, which unwraps a kinematic failure and drops
        // the time it happened at).
        return Error::Dynamics(Source::new(dynamics_in_units(d.clone(), kinds)));
    }
    if let (true, Some(at)) = (deg, e.location_mut()) {
        for ((_, v), k) in at.inputs.iter_mut().zip(kinds) {
            if *k == QuantityKind::Angle {
                *v = degrees(*v);
            }
        }
    }
    // An input's spacings as well as its value: the message compares them.
    if let Error::InputTooCoarse { input, apart, step, .. } = &mut e
        && deg
        && kinds.get(*input) == Some(&QuantityKind::Angle)
    {
        (*apart, *step) = (apart.to_degrees(), step.to_degrees());
    }
    e
}

/// A dynamics error with the inputs it names (of kinds `kinds`) in degrees where they are
/// angles, and a simulation's speeds with them (per time unit, the factor is the angle's); a
/// kinematic failure inside it by [`in_units`]. Without this `--deg` wrote these in radians
/// beside a table in degrees: a load not finite at the sample of 90 degrees was said to be
/// at `phi = 1.5707963267948966`.
fn dynamics_in_units(mut d: DynamicsError, kinds: &[QuantityKind]) -> DynamicsError {
    let angles = |values: &mut [f64]| {
        for (v, k) in values.iter_mut().zip(kinds) {
            if *k == QuantityKind::Angle {
                *v = degrees(*v);
            }
        }
    };
    match &mut d {
        DynamicsError::NonFiniteLoad { x, .. }
        | DynamicsError::SingularMass { x, .. }
        | DynamicsError::Overflow { x, .. } => angles(x),
        DynamicsError::SingularMotion { x, speed, .. } => {
            angles(x);
            angles(speed);
        }
        DynamicsError::Kinematics { source, .. } => *source = in_units(source.clone(), kinds, true),
        _ => {}
    }
    d
}

/// A failed solve of the model `name` reported: its error in the units written ([`in_units`]),
/// and the exit code its kind calls for ([`exit_code`]).
pub fn solve_failed(name: &str, e: Error, kinds: &[QuantityKind], deg: bool) -> Failed {
    let code = exit_code(&e);
    let notes = Notes::of(&e);
    eprintln!("error: {}", named(name, &in_units(e, kinds, deg)));
    notes.write();
    Failed(code)
}

/// The notes written under a failed solve's error: the command line's options and commands
/// that its advice, written for the library, stands for.
#[derive(Clone, Copy)]
pub struct Notes {
    /// A sweep passes too near a singular position: `--singular-pivot` lowers the ratio.
    lower_pivot: bool,
    /// A sweep stopped at a limit position: a trace goes on through it.
    at_limit: bool,
    /// A sweep stopped at a crossing: `--through-crossings` or a trace goes on through it.
    at_crossing: bool,
    /// A sweep starts at a singular position: a trace starts at a limit position.
    singular_start: bool,
    /// ... with a pivot ratio below the sweep's `singular_pivot`, which the error names.
    start_below_pivot: bool,
}

impl Notes {
    /// The notes of the error `e`.
    pub fn of(e: &Error) -> Notes {
        Notes {
            // The sweep's advice names the library's setting; the command line's option sets it.
            lower_pivot: matches!(e, Error::NearSingular { .. }),
            at_limit: matches!(e, Error::SweepStopped { kind: EventKind::LimitPosition, .. }),
            at_crossing: matches!(e, Error::SweepStopped { kind: EventKind::SingularCrossing, .. }),
            singular_start: matches!(e, Error::SingularStart { .. }),
            // The start's cause names the library's setting where the pivot ratio is below it.
            start_below_pivot: matches!(e, Error::SingularStart { pivot_ratio, singular_pivot, .. }
                if pivot_ratio < singular_pivot),
        }
    }

    /// Writes the notes on standard error.
    pub fn write(self) {
        let Notes { lower_pivot, at_limit, at_crossing, singular_start, start_below_pivot } = self;
        if lower_pivot {
            eprintln!("note: `--singular-pivot RATIO` lowers it on the command line");
        }
        if singular_start {
            eprintln!("note: `kinloop trace` traces the curve from a limit position (not from a change point)");
        }
        if start_below_pivot {
            eprintln!("note: `SweepConfig::singular_pivot` is `--singular-pivot RATIO` on the command line");
        }
        // The error says what goes on from a stop in the library's names (`trace_curve`,
        // `AtSingular::Continue`, `SweepConfig::singular_pivot`); the notes name the command
        // line's, without saying it all again.
        if at_limit {
            eprintln!("note: `trace_curve` is `kinloop trace` on the command line");
        }
        if at_crossing {
            eprintln!(
                "note: on the command line, `AtSingular::Continue` is `--through-crossings`, `trace_curve` is \
                 `kinloop trace`, and `SweepConfig::singular_pivot` is `--singular-pivot RATIO`"
            );
        }
    }
}

/// [`solve_failed`] of a start at the inputs `at` (a sweep's, a trace's, on the path to `to`
/// where one is given), with the note of where the mechanism assembles where it does not there
/// ([`crate::assembles::note`]).
pub fn start_failed(model: &mut Model, name: &str, e: Error, (at, to): (&[f64], Option<&[f64]>), deg: bool) -> Failed {
    let kinds = model.input_kinds().to_vec();
    let failed = solve_failed(name, text_in_units(model, e.clone(), at, deg), &kinds, deg);
    crate::assembles::note(model, &e, at, to, deg);
    failed
}

/// The exit code of a failed solve's error `e`: a usage error ([`exit::USAGE`]) where the
/// arguments stand in the way, not the mechanism (an input too coarse where the range lies: a
/// range far out, to be reduced by whole turns; an invalid argument, such as a loop whose
/// lengths are all zero, parameters left at 0), [`exit::SOLVE_FAILED`] otherwise. A kinematic
/// failure inside a dynamics error (an inverse cycle's, a simulation's) is judged as itself:
/// the same failure has one code under every subcommand.
pub fn exit_code(e: &Error) -> u8 {
    match e {
        Error::InputTooCoarse { .. } | Error::RangeTooLong { .. } | Error::InvalidArgument(_) => exit::USAGE,
        Error::Dynamics(source) => match source.downcast_ref::<DynamicsError>() {
            Some(DynamicsError::Kinematics { source, .. }) => exit_code(source),
            _ => exit::SOLVE_FAILED,
        },
        _ => exit::SOLVE_FAILED,
    }
}

/// One list of inputs (of the option `option`) in the model's units: one number per input of
/// kind `kinds`, angles given in degrees where `deg` is set and turned into radians. An angle
/// so many turns out that its conversion rounds it by more than a solve's precision (beyond
/// [`NewtonConfig::largest_precise_angle`]: `1e17` degrees, 280 degrees on its turn, came out
/// 275.6, where doubles are 0.25 rad apart) is refused.
pub fn model_inputs(spec: &str, kinds: &[QuantityKind], deg: bool, option: &str) -> Result<Vec<f64>, Failed> {
    let mut x = parse_inputs(spec, kinds.len(), option)?;
    for (v, k) in x.iter_mut().zip(kinds) {
        if deg && *k == QuantityKind::Angle {
            *v = radians_of(*v, &format!("{option} {spec}"))?;
        }
    }
    Ok(x)
}

/// An angle `v` given in degrees (by the option and value `given`) in radians, or the usage
/// error of one so many turns out that the conversion rounds it by more than a solve's
/// precision (beyond [`NewtonConfig::largest_precise_angle`]).
pub fn radians_of(v: f64, given: &str) -> Result<f64, Failed> {
    let radians = v.to_radians();
    let largest = NewtonConfig::default().largest_precise_angle();
    if radians.abs() > largest {
        return Err(exit::usage(format!(
            "{given}: {} degrees are too many turns out to convert to radians to a solve's precision (the doubles of \
             the radians there are {} degrees apart; angles up to {:.3e} degrees convert precisely): give it whole \
             turns nearer (e.g. {} for a mechanism that repeats every turn)",
            Number(v),
            Number((radians.abs().next_up() - radians.abs()).to_degrees()),
            degrees(largest),
            Number(v.rem_euclid(360.0)),
        )));
    }
    Ok(radians)
}

/// A point `x,y` of two finite numbers, given to the option `option` (`--about`, `--pivot`).
pub fn point(spec: &str, option: &str) -> Result<[f64; 2], Failed> {
    if spec.trim().is_empty() {
        return Err(empty(option, "a point `x,y` of two finite numbers"));
    }
    let not_a_point = format!("{option} {spec} is not a point `x,y` of two finite numbers");
    match spec.split(',').map(number).collect::<Result<Vec<f64>, _>>() {
        Ok(v) => match v[..] {
            [x, y] if x.is_finite() && y.is_finite() => Ok([x, y]),
            _ => Err(exit::usage(not_a_point)),
        },
        Err(e) => Err(exit::usage(format!("{not_a_point}: {e}"))),
    }
}

/// The usage error of the option `option` given an empty value (an unset shell variable), which
/// takes `what`. Written as the other values are, `{option} {spec}`, it read with two spaces and
/// the number "``" (`--at  is not a list of finite numbers: `` is not a number`).
pub(crate) fn empty(option: &str, what: &str) -> Failed {
    exit::usage(format!("{option} is given nothing: give {what}"))
}

/// One list of inputs (of the option `option`): one number per input.
pub fn parse_inputs(spec: &str, ni: usize, option: &str) -> Result<Vec<f64>, Failed> {
    if spec.trim().is_empty() {
        let what = match ni {
            1 => "a finite number, the mechanism's input".to_string(),
            _ => format!("{ni} finite numbers separated by commas, one per input of the mechanism"),
        };
        return Err(empty(option, &what));
    }
    // A number too small for a double is refused, as in --params (`1e-400` was taken as 0
    // without a word).
    let x = spec.split(',').map(number).collect::<Result<Vec<f64>, _>>();
    match x {
        Ok(x) if x.len() == ni && x.iter().all(|v| v.is_finite()) => Ok(x),
        Ok(x) if x.len() != ni => {
            eprintln!("error: {option} {spec} gives {}, the mechanism has {ni}", Count(x.len(), "input"));
            Err(Failed(exit::USAGE))
        }
        Ok(_) => Err(exit::usage(format!("{option} {spec} is not a list of finite numbers"))),
        Err(e) => Err(exit::usage(format!("{option} {spec} is not a list of finite numbers: {e}"))),
    }
}

/// Per column of [`Model::columns`]: the factor that converts its value to degrees where
/// angles are written in degrees (an angle in the quantity: times `180/π`; an angle input in
/// the derivative: divided by it), 1 otherwise.
pub fn factors(model: &Model, kinds: &[QuantityKind], deg: bool) -> Vec<f64> {
    let d = 180.0 / std::f64::consts::PI;
    let of = |k: QuantityKind| if deg && k == QuantityKind::Angle { d } else { 1.0 };
    let ni = model.inputs().len();
    let (inputs, rest) = kinds.split_at(ni);
    let (unknowns, outputs) = rest.split_at(model.unknowns().len());
    let mut f: Vec<f64> = inputs.iter().map(|&k| of(k)).collect();
    for group in [unknowns, outputs] {
        f.extend(group.iter().map(|&k| of(k)));
        for &k in group {
            f.extend(inputs.iter().map(|&i| of(k) / of(i)));
        }
        for &k in group {
            for a in 0..ni {
                for b in a..ni {
                    f.push(of(k) / (of(inputs[a]) * of(inputs[b])));
                }
            }
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The location of the inputs solved at is converted where it stands whole, and only
    /// there: the location at `0.5` begins the one at `0.55`, which is another solve's.
    #[test]
    fn a_location_in_a_text_is_converted_where_it_is_the_one_solved_at() {
        let text = "pub struct Crank { params r = 1, l = 3; input phi; unknowns psi = 0, x = 3; loop a: r @ phi == (x, 0) + l @ psi; }";
        let model = Model::read("crank.kl", text).expect("the crank reads");
        let said = |phi: &str| format!("zero in `Crank` at phi = {phi} (block 0: ...): give them values");
        let at = |phi: f64, deg| located_in_units(&model, &said(&Number(0.55).to_string()), &[phi], deg);
        assert_eq!(at(0.55, true), said(&Number(degrees(0.55)).to_string()));
        assert_eq!(at(0.55, false), said("0.55"));
        assert_eq!(at(0.5, true), said("0.55"));
        // At the text's end too.
        let end = located_in_units(&model, "in `Crank` at phi = 0.5", &[0.5], true);
        assert_eq!(end, format!("in `Crank` at phi = {}", Number(degrees(0.5))));
    }
}
