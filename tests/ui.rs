//! Compile-fail tests: every diagnostic of `mechanism!` is pinned by a `.stderr` file, one case
//! per file, in category folders:
//!
//! * `syntax/`: the declaration's grammar (missing `;`, `=` for `==`, number suffixes, ...);
//! * `names/`: name resolution (unknown, duplicate, used before its `let`, unsupported function);
//! * `types/`: vectors versus scalars (`r @ phi + gamma`, a `loop` of scalars, wrong arity, ...);
//! * `structure/`: counts and mobility, over- and under-determined parts, unused names;
//! * `limits/`: declarations too deep or too large, rejected before expansion would overflow the
//!   stack or take too long;
//! * `fallback/`: the items emitted next to the errors keep user code free of secondary errors;
//! * `combined/`: several mistakes in one declaration are all reported at once;
//! * `analysis/`: the generated typed columns (`Name::COL.x`) make a misspelled column, or a
//!   column of another mechanism, a compile error.
//!
//! Regenerate after an intended change with `TRYBUILD=overwrite cargo test --test ui` and review
//! the diff of every `.stderr`: each message must say what is wrong, where, and what to write.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*/*.rs");
}
