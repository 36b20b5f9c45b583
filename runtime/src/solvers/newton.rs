//! Damped Newton's method for one square block, with diagnostics.
//!
//! The configuration ([`NewtonConfig`]) is separate from the problem (the block's generated
//! evaluation closure) and the outcome carries its diagnostics ([`SolveReport`]): iterations,
//! evaluations, final residual and why it stopped.
//!
//! **Scale-free tests.** Every test is made in the units of the problem: residual `i` is divided
//! by its row magnitude `scale_i` (see [`Magnitudes`]), a step in unknown `j` by that
//! unknown's magnitude, and the pivots of the factorisation are those of the row-equilibrated
//! Jacobian (of the column-equilibrated one for a final correction made with the analogs'
//! factorisation, below). A mechanism in metres, millimetres or micrometres therefore stops at
//! the same relative accuracy.
//!
//! **No silent wrong answer.** Whatever stops the iteration, the final scaled residual is
//! checked; the last Newton correction is applied (a prediction that already meets the
//! tolerance is still corrected once); a root reached with linear convergence (the signature
//! of a singular Jacobian at the root) is reported as singular, not returned as an inaccurate
//! success.
//!
//! **One factorisation at the root.** The last correction is made at the evaluation the block
//! returns, whose Jacobian the analogs factorise. [`newton_keeping_lu`] makes that correction
//! with the analogs' own factorisation (columns divided by their magnitudes) and hands it over,
//! so a block factorises its Jacobian at the root once, as a hand-written solver would.
//!
//! **Magnitudes made once.** The magnitudes of a loop of links of given lengths do not depend on
//! the block's unknowns: the generated code makes them, checks them and takes the reciprocals of
//! the row magnitudes once per solve, and the evaluations carry only residuals, Jacobian and kept
//! values. A block whose magnitudes depend on its unknowns (a slider's distance is a length of
//! its loop) keeps them with each evaluation.

pub use super::newton_config::{NewtonConfig, SolveReport, Termination};
use crate::solvers::closed::unwrap_to_turn;
use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::lu::{Lu, RowScales, all_positive_finite, largest};
use core::f64::consts::PI;

/// One evaluation of a block: residuals, Jacobian rows, and intermediate values the generated
/// code keeps for later stages (so they are not recomputed after convergence).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct BlockEval<const N: usize, const K: usize, J = [[f64; N]; N]> {
    pub f: [f64; N],
    /// The Jacobian: dense rows, or a sparse block's non-zeros (see [`BlockJacobian`]).
    pub j: J,
    pub keep: [f64; K],
}

/// The magnitudes a block's tests judge it in. The generated code makes them once per solve
/// when they do not depend on the block's unknowns (every loop of links of given lengths), and
/// from each evaluation otherwise (a slider coordinate's magnitude is its own).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Magnitudes<const N: usize> {
    /// The row equilibration by the magnitude of each row: a structural bound of the
    /// equation's terms (for a loop projection, the sum of its link lengths), in the equation's
    /// unit, generated for every equation. Residual `i` is judged relative to it. Where one is
    /// not positive and finite (`degenerate`: a hand-written block that has none, or a
    /// degenerate mechanism whose terms all vanish) the row sums `sum_j |J_ij|` of each
    /// evaluation replace the invalid ones, which is right for angle unknowns only.
    rows: RowScales<N>,
    /// The unit of each unknown: one radian for an angle, the magnitude of the rows it appears
    /// in per unit of its Jacobian entry otherwise (a slider coordinate: its loop's lengths). A
    /// step `dz_j` is judged relative to `max(|z_j|, unit_j)`; a value that is not positive and
    /// finite counts as `1` (replaced here).
    unit: [f64; N],
    /// The unknowns whose equations repeat every turn (angles that enter the block through
    /// sines and cosines of whole multiples of themselves): an iteration that carried one more
    /// than half a turn from its guess returns it on the guess's turn, as a closed form does.
    turns: [bool; N],
}

impl<const N: usize> Magnitudes<N> {
    /// The row magnitudes `scale` and the units `unit` of the unknowns, checked once.
    #[inline(always)]
    pub fn new(scale: [f64; N], unit: [f64; N]) -> Self {
        Magnitudes { rows: RowScales::new(scale), unit: units(&unit), turns: [false; N] }
    }

    /// These magnitudes, with `turns` marking the unknowns whose equations repeat every turn
    /// (see [`Magnitudes::turns`]).
    #[inline(always)]
    pub fn with_turns(mut self, turns: [bool; N]) -> Self {
        self.turns = turns;
        self
    }
}

/// Where a block's magnitudes come from: made once for the solve ([`Magnitudes`] itself), or
/// made from each evaluation (a closure).
#[doc(hidden)]
pub trait MagnitudesOf<const N: usize, const K: usize, J> {
    /// The magnitudes of every evaluation, when they are the same for all.
    fn fixed(&self) -> Option<&Magnitudes<N>>;
    /// The magnitudes at the evaluation `ev`.
    fn of(&self, ev: &BlockEval<N, K, J>) -> Magnitudes<N>;
}

impl<const N: usize, const K: usize, J> MagnitudesOf<N, K, J> for Magnitudes<N> {
    #[inline(always)]
    fn fixed(&self) -> Option<&Magnitudes<N>> {
        Some(self)
    }
    #[inline(always)]
    fn of(&self, _ev: &BlockEval<N, K, J>) -> Magnitudes<N> {
        *self
    }
}

impl<const N: usize, const K: usize, J, F: Fn(&BlockEval<N, K, J>) -> Magnitudes<N>> MagnitudesOf<N, K, J> for F {
    #[inline(always)]
    fn fixed(&self) -> Option<&Magnitudes<N>> {
        None
    }
    #[inline(always)]
    fn of(&self, ev: &BlockEval<N, K, J>) -> Magnitudes<N> {
        self(ev)
    }
}

/// The magnitudes `$mags` gives at the evaluation `$ev`: those made once, or made into
/// `$current` (the caller's slot, left uninitialised for fixed magnitudes: nothing is copied).
macro_rules! magnitudes_at {
    ($mags:expr, $ev:expr, $current:ident) => {
        match $mags.fixed() {
            Some(m) => m,
            None => {
                $current = $mags.of($ev);
                &$current
            }
        }
    };
}

/// The row equilibration of the magnitudes `$m` at the evaluation `$ev`: `$m`'s own when its
/// scales are all valid (one branch for the set), otherwise made row by row into `$fallback`
/// (the caller's slot, left uninitialised on the common path).
macro_rules! rows_at {
    ($m:expr, $ev:expr, $fallback:ident) => {
        if $m.rows.degenerate {
            $fallback = fallback_rows(&$m.rows.s, $ev);
            &$fallback
        } else {
            &$m.rows
        }
    };
}

// After the macros, which it uses.
#[path = "restarts.rs"]
mod restarts;

/// A converged block. Its evaluation is the caller's (see [`newton`]): at `z`, or (after a
/// correction at the rounding level, applied without a new evaluation) at a point within a few
/// rounding units of `z`.
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Solved<const N: usize> {
    pub z: [f64; N],
    pub iterations: u32,
    pub evaluations: u32,
    pub residual: f64,
    pub termination: Termination,
}

/// Why a block failed; the generated code adds the location and names.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BlockFailure {
    /// A residual or Jacobian entry is not finite; `row` is the block row.
    NonFinite { row: usize, iterations: u32 },
    /// The iteration cap was reached while the residual still decreased.
    NoConvergence { row: usize, iterations: u32, residual: f64 },
    /// The iteration stalled at a stationary point of the squared residual that is not a root
    /// (no descent direction, scaled residual clearly non-zero): the loops cannot close there.
    /// `evaluations` counts the block's evaluations (restarts after it add theirs).
    NoAssembly { row: usize, iterations: u32, evaluations: u32, residual: f64 },
    /// The Jacobian is singular at (or the iteration converged only linearly to) a root: a
    /// singular position, where the solution is not determined to working accuracy.
    Singular { row: usize, iterations: u32, residual: f64, pivot_ratio: f64, tolerance: f64 },
    /// A configuration field is out of range (see [`NewtonConfig::invalid_field`]).
    InvalidConfig { field: &'static str },
    /// A closed form's angle is `value`, on its guess's turn so many turns out that the spacing
    /// of doubles there exceeds what the tolerance accepts (see
    /// [`largest_precise_angle`](crate::solvers::closed::largest_precise_angle)). The generated
    /// code names the angle by its guess; it also reports Newton's failure from such a guess as
    /// this (see `block_failure`).
    TooManyTurns { value: f64 },
}

/// A scaled residual above this at a stall means the loops do not close there (not merely a
/// root reached slowly): far above any rounding floor, far below the residual of a mechanism
/// that visibly cannot assemble.
const STALL_RESIDUAL: f64 = 1e-8;

/// The scaled residual may exceed `residual_tol` by this factor when the iteration stops on the
/// step test (rows whose terms are much larger than their derivatives have a higher floor).
const FLOOR_FACTOR: f64 = 1e3;

/// The largest scaled correction applied to an accepted guess without iterating (larger ones,
/// from an ill-conditioned block, are iterated and checked).
const MAX_FREE_CORRECTION: f64 = 1e-6;

/// The largest scaled final correction of an iteration applied without evaluating the block
/// again: a few rounding units, below which the values the generated code keeps from the last
/// evaluation (sines and cosines of the unknowns, from which later unknowns and outputs are
/// computed) are as accurate as new ones. A larger correction is checked by a new evaluation
/// (and undone if it made the residual worse).
const MAX_UNCHECKED_CORRECTION: f64 = 16.0 * f64::EPSILON;

/// The smallest pivot of a row-equilibrated factorisation from which its Newton step is taken
/// to be exact to rounding (the residual `J dz + f` is then a few rounding units of the
/// equations' magnitudes, far below what the descent test can see).
const ACCURATE_PIVOT: f64 = 1e-3;

/// A final step this large relative to the previous one means linear, not quadratic,
/// convergence.
const LINEAR_CONTRACTION: f64 = 0.1;

/// `rows_at!` where a generated magnitude is missing or degenerate: the row sum replaces it.
#[cold]
#[inline(never)]
fn fallback_rows<const N: usize, const K: usize, J: BlockJacobian<N>>(
    scale: &[f64; N],
    ev: &BlockEval<N, K, J>,
) -> RowScales<N> {
    let mut s = [0.0; N];
    for r in 0..N {
        let given = scale[r];
        s[r] = if given > 0.0 && given < f64::INFINITY { given } else { ev.j.row_abs_sum(r) };
    }
    RowScales::new(s)
}

/// The units of the unknowns (see [`Magnitudes::unit`]): the generated ones when they are all
/// valid (one branch for the set), otherwise `1` for each invalid one.
#[inline(always)]
fn units<const N: usize>(unit: &[f64; N]) -> [f64; N] {
    if all_positive_finite(unit) { *unit } else { fallback_units(unit) }
}

/// [`units`] with an invalid unit.
#[cold]
#[inline(never)]
fn fallback_units<const N: usize>(unit: &[f64; N]) -> [f64; N] {
    unit.map(|u| if u > 0.0 && u < f64::INFINITY { u } else { 1.0 })
}

/// `max_i |f_i| / s_i`; NaN propagates, a non-zero residual over a zero scale is infinite.
#[inline(always)]
fn scaled_residual<const N: usize>(f: &[f64; N], s: &[f64; N]) -> f64 {
    largest::<N>(core::array::from_fn(|r| {
        let a = f[r].abs();
        if a == 0.0 { 0.0 } else { a / s[r] }
    }))
}

/// [`scaled_residual`] and [`sum_sq_scaled`] in one pass (one division per row). The maximum
/// skips a NaN (one `maxsd` per row): the sum of squares, which the callers test first, does
/// not. Valid scales need no test of a zero residual (measured: the loop without it is 80
/// instructions a class IV step cheaper than one loop with the test made conditional).
#[inline(always)]
fn scaled_norms<const N: usize>(f: &[f64; N], rows: &RowScales<N>) -> (f64, f64) {
    let s = &rows.s;
    let mut m = 0.0f64;
    let mut acc = 0.0;
    if rows.degenerate {
        for r in 0..N {
            let v = f[r] / s[r];
            // A zero residual counts as zero even over a zero scale.
            let a = if f[r] == 0.0 { 0.0 } else { v.abs() };
            m = if a > m { a } else { m };
            acc += v * v;
        }
    } else {
        for r in 0..N {
            let v = f[r] / s[r];
            let a = v.abs();
            m = if a > m { a } else { m };
            acc += v * v;
        }
    }
    (m, if acc.is_nan() { f64::INFINITY } else { acc })
}

/// `max_j |dz_j| / max(|z_j|, unit_j)`: steps relative to each unknown's magnitude, in its own
/// unit (see [`Magnitudes::unit`], checked); NaN propagates.
#[inline(always)]
fn scaled_step<const N: usize>(dz: &[f64; N], z: &[f64; N], unit: &[f64; N]) -> f64 {
    largest::<N>(core::array::from_fn(|c| {
        // The larger of `|z|` and the unit (a NaN `z` gives the unit, as `f64::max` would), one
        // `maxsd` where `f64::max` also tests for NaN.
        let (a, u) = (z[c].abs(), unit[c]);
        dz[c].abs() / if a > u { a } else { u }
    }))
}

/// Whether an unknown moved more than half a turn (in its own unit: only an angle's distance
/// matters); a NaN counts as no move (a non-finite result is reported otherwise).
#[inline(always)]
fn beyond_half_turn<const N: usize>(z: &[f64; N], guess: &[f64; N]) -> bool {
    // One comparison per unknown, or-ed: no maximum to carry from one to the next.
    let mut far = false;
    for c in 0..N {
        far |= (z[c] - guess[c]).abs() > PI;
    }
    far
}

/// The scaled residual of a full system (continuation, event location): each residual relative
/// to the larger of its generated row magnitude `scale` (see [`Magnitudes`]) and
/// `sum_j |J_ij| + |extra_i|`, where `extra` holds further derivatives of the row (along the
/// input path). The second keeps the test attainable where every term of a row vanishes at a
/// branch point (e.g. `s^2 - x^2` at the origin), where the continuation's absolute step test
/// stops before a residual relative to the vanishing magnitude is reached.
pub(crate) fn system_residual<const N: usize>(
    f: &[f64; N],
    j: &[[f64; N]; N],
    extra: &[f64; N],
    scale: &[f64; N],
) -> f64 {
    let mut s = [0.0; N];
    for r in 0..N {
        let derivatives = j[r].iter().map(|v| v.abs()).sum::<f64>() + extra[r].abs();
        // NaN in `scale` leaves `derivatives`.
        s[r] = if scale[r] > derivatives { scale[r] } else { derivatives };
    }
    scaled_residual(f, &s)
}

fn argmax_scaled<const N: usize>(f: &[f64; N], s: &[f64; N]) -> usize {
    let mut k = 0;
    let mut best = -1.0;
    for r in 0..N {
        let v = f[r].abs() / s[r];
        if v > best || v.is_nan() {
            k = r;
            best = if v.is_nan() { f64::INFINITY } else { v };
        }
    }
    k
}

/// Where a residual is not finite, the first row with a residual or Jacobian entry that is
/// not: one test for the residuals, and the search only when it fails. The Jacobian is tested
/// where the iteration stops ([`jacobian_non_finite`]): a non-finite entry on the way can at
/// worst spoil a step, which the descent test and the final checks catch.
#[inline(always)]
fn residual_non_finite<const N: usize, const K: usize, J: BlockJacobian<N>>(ev: &BlockEval<N, K, J>) -> Option<usize> {
    let mut finite = true;
    for r in 0..N {
        finite &= ev.f[r].abs() < f64::INFINITY;
    }
    if finite { None } else { non_finite_row(ev) }
}

/// Where a Jacobian entry is not finite, the first row with a residual or Jacobian entry that
/// is not (one test for the matrix).
#[inline(always)]
fn jacobian_non_finite<const N: usize, const K: usize, J: BlockJacobian<N>>(ev: &BlockEval<N, K, J>) -> Option<usize> {
    if ev.j.finite() { None } else { non_finite_row(ev) }
}

/// [`residual_non_finite`] and [`jacobian_non_finite`] where an entry is not finite.
#[cold]
#[inline(never)]
fn non_finite_row<const N: usize, const K: usize, J: BlockJacobian<N>>(ev: &BlockEval<N, K, J>) -> Option<usize> {
    (0..N).find(|&r| !ev.f[r].is_finite() || !ev.j.row_finite(r))
}

/// The Newton step `-J^-1 f` with `J` equilibrated by the row magnitudes, and the pivot ratio.
#[inline(always)]
fn newton_step<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
    rows: &RowScales<N>,
) -> ([f64; N], f64) {
    if N == 1 {
        // A scalar block needs no factorisation: the row-equilibrated pivot is `|J| / s` (NaN
        // when both vanish, which fails every test and is reported as 0; a non-finite `J` is
        // caught by the callers).
        let j = ev.j.first();
        let mut dz = [0.0; N];
        dz[0] = -ev.f[0] / j;
        return (dz, j.abs() / rows.s[0]);
    }
    ev.j.newton_step(&ev.f, rows)
}

/// The guess `z0` corrected by one Newton step `dz` with the Jacobian of its evaluation `ev`,
/// with the step and its scaled size, or `None` when that Jacobian is near singular or the step
/// is not small (then it iterates). A correction within the rounding of the unknowns is noise: the guess is
/// kept, so a solve from a solution returns it unchanged.
#[inline(always)]
fn free_correction<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
    rows: &RowScales<N>,
    unit: &[f64; N],
    rho: f64,
    z0: [f64; N],
    cfg: &NewtonConfig,
    last: &mut impl LastStep<N, K, J>,
) -> Option<([f64; N], [f64; N], f64)> {
    let (dz, pivot) = last.correction(ev, rows, rho);
    let step = scaled_step(&dz, &z0, unit);
    // NaN fails both tests.
    if !(pivot > cfg.singular_tol && step <= MAX_FREE_CORRECTION) {
        return None;
    }
    let mut z = z0;
    if step > 4.0 * f64::EPSILON {
        for c in 0..N {
            z[c] += dz[c];
        }
    }
    Some((z, dz, step))
}

/// Moves `z` (evaluated as `ev`) to `z + dz` and its evaluation, and returns the scaled residual
/// there, when that residual is at most `bound` (NaN fails); otherwise leaves both as they are:
/// a final correction is kept only if it did not make things worse (rounding noise near a
/// singular position can). The new evaluation is moved into `ev` once (a large block's
/// evaluation is kilobytes).
#[inline(always)]
fn evaluated_correction<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z: &mut [f64; N],
    ev: &mut BlockEval<N, K, J>,
    dz: &[f64; N],
    bound: f64,
    eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    mags: &impl MagnitudesOf<N, K, J>,
) -> Option<f64> {
    let mut z1 = *z;
    for c in 0..N {
        z1[c] += dz[c];
    }
    let ev1 = eval(&z1);
    let (current, fallback);
    let m = magnitudes_at!(mags, &ev1, current);
    let rho = scaled_residual(&ev1.f, &rows_at!(m, &ev1, fallback).s);
    if rho <= bound {
        *z = z1;
        *ev = ev1;
        Some(rho)
    } else {
        None
    }
}

/// The accepted guess `z0` (evaluation `ev0`, scaled residual `rho0`) corrected by `dz`, a step
/// above the rounding level: evaluated again there, so that the Jacobian and the values the
/// generated code keeps (sines and cosines of the unknowns, which later unknowns and outputs are
/// computed from) describe the returned position; undone if it made the residual worse (the
/// guess already met the tolerance).
#[cold]
#[inline(never)]
fn checked_free_correction<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K, J>,
    rho0: f64,
    dz: &[f64; N],
    eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    mags: &impl MagnitudesOf<N, K, J>,
    last: &mut impl LastStep<N, K, J>,
) -> Solved<N> {
    let mut z = z0;
    let residual = evaluated_correction(&mut z, ev, dz, rho0, eval, mags).unwrap_or(rho0);
    last.keep(ev);
    Solved { z, iterations: 0, evaluations: 2, residual, termination: Termination::ResidualTolerance }
}

/// Solves one block from the guess `z0`, whose evaluation the caller has made into `ev`: the
/// iteration updates it in place (each accepted step's evaluation is written over it), and on
/// return it is the evaluation at the returned position ([`Solved`]). The caller's slot, not a
/// value moved through the result: a block's evaluation is hundreds of bytes (a large sparse
/// block's, kilobytes). In the common warm-started case this costs one evaluation and one small
/// factorisation: the guess already meets the tolerance and is corrected once by the Newton step
/// (its Jacobian is the one the analogs use). The iteration itself is a separate, out-of-line
/// function.
#[doc(hidden)]
#[inline(always)]
pub fn newton<const N: usize, const K: usize>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K>,
    cfg: &NewtonConfig,
    eval: impl FnMut(&[f64; N]) -> BlockEval<N, K>,
    mags: &impl MagnitudesOf<N, K, [[f64; N]; N]>,
) -> Result<Solved<N>, BlockFailure> {
    newton_with(z0, ev, cfg, eval, mags)
}

/// [`newton`] for any representation of the Jacobian (a sparse block's non-zeros).
#[doc(hidden)]
#[inline(always)]
pub fn newton_with<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K, J>,
    cfg: &NewtonConfig,
    eval: impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    mags: &impl MagnitudesOf<N, K, J>,
) -> Result<Solved<N>, BlockFailure> {
    newton_last(z0, ev, cfg, eval, mags, &mut RowSteps)
}

/// [`newton`] that also writes into `lu` the factorisation the analogs use: `J` with each
/// column divided by its largest magnitude ([`Lu::factor_cols`]) at the returned evaluation.
/// It is the one that made the final correction, or (where the iteration did not end with
/// one, or a final correction was evaluated again) one made there. For a block whose Jacobian
/// columns have no entries outside the block, the analogs reuse it instead of factorising the
/// same matrix again. Written in place: a factorisation moved through the result would be
/// copied.
#[doc(hidden)]
#[inline(always)]
pub fn newton_keeping_lu<const N: usize, const K: usize>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K>,
    cfg: &NewtonConfig,
    eval: impl FnMut(&[f64; N]) -> BlockEval<N, K>,
    mags: &impl MagnitudesOf<N, K, [[f64; N]; N]>,
    lu: &mut Lu<N>,
) -> Result<Solved<N>, BlockFailure> {
    newton_last(z0, ev, cfg, eval, mags, &mut KeptLu { lu, valid: false })
}

/// [`newton_with`] whose correction at a converged iterate comes from `last`.
#[inline(always)]
fn newton_last<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K, J>,
    cfg: &NewtonConfig,
    mut eval: impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    mags: &impl MagnitudesOf<N, K, J>,
    last: &mut impl LastStep<N, K, J>,
) -> Result<Solved<N>, BlockFailure> {
    let (current, fallback);
    let m = magnitudes_at!(mags, ev, current);
    let rows = rows_at!(m, ev, fallback);
    let rho = scaled_residual(&ev.f, &rows.s);
    // NaN fails both tests; an out-of-range tolerance is diagnosed by `iterate`.
    if rho <= cfg.residual_tol
        && cfg.residual_tol <= 1e-3
        && let Some((z, dz, step)) = free_correction(ev, rows, &m.unit, rho, z0, cfg, last)
    {
        if step > MAX_UNCHECKED_CORRECTION {
            last.forget();
            return Ok(checked_free_correction(z0, ev, rho, &dz, &mut eval, mags, last));
        }
        last.keep(ev);
        return Ok(Solved {
            z,
            iterations: 0,
            evaluations: 1,
            residual: rho,
            termination: Termination::ResidualTolerance,
        });
    }
    iterate(z0, ev, cfg, eval, mags, last, rho)
}

/// How the correction at a converged iterate is computed: the step that ends the iteration,
/// applied to the returned position. Only that step asks it (`correction`), so whatever it keeps
/// describes the current evaluation until the evaluation changes (`forget`). An iteration that
/// ends otherwise has kept nothing and says so (`forget` again: measured 12 instructions
/// cheaper on the class IV block than leaving `keep` to test it), and `keep` makes it.
trait LastStep<const N: usize, const K: usize, J> {
    /// The correction `-J^-1 f` at `ev` (rows equilibrated by `rows`, scaled residual `rho`)
    /// and the smallest pivot of its factorisation.
    fn correction(&mut self, ev: &BlockEval<N, K, J>, rows: &RowScales<N>, rho: f64) -> ([f64; N], f64);
    /// The evaluation last corrected is not the one returned: nothing it factorised is valid.
    fn forget(&mut self);
    /// Makes what is kept describe `ev`, the returned evaluation.
    fn keep(&mut self, ev: &BlockEval<N, K, J>);
    /// Whether what the last correction factorised shows the current evaluation's Jacobian to
    /// be finite (then it need not be scanned).
    fn finite_jacobian(&self) -> bool;
}

/// The iteration's own row-equilibrated step; nothing is kept.
struct RowSteps;

impl<const N: usize, const K: usize, J: BlockJacobian<N>> LastStep<N, K, J> for RowSteps {
    #[inline(always)]
    fn correction(&mut self, ev: &BlockEval<N, K, J>, rows: &RowScales<N>, _rho: f64) -> ([f64; N], f64) {
        newton_step(ev, rows)
    }
    #[inline(always)]
    fn forget(&mut self) {}
    #[inline(always)]
    fn keep(&mut self, _ev: &BlockEval<N, K, J>) {}
    #[inline(always)]
    fn finite_jacobian(&self) -> bool {
        false
    }
}

/// The correction from the factorisation the analogs use: the Jacobian with each column
/// divided by its largest magnitude ([`Lu::factor_cols`]), written to `lu`. Its pivot ratio is
/// the one [`Health`](crate::Health) reads, so the correction is applied unchecked exactly where
/// the analogs will accept the factorisation.
struct KeptLu<'a, const N: usize> {
    lu: &'a mut Lu<N>,
    /// Whether `lu` is the factorisation of the evaluation last corrected.
    valid: bool,
}

impl<const N: usize, const K: usize> LastStep<N, K, [[f64; N]; N]> for KeptLu<'_, N> {
    #[inline(always)]
    fn correction(&mut self, ev: &BlockEval<N, K>, rows: &RowScales<N>, rho: f64) -> ([f64; N], f64) {
        if rho > MAX_UNCHECKED_CORRECTION {
            // A residual above the rounding level means, for all but an ill-conditioned block,
            // a correction above it too, which is checked by a new evaluation whose Jacobian
            // the analogs then need factorised: a factorisation kept here would be discarded.
            // The cheaper row-equilibrated step instead; `keep` factorises what is returned
            // (whichever way the guess goes, only the cost differs).
            self.valid = false;
            return newton_step(ev, rows);
        }
        refactor_columns(self.lu, ev);
        self.valid = true;
        (self.lu.solve(ev.f.map(|v| -v)), self.lu.pivot_ratio())
    }
    #[inline(always)]
    fn forget(&mut self) {
        self.valid = false;
    }
    #[inline(always)]
    fn keep(&mut self, ev: &BlockEval<N, K>) {
        if !self.valid {
            refactor_columns(self.lu, ev);
        }
    }
    /// A positive pivot ratio means the equilibrated Jacobian had neither a NaN entry nor a
    /// column with an infinite one ([`refactor_columns`]).
    #[inline(always)]
    fn finite_jacobian(&self) -> bool {
        self.valid && self.lu.pivot_ratio() > 0.0
    }
}

/// The analogs' factorisation of an evaluation's Jacobian, written over `lu`: each column
/// divided by its largest magnitude (a structural zero changes no maximum). The magnitudes are
/// plain maxima (one select per entry), neither screened nor NaN-tested: an infinite entry
/// zeroes its column (and is itself NaN there), a NaN entry stays NaN in the equilibrated
/// matrix, and either way a pivot is zero or NaN and the pivot ratio 0 ([`Lu::refactor_cols`]);
/// for a finite Jacobian they are `max_abs`'s, bit for bit.
#[inline(always)]
fn refactor_columns<const N: usize, const K: usize>(lu: &mut Lu<N>, ev: &BlockEval<N, K>) {
    let cols: [f64; N] = core::array::from_fn(|c| {
        let mut m = 0.0f64;
        for row in &ev.j {
            let a = row[c].abs();
            m = if a > m { a } else { m };
        }
        m
    });
    lu.refactor_cols(&ev.j, cols);
}

/// Newton iterations from `z0`, whose evaluation is `ev` (updated in place: each accepted
/// step's evaluation is written over it, never copied). The generated code calls it through
/// [`newton`] when the guess does not meet the tolerance; the correction at a converged
/// iterate comes from `last`.
///
/// The common path (a full Newton step accepted, then convergence) runs in this one function;
/// the rare paths (backtracking, descent, failures, a final correction that must be checked)
/// are out of line.
#[cold]
#[inline(never)]
#[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what lets NaN through
fn iterate<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K, J>,
    cfg: &NewtonConfig,
    mut eval: impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    mags: &impl MagnitudesOf<N, K, J>,
    last: &mut impl LastStep<N, K, J>,
    rho0: f64,
) -> Result<Solved<N>, BlockFailure> {
    if let Some(field) = cfg.invalid_field() {
        return Err(BlockFailure::InvalidConfig { field });
    }
    let floor = FLOOR_FACTOR * cfg.residual_tol.max(16.0 * f64::EPSILON);
    // Fixed magnitudes with valid scales (not the row sums that replace invalid ones): every
    // iterate is judged in the same scales.
    let fixed_rows = mags.fixed().is_some_and(|m| !m.rows.degenerate);
    let mut it = Iter {
        z: z0,
        guess: &z0,
        // The caller's evaluation, not a copy: the iteration updates it in place.
        ev,
        iterations: 0,
        evaluations: 1,
        prev_step: f64::INFINITY,
        slow_run: 0,
        rho_mark: f64::INFINITY,
        prev_rho: f64::INFINITY,
        judged: None,
    };
    loop {
        let (current, fallback);
        let m = magnitudes_at!(mags, it.ev, current);
        let rows = rows_at!(m, it.ev, fallback);
        let s = &rows.s;
        // The guess's scaled residual is the caller's; an iterate reached by a full step in
        // fixed scales was judged by that step.
        let (rho, phi) = match it.judged.take() {
            Some(judged) => judged,
            None if it.iterations == 0 => (rho0, sum_sq_scaled(&it.ev.f, s)),
            None => scaled_norms(&it.ev.f, rows),
        };
        // A residual that is not finite makes the sum of squares infinite or NaN (which it
        // reports as infinite); so does an overflow, for which the search finds no row.
        if !(phi < f64::INFINITY)
            && let Some(row) = residual_non_finite(it.ev)
        {
            return Err(BlockFailure::NonFinite { row, iterations: it.iterations });
        }
        if rho <= cfg.residual_tol {
            // Converged: the last correction, from the factorisation `last` keeps.
            let (dz, pivot) = last.correction(it.ev, rows, rho);
            let step = scaled_step(&dz, &it.z, &m.unit);
            return it.finish(dz, step, pivot, rho, s, Termination::ResidualTolerance, cfg, &mut eval, mags, last);
        }
        let (dz, pivot) = newton_step(it.ev, rows);
        let step = scaled_step(&dz, &it.z, &m.unit);
        // At the rounding floor the step no longer shrinks below `step_tol` or the residual no
        // longer decreases (a singular root still divides it by about four per iteration).
        let stagnant = rho >= 0.5 * it.prev_rho;
        if (step <= cfg.step_tol || stagnant) && rho <= floor {
            last.forget();
            return it.finish(dz, step, pivot, rho, s, Termination::StepTolerance, cfg, &mut eval, mags, last);
        }
        if it.iterations >= cfg.max_iterations {
            let capped = it.capped(rho, s, cfg);
            return restarts::after(capped, z0, it.ev, cfg, &mut eval, mags, last);
        }
        if it.iterations == cfg.max_iterations / 2 {
            it.rho_mark = rho;
        }
        let newton_ok = pivot > cfg.singular_tol * 1e-3 && step.is_finite();
        // At the rounding floor only the Newton step is worth trying.
        let moved = (newton_ok && it.full_step(&dz, pivot, rows, fixed_rows, phi, cfg, &mut eval))
            || (rho > floor && it.descend(s, cfg, &mut eval));
        if !moved {
            if rho <= floor {
                // No step decreases a residual already at its rounding floor.
                last.forget();
                return it.finish(dz, step, pivot, rho, s, Termination::StepTolerance, cfg, &mut eval, mags, last);
            }
            let stalled = it.stalled(rho, pivot, s, cfg);
            return restarts::after(stalled, z0, it.ev, cfg, &mut eval, mags, last);
        }
        let slow = newton_ok && step > LINEAR_CONTRACTION * it.prev_step;
        it.slow_run = if slow { it.slow_run + 1 } else { 0 };
        it.prev_step = if newton_ok { step } else { f64::INFINITY };
        it.prev_rho = rho;
        it.iterations += 1;
    }
}

/// The state of an iteration.
struct Iter<'e, const N: usize, const K: usize, J> {
    z: [f64; N],
    /// Where the iteration started.
    guess: &'e [f64; N],
    /// The evaluation at `z`.
    ev: &'e mut BlockEval<N, K, J>,
    iterations: u32,
    evaluations: u32,
    /// Scaled length of the previous full Newton step (infinite after a gradient step).
    prev_step: f64,
    /// How many consecutive Newton steps each kept more than `LINEAR_CONTRACTION` of the
    /// previous one (linear convergence).
    slow_run: u32,
    /// The scaled residual half way through the iteration budget.
    rho_mark: f64,
    /// The scaled residual at the previous iterate.
    prev_rho: f64,
    /// The scaled residual and sum of squares of the current iterate, when the full step that
    /// reached it computed them in scales the next iteration uses too.
    judged: Option<(f64, f64)>,
}

impl<const N: usize, const K: usize, J: BlockJacobian<N>> Iter<'_, N, K, J> {
    /// Ends a converged iteration: diagnoses linear convergence (a singular root), then applies
    /// the last correction `dz`. A correction far below the tolerance is applied as it is; a
    /// larger one is checked by a new evaluation (so the Jacobian and kept values match the
    /// returned position) and undone if it made the residual worse.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn finish(
        mut self,
        dz: [f64; N],
        step: f64,
        pivot: f64,
        rho: f64,
        s: &[f64; N],
        termination: Termination,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
        mags: &impl MagnitudesOf<N, K, J>,
        last: &mut impl LastStep<N, K, J>,
    ) -> Result<Solved<N>, BlockFailure> {
        if !last.finite_jacobian()
            && let Some(row) = jacobian_non_finite(self.ev)
        {
            return Err(BlockFailure::NonFinite { row, iterations: self.iterations });
        }
        // The position is known to about the last step of a linearly converging iteration (the
        // residual of a row can round to zero before the unknowns settle).
        let visible = FLOOR_FACTOR * cfg.residual_tol.max(cfg.step_tol);
        let slow = self.prev_step.is_finite() && step > LINEAR_CONTRACTION * self.prev_step;
        let singular_root = !step.is_finite()
            || (slow && step > visible)
            || (self.slow_run >= 2 && self.prev_step.is_finite() && self.prev_step > visible);
        if singular_root && self.iterations > 0 {
            // Newton converges quadratically to a regular root; linearly (each step a fixed
            // fraction of the previous one) only where the Jacobian is singular at the root,
            // and the position is then only known to about the size of the last step.
            return Err(self.singular(rho, pivot, s, cfg));
        }
        if step.is_finite() && step > 0.0 {
            if pivot > cfg.singular_tol && step <= MAX_UNCHECKED_CORRECTION {
                // A quadratically converging iteration often ends with a correction at the
                // rounding level: the last evaluation holds at `z` to rounding.
                for c in 0..N {
                    self.z[c] += dz[c];
                }
            } else {
                last.forget();
                self.checked_correction(&dz, rho, cfg, eval, mags);
            }
        }
        // After one step the test is skipped (it would cost the common path: a solve from a
        // sweep's prediction usually takes one step). One step that carries an angle over half
        // a turn follows a linearisation that is off there by about the sine's own size, so it
        // ends within the tolerance of a root only from a set of guesses about the tolerance
        // wide; the position is right even then, only on another turn.
        if self.iterations > 1 && beyond_half_turn(&self.z, self.guess) {
            self.back_to_guess_turns(rho, cfg, eval, mags, last);
        }
        last.keep(self.ev);
        Ok(Solved { z: self.z, iterations: self.iterations, evaluations: self.evaluations, residual: rho, termination })
    }

    /// Moves every unknown whose equations repeat every turn (see [`Magnitudes::turns`]) and
    /// that ended more than half a turn from its guess to the guess's turn. A long Newton step
    /// (from a near-singular Jacobian far from the root) can carry an angle many turns out.
    /// The position is the same; its numbers are not: many turns out the spacing of doubles is
    /// coarser. So the block is evaluated and corrected once more on the guess's turn, which
    /// also makes the evaluation describe the returned position. The move is kept only if the
    /// residual there, corrected or not, is no worse than `rho` (or the tolerance): it always
    /// is for an equation that repeats, so a mistaken mark could not return a wrong position.
    #[cold]
    #[inline(never)]
    fn back_to_guess_turns(
        &mut self,
        rho: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
        mags: &impl MagnitudesOf<N, K, J>,
        last: &mut impl LastStep<N, K, J>,
    ) {
        let (before, after, fallback);
        let turns = magnitudes_at!(mags, self.ev, before).turns;
        let unmoved = self.z;
        let mut moved = false;
        for c in (0..N).filter(|&c| turns[c]) {
            let (z, g) = (self.z[c], self.guess[c]);
            let on_turn = unwrap_to_turn(z, g);
            // Only a move that brings it nearer (not so for a guess too large for its turns
            // to be counted in doubles).
            if (on_turn - g).abs() < (z - g).abs() {
                self.z[c] = on_turn;
                moved = true;
            }
        }
        if !moved {
            return;
        }
        last.forget();
        let bound = rho.max(cfg.residual_tol);
        *self.ev = eval(&self.z);
        self.evaluations += 1;
        let m = magnitudes_at!(mags, self.ev, after);
        let rows = rows_at!(m, self.ev, fallback);
        let moved_rho = scaled_residual(&self.ev.f, &rows.s);
        let (dz, _) = newton_step(self.ev, rows);
        let finite = dz.iter().all(|v| v.is_finite());
        self.evaluations += u32::from(finite);
        let corrected = finite && evaluated_correction(&mut self.z, self.ev, &dz, bound, eval, mags).is_some();
        // NaN fails the comparison: not kept.
        let kept = corrected || moved_rho <= bound;
        if !kept {
            // Not a position of the block: back to where the iteration ended.
            self.z = unmoved;
            *self.ev = eval(&self.z);
            self.evaluations += 1;
        }
    }

    /// Applies the final correction `dz` after evaluating there, unless it made the residual
    /// worse than `rho` (rounding noise near a singular position).
    #[cold]
    #[inline(never)]
    fn checked_correction(
        &mut self,
        dz: &[f64; N],
        rho: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
        mags: &impl MagnitudesOf<N, K, J>,
    ) {
        self.evaluations += 1;
        evaluated_correction(&mut self.z, self.ev, dz, rho.max(cfg.residual_tol), eval, mags);
    }

    /// The failure of a root reached with linear convergence.
    #[cold]
    #[inline(never)]
    fn singular(&self, rho: f64, pivot: f64, s: &[f64; N], cfg: &NewtonConfig) -> BlockFailure {
        BlockFailure::Singular {
            row: argmax_scaled(&self.ev.f, s),
            iterations: self.iterations,
            residual: rho,
            pivot_ratio: if pivot.is_nan() { 0.0 } else { pivot },
            tolerance: cfg.singular_tol,
        }
    }

    /// The failure at the iteration cap: over the second half of the iterations the residual
    /// did not even halve (it crawls into a minimum that is not a root), or it still decreased.
    #[cold]
    #[inline(never)]
    fn capped(&self, rho: f64, s: &[f64; N], cfg: &NewtonConfig) -> BlockFailure {
        if let Some(row) = jacobian_non_finite(self.ev) {
            return BlockFailure::NonFinite { row, iterations: self.iterations };
        }
        let row = argmax_scaled(&self.ev.f, s);
        let iterations = self.iterations;
        if cfg.max_iterations >= 8 && rho > STALL_RESIDUAL && rho > 0.5 * self.rho_mark {
            return BlockFailure::NoAssembly { row, iterations, evaluations: self.evaluations, residual: rho };
        }
        BlockFailure::NoConvergence { row, iterations, residual: rho }
    }

    /// The full Newton step `dz` (from a factorisation whose smallest pivot is `pivot`) when it
    /// decreases the squared scaled residual enough (Armijo, `c = 1e-4`), otherwise backtracking
    /// along it ([`Iter::search`]); moves and returns `true` on success.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn full_step(
        &mut self,
        dz: &[f64; N],
        pivot: f64,
        rows: &RowScales<N>,
        fixed_rows: bool,
        phi0: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    ) -> bool {
        let s = &rows.s;
        // The slope of phi along dz is -2 phi0 for a Newton step. A well-conditioned
        // factorisation solves to rounding, so that is its slope; otherwise it is computed, so
        // that an inaccurate solve is caught (it is not a descent direction).
        let slope = if pivot >= ACCURATE_PIVOT { -2.0 * phi0 } else { directional_slope(self.ev, s, dz) };
        if slope.is_nan() || slope >= 0.0 {
            return false;
        }
        let mut trial = self.z;
        for c in 0..N {
            trial[c] += dz[c];
        }
        // Evaluated in place (no copy of the evaluation on the common path, the step accepted);
        // a rejected step's evaluation is replaced by the backtracking's or restored.
        *self.ev = eval(&trial);
        self.evaluations += 1;
        let (rho, phi) = scaled_norms(&self.ev.f, rows);
        if phi <= phi0 + 1e-4 * slope {
            self.z = trial;
            // In scales that stay the same, the next iteration's test of this iterate.
            self.judged = if fixed_rows { Some((rho, phi)) } else { None };
            return true;
        }
        self.rejected(dz, s, phi0, slope, cfg, eval)
    }

    /// After a rejected full step (its evaluation in `self.ev`): backtracking from half the
    /// step; if that fails too, the evaluation at the unmoved `z` is restored (evaluated again:
    /// the same position gives the same values), which the callers' fallbacks read.
    #[allow(clippy::too_many_arguments)]
    #[cold]
    #[inline(never)]
    fn rejected(
        &mut self,
        dz: &[f64; N],
        s: &[f64; N],
        phi0: f64,
        slope: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    ) -> bool {
        if self.search(dz, s, phi0, slope, 0.5, cfg, eval) {
            return true;
        }
        *self.ev = eval(&self.z);
        self.evaluations += 1;
        false
    }

    /// Backtracking (Armijo, `c = 1e-4`) along `dz` on the squared scaled residual from the
    /// damping `t` down to the configured minimum, given its value `phi0` and `slope` at the
    /// current iterate; moves and returns `true` on success.
    #[allow(clippy::too_many_arguments)]
    #[cold]
    #[inline(never)]
    fn search(
        &mut self,
        dz: &[f64; N],
        s: &[f64; N],
        phi0: f64,
        slope: f64,
        mut t: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    ) -> bool {
        while t >= cfg.min_damping {
            let mut trial = self.z;
            for c in 0..N {
                trial[c] += t * dz[c];
            }
            let ev_t = eval(&trial);
            self.evaluations += 1;
            let phi = sum_sq_scaled(&ev_t.f, s);
            if phi <= phi0 + 1e-4 * t * slope {
                self.z = trial;
                *self.ev = ev_t;
                return true;
            }
            t *= 0.5;
        }
        false
    }

    /// Where the Newton step fails (singular Jacobian, no decrease), Levenberg-Marquardt steps
    /// of increasing damping, down to steepest descent: they leave saddles of the squared
    /// residual that a far guess can lead to. Returns `true` when one decreased the residual.
    #[cold]
    #[inline(never)]
    fn descend(
        &mut self,
        s: &[f64; N],
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
    ) -> bool {
        let (a, g) = normal_equations(self.ev, s);
        let trace: f64 = (0..N).map(|k| a[k][k]).sum();
        if !(trace > 0.0 && trace.is_finite()) {
            return false;
        }
        for mu in [1e-9, 1e-6, 1e-3, 1.0] {
            let mut damped = a;
            for k in 0..N {
                damped[k][k] += mu * trace;
            }
            let lu = Lu::factor(&damped, [1.0; N]);
            let mut neg_g = g;
            for v in &mut neg_g {
                *v = -*v;
            }
            let dz = lu.solve(neg_g);
            if !dz.iter().all(|v| v.is_finite()) {
                continue;
            }
            let phi0 = sum_sq_scaled(&self.ev.f, s);
            let slope = directional_slope(self.ev, s, &dz);
            if !(slope.is_nan() || slope >= 0.0) && self.search(&dz, s, phi0, slope, 1.0, cfg, eval) {
                return true;
            }
        }
        false
    }

    /// Why no step decreases the residual: at a root the Jacobian is singular (a singular
    /// position); away from one the loops cannot close here.
    #[cold]
    #[inline(never)]
    fn stalled(&self, rho: f64, pivot: f64, s: &[f64; N], cfg: &NewtonConfig) -> BlockFailure {
        if let Some(row) = jacobian_non_finite(self.ev) {
            return BlockFailure::NonFinite { row, iterations: self.iterations };
        }
        let row = argmax_scaled(&self.ev.f, s);
        let iterations = self.iterations;
        if rho <= STALL_RESIDUAL {
            let pivot_ratio = if pivot.is_nan() { 0.0 } else { pivot };
            BlockFailure::Singular { row, iterations, residual: rho, pivot_ratio, tolerance: cfg.singular_tol }
        } else {
            BlockFailure::NoAssembly { row, iterations, evaluations: self.evaluations, residual: rho }
        }
    }
}

fn sum_sq_scaled<const N: usize>(f: &[f64; N], s: &[f64; N]) -> f64 {
    let mut acc = 0.0;
    for r in 0..N {
        let v = f[r] / s[r];
        acc += v * v;
    }
    if acc.is_nan() { f64::INFINITY } else { acc }
}

/// `d/dt |D^-1 f(z + t dz)|^2` at `t = 0`: `2 (D^-1 f) . (D^-1 J dz)`.
fn directional_slope<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
    s: &[f64; N],
    dz: &[f64; N],
) -> f64 {
    let jd = ev.j.mul(dz);
    let mut acc = 0.0;
    for r in 0..N {
        acc += ev.f[r] * jd[r] / (s[r] * s[r]);
    }
    2.0 * acc
}

/// `A = (D^-1 J)^T (D^-1 J)` and `g = (D^-1 J)^T D^-1 f` with `D` the row magnitudes.
fn normal_equations<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
    s: &[f64; N],
) -> ([[f64; N]; N], [f64; N]) {
    let j = ev.j.to_dense();
    let mut a = [[0.0; N]; N];
    let mut g = [0.0; N];
    for r in 0..N {
        let w = 1.0 / s[r];
        for c in 0..N {
            let jrc = j[r][c] * w;
            g[c] += jrc * ev.f[r] * w;
            for k in 0..N {
                a[c][k] += jrc * j[r][k] * w;
            }
        }
    }
    (a, g)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::lu::max_abs;
    use core::f64::consts::FRAC_PI_2;

    /// [`newton`] from `z0` with the evaluation made as the generated code makes it (into the
    /// caller's slot); the solved block and its final evaluation.
    fn solve<const N: usize, const K: usize>(
        z0: [f64; N],
        cfg: &NewtonConfig,
        mut eval: impl FnMut(&[f64; N]) -> BlockEval<N, K>,
    ) -> Result<(Solved<N>, BlockEval<N, K>), BlockFailure> {
        let mut ev = eval(&z0);
        newton(z0, &mut ev, cfg, eval, &mags).map(|s| (s, ev))
    }

    /// An evaluation whose magnitudes depend on the unknowns: `scale` and `unit` kept after
    /// each other, as the generated code keeps such magnitudes (`K = 2 N`).
    fn varying<const N: usize, const K: usize>(
        f: [f64; N],
        j: [[f64; N]; N],
        scale: [f64; N],
        unit: [f64; N],
    ) -> BlockEval<N, K> {
        let mut keep = [0.0; K];
        keep[..N].copy_from_slice(&scale);
        keep[N..2 * N].copy_from_slice(&unit);
        BlockEval { f, j, keep }
    }

    /// The magnitudes [`varying`] keeps.
    fn mags<const N: usize, const K: usize>(ev: &BlockEval<N, K>) -> Magnitudes<N> {
        Magnitudes::new(core::array::from_fn(|r| ev.keep[r]), core::array::from_fn(|c| ev.keep[N + c]))
    }

    fn circle(z: &[f64; 2]) -> BlockEval<2, 4> {
        // x^2 + y^2 = 4, y = x^3 (root near (1.03, 1.72), solved numerically).
        let [x, y] = *z;
        varying(
            [x * x + y * y - 4.0, y - x * x * x],
            [[2.0 * x, 2.0 * y], [-3.0 * x * x, 1.0]],
            [x * x + y * y + 4.0, y.abs() + (x * x * x).abs()],
            [1.0; 2],
        )
    }

    #[test]
    fn converges_quadratically_and_reports() {
        let (s, _) = solve([1.0, 1.0], &NewtonConfig::default(), circle).unwrap();
        assert!(s.residual <= 1e-12);
        assert!(s.iterations > 0 && s.iterations < 10, "{}", s.iterations);
        let [x, y] = s.z;
        // After the last correction the residual is at the rounding floor (a few ulps of 4).
        assert!((x * x + y * y - 4.0).abs() < 4.0 * 4.0 * f64::EPSILON && (y - x.powi(3)).abs() < 8.0 * f64::EPSILON);
        // Warm start: no iteration at all, one evaluation.
        let (again, _) = solve(s.z, &NewtonConfig::default(), circle).unwrap();
        assert_eq!(again.iterations, 0);
        assert_eq!(again.evaluations, 1);
    }

    /// `x^2 + y^2 + z^2 = 3`, `x = y z`, `z = x y`: a 3x3 block (the general factorisation)
    /// with a regular root at `(1, 1, 1)`.
    fn sphere(z: &[f64; 3]) -> BlockEval<3, 6> {
        let [x, y, w] = *z;
        varying(
            [x * x + y * y + w * w - 3.0, x - y * w, w - x * y],
            [[2.0 * x, 2.0 * y, 2.0 * w], [1.0, -w, -y], [-y, -x, 1.0]],
            [x * x + y * y + w * w + 3.0, x.abs() + (y * w).abs(), w.abs() + (x * y).abs()],
            [1.0; 3],
        )
    }

    /// The factorisation `newton_keeping_lu` leaves is, bit for bit, the analogs' own of the
    /// returned evaluation (columns divided by their largest magnitudes), whichever way the
    /// solve ended: a guess corrected once, an iteration converged on its residual, or one
    /// stopped on its step test (no residual tolerance can be met) that never made a
    /// correction from it. The position is the row-equilibrated iteration's to rounding.
    #[test]
    fn the_kept_factorisation_is_the_analogs_own() {
        fn check<const N: usize, const K: usize>(
            guess: [f64; N],
            cfg: &NewtonConfig,
            eval: impl Fn(&[f64; N]) -> BlockEval<N, K> + Copy,
        ) -> Termination {
            let mut kept = Lu::unfactored();
            let mut ev = eval(&guess);
            let s = newton_keeping_lu(guess, &mut ev, cfg, eval, &mags, &mut kept).unwrap();
            let cols: [f64; N] = core::array::from_fn(|c| max_abs(ev.j.map(|row| row[c])));
            let own = Lu::factor_cols(&ev.j, cols);
            assert_eq!(kept.pivot_ratio().to_bits(), own.pivot_ratio().to_bits());
            assert_eq!(kept.det().to_bits(), own.det().to_bits());
            assert_eq!(kept.negative_det(), own.negative_det());
            assert!(kept.pivot_ratio() > 0.01, "{}", kept.pivot_ratio());
            for k in 0..N {
                let mut e = [0.0; N];
                e[k] = 1.0;
                assert_eq!(kept.solve(e).map(f64::to_bits), own.solve(e).map(f64::to_bits));
            }
            let (rows, _) = solve(guess, cfg, eval).unwrap();
            for c in 0..N {
                assert!((s.z[c] - rows.z[c]).abs() <= 4.0 * f64::EPSILON, "{:?} {:?}", s.z, rows.z);
            }
            s.termination
        }
        let cfg = NewtonConfig::default();
        let root = solve([1.0, 1.0], &cfg, circle).unwrap().0.z;
        for guess in [[1.0, 1.0], [1.5, 0.5], root] {
            assert_eq!(check(guess, &cfg, circle), Termination::ResidualTolerance);
        }
        for guess in [[1.2, 0.9, 1.1], [1.0, 1.0, 1.0], [1.0 + 1e-9, 1.0, 1.0 - 1e-9]] {
            assert_eq!(check(guess, &cfg, sphere), Termination::ResidualTolerance);
        }
        let unreachable = NewtonConfig { residual_tol: 0.0, ..cfg };
        assert_eq!(check([1.2, 0.9, 1.1], &unreachable, sphere), Termination::StepTolerance);
    }

    /// Magnitudes made once for the solve (as the generated code makes those free of the
    /// unknowns) and the same magnitudes read from every evaluation give the same solve, bit
    /// for bit, and so does an invalid scale replaced by the row sums of each evaluation.
    #[test]
    fn magnitudes_made_once_are_those_of_every_evaluation() {
        for scale in [[3.0, 0.25], [0.0, 2.0], [f64::NAN, f64::INFINITY]] {
            let eval = |z: &[f64; 2]| {
                let ev = circle(z);
                varying::<2, 4>(ev.f, ev.j, scale, [1.0, 0.0])
            };
            let cfg = NewtonConfig::default();
            for guess in [[1.0, 1.0], [1.5, 0.5], [1.03, 1.72]] {
                let (each, ev_each) = solve(guess, &cfg, eval).unwrap();
                let once = Magnitudes::new(scale, [1.0, 0.0]);
                let mut ev_once = eval(&guess);
                let s = newton(guess, &mut ev_once, &cfg, eval, &once).unwrap();
                assert_eq!(s.z.map(f64::to_bits), each.z.map(f64::to_bits), "{scale:?} {guess:?}");
                assert_eq!((s.iterations, s.evaluations), (each.iterations, each.evaluations));
                assert_eq!(
                    s.residual.to_bits(),
                    each.residual.to_bits(),
                    "{scale:?} {guess:?} {} {}",
                    s.residual,
                    each.residual
                );
                assert_eq!(ev_once.f, ev_each.f);
            }
        }
    }

    #[test]
    fn impossible_system_is_no_assembly_not_a_hang() {
        // x^2 + 1 = 0 has no real root: Newton heads for the minimum at x = 0 where J = 0.
        let f = |z: &[f64; 1]| varying::<1, 2>([z[0] * z[0] + 1.0], [[2.0 * z[0]]], [z[0] * z[0] + 1.0], [1.0]);
        let e = solve([0.7], &NewtonConfig::default(), f).unwrap_err();
        assert!(matches!(e, BlockFailure::NoAssembly { .. }), "{e:?}");
    }

    #[test]
    fn nan_is_reported() {
        let f = |z: &[f64; 1]| varying::<1, 2>([z[0].sqrt() - 1.0], [[0.5 / z[0].sqrt()]], [0.0], [1.0]);
        let e = solve([-1.0], &NewtonConfig::default(), f).unwrap_err();
        assert!(matches!(e, BlockFailure::NonFinite { row: 0, .. }));
    }

    /// A Jacobian that is not finite where the iteration stops is reported, although the
    /// residuals are finite: at a root (`x^(1/3)` at 0, where `d/dx` is infinite) and where no
    /// step can be taken (a NaN slope).
    #[test]
    fn a_jacobian_not_finite_where_it_stops_is_reported() {
        let cube_root = |z: &[f64; 2]| {
            varying::<2, 4>(
                [z[0].cbrt(), z[1] - 1.0],
                [[1.0 / (3.0 * z[0].cbrt().powi(2)), 0.0], [0.0, 1.0]],
                [1.0, 1.0],
                [1.0; 2],
            )
        };
        let e = solve([0.0, 2.0], &NewtonConfig::default(), cube_root).unwrap_err();
        assert!(matches!(e, BlockFailure::NonFinite { row: 0, .. }), "{e:?}");
        // The same where the final correction is made with the analogs' factorisation (which
        // vouches for a finite Jacobian only through a positive pivot ratio).
        let (mut ev, mut kept) = (cube_root(&[0.0, 2.0]), Lu::unfactored());
        let e = newton_keeping_lu([0.0, 2.0], &mut ev, &NewtonConfig::default(), cube_root, &mags, &mut kept);
        assert!(matches!(e, Err(BlockFailure::NonFinite { row: 0, .. })), "{e:?}");
        // A 3x3 block (the general factorisation, whose column magnitudes are not screened):
        // an infinite or NaN entry, anywhere, at a root the guess already meets.
        for (r, c, bad) in [(0, 0, f64::INFINITY), (2, 1, f64::NAN), (1, 2, f64::NEG_INFINITY), (2, 2, f64::NAN)] {
            let block = move |z: &[f64; 3]| {
                let mut j = [[2.0, 0.5, 0.0], [0.0, 3.0, 1.0], [1.0, 0.0, 4.0]];
                j[r][c] = bad;
                varying::<3, 6>([z[0] - 1.0, z[1] - 2.0, z[2] - 3.0], j, [1.0; 3], [1.0; 3])
            };
            let (mut ev, mut kept) = (block(&[1.0, 2.0, 3.0]), Lu::unfactored());
            let e = newton_keeping_lu([1.0, 2.0, 3.0], &mut ev, &NewtonConfig::default(), block, &mags, &mut kept);
            assert!(matches!(e, Err(BlockFailure::NonFinite { row, .. }) if row == r), "{r} {c}: {e:?}");
        }
        let nan_slope = |z: &[f64; 2]| {
            varying::<2, 4>([z[0] - 3.0, z[1] - 1.0], [[1.0, 0.0], [f64::NAN, 1.0]], [1.0, 1.0], [1.0; 2])
        };
        let e = solve([0.0, 0.0], &NewtonConfig::default(), nan_slope).unwrap_err();
        assert!(matches!(e, BlockFailure::NonFinite { row: 1, iterations: 0 }), "{e:?}");
    }

    #[test]
    fn iteration_cap_is_respected() {
        let cfg = NewtonConfig::default().with_max_iterations(1);
        let e = solve([10.0, 10.0], &cfg, circle).unwrap_err();
        assert!(matches!(e, BlockFailure::NoConvergence { iterations: 1, .. }), "{e:?}");
    }

    /// `x^2 = 0`: the Jacobian vanishes at the root, Newton halves the error each step. The
    /// root must come back as singular, not as an inaccurate success.
    #[test]
    fn singular_root_reached_linearly_is_singular() {
        let f = |z: &[f64; 1]| varying::<1, 2>([z[0] * z[0]], [[2.0 * z[0]]], [1.0], [1.0]);
        let e = solve([1.0], &NewtonConfig::default(), f).unwrap_err();
        assert!(matches!(e, BlockFailure::Singular { .. }), "{e:?}");
    }

    /// The same circle in units a billion times smaller: the same iterations and the same
    /// relative answer (an absolute residual test would accept the guess as it is).
    #[test]
    fn tests_are_unit_free() {
        let k = 1e-9;
        let small = |z: &[f64; 2]| {
            let ev = circle(&[z[0], z[1] / k]);
            // Scale the second unknown: y' = k y; rows scaled by k.
            varying::<2, 4>(
                [ev.f[0] * k, ev.f[1] * k],
                [[ev.j[0][0] * k, ev.j[0][1]], [ev.j[1][0] * k, ev.j[1][1]]],
                [ev.keep[0] * k, ev.keep[1] * k],
                [1.0, k],
            )
        };
        let (a, _) = solve([1.0, 1.0], &NewtonConfig::default(), circle).unwrap();
        let (b, _) = solve([1.0, k], &NewtonConfig::default(), small).unwrap();
        assert_eq!(a.iterations, b.iterations);
        assert!((a.z[0] - b.z[0]).abs() <= 4.0 * f64::EPSILON, "{:?} {:?}", a.z, b.z);
        assert!((a.z[1] - b.z[1] / k).abs() <= 8.0 * f64::EPSILON * a.z[1], "{:?} {:?}", a.z, b.z);
    }

    #[test]
    fn out_of_range_configurations_are_named() {
        for (cfg, field) in [
            (NewtonConfig::default().with_residual_tol(f64::INFINITY), "residual_tol"),
            (NewtonConfig::default().with_residual_tol(f64::NAN), "residual_tol"),
            (NewtonConfig::default().with_step_tol(-1.0), "step_tol"),
            (NewtonConfig::default().with_singular_tol(f64::NAN), "singular_tol"),
            (NewtonConfig::default().with_min_damping(0.0), "min_damping"),
        ] {
            assert_eq!(cfg.invalid_field(), Some(field));
            let e = solve([1.0, 1.0], &cfg, circle).unwrap_err();
            assert_eq!(e, BlockFailure::InvalidConfig { field });
        }
    }

    /// `sin q = 1/2`, a pin on a unit crank at height one half: roots `pi/6` and `5 pi/6`, every
    /// turn. Its equation repeats every turn of `q` when `turns` says so.
    fn pin_solve(guess: f64, turns: bool) -> Solved<1> {
        let eval = |z: &[f64; 1]| BlockEval { f: [z[0].sin() - 0.5], j: [[z[0].cos()]], keep: [] };
        let mags = Magnitudes::new([1.5], [1.0]).with_turns([turns]);
        let mut ev: BlockEval<1, 0> = eval(&[guess]);
        newton([guess], &mut ev, &NewtonConfig::default(), eval, &mags).unwrap()
    }

    #[test]
    fn an_angle_carried_turns_away_returns_on_its_guess_turn() {
        // Guesses near the top of the crank, where the cosine (the Jacobian) nearly vanishes:
        // the first Newton step is long.
        let guesses: Vec<f64> = (0..200).map(|k| FRAC_PI_2 + (k as f64 - 99.5) * 1e-4).collect();
        let leapt = guesses.iter().filter(|&&g| (pin_solve(g, false).z[0] - g).abs() > PI).count();
        assert!(leapt > 20, "only {leapt} of the unmarked solves ended over half a turn out");
        for g in guesses {
            let q = pin_solve(g, true).z[0];
            assert!((q - g).abs() <= PI, "guess {g}: {q}");
            // One of the two roots of the guess's turn, to rounding.
            let root = if q < FRAC_PI_2 { PI / 6.0 } else { 5.0 * PI / 6.0 };
            assert!((q - root).abs() <= 2.0 * f64::EPSILON, "guess {g}: {q} vs {root}");
        }
    }

    #[test]
    fn a_mistaken_turn_mark_cannot_move_a_root() {
        // `q^3 = 1000`: one root, at 10, reached from 1 in several steps. Marked as if it
        // repeated every turn, its move to the guess's turn (10 - 2 pi) is no root: undone.
        let eval = |z: &[f64; 1]| BlockEval { f: [z[0].powi(3) - 1000.0], j: [[3.0 * z[0] * z[0]]], keep: [] };
        let mags = Magnitudes::new([1000.0], [1.0]).with_turns([true]);
        let mut ev: BlockEval<1, 0> = eval(&[1.0]);
        let s = newton([1.0], &mut ev, &NewtonConfig::default(), eval, &mags).unwrap();
        assert!(s.iterations > 1);
        assert!((s.z[0] - 10.0).abs() <= 8.0 * f64::EPSILON, "{}", s.z[0]);
        assert_eq!(ev.f, eval(&s.z).f, "the evaluation is the returned position's");
    }
}
