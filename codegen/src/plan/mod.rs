//! The computation plan: every symbolic derivative the generated code evaluates, built by
//! forward-mode differentiation of the declared equations on the shared graph.
//!
//! For an equation `f(q(x), x) = 0` with unknowns `q` and inputs `x`:
//!
//! * position Newton needs `f` and `J = df/dq` per block ([`positions`]); how each block is
//!   solved is decided once, from them ([`solve`]: directly when it is linear, in closed form
//!   when it is a classical Assur group, [`closed_form`], otherwise by Newton, dense or
//!   [`sparse`]);
//! * velocity analogs solve `J_bb q'_b = -T_i f_b` where `T_i` is the total derivative along
//!   input `i` with the block's own analogs set to zero (earlier blocks' analogs are known);
//!   acceleration analogs solve `J_bb q''_b = -T_j T_i f_b`, again with the block's own second
//!   analogs set to zero: the second directional derivative of `f` along `(q', 1)` ([`analogs`]);
//! * the outputs' analogs follow by the chain rule ([`outputs`]);
//! * parameter sensitivities, only when the declaration asks for them ([`sensitivities`]);
//! * the magnitude of every equation's terms and the unit of every unknown, in which the
//!   runtime's convergence tests are made ([`magnitudes`]), and by which a column's entries in
//!   rows of another unit are weighed into its block's ([`column_units`]);
//! * read from the finished plan by the emitter: which values a kernel's finiteness test must
//!   add up, the others' finiteness implying the rest ([`finite`]).
//!
//! The analogs themselves are leaves of the graph (`Tan`, `Tan2`, ...), created by [`seeds`].
//! Each pass adds nodes to the graph; [`build`] runs them in order and returns a [`Plan`]
//! ([`finished`]) that owns the finished graph and is not changed afterwards, with a
//! [`BlockPlan`] per block ([`block_plan`]) and the sensitivities by [`Stages`] ([`stages`]).
//! What the passes share has a module of its own: the order of input pairs ([`input_pairs`]),
//! rows from columns ([`columns`]), the parameters' defaults ([`defaults`]); and so has what more
//! than one back end reads from the finished plan: the closed-form angles
//! ([`closed_form_angles`](mod@closed_form_angles)) and whether the positions may jump
//! ([`piecewise`](mod@piecewise)).

pub mod analogs;
pub mod block_plan;
pub mod closed_form;
pub mod closed_form_angles;
pub mod column_units;
pub mod columns;
pub mod defaults;
pub mod finished;
pub mod finite;
pub mod followers;
pub mod input_pairs;
pub mod kinds;
pub mod magnitudes;
pub mod outputs;
pub mod piecewise;
pub mod positions;
pub mod seeds;
pub mod sensitivities;
pub mod solve;
pub mod sparse;
pub mod stages;
pub mod turns;

pub use block_plan::BlockPlan;
pub use closed_form_angles::closed_form_angles;
pub use columns::rows_from_columns;
pub use defaults::{model_defaults, param_defaults};
pub use finished::Plan;
pub use input_pairs::{pair_index, pairs};
pub use piecewise::piecewise;
pub use stages::Stages;

use crate::graph::dag::{Graph, Leaf, NodeId, Op};
use crate::semantics::model::Model;
use crate::structure::Block;
use seeds::Seeds;
use solve::Solve;

/// Runs every pass over the model's graph, which the plan takes over.
pub fn build(model: &mut Model, blocks: &[Block], with_sensitivities: bool) -> Plan {
    let defaults = model_defaults(model);
    let residuals: Vec<NodeId> = model.equations.iter().map(|e| e.residual).collect();
    let outputs = model.output_nodes();
    let mut g = std::mem::take(&mut model.graph);
    let (n, ni, np) = (model.unknowns.len(), model.inputs.len(), model.params.len());
    let seeds = Seeds::new(&mut g, n, ni, np, blocks, with_sensitivities);
    let full = positions::full_jacobians(&mut g, &residuals, n, ni);
    // Every block's position part first, then each one's solve: the graph's nodes (whose order
    // names the generated temporaries) are added in that order. Closed-form recognition adds
    // nodes too: before the levels are computed.
    let positions: Vec<positions::Position> =
        blocks.iter().map(|blk| positions::block(&mut g, blk, &residuals, &full.0)).collect();
    let mut plans: Vec<BlockPlan> = blocks
        .iter()
        .zip(positions)
        .map(|(blk, pos)| {
            let solve = Solve::decide(&mut g, blk, &pos, np, &model.options);
            BlockPlan::new(blk, pos, solve)
        })
        .collect();
    for bp in plans.iter_mut().filter(|bp| bp.solve.is_newton()) {
        bp.turns = turns::turns(&g, bp);
    }
    let mut mags = magnitudes::Magnitudes::new(&g, &residuals);
    let row_powers = kinds::row_powers(model, &g, &residuals, &outputs);
    for bp in plans.iter_mut() {
        (bp.scale, bp.unit) = mags.block(&mut g, bp);
        bp.lever_floor = mags.lever_floors(&mut g, bp);
        column_units::weigh(&mut g, &mut mags, bp, &full.0, &residuals, &row_powers);
    }
    // A linear block whose column scales are not known before its solve is solved by Newton.
    let mut solved = vec![false; n];
    for bp in plans.iter_mut() {
        if let Some(solve) = bp.without_unknown_scales(&mut g, &solved, &model.options) {
            bp.solve = solve;
            bp.turns = turns::turns(&g, bp);
        }
        for &u in &bp.unknowns {
            solved[u] = true;
        }
    }
    let scale_full = residuals.iter().map(|&r| mags.of(&mut g, r)).collect();
    let mut unit_full = vec![g.one(); n];
    for bp in &plans {
        for (c, &u) in bp.unknowns.iter().enumerate() {
            unit_full[u] = bp.unit[c];
        }
    }
    let input_unit = (0..ni).map(|i| mags.input_unit(&mut g, &residuals, &full.1, i)).collect();
    let mut firsts = Vec::new();
    for (b, bp) in plans.iter_mut().enumerate() {
        firsts.push(analogs::block(&mut g, &seeds, b, bp));
    }
    let (out_d1, out_d2, out_first) = outputs::analogs(&mut g, &seeds, &outputs);
    let mut out_sens = None;
    if with_sensitivities {
        for (b, (bp, (first, second))) in plans.iter_mut().zip(&firsts).enumerate() {
            bp.sens = Some(sensitivities::block(&mut g, &seeds, b, &bp.f, first, second));
        }
        out_sens = Some(sensitivities::outputs(&mut g, &seeds, &outputs, &out_first, &out_d2));
    }
    // The sines and cosines of the parameter angles that sums of angles are computed from, last:
    // no pass differentiates them.
    crate::graph::angle_sums::provide(&mut g);
    // The closed forms' terms, read only where a limit position is missed, after every other
    // node: the temporaries' names stay as they were.
    for bp in plans.iter_mut() {
        bp.terms = mags.closed_form_terms(&mut g, bp);
    }
    let zero = g.zero();
    let guesses = model.unknowns.iter().map(|u| u.value.unwrap_or(zero)).collect();
    let level = levels(&g, &seeds.block_of);
    Plan {
        graph: g,
        n,
        ni,
        np,
        blocks: plans,
        residuals,
        outputs,
        out_d1,
        out_d2,
        out_sens,
        guesses,
        jac_full: full.0,
        fx_full: full.1,
        scale_full,
        unit_full,
        input_unit,
        defaults,
        level,
    }
}

/// Per node, the highest block whose unknowns it depends on (`-1`: none; derived leaves such as
/// analogs are known only after every position, `i32::MAX`).
fn levels(g: &Graph, block_of: &[usize]) -> Vec<i32> {
    let mut level = vec![-1i32; g.len()];
    for k in 0..g.len() {
        level[k] = match g.op(NodeId(k as u32)) {
            Op::Leaf(Leaf::Unknown(a)) => block_of[a as usize] as i32,
            Op::Leaf(l) if l.is_derived() => i32::MAX,
            op => op.operands().map(|o| level[o.index()]).max().unwrap_or(-1),
        };
    }
    level
}
