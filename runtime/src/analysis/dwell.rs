//! Dwells (stops) of a progressive output: an output that advances overall (a rocker turning on
//! average, an indexing table) but swings back briefly, or nearly stops, during each stop.
//!
//! **Definition.** Let the output `v(x)` advance overall in the direction `s` (the sign of
//! `v(end) - v(start)`). A *reversal* is a pair of consecutive local extremes `v(x1) = v1`,
//! `v(x2) = v2` (`x1 < x2`) where the output moves against `s`: a maximum followed by a
//! minimum for an increasing output (a minimum followed by a maximum for a decreasing one). Its
//! *swing* is `|v1 - v2|`, and the band `[min(v1, v2), max(v1, v2)]` is the swing of the
//! reversal. The **dwell** is the input interval `[x_in, x_out]` during which the output stays
//! within that band: it enters the band at `x_in < x1` (where `v(x_in) = v2`, the band edge
//! opposite to where the reversal starts) and leaves it at `x_out > x2` (where
//! `v(x_out) = v1`). Its **duration** is `x_out - x_in` (in input units, e.g. carrier angle),
//! and its **quality** the swing: the smaller, the better the output stands still.
//!
//! All four points are located precisely: `x1`, `x2` as roots of the velocity analog (see
//! [`extremes`](super::extremes::extremes)), `x_in`, `x_out` as roots of `v - level` by a
//! safeguarded Newton iteration using the velocity analog. Between consecutive extremes the
//! output is monotonic, so each crossing is unique.
//!
//! A dwell is reported only when it lies entirely within the sampled range and its band is not
//! re-entered from a neighbouring reversal (overlapping dwells): sweep a little more than one
//! cycle, or start the sweep where the output moves, to see every dwell of a cycle. An output
//! that comes to rest without reversing (a velocity analog touching zero) has a dwell of zero
//! swing in the limit; it is not reported by this definition.

use super::Jet;
use super::extremes::{Corner, Extreme, LocalExtreme, bracketed_root, check_increasing, extremes_across};
use crate::error::Error;

/// A dwell of a progressive output; see the [module documentation](self) for the definition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dwell {
    /// Where the output enters the band of the reversal.
    pub start: Jet,
    /// The extreme where the output starts to move backwards.
    pub first: LocalExtreme,
    /// The extreme where it moves forwards again.
    pub second: LocalExtreme,
    /// Where the output leaves the band.
    pub end: Jet,
}

impl Dwell {
    /// Duration in input units: `end.x - start.x`.
    pub fn duration(&self) -> f64 {
        self.end.x - self.start.x
    }

    /// Swing of the output during the dwell (the dwell quality): `|first - second|`.
    pub fn swing(&self) -> f64 {
        (self.first.value() - self.second.value()).abs()
    }
}

/// The largest net travel, relative to the output's range over the samples, that counts as none:
/// far above the rounding of an output that returns to where it started (a few units in the
/// last place of its values), far below the travel of any progressive output.
pub const NO_TRAVEL: f64 = 1e-9;

/// All dwells of a progressive output sampled at `samples` (jets in increasing `x`; `eval`
/// computes the jet at any `x` of the range). See the [module documentation](self). An output
/// whose net travel over the samples is at most [`NO_TRAVEL`] of its range (an oscillating one)
/// is an [`Error::InvalidArgument`].
///
/// ```
/// use kinloop_runtime::analysis::{Jet, dwell::dwells};
/// // v = x^3 - 3x on [-3, 3] rises overall, with a reversal from the maximum v(-1) = 2 to the
/// // minimum v(1) = -2. It enters the band [-2, 2] at x = -2 (v = -2) and leaves it at x = 2.
/// let f = |x: f64| Ok(Jet { x, value: x * x * x - 3.0 * x, d1: 3.0 * x * x - 3.0, d2: 6.0 * x });
/// let samples: Vec<Jet> = (0..=60).map(|i| f(-3.0 + 0.1 * i as f64)).collect::<Result<_, _>>()?;
/// let d = dwells(&samples, f)?;
/// assert_eq!(d.len(), 1);
/// assert!((d[0].start.x + 2.0).abs() < 1e-12 && (d[0].end.x - 2.0).abs() < 1e-12);
/// assert!((d[0].duration() - 4.0).abs() < 1e-12 && (d[0].swing() - 4.0).abs() < 1e-12);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn dwells(samples: &[Jet], eval: impl FnMut(f64) -> Result<Jet, Error>) -> Result<Vec<Dwell>, Error> {
    dwells_across(samples, &[], eval, 0.0)
}

/// [`dwells`] with `corners` between samples, where the output cannot be evaluated nearby (the
/// singular crossings of a sampled range): its extremes found as
/// [`extremes_across`](super::extremes::extremes_across) finds them, an extreme at a crossing
/// taken there. A net travel of at most `still` is none too, whatever the range (the rounding
/// of an output that stands still, whose range is rounding as well).
pub(crate) fn dwells_across(
    samples: &[Jet],
    corners: &[Corner],
    mut eval: impl FnMut(f64) -> Result<Jet, Error>,
    still: f64,
) -> Result<Vec<Dwell>, Error> {
    check_increasing(samples)?;
    let (first, last) = (samples[0], samples[samples.len() - 1]);
    let travel = last.value - first.value;
    // Against the output's range over the samples: an oscillating output sampled over whole
    // cycles ends where it started up to the rounding of its values, a travel whose sign (and so
    // which extreme starts a reversal) the units decide (a crank-rocker's rocker over two turns:
    // exactly 0 in metres, 4.4e-16 in inches, where a dwell of half a turn was reported).
    let (lo, hi) =
        samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), j| (lo.min(j.value), hi.max(j.value)));
    if travel.abs() <= (NO_TRAVEL * (hi - lo)).max(still) {
        return Err(Error::InvalidArgument(format!(
            "dwells are defined for a progressive output: the output has no net travel over the range (it moves by \
             {travel:e} from start to end, over a range of {:e})",
            hi - lo
        )));
    }
    // A reversal starts at a maximum for an increasing output, at a minimum for a decreasing one.
    let starts_reversal = if travel > 0.0 { Extreme::Max } else { Extreme::Min };
    let ext = extremes_across(samples, corners, &mut eval)?;
    let mut out = Vec::new();
    for i in 0..ext.len().saturating_sub(1) {
        let (e1, e2) = (ext[i], ext[i + 1]);
        if e1.kind != starts_reversal {
            continue;
        }
        // Monotonic stretch before e1 (from the previous extreme or the start of the range) and
        // after e2 (to the next extreme or the end of the range).
        let before = if i > 0 { ext[i - 1].at } else { first };
        let after = if i + 2 < ext.len() { ext[i + 2].at } else { last };
        let Some(start) = crossing(samples, before, e1.at, e2.value(), &mut eval)? else { continue };
        let Some(end) = crossing(samples, e2.at, after, e1.value(), &mut eval)? else { continue };
        // The band is not visited before the output enters it, nor after it leaves: a
        // neighbouring reversal whose swing reaches into it (bands overlapping, as they do where
        // the swing exceeds the advance per cycle) re-enters it, and no dwell is reported (the
        // stretches beside the extremes alone were looked at: overlapping dwells were reported).
        let s = travel.signum();
        let earlier = ext[..i].iter().map(LocalExtreme::value).chain([first.value]);
        let later = ext[i + 2..].iter().map(LocalExtreme::value).chain([last.value]);
        if earlier.into_iter().any(|v| s * (v - e2.value()) >= 0.0)
            || later.into_iter().any(|v| s * (v - e1.value()) <= 0.0)
        {
            continue;
        }
        out.push(Dwell { start, first: e1, second: e2, end });
    }
    Ok(out)
}

/// The point where a quantity, monotonic between the jets `from` and `to`, crosses `level`;
/// `None` when it does not cross it there.
fn crossing(
    samples: &[Jet],
    from: Jet,
    to: Jet,
    level: f64,
    eval: &mut impl FnMut(f64) -> Result<Jet, Error>,
) -> Result<Option<Jet>, Error> {
    let above = |j: &Jet| j.value >= level;
    if above(&from) == above(&to) {
        return Ok(None);
    }
    // The knots of the stretch: its ends and the samples strictly inside.
    let inner = samples.iter().copied().filter(|j| j.x > from.x && j.x < to.x);
    let knots: Vec<Jet> = std::iter::once(from).chain(inner).chain(std::iter::once(to)).collect();
    for w in knots.windows(2) {
        if above(&w[0]) != above(&w[1]) {
            let root = bracketed_root(w[0], w[1], |j| (j.value - level, j.d1), &mut *eval)?;
            return Ok(Some(root));
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    fn grid(f: impl Fn(f64) -> Result<Jet, Error>, a: f64, b: f64, n: usize) -> Vec<Jet> {
        (0..=n).map(|i| f(a + (b - a) * i as f64 / n as f64).unwrap()).collect()
    }

    #[test]
    fn cubic_has_one_dwell_with_exact_ends() {
        // x^3 - 3x: reversal from v(-1) = 2 to v(1) = -2; (x + 2)(x - 1)^2 = x^3 - 3x + 2 and
        // (x - 2)(x + 1)^2 = x^3 - 3x - 2 give the band crossings x = -2 and x = 2 exactly.
        let f = |x: f64| Ok(Jet { x, value: x * x * x - 3.0 * x, d1: 3.0 * x * x - 3.0, d2: 6.0 * x });
        let d = dwells(&grid(f, -3.0, 3.0, 17), f).unwrap();
        assert_eq!(d.len(), 1);
        let d = d[0];
        assert!((d.start.x + 2.0).abs() < 1e-14, "{}", d.start.x);
        assert!((d.end.x - 2.0).abs() < 1e-14, "{}", d.end.x);
        assert!((d.first.x() + 1.0).abs() < 1e-14 && (d.second.x() - 1.0).abs() < 1e-14);
        assert!((d.swing() - 4.0).abs() < 1e-14 && (d.duration() - 4.0).abs() < 1e-14);
        // The decreasing mirror image has the same dwell.
        let g = |x: f64| f(x).map(|j| Jet { x, value: -j.value, d1: -j.d1, d2: -j.d2 });
        let e = dwells(&grid(g, -3.0, 3.0, 17), g).unwrap();
        assert_eq!(e.len(), 1);
        assert!((e[0].duration() - 4.0).abs() < 1e-14 && e[0].first.kind == Extreme::Min);
    }

    /// v = x + a sin x (a > 1): an increasing output with one reversal per period, symmetric
    /// about x = pi (mod 2 pi): v(pi + t) - pi = t - a sin t is odd in t.
    fn trochoid(a: f64) -> impl Fn(f64) -> Result<Jet, Error> + Copy {
        move |x: f64| Ok(Jet { x, value: x + a * x.sin(), d1: 1.0 + a * x.cos(), d2: -a * x.sin() })
    }

    #[test]
    fn trochoid_dwells_are_symmetric_with_the_closed_form_swing() {
        let a = 1.5;
        let f = trochoid(a);
        // Two periods starting where the output moves forward fastest: two whole dwells.
        let d = dwells(&grid(f, 0.0, 4.0 * PI, 200), f).unwrap();
        assert_eq!(d.len(), 2, "{d:?}");
        // Extremes where cos x = -1/a: x1 = pi - t*, x2 = pi + t*, t* = acos(1/a).
        let ts = (1.0 / a).acos();
        let swing = 2.0 * (a * ts.sin() - ts);
        for (k, d) in d.iter().enumerate() {
            let c = PI + 2.0 * PI * k as f64;
            assert!((d.first.x() - (c - ts)).abs() < 1e-13 && (d.second.x() - (c + ts)).abs() < 1e-13);
            assert!((d.swing() - swing).abs() < 1e-13, "{} vs {swing}", d.swing());
            // Symmetric about the centre, and the ends lie on the band edges.
            assert!(((d.start.x + d.end.x) / 2.0 - c).abs() < 1e-13);
            assert!((d.start.value - d.second.value()).abs() < 1e-13);
            assert!((d.end.value - d.first.value()).abs() < 1e-13);
            // The band edge is crossed where t - a sin t = -(swing / 2) with t = x - c, i.e.
            // t_out solves t - a sin t = a sin t* - t*; check that independently by bisection.
            let g = |t: f64| t - a * t.sin() - (a * ts.sin() - ts);
            let (mut lo, mut hi) = (ts, PI);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if g(mid) < 0.0 { lo = mid } else { hi = mid }
            }
            assert!((d.end.x - c - lo).abs() < 1e-13, "{} vs {}", d.end.x - c, lo);
        }
    }

    /// `v = x + a sin 3x`: a reversal every third of a turn, from the maximum where
    /// `3x = acos(-1 / (3a))` to the minimum where `3x = 2 pi - acos(-1 / (3a))`. Where its swing
    /// exceeds the advance per reversal, `2 pi / 3`, each band overlaps its neighbours': the
    /// output re-enters it from them, and by the definition no dwell is reported. At `a = 2`
    /// four were, each running into the next (the first from 2.03 to 4.25, the second from
    /// 4.12); at `a = 1` the bands are apart and every whole reversal is a dwell.
    #[test]
    fn bands_re_entered_from_a_neighbouring_reversal_are_no_dwells() {
        for (a, dwells_expected) in [(1.0f64, 6), (2.0, 0)] {
            let t = (-1.0 / (3.0 * a)).acos();
            let v = |x: f64| x + a * (3.0 * x).sin();
            let swing = v(t / 3.0) - v((TAU - t) / 3.0);
            assert_eq!(swing > TAU / 3.0, dwells_expected == 0, "a = {a}: swing {swing}");
            let f = move |x: f64| {
                Ok(Jet { x, value: v(x), d1: 1.0 + 3.0 * a * (3.0 * x).cos(), d2: -9.0 * a * (3.0 * x).sin() })
            };
            let d = dwells(&grid(f, 0.0, 4.0 * PI, 400), f).unwrap();
            assert_eq!(d.len(), dwells_expected, "a = {a}: {d:?}");
            for w in d.windows(2) {
                assert!(w[0].end.x < w[1].start.x, "a = {a}: {w:?}");
            }
            for d in &d {
                assert!((d.swing() - swing).abs() < 1e-13, "a = {a}: {d:?}");
            }
        }
    }

    #[test]
    fn a_dwell_cut_by_the_range_is_not_reported() {
        // Starting inside the first band: only the second dwell is whole.
        let f = trochoid(1.5);
        let d = dwells(&grid(f, 2.5, 4.0 * PI, 200), f).unwrap();
        assert_eq!(d.len(), 1);
        assert!((d[0].first.x() - (3.0 * PI - (1.0f64 / 1.5).acos())).abs() < 1e-12);
    }

    #[test]
    fn no_reversal_no_dwell_and_no_travel_is_an_error() {
        let f = trochoid(0.5);
        assert!(dwells(&grid(f, 0.0, 4.0 * PI, 100), f).unwrap().is_empty());
        let c = |x: f64| Ok(Jet { x, value: x.cos(), d1: -x.sin(), d2: -x.cos() });
        assert!(matches!(dwells(&grid(c, 0.0, 2.0 * PI, 100), c), Err(Error::InvalidArgument(_))));
    }
    /// An oscillation sampled over whole cycles ends where it started up to rounding: no net
    /// travel, whichever sign the rounding gives it (the units decide it), never a dwell.
    #[test]
    fn an_oscillation_has_no_travel_whatever_its_rounding() {
        let f = |x: f64| Ok(Jet { x, value: x.sin(), d1: x.cos(), d2: -x.sin() });
        for end in [2.0 * PI, 4.0 * PI, 6.0 * PI] {
            let samples = grid(f, 0.0, end, 73);
            let travel = samples[73].value - samples[0].value;
            assert!(travel != 0.0, "the test needs a rounding travel: {travel:e}");
            let e = dwells(&samples, f).unwrap_err();
            assert!(e.to_string().contains("no net travel"), "{e}");
        }
        // A progressive output is one however small its travel beside its swing, down to a
        // millionth: not refused. (Its reversals, each swinging over nearly all of its range,
        // re-enter each other's bands: none is a dwell.)
        let g = |x: f64| Ok(Jet { x, value: 1e-6 * x + x.sin(), d1: 1e-6 + x.cos(), d2: -x.sin() });
        assert_eq!(dwells(&grid(g, 0.0, 6.0 * PI, 145), g).unwrap(), []);
    }
}
