//! A 2x2 block's analogs come from its explicit inverse (`Inverse2::in_cols`), equilibrated by
//! its Jacobian columns: the block's own entries and, passed separately, the entries of the
//! columns beyond it (the rows of later blocks that hold the block's unknowns).

use proc_macro2::TokenStream;

/// The fused kernel of `decl`, as expanded text without whitespace.
fn fused_kernel(decl: &str) -> String {
    let tokens: TokenStream = decl.parse().expect("declaration tokens");
    let file: syn::File = syn::parse2(kinloop_codegen::expand(tokens)).expect("expansion is a file");
    let code = prettyplease::unparse(&file);
    code[code.find("fn kinematics_step_sink").expect("the fused kernel")..].split_whitespace().collect()
}

/// The inverse statement of block `b`.
fn inverse_of(kernel: &str, b: usize) -> String {
    let at = kernel.find(&format!("let__lu{b}=")).unwrap_or_else(|| panic!("no factorisation of block {b}"));
    kernel[at..at + kernel[at..].find(';').expect("end of statement")].to_string()
}

/// A four-bar whose coupler carries a second dyad: `beta` also appears in the second loop, so
/// the first block's column of `beta` reaches beyond it; `gamma`'s does not.
const WATT: &str = "pub struct Watt {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, e = 2.0, f = 2.8, g = 1.5, h = 2.6, k = 3.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, delta = 0.2, eps = 1.8;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop second: a @ phi + e @ (beta + 0.3) + f @ delta == (g, h) + k @ eps;
    }";

#[test]
fn a_column_reaching_a_later_block_passes_its_further_entries() {
    let kernel = fused_kernel(WATT);
    let first = inverse_of(&kernel, 0);
    assert!(first.contains("Inverse2::in_cols("), "{first}");
    // Two entries of `beta`'s column lie in the second loop's rows; `gamma`'s column has none
    // (padded with zeros to the same length).
    let beyond = &first[first.find(",[[").expect("the entries beyond the block")..];
    assert!(beyond.starts_with(",[[j_second_x_beta,j_second_y_beta],[0.0,0.0]]"), "{beyond}");
    // The second dyad's columns hold only its own rows.
    let second = inverse_of(&kernel, 1);
    assert!(second.contains(",[[],[]]"), "{second}");
}
