//! Snapshot tests of the code `mechanism!` generates, pretty-printed, so that every change to
//! code generation is reviewed as a readable diff of the `.snap` files in `tests/snapshots/`.
//!
//! After an intended change: `INSTA_UPDATE=always cargo test -p kinloop-codegen --test snapshots`
//! (or `cargo insta review` with cargo-insta installed), then read the diff of every `.snap`.

use proc_macro2::TokenStream;

/// The expansion of `decl`, formatted by prettyplease.
fn expanded(decl: &str) -> String {
    let tokens: TokenStream = decl.parse().expect("declaration tokens");
    let out = kinloop_codegen::expand(tokens);
    let file: syn::File = syn::parse2(out.clone()).unwrap_or_else(|e| panic!("expansion is not a file: {e}\n{out}"));
    prettyplease::unparse(&file)
}

#[test]
fn offset_slider_crank() {
    let code = expanded(
        "/// Offset slider-crank: crank `r`, rod `l`, slider on the line y = e.
         pub struct SliderCrank {
             params r = 1.0, l = 3.0, e = 0.2;
             input phi;
             unknowns psi = 0, x = r + l;
             loop oabo: r @ phi == (x, e) + l @ psi;
             point mid = r @ phi + 0.5 * l @ psi;
         }",
    );
    insta::assert_snapshot!(code);
}

#[test]
fn four_bar() {
    let code = expanded(
        "/// Four-bar linkage: crank `a`, coupler `b`, rocker `c`, frame `d`.
         pub struct FourBar {
             params a, b, c, d;
             input phi;
             unknowns beta = 0.5, gamma = 1.5;
             loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
             output transmission = gamma - beta;
         }",
    );
    insta::assert_snapshot!(code);
}

/// Closed forms: the four-bar's coupler and rocker by circle intersection (one square root,
/// the branch from the sign of the cross product at the guess), the Jacobian only for the
/// analogs, and no `sin_cos` of the solved angles.
#[test]
fn closed_form_rrr_dyad() {
    let code = expanded(
        "/// Four-bar linkage: crank `a`, coupler `b`, rocker `c`, frame `d`.
         pub struct FourBar {
             params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
             input phi;
             unknowns beta = 0.5, gamma = 1.5;
             loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
         }",
    );
    assert!(code.contains("closed form, RRR dyad"), "{code}");
    insta::assert_snapshot!(code);
}

/// Closed forms: an inclined slide couples the rod angle and the slider in one block (angle
/// from the slider-free combination of the two projections, then the slider); a slotted rocker
/// gets its length and angle from the crank pin.
#[test]
fn closed_form_angle_slider_and_length_angle() {
    let code = expanded(
        "/// Slider-crank on an inclined slide, and a slotted rocker on the same crank.
         pub struct Tilted {
             params r = 1.0, l = 2.6, tilt = 0.5, h = 1.8;
             input phi;
             unknowns psi = 0, x = 3, s = 2.8, theta = 1.57;
             loop slide: r @ phi == x @ tilt + l @ psi;
             loop slot: (0, h) + r @ phi == s @ theta;
         }",
    );
    assert!(code.contains("closed form, angle and slider") && code.contains("closed form, length and angle"), "{code}");
    insta::assert_snapshot!(code);
}

/// A rejected declaration: the `compile_error!`s and the fallback items emitted next to them.
#[test]
fn rejected_declaration_fallback() {
    let code = expanded(
        "pub struct FourBar {
             params a = 1.0, b = 3.0, c = 2.5, d = 3.5;
             input phi;
             unknowns beta, gamma, delta;
             loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma + c @ delta;
             point coupler = a @ phi + b @ beta;
         }",
    );
    assert!(code.contains("compile_error!"), "{code}");
    assert!(!code.contains("fn solve"), "the fallback must not pretend to solve:\n{code}");
    insta::assert_snapshot!(code);
}

/// A Newton block (the four-bar's loop solved by Newton): the guess's evaluation seeds the
/// solve's `NearTrig` with libm's sines and cosines, and the solver's evaluation closure rotates
/// them.
#[test]
fn newton_block() {
    let code = expanded(
        "/// Four-bar linkage solved by Newton.
         #[kinloop(newton)]
         pub struct FourBarNewton {
             params a, b, c, d;
             input phi;
             unknowns beta = 0.5, gamma = 1.5;
             loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
         }",
    );
    insta::assert_snapshot!(code);
}
