//! Items emitted next to the `compile_error!`s of a rejected declaration, so that the user's
//! code around the mechanism does not drown the real errors in secondary ones ("cannot find
//! type `FourBar`", "no field `q`").
//!
//! Only what can be stated honestly is emitted: the parameter struct with its fields (and
//! `Default` when the default values are known), the named structs for inputs, unknowns and
//! outputs, and the state and motion structs with their named fields. No method is emitted: a
//! method whose body could not be generated would be a fake that pretends to solve something.
//! Calls of the generated methods therefore still report "no method named ..." — after the
//! errors that explain why.

use crate::expr::Expr;
use crate::items::params_struct;
use crate::syntax::{DeclKind, ItemKind, MechanismDef};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashSet;
use syn::ext::IdentExt;
use syn::{Attribute, Visibility};

/// A declared name and its doc comments.
struct Field {
    docs: Vec<Attribute>,
    name: Ident,
}

/// The names of a declaration, collected from its syntax before the model consumes it.
pub struct Shape {
    docs: Vec<Attribute>,
    vis: Visibility,
    name: Ident,
    params: Vec<Field>,
    /// Default values of the parameters when every one is a number literal.
    literal_defaults: Option<Vec<f64>>,
    inputs: Vec<Field>,
    unknowns: Vec<Field>,
    points: Vec<Field>,
    scalars: Vec<Field>,
}

/// Adds `name` to `fields` unless a field of that name exists (a duplicate was reported).
fn push_unique(fields: &mut Vec<Field>, seen: &mut HashSet<String>, docs: &[Attribute], name: &Ident) {
    if seen.insert(name.unraw().to_string()) {
        fields.push(Field { docs: docs.to_vec(), name: name.clone() });
    }
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

impl Shape {
    pub fn of(def: &MechanismDef) -> Shape {
        let (mut params, mut inputs, mut unknowns, mut points, mut scalars) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let (mut seen_p, mut seen_i, mut seen_u, mut seen_o) =
            (HashSet::new(), HashSet::new(), HashSet::new(), HashSet::new());
        let mut defaults = Some(Vec::new());
        for item in &def.items {
            match &item.kind {
                ItemKind::Decls(kind, decls) => {
                    for d in decls {
                        match kind {
                            DeclKind::Params => {
                                if seen_p.contains(&d.name.unraw().to_string()) {
                                    continue;
                                }
                                push_unique(&mut params, &mut seen_p, &d.docs, &d.name);
                                let v = d.value.as_ref().and_then(literal);
                                defaults = defaults.zip(v).map(|(mut all, v)| {
                                    all.push(v);
                                    all
                                });
                            }
                            DeclKind::Inputs => push_unique(&mut inputs, &mut seen_i, &d.docs, &d.name),
                            DeclKind::Unknowns => push_unique(&mut unknowns, &mut seen_u, &d.docs, &d.name),
                        }
                    }
                }
                ItemKind::Point { name, .. } => push_unique(&mut points, &mut seen_o, &item.docs, name),
                ItemKind::Output { name, .. } => push_unique(&mut scalars, &mut seen_o, &item.docs, name),
                _ => {}
            }
        }
        let literal_defaults = defaults.filter(|d| !d.is_empty());
        Shape {
            docs: def.docs.clone(),
            vis: def.vis.clone(),
            name: def.name.clone(),
            params,
            literal_defaults,
            inputs,
            unknowns,
            points,
            scalars,
        }
    }

    /// The fallback items. `defaults` are the parameters' default values when the model knows
    /// them (otherwise the literal defaults of the syntax are used, if all are literals).
    pub fn items(&self, defaults: Option<Vec<f64>>) -> TokenStream {
        let rt = quote!(::kinloop::__private);
        let Shape { docs, vis, name, .. } = self;
        let base = name.unraw().to_string();
        let (inputs_ty, unknowns_ty, outputs_ty, state_ty, motion_ty) = (
            format_ident!("{}Inputs", base),
            format_ident!("{}Unknowns", base),
            format_ident!("{}Outputs", base),
            format_ident!("{}State", base),
            format_ident!("{}Motion", base),
        );
        let pfields = self.params.iter().map(|f| {
            let (d, n) = (&f.docs, &f.name);
            quote!(#(#d)* pub #n: f64,)
        });
        let defaults = defaults.filter(|d| d.len() == self.params.len()).or_else(|| self.literal_defaults.clone());
        let default_impl = match defaults {
            Some(values) if values.len() == self.params.len() && values.iter().all(|v| v.is_finite()) => {
                let names = self.params.iter().map(|f| &f.name);
                quote! {
                    impl ::core::default::Default for #name {
                        fn default() -> Self {
                            #name { #(#names: #values),* }
                        }
                    }
                }
            }
            _ => quote!(),
        };
        let generic = |ty: &Ident, fields: &[Field], elem: TokenStream| {
            let decl = fields.iter().map(|f| {
                let (d, n) = (&f.docs, &f.name);
                quote!(#(#d)* pub #n: #elem,)
            });
            let marker = if fields.is_empty() {
                quote!(#[doc(hidden)] pub __marker: ::core::marker::PhantomData<T>,)
            } else {
                quote!()
            };
            quote! {
                #[derive(Clone, Copy, Debug, Default, PartialEq)]
                #[allow(non_snake_case)]
                #vis struct #ty<T = f64> {
                    #(#decl)*
                    #marker
                }
            }
        };
        let inputs_struct = generic(&inputs_ty, &self.inputs, quote!(T));
        let unknowns_struct = generic(&unknowns_ty, &self.unknowns, quote!(T));
        let out_fields = self
            .points
            .iter()
            .map(|f| {
                let (d, n) = (&f.docs, &f.name);
                quote!(#(#d)* pub #n: #rt::Vec2<T>,)
            })
            .chain(self.scalars.iter().map(|f| {
                let (d, n) = (&f.docs, &f.name);
                quote!(#(#d)* pub #n: T,)
            }));
        let out_marker = if self.points.is_empty() && self.scalars.is_empty() {
            quote!(#[doc(hidden)] pub __marker: ::core::marker::PhantomData<T>,)
        } else {
            quote!()
        };
        let (v_ty, a_ty) = if self.inputs.len() == 1 {
            (quote!(f64), quote!(f64))
        } else {
            (quote!(#inputs_ty<f64>), quote!(#inputs_ty<#inputs_ty<f64>>))
        };
        let params_struct = params_struct(docs, vis, name, pfields);
        quote! {
            #params_struct
            #default_impl
            #inputs_struct
            #unknowns_struct
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            #[allow(non_snake_case)]
            #vis struct #outputs_ty<T = f64> {
                #(#out_fields)*
                #out_marker
            }
            #[derive(Clone, Copy, Debug, PartialEq)]
            #vis struct #state_ty {
                pub input: #inputs_ty,
                pub q: #unknowns_ty,
                pub dq: #unknowns_ty<#v_ty>,
                pub d2q: #unknowns_ty<#a_ty>,
                pub out: #outputs_ty,
                pub dout: #outputs_ty<#v_ty>,
                pub d2out: #outputs_ty<#a_ty>,
            }
            #[derive(Clone, Copy, Debug, PartialEq)]
            #vis struct #motion_ty {
                pub qdot: #unknowns_ty,
                pub qddot: #unknowns_ty,
                pub out_dot: #outputs_ty,
                pub out_ddot: #outputs_ty,
            }
        }
    }
}
