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
//!   runtime's convergence tests are made ([`magnitudes`]);
//! * read from the finished plan by the emitter: which values a kernel's finiteness test must
//!   add up, the others' finiteness implying the rest ([`finite`]).
//!
//! The analogs themselves are leaves of the graph (`Tan`, `Tan2`, ...), created by [`seeds`].
//! Each pass adds nodes to the graph; [`build`] runs them in order and returns a [`Plan`] that
//! owns the finished graph and is not changed afterwards.

pub mod analogs;
pub mod closed_form;
pub mod finite;
pub mod followers;
pub mod kinds;
pub mod magnitudes;
pub mod outputs;
pub mod positions;
pub mod seeds;
pub mod sensitivities;
pub mod solve;
pub mod sparse;
pub mod turns;

use crate::graph::dag::{Graph, Leaf, NodeId, Op};
use crate::semantics::model::Model;
use crate::structure::Block;
use positions::Position;
use seeds::Seeds;
use solve::Solve;

/// Everything computed for one block of the decomposition.
pub struct BlockPlan {
    /// The block's unknowns (indices into the model's unknowns).
    pub unknowns: Vec<usize>,
    /// The block's equations (indices into the model's equations).
    pub equations: Vec<usize>,
    /// How the block's positions are solved.
    pub solve: Solve,
    /// Residuals of the block's equations.
    pub f: Vec<NodeId>,
    /// `jac[r][c] = d f_r / d q_c` over the block's unknowns.
    pub jac: Vec<Vec<NodeId>>,
    /// Per block unknown: the non-zero entries of its column of the full Jacobian, whose largest
    /// magnitude equilibrates the column (see `kinloop_runtime::Lu`).
    pub col_scale: Vec<Vec<NodeId>>,
    /// Per block unknown: the lever floors its column's magnitude is raised to (see
    /// [`magnitudes`]); empty for most columns.
    pub lever_floor: Vec<Vec<NodeId>>,
    /// `vel[r][i]`: the velocity right-hand side.
    pub vel: Vec<Vec<NodeId>>,
    /// `acc[r][p]`: the acceleration right-hand side for input pair `p`.
    pub acc: Vec<Vec<NodeId>>,
    /// Right-hand sides of the parameter sensitivities, when requested.
    pub sens: Option<Stages>,
    /// Per row: the magnitude of the equation's terms (see [`magnitudes`]).
    pub scale: Vec<NodeId>,
    /// Per block unknown: the unit its Newton steps are judged in (see [`magnitudes`]).
    pub unit: Vec<NodeId>,
    /// Per block unknown of a Newton block: whether its equations repeat every turn of it
    /// (see [`turns`]); all `false` for the other blocks.
    pub turns: Vec<bool>,
}

impl BlockPlan {
    /// The plan of block `blk` from its position part and its solve (its magnitudes, analogs and
    /// sensitivities are filled in later).
    pub fn new(blk: &Block, pos: Position, solve: Solve) -> BlockPlan {
        // The linear right-hand side went into `solve`.
        let Position { f, jac, col_scale, rhs: _ } = pos;
        BlockPlan {
            unknowns: blk.unknowns.clone(),
            equations: blk.equations.clone(),
            solve,
            f,
            jac,
            col_scale,
            lever_floor: vec![Vec::new(); blk.unknowns.len()],
            turns: vec![false; blk.unknowns.len()],
            vel: Vec::new(),
            acc: Vec::new(),
            sens: None,
            scale: Vec::new(),
            unit: Vec::new(),
        }
    }
}

/// Right-hand sides (per row) or values (per output) of the parameter sensitivities, by stage:
/// `q[r][k]`, `v[r][i * np + k]`, `a[r][p * np + k]` for parameter `k`, input `i`, input pair `p`.
pub struct Stages {
    /// Position stage, per parameter.
    pub q: Vec<Vec<NodeId>>,
    /// Velocity-analog stage, per input and parameter.
    pub v: Vec<Vec<NodeId>>,
    /// Acceleration-analog stage, per input pair and parameter.
    pub a: Vec<Vec<NodeId>>,
}

/// The finished plan; it owns the graph every `NodeId` refers to.
pub struct Plan {
    /// The finished expression graph.
    pub graph: Graph,
    /// Number of unknowns (and scalar equations).
    pub n: usize,
    /// Number of inputs.
    pub ni: usize,
    /// Number of parameters.
    pub np: usize,
    /// The blocks in solve order.
    pub blocks: Vec<BlockPlan>,
    /// Residuals of all equations, in declaration order.
    pub residuals: Vec<NodeId>,
    /// Output columns: each point's x and y, then each scalar output.
    pub outputs: Vec<NodeId>,
    /// `out_d1[o][i]`.
    pub out_d1: Vec<Vec<NodeId>>,
    /// `out_d2[o][p]` for input pair `p`.
    pub out_d2: Vec<Vec<NodeId>>,
    /// Output sensitivities, when requested.
    pub out_sens: Option<Stages>,
    /// Declared initial guesses (0 when not declared).
    pub guesses: Vec<NodeId>,
    /// The full Jacobian `jac_full[e][u] = d f_e / d q_u` (for continuation and event location).
    pub jac_full: Vec<Vec<NodeId>>,
    /// `fx_full[e][i] = d f_e / d x_i`.
    pub fx_full: Vec<Vec<NodeId>>,
    /// `scale_full[e]`: the magnitude of equation `e`'s terms (see [`magnitudes`]).
    pub scale_full: Vec<NodeId>,
    /// `unit_full[u]`: the unit of unknown `u` (its block's, see [`magnitudes`]).
    pub unit_full: Vec<NodeId>,
    /// `input_unit[i]`: the unit of input `i` (see [`magnitudes::Magnitudes::input_unit`]).
    pub input_unit: Vec<NodeId>,
    /// Parameter defaults, when every parameter has one.
    pub defaults: Option<Vec<f64>>,
    /// Per node: highest block whose unknowns it depends on (`-1`: none).
    pub level: Vec<i32>,
}

impl Plan {
    /// Whether the parameter sensitivities were requested.
    pub fn has_sensitivities(&self) -> bool {
        self.out_sens.is_some()
    }
}

/// Per unknown, whether a closed-form block gives it as an angle: the runtime's
/// `CLOSED_FORM_ANGLES`, written by the emitter and read by a run-time model, from one place
/// (see also [`followers::followers`]).
pub fn closed_form_angles(plan: &Plan) -> Vec<bool> {
    let mut out = vec![false; plan.n];
    for u in plan.blocks.iter().filter_map(|bp| bp.solve.closed_form()).flat_map(|r| r.form.angles()) {
        out[u] = true;
    }
    out
}

/// Input pairs `(i, j)` with `i <= j`, in the order second analogs are stored.
pub fn pairs(ni: usize) -> Vec<(usize, usize)> {
    (0..ni).flat_map(|i| (i..ni).map(move |j| (i, j))).collect()
}

/// Index of the input pair `(i, j)` (in either order) among [`pairs`].
pub fn pair_index(ni: usize, i: usize, j: usize) -> usize {
    let (i, j) = if i <= j { (i, j) } else { (j, i) };
    pairs(ni).iter().position(|&p| p == (i, j)).unwrap_or(0)
}

/// Rows from columns: `columns[c][r]` becomes `rows[r][c]` (every pass differentiates one
/// column at a time: one input, one parameter).
pub fn rows_from_columns(rows: usize, columns: impl IntoIterator<Item = Vec<NodeId>>) -> Vec<Vec<NodeId>> {
    let mut out = vec![Vec::new(); rows];
    for col in columns {
        for (r, node) in col.into_iter().enumerate() {
            out[r].push(node);
        }
    }
    out
}

/// The parameters' default values when every parameter has one that is a finite constant: the
/// one rule for `Default`, used by the generated items and by the fallback after an error.
pub fn param_defaults(values: impl IntoIterator<Item = Option<f64>>) -> Option<Vec<f64>> {
    values.into_iter().map(|v| v.filter(|v| v.is_finite())).collect()
}

/// The defaults of a resolved model's parameters (see [`param_defaults`]).
pub fn model_defaults(model: &Model) -> Option<Vec<f64>> {
    param_defaults(model.params.iter().map(|p| p.value.and_then(|v| model.graph.as_const(v))))
}

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
    for bp in plans.iter_mut() {
        (bp.scale, bp.unit) = mags.block(&mut g, bp);
        bp.lever_floor = mags.lever_floors(&mut g, bp);
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
