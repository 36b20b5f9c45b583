//! What a block's solve evaluates and judges in: the evaluation of a block ([`BlockEval`]), and
//! the magnitudes its tests are made in ([`Magnitudes`]: the rows' magnitudes and the unknowns'
//! units), made once for the solve or from each evaluation ([`MagnitudesOf`]).

use super::config::NewtonConfig;
use super::report::BlockFailure;
use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::lu::{RowScales, all_positive_finite};

/// One evaluation of a block: residuals, Jacobian rows, and intermediate values the generated
/// code keeps for later stages (so they are not recomputed after convergence).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct BlockEval<const N: usize, const K: usize, J = [[f64; N]; N]> {
    pub f: [f64; N],
    /// The Jacobian: dense rows, or a sparse block's non-zeros (see [`BlockJacobian`]).
    pub j: J,
    pub keep: [f64; K],
}

/// The magnitudes a block's tests judge it in. The generated code makes them once per solve
/// when they do not depend on the block's unknowns (every loop of links of given lengths), and
/// from each evaluation otherwise (a slider coordinate's magnitude is its own).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Magnitudes<const N: usize> {
    /// The row equilibration by the magnitude of each row: a structural bound of the
    /// equation's terms (for a loop projection, the sum of its link lengths), in the equation's
    /// unit, generated for every equation. Residual `i` is judged relative to it. Where one is
    /// not positive and finite (`degenerate`: a hand-written block that has none, or a
    /// degenerate mechanism whose terms all vanish) the row sums `sum_j |J_ij|` of each
    /// evaluation replace the invalid ones, which is right for angle unknowns only. A solve
    /// that ends where one is too small to judge its residual (below
    /// [`least_judged_magnitude`], or zero where the row's terms underflowed) or too large
    /// (infinite where the row's terms overflowed) fails instead ([`unjudged`]).
    pub(super) rows: RowScales<N>,
    /// The unit of each unknown: one radian for an angle, the magnitude of the rows it appears
    /// in per unit of its Jacobian entry otherwise (a slider coordinate: its loop's lengths). A
    /// step `dz_j` is judged relative to `max(|z_j|, unit_j)`, and the Newton factorisations'
    /// column `j` is multiplied by it where their pivots are measured; a value that is not
    /// positive and finite counts as `1` (replaced here).
    pub(super) unit: [f64; N],
    /// The unknowns whose equations repeat every turn (angles that enter the block through
    /// sines and cosines of whole multiples of themselves): an iteration that carried one more
    /// than half a turn from its guess returns it on the guess's turn, as a closed form does.
    pub(super) turns: [bool; N],
}

impl<const N: usize> Magnitudes<N> {
    /// The row magnitudes `scale` and the units `unit` of the unknowns, checked once.
    #[inline(always)]
    pub fn new(scale: [f64; N], unit: [f64; N]) -> Self {
        Magnitudes { rows: RowScales::new(scale), unit: units(&unit), turns: [false; N] }
    }

    /// These magnitudes, with `turns` marking the unknowns whose equations repeat every turn
    /// (see [`Magnitudes::turns`]).
    #[inline(always)]
    pub fn with_turns(mut self, turns: [bool; N]) -> Self {
        self.turns = turns;
        self
    }

    /// The units of the unknowns the tests use (see [`Magnitudes::unit`]: an invalid one
    /// replaced by `1`), for a caller that checks a solve's steps in the solver's own units.
    #[inline(always)]
    pub fn unit(&self) -> &[f64; N] {
        &self.unit
    }
}

/// Where a block's magnitudes come from: made once for the solve ([`Magnitudes`] itself), or
/// made from each evaluation (a closure).
#[doc(hidden)]
pub trait MagnitudesOf<const N: usize, const K: usize, J> {
    /// The magnitudes of every evaluation, when they are the same for all.
    fn fixed(&self) -> Option<&Magnitudes<N>>;
    /// The magnitudes at the evaluation `ev`.
    fn of(&self, ev: &BlockEval<N, K, J>) -> Magnitudes<N>;
}

impl<const N: usize, const K: usize, J> MagnitudesOf<N, K, J> for Magnitudes<N> {
    #[inline(always)]
    fn fixed(&self) -> Option<&Magnitudes<N>> {
        Some(self)
    }
    #[inline(always)]
    fn of(&self, _ev: &BlockEval<N, K, J>) -> Magnitudes<N> {
        *self
    }
}

impl<const N: usize, const K: usize, J, F: Fn(&BlockEval<N, K, J>) -> Magnitudes<N>> MagnitudesOf<N, K, J> for F {
    #[inline(always)]
    fn fixed(&self) -> Option<&Magnitudes<N>> {
        None
    }
    #[inline(always)]
    fn of(&self, ev: &BlockEval<N, K, J>) -> Magnitudes<N> {
        self(ev)
    }
}

/// The magnitudes `$mags` gives at the evaluation `$ev`: those made once, or made into
/// `$current` (the caller's slot, left uninitialised for fixed magnitudes: nothing is copied).
macro_rules! magnitudes_at {
    ($mags:expr, $ev:expr, $current:ident) => {
        match $mags.fixed() {
            Some(m) => m,
            None => {
                $current = $mags.of($ev);
                &$current
            }
        }
    };
}
pub(super) use magnitudes_at;

/// The row equilibration of the magnitudes `$m` at the evaluation `$ev`: `$m`'s own when its
/// scales are all valid (one branch for the set), otherwise made row by row into `$fallback`
/// (the caller's slot, left uninitialised on the common path).
macro_rules! rows_at {
    ($m:expr, $ev:expr, $fallback:ident) => {
        if $m.rows.degenerate {
            $fallback = fallback_rows(&$m.rows.s, $ev);
            &$fallback
        } else {
            &$m.rows
        }
    };
}
pub(super) use rows_at;

/// `rows_at!` where a generated magnitude is missing or degenerate: the row sum replaces it.
#[cold]
#[inline(never)]
pub(super) fn fallback_rows<const N: usize, const K: usize, J: BlockJacobian<N>>(
    scale: &[f64; N],
    ev: &BlockEval<N, K, J>,
) -> RowScales<N> {
    let mut s = [0.0; N];
    for r in 0..N {
        let given = scale[r];
        s[r] = if given > 0.0 && given < f64::INFINITY { given } else { ev.j.row_abs_sum(r) };
    }
    RowScales::new(s)
}

/// The spacing of doubles below `f64::MIN_POSITIVE` (`2^-1022`), whatever their size: the
/// subnormal numbers are the multiples of the smallest one, `2^-1074`.
const SUBNORMAL_SPACING: f64 = f64::from_bits(1);

/// The smallest row magnitude whose residual a solve with `cfg` can judge. A residual is a sum
/// of terms bounded by the magnitude `s`; each is rounded to `eps / 2` of itself or to half
/// the subnormal spacing `2^-1074`, whichever is larger, so below `2^-1022` the residual is
/// known only to about `2^-1074 / s` of the magnitude, however small the terms are. The test
/// `|f| <= residual_tol s` means something only where that is at most the tolerance (with a
/// floor of 16 eps: a tolerance of 0 iterates down to the rounding floor, which the iteration
/// takes as 16 eps of the magnitude): `s >= 2^-1074 / max(residual_tol, 16 eps)`, `4.9e-312`
/// by default, `1.4e-309` at the least. Every such bound is below `2^-1024`, under which the
/// reciprocal of a magnitude overflows and [`RowScales`] marks it degenerate: a magnitude
/// below it is always a degenerate one, and the test ([`unjudged`]) runs only for those.
///
/// That holds where the row sums of the Jacobian, which replace a degenerate magnitude, are
/// of normal size (the terms are squares of lengths of normal size, say). Where they are below
/// `2^-1024` too ([`NO_RECIPROCAL`]: the terms are lengths that are themselves subnormal), the
/// row can be equilibrated by neither, and its least magnitude is that bound: a four-bar of
/// lengths about `1e-310` was said not to assemble, a rhombic drive's velocity analogs not to
/// be finite, where the same mechanism in a smaller unit solves.
#[inline]
pub(crate) fn least_judged_magnitude(cfg: &NewtonConfig) -> f64 {
    SUBNORMAL_SPACING / cfg.residual_tol.max(16.0 * f64::EPSILON)
}

/// `2^-1024`: the largest double whose reciprocal overflows (a magnitude below it has none).
const NO_RECIPROCAL: f64 = f64::MIN_POSITIVE / 4.0;

/// The failure of a solve that ends at the evaluation `ev` of `z`, judged in the magnitudes
/// `m` of that evaluation (made from it by `mags`), when a row cannot be judged there
/// ([`BlockFailure::Underflow`]): its magnitude is below [`least_judged_magnitude`], or
/// underflowed to zero though its terms do not vanish; or ([`BlockFailure::Overflow`]) it
/// overflowed to infinity with terms too large for `f64` ([`overflowed`]), where the row sums
/// that replace it would judge a residual of squared lengths in lengths (the slider-crank by its
/// rod's length squared at `3.5e153` times its size was said not to assemble at 4 of 12 inputs,
/// and solved at 3, so judged). Tested where a solve returns, by a branch
/// on the magnitudes' degenerate mark, which valid magnitudes do not take; magnitudes made once
/// for the solve are tested once, at its start ([`unjudged_fixed`]), and not here: the test
/// compiles to nothing for them.
#[inline(always)]
pub(super) fn unjudged<const N: usize, const K: usize, J: BlockJacobian<N>>(
    mags: &impl MagnitudesOf<N, K, J>,
    m: &Magnitudes<N>,
    ev: &BlockEval<N, K, J>,
    z: &[f64; N],
    cfg: &NewtonConfig,
) -> Option<BlockFailure> {
    if mags.fixed().is_none() && m.rows.degenerate { unjudged_row(&m.rows.s, ev, z, cfg) } else { None }
}

/// [`unjudged`] of magnitudes made once for the solve, at its guess `z0` (evaluation `ev`):
/// they do not depend on the unknowns (the unknowns of such a block are angles, which enter its
/// terms through sines and cosines), so a magnitude too small or too large to judge a residual
/// at the guess is so at every iterate. Asked where the row equilibration found them degenerate.
#[inline(always)]
pub(super) fn unjudged_fixed<const N: usize, const K: usize, J: BlockJacobian<N>>(
    mags: &impl MagnitudesOf<N, K, J>,
    ev: &BlockEval<N, K, J>,
    z0: &[f64; N],
    cfg: &NewtonConfig,
) -> Option<BlockFailure> {
    match mags.fixed() {
        Some(m) if m.rows.degenerate => unjudged_or_vanished(&m.rows.s, ev, z0, cfg),
        _ => None,
    }
}

/// [`unjudged_row`] of magnitudes made once for the solve, then [`vanished`]: one out-of-line
/// call in the inlined [`unjudged_fixed`], as before the second test was added (inlined beside
/// it, the two calls changed the code generated for the solve's common path: three
/// instructions a step of the class IV group's point step under callgrind).
#[cold]
#[inline(never)]
fn unjudged_or_vanished<const N: usize, const K: usize, J: BlockJacobian<N>>(
    scale: &[f64; N],
    ev: &BlockEval<N, K, J>,
    z0: &[f64; N],
    cfg: &NewtonConfig,
) -> Option<BlockFailure> {
    unjudged_row(scale, ev, z0, cfg).or_else(|| vanished(scale, ev))
}

/// The first row of magnitudes made once for the solve, `scale` (degenerate: asked where
/// [`unjudged_row`] finds none too small or too large), whose terms all vanish at every
/// position ([`BlockFailure::Vanished`]): its magnitude is exactly zero and, at the evaluation
/// `ev`, so are its residual and its every derivative ([`row_vanishes`]). Such magnitudes do not
/// depend on the unknowns, and a magnitude bounds the terms (see [`Magnitudes::rows`]), so the
/// row is zero wherever the solve goes: a loop whose lengths are all zero, which no position
/// closes more than another. The solve returned its guess as the root (the residual is zero
/// there), and the block was reported as its singular position by the analogs (their Jacobian
/// has a zero row), the diagnosis of a dead centre, where the lengths are unset. Not asked of
/// magnitudes made from each evaluation: one that is zero at an iterate (a slider at its
/// pivot beside links of zero length) may not be at the next.
#[cold]
#[inline(never)]
fn vanished<const N: usize, const K: usize, J: BlockJacobian<N>>(
    scale: &[f64; N],
    ev: &BlockEval<N, K, J>,
) -> Option<BlockFailure> {
    let j = ev.j.to_dense();
    (0..N).find(|&r| row_vanishes(scale[r], ev.f[r], &j[r])).map(|row| BlockFailure::Vanished { row })
}

/// Whether a row of magnitude `scale`, residual `f` and Jacobian row `j` has terms that all
/// vanish: each exactly zero. A magnitude that underflowed to zero is told apart by
/// [`unjudged_row`] first (its terms in an unknown, a Jacobian entry times the unknown, are not
/// zero), and lengths that are tiny but not zero (`1e-200`) make a loop's magnitude, the sum of
/// their absolute values, no smaller than the longest of them: not zero. (A row whose terms are
/// products of lengths below about `1e-162` with derivatives that underflowed too is not told
/// from one whose lengths are zero; its message says so.)
pub(crate) fn row_vanishes(scale: f64, f: f64, j: &[f64]) -> bool {
    scale == 0.0 && f == 0.0 && j.iter().all(|&v| v == 0.0)
}

/// [`unjudged`] of degenerate magnitudes `scale` (as given, before the row sums replace them):
/// the first row too small for `f64` ([`BlockFailure::Underflow`]) or too large
/// ([`BlockFailure::Overflow`], see [`overflowed`]).
///
/// A positive magnitude below the least is judged by its own value. A magnitude of zero is
/// either a row whose terms all vanish (each term of the structural bound holds a length that is
/// zero, or the bound is a function's value, as `|ln x|` at `x = 1`) or one whose terms
/// underflowed (a product of lengths below about `1e-162`: `(1e-200)^2` is zero in `f64`). The
/// Jacobian tells them apart. Where every term holds a zero factor, so does its derivative by
/// an unknown, except by that factor itself, which is then a zero unknown: `J_rc z_c` is zero.
/// Otherwise `|J_rc z_c|` is the size of the terms in `z_c` (a term of degree `d` in `z_c` is
/// `z_c / d` times its derivative): where it is not zero but below the least magnitude the zero
/// is their underflow. (`|ln x|` at `x = 1` has `|J z| = 1`: judged by the row sums, as
/// before. A row whose unknowns with non-zero entries are all exactly zero, or whose Jacobian
/// underflowed too, is not told from one whose terms vanish.) The product rounds monotonically,
/// so its comparison with the least magnitude (a double) holds for the exact product.
#[cold]
#[inline(never)]
fn unjudged_row<const N: usize, const K: usize, J: BlockJacobian<N>>(
    scale: &[f64; N],
    ev: &BlockEval<N, K, J>,
    z: &[f64; N],
    cfg: &NewtonConfig,
) -> Option<BlockFailure> {
    let least = least_judged_magnitude(cfg);
    let nonzero = |v: f64| v != 0.0 && v.is_finite();
    let mut dense = None;
    (0..N).find_map(|r| {
        let given = scale[r];
        let underflow = Some(BlockFailure::Underflow { row: r, magnitude: given, least });
        if given == f64::INFINITY {
            let j = dense.get_or_insert_with(|| ev.j.to_dense());
            overflowed_in(&j[r], ev.f[r], z).then_some(BlockFailure::Overflow { row: r })
        } else if given > 0.0 && given < least {
            underflow
        } else if given > 0.0 && given < NO_RECIPROCAL {
            // Judged in its row sums, unless they have no reciprocal either (see `NO_RECIPROCAL`).
            let sum = ev.j.row_abs_sum(r);
            (sum > 0.0 && sum < NO_RECIPROCAL).then_some(BlockFailure::Underflow {
                row: r,
                magnitude: given,
                least: NO_RECIPROCAL,
            })
        } else if given == 0.0 {
            let j = dense.get_or_insert_with(|| ev.j.to_dense());
            let under = (0..N).any(|c| nonzero(j[r][c]) && nonzero(z[c]) && (j[r][c] * z[c]).abs() < least);
            if under { underflow } else { None }
        } else {
            None
        }
    })
}

/// Whether row `r` of the evaluation `ev` at `z`, whose magnitude (as given) is `scale`, holds
/// terms too large for `f64` ([`BlockFailure::Overflow`]): its magnitude overflowed to
/// infinity, and that is the size of its terms, not a division by zero.
///
/// The magnitude bounds every term (see [`Magnitudes::rows`]), so terms beyond `f64::MAX`
/// (`1.8e308`: squared lengths beyond about `1.3e154`) make it infinite; so do a division by
/// zero (`a / b` bounds its terms by `M(a) / |b|`) and a function's infinite value (`|ln 0|`).
/// The residual tells them apart where it is finite: a term that is infinite makes it so, so
/// its terms are finite and their bound overflowed, as sums and products of terms near
/// `f64::MAX` do. Where it is not finite the Jacobian does, as in [`unjudged_row`]: `|J_rc
/// z_c|` is the size of the terms in `z_c` (a term of degree `d` is `z_c / d` times its
/// derivative), and a product of a finite entry and a finite unknown that overflows is terms
/// beyond `f64::MAX / d`; a division by zero in the row's terms in `z_c` makes their derivative
/// infinite instead (`x / b` at `b = 0`), and one in terms free of them leaves `J_rc z_c` of
/// their ordinary size. (A row whose only terms beyond `f64::MAX` are free of the unknowns, or
/// whose Jacobian overflowed too, as a row of squared lengths in angles does, is not told from
/// one that left its domain: it stays that.)
#[cold]
#[inline(never)]
pub(super) fn overflowed<const N: usize, const K: usize, J: BlockJacobian<N>>(
    scale: f64,
    r: usize,
    ev: &BlockEval<N, K, J>,
    z: &[f64; N],
) -> bool {
    scale == f64::INFINITY && overflowed_in(&ev.j.to_dense()[r], ev.f[r], z)
}

/// [`overflowed`] of a row whose magnitude is infinite, by its residual `f` and Jacobian row `j`.
fn overflowed_in<const N: usize>(j: &[f64; N], f: f64, z: &[f64; N]) -> bool {
    f.is_finite() || (0..N).any(|c| j[c].is_finite() && z[c].is_finite() && (j[c] * z[c]).abs() == f64::INFINITY)
}

/// The units of the unknowns (see [`Magnitudes::unit`]): the generated ones when they are all
/// valid (one branch for the set), otherwise `1` for each invalid one.
#[inline(always)]
pub(super) fn units<const N: usize>(unit: &[f64; N]) -> [f64; N] {
    if all_positive_finite(unit) { *unit } else { fallback_units(unit) }
}

/// [`units`] with an invalid unit.
#[cold]
#[inline(never)]
fn fallback_units<const N: usize>(unit: &[f64; N]) -> [f64; N] {
    unit.map(|u| if u > 0.0 && u < f64::INFINITY { u } else { 1.0 })
}

#[cfg(test)]
mod tests {
    use super::super::newton;
    use super::super::test_blocks::{circle, in_place, solve, varying};
    use super::*;
    use crate::solvers::newton::NewtonConfig;

    /// A slider `x` at distance `c` from a pivot, by the square of that distance, `x^2 = c^2`,
    /// as the generated code judges it: the magnitude `x^2 + c^2`, the unit of `x` that over
    /// the derivative's magnitude `2 |x|`.
    fn squared(c: f64) -> impl Fn(&[f64; 1]) -> BlockEval<1, 2> {
        move |z: &[f64; 1]| {
            let x = z[0];
            let m = x * x + c * c;
            varying([x * x - c * c], [[2.0 * x]], [m], [m / (2.0 * x.abs())])
        }
    }

    /// Where the squares of the lengths are normal numbers the root is found to rounding; where
    /// they are subnormal (`c = 1e-160`: a magnitude of `2e-320`, its residual known to `2e-4`
    /// of it) or zero (`c = 1e-200`: `x^2` and `c^2` underflow, and the residual is exactly
    /// zero at any `x` near `c`), the solve is refused, from guesses on either side. It returned
    /// `x` `1e-5` off at `1e-160`, and the guess itself at `1e-200`.
    #[test]
    fn a_magnitude_too_small_to_judge_a_residual_is_refused() {
        let cfg = NewtonConfig::default();
        for g in [0.7, 1.3] {
            let c = 1e-150;
            let (s, _) = solve([g * c], &cfg, squared(c)).unwrap();
            assert!((s.z[0] - c).abs() <= 2.0 * f64::EPSILON * c, "{:e}", s.z[0]);
            for (c, zero) in [(1e-160, false), (1e-200, true)] {
                let fail = solve([g * c], &cfg, squared(c)).map(|(s, _)| s.z).unwrap_err();
                let BlockFailure::Underflow { row: 0, magnitude, least } = fail else { panic!("{c:e}: {fail:?}") };
                assert_eq!((magnitude == 0.0, least), (zero, least_judged_magnitude(&cfg)), "{c:e}: {fail:?}");
            }
        }
    }

    /// A row whose magnitude and derivatives are both below `2^-1024` (a length `a` times an
    /// angle's sine, `a` subnormal) is refused with that bound as its least magnitude: neither
    /// has a finite reciprocal to judge it in. Where its derivative is of normal size (the same
    /// magnitude, `x` a length), it is judged in the row sums and solved.
    #[test]
    fn a_row_whose_derivatives_are_subnormal_too_is_refused() {
        let cfg = NewtonConfig::default();
        for a in [1e-310, 2e-309] {
            let angle = move |z: &[f64; 1]| varying::<1, 2>([a * z[0].sin() - 0.5 * a], [[a * z[0].cos()]], [a], [1.0]);
            let fail = solve([0.4], &cfg, angle).map(|(s, _)| s.z).unwrap_err();
            assert_eq!(fail, BlockFailure::Underflow { row: 0, magnitude: a, least: NO_RECIPROCAL }, "{a:e}");
            let length = move |z: &[f64; 1]| varying::<1, 2>([z[0] - 0.5 * a], [[1.0]], [a], [a]);
            let (s, _) = solve([0.4 * a], &cfg, length).unwrap();
            assert_eq!(s.z, [0.5 * a]);
        }
    }

    /// Where the squares of the lengths overflow, the solve is refused as too large for `f64`,
    /// from guesses on either side: at `c = 1e160` and `1e300` the squares are infinite and the
    /// residual (`inf - inf`, or `inf - c^2` from below) is not finite, told from an expression
    /// outside its domain by the term in `x`, `2 x^2`, which overflows too; at `c = 1.2e154`
    /// from the guess below, the magnitude `x^2 + c^2` overflows while the residual does not
    /// (`x^2 - c^2` = `-7.4e307`). Refused at every size as outside its domain before, and at
    /// `1.2e154` the row sum `2 |x|` that replaced the magnitude judged a residual of squared
    /// lengths in lengths. At `1e150` the root is found to rounding.
    #[test]
    fn a_magnitude_too_large_to_judge_a_residual_is_refused() {
        let cfg = NewtonConfig::default();
        for g in [0.7, 1.3] {
            let c = 1e150;
            let (s, _) = solve([g * c], &cfg, squared(c)).unwrap();
            assert!((s.z[0] - c).abs() <= 2.0 * f64::EPSILON * c, "{:e}", s.z[0]);
            for c in [1.2e154, 1e160, 1e300] {
                let finite = squared(c)(&[g * c]).f[0].is_finite();
                assert_eq!(finite, c == 1.2e154 && g < 1.0, "{c:e}, guess {g}");
                let fail = solve([g * c], &cfg, squared(c)).map(|(s, _)| s.z).unwrap_err();
                assert_eq!(fail, BlockFailure::Overflow { row: 0 }, "{c:e}, guess {g}");
            }
        }
    }

    /// A residual made infinite by a division by zero is an expression outside its domain, not
    /// terms too large, though its magnitude (which bounds `a / b` by `|a| / |b|`) is infinite
    /// too: `x^2 = a / b` at `b = 0` (the terms in `x`, `2 x^2`, of ordinary size) and `x^2 / b
    /// = a` (their derivative `2 x / b` infinite). Nor is a magnitude that is NaN (`sqrt` of a
    /// negative bound) one too large.
    #[test]
    fn a_division_by_zero_is_not_taken_for_terms_too_large() {
        let cfg = NewtonConfig::default();
        let (a, b) = (2.0f64, 0.0f64);
        let over_rhs = |z: &[f64; 1]| {
            let x = z[0];
            varying::<1, 2>([x * x - a / b], [[2.0 * x]], [x * x + a.abs() / b.abs()], [1.0])
        };
        let over_lhs = |z: &[f64; 1]| {
            let x = z[0];
            varying::<1, 2>([x * x / b - a], [[2.0 * x / b]], [x * x / b.abs() + a.abs()], [1.0])
        };
        let nan = |z: &[f64; 1]| varying::<1, 2>([(z[0] - 3.0).sqrt()], [[1.0]], [f64::NAN], [1.0]);
        for g in [0.5, 1.5] {
            assert_eq!(over_rhs(&[g]).keep[0], f64::INFINITY);
            let domain = BlockFailure::NonFinite { row: 0, iterations: 0 };
            assert_eq!(solve([g], &cfg, over_rhs).map(|(s, _)| s.z).unwrap_err(), domain, "{g}");
            assert_eq!(solve([g], &cfg, over_lhs).map(|(s, _)| s.z).unwrap_err(), domain, "{g}");
            assert_eq!(solve([g], &cfg, nan).map(|(s, _)| s.z).unwrap_err(), domain, "{g}");
        }
    }

    /// The least magnitude judged is where the subnormal spacing is the residual tolerance (16
    /// eps for a tolerance of 0): `x = 1/2` (a linear row, solved exactly) in a magnitude given
    /// as that bound is solved, in one a double below it refused.
    #[test]
    fn the_least_magnitude_judged_is_the_tolerance_in_subnormal_spacings() {
        for tol in [1e-12, 0.0, 1e-3] {
            let cfg = NewtonConfig::default().with_residual_tol(tol);
            let least = least_judged_magnitude(&cfg);
            assert_eq!(least, f64::from_bits(1) / tol.max(16.0 * f64::EPSILON));
            assert!(least < NO_RECIPROCAL, "{least:e}: not always degenerate");
            // `x = c` (exact in subnormal arithmetic), `c` a quarter of the magnitude.
            let c = least / 4.0;
            let row = |s: f64| move |z: &[f64; 1]| varying::<1, 2>([z[0] - c], [[1.0]], [s], [s]);
            let below = f64::from_bits(least.to_bits() - 1);
            for g in [c, 3.0 * c] {
                let (solved, _) = solve([g], &cfg, row(least)).unwrap();
                assert_eq!(solved.z, [c]);
                let fail = solve([g], &cfg, row(below)).map(|(s, _)| s.z).unwrap_err();
                assert_eq!(fail, BlockFailure::Underflow { row: 0, magnitude: below, least }, "{tol:e}");
            }
        }
    }

    /// A row whose magnitude is zero at the root without underflowing is judged by its row
    /// sum, as before, and solved: `x = e` with `e = 0` (the magnitude `|x| + |e|`; its
    /// non-zero Jacobian entry is at an unknown that is zero), and `ln x = 0` (the magnitude
    /// `|ln x|`, a function's value; its derivative times `x` is 1).
    #[test]
    fn a_row_whose_magnitude_vanishes_at_the_root_is_solved() {
        let cfg = NewtonConfig::default();
        let vanishing = |z: &[f64; 1]| varying::<1, 2>([z[0]], [[1.0]], [z[0].abs()], [z[0].abs()]);
        let (s, ev) = solve([0.5], &cfg, vanishing).unwrap();
        assert_eq!((s.z, ev.keep[0]), ([0.0], 0.0));
        let log = |z: &[f64; 1]| varying::<1, 2>([z[0].ln()], [[1.0 / z[0]]], [z[0].ln().abs()], [1.0]);
        let (s, ev) = solve([1.0], &cfg, log).unwrap();
        assert_eq!((s.z, ev.keep[0]), ([1.0], 0.0));
    }

    /// A loop of two links from a pivot to a point, `a @ q0 + b @ q1 == (d, e)`, its
    /// magnitudes made once (`|a| + |b| + |d|` and `|a| + |b| + |e|`, as the generated code
    /// makes them), at size `k`: at `k = 0` every term and derivative of both rows vanishes,
    /// and the solve is refused as such from every guess (row 0, the first); the block's own
    /// solve returned the guess `[0.2, 1]` as its root (the residual is zero there), which the generated
    /// code's analogs then found singular. Lengths of `1e-200`, tiny but not zero,
    /// are judged in magnitudes of their own size and solve, to the angles of size 1 within
    /// `1e-12` rad (the residual tolerance: the loop of size 1 closes within it); subnormal ones
    /// (`1e-310`) are refused as too small to judge, as before.
    #[test]
    fn a_loop_whose_lengths_are_all_zero_vanishes() {
        let cfg = NewtonConfig::default();
        let two_links = |k: f64| {
            let [a, b, d, e] = [2.0, 1.5, 2.5, 1.0].map(|l| l * k);
            move |z: &[f64; 2]| {
                let ([s0, c0], [s1, c1]) = (z[0].sin_cos().into(), z[1].sin_cos().into());
                BlockEval::<2, 0> {
                    f: [a * c0 + b * c1 - d, a * s0 + b * s1 - e],
                    j: [[-a * s0, -b * s1], [a * c0, b * c1]],
                    keep: [],
                }
            }
        };
        let solve_at = |k: f64, guess: [f64; 2]| {
            let once = Magnitudes::new([2.0 + 1.5 + 2.5, 2.0 + 1.5 + 1.0].map(|m| m * k), [1.0; 2]);
            let eval = two_links(k);
            let mut ev = eval(&guess);
            newton(guess, &mut ev, &cfg, in_place(eval), &once).map(|s| s.z)
        };
        for guess in [[0.2, 1.0], [-2.0, 3.0], [0.0, 0.0]] {
            assert_eq!(solve_at(0.0, guess), Err(BlockFailure::Vanished { row: 0 }), "{guess:?}");
            let one = solve_at(1.0, guess).unwrap();
            let tiny = solve_at(1e-200, guess).unwrap_or_else(|e| panic!("{guess:?}: {e:?}"));
            for (t, o) in tiny.iter().zip(one) {
                assert!((t - o).abs() <= 1e-12, "{guess:?}: {tiny:?} against {one:?}");
            }
            let fail = solve_at(1e-310, guess).unwrap_err();
            assert!(matches!(fail, BlockFailure::Underflow { .. }), "{guess:?}: {fail:?}");
        }
    }

    /// Magnitudes made once for the solve (as the generated code makes those free of the
    /// unknowns) and the same magnitudes read from every evaluation give the same solve, bit
    /// for bit, and so does an invalid scale replaced by the row sums of each evaluation.
    #[test]
    fn magnitudes_made_once_are_those_of_every_evaluation() {
        // (An infinite scale is a magnitude too large, refused: see
        // `a_magnitude_too_large_to_judge_a_residual_is_refused`.)
        for scale in [[3.0, 0.25], [0.0, 2.0], [f64::NAN, -2.0]] {
            let eval = |z: &[f64; 2]| {
                let ev = circle(z);
                varying::<2, 4>(ev.f, ev.j, scale, [1.0, 0.0])
            };
            let cfg = NewtonConfig::default();
            for guess in [[1.0, 1.0], [1.5, 0.5], [1.03, 1.72]] {
                let (each, ev_each) = solve(guess, &cfg, eval).unwrap();
                let once = Magnitudes::new(scale, [1.0, 0.0]);
                let mut ev_once = eval(&guess);
                let s = newton(guess, &mut ev_once, &cfg, in_place(eval), &once).unwrap();
                assert_eq!(s.z.map(f64::to_bits), each.z.map(f64::to_bits), "{scale:?} {guess:?}");
                assert_eq!((s.iterations, s.evaluations), (each.iterations, each.evaluations));
                assert_eq!(
                    s.residual.to_bits(),
                    each.residual.to_bits(),
                    "{scale:?} {guess:?} {} {}",
                    s.residual,
                    each.residual
                );
                assert_eq!(ev_once.f, ev_each.f);
            }
        }
    }
}
