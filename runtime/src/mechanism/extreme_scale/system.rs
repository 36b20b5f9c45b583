//! What the rescue's solves share: a system's magnitudes, units, angles and configuration
//! ([`System`]), its blocks ([`Block`]), a blank evaluation and the scaled residual its tolerance
//! applies to, and what a limit position gives ([`AtLimit`]). Its own module, below both the solves
//! (`extreme_scale`) and the assembly modes (`modes`), which read these and nothing of each other
//! but `keep_modes`.

use crate::solvers::newton::{BlockEval, NewtonConfig};

/// What Newton over the whole system gives at a limit position of the input (a root it reaches
/// only linearly, where two assembly modes meet and the Jacobian is singular), where a closed
/// form gives its double root: the position, for a solve of the positions alone (the compiled
/// `position_flat`, the run-time model's `positions`), as the closed form does at size 1; or
/// Newton's singular failure, for a solve of the analogs, as the closed form's analogs fail
/// there (they are not determined: see [`whole_position`](super::whole_position)).
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AtLimit {
    /// The position, to the rounding of the residual (see
    /// [`whole_position`](super::whole_position)).
    Position,
    /// Newton's [`BlockFailure::Singular`](crate::solvers::newton::BlockFailure::Singular).
    Singular,
}

/// A block of a mechanism's decomposition as [`whole_position`](super::whole_position) sees it: its
/// equations (indices into the whole system's, in the block's order), its unknowns, and whether it
/// is a closed-form block whose root is kept in the assembly mode the closed form picks from the
/// guess: one angle (`a cos q + b sin q = c`), a dyad's two angles (two links of fixed lengths
/// closing a loop), or an angle and a length (a length along a turning direction, or a slider).
/// Made by [`solve_blocks`](super::solve_blocks).
#[doc(hidden)]
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    /// The block's equations, as rows of the whole system.
    pub rows: Vec<usize>,
    /// The block's unknowns, as columns of the whole system.
    pub cols: Vec<usize>,
    /// Whether its assembly mode is kept (see `keep_modes`).
    pub closed_form: bool,
}

/// What every solve of [`whole_position`](super::whole_position) shares, of the whole system or of
/// one of its blocks: the equations' magnitudes, the unknowns' units (positive and finite) and
/// which are angles, the configuration, and what a limit position gives.
pub(super) struct System<'a, const N: usize> {
    pub(super) scale: [f64; N],
    pub(super) unit: [f64; N],
    pub(super) turns: [bool; N],
    pub(super) cfg: &'a NewtonConfig,
    pub(super) at_limit: AtLimit,
}

/// An evaluation to be written by the caller's closure (its values are never read first).
pub(super) fn blank_evaluation<const N: usize>() -> BlockEval<N, 0> {
    BlockEval { f: [0.0; N], j: [[0.0; N]; N], keep: [] }
}

/// The largest residual over its row's magnitude: the measure the rescue's tolerance applies to.
pub(super) fn scaled_residual<const N: usize>(f: &[f64; N], scale: &[f64; N]) -> f64 {
    (0..N).fold(0.0f64, |m, r| m.max(f[r].abs() / scale[r]))
}
