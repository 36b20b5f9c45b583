//! Generation of the parameter-sensitivity API: `NameParams<T>` (one field per parameter),
//! `NameSensitivities` (named sensitivities of positions, analogs and outputs), the
//! `sensitivities` / `sensitivities_at` methods and the `Sensitivities` trait impl.
//!
//! The sensitivities are a separate generated solver (the kinematic solve followed by one more
//! set of right-hand sides per block and stage, on the same factorisations), so they cost
//! nothing when not requested.

use crate::emit::Names;
use crate::items::{lit, named_struct, solver_lints};
use crate::model::Model;
use crate::plan::Plan;
use crate::solver::{Mode, solver_body_with};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use syn::ext::IdentExt;

pub fn generate(model: &Model, plan: &Plan, names: &Names, rt: &TokenStream) -> TokenStream {
    let name = &model.name;
    let name_s = name.unraw().to_string();
    let vis = &model.vis;
    let inputs_ty = format_ident!("{}Inputs", name_s);
    let unknowns_ty = format_ident!("{}Unknowns", name_s);
    let outputs_ty = format_ident!("{}Outputs", name_s);
    let state_ty = format_ident!("{}State", name_s);
    let params_ty = format_ident!("{}Params", name_s);
    let sens_ty = format_ident!("{}Sensitivities", name_s);
    let (nl, nil, nol, npl) = (lit(plan.n), lit(plan.ni), lit(plan.outputs.len()), lit(plan.np));
    let ni = plan.ni;

    let fields: Vec<&Ident> = model.params.iter().map(|p| &p.name).collect();
    let params_doc = format!(
        "One value per parameter of [`{name_s}`]: the innermost level of [`{name_s}Sensitivities`] \
         (`sens.q.x.l` is `d x / d l`)."
    );
    let sens_doc = format!(
        "Exact sensitivities of a [`{name_s}State`] to the parameters: append a parameter name to \
         a state path (`state.dq.u` -> `sens.dq.u.p` is `d(du/dinput)/dp`)."
    );
    let field_docs: Vec<TokenStream> = fields
        .iter()
        .map(|f| {
            let doc = format!("Parameter `{}`.", f.unraw());
            quote!(#[doc = #doc])
        })
        .collect();
    let params_struct = named_struct(vis, &params_ty, &params_doc, &fields, &field_docs);

    let (vp, ap, conv_v, conv_a) = if ni == 1 {
        (
            quote!(#params_ty<f64>),
            quote!(#params_ty<f64>),
            quote!(|r: [[f64; #npl]; 1]| #params_ty::from(r[0])),
            quote!(|r: [[[f64; #npl]; 1]; 1]| #params_ty::from(r[0][0])),
        )
    } else {
        (
            quote!(#inputs_ty<#params_ty<f64>>),
            quote!(#inputs_ty<#inputs_ty<#params_ty<f64>>>),
            quote!(|r: [[f64; #npl]; #nil]| #inputs_ty::from(r.map(#params_ty::from))),
            quote!(|r: [[[f64; #npl]; #nil]; #nil]| #inputs_ty::from(r.map(|s| #inputs_ty::from(s.map(#params_ty::from))))),
        )
    };

    let fused = solver_body_with(model, plan, names, Mode::Fused, true, rt);
    let at = solver_body_with(model, plan, names, Mode::At, true, rt);
    let err = quote!(#rt::Error);
    let lints = solver_lints();
    let pvals = fields.iter().map(|f| quote!(self.#f));
    let from_p = fields.iter().enumerate().map(|(k, f)| {
        let k = lit(k);
        quote!(#f: p[#k])
    });

    quote! {
        #params_struct

        #[doc = #sens_doc]
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #sens_ty {
            /// `d q / d p`.
            pub q: #unknowns_ty<#params_ty<f64>>,
            /// Sensitivities of the velocity analogs.
            pub dq: #unknowns_ty<#vp>,
            /// Sensitivities of the acceleration analogs.
            pub d2q: #unknowns_ty<#ap>,
            /// Sensitivities of the outputs.
            pub out: #outputs_ty<#params_ty<f64>>,
            /// Sensitivities of the outputs' velocity analogs.
            pub dout: #outputs_ty<#vp>,
            /// Sensitivities of the outputs' acceleration analogs.
            pub d2out: #outputs_ty<#ap>,
            /// The same values as flat arrays (parameter innermost).
            pub flat: #rt::Sens<#nl, #nil, #nol, #npl>,
        }
        impl ::core::convert::From<#rt::Sens<#nl, #nil, #nol, #npl>> for #sens_ty {
            fn from(s: #rt::Sens<#nl, #nil, #nol, #npl>) -> Self {
                #sens_ty {
                    q: #unknowns_ty::from(s.q.map(#params_ty::from)),
                    dq: #unknowns_ty::from(s.dq.map(#conv_v)),
                    d2q: #unknowns_ty::from(s.d2q.map(#conv_a)),
                    out: #outputs_ty::from(s.out.map(#params_ty::from)),
                    dout: #outputs_ty::from(s.dout.map(#conv_v)),
                    d2out: #outputs_ty::from(s.d2out.map(#conv_a)),
                    flat: s,
                }
            }
        }

        #[allow(clippy::all, clippy::pedantic, clippy::nursery)]
        impl #name {
            /// Solves the kinematics from `guess` and the exact sensitivities of positions,
            /// analogs and outputs to every parameter (implicit function theorem on the same
            /// factorisations). Costs a few extra solves per block; `kinematics` does none of it.
            pub fn sensitivities(
                &self,
                input: impl ::core::convert::Into<#inputs_ty>,
                guess: &#unknowns_ty,
            ) -> ::core::result::Result<(#state_ty, #sens_ty), #err> {
                let __x: [f64; #nil] = ::core::convert::Into::<#inputs_ty>::into(input).into();
                let (k, s) = self.__sensitivities(&__x, &(*guess).into(), &#rt::NewtonConfig::default())?;
                Ok((k.into(), s.into()))
            }

            /// [`Self::sensitivities`] at a position the caller already solved.
            pub fn sensitivities_at(
                &self,
                input: impl ::core::convert::Into<#inputs_ty>,
                q: &#unknowns_ty,
            ) -> ::core::result::Result<(#state_ty, #sens_ty), #err> {
                let __x: [f64; #nil] = ::core::convert::Into::<#inputs_ty>::into(input).into();
                let (k, s) = self.__sensitivities_at(&__x, &(*q).into(), &#rt::NewtonConfig::default())?;
                Ok((k.into(), s.into()))
            }

            #lints
            fn __sensitivities(
                &self,
                __x: &[f64; #nil],
                __guess: &[f64; #nl],
                __cfg: &#rt::NewtonConfig,
            ) -> ::core::result::Result<(#rt::Kin<#nl, #nil, #nol>, #rt::Sens<#nl, #nil, #nol, #npl>), #err> {
                #fused
            }

            #lints
            fn __sensitivities_at(
                &self,
                __x: &[f64; #nil],
                __q: &[f64; #nl],
                __cfg: &#rt::NewtonConfig,
            ) -> ::core::result::Result<(#rt::Kin<#nl, #nil, #nol>, #rt::Sens<#nl, #nil, #nol, #npl>), #err> {
                #at
            }
        }

        #[allow(clippy::all, clippy::pedantic, clippy::nursery)]
        impl #rt::Sensitivities<#nl, #nil, #nol, #npl> for #name {
            fn params_flat(&self) -> [f64; #npl] {
                [#(#pvals),*]
            }
            fn with_params_flat(&self, p: [f64; #npl]) -> Self {
                #name { #(#from_p),* }
            }
            fn sensitivities_flat(
                &self,
                x: &[f64; #nil],
                guess: &[f64; #nl],
                cfg: &#rt::NewtonConfig,
            ) -> ::core::result::Result<(#rt::Kin<#nl, #nil, #nol>, #rt::Sens<#nl, #nil, #nol, #npl>), #err> {
                self.__sensitivities(x, guess, cfg)
            }
            fn sensitivities_at_flat(
                &self,
                x: &[f64; #nil],
                q: &[f64; #nl],
                cfg: &#rt::NewtonConfig,
            ) -> ::core::result::Result<(#rt::Kin<#nl, #nil, #nol>, #rt::Sens<#nl, #nil, #nol, #npl>), #err> {
                self.__sensitivities_at(x, q, cfg)
            }
        }
    }
}
