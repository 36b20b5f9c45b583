//! The dimension of an expression, bottom-up from the dimensions of its leaves: a number, an
//! angle, a power of length (`L^k`), or unknown. `atan2` of two lengths is an angle, a
//! difference of lengths a length, a ratio of lengths a number of no unit, `sqrt` of a sum of
//! squares of lengths a length; an angle is a number in a product (an angle times a length is
//! an arc length). Whatever does not follow from the leaves is [`Dim::Other`]: nothing is
//! guessed. The plan names the kinds of its columns by it, and the semantics judges by it
//! whether a coordinate of a position is an angle.

use super::dag::{Func, Graph, Leaf, NodeId, Op};
use std::collections::HashMap;

/// The dimension of an expression: a number, an angle, a power of length, or unknown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dim {
    /// A number (a constant, or of no unit as a sine is).
    Num,
    /// An angle.
    Angle,
    /// Length to this power (`L(0)`: a ratio of lengths).
    L(i32),
    /// None that follows from the leaves.
    Other,
}

impl Dim {
    /// The power of length in a product (an angle is a pure number there).
    pub fn power(self) -> Option<i32> {
        match self {
            Dim::Num | Dim::Angle => Some(0),
            Dim::L(k) => Some(k),
            Dim::Other => None,
        }
    }

    /// Dimensionless (a number, an angle or `L^0`): a valid argument of `exp`, `asin`, ...
    fn unitless(self) -> bool {
        self.power() == Some(0)
    }
}

/// Whether the expression `n` is an angle, its leaves of the dimensions `leaf` gives: an angle
/// offset by a number or by another angle, a multiple of one by a number, an angle's minimum,
/// an inverse sine, the magnitude of a vector of angles. A leaf of no known dimension
/// (`Dim::Other`) makes nothing an angle.
pub fn is_angle(g: &Graph, n: NodeId, leaf: &dyn Fn(Leaf) -> Dim) -> bool {
    judged(g, &[n], leaf).get(&n) == Some(&Dim::Angle)
}

/// The dimension of every node reachable from `roots`, bottom-up.
pub fn dimensions(g: &Graph, roots: &[NodeId], leaf: &dyn Fn(Leaf) -> Dim) -> HashMap<NodeId, Dim> {
    walk(g, roots, leaf, false)
}

/// As [`dimensions`], and the magnitude of a vector of angles (`norm((phi, psi))`,
/// `hypot(phi, 0.5)`: the square root of a sum of squares of angles and numbers) is an angle
/// too. For what a value written where a length belongs is made of; the kinds the plan names
/// keep such a magnitude unnamed, as a reported value of no unit kinloop writes.
pub fn judged(g: &Graph, roots: &[NodeId], leaf: &dyn Fn(Leaf) -> Dim) -> HashMap<NodeId, Dim> {
    walk(g, roots, leaf, true)
}

/// The dimensions of [`dimensions`], with magnitudes of angles as [`judged`] takes them if
/// `magnitudes`.
fn walk(g: &Graph, roots: &[NodeId], leaf: &dyn Fn(Leaf) -> Dim, magnitudes: bool) -> HashMap<NodeId, Dim> {
    let mut dim: HashMap<NodeId, Dim> = HashMap::new();
    // Ids are a topological order: operands come first.
    for n in g.reachable(roots) {
        let d = |a: NodeId| dim[&a];
        let v = match g.op(n) {
            Op::Func(Func::Sqrt, a) if magnitudes && squares_of_angles(g, a, &dim) => Dim::Angle,
            Op::Const(_) => Dim::Num,
            Op::Leaf(l) => leaf(l),
            Op::Add(a, b) | Op::Sub(a, b) => sum(d(a), d(b)),
            Op::Neg(a) | Op::Func(Func::Abs | Func::Floor, a) => d(a),
            Op::Mul(a, b) => product(d(a), d(b), 1),
            Op::Div(a, b) => product(d(a), d(b), -1),
            Op::Powi(a, k) => match d(a) {
                Dim::Num => Dim::Num,
                Dim::Angle if k == 1 => Dim::Angle,
                Dim::L(p) => p.checked_mul(k).map_or(Dim::Other, Dim::L),
                _ => Dim::Other,
            },
            Op::Func(Func::Sqrt, a) => match d(a) {
                Dim::Num => Dim::Num,
                Dim::L(p) if p % 2 == 0 => Dim::L(p / 2),
                _ => Dim::Other,
            },
            Op::Func(Func::Signum, _) => Dim::Num,
            Op::Func(Func::Asin | Func::Acos | Func::Atan, a) if d(a).unitless() => Dim::Angle,
            Op::Func(_, a) if d(a).unitless() => Dim::L(0),
            Op::Atan2(y, x) if sum(d(y), d(x)) != Dim::Other => Dim::Angle,
            // As a sum: the compared arguments of one kind (an angle against a length is not
            // inferred), and the result the kind of the chosen operands.
            Op::Select(a, b, x, y) if sum(d(a), d(b)) != Dim::Other => sum(d(x), d(y)),
            _ => Dim::Other,
        };
        dim.insert(n, v);
    }
    dim
}

/// More terms than the sum under a magnitude of angles is read through.
const MAX_SQUARES: usize = 32;

/// Whether `n` is a sum of squares of angles and numbers with at least one angle (what
/// `norm` and `hypot` of angles take the square root of), the dimensions of its operands in
/// `dim`.
/// A magnitude has a few terms: beyond [`MAX_SQUARES`] (a sum that shares its terms would be
/// walked once per path) it is not read as one.
fn squares_of_angles(g: &Graph, n: NodeId, dim: &HashMap<NodeId, Dim>) -> bool {
    let (mut stack, mut angles, mut seen) = (vec![n], 0, 0);
    while let Some(t) = stack.pop() {
        seen += 1;
        if seen > MAX_SQUARES {
            return false;
        }
        match g.op(t) {
            Op::Add(a, b) => stack.extend([a, b]),
            Op::Const(_) if g.as_const(t).is_some_and(|c| c >= 0.0) => {}
            Op::Powi(a, 2) if dim.get(&a) == Some(&Dim::Angle) => angles += 1,
            Op::Powi(a, 2) if dim.get(&a) == Some(&Dim::Num) => {}
            _ => return false,
        }
    }
    angles > 0
}

/// The dimension of a sum: both terms alike (a number adopts the other's).
fn sum(a: Dim, b: Dim) -> Dim {
    match (a, b) {
        (Dim::Num, x) | (x, Dim::Num) => x,
        (x, y) if x == y => x,
        _ => Dim::Other,
    }
}

/// The dimension of `a * b^sign` (`sign` = 1 or -1).
fn product(a: Dim, b: Dim, sign: i32) -> Dim {
    match (a, b) {
        (x, Dim::Num) => x,
        (Dim::Num, Dim::Angle) if sign == 1 => Dim::Angle,
        // Per radian, a squared angle, an angle times a ratio: no unit kinloop writes (an angle
        // times a length is an arc length).
        (_, Dim::Angle) if sign == -1 => Dim::Other,
        (Dim::Angle | Dim::Num | Dim::L(0), Dim::Angle) | (Dim::Angle, Dim::L(0)) => Dim::Other,
        // Checked: a declaration may raise a length to any power.
        _ => match (a.power(), b.power()) {
            (Some(p), Some(q)) => q.checked_mul(sign).and_then(|q| p.checked_add(q)).map_or(Dim::Other, Dim::L),
            _ => Dim::Other,
        },
    }
}
