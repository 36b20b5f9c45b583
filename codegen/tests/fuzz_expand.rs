//! Fuzz-style robustness test of the macro's entry points: thousands of random and mutated token
//! streams (from valid declarations) go through `kinloop_codegen::expand` and `analyze`, which
//! must return (Ok or Err / code or `compile_error!`) without panicking. A hang cannot pass
//! either: the front end's size and operation limits (`front/limits.rs`, pinned by their own
//! tests) bound the work any input causes; no test here reads the clock.
//!
//! Deterministic: a fixed-seed PRNG drives every choice, so a failure names the case number and
//! its input, and reruns the same. Set `KINLOOP_FUZZ_CASES` to run more cases (the coverage-guided
//! cargo-fuzz target in `fuzz/` explores further; see the README).

use proc_macro2::{Delimiter, Group, Ident, Literal, Punct, Spacing, Span, TokenStream, TokenTree};
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Valid declarations (bodies of `mechanism!`), the material mutations start from.
const SEEDS: &[&str] = &[
    // Offset slider-crank with an output point.
    "/// Slider-crank.
     pub struct SliderCrank {
         params r = 1.0, l = 3.0, e = 0.2;
         input phi;
         unknowns psi = 0, x = r + l;
         loop oabo: r @ phi == (x, e) + l @ psi;
         point mid = r @ phi + 0.5 * l @ psi;
     }",
    // Four-bar with a scalar output and functions.
    "pub struct FourBar {
         params a, b, c, d;
         input phi;
         unknowns beta = 0.5, gamma = 1.5;
         loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
         output tr = atan2(sin(gamma - beta), cos(gamma - beta)) ^ 2 + hypot(a, b) / sqrt(abs(c));
     }",
    // Rhombic drive (paper 000): two independent groups.
    "#[kinloop(dense)]
     pub struct RhombicDrive {
         params r_p, r_b, l_p, l_b, e_p, de, gamma, l_cs2;
         input phi1;
         unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
         loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
         loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
         point s2 = (x_c, 0) + l_cs2 @ phi2;
     }",
    // Class IV mechanism (paper 003): one coupled block.
    "pub struct ClassFour {
         params oa = 1.0, xb = 4.4, yb = 0.6, ac = 2.3, ae = 2.4, alpha_a = 0.84,
                bd = 1.6, bf = 3.5, alpha_b = 0.62, cd = 2.0, ef = 3.4;
         input phi;
         unknowns th1 = 1.4, th2 = 3.0, psi1 = -0.8, psi2 = -1.0;
         let a = oa @ phi;
         let b = (xb, yb);
         loop acdb: a + ac @ th1 + cd @ psi1 == b + bd @ th2;
         loop aefb: a + ae @ (th1 + alpha_a) + ef @ psi2 == b + bf @ (th2 + alpha_b);
     }",
    // Two inputs, a scalar equation, vector functions, time-like input.
    "pub(crate) struct TwoInputs {
         params l1 = 2, l2 = 1.5, v = 0.1;
         inputs th1, t;
         unknowns s = 1, phi = 0.3;
         let p = rot((l1, 0), th1) + v * t * (1, 0);
         eq along: dot(p, (cos(phi), sin(phi))) == s;
         eq across: cross(p, 1 @ phi) == 0;
         output len = norm(p) + angle(p) - exp(ln(l2)) + pow(l2, 0.5) + tan(asin(0.1)) + acos(0.2) - atan(1);
         point tip = p.x * (1, 0) + (0, p.y) - -p / 2;
     }",
];

/// SplitMix64: tiny, deterministic, good enough to drive mutations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        if n == 0 { 0 } else { (self.next() % n as u64) as usize }
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// A token tree we can edit: leaves, or groups holding a list.
#[derive(Clone)]
enum Tok {
    Leaf(TokenTree),
    Group(Delimiter, Vec<Tok>),
}

fn to_toks(ts: TokenStream) -> Vec<Tok> {
    ts.into_iter()
        .map(|tt| match tt {
            TokenTree::Group(g) => Tok::Group(g.delimiter(), to_toks(g.stream())),
            other => Tok::Leaf(other),
        })
        .collect()
}

fn to_stream(toks: &[Tok]) -> TokenStream {
    toks.iter()
        .map(|t| match t {
            Tok::Leaf(tt) => tt.clone(),
            Tok::Group(d, inner) => TokenTree::Group(Group::new(*d, to_stream(inner))),
        })
        .collect()
}

/// Number of lists (the top level and every group's contents) in `toks`.
fn lists(toks: &[Tok]) -> usize {
    1 + toks.iter().map(|t| if let Tok::Group(_, inner) = t { lists(inner) } else { 0 }).sum::<usize>()
}

/// Runs `f` on the `k`-th list in pre-order; returns whether it was found.
fn with_list(toks: &mut Vec<Tok>, k: &mut usize, f: &mut dyn FnMut(&mut Vec<Tok>)) -> bool {
    if *k == 0 {
        f(toks);
        return true;
    }
    *k -= 1;
    for t in toks.iter_mut() {
        if let Tok::Group(_, inner) = t
            && with_list(inner, k, f)
        {
            return true;
        }
    }
    false
}

const PUNCTS: &[&str] =
    &[";", ",", "=", "==", "@", "+", "-", "*", "/", "^", ".", ":", "::", "#", "<", ">", "!", "&", "->", "=>", ".."];
const WORDS: &[&str] = &[
    "params",
    "param",
    "input",
    "inputs",
    "unknowns",
    "unknown",
    "let",
    "loop",
    "eq",
    "point",
    "output",
    "pub",
    "struct",
    "kinloop",
    "dense",
    "doc",
    "pi",
    "phi",
    "x",
    "y",
    "r",
    "l",
    "sin",
    "cos",
    "atan2",
    "norm",
    "rot",
    "dot",
    "pow",
    "hypot",
    "log",
    "r#type",
    "self",
    "crate",
    "fn",
    "_",
    "Self",
    "λ",
    "a_very_long_name_that_is_not_declared_anywhere",
];
const LITERALS: &[&str] = &[
    "0",
    "1",
    "2.5",
    "1e308",
    "1e999",
    "-1",
    "0x10",
    "1_000",
    "2f32",
    "3u8",
    "1e-400",
    "\"text\"",
    "'c'",
    "b'x'",
    "9999999999999999999999",
    "2147483647",
    "1024",
    "1025",
    "0.0",
    "1.5e3",
];

fn random_leaf(rng: &mut Rng) -> Tok {
    let src = match rng.below(3) {
        0 => *rng.pick(PUNCTS),
        1 => *rng.pick(WORDS),
        _ => *rng.pick(LITERALS),
    };
    let ts: TokenStream = src.parse().unwrap_or_default();
    let mut toks = to_toks(ts);
    if toks.len() == 1 { toks.pop().unwrap_or(Tok::Leaf(punct(';'))) } else { Tok::Group(Delimiter::None, toks) }
}

fn punct(c: char) -> TokenTree {
    TokenTree::Punct(Punct::new(c, Spacing::Alone))
}

fn random_delimiter(rng: &mut Rng) -> Delimiter {
    *rng.pick(&[Delimiter::Parenthesis, Delimiter::Brace, Delimiter::Bracket, Delimiter::None])
}

/// One random edit somewhere in the tree.
fn mutate(rng: &mut Rng, toks: &mut Vec<Tok>, donor: &[Tok]) {
    let mut k = rng.below(lists(toks));
    with_list(toks, &mut k, &mut |list| edit(rng, list, donor));
}

/// One random edit of `list`.
fn edit(rng: &mut Rng, list: &mut Vec<Tok>, donor: &[Tok]) {
    let n = list.len();
    let i = rng.below(n + 1);
    match rng.below(10) {
        0 if n > 0 => {
            list.remove(i.min(n - 1));
        }
        1 if n > 0 => {
            let t = list[i.min(n - 1)].clone();
            list.insert(i.min(n - 1), t);
        }
        2 if n > 1 => {
            let j = i.min(n - 2);
            list.swap(j, j + 1);
        }
        3 | 4 => list.insert(i, random_leaf(rng)),
        5 if n > 0 => {
            // Wrap a run in a group.
            let a = i.min(n - 1);
            let b = (a + 1 + rng.below(4)).min(n);
            let run: Vec<Tok> = list.drain(a..b).collect();
            list.insert(a, Tok::Group(random_delimiter(rng), run));
        }
        6 if n > 0 => {
            // Unwrap a group.
            let a = i.min(n - 1);
            if let Tok::Group(_, inner) = list[a].clone() {
                list.splice(a..=a, inner);
            }
        }
        7 if !donor.is_empty() => {
            // A run of tokens from another declaration.
            let a = rng.below(donor.len());
            let b = (a + 1 + rng.below(6)).min(donor.len());
            list.splice(i..i, donor[a..b].iter().cloned());
        }
        8 if n > 0 => {
            // Truncate: an unfinished declaration.
            list.truncate(i.min(n - 1));
        }
        _ => list.insert(i, Tok::Leaf(punct(*rng.pick(&[';', ',', '=', '@', '.', '-'])))),
    }
}

/// A stream of random tokens with random nesting.
fn random_stream(rng: &mut Rng, len: usize, depth: usize) -> Vec<Tok> {
    (0..len)
        .map(|_| {
            if depth < 6 && rng.below(8) == 0 {
                let (delimiter, len) = (random_delimiter(rng), rng.below(6));
                Tok::Group(delimiter, random_stream(rng, len, depth + 1))
            } else {
                random_leaf(rng)
            }
        })
        .collect()
}

/// Runs both entry points on `ts`; panics become test failures naming the input. Returns whether
/// the declaration was accepted (code without `compile_error!`).
fn check(case: &str, ts: TokenStream) -> bool {
    let text = ts.to_string();
    let analyzed = catch_unwind(AssertUnwindSafe(|| kinloop_codegen::analyze(ts.clone()).map(|_| ())));
    let expanded = catch_unwind(AssertUnwindSafe(|| kinloop_codegen::expand(ts)));
    let shown: String = text.chars().take(2000).collect();
    assert!(analyzed.is_ok(), "`analyze` panicked on {case}:\n{shown}");
    let out = expanded.unwrap_or_else(|_| panic!("`expand` panicked on {case}:\n{shown}"));
    // Whatever comes out must be tokens the compiler can read back; after errors, Rust items:
    // the `compile_error!`s and the fallback items. (Accepted code is compiled by the other tests.)
    let printed = out.to_string();
    assert!(printed.parse::<TokenStream>().is_ok(), "`expand` produced unlexable tokens on {case}");
    if printed.contains("compile_error")
        && let Err(e) = syn::parse2::<syn::File>(out)
    {
        panic!("`expand` produced tokens that are not Rust items on {case}: {e}\n{shown}\n=> {printed}");
    }
    let accepted = !printed.contains("compile_error");
    assert_eq!(accepted, matches!(analyzed, Ok(Ok(()))), "`analyze` and `expand` disagree on {case}:\n{shown}");
    accepted
}

fn cases() -> usize {
    std::env::var("KINLOOP_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(3000)
}

/// Runs `f` on a thread with the stack of a compiler's main thread (8 MiB), so a recursion that
/// would overflow inside rustc overflows here too.
fn with_compiler_stack(f: impl FnOnce() + Send + 'static) {
    let handle = std::thread::Builder::new().stack_size(8 << 20).spawn(f).expect("spawn");
    if let Err(e) = handle.join() {
        std::panic::resume_unwind(e);
    }
}

#[test]
fn seeds_expand_without_errors() {
    // The mutations start from valid declarations: check that they are.
    for (k, seed) in SEEDS.iter().enumerate() {
        let ts: TokenStream = seed.parse().expect("seed tokens");
        let out = kinloop_codegen::expand(ts).to_string();
        assert!(!out.contains("compile_error"), "seed {k} is not valid:\n{out}");
    }
}

#[test]
fn mutated_declarations_never_panic() {
    with_compiler_stack(|| {
        let seeds: Vec<Vec<Tok>> = SEEDS.iter().map(|s| to_toks(s.parse().expect("seed tokens"))).collect();
        let mut rng = Rng(0x6b69_6e6c_6f6f_7031);
        let mut accepted = 0;
        for case in 0..cases() {
            let mut toks = rng.pick(&seeds).clone();
            let donor = rng.pick(&seeds).clone();
            for _ in 0..1 + rng.below(6) {
                mutate(&mut rng, &mut toks, &donor);
            }
            accepted += usize::from(check(&format!("mutation case {case}"), to_stream(&toks)));
        }
        eprintln!("mutations: {} cases ({accepted} still valid)", cases());
        // Some mutants must stay valid (e.g. a duplicated `,`), or code generation is never fuzzed.
        assert!(accepted > cases() / 50, "only {accepted} mutants were valid");
    });
}

#[test]
fn random_streams_never_panic() {
    with_compiler_stack(|| {
        let mut rng = Rng(0x7261_6e64_6f6d_0002);
        for case in 0..cases() {
            let len = rng.below(40);
            let mut toks = random_stream(&mut rng, len, 0);
            // Half of them look like the start of a declaration, to get past the first checks.
            if rng.below(2) == 0 {
                let head: TokenStream = "pub struct M".parse().expect("tokens");
                let mut body = to_toks(head);
                body.push(Tok::Group(Delimiter::Brace, toks));
                toks = body;
            }
            check(&format!("random case {case}"), to_stream(&toks));
        }
    });
}

/// Declarations at and beyond the size limits: deep nesting, long chains, many names.
#[test]
fn extreme_inputs_are_rejected_or_accepted_without_panic() {
    with_compiler_stack(|| {
        let decl = |body: &str| format!("pub struct M {{ params r, l; input phi; unknowns psi, x; {body} }}");
        let deep = |open: &str, close: &str, n: usize| format!("{}x{}", open.repeat(n), close.repeat(n));
        let mut inputs: Vec<(String, String)> = vec![
            ("nested parentheses".into(), decl(&format!("output o = {};", deep("(", ")", 3000)))),
            ("nested calls".into(), decl(&format!("output o = {};", deep("sin(", ")", 3000)))),
            ("unary minus chain".into(), decl(&format!("output o = {}x;", "- ".repeat(5000)))),
            ("power chain".into(), decl(&format!("output o = x{};", " ^ x".repeat(5000)))),
            ("sum chain".into(), decl(&format!("output o = x{};", " + x".repeat(20_000)))),
            ("component chain".into(), decl(&format!("output o = (x, x){};", ".x".repeat(20_000)))),
            (
                "nested vectors".into(),
                decl(&format!("point p = {};", deep("(x, ", ")", 2000).replace("x)", "(x, x))"))),
            ),
            ("nested braces".into(), format!("pub struct M {}", deep("{", "}", 3000))),
            ("nested attribute".into(), format!("#[kinloop{}] pub struct M {{}}", deep("(", ")", 3000))),
            ("huge exponent".into(), decl("loop c: r @ phi == (x, 0) + l @ psi; output o = x ^ -2147483647;")),
            ("long identifier".into(), decl(&format!("output o = {};", "q".repeat(100_000)))),
            ("empty".into(), String::new()),
            (
                "raw identifiers".into(),
                "pub struct r#type { params r#fn = 1.0, r#unused; input r#loop; unknowns r#in; \
                 eq r#match: r#in == r#fn * r#loop; point r#let = (r#in, 0); }"
                    .into(),
            ),
            ("only a name".into(), "struct".into()),
        ];
        // A long chain of `let`s, each using the previous one: deep graphs without deep syntax.
        let lets: String = (1..1000).map(|k| format!("let v{k} = v{} * 1.0001 + r;", k - 1)).collect();
        inputs.push(("let chain".into(), decl(&format!("let v0 = x; {lets} loop c: r @ phi == (v999, 0) + l @ psi;"))));
        // Many unknowns: beyond the limit, and a large valid chain of slider equations.
        let names: Vec<String> = (0..300).map(|k| format!("u{k}")).collect();
        inputs.push((
            "too many unknowns".into(),
            format!(
                "pub struct M {{ params r; input phi; unknowns {}; {} }}",
                names.join(", "),
                names.iter().map(|n| format!("eq e{n}: {n} == r * phi;")).collect::<String>()
            ),
        ));
        let chain: String = (1..60).map(|k| format!("eq e{k}: u{k} == u{} + r * sin(u{k});", k - 1)).collect();
        inputs.push((
            "long chain of blocks".into(),
            format!(
                "pub struct M {{ params r = 0.1; input phi; unknowns {}; eq e0: u0 == phi; {chain} }}",
                (0..60).map(|k| format!("u{k}")).collect::<Vec<_>>().join(", ")
            ),
        ));
        for (what, src) in inputs {
            let ts: TokenStream = src.parse().unwrap_or_else(|e| panic!("{what}: {e}"));
            check(what.as_str(), ts);
        }
        // Idents and literals built directly (not from text).
        let odd: TokenStream = [
            TokenTree::Ident(Ident::new("pub", Span::call_site())),
            TokenTree::Ident(Ident::new("struct", Span::call_site())),
            TokenTree::Ident(Ident::new_raw("match", Span::call_site())),
            TokenTree::Group(Group::new(
                Delimiter::Brace,
                [TokenTree::Literal(Literal::f64_suffixed(f64::MAX))].into_iter().collect(),
            )),
        ]
        .into_iter()
        .collect();
        check("direct tokens", odd);
    });
}

/// Runs both entry points on a huge input without printing it (printing a token stream
/// recurses into its groups) and returns the expansion's text.
fn run_huge(what: &str, src: &str) -> String {
    let ts: TokenStream = src.parse().unwrap_or_else(|e| panic!("{what}: {e}"));
    let analyzed = catch_unwind(AssertUnwindSafe(|| kinloop_codegen::analyze(ts.clone()).err().map(|e| e.to_string())));
    let expanded = catch_unwind(AssertUnwindSafe(|| kinloop_codegen::expand(ts)));
    assert!(analyzed.is_ok(), "`analyze` panicked on {what}");
    expanded.unwrap_or_else(|_| panic!("`expand` panicked on {what}")).to_string()
}

/// Brackets nested far beyond any parser's recursion: rejected by one error naming the limit,
/// before syn's recursive token buffer sees them (which would overflow the stack and abort the
/// compiler).
#[test]
fn deep_nesting_is_one_error_without_stack_overflow() {
    with_compiler_stack(|| {
        let decl = |body: &str| format!("pub struct M {{ params r, l; input phi; unknowns psi, x; {body} }}");
        for n in [50_000, 1_000_000] {
            for (open, close) in [("(", ")"), ("[", "]"), ("{", "}"), ("sin(", ")")] {
                let deep = format!("{}x{}", open.repeat(n), close.repeat(n));
                for (place, src) in [
                    ("expression", decl(&format!("output o = {deep};"))),
                    ("body", format!("pub struct M {deep}")),
                    ("attribute", format!("#[kinloop{deep}] pub struct M {{}}")),
                ] {
                    let what = format!("{n} nested `{open}` in the {place}");
                    let out = run_huge(&what, &src);
                    assert_eq!(out.matches("compile_error").count(), 1, "{what}: {out}");
                    assert!(out.contains("nested more than 256 levels deep"), "{what}: {out}");
                }
            }
        }
    });
}

/// Long chains of `let`s: accepted while small, then one error naming the limit that is hit
/// (the size of the lowered declaration, then the number of tokens).
#[test]
fn huge_let_chains_are_bounded() {
    with_compiler_stack(|| {
        let chain = |n: usize| {
            let lets: String = (1..n).map(|k| format!("let v{k} = v{} * 1.0001 + r;", k - 1)).collect();
            format!(
                "pub struct M {{ params r, l; input phi; unknowns psi, x; let v0 = x; {lets} \
                 loop c: r @ phi == (v{}, 0) + l @ psi; }}",
                n - 1
            )
        };
        let out = run_huge("2000 lets", &chain(2000));
        assert!(!out.contains("compile_error"), "2000 lets are a valid declaration");
        // Two operations per `let`: the limit of 5000 is crossed near the 2500th.
        for n in [3000, 9000] {
            let out = run_huge(&format!("{n} lets"), &chain(n));
            assert_eq!(out.matches("compile_error").count(), 1, "{}", &out[..out.len().min(2000)]);
            assert!(out.contains("more than 5000 distinct operations"), "{}", &out[..out.len().min(2000)]);
        }
        // Nine tokens per `let`: beyond 11111 of them the token limit stops everything first.
        for n in [15_000, 50_000, 200_000] {
            let out = run_huge(&format!("{n} lets"), &chain(n));
            assert_eq!(out.matches("compile_error").count(), 1);
            assert!(out.contains("more than 100000 tokens"), "{}", &out[..out.len().min(2000)]);
        }
    });
}
