//! The instruction tape: the plan's expression graph as straight-line instructions over `f64`
//! registers, one register per graph node.
//!
//! A register holds its node's value: constants are written once when the tape is built,
//! parameters when they are set, inputs, unknowns and analogs when a step reaches them, every
//! other node by the instruction that computes it. The instructions of one part of a step (a
//! block's coefficients, its Newton evaluation, its analogs' right-hand sides, the outputs) form
//! a [`Segment`]: the nodes its roots need that no earlier segment computed, in the graph's
//! order (a topological order). Each instruction performs the operation the emitted code
//! writes for its node (`a * a` for a square, `1.0 / a` for a reciprocal, `f64::signum`, ...),
//! so that a run-time step computes the same values as the compiled one.
//!
//! What makes a step cheaper without changing a value: the nodes of the parameters alone are
//! computed when the parameters are set ([`statics`]; the compiled step recomputes them with
//! the same operations), a sine and a cosine of one argument are one instruction, and two
//! consecutive arithmetic operations share one dispatch (each still rounds on its own, in its
//! order: no fused multiply-add, which the emitted code does not use). Operands are `u32`
//! register indices checked once per segment when it is built.

use kinloop_codegen::graph::dag::{Func, Graph, Leaf, NodeId, Op};

/// One operation: destination register first, then the operands' registers.
///
/// The elementary functions are variants of their own (one dispatch, not two), a sine and a
/// cosine of one argument are one instruction ([`Ins::SinCos`], as the emitted code's
/// `sin_cos`, which computes `(sin, cos)`), and two consecutive arithmetic operations are one
/// instruction (`Ins::MulAdd`, ...): each still performs its own rounding in its own order, so the
/// values are those of the separate operations; only the dispatch is shared.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Ins {
    Add(u32, u32, u32),
    Sub(u32, u32, u32),
    Mul(u32, u32, u32),
    Div(u32, u32, u32),
    Neg(u32, u32),
    /// `a * a` (the emitter's square).
    Square(u32, u32),
    /// `1.0 / a` (the emitter's reciprocal).
    Recip(u32, u32),
    Powi(u32, u32, i32),
    Powf(u32, u32, u32),
    Sin(u32, u32),
    Cos(u32, u32),
    /// `(sin a, cos a)` into the first two registers.
    SinCos(u32, u32, u32),
    Tan(u32, u32),
    Asin(u32, u32),
    Acos(u32, u32),
    Atan(u32, u32),
    Sqrt(u32, u32),
    Exp(u32, u32),
    Ln(u32, u32),
    Abs(u32, u32),
    Signum(u32, u32),
    Atan2(u32, u32, u32),
    /// Two arithmetic operations executed in order (the second may read the first's result),
    /// named by the first's operation and the second's: `AddMul([d, a, b], [e, x, y])` is
    /// `d = a + b; e = x * y`.
    AddAdd([u32; 3], [u32; 3]),
    AddSub([u32; 3], [u32; 3]),
    AddMul([u32; 3], [u32; 3]),
    AddDiv([u32; 3], [u32; 3]),
    SubAdd([u32; 3], [u32; 3]),
    SubSub([u32; 3], [u32; 3]),
    SubMul([u32; 3], [u32; 3]),
    SubDiv([u32; 3], [u32; 3]),
    MulAdd([u32; 3], [u32; 3]),
    MulSub([u32; 3], [u32; 3]),
    MulMul([u32; 3], [u32; 3]),
    MulDiv([u32; 3], [u32; 3]),
    DivAdd([u32; 3], [u32; 3]),
    DivSub([u32; 3], [u32; 3]),
    DivMul([u32; 3], [u32; 3]),
    DivDiv([u32; 3], [u32; 3]),
}

impl Ins {
    /// The registers the instruction writes, then those it reads.
    fn registers(&self) -> impl Iterator<Item = u32> {
        let (v, n): ([u32; 6], usize) = match *self {
            Ins::Add(d, a, b)
            | Ins::Sub(d, a, b)
            | Ins::Mul(d, a, b)
            | Ins::Div(d, a, b)
            | Ins::Powf(d, a, b)
            | Ins::Atan2(d, a, b)
            | Ins::SinCos(d, a, b) => ([d, a, b, 0, 0, 0], 3),
            Ins::Neg(d, a)
            | Ins::Square(d, a)
            | Ins::Recip(d, a)
            | Ins::Powi(d, a, _)
            | Ins::Sin(d, a)
            | Ins::Cos(d, a)
            | Ins::Tan(d, a)
            | Ins::Asin(d, a)
            | Ins::Acos(d, a)
            | Ins::Atan(d, a)
            | Ins::Sqrt(d, a)
            | Ins::Exp(d, a)
            | Ins::Ln(d, a)
            | Ins::Abs(d, a)
            | Ins::Signum(d, a) => ([d, a, 0, 0, 0, 0], 2),
            Ins::AddAdd([d, a, b], [e, x, y])
            | Ins::AddSub([d, a, b], [e, x, y])
            | Ins::AddMul([d, a, b], [e, x, y])
            | Ins::AddDiv([d, a, b], [e, x, y])
            | Ins::SubAdd([d, a, b], [e, x, y])
            | Ins::SubSub([d, a, b], [e, x, y])
            | Ins::SubMul([d, a, b], [e, x, y])
            | Ins::SubDiv([d, a, b], [e, x, y])
            | Ins::MulAdd([d, a, b], [e, x, y])
            | Ins::MulSub([d, a, b], [e, x, y])
            | Ins::MulMul([d, a, b], [e, x, y])
            | Ins::MulDiv([d, a, b], [e, x, y])
            | Ins::DivAdd([d, a, b], [e, x, y])
            | Ins::DivSub([d, a, b], [e, x, y])
            | Ins::DivMul([d, a, b], [e, x, y])
            | Ins::DivDiv([d, a, b], [e, x, y]) => ([d, a, b, e, x, y], 6),
        };
        v.into_iter().take(n)
    }

    /// The arithmetic operation `(op, [d, a, b])` of a single instruction, for pairing.
    fn arith(&self) -> Option<(u8, [u32; 3])> {
        match *self {
            Ins::Add(d, a, b) => Some((0, [d, a, b])),
            Ins::Sub(d, a, b) => Some((1, [d, a, b])),
            Ins::Mul(d, a, b) => Some((2, [d, a, b])),
            Ins::Div(d, a, b) => Some((3, [d, a, b])),
            _ => None,
        }
    }
}

/// A run of instructions, executed in order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Segment {
    ins: Vec<Ins>,
    /// One more than the largest register an instruction names: the registers a run needs.
    needs: usize,
    /// The graph operations the segment performs (an instruction may perform two).
    ops: usize,
}

impl Segment {
    /// Executes the segment over the registers.
    #[inline]
    pub(crate) fn run(&self, r: &mut [f64]) {
        // Every register an instruction names is below `needs` (checked when the segment was
        // built): one test here instead of one per operand.
        if self.ins.is_empty() {
            return;
        }
        assert!(r.len() >= self.needs, "registers of another tape");
        let p = r[..self.needs].as_mut_ptr();
        for ins in &self.ins {
            // SAFETY: every index is below `needs` <= `r.len()` (see `Segment::new`).
            unsafe {
                let v = |k: u32| *p.add(k as usize);
                macro_rules! pair {
                    ($d:ident, $a:ident, $f:tt, $b:ident, $e:ident, $x:ident, $g:tt, $y:ident) => {{
                        *p.add($d as usize) = v($a) $f v($b);
                        ($e, v($x) $g v($y))
                    }};
                }
                let (d, x) = match *ins {
                    Ins::Add(d, a, b) => (d, v(a) + v(b)),
                    Ins::Sub(d, a, b) => (d, v(a) - v(b)),
                    Ins::Mul(d, a, b) => (d, v(a) * v(b)),
                    Ins::Div(d, a, b) => (d, v(a) / v(b)),
                    Ins::Neg(d, a) => (d, -v(a)),
                    Ins::Square(d, a) => {
                        let x = v(a);
                        (d, x * x)
                    }
                    Ins::Recip(d, a) => (d, 1.0 / v(a)),
                    Ins::Powi(d, a, k) => (d, v(a).powi(k)),
                    Ins::Powf(d, a, b) => (d, v(a).powf(v(b))),
                    Ins::Sin(d, a) => (d, v(a).sin()),
                    Ins::Cos(d, a) => (d, v(a).cos()),
                    Ins::SinCos(s, c, a) => {
                        let (sin, cos) = v(a).sin_cos();
                        *p.add(s as usize) = sin;
                        (c, cos)
                    }
                    Ins::Tan(d, a) => (d, v(a).tan()),
                    Ins::Asin(d, a) => (d, v(a).asin()),
                    Ins::Acos(d, a) => (d, v(a).acos()),
                    Ins::Atan(d, a) => (d, v(a).atan()),
                    Ins::Sqrt(d, a) => (d, v(a).sqrt()),
                    Ins::Exp(d, a) => (d, v(a).exp()),
                    Ins::Ln(d, a) => (d, v(a).ln()),
                    Ins::Abs(d, a) => (d, v(a).abs()),
                    // `f64::signum`, as the emitted code calls it (not the constant folder's,
                    // which gives 0 at 0).
                    Ins::Signum(d, a) => (d, v(a).signum()),
                    Ins::Atan2(d, y, x) => (d, v(y).atan2(v(x))),
                    Ins::AddAdd([d, a, b], [e, x, y]) => pair!(d, a, +, b, e, x, +, y),
                    Ins::AddSub([d, a, b], [e, x, y]) => pair!(d, a, +, b, e, x, -, y),
                    Ins::AddMul([d, a, b], [e, x, y]) => pair!(d, a, +, b, e, x, *, y),
                    Ins::AddDiv([d, a, b], [e, x, y]) => pair!(d, a, +, b, e, x, /, y),
                    Ins::SubAdd([d, a, b], [e, x, y]) => pair!(d, a, -, b, e, x, +, y),
                    Ins::SubSub([d, a, b], [e, x, y]) => pair!(d, a, -, b, e, x, -, y),
                    Ins::SubMul([d, a, b], [e, x, y]) => pair!(d, a, -, b, e, x, *, y),
                    Ins::SubDiv([d, a, b], [e, x, y]) => pair!(d, a, -, b, e, x, /, y),
                    Ins::MulAdd([d, a, b], [e, x, y]) => pair!(d, a, *, b, e, x, +, y),
                    Ins::MulSub([d, a, b], [e, x, y]) => pair!(d, a, *, b, e, x, -, y),
                    Ins::MulMul([d, a, b], [e, x, y]) => pair!(d, a, *, b, e, x, *, y),
                    Ins::MulDiv([d, a, b], [e, x, y]) => pair!(d, a, *, b, e, x, /, y),
                    Ins::DivAdd([d, a, b], [e, x, y]) => pair!(d, a, /, b, e, x, +, y),
                    Ins::DivSub([d, a, b], [e, x, y]) => pair!(d, a, /, b, e, x, -, y),
                    Ins::DivMul([d, a, b], [e, x, y]) => pair!(d, a, /, b, e, x, *, y),
                    Ins::DivDiv([d, a, b], [e, x, y]) => pair!(d, a, /, b, e, x, /, y),
                };
                *p.add(d as usize) = x;
            }
        }
    }

    /// A segment of `ins` (one instruction per graph operation, in order): a sine and a cosine
    /// of one argument merged, consecutive arithmetic operations paired, the registers counted.
    fn new(ins: Vec<Ins>) -> Segment {
        let ops = ins.len();
        let ins = pair(sin_cos(ins));
        let needs = ins.iter().flat_map(Ins::registers).max().map_or(0, |m| m as usize + 1);
        Segment { ins, needs, ops }
    }

    /// The number of graph operations.
    pub(crate) fn len(&self) -> usize {
        self.ops
    }
}

/// Merges a sine and a cosine of the same register into one [`Ins::SinCos`] at the place of
/// the first: its argument is computed before either, and nothing between the two reads the
/// second's register (it is written once, by the second).
fn sin_cos(ins: Vec<Ins>) -> Vec<Ins> {
    let mut out: Vec<Ins> = Vec::with_capacity(ins.len());
    // Per argument register: the index in `out` of a lone sine or cosine of it.
    let mut lone: std::collections::HashMap<u32, usize> = std::collections::HashMap::new();
    for i in ins {
        match i {
            Ins::Sin(d, a) | Ins::Cos(d, a) => {
                if let Some(k) = lone.remove(&a) {
                    match (out[k], i) {
                        (Ins::Sin(s, _), Ins::Cos(c, _)) | (Ins::Cos(c, _), Ins::Sin(s, _)) => {
                            out[k] = Ins::SinCos(s, c, a);
                            continue;
                        }
                        _ => {}
                    }
                }
                lone.insert(a, out.len());
                let _ = d;
                out.push(i);
            }
            _ => out.push(i),
        }
    }
    out
}

/// Pairs consecutive arithmetic instructions into one (`Ins::AddMul`, ...: same operations,
/// same order).
fn pair(ins: Vec<Ins>) -> Vec<Ins> {
    type Make = fn([u32; 3], [u32; 3]) -> Ins;
    const TABLE: [[Make; 4]; 4] = [
        [Ins::AddAdd, Ins::AddSub, Ins::AddMul, Ins::AddDiv],
        [Ins::SubAdd, Ins::SubSub, Ins::SubMul, Ins::SubDiv],
        [Ins::MulAdd, Ins::MulSub, Ins::MulMul, Ins::MulDiv],
        [Ins::DivAdd, Ins::DivSub, Ins::DivMul, Ins::DivDiv],
    ];
    let mut out = Vec::with_capacity(ins.len());
    let mut k = 0;
    while k < ins.len() {
        match (ins[k].arith(), ins.get(k + 1).and_then(Ins::arith)) {
            (Some((f, first)), Some((g, second))) => {
                out.push(TABLE[f as usize][g as usize](first, second));
                k += 2;
            }
            _ => {
                out.push(ins[k]);
                k += 1;
            }
        }
    }
    out
}

/// Builds segments in the order a step runs them, each computing only what no earlier one did.
pub(crate) struct Builder<'g> {
    g: &'g Graph,
    /// Per node: whether a register already holds its value when the next segment runs.
    known: Vec<bool>,
}

/// A node the segments need whose value nothing provides: a leaf read before its stage (a
/// plan the tape does not understand). Never expected from the macro's planner.
#[derive(Debug)]
pub(crate) struct Unavailable(pub(crate) Leaf);

impl<'g> Builder<'g> {
    /// A builder over `g`, with the constants, parameters, inputs and the nodes of parameters
    /// alone (computed when the parameters are set, [`statics`]) known.
    pub(crate) fn new(g: &'g Graph) -> Self {
        let mut known = fixed(g);
        for (k, op) in (0..g.len()).map(|k| (k, g.op(NodeId(k as u32)))) {
            known[k] |= matches!(op, Op::Leaf(Leaf::Input(_)));
        }
        Builder { g, known }
    }

    /// Marks nodes whose registers a solve writes (unknowns, analogs, a closed form's sines and
    /// cosines).
    pub(crate) fn provide(&mut self, nodes: impl IntoIterator<Item = NodeId>) {
        for n in nodes {
            self.known[n.index()] = true;
        }
    }

    /// The segment computing `roots`; with `only`, only the nodes it accepts (the others are
    /// left for a later segment).
    pub(crate) fn segment(
        &mut self,
        roots: &[NodeId],
        only: Option<&dyn Fn(NodeId) -> bool>,
    ) -> Result<Segment, Unavailable> {
        let mut out = Vec::new();
        let mut seen = vec![false; self.g.len()];
        let mut stack: Vec<NodeId> = roots.to_vec();
        let mut order = Vec::new();
        while let Some(n) = stack.pop() {
            if self.known[n.index()] || std::mem::replace(&mut seen[n.index()], true) {
                continue;
            }
            // A node left for a later segment is not computed here, but its operands may be.
            if only.is_none_or(|f| f(n)) {
                order.push(n);
            }
            stack.extend(self.g.op(n).operands());
        }
        // A sine or cosine brings its partner of the same argument, when the graph has one that
        // no segment computed yet: the two are then one instruction (one libm call for both)
        // instead of one here and one in a later segment. The partner's value is the same
        // wherever it is computed.
        for k in 0..order.len() {
            let partner = match self.g.op(order[k]) {
                Op::Func(Func::Sin, a) => self.g.find(Op::Func(Func::Cos, a)),
                Op::Func(Func::Cos, a) => self.g.find(Op::Func(Func::Sin, a)),
                _ => None,
            };
            if let Some(p) = partner
                && !self.known[p.index()]
                && !std::mem::replace(&mut seen[p.index()], true)
                && only.is_none_or(|f| f(p))
            {
                order.push(p);
            }
        }
        order.sort_unstable();
        for n in order {
            let d = n.0;
            let o = |x: NodeId| x.0;
            out.push(match self.g.op(n) {
                Op::Const(_) => continue,
                Op::Leaf(l) => return Err(Unavailable(l)),
                Op::Add(a, b) => Ins::Add(d, o(a), o(b)),
                Op::Sub(a, b) => Ins::Sub(d, o(a), o(b)),
                Op::Mul(a, b) => Ins::Mul(d, o(a), o(b)),
                Op::Div(a, b) => Ins::Div(d, o(a), o(b)),
                Op::Neg(a) => Ins::Neg(d, o(a)),
                Op::Powi(a, 2) => Ins::Square(d, o(a)),
                Op::Powi(a, -1) => Ins::Recip(d, o(a)),
                Op::Powi(a, k) => Ins::Powi(d, o(a), k),
                Op::Powf(a, b) => Ins::Powf(d, o(a), o(b)),
                Op::Func(f, a) => {
                    let a = o(a);
                    match f {
                        Func::Sin => Ins::Sin(d, a),
                        Func::Cos => Ins::Cos(d, a),
                        Func::Tan => Ins::Tan(d, a),
                        Func::Asin => Ins::Asin(d, a),
                        Func::Acos => Ins::Acos(d, a),
                        Func::Atan => Ins::Atan(d, a),
                        Func::Sqrt => Ins::Sqrt(d, a),
                        Func::Exp => Ins::Exp(d, a),
                        Func::Ln => Ins::Ln(d, a),
                        Func::Abs => Ins::Abs(d, a),
                        Func::Signum => Ins::Signum(d, a),
                    }
                }
                Op::Atan2(y, x) => Ins::Atan2(d, o(y), o(x)),
            });
        }
        for ins in &out {
            // The first register an unmerged instruction names is the one it writes.
            if let Some(d) = ins.registers().next() {
                self.known[d as usize] = true;
            }
        }
        Ok(Segment::new(out))
    }
}

/// The registers of a graph with its constants written.
pub(crate) fn registers(g: &Graph) -> Vec<f64> {
    (0..g.len()).map(|k| g.as_const(NodeId(k as u32)).unwrap_or(0.0)).collect()
}

/// Per node: whether its value depends on the parameters and constants alone (the graph's
/// order is topological: operands come before their users).
fn fixed(g: &Graph) -> Vec<bool> {
    let mut fixed = vec![false; g.len()];
    for k in 0..g.len() {
        let op = g.op(NodeId(k as u32));
        fixed[k] = match op {
            Op::Const(_) | Op::Leaf(Leaf::Param(_)) => true,
            Op::Leaf(_) => false,
            _ => op.operands().all(|o| fixed[o.index()]),
        };
    }
    fixed
}

/// The segment computing every node of the parameters alone, run when the parameters are set:
/// the compiled step computes these nodes on every call, with the same operations, so hoisting
/// them out of the step changes no value.
pub(crate) fn statics(g: &Graph) -> Segment {
    let fixed = fixed(g);
    let roots: Vec<NodeId> = (0..g.len()).filter(|&k| fixed[k]).map(|k| NodeId(k as u32)).collect();
    let mut b = Builder {
        g,
        known: (0..g.len())
            .map(|k| matches!(g.op(NodeId(k as u32)), Op::Const(_) | Op::Leaf(Leaf::Param(_))))
            .collect(),
    };
    // Every operand of a fixed node is fixed: no leaf but a parameter is reached.
    b.segment(&roots, None).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use kinloop_codegen::graph::dag::Func;

    /// The merged and paired instructions compute what the separate operations compute, bit for
    /// bit: the reference is the same expression written out in Rust, as the emitted code
    /// writes it.
    #[test]
    fn merged_and_paired_instructions_give_the_separate_operations_values() {
        let mut g = Graph::new();
        let x = g.leaf(Leaf::Input(0));
        let y = g.leaf(Leaf::Input(1));
        let p = g.leaf(Leaf::Param(0));
        let sx = g.func(Func::Sin, x);
        let cx = g.func(Func::Cos, x);
        let a = g.mul(p, sx);
        let b = g.mul(y, cx);
        let s = g.add(a, b);
        let d = g.sub(x, y);
        let e = g.add(x, y);
        let q = g.div(d, e);
        let pp = g.mul(p, p);
        let pp = g.func(Func::Sqrt, pp);
        let t = g.mul(q, pp);
        let roots = [s, t];

        let statics = statics(&g);
        let seg = Builder::new(&g).segment(&roots, None).expect("every leaf is known");
        assert!(seg.ins.iter().any(|i| matches!(i, Ins::SinCos(..))), "{:?}", seg.ins);
        assert!(
            seg.ins.iter().any(|i| matches!(i, Ins::MulMul(..) | Ins::MulAdd(..) | Ins::SubAdd(..))),
            "{:?}",
            seg.ins
        );
        assert!(!seg.ins.iter().any(|i| matches!(i, Ins::Sqrt(..))), "the parameters' nodes are hoisted");

        for (xv, yv, pv) in [(0.3, -1.7, 2.5), (1e-3, 4.0, -0.7), (-2.9, 1e5, 1e-9)] {
            let mut r = registers(&g);
            r[x.index()] = xv;
            r[y.index()] = yv;
            r[p.index()] = pv;
            statics.run(&mut r);
            seg.run(&mut r);
            let (sin, cos) = xv.sin_cos();
            let want_s = pv * sin + yv * cos;
            let want_t = ((xv - yv) / (xv + yv)) * (pv * pv).sqrt();
            assert_eq!(r[s.index()].to_bits(), want_s.to_bits());
            assert_eq!(r[t.index()].to_bits(), want_t.to_bits());
        }
    }
}
