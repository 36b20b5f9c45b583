//! Planar vectors of named outputs, with the arithmetic of the language's vectors.

use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A planar vector: an output point's coordinates, or their analogs.
///
/// For a single-input mechanism the analogs of a point are again `Vec2<f64>`; for several inputs
/// each component holds one partial derivative per input.
///
/// `Vec2<f64>` has the arithmetic of the `mechanism!` language's vectors (`+`, `-`, a scalar
/// factor, `norm`, `dot`, `cross`, `angle`) and converts to and from `nalgebra::Vector2<f64>`,
/// `[f64; 2]` and, with the feature `mint`, `mint::Vector2<f64>`.
///
/// ```
/// use kinloop_runtime::Vec2;
/// let v = Vec2 { x: 3.0, y: 4.0 };
/// assert_eq!(v.norm(), 5.0);
/// assert!((v.angle() - 4f64.atan2(3.0)).abs() < 1e-15);
/// let w = Vec2::new(1.0, -2.0);
/// assert_eq!(v + w, Vec2::new(4.0, 2.0));
/// assert_eq!(v - w, Vec2::new(2.0, 6.0));
/// assert_eq!(-w * 2.0, Vec2::new(-2.0, 4.0));
/// assert_eq!(2.0 * w, w * 2.0);
/// assert_eq!(v.dot(w), 3.0 - 8.0);
/// assert_eq!(v.cross(w), 3.0 * -2.0 - 4.0 * 1.0);
/// let n: kinloop_runtime::nalgebra::Vector2<f64> = v.into();
/// assert_eq!(Vec2::from(n), v);
/// ```
///
/// With the feature `serde` a vector is `{"x": .., "y": ..}` for any component type that
/// serializes, and every `f64` within reads back as it was written, bit for bit: a
/// self-describing format such as JSON, which has no NaN nor infinity, gets those as the strings
/// `"inf"`, `"-inf"` and `"NaN"`, `"-NaN"` or `"NaN(0x..)"` (a NaN with its sign and payload)
/// where it wrote `null`, which did not read back, and reads a number, such a string, or `null`
/// as NaN; a compact binary format holds the `f64` itself. The
/// components pass through an adapter of the format rather than a trait of their type: the
/// structs `mechanism!` generates hold `Vec2<T>` for any `T` they are given, with no more known of
/// it than that it serializes, and `Vec2<[f64; N]>` or a user's own `T` keep serializing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(bound(serialize = "T: serde::Serialize", deserialize = "T: serde::Deserialize<'de>"))
)]
pub struct Vec2<T = f64> {
    /// X component.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub x: T,
    /// Y component.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub y: T,
}

impl<T> Vec2<T> {
    /// The vector `(x, y)`.
    pub const fn new(x: T, y: T) -> Self {
        Vec2 { x, y }
    }
}

impl Vec2<f64> {
    /// Magnitude `sqrt(x^2 + y^2)` (e.g. the speed of a point from its velocity), without
    /// overflow or underflow for any finite components.
    pub fn norm(&self) -> f64 {
        self.x.hypot(self.y)
    }

    /// Direction `atan2(y, x)` in radians, counter-clockwise from the X axis, in `(-pi, pi]`.
    pub fn angle(&self) -> f64 {
        self.y.atan2(self.x)
    }

    /// Scalar product `x1 x2 + y1 y2`.
    pub fn dot(&self, other: Vec2) -> f64 {
        self.x * other.x + self.y * other.y
    }

    /// The z component of the cross product, `x1 y2 - y1 x2` (positive when `other` lies
    /// counter-clockwise of `self`).
    pub fn cross(&self, other: Vec2) -> f64 {
        self.x * other.y - self.y * other.x
    }
}

impl Add for Vec2<f64> {
    type Output = Vec2<f64>;
    fn add(self, rhs: Vec2<f64>) -> Vec2<f64> {
        Vec2 { x: self.x + rhs.x, y: self.y + rhs.y }
    }
}

impl Sub for Vec2<f64> {
    type Output = Vec2<f64>;
    fn sub(self, rhs: Vec2<f64>) -> Vec2<f64> {
        Vec2 { x: self.x - rhs.x, y: self.y - rhs.y }
    }
}

impl AddAssign for Vec2<f64> {
    fn add_assign(&mut self, rhs: Vec2<f64>) {
        *self = *self + rhs;
    }
}

impl SubAssign for Vec2<f64> {
    fn sub_assign(&mut self, rhs: Vec2<f64>) {
        *self = *self - rhs;
    }
}

impl Neg for Vec2<f64> {
    type Output = Vec2<f64>;
    fn neg(self) -> Vec2<f64> {
        Vec2 { x: -self.x, y: -self.y }
    }
}

impl Mul<f64> for Vec2<f64> {
    type Output = Vec2<f64>;
    fn mul(self, k: f64) -> Vec2<f64> {
        Vec2 { x: self.x * k, y: self.y * k }
    }
}

impl Mul<Vec2<f64>> for f64 {
    type Output = Vec2<f64>;
    fn mul(self, v: Vec2<f64>) -> Vec2<f64> {
        v * self
    }
}

impl<T> From<[T; 2]> for Vec2<T> {
    fn from([x, y]: [T; 2]) -> Self {
        Vec2 { x, y }
    }
}

impl<T> From<Vec2<T>> for [T; 2] {
    fn from(v: Vec2<T>) -> Self {
        [v.x, v.y]
    }
}

impl From<nalgebra::Vector2<f64>> for Vec2<f64> {
    fn from(v: nalgebra::Vector2<f64>) -> Self {
        Vec2 { x: v.x, y: v.y }
    }
}

impl From<Vec2<f64>> for nalgebra::Vector2<f64> {
    fn from(v: Vec2<f64>) -> Self {
        nalgebra::Vector2::new(v.x, v.y)
    }
}

#[cfg(feature = "mint")]
impl From<mint::Vector2<f64>> for Vec2<f64> {
    fn from(v: mint::Vector2<f64>) -> Self {
        Vec2 { x: v.x, y: v.y }
    }
}

#[cfg(feature = "mint")]
impl From<Vec2<f64>> for mint::Vector2<f64> {
    fn from(v: Vec2<f64>) -> Self {
        mint::Vector2 { x: v.x, y: v.y }
    }
}

#[cfg(test)]
mod tests {
    use super::Vec2;

    /// `cross` and `dot` against the polar forms `|a||b| sin(tb - ta)` and `|a||b| cos(tb - ta)`,
    /// and `angle` against the construction angle.
    #[test]
    fn products_match_polar_forms() {
        for k in 0..24 {
            let (ta, tb) = (0.3 + 0.27 * k as f64, -1.1 + 0.41 * k as f64);
            let (ra, rb) = (2.5, 0.75);
            let a = Vec2::new(ra * ta.cos(), ra * ta.sin());
            let b = Vec2::new(rb * tb.cos(), rb * tb.sin());
            // Components of size ~2.5 carry rounding ~1e-15; the products ~2 ulp of |a||b|.
            assert!((a.cross(b) - ra * rb * (tb - ta).sin()).abs() < 1e-14);
            assert!((a.dot(b) - ra * rb * (tb - ta).cos()).abs() < 1e-14);
            let wrapped = (ta + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
            assert!((a.angle() - wrapped).abs() < 1e-14, "{} vs {wrapped}", a.angle());
            assert!((a.norm() - ra).abs() < 1e-15 * 4.0);
        }
    }

    #[test]
    fn norm_survives_large_and_small_components() {
        assert_eq!(Vec2::new(3e300, 4e300).norm(), 5e300);
        assert_eq!(Vec2::new(3e-300, 4e-300).norm(), 5e-300);
    }

    #[cfg(feature = "mint")]
    #[test]
    fn mint_round_trip() {
        let v = Vec2::new(1.5, -2.0);
        let m: mint::Vector2<f64> = v.into();
        assert_eq!((m.x, m.y), (1.5, -2.0));
        assert_eq!(Vec2::from(m), v);
    }
}
