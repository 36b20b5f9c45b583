//! Fuzz target: any text goes through the run-time reader (`kinloop_model::Model::read`: lexing,
//! the macro's front end, checks and plan) and, when accepted, one solve; none may panic,
//! overflow the stack or hang. Run with `cargo +nightly fuzz run read_model` from the repository
//! root (see README.md, "Fuzzing").
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(mut model) = kinloop_model::Model::read("fuzz.kl", text) {
        let inputs = vec![0.5; model.inputs().len()];
        let _ = model.solve(&inputs);
    }
    // The reader keeps no span: the lexer's per-thread source map can be emptied, which bounds
    // the memory of a long run.
    kinloop_model::source::forget_spans();
});
