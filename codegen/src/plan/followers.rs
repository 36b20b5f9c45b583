//! The unknowns that follow the others: a sweep need not judge them.
//!
//! A sweep accepts a step when the new position lies near its Taylor prediction and its velocity
//! analogs near theirs (the runtime's `Sweep::judge`): that is how it notices a solve that
//! slid onto another branch, jumped, or crossed a kink. Some unknowns cannot do any of that on
//! their own. An unknown *follows* when its block is linear with a constant matrix (a slider's
//! coordinate `x_c` in `... == (x_c, 0) + l @ phi`) and its right-hand side is an entire
//! function of the inputs and of the unknowns solved before it: built of sums, products,
//! non-negative integer powers, sines, cosines, exponentials and divisions by parameters. Its
//! value is then one analytic function of those: it has no second branch, no pole and no kink,
//! so it is continuous and smooth wherever they are, and judging them judges it.
//!
//! Anything else keeps its judgment: a matrix that varies (it may become singular between two
//! samples), and a right-hand side with `abs` (a kink), `atan2` or `angle` (a jump of a turn),
//! `tan`, a division by a varying value (poles), `sqrt`, `asin`, `acos`, `ln` or `powf` (ends
//! of their domains).

use super::block_plan::BlockPlan;
use crate::graph::dag::{Func, Graph, Leaf, Op};

/// Per unknown, whether it follows the others (see the module documentation).
pub fn followers(g: &Graph, blocks: &[BlockPlan], n: usize) -> Vec<bool> {
    let mut out = vec![false; n];
    for bp in blocks.iter().filter(|bp| follows(g, bp)) {
        for &u in &bp.unknowns {
            out[u] = true;
        }
    }
    out
}

/// Whether every unknown of block `bp` follows the others.
fn follows(g: &Graph, bp: &BlockPlan) -> bool {
    let constant_matrix = bp.jac.iter().flatten().all(|&e| g.as_const(e).is_some());
    bp.solve.is_linear() && constant_matrix && g.reachable(&bp.f).into_iter().all(|node| is_entire(g, g.op(node)))
}

/// Whether node operation `op` is an entire function of its operands (divisions only by
/// parameters and constants).
fn is_entire(g: &Graph, op: Op) -> bool {
    match op {
        Op::Const(_) | Op::Add(..) | Op::Sub(..) | Op::Mul(..) | Op::Neg(_) => true,
        Op::Leaf(leaf) => matches!(leaf, Leaf::Param(_) | Leaf::Input(_) | Leaf::Unknown(_)),
        Op::Powi(_, k) => k >= 0,
        Op::Func(f, _) => matches!(f, Func::Sin | Func::Cos | Func::Exp),
        Op::Div(_, d) => g.leaves_of(&[d]).iter().all(|l| matches!(l, Leaf::Param(_))),
        Op::Powf(..) | Op::Atan2(..) | Op::Select(..) => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The followers of a declaration, by unknown name.
    fn followers_of(src: &str) -> Vec<(String, bool)> {
        let a = crate::analyze(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}"));
        let mut model = a.model;
        let plan = crate::plan::build(&mut model, &a.blocks, false);
        let f = followers(&plan.graph, &plan.blocks, plan.n);
        model.unknowns.iter().map(|u| u.name.to_string()).zip(f).collect()
    }

    fn named(pairs: &[(&str, bool)]) -> Vec<(String, bool)> {
        pairs.iter().map(|&(n, b)| (n.to_string(), b)).collect()
    }

    /// The slider of an offset slider-crank follows its rod's angle; the angle does not follow.
    #[test]
    fn a_slider_follows_its_rod() {
        let src = "pub struct S { params r = 1, l = 3, e = 0.5; input phi; unknowns psi = 0, x = 3;
                   loop oab: r @ phi == (x, e) + l @ psi; }";
        assert_eq!(followers_of(src), named(&[("psi", false), ("x", true)]));
    }

    /// The rocker and coupler of a four-bar (a nonlinear block) never follow.
    #[test]
    fn a_dyad_does_not_follow() {
        let src = "pub struct F { params a = 1, b = 3, c = 2.5, d = 3; input th; unknowns be = 0.5, ga = 1.5;
                   loop l: a @ th + b @ be == (d, 0) + c @ ga; }";
        assert_eq!(followers_of(src), named(&[("be", false), ("ga", false)]));
    }

    /// A right-hand side with a kink, a jump or a pole keeps the slider judged; a division by
    /// a parameter, a square and an exponential do not.
    #[test]
    fn only_entire_right_hand_sides_follow() {
        let with = |rhs: &str| {
            let src = format!(
                "pub struct S {{ params r = 1, l = 3, e = 0.5; input phi; unknowns psi = 0, x = 3;
                   loop oab: r @ phi == (x - {rhs}, e) + l @ psi; }}"
            );
            followers_of(&src)[1].1
        };
        for entire in ["r / l", "(r * cos(psi)) ^ 2", "exp(sin(phi))", "-r * r / (l + e)"] {
            assert!(with(entire), "{entire}");
        }
        for not in ["abs(cos(psi))", "atan2(sin(phi), e)", "tan(phi)", "r / (2 + cos(phi))", "sqrt(l + cos(phi))"] {
            assert!(!with(not), "{not}");
        }
    }

    /// A linear block whose matrix varies (a slider along the turning rod `x @ phi`, reaching
    /// the line at `d`) keeps its unknown judged: its matrix can become singular between two
    /// samples. The height `y` then follows `x`.
    #[test]
    fn a_varying_matrix_does_not_follow() {
        let src = "pub struct Rod { params d = 2; input phi; unknowns x = 1, y = 1;
                   loop l: x @ phi == (d, y); }";
        assert_eq!(followers_of(src), named(&[("x", false), ("y", true)]));
    }
}
