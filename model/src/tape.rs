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

use kinloop_codegen::graph::dag::{Func, Graph, Leaf, NodeId, Op};

/// One operation: destination register first, then the operands' registers.
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
    Func(u32, Func, u32),
    Atan2(u32, u32, u32),
}

/// A run of instructions, executed in order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Segment {
    ins: Vec<Ins>,
    /// One more than the largest register an instruction names: the registers a run needs.
    needs: usize,
}

impl Segment {
    /// Executes the segment over the registers.
    #[inline]
    pub(crate) fn run(&self, r: &mut [f64]) {
        // Every register an instruction names is below `needs` (checked when the segment was
        // built): one test here instead of one per operand.
        assert!(r.len() >= self.needs, "registers of another tape");
        let r = &mut r[..self.needs];
        for ins in &self.ins {
            // SAFETY: every index is below `needs` = `r.len()` (see `Segment::new`).
            unsafe {
                let v = |k: u32| *r.get_unchecked(k as usize);
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
                    Ins::Func(d, f, a) => (d, func(f, v(a))),
                    Ins::Atan2(d, y, x) => (d, v(y).atan2(v(x))),
                };
                *r.get_unchecked_mut(d as usize) = x;
            }
        }
    }

    /// A segment of `ins`, with the registers it names counted.
    fn new(ins: Vec<Ins>) -> Segment {
        let needs = ins
            .iter()
            .map(|i| match *i {
                Ins::Add(d, a, b)
                | Ins::Sub(d, a, b)
                | Ins::Mul(d, a, b)
                | Ins::Div(d, a, b)
                | Ins::Powf(d, a, b)
                | Ins::Atan2(d, a, b) => d.max(a).max(b),
                Ins::Neg(d, a) | Ins::Square(d, a) | Ins::Recip(d, a) | Ins::Powi(d, a, _) | Ins::Func(d, _, a) => {
                    d.max(a)
                }
            })
            .max()
            .map_or(0, |m| m as usize + 1);
        Segment { ins, needs }
    }

    /// The number of instructions.
    pub(crate) fn len(&self) -> usize {
        self.ins.len()
    }
}

/// The `f64` method the emitter calls for `f` ([`Func::method`]): `signum` is `f64::signum`
/// there (not the constant folder's, which gives 0 at 0).
#[inline]
fn func(f: Func, x: f64) -> f64 {
    match f {
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
        Func::Signum => x.signum(),
    }
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
    /// A builder over `g`, with the constants, parameters and inputs known.
    pub(crate) fn new(g: &'g Graph) -> Self {
        let known = (0..g.len())
            .map(|k| matches!(g.op(NodeId(k as u32)), Op::Const(_) | Op::Leaf(Leaf::Param(_) | Leaf::Input(_))))
            .collect();
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
                Op::Func(f, a) => Ins::Func(d, f, o(a)),
                Op::Atan2(y, x) => Ins::Atan2(d, o(y), o(x)),
            });
        }
        for ins in &out {
            let d = match *ins {
                Ins::Add(d, ..)
                | Ins::Sub(d, ..)
                | Ins::Mul(d, ..)
                | Ins::Div(d, ..)
                | Ins::Neg(d, _)
                | Ins::Square(d, _)
                | Ins::Recip(d, _)
                | Ins::Powi(d, ..)
                | Ins::Powf(d, ..)
                | Ins::Func(d, ..)
                | Ins::Atan2(d, ..) => d,
            };
            self.known[d as usize] = true;
        }
        Ok(Segment::new(out))
    }
}

/// The registers of a graph with its constants written.
pub(crate) fn registers(g: &Graph) -> Vec<f64> {
    (0..g.len()).map(|k| g.as_const(NodeId(k as u32)).unwrap_or(0.0)).collect()
}
