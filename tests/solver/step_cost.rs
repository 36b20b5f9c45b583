//! Instruction count of one kinematic step of the rhombic drive (positions warm-started by the
//! second-order Taylor predictor, then velocity and acceleration analogs), for profiling with
//! `valgrind --tool=callgrind`:
//!
//! ```text
//! cargo test --release --test solver -- step_cost --ignored --nocapture
//! valgrind --tool=callgrind target/release/deps/solver-* step_cost --ignored --test-threads=1
//! ```
//!
//! Ignored by default: it only measures. Divide the instruction count by `STEPS`.

use kinloop::Mechanism;
use std::f64::consts::TAU;

kinloop::mechanism! {
    /// The rhombic drive as timed by the benchmarks: four unknowns, no output points.
    pub struct RhombicDrive {
        params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7;
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
    }
}

const STEPS: usize = 1_000_000;

#[test]
#[ignore = "measurement only: run under callgrind"]
fn rhombic_step_cost() {
    let m = RhombicDrive::default();
    let cfg = kinloop::NewtonConfig::default();
    let h = TAU / STEPS as f64;
    let mut k = m.kinematics_flat(&[0.0], &m.guess_flat(&[0.0]), &cfg).unwrap();
    let mut iterations = 0u64;
    for s in 1..STEPS {
        let x = [h * s as f64];
        let guess: [f64; 4] = std::array::from_fn(|u| k.q[u] + h * (k.dq[u][0] + 0.5 * h * k.d2q[u][0][0]));
        k = m.kinematics_flat(std::hint::black_box(&x), &guess, &cfg).unwrap();
        iterations += u64::from(k.report.iterations);
    }
    println!("{STEPS} steps, {iterations} Newton iterations, last q = {:?}", k.q);
}
