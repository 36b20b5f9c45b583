//! Text from anyone: random token soups and randomly mutated declarations are read (and, when
//! accepted, solved) without a panic. Time is bounded by construction (the front end's limits
//! on tokens, nesting and operations, the Newton iteration cap), never measured here.

use kinloop_model::{Model, ReadError, source};
use proptest::prelude::*;

/// Pieces of the language and of its mistakes.
const PIECES: &[&str] = &[
    "pub",
    "struct",
    "S",
    "{",
    "}",
    "(",
    ")",
    "[",
    "]",
    "params",
    "input",
    "inputs",
    "unknowns",
    "loop",
    "eq",
    "let",
    "point",
    "output",
    "body",
    "force",
    "mass",
    "com",
    "a",
    "b",
    "phi",
    "x",
    "=",
    "==",
    "@",
    "+",
    "-",
    "*",
    "/",
    "^",
    ",",
    ";",
    ":",
    "0",
    "1",
    "2.5",
    "1e308",
    "-1e-308",
    "pi",
    "sin",
    "cos",
    "atan2",
    "sqrt",
    "ln",
    "norm",
    "dot",
    "#",
    "!",
    "kinloop",
    "newton",
    "dense",
    "sensitivities",
    "///",
    "\"",
    "'",
    "°",
    "\n",
    " ",
];

const FOUR_BAR: &str = "pub struct FourBar {
    params a = 1, b = 3, c = 2.5, d = 3.2;
    input phi;
    unknowns beta = 0.5, gamma = 1.5;
    loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    point pc = a @ phi + b @ beta;
    output ratio = b / c;
}";

/// Reads `text`; when accepted, solves at a few inputs (any result but a panic is fine).
fn exercise(text: &str) {
    match Model::read("fuzz.kl", text) {
        Ok(mut m) => {
            let ni = m.inputs().len();
            for x in [0.0, 1.0, -2.5, 1e6] {
                let _ = m.solve(&vec![x; ni]);
            }
        }
        Err(ReadError::Rejected(d)) => {
            assert!(!d.items.is_empty());
            let _ = d.render(false);
        }
        Err(ReadError::Unsupported(_)) => {}
    }
    // Nothing read above is kept: the spans of this text may go.
    source::forget_spans();
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn token_soups_never_panic(pieces in prop::collection::vec(0..PIECES.len(), 0..80)) {
        let text: Vec<&str> = pieces.iter().map(|&k| PIECES[k]).collect();
        exercise(&text.join(" "));
    }

    #[test]
    fn mutated_declarations_never_panic(
        edits in prop::collection::vec((0usize..4, 0usize..1000, 0..PIECES.len()), 1..6),
    ) {
        let mut words: Vec<String> = FOUR_BAR.split(' ').map(str::to_string).collect();
        for (kind, at, piece) in edits {
            if words.is_empty() {
                break;
            }
            let at = at % words.len();
            match kind {
                0 => {
                    words.remove(at);
                }
                1 => words.insert(at, PIECES[piece].to_string()),
                2 => words[at] = PIECES[piece].to_string(),
                _ => {
                    let w = words[at].clone();
                    words.insert(at, w);
                }
            }
        }
        exercise(&words.join(" "));
    }

    #[test]
    fn any_parameters_and_inputs_never_panic(
        values in prop::collection::vec(prop_oneof![any::<f64>(), -10.0..10.0f64], 5),
    ) {
        let mut m = Model::read("four_bar.kl", FOUR_BAR).expect("valid");
        for (p, v) in ["a", "b", "c", "d"].iter().zip(&values) {
            m.set_param(p, *v);
        }
        let _ = m.solve(&[values[4]]);
    }
}
