//! Blocks solved by sparse Newton, read at run time, against the compiled mechanisms of the
//! same declarations: the ring of 64 four-bar loops closed through a differential (one block of
//! 128 unknowns), rings of nine and of 128 (256 unknowns, the largest read), and a randomly
//! coupled declaration, over whole turns; the
//! dense fallback of a weak static pivot exercised and compared; the sensitivities.
//!
//! The reference is independent of the run-time reader: the compiled kernels are straight-line
//! Rust emitted by the macro (the block's elimination as one statement per update), optimised
//! by rustc; the reader runs the runtime's loops over the same tables. Both perform the same
//! operations in the same order, so the states are demanded equal bit for bit; the test counts
//! and asserts it.

#[macro_use]
mod common;

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

/// A clone is an independent workspace with the original's parameters: over a turn it equals
/// the compiled mechanism as the original does, and a parameter set on the clone leaves the
/// original's states as they were (the ring of nine: a sparse block, the one solver the model
/// copies through its trait).
#[test]
fn a_clone_is_an_independent_model() {
    let mut original = read(RING9_TEXT);
    let mut copy = original.clone();
    assert_eq!(turn(&Ring9::default(), &mut copy, 36).states, 36);
    assert!(copy.set_param("c", 2.6));
    let cfg = NewtonConfig::default();
    let mut guess = vec![0.0; original.unknowns().len()];
    original.guess(&[0.3], &mut guess).unwrap();
    let before = original.kinematics(&[0.3], &guess, &cfg).unwrap().clone();
    copy.guess(&[0.3], &mut guess).unwrap();
    let changed = copy.kinematics(&[0.3], &guess, &cfg).unwrap().q.clone();
    assert_ne!(bits(&changed), bits(&before.q), "the clone's parameter took no effect");
    assert_eq!(turn(&Ring9::default(), &mut original, 36).states, 36);
    original.guess(&[0.3], &mut guess).unwrap();
    assert_eq!(bits(&original.kinematics(&[0.3], &guess, &cfg).unwrap().q), bits(&before.q));
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

declared! {
    RING128_TEXT =>
    /// 128 four-bar loops closed through a differential: one sparse block of 256 unknowns, the
    /// largest size read at run time (`MAX_SPARSE`).
    pub struct Ring128 {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
            u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9,
            u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9,
            u12 = 0.6, v12 = 1.9, u13 = 0.6, v13 = 1.9, u14 = 0.6, v14 = 1.9, u15 = 0.6, v15 = 1.9,
            u16 = 0.6, v16 = 1.9, u17 = 0.6, v17 = 1.9, u18 = 0.6, v18 = 1.9, u19 = 0.6, v19 = 1.9,
            u20 = 0.6, v20 = 1.9, u21 = 0.6, v21 = 1.9, u22 = 0.6, v22 = 1.9, u23 = 0.6, v23 = 1.9,
            u24 = 0.6, v24 = 1.9, u25 = 0.6, v25 = 1.9, u26 = 0.6, v26 = 1.9, u27 = 0.6, v27 = 1.9,
            u28 = 0.6, v28 = 1.9, u29 = 0.6, v29 = 1.9, u30 = 0.6, v30 = 1.9, u31 = 0.6, v31 = 1.9,
            u32 = 0.6, v32 = 1.9, u33 = 0.6, v33 = 1.9, u34 = 0.6, v34 = 1.9, u35 = 0.6, v35 = 1.9,
            u36 = 0.6, v36 = 1.9, u37 = 0.6, v37 = 1.9, u38 = 0.6, v38 = 1.9, u39 = 0.6, v39 = 1.9,
            u40 = 0.6, v40 = 1.9, u41 = 0.6, v41 = 1.9, u42 = 0.6, v42 = 1.9, u43 = 0.6, v43 = 1.9,
            u44 = 0.6, v44 = 1.9, u45 = 0.6, v45 = 1.9, u46 = 0.6, v46 = 1.9, u47 = 0.6, v47 = 1.9,
            u48 = 0.6, v48 = 1.9, u49 = 0.6, v49 = 1.9, u50 = 0.6, v50 = 1.9, u51 = 0.6, v51 = 1.9,
            u52 = 0.6, v52 = 1.9, u53 = 0.6, v53 = 1.9, u54 = 0.6, v54 = 1.9, u55 = 0.6, v55 = 1.9,
            u56 = 0.6, v56 = 1.9, u57 = 0.6, v57 = 1.9, u58 = 0.6, v58 = 1.9, u59 = 0.6, v59 = 1.9,
            u60 = 0.6, v60 = 1.9, u61 = 0.6, v61 = 1.9, u62 = 0.6, v62 = 1.9, u63 = 0.6, v63 = 1.9,
            u64 = 0.6, v64 = 1.9, u65 = 0.6, v65 = 1.9, u66 = 0.6, v66 = 1.9, u67 = 0.6, v67 = 1.9,
            u68 = 0.6, v68 = 1.9, u69 = 0.6, v69 = 1.9, u70 = 0.6, v70 = 1.9, u71 = 0.6, v71 = 1.9,
            u72 = 0.6, v72 = 1.9, u73 = 0.6, v73 = 1.9, u74 = 0.6, v74 = 1.9, u75 = 0.6, v75 = 1.9,
            u76 = 0.6, v76 = 1.9, u77 = 0.6, v77 = 1.9, u78 = 0.6, v78 = 1.9, u79 = 0.6, v79 = 1.9,
            u80 = 0.6, v80 = 1.9, u81 = 0.6, v81 = 1.9, u82 = 0.6, v82 = 1.9, u83 = 0.6, v83 = 1.9,
            u84 = 0.6, v84 = 1.9, u85 = 0.6, v85 = 1.9, u86 = 0.6, v86 = 1.9, u87 = 0.6, v87 = 1.9,
            u88 = 0.6, v88 = 1.9, u89 = 0.6, v89 = 1.9, u90 = 0.6, v90 = 1.9, u91 = 0.6, v91 = 1.9,
            u92 = 0.6, v92 = 1.9, u93 = 0.6, v93 = 1.9, u94 = 0.6, v94 = 1.9, u95 = 0.6, v95 = 1.9,
            u96 = 0.6, v96 = 1.9, u97 = 0.6, v97 = 1.9, u98 = 0.6, v98 = 1.9, u99 = 0.6, v99 = 1.9,
            u100 = 0.6, v100 = 1.9, u101 = 0.6, v101 = 1.9, u102 = 0.6, v102 = 1.9, u103 = 0.6, v103 = 1.9,
            u104 = 0.6, v104 = 1.9, u105 = 0.6, v105 = 1.9, u106 = 0.6, v106 = 1.9, u107 = 0.6, v107 = 1.9,
            u108 = 0.6, v108 = 1.9, u109 = 0.6, v109 = 1.9, u110 = 0.6, v110 = 1.9, u111 = 0.6, v111 = 1.9,
            u112 = 0.6, v112 = 1.9, u113 = 0.6, v113 = 1.9, u114 = 0.6, v114 = 1.9, u115 = 0.6, v115 = 1.9,
            u116 = 0.6, v116 = 1.9, u117 = 0.6, v117 = 1.9, u118 = 0.6, v118 = 1.9, u119 = 0.6, v119 = 1.9,
            u120 = 0.6, v120 = 1.9, u121 = 0.6, v121 = 1.9, u122 = 0.6, v122 = 1.9, u123 = 0.6, v123 = 1.9,
            u124 = 0.6, v124 = 1.9, u125 = 0.6, v125 = 1.9, u126 = 0.6, v126 = 1.9, u127 = 0.6, v127 = 1.9;
        loop l0: a @ (0.5 * (phi + v127)) + b @ u0 == (d, 0) + c @ v0;
        loop l1: a @ v0 + b @ u1 == (d, 0) + c @ v1;
        loop l2: a @ v1 + b @ u2 == (d, 0) + c @ v2;
        loop l3: a @ v2 + b @ u3 == (d, 0) + c @ v3;
        loop l4: a @ v3 + b @ u4 == (d, 0) + c @ v4;
        loop l5: a @ v4 + b @ u5 == (d, 0) + c @ v5;
        loop l6: a @ v5 + b @ u6 == (d, 0) + c @ v6;
        loop l7: a @ v6 + b @ u7 == (d, 0) + c @ v7;
        loop l8: a @ v7 + b @ u8 == (d, 0) + c @ v8;
        loop l9: a @ v8 + b @ u9 == (d, 0) + c @ v9;
        loop l10: a @ v9 + b @ u10 == (d, 0) + c @ v10;
        loop l11: a @ v10 + b @ u11 == (d, 0) + c @ v11;
        loop l12: a @ v11 + b @ u12 == (d, 0) + c @ v12;
        loop l13: a @ v12 + b @ u13 == (d, 0) + c @ v13;
        loop l14: a @ v13 + b @ u14 == (d, 0) + c @ v14;
        loop l15: a @ v14 + b @ u15 == (d, 0) + c @ v15;
        loop l16: a @ v15 + b @ u16 == (d, 0) + c @ v16;
        loop l17: a @ v16 + b @ u17 == (d, 0) + c @ v17;
        loop l18: a @ v17 + b @ u18 == (d, 0) + c @ v18;
        loop l19: a @ v18 + b @ u19 == (d, 0) + c @ v19;
        loop l20: a @ v19 + b @ u20 == (d, 0) + c @ v20;
        loop l21: a @ v20 + b @ u21 == (d, 0) + c @ v21;
        loop l22: a @ v21 + b @ u22 == (d, 0) + c @ v22;
        loop l23: a @ v22 + b @ u23 == (d, 0) + c @ v23;
        loop l24: a @ v23 + b @ u24 == (d, 0) + c @ v24;
        loop l25: a @ v24 + b @ u25 == (d, 0) + c @ v25;
        loop l26: a @ v25 + b @ u26 == (d, 0) + c @ v26;
        loop l27: a @ v26 + b @ u27 == (d, 0) + c @ v27;
        loop l28: a @ v27 + b @ u28 == (d, 0) + c @ v28;
        loop l29: a @ v28 + b @ u29 == (d, 0) + c @ v29;
        loop l30: a @ v29 + b @ u30 == (d, 0) + c @ v30;
        loop l31: a @ v30 + b @ u31 == (d, 0) + c @ v31;
        loop l32: a @ v31 + b @ u32 == (d, 0) + c @ v32;
        loop l33: a @ v32 + b @ u33 == (d, 0) + c @ v33;
        loop l34: a @ v33 + b @ u34 == (d, 0) + c @ v34;
        loop l35: a @ v34 + b @ u35 == (d, 0) + c @ v35;
        loop l36: a @ v35 + b @ u36 == (d, 0) + c @ v36;
        loop l37: a @ v36 + b @ u37 == (d, 0) + c @ v37;
        loop l38: a @ v37 + b @ u38 == (d, 0) + c @ v38;
        loop l39: a @ v38 + b @ u39 == (d, 0) + c @ v39;
        loop l40: a @ v39 + b @ u40 == (d, 0) + c @ v40;
        loop l41: a @ v40 + b @ u41 == (d, 0) + c @ v41;
        loop l42: a @ v41 + b @ u42 == (d, 0) + c @ v42;
        loop l43: a @ v42 + b @ u43 == (d, 0) + c @ v43;
        loop l44: a @ v43 + b @ u44 == (d, 0) + c @ v44;
        loop l45: a @ v44 + b @ u45 == (d, 0) + c @ v45;
        loop l46: a @ v45 + b @ u46 == (d, 0) + c @ v46;
        loop l47: a @ v46 + b @ u47 == (d, 0) + c @ v47;
        loop l48: a @ v47 + b @ u48 == (d, 0) + c @ v48;
        loop l49: a @ v48 + b @ u49 == (d, 0) + c @ v49;
        loop l50: a @ v49 + b @ u50 == (d, 0) + c @ v50;
        loop l51: a @ v50 + b @ u51 == (d, 0) + c @ v51;
        loop l52: a @ v51 + b @ u52 == (d, 0) + c @ v52;
        loop l53: a @ v52 + b @ u53 == (d, 0) + c @ v53;
        loop l54: a @ v53 + b @ u54 == (d, 0) + c @ v54;
        loop l55: a @ v54 + b @ u55 == (d, 0) + c @ v55;
        loop l56: a @ v55 + b @ u56 == (d, 0) + c @ v56;
        loop l57: a @ v56 + b @ u57 == (d, 0) + c @ v57;
        loop l58: a @ v57 + b @ u58 == (d, 0) + c @ v58;
        loop l59: a @ v58 + b @ u59 == (d, 0) + c @ v59;
        loop l60: a @ v59 + b @ u60 == (d, 0) + c @ v60;
        loop l61: a @ v60 + b @ u61 == (d, 0) + c @ v61;
        loop l62: a @ v61 + b @ u62 == (d, 0) + c @ v62;
        loop l63: a @ v62 + b @ u63 == (d, 0) + c @ v63;
        loop l64: a @ v63 + b @ u64 == (d, 0) + c @ v64;
        loop l65: a @ v64 + b @ u65 == (d, 0) + c @ v65;
        loop l66: a @ v65 + b @ u66 == (d, 0) + c @ v66;
        loop l67: a @ v66 + b @ u67 == (d, 0) + c @ v67;
        loop l68: a @ v67 + b @ u68 == (d, 0) + c @ v68;
        loop l69: a @ v68 + b @ u69 == (d, 0) + c @ v69;
        loop l70: a @ v69 + b @ u70 == (d, 0) + c @ v70;
        loop l71: a @ v70 + b @ u71 == (d, 0) + c @ v71;
        loop l72: a @ v71 + b @ u72 == (d, 0) + c @ v72;
        loop l73: a @ v72 + b @ u73 == (d, 0) + c @ v73;
        loop l74: a @ v73 + b @ u74 == (d, 0) + c @ v74;
        loop l75: a @ v74 + b @ u75 == (d, 0) + c @ v75;
        loop l76: a @ v75 + b @ u76 == (d, 0) + c @ v76;
        loop l77: a @ v76 + b @ u77 == (d, 0) + c @ v77;
        loop l78: a @ v77 + b @ u78 == (d, 0) + c @ v78;
        loop l79: a @ v78 + b @ u79 == (d, 0) + c @ v79;
        loop l80: a @ v79 + b @ u80 == (d, 0) + c @ v80;
        loop l81: a @ v80 + b @ u81 == (d, 0) + c @ v81;
        loop l82: a @ v81 + b @ u82 == (d, 0) + c @ v82;
        loop l83: a @ v82 + b @ u83 == (d, 0) + c @ v83;
        loop l84: a @ v83 + b @ u84 == (d, 0) + c @ v84;
        loop l85: a @ v84 + b @ u85 == (d, 0) + c @ v85;
        loop l86: a @ v85 + b @ u86 == (d, 0) + c @ v86;
        loop l87: a @ v86 + b @ u87 == (d, 0) + c @ v87;
        loop l88: a @ v87 + b @ u88 == (d, 0) + c @ v88;
        loop l89: a @ v88 + b @ u89 == (d, 0) + c @ v89;
        loop l90: a @ v89 + b @ u90 == (d, 0) + c @ v90;
        loop l91: a @ v90 + b @ u91 == (d, 0) + c @ v91;
        loop l92: a @ v91 + b @ u92 == (d, 0) + c @ v92;
        loop l93: a @ v92 + b @ u93 == (d, 0) + c @ v93;
        loop l94: a @ v93 + b @ u94 == (d, 0) + c @ v94;
        loop l95: a @ v94 + b @ u95 == (d, 0) + c @ v95;
        loop l96: a @ v95 + b @ u96 == (d, 0) + c @ v96;
        loop l97: a @ v96 + b @ u97 == (d, 0) + c @ v97;
        loop l98: a @ v97 + b @ u98 == (d, 0) + c @ v98;
        loop l99: a @ v98 + b @ u99 == (d, 0) + c @ v99;
        loop l100: a @ v99 + b @ u100 == (d, 0) + c @ v100;
        loop l101: a @ v100 + b @ u101 == (d, 0) + c @ v101;
        loop l102: a @ v101 + b @ u102 == (d, 0) + c @ v102;
        loop l103: a @ v102 + b @ u103 == (d, 0) + c @ v103;
        loop l104: a @ v103 + b @ u104 == (d, 0) + c @ v104;
        loop l105: a @ v104 + b @ u105 == (d, 0) + c @ v105;
        loop l106: a @ v105 + b @ u106 == (d, 0) + c @ v106;
        loop l107: a @ v106 + b @ u107 == (d, 0) + c @ v107;
        loop l108: a @ v107 + b @ u108 == (d, 0) + c @ v108;
        loop l109: a @ v108 + b @ u109 == (d, 0) + c @ v109;
        loop l110: a @ v109 + b @ u110 == (d, 0) + c @ v110;
        loop l111: a @ v110 + b @ u111 == (d, 0) + c @ v111;
        loop l112: a @ v111 + b @ u112 == (d, 0) + c @ v112;
        loop l113: a @ v112 + b @ u113 == (d, 0) + c @ v113;
        loop l114: a @ v113 + b @ u114 == (d, 0) + c @ v114;
        loop l115: a @ v114 + b @ u115 == (d, 0) + c @ v115;
        loop l116: a @ v115 + b @ u116 == (d, 0) + c @ v116;
        loop l117: a @ v116 + b @ u117 == (d, 0) + c @ v117;
        loop l118: a @ v117 + b @ u118 == (d, 0) + c @ v118;
        loop l119: a @ v118 + b @ u119 == (d, 0) + c @ v119;
        loop l120: a @ v119 + b @ u120 == (d, 0) + c @ v120;
        loop l121: a @ v120 + b @ u121 == (d, 0) + c @ v121;
        loop l122: a @ v121 + b @ u122 == (d, 0) + c @ v122;
        loop l123: a @ v122 + b @ u123 == (d, 0) + c @ v123;
        loop l124: a @ v123 + b @ u124 == (d, 0) + c @ v124;
        loop l125: a @ v124 + b @ u125 == (d, 0) + c @ v125;
        loop l126: a @ v125 + b @ u126 == (d, 0) + c @ v126;
        loop l127: a @ v126 + b @ u127 == (d, 0) + c @ v127;
    }
}

/// The largest sparse block read at run time, over a turn.
#[test]
fn the_ring_of_128_equals_the_compiled_one() {
    let mut model = read(RING128_TEXT);
    assert!(model.decomposition().contains("256x256 sparse"), "{}", model.decomposition());
    let seen = turn(&Ring128::default(), &mut model, 90);
    assert_eq!(seen.states, 90, "{seen:?}");
    eprintln!("ring of 128: {seen:?}");
}

/// The ring of 128 at link lengths (2, 2, 4, 2), solved compiled and at run time from the
/// declared guesses at inputs next to its limit position at `phi = 0`: from there Newton's
/// first steps meet a weak static pivot, and the block (256 unknowns, the largest) is
/// factorised by the dense fallback (a debugger shows one fallback per solve at 0.01, 0.02 and
/// 0.03, in both). At `phi = 0` itself both end singular through the failure paths (the
/// fallback, the descent's normal equations, the extreme-size check). Returns what each solve gave: the positions as bits,
/// or the error's message. Every loop of a solved position is checked closed from the positions
/// alone: `a e^(i theta) + b e^(i u) - d - c e^(i v)`, `theta` the half sum of the input and the
/// last rocker for the first loop and the previous loop's rocker for the others (the
/// declaration, written out apart from the library's residuals).
fn weak_ring128() -> Vec<Result<Vec<u64>, String>> {
    let (a, b, c, d) = (2.0, 2.0, 4.0, 2.0);
    let cfg = NewtonConfig::default();
    let compiled = Ring128 { a, b, c, d };
    let mut model = read(RING128_TEXT);
    for (p, v) in [("a", a), ("b", b), ("c", c), ("d", d)] {
        assert!(model.set_param(p, v));
    }
    let open = |phi: f64, q: &[f64]| {
        let mut worst = 0.0f64;
        for i in 0..128 {
            let (u, v) = (q[2 * i], q[2 * i + 1]);
            let theta = if i == 0 { 0.5 * (phi + q[255]) } else { q[2 * i - 1] };
            let x = a * theta.cos() + b * u.cos() - d - c * v.cos();
            let y = a * theta.sin() + b * u.sin() - c * v.sin();
            worst = worst.max(x.abs()).max(y.abs());
        }
        worst
    };
    // A loop's closure sums four terms of at most the longest link (4): closed to rounding is a
    // few of its ulps (the solve ends with a correction at the rounding level).
    let closed_tol = 16.0 * f64::EPSILON * c;
    let mut seen = vec![];
    for phi in [0.0, 0.01, 0.02, 0.03] {
        let guess = compiled.guess_flat(&[phi]);
        let ck = compiled.kinematics_flat(&[phi], &guess, &cfg).map(|k| k.q.to_vec());
        let rk = model.kinematics(&[phi], &guess, &cfg).map(|k| k.q.clone());
        for q in [ck.as_ref().ok(), rk.as_ref().ok()].into_iter().flatten() {
            let worst = open(phi, q);
            assert!(worst <= closed_tol, "at {phi}: a loop open by {worst:e}");
        }
        assert_eq!(ck.is_ok(), rk.is_ok(), "at {phi}");
        seen.push(ck.map(|q| bits(&q)).map_err(|e| e.to_string()));
        seen.push(rk.map(|q| bits(&q)).map_err(|e| e.to_string()));
    }
    seen
}

/// The largest block (256 unknowns) through the dense fallback and the descent, compiled and at
/// run time, in a test build on a thread with the default 2 MiB stack: its evaluations and
/// matrices are kept off the stack. The same as on a thread with a 64 MiB stack, bit for bit,
/// and closed. `KINLOOP_STACK_KIB` sets the small thread's stack instead (to measure the
/// high-water mark by bisection: the smallest that does not overflow).
#[test]
fn the_largest_block_falls_back_to_the_dense_lu_on_a_default_stack() {
    let on = |stack: usize| {
        std::thread::Builder::new().stack_size(stack).spawn(weak_ring128).expect("thread").join().expect("solved")
    };
    let kib = std::env::var("KINLOOP_STACK_KIB").ok().and_then(|s| s.parse::<usize>().ok()).unwrap_or(2048);
    let small = on(kib << 10);
    // The limit position fails (singular), the solves beside it succeed.
    let solved: Vec<bool> = small.iter().map(Result::is_ok).collect();
    assert_eq!(solved, [false, false, true, true, true, true, true, true], "{small:?}");
    assert_eq!(small, on(64 << 20));
}
