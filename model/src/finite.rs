//! The step's finiteness test, as the compiled fused kernel makes it: one sum of the state's
//! values whose finiteness the others' does not imply (the plan's `finite` analysis, with the
//! terms in the emitter's order), and the state examined value by value only when that sum is
//! not finite (a sum of finite values can overflow).

use crate::gather::Gather;
use kinloop_codegen::graph::dag::{Leaf, Op};
use kinloop_codegen::plan::Plan;
use kinloop_codegen::plan::finite::{Term, summed};

/// Largest `terms × nodes` analysed when a model is read (the analysis visits the graph once per
/// term); beyond it every value is summed. The ring of 64 coupled loops is beyond it: there the
/// analysis took two thirds as many instructions again as the rest of the reading (callgrind).
const READ_BUDGET: usize = 200_000;

/// What a step's finiteness test adds up: registers of graph nodes (the nodes are written once
/// a step, so their registers hold the state's values), and the places in the state of the
/// values no node holds (an unknown or analog nothing reads is written to the scratch register).
#[derive(Clone, Debug, Default)]
pub(crate) struct Finite {
    regs: Gather,
    q: Vec<u32>,
    dq: Vec<u32>,
    d2q: Vec<u32>,
}

/// Where a term's value is: a node's register, or a place in `q`, `dq` or `d2q`.
enum At {
    Reg(u32),
    Q(u32),
    Dq(u32),
    D2q(u32),
}

impl Finite {
    /// The terms of `plan`'s fused kernel (`Kernel::finite_sum` in the emitter: the unknowns,
    /// per unknown its analogs, then per output its value and analogs) that its sum keeps.
    pub(crate) fn build(plan: &Plan) -> Finite {
        let (g, ni) = (&plan.graph, plan.ni);
        let leaf = |l: Leaf| g.find(Op::Leaf(l)).map(Term::Node);
        let mut terms: Vec<(Option<Term>, At)> = Vec::new();
        for u in 0..plan.n {
            terms.push((leaf(Leaf::Unknown(u as u16)), At::Q(u as u32)));
        }
        for u in 0..plan.n {
            for i in 0..ni {
                terms.push((leaf(Leaf::Tan { unknown: u as u16, input: i as u16 }), At::Dq((u * ni + i) as u32)));
                for j in 0..ni {
                    let (a, b) = (i.min(j) as u16, i.max(j) as u16);
                    let t = leaf(Leaf::Tan2 { unknown: u as u16, i: a, j: b });
                    terms.push((t, At::D2q(((u * ni + i) * ni + j) as u32)));
                }
            }
        }
        for (o, &node) in plan.outputs.iter().enumerate() {
            for n in std::iter::once(node).chain(plan.out_d1[o].iter().copied()).chain(plan.out_d2[o].iter().copied()) {
                terms.push((Some(Term::Node(n)), At::Reg(n.0)));
            }
        }
        let ids: Vec<Term> = terms.iter().filter_map(|(t, _)| *t).collect();
        let kept =
            if ids.len().saturating_mul(g.len()) <= READ_BUDGET { summed(plan, &ids) } else { vec![true; ids.len()] };
        let mut kept = kept.into_iter();
        let (mut regs, mut f) = (Vec::new(), Finite::default());
        for (t, at) in terms {
            // A term with no graph node is always summed (as in the emitter).
            let keep = match t {
                Some(_) => kept.next() == Some(true),
                None => true,
            };
            match (keep, t, at) {
                (false, _, _) => {}
                (true, Some(Term::Node(n)), _) => regs.push(n.0),
                (true, _, At::Q(k)) => f.q.push(k),
                (true, _, At::Dq(k)) => f.dq.push(k),
                (true, _, At::D2q(k)) => f.d2q.push(k),
                (true, _, At::Reg(k)) => regs.push(k),
            }
        }
        f.regs = Gather::new(regs);
        f
    }

    /// The sum of the kept values: finite exactly when every value of the state is, unless
    /// finite values overflow it (then [`all_finite`] decides).
    #[inline(always)]
    pub(crate) fn sum(&self, r: &[f64], q: &[f64], dq: &[f64], d2q: &[f64]) -> f64 {
        let mut s = self.regs.sum(r);
        for (v, idx) in [(q, &self.q), (dq, &self.dq), (d2q, &self.d2q)] {
            for &k in idx.iter() {
                s += v[k as usize];
            }
        }
        s
    }
}

/// Whether every value of `v` is finite: an exponent test on the bits, without a branch per
/// value (the loop vectorises).
pub(crate) fn all_finite(v: &[f64]) -> bool {
    const EXP: u64 = 0x7ff0_0000_0000_0000;
    !v.iter().fold(false, |bad, x| bad | (x.to_bits() & EXP == EXP))
}
