//! The parameter-sensitivity API, generated under `#[kinloop(sensitivities)]` only:
//! `NameParams<T>` (one field per parameter), `NameSensitivities` (named sensitivities of
//! positions, analogs and outputs), the `Sensitivities` kernels (the kinematic solve followed by
//! one more set of right-hand sides per block and stage, on the same factorisations) and the
//! `sensitivities` / `sensitivities_at` forwarders.
//!
//! Without the attribute, [`absent`] declares the two methods with a bound no type satisfies,
//! so calling them is a compile error that says to add the attribute.

use super::api::rescued;
use super::dims::Dims;
use super::kernel::{Mode, solver_body};
use super::lints::kernel_lints;
use super::names::Names;
use super::runtime_path::runtime;
use super::surface::{Field, analog_conversions, analog_types, named_struct, std_derives};
use super::type_names::Types;
use crate::plan::Plan;
use crate::semantics::model::Model;
use proc_macro2::TokenStream;
use quote::quote;
use syn::Visibility;

/// Every sensitivity item of a mechanism declared with `#[kinloop(sensitivities)]`.
pub fn items(model: &Model, plan: &Plan, t: &Types) -> TokenStream {
    let fields: Vec<Field> = model.params.iter().map(|p| Field::new(&[], &p.name)).collect();
    let mut out = types(&model.vis, &fields, &Dims::of(plan), plan.ni, t);
    out.extend(kernels(model, plan, t));
    out
}

/// `NameParams` and `NameSensitivities` (from a flat `Sens`), of a mechanism with the parameters
/// `fields`, sizes `dims` and `ni` inputs (also emitted for a rejected declaration).
pub fn types(vis: &Visibility, fields: &[Field], dims: &Dims, ni: usize, t: &Types) -> TokenStream {
    let (rt, plain) = (runtime(), &t.plain);
    let Types { inputs, unknowns, outputs, params, sens, .. } = t;
    let Dims { n, ni: ni_lit, no, np } = dims;
    let params_doc = format!(
        "One value per parameter of [`{plain}`]: the innermost level of [`{plain}Sensitivities`] \
         (`sens.q.x.l` is `d x / d l`)."
    );
    let sens_doc = format!(
        " Exact sensitivities of a [`{plain}State`] to the parameters: append a parameter name to a \
         state path (`state.dq.u` -> `sens.dq.u.p` is `d(du/dinput)/dp`)."
    );
    let params_struct = named_struct(vis, params, &params_doc, fields, "Parameter");
    let (vp, ap) = analog_types(ni, inputs, quote!(#params<::core::primitive::f64>));
    let derives = std_derives(false);
    let to_params = quote!(<#params<::core::primitive::f64> as ::core::convert::From<_>>::from);
    let (conv_v, conv_a) =
        analog_conversions(ni, inputs, quote!([::core::primitive::f64; #np]), Some(to_params.clone()));
    quote! {
        #params_struct
        #[doc = #sens_doc]
        #[derive(#derives)]
        #vis struct #sens {
            /// `d q / d p`.
            pub q: #unknowns<#params<::core::primitive::f64>>,
            /// Sensitivities of the velocity analogs.
            pub dq: #unknowns<#vp>,
            /// Sensitivities of the acceleration analogs.
            pub d2q: #unknowns<#ap>,
            /// Sensitivities of the outputs.
            pub out: #outputs<#params<::core::primitive::f64>>,
            /// Sensitivities of the outputs' velocity analogs.
            pub dout: #outputs<#vp>,
            /// Sensitivities of the outputs' acceleration analogs.
            pub d2out: #outputs<#ap>,
            /// The same values as flat arrays (parameter innermost).
            pub flat: #rt::Sens<#n, #ni_lit, #no, #np>,
        }
        impl ::core::convert::From<#rt::Sens<#n, #ni_lit, #no, #np>> for #sens {
            fn from(__s: #rt::Sens<#n, #ni_lit, #no, #np>) -> Self {
                #sens {
                    q: ::core::convert::From::from(__s.q.map(#to_params)),
                    dq: ::core::convert::From::from(__s.dq.map(#conv_v)),
                    d2q: ::core::convert::From::from(__s.d2q.map(#conv_a)),
                    out: ::core::convert::From::from(__s.out.map(#to_params)),
                    dout: ::core::convert::From::from(__s.dout.map(#conv_v)),
                    d2out: ::core::convert::From::from(__s.d2out.map(#conv_a)),
                    flat: __s,
                }
            }
        }
    }
}

/// The `Sensitivities` kernels, `NamedSensitivities`, and the inherent forwarders.
fn kernels(model: &Model, plan: &Plan, t: &Types) -> TokenStream {
    let (rt, name, names) = (runtime(), &t.name, Names::new(model, plan));
    let Types { inputs, unknowns, state, sens, .. } = t;
    let Dims { n, ni, no, np } = Dims::of(plan);
    // A failure at an extreme size is rescued as `kinematics_flat`'s is (see `api::rescued`).
    let flat = quote!(::core::result::Result<(#rt::Kin<#n, #ni, #no>, #rt::Sens<#n, #ni, #no, #np>), #rt::Error>);
    let fused = rescued(solver_body(plan, &names, Mode::Fused, true), &flat, quote!(#rt::rescue_sensitivities));
    let at = solver_body(plan, &names, Mode::At, true);
    let lints = kernel_lints();
    let pnames: Vec<_> = model.params.iter().map(|p| &p.name).collect();
    let named = quote!(<Self as #rt::NamedSensitivities<#n, #ni, #no, #np>>);
    let input = quote!(input: impl ::core::convert::Into<#inputs>);
    let ret = quote!(::core::result::Result<(#state, #sens), #rt::Error>);
    let (x, cfg) = (quote!(__x: &[::core::primitive::f64; #ni]), quote!(__cfg: &#rt::NewtonConfig));
    quote! {
        impl #name {
            /// Solves the kinematics from `guess` and the exact sensitivities of positions,
            /// analogs and outputs to every parameter (implicit function theorem on the same
            /// factorisations). Costs a few extra solves per block; `kinematics` does none of it.
            pub fn sensitivities(&self, #input, guess: &#unknowns) -> #ret { #named::sensitivities(self, input, guess) }
            /// [`Self::sensitivities`] at a position the caller already solved.
            pub fn sensitivities_at(&self, #input, unknowns: &#unknowns) -> #ret { #named::sensitivities_at(self, input, unknowns) }
        }
        #lints
        impl #rt::Sensitivities<#n, #ni, #no, #np> for #name {
            fn params_flat(&self) -> [::core::primitive::f64; #np] {
                [#(self.#pnames),*]
            }
            fn with_params_flat(&self, __p: [::core::primitive::f64; #np]) -> Self {
                #name::from_param_values(__p)
            }
            fn sensitivities_flat(&self, #x, __guess: &[::core::primitive::f64; #n], #cfg) -> #flat { #fused }
            fn sensitivities_at_flat(&self, #x, __q: &[::core::primitive::f64; #n], #cfg) -> #flat { #at }
        }
        impl #rt::NamedSensitivities<#n, #ni, #no, #np> for #name {
            type Sens = #sens;
        }
    }
}

/// `sensitivities` and `sensitivities_at` of a mechanism declared without
/// `#[kinloop(sensitivities)]`: a bound no type satisfies, whose diagnostic says what to add.
pub fn absent(t: &Types) -> TokenStream {
    let rt = runtime();
    let Types { name, inputs, unknowns, .. } = t;
    let stub = |method: TokenStream, arg: TokenStream| {
        quote! {
            /// Not generated: declare the mechanism with `#[kinloop(sensitivities)]`.
            #[doc(hidden)]
            pub fn #method<I: ::core::convert::Into<#inputs>>(&self, _input: I, #arg: &#unknowns) -> ::core::convert::Infallible
            where
                Self: #rt::SensitivitiesRequested<I>,
            {
                #rt::SensitivitiesRequested::<I>::absurd(*self)
            }
        }
    };
    let (s, s_at) = (stub(quote!(sensitivities), quote!(_guess)), stub(quote!(sensitivities_at), quote!(_q)));
    quote! {
        impl #name {
            #s
            #s_at
        }
    }
}
