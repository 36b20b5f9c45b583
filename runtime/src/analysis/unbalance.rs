//! Residual unbalance: what remains of a periodic quantity after its lowest harmonics are
//! removed (balanced), e.g. the centre of mass of a mechanism's reciprocating masses after
//! counterweights cancel its first harmonic (`docs/papers.md`, paper 004):
//!
//! ```text
//! D = max over a cycle of |v(x) - v_m(x)|,     v_m = a0 + sum_{k=1..m} a_k cos kθ + b_k sin kθ
//! ```
//!
//! The harmonics come from [`fourier`] over the cycle's samples; the
//! maximum of `|v - v_m|` is located among the extremes of the residual `r = v - v_m`, found as
//! roots of `r' = v' - v_m'` with `r'' = v'' - v_m''` (see [`extremes`](super::extremes::extremes)), so
//! `D` is exact to rounding rather than to the sample spacing.

use super::Jet;
use super::extremes::{Corner, check_increasing, extremes_across};
use super::fourier::{Fourier, fourier};
use crate::error::Error;

/// How far, relative to how far a quantity moves, its last sample over a period may differ from
/// its first for the samples to be one period: a thousand times the rounding a solve leaves in a
/// mechanism's positions (Newton's residual tolerance, 1e-12 of the mechanism's size), far below
/// what a sweep a step short of a cycle leaves. Beside it the rounding of the values' own
/// magnitude, [`ROUNDING`] of it, which is all a quantity far from 0 adds: a tolerance relative
/// to the magnitude grew with the offset (a slider a millimetre across, 6.4e6 m out, took half a
/// turn for a period within 6.4 mm).
pub const PERIODIC_TOLERANCE: f64 = 1e-9;

/// The rounding of a value, relative to its magnitude, that tells it from a different one: 64
/// units of rounding (`f64::EPSILON`, twice a unit in the last place at most), room for the
/// roundings of the sums and the last Newton correction a position is computed by, each of a
/// unit or so of the largest term (a point far from 0 repeats its value over a turn to the last
/// bit, as measured).
pub const ROUNDING: f64 = 64.0 * f64::EPSILON;

/// The tolerance within which a quantity whose values over the samples are `values` returns to
/// its start: [`PERIODIC_TOLERANCE`] of its range, and [`ROUNDING`] of its largest magnitude.
/// Both are free of the unit, and the range of an offset as well.
pub(crate) fn periodic_tolerance(values: impl Iterator<Item = f64>) -> f64 {
    let (lo, hi, big) = values
        .fold((f64::INFINITY, f64::NEG_INFINITY, 0.0f64), |(lo, hi, big), v| (lo.min(v), hi.max(v), big.max(v.abs())));
    let range = if hi >= lo { hi - lo } else { 0.0 };
    PERIODIC_TOLERANCE * range + ROUNDING * big
}

/// The unbalance left in a periodic quantity after removing harmonics `0 ..= removed`: the
/// residual `v - v_m` and its largest magnitude.
#[derive(Clone, Debug, PartialEq)]
pub struct Unbalance {
    /// The removed harmonics (mean and harmonics `1 ..= removed`).
    pub fourier: Fourier,
    /// `D = max |v - v_m|` over the cycle.
    pub max_abs: f64,
    /// The residual `r = v - v_m` (value and analogs) where `|r|` is largest.
    pub at: Jet,
}

/// The residual of a periodic quantity after removing its mean and its harmonics up to
/// `removed`, and its largest magnitude over the cycle (see the [module documentation](self)).
///
/// `samples` are `n + 1` jets equally spaced over one closed period `[x0, x0 + T]` (the last
/// repeats the first; `n > 2 removed` samples per period); `eval` computes the jet anywhere in
/// the period.
///
/// Errors (`InvalidArgument`): samples not equally spaced to `1e-9` of the period, or too far
/// from 0 for a double to resolve their spacing to that (beyond about `4.5e6` periods, the
/// error naming their magnitude and its resolution: shift them by whole periods), or whose
/// last value does not repeat the first (to [`PERIODIC_TOLERANCE`] of their range and
/// [`ROUNDING`] of their largest magnitude, whatever their offset from 0: not one period; a quantity
/// that is rounding alone, zero in exact arithmetic, may fail this: give its samples to
/// [`Sampled::unbalance`](crate::analysis::Sampled::unbalance), which judges a column against
/// the size of what it is computed from); too many harmonics `removed` for the samples (see
/// [`fourier`]).
///
/// ```
/// use kinloop_runtime::analysis::{Jet, unbalance::unbalance};
/// use std::f64::consts::TAU;
/// // v = 1 + cos x + 0.01 cos 2x: after removing the first harmonic, |0.01 cos 2x| <= 0.01.
/// let f = |x: f64| Ok(Jet {
///     x,
///     value: 1.0 + x.cos() + 0.01 * (2.0 * x).cos(),
///     d1: -x.sin() - 0.02 * (2.0 * x).sin(),
///     d2: -x.cos() - 0.04 * (2.0 * x).cos(),
/// });
/// let s: Vec<Jet> = (0..=24).map(|j| f(TAU * j as f64 / 24.0)).collect::<Result<_, _>>()?;
/// let r = unbalance(&s, f, 1)?;
/// assert!((r.max_abs - 0.01).abs() < 1e-15);
/// assert!((r.fourier.a[0] - 1.0).abs() < 1e-15);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn unbalance(
    samples: &[Jet],
    eval: impl FnMut(f64) -> Result<Jet, Error>,
    removed: usize,
) -> Result<Unbalance, Error> {
    let tolerance = periodic_tolerance(samples.iter().map(|s| s.value));
    unbalance_across(samples, samples, &[], eval, removed, tolerance)
}

/// [`unbalance`], the last sample's return to the first judged within `tolerance` (see
/// [`SampledOf::unbalance`](crate::analysis::SampledOf::unbalance), which knows what a column
/// is computed from), with the residual's extremes looked for among the jets `search` (the
/// samples and points between them, in increasing `x`) and across `corners` between them (the
/// singular crossings of a sampled range, where nothing is evaluated nearby: see
/// `extremes_across`); the harmonics are still those of the equally spaced `samples`.
pub(crate) fn unbalance_across(
    samples: &[Jet],
    search: &[Jet],
    corners: &[Corner],
    mut eval: impl FnMut(f64) -> Result<Jet, Error>,
    removed: usize,
    tolerance: f64,
) -> Result<Unbalance, Error> {
    check_increasing(samples)?;
    let n = samples.len() - 1;
    let (x0, x_end) = (samples[0].x, samples[n].x);
    let period = x_end - x0;
    check_spacing(samples, x0, period)?;
    // Over part of a period (or more) the harmonics are of another quantity, which repeats the
    // samples of the range: the residual of half a turn of a cosine was 1.125, as `Ok`.
    if (samples[n].value - samples[0].value).abs() > tolerance {
        return Err(Error::InvalidArgument(format!(
            "residual needs samples over one period: the quantity is {} at the start and {} at the end",
            samples[0].value, samples[n].value
        )));
    }
    let values: Vec<f64> = samples[..n].iter().map(|s| s.value).collect();
    let f = fourier(&values, x0, period, removed)?;
    let minus = |j: Jet| {
        let (v, d1, d2) = f.eval_upto(removed, j.x);
        Jet { x: j.x, value: j.value - v, d1: j.d1 - d1, d2: j.d2 - d2 }
    };
    let r: Vec<Jet> = search.iter().map(|&s| minus(s)).collect();
    let rc: Vec<Corner> = corners.iter().map(|c| Corner { after: c.after, at: minus(c.at) }).collect();
    let found = extremes_across(&r, &rc, |x| eval(x).map(minus))?;
    // The residual's largest magnitude: at an extreme, at a point of the search (an end of the
    // period among them), or at a crossing, where its analog may jump without changing sign.
    let mut at = r[0];
    for c in found.iter().map(|e| e.at).chain(r.iter().copied()).chain(rc.iter().map(|c| c.at)) {
        if c.value.abs() > at.value.abs() {
            at = c;
        }
    }
    Ok(Unbalance { fourier: f, max_abs: at.value.abs(), at })
}

/// How far, relative to the period, a sample may lie from its place in an equal spacing.
const SPACING_TOLERANCE: f64 = 1e-9;

/// Refuses `samples` (`n + 1` of them, `x0` the first, over `period`) that are not equally
/// spaced to [`SPACING_TOLERANCE`] of the period. Where rounding alone explains the gap
/// (within two units in the last place of the samples' largest magnitude: half a unit where
/// the caller rounded each sample, half where the place below is computed, and at most half
/// from the last sample's rounding carried into the period), the samples are equally spaced
/// as given, but too far from 0 for a double to resolve their spacing to that tolerance (about
/// `4.5e6` periods): the error says so, with the numbers.
fn check_spacing(samples: &[Jet], x0: f64, period: f64) -> Result<(), Error> {
    let n = samples.len() - 1;
    let gap = |j: usize| (samples[j].x - (x0 + period * j as f64 / n as f64)).abs();
    let Some((j, worst)) = (0..=n).map(|j| (j, gap(j))).max_by(|a, b| a.1.total_cmp(&b.1)) else {
        return Ok(());
    };
    if worst <= SPACING_TOLERANCE * period {
        return Ok(());
    }
    let far = samples.iter().fold(0.0f64, |m, s| m.max(s.x.abs()));
    let resolution = far.next_up() - far;
    if worst <= 2.0 * resolution {
        return Err(Error::InvalidArgument(format!(
            "residual needs the samples' spacing resolved to {SPACING_TOLERANCE:e} of the period, but they are too \
             far from 0 for that: at {far:e} a double is resolved to {resolution:e}, {:.2e} of the period {period:e} \
             (sample {j} is {worst:e} off an equal spacing, by rounding alone); give the samples nearer 0, shifted by \
             whole periods",
            resolution / period
        )));
    }
    Err(Error::InvalidArgument("residual needs equally spaced samples over one period".into()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn residual_of_a_two_harmonic_signal_with_an_off_grid_peak() {
        // v = 3 + 2 cos(x - 0.4) + 0.05 cos(2x - 1.1) + 0.02 sin 3x. After removing the first
        // harmonic the residual is 0.05 cos(2x - 1.1) + 0.02 sin 3x; its maximum magnitude is
        // found independently by a fine scan refined with golden sections.
        let f = |x: f64| {
            Ok(Jet {
                x,
                value: 3.0 + 2.0 * (x - 0.4).cos() + 0.05 * (2.0 * x - 1.1).cos() + 0.02 * (3.0 * x).sin(),
                d1: -2.0 * (x - 0.4).sin() - 0.1 * (2.0 * x - 1.1).sin() + 0.06 * (3.0 * x).cos(),
                d2: -2.0 * (x - 0.4).cos() - 0.2 * (2.0 * x - 1.1).cos() - 0.18 * (3.0 * x).sin(),
            })
        };
        let s: Vec<Jet> = (0..=36).map(|j| f(TAU * j as f64 / 36.0).unwrap()).collect();
        let r = unbalance(&s, f, 1).unwrap();
        assert!((r.fourier.a0 - 3.0).abs() < 1e-14);
        assert!((r.fourier.a[0] - 2.0 * 0.4f64.cos()).abs() < 1e-14);
        assert!((r.fourier.b[0] - 2.0 * 0.4f64.sin()).abs() < 1e-14);
        let res = |x: f64| (0.05 * (2.0 * x - 1.1).cos() + 0.02 * (3.0 * x).sin()).abs();
        let mut best = (0.0, 0.0);
        for i in 0..100_000 {
            let x = TAU * i as f64 / 100_000.0;
            if res(x) > best.1 {
                best = (x, res(x));
            }
        }
        let (x, _) = crate::analysis::extremes::maximize(best.0 - 1e-4, best.0 + 1e-4, |x| Ok(res(x))).unwrap();
        assert!((r.max_abs - res(x)).abs() < 1e-15, "{} vs {}", r.max_abs, res(x));
        assert!((r.at.x - x).abs() < 1e-7);
        // The grid alone would miss the peak by far more than rounding.
        let sampled = s.iter().map(|j| res(j.x)).fold(0.0, f64::max);
        assert!(r.max_abs - sampled > 1e-6);
    }

    #[test]
    fn removing_more_harmonics_leaves_less() {
        let f = |x: f64| {
            Ok(Jet {
                x,
                value: x.cos() + 0.1 * (2.0 * x).cos() + 0.001 * (3.0 * x).sin(),
                d1: -x.sin() - 0.2 * (2.0 * x).sin() + 0.003 * (3.0 * x).cos(),
                d2: -x.cos() - 0.4 * (2.0 * x).cos() - 0.009 * (3.0 * x).sin(),
            })
        };
        let s: Vec<Jet> = (0..=20).map(|j| f(TAU * j as f64 / 20.0).unwrap()).collect();
        assert!((unbalance(&s, f, 1).unwrap().max_abs - 0.1).abs() < 2e-3);
        assert!((unbalance(&s, f, 2).unwrap().max_abs - 0.001).abs() < 1e-15);
        assert!(unbalance(&s, f, 3).unwrap().max_abs < 1e-14);
        // Samples over part of a period are refused: half a turn gave a residual of 1.15, as `Ok`.
        let half: Vec<Jet> = (0..=20).map(|j| f(TAU * j as f64 / 40.0).unwrap()).collect();
        let r = unbalance(&half, f, 1);
        assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("one period")), "{r:?}");
        // Unequal spacing is refused.
        let mut bad = s.clone();
        bad[3].x += 0.01;
        let r = unbalance(&bad, f, 1);
        assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("equally spaced samples")), "{r:?}");
    }

    /// The same quantity `1e7` of its amplitude from 0: half a period is still not one, and a
    /// whole one leaves the same residual, to the rounding of values that far out. The return
    /// to the start was judged within 1e-9 of the values' magnitude, `1e-2` there: half a turn
    /// of `1e7 + cos x`, from `1e7 + 1` to `1e7 - 1`, was refused, but one of `1e7 + 1e-3 cos x`
    /// passed for a period.
    #[test]
    fn a_quantity_far_from_zero_is_judged_periodic_as_near_it() {
        for (offset, amplitude) in [(0.0, 1e-3), (1e7, 1e-3), (-1e7, 1.0)] {
            let f = move |x: f64| {
                Ok(Jet {
                    x,
                    value: offset + amplitude * (x.cos() + 0.1 * (2.0 * x).sin()),
                    d1: amplitude * (-x.sin() + 0.2 * (2.0 * x).cos()),
                    d2: amplitude * (-x.cos() - 0.4 * (2.0 * x).sin()),
                })
            };
            let half: Vec<Jet> = (0..=20).map(|j| f(TAU * j as f64 / 40.0).unwrap()).collect();
            let r = unbalance(&half, f, 1);
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("one period")), "{offset:e}: {r:?}");
            let turn: Vec<Jet> = (0..=24).map(|j| f(TAU * j as f64 / 24.0).unwrap()).collect();
            let u = unbalance(&turn, f, 1).unwrap();
            // The second harmonic is left, `0.1` of the amplitude, to the rounding of the values.
            let tol = 16.0 * f64::EPSILON * (offset.abs() + amplitude);
            assert!((u.max_abs - 0.1 * amplitude).abs() < tol, "{offset:e}: {u:?}");
        }
    }

    /// Samples equally spaced as given, `1e7` periods from 0: a double there is resolved to
    /// `7.45e-9`, `1.19e-9` of the period `2π`, so rounding alone moves a sample by more than the
    /// `1e-9` of a period the spacing is checked to. The refusal says so, with the numbers, where
    /// it said the samples were not equally spaced. Each sample is `x0 + j T / 24` rounded
    /// once; their largest gap from the places the check computes is one unit in the last
    /// place, `7.45e-9` (sample 13 first, as computed apart with Python's floats, which round
    /// as Rust's).
    #[test]
    fn samples_too_far_from_zero_for_their_spacing_say_so() {
        let f = |x: f64| Ok(Jet { x, value: x.cos(), d1: -x.sin(), d2: -x.cos() });
        let x0 = TAU * 1e7;
        let far: Vec<Jet> = (0..=24).map(|j| f(x0 + TAU * j as f64 / 24.0).unwrap()).collect();
        let r = unbalance(&far, f, 1);
        let Err(Error::InvalidArgument(m)) = &r else { panic!("{r:?}") };
        assert!(m.contains("too far from 0"), "{m}");
        assert!(!m.contains("equally spaced samples"), "{m}");
        // The resolution at the last sample, 2^-27 = 7.450580596923828e-9, and its part of 2π.
        assert!(m.contains("resolved to 7.450580596923828e-9, 1.19e-9 of the period"), "{m}");
        // The same samples a whole number of periods nearer 0 (`1e5`) are accepted.
        let near: Vec<Jet> = (0..=24).map(|j| f(TAU * 1e5 + TAU * j as f64 / 24.0).unwrap()).collect();
        assert!(unbalance(&near, f, 1).is_ok());
    }
}
