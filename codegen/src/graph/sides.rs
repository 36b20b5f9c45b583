//! An equation's residual from its two sides, with the terms common to both cancelled.
//!
//! `lhs - rhs` is built by [`Graph::sub`], which cancels only a whole side (`x - x = 0`). A term
//! that stands in both sums (`beta * 0 + x == x + k`, a frame vector written on both sides of a
//! loop) stayed in the residual: the unknown then counted as part of the equation, although its
//! terms cancel, and the equation was solved for it — singular at every input. Cancelled here,
//! the equation is what it says (`-k`), and the structural analysis reports an unknown that
//! nothing determines. Only equations are rewritten this way: where nothing cancels the residual
//! is `lhs - rhs` node for node, so the code emitted for every other equation keeps its bits.

use super::dag::{Graph, NodeId, Op};

/// The most terms a side is split into; a larger sum is left whole (its residual `lhs - rhs`).
const MAX_TERMS: usize = 64;

impl Graph {
    /// `lhs - rhs` with the additive terms common to both sides removed (as a multiset of nodes:
    /// `x + x == x` keeps one `x`). Where none is common, exactly [`Graph::sub`]`(lhs, rhs)`.
    pub fn sides_difference(&mut self, lhs: NodeId, rhs: NodeId) -> NodeId {
        let mut terms = Vec::new();
        if !self.terms_into(lhs, true, &mut terms) || !self.terms_into(rhs, false, &mut terms) {
            return self.sub(lhs, rhs);
        }
        let mut cancelled = false;
        for i in 0..terms.len() {
            let Some((node, sign)) = terms[i] else { continue };
            let partner = (i + 1..terms.len()).find(|&k| terms[k] == Some((node, !sign)));
            if let Some(k) = partner {
                (terms[i], terms[k], cancelled) = (None, None, true);
            }
        }
        if !cancelled {
            return self.sub(lhs, rhs);
        }
        // What remains, in the order the sides were written: the positive terms summed, then
        // the negative ones subtracted.
        let (mut plus, mut minus) = (self.zero(), self.zero());
        for (node, positive) in terms.into_iter().flatten() {
            if positive {
                plus = self.add(plus, node);
            } else {
                minus = self.add(minus, node);
            }
        }
        self.sub(plus, minus)
    }

    /// Pushes the additive terms of `n` with their signs (`true`: added), through sums,
    /// differences and negations; `false` where there would be more than [`MAX_TERMS`].
    fn terms_into(&self, n: NodeId, positive: bool, out: &mut Vec<Option<(NodeId, bool)>>) -> bool {
        // An explicit stack: a long chain of sums must not recurse deeply.
        let mut stack = vec![(n, positive)];
        while let Some((n, positive)) = stack.pop() {
            match self.op(n) {
                // Pushed right first, so that terms come out left to right.
                Op::Add(a, b) => stack.extend([(b, positive), (a, positive)]),
                Op::Sub(a, b) => stack.extend([(b, !positive), (a, positive)]),
                Op::Neg(a) => stack.push((a, !positive)),
                _ if self.is_zero(n) => {}
                _ => {
                    if out.len() == MAX_TERMS {
                        return false;
                    }
                    out.push(Some((n, positive)));
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::dag::Leaf;

    fn leaves(g: &mut Graph) -> [NodeId; 3] {
        [g.leaf(Leaf::Unknown(0)), g.leaf(Leaf::Param(0)), g.leaf(Leaf::Param(1))]
    }

    #[test]
    fn a_term_on_both_sides_cancels() {
        let mut g = Graph::new();
        let [x, k, m] = leaves(&mut g);
        // x == x + k: -k.
        let xk = g.add(x, k);
        let f = g.sides_difference(x, xk);
        assert_eq!(f, g.neg(k));
        // k + x == x + m (a frame term on both sides of a loop): k - m.
        let kx = g.add(k, x);
        let xm = g.add(x, m);
        let f = g.sides_difference(kx, xm);
        assert_eq!(f, g.sub(k, m));
        // x - k == -k + x: zero.
        let x_k = g.sub(x, k);
        let nk = g.neg(k);
        let nkx = g.add(nk, x);
        assert!(g.is_zero(g.clone().sides_difference(x_k, nkx)));
    }

    #[test]
    fn terms_cancel_as_a_multiset() {
        let mut g = Graph::new();
        let [x, k, _] = leaves(&mut g);
        // x + (x + k) == x: x + k remains (one `x` cancels, not both).
        let xk = g.add(x, k);
        let lhs = g.add(x, xk);
        let f = g.sides_difference(lhs, x);
        let got = g.eval(&[f], &|l| if l == Leaf::Unknown(0) { 2.0 } else { 3.0 })[0];
        assert_eq!(got, 5.0);
        assert!(g.leaves_of(&[f]).contains(&Leaf::Unknown(0)));
    }

    #[test]
    fn nothing_common_is_the_plain_difference() {
        let mut g = Graph::new();
        let [x, k, m] = leaves(&mut g);
        let s = g.func(crate::graph::dag::Func::Sin, x);
        let lhs = g.mul(k, s);
        let rhs = g.add(m, x);
        let f = g.sides_difference(lhs, rhs);
        assert_eq!(f, g.sub(lhs, rhs));
        // A term inside a product is no term of the sum: `2 x == x` keeps both.
        let two = g.constant(2.0);
        let twice = g.mul(two, x);
        let f = g.sides_difference(twice, x);
        assert_eq!(f, g.sub(twice, x));
    }
}
