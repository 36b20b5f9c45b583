//! Macro expansion as a plain function call (`kinloop_codegen::expand`) and the size of what it
//! generates.

use proc_macro2::TokenStream;

/// The token stream of a declaration body (what `mechanism!` receives).
pub fn tokens(text: &str) -> TokenStream {
    text.parse().expect("a declaration's text is valid Rust tokens")
}

/// Expands a declaration as the macro does.
pub fn expand(text: &str) -> TokenStream {
    kinloop_codegen::expand(tokens(text))
}

/// Size of one expansion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    /// Lines of the expansion formatted by prettyplease (as `cargo run -p kinloop-codegen
    /// --example expand` prints it).
    pub lines: usize,
    /// Token trees of the expansion (independent of formatting).
    pub tokens: usize,
}

fn count_tokens(ts: TokenStream) -> usize {
    ts.into_iter()
        .map(|t| match t {
            proc_macro2::TokenTree::Group(g) => 1 + count_tokens(g.stream()),
            _ => 1,
        })
        .sum()
}

/// Expands `text` and measures the result. Panics when the expansion is a compile error.
pub fn size(text: &str) -> Size {
    let out = expand(text);
    let file: syn::File = syn::parse2(out.clone()).expect("the expansion parses as a file");
    let pretty = prettyplease::unparse(&file);
    assert!(!pretty.contains("compile_error"), "the declaration does not expand cleanly:\n{pretty}");
    Size { lines: pretty.lines().count(), tokens: count_tokens(out) }
}

/// A synthetic declaration with `k` four-bar loops in series (loop `i` is driven by the rocker
/// of loop `i - 1`): `2k` equations in `k` blocks of two, for the growth of the generated code
/// with the number of equations.
pub fn four_bar_chain(k: usize) -> String {
    loops("Chain", k, "phi".to_string())
}

/// The same `k` loops closed into a ring through a differential: the first loop is driven by
/// `(phi + v_(k-1)) / 2` (see [`crate::ring`]), which couples all `2k` unknowns into one sparse
/// Newton block.
pub fn four_bar_ring(k: usize) -> String {
    loops("Ring", k, format!("(0.5 * (phi + v{}))", k.saturating_sub(1)))
}

/// `k` four-bar loops, each driven by the rocker of the one before, the first by `first`.
fn loops(name: &str, k: usize, first: String) -> String {
    let mut s = format!("pub struct {name} {{\n    params a = 1.0, b = 3.0, c = 2.5, d = 3.2;\n    input phi;\n");
    let unknowns: Vec<String> = (0..k).map(|i| format!("u{i} = 0.6, v{i} = 1.9")).collect();
    s += &format!("    unknowns {};\n", unknowns.join(", "));
    for i in 0..k {
        let driver = if i == 0 { first.clone() } else { format!("v{}", i - 1) };
        s += &format!("    loop l{i}: a @ {driver} + b @ u{i} == (d, 0) + c @ v{i};\n");
    }
    s += "}\n";
    s
}

/// The same chain declared `#[kinloop(dense)]`: one block of `2k` unknowns (what the block
/// decomposition saves).
pub fn four_bar_chain_dense(k: usize) -> String {
    format!("#[kinloop(dense)]\n{}", four_bar_chain(k))
}
