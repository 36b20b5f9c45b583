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

const SLIDER: &str = "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";

#[test]
fn mechanism_names_that_would_shadow_what_the_expansion_uses_are_one_error() {
    for (name, says) in [
        ("f64", "it is a primitive type"),
        ("usize", "it is a primitive type"),
        ("kinloop", "the name of a crate"),
        ("core", "the name of a crate"),
        ("std", "the name of a crate"),
        ("T", "the type parameter of the generated types"),
        ("gen", "reserved keyword in Rust 2024"),
    ] {
        let src = format!("pub struct {name} {{ {SLIDER} }}");
        let e = errors(&src);
        assert_eq!(e.len(), 1, "{name}: {e:#?}");
        assert!(e[0].contains(says), "{name}: {e:#?}");
        // No fallback item may use the name: only the error comes out.
        let out = kinloop_codegen::expand(tokens(&src)).to_string();
        assert_eq!(out.matches("compile_error").count(), 1, "{name}: {out}");
        assert!(!out.contains("struct"), "{name}: {out}");
    }
    // Names that merely resemble them are fine, and so is the raw identifier of a keyword.
    for name in ["F64", "Kinloop", "Tee", "Gen", "r#gen"] {
        assert!(errors(&format!("pub struct {name} {{ {SLIDER} }}")).is_empty(), "{name}");
    }
}

#[test]
fn a_reserved_keyword_as_a_declared_name_is_one_error_per_name() {
    for (body, what) in [
        ("params r, l, gen; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;", "a parameter"),
        ("params r, l; input gen; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;", "an input"),
        ("params r, l; input phi; unknowns psi, x, gen; loop c: r @ phi == (x, 0) + l @ psi;", "an unknown"),
        (&format!("{SLIDER} point gen = (x, 0);"), "a `point`"),
        (&format!("{SLIDER} output gen = x;"), "an `output`"),
        (&format!("{SLIDER} let gen = x;"), "a `let`"),
        ("params r, l; input phi; unknowns psi, x; loop gen: r @ phi == (x, 0) + l @ psi;", "a `loop`"),
    ] {
        let src = format!("pub struct S {{ {body} }}");
        let e = errors(&src);
        assert_eq!(e.len(), 1, "{what}: {e:#?}");
        assert!(
            e[0].starts_with(&format!("`gen` is a reserved keyword in Rust 2024 and cannot name {what}")),
            "{e:#?}"
        );
        assert!(e[0].contains("`gen_`") && e[0].contains("`r#gen`"), "says what to write: {e:#?}");
        // The fallback items leave the name out (a field `gen` would be one more error).
        let out = kinloop_codegen::expand(tokens(&src)).to_string();
        assert_eq!(out.matches("compile_error").count(), 1, "{what}: {out}");
        assert!(!out.contains(" gen "), "{what}: {out}");
    }
    // The raw identifier works end to end.
    let ok = "pub struct S { params r, l, r#gen = 1.0; input phi; unknowns psi, x;
              loop c: r @ phi == (x, 0) + l @ psi; output o = r#gen * x; }";
    assert!(errors(ok).is_empty());
    assert!(!kinloop_codegen::expand(tokens(ok)).to_string().contains("compile_error"));
}

#[test]
fn nesting_beyond_the_limit_is_one_error_at_the_first_bracket_too_deep() {
    let deep = |n: usize| format!("pub struct S {{ {SLIDER} output o = {}x{}; }}", "(".repeat(n), ")".repeat(n));
    // The body's braces are level 1: 255 parentheses inside them reach the limit of 256 and
    // pass this check (the expression parser has its own, smaller limit).
    let at = errors(&deep(255));
    assert!(at.iter().all(|m| !m.contains("levels deep, the most kinloop accepts")), "{at:#?}");
    let over = errors(&deep(256));
    assert_eq!(over.len(), 1, "{over:#?}");
    assert!(over[0].starts_with("brackets nested more than 256 levels deep"), "{over:#?}");
}

#[test]
fn the_largest_test_mechanisms_are_far_below_the_size_limit() {
    // The class IV mechanism with outputs (81 operations): the limit leaves room for over fifty.
    let a = kinloop_codegen::analyze(tokens(
        "pub struct ClassFour {
             params oa = 1.0, xb = 4.4, yb = 0.6, ac = 2.3, ae = 2.4, alpha_a = 0.84,
                    bd = 1.6, bf = 3.5, alpha_b = 0.62, cd = 2.0, ef = 3.4;
             input phi;
             unknowns th1 = 1.4, th2 = 3.0, psi1 = -0.8, psi2 = -1.0;
             let a = oa @ phi;
             let b = (xb, yb);
             loop acdb: a + ac @ th1 + cd @ psi1 == b + bd @ th2;
             loop aefb: a + ae @ (th1 + alpha_a) + ef @ psi2 == b + bf @ (th2 + alpha_b);
             point c = a + ac @ th1; point d = b + bd @ th2; point e = a + ae @ (th1 + alpha_a);
             output angle_sum = th1 + th2 + psi1 + psi2;
         }",
    ))
    .unwrap_or_else(|e| panic!("{e}"));
    let limit = kinloop_codegen::model::MAX_MODEL_NODES;
    assert!(a.model.graph.len() * 50 < limit, "{} nodes", a.model.graph.len());
}

#[test]
fn an_angle_sum_without_parentheses_at_the_end_of_a_chain_gets_the_fix() {
    // A rotating guide offset by `delta`: the polar term is the last of a chain of vectors,
    // so `+ delta` meets the whole chain, not the polar term alone.
    let e = errors(
        "pub struct Guide { params r, d, delta; input phi; unknowns th, s;
         loop g: r @ phi == (0, -d) + s @ th + delta; }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("cannot add a vector and a scalar"), "{e:#?}");
    assert!(e[0].contains("write `s @ (th + delta)`"), "{e:#?}");
    let e = errors(
        "pub struct Guide { params r, d, delta; input phi; unknowns th, s;
         loop g: r @ phi == (0, -d) - s @ th - delta; }",
    );
    assert!(e[0].contains("write `s @ (th - delta)`"), "{e:#?}");
    // A literal zero is not an angle offset: no parentheses are suggested for it.
    let e = errors(
        "pub struct Guide { params r, d; input phi; unknowns th, s;
         loop g: r @ phi == (0, -d) + s @ th + 0; }",
    );
    assert!(e[0].starts_with("cannot add a vector and a scalar") && !e[0].contains("help"), "{e:#?}");
}

#[test]
fn an_unknown_in_no_equation_is_not_counted_in_the_under_determined_equations() {
    // `s` is in no loop at all; `x` and `t` share the loop's x projection alone.
    for extra in ["", "point q = (s, 0); output o = s;"] {
        let e = errors(&format!(
            "pub struct S {{ params r, l; input phi; unknowns psi, x, s, t;
             loop oab: r @ phi == (x, 0) + l @ psi + t @ 0; {extra} }}"
        ));
        let summary = &e[0];
        assert!(
            summary.contains(
                "under-determined part: 2 unknowns `x`, `t` appear in only 1 equation `oab.x`, \
                 and 1 unknown `s` appears in no equation"
            ),
            "{e:#?}"
        );
        // Removing `s` leaves 3 unknowns for 2 equations: one equation is missing, not two.
        assert!(summary.contains("help: add 1 scalar equation involving `x`, `t`"), "{e:#?}");
        assert!(summary.contains("help: use `s` in a loop or equation, or remove it"), "{e:#?}");
        assert!(
            e.iter().any(|m| m.starts_with("unknown `s` ") && m.contains("appears in no `loop` or `eq`")),
            "{e:#?}"
        );
    }
}

#[test]
fn an_equation_without_unknowns_is_not_counted_in_the_over_determined_unknowns() {
    let e = errors(
        "pub struct S { params r, l, a, b; input phi; unknowns psi, x;
         loop oab: r @ phi == (x, 0) + l @ psi; eq e1: psi == phi; eq e2: a == b; }",
    );
    assert!(
        e[0].contains(
            "over-determined part: 2 equations `oab.y`, `e1` involve only 1 unknown `psi`, \
             and 1 equation `e2` involves no unknown"
        ),
        "{e:#?}"
    );
    assert!(e[0].contains("help: remove 1 scalar equation of the over-determined part"), "{e:#?}");
    assert!(e[0].contains("help: remove `e2` (see the errors below)"), "{e:#?}");
}

#[test]
fn an_unknown_used_only_in_an_output_is_told_to_become_a_let() {
    for (extra, place) in [("point q = (s, 0);", "`point q`"), ("output o = 2 * s;", "`output o`")] {
        let e = errors(&format!(
            "pub struct S {{ params r, l; input phi; unknowns psi, x, s; loop oab: r @ phi == (x, 0) + l @ psi; {extra} }}"
        ));
        let local: Vec<&String> = e.iter().filter(|m| m.starts_with("unknown `s`")).collect();
        assert_eq!(local.len(), 1, "{e:#?}");
        assert!(
            local[0].starts_with(&format!("unknown `s` is used in {place} but appears in no `loop` or `eq`")),
            "{e:#?}"
        );
        assert!(local[0].contains("declare it with `let s = ...;` in place of the unknown"), "{e:#?}");
    }
}

#[test]
fn a_comma_for_the_semicolon_before_the_next_item_is_one_error_at_the_comma() {
    for (src, keyword, next) in [
        ("params r, l, input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;", "params", "input"),
        ("params r, l; input phi, unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;", "input", "unknowns"),
        ("params r, l; input phi; unknowns psi, x, loop c: r @ phi == (x, 0) + l @ psi;", "unknowns", "loop"),
        (
            "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi, point p = (x, 0);",
            "loop",
            "point",
        ),
    ] {
        let src = format!("pub struct S {{ {src} }}");
        let e = errors(&src);
        assert_eq!(e.len(), 1, "{e:#?}");
        assert!(
            e[0].starts_with(&format!(
                "expected `;` at the end of this `{keyword}` item, found `,`: write `;` here, before `{next}`"
            )),
            "{e:#?}"
        );
        // The next item is kept: the fallback still declares its names.
        let out = kinloop_codegen::expand(tokens(&src)).to_string();
        assert!(out.contains("pub phi") && out.contains("pub psi"), "{out}");
    }
    // A parameter may still be named like an item's keyword.
    assert!(
        errors(
            "pub struct S { params r, l, force, mass; input phi; unknowns psi, x;
         loop c: r @ phi == (x, 0) + l @ psi; output o = force * mass * x; }"
        )
        .is_empty()
    );
}

#[test]
fn a_trailing_double_equals_is_told_to_be_removed() {
    let e = errors("pub struct S { params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi ==; }");
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("nothing follows this `==`; remove it"), "{e:#?}");
    // A second equality after it is a chain, written as two items.
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi == (0, 0); }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("an equation has one `==`: write each equality as its own"), "{e:#?}");
}

#[test]
fn a_body_property_given_with_equals_or_colon_is_told_to_drop_it() {
    for (clause, sign) in [("mass = m", "="), ("mass: m", ":")] {
        let e = errors(&format!("pub struct S {{ {SLIDER} params m; body b: {clause}, com (x, 0); }}"));
        assert_eq!(e.len(), 1, "{e:#?}");
        assert!(e[0].starts_with(&format!("no `{sign}` after `mass`: write `mass value`")), "{e:#?}");
    }
}

/// A load written without its name read `at` or `on` as the name, and then asked for the `at`
/// or `on` the user had written.
#[test]
fn a_load_without_its_name_is_told_to_name_it() {
    for (load, says) in [
        (
            "force at (x, 0) = (1, 0);",
            "expected the force's name before `at` (it appears in error messages): `force name at point = (fx, fy);`",
        ),
        (
            "torque on phi = 1;",
            "expected the torque's name before `on` (it appears in error messages): `torque name on angle = scalar;`",
        ),
    ] {
        let e = errors(&format!("pub struct S {{ {SLIDER} params m; body b: mass m, com (x, 0); {load} }}"));
        assert_eq!(e, [says], "{load}");
    }
    // Loads named `at` and `on` are loads all the same.
    let e = errors(&format!(
        "pub struct S {{ {SLIDER} params m; body b: mass m, com (x, 0); \
         force at at (x, 0) = (1, 0); torque on on phi = 1; }}"
    ));
    assert_eq!(e, Vec::<String>::new());
}

/// A misspelt angle after `turns` or `on` is named with the input or unknown meant.
#[test]
fn a_misspelt_angle_of_a_body_or_torque_gets_the_name_meant() {
    let e = errors(&format!(
        "pub struct S {{ {SLIDER} params m; body b: mass m, com (x, 0), turns pis; torque t on ph = 1; }}"
    ));
    assert_eq!(
        e,
        [
            "`turns pis`: `pis` is not declared (did you mean `psi`?); `turns` takes an input or an angle unknown",
            "`on ph`: `ph` is not declared (did you mean `phi`?); `on` takes an input or an angle unknown",
        ]
    );
}

#[test]
fn gravity_without_parentheses_is_told_to_add_them() {
    let e = errors(&format!("pub struct S {{ {SLIDER} params m, g; body b: mass m, com (x, 0); gravity 0, -g; }}"));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("gravity is one vector: write its components in parentheses"), "{e:#?}");
}

#[test]
fn a_loop_projection_without_unknowns_is_not_told_to_be_removed() {
    // The slider's y is given: only the x projection of the loop involves an unknown. A
    // projection cannot be removed from a loop; the loop becomes an `eq`, or gains an unknown.
    let e = errors("pub struct S { params r, e; input phi; unknowns x; loop oab: r @ phi == (x, e); }");
    assert_eq!(e.len(), 2, "{e:#?}");
    assert!(!e[0].contains("remove `oab.y`"), "{e:#?}");
    assert!(e[0].contains("help: write `loop oab` as an `eq` of its other projection, or use in `oab.y`"), "{e:#?}");
    assert!(e[1].starts_with("the y projection of `loop oab` (`oab.y`) contains no unknown"), "{e:#?}");
    assert!(!e[1].contains("help: remove it"), "{e:#?}");
    assert!(e[1].contains("write it as `eq oab: ... == ...;` in place of the loop"), "{e:#?}");
    // An `eq` without unknowns, or a whole loop, can be removed, and is told so.
    let e = errors(&format!("pub struct S {{ {SLIDER} params a; eq k: a == 2; }}"));
    assert!(e[0].contains("help: remove `k` (see the errors below)"), "{e:#?}");
}

#[test]
fn the_name_of_a_loop_or_load_used_as_a_value_is_not_an_unknown_name() {
    for (extra, label) in [
        ("output o = c.x;", "loop c"),
        ("params m; body b: mass m, com (x, 0); output o = b.x;", "body b"),
        ("torque t on psi = 1; output o = t;", "torque t"),
    ] {
        let e = errors(&format!("pub struct S {{ {SLIDER} {extra} }}"));
        assert_eq!(e.len(), 1, "{e:#?}");
        let name = label.split(' ').nth(1).unwrap_or_default();
        assert!(e[0].starts_with(&format!("`{name}` is the name of `{label}`, a label, not a value")), "{e:#?}");
        assert!(!e[0].contains("unknown name"), "{e:#?}");
    }
}

#[test]
fn a_guess_that_uses_an_unknown_through_a_name_says_which_unknown() {
    // Above the guess: the output it names depends on `x`.
    let e = errors(
        "pub struct S { params r, l; input phi; output o = 2 * x; unknowns psi = o, x;
         loop c: r @ phi == (x, 0) + l @ psi; }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("an initial guess cannot use unknowns"), "{e:#?}");
    assert!(e[0].contains("this one depends on `x`"), "{e:#?}");
    // Below the guess: moving it up is the fix only where it uses no unknown.
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi = o, x;
         loop c: r @ phi == (x, 0) + l @ psi; output o = 2 * x; }",
    );
    assert!(e[0].starts_with("`o` is used before it is defined; move `output o = ...;` above this line"), "{e:#?}");
    assert!(e[0].contains("an initial guess may use it only if it uses no unknown"), "{e:#?}");
    // Elsewhere the move is the whole fix, and said alone.
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi, x;
         loop c: p == (x, 0) + l @ psi; point p = r @ phi; }",
    );
    assert!(e[0].ends_with("move `point p = ...;` above this line"), "{e:#?}");
}

#[test]
fn a_vector_in_square_brackets_or_braces_is_told_to_use_parentheses() {
    for (vector, says) in [("[x, 0]", "not `[x, 0]`"), ("{x, 0}", "not `{x, 0}`")] {
        let e = errors(&format!(
            "pub struct S {{ params r, l; input phi; unknowns psi, x; loop c: r @ phi == {vector} + l @ psi; }}"
        ));
        assert_eq!(e.len(), 1, "{e:#?}");
        assert!(e[0].starts_with("a vector is written in parentheses: write `(x, 0)`"), "{e:#?}");
        assert!(e[0].contains(says), "{e:#?}");
    }
}

#[test]
fn a_macro_call_is_told_to_drop_the_bang() {
    let e = errors(&format!("pub struct S {{ {SLIDER} output o = max!(x, 1); }}"));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("kinloop has no macros: call the function without `!`"), "{e:#?}");
}

#[test]
fn a_name_in_the_wrong_case_is_suggested_in_the_right_one() {
    let e = errors(&format!("pub struct S {{ {SLIDER} output o = Sin(x); }}"));
    assert!(e[0].starts_with("unsupported function `Sin`; did you mean `sin`?"), "{e:#?}");
    let e = errors(&format!("pub struct S {{ {SLIDER} output o = PI * x; }}"));
    assert!(e[0].starts_with("unknown name `PI`; did you mean `pi`?"), "{e:#?}");
}

#[test]
fn an_input_the_loops_determine_is_offered_to_become_an_unknown() {
    // The slider's `x` declared an input: the loop over-determines `psi`.
    let e = errors("pub struct S { params r, l; inputs phi, x; unknowns psi; loop c: r @ phi == (x, 0) + l @ psi; }");
    assert!(e[0].contains("or turn 1 parameter or input it uses into an unknown"), "{e:#?}");
    // With one input only, it must stay: parameters alone are offered.
    let e = errors("pub struct S { params r, l, x; input phi; unknowns psi; loop c: r @ phi == (x, 0) + l @ psi; }");
    assert!(e[0].contains("or turn 1 parameter it uses into an unknown"), "{e:#?}");
}

/// An over-determined part that uses no parameter is not told to turn one into an unknown.
#[test]
fn an_over_determined_part_without_parameters_offers_none() {
    let e = errors("pub struct S { input phi; unknowns x; eq e: x == 1 + phi; eq f: x == 2 + phi; }");
    assert_eq!(e.len(), 3, "{e:#?}");
    let help = "help: remove 1 scalar equation of the over-determined part (a loop that repeats another contour?)";
    assert!(e[0].ends_with(help), "{e:#?}");
    // With two inputs, one of them may become the unknown.
    let e = errors("pub struct S { inputs phi, t; unknowns x; eq e: x == phi; eq f: x == t; }");
    assert!(e[0].contains("or turn 1 input it uses into an unknown"), "{e:#?}");
}

/// A vector as the angle of `@` is the one type error: its coordinates are no coordinates of a
/// position, and an angle among them was told to be a length as well.
#[test]
fn a_vector_as_the_angle_of_a_polar_term_is_one_error() {
    for tail in ["point p = r @ (phi, 1);", "loop d: r @ (psi, phi) == (x, 0);", "point p = (phi, 0) @ psi;"] {
        let e = errors(&format!("pub struct S {{ {SLIDER} {tail} }}"));
        assert_eq!(e.len(), 1, "{tail}: {e:#?}");
        assert!(e[0].starts_with("`@` builds a vector from a scalar length and a scalar angle"), "{e:#?}");
    }
}

/// `min`, `max` and `clamp` return one of their arguments: an angle beside a length there is the
/// unit mix a sum of the two is, which compiled into an output that changed with the unit of
/// length. One error per call, however many of its arguments mix.
#[test]
fn an_angle_beside_a_length_in_min_max_or_clamp_is_a_unit_mix() {
    for (tail, shown) in [
        ("output w = max(x, psi);", "max(x, psi)"),
        ("output w = 2 * min(psi, x);", "min(psi, x)"),
        ("output w = clamp(x, 0, psi);", "clamp(x, 0, psi)"),
        ("output w = clamp(psi, x, l);", "clamp(psi, x, l)"),
        ("eq e: u == max(x, phi);", "max(x, phi)"),
    ] {
        let e = errors(&format!(
            "pub struct S {{ {SLIDER} {} {tail} }}",
            if tail.starts_with("eq") { "unknowns u;" } else { "" }
        ));
        assert_eq!(e.len(), 1, "{tail}: {e:#?}");
        assert!(
            e[0].starts_with(&format!("`{shown}` compares an angle and a length, so its value would change")),
            "{e:#?}"
        );
    }
    // Arguments of one kind, or a constant bound, stay as written.
    for tail in ["output w = max(x, l);", "output w = clamp(psi, 0, pi);", "output w = min(phi, psi);"] {
        assert_eq!(errors(&format!("pub struct S {{ {SLIDER} {tail} }}")), Vec::<String>::new(), "{tail}");
    }
}

/// `atan2`, `hypot` and `wrap` of an angle and a length change with the unit of length as their
/// sum does: the same error, "combines". Of one kind, or with a constant, they stay as written.
#[test]
fn an_angle_beside_a_length_in_atan2_hypot_or_wrap_is_a_unit_mix() {
    for (tail, shown) in [
        ("output w = atan2(x, psi);", "atan2(x, psi)"),
        ("output w = hypot(psi, x);", "hypot(psi, x)"),
        ("output w = wrap(x, psi);", "wrap(x, psi)"),
        ("eq e: u == atan2(phi, x);", "atan2(phi, x)"),
    ] {
        let e = errors(&format!(
            "pub struct S {{ {SLIDER} {} {tail} }}",
            if tail.starts_with("eq") { "unknowns u;" } else { "" }
        ));
        assert_eq!(e.len(), 1, "{tail}: {e:#?}");
        assert!(
            e[0].starts_with(&format!("`{shown}` combines an angle and a length, so its value would change")),
            "{e:#?}"
        );
    }
    for tail in [
        "output w = atan2(x, l);",
        "output w = hypot(psi, 0.5);",
        "output w = wrap(psi, 2 * pi);",
        "output w = atan2(sin(psi), cos(psi));",
        "output w = hypot(phi, psi);",
    ] {
        assert_eq!(errors(&format!("pub struct S {{ {SLIDER} {tail} }}")), Vec::<String>::new(), "{tail}");
    }
}

/// A vector of an angle and a length changes with the unit of length as their sum does: its
/// magnitude, its products and its direction. It is refused where it is built (a tuple given to
/// `norm`, `dot`, `cross`, `angle` or `rot`, a sum of vectors), once: a vector built from it
/// (`2 * (x, psi)`) is that mistake, and one that is a position is told at its coordinate.
#[test]
fn a_vector_of_an_angle_and_a_length_is_a_unit_mix() {
    for (tail, shown, side) in [
        ("output w = norm((x, psi));", "(x, psi)", "`psi` is an angle ("),
        ("output w = dot((x, psi), (cos(phi), sin(phi)));", "(x, psi)", "`psi` is an angle ("),
        ("output w = cross((psi, x), (0, 1));", "(psi, x)", "`psi` is an angle ("),
        ("output w = angle(2 * (x, psi));", "(x, psi)", "`psi` is an angle ("),
        ("output w = norm(rot((x, phi), psi));", "(x, phi)", "`phi` is an angle ("),
        (
            "let v = (x, 0) + (0, psi); output w = norm(v);",
            "(x, 0) + (0, psi)",
            "`((x, 0) + (0, psi)).y` is an angle (made from `psi`",
        ),
        ("output w = norm(x * (1, 0) + (0, 2 * psi));", "x * (1, 0) + (0, 2 * psi)", "(made from `psi`"),
        ("eq e: u == dot((x, psi), (1, 0));", "(x, psi)", "`psi` is an angle ("),
    ] {
        let e = errors(&format!(
            "pub struct S {{ {SLIDER} {} {tail} }}",
            if tail.starts_with("eq") { "unknowns u;" } else { "" }
        ));
        assert_eq!(e.len(), 1, "{tail}: {e:#?}");
        assert!(
            e[0].starts_with(&format!("`{shown}` combines an angle and a length, so its value would change")),
            "{tail}: {e:#?}"
        );
        assert!(e[0].contains(side) && e[0].contains("such as `r * "), "{tail}: {e:#?}");
    }
    // A vector that is a position is told at its coordinate, as before, and only there.
    for tail in ["point p = (x, 0) + (0, psi);", "let v = (x, psi); point p = v + (1, 1);"] {
        let e = errors(&format!("pub struct S {{ {SLIDER} {tail} }}"));
        assert_eq!(e.len(), 1, "{tail}: {e:#?}");
        assert!(e[0].starts_with("`psi` is an angle") && e[0].contains("a coordinate of"), "{tail}: {e:#?}");
    }
    // Coordinates of one kind, a constant, a number of no unit (a sine), a length times an angle.
    for tail in [
        "output w = norm((x, l));",
        "output w = norm((phi, psi));",
        "output w = norm((x, 0.5)); output v = dot((psi, 1), (1, 0));",
        "output w = norm((x, l * sin(psi)));",
        "output w = norm((x, r * psi));",
        "output w = dot((x, 0), (0, psi));",
        "output w = (x, psi * r).y;",
    ] {
        assert_eq!(errors(&format!("pub struct S {{ {SLIDER} {tail} }}")), Vec::<String>::new(), "{tail}");
    }
}

/// An unknown that an `eq` sets to an expression of an angle (`y == 2 * psi`) is an angle, the
/// kind its column is given: beside a length it is the unit mix, as a coordinate of a position
/// it is refused. Set to a length times an angle (an arc), or through a circle of equations
/// that nothing else makes angles, it is no angle.
#[test]
fn an_unknown_an_eq_sets_to_an_angle_is_an_angle() {
    for (tail, shown) in [
        ("unknowns y; eq e: y == 2 * psi; output w = y + x;", "`y + x` adds an angle and a length"),
        ("params g0; unknowns y; eq e: y == psi + g0; output w = x - y;", "`x - y` subtracts an angle and a length"),
        ("unknowns y, z; eq e: 0 == y - phi / 2; eq f: z == y + pi; output w = max(z, x);", "`max(z, x)` compares"),
        // Placed as a length, it is one, and the `eq` is told.
        ("unknowns y; eq e: y == 2 * psi; point p = (x, y);", "`y == 2 * psi` equates an angle and a length"),
        ("unknowns y; eq e: y == 2 * psi; output w = norm((y, x));", "`(y, x)` combines"),
    ] {
        let e = errors(&format!("pub struct S {{ {SLIDER} {tail} }}"));
        assert_eq!(e.len(), 1, "{tail}: {e:#?}");
        assert!(e[0].starts_with(shown), "{tail}: {e:#?}");
        assert!(e[0].contains("or an `eq` sets it to an angle") || e[0].contains("equates"), "{tail}: {e:#?}");
    }
    for tail in [
        "unknowns y, z; eq e: y == r * psi; eq f: z == y; output w = y + x + z;",
        "unknowns y, z; eq e: y == 2 * z; eq f: z == y / 2 + x; output w = y + x;",
    ] {
        assert_eq!(errors(&format!("pub struct S {{ {SLIDER} {tail} }}")), Vec::<String>::new(), "{tail}");
    }
}

/// Unknowns set by `eq`s to one another in circles are judged at once: twenty unknowns each set
/// to the sum of the next two and the input, round in a circle, which nothing else makes
/// angles, are no angles (`y0 + x` is no unit mix); the same twenty in a chain from `psi`, each
/// set to the next plus the input and the last to twice `psi`, are angles every one. A search
/// from each unknown through the equations that set it, which kept no verdict found inside a
/// circle, took exponential time: the circle of eight held it for minutes.
#[test]
fn unknowns_set_to_one_another_in_circles_are_judged_at_once() {
    let n = 20;
    let mechanism = |set: &dyn Fn(usize) -> String| {
        let names: Vec<String> = (0..n).map(|i| format!("y{i}")).collect();
        let eqs: String = (0..n).map(|i| format!("eq e{i}: y{i} == {};", set(i))).collect();
        format!("pub struct S {{ {SLIDER} unknowns {}; {eqs} output w = y0 + x; }}", names.join(", "))
    };
    let circle = mechanism(&|i| format!("y{} + y{} + phi", (i + 1) % n, (i + 2) % n));
    assert_eq!(errors(&circle), Vec::<String>::new());
    let chain = mechanism(&|i| if i + 1 == n { "2 * psi".to_string() } else { format!("y{} + phi", i + 1) });
    let e = errors(&chain);
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`y0 + x` adds an angle and a length"), "{e:#?}");
}

/// A body's `turns`, a torque's `on` and the angle of a polar term (swapped or not, asked with
/// the term set aside) take the same verdicts on unknowns set to one another in circles, found
/// at once: each could reach the exponential search.
#[test]
fn turns_and_the_terms_set_aside_judge_unknowns_in_circles_at_once() {
    let n = 20;
    let mechanism = |set: &dyn Fn(usize) -> String, tail: &str| {
        let names: Vec<String> = (0..n).map(|i| format!("y{i}")).collect();
        let eqs: String = (0..n).map(|i| format!("eq e{i}: y{i} == {};", set(i))).collect();
        format!("pub struct S {{ {SLIDER} params m, j; unknowns {}; {eqs} {tail} }}", names.join(", "))
    };
    let circle = |i: usize| format!("y{} + y{} + phi", (i + 1) % n, (i + 2) % n);
    let chain = |i: usize| if i + 1 == n { "2 * psi".to_string() } else { format!("y{} + phi", i + 1) };
    let turns = "body b: mass m, com (x, 0), inertia j, turns y0; torque t on y1 = 1.0;";
    // In a circle nothing else makes angles, neither is one; in a chain from `psi`, both are.
    let e = errors(&mechanism(&circle, turns));
    assert_eq!(e.len(), 2, "{e:#?}");
    assert!(e[0].starts_with("`y0` is not an angle"), "{e:#?}");
    assert!(e[1].starts_with("`y1` is not an angle"), "{e:#?}");
    assert_eq!(errors(&mechanism(&chain, turns)), Vec::<String>::new());
    // Written as a length elsewhere, it is asked again with that place set aside.
    let placed = "point p = (x, y0); body b: mass m, com (x, 0), inertia j, turns y0;";
    let e = errors(&mechanism(&circle, placed));
    assert!(e.iter().any(|e| e.starts_with("`y0` is not an angle")), "{e:#?}");
    // The angle of `psi @ y0`, apart from the term: a length swapped in the circle, an angle in
    // the chain (swapping cannot help).
    let e = errors(&mechanism(&circle, "point p = psi @ y0;"));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].contains("write `y0 @ psi`"), "{e:#?}");
    let e = errors(&mechanism(&chain, "point p = psi @ y0;"));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].contains("`y0` is an angle too, so swapping the two cannot help"), "{e:#?}");
    // Two terms that take two names in opposite orders, told apart with both set aside.
    let opposite = "params a; point p = (2 * y0) @ a; point q = a @ y0;";
    let e = errors(&mechanism(&chain, opposite));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`2 * y0` is an angle"), "{e:#?}");
    let _ = errors(&mechanism(&circle, opposite));
}

/// `rot(phi, v)`, the vector and the angle the other way round, is one error that says to swap
/// them; each argument was told it is of the wrong kind.
#[test]
fn the_arguments_of_rot_the_other_way_round_are_told_to_swap() {
    let e = errors(&format!("pub struct S {{ {SLIDER} point p = rot(psi, (x, 0)); }}"));
    assert_eq!(
        e,
        ["`rot` takes `rot(vector, angle)`: the arguments are the other way round, write `rot((x, 0), psi)`"]
    );
    // One argument of the wrong kind is still told so.
    let e = errors(&format!("pub struct S {{ {SLIDER} point p = rot(psi, x); }}"));
    assert!(e[0].starts_with("this argument is a scalar: `rot` takes a vector here"), "{e:#?}");
}

/// `norm(x, y)`, the components of the vector without their parentheses, is told to write the
/// vector.
#[test]
fn two_components_given_for_one_vector_are_told_to_make_the_vector() {
    let e = errors(&format!("pub struct S {{ {SLIDER} output w = norm(x, l); }}"));
    assert_eq!(
        e,
        ["`norm` takes 1 argument: `norm(vector)`, but 2 were given; for the vector of the two write `norm((x, l))`"]
    );
}

/// A centre of mass or a force's point has lengths for coordinates: an angle unknown there put
/// the body at so many radians, its mass counted in mass rad^2 beside the others' mass
/// length^2, and the reduced inertia changed with the unit of length, without a word. The
/// slider's own unknown and constants remain coordinates.
#[test]
fn an_angle_unknown_is_no_coordinate_of_a_body_or_a_force() {
    let engine = |body: &str, force: &str| {
        format!(
            "pub struct E {{ params r, l, e, m; input phi; unknowns beta, x;
             loop c: r @ phi + l @ beta == (x, e);
             body piston: mass m, com {body}; force gas at {force} = (1, 0); }}"
        )
    };
    assert_eq!(errors(&engine("(x, e)", "(x, e)")), Vec::<String>::new());
    let e = errors(&engine("(beta, e)", "(x, e)"));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("a centre of mass is a point of lengths, but `beta` is an angle"), "{e:#?}");
    let e = errors(&engine("(x, e)", "(e, beta)"));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("the point a force acts at is a point of lengths, but `beta` is an angle"), "{e:#?}");
}

#[test]
fn an_angle_written_as_the_length_of_a_polar_term_gets_the_swap() {
    // `psi` turns the rod in the point and is the argument of a sine, so `psi @ l` in the loop
    // has its operands swapped. (Without the sine, nothing but the two terms tells which of
    // `psi` and `l` is the length: a tie, see `a_bare_term_beside_an_expression_...`.)
    let e = errors(
        "pub struct SliderCrank { params r, l, e; input phi; unknowns psi, x;
         loop oab: r @ phi == (x, e) + psi @ l;
         point mid = r @ phi + 0.5 * l @ psi; output lean = sin(psi); }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`psi` is an angle (elsewhere it turns a link"), "{e:#?}");
    assert!(e[0].ends_with("write `l @ psi`"), "{e:#?}");
    // An angle written in degrees, a parameter, and an angle that is a sum: where the angle of
    // `@` is an angle too (`phi - psi`), swapping the two cannot help.
    let e = errors(
        "pub struct SliderCrank { params r, l, gamma = deg(10); input phi; unknowns psi = deg(-20), x;
         loop oab: r @ phi == (x, 0) + psi @ l + gamma @ (phi - psi); }",
    );
    assert_eq!(e.len(), 2, "{e:#?}");
    assert!(e[0].starts_with("`psi` is an angle (its value is written in degrees)"), "{e:#?}");
    assert!(e[0].ends_with("write `l @ psi`"), "{e:#?}");
    assert!(
        e[1].ends_with("`phi - psi` is an angle too, so swapping the two cannot help; write a length there, such as `r * gamma` for the arc a radius `r` rolls"),
        "{e:#?}"
    );
    // An angle that an `eq` sets, and one whose sine is taken.
    let e = errors(
        "pub struct Guide { params r, d; input phi; unknowns th, s, x;
         eq a: th == atan2(r * sin(phi), d);
         loop g: r @ phi == (x, 0) + th @ s;
         eq b: s == d * sin(phi); }",
    );
    assert!(e.iter().any(|m| m.ends_with("write `s @ th`")), "{e:#?}");
    // An angle as the length of a constant direction: no swap to write, a length to write.
    let e = errors(
        "pub struct Rack { params r; input phi; unknowns x;
         loop c: phi @ 0 == (x, 0) + r @ phi; }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`phi` is an angle"), "{e:#?}");
    assert!(e[0].ends_with("write a length there, such as `r * phi` for the arc a radius `r` rolls"), "{e:#?}");
}

#[test]
fn lengths_times_angles_constants_and_names_of_no_known_kind_are_polar_lengths() {
    for body in [
        // A length of no known kind, however it is named.
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;",
        // A rolled arc, a length times an angle: not a bare name.
        "params r, l; input phi; unknowns psi, x; loop c: (r * phi) @ 0 + r @ phi == (x, 0) + l @ psi;",
        // A constant length, and a slider's unknown as a length turned by an angle unknown.
        "params r, d; input phi; unknowns th, s; loop c: r @ phi + 1 @ th == (d, 0) + s @ th;",
        // A length unknown that is also scaled into an argument (a rack's travel).
        "params r, rp, l; input phi; unknowns x, psi; loop c: r @ phi + x @ 0 == (0, 1) + l @ (x / rp) + l @ psi;",
    ] {
        let e = errors(&format!("pub struct M {{ {body} }}"));
        assert!(e.iter().all(|m| !m.contains("is an angle")), "{body}: {e:#?}");
    }
}

#[test]
fn a_body_turning_with_the_length_of_a_polar_term_is_told_of_the_swap() {
    // `beta` turns the rod but is the length of `beta @ l`: the term is swapped.
    let e = errors(
        "pub struct Engine { params r, l, m; input phi; unknowns beta, x;
         loop abc: r @ phi + beta @ l == (x, 0);
         body rod: mass m, com (x, 0), turns beta; }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`beta` is not an angle"), "{e:#?}");
    assert!(e[0].ends_with("help: `beta @ l` has `beta` as the length of `@`, which takes `length @ angle`: if `beta` is the angle, write `l @ beta`"), "{e:#?}");
    // A slider's coordinate as the length of a constant direction is no swap: no help.
    let e = errors(
        "pub struct Engine { params r, l, m; input phi; unknowns beta, x;
         loop abc: r @ phi + l @ beta == x @ 0;
         body rod: mass m, com (x, 0), turns x; }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`x` is not an angle") && !e[0].contains("help:"), "{e:#?}");
}

/// An angle written in degrees and scaled by a number, or added to one, is as much an angle as
/// `deg(15)` alone: as a name's value (`th = 2 * deg(15)`), and as the length of a polar term
/// itself (`deg(3) @ psi`), which compiled into a link 0.05 units long.
#[test]
fn degrees_scaled_or_offset_are_angles_where_the_length_of_a_polar_term_belongs() {
    for guess in ["deg(15)", "2 * deg(15)", "deg(15) * 2", "deg(30) / 2", "-(deg(10) + deg(5))", "deg(90) - pi / 4"] {
        let e = errors(&format!(
            "pub struct S {{ params r, d; input phi; unknowns th = {guess}, s = d;
             loop oab: r @ phi == (d, 0) + th @ s; }}"
        ));
        assert_eq!(e.len(), 1, "{guess}: {e:#?}");
        assert!(e[0].starts_with("`th` is an angle (its value is written in degrees)"), "{guess}: {e:#?}");
        assert!(e[0].ends_with("write `s @ th`"), "{guess}: {e:#?}");
    }
    for (length, swapped) in [("deg(3)", "psi @ deg(3)"), ("2 * deg(15)", "psi @ (2 * deg(15))")] {
        let e = errors(&format!(
            "pub struct S {{ params r; input phi; unknowns psi, x;
             loop oab: r @ phi == (x, 0) + {length} @ psi; }}"
        ));
        assert_eq!(e.len(), 1, "{length}: {e:#?}");
        assert!(e[0].starts_with(&format!("`{length}` is an angle (its value is written in degrees)")), "{e:#?}");
        assert!(e[0].ends_with(&format!("write `{swapped}`")), "{e:#?}");
    }
    // A constant direction: no length to swap with.
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi, x;
         loop oab: r @ phi + deg(30) @ 0 == (x, 0) + l @ psi; }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].ends_with("write a length there, such as `r * deg(30)` for the arc a radius `r` rolls"), "{e:#?}");
    // A product of degrees with a name or with degrees is of no certain kind; an angle turning a
    // link stays where it belongs.
    for body in [
        "params r, k, d; input phi; unknowns th = k * deg(15), s = d; loop c: r @ phi == (d, 0) + th @ s;",
        "params r, d; input phi; unknowns th = deg(15) * deg(15), s = d; loop c: r @ phi == (d, 0) + th @ s;",
        "params r, l; input phi; unknowns psi = 2 * deg(15), x; loop c: r @ phi == (x, 0) + l @ (psi + deg(5));",
    ] {
        assert_eq!(errors(&format!("pub struct S {{ {body} }}")), Vec::<String>::new(), "{body}");
    }
}

/// A `let`, `point` or `output` defined from itself, or two defined from each other, is not
/// an ordering mistake that moving a line mends: the message said to move the definition
/// "above this line", its own line.
#[test]
fn a_definition_from_itself_or_in_a_circle_is_not_told_to_move() {
    for (item, what) in
        [("let v = v + 1; output w = v;", "let"), ("output v = v * 2;", "output"), ("point v = v + (1, 0);", "point")]
    {
        let e = errors(&format!("pub struct S {{ {SLIDER} {item} }}"));
        assert_eq!(e.len(), 1, "{item}: {e:#?}");
        assert!(
            e[0].starts_with(&format!("`v` is used in its own definition: `{what} v = ...;` is computed once")),
            "{e:#?}"
        );
        assert!(e[0].ends_with("declare it with `unknowns` and write that equation as an `eq`"), "{e:#?}");
    }
    let e = errors(&format!("pub struct S {{ {SLIDER} output a = b + x; output b = a + x; }}"));
    assert_eq!(e.len(), 2, "{e:#?}");
    assert!(e[0].starts_with("`a` and `b` are defined from each other: `output b` below uses `a`"), "{e:#?}");
    assert_eq!(e[1], "`output b` is defined here, from `a`");
    assert!(e.iter().all(|m| !m.contains("move")), "{e:#?}");
}

/// A misspelt item keyword, or another language's word for one, is named with the keyword.
#[test]
fn a_misspelt_item_keyword_gets_the_keyword() {
    for (word, keyword) in [
        ("lop", "loop"),
        ("imput", "input"),
        ("unknows", "unknowns"),
        ("Loop", "loop"),
        ("parameters", "params"),
        ("const", "params"),
    ] {
        let e = errors(&format!(
            "pub struct S {{ params r, l; input phi; unknowns psi, x; {word} c: r @ phi == (x, 0) + l @ psi; }}"
        ));
        assert_eq!(e.len(), 1, "{word}: {e:#?}");
        assert!(e[0].starts_with(&format!("`{word}` does not start an item (did you mean `{keyword}`?); ")), "{e:#?}");
    }
    // A word like no keyword gets the list alone.
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi, x; link c = r @ phi; loop c: r @ phi == (x, 0) + l @ psi; }",
    );
    assert!(e[0].starts_with("`link` does not start an item; an item starts with"), "{e:#?}");
}

/// A loop adds lengths: an angle as a coordinate of one of its vectors compiled into a
/// mechanism whose every result changed with the unit of length (`(x, phi)` with `phi` in
/// radians beside `x` in millimetres).
#[test]
fn an_angle_as_a_coordinate_in_a_loop_is_a_unit_mix() {
    for (body, name, why) in [
        ("loop c: r @ phi == (x, phi) + l @ psi;", "phi", "elsewhere it turns a link"),
        ("loop c: r @ phi == (x, 0) + l @ psi + ((psi), 0);", "psi", "elsewhere it turns a link"),
        ("loop c: r @ phi == (x, e) + l @ psi;", "e", "its value is written in degrees"),
    ] {
        let e = errors(&format!("pub struct S {{ params r, l, e = deg(5); input phi; unknowns psi, x; {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        assert!(e[0].starts_with(&format!("`{name}` is an angle ({why}")), "{e:#?}");
        assert!(e[0].ends_with(&format!("such as `r * {name}` for the arc a radius `r` rolls")), "{e:#?}");
    }
    // Lengths, a rolled arc, a name of no known kind, and an angle in an `eq` (not a loop) stay
    // as written; a point is a position too (see the next test).
    for body in [
        "params r, l, e; input phi; unknowns psi, x; loop c: r @ phi == (x, e) + l @ psi;",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi + (r * phi, 0) == (x, 0) + l @ psi;",
        "params r, l; input t; unknowns psi, x; loop c: r @ psi == (x, t) + (l, 0);",
        "params r, l; input phi; unknowns psi, x, u; loop c: r @ phi == (x, 0) + l @ psi; eq d: u == dot((phi, psi), (1, 0));",
    ] {
        assert_eq!(errors(&format!("pub struct S {{ {body} }}")), Vec::<String>::new(), "{body}");
    }
}

/// Notations of formulas and of other languages, each told what to write instead: a number
/// without its leading `0`, the Greek letter for `pi`, `gravity` given with `=`.
#[test]
fn other_notations_are_told_what_to_write() {
    let slider = |tail: &str| format!("pub struct S {{ params r, l, g; input phi; unknowns psi, x; {tail} }}");
    for (tail, says) in [
        ("loop c: r @ phi == (x, 0) + .5 * l @ psi;", "a number starts with a digit: write `0.5`"),
        ("loop c: r @ phi == (x, 0) + l @ (psi + π);", "`π` is not a name of the language: write `pi` for 3.14159..."),
        (
            "loop c: r @ phi == (x, 0) + l @ psi; gravity = (0, -g);",
            "`gravity` takes its vector without `=`: write `gravity (0, -g);`",
        ),
    ] {
        let e = errors(&slider(tail));
        assert_eq!(e, [says], "{tail}");
    }
    // A component after a value is not a number: `v.x` still reads.
    assert_eq!(errors(&slider("loop c: r @ phi == (x, 0) + l @ psi; output w = (x, 0).x;")), Vec::<String>::new());
}

/// A value in degrees written with `deg` as a unit, before or after its number: `deg` is a
/// function, and the product `30 * deg` the messages suggested for `30deg` and `deg 30` would
/// not compile either.
#[test]
fn degrees_written_as_a_unit_are_told_to_call_deg() {
    for (guess, says) in [
        ("30deg", "a value in degrees is written `deg(30)`: `deg` is a function"),
        ("30 deg", "a value in degrees is written `deg(30)`: `deg` is a function"),
        ("deg 30", "a value in degrees is written `deg(30)`: `deg` is a function"),
        ("1.5deg", "a value in degrees is written `deg(1.5)`: `deg` is a function"),
        ("1.5rad", "`1.5rad` is not a number: angles are in radians already, write `1.5`"),
    ] {
        let e = errors(&format!(
            "pub struct S {{ params r, l; input phi; unknowns psi = {guess}, x; loop c: r @ phi == (x, 0) + l @ psi; }}"
        ));
        assert_eq!(e, [says], "{guess}");
    }
    // Another function before a number may be a call or a product with a name of the same spelling.
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi = sin 30, x; loop c: r @ phi == (x, 0) + l @ psi; }",
    );
    assert_eq!(
        e,
        ["expected an operator between `sin` and `30`: write `sin * 30` for a product, \
             or `sin(30)` to call a function"]
    );
}

/// A Rust keyword where a name belongs is named as one, with a name to write instead; the
/// message said "expected a name" of a word that reads as one.
#[test]
fn a_keyword_as_a_name_is_told_to_change_or_go_raw() {
    for (decl, says) in [
        (
            "params r, l, in; input phi; unknowns psi, x;",
            "`in` is a Rust keyword and cannot name a parameter: choose another name, such as `in_`, or write the raw identifier `r#in`",
        ),
        (
            "params r, l; input self; unknowns psi, x;",
            "`self` is a Rust keyword and cannot name an input: choose another name, such as `self_`",
        ),
        (
            "params r, l; input phi; unknowns psi, x, type;",
            "`type` is a Rust keyword and cannot name an unknown: choose another name, such as `type_`, or write the raw identifier `r#type`",
        ),
        (
            "params r, l; input phi; unknowns psi, x; output match = x;",
            "`match` is a Rust keyword and cannot name an `output`: choose another name, such as `match_`, or write the raw identifier `r#match`",
        ),
        (
            "params r, l; input phi; unknowns psi, x; let mut v = x;",
            "remove `mut`: a `let` names one value, which is never reassigned",
        ),
        (
            "params r, l; input phi; unknowns psi, x; eq as: x == 1;",
            "`as` is a Rust keyword and cannot name an `eq`: choose another name, such as `as_`, or write the raw identifier `r#as`",
        ),
        // `_` is no name, and `r#_` does not lex: neither `__` nor the raw form is offered.
        (
            "params r, l, _; input phi; unknowns psi, x;",
            "`_` is Rust's placeholder, not a name, and cannot name a parameter: give it a name (one that starts \
             with `_`, such as `_spare`, keeps an unused parameter without a warning)",
        ),
        (
            "params r, l; input phi; unknowns psi, x; let _ = x;",
            "`_` is Rust's placeholder, not a name, and cannot name a `let`: give it a name",
        ),
    ] {
        let e = errors(&format!("pub struct S {{ {decl} loop c: r @ phi == (x, 0) + l @ psi; }}"));
        assert!(e.iter().any(|m| m == says), "{decl}: {e:#?}");
    }
}

/// A point is a position, and so are the point a force acts at, a body's centre of mass and a
/// vector `let` that a loop or point uses: their coordinates are lengths, as a loop's are, and
/// an angle there compiled into outputs (and a mass model) that changed with the unit of length.
#[test]
fn an_angle_as_a_coordinate_of_a_point_is_a_unit_mix() {
    let head = "params r, l, e = deg(5); input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";
    for (body, name, place) in [
        ("point p = (x, phi);", "phi", "a coordinate of a point, which is a position in lengths"),
        ("point p = (x, 0) + (psi, 0);", "psi", "a coordinate of a point, which is a position in lengths"),
        ("point p = (x, e);", "e", "a coordinate of a point, which is a position in lengths"),
        ("point p = rot((x, (e)), psi);", "e", "a coordinate of a point, which is a position in lengths"),
        (
            "let v = (phi, 0); point p = (x, 0) + v;",
            "phi",
            "a coordinate of `v`, a vector that a loop or point takes as lengths",
        ),
        (
            "let v = (0, psi); let w = 2 * v; point p = w;",
            "psi",
            "a coordinate of `v`, a vector that a loop or point takes as lengths",
        ),
        ("point p = (x, 2 * deg(3));", "2 * deg(3)", "a coordinate of a point, which is a position in lengths"),
        (
            "let v = (psi, 0); loop d: (x, 0) + v == r @ psi + (l, 0) + 0 * (x, 0);",
            "psi",
            "a coordinate of `v`, a vector that a loop or point takes as lengths",
        ),
        ("force f at (x, e) = (1, 0);", "e", "a coordinate of the point a force acts at, a position in lengths"),
        ("body b: mass 1, com (e, x);", "e", "a coordinate of a centre of mass, a position in lengths"),
        ("force f at (phi, 0) = (1, 0);", "phi", "a coordinate of the point a force acts at, a position in lengths"),
        (
            "point p = (x, 0); body b: mass 1, com (p.x, deg(5));",
            "deg(5)",
            "a coordinate of a centre of mass, a position in lengths",
        ),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        assert!(e[0].starts_with(&format!("`{name}` is an angle (")), "{body}: {e:#?}");
        assert!(e[0].contains(&format!("), but here it is {place}: write a length there")), "{body}: {e:#?}");
        let arc = if name.contains(' ') { format!("({name})") } else { name.to_string() };
        assert!(e[0].ends_with(&format!("such as `r * {arc}` for the arc a radius `r` rolls")), "{e:#?}");
    }
    // In a loop too, degrees written as a coordinate are an angle.
    let e =
        errors("pub struct S { params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, deg(5)) + l @ psi; }");
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(
        e[0].starts_with(
            "`deg(5)` is an angle (its value is written in degrees), but here it is a coordinate of a vector in a loop"
        ),
        "{e:#?}"
    );
    // Lengths, a rolled arc, a vector scaled by a length, a name of no known kind, a vector let
    // that no loop or point uses, and vectors of forces or accelerations stay as written.
    for body in [
        "params r, l, e; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; point p = (x, e);",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; point p = (r * phi, x);",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; point p = l * (psi, 1);",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; let v = (psi, 1); point p = v * l;",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi + r * (phi, 0) == (x, 0) + l @ psi;",
        "params r, l; input t; unknowns psi, x; loop c: r @ psi == (x, 0) + (l, 0); point p = (x, t);",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; let v = (phi, psi); output w = norm(v);",
        "params r, l, g; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;
         force f at (x, 0) = (psi, phi); gravity (0, -g);",
    ] {
        assert_eq!(errors(&format!("pub struct S {{ {body} }}")), Vec::<String>::new(), "{body}");
    }
}

/// A coordinate of a position is judged by the kind of its expression, not by how it is
/// written: an angle offset by a number or by an angle, a multiple of one by a number, a scalar
/// `let` of one, the dot product of a vector of angles with a direction, and an angle scaling a
/// direction all compiled into positions whose values changed with the unit of length. The
/// arguments of `dot` are no positions themselves: a length times such a product is a length.
#[test]
fn an_angle_computed_as_a_coordinate_is_a_unit_mix() {
    let head = "params r, l, m, e0 = deg(3); input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";
    for (body, shown, from, place) in [
        ("point p = (x, phi + 0.0);", "phi + 0.0", "phi", "a point"),
        ("point p = (2.0 * phi, x);", "2.0 * phi", "phi", "a point"),
        ("point p = (x, e0 - 0.5 * psi);", "e0 - 0.5 * psi", "psi", "a point"),
        ("let a = phi / 2; point p = (x, a);", "a", "phi", "a point"),
        ("let a = phi; point p = (x, a);", "a", "phi", "a point"),
        ("point p = (x, 0) + (dot((psi, 0), (1, 0)), 0);", "dot((psi, 0), (1, 0))", "psi", "a point"),
        ("point p = (x, 0) + psi * (0, 1);", "psi", "", "a point"),
        ("point p = (x, wrap(phi, 2 * pi));", "wrap(phi, 2 * pi)", "phi", "a point"),
        (
            "loop d: (x, cross((0, 1), (psi, 0))) == (x, 0) + r @ psi;",
            "cross((0, 1), (psi, 0))",
            "psi",
            "a vector in a loop",
        ),
        ("body b: mass m, com (x, 2 * psi);", "2 * psi", "psi", "a centre of mass"),
        ("force f at (min(phi, psi), x) = (1, 0);", "min(phi, psi)", "phi", "the point a force acts at"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        let why = if from.is_empty() { String::new() } else { format!("made from `{from}`, an angle: ") };
        assert!(e[0].starts_with(&format!("`{shown}` is an angle ({why}")), "{body}: {e:#?}");
        assert!(e[0].contains(&format!("but here it is a coordinate of {place}")), "{body}: {e:#?}");
    }
    // Lengths made from angles (a rolled arc, a length times a dot product of angles), numbers
    // of an angle (a sine), a sum of a name of no known kind and an angle, and an angle that is
    // no position (a norm, a force's value) stay as written.
    for body in [
        "point p = (x, 0) + l * (phi, 0) + phi * (l, 0) + (r * phi + x, sin(phi));",
        "point p = (l * dot((phi, 0), (1, 0)), x);",
        "point p = (x, cross((0, l), (psi, 0)));",
        "point p = (m + psi, x);",
        "output w = norm((phi, psi)); point p = (x, min(l, r));",
        "force f at (x, 0) = (2 * psi, 0);",
        "eq d: x == r * cos(phi) + dot((phi, psi), (0, 0)) + sqrt(l ^ 2 - (r * sin(phi)) ^ 2);",
    ] {
        let src = format!(
            "pub struct S {{ params r, l, m; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; {body} }}"
        );
        let e = errors(&src);
        assert!(e.iter().all(|m| !m.contains("is an angle")), "{body}: {e:#?}");
    }
}

/// A vector `let` of an angle that a point and a centre of mass (or a force's point) both use
/// is one mistake, reported once at its coordinate: the dynamics said it again of the centre of
/// mass, and for an input told to declare the point.
#[test]
fn an_angle_in_a_let_of_a_point_and_a_mass_is_reported_once() {
    let head = "params r, l, m; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";
    for body in [
        "let v = (x, psi); point p = v; body b: mass m, com v;",
        "let v = (x, psi); body b: mass m, com v;",
        "let v = (x, phi); body b: mass m, com v;",
        "let v = (x, psi); point p = v; force f at v = (1, 0);",
        "let v = (x, psi); body b: mass m, com v; force f at v = (1, 0);",
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        assert!(e[0].contains("but here it is a coordinate of `v`, a vector that"), "{body}: {e:#?}");
    }
}

/// A vector `let` of an angle that only the dynamics takes as a position was said to be taken
/// by "a loop or point", which named neither where it was used: it names the centre of mass or
/// the force's point that takes it, directly or through another `let`.
#[test]
fn a_let_taken_only_by_the_dynamics_names_what_takes_it() {
    let head = "params r, l, m; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";
    for (body, taken) in [
        ("let v = (x, psi); body b: mass m, com v;", "a centre of mass takes"),
        ("let v = (x, psi); force f at v = (1, 0);", "the point a force acts at takes"),
        ("let v = (x, phi); let w = v; body b: mass m, com w;", "a centre of mass takes"),
        (
            "let v = (x, psi); body b: mass m, com v; force f at v = (1, 0);",
            "a centre of mass and the point a force acts at take",
        ),
        ("let v = (x, psi); point p = v; body b: mass m, com v;", "a loop or point takes"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        let place = format!("but here it is a coordinate of `v`, a vector that {taken} as lengths: write a length");
        assert!(e[0].contains(&place), "{body}: {e:#?}");
    }
}

/// Each wrong coordinate of a centre of mass or a force's point gets its one error: an angle
/// unknown written there was told nothing when the other coordinate was refused as an angle
/// (`(psi, 2 * phi)`, `(psi, phi)`), when it was refused elsewhere (a point `(x, psi)`), or
/// beside another angle unknown (`(psi, beta)`, where only the first was told). One written
/// twice, or reaching the position through a `let` or point refused for it, is told once.
#[test]
fn each_angle_in_a_centre_of_mass_is_reported_once() {
    let head = "params r, l, m; input phi; unknowns psi, x, beta, y;
                loop c: r @ phi == (x, 0) + l @ psi; loop d: r @ phi + l @ beta == (y, 1);";
    let unknown = |name: &str| format!("a centre of mass is a point of lengths, but `{name}` is an angle");
    let coordinate = |name: &str| format!("`{name}` is an angle (");
    for (body, says) in [
        ("body b: mass m, com (psi, 2 * phi);", vec![unknown("psi"), coordinate("2 * phi")]),
        ("body b: mass m, com (psi, phi);", vec![unknown("psi"), coordinate("phi")]),
        ("body b: mass m, com (psi, beta);", vec![unknown("psi"), unknown("beta")]),
        ("body b: mass m, com (psi, psi);", vec![unknown("psi")]),
        ("point p = (x, psi); body b: mass m, com (x, psi);", vec![unknown("psi"), coordinate("psi")]),
        (
            "point p = (x, psi); body b: mass m, com (beta, psi);",
            vec![unknown("beta"), unknown("psi"), coordinate("psi")],
        ),
        ("point p = (x, psi); body b: mass m, com p;", vec![coordinate("psi")]),
        ("let v = (psi, 0); body b: mass m, com (v.x, beta);", vec![unknown("beta"), coordinate("psi")]),
        (
            "body b: mass m, com (y, 2 * psi); body d: mass m, com (psi, 0);",
            vec![unknown("psi"), coordinate("2 * psi")],
        ),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), says.len(), "{body}: {e:#?}");
        for (m, s) in e.iter().zip(&says) {
            assert!(m.starts_with(s.as_str()), "{body}: {e:#?}");
        }
    }
    let e = errors(&format!("pub struct S {{ {head} force f at (psi, phi) = (1, 0); }}"));
    assert_eq!(e.len(), 2, "{e:#?}");
    assert!(e[0].starts_with("the point a force acts at is a point of lengths, but `psi` is an angle"), "{e:#?}");
    assert!(e[1].starts_with("`phi` is an angle ("), "{e:#?}");
}

/// An angle beside a length, in an `eq` or in a sum of a `loop`, `eq`, `let`, `point` or
/// `output`, makes a mechanism or a value that changes with the unit of length: a length is a
/// name written bare as a coordinate of a position or as the length of `@`, an angle one that
/// turns a link (or is in degrees). An output's or point's sum is refused as the same sum named
/// by a `let` is. Names of no known kind, a length times an angle and an angle beside a ratio of
/// lengths (inside a sine) stay as written.
#[test]
fn an_angle_beside_a_length_is_a_unit_mix() {
    let head = "params r, l, e0 = deg(3); input phi; unknowns psi, x, s; loop c: r @ phi == (x, s) + l @ psi;";
    for (body, shown, angle, length) in [
        ("eq e: s == phi;", "s == phi", "phi", "s"),
        ("eq e: 2 * phi - 0.1 == s;", "2 * phi - 0.1 == s", "2 * phi - 0.1", "s"),
        ("eq e: s == l * cos(psi) + e0;", "l * cos(psi) + e0", "e0", "l * cos(psi)"),
        ("eq e: s == r * phi; let d = x + psi; output o = d;", "x + psi", "psi", "x"),
        ("eq e: s == r * phi; let d = x - phi; output o = d * l;", "x - phi", "phi", "x"),
        ("eq e: s == r * phi; output o = x + psi;", "x + psi", "psi", "x"),
        ("eq e: s == r * phi; output o = x - 2 * psi;", "x - 2 * psi", "2 * psi", "x"),
        ("eq e: s == r * phi; point p = (x + psi, 0);", "x + psi", "psi", "x"),
        ("eq e: s == r * phi; point p = (l + phi, s);", "l + phi", "phi", "l"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        assert!(e[0].starts_with(&format!("`{shown}` ")), "{body}: {e:#?}");
        assert!(e[0].contains(&format!("`{angle}` is an angle (")), "{body}: {e:#?}");
        assert!(e[0].contains(&format!("and `{length}` a length (")), "{body}: {e:#?}");
    }
    for body in [
        "params r, l; input phi; unknowns psi, x, s; loop c: r @ phi == (x, s) + l @ psi; eq e: s == r * phi;",
        "params r, l; input phi; unknowns psi, x, s; loop c: r @ phi == (x, 0) + l @ psi; eq e: s == phi;",
        "params r, l, k; input phi; unknowns psi, x, s; loop c: r @ phi == (x, s) + l @ psi; eq e: s == k + phi;",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; output o = sin(x / l + phi) + x - r;",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; output o = psi - phi;",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; output o = x / l + psi;",
        "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; point p = (x + r * psi, l);",
    ] {
        assert_eq!(errors(&format!("pub struct S {{ {body} }}")), Vec::<String>::new(), "{body}");
    }
}

/// The length of `@` is judged by the kind of its expression, as a coordinate is: twice an
/// angle, an angle offset by a number, a scalar `let` of one and the magnitude of a vector of
/// angles compiled into a link so many radians long. Each is told the length to write, and
/// unless the angle of `@` is a constant or an angle itself (`psi`, `phi`), the swap too.
#[test]
fn an_angle_computed_as_the_length_of_a_polar_term_is_refused() {
    let head = "params r, l, s, e0 = deg(3); input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";
    for (body, shown, from, fix) in [
        ("point p = (x, 0) + (2 * phi) @ psi;", "2 * phi", "phi", "write a length there, such as `r * (2 * phi)`"),
        (
            "point p = (x, 0) + (phi + 0.0) @ s;",
            "phi + 0.0",
            "phi",
            "rolls, or if the two are swapped, write `s @ (phi + 0.0)`",
        ),
        ("let h = psi / 2; point p = (x, 0) + h @ 0;", "h", "psi", "write a length there, such as `r * h`"),
        ("let h = phi; point p = (x, 0) + h @ s;", "h", "phi", "such as `r * h` for the arc a radius `r` rolls, or if"),
        ("point p = (x, 0) + (2 * e0) @ s;", "2 * e0", "e0", "if the two are swapped, write `s @ (2 * e0)`"),
        ("point p = (x, 0) + norm((phi, psi)) @ phi;", "norm((phi, psi))", "phi", "write a length there"),
        ("point p = (x, 0) + hypot(psi, 0.1) @ s;", "hypot(psi, 0.1)", "psi", "write `s @ hypot(psi, 0.1)`"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        assert!(e[0].starts_with(&format!("`{shown}` is an angle (made from `{from}`, an angle: ")), "{body}: {e:#?}");
        assert!(e[0].contains("but here it is the length of `@`, which takes `length @ angle`: "), "{body}: {e:#?}");
        assert!(e[0].contains(fix), "{body}: {e:#?}");
        // A constant direction has no angle to swap with, and an angle no length.
        assert_eq!(e[0].contains("swapped"), body.contains("@ s;"), "{body}: {e:#?}");
        let angle = body.contains("@ psi;") || body.contains("@ phi;");
        assert_eq!(e[0].contains("is an angle too, so swapping the two cannot help"), angle, "{body}: {e:#?}");
    }
}

/// The magnitude of a vector of angles (`norm`, `hypot`) is an angle where a length belongs: a
/// coordinate of a position, or beside a length in an `eq`.
#[test]
fn the_magnitude_of_angles_is_an_angle_where_a_length_belongs() {
    let head = "params r, l, m; input phi; unknowns psi, x, s; loop c: r @ phi == (x, s) + l @ psi;";
    for (body, shown, place) in [
        ("eq e: s == r * phi; point p = (x, norm((phi, psi)));", "norm((phi, psi))", "a coordinate of a point"),
        ("eq e: s == r * phi; body b: mass m, com (x, norm((psi, 0)));", "norm((psi, 0))", "a coordinate of a centre"),
        ("eq e: s == r * phi; point p = (x, 0) + (hypot(phi, 1), 0);", "hypot(phi, 1)", "a coordinate of a point"),
        ("eq e: s == norm((phi, 0.5));", "s == norm((phi, 0.5))", "equates an angle and a length"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        assert!(e[0].starts_with(&format!("`{shown}` ")), "{body}: {e:#?}");
        assert!(e[0].contains(place), "{body}: {e:#?}");
    }
}

/// What must keep compiling: a length times an angle as the length of `@` (a rolled arc), a
/// sine of an angle as a factor of a coordinate, the magnitude of a vector of lengths, a length
/// times a magnitude of angles, and a magnitude of angles that is no position (an output).
#[test]
fn lengths_made_from_angles_stay_lengths_of_polar_terms_and_coordinates() {
    for body in [
        "point p = (x, 0) + (r * psi) @ phi + (l * phi) @ 0;",
        "point p = (x + r * sin(phi), sin(phi) * l) + sin(psi) * (r, 0) + (l * cos(phi)) @ psi;",
        "point p = (x, 0) + norm((x, l)) @ phi + (x, hypot(r, l));",
        "point p = (x, l * norm((phi, psi))) + (r * hypot(psi, 1)) @ 0;",
        "output w = norm((phi, psi)) + hypot(phi, 1);",
        "let k = r / l; point p = (x, 0) + (k * l) @ phi;",
    ] {
        let src = format!(
            "pub struct S {{ params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; {body} }}"
        );
        assert_eq!(errors(&src), Vec::<String>::new(), "{body}");
    }
}

/// A misspelt option, or a misspelt `kinloop` before it, gets the word meant, as a misspelt
/// item keyword does; a word like none of them gets the list alone.
#[test]
fn a_misspelt_option_gets_the_option() {
    let decl = |attr: &str| {
        errors(&format!(
            "{attr} pub struct S {{ params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; }}"
        ))
    };
    for (attr, meant) in [
        ("#[kinloop(Dense)]", "dense"),
        ("#[kinloop(newtn)]", "newton"),
        ("#[kinloop(sensitivites)]", "sensitivities"),
        ("#[kinloop(dense, nweton)]", "newton"),
        // Three edits, but a third of a long word: the singular of the option.
        ("#[kinloop(sensitivity)]", "sensitivities"),
        ("#[kinloop(sensitiv)]", "sensitivities"),
    ] {
        let e = decl(attr);
        assert_eq!(e.len(), 1, "{attr}: {e:#?}");
        assert!(
            e[0].starts_with(&format!("unknown kinloop option (did you mean `{meant}`?); the supported")),
            "{attr}: {e:#?}"
        );
    }
    for (attr, meant) in [("#[kinlop(dense)]", "kinloop"), ("#[Kinloop(dense)]", "kinloop")] {
        let e = decl(attr);
        assert_eq!(e.len(), 1, "{attr}: {e:#?}");
        assert!(e[0].contains(&format!("(did you mean `#[{meant}(...)]`?)")), "{e:#?}");
    }
    let e = decl("#[kinloop(fast)]");
    assert!(e[0].starts_with("unknown kinloop option; the supported options are"), "{e:#?}");
    let e = decl("#[inline]");
    assert!(!e[0].contains("did you mean"), "{e:#?}");
}

/// A `;` written for the `,` between the names of a list: the name after it is told to join
/// the list with a `,`; "does not start an item" named no fix.
#[test]
fn a_semicolon_between_the_names_of_a_list_is_told_to_be_a_comma() {
    for (decls, says) in [
        (
            "params r, l; input phi; unknowns psi = 0.5; x = 1;",
            "`x` does not start an item: to declare it with the `unknowns` before, separate the names with `,`, \
             not `;` (`unknowns ..., psi, x`)",
        ),
        (
            "params r; l; input phi; unknowns psi, x;",
            "`l` does not start an item: to declare it with the `params` before, separate the names with `,`, \
             not `;` (`params ..., r, l`)",
        ),
    ] {
        let e = errors(&format!("pub struct S {{ {decls} loop c: r @ phi == (x, 0) + l @ psi; }}"));
        assert_eq!(e, [says], "{decls}");
    }
    // After another item, or before `==` (see the next test), the word is no name of the list.
    let e =
        errors("pub struct S { params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; y = 1; }");
    assert!(e[0].starts_with("`y` does not start an item; an item starts with"), "{e:#?}");
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi, x; x == r; loop c: r @ phi == (x, 0) + l @ psi; }",
    );
    assert!(e[0].starts_with("`x` does not start an item: an equation starts with `eq`"), "{e:#?}");
}

/// An equation written without its keyword and name is told to take them; the list of items
/// did not say which one it is.
#[test]
fn an_equation_without_its_keyword_is_told_to_take_it() {
    let says = "does not start an item: an equation starts with `eq` and its name, `eq name: lhs == rhs;` \
                (`loop name: lhs == rhs;` for vectors)";
    for (tail, word) in [("u == 2 * x;", "u"), ("c: r @ phi == (x, 0) + l @ psi;", "c")] {
        let e = errors(&format!("pub struct S {{ {SLIDER} unknowns u; {tail} }}"));
        assert_eq!(e, [format!("`{word}` {says}")], "{tail}");
    }
    // A misspelt keyword is still named, and an item without `==` gets the list.
    let e = errors(&format!("pub struct S {{ {SLIDER} unknowns u; equation e: u == 2 * x; }}"));
    assert!(e[0].starts_with("`equation` does not start an item (did you mean `eq`?)"), "{e:#?}");
}

/// Two values in parentheses without the `,` between them are a vector's components: "write
/// `x * 0` for a product" did not name the `,`. A number and a name stay a product (`(2 pi)`).
#[test]
fn a_vector_without_its_comma_is_told_to_take_it() {
    for (point, says) in [
        ("(x 0)", "expected `,` between the components of a vector: write `(x, 0)`, or `x * 0` for a product"),
        ("(1.5 2)", "expected `,` between the components of a vector: write `(1.5, 2)`, or `1.5 * 2` for a product"),
    ] {
        let e = errors(&format!("pub struct S {{ {SLIDER} point p = {point}; }}"));
        assert_eq!(e, [says], "{point}");
    }
    let e = errors(&format!("pub struct S {{ {SLIDER} output w = (2 pi) * x; }}"));
    assert_eq!(e, ["expected an operator between `2` and `pi`: write `2 * pi` for a product"]);
}

/// A value after `:` (`psi: 0.5`, as YAML writes a key's value) is told to take `=`: "no type
/// is needed: write `psi` alone" dropped the value. A type after it is still told to go.
#[test]
fn a_value_after_a_colon_is_told_to_take_equals() {
    for (decls, says) in [
        ("params r: 1.5, l; input phi; unknowns psi, x;", "a value is given with `=`, not `:`: write `r = ...`"),
        ("params r, l; input phi; unknowns psi: -0.5, x;", "a value is given with `=`, not `:`: write `psi = ...`"),
        (
            "params r, l; input phi; unknowns psi: f64, x;",
            "no type is needed: write `psi` alone (every parameter, input and unknown is an `f64`)",
        ),
    ] {
        let e = errors(&format!("pub struct S {{ {decls} loop c: r @ phi == (x, 0) + l @ psi; }}"));
        assert_eq!(e, [says], "{decls}");
    }
}

/// Options without their `,` and options written as strings are told how to write them: the
/// first was "options take no value" of the second option, the other syn's "expected ident".
#[test]
fn options_without_comma_or_in_quotes_are_told_how_to_write() {
    let decl = |attr: &str| {
        errors(&format!(
            "{attr} pub struct S {{ params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi; }}"
        ))
    };
    for (attr, says) in [
        ("#[kinloop(dense newton)]", "options are separated by `,`: write `#[kinloop(dense, newton)]`"),
        ("#[kinloop(dense = 1)]", "kinloop options take no value: write `#[kinloop(dense)]`"),
        ("#[kinloop(\"newton\")]", "an option is a name, not a string: write `#[kinloop(newton)]`"),
        (
            "#[kinloop(\"fast\")]",
            "an option is a name, not a string: `#[kinloop(dense)]`, `#[kinloop(newton)]` or \
             `#[kinloop(sensitivities)]`",
        ),
    ] {
        assert_eq!(decl(attr), [says], "{attr}");
    }
}

/// Where the angle of `@` is an angle by the rest of the mechanism, swapping the two cannot
/// help: the length is told to be a length, not to trade places with another angle. Where the
/// angle is one only by terms whose length is an angle (`th @ e`, `deg(30) @ e`), it is a
/// length written in the wrong place, and the swap stands.
#[test]
fn a_polar_term_of_two_angles_is_not_told_to_swap_them() {
    let head = "params r, l, e, tilt = deg(5); input phi; unknowns psi, x; loop c: r @ phi == (x, e) + l @ psi;";
    for (body, length, angle) in [
        ("point p = psi @ phi;", "psi", "phi"),
        ("point p = (2 * psi) @ phi;", "(2 * psi)", "phi"),
        ("point p = deg(3) @ phi;", "deg(3)", "phi"),
        ("point p = tilt @ (phi - psi);", "tilt", "phi - psi"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        let fix = format!(
            "`{angle}` is an angle too, so swapping the two cannot help; write a length there, such as `r * {length}` \
             for the arc a radius `r` rolls"
        );
        assert!(e[0].ends_with(&fix), "{body}: {e:#?}");
    }
    for (body, swap) in [
        ("point p = tilt @ e; point q = deg(30) @ e;", ["e @ tilt", "e @ deg(30)"]),
        ("point p = psi @ e; point q = tilt @ e;", ["e @ psi", "e @ tilt"]),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 2, "{body}: {e:#?}");
        for (m, swap) in e.iter().zip(swap) {
            assert!(m.ends_with(&format!("the two are swapped; write `{swap}`")), "{body}: {e:#?}");
        }
    }
}

/// The angle of a swapped term (`l` in `psi @ l`) is an angle only by that mistake: a
/// coordinate, a sum and a `let` that use it as the length it is are not refused as well.
#[test]
fn the_angle_of_a_swapped_term_is_a_length_elsewhere() {
    let head = "params r, l, e; input phi; unknowns psi, x;
                loop c: r @ phi == (x, e) + psi @ l; point mid = r @ phi + 0.5 * l @ psi;";
    for body in ["point p = (x, 2 * l);", "point p = (x, l);", "let k = x + l; point p = (k, 0);", "eq q: x == l + e;"]
    {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        let angles: Vec<&String> = e.iter().filter(|m| m.contains("is an angle")).collect();
        assert_eq!(angles.len(), 1, "{body}: {e:#?}");
        assert!(angles[0].ends_with("the two are swapped; write `l @ psi`"), "{body}: {e:#?}");
    }
    // A name `l` that is an angle is shown turned by a link of another name.
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns x; loop c: r @ phi + r @ l == (x, 0); point p = (x, l); }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].contains("as in `r @ l`"), "{e:#?}");
}

/// An angle unknown known as one only from its guess in degrees (a pinion rolled into a
/// length, `x == r * w`) is refused bare in a centre of mass or a force's point, as an angle
/// of the kinematics is.
#[test]
fn an_unknown_guessed_in_degrees_is_no_coordinate_of_a_body_or_a_force() {
    let head = "params r, l, e, m; input phi; unknowns psi, x, w = deg(30);
                loop c: r @ phi == (x, e) + l @ psi; eq roll: x == r * w;";
    for (body, what) in [
        ("body b: mass m, com (w, e);", "a centre of mass"),
        ("force f at (x, w) = (1, 0);", "the point a force acts at"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        let told = format!("{what} is a point of lengths, but `w` is an angle (its value is written in degrees): ");
        assert!(e[0].starts_with(&told), "{body}: {e:#?}");
    }
}

/// A centre of mass or a force's point with an angle among its coordinates gets the angle's
/// error alone: declaring the point, which its other coordinate would need, cannot mend it.
#[test]
fn an_angle_beside_an_undeclared_coordinate_is_the_one_error() {
    let head = "params r, l, m; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";
    for (body, angle) in [
        ("body b: mass m, com (psi, x * l);", "psi"),
        ("body b: mass m, com (2 * psi, x * l);", "2 * psi"),
        ("force f at (phi, x / 2) = (1, 0);", "phi"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        assert!(e[0].contains(&format!("`{angle}` is an angle")), "{body}: {e:#?}");
    }
    // Without the angle, the point is still to be declared.
    let e = errors(&format!("pub struct S {{ {head} body b: mass m, com (x, x * l); }}"));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("a centre of mass must be a declared point"), "{e:#?}");
}

/// A name written as a length (a coordinate of the loop, the length of `@`) that enters a sine
/// only as a fraction of itself (`sin(x / 2)`: the 2 may be a radius written as a number) is
/// of no certain kind, so a length: neither it nor its term is refused. A whole multiple
/// (`sin(2 * x)`) still makes it an angle, and so does a half angle of a name not written as a
/// length.
#[test]
fn a_length_scaled_into_a_sine_by_a_number_stays_a_length() {
    let head = "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";
    for body in ["point p = x @ psi; output s = sin(x / 2);", "point p = (x / 2) @ psi; output s = cos(1.5 * x);"] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert!(e.iter().all(|m| !m.contains("is an angle")), "{body}: {e:#?}");
    }
    let e = errors(&format!("pub struct S {{ {head} point p = x @ psi; output s = sin(2 * x); }}"));
    assert!(e.iter().any(|m| m.starts_with("`x` is an angle")), "{e:#?}");
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi, x, h; loop c: r @ phi == (x, 0) + l @ psi;
                    eq half: h == x / l; output s = sin(h / 2); let k = x + h; output o = k; }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`x + h` adds an angle and a length"), "{e:#?}");
}

/// A scalar `let` of a value in degrees is an angle where it is written as a length, as the
/// value written there is: the length of `@` and a coordinate of a position, directly or
/// scaled by a number, or through another such `let`.
#[test]
fn a_let_in_degrees_is_an_angle_where_a_length_belongs() {
    let head = "params r, l; input phi; unknowns psi, x; loop c: r @ phi == (x, 0) + l @ psi;";
    for (body, shown) in [
        ("let tilt = deg(15); point p = (x, 0) + tilt @ l;", "tilt"),
        ("let tilt = 2 * deg(15); point p = (x, tilt);", "tilt"),
        ("let tilt = deg(15); point p = (x, 0) + (2 * tilt) @ l;", "2 * tilt"),
        ("let tilt = deg(15); let more = tilt + pi / 2; point p = (x, more);", "more"),
    ] {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        assert_eq!(e.len(), 1, "{body}: {e:#?}");
        assert!(
            e[0].starts_with(&format!("`{shown}` is an angle (its value is written in degrees)")),
            "{body}: {e:#?}"
        );
    }
    // A `let` of a number is a length as written.
    let e = errors(&format!("pub struct S {{ {head} let k = 2 * pi / 3; point p = (x, k) + k @ psi; }}"));
    assert!(e.is_empty(), "{e:#?}");
}

/// An unknown whose guess is written in degrees is declared an angle by it: the pinion's angle
/// `w` (rolled into a length, `x == r * w`) is refused bare in a centre of mass as an angle, so
/// a body turning with it and a torque on it are accepted. Both were refused as "not an angle".
#[test]
fn an_unknown_guessed_in_degrees_is_an_angle_a_body_turns_with() {
    let head = "params r, l, e, m, j; input phi; unknowns psi, x, w = deg(30);
                loop c: r @ phi == (x, e) + l @ psi; eq roll: x == r * w;";
    for body in ["body b: mass m, com (x, e), inertia j, turns w;", "torque t on w = 1.0;"] {
        assert_eq!(errors(&format!("pub struct S {{ {head} {body} }}")), Vec::<String>::new(), "{body}");
    }
    // The same unknown guessed in radians is known as an angle by nothing: still refused.
    let e =
        errors(&format!("pub struct S {{ {} body b: mass m, com (x, e), turns w; }}", head.replace("deg(30)", "0.5")));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`w` is not an angle"), "{e:#?}");
}

/// The angle of a term whose length is an angle expression (`l` in `(2 * psi) @ l`) is an angle
/// only by that term, as the angle of a bare swapped term is: a coordinate, a sum, a `let` and
/// another term that use it as the length it is are not refused as well.
#[test]
fn the_angle_of_a_term_of_an_angle_expression_is_a_length_elsewhere() {
    let head = "params r, l, e; input phi; unknowns psi, x;
                loop c: r @ phi == (x, e) + (2 * psi) @ l; point mid = r @ phi + 0.5 * l @ psi;";
    for body in ["point p = (x, 2 * l);", "point p = (x, l);", "let k = x + l; point p = (k, 0);", "eq q: x == l + e;"]
    {
        let e = errors(&format!("pub struct S {{ {head} {body} }}"));
        let angles: Vec<&String> = e.iter().filter(|m| m.contains("is an angle")).collect();
        assert_eq!(angles.len(), 1, "{body}: {e:#?}");
        assert!(angles[0].starts_with("`2 * psi` is an angle"), "{body}: {e:#?}");
        assert!(angles[0].ends_with("or if the two are swapped, write `l @ (2 * psi)`"), "{body}: {e:#?}");
    }
}

/// `psi @ (phi + e)`, its angle an angle `phi` beside a name `e` of no known kind, was told to
/// swap the two: `(phi + e) @ psi` puts the angle `phi` into a length. Whatever `e` is, the
/// angle of `@` holds an angle, so the length is told to be a length, and `e` that it makes a
/// mix if it is a length. A product (`r * phi`, a rolled arc) is a length: the swap stands.
#[test]
fn an_angle_beside_a_name_of_no_known_kind_is_not_swapped_into_a_length() {
    for (coordinate, length) in [("0", "psi"), ("e", "psi"), ("0", "(2 * psi)")] {
        let e = errors(&format!(
            "pub struct S {{ params r, l, e; input phi; unknowns psi, x;
             loop c: r @ phi == (x, {coordinate}) + l @ psi; point p = (x, 0) + {length} @ (phi + e); }}"
        ));
        assert_eq!(e.len(), 1, "{length}, {coordinate}: {e:#?}");
        assert!(!e[0].contains("swapped"), "{e:#?}");
        let fix = format!(
            ": `phi + e` holds `phi`, an angle, so swapping the two cannot help; write a length there, such as \
             `r * {length}` for the arc a radius `r` rolls, and if `e` is a length, `phi + e` mixes an angle and a \
             length: write an angle for it"
        );
        assert!(e[0].ends_with(&fix), "{e:#?}");
    }
    let e = errors(
        "pub struct S { params r, l; input phi; unknowns psi, x;
         loop c: r @ phi == (x, 0) + l @ psi; point p = (x, 0) + psi @ (r * phi); }",
    );
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].ends_with("the two are swapped; write `(r * phi) @ psi`"), "{e:#?}");
}

/// `l @ psi` and `psi @ l` both written bare, with nothing else to tell which name is the
/// length: the first written was told "the two are swapped", whichever it was (the loop's
/// `l @ psi` was told to become `psi @ l`). The first is now told that the two terms disagree,
/// and how to write them alike either way. Where the rest of the mechanism tells (`0.5 * l @
/// psi` turns by `psi`), the term that disagrees with it is told to swap, and only it: `l @ psi`
/// was told that `psi` is an angle too, so it needed a length.
#[test]
fn two_terms_of_the_same_names_in_opposite_orders_are_one_error() {
    for (first, second, [a, b]) in [("l @ psi", "psi @ l", ["l", "psi"]), ("psi @ l", "l @ psi", ["psi", "l"])] {
        let tie = format!(
            "take `{a}` and `{b}` in opposite orders, and nothing else in the mechanism tells which is the length: \
             `@` takes `length @ angle`, so write the two terms alike, `{first}` if `{a}` is the length, `{second}` \
             if `{b}` is"
        );
        let e = errors(&format!(
            "pub struct S {{ params r, l, e; input phi; unknowns psi, x;
             loop c: r @ phi == (x, e) + {first}; point p = (x, 0) + {second}; point q = (x, l + psi); }}"
        ));
        assert_eq!(e.len(), 1, "{first}: {e:#?}");
        assert_eq!(e[0], format!("`{first}` and `{second}`, written after it, {tie}"), "{e:#?}");
    }
    for (first, second) in [("l @ psi", "psi @ l"), ("psi @ l", "l @ psi")] {
        let e = errors(&format!(
            "pub struct S {{ params r, l, e; input phi; unknowns psi, x;
             loop c: r @ phi == (x, e) + {first}; point p = (x, 0) + {second}; point m = 0.5 * l @ psi; }}"
        ));
        assert_eq!(e.len(), 1, "{first}: {e:#?}");
        assert!(e[0].starts_with("`psi` is an angle"), "{first}: {e:#?}");
        assert!(e[0].ends_with("the two are swapped; write `l @ psi`"), "{first}: {e:#?}");
    }
}

/// Two terms whose lengths are expressions that take two names in opposite orders
/// (`0.5 * l @ psi` and `(2 * psi) @ l`), with nothing else to tell which is the length: the
/// first written was told its length is an angle, whichever it was. The first of the two now
/// says that they disagree, naming both readings, in either order.
#[test]
fn expression_terms_of_two_names_in_opposite_orders_are_one_error() {
    let (one, two) = ("0.5 * l @ psi", "(2 * psi) @ l");
    {
        for (first, second) in [(one, two), (two, one)] {
            let e = errors(&format!(
                "pub struct S {{ params r, l, e; input phi; unknowns psi, x;
                 loop c: r @ phi == (x, e) + {first}; point p = (x, 0) + {second}; }}"
            ));
            assert_eq!(e.len(), 1, "{first}: {e:#?}");
            let (a, b) = if first.ends_with("psi") { ("l", "psi") } else { ("psi", "l") };
            // The length that is a product is shown as the one operand it is.
            let shown = |term: &str| term.replace("0.5 * l @", "(0.5 * l) @");
            let (first, second) = (shown(first), shown(second));
            let tie = format!(
                "`{first}` and `{second}`, written after it, take `{a}` and `{b}` in opposite orders, and nothing \
                 else in the mechanism tells which is the length: `@` takes `length @ angle`, so write the two \
                 terms alike, `{first}` if `{a}` is the length, `{second}` if `{b}` is"
            );
            assert_eq!(e[0], tie, "{e:#?}");
        }
    }
}

/// The tie message of two terms `first` and `second` (as written in the message) that take
/// `a` and `b` in opposite orders.
fn tie_message(first: &str, second: &str, [a, b]: [&str; 2]) -> String {
    format!(
        "`{first}` and `{second}`, written after it, take `{a}` and `{b}` in opposite orders, and nothing else in the \
         mechanism tells which is the length: `@` takes `length @ angle`, so write the two terms alike, `{first}` \
         if `{a}` is the length, `{second}` if `{b}` is"
    )
}

/// A bare term beside an expression term of the same two names in opposite roles (`l @ psi`
/// beside `(2 * psi) @ l`, `psi @ l` beside `0.5 * l @ psi`), nothing else telling which is the
/// length, was told to swap the bare one, in either order, where two bare terms and two
/// expression terms get the tie: it gets the tie too, at the first written, in either order.
#[test]
fn a_bare_term_beside_an_expression_of_its_names_in_opposite_roles_is_a_tie() {
    // Each pair as written, and as the message shows it, with the names in its first term's order.
    for ((one, one_shown), (two, two_shown), names) in [
        (("l @ psi", "l @ psi"), ("(2 * psi) @ l", "(2 * psi) @ l"), ["l", "psi"]),
        (("psi @ l", "psi @ l"), ("0.5 * l @ psi", "(0.5 * l) @ psi"), ["psi", "l"]),
    ] {
        for ((first, first_shown), (second, second_shown), [a, b]) in
            [((one, one_shown), (two, two_shown), names), ((two, two_shown), (one, one_shown), [names[1], names[0]])]
        {
            let e = errors(&format!(
                "pub struct S {{ params r, l, e; input phi; unknowns psi, x;
                 loop c: r @ phi == (x, e) + {first}; point p = (x, 0) + {second}; }}"
            ));
            assert_eq!(e, [tie_message(first_shown, second_shown, [a, b])], "{first}, {second}");
        }
    }
}

/// Two terms of the same two names in opposite roles, bare or expressions, are judged by one
/// and the same evidence: a name written in a coordinate of a position or in a sum beside a
/// length is a length, one in a sine elsewhere an angle. Where it tells, the term it says is
/// wrong is told, alone and in either order; the verdict followed source order for expressions,
/// and two bare terms took no coordinate or sum for evidence (a tie).
#[test]
fn what_settles_which_name_is_the_length_blames_the_same_term_in_either_order() {
    // `l`-first terms (`l` the length) and `psi`-first ones, with what each says when wrong.
    let l_first = [
        ("l @ psi", "`l` is an angle", "the two are swapped; write `psi @ l`"),
        ("0.5 * l @ psi", "`0.5 * l` is an angle", "or if the two are swapped, write `psi @ (0.5 * l)`"),
    ];
    let psi_first = [
        ("psi @ l", "`psi` is an angle", "the two are swapped; write `l @ psi`"),
        ("(2 * psi) @ l", "`2 * psi` is an angle", "or if the two are swapped, write `l @ (2 * psi)`"),
    ];
    // What the rest of the mechanism says, and whether it makes `l` the length.
    let evidence = [
        ("point q = (x, 2 * l);", true),
        ("let k = x + l; output o = k;", true),
        ("output s = sin(psi);", true),
        ("let k = x + psi; output o = k;", false),
        ("point q = (x, psi);", false),
        ("output s = cos(l);", false),
    ];
    for (settles, l_is_length) in evidence {
        for l_term in l_first {
            for psi_term in psi_first {
                let wrong = if l_is_length { psi_term } else { l_term };
                for (first, second) in [(l_term.0, psi_term.0), (psi_term.0, l_term.0)] {
                    let e = errors(&format!(
                        "pub struct S {{ params r, l, e; input phi; unknowns psi, x;
                         loop c: r @ phi == (x, e) + {first}; point p = (x, 0) + {second}; {settles} }}"
                    ));
                    let case = format!("{first}, {second}, {settles}");
                    assert_eq!(e.len(), 1, "{case}: {e:#?}");
                    assert!(e[0].starts_with(wrong.1) && e[0].ends_with(wrong.2), "{case}: {e:#?}");
                }
            }
        }
    }
}

/// A pair of terms in opposite roles written twice (`l @ psi`, `psi @ l` in the loop and again
/// in the points) is one tie: the second pair's names are lengths by the first's, so its terms
/// are told nothing more.
#[test]
fn a_pair_in_opposite_roles_written_twice_is_one_tie() {
    let e = errors(
        "pub struct S { params r, l, e; input phi; unknowns psi, x;
         loop c: r @ phi == (x, e) + l @ psi; point p = (x, 0) + psi @ l; point q = (x, 0) + psi @ l;
         point w = l @ psi; }",
    );
    assert_eq!(e, [tie_message("l @ psi", "psi @ l", ["l", "psi"])], "{e:#?}");
}

/// `psi @ l` beside `th @ psi`, `th` an angle elsewhere: swapping `th @ psi` makes every term
/// right (`psi` a length, turned by `l` and by `th`), where swapping `psi @ l` leaves `th`, an
/// angle, as a length. Both were told in one order. The term whose length is an angle by the
/// rest of the mechanism is judged first, so its swap alone is told, in either order.
#[test]
fn one_swap_that_mends_two_terms_is_the_one_error() {
    for angle in ["th", "phi"] {
        let (a, b) = ("psi @ l", format!("{angle} @ psi"));
        for (first, second) in [(a, b.as_str()), (b.as_str(), a)] {
            let e = errors(&format!(
                "pub struct S {{ params r, l, e, th; input phi; unknowns psi, x;
                 loop c: r @ phi == (x, e) + {first}; point p = (x, 0) + {second}; output s = sin(th); }}"
            ));
            assert_eq!(e.len(), 1, "{first}, {second}: {e:#?}");
            let told = format!("`{angle}` is an angle");
            let swap = format!("the two are swapped; write `psi @ {angle}`");
            assert!(e[0].starts_with(&told) && e[0].ends_with(&swap), "{first}, {second}: {e:#?}");
        }
    }
}

/// A term whose length and angle are one name (`beta @ beta`, `(2 * beta) @ beta`) was told to
/// swap the two, which keeps the name in both places. The fix is a length where the length
/// belongs, whether the name is an angle elsewhere or only by this term.
#[test]
fn a_term_of_one_name_as_length_and_angle_is_told_to_write_a_length() {
    for length in ["beta", "(2 * beta)"] {
        for elsewhere in ["", " output s = sin(beta);"] {
            let e = errors(&format!(
                "pub struct S {{ params a, c, d; input phi; unknowns beta, gamma;
                 loop abcd: a @ phi + {length} @ beta == (d, 0) + c @ gamma;{elsewhere} }}"
            ));
            assert_eq!(e.len(), 1, "{length}{elsewhere}: {e:#?}");
            assert!(!e[0].contains("swapped"), "{length}{elsewhere}: {e:#?}");
            let fix = format!(
                "swapping the two cannot help; write a length there, such as `r * {length}` for the arc a radius `r` rolls"
            );
            assert!(e[0].ends_with(&fix), "{length}{elsewhere}: {e:#?}");
        }
    }
}

/// A loop closed with a negated zero (`== -0`, `-(0) ==`, `== (-0)`) is the loop closed with
/// `== 0`: the negated zero vector is the zero vector. It was refused as "the left side is a
/// vector but the right side is a scalar", though `0` is taken for the zero vector there.
#[test]
fn a_negated_zero_closes_a_loop_as_zero_does() {
    let declaration = |closed: &str| {
        format!(
            "pub struct FourBar {{ params a, b, c, d; input phi; unknowns beta = 0.5, gamma = 1.5; \
             loop abcd: {closed}; }}"
        )
    };
    let sum = "a @ phi + b @ beta - (d, 0) - c @ gamma";
    // Each closed with a negated zero beside the same closed with `0` (on the same side: the
    // equations of `0 == sum` are those of `sum == 0` negated).
    let cases = [
        (format!("{sum} == -0"), format!("{sum} == 0")),
        (format!("{sum} == (-0)"), format!("{sum} == 0")),
        (format!("{sum} == -(0)"), format!("{sum} == 0")),
        (format!("-0 == {sum}"), format!("0 == {sum}")),
    ];
    for (negated, zero) in cases {
        let zero = kinloop_codegen::expand(tokens(&declaration(&zero))).to_string();
        assert!(!zero.contains("compile_error"), "{zero}");
        let src = declaration(&negated);
        assert_eq!(errors(&src), Vec::<String>::new(), "{negated}");
        assert_eq!(kinloop_codegen::expand(tokens(&src)).to_string(), zero, "{negated}");
    }
}

/// A body turns with, and a torque acts on, an unknown an `eq` sets to an expression of an angle
/// (`y == 2 * psi`, a gear's angle), the angle the unit check and the plan's column (`y [rad]`)
/// take it for: both were refused as "not an angle". Set to a length times an angle (an arc),
/// through a circle of equations, or written as a length elsewhere, it is still refused: as a
/// length elsewhere it is told so, and so is a slider's coordinate that a sine takes only as a
/// fraction (`l @ (x / 2)`, the 2 perhaps a radius), which the unit check takes for no angle.
#[test]
fn a_body_turns_with_an_unknown_an_eq_sets_to_an_angle() {
    let head = "params m, j, g0; unknowns y;";
    for tail in [
        "eq e: y == 2 * psi; body b: mass m, com (x, 0), inertia j, turns y; torque t on y = 1.0;",
        "eq e: y == psi + g0; body b: mass m, com (x, 0), inertia j, turns y;",
        "eq e: 0 == y - phi / 2; torque t on y = 1.0;",
    ] {
        assert_eq!(errors(&format!("pub struct S {{ {SLIDER} {head} {tail} }}")), Vec::<String>::new(), "{tail}");
    }
    // Each refused as "not an angle", with the other errors it has, and whether it is told that
    // it is written as a length elsewhere.
    for (tail, name, count, placed) in [
        ("eq e: y == r * psi; body b: mass m, com (x, 0), inertia j, turns y;", "y", 1, false),
        ("unknowns z; eq e: y == 2 * z; eq f: z == y / 2 + x; torque t on y = 1.0;", "y", 1, false),
        // Written as a length, it is one: the `eq` is told as well.
        ("eq e: y == 2 * psi; point p = (x, y); body b: mass m, com (x, 0), inertia j, turns y;", "y", 2, true),
        ("point q = l @ (x / 2); body b: mass m, com (x, 0), inertia j, turns x;", "x", 1, true),
        ("body b: mass m, com (x, 0), inertia j, turns x;", "x", 1, false),
    ] {
        let e = errors(&format!("pub struct S {{ {SLIDER} {head} {tail} }}"));
        assert_eq!(e.len(), count, "{tail}: {e:#?}");
        assert!(e[0].starts_with(&format!("`{name}` is not an angle")), "{tail}: {e:#?}");
        assert!(e[0].contains(&format!("or `{name} == 2 * psi` with `psi` an angle)")), "{tail}: {e:#?}");
        let told =
            "; it is written as a length elsewhere (a coordinate of a position or the length of `@`), where only";
        assert_eq!(e[0].contains(told), placed, "{tail}: {e:#?}");
    }
}

/// The angle of a polar term that an `eq` sets to an angle (`y` in `psi @ y`, `y == 2 * phi`)
/// is an angle apart from the term, as the unit check finds it: swapping cannot help, and `y`
/// stays the angle it is (`y + x` is told). It was taken for a length written in the wrong
/// place: "write `y @ psi`", a link `2 * phi` long, and `y + x` passed.
#[test]
fn the_angle_of_a_term_that_an_eq_sets_to_an_angle_is_no_swapped_length() {
    let e = errors(&format!("pub struct S {{ {SLIDER} unknowns y; eq e: y == 2 * phi; point p = psi @ y; }}"));
    assert_eq!(e.len(), 1, "{e:#?}");
    assert!(e[0].starts_with("`psi` is an angle"), "{e:#?}");
    assert!(e[0].contains("`y` is an angle too, so swapping the two cannot help"), "{e:#?}");
    let e = errors(&format!(
        "pub struct S {{ {SLIDER} unknowns y; eq e: y == 2 * phi; point p = psi @ y; output w = y + x; }}"
    ));
    assert_eq!(e.len(), 2, "{e:#?}");
    assert!(e[1].starts_with("`y + x` adds an angle and a length"), "{e:#?}");
}

/// Two terms that take two names in opposite orders (`(2 * y) @ a` beside `a @ y`) are told
/// apart by an `eq` that sets one to an angle (`y == phi / 2`), in either order: the term that
/// takes `y` in its length is told. It was a tie, "nothing else in the mechanism tells which is
/// the length".
#[test]
fn an_eq_that_sets_a_name_to_an_angle_tells_two_opposite_terms_apart() {
    for points in ["point p = (2 * y) @ a; point q = a @ y;", "point p = a @ y; point q = (2 * y) @ a;"] {
        let e = errors(&format!("pub struct S {{ {SLIDER} params a; unknowns y; eq e: y == phi / 2; {points} }}"));
        assert_eq!(e.len(), 1, "{points}: {e:#?}");
        assert!(e[0].starts_with("`2 * y` is an angle"), "{points}: {e:#?}");
        assert!(!e[0].contains("nothing else"), "{points}: {e:#?}");
    }
}
