//! Symbolic differentiation (forward mode) and substitution over the graph. Both rebuild nodes
//! through the simplifying constructors, in topological order: no recursion, so deep
//! expressions cannot overflow the stack.

use super::dag::{Func, Graph, Leaf, NodeId, Op};
use std::collections::HashMap;

impl Graph {
    /// Forward-mode differentiation: the tangent of `root` when every leaf `l` moves with
    /// tangent `seed(l)` (`None` = does not move). Used with different seeds for partial
    /// derivatives (one unknown seeded with 1), for total derivatives along an input (unknowns
    /// seeded with their analog leaves `Tan`), and for second derivatives (applied twice).
    pub fn tangent(&mut self, roots: &[NodeId], seed: &dyn Fn(Leaf) -> Option<NodeId>) -> Vec<NodeId> {
        let order = self.reachable(roots);
        let mut memo: HashMap<NodeId, NodeId> = HashMap::with_capacity(order.len());
        for n in order {
            let d = self.tangent_of(n, &memo, seed);
            memo.insert(n, d);
        }
        roots.iter().map(|r| memo[r]).collect()
    }

    fn tangent_of(
        &mut self,
        n: NodeId,
        memo: &HashMap<NodeId, NodeId>,
        seed: &dyn Fn(Leaf) -> Option<NodeId>,
    ) -> NodeId {
        let d = |x: NodeId| memo[&x];
        match self.op(n) {
            Op::Const(_) => self.zero(),
            Op::Leaf(l) => match seed(l) {
                Some(t) => t,
                None => self.zero(),
            },
            Op::Add(a, b) => self.add(d(a), d(b)),
            Op::Sub(a, b) => self.sub(d(a), d(b)),
            Op::Neg(a) => self.neg(d(a)),
            Op::Mul(a, b) => {
                let (da, db) = (d(a), d(b));
                let t1 = self.mul(da, b);
                let t2 = self.mul(a, db);
                self.add(t1, t2)
            }
            Op::Div(a, b) => {
                // d(a/b) = (da - (a/b) db) / b: reuses the quotient node itself.
                let (da, db) = (d(a), d(b));
                let q_db = self.mul(n, db);
                let num = self.sub(da, q_db);
                self.div(num, b)
            }
            Op::Powi(a, k) => {
                let da = d(a);
                let c = self.constant(k as f64);
                let p = self.powi(a, k.saturating_sub(1));
                let cp = self.mul(c, p);
                self.mul(cp, da)
            }
            Op::Powf(a, b) => {
                // d(a^b) = a^b (db ln a + b da / a)
                let (da, db) = (d(a), d(b));
                let ln_a = self.func(Func::Ln, a);
                let t1 = self.mul(db, ln_a);
                let b_da = self.mul(b, da);
                let t2 = self.div(b_da, a);
                let s = self.add(t1, t2);
                self.mul(n, s)
            }
            Op::Atan2(y, x) => {
                // d atan2(y, x) = (x dy - y dx) / (x^2 + y^2)
                let (dy, dx) = (d(y), d(x));
                let t1 = self.mul(x, dy);
                let t2 = self.mul(y, dx);
                let num = self.sub(t1, t2);
                let x2 = self.powi(x, 2);
                let y2 = self.powi(y, 2);
                let den = self.add(x2, y2);
                self.div(num, den)
            }
            // The derivative of the chosen argument, chosen by the same comparison (at a tie,
            // the first's, as the value): no weights, so the unused argument's derivative never
            // enters the result, and differentiating again selects again.
            Op::Select(a, b, x, y) => self.select(a, b, d(x), d(y)),
            Op::Func(f, a) => {
                let da = d(a);
                if self.is_zero(da) {
                    return da;
                }
                let factor = self.func_derivative(f, a, n);
                self.mul(factor, da)
            }
        }
    }

    /// The derivative of `f` at `a`, where `n` is the node `f(a)` itself (reused by `tan`,
    /// `sqrt` and `exp`).
    fn func_derivative(&mut self, f: Func, a: NodeId, n: NodeId) -> NodeId {
        match f {
            Func::Sin => self.func(Func::Cos, a),
            Func::Cos => {
                let s = self.func(Func::Sin, a);
                self.neg(s)
            }
            Func::Tan => {
                let t2 = self.powi(n, 2);
                let one = self.one();
                self.add(one, t2)
            }
            Func::Asin | Func::Acos => {
                let one = self.one();
                let a2 = self.powi(a, 2);
                let r = self.sub(one, a2);
                let s = self.func(Func::Sqrt, r);
                let inv = self.div(one, s);
                if f == Func::Acos { self.neg(inv) } else { inv }
            }
            Func::Atan => {
                let one = self.one();
                let a2 = self.powi(a, 2);
                let r = self.add(one, a2);
                self.div(one, r)
            }
            Func::Sqrt => {
                let two = self.constant(2.0);
                let den = self.mul(two, n);
                let one = self.one();
                self.div(one, den)
            }
            Func::Exp => n,
            Func::Ln => {
                let one = self.one();
                self.div(one, a)
            }
            Func::Abs => self.func(Func::Signum, a),
            Func::Signum | Func::Floor => self.zero(),
        }
    }

    /// Replaces leaves by other nodes (e.g. block unknowns by zero for a linear block's
    /// constant term), rebuilding every node on the way so simplification applies again.
    pub fn substitute(&mut self, roots: &[NodeId], map: &dyn Fn(Leaf) -> Option<NodeId>) -> Vec<NodeId> {
        let order = self.reachable(roots);
        let mut memo: HashMap<NodeId, NodeId> = HashMap::with_capacity(order.len());
        for n in order {
            let m = |x: NodeId| memo[&x];
            let new = match self.op(n) {
                Op::Const(_) => n,
                Op::Leaf(l) => map(l).unwrap_or(n),
                Op::Add(a, b) => self.add(m(a), m(b)),
                Op::Sub(a, b) => self.sub(m(a), m(b)),
                Op::Mul(a, b) => self.mul(m(a), m(b)),
                Op::Div(a, b) => self.div(m(a), m(b)),
                Op::Neg(a) => self.neg(m(a)),
                Op::Powi(a, k) => self.powi(m(a), k),
                Op::Powf(a, b) => self.powf(m(a), m(b)),
                Op::Func(f, a) => self.func(f, m(a)),
                Op::Atan2(a, b) => self.atan2(m(a), m(b)),
                Op::Select(a, b, x, y) => self.select(m(a), m(b), m(x), m(y)),
            };
            memo.insert(n, new);
        }
        roots.iter().map(|r| memo[r]).collect()
    }
}
