//! What Newton's method and the analog solves need from a block's Jacobian, so that one
//! iteration serves both representations: dense rows (`[[f64; N]; N]`, small blocks) and the
//! structural non-zeros of a large sparse block ([`SparseJac`](super::sparse_lu::SparseJac)).

use super::lu::{Factor, Lu, RowScales, boxed_zeros, solve_row_scaled};

/// A factorised block Jacobian: solves and the pivot diagnostics of [`Factor`].
#[doc(hidden)]
pub trait BlockFactor<const N: usize>: Factor {
    /// Solves `J z = b`.
    fn solve_block(&self, b: [f64; N]) -> [f64; N];
}

/// A block Jacobian as Newton's method reads it.
#[doc(hidden)]
pub trait BlockJacobian<const N: usize>: Copy {
    /// Its factorisation.
    type Factor: BlockFactor<N>;
    /// Where its Newton steps factorise: nothing for dense rows (the step eliminates the
    /// right-hand side with the matrix) or a run-time model's block (which has its own slot), a
    /// factorisation written over by each step for a compiled sparse block (kilobytes: a new
    /// one made and moved by each step would be copied, and the analogs factorise into the
    /// same slot after the solve).
    type Work;
    /// A [`Work`](BlockJacobian::Work) for a solve given none, holding no factorisation yet.
    fn work(&self) -> Self::Work;
    /// The Newton step `-J^-1 f` with row `r` divided by `rows.s[r]`, and the smallest pivot
    /// of that row-equilibrated matrix with column `c` multiplied by `unit[c]`, the unknown's
    /// unit ([`Factor::pivot_ratio`] of its factorisation): the matrix that maps a step in
    /// the unknowns' units to residuals in the rows' units. Its pivots are the same in metres,
    /// millimetres or light years, where those of the rows' equilibration alone shrink with
    /// the size of the mechanism in a column of a length (whose entries are pure numbers, as a
    /// slider's or a polar length's direction) beside columns of angles (whose entries are
    /// lengths).
    #[inline(always)]
    fn newton_step(&self, f: &[f64; N], rows: &RowScales<N>, unit: &[f64; N]) -> ([f64; N], f64) {
        self.newton_step_in(f, rows, unit, &mut self.work())
    }
    /// [`newton_step`](BlockJacobian::newton_step), factorising into `work` (the same step bit
    /// for bit).
    fn newton_step_in(
        &self,
        f: &[f64; N],
        rows: &RowScales<N>,
        unit: &[f64; N],
        work: &mut Self::Work,
    ) -> ([f64; N], f64);
    /// `sum_c |J_rc|`.
    fn row_abs_sum(&self, r: usize) -> f64;
    /// Whether every entry of row `r` is finite.
    fn row_finite(&self, r: usize) -> bool;
    /// Whether every entry is finite.
    #[inline(always)]
    fn finite(&self) -> bool {
        (0..N).all(|r| self.row_finite(r))
    }
    /// `J dz`.
    fn mul(&self, dz: &[f64; N]) -> [f64; N];
    /// The entry `J_00` (the whole matrix of a scalar block).
    fn first(&self) -> f64;
    /// The matrix as dense rows (cold paths only: Levenberg-Marquardt steps, the dense fallback
    /// of a sparse block), on the heap: a block of 256 unknowns is 512 KiB.
    fn to_dense(&self) -> Box<[[f64; N]; N]>;
}

impl<const N: usize> BlockFactor<N> for Lu<N> {
    #[inline(always)]
    fn solve_block(&self, b: [f64; N]) -> [f64; N] {
        self.solve(b)
    }
}

impl<const N: usize> BlockJacobian<N> for [[f64; N]; N] {
    type Factor = Lu<N>;
    type Work = ();

    #[inline(always)]
    fn work(&self) {}

    /// Eliminates the right-hand side with the matrix: no factorisation is kept.
    #[inline(always)]
    fn newton_step_in(&self, f: &[f64; N], rows: &RowScales<N>, unit: &[f64; N], _: &mut ()) -> ([f64; N], f64) {
        solve_row_scaled(self, f, rows, unit)
    }

    #[inline(always)]
    fn row_abs_sum(&self, r: usize) -> f64 {
        let mut sum = 0.0;
        for c in 0..N {
            sum += self[r][c].abs();
        }
        sum
    }

    #[inline(always)]
    fn row_finite(&self, r: usize) -> bool {
        self[r].iter().all(|v| v.is_finite())
    }

    /// One test for the whole matrix (no branch per entry).
    #[inline(always)]
    fn finite(&self) -> bool {
        let mut finite = true;
        for r in 0..N {
            for c in 0..N {
                finite &= self[r][c].abs() < f64::INFINITY;
            }
        }
        finite
    }

    #[inline(always)]
    fn mul(&self, dz: &[f64; N]) -> [f64; N] {
        let mut out = [0.0; N];
        for r in 0..N {
            let mut acc = 0.0;
            for c in 0..N {
                acc += self[r][c] * dz[c];
            }
            out[r] = acc;
        }
        out
    }

    #[inline(always)]
    fn first(&self) -> f64 {
        self[0][0]
    }

    fn to_dense(&self) -> Box<[[f64; N]; N]> {
        let mut d = boxed_zeros();
        d.copy_from_slice(self);
        d
    }
}
