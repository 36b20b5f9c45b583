//! Syntax tree of a `mechanism!` declaration and its parser.
//!
//! ```text
//! /// docs
//! #[kinloop(dense)]                    // optional: no block decomposition, dense LU
//! #[kinloop(newton)]                   // optional: no closed-form blocks
//! pub struct Name {
//!     params a, b = 1.0, c;            // design parameters (optional default values)
//!     input phi;                       // or: inputs th1, th2;
//!     unknowns q1 = 0.5, s = -l;       // unknowns with optional initial guesses
//!     let name = expr;                 // named intermediate (scalar or vector)
//!     loop name: vec == vec;           // one vector loop = two scalar equations
//!     eq name: scalar == scalar;       // one scalar equation
//!     point name = vec;                // named output point (x, y)
//!     output name = scalar;            // named scalar output
//!     body name: mass m, com p, inertia j, turns angle;   // dynamics: a rigid body
//!     force name at p = vec;           // a force at a point (an expression of the state)
//!     torque name on angle = scalar;   // a torque on an input or an angle unknown
//!     gravity vec;                     // the gravitational acceleration
//! }
//! ```
//!
//! The parser recovers at `;` after an error, so all syntax errors of a declaration are reported
//! together.

use super::expr::{Expr, SpanRange};
use super::item::parse_item;
use super::{limits, names};
use proc_macro2::{Span, TokenStream};
use syn::parse::{ParseStream, Parser};
use syn::{Attribute, Ident, Token, Visibility};

/// A whole declaration.
pub struct MechanismDef {
    /// Doc comments on the declaration, for the generated struct.
    pub docs: Vec<Attribute>,
    /// The `#[kinloop(...)]` options.
    pub options: Options,
    /// Visibility of the struct, given to every generated type.
    pub vis: Visibility,
    /// The mechanism's name.
    pub name: Ident,
    /// The body's items, in order.
    pub items: Vec<Item>,
    /// Span of the `{ ... }` body, for errors about what is missing from it.
    pub body: Span,
}

/// The `#[kinloop(...)]` options, each with the span of its word (for errors about it).
#[derive(Default)]
pub struct Options {
    /// `#[kinloop(dense)]`: solve every unknown in one block, with a dense LU.
    pub dense: Option<Span>,
    /// `#[kinloop(sensitivities)]`: also generate the parameter sensitivities.
    pub sensitivities: Option<Span>,
    /// `#[kinloop(newton)]`: solve every nonlinear block by Newton, even where a closed form
    /// exists (closed-form hook: the option).
    pub newton: Option<Span>,
}

/// A declared name with its doc comments and optional `= value`.
pub struct Decl {
    /// Doc comments on the name, for the generated field.
    pub docs: Vec<Attribute>,
    /// The declared name.
    pub name: Ident,
    /// Default value (parameters) or initial guess (unknowns), if given.
    pub value: Option<Expr>,
}

/// Which list a declaration item declares.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum DeclKind {
    /// `params`: design parameters.
    Params,
    /// `input`, `inputs`: the driven coordinates.
    Inputs,
    /// `unknowns`: solved from the equations.
    Unknowns,
}

/// What one item of the body declares.
pub enum ItemKind {
    /// `params`, `input(s)` or `unknowns` with their names.
    Decls(DeclKind, Vec<Decl>),
    /// `let name = expr;`: a named intermediate value.
    Let {
        /// The name.
        name: Ident,
        /// The value, a scalar or a vector.
        value: Expr,
    },
    /// `loop name: vector == vector;`: one vector loop, two scalar equations.
    Loop {
        /// The loop's name.
        name: Ident,
        /// The left side.
        lhs: Expr,
        /// The right side (`0` for the zero vector).
        rhs: Expr,
        /// The `==` token.
        eq: Span,
    },
    /// `eq name: scalar == scalar;`: one scalar equation.
    Eq {
        /// The equation's name.
        name: Ident,
        /// The left side.
        lhs: Expr,
        /// The right side.
        rhs: Expr,
        /// The `==` token.
        eq: Span,
    },
    /// `point name = vector;`: an output point.
    Point {
        /// The point's name.
        name: Ident,
        /// Its position.
        value: Expr,
    },
    /// `output name = scalar;`: a scalar output.
    Output {
        /// The output's name.
        name: Ident,
        /// Its value.
        value: Expr,
    },
    /// `body name: mass m, com s, inertia j, turns phi;` (`inertia` and `turns` optional).
    Body(BodyDef),
    /// `force name at point = vector;`
    Force {
        /// The force's name.
        name: Ident,
        /// The point it acts at.
        at: Expr,
        /// The force vector.
        value: Expr,
    },
    /// `torque name on angle = scalar;`
    Torque {
        /// The torque's name.
        name: Ident,
        /// The input or angle unknown it acts on.
        on: Ident,
        /// The torque.
        value: Expr,
    },
    /// `gravity vector;`
    Gravity {
        /// The gravitational acceleration.
        value: Expr,
    },
}

/// A rigid body of the machine's dynamics.
pub struct BodyDef {
    /// The body's name.
    pub name: Ident,
    /// Its mass, an expression of the parameters.
    pub mass: Expr,
    /// Its centre of mass, a point.
    pub com: Expr,
    /// Its moment of inertia about the centre of mass (zero when not given).
    pub inertia: Option<Expr>,
    /// The angle the body turns with (none for a slider).
    pub turns: Option<Ident>,
    /// The last token of the item, for errors about the whole body.
    pub end: Span,
}

/// One item of the body, with its doc comments.
pub struct Item {
    /// Doc comments on the item (kept on the fields of points and outputs).
    pub docs: Vec<Attribute>,
    /// The item's keyword (`loop`, `params`, ...).
    pub keyword: Span,
    /// What the item declares.
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
            ItemKind::Body(b) => start.to(SpanRange::single(b.end)),
            ItemKind::Force { value, .. } | ItemKind::Torque { value, .. } | ItemKind::Gravity { value } => {
                start.to(value.range())
            }
        }
    }
}

/// Collects errors so that every mistake is reported at once.
#[derive(Default)]
pub struct Errors(Option<syn::Error>);

impl Errors {
    /// Adds an error to the others.
    pub fn push(&mut self, e: syn::Error) {
        match &mut self.0 {
            Some(all) => all.combine(e),
            None => self.0 = Some(e),
        }
    }

    /// `value` if no error was pushed, else all the errors combined.
    pub fn finish<T>(self, value: T) -> Result<T, syn::Error> {
        match self.0 {
            Some(e) => Err(e),
            None => Ok(value),
        }
    }

    /// Whether no error was pushed.
    pub fn is_empty(&self) -> bool {
        self.0.is_none()
    }

    /// The combined errors, if any.
    pub fn into_error(self) -> Option<syn::Error> {
        self.0
    }
}

/// Parses a declaration. Never panics; all syntax errors found are combined into one.
pub fn parse(tokens: TokenStream) -> Result<MechanismDef, syn::Error> {
    match parse_recover(tokens) {
        (Some(def), None) => Ok(def),
        (_, Some(e)) => Err(e),
        (None, None) => Err(syn::Error::new(Span::call_site(), SHAPE)),
    }
}

/// Parses a declaration as far as it goes: the declaration (with the items that parsed) as soon
/// as its name is known, and the combined syntax errors, if any. The partial declaration lets
/// the macro emit fallback items next to the errors.
pub fn parse_recover(tokens: TokenStream) -> (Option<MechanismDef>, Option<syn::Error>) {
    // Before syn sees the tokens: its token buffer recurses into every bracket.
    if let Err(e) = limits::check(&tokens) {
        return (None, Some(e));
    }
    let (def, errors) = parse_tokens(tokens);
    let Some(mut def) = def else { return (None, errors) };
    let (name_ok, problems) = names::check(&mut def);
    let mut all = Errors(errors);
    for e in problems {
        all.push(e);
    }
    (name_ok.then_some(def), all.into_error())
}

/// The parser proper, on tokens whose size and depth [`limits::check`] accepted.
fn parse_tokens(tokens: TokenStream) -> (Option<MechanismDef>, Option<syn::Error>) {
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
        Some((def, errors)) => (def, errors.into_error()),
        None => (None, Some(verdict.err().unwrap_or_else(|| syn::Error::new(Span::call_site(), SHAPE)))),
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
pub(super) fn skip_item(input: ParseStream) {
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

fn parse_def(input: ParseStream) -> (Option<MechanismDef>, Errors) {
    let mut errors = Errors::default();
    let def = parse_def_into(input, &mut errors);
    (def, errors)
}

/// Parses the declaration, pushing every error into `errors`; returns the declaration once its
/// name is known (with the items that parsed), `None` before that.
fn parse_def_into(input: ParseStream, errors: &mut Errors) -> Option<MechanismDef> {
    let fail = |errors: &mut Errors, e: syn::Error| {
        errors.push(e);
        None
    };
    if input.is_empty() {
        return fail(errors, input.error(SHAPE));
    }
    let attrs = match Attribute::parse_outer(input) {
        Ok(a) => a,
        Err(e) => return fail(errors, e),
    };
    let (docs, options) = split_attributes(attrs, errors);
    let vis: Visibility = match input.parse() {
        Ok(v) => v,
        Err(e) => return fail(errors, e),
    };
    if !input.peek(Token![struct]) {
        return fail(errors, input.error(SHAPE));
    }
    if let Err(e) = input.parse::<Token![struct]>() {
        return fail(errors, e);
    }
    let name: Ident = match input.parse() {
        Ok(n) => n,
        Err(_) => return fail(errors, input.error("expected the mechanism's name: `pub struct Name { ... }`")),
    };
    let mut def = MechanismDef { docs, options, vis, name, items: Vec::new(), body: Span::call_site() };
    def.body = def.name.span();
    if input.peek(Token![<]) {
        errors.push(input.error(
            "a mechanism cannot be generic; remove `<...>`: its parameters are `f64` fields declared with `params`",
        ));
        return Some(def);
    }
    if !input.peek(syn::token::Brace) {
        errors.push(input.error("expected `{` with the mechanism's items: `pub struct Name { params ...; ... }`"));
        return Some(def);
    }
    if let Err(e) = parse_body(input, &mut def, errors) {
        errors.push(e);
    }
    if !input.is_empty() {
        errors.push(
            input.error("unexpected tokens after the mechanism's `{ ... }`; declare one mechanism per `mechanism!`"),
        );
        skip_all(input);
    }
    Some(def)
}

/// Splits the attributes before a mechanism into its doc comments and its `#[kinloop(...)]`
/// options, pushing an error for any other attribute.
fn split_attributes(attrs: Vec<Attribute>, errors: &mut Errors) -> (Vec<Attribute>, Options) {
    let mut docs = Vec::new();
    let mut options = Options::default();
    for attr in attrs {
        if attr.path().is_ident("doc") {
            docs.push(attr);
        } else if attr.path().is_ident("kinloop") {
            if let Err(e) = attr.parse_nested_meta(|meta| parse_option(&meta, &mut options)) {
                errors.push(e);
            }
        } else {
            let msg = if attr.path().is_ident("derive") {
                "remove `#[derive(...)]`: kinloop derives Clone, Copy, Debug and PartialEq itself, \
                 and implements Default when every parameter has a default value"
            } else {
                "only doc comments (`///`) and `#[kinloop(...)]` options (`dense`, `newton`, `sensitivities`) are \
                 accepted before a mechanism"
            };
            errors.push(syn::Error::new_spanned(attr.path(), msg));
        }
    }
    (docs, options)
}

/// One option of `#[kinloop(...)]`, recorded with its span.
fn parse_option(meta: &syn::meta::ParseNestedMeta, options: &mut Options) -> syn::Result<()> {
    let span = meta.path.get_ident().map_or(Span::call_site(), Ident::span);
    if meta.path.is_ident("dense") {
        options.dense = Some(span);
    } else if meta.path.is_ident("sensitivities") {
        options.sensitivities = Some(span);
    } else if meta.path.is_ident("newton") {
        // Closed-form hook: the option forcing Newton.
        options.newton = Some(span);
    } else {
        return Err(meta.error(
            "unknown kinloop option; the supported options are `#[kinloop(dense)]`, \
             `#[kinloop(newton)]` and `#[kinloop(sensitivities)]`",
        ));
    }
    Ok(())
}

/// Parses `{ items }`, recovering at `;` after an item's error.
fn parse_body(input: ParseStream, def: &mut MechanismDef, errors: &mut Errors) -> syn::Result<()> {
    let content;
    let brace = syn::braced!(content in input);
    def.body = brace.span.join();
    while !content.is_empty() {
        match parse_item(&content, errors) {
            Ok(item) => def.items.push(item),
            Err(e) => {
                errors.push(e);
                skip_item(&content);
            }
        }
    }
    Ok(())
}
