//! LU factorisation of a large sparse block along an elimination order fixed at compile time.
//!
//! The macro computes, for every block above a size threshold, a fill-reducing order of pivots
//! on the block's structural non-zeros (a matching for a zero-free diagonal, then Markowitz
//! minimum fill) and the symbolic factorisation: where each entry of the Jacobian goes, which
//! entries of `L` and `U` each pivot produces and which entries each elimination updates. That is
//! a [`SparsePattern`] of index tables; the factorisation follows them, its cost the number of
//! non-zeros and updates, not `N^3`.
//!
//! A static order cannot pivot on values. Every pivot is therefore checked against the other
//! entries of its column in the active submatrix (threshold partial pivoting: `|p| >=
//! THRESHOLD * max |column|`, a ratio of entries of the same column, so free of units); when one
//! is weak, or not finite, the block is factorised by the dense partial-pivoting [`Lu`] instead,
//! so no answer is worse than the dense factorisation's. Both measure the same matrix (the
//! Jacobian equilibrated by the caller's row and column scales): the determinant's sign (the
//! assembly mode) is the same, and the pivot ratio is the smallest pivot of the factorisation
//! that was used.
//!
//! The numeric steps run as loops over the pattern's tables ([`Tables`]) or, for a block the
//! macro generated, as straight-line code emitted for its pattern (the type parameter `E`, see
//! [`SparseSteps`]), about four times fewer instructions: the same arithmetic in the same order,
//! so the same factor bit for bit.

use super::jacobian::{BlockFactor, BlockJacobian};
use super::lu::{ColScales, Factor, Lu, RowScales, boxed_zeros, inverses_into};
pub use super::sparse_steps::SparsePattern;
use super::sparse_steps::{SparseSteps, Tables};
use core::marker::PhantomData;

/// The structural non-zeros of a sparse block's Jacobian (`NNZ` values, in the order of its
/// [`SparsePattern`]); `NLU` is the number of slots of its factor; `E` runs the factorisation's
/// numeric steps (the pattern's tables unless the macro emitted them as straight-line code).
#[doc(hidden)]
#[derive(Debug)]
pub struct SparseJac<const N: usize, const NNZ: usize, const NLU: usize, E = Tables> {
    /// Values of the entries.
    pub v: [f64; NNZ],
    /// Their positions and the symbolic factorisation.
    pub pattern: &'static SparsePattern,
    steps: PhantomData<fn() -> E>,
}

// Not derived: a derive would ask `E: Clone` of the marker type.
impl<const N: usize, const NNZ: usize, const NLU: usize, E> Clone for SparseJac<N, NNZ, NLU, E> {
    #[inline(always)]
    fn clone(&self) -> Self {
        *self
    }
}

impl<const N: usize, const NNZ: usize, const NLU: usize, E> Copy for SparseJac<N, NNZ, NLU, E> {}

/// A factorised sparse block: `P D_r J D_c Q = L U` along the static order, or the dense
/// partial-pivoting factorisation where a static pivot was weak.
#[doc(hidden)]
#[derive(Debug)]
pub struct SparseLu<const N: usize, const NLU: usize, E = Tables> {
    lu: [f64; NLU],
    pattern: &'static SparsePattern,
    inv_row: [f64; N],
    inv_col: [f64; N],
    inv_diag: [f64; N],
    pivot_ratio: f64,
    negative_det: bool,
    det: f64,
    /// The dense fallback (on the heap: it is `N^2` values, and needed only near singular
    /// positions or for unusual values).
    dense: Option<Box<Lu<N>>>,
    steps: PhantomData<fn() -> E>,
}

impl<const N: usize, const NLU: usize, E> Clone for SparseLu<N, NLU, E> {
    fn clone(&self) -> Self {
        SparseLu { dense: self.dense.clone(), ..*self }
    }
}

impl<const N: usize, const NNZ: usize, const NLU: usize, E: SparseSteps<N, NLU>> SparseJac<N, NNZ, NLU, E> {
    /// The Jacobian with entry values `v` of `pattern`.
    #[inline(always)]
    pub fn new(v: [f64; NNZ], pattern: &'static SparsePattern) -> Self {
        debug_assert!(pattern.row_ptr.len() == N + 1 && pattern.col.len() == NNZ && pattern.diag.len() == N);
        SparseJac { v, pattern, steps: PhantomData }
    }

    /// The same entries factorised by the steps `F` (a test compares the emitted steps with
    /// the tables).
    #[inline(always)]
    pub fn with_steps<F: SparseSteps<N, NLU>>(&self) -> SparseJac<N, NNZ, NLU, F> {
        SparseJac { v: self.v, pattern: self.pattern, steps: PhantomData }
    }

    /// Factorises the matrix equilibrated by row and column scales (see [`Lu::factor_scaled`]).
    pub fn factor_scaled(&self, row_scale: [f64; N], col_scale: [f64; N]) -> SparseLu<N, NLU, E> {
        SparseLu::factor(self, row_scale, col_scale)
    }

    /// Factorises the matrix with column `c` divided by `col_scale[c]`.
    #[inline]
    pub fn factor_cols(&self, col_scale: [f64; N]) -> SparseLu<N, NLU, E> {
        SparseLu::factor(self, [1.0; N], col_scale)
    }

    /// [`SparseJac::factor_cols`] written over `lu` (see [`SparseLu::refactor`]): the analogs'
    /// factorisation in the slot the Newton steps factorised into.
    #[inline]
    pub fn factor_cols_into(&self, lu: &mut SparseLu<N, NLU, E>, col_scale: &[f64; N]) {
        lu.refactor(self, &[1.0; N], col_scale);
    }

    /// [`SparseJac::factor_cols_into`] with row `r` divided by `row_scale[r]` first: the
    /// analogs' factorisation of a block whose rows have more than one unit (their magnitudes).
    #[inline]
    pub fn factor_scaled_into(&self, lu: &mut SparseLu<N, NLU, E>, row_scale: &[f64; N], col_scale: &[f64; N]) {
        lu.refactor(self, row_scale, col_scale);
    }

    /// The first row holding a non-finite value (cold-path diagnosis of a failed
    /// factorisation).
    #[cold]
    pub fn first_bad_row(&self) -> Option<usize> {
        (0..N).find(|&r| !self.row_finite(r))
    }

    fn entries(&self, r: usize) -> core::ops::Range<usize> {
        self.pattern.row_ptr[r] as usize..self.pattern.row_ptr[r + 1] as usize
    }
}

impl<const N: usize, const NNZ: usize, const NLU: usize, E: SparseSteps<N, NLU>> BlockJacobian<N>
    for SparseJac<N, NNZ, NLU, E>
{
    type Factor = SparseLu<N, NLU, E>;
    type Work = SparseLu<N, NLU, E>;

    #[inline(always)]
    fn work(&self) -> SparseLu<N, NLU, E> {
        SparseLu::unfactored(self.pattern)
    }

    /// Factorises over `lu` with the row scales' reciprocals of `rows` (not taken again), each
    /// column multiplied by its unknown's unit.
    #[inline(always)]
    fn newton_step_in(
        &self,
        f: &[f64; N],
        rows: &RowScales<N>,
        unit: &[f64; N],
        lu: &mut SparseLu<N, NLU, E>,
    ) -> ([f64; N], f64) {
        lu.refactor_inverses(self, &rows.s, &rows.inv, rows.degenerate, ColScales::Multiplied(unit));
        let mut dz = f.map(|v| -v);
        lu.solve_in_place(&mut dz);
        (dz, lu.pivot_ratio())
    }

    fn row_abs_sum(&self, r: usize) -> f64 {
        self.entries(r).map(|e| self.v[e].abs()).sum()
    }

    fn row_finite(&self, r: usize) -> bool {
        self.entries(r).all(|e| self.v[e].is_finite())
    }

    fn mul(&self, dz: &[f64; N]) -> [f64; N] {
        let mut out = [0.0; N];
        for (r, o) in out.iter_mut().enumerate() {
            *o = self.entries(r).map(|e| self.v[e] * dz[self.pattern.col[e] as usize]).sum();
        }
        out
    }

    fn first(&self) -> f64 {
        self.entries(0).find(|&e| self.pattern.col[e] == 0).map_or(0.0, |e| self.v[e])
    }

    fn to_dense(&self) -> Box<[[f64; N]; N]> {
        let mut d = boxed_zeros::<N>();
        for (r, row) in d.iter_mut().enumerate() {
            for e in self.entries(r) {
                row[self.pattern.col[e] as usize] = self.v[e];
            }
        }
        d
    }
}

impl<const N: usize, const NLU: usize, E: SparseSteps<N, NLU>> SparseLu<N, NLU, E> {
    /// A slot for the factorisations of blocks of `pattern`, holding none yet: every value NaN
    /// (its pivot ratio reads 0, singular). A solve makes one and factorises over it
    /// ([`SparseLu::refactor`]): its kilobytes are written in place by each factorisation,
    /// where a new one returned by value would be made in a temporary and copied. NaN, not
    /// zero: a fill of zeros is a `memset`, which for kilobytes is a `rep stosb` that
    /// `callgrind` counts byte by byte (the benchmarks count instructions); NaN is a copy.
    #[inline(always)]
    pub fn unfactored(pattern: &'static SparsePattern) -> Self {
        SparseLu {
            lu: [f64::NAN; NLU],
            pattern,
            inv_row: [f64::NAN; N],
            inv_col: [f64::NAN; N],
            inv_diag: [f64::NAN; N],
            pivot_ratio: f64::NAN,
            negative_det: false,
            det: f64::NAN,
            dense: None,
            steps: PhantomData,
        }
    }

    /// Factorises `j` equilibrated by `row_scale` and `col_scale` along its static order, or
    /// densely when a static pivot is weak (see the module documentation).
    pub fn factor<const NNZ: usize>(j: &SparseJac<N, NNZ, NLU, E>, row_scale: [f64; N], col_scale: [f64; N]) -> Self {
        let mut f = Self::unfactored(j.pattern);
        f.refactor(j, &row_scale, &col_scale);
        f
    }

    /// [`SparseLu::factor`] written over `self`, every field: whatever it held before (another
    /// factorisation, of any block of the same size, or none) is not read.
    pub fn refactor<const NNZ: usize>(
        &mut self,
        j: &SparseJac<N, NNZ, NLU, E>,
        row_scale: &[f64; N],
        col_scale: &[f64; N],
    ) {
        let mut degenerate = false;
        inverses_into(row_scale, &mut self.inv_row, &mut degenerate);
        self.factor_rows_taken(j, row_scale, degenerate, ColScales::Divided(col_scale));
    }

    /// [`SparseLu::refactor`] with the row scales' reciprocals `inv_row` already taken
    /// (`degenerate` when a row scale is not positive and finite), the columns equilibrated by
    /// `cols`.
    #[inline(always)]
    fn refactor_inverses<const NNZ: usize>(
        &mut self,
        j: &SparseJac<N, NNZ, NLU, E>,
        row_scale: &[f64; N],
        inv_row: &[f64; N],
        degenerate: bool,
        cols: ColScales<'_, N>,
    ) {
        self.inv_row = *inv_row;
        self.factor_rows_taken(j, row_scale, degenerate, cols);
    }

    /// The factorisation, every field written, once the row scales' reciprocals are in
    /// `self.inv_row`.
    #[inline(always)]
    fn factor_rows_taken<const NNZ: usize>(
        &mut self,
        j: &SparseJac<N, NNZ, NLU, E>,
        row_scale: &[f64; N],
        mut degenerate: bool,
        cols: ColScales<'_, N>,
    ) {
        let p = j.pattern;
        self.pattern = p;
        cols.factors_into(&mut self.inv_col, &mut degenerate);
        E::load(p, &j.v, &self.inv_row, &self.inv_col, &mut self.lu);
        self.pivot_ratio = 0.0;
        self.negative_det = p.odd;
        self.det = if p.odd { -1.0 } else { 1.0 };
        self.dense = None;
        // The elimination writes every pivot's reciprocal (up to a weak pivot, after which the
        // dense fallback's are read instead).
        match E::eliminate(p, &mut self.lu, &mut self.inv_diag, &mut self.det, &mut self.negative_det) {
            Some(min_pivot) if !degenerate => self.pivot_ratio = min_pivot,
            Some(_) => {}
            None => self.dense = Some(dense_fallback(j, *row_scale, cols.scales())),
        }
    }

    /// Whether the dense fallback factorised this block.
    pub fn is_dense(&self) -> bool {
        self.dense.is_some()
    }

    /// Smallest pivot of the equilibrated matrix, in `[0, ~1]` (see [`Lu::pivot_ratio`]).
    #[inline]
    pub fn pivot_ratio(&self) -> f64 {
        match &self.dense {
            Some(d) => d.pivot_ratio(),
            None if self.pivot_ratio.is_nan() => 0.0,
            None => self.pivot_ratio,
        }
    }

    /// Determinant of the equilibrated matrix (see [`Lu::det`]).
    #[inline]
    pub fn det(&self) -> f64 {
        self.dense.as_ref().map_or(self.det, |d| d.det())
    }

    /// Sign of the determinant (`true` when negative).
    #[inline]
    pub fn negative_det(&self) -> bool {
        self.dense.as_ref().map_or(self.negative_det, |d| d.negative_det())
    }

    /// Solves `J z = b`.
    pub fn solve(&self, b: [f64; N]) -> [f64; N] {
        let mut x = b;
        self.solve_in_place(&mut x);
        x
    }

    /// Solves `J z = b`, `z` written over `b`: no array moved in or out (a kilobyte each for
    /// a block of 128 unknowns).
    pub fn solve_in_place(&self, b: &mut [f64; N]) {
        if let Some(d) = &self.dense {
            *b = d.solve(*b);
            return;
        }
        let p = self.pattern;
        // Made value by value (measured: fewer instructions than zeroed, then written).
        let mut z: [f64; N] = core::array::from_fn(|k| {
            let r = p.prow[k] as usize;
            b[r] * self.inv_row[r]
        });
        E::substitute(p, &self.lu, &self.inv_diag, &mut z);
        // `pcol` is a permutation: every value of `b` is written.
        for (k, &zk) in z.iter().enumerate() {
            let c = p.pcol[k] as usize;
            b[c] = zk * self.inv_col[c];
        }
    }

    /// Solves `J Z = B` for `M` right-hand sides given as rows `B[r][m]`.
    pub fn solve_cols<const M: usize>(&self, b: [[f64; M]; N]) -> [[f64; M]; N] {
        let mut out = b;
        for m in 0..M {
            let mut z = [0.0; N];
            for r in 0..N {
                z[r] = out[r][m];
            }
            self.solve_in_place(&mut z);
            for r in 0..N {
                out[r][m] = z[r];
            }
        }
        out
    }
}

/// The dense partial-pivoting factorisation of a block whose static pivot was weak (cold: near
/// singular positions or unusual values only).
#[cold]
#[inline(never)]
fn dense_fallback<const N: usize, J: BlockJacobian<N>>(j: &J, row_scale: [f64; N], col_scale: [f64; N]) -> Box<Lu<N>> {
    // Both on the heap, the factorisation made where it is kept: the dense matrix and the
    // factorisation are 512 KiB each for a block of 256 unknowns, which on the stack (as built
    // by an unoptimised build) overflow a thread's default 2 MiB.
    let mut lu = Lu::boxed_unfactored();
    lu.refactor_scaled(&j.to_dense(), row_scale, col_scale);
    lu
}

impl<const N: usize, const NLU: usize, E: SparseSteps<N, NLU>> Factor for SparseLu<N, NLU, E> {
    #[inline]
    fn pivot_ratio(&self) -> f64 {
        SparseLu::pivot_ratio(self)
    }
    #[inline]
    fn negative_det(&self) -> bool {
        SparseLu::negative_det(self)
    }
}

impl<const N: usize, const NLU: usize, E: SparseSteps<N, NLU>> BlockFactor<N> for SparseLu<N, NLU, E> {
    fn solve_block(&self, b: [f64; N]) -> [f64; N] {
        self.solve(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leak<T: Copy>(v: Vec<T>) -> &'static [T] {
        Box::leak(v.into_boxed_slice())
    }

    fn odd(p: &[usize]) -> bool {
        let mut inversions = 0;
        for i in 0..p.len() {
            inversions += (i + 1..p.len()).filter(|&j| p[j] < p[i]).count();
        }
        inversions % 2 == 1
    }

    /// The tables of a full `N x N` pattern eliminated with pivots `(prow[k], pcol[k])`.
    fn full_pattern<const N: usize>(prow: [usize; N], pcol: [usize; N]) -> &'static SparsePattern {
        let (mut row_at, mut col_at) = ([0; N], [0; N]);
        for k in 0..N {
            row_at[prow[k]] = k;
            col_at[pcol[k]] = k;
        }
        let slot = |i: usize, j: usize| (i * N + j) as u32;
        let (mut l_slot, mut l_row, mut u_slot, mut u_col, mut upd) = (vec![], vec![], vec![], vec![], vec![]);
        let (mut l_ptr, mut u_ptr) = (vec![0u32], vec![0u32]);
        for k in 0..N {
            for i in k + 1..N {
                l_slot.push(slot(i, k));
                l_row.push(i as u16);
                u_slot.push(slot(k, i));
                u_col.push(i as u16);
                upd.extend((k + 1..N).map(|j| slot(i, j)));
            }
            l_ptr.push(l_slot.len() as u32);
            u_ptr.push(u_slot.len() as u32);
        }
        Box::leak(Box::new(SparsePattern {
            row_ptr: leak((0..=N).map(|r| (r * N) as u32).collect()),
            col: leak((0..N * N).map(|e| (e % N) as u16).collect()),
            slot: leak((0..N * N).map(|e| slot(row_at[e / N], col_at[e % N])).collect()),
            prow: leak(prow.iter().map(|&r| r as u16).collect()),
            pcol: leak(pcol.iter().map(|&c| c as u16).collect()),
            odd: odd(&prow) ^ odd(&pcol),
            diag: leak((0..N).map(|k| slot(k, k)).collect()),
            l_ptr: leak(l_ptr),
            l_slot: leak(l_slot),
            l_row: leak(l_row),
            u_ptr: leak(u_ptr),
            u_slot: leak(u_slot),
            u_col: leak(u_col),
            upd: leak(upd),
        }))
    }

    fn sparse<const N: usize, const NN: usize>(
        j: &[[f64; N]; N],
        pattern: &'static SparsePattern,
    ) -> SparseJac<N, NN, NN> {
        SparseJac::new(std::array::from_fn(|e| j[e / N][e % N]), pattern)
    }

    /// A matrix whose entries `(prow[k], pcol[k])` dominate their columns, with mixed signs.
    const J: [[f64; 4]; 4] =
        [[0.3, -5.0, 0.2, 0.1], [4.0, 0.5, -0.3, 0.2], [0.1, 0.2, -0.4, 6.0], [-0.2, 0.3, 3.0, 0.4]];
    const PROW: [usize; 4] = [1, 0, 3, 2];
    const PCOL: [usize; 4] = [0, 1, 2, 3];

    #[test]
    fn static_order_solves_like_the_dense_lu() {
        let p = full_pattern(PROW, PCOL);
        let (rows, cols) = ([2.0, 1.0, 4.0, 0.5], [3.0, 5.0, 2.0, 6.0]);
        let s = sparse::<4, 16>(&J, p).factor_scaled(rows, cols);
        let d = Lu::factor_scaled(&J, rows, cols);
        assert!(!s.is_dense());
        let b = [1.0, -2.0, 0.5, 3.0];
        let (zs, zd) = (s.solve(b), d.solve(b));
        for k in 0..4 {
            assert!((zs[k] - zd[k]).abs() <= 1e-14 * zd[k].abs().max(1.0), "{zs:?} {zd:?}");
        }
        // The same matrix: the same determinant and sign.
        assert_eq!(s.negative_det(), d.negative_det());
        assert!((s.det() - d.det()).abs() <= 1e-14 * d.det().abs(), "{} {}", s.det(), d.det());
        assert!(s.pivot_ratio() > 0.1 && d.pivot_ratio() > 0.1);
        let cols2 = s.solve_cols([[1.0, 0.0], [-2.0, 0.0], [0.5, 0.0], [3.0, 1.0]]);
        assert_eq!(cols2.map(|r| r[0]), zs);
    }

    /// A Newton step multiplies each column by its unknown's unit: the step is the dense one's
    /// and the pivot ratio that of the matrix with its columns so scaled (powers of two, exact),
    /// as the analogs' factorisation divided by their reciprocals gives it.
    #[test]
    fn a_newton_step_measures_its_pivots_in_the_units() {
        let s = sparse::<4, 16>(&J, full_pattern(PROW, PCOL));
        let (rows, unit) = (RowScales::new([2.0, 1.0, 4.0, 0.5]), [2f64.powi(20), 1.0, 2f64.powi(-7), 4.0]);
        let f = [1.0, -2.0, 0.5, 3.0];
        let (dz, pivot) = s.newton_step(&f, &rows, &unit);
        let (dense, dense_pivot) = crate::solvers::lu::solve_row_scaled(&J, &f, &rows, &unit);
        for k in 0..4 {
            assert!((dz[k] - dense[k]).abs() <= 1e-14 * dense[k].abs().max(1.0), "{dz:?} {dense:?}");
        }
        let divided = s.factor_scaled(rows.s, unit.map(|u| 1.0 / u));
        assert!(!divided.is_dense());
        assert_eq!(pivot.to_bits(), divided.pivot_ratio().to_bits());
        // The units move the pivots: the static order's and the dense order's both see them.
        let (_, ones) = s.newton_step(&f, &rows, &[1.0; 4]);
        assert!(pivot != ones && dense_pivot > 0.0 && pivot > 0.0, "{pivot} {ones} {dense_pivot}");
        // A weak static pivot: the dense fallback, given the units' reciprocals as scales.
        let mut weak = J;
        weak[1][0] = 0.01;
        let s = sparse::<4, 16>(&weak, full_pattern(PROW, PCOL));
        let (dz, pivot) = s.newton_step(&f, &rows, &unit);
        let (dense, dense_pivot) = crate::solvers::lu::solve_row_scaled(&weak, &f, &rows, &unit);
        assert!(s.factor_scaled(rows.s, unit.map(|u| 1.0 / u)).is_dense());
        assert_eq!(dz.map(f64::to_bits), dense.map(f64::to_bits));
        assert_eq!(pivot.to_bits(), dense_pivot.to_bits());
    }

    #[test]
    fn a_weak_static_pivot_falls_back_to_the_dense_lu() {
        // The static pivot (1, 0) is below a tenth of its column's largest entry.
        let mut j = J;
        j[1][0] = 0.01;
        let p = full_pattern(PROW, PCOL);
        let s = sparse::<4, 16>(&j, p).factor_cols([1.0; 4]);
        let d = Lu::factor_cols(&j, [1.0; 4]);
        assert!(s.is_dense());
        assert_eq!(s.solve([1.0, 2.0, 3.0, 4.0]), d.solve([1.0, 2.0, 3.0, 4.0]));
        assert_eq!((s.pivot_ratio(), s.det(), s.negative_det()), (d.pivot_ratio(), d.det(), d.negative_det()));
    }

    #[test]
    fn non_finite_entries_and_degenerate_scales_are_singular() {
        let p = full_pattern(PROW, PCOL);
        let mut j = J;
        j[2][1] = f64::NAN;
        assert_eq!(sparse::<4, 16>(&j, p).factor_cols([1.0; 4]).pivot_ratio(), 0.0);
        assert_eq!(sparse::<4, 16>(&j, p).first_bad_row(), Some(2));
        assert_eq!(sparse::<4, 16>(&J, p).factor_cols([1.0, 0.0, 1.0, 1.0]).pivot_ratio(), 0.0);
    }

    #[test]
    fn the_newton_view_of_the_matrix() {
        let s = sparse::<4, 16>(&J, full_pattern(PROW, PCOL));
        assert_eq!(*s.to_dense(), J);
        assert_eq!(s.first(), J[0][0]);
        assert_eq!(s.row_abs_sum(1), 5.0);
        assert_eq!(s.mul(&[1.0, 0.0, 0.0, 1.0]), J.map(|r| r[0] + r[3]));
    }
}
