//! The step's finiteness test, as the compiled fused kernel makes it: one sum of the state's
//! values whose finiteness the others' does not imply (the plan's `finite` analysis, on the
//! terms the emitter takes), and the state examined value by value only when that sum is
//! not finite (a sum of finite values can overflow).

use crate::gather::Gather;
use kinloop_codegen::plan::Plan;
use kinloop_codegen::plan::finite::{READ_BUDGET, Term, Value, kept, state_terms};

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

impl Finite {
    /// The values of `plan`'s state that its fused kernel's sum keeps (`plan::finite`'s
    /// `state_terms`, kept by the same rule within the reader's budget).
    pub(crate) fn build(plan: &Plan) -> Finite {
        let ni = plan.ni;
        let terms = state_terms(plan);
        let keep = kept(plan, &terms, READ_BUDGET);
        let (mut regs, mut f) = (Vec::new(), Finite::default());
        for ((t, v), _) in terms.into_iter().zip(keep).filter(|(_, k)| *k) {
            match (t, v) {
                // A node's register holds its value, wherever it is in the state.
                (Some(Term::Node(n)), _) | (_, Value::Node(n)) => regs.push(n.0),
                (_, Value::Q(u)) => f.q.push(u as u32),
                (_, Value::Dq(u, i)) => f.dq.push((u * ni + i) as u32),
                (_, Value::D2q(u, i, j)) => f.d2q.push(((u * ni + i) * ni + j) as u32),
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
