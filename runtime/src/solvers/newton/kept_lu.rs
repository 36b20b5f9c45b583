//! How the correction at a converged iterate is computed ([`LastStep`]): the iteration's own
//! row-equilibrated step ([`RowSteps`]), or the factorisation the analogs use, kept for them
//! ([`KeptLu`]: a block factorises its Jacobian at the root once).

use super::scales::BlockEval;
use super::step::{MAX_UNCHECKED_CORRECTION, newton_step};
use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::lu::{Lu, RowScales};

/// How the correction at a converged iterate is computed: the step that ends the iteration,
/// applied to the returned position. Only that step asks it (`correction`), so whatever it keeps
/// describes the current evaluation until the evaluation changes (`forget`). An iteration that
/// ends otherwise has kept nothing and says so (`forget` again: measured 12 instructions
/// cheaper on the class IV block than leaving `keep` to test it), and `keep` makes it.
pub(super) trait LastStep<const N: usize, const K: usize, J> {
    /// The iteration's Newton step at `ev` (see [`newton_step`]), factorised where the solve
    /// factorises its steps.
    fn step(&mut self, ev: &BlockEval<N, K, J>, rows: &RowScales<N>, unit: &[f64; N]) -> ([f64; N], f64);
    /// The correction `-J^-1 f` at `ev` (rows equilibrated by `rows`, the unknowns' units
    /// `unit`, scaled residual `rho`) and the smallest pivot of its factorisation.
    fn correction(
        &mut self,
        ev: &BlockEval<N, K, J>,
        rows: &RowScales<N>,
        unit: &[f64; N],
        rho: f64,
    ) -> ([f64; N], f64);
    /// The evaluation last corrected is not the one returned: nothing it factorised is valid.
    fn forget(&mut self);
    /// Makes what is kept describe `ev`, the returned evaluation.
    fn keep(&mut self, ev: &BlockEval<N, K, J>);
    /// Whether what the last correction factorised shows the current evaluation's Jacobian to
    /// be finite (then it need not be scanned).
    fn finite_jacobian(&self) -> bool;
}

/// The iteration's own row-equilibrated step, factorised into the solve's slot `.0` (see
/// [`BlockJacobian::Work`]); nothing is kept.
pub(super) struct RowSteps<'a, W>(pub(super) &'a mut W);

impl<const N: usize, const K: usize, J: BlockJacobian<N>> LastStep<N, K, J> for RowSteps<'_, J::Work> {
    #[inline(always)]
    fn step(&mut self, ev: &BlockEval<N, K, J>, rows: &RowScales<N>, unit: &[f64; N]) -> ([f64; N], f64) {
        newton_step(ev, rows, unit, self.0)
    }
    #[inline(always)]
    fn correction(
        &mut self,
        ev: &BlockEval<N, K, J>,
        rows: &RowScales<N>,
        unit: &[f64; N],
        _rho: f64,
    ) -> ([f64; N], f64) {
        newton_step(ev, rows, unit, self.0)
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
pub(super) struct KeptLu<'a, const N: usize> {
    pub(super) lu: &'a mut Lu<N>,
    /// Whether `lu` is the factorisation of the evaluation last corrected.
    pub(super) valid: bool,
}

impl<const N: usize, const K: usize> LastStep<N, K, [[f64; N]; N]> for KeptLu<'_, N> {
    /// A dense step factorises nothing it keeps.
    #[inline(always)]
    fn step(&mut self, ev: &BlockEval<N, K>, rows: &RowScales<N>, unit: &[f64; N]) -> ([f64; N], f64) {
        newton_step(ev, rows, unit, &mut ())
    }
    #[inline(always)]
    fn correction(&mut self, ev: &BlockEval<N, K>, rows: &RowScales<N>, unit: &[f64; N], rho: f64) -> ([f64; N], f64) {
        if rho > MAX_UNCHECKED_CORRECTION {
            // A residual above the rounding level means, for all but an ill-conditioned block,
            // a correction above it too, which is checked by a new evaluation whose Jacobian
            // the analogs then need factorised: a factorisation kept here would be discarded.
            // The cheaper row-equilibrated step instead; `keep` factorises what is returned
            // (whichever way the guess goes, only the cost differs).
            self.valid = false;
            return newton_step(ev, rows, unit, &mut ());
        }
        let cols = refactor_columns(self.lu, ev);
        self.valid = true;
        let pivot = if short_column(&cols, rows, unit) { 0.0 } else { self.lu.pivot_ratio() };
        (self.lu.solve(ev.f.map(|v| -v)), pivot)
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
/// Returns the magnitudes, for [`short_column`].
#[inline(always)]
fn refactor_columns<const N: usize, const K: usize>(lu: &mut Lu<N>, ev: &BlockEval<N, K>) -> [f64; N] {
    let cols: [f64; N] = core::array::from_fn(|c| {
        let mut m = 0.0f64;
        for row in &ev.j {
            let a = row[c].abs();
            m = if a > m { a } else { m };
        }
        m
    });
    lu.refactor_cols(&ev.j, cols);
    cols
}

/// Whether a column of largest magnitude `cols[c]`, in its unknown's unit `unit[c]`, is at
/// most the rounding (`eps`) of the sum of the row magnitudes: the cheap test (a multiplication
/// per column, a minimum, one comparison) that a correction's pivot must be taken for 0, so
/// that the iteration's end judges the column against each row's magnitude
/// (`iterate::angle_not_determined`, which implies this). The equilibration by the columns'
/// magnitudes hides such a column (divided by its own tiny magnitude, it is as long as any):
/// the column of a link `l @ q` below the rounding of its loop, whose angle the data do not
/// determine (a rocker of `1e-20` whose pivot the coupler's end reaches was `1.4999999986` rad,
/// near its guess). A length's column, a direction in the length's unit (its loop's
/// magnitude), is about its rows' magnitudes and never passes. A NaN column is passed over
/// (its factorisation's pivot ratio is 0 anyway).
#[inline(always)]
fn short_column<const N: usize>(cols: &[f64; N], rows: &RowScales<N>, unit: &[f64; N]) -> bool {
    let mut sum = 0.0;
    let mut least = f64::INFINITY;
    for c in 0..N {
        sum += rows.s[c];
        let v = cols[c] * unit[c];
        least = if v < least { v } else { least };
    }
    least <= f64::EPSILON * sum
}

#[cfg(test)]
mod tests {
    use super::super::newton_keeping_lu;
    use super::super::test_blocks::{circle, in_place, mags, solve, sphere};
    use super::*;
    use crate::solvers::lu::max_abs;
    use crate::solvers::newton::{NewtonConfig, NewtonStop};

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
        ) -> NewtonStop {
            let mut kept = Lu::unfactored();
            let mut ev = eval(&guess);
            let s = newton_keeping_lu(guess, &mut ev, cfg, in_place(eval), &mags, &mut kept).unwrap();
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
            assert_eq!(check(guess, &cfg, circle), NewtonStop::ResidualTolerance);
        }
        for guess in [[1.2, 0.9, 1.1], [1.0, 1.0, 1.0], [1.0 + 1e-9, 1.0, 1.0 - 1e-9]] {
            assert_eq!(check(guess, &cfg, sphere), NewtonStop::ResidualTolerance);
        }
        let unreachable = NewtonConfig { residual_tol: 0.0, ..cfg };
        assert_eq!(check([1.2, 0.9, 1.1], &unreachable, sphere), NewtonStop::StepTolerance);
    }
}
