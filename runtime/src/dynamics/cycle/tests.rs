//! The exact flywheel in closed form and its steady cycle's energy level by a safeguarded Newton
//! iteration, against the bisections they replaced (a pass over the samples per step: thousands
//! per sizing), and the passes the level takes.

use super::*;
use crate::dynamics::Shaking;

/// A cycle of `n` samples at constant speed `omega` with reduced inertia `inertia(phi)` and
/// loads `load(phi)`.
fn cycle(n: usize, omega: f64, inertia: impl Fn(f64) -> f64, load: impl Fn(f64) -> f64) -> Cycle {
    let points = (0..n)
        .map(|j| {
            let phi = TAU * j as f64 / n as f64;
            CyclePoint {
                phi,
                omega,
                eps: 0.0,
                inertia: inertia(phi),
                inertia_slope: 0.0,
                load: load(phi),
                torque: 0.0,
                shaking: Shaking { force: [0.0, 0.0], moment: 0.0 },
            }
        })
        .collect();
    Cycle { points }
}

/// Values in `[0, 1)` from a fixed linear congruential sequence: cycles whose extremes sit at
/// scattered samples, the envelope of the speeds kinked everywhere.
fn noise(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn tabled(n: usize, omega: f64, inertia: &[f64], load: &[f64]) -> Cycle {
    let at = |table: &[f64], phi: f64| table[(phi / TAU * n as f64).round() as usize % n];
    cycle(n, omega, |phi| at(inertia, phi), |phi| at(load, phi))
}

/// The sizing as it was: the level bisected for the mean speed, the flywheel for the
/// fluctuation, a pass over the samples at every step. `(exact, start_speed)`.
fn bisected(c: &Cycle, delta: f64) -> Option<(f64, f64)> {
    let speed_range = |work: &[f64], j_fly: f64, e0: f64| {
        let (mut hi, mut lo) = (0.0f64, f64::INFINITY);
        for (p, w) in c.points.iter().zip(work) {
            let omega = (2.0 * (e0 + w) / (j_fly + p.inertia)).max(0.0).sqrt();
            hi = hi.max(omega);
            lo = lo.min(omega);
        }
        (hi, lo)
    };
    let fluctuation = |work: &[f64], j_fly: f64, omega_m: f64| {
        let j_max = c.points.iter().map(|p| p.inertia).fold(0.0, f64::max) + j_fly;
        let mut lo = -work.iter().copied().fold(f64::INFINITY, f64::min);
        let mut hi = lo + 0.5 * j_max * omega_m * omega_m;
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            let (a, b) = speed_range(work, j_fly, mid);
            if 0.5 * (a + b) < omega_m { lo = mid } else { hi = mid }
        }
        let e0 = 0.5 * (lo + hi);
        let (a, b) = speed_range(work, j_fly, e0);
        ((a - b) / omega_m, e0)
    };
    let omega_m = mean(c.points.iter().map(|p| p.omega));
    let work = c.work(-mean(c.points.iter().map(|p| p.load)));
    let exact = if fluctuation(&work, 0.0, omega_m).0 <= delta {
        0.0
    } else {
        let mut hi = c.points.iter().map(|p| p.inertia).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        while fluctuation(&work, hi, omega_m).0 > delta && hi < f64::MAX / 4.0 {
            hi *= 2.0;
        }
        if fluctuation(&work, hi, omega_m).0 > delta {
            return None;
        }
        let mut lo = 0.0;
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if fluctuation(&work, mid, omega_m).0 > delta { lo = mid } else { hi = mid }
        }
        0.5 * (lo + hi)
    };
    let e0 = fluctuation(&work, exact, omega_m).1;
    Some((exact, (2.0 * (e0 + work[0]) / (exact + c.points[0].inertia)).sqrt()))
}

/// The cycles of the comparison, each with whether the mechanism alone keeps within 0.05.
fn cycles(n: usize) -> Vec<(&'static str, Cycle)> {
    let mut rand = noise(7);
    let inertia: Vec<f64> = (0..n).map(|_| 2.0 + rand()).collect();
    let load: Vec<f64> = (0..n).map(|_| rand() - 0.5).collect();
    vec![
        // An engine's: inertia and loads varying at several harmonics.
        (
            "engine",
            cycle(
                n,
                150.0,
                |p| 0.02 + 0.006 * (2.0 * p).cos() + 0.002 * p.sin(),
                |p| -40.0 + 60.0 * (p.sin() + 0.4 * (3.0 * p).cos()).max(0.0),
            ),
        ),
        // The mechanism alone suffices for the larger fluctuations: the level is solved for.
        ("heavy", cycle(n, 10.0, |p| 100.0 + (2.0 * p).cos() + 0.3 * (5.0 * p).sin(), |p| 0.5 * p.sin())),
        // No inertia of its own: the flywheel carries everything.
        ("no inertia", cycle(n, 3.0, |_| 0.0, |p| p.cos() + 0.2 * (4.0 * p).sin())),
        // Constant inertia, loads of a square wave: flat extremes, ties at many samples.
        ("ties", cycle(n, 1.0, |_| 0.5, |p| if p < std::f64::consts::PI { 1.0 } else { -1.0 })),
        // Scattered inertias and loads, in other units.
        ("noise", tabled(n, 1e-3, &inertia, &load)),
        ("noise, heavy", tabled(n, 1e3, &inertia.iter().map(|j| 1e3 * j).collect::<Vec<_>>(), &load)),
    ]
}

/// The bisections lost about `eps / delta` of the flywheel (the fluctuation a difference of
/// speeds, see [`MIN_DELTA`]), the closed form about `eps (1 + J / (J_fly delta))`: measured, the
/// two agree within `eps / delta` of `J_fly + J_max` (1.3e-10 at `delta = 1e-6`, 2e-15 near
/// 2); allowed, 16 times that. Both speeds at the start come from energies rounded to a few
/// `eps`: measured within 1.5e-15 of the mean speed, allowed `32 eps`.
#[test]
fn the_exact_flywheel_and_its_start_speed_are_the_bisections() {
    for n in [360, 1000] {
        for (name, c) in cycles(n) {
            for delta in [MIN_DELTA, 1e-3, 0.02, 0.05, 0.2, 1.0, 1.9] {
                let (exact, start) = bisected(&c, delta).unwrap();
                let f = c.flywheel(delta).unwrap();
                let j_max = c.points.iter().map(|p| p.inertia).fold(0.0, f64::max);
                let omega_m = c.points[0].omega;
                let (d_exact, d_start) = ((f.exact - exact).abs(), (f.start_speed - start).abs());
                let why = format!("{name}, {n} samples, delta {delta}: {f:?} against {exact}, {start}");
                assert!(d_exact <= 16.0 * f64::EPSILON * (1.0 + 1.0 / delta) * (exact + j_max), "{why}");
                assert!(d_start <= 32.0 * f64::EPSILON * omega_m, "{why}");
                // The mechanism alone suffices exactly when it did.
                assert_eq!(f.exact == 0.0, exact == 0.0, "{why}");
            }
        }
    }
}

/// The level of a steady cycle: a few passes over the samples where a bisection to the doubles'
/// resolution made 80, and the bisection's level. Also from the wide bracket the bisection
/// started from (the flywheel's sizing starts from the band of levels, narrower), on cycles
/// whose extremes sit at scattered samples, at 100000 samples a turn.
#[test]
fn the_energy_level_takes_a_few_passes() {
    for n in [360, 100_000] {
        for (name, c) in cycles(n) {
            let omega_m = mean(c.points.iter().map(|p| p.omega));
            let work = c.work(-mean(c.points.iter().map(|p| p.load)));
            let j_max = c.points.iter().map(|p| p.inertia).fold(0.0, f64::max);
            for delta in [0.05, 0.2, 1.0] {
                let (fly, levels) = c.exact_flywheel(&work, omega_m, delta).unwrap();
                let (e0, passes) = c.energy_level(&work, fly, omega_m, levels);
                assert!(passes <= 6, "{name}, {n} samples, delta {delta}: {passes} passes");
                // From the bisection's bracket, reduced by omega_m^2 as the level is.
                let lo = -work.iter().copied().fold(f64::INFINITY, f64::min) / omega_m / omega_m;
                let wide = [lo, lo + 0.5 * (j_max + fly)];
                let (e_wide, passes) = c.energy_level(&work, fly, omega_m, wide);
                let why = format!("{name}, {n} samples, delta {delta}: {passes} passes from {wide:?}");
                assert!(passes <= 8, "{why}");
                // The same level, to the rounding of the energies it is a sum of.
                let scale = e0.abs() + lo.abs() + wide[1] - wide[0];
                assert!((e_wide - e0).abs() <= 16.0 * f64::EPSILON * scale, "{why}: {e_wide} against {e0}");
            }
        }
    }
}
