//! Declaration text read at run time: its tokens (with line and column), and the diagnostics of
//! the macro's own checks rendered over it with a caret.
//!
//! The text is the language inside `mechanism! { ... }` (a `.kl` file holds one declaration).
//! It is turned into a `proc_macro2::TokenStream` by proc-macro2's own lexer, which outside a
//! compiler keeps a source map of every text it lexed: each token's span then knows its line,
//! column and byte range, and the macro's errors (`syn::Error`, at the user's span) come back
//! here exactly as the compiler would place them.

use codespan_reporting::diagnostic::{Diagnostic as Report, Label};
use codespan_reporting::files::SimpleFile;
use codespan_reporting::term::{self, Config};
use proc_macro2::TokenStream;
use std::fmt;
use std::ops::Range;

/// The largest text read (bytes). The front end bounds the tokens and their nesting
/// (`kinloop_codegen`'s limits, 100 000 tokens); this bounds the memory the lexer takes before
/// those limits are checked. A large mechanism's declaration is a few kilobytes.
pub const MAX_SOURCE_BYTES: usize = 1 << 20;

/// One message of a rejected declaration, at a place in its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// The message, as `mechanism!` reports it. Where a character starts no token (`−`, `°`),
    /// its first line is the compiler's and a `help:` line after it says what to write: the
    /// compiler prints its own help apart from the message; for a character most editors do
    /// not show (a zero-width space, a byte order mark inside the text), the help names it. So
    /// does a `help:` line after a message at a name that holds, or whose look-alike holds,
    /// letters of another script that look like Latin ones (`а`, U+0430, for `a`) or a joiner
    /// no editor shows: which characters, and what to write.
    pub message: String,
    /// Byte range in the text (empty when the message is about the whole text).
    pub range: Range<usize>,
    /// Line of the start, from 1.
    pub line: usize,
    /// Column of the start, from 1, in characters (as the compiler counts them).
    pub column: usize,
}

/// The macro's message `message` said for a declaration read as text: the words about the
/// macro's invocation and the Rust types it generates (which a `.kl` file has neither of) in
/// terms of the text.
fn for_text(message: String) -> String {
    const SAID: [(&str, &str); 4] = [
        (
            "; declare one mechanism per `mechanism!`",
            "; a declaration read as text (a `.kl` file) holds one mechanism: put each in a file of its own",
        ),
        (
            "it is the type parameter of the generated types (`NameInputs<T>`, ...)",
            "`mechanism!` uses it for the type parameter of the Rust types it generates, so the same declaration \
             would not compile there",
        ),
        (
            "that the generated code refers to",
            "that the Rust code `mechanism!` generates refers to, so the same declaration would not compile there",
        ),
        (
            "that the generated code uses",
            "that the Rust code `mechanism!` generates uses, so the same declaration would not compile there",
        ),
    ];
    SAID.iter().fold(message, |m, (macro_words, text_words)| m.replace(macro_words, text_words))
}

/// How serious a set of messages is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    /// The declaration is rejected.
    Error,
    /// The declaration is accepted; something in it is probably a mistake (an unused parameter).
    Warning,
}

/// Messages about a declaration, in order, with the text they point into: why it was rejected,
/// or (level [`Level::Warning`]) what in an accepted one looks wrong.
#[derive(Clone, Debug)]
pub struct Diagnostics {
    /// Errors or warnings.
    pub level: Level,
    /// The name the text is shown under (a file name).
    pub name: String,
    /// The declaration's text.
    pub text: String,
    /// The messages.
    pub items: Vec<Diagnostic>,
}

impl Diagnostics {
    /// One message about the whole text (its first line).
    fn whole(name: &str, text: &str, message: String) -> Diagnostics {
        let items = vec![Diagnostic { message, range: 0..0, line: 1, column: 1 }];
        Diagnostics { level: Level::Error, name: name.to_string(), text: text.to_string(), items }
    }

    /// The messages of a `syn::Error` (it holds several when the macro found several mistakes),
    /// each at its span, for the declaration whose tokens are `tokens`. A message at a name
    /// that holds letters of another script looking like Latin ones (`а`, U+0430, Cyrillic, for
    /// `a`) or a character no editor shows (a zero width joiner), or at a name whose look-alike
    /// is declared instead (`a` used, `а` declared), gets a `help:` line naming those characters
    /// and what to write ([`LookAlikes::help`]): the two names print alike, so "unknown name
    /// `a`" beside a declared `а` left the author nothing to see.
    pub(crate) fn from_syn(name: &str, text: &str, error: syn::Error, tokens: &TokenStream) -> Diagnostics {
        // An ASCII text (nearly every one) has no name that reads as another.
        let names = if text.is_ascii() { Vec::new() } else { names(text, tokens) };
        let look_alikes = LookAlikes::of(&names);
        let items = error
            .into_iter()
            .map(|e| {
                let mut d = at_span(text, e.span(), e.to_string());
                if let Some(help) = look_alikes.help(&d) {
                    d.message = format!("{}\nhelp: {help}", d.message);
                }
                d
            })
            .collect();
        Diagnostics { level: Level::Error, name: name.to_string(), text: text.to_string(), items }
    }

    /// The messages as said to the author of a declaration read as text (a `.kl` file): those
    /// that speak of the macro's invocation (`one mechanism per mechanism!`) or of the Rust
    /// types it generates (`NameInputs<T>`) in the terms of the text. [`Model::read`] gives the
    /// macro's own words (the same as the compiler's for the same declaration); a program that
    /// shows them to the author of a file calls this.
    ///
    /// [`Model::read`]: crate::Model::read
    pub fn for_text(mut self) -> Diagnostics {
        for item in &mut self.items {
            item.message = for_text(std::mem::take(&mut item.message));
        }
        self
    }

    /// The warnings of an accepted declaration (`None` when there are none).
    pub(crate) fn warnings(name: &str, text: &str, warnings: &[kinloop_codegen::diag::Warning]) -> Option<Diagnostics> {
        let items: Vec<Diagnostic> = warnings.iter().map(|w| at_span(text, w.span, w.message.clone())).collect();
        (!items.is_empty()).then(|| Diagnostics {
            level: Level::Warning,
            name: name.to_string(),
            text: text.to_string(),
            items,
        })
    }

    /// The messages rendered as the compiler shows them: `error: message`, the file, line and
    /// column, and the line of text with a caret under the span. `color` adds terminal colours.
    ///
    /// A line longer than [`SHOWN_LINE`] characters (a declaration written on one line, a
    /// generated one) is shown as a window around the place, marked `…` where cut: the whole
    /// line would repeat up to the megabyte of the text for every message.
    pub fn render(&self, color: bool) -> String {
        // A byte order mark starting the text is no character of it (see `at_span`): the file
        // shown is the text after it, each range moved back by its length.
        let skip = if self.text.starts_with(BOM) { BOM.len_utf8() } else { 0 };
        let file = SimpleFile::new(self.name.as_str(), &self.text[skip..]);
        let config = Config::default();
        let mut out = Vec::new();
        for d in &self.items {
            if let Some(window) = self.window(d) {
                out.extend(window.bytes());
                continue;
            }
            let report = match self.level {
                Level::Error => Report::error(),
                Level::Warning => Report::warning(),
            };
            let range = d.range.start.saturating_sub(skip)..d.range.end.saturating_sub(skip);
            let report = report.with_message(&d.message).with_labels(vec![Label::primary((), range)]);
            let written = if color {
                let mut w = term::termcolor::Ansi::new(&mut out);
                term::emit(&mut w, &config, &file, &report)
            } else {
                let mut w = term::termcolor::NoColor::new(&mut out);
                term::emit(&mut w, &config, &file, &report)
            };
            if written.is_err() {
                // Rendering into memory fails only on a range outside the text: the plain form.
                out.extend(
                    format!(
                        "{}: {}\n --> {}:{}:{}\n",
                        if self.level == Level::Error { "error" } else { "warning" },
                        d.message,
                        self.name,
                        d.line,
                        d.column
                    )
                    .bytes(),
                );
            }
        }
        String::from_utf8_lossy(&out).into_owned()
    }
}

/// The most characters of a line a rendered diagnostic shows (see [`Diagnostics::render`]).
pub const SHOWN_LINE: usize = 160;

/// Characters shown before the place of a mistake on a line longer than [`SHOWN_LINE`].
const SHOWN_BEFORE: usize = 60;

impl Diagnostics {
    /// `d` rendered as the compiler shows it, its line cut to a window of [`SHOWN_LINE`]
    /// characters around the place; `None` where the line is short enough to show whole.
    fn window(&self, d: &Diagnostic) -> Option<String> {
        let text = self.text.as_str();
        let start = d.range.start.min(text.len());
        let mut line_start = text[..start].rfind('\n').map_or(0, |k| k + 1);
        // A byte order mark starting the text is no character of its first line (`at_span`):
        // not shown, and not counted before the caret.
        if line_start == 0 && start >= BOM.len_utf8() && text.starts_with(BOM) {
            line_start = BOM.len_utf8();
        }
        let line_end = text[start..].find('\n').map_or(text.len(), |k| start + k);
        let line = text[line_start..line_end].trim_end_matches('\r');
        let chars = line.chars().count();
        if chars <= SHOWN_LINE {
            return None;
        }
        // In characters of the line: the place, the span's end on it, the window.
        let at = text[line_start..start].chars().count();
        let end = at + text[start..d.range.end.clamp(start, line_end)].chars().count();
        let from = at.saturating_sub(SHOWN_BEFORE);
        let to = (from + SHOWN_LINE).min(chars);
        let shown: String = line.chars().skip(from).take(to - from).collect();
        let (cut_before, cut_after) = (if from > 0 { "…" } else { "" }, if to < chars { "…" } else { "" });
        let caret = " ".repeat(at - from + cut_before.chars().count()) + &"^".repeat((end.min(to) - at).max(1));
        let level = if self.level == Level::Error { "error" } else { "warning" };
        let number = d.line.to_string();
        let pad = " ".repeat(number.len());
        Some(format!(
            "{level}: {}\n{pad} ┌─ {}:{}:{}\n{pad} │\n{number} │ {cut_before}{shown}{cut_after}\n{pad} │ {caret}\n\n",
            d.message, self.name, d.line, d.column
        ))
    }
}

impl fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render(false))
    }
}

impl std::error::Error for Diagnostics {}

/// The diagnostic of `message` at `span` of `text`.
fn at_span(text: &str, span: proc_macro2::Span, message: String) -> Diagnostic {
    let start = span.start();
    let range = span.byte_range();
    // A span from another text (never made here) or past the end: the whole text.
    let range = if range.start <= range.end && range.end <= text.len() { range } else { 0..0 };
    // A byte order mark starting the text is no character of its first line: the compiler
    // drops it before reading, and editors show no column for it. proc-macro2's lexer skips it
    // but counts it, one column too many on line 1.
    let bom = usize::from(start.line <= 1 && start.column > 0 && text.starts_with(BOM));
    Diagnostic { message, range, line: start.line.max(1), column: start.column + 1 - bom }
}

/// The byte order mark, which may start a text (see [`at_span`]).
const BOM: char = '\u{feff}';

/// A name of a declaration's text at one place.
struct Name {
    /// The name, in Unicode Normalization Form C (as the front end reads it).
    name: String,
    /// Where it is written.
    place: Diagnostic,
}

/// Every name (identifier) of `tokens`, the tokens of `text`, at each of its places, in the
/// order of the tokens. Without recursion, as [`nfc_identifiers`]: the brackets of a rejected
/// text may nest as deep as the text allows.
fn names(text: &str, tokens: &TokenStream) -> Vec<Name> {
    use proc_macro2::TokenTree;
    let mut out = Vec::new();
    let mut stack = vec![tokens.clone().into_iter()];
    while let Some(top) = stack.last_mut() {
        match top.next() {
            Some(TokenTree::Group(group)) => stack.push(group.stream().into_iter()),
            Some(TokenTree::Ident(ident)) => {
                out.push(Name { name: ident.to_string(), place: at_span(text, ident.span(), String::new()) })
            }
            Some(_) => {}
            None => {
                stack.pop();
            }
        }
    }
    out
}

/// The names of a rejected text that read as others, found once for all its messages.
struct LookAlikes<'a> {
    /// Every name at each of its places, in the order of the text.
    names: &'a [Name],
    /// The names holding characters that make them read as another: each, as it reads
    /// (`confusables::latin_name`), and what those characters are. Empty in nearly every text.
    reading: Vec<(&'a Name, String, String)>,
    /// The names as written, where `reading` is not empty.
    written: std::collections::HashSet<&'a str>,
}

impl<'a> LookAlikes<'a> {
    fn of(names: &'a [Name]) -> LookAlikes<'a> {
        let reading: Vec<(&Name, String, String)> = names
            .iter()
            .filter(|n| !n.name.is_ascii())
            .filter_map(|n| crate::confusables::latin_name(&n.name).map(|(latin, said)| (n, latin, said)))
            .collect();
        let written = if reading.is_empty() { Default::default() } else { names.iter().map(|n| &*n.name).collect() };
        LookAlikes { names, reading, written }
    }

    /// The help for a message `d` that points at exactly one of the text's names, where that
    /// name holds letters that look like Latin ones or characters no editor shows (what they
    /// are, and the name as it reads to write, where the text or the message has it), or where
    /// another name of the text reads as this one but for such characters (that name's place,
    /// and what to write there). `None` otherwise: most messages, and every one of an ASCII
    /// text.
    fn help(&self, d: &Diagnostic) -> Option<String> {
        if self.reading.is_empty() || d.range.is_empty() {
            return None;
        }
        // The names are in the order of the text: the one at the message's place, if any.
        let k = self.names.partition_point(|n| n.place.range.start < d.range.start);
        let here = self.names.get(k).filter(|n| n.place.range == d.range)?;
        if let Some((_, latin, said)) = self.reading.iter().find(|(n, ..)| n.name == here.name) {
            let known = self.written.contains(latin.as_str()) || d.message.contains(&format!("`{latin}`"));
            return Some(if known { format!("{said}; write `{latin}`") } else { said.clone() });
        }
        let (other, _, said) = self.reading.iter().find(|(_, latin, _)| *latin == here.name)?;
        Some(format!(
            "`{}` at line {}, column {} is not `{}`: {said}; write `{}` there",
            other.name, other.place.line, other.place.column, here.name, here.name
        ))
    }
}

/// The tokens of a declaration's text, or why it has none: too large, or a lexical error
/// (an unclosed bracket or string) at its place. `name` names the text in diagnostics.
pub fn tokens(name: &str, text: &str) -> Result<TokenStream, Diagnostics> {
    if text.len() > MAX_SOURCE_BYTES {
        let message = format!(
            "the declaration has {} bytes, more than the {MAX_SOURCE_BYTES} a text read at run time may have",
            text.len()
        );
        return Err(Diagnostics::whole(name, text, message));
    }
    if let Some(d) = foreign_character(text) {
        return Err(Diagnostics {
            level: Level::Error,
            name: name.to_string(),
            text: text.to_string(),
            items: vec![d],
        });
    }
    let lexed = text.parse::<TokenStream>().map_err(|e| {
        let mut d = at_span(text, e.span(), String::new());
        d.message = lex_message(&text[d.range.start..], &e);
        if let Some(open) = unclosed_before(text, &d).or_else(|| mismatched_before(text, &d)) {
            d = open;
        }
        Diagnostics { level: Level::Error, name: name.to_string(), text: text.to_string(), items: vec![d] }
    })?;
    // An ASCII text (nearly every one) has nothing to normalise.
    Ok(if text.is_ascii() { lexed } else { nfc_identifiers(lexed) })
}

/// `tokens` with every identifier in Unicode Normalization Form C, each at its own span, as
/// the compiler reads identifiers: a name written with a precomposed letter (`é`, U+00E9) and
/// the same name with a base letter and a combining mark (`e` U+0065, U+0301) are one name in
/// a compiled declaration, so they are one name in a text read at run time too. proc-macro2's
/// lexer, outside a compiler, keeps identifiers as written.
///
/// Without recursion: the groups being rebuilt are frames of a stack of its own, so brackets
/// nested as deep as the text allows (the front end refuses more than its limit afterwards,
/// with its message) cannot overflow the reader's stack, as one call per bracket did.
fn nfc_identifiers(tokens: TokenStream) -> TokenStream {
    use proc_macro2::{Group, TokenTree, token_stream::IntoIter};
    /// A group being rebuilt: the group (`None` for the whole text), its tokens still to
    /// read, and those read.
    struct Frame {
        group: Option<Group>,
        rest: IntoIter,
        done: Vec<TokenTree>,
    }
    let mut stack = vec![Frame { group: None, rest: tokens.into_iter(), done: Vec::new() }];
    loop {
        let top = stack.last_mut().expect("the whole text's frame is popped last");
        match top.rest.next() {
            Some(TokenTree::Group(group)) => {
                stack.push(Frame { rest: group.stream().into_iter(), group: Some(group), done: Vec::new() })
            }
            Some(TokenTree::Ident(ident)) => top.done.push(TokenTree::Ident(nfc_identifier(ident))),
            Some(other) => top.done.push(other),
            None => {
                let Frame { group, done, .. } = stack.pop().expect("a frame");
                let stream: TokenStream = done.into_iter().collect();
                match (group, stack.last_mut()) {
                    (Some(group), Some(parent)) => {
                        let mut normal = Group::new(group.delimiter(), stream);
                        normal.set_span(group.span());
                        parent.done.push(TokenTree::Group(normal));
                    }
                    _ => return stream,
                }
            }
        }
    }
}

/// `ident` in Unicode Normalization Form C, at its span (see [`nfc_identifiers`]).
fn nfc_identifier(ident: proc_macro2::Ident) -> proc_macro2::Ident {
    use proc_macro2::Ident;
    use unicode_normalization::{UnicodeNormalization, is_nfc};
    let written = ident.to_string();
    if is_nfc(&written) {
        return ident;
    }
    // The normal form of an identifier is an identifier (XID is closed under NFC).
    match written.strip_prefix("r#") {
        Some(raw) => Ident::new_raw(&raw.nfc().collect::<String>(), ident.span()),
        None => Ident::new(&written.nfc().collect::<String>(), ident.span()),
    }
}

/// Rust's white space (`Pattern_White_Space`): the only characters between tokens the compiler
/// accepts.
fn rust_white_space(c: char) -> bool {
    matches!(
        c,
        '\t' | '\n' | '\u{b}' | '\u{c}' | '\r' | ' ' | '\u{85}' | '\u{200e}' | '\u{200f}' | '\u{2028}' | '\u{2029}'
    )
}

/// The first character outside comments and strings that Unicode calls white space and Rust
/// does not (a no-break space pasted from a web page, an em space): proc-macro2's lexer takes it
/// for a space where the compiler refuses the same declaration in `mechanism!` ("unknown start
/// of token"), and a `.kl` file is the same language as the macro's. Or the first control
/// character that is not Rust's white space (a NUL, a bell, an escape from a terminal): the
/// lexer's own error names neither the character nor its place. Inside a comment or a string
/// (the text of a `#[doc = "..."]`) both are text, as to the compiler; a `//` or `/*` inside a
/// string starts no comment.
fn foreign_character(text: &str) -> Option<Diagnostic> {
    let mut scan = Scan { chars: text.char_indices().peekable(), line: 1, column: 1, last: None, before: None };
    // A byte order mark starting the text takes no column (see `at_span`).
    if text.starts_with(BOM) {
        scan.next();
        scan.column = 1;
    }
    // Block comments nest in Rust; a line comment runs to the end of its line.
    let (mut depth, mut in_line_comment) = (0usize, false);
    while let Some((at, c)) = scan.next() {
        let next = scan.peek();
        if in_line_comment {
            in_line_comment = c != '\n';
        } else if c == '/' && next == Some('*') {
            depth += 1;
            scan.next();
        } else if depth > 0 && c == '*' && next == Some('/') {
            depth -= 1;
            scan.next();
        } else if depth > 0 {
            // Text of a block comment.
        } else if c == '/' && next == Some('/') {
            in_line_comment = true;
        } else if c == '"' {
            scan.skip_string();
        } else if let Some(hashes) = scan.raw_string_start(c) {
            scan.skip_raw_string(hashes);
        } else if let Some(message) = foreign_message(c) {
            // The place of `c`: `scan` has moved one column past it.
            let (line, column) = (scan.line, scan.column - 1);
            return Some(Diagnostic { message, range: at..at + c.len_utf8(), line, column });
        }
    }
    None
}

/// What the compiler says of the character `c` between tokens, when it refuses it.
fn foreign_message(c: char) -> Option<String> {
    if c.is_whitespace() && !rust_white_space(c) {
        Some(format!(
            "the character U+{:04X} is white space in Unicode but not in Rust: replace it with a plain space",
            c as u32
        ))
    } else if c.is_control() && !rust_white_space(c) {
        Some(format!(
            "unknown start of token: {}: the control character U+{:04X} has no place in a declaration; remove it",
            c.escape_default(),
            c as u32
        ))
    } else {
        None
    }
}

/// The characters of a text with the line and column (in characters, from 1) of the next one.
struct Scan<'a> {
    chars: std::iter::Peekable<std::str::CharIndices<'a>>,
    line: usize,
    column: usize,
    /// The character read last and the one before it.
    last: Option<char>,
    before: Option<char>,
}

impl Scan<'_> {
    /// The next character and its byte offset; the line and column move past it.
    fn next(&mut self) -> Option<(usize, char)> {
        let (at, c) = self.chars.next()?;
        if c == '\n' {
            self.line += 1;
            self.column = 1;
        } else {
            self.column += 1;
        }
        (self.before, self.last) = (self.last, Some(c));
        Some((at, c))
    }

    fn peek(&mut self) -> Option<char> {
        self.chars.peek().map(|&(_, c)| c)
    }

    /// Past the end of a string whose opening `"` was just read: a `\` escapes the character
    /// after it. An unterminated string runs to the end of the text (the lexer names it).
    fn skip_string(&mut self) {
        while let Some((_, c)) = self.next() {
            match c {
                '\\' => {
                    self.next();
                }
                '"' => return,
                _ => {}
            }
        }
    }

    /// The number of `#` of a raw string (`r"..."`, `r#"..."#`, with a `b` or `c` before the
    /// `r`) whose `r` is `c`, just read; past its opening `"`. `None` (nothing read) where `c`
    /// starts no raw string: part of a name, or an `r` followed by no `"`.
    fn raw_string_start(&mut self, c: char) -> Option<usize> {
        if c != 'r' || !matches!(self.peek(), Some('"' | '#')) {
            return None;
        }
        // A raw string starts a token: an `r` ending a name (`for"`) starts none. `before` is
        // the character before the `r`, just read.
        if self.before.is_some_and(|p| (p.is_alphanumeric() || p == '_') && !matches!(p, 'b' | 'c')) {
            return None;
        }
        let mut lookahead = self.chars.clone();
        let hashes = std::iter::from_fn(|| lookahead.next_if(|&(_, c)| c == '#')).count();
        if lookahead.next().map(|(_, c)| c) != Some('"') {
            return None;
        }
        for _ in 0..=hashes {
            self.next();
        }
        Some(hashes)
    }

    /// Past the end of a raw string with `hashes` `#` whose opening `"` was just read.
    fn skip_raw_string(&mut self, hashes: usize) {
        while let Some((_, c)) = self.next() {
            if c == '"' {
                let mut lookahead = self.chars.clone();
                if (0..hashes).all(|_| lookahead.next().is_some_and(|(_, c)| c == '#')) {
                    for _ in 0..hashes {
                        self.next();
                    }
                    return;
                }
            }
        }
    }
}

/// How many brackets open around a rejected closing one [`unclosed_before`] looks through for
/// the one it closes (each a lexing of the text before it): far more than a declaration nests.
const UNCLOSED_DEPTH: usize = 16;

/// Where a closing bracket the lexer rejects (`d`, at the `}` of `{ (x }`) ends a block in
/// which an opening one is never closed: the innermost bracket still open before it, where the
/// compiler reports the mistake (the closing one only ends an outer bracket). The text before
/// the closing bracket, lexed, is refused at that innermost open bracket; the text before that
/// one at the next bracket out, and so on until one of the closing bracket's kind. `None`
/// otherwise: `d` is no closing bracket, or it closes no bracket open around it (`{ ) }`: a
/// closing bracket too many, reported where it is).
fn unclosed_before(text: &str, d: &Diagnostic) -> Option<Diagnostic> {
    let close = text[d.range.start..].chars().next().filter(|c| matches!(c, ')' | ']' | '}'))?;
    // The innermost open bracket with its closing one, once found.
    let mut innermost: Option<(Diagnostic, char, char)> = None;
    let mut end = d.range.start;
    for _ in 0..UNCLOSED_DEPTH {
        let before = &text[..end];
        // Every bracket before `end` closed: `close` closes nothing.
        let e = before.parse::<TokenStream>().err()?;
        let open = at_span(before, e.span(), String::new());
        let c = before[open.range.start..].chars().next()?;
        let closing = closing_of(c)?;
        end = open.range.start;
        match innermost {
            None => innermost = Some((open, c, closing)),
            Some((mut inner, c, inner_closing)) if closing == close => {
                inner.message = format!(
                    "unclosed delimiter: this `{c}` is never closed: close it with `{inner_closing}` before the \
                     `{close}` at line {}, column {}",
                    d.line, d.column
                );
                return Some(inner);
            }
            Some(_) => {}
        }
    }
    None
}

/// Where a closing bracket the lexer rejects (`d`, at the `]` of `(x, 0]`) closes no bracket
/// of its kind ([`unclosed_before`] found none): the innermost bracket still open before it,
/// of another kind, which the compiler reports as closed by a "mismatched closing delimiter"
/// (the `(`), with the fixes. `None` where `d` is no closing bracket, or no bracket but the
/// declaration's `{` is open before it (`)` alone: unexpected, reported where it is).
fn mismatched_before(text: &str, d: &Diagnostic) -> Option<Diagnostic> {
    let close = text[d.range.start..].chars().next().filter(|c| matches!(c, ')' | ']' | '}'))?;
    let before = &text[..d.range.start];
    let e = before.parse::<TokenStream>().err()?;
    let mut open = at_span(before, e.span(), String::new());
    // The declaration's own `{` (every bracket before it closed): the closing bracket is
    // unexpected inside the block, as the compiler says of one in a function's body.
    before[..open.range.start].parse::<TokenStream>().err()?;
    let c = before[open.range.start..].chars().next()?;
    let closing = closing_of(c)?;
    // The other fix, an opening bracket of the closing one's kind: not `[`, which opens nothing
    // in a declaration's expressions (its vectors are written in parentheses).
    let other = match opening_of(close)? {
        '[' => String::new(),
        opening => format!(", or open it with `{opening}`"),
    };
    open.message = format!(
        "mismatched closing delimiter: this `{c}` is closed by the `{close}` at line {}, column {}: close it with \
         `{closing}`{other}",
        d.line, d.column
    );
    Some(open)
}

/// The opening bracket of the closing one `c`.
fn opening_of(c: char) -> Option<char> {
    match c {
        ')' => Some('('),
        ']' => Some('['),
        '}' => Some('{'),
        _ => None,
    }
}

/// The closing bracket of the opening one `c`.
fn closing_of(c: char) -> Option<char> {
    match c {
        '(' => Some(')'),
        '[' => Some(']'),
        '{' => Some('}'),
        _ => None,
    }
}

/// The compiler's message for a text its lexer rejects at the start of `rest`, for the
/// mistakes it names (a character no token starts with, a closing bracket without its opening
/// one, an opening one never closed, a string or block comment without its end);
/// proc-macro2's own message otherwise.
fn lex_message(rest: &str, e: &proc_macro2::LexError) -> String {
    let mut chars = rest.chars();
    match (chars.next(), chars.next()) {
        (Some(c @ (')' | ']' | '}')), _) => format!("unexpected closing delimiter: `{c}`"),
        (Some(c @ ('(' | '[' | '{')), _) => format!("unclosed delimiter: this `{c}` is never closed"),
        (Some('"'), _) => "unterminated double quote string".to_string(),
        (Some('/'), Some('*')) => "unterminated block comment".to_string(),
        // ASCII characters that start no token: the compiler writes them as they are.
        (Some(c @ ('`' | '\\')), _) => format!("unknown start of token: {c}"),
        (Some('r'), Some('#')) => {
            let word: String = rest[2..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            if matches!(word.as_str(), "super" | "self" | "Self" | "crate" | "_") {
                format!("`{word}` cannot be a raw identifier")
            } else {
                format!("cannot read the declaration: {e}")
            }
        }
        (Some(c), _) if c.is_ascii_digit() => {
            let number: String = rest.chars().take_while(|c| c.is_alphanumeric() || matches!(c, '_' | '.')).collect();
            // A digit its base does not have (`0b102`): the macro's words (after the compiler's
            // own lexer error, its error at the same number).
            kinloop_codegen::digit_outside_its_base(&number)
                .unwrap_or_else(|| format!("invalid number `{number}`; write a number such as `2.5`, `1e-3` or `0x1F`"))
        }
        (Some('\''), _) => {
            "unexpected `'`: a declaration has no character literals; write a number or a name".to_string()
        }
        // A typographic or mathematical sign (`−`, `×`, `°`, `²`): what to write instead, as
        // the compiler names the ASCII character one looks like.
        (Some(c), _) if !c.is_ascii() && !unicode_ident_start(c) => match crate::confusables::help(c) {
            Some(help) => format!("unknown start of token: {}\nhelp: {help}", c.escape_default()),
            None => format!("unknown start of token: {}", c.escape_default()),
        },
        _ => format!("cannot read the declaration: {e}"),
    }
}

/// Whether `c` may start an identifier (approximated: alphabetic), where the compiler reports
/// a non-ASCII identifier instead of an unknown token.
fn unicode_ident_start(c: char) -> bool {
    c.is_alphabetic()
}

/// Forgets the spans of every text this thread lexed. proc-macro2 keeps the text of each
/// lexed source in a per-thread map for the spans' locations; a long-running reader (a service)
/// calls this between declarations to bound its memory. Spans made before are invalid after it:
/// call it only when no token stream, span or error from an earlier read is in use.
pub fn forget_spans() {
    proc_macro2::extra::invalidate_current_thread_spans();
}
