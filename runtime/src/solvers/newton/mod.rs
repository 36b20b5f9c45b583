//! Damped Newton's method for one square block, with diagnostics.
//!
//! The configuration ([`NewtonConfig`]) is separate from the problem (the block's generated
//! evaluation closure) and the outcome carries its diagnostics ([`SolveReport`]): iterations,
//! evaluations, final residual and why it stopped.
//!
//! **Evaluations written in place.** The evaluation closure `eval(z, ev)` writes the evaluation
//! at `z` over the caller's slot `ev`, every field of it: a block's evaluation is hundreds of
//! bytes (a large sparse block's, kilobytes), and one returned by value is made in a temporary
//! and copied wherever the compiler cannot make it in the slot (as for a closure that owns its
//! solve's sine and cosine cache). The solver keeps one slot, the evaluation at the current
//! iterate: a trial is evaluated over it, and where a trial is rejected and the iterate's
//! evaluation is read again, the slot is never left holding the trial's. After a rejected step
//! or an undone final correction (both rare) the iterate is evaluated again: the same values,
//! to the rounding of a generated block's sines and cosines (rotated back from the trial's), at
//! no cost to the common path, where a copy kept for the undo would cost every checked
//! correction a copy of the evaluation. Between the descent's searches (a cold path that reads
//! the iterate's Jacobian again) it is copied back from a copy made once.
//!
//! **The returned evaluation is the last one made.** On every path that returns a solution the
//! slot holds the evaluation made by the last call of `eval`, at the returned position (or,
//! after a final correction at the rounding level, which is applied without evaluating, at the
//! position it corrected). A generated block needs only the second half: after the solve it
//! reads the values it kept and its Jacobian entries from the returned slot, whichever call
//! made that evaluation. The run-time model needs the first half too: its evaluation writes
//! every value of the block into its registers, which it reads after the solve, so they are the
//! last call's, and the returned evaluation's only if the slot holds the last call's. (That is
//! why the compiled block is an independent reference for the model.) The descent's
//! copy-back is always followed by another search's evaluations, or by a failure. The tests
//! of `returned_evaluation` drive the paths that decide which evaluation is returned (shown by
//! the solver's trace of the paths it takes, `trace`, recorded in the unit tests only) and
//! check this.
//!
//! **Scale-free tests.** Every test is made in the units of the problem: residual `i` is divided
//! by its row magnitude `scale_i` (see [`Magnitudes`]), a step in unknown `j` by that
//! unknown's magnitude, and the pivots of the factorisation are those of the Jacobian with its
//! rows divided by their magnitudes and its columns multiplied by the unknowns' units (of the
//! column-equilibrated one for a final correction made with the analogs' factorisation,
//! below): where a block mixes a length (a column of pure numbers) with angles (columns of
//! lengths), the rows' equilibration alone would make its pivots shrink with the mechanism's
//! size. A mechanism in metres, millimetres or micrometres therefore stops at the same relative
//! accuracy, and is judged singular at the same positions.
//!
//! **No silent wrong answer.** Whatever stops the iteration, the final scaled residual is
//! checked; the last Newton correction is applied (a prediction that already meets the
//! tolerance is still corrected once); a root reached with linear convergence (the signature
//! of a singular Jacobian at the root) is reported as singular, not returned as an inaccurate
//! success. Nor is a root judged in magnitudes too small for `f64` to resolve its residual to
//! the tolerance (subnormal ones, or zero where the terms underflowed: an equation of squared
//! lengths below about `1e-156`): the solve fails with `BlockFailure::Underflow`
//! (`scales::unjudged`), tested only where the magnitudes are degenerate. Nor in magnitudes
//! too large for `f64` (infinite where the terms overflowed: the same equation beyond about
//! `1e154`): `BlockFailure::Overflow`, also where the residual itself overflowed, which is
//! told there from an expression outside its domain (`scales::overflowed`). Nor a root with
//! an angle whose Jacobian column is below the rounding of every row's magnitude (the column
//! of a link `l @ q` is as long as the link at every angle: a link below the rounding of its
//! loop, every angle of which closes it): the block's singular position, pivot ratio 0, as the
//! closed form reports it (`iterate::angle_not_determined`; the analogs' factorisation, whose
//! columns are divided by their magnitudes, does not see such a column, and tests it apart).
//! Nor a point where the iteration stalled: stopped on the step test above the residual
//! tolerance, at a Jacobian singular by the tolerance, and still above it after the final
//! correction (`iterate::Iter::end_at_small_pivot`): the block's singular position.
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
//!
//! **Sines and cosines rotated, not recomputed.** A generated block's evaluation asks its
//! solve's `NearTrig` for the sines and cosines of its angles: libm's at the guess, and at every
//! later evaluation the previous one's rotated by the change of the angle when it is small (as
//! Newton's corrections soon are), at a fraction of a libm call and within a few units in the
//! last place of libm's values. The solver sees only the evaluation closure.
//!
//! **The parts**, from the bottom up, each using only parts before it: the configuration
//! (`config`) and what a solve returns (`report`); a block's evaluation and the magnitudes its
//! tests are made in (`scales`), and the norms of those tests (`norms`); the iteration's state
//! (`state`), the Newton step and a correction checked by a new evaluation (`step`), and the
//! final correction from the analogs' kept factorisation (`kept_lu`); the diagnosis of a failed
//! iteration (`diagnose`) and the line search and descent (`search`); the iteration
//! (`iterate`); the restarts of a block that stalled (`restarts`); and here, the entry points
//! ([`newton`], [`newton_with`], [`newton_with_work`], [`newton_keeping_lu`]). Beside them, the
//! trace of the paths a solve took, for the unit tests (`trace`).

mod config;
mod diagnose;
mod iterate;
mod kept_lu;
mod norms;
mod report;
mod restarts;
#[cfg(test)]
mod returned_evaluation;
mod scales;
mod search;
mod state;
mod step;
#[cfg(test)]
mod test_blocks;
mod trace;

pub use config::NewtonConfig;
pub use report::{BlockFailure, NewtonStop, SolveReport, Solved};
pub(crate) use scales::row_vanishes;
pub use scales::{BlockEval, Magnitudes, MagnitudesOf};

use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::lu::{Lu, RowScales};
use kept_lu::{KeptLu, LastStep, RowSteps};
use norms::{scaled_residual, scaled_step};
use scales::{fallback_rows, magnitudes_at, unjudged, unjudged_fixed};
use step::{MAX_UNCHECKED_CORRECTION, evaluated_correction};
use trace::{SolvePath, note};

/// The largest scaled correction applied to an accepted guess without iterating (larger ones,
/// from an ill-conditioned block, are iterated and checked).
const MAX_FREE_CORRECTION: f64 = 1e-6;

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
    let (dz, pivot) = last.correction(ev, rows, unit, rho);
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
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    mags: &impl MagnitudesOf<N, K, J>,
    last: &mut impl LastStep<N, K, J>,
) -> Solved<N> {
    let (mut z, mut evaluations) = (z0, 1);
    let residual = evaluated_correction(&mut z, ev, dz, rho0, eval, mags, &mut evaluations).unwrap_or(rho0);
    last.keep(ev);
    Solved { z, iterations: 0, evaluations, residual, termination: NewtonStop::ResidualTolerance }
}

/// Solves one block from the guess `z0`, whose evaluation the caller has made into `ev`: the
/// iteration updates it in place (`eval(z, ev)` writes the evaluation at `z` over it, every
/// field), and on return it is the evaluation at the returned position ([`Solved`]). The
/// caller's slot, not a value moved through the result or returned by `eval`: a block's
/// evaluation is hundreds of bytes (a large sparse block's, kilobytes). In the common
/// warm-started case this costs one evaluation and one small factorisation: the guess already
/// meets the tolerance and is corrected once by the Newton step (its Jacobian is the one the
/// analogs use). The iteration itself is a separate, out-of-line function.
#[doc(hidden)]
#[inline(always)]
pub fn newton<const N: usize, const K: usize>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K>,
    cfg: &NewtonConfig,
    eval: impl FnMut(&[f64; N], &mut BlockEval<N, K>),
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
    eval: impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    mags: &impl MagnitudesOf<N, K, J>,
) -> Result<Solved<N>, BlockFailure> {
    let mut work = ev.j.work();
    newton_with_work(z0, ev, cfg, eval, mags, &mut work)
}

/// [`newton_with`] whose Newton steps factorise into the caller's `work` (see
/// [`BlockJacobian::Work`]): a compiled sparse block's kernel makes one slot for its solve and
/// its analogs, and each factorisation is written over it, where one made and returned by
/// each step would be copied (kilobytes). On return it holds the last step's factorisation,
/// or none; the analogs factorise over it again.
#[doc(hidden)]
#[inline(always)]
pub fn newton_with_work<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K, J>,
    cfg: &NewtonConfig,
    eval: impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    mags: &impl MagnitudesOf<N, K, J>,
    work: &mut J::Work,
) -> Result<Solved<N>, BlockFailure> {
    newton_last(z0, ev, cfg, eval, mags, &mut RowSteps(work))
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
    eval: impl FnMut(&[f64; N], &mut BlockEval<N, K>),
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
    mut eval: impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    mags: &impl MagnitudesOf<N, K, J>,
    last: &mut impl LastStep<N, K, J>,
) -> Result<Solved<N>, BlockFailure> {
    let (current, fallback);
    let m = magnitudes_at!(mags, ev, current);
    // `rows_at!`, and in its branch for degenerate magnitudes (no branch more on the common
    // path), magnitudes made once that are too small or too large to judge a residual: no root
    // can be told (see `scales::unjudged`). Those of each evaluation are judged where the solve
    // ends.
    let rows = if m.rows.degenerate {
        if let Some(fail) = unjudged_fixed(mags, ev, &z0, cfg) {
            return Err(fail);
        }
        fallback = fallback_rows(&m.rows.s, ev);
        &fallback
    } else {
        &m.rows
    };
    let rho = scaled_residual(&ev.f, rows);
    // NaN fails both tests; an out-of-range tolerance is diagnosed by `iterate`.
    if rho <= cfg.residual_tol
        && cfg.residual_tol <= 1e-3
        && let Some((z, dz, step)) = free_correction(ev, rows, &m.unit, rho, z0, cfg, last)
    {
        // Met in magnitudes too small or too large to judge it: no root (see `scales::unjudged`).
        if let Some(fail) = unjudged(mags, m, ev, &z0, cfg) {
            return Err(fail);
        }
        if step > MAX_UNCHECKED_CORRECTION {
            last.forget();
            return Ok(checked_free_correction(z0, ev, rho, &dz, &mut eval, mags, last));
        }
        note(SolvePath::UncheckedCorrection);
        last.keep(ev);
        return Ok(Solved {
            z,
            iterations: 0,
            evaluations: 1,
            residual: rho,
            termination: NewtonStop::ResidualTolerance,
        });
    }
    restarts::iterate_restarting(z0, ev, cfg, eval, mags, last, rho)
}

#[cfg(test)]
mod tests {
    use super::test_blocks::{circle, solve, varying};
    use super::*;

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

    /// A final correction that makes the residual worse is undone, and the evaluation left in
    /// the caller's slot is the one at the returned position (every field), not the rejected
    /// correction's. The block `x = 1` is evaluated with noise exactly at its root (where the
    /// correction from a guess one part in 10^13 off lands, `x0 + (1 - x0)` being exact).
    #[test]
    fn an_undone_correction_leaves_the_returned_positions_evaluation() {
        let noisy = |z: &[f64; 1]| {
            let f = if z[0] == 1.0 { 1e-9 } else { z[0] - 1.0 };
            BlockEval::<1, 1> { f: [f], j: [[1.0]], keep: [z[0]] }
        };
        let x0 = 1.0 + 1e-13;
        let mags = Magnitudes::new([1.0], [1.0]);
        let mut ev = noisy(&[x0]);
        let s = newton([x0], &mut ev, &NewtonConfig::default(), test_blocks::in_place(noisy), &mags).unwrap();
        assert_eq!(s.z, [x0]);
        assert_eq!(s.residual.to_bits(), (x0 - 1.0).to_bits());
        assert_eq!((ev.f[0].to_bits(), ev.keep), ((x0 - 1.0).to_bits(), [x0]));
        // The guess's evaluation, the correction's and the guess's again.
        assert_eq!(s.evaluations, 3);
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

    /// A block of a length `s` and an angle `q` (a point at `k (2.98, -0.143)` reached by
    /// `s (cos q, sin q)`, a slotted rocker), as large as `k`: its rows' magnitudes and the
    /// length's unit are `4 k`. By powers of two every product and quotient of the solve
    /// scales exactly, so at every size it takes the same iterations to the same angle and the
    /// same length over `k`, bit for bit. The length's Jacobian column is a direction (pure
    /// numbers), the angle's a length: in the rows' units alone the first is `1 / (4 k)`, and
    /// its pivot was below the singularity test at `2^50` and every larger size tried, where
    /// every Newton step was refused and the iteration stalled.
    #[test]
    fn a_length_beside_an_angle_is_solved_alike_at_every_size() {
        let one = slotted_rocker([3.3, 0.0], 1.0);
        assert!(one.iterations > 1, "{one:?}");
        alike_at_every_size([3.3, 0.0], &one, &[-1000, -500, -100, -50, -10, 10, 50, 100, 500, 1000]);
    }

    /// The slotted rocker of the test above from a guess whose length is nearly zero: its
    /// Jacobian is nearly singular there, Newton's step is refused and Levenberg-Marquardt steps
    /// move it away first. Made in the unknowns' units, they are the same at every size (in the
    /// length's own units the damping weighed the length's column by one over the size).
    #[test]
    fn a_descent_from_a_near_singular_guess_is_alike_at_every_size() {
        let guess = [2f64.powi(-47), 0.3];
        let _ = trace::take();
        let one = slotted_rocker(guess, 1.0);
        assert!(trace::take().contains(&SolvePath::Descend), "the guess is not refused");
        alike_at_every_size(guess, &one, &[-1000, -600, -540, -500, -100, -50, -10, 10, 50, 100, 500, 1000]);
    }

    /// The slotted rocker `s (cos q, sin q) = k (2.98, -0.143)` solved from the guess `[s / k,
    /// q]` at size `k`.
    fn slotted_rocker(guess: [f64; 2], k: f64) -> Solved<2> {
        let eval = move |z: &[f64; 2]| {
            let [s, q] = *z;
            let (sin, cos) = q.sin_cos();
            BlockEval::<2, 0> {
                f: [s * cos - 2.98 * k, s * sin + 0.143 * k],
                j: [[cos, -s * sin], [sin, s * cos]],
                keep: [],
            }
        };
        let mags = Magnitudes::new([4.0 * k; 2], [4.0 * k, 1.0]);
        let guess = [guess[0] * k, guess[1]];
        let mut ev = eval(&guess);
        newton(guess, &mut ev, &NewtonConfig::default(), test_blocks::in_place(eval), &mags)
            .unwrap_or_else(|e| panic!("size {k:e}: {e:?}"))
    }

    /// The slotted rocker from `guess` at the sizes `2^e` of `exponents`: the solve `one` of
    /// size 1, bit for bit (powers of two scale every product and quotient exactly).
    fn alike_at_every_size(guess: [f64; 2], one: &Solved<2>, exponents: &[i32]) {
        for &e in exponents {
            let k = 2f64.powi(e);
            let got = slotted_rocker(guess, k);
            assert_eq!((got.iterations, got.evaluations), (one.iterations, one.evaluations), "2^{e}");
            assert_eq!([got.z[0] / k, got.z[1]].map(f64::to_bits), one.z.map(f64::to_bits), "2^{e}");
        }
    }
}
