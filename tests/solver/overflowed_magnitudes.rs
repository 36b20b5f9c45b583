//! The whole-system Newton solve that rescues a mechanism beyond the closed forms' sizes
//! (`kinloop::__gen::whole_position`, the compiled mechanism's and the run-time model's)
//! refuses equations whose terms are too large for `f64` as a block's Newton does: their
//! magnitude overflowed, and with it (or not) their residual.

use kinloop::__gen::{AtLimit, BlockEval, BlockFailure, whole_position};
use kinloop::NewtonConfig;

/// A slider `x` at distance `c` from a pivot by the square of that distance, `x^2 - c^2`, with
/// its Jacobian; its magnitude `x^2 + c^2` and the unit of `x`, that over the derivative's
/// magnitude `2 |x|`, as the generated code makes them.
fn squared(c: f64, x: f64) -> (f64, f64, f64, f64) {
    let m = x * x + c * c;
    (x * x - c * c, 2.0 * x, m, m / (2.0 * x.abs()))
}

/// At `c = 1e150` the squares are normal and the root is found to rounding. At `1.2e154` from
/// `0.7 c` the magnitude `x^2 + c^2` overflows and the residual does not (`-7.4e307`); at
/// `1e160` and `1e300` the squares overflow and the residual is NaN (`inf - inf`): the solve
/// fails as `BlockFailure::Overflow` (the error the rescue reports as the equation's terms too
/// large for `f64`), from guesses on either side. It failed as an expression outside its domain
/// (`NonFinite`) at `1e160` and `1e300`, and at `1.2e154` judged its residual, a squared length,
/// against the row sum `2 |x|` that replaced its magnitude, a length.
#[test]
fn the_whole_system_solve_refuses_a_magnitude_too_large_for_f64() {
    let cfg = NewtonConfig::default();
    for g in [0.7, 1.3] {
        for c in [1e150, 1.2e154, 1e160, 1e300] {
            let x0 = [g * c];
            let (f, _, scale, unit) = squared(c, x0[0]);
            // The cases as described: which magnitudes and residuals overflow at the guess.
            assert_eq!(scale.is_finite(), c == 1e150, "{c:e}, {g}");
            assert_eq!(f.is_finite(), c == 1e150 || (c == 1.2e154 && g < 1.0), "{c:e}, {g}");
            let at = |q: &[f64; 1], e: &mut BlockEval<1, 0>| {
                let (f, j, _, _) = squared(c, q[0]);
                (e.f, e.j) = ([f], [[j]]);
            };
            match whole_position(&x0, [scale], [unit], [false], &cfg, AtLimit::Singular, &[], at) {
                Ok((q, _)) => assert!(c == 1e150 && (q[0] - c).abs() <= 2.0 * f64::EPSILON * c, "{c:e}: {q:?}"),
                Err(fail) => assert!(c > 1e150 && fail == BlockFailure::Overflow { row: 0 }, "{c:e}, {g}: {fail:?}"),
            }
        }
    }
}
