//! Fuzz target: any text that lexes as Rust tokens goes through `kinloop_codegen::expand` and
//! `analyze`, which must not panic, overflow the stack or hang. Run with
//! `cargo +nightly fuzz run expand` from the repository root (see README.md, "Fuzzing").
#![no_main]

use libfuzzer_sys::fuzz_target;
use proc_macro2::TokenStream;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    // Text that is not a token stream never reaches a procedural macro: the compiler rejects it.
    let Ok(tokens) = text.parse::<TokenStream>() else { return };
    let _ = kinloop_codegen::analyze(tokens.clone());
    let out = kinloop_codegen::expand(tokens);
    // The expansion must be tokens the compiler can read back.
    assert!(out.to_string().parse::<TokenStream>().is_ok());
});
