//! The named types of a mechanism: the parameter struct, `NameInputs`, `NameUnknowns`,
//! `NameOutputs` (generic over the element type so analogs reuse them), `NameState` and
//! `NameMotion`, with their conversions from and to flat arrays.
//!
//! They depend only on the declared names, so the fallback after a rejected declaration emits
//! the same items from the syntax ([`Surface`] is built from either).

use super::literals::lit;
use super::runtime_path::{RUNTIME_ALIAS, runtime};
use super::type_names::Types;
use crate::semantics::model::Model;
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;
use syn::{Attribute, Visibility};

/// A declared name and its doc comments.
pub struct Field {
    pub docs: Vec<Attribute>,
    pub name: Ident,
}

impl Field {
    pub fn new(docs: &[Attribute], name: &Ident) -> Field {
        Field { docs: docs.to_vec(), name: name.clone() }
    }

    /// The doc comments, or `fallback` with the field's name when there are none.
    fn doc(&self, kind: &str) -> TokenStream {
        if self.docs.is_empty() {
            let d = format!(" {kind} `{}`.", self.name.unraw());
            quote!(#[doc = #d])
        } else {
            let d = &self.docs;
            quote!(#(#d)*)
        }
    }
}

/// The declared names of a mechanism.
pub struct Surface {
    pub docs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub params: Vec<Field>,
    /// Default values of the parameters, when every one has one (`Default`).
    pub defaults: Option<Vec<f64>>,
    pub inputs: Vec<Field>,
    pub unknowns: Vec<Field>,
    pub points: Vec<Field>,
    pub scalars: Vec<Field>,
}

impl Surface {
    pub fn of_model(m: &Model, defaults: Option<Vec<f64>>) -> Surface {
        Surface {
            docs: m.docs.clone(),
            vis: m.vis.clone(),
            name: m.name.clone(),
            params: m.params.iter().map(|p| Field::new(&p.docs, &p.name)).collect(),
            defaults,
            inputs: m.inputs.iter().map(|p| Field::new(&p.docs, &p.name)).collect(),
            unknowns: m.unknowns.iter().map(|p| Field::new(&p.docs, &p.name)).collect(),
            points: m.points.iter().map(|p| Field::new(&p.docs, &p.name)).collect(),
            scalars: m.scalars.iter().map(|p| Field::new(&p.docs, &p.name)).collect(),
        }
    }

    /// Number of flat output columns: `x`, `y` per point, then the scalars.
    pub fn n_outputs(&self) -> usize {
        2 * self.points.len() + self.scalars.len()
    }
}

/// Every named type of `s` with its conversions.
pub fn items(s: &Surface, t: &Types) -> TokenStream {
    let plain = &t.plain;
    let inputs_doc = format!(
        "Inputs (generalized coordinates) of [`{plain}`]. With `T = f64` the input values; for a \
         mechanism with several inputs, analogs hold one `{plain}Inputs` of partial derivatives \
         per quantity."
    );
    let unknowns_doc = format!(
        "Unknowns of [`{plain}`] by name: positions (`T = f64`), and their velocity and \
         acceleration analogs in [`{plain}State`]."
    );
    let mut out = params_struct(s);
    out.extend(named_struct(&s.vis, &t.inputs, &inputs_doc, &s.inputs, "Input"));
    out.extend(named_struct(&s.vis, &t.unknowns, &unknowns_doc, &s.unknowns, "Unknown"));
    out.extend(array_conversions(s, t));
    out.extend(outputs_struct(s, t));
    out.extend(state_struct(s, t));
    out.extend(columns_struct(s, t));
    out
}

/// `NameColumns` and the constant `Name::COL`: one typed analysis handle per input, unknown
/// and output column, with the state's paths (`COL.beta`, `COL.cp.x`); written by the runtime's
/// macro from the names and flat indices.
fn columns_struct(s: &Surface, t: &Types) -> TokenStream {
    let (rt, vis, name, ty) = (runtime(), &s.vis, &t.name, &t.columns);
    let named = |fields: &[Field]| -> Vec<TokenStream> {
        let entry = |(k, f): (usize, &Field)| {
            let (n, plain, k) = (&f.name, f.name.unraw().to_string(), lit(k));
            quote!(#n #plain #k)
        };
        fields.iter().enumerate().map(entry).collect()
    };
    let (inputs, unknowns) = (named(&s.inputs), named(&s.unknowns));
    let points = s.points.iter().enumerate().map(|(k, f)| {
        let (n, plain) = (&f.name, f.name.unraw());
        let (x, y, k) = (format!("{plain}.x"), format!("{plain}.y"), lit(2 * k));
        quote!(#n #x #y #k)
    });
    let scalars = s.scalars.iter().enumerate().map(|(k, f)| {
        let (n, plain, k) = (&f.name, f.name.unraw().to_string(), lit(2 * s.points.len() + k));
        quote!(#n #plain #k)
    });
    quote! {
        #rt::columns!(#vis #name, #ty; inputs #(#inputs),*; unknowns #(#unknowns),*;
            points #(#points),*; outputs #(#scalars),*);
    }
}

/// A single input from a number (`m.solve(0.3)`).
fn array_conversions(s: &Surface, t: &Types) -> TokenStream {
    let inputs = &t.inputs;
    match s.inputs.as_slice() {
        [one] => {
            let i = &one.name;
            quote! {
                impl ::core::convert::From<::core::primitive::f64> for #inputs<::core::primitive::f64> {
                    fn from(__v: ::core::primitive::f64) -> Self {
                        #inputs { #i: __v }
                    }
                }
            }
        }
        _ => quote!(),
    }
}

/// The parameter struct, and `Default` when every parameter has a default (also when there
/// are no parameters).
fn params_struct(s: &Surface) -> TokenStream {
    let Surface { docs, vis, name, .. } = s;
    let fields = s.params.iter().map(|f| {
        let (d, n) = (f.doc("Parameter"), &f.name);
        quote!(#d pub #n: ::core::primitive::f64,)
    });
    let default = match &s.defaults {
        Some(values) if values.len() == s.params.len() => {
            let values = values.iter().map(|&v| super::names::float(v));
            // Through `from_param_values`, which sets the fields by name: bound to locals, a
            // constant of the user's module named like a parameter would turn the binding into
            // a pattern.
            quote! {
                impl ::core::default::Default for #name {
                    /// The parameter values declared in the mechanism.
                    fn default() -> Self {
                        Self::from_param_values([#(#values),*])
                    }
                }
            }
        }
        _ => quote!(),
    };
    let derive = derives(std_derives(false), quote!());
    quote! {
        #(#docs)*
        #derive
        #[allow(non_snake_case)]
        #vis struct #name {
            #(#fields)*
        }
        #default
    }
}

/// A struct generic over its element type `T` with one field per name, and its conversions
/// from and to `[T; n]` in field order.
pub fn named_struct(vis: &Visibility, ty: &Ident, doc: &str, fields: &[Field], kind: &str) -> TokenStream {
    let (rt, n) = (runtime(), lit(fields.len()));
    let names: Vec<&Ident> = fields.iter().map(|f| &f.name).collect();
    let docs = fields.iter().map(|f| f.doc(kind));
    let bind: Vec<Ident> = (0..fields.len()).map(|k| Ident::new(&format!("f{k}"), Span::call_site())).collect();
    // A struct without fields still mentions `T`.
    let marker = fields.is_empty().then(marker);
    let derive = derives(std_derives(true), quote!());
    let doc_line = format!(" {doc}");
    quote! {
        #[doc = #doc_line]
        #derive
        #[allow(non_snake_case)]
        #vis struct #ty<T = ::core::primitive::f64> {
            #(#docs pub #names: T,)*
            #marker
        }
        #rt::array_conversions!(#ty, #n; #(#names(#bind)),*);
    }
}

/// The field of a generated struct without declared ones (no outputs, no unknowns), which still
/// mentions its element type `T`. Skipped by serde: the struct is `{}`, as it reads, not
/// `{"__marker":null}`, and `{}` reads back (without the skip it was "missing field
/// `__marker`", a field the user does not know of).
fn marker() -> TokenStream {
    quote!(#[doc(hidden)] #[serde(skip)] pub __marker: ::core::marker::PhantomData<T>,)
}

/// Outputs: points are `Vec2<T>`, scalars `T`; flat order is x, y per point then scalars.
fn outputs_struct(s: &Surface, t: &Types) -> TokenStream {
    let (rt, vis, ty, plain) = (runtime(), &s.vis, &t.outputs, &t.plain);
    let (mut fields, mut points, mut scalars, mut flat) = (Vec::new(), Vec::new(), Vec::new(), 0);
    let o = |k: usize| Ident::new(&format!("o{k}"), Span::call_site());
    for p in &s.points {
        let (d, f, a, b) = (p.doc("Point"), &p.name, o(flat), o(flat + 1));
        fields.push(quote!(#d pub #f: #rt::Vec2<T>,));
        points.push(quote!(#f(#a, #b)));
        flat += 2;
    }
    for p in &s.scalars {
        let (d, f, a) = (p.doc("Output"), &p.name, o(flat));
        fields.push(quote!(#d pub #f: T,));
        scalars.push(quote!(#f(#a)));
        flat += 1;
    }
    let conversions = if flat == 0 {
        fields.push(marker());
        quote!(#rt::array_conversions!(#ty, 0;);)
    } else {
        let nol = lit(flat);
        quote!(#rt::array_conversions!(#ty, #nol; points #(#points),*; scalars #(#scalars),*);)
    };
    let doc = format!(
        " Named outputs of [`{plain}`] (points and scalar outputs); with `T = f64` their values, in \
         [`{plain}State`] also their analogs."
    );
    let derive = derives(std_derives(true), quote!());
    quote! {
        #[doc = #doc]
        #derive
        #[allow(non_snake_case)]
        #vis struct #ty<T = ::core::primitive::f64> {
            #(#fields)*
        }
        #conversions
    }
}

/// Element types of the first and second analogs: scalars for one input, per-input structs
/// (`dq.u.i`, `d2q.u.i.j`) for several.
pub fn analog_types(ni: usize, inputs: &Ident, elem: TokenStream) -> (TokenStream, TokenStream) {
    if ni == 1 { (elem.clone(), elem) } else { (quote!(#inputs<#elem>), quote!(#inputs<#inputs<#elem>>)) }
}

/// Conversions of flat analog rows (`[flat; NI]`, `[[flat; NI]; NI]`) to the analog element
/// types of [`analog_types`]; `elem` converts one innermost value (`None`: it is kept).
pub fn analog_conversions(
    ni: usize,
    inputs: &Ident,
    flat: TokenStream,
    elem: Option<TokenStream>,
) -> (TokenStream, TokenStream) {
    let nil = lit(ni);
    // Through the trait by its path: `Inputs::from` needs `From` in scope (the prelude's).
    let from = quote!(<#inputs<_> as ::core::convert::From<_>>::from);
    let from_f64 = quote!(<#inputs<::core::primitive::f64> as ::core::convert::From<_>>::from);
    match (ni, elem) {
        // One input: the array's element type is known to `map`, no annotation needed.
        (1, Some(e)) => (quote!(|__r| #e(__r[0])), quote!(|__r| #e(__r[0][0]))),
        (1, None) => (quote!(|__r| __r[0]), quote!(|__r| __r[0][0])),
        (_, Some(e)) => (
            quote!(|__r: [#flat; #nil]| #from(__r.map(#e))),
            quote!(|__r: [[#flat; #nil]; #nil]| #from(__r.map(|__s| #from(__s.map(#e))))),
        ),
        (_, None) => (quote!(#from_f64), quote!(|__r: [[#flat; #nil]; #nil]| #from(__r.map(#from_f64)))),
    }
}

/// `NameState` (from a flat `Kin`) and `NameMotion`.
fn state_struct(s: &Surface, t: &Types) -> TokenStream {
    let (rt, vis, plain) = (runtime(), &s.vis, &t.plain);
    let Types { inputs, unknowns, outputs, state, .. } = t;
    let ni = s.inputs.len();
    let (nl, nil, nol) = (lit(s.unknowns.len()), lit(ni), lit(s.n_outputs()));
    let (v_ty, a_ty) = analog_types(ni, inputs, quote!(::core::primitive::f64));
    let (conv_v, conv_a) = analog_conversions(ni, inputs, quote!(::core::primitive::f64), None);
    let analog_doc = match s.inputs.first() {
        Some(i) if ni == 1 => format!("`d/d{}`", i.name.unraw()),
        _ => "partial derivatives: `dq.u.i` is `d u / d i`".to_string(),
    };
    let state_doc = format!(
        "Kinematic state of [`{plain}`] at one input value: positions, velocity analogs \
         ({analog_doc}), acceleration analogs, and the same for every output."
    );
    let motion_struct = motion_struct(s, t);
    // A state serializes by name: its named fields without the flat copy of the same values,
    // which deserialization rebuilds from them (the runtime's `StateByName`).
    // The derives read these types where the struct is declared: `f64` by its path, as in the
    // code, and the runtime by the alias they declare for it (its path may be `$crate`, which a
    // string cannot hold).
    let f64 = "::core::primitive::f64";
    let (vs, as_) = if ni == 1 {
        (f64.to_string(), f64.to_string())
    } else {
        (format!("{inputs}<{f64}>"), format!("{inputs}<{inputs}<{f64}>>"))
    };
    let by_name = format!(
        "{RUNTIME_ALIAS}::StateByName<{inputs}, {unknowns}, {unknowns}<{vs}>, {unknowns}<{as_}>, {outputs}, \
         {outputs}<{vs}>, {outputs}<{as_}>>"
    );
    let derive = derives(std_derives(false), quote!(, from = #by_name, into = #by_name));
    let arity = if ni == 1 { quote!(one) } else { quote!(many) };
    let by_name_conversions =
        quote!(#rt::state_by_name!(#state, #inputs, #unknowns, #outputs, #nl, #nil, #nol, #arity););
    let state_line = format!(" {state_doc}");
    quote! {
        #[doc = #state_line]
        #derive
        #vis struct #state {
            /// The input values.
            pub input: #inputs,
            /// Positions of the unknowns.
            pub q: #unknowns,
            /// Velocity analogs (first derivatives with respect to the inputs).
            pub dq: #unknowns<#v_ty>,
            /// Acceleration analogs (second derivatives with respect to the inputs).
            pub d2q: #unknowns<#a_ty>,
            /// Output values.
            pub out: #outputs,
            /// Velocity analogs of the outputs.
            pub dout: #outputs<#v_ty>,
            /// Acceleration analogs of the outputs.
            pub d2out: #outputs<#a_ty>,
            /// Diagnostics of the position solve.
            pub report: #rt::SolveReport,
            /// Conditioning and assembly mode of each block.
            pub health: #rt::Health,
            /// The same values as flat arrays in declaration order (for generic code).
            pub flat: #rt::Kin<#nl, #nil, #nol>,
        }
        impl ::core::convert::From<#state> for #rt::Kin<#nl, #nil, #nol> {
            #[inline]
            fn from(__s: #state) -> Self {
                __s.flat
            }
        }
        impl ::core::convert::From<#rt::Kin<#nl, #nil, #nol>> for #state {
            #[inline]
            fn from(__k: #rt::Kin<#nl, #nil, #nol>) -> Self {
                #state {
                    input: ::core::convert::From::from(__k.x),
                    q: ::core::convert::From::from(__k.q),
                    dq: ::core::convert::From::from(__k.dq.map(#conv_v)),
                    d2q: ::core::convert::From::from(__k.d2q.map(#conv_a)),
                    out: ::core::convert::From::from(__k.out),
                    dout: ::core::convert::From::from(__k.dout.map(#conv_v)),
                    d2out: ::core::convert::From::from(__k.d2out.map(#conv_a)),
                    report: __k.report,
                    health: __k.health,
                    flat: __k,
                }
            }
        }
        #by_name_conversions
        #motion_struct
    }
}

/// `NameMotion`: true velocities and accelerations.
fn motion_struct(s: &Surface, t: &Types) -> TokenStream {
    let (vis, plain) = (&s.vis, &t.plain);
    let Types { unknowns, outputs, motion, .. } = t;
    let motion_line = format!(" True velocities and accelerations of [`{plain}`] (time derivatives).");
    let derive = derives(std_derives(false), quote!());
    quote! {
        #[doc = #motion_line]
        #derive
        #vis struct #motion {
            /// Velocities of the unknowns.
            pub qdot: #unknowns,
            /// Accelerations of the unknowns.
            pub qddot: #unknowns,
            /// Velocities of the outputs.
            pub out_dot: #outputs,
            /// Accelerations of the outputs.
            pub out_ddot: #outputs,
        }
    }
}

/// The standard traits a generated struct derives, by their paths in `core`: a bare `Clone` or
/// `Default` is the prelude's, which a module with `#![no_implicit_prelude]` does not have.
/// `Default` and `Eq` are derived by the named structs of values (`with_default`), generic over
/// their element type, not by the states: such a struct is `Eq` where its element type is (a
/// struct of `f64`s is not), which `clippy::derive_partial_eq_without_eq` asks of a public type
/// deriving `PartialEq` in a crate that turns on `clippy::nursery`.
pub fn std_derives(with_default: bool) -> TokenStream {
    let default = with_default.then(|| quote!(::core::default::Default,));
    let eq = with_default.then(|| quote!(, ::core::cmp::Eq));
    quote!(::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug, #default ::core::cmp::PartialEq #eq)
}

/// The derive attributes of a generated struct: the standard traits `std`, and `Serialize` and
/// `Deserialize` from the facade's `__gen`, serde's with kinloop's feature `serde` and otherwise
/// derives that implement nothing (the user's crate cannot test kinloop's features, so the
/// expansion is the same either way); then the container attribute of kinloop's derives, naming
/// the runtime as this expansion does (see `serde_derive`), with the further arguments `extra`
/// (`, from = ..`).
fn derives(std: TokenStream, extra: TokenStream) -> TokenStream {
    let rt = runtime();
    quote! {
        #[derive(#std)]
        #[derive(#rt::Serialize, #rt::Deserialize)]
        #[serde(runtime = #rt #extra)]
    }
}
