//! The syntax tree of a `mechanism!` declaration, what the parsers build and the later stages
//! read, with the words of the language that are not Rust's ([`kw`]).
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
//! The tree is apart from its parsers (`declaration`, `item` and `dynamics`) and from the checks
//! of its names ([`super::names`]): they all take their types from here, and this file takes
//! nothing from them.

use super::expr::{Expr, SpanRange};
use proc_macro2::Span;
use syn::{Attribute, Ident, Visibility};

/// The words of the declaration language that are not Rust keywords (`let` and `loop` are), for
/// the parsers to peek and parse.
pub(super) mod kw {
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
    syn::custom_keyword!(body);
    syn::custom_keyword!(force);
    syn::custom_keyword!(torque);
    syn::custom_keyword!(gravity);
    syn::custom_keyword!(at);
    syn::custom_keyword!(on);
    syn::custom_keyword!(doc);
}

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
pub struct Errors(pub(super) Option<syn::Error>);

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
