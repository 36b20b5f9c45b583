//! The generic steps of a closed-form block solve, shared by every generated closed form: the
//! root of `a cos q + b sin q = c`, an angle moved to its guess's turn, and the checks of the
//! guess and of the result.
//!
//! The generated code calls these with the operations the macro used to emit inline, in the same
//! order, so the results are bit-for-bit those of the inline code. A failure is returned as a
//! [`BlockFailure`]; the generated code adds the mechanism's location to it.
//!
//! The steps come in two forms: checked, and without their tests (`_deferred`), for a kernel
//! whose checks are deferred to its end ([`deferred`](super::deferred), which switches between
//! the two).

use super::newton::{BlockFailure, NewtonConfig};
use super::turns::whole_turns;
use core::f64::consts::PI;

/// The angle of sine `s` nearest to the guess `g` on its side of the vertical (`right`: the
/// guess's cosine is positive), given `r = reduce_turn(g)`, with `right = |r| < π/2`: `asin`
/// or its supplement, moved to the guess's turn by `g - r`, the whole turns the reduction took
/// off (no second reduction, as [`unwrap_to_turn`](super::turns::unwrap_to_turn) would make).
///
/// ```
/// use kinloop_runtime::generated::{asin_near, reduce_turn};
/// use std::f64::consts::{PI, TAU};
/// let g = 2.8 - 3.0 * TAU; // left of the vertical, three turns down
/// let r = reduce_turn(g);
/// assert!((asin_near(0.5, r.abs() < PI / 2.0, r, g) - (5.0 * PI / 6.0 - 3.0 * TAU)).abs() < 1e-13);
/// ```
#[inline]
pub fn asin_near(s: f64, right: bool, r: f64, g: f64) -> f64 {
    let base = s.clamp(-1.0, 1.0).asin();
    let side = if right {
        base
    } else if r > 0.0 {
        PI - base
    } else {
        -PI - base
    };
    (g - r) + side
}

/// The angle of cosine `c` on the side of sine `s` by `acos`, in `[-π, π]`.
#[inline]
pub fn acos_on_side(c: f64, s: f64) -> f64 {
    if s >= 0.0 { c.clamp(-1.0, 1.0).acos() } else { -c.clamp(-1.0, 1.0).acos() }
}

/// Bound on the absolute error of [`sin_cos_coarse`] (each of the sine and the cosine): the
/// Taylor remainders on `[-π/4, π/4]` are below `5e-13`; the reduction's rounding grows with
/// `|x|` to about `1e-11` at `|x| = 1e4` (the unit test measures 7.8e-12 there); the bound keeps
/// a margin of 10.
pub const SIN_COS_COARSE_ERR: f64 = 1e-10;

/// Sine and cosine of `x` within [`SIN_COS_COARSE_ERR`] without libm, for choosing a root by a
/// sign: a sign decided from these values is the exact one whenever the quantity exceeds its
/// error bound, and the generated code recomputes it with libm's `sin_cos` otherwise. Beyond
/// `|x| = 1e4` (and for NaN) this is libm's `sin_cos`.
///
/// ```
/// use kinloop_runtime::generated::{SIN_COS_COARSE_ERR, sin_cos_coarse};
/// let (s, c) = sin_cos_coarse(2.5);
/// assert!((s - 2.5f64.sin()).abs() < SIN_COS_COARSE_ERR && (c - 2.5f64.cos()).abs() < SIN_COS_COARSE_ERR);
/// ```
#[inline(always)]
pub fn sin_cos_coarse(x: f64) -> (f64, f64) {
    // NaN fails the comparison too.
    if x.abs() <= 1e4 { sin_cos_reduced(x) } else { libm_sin_cos(x) }
}

/// [`sin_cos_coarse`] for `|x| <= 1e4`.
#[inline(always)]
fn sin_cos_reduced(x: f64) -> (f64, f64) {
    // Quadrant `k` and the remainder `r` in about `[-π/4, π/4]` (its rounding is about an ulp
    // of `x` plus `k` times that of π/2: below 1e-11 for `|x| <= 1e4`).
    let k = whole_turns(x * core::f64::consts::FRAC_2_PI);
    let r = x - k * core::f64::consts::FRAC_PI_2;
    let r2 = r * r;
    // Taylor polynomials: the first omitted terms are `r^13 / 13!` and `r^14 / 14!`.
    let sr = r
        * (1.0
            + r2 * (-1.0 / 6.0
                + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362_880.0 + r2 * (-1.0 / 39_916_800.0))))));
    let cr = 1.0
        + r2 * (-0.5
            + r2 * (1.0 / 24.0
                + r2 * (-1.0 / 720.0
                    + r2 * (1.0 / 40_320.0 + r2 * (-1.0 / 3_628_800.0 + r2 * (1.0 / 479_001_600.0))))));
    // `x = r + k π/2`: rotate `(sin r, cos r)` by `k` quarter turns.
    match (k as i64) & 3 {
        0 => (sr, cr),
        1 => (cr, -sr),
        2 => (-sr, -cr),
        _ => (-cr, sr),
    }
}

/// `f` of the sine and cosine of the angle `g`, with a sign that is certain: `f` of their
/// [`sin_cos_coarse`] values when its magnitude exceeds `bound · SIN_COS_COARSE_ERR` (the caller's
/// bound on the error of `f` per unit error of the sine or cosine), otherwise `f` of libm's. The
/// sign is therefore the one libm's values give.
///
/// ```
/// use kinloop_runtime::generated::sign_at_guess;
/// // sin(g) - cos(g) > 0 for g = 1; a bound of 2 (two terms of unit factors).
/// assert!(sign_at_guess(1.0, 2.0, |(s, c)| s - c) > 0.0);
/// ```
#[inline(always)]
pub fn sign_at_guess(g: f64, bound: f64, f: impl Fn((f64, f64)) -> f64) -> f64 {
    let v = f(sin_cos_coarse(g));
    // A NaN bound or value takes libm's path.
    if v.abs() > bound * SIN_COS_COARSE_ERR { v } else { f(libm_sin_cos(g)) }
}

/// libm's `sin_cos`, out of line: the rare paths of [`sin_cos_coarse`] and [`sign_at_guess`].
#[cold]
#[inline(never)]
fn libm_sin_cos(x: f64) -> (f64, f64) {
    x.sin_cos()
}

/// The guess only picks the branch and the turn, through comparisons that a NaN would silently
/// answer: `guess_sum`, the sum of the block's guesses, must be finite. (A guess of an angle
/// needs no check of its own: the angle is moved to its turn, which makes it non-finite too,
/// and [`check_closed`] rejects it.)
#[inline]
pub fn check_guess(guess_sum: f64) -> Result<(), BlockFailure> {
    if guess_sum.is_finite() { Ok(()) } else { Err(BlockFailure::NonFinite { row: 0, iterations: 0 }) }
}

/// Why `a cos q + b sin q = c` has no single root, given `d2 = a² + b² - c²` and `r2 = a² + b²`:
/// a coefficient that is not finite; an equation that every angle satisfies (`a = b = c = 0`:
/// coincident circles of equal radii, the position is not determined, a singular position as
/// Newton reports it); or links that cannot reach, with the residual [`unreached`].
#[cold]
#[inline(never)]
fn no_root(d2: f64, r2: f64, c: f64, cfg: &NewtonConfig) -> BlockFailure {
    if d2.is_nan() {
        BlockFailure::NonFinite { row: 0, iterations: 0 }
    } else if r2 == 0.0 && c == 0.0 {
        undetermined(cfg)
    } else {
        BlockFailure::NoAssembly { row: 0, iterations: 0, evaluations: 0, residual: unreached(r2.sqrt(), c) }
    }
}

/// The residual of `a cos q + b sin q = c` (`r = sqrt(a² + b²) < |c|`) where it is least, `|c|
/// - r` at the angle of `(a, b)`, relative to the magnitude of its terms there, `|c| + r`: what
/// Newton's failure reports too (the residual over the magnitude of the equation's terms), free
/// of the units of the coefficients (lengths, or products of two for a dyad's), so that the
/// same mechanism at another size reports the same number. Between 0 and 1 (1 where the left
/// side vanishes: nothing can reach `c`).
fn unreached(r: f64, c: f64) -> f64 {
    (c.abs() - r) / (c.abs() + r)
}

/// A dyad's circle intersection's failure `fail`, judged in the dyad's lengths, `links` `[e0,
/// e1, l0², l1²]`, rather than in its equation's coefficients (products of two lengths, see
/// [`dyad_of`]): where every angle of its first link closes it within the residual tolerance
/// of its size ([`turns_freely`]), or every angle of its second within the rounding
/// ([`second_turns_freely`]), the angle is not determined, singular as [`undetermined`];
/// otherwise one that cannot be assembled, with the residual [`dyad_gap`].
#[cold]
#[inline(never)]
fn dyad_failure(fail: BlockFailure, links: [f64; 4], cfg: &NewtonConfig) -> BlockFailure {
    match fail {
        BlockFailure::NoAssembly { .. } if turns_freely(links, cfg) || second_turns_freely(links) => undetermined(cfg),
        BlockFailure::NoAssembly { row, iterations, evaluations, .. } => {
            BlockFailure::NoAssembly { row, iterations, evaluations, residual: dyad_gap(links) }
        }
        other => other,
    }
}

/// Whether a dyad of `links` `[e0, e1, l0², l1²]` closes within the residual tolerance of its
/// size `l0 + l1 + |e|` (as [`touching`] takes it, at least `16 eps`) at every angle of its
/// first link: the distance from the second link's centre to the first link's end ranges over
/// `[||e| - l0|, |e| + l0]`, so the worst miss is the larger of `||e| - l0| - l1` and `|e| + l0 -
/// l1` in magnitude. It is at least the shorter of `l0` and `|e|`, so this holds only where the
/// first link, or the centres' offset, is within the tolerance of nothing beside the others:
/// a coupler of `1e-300` on a four-bar of size 1, whose crank pin lies within rounding of the
/// rocker's reach. [`touching`]'s allowance, relative to the equation's own `|c|` (about `l0
/// |e|`), is then the tolerance of the short link, and such a dyad, closed to the rounding of
/// its size (`5e-17`), was reported as one that cannot be assembled, its gap `0`.
fn turns_freely([e0, e1, l0_sq, l1_sq]: [f64; 4], cfg: &NewtonConfig) -> bool {
    let (l0, l1, e) = (l0_sq.sqrt(), l1_sq.sqrt(), e0.hypot(e1));
    let tol = cfg.residual_tol.max(16.0 * f64::EPSILON);
    let worst = ((e - l0).abs() - l1).abs().max((e + l0 - l1).abs());
    // Written so that a NaN fails.
    worst <= tol * (l0 + l1 + e)
}

/// Whether a dyad of `links` `[e0, e1, l0², l1²]` closes within the rounding of its size
/// `l0 + l1 + |e|` (one `eps` of it) at every angle of its SECOND link: the distance from the
/// first link's centre to the second link's end ranges over `[||e| - l1|, |e| + l1]`, so the
/// worst miss is the larger of `||e| - l1| - l0` and `|e| + l1 - l0` in magnitude (the test of
/// [`turns_freely`] with the links swapped). That holds only where the second link is shorter
/// than the rounding of the others and the first link's end lies on its centre to that
/// rounding: a rocker of `1e-20` on a four-bar of size 1 whose coupler's end reaches the
/// rocker's pivot. Its angle is then the direction of the rounding error of the first link's
/// end (`-1.107` rad with a velocity analog of `-1.2e17`, or `pi / 2` where the triangle is
/// exact in doubles), not the data's. Judged against the rounding, not the residual
/// tolerance: a second link above the rounding has an angle the data give (the rocker of 1 on
/// a parallelogram of 2e12, known to `eps 2e12`, 1e-3 rad), though every angle of it closes
/// the loop within a tolerance of `1e-12`.
fn second_turns_freely([e0, e1, l0_sq, l1_sq]: [f64; 4]) -> bool {
    let (l0, l1, e) = (l0_sq.sqrt(), l1_sq.sqrt(), e0.hypot(e1));
    let worst = ((e - l1).abs() - l0).abs().max((e + l1 - l0).abs());
    // Written so that a NaN fails.
    worst <= f64::EPSILON * (l0 + l1 + e)
}

/// Whether a dyad of `links` `[e0, e1, l0², l1²]` has a link no longer than the rounding of its
/// size `l0 + l1 + |e|` (one `eps` of it): where such a dyad assembles (its triangle closes, or
/// its links in line close it within the tolerance), every angle of that link moves the loop by
/// at most twice its length, below the rounding of the others, and the data do not determine
/// its angle, whichever link it is (the declaration's order of the unknowns picks the first).
/// A rocker of 1 on a parallelogram of 2e12 is not such a link (`1` against `8.9e-4`). A link
/// whose square underflowed to zero is such a link beside others of normal squares; a size that
/// overflows or vanishes says nothing, and a NaN fails.
fn short_link([e0, e1, l0_sq, l1_sq]: [f64; 4]) -> bool {
    short_link_of(l0_sq.sqrt(), l1_sq.sqrt(), e0.hypot(e1))
}

/// [`short_link`] of the dyad's lengths: its links `l0`, `l1` and its centres' offset `e`.
fn short_link_of(l0: f64, l1: f64, e: f64) -> bool {
    let size = l0 + l1 + e;
    size > 0.0 && size < f64::INFINITY && l0.min(l1) <= f64::EPSILON * size
}

/// How far a dyad's two links (of lengths `l0`, `l1`) fall short of closing the triangle with
/// their centres' offset `e`, given `links` `[e0, e1, l0², l1²]`, relative to the dyad's size
/// `l0 + l1 + |e|`: the longest of the three less the other two, `2 max - (l0 + l1 + |e|)`,
/// over that size. The loop's own gap (at its least, the loop misses closing by it), in
/// proportion to its lengths as Newton's residual is: the same at every size, and close to
/// Newton's on the same mechanism, whose residual is the gap's component in its worst
/// equation over that equation's magnitude (the four-bar of crank 2, coupler 1.5, rocker 2 and
/// frame 3 at an input of 3: the links 1.488 short of the centres 4.988 apart, 0.1753 here,
/// 0.1749 by Newton). Zero where rounding makes the sides a triangle; NaN where a length is not
/// finite.
fn dyad_gap([e0, e1, l0_sq, l1_sq]: [f64; 4]) -> f64 {
    let (l0, l1, e) = (l0_sq.sqrt(), l1_sq.sqrt(), e0.hypot(e1));
    let size = l0 + l1 + e;
    let gap = (2.0 * l0.max(l1).max(e) - size) / size;
    // Written so that a NaN stays.
    if gap < 0.0 { 0.0 } else { gap }
}

/// [`touching`] for a dyad's circle intersection whose circles miss (`d2 < 0`), judged in the
/// dyad's lengths, `links` `[e0, e1, l0², l1²]`, as Newton judges its loop: where every angle of
/// its first link closes it within the tolerance ([`turns_freely`]), or every angle of its
/// second within the rounding ([`second_turns_freely`]), singular as [`undetermined`]; where
/// its links laid in line close it within the residual tolerance of its size (its
/// [`dyad_gap`] within it, at least `16 eps`), the limit position, offset `0`;
/// otherwise one that cannot be assembled, with that gap as residual. [`touching`]'s own test is
/// relative to the equation's `|c|`, about `l0 |e|`, a product of two of the three lengths, so
/// the miss it allowed scaled with the product of the two it does not hold over the third
/// (about `tol l0 |e| / l1` where `|e|` is longest, `tol l0 l1 / |e|` where `l1` is): the
/// tolerance of the short link where it is the first, a miss of `1e-6` of the loop where the
/// second link is `1e-6` of the others (returned as a position with the loop open by it). A
/// dyad whose lengths cannot be read here (a square out of the normal range, a length not
/// finite) takes [`touching`]'s verdict in its coefficients, a failure's residual the gap as
/// [`dyad_failure`] gives it.
#[cold]
#[inline(never)]
fn dyad_touching(d2: f64, r2: f64, c: f64, links: [f64; 4], cfg: &NewtonConfig) -> Result<f64, BlockFailure> {
    // Written so that a NaN takes the coefficients' verdict.
    if !(d2 < 0.0 && r2 >= f64::MIN_POSITIVE && readable(links)) {
        let limit = touching(d2, r2, c, cfg).map_err(|f| dyad_failure(f, links, cfg))?;
        return in_line_determined(limit, links, cfg);
    }
    if turns_freely(links, cfg) || second_turns_freely(links) {
        return Err(undetermined(cfg));
    }
    let gap = dyad_gap(links);
    if gap <= cfg.residual_tol.max(16.0 * f64::EPSILON) {
        in_line_determined(0.0, links, cfg)
    } else {
        Err(BlockFailure::NoAssembly { row: 0, iterations: 0, evaluations: 0, residual: gap })
    }
}

/// The limit position `offset` of a dyad of `links` `[e0, e1, l0², l1²]` (its links in line),
/// unless a link is below the rounding of its size ([`short_link`]): then that link's angle is
/// not determined, singular as [`undetermined`]. A coupler of `1e-20` declared as the dyad's
/// second link, `8.7e-13` of its loop's size short of the rocker's pivot, was given an angle
/// from the rounding (`-1.047` rad, with a velocity analog of `8e18`), where declared as the
/// first it turns freely ([`turns_freely`]); with its square underflowed to zero, the division
/// by its length made its angle NaN, reported as an equation outside its domain.
fn in_line_determined(offset: f64, links: [f64; 4], cfg: &NewtonConfig) -> Result<f64, BlockFailure> {
    if short_link(links) { Err(undetermined(cfg)) } else { Ok(offset) }
}

/// Whether a dyad's `links` `[e0, e1, l0², l1²]` give its lengths to full precision: the
/// offset's components finite, the links' squares normal numbers (not zero, subnormal or
/// overflowed).
fn readable([e0, e1, l0_sq, l1_sq]: [f64; 4]) -> bool {
    let normal = |v: f64| (f64::MIN_POSITIVE..=f64::MAX).contains(&v);
    e0.is_finite() && e1.is_finite() && normal(l0_sq) && normal(l1_sq)
}

/// The failure of a block whose equations hold for every value of an angle: singular, with a
/// zero pivot ratio (its Jacobian's columns are parallel there).
#[cold]
#[inline(never)]
fn undetermined(cfg: &NewtonConfig) -> BlockFailure {
    BlockFailure::Singular { row: 0, iterations: 0, residual: 0.0, pivot_ratio: 0.0, tolerance: cfg.singular_tol }
}

/// `±sqrt(d2)` for the root of `a cos q + b sin q = c` with `d2 = r2 - c²`, `r2 = a² + b²`: the
/// square root, negated when `flip` holds; `0` (the limit position, where both roots meet) when
/// `d2` is negative by no more than the residual tolerance allows (a limit position rounded
/// past); else the failure when there is no single real root.
#[inline]
pub fn root_offset(d2: f64, r2: f64, c: f64, flip: bool, cfg: &NewtonConfig) -> Result<f64, BlockFailure> {
    // A subnormal `r2` (links shorter than about 1e-154 of the unit) would give `d2` with few
    // significant bits: a failure, as a zero `r2` is (see `mechanism::extreme_scale`).
    if !(d2 >= 0.0 && r2 >= f64::MIN_POSITIVE) {
        return touching(d2, r2, c, cfg);
    }
    Ok(root_offset_deferred(d2, flip))
}

/// [`root_offset`] for an equation `a cos q + b sin q = c` whose `r2 = a² + b²` and `d2 = r2 -
/// c²` the caller computed with a coefficient folded to a constant (the emitted `a cos q = c`,
/// `b sin q = c` and dyads with a constant coefficient, and the run-time model's mirror of
/// them). Where `r2` leaves the normal range (the coefficients are products of two lengths, so
/// beyond sizes of about `1e±77`), the offset of the equation divided by the power of two
/// nearest its largest coefficient (exact: the same roots), back in the coefficients' units,
/// as [`dyad_roots`] rescales; the one extra test on the way is `r2`'s upper bound.
///
/// ```
/// use kinloop_runtime::generated::folded_root_offset;
/// use kinloop_runtime::NewtonConfig;
/// let cfg = NewtonConfig::default();
/// // 3e200 cos q = 1.5e200 (a product of lengths of 1e100): the offset sqrt(a² - c²).
/// let (a, c) = (3e200, 1.5e200);
/// let d = folded_root_offset(a * a - c * c, a * a, a, 0.0, c, false, &cfg).unwrap();
/// assert!((d / a - 0.75f64.sqrt()).abs() < 1e-15);
/// ```
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn folded_root_offset(
    d2: f64,
    r2: f64,
    a: f64,
    b: f64,
    c: f64,
    flip: bool,
    cfg: &NewtonConfig,
) -> Result<f64, BlockFailure> {
    if !(d2 >= 0.0 && (f64::MIN_POSITIVE..=f64::MAX).contains(&r2)) {
        return folded_off_range(d2, r2, a, b, c, flip, cfg);
    }
    Ok(root_offset_deferred(d2, flip))
}

/// [`folded_root_offset`] of a dyad's circle intersection with a coefficient folded, given its
/// `links` `[e0, e1, l0², l1²]` as [`dyad_of`] is (`d2` from [`dyad_d2`]): the same offset, and
/// a failure's residual the dyad's gap (`dyad_failure`), as [`dyad_of`]'s.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn folded_dyad_root_offset(
    d2: f64,
    r2: f64,
    a: f64,
    b: f64,
    c: f64,
    links: [f64; 4],
    flip: bool,
    cfg: &NewtonConfig,
) -> Result<f64, BlockFailure> {
    if !(d2 >= 0.0 && (f64::MIN_POSITIVE..=f64::MAX).contains(&r2)) {
        return folded_dyad_off_range(d2, r2, a, b, c, links, flip, cfg);
    }
    Ok(root_offset_deferred(d2, flip))
}

/// [`folded_dyad_root_offset`] where its test fails: as [`folded_off_range`], the verdict on
/// circles that miss the dyad's ([`dyad_touching`]), a failure's residual the dyad's gap.
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn folded_dyad_off_range(
    d2: f64,
    r2: f64,
    a: f64,
    b: f64,
    c: f64,
    links: [f64; 4],
    flip: bool,
    cfg: &NewtonConfig,
) -> Result<f64, BlockFailure> {
    if (f64::MIN_POSITIVE..=f64::MAX).contains(&r2) {
        return dyad_touching(d2, r2, c, links, cfg);
    }
    let (k, _, _, d) = rescaled(a, b, c, Some(links), flip, cfg).map_err(|f| dyad_failure(f, links, cfg))?;
    Ok(d / k)
}

/// [`folded_root_offset`] where its test fails: [`touching`] for a normal `r2`; otherwise the
/// offset of the equation [`rescaled`], back in the coefficients' units.
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn folded_off_range(
    d2: f64,
    r2: f64,
    a: f64,
    b: f64,
    c: f64,
    flip: bool,
    cfg: &NewtonConfig,
) -> Result<f64, BlockFailure> {
    if (f64::MIN_POSITIVE..=f64::MAX).contains(&r2) {
        return touching(d2, r2, c, cfg);
    }
    let (k, _, _, d) = rescaled(a, b, c, None, flip, cfg)?;
    Ok(d / k)
}

/// A negative `d2 = r2 - c²` that is the rounding of a limit position: the links fall short of
/// `|c|` by `|c| - r ≈ -d2 / (2 |c|)`, which within `tol |c|` (`tol` the residual tolerance,
/// at least `16 eps`) is a residual Newton accepts, so the offset is `0`, the position where
/// both roots meet (its analogs then report the singular position, as Newton's do). Otherwise
/// the failure of [`no_root`]. Without it whether a mechanism designed to touch its limit
/// assembles there would depend on the rounding of its dimensions, that is on its units
/// (`0.1 + 0.2 > 0.3` in metres, `100 + 200 = 300` in millimetres). That allowance, relative
/// to `|c|`, is not enough where `c` is a difference of longer terms: a closed form of one angle
/// judges a failure again in the magnitude of those terms ([`offset_in_terms`]), a dyad in its
/// lengths ([`dyad_touching`]).
///
/// Where `c²` overflows (a finite `c` beyond about `1.3e154`, with `r2` still finite: a dyad's
/// coefficients are products of two lengths, so a mechanism near `1e77` in size), both sides of
/// `-d2 <= 2 tol c²` are infinite and the test held for any `c`: links falling short by most of
/// their size were taken for a limit position and given a cosine far beyond 1. There the same
/// test is made relative to `c²` (see [`short_within`]), which does not overflow. An infinite
/// `c` is no limit position but an overflow ([`non_finite_coefficient`]): taken for one, it gave
/// the cosine `c a / r2`, infinite, with no error.
#[cold]
#[inline(never)]
fn touching(d2: f64, r2: f64, c: f64, cfg: &NewtonConfig) -> Result<f64, BlockFailure> {
    if c.is_infinite() {
        return Err(non_finite_coefficient(0.0, 0.0, c));
    }
    let tol = cfg.residual_tol.max(16.0 * f64::EPSILON);
    let c2 = c * c;
    let within = if c2 == f64::INFINITY { short_within(r2, c, tol) } else { -d2 <= 2.0 * tol * c2 };
    // Written so that a NaN fails.
    if r2 >= f64::MIN_POSITIVE && within { Ok(0.0) } else { Err(no_root(d2, r2, c, cfg)) }
}

/// [`touching`]'s test `c² - r2 <= 2 tol c²` divided by `c²`: `(1 - x) (1 + x) <= 2 tol` with
/// `x = r / |c|` (`r = sqrt(r2)`), every factor of order one, for a `c` whose square overflows.
fn short_within(r2: f64, c: f64, tol: f64) -> bool {
    let x = r2.sqrt() / c.abs();
    (1.0 - x) * (1.0 + x) <= 2.0 * tol
}

/// [`folded_root_offset`]'s failure `fail` of `a cos q + b sin q = c`, judged again in `size`,
/// the magnitude of the terms its coefficients are made of (the sum of the loop's lengths in
/// the equation, as Newton's residual is measured): the offset `0` of the limit position, or the
/// failure. Called where [`folded_root_offset_in`] or [`dyad_roots_in`] fails, which compute
/// `size` only there.
///
/// The coefficients' own test (`touching`) allows a miss relative to `|c|` alone. Where `c` is a
/// difference of terms much larger than itself (a short rod beside a long crank and offset:
/// `l sin q = e + r sin phi` with `e` near `-r`), its rounding, a few `eps` of those terms, is
/// many `eps` of `|c|`, and depends on the unit: a slider-crank closing exactly at its limit in
/// decimal (crank 0.406, offset -0.4057, rod 0.0003 at `phi = pi/2`) was "cannot be assembled"
/// in metres and millimetres and a position in micrometres. Here the miss `|c| - sqrt(a² + b²)`
/// is judged against the residual tolerance (at least `16 eps`) of `size`, the same number in every
/// unit (`miss_in_terms`): within it, the limit position; where every angle closes the
/// equation within it (`|c| + sqrt(a² + b²)` within it: the angle's lever as short as the
/// tolerance, the position not determined), singular (the pivot ratio 0); otherwise no
/// assembly with the miss over `size` as residual. A failure other than no assembly, or a
/// `size` that is not a positive finite number, stays as it is.
///
/// ```
/// use kinloop_runtime::generated::{folded_root_offset, offset_in_terms};
/// use kinloop_runtime::NewtonConfig;
/// let cfg = NewtonConfig::default().with_residual_tol(0.0);
/// // `-l sin q = -(e + r)`: crank 0.406, offset -0.4057, rod 0.0003, closing exactly in decimal.
/// let (b, c) = (-0.0003, -(-0.4057 + 0.406));
/// let fail = folded_root_offset(b * b - c * c, b * b, 0.0, b, c, false, &cfg).unwrap_err();
/// assert_eq!(offset_in_terms(fail, 0.0, b, c, 0.406 + 0.4057 + 0.0003, &cfg), Ok(0.0));
/// ```
#[cold]
#[inline(never)]
pub fn offset_in_terms(
    fail: BlockFailure,
    a: f64,
    b: f64,
    c: f64,
    size: f64,
    cfg: &NewtonConfig,
) -> Result<f64, BlockFailure> {
    let BlockFailure::NoAssembly { row, iterations, evaluations, .. } = fail else { return Err(fail) };
    let Some((miss, reach)) = miss_in_terms(a, b, c, size) else { return Err(fail) };
    let tol = cfg.residual_tol.max(16.0 * f64::EPSILON);
    if miss + 2.0 * reach <= tol {
        Err(undetermined(cfg))
    } else if miss <= tol {
        Ok(0.0)
    } else {
        Err(BlockFailure::NoAssembly { row, iterations, evaluations, residual: miss })
    }
}

/// [`folded_root_offset`] of a closed form of one angle (an angle equation, an angle and a
/// slider), its failure judged again in the magnitude of its equation's terms `terms()`
/// ([`offset_in_terms`]): `terms` is called only there, so the step does no more than
/// [`folded_root_offset`]'s where the root exists.
///
/// ```
/// use kinloop_runtime::generated::folded_root_offset_in;
/// use kinloop_runtime::NewtonConfig;
/// let cfg = NewtonConfig::default().with_residual_tol(0.0);
/// // `-l sin q = -(e + r)`: crank 0.406, offset -0.4057, rod 0.0003, closing exactly in decimal.
/// let (b, c) = (-0.0003, -(-0.4057 + 0.406));
/// let terms = || 0.406 + 0.4057 + 0.0003;
/// assert_eq!(folded_root_offset_in(b * b - c * c, b * b, 0.0, b, c, false, &cfg, terms), Ok(0.0));
/// ```
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn folded_root_offset_in(
    d2: f64,
    r2: f64,
    a: f64,
    b: f64,
    c: f64,
    flip: bool,
    cfg: &NewtonConfig,
    terms: impl FnOnce() -> f64,
) -> Result<f64, BlockFailure> {
    if !(d2 >= 0.0 && (f64::MIN_POSITIVE..=f64::MAX).contains(&r2)) {
        return folded_off_range_in(d2, r2, a, b, c, flip, cfg, terms);
    }
    Ok(root_offset_deferred(d2, flip))
}

/// [`folded_root_offset_in`] where its test fails: [`folded_off_range`], a failure judged again
/// in `terms()`.
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn folded_off_range_in<F: FnOnce() -> f64>(
    d2: f64,
    r2: f64,
    a: f64,
    b: f64,
    c: f64,
    flip: bool,
    cfg: &NewtonConfig,
    terms: F,
) -> Result<f64, BlockFailure> {
    folded_off_range(d2, r2, a, b, c, flip, cfg).or_else(|f| offset_in_terms(f, a, b, c, terms(), cfg))
}

/// [`dyad_roots`] of a closed form of one angle with no coefficient folded, its failure judged
/// again in the magnitude of its equation's terms `terms()` ([`offset_in_terms`]): the same
/// roots, `terms` called only where [`dyad_roots`] fails.
#[inline]
pub fn dyad_roots_in(
    a: f64,
    b: f64,
    c: f64,
    flip: bool,
    cfg: &NewtonConfig,
    terms: impl FnOnce() -> f64,
) -> Result<(f64, f64), BlockFailure> {
    let r2 = a * a + b * b;
    let d2 = r2 - c * c;
    // `dyad_roots`'s tests, `r2` normal and `d2` not negative (written so that a NaN fails).
    if !((f64::MIN_POSITIVE..=f64::MAX).contains(&r2) && d2 >= 0.0) {
        return dyad_roots_off_range_in(a, b, c, flip, cfg, terms);
    }
    Ok(roots_of_offset(a, b, c, r2, root_offset_deferred(d2, flip)))
}

/// [`dyad_roots_in`] where its tests fail: [`dyad_roots`], a failure judged again in `terms()`.
#[cold]
#[inline(never)]
fn dyad_roots_off_range_in<F: FnOnce() -> f64>(
    a: f64,
    b: f64,
    c: f64,
    flip: bool,
    cfg: &NewtonConfig,
    terms: F,
) -> Result<(f64, f64), BlockFailure> {
    dyad_roots(a, b, c, flip, cfg).or_else(|f| roots_in_terms(f, a, b, c, terms(), cfg))
}

/// [`offset_in_terms`] of [`dyad_roots`]'s failure: `(cos q, sin q)` of the limit position,
/// where the offset is `0` (`c (a, b) / (a² + b²)`, from the equation divided by the power of
/// two nearest its largest coefficient where `a² + b²` leaves the normal range, as
/// [`dyad_roots`] rescales), or the failure.
fn roots_in_terms(
    fail: BlockFailure,
    a: f64,
    b: f64,
    c: f64,
    size: f64,
    cfg: &NewtonConfig,
) -> Result<(f64, f64), BlockFailure> {
    let d = offset_in_terms(fail, a, b, c, size, cfg)?;
    // Reached only with finite coefficients (`miss_in_terms`), not all zero (`|c|` exceeds the
    // reach): the division is exact and `r2` of order one.
    let k = reciprocal_power_of_two(a.abs().max(b.abs()).max(c.abs()));
    let (a, b, c) = (a * k, b * k, c * k);
    Ok(roots_of_offset(a, b, c, a * a + b * b, d))
}

/// How far `a cos q + b sin q = c` is from a root where its left side comes nearest `c`, and
/// how far its left side reaches, both over `size` (the magnitude of the terms the coefficients
/// are made of): `((|c| - r) / size, r / size)` with `r = sqrt(a² + b²)` (by `hypot`: free of
/// the overflow of the squares at any size), where `|c| > r`. `None` where that does not hold
/// or a value is not finite, or `size` is not positive.
fn miss_in_terms(a: f64, b: f64, c: f64, size: f64) -> Option<(f64, f64)> {
    let r = a.hypot(b);
    let finite = a.is_finite() && b.is_finite() && c.is_finite() && size.is_finite();
    // Written so that a NaN fails.
    (finite && size > 0.0 && c.abs() > r).then(|| ((c.abs() - r) / size, r / size))
}

/// `(cos q, sin q)` of the root of `a cos q + b sin q = c` with `h' = -d < 0` (`h = a cos q +
/// b sin q - c`, `d = sqrt(a² + b² - c²)`), or with `h' = d > 0` when `flip` holds:
/// `((a c - b d) / r², (b c + a d) / r²)`.
///
/// ```
/// use kinloop_runtime::generated::dyad_roots;
/// use kinloop_runtime::NewtonConfig;
/// let cfg = NewtonConfig::default();
/// // cos q + sin q = 1: q = π/2 (h' = cos q - sin q = -1 < 0) or q = 0 (h' = 1 > 0).
/// assert_eq!(dyad_roots(1.0, 1.0, 1.0, false, &cfg).unwrap(), (0.0, 1.0));
/// assert_eq!(dyad_roots(1.0, 1.0, 1.0, true, &cfg).unwrap(), (1.0, 0.0));
/// assert!(dyad_roots(1.0, 1.0, 2.0, false, &cfg).is_err());
/// ```
#[inline]
pub fn dyad_roots(a: f64, b: f64, c: f64, flip: bool, cfg: &NewtonConfig) -> Result<(f64, f64), BlockFailure> {
    let r2 = a * a + b * b;
    // Written so that a NaN takes the rescaled path too (which then fails as below).
    if !(f64::MIN_POSITIVE..=f64::MAX).contains(&r2) {
        return dyad_roots_rescaled(a, b, c, flip, cfg);
    }
    let d = root_offset(r2 - c * c, r2, c, flip, cfg)?;
    Ok(roots_of_offset(a, b, c, r2, d))
}

/// [`dyad_roots`] for a dyad's circle intersection `|e + m0 c0| = |m1 c1|`: the root of `a cos q
/// + b sin q = c` given `dyad = [a, b, e0, e1, l0², l1²]`, the coefficients (`(a, b) = m0ᵀ e`,
/// `c = (l1² - l0² - |e|²) / 2`), the centres' offset `e` and the links' squared lengths: the
/// same roots, with `d2` from the triangle of the lengths where `a² + b² - c²` cancels (see
/// [`dyad_d2`]).
///
/// ```
/// use kinloop_runtime::generated::{dyad_of, dyad_roots};
/// use kinloop_runtime::NewtonConfig;
/// let cfg = NewtonConfig::default();
/// // The coupler of a parallelogram four-bar, crank and rocker 1 on a coupler and frame of 2e9,
/// // at a crank angle of 0.3: `e` from the frame's pivot to the crank's end, `m0` the coupler
/// // (2e9), `m1` the rocker. On the parallelogram branch the coupler lies along the frame.
/// let (k, phi) = (2e9f64, 0.3f64);
/// let e = [phi.cos() - k, phi.sin()];
/// let (a, b) = (k * e[0], k * e[1]);
/// let c = 0.5 * ((1.0 - k * k) - (e[0] * e[0] + e[1] * e[1]));
/// let (_, sq) = dyad_of([a, b, e[0], e[1], k * k, 1.0], c, true, &cfg).unwrap();
/// assert!(sq.abs() < 1e-15);
/// // From the coefficients alone, the coupler's 2e9 turn by 1.7e-8 rad: 34 crank lengths.
/// let (_, sq) = dyad_roots(a, b, c, true, &cfg).unwrap();
/// assert!(sq.abs() > 1e-8);
/// ```
#[inline(always)]
pub fn dyad_of(dyad: [f64; 6], c: f64, flip: bool, cfg: &NewtonConfig) -> Result<(f64, f64), BlockFailure> {
    let [a, b, e0, e1, l0, l1] = dyad;
    let r2 = a * a + b * b;
    // Written so that a NaN takes the rescaled path too (which then fails as below).
    if !(f64::MIN_POSITIVE..=f64::MAX).contains(&r2) {
        return dyad_of_rescaled(a, b, c, [e0, e1, l0, l1], flip, cfg);
    }
    let d2 = r2 - c * c;
    // `root_offset`'s test with `d2` against its cancellation instead of zero, and the first
    // link against the rounding of the second (`first_link_long`).
    let d = if d2 >= r2 * DYAD_CANCELLED && r2 >= f64::MIN_POSITIVE && first_link_long(l0, l1) {
        root_offset_deferred(d2, flip)
    } else {
        dyad_offset_cancelled(d2, r2, c, [e0, e1, l0, l1], flip, cfg)?
    };
    Ok(roots_of_offset(a, b, c, r2, d))
}

/// [`dyad_of`]'s root offset where `d2` is negative or cancelled, or the first link is not
/// [`first_link_long`]: recomputed from the triangle ([`dyad_d2`]), then [`root_offset`]'s,
/// circles that miss judged in the dyad's lengths ([`dyad_touching`]); a triangle that closes
/// with a second link below the rounding of the others ([`second_turns_freely`]) singular as
/// [`undetermined`], and one with a first link below it ([`short_link`]) too, by way of
/// [`dyad_d2`], which takes it for no triangle.
#[cold]
#[inline(never)]
fn dyad_offset_cancelled(
    d2: f64,
    r2: f64,
    c: f64,
    links: [f64; 4],
    flip: bool,
    cfg: &NewtonConfig,
) -> Result<f64, BlockFailure> {
    let d2 = dyad_d2(d2, r2, links);
    // `root_offset`'s test, its failure the dyad's.
    if d2 >= 0.0 && r2 >= f64::MIN_POSITIVE {
        // A triangle that closes, but with a link below the rounding of the others (a rocker
        // of 1e-20 whose pivot the coupler's end reaches): its angle would be the rounding's.
        // Tested here alone: such a triangle's `d2` cancels where the short link is the second,
        // and a first one fails `first_link_long`.
        if second_turns_freely(links) || short_link(links) {
            return Err(undetermined(cfg));
        }
        Ok(root_offset_deferred(d2, flip))
    } else {
        dyad_touching(d2, r2, c, links, cfg)
    }
}

/// [`dyad_of`] where `a² + b²` is not a normal number: [`dyad_roots_rescaled`], circles that
/// miss judged in the dyad's lengths ([`dyad_touching`]), a failure's residual the dyad's gap
/// ([`dyad_failure`]).
#[cold]
#[inline(never)]
fn dyad_of_rescaled(
    a: f64,
    b: f64,
    c: f64,
    links: [f64; 4],
    flip: bool,
    cfg: &NewtonConfig,
) -> Result<(f64, f64), BlockFailure> {
    let (_, [a, b, c], r2, d) = rescaled(a, b, c, Some(links), flip, cfg).map_err(|f| dyad_failure(f, links, cfg))?;
    Ok(roots_of_offset(a, b, c, r2, d))
}

/// `d2 = r2 - c²` of a dyad's circle intersection, recomputed from the triangle of its lengths
/// where the subtraction cancels (`|d2| < r2 / 2^6`), given its `links` `[e0, e1, l0², l1²]`
/// (see [`dyad_of`]): `d2 = 4 A²` for the triangle of sides `l0`, `l1` and `|e|` (area `A`),
/// by Kahan's stable form of Heron's formula. The direct `d2` carries an error of about `eps r2` (that of `c`, whose terms are the squares of the
/// lengths), so the root's angle one of `eps / sin θ` for the triangle's angle `θ` between `e`
/// and the first link: where the first link is much the longer (a link of 1 beside links of 2e9),
/// `θ` is tiny however regular the position, and the short link's angle came out radians off
/// (2.9e-4 rad at 2e6, 2.6e-10 at 2e3). From the lengths, the error is that of the data's own
/// rounding. Near a limit position of the dyad (`θ` tiny as well) the same form is the more
/// accurate. `d2` as it is where it is NaN or the subtraction kept its digits.
///
/// A first link below the rounding of the others (`short_link`) is recomputed too (it fails
/// `first_link_long`), for the negative `d2` of no triangle: where such a triangle closes
/// exactly, the short link's square is below the rounding of `c`, which is then exactly `0`,
/// and `d2 = a² + b²` does not cancel, so the caller's root (`Ok([π/2, π])` for the slide dyad
/// with a coupler of `1e-20`: the coupler square to nothing) came from no cold branch.
#[inline(always)]
pub fn dyad_d2(d2: f64, r2: f64, links: [f64; 4]) -> f64 {
    // A NaN `d2` fails the first test and keeps itself; a NaN length recomputes a NaN.
    if d2.abs() < r2 * DYAD_CANCELLED || !first_link_long(links[2], links[3]) { dyad_d2_stable(links) } else { d2 }
}

/// Whether a dyad's first link, of squared length `l0_sq`, is above [`FIRST_LINK_SHORT`] times
/// its second (`l1_sq`), the regular steps' one test of a short first link (a multiplication
/// and a comparison): where it fails the cold paths judge the lengths ([`short_link`]). A first
/// link that [`short_link`] holds below the rounding in a triangle that closes (its offset
/// `|e|` at most `l0 + l1`, so its size `l0 + l1 + |e|` at most `2 (l0 + l1)`) is at most `2
/// eps / (1 - 2 eps)` times the second link, and its square within `4.000001 eps²` of the
/// second's square: the bound of `16 eps²` holds it with the rounding of the squares to spare.
/// A NaN fails (the cold paths see it, as they do the NaN `d2` it makes); where the bound underflows
/// (a second link below about `1e-139`) or overflows, the dyad's `a² + b²` (a fourth power of its
/// lengths) has left the normal range, which the callers test first, and which rescales.
#[inline(always)]
fn first_link_long(l0_sq: f64, l1_sq: f64) -> bool {
    l0_sq > FIRST_LINK_SHORT * l1_sq
}

/// `16 eps²`: see [`first_link_long`].
const FIRST_LINK_SHORT: f64 = 16.0 * f64::EPSILON * f64::EPSILON;

/// `|d2| / r2` below which [`dyad_d2`] recomputes (`2^-6`: the triangle's angle `θ` between `e`
/// and the first link below about 7 degrees). The direct form's angle is off by about
/// `eps / (2 tan θ)`, a few eps at this bound; and the second link's angle by that times the
/// ratio of the first link to the second, where the first is much the longer (a coupler twelve
/// times its rocker, `θ` below 3 degrees over the turn: at a bound of `2^-20` the rocker's angle
/// came out `3e-14` rad off, where the triangle gives rounding alone; tested against
/// 50-digit references).
const DYAD_CANCELLED: f64 = 1.0 / (1u64 << 6) as f64;

/// `4 A²` for the triangle of sides `|e|`, `l0` and `l1` of `links` `[e0, e1, l0², l1²]`, by
/// Kahan's ordering (sides `x >= y >= z`): `16 A² = (x + (y + z)) (z - (x - y)) (z + (x - y)) (x + (y - z))`,
/// each factor a sum or a difference of values known to their rounding. Negative where the
/// sides make no triangle (no root), as `r2 - c²` is, and (`-2^-1022`) where one side is a link
/// below the rounding of the others ([`short_link`]).
#[cold]
#[inline(never)]
fn dyad_d2_stable([e0, e1, l0, l1]: [f64; 4]) -> f64 {
    // A link below the rounding of the others ([`short_link`]): its angle is the rounding's,
    // so its triangle is taken for none. The callers' test of `d2` then fails into their
    // cold judgement of circles that miss (`dyad_touching`), which reports it singular: a
    // dyad with a coefficient folded (`folded_dyad_root_offset`) had no other cold branch.
    let mut s = [l0.sqrt(), l1.sqrt(), e0.hypot(e1)];
    if short_link_of(s[0], s[1], s[2]) {
        return -f64::MIN_POSITIVE;
    }
    s.sort_by(|p, q| q.total_cmp(p));
    let [x, y, z] = s;
    0.25 * ((x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z)))
}

/// [`dyad_roots`] where `a² + b²` is not a normal number: the coefficients are products of two
/// lengths, so `a² + b²` is a fourth power of the mechanism's size and leaves the range of
/// `f64` at sizes beyond about `1e±77`. The equation is homogeneous in `(a, b, c)`: divided by
/// the power of two nearest their largest magnitude (exact), its roots are the same and its
/// squares are of order one. Coefficients that are not finite, all zero, or so small that they
/// carry less than full precision (below `2^-1000`) fail as the unscaled formulas do.
#[cold]
#[inline(never)]
fn dyad_roots_rescaled(a: f64, b: f64, c: f64, flip: bool, cfg: &NewtonConfig) -> Result<(f64, f64), BlockFailure> {
    let (_, [a, b, c], r2, d) = rescaled(a, b, c, None, flip, cfg)?;
    Ok(roots_of_offset(a, b, c, r2, d))
}

/// `a cos q + b sin q = c` divided by `k`, the power of two nearest its largest coefficient
/// (exact: the same roots, squares of order one), and its root's offset there: `(k, [a, b, c]
/// k, r2, d)`. Coefficients that are not finite, all zero, or below
/// [`SMALLEST_PRECISE_COEFFICIENT`] are not divided (`k = 1`), and fail as the unscaled
/// formulas do; a failure's residual is relative ([`unreached`]), the same for the equation
/// divided. A coefficient that is not finite has no root to divide
/// ([`non_finite_coefficient`]: an infinite `a` gave `d = inf` and the cosine `inf / inf`,
/// NaN, with no error). A dyad's circles that miss (`links` its lengths, as [`dyad_of`] takes
/// them) are judged in its lengths ([`dyad_touching`]), which the division leaves as they are.
fn rescaled(
    a: f64,
    b: f64,
    c: f64,
    links: Option<[f64; 4]>,
    flip: bool,
    cfg: &NewtonConfig,
) -> Result<(f64, [f64; 3], f64, f64), BlockFailure> {
    if !(a.is_finite() && b.is_finite() && c.is_finite()) {
        return Err(non_finite_coefficient(a, b, c));
    }
    let big = a.abs().max(b.abs()).max(c.abs());
    let k = if big >= SMALLEST_PRECISE_COEFFICIENT { reciprocal_power_of_two(big) } else { 1.0 };
    let (a, b, c) = (a * k, b * k, c * k);
    let r2 = a * a + b * b;
    let d2 = r2 - c * c;
    // A dyad's cancelled `d2` from the triangle, as where the size needs no rescaling.
    let d2 = links.map_or(d2, |links| dyad_d2_divided(d2, r2, links, k));
    let d = match links {
        Some(links) if !(d2 >= 0.0 && r2 >= f64::MIN_POSITIVE) => dyad_touching(d2, r2, c, links, cfg)?,
        // A triangle that closes with a link below the rounding of the others: its angle is
        // the rounding's, as where the size needs no rescaling (`dyad_offset_cancelled`).
        Some(links) if short_link(links) => return Err(undetermined(cfg)),
        _ => root_offset(d2, r2, c, flip, cfg)?,
    };
    Ok((k, [a, b, c], r2, d))
}

/// [`dyad_d2`] of a dyad's equation divided by `k` ([`rescaled`]), given its `links` as they are
/// (`[e0, e1, l0², l1²]`, at a size where the triangle's `4 A²`, a fourth power of the lengths,
/// may leave the range of `f64`): the triangle of the lengths divided by `s`, the power of two
/// nearest the reciprocal of the largest (exact), whose `4 A² s⁴` is then of order one, times
/// `(k / s²)²` (a power of two) for the divided equation's `d2 = 4 A² k²`. Without it the dyad
/// was solved from its coefficients alone at sizes beyond about `2^±256`, where `a² + b²`
/// leaves the range, and lost to cancellation what the triangle keeps at other sizes.
fn dyad_d2_divided(d2: f64, r2: f64, [e0, e1, l0, l1]: [f64; 4], k: f64) -> f64 {
    if d2.abs() >= r2 * DYAD_CANCELLED && first_link_long(l0, l1) {
        return d2;
    }
    let big = e0.abs().max(e1.abs()).max(l0.sqrt()).max(l1.sqrt());
    // Lengths that are not finite, or all zero: the coefficients' own verdict.
    if !(big.is_finite() && big > 0.0) {
        return d2;
    }
    let s = reciprocal_power_of_two(big);
    let f = k / (s * s);
    dyad_d2_stable([e0 * s, e1 * s, l0 * (s * s), l1 * (s * s)]) * f * f
}

/// The failure of `a cos q + b sin q = c` with a coefficient that is not finite: a NaN one's
/// value not finite; an infinite one's an overflow (its terms too large for `f64`: a length
/// whose square, or a product of two, overflowed, at a size the rescue answers by Newton; an
/// infinite length given is reported as such before the block's failure).
#[cold]
#[inline(never)]
fn non_finite_coefficient(a: f64, b: f64, c: f64) -> BlockFailure {
    if a.is_nan() || b.is_nan() || c.is_nan() {
        BlockFailure::NonFinite { row: 0, iterations: 0 }
    } else {
        BlockFailure::Overflow { row: 0 }
    }
}

/// `2^-1000`: a coefficient at least this large is a normal number with 22 binary orders of
/// magnitude to spare, so the subnormal rounding of the terms it was computed from (absolute
/// `2^-1075`) is far below its own rounding.
const SMALLEST_PRECISE_COEFFICIENT: f64 = 9.332636185032189e-302;

/// The power of two `2^-e` with `2^e <= x < 2^(e+1)`, for a positive finite `x`: multiplying by
/// it is exact and brings `x` into `[1, 2)` (for a subnormal `x` below `2^-1023`, the largest
/// power of two, `2^1023`, which brings it to at least `2^-51`). `1` for anything else (zero,
/// negative, infinite, NaN), which leaves a value unchanged.
pub(crate) fn reciprocal_power_of_two(x: f64) -> f64 {
    if !(x > 0.0 && x <= f64::MAX) {
        return 1.0;
    }
    let exponent = |v: f64| ((v.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    // A subnormal's exponent, read from it times 2^600 (exact).
    let e = if x >= f64::MIN_POSITIVE { exponent(x) } else { exponent(x * 2f64.powi(600)) - 600 };
    // `2^-e` for `e` in `-1023 ..= 1023`: `2^-1023` is subnormal, and still exact.
    if e > 1022 { 0.5 * 2f64.powi(-(e - 1)) } else { 2f64.powi(-e.max(-1023)) }
}

/// `sqrt(1 / d2)`, the normalisation of the direction `(a, b)` with `d2 = a² + b²` of a polar
/// length along offset `(e0, e1)`, or the failure when there is no direction: a zero offset
/// (a zero length, whose angle every value satisfies: singular), a direction that vanishes
/// although the offset does not (it cannot be reached: the relative residual 1, see
/// `unreached`), or one whose square overflowed (`d2` infinite, its terms too large for `f64`:
/// [`BlockFailure::Overflow`], which the rescue answers by Newton at any size, see
/// `mechanism::extreme_scale`). Taken as a direction, an overflowed square gave the
/// normalisation 0: a length 0, with no error.
#[inline]
pub fn polar_norm(d2: f64, e0: f64, e1: f64, cfg: &NewtonConfig) -> Result<f64, BlockFailure> {
    let ir = polar_norm_deferred(d2);
    // Written so that a NaN fails; infinite for a zero `d2`, and for one so small (an offset
    // below about 1e-154 of the unit) that it has lost significant bits; zero for an infinite
    // `d2`.
    if ir <= f64::MAX && ir > 0.0 { Ok(ir) } else { Err(polar_failure(d2, e0, e1, cfg)) }
}

/// [`polar_norm`]'s failure for the squared direction `d2` of offset `(e0, e1)`.
#[cold]
#[inline(never)]
fn polar_failure(d2: f64, e0: f64, e1: f64, cfg: &NewtonConfig) -> BlockFailure {
    if d2 == f64::INFINITY { BlockFailure::Overflow { row: 0 } } else { no_root(d2, 0.0, e0.abs().max(e1.abs()), cfg) }
}

/// The test of a polar length's lever in a position-only solve: the length `|(e0, e1)|` against
/// `floor`, the loop's other lengths. Below `singular_tol` times the floor the angle is
/// determined by the data no better than `eps / singular_tol` radians (the length's pivot ratio,
/// which the analogs' factorisation would report, is under the tolerance): singular, as Newton
/// finds it. A NaN passes, for the solution's own finiteness check.
///
/// ```
/// use kinloop_runtime::NewtonConfig;
/// use kinloop_runtime::generated::check_lever;
/// let cfg = NewtonConfig::default(); // singular_tol = 1e-10
/// assert!(check_lever(3e-10, 4e-10, 2.0, &cfg).is_ok()); // 5e-10 of a loop of 2: 2.5e-10
/// assert!(check_lever(3e-11, 4e-11, 2.0, &cfg).is_err());
/// ```
#[inline]
pub fn check_lever(e0: f64, e1: f64, floor: f64, cfg: &NewtonConfig) -> Result<(), BlockFailure> {
    lever_against(e0, e1, floor * floor, cfg)
}

/// The test of a dyad's centres in a position-only solve: their offset `(e0, e1)` against the
/// longer of the two links (`l0_sq`, `l1_sq` the links' squared lengths). Centres closer than
/// `singular_tol` times the link leave the dyad's orientation to the rounding (two equal links
/// folded onto coincident centres turn freely about them): singular, as the analogs' pivot ratio
/// (about the offset over the link) and Newton find it. A limit position of two unequal links
/// keeps its centres `|l0 - l1|` apart and passes. A NaN passes, for the solution's own
/// finiteness check.
///
/// ```
/// use kinloop_runtime::NewtonConfig;
/// use kinloop_runtime::generated::check_centres;
/// let cfg = NewtonConfig::default(); // singular_tol = 1e-10
/// assert!(check_centres(1e-9, 0.0, 4.0, 4.0, &cfg).is_ok());
/// assert!(check_centres(1e-11, 0.0, 4.0, 4.0, &cfg).is_err());
/// ```
#[inline]
pub fn check_centres(e0: f64, e1: f64, l0_sq: f64, l1_sq: f64, cfg: &NewtonConfig) -> Result<(), BlockFailure> {
    lever_against(e0, e1, if l0_sq > l1_sq { l0_sq } else { l1_sq }, cfg)
}

/// The test of [`check_lever`] and [`check_centres`] on squares: the lever `(e0, e1)` against
/// `singular_tol` times the length whose square is `floor_sq` (no square root on the path that
/// passes).
#[inline]
fn lever_against(e0: f64, e1: f64, floor_sq: f64, cfg: &NewtonConfig) -> Result<(), BlockFailure> {
    let tol = cfg.singular_tol;
    if e0 * e0 + e1 * e1 < tol * tol * floor_sq { Err(short_lever(e0, e1, floor_sq, cfg)) } else { Ok(()) }
}

/// The failure of a lever shorter than the tolerance allows.
#[cold]
#[inline(never)]
fn short_lever(e0: f64, e1: f64, floor_sq: f64, cfg: &NewtonConfig) -> BlockFailure {
    let pivot_ratio = e0.hypot(e1) / floor_sq.sqrt();
    BlockFailure::Singular { row: 0, iterations: 0, residual: 0.0, pivot_ratio, tolerance: cfg.singular_tol }
}

/// The magnitude beyond which an angle cannot be solved to the tolerance of `cfg` on its turn
/// ([`NewtonConfig::largest_precise_angle`]).
#[inline]
pub fn largest_precise_angle(cfg: &NewtonConfig) -> f64 {
    cfg.largest_precise_angle()
}

/// The checks of a closed-form solution `out` whose first `angles` entries are angles: every
/// entry finite (a NaN comes from the inputs, parameters, guess or a coefficient's domain), and
/// every angle small enough to be accurate. On the guess's turn an angle is a large number when
/// the guess is: beyond [`largest_precise_angle`] its own rounding would be a wrong answer.
#[inline]
pub fn check_closed<const K: usize>(out: &[f64; K], angles: usize, cfg: &NewtonConfig) -> Result<(), BlockFailure> {
    if !out.iter().sum::<f64>().is_finite() {
        return Err(BlockFailure::NonFinite { row: 0, iterations: 0 });
    }
    // Each angle against the limit: the test of their largest magnitude, without the maximum.
    let limit = largest_precise_angle(cfg);
    if out[..angles].iter().all(|q| q.abs() <= limit) { Ok(()) } else { Err(imprecise(*out, angles)) }
}

/// The failure of angles too large to be accurate: the largest of the first `angles` values of
/// `out` (the error names the block's angle whose guess it is on the turn of). Given the values,
/// not a reference to them: a reference would keep a solution's array in memory on the path
/// that passes its checks (the stores of every block's values at every step of a point solve),
/// where a copy is made on this path only.
#[cold]
#[inline(never)]
fn imprecise<const K: usize>(out: [f64; K], angles: usize) -> BlockFailure {
    let value = out[..angles].iter().fold(0.0f64, |m, q| if q.abs() > m.abs() { *q } else { m });
    BlockFailure::TooManyTurns { value }
}

// The steps without their tests, for a kernel whose checks are deferred to its end (see
// `deferred`): the same formulas, NaN or infinite where a test would fail.

/// [`root_offset`] without its test: `±sqrt(d2)`, NaN when `d2` is
/// negative (no real root, or a limit position rounded past, which the checked kernel tells
/// apart) or NaN.
#[inline(always)]
pub fn root_offset_deferred(d2: f64, flip: bool) -> f64 {
    if flip { -d2.sqrt() } else { d2.sqrt() }
}

/// [`dyad_of`] without its test: the same formulas, NaN where it fails.
#[inline(always)]
pub fn dyad_of_deferred(dyad: [f64; 6], c: f64, flip: bool) -> (f64, f64) {
    let [a, b, _, _, l0, l1] = dyad;
    let r2 = a * a + b * b;
    // Where the checked step rescales (`a² + b²` not normal), a NaN trace: the checked kernel
    // then answers. A cancelled `d2` or a short first link: the triangle, out of line.
    let r2 = if r2 >= f64::MIN_POSITIVE { r2 } else { f64::NAN };
    let d2 = r2 - c * c;
    let d = if d2 >= r2 * DYAD_CANCELLED && first_link_long(l0, l1) {
        root_offset_deferred(d2, flip)
    } else {
        dyad_offset_cancelled_deferred(d2, r2, [dyad[2], dyad[3], l0, l1], flip)
    };
    roots_of_offset(a, b, c, r2, d)
}

/// [`dyad_offset_cancelled`] without its tests: the offset from the triangle where the checked
/// step takes it from there and succeeds (a dyad whose first link is much the longer takes
/// this path at every step: sent back to the checked kernel, each of its sweep's samples was
/// solved twice); NaN wherever the checked step judges further (no triangle, a limit position
/// rounded past, a link below the rounding), which the checked kernel then answers.
#[cold]
#[inline(never)]
fn dyad_offset_cancelled_deferred(d2: f64, r2: f64, links: [f64; 4], flip: bool) -> f64 {
    let d2 = dyad_d2(d2, r2, links);
    if d2 >= 0.0 && !second_turns_freely(links) && !short_link(links) {
        root_offset_deferred(d2, flip)
    } else {
        f64::NAN
    }
}

/// [`dyad_roots`] without its test: the same formulas, NaN where it
/// fails (a negative `d2`, or `r2 = 0`: `0 · ∞`).
#[inline(always)]
pub fn dyad_roots_deferred(a: f64, b: f64, c: f64, flip: bool) -> (f64, f64) {
    let r2 = a * a + b * b;
    // Where the checked step rescales (`a² + b²` not normal), a NaN trace: the checked kernel
    // then answers.
    let r2 = if r2 >= f64::MIN_POSITIVE { r2 } else { f64::NAN };
    roots_of_offset(a, b, c, r2, root_offset_deferred(r2 - c * c, flip))
}

/// `(cos q, sin q)` of the root of `a cos q + b sin q = c` with offset `d` (see
/// [`root_offset`]) and `r2 = a² + b²`: `((a c - b d) / r², (b c + a d) / r²)`, checked or not.
#[inline(always)]
pub(crate) fn roots_of_offset(a: f64, b: f64, c: f64, r2: f64, d: f64) -> (f64, f64) {
    let inv = 1.0 / r2;
    ((a * c - b * d) * inv, (b * c + a * d) * inv)
}

/// [`polar_norm`] without its test: `sqrt(1 / d2)`, infinite for a zero direction (whose
/// components, both zero, then give NaN sines and cosines) and for a subnormal one below about
/// `5.6e-309` (few significant bits: see `mechanism::extreme_scale`), NaN for a NaN one. (The
/// reciprocal first: as cheap as `1 / sqrt(d2)`, and its overflow is the trace of a `d2` too small.)
#[inline(always)]
pub fn polar_norm_deferred(d2: f64) -> f64 {
    (1.0 / d2).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::turns::{reduce_turn, unwrap_to_turn};
    use core::f64::consts::TAU;

    /// The triangle's `4 A²` is `r2 - c²` wherever the subtraction keeps its digits (sides of
    /// every order, a reflection's sign of `e` included), and no triangle is a negative one.
    #[test]
    fn the_triangle_of_a_dyad_gives_its_d2() {
        for (e, l0, l1) in [([3.0, 0.0], 4.0, 5.0), ([-1.2, 0.7], 2.5, 1.9), ([0.1, -0.2], 0.3, 0.25)] {
            let ee: f64 = e[0] * e[0] + e[1] * e[1];
            let r2 = l0 * l0 * ee;
            let c = 0.5 * ((l1 * l1 - l0 * l0) - ee);
            let direct = r2 - c * c;
            let stable = dyad_d2_stable([e[0], e[1], l0 * l0, l1 * l1]);
            assert!((stable - direct).abs() <= 1e-14 * r2, "{e:?} {l0} {l1}: {stable} vs {direct}");
        }
        // Sides 1, 1 and 3: no triangle, as `r2 - c² = 9 - 4.5^2` says.
        let stable = dyad_d2_stable([3.0, 0.0, 1.0, 1.0]);
        assert!(stable < 0.0 && (stable - 9.0 * (1.0 - 20.25 / 9.0)).abs() < 1e-12, "{stable}");
    }

    /// The root satisfies the equation and has the requested sign of `h' = b cos q - a sin q`.
    #[test]
    fn dyad_roots_solve_the_equation_on_the_requested_branch() {
        let (a, b, c) = (0.3, -1.7, 0.9);
        for flip in [false, true] {
            let (cq, sq) = dyad_roots(a, b, c, flip, &NewtonConfig::default()).unwrap();
            assert!((a * cq + b * sq - c).abs() < 1e-15);
            assert!((cq * cq + sq * sq - 1.0).abs() < 1e-15);
            assert_eq!(b * cq - a * sq > 0.0, flip);
        }
    }

    /// No real root is no assembly, its residual relative: `cos q = 2` misses by 1 of 3 (`|c| -
    /// r` over `|c| + r`), a direction that vanishes misses its whole offset.
    #[test]
    fn no_real_root_is_a_typed_failure() {
        let cfg = NewtonConfig::default();
        assert!(
            matches!(dyad_roots(1.0, 0.0, 2.0, false, &cfg), Err(BlockFailure::NoAssembly { residual, .. }) if residual == 1.0 / 3.0)
        );
        assert!(matches!(dyad_roots(f64::NAN, 0.0, 0.0, false, &cfg), Err(BlockFailure::NonFinite { .. })));
        assert!(
            matches!(polar_norm(0.0, 3.0, -4.0, &cfg), Err(BlockFailure::NoAssembly { residual, .. }) if residual == 1.0)
        );
        // Concentric circles of different radii: `0 = c` with `c` non-zero cannot hold.
        assert!(matches!(dyad_roots(0.0, 0.0, 0.5, true, &cfg), Err(BlockFailure::NoAssembly { .. })));
    }

    /// A discriminant negative by rounding only is the limit position (the double root); one
    /// negative beyond the residual tolerance is still no assembly, with the residual `|c| - r`
    /// over `|c| + r`.
    #[test]
    fn a_limit_position_rounded_past_is_the_double_root() {
        let cfg = NewtonConfig::default();
        // `0.1 + 0.2` rounds above `0.3`: in metres the rod falls 4e-17 short of the offset.
        let (b, c) = (0.3, 0.1 + 0.2);
        assert!(b * b - c * c < 0.0, "the example must round past the limit");
        for flip in [false, true] {
            let (cq, sq) = dyad_roots(0.0, b, c, flip, &cfg).unwrap();
            assert_eq!(cq, 0.0);
            assert!((sq - 1.0).abs() <= 2.0 * f64::EPSILON, "{sq}");
        }
        // Short by 1e-9 of the offset: beyond the default 1e-12, and beyond a tolerance of 0
        // (which still allows the rounding floor, 16 eps) even by rounding.
        let short = 0.3 * (1.0 - 1e-9);
        for cfg in [cfg, NewtonConfig { residual_tol: 0.0, ..cfg }] {
            match dyad_roots(0.0, short, 0.3, false, &cfg) {
                Err(BlockFailure::NoAssembly { residual, .. }) => {
                    assert!((residual - 5e-10).abs() < 1e-15, "{residual}")
                }
                other => panic!("{other:?}"),
            }
        }
        // Short by 1e-13 relative: within the default tolerance, not within a tolerance of 0.
        let near = 0.3 * (1.0 - 1e-13);
        assert_eq!(dyad_roots(0.0, near, 0.3, false, &cfg).unwrap().0, 0.0);
        let exact = NewtonConfig { residual_tol: 0.0, ..cfg };
        assert!(matches!(dyad_roots(0.0, near, 0.3, false, &exact), Err(BlockFailure::NoAssembly { .. })));
    }

    /// The coefficients of the dyad `|e + l0 c0| = l1` (centres `e` apart, links `l0`, `l1`) as
    /// a closed-form block gives them: `(a, b) = l0 e`, `c = (l1² - l0² - |e|²) / 2`, with its
    /// `links` `[e0, e1, l0², l1²]`, `r2 = a² + b²` and the discriminant `d2`.
    struct Dyad {
        a: f64,
        b: f64,
        c: f64,
        links: [f64; 4],
        r2: f64,
        d2: f64,
    }

    impl Dyad {
        fn of([e0, e1]: [f64; 2], l0: f64, l1: f64) -> Self {
            let (a, b) = (l0 * e0, l0 * e1);
            let c = 0.5 * ((l1 * l1 - l0 * l0) - (e0 * e0 + e1 * e1));
            let links = [e0, e1, l0 * l0, l1 * l1];
            let r2 = a * a + b * b;
            Dyad { a, b, c, links, r2, d2: dyad_d2(r2 - c * c, r2, links) }
        }
    }

    /// A dyad that cannot be assembled reports how far its links fall short of closing the
    /// triangle with their centres' offset, over the dyad's size (the three lengths' sum),
    /// whichever path solves it: links 1.5 and 2 on centres 5 apart (1.5 short: 3/17), links
    /// 1 and 4 on centres 2 apart (the long one 1 too long: 1/7); the same at every size, where
    /// its coefficients' squares are in range and where they are not (`1e±100`: `a² + b²` is
    /// a fourth power of the size, rescaled); and a coefficient folded (the second offset zero)
    /// reports the same. In the coefficients' units, products of two lengths, the first
    /// reported `|c| - r = 4.125` times the size squared.
    #[test]
    fn a_dyad_that_cannot_close_reports_its_gap_over_its_size() {
        let cfg = NewtonConfig::default();
        for ([e0, e1], l0, l1, want) in [([3.0, 4.0], 1.5, 2.0, 3.0 / 17.0), ([-2.0, 0.0], 1.0, 4.0, 1.0 / 7.0)] {
            for k in [1.0, 2f64.powi(100), 2f64.powi(-100), 1e100, 1e-100] {
                let Dyad { a, b, c, links, r2, d2 } = Dyad::of([e0 * k, e1 * k], l0 * k, l1 * k);
                let results = [
                    dyad_of([a, b, links[0], links[1], links[2], links[3]], c, false, &cfg).map(|(cq, _)| cq),
                    folded_dyad_root_offset(d2, r2, a, b, c, links, false, &cfg),
                ];
                for got in results {
                    match got {
                        Err(BlockFailure::NoAssembly { residual, .. }) => {
                            assert!((residual - want).abs() <= 1e-15, "size {k:e}: {residual} against {want}")
                        }
                        other => panic!("size {k:e}: {other:?}"),
                    }
                }
            }
        }
    }

    /// A dyad whose first link is within the tolerance of nothing beside the others closes
    /// within the tolerance at every angle of it, which is then not determined: a coupler of
    /// `1e-300` or `1e-20` (whose `a² + b²` is subnormal, rescaled, or normal) from the pin of
    /// a unit crank at `fl(π/3)`, `1 - 9.9e-17` from the pivot of a unit rocker (mpmath at 50
    /// digits: no exact triangle, yet every coupler angle leaves the dyad open by at most
    /// `5e-17` of its size, far within the tolerance `1e-12`). Singular, with the configured
    /// tolerance, whichever path solves it; it was "cannot be assembled" with a gap of `0`.
    /// Where the pin misses the rocker's reach by `2e-9` of it, far beyond the tolerance, no
    /// assembly still, with the gap `(1 - |e|) / (1 + |e|)` (the coupler's length below its
    /// rounding).
    #[test]
    fn a_dyad_whose_short_link_closes_it_at_every_angle_is_singular() {
        let cfg = NewtonConfig::default().with_singular_tol(1e-9);
        let phi = PI / 3.0;
        let pin = [phi.cos() - 1.0, phi.sin()];
        for (miss, l0) in [(1.0, 1e-300), (1.0, 1e-20), (1.0 - 2e-9, 1e-300), (1.0 - 2e-9, 1e-20)] {
            let Dyad { a, b, c, links, r2, d2 } = Dyad::of([pin[0] * miss, pin[1] * miss], l0, 1.0);
            let results = [
                dyad_of([a, b, links[0], links[1], links[2], links[3]], c, false, &cfg).map(|(cq, _)| cq),
                folded_dyad_root_offset(d2, r2, a, b, c, links, false, &cfg),
            ];
            let e = links[0].hypot(links[1]);
            for got in results {
                match got {
                    Err(BlockFailure::Singular { pivot_ratio, tolerance, .. }) if miss == 1.0 => {
                        assert_eq!((pivot_ratio, tolerance), (0.0, 1e-9), "{l0:e}");
                    }
                    Err(BlockFailure::NoAssembly { residual, .. }) if miss < 1.0 => {
                        let want = (1.0 - e) / (1.0 + e);
                        assert!((residual - want).abs() <= 1e-15, "{l0:e}: {residual} against {want}");
                    }
                    other => panic!("miss {miss}, coupler {l0:e}: {other:?}"),
                }
            }
        }
    }

    /// A dyad whose `c²` overflows although `a² + b²` does not (centres `3 s` apart, links
    /// `0.01 s` and `2 s`: `a ~ 0.03 s²`, `c ~ -2.5 s²`, at `s = 1e77` `c² ~ 6e308`) falls short
    /// of closing by `0.99 s` at every size: no assembly, with the same gap over its size,
    /// `0.99 / 5.01`, as at sizes where nothing overflows. It was taken for a limit position
    /// (`-d2 = inf` within `2 tol c² = inf`) and a position returned. Where the links fall short
    /// by less than the tolerance allows, the limit position is still found at that size.
    #[test]
    fn a_dyad_whose_offset_squared_overflows_is_judged_at_its_size() {
        let cfg = NewtonConfig::default();
        let want = 0.99 / 5.01;
        for s in [1.0, 1e-77, 1e77, 1.2e77] {
            let Dyad { a, b, c, links, r2, d2 } = Dyad::of([3.0 * s, 0.0], 0.01 * s, 2.0 * s);
            let results = [
                dyad_of([a, b, links[0], links[1], links[2], links[3]], c, false, &cfg).map(|(cq, _)| cq),
                folded_dyad_root_offset(d2, r2, a, b, c, links, false, &cfg),
                dyad_roots(a, b, c, false, &cfg).map(|(cq, _)| cq),
                root_offset(r2 - c * c, r2, c, false, &cfg),
            ];
            for (i, got) in results.into_iter().enumerate() {
                match got {
                    // The coefficients' own residual (`dyad_roots`, `root_offset`) is `|c| - r`
                    // over `|c| + r`, not the dyad's gap: only its being a failure is compared.
                    Err(BlockFailure::NoAssembly { residual, .. }) => {
                        assert!(i >= 2 || (residual - want).abs() <= 1e-15, "size {s:e}: {residual} against {want}")
                    }
                    other => panic!("size {s:e}, result {i}: {other:?}"),
                }
            }
        }
        // `cos q = c / a` with `a` just below `c` (by a relative 1e-13 at size 1; by 8 eps
        // about the square root of `f64::MAX`, where `c²` overflows and `a²` does not): within
        // the default tolerance, the limit position `cos q = 1`.
        let big = f64::MAX.sqrt();
        let (c_over, a_under) = (big * (1.0 + 4.0 * f64::EPSILON), big * (1.0 - 4.0 * f64::EPSILON));
        assert!(c_over * c_over == f64::INFINITY && a_under * a_under < f64::MAX);
        for (c, a) in [(1.0, 1.0 - 1e-13), (c_over, a_under)] {
            let (cq, sq) = dyad_roots(a, 0.0, c, false, &cfg).unwrap();
            assert!((cq - 1.0).abs() <= 1e-12 && sq == 0.0, "{c:e}: {cq} {sq}");
        }
    }

    /// Dyads whose links, laid in line, miss closing the triangle with their centres' offset by
    /// `delta`, on centres along `x` (so that `b = 0`, as a folded dyad's too): `(name, |e|,
    /// l0, l1, delta)`, every length a sum of powers of two (exact at size 1 and `2^-30`). The
    /// loop's least residual is `delta` (the in-line position), the dyad's size `l0 + l1 + |e|`;
    /// its gap over its size is the closed form `delta / size`.
    const IN_LINE: [(&str, f64, f64, f64, f64); 5] = {
        const S: f64 = 1.0 / (1u64 << 20) as f64; // the short link, 9.5e-7 of the others
        const NEAR: f64 = 1.0 / (1u64 << 42) as f64; // 2.3e-13: within the tolerance of 1e-12
        const FAR: f64 = 1.0 / (1u64 << 30) as f64; // 9.3e-10: beyond it
        [
            ("short first link, centres farthest", 1.0 + S + NEAR, S, 1.0, NEAR),
            ("short first link, second longest", 1.0, S, 1.0 + S + NEAR, NEAR),
            ("short second link, centres farthest", 1.0 + S + FAR, 1.0, S, FAR),
            ("short second link, first longest", 1.0, 1.0 + S + FAR, S, FAR),
            ("equal links, centres farthest", 2.0 + NEAR, 1.0, 1.0, NEAR),
        ]
    };

    /// Whether the dyad `(|e|, l0, l1, delta)` of [`IN_LINE`] is a limit position: its loop closes
    /// within the default tolerance (`1e-12`) of its size in line.
    fn closes_in_line(e: f64, l0: f64, l1: f64, delta: f64) -> bool {
        delta <= NewtonConfig::default().residual_tol * (e + l0 + l1)
    }

    /// A dyad whose links laid in line close its loop within the residual tolerance of its size
    /// is its limit position, and one whose links miss by more cannot be assembled, with the
    /// miss over its size as residual, whichever link is short, at every size and whichever
    /// path solves it (`dyad_of`, with its coefficients' squares in range or rescaled, and a
    /// folded coefficient's `folded_dyad_root_offset`). The verdict was taken in the equation's
    /// coefficients, whose `|c|` is about `l0 |e|`: with a short first link a miss of `2.3e-13`
    /// of a loop of 2 (its allowance `tol l0`, `1e-18`) was "cannot be assembled"; with a short
    /// second link one of `9.3e-10` (allowance `tol l0² / l1`, `1e-6`) was a limit position
    /// returned with the loop open by it and the second link's cosine `1 + 2^-10`. The limit
    /// position returned has the links in line: its first link's end, at the angle of the
    /// returned cosine and sine, is the second link's length from its centre, to the tolerance
    /// (an independent construction of the loop).
    #[test]
    fn a_dyad_is_a_limit_position_where_its_links_in_line_close_it_within_the_tolerance() {
        let cfg = NewtonConfig::default();
        let tol = cfg.residual_tol;
        for (what, e, l0, l1, delta) in IN_LINE {
            let closes = closes_in_line(e, l0, l1, delta);
            let want_gap = delta / (e + l0 + l1);
            for k in [1.0, 1e-3, 1e-6, 2f64.powi(-30), 1e3, 1e100, 1e-100] {
                let Dyad { a, b, c, links, r2, d2 } = Dyad::of([e * k, 0.0], l0 * k, l1 * k);
                let of = dyad_of([a, b, links[0], links[1], links[2], links[3]], c, false, &cfg);
                // The emitted code's roots for `b = 0`: `(c / a, d / a)`.
                let folded = folded_dyad_root_offset(d2, r2, a, b, c, links, false, &cfg).map(|d| (c / a, d / a));
                for (path, got) in [("dyad_of", of), ("folded", folded)] {
                    let at = format!("{what}, size {k:e}, {path}");
                    match got {
                        Ok((cq, sq)) => {
                            assert!(closes, "{at}: a position ({cq}, {sq}) where the loop misses by {want_gap:e}");
                            let q = sq.atan2(cq);
                            let end = (e * k + l0 * k * q.cos()).hypot(l0 * k * q.sin());
                            let miss = (end - l1 * k).abs() / (k * (e + l0 + l1));
                            // The in-line miss plus the rounding of a few lengths (`8 eps`).
                            assert!(miss <= tol + 8.0 * f64::EPSILON, "{at}: loop open by {miss:e} of its size");
                        }
                        Err(BlockFailure::NoAssembly { residual, .. }) => {
                            assert!(!closes, "{at}: no assembly, yet the links in line close it to {want_gap:e}");
                            // The gap of lengths rounded at size `k` (a few `eps` of the size).
                            assert!(
                                (residual - want_gap).abs() <= 8.0 * f64::EPSILON,
                                "{at}: {residual:e} against {want_gap:e}"
                            );
                        }
                        other => panic!("{at}: {other:?}"),
                    }
                }
            }
        }
    }

    /// A coefficient that is not finite (an infinite one: a length whose square overflowed, or
    /// an infinite length) gives no root: every closed-form step fails with a typed error, an
    /// overflow (which the rescue answers at the mechanism's own size) or a value not finite,
    /// and none returns a position with a value that is not finite. `dyad_roots(1, 0, inf)`
    /// returned `Ok((inf, NaN))` (an infinite `c` taken for a limit position), `dyad_roots(inf,
    /// 0, 1)` `Ok((NaN, NaN))`, and `folded_root_offset` the offset `0` of a cosine `c / a =
    /// inf`.
    #[test]
    fn a_coefficient_that_is_not_finite_is_a_typed_failure() {
        let cfg = NewtonConfig::default();
        let (inf, nan) = (f64::INFINITY, f64::NAN);
        let typed = |what: &str, got: Result<(f64, f64), BlockFailure>| match got {
            Err(BlockFailure::Overflow { .. } | BlockFailure::NonFinite { .. }) => {}
            other => panic!("{what}: {other:?}"),
        };
        for (a, b, c) in
            [(1.0, 0.0, inf), (1.0, 0.5, -inf), (inf, 0.0, 1.0), (0.0, -inf, 1.0), (inf, 1.0, inf), (1.0, nan, 0.5)]
        {
            let what = format!("({a}, {b}, {c})");
            typed(&what, dyad_roots(a, b, c, false, &cfg));
            let r2 = a * a + b * b;
            typed(&what, folded_root_offset(r2 - c * c, r2, a, b, c, false, &cfg).map(|d| (d, d)));
            // `root_offset` is given a normal `r2` by its callers, which rescale any other.
            if (f64::MIN_POSITIVE..=f64::MAX).contains(&r2) {
                typed(&what, root_offset(r2 - c * c, r2, c, false, &cfg).map(|d| roots_of_offset(a, b, c, r2, d)));
            }
        }
        // A dyad whose second link's square overflowed: `c = inf`, its `a² + b²` of order one.
        let links = [1.0, 0.0, 1.0, inf];
        let c = 0.5 * ((links[3] - links[2]) - 1.0);
        typed("dyad_of", dyad_of([1.0, 0.0, links[0], links[1], links[2], links[3]], c, false, &cfg));
        typed(
            "folded dyad",
            folded_dyad_root_offset(1.0 - c * c, 1.0, 1.0, 0.0, c, links, false, &cfg).map(|d| (d, d)),
        );
    }

    /// An equation every angle satisfies (`0 cos q + 0 sin q = 0`: coincident circles of equal
    /// radii; a zero length along a zero offset) determines no position: singular, as Newton
    /// reports it, with the configured tolerance; not "cannot be assembled".
    #[test]
    fn an_equation_every_angle_satisfies_is_singular() {
        let cfg = NewtonConfig::default().with_singular_tol(1e-9);
        for f in [dyad_roots(0.0, 0.0, 0.0, false, &cfg).map(|_| 0.0), polar_norm(0.0, 0.0, -0.0, &cfg)] {
            match f {
                Err(BlockFailure::Singular { pivot_ratio, tolerance, .. }) => {
                    assert_eq!((pivot_ratio, tolerance), (0.0, 1e-9));
                }
                other => panic!("{other:?}"),
            }
        }
    }

    /// Against libm over the whole range where no libm is called, densely near the quadrant
    /// boundaries (where the reduction switches) and at large arguments (where it is least
    /// accurate): every error well inside the documented bound.
    #[test]
    fn coarse_sine_and_cosine_stay_within_their_bound() {
        let mut worst = 0.0f64;
        let mut check = |x: f64| {
            let (s, c) = sin_cos_coarse(x);
            let (se, ce) = x.sin_cos();
            worst = worst.max((s - se).abs()).max((c - ce).abs());
        };
        for i in -200_000..=200_000 {
            check(i as f64 * 0.05);
            check(i as f64 * 0.0000371);
        }
        for k in -6400..=6400 {
            let b = k as f64 * core::f64::consts::FRAC_PI_4;
            for d in [-1e-9, -1e-15, 0.0, 1e-15, 1e-9] {
                check(b + d);
            }
        }
        for x in [1e4, -1e4, 9999.999, 1e4 + 1.0, 1e9, -3e15] {
            check(x);
        }
        assert!(worst < SIN_COS_COARSE_ERR / 10.0, "{worst:e}");
        let (s, c) = sin_cos_coarse(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
    }

    #[test]
    fn angles_move_to_the_guess_turn_and_are_reduced_to_one_turn() {
        let q = unwrap_to_turn(-3.0, 3.0 - 5.0 * TAU);
        assert!((q - (-3.0 - 4.0 * TAU)).abs() < 1e-12, "{q}");
        assert!((reduce_turn(1.0 + 7.0 * TAU) - 1.0).abs() < 1e-12);
        assert!((asin_near(0.5, false, 2.0, 2.0) - 5.0 * PI / 6.0).abs() < 1e-15);
        assert!((acos_on_side(0.5, -1.0) + PI / 3.0).abs() < 1e-15);
    }

    /// `asin_near` is the angle of the given sine whose cosine has the sign of the guess's,
    /// on the guess's turn (within half a turn of it), over guesses of many turns and sines
    /// up to ±1; the same as `asin` or its supplement moved by `unwrap_to_turn`.
    #[test]
    fn asin_near_keeps_the_guess_side_and_turn() {
        for i in -400..=400 {
            let g = i as f64 * 0.0731 + 0.01;
            let r = reduce_turn(g);
            let right = r.abs() < PI / 2.0;
            for k in -10..=10 {
                let s = k as f64 / 10.0;
                let q = asin_near(s, right, r, g);
                assert!((q.sin() - s).abs() < 1e-13, "{g} {s}: {q}");
                assert!((q - g).abs() <= PI + 1e-12, "{g} {s}: {q}");
                if g.cos().abs() > 1e-9 && s.abs() < 1.0 {
                    assert_eq!(q.cos() > 0.0, g.cos() > 0.0, "{g} {s}: {q}");
                }
                let side = if right { s.asin() } else { PI - s.asin() };
                assert!((q - unwrap_to_turn(side, g)).abs() < 1e-12, "{g} {s}: {q}");
            }
        }
    }

    #[test]
    fn checks_reject_non_finite_values_and_imprecise_angles() {
        let cfg = NewtonConfig::default();
        assert!(check_guess(f64::NAN).is_err() && check_guess(1.0).is_ok());
        assert!(check_closed(&[1.0, 0.5, f64::INFINITY], 1, &cfg).is_err());
        assert!(check_closed(&[1.0, 0.5, 0.8], 1, &cfg).is_ok());
        assert_eq!(check_closed(&[1e9, 0.5], 1, &cfg), Err(BlockFailure::TooManyTurns { value: 1e9 }));
        assert_eq!(check_closed(&[0.5, -1e9, 0.5], 2, &cfg), Err(BlockFailure::TooManyTurns { value: -1e9 }));
        // Only the angles count: a large length is accurate.
        assert!(check_closed(&[1.0, 1e9], 1, &cfg).is_ok());
    }
}
