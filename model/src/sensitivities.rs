//! Parameter sensitivities at run time, for declarations that ask for them
//! (`#[kinloop(sensitivities)]`): per stage (positions, first analogs, second analogs) and block,
//! the plan's right-hand sides solved with the block's factorisation of the kinematic step, then
//! the outputs' by the chain rule — the emitted sensitivity kernel's order and operations.

use crate::factor::Fac;
use crate::tape::{Builder, Segment, Unavailable};
use kinloop_codegen::graph::dag::{Graph, Leaf, Op};
use kinloop_codegen::plan::{Plan, Stages, pairs};

/// Sensitivities of a state to the `np` parameters, flat with the parameter innermost (the
/// runtime's `Sens` with its sizes known at run time).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sensitivities {
    /// `q[u * np + k] = d q_u / d p_k`.
    pub q: Vec<f64>,
    /// `dq[(u * ni + i) * np + k]`.
    pub dq: Vec<f64>,
    /// `d2q[((u * ni + i) * ni + j) * np + k]`.
    pub d2q: Vec<f64>,
    /// `out[o * np + k]`.
    pub out: Vec<f64>,
    /// `dout[(o * ni + i) * np + k]`.
    pub dout: Vec<f64>,
    /// `d2out[((o * ni + i) * ni + j) * np + k]`.
    pub d2out: Vec<f64>,
}

/// One stage of one block: its right-hand sides and where the solutions go.
#[derive(Clone)]
struct StageProg {
    seg: Segment,
    /// `rows[r * width + c]`.
    rows: Vec<u32>,
    width: usize,
    /// Per block unknown and column: the unknown's index and the leaf's register.
    unknowns: Vec<usize>,
    leaves: Vec<Option<u32>>,
}

/// The sensitivity program of a planned declaration.
#[derive(Clone)]
pub(crate) struct SensProg {
    np: usize,
    ni: usize,
    /// `[stage][block]`.
    stages: [Vec<StageProg>; 3],
    out: Segment,
    out_q: Vec<u32>,
    out_v: Vec<u32>,
    out_a: Vec<u32>,
    /// `pair_of[i * ni + j]`.
    pair_of: Vec<usize>,
}

fn stage_rows(s: &Stages, stage: usize) -> &Vec<Vec<kinloop_codegen::graph::dag::NodeId>> {
    [&s.q, &s.v, &s.a][stage]
}

impl SensProg {
    /// Built after the kinematic step's segments (`tape` has them).
    pub(crate) fn build(plan: &Plan, tape: &mut Builder<'_>) -> Result<Option<SensProg>, Unavailable> {
        let Some(os) = &plan.out_sens else { return Ok(None) };
        let g: &Graph = &plan.graph;
        let (ni, np) = (plan.ni, plan.np);
        let pair_list = pairs(ni);
        let find = |l: Leaf| g.find(Op::Leaf(l)).map(|n| n.0);
        let mut stages: [Vec<StageProg>; 3] = Default::default();
        for (stage, progs) in stages.iter_mut().enumerate() {
            for bp in &plan.blocks {
                let Some(st) = &bp.sens else {
                    progs.push(StageProg {
                        seg: Segment::default(),
                        rows: Vec::new(),
                        width: 0,
                        unknowns: Vec::new(),
                        leaves: Vec::new(),
                    });
                    continue;
                };
                let rows = stage_rows(st, stage);
                let seg = tape.segment(&rows.concat(), None)?;
                let width = rows.first().map_or(0, Vec::len);
                let leaves: Vec<Option<u32>> = bp
                    .unknowns
                    .iter()
                    .flat_map(|&u| (0..width).map(move |c| (u as u16, c)))
                    .map(|(u, c)| {
                        let k = (c % np.max(1)) as u16;
                        let slot = c / np.max(1);
                        find(match stage {
                            0 => Leaf::SensQ { unknown: u, param: k },
                            1 => Leaf::SensV { unknown: u, input: slot as u16, param: k },
                            _ => {
                                let (i, j) = pair_list[slot];
                                Leaf::SensA { unknown: u, i: i as u16, j: j as u16, param: k }
                            }
                        })
                    })
                    .collect();
                tape.provide(leaves.iter().flatten().map(|&r| kinloop_codegen::graph::dag::NodeId(r)));
                progs.push(StageProg {
                    seg,
                    rows: rows.concat().iter().map(|n| n.0).collect(),
                    width,
                    unknowns: bp.unknowns.clone(),
                    leaves,
                });
            }
        }
        let roots: Vec<_> = os.q.concat().into_iter().chain(os.v.concat()).chain(os.a.concat()).collect();
        let out = tape.segment(&roots, None)?;
        let regs = |v: &Vec<Vec<kinloop_codegen::graph::dag::NodeId>>| v.concat().iter().map(|n| n.0).collect();
        Ok(Some(SensProg {
            np,
            ni,
            stages,
            out,
            out_q: regs(&os.q),
            out_v: regs(&os.v),
            out_a: regs(&os.a),
            pair_of: (0..ni * ni).map(|ij| kinloop_codegen::plan::pair_index(ni, ij / ni, ij % ni)).collect(),
        }))
    }

    /// The sensitivities of the state in the registers, with the blocks' factorisations.
    pub(crate) fn run(&self, r: &mut [f64], facs: &[Fac], s: &mut Sensitivities) {
        let (ni, np) = (self.ni, self.np);
        let npairs = ni * (ni + 1) / 2;
        for (stage, progs) in self.stages.iter().enumerate() {
            for (b, p) in progs.iter().enumerate() {
                p.seg.run(r);
                let n = p.unknowns.len();
                let mut z = [0.0; crate::sparse::MAX_BLOCK];
                for c in 0..p.width {
                    for (row, zr) in z.iter_mut().enumerate().take(n) {
                        *zr = r[p.rows[row * p.width + c] as usize];
                    }
                    facs[b].solve(&mut z[..n]);
                    let (slot, k) = (c / np, c % np);
                    for (m, &u) in p.unknowns.iter().enumerate() {
                        if let Some(reg) = p.leaves[m * p.width + c] {
                            r[reg as usize] = z[m];
                        }
                        match stage {
                            0 => s.q[u * np + k] = z[m],
                            1 => s.dq[(u * ni + slot) * np + k] = z[m],
                            _ => {
                                for (ij, &pp) in self.pair_of.iter().enumerate() {
                                    if pp == slot {
                                        s.d2q[(u * ni * ni + ij) * np + k] = z[m];
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        self.out.run(r);
        for (o, &reg) in s.out.iter_mut().zip(&self.out_q) {
            *o = r[reg as usize];
        }
        for (o, &reg) in s.dout.iter_mut().zip(&self.out_v) {
            *o = r[reg as usize];
        }
        let no = self.out_q.len() / np.max(1);
        for o in 0..no {
            for (ij, &p) in self.pair_of.iter().enumerate() {
                for k in 0..np {
                    s.d2out[(o * ni * ni + ij) * np + k] = r[self.out_a[(o * npairs + p) * np + k] as usize];
                }
            }
        }
    }

    /// A zeroed result of the right sizes for `n` unknowns and `no` output columns.
    pub(crate) fn empty(&self, n: usize, no: usize) -> Sensitivities {
        let (ni, np) = (self.ni, self.np);
        Sensitivities {
            q: vec![0.0; n * np],
            dq: vec![0.0; n * ni * np],
            d2q: vec![0.0; n * ni * ni * np],
            out: vec![0.0; no * np],
            dout: vec![0.0; no * ni * np],
            d2out: vec![0.0; no * ni * ni * np],
        }
    }
}
