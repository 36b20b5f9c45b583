//! The unknowns whose equations repeat every turn.
//!
//! An angle `q` that enters its block's equations only through sines and cosines of whole
//! multiples of itself (`l @ q`, `l @ (q + gamma)`, `r @ (2 q)`) leaves every residual unchanged
//! when it moves by a whole turn: `q` and `q + 2 pi` are the same position. Newton's method does
//! not know that and may end turns away from its guess (a long step from a near-singular
//! Jacobian); the runtime then moves such an unknown back to its guess's turn, as a closed form
//! does. An angle that also enters otherwise does not repeat: a rolling contact `x == r q`, a
//! half angle `l @ (q / 2)`, a parameter multiple `l @ (k q)`.
//!
//! Each residual is classified bottom-up ([`multiples`]): free of `q`, an integer multiple of
//! `q` plus a part free of it, a function that repeats every turn of `q`, or anything else. Only
//! the rows whose Jacobian entry in `q`'s column is not the constant zero are looked at (the
//! others do not contain `q`), so the pass costs about the block's own graph, not the graph
//! times the block.

use super::block_plan::BlockPlan;
use crate::graph::dag::{Graph, Leaf, NodeId};
use crate::graph::multiples::{self, Class};

/// Per unknown of block `bp`, whether its equations repeat every turn of it (see the module
/// documentation).
pub fn turns(g: &Graph, bp: &BlockPlan) -> Vec<bool> {
    (0..bp.unknowns.len())
        .map(|c| {
            let u = bp.unknowns[c];
            let rows: Vec<NodeId> =
                bp.f.iter().zip(&bp.jac).filter(|(_, row)| !g.is_zero(row[c])).map(|(&f, _)| f).collect();
            let class = multiples::classify(g, Leaf::Unknown(u as u16), &rows);
            rows.iter().all(|r| matches!(class.get(r), Some(Class::Free | Class::Periodic)))
        })
        .collect()
}
