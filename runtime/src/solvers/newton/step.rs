//! The Newton step of an evaluation, and a final correction kept only where a new evaluation
//! shows it did not make the residual worse.

use super::norms::scaled_residual;
use super::scales::{BlockEval, MagnitudesOf, fallback_rows, magnitudes_at, rows_at};
use super::trace::{SolvePath, note};
use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::lu::RowScales;

/// The largest scaled final correction of an iteration applied without evaluating the block
/// again: a few rounding units, below which the values the generated code keeps from the last
/// evaluation (sines and cosines of the unknowns, from which later unknowns and outputs are
/// computed) are as accurate as a new evaluation's (which would rotate them by the correction,
/// a few units in the last place off libm's as they are). A larger correction is checked by a
/// new evaluation (and undone if it made the residual worse).
pub(super) const MAX_UNCHECKED_CORRECTION: f64 = 16.0 * f64::EPSILON;

/// The Newton step `-J^-1 f` with `J` equilibrated by the row magnitudes, and the pivot ratio
/// of `J` equilibrated by the rows' magnitudes and the unknowns' units `unit` (see
/// [`BlockJacobian::newton_step`]), factorising into `work`.
#[inline(always)]
pub(super) fn newton_step<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
    rows: &RowScales<N>,
    unit: &[f64; N],
    work: &mut J::Work,
) -> ([f64; N], f64) {
    if N == 1 {
        // A scalar block needs no factorisation: the equilibrated pivot is `|J| / s * unit`
        // (NaN when `J` and `s` both vanish, which fails every test and is reported as 0; a
        // non-finite `J` is caught by the callers).
        let j = ev.j.first();
        let mut dz = [0.0; N];
        dz[0] = -ev.f[0] / j;
        return (dz, j.abs() / rows.s[0] * unit[0]);
    }
    ev.j.newton_step_in(&ev.f, rows, unit, work)
}

/// Moves `z` (evaluated as `ev`) to `z + dz` and its evaluation, and returns the scaled residual
/// there, when that residual is at most `bound` (NaN fails); otherwise leaves `z` as it is and
/// `ev` its evaluation: a final correction is kept only if it did not make things worse
/// (rounding noise near a singular position can). Counts its evaluations in `evaluations`.
///
/// The new evaluation is written over `ev` in place, with no copy of the old one: a correction
/// undone (rare) evaluates `z` again instead, which gives the values `ev` had to the rounding of
/// a generated block's sines and cosines (its `NearTrig` rotates them back from the
/// correction's), as after a rejected Newton step. A copy kept for the undo would cost every
/// checked correction a copy of the evaluation (kilobytes for a large sparse block).
#[inline(always)]
pub(super) fn evaluated_correction<const N: usize, const K: usize, J: BlockJacobian<N>>(
    z: &mut [f64; N],
    ev: &mut BlockEval<N, K, J>,
    dz: &[f64; N],
    bound: f64,
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, K, J>),
    mags: &impl MagnitudesOf<N, K, J>,
    evaluations: &mut u32,
) -> Option<f64> {
    let mut z1 = *z;
    for c in 0..N {
        z1[c] += dz[c];
    }
    eval(&z1, ev);
    *evaluations += 1;
    let (current, fallback);
    let m = magnitudes_at!(mags, &*ev, current);
    let rho = scaled_residual(&ev.f, rows_at!(m, &*ev, fallback));
    if rho <= bound {
        note(SolvePath::CorrectionKept);
        *z = z1;
        Some(rho)
    } else {
        note(SolvePath::CorrectionUndone);
        eval(z, ev);
        *evaluations += 1;
        None
    }
}
