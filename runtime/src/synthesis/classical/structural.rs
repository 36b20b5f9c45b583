//! The structural error of a function generator: how far the linkage's output is from the
//! function between (and beyond) its precision points.

use super::chebyshev::span_of;
use super::error::ClassicalError;
use super::freudenstein::FunctionGenerator;
use super::function_map::FunctionMap;
use super::position::angle_difference;

/// The deviation of a function generator's output from the function it generates, sampled
/// over the whole range; from [`structural_error`].
#[derive(Clone, Debug, PartialEq)]
pub struct StructuralError {
    /// The largest output angle error over the samples (radians, absolute); infinite when the
    /// linkage cannot be assembled at some sample.
    pub max: f64,
    /// The argument `x` where it occurs: the first unassembled sample's when there is one.
    pub at_x: f64,
    /// The largest error in units of the function value `y` (the angle error scaled by
    /// `(y1 - y0) / dpsi`); infinite with `max`.
    pub max_y: f64,
    /// The root mean square of the output angle error over the samples (radians); infinite
    /// with `max`.
    pub rms: f64,
    /// How many samples were taken (evenly spaced over `x0 ..= x1`).
    pub samples: usize,
    /// How many of them the linkage cannot be assembled at (on its closure). There the linkage
    /// has no output angle, so its error is unbounded: `max`, `max_y` and `rms` are infinite
    /// whenever this is not zero, and a test such as `e.max < tolerance` rejects the design.
    pub unassembled: usize,
}

/// The structural error of `generator` against `f` over the range of `map`, from `samples`
/// evenly spaced arguments: at each the linkage is analysed by intersecting circles (on the
/// generator's [`closure`](FunctionGenerator::closure)) and its output angle compared with `map.psi(f(x))`.
/// A sample where the linkage cannot be assembled counts as an infinite error: a design that
/// does not move over the whole range never reports a small one (see
/// [`StructuralError::unassembled`]).
///
/// Errors: fewer than two samples or more than [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES)
/// (before `f` is called); `f` not finite at a sample.
///
/// ```
/// use kinloop_runtime::deg;
/// use kinloop_runtime::synthesis::classical::{FunctionMap, chebyshev_points, freudenstein, structural_error};
/// let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0))?;
/// let g = freudenstein(&map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0)?)?)?;
/// let e = structural_error(&g, &map, f64::log10, 201)?;
/// assert_eq!(e.unassembled, 0);
/// assert!(e.max < deg(1.0)); // under a degree over the whole range
///
/// // Other ranges (the input from -120 degrees, the output from -150 through 120): the
/// // linkage cannot be assembled over part of the range, and its error is infinite there,
/// // not that of the part it reaches.
/// let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(-120.0), deg(90.0), deg(-150.0), deg(120.0))?;
/// let g = freudenstein(&map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0)?)?)?;
/// let e = structural_error(&g, &map, f64::log10, 201)?;
/// assert!(e.unassembled > 0 && e.max == f64::INFINITY);
/// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
/// ```
pub fn structural_error(
    generator: &FunctionGenerator,
    map: &FunctionMap,
    f: impl Fn(f64) -> f64,
    samples: usize,
) -> Result<StructuralError, ClassicalError> {
    if samples < 2 {
        return Err(ClassicalError::BadRange {
            what: "number of samples",
            why: format!("{samples}: the ends of the range take two"),
        });
    }
    crate::analysis::check_sample_count("samples", samples)
        .map_err(|why| ClassicalError::BadRange { what: "number of samples", why })?;
    let (mut max, mut at_x, mut sum_sq, mut unassembled) = (0.0f64, map.x0, 0.0, 0usize);
    for i in 0..samples {
        let x = sample(map.x0, map.x1, i, samples);
        let y = f(x);
        if !y.is_finite() {
            return Err(ClassicalError::NonFinite { what: format!("f({x})"), value: y });
        }
        // No output angle (or a NaN one, from lengths not finite): an unbounded error, at the
        // first such sample.
        let e = generator.output_angle(map.phi(x)).map(|psi| angle_difference(psi, map.psi(y)).abs());
        let Some(e) = e.filter(|e| e.is_finite()) else {
            if unassembled == 0 {
                (max, at_x) = (f64::INFINITY, x);
            }
            unassembled += 1;
            continue;
        };
        sum_sq += e * e;
        if e > max {
            (max, at_x) = (e, x);
        }
    }
    let rms = if unassembled > 0 { f64::INFINITY } else { (sum_sq / samples as f64).sqrt() };
    let max_y = max * ((map.y1 - map.y0) / map.dpsi).abs();
    Ok(StructuralError { max, at_x, max_y, rms, samples, unassembled })
}

/// The `i`-th of `n` evenly spaced arguments over `x0 ..= x1`, measured from the nearer end:
/// from `x0` alone the last one, `x0 + (x1 - x0) * 1`, can round past `x1` (over `-1.2 ..= 1`
/// it is `1.0000000000000002`), where a function such as `sqrt(1 - x)` is not defined. Ends far
/// apart near the largest f64 overflow `x1 - x0`: see [`span_of`].
fn sample(x0: f64, x1: f64, i: usize, n: usize) -> f64 {
    let (span, factor) = span_of(x0, x1);
    let last = (n - 1) as f64;
    if 2 * i < n { x0 + span * (factor * i as f64 / last) } else { x1 - span * (factor * (n - 1 - i) as f64 / last) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::FourBarLinks;
    use crate::synthesis::classical::Closure;

    /// A generator of the given lengths (ground 1); its ratios and fit do not enter the analysis.
    fn generator(input: f64, coupler: f64, output: f64) -> FunctionGenerator {
        FunctionGenerator {
            k: [1.0 / input, 1.0 / output, 0.0],
            links: FourBarLinks { ground: 1.0, input, coupler, output },
            residual: 0.0,
            max_residual: 0.0,
            rcond: 1.0,
            closure: Closure::CounterClockwise,
            one_closure: true,
        }
    }

    /// `y = x` over `0 ..= 1` onto the input angles `0.5 ..= 3.0` (output `1 ..= 2`).
    fn map() -> FunctionMap {
        FunctionMap::new(|x| x, 0.0, 1.0, 0.5, 2.5, 1.0, 1.0).unwrap()
    }

    /// A coupler far longer than the other links: the loop closes at no input angle, and the
    /// error must not look small (it used to be reported as zero).
    #[test]
    fn a_design_assembled_nowhere_has_an_infinite_error() {
        let g = generator(0.1, 5.0, 0.1);
        let e = structural_error(&g, &map(), |x| x, 11).unwrap();
        assert_eq!((e.samples, e.unassembled), (11, 11));
        assert!(e.max == f64::INFINITY && e.max_y == f64::INFINITY && e.rms == f64::INFINITY, "{e:?}");
        assert_eq!(e.at_x, 0.0, "the first unassembled argument");
        assert!(e.max >= 1e-3 && e.max_y >= 1e-3, "a test `e.max < tolerance` rejects it");
    }

    /// Input 0.5, coupler 0.7, output 0.5: the loop closes while `|B - D| <= b + c`, i.e.
    /// `1.25 - cos(phi) <= 1.44`, `phi <= acos(-0.19) = 1.7619` rad: the samples at
    /// `phi = 0.5 + 0.25 i` for `i <= 5` only.
    #[test]
    fn a_design_assembled_over_part_of_the_range_has_an_infinite_error_at_the_first_gap() {
        let (a, b, c): (f64, f64, f64) = (0.5, 0.7, 0.5);
        let m = map();
        let limit = ((a * a + 1.0 - (b + c) * (b + c)) / (2.0 * a)).acos();
        assert!((limit - 1.7619).abs() < 1e-4 && limit > m.phi(0.5) + 0.01 && limit < m.phi(0.6) - 0.01);
        let g = generator(a, b, c);
        let e = structural_error(&g, &m, |x| x, 11).unwrap();
        assert_eq!(e.unassembled, 5, "{e:?}");
        assert!(e.max == f64::INFINITY && e.max_y == f64::INFINITY && e.rms == f64::INFINITY, "{e:?}");
        assert!((e.at_x - 0.6).abs() < 1e-15, "{e:?}");
        // Over the assembled part alone the error is finite: it is not what is reported.
        assert!(g.output_angle(m.phi(0.5)).is_some() && g.output_angle(m.phi(0.6)).is_none());
    }

    /// The `log10` generator over other ranges (the doc example): an mpmath solution of the
    /// same system at 40 digits, checked for assembly by `|b - c| <= |B - D| <= b + c` at the
    /// same 201 inputs, cannot be assembled at the first 12 (`x = 1 ..= 1.055`; no input within
    /// 0.0019 of either bound, so rounding cannot move one across).
    #[test]
    fn the_log10_generator_over_ranges_it_cannot_reach_counts_the_samples_it_misses() {
        use crate::deg;
        use crate::synthesis::classical::{chebyshev_points, freudenstein};
        let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(-120.0), deg(90.0), deg(-150.0), deg(120.0)).unwrap();
        let g =
            freudenstein(&map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0).unwrap()).unwrap()).unwrap();
        for (got, want) in [(g.links.input, 1.9347320415003865), (g.links.coupler, 0.823812960566072)] {
            assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        }
        let e = structural_error(&g, &map, f64::log10, 201).unwrap();
        assert_eq!(e.unassembled, 12, "{e:?}");
        assert_eq!((e.max, e.rms, e.at_x), (f64::INFINITY, f64::INFINITY, 1.0));
    }

    /// More samples than `analysis::MAX_SAMPLES` are refused before `f` is called: the largest
    /// `usize` evaluated practically forever.
    #[test]
    fn absurd_sample_counts_are_refused_before_sampling() {
        let g = generator(0.5, 0.7, 0.5);
        for samples in [crate::analysis::MAX_SAMPLES + 1, usize::MAX] {
            let calls = std::cell::Cell::new(0usize);
            // An unbounded run stops after a few calls with an error of its own.
            let f = |x: f64| {
                calls.set(calls.get() + 1);
                if calls.get() > 1000 { f64::NAN } else { x }
            };
            let r = structural_error(&g, &map(), f, samples);
            assert!(matches!(&r, Err(ClassicalError::BadRange { why, .. }) if why.contains("at most")), "{r:?}");
            assert_eq!(calls.get(), 0);
        }
    }

    #[test]
    fn fewer_than_two_samples_or_a_function_not_finite_is_an_error() {
        let g = generator(0.5, 0.7, 0.5);
        assert!(matches!(structural_error(&g, &map(), |x| x, 1), Err(ClassicalError::BadRange { .. })));
        let bad = |x: f64| if x > 0.5 { f64::NAN } else { x };
        assert!(matches!(structural_error(&g, &map(), bad, 11), Err(ClassicalError::NonFinite { .. })));
    }

    /// The last sample is the end of the range: from the start alone, `-1.2 + 2.2 * 1` is
    /// `1.0000000000000002`, where `sqrt(1 - x)` (defined over the whole range `FunctionMap`
    /// accepted) is NaN and the error was `NonFinite`.
    #[test]
    fn the_last_sample_is_the_end_of_the_range() {
        let f = |x: f64| (1.0 - x).sqrt();
        let map = FunctionMap::new(f, -1.2, 1.0, 0.5, 2.5, 1.0, 1.0).unwrap();
        let g = generator(0.5, 0.7, 0.5);
        for samples in [2, 3, 5, 201] {
            let r = structural_error(&g, &map, f, samples);
            assert!(r.is_ok(), "{samples} samples: {r:?}");
        }
        let x: Vec<f64> = (0..5).map(|i| sample(-1.2, 1.0, i, 5)).collect();
        assert_eq!((x[0], x[4]), (-1.2, 1.0));
        assert!(x.windows(2).all(|w| w[0] < w[1]), "{x:?}");
        // Ends whose difference overflows: every sample finite, in order, the ends exact.
        let x: Vec<f64> = (0..7).map(|i| sample(-1e308, 1e308, i, 7)).collect();
        assert_eq!((x[0], x[3], x[6]), (-1e308, 0.0, 1e308));
        assert!(x.windows(2).all(|w| w[0] < w[1]), "{x:?}");
    }
}
