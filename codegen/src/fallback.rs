//! Items emitted next to the `compile_error!`s of a rejected declaration, so that the user's
//! code around the mechanism does not drown the real errors in secondary ones ("cannot find
//! type `FourBar`", "no field `q`").
//!
//! The items are the whole surface of an accepted declaration, built here from the syntax: the
//! named types of [`crate::emit::surface`] (with `Default` when the default values are known),
//! the constants, the `Mechanism` and `Named` implementations with the inherent named API, and
//! `mass_model` or its explanation. The kernels' bodies are the runtime's `rejected()`: never
//! run, because a crate with a `compile_error!` does not compile; they only let the user's calls
//! (`m.solve(x)?.q.beta`) type-check, so that the declaration's errors are the only ones.

use crate::emit::dims::Dims;
use crate::emit::literals::lit;
use crate::emit::runtime_path::runtime;
use crate::emit::surface::{Field, Surface, items};
use crate::emit::type_names::Types;
use crate::emit::{dynamics, sensitivities};
use crate::front::expr::Expr;
use crate::front::syntax::{DeclKind, ItemKind, MechanismDef};
use crate::plan::param_defaults;
use proc_macro2::{Ident, TokenStream};
use quote::quote;
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
    /// The declaration has masses, inertias or loads: `mass_model` exists (else it explains).
    dynamics: bool,
    /// The declaration asks for `#[kinloop(sensitivities)]`: their API exists (else it explains).
    sensitivities: bool,
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
        let mut dynamics = false;
        // Inputs, unknowns, points and outputs are the columns of one table (`Name::COL`) and
        // share one namespace, as the model's names do: the first declaration of a name keeps it.
        let (mut seen_p, mut seen_columns) = (HashSet::new(), HashSet::new());
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
                            DeclKind::Inputs => _ = push_unique(&mut s.inputs, &mut seen_columns, &d.docs, &d.name),
                            DeclKind::Unknowns => _ = push_unique(&mut s.unknowns, &mut seen_columns, &d.docs, &d.name),
                        }
                    }
                }
                ItemKind::Point { name, .. } => _ = push_unique(&mut s.points, &mut seen_columns, &item.docs, name),
                ItemKind::Output { name, .. } => _ = push_unique(&mut s.scalars, &mut seen_columns, &item.docs, name),
                ItemKind::Body(_) | ItemKind::Force { .. } | ItemKind::Torque { .. } | ItemKind::Gravity { .. } => {
                    dynamics = true
                }
                _ => {}
            }
        }
        Shape { surface: s, literal_defaults, dynamics, sensitivities: def.options.sensitivities.is_some() }
    }

    /// The fallback items. `defaults` are the parameters' default values when the model knows
    /// them (otherwise the literal defaults of the syntax are used, if all are literals).
    pub fn items(mut self, defaults: Option<Vec<f64>>) -> TokenStream {
        let n = self.surface.params.len();
        self.surface.defaults = defaults.filter(|d| d.len() == n).or_else(|| param_defaults(self.literal_defaults));
        let types = Types::of(&self.surface.name);
        let mut out = items(&self.surface, &types);
        out.extend(rejected_api(&self.surface, &types));
        out.extend(if self.dynamics { rejected_mass_model(&self.surface, &types) } else { dynamics::absent(&types) });
        out.extend(if self.sensitivities {
            rejected_sensitivities(&self.surface, &types)
        } else {
            sensitivities::absent(&types)
        });
        out
    }
}

/// Plain names, for the name constants.
fn plain(fields: &[Field]) -> Vec<String> {
    fields.iter().map(|f| f.name.unraw().to_string()).collect()
}

/// The constants, `Mechanism`, `Named` and the inherent named API of a rejected declaration:
/// one invocation of the runtime's macro.
fn rejected_api(s: &Surface, t: &Types) -> TokenStream {
    let rt = runtime();
    let Types { name, inputs, unknowns, outputs, state, motion, plain: plain_name, .. } = t;
    let outputs_str: Vec<String> = s
        .points
        .iter()
        .flat_map(|p| {
            let p = p.name.unraw();
            [format!("{p}.x"), format!("{p}.y")]
        })
        .chain(plain(&s.scalars))
        .collect();
    let (n, ni, no, np) = (lit(s.unknowns.len()), lit(s.inputs.len()), lit(outputs_str.len()), lit(s.params.len()));
    let params = s.params.iter().enumerate().map(|(k, f)| {
        let (field, k, plain) = (&f.name, lit(k), f.name.unraw().to_string());
        quote!(#field #k #plain)
    });
    let (is, us) = (plain(&s.inputs), plain(&s.unknowns));
    quote! {
        #rt::rejected_mechanism!(
            #name, #inputs, #unknowns, #outputs, #state, #motion, #n, #ni, #no, #np, #plain_name,
            params [#(#params),*], inputs [#(#is),*], unknowns [#(#us),*], outputs [#(#outputs_str),*]
        );
    }
}

/// The sensitivity API of a rejected declaration with `#[kinloop(sensitivities)]`: the named
/// types, `Sensitivities`, `NamedSensitivities` and the inherent methods, never run.
fn rejected_sensitivities(s: &Surface, t: &Types) -> TokenStream {
    let rt = runtime();
    let Types { name, inputs, unknowns, state, sens, .. } = t;
    let no = 2 * s.points.len() + s.scalars.len();
    let dims = Dims { n: lit(s.unknowns.len()), ni: lit(s.inputs.len()), no: lit(no), np: lit(s.params.len()) };
    let types = sensitivities::types(&s.vis, &s.params, &dims, s.inputs.len(), t);
    let Dims { n, ni, no, np } = dims;
    let input = quote!(_input: impl ::core::convert::Into<#inputs>);
    let ret = quote!(::core::result::Result<(#state, #sens), #rt::Error>);
    let flat = quote!(::core::result::Result<(#rt::Kin<#n, #ni, #no>, #rt::Sens<#n, #ni, #no, #np>), #rt::Error>);
    quote! {
        #types
        impl #name {
            /// The kinematics and their parameter sensitivities (not generated: the declaration
            /// was rejected).
            pub fn sensitivities(&self, #input, _guess: &#unknowns) -> #ret {
                #rt::rejected()
            }
            /// [`Self::sensitivities`] at a solved position (not generated).
            pub fn sensitivities_at(&self, #input, _q: &#unknowns) -> #ret {
                #rt::rejected()
            }
        }
        impl #rt::Sensitivities<#n, #ni, #no, #np> for #name {
            fn params_flat(&self) -> [::core::primitive::f64; #np] {
                #rt::rejected()
            }
            fn with_params_flat(&self, _: [::core::primitive::f64; #np]) -> Self {
                #rt::rejected()
            }
            fn sensitivities_flat(
                &self,
                _: &[::core::primitive::f64; #ni],
                _: &[::core::primitive::f64; #n],
                _: &#rt::NewtonConfig,
            ) -> #flat {
                #rt::rejected()
            }
            fn sensitivities_at_flat(
                &self,
                _: &[::core::primitive::f64; #ni],
                _: &[::core::primitive::f64; #n],
                _: &#rt::NewtonConfig,
            ) -> #flat {
                #rt::rejected()
            }
        }
        impl #rt::NamedSensitivities<#n, #ni, #no, #np> for #name {
            type Sens = #sens;
        }
    }
}

/// `mass_model` of a rejected declaration that declares dynamics items: its signature, never run.
fn rejected_mass_model(s: &Surface, t: &Types) -> TokenStream {
    let (rt, name) = (runtime(), &t.name);
    let no = 2 * s.points.len() + s.scalars.len();
    let (n, ni, no) = (lit(s.unknowns.len()), lit(s.inputs.len()), lit(no));
    quote! {
        impl #name {
            /// The declared bodies, loads and gravity as a mass model (not generated: the
            /// declaration was rejected).
            pub fn mass_model(&self) -> ::core::result::Result<#rt::MassModel<#n, #ni, #no>, #rt::DynamicsError> {
                #rt::rejected()
            }
        }
    }
}
