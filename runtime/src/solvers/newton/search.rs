//! The steps of an iteration that is not converged: the full Newton step when it decreases the
//! squared scaled residual enough, otherwise backtracking along it, and where the Newton step
//! fails, Levenberg-Marquardt steps down to steepest descent.

use super::config::NewtonConfig;
use super::norms::{scaled_norms, sum_sq_scaled};
use super::scales::BlockEval;
use super::state::Iter;
use super::trace::{SolvePath, note};
use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::lu::{Lu, RowScales, boxed_zeros};

/// The smallest pivot of an equilibrated factorisation from which its Newton step is taken
/// to be exact to rounding (the residual `J dz + f` is then a few rounding units of the
/// equations' magnitudes, far below what the descent test can see).
pub(super) const ACCURATE_PIVOT: f64 = 1e-3;

impl<const N: usize, const K: usize, J: BlockJacobian<N>> Iter<'_, N, K, J> {
    /// The full Newton step `dz` (from a factorisation whose smallest pivot is `pivot`) when it
    /// decreases the squared scaled residual enough (Armijo, `c = 1e-4`), otherwise backtracking
    /// along it ([`Iter::search`]); moves and returns `true` on success.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn full_step(
        &mut self,
        dz: &[f64; N],
        pivot: f64,
        rows: &RowScales<N>,
        fixed_rows: bool,
        phi0: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
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
        eval(&trial, self.ev);
        self.evaluations += 1;
        let (rho, phi) = scaled_norms(&self.ev.f, rows);
        if phi <= phi0 + 1e-4 * slope {
            note(SolvePath::FullStep);
            self.z = trial;
            // In scales that stay the same, the next iteration's test of this iterate.
            self.judged = if fixed_rows { Some((rho, phi)) } else { None };
            return true;
        }
        self.rejected(dz, rows, phi0, slope, cfg, eval)
    }

    /// After a rejected full step (its evaluation in `self.ev`): backtracking from half the
    /// step; if that fails too (its last trial's evaluation in `self.ev`), the evaluation at the
    /// unmoved `z` is restored (evaluated again: the same position gives the same values, to the
    /// rounding of a generated block's sines and cosines, which its `NearTrig` rotates back from
    /// the trial's), which the callers' fallbacks read.
    #[allow(clippy::too_many_arguments)]
    #[cold]
    #[inline(never)]
    fn rejected(
        &mut self,
        dz: &[f64; N],
        rows: &RowScales<N>,
        phi0: f64,
        slope: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    ) -> bool {
        if self.search(dz, rows, phi0, slope, 0.5, cfg, eval) {
            return true;
        }
        note(SolvePath::Reevaluated);
        eval(&self.z, self.ev);
        self.evaluations += 1;
        false
    }

    /// Backtracking (Armijo, `c = 1e-4`) along `dz` on the squared scaled residual from the
    /// damping `t` down to the configured minimum, given its value `phi0` and `slope` at the
    /// current iterate; moves and returns `true` on success. Each trial is evaluated in place,
    /// over `self.ev`: on success it holds the accepted trial's evaluation, on failure the last
    /// rejected one's (not the evaluation at the unmoved `z`: the callers restore that).
    #[allow(clippy::too_many_arguments)]
    #[cold]
    #[inline(never)]
    fn search(
        &mut self,
        dz: &[f64; N],
        rows: &RowScales<N>,
        phi0: f64,
        slope: f64,
        mut t: f64,
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    ) -> bool {
        while t >= cfg.min_damping {
            let mut trial = self.z;
            for c in 0..N {
                trial[c] += t * dz[c];
            }
            eval(&trial, self.ev);
            self.evaluations += 1;
            let phi = sum_sq_scaled(&self.ev.f, rows);
            if phi <= phi0 + 1e-4 * t * slope {
                note(SolvePath::SearchAccepted);
                self.z = trial;
                return true;
            }
            t *= 0.5;
        }
        false
    }

    /// Where the Newton step fails (singular Jacobian, no decrease), Levenberg-Marquardt steps
    /// of increasing damping, down to steepest descent: they leave saddles of the squared
    /// residual that a far guess can lead to. The steps are made in the unknowns' units `unit`
    /// (residuals in the rows' units): the damping, a multiple of the identity, then weighs a
    /// length's column as an angle's at every size of the mechanism, where in the lengths' own
    /// units it would weigh a length beside angles by the mechanism's size. Returns `true` when
    /// one decreased the residual; otherwise `self.ev` is the evaluation at the unmoved `z`
    /// still: each failed search's trials are evaluated over it, and it is copied back from a
    /// copy made once (on the heap, like the matrices below) rather than evaluated again after
    /// each of up to four searches, so that the next search starts from the same bits as the
    /// first.
    #[cold]
    #[inline(never)]
    pub(super) fn descend(
        &mut self,
        rows: &RowScales<N>,
        unit: &[f64; N],
        cfg: &NewtonConfig,
        eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    ) -> bool {
        note(SolvePath::Descend);
        let s = &rows.s;
        let (a, g) = normal_equations(self.ev, s, unit);
        let trace: f64 = (0..N).map(|k| a[k][k]).sum();
        if !(trace > 0.0 && trace.is_finite()) {
            return false;
        }
        // The damped copy and its factorisation on the heap too, made once for the four dampings.
        let mut damped = boxed_zeros::<N>();
        let mut lu = Lu::boxed_unfactored();
        // The evaluation at `z`, made a copy of before the first search.
        let mut at_z: Option<Box<BlockEval<N, K, J>>> = None;
        for mu in [1e-9, 1e-6, 1e-3, 1.0] {
            damped.copy_from_slice(&*a);
            for k in 0..N {
                damped[k][k] += mu * trace;
            }
            lu.refactor_scaled(&damped, [1.0; N], [1.0; N]);
            let mut neg_g = g;
            for v in &mut neg_g {
                *v = -*v;
            }
            // Back from the units to the unknowns.
            let mut dz = lu.solve(neg_g);
            for c in 0..N {
                dz[c] *= unit[c];
            }
            if !dz.iter().all(|v| v.is_finite()) {
                continue;
            }
            let phi0 = sum_sq_scaled(&self.ev.f, rows);
            let slope = directional_slope(self.ev, s, &dz);
            if slope.is_nan() || slope >= 0.0 {
                continue;
            }
            let at_z = at_z.get_or_insert_with(|| Box::new(*self.ev));
            if self.search(&dz, rows, phi0, slope, 1.0, cfg, eval) {
                return true;
            }
            note(SolvePath::CopyBack);
            *self.ev = **at_z;
        }
        false
    }
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
        // Each factor in its row's units: `s^2` leaves the range of `f64` (or loses its
        // precision) for magnitudes outside about `1e-154 .. 1e154`, where the residual and the
        // step do not.
        acc += (ev.f[r] / s[r]) * (jd[r] / s[r]);
    }
    2.0 * acc
}

/// `A = B^T B` and `g = B^T D^-1 f` with `B = D^-1 J U`, `D` the row magnitudes and `U` the
/// unknowns' units `unit`: the normal equations of a step in the units (`dz = U y`).
///
/// `A` lives on the heap, as do the dense Jacobian, its damped copy and their factorisation:
/// on the stack they would be four `N x N` matrices, which for the largest blocks (256
/// unknowns, 512 KiB each) overflow a thread's default 2 MiB (this is the cold path of a
/// failing step).
fn normal_equations<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
    s: &[f64; N],
    unit: &[f64; N],
) -> (Box<[[f64; N]; N]>, [f64; N]) {
    // Each column in its unit first (a product by one, exact, for an angle's).
    let mut j = ev.j.to_dense();
    for row in j.iter_mut() {
        for c in 0..N {
            row[c] *= unit[c];
        }
    }
    let mut a = boxed_zeros::<N>();
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
