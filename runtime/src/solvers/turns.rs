//! Angles on their turns, without libm: an angle moved by whole turns to a guess's turn
//! ([`unwrap_to_turn`]), reduced to `[-π, π]` ([`reduce_turn`]), or turned by a half turn
//! ([`half_turn_if`]). Every block solver keeps its angles on their guesses' turns with these
//! (the closed forms' roots, Newton's iterates and restarts), and the generated code calls them.

use core::f64::consts::{PI, TAU};

/// `x` rounded to the nearest integer (ties to even) by the addition and subtraction of
/// `1.5 · 2^52`, where the spacing of doubles is 1: two additions, no libm call and no integer
/// conversion. Exact for `|x| < 2^51`; beyond that the value is meaningless as a number of turns
/// anyway (a large number near `x`: the precision check of [`check_closed`](super::closed::check_closed) rejects such angles).
/// A NaN stays NaN.
#[inline]
pub(crate) fn whole_turns(x: f64) -> f64 {
    const ROUND: f64 = 6_755_399_441_055_744.0;
    (x + ROUND) - ROUND
}

/// `q` moved by whole turns to the turn of `guess` (the nearest angle `q + 2πk` to `guess`).
///
/// ```
/// use kinloop_runtime::generated::unwrap_to_turn;
/// use std::f64::consts::TAU;
/// assert!((unwrap_to_turn(0.5, 0.4 + 3.0 * TAU) - (0.5 + 3.0 * TAU)).abs() < 1e-12);
/// assert_eq!(unwrap_to_turn(0.5, 0.4), 0.5);
/// ```
#[inline]
pub fn unwrap_to_turn(q: f64, guess: f64) -> f64 {
    q + TAU * whole_turns((guess - q) * (1.0 / TAU))
}

/// The angle `q` of `[-π, π]` turned by a half turn when `flip` holds, kept in `[-π, π]`: the
/// angle of the reversed direction. A polar length's angle is `atan2` of its direction before
/// the length's sign is known (the call need not wait for the sign, nor for the direction's
/// normalisation); reversing it costs one rounding of `π`'s size, below `4.5e-16` rad.
///
/// ```
/// use kinloop_runtime::generated::half_turn_if;
/// use std::f64::consts::PI;
/// assert_eq!(half_turn_if(0.5, false), 0.5);
/// assert!((half_turn_if(0.5, true) - (0.5 - PI)).abs() < 1e-15);
/// assert!((half_turn_if(-3.0, true) - (PI - 3.0)).abs() < 1e-15);
/// ```
#[inline(always)]
pub fn half_turn_if(q: f64, flip: bool) -> f64 {
    if flip { q - PI.copysign(q) } else { q }
}

/// `g` reduced to `[-π, π]` (the signs of its sine and cosine without libm).
#[inline]
pub fn reduce_turn(g: f64) -> f64 {
    g - TAU * whole_turns(g * (1.0 / TAU))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_turns_round_to_the_nearest_integer() {
        for (x, want) in [(0.4, 0.0), (0.6, 1.0), (-0.6, -1.0), (-2.3, -2.0), (1e15 + 0.75, 1e15 + 1.0), (-7.0, -7.0)] {
            assert_eq!(whole_turns(x), want, "{x}");
        }
        assert_eq!(whole_turns(-0.2), 0.0);
        assert!(whole_turns(f64::NAN).is_nan());
        // Far beyond any representable turn count: still a large number, never a small one.
        assert!(whole_turns(1e300) > 1e299 && whole_turns(-1e300) < -1e299);
    }

    /// The half turn of an angle is the angle of the reversed direction (libm's `atan2` of the
    /// negated components, exact negations) to the rounding of one addition of `π`'s size, in
    /// `[-π, π]`, for directions all round the circle and at scales where the direction's
    /// squares under- or overflow.
    #[test]
    fn the_half_turn_is_the_angle_of_the_reversed_direction() {
        for scale in [1.0, 1e-300, 5e-324 * 1e3, 1e300, f64::MAX / 4.0] {
            for i in 0..=96 {
                let t = -PI + TAU * i as f64 / 96.0;
                let (y, x) = (scale * t.sin(), scale * t.cos());
                let reversed = half_turn_if(y.atan2(x), true);
                let want = (-y).atan2(-x);
                // Both in `[-π, π]`; at `±π` either sign names the same direction.
                let d = (reversed - want).abs();
                assert!(d <= 4.5e-16 || (TAU - d).abs() <= 4.5e-16, "{scale:e} {t}: {reversed} {want}");
                assert!(reversed.abs() <= PI, "{reversed}");
                assert_eq!(half_turn_if(y.atan2(x), false), y.atan2(x));
            }
        }
        assert!(half_turn_if(f64::NAN, true).is_nan());
    }
}
