//! A guess that already meets the residual tolerance is corrected once without iterating; the
//! values the generated code keeps from that evaluation (sines and cosines of the unknowns, from
//! which outputs and later blocks are computed) must then describe the corrected position, not
//! the guess. Reference: the coupler point recomputed here from the returned angles.

use kinloop::{Mechanism, NewtonConfig};

kinloop::mechanism! {
    /// A four-bar solved by Newton, with a coupler point built from the solved angles.
    #[kinloop(newton)]
    pub struct FourBarPoint {
        params a = 1.0, b = 3.5, c = 3.0, d = 4.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point p = a @ phi + b @ beta;
        point r = (d, 0) + c @ gamma;
    }
}

/// Guesses off the solution by 1e-15 .. 1e-11 rad, most of which meet the residual tolerance
/// (1e-12 relative to the loop's magnitude): the points come out consistent with the returned
/// angles to 1e-14, whatever the size of the correction (before the fix: 8.3e-13).
#[test]
fn outputs_describe_the_corrected_position_not_the_guess() {
    let m = FourBarPoint::default();
    let cfg = NewtonConfig::default();
    let scale = m.a + m.b + m.c + m.d;
    let mut worst: f64 = 0.0;
    for i in 0..40 {
        let phi = 0.1 + 0.15 * i as f64;
        let exact = m.kinematics_flat(&[phi], &m.guess_flat(&[phi]), &cfg).unwrap().q;
        for k in 0..9 {
            let delta = 1e-15 * 10f64.powf(0.5 * k as f64);
            let guess = [exact[0] + delta, exact[1] - 0.7 * delta];
            let s = m.kinematics_flat(&[phi], &guess, &cfg).unwrap();
            let [beta, gamma] = s.q;
            let p = [m.a * phi.cos() + m.b * beta.cos(), m.a * phi.sin() + m.b * beta.sin()];
            let r = [m.d + m.c * gamma.cos(), m.c * gamma.sin()];
            for (got, want) in s.out.iter().zip(p.iter().chain(&r)) {
                worst = worst.max((got - want).abs() / scale);
            }
        }
    }
    // Positions to 1e-14 of the loop's size (the sum of its links), as every position.
    assert!(worst <= 1e-14, "points off the returned angles by {worst:e} of the loop's size");
}
