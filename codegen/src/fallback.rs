//! Items emitted next to the `compile_error!`s of a rejected declaration, so that the user's
//! code around the mechanism does not drown the real errors in secondary ones ("cannot find
//! type `FourBar`", "no field `q`").
//!
//! Only what can be stated honestly is emitted: the named types of [`crate::emit::surface`]
//! (the very items an accepted declaration gets, with `Default` when the default values are
//! known), built here from the syntax. No method is emitted: a method whose body could not be
//! generated would be a fake that pretends to solve something.
//! Calls of the generated methods therefore still report "no method named ..." — after the
//! errors that explain why.

use crate::emit::Types;
use crate::emit::surface::{Field, Surface, items};
use crate::front::expr::Expr;
use crate::front::syntax::{DeclKind, ItemKind, MechanismDef};
use crate::plan::param_defaults;
use proc_macro2::{Ident, TokenStream};
use std::collections::HashSet;
use syn::Attribute;
use syn::ext::IdentExt;

/// Adds `name` to `fields` unless a field of that name exists (a duplicate was reported).
fn push_unique(fields: &mut Vec<Field>, seen: &mut HashSet<String>, docs: &[Attribute], name: &Ident) -> bool {
    let fresh = seen.insert(name.unraw().to_string());
    if fresh {
        fields.push(Field::new(docs, name));
    }
    fresh
}

/// A number literal, possibly negated or parenthesized.
fn literal(e: &Expr) -> Option<f64> {
    match e {
        Expr::Num { value, .. } => Some(*value),
        Expr::Neg { expr, .. } => literal(expr).map(|v| -v),
        Expr::Paren { inner, .. } => literal(inner),
        _ => None,
    }
}

/// The names of a declaration, collected from its syntax before the model consumes it, with
/// the parameters' literal default values.
pub struct Shape {
    surface: Surface,
    literal_defaults: Vec<Option<f64>>,
}

impl Shape {
    /// Collects the names of `def` (as far as it parsed).
    pub fn of(def: &MechanismDef) -> Shape {
        let mut s = Surface {
            docs: def.docs.clone(),
            vis: def.vis.clone(),
            name: def.name.clone(),
            params: Vec::new(),
            defaults: None,
            inputs: Vec::new(),
            unknowns: Vec::new(),
            points: Vec::new(),
            scalars: Vec::new(),
        };
        let mut literal_defaults = Vec::new();
        let (mut seen_p, mut seen_i, mut seen_u, mut seen_o) =
            (HashSet::new(), HashSet::new(), HashSet::new(), HashSet::new());
        for item in &def.items {
            match &item.kind {
                ItemKind::Decls(kind, decls) => {
                    for d in decls {
                        match kind {
                            DeclKind::Params => {
                                if push_unique(&mut s.params, &mut seen_p, &d.docs, &d.name) {
                                    literal_defaults.push(d.value.as_ref().and_then(literal));
                                }
                            }
                            DeclKind::Inputs => _ = push_unique(&mut s.inputs, &mut seen_i, &d.docs, &d.name),
                            DeclKind::Unknowns => _ = push_unique(&mut s.unknowns, &mut seen_u, &d.docs, &d.name),
                        }
                    }
                }
                ItemKind::Point { name, .. } => _ = push_unique(&mut s.points, &mut seen_o, &item.docs, name),
                ItemKind::Output { name, .. } => _ = push_unique(&mut s.scalars, &mut seen_o, &item.docs, name),
                _ => {}
            }
        }
        Shape { surface: s, literal_defaults }
    }

    /// The fallback items. `defaults` are the parameters' default values when the model knows
    /// them (otherwise the literal defaults of the syntax are used, if all are literals).
    pub fn items(mut self, defaults: Option<Vec<f64>>) -> TokenStream {
        let n = self.surface.params.len();
        self.surface.defaults = defaults.filter(|d| d.len() == n).or_else(|| param_defaults(self.literal_defaults));
        items(&self.surface, &Types::of(&self.surface.name))
    }
}
