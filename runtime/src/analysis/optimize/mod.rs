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
    /// The convergence tolerances were met: the residual's (Levenberg–Marquardt's `tol`, the
    /// synthesis' local solve's [`LocalConfig::tol`](crate::synthesis::LocalConfig::tol)), or
    /// both of [`NelderMead`]'s.
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
    /// A step changed no variable by more than the step tolerance (the synthesis' local solve's
    /// [`LocalConfig::step_tol`](crate::synthesis::LocalConfig::step_tol), relative to each
    /// variable's size) before the residual met its tolerance: the minimiser moves the point no
    /// further. Usually a local minimum whose residual is not zero, as a least-squares fit of
    /// more targets than the variables can meet stops, and then the point is the usable
    /// answer; but not proven one, since a heavily damped step (after rejected ones, as near
    /// where a design stops assembling) can be that small where the gradient is not zero. Judge
    /// the point by its residual. Only the synthesis' local solve stops so.
    StepTolerance,
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
