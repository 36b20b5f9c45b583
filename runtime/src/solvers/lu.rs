//! LU factorisation of small fixed-size blocks with equilibration and a pivot-ratio check.
//!
//! nalgebra's LU only reports failure on an exactly zero pivot; near a dead centre the pivots are
//! tiny but non-zero and the solution is garbage. Here the matrix is first equilibrated — its
//! rows and/or columns divided by scales supplied by the caller — so the smallest pivot of the
//! equilibrated matrix is a dimension-free measure of how close the block is to singular:
//! [`Lu::pivot_ratio`].
//!
//! For loop-closure equations the natural scales are the columns': the derivative of a link
//! vector `l @ theta` with respect to `theta` has magnitude `l` in every configuration, so
//! dividing each column by the largest magnitude in the *full* Jacobian column (all equations,
//! not just the block's) makes the pivots fall to zero exactly at dead centres, limit positions
//! and change points, whatever the units. The generated code passes those column scales; the
//! Newton iteration, which only sees its block, scales rows, and measures each pivot in its
//! column's unknown's unit (`solve_row_scaled`; the sparse factorisations take the units as
//! column factors), so that a length beside angles is judged alike at every size.

/// A factorised `N x N` block: `P D_r J D_c = L U` with `D_r`, `D_c` the equilibrations.
#[derive(Clone, Copy, Debug)]
pub struct Lu<const N: usize> {
    /// `L` below the diagonal (unit diagonal implied) and `U` on and above it.
    lu: [[f64; N]; N],
    perm: [usize; N],
    inv_row: [f64; N],
    /// Whether `inv_row` is anything but ones: the analogs' factorisations scale columns only,
    /// and their solves then skip the multiplications by one.
    rows_scaled: bool,
    inv_col: [f64; N],
    /// Reciprocals of the pivots, so that solves multiply instead of divide.
    inv_diag: [f64; N],
    pivot_ratio: f64,
    negative_det: bool,
    det: f64,
}

/// The reciprocals of the equilibration scales; a zero, negative, infinite or NaN scale, or a
/// positive one so small that its reciprocal overflows (below `1 / f64::MAX`, about 5.6e-309),
/// gives 0 and marks the factorisation `degenerate` (an infinite reciprocal would make a zero
/// residual `0 * inf`, NaN). All the reciprocals are computed, and one test of them
/// ([`all_positive_finite`]) and one branch decide for the whole set: this runs for every row
/// and column of every factorisation, dense or sparse, and the scales are almost always valid.
/// The reciprocals alone tell: a zero scale gives infinity, a negative one (or `-0`) a negative
/// reciprocal, NaN stays NaN, an infinite scale gives 0 and a tiny one overflows.
#[inline(always)]
pub(crate) fn inverses<const N: usize>(scale: [f64; N], degenerate: &mut bool) -> [f64; N] {
    let mut inv = [0.0; N];
    inverses_into(&scale, &mut inv, degenerate);
    inv
}

/// [`inverses`] written over `inv`: a factorisation's own storage, where a returned value
/// would be copied (a kilobyte for a block of 128 unknowns).
#[inline(always)]
pub(crate) fn inverses_into<const N: usize>(scale: &[f64; N], inv: &mut [f64; N], degenerate: &mut bool) {
    for k in 0..N {
        inv[k] = 1.0 / scale[k];
    }
    if !all_positive_finite(inv) {
        *degenerate = true;
        *inv = invalid_inverses(*scale);
    }
}

/// An `N x N` matrix of zeros on the heap, made row by row (never whole on the stack): the cold
/// paths' dense copies of a large block's Jacobian (512 KiB for 256 unknowns).
pub(crate) fn boxed_zeros<const N: usize>() -> Box<[[f64; N]; N]> {
    vec![[0.0; N]; N].into_boxed_slice().try_into().expect("N rows")
}

/// Whether every value is positive and finite: their bit patterns lie in `1 ..= f64::MAX`, so
/// one subtraction and one unsigned maximum per value and a single comparison test them all
/// (zero, negative values and `-0` wrap or carry the sign bit; infinity and NaN lie above).
#[inline(always)]
pub(crate) fn all_positive_finite<const N: usize>(v: &[f64; N]) -> bool {
    let mut worst = 0u64;
    for x in v {
        worst = worst.max(x.to_bits().wrapping_sub(1));
    }
    worst < f64::MAX.to_bits()
}

/// [`inverses`] of a set with an invalid scale: those, and those whose reciprocal overflows,
/// give 0.
#[cold]
#[inline(never)]
fn invalid_inverses<const N: usize>(scale: [f64; N]) -> [f64; N] {
    scale.map(|s| if s > 0.0 && s < f64::INFINITY && 1.0 / s < f64::INFINITY { 1.0 / s } else { 0.0 })
}

/// Partial pivoting: the row at or below `k` with the largest magnitude in column `k` (the
/// first on ties; a NaN never wins).
#[inline(always)]
fn pivot_row<const N: usize>(a: &[[f64; N]; N], k: usize) -> usize {
    let mut best = k;
    let mut best_mag = a[k][k].abs();
    for r in 0..N {
        let m = a[r][k].abs();
        if r > k && m > best_mag {
            best = r;
            best_mag = m;
        }
    }
    best
}

/// Back substitution through the upper triangle of `u` (its diagonal as the reciprocals
/// `inv_diag`), in place.
#[inline(always)]
fn back_substitute<const N: usize>(u: &[[f64; N]; N], inv_diag: &[f64; N], z: &mut [f64; N]) {
    for r in (0..N).rev() {
        let mut acc = z[r];
        for c in 0..N {
            if c > r {
                acc -= u[r][c] * z[c];
            }
        }
        z[r] = acc * inv_diag[r];
    }
}

/// How a sparse factorisation's columns are equilibrated: divided by scales (the analogs'
/// columns' magnitudes), whose reciprocals it takes, or multiplied by the unknowns' units (a
/// Newton step's, positive and finite by construction), which are those reciprocals already:
/// their own reciprocals, the scales, only the cold dense fallback needs. Borrowed: a large
/// block's are kilobytes, read once.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ColScales<'a, const N: usize> {
    /// Column `c` divided by `scale[c]`.
    Divided(&'a [f64; N]),
    /// Column `c` multiplied by `unit[c]`.
    Multiplied(&'a [f64; N]),
}

impl<const N: usize> ColScales<'_, N> {
    /// Writes the factors the columns are multiplied by over `factors` (`degenerate` set where
    /// a scale is invalid).
    #[inline(always)]
    pub(crate) fn factors_into(&self, factors: &mut [f64; N], degenerate: &mut bool) {
        match self {
            ColScales::Divided(scale) => inverses_into(scale, factors, degenerate),
            ColScales::Multiplied(unit) => {
                debug_assert!(all_positive_finite(unit), "the units are checked when they are made");
                *factors = **unit;
            }
        }
    }

    /// The scales the columns are divided by, as the dense factorisation takes them (a unit
    /// below about `5.6e-309`, whose reciprocal overflows, makes the dense fallback degenerate:
    /// a mechanism that small in its own unit).
    #[inline(always)]
    pub(crate) fn scales(&self) -> [f64; N] {
        match self {
            ColScales::Divided(scale) => **scale,
            ColScales::Multiplied(unit) => unit.map(|u| 1.0 / u),
        }
    }
}

/// A Newton iteration's row equilibration: the scales, their reciprocals (as [`inverses`]
/// gives them) and whether one was invalid. A block whose row magnitudes do not depend on its
/// unknowns makes it once per solve.
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct RowScales<const N: usize> {
    /// Row `r` is divided by `s[r]`.
    pub s: [f64; N],
    /// `1 / s`, 0 where `s` is invalid or its reciprocal overflows.
    pub inv: [f64; N],
    /// Whether a scale is zero, negative, infinite or NaN, or has no finite reciprocal (the
    /// factorisation is then degenerate).
    pub degenerate: bool,
}

impl<const N: usize> RowScales<N> {
    /// The equilibration by `s`.
    #[inline(always)]
    pub fn new(s: [f64; N]) -> Self {
        let mut degenerate = false;
        let inv = inverses(s, &mut degenerate);
        RowScales { s, inv, degenerate }
    }
}

/// Solves `J x = -f` with the rows of `J` divided by `rows.s`, and returns `x` with the
/// smallest pivot of the row-equilibrated matrix with column `c` multiplied by `unit[c]` (0
/// when degenerate or not finite, as [`Lu::pivot_ratio`]): the Newton step of a dense block.
/// The same operations in the same order as [`Lu::factor`] followed by [`Lu::solve`] of `-f`
/// (so the step is bit for bit the same), without the factorisation's record (permutation,
/// determinant, column scales): the right-hand side is eliminated with the matrix. The
/// columns' units change no choice of pivot row (each scales a whole column) and no step:
/// pivot `k`, of column `k`, is multiplied by `unit[k]` where it is measured.
#[inline(always)]
#[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what lets NaN through
pub(crate) fn solve_row_scaled<const N: usize>(
    j: &[[f64; N]; N],
    f: &[f64; N],
    rows: &RowScales<N>,
    unit: &[f64; N],
) -> ([f64; N], f64) {
    let (inv_row, degenerate) = (rows.inv, rows.degenerate);
    // Scaled in place: no zero-filled array to overwrite.
    let mut a = *j;
    let mut b = [0.0; N];
    for r in 0..N {
        for c in 0..N {
            a[r][c] *= inv_row[r];
        }
        b[r] = -f[r] * inv_row[r];
    }
    let mut min_pivot = f64::INFINITY;
    let mut inv_diag = [0.0; N];
    for k in 0..N {
        let best = pivot_row(&a, k);
        if best != k {
            a.swap(k, best);
            b.swap(k, best);
        }
        let pivot = a[k][k];
        let measured = pivot.abs() * unit[k];
        // `f64::min` would skip a NaN pivot; a NaN must never pass as a regular pivot (the
        // negated comparison holds for a smaller magnitude and for NaN).
        if !(measured >= min_pivot) {
            min_pivot = measured;
        }
        let inv = 1.0 / pivot;
        inv_diag[k] = inv;
        for r in 0..N {
            if r > k {
                let factor = a[r][k] * inv;
                for c in 0..N {
                    if c > k {
                        a[r][c] -= factor * a[k][c];
                    }
                }
                b[r] -= factor * b[k];
            }
        }
    }
    let mut x = b;
    back_substitute(&a, &inv_diag, &mut x);
    let ratio = if degenerate || !min_pivot.is_finite() { 0.0 } else { min_pivot };
    (x, ratio)
}

impl<const N: usize> Lu<N> {
    /// Factorises `j` (rows given as arrays), dividing row `r` by `row_scale[r]`. A zero or
    /// non-finite scale marks the matrix as degenerate (pivot ratio 0).
    #[inline(always)]
    pub fn factor(j: &[[f64; N]; N], row_scale: [f64; N]) -> Self {
        Self::factor_scaled(j, row_scale, [1.0; N])
    }

    /// Factorises `j`, dividing column `c` by `col_scale[c]`.
    #[inline(always)]
    pub fn factor_cols(j: &[[f64; N]; N], col_scale: [f64; N]) -> Self {
        Self::factor_scaled(j, [1.0; N], col_scale)
    }

    /// Factorises `j` equilibrated by both row and column scales.
    ///
    /// The loops run over full ranges with conditions (rather than `k + 1..N`) so that their trip
    /// counts are constants and the compiler unrolls them completely for small blocks.
    #[inline(always)]
    pub fn factor_scaled(j: &[[f64; N]; N], row_scale: [f64; N], col_scale: [f64; N]) -> Self {
        if N == 1 {
            // A scalar block: the equilibration only measures the pivot; the solve divides by
            // the unscaled coefficient (which folds away when it is a constant). The product
            // of the scales is positive and finite for valid scales (it is the column scale
            // itself for `factor_cols`); two comparisons reject zero, negative, infinite and
            // NaN scales, and a scale product out of range, as degenerate.
            let rc = row_scale[0] * col_scale[0];
            let p = if rc > 0.0 && rc < f64::INFINITY { j[0][0] / rc } else { 0.0 };
            let ratio = p.abs();
            return Lu {
                lu: *j,
                perm: [0; N],
                inv_row: [1.0; N],
                rows_scaled: false,
                inv_col: [1.0; N],
                inv_diag: [1.0 / j[0][0]; N],
                // A NaN or infinite pivot counts as singular.
                pivot_ratio: if ratio < f64::INFINITY { ratio } else { 0.0 },
                negative_det: p < 0.0,
                det: p,
            };
        }
        if N == 2 {
            return Self::factor_2x2(j, row_scale, col_scale);
        }
        Self::factor_general(j, row_scale, col_scale)
    }

    /// A placeholder to factorise into (see `newton_keeping_lu`): every field zero, so that
    /// read as it is it is singular ([`Lu::pivot_ratio`] 0).
    #[doc(hidden)]
    #[inline(always)]
    pub const fn unfactored() -> Self {
        Lu {
            lu: [[0.0; N]; N],
            perm: [0; N],
            inv_row: [0.0; N],
            rows_scaled: true,
            inv_col: [0.0; N],
            inv_diag: [0.0; N],
            pivot_ratio: 0.0,
            negative_det: false,
            det: 0.0,
        }
    }

    /// [`Lu::unfactored`] made on the heap, never on the stack: the cold paths of large blocks
    /// keep their dense factorisations there (a block of 256 unknowns is 512 KiB, and a value
    /// built and then moved into a box takes that much of the stack in an unoptimised build).
    #[doc(hidden)]
    pub fn boxed_unfactored() -> Box<Self> {
        // SAFETY: every field of `Lu` is a float, an integer or a bool, or an array of them,
        // for which all-zero bytes are a valid value (0.0, 0, `false`).
        let mut lu = unsafe { Box::<Self>::new_zeroed().assume_init() };
        // The one field of `Lu::unfactored` that is not zero.
        lu.rows_scaled = true;
        lu
    }

    /// [`Lu::factor_scaled`] for any size: partial pivoting on the equilibrated matrix.
    #[inline(always)]
    fn factor_general(j: &[[f64; N]; N], row_scale: [f64; N], col_scale: [f64; N]) -> Self {
        let mut lu = Self::unfactored();
        lu.refactor_general(j, row_scale, col_scale);
        lu
    }

    /// [`Lu::factor_cols`] written over `self`: made where it is kept, since moving a
    /// factorisation of 3 or more unknowns is a copy of `N^2 + 5N` words (a smaller one is
    /// made and moved). `col_scale` holds the columns' largest magnitudes ([`max_abs`]), which
    /// are not screened: one that is zero, infinite or NaN makes
    /// its column of the equilibrated matrix NaN or zero, so a pivot is NaN or zero and
    /// [`Lu::pivot_ratio`] is 0 as in the screened factorisation (only the other fields of such
    /// a degenerate factorisation differ).
    #[inline(always)]
    pub(crate) fn refactor_cols(&mut self, j: &[[f64; N]; N], col_scale: [f64; N]) {
        if N <= 2 {
            *self = Self::factor_cols(j, col_scale);
        } else {
            self.refactor_with(j, [1.0; N], col_scale.map(|s| 1.0 / s), false);
        }
    }

    /// [`Lu::factor_scaled`] written over `self`: where a large factorisation is kept on the
    /// heap, made there rather than on the stack and moved (a block of 256 unknowns is 512 KiB).
    #[inline(always)]
    pub(crate) fn refactor_scaled(&mut self, j: &[[f64; N]; N], row_scale: [f64; N], col_scale: [f64; N]) {
        if N <= 2 {
            *self = Self::factor_scaled(j, row_scale, col_scale);
        } else {
            self.refactor_general(j, row_scale, col_scale);
        }
    }

    /// [`Lu::factor_general`] written over `self` (every field is set).
    #[inline(always)]
    fn refactor_general(&mut self, j: &[[f64; N]; N], row_scale: [f64; N], col_scale: [f64; N]) {
        let mut degenerate = false;
        let inv_row = inverses(row_scale, &mut degenerate);
        let inv_col = inverses(col_scale, &mut degenerate);
        self.refactor_with(j, inv_row, inv_col, degenerate);
    }

    /// The elimination of [`Lu::refactor_general`] from the reciprocals of the scales;
    /// `degenerate` when one was invalid.
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what lets NaN through
    fn refactor_with(&mut self, j: &[[f64; N]; N], inv_row: [f64; N], inv_col: [f64; N], degenerate: bool) {
        self.inv_row = inv_row;
        // A constant set of ones (the analogs' factorisations) folds to `false`.
        self.rows_scaled = inv_row != [1.0; N];
        self.inv_col = inv_col;
        let lu = &mut self.lu;
        for r in 0..N {
            for c in 0..N {
                lu[r][c] = j[r][c] * inv_row[r] * inv_col[c];
            }
        }
        self.eliminate(degenerate);
    }

    /// [`Lu::refactor_scaled`] of the matrix that `load` writes (unscaled, every entry) into the
    /// factorisation's own storage: a large matrix then needs no copy of its own (a block of 256
    /// unknowns is 512 KiB), nor an allocation. The same operations as from a matrix, so the
    /// same bits.
    pub(crate) fn refactor_scaled_loaded(
        &mut self,
        load: impl FnOnce(&mut [[f64; N]; N]),
        row_scale: [f64; N],
        col_scale: [f64; N],
    ) {
        // The general elimination for every size (the 2x2 form of `factor_scaled` gives the same
        // bits); no matrix-sized temporary, which a debug build would keep on the stack.
        let mut degenerate = false;
        let inv_row = inverses(row_scale, &mut degenerate);
        let inv_col = inverses(col_scale, &mut degenerate);
        self.inv_row = inv_row;
        self.rows_scaled = inv_row != [1.0; N];
        self.inv_col = inv_col;
        load(&mut self.lu);
        let lu = &mut self.lu;
        for r in 0..N {
            for c in 0..N {
                lu[r][c] = lu[r][c] * inv_row[r] * inv_col[c];
            }
        }
        self.eliminate(degenerate);
    }

    /// The partial-pivoting elimination of the scaled matrix in `self.lu`; `degenerate` when a
    /// scale was invalid.
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what lets NaN through
    fn eliminate(&mut self, degenerate: bool) {
        let lu = &mut self.lu;
        for (k, p) in self.perm.iter_mut().enumerate() {
            *p = k;
        }
        let mut negative_det = false;
        let mut min_pivot = f64::INFINITY;
        let mut det = 1.0;
        for k in 0..N {
            let best = pivot_row(lu, k);
            if best != k {
                lu.swap(k, best);
                self.perm.swap(k, best);
                negative_det = !negative_det;
                det = -det;
            }
            let pivot = lu[k][k];
            if pivot < 0.0 {
                negative_det = !negative_det;
            }
            // `f64::min` would skip a NaN pivot; a NaN must never pass as a regular pivot (the
            // negated comparison holds for a smaller magnitude and for NaN).
            if !(pivot.abs() >= min_pivot) {
                min_pivot = pivot.abs();
            }
            det *= pivot;
            let inv = 1.0 / pivot;
            self.inv_diag[k] = inv;
            for r in 0..N {
                if r > k {
                    let factor = lu[r][k] * inv;
                    lu[r][k] = factor;
                    for c in 0..N {
                        if c > k {
                            lu[r][c] -= factor * lu[k][c];
                        }
                    }
                }
            }
        }
        self.pivot_ratio = if degenerate || !min_pivot.is_finite() { 0.0 } else { min_pivot };
        self.negative_det = negative_det;
        self.det = det;
    }

    /// The 2x2 case of [`Lu::factor_scaled`] (every dyad, slotted rocker and angle with a slider
    /// solved by Newton is one): the operations of the general elimination in the same order, so
    /// the results are bit-for-bit the same, with the row exchange a selection instead of the
    /// loops' searches and index bookkeeping.
    #[inline(always)]
    fn factor_2x2(j: &[[f64; N]; N], row_scale: [f64; N], col_scale: [f64; N]) -> Self {
        let mut degenerate = false;
        let inv_row = inverses(row_scale, &mut degenerate);
        let inv_col = inverses(col_scale, &mut degenerate);
        let e = |r: usize, c: usize| j[r][c] * inv_row[r] * inv_col[c];
        // Partial pivoting: the second row leads when its first entry is larger (a NaN never
        // is, as in the general search).
        let swap = e(1, 0).abs() > e(0, 0).abs();
        let (top, bottom) = if swap { (1, 0) } else { (0, 1) };
        let (p0, u01, l0, l1) = (e(top, 0), e(top, 1), e(bottom, 0), e(bottom, 1));
        let inv0 = 1.0 / p0;
        let factor = l0 * inv0;
        let p1 = l1 - factor * u01;
        // The general loop's running minimum from infinity: the first pivot's magnitude (a NaN
        // included), then the second's when smaller or NaN.
        // One select: the second when smaller or NaN (the comparison fails for a NaN). A NaN
        // first pivot makes the second NaN too (through `factor`), so it is never lost.
        let min_pivot = if p1.abs() >= p0.abs() { p0.abs() } else { p1.abs() };
        let mut lu = [[0.0; N]; N];
        (lu[0][0], lu[0][1], lu[1][0], lu[1][1]) = (p0, u01, factor, p1);
        let mut perm = [0usize; N];
        perm[0] = top;
        perm[1] = bottom;
        let mut inv_diag = [0.0; N];
        inv_diag[0] = inv0;
        inv_diag[1] = 1.0 / p1;
        Lu {
            lu,
            perm,
            inv_row,
            // As the general factorisation records it (the 2x2 solve does not read it).
            rows_scaled: inv_row != [1.0; N],
            inv_col,
            inv_diag,
            pivot_ratio: if degenerate || !min_pivot.is_finite() { 0.0 } else { min_pivot },
            negative_det: swap ^ (p0 < 0.0) ^ (p1 < 0.0),
            det: (if swap { -1.0 } else { 1.0 }) * p0 * p1,
        }
    }

    /// A direction `w` (in the equilibrated matrix's columns) that the equilibrated matrix maps
    /// to about `0` when its smallest pivot is: `U w = 0` with that pivot taken for zero, `w` one
    /// at its column and zero beyond it, the columns before it by back-substitution (their
    /// pivots the larger). Not finite where an earlier pivot is zero or not finite too.
    pub(crate) fn null_direction(&self) -> [f64; N] {
        let mut k = 0;
        for r in 1..N {
            if self.lu[r][r].abs() < self.lu[k][k].abs() {
                k = r;
            }
        }
        let mut w = [0.0; N];
        w[k] = 1.0;
        for r in (0..k).rev() {
            let acc = (r + 1..=k).fold(0.0, |acc, c| acc - self.lu[r][c] * w[c]);
            w[r] = acc / self.lu[r][r];
        }
        w
    }

    /// Smallest pivot of the equilibrated matrix, in `[0, ~1]`: `0` when singular. `NaN`
    /// inputs give `0`.
    #[inline(always)]
    pub fn pivot_ratio(&self) -> f64 {
        if self.pivot_ratio.is_nan() { 0.0 } else { self.pivot_ratio }
    }

    /// Determinant of the equilibrated matrix: a smooth, signed, unit-free measure whose
    /// zeros are the singular positions (used to locate them along a sweep).
    #[inline(always)]
    pub fn det(&self) -> f64 {
        self.det
    }

    /// Sign of the determinant (`true` when negative); the assembly mode of a block.
    #[inline(always)]
    pub fn negative_det(&self) -> bool {
        self.negative_det
    }

    /// Solves `J z = b`.
    #[inline(always)]
    pub fn solve(&self, b: [f64; N]) -> [f64; N] {
        if N == 1 {
            let mut z = b;
            z[0] *= self.inv_diag[0];
            return z;
        }
        if N == 2 {
            return self.solve_2x2(b);
        }
        self.solve_general(b)
    }

    /// The 2x2 case of [`Lu::solve`]: the general substitutions' operations in the same order
    /// (bit for bit: unit test), with the row exchange a selection instead of indexed loads.
    #[inline(always)]
    fn solve_2x2(&self, b: [f64; N]) -> [f64; N] {
        let swap = self.perm[0] != 0;
        let (top, bottom) = if swap { (1, 0) } else { (0, 1) };
        let z0 = b[top] * self.inv_row[top];
        let z1 = (b[bottom] * self.inv_row[bottom] - self.lu[1][0] * z0) * self.inv_diag[1];
        let z0 = (z0 - self.lu[0][1] * z1) * self.inv_diag[0];
        let mut z = [0.0; N];
        z[0] = z0 * self.inv_col[0];
        z[1] = z1 * self.inv_col[1];
        z
    }

    /// [`Lu::solve`] for any size: forward and back substitution.
    #[inline(always)]
    fn solve_general(&self, b: [f64; N]) -> [f64; N] {
        let mut z = [0.0; N];
        if self.rows_scaled {
            for r in 0..N {
                let p = self.perm[r];
                z[r] = b[p] * self.inv_row[p];
            }
        } else {
            // The same values: a multiplication by one is exact.
            for r in 0..N {
                z[r] = b[self.perm[r]];
            }
        }
        for r in 0..N {
            let mut acc = z[r];
            for c in 0..N {
                if c < r {
                    acc -= self.lu[r][c] * z[c];
                }
            }
            z[r] = acc;
        }
        back_substitute(&self.lu, &self.inv_diag, &mut z);
        for c in 0..N {
            z[c] *= self.inv_col[c];
        }
        z
    }

    /// Solves `J Z = B` for `M` right-hand sides given as rows `B[r][m]`.
    #[inline(always)]
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

impl Lu<1> {
    /// [`Lu::factor_cols`] of the scalar block `[[col[k]]]` whose column scale is the largest
    /// magnitude in `col`, the full Jacobian column the entry belongs to (`max_abs(col)`, as
    /// the generated code passes it): the same pivot ratio, determinant sign, determinant and
    /// solves (unit test) with fewer checks. Because `|col[k]| <= max_abs(col)`, the pivot is in
    /// `[-1, 1]` or NaN, and NaN exactly where the general path finds a degenerate scale (zero:
    /// the whole column is zero, or not finite), except that an infinite scale with a finite
    /// entry gives a zero pivot, as there. [`Lu::pivot_ratio`] reads a NaN as 0; only the
    /// determinant of such a degenerate block differs (NaN instead of 0).
    #[inline(always)]
    pub fn factor_in_col<const M: usize>(col: [f64; M], k: usize) -> Self {
        let j = [[col[k]]];
        let p = j[0][0] / max_abs(col);
        Lu {
            lu: j,
            perm: [0],
            inv_row: [1.0],
            rows_scaled: false,
            inv_col: [1.0],
            inv_diag: [1.0 / j[0][0]],
            pivot_ratio: p.abs(),
            negative_det: p < 0.0,
            det: p,
        }
    }
}

/// What [`Health`](crate::Health) reads from a block's factorisation.
pub trait Factor {
    /// Smallest pivot of the equilibrated matrix: never NaN (a NaN pivot, from a NaN entry or
    /// scale, is reported as 0, singular).
    fn pivot_ratio(&self) -> f64;
    /// Negative determinant.
    fn negative_det(&self) -> bool;
}

impl<const N: usize> Factor for Lu<N> {
    #[inline]
    fn pivot_ratio(&self) -> f64 {
        Lu::pivot_ratio(self)
    }
    #[inline]
    fn negative_det(&self) -> bool {
        Lu::negative_det(self)
    }
}

/// A 1x1 block whose Jacobian is a non-zero constant known at compile time (an unknown that
/// appears linearly with a constant coefficient, such as a slider coordinate in its loop): it is
/// solved by one division, never singular.
#[derive(Clone, Copy, Debug)]
pub struct Fixed(pub f64);

impl Fixed {
    /// Solves `c z = b`.
    #[inline]
    pub fn solve(&self, b: [f64; 1]) -> [f64; 1] {
        [b[0] / self.0]
    }

    /// Solves `c Z = B` for `M` right-hand sides.
    #[inline]
    pub fn solve_cols<const M: usize>(&self, b: [[f64; M]; 1]) -> [[f64; M]; 1] {
        let c = self.0;
        [b[0].map(|v| v / c)]
    }
}

impl Factor for Fixed {
    #[inline]
    fn pivot_ratio(&self) -> f64 {
        1.0
    }
    #[inline]
    fn negative_det(&self) -> bool {
        self.0 < 0.0
    }
}

/// Largest magnitude among `v` (a row or column scale, a residual), or NaN when an entry is
/// NaN: `largest` of the magnitudes.
#[inline]
pub fn max_abs<const M: usize>(v: [f64; M]) -> f64 {
    largest(v.map(f64::abs))
}

/// The largest of the values `v` (each non-negative or NaN), or NaN when one is NaN: per value a
/// select (one `maxsd`, which skips a NaN, where `f64::max` needs a NaN fix-up) and an addition
/// (which does not skip it), where a maximum that keeps a NaN costs a comparison and a blend.
/// A NaN anywhere makes the result NaN (then a row counts as degenerate and a residual as not
/// converged). From `-0.0`, the additive identity, the first addition folds away.
#[inline(always)]
pub(crate) fn largest<const M: usize>(v: [f64; M]) -> f64 {
    let (mut m, mut sum) = (0.0f64, -0.0f64);
    for x in v {
        m = if x > m { x } else { m };
        sum += x;
    }
    if sum.is_nan() { f64::NAN } else { m }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A matrix of rank 2 whose second column is the singular one (`c1 = c0 + c2`): the
    /// direction the factorisation gives is its null vector `(1, -1, 1)` up to its rounding, and
    /// for a regular 2x2 one the smallest pivot's column.
    #[test]
    fn the_null_direction_is_the_singular_columns() {
        let j = [[1.0, 3.0, 2.0], [4.0, 9.0, 5.0], [7.0, 15.0, 8.0]];
        let w = Lu::factor(&j, [1.0; 3]).null_direction();
        let scaled = w.map(|v| v / w[0]);
        let want = [1.0, -1.0, 1.0];
        for (v, want) in scaled.iter().zip(want) {
            assert!((v - want).abs() <= 8.0 * f64::EPSILON, "{scaled:?}");
        }
        let w = Lu::factor(&[[2.0, 0.0], [0.0, 1e-12]], [1.0; 2]).null_direction();
        assert_eq!(w, [0.0, 1.0]);
    }

    /// A positive scale below `1 / f64::MAX` has an infinite reciprocal: the set is degenerate
    /// and that reciprocal 0 (an infinite one would turn a zero residual into NaN), as for a
    /// zero scale; a small scale with a finite reciprocal stays valid.
    #[test]
    fn a_positive_scale_whose_reciprocal_overflows_is_degenerate() {
        let tiny = 1e-310_f64; // positive (subnormal): 1 / tiny overflows to infinity
        assert!(tiny > 0.0 && (1.0 / tiny).is_infinite());
        let mut degenerate = false;
        assert_eq!(inverses([2.0, tiny, 4.0], &mut degenerate), [0.5, 0.0, 0.25]);
        assert!(degenerate);
        let mut degenerate = false;
        // 2^-1000 and 2^1000: exact reciprocals.
        assert_eq!(inverses([2.0, 0.5f64.powi(1000)], &mut degenerate), [0.5, 2f64.powi(1000)]);
        assert!(!degenerate);
        let rows = RowScales::new([1.0, tiny, 1.0]);
        assert!(rows.degenerate);
        assert_eq!(rows.inv, [1.0, 0.0, 1.0]);
        let j = [[2.0, 0.0, 0.0], [0.0, 3.0, 0.0], [0.0, 0.0, 5.0]];
        assert_eq!(Lu::<3>::factor(&j, [1.0, tiny, 1.0]).pivot_ratio(), 0.0);
        assert_eq!(Lu::<3>::factor_cols(&j, [1.0, 1.0, tiny]).pivot_ratio(), 0.0);
    }

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
        // det = 0*(1-0) - 2*(1-0) + 1*(0-3) = -5; rows scaled by 1/2, 1/1, 1/3.
        assert!(lu.negative_det());
        assert!((lu.det() - (-5.0 / 6.0)).abs() < 1e-14, "{}", lu.det());
    }

    /// The bits of every field of a factorisation, to compare two bit for bit.
    fn bits(lu: &Lu<2>) -> Vec<u64> {
        let f = [
            lu.lu.concat(),
            lu.inv_row.to_vec(),
            lu.inv_col.to_vec(),
            lu.inv_diag.to_vec(),
            vec![lu.pivot_ratio, lu.det],
        ];
        // Any NaN is the same NaN (its sign bit is not a result).
        let mut v: Vec<u64> = f.concat().iter().map(|x| if x.is_nan() { u64::MAX } else { x.to_bits() }).collect();
        v.extend(lu.perm.iter().map(|&p| p as u64));
        v.push(u64::from(lu.negative_det));
        v
    }

    /// The kept factorisation with unscreened column magnitudes (`refactor_cols`, 3x3 and 4x4) is
    /// the screened `factor_cols`, bit for bit, wherever the magnitudes are valid, and where one
    /// is not (a zero column, an infinite or NaN entry, a NaN or zero magnitude) its pivot ratio
    /// is 0 as the screened one's.
    #[test]
    fn unscreened_column_magnitudes_give_the_screened_pivot_ratio() {
        fn check<const N: usize>(j: [[f64; N]; N], cols: [f64; N]) {
            let canon = |x: f64| if x.is_nan() { u64::MAX } else { x.to_bits() };
            let screened = Lu::factor_cols(&j, cols);
            let mut kept = Lu::unfactored();
            kept.refactor_cols(&j, cols);
            assert_eq!(canon(kept.pivot_ratio()), canon(screened.pivot_ratio()), "{j:?} {cols:?}");
            if cols.iter().all(|&c| c > 0.0 && c < f64::INFINITY) {
                assert_eq!(canon(kept.det()), canon(screened.det()), "{j:?}");
                assert_eq!(kept.negative_det(), screened.negative_det(), "{j:?}");
                for k in 0..N {
                    let mut e = [0.0; N];
                    e[k] = 1.0;
                    assert_eq!(kept.solve(e).map(canon), screened.solve(e).map(canon), "{j:?}");
                }
            } else {
                assert_eq!(kept.pivot_ratio(), 0.0, "{j:?} {cols:?}");
            }
        }
        // The columns' largest magnitudes as the Newton iteration takes them (plain maxima).
        fn magnitudes<const N: usize>(j: &[[f64; N]; N]) -> [f64; N] {
            core::array::from_fn(|c| j.iter().fold(0.0f64, |m, row| if row[c].abs() > m { row[c].abs() } else { m }))
        }
        let specials = [0.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 1e-310, 1e308];
        for seed in 0..300usize {
            let mut j: [[f64; 4]; 4] =
                core::array::from_fn(|r| core::array::from_fn(|c| ((seed * 31 + r * 7 + c * 13) % 17) as f64 - 8.0));
            if seed % 3 == 0 {
                j[seed % 4][(seed / 4) % 4] = specials[(seed / 16) % specials.len()];
            }
            if seed % 7 == 0 {
                for row in &mut j {
                    row[seed % 4] = 0.0;
                }
            }
            check(j, magnitudes(&j));
            let j3: [[f64; 3]; 3] = core::array::from_fn(|r| core::array::from_fn(|c| j[r][c]));
            check(j3, magnitudes(&j3));
            // A magnitude that is NaN or zero although the column is not.
            check(j, [f64::NAN, 1.0, 1.0, 1.0]);
            check(j, [1.0, 0.0, 1.0, 1.0]);
        }
    }

    /// The unrolled 2x2 factorisation is the general elimination, bit for bit, on regular,
    /// singular, row-exchanging, negative, zero, infinite and NaN entries and scales.
    #[test]
    fn the_2x2_case_is_the_general_elimination() {
        let values = [0.0, -0.0, 1.0, -2.5, 3.0e-7, 7.0e5, 1.0 + 1e-14, f64::INFINITY, f64::NAN];
        let scales = [1.0, 2.0, 0.0, -1.0, 1e-300, f64::INFINITY, f64::NAN];
        let mut n = 0usize;
        for (i, &a) in values.iter().enumerate() {
            for (k, &b) in values.iter().enumerate() {
                let (c, d) = (values[(i + 3 * k + 1) % values.len()], values[(2 * i + k + 5) % values.len()]);
                let j = [[a, b], [c, d]];
                for (r, &s) in scales.iter().enumerate() {
                    let rows = [1.0, s];
                    let cols = [scales[(r + i) % scales.len()], 0.5];
                    let fast = Lu::<2>::factor_scaled(&j, rows, cols);
                    let general = Lu::<2>::factor_general(&j, rows, cols);
                    assert_eq!(bits(&fast), bits(&general), "{j:?} {rows:?} {cols:?}");
                    let rhs = [b - 1.0, a + 0.25];
                    let (zf, zg) = (fast.solve(rhs), general.solve_general(rhs));
                    let canon = |z: [f64; 2]| z.map(|x| if x.is_nan() { u64::MAX } else { x.to_bits() });
                    assert_eq!(canon(zf), canon(zg));
                    assert_eq!(canon(general.solve(rhs)), canon(zg));
                    n += 1;
                }
            }
        }
        assert_eq!(n, 9 * 9 * 7);
    }

    /// The scalar factorisation inside its column is the general one with the column scale
    /// `max_abs(col)`: the same pivot ratio, determinant sign and solves on regular, zero,
    /// signed-zero, tiny, huge, infinite and NaN entries; the same determinant wherever the
    /// scale is valid.
    #[test]
    fn the_scalar_in_its_column_is_the_general_factorisation() {
        let values = [0.0, -0.0, 1.0, -2.5, 3.0e-7, -7.0e5, 1e-310, 1e308, f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
        let canon = |x: f64| if x.is_nan() { u64::MAX } else { x.to_bits() };
        let mut n = 0;
        for &a in &values {
            for &b in &values {
                for &c in &values {
                    let col = [a, b, c];
                    for k in 0..3 {
                        let fast = Lu::<1>::factor_in_col(col, k);
                        let general = Lu::<1>::factor_cols(&[[col[k]]], [max_abs(col)]);
                        let at = format!("{col:?} {k}");
                        assert_eq!(fast.pivot_ratio().to_bits(), general.pivot_ratio().to_bits(), "{at}");
                        assert_eq!(fast.negative_det(), general.negative_det(), "{at}");
                        if general.pivot_ratio() > 0.0 {
                            assert_eq!(fast.det().to_bits(), general.det().to_bits(), "{at}");
                        }
                        for rhs in [1.5, -0.0, f64::INFINITY] {
                            assert_eq!(canon(fast.solve([rhs])[0]), canon(general.solve([rhs])[0]), "{at}");
                        }
                        n += 1;
                    }
                }
            }
        }
        assert_eq!(n, 11 * 11 * 11 * 3);
    }

    /// The Newton step's elimination with its right-hand side is the factorisation followed by
    /// the solve, bit for bit (step and pivot ratio), on regular, row-exchanging, singular,
    /// infinite and NaN matrices and degenerate scales, for 3x3 and 4x4 blocks. With the
    /// unknowns' units (powers of two, which scale exactly) the step is the same and the pivot
    /// ratio that of the matrix with its columns multiplied by them.
    #[test]
    fn the_newton_step_is_the_factorisation_and_solve() {
        fn check<const N: usize>(j: [[f64; N]; N], f: [f64; N], s: [f64; N]) {
            let canon = |x: f64| if x.is_nan() { u64::MAX } else { x.to_bits() };
            let (x, ratio) = solve_row_scaled(&j, &f, &RowScales::new(s), &[1.0; N]);
            let lu = Lu::factor(&j, s);
            let z = lu.solve(f.map(|v| -v));
            assert_eq!(x.map(canon), z.map(canon), "{j:?} {f:?} {s:?}");
            assert_eq!(canon(ratio), canon(lu.pivot_ratio()), "{j:?} {s:?}");
            let unit: [f64; N] = std::array::from_fn(|c| [2f64.powi(20), 1.0, 2f64.powi(-7), 4.0][c]);
            let (xu, ratio_u) = solve_row_scaled(&j, &f, &RowScales::new(s), &unit);
            assert_eq!(xu.map(canon), x.map(canon), "{j:?} {f:?} {s:?}");
            let scaled = Lu::factor_scaled(&j, s, unit.map(|u| 1.0 / u));
            assert_eq!(canon(ratio_u), canon(scaled.pivot_ratio()), "{j:?} {s:?}");
        }
        let values = [0.0, 1.0, -2.5, 3.0e-7, 7.0e5, 1.0 + 1e-14, -0.75, 4.25, f64::INFINITY, f64::NAN];
        let scales = [1.0, 2.0, 0.3, 0.0, f64::INFINITY, f64::NAN];
        let pick = |k: usize| values[(k * 7 + k / 3) % values.len()];
        for seed in 0..400usize {
            // Mostly finite entries (every row exchange pattern), sometimes a special value.
            let v = |r: usize, c: usize| {
                let k = seed * 31 + r * 11 + c * 5;
                if k.is_multiple_of(17) { pick(k) } else { ((k * 7919) % 1000) as f64 / 97.0 - 5.0 }
            };
            let sc =
                |r: usize| if seed.is_multiple_of(9) { scales[(seed / 9 + r) % scales.len()] } else { 1.0 + r as f64 };
            check::<3>(
                std::array::from_fn(|r| std::array::from_fn(|c| v(r, c))),
                [v(3, 0), v(3, 1), v(3, 2)],
                [sc(0), sc(1), sc(2)],
            );
            check::<4>(
                std::array::from_fn(|r| std::array::from_fn(|c| v(r, c))),
                [v(4, 0), v(4, 1), v(4, 2), v(4, 3)],
                [sc(0), sc(1), sc(2), sc(3)],
            );
        }
        // The class IV block's sparsity (structural zeros) at a regular position.
        check::<4>(
            [[-1.2, 0.8, -1.9, 0.0], [2.0, -1.4, 0.6, 0.0], [-2.2, 3.1, 0.0, -0.5], [0.9, -1.6, 0.0, 3.3]],
            [1e-9, -2e-9, 3e-10, 0.0],
            [9.0, 6.0, 12.0, 9.0],
        );
    }

    /// The one-comparison test of a set of scales is the two comparisons of each.
    #[test]
    fn positive_finite_sets() {
        let tiny = f64::from_bits(1);
        let values = [
            1.0,
            0.0,
            -0.0,
            -1.0,
            tiny,
            -tiny,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            -f64::INFINITY,
            f64::NAN,
        ];
        for &a in &values {
            assert_eq!(all_positive_finite(&[a]), a > 0.0 && a < f64::INFINITY, "{a:e}");
            for &b in &values {
                let both = [a, b].iter().all(|&v| v > 0.0 && v < f64::INFINITY);
                assert_eq!(all_positive_finite(&[a, b, 2.5]), both, "{a:e} {b:e}");
            }
        }
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
        // A NaN pivot after a regular one (f64::min would keep the regular one).
        let lu = Lu::<3>::factor(&[[4.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, f64::NAN]], [4.0, 1.0, 1.0]);
        assert_eq!(lu.pivot_ratio(), 0.0);
    }

    #[test]
    fn column_scaling_solves_and_detects() {
        // A rotating link's column has constant magnitude: scaling by it exposes the dead
        // centre where the block's own entry vanishes.
        let j = [[3.0, 0.5], [0.2, 4.0]];
        let lu = Lu::<2>::factor_scaled(&j, [1.0, 2.0], [3.0, 4.0]);
        let x = [0.7, -1.1];
        let b = [3.0 * 0.7 + 0.5 * -1.1, 0.2 * 0.7 + 4.0 * -1.1];
        let z = lu.solve(b);
        assert!((z[0] - x[0]).abs() < 1e-14 && (z[1] - x[1]).abs() < 1e-14, "{z:?}");
        let dead = Lu::<1>::factor_cols(&[[3.0 * 1e-9]], [3.0]);
        assert!(dead.pivot_ratio() < 1e-8);
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
