//! Compile-fail tests: every diagnostic of `mechanism!` is pinned by a `.stderr` file.
//! Regenerate after an intended change with `TRYBUILD=overwrite cargo test --test ui` and review
//! the diff of every `.stderr`.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*/*.rs");
}
