//! How the expansion names its temporaries: declared quantities after themselves, terms that
//! several quantities share and short subexpressions after their form.

use proc_macro2::TokenStream;

/// The formatted expansion of `decl`.
fn expanded(decl: &str) -> String {
    let tokens: TokenStream = decl.parse().expect("declaration tokens");
    let file: syn::File = syn::parse2(kinloop_codegen::expand(tokens)).expect("expansion is a file");
    prettyplease::unparse(&file)
}

const COUPLER_FOUR_BAR: &str = "
    pub struct CouplerFourBar {
        params a, b, c, d, e, f;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point p = a @ phi + e @ (beta + f);
    }";

/// `a cos phi` is the loop's derivative by `phi` on Y, a term of its residual on X and of the
/// coupler point: named by its form, not as the derivative the output would read as built from.
#[test]
fn a_term_several_quantities_share_is_named_by_its_form() {
    let code = expanded(COUPLER_FOUR_BAR);
    assert!(code.contains("let a_cos_phi: ::core::primitive::f64 = self.a * cos_phi;"), "{code}");
    assert!(code.contains("let out_p_x: ::core::primitive::f64 = a_cos_phi + "), "{code}");
    assert!(code.contains("__jac.fx[1][0] = a_cos_phi;"), "{code}");
    assert!(!code.contains("fx_abcd_y_phi"), "{code}");
    // A derivative nothing else is computed from keeps its role's name.
    assert!(code.contains("let j_abcd_x_beta: ::core::primitive::f64 = -b_sin_beta;"), "{code}");
}

/// The analogs of a declared output are named after it, by input.
#[test]
fn the_analogs_of_an_output_are_named_after_it() {
    let code = expanded(COUPLER_FOUR_BAR);
    for name in ["dout_p_x_phi", "dout_p_y_phi", "d2out_p_x_phi_phi", "d2out_p_y_phi_phi"] {
        assert!(code.contains(&format!("let {name}: ::core::primitive::f64 = ")), "{name}: {code}");
    }
}

/// A form that would read as a leaf's local (an input `x_phi`) is not a name: the temporary
/// stays anonymous rather than shadow the input.
#[test]
fn a_form_spelled_like_a_leaf_is_not_a_name() {
    let code = expanded(
        "pub struct S { params x = 1, phi = 2, l = 3; input th; unknowns s = 1;
            eq e: s == x * phi + th * l; }",
    );
    assert!(code.contains(": ::core::primitive::f64 = self.x * self.phi;") && !code.contains("let x_phi"), "{code}");
    assert!(code.contains("let th_l: ::core::primitive::f64 = x_th * self.l;"), "{code}");
}

/// A `let` names the temporary that holds its value (a vector's components `_x`, `_y`), after
/// `let_`: the name alone may read as one the generator gives (here `t2`, an anonymous
/// temporary's spelling), or be a constant of the user's module, which would make the binding a
/// pattern.
#[test]
fn a_let_names_the_temporary_it_produced() {
    let code = expanded(
        "pub struct Crank { params a, b, c, d; input phi; unknowns beta = 0.5, gamma = 1.5;
            let crank_pin = a @ phi + (0, c);
            let reach = b * cos(beta) + d;
            let t2 = reach * reach;
            loop abcd: crank_pin + b @ beta == (d, 0) + c @ gamma;
            output spread = reach + t2; }",
    );
    assert!(code.contains("let let_crank_pin_x: ::core::primitive::f64 = "), "{code}");
    assert!(code.contains("let let_crank_pin_y: ::core::primitive::f64 = "), "{code}");
    assert!(code.contains("let let_reach: ::core::primitive::f64 = "), "{code}");
    assert!(code.contains("let let_t2: ::core::primitive::f64 = let_reach * let_reach;"), "{code}");
}
