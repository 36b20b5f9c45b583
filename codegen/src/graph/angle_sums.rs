//! Sines and cosines of a sum of angles `a + b` whose part `b` is fixed (parameters and
//! constants: `phi1 + gamma`, `phi + deg(30)`) and whose part `a` varies with the inputs alone,
//! where the graph also has `a`'s own sine and cosine (as a loop with two crank arms at a fixed
//! angle has: `r_p @ phi1`, `r_b @ (phi1 + gamma)`).
//!
//! Such a value is computed by angle addition from `a`'s sine and cosine and `b`'s
//! (`kinloop::__gen::add_angles`), not by libm from the rounded sum: four products instead of
//! a call, since `b`'s values do not change while the inputs move (a caller's loop computes them
//! once, a sweep's cache keeps them, the run-time model computes them with the parameters' other
//! values), and closer to the exact sum's values (the sum's rounding moves libm's argument by up
//! to half an ulp of it). [`provide`] adds `b`'s sine and cosine to the graph; the emitted code
//! and the run-time model both ask this module which nodes are so computed, and from what
//! ([`sources`]), so that they compute the same values to the bit.

use super::dag::{Func, Graph, Leaf, NodeId, Op};

/// A sine or cosine computed by angle addition (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AngleSum {
    /// The sum's part that varies with the inputs.
    pub a: NodeId,
    /// The fixed part (parameters and constants).
    pub b: NodeId,
    /// `sin a`.
    pub sin_a: NodeId,
    /// `cos a`.
    pub cos_a: NodeId,
    /// `sin b` (a constant where `b` is one).
    pub sin_b: NodeId,
    /// `cos b`.
    pub cos_b: NodeId,
    /// Whether the node is the sum's sine (otherwise its cosine).
    pub sine: bool,
}

/// The angle addition that computes `n`, if `n` is the sine or cosine of such a sum (after
/// [`provide`]).
pub fn angle_sum(g: &Graph, n: NodeId) -> Option<AngleSum> {
    let (sine, (a, b)) = parts(g, n)?;
    let sin_a = g.find(Op::Func(Func::Sin, a))?;
    let cos_a = g.find(Op::Func(Func::Cos, a))?;
    let sin_b = of(g, Func::Sin, b)?;
    let cos_b = of(g, Func::Cos, b)?;
    Some(AngleSum { a, b, sin_a, cos_a, sin_b, cos_b, sine })
}

/// Adds the sine and cosine of the fixed part `b` of every sum whose varying part `a` has its
/// own sine and cosine in the graph, so that [`angle_sum`] finds them: nodes of the parameters
/// alone (constants where `b` is one).
pub fn provide(g: &mut Graph) {
    let nodes = g.len();
    for k in 0..nodes {
        let Some((_, (a, b))) = parts(g, NodeId(k as u32)) else { continue };
        if g.find(Op::Func(Func::Sin, a)).is_some() && g.find(Op::Func(Func::Cos, a)).is_some() {
            g.func(Func::Sin, b);
            g.func(Func::Cos, b);
        }
    }
}

/// `f(b)`'s node: a constant's folded value, or the function's node.
fn of(g: &Graph, f: Func, b: NodeId) -> Option<NodeId> {
    match g.as_const(b) {
        Some(x) => g.find(Op::Const(f.eval(x).to_bits())),
        None => g.find(Op::Func(f, b)),
    }
}

/// Whether `n` is a sine (`true`) or cosine of a sum `a + b` with `a` varying with the inputs
/// and `b` fixed, and its parts `(a, b)`.
fn parts(g: &Graph, n: NodeId) -> Option<(bool, (NodeId, NodeId))> {
    let (sine, arg) = match g.op(n) {
        Op::Func(Func::Sin, arg) => (true, arg),
        Op::Func(Func::Cos, arg) => (false, arg),
        _ => return None,
    };
    let Op::Add(x, y) = g.op(arg) else { return None };
    let leaves = |m: NodeId| g.leaves_of(&[m]);
    let fixed = |l: &[Leaf]| l.iter().all(|l| matches!(l, Leaf::Param(_)));
    // Inputs and parameters only, at least one input: free of the unknowns and their analogs.
    let varies = |l: &[Leaf]| {
        l.iter().all(|l| matches!(l, Leaf::Param(_) | Leaf::Input(_))) && l.iter().any(|l| matches!(l, Leaf::Input(_)))
    };
    let (lx, ly) = (leaves(x), leaves(y));
    let (a, b) = if varies(&lx) && fixed(&ly) {
        (x, y)
    } else if varies(&ly) && fixed(&lx) {
        (y, x)
    } else {
        return None;
    };
    Some((sine, (a, b)))
}

/// The nodes `n`'s value is computed from: an angle sum's `sin a`, `cos a`, `sin b` and `cos b`
/// (not the sum itself), any other node's operands.
pub fn sources(g: &Graph, n: NodeId) -> Vec<NodeId> {
    match angle_sum(g, n) {
        Some(s) => vec![s.sin_a, s.cos_a, s.sin_b, s.cos_b],
        None => g.op(n).operands().collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crank_arm_at_a_fixed_angle_is_an_angle_sum() {
        let mut g = Graph::new();
        let (phi, gamma, q) = (g.leaf(Leaf::Input(0)), g.leaf(Leaf::Param(0)), g.leaf(Leaf::Unknown(0)));
        let (sin_phi, cos_phi) = (g.func(Func::Sin, phi), g.func(Func::Cos, phi));
        let sum = g.add(gamma, phi);
        let (s, c) = (g.func(Func::Sin, sum), g.func(Func::Cos, sum));
        // Before `provide`, `gamma`'s sine and cosine are missing.
        assert_eq!(angle_sum(&g, s), None);
        provide(&mut g);
        let (sin_gamma, cos_gamma) = (g.func(Func::Sin, gamma), g.func(Func::Cos, gamma));
        let expected = AngleSum {
            a: phi,
            b: gamma,
            sin_a: sin_phi,
            cos_a: cos_phi,
            sin_b: sin_gamma,
            cos_b: cos_gamma,
            sine: true,
        };
        assert_eq!(angle_sum(&g, s), Some(expected));
        assert_eq!(angle_sum(&g, c), Some(AngleSum { sine: false, ..expected }));
        assert_eq!(sources(&g, s), vec![sin_phi, cos_phi, sin_gamma, cos_gamma]);
        // A sum with an unknown in it, or of parameters alone, is libm's.
        let with_q = g.add(q, gamma);
        let sin_q = g.func(Func::Sin, with_q);
        assert_eq!(angle_sum(&g, sin_q), None);
        let fixed = g.add(gamma, gamma);
        let sin_fixed = g.func(Func::Sin, fixed);
        provide(&mut g);
        assert_eq!(angle_sum(&g, sin_q), None);
        assert_eq!(angle_sum(&g, sin_fixed), None);
        assert_eq!(sources(&g, sin_fixed), vec![fixed]);
    }

    #[test]
    fn a_constant_offset_s_sine_and_cosine_are_constants() {
        let mut g = Graph::new();
        let phi = g.leaf(Leaf::Input(0));
        let (sin_phi, cos_phi) = (g.func(Func::Sin, phi), g.func(Func::Cos, phi));
        let offset = g.constant(0.5);
        let sum = g.add(phi, offset);
        let s = g.func(Func::Sin, sum);
        provide(&mut g);
        let sum = angle_sum(&g, s).expect("an angle sum");
        assert_eq!((sum.sin_a, sum.cos_a), (sin_phi, cos_phi));
        assert_eq!((g.as_const(sum.sin_b), g.as_const(sum.cos_b)), (Some(0.5f64.sin()), Some(0.5f64.cos())));
    }

    #[test]
    fn without_the_varying_part_s_own_sine_and_cosine_the_sum_is_libm_s() {
        let mut g = Graph::new();
        let (phi, gamma) = (g.leaf(Leaf::Input(0)), g.leaf(Leaf::Param(0)));
        let sum = g.add(phi, gamma);
        let s = g.func(Func::Sin, sum);
        provide(&mut g);
        assert_eq!(angle_sum(&g, s), None);
        // Its sine alone is not enough either: the addition needs both.
        g.func(Func::Sin, phi);
        provide(&mut g);
        assert_eq!(angle_sum(&g, s), None);
        assert_eq!(g.find(Op::Func(Func::Sin, gamma)), None, "nothing added for it");
    }
}
