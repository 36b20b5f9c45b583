//! The leaves that stand for derived quantities (analogs, sensitivities) and the directional
//! derivatives seeded with them.

use super::input_pairs::pairs;
use crate::graph::dag::{Graph, Leaf, NodeId};
use crate::structure::Block;

/// Leaves of the derived quantities, and which block solves each unknown.
pub struct Seeds {
    /// The constant one: the seed of the input (or parameter) being differentiated along.
    pub one: NodeId,
    ni: usize,
    np: usize,
    /// `block_of[u]`: the index of the block that solves unknown `u`.
    pub block_of: Vec<usize>,
    /// `tan[u][i]`: first analog `d q_u / d x_i`.
    tan: Vec<Vec<NodeId>>,
    /// `tan2[u][i][j]`: second analog (symmetric in `i`, `j`).
    tan2: Vec<Vec<Vec<NodeId>>>,
    /// Sensitivity leaves (empty unless requested): `sq[u][k]`, `sv[u][i][k]`, `sa[u][i][j][k]`.
    sq: Vec<Vec<NodeId>>,
    sv: Vec<Vec<Vec<NodeId>>>,
    sa: Vec<Vec<Vec<Vec<NodeId>>>>,
}

fn ordered(i: usize, j: usize) -> (u16, u16) {
    let (lo, hi) = if i <= j { (i, j) } else { (j, i) };
    (lo as u16, hi as u16)
}

impl Seeds {
    /// The leaves for `n` unknowns, `ni` inputs and `np` parameters (the sensitivity leaves only
    /// when `sens`).
    pub fn new(g: &mut Graph, n: usize, ni: usize, np: usize, blocks: &[Block], sens: bool) -> Seeds {
        let mut block_of = vec![0usize; n];
        for (b, blk) in blocks.iter().enumerate() {
            for &u in &blk.unknowns {
                block_of[u] = b;
            }
        }
        let mut leaf = |l: Leaf| g.leaf(l);
        let u16s = |k: usize| k as u16;
        let tan =
            (0..n).map(|a| (0..ni).map(|i| leaf(Leaf::Tan { unknown: u16s(a), input: u16s(i) })).collect()).collect();
        let pair = |a: usize, i: usize, j: usize, leaf: &mut dyn FnMut(Leaf) -> NodeId| {
            let (i, j) = ordered(i, j);
            leaf(Leaf::Tan2 { unknown: a as u16, i, j })
        };
        let tan2 =
            (0..n).map(|a| (0..ni).map(|i| (0..ni).map(|j| pair(a, i, j, &mut leaf)).collect()).collect()).collect();
        let np = if sens { np } else { 0 };
        let sq =
            (0..n).map(|a| (0..np).map(|k| leaf(Leaf::SensQ { unknown: u16s(a), param: u16s(k) })).collect()).collect();
        let sv = (0..n)
            .map(|a| {
                (0..ni)
                    .map(|i| {
                        (0..np)
                            .map(|k| leaf(Leaf::SensV { unknown: u16s(a), input: u16s(i), param: u16s(k) }))
                            .collect()
                    })
                    .collect()
            })
            .collect();
        let sa_leaf = |a: usize, i: usize, j: usize, k: usize, leaf: &mut dyn FnMut(Leaf) -> NodeId| {
            let (i, j) = ordered(i, j);
            leaf(Leaf::SensA { unknown: a as u16, i, j, param: k as u16 })
        };
        let sa = (0..n)
            .map(|a| {
                (0..ni)
                    .map(|i| (0..ni).map(|j| (0..np).map(|k| sa_leaf(a, i, j, k, &mut leaf)).collect()).collect())
                    .collect()
            })
            .collect();
        let one = g.one();
        Seeds { one, ni, np, block_of, tan, tan2, sq, sv, sa }
    }

    /// First total derivative of `roots` along input `i`; the analogs of block `own` are left
    /// out (they are what the block solves for).
    pub fn first(&self, g: &mut Graph, roots: &[NodeId], i: usize, own: Option<usize>) -> Vec<NodeId> {
        let seed = |l: Leaf| match l {
            Leaf::Unknown(a) if own != Some(self.block_of[a as usize]) => Some(self.tan[a as usize][i]),
            Leaf::Input(k) if k as usize == i => Some(self.one),
            _ => None,
        };
        g.tangent(roots, &seed)
    }

    /// Derivative along input `j` of expressions that already contain first analogs.
    pub fn second(&self, g: &mut Graph, roots: &[NodeId], j: usize, own: Option<usize>) -> Vec<NodeId> {
        let seed = |l: Leaf| match l {
            Leaf::Unknown(a) => Some(self.tan[a as usize][j]),
            Leaf::Input(k) if k as usize == j => Some(self.one),
            Leaf::Tan { unknown, input } if own != Some(self.block_of[unknown as usize]) => {
                Some(self.tan2[unknown as usize][input as usize][j])
            }
            _ => None,
        };
        g.tangent(roots, &seed)
    }

    /// Total derivative along parameter `k`. The leaves of the stage being solved for (0:
    /// positions, 1: first analogs, 2: second analogs) of block `own` are left out: they form
    /// the left-hand side `J_bb * sensitivity`. Needs the sensitivity leaves (`Seeds::new` with
    /// `sens`).
    pub fn param(&self, g: &mut Graph, roots: &[NodeId], k: usize, own: Option<usize>, stage: u8) -> Vec<NodeId> {
        let mine = |u: u16, st: u8| own == Some(self.block_of[u as usize]) && stage == st;
        let seed = |l: Leaf| match l {
            Leaf::Param(p) if p as usize == k => Some(self.one),
            Leaf::Unknown(a) if !mine(a, 0) => Some(self.sq[a as usize][k]),
            Leaf::Tan { unknown, input } if !mine(unknown, 1) => Some(self.sv[unknown as usize][input as usize][k]),
            Leaf::Tan2 { unknown, i, j } if !mine(unknown, 2) => {
                Some(self.sa[unknown as usize][i as usize][j as usize][k])
            }
            _ => None,
        };
        g.tangent(roots, &seed)
    }

    /// The input pairs of the second analogs.
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        pairs(self.ni)
    }

    /// Number of inputs.
    pub fn ni(&self) -> usize {
        self.ni
    }

    /// Number of parameters with sensitivity leaves (0 unless requested).
    pub fn np(&self) -> usize {
        self.np
    }
}
