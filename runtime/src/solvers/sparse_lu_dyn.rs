//! A large sparse block's LU with its pattern known only at run time (a mechanism read from
//! text): the tables of [`SparsePattern`](super::sparse_steps::SparsePattern) owned, and the
//! factorisation's numeric steps as loops over them, operation for operation those of the
//! compiled path's `Tables` (so the same factor bit for bit: unit tests compare them).
//!
//! Newton's method and the analogs are written over a block size known when the code is
//! compiled (`[f64; N]`). A block of `n` unknowns read at run time is solved at the next size
//! `P >= n` the reader instantiates, *padded*: unknowns `n..P` have the residual 0 and the
//! Jacobian rows and columns of the identity, so they stay 0 and every test of the iteration
//! (largest scaled residual and step, sums of squares, the pivots' test against the
//! configuration's tolerance) gives what it gives on the `n` unknowns alone: the padding adds
//! exact zeros after the real terms, and a pivot of 1 that only a pivot ratio above 1 would
//! notice. The sparse elimination itself runs on the `n` unknowns only. Where a static pivot is
//! weak the dense partial-pivoting [`Lu`] of the padded matrix factorises it: its pivot
//! search never picks a padded row (their entries in the real columns are zero), and the
//! updates it makes to padded entries subtract exact zeros, so the real part is the dense
//! factorisation of the `n x n` matrix (a substitution may turn an exact `-0` of a real value
//! into `+0` there, where a zero product of the padding is subtracted: equal values).

use super::jacobian::BlockJacobian;
use super::lu::{ColScales, Factor, Lu, RowScales, boxed_zeros, inverses};
use super::sparse_steps::PatternView;
use std::sync::Mutex;

/// The symbolic factorisation of one sparse block, owned (the meaning of every field is that of
/// [`SparsePattern`](super::sparse_steps::SparsePattern)'s).
#[doc(hidden)]
#[derive(Clone, Debug, Default)]
pub struct SparseTables {
    /// Number of unknowns.
    pub n: usize,
    /// Number of slots of the factor.
    pub nlu: usize,
    /// Entries of block row `r` are `row_ptr[r]..row_ptr[r + 1]`.
    pub row_ptr: Vec<u32>,
    /// Block column of each entry.
    pub col: Vec<u16>,
    /// Slot of each entry in the factor.
    pub slot: Vec<u32>,
    /// Block row of pivot `k`.
    pub prow: Vec<u16>,
    /// Block column of pivot `k`.
    pub pcol: Vec<u16>,
    /// Whether the row and column permutations together are odd.
    pub odd: bool,
    /// Slot of pivot `k`.
    pub diag: Vec<u32>,
    /// Sub-diagonal entries of column `k` of `L`.
    pub l_ptr: Vec<u32>,
    /// See `l_ptr`.
    pub l_slot: Vec<u32>,
    /// See `l_ptr`.
    pub l_row: Vec<u16>,
    /// Super-diagonal entries of row `k` of `U`.
    pub u_ptr: Vec<u32>,
    /// See `u_ptr`.
    pub u_slot: Vec<u32>,
    /// See `u_ptr`.
    pub u_col: Vec<u16>,
    /// The slots each elimination updates.
    pub upd: Vec<u32>,
}

impl SparseTables {
    /// The number of structural non-zeros.
    pub fn nnz(&self) -> usize {
        self.col.len()
    }

    fn entries(&self, r: usize) -> core::ops::Range<usize> {
        self.row_ptr[r] as usize..self.row_ptr[r + 1] as usize
    }

    /// The tables as the loops of the compiled path read them
    /// ([`PatternView`](super::sparse_steps::PatternView): the same arithmetic).
    pub fn view(&self) -> PatternView<'_> {
        PatternView {
            n: self.n,
            row_ptr: &self.row_ptr,
            col: &self.col,
            slot: &self.slot,
            diag: &self.diag,
            l_ptr: &self.l_ptr,
            l_slot: &self.l_slot,
            l_row: &self.l_row,
            u_ptr: &self.u_ptr,
            u_slot: &self.u_slot,
            u_col: &self.u_col,
            upd: &self.upd,
        }
    }

    /// The factor's slots before elimination, fill slots zero (see [`PatternView::load`]).
    pub fn load(&self, v: &[f64], inv_row: &[f64], inv_col: &[f64], lu: &mut [f64]) {
        lu.fill(0.0);
        self.view().load(v, inv_row, inv_col, lu);
    }

    /// The matrix of entry values `v` padded to `P` with the identity (dense rows).
    /// On the heap: a block of 256 unknowns is 512 KiB.
    fn padded_dense<const P: usize>(&self, v: &[f64]) -> Box<[[f64; P]; P]> {
        let mut d = boxed_zeros::<P>();
        self.load_padded(v, &mut d);
        d
    }

    /// The matrix of entry values `v` padded to `P` with the identity, written over `d`.
    fn load_padded<const P: usize>(&self, v: &[f64], d: &mut [[f64; P]; P]) {
        for (r, row) in d.iter_mut().enumerate() {
            row.fill(0.0);
            if r < self.n {
                for e in self.entries(r) {
                    row[self.col[e] as usize] = v[e];
                }
            } else {
                row[r] = 1.0;
            }
        }
    }
}

/// A factorised sparse block of `n <= P` unknowns along its static order, or (where a static
/// pivot was weak) by the dense [`Lu`] of the padded matrix: the compiled `SparseLu`'s fields
/// and arithmetic, written in place (allocated once, when the block's reader is made).
#[doc(hidden)]
#[derive(Clone, Debug)]
pub struct PaddedLu<const P: usize> {
    lu: Vec<f64>,
    inv_row: [f64; P],
    inv_col: [f64; P],
    inv_diag: [f64; P],
    pivot_ratio: f64,
    negative_det: bool,
    det: f64,
    is_dense: bool,
    dense: Box<Lu<P>>,
}

impl<const P: usize> PaddedLu<P> {
    /// An unfactorised slot for a block with tables `t` (singular until factorised).
    pub fn new(t: &SparseTables) -> Self {
        assert!(t.n <= P, "a block of {} unknowns padded to {P}", t.n);
        PaddedLu {
            lu: vec![0.0; t.nlu],
            inv_row: [0.0; P],
            inv_col: [0.0; P],
            inv_diag: [0.0; P],
            pivot_ratio: 0.0,
            negative_det: false,
            det: 0.0,
            is_dense: false,
            dense: Lu::boxed_unfactored(),
        }
    }

    /// `SparseLu::refactor`: the block with entry values `v`, equilibrated by `row_scale` and
    /// `col_scale` (padded with ones).
    pub fn factor(&mut self, t: &SparseTables, v: &[f64], row_scale: [f64; P], col_scale: [f64; P]) {
        let mut degenerate = false;
        let inv_row = inverses(row_scale, &mut degenerate);
        self.factor_inverses(t, v, row_scale, inv_row, degenerate, ColScales::Divided(&col_scale));
    }

    /// `SparseLu::refactor_inverses`.
    fn factor_inverses(
        &mut self,
        t: &SparseTables,
        v: &[f64],
        row_scale: [f64; P],
        inv_row: [f64; P],
        mut degenerate: bool,
        cols: ColScales<'_, P>,
    ) {
        let n = t.n;
        cols.factors_into(&mut self.inv_col, &mut degenerate);
        self.inv_row = inv_row;
        t.load(v, &inv_row[..n], &self.inv_col[..n], &mut self.lu);
        self.inv_diag = [0.0; P];
        self.pivot_ratio = 0.0;
        self.negative_det = t.odd;
        self.det = if t.odd { -1.0 } else { 1.0 };
        self.is_dense = false;
        match t.view().eliminate(&mut self.lu, &mut self.inv_diag[..n], &mut self.det, &mut self.negative_det) {
            Some(min_pivot) if !degenerate => self.pivot_ratio = min_pivot,
            Some(_) => {}
            None => self.dense_fallback(t, v, row_scale, cols.scales()),
        }
    }

    /// The dense partial-pivoting factorisation of the padded block (cold).
    #[cold]
    #[inline(never)]
    fn dense_fallback(&mut self, t: &SparseTables, v: &[f64], row_scale: [f64; P], col_scale: [f64; P]) {
        // Written into the factorisation's own storage: no copy, no allocation per fallback.
        self.dense.refactor_scaled_loaded(|d| t.load_padded(v, d), row_scale, col_scale);
        self.is_dense = true;
    }

    /// Whether the dense fallback factorised the block.
    pub fn is_dense(&self) -> bool {
        self.is_dense
    }

    /// `SparseLu::pivot_ratio`.
    pub fn pivot_ratio(&self) -> f64 {
        if self.is_dense {
            self.dense.pivot_ratio()
        } else if self.pivot_ratio.is_nan() {
            0.0
        } else {
            self.pivot_ratio
        }
    }

    /// `SparseLu::det`.
    pub fn det(&self) -> f64 {
        if self.is_dense { self.dense.det() } else { self.det }
    }

    /// `SparseLu::negative_det`.
    pub fn negative_det(&self) -> bool {
        if self.is_dense { self.dense.negative_det() } else { self.negative_det }
    }

    /// `SparseLu::solve` of the padded block: `J z = b` for the first `n` values, `z = b`
    /// for the padding.
    pub fn solve(&self, t: &SparseTables, b: [f64; P]) -> [f64; P] {
        if self.is_dense {
            return self.dense.solve(b);
        }
        let n = t.n;
        let mut z = [0.0; P];
        for (k, zk) in z.iter_mut().enumerate().take(n) {
            let r = t.prow[k] as usize;
            *zk = b[r] * self.inv_row[r];
        }
        t.view().substitute(&self.lu, &self.inv_diag[..n], &mut z[..n]);
        let mut x = b;
        for (k, &zk) in z.iter().enumerate().take(n) {
            let c = t.pcol[k] as usize;
            x[c] = zk * self.inv_col[c];
        }
        x
    }

    /// [`PaddedLu::solve`] of `n` values in place.
    pub fn solve_in_place(&self, t: &SparseTables, z: &mut [f64]) {
        let mut b = [0.0; P];
        b[..z.len()].copy_from_slice(z);
        let x = self.solve(t, b);
        z.copy_from_slice(&x[..z.len()]);
    }
}

impl<const P: usize> Factor for PaddedLu<P> {
    fn pivot_ratio(&self) -> f64 {
        PaddedLu::pivot_ratio(self)
    }
    fn negative_det(&self) -> bool {
        PaddedLu::negative_det(self)
    }
}

/// What a padded block's Jacobians share: the tables and the factorisation Newton's steps are
/// made in (one per block, written by each step; behind a lock that is never contended, since a
/// block is solved by one thread at a time, so that a reader holding it stays `Sync`).
#[doc(hidden)]
#[derive(Debug)]
pub struct PaddedWork<const P: usize> {
    /// The block's tables.
    pub tables: SparseTables,
    step: Mutex<PaddedLu<P>>,
}

impl<const P: usize> PaddedWork<P> {
    /// The work of a block with tables `t`.
    pub fn new(tables: SparseTables) -> Self {
        let step = Mutex::new(PaddedLu::new(&tables));
        PaddedWork { tables, step }
    }
}

/// A copy with its own lock: the factorisation in it is scratch written by each Newton step, so
/// the copy holds the same values without sharing the original's lock.
impl<const P: usize> Clone for PaddedWork<P> {
    fn clone(&self) -> Self {
        let step = self.step.lock().unwrap_or_else(std::sync::PoisonError::into_inner).clone();
        PaddedWork { tables: self.tables.clone(), step: Mutex::new(step) }
    }
}

/// One evaluation's Jacobian of a sparse block of `n <= P` unknowns with at most `CAP`
/// structural non-zeros, as Newton's method reads it (see the module documentation): the
/// compiled `SparseJac`'s operations on the real rows, the identity on the padding.
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct PaddedJac<'w, const P: usize, const CAP: usize> {
    /// Values of the entries, in the tables' order (the first `nnz`).
    pub v: [f64; CAP],
    work: &'w PaddedWork<P>,
}

impl<'w, const P: usize, const CAP: usize> PaddedJac<'w, P, CAP> {
    /// A Jacobian of the block of `work` with entry values `v`.
    #[inline(always)]
    pub fn new(v: [f64; CAP], work: &'w PaddedWork<P>) -> Self {
        PaddedJac { v, work }
    }

    fn t(&self) -> &SparseTables {
        &self.work.tables
    }
}

impl<const P: usize, const CAP: usize> BlockJacobian<P> for PaddedJac<'_, P, CAP> {
    /// Newton's method makes its steps through [`BlockJacobian::newton_step_in`] and keeps no
    /// factorisation of a sparse block (the analogs make theirs, a [`PaddedLu`]): the dense
    /// factorisation of the padded matrix is what one would be.
    type Factor = Lu<P>;
    /// The slot is the block's own ([`PaddedWork`]).
    type Work = ();

    fn work(&self) {}

    fn newton_step_in(&self, f: &[f64; P], rows: &RowScales<P>, unit: &[f64; P], _: &mut ()) -> ([f64; P], f64) {
        // A poisoned lock (a panic elsewhere mid-step) still holds a slot this step rewrites.
        let mut lu = self.work.step.lock().unwrap_or_else(|e| e.into_inner());
        let t = self.t();
        lu.factor_inverses(t, &self.v, rows.s, rows.inv, rows.degenerate, ColScales::Multiplied(unit));
        (lu.solve(t, f.map(|v| -v)), lu.pivot_ratio())
    }

    fn row_abs_sum(&self, r: usize) -> f64 {
        if r >= self.t().n {
            return 1.0;
        }
        self.t().entries(r).map(|e| self.v[e].abs()).sum()
    }

    fn row_finite(&self, r: usize) -> bool {
        r >= self.t().n || self.t().entries(r).all(|e| self.v[e].is_finite())
    }

    fn mul(&self, dz: &[f64; P]) -> [f64; P] {
        let t = self.t();
        let mut out = *dz;
        for (r, o) in out.iter_mut().enumerate().take(t.n) {
            *o = t.entries(r).map(|e| self.v[e] * dz[t.col[e] as usize]).sum();
        }
        out
    }

    fn first(&self) -> f64 {
        let t = self.t();
        t.entries(0).find(|&e| t.col[e] == 0).map_or(0.0, |e| self.v[e])
    }

    fn to_dense(&self) -> Box<[[f64; P]; P]> {
        self.t().padded_dense::<P>(&self.v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::sparse_lu::SparseJac;
    use crate::solvers::sparse_steps::SparsePattern;

    fn leak<T: Copy>(v: &[T]) -> &'static [T] {
        Box::leak(v.to_vec().into_boxed_slice())
    }

    /// A tridiagonal block of 6 with one far entry (fill), eliminated in the diagonal's order:
    /// its tables, built by hand.
    fn tables() -> SparseTables {
        // Entries by rows; pivots in order 0..6 on the diagonal.
        let pattern: Vec<Vec<usize>> =
            vec![vec![0, 1, 5], vec![0, 1, 2], vec![1, 2, 3], vec![2, 3, 4], vec![3, 4, 5], vec![0, 4, 5]];
        let n = pattern.len();
        // Symbolic elimination on the full structure (fill included).
        let mut s: Vec<Vec<bool>> = (0..n).map(|r| (0..n).map(|c| pattern[r].contains(&c)).collect()).collect();
        let mut slot_of = std::collections::HashMap::new();
        let mut slot = |i: usize, j: usize| {
            let next = slot_of.len() as u32;
            *slot_of.entry((i, j)).or_insert(next)
        };
        let mut t =
            SparseTables { n, odd: false, l_ptr: vec![0], u_ptr: vec![0], row_ptr: vec![0], ..Default::default() };
        for (r, row) in pattern.iter().enumerate() {
            for &c in row {
                t.col.push(c as u16);
                t.slot.push(slot(r, c));
            }
            t.row_ptr.push(t.col.len() as u32);
        }
        for k in 0..n {
            t.prow.push(k as u16);
            t.pcol.push(k as u16);
            t.diag.push(slot(k, k));
            let lower: Vec<usize> = (k + 1..n).filter(|&i| s[i][k]).collect();
            let upper: Vec<usize> = (k + 1..n).filter(|&j| s[k][j]).collect();
            for &i in &lower {
                t.l_slot.push(slot(i, k));
                t.l_row.push(i as u16);
                for &j in &upper {
                    s[i][j] = true;
                    t.upd.push(slot(i, j));
                }
            }
            for &j in &upper {
                t.u_slot.push(slot(k, j));
                t.u_col.push(j as u16);
            }
            t.l_ptr.push(t.l_slot.len() as u32);
            t.u_ptr.push(t.u_slot.len() as u32);
        }
        t.nlu = slot_of.len();
        t
    }

    fn pattern(t: &SparseTables) -> &'static SparsePattern {
        Box::leak(Box::new(SparsePattern {
            row_ptr: leak(&t.row_ptr),
            col: leak(&t.col),
            slot: leak(&t.slot),
            prow: leak(&t.prow),
            pcol: leak(&t.pcol),
            odd: t.odd,
            diag: leak(&t.diag),
            l_ptr: leak(&t.l_ptr),
            l_slot: leak(&t.l_slot),
            l_row: leak(&t.l_row),
            u_ptr: leak(&t.u_ptr),
            u_slot: leak(&t.u_slot),
            u_col: leak(&t.u_col),
            upd: leak(&t.upd),
        }))
    }

    const V: [f64; 18] =
        [4.0, -1.0, 0.5, -1.2, 5.0, 0.7, 0.3, -6.0, 1.1, 0.9, 3.5, -0.4, 0.2, 4.4, 1.3, 0.6, -0.8, -5.5];

    /// The dynamic tables' factor and solutions are the compiled tables' bit for bit, padded
    /// or not, and solve the system (residual at the rounding level).
    #[test]
    fn the_same_factor_as_the_compiled_tables() {
        let t = tables();
        assert!(t.nlu <= 36);
        let p = pattern(&t);
        let (rows, cols) = ([2.0, 1.0, 4.0, 0.5, 3.0, 1.5], [3.0, 5.0, 2.0, 6.0, 1.0, 0.25]);
        let compiled = SparseJac::<6, 18, 36>::new(V, p).factor_scaled(rows, cols);
        assert!(!compiled.is_dense());
        let pad = |a: [f64; 6]| -> [f64; 8] { std::array::from_fn(|k| if k < 6 { a[k] } else { 1.0 }) };
        let mut lu = PaddedLu::<8>::new(&t);
        lu.factor(&t, &V, pad(rows), pad(cols));
        assert!(!lu.is_dense());
        assert_eq!(lu.pivot_ratio().to_bits(), compiled.pivot_ratio().to_bits());
        assert_eq!(lu.det().to_bits(), compiled.det().to_bits());
        assert_eq!(lu.negative_det(), compiled.negative_det());
        let b = [1.0, -2.0, 0.5, 3.0, -0.25, 7.0];
        let mut z = b;
        lu.solve_in_place(&t, &mut z);
        assert_eq!(z.map(f64::to_bits), compiled.solve(b).map(f64::to_bits));
        // J z = b: an independent check of the factor (dense product).
        let j = t.padded_dense::<6>(&V);
        for r in 0..6 {
            let jz: f64 = (0..6).map(|c| j[r][c] * z[c]).sum();
            assert!((jz - b[r]).abs() <= 1e-13 * (1.0 + b[r].abs()), "row {r}: {jz} against {}", b[r]);
        }
    }

    /// A weak static pivot: both fall back to the dense LU, the padded one of the padded matrix,
    /// with the same solution.
    #[test]
    fn a_weak_pivot_falls_back_to_the_dense_lu_like_the_compiled_one() {
        let t = tables();
        let mut v = V;
        // Row 0's pivot (entry 0) far below the column's other entry (row 1: -1.2).
        v[0] = 1e-3;
        let compiled = SparseJac::<6, 18, 36>::new(v, pattern(&t)).factor_cols([1.0; 6]);
        let mut lu = PaddedLu::<16>::new(&t);
        lu.factor(&t, &v, [1.0; 16], [1.0; 16]);
        assert!(compiled.is_dense() && lu.is_dense());
        assert_eq!(lu.negative_det(), compiled.negative_det());
        let b = [1.0, -2.0, 0.5, 3.0, -0.25, 7.0];
        let mut z = b;
        lu.solve_in_place(&t, &mut z);
        assert_eq!(z.map(f64::to_bits), compiled.solve(b).map(f64::to_bits));
        assert_eq!(lu.det().to_bits(), compiled.det().to_bits());
    }

    /// The padded Jacobian as Newton reads it: the compiled one's rows, the identity beyond.
    #[test]
    fn the_newton_view_of_the_padded_matrix() {
        let t = tables();
        let compiled = SparseJac::<6, 18, 36>::new(V, pattern(&t));
        let work = PaddedWork::<8>::new(t);
        let mut v = [0.0; 24];
        v[..18].copy_from_slice(&V);
        let j = PaddedJac::<8, 24>::new(v, &work);
        let dz = [1.0, 0.5, -2.0, 0.25, 3.0, -1.0, 7.0, 9.0];
        let m = j.mul(&dz);
        assert_eq!(&m[..6], &compiled.mul(&std::array::from_fn(|k| dz[k]))[..]);
        assert_eq!(&m[6..], &[7.0, 9.0]);
        assert_eq!(j.row_abs_sum(2), compiled.row_abs_sum(2));
        assert_eq!(j.row_abs_sum(7), 1.0);
        assert_eq!(j.first(), compiled.first());
        let f = [0.1, -0.2, 0.3, 0.05, -0.4, 0.6, 0.0, 0.0];
        let rows = RowScales::new([2.0, 1.0, 4.0, 0.5, 3.0, 1.5, 1.0, 1.0]);
        let unit = [1.5, 1.0, 0.25, 3.0, 1.0, 2.0, 1.0, 1.0];
        let (dz, pivot) = j.newton_step(&f, &rows, &unit);
        let (cdz, cpivot) = compiled.newton_step(
            &std::array::from_fn(|k| f[k]),
            &RowScales::new(std::array::from_fn(|k| rows.s[k])),
            &std::array::from_fn(|k| unit[k]),
        );
        assert_eq!(dz[..6].iter().map(|x| x.to_bits()).collect::<Vec<_>>(), cdz.map(f64::to_bits));
        assert_eq!(pivot.to_bits(), cpivot.to_bits());
        assert_eq!(&dz[6..], &[0.0, 0.0]);
    }
}
