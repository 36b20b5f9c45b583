//! How an expression depends on one leaf through sums and whole multiples: free of it, a whole
//! multiple of it plus a part free of it (`2 q + gamma`), a function that repeats every turn of
//! it (`cos(q + gamma)`), or anything else.
//!
//! The planner asks which unknowns' equations repeat every turn (`plan::turns`); the semantics
//! asks which unknowns and inputs are angles (the unit check, a body's `turns`, a torque's
//! `on`): a leaf that enters a sine or cosine as a whole multiple of itself (`l @ q`), not one
//! scaled into it (a rack's travel `sin(x / rp)`). One classification serves both.

use super::dag::{Func, Graph, Leaf, NodeId, Op};
use std::collections::{HashMap, HashSet};

/// How a node depends on the leaf being classified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Class {
    /// Not at all.
    Free,
    /// `k q` plus a part free of `q`, for an integer `k`.
    Multiple(i64),
    /// `c q` plus a part free of `q`, for a constant `c` that is not a whole number (a half
    /// angle `q / 2`): an angle's argument, which does not repeat every turn of it.
    Fraction,
    /// Unchanged when `q` moves by a whole turn.
    Periodic,
    /// Otherwise.
    Other,
}

use Class::{Fraction, Free, Multiple, Other, Periodic};

/// The arguments of the sines, cosines and tangents below `roots`, for [`in_whole_angle`]:
/// found once, and each leaf then classified over them alone, not over the whole graph.
pub fn trig_arguments(g: &Graph, roots: &[NodeId]) -> Vec<NodeId> {
    trig_arguments_avoiding(g, roots, &[])
}

/// The arguments of the sines, cosines and tangents below `roots` that are reached without
/// passing through a node of `avoided`: what the rest of a mechanism says of a leaf, one term
/// of it set aside (the two products of a polar term, whose own angle is in question).
pub fn trig_arguments_avoiding(g: &Graph, roots: &[NodeId], avoided: &[NodeId]) -> Vec<NodeId> {
    let mut out: Vec<NodeId> = g
        .reachable_avoiding(roots, avoided)
        .into_iter()
        .filter_map(|n| match g.op(n) {
            Op::Func(Func::Sin | Func::Cos | Func::Tan, a) => Some(a),
            _ => None,
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Whether `q` enters one of `arguments` (of sines, cosines and tangents: [`trig_arguments`])
/// as a multiple of itself by a constant plus a part free of it (`q`, `q + gamma`, `-q`, `2 q`,
/// a half angle `q / 2`): as an angle enters a loop (`l @ q`). A length enters an argument
/// scaled by a length (`sin(x / l)`), never so; nor does a leaf scaled by a parameter (`k q`, as
/// the planner's units take it: the change that turns the argument by a radian is `1 / |k|`).
pub fn in_whole_angle(g: &Graph, q: Leaf, arguments: &[NodeId]) -> bool {
    let class = classify(g, q, arguments);
    arguments.iter().any(|a| matches!(class.get(a), Some(Multiple(k)) if *k != 0) || class.get(a) == Some(&Fraction))
}

/// Whether `q` enters one of `arguments` as a whole multiple of itself (`q`, `q + gamma`, `-q`,
/// `2 q`), not only as a fraction (`q / 2`, `1.5 q`): a fraction's divisor may be a length
/// written as a number (`sin(x / 2)` for a rack of radius 2), so only a whole multiple makes
/// `q` an angle against a place that writes it as a length.
pub fn in_whole_multiple(g: &Graph, q: Leaf, arguments: &[NodeId]) -> bool {
    let class = classify(g, q, arguments);
    arguments.iter().any(|a| matches!(class.get(a), Some(Multiple(k)) if *k != 0))
}

/// The class of every node below `roots` with respect to leaf `q`.
pub fn classify(g: &Graph, q: Leaf, roots: &[NodeId]) -> HashMap<NodeId, Class> {
    let mut seen: HashSet<NodeId> = HashSet::new();
    let mut stack = roots.to_vec();
    let mut order = Vec::new();
    while let Some(n) = stack.pop() {
        if seen.insert(n) {
            order.push(n);
            stack.extend(g.op(n).operands());
        }
    }
    // Operands are made before the nodes that use them: ascending ids are a topological order.
    order.sort_unstable();
    let mut class = HashMap::with_capacity(order.len());
    for n in order {
        // Every operand was classified before (a lower id); were one not, it would count as
        // anything, never as a panic of the macro.
        let of = |m: NodeId| class.get(&m).copied().unwrap_or(Other);
        let c = match g.op(n) {
            Op::Leaf(l) if l == q => Multiple(1),
            Op::Const(_) | Op::Leaf(_) => Free,
            Op::Add(a, b) => sum(of(a), of(b), 1),
            Op::Sub(a, b) => sum(of(a), of(b), -1),
            Op::Neg(a) => scaled(of(a), -1),
            Op::Mul(a, b) => match (of(a), of(b), whole(g, a), whole(g, b)) {
                (_, Multiple(k), Some(m), _) | (Multiple(k), _, _, Some(m)) => scaled(Multiple(k), m),
                (_, Multiple(_) | Fraction, ..) if factor(g, a) => Fraction,
                (Multiple(_) | Fraction, ..) if factor(g, b) => Fraction,
                (x, y, ..) => combined(x, y),
            },
            Op::Div(a, b) if matches!(of(a), Multiple(_) | Fraction) && factor(g, b) => Fraction,
            Op::Div(a, b) | Op::Powf(a, b) | Op::Atan2(a, b) => combined(of(a), of(b)),
            Op::Select(a, b, x, y) => combined(combined(of(a), of(b)), combined(of(x), of(y))),
            Op::Powi(a, _) => combined(of(a), Free),
            Op::Func(Func::Sin | Func::Cos | Func::Tan, a) if matches!(of(a), Multiple(_)) => Periodic,
            Op::Func(_, a) => combined(of(a), Free),
        };
        class.insert(n, c);
    }
    class
}

/// The value of `n` when it is a constant whole number (small enough for any multiple of an
/// unknown's coefficient to stay exact).
fn whole(g: &Graph, n: NodeId) -> Option<i64> {
    g.as_const(n).filter(|v| v.fract() == 0.0 && v.abs() <= 1e6).map(|v| v as i64)
}

/// Whether `n` is a constant that scales a multiple into a [`Fraction`]: finite and not zero.
fn factor(g: &Graph, n: NodeId) -> bool {
    g.as_const(n).is_some_and(|v| v.is_finite() && v != 0.0)
}

/// `a + sign b` (`sign` is 1 or -1).
fn sum(a: Class, b: Class, sign: i64) -> Class {
    match (a, b) {
        (Free, Free) => Free,
        (Fraction, Free | Multiple(_) | Fraction) | (Free | Multiple(_), Fraction) => Fraction,
        (Multiple(k), Free) => Multiple(k),
        (Free, Multiple(k)) => scaled(Multiple(k), sign),
        (Multiple(j), Multiple(k)) => sign.checked_mul(k).and_then(|k| j.checked_add(k)).map_or(Other, Multiple),
        (x, y) => combined(x, y),
    }
}

/// `m a` for a whole number `m` (a coefficient too large for an integer is anything: no
/// declaration writes one, and the macro must not overflow on one that does).
fn scaled(a: Class, m: i64) -> Class {
    match a {
        Multiple(k) => k.checked_mul(m).map_or(Other, Multiple),
        Fraction if m != 0 => Fraction,
        other => other,
    }
}

/// An operation of `a` and `b` other than a sum or a whole multiple: free if both are,
/// repeating if both do, otherwise anything (`q` itself, not inside a sine, breaks the period).
fn combined(a: Class, b: Class) -> Class {
    match (a, b) {
        (Free, Free) => Free,
        (Free | Periodic, Free | Periodic) => Periodic,
        _ => Other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The class of `root` with respect to unknown 0 of a fresh graph built by `build`.
    fn class_of(build: impl FnOnce(&mut Graph, NodeId, NodeId) -> NodeId) -> Class {
        let mut g = Graph::new();
        let q = g.leaf(Leaf::Unknown(0));
        let p = g.leaf(Leaf::Param(0));
        let root = build(&mut g, q, p);
        classify(&g, Leaf::Unknown(0), &[root])[&root]
    }

    /// Whether unknown 0 enters an argument of `root` whole, in a fresh graph built by `build`.
    fn whole_angle(build: impl FnOnce(&mut Graph, NodeId, NodeId) -> NodeId) -> bool {
        let mut g = Graph::new();
        let q = g.leaf(Leaf::Unknown(0));
        let p = g.leaf(Leaf::Param(0));
        let root = build(&mut g, q, p);
        in_whole_angle(&g, Leaf::Unknown(0), &trig_arguments(&g, &[root]))
    }

    #[test]
    fn an_angle_enters_an_argument_whole() {
        // p cos(q + p) - q: a link at an angle, the angle also outside.
        assert!(whole_angle(|g, q, p| {
            let a = g.add(q, p);
            let cos = g.func(Func::Cos, a);
            let l = g.mul(p, cos);
            g.sub(l, q)
        }));
        // sin(-2 q).
        assert!(whole_angle(|g, q, _| {
            let two = g.constant(-2.0);
            let a = g.mul(two, q);
            g.func(Func::Sin, a)
        }));
        // q + 0.01 sin(q / p): a length scaled into a sine, and beside it.
        assert!(!whole_angle(|g, q, p| {
            let a = g.div(q, p);
            let s = g.func(Func::Sin, a);
            let k = g.constant(0.01);
            let t = g.mul(k, s);
            g.add(q, t)
        }));
        // A half angle, cos(q / 2 + p), and 1.5 q.
        assert!(whole_angle(|g, q, p| {
            let two = g.constant(2.0);
            let h = g.div(q, two);
            let a = g.add(h, p);
            g.func(Func::Cos, a)
        }));
        assert!(whole_angle(|g, q, _| {
            let k = g.constant(1.5);
            let a = g.mul(q, k);
            g.func(Func::Sin, a)
        }));
        // cos(p q), and q in the argument of no sine at all.
        assert!(!whole_angle(|g, q, p| {
            let a = g.mul(p, q);
            g.func(Func::Cos, a)
        }));
        assert!(!whole_angle(|g, q, p| g.mul(p, q)));
    }

    #[test]
    fn sines_of_whole_multiples_repeat() {
        // l cos(q + p): a link at an angle plus an offset.
        let link = class_of(|g, q, p| {
            let a = g.add(q, p);
            let cos = g.func(Func::Cos, a);
            g.mul(p, cos)
        });
        assert_eq!(link, Periodic);
        // sin(2 q - p) + p: a whole multiple.
        let double = class_of(|g, q, p| {
            let two = g.constant(2.0);
            let a = g.mul(two, q);
            let b = g.sub(a, p);
            let s = g.func(Func::Sin, b);
            g.add(s, p)
        });
        assert_eq!(double, Periodic);
        // sqrt(1 + sin(q)^2): a function of a repeating value repeats.
        let root = class_of(|g, q, _| {
            let s = g.func(Func::Sin, q);
            let s2 = g.powi(s, 2);
            let one = g.constant(1.0);
            let a = g.add(one, s2);
            g.func(Func::Sqrt, a)
        });
        assert_eq!(root, Periodic);
        assert_eq!(class_of(|g, _, p| g.func(Func::Cos, p)), Free);
    }

    #[test]
    fn other_uses_of_the_angle_do_not_repeat() {
        // r q: a rolling contact.
        assert_eq!(class_of(|g, q, p| g.mul(p, q)), Other);
        // cos(q / 2): a half angle repeats every two turns only.
        let half = class_of(|g, q, _| {
            let two = g.constant(2.0);
            let a = g.div(q, two);
            g.func(Func::Cos, a)
        });
        assert_eq!(half, Other);
        // cos(1.5 q): not a whole multiple.
        let ratio = class_of(|g, q, _| {
            let k = g.constant(1.5);
            let a = g.mul(k, q);
            g.func(Func::Cos, a)
        });
        assert_eq!(ratio, Other);
        // cos(q) + q: the angle itself beside its cosine.
        let beside = class_of(|g, q, _| {
            let cos = g.func(Func::Cos, q);
            g.add(cos, q)
        });
        assert_eq!(beside, Other);
        // atan(q): not inside a sine or cosine.
        assert_eq!(class_of(|g, q, _| g.func(Func::Atan, q)), Other);
        // A coefficient beyond any integer (doubled 70 times): anything, not an overflow.
        let huge = class_of(|g, q, p| {
            let mut a = q;
            for _ in 0..70 {
                // `+ p - p` keeps the graph from folding the doublings into one constant.
                let b = g.add(a, p);
                let c = g.sub(a, p);
                a = g.add(b, c);
            }
            g.func(Func::Cos, a)
        });
        assert_eq!(huge, Other);
    }
}
