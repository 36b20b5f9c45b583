//! What the run-time evaluator does not evaluate yet is refused when the model is built, with
//! the reason, never evaluated differently from the compiled mechanism: a dense block of more
//! than `MAX_DENSE` unknowns. Every block solved by sparse Newton is evaluated: `MAX_SPARSE` is
//! the language's limit of unknowns.

use kinloop_model::{MAX_DENSE, MAX_SPARSE, Model, ReadError};

/// A ring of `n` four-bar loops closed through the input: one coupled block of `2n` unknowns.
fn ring(n: usize, dense: bool) -> String {
    let unknowns: Vec<String> = (0..n).map(|i| format!("u{i} = 0.6, v{i} = 1.9")).collect();
    let mut loops = vec![format!("loop l0: a @ (0.5 * (phi + v{})) + b @ u0 == (d, 0) + c @ v0;", n - 1)];
    loops.extend((1..n).map(|i| format!("loop l{i}: a @ v{} + b @ u{i} == (d, 0) + c @ v{i};", i - 1)));
    format!(
        "{} pub struct Ring {{ params a = 1.0, b = 3.0, c = 2.5, d = 3.2; input phi; unknowns {}; {} }}",
        if dense { "#[kinloop(dense)]" } else { "" },
        unknowns.join(", "),
        loops.join(" ")
    )
}

#[test]
fn large_blocks_are_refused_with_the_reason() {
    // Sparse blocks are evaluated up to the language's limit (`sparse_parity.rs` solves both
    // rings); one unknown more is rejected by the macro's own check, before any block is planned.
    assert!(Model::read("ring.kl", &ring(9, false)).is_ok());
    assert!(Model::read("ring.kl", &ring(MAX_SPARSE / 2, false)).is_ok());
    match Model::read("ring.kl", &ring(MAX_SPARSE / 2 + 1, false)) {
        Err(ReadError::Rejected(d)) => {
            assert!(d.items.iter().any(|i| i.message.contains(&format!("at most {MAX_SPARSE} unknowns"))), "{d}")
        }
        other => panic!("expected a rejection, got {:?}", other.map(|m| m.name().to_string())),
    }
    match Model::read("ring.kl", &ring(9, true)) {
        Err(ReadError::Unsupported(why)) => assert!(why.contains(&format!("at most {MAX_DENSE}")), "{why}"),
        other => panic!("expected a refusal, got {:?}", other.map(|m| m.name().to_string())),
    }
    // A ring small enough for a dense block is evaluated.
    let mut small = Model::read("ring.kl", &ring(2, true)).expect("a 4x4 dense block");
    assert!(small.solve(&[0.3]).is_ok());
}
