//! How a block's positions are solved: decided once per block, here, from its equations and the
//! declaration's options; the emitter dispatches on the answer with one `match`.
//!
//! The order of the tests is the order of preference: a block linear in its unknowns is solved
//! directly (by one division when its coefficient is a constant); a nonlinear block that is a
//! classical Assur group in closed form (unless `#[kinloop(newton)]`); any other by Newton, over
//! a sparse factorisation when it is large and sparse (unless `#[kinloop(dense)]`).

use super::closed_form::{Recognised, recognise};
use super::positions::Position;
use super::sparse::{self, Sparse};
use crate::front::syntax::Options;
use crate::graph::dag::{Graph, NodeId};
use crate::structure::Block;

/// How one block's positions are solved.
pub enum Solve {
    /// A 1x1 linear block with a constant, non-zero, finite coefficient: one division, never
    /// singular.
    Fixed {
        /// The coefficient of the unknown.
        coefficient: f64,
        /// Minus the residual with the unknown set to zero.
        rhs: NodeId,
    },
    /// `J_bb` does not depend on the block's unknowns: one linear solve.
    Linear {
        /// Minus the residuals with the block's unknowns set to zero, per row.
        rhs: Vec<NodeId>,
    },
    /// A classical Assur group: the straight-line solve of its closed form.
    ClosedForm(Recognised),
    /// Newton over a dense LU.
    Newton,
    /// Newton over the symbolic factorisation of a large sparse block (see [`sparse`]; boxed:
    /// its tables are large beside the other variants).
    NewtonSparse(Box<Sparse>),
}

impl Solve {
    /// Decides how the block `blk` with position part `pos` is solved. Closed-form recognition
    /// adds nodes to the graph: called once per block, in solve order.
    pub fn decide(g: &mut Graph, blk: &Block, pos: &Position, n_params: usize, options: &Options) -> Solve {
        if let Some(rhs) = pos.rhs.clone() {
            let coefficient = match pos.jac.as_slice() {
                [row] if row.len() == 1 => g.as_const(row[0]).filter(|c| *c != 0.0 && c.is_finite()),
                _ => None,
            };
            return match (coefficient, rhs.as_slice()) {
                (Some(coefficient), &[rhs]) => Solve::Fixed { coefficient, rhs },
                _ => Solve::Linear { rhs },
            };
        }
        if options.newton.is_none()
            && let Some(rec) = recognise(g, blk, &pos.f, n_params)
        {
            return Solve::ClosedForm(rec);
        }
        if options.dense.is_none()
            && let Some(sp) = sparse::analyse(g, &pos.jac)
        {
            return Solve::NewtonSparse(Box::new(sp));
        }
        Solve::Newton
    }

    /// The right-hand side of a linear block (of [`Solve::Fixed`] and [`Solve::Linear`]), per
    /// row; `None` for the others.
    pub fn linear_rhs(&self) -> Option<&[NodeId]> {
        match self {
            Solve::Fixed { rhs, .. } => Some(std::slice::from_ref(rhs)),
            Solve::Linear { rhs } => Some(rhs),
            Solve::ClosedForm(_) | Solve::Newton | Solve::NewtonSparse(_) => None,
        }
    }

    /// Whether the block is linear in its unknowns ([`Solve::Fixed`] or [`Solve::Linear`]).
    pub fn is_linear(&self) -> bool {
        self.linear_rhs().is_some()
    }

    /// The closed form of a [`Solve::ClosedForm`] block.
    pub fn closed_form(&self) -> Option<&Recognised> {
        match self {
            Solve::ClosedForm(rec) => Some(rec),
            Solve::Fixed { .. } | Solve::Linear { .. } | Solve::Newton | Solve::NewtonSparse(_) => None,
        }
    }

    /// Whether the block is solved by Newton (dense or sparse): the blocks that iterate, check the
    /// configuration and add to the solve report.
    pub fn is_newton(&self) -> bool {
        match self {
            Solve::Newton | Solve::NewtonSparse(_) => true,
            Solve::Fixed { .. } | Solve::Linear { .. } | Solve::ClosedForm(_) => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Solve;

    /// How each block of a declaration is solved, in solve order, by the variant's name.
    fn solves(src: &str) -> Vec<&'static str> {
        let a = crate::analyze(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}"));
        let mut model = a.model;
        let plan = crate::plan::build(&mut model, &a.blocks, false);
        plan.blocks
            .iter()
            .map(|bp| match &bp.solve {
                Solve::Fixed { .. } => "fixed",
                Solve::Linear { .. } => "linear",
                Solve::ClosedForm(_) => "closed form",
                Solve::Newton => "Newton",
                Solve::NewtonSparse(_) => "sparse Newton",
            })
            .collect()
    }

    const SLIDER_CRANK: &str = "pub struct S { params r = 1, l = 3, e = 0.5; input phi; unknowns psi = 0, x = 3;
        loop oab: r @ phi == (x, e) + l @ psi; }";

    #[test]
    fn the_slider_crank_rod_in_closed_form_the_slider_by_one_division() {
        assert_eq!(solves(SLIDER_CRANK), ["closed form", "fixed"]);
        assert_eq!(solves(&format!("#[kinloop(newton)] {SLIDER_CRANK}")), ["Newton", "fixed"]);
    }

    #[test]
    fn a_coefficient_that_varies_is_a_linear_solve() {
        // `x` scaled by the input: linear in `x`, its coefficient not a constant.
        let src = "pub struct S { params a = 1; input phi; unknowns x = 1; eq e: phi * x == a; }";
        assert_eq!(solves(src), ["linear"]);
    }

    #[test]
    fn a_linear_block_whose_column_a_later_equation_scales_by_its_unknown_is_newton() {
        // `-cos x` in the column of `x`: its scale is known only once `x` is solved.
        let later = "eq e2: y == sin(x);";
        let head = "pub struct S { params a = 1; input phi; unknowns x = 1, y = 0;";
        assert_eq!(solves(&format!("{head} eq e1: (2 + phi * phi) * x == a * phi; {later} }}")), ["Newton", "fixed"]);
        // By one division, the block needs no scale: it stays.
        assert_eq!(solves(&format!("{head} eq e1: x == a * phi; {later} }}")), ["fixed", "fixed"]);
        // A later entry free of `x` (`y == 2 x`): the linear solve stands.
        let src = format!("{head} eq e1: (2 + phi * phi) * x == a * phi; eq e2: y == 2 * x; }}");
        assert_eq!(solves(&src), ["linear", "fixed"]);
    }

    #[test]
    fn a_large_ring_is_sparse_newton_unless_dense() {
        let n = 9;
        let unknowns: Vec<String> = (0..n).map(|i| format!("u{i} = 0.6, v{i} = 1.9")).collect();
        let mut loops = vec![format!("loop l0: a @ (0.5 * (phi + v{})) + b @ u0 == (d, 0) + c @ v0;", n - 1)];
        loops.extend((1..n).map(|i| format!("loop l{i}: a @ v{} + b @ u{i} == (d, 0) + c @ v{i};", i - 1)));
        let ring = format!(
            "pub struct Ring {{ params a = 1.0, b = 3.0, c = 2.5, d = 3.2; input phi; unknowns {}; {} }}",
            unknowns.join(", "),
            loops.join(" ")
        );
        assert_eq!(solves(&ring), ["sparse Newton"]);
        assert_eq!(solves(&format!("#[kinloop(dense)] {ring}")), ["Newton"]);
    }
}
