//! Every declaration in the repository (the `.kl` files, and the fixtures' texts the compiled
//! mechanisms are built from), mutated a token at a time, is read without a panic, a hang or
//! a stack overflow; what is rejected says why in a message that is not empty, at a place in
//! the text; what is accepted solves at one point and sweeps a short stretch, each failure
//! said in words and each success finite (never a silent NaN).
//!
//! The mutations are those of a text edited carelessly or generated badly: tokens deleted,
//! doubled, exchanged or put elsewhere; numbers replaced by extreme ones (0, -0, 1e308,
//! 1e-320, nan, inf, integers beyond any integer type); a token nested 10,000 parentheses
//! deep (closed or not); the text cut short; letters and marks outside ASCII inserted; a
//! line repeated. Deterministic (a xorshift generator, a fixed seed); each case runs on a
//! thread of its own (a hang shows as a test that does not end, which the test harness names;
//! no test here reads the clock, which a loaded host would make fail).
//!
//! `KINLOOP_FUZZ_CASES` (cases per declaration, 100 by default) and `KINLOOP_FUZZ_SEED` run a
//! longer campaign, best in release (`cargo test --release -p kinloop-model --test
//! token_mutations`), and `KINLOOP_FUZZ_TRACE` a file each case is written to before it runs (what a stack overflow,
//! which aborts the process, leaves behind).

use kinloop_fixtures as fx;
use kinloop_model::{Model, ReadError, source};
use std::path::{Path, PathBuf};
use std::sync::mpsc;

/// The fixtures' declarations, as `mechanism!` compiles them (one line each, as `stringify!`
/// writes tokens): kinds of blocks and items the shipped files do not have (class IV groups,
/// gears, time inputs, sensitivities, every dynamics item).
const FIXTURES: &[(&str, &str)] = &[
    ("BALANCE_TEXT", fx::balancing::BALANCE_TEXT),
    ("CAM_LINKAGE_TEXT", fx::cam_linkage::CAM_LINKAGE_TEXT),
    ("HARMONIC_CAM_ROCKER_TEXT", fx::cam_linkage::HARMONIC_CAM_ROCKER_TEXT),
    ("DWELL_CAM_ROCKER_TEXT", fx::cam_linkage::DWELL_CAM_ROCKER_TEXT),
    ("CLASS_FOUR_TEXT", fx::CLASS_FOUR_TEXT),
    ("CLASS_FOUR_CORE_TEXT", fx::CLASS_FOUR_CORE_TEXT),
    ("GEAR_LEVER_TEXT", fx::gear_lever::GEAR_LEVER_TEXT),
    ("FOUR_BAR_TEXT", fx::FOUR_BAR_TEXT),
    ("FOUR_BAR_SENS_TEXT", fx::FOUR_BAR_SENS_TEXT),
    ("SLIDER_CRANK_TEXT", fx::SLIDER_CRANK_TEXT),
    ("FIVE_BAR_TEXT", fx::FIVE_BAR_TEXT),
    ("SLOTTED_LEVER_TEXT", fx::SLOTTED_LEVER_TEXT),
    ("ENGINE_MACHINE_TEXT", fx::ENGINE_MACHINE_TEXT),
    ("FIVE_BAR_MACHINE_TEXT", fx::FIVE_BAR_MACHINE_TEXT),
    ("RHOMBIC_DRIVE_TEXT", fx::RHOMBIC_DRIVE_TEXT),
    ("STIRLING_ENGINE_TEXT", fx::STIRLING_ENGINE_TEXT),
    ("DISPLACER_ROD_DRIVE_TEXT", fx::DISPLACER_ROD_DRIVE_TEXT),
    ("WORKING_ROD_DRIVE_TEXT", fx::WORKING_ROD_DRIVE_TEXT),
    ("ROLLER_EDGER_TEXT", fx::roller_edger::ROLLER_EDGER_TEXT),
];

/// Numbers put in place of one of the text's: signed zeros, the ends of `f64`'s range and
/// beyond it, its subnormals, the names of what is not a number, integers no integer type
/// holds, and numbers with a suffix or separators.
const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "0.0",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "1e309",
    "1e-320",
    "4.9e-324",
    "1e-400",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "infinity",
    "18446744073709551616",
    "340282366920938463463374607431768211456",
    "99999999999999999999999999999999999999999999999999999999999999999999999999999999",
    "1_000_000",
    "1e99999999999",
    "0x10",
    "1f64",
    "2.5e",
];

/// Characters inserted: letters and marks outside ASCII (wide, combining, a byte-order mark, a
/// right-to-left mark, a no-break and an ideographic space, a line separator, a minus sign,
/// full-width digits, a Greek pi), and a NUL.
const UNICODE: &[&str] = &[
    "é", "λ", "π", "°", "😀", "\u{301}", "\u{feff}", "\u{200f}", "\u{a0}", "\u{3000}", "\u{2028}", "\u{2212}", "１",
    "\0", "e\u{301}", "ﬁ",
];

/// How deep a token is nested: past the expressions' limit (128), past the brackets' and
/// far past both.
const DEPTHS: &[usize] = &[129, 257, 10_000];

/// A small deterministic generator (xorshift64*).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// A number in `0..n` (`n > 0`).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// What a token is, as far as the mutations care.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Spaces and line breaks.
    Space,
    /// A `//` comment to the end of its line.
    Comment,
    /// A name or keyword.
    Word,
    /// A number literal.
    Number,
    /// Punctuation (`==` as one).
    Punct,
}

#[derive(Clone, Debug)]
struct Token {
    kind: Kind,
    text: String,
}

/// The tokens of `text`, spaces and comments included, so that joined they give it back.
fn lex(text: &str) -> Vec<Token> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let start = i;
        let kind = if c.is_whitespace() {
            while i < chars.len() && chars[i].is_whitespace() {
                i += 1;
            }
            Kind::Space
        } else if c == '/' && chars.get(i + 1) == Some(&'/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
            Kind::Comment
        } else if c.is_ascii_digit() {
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '.' || chars[i] == '_') {
                // A sign belongs to the number after its exponent's `e`.
                let exponent = matches!(chars[i], 'e' | 'E') && matches!(chars.get(i + 1), Some('+' | '-'));
                i += if exponent { 2 } else { 1 };
            }
            Kind::Number
        } else if c.is_alphabetic() || c == '_' {
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            Kind::Word
        } else {
            i += if c == '=' && chars.get(i + 1) == Some(&'=') { 2 } else { 1 };
            Kind::Punct
        };
        out.push(Token { kind, text: chars[start..i].iter().collect() });
    }
    out
}

fn join(tokens: &[Token]) -> String {
    tokens.iter().map(|t| t.text.as_str()).collect()
}

/// The indices of the tokens that are not spaces, of kind `kind` if given.
fn indices(tokens: &[Token], kind: Option<Kind>) -> Vec<usize> {
    (0..tokens.len()).filter(|&k| tokens[k].kind != Kind::Space && kind.is_none_or(|w| tokens[k].kind == w)).collect()
}

fn token(kind: Kind, text: &str) -> Token {
    Token { kind, text: text.to_string() }
}

/// One edit of `text`, and what it was (for the failure's message).
fn mutate(text: &str, rng: &mut Rng) -> (String, String) {
    let mut t = lex(text);
    let all = indices(&t, None);
    if all.is_empty() {
        return (format!("{text}("), "an opening bracket appended".to_string());
    }
    let at = *rng.pick(&all);
    let said = |what: &str, t: &Token| format!("{what} `{}`", t.text.chars().take(40).collect::<String>());
    let what = match rng.below(12) {
        0 => {
            let w = said("deleted", &t[at]);
            t.remove(at);
            w
        }
        1 => {
            let copy = t[at].clone();
            t.insert(at, token(Kind::Space, " "));
            t.insert(at, copy);
            said("doubled", &t[at])
        }
        2 => {
            // The next token half the time, any other otherwise.
            let other = match all.iter().position(|&k| k == at) {
                Some(p) if rng.below(2) == 0 && p + 1 < all.len() => all[p + 1],
                _ => *rng.pick(&all),
            };
            let w = format!("`{}` and `{}` exchanged", t[at].text, t[other].text);
            t.swap(at, other);
            w
        }
        3..=5 => {
            let numbers = indices(&t, Some(Kind::Number));
            let k = if numbers.is_empty() { at } else { *rng.pick(&numbers) };
            let n = *rng.pick(NUMBERS);
            let w = format!("`{}` replaced by `{n}`", t[k].text);
            t[k] = token(Kind::Number, n);
            w
        }
        6 => {
            let depth = *rng.pick(DEPTHS);
            let closed = rng.below(2) == 0;
            let inner = t[at].text.clone();
            t[at].text =
                format!("{}{inner}{}", "(".repeat(depth), if closed { ")".repeat(depth) } else { String::new() });
            format!("`{inner}` nested {depth} deep{}", if closed { "" } else { ", not closed" })
        }
        7 => {
            t.truncate(at);
            format!("cut short at token {at}")
        }
        8 => {
            let u = *rng.pick(UNICODE);
            // Between tokens, or inside a word.
            let k = if rng.below(2) == 0 { at } else { at + 1 };
            t.insert(k.min(t.len()), token(Kind::Punct, u));
            format!("{u:?} inserted")
        }
        9 => {
            let lines: Vec<&str> = text.split('\n').collect();
            let line = rng.below(lines.len());
            let mut out = lines.clone();
            out.insert(line, lines[line]);
            return (out.join("\n"), format!("line {} repeated", line + 1));
        }
        10 => {
            let other = t[*rng.pick(&all)].clone();
            let w = format!("`{}` replaced by `{}`", t[at].text, other.text);
            t[at] = other;
            w
        }
        _ => {
            let other = t[*rng.pick(&all)].clone();
            let w = said("inserted", &other);
            t.insert(at, token(Kind::Space, " "));
            t.insert(at, other);
            w
        }
    };
    (join(&t), what)
}

/// Every `.kl` file under `dir` (not in build outputs or hidden directories), sorted.
fn kl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        if path.is_dir() {
            if !name.starts_with('.') && name != "target" {
                kl_files(&path, out);
            }
        } else if name.ends_with(".kl") {
            out.push(path);
        }
    }
}

/// The declarations mutated: every `.kl` file of the repository, then the fixtures'.
fn declarations() -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace's root").to_path_buf();
    let mut files = Vec::new();
    kl_files(&root, &mut files);
    files.sort();
    // The command line's shipped files at least: a walk that found none tests nothing.
    assert!(files.len() >= 7, "found only {files:?} under {}", root.display());
    let mut out: Vec<(String, String)> = files
        .iter()
        .map(|p| {
            let name = p.strip_prefix(&root).unwrap_or(p).display().to_string();
            (name, std::fs::read_to_string(p).expect("a .kl file reads"))
        })
        .collect();
    out.extend(FIXTURES.iter().map(|(n, t)| (n.to_string(), t.to_string())));
    out
}

/// What is wrong with a message: nothing (`None`) unless it is empty.
fn said(what: &str, message: String) -> Option<String> {
    message.trim().is_empty().then(|| format!("{what}: an error with an empty message"))
}

/// The first value of `values` that is not finite, named by `what`.
fn non_finite(what: &str, columns: &[(&str, &[f64])]) -> Option<String> {
    for (name, values) in columns {
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Some(format!("{what}: accepted with {name}[{k}] = {}", values[k]));
        }
    }
    None
}

/// Reads `text`; when accepted, solves it at two inputs and sweeps a short stretch. The
/// problems found: an error without a message, a rejection without a place, a result that is
/// not finite.
fn exercise(name: &str, text: &str) -> Vec<String> {
    let mut problems = Vec::new();
    match Model::read(name, text) {
        Ok(m) => run_model(m, &mut problems),
        Err(ReadError::Rejected(d)) => {
            if d.items.is_empty() {
                problems.push("rejected without a diagnostic".to_string());
            }
            for item in &d.items {
                problems.extend(said("rejected", item.message.clone()));
                if item.line == 0 || item.column == 0 || item.range.end > text.len() {
                    problems.push(format!("rejected at no place in the text: {item:?}"));
                }
            }
            problems.extend(said("rendered rejection", d.render(false)));
        }
        Err(e @ ReadError::Unsupported(_)) => problems.extend(said("unsupported", e.to_string())),
    }
    // Nothing read above is kept: the spans of this text may go.
    source::forget_spans();
    problems
}

/// One solve at two inputs and a sweep of five samples of an accepted model, parameters
/// without a default given 1.5 (as `--params` would).
fn run_model(mut m: Model, problems: &mut Vec<String>) {
    let unset: Vec<String> =
        (m.params().iter().zip(m.param_values())).filter(|(_, v)| v.is_none()).map(|(p, _)| p.clone()).collect();
    for p in unset {
        m.set_param(&p, 1.5);
    }
    let ni = m.inputs().len();
    for x in [0.3, 0.0] {
        match m.solve(&vec![x; ni]) {
            Ok(s) => problems.extend(non_finite(
                &format!("solve at {x}"),
                &[("q", &s.q), ("dq", &s.dq), ("d2q", &s.d2q), ("out", &s.out), ("dout", &s.dout), ("d2out", &s.d2out)],
            )),
            Err(e) => problems.extend(said("solve", e.to_string())),
        }
    }
    let (from, to) = (vec![0.3; ni], vec![0.8; ni]);
    let mut guess = vec![0.0; m.unknowns().len()];
    if let Err(e) = m.guess(&from, &mut guess) {
        problems.extend(said("guess", e.to_string()));
        return;
    }
    match m.sweep(&from, &to, 5, &guess) {
        Ok(sweep) => {
            for (k, state) in sweep.enumerate() {
                match state {
                    Ok(s) => problems.extend(non_finite(
                        &format!("sweep sample {k}"),
                        &[("q", &s.q), ("dq", &s.dq), ("d2q", &s.d2q), ("out", &s.out)],
                    )),
                    Err(e) => problems.extend(said("sweep", e.to_string())),
                }
            }
        }
        Err(e) => problems.extend(said("sweep", e.to_string())),
    }
}

/// How a case ended, when it did not end well.
fn run_case(name: &str, text: &str) -> Result<(), String> {
    let (tx, rx) = mpsc::channel();
    let (name, text) = (name.to_string(), text.to_string());
    // A thread of the default size (2 MiB, less than a main thread's 8): what does not
    // overflow it does not overflow a program's reader either.
    std::thread::spawn(move || {
        let run = std::panic::catch_unwind(|| exercise(&name, &text));
        let _ = tx.send(run.map_err(|p| {
            p.downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default()
        }));
    });
    match rx.recv() {
        Ok(Ok(problems)) if problems.is_empty() => Ok(()),
        Ok(Ok(problems)) => Err(problems.join("; ")),
        Ok(Err(panic)) => Err(format!("panicked: {panic}")),
        Err(_) => Err("the case's thread ended without an answer".to_string()),
    }
}

fn env<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name).ok().and_then(|s| s.parse().ok()).unwrap_or(default)
}

#[test]
fn mutated_declarations_are_read_solved_and_swept_or_refused_in_words() {
    let cases: usize = env("KINLOOP_FUZZ_CASES", 100);
    let seed: u64 = env("KINLOOP_FUZZ_SEED", 0x6b69_6e6c_6f6f_7033);
    // Seeds mixed (consecutive ones apart), and never 0, which xorshift never leaves.
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let mut failures = Vec::new();
    for (name, text) in declarations() {
        for case in 0..cases {
            // One to three edits on the same text.
            let (mut t, mut edits) = (text.clone(), Vec::new());
            for _ in 0..=rng.below(3) {
                let (next, what) = mutate(&t, &mut rng);
                t = next;
                edits.push(what);
            }
            let label = format!("{name}, case {case} (seed {seed:#x}): {}", edits.join(", "));
            // A stack overflow aborts the process with no word of the case: left in this file.
            if let Ok(file) = std::env::var("KINLOOP_FUZZ_TRACE") {
                let _ = std::fs::write(file, format!("{label}\n{t}"));
            }
            if let Err(problem) = run_case(&name, &t) {
                failures.push(format!("{label}: {problem}"));
            }
        }
    }
    assert!(failures.is_empty(), "{} of the cases failed:\n{}", failures.len(), failures.join("\n"));
}

/// The lexer gives the text back, and finds the tokens the mutations work on.
#[test]
fn tokens_join_back_into_their_text() {
    for (name, text) in declarations() {
        assert_eq!(join(&lex(&text)), text, "{name}");
    }
    let t = lex("a = 1.5e-3; // x\nb == 2");
    let kinds: Vec<Kind> = t.iter().filter(|t| t.kind != Kind::Space).map(|t| t.kind).collect();
    use Kind::*;
    assert_eq!(kinds, [Word, Punct, Number, Punct, Comment, Word, Punct, Number]);
    assert_eq!(t[4].text, "1.5e-3");
}

/// Parentheses nested 10,000 deep in a text with a letter outside ASCII: refused for their
/// depth, as in an ASCII text, where the identifiers' normalisation (which only a non-ASCII
/// text goes through) recursed once per bracket and overflowed the stack first.
#[test]
fn deep_brackets_in_a_text_outside_ascii_are_refused_for_their_depth() {
    let deep = format!("{}1{}", "(".repeat(10_000), ")".repeat(10_000));
    let text = format!("pub struct S {{ params é = {deep}; input x; unknowns q = 0; eq e: q == é * x; }}");
    // A thread of the default size, as a program's reader may run on.
    let run = std::thread::spawn(move || match Model::read("deep.kl", &text) {
        Err(ReadError::Rejected(d)) => d.items.iter().map(|i| i.message.clone()).collect::<Vec<_>>().join("\n"),
        Ok(_) => "accepted".to_string(),
        Err(e) => e.to_string(),
    });
    let message = run.join().expect("no panic");
    assert!(message.contains("nested more than 256 levels deep"), "{message}");
}
