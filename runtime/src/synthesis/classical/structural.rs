//! The structural error of a function generator: how far the linkage's output is from the
//! function between (and beyond) its precision points.

use super::error::ClassicalError;
use super::freudenstein::FunctionGenerator;
use super::function_map::FunctionMap;
use super::position::angle_difference;

/// The deviation of a function generator's output from the function it generates, sampled
/// over the whole range; from [`structural_error`].
#[derive(Clone, Debug, PartialEq)]
pub struct StructuralError {
    /// The largest output angle error over the samples (radians, absolute).
    pub max: f64,
    /// The argument `x` where it occurs.
    pub at_x: f64,
    /// The largest error in units of the function value `y` (the angle error scaled by
    /// `(y1 - y0) / dpsi`).
    pub max_y: f64,
    /// The root mean square of the output angle error over the samples (radians).
    pub rms: f64,
    /// How many samples were taken (evenly spaced over `x0 ..= x1`).
    pub samples: usize,
    /// How many of them the linkage cannot be assembled at (on its closure). They are left
    /// out of `max` and `rms`; a design with any is not usable over the range.
    pub unassembled: usize,
}

/// The structural error of `generator` against `f` over the range of `map`, from `samples`
/// evenly spaced arguments: at each the linkage is analysed by intersecting circles (on the
/// closure of its first precision point) and its output angle compared with `map.psi(f(x))`.
///
/// Errors: fewer than two samples; `f` not finite at a sample.
///
/// ```
/// use kinloop_runtime::deg;
/// use kinloop_runtime::synthesis::classical::{FunctionMap, chebyshev_points, freudenstein, structural_error};
/// let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0))?;
/// let g = freudenstein(&map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0)?)?)?;
/// let e = structural_error(&g, &map, f64::log10, 201)?;
/// assert_eq!(e.unassembled, 0);
/// assert!(e.max < deg(1.0)); // under a degree over the whole range
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
    let (mut max, mut at_x, mut sum_sq, mut assembled) = (0.0f64, map.x0, 0.0, 0usize);
    for i in 0..samples {
        let x = map.x0 + (map.x1 - map.x0) * i as f64 / (samples - 1) as f64;
        let y = f(x);
        if !y.is_finite() {
            return Err(ClassicalError::NonFinite { what: format!("f({x})"), value: y });
        }
        let Some(psi) = generator.output_angle(map.phi(x)) else { continue };
        let e = angle_difference(psi, map.psi(y)).abs();
        assembled += 1;
        sum_sq += e * e;
        if e > max {
            (max, at_x) = (e, x);
        }
    }
    let rms = if assembled > 0 { (sum_sq / assembled as f64).sqrt() } else { 0.0 };
    let max_y = max * ((map.y1 - map.y0) / map.dpsi).abs();
    Ok(StructuralError { max, at_x, max_y, rms, samples, unassembled: samples - assembled })
}
