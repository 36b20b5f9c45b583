//! Whether the positions may jump: the equations hold a piecewise function of the inputs or
//! unknowns, whose value can step where its piece changes.
//!
//! A sweep judges a step by the distance of the new positions from their prediction, except
//! where every unknown it judges is an angle that a closed form gives (the runtime's
//! `positions_judged`): such an angle is the one root of its block on the assembly mode the
//! determinant's sign keeps, however far the prediction was, so smooth equations give nothing
//! for a distance test to find. That argument needs the equations to be continuous in the
//! inputs. `floor` and `wrap` step, `min`, `max` and `clamp` do where an argument is infinite (a
//! law `clamp((t - t0) / w, 0, 1)` with a width `w` of zero steps from 0 to 1 at `t0`), and
//! `atan2` and `angle` turn by a whole turn at their cut: through any of them the positions
//! can jump between two samples, with the velocity analogs alike on both sides, and only the
//! distance from the prediction tells. Where the equations hold one, the sweep judges every
//! position's distance, as it does for a Newton block's: the jump then stops it ("however
//! small the step, the solution jumps") instead of passing unseen.
//!
//! A piecewise function of parameters and constants alone (`max(a, b)` of two lengths) is one
//! value along a sweep, and does not count.

use super::finished::Plan;
use crate::graph::dag::{Func, Graph, Leaf, Op};

/// Whether the position equations of `plan` hold a piecewise function (`floor`, `wrap`, `min`,
/// `max`, `clamp`, `atan2`, `angle`) of the inputs or unknowns (see the module documentation):
/// the runtime's `Mechanism::PIECEWISE`.
pub fn piecewise(plan: &Plan) -> bool {
    let g = &plan.graph;
    g.reachable(&plan.residuals).into_iter().any(|node| match g.op(node) {
        Op::Func(Func::Floor | Func::Signum, x) => varies(g, &[x]),
        Op::Select(a, b, _, _) => varies(g, &[a, b]),
        Op::Atan2(y, x) => varies(g, &[y, x]),
        _ => false,
    })
}

/// Whether any of `nodes` depends on an input or an unknown.
fn varies(g: &Graph, nodes: &[crate::graph::dag::NodeId]) -> bool {
    g.leaves_of(nodes).iter().any(|l| matches!(l, Leaf::Input(_) | Leaf::Unknown(_)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piecewise_of(src: &str) -> bool {
        let a = crate::analyze(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}"));
        let mut model = a.model;
        let plan = crate::plan::build(&mut model, &a.blocks, false);
        piecewise(&plan)
    }

    /// A four-bar's equations are smooth: its closed-form angles need no distance test.
    #[test]
    fn a_four_bar_is_not_piecewise() {
        let src = "pub struct F { params a = 1, b = 3, c = 2.5, d = 3; input th; unknowns be = 0.5, ga = 1.5;
                   loop l: a @ th + b @ be == (d, 0) + c @ ga; }";
        assert!(!piecewise_of(src));
    }

    /// A cam law of the input through `clamp` and `wrap` (a dwell cam's) is piecewise, each
    /// function alone too.
    #[test]
    fn a_law_through_clamp_or_wrap_is_piecewise() {
        for law in ["clamp((th - t0) / w, 0, 1)", "wrap(th, 2 * pi)", "min(th, t0)", "max(th, t0)", "floor(th)"] {
            let src = format!(
                "pub struct C {{ params l = 3, c = 2, t0 = 0.5, w = 1, h = 0.5; input th; unknowns ga = 1.6, ps = 0;
                 let s = h * {law};
                 loop r: (0, 1 + s) + l @ ga == (1, 4) + c @ ps; }}"
            );
            assert!(piecewise_of(&src), "{law}");
        }
    }

    /// `angle` of a vector that turns with the input: its cut is a turn's jump.
    #[test]
    fn an_angle_of_the_input_is_piecewise() {
        let src = "pub struct A { params a = 1, b = 3, c = 2.5, d = 3; input th; unknowns be = 0.5, ga = 1.5;
                   let k = angle((cos(th), 1));
                   loop l: a @ th + b @ be == (d, a * k) + c @ ga; }";
        assert!(piecewise_of(src));
    }

    /// A piecewise function of parameters alone is one value along a sweep; one that only an
    /// output holds cannot move the positions.
    #[test]
    fn parameters_alone_and_outputs_do_not_count() {
        let src = "pub struct F { params a = 1, b = 3, c = 2.5, d = 3; input th; unknowns be = 0.5, ga = 1.5;
                   loop l: a @ th + max(b, c) @ be == (d, 0) + c @ ga;
                   output o = floor(th) + clamp(be, 0, 1); }";
        assert!(!piecewise_of(src));
    }
}
