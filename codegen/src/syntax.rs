//! Syntax tree of a `mechanism!` declaration and its parser.
//!
//! ```text
//! /// docs
//! #[kinloop(dense)]                    // optional: no block decomposition
//! pub struct Name {
//!     params a, b = 1.0, c;            // design parameters (optional default values)
//!     input phi;                       // or: inputs th1, th2;
//!     unknowns q1 = 0.5, s = -l;       // unknowns with optional initial guesses
//!     let name = expr;                 // named intermediate (scalar or vector)
//!     loop name: vec == vec;           // one vector loop = two scalar equations
//!     eq name: scalar == scalar;       // one scalar equation
//!     point name = vec;                // named output point (x, y)
//!     output name = scalar;            // named scalar output
//! }
//! ```
//!
//! The parser recovers at `;` after an error, so all syntax errors of a declaration are reported
//! together.

use crate::expr::{Expr, SpanRange, parse_expr};
use proc_macro2::{Span, TokenStream};
use syn::parse::{ParseStream, Parser};
use syn::{Attribute, Ident, Token, Visibility};

mod kw {
    syn::custom_keyword!(params);
    syn::custom_keyword!(param);
    syn::custom_keyword!(input);
    syn::custom_keyword!(inputs);
    syn::custom_keyword!(unknowns);
    syn::custom_keyword!(unknown);
    syn::custom_keyword!(point);
    syn::custom_keyword!(output);
    syn::custom_keyword!(eq);
    syn::custom_keyword!(dense);
}

/// A whole declaration.
pub struct MechanismDef {
    pub docs: Vec<Attribute>,
    pub options: Options,
    pub vis: Visibility,
    pub name: Ident,
    pub items: Vec<Item>,
    /// Span of the `{ ... }` body, for errors about what is missing from it.
    pub body: Span,
}

#[derive(Default)]
pub struct Options {
    /// `#[kinloop(dense)]`: solve every unknown in one block.
    pub dense: Option<Span>,
}

/// A declared name with its doc comments and optional `= value`.
pub struct Decl {
    pub docs: Vec<Attribute>,
    pub name: Ident,
    pub value: Option<Expr>,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum DeclKind {
    Params,
    Inputs,
    Unknowns,
}

pub enum ItemKind {
    Decls(DeclKind, Vec<Decl>),
    Let { name: Ident, value: Expr },
    Loop { name: Ident, lhs: Expr, rhs: Expr, eq: Span },
    Eq { name: Ident, lhs: Expr, rhs: Expr, eq: Span },
    Point { name: Ident, value: Expr },
    Output { name: Ident, value: Expr },
}

pub struct Item {
    pub docs: Vec<Attribute>,
    /// The item's keyword (`loop`, `params`, ...).
    pub keyword: Span,
    pub kind: ItemKind,
}

impl Item {
    /// The range from the keyword to the end of the item, for errors about a whole item.
    pub fn range(&self) -> SpanRange {
        let start = SpanRange::single(self.keyword);
        match &self.kind {
            ItemKind::Decls(_, decls) => match decls.last() {
                Some(d) => start.to(d.value.as_ref().map_or(SpanRange::single(d.name.span()), Expr::range)),
                None => start,
            },
            ItemKind::Let { value, .. } | ItemKind::Point { value, .. } | ItemKind::Output { value, .. } => {
                start.to(value.range())
            }
            ItemKind::Loop { rhs, .. } | ItemKind::Eq { rhs, .. } => start.to(rhs.range()),
        }
    }
}

/// Collects errors so that every mistake is reported at once.
#[derive(Default)]
pub struct Errors(Option<syn::Error>);

impl Errors {
    pub fn push(&mut self, e: syn::Error) {
        match &mut self.0 {
            Some(all) => all.combine(e),
            None => self.0 = Some(e),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_none()
    }

    pub fn finish<T>(self, value: T) -> Result<T, syn::Error> {
        match self.0 {
            Some(e) => Err(e),
            None => Ok(value),
        }
    }

    pub fn into_error(self) -> Option<syn::Error> {
        self.0
    }
}

/// Parses a declaration. Never panics; all syntax errors found are combined into one.
pub fn parse(tokens: TokenStream) -> Result<MechanismDef, syn::Error> {
    let mut out = None;
    // The parser stores its own verdict in `out`: syn's end-of-input checks cannot then replace
    // the collected errors by a generic "unexpected token" after recovery skipped some tokens.
    let verdict = (|input: ParseStream| {
        out = Some(parse_def(input));
        skip_all(input);
        Ok(())
    })
    .parse2(tokens);
    match out {
        Some(result) => result,
        None => Err(verdict.err().unwrap_or_else(|| syn::Error::new(Span::call_site(), "empty declaration"))),
    }
}

fn skip_all(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((_, next)) = rest.token_tree() {
            rest = next;
        }
        Ok(((), rest))
    });
}

/// Skips to just after the next top-level `;` (error recovery).
fn skip_item(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tt, next)) = rest.token_tree() {
            rest = next;
            if let proc_macro2::TokenTree::Punct(p) = &tt
                && p.as_char() == ';'
            {
                break;
            }
        }
        Ok(((), rest))
    });
}

const SHAPE: &str = "expected a declaration: `pub struct Name { params ...; input ...; unknowns ...; loop ...; }`";

fn parse_def(input: ParseStream) -> Result<MechanismDef, syn::Error> {
    let mut errors = Errors::default();
    if input.is_empty() {
        return Err(input.error(SHAPE));
    }
    let attrs = Attribute::parse_outer(input)?;
    let mut docs = Vec::new();
    let mut options = Options::default();
    for attr in attrs {
        if attr.path().is_ident("doc") {
            docs.push(attr);
        } else if attr.path().is_ident("kinloop") {
            let res = attr.parse_nested_meta(|meta| {
                if meta.path.is_ident("dense") {
                    options.dense = Some(meta.path.get_ident().map_or(Span::call_site(), Ident::span));
                    Ok(())
                } else {
                    Err(meta.error("unknown kinloop option; the supported option is `#[kinloop(dense)]`"))
                }
            });
            if let Err(e) = res {
                errors.push(e);
            }
        } else {
            errors.push(syn::Error::new_spanned(
                &attr,
                "only doc comments and `#[kinloop(...)]` are accepted here \
                 (kinloop derives Clone, Copy, Debug and PartialEq itself)",
            ));
        }
    }
    let vis: Visibility = input.parse()?;
    if !input.peek(Token![struct]) {
        return Err(input.error(SHAPE));
    }
    input.parse::<Token![struct]>()?;
    let name: Ident = input.parse()?;
    if input.peek(Token![<]) {
        return Err(
            input.error("a mechanism cannot be generic; its parameters are `f64` fields declared with `params`")
        );
    }
    if !input.peek(syn::token::Brace) {
        return Err(input.error("expected `{` with the mechanism's items"));
    }
    let content;
    let brace = syn::braced!(content in input);
    let mut items = Vec::new();
    while !content.is_empty() {
        match parse_item(&content) {
            Ok(item) => items.push(item),
            Err(e) => {
                errors.push(e);
                skip_item(&content);
            }
        }
    }
    if !input.is_empty() {
        errors.push(
            input.error("unexpected tokens after the mechanism's `{ ... }`; declare one mechanism per `mechanism!`"),
        );
        skip_all(input);
    }
    errors.finish(MechanismDef { docs, options, vis, name, items, body: brace.span.join() })
}

fn parse_item(input: ParseStream) -> syn::Result<Item> {
    let attrs = Attribute::parse_outer(input)?;
    let mut docs = Vec::new();
    for attr in attrs {
        if attr.path().is_ident("doc") {
            docs.push(attr);
        } else {
            return Err(syn::Error::new_spanned(&attr, "only doc comments (`///`) are accepted before an item"));
        }
    }
    let keyword = input.span();
    let look = input.lookahead1();
    let kind = if look.peek(kw::params) || look.peek(kw::param) {
        skip_keyword(input)?;
        ItemKind::Decls(DeclKind::Params, parse_decls(input, DeclKind::Params)?)
    } else if look.peek(kw::input) || look.peek(kw::inputs) {
        skip_keyword(input)?;
        ItemKind::Decls(DeclKind::Inputs, parse_decls(input, DeclKind::Inputs)?)
    } else if look.peek(kw::unknowns) || look.peek(kw::unknown) {
        skip_keyword(input)?;
        ItemKind::Decls(DeclKind::Unknowns, parse_decls(input, DeclKind::Unknowns)?)
    } else if look.peek(Token![let]) {
        input.parse::<Token![let]>()?;
        let (name, value) = parse_binding(input, "let")?;
        ItemKind::Let { name, value }
    } else if look.peek(kw::point) {
        input.parse::<kw::point>()?;
        let (name, value) = parse_binding(input, "point")?;
        ItemKind::Point { name, value }
    } else if look.peek(kw::output) {
        input.parse::<kw::output>()?;
        let (name, value) = parse_binding(input, "output")?;
        ItemKind::Output { name, value }
    } else if look.peek(Token![loop]) {
        input.parse::<Token![loop]>()?;
        let (name, lhs, rhs, eq) = parse_equation(input, "loop")?;
        ItemKind::Loop { name, lhs, rhs, eq }
    } else if look.peek(kw::eq) {
        input.parse::<kw::eq>()?;
        let (name, lhs, rhs, eq) = parse_equation(input, "eq")?;
        ItemKind::Eq { name, lhs, rhs, eq }
    } else {
        let mut err = look.error();
        if input.peek(Ident) {
            err = input.error(
                "expected an item: `params`, `input`, `inputs`, `unknowns`, `let`, `loop`, `eq`, `point` or `output`",
            );
        }
        return Err(err);
    };
    expect_semicolon(input)?;
    Ok(Item { docs, keyword, kind })
}

fn skip_keyword(input: ParseStream) -> syn::Result<()> {
    input.parse::<Ident>().map(drop)
}

fn expect_semicolon(input: ParseStream) -> syn::Result<()> {
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
        Ok(())
    } else if input.peek(Token![=]) {
        Err(input.error("unexpected `=`: equations are written with `==`"))
    } else {
        Err(input.error("expected `;` at the end of the item"))
    }
}

fn parse_decls(input: ParseStream, kind: DeclKind) -> syn::Result<Vec<Decl>> {
    let mut decls = Vec::new();
    loop {
        let attrs = Attribute::parse_outer(input)?;
        if let Some(bad) = attrs.iter().find(|a| !a.path().is_ident("doc")) {
            return Err(syn::Error::new_spanned(bad, "only doc comments (`///`) are accepted before a name"));
        }
        if !input.peek(Ident) {
            return Err(input.error(match kind {
                DeclKind::Params => "expected a parameter name",
                DeclKind::Inputs => "expected an input name",
                DeclKind::Unknowns => "expected an unknown's name",
            }));
        }
        let name: Ident = input.parse()?;
        let value = if input.peek(Token![=]) && !input.peek(Token![==]) {
            let eq = input.parse::<Token![=]>()?;
            if kind == DeclKind::Inputs {
                return Err(syn::Error::new(
                    eq.span,
                    "inputs take no value in the declaration; they are given when the mechanism is solved",
                ));
            }
            Some(parse_expr(input)?)
        } else if input.peek(Token![:]) {
            return Err(input.error("no type is needed: every parameter, input and unknown is an `f64`"));
        } else {
            None
        };
        decls.push(Decl { docs: attrs, name, value });
        if input.peek(Token![,]) {
            input.parse::<Token![,]>()?;
            if input.peek(Token![;]) {
                break;
            }
        } else {
            break;
        }
    }
    Ok(decls)
}

fn parse_binding(input: ParseStream, what: &str) -> syn::Result<(Ident, Expr)> {
    if !input.peek(Ident) {
        return Err(input.error(format!("expected a name: `{what} name = expression;`")));
    }
    let name: Ident = input.parse()?;
    if input.peek(Token![:]) {
        return Err(input.error(format!("no type is needed: write `{what} {name} = expression;`")));
    }
    if !input.peek(Token![=]) || input.peek(Token![==]) {
        return Err(input.error(format!("expected `=`: `{what} {name} = expression;`")));
    }
    input.parse::<Token![=]>()?;
    let value = parse_expr(input)?;
    Ok((name, value))
}

fn parse_equation(input: ParseStream, what: &str) -> syn::Result<(Ident, Expr, Expr, Span)> {
    if !input.peek(Ident) {
        return Err(input.error(format!(
            "expected the equation's name: `{what} name: lhs == rhs;` (names appear in error messages)"
        )));
    }
    let name: Ident = input.parse()?;
    if !input.peek(Token![:]) || input.peek(Token![::]) {
        return Err(input.error(format!("expected `:` after the name: `{what} {name}: lhs == rhs;`")));
    }
    input.parse::<Token![:]>()?;
    let lhs = parse_expr(input)?;
    if input.peek(Token![=]) && !input.peek(Token![==]) {
        return Err(input.error("expected `==`: an equation is written `lhs == rhs`"));
    }
    if !input.peek(Token![==]) {
        return Err(input.error(format!("expected `==`: `{what} {name}: lhs == rhs;`")));
    }
    let eq = input.parse::<Token![==]>()?.spans[0];
    let rhs = parse_expr(input)?;
    Ok((name, lhs, rhs, eq))
}
