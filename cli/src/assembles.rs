//! The note after "the mechanism cannot be assembled" at the input asked for: where it does,
//! nearest that input (the runtime's `assembly_near` over the model), so that a designer learns
//! the input range to ask for, or that the lengths close nowhere, without trying inputs one by
//! one. The error line names the mechanism; the note does not again.

use crate::numbers::significant;
use crate::solve::degrees;
use kinloop_model::Model;
use kinloop_runtime::dims::Heap;
use kinloop_runtime::paths::assembles::ASSEMBLY_SAMPLES;
use kinloop_runtime::paths::assembles::Assembly;
use kinloop_runtime::{Error, Number, QuantityKind};

/// Writes the note on standard error where `e` is a failure to assemble at the inputs `at` (in
/// radians: the error's own location, a sweep's or a trace's start, not a later step), its
/// numbers in the units written (degrees where `deg` is set): for a model of one angle input,
/// where it assembles nearest `at`; for any other, where it first assembles along the path to
/// `to` (a sweep's, a trace's), where one is given. Nothing otherwise, nor where the search
/// itself fails (the error already said what it could).
pub fn note(model: &mut Model, e: &Error, at: &[f64], to: Option<&[f64]>, deg: bool) {
    let here = e.location().is_some_and(|l| l.inputs.iter().map(|(_, v)| *v).eq(at.iter().copied()));
    if !matches!(e, Error::NoAssembly { .. }) || !here {
        return;
    }
    let text = match (model.input_kinds() == [QuantityKind::Angle], to) {
        (true, _) => text(model, at[0], deg),
        (false, Some(to)) => along(model, at, to, deg),
        (false, None) => None,
    };
    if let Some(text) = text {
        eprintln!("note: {text}");
    }
}

/// The note's text for a model that does not assemble at `from` on the path to `to` (radians):
/// where along it the point solves from the declared guess begin to succeed, and the first of
/// the samples there, a start for a sweep.
fn along(model: &mut Model, from: &[f64], to: &[f64], deg: bool) -> Option<String> {
    let entry = model.assembly_along(from, to, ASSEMBLY_SAMPLES).ok()?;
    let Some(entry) = entry else {
        return Some(format!(
            "from the declared guess, the mechanism assembles at none of {ASSEMBLY_SAMPLES} inputs equally spaced along \
             the path to --to"
        ));
    };
    let kinds = model.input_kinds().to_vec();
    let inputs = |x: &[f64]| {
        let named = model.inputs().iter().zip(x).zip(&kinds);
        named
            .map(|((n, v), k)| match deg && *k == QuantityKind::Angle {
                true => format!("{n} = {} deg", Number(note_degrees(*v))),
                false => format!("{n} = {}", Number(*v)),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    Some(format!(
        "along the path to --to, the mechanism first assembles at {} ({} of the way, from the declared guess); a \
         sweep can start at {}, the first of {ASSEMBLY_SAMPLES} inputs along the path that solves",
        inputs(&entry.at.0),
        Number(entry.fraction),
        inputs(&entry.sample.0)
    ))
}

/// The note's text for the model at the input angle `at` (radians).
fn text(model: &mut Model, at: f64, deg: bool) -> Option<String> {
    let input = model.inputs()[0].clone();
    let shown = |v: f64| shown(v, deg);
    let near = model.assembly_near(&[at], ASSEMBLY_SAMPLES).ok()?;
    let Some(a) = near else {
        return Some(format!(
            "from the declared guess, the mechanism assembles at none of {ASSEMBLY_SAMPLES} values of {input} over \
             the turn about {}, a degree apart: its loops close at no input angle with these lengths (or only over \
             less than a degree)",
            shown(at)
        ));
    };
    let (found, from, to) = (a.found[0], a.reach.from[0], a.reach.to[0]);
    // The point solve at `at` failed from the declared guess, but a sweep on the mode found
    // reaches it (Newton's method from a guess far from the position there).
    if from <= at && at <= to {
        return Some(format!(
            "the mechanism assembles at {input} = {found_s} from the declared guess, and a sweep from there on that \
             assembly mode reaches {input} = {at_s}: `kinloop sweep --from {found_s} --to {at_s}{unit}` (the \
             declared guess is far from the position at {at_s})",
            found_s = plain(found, deg),
            at_s = plain(at, deg),
            unit = if deg { " --deg" } else { "" },
        ));
    }
    let [from, to] = ends(&a, deg);
    Some(format!(
        "nearest {input} = {}, the mechanism assembles on the assembly mode of the declared guess for {input} from \
         {from} to {to}",
        shown(at),
    ))
}

/// Writes, after a machine turned by its crank at a constant speed meets a limit position
/// (`dynamics`), how far that input moves from `start` (radians) on the declared guess's
/// assembly mode, where it cannot turn fully: the stretch between its limit positions, which
/// tells a designer that the lengths make a rocker, not a crank. Nothing where the input turns
/// fully (the position met is a change point), for other mechanisms, or where the search fails.
pub fn rocks_note(model: &mut Model, start: f64, deg: bool) {
    if model.input_kinds() != [QuantityKind::Angle] {
        return;
    }
    let Ok(Some(a)) = model.assembly_near(&[start], ASSEMBLY_SAMPLES) else { return };
    if a.turns_fully() || a.found[0] != start {
        return;
    }
    let input = model.inputs()[0].clone();
    let [from, to] = ends(&a, deg);
    eprintln!(
        "note: from {input} = {} on the assembly mode of the declared guess, {input} moves only between {from} and \
         {to}: with these lengths it rocks, and no speed turns it a full turn",
        shown(start, deg),
    );
}

/// The two ends of the stretch `a` found, in the notes' units (see [`shown`]): each a limit
/// position, or where none comes within a turn of where the stretch was found, the search's end.
pub fn ends(a: &Assembly<Heap>, deg: bool) -> [String; 2] {
    let end = |v: f64, limit: bool| match limit {
        true => format!("{} (a limit position)", shown(v, deg)),
        false => format!("{} (a turn on: no limit position within it)", shown(v, deg)),
    };
    [end(a.reach.from[0], a.reach.from_event.is_some()), end(a.reach.to[0], a.reach.to_event.is_some())]
}

/// An input angle `v` (radians) as the notes write it: in degrees, marked so, where `deg` is
/// set.
pub fn shown(v: f64, deg: bool) -> String {
    if deg { format!("{} deg", Number(note_degrees(v))) } else { Number(v).to_string() }
}

/// An angle `v` (radians) in degrees to 15 significant digits, as a note writes it: the
/// inputs the search found are radians (a sample along a path given in degrees, a located
/// limit position), whose conversion puts rounding into the 16th digit (82 degrees written
/// `82.00000000000001`), below what a designer types or a sweep's start needs.
fn note_degrees(v: f64) -> f64 {
    significant(degrees(v), 15)
}

/// `v` (radians) as an option takes it: degrees where `deg` is set.
fn plain(v: f64, deg: bool) -> String {
    Number(if deg { note_degrees(v) } else { v }).to_string()
}
