//! Synthesis: from the motion a designer needs to the dimensions of a declared mechanism that
//! makes it, for any mechanism declared with `#[kinloop(sensitivities)]`.
//!
//! Written once over [`SensKernel`](crate::SensKernel) ([`ProblemOf`]): a compiled mechanism's
//! problem is [`Problem`] (over [`CompiledSens`](crate::CompiledSens)), a run-time model's
//! `kinloop_model::Model::synthesis_problem`; the search, the local solve and the verification
//! are the same code, and give the same candidates where the kernels give the same states.
//!
//! A [`Problem`] names the design variables (parameters, with bounds: [`Design`]), the
//! [`Task`] (path generation with or without prescribed timing, path fitting with a free
//! placement, function generation, motion generation) and optional [`Constraints`]. A
//! [`Search`] runs Levenberg–Marquardt from many starts spread over the box by a shifted Halton
//! sequence, on the residuals with their exact Jacobian (the generated parameter
//! sensitivities; the velocity analogs for free input values; closed forms for the placement),
//! verifies every result with a branch-safe sweep through the targets in order ([`Defect`]s:
//! branch, circuit, order, and the constraints), and ranks them in a [`SynthesisReport`].
//!
//! [`classical`] holds the closed-form four-bar results of the theory (function generation by
//! Freudenstein's equation, Burmester's center-point and circle-point curves), used as exact
//! answers and as starts for the general search.
//!
//! See `docs/synthesis.md` in the repository for the method and what is verified.

mod candidate;
pub mod classical;
mod constraints;
mod error;
mod evolution;
mod halton;
mod local;
mod problem;
mod report;
mod residuals;
mod resolve;
mod search;
mod task;
mod vars;
mod verify;

pub use candidate::{Candidate, Defect, FourBarClass, Origin};
pub use constraints::{Constraints, FourBarNames, LinkRatioBound, TransmissionBound};
pub use error::SynthesisError;
pub use evolution::{DeConfig, Global};
pub use halton::Halton;
pub use local::{LocalConfig, LocalReport};
pub use problem::{Problem, ProblemOf};
pub use report::{Rejections, SynthesisReport, grashof_code};
pub use residuals::Residuals;
pub use search::Search;
pub use task::{Channel, PlacementBounds, Task, Timing, chebyshev};
pub use vars::{Design, Variable};

/// The Euclidean norm of `values`, each divided by the power of two at most the largest first
/// (exact) so that no square leaves the range of `f64`: the residuals of targets near `1e308`
/// have squares beyond it. NaN if a value is NaN, infinite if one is infinite.
pub(crate) fn norm_of(values: impl IntoIterator<Item = f64> + Clone) -> f64 {
    let mut big = 0.0f64;
    for v in values.clone() {
        // `f64::max` passes over a NaN: kept here instead.
        if v.is_nan() || v.abs() > big {
            big = v.abs();
        }
        if big.is_nan() {
            return big;
        }
    }
    if big == 0.0 || big == f64::INFINITY {
        return big;
    }
    let unit = crate::number::pow2_at_most(big);
    values.into_iter().map(|v| (v / unit) * (v / unit)).sum::<f64>().sqrt() * unit
}

#[cfg(test)]
mod tests {
    /// Against the plain formula where it holds, and exactly scaled beyond it.
    #[test]
    fn norms_of_values_whose_squares_leave_f64() {
        use super::norm_of;
        assert_eq!(norm_of([3.0, 4.0]), 5.0);
        assert_eq!(norm_of([0.0; 3]), 0.0);
        assert_eq!(norm_of(std::iter::empty::<f64>()), 0.0);
        for k in [-1074, -600, 600, 970] {
            let s = 2f64.powi(k);
            assert_eq!(norm_of([3.0 * s, -4.0 * s]), 5.0 * s, "{k}");
        }
        assert!(norm_of([1.0, f64::NAN, 1e308]).is_nan() && norm_of([f64::NAN, f64::INFINITY]).is_nan());
        assert_eq!(norm_of([1.0, f64::NEG_INFINITY]), f64::INFINITY);
    }
}
