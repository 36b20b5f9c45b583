//! The iteration ([`iterate`]): Newton steps from a guess that does not meet the tolerance, until
//! the residual or the step is small enough, and the end of a converged iteration (its last
//! correction, a root reached only linearly, an angle carried turns away).

use super::config::NewtonConfig;
use super::diagnose::{jacobian_non_finite, non_finite, residual_non_finite};
use super::kept_lu::LastStep;
use super::norms::{beyond_half_turn, scaled_norms, scaled_residual, scaled_step, sum_sq_scaled};
use super::report::{BlockFailure, NewtonStop, Solved};
use super::scales::{BlockEval, Magnitudes, MagnitudesOf, fallback_rows, magnitudes_at, rows_at, unjudged};
use super::state::Iter;
use super::step::{MAX_UNCHECKED_CORRECTION, evaluated_correction};
use super::trace::{SolvePath, note};
use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::turns::unwrap_to_turn;

/// The scaled residual may exceed `residual_tol` by this factor when the iteration stops on the
/// step test (rows whose terms are much larger than their derivatives have a higher floor).
pub(super) const FLOOR_FACTOR: f64 = 1e3;

/// A final step this large relative to the previous one means linear, not quadratic,
/// convergence.
pub(super) const LINEAR_CONTRACTION: f64 = 0.1;

/// Iterations taken past the residual tolerance when it was reached only linearly with a
/// regular Jacobian. Just inside a limit position Newton approaches the root linearly (each
/// step about half the last) until it is nearer to it than to its twin across the fold, which
/// is about where the residual meets the tolerance; from there it converges quadratically
/// within two or three steps. At a singular root the steps keep halving: four more halvings
/// confirm it.
const LINEAR_EXTRA: u32 = 4;

/// Newton iterations from `z0`, whose evaluation is `ev` (updated in place: `eval` writes each
/// trial's evaluation over it; only the descent's failed searches restore it from a copy). The generated code calls it through
/// [`newton`](super::newton) when the guess does not meet the tolerance; the correction at a converged
/// iterate comes from `last`. The guess is borrowed: a large block's is a kilobyte, which passed
/// by value to this out-of-line function would be copied.
///
/// The common path (a full Newton step accepted, then convergence) runs in this one function;
/// the rare paths (backtracking, descent, failures, a final correction that must be checked)
/// are out of line.
#[cold]
#[inline(never)]
#[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what lets NaN through
pub(super) fn iterate<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z0: &[f64; N],
    ev: &mut BlockEval<N, K, J>,
    cfg: &NewtonConfig,
    mut eval: impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
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
        z: *z0,
        guess: z0,
        // The caller's evaluation, not a copy: the iteration updates it in place.
        ev,
        iterations: 0,
        evaluations: 1,
        prev_step: f64::INFINITY,
        slow_run: 0,
        rho_mark: f64::INFINITY,
        prev_rho: f64::INFINITY,
        judged: None,
        past_tolerance: 0,
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
            None if it.iterations == 0 => (rho0, sum_sq_scaled(&it.ev.f, rows)),
            None => scaled_norms(&it.ev.f, rows),
        };
        // A residual that is not finite makes the sum of squares infinite or NaN (which it
        // reports as infinite); so does an overflow, for which the search finds no row. Terms
        // too large for `f64` are told from an expression outside its domain there.
        if !(phi < f64::INFINITY)
            && let Some(row) = residual_non_finite(it.ev)
        {
            return Err(non_finite(row, it.iterations, m, it.ev, &it.z));
        }
        if rho <= cfg.residual_tol {
            // Converged: the last correction, from the factorisation `last` keeps.
            let (dz, pivot) = last.correction(it.ev, rows, &m.unit, rho);
            let step = scaled_step(&dz, &it.z, &m.unit);
            let again = it.past_tolerance < LINEAR_EXTRA && it.iterations < cfg.max_iterations;
            if !(again && pivot > cfg.singular_tol && it.reached_linearly(step, cfg)) {
                return it.finish(
                    &dz,
                    step,
                    pivot,
                    rho,
                    m,
                    s,
                    NewtonStop::ResidualTolerance,
                    cfg,
                    &mut eval,
                    mags,
                    last,
                );
            }
            // Reached linearly, yet the Jacobian here is regular by the tolerance: perhaps a
            // root just inside a limit position (see `LINEAR_EXTRA`). A few more steps tell.
            note(SolvePath::PastTolerance);
            it.past_tolerance += 1;
            last.forget();
        }
        let (dz, pivot) = last.step(it.ev, rows, &m.unit);
        let step = scaled_step(&dz, &it.z, &m.unit);
        // At the rounding floor the step no longer shrinks below `step_tol` or the residual no
        // longer decreases (a singular root still divides it by about four per iteration).
        let stagnant = rho >= 0.5 * it.prev_rho;
        if (step <= cfg.step_tol || stagnant) && rho <= floor {
            last.forget();
            return it.finish(&dz, step, pivot, rho, m, s, NewtonStop::StepTolerance, cfg, &mut eval, mags, last);
        }
        if it.iterations >= cfg.max_iterations {
            // In magnitudes too small or too large to judge the residual, the cap or a stall says
            // nothing of the mechanism: the magnitudes are the failure (see `scales::unjudged`).
            if let Some(fail) = unjudged(mags, m, it.ev, &it.z, cfg) {
                return Err(fail);
            }
            let capped = it.capped(rho, s, cfg);
            // A stall away from every root is solved again from restarts by the caller
            // (`restarts::iterate_restarting`).
            return Err(capped);
        }
        if it.iterations == cfg.max_iterations / 2 {
            it.rho_mark = rho;
        }
        let newton_ok = pivot > cfg.singular_tol * 1e-3 && step.is_finite();
        // At the rounding floor only the Newton step is worth trying.
        let moved = (newton_ok && it.full_step(&dz, pivot, rows, fixed_rows, phi, cfg, &mut eval))
            || (rho > floor && it.descend(rows, &m.unit, cfg, &mut eval));
        if !moved {
            if rho <= floor {
                // No step decreases a residual already at its rounding floor.
                note(SolvePath::AtFloor);
                last.forget();
                return it.finish(&dz, step, pivot, rho, m, s, NewtonStop::StepTolerance, cfg, &mut eval, mags, last);
            }
            if let Some(fail) = unjudged(mags, m, it.ev, &it.z, cfg) {
                return Err(fail);
            }
            let stalled = it.stalled(rho, pivot, s, cfg);
            return Err(stalled);
        }
        let slow = newton_ok && step > LINEAR_CONTRACTION * it.prev_step;
        it.slow_run = if slow { it.slow_run + 1 } else { 0 };
        it.prev_step = if newton_ok { step } else { f64::INFINITY };
        it.prev_rho = rho;
        it.iterations += 1;
    }
}

impl<const N: usize, const K: usize, J: BlockJacobian<N>> Iter<'_, N, K, J> {
    /// Ends a converged iteration judged in the magnitudes `m` (whose row scales, or the row
    /// sums that replace invalid ones, are `s`): refuses magnitudes too small or too large to
    /// judge it (`scales::unjudged`), diagnoses linear convergence (a singular root), then
    /// applies the last correction `dz`. A correction far below the tolerance is applied as it
    /// is; a larger one is checked by a new evaluation (so the Jacobian and kept values match
    /// the returned position) and undone if it made the residual worse. The iteration is
    /// borrowed, not moved into its end (its position is a kilobyte for a large block).
    #[allow(clippy::too_many_arguments)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what sends NaN to the cold path
    #[inline(always)]
    pub(super) fn finish(
        &mut self,
        dz: &[f64; N],
        step: f64,
        pivot: f64,
        rho: f64,
        m: &Magnitudes<N>,
        s: &[f64; N],
        termination: NewtonStop,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
        mags: &impl MagnitudesOf<N, K, J>,
        last: &mut impl LastStep<N, K, J>,
    ) -> Result<Solved<N>, BlockFailure> {
        if !last.finite_jacobian()
            && let Some(row) = jacobian_non_finite(self.ev)
        {
            return Err(non_finite(row, self.iterations, m, self.ev, &self.z));
        }
        // Met in magnitudes too small or too large to judge it: no root (see `scales::unjudged`).
        if let Some(fail) = unjudged(mags, m, self.ev, &self.z, cfg) {
            return Err(fail);
        }
        if self.reached_linearly(step, cfg) && self.iterations > 0 {
            // Newton converges quadratically to a regular root; linearly (each step a fixed
            // fraction of the previous one) only where the Jacobian is singular at the root,
            // and the position is then only known to about the size of the last step.
            return Err(self.singular(rho, pivot, s, cfg));
        }
        // NaN is no regular pivot.
        if !(pivot > cfg.singular_tol) {
            self.end_at_small_pivot(dz, step, pivot, rho, m, s, cfg, eval, mags, last)?;
        } else if step.is_finite() && step > 0.0 {
            if step <= MAX_UNCHECKED_CORRECTION {
                // A quadratically converging iteration often ends with a correction at the
                // rounding level: the last evaluation holds at `z` to rounding.
                note(SolvePath::UncheckedCorrection);
                for c in 0..N {
                    self.z[c] += dz[c];
                }
            } else {
                last.forget();
                self.checked_correction(dz, rho, cfg, eval, mags);
            }
        }
        // After one step the test is skipped (it would cost the common path: a solve from a
        // sweep's prediction usually takes one step). One step that carries an angle over half
        // a turn follows a linearisation that is off there by about the sine's own size, so it
        // ends within the tolerance of a root only from a set of guesses about the tolerance
        // wide; the position is right even then, only on another turn.
        if self.iterations > 1 && beyond_half_turn(&self.z, self.guess) {
            self.back_to_guess_turns(rho, cfg, eval, mags, last)?;
        }
        // An angle carried beyond the precise bound from a guess inside it is not resolved
        // there: a root of a block whose angle every value closes (a link shorter than the
        // tolerance of its loop, a final correction of 1e283 rad through a pivot of 0), or a
        // root on a turn where doubles are coarser than the tolerance. One comparison per
        // unknown, or-ed, on values at hand.
        if past_precise_angle(&self.z, self.guess, &m.turns, cfg.largest_precise_angle()) {
            return Err(self.past_precise(rho, pivot, s, &m.turns, cfg));
        }
        last.keep(self.ev);
        Ok(Solved { z: self.z, iterations: self.iterations, evaluations: self.evaluations, residual: rho, termination })
    }

    /// The end of a converged iteration whose last factorisation's pivot (`pivot`) is at most
    /// the singular tolerance (or NaN): where an angle's Jacobian column is below the rounding
    /// of every row ([`angle_not_determined`]) the block's singular position, as the closed form
    /// reports a link below the rounding of its loop; otherwise the final correction `dz`
    /// (scaled size `step`), checked by a new evaluation.
    ///
    /// An iteration that stopped on the step test with its residual `rho` above the tolerance
    /// (within [`FLOOR_FACTOR`] times it: no step decreased it further) and that still misses
    /// the tolerance after that correction, on its guess's turns, has stalled at a singular
    /// point of its equations, not reached a root: the block's singular position. (A dyad whose
    /// rocker is `1e-10` of its loop stopped so with the rocker along the coupler, where the
    /// exact triangle has it at right angles, `3.139` rad for `pi / 2`: the loop open by the
    /// rocker's whole length, returned as a position.) The angles are moved to their guesses'
    /// turns first, as [`Self::finish`] moves them, where a move may close the loop.
    #[cold]
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn end_at_small_pivot(
        &mut self,
        dz: &[f64; N],
        step: f64,
        pivot: f64,
        rho: f64,
        m: &Magnitudes<N>,
        s: &[f64; N],
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
        mags: &impl MagnitudesOf<N, K, J>,
        last: &mut impl LastStep<N, K, J>,
    ) -> Result<(), BlockFailure> {
        if angle_not_determined(&self.ev.j, s, &m.unit, &m.turns) {
            return Err(self.undetermined(rho, cfg));
        }
        if step.is_finite() && step > 0.0 {
            last.forget();
            self.checked_correction(dz, rho, cfg, eval, mags);
        }
        if rho > cfg.residual_tol {
            if self.iterations > 1 && beyond_half_turn(&self.z, self.guess) {
                self.back_to_guess_turns(rho, cfg, eval, mags, last)?;
            }
            let missed = residual_in(&self.ev.f, s);
            if missed > cfg.residual_tol {
                return Err(self.singular(missed, pivot, s, cfg));
            }
        }
        Ok(())
    }

    /// Whether the iteration ends on a root it reached only linearly (each step a fixed fraction
    /// of the previous one), whose position is then known only to about the size of the last
    /// step (the residual of a row can round to zero before the unknowns settle). Steps at the
    /// rounding level are noise, not evidence of linear convergence: they are not counted
    /// however small the tolerances.
    #[inline(always)]
    pub(super) fn reached_linearly(&self, step: f64, cfg: &NewtonConfig) -> bool {
        let visible = FLOOR_FACTOR * cfg.residual_tol.max(cfg.step_tol).max(16.0 * f64::EPSILON);
        let slow = self.prev_step.is_finite() && step > LINEAR_CONTRACTION * self.prev_step;
        !step.is_finite()
            || (slow && step > visible)
            || (self.slow_run >= 2 && self.prev_step.is_finite() && self.prev_step > visible)
    }

    /// Moves every unknown whose equations repeat every turn (see [`Magnitudes::turns`](super::scales::Magnitudes::turns)) and
    /// that ended more than half a turn from its guess to the guess's turn. A long Newton step
    /// (from a near-singular Jacobian far from the root) can carry an angle many turns out.
    /// The position is the same; its numbers are not: many turns out the spacing of doubles is
    /// coarser. So the block is evaluated and corrected once more on the guess's turn, which
    /// also makes the evaluation describe the returned position. The move is kept only if the
    /// residual there, corrected or not, is no worse than `rho` (or the tolerance): it always
    /// is for an equation that repeats, so a mistaken mark could not return a wrong position.
    ///
    /// An angle that moved so far may be one the block does not determine (see
    /// [`Self::moved_angle_undetermined`]): then no position is returned but the block's
    /// singular position, as the closed form reports it.
    #[cold]
    #[inline(never)]
    fn back_to_guess_turns(
        &mut self,
        rho: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
        mags: &impl MagnitudesOf<N, K, J>,
        last: &mut impl LastStep<N, K, J>,
    ) -> Result<(), BlockFailure> {
        let (before, after, fallback);
        let turns = magnitudes_at!(mags, self.ev, before).turns;
        if self.moved_angle_undetermined(&turns, cfg, eval, mags) {
            return Err(self.undetermined(rho, cfg));
        }
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
            return Ok(());
        }
        note(SolvePath::TurnsMoved);
        last.forget();
        let bound = rho.max(cfg.residual_tol);
        eval(&self.z, self.ev);
        self.evaluations += 1;
        let m = magnitudes_at!(mags, self.ev, after);
        let rows = rows_at!(m, self.ev, fallback);
        let moved_rho = scaled_residual(&self.ev.f, rows);
        let (dz, _) = last.step(self.ev, rows, &m.unit);
        let finite = dz.iter().all(|v| v.is_finite());
        let corrected = finite
            && evaluated_correction(&mut self.z, self.ev, &dz, bound, eval, mags, &mut self.evaluations).is_some();
        // NaN fails the comparison: not kept.
        let kept = corrected || moved_rho <= bound;
        if !kept {
            // Not a position of the block: back to where the iteration ended.
            note(SolvePath::TurnsUndone);
            self.z = unmoved;
            eval(&self.z, self.ev);
            self.evaluations += 1;
        }
        Ok(())
    }

    /// Whether an angle (`turns`) that the iteration carried more than half a turn from its
    /// guess closes the block within the residual tolerance at another angle too: the block
    /// evaluated with that angle alone turned by [`PROBE_TURN`] from its root (on the guess's
    /// turn), the others where the iteration ended. A link shorter than the tolerance of its
    /// loop (a coupler of `1e-20` on a four-bar of size 1 whose crank pin lies on the rocker's
    /// reach) closes it at every angle, and the final steps, through a column of its own size,
    /// carry its angle anywhere (`-5468` rad): the data do not determine it. A determined
    /// angle's terms change by about its link's length there, far beyond the tolerance. Each
    /// such angle is probed by one evaluation, and the evaluation is made again at the end
    /// position after any probe, so that it describes the position returned.
    #[cold]
    #[inline(never)]
    fn moved_angle_undetermined(
        &mut self,
        turns: &[bool; N],
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
        mags: &impl MagnitudesOf<N, K, J>,
    ) -> bool {
        let (mut undetermined, mut probed) = (false, false);
        for c in (0..N).filter(|&c| turns[c] && (self.z[c] - self.guess[c]).abs() > core::f64::consts::PI) {
            let (z, g) = (self.z[c], self.guess[c]);
            // The root on the guess's turn; an angle too far out for its turns to be counted
            // in doubles has no root to speak of: any angle probes it, the guess's.
            let on_turn = unwrap_to_turn(z, g);
            let root = if (on_turn - g).abs() < (z - g).abs() { on_turn } else { g };
            let mut probe = self.z;
            probe[c] = root + PROBE_TURN;
            eval(&probe, self.ev);
            self.evaluations += 1;
            probed = true;
            let (current, fallback);
            let m = magnitudes_at!(mags, self.ev, current);
            let rows = rows_at!(m, self.ev, fallback);
            // Written so that a NaN fails.
            if scaled_residual(&self.ev.f, rows) <= cfg.residual_tol {
                undetermined = true;
                break;
            }
        }
        // A length's move probes nothing (its evaluation is still the end position's).
        if probed {
            eval(&self.z, self.ev);
            self.evaluations += 1;
        }
        undetermined
    }

    /// The failure of a block that closes at every value of an angle (see
    /// [`Self::moved_angle_undetermined`]): singular, with a zero pivot ratio, as the closed
    /// form reports such a block (the factorisation's ratio is of the columns scaled to their
    /// magnitudes, in which the angle's column is as long as any).
    #[cold]
    #[inline(never)]
    fn undetermined(&self, rho: f64, cfg: &NewtonConfig) -> BlockFailure {
        BlockFailure::Singular {
            row: 0,
            iterations: self.iterations,
            residual: rho,
            pivot_ratio: 0.0,
            tolerance: cfg.singular_tol,
        }
    }

    /// The failure of a converged iteration that carried an angle past the precise bound (see
    /// [`past_precise_angle`]): where the Jacobian there is singular by the tolerance, the
    /// angle is not determined (every value closes the block), a singular position as the
    /// closed form reports it; otherwise a root on a turn too far out to be resolved, the
    /// angle's [`BlockFailure::TooManyTurns`].
    #[cold]
    #[inline(never)]
    fn past_precise(&self, rho: f64, pivot: f64, s: &[f64; N], turns: &[bool; N], cfg: &NewtonConfig) -> BlockFailure {
        // NaN is no regular pivot.
        if pivot.is_nan() || pivot <= cfg.singular_tol {
            return self.singular(rho, pivot, s, cfg);
        }
        // The angle farthest out (a length's value says nothing of turns).
        let angles = (0..N).filter(|&c| turns[c]).map(|c| self.z[c]);
        let value = angles.max_by(|a, b| a.abs().total_cmp(&b.abs())).unwrap_or(0.0);
        BlockFailure::TooManyTurns { value }
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
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
        mags: &impl MagnitudesOf<N, K, J>,
    ) {
        evaluated_correction(&mut self.z, self.ev, dz, rho.max(cfg.residual_tol), eval, mags, &mut self.evaluations);
    }
}

/// Whether the Jacobian `j` has the column of an angle (`turns`) whose every entry, in the
/// angle's unit (`unit`: a radian), is at most the rounding (`eps`) of its row's magnitude
/// (`s`): the column of a link `l @ q` is the link's `l` turned a quarter, as long as the link
/// at every angle, so such a link is below the rounding of its loop and every angle of it
/// closes the loop to that rounding (the data do not determine it), or the angle's equations
/// are stationary in it to rounding (a singular position). The factorisation the analogs use
/// divides each column by its largest entry, which makes a uniformly short column as long as
/// any, so its pivot ratio does not see it; that of the iteration's own steps (rows divided by
/// their magnitudes) does, which is what sends a converged iteration here. A length's column
/// (a direction, pure numbers) is never compared. NaN fails.
fn angle_not_determined<const N: usize, J: BlockJacobian<N>>(
    j: &J,
    s: &[f64; N],
    unit: &[f64; N],
    turns: &[bool; N],
) -> bool {
    let j = j.to_dense();
    (0..N).filter(|&c| turns[c]).any(|c| (0..N).all(|r| j[r][c].abs() * unit[c] <= f64::EPSILON * s[r]))
}

/// The largest residual of `f` in the row magnitudes `s` (a zero residual is zero over a zero
/// magnitude; NaN is passed over: a residual that is not finite is reported otherwise).
fn residual_in<const N: usize>(f: &[f64; N], s: &[f64; N]) -> f64 {
    (0..N).map(|r| if f[r] == 0.0 { 0.0 } else { f[r].abs() / s[r] }).fold(0.0, f64::max)
}

/// How far [`Iter::moved_angle_undetermined`] turns an angle from its root to probe whether
/// the block determines it: 2 rad, no whole fraction of a turn (an equation that repeats every
/// half or third of a turn closes again there), and a chord of `2 sin 1 = 1.68` times the link.
const PROBE_TURN: f64 = 2.0;

/// Whether an angle (an unknown whose equations repeat every turn, `turns`) ended beyond
/// `bound` (the configuration's `largest_precise_angle`) from a guess within it: no angle is
/// resolved to the tolerance there (a guess beyond it is the caller's, diagnosed as too many
/// turns where it fails). NaN counts as within (a non-finite result is reported otherwise).
#[inline(always)]
fn past_precise_angle<const N: usize>(z: &[f64; N], guess: &[f64; N], turns: &[bool; N], bound: f64) -> bool {
    let mut past = false;
    for c in 0..N {
        past |= turns[c] & (z[c].abs() > bound) & (guess[c].abs() <= bound);
    }
    past
}

#[cfg(test)]
mod tests {
    use super::super::newton;
    use super::super::test_blocks::in_place;
    use crate::solvers::newton::{BlockEval, Magnitudes, NewtonConfig, Solved};
    use core::f64::consts::{FRAC_PI_2, PI};

    /// `sin q = 1/2`, a pin on a unit crank at height one half: roots `pi/6` and `5 pi/6`, every
    /// turn. Its equation repeats every turn of `q` when `turns` says so.
    fn pin_solve(guess: f64, turns: bool) -> Solved<1> {
        let eval = |z: &[f64; 1]| BlockEval { f: [z[0].sin() - 0.5], j: [[z[0].cos()]], keep: [] };
        let mags = Magnitudes::new([1.5], [1.0]).with_turns([turns]);
        let mut ev: BlockEval<1, 0> = eval(&[guess]);
        newton([guess], &mut ev, &NewtonConfig::default(), in_place(eval), &mags).unwrap()
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
        let s = newton([1.0], &mut ev, &NewtonConfig::default(), in_place(eval), &mags).unwrap();
        assert!(s.iterations > 1);
        assert!((s.z[0] - 10.0).abs() <= 8.0 * f64::EPSILON, "{}", s.z[0]);
        assert_eq!(ev.f, eval(&s.z).f, "the evaluation is the returned position's");
    }
}
