//! Expressions of the declaration language and their Pratt parser.
//!
//! Precedence, loosest first:
//!
//! | level | operators | associativity |
//! |-------|-----------|---------------|
//! | 1 | `+` `-` | left |
//! | 2 | `@` (polar vector `length @ angle`) | left |
//! | 3 | `*` `/` | left |
//! | 4 | unary `-` | prefix |
//! | 5 | `^` (power) | right |
//! | 6 | `.x` `.y` (vector components) | postfix |
//!
//! So `a + r @ phi` is `a + (r @ phi)`, `2 * r @ phi` is `(2 * r) @ phi`, and `-x^2` is
//! `-(x^2)`. An angle that is a sum needs parentheses: `r @ (phi + gamma)`.

use proc_macro2::{Span, TokenStream};
use quote::quote_spanned;
use syn::parse::ParseStream;
use syn::{Ident, Token};

/// The first and last token of a syntax node, so errors can underline the whole node.
#[derive(Clone, Copy, Debug)]
pub struct SpanRange {
    /// Span of the first token.
    pub start: Span,
    /// Span of the last token.
    pub end: Span,
}

impl SpanRange {
    /// The range of one token.
    pub fn single(span: Span) -> Self {
        SpanRange { start: span, end: span }
    }

    /// From the start of `self` to the end of `other`.
    pub fn to(self, other: SpanRange) -> Self {
        SpanRange { start: self.start, end: other.end }
    }

    /// A `syn::Error` underlining this range.
    pub fn error(self, message: impl std::fmt::Display) -> syn::Error {
        // `Error::new_spanned` records the first and last token's spans, which is how a range is
        // expressed on stable Rust (where `Span::join` is unavailable).
        let (start, end) = (self.start, self.end);
        let tokens: TokenStream = quote_spanned!(start=> __a).into_iter().chain(quote_spanned!(end=> __b)).collect();
        syn::Error::new_spanned(tokens, message)
    }
}

/// A binary operator.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum BinOp {
    /// `a + b` (scalars or vectors).
    Add,
    /// `a - b` (scalars or vectors).
    Sub,
    /// `a * b` (a scalar times a scalar or a vector).
    Mul,
    /// `a / b` (a scalar or a vector over a scalar).
    Div,
    /// `a ^ b` (scalars).
    Pow,
    /// `length @ angle`.
    Polar,
}

impl BinOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "^",
            BinOp::Polar => "@",
        }
    }
}

/// A component of a vector, `.x` or `.y`.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Component {
    /// `.x`.
    X,
    /// `.y`.
    Y,
}

/// An expression of the declaration language, as parsed (types are checked later, when it is
/// lowered to the graph).
#[derive(Clone, Debug)]
pub enum Expr {
    /// A number literal; `integer` is set when it was written without a decimal point.
    Num {
        /// Its value.
        value: f64,
        /// Its value when it is an integer literal (exponents of `powi`).
        integer: Option<i64>,
        /// Where it is written.
        span: Span,
    },
    /// A name: parameter, input, unknown, `let`, `pi`, or an undeclared name reported later.
    Var(Ident),
    /// Unary minus.
    Neg {
        /// The `-` token.
        op: Span,
        /// The negated expression.
        expr: Box<Expr>,
    },
    /// A binary operation.
    Binary {
        /// The operator.
        op: BinOp,
        /// The operator's token.
        op_span: Span,
        /// The left operand.
        lhs: Box<Expr>,
        /// The right operand.
        rhs: Box<Expr>,
    },
    /// A call of a built-in function.
    Call {
        /// The function's name.
        func: Ident,
        /// The arguments.
        args: Vec<Expr>,
        /// The closing parenthesis.
        close: Span,
    },
    /// A Cartesian vector `(x, y)`.
    Tuple {
        /// The opening parenthesis.
        open: Span,
        /// The x component.
        x: Box<Expr>,
        /// The y component.
        y: Box<Expr>,
        /// The closing parenthesis.
        close: Span,
    },
    /// A parenthesised expression, kept so that messages show the user's parentheses.
    Paren {
        /// The opening parenthesis.
        open: Span,
        /// The expression inside.
        inner: Box<Expr>,
        /// The closing parenthesis.
        close: Span,
    },
    /// A vector component, `v.x` or `v.y`.
    Field {
        /// The vector.
        base: Box<Expr>,
        /// Which component.
        component: Component,
        /// The component's name as written.
        name: Ident,
    },
}

impl Expr {
    /// Whether the expression is written in degrees, `deg(...)` (negated or in parentheses
    /// too), or is such a value scaled by a number (`2 * deg(15)`, `deg(15) * 2`,
    /// `deg(30) / 2`) or added to one or to another such value (`deg(90) + pi / 4`,
    /// `deg(10) + deg(5)`): the value is then certainly an angle, whatever number it is. A
    /// product of two of them, or of one with a name, is not: its kind is not certain.
    pub fn written_in_degrees(&self) -> bool {
        self.written_in_degrees_with(&|_| false)
    }

    /// As [`Expr::written_in_degrees`], a name that `named` says stands for a value in degrees
    /// (a `let` of one: `let tilt = deg(5);`) counted as one written there.
    pub fn written_in_degrees_with(&self, named: &dyn Fn(&Ident) -> bool) -> bool {
        let degrees = |e: &Expr| e.written_in_degrees_with(named);
        match self {
            Expr::Call { func, .. } => func == "deg",
            Expr::Var(id) => named(id),
            Expr::Neg { expr, .. } => degrees(expr),
            Expr::Paren { inner, .. } => degrees(inner),
            Expr::Binary { op: BinOp::Mul, lhs, rhs, .. } => {
                (degrees(lhs) && rhs.is_plain_number()) || (lhs.is_plain_number() && degrees(rhs))
            }
            Expr::Binary { op: BinOp::Div, lhs, rhs, .. } => degrees(lhs) && rhs.is_plain_number(),
            Expr::Binary { op: BinOp::Add | BinOp::Sub, lhs, rhs, .. } => {
                // At least one term in degrees, and the other in degrees or a plain number.
                let term = |e: &Expr| degrees(e) || e.is_plain_number();
                (degrees(lhs) || degrees(rhs)) && term(lhs) && term(rhs)
            }
            _ => false,
        }
    }

    /// Whether the expression is a number without a unit: literals, `pi`, and operations and
    /// calls of those, with no name and no value in degrees.
    fn is_plain_number(&self) -> bool {
        match self {
            Expr::Num { .. } => true,
            Expr::Var(id) => id == "pi",
            Expr::Neg { expr, .. } => expr.is_plain_number(),
            Expr::Paren { inner, .. } => inner.is_plain_number(),
            Expr::Binary { op: BinOp::Polar, .. } => false,
            Expr::Binary { lhs, rhs, .. } => lhs.is_plain_number() && rhs.is_plain_number(),
            Expr::Call { func, args, .. } => func != "deg" && args.iter().all(Expr::is_plain_number),
            Expr::Tuple { .. } | Expr::Field { .. } => false,
        }
    }

    /// The tokens the expression spans, for errors about it.
    pub fn range(&self) -> SpanRange {
        match self {
            Expr::Num { span, .. } => SpanRange::single(*span),
            Expr::Var(id) => SpanRange::single(id.span()),
            Expr::Neg { op, expr } => SpanRange::single(*op).to(expr.range()),
            Expr::Binary { lhs, rhs, .. } => lhs.range().to(rhs.range()),
            Expr::Call { func, close, .. } => SpanRange { start: func.span(), end: *close },
            Expr::Tuple { open, close, .. } | Expr::Paren { open, close, .. } => {
                SpanRange { start: *open, end: *close }
            }
            Expr::Field { base, name, .. } => base.range().to(SpanRange::single(name.span())),
        }
    }

    /// The expression as source text (with the user's parentheses), for "write ... instead"
    /// hints in messages.
    pub fn show(&self) -> String {
        match self {
            Expr::Num { value, integer, .. } => match integer {
                Some(n) => n.to_string(),
                None => format!("{value:?}"),
            },
            Expr::Var(id) => id.to_string(),
            Expr::Neg { expr, .. } => format!("-{}", expr.show()),
            Expr::Binary { op: BinOp::Pow, lhs, rhs, .. } => format!("{}^{}", lhs.show(), rhs.show()),
            Expr::Binary { op, lhs, rhs, .. } => format!("{} {} {}", lhs.show(), op.symbol(), rhs.show()),
            Expr::Call { func, args, .. } => {
                format!("{func}({})", args.iter().map(Expr::show).collect::<Vec<_>>().join(", "))
            }
            Expr::Tuple { x, y, .. } => format!("({}, {})", x.show(), y.show()),
            Expr::Paren { inner, .. } => format!("({})", inner.show()),
            Expr::Field { base, name, .. } => format!("{}.{name}", base.show()),
        }
    }

    /// Adds the names the expression uses (as values, not the functions it calls), without
    /// `r#`, to `out`.
    pub fn names_used(&self, out: &mut std::collections::HashSet<String>) {
        match self {
            Expr::Num { .. } => {}
            Expr::Var(id) => {
                out.insert(syn::ext::IdentExt::unraw(id).to_string());
            }
            Expr::Neg { expr: e, .. } | Expr::Paren { inner: e, .. } | Expr::Field { base: e, .. } => e.names_used(out),
            Expr::Binary { lhs, rhs, .. } | Expr::Tuple { x: lhs, y: rhs, .. } => {
                lhs.names_used(out);
                rhs.names_used(out);
            }
            Expr::Call { args, .. } => args.iter().for_each(|a| a.names_used(out)),
        }
    }

    /// Is this the literal `0` (used for `loop name: a + b - c == 0`), negated or in
    /// parentheses (`-0`, `(0)`): the negated zero vector is the zero vector, so `== -0` closes
    /// a loop as `== 0` does, where it was refused as a scalar facing a vector.
    pub fn is_literal_zero(&self) -> bool {
        match self {
            Expr::Num { value, .. } => *value == 0.0,
            Expr::Paren { inner, .. } | Expr::Neg { expr: inner, .. } => inner.is_literal_zero(),
            _ => false,
        }
    }
}

/// Deepest expression nesting accepted. Deeper input is rejected with an error instead of
/// risking the compiler's stack in the recursive parts (parsing, lowering, dropping the tree).
pub const MAX_DEPTH: usize = 128;

/// The error for a vector written in square brackets or braces (`[x, 0]`, `{x, 0}`), as other
/// languages write one: a vector is `(x, y)`. `None` for anything else.
fn vector_in_other_brackets(input: ParseStream) -> Option<syn::Error> {
    let Some((proc_macro2::TokenTree::Group(group), _)) = input.cursor().token_tree() else {
        return None;
    };
    let (open, close) = match group.delimiter() {
        proc_macro2::Delimiter::Bracket => ('[', ']'),
        proc_macro2::Delimiter::Brace => ('{', '}'),
        _ => return None,
    };
    let comma = |t: &proc_macro2::TokenTree| matches!(t, proc_macro2::TokenTree::Punct(p) if p.as_char() == ',');
    if !group.stream().into_iter().any(|t| comma(&t)) {
        return None;
    }
    let inside = group.stream().to_string().replace(" ,", ",");
    Some(input.error(format!("a vector is written in parentheses: write `({inside})`, not `{open}{inside}{close}`")))
}

/// The error for parentheses that hold a name or a number and then a number, `(x 0)`: a vector
/// without the `,` between its components, which the message for a product without its `*`
/// ("write `x * 0`") did not name. `None` for anything else (`(2 pi)` stays a product).
fn vector_without_comma(content: ParseStream) -> Option<syn::Error> {
    let (first, rest) = content.cursor().token_tree()?;
    let (second, end) = rest.token_tree()?;
    let value = matches!(&first, proc_macro2::TokenTree::Literal(_))
        || matches!(&first, proc_macro2::TokenTree::Ident(id) if id != "deg");
    if !end.eof() || !value || !matches!(second, proc_macro2::TokenTree::Literal(_)) {
        return None;
    }
    Some(syn::Error::new(
        second.span(),
        format!(
            "expected `,` between the components of a vector: write `({first}, {second})`, \
             or `{first} * {second}` for a product"
        ),
    ))
}

/// The error for a number written without its leading `0` (`.5`, which Rust reads as a `.` and
/// the number `5`), saying to write `0.5`. `None` for anything else.
fn number_without_leading_digit(input: ParseStream) -> Option<syn::Error> {
    let (dot, rest) = input.cursor().punct()?;
    let (lit, _) = rest.literal()?;
    if dot.as_char() != '.' || dot.spacing() != proc_macro2::Spacing::Alone {
        return None;
    }
    let range = SpanRange { start: dot.span(), end: lit.span() };
    Some(range.error(format!("a number starts with a digit: write `0.{lit}`")))
}

/// The error for a Rust keyword called as a function where a value belongs (`if(x)`, `fn(x)`):
/// it is no function of the language; where a built-in does its work (`min`, `max`, `clamp`,
/// `abs` for a value chosen by a condition) the message names it, and it lists the functions.
/// `None` for anything else. (`mod(x, p)` is taken for a call of an unsupported function,
/// whose message says to write `wrap`.)
fn keyword_called(input: ParseStream) -> Option<syn::Error> {
    let (word, rest) = input.cursor().ident().filter(|(word, _)| word != "_")?;
    rest.group(proc_macro2::Delimiter::Parenthesis)?;
    // A name that is no keyword (syn reads it as an identifier) is not one called.
    if syn::parse_str::<Ident>(&word.to_string()).is_ok() {
        return None;
    }
    let hint = match word.to_string().as_str() {
        "if" | "else" | "match" => {
            "; a value chosen by a condition is written with `min`, `max`, `clamp` or `abs` (`max(x, 0)`, \
             `clamp(x, lo, hi)`)"
        }
        "fn" => "; call a built-in function by its name (`sin(x)`), and name a value with `let`",
        "return" => "; write the value alone",
        _ => "",
    };
    Some(syn::Error::new(
        word.span(),
        format!(
            "`{word}` is a Rust keyword, not a function of the language{hint}\navailable functions: {}",
            crate::semantics::builtins::listing()
        ),
    ))
}

/// Parses one expression, stopping before `==`, `;`, `,` or the end of the input.
pub fn parse_expr(input: ParseStream) -> syn::Result<Expr> {
    Parser { depth: 0 }.expr(input, 0)
}

/// The value of a number literal (integer or float): finite, without a type suffix.
fn number(digits: &str, suffix: &str, span: Span) -> syn::Result<f64> {
    const TYPES: [&str; 16] = [
        "f16", "f32", "f64", "f128", "i8", "i16", "i32", "i64", "i128", "isize", "u8", "u16", "u32", "u64", "u128",
        "usize",
    ];
    // `30deg`, `1.5rad`: a unit written right after a number. `deg` is a function, so the
    // product that `2pi` below suggests would not compile either.
    if suffix == "deg" {
        return Err(syn::Error::new(span, degrees_message(digits)));
    }
    if suffix == "rad" {
        return Err(syn::Error::new(
            span,
            format!("`{digits}{suffix}` is not a number: angles are in radians already, write `{digits}`"),
        ));
    }
    // `1e`: an exponent without its digits (the compiler's lexer says so first, and hands the
    // token on as a number with a suffix `e`), not a product with a name `e`.
    if suffix == "e" || suffix == "E" {
        return Err(syn::Error::new(
            span,
            format!("`{digits}{suffix}` is not a number: an exponent needs its digits, as in `{digits}{suffix}3`"),
        ));
    }
    if let Some(message) = digit_outside_its_base(&format!("{digits}{suffix}")) {
        return Err(syn::Error::new(span, message));
    }
    if !suffix.is_empty() && !TYPES.contains(&suffix) && suffix.starts_with(|c: char| c.is_alphabetic()) {
        // `2pi`: a name written right after a number, as in a textbook.
        return Err(syn::Error::new(
            span,
            format!("`{digits}{suffix}` is not a number: write `{digits} * {suffix}` for a product"),
        ));
    }
    if !suffix.is_empty() {
        return Err(syn::Error::new(
            span,
            format!("number suffixes are not needed: write `{digits}` (all values are f64)"),
        ));
    }
    let value: f64 = digits.parse().map_err(|_| syn::Error::new(span, "invalid number"))?;
    if !value.is_finite() {
        return Err(syn::Error::new(span, "number is too large for an f64 (the largest is about 1.8e308)"));
    }
    // A mantissa that is not zero read as zero: below the smallest f64 (about 4.9e-324).
    let mantissa = digits.split(['e', 'E']).next().unwrap_or_default();
    if value == 0.0 && mantissa.contains(|c: char| ('1'..='9').contains(&c)) {
        return Err(syn::Error::new(
            span,
            format!("`{digits}` is too small for an f64 (the smallest is about 4.9e-324): write `0` for zero"),
        ));
    }
    Ok(value)
}

/// The message for a binary or octal number written with a digit its base does not have
/// (`0b102`, `0o78`): which digit, and the digits of the base. The compiler's lexer says so first
/// and hands the token on as `0` with a suffix (`b102`), not a product with a name; the run-time
/// reader's lexer refuses the token, and says the same. `None` for any other text.
pub fn digit_outside_its_base(number: &str) -> Option<String> {
    let (base, digits, last) = match number.get(..2)? {
        "0b" => ("a binary", "`0` and `1`", '1'),
        "0o" => ("an octal", "`0` to `7`", '7'),
        _ => return None,
    };
    let rest = &number[2..];
    let bad = rest.chars().find(|c| *c != '_' && !('0'..=last).contains(c))?;
    // A letter ends the digits (a suffix, `0b1f64`): only a decimal digit can be one outside the
    // base.
    if !bad.is_ascii_digit() || rest.chars().take_while(|c| *c != bad).any(|c| c.is_alphabetic()) {
        return None;
    }
    Some(format!("`{number}` is not a number: `{bad}` is not a digit of {base} number, which has only {digits}"))
}

/// The error for a value in degrees written with `deg` as a unit (`30 deg`, `30deg`, `deg 30`)
/// instead of called.
fn degrees_message(value: &str) -> String {
    format!("a value in degrees is written `deg({value})`: `deg` is a function")
}

struct Parser {
    depth: usize,
}

/// At most 24 characters of `s`, for quoting source in messages.
/// Names that start the next part of a declaration (an item, a body's field, a load's point or
/// angle), not a factor: after a number they mean a missing `;` or `,`.
const STARTS_A_PART: &[&str] = &[
    "params", "param", "input", "inputs", "unknowns", "unknown", "let", "loop", "eq", "point", "output", "body",
    "force", "torque", "gravity", "at", "on", "mass", "com", "inertia", "turns",
];

/// The words that start an item. Here, below `syntax` (whose custom keywords would import it
/// back), so that `item`, `dynamics` and this parser all tell an item's start by one list.
const ITEM_KEYWORDS: &[&str] = &[
    "params", "param", "input", "inputs", "unknowns", "unknown", "let", "loop", "eq", "point", "output", "body",
    "force", "torque", "gravity",
];

/// Whether `input` starts an item: at its keyword, or at a doc comment or attribute before one.
pub(super) fn starts_an_item(input: ParseStream) -> bool {
    input.peek(Token![#])
        || input.cursor().ident().is_some_and(|(id, _)| ITEM_KEYWORDS.contains(&id.to_string().as_str()))
}

/// The error for a doc comment inside an item (`loop c: r @ phi /// the crank` on a line of
/// its own), where it documents nothing: the parsers met it as a `#` where a value, an
/// operator, a name or the `;` belonged, and said so of the `#` the user did not write. `None`
/// where no doc comment stands, and where one starts the next item (that item's own, after an
/// item without its `;`: the `;` is what is missing).
pub(super) fn misplaced_doc_comment(input: ParseStream) -> Option<syn::Error> {
    if !input.peek(Token![#]) || input.peek2(Token![!]) {
        return None;
    }
    let fork = input.fork();
    let attrs = syn::Attribute::parse_outer(&fork).ok()?;
    let first = attrs.first().filter(|a| a.path().is_ident("doc"))?;
    if starts_an_item(&fork) {
        return None;
    }
    Some(syn::Error::new_spanned(
        first,
        "a doc comment documents the item or the name after it and cannot stand inside an item; \
         move it above the item, or write a plain comment with `//`",
    ))
}

fn short(s: &str) -> String {
    if s.chars().count() <= 24 { s.to_string() } else { format!("{}...", s.chars().take(24).collect::<String>()) }
}

/// After "write `f * x` for a product" where the left side is a name: the call it may have
/// meant, `sin phi` for `sin(phi)`.
fn call_hint(lhs: &Expr, next: &str) -> String {
    match lhs {
        Expr::Var(f) => format!(", or `{f}({next})` to call a function"),
        _ => String::new(),
    }
}

/// Binding power of an infix operator at the front of `input`, if one is there.
fn peek_infix(input: ParseStream) -> Option<(BinOp, u8)> {
    if input.peek(Token![==]) || input.peek(Token![=>]) {
        return None;
    }
    if input.peek(Token![+]) {
        Some((BinOp::Add, 1))
    } else if input.peek(Token![-]) && !input.peek(Token![->]) {
        Some((BinOp::Sub, 1))
    } else if input.peek(Token![@]) {
        Some((BinOp::Polar, 2))
    } else if input.peek(Token![*]) {
        Some((BinOp::Mul, 3))
    } else if input.peek(Token![/]) {
        Some((BinOp::Div, 3))
    } else if input.peek(Token![^]) {
        Some((BinOp::Pow, 5))
    } else {
        None
    }
}

const PREFIX_NEG: u8 = 4;

impl Parser {
    fn enter(&mut self, input: ParseStream) -> syn::Result<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(input.error(format!(
                "expression nested more than {MAX_DEPTH} levels deep; split it into named parts with `let`"
            )));
        }
        Ok(())
    }

    fn expr(&mut self, input: ParseStream, min_bp: u8) -> syn::Result<Expr> {
        self.enter(input)?;
        let mut lhs = self.prefix(input)?;
        // `x as f64`: every value is already an f64, and a cast ended the expression, which
        // the item then reported as a missing `;`.
        if input.peek(Token![as]) {
            return Err(input.error(format!(
                "casts are not part of the language: every value is an f64, write `{}` alone",
                short(&lhs.show())
            )));
        }
        // `h (1 - cos(phi))`, `2(r + h)`: a parenthesised value or a number right after a
        // value, which nothing in the language allows, is a product without its `*`.
        // (On the raw tokens: syn's `peek(LitInt)` also takes `- 15` for a negative literal.)
        // Vectors are left to the item's own message: `force f at (x, 0) (p, 0)` lacks its `=`.
        let cursor = input.cursor();
        let group = cursor.group(proc_macro2::Delimiter::Parenthesis);
        let vector = matches!(lhs, Expr::Tuple { .. })
            || group.is_some_and(|(inside, _, _)| {
                inside
                    .token_stream()
                    .into_iter()
                    .any(|t| matches!(t, proc_macro2::TokenTree::Punct(p) if p.as_char() == ','))
            });
        if !vector && (group.is_some() || cursor.literal().is_some()) {
            let next = input.cursor().token_tree().map(|(tt, _)| tt.to_string()).unwrap_or_default();
            let next: String = next.chars().take(24).collect();
            // `deg 30`: a function, so `deg * 30` would not compile; only the call is meant.
            if matches!(&lhs, Expr::Var(f) if f == "deg") && cursor.literal().is_some() {
                return Err(input.error(degrees_message(&next)));
            }
            return Err(input.error(format!(
                "expected an operator between `{}` and `{next}`: write `{} * {next}` for a product{}",
                short(&lhs.show()),
                short(&lhs.show()),
                call_hint(&lhs, &next)
            )));
        }
        // `2 pi`, `30 deg`: a number right before a name is a product without its `*` (or a
        // value in degrees written the other way round); `sin phi`, a name right before a name
        // (not a keyword: `x as f64` is another mistake), is a call or a product. Not where the
        // name starts the next part of the declaration: an item or a body's field after a
        // missing `;` or `,`, or a name given its value (`params r = 1 l = 2` lacks its `,`).
        if let (Expr::Num { .. } | Expr::Var(_), Some((name, rest))) = (&lhs, cursor.ident())
            && (matches!(lhs, Expr::Num { .. }) || input.peek(Ident))
            && !rest.punct().is_some_and(|(p, next)| match p.as_char() {
                ':' => true,
                // `name = value`, not `name == value`.
                '=' => next.punct().is_none_or(|(q, _)| q.as_char() != '='),
                _ => false,
            })
            && !STARTS_A_PART.contains(&name.to_string().as_str())
        {
            let left = short(&lhs.show());
            return Err(input.error(if name == "deg" {
                degrees_message(&left)
            } else {
                format!(
                    "expected an operator between `{left}` and `{name}`: write `{left} * {name}` for a product{}",
                    call_hint(&lhs, &name.to_string())
                )
            }));
        }
        // Counts how many operators were chained at this level: a long chain `a + b + c + ...`
        // builds a left-deep tree, which must respect the depth bound too.
        let mut chain = 0usize;
        while let Some((op, bp)) = peek_infix(input) {
            if bp < min_bp {
                break;
            }
            chain += 1;
            if self.depth + chain > MAX_DEPTH {
                return Err(input.error(format!(
                    "expression has more than {MAX_DEPTH} chained operators; split it into named parts with `let`"
                )));
            }
            let op_span = input.span();
            match op {
                BinOp::Add => drop(input.parse::<Token![+]>()?),
                BinOp::Sub => drop(input.parse::<Token![-]>()?),
                BinOp::Mul => {
                    input.parse::<Token![*]>()?;
                    // `x ** 2`, as Python and Fortran write a power.
                    if input.peek(Token![*]) {
                        return Err(syn::Error::new(op_span, "`**` is not an operator: write `x ^ 2` for a power"));
                    }
                }
                BinOp::Div => drop(input.parse::<Token![/]>()?),
                BinOp::Pow => drop(input.parse::<Token![^]>()?),
                BinOp::Polar => drop(input.parse::<Token![@]>()?),
            }
            // Left-associative operators parse their right side one level tighter; `^` is
            // right-associative and parses its right side at its own level.
            let rhs_bp = if op == BinOp::Pow { bp } else { bp + 1 };
            let rhs = if op == BinOp::Pow {
                // The exponent may carry its own sign: `x^-1`.
                self.expr(input, rhs_bp.min(PREFIX_NEG))?
            } else {
                self.expr(input, rhs_bp)?
            };
            lhs = Expr::Binary { op, op_span, lhs: Box::new(lhs), rhs: Box::new(rhs) };
        }
        if let Some(e) = misplaced_doc_comment(input) {
            return Err(e);
        }
        self.depth -= 1;
        Ok(lhs)
    }

    fn prefix(&mut self, input: ParseStream) -> syn::Result<Expr> {
        if input.peek(Token![-]) {
            let op = input.parse::<Token![-]>()?.span;
            let expr = self.expr(input, PREFIX_NEG)?;
            return Ok(Expr::Neg { op, expr: Box::new(expr) });
        }
        if input.peek(Token![+]) {
            return Err(input.error("unary `+` is not supported; write the value without a sign"));
        }
        let primary = self.primary(input)?;
        self.postfix(input, primary)
    }

    fn postfix(&mut self, input: ParseStream, mut base: Expr) -> syn::Result<Expr> {
        // A chain `v.x.x.x...` nests too: it must respect the depth bound like operators do.
        let mut chain = 0usize;
        while input.peek(Token![.]) && !input.peek(Token![..]) {
            chain += 1;
            if self.depth + chain > MAX_DEPTH {
                return Err(input.error(format!(
                    "expression has more than {MAX_DEPTH} chained `.x`/`.y`; a component of a scalar is an error anyway"
                )));
            }
            let dot = input.parse::<Token![.]>()?;
            let name: Ident = match input.parse() {
                Ok(id) => id,
                // `1.0.0`: Rust's lexer reads a number `1.0`, a `.` and a number `0`.
                Err(_) if matches!(base, Expr::Num { .. }) && input.peek(syn::Lit) => {
                    return Err(syn::Error::new(dot.span, "a number has one decimal point: remove this `.`"));
                }
                Err(_) => return Err(input.error("expected `x` or `y` after `.` (a vector component)")),
            };
            let component = match name.to_string().as_str() {
                "x" => Component::X,
                "y" => Component::Y,
                other => {
                    let hint = if input.peek(syn::token::Paren) {
                        format!("method calls are not supported: write `{other}(value)` instead of `value.{other}()`")
                    } else {
                        format!("a vector has only the components `.x` and `.y`, not `.{other}`")
                    };
                    return Err(syn::Error::new(name.span(), hint));
                }
            };
            base = Expr::Field { base: Box::new(base), component, name };
        }
        Ok(base)
    }

    fn primary(&mut self, input: ParseStream) -> syn::Result<Expr> {
        let look = input.lookahead1();
        if look.peek(syn::LitInt) {
            let lit: syn::LitInt = input.parse()?;
            let value = number(lit.base10_digits(), lit.suffix(), lit.span())?;
            let integer = lit.base10_digits().parse::<i64>().ok();
            return Ok(Expr::Num { value, integer, span: lit.span() });
        }
        if look.peek(syn::LitFloat) {
            let lit: syn::LitFloat = input.parse()?;
            let value = number(lit.base10_digits(), lit.suffix(), lit.span())?;
            return Ok(Expr::Num { value, integer: None, span: lit.span() });
        }
        if look.peek(Ident) {
            let id: Ident = input.parse()?;
            if input.peek(syn::token::Paren) {
                return self.call(input, id);
            }
            return Ok(Expr::Var(id));
        }
        // `mod(x, 360)`, as other languages write a remainder: a call of a function the
        // language does not have, which the names' check says with what to write (`wrap`), not
        // the Rust keyword where a value belongs.
        if let Some((id, rest)) = input.cursor().ident()
            && id == "mod"
            && rest.group(proc_macro2::Delimiter::Parenthesis).is_some()
        {
            let id = input.call(<Ident as syn::ext::IdentExt>::parse_any)?;
            return self.call(input, id);
        }
        if look.peek(syn::token::Paren) {
            return self.paren_or_vector(input);
        }
        const VALUE: &str = "a number, a name, a call `f(x)`, a vector `(x, y)` or `(expression)`";
        if let Some(e) = vector_in_other_brackets(input) {
            return Err(e);
        }
        if input.is_empty() {
            return Err(input.error(format!("expected a value: {VALUE}")));
        }
        if let Some(e) = number_without_leading_digit(input) {
            return Err(e);
        }
        if let Some(e) = misplaced_doc_comment(input) {
            return Err(e);
        }
        if let Some(e) = keyword_called(input) {
            return Err(e);
        }
        // The operator or token where a value was expected (a joint operator such as `==` whole).
        let mut found = String::new();
        let mut cursor = input.cursor();
        let mut range = SpanRange::single(input.span());
        while let Some((tt, next)) = cursor.token_tree() {
            found.push_str(&tt.to_string().chars().take(24).collect::<String>());
            range.end = tt.span();
            match tt {
                proc_macro2::TokenTree::Punct(p) if p.spacing() == proc_macro2::Spacing::Joint => cursor = next,
                _ => break,
            }
        }
        // Underlined whole, as it is quoted: both characters of `==`.
        Err(range.error(format!("expected a value ({VALUE}), found `{found}`")))
    }

    /// The arguments of a call of `func`, `func(a, b)`, at the `(`.
    fn call(&mut self, input: ParseStream, func: Ident) -> syn::Result<Expr> {
        let content;
        let paren = syn::parenthesized!(content in input);
        let mut args = Vec::new();
        while !content.is_empty() {
            args.push(self.expr(&content, 0)?);
            if content.is_empty() {
                break;
            }
            if !content.peek(Token![,]) {
                return Err(content.error("expected `,` between function arguments"));
            }
            content.parse::<Token![,]>()?;
        }
        Ok(Expr::Call { func, args, close: paren.span.close() })
    }

    /// `(expression)` or a vector `(x, y)`.
    fn paren_or_vector(&mut self, input: ParseStream) -> syn::Result<Expr> {
        let content;
        let paren = syn::parenthesized!(content in input);
        let (open, close) = (paren.span.open(), paren.span.close());
        if content.is_empty() {
            return Err(syn::Error::new(
                paren.span.join(),
                "empty parentheses: write a value `(e)` or a vector `(x, y)`",
            ));
        }
        if let Some(e) = vector_without_comma(&content) {
            return Err(e);
        }
        let first = self.expr(&content, 0)?;
        if content.is_empty() {
            return Ok(Expr::Paren { open, inner: Box::new(first), close });
        }
        if !content.peek(Token![,]) {
            return Err(content.error("expected `,` (a vector is written `(x, y)`) or `)`"));
        }
        content.parse::<Token![,]>()?;
        if content.is_empty() {
            return Err(syn::Error::new(close, "a vector needs two components: `(x, y)`"));
        }
        let second = self.expr(&content, 0)?;
        if content.peek(Token![,]) {
            content.parse::<Token![,]>()?;
            if !content.is_empty() {
                return Err(content.error("planar vectors have two components: write `(x, y)`"));
            }
        }
        if !content.is_empty() {
            return Err(content.error("expected `)` after the vector's second component"));
        }
        Ok(Expr::Tuple { open, x: Box::new(first), y: Box::new(second), close })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use syn::parse::Parser as _;

    fn show(e: &Expr) -> String {
        match e {
            Expr::Num { value, .. } => format!("{value}"),
            Expr::Var(id) => id.to_string(),
            Expr::Neg { expr, .. } => format!("(-{})", show(expr)),
            Expr::Binary { op, lhs, rhs, .. } => format!("({} {} {})", show(lhs), op.symbol(), show(rhs)),
            Expr::Call { func, args, .. } => {
                format!("{func}({})", args.iter().map(show).collect::<Vec<_>>().join(", "))
            }
            Expr::Tuple { x, y, .. } => format!("<{}, {}>", show(x), show(y)),
            Expr::Paren { inner, .. } => show(inner),
            Expr::Field { base, component, .. } => format!("{}.{:?}", show(base), component),
        }
    }

    fn parse(s: &str) -> String {
        let ts: TokenStream = s.parse().unwrap();
        match parse_expr.parse2(ts) {
            Ok(e) => show(&e),
            Err(e) => format!("error: {e}"),
        }
    }

    /// Only a keyword called as a function is said to be one: a name is not, wherever the
    /// error path meets it.
    #[test]
    fn a_keyword_called_is_told_and_a_name_is_not() {
        let called = |s: &str| {
            let ts: TokenStream = s.parse().unwrap();
            (|input: ParseStream| {
                let told = keyword_called(input).map(|e| e.to_string());
                input.parse::<TokenStream>()?;
                Ok(told)
            })
            .parse2(ts)
            .unwrap()
        };
        assert!(called("if(x)").is_some_and(|m| m.starts_with("`if` is a Rust keyword")));
        assert!(called("match(x, 1)").is_some_and(|m| m.starts_with("`match` is a Rust keyword")));
        assert_eq!(called("sin(x)"), None);
        assert_eq!(called("iff(x)"), None);
    }

    #[test]
    fn precedence() {
        assert_eq!(parse("a + r @ phi"), "(a + (r @ phi))");
        assert_eq!(parse("2 * r @ phi"), "((2 * r) @ phi)");
        assert_eq!(parse("r @ (phi + g)"), "(r @ (phi + g))");
        assert_eq!(parse("-x^2"), "(-(x ^ 2))");
        assert_eq!(parse("a^b^c"), "(a ^ (b ^ c))");
        assert_eq!(parse("a - b - c"), "((a - b) - c)");
        assert_eq!(parse("a / b * c"), "((a / b) * c)");
        assert_eq!(parse("x^-1"), "(x ^ (-1))");
        assert_eq!(parse("(0, e) + r @ p"), "(<0, e> + (r @ p))");
        assert_eq!(parse("atan2(y, x) * 2"), "(atan2(y, x) * 2)");
        assert_eq!(parse("(a + b).x"), "(a + b).X");
        assert_eq!(parse("2 * -x"), "(2 * (-x))");
    }

    #[test]
    fn show_round_trips_the_source() {
        for src in ["a + r @ (phi + g)", "-x^2", "atan2(y, x) * 2", "(a + b).x", "(0, e) - 2.5 * l @ psi"] {
            let ts: TokenStream = src.parse().unwrap();
            let e = parse_expr.parse2(ts).unwrap();
            assert_eq!(e.show(), src);
        }
    }

    #[test]
    fn a_product_without_its_operator_is_named_but_vectors_are_left_alone() {
        assert!(parse("2(a + b)").contains("write `2 * (a + b)` for a product"), "{}", parse("2(a + b)"));
        assert!(parse("(a + b) 3").contains("write `(a + b) * 3` for a product"));
        assert!(parse("2pi").contains("write `2 * pi` for a product"));
        assert!(parse("2f32").contains("number suffixes are not needed"));
        // `10 - 15`: syn takes `- 15` for a negative literal; it is an operator and a number.
        assert_eq!(parse("10 - 15"), "(10 - 15)");
        // A vector next to a value is some other mistake (`force f at (x, 0) (p, 0)` lacks `=`):
        // parsing stops before it, for the item to report.
        assert_eq!(parse_prefix("(x, 0) (p, 0)"), "<x, 0>");
        assert_eq!(parse_prefix("(a + b) (p, 0)"), "(a + b)");
    }

    /// The expression at the start of `s`, leaving the rest unparsed.
    fn parse_prefix(s: &str) -> String {
        let ts: TokenStream = s.parse().unwrap();
        let parser = |input: ParseStream| {
            let e = parse_expr(input)?;
            let _: TokenStream = input.parse()?;
            Ok(e)
        };
        match parser.parse2(ts) {
            Ok(e) => show(&e),
            Err(e) => format!("error: {e}"),
        }
    }

    #[test]
    fn errors_are_reported_not_panicked() {
        assert!(parse("").starts_with("error"));
        assert!(parse("(a, b, c)").starts_with("error"));
        assert!(parse("()").starts_with("error"));
        assert!(parse("1f32").starts_with("error"));
        assert!(parse("a.z").starts_with("error"));
        let deep = format!("{}x{}", "(".repeat(500), ")".repeat(500));
        assert!(parse(&deep).contains("nested"));
        let long = vec!["x"; 1000].join(" + ");
        assert!(parse(&long).contains("chained"));
        let fields = format!("v{}", ".x".repeat(100_000));
        assert!(parse(&fields).contains("chained"));
    }
}
