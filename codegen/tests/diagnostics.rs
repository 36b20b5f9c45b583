//! Diagnostics as data: what `analyze` and `expand` return for flawed declarations (the
//! rendered messages are pinned by the trybuild UI tests in `tests/ui/`).

use proc_macro2::TokenStream;

fn tokens(src: &str) -> TokenStream {
    src.parse().expect("tokens")
}

fn errors(src: &str) -> Vec<String> {
    match kinloop_codegen::analyze(tokens(src)) {
        Ok(_) => Vec::new(),
        Err(e) => e.into_iter().map(|e| e.to_string()).collect(),
    }
}

#[test]
fn unused_parameters_are_warnings_unless_prefixed_with_underscore() {
    let a = kinloop_codegen::analyze(tokens(
        "pub struct S { params r, l, mass, _speed; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; }",
    ))
    .unwrap_or_else(|e| panic!("{e}"));
    let msgs: Vec<&str> = a.warnings.iter().map(|w| w.message.as_str()).collect();
    assert_eq!(msgs.len(), 1, "{msgs:?}");
    assert!(msgs[0].starts_with("parameter `mass` is used in no loop"), "{msgs:?}");
    // The expansion compiles the mechanism and carries the warning.
    let out = kinloop_codegen::expand(tokens(
        "pub struct S { params r, l, mass; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; }",
    ))
    .to_string();
    assert!(!out.contains("compile_error"));
    assert!(out.contains("deprecated") && out.contains("unused_parameter_mass"));
}

#[test]
fn structural_problem_is_one_primary_error_then_short_notes() {
    let e = errors(
        "pub struct FourBar { params a, b, c, d; input phi; unknowns beta, gamma, delta;
         loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma + c @ delta; }",
    );
    assert_eq!(e.len(), 3, "{e:#?}");
    assert!(e[0].starts_with("`FourBar` is under-determined: 2 scalar equations for 3 unknowns"), "{e:#?}");
    // Mobility stated once, in the primary error.
    assert_eq!(e.iter().filter(|m| m.contains("mobility")).count(), 1, "{e:#?}");
    assert!(e[0].contains("mobility W = 3 unknowns + 1 input - 2 equations = 2"), "{e:#?}");
    assert!(e[1].starts_with("`beta`, `gamma`, `delta` are not determined"), "{e:#?}");
    assert!(e[2].starts_with("`loop abcd` is in the under-determined part"), "{e:#?}");
    assert!(e[1..].iter().all(|m| m.len() < 120 && !m.contains('\n')), "notes stay short: {e:#?}");
}

#[test]
fn over_determined_loops_are_each_named() {
    let e = errors(
        "pub struct FourBar { params a, b, c, d; input phi; unknowns beta, gamma;
         loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
         loop adcb: (d, 0) + c @ gamma - b @ beta == a @ phi; }",
    );
    assert_eq!(e.len(), 3, "{e:#?}");
    assert!(e[0].contains("over-determined part: 4 equations `abcd.x`, `abcd.y`, `adcb.x`, `adcb.y`"), "{e:#?}");
    assert!(e[1].starts_with("`loop abcd` is in the over-determined part"), "{e:#?}");
    assert!(e[2].starts_with("`loop adcb` is in the over-determined part"), "{e:#?}");
}

#[test]
fn errors_of_one_stage_are_all_reported() {
    let e = errors(
        "pub struct S { params r, l, e; input phi; unknowns psi, x;
         loop oab: r @ phi + e == (x, 0) + l @ pis; point b = x; output w = log(x); }",
    );
    assert_eq!(e.len(), 4, "{e:#?}");
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi = 0f64, x;
         loop r @ phi == (x, 0) + l @ psi; eq e: x = 2 * r; point p = (x, 0, 0); }",
    );
    assert_eq!(e.len(), 4, "{e:#?}");
}

#[test]
fn fallback_items_come_with_errors_once_the_name_is_known() {
    let out = kinloop_codegen::expand(tokens(
        "pub struct FourBar { params a = 1.0, b; input phi; unknowns beta, gamma, delta;
         loop abcd: a @ phi + b @ beta == (0, 0) + b @ gamma + b @ delta; }",
    ))
    .to_string();
    assert!(out.contains("compile_error"));
    for item in ["struct FourBar", "struct FourBarInputs", "struct FourBarUnknowns", "struct FourBarState"] {
        assert!(out.contains(item), "missing `{item}` in {out}");
    }
    // No method pretends to solve anything.
    assert!(!out.contains("fn solve") && !out.contains("fn kinematics"), "{out}");
    // Not every parameter has a default: no `Default`.
    assert!(!out.contains("Default for FourBar"), "{out}");

    // Before the name is known there is nothing to fall back on.
    let out = kinloop_codegen::expand(tokens("pub fn nope() {}")).to_string();
    assert!(out.contains("compile_error") && !out.contains("derive"), "{out}");
}

#[test]
fn a_missing_semicolon_loses_no_item() {
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi, x
         loop oab: r @ phi == (x, 0) + l @ psi; output w = x }",
    );
    assert_eq!(e.len(), 2, "{e:#?}");
    assert!(e[0].starts_with("expected `;` at the end of this `unknowns` item (before `loop`)"), "{e:#?}");
    assert!(e[1].starts_with("expected `;` at the end of this `output` item"), "{e:#?}");
    // The items were kept: the fallback knows the unknowns.
    let out = kinloop_codegen::expand(tokens(
        "pub struct S { params r, l; input phi; unknowns psi, x
         loop oab: r @ phi == (x, 0) + l @ psi; }",
    ))
    .to_string();
    assert!(out.contains("pub psi"), "{out}");
}
