//! The kind of quantity of every input, unknown and output column (angle, length,
//! dimensionless, or not inferred), from which the runtime writes units into CSV headers.
//!
//! **Leaves** (parameters, inputs, unknowns) are classified top-down from places whose kind is
//! certain: the argument of a sine, cosine or tangent is an angle; a loop projection and a
//! point coordinate are lengths. The expected kind passes through sums, differences, negation
//! and `abs`, and through a product or quotient only onto a factor whose partner is a pure
//! number (a constant, a sine, ...): in `l @ th` the length `l` multiplies `cos(th)`, in
//! `2 phi` the angle `phi` a constant, but in `sin(k t)` neither `k` nor `t` is known to be an
//! angle. A leaf reached as two different kinds is not classified.
//!
//! A parameter or unknown whose value is written in degrees (`params phi0 = deg(30);`) is an
//! angle too, and so is whatever of no dimension yet is added to, subtracted from or compared
//! with an angle: in a cam law `clamp((wrap(phi, 2 pi) - phi0) / rise, 0, 1)` the input `phi`
//! is an angle because `phi0` is, though it never meets a sine. Such sums are looked at once
//! the kinds above are known (by the dimensions below), and again after whatever they
//! classify, until nothing changes.
//!
//! **Scalar outputs** get the kind of their expression, computed bottom-up with lengths
//! carrying a power (`L^k`): `atan2` of two lengths is an angle, a difference of lengths a
//! length, a ratio of lengths dimensionless, `sqrt` of a sum of squares of lengths a length.
//! Whatever does not follow from the classified leaves is [`Kind::Other`]: nothing is guessed.

use crate::graph::dag::{Func, Graph, Leaf, NodeId, Op};
use crate::graph::dims::{Dim, dimensions};
use crate::semantics::model::{Model, Named};
use std::collections::{HashMap, HashSet};

/// The kind of quantity of a column.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    Angle,
    Length,
    Dimensionless,
    Other,
}

/// The kinds of a mechanism's columns, in declaration order.
pub struct Kinds {
    pub inputs: Vec<Kind>,
    pub unknowns: Vec<Kind>,
    /// Per flat output column: `x`, `y` per point, then the scalars.
    pub outputs: Vec<Kind>,
    /// Per parameter: an angle parameter's value bounds where its sums with other angles are
    /// resolved (see the runtime's `largest_precise_angle`).
    pub params: Vec<Kind>,
}

/// Classifies the columns of `model`, whose expressions are nodes of `g`.
pub fn classify(model: &Model, g: &Graph, residuals: &[NodeId], outputs: &[NodeId]) -> Kinds {
    let leaves = leaf_kinds(model, g, residuals, outputs);
    let of = |l: Leaf| leaves.get(&l).copied().flatten().unwrap_or(Kind::Other);
    let inputs = (0..model.inputs.len()).map(|i| of(Leaf::Input(i as u16))).collect();
    let unknowns = (0..model.unknowns.len()).map(|u| of(Leaf::Unknown(u as u16))).collect();
    let params = (0..model.params.len()).map(|k| of(Leaf::Param(k as u16))).collect();
    let n_point_columns = 2 * model.points.len();
    let scalars = &outputs[n_point_columns.min(outputs.len())..];
    let dims = dimensions(g, scalars, &|l| dim(of(l)));
    let mut out = vec![Kind::Length; n_point_columns];
    out.extend(scalars.iter().map(|s| kind(dims[s])));
    Kinds { inputs, unknowns, outputs: out, params }
}

/// The power of length of every equation's terms, its unit (`Some(0)`: no unit, an equation
/// between angles; `None`: not inferred from the classified leaves), by the dimensions of its
/// residual: a loop's projections are lengths (`Some(1)`), a gear's `th3 == 2 gamma` is of no
/// unit.
pub fn row_powers(model: &Model, g: &Graph, residuals: &[NodeId], outputs: &[NodeId]) -> Vec<Option<i32>> {
    let leaves = leaf_kinds(model, g, residuals, outputs);
    let of = |l: Leaf| leaves.get(&l).copied().flatten().unwrap_or(Kind::Other);
    let dims = dimensions(g, residuals, &|l| dim(of(l)));
    residuals.iter().map(|r| dims[r].power()).collect()
}

/// The kind of every classified leaf (`None`: reached as two different kinds).
fn leaf_kinds(model: &Model, g: &Graph, residuals: &[NodeId], outputs: &[NodeId]) -> HashMap<Leaf, Option<Kind>> {
    let roots: Vec<NodeId> = residuals.iter().chain(outputs).copied().collect();
    let mut start: Vec<(NodeId, Kind)> = Vec::new();
    for n in g.reachable(&roots) {
        if let Op::Func(Func::Sin | Func::Cos | Func::Tan, a) = g.op(n) {
            start.push((a, Kind::Angle));
        }
    }
    let loops = model.equations.iter().zip(residuals).filter(|(e, _)| e.is_loop);
    start.extend(loops.map(|(_, &r)| (r, Kind::Length)));
    start.extend(outputs.iter().take(2 * model.points.len()).map(|&p| (p, Kind::Length)));
    let mut kinds: HashMap<Leaf, Option<Kind>> = HashMap::new();
    let degrees = |list: &[Named]| {
        list.iter().enumerate().filter(|(_, n)| n.in_degrees).map(|(i, _)| i as u16).collect::<Vec<_>>()
    };
    for leaf in degrees(&model.params)
        .into_iter()
        .map(Leaf::Param)
        .chain(degrees(&model.unknowns).into_iter().map(Leaf::Unknown))
    {
        kinds.insert(leaf, Some(Kind::Angle));
    }
    let mut seen: HashSet<(NodeId, Kind)> = HashSet::new();
    let mut stack = start;
    // The certain places first, where a leaf reached as two kinds is not classified; then the
    // sums, which only classify leaves nothing has classified (an inconsistent declaration,
    // an angle plus a difference of lengths, leaves the lengths as they are).
    let mut certain = true;
    loop {
        descend(g, &mut stack, &mut seen, &mut kinds, certain);
        certain = false;
        // The terms of a sum (and the compared arguments of a select) are of one kind: an angle
        // beside a term of no dimension yet passes down into it. A term with a dimension of its
        // own keeps it (`y + phi` with `y` a length: the sum is nothing kinloop names, and `y`
        // stays a length).
        let of = |l: Leaf| kinds.get(&l).copied().flatten().unwrap_or(Kind::Other);
        let dims = dimensions(g, &roots, &|l| dim(of(l)));
        for n in g.reachable(&roots) {
            let pair = match g.op(n) {
                Op::Add(a, b) | Op::Sub(a, b) | Op::Select(a, b, _, _) => [a, b],
                _ => continue,
            };
            for (this, other) in [(pair[0], pair[1]), (pair[1], pair[0])] {
                if dims[&this] == Dim::Angle && dims[&other] == Dim::Other && !seen.contains(&(other, Kind::Angle)) {
                    stack.push((other, Kind::Angle));
                }
            }
        }
        if stack.is_empty() {
            return kinds;
        }
    }
}

/// Passes the kinds on `stack` down through the graph (see the module documentation), noting
/// each leaf reached in `kinds`: where the kinds are `certain`, `None` once reached as two
/// kinds; otherwise only a leaf not reached before.
fn descend(
    g: &Graph,
    stack: &mut Vec<(NodeId, Kind)>,
    seen: &mut HashSet<(NodeId, Kind)>,
    kinds: &mut HashMap<Leaf, Option<Kind>>,
    certain: bool,
) {
    while let Some((n, kind)) = stack.pop() {
        if !seen.insert((n, kind)) {
            continue;
        }
        match g.op(n) {
            Op::Leaf(l @ (Leaf::Param(_) | Leaf::Input(_) | Leaf::Unknown(_))) => {
                let entry = kinds.entry(l).or_insert(Some(kind));
                if certain && *entry != Some(kind) {
                    *entry = None;
                }
            }
            Op::Add(a, b) | Op::Sub(a, b) => stack.extend([(a, kind), (b, kind)]),
            // `floor` as `abs`: of an angle (a count of turns, times a period) the argument is
            // of the result's kind.
            Op::Neg(a) | Op::Func(Func::Abs | Func::Floor, a) => stack.push((a, kind)),
            // `min`, `max`, `clamp`: the result is one of the compared arguments (as a sum's
            // terms, all of one kind). A select whose comparison is of other nodes (a
            // derivative's) passes the kind to its chosen operands only.
            Op::Select(a, b, x, y) => {
                stack.extend([(x, kind), (y, kind)]);
                if [a, b] == [x, y] || [b, a] == [x, y] {
                    stack.extend([(a, kind), (b, kind)]);
                }
            }
            Op::Mul(a, b) if pure_number(g, a, 8) => stack.push((b, kind)),
            Op::Mul(a, b) | Op::Div(a, b) if pure_number(g, b, 8) => stack.push((a, kind)),
            _ => {}
        }
    }
}

/// Whether `n` is a pure number: a constant, a sine, cosine or tangent, or products, quotients,
/// powers and floors of those (looked at to `depth` levels).
pub(crate) fn pure_number(g: &Graph, n: NodeId, depth: u32) -> bool {
    if depth == 0 {
        return false;
    }
    match g.op(n) {
        Op::Const(_) | Op::Func(Func::Sin | Func::Cos | Func::Tan | Func::Signum, _) => true,
        Op::Neg(a) | Op::Powi(a, _) | Op::Func(Func::Floor, a) => pure_number(g, a, depth - 1),
        Op::Mul(a, b) | Op::Div(a, b) => pure_number(g, a, depth - 1) && pure_number(g, b, depth - 1),
        _ => false,
    }
}

/// The kind of an expression of dimension `d`.
fn kind(d: Dim) -> Kind {
    match d {
        Dim::Angle => Kind::Angle,
        Dim::L(1) => Kind::Length,
        Dim::Num | Dim::L(0) => Kind::Dimensionless,
        _ => Kind::Other,
    }
}

/// The dimension of a leaf of kind `k`.
fn dim(k: Kind) -> Dim {
    match k {
        Kind::Angle => Dim::Angle,
        Kind::Length => Dim::L(1),
        Kind::Dimensionless => Dim::L(0),
        Kind::Other => Dim::Other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kinds of the inputs and unknowns of a declaration.
    fn kinds_of(src: &str) -> (Vec<Kind>, Vec<Kind>) {
        let p = crate::plan_declaration(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}"));
        let k = classify(&p.model, &p.plan.graph, &p.plan.residuals, &p.plan.outputs);
        (k.inputs, k.unknowns)
    }

    /// A cam's law compares the input with a start and divides by a rise written in degrees:
    /// the input is an angle by them, however the degrees are scaled (`2 * deg(15)` is 30
    /// degrees as much as `deg(30)` is), and so is an unknown whose guess is scaled degrees.
    /// A multiple of degrees by a name is of no certain kind, and infers nothing.
    #[test]
    fn degrees_scaled_by_a_number_are_angles_as_degrees_are() {
        for (start, rise, guess) in [
            ("deg(30)", "deg(120)", "deg(10)"),
            ("2 * deg(15)", "deg(60) * 2", "deg(20) / 2"),
            ("-(deg(5) - deg(35))", "deg(90) + pi / 6", "0.5 * deg(20)"),
        ] {
            let src = format!(
                "pub struct Cam {{ params h = 0.02, phi0 = {start}, rise = {rise}; input phi;
                 unknowns s, w = {guess};
                 let u = clamp((phi - phi0) / rise, 0, 1);
                 eq lift: s == h * u ^ 2;
                 eq lag: w == phi0 * u; }}"
            );
            assert_eq!(kinds_of(&src), (vec![Kind::Angle], vec![Kind::Other, Kind::Angle]), "{start}, {rise}, {guess}");
        }
        let src = "pub struct Cam { params h = 0.02, k = 2, rise = k * deg(60); input phi; unknowns s;
                   eq lift: s == h * clamp(phi / rise, 0, 1); }";
        // `k * deg(60)` is no constant: refused as a default before any kind is inferred.
        assert!(crate::plan_declaration(src.parse().expect("tokens")).is_err());
        let src = "pub struct Cam { params h = 0.02, k = 2; input phi; unknowns s, w = k * deg(10);
                   eq lift: s == h * phi; eq lag: w == k * s; }";
        assert_eq!(kinds_of(src).1[1], Kind::Other);
    }

    /// A parameter added to an unknown inside a polar vector (`bf @ (th2 + alpha_b)`) is an
    /// angle, the lengths beside it lengths: the parameters whose size the runtime bounds.
    #[test]
    fn a_parameter_turning_a_link_is_an_angle() {
        let src = "pub struct ClassFour { params oa = 1, ac = 2.3, bd = 1.6, bf = 3.5, alpha_b = 0.3, cd = 2, ef = 3.4;
                   input phi; unknowns th1 = 1.4, th2 = 3, psi1 = -0.8, psi2 = -1;
                   loop a: oa @ phi + ac @ th1 + cd @ psi1 == (4.4, 0.6) + bd @ th2;
                   loop b: oa @ phi + ac @ th1 + ef @ psi2 == (4.4, 0.6) + bf @ (th2 + alpha_b); }";
        let p = crate::plan_declaration(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}"));
        let k = classify(&p.model, &p.plan.graph, &p.plan.residuals, &p.plan.outputs);
        use Kind::{Angle, Length};
        assert_eq!(k.params, [Length, Length, Length, Length, Angle, Length, Length]);
    }
}
