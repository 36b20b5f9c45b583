//! Diagnostics parity: the declarations of the macro's UI tests (`tests/ui/**/*.rs`, whose
//! compiler output is pinned in the `.stderr` beside each) read at run time give the same
//! messages at the same lines and columns (errors, and the warnings of accepted declarations).
//!
//! Each `mechanism! { ... }` body is read in place: the rest of the file is blanked (newlines
//! kept), so a run-time location is directly comparable with the compiler's. The reference is
//! the compiler's own rendering of the macro's errors in the `.stderr` files; errors there that
//! lie outside every declaration (code using the generated types) are not the reader's and are
//! left out.

use kinloop_model::{Model, ReadError};
use std::path::{Path, PathBuf};

/// One error of a `.stderr`: message (continuation lines joined by newlines), line and column.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct Expected {
    line: usize,
    column: usize,
    message: String,
}

fn errors_of(stderr: &str) -> Vec<Expected> {
    messages_of(stderr, "error: ")
}

/// The warnings the macro makes the compiler print: `use of deprecated associated constant
/// `Name::tag`: message`, of which the message is the macro's.
fn warnings_of(stderr: &str) -> Vec<Expected> {
    messages_of(stderr, "warning: use of deprecated associated constant ")
        .into_iter()
        .filter_map(|e| {
            let (_, message) = e.message.split_once("`: ")?;
            Some(Expected { message: message.to_string(), ..e })
        })
        .collect()
}

fn messages_of(stderr: &str, prefix: &str) -> Vec<Expected> {
    let lines: Vec<&str> = stderr.lines().collect();
    let mut out = Vec::new();
    let mut k = 0;
    while k < lines.len() {
        if let Some(first) = lines[k].strip_prefix(prefix) {
            let mut message = first.to_string();
            k += 1;
            while k < lines.len() && !lines[k].trim_start().starts_with("--> ") {
                if let Some(more) = lines[k].strip_prefix("       ") {
                    message.push('\n');
                    message.push_str(more);
                }
                k += 1;
            }
            if let Some(at) = lines.get(k).and_then(|l| l.trim_start().strip_prefix("--> ")) {
                let mut parts = at.rsplitn(3, ':');
                let column = parts.next().and_then(|c| c.parse().ok()).unwrap_or(0);
                let line = parts.next().and_then(|c| c.parse().ok()).unwrap_or(0);
                out.push(Expected { line, column, message });
            }
        }
        k += 1;
    }
    out
}

/// The byte ranges of the bodies of every `mechanism! { ... }` in `src` (inside the braces).
fn bodies(src: &str) -> Vec<(usize, usize)> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(at) = src[from..].find("mechanism!") {
        let start = from + at + "mechanism!".len();
        let Some(open) = src[start..].find('{').map(|o| start + o) else { break };
        let (mut depth, mut k) = (0usize, open);
        while k < b.len() {
            match b[k] {
                b'{' => depth += 1,
                b'}' => {
                    depth -= 1;
                    if depth == 0 {
                        break;
                    }
                }
                b'"' => {
                    k += 1;
                    while k < b.len() && b[k] != b'"' {
                        k += if b[k] == b'\\' { 2 } else { 1 };
                    }
                }
                b'/' if b.get(k + 1) == Some(&b'/') => {
                    while k < b.len() && b[k] != b'\n' {
                        k += 1;
                    }
                }
                _ => {}
            }
            k += 1;
        }
        out.push((open + 1, k.min(b.len())));
        from = k.min(b.len());
    }
    out
}

/// `src` with everything outside `range` blanked, newlines kept.
fn in_place(src: &str, (from, to): (usize, usize)) -> String {
    src.char_indices().map(|(i, c)| if (from..to).contains(&i) || c == '\n' { c } else { ' ' }).collect()
}

/// `message` without the help the reader adds under an unknown start of token (what to write
/// instead of `−` or `°`): the compiler gives its own apart from the message, after the code
/// (`help: Unicode character ... looks like ...`), or none (`°`), so the message compared with
/// its `error:` line is the line before the help.
fn without_sign_help(message: String) -> String {
    match message.split_once("\nhelp: ") {
        Some((first, _)) if first.starts_with("unknown start of token: ") => first.to_string(),
        _ => message,
    }
}

/// Whether `e` is the compiler's own lexer error for a malformed number (`1e`, `0b102`), given
/// before the macro's error at the same number, which says what is wrong and what to write: the
/// reader's lexer is proc-macro2's, not the compiler's, and it gives the macro's message alone,
/// once. Only where such an error of the macro (`` `1e` is not a number: ... ``) starts on the
/// same line, at or before the lexer's column (the lexer's points at the digit, the macro's at
/// the number).
fn compilers_number_lexer_error(e: &Expected, all: &[Expected]) -> bool {
    let lexer = e.message == "expected at least one digit in exponent"
        || (e.message.starts_with("invalid digit for a base ") && e.message.ends_with(" literal"));
    lexer && all.iter().any(|o| o.line == e.line && o.column <= e.column && o.message.contains("` is not a number: "))
}

fn ui_cases() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/ui");
    let mut out = Vec::new();
    let mut dirs = vec![root];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).expect("tests/ui") {
            let p = e.expect("entry").path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") && p.with_extension("stderr").exists() {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

#[test]
fn ui_declarations_read_at_run_time_give_the_macros_messages() {
    let mut compared = 0;
    let mut cases = 0;
    for case in ui_cases() {
        let src = std::fs::read_to_string(&case).expect("case");
        let stderr = std::fs::read_to_string(case.with_extension("stderr")).expect("stderr");
        let line_of = |byte: usize| src[..byte].matches('\n').count() + 1;
        let spans = bodies(&src);
        if spans.is_empty() {
            continue;
        }
        let inside = |e: &Expected| spans.iter().any(|&(a, b)| (line_of(a)..=line_of(b)).contains(&e.line));
        let mut expected: Vec<Expected> = errors_of(&stderr).into_iter().filter(inside).collect();
        let all = expected.clone();
        expected.retain(|e| !compilers_number_lexer_error(e, &all));
        let mut got = Vec::new();
        let mut expected_warnings: Vec<Expected> = warnings_of(&stderr).into_iter().filter(inside).collect();
        let mut got_warnings = Vec::new();
        for &span in &spans {
            match Model::read(&case.display().to_string(), &in_place(&src, span)) {
                Ok(m) => got_warnings.extend(m.warnings().into_iter().flat_map(|d| {
                    d.items.iter().map(|i| Expected { line: i.line, column: i.column, message: i.message.clone() })
                })),
                Err(ReadError::Unsupported(_)) => {}
                Err(ReadError::Rejected(d)) => got.extend(d.items.into_iter().map(|i| Expected {
                    line: i.line,
                    column: i.column,
                    message: without_sign_help(i.message),
                })),
            }
        }
        expected.sort();
        got.sort();
        assert_eq!(got, expected, "{}", case.display());
        expected_warnings.sort();
        got_warnings.sort();
        assert_eq!(got_warnings, expected_warnings, "{}: warnings", case.display());
        compared += expected.len() + expected_warnings.len();
        cases += 1;
    }
    eprintln!("{cases} UI cases, {compared} messages compared");
    assert!(compared >= 50, "only {compared} messages compared");
}

/// Texts the lexer rejects before the macro sees them (the compiler's lexer would): the
/// mistake named as the compiler names it, at the character that starts it, not the lexer's
/// bare "cannot parse string into token stream".
#[test]
fn texts_the_lexer_rejects_name_the_mistake() {
    let body = "    params a = 1;\n    input phi;\n    unknowns x = 0;\n";
    let cases = [
        (
            format!("pub struct S {{\n{body}    eq e: x == a * phi;\n"),
            "unclosed delimiter: this `{` is never closed",
            1,
            14,
        ),
        (format!("pub struct S {{\n{body}    eq e: x == \"a * phi;\n}}\n"), "unterminated double quote string", 5, 16),
        (
            format!("pub struct S {{\n{body}    eq e: x == a * phi; /* no end\n}}\n"),
            "unterminated block comment",
            5,
            25,
        ),
        (format!("pub struct S {{\n{body}    eq e: x == a ` phi;\n}}\n"), "unknown start of token: `", 5, 18),
        (format!("pub struct S {{\n{body}    eq e: x == a \\ phi;\n}}\n"), "unknown start of token: \\", 5, 18),
        // Words that cannot be raw identifiers, malformed numbers and character literals: what
        // the compiler says, not the lexer's "cannot parse string into token stream".
        (
            "pub struct S {\n    params r#super = 1;\n    input phi;\n    unknowns x = 0;\n    eq e: x == phi;\n}\n"
                .to_string(),
            "`super` cannot be a raw identifier",
            2,
            12,
        ),
        (
            format!("pub struct S {{\n{body}    eq e: x == a * 0b102;\n}}\n"),
            "`0b102` is not a number: `2` is not a digit of a binary number, which has only `0` and `1`",
            5,
            20,
        ),
        (
            format!("pub struct S {{\n{body}    eq e: x == a * 0o78;\n}}\n"),
            "`0o78` is not a number: `8` is not a digit of an octal number, which has only `0` to `7`",
            5,
            20,
        ),
        (
            format!("pub struct S {{\n{body}    eq e: x == a * 'ab';\n}}\n"),
            "unexpected `'`: a declaration has no character literals; write a number or a name",
            5,
            20,
        ),
        // A control character (a bell typed into the file): named, at its place.
        (
            format!("pub struct S {{\n{body}    eq e: x == a *\u{7} phi;\n}}\n"),
            "unknown start of token: \\u{7}: the control character U+0007 has no place in a declaration; remove it",
            5,
            19,
        ),
        // White space in Unicode but not in Rust (a no-break space pasted from a web page, an
        // em space): the compiler refuses them; inside a comment they are text.
        (
            format!("pub struct S {{\n{body}    eq e: x == a\u{a0}* phi; // a\u{a0}b /* c\u{2003} */\n}}\n"),
            "the character U+00A0 is white space in Unicode but not in Rust: replace it with a plain space",
            5,
            17,
        ),
        (
            format!("pub struct S {{\n{body}    /* é\u{a0} /* */ */ eq e: x ==\u{2003}a * phi;\n}}\n"),
            "the character U+2003 is white space in Unicode but not in Rust: replace it with a plain space",
            5,
            30,
        ),
    ];
    for (text, message, line, column) in cases {
        let Err(ReadError::Rejected(d)) = Model::read("lex.kl", &text) else { panic!("accepted: {text}") };
        let got: Vec<(&str, usize, usize)> = d.items.iter().map(|i| (i.message.as_str(), i.line, i.column)).collect();
        assert_eq!(got, [(message, line, column)], "{text}");
    }
}

/// Signs typed or pasted from a document that start no token (a minus sign, a multiplication
/// sign, a degree sign, a superscript, a comparison, curly quotes): named as the compiler names
/// them, with what to write instead in a declaration, not "unknown start of token" alone.
#[test]
fn signs_from_documents_are_told_what_to_write() {
    let body = "    params a = 1;\n    input phi;\n    unknowns x = 0;\n";
    let cases = [
        ("a \u{2212} phi", "\\u{2212}", "`\u{2212}` (U+2212) looks like `-`; write `-`"),
        ("a \u{d7} phi", "\\u{d7}", "`\u{d7}` (U+00D7) looks like `*`; write `*`"),
        ("a \u{b7} phi", "\\u{b7}", "`\u{b7}` (U+00B7) looks like `*`; write `*`"),
        ("a * phi\u{b2}", "\\u{b2}", "`\u{b2}` (U+00B2) is no operator: write a power as `x ^ 2` or `pow(x, 2)`"),
        (
            "a * 30\u{b0}",
            "\\u{b0}",
            "`\u{b0}` (U+00B0) is no operator: write an angle in degrees as `deg(30)` (30 degrees, in radians), or \
             in radians",
        ),
        (
            "a \u{2264} phi",
            "\\u{2264}",
            "`\u{2264}` (U+2264) looks like `<=`; a declaration has no comparisons: an equation is written `lhs == \
             rhs`, a bound with `min`, `max` or `clamp`",
        ),
        (
            "a \u{2265} phi",
            "\\u{2265}",
            "`\u{2265}` (U+2265) looks like `>=`; a declaration has no comparisons: an equation is written `lhs == \
             rhs`, a bound with `min`, `max` or `clamp`",
        ),
        (
            "a \u{2260} phi",
            "\\u{2260}",
            "`\u{2260}` (U+2260) looks like `!=`; a declaration has no comparisons: an equation is written `lhs == \
             rhs`, a bound with `min`, `max` or `clamp`",
        ),
        ("a * \u{201c}phi\u{201d}", "\\u{201c}", "`\u{201c}` (U+201C) looks like `\"`; write `\"`"),
        (
            "a * \u{2018}phi\u{2019}",
            "\\u{2018}",
            "`\u{2018}` (U+2018) looks like `'`; a declaration has no character literals: write `\"` around a text",
        ),
        ("a * \u{221a}phi", "\\u{221a}", "`\u{221a}` (U+221A) is no operator: write a square root as `sqrt(x)`"),
        (
            "a\u{207b}\u{b9} * phi",
            "\\u{207b}",
            "`\u{207b}` (U+207B) is no operator: write a negative power as `x ^ -1` or `pow(x, -1)`, a reciprocal \
             as `1 / x`",
        ),
        ("\u{bd} * a * phi", "\\u{bd}", "`\u{bd}` (U+00BD) is no number: write `1 / 2`"),
        ("a * \u{ff08}phi)", "\\u{ff08}", "`\u{ff08}` (U+FF08) looks like `(`; write `(`"),
    ];
    for (expr, escaped, help) in cases {
        let text = format!("pub struct S {{\n{body}    eq e: x == {expr};\n}}\n");
        let Err(ReadError::Rejected(d)) = Model::read("sign.kl", &text) else { panic!("accepted: {text}") };
        // The column of the sign, in characters, after `    eq e: x == ` (15 of them).
        let column = 16 + expr.chars().position(|c| !c.is_ascii()).expect("a sign");
        let message = format!("unknown start of token: {escaped}\nhelp: {help}");
        let got: Vec<(&str, usize, usize)> = d.items.iter().map(|i| (i.message.as_str(), i.line, i.column)).collect();
        assert_eq!(got, [(message.as_str(), 5, column)], "{text}");
    }
}

/// A name written with a Greek letter, as a paper writes the angle (`φ`), is told the name of the
/// declaration that spells it out, by the reader as by the macro.
#[test]
fn a_greek_letter_is_told_the_name_that_spells_it_out() {
    let text =
        "pub struct S {\n    params a = 1;\n    input phi;\n    unknowns x = 0;\n    eq e: x == a * \u{3c6};\n}\n";
    let Err(ReadError::Rejected(d)) = Model::read("greek.kl", text) else { panic!("accepted: {text}") };
    let got: Vec<(&str, usize, usize)> = d.items.iter().map(|i| (i.message.as_str(), i.line, i.column)).collect();
    let message = "unknown name `\u{3c6}`; did you mean `phi`? (declare it with `params`, `input`, `unknowns` or `let` \
                   before using it)";
    assert_eq!(got, [(message, 5, 20)], "{text}");
}

/// A letter of another script that looks like a Latin one (`а`, U+0430, Cyrillic; a keyboard
/// left on another layout, a name pasted from a document) is named with the letter it looks
/// like, both where it is used and where the name it spells is used instead: the two names print
/// alike, so the macro's "unknown name `а`" beside a declared `a` (or "unknown name `a`"
/// beside a declared `а`) gave the author nothing to change.
#[test]
fn a_letter_that_looks_latin_is_named_with_what_to_write() {
    let said = "`\u{430}` (U+0430) is a Cyrillic letter that looks like the Latin `a`";
    let unknown = |name: &str| {
        format!("unknown name `{name}` (declare it with `params`, `input`, `unknowns` or `let` before using it)")
    };
    let messages = |text: &str| -> Vec<(String, usize, usize)> {
        let Err(ReadError::Rejected(d)) = Model::read("look_alike.kl", text) else { panic!("accepted: {text}") };
        d.items.into_iter().map(|i| (i.message, i.line, i.column)).collect()
    };
    // Used: the letter, and the declared name to write.
    let used =
        "pub struct S {\n    params a = 1;\n    input phi;\n    unknowns x = 0;\n    eq e: x == \u{430} * phi;\n}\n";
    let help = format!("{}\nhelp: {said}; write `a`", unknown("\u{430}"));
    assert_eq!(messages(used), [(help, 5, 16)]);
    // Declared: at each use of the Latin name, the place of the declared one and what to write there.
    let declared =
        "pub struct S {\n    params \u{430} = 1;\n    input phi;\n    unknowns x = 0;\n    eq e: x == a * phi;\n}\n";
    let help = format!("{}\nhelp: `\u{430}` at line 2, column 12 is not `a`: {said}; write `a` there", unknown("a"));
    assert_eq!(messages(declared), [(help, 5, 16)]);
    // A keyword: the letter, and the keyword the message names.
    let keyword = used.replace("\u{430} * phi", "a * phi").replace("eq e", "\u{435}q e");
    let got = messages(&keyword);
    let help = "help: `\u{435}` (U+0435) is a Cyrillic letter that looks like the Latin `e`; write `eq`";
    assert!(got.len() == 1 && got[0].0.ends_with(help) && (got[0].1, got[0].2) == (5, 5), "{got:?}");
}

/// A character most editors do not show (a zero-width space, a byte order mark inside the text,
/// as where two files were joined) is named and removed, not only escaped ("unknown start of
/// token: \u{200b}" under a caret beneath nothing); and a joiner inside a name, which continues
/// it, makes another name that prints as the one meant: the help says what it holds and what to
/// write.
#[test]
fn an_invisible_character_is_named_with_what_to_write() {
    let text = "pub struct S {\n    params a = 1;\n    input phi;\n    unknowns x = 0;\n    eq e: x == a * phi;\n}\n";
    let messages = |text: &str| -> Vec<(String, usize, usize)> {
        let Err(ReadError::Rejected(d)) = Model::read("invisible.kl", text) else { panic!("accepted: {text}") };
        d.items.into_iter().map(|i| (i.message, i.line, i.column)).collect()
    };
    let between = text.replace("a * phi", "a *\u{200b} phi");
    let help =
        "unknown start of token: \\u{200b}\nhelp: U+200B (zero width space) is invisible in most editors: remove it";
    assert_eq!(messages(&between), [(help.to_string(), 5, 19)]);
    // A second byte order mark: the first, which starts the file, is no character of the text
    // and takes no column.
    let twice = format!("\u{feff}\u{feff}{text}");
    let help = "unknown start of token: \\u{feff}\nhelp: U+FEFF (zero width no-break space, the byte order mark) is \
                invisible in most editors: remove it";
    assert_eq!(messages(&twice), [(help.to_string(), 1, 1)]);
    let joined = text.replace("a * phi", "a * ph\u{200d}i");
    let message = "unknown name `ph\u{200d}i`; did you mean `phi`? (declare it with `params`, `input`, `unknowns` or \
                   `let` before using it)\nhelp: the name holds U+200D (zero width joiner), which most editors do not \
                   show; write `phi`";
    assert_eq!(messages(&joined), [(message.to_string(), 5, 20)]);
}

/// A text saved with a byte order mark (as some Windows editors save) is refused at the same
/// lines and columns as without it, on its first line too: the compiler drops the mark before
/// reading and editors give it no column, where the lexer counted it, one column too many. The
/// rendering is the same, a long first line's window and caret included.
#[test]
fn a_byte_order_mark_takes_no_column() {
    let items = |text: &str| -> (Vec<(String, usize, usize)>, String) {
        let Err(ReadError::Rejected(d)) = Model::read("bom.kl", text) else { panic!("accepted: {text}") };
        (d.items.iter().map(|i| (i.message.clone(), i.line, i.column)).collect(), d.render(false))
    };
    let long = format!("pub strukt S {{ params a = 1; {} }}", "let x = a; ".repeat(20));
    for text in [
        // The front end's message at a name, the lexer's at a bracket, the reader's at a space.
        "pub strukt S {\n}\n".to_string(),
        "pub struct S { params a = (1; }".to_string(),
        "pub struct S {\u{a0}params a = 1; }".to_string(),
        "pub struct S {\n    params a = 1;\n    input phi;\n    unknowns x = 0;\n    eq e: x == b * phi;\n}\n"
            .to_string(),
        long,
    ] {
        let (plain, plain_render) = items(&text);
        let (marked, marked_render) = items(&format!("\u{feff}{text}"));
        assert_eq!(marked, plain, "{text}");
        assert_eq!(marked_render.replace("\u{feff}", ""), plain_render, "{text}");
    }
    assert_eq!(items("\u{feff}pub strukt S {\n}\n").0[0].2, 5);
}

/// A declaration written on one long line (generated, or a table named by mistake) is shown
/// around the place of each mistake, not whole: the rendering stays a few lines long, with
/// the line and column of the whole text and the caret under the name.
#[test]
fn a_long_line_is_shown_around_the_mistake() {
    let pad = format!("/* {} */", "long ".repeat(20_000));
    let text = format!("pub struct S {{ params a = 1; {pad} input phi; unknowns x = 0; eq e: x == a * phy; {pad} }}");
    let column = text.find("phy").unwrap() + 1;
    let Err(ReadError::Rejected(d)) = Model::read("long.kl", &text) else { panic!("accepted") };
    let shown = d.render(false);
    assert!(shown.len() < 1000, "{} bytes:\n{}", shown.len(), &shown[..shown.len().min(2000)]);
    assert!(shown.contains("error: unknown name `phy`"), "{shown}");
    assert!(shown.contains(&format!("long.kl:1:{column}")), "{shown}");
    // The caret under the name: as many columns in as the name on the line above.
    let lines: Vec<&str> = shown.lines().collect();
    let k = lines.iter().position(|l| l.contains("a * phy")).expect("the line shown");
    let at = lines[k].find("phy").expect("the name shown");
    let caret = lines[k + 1];
    assert_eq!(caret.chars().count(), lines[k][..at].chars().count() + 3, "{shown}");
    assert!(caret.ends_with("^^^"), "{shown}");
    // A short line keeps the compiler's rendering.
    let Err(ReadError::Rejected(d)) =
        Model::read("short.kl", "pub struct S { params a = 1; input phi; unknowns x = 0; eq e: x == a * phy; }")
    else {
        panic!("accepted")
    };
    assert!(d.render(false).contains("eq e: x == a * phy; }"), "{}", d.render(false));
}

/// A name is read in Unicode Normalization Form C, as the compiler reads identifiers: written
/// with a precomposed letter (`é`, U+00E9) in one place and with a base letter and a combining
/// mark (`e`, U+0301) in another, it is one name. (The UI test `duplicate_name_in_normal_form`
/// pins the compiler's reading: the two forms declared twice are one name declared twice, and
/// the parity test above reads it at run time with the same message and place.)
#[test]
fn a_name_written_with_a_combining_mark_is_its_precomposed_name() {
    let text = |declared: &str, used: &str| {
        format!(
            "pub struct S {{\n    params r = 1, {declared} = 3, e = 0.5;\n    input phi;\n    unknowns psi = 0, x = 4;\n    \
             loop oab: r @ phi == (x, e) + {used} @ psi;\n}}\n"
        )
    };
    let composed = "l\u{e9}";
    let decomposed = "le\u{301}";
    let mut reference = Model::read("composed.kl", &text(composed, composed)).unwrap();
    for (declared, used) in [(composed, decomposed), (decomposed, composed), (decomposed, decomposed)] {
        let mut m = Model::read("mixed.kl", &text(declared, used)).unwrap_or_else(|e| panic!("{declared} {used}: {e}"));
        assert_eq!(m.params(), ["r", composed, "e"]);
        let (got, want) = (m.solve(&[0.7]).unwrap().q.clone(), reference.solve(&[0.7]).unwrap().q.clone());
        assert_eq!(got, want, "{declared} {used}");
    }
    // A raw identifier too.
    let raw = text(composed, &format!("r#{decomposed}"));
    assert_eq!(Model::read("raw.kl", &raw).unwrap().params(), ["r", composed, "e"]);
}

/// A string (the text of a `#[doc = "..."]`, what a doc comment is written as) is text to the
/// white-space check, as to the compiler: a no-break space in it is accepted, as `mechanism!`
/// accepts it, and a `//` or `/*` in it starts no comment that would hide a no-break space
/// after the string from the check (the compiler refuses that one).
#[test]
fn strings_are_text_to_the_white_space_check() {
    let text = |doc: &str, after: &str| {
        format!(
            "pub struct S {{\n    params a = 1;\n    input phi;\n    unknowns x = 0;\n    eq e: x == a * phi;\n    \
             #[doc = {doc}]\n    point p = (x, a);{after}\n}}\n"
        )
    };
    let strings = ["\"crank\u{a0}pin\"", "\"a // b\"", "\"a /* b\"", "\"a \\\" /* b\"", "r#\"a \" /* b\"#"];
    for doc in strings {
        let accepted = text(doc, "");
        // The macro's own front end over the same tokens: the reference.
        let tokens: proc_macro2::TokenStream = accepted.parse().expect("tokens");
        assert!(kinloop_codegen::analyze(tokens).is_ok(), "the macro refuses {doc}");
        if let Err(e) = Model::read("doc.kl", &accepted) {
            panic!("{doc}: {e}");
        }
    }
    for doc in &strings[1..] {
        let Err(ReadError::Rejected(d)) = Model::read("doc.kl", &text(doc, " \u{a0}")) else {
            panic!("accepted: {doc}")
        };
        let got: Vec<(&str, usize, usize)> = d.items.iter().map(|i| (i.message.as_str(), i.line, i.column)).collect();
        let message = "the character U+00A0 is white space in Unicode but not in Rust: replace it with a plain space";
        assert_eq!(got, [(message, 7, 23)], "{doc}");
    }
}

/// A closing bracket of another kind than the one it closes (`(d, 0]`): the opening bracket is
/// named with the closing one and the fix (as the compiler's "mismatched closing delimiter", at
/// the opening bracket), not "unexpected closing delimiter" at the `]` alone. A `[` opens no
/// vector: it is not offered.
#[test]
fn a_mismatched_closing_bracket_names_the_one_it_closes() {
    let text = |vector: &str| {
        format!(
            "pub struct S {{\n    params a = 1, d = 3;\n    input phi;\n    unknowns psi = 0, x = 2;\n    \
             loop l: a @ phi == {vector} + 2 @ psi;\n}}\n"
        )
    };
    let cases = [
        (
            "(x, d]",
            "mismatched closing delimiter: this `(` is closed by the `]` at line 5, column 29: close it with `)`",
            5,
            24,
        ),
        (
            "[x, d)",
            "mismatched closing delimiter: this `[` is closed by the `)` at line 5, column 29: close it with `]`, or open it with `(`",
            5,
            24,
        ),
        (
            "((x, d)]",
            "mismatched closing delimiter: this `(` is closed by the `]` at line 5, column 31: close it with `)`",
            5,
            24,
        ),
    ];
    for (vector, message, line, column) in cases {
        let Err(ReadError::Rejected(d)) = Model::read("bracket.kl", &text(vector)) else {
            panic!("accepted: {vector}")
        };
        let got: Vec<(&str, usize, usize)> = d.items.iter().map(|i| (i.message.as_str(), i.line, i.column)).collect();
        assert_eq!(got, [(message, line, column)], "{vector}");
    }
    // A closing bracket inside the declaration's block alone, or after it, is still unexpected,
    // where it is (the compiler's words for one in a function's body).
    let inside = text("(x, d)").replace("\n}", "\n    ]\n}");
    let after = format!("{})", text("(x, d)"));
    for (stray, message, line, column) in
        [(inside, "unexpected closing delimiter: `]`", 6, 5), (after, "unexpected closing delimiter: `)`", 7, 1)]
    {
        let Err(ReadError::Rejected(d)) = Model::read("bracket.kl", &stray) else { panic!("accepted: {stray}") };
        let got: Vec<(&str, usize, usize)> = d.items.iter().map(|i| (i.message.as_str(), i.line, i.column)).collect();
        assert_eq!(got, [(message, line, column)], "{stray}");
    }
}

/// A polar term with its length and angle swapped (`psi @ l`, where `psi` turns the rod in the
/// point) is refused in a `.kl` file as by the macro: at the term, saying what to write.
#[test]
fn a_swapped_polar_term_is_refused_at_run_time() {
    let text = "pub struct SliderCrank {\n    params r = 1, l = 3, e = 0.5;\n    input phi;\n    unknowns psi, x = 3;\n    \
                loop oab: r @ phi == (x, e) + psi @ l;\n    point mid = r @ phi + 0.5 * l @ psi;\n    \
                output lean = sin(psi);\n}\n";
    let Err(ReadError::Rejected(d)) = Model::read("swap.kl", text) else { panic!("accepted: {text}") };
    let got: Vec<(usize, usize)> = d.items.iter().map(|i| (i.line, i.column)).collect();
    assert_eq!(got, [(5, 35)], "{d}");
    assert!(d.items[0].message.starts_with("`psi` is an angle"), "{d}");
    assert!(d.items[0].message.ends_with("write `l @ psi`"), "{d}");
}

/// The head of a slider-crank whose unknown `y` an `eq` sets to twice the rod's angle, `psi`:
/// the next item starts at line 7.
const SET_TO_AN_ANGLE: &str = "pub struct SliderCrank {\n    params r = 1, l = 3;\n    input phi;\n    \
                               unknowns psi, x = 3, y;\n    loop oab: r @ phi == (x, 0) + l @ psi;\n    \
                               eq double: y == 2 * psi;\n";

/// The one error of `SET_TO_AN_ANGLE` and then `tail`: its line and column, and its message.
fn one_error(tail: &str) -> ((usize, usize), String) {
    let text = format!("{SET_TO_AN_ANGLE}{tail}}}\n");
    let Err(ReadError::Rejected(d)) = Model::read("mix.kl", &text) else { panic!("accepted: {text}") };
    assert_eq!(d.items.len(), 1, "{d}");
    ((d.items[0].line, d.items[0].column), d.items[0].message.clone())
}

/// A vector of an angle and a length given to `norm` or `dot` (`(x, psi)`, `(x, 0) + (0, psi)`)
/// is refused in a `.kl` file as by the macro: at the vector, saying that it combines the two.
#[test]
fn a_vector_of_an_angle_and_a_length_is_refused_at_run_time() {
    for (tail, at, says) in [
        ("    output reach = norm((x, psi));\n", (7, 25), "`(x, psi)` combines an angle and a length"),
        ("    output along = dot((x, 0) + (0, psi), (1, 0));\n", (7, 24), "`(x, 0) + (0, psi)` combines an angle"),
    ] {
        let (got, message) = one_error(tail);
        assert_eq!(got, at, "{message}");
        assert!(message.starts_with(says), "{message}");
    }
    let fine = format!("{SET_TO_AN_ANGLE}    output reach = norm((x, l));\n    output turn = norm((phi, psi));\n}}\n");
    assert!(Model::read("fine.kl", &fine).is_ok(), "{fine}");
}

/// An unknown that an `eq` sets to an angle (`y == 2 * psi`) is refused beside a length in a
/// `.kl` file as by the macro, and read as it was beside an angle.
#[test]
fn an_unknown_an_eq_sets_to_an_angle_is_one_at_run_time() {
    let (at, message) = one_error("    output w = y + x;\n");
    assert_eq!(at, (7, 16), "{message}");
    assert!(message.starts_with("`y + x` adds an angle and a length"), "{message}");
    let fine = format!("{SET_TO_AN_ANGLE}    output turn = y + phi;\n}}\n");
    assert!(Model::read("fine.kl", &fine).is_ok(), "{fine}");
}

/// The angle of a polar term that an `eq` sets to an angle (`y` in `phi @ y`) is an angle in a
/// `.kl` file as by the macro: swapping the term cannot help, and it is not told to.
#[test]
fn the_angle_of_a_term_an_eq_sets_to_an_angle_is_no_swap_at_run_time() {
    let (_, message) = one_error("    point p = phi @ y;\n");
    assert!(message.starts_with("`phi` is an angle"), "{message}");
    assert!(message.contains("`y` is an angle too, so swapping the two cannot help"), "{message}");
}

/// A slider-crank whose loop ends in `first` and whose point `p` ends in `second`, with `more`
/// on a line of its own: the two terms start at line 5, column 35, and line 6, column 24.
fn two_terms(first: &str, second: &str, more: &str) -> String {
    format!(
        "pub struct SliderCrank {{\n    params r = 1, l = 3, e = 0.5, th = 0.2;\n    input phi;\n    unknowns psi, x = 3;\n    \
         loop oab: r @ phi == (x, e) + {first};\n    point p = (x, 0) + {second};\n    {more}\n}}\n"
    )
}

/// Two polar terms of two names in opposite roles, bare or expressions, are judged at run time
/// as by the macro: a tie at the first where nothing else tells which name is the length (a bare
/// term beside an expression too), else the wrong term alone, in either order, whatever tells
/// (a sine, a coordinate); and one swap that mends two terms is the one error.
#[test]
fn polar_terms_in_opposite_roles_are_judged_at_run_time_as_by_the_macro() {
    let (at_loop, at_point) = ((5, 35), (6, 24));
    let tie = "nothing else in the mechanism tells which is the length";
    for (first, second, more, at, told) in [
        ("l @ psi", "(2 * psi) @ l", "", at_loop, tie),
        ("(2 * psi) @ l", "l @ psi", "", at_loop, tie),
        ("l @ psi", "psi @ l", "point q = (x, 0) + psi @ l; point w = l @ psi;", at_loop, tie),
        ("0.5 * l @ psi", "(2 * psi) @ l", "output lean = sin(psi);", at_point, "write `l @ (2 * psi)`"),
        ("(2 * psi) @ l", "0.5 * l @ psi", "output lean = sin(psi);", at_loop, "write `l @ (2 * psi)`"),
        ("l @ psi", "psi @ l", "point q = (x, 2 * l);", at_point, "write `l @ psi`"),
        ("psi @ l", "l @ psi", "point q = (x, 2 * l);", at_loop, "write `l @ psi`"),
        ("psi @ l", "th @ psi", "output lean = sin(th);", at_point, "write `psi @ th`"),
        ("th @ psi", "psi @ l", "output lean = sin(th);", at_loop, "write `psi @ th`"),
    ] {
        let text = two_terms(first, second, more);
        let Err(ReadError::Rejected(d)) = Model::read("opposite.kl", &text) else { panic!("accepted: {text}") };
        let got: Vec<(usize, usize)> = d.items.iter().map(|i| (i.line, i.column)).collect();
        assert_eq!(got, [at], "{text}\n{d}");
        assert!(d.items[0].message.contains(told), "{text}\n{d}");
    }
}

/// `beta @ beta`, one name as the length and the angle, is told to write a length, as by the
/// macro, not to swap the two (which writes the same term).
#[test]
fn a_term_of_one_name_as_length_and_angle_is_told_a_length_at_run_time() {
    let text = "pub struct S {\n    params a, c, d;\n    input phi;\n    unknowns beta, gamma;\n    \
                loop abcd: a @ phi + beta @ beta == (d, 0) + c @ gamma;\n}\n";
    let Err(ReadError::Rejected(d)) = Model::read("same.kl", text) else { panic!("accepted: {text}") };
    let got: Vec<(usize, usize)> = d.items.iter().map(|i| (i.line, i.column)).collect();
    assert_eq!(got, [(5, 26)], "{d}");
    assert!(d.items[0].message.contains("swapping the two cannot help; write a length there"), "{d}");
}

/// A loop closed with a negated zero (`== -0`) is read as the loop closed with `== 0`, as the
/// macro reads it: the negated zero vector is the zero vector (it was refused as a scalar
/// facing a vector).
#[test]
fn a_loop_closed_with_a_negated_zero_is_read_as_with_zero() {
    let text = |zero: &str| {
        format!(
            "pub struct FourBar {{\n    params a = 1, b = 3, c = 2.5, d = 3.2;\n    input phi;\n    unknowns beta = \
             0.5, gamma = 1.5;\n    loop abcd: a @ phi + b @ beta - (d, 0) - c @ gamma == {zero};\n}}\n"
        )
    };
    let mut zero = Model::read("zero.kl", &text("0")).unwrap_or_else(|e| panic!("{e:?}"));
    let want = zero.solve(&[0.7]).expect("solved").clone();
    for negated in ["-0", "(-0)", "-(0)"] {
        let mut model = Model::read("negated.kl", &text(negated)).unwrap_or_else(|e| panic!("{negated}: {e:?}"));
        let got = model.solve(&[0.7]).expect("solved");
        assert_eq!((&got.q, &got.dq, &got.out), (&want.q, &want.dq, &want.out), "{negated}");
    }
}

/// An inner doc comment is named as it was written: a block one, `/*! ... */`, was called
/// "`//!`", a comment the text does not have. (The `//!` of a line keeps its name.)
#[test]
fn an_inner_block_doc_comment_is_named_as_written() {
    let body = "    params a = 1;\n    input phi;\n    unknowns x = 0;\n    eq e: x == a * phi;\n}\n";
    let cases = [("/*! A lever. */", "`/*! ... */`"), ("//! A lever.", "`//!`")];
    for (comment, named) in cases {
        let text = format!("pub struct S {{\n    {comment}\n{body}");
        let Err(ReadError::Rejected(d)) = Model::read("doc.kl", &text) else { panic!("accepted: {text}") };
        let got: Vec<(&str, usize, usize)> = d.items.iter().map(|i| (i.message.as_str(), i.line, i.column)).collect();
        let message = format!(
            "an inner doc comment ({named}) is not accepted in a declaration; document the mechanism or an item with \
             `///` before it, or write a plain comment with `//`"
        );
        assert_eq!(got, [(message.as_str(), 2, 5)], "{text}");
    }
}
