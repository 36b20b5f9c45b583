//! The explicit inverse of a 2x2 block, for its analogs: every closed-form dyad, slotted rocker
//! and angle with a slider is a 2x2 block, and its velocity and acceleration analogs are two
//! solves with one Jacobian. Cramer's rule is forward stable for two unknowns, and after the
//! inverse is made each solve is four products and two sums, where a pivoted, equilibrated LU
//! solve also selects rows and scales both ways.
//!
//! The inverse reports what the LU reports ([`Factor`]): the same pivot ratio (the smallest pivot
//! of the column-equilibrated matrix under partial pivoting, to rounding) and the sign of the
//! determinant, so the sweep's singularity tests and assembly modes read it unchanged.

use super::closed::reciprocal_power_of_two;
use super::lu::Factor;

/// `J⁻¹` of a 2x2 block `J`, with the pivot ratio and determinant sign of its column-equilibrated
/// LU (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub struct Inverse2 {
    /// `[d, a] / det` for `J = [[a, b], [c, d]]`: the diagonal of `J⁻¹`.
    diag: [f64; 2],
    /// `[b, c] / det`: the off-diagonal of `J⁻¹` with its signs flipped (see
    /// [`Inverse2::solve`]).
    ///
    /// Kept apart from the diagonal as [`Inverse2::solve`] reads them, one pair each: where the
    /// inverse is made in memory (it is the value of a branch whose other arm is out of line),
    /// a solve that read two rows' halves as one pair would wait for both stores to retire (a
    /// store cannot be forwarded to a load that spans two of them): the gear-lever's point
    /// step takes about 7 % longer so in CPU time, its sweep's sample about 12 %.
    off: [f64; 2],
    pivot_ratio: f64,
    negative_det: bool,
}

impl Inverse2 {
    /// The inverse of `j`, whose column `c` is equilibrated by the largest magnitude among its
    /// two entries and `beyond[c]`, the column's further non-zero entries in the full Jacobian
    /// (the rows of later blocks, padded with zeros; an entry in a row of another unit than the
    /// block's weighed into the block's unit by the macro): the largest magnitudes of the whole
    /// columns, by which [`Lu::factor_cols`](super::lu::Lu::factor_cols) would equilibrate.
    ///
    /// The LU's first pivot is the larger entry of the first column, `t / m0` with `t =
    /// max(|j00|, |j10|)` and `m0`, `m1` the columns' magnitudes; the second is the
    /// equilibrated determinant over the first, `|det| / (t m1)`. A zero, infinite or NaN
    /// magnitude or entry gives pivot ratio 0, as there: one of the block's own makes a pivot
    /// NaN (through `t`, the determinant or a magnitude), one beyond it the sum of those entries.
    #[inline(always)]
    pub fn in_cols<const K: usize>(j: &[[f64; 2]; 2], beyond: [[f64; K]; 2]) -> Self {
        Self::in_cols_floored(j, beyond, [None; 2])
    }

    /// [`Inverse2::in_cols`] with column `c`'s magnitude raised to at least `floor[c]` when there
    /// is one (`None`, known when the code is compiled, costs nothing): the lever floor of an
    /// angle whose lever is a variable length, which keeps the pivot ratio from hiding the
    /// singular position where that length vanishes. The general factorisation equilibrated by
    /// `max(column magnitude, floor)` reports the same (unit test); a NaN or infinite floor gives
    /// pivot ratio 0, as an entry beyond the block does.
    ///
    /// Where the determinant or a pivot leaves the range of `f64` although the block is regular
    /// (entries about `s` give a determinant about `s²`, beyond it for `s` beyond about `1e±154`),
    /// the inverse is made from the columns divided by powers of two near their magnitudes
    /// (exact), which changes neither the pivots nor the determinant's sign.
    #[inline(always)]
    pub fn in_cols_floored<const K: usize>(j: &[[f64; 2]; 2], beyond: [[f64; K]; 2], floor: [Option<f64>; 2]) -> Self {
        match Self::unscaled(j, beyond, floor) {
            Ok(inverse) => inverse,
            Err(magnitudes) => {
                let [[a, b], [c, d]] = *j;
                Self::column_scaled(a, b, c, d, beyond, floor[0], floor[1], magnitudes)
            }
        }
    }

    /// [`Inverse2::in_cols_floored`] as computed, or the columns' magnitudes where a pivot, the
    /// determinant or its reciprocal is not finite (pivot ratio 0 as computed: singular, or out
    /// of range).
    #[inline(always)]
    fn unscaled<const K: usize>(
        j: &[[f64; 2]; 2],
        beyond: [[f64; K]; 2],
        floor: [Option<f64>; 2],
    ) -> Result<Self, [f64; 2]> {
        let [[a, b], [c, d]] = *j;
        let det = a * d - b * c;
        let id = 1.0 / det;
        let select_max = |x: f64, y: f64| if x > y { x } else { y };
        let top = select_max(c.abs(), a.abs());
        // The columns' magnitudes by selects, which skip a NaN; the sum of the entries beyond the
        // block does not (a block without any, the usual case, has no sum to make).
        let (mut m, mut sum) = ([top, select_max(d.abs(), b.abs())], 0.0);
        for k in 0..2 {
            for v in beyond[k] {
                m[k] = select_max(v.abs(), m[k]);
                sum += v;
            }
            if let Some(f) = floor[k] {
                m[k] = select_max(f, m[k]);
                sum += f;
            }
        }
        // Without entries beyond the block or a floor, the first column's magnitude is `top`:
        // its pivot is 1 (or NaN, which the second shares: no division for it).
        let p0 = if K == 0 && floor[0].is_none() { 1.0 } else { top / m[0] };
        let tm = top * m[1];
        let p1 = det.abs() / tm;
        let smaller = if p1 < p0 { p1 } else { p0 };
        // A NaN or infinite pivot, or a NaN or infinite entry beyond the block, or a determinant
        // whose reciprocal is not finite, fails the test however the selections went; so does a
        // product `tm` of the magnitudes that overflows where the determinant does not (a
        // regular block near a singular position with entries about `1e154`: `p1` came out 0, a
        // finite pivot, and the block was reported singular at that size alone).
        if p0 + p1 + 0.0 * (sum + id + tm) < f64::INFINITY {
            Ok(Inverse2 {
                diag: [d * id, a * id],
                off: [b * id, c * id],
                pivot_ratio: smaller,
                negative_det: det < 0.0,
            })
        } else {
            Err(m)
        }
    }

    /// The inverse made from `J D`, `D` the powers of two nearest the reciprocals of the
    /// columns' magnitudes `m`: `J⁻¹ = D (J D)⁻¹`. Pivot ratio 0 where that fails too (a
    /// singular block, or a NaN or infinite entry), as the LU's. Given the block's entries
    /// (rows `[a, b]`, `[c, d]`) and each floor one by one, which are passed in registers:
    /// given a reference to the entries, then the entries and the floors as arrays, this call
    /// out of line kept them in memory on the path that does not make it, stored at every step
    /// (measured with callgrind on the four-bar, the gear-lever and the series of 64 loops).
    #[allow(clippy::too_many_arguments)] // one by one, for the registers (see above)
    #[cold]
    #[inline(never)]
    fn column_scaled<const K: usize>(
        a: f64,
        b: f64,
        c: f64,
        d: f64,
        beyond: [[f64; K]; 2],
        floor0: Option<f64>,
        floor1: Option<f64>,
        m: [f64; 2],
    ) -> Self {
        let s = m.map(reciprocal_power_of_two);
        let scaled = [[a * s[0], b * s[1]], [c * s[0], d * s[1]]];
        let beyond = [beyond[0].map(|v| v * s[0]), beyond[1].map(|v| v * s[1])];
        let floor = [floor0.map(|f| f * s[0]), floor1.map(|f| f * s[1])];
        match Self::unscaled(&scaled, beyond, floor) {
            // Row `k` of the inverse (the unknown `k`) scaled back by `s[k]`: the diagonal's and
            // the off-diagonal's entry `k`.
            Ok(mut inverse) => {
                inverse.diag = [inverse.diag[0] * s[0], inverse.diag[1] * s[1]];
                inverse.off = [inverse.off[0] * s[0], inverse.off[1] * s[1]];
                inverse
            }
            Err(_) => {
                let det = a * d - b * c;
                let id = 1.0 / det;
                Inverse2 { diag: [d * id, a * id], off: [b * id, c * id], pivot_ratio: 0.0, negative_det: det < 0.0 }
            }
        }
    }

    /// Smallest pivot of the equilibrated matrix, in `[0, ~1]`: `0` when singular.
    #[inline(always)]
    pub fn pivot_ratio(&self) -> f64 {
        self.pivot_ratio
    }

    /// Solves `J z = r`.
    #[inline(always)]
    pub fn solve(&self, r: [f64; 2]) -> [f64; 2] {
        // `off` holds the inverse's off-diagonal entries with their signs flipped (a subtraction
        // here instead of a negation per entry when it is made).
        let ([i00, i11], [i01, i10]) = (self.diag, self.off);
        [i00 * r[0] - i01 * r[1], i11 * r[1] - i10 * r[0]]
    }

    /// Solves `J Z = B` for `M` right-hand sides given as rows `B[r][m]`.
    #[inline(always)]
    pub fn solve_cols<const M: usize>(&self, b: [[f64; M]; 2]) -> [[f64; M]; 2] {
        let mut out = [[0.0; M]; 2];
        for m in 0..M {
            let [z0, z1] = self.solve([b[0][m], b[1][m]]);
            (out[0][m], out[1][m]) = (z0, z1);
        }
        out
    }
}

impl Factor for Inverse2 {
    #[inline]
    fn pivot_ratio(&self) -> f64 {
        self.pivot_ratio
    }
    #[inline]
    fn negative_det(&self) -> bool {
        self.negative_det
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::lu::{Lu, max_abs};
    use crate::test_rng::Rng;

    /// The general factorisation equilibrated by the columns' largest magnitudes.
    fn general<const M: usize>(j: &[[f64; 2]; 2], cols: [[f64; M]; 2]) -> Lu<2> {
        Lu::<2>::factor_cols(j, [max_abs(cols[0]), max_abs(cols[1])])
    }

    /// A regular block near a singular position, its entries about `s`: the pivot ratio is the
    /// same at every size, also where the product of the magnitudes in the second pivot's
    /// denominator overflows while the determinant's products do not (rows `1.5 (s, s)` and
    /// `(s, (1 + 1e-8) s)` at `s` about `1e154`: `(1.5 s)² = 2.25e308`, `1.5 s² = 1.5e308`). It
    /// came out 0 there, a regular block reported singular at those sizes alone. The reference
    /// is the unit block's ratio in exact arithmetic, `|det| / (max|col 0| max|col 1|)` =
    /// `1.5e-8 / 2.25`, to the rounding of `1 + 1e-8` (1e-8 of it).
    #[test]
    fn a_regular_block_has_its_pivot_ratio_at_every_size() {
        let want = 1.5e-8 / 2.25;
        for s in [1.0, 1e150, 1e154, 1.05e154, 1e155, 1e-154, 1e-160] {
            let j = [[1.5 * s, 1.5 * s], [s, (1.0 + 1e-8) * s]];
            let inv = Inverse2::in_cols(&j, [[], []]);
            let got = inv.pivot_ratio();
            assert!((got - want).abs() <= 1e-7 * want, "size {s:e}: pivot ratio {got:e}, want {want:e}");
            // And the inverse solves the block, to its condition (about 1e8 roundings).
            let x = inv.solve([1.5 * s, s]);
            assert!((x[0] - 1.0).abs() < 1e-6 && x[1].abs() < 1e-6, "size {s:e}: {x:?}");
        }
    }

    /// Against the equilibrated LU over random blocks of entries spanning 24 orders of magnitude
    /// (each column its own unit, some columns with a third entry from another block) and
    /// condition numbers up to 1e12: the pivot ratio to a few roundings, the determinant's sign
    /// wherever it is not rounding noise, and solutions within the forward error a backward
    /// stable solve allows (the condition number times a few units in the last place).
    #[test]
    fn the_inverse_agrees_with_the_equilibrated_lu() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mut worst = 0.0f64;
        for n in 0..20_000 {
            let mut u = || rng.uniform(-1.0, 1.0);
            let units = [10f64.powf(12.0 * u()), 10f64.powf(12.0 * u())];
            let near_singular = 10f64.powf(-6.0 * (u() + 1.0));
            let (a, b, c) = (u(), u(), u());
            // d near b c / a makes every third block nearly singular.
            let d = if n % 3 == 0 { b * c / a + near_singular * u() } else { u() };
            let j = [[a * units[0], b * units[1]], [c * units[0], d * units[1]]];
            let extra = if n % 2 == 0 { 0.0 } else { 1.5 * u() * units[0] };
            let cols = [[j[0][0], j[1][0], extra], [j[0][1], j[1][1], 0.0]];
            // Without an entry beyond the block, the form without any (its own first pivot).
            let inv =
                if extra == 0.0 { Inverse2::in_cols(&j, [[]; 2]) } else { Inverse2::in_cols(&j, [[extra], [0.0]]) };
            let lu = general(&j, cols);
            let (pi, pl) = (inv.pivot_ratio(), lu.pivot_ratio());
            assert!((pi - pl).abs() <= 1e-13 * pl + 1e-15, "{j:?}: {pi:e} {pl:e}");
            if pl > 1e-10 {
                assert_eq!(inv.negative_det(), lu.negative_det(), "{j:?}");
                let r = [u(), u()];
                let (zi, zl) = (inv.solve(r), lu.solve(r));
                for k in 0..2 {
                    // In units of the solution's own column: relative to the larger component.
                    let scale = zl[k].abs().max(zl[1 - k].abs() * units[1 - k] / units[k]);
                    let err = (zi[k] - zl[k]).abs() / scale * pl;
                    worst = worst.max(err);
                }
            }
        }
        assert!(worst < 1e-14, "{worst:e}");
    }

    /// With a floor on either column: the general factorisation equilibrated by the larger of
    /// the column's magnitude and its floor, over random blocks and floors from far below to far
    /// above the columns' magnitudes; a NaN or infinite floor gives pivot ratio 0.
    #[test]
    fn a_floored_column_agrees_with_the_lu_equilibrated_by_its_floor() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for n in 0..10_000 {
            let mut u = || rng.uniform(-1.0, 1.0);
            let j = [[u(), 3.0 * u()], [u(), 3.0 * u()]];
            let mut floor = [None, None];
            floor[n % 2] = Some(10f64.powf(4.0 * u()));
            let extra = if n % 3 == 0 { 2.0 * u() } else { 0.0 };
            let inv = Inverse2::in_cols_floored(&j, [[extra], [0.0]], floor);
            let cols = [[j[0][0], j[1][0], extra], [j[0][1], j[1][1], 0.0]];
            let lu = Lu::<2>::factor_cols(&j, [0, 1].map(|c| max_abs(cols[c]).max(floor[c].unwrap_or(0.0))));
            let (pi, pl) = (inv.pivot_ratio(), lu.pivot_ratio());
            assert!((pi - pl).abs() <= 1e-13 * pl + 1e-15, "{j:?} {floor:?}: {pi:e} {pl:e}");
            if pl > 1e-10 {
                assert_eq!(inv.negative_det(), lu.negative_det(), "{j:?}");
            }
        }
        let j = [[1.0, 2.0], [3.0, 5.0]];
        for bad in [f64::NAN, f64::INFINITY] {
            for c in 0..2 {
                let mut floor = [None; 2];
                floor[c] = Some(bad);
                assert_eq!(Inverse2::in_cols_floored(&j, [[]; 2], floor).pivot_ratio(), 0.0, "{floor:?}");
            }
        }
    }

    /// Degenerate blocks report pivot ratio 0, as the LU does: a zero column, an infinite or NaN
    /// entry, a NaN in the column beyond the block, a singular block.
    #[test]
    fn degenerate_blocks_have_pivot_ratio_zero() {
        // Each case: the block, and its two Jacobian columns (with a third entry beyond it).
        type Case = ([[f64; 2]; 2], [[f64; 3]; 2]);
        let cases: [Case; 6] = [
            ([[0.0, 1.0], [0.0, 2.0]], [[0.0, 0.0, 0.0], [1.0, 2.0, 0.0]]),
            ([[1.0, 0.0], [2.0, 0.0]], [[1.0, 2.0, 0.0], [0.0, 0.0, 0.0]]),
            ([[f64::INFINITY, 1.0], [1.0, 2.0]], [[f64::INFINITY, 1.0, 0.0], [1.0, 2.0, 0.0]]),
            ([[1.0, f64::NAN], [1.0, 2.0]], [[1.0, 1.0, 0.0], [f64::NAN, 2.0, 0.0]]),
            ([[1.0, 1.0], [1.0, 2.0]], [[1.0, 1.0, f64::NAN], [1.0, 2.0, 0.0]]),
            ([[1.0, 2.0], [2.0, 4.0]], [[1.0, 2.0, 0.0], [2.0, 4.0, 0.0]]),
        ];
        for (j, cols) in cases {
            let beyond = [[cols[0][2]], [cols[1][2]]];
            assert_eq!(Inverse2::in_cols(&j, beyond).pivot_ratio(), 0.0, "{j:?} {cols:?}");
            assert_eq!(general(&j, cols).pivot_ratio(), 0.0, "{j:?} {cols:?}");
        }
    }

    /// Over a grid of zero, signed-zero, tiny, huge, subnormal, infinite and NaN entries, with a
    /// third entry of one column beyond the block: the general factorisation's pivot ratio (to a
    /// few roundings; 0 exactly where it is 0) and determinant sign. Where a column's magnitude
    /// is subnormal the general factorisation's reciprocal scale overflows and it reports 0; the
    /// inverse, which divides by the magnitude, equilibrates such a block as it does the same
    /// block in a unit 2^600 times smaller (bit for bit), which the general factorisation then
    /// agrees with. A subnormal pivot ratio (a block's own entries below 2^-1022 of a column
    /// entry beyond it) is reported as such, where the LU's reciprocal of that pivot overflows and
    /// it reports 0; a determinant whose reciprocal overflows with the columns equilibrated is
    /// reported as 0 by the inverse, where the LU finds a ratio below 1e-300: both singular to
    /// any tolerance.
    #[test]
    fn the_inverse_agrees_with_the_lu_on_special_values() {
        let values = [0.0, -0.0, 1.0, -2.5, 3.0e-7, 7.0e5, 1e-310, f64::INFINITY, f64::NAN];
        let scale = 2f64.powi(600);
        let (mut n, mut subnormal) = (0usize, 0usize);
        for (i, &a) in values.iter().enumerate() {
            for (k, &b) in values.iter().enumerate() {
                for &x in &values {
                    let (c, d) = (values[(i + 3 * k + 1) % 9], values[(2 * i + k + 5) % 9]);
                    // Column 0 holds the block's entries and one more row's; column 1 only its own.
                    let (mut j, mut cols) = ([[a, b], [c, d]], [[a, c, x], [b, d, 0.0]]);
                    let inv = Inverse2::in_cols(&j, [[cols[0][2]], [cols[1][2]]]);
                    // A block without entries beyond it is the same block with zeros beyond it.
                    let (alone, zeros) = (Inverse2::in_cols(&j, [[]; 2]), Inverse2::in_cols(&j, [[0.0]; 2]));
                    assert_eq!(alone.pivot_ratio().to_bits(), zeros.pivot_ratio().to_bits(), "{j:?}");
                    assert_eq!(alone.negative_det(), zeros.negative_det(), "{j:?}");
                    let tiny = cols.iter().any(|c| max_abs(*c) > 0.0 && max_abs(*c) < f64::MIN_POSITIVE);
                    if tiny {
                        // The same block in a smaller unit: exact products by a power of two.
                        j = j.map(|row| row.map(|v| v * scale));
                        cols = cols.map(|col| col.map(|v| v * scale));
                        let scaled = Inverse2::in_cols(&j, [[cols[0][2]], [cols[1][2]]]);
                        assert_eq!(inv.pivot_ratio().to_bits(), scaled.pivot_ratio().to_bits(), "{j:?}");
                        subnormal += 1;
                    }
                    let lu = general(&j, cols);
                    let (pi, pl) = (inv.pivot_ratio(), lu.pivot_ratio());
                    // A subnormal pivot's reciprocal overflows in the LU, which reports 0; a
                    // determinant whose reciprocal overflows even with the columns equilibrated
                    // makes the inverse report 0 (a pivot ratio below 1e-300 there).
                    let lu_overflows = pi < f64::MIN_POSITIVE && pl == 0.0;
                    let inverse_overflows = pi == 0.0 && pl < 1e-300;
                    assert!(
                        (pi - pl).abs() <= 1e-13 * pl || lu_overflows || inverse_overflows,
                        "{j:?} {cols:?}: {pi:e} {pl:e}"
                    );
                    if pl > 1e-10 {
                        assert_eq!(inv.negative_det(), lu.negative_det(), "{j:?} {cols:?}");
                    }
                    n += usize::from(pl > 0.0);
                }
            }
        }
        assert!(n > 100 && subnormal > 10, "{n} regular, {subnormal} subnormal cases");
    }

    #[test]
    fn solves_several_right_hand_sides() {
        let j = [[2.0, -1.0], [0.5, 3.0]];
        let inv = Inverse2::in_cols(&j, [[]; 2]);
        let z = inv.solve_cols([[1.0, 0.0], [0.0, 1.0]]);
        // J Z = I.
        for r in 0..2 {
            for m in 0..2 {
                let v = j[r][0] * z[0][m] + j[r][1] * z[1][m];
                assert!((v - if r == m { 1.0 } else { 0.0 }).abs() < 1e-15, "{z:?}");
            }
        }
        assert!(!inv.negative_det() && Inverse2::in_cols(&[[0.0, 1.0], [1.0, 0.0]], [[]; 2]).negative_det());
    }
}
