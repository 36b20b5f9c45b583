//! The code generator's modules import each other without a circle: a module that needs another's
//! item is not needed by it, directly or around a loop, so that every stage (and every module of
//! a stage) can be read, tested and moved with only what is below it. A parent module declares
//! its children, re-exports their items and holds the entry that calls them; what its children
//! share lives in a child of its own (`plan::block_plan`, `emit::type_names`, ...).
//!
//! The check is the runtime's (`runtime/tests/layering.rs` describes it), run on `src/` with
//! the checker that test uses:
//!
//! ```text
//! cargo test -p kinloop-codegen --test layering -- --nocapture
//! ```
//!
//! prints the module graph's size and its circles with the lines that close them. Only the
//! circles fail this test: the code generator has no bottom layer, and the checker's other
//! findings are printed, not enforced.

#[path = "../../runtime/tests/layering/checker.rs"]
mod checker;

use checker::{Rules, check, name};
use std::path::Path;

#[test]
fn no_import_circle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let f = check(&src, &Rules { bottom: None, module_aliases_allowed: &[] });
    println!("{}", f.text);
    // The stages in order, each importing from the one before it: a scan that read nothing (or
    // lost a stage) would find no circle either.
    for (a, b) in [
        ("semantics", "front"),
        ("semantics", "graph"),
        ("structure", "semantics"),
        ("plan", "graph"),
        ("plan", "structure"),
        ("emit", "plan"),
        ("fallback", "emit"),
    ] {
        assert!(f.imports(a, b), "the scan lost the import of {b} by {a}:\n{}", f.text);
    }
    let circles: Vec<String> = f.circles.iter().map(|c| c.iter().map(name).collect::<Vec<_>>().join(", ")).collect();
    assert!(circles.is_empty(), "{} import circle(s):\n{}\n\n{}", circles.len(), circles.join("\n"), f.text);
    println!("no import circle");
    if !f.problems.is_empty() {
        println!("not enforced here:\n{}", f.problems.join("\n"));
    }
}
