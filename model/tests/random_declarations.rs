//! Random valid declarations read at run time, checked against what does not come from
//! kinloop: the loop closure computed here from the solved angles, and the velocity and
//! acceleration analogs against central finite differences of the positions.

use kinloop::NewtonConfig;
use kinloop_model::Model;
use proptest::prelude::*;

/// Closure of the four-bar's loop computed here, relative to its lengths: rounding only.
const CLOSURE: f64 = 1e-12;
/// Central differences with step `H` of angles that are smooth at the scale of the links:
/// truncation `~H^4` (first, extrapolated) or `~H^2` (second) and rounding `~1e-16 / H` (first)
/// or `~1e-16 / H^2` (second).
const H: f64 = 1e-4;
const FD1: f64 = 1e-6;
const FD2: f64 = 1e-3;

fn four_bar(a: f64, b: f64, c: f64, d: f64) -> String {
    format!(
        "pub struct RandomFourBar {{
            params a = {a:?}, b = {b:?}, c = {c:?}, d = {d:?};
            input phi;
            unknowns beta = 0.5, gamma = 1.5;
            loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
            point pc = a @ phi + b @ beta;
        }}"
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn random_four_bars_close_their_loop_and_match_finite_differences(
        a in 0.3..1.5f64, b in 2.0..4.0f64, c in 1.5..3.5f64, d in 2.0..4.0f64, phi in -3.0..3.0f64,
    ) {
        let mut m = Model::read("random.kl", &four_bar(a, b, c, d)).expect("a valid declaration");
        let cfg = NewtonConfig::default();
        // The distance from the crank's joint B to the rocker's pivot D.
        let bd = ((a * phi.cos() - d).powi(2) + (a * phi.sin()).powi(2)).sqrt();
        let Ok(s) = m.solve(&[phi]) else {
            // Out of reach at this angle: B is too far from or too near D.
            prop_assert!(bd > b + c - 1e-9 || bd < (b - c).abs() + 1e-9, "no solution where the dyad reaches");
            return Ok(());
        };
        // Central differences need the branch smooth over their stencil: within about 1 % of
        // the loop's size of a limit position (the dyad stretched or folded) the higher
        // derivatives grow as powers of the inverse distance, and Richardson's error on a step
        // of `H` exceeds `FD1` (a dyad 1.1e-4 of its length from stretched missed by 5e-6).
        // There the model's analogs are the compiled kernel's to the bit (`parity.rs`), whose
        // are checked near limit positions in `tests/kinematics`.
        if (b + c - bd).min(bd - (b - c).abs()) < 1e-2 * (b + c) {
            return Ok(());
        }
        let (q, dq, d2q) = (s.q.clone(), s.dq.clone(), s.d2q.clone());
        let (beta, gamma) = (q[0], q[1]);
        let gap_x = a * phi.cos() + b * beta.cos() - d - c * gamma.cos();
        let gap_y = a * phi.sin() + b * beta.sin() - c * gamma.sin();
        prop_assert!(gap_x.hypot(gap_y) <= CLOSURE * (a + b + c + d), "loop open by {}", gap_x.hypot(gap_y));
        // The point is where the declaration says.
        prop_assert!((s.out[0] - (a * phi.cos() + b * beta.cos())).abs() <= CLOSURE * (a + b));
        // Analogs against central differences of positions on the same branch.
        let mut at = |x: f64| m.kinematics(&[x], &q, &cfg).map(|s| s.q.clone());
        let (Ok(p), Ok(n)) = (at(phi + H), at(phi - H)) else { return Ok(()) };
        let (Ok(ph), Ok(nh)) = (at(phi + 0.5 * H), at(phi - 0.5 * H)) else { return Ok(()) };
        for u in 0..2 {
            // Richardson's extrapolation of two central differences: truncation `~H^4` times
            // the fifth derivative, which near a limit position (where the derivatives grow)
            // the plain central difference's `H^2` times the third is not small against FD1.
            let fd1 = (4.0 * (ph[u] - nh[u]) / H - (p[u] - n[u]) / (2.0 * H)) / 3.0;
            let fd2 = (p[u] - 2.0 * q[u] + n[u]) / (H * H);
            let scale = 1.0 + dq[u].abs();
            prop_assert!((fd1 - dq[u]).abs() <= FD1 * scale, "dq[{u}]: {} vs {fd1}", dq[u]);
            prop_assert!((fd2 - d2q[u]).abs() <= FD2 * (1.0 + d2q[u].abs()), "d2q[{u}]: {} vs {fd2}", d2q[u]);
        }
    }
}
