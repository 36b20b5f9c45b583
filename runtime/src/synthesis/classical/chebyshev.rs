//! Chebyshev spacing of precision points.
//!
//! A linkage that meets a function exactly at `n` precision points deviates from it in between
//! by an error that vanishes at those points. Spacing them at the zeros of the Chebyshev
//! polynomial of degree `n`, mapped onto the range, is the classical first choice: for an error
//! that behaves like a polynomial of degree `n` in `x` it makes the largest deviation over the
//! range the smallest, the deviations at the ends and between the points coming out about equal.

use super::error::{ClassicalError, finite};

/// `x1 - x0` as `(span, factor)` with `span * factor` the difference: ends far apart near the
/// largest f64 (`-1e308` to `1e308`) overflow `x1 - x0`, so the span is halved then, which is
/// exact there, and the factor 2. A point measured from the nearer end takes a fraction of at
/// most a half times the factor, so no product overflows.
pub(super) fn span_of(x0: f64, x1: f64) -> (f64, f64) {
    if (x1 - x0).is_finite() { (x1 - x0, 1.0) } else { (0.5 * x1 - 0.5 * x0, 2.0) }
}

/// `n` precision points over `[x0, x1]` at Chebyshev spacing, in increasing order when
/// `x0 < x1`:
///
/// `x_j = (x0 + x1) / 2 - (x1 - x0) / 2 * cos((2 j - 1) pi / (2 n))`, `j = 1 ..= n`.
///
/// Each point is computed from the end it lies nearer, as `x0 + (x1 - x0) sin^2(theta / 2)` or
/// `x1 - (x1 - x0) cos^2(theta / 2)` (the same point): one rounding from that end, so the points
/// stay inside the range and distinct as long as the doubles there allow.
///
/// Errors (`BadRange`): `n == 0` or more than memory holds, `x0 == x1`, or a range too narrow
/// for `n` distinct doubles at Chebyshev spacing (points that are not distinct are no precision
/// points); `NonFinite`: a bound not finite.
///
/// ```
/// use kinloop_runtime::synthesis::classical::chebyshev_points;
/// let x = chebyshev_points(3, 1.0, 2.0)?;
/// let half_root3 = 3f64.sqrt() / 2.0;
/// assert!((x[0] - (1.5 - 0.5 * half_root3)).abs() < 1e-15);
/// assert!((x[1] - 1.5).abs() < 1e-15);
/// assert!((x[2] - (1.5 + 0.5 * half_root3)).abs() < 1e-15);
/// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
/// ```
pub fn chebyshev_points(n: usize, x0: f64, x1: f64) -> Result<Vec<f64>, ClassicalError> {
    finite(x0, || "the start of the range".into())?;
    finite(x1, || "the end of the range".into())?;
    if n == 0 {
        return Err(ClassicalError::BadRange { what: "number of precision points", why: "it is zero".into() });
    }
    // More points than a vector can hold panicked in the allocator (a capacity overflow).
    if n > isize::MAX as usize / std::mem::size_of::<f64>() {
        return Err(ClassicalError::BadRange {
            what: "number of precision points",
            why: format!("{n}: too many to hold in memory"),
        });
    }
    if x0 == x1 {
        return Err(ClassicalError::BadRange { what: "range", why: format!("it is empty ({x0} to {x1})") });
    }
    let (span, factor) = span_of(x0, x1);
    // From the midpoint (`mid - half cos(theta)`) the midpoint's own rounding moved every point:
    // over `[1, 1 + eps]` the two points came out `1 - eps / 2`, outside the range, and `1`.
    let x: Vec<f64> = (1..=n)
        .map(|j| {
            let theta = (2 * j - 1) as f64 * std::f64::consts::PI / (2 * n) as f64;
            let (sin, cos) = (0.5 * theta).sin_cos();
            if 2 * j - 1 <= n { x0 + span * (factor * sin * sin) } else { x1 - span * (factor * cos * cos) }
        })
        .collect();
    // Rounding is monotone, so the points are in order; over a range of too few doubles some
    // come out equal (all `0` over `[0, 5e-324]`).
    let distinct = x.windows(2).all(|w| if x0 < x1 { w[0] < w[1] } else { w[0] > w[1] });
    if !distinct {
        return Err(ClassicalError::BadRange {
            what: "range",
            why: format!("{x0} to {x1} is too narrow for {n} distinct points at Chebyshev spacing"),
        });
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The points are the roots of the Chebyshev polynomial `T_n` mapped onto the range: mapped
    /// back to `[-1, 1]`, `T_n(t) = cos(n acos t)` vanishes there (a check through the
    /// polynomial's definition, not through the spacing formula).
    #[test]
    fn points_are_the_mapped_roots_of_the_chebyshev_polynomial() {
        for n in 1..=9 {
            let x = chebyshev_points(n, -3.0, 5.0).unwrap();
            assert_eq!(x.len(), n);
            for (j, &xj) in x.iter().enumerate() {
                let t = (xj - 1.0) / 4.0;
                let tn = (n as f64 * t.acos()).cos();
                assert!(tn.abs() < 1e-13, "n {n}, point {j}: T_n = {tn}");
                assert!(j == 0 || xj > x[j - 1], "increasing");
                assert!((-3.0..=5.0).contains(&xj));
            }
        }
    }

    #[test]
    fn an_inverted_range_gives_the_points_in_decreasing_order() {
        let up = chebyshev_points(4, 0.0, 1.0).unwrap();
        let down = chebyshev_points(4, 1.0, 0.0).unwrap();
        for (u, d) in up.iter().zip(down.iter()) {
            assert!((u - (1.0 - d)).abs() < 1e-15);
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(matches!(chebyshev_points(0, 0.0, 1.0), Err(ClassicalError::BadRange { .. })));
        assert!(matches!(chebyshev_points(3, 1.0, 1.0), Err(ClassicalError::BadRange { .. })));
        assert!(matches!(chebyshev_points(3, f64::NAN, 1.0), Err(ClassicalError::NonFinite { .. })));
        assert!(matches!(chebyshev_points(3, 0.0, f64::INFINITY), Err(ClassicalError::NonFinite { .. })));
    }

    /// A range too narrow for `n` distinct doubles at Chebyshev spacing is an error saying so
    /// (the points came out equal: all `0` over `[0, 5e-324]`), at any magnitude of the range;
    /// a range just wide enough gives distinct points, inside it and in order (two over
    /// `[1, 1 + eps]` came out `1 - eps / 2`, outside it, and `1`).
    #[test]
    fn a_range_too_narrow_for_distinct_points_is_an_error() {
        let tiny = f64::from_bits(1); // 5e-324, the smallest double
        for (n, x0, x1) in [
            (3, 0.0, tiny),
            (3, tiny, 0.0),
            (3, 1.0, 1.0 + f64::EPSILON),
            (3, 1e300, 1e300 * (1.0 + f64::EPSILON)),
            (1000, 1.0, 1.0 + 1e-13),
        ] {
            let e = chebyshev_points(n, x0, x1).unwrap_err();
            assert!(
                matches!(&e, ClassicalError::BadRange { why, .. } if why.contains("too narrow")),
                "{n} over {x0:e} to {x1:e}: {e:?}"
            );
        }
        let wide_enough = [
            (3, 0.0, 4.0 * tiny),
            (3, 4.0 * tiny, 0.0),
            (2, 1.0, 1.0 + f64::EPSILON),
            (3, 1.0, 1.0 + 2.0 * f64::EPSILON),
        ];
        for (n, x0, x1) in wide_enough {
            let x = chebyshev_points(n, x0, x1).unwrap();
            let inside = |v: &f64| (x0.min(x1)..=x0.max(x1)).contains(v);
            let ordered = x.windows(2).all(|w| if x0 < x1 { w[0] < w[1] } else { w[0] > w[1] });
            assert!(ordered && x.iter().all(inside), "{n} over {x0:e} to {x1:e}: {x:?}");
        }
    }

    /// A count of points no vector holds is an error, not a capacity-overflow panic.
    #[test]
    fn too_many_points_are_an_error() {
        let e = chebyshev_points(usize::MAX, 0.0, 1.0).unwrap_err();
        assert!(matches!(&e, ClassicalError::BadRange { why, .. } if why.contains("too many")), "{e:?}");
    }

    /// Ends whose difference overflows give the points, not infinities.
    #[test]
    fn a_range_wider_than_f64_gives_finite_points() {
        let x = chebyshev_points(3, -1e308, 1e308).unwrap();
        let half_root3 = 3f64.sqrt() / 2.0;
        let scaled: Vec<f64> = x.iter().map(|v| v / 1e308).collect();
        assert!((scaled[0] + half_root3).abs() < 1e-15 && scaled[1].abs() < 1e-15, "{x:?}");
        assert!((scaled[2] - half_root3).abs() < 1e-15, "{x:?}");
        let x = chebyshev_points(2, -f64::MAX, f64::MAX).unwrap();
        assert!(x.iter().all(|v| (v.abs() / f64::MAX - 0.5f64.sqrt()).abs() < 1e-15) && x[0] < 0.0, "{x:?}");
    }
}
