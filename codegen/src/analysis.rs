//! Structural checks with diagnostics at the user's spans: counts and mobility, unknowns and
//! equations that do not take part, Dulmage–Mendelsohn over/under-determined parts, and the
//! block decomposition used by code generation.

use crate::model::Model;
use crate::structure::{self, Block};
use crate::syntax::Errors;
use std::collections::BTreeSet;

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

fn list(names: impl Iterator<Item = String>) -> String {
    names.map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
}

/// Checks the structure and returns the blocks in solve order.
pub fn analyze(model: &Model) -> Result<Vec<Block>, syn::Error> {
    let mut errors = Errors::default();
    let n_eq = model.equations.len();
    let n_u = model.unknowns.len();
    let n_in = model.inputs.len();
    let inc = structure::incidence(model);
    let name = &model.name;

    for (e, eq) in model.equations.iter().enumerate() {
        if inc[e].is_empty() {
            errors.push(eq.range.error(format!(
                "equation `{}` contains no unknown: it only relates parameters and inputs, so it cannot be \
                 solved for anything; remove it, or make one of its names an unknown",
                eq.name
            )));
        }
    }
    let mut appears = vec![false; n_u];
    for s in &inc {
        for &u in s {
            appears[u] = true;
        }
    }
    for (u, unk) in model.unknowns.iter().enumerate() {
        if !appears[u] {
            errors.push(syn::Error::new(
                unk.name.span(),
                format!(
                    "unknown `{}` appears in no equation, so nothing determines it; use it in a `loop` or `eq`, \
                     or remove it (a value computed from the others is a `let` or an `output`)",
                    unk.name
                ),
            ));
        }
    }
    for (i, used) in model.used_inputs.iter().enumerate() {
        if !used {
            let inp = &model.inputs[i].name;
            errors.push(syn::Error::new(
                inp.span(),
                format!(
                    "input `{inp}` is never used: the mechanism would not move with it; use it in a loop, \
                     an equation or a `let`, or remove it"
                ),
            ));
        }
    }
    for (k, used) in model.used_params.iter().enumerate() {
        if !used {
            let p = &model.params[k].name;
            errors.push(syn::Error::new(
                p.span(),
                format!("parameter `{p}` is never used; use it in a loop, equation or output, or remove it"),
            ));
        }
    }

    if n_eq != n_u {
        let mobility = n_u as i64 + n_in as i64 - n_eq as i64;
        let advice = if n_eq < n_u {
            format!(
                "add {} (each `loop` gives two), or declare {} more input{}",
                plural(n_u - n_eq, "scalar equation", "scalar equations"),
                n_u - n_eq,
                if n_u - n_eq == 1 { "" } else { "s" }
            )
        } else {
            format!(
                "remove {} or declare {} more unknown{}",
                plural(n_eq - n_u, "scalar equation", "scalar equations"),
                n_eq - n_u,
                if n_eq - n_u == 1 { "" } else { "s" }
            )
        };
        errors.push(syn::Error::new(
            name.span(),
            format!(
                "`{name}` has {} for {}: its mobility is W = {n_u} + {n_in} - {n_eq} = {mobility}, but {} declared; {advice}",
                plural(n_eq, "scalar equation", "scalar equations"),
                plural(n_u, "unknown", "unknowns"),
                plural(n_in, "input is", "inputs are"),
            ),
        ));
    }

    let matching = structure::maximum_matching(&inc, n_u);
    if !matching.is_perfect() {
        let dm = structure::dulmage_mendelsohn(&inc, n_u, &matching);
        report_imbalance(
            model,
            &dm.over_equations,
            &dm.over_unknowns,
            &dm.under_unknowns,
            &dm.under_equations,
            &mut errors,
        );
    }
    if !errors.is_empty() {
        return Err(errors.into_error().unwrap_or_else(|| syn::Error::new(name.span(), "invalid mechanism")));
    }
    if model.options.dense.is_some() {
        let all: Vec<usize> = (0..n_u).collect();
        return Ok(if n_u == 0 { Vec::new() } else { vec![Block { unknowns: all.clone(), equations: all }] });
    }
    Ok(structure::blt(&inc, &matching))
}

fn report_imbalance(
    model: &Model,
    over_eq: &BTreeSet<usize>,
    over_u: &BTreeSet<usize>,
    under_u: &BTreeSet<usize>,
    under_eq: &BTreeSet<usize>,
    errors: &mut Errors,
) {
    let eq_names = |s: &BTreeSet<usize>| list(s.iter().map(|&e| model.equations[e].name.clone()));
    let u_names = |s: &BTreeSet<usize>| list(s.iter().map(|&u| model.unknowns[u].name.to_string()));
    if !over_eq.is_empty() {
        let msg = format!(
            "over-determined: the {} {} can only fix the {} {}; they cannot all hold in general. \
             Remove one of these equations (a loop that repeats another contour?) or declare another unknown",
            plural(over_eq.len(), "equation", "equations"),
            eq_names(over_eq),
            plural(over_u.len(), "unknown", "unknowns"),
            if over_u.is_empty() { "(none)".to_string() } else { u_names(over_u) },
        );
        let mut err: Option<syn::Error> = None;
        // Point at each offending loop once (a loop's x and y share a range).
        let mut seen = BTreeSet::new();
        for &e in over_eq {
            let key = model.equations[e].name.split('.').next().unwrap_or("").to_string();
            if !seen.insert(key) {
                continue;
            }
            let one = model.equations[e].range.error(&msg);
            match &mut err {
                Some(all) => all.combine(one),
                None => err = Some(one),
            }
        }
        if let Some(e) = err {
            errors.push(e);
        }
    }
    if !under_u.is_empty() {
        let msg = format!(
            "under-determined: the {} {} {} fixed by the equations ({} among them for {}); \
             add a loop or equation that involves {}, or declare an input that drives {}",
            plural(under_u.len(), "unknown", "unknowns"),
            u_names(under_u),
            if under_u.len() == 1 { "is not" } else { "are not" },
            plural(under_eq.len(), "equation", "equations"),
            plural(under_u.len(), "unknown", "unknowns"),
            if under_u.len() == 1 { "it" } else { "them" },
            if under_u.len() == 1 { "it" } else { "them" },
        );
        for &u in under_u {
            errors.push(syn::Error::new(model.unknowns[u].name.span(), &msg));
        }
    }
}
