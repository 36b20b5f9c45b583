//! The norms a block's tests are made with: residuals relative to their rows' magnitudes, steps
//! relative to the unknowns' magnitudes, and the scaled residual of a full system.

use crate::solvers::lu::{RowScales, largest};
use core::f64::consts::PI;

/// `max_i |f_i| / s_i`; NaN propagates, a non-zero residual over a zero scale is infinite.
/// With valid scales, `|f_i| · (1 / s_i)`: the reciprocals the equilibration made once
/// (`RowScales::inv`), by which the Newton step scales the same residuals, not a division per
/// row each time.
#[inline(always)]
pub(super) fn scaled_residual<const N: usize>(f: &[f64; N], rows: &RowScales<N>) -> f64 {
    if !rows.degenerate {
        return largest::<N>(core::array::from_fn(|r| f[r].abs() * rows.inv[r]));
    }
    let s = &rows.s;
    largest::<N>(core::array::from_fn(|r| {
        let a = f[r].abs();
        if a == 0.0 { 0.0 } else { a / s[r] }
    }))
}

/// [`scaled_residual`] and [`sum_sq_scaled`] in one pass. The maximum skips a NaN (one `maxsd`
/// per row): the sum of squares, which the callers test first, does not. Valid scales need no
/// test of a zero residual (measured: the loop without it is 80 instructions a class IV step
/// cheaper than one loop with the test made conditional), nor a division: their reciprocals.
#[inline(always)]
pub(super) fn scaled_norms<const N: usize>(f: &[f64; N], rows: &RowScales<N>) -> (f64, f64) {
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
            let v = f[r] * rows.inv[r];
            let a = v.abs();
            m = if a > m { a } else { m };
            acc += v * v;
        }
    }
    (m, if acc.is_nan() { f64::INFINITY } else { acc })
}

/// `max_j |dz_j| / max(|z_j|, unit_j)`: steps relative to each unknown's magnitude, in its own
/// unit (see [`Magnitudes::unit`](super::scales::Magnitudes::unit), checked); NaN propagates.
#[inline(always)]
pub(super) fn scaled_step<const N: usize>(dz: &[f64; N], z: &[f64; N], unit: &[f64; N]) -> f64 {
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
pub(super) fn beyond_half_turn<const N: usize>(z: &[f64; N], guess: &[f64; N]) -> bool {
    // One comparison per unknown, or-ed: no maximum to carry from one to the next.
    let mut far = false;
    for c in 0..N {
        far |= (z[c] - guess[c]).abs() > PI;
    }
    far
}

/// `sum_i (f_i / s_i)²` (infinite for NaN), by the reciprocals of valid scales as
/// [`scaled_norms`].
pub(super) fn sum_sq_scaled<const N: usize>(f: &[f64; N], rows: &RowScales<N>) -> f64 {
    let mut acc = 0.0;
    for r in 0..N {
        let v = if rows.degenerate { f[r] / rows.s[r] } else { f[r] * rows.inv[r] };
        acc += v * v;
    }
    if acc.is_nan() { f64::INFINITY } else { acc }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A zero residual over a positive scale whose reciprocal overflows (below `1 / f64::MAX`)
    /// is zero in every norm, not `0 * inf` = NaN; a non-zero one is large, not NaN.
    #[test]
    fn a_zero_residual_over_a_scale_without_a_finite_reciprocal_is_zero() {
        let rows = RowScales::new([1.0, 1e-310, 1.0]);
        let f = [0.5, 0.0, -0.25];
        assert_eq!(scaled_residual(&f, &rows), 0.5);
        assert_eq!(scaled_norms(&f, &rows), (0.5, 0.3125));
        assert_eq!(sum_sq_scaled(&f, &rows), 0.3125);
        let g = [0.0, 1e-300, 0.0];
        assert!(scaled_residual(&g, &rows) > 1e9, "{}", scaled_residual(&g, &rows));
        assert!(!scaled_norms(&g, &rows).0.is_nan());
    }
}
