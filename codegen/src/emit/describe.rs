//! The human-readable description of a mechanism's decomposition, generated as the constant
//! `Name::DECOMPOSITION`:
//!
//! ```text
//! SliderCrank: 2 unknowns, 2 scalar equations, 1 input (mobility W = 1); 2 blocks in solve order
//!   block 0 (closed form, angle equation): psi <- oabo.y
//!   block 1 (linear, 1x1): x <- oabo.x
//! ```
//!
//! One line per block, in solve order (the index is the one of `Name::BLOCKS` and of the
//! runtime's error locations): how it is solved (`closed form, ...` names the recognised Assur
//! group, `Newton, NxN` iterates (`Newton, NxN sparse (K non-zeros)`: a large block
//! factorised along its sparsity), `linear, NxN` is one linear solve because the block's
//! unknowns appear linearly), its unknowns and its scalar equations (`loop.x`, `loop.y`, or an
//! `eq` name).

use crate::plan::Plan;
use crate::plan::solve::Solve;
use crate::semantics::model::Model;

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Renders the decomposition of `plan` (see the module docs).
pub fn decomposition(model: &Model, plan: &Plan) -> String {
    let n_u = model.unknowns.len();
    let n_eq = model.equations.len();
    let n_in = model.inputs.len();
    let mobility = n_u as i64 + n_in as i64 - n_eq as i64;
    let mut s = format!(
        "{}: {}, {}, {} (mobility W = {mobility}); {}",
        syn::ext::IdentExt::unraw(&model.name),
        plural(n_u, "unknown", "unknowns"),
        plural(n_eq, "scalar equation", "scalar equations"),
        plural(n_in, "input", "inputs"),
        plural(plan.blocks.len(), "block", "blocks"),
    );
    s.push_str(if model.options.dense.is_some() {
        " (dense: decomposition disabled by #[kinloop(dense)])"
    } else {
        " in solve order"
    });
    for (k, b) in plan.blocks.iter().enumerate() {
        let unknowns: Vec<String> =
            b.unknowns.iter().map(|&u| syn::ext::IdentExt::unraw(&model.unknowns[u].name).to_string()).collect();
        let equations: Vec<&str> = b.equations.iter().map(|&e| model.equations[e].name.as_str()).collect();
        s.push_str(&format!(
            "\n  block {k} ({}): {} <- {}",
            // How the block is solved.
            match &b.solve {
                Solve::ClosedForm(c) => c.form.describe().to_string(),
                Solve::Fixed { .. } | Solve::Linear { .. } => {
                    format!("linear, {}x{}", b.equations.len(), b.unknowns.len())
                }
                Solve::NewtonSparse(sp) => format!(
                    "Newton, {}x{} sparse ({} non-zeros)",
                    b.equations.len(),
                    b.unknowns.len(),
                    sp.entries.len()
                ),
                Solve::Newton => format!("Newton, {}x{}", b.equations.len(), b.unknowns.len()),
            },
            unknowns.join(", "),
            equations.join(", ")
        ));
    }
    s
}
