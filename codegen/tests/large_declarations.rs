//! Declarations whose expressions share subexpressions many times over are planned in time and
//! memory about proportional to their size: the planner walks each node of the expression graph
//! a bounded number of times, not each path through it (a chain of `n` lets, each using the
//! one before twice, has `2^n` paths). Without that bound these declarations would keep the
//! compiler (or `kinloop check`) busy for hours: the tests finish, or hang.

use proc_macro2::TokenStream;

/// A declaration with `lets` lets, the `i`-th one written by `let_i(i)`, and one equation in
/// the last of them.
fn declaration(lets: usize, let_i: impl Fn(usize) -> String, equation: &str) -> TokenStream {
    let body: String = (1..=lets).map(|i| format!("let l{i} = {};\n", let_i(i))).collect();
    let eq = equation.replace("LAST", &format!("l{lets}"));
    let text = format!("pub struct D {{ params a = 1; input phi; unknowns q = 0; let l0 = a * phi;\n{body}{eq} }}");
    text.parse().expect("declaration tokens")
}

/// Plans the declaration as `mechanism!` does, and checks that it succeeds.
fn plans(decl: TokenStream) {
    if let Err(e) = kinloop_codegen::plan_declaration(decl) {
        panic!("not planned: {e}");
    }
}

/// `l_i = l_(i-1) + l_(i-1) (phi + i)`, 40 deep: `phi` appears scaled in the argument of the
/// sine along `2^40` paths.
#[test]
fn a_chain_of_shared_products_is_planned() {
    plans(declaration(40, |i| format!("l{0} + l{0} * (phi + {i})", i - 1), "eq e: q == sin(LAST) * phi;"));
}

/// `l_i = sin(l_j) cos(l_j) + l_j phi` over 800 lines, each `l_j` an earlier line: arguments
/// nested and shared hundreds of times.
#[test]
fn hundreds_of_nested_arguments_are_planned() {
    plans(declaration(800, |i| format!("sin(l{0}) * cos(l{0}) + l{0} * phi", i - 1), "eq e: q == LAST * phi;"));
}
