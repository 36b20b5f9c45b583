//! How the kernel a point solve and a sweep call solves and factorises its blocks.
//!
//! Which Newton blocks hand their final factorisation to their analogs: those whose unknowns'
//! Jacobian columns have no entry outside the block (the column magnitudes the analogs
//! equilibrate by are then known when the block is solved). Which make the magnitudes their
//! tests judge in once per solve: those whose magnitudes do not depend on their unknowns. And
//! what a 2x2 block's explicit inverse (`Inverse2::in_cols`) is given besides its own entries:
//! the entries of its columns beyond it (the rows of later blocks that hold its unknowns). And
//! which sines and cosines a sweep's kernel has by angle addition (`add_angles`).

use proc_macro2::TokenStream;

/// The statement that solves block `b` in the kernel a point solve and a sweep call
/// (`kinematics_step_sink`), as expanded text without whitespace.
fn newton_call(decl: &str, b: usize) -> String {
    let kernel = fused_kernel(decl);
    let at = kernel.find(&format!("let__r{b}=")).unwrap_or_else(|| panic!("no Newton call for block {b}"));
    kernel[at..at + kernel[at..].find(';').expect("end of statement")].to_string()
}

/// The fused kernel of `decl` to its end, as expanded text without whitespace.
fn fused_kernel(decl: &str) -> String {
    let tokens: TokenStream = decl.parse().expect("declaration tokens");
    let file: syn::File = syn::parse2(kinloop_codegen::expand(tokens)).expect("expansion is a file");
    let code = prettyplease::unparse(&file);
    code[code.find("fn kinematics_step_sink").expect("the fused kernel")..].split_whitespace().collect()
}

/// The whole expansion of `decl`, as text without whitespace.
fn expansion(decl: &str) -> String {
    let tokens: TokenStream = decl.parse().expect("declaration tokens");
    let file: syn::File = syn::parse2(kinloop_codegen::expand(tokens)).expect("expansion is a file");
    prettyplease::unparse(&file).split_whitespace().collect()
}

/// The declaration of both Watt chains, after their attributes.
macro_rules! watt_body {
    () => {
        "pub struct Watt {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, e = 2.0, f = 2.8, g = 1.5, h = 2.6, k = 3.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, delta = 0.2, eps = 1.8;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop second: a @ phi + e @ (beta + 0.3) + f @ delta == (g, h) + k @ eps;
    }"
    };
}

/// A four-bar whose coupler carries a second dyad, both solved by Newton: the coupler angle
/// `beta` also appears in the second loop, so the first block's columns reach outside it.
const WATT: &str = concat!("#[kinloop(newton)]", watt_body!());

/// [`WATT`] with its dyads in closed form.
const WATT_CLOSED: &str = watt_body!();

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

/// A slotted rocker: the slider's distance `s` is a length of its own loop, so the loop's
/// magnitude depends on it.
const ROCKER: &str = "#[kinloop(newton)]
    pub struct Rocker {
        params a = 1.0, d = 2.0;
        input phi;
        unknowns s = 2.5, psi = 0.3;
        loop l: a @ phi == (d, 0) + s @ psi;
    }";

#[test]
fn magnitudes_free_of_the_unknowns_are_made_once_per_solve() {
    let kernel = fused_kernel(WATT);
    for b in 0..2 {
        let made = kernel.find(&format!("let__mag{b}=::kinloop::__gen::Magnitudes::new(")).expect("made once");
        let evaluation = kernel.find(&format!("let__eval{b}=")).expect("the evaluation closure");
        // The closure's body: from its first brace to the one that closes it.
        let open = evaluation + kernel[evaluation..].find('{').expect("the closure's body");
        let mut depth = 0;
        let close = open
            + kernel[open..]
                .char_indices()
                .find(|&(_, ch)| {
                    depth += match ch {
                        '{' => 1,
                        '}' => -1,
                        _ => 0,
                    };
                    depth == 0
                })
                .expect("the body closes")
                .0;
        assert!(made < open || made > close, "made outside the evaluation closure");
        let call = newton_call(WATT, b);
        assert!(call.contains(&format!("__eval{b},&__mag{b}")), "{call}");
    }
    assert!(!kernel.contains("scale:") && !kernel.contains("unit:"), "no magnitudes in the evaluations");
}

#[test]
fn magnitudes_that_depend_on_the_unknowns_come_from_each_evaluation() {
    let call = newton_call(ROCKER, 0);
    assert!(call.contains("&|__e:&::kinloop::__gen::BlockEval<2,6>|{::kinloop::__gen::Magnitudes::new("), "{call}");
    assert!(call.contains("[__e.keep[2],__e.keep[3]],[__e.keep[4],__e.keep[5]]"), "{call}");
    assert!(!fused_kernel(ROCKER).contains("let__mag0"), "nothing made once");
    // The angle repeats every turn; the slide, which its loop holds linearly, does not.
    assert!(call.contains(".with_turns([false,true])"), "{call}");
}

#[test]
fn angles_that_repeat_every_turn_are_marked_for_newton() {
    let kernel = fused_kernel(WATT);
    // `beta` enters the second block as `e @ (beta + 0.3)`, a known angle there.
    for b in 0..2 {
        assert!(kernel.contains(&format!("let__mag{b}=::kinloop::__gen::Magnitudes::new(")), "block {b}");
    }
    assert_eq!(kernel.matches(".with_turns([true,true]);").count(), 2, "both dyads' angles");
    // An angle that also enters by itself (rolling, `r th`) is a different position a turn
    // on; so is half an angle, and a ratio that is not a whole number. (Each loop couples `x`
    // and `th` into one block.)
    for (loop_, why) in [
        ("loop w: (x, 0) + r @ th == (u + r * th, x);", "rolling"),
        ("loop w: (x, 0) + r @ (th / 2) == (u, x);", "half angle"),
        ("loop w: (x, 0) + r @ (1.5 * th) == (u, x);", "ratio"),
        ("loop w: (x, 0) + r @ (2 * th) == (u, x) + (0, r * th);", "beside its sine"),
    ] {
        let decl =
            format!("#[kinloop(newton)] pub struct W {{ params r = 1.0; input u; unknowns x = 0, th = 0.5; {loop_} }}");
        let kernel = fused_kernel(&decl);
        assert!(kernel.contains("let__r0=::kinloop::__gen::newton"), "{why}: one Newton block");
        assert!(!kernel.contains("with_turns"), "{why}");
    }
}

/// The inverse statement of block `b`.
fn inverse_of(kernel: &str, b: usize) -> String {
    let at = kernel.find(&format!("let__lu{b}=")).unwrap_or_else(|| panic!("no factorisation of block {b}"));
    kernel[at..at + kernel[at..].find(';').expect("end of statement")].to_string()
}

/// The closed-form Watt chain: `beta`'s column of the first dyad reaches the second loop's rows,
/// `gamma`'s does not.
#[test]
fn a_column_reaching_a_later_block_passes_its_further_entries() {
    let kernel = fused_kernel(WATT_CLOSED);
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

/// The statements of `kernel` that ask the sweep's cache for sines and cosines, in order.
fn trig_calls(kernel: &str) -> Vec<&str> {
    kernel.split(';').filter(|s| s.contains("__trig.sin_cos")).collect()
}

/// An input angle plus a parameter angle or a constant: in a sweep's kernel its sine and cosine
/// come by angle addition (`add_angles`) from the input's pair (asked first even where it is
/// declared later) and the offset's (a parameter's asked of the cache, which keeps it; a
/// constant's a constant), not by a rotation of their own. Without the input's own pair, or
/// with an unknown in the sum, the argument keeps its rotation.
#[test]
fn an_input_angle_plus_an_offset_comes_by_angle_addition() {
    let drive = |first: &str, second: &str| {
        fused_kernel(&format!(
            "pub struct Drive {{
                params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, gamma = 0.7;
                input phi;
                unknowns phi4 = 3.1, x_f = 3.5, phi2 = 0, x_c = -3;
                {first}
                {second}
            }}"
        ))
    };
    // The names a `let((s,c)):(f64,f64)=...` statement gives its pair.
    let pair_of =
        |call: &str| call[call.find("let(").expect("a pair") + 4..call.find("):(").expect("typed")].to_string();
    let by_gamma = "loop b: (0, e_p) + r_b @ (phi + gamma) == (x_f, 0.9) + l_b @ phi4;";
    let by_input = "loop a: (0, e_p) + r_p @ phi == (x_c, 0) + l_p @ phi2;";
    for (kernel, offset) in [
        (drive(by_gamma, by_input), Some("self.gamma")),
        (drive(&by_gamma.replace("phi + gamma", "gamma + phi"), by_input), Some("self.gamma")),
        (drive(&by_gamma.replace("phi + gamma", "phi + 0.7"), by_input), None),
    ] {
        let calls = trig_calls(&kernel);
        let input = calls[0];
        assert!(input.contains("__trig.sin_cos(") && input.ends_with("x_phi)"), "{input}");
        let sum = kernel.split(';').find(|s| s.contains("add_angles(")).expect("a sum by angle addition");
        assert!(sum.contains(&format!("add_angles(({}),(", pair_of(input))), "{sum}");
        match offset {
            Some(offset) => {
                assert_eq!(calls.len(), 2, "{calls:?}");
                assert!(calls[1].ends_with(&format!(",{offset})")), "{}", calls[1]);
                assert!(sum.contains(&format!("),({})", pair_of(calls[1]))), "{sum}");
            }
            // The constant's sine and cosine, folded.
            None => {
                assert_eq!(calls.len(), 1, "{calls:?}");
                assert!(sum.contains(&format!("{:?}f64", 0.7f64.sin())), "{sum}");
            }
        }
    }
    // Without the input's own pair, and with an unknown in the sum: rotations of their own.
    let alone = fused_kernel(
        "pub struct Alone { params r_b = 1.2, l_b = 3.5, e_p = 0.5, gamma = 0.7; input phi;
            unknowns phi4 = 3.1, x_f = 3.5;
            loop b: (0, e_p) + r_b @ (phi + gamma) == (x_f, 0.9) + l_b @ phi4; }",
    );
    assert!(!alone.contains("add_angles") && trig_calls(&alone).len() == 1, "{:?}", trig_calls(&alone));
    let coupler = fused_kernel(concat!("#[kinloop(newton)]", watt_body!()));
    assert!(!coupler.contains("add_angles"), "{:?}", trig_calls(&coupler));
}

/// A block whose rows have two units (a geared five-bar's loop and gear, one block) divides its
/// rows by their magnitudes before its columns (`Lu::factor_scaled`): it neither keeps Newton's
/// factorisation, equilibrated by its columns alone, nor takes the 2x2 inverse. A block of
/// loops and a gear large enough to be sparse does the same over its sparse factorisation.
#[test]
fn a_block_of_rows_of_two_units_divides_its_rows_first() {
    let five_bar = fused_kernel(
        "pub struct G { params a = 1, b = 2.5, c = 2.2, d = 1.5, e = 1.2; input th1;
            unknowns phi2 = 1.0, th2 = 0.8, phi3 = 1.6;
            loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3; eq gear: phi3 == 2 * th2; }",
    );
    assert!(five_bar.contains("::newton::<3,") && !five_bar.contains("newton_keeping_lu"), "{five_bar}");
    let lu = inverse_of(&five_bar, 0);
    assert!(lu.contains("Lu::<3,>::factor_scaled(&__j,"), "{lu}");
    let loops: String = (1..8).map(|k| format!("loop l{k}: a @ v{} + b @ u{k} == (d, 0) + c @ v{k};", k - 1)).collect();
    // Its kernels are the point solve's (`kinematics_flat`), not fused.
    let ring = expansion(&format!(
        "pub struct R {{ params a = 1, b = 3, c = 2.5, d = 3.2; input phi;
            unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
                u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9, w = 0.95;
            loop l0: a @ (0.5 * (phi + w)) + b @ u0 == (d, 0) + c @ v0; {loops} eq gear: w == 0.5 * v7; }}"
    ));
    assert!(ring.contains("__j.factor_scaled_into(&mut__lu0,"), "{ring}");
    // The plain chain of four-bars: its columns alone.
    let plain = fused_kernel(&watt_body!().replace("Watt", "W"));
    assert!(!plain.contains("factor_scaled"), "{plain}");
}
