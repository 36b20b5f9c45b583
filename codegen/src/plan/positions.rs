//! Positions: the full Jacobians, and per block its residuals, Jacobian, column scales and
//! whether it is linear in its unknowns.

use super::{BlockPlan, rows_from_columns};
use crate::dag::{Graph, Leaf, NodeId};
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

/// The position part of a block's plan (its analogs and sensitivities are filled in later).
pub fn block(g: &mut Graph, blk: &Block, residuals: &[NodeId], jac_full: &[Vec<NodeId>]) -> BlockPlan {
    let f: Vec<NodeId> = blk.equations.iter().map(|&e| residuals[e]).collect();
    let jac: Vec<Vec<NodeId>> =
        blk.equations.iter().map(|&e| blk.unknowns.iter().map(|&u| jac_full[e][u]).collect()).collect();
    // Column scales: every structurally non-zero entry of the unknown's full Jacobian column.
    let col_scale: Vec<Vec<NodeId>> =
        blk.unknowns.iter().map(|&u| jac_full.iter().map(|row| row[u]).filter(|&n| !g.is_zero(n)).collect()).collect();
    let own: Vec<Leaf> = blk.unknowns.iter().map(|&a| Leaf::Unknown(a as u16)).collect();
    let linear = !g.leaves_of(&jac.concat()).iter().any(|l| own.contains(l));
    let rhs0 = if linear {
        let zero = g.zero();
        let f0 = g.substitute(&f, &|l| own.contains(&l).then_some(zero));
        f0.into_iter().map(|x| g.neg(x)).collect()
    } else {
        Vec::new()
    };
    BlockPlan {
        unknowns: blk.unknowns.clone(),
        equations: blk.equations.clone(),
        linear,
        f,
        jac,
        col_scale,
        lever_floor: vec![Vec::new(); blk.unknowns.len()],
        turns: vec![false; blk.unknowns.len()],
        rhs0,
        vel: Vec::new(),
        acc: Vec::new(),
        sens: None,
        closed: None,
        sparse: None,
        scale: Vec::new(),
        unit: Vec::new(),
    }
}
