//! The numeric steps of a sparse block's factorisation along its static order ([`SparseSteps`]):
//! loading the equilibrated entries into the factor's slots, the elimination, and the forward
//! and back substitution. Two implementations do the same arithmetic in the same order, so
//! their results agree bit for bit: [`Tables`], loops over the index tables of a
//! [`SparsePattern`], and the straight-line code the macro emits for each large sparse block
//! (every slot a constant index, no table read, no loop).
//!
//! Both test every pivot against the other entries of its column in the active submatrix
//! (threshold partial pivoting, [`THRESHOLD`](super::sparse_lu::THRESHOLD)): where one is weak,
//! zero or not finite the elimination reports it and the caller factorises densely.

use super::sparse_lu::{SparsePattern, THRESHOLD};

/// The numeric steps of a sparse factorisation along a static order (see the module
/// documentation). `N` unknowns, `NLU` slots of the factor.
#[doc(hidden)]
pub trait SparseSteps<const N: usize, const NLU: usize> {
    /// The factor's slots before elimination: entry `e` of row `r`, column `c` (value `v[e]`)
    /// as `v[e] * inv_row[r] * inv_col[c]` at its slot, fill slots zero.
    fn load<const NNZ: usize>(p: &SparsePattern, v: &[f64; NNZ], inv_row: &[f64; N], inv_col: &[f64; N]) -> [f64; NLU];

    /// Eliminates `lu` in place: `L` below the pivots (multipliers), `U` above, the pivots'
    /// reciprocals in `inv_diag`; multiplies `det` by every pivot and flips `negative` at every
    /// negative one. Returns the smallest pivot magnitude, or `None` when a pivot is weak
    /// (below [`THRESHOLD`] times the largest entry of its column), zero or not finite; then
    /// `lu`, `inv_diag`, `det` and `negative` hold nothing usable.
    fn eliminate(
        p: &SparsePattern,
        lu: &mut [f64; NLU],
        inv_diag: &mut [f64; N],
        det: &mut f64,
        negative: &mut bool,
    ) -> Option<f64>;

    /// Solves `L U z = z` in place (`z` in pivot order).
    fn substitute(p: &SparsePattern, lu: &[f64; NLU], inv_diag: &[f64; N], z: &mut [f64; N]);
}

/// The steps as loops over a [`SparsePattern`]'s index tables.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, Default)]
pub struct Tables;

impl<const N: usize, const NLU: usize> SparseSteps<N, NLU> for Tables {
    fn load<const NNZ: usize>(p: &SparsePattern, v: &[f64; NNZ], inv_row: &[f64; N], inv_col: &[f64; N]) -> [f64; NLU] {
        let mut lu = [0.0; NLU];
        for (r, &ir) in inv_row.iter().enumerate() {
            let e = p.row_ptr[r] as usize..p.row_ptr[r + 1] as usize;
            for ((&s, &c), &v) in p.slot[e.clone()].iter().zip(&p.col[e.clone()]).zip(&v[e]) {
                lu[s as usize] = v * ir * inv_col[c as usize];
            }
        }
        lu
    }

    fn eliminate(
        p: &SparsePattern,
        lu: &mut [f64; NLU],
        inv_diag: &mut [f64; N],
        det: &mut f64,
        negative: &mut bool,
    ) -> Option<f64> {
        let (mut upd, mut min_pivot) = (p.upd.iter(), f64::INFINITY);
        for k in 0..N {
            let pivot = lu[p.diag[k] as usize];
            let lower = &p.l_slot[p.l_ptr[k] as usize..p.l_ptr[k + 1] as usize];
            let upper = &p.u_slot[p.u_ptr[k] as usize..p.u_ptr[k + 1] as usize];
            let mut col_max = 0.0f64;
            for &s in lower {
                // NaN propagates (`f64::max` would drop it).
                let a = lu[s as usize].abs();
                if a > col_max || a.is_nan() {
                    col_max = a;
                }
            }
            // NaN fails the test (the dense factorisation reports it).
            let magnitude = pivot.abs();
            if !(magnitude >= THRESHOLD * col_max && magnitude > 0.0 && magnitude < f64::INFINITY) {
                return None;
            }
            min_pivot = min_pivot.min(magnitude);
            *det *= pivot;
            if pivot < 0.0 {
                *negative = !*negative;
            }
            let inv = 1.0 / pivot;
            inv_diag[k] = inv;
            for &s in lower {
                let li = lu[s as usize] * inv;
                lu[s as usize] = li;
                // `zip` takes the next `upper.len()` targets (it asks `upper` first).
                for (&u, &t) in upper.iter().zip(upd.by_ref()) {
                    lu[t as usize] -= li * lu[u as usize];
                }
            }
        }
        Some(min_pivot)
    }

    fn substitute(p: &SparsePattern, lu: &[f64; NLU], inv_diag: &[f64; N], z: &mut [f64; N]) {
        for k in 0..N {
            let (zk, l) = (z[k], p.l_ptr[k] as usize..p.l_ptr[k + 1] as usize);
            for (&s, &i) in p.l_slot[l.clone()].iter().zip(&p.l_row[l]) {
                z[i as usize] -= lu[s as usize] * zk;
            }
        }
        for k in (0..N).rev() {
            let (mut acc, u) = (z[k], p.u_ptr[k] as usize..p.u_ptr[k + 1] as usize);
            for (&s, &j) in p.u_slot[u.clone()].iter().zip(&p.u_col[u]) {
                acc -= lu[s as usize] * z[j as usize];
            }
            z[k] = acc * inv_diag[k];
        }
    }
}

/// `v * r * c`, an entry `v` of a block equilibrated by its row's and its column's inverse
/// scales `r` and `c` ([`SparseSteps::load`]), in the tables' order of operations.
#[doc(hidden)]
#[inline(always)]
pub fn scaled(v: f64, r: f64, c: f64) -> f64 {
    v * r * c
}

/// The running state of an elimination emitted as straight-line code: every pivot is tested
/// and accumulated here, and the elimination is judged once at its end ([`Pivots::finish`]),
/// so the straight-line code has no branch. After a weak pivot the remaining arithmetic runs on
/// values nobody reads: the caller factorises densely.
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Pivots {
    ok: bool,
    min: f64,
    det: f64,
    negative: bool,
}

impl Pivots {
    /// Starts from the determinant `det` and its sign `negative` of the permutations.
    #[inline(always)]
    pub fn new(det: f64, negative: bool) -> Self {
        Pivots { ok: true, min: f64::INFINITY, det, negative }
    }

    /// Takes `p` as the next pivot, `lower` the other entries of its column in the active
    /// submatrix: tests it as [`Tables`] does (`|p| >= THRESHOLD * max |lower|`, zero and
    /// non-finite pivots and NaN entries fail) and returns `1 / p`.
    #[inline(always)]
    pub fn pivot<const M: usize>(&mut self, p: f64, lower: [f64; M]) -> f64 {
        let q = p.abs();
        // `THRESHOLD * max |l| <= q` for every `l` at once: multiplying by a positive constant
        // keeps the order, so this is the tables' test of the largest entry; a NaN fails it.
        let mut ok = q > 0.0 && q < f64::INFINITY;
        for l in lower {
            ok &= THRESHOLD * l.abs() <= q;
        }
        self.ok &= ok;
        self.min = if q < self.min { q } else { self.min };
        self.det *= p;
        self.negative ^= p < 0.0;
        1.0 / p
    }

    /// Writes the determinant and its sign, and returns the smallest pivot, or `None` when a
    /// pivot failed its test.
    #[inline(always)]
    pub fn finish(self, det: &mut f64, negative: &mut bool) -> Option<f64> {
        *det = self.det;
        *negative = self.negative;
        self.ok.then_some(self.min)
    }
}
