//! `kinloop check`: the structure report of a declaration.

use kinloop_model::{Count, Model};
use std::fmt::Write;

/// The decomposition (counts, mobility, blocks and how each is solved), then the parameters
/// with their values, the quantities with their units, and the size of the run-time program.
pub fn structure(model: &Model) -> String {
    let mut s = format!("{}\n", model.decomposition());
    let params: Vec<String> = model
        .params()
        .iter()
        .zip(model.param_values())
        .map(|(p, v)| match v {
            // As numbers are written elsewhere: `{v}` wrote 1e308 in 309 digits, 1e-300 in 301.
            Some(v) => format!("{p} = {}", kinloop_runtime::Number(*v)),
            None => format!("{p} (no value)"),
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
    s
}
