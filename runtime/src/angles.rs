//! Degrees at the boundary: every angle in kinloop is in radians; these convert what a person
//! writes or reads.

/// An angle given in degrees, in radians: `deg(30.0)` is `pi / 6`. The same conversion as the
/// declaration's `deg(30)`, bit for bit (`degrees * (pi / 180)`).
///
/// ```
/// use kinloop_runtime::{deg, to_deg};
/// assert_eq!(deg(180.0), std::f64::consts::PI);
/// assert!((to_deg(deg(30.0)) - 30.0).abs() < 1e-13);
/// ```
pub fn deg(degrees: f64) -> f64 {
    degrees * (std::f64::consts::PI / 180.0)
}

/// An angle given in radians, in degrees (for printing and reading results).
pub fn to_deg(radians: f64) -> f64 {
    radians * (180.0 / std::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact values: multiples of 90 degrees against the constants, and `to_deg` against the
    /// standard library's independent `to_degrees`.
    #[test]
    fn conversions_match_known_angles() {
        use std::f64::consts::{FRAC_PI_2, FRAC_PI_6, PI, TAU};
        assert_eq!(deg(90.0), FRAC_PI_2);
        assert_eq!(deg(360.0), TAU);
        assert_eq!(deg(-180.0), -PI);
        assert!((deg(30.0) - FRAC_PI_6).abs() <= f64::EPSILON * FRAC_PI_6);
        for k in -20..=20 {
            let r = 0.37 * k as f64;
            assert!((to_deg(r) - r.to_degrees()).abs() <= 2.0 * f64::EPSILON * r.to_degrees().abs());
        }
    }
}
