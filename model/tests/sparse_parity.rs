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
                seen.dense += (0..model.block_count()).filter(|&b| model.dense_fallback(b) == Some(true)).count();
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

/// The body of a declaration of `loops` four-bar loops, each driven through a differential by
/// the input and the rockers of two other loops drawn at random (seeded, a linear congruential
/// generator): a coupled block whose pattern follows no ring or band. The four-bar (crank 1,
/// coupler 3, rocker 2.5, frame 3.2) is a Grashof crank-rocker: it assembles at every crank
/// angle, so every combination of drivers does.
fn random_coupled(loops: usize, seed: u64) -> String {
    let mut state = seed;
    let mut draw = |m: usize| {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 33) % m as u64) as usize
    };
    let mut body = String::from("params a = 1.0, b = 3.0, c = 2.5, d = 3.2; input phi; unknowns ");
    body += &(0..loops).map(|i| format!("u{i} = 0.6, v{i} = 1.9")).collect::<Vec<_>>().join(", ");
    body += ";";
    for i in 0..loops {
        let j = (i + 1 + draw(loops - 1)) % loops;
        let mut k = (i + 1 + draw(loops - 1)) % loops;
        if k == j {
            k = (j + 1) % loops;
            if k == i {
                k = (k + 1) % loops;
            }
        }
        body += &format!(" loop l{i}: a @ ((phi + v{j} + v{k}) / 3) + b @ u{i} == (d, 0) + c @ v{i};");
    }
    body
}

declared! {
    RANDOM_TEXT =>
    /// Twenty four-bar loops coupled at random (`random_coupled(20, 7)`, written out: a
    /// declaration is tokens).
    pub struct RandomCoupled {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9, u4 = 0.6,
            v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9, u8 = 0.6, v8 = 1.9,
            u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9, u12 = 0.6, v12 = 1.9, u13 = 0.6,
            v13 = 1.9, u14 = 0.6, v14 = 1.9, u15 = 0.6, v15 = 1.9, u16 = 0.6, v16 = 1.9, u17 = 0.6,
            v17 = 1.9, u18 = 0.6, v18 = 1.9, u19 = 0.6, v19 = 1.9;
        loop l0: a @ ((phi + v19 + v6) / 3) + b @ u0 == (d, 0) + c @ v0;
        loop l1: a @ ((phi + v19 + v13) / 3) + b @ u1 == (d, 0) + c @ v1;
        loop l2: a @ ((phi + v8 + v18) / 3) + b @ u2 == (d, 0) + c @ v2;
        loop l3: a @ ((phi + v16 + v17) / 3) + b @ u3 == (d, 0) + c @ v3;
        loop l4: a @ ((phi + v6 + v0) / 3) + b @ u4 == (d, 0) + c @ v4;
        loop l5: a @ ((phi + v1 + v11) / 3) + b @ u5 == (d, 0) + c @ v5;
        loop l6: a @ ((phi + v16 + v0) / 3) + b @ u6 == (d, 0) + c @ v6;
        loop l7: a @ ((phi + v17 + v18) / 3) + b @ u7 == (d, 0) + c @ v7;
        loop l8: a @ ((phi + v10 + v12) / 3) + b @ u8 == (d, 0) + c @ v8;
        loop l9: a @ ((phi + v11 + v10) / 3) + b @ u9 == (d, 0) + c @ v9;
        loop l10: a @ ((phi + v19 + v6) / 3) + b @ u10 == (d, 0) + c @ v10;
        loop l11: a @ ((phi + v17 + v13) / 3) + b @ u11 == (d, 0) + c @ v11;
        loop l12: a @ ((phi + v9 + v0) / 3) + b @ u12 == (d, 0) + c @ v12;
        loop l13: a @ ((phi + v17 + v6) / 3) + b @ u13 == (d, 0) + c @ v13;
        loop l14: a @ ((phi + v5 + v3) / 3) + b @ u14 == (d, 0) + c @ v14;
        loop l15: a @ ((phi + v4 + v5) / 3) + b @ u15 == (d, 0) + c @ v15;
        loop l16: a @ ((phi + v12 + v1) / 3) + b @ u16 == (d, 0) + c @ v16;
        loop l17: a @ ((phi + v14 + v7) / 3) + b @ u17 == (d, 0) + c @ v17;
        loop l18: a @ ((phi + v17 + v4) / 3) + b @ u18 == (d, 0) + c @ v18;
        loop l19: a @ ((phi + v0 + v12) / 3) + b @ u19 == (d, 0) + c @ v19;
    }
}

#[test]
fn the_written_out_random_declaration_is_the_generated_one() {
    let strip = |s: &str| s.chars().filter(|c| !c.is_whitespace()).collect::<String>();
    assert!(strip(RANDOM_TEXT).ends_with(&format!("{{{}}}", strip(&random_coupled(20, 7)))), "{RANDOM_TEXT}");
}

#[test]
fn a_randomly_coupled_declaration_equals_the_compiled_one() {
    let mut model = read(RANDOM_TEXT);
    eprintln!("{}", model.decomposition());
    assert!(model.decomposition().contains("sparse"), "{}", model.decomposition());
    let seen = turn(&RandomCoupled::default(), &mut model, 360);
    assert_eq!(seen.states, 360, "{seen:?}");
    eprintln!("randomly coupled: {seen:?}");
}

/// Parameters of the ring of nine at which the static order's pivots turn weak at some inputs of
/// the turn (found by a scan of link lengths): there both factorise densely.
#[test]
fn the_dense_fallback_of_a_weak_static_pivot_equals_the_compiled_one() {
    let (a, b, c, d) = (2.0, 2.0, 4.0, 2.0);
    let mut model = read(RING9_TEXT);
    for (p, v) in [("a", a), ("b", b), ("c", c), ("d", d)] {
        assert!(model.set_param(p, v));
    }
    let seen = turn(&Ring9 { a, b, c, d }, &mut model, 360);
    assert_eq!(seen.states, 360, "{seen:?}");
    // Both paths taken: the sparse order where it holds, the dense fallback where it does not.
    assert!(seen.dense > 0 && seen.dense < seen.states, "{seen:?}");
    eprintln!("ring of nine with weak static pivots: {seen:?}");
}

declared! {
    RING9_SENS_TEXT =>
    /// The ring of nine with its parameter sensitivities.
    #[kinloop(sensitivities)]
    pub struct Ring9Sens {
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
        point p8 = b @ u8;
    }
}

/// Sensitivities to every parameter along a turn, on the sparse factorisation and on its dense
/// fallback (the second parameter set), against the compiled `sensitivities_flat`, bit for bit.
#[test]
fn sensitivities_of_a_sparse_block_equal_the_compiled_ones() {
    use kinloop::Sensitivities as _;
    let cfg = NewtonConfig::default();
    let mut model = read(RING9_SENS_TEXT);
    for (a, b, c, d) in [(1.0, 3.0, 2.5, 3.2), (2.0, 2.0, 4.0, 2.0)] {
        let compiled = Ring9Sens { a, b, c, d };
        for (p, v) in [("a", a), ("b", b), ("c", c), ("d", d)] {
            assert!(model.set_param(p, v));
        }
        let mut guess = compiled.guess_flat(&[0.0]);
        let mut dense = 0;
        for k in 0..90 {
            let x = [TAU * k as f64 / 90.0];
            let (ck, cs) = compiled.sensitivities_flat(&x, &guess, &cfg).expect("compiled");
            let (_, rs) = model.sensitivities(&x, &guess, &cfg).expect("run time");
            let rs = rs.expect("declared with sensitivities");
            for (what, c, r) in [
                ("q", cs.q.iter().flatten().copied().collect::<Vec<_>>(), &rs.q),
                ("dq", cs.dq.iter().flatten().flatten().copied().collect(), &rs.dq),
                ("d2q", cs.d2q.iter().flatten().flatten().flatten().copied().collect(), &rs.d2q),
                ("out", cs.out.iter().flatten().copied().collect(), &rs.out),
                ("dout", cs.dout.iter().flatten().flatten().copied().collect(), &rs.dout),
                ("d2out", cs.d2out.iter().flatten().flatten().flatten().copied().collect(), &rs.d2out),
            ] {
                assert_eq!(bits(&c), bits(r), "at {x:?}: sensitivities {what} differ");
            }
            dense += usize::from(model.dense_fallback(0) == Some(true));
            guess = ck.q;
        }
        eprintln!("ring of nine ({a}, {b}, {c}, {d}): sensitivities equal at 90 inputs, {dense} by the dense fallback");
    }
}

/// Analogs at given positions (solved and perturbed), the block's Jacobian factorised from the
/// graph: the compiled `kinematics_at_flat`.
#[test]
fn kinematics_at_a_position_of_a_sparse_block_equal_the_compiled_ones() {
    let cfg = NewtonConfig::default();
    let compiled = Ring9::default();
    let mut model = read(RING9_TEXT);
    let mut compared = 0;
    let mut guess = compiled.guess_flat(&[0.0]);
    for k in 0..24 {
        let x = [0.27 * k as f64];
        let solved = compiled.kinematics_flat(&x, &guess, &cfg).expect("assembles");
        guess = solved.q;
        for shift in [0.0, 1e-7] {
            let q = solved.q.map(|v| v + shift);
            let c = compiled.kinematics_at_flat(&x, &q, &cfg).expect("compiled");
            let r = model.kinematics_at(&x, &q, &cfg).expect("run time");
            assert_eq!(c.report.residual.to_bits(), r.report.residual.to_bits());
            let flat = |v: &[[f64; 1]]| v.iter().flatten().copied().collect::<Vec<f64>>();
            let flat3 = |v: &[[[f64; 1]; 1]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
            assert_eq!(bits(&flat(&c.dq)), bits(&r.dq), "at {x:?}");
            assert_eq!(bits(&flat3(&c.d2q)), bits(&r.d2q), "at {x:?}");
            compared += 1;
        }
    }
    assert_eq!(compared, 48);
}

/// A model holding a sparse block's solver can move to and be shared with other threads.
#[test]
fn a_model_with_a_sparse_block_is_send_and_sync() {
    fn send_sync<T: Send + Sync>(_: &T) {}
    send_sync(&read(RING9_TEXT));
}

/// The comparison can fail: the ring of nine read with one link length changed by one part in
/// 10^12 differs from the compiled mechanism.
#[test]
fn a_changed_parameter_is_seen() {
    let mut model = read(RING9_TEXT);
    assert!(model.set_param("c", 2.5 * (1.0 + 1e-12)));
    let caught =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| turn(&Ring9::default(), &mut model, 8))).is_err();
    assert!(caught, "a parameter changed by 1e-12 went unnoticed");
}
