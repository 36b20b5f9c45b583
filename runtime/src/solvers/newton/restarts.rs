//! Restarts of a block whose Newton iteration stalled away from every root (see
//! [`NewtonConfig::restarts`]).
//!
//! Loop equations are sums of sines and cosines of the angles, so their squared residual has
//! local minima that are not roots: configurations where links lie folded against each other.
//! A damped Newton iteration from a far guess can end in one, where no step decreases the
//! residual, though the loops close elsewhere: up to one guess in sixteen on the class IV group
//! of the tests, and one in ten on a class III triad, of guesses whose angles are each within a
//! radian of an assembly. Reporting "the mechanism cannot be assembled" there would be false.
//! The restarts leave the minimum's basin the way a designer would: they turn one angle at a
//! time by a quarter turn either way and by a half turn, and iterate again from there. Of the
//! roots they reach, the one nearest the guess is returned, on the guess's turns. Only when
//! every restart fails too is the block reported as not assemblable, now with that much more
//! evidence.

use super::config::NewtonConfig;
use super::iterate::iterate;
use super::kept_lu::LastStep;
use super::norms::scaled_residual;
use super::report::{BlockFailure, Solved};
use super::scales::{BlockEval, MagnitudesOf, fallback_rows, magnitudes_at, rows_at};
use super::trace::{SolvePath, note};
use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::turns::{reduce_turn, unwrap_to_turn};
use core::f64::consts::{FRAC_PI_2, PI};

/// The turns of an angle a restart starts from, relative to the guess.
const TURNS: [f64; 3] = [FRAC_PI_2, -FRAC_PI_2, PI];

/// The most angles a block may have for its restarts (three each): the coupled groups of
/// classes III and IV have four to six. A larger coupled block (a ring of loops through a
/// differential) would restart hundreds of times at the cost of a solve each, where one
/// angle turned rarely leaves a fold of so many links: its stall is reported as it is.
const MAX_ANGLES: usize = 8;

/// The iterations a failure reports.
fn iterations_of(fail: &BlockFailure) -> u32 {
    match *fail {
        BlockFailure::NonFinite { iterations, .. }
        | BlockFailure::NoConvergence { iterations, .. }
        | BlockFailure::NoAssembly { iterations, .. }
        | BlockFailure::Singular { iterations, .. } => iterations,
        BlockFailure::InvalidConfig { .. }
        | BlockFailure::TooManyTurns { .. }
        | BlockFailure::Underflow { .. }
        | BlockFailure::Overflow { .. }
        | BlockFailure::Vanished { .. } => 0,
    }
}

/// The squared distance of `z` from the guess `z0` in the units of the unknowns: a marked angle
/// (`turns`) by its difference modulo whole turns, in radians; any other unknown relative to
/// the larger of its guess's magnitude and its unit.
fn distance<const N: usize>(z: &[f64; N], z0: &[f64; N], turns: &[bool; N], unit: &[f64; N]) -> f64 {
    (0..N)
        .map(|c| {
            let d = z[c] - z0[c];
            let d = if turns[c] { reduce_turn(d) } else { d / z0[c].abs().max(unit[c]) };
            d * d
        })
        .sum()
}

/// The iteration from `z0` ([`iterate`], whose guess's evaluation is `ev` and scaled residual
/// `rho0`), solved again from restarts where it stalls away from every root ([`after`]): the
/// iteration of the entry points.
#[inline(always)]
pub(super) fn iterate_restarting<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z0: [f64; N],
    ev: &mut BlockEval<N, K, J>,
    cfg: &NewtonConfig,
    mut eval: impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    mags: &impl MagnitudesOf<N, K, J>,
    last: &mut impl LastStep<N, K, J>,
    rho0: f64,
) -> Result<Solved<N>, BlockFailure> {
    // The iteration calls `eval` itself, not through a reference to it (whose forwarding call
    // is not inlined into the iteration as the evaluation itself is).
    match iterate(&z0, ev, cfg, |z: &[f64; N], e: &mut BlockEval<N, K, J>| eval(z, e), mags, last, rho0) {
        Err(fail) => after(fail, z0, ev, cfg, &mut eval, mags, last),
        solved => solved,
    }
}

/// The result of an iteration from `z0` that failed with `fail`: when it stalled away from every
/// root (`NoAssembly`) and the configuration allows restarts, the root nearest `z0` that a
/// restart reaches (moved to `z0`'s turns), with the work of every restart in its counts;
/// otherwise, or when no restart reaches a root, `fail` itself. `ev` and `last` end as the
/// returned solve leaves them.
#[cold]
#[inline(never)]
fn after<const N: usize, const K: usize, J: BlockJacobian<N>>(
    fail: BlockFailure,
    z0: [f64; N],
    ev: &mut BlockEval<N, K, J>,
    cfg: &NewtonConfig,
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    mags: &impl MagnitudesOf<N, K, J>,
    last: &mut impl LastStep<N, K, J>,
) -> Result<Solved<N>, BlockFailure> {
    let BlockFailure::NoAssembly { iterations, evaluations, .. } = fail else {
        return Err(fail);
    };
    if !cfg.restarts {
        return Err(fail);
    }
    let marks = mags.of(ev);
    let (turns, unit) = (marks.turns, marks.unit);
    if turns.iter().filter(|&&t| t).count() > MAX_ANGLES {
        return Err(fail);
    }
    // The restarts' own iterations do not restart again.
    let once = cfg.with_restarts(false);
    // Every evaluation is counted, the failed restarts' too (a failure does not report them),
    // from the stalled iteration's on.
    let mut evaluations = evaluations;
    let mut counted = |z: &[f64; N], e: &mut BlockEval<N, K, J>| {
        evaluations += 1;
        eval(z, e);
    };
    // Called through a trait object: one instance of the iteration serves the restarts of every
    // evaluation type. (When the iteration itself called this function, the closure's own type
    // would have instantiated both functions anew at every level, without end.)
    let counted: &mut dyn FnMut(&[f64; N], &mut BlockEval<N, K, J>) = &mut counted;
    let mut iterations = iterations;
    let mut best: Option<([f64; N], f64)> = None;
    for c in (0..N).filter(|&c| turns[c]) {
        for turn in TURNS {
            note(SolvePath::Restart);
            let mut g = z0;
            g[c] += turn;
            counted(&g, ev);
            let rho = residual_at(ev, mags);
            match iterate(&g, ev, &once, &mut *counted, mags, last, rho) {
                Ok(s) => {
                    iterations += s.iterations;
                    let d = distance(&s.z, &z0, &turns, &unit);
                    // NaN is never nearer.
                    if best.is_none_or(|(_, b)| d < b) {
                        best = Some((s.z, d));
                    }
                }
                Err(fail) => iterations += iterations_of(&fail),
            }
        }
    }
    let Some((mut z, _)) = best else {
        return Err(fail);
    };
    // One more solve from the root on the guess's turns: it returns at once, and leaves the
    // evaluation and the kept factorisation at the returned position.
    for c in (0..N).filter(|&c| turns[c]) {
        z[c] = unwrap_to_turn(z[c], z0[c]);
    }
    note(SolvePath::RestartReturned);
    counted(&z, ev);
    let rho = residual_at(ev, mags);
    let s = iterate(&z, ev, &once, &mut *counted, mags, last, rho)?;
    Ok(Solved { iterations: iterations + s.iterations, evaluations, ..s })
}

/// The scaled residual of the evaluation `ev` in the block's magnitudes there.
fn residual_at<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
    mags: &impl MagnitudesOf<N, K, J>,
) -> f64 {
    let (current, fallback);
    let m = magnitudes_at!(mags, ev, current);
    let rows = rows_at!(m, ev, fallback);
    scaled_residual(&ev.f, rows)
}

#[cfg(test)]
mod tests {
    use super::super::test_blocks::in_place;
    use crate::solvers::newton::{BlockEval, BlockFailure, Magnitudes, NewtonConfig, Solved, newton};
    use core::f64::consts::PI;

    /// `f(q) = 0.2 + 2 t - 2 t^2` with `t = 1 + cos q`: roots where `cos q = 0.0916...`
    /// (`q = ±1.4791...` every turn), and at `q = π` (`t = 0`) a minimum of `f^2` that is no root
    /// (`f = 0.2`, `f' = 0`), which a guess near it runs into. Solved from `guess`, the angle
    /// marked as repeating every turn when `turns` says so.
    fn folded(guess: f64, turns: bool, cfg: &NewtonConfig) -> Result<Solved<1>, BlockFailure> {
        let eval = |z: &[f64; 1]| {
            let t = 1.0 + z[0].cos();
            BlockEval { f: [0.2 + 2.0 * t - 2.0 * t * t], j: [[-z[0].sin() * (2.0 - 4.0 * t)]], keep: [] }
        };
        let mags = Magnitudes::new([2.2], [1.0]).with_turns([turns]);
        let mut ev: BlockEval<1, 0> = eval(&[guess]);
        newton([guess], &mut ev, cfg, in_place(eval), &mags)
    }

    /// The root `1.4791...` of [`folded`] in closed form: `2 t^2 - 2 t - 0.2 = 0` gives
    /// `t = (1 + sqrt(1.4)) / 2`.
    fn root() -> f64 {
        ((1.0 + 1.4f64.sqrt()) / 2.0 - 1.0).acos()
    }

    #[test]
    fn a_stall_in_a_fold_restarts_to_the_nearest_root_on_the_guess_turn() {
        let cfg = NewtonConfig::default();
        // Just past the fold the nearer root is `2 pi - 1.479` (1.62 rad away, against 1.70 for
        // `1.479`); just before it, `1.479`.
        for (side, root_near) in [(0.04, 2.0 * PI - root()), (-0.04, root())] {
            for k in [-3.0, 0.0, 5.0] {
                let g = PI + side + k * 2.0 * PI;
                // Without restarts (or without the mark that allows them) the fold is reported
                // as no assembly, at the fold's residual.
                let mut stalled = 0;
                for (turns, restarts) in [(true, false), (false, true)] {
                    let e = folded(g, turns, &cfg.with_restarts(restarts)).unwrap_err();
                    let BlockFailure::NoAssembly { iterations, residual, .. } = e else { panic!("{g}: {e:?}") };
                    assert!((residual - 0.2 / 2.2).abs() < 1e-4, "{g}: {residual}");
                    stalled = iterations;
                }
                let s = folded(g, true, &cfg).unwrap();
                let want = root_near + k * 2.0 * PI;
                assert!((s.z[0] - want).abs() <= 1e-14 * (1.0 + want.abs()), "{g}: {} vs {want}", s.z[0]);
                assert!(s.residual <= cfg.residual_tol);
                // The report counts the stalled iteration and every restart.
                assert!(s.iterations > stalled && s.evaluations > s.iterations, "{s:?} after {stalled}");
            }
        }
    }

    #[test]
    fn a_block_without_a_root_is_still_no_assembly() {
        // `2 + cos q = 0` has no root: every restart stalls too, and the first stall is reported.
        let eval = |z: &[f64; 1]| BlockEval { f: [2.0 + z[0].cos()], j: [[-z[0].sin()]], keep: [] };
        let mags = Magnitudes::new([3.0], [1.0]).with_turns([true]);
        let mut ev: BlockEval<1, 0> = eval(&[2.0]);
        let e = newton([2.0], &mut ev, &NewtonConfig::default(), in_place(eval), &mags).unwrap_err();
        let BlockFailure::NoAssembly { residual, .. } = e else { panic!("{e:?}") };
        assert!((residual - 1.0 / 3.0).abs() < 1e-4, "{residual}");
    }

    #[test]
    fn distances_count_angles_modulo_turns_and_lengths_in_their_units() {
        let z0 = [0.1, 10.0];
        let d = super::distance(&[0.1 + 2.0 * PI + 0.5, 12.0], &z0, &[true, false], &[1.0, 1.0]);
        assert!((d - (0.25 + 0.04)).abs() < 1e-12, "{d}");
    }
}
