//! The whole-system Newton solve that rescues a mechanism beyond the closed forms' sizes
//! (`kinloop::__gen::whole_position`, the compiled mechanism's and the run-time model's) judges
//! its residuals in the equations' magnitudes as a block's Newton does, and refuses those too
//! small for `f64` to judge to the tolerance.

use kinloop::__gen::{AtLimit, BlockEval, BlockFailure, whole_position};
use kinloop::NewtonConfig;

/// A slider `x` at distance `c` from a pivot by the square of that distance, `x^2 - c^2`, with
/// its Jacobian; its magnitude `x^2 + c^2` and the unit of `x`, that over the derivative's
/// magnitude `2 |x|`, as the generated code makes them.
fn squared(c: f64, x: f64) -> (f64, f64, f64, f64) {
    let m = x * x + c * c;
    (x * x - c * c, 2.0 * x, m, m / (2.0 * x.abs()))
}

/// At `c = 1e-150` the squares are normal and the root is found to rounding. At `1e-160` they
/// are subnormal (the magnitude `2.7e-320`, its residual known to `2e-4` of it) and at `1e-200`
/// zero: the solve fails as `BlockFailure::Underflow` (the error the rescue reports). It
/// returned `x` `1e-4` of itself off at `1e-160`, and the guess unchanged at `1e-200`.
#[test]
fn the_whole_system_solve_refuses_a_magnitude_too_small_to_judge() {
    let cfg = NewtonConfig::default();
    for c in [1e-150, 1e-160, 1e-200] {
        let g = [1.3 * c];
        let (_, _, scale, unit) = squared(c, g[0]);
        let at = |q: &[f64; 1], e: &mut BlockEval<1, 0>| {
            let (f, j, _, _) = squared(c, q[0]);
            (e.f, e.j) = ([f], [[j]]);
        };
        match whole_position(&g, [scale], [unit], [false], &cfg, AtLimit::Singular, &[], at) {
            Ok((q, _)) => assert!(c == 1e-150 && (q[0] - c).abs() <= 2.0 * f64::EPSILON * c, "{c:e}: {q:?}"),
            Err(fail) => assert!(c < 1e-150 && matches!(fail, BlockFailure::Underflow { .. }), "{c:e}: {fail:?}"),
        }
    }
}
