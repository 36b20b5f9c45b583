//! The diagnosis of a structurally singular system: one primary error at the mechanism's name
//! (counts, mobility, the over- and under-determined parts, what to add or remove), then one
//! short note per place that takes part.

use super::Imbalance;
use crate::front::expr::SpanRange;
use crate::front::syntax::Errors;
use crate::graph::dag::Leaf;
use crate::semantics::model::Model;
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

/// The primary error at the mechanism's name and the notes at each place of the parts.
pub(super) fn report(
    model: &Model,
    dm: &Imbalance,
    empty: &BTreeSet<usize>,
    isolated: &BTreeSet<usize>,
    errors: &mut Errors,
) {
    let name = &model.name;
    let n_eq = model.equations.len();
    let n_u = model.unknowns.len();
    // What the local errors above have not explained yet.
    let over_notes: Vec<usize> = dm.over_equations.iter().copied().filter(|e| !empty.contains(e)).collect();
    let under_notes: Vec<usize> = dm.under_unknowns.iter().copied().filter(|u| !isolated.contains(u)).collect();
    if n_eq == n_u && over_notes.is_empty() && under_notes.is_empty() {
        return;
    }

    let mut msg = summary(model);
    let mut help = Vec::new();
    if !dm.over_equations.is_empty() {
        over_part(model, dm, &over_notes, &mut msg, &mut help);
    }
    if !dm.under_unknowns.is_empty() {
        under_part(model, dm, &under_notes, &mut msg, &mut help);
    }
    for h in help {
        msg.push_str("\nhelp: ");
        msg.push_str(&h);
    }
    errors.push(syn::Error::new(name.span(), msg));

    notes(model, dm, &over_notes, &under_notes, errors);
}

/// The headline with the counts, and the mobility.
fn summary(model: &Model) -> String {
    let name = &model.name;
    let (n_eq, n_u, n_in) = (model.equations.len(), model.unknowns.len(), model.inputs.len());
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
    format!(
        "{headline}\nmobility W = {} + {} - {} = {mobility}, {verdict}",
        plural(n_u, "unknown", "unknowns"),
        plural(n_in, "input", "inputs"),
        plural(n_eq, "equation", "equations")
    )
}

/// Names of equations (`eq_names`) and unknowns (`u_names`), as a message lists them.
fn namers(model: &Model) -> (impl Fn(&BTreeSet<usize>) -> String + '_, impl Fn(&BTreeSet<usize>) -> String + '_) {
    (
        |s: &BTreeSet<usize>| list(s.iter().map(|&e| model.equations[e].name.clone())),
        |s: &BTreeSet<usize>| list(s.iter().map(|&u| model.unknowns[u].name.to_string())),
    )
}

/// Describes the over-determined part in `msg` and adds its help lines. `involved`: the
/// equations of the part that involve some unknown; the others (no unknown at all) have their
/// own errors, so they are listed apart and counted in no surplus.
fn over_part(model: &Model, dm: &Imbalance, involved: &[usize], msg: &mut String, help: &mut Vec<String>) {
    let (eq_names, u_names) = namers(model);
    let eqs = |n: usize| plural(n, "scalar equation", "scalar equations");
    let involved: BTreeSet<usize> = involved.iter().copied().collect();
    let empty: BTreeSet<usize> = dm.over_equations.difference(&involved).copied().collect();
    let no_unknown = |set: &BTreeSet<usize>| {
        let verb = if set.len() == 1 { "involves" } else { "involve" };
        format!("{} {} {verb} no unknown", plural(set.len(), "equation", "equations"), eq_names(set))
    };
    msg.push_str("\nover-determined part: ");
    if involved.is_empty() {
        msg.push_str(&no_unknown(&empty));
    } else {
        let verb = if involved.len() == 1 { "involves" } else { "involve" };
        msg.push_str(&format!(
            "{} {} {verb} only {} {}",
            plural(involved.len(), "equation", "equations"),
            eq_names(&involved),
            plural(dm.over_unknowns.len(), "unknown", "unknowns"),
            u_names(&dm.over_unknowns)
        ));
        if !empty.is_empty() {
            msg.push_str(&format!(", and {}", no_unknown(&empty)));
        }
        let surplus = involved.len().saturating_sub(dm.over_unknowns.len()).max(1);
        // Only what the part uses can become an unknown: equations of constants and inputs
        // (`eq e: x == 1; eq f: x == 2;`) have no parameter to offer.
        let leaves = leaves_of_equations(model, &involved);
        let params = leaves.iter().filter(|l| matches!(l, Leaf::Param(_))).count() >= surplus;
        let what = match (inputs_may_become_unknowns(model, &leaves, surplus), params) {
            (true, true) => Some(plural(surplus, "parameter or input", "parameters or inputs")),
            (true, false) => Some(plural(surplus, "input", "inputs")),
            (false, true) => Some(plural(surplus, "parameter", "parameters")),
            (false, false) => None,
        };
        let turn = match what {
            Some(what) => {
                format!(", or turn {what} it uses into {}", if surplus == 1 { "an unknown" } else { "unknowns" })
            }
            None => String::new(),
        };
        help.push(format!(
            "remove {} of the over-determined part (a loop that repeats another contour?){turn}",
            eqs(surplus)
        ));
    }
    if !empty.is_empty() {
        help.push(empty_help(model, &empty));
    }
}

/// The help for equations without unknowns, whose own errors follow: an `eq` or a whole loop is
/// removed; a loop's projection cannot be, so the loop becomes an `eq` of its other projection
/// (or gains the unknown the projection lacks).
fn empty_help(model: &Model, empty: &BTreeSet<usize>) -> String {
    let (eq_names, _) = namers(model);
    let lone = |e: &usize| {
        let eq = &model.equations[*e];
        eq.is_loop && model.equations.iter().enumerate().any(|(k, o)| o.item == eq.item && !empty.contains(&k))
    };
    let (projections, whole): (BTreeSet<usize>, BTreeSet<usize>) = empty.iter().copied().partition(lone);
    let mut parts = Vec::new();
    if !whole.is_empty() {
        parts.push(format!("remove {}", eq_names(&whole)));
    }
    if !projections.is_empty() {
        let loops = list(projections.iter().map(|&e| format!("loop {}", model.equations[e].item)));
        let one = projections.len() == 1;
        parts.push(format!(
            "write {loops} as {} of {} other projection, or use in {} the unknown {} should determine",
            if one { "an `eq`" } else { "`eq`s" },
            if one { "its" } else { "their" },
            eq_names(&projections),
            if one { "it" } else { "each" }
        ));
    }
    format!("{} (see the errors below)", parts.join("; "))
}

/// Whether turning `surplus` inputs into unknowns is a fix to offer: the equations depend on an
/// input (one of their `leaves`), and one input at least is left to drive the mechanism. A
/// quantity declared an input that the loops determine (`inputs phi, x;` for a slider's `x`)
/// over-determines them so.
fn inputs_may_become_unknowns(model: &Model, leaves: &[Leaf], surplus: usize) -> bool {
    model.inputs.len() > surplus && leaves.iter().any(|l| matches!(l, Leaf::Input(_)))
}

/// The leaves (parameters, inputs, unknowns) the residuals of `equations` depend on: what an
/// over-determined part could turn into unknowns.
fn leaves_of_equations(model: &Model, equations: &BTreeSet<usize>) -> Vec<Leaf> {
    let residuals: Vec<_> = equations.iter().map(|&e| model.equations[e].residual).collect();
    model.graph.leaves_of(&residuals)
}

/// Describes the under-determined part in `msg` and adds its help lines. `involved`: the
/// unknowns of the part that appear in some equation; the others (in no equation at all, or
/// whose terms cancel) have their own errors, so they are listed apart and counted in no
/// missing equation: an unknown in no equation does not appear in the part's equations.
fn under_part(model: &Model, dm: &Imbalance, involved: &[usize], msg: &mut String, help: &mut Vec<String>) {
    let (eq_names, u_names) = namers(model);
    let eqs = |n: usize| plural(n, "scalar equation", "scalar equations");
    let involved: BTreeSet<usize> = involved.iter().copied().collect();
    let absent: BTreeSet<usize> = dm.under_unknowns.difference(&involved).copied().collect();
    let in_no_equation = |set: &BTreeSet<usize>| {
        let verb = if set.len() == 1 { "appears" } else { "appear" };
        format!("{} {} {verb} in no equation", plural(set.len(), "unknown", "unknowns"), u_names(set))
    };
    msg.push_str("\nunder-determined part: ");
    if involved.is_empty() {
        msg.push_str(&in_no_equation(&absent));
    } else {
        let verb = if involved.len() == 1 { "appears" } else { "appear" };
        msg.push_str(&format!(
            "{} {} {verb} in only {} {}",
            plural(involved.len(), "unknown", "unknowns"),
            u_names(&involved),
            plural(dm.under_equations.len(), "equation", "equations"),
            eq_names(&dm.under_equations)
        ));
        if !absent.is_empty() {
            msg.push_str(&format!(", and {}", in_no_equation(&absent)));
        }
        let missing = involved.len().saturating_sub(dm.under_equations.len()).max(1);
        let them = if absent.is_empty() { "the under-determined unknowns".to_string() } else { u_names(&involved) };
        help.push(format!(
            "add {} involving {them} (a `loop` gives two, an `eq` one), or turn {} of them into {}",
            eqs(missing),
            missing,
            if missing == 1 { "an input" } else { "inputs" }
        ));
    }
    if !absent.is_empty() {
        help.push(absent_help(model, &absent));
    }
}

/// The help for unknowns in no equation, whose own errors follow: written in equations where
/// their terms cancel, or never used in one.
fn absent_help(model: &Model, absent: &BTreeSet<usize>) -> String {
    let (_, u_names) = namers(model);
    let one = absent.len() == 1;
    let written = |u: &usize| model.written_in_equations.get(*u).copied().unwrap_or(false);
    if absent.iter().all(written) {
        format!(
            "check the equations {} {} written in: {} terms cancel there (see the errors below)",
            u_names(absent),
            if one { "is" } else { "are" },
            if one { "its" } else { "their" }
        )
    } else {
        format!(
            "use {} in a loop or equation, or remove {} (see the errors below)",
            u_names(absent),
            if one { "it" } else { "them" }
        )
    }
}

/// One short note per loop or equation of each part and per run of under-determined unknowns,
/// each pointing back to the primary error.
fn notes(model: &Model, dm: &Imbalance, over_notes: &[usize], under_notes: &[usize], errors: &mut Errors) {
    let name = &model.name;
    let n_eq = model.equations.len();
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
    for &e in over_notes {
        if seen.insert(model.equations[e].item.to_string()) {
            let what = in_part(e, &dm.over_equations);
            errors.push(model.equations[e].range.error(format!("{what} is in the over-determined part ({see})")));
        }
    }
    // Notes: runs of neighbouring under-determined unknowns of one declaration, underlined
    // together, then the loops and equations of the under-determined part.
    for run in runs(model, under_notes) {
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
