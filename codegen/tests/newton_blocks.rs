//! Which Newton blocks hand their final factorisation to their analogs: those whose unknowns'
//! Jacobian columns have no entry outside the block (the column magnitudes the analogs
//! equilibrate by are then known when the block is solved).

use proc_macro2::TokenStream;

/// The statement that solves block `b` in the kernel a point solve and a sweep call
/// (`kinematics_step_flat`), as expanded text without whitespace.
fn newton_call(decl: &str, b: usize) -> String {
    let tokens: TokenStream = decl.parse().expect("declaration tokens");
    let file: syn::File = syn::parse2(kinloop_codegen::expand(tokens)).expect("expansion is a file");
    let code = prettyplease::unparse(&file);
    let kernel = &code[code.find("fn kinematics_step_flat").expect("the fused kernel")..];
    let at = kernel.find(&format!("let __r{b} = ")).unwrap_or_else(|| panic!("no Newton call for block {b}"));
    kernel[at..at + kernel[at..].find(';').expect("end of statement")].split_whitespace().collect()
}

/// A four-bar whose coupler carries a second dyad, both solved by Newton: the coupler angle
/// `beta` also appears in the second loop, so the first block's columns reach outside it.
const WATT: &str = "#[kinloop(newton)]
    pub struct Watt {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, e = 2.0, f = 2.8, g = 1.5, h = 2.6, k = 3.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, delta = 0.2, eps = 1.8;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop second: a @ phi + e @ (beta + 0.3) + f @ delta == (g, h) + k @ eps;
    }";

#[test]
fn a_block_with_its_columns_inside_keeps_its_factorisation() {
    let call = newton_call(WATT, 1);
    assert!(call.contains("newton_keeping_lu::<2,") && call.contains("&mut__lu1)"), "{call}");
}

#[test]
fn a_block_whose_columns_reach_a_later_block_factorises_again() {
    let call = newton_call(WATT, 0);
    assert!(call.contains("::newton::<2,") && !call.contains("__lu0"), "{call}");
}
