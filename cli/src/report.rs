//! `kinloop check`: the structure report of a declaration.

use kinloop_model::{Count, Model};
use kinloop_runtime::paths::assembles::ASSEMBLY_SAMPLES;
use kinloop_runtime::{Error, EventKind, Number, QuantityKind};
use std::fmt::Write;

/// The decomposition (counts, mobility, blocks and how each is solved), then the parameters
/// with their units and values, the quantities with their units, the size of the run-time program, and
/// for a mechanism of one angle input whose parameters all have values, how far that input
/// moves ([`motion`]).
pub fn structure(model: &mut Model) -> String {
    let mut s = format!("{}\n", model.decomposition());
    let params: Vec<String> = model
        .params()
        .iter()
        .zip(model.param_values())
        .zip(model.param_kinds())
        .map(|((p, v), k)| {
            // With its unit as the quantities below are written (`gamma [rad]`): an angle
            // parameter is in radians, whatever `--deg` does to inputs.
            let p = if k.unit().is_empty() { p.to_string() } else { format!("{p} [{}]", k.unit()) };
            match v {
                // As numbers are written elsewhere: `{v}` wrote 1e308 in 309 digits, 1e-300 in 301.
                Some(v) => format!("{p} = {}", kinloop_runtime::Number(*v)),
                None => format!("{p} (no value)"),
            }
        })
        .collect();
    let _ = writeln!(s, "parameters: {}", if params.is_empty() { "none".to_string() } else { params.join(", ") });
    let quantities = model.quantities();
    let (ni, nu) = (model.inputs().len(), model.unknowns().len());
    // An input's unit as the tables write it: `unit of t` for a time `t` (a kind not inferred),
    // where the report wrote `t` alone and the tables `t [unit of t]`.
    let list = |q: &[(&str, kinloop_runtime::QuantityKind)], input: bool| {
        let v: Vec<String> = q
            .iter()
            .map(|(n, k)| {
                let unit = if input { k.input_unit(n) } else { k.unit().into() };
                if unit.is_empty() { n.to_string() } else { format!("{n} [{unit}]") }
            })
            .collect();
        if v.is_empty() { "none".to_string() } else { v.join(", ") }
    };
    let _ = writeln!(s, "inputs: {}", list(&quantities[..ni], true));
    let _ = writeln!(s, "unknowns: {}", list(&quantities[ni..ni + nu], false));
    let _ = writeln!(s, "outputs: {}", list(&quantities[ni + nu..], false));
    let (registers, instructions) = (Count(model.registers(), "register"), Count(model.instructions(), "instruction"));
    let _ = writeln!(s, "run-time program: {registers}, {instructions}");
    if let Some(motion) = motion(model) {
        let _ = writeln!(s, "motion: {motion}");
    }
    s
}

/// How far the one angle input of `model` moves from 0 on the assembly mode of the declared
/// guess there (the runtime's `assembly_near`): whether it turns fully (no limit position within
/// a turn either way) or rocks between two limit positions, as a designer asks of a linkage
/// first (a four-bar's Grashof type, told by its motion rather than by its link lengths);
/// where the mechanism does not assemble at 0, the stretch nearest it. `None` for other
/// mechanisms, or where a parameter has no value.
fn motion(model: &mut Model) -> Option<String> {
    let one_angle = model.input_kinds() == [QuantityKind::Angle];
    if !one_angle || model.param_values().iter().any(Option::is_none) {
        return None;
    }
    // Said in the command line's terms: the solves' refusal gives the library's advice.
    if let Some(why) = crate::params::imprecise_angle(model) {
        return Some(format!("not determined: {why}"));
    }
    let input = model.inputs()[0].clone();
    let found = match model.assembly_near(&[0.0], ASSEMBLY_SAMPLES) {
        Ok(Some(found)) => found,
        Ok(None) => {
            return Some(format!(
                "from the declared guess, the mechanism assembles at none of {ASSEMBLY_SAMPLES} values of {input} over \
                 a turn"
            ));
        }
        // A change point (a parallelogram's, its links in line): two branches cross there.
        Err(Error::SweepStopped { kind: EventKind::SingularCrossing, at }) => {
            let x = at.inputs.first().map_or(f64::NAN, |(_, v)| *v);
            return Some(format!(
                "{input} meets a change point at {input} = {} on the assembly mode of the declared guess at 0: two \
                 branches of the motion cross there, and the input alone does not say which one the linkage follows \
                 (`kinloop sweep --through-crossings` goes on along the smooth continuation)",
                Number(x)
            ));
        }
        Err(e) => return Some(format!("not determined: {e}")),
    };
    let [from, to] = crate::assembles::ends(&found, false);
    let ends = format!("{from} and {to}");
    Some(match (found.found[0] == 0.0, found.turns_fully()) {
        (true, true) => format!(
            "{input} turns fully from 0 on the assembly mode of the declared guess (no limit position within a turn \
             either way)"
        ),
        (true, false) => format!("from 0 on the assembly mode of the declared guess, {input} moves between {ends}"),
        (false, true) => format!(
            "the point solve at {input} = 0 from the declared guess fails, but {input} turns fully on the assembly \
             mode found at {}",
            Number(found.found[0])
        ),
        (false, false) => format!(
            "the mechanism does not assemble at {input} = 0 from the declared guess; nearest, it does between {ends}"
        ),
    })
}
