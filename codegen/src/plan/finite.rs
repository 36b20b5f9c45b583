//! Which of a kernel's values its finiteness test must add up.
//!
//! A kernel accepts its state when the sum of the state's values is finite (NaN and infinity
//! propagate through a sum). Most of those values are also operands of others: a second analog
//! `d2q_x_c = (r_p cos phi - l_p (dq² cos q + sin q d2q)) / -1` is not finite when `cos q`,
//! `dq` or `d2q` of the rod is not, so once it is in the sum they need not be. This pass keeps
//! a value out of the sum when the finiteness of the values kept implies its own, by rules that
//! hold for every IEEE operation as the generated code evaluates it:
//!
//! * an operand of `+`, `-`, `*`, of a negation, of `sqrt`, `abs`, `sin`, `cos` or of a
//!   positive integer power, and the numerator of a division, is finite when the result is
//!   (infinity and NaN give infinity or NaN; the converse, overflow, is not used);
//! * the solution of a non-singular linear system (an analog, a linear block's unknowns) is
//!   finite only when every right-hand side row is: some unknown carries a non-finite row
//!   (the kernel rejects a singular or non-finite matrix through its pivot ratio);
//! * a closed-form angle is finite when its cosine and sine are (it is their `atan2`, or an
//!   anchor's angle advanced by a rotation of them, on the turn of a finite guess), and a
//!   closed-form block's check sum (its sines and cosines) when all of them are.
//!
//! Not used: a sine or cosine that a sweep's cache computes (it rotates cached values, whatever
//! its argument), an unknown that Newton solved, and every other function (`atan2(∞, ∞)` is
//! finite).

use super::block_plan::BlockPlan;
use super::closed_form::Recognised;
use super::finished::Plan;
use super::input_pairs::pairs;
use super::solve::Solve;
use crate::graph::dag::{Func, Leaf, NodeId, Op};
use std::collections::HashSet;

/// One value of a kernel's finiteness test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Term {
    /// A graph node (an unknown, an analog, an output or one of its derivatives).
    Node(NodeId),
    /// The check sum of closed-form block `b` (its sines and cosines; a length's or a slider's
    /// guess too, which no rule covers).
    Check(usize),
}

/// A value of a kernel's state, by its place in the state: what the finiteness test adds up,
/// named once for the compiled kernel (which maps it to a local) and the run-time model (which
/// maps it to a register or a place in its state).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Value {
    /// Unknown `u`.
    Q(usize),
    /// `Dq(u, i)`: the analog of unknown `u` with respect to input `i`.
    Dq(usize, usize),
    /// `D2q(u, i, j)`: the second analog of unknown `u` with respect to inputs `i` and `j` (both
    /// orders are in the state: one node).
    D2q(usize, usize, usize),
    /// A graph node: an output or one of its analogs.
    Node(NodeId),
}

/// The values of a fused kernel's state in the order its finiteness test takes them (the
/// unknowns, per unknown its analogs and second analogs, then per output its value and
/// analogs: the values others are computed from first), each with its term (`None`: a leaf the
/// graph does not hold, an unknown or analog nothing reads).
pub fn state_terms(plan: &Plan) -> Vec<(Option<Term>, Value)> {
    let (g, ni) = (&plan.graph, plan.ni);
    let leaf = |l: Leaf| g.find(Op::Leaf(l)).map(Term::Node);
    let mut terms = Vec::new();
    for u in 0..plan.n {
        terms.push((leaf(Leaf::Unknown(u as u16)), Value::Q(u)));
    }
    for u in 0..plan.n {
        for i in 0..ni {
            terms.push((leaf(Leaf::Tan { unknown: u as u16, input: i as u16 }), Value::Dq(u, i)));
            for j in 0..ni {
                let (a, b) = (i.min(j) as u16, i.max(j) as u16);
                terms.push((leaf(Leaf::Tan2 { unknown: u as u16, i: a, j: b }), Value::D2q(u, i, j)));
            }
        }
    }
    for (o, &node) in plan.outputs.iter().enumerate() {
        for n in std::iter::once(node).chain(plan.out_d1[o].iter().copied()).chain(plan.out_d2[o].iter().copied()) {
            terms.push((Some(Term::Node(n)), Value::Node(n)));
        }
    }
    terms
}

/// Largest `terms × nodes` the analysis visits in the macro; beyond it every term is summed (a
/// block of hundreds of coupled loops, where the sum's additions do not matter).
pub const BUDGET: usize = 50_000_000;

/// Largest `terms × nodes` the analysis visits when a model is read at run time: the analysis
/// visits the graph once per term, and on the ring of 64 coupled loops (128 unknowns) it took
/// two thirds as many instructions again as the rest of the reading and one step (callgrind:
/// 366M against 219M). Beyond it the model sums what the compiled kernel sums beyond
/// [`BUDGET`] (on the ring 384 values instead of 256: 128 additions in a step of ~460k
/// instructions). Either sum accepts exactly the finite states (see the module's rules), so
/// the smaller budget changes the step's cost, never its verdict.
pub const READ_BUDGET: usize = 200_000;

/// [`summed_within`] the macro's [`BUDGET`].
pub fn summed(plan: &Plan, terms: &[Term]) -> Vec<bool> {
    summed_within(plan, terms, BUDGET)
}

/// Per term, whether the sum must include it: the terms left out are finite whenever the terms
/// kept are. A term given twice is kept at most once, a finite constant never. Terms are left
/// out greedily in the order given (put the values that others are computed from first). When
/// `terms × nodes` exceeds `budget`, nothing else is left out.
pub fn summed_within(plan: &Plan, terms: &[Term], budget: usize) -> Vec<bool> {
    let mut seen = HashSet::new();
    let mut keep: Vec<bool> = terms.iter().map(|t| !is_finite_constant(plan, t) && seen.insert(*t)).collect();
    if terms.len().saturating_mul(plan.graph.len()) > budget {
        return keep;
    }
    let rules = Rules::new(plan);
    for t in 0..terms.len() {
        if !keep[t] {
            continue;
        }
        keep[t] = false;
        let kept = terms.iter().zip(&keep).filter(|(_, k)| **k).map(|(term, _)| rules.id(*term));
        let hit = rules.closure(kept);
        keep[t] = !hit[rules.id(terms[t])];
    }
    keep
}

/// Per value of `terms` (each with its term, `None` for a value no graph node holds), whether
/// the sum includes it: a value with no node always (nothing implies it, and no other value is
/// it), the others as [`summed_within`] `budget` keeps their terms.
pub fn kept<V>(plan: &Plan, terms: &[(Option<Term>, V)], budget: usize) -> Vec<bool> {
    let ids: Vec<Term> = terms.iter().filter_map(|(t, _)| *t).collect();
    let mut summed = summed_within(plan, &ids, budget).into_iter();
    terms.iter().map(|(t, _)| t.is_none() || summed.next() == Some(true)).collect()
}

fn is_finite_constant(plan: &Plan, t: &Term) -> bool {
    matches!(t, Term::Node(n) if plan.graph.as_const(*n).is_some_and(f64::is_finite))
}

/// The implications among a plan's values: a node implies its operands' finiteness (see
/// [`operands`]); a group's members together imply its target's.
struct Rules<'a> {
    plan: &'a Plan,
    /// Per node: the operands whose finiteness its own implies (see [`operands`]).
    implies: Vec<Vec<usize>>,
    /// `(target, members)`: the target is finite when every member is.
    groups: Vec<(usize, Vec<usize>)>,
    /// Per value: the groups it is a member of.
    member_of: Vec<Vec<usize>>,
}

impl<'a> Rules<'a> {
    fn new(plan: &'a Plan) -> Self {
        let g = &plan.graph;
        let leaf = |l: Leaf| g.find(Op::Leaf(l));
        let mut rules = Rules {
            plan,
            implies: Vec::new(),
            groups: Vec::new(),
            member_of: vec![Vec::new(); g.len() + plan.blocks.len()],
        };
        // Sines and cosines a closed-form solve defines (not computed from the angle), and
        // unknowns Newton solved: see `operands`.
        let (mut closed_trig, mut newton) = (HashSet::new(), HashSet::new());
        for (b, bp) in plan.blocks.iter().enumerate() {
            let leaves = |make: &dyn Fn(u16) -> Leaf| -> Option<Vec<usize>> {
                bp.unknowns.iter().map(|&u| leaf(make(u as u16)).map(|n| n.index())).collect()
            };
            match &bp.solve {
                Solve::Fixed { .. } | Solve::Linear { .. } => {
                    if let (Some(rhs), Some(qs)) = (bp.solve.linear_rhs(), leaves(&Leaf::Unknown)) {
                        rules.rows(rhs, &qs);
                    }
                }
                Solve::Newton | Solve::NewtonSparse(_) => {
                    newton.extend(bp.unknowns.iter().filter_map(|&u| leaf(Leaf::Unknown(u as u16))));
                }
                // Its rules follow its analogs' (see `Rules::closed`).
                Solve::ClosedForm(_) => {}
            }
            for i in 0..plan.ni {
                if let Some(tans) = leaves(&|u| Leaf::Tan { unknown: u, input: i as u16 }) {
                    rules.rows(&column(&bp.vel, i), &tans);
                }
            }
            for (p, &(i, j)) in pairs(plan.ni).iter().enumerate() {
                if let Some(tans) = leaves(&|u| Leaf::Tan2 { unknown: u, i: i as u16, j: j as u16 }) {
                    rules.rows(&column(&bp.acc, p), &tans);
                }
            }
            if let Solve::ClosedForm(rec) = &bp.solve {
                closed_trig.extend(rec.sin_cos.iter().flatten().copied());
                rules.closed(b, bp, rec, &leaf);
            }
        }
        rules.implies = (0..g.len()).map(|w| operands(plan, NodeId(w as u32), &closed_trig, &newton)).collect();
        rules
    }

    /// The rules of closed-form block `b` solved by `rec`: each angle from its cosine and sine,
    /// the check sum from all of them when it sums nothing else.
    fn closed(&mut self, b: usize, bp: &BlockPlan, rec: &Recognised, leaf: &dyn Fn(Leaf) -> Option<NodeId>) {
        for (u, pair) in rec.form.angles().into_iter().zip(&rec.sin_cos) {
            if let Some(q) = leaf(Leaf::Unknown(u as u16)) {
                self.group(q.index(), pair.iter().map(|n| n.index()).collect());
            }
        }
        if rec.form.angles().len() == bp.unknowns.len() {
            let all = rec.sin_cos.iter().flatten().map(|n| n.index()).collect();
            self.group(self.plan.graph.len() + b, all);
        }
    }

    /// A linear solve: each right-hand side row is finite when every solution is.
    fn rows(&mut self, rhs: &[NodeId], solution: &[usize]) {
        for r in rhs {
            self.group(r.index(), solution.to_vec());
        }
    }

    fn group(&mut self, target: usize, members: Vec<usize>) {
        for &m in &members {
            self.member_of[m].push(self.groups.len());
        }
        self.groups.push((target, members));
    }

    /// The index of a term among the values.
    fn id(&self, t: Term) -> usize {
        match t {
            Term::Node(n) => n.index(),
            Term::Check(b) => self.plan.graph.len() + b,
        }
    }

    /// The values whose finiteness follows from that of `kept`'s (`kept` included).
    fn closure(&self, kept: impl Iterator<Item = usize>) -> Vec<bool> {
        let mut hit = vec![false; self.member_of.len()];
        let mut missing: Vec<usize> = self.groups.iter().map(|(_, m)| m.len()).collect();
        let mut stack: Vec<usize> = kept.collect();
        while let Some(v) = stack.pop() {
            if std::mem::replace(&mut hit[v], true) {
                continue;
            }
            if let Some(ops) = self.implies.get(v) {
                stack.extend(ops.iter().filter(|&&a| !hit[a]));
            }
            for &k in &self.member_of[v] {
                missing[k] -= 1;
                if missing[k] == 0 && !hit[self.groups[k].0] {
                    stack.push(self.groups[k].0);
                }
            }
        }
        hit
    }
}

/// The operands of node `w` whose finiteness its own implies. Not those of a sine or cosine a
/// closed-form solve defines (`closed_trig`: not computed from the angle) or a sweep's cache
/// rotates (of an argument free of unknowns: the cache's values are finite whatever it is), and
/// never an unknown Newton solved (`newton`).
fn operands(plan: &Plan, w: NodeId, closed_trig: &HashSet<NodeId>, newton: &HashSet<NodeId>) -> Vec<usize> {
    let ops = match plan.graph.op(w) {
        Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) => vec![a, b],
        Op::Div(a, _) | Op::Neg(a) => vec![a],
        Op::Powi(a, k) if k >= 1 => vec![a],
        // `f64::floor` of NaN or an infinity is itself: a finite floor has a finite argument.
        Op::Func(Func::Sqrt | Func::Abs | Func::Floor, a) => vec![a],
        Op::Func(Func::Sin | Func::Cos, a) if !closed_trig.contains(&w) && plan.level[a.index()] >= 0 => vec![a],
        // A finite `min`/`max` implies nothing: the argument it did not choose may be infinite
        // (`min(inf, 1)`), and the compared ones only are not NaN.
        Op::Select(..) => Vec::new(),
        _ => Vec::new(),
    };
    ops.into_iter().filter(|a| !newton.contains(a)).map(|a| a.index()).collect()
}

/// Column `k` of rows `m`.
fn column(m: &[Vec<NodeId>], k: usize) -> Vec<NodeId> {
    m.iter().filter_map(|row| row.get(k).copied()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names of the terms a fused kernel's sum keeps for a one-input declaration: its
    /// state's terms ([`state_terms`]) then, as in a deferred kernel, the closed-form blocks'
    /// checks.
    fn kept(src: &str) -> Vec<String> {
        let a = crate::analyze(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}"));
        let mut model = a.model;
        let plan = crate::plan::build(&mut model, &a.blocks, false);
        let output = |n: NodeId| {
            let slots = [("out", &plan.outputs), ("dout", &plan.out_d1.concat()), ("d2out", &plan.out_d2.concat())];
            let mut named =
                slots.iter().flat_map(|(what, nodes)| nodes.iter().position(|&m| m == n).map(|o| format!("{what}{o}")));
            named.next().expect("an output's node")
        };
        let name = |v: Value| match v {
            Value::Q(u) => model.unknowns[u].name.to_string(),
            Value::Dq(u, _) => format!("d{}", model.unknowns[u].name),
            Value::D2q(u, ..) => format!("d2{}", model.unknowns[u].name),
            Value::Node(n) => output(n),
        };
        let mut terms: Vec<(Option<Term>, String)> =
            state_terms(&plan).into_iter().map(|(t, v)| (t, name(v))).collect();
        for b in (0..plan.blocks.len()).filter(|&b| plan.blocks[b].solve.closed_form().is_some()) {
            terms.push((Some(Term::Check(b)), format!("check{b}")));
        }
        let summed = super::kept(&plan, &terms, BUDGET);
        terms.into_iter().zip(summed).filter(|(_, s)| *s).map(|((_, name), _)| name).collect()
    }

    const SLIDER_CRANK: &str = "pub struct S { params r = 1, l = 3, e = 0.5; input phi; unknowns psi = 0, x = 3;
        loop oab: r @ phi == (x, e) + l @ psi; }";

    /// The offset slider-crank: the slider's second analog is computed from the rod's angle,
    /// sine, cosine and analogs, so the slider's values imply the rod's and its block's check.
    #[test]
    fn a_slider_implies_its_rod() {
        assert_eq!(kept(SLIDER_CRANK), ["x", "dx", "d2x"]);
    }

    /// With Newton for the rod, nothing implies its angle: it stays (its sine and cosine are
    /// computed from it, but a Newton iterate is not the value the kernel returns).
    #[test]
    fn a_newton_unknown_is_summed() {
        let src = format!("#[kinloop(newton)] {SLIDER_CRANK}");
        assert_eq!(kept(&src), ["psi", "x", "dx", "d2x"]);
    }

    /// `atan2` (finite for infinite arguments) implies nothing of its arguments; a product
    /// implies both factors.
    #[test]
    fn only_operations_that_propagate_non_finite_values_imply() {
        let src = SLIDER_CRANK.replace("}", "output o = atan2(x, 1); }");
        let a = crate::analyze(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}"));
        let mut model = a.model;
        let plan = crate::plan::build(&mut model, &a.blocks, false);
        let rules = Rules::new(&plan);
        let ops = (0..plan.graph.len()).map(|k| (k, plan.graph.op(NodeId(k as u32))));
        let (mut atan2, mut products) = (0, 0);
        for (k, op) in ops {
            match op {
                Op::Atan2(..) => {
                    atan2 += 1;
                    assert!(rules.implies[k].is_empty());
                }
                Op::Mul(a, b) => {
                    products += 1;
                    assert_eq!(rules.implies[k], [a.index(), b.index()]);
                }
                _ => {}
            }
        }
        assert!(atan2 == 1 && products > 0);
        // Through the output's analogs (a product with the slider), the slider is implied.
        assert_eq!(kept(&SLIDER_CRANK.replace("}", "output o = 3 * x; }")), ["out0", "dout0", "d2out0"]);
    }

    /// A closed-form block with a slider or a length keeps its check: it sums the guess of that
    /// unknown, which no value of the kernel reads.
    #[test]
    fn a_check_with_a_guess_is_summed() {
        let src = "pub struct G { params a = 1, d = 2; input phi; unknowns s = 2, psi = 0.3;
            loop l: a @ phi == (d, 0) + s @ psi; }";
        let kept = kept(src);
        assert!(kept.contains(&"check0".to_string()), "{kept:?}");
    }

    /// Terms that imply each other are never all left out: one of them carries the others.
    #[test]
    fn one_of_mutually_implied_terms_stays() {
        let src = "pub struct S { params r = 1, l = 3, e = 0.5; input phi; unknowns psi = 0, x = 3;
            loop oab: r @ phi == (x, e) + l @ psi; output twice = 2 * x; output again = x * 2; }";
        assert_eq!(kept(src), ["out0", "dout0", "d2out0"]);
    }
}
