//! LU factorisation of small fixed-size blocks with row equilibration and a pivot-ratio check.
//!
//! nalgebra's LU only reports failure on an exactly zero pivot; near a dead centre the pivots are
//! tiny but non-zero and the solution is garbage. Here each row is first divided by its scale (the
//! largest magnitude in the row of the augmented system, supplied by the generated code), so the
//! smallest pivot of the equilibrated matrix is a dimension-free measure of how close the block
//! is to singular: [`Lu::pivot_ratio`].

use nalgebra::SMatrix;

/// A factorised `N x N` block: `P D J = L U` with `D` the row equilibration.
#[derive(Clone, Copy, Debug)]
pub struct Lu<const N: usize> {
    lu: SMatrix<f64, N, N>,
    perm: [usize; N],
    inv_scale: [f64; N],
    pivot_ratio: f64,
    negative_det: bool,
}

impl<const N: usize> Lu<N> {
    /// Factorises `j` (rows given as arrays). `scale[i]` is the magnitude row `i` is measured
    /// against; a zero or non-finite scale marks the row as degenerate.
    #[inline]
    pub fn factor(j: &[[f64; N]; N], scale: [f64; N]) -> Self {
        let mut lu = SMatrix::<f64, N, N>::zeros();
        let mut inv_scale = [0.0; N];
        let mut degenerate = false;
        for r in 0..N {
            let s = scale[r];
            let inv = if s > 0.0 && s.is_finite() {
                1.0 / s
            } else {
                degenerate = true;
                0.0
            };
            inv_scale[r] = inv;
            for c in 0..N {
                lu[(r, c)] = j[r][c] * inv;
            }
        }
        let mut perm = [0usize; N];
        for (k, p) in perm.iter_mut().enumerate() {
            *p = k;
        }
        let mut negative_det = false;
        let mut min_pivot = f64::INFINITY;
        for k in 0..N {
            // Partial pivoting.
            let mut best = k;
            let mut best_mag = lu[(k, k)].abs();
            for r in k + 1..N {
                let m = lu[(r, k)].abs();
                if m > best_mag {
                    best = r;
                    best_mag = m;
                }
            }
            if best != k {
                lu.swap_rows(k, best);
                perm.swap(k, best);
                negative_det = !negative_det;
            }
            let pivot = lu[(k, k)];
            if pivot < 0.0 {
                negative_det = !negative_det;
            }
            min_pivot = min_pivot.min(pivot.abs());
            if pivot != 0.0 {
                let inv = 1.0 / pivot;
                for r in k + 1..N {
                    let factor = lu[(r, k)] * inv;
                    lu[(r, k)] = factor;
                    for c in k + 1..N {
                        let v = lu[(k, c)];
                        lu[(r, c)] -= factor * v;
                    }
                }
            }
        }
        let pivot_ratio = if degenerate || !min_pivot.is_finite() { 0.0 } else { min_pivot };
        Lu { lu, perm, inv_scale, pivot_ratio, negative_det }
    }

    /// Factorises `j`, scaling each row by its largest magnitude in the augmented system
    /// `[j | rhs]` (the right-hand sides carry the input's influence, so a block whose own
    /// Jacobian row vanishes while its input row does not is seen as singular).
    #[inline]
    pub fn factor_aug<const M: usize>(j: &[[f64; N]; N], rhs: &[[f64; M]; N]) -> Self {
        let mut scale = [0.0; N];
        for r in 0..N {
            let a = max_abs(j[r]);
            let b = max_abs(rhs[r]);
            scale[r] = if a.is_nan() || b.is_nan() { f64::NAN } else { a.max(b) };
        }
        Self::factor(j, scale)
    }

    /// Smallest pivot of the row-equilibrated matrix, in `[0, ~1]`: `0` when singular. `NaN`
    /// inputs give `0`.
    #[inline]
    pub fn pivot_ratio(&self) -> f64 {
        if self.pivot_ratio.is_nan() { 0.0 } else { self.pivot_ratio }
    }

    /// Sign of the determinant (`true` when negative); the assembly mode of a block.
    #[inline]
    pub fn negative_det(&self) -> bool {
        self.negative_det
    }

    /// Solves `J z = b`.
    #[inline]
    #[allow(clippy::needless_range_loop)] // index loops read like the textbook substitutions
    pub fn solve(&self, b: [f64; N]) -> [f64; N] {
        let mut z = [0.0; N];
        for r in 0..N {
            let p = self.perm[r];
            z[r] = b[p] * self.inv_scale[p];
        }
        for r in 0..N {
            let mut acc = z[r];
            for c in 0..r {
                acc -= self.lu[(r, c)] * z[c];
            }
            z[r] = acc;
        }
        for r in (0..N).rev() {
            let mut acc = z[r];
            for c in r + 1..N {
                acc -= self.lu[(r, c)] * z[c];
            }
            z[r] = acc / self.lu[(r, r)];
        }
        z
    }

    /// Solves `J Z = B` for `M` right-hand sides given as rows `B[r][m]`.
    #[inline]
    pub fn solve_cols<const M: usize>(&self, b: [[f64; M]; N]) -> [[f64; M]; N] {
        let mut out = [[0.0; M]; N];
        for m in 0..M {
            let mut col = [0.0; N];
            for r in 0..N {
                col[r] = b[r][m];
            }
            let z = self.solve(col);
            for r in 0..N {
                out[r][m] = z[r];
            }
        }
        out
    }
}

/// Largest magnitude among `v` (the row scale of the augmented system). `NaN` propagates.
#[inline]
pub fn max_abs<const M: usize>(v: [f64; M]) -> f64 {
    let mut m = 0.0f64;
    for x in v {
        let a = x.abs();
        // Written so that a NaN makes the result NaN (then the row counts as degenerate).
        m = if a > m || a.is_nan() { a } else { m };
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_with_pivoting() {
        let j = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]];
        let lu = Lu::<3>::factor(&j, [2.0, 1.0, 3.0]);
        let x = [1.0, -2.0, 0.5];
        let b: [f64; 3] = std::array::from_fn(|r| (0..3).map(|c| j[r][c] * x[c]).sum());
        let z = lu.solve(b);
        for k in 0..3 {
            assert!((z[k] - x[k]).abs() < 1e-14, "{z:?}");
        }
        assert!(lu.pivot_ratio() > 0.1);
        // det = 0*(1-0) - 2*(1-0) + 1*(0-3) = -5
        assert!(lu.negative_det());
    }

    #[test]
    fn detects_near_singular_and_nan() {
        let j = [[1.0, 1.0], [1.0, 1.0 + 1e-14]];
        let lu = Lu::<2>::factor(&j, [1.0, 1.0]);
        assert!(lu.pivot_ratio() < 1e-13);
        let lu = Lu::<2>::factor(&[[f64::NAN, 0.0], [0.0, 1.0]], [1.0, 1.0]);
        assert_eq!(lu.pivot_ratio(), 0.0);
        let lu = Lu::<1>::factor(&[[2.0]], [max_abs([2.0, f64::NAN])]);
        assert_eq!(lu.pivot_ratio(), 0.0);
    }

    #[test]
    fn equilibration_is_unit_free() {
        // The same block in metres and in millimetres has the same pivot ratio.
        let j = [[3.0, 0.5], [0.2, 4.0]];
        let jm = [[3000.0, 500.0], [200.0, 4000.0]];
        let a = Lu::<2>::factor(&j, [3.0, 4.0]);
        let b = Lu::<2>::factor(&jm, [3000.0, 4000.0]);
        assert!((a.pivot_ratio() - b.pivot_ratio()).abs() < 1e-15);
    }
}
