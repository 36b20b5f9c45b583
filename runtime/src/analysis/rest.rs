//! Rests of an output: the stretches of the input over which it stands exactly still, as the
//! follower of a cam law with dwells does (its segments clamped, its velocity analog exactly
//! zero between them), or a motion declared piecewise.
//!
//! **Definition.** A *rest* is a stretch `[start, end]` of the input, of positive length, over
//! which the output's velocity analog is exactly zero and its value the same (to the rounding
//! of the output's values: [`SAME_VALUE`] of the largest among the samples). A law that jumps
//! (a `floor`, a segment of no length) from one value to another with its velocity zero on
//! both sides leaves two rests, one each side of the jump, located to the doubles as a rest's
//! end is. This is not the [dwell](super::dwell) of
//! a progressive output, which swings back within a band: an output that comes to rest without
//! reversing has no dwell by that definition, and an oscillating output (a cam follower that
//! rises, dwells, returns and dwells) has no net travel to define one. A velocity analog that
//! only touches zero (an extreme, a limit of the output) is an instant, not a rest. A column of
//! a sampled run that stands still over the whole range to its rounding (zero in exact
//! arithmetic, its analog exactly zero over some stretches only) is one rest, the range, as
//! `SampledOf::rests` judges it before looking for these.
//!
//! **Location.** Two or more consecutive samples at rest, with the midpoint between each two at
//! rest too, mark a rest; each end between a sample at rest and a moving input is found by
//! bisection on "at rest" to the spacing of the doubles of the input there, so the ends of a
//! clamped law's segments come out where the law switches, to its rounding. A single sample at
//! rest is not a rest: where a velocity analog only touches or crosses zero, its rounding can
//! leave it exactly zero over a few units in the last place (or, where it touches zero, over
//! about `sqrt(eps)` of the input), an instant that two samples cannot both fall in. So a rest
//! is seen where it holds two samples: sample more finely than half the shortest rest. A rest
//! reaching an end of the sampled range is cut there (it may go on beyond it): start the range
//! where the output moves to see every rest of a cycle whole.
//!
//! Exact zeros are what a law with clamped segments gives: the derivative of a clamp at its
//! bound is zero, and every analog computed from zero velocities alone (a linkage the output
//! drives, its points and angles) is exactly zero too, in any unit. Where a law leaves a rest
//! smoothly (a 3-4-5 law's velocity vanishes as the square of the distance from its switch),
//! its computed velocity rounds to zero a little before the switch, where the output moves by
//! far less than the rounding of its value: the end is located there (for the 3-4-5 law within
//! about `sqrt(eps / 10)` of the segment's length, 1e-8 rad of a rise over 120 degrees).

use super::Jet;
use super::extremes::{Corner, check_increasing};
use crate::error::Error;

/// A rest of an output: where it stands exactly still; see the [module documentation](self).
/// Its jets' `x` are the input, or along a path through several inputs the path's parameter
/// (`SampledOf::inputs_at` gives the inputs there), as the samples' are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rest {
    /// The first input at rest (the start of the sampled range where the rest reaches it).
    pub start: Jet,
    /// The last input at rest (the end of the sampled range where the rest reaches it).
    pub end: Jet,
}

impl Rest {
    /// Duration in input units: `end.x - start.x`.
    pub fn duration(&self) -> f64 {
        self.end.x - self.start.x
    }

    /// Where the output stands during the rest (its value at the start).
    pub fn value(&self) -> f64 {
        self.start.value
    }
}

/// Whether the output stands still at `j`: its velocity analog exactly zero (either sign).
fn at_rest(j: &Jet) -> bool {
    j.d1 == 0.0
}

/// The difference, relative to the largest magnitude of the output's values over the samples,
/// within which two values at rest are one rest's: a rest's values are exact repeats where a
/// closed form or a clamped law gives them, and a Newton block's within its rounding, far below
/// this; a jump of the law, far above.
pub const SAME_VALUE: f64 = 1e-12;

/// A rest under way: the value it stands at, and the difference within which a value is the
/// same ([`SAME_VALUE`] of the output's scale).
#[derive(Clone, Copy)]
struct Still {
    value: f64,
    tol: f64,
}

impl Still {
    /// Whether `j` is in this rest: at rest, at its value.
    fn holds(&self, j: &Jet) -> bool {
        at_rest(j) && (j.value - self.value).abs() <= self.tol
    }
}

/// All rests of an output sampled at `samples` (jets in increasing `x`; `eval` computes the
/// jet at any `x` of the range, for the ends between samples). See the
/// [module documentation](self).
///
/// ```
/// use kinloop_runtime::analysis::{Jet, rest::rests};
/// // Still up to x = 1, rising as (x - 1)^3 to 1 at x = 2, still up to x = 3, then falling.
/// let f = |x: f64| {
///     let (value, d1) = match x {
///         x if x < 1.0 => (0.0, 0.0),
///         x if x < 2.0 => ((x - 1.0).powi(3), 3.0 * (x - 1.0).powi(2)),
///         x if x < 3.0 => (1.0, 0.0),
///         x => (1.0 - (x - 3.0).powi(3), -3.0 * (x - 3.0).powi(2)),
///     };
///     Ok(Jet { x, value, d1, d2: 0.0 })
/// };
/// let samples: Vec<Jet> = (0..=12).map(|i| f(0.5 + 0.3 * i as f64)).collect::<Result<_, _>>()?;
/// let r = rests(&samples, f)?;
/// assert_eq!(r.len(), 2);
/// assert_eq!((r[0].start.x, r[0].end.x), (0.5, 1.0)); // cut at the start of the range
/// assert_eq!((r[1].start.x, r[1].end.x, r[1].value()), (2.0, 3.0, 1.0));
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
///
/// Errors: fewer than two samples, samples not in strictly increasing `x` or not finite, and
/// `eval`'s.
pub fn rests(samples: &[Jet], eval: impl FnMut(f64) -> Result<Jet, Error>) -> Result<Vec<Rest>, Error> {
    rests_across(samples, &[], eval)
}

/// [`rests`] with `corners` between samples, where the output cannot be evaluated nearby (the
/// singular crossings of a sampled range, see `extremes_across`): the midpoint between the two
/// samples about a corner is the corner itself (at rest where both samples are, its analog
/// interpolated), and an end of a rest that lies between them is located there to their
/// distance (the crossing's band, about a millionth of a radian), not within it.
pub(crate) fn rests_across(
    samples: &[Jet],
    corners: &[Corner],
    mut eval: impl FnMut(f64) -> Result<Jet, Error>,
) -> Result<Vec<Rest>, Error> {
    check_increasing(samples)?;
    let gaps: Vec<(f64, f64)> = corners.iter().map(|c| (samples[c.after].x, samples[c.after + 1].x)).collect();
    let scale = samples.iter().map(|s| s.value.abs()).fold(0.0, f64::max);
    let tol = SAME_VALUE * scale;
    let n = samples.len();
    let mut out = Vec::new();
    // The nearest input known to be out of the next rest before sample `i`, moving or at rest
    // at another value (NaN: none, the start of the range).
    let mut out_before = f64::NAN;
    let mut i = 0;
    while i < n {
        if !at_rest(&samples[i]) {
            out_before = samples[i].x;
            i += 1;
            continue;
        }
        let still = Still { value: samples[i].value, tol };
        // A run of samples in one rest, `i ..= k`, each two joined by a midpoint in it too: two
        // samples where the velocity only crosses zero (a symmetric mechanism's, exactly) with
        // motion between them are no rest, nor two at rest at values a jump apart. `out_after`:
        // the nearest input known to be out of the rest after the run (NaN: none, the end of
        // the range); `next_out_before`: the same before the next run (a sample of this rest
        // where the run ends on a jump).
        let (mut k, mut out_after, mut next_out_before) = (i, f64::NAN, f64::NAN);
        while k + 1 < n {
            if !still.holds(&samples[k + 1]) {
                out_after = samples[k + 1].x;
                next_out_before = if at_rest(&samples[k + 1]) { samples[k].x } else { out_after };
                break;
            }
            let mid = match corners.iter().find(|c| c.after == k) {
                Some(c) => c.at,
                None => evaluated(0.5 * samples[k].x + 0.5 * samples[k + 1].x, &mut eval)?,
            };
            if !still.holds(&mid) {
                out_after = mid.x;
                next_out_before = if at_rest(&mid) { samples[k].x } else { out_after };
                break;
            }
            k += 1;
        }
        // One sample at rest: an instant (see the module documentation).
        if k > i {
            let start =
                if out_before.is_nan() { samples[i] } else { edge(out_before, samples[i], still, &gaps, &mut eval)? };
            let end =
                if out_after.is_nan() { samples[k] } else { edge(out_after, samples[k], still, &gaps, &mut eval)? };
            out.push(Rest { start, end });
        }
        out_before = next_out_before;
        i = k + 1;
    }
    Ok(out)
}

/// The end of the rest `still` between the input `out`, out of it (moving, or at rest at
/// another value), and the jet `inside` in it: the input in the rest nearest to `out`, by
/// bisection on "in the rest" until the two are adjacent doubles (at most about 64 halvings
/// where the two are of one sign, a few more across zero), or a midpoint falls within one of
/// the `gaps` (open intervals where nothing can be evaluated).
fn edge(
    out: f64,
    inside: Jet,
    still: Still,
    gaps: &[(f64, f64)],
    eval: &mut impl FnMut(f64) -> Result<Jet, Error>,
) -> Result<Jet, Error> {
    let (mut out, mut inside) = (out, inside);
    loop {
        // Halves of each: no overflow for ends near the largest doubles.
        let mid = 0.5 * out + 0.5 * inside.x;
        if mid == out || mid == inside.x || gaps.iter().any(|&(a, b)| mid > a && mid < b) {
            return Ok(inside);
        }
        let j = evaluated(mid, eval)?;
        if still.holds(&j) {
            inside = j;
        } else {
            out = mid;
        }
    }
}

/// The jet at `x`, an error where it is not finite.
fn evaluated(x: f64, eval: &mut impl FnMut(f64) -> Result<Jet, Error>) -> Result<Jet, Error> {
    let j = eval(x)?;
    if !(j.value.is_finite() && j.d1.is_finite()) {
        return Err(Error::InvalidArgument(format!("non-finite value at x = {x} while locating a rest")));
    }
    Ok(j)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Still on `[1, 2]` and `[3, 3.5]`, moving as a cubic between, a velocity analog touching
    /// zero at 2.5 (an inflection at rest for an instant) and at the sample 4.
    fn jet(x: f64) -> Result<Jet, Error> {
        let (value, d1) = match x {
            x if x < 1.0 => (-(1.0 - x).powi(3), 3.0 * (1.0 - x).powi(2)),
            x if x <= 2.0 => (0.0, 0.0),
            x if x < 3.0 => ((x - 2.5).powi(3) + 0.125, 3.0 * (x - 2.5).powi(2)),
            x if x <= 3.5 => (0.25, 0.0),
            x => (0.25 + (x - 3.5) * (x - 4.0).powi(2), (x - 4.0).powi(2) + 2.0 * (x - 3.5) * (x - 4.0)),
        };
        Ok(Jet { x, value, d1, d2: 0.0 })
    }

    #[test]
    fn rests_are_located_to_the_doubles_and_instants_are_not_rests() {
        // Samples at 0, 0.1, ..., 5: 2.5 is a sample where the analog touches zero.
        let samples: Vec<Jet> = (0..=50).map(|i| jet(0.1 * i as f64)).collect::<Result<_, _>>().unwrap();
        let r = rests(&samples, jet).unwrap();
        let ends: Vec<(f64, f64)> = r.iter().map(|r| (r.start.x, r.end.x)).collect();
        assert_eq!(ends, [(1.0, 2.0), (3.0, 3.5)], "{r:?}");
        assert_eq!(r.iter().map(Rest::value).collect::<Vec<_>>(), [0.0, 0.25]);
        assert_eq!(r[1].duration(), 0.5);
    }

    /// A velocity analog crossing zero at a sample, rounded to exactly zero over a few units in
    /// the last place around it: an instant, not a rest.
    #[test]
    fn a_velocity_rounded_to_zero_for_an_instant_is_no_rest() {
        let f = |x: f64| {
            let d1 = if (x - 2.5).abs() < 4e-15 { 0.0 } else { x - 2.5 };
            Ok(Jet { x, value: 0.5 * (x - 2.5) * (x - 2.5), d1, d2: 1.0 })
        };
        for from in [2.5, 0.0] {
            let samples: Vec<Jet> = (0..=10).map(|i| f(from + 0.25 * f64::from(i)).unwrap()).collect();
            assert_eq!(rests(&samples, f).unwrap(), [], "from {from}");
        }
    }

    /// A velocity exactly zero at two consecutive samples, `(x - 1) (x - 2)` at 1 and 2, with
    /// the output moving between them: no rest.
    #[test]
    fn two_samples_at_rest_with_motion_between_are_no_rest() {
        let f =
            |x: f64| Ok(Jet { x, value: x * x * x / 3.0 - 1.5 * x * x + 2.0 * x, d1: (x - 1.0) * (x - 2.0), d2: 0.0 });
        let samples: Vec<Jet> = (0..4).map(|i| f(f64::from(i)).unwrap()).collect();
        assert_eq!(rests(&samples, f).unwrap(), []);
    }

    #[test]
    fn a_rest_at_an_end_of_the_range_is_cut_there() {
        let samples: Vec<Jet> = (0..=10).map(|i| jet(1.5 + 0.25 * i as f64)).collect::<Result<_, _>>().unwrap();
        let r = rests(&samples, jet).unwrap();
        assert_eq!((r[0].start.x, r[0].end.x), (1.5, 2.0));
        // An output at rest over the whole range: one rest, the range.
        let flat = |x: f64| Ok(Jet { x, value: 7.0, d1: 0.0, d2: 0.0 });
        let samples: Vec<Jet> = (0..5).map(|i| flat(f64::from(i)).unwrap()).collect();
        let r = rests(&samples, flat).unwrap();
        assert_eq!(r.len(), 1);
        assert_eq!((r[0].start.x, r[0].end.x, r[0].value()), (0.0, 4.0, 7.0));
    }

    /// A law that jumps from one stretch at rest to another, its velocity zero on both sides
    /// (a `floor` of the input): two rests, each end at the jump to the doubles, where it was
    /// one rest standing at the first value over both.
    #[test]
    fn a_jump_between_two_stretches_at_rest_ends_one_rest_and_begins_another() {
        let jump = std::f64::consts::FRAC_PI_3;
        let f = |x: f64| Ok(Jet { x, value: if x < jump { 60.0 } else { 80.0 }, d1: 0.0, d2: 0.0 });
        for samples in [11, 12, 1000] {
            let samples: Vec<Jet> =
                (0..samples).map(|i| f(3.0 * f64::from(i) / f64::from(samples - 1)).unwrap()).collect();
            let r = rests(&samples, f).unwrap();
            let ends: Vec<(f64, f64, f64)> = r.iter().map(|r| (r.start.x, r.end.x, r.value())).collect();
            let below = f64::from_bits(jump.to_bits() - 1);
            assert_eq!(ends, [(0.0, below, 60.0), (jump, 3.0, 80.0)], "{} samples", samples.len());
        }
        // Values at rest that differ by rounding alone are one rest.
        let noisy = |x: f64| {
            Ok(Jet { x, value: 80.0 + if x.to_bits().is_multiple_of(2) { 0.0 } else { 1e-13 }, d1: 0.0, d2: 0.0 })
        };
        let samples: Vec<Jet> = (0..=10).map(|i| noisy(0.3 * f64::from(i)).unwrap()).collect();
        assert_eq!(rests(&samples, noisy).unwrap().len(), 1);
    }

    #[test]
    fn bad_samples_and_failed_evaluations_are_errors() {
        assert!(rests(&[], jet).is_err());
        let a = jet(1.5).unwrap();
        assert!(rests(&[a, a], jet).is_err(), "not increasing");
        let samples: Vec<Jet> = (0..=10).map(|i| jet(0.5 * i as f64)).collect::<Result<_, _>>().unwrap();
        let fails = |_: f64| Err(Error::InvalidArgument("no state".into()));
        assert!(matches!(rests(&samples, fails), Err(Error::InvalidArgument(m)) if m == "no state"));
        let nan = |x: f64| Ok(Jet { x, value: f64::NAN, d1: f64::NAN, d2: 0.0 });
        assert!(rests(&samples, nan).is_err());
    }
}
