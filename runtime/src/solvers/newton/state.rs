//! The state of an iteration ([`Iter`]): the parts of the iteration (its loop, line search and
//! diagnosis) are its methods, each in its own module.

use super::scales::BlockEval;

/// The state of an iteration.
pub(super) struct Iter<'e, const N: usize, const K: usize, J> {
    pub(super) z: [f64; N],
    /// Where the iteration started.
    pub(super) guess: &'e [f64; N],
    /// The evaluation at `z` (a trial's while the trial is judged: each evaluation is written
    /// over it in place).
    pub(super) ev: &'e mut BlockEval<N, K, J>,
    pub(super) iterations: u32,
    pub(super) evaluations: u32,
    /// Scaled length of the previous full Newton step (infinite after a gradient step).
    pub(super) prev_step: f64,
    /// How many consecutive Newton steps each kept more than `LINEAR_CONTRACTION` of the
    /// previous one (linear convergence).
    pub(super) slow_run: u32,
    /// The scaled residual half way through the iteration budget.
    pub(super) rho_mark: f64,
    /// The scaled residual at the previous iterate.
    pub(super) prev_rho: f64,
    /// The scaled residual and sum of squares of the current iterate, when the full step that
    /// reached it computed them in scales the next iteration uses too.
    pub(super) judged: Option<(f64, f64)>,
    /// Iterations taken past the residual tolerance because it was reached only linearly (see
    /// `iterate`'s `LINEAR_EXTRA`).
    pub(super) past_tolerance: u32,
}
