//! The time (quick-return) ratio of an output over one input turn: at a constant input speed,
//! the input angle spent while the output rises from its minimum to its maximum, against the
//! angle spent while it falls back.

use crate::Kernel;
use crate::analysis::extremes::{Corner, extremes_across, sign_change};
use crate::analysis::{ColumnOf, Extreme, Jet, SampledOf};
use crate::error::Error;

/// The strokes of an output over one input turn, from its located extremes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeRatio {
    /// The output's minimum (input, value, analogs).
    pub min: Jet,
    /// The output's maximum.
    pub max: Jet,
    /// Input angle while the output rises from its minimum to its maximum.
    pub rising: f64,
    /// Input angle while it falls back (`period - rising`).
    pub falling: f64,
}

impl TimeRatio {
    /// The time ratio: the slower stroke over the quicker one (`>= 1`; `1` without quick return).
    pub fn ratio(&self) -> f64 {
        self.rising.max(self.falling) / self.rising.min(self.falling)
    }
}

/// The time ratio of an output sampled over one full period of the input (`samples` in
/// increasing input, the last one period after the first, e.g. `0 ..= 2 pi`); `eval` gives the
/// output's jet at any input of the range.
///
/// The output must have exactly one maximum and one minimum per turn. They are located as roots
/// of the velocity analog ([`extremes()`](crate::analysis::extremes::extremes)); an extreme on
/// the seam (at the first sample, where the analog changes sign across the period) is taken
/// there. Errors: fewer or more extremes, a range that is not increasing, an output that does
/// not return to its first value at the last sample (not one period).
///
/// ```
/// use kinloop_runtime::analysis::Jet;
/// use kinloop_runtime::metrics::time_ratio;
/// use std::f64::consts::{PI, TAU};
/// // An output rising for 4 pi / 3 and falling for 2 pi / 3: v(x) = -cos(g(x)), where g
/// // runs through 0 .. pi while x runs through 0 .. 4 pi / 3, then pi .. 2 pi.
/// let f = |x: f64| {
///     let y = x.rem_euclid(TAU);
///     let (k, y0, g0) = if y < 4.0 * PI / 3.0 { (0.75, 0.0, 0.0) } else { (1.5, 4.0 * PI / 3.0, PI) };
///     let g = g0 + k * (y - y0);
///     Ok(Jet { x, value: -g.cos(), d1: k * g.sin(), d2: k * k * g.cos() })
/// };
/// let samples = Jet::sample(f, 0.1, 0.1 + TAU, 72)?;
/// let t = time_ratio(&samples, f)?;
/// assert!((t.rising - 4.0 * PI / 3.0).abs() < 1e-12);
/// assert!((t.ratio() - 2.0).abs() < 1e-11);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn time_ratio(samples: &[Jet], eval: impl FnMut(f64) -> Result<Jet, Error>) -> Result<TimeRatio, Error> {
    time_ratio_across(samples, &[], eval)
}

/// [`time_ratio`] with `corners` between samples (see `extremes_across`).
fn time_ratio_across(
    samples: &[Jet],
    corners: &[Corner],
    eval: impl FnMut(f64) -> Result<Jet, Error>,
) -> Result<TimeRatio, Error> {
    let mut found = extremes_across(samples, corners, eval)?;
    let n = samples.len();
    let (first, last) = (samples[0], samples[n - 1]);
    // Over less (or more) than a period the seam below is no seam: it made an extreme of the
    // first sample and a ratio of the range's length, as `Ok`. Over one period the output
    // returns to its first value but for the rounding of the input's turn (about 1e-15 of its
    // range); the test is relative to the range, so that it is the same in any unit.
    let (lo, hi) =
        samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), j| (l.min(j.value), h.max(j.value)));
    if (last.value - first.value).abs() > 1e-9 * (hi - lo) {
        return Err(Error::InvalidArgument(format!(
            "a time ratio needs the output over one period (one input turn): it is {} at the start and {} at the end",
            first.value, last.value
        )));
    }
    let period = last.x - first.x;
    // Seam: the analog changes sign between the last interval and the first one. Its signs
    // compared, not their product's: the analogs of a tiny output (1e-300 of a mechanism's
    // unit) multiply to zero, and the extreme on the seam was lost.
    let (before, after) = (samples[n - 2].d1, samples[1].d1);
    if found.len() == 1 && sign_change(before, after) {
        let kind = if before > 0.0 { Extreme::Max } else { Extreme::Min };
        let at = if first.d1.abs() <= last.d1.abs() { first } else { Jet { x: first.x, ..last } };
        found.push(crate::analysis::LocalExtreme { kind, at });
    }
    let pick = |k: Extreme| found.iter().filter(|e| e.kind == k).map(|e| e.at).collect::<Vec<_>>();
    let (maxima, minima) = (pick(Extreme::Max), pick(Extreme::Min));
    if maxima.len() != 1 || minima.len() != 1 {
        return Err(Error::InvalidArgument(format!(
            "a time ratio needs one maximum and one minimum of the output per turn; found {} maxima and {} minima",
            maxima.len(),
            minima.len()
        )));
    }
    let (min, max) = (minima[0], maxima[0]);
    let rising = (max.x - min.x).rem_euclid(period);
    Ok(TimeRatio { min, max, rising, falling: period - rising })
}

impl<K: Kernel> SampledOf<K> {
    /// The time (quick-return) ratio ([`time_ratio()`]) of a column (`Name::COL.psi`, or its
    /// name) of a sweep over one full input turn (one period of the path parameter). Its
    /// extremes are looked for between the samples as [`SampledOf::extremes`] looks for them:
    /// a turn of few samples gives the ratio of many.
    pub fn time_ratio(&self, column: impl ColumnOf<K>) -> Result<TimeRatio, Error> {
        let c = column.resolve(self.kernel())?;
        self.searched(c, |jets, corners, eval| time_ratio_across(jets, corners, eval))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    fn offset_cosine(x: f64) -> Result<Jet, Error> {
        Ok(Jet { x, value: (x - 1.0).cos(), d1: -(x - 1.0).sin(), d2: -(x - 1.0).cos() })
    }

    #[test]
    fn an_output_without_quick_return_has_ratio_one() {
        let s = Jet::sample(offset_cosine, 0.0, TAU, 36).unwrap();
        let t = time_ratio(&s, offset_cosine).unwrap();
        assert!((t.max.x - 1.0).abs() < 1e-15 && (t.ratio() - 1.0).abs() < 1e-14, "{t:?}");
    }

    #[test]
    fn an_extreme_on_the_seam_is_found() {
        // Maximum exactly at the first sample x = 1.
        let s = Jet::sample(offset_cosine, 1.0, 1.0 + TAU, 36).unwrap();
        let t = time_ratio(&s, offset_cosine).unwrap();
        assert_eq!(t.max.x, 1.0);
        assert!((t.rising - TAU / 2.0).abs() < 1e-14);
    }

    /// An extreme on the seam is found at every size of the output: a cosine of amplitude `r`
    /// with its maximum at the first sample, from `r = 1e-300` (a mechanism's length at a tiny
    /// size) to `1e300`. The seam was judged by the product of the analogs either side of it,
    /// which underflowed to zero below an amplitude of about `1e-161` (analogs of `0.17` of it,
    /// squared, below half the least subnormal): the maximum was lost and the ratio refused as "0 maxima". The ratio of a
    /// cosine is exactly 1 (rising for pi, the half turn from the maximum on the seam to the
    /// minimum at `1 + pi`, located to rounding).
    #[test]
    fn an_extreme_on_the_seam_is_found_at_every_scale() {
        for r in [1e-300, 1e-200, 1e-170, 1e-6, 1.0, 1e6, 1e300] {
            let f =
                |x: f64| Ok(Jet { x, value: r * (x - 1.0).cos(), d1: -r * (x - 1.0).sin(), d2: -r * (x - 1.0).cos() });
            let s = Jet::sample(f, 1.0, 1.0 + TAU, 36).unwrap();
            let t = time_ratio(&s, f).unwrap_or_else(|e| panic!("r = {r:e}: {e}"));
            assert_eq!(t.max.x, 1.0, "r = {r:e}: {t:?}");
            assert!((t.min.x - (1.0 + PI)).abs() < 1e-14, "r = {r:e}: {t:?}");
            assert!((t.rising - PI).abs() < 1e-14 && (t.ratio() - 1.0).abs() < 1e-14, "r = {r:e}: {t:?}");
            assert!((t.max.value / r - 1.0).abs() < 1e-15 && (t.min.value / r + 1.0).abs() < 1e-15, "{t:?}");
        }
    }

    /// Samples over part of a period are refused: the seam made the first sample an extreme
    /// and the ratio one of the range's length (over a quarter turn of a cosine, `Ok`).
    #[test]
    fn samples_over_part_of_a_period_are_an_error() {
        let s = Jet::sample(offset_cosine, 0.0, 3.0, 36).unwrap();
        let r = time_ratio(&s, offset_cosine);
        assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("one period")), "{r:?}");
    }

    /// The period test is the same in any unit: a cosine of amplitude 1e-7 from its maximum
    /// over a turn less 0.05 rad (its ends 1.2e-10 apart, within an absolute 1e-9) is refused;
    /// over a whole turn it gives the cosine's ratio.
    #[test]
    fn the_period_test_is_relative_to_the_output() {
        let small = |x: f64| Ok(Jet { x, value: 1e-7 * x.cos(), d1: -1e-7 * x.sin(), d2: -1e-7 * x.cos() });
        let part = Jet::sample(small, 0.0, TAU - 0.05, 72).unwrap();
        let r = time_ratio(&part, small);
        assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("one period")), "{r:?}");
        let whole = Jet::sample(small, 0.3, 0.3 + TAU, 72).unwrap();
        let t = time_ratio(&whole, small).unwrap();
        assert!((t.rising - PI).abs() < 1e-12 && (t.falling - PI).abs() < 1e-12, "{t:?}");
    }

    #[test]
    fn two_maxima_per_turn_are_an_error() {
        let f = |x: f64| Ok(Jet { x, value: (2.0 * x).cos(), d1: -2.0 * (2.0 * x).sin(), d2: -4.0 * (2.0 * x).cos() });
        let s = Jet::sample(f, 0.3, 0.3 + TAU, 72).unwrap();
        assert!(matches!(time_ratio(&s, f), Err(Error::InvalidArgument(_))));
    }
}
