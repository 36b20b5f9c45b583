//! The runtime's layering, checked on its sources: the block solvers (`src/solvers/`) are the
//! bottom layer and import nothing from above them, and no import circle runs anywhere (no
//! modules import each other, directly or around a loop), so that every module can be read,
//! tested and moved with only what is below it.
//!
//! The checker (`layering/checker.rs`) reads `src/**/*.rs` from `lib.rs` down along the `mod`
//! declarations, resolves every `crate::`, `$crate::`, `super::` and `self::` path (in `use`
//! declarations and inline, as `crate::kin::Kin` in a signature) and every `use` of a child
//! module, through the re-exports on the way (`crate::Kin` is `kin::Kin`), to the module that
//! defines the item.
//! Those references are the edges of the module graph; its strongly connected components
//! (Tarjan) are the import circles, printed with the lines that close them:
//!
//! ```text
//! cargo test -p kinloop-runtime --test layering -- --nocapture
//! ```
//!
//! prints the circles of this tree; `KINLOOP_LAYERING_SRC=<dir>` prints (and checks) those of
//! another source tree, e.g. an older revision checked out elsewhere.
//!
//! Comments are not read, doc comments included: an intra-doc link (`[x](crate::kin::Kin)`)
//! compiles to a hyperlink, not to a dependency. A parent's re-export of a descendant's item
//! (`pub use column::Column` in `analysis/mod.rs`) is the parent's face, not an import: the
//! parent contains the child. A module's `#[cfg(test)]` modules are read:
//! their references count for the solvers' boundary (a solver's tests use nothing above the
//! solvers either, so a solver can be tested alone), but not for the circles, which are those
//! of the library as built (a test of a low module may run the solve through the entry points
//! of the module above it).
//!
//! The checker is shared: `codegen/tests/layering.rs` runs it on the code generator's sources,
//! which have no bottom layer, for their import circles. The solvers' rules are the runtime's
//! (`RULES` below).

#[path = "layering/checker.rs"]
mod checker;

use checker::{BottomLayer, Rules, check, name};
use std::path::{Path, PathBuf};

/// The modules (and everything below them) that the solvers may use besides themselves: small
/// leaves that import nothing from above them either (checked: they reference only each
/// other).
const SOLVERS_MAY_USE: [&str; 8] = ["error", "events", "kinds", "trig", "vec2", "angles", "number", "test_rng"];

/// Modules of the crate root's `use` declarations that may name a module (a second path to it,
/// such as `crate::newton` beside `crate::solvers::newton`), with why each stays: none. A
/// module with child modules imports no module.
const MODULE_ALIASES_ALLOWED: [(&str, &str); 0] = [];

/// The runtime's rules: the solvers are its bottom layer, and its root names no module twice.
const RULES: Rules = Rules {
    bottom: Some(BottomLayer { top: "solvers", may_use: &SOLVERS_MAY_USE }),
    module_aliases_allowed: &MODULE_ALIASES_ALLOWED,
};

fn source_dir() -> PathBuf {
    match std::env::var_os("KINLOOP_LAYERING_SRC") {
        Some(dir) => PathBuf::from(dir),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
    }
}

/// The runtime's sources: the solvers are a leaf, no import circle runs anywhere, and the graph
/// holds the imports every layer is known to make (so a scan that read nothing would fail).
#[test]
fn the_solvers_are_the_bottom_layer() {
    let f = check(&source_dir(), &RULES);
    println!("{}", f.text);
    for (a, b) in
        [("paths::sweep", "mechanism"), ("mechanism", "kin"), ("kin", "solvers::"), ("generated", "solvers::")]
    {
        assert!(f.imports(a, b), "the scan lost the import of {b} by {a}:\n{}", f.text);
    }
    assert!(
        f.problems.is_empty(),
        "{} layering problem(s):\n{}\n\n{}",
        f.problems.len(),
        f.problems.join("\n"),
        f.text
    );
    println!("no import circle");
}

/// A small crate whose solver imports the mechanism above it (inline, in a `use` through a
/// re-export, and in its tests), whose two sweep modules import each other, with an alias path
/// and a `#[path]` mount: every rule fires. Neither the parent's re-export of its child's item,
/// nor the test's import, nor a visibility's path (`pub(in crate::drawing)`) closes a circle.
#[test]
fn an_upward_import_is_found() {
    let dir = std::env::temp_dir().join(format!("kinloop-layering-{}", std::process::id()));
    let files = [
        (
            "lib.rs",
            "mod mechanism;\nmod solvers;\nmod error;\nmod paths;\nmod drawing;\nuse solvers::closed;\n\
             pub use mechanism::Mechanism;\n",
        ),
        // A visibility's path (`pub(in crate::drawing)`) restricts an item; it imports nothing.
        ("drawing/mod.rs", "pub mod part;\npub fn draw() { part::line() }\n"),
        ("drawing/part.rs", "pub(in crate::drawing) fn line() {}\n"),
        ("paths/mod.rs", "pub mod sweep;\npub mod curve;\n"),
        ("paths/sweep.rs", "use super::curve::Point;\npub struct Sweep(Point);\n"),
        ("paths/curve.rs", "pub struct Point;\npub fn trace(_: &super::sweep::Sweep) {}\n"),
        ("error.rs", "/// Not an import: [`x`](crate::mechanism::Mechanism).\npub struct Error;\n"),
        (
            "mechanism.rs",
            "use crate::solvers::newton::Config;\npub trait Mechanism { fn c(&self) -> Config; }\n\
             pub fn m() { crate::solvers::closed::h(0) }\n",
        ),
        ("solvers/mod.rs", "pub mod newton;\npub mod closed;\npub use newton::Config;\npub fn helper() {}\n"),
        (
            "solvers/newton.rs",
            "use crate::error::Error;\npub struct Config;\npub fn f(m: &dyn crate::Mechanism) {}\n\
             #[path = \"extra.rs\"]\nmod extra;\npub fn k() { super::helper() }\n",
        ),
        ("solvers/extra.rs", "pub fn g() {}\n"),
        (
            "solvers/closed.rs",
            "pub fn h(_: u8) {}\n#[cfg(test)]\nmod tests {\n    use crate::mechanism::Mechanism;\n}\n",
        ),
    ];
    for (f, text) in files {
        let p = dir.join(f);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }
    let found = check(&dir, &RULES);
    std::fs::remove_dir_all(&dir).unwrap();
    println!("{}\n{}", found.text, found.problems.join("\n"));
    let names: Vec<Vec<String>> = found.circles.iter().map(|c| c.iter().map(name).collect()).collect();
    assert_eq!(names, [vec!["mechanism", "solvers::newton"], vec!["paths::curve", "paths::sweep"]]);
    let expect = [
        "solvers::closed imports mechanism (solvers/closed.rs:4, in its tests)",
        "solvers::newton imports mechanism (solvers/newton.rs:3)",
        "an import circle runs through the solvers: mechanism, solvers::newton",
        "an import circle: paths::curve, paths::sweep",
        "solvers/newton.rs:4: a module mounted by `#[path]`",
        "lib.rs: `use` of module solvers::closed as crate::closed",
    ];
    for e in expect {
        assert!(found.problems.iter().any(|p| p.starts_with(e)), "not found: {e}\n{}", found.problems.join("\n"));
    }
    assert_eq!(found.problems.len(), expect.len(), "{}", found.problems.join("\n"));
}
