//! Extreme values of a quantity, located precisely as roots of its velocity analog (or, at a
//! corner of the motion, a kink, where the analog jumps from one sign to the other).
//!
//! The samples of a sweep bracket every sign change of the velocity analog `v'`; each bracket is
//! then refined by a safeguarded Newton iteration on `v'` using the acceleration analog `v''`
//! (a Newton step that leaves the bracket, or does not shrink it fast enough, is replaced by a
//! bisection). The result is exact to a few units of rounding in `x`; the extreme value itself
//! is insensitive to the location error (it enters quadratically).
//!
//! Two extremes closer together than one sample spacing (two sign changes within one interval)
//! are not seen: sample finely enough to separate them.
//!
//! For quantities without a second derivative (e.g. the peak of an acceleration analog), use
//! [`maximize`], a derivative-free bracketed search (Brent's method).

use super::Jet;
use crate::error::Error;

/// A maximum or a minimum: what a located local extreme is ([`LocalExtreme::kind`]), and which
/// extremum an objective asks for ([`Sampled::extremum_with_gradient`](crate::analysis::Sampled::extremum_with_gradient)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extreme {
    /// The largest value (at a local extreme: the velocity analog changes sign from positive
    /// to negative).
    Max,
    /// The smallest value (at a local extreme: the velocity analog changes sign from negative
    /// to positive).
    Min,
}

/// A local extreme of a quantity: where its velocity analog vanishes and changes sign, or
/// jumps from one sign to the other at a corner of the motion (a kink: `abs`, `min`, `max`,
/// `clamp` in the declaration, as a uniform-velocity cam law has).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalExtreme {
    /// A maximum or a minimum.
    pub kind: Extreme,
    /// The quantity, its velocity analog (vanishing; at a kink, one side's) and its
    /// acceleration analog at the extreme (at a kink, within a few units of rounding of it).
    pub at: Jet,
}

impl LocalExtreme {
    /// Input value at the extreme.
    pub fn x(&self) -> f64 {
        self.at.x
    }
    /// The extreme value.
    pub fn value(&self) -> f64 {
        self.at.value
    }
}

/// `true` when `a` and `b` have strictly opposite signs (compared, not multiplied: the product
/// of two analogs of a tiny mechanism underflows to zero).
pub(crate) fn sign_change(a: f64, b: f64) -> bool {
    (a > 0.0 && b < 0.0) || (a < 0.0 && b > 0.0)
}

/// Locates a root of `h` (a function of a [`Jet`] returning its value and derivative) between
/// the jets `lo` and `hi`, where `h` changes sign, by safeguarded Newton steps with bisection;
/// `eval` computes the jet at any `x` of the bracket. Returns the jet at the root.
///
/// Converges quadratically near a simple root; always keeps a bracket, so it cannot diverge. It
/// stops when the step or the bracket falls below `2 eps |x|` (a couple of units of
/// rounding; for a root near `x = 0` an absolute floor of `1e-6` times the initial bracket applies),
/// or after 100 evaluations, and answers the end of the final bracket where `|h|` is smaller.
/// Where `h` jumps across zero instead of passing through it (the velocity analog at a corner
/// of the motion, a kink), the bracket closes on the jump: the answer is the jet there, to the
/// same tolerance.
///
/// Errors (`InvalidArgument`): no sign change of `h` between the ends, a bracket whose width
/// is not finite, a value of `h` not finite; and those of `eval`.
///
/// ```
/// use kinloop_runtime::analysis::{Jet, extremes::bracketed_root};
/// // Root of cos(x) - x (the Dottie number) with its derivative -sin(x) - 1.
/// let eval = |x: f64| Ok(Jet { x, value: x.cos() - x, d1: -x.sin() - 1.0, d2: -x.cos() });
/// let (lo, hi) = (eval(0.0)?, eval(1.0)?);
/// let root = bracketed_root(lo, hi, |j| (j.value, j.d1), eval)?;
/// assert!((root.x - 0.739_085_133_215_160_6).abs() < 1e-15);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn bracketed_root(
    lo: Jet,
    hi: Jet,
    h: impl Fn(&Jet) -> (f64, f64),
    mut eval: impl FnMut(f64) -> Result<Jet, Error>,
) -> Result<Jet, Error> {
    // The tolerances are relative to the bracket's width: an infinite one (ends near the
    // largest f64 of both signs) accepted the first step, the end `lo`, as the root.
    if !(hi.x - lo.x).is_finite() {
        return Err(Error::InvalidArgument(format!(
            "bracketed_root needs a bracket of finite width, not x = {} to {}",
            lo.x, hi.x
        )));
    }
    let (fa, _) = h(&lo);
    let (fb, _) = h(&hi);
    if !fa.is_finite() || !fb.is_finite() || !sign_change(fa, fb) && fa != 0.0 && fb != 0.0 {
        return Err(Error::InvalidArgument(format!(
            "bracketed_root needs a sign change between x = {} ({fa:e}) and x = {} ({fb:e})",
            lo.x, hi.x
        )));
    }
    if fa == 0.0 {
        return Ok(lo);
    }
    if fb == 0.0 {
        return Ok(hi);
    }
    // `neg` keeps the end where h < 0, `pos` the end where h > 0.
    let (mut neg, mut pos) = if fa < 0.0 { (lo, hi) } else { (hi, lo) };
    // Start from the end with the smaller |h|.
    let mut cur = if fa.abs() <= fb.abs() { lo } else { hi };
    let mut dx_old = (hi.x - lo.x).abs();
    // Absolute floor of the tolerances, for a root at or near x = 0.
    let floor = 1e-6 * dx_old;
    let mut dx = dx_old;
    // The answer is the final bracket's end with the smaller |h|: the root lies between them.
    // Not the evaluated point of smallest |h| over the whole search: where h jumps across zero
    // (at a kink) every point on one side has about the same |h|, and an end of the first
    // bracket, a sample spacing from the kink, stood for the root there.
    let better = |a: Jet, b: Jet| if h(&b).0.abs() < h(&a).0.abs() { b } else { a };
    for _ in 0..100 {
        let (f, df) = h(&cur);
        let (a, b) = (neg.x.min(pos.x), neg.x.max(pos.x));
        let newton = cur.x - f / df;
        // Newton when it stays within the bracket and at least halves the previous
        // step; otherwise bisect.
        let x_new = if df != 0.0 && newton >= a && newton <= b && (2.0 * f).abs() <= (dx_old * df).abs() {
            dx_old = dx;
            dx = newton - cur.x;
            newton
        } else {
            dx_old = dx;
            dx = 0.5 * (b - a);
            0.5 * (a + b)
        };
        let scale = x_new.abs() + floor;
        if dx.abs() <= 2.0 * f64::EPSILON * scale || x_new == cur.x {
            return Ok(better(neg, pos));
        }
        let next = eval(x_new)?;
        let (fn_, _) = h(&next);
        if !fn_.is_finite() {
            return Err(Error::InvalidArgument(format!("bracketed_root: non-finite value at x = {x_new}")));
        }
        if fn_ == 0.0 {
            return Ok(next);
        }
        if fn_ < 0.0 {
            neg = next;
        } else {
            pos = next;
        }
        cur = next;
        if (pos.x - neg.x).abs() <= 2.0 * f64::EPSILON * scale {
            return Ok(better(neg, pos));
        }
    }
    Ok(better(neg, pos))
}

/// All local extremes of a quantity sampled at `samples` (jets in increasing `x`): every sign
/// change of the velocity analog between neighbouring samples is refined to the root of the
/// analog by [`bracketed_root`], evaluating `eval` inside the bracket. A sample where the analog
/// is exactly zero is an extreme when the analog has opposite signs on its two sides, and a
/// stationary inflection (no extreme) otherwise. Returned in increasing `x`. Ends of the range
/// are not extremes here (see [`global_range`]).
///
/// ```
/// use kinloop_runtime::analysis::{Jet, extremes::{Extreme, extremes}};
/// // v = sin(x) + 0.5 sin(2x) on [0, 2 pi]: v' = cos x + cos 2x vanishes at pi/3 (max), at
/// // 5 pi/3 (min), and at pi, a sample of this grid, without changing sign (no extreme).
/// let f = |x: f64| Ok(Jet {
///     x,
///     value: x.sin() + 0.5 * (2.0 * x).sin(),
///     d1: x.cos() + (2.0 * x).cos(),
///     d2: -x.sin() - 2.0 * (2.0 * x).sin(),
/// });
/// let samples: Vec<Jet> = (0..=36).map(|i| f(i as f64 * std::f64::consts::TAU / 36.0)).collect::<Result<_, _>>()?;
/// let found = extremes(&samples, f)?;
/// let pi = std::f64::consts::PI;
/// assert_eq!(found.len(), 2);
/// assert_eq!(found[0].kind, Extreme::Max);
/// assert!((found[0].x() - pi / 3.0).abs() < 1e-14);
/// assert!((found[0].value() - 0.75 * 3f64.sqrt()).abs() < 1e-15);
/// assert_eq!(found[1].kind, Extreme::Min);
/// assert!((found[1].x() - 5.0 * pi / 3.0).abs() < 1e-14);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn extremes(samples: &[Jet], eval: impl FnMut(f64) -> Result<Jet, Error>) -> Result<Vec<LocalExtreme>, Error> {
    extremes_across(samples, &[], eval)
}

/// A point between two samples where the quantity cannot be evaluated nearby: a singular
/// crossing (change point) of the mechanism, between the samples `after` and `after + 1`, the
/// nearest either side that a sweep reaches on its branch. Its jet `at` holds the quantity's
/// value at the crossing (the positions there are continuous, the analogs not defined).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Corner {
    pub(crate) after: usize,
    pub(crate) at: Jet,
}

/// [`extremes`] with `corners` (in increasing `after`) between samples: a sign change of the
/// velocity analog across a corner is an extreme at the corner itself (at a change point the
/// motion is continuous and an extreme there is the crossing's position: a coupler point's
/// coordinate whose analog changes sign there, as its derivative does on either branch), not
/// refined by evaluations inside it, which fail.
pub(crate) fn extremes_across(
    samples: &[Jet],
    corners: &[Corner],
    mut eval: impl FnMut(f64) -> Result<Jet, Error>,
) -> Result<Vec<LocalExtreme>, Error> {
    check_increasing(samples)?;
    let sign = |v: f64| {
        if v > 0.0 {
            1i8
        } else if v < 0.0 {
            -1
        } else {
            0
        }
    };
    let mut out: Vec<LocalExtreme> = Vec::new();
    // Walk from one sample with a non-zero analog to the next one; samples where the analog is
    // exactly zero in between are roots themselves.
    let Some(mut i) = samples.iter().position(|j| j.d1 != 0.0) else { return Ok(out) };
    // The analogs' scale, against which an end's analog is zero but for rounding.
    let largest = samples.iter().fold(0.0f64, |m, j| m.max(j.d1.abs()));
    while let Some(step) = samples[i + 1..].iter().position(|j| j.d1 != 0.0) {
        let k = i + 1 + step;
        let (a, b) = (samples[i], samples[k]);
        if sign(a.d1) != sign(b.d1) {
            let kind = if a.d1 > 0.0 { Extreme::Max } else { Extreme::Min };
            let corner = corners.iter().find(|c| c.after >= i && c.after < k);
            let at = if let Some(corner) = corner {
                corner.at
            } else if k == i + 1 {
                bracketed_root(a, b, |j| (j.d1, j.d2), &mut eval)?
            } else {
                // The analog is exactly zero at the samples between: take the middle one.
                samples[(i + k) / 2]
            };
            // Only interior extremes: a range that starts or ends at an extreme (its analog
            // rounded to a tiny non-zero value there) does not report that end.
            if !at_an_end(samples, largest, at.x) {
                out.push(LocalExtreme { kind, at });
            }
        }
        i = k;
    }
    Ok(out)
}

/// `x` is one of the ends of the sampled range: within a millionth of the first or last sample
/// spacing of it, where the analog is zero but for its rounding (at most [`END_ROUNDING`] of the
/// samples' `largest` in magnitude). Both: a root located within that distance of an end whose analog is not
/// that small is an extreme of its own (a range starting 1e-7 rad before a slider's dead centre,
/// sampled 1.6 rad apart, lost its maximum to the position test alone).
fn at_an_end(samples: &[Jet], largest: f64, x: f64) -> bool {
    let n = samples.len();
    if n < 2 {
        return true;
    }
    let (first, last) = (samples[0], samples[n - 1]);
    let flat = |j: Jet| j.d1.abs() <= END_ROUNDING * largest;
    ((x - first.x).abs() <= 1e-6 * (samples[1].x - first.x) && flat(first))
        || ((last.x - x).abs() <= 1e-6 * (last.x - samples[n - 2].x) && flat(last))
}

/// The largest analog at an end of a sampled range, against the samples' largest, that counts as
/// zero but for rounding (about 1e-16 of the terms it is computed from; a thousand-fold margin
/// twice over): an extreme located there is the end itself, not one inside the range.
const END_ROUNDING: f64 = 1e-9;

/// The global minimum and maximum of a sampled quantity over its range, with its located local
/// extremes: the smallest and largest of the interior extremes and the two ends of the range.
#[derive(Clone, Debug, PartialEq)]
pub struct GlobalRange {
    /// Where the quantity is smallest (an interior extreme or an end of the range).
    pub min: Jet,
    /// Where the quantity is largest.
    pub max: Jet,
    /// All interior local extremes, in increasing `x`.
    pub extremes: Vec<LocalExtreme>,
}

impl GlobalRange {
    /// `max - min`: the stroke of a slider, the swing of a rocker.
    pub fn span(&self) -> f64 {
        self.max.value - self.min.value
    }
}

/// The global range of a sampled quantity: the smallest and largest of [`extremes`] and of the
/// samples themselves (the ends of the range among them). The samples count too: where the
/// analogs are exactly zero on every sample of a stretch (a dwell met only by samples), or jump
/// (a kink), no sign change marks an extreme that a sample shows.
pub fn global_range(samples: &[Jet], eval: impl FnMut(f64) -> Result<Jet, Error>) -> Result<GlobalRange, Error> {
    global_range_across(samples, &[], eval)
}

/// [`global_range`] with `corners` between samples (see [`extremes_across`]): the values at the
/// corners are candidates too.
pub(crate) fn global_range_across(
    samples: &[Jet],
    corners: &[Corner],
    eval: impl FnMut(f64) -> Result<Jet, Error>,
) -> Result<GlobalRange, Error> {
    let found = extremes_across(samples, corners, eval)?;
    Ok(range_with(found, samples, corners))
}

/// The global range of a quantity with its interior extremes `found`: the smallest and largest
/// of them, of the samples and of the values at the `corners`.
pub(crate) fn range_with(found: Vec<LocalExtreme>, samples: &[Jet], corners: &[Corner]) -> GlobalRange {
    let first = samples[0];
    let candidates = found.iter().map(|e| e.at).chain(samples.iter().copied()).chain(corners.iter().map(|c| c.at));
    let mut min = first;
    let mut max = first;
    for c in candidates {
        if c.value < min.value {
            min = c;
        }
        if c.value > max.value {
            max = c;
        }
    }
    GlobalRange { min, max, extremes: found }
}

pub(crate) fn check_increasing(samples: &[Jet]) -> Result<(), Error> {
    if samples.len() < 2 {
        return Err(Error::InvalidArgument("at least two samples are needed".into()));
    }
    if let Some(w) = samples.windows(2).find(|w| w[1].x.partial_cmp(&w[0].x) != Some(std::cmp::Ordering::Greater)) {
        return Err(Error::InvalidArgument(format!(
            "samples must be in strictly increasing x (found {} then {})",
            w[0].x, w[1].x
        )));
    }
    if let Some(j) = samples.iter().find(|j| !(j.value.is_finite() && j.d1.is_finite() && j.d2.is_finite())) {
        return Err(Error::InvalidArgument(format!("non-finite sample at x = {}", j.x)));
    }
    Ok(())
}

/// The maximum of `f` on `[a, b]` by Brent's derivative-free method (golden-section search with
/// parabolic interpolation), to a location tolerance of `sqrt(eps)` of `|x|` or of the width
/// `b - a`, whichever is smaller (the best possible for a smooth maximum varying over the
/// interval's width: the value is then exact to rounding, wherever the interval lies). Returns `(x, f(x))`. For a
/// unimodal `f` on the interval this is the maximum; otherwise a local one. Use it to locate the
/// peak of a quantity whose derivative is not available, starting from the best sample and its
/// neighbours.
///
/// Errors (`InvalidArgument`): not `a < b`, or a width `b - a` not finite; a value of `f` not
/// finite at any point tried; and those of `f`.
///
/// ```
/// use kinloop_runtime::analysis::extremes::maximize;
/// let (x, v) = maximize(0.0, 3.0, |x| Ok(x * (2.0 - x)))?;
/// assert!((x - 1.0).abs() < 1e-7 && (v - 1.0).abs() < 1e-14);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn maximize(a: f64, b: f64, mut f: impl FnMut(f64) -> Result<f64, Error>) -> Result<(f64, f64), Error> {
    // (A width beyond f64, `-1e308` to `1e308`, put the first trial point at infinity.)
    if !(a < b && (b - a).is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "maximize needs a finite interval a < b of finite width, got [{a}, {b}]"
        )));
    }
    // Brent's `fmin` on g = -f (R. P. Brent, Algorithms for Minimization without Derivatives,
    // 1973, ch. 5).
    let golden = 0.5 * (3.0 - 5f64.sqrt());
    let tol = f64::EPSILON.sqrt();
    // The location tolerance is relative to `|x|`, as Brent's, but never to more than the
    // interval's width: a maximum's value tells its location apart only to about `sqrt(eps)`
    // of the scale over which `f` varies, which the width of a bracket around it tells and the
    // distance of the interval from 0 does not (the same peak 1e6 widths from 0 was located
    // to 5e-4 of its width, its value to 1e-7). Two units of rounding of `x` keep each trial
    // point apart from `x`.
    let width = b - a;
    let (mut a, mut b) = (a, b);
    let mut x = a + golden * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = -f(x)?;
    // Every value is checked, the first too: a NaN there, never replaced (no comparison with it
    // holds), was returned as the maximum.
    if !fx.is_finite() {
        return Err(Error::InvalidArgument(format!("maximize: non-finite value at x = {x}")));
    }
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        let tol1 =
            tol * x.abs().min(width) + 2.0 * f64::EPSILON * x.abs() + 1e-12 * (b - a).abs().max(f64::MIN_POSITIVE);
        let tol2 = 2.0 * tol1;
        if (x - m).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden_step = true;
        if e.abs() > tol1 {
            // Parabola through (v, fv), (w, fw), (x, fx).
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            if p.abs() < (0.5 * q * e).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = if x < m { tol1 } else { -tol1 };
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x < m { b - x } else { a - x };
            d = golden * e;
        }
        let u = if d.abs() >= tol1 { x + d } else { x + tol1.copysign(d) };
        let fu = -f(u)?;
        if !fu.is_finite() {
            return Err(Error::InvalidArgument(format!("maximize: non-finite value at x = {u}")));
        }
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    Ok((x, -fx))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn poly(x: f64) -> Result<Jet, Error> {
        // (x - 1)(x - 2)(x - 4) = x^3 - 7x^2 + 14x - 8: v' = 3x^2 - 14x + 14.
        Ok(Jet {
            x,
            value: x * x * x - 7.0 * x * x + 14.0 * x - 8.0,
            d1: 3.0 * x * x - 14.0 * x + 14.0,
            d2: 6.0 * x - 14.0,
        })
    }

    fn grid(f: impl Fn(f64) -> Result<Jet, Error>, a: f64, b: f64, n: usize) -> Vec<Jet> {
        (0..=n).map(|i| f(a + (b - a) * i as f64 / n as f64).unwrap()).collect()
    }

    /// A bracket whose width overflows is refused: its tolerances, relative to the width, took
    /// the end `-1e308` for the root of `x` at 0.
    #[test]
    fn a_bracket_of_infinite_width_is_an_error() {
        let line = |x: f64| Ok(Jet { x, value: x, d1: 1.0, d2: 0.0 });
        let r = bracketed_root(line(-1e308).unwrap(), line(1e308).unwrap(), |j| (j.value, j.d1), line);
        assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("finite width")), "{r:?}");
        let root = bracketed_root(line(-1e307).unwrap(), line(1e307).unwrap(), |j| (j.value, j.d1), line).unwrap();
        assert_eq!(root.x, 0.0);
    }

    /// An interval whose width overflows is refused as such; its first trial point was at
    /// infinity and the error said `f` was not finite at NaN.
    #[test]
    fn an_interval_of_infinite_width_is_an_error() {
        let r = maximize(-1e308, 1e308, |x| Ok(-(x / 1e300).powi(2)));
        assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("finite width")), "{r:?}");
        let (x, v) = maximize(-1e307, 1e307, |x| Ok(-(x / 1e300).powi(2))).unwrap();
        assert!(x.abs() < 1e300 && v > -1.0, "{x} {v}");
    }

    #[test]
    fn extremes_of_a_cubic_are_the_roots_of_its_derivative() {
        let s = grid(poly, 0.0, 5.0, 13);
        let e = extremes(&s, poly).unwrap();
        assert_eq!(e.len(), 2);
        let r = 7f64.sqrt();
        let (x_max, x_min) = ((7.0 - r) / 3.0, (7.0 + r) / 3.0);
        assert_eq!(e[0].kind, Extreme::Max);
        assert_eq!(e[1].kind, Extreme::Min);
        assert!((e[0].x() - x_max).abs() < 1e-14, "{}", e[0].x());
        assert!((e[1].x() - x_min).abs() < 1e-14);
        assert!((e[0].value() - poly(x_max).unwrap().value).abs() < 1e-14);
        let g = global_range(&s, poly).unwrap();
        // On [0, 5] the ends win: v(0) = -8, v(5) = 12.
        assert_eq!(g.min.x, 0.0);
        assert_eq!(g.max.x, 5.0);
        assert_eq!(g.span(), 20.0);
        assert_eq!(g.extremes.len(), 2);
    }

    #[test]
    fn root_exactly_at_a_sample_is_found_once() {
        // cos x on a grid containing pi exactly: one minimum at pi.
        let f = |x: f64| Ok(Jet { x, value: x.cos(), d1: -x.sin(), d2: -x.cos() });
        let s: Vec<Jet> = [0.5, 1.5, 2.5, PI, 3.5, 4.5].iter().map(|&x| f(x).unwrap()).collect();
        // Force an exact zero at the sample at pi.
        let mut s = s;
        s[3].d1 = 0.0;
        let e = extremes(&s, f).unwrap();
        assert_eq!(e.len(), 1, "{e:?}");
        assert_eq!(e[0].kind, Extreme::Min);
        assert!((e[0].x() - PI).abs() < 1e-15);
    }

    #[test]
    fn a_stationary_inflection_is_not_an_extreme() {
        // x^3 has v' = 0 at 0 without a sign change.
        let f = |x: f64| Ok(Jet { x, value: x * x * x, d1: 3.0 * x * x, d2: 6.0 * x });
        let s = grid(f, -1.0, 1.0, 10);
        assert!(extremes(&s, f).unwrap().is_empty());
    }

    /// A rise-dwell-return-dwell law sampled only on its dwells (every analog exactly zero):
    /// the top dwell's sample is the maximum, though no analog changes sign around it.
    #[test]
    fn a_dwell_between_samples_of_zero_analog_is_in_the_range() {
        let dwell = |x: f64, value: f64| Jet { x, value, d1: 0.0, d2: 0.0 };
        let s = [dwell(0.0, 60.0), dwell(PI, 80.0), dwell(2.0 * PI, 60.0)];
        let r = global_range(&s, |x| Ok(dwell(x, f64::NAN))).unwrap();
        assert_eq!((r.min.value, r.max.value, r.max.x), (60.0, 80.0, PI));
        // A sample above every located extreme and both ends, the analogs of its neighbours of
        // one sign (a peak between samples the analogs miss, as a kink makes).
        let s = [
            dwell(0.0, 0.0),
            Jet { x: 1.0, value: 5.0, d1: 1.0, d2: 0.0 },
            Jet { x: 2.0, value: 1.0, d1: 1.0, d2: 0.0 },
        ];
        let r = global_range(&s, |x| Ok(dwell(x, f64::NAN))).unwrap();
        assert_eq!(r.max.value, 5.0);
    }

    #[test]
    fn newton_converges_in_few_evaluations() {
        let mut calls = 0;
        let f = |x: f64| Ok(Jet { x, value: x.sin(), d1: x.cos(), d2: -x.sin() });
        let s = grid(f, 0.0, 2.0 * PI, 36);
        let e = extremes(&s, |x| {
            calls += 1;
            f(x)
        })
        .unwrap();
        assert_eq!(e.len(), 2);
        assert!((e[0].x() - PI / 2.0).abs() < 1e-15 && (e[1].x() - 1.5 * PI).abs() < 2e-15, "{e:?}");
        assert!(calls <= 12, "{calls} evaluations for two roots");
    }

    #[test]
    fn bracketed_root_survives_a_bad_derivative() {
        // A wrong derivative sends Newton astray; the bisection safeguard still converges.
        let f = |x: f64| Ok(Jet { x, value: x * x - 2.0, d1: 1e-3, d2: 0.0 });
        let r = bracketed_root(f(0.0).unwrap(), f(3.0).unwrap(), |j| (j.value, j.d1), f).unwrap();
        assert!((r.x - 2f64.sqrt()).abs() < 1e-14, "{}", r.x);
        // Without a sign change it is an error, not a wrong answer.
        assert!(bracketed_root(f(2.0).unwrap(), f(3.0).unwrap(), |j| (j.value, j.d1), f).is_err());
    }

    #[test]
    fn bad_samples_are_errors() {
        let s = vec![poly(1.0).unwrap(), poly(0.5).unwrap()];
        assert!(extremes(&s, poly).is_err());
        assert!(extremes(&s[..1], poly).is_err());
    }

    /// A value not finite at the first point tried is an error, as at any other: it was
    /// returned as the maximum, `Ok((0.38, NaN))`, of a parabola NaN at that point alone.
    #[test]
    fn maximize_refuses_a_first_value_not_finite() {
        let first = 0.5 * (3.0 - 5f64.sqrt());
        for bad in [f64::NAN, f64::INFINITY] {
            let r = maximize(0.0, 1.0, |x| Ok(if x == first { bad } else { x * (1.0 - x) }));
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("non-finite")), "{bad}: {r:?}");
        }
    }

    #[test]
    fn maximize_finds_the_peak_of_a_smooth_function() {
        let (x, v) = maximize(0.0, 2.0, |x| Ok((3.0 * x).sin() * (-x).exp())).unwrap();
        // d/dx = e^-x (3 cos 3x - sin 3x) = 0 -> tan 3x = 3.
        let xs = 3f64.atan() / 3.0;
        assert!((x - xs).abs() < 1e-7, "{x} vs {xs}");
        assert!((v - (3.0 * xs).sin() * (-xs).exp()).abs() < 1e-14);
        assert!(maximize(1.0, 1.0, Ok).is_err());
        // A maximum at the end of the interval is approached to within the tolerance.
        let (x, _) = maximize(0.0, 1.0, Ok).unwrap();
        assert!(x > 1.0 - 1e-7);
    }

    /// A peak is located to `sqrt(eps)` of the interval's width wherever the interval lies: the
    /// tolerance, relative to `|x|` alone, located `cos((x - c) / w)` on `[c - 1.3 w, c + 1.7 w]`
    /// with `c` 1e6 widths from 0 to 4.7e-4 of its width, its value 1 to 1.1e-7 (100 widths
    /// from 0: to 5.4e-7 and 1.5e-13), in any unit.
    #[test]
    fn maximize_locates_a_peak_far_from_zero_as_near_it() {
        for offset in [0.0, 1e2, 1e4, 1e6, 1e8] {
            for w in [1e-6, 1.0, 1e6] {
                let c = (offset + 0.3) * w;
                let (x, v) = maximize(c - 1.3 * w, c + 1.7 * w, |x| Ok(((x - c) / w).cos())).unwrap();
                // Brent's bracket closes to about 2 sqrt(eps) (3.3e-8) of the width 3 w, and the
                // value's error is half the square of the location's, below rounding.
                assert!(((x - c) / w).abs() < 1e-7, "offset {offset:e}, w {w:e}: x = {x}, c = {c}");
                assert!(1.0 - v < 1e-14, "offset {offset:e}, w {w:e}: 1 - v = {:e}", 1.0 - v);
            }
        }
    }
}
