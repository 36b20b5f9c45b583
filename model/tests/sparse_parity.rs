//! Blocks solved by sparse Newton, read at run time, against the compiled mechanisms of the
//! same declarations: the ring of 64 four-bar loops closed through a differential (one block of
//! 128 unknowns), a ring of nine, and a randomly coupled declaration, over whole turns; the
//! dense fallback of a weak static pivot exercised and compared; the sensitivities.
//!
//! The reference is independent of the run-time reader: the compiled kernels are straight-line
//! Rust emitted by the macro (the block's elimination as one statement per update), optimised
//! by rustc; the reader runs the runtime's loops over the same tables. Both perform the same
//! operations in the same order, so the states are demanded equal bit for bit; the test counts
//! and asserts it.

use kinloop::{Mechanism, NewtonConfig};
use kinloop_model::Model;
use std::f64::consts::TAU;

/// What a comparison over a turn saw.
#[derive(Debug, Default)]
struct Seen {
    /// States compared (both solved).
    states: usize,
    /// States where the run-time analogs were factorised by the dense fallback.
    dense: usize,
    /// Samples where both failed alike.
    failed: usize,
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Sweeps input 0 over a turn in `samples` steps, each warm-started from the compiled
/// mechanism's previous position (both get the same guess, bit for bit), and demands the same
/// positions, analogs, outputs, solve report and health, bit for bit.
fn turn<M, const N: usize, const NI: usize, const NO: usize>(compiled: &M, model: &mut Model, samples: usize) -> Seen
where
    M: Mechanism<N, NI, NO>,
{
    let cfg = NewtonConfig::default();
    let name = model.name().to_string();
    let mut guess = compiled.guess_flat(&[0.0; NI]);
    let mut seen = Seen::default();
    for k in 0..samples {
        let mut x = [0.0; NI];
        x[0] = TAU * k as f64 / samples as f64;
        let c = compiled.kinematics_flat(&x, &guess, &cfg);
        let r = model.kinematics(&x, &guess, &cfg).cloned();
        match (c, r) {
            (Ok(c), Ok(r)) => {
                let flat2 = |v: &[[f64; NI]]| v.iter().flatten().copied().collect::<Vec<f64>>();
                let flat3 = |v: &[[[f64; NI]; NI]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
                for (what, a, b) in [
                    ("q", c.q.to_vec(), r.q.clone()),
                    ("dq", flat2(&c.dq), r.dq.clone()),
                    ("d2q", flat3(&c.d2q), r.d2q.clone()),
                    ("out", c.out.to_vec(), r.out.clone()),
                    ("dout", flat2(&c.dout), r.dout.clone()),
                    ("d2out", flat3(&c.d2out), r.d2out.clone()),
                ] {
                    assert_eq!(bits(&a), bits(&b), "{name} at {x:?}: {what} differs");
                }
                assert_eq!(c.report.iterations, r.report.iterations, "{name} at {x:?}: iterations");
                assert_eq!(c.report.evaluations, r.report.evaluations, "{name} at {x:?}: evaluations");
                assert_eq!(c.report.residual.to_bits(), r.report.residual.to_bits(), "{name} at {x:?}: residual");
                assert_eq!(c.health.det_signs, r.health.det_signs, "{name} at {x:?}: determinant signs");
                assert_eq!(c.health.min_pivot.to_bits(), r.health.min_pivot.to_bits(), "{name} at {x:?}: pivot ratio");
                seen.dense += usize::from(model.dense_fallback(0) == Some(true));
                guess = c.q;
                seen.states += 1;
            }
            (Err(_), Err(_)) => {
                guess = compiled.guess_flat(&x);
                seen.failed += 1;
            }
            (c, r) => panic!("{name} at {x:?}: compiled {:?}, run time {:?}", c.map(|k| k.q), r.map(|s| s.q)),
        }
    }
    seen
}

fn read(text: &str) -> Model {
    Model::read("sparse.kl", text).unwrap_or_else(|e| panic!("{e}"))
}

/// Declares a mechanism with `kinloop::mechanism!` and keeps its text.
macro_rules! declared {
    ($text:ident => $($t:tt)*) => {
        kinloop::mechanism! { $($t)* }
        const $text: &str = stringify!($($t)*);
    };
}

declared! {
    RING9_TEXT =>
    /// Nine four-bar loops closed through a differential: one sparse block of 18 unknowns
    /// (solved at run time padded to 32).
    pub struct Ring9 {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
            u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9,
            u8 = 0.6, v8 = 1.9;
        loop l0: a @ (0.5 * (phi + v8)) + b @ u0 == (d, 0) + c @ v0;
        loop l1: a @ v0 + b @ u1 == (d, 0) + c @ v1;
        loop l2: a @ v1 + b @ u2 == (d, 0) + c @ v2;
        loop l3: a @ v2 + b @ u3 == (d, 0) + c @ v3;
        loop l4: a @ v3 + b @ u4 == (d, 0) + c @ v4;
        loop l5: a @ v4 + b @ u5 == (d, 0) + c @ v5;
        loop l6: a @ v5 + b @ u6 == (d, 0) + c @ v6;
        loop l7: a @ v6 + b @ u7 == (d, 0) + c @ v7;
        loop l8: a @ v7 + b @ u8 == (d, 0) + c @ v8;
    }
}

#[test]
fn the_ring_of_nine_equals_the_compiled_one() {
    let mut model = read(RING9_TEXT);
    assert!(model.decomposition().contains("sparse"), "{}", model.decomposition());
    let seen = turn(&Ring9::default(), &mut model, 360);
    assert_eq!(seen.states, 360, "{seen:?}");
    eprintln!("ring of nine: {seen:?}");
}

#[test]
fn the_ring_of_64_equals_the_compiled_one() {
    let mut model = read(kinloop_bench::ring::RING);
    assert!(model.decomposition().contains("128x128 sparse"), "{}", model.decomposition());
    let seen = turn(&kinloop_bench::ring::Ring::default(), &mut model, 360);
    assert_eq!(seen.states, 360, "{seen:?}");
    eprintln!("ring of 64: {seen:?}");
}
