//! The Rust blocks of the project's Markdown files, and the check that a test holds them as
//! written: a snippet copied into a test compiles and runs there, and the check fails when the
//! document and the test part, so a document cannot go on showing code that no longer compiles.

use std::path::Path;

/// The Rust code blocks (```` ```rust ````, ```` ```rust,ignore ````, indented or not) of the
/// Markdown file at `path` (from the repository's root) in its section whose heading line starts
/// with `section`, up to the next heading of the second level (`## `), each as its lines with the
/// indentation of its fence removed.
pub fn rust_blocks(path: &str, section: &str) -> Vec<Vec<String>> {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let mut lines = text.lines().skip_while(|l| !l.starts_with(section));
    assert!(lines.next().is_some(), "{path} has no line starting with {section:?}");
    let mut lines = lines.take_while(|l| !l.starts_with("## "));
    let mut blocks = Vec::new();
    while let Some(fence) = lines.by_ref().find(|l| l.trim_start().starts_with("```rust")) {
        let indent = fence.len() - fence.trim_start().len();
        let block = lines.by_ref().take_while(|l| l.trim_start() != "```");
        blocks.push(block.map(|l| l.get(indent..).unwrap_or(l.trim_start()).to_string()).collect());
    }
    blocks
}

/// Panics unless every non-blank line of `block` is a line of `source`, in the same order (other
/// lines may come between them), each compared with its runs of whitespace made one space, so
/// that formatting the test does not part it from the document.
pub fn assert_written_in(source: &str, block: &[String], what: &str) {
    let squeeze = |l: &str| l.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut source = source.lines().map(squeeze);
    for line in block.iter().map(|l| squeeze(l)).filter(|l| !l.is_empty()) {
        assert!(source.any(|l| l == line), "{what}: the line `{line}` is not in the test that runs it (in this order)");
    }
}
