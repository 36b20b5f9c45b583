//! A function `y = f(x)` as the angles of a linkage: the input turns in proportion to `x`, the
//! output in proportion to `y`.

use super::error::{ClassicalError, finite};
use super::freudenstein::PrecisionPoint;

/// The linear scales that turn a function `y = f(x)` over `x0 <= x <= x1` into the angles of a
/// function generator:
///
/// `phi = phi0 + (x - x0) / (x1 - x0) * dphi`, `psi = psi0 + (y - y0) / (y1 - y0) * dpsi`,
///
/// with `y0 = f(x0)` and `y1 = f(x1)`, so that the input turns through `dphi` and the output
/// through `dpsi` while `x` runs over its range (a negative `dphi` or `dpsi` turns that link
/// clockwise). Angles in radians, measured as in [`freudenstein`](super::freudenstein()).
///
/// ```
/// use kinloop_runtime::deg;
/// use kinloop_runtime::synthesis::classical::FunctionMap;
/// let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0))?;
/// assert!((map.phi(1.5) - deg(105.0)).abs() < 1e-15);
/// // log10(2) is the end of the output range: psi0 + dpsi.
/// assert!((map.psi(2f64.log10()) - deg(180.0)).abs() < 1e-15);
/// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FunctionMap {
    /// Start of the function's argument range.
    pub x0: f64,
    /// End of the argument range.
    pub x1: f64,
    /// `f(x0)`.
    pub y0: f64,
    /// `f(x1)`.
    pub y1: f64,
    /// Input angle at `x0`.
    pub phi0: f64,
    /// Input rotation over the range.
    pub dphi: f64,
    /// Output angle at `y0`.
    pub psi0: f64,
    /// Output rotation over the range.
    pub dpsi: f64,
}

impl FunctionMap {
    /// The map of `f` over `x0 ..= x1` onto input angles `phi0 ..= phi0 + dphi` and output
    /// angles `psi0 ..= psi0 + dpsi`.
    ///
    /// Errors: a value (or `f` at an end) not finite; an empty range of `x` or of `y`
    /// (`f(x0) == f(x1)`), or one whose width overflows; a zero rotation.
    pub fn new(
        f: impl Fn(f64) -> f64,
        x0: f64,
        x1: f64,
        phi0: f64,
        dphi: f64,
        psi0: f64,
        dpsi: f64,
    ) -> Result<FunctionMap, ClassicalError> {
        for (value, what) in [(x0, "x0"), (x1, "x1"), (phi0, "phi0"), (dphi, "dphi"), (psi0, "psi0"), (dpsi, "dpsi")] {
            finite(value, || format!("the function map's `{what}`"))?;
        }
        let y0 = finite(f(x0), || format!("f(x0) = f({x0})"))?;
        let y1 = finite(f(x1), || format!("f(x1) = f({x1})"))?;
        let empty = |what, why: String| Err(ClassicalError::BadRange { what, why });
        if x0 == x1 {
            return empty("range of x", format!("it is empty ({x0} to {x1})"));
        }
        if y0 == y1 {
            return empty("range of y", format!("f(x0) = f(x1) = {y0}: the output would not move"));
        }
        // Ranges wider than f64 holds (`-1e308` to `1e308`) made `x1 - x0` infinite and mapped
        // every argument onto `phi0` (every value onto `psi0`).
        for (width, what, ends) in [(x1 - x0, "range of x", (x0, x1)), (y1 - y0, "range of y", (y0, y1))] {
            if !width.is_finite() {
                return empty(what, format!("{} to {} is wider than f64 holds", ends.0, ends.1));
            }
        }
        if dphi == 0.0 || dpsi == 0.0 {
            return empty("rotation", "the input and the output must both turn (dphi, dpsi not zero)".into());
        }
        Ok(FunctionMap { x0, x1, y0, y1, phi0, dphi, psi0, dpsi })
    }

    /// The input angle for the argument `x`.
    pub fn phi(&self, x: f64) -> f64 {
        self.phi0 + (x - self.x0) / (self.x1 - self.x0) * self.dphi
    }

    /// The output angle for the function value `y`.
    pub fn psi(&self, y: f64) -> f64 {
        self.psi0 + (y - self.y0) / (self.y1 - self.y0) * self.dpsi
    }

    /// The function value an output angle `psi` stands for (the inverse of [`psi`](Self::psi)).
    pub fn y(&self, psi: f64) -> f64 {
        self.y0 + (psi - self.psi0) / self.dpsi * (self.y1 - self.y0)
    }

    /// The precision points `(phi(x), psi(f(x)))` for the arguments `xs` (e.g. from
    /// [`chebyshev_points`](super::chebyshev_points)).
    ///
    /// Errors: an argument, or `f` there, not finite.
    pub fn precision_points(&self, f: impl Fn(f64) -> f64, xs: &[f64]) -> Result<Vec<PrecisionPoint>, ClassicalError> {
        xs.iter()
            .enumerate()
            .map(|(i, &x)| {
                finite(x, || format!("the argument of precision point {i}"))?;
                let y = finite(f(x), || format!("f at precision point {i} (x = {x})"))?;
                Ok(PrecisionPoint { phi: self.phi(x), psi: self.psi(y) })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map() -> FunctionMap {
        FunctionMap::new(|x| x * x, 1.0, 3.0, 0.5, 2.0, -1.0, -0.75).unwrap()
    }

    /// The ends of the ranges map onto the ends of the rotations; `y` inverts `psi`.
    #[test]
    fn ends_map_onto_ends_and_y_inverts_psi() {
        let m = map();
        assert_eq!((m.y0, m.y1), (1.0, 9.0));
        assert_eq!(m.phi(1.0), 0.5);
        assert_eq!(m.phi(3.0), 2.5);
        assert_eq!(m.psi(1.0), -1.0);
        assert_eq!(m.psi(9.0), -1.75);
        for y in [1.0, 2.5, 7.0] {
            assert!((m.y(m.psi(y)) - y).abs() < 1e-15);
        }
        let p = m.precision_points(|x| x * x, &[2.0]).unwrap();
        assert_eq!(p, vec![PrecisionPoint { phi: 1.5, psi: -1.0 - 3.0 / 8.0 * 0.75 }]);
    }

    #[test]
    fn bad_input_is_an_error() {
        let bad = |r: Result<FunctionMap, ClassicalError>| r.unwrap_err();
        assert!(matches!(
            bad(FunctionMap::new(|x| x, f64::NAN, 1.0, 0.0, 1.0, 0.0, 1.0)),
            ClassicalError::NonFinite { .. }
        ));
        assert!(matches!(
            bad(FunctionMap::new(|x| x, 0.0, 1.0, 0.0, f64::INFINITY, 0.0, 1.0)),
            ClassicalError::NonFinite { .. }
        ));
        assert!(matches!(
            bad(FunctionMap::new(f64::ln, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0)),
            ClassicalError::NonFinite { .. }
        ));
        assert!(matches!(bad(FunctionMap::new(|x| x, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0)), ClassicalError::BadRange { .. }));
        assert!(matches!(
            bad(FunctionMap::new(|_| 2.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0)),
            ClassicalError::BadRange { .. }
        ));
        assert!(matches!(bad(FunctionMap::new(|x| x, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)), ClassicalError::BadRange { .. }));
        // Ranges whose width overflows: every argument mapped onto phi0, every value onto psi0.
        for (f, x1, what) in [(1.0, 1e308, "range of x"), (1e308, 1.0, "range of y")] {
            let r = FunctionMap::new(|x| f * x, -x1, x1, 0.0, 1.0, 0.0, 1.0);
            assert!(matches!(&r, Err(ClassicalError::BadRange { what: w, .. }) if *w == what), "{r:?}");
        }
        let m = map();
        assert!(matches!(m.precision_points(|x| x * x, &[f64::NAN]), Err(ClassicalError::NonFinite { .. })));
        assert!(matches!(m.precision_points(|x| 1.0 / (x - 2.0), &[2.0]), Err(ClassicalError::NonFinite { .. })));
    }
}
