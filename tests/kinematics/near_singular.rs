//! Accuracy beside a singular position, as the crate's documentation states it: with the
//! smallest pivot ratio `p` of a state, positions lose accuracy as `eps / p`, velocity analogs
//! as `eps / p^2` and acceleration analogs as `eps / p^3` (the solution's own conditioning: the
//! rounding of the data moves the solution by that much, whatever the solver).
//!
//! The reference is exact: a slider-crank of rod equal to its crank (`r = l`, no offset) has
//! the branch `psi = phi`, `x = 0` (`dpsi = 1`, `d2psi = 0`), crossed at `phi = pi / 2` by the
//! branch `psi = pi - phi` (a change point, where the analogs' block is singular).

use kinloop_fixtures::linkages::{SliderCrank, SliderCrankUnknowns};
use std::f64::consts::FRAC_PI_2;

#[test]
fn analogs_lose_accuracy_as_the_pivot_ratio_s_powers() {
    let eps = f64::EPSILON;
    for scale in [1.0, 1e-3, 1e3] {
        let m = SliderCrank { r: scale, l: scale, e: 0.0 };
        for delta in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7] {
            let phi = FRAC_PI_2 - delta;
            let s = m.kinematics(phi, &SliderCrankUnknowns { psi: phi, x: 0.0 }).unwrap();
            let p = s.health.min_pivot;
            // The pivot ratio is the distance from the change point (the block's determinant is
            // `l cos psi` against its columns' size).
            assert!((p / delta - 1.0).abs() < 0.01, "pivot {p:e} at {delta:e}");
            let (e0, e1, e2) = ((s.q.psi - phi).abs(), (s.dq.psi - 1.0).abs(), s.d2q.psi.abs());
            // Measured: each error between 0.02 and 0.7 of its bound's `eps / p^k`.
            assert!(e0 <= 4.0 * eps / p, "{scale} {delta:e}: psi off by {e0:e}");
            assert!(e1 <= 4.0 * eps / (p * p), "{scale} {delta:e}: dpsi off by {e1:e}");
            assert!(e2 <= 4.0 * eps / (p * p * p), "{scale} {delta:e}: d2psi off by {e2:e}");
            assert!(s.q.x.abs() <= 4.0 * eps / p * scale, "{scale} {delta:e}: x = {:e}", s.q.x);
        }
    }
}
