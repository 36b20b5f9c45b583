//! The description's evaluator: a straight list of scalar operations over the parameters,
//! inputs and unknowns, each reading earlier entries only, run once per state.

use crate::error::Error;
use crate::number::Count;

/// Functions of one argument the tape applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sqrt,
    Exp,
    Ln,
    Abs,
    Signum,
    Floor,
}

impl Func {
    pub(super) const ALL: [(&'static str, Func); 12] = [
        ("sin", Func::Sin),
        ("cos", Func::Cos),
        ("tan", Func::Tan),
        ("asin", Func::Asin),
        ("acos", Func::Acos),
        ("atan", Func::Atan),
        ("sqrt", Func::Sqrt),
        ("exp", Func::Exp),
        ("ln", Func::Ln),
        ("abs", Func::Abs),
        ("signum", Func::Signum),
        ("floor", Func::Floor),
    ];

    fn eval(self, v: f64) -> f64 {
        match self {
            Func::Sin => v.sin(),
            Func::Cos => v.cos(),
            Func::Tan => v.tan(),
            Func::Asin => v.asin(),
            Func::Acos => v.acos(),
            Func::Atan => v.atan(),
            Func::Sqrt => v.sqrt(),
            Func::Exp => v.exp(),
            Func::Ln => v.ln(),
            Func::Abs => v.abs(),
            Func::Floor => v.floor(),
            // The sign as the macro's graph defines it: 0 at 0.
            Func::Signum => crate::number::sign(v),
        }
    }
}

/// One entry of the tape; operands are indices of earlier entries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum TapeOp {
    Const(f64),
    Param(usize),
    Input(usize),
    Unknown(usize),
    Add(usize, usize),
    Sub(usize, usize),
    Mul(usize, usize),
    Div(usize, usize),
    Neg(usize),
    Powi(usize, i32),
    Powf(usize, usize),
    Atan2(usize, usize),
    /// `x` when `a <= b`, `y` when `b < a`, NaN otherwise (`min`, `max`, `clamp`).
    Select(usize, usize, usize, usize),
    Func(Func, usize),
}

/// The joints' coordinates and the segments' angles at one state.
#[derive(Clone, Debug, PartialEq)]
pub struct Values {
    /// Each joint's `[x, y]`, in the order of `Description::joints`.
    pub joints: Vec<[f64; 2]>,
    /// Each segment's angle (radians) where it has one (links and sliders), in the order of
    /// `Description::segments`.
    pub angles: Vec<Option<f64>>,
}

/// Every entry of `tape` at `(params, x, q)`. Operand indices were checked when the tape was
/// read; the leaves are checked here against the slices given.
pub(super) fn run(tape: &[TapeOp], params: &[f64], x: &[f64], q: &[f64]) -> Result<Vec<f64>, Error> {
    let leaf = |slice: &[f64], i: usize, what: &str| {
        slice.get(i).copied().ok_or_else(|| {
            Error::InvalidArgument(format!(
                "the drawing reads {what} {i}, but {} given",
                Count(slice.len(), &format!("{what} value"))
            ))
        })
    };
    let mut v: Vec<f64> = Vec::with_capacity(tape.len());
    for op in tape {
        let value = match *op {
            TapeOp::Const(c) => c,
            TapeOp::Param(i) => leaf(params, i, "parameter")?,
            TapeOp::Input(i) => leaf(x, i, "input")?,
            TapeOp::Unknown(i) => leaf(q, i, "unknown")?,
            TapeOp::Add(a, b) => v[a] + v[b],
            TapeOp::Sub(a, b) => v[a] - v[b],
            TapeOp::Mul(a, b) => v[a] * v[b],
            TapeOp::Div(a, b) => v[a] / v[b],
            TapeOp::Neg(a) => -v[a],
            TapeOp::Powi(a, n) => v[a].powi(n),
            TapeOp::Powf(a, b) => v[a].powf(v[b]),
            TapeOp::Atan2(a, b) => v[a].atan2(v[b]),
            TapeOp::Select(a, b, x, y) => {
                if v[a] <= v[b] {
                    v[x]
                } else if v[b] < v[a] {
                    v[y]
                } else {
                    f64::NAN
                }
            }
            TapeOp::Func(f, a) => f.eval(v[a]),
        };
        v.push(value);
    }
    Ok(v)
}
