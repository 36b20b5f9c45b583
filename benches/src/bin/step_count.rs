//! One kinematic step of a mechanism, compiled or read at run time, repeated along turns of
//! 720 steps (each warm-started from the previous position, as the benchmarks' point rows):
//! the harness that `model/callgrind.sh` runs under callgrind to count instructions per step.
//!
//! ```text
//! cargo run --release -p kinloop-bench --bin step_count -- VARIANT STEPS
//! ```
//!
//! `VARIANT` is `MECHANISM-compiled` or `MECHANISM-runtime` with `MECHANISM` one of
//! `rhombic`, `four-bar`, `class-four`, `ring` (64 four-bar loops closed through a
//! differential: one sparse Newton block of 128 unknowns); `read-rhombic` and `read-class-four` read and plan the
//! declaration `STEPS` times instead. Prints the sum of the last state's values (so the work
//! is not optimised away) and the wall time per step (one run; callgrind's counts are the
//! figure to compare).

use kinloop::{Mechanism, NewtonConfig};
use kinloop_fixtures as fx;
use kinloop_model::Model;
use std::f64::consts::TAU;
use std::hint::black_box;
use std::time::Instant;

const TURN: usize = 720;

// Out of line, as `runtime`: `model/callgrind.sh` counts the instructions inside these two only.
#[inline(never)]
fn compiled<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(m: &M, steps: usize) -> f64 {
    let cfg = black_box(NewtonConfig::default());
    let mut q = m.guess_flat(&[0.0; NI]);
    let mut sum = 0.0;
    for k in 0..steps {
        let mut x = [0.0; NI];
        x[0] = TAU * (k % TURN) as f64 / TURN as f64;
        let s = m.kinematics_flat(black_box(&x), &q, &cfg).expect("solve");
        q = s.q;
        sum += s.out.iter().sum::<f64>() + s.dq[0][0];
    }
    sum
}

#[inline(never)]
fn runtime(m: &mut Model, steps: usize) -> f64 {
    let cfg = black_box(NewtonConfig::default());
    let ni = m.inputs().len();
    let mut q = vec![0.0; m.unknowns().len()];
    m.guess(&vec![0.0; ni], &mut q).expect("guess");
    let mut x = vec![0.0; ni];
    let mut sum = 0.0;
    for k in 0..steps {
        x[0] = TAU * (k % TURN) as f64 / TURN as f64;
        let s = m.kinematics(black_box(&x), &q, &cfg).expect("solve");
        q.copy_from_slice(&s.q);
        sum += s.out.iter().sum::<f64>() + s.dq[0];
    }
    sum
}

fn model(text: &str, params: &[(&str, f64)]) -> Model {
    let mut m = Model::read("bench.kl", text).expect("valid declaration");
    for (p, v) in params {
        m.set_param(p, *v);
    }
    m
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let variant = args.get(1).map_or("rhombic-runtime", String::as_str);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let four_bar = [("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)];
    let start = Instant::now();
    let sum = match variant {
        "rhombic-compiled" => compiled(&fx::RhombicDrive::default(), steps),
        "rhombic-runtime" => runtime(&mut model(fx::RHOMBIC_DRIVE_TEXT, &[]), steps),
        "four-bar-compiled" => compiled(&fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 }, steps),
        "four-bar-runtime" => runtime(&mut model(fx::FOUR_BAR_TEXT, &four_bar), steps),
        "class-four-compiled" => compiled(&fx::ClassFour::default(), steps),
        "class-four-runtime" => runtime(&mut model(fx::CLASS_FOUR_TEXT, &[]), steps),
        "ring-compiled" => compiled(&kinloop_bench::ring::Ring::default(), steps),
        "ring-runtime" => runtime(&mut model(kinloop_bench::ring::RING, &[]), steps),
        // Reading and planning a declaration, `STEPS` times.
        "read-rhombic" | "read-class-four" => {
            let text = if variant == "read-rhombic" { fx::RHOMBIC_DRIVE_TEXT } else { fx::CLASS_FOUR_TEXT };
            (0..steps).map(|_| model(black_box(text), &[]).instructions() as f64).sum()
        }
        other => {
            eprintln!("unknown variant {other}");
            std::process::exit(2);
        }
    };
    let ns = start.elapsed().as_nanos() as f64 / steps as f64;
    println!("{variant} {steps} steps: {ns:.0} ns/step (including setup), checksum {sum}");
}
