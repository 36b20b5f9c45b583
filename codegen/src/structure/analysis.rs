//! Structural checks with diagnostics at the user's spans: counts and mobility, unknowns and
//! equations that do not take part, Dulmage–Mendelsohn over/under-determined parts, unused
//! names, and the block decomposition used by code generation.
//!
//! How the diagnostics are laid out (compile errors cannot carry notes on stable Rust, so every
//! underlined place is an error of its own):
//!
//! * A mistake local to one name gets one error there: an unknown that appears in no equation,
//!   a loop or equation without unknowns, an input that drives nothing.
//! * A structural imbalance gets **one primary error** at the mechanism's name, which states the
//!   counts and the mobility once, names the over- and under-determined parts with their
//!   equations and unknowns, and says what to add or remove; then **one short note per place**
//!   (each loop or equation of a part, each run of neighbouring unknowns) that points back to it.
//!   Names already reported by a local error above are left out of the notes.
//! * An unused parameter is a warning (see [`warnings`]).

use crate::front::syntax::Errors;
use crate::graph::dag::{Leaf, NodeId};
use crate::semantics::model::Model;
use crate::structure::diag::Warning;
use crate::structure::{self, Block};
use std::collections::BTreeSet;

/// Checks the structure and returns the blocks in solve order.
pub fn analyze(model: &Model) -> Result<Vec<Block>, syn::Error> {
    let n_eq = model.equations.len();
    let n_u = model.unknowns.len();
    let inc = structure::incidence(model);
    let mut errors = Errors::default();
    let empty = equations_without_unknowns(model, &inc, &mut errors);
    equations_without_slopes(model, &inc, &mut errors);
    let isolated = unknowns_in_no_equation(model, &inc, &mut errors);
    unused_inputs(model, &mut errors);

    // ------------------------------------------------------------------ counts and DM
    // The structural summary comes first: it is at the mechanism's name, above everything else.
    let matching = structure::maximum_matching(&inc, n_u);
    let mut structural = Errors::default();
    if n_eq != n_u || !matching.is_perfect() {
        let dm = structure::dulmage_mendelsohn(&inc, n_u, &matching);
        super::imbalance::report(model, &dm, &empty, &isolated, &mut structural);
    }
    if let Some(mut e) = structural.into_error() {
        if let Some(local) = errors.into_error() {
            e.combine(local);
        }
        return Err(e);
    }
    if let Some(e) = errors.into_error() {
        return Err(e);
    }
    if model.options.dense.is_some() {
        let all: Vec<usize> = (0..n_u).collect();
        return Ok(if n_u == 0 { Vec::new() } else { vec![Block { unknowns: all.clone(), equations: all }] });
    }
    Ok(structure::blt(&inc, &matching))
}

/// Equations without unknowns, reported once per item (a loop's x and y share the item).
fn equations_without_unknowns(model: &Model, inc: &[BTreeSet<usize>], errors: &mut Errors) -> BTreeSet<usize> {
    let n_eq = model.equations.len();
    let empty: BTreeSet<usize> = (0..n_eq).filter(|&e| inc[e].is_empty()).collect();
    let mut reported_items = BTreeSet::new();
    for &e in &empty {
        let eq = &model.equations[e];
        if !reported_items.insert(eq.item.to_string()) {
            continue;
        }
        let both = eq.is_loop && (0..n_eq).filter(|&k| model.equations[k].item == eq.item).all(|k| empty.contains(&k));
        let item = if eq.is_loop { format!("`loop {}`", eq.item) } else { format!("`eq {}`", eq.item) };
        // The unknowns its source names, whose terms cancel: "only parameters and inputs" would
        // contradict what the user reads in it. (A loop's projection may rightly lack the
        // unknowns its other projection has: said so only where both are empty.)
        let named: Vec<String> =
            eq.written.iter().filter_map(|&u| model.unknowns.get(u)).map(|u| format!("`{}`", u.name)).collect();
        let message = if !named.is_empty() && (!eq.is_loop || both) {
            let them = if named.len() == 1 { "its terms cancel" } else { "their terms cancel" };
            format!(
                "{item} names {} but {them} (as in `x - x` or `x * 0`), so it contains no unknown and cannot \
                 be solved for anything\n\
                 help: write it so that an unknown remains in it, or remove it",
                named.join(", ")
            )
        } else if !eq.is_loop || both {
            format!(
                "{item} contains no unknown: it only relates parameters and inputs, so it cannot be solved \
                 for anything\n\
                 help: remove it, or declare the quantity it should determine with `unknowns`"
            )
        } else {
            // One projection of a loop cannot be removed: the loop is one scalar equation (an
            // `eq` of its other projection), or the projection lacks an unknown.
            let (axis, other) = if eq.name.ends_with(".x") { ("x", "y") } else { ("y", "x") };
            format!(
                "the {axis} projection of `loop {}` (`{}`) contains no unknown: it only relates parameters \
                 and inputs, so it cannot be solved for anything\n\
                 help: if only the {other} projection is an equation, write it as `eq {}: ... == ...;` in \
                 place of the loop; otherwise use in the {axis} projection the unknown it should determine",
                eq.item, eq.name, eq.item
            )
        };
        errors.push(eq.range.error(message));
    }
    empty
}

/// Equations whose unknowns all appear only inside `floor` (or a comparison of `min`, `max`,
/// `clamp`): their derivatives by every unknown are zero, so they can be solved for none of
/// them (every solve would fail as singular), reported once per item.
fn equations_without_slopes(model: &Model, inc: &[BTreeSet<usize>], errors: &mut Errors) {
    let mut reported_items = BTreeSet::new();
    for (e, eq) in model.equations.iter().enumerate() {
        if inc[e].is_empty() || reported_items.contains(&eq.item.to_string()) {
            continue;
        }
        let sloped = model.graph.differentiable_leaves_of(&[eq.residual]);
        if sloped.iter().any(|l| matches!(l, crate::graph::dag::Leaf::Unknown(_))) {
            continue;
        }
        reported_items.insert(eq.item.to_string());
        let names: Vec<String> =
            inc[e].iter().filter_map(|&u| model.unknowns.get(u)).map(|u| format!("`{}`", u.name)).collect();
        let what =
            if eq.is_loop { format!("`{}` of `loop {}`", eq.name, eq.item) } else { format!("`eq {}`", eq.item) };
        errors.push(eq.range.error(format!(
            "{what} has {} only inside `floor`, whose derivative is zero, so it cannot be solved for {}; \
             write the equation so that an unknown appears outside `floor` (use `wrap(x, period)` to reduce \
             an unknown by whole turns)",
            names.join(", "),
            if names.len() == 1 { "it" } else { "them" }
        )));
    }
}

/// Unknowns that appear in no equation.
fn unknowns_in_no_equation(model: &Model, inc: &[BTreeSet<usize>], errors: &mut Errors) -> BTreeSet<usize> {
    let n_u = model.unknowns.len();
    let mut appears = vec![false; n_u];
    for s in inc {
        for &u in s {
            appears[u] = true;
        }
    }
    let isolated: BTreeSet<usize> = (0..n_u).filter(|&u| !appears[u]).collect();
    for &u in &isolated {
        let unk = &model.unknowns[u].name;
        let message = if model.written_in_equations.get(u).copied().unwrap_or(false) {
            format!(
                "unknown `{unk}` is written in a `loop` or `eq`, but its terms there cancel (as in `{unk} - {unk}`), \
                 so nothing determines it\n\
                 help: check the equations it is written in; if nothing should determine it, remove it"
            )
        } else if let Some(column) = first_output_using(model, u) {
            // Named in an output alone: removing it would leave that output undefined, so say
            // what to write in its place.
            format!(
                "unknown `{unk}` is used in {column} but appears in no `loop` or `eq`, so nothing \
                 determines it\n\
                 help: use it in a loop or equation; if it is a value computed from the others, \
                 declare it with `let {unk} = ...;` in place of the unknown"
            )
        } else {
            format!(
                "unknown `{unk}` appears in no `loop` or `eq`, so nothing determines it\n\
                 help: use it in a loop or equation, or remove it (a value computed from the others \
                 is a `let`, a `point` or an `output`)"
            )
        };
        errors.push(syn::Error::new(unk.span(), message));
    }
    isolated
}

/// The first `point` or `output` whose value depends on unknown `u`, as `` `point p` ``.
fn first_output_using(model: &Model, u: usize) -> Option<String> {
    let uses = |node: NodeId| model.graph.leaves_of(&[node]).contains(&Leaf::Unknown(u as u16));
    let point = model.points.iter().find(|p| uses(p.x) || uses(p.y)).map(|p| format!("`point {}`", p.name));
    point.or_else(|| model.scalars.iter().find(|s| uses(s.value)).map(|s| format!("`output {}`", s.name)))
}

/// Inputs nothing depends on: named nowhere, or named only where no equation or output depends
/// on them (an initial guess, a `let` that nothing uses, terms that cancel).
fn unused_inputs(model: &Model, errors: &mut Errors) {
    let mut roots: Vec<NodeId> = model.equations.iter().map(|e| e.residual).collect();
    roots.extend(model.output_nodes());
    let moved = model.graph.leaves_of(&roots);
    for (i, named) in model.used_inputs.iter().enumerate() {
        if moved.contains(&Leaf::Input(i as u16)) {
            continue;
        }
        let inp = &model.inputs[i].name;
        let message = if *named {
            format!(
                "input `{inp}` moves nothing: no loop, equation or output depends on it (it is named only in \
                 an initial guess or a `let` that nothing uses, or its terms cancel, as in `{inp} - {inp}`)\n\
                 help: use it in a loop, an equation or an output, or remove it"
            )
        } else {
            format!(
                "input `{inp}` is never used, so nothing moves with it\n\
                 help: use it in a loop, an equation or an output (directly or through a `let` they use), \
                 or remove it"
            )
        };
        errors.push(syn::Error::new(inp.span(), message));
    }
}

/// Unused parameters. They are warnings, not errors, by choice: the mechanism is still well
/// posed (unlike with an unused input, which would claim a degree of freedom nothing moves
/// with), and a parameter may be kept on purpose for the user's own computations (a mass, a
/// speed); refusing to compile would be wrong. Procedural macros cannot emit warnings on stable
/// Rust, so they reach the user as a `deprecated` lint at the parameter's name (see
/// [`crate::structure::diag`]), which `-D warnings` turns into an error like any warning. A parameter whose
/// name starts with `_` is never reported, as in Rust.
pub fn warnings(model: &Model) -> Vec<Warning> {
    model
        .used_params
        .iter()
        .zip(&model.params)
        .filter(|(used, p)| !**used && !p.name.to_string().starts_with('_'))
        .map(|(_, p)| Warning {
            span: p.name.span(),
            tag: format!("unused_parameter_{}", p.name),
            message: format!(
                "parameter `{}` is used in no loop, equation, `let` or output; remove it, \
                 or name it `_{}` to keep it on purpose",
                p.name, p.name
            ),
        })
        .collect()
}
