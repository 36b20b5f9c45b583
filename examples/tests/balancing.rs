//! The harmonics and residual unbalance the `balancing` example prints, against the drive's
//! positions written from its loops (paper 000's Fig. 1 in units of the working crank radius,
//! `docs/papers.md`, paper 004), never solved by kinloop:
//! `sin phi2 = (k + sin a) / gamma`, `X_C = cos a - gamma cos phi2` (the rod towards +x of the
//! piston, `phi2` near 0), `sin phi4 = rho (sin(a + delta) + k_b) / gamma_b`,
//! `X_F = rho cos(a + delta) - gamma_b cos phi4` (`phi4` near pi), the centre of mass
//! `X_c = -(M' X_C + X_F) / (M' + 1)`; its Fourier coefficients by a sum over 4,096 samples, and
//! `D` by a brute-force search of `|X_c - a0 - a1 cos a - b1 sin a|` over the turn.

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../balancing.rs"]
mod balancing;

#[allow(dead_code)]
mod turn_search;

use balancing::analyse;
use kinloop_fixtures::balancing::{Balance, SAMPLES, design, phased, unbalance};
use std::f64::consts::TAU;
use turn_search::smallest;

/// `X_c` at crank angle `a`, from the loops' projections.
fn centre(m: &Balance, a: f64) -> f64 {
    let s2 = (m.k + a.sin()) / m.gamma;
    let x_c = a.cos() - m.gamma * (1.0 - s2 * s2).sqrt();
    let s4 = m.rho * ((a + m.delta).sin() + m.k_b) / m.gamma_b;
    let x_f = m.rho * (a + m.delta).cos() + m.gamma_b * (1.0 - s4 * s4).sqrt();
    -(m.mass_ratio * x_c + x_f) / (m.mass_ratio + 1.0)
}

/// `a0` and `[a_k, b_k]` for `k = 1..=6`: sums over 4,096 samples of the turn, exact to rounding
/// for a smooth periodic curve whose harmonics decay geometrically.
fn fourier(m: &Balance) -> (f64, [[f64; 2]; 6]) {
    let n = 4096;
    let samples: Vec<(f64, f64)> = (0..n).map(|j| TAU * j as f64 / n as f64).map(|a| (a, centre(m, a))).collect();
    let a0 = samples.iter().map(|s| s.1).sum::<f64>() / n as f64;
    let harmonics = std::array::from_fn(|k| {
        let k = (k + 1) as f64;
        let sum = |f: fn(f64) -> f64| samples.iter().map(|&(a, x)| x * f(k * a)).sum::<f64>() * 2.0 / n as f64;
        [sum(f64::cos), sum(f64::sin)]
    });
    (a0, harmonics)
}

/// The residual after the mean `a0` and the first harmonic `[a1, b1]` at `a`.
fn residual(m: &Balance, (a0, [a1, b1]): (f64, [f64; 2]), a: f64) -> f64 {
    centre(m, a) - a0 - a1 * a.cos() - b1 * a.sin()
}

/// Amplitudes and `D` to 1e-12 (the sums are exact to rounding, about 1e-15 of the unit-size
/// values, and the example's 128 samples alias harmonics above the 64th, below 1e-20 here); the
/// residual at the printed crank angle to 1e-9 of `D` (where `|r|` is largest it is flat, so an
/// angle off by `e` changes it by about `e^2`, and the example locates it to better than 1e-5
/// rad): for the reference design, a design with the phase shift held, and the exact balance.
#[test]
fn the_printed_harmonics_and_unbalance_agree_with_the_loops_written_out() -> Result<(), Box<dyn std::error::Error>> {
    for m in [design([1.0, 2.0, 0.3, 0.0]), phased([1.0, 2.0, 0.3]), phased([1.4, 3.5, -0.2])] {
        let printed = analyse(&m)?;
        let (a0, h) = fourier(&m);
        for (k, [a, b]) in h.iter().enumerate() {
            let amplitude = a.hypot(*b);
            let got = printed.amplitudes[k];
            assert!((got - amplitude).abs() <= 1e-12, "{m:?}: harmonic {}: {got} vs {amplitude}", k + 1);
        }
        let (_, least) = smallest(|a| -residual(&m, (a0, h[0]), a).abs());
        let d = -least;
        assert!((printed.d - d).abs() <= 1e-12, "{m:?}: D {} vs {d}", printed.d);
        let there = residual(&m, (a0, h[0]), printed.at).abs();
        assert!((there - d).abs() <= 1e-9 * d, "{m:?}: |r| at the printed angle {} is {there}, D {d}", printed.at);
        // The family of the reference design the example prints `D` of goes through the same
        // unbalance (the fixtures' function the example calls).
        assert!((unbalance(&m, SAMPLES) - d).abs() <= 1e-12, "{m:?}");
    }
    // The closed-form optimum balances exactly: `M' X_C + X_F = 2 M' cos a`, whose first
    // harmonic alone is left, of amplitude `2 M' / (M' + 1)`.
    let balanced = design([1.5, 3.0, 0.3, 0.0]);
    let printed = analyse(&balanced)?;
    assert!((printed.amplitudes[0] - 2.0 * 1.5 / 2.5).abs() <= 1e-12, "{:?}", printed.amplitudes);
    assert!(printed.amplitudes[1..].iter().all(|a| *a <= 1e-12) && printed.d <= 1e-12, "{:?}", printed.amplitudes);
    Ok(())
}
