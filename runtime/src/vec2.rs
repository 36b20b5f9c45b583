//! Planar vectors of named outputs.

/// A planar vector: an output point's coordinates, or their analogs.
///
/// For a single-input mechanism the analogs of a point are again `Vec2<f64>`; for several inputs
/// each component holds one partial derivative per input.
///
/// ```
/// use kinloop_runtime::Vec2;
/// let v = Vec2 { x: 3.0, y: 4.0 };
/// assert_eq!(v.norm(), 5.0);
/// assert!((v.angle() - 4f64.atan2(3.0)).abs() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec2<T = f64> {
    /// X component.
    pub x: T,
    /// Y component.
    pub y: T,
}

impl Vec2<f64> {
    /// Magnitude `sqrt(x^2 + y^2)` (e.g. the speed of a point from its velocity).
    pub fn norm(&self) -> f64 {
        self.x.hypot(self.y)
    }

    /// Direction `atan2(y, x)` in radians, counter-clockwise from the X axis.
    pub fn angle(&self) -> f64 {
        self.y.atan2(self.x)
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
