//! The plan of one block of the decomposition: how its positions are solved, and every
//! derivative and magnitude computed for it.

use super::positions::Position;
use super::solve::Solve;
use super::sparse;
use super::stages::Stages;
use crate::front::syntax::Options;
use crate::graph::dag::NodeId;
use crate::graph::dag::{Graph, Leaf};
use crate::structure::Block;

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
    /// magnitude equilibrates the column (see `kinloop_runtime::Lu`); an entry in a row of
    /// another unit than the block's weighed into the block's (see
    /// [`column_units`](super::column_units)).
    pub col_scale: Vec<Vec<NodeId>>,
    /// Per block unknown: the lever floors its column's magnitude is raised to (see
    /// [`magnitudes`](super::magnitudes)); empty for most columns.
    pub lever_floor: Vec<Vec<NodeId>>,
    /// Per block row, what the analogs' factorisation divides it by before its columns, where
    /// the block's rows have more than one unit (their magnitudes, and `col_scale` holds each
    /// entry over its row's: see [`column_units`](super::column_units)); empty where the
    /// columns alone are equilibrated.
    pub row_scale: Vec<NodeId>,
    /// `vel[r][i]`: the velocity right-hand side.
    pub vel: Vec<Vec<NodeId>>,
    /// `acc[r][p]`: the acceleration right-hand side for input pair `p`.
    pub acc: Vec<Vec<NodeId>>,
    /// Right-hand sides of the parameter sensitivities, when requested.
    pub sens: Option<Stages>,
    /// Per row: the magnitude of the equation's terms (see [`magnitudes`](super::magnitudes)).
    pub scale: Vec<NodeId>,
    /// Per block unknown: the unit its Newton steps are judged in (see
    /// [`magnitudes`](super::magnitudes)).
    pub unit: Vec<NodeId>,
    /// Per block unknown of a Newton block: whether its equations repeat every turn of it
    /// (see [`turns`](super::turns)); all `false` for the other blocks.
    pub turns: Vec<bool>,
    /// A closed form solved from one equation `a cos q + b sin q = c` of its angle alone (an
    /// angle equation; an angle and a slider, from the combination of its rows free of the
    /// slider): the magnitude of the terms that equation is made of, in which a miss of its
    /// limit position is judged (see [`magnitudes::closed_form_terms`](super::magnitudes)).
    /// `None` for the other blocks.
    pub terms: Option<NodeId>,
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
            row_scale: Vec::new(),
            turns: vec![false; blk.unknowns.len()],
            terms: None,
            vel: Vec::new(),
            acc: Vec::new(),
            sens: None,
            scale: Vec::new(),
            unit: Vec::new(),
        }
    }

    /// The solve of a [`Solve::Linear`] block whose factorisation cannot be made before the
    /// block is solved: the largest magnitudes that equilibrate its columns (every entry of each
    /// column, and its lever floors) are known before the block only if they depend on no
    /// unknown of the block or of a later one (`solved[u]`: unknown `u` is solved before the
    /// block). A later equation's entry in the column can: `y == sin(x)` puts `-cos x` in the
    /// column of `x`. Such a block is solved by Newton instead (over a sparse factorisation where
    /// `Solve::decide` would take one), which factorises its analogs after every position is
    /// known; `None` where the linear solve stands (and for the other solves: a
    /// [`Solve::Fixed`] coefficient is its own scale).
    pub fn without_unknown_scales(&self, g: &mut Graph, solved: &[bool], options: &Options) -> Option<Solve> {
        if !matches!(self.solve, Solve::Linear { .. }) {
            return None;
        }
        let scales: Vec<NodeId> =
            self.col_scale.iter().chain(&self.lever_floor).flatten().chain(&self.row_scale).copied().collect();
        let unknown = g.leaves_of(&scales).into_iter().any(|l| matches!(l, Leaf::Unknown(u) if !solved[u as usize]));
        if !unknown {
            return None;
        }
        Some(match options.dense.is_none().then(|| sparse::analyse(g, &self.jac)).flatten() {
            Some(sp) => Solve::NewtonSparse(Box::new(sp)),
            None => Solve::Newton,
        })
    }
}
