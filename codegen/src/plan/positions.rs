//! Positions: the full Jacobians, and per block its residuals, Jacobian, column scales and
//! whether it is linear in its unknowns.
//!
//! How a block is solved is decided from its [`Position`] in [`super::solve`], which imports it
//! from here; the block's plan is assembled from both by [`super::block_plan::BlockPlan::new`].

use super::columns::rows_from_columns;
use crate::graph::dag::{Graph, Leaf, NodeId};
use crate::structure::Block;

/// `(df/dq, df/dx)` of every equation, each as rows.
pub fn full_jacobians(
    g: &mut Graph,
    residuals: &[NodeId],
    n: usize,
    ni: usize,
) -> (Vec<Vec<NodeId>>, Vec<Vec<NodeId>>) {
    let one = g.one();
    let dq: Vec<Vec<NodeId>> =
        (0..n).map(|a| g.tangent(residuals, &|l| (l == Leaf::Unknown(a as u16)).then_some(one))).collect();
    let dx: Vec<Vec<NodeId>> =
        (0..ni).map(|i| g.tangent(residuals, &|l| (l == Leaf::Input(i as u16)).then_some(one))).collect();
    (rows_from_columns(residuals.len(), dq), rows_from_columns(residuals.len(), dx))
}

/// The position part of a block, from which its solve is decided (see
/// [`super::solve::Solve::decide`]).
pub struct Position {
    /// Residuals of the block's equations.
    pub f: Vec<NodeId>,
    /// `jac[r][c] = d f_r / d q_c` over the block's unknowns.
    pub jac: Vec<Vec<NodeId>>,
    /// Per block unknown: the non-zero entries of its column of the full Jacobian.
    pub col_scale: Vec<Vec<NodeId>>,
    /// When the block is linear in its unknowns (`J_bb` free of them): minus the residuals with
    /// the block's unknowns set to zero, the right-hand side of its linear solve.
    pub rhs: Option<Vec<NodeId>>,
}

/// The position part of a block.
pub fn block(g: &mut Graph, blk: &Block, residuals: &[NodeId], jac_full: &[Vec<NodeId>]) -> Position {
    let f: Vec<NodeId> = blk.equations.iter().map(|&e| residuals[e]).collect();
    let jac: Vec<Vec<NodeId>> =
        blk.equations.iter().map(|&e| blk.unknowns.iter().map(|&u| jac_full[e][u]).collect()).collect();
    // Column scales: every structurally non-zero entry of the unknown's full Jacobian column
    // (those in rows of another unit are weighed once the rows' magnitudes are known, see
    // `column_units`).
    let col_scale: Vec<Vec<NodeId>> =
        blk.unknowns.iter().map(|&u| jac_full.iter().map(|row| row[u]).filter(|&n| !g.is_zero(n)).collect()).collect();
    let own: Vec<Leaf> = blk.unknowns.iter().map(|&a| Leaf::Unknown(a as u16)).collect();
    let linear = !g.leaves_of(&jac.concat()).iter().any(|l| own.contains(l));
    let rhs = linear.then(|| {
        let zero = g.zero();
        let f0 = g.substitute(&f, &|l| own.contains(&l).then_some(zero));
        f0.into_iter().map(|x| g.neg(x)).collect()
    });
    Position { f, jac, col_scale, rhs }
}
