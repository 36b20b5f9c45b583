//! Minimisers with one vocabulary: a configuration apart from the problem (built once, with
//! builders), a `minimize` method taking the problem, and one result type, [`Minimum`], carrying
//! the diagnostics.
//!
//! | problem | minimiser |
//! |---|---|
//! | a sum of squares with its Jacobian (e.g. from generated sensitivities) | [`LevenbergMarquardt`] |
//! | any objective, values only (in a box, or with infeasible points) | [`NelderMead`] |

mod levenberg_marquardt;
mod nelder_mead;

pub use levenberg_marquardt::LevenbergMarquardt;
pub use nelder_mead::NelderMead;

/// Why a minimiser stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum OptimizerStop {
    /// The tolerances were met.
    Converged,
    /// The evaluation budget ran out first.
    MaxEvaluations,
    /// No step improves the objective any more (e.g. Levenberg–Marquardt's damping grew
    /// without bound) before the tolerances were met.
    Stalled,
    /// Every point of [`NelderMead`]'s starting simplex is infeasible (its objective infinite
    /// or NaN): with nothing to compare, no step can improve, so it stops after evaluating the
    /// simplex. Start from a feasible point.
    InfeasibleStart,
}

/// The result of a minimiser: the best point and its diagnostics.
#[derive(Clone, Debug, PartialEq)]
pub struct Minimum<const P: usize> {
    /// The best point found.
    pub x: [f64; P],
    /// The objective there: `f(x)` for [`NelderMead`], the residual norm `|r(x)|` for
    /// [`LevenbergMarquardt`].
    pub value: f64,
    /// Objective evaluations made (every call, feasible or not).
    pub evaluations: usize,
    /// Iterations (simplex iterations, accepted Levenberg–Marquardt steps).
    pub iterations: usize,
    /// Why it stopped.
    pub termination: OptimizerStop,
    /// The objective after every iteration ([`LevenbergMarquardt`]) or every restart round
    /// ([`NelderMead`]), starting with the value at the starting point.
    pub history: Vec<f64>,
}

impl<const P: usize> Minimum<P> {
    /// The tolerances were met.
    pub fn converged(&self) -> bool {
        self.termination == OptimizerStop::Converged
    }
}
