//! The expression graph: a hash-consed DAG of scalar operations.
//!
//! Every scalar quantity of a mechanism (residuals, outputs, their derivatives) is a node of one
//! graph. Nodes are created bottom-up and de-duplicated, so a node's operands always have smaller
//! ids than the node itself: ids are a topological order, which lets every traversal below be a
//! simple loop instead of a recursion (deep expressions cannot overflow the stack).
//!
//! Constructors simplify locally (constant folding, `x + 0`, `1 * x`, `x - x`, ...), which keeps
//! the derivative graphs small: differentiating `l * cos(phi)` with respect to an unrelated
//! unknown yields the constant zero, and zero terms vanish from the generated code.

use std::collections::HashMap;

/// Index of a node in a [`Graph`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct NodeId(pub u32);

impl NodeId {
    /// The position of the node in the graph's node list.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// The free variables of the graph.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub enum Leaf {
    /// A design parameter (constant during a sweep).
    Param(u16),
    /// A generalized coordinate (crank angle, time, ...).
    Input(u16),
    /// A position unknown (link angle, slider coordinate).
    Unknown(u16),
    /// First total derivative of an unknown with respect to an input: `dq_u / dx_i`.
    Tan { unknown: u16, input: u16 },
    /// Second total derivative `d2q_u / dx_i dx_j` with `i <= j`.
    Tan2 { unknown: u16, i: u16, j: u16 },
    /// Sensitivity of a position to a parameter: `dq_u / dp_k`.
    SensQ { unknown: u16, param: u16 },
    /// Sensitivity of a velocity analog: `d(dq_u/dx_i) / dp_k`.
    SensV { unknown: u16, input: u16, param: u16 },
    /// Sensitivity of an acceleration analog: `d(d2q_u/dx_i dx_j) / dp_k` with `i <= j`.
    SensA { unknown: u16, i: u16, j: u16, param: u16 },
}

impl Leaf {
    /// Leaves that are only known after the position and analog solves (analogs and
    /// sensitivities), as opposed to parameters, inputs and unknowns.
    pub fn is_derived(self) -> bool {
        !matches!(self, Leaf::Param(_) | Leaf::Input(_) | Leaf::Unknown(_))
    }
}

/// Elementary functions of one argument.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Func {
    /// `sin x`.
    Sin,
    /// `cos x`.
    Cos,
    /// `tan x`.
    Tan,
    /// `asin x`.
    Asin,
    /// `acos x`.
    Acos,
    /// `atan x`.
    Atan,
    /// `sqrt x`.
    Sqrt,
    /// `exp x`.
    Exp,
    /// Natural logarithm `ln x`.
    Ln,
    /// `|x|`.
    Abs,
    /// Sign of the argument (derivative of `abs`); its own derivative is zero.
    Signum,
    /// `floor x`, the largest integer not above `x` (`f64::floor`: NaN and the infinities are
    /// their own floor); its derivative is zero (at the jumps too, as for `signum`).
    Floor,
}

impl Func {
    /// The function's value at `x`, for constant folding and the macro's numeric checks.
    pub fn eval(self, x: f64) -> f64 {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Sqrt => x.sqrt(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Abs => x.abs(),
            Func::Signum => {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            }
            Func::Floor => x.floor(),
        }
    }

    /// Name of the `f64` method that computes this function.
    pub fn method(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sqrt => "sqrt",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Abs => "abs",
            Func::Signum => "signum",
            Func::Floor => "floor",
        }
    }
}

/// One node. Constants are stored by their bit pattern so nodes can be hashed.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Op {
    /// A constant, as the bits of its `f64`.
    Const(u64),
    /// A free variable: parameter, input, unknown, analog or sensitivity.
    Leaf(Leaf),
    /// `a + b`.
    Add(NodeId, NodeId),
    /// `a - b`.
    Sub(NodeId, NodeId),
    /// `a * b`.
    Mul(NodeId, NodeId),
    /// `a / b`.
    Div(NodeId, NodeId),
    /// `-a`.
    Neg(NodeId),
    /// `a` to an integer power (`powi`).
    Powi(NodeId, i32),
    /// `a` to a power `b` that is not a small integer constant (`powf`).
    Powf(NodeId, NodeId),
    /// An elementary function of one argument.
    Func(Func, NodeId),
    /// `atan2(y, x)`.
    Atan2(NodeId, NodeId),
    /// `Select(a, b, x, y)`: `x` when `a <= b`, `y` when `b < a`, NaN when `a` or `b` is NaN
    /// (see [`select`]). `min(a, b)` is `Select(a, b, a, b)` and `max(a, b)` is
    /// `Select(b, a, a, b)`; a tie picks the first argument. Its derivative picks the chosen
    /// argument's derivative, `Select(a, b, dx, dy)`: the other one is never multiplied in, so a
    /// non-finite derivative of the unused argument cannot leak into the result.
    Select(NodeId, NodeId, NodeId, NodeId),
}

/// The value of [`Op::Select`]: `x` when `a <= b`, `y` when `b < a`, and NaN when the two
/// cannot be compared (one of them is NaN), so that a NaN argument of `min`, `max` or `clamp`
/// is never hidden (unlike `f64::min`, which returns the other argument). The emitted code
/// writes exactly these comparisons, and the run-time model calls this function.
#[inline]
pub fn select(a: f64, b: f64, x: f64, y: f64) -> f64 {
    if a <= b {
        x
    } else if b < a {
        y
    } else {
        f64::NAN
    }
}

impl Op {
    /// The operands of this node (at most four, a [`Op::Select`]'s).
    pub fn operands(&self) -> impl Iterator<Item = NodeId> {
        let (v, n): ([NodeId; 4], usize) = match *self {
            Op::Const(_) | Op::Leaf(_) => ([NodeId(0); 4], 0),
            Op::Neg(a) | Op::Powi(a, _) | Op::Func(_, a) => ([a, a, a, a], 1),
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) | Op::Powf(a, b) | Op::Atan2(a, b) => {
                ([a, b, b, b], 2)
            }
            Op::Select(a, b, x, y) => ([a, b, x, y], 4),
        };
        v.into_iter().take(n)
    }
}

/// A hash-consed expression graph.
#[derive(Default, Clone)]
pub struct Graph {
    nodes: Vec<Op>,
    index: HashMap<Op, NodeId>,
}

/// The largest graph the macro builds; beyond it the declaration is rejected as too large
/// instead of exhausting the compiler's memory.
pub const MAX_NODES: usize = 2_000_000;

impl Graph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// The number of distinct nodes (the size the declaration's limits are measured in).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the graph has no node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The operation of node `n`.
    pub fn op(&self, n: NodeId) -> Op {
        self.nodes[n.index()]
    }

    /// Whether the graph reached [`MAX_NODES`]; the model then rejects the declaration as too
    /// large.
    pub fn overflowed(&self) -> bool {
        self.nodes.len() >= MAX_NODES
    }

    fn intern(&mut self, op: Op) -> NodeId {
        if let Some(&id) = self.index.get(&op) {
            return id;
        }
        let id = NodeId(self.nodes.len() as u32);
        self.nodes.push(op);
        self.index.insert(op, id);
        id
    }

    /// The node of `op`, if the graph has it (nothing is added).
    pub fn find(&self, op: Op) -> Option<NodeId> {
        self.index.get(&op).copied()
    }

    /// The value of a constant node.
    pub fn as_const(&self, n: NodeId) -> Option<f64> {
        match self.op(n) {
            Op::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    /// Whether `n` is the constant zero.
    pub fn is_zero(&self, n: NodeId) -> bool {
        self.as_const(n) == Some(0.0)
    }

    /// Whether `n` is the constant one.
    pub fn is_one(&self, n: NodeId) -> bool {
        self.as_const(n) == Some(1.0)
    }

    /// The node of a constant (`-0.0` and `0.0` are one node).
    pub fn constant(&mut self, v: f64) -> NodeId {
        // -0.0 and 0.0 are the same node.
        let v = if v == 0.0 { 0.0 } else { v };
        self.intern(Op::Const(v.to_bits()))
    }

    /// The constant zero.
    pub fn zero(&mut self) -> NodeId {
        self.constant(0.0)
    }

    /// The constant one.
    pub fn one(&mut self) -> NodeId {
        self.constant(1.0)
    }

    /// The node of a free variable.
    pub fn leaf(&mut self, leaf: Leaf) -> NodeId {
        self.intern(Op::Leaf(leaf))
    }

    /// Folds a constant result; non-finite results are left unfolded so that the generated code,
    /// not the compiler, reports them (at run time, with the equation's name).
    fn fold(&mut self, v: f64) -> Option<NodeId> {
        v.is_finite().then(|| self.constant(v))
    }

    /// `a + b`, simplified: constants folded, zero dropped, a negated operand turned into a
    /// subtraction, operands ordered so that `a + b` and `b + a` are one node.
    pub fn add(&mut self, a: NodeId, b: NodeId) -> NodeId {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => {
                if let Some(n) = self.fold(x + y) {
                    return n;
                }
            }
            (Some(0.0), None) => return b,
            (None, Some(0.0)) => return a,
            _ => {}
        }
        if let Op::Neg(nb) = self.op(b) {
            return self.sub(a, nb);
        }
        if let Op::Neg(na) = self.op(a) {
            return self.sub(b, na);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Op::Add(a, b))
    }

    /// `a - b`, simplified: `x - x = 0`, constants folded, zero dropped, `a - (-b) = a + b`.
    pub fn sub(&mut self, a: NodeId, b: NodeId) -> NodeId {
        if a == b {
            return self.zero();
        }
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => {
                if let Some(n) = self.fold(x - y) {
                    return n;
                }
            }
            (Some(0.0), None) => return self.neg(b),
            (None, Some(0.0)) => return a,
            _ => {}
        }
        if let Op::Neg(nb) = self.op(b) {
            return self.add(a, nb);
        }
        self.intern(Op::Sub(a, b))
    }

    /// `-a`, simplified: constants folded, `-(-x) = x`, `-(x - y) = y - x`, the sign moved into a
    /// constant factor.
    pub fn neg(&mut self, a: NodeId) -> NodeId {
        match self.op(a) {
            Op::Const(bits) => self.constant(-f64::from_bits(bits)),
            Op::Neg(x) => x,
            Op::Sub(x, y) => self.intern(Op::Sub(y, x)),
            Op::Mul(x, y) if self.as_const(x).is_some() => {
                let c = self.constant(-self.as_const(x).unwrap_or(0.0));
                self.mul(c, y)
            }
            _ => self.intern(Op::Neg(a)),
        }
    }

    /// `a * b`, simplified: constants folded and gathered in front, multiplications by 0, 1 and -1
    /// removed, negations lifted to the top, `x * x = x^2`, operands ordered.
    pub fn mul(&mut self, a: NodeId, b: NodeId) -> NodeId {
        // Constants go first so the rules below see them in one place.
        let (a, b) = if self.as_const(b).is_some() && self.as_const(a).is_none() { (b, a) } else { (a, b) };
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => {
                if let Some(n) = self.fold(x * y) {
                    return n;
                }
            }
            (Some(x), None) => {
                if x == 0.0 {
                    return self.zero();
                }
                if x == 1.0 {
                    return b;
                }
                if x == -1.0 {
                    return self.neg(b);
                }
                // c1 * (c2 * y) = (c1 c2) * y
                if let Op::Mul(c2, y) = self.op(b)
                    && let Some(c2v) = self.as_const(c2)
                    && let Some(c) = self.fold(x * c2v)
                {
                    return self.mul(c, y);
                }
                if let Op::Neg(y) = self.op(b) {
                    let c = self.constant(-x);
                    return self.mul(c, y);
                }
            }
            _ => {}
        }
        // (-x) * (-y) = x * y; (-x) * y = -(x * y): keeps negations at the top, where add/sub
        // absorb them.
        match (self.op(a), self.op(b)) {
            (Op::Neg(x), Op::Neg(y)) => return self.mul(x, y),
            (Op::Neg(x), _) => {
                let m = self.mul(x, b);
                return self.neg(m);
            }
            (_, Op::Neg(y)) => {
                let m = self.mul(a, y);
                return self.neg(m);
            }
            _ => {}
        }
        if a == b && self.as_const(a).is_none() {
            return self.powi(a, 2);
        }
        let (a, b) = if self.as_const(a).is_some() || a <= b { (a, b) } else { (b, a) };
        self.intern(Op::Mul(a, b))
    }

    /// `a / b`, simplified: `x / x = 1` (for `x` not a constant: a constant is folded, so that
    /// `0 / 0` stays NaN), constants folded, division by 1, -1 or a power of two turned into an
    /// exact multiplication, negations lifted.
    pub fn div(&mut self, a: NodeId, b: NodeId) -> NodeId {
        if a == b && self.as_const(a).is_none() {
            return self.one();
        }
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => {
                if let Some(n) = self.fold(x / y) {
                    return n;
                }
            }
            (Some(0.0), None) => return self.zero(),
            (None, Some(1.0)) => return a,
            (None, Some(-1.0)) => return self.neg(a),
            (None, Some(y)) if y != 0.0 && (1.0 / y).is_finite() && is_power_of_two(y) => {
                // Division by a power of two is an exact multiplication.
                let c = self.constant(1.0 / y);
                return self.mul(c, a);
            }
            _ => {}
        }
        if let Op::Neg(x) = self.op(a) {
            let d = self.div(x, b);
            return self.neg(d);
        }
        self.intern(Op::Div(a, b))
    }

    /// `a^n` for an integer `n`: `x^0 = 1`, `x^1 = x`, constants folded; huge exponents become
    /// `powf`.
    pub fn powi(&mut self, a: NodeId, n: i32) -> NodeId {
        // Huge integer exponents go through `powf`, so that differentiating them (n - 1, n - 2,
        // ...) can never overflow the exponent.
        if n.unsigned_abs() > 1 << 20 {
            let e = self.constant(n as f64);
            return self.intern(Op::Powf(a, e));
        }
        match n {
            0 => return self.one(),
            1 => return a,
            _ => {}
        }
        if let Some(x) = self.as_const(a)
            && let Some(c) = self.fold(x.powi(n))
        {
            return c;
        }
        self.intern(Op::Powi(a, n))
    }

    /// `a^b`: an integer constant exponent (up to 64) becomes `powi`, `x^0.5` becomes `sqrt`,
    /// constants folded.
    pub fn powf(&mut self, a: NodeId, b: NodeId) -> NodeId {
        if let Some(e) = self.as_const(b) {
            if e == e.trunc() && e.abs() <= 64.0 {
                return self.powi(a, e as i32);
            }
            if e == 0.5 {
                return self.func(Func::Sqrt, a);
            }
        }
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b))
            && let Some(c) = self.fold(x.powf(y))
        {
            return c;
        }
        self.intern(Op::Powf(a, b))
    }

    /// `f(a)`: constants folded, `abs(abs x) = abs x`, `signum(signum x) = signum x` and
    /// `floor(floor x) = floor x`.
    pub fn func(&mut self, f: Func, a: NodeId) -> NodeId {
        if let Some(x) = self.as_const(a)
            && let Some(c) = self.fold(f.eval(x))
        {
            return c;
        }
        match (f, self.op(a)) {
            (Func::Abs, Op::Func(Func::Abs, _)) => return a,
            (Func::Signum, Op::Func(Func::Signum, _)) => return a,
            (Func::Floor, Op::Func(Func::Floor, _)) => return a,
            _ => {}
        }
        self.intern(Op::Func(f, a))
    }

    /// `atan2(y, x)`, folded when both are constants.
    pub fn atan2(&mut self, y: NodeId, x: NodeId) -> NodeId {
        if let (Some(yv), Some(xv)) = (self.as_const(y), self.as_const(x))
            && let Some(c) = self.fold(yv.atan2(xv))
        {
            return c;
        }
        self.intern(Op::Atan2(y, x))
    }

    /// `Select(a, b, x, y)` ([`Op::Select`]), simplified: folded when `a` and `b` are
    /// comparable constants (the chosen operand), and when `x` and `y` are one node (that
    /// node: a derivative `Select(a, b, 0, 0)` is zero).
    pub fn select(&mut self, a: NodeId, b: NodeId, x: NodeId, y: NodeId) -> NodeId {
        if x == y {
            return x;
        }
        if let (Some(av), Some(bv)) = (self.as_const(a), self.as_const(b)) {
            if av <= bv {
                return x;
            }
            if bv < av {
                return y;
            }
        }
        self.intern(Op::Select(a, b, x, y))
    }

    /// `min(a, b)`: exactly the smaller argument, the first at a tie, NaN when either is NaN.
    pub fn min(&mut self, a: NodeId, b: NodeId) -> NodeId {
        self.select(a, b, a, b)
    }

    /// `max(a, b)`: exactly the larger argument, the first at a tie, NaN when either is NaN.
    pub fn max(&mut self, a: NodeId, b: NodeId) -> NodeId {
        self.select(b, a, a, b)
    }

    /// All nodes reachable from `roots`, in increasing (topological) order.
    pub fn reachable(&self, roots: &[NodeId]) -> Vec<NodeId> {
        let mut out = self.walk(roots, |op, next| next.extend(op.operands()));
        out.sort_unstable();
        out
    }

    /// All nodes reachable from `roots` without passing through a node of `avoided` (which are
    /// not reached themselves), in increasing (topological) order.
    pub fn reachable_avoiding(&self, roots: &[NodeId], avoided: &[NodeId]) -> Vec<NodeId> {
        let roots: Vec<NodeId> = roots.iter().copied().filter(|r| !avoided.contains(r)).collect();
        let mut out = self.walk(&roots, |op, next| next.extend(op.operands().filter(|o| !avoided.contains(o))));
        out.sort_unstable();
        out
    }

    /// Every node reachable from `roots` through the operands `through` pushes for each node's
    /// operation, each once, in the order found.
    fn walk(&self, roots: &[NodeId], through: impl Fn(Op, &mut Vec<NodeId>)) -> Vec<NodeId> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack: Vec<NodeId> = roots.to_vec();
        let mut out = Vec::new();
        while let Some(n) = stack.pop() {
            if std::mem::replace(&mut seen[n.index()], true) {
                continue;
            }
            out.push(n);
            through(self.op(n), &mut stack);
        }
        out
    }

    /// The leaves a set of roots depends on.
    pub fn leaves_of(&self, roots: &[NodeId]) -> Vec<Leaf> {
        self.reachable(roots)
            .into_iter()
            .filter_map(|n| match self.op(n) {
                Op::Leaf(l) => Some(l),
                _ => None,
            })
            .collect()
    }

    /// The leaves a set of roots depends on through its derivatives: the leaves of
    /// [`Graph::leaves_of`] but for those reached only through a function whose derivative is
    /// zero (`floor`, `signum`) or through the comparison of a `Select` (its derivative is that
    /// of the chosen operand).
    pub fn differentiable_leaves_of(&self, roots: &[NodeId]) -> Vec<Leaf> {
        // The operands each operation passes its derivative through.
        let sloped = |op: Op, next: &mut Vec<NodeId>| match op {
            Op::Func(Func::Floor | Func::Signum, _) => {}
            Op::Select(_, _, x, y) => next.extend([x, y]),
            op => next.extend(op.operands()),
        };
        self.walk(roots, sloped)
            .into_iter()
            .filter_map(|n| match self.op(n) {
                Op::Leaf(l) => Some(l),
                _ => None,
            })
            .collect()
    }

    /// Evaluates nodes numerically (used by the macro's own tests and by constant guesses).
    pub fn eval(&self, roots: &[NodeId], leaf: &dyn Fn(Leaf) -> f64) -> Vec<f64> {
        let order = self.reachable(roots);
        let mut val: HashMap<NodeId, f64> = HashMap::with_capacity(order.len());
        for n in order {
            let v = |x: NodeId| val[&x];
            let r = match self.op(n) {
                Op::Const(bits) => f64::from_bits(bits),
                Op::Leaf(l) => leaf(l),
                Op::Add(a, b) => v(a) + v(b),
                Op::Sub(a, b) => v(a) - v(b),
                Op::Mul(a, b) => v(a) * v(b),
                Op::Div(a, b) => v(a) / v(b),
                Op::Neg(a) => -v(a),
                Op::Powi(a, k) => v(a).powi(k),
                Op::Powf(a, b) => v(a).powf(v(b)),
                Op::Func(f, a) => f.eval(v(a)),
                Op::Atan2(a, b) => v(a).atan2(v(b)),
                Op::Select(a, b, x, y) => select(v(a), v(b), v(x), v(y)),
            };
            val.insert(n, r);
        }
        roots.iter().map(|r| val[r]).collect()
    }
}

fn is_power_of_two(y: f64) -> bool {
    let m = y.abs();
    m.is_normal() && m.log2() == m.log2().trunc()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leaves(g: &mut Graph) -> (NodeId, NodeId) {
        (g.leaf(Leaf::Unknown(0)), g.leaf(Leaf::Param(0)))
    }

    #[test]
    fn hash_consing_shares_nodes() {
        let mut g = Graph::new();
        let (q, p) = leaves(&mut g);
        let a = g.mul(p, q);
        let b = g.mul(q, p);
        assert_eq!(a, b, "multiplication is commutative in the key");
        let s1 = g.func(Func::Sin, q);
        let s2 = g.func(Func::Sin, q);
        assert_eq!(s1, s2);
    }

    #[test]
    fn simplification_removes_trivial_terms() {
        let mut g = Graph::new();
        let (q, _) = leaves(&mut g);
        let zero = g.zero();
        let one = g.one();
        assert_eq!(g.add(q, zero), q);
        assert_eq!(g.mul(one, q), q);
        assert!(g.is_zero(g.clone().mul(zero, q)));
        assert!(g.is_zero(g.clone().sub(q, q)));
        let nq = g.neg(q);
        assert_eq!(g.neg(nq), q);
        assert!(g.is_one(g.clone().div(q, q)));
    }

    #[test]
    fn differentiable_leaves_skip_floor_and_comparisons() {
        let mut g = Graph::new();
        let (q, p) = leaves(&mut g);
        let fl = g.func(Func::Floor, q);
        let sum = g.add(fl, p);
        assert_eq!(g.differentiable_leaves_of(&[fl]), Vec::<Leaf>::new());
        assert_eq!(g.leaves_of(&[fl]).len(), 1);
        assert_eq!(g.differentiable_leaves_of(&[sum]), g.leaves_of(&[p]));
        let one = g.one();
        let chosen = g.select(q, p, one, p);
        assert_eq!(g.differentiable_leaves_of(&[chosen]), g.leaves_of(&[p]));
        let m = g.min(q, p);
        assert_eq!(g.differentiable_leaves_of(&[m]).len(), 2);
    }

    #[test]
    fn zero_over_zero_stays_nan() {
        // `x / x = 1` holds for a symbol; a constant zero over itself is NaN, not one.
        let mut g = Graph::new();
        let zero = g.zero();
        let nan = g.div(zero, zero);
        assert!(g.as_const(nan).is_none(), "0 / 0 was folded");
        assert!(g.eval(&[nan], &|_| 0.0)[0].is_nan());
        let two = g.constant(2.0);
        let one = g.div(two, two);
        assert!(g.is_one(one));
    }

    /// Derivatives against central finite differences of the graph's own evaluation.
    #[test]
    fn tangent_matches_finite_differences() {
        let mut g = Graph::new();
        let (q, p) = leaves(&mut g);
        let s = g.func(Func::Sin, q);
        let c = g.func(Func::Cos, q);
        let pq = g.mul(p, s);
        let r = g.div(pq, c);
        let two = g.constant(2.0);
        let sq = g.powf(q, two);
        let e = g.func(Func::Exp, sq);
        let at = g.atan2(s, e);
        let l = g.func(Func::Ln, e);
        let half = g.constant(0.3);
        let pw = g.powf(p, half);
        let as_ = g.mul(half, s);
        let asn = g.func(Func::Asin, as_);
        let ac = g.func(Func::Acos, as_);
        let sqr = g.func(Func::Sqrt, e);
        let t = g.func(Func::Tan, as_);
        let ab = g.func(Func::Abs, r);
        let at1 = g.func(Func::Atan, r);
        let qp = g.powf(p, q);
        let roots = [r, at, l, pw, asn, ac, sqr, t, ab, at1, qp, e];
        let one = g.one();
        let d = g.tangent(&roots, &|leaf| (leaf == Leaf::Unknown(0)).then_some(one));
        let eval_at = |g: &Graph, qv: f64, nodes: &[NodeId]| {
            g.eval(nodes, &|l| match l {
                Leaf::Unknown(0) => qv,
                Leaf::Param(0) => 1.7,
                _ => f64::NAN,
            })
        };
        let q0 = 0.4;
        let h = 1e-6;
        let plus = eval_at(&g, q0 + h, &roots);
        let minus = eval_at(&g, q0 - h, &roots);
        let exact = eval_at(&g, q0, &d);
        for i in 0..roots.len() {
            let fd = (plus[i] - minus[i]) / (2.0 * h);
            assert!((fd - exact[i]).abs() <= 1e-7 * (1.0 + fd.abs()), "root {i}: fd {fd} vs ad {}", exact[i]);
        }
    }

    /// `min`, `max`: exactly one argument (tiny values kept, the first at a tie, told by the
    /// sign of zero), NaN whichever argument is NaN, constants folded, nodes shared.
    #[test]
    fn min_max_pick_an_argument_exactly() {
        let mut g = Graph::new();
        let (a, b) = (g.leaf(Leaf::Unknown(0)), g.leaf(Leaf::Unknown(1)));
        let (mn, mx) = (g.min(a, b), g.max(a, b));
        assert_eq!(g.min(a, b), mn, "hash-consed");
        assert_ne!(mn, mx);
        let at = |g: &Graph, x: f64, y: f64| {
            let v = g.eval(&[mn, mx], &|l| if l == Leaf::Unknown(0) { x } else { y });
            (v[0], v[1])
        };
        assert_eq!(at(&g, 1e-300, 1.0), (1e-300, 1.0));
        assert_eq!(at(&g, 1.0, -1e-310), (-1e-310, 1.0));
        // A tie picks the first argument: -0.0 and 0.0 compare equal.
        let (m0, x0) = at(&g, -0.0, 0.0);
        assert!(m0.is_sign_negative() && x0.is_sign_negative());
        let (m1, x1) = at(&g, 0.0, -0.0);
        assert!(m1.is_sign_positive() && x1.is_sign_positive());
        for (x, y) in [(f64::NAN, 1.0), (1.0, f64::NAN), (f64::NAN, f64::INFINITY), (f64::NAN, f64::NAN)] {
            let (lo, hi) = at(&g, x, y);
            assert!(lo.is_nan() && hi.is_nan(), "min/max({x}, {y}) = {lo}, {hi}");
        }
        assert_eq!(at(&g, f64::INFINITY, 2.0), (2.0, f64::INFINITY));
        assert_eq!(select(1.0, 2.0, 3.0, 4.0), 3.0);
        assert_eq!(select(2.0, 1.0, 3.0, 4.0), 4.0);
        assert!(select(f64::NAN, 1.0, 3.0, 4.0).is_nan());
        // Constant folding and simplification.
        let (c2, c3) = (g.constant(2.0), g.constant(3.0));
        assert_eq!(g.min(c2, c3), c2);
        assert_eq!(g.max(c2, c3), c3);
        assert_eq!(g.min(a, a), a);
        let nan = g.constant(f64::NAN);
        let with_nan = g.min(nan, c2);
        assert!(matches!(g.op(with_nan), Op::Select(..)), "a NaN constant is not folded away");
        let clamp = {
            let low = g.max(c3, c2);
            let hi = g.constant(2.5);
            g.min(low, hi)
        };
        assert_eq!(g.as_const(clamp), Some(2.5));
    }

    /// The derivative of `min`/`max` is the chosen argument's (the first's at a tie), to second
    /// order, and the unused argument's non-finite derivative does not leak.
    #[test]
    fn min_max_derivatives_follow_the_chosen_argument() {
        let mut g = Graph::new();
        let (q, p) = leaves(&mut g);
        let q2 = g.powi(q, 3);
        let three_q = {
            let c = g.constant(3.0);
            g.mul(c, q)
        };
        let mn = g.min(q2, three_q);
        let mx = g.max(q2, three_q);
        let one = g.one();
        let seed = |l: Leaf| (l == Leaf::Unknown(0)).then_some(one);
        let d1 = g.tangent(&[mn, mx], &seed);
        let d2 = g.tangent(&d1, &seed);
        let at = |g: &Graph, qv: f64, n: &[NodeId]| g.eval(n, &|l| if l == Leaf::Unknown(0) { qv } else { 1.0 });
        // q^3 < 3q for q = 1: min is q^3 (3q^2, 6q), max 3q (3, 0).
        assert_eq!(at(&g, 1.0, &d1), [3.0, 3.0]);
        assert_eq!(at(&g, 1.0, &d2), [6.0, 0.0]);
        // q = 2: q^3 = 8 > 6.
        assert_eq!(at(&g, 2.0, &d1), [3.0, 12.0]);
        assert_eq!(at(&g, 2.0, &d2), [0.0, 12.0]);
        // A tie (q = sqrt 3, rounded, is not one; q = 0 is): the first argument's, q^3's.
        assert_eq!(at(&g, 0.0, &d1), [0.0, 0.0]);
        assert_eq!(at(&g, 0.0, &d2), [0.0, 0.0]);
        // max(q, sqrt(p - q)) at q = p = 1: q is chosen, the square root's derivative is -inf.
        let r = {
            let d = g.sub(p, q);
            g.func(Func::Sqrt, d)
        };
        let m = g.max(q, r);
        let dm = g.tangent(&[m, r], &seed);
        let v = g.eval(&dm, &|l| if l == Leaf::Unknown(0) || l == Leaf::Param(0) { 1.0 } else { 0.0 });
        assert!(v[1].is_infinite(), "the unused derivative is infinite: {}", v[1]);
        assert_eq!(v[0], 1.0);
        // A constant argument's zero derivative: `min(q, 2)` has derivative 1 or 0, a NaN q NaN.
        let c2 = g.constant(2.0);
        let mc = g.min(q, c2);
        let dmc = g.tangent(&[mc], &seed)[0];
        assert!(matches!(g.op(dmc), Op::Select(..)));
        assert_eq!(at(&g, 1.0, &[dmc]), [1.0]);
        assert_eq!(at(&g, 3.0, &[dmc]), [0.0]);
        assert!(at(&g, f64::NAN, &[mc, dmc]).iter().all(|v| v.is_nan()));
        // Substitution rebuilds and folds.
        let s = g.substitute(&[mc], &|l| (l == Leaf::Unknown(0)).then_some(one))[0];
        assert_eq!(g.as_const(s), Some(1.0));
    }

    /// `floor`: the largest integer not above the argument, exactly (negative arguments round
    /// away from zero, integers and huge values are their own floor, the sign of zero kept), NaN
    /// and the infinities their own floor; folded for finite constants, `floor(floor x)` shared.
    #[test]
    fn floor_is_the_largest_integer_not_above() {
        let mut g = Graph::new();
        let (q, _) = leaves(&mut g);
        let fl = g.func(Func::Floor, q);
        assert_eq!(g.func(Func::Floor, fl), fl, "floor(floor x) = floor x");
        let at = |g: &Graph, x: f64| g.eval(&[fl], &|_| x)[0];
        let cases = [
            (2.5, 2.0),
            (2.0, 2.0),
            (-2.0, -2.0),
            (-2.5, -3.0),
            (-0.5, -1.0),
            (-1e-300, -1.0),
            (1e-300, 0.0),
            (0.999_999_999_999_999_9, 0.0),
            (-0.999_999_999_999_999_9, -1.0),
            (4_503_599_627_370_495.5, 4_503_599_627_370_495.0),
            (-4_503_599_627_370_495.5, -4_503_599_627_370_496.0),
            (1e300, 1e300),
            (-1e300, -1e300),
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        ];
        for (x, want) in cases {
            assert_eq!(Func::Floor.eval(x).to_bits(), want.to_bits(), "floor({x})");
            assert_eq!(at(&g, x).to_bits(), want.to_bits(), "floor({x}) in the graph");
        }
        assert!(at(&g, 0.0).is_sign_positive() && at(&g, -0.0).is_sign_negative());
        assert!(Func::Floor.eval(f64::NAN).is_nan() && at(&g, f64::NAN).is_nan());
        assert_eq!(Func::Floor.method(), "floor");
        // Constants: folded when finite.
        let c = g.constant(-7.25);
        let folded = g.func(Func::Floor, c);
        assert_eq!(g.as_const(folded), Some(-8.0));
        let nan = g.constant(f64::NAN);
        let kept = g.func(Func::Floor, nan);
        assert!(matches!(g.op(kept), Op::Func(Func::Floor, _)), "a NaN constant is not folded away");
    }

    /// The derivative of `floor` is zero to second order, also where its argument's derivative
    /// is infinite; `x - p floor(x / p)` (`wrap`) has the derivatives of `x`.
    #[test]
    fn floor_has_zero_derivatives() {
        let mut g = Graph::new();
        let (q, p) = leaves(&mut g);
        let q3 = g.powi(q, 3);
        let fl = g.func(Func::Floor, q3);
        let one = g.one();
        let seed = |l: Leaf| (l == Leaf::Unknown(0)).then_some(one);
        let d1 = g.tangent(&[fl], &seed);
        assert!(g.is_zero(d1[0]), "d floor(q^3) is the zero node");
        let d2 = g.tangent(&d1, &seed);
        assert!(g.is_zero(d2[0]));
        // floor(sqrt(p - q)) at q = p: the argument's derivative is -inf, the floor's still 0.
        let r = {
            let d = g.sub(p, q);
            g.func(Func::Sqrt, d)
        };
        let fr = g.func(Func::Floor, r);
        let dr = g.tangent(&[fr], &seed);
        assert_eq!(g.eval(&dr, &|_| 1.0), [0.0]);
        // wrap(q^3, p) = q^3 - p floor(q^3 / p): analogs 3q^2 and 6q, in every turn.
        let w = {
            let t = g.div(q3, p);
            let f = g.func(Func::Floor, t);
            let back = g.mul(p, f);
            g.sub(q3, back)
        };
        let w1 = g.tangent(&[w], &seed);
        let w2 = g.tangent(&w1, &seed);
        let x1 = g.tangent(&[q3], &seed);
        let x2 = g.tangent(&x1, &seed);
        assert_eq!((w1[0], w2[0]), (x1[0], x2[0]), "the analogs of q^3 itself");
        for qv in [-2.5, -1.0, 0.3, 1.7, 4.0] {
            let leaf = |l: Leaf| if l == Leaf::Unknown(0) { qv } else { 1.5 };
            let v = g.eval(&[w, w1[0], w2[0]], &leaf);
            let want = qv.powi(3) - 1.5 * (qv.powi(3) / 1.5).floor();
            assert_eq!(v[0], want, "q = {qv}");
            assert!((v[1] - 3.0 * qv * qv).abs() <= 1e-14 * v[1] && v[2] == 6.0 * qv, "q = {qv}: {v:?}");
            assert!((0.0..1.5).contains(&v[0]), "q = {qv}: {}", v[0]);
        }
    }

    #[test]
    fn deep_chains_do_not_recurse() {
        let mut g = Graph::new();
        let (q, _) = leaves(&mut g);
        let mut acc = q;
        for _ in 0..200_000 {
            let s = g.func(Func::Sin, acc);
            acc = g.add(s, q);
        }
        let one = g.one();
        let d = g.tangent(&[acc], &|l| (l == Leaf::Unknown(0)).then_some(one));
        assert!(g.eval(&d, &|_| 0.1)[0].is_finite());
    }
}
