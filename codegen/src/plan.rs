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
    /// Per block unknown: the non-zero entries of its column of the full Jacobian, whose largest
    /// magnitude equilibrates the column (see `kinloop_runtime::Lu`).
    pub col_scale: Vec<Vec<NodeId>>,
    /// For linear blocks: the residuals with the block's unknowns set to zero.
    pub f0: Vec<NodeId>,
    /// `vel[r][i]`: minus the velocity right-hand side.
    pub vel: Vec<Vec<NodeId>>,
    /// `acc[r][p]`: minus the acceleration right-hand side for input pair `p`.
    pub acc: Vec<Vec<NodeId>>,
    /// Parameter sensitivities, minus the right-hand sides: `sens_q[r][k]`,
    /// `sens_v[r][i * np + k]`, `sens_a[r][p * np + k]`.
    pub sens_q: Vec<Vec<NodeId>>,
    pub sens_v: Vec<Vec<NodeId>>,
    pub sens_a: Vec<Vec<NodeId>>,
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
    /// Output sensitivities: `out_sq[o][k]`, `out_sv[o][i * np + k]`, `out_sa[o][p * np + k]`.
    pub out_sq: Vec<Vec<NodeId>>,
    pub out_sv: Vec<Vec<NodeId>>,
    pub out_sa: Vec<Vec<NodeId>>,
    /// Number of parameters.
    pub np: usize,
    /// Declared initial guesses (0 when not declared).
    pub guesses: Vec<NodeId>,
    /// The full Jacobian `jac_full[e][u] = d f_e / d q_u` (for continuation and event location).
    pub jac_full: Vec<Vec<NodeId>>,
    /// `fx_full[e][i] = d f_e / d x_i`.
    pub fx_full: Vec<Vec<NodeId>>,
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

    // Total derivative along parameter k. The leaves of the stage being solved for (positions,
    // first or second analogs) of block `own` are left out: they form the left-hand side
    // `J_bb * sensitivity`.
    let np = model.params.len();
    let sq: Vec<Vec<NodeId>> =
        (0..n).map(|a| (0..np).map(|k| g.leaf(Leaf::SensQ { unknown: a as u16, param: k as u16 })).collect()).collect();
    let sv: Vec<Vec<Vec<NodeId>>> = (0..n)
        .map(|a| {
            (0..ni)
                .map(|i| {
                    (0..np)
                        .map(|k| g.leaf(Leaf::SensV { unknown: a as u16, input: i as u16, param: k as u16 }))
                        .collect()
                })
                .collect()
        })
        .collect();
    let sa: Vec<Vec<Vec<Vec<NodeId>>>> = (0..n)
        .map(|a| {
            (0..ni)
                .map(|i| {
                    (0..ni)
                        .map(|j| {
                            let (lo, hi) = if i <= j { (i, j) } else { (j, i) };
                            (0..np)
                                .map(|k| {
                                    g.leaf(Leaf::SensA {
                                        unknown: a as u16,
                                        i: lo as u16,
                                        j: hi as u16,
                                        param: k as u16,
                                    })
                                })
                                .collect()
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    let sens = |g: &mut Graph, roots: &[NodeId], k: usize, own: Option<usize>, stage: u8| {
        let mine = |u: u16, st: u8| own == Some(block_of[u as usize]) && stage == st;
        let seed = |l: Leaf| match l {
            Leaf::Param(p) if p as usize == k => Some(one),
            Leaf::Unknown(a) if !mine(a, 0) => Some(sq[a as usize][k]),
            Leaf::Tan { unknown, input } if !mine(unknown, 1) => Some(sv[unknown as usize][input as usize][k]),
            Leaf::Tan2 { unknown, i, j } if !mine(unknown, 2) => Some(sa[unknown as usize][i as usize][j as usize][k]),
            _ => None,
        };
        g.tangent(roots, &seed)
    };

    let mut jac_full = vec![Vec::new(); residuals.len()];
    for a in 0..n {
        let col = g.tangent(&residuals, &|l| (l == Leaf::Unknown(a as u16)).then_some(one));
        for (e, node) in col.into_iter().enumerate() {
            jac_full[e].push(node);
        }
    }
    let mut fx_full = vec![Vec::new(); residuals.len()];
    for i in 0..ni {
        let col = g.tangent(&residuals, &|l| (l == Leaf::Input(i as u16)).then_some(one));
        for (e, node) in col.into_iter().enumerate() {
            fx_full[e].push(node);
        }
    }

    let mut plans = Vec::new();
    for (b, blk) in blocks.iter().enumerate() {
        let f: Vec<NodeId> = blk.equations.iter().map(|&e| residuals[e]).collect();
        let jac: Vec<Vec<NodeId>> =
            blk.equations.iter().map(|&e| blk.unknowns.iter().map(|&u| jac_full[e][u]).collect()).collect();
        // Column scales: every structurally non-zero entry of the unknown's full Jacobian column.
        let col_scale: Vec<Vec<NodeId>> = blk
            .unknowns
            .iter()
            .map(|&u| (0..residuals.len()).map(|e| jac_full[e][u]).filter(|&n| !g.is_zero(n)).collect())
            .collect();
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
        let mut full_second = Vec::new();
        for (i, j) in pairs(ni) {
            let d = second(g, &full_first[i], j, Some(b));
            for (r, node) in d.into_iter().enumerate() {
                acc[r].push(node);
            }
            full_second.push(second(g, &full_first[i], j, None));
        }
        let (mut sens_q, mut sens_v, mut sens_a) =
            (vec![Vec::new(); f.len()], vec![Vec::new(); f.len()], vec![Vec::new(); f.len()]);
        for k in 0..np {
            for (r, node) in sens(g, &f, k, Some(b), 0).into_iter().enumerate() {
                sens_q[r].push(node);
            }
        }
        for first_i in &full_first {
            for k in 0..np {
                for (r, node) in sens(g, first_i, k, Some(b), 1).into_iter().enumerate() {
                    sens_v[r].push(node);
                }
            }
        }
        for second_p in &full_second {
            for k in 0..np {
                for (r, node) in sens(g, second_p, k, Some(b), 2).into_iter().enumerate() {
                    sens_a[r].push(node);
                }
            }
        }
        plans.push(BlockPlan {
            unknowns: blk.unknowns.clone(),
            equations: blk.equations.clone(),
            linear,
            f,
            jac,
            col_scale,
            f0,
            vel,
            acc,
            sens_q,
            sens_v,
            sens_a,
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

    let (mut out_sq, mut out_sv, mut out_sa) =
        (vec![Vec::new(); outputs.len()], vec![Vec::new(); outputs.len()], vec![Vec::new(); outputs.len()]);
    for k in 0..np {
        for (o, node) in sens(g, &outputs, k, None, 0).into_iter().enumerate() {
            out_sq[o].push(node);
        }
    }
    for d in &out_first {
        for k in 0..np {
            for (o, node) in sens(g, d, k, None, 0).into_iter().enumerate() {
                out_sv[o].push(node);
            }
        }
    }
    for p in 0..pairs(ni).len() {
        let roots: Vec<NodeId> = out_d2.iter().map(|row| row[p]).collect();
        for k in 0..np {
            for (o, node) in sens(g, &roots, k, None, 0).into_iter().enumerate() {
                out_sa[o].push(node);
            }
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
            Op::Leaf(l) if l.is_derived() => i32::MAX,
            op => op.operands().map(|o| level[o.index()]).max().unwrap_or(-1),
        };
    }

    Plan {
        n,
        ni,
        blocks: plans,
        block_of,
        residuals,
        outputs,
        out_d1,
        out_d2,
        out_sq,
        out_sv,
        out_sa,
        np,
        guesses,
        jac_full,
        fx_full,
        defaults,
        level,
    }
}
