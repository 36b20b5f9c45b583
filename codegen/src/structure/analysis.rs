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

use crate::diag::Warning;
use crate::expr::SpanRange;
use crate::model::Model;
use crate::structure::{self, Block};
use crate::syntax::Errors;
use std::collections::BTreeSet;

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Most names a list in a message spells out; the rest are counted.
const LIST_MAX: usize = 8;

/// `` `a`, `b`, `c` `` (at most [`LIST_MAX`] names, then "and N more").
fn list(names: impl Iterator<Item = String>) -> String {
    let names: Vec<String> = names.collect();
    let mut out = names.iter().take(LIST_MAX).map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ");
    if names.len() > LIST_MAX {
        out.push_str(&format!(" and {} more", names.len() - LIST_MAX));
    }
    out
}

/// `loop name` or `eq name`, as the user wrote the item.
fn item_label(model: &Model, e: usize) -> String {
    let eq = &model.equations[e];
    format!("{} {}", if eq.is_loop { "loop" } else { "eq" }, eq.item)
}

/// Checks the structure and returns the blocks in solve order.
pub fn analyze(model: &Model) -> Result<Vec<Block>, syn::Error> {
    let mut errors = Errors::default();
    let n_eq = model.equations.len();
    let n_u = model.unknowns.len();
    let inc = structure::incidence(model);

    // ------------------------------------------------------------------ local mistakes
    // Equations without unknowns, reported once per item (a loop's x and y share the item).
    let empty: BTreeSet<usize> = (0..n_eq).filter(|&e| inc[e].is_empty()).collect();
    let mut reported_items = BTreeSet::new();
    for &e in &empty {
        let eq = &model.equations[e];
        if !reported_items.insert(eq.item.to_string()) {
            continue;
        }
        let both = eq.is_loop && (0..n_eq).filter(|&k| model.equations[k].item == eq.item).all(|k| empty.contains(&k));
        let what = if !eq.is_loop {
            format!("`eq {}` contains no unknown", eq.item)
        } else if both {
            format!("`loop {}` contains no unknown", eq.item)
        } else {
            let axis = if eq.name.ends_with(".x") { "x" } else { "y" };
            format!("the {axis} projection of `loop {}` (`{}`) contains no unknown", eq.item, eq.name)
        };
        errors.push(eq.range.error(format!(
            "{what}: it only relates parameters and inputs, so it cannot be solved for anything\n\
             help: remove it, or declare the quantity it should determine with `unknowns`"
        )));
    }
    let mut appears = vec![false; n_u];
    for s in &inc {
        for &u in s {
            appears[u] = true;
        }
    }
    let isolated: BTreeSet<usize> = (0..n_u).filter(|&u| !appears[u]).collect();
    for &u in &isolated {
        let unk = &model.unknowns[u].name;
        errors.push(syn::Error::new(
            unk.span(),
            format!(
                "unknown `{unk}` appears in no `loop` or `eq`, so nothing determines it\n\
                 help: use it in a loop or equation, or remove it (a value computed from the others \
                 is a `let`, a `point` or an `output`)"
            ),
        ));
    }
    for (i, used) in model.used_inputs.iter().enumerate() {
        if !used {
            let inp = &model.inputs[i].name;
            errors.push(syn::Error::new(
                inp.span(),
                format!(
                    "input `{inp}` is never used, so nothing moves with it\n\
                     help: use it in a loop, an equation or a `let`, or remove it"
                ),
            ));
        }
    }

    // ------------------------------------------------------------------ counts and DM
    // The structural summary comes first: it is at the mechanism's name, above everything else.
    let matching = structure::maximum_matching(&inc, n_u);
    let mut structural = Errors::default();
    if n_eq != n_u || !matching.is_perfect() {
        let dm = structure::dulmage_mendelsohn(&inc, n_u, &matching);
        report_imbalance(model, &dm, &empty, &isolated, &mut structural);
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

/// Unused parameters. They are warnings, not errors, by choice: the mechanism is still well
/// posed (unlike with an unused input, which would claim a degree of freedom nothing moves
/// with), and a parameter may be kept on purpose for the user's own computations (a mass, a
/// speed); refusing to compile would be wrong. Procedural macros cannot emit warnings on stable
/// Rust, so they reach the user as a `deprecated` lint at the parameter's name (see
/// [`crate::diag`]), which `-D warnings` turns into an error like any warning. A parameter whose
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

/// The primary error at the mechanism's name and the notes at each place of the parts.
fn report_imbalance(
    model: &Model,
    dm: &structure::Imbalance,
    empty: &BTreeSet<usize>,
    isolated: &BTreeSet<usize>,
    errors: &mut Errors,
) {
    let name = &model.name;
    let n_eq = model.equations.len();
    let n_u = model.unknowns.len();
    let n_in = model.inputs.len();
    // What the local errors above have not explained yet.
    let over_notes: Vec<usize> = dm.over_equations.iter().copied().filter(|e| !empty.contains(e)).collect();
    let under_notes: Vec<usize> = dm.under_unknowns.iter().copied().filter(|u| !isolated.contains(u)).collect();
    if n_eq == n_u && over_notes.is_empty() && under_notes.is_empty() {
        return;
    }

    let eq_names = |s: &BTreeSet<usize>| list(s.iter().map(|&e| model.equations[e].name.clone()));
    let u_names = |s: &BTreeSet<usize>| list(s.iter().map(|&u| model.unknowns[u].name.to_string()));
    let eqs = |n: usize| plural(n, "scalar equation", "scalar equations");
    let unks = |n: usize| plural(n, "unknown", "unknowns");

    let headline = if n_eq < n_u {
        format!("`{name}` is under-determined: {} for {}", eqs(n_eq), unks(n_u))
    } else if n_eq > n_u {
        format!("`{name}` is over-determined: {} for {}", eqs(n_eq), unks(n_u))
    } else {
        format!(
            "`{name}` is structurally singular: {} for {}, but they do not pair up \
             (some equations fix too many unknowns, others too few)",
            eqs(n_eq),
            unks(n_u)
        )
    };
    let mobility = n_u as i64 + n_in as i64 - n_eq as i64;
    let verdict = if mobility == n_in as i64 {
        format!("as declared ({})", plural(n_in, "input", "inputs"))
    } else {
        format!("but {} declared", plural(n_in, "input is", "inputs are"))
    };
    let mut msg = format!(
        "{headline}\nmobility W = {} + {} - {} = {mobility}, {verdict}",
        plural(n_u, "unknown", "unknowns"),
        plural(n_in, "input", "inputs"),
        plural(n_eq, "equation", "equations")
    );
    let mut help = Vec::new();
    if !dm.over_equations.is_empty() {
        let surplus = dm.over_equations.len().saturating_sub(dm.over_unknowns.len()).max(1);
        let verb = if dm.over_equations.len() == 1 { "involves" } else { "involve" };
        if dm.over_unknowns.is_empty() {
            msg.push_str(&format!(
                "\nover-determined part: {} {} {verb} no unknown",
                plural(dm.over_equations.len(), "equation", "equations"),
                eq_names(&dm.over_equations)
            ));
        } else {
            msg.push_str(&format!(
                "\nover-determined part: {} {} {verb} only {} {}",
                plural(dm.over_equations.len(), "equation", "equations"),
                eq_names(&dm.over_equations),
                plural(dm.over_unknowns.len(), "unknown", "unknowns"),
                u_names(&dm.over_unknowns)
            ));
        }
        help.push(if over_notes.is_empty() {
            // Only equations without unknowns: their own errors say what to do.
            format!("remove {} (see the errors below)", eq_names(&dm.over_equations))
        } else {
            format!(
                "remove {} of the over-determined part (a loop that repeats another contour?), \
                 or turn {} it uses into {}",
                eqs(surplus),
                plural(surplus, "parameter", "parameters"),
                if surplus == 1 { "an unknown" } else { "unknowns" }
            )
        });
    }
    if !dm.under_unknowns.is_empty() {
        let missing = dm.under_unknowns.len().saturating_sub(dm.under_equations.len()).max(1);
        let verb = if dm.under_unknowns.len() == 1 { "appears" } else { "appear" };
        if dm.under_equations.is_empty() {
            msg.push_str(&format!(
                "\nunder-determined part: {} {} {verb} in no equation",
                plural(dm.under_unknowns.len(), "unknown", "unknowns"),
                u_names(&dm.under_unknowns)
            ));
        } else {
            msg.push_str(&format!(
                "\nunder-determined part: {} {} {verb} in only {} {}",
                plural(dm.under_unknowns.len(), "unknown", "unknowns"),
                u_names(&dm.under_unknowns),
                plural(dm.under_equations.len(), "equation", "equations"),
                eq_names(&dm.under_equations)
            ));
        }
        help.push(if under_notes.is_empty() {
            // Only unknowns in no equation: their own errors say what to do.
            format!(
                "use {} in a loop or equation, or remove {} (see the errors below)",
                u_names(&dm.under_unknowns),
                if dm.under_unknowns.len() == 1 { "it" } else { "them" }
            )
        } else {
            format!(
                "add {} involving the under-determined unknowns (a `loop` gives two, an `eq` one), \
                 or turn {} of them into {}",
                eqs(missing),
                missing,
                if missing == 1 { "an input" } else { "inputs" }
            )
        });
    }
    for h in help {
        msg.push_str("\nhelp: ");
        msg.push_str(&h);
    }
    errors.push(syn::Error::new(name.span(), msg));

    // Notes: each loop or equation of the over-determined part, once per item.
    let see = format!("see the error at `{name}`");
    let in_part = |e: usize, part: &BTreeSet<usize>| {
        let label = item_label(model, e);
        let eq = &model.equations[e];
        let members: Vec<usize> = (0..n_eq).filter(|&k| model.equations[k].item == eq.item).collect();
        if eq.is_loop && !members.iter().all(|k| part.contains(k)) {
            // One projection of a loop: say which.
            format!("`{label}` (its equation `{}`)", eq.name)
        } else {
            format!("`{label}`")
        }
    };
    let mut seen = BTreeSet::new();
    for &e in &over_notes {
        if seen.insert(model.equations[e].item.to_string()) {
            let what = in_part(e, &dm.over_equations);
            errors.push(model.equations[e].range.error(format!("{what} is in the over-determined part ({see})")));
        }
    }
    // Notes: runs of neighbouring under-determined unknowns of one declaration, underlined
    // together, then the loops and equations of the under-determined part.
    for run in runs(model, &under_notes) {
        let (first, last) = (&model.unknowns[run[0]].name, &model.unknowns[run[run.len() - 1]].name);
        let range = SpanRange { start: first.span(), end: last.span() };
        let names = list(run.iter().map(|&u| model.unknowns[u].name.to_string()));
        let verb = if run.len() == 1 { "is" } else { "are" };
        errors.push(range.error(format!("{names} {verb} not determined: in the under-determined part ({see})")));
    }
    let mut seen = BTreeSet::new();
    for &e in &dm.under_equations {
        if seen.insert(model.equations[e].item.to_string()) {
            let what = in_part(e, &dm.under_equations);
            errors.push(model.equations[e].range.error(format!("{what} is in the under-determined part ({see})")));
        }
    }
}

/// Splits sorted unknown indices into runs that are consecutive in one declaration item.
fn runs(model: &Model, unknowns: &[usize]) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = Vec::new();
    for &u in unknowns {
        match out.last_mut() {
            Some(run)
                if run.last().is_some_and(|&p| p + 1 == u && model.unknowns[p].item == model.unknowns[u].item) =>
            {
                run.push(u)
            }
            _ => out.push(vec![u]),
        }
    }
    out
}
