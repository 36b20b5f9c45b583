//! The computation plan: every symbolic derivative the generated code evaluates, built by
//! forward-mode differentiation of the declared equations on the shared graph.
//!
//! For an equation `f(q(x), x) = 0` with unknowns `q` and inputs `x`:
//!
//! * position Newton needs `f` and `J = df/dq` per block;
//! * velocity analogs solve `J_bb q'_b = -T_i f_b` where `T_i` is the total derivative along
//!   input `i` with the block's own analogs set to zero (earlier blocks' analogs are known);
//! * acceleration analogs solve `J_bb q''_b = -T_j T_i f_b`, again with the block's own second
//!   analogs set to zero: this is the second directional derivative of `f` along `(q', 1)`.
//!
//! The analogs themselves are leaves of the graph (`Tan`, `Tan2`), so the same machinery gives
//! the outputs' analogs by the chain rule.

use crate::dag::{Graph, Leaf, NodeId, Op};
use crate::model::Model;
use crate::structure::Block;

pub struct BlockPlan {
    pub unknowns: Vec<usize>,
    pub equations: Vec<usize>,
    /// `J_bb` does not depend on the block's unknowns: solved by one linear solve.
    pub linear: bool,
    /// Residuals of the block's equations.
    pub f: Vec<NodeId>,
    /// `jac[r][c] = d f_r / d q_c` over the block's unknowns.
    pub jac: Vec<Vec<NodeId>>,
    /// For linear blocks: the residuals with the block's unknowns set to zero.
    pub f0: Vec<NodeId>,
    /// `vel[r][i]`: minus the velocity right-hand side.
    pub vel: Vec<Vec<NodeId>>,
    /// `acc[r][p]`: minus the acceleration right-hand side for input pair `p`.
    pub acc: Vec<Vec<NodeId>>,
}

pub struct Plan {
    pub n: usize,
    pub ni: usize,
    pub blocks: Vec<BlockPlan>,
    /// Unknown index -> its block.
    pub block_of: Vec<usize>,
    pub residuals: Vec<NodeId>,
    pub outputs: Vec<NodeId>,
    /// `out_d1[o][i]`.
    pub out_d1: Vec<Vec<NodeId>>,
    /// `out_d2[o][p]` for input pair `p`.
    pub out_d2: Vec<Vec<NodeId>>,
    /// Declared initial guesses (0 when not declared).
    pub guesses: Vec<NodeId>,
    /// Parameter defaults, when every parameter has one.
    pub defaults: Option<Vec<f64>>,
    /// Per node: highest block whose unknowns it depends on (`-1`: none).
    pub level: Vec<i32>,
}

/// Input pairs `(i, j)` with `i <= j`, in the order second analogs are stored.
pub fn pairs(ni: usize) -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    for i in 0..ni {
        for j in i..ni {
            v.push((i, j));
        }
    }
    v
}

pub fn pair_index(ni: usize, i: usize, j: usize) -> usize {
    let (i, j) = if i <= j { (i, j) } else { (j, i) };
    pairs(ni).iter().position(|&p| p == (i, j)).unwrap_or(0)
}

pub fn build(model: &mut Model, blocks: &[Block]) -> Plan {
    let n = model.unknowns.len();
    let ni = model.inputs.len();
    let mut block_of = vec![0usize; n];
    for (b, blk) in blocks.iter().enumerate() {
        for &u in &blk.unknowns {
            block_of[u] = b;
        }
    }
    let residuals: Vec<NodeId> = model.equations.iter().map(|e| e.residual).collect();
    let outputs = model.output_nodes();
    let g = &mut model.graph;
    let one = g.one();
    let tan: Vec<Vec<NodeId>> =
        (0..n).map(|a| (0..ni).map(|i| g.leaf(Leaf::Tan { unknown: a as u16, input: i as u16 })).collect()).collect();
    let tan2: Vec<Vec<Vec<NodeId>>> = (0..n)
        .map(|a| {
            (0..ni)
                .map(|i| {
                    (0..ni)
                        .map(|j| {
                            let (i, j) = if i <= j { (i, j) } else { (j, i) };
                            g.leaf(Leaf::Tan2 { unknown: a as u16, i: i as u16, j: j as u16 })
                        })
                        .collect()
                })
                .collect()
        })
        .collect();

    // First total derivative along input i; `own` = block whose analogs are left out.
    let first = |g: &mut Graph, roots: &[NodeId], i: usize, own: Option<usize>| {
        let seed = |l: Leaf| match l {
            Leaf::Unknown(a) if own != Some(block_of[a as usize]) => Some(tan[a as usize][i]),
            Leaf::Input(k) if k as usize == i => Some(one),
            _ => None,
        };
        g.tangent(roots, &seed)
    };
    // Derivative along input j of expressions that already contain first analogs.
    let second = |g: &mut Graph, roots: &[NodeId], j: usize, own: Option<usize>| {
        let seed = |l: Leaf| match l {
            Leaf::Unknown(a) => Some(tan[a as usize][j]),
            Leaf::Input(k) if k as usize == j => Some(one),
            Leaf::Tan { unknown, input } if own != Some(block_of[unknown as usize]) => {
                Some(tan2[unknown as usize][input as usize][j])
            }
            _ => None,
        };
        g.tangent(roots, &seed)
    };

    let mut plans = Vec::new();
    for (b, blk) in blocks.iter().enumerate() {
        let f: Vec<NodeId> = blk.equations.iter().map(|&e| residuals[e]).collect();
        let mut cols: Vec<Vec<NodeId>> = Vec::new();
        for &a in &blk.unknowns {
            cols.push(g.tangent(&f, &|l| (l == Leaf::Unknown(a as u16)).then_some(one)));
        }
        let jac: Vec<Vec<NodeId>> = (0..f.len()).map(|r| cols.iter().map(|c| c[r]).collect()).collect();
        let own: Vec<Leaf> = blk.unknowns.iter().map(|&a| Leaf::Unknown(a as u16)).collect();
        let linear = !g.leaves_of(&jac.concat()).iter().any(|l| own.contains(l));
        let f0 = if linear {
            let zero = g.zero();
            g.substitute(&f, &|l| own.contains(&l).then_some(zero))
        } else {
            Vec::new()
        };
        let mut vel = vec![Vec::new(); f.len()];
        let mut full_first = Vec::new();
        for i in 0..ni {
            let v = first(g, &f, i, Some(b));
            for (r, node) in v.into_iter().enumerate() {
                vel[r].push(node);
            }
            full_first.push(first(g, &f, i, None));
        }
        let mut acc = vec![Vec::new(); f.len()];
        for (i, j) in pairs(ni) {
            let d = second(g, &full_first[i], j, Some(b));
            for (r, node) in d.into_iter().enumerate() {
                acc[r].push(node);
            }
        }
        plans.push(BlockPlan {
            unknowns: blk.unknowns.clone(),
            equations: blk.equations.clone(),
            linear,
            f,
            jac,
            f0,
            vel,
            acc,
        });
    }

    let mut out_d1 = vec![Vec::new(); outputs.len()];
    let mut out_first = Vec::new();
    for i in 0..ni {
        let d = first(g, &outputs, i, None);
        for (o, node) in d.iter().enumerate() {
            out_d1[o].push(*node);
        }
        out_first.push(d);
    }
    let mut out_d2 = vec![Vec::new(); outputs.len()];
    for (i, j) in pairs(ni) {
        let d = second(g, &out_first[i], j, None);
        for (o, node) in d.into_iter().enumerate() {
            out_d2[o].push(node);
        }
    }

    let zero = g.zero();
    let guesses = model.unknowns.iter().map(|u| u.value.unwrap_or(zero)).collect();
    let defaults =
        model.params.iter().map(|p| p.value.and_then(|v| model.graph.as_const(v))).collect::<Option<Vec<f64>>>();

    let g = &model.graph;
    let mut level = vec![-1i32; g.len()];
    for k in 0..g.len() {
        let node = NodeId(k as u32);
        level[k] = match g.op(node) {
            Op::Leaf(Leaf::Unknown(a)) => block_of[a as usize] as i32,
            Op::Leaf(Leaf::Tan { .. } | Leaf::Tan2 { .. }) => i32::MAX,
            op => op.operands().map(|o| level[o.index()]).max().unwrap_or(-1),
        };
    }

    Plan { n, ni, blocks: plans, block_of, residuals, outputs, out_d1, out_d2, guesses, defaults, level }
}
