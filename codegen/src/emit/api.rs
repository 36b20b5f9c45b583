//! The mechanism's implementation of the runtime traits (`Mechanism` with the kernels, `Named`
//! with the named types), its constants, and its inherent methods: one-line forwarders into the
//! runtime's generic code, so that `m.solve(x)` needs no import.

use super::kernels::{Mode, jacobian_body, solver_body, straight_line};
use super::names::Names;
use super::{Dims, Types, kernel_lints, lit, runtime};
use crate::model::Model;
use crate::plan::Plan;
use proc_macro2::TokenStream;
use quote::quote;
use syn::ext::IdentExt;

/// Every item implementing the mechanism.
pub fn items(model: &Model, plan: &Plan, t: &Types) -> TokenStream {
    let mut out = constants(model, plan, t);
    out.extend(forwarders(t, &Dims::of(plan)));
    out.extend(motion(t, &Dims::of(plan)));
    out.extend(mechanism_impl(model, plan, t));
    out
}

/// The constants and the parameter conversions.
fn constants(model: &Model, plan: &Plan, t: &Types) -> TokenStream {
    let (rt, name, plain) = (runtime(), &t.name, &t.plain);
    let Dims { n, ni, no, np } = Dims::of(plan);
    let strs = |ids: Vec<&proc_macro2::Ident>| ids.into_iter().map(|i| i.unraw().to_string()).collect::<Vec<_>>();
    let pnames: Vec<_> = model.params.iter().map(|p| &p.name).collect();
    let pstrs = strs(pnames.clone());
    let istrs = strs(model.inputs.iter().map(|p| &p.name).collect());
    let ustrs = strs(model.unknowns.iter().map(|p| &p.name).collect());
    let estrs: Vec<String> = model.equations.iter().map(|e| e.name.clone()).collect();
    let ostrs = model.output_names();
    let decomposition = super::describe::decomposition(model, plan);
    let blocks = plan.blocks.iter().map(|b| {
        let us = b.unknowns.iter().map(|&u| &ustrs[u]);
        let es = b.equations.iter().map(|&e| &estrs[e]);
        let linear = b.linear;
        quote!(#rt::BlockInfo { unknowns: &[#(#us),*], equations: &[#(#es),*], linear: #linear })
    });
    let from_params = pnames.iter().enumerate().map(|(k, p)| {
        let k = lit(k);
        quote!(#p: v[#k])
    });
    quote! {
        impl #name {
            /// The mechanism's type name.
            pub const NAME: &'static str = #plain;
            /// Parameter names, in declaration order.
            pub const PARAMS: [&'static str; #np] = [#(#pstrs),*];
            /// Input names.
            pub const INPUTS: [&'static str; #ni] = [#(#istrs),*];
            /// Unknown names.
            pub const UNKNOWNS: [&'static str; #n] = [#(#ustrs),*];
            /// Scalar equation names: `loop.x` and `loop.y` for each loop, the `eq` names.
            pub const EQUATIONS: [&'static str; #n] = [#(#estrs),*];
            /// Output columns: `point.x`, `point.y` for each point, then scalar outputs.
            pub const OUTPUTS: [&'static str; #no] = [#(#ostrs),*];
            /// The block-triangular decomposition of the equations, in solve order.
            pub const BLOCKS: &'static [#rt::BlockInfo] = &[#(#blocks),*];
            /// The decomposition in words: counts and mobility, then one line per block in
            /// solve order (Newton or linear, size, unknowns `<-` equations).
            pub const DECOMPOSITION: &'static str = #decomposition;

            /// Parameter values in declaration order.
            pub fn param_values(&self) -> [f64; #np] {
                [#(self.#pnames),*]
            }

            /// Builds the mechanism from parameter values in declaration order.
            pub fn from_param_values(v: [f64; #np]) -> Self {
                #name { #(#from_params),* }
            }
        }
    }
}

/// The inherent named API, forwarded to the runtime's `Named` (documented there).
fn forwarders(t: &Types, d: &Dims) -> TokenStream {
    let (rt, name) = (runtime(), &t.name);
    let Types { inputs, unknowns, outputs, state, .. } = t;
    let Dims { n, ni, no, .. } = d;
    let named = quote!(<Self as #rt::Named<#n, #ni, #no>>);
    let input = quote!(input: impl ::core::convert::Into<#inputs>);
    let res = |ty: TokenStream| quote!(::core::result::Result<#ty, #rt::Error>);
    let (r_state, r_pos, r_unit) = (res(quote!(#state)), res(quote!((#unknowns, #rt::SolveReport))), res(quote!(())));
    let r_sweep = res(quote!(#rt::Sweep<'_, Self, #state, #n, #ni, #no>));
    let cfg = quote!(cfg: &#rt::NewtonConfig);
    quote! {
        /// The named API; see [`Named`](::kinloop::Named) for each method.
        impl #name {
            /// Checks that every parameter is finite.
            pub fn check(&self) -> #r_unit { #named::check(self) }
            /// The declared initial guess (assembly mode) at `input`.
            pub fn guess(&self, #input) -> #unknowns { #named::guess(self, input) }
            /// Residuals of the scalar equations (named by [`Self::EQUATIONS`]) at a position.
            pub fn residual(&self, #input, q: &#unknowns) -> [f64; #n] { #named::residual(self, input, q) }
            /// Output values at a position.
            pub fn outputs(&self, #input, q: &#unknowns) -> #outputs { #named::outputs(self, input, q) }
            /// Solves the positions by Newton's method from `guess` (which picks the assembly mode).
            pub fn position(&self, #input, guess: &#unknowns) -> #r_pos { #named::position(self, input, guess) }
            /// [`Self::position`] with an explicit solver configuration.
            pub fn position_with(&self, #input, guess: &#unknowns, #cfg) -> #r_pos { #named::position_with(self, input, guess, cfg) }
            /// Positions, velocity and acceleration analogs, and outputs, solved from `guess`.
            pub fn kinematics(&self, #input, guess: &#unknowns) -> #r_state { #named::kinematics(self, input, guess) }
            /// [`Self::kinematics`] with an explicit solver configuration.
            #[inline]
            pub fn kinematics_with(&self, #input, guess: &#unknowns, #cfg) -> #r_state { #named::kinematics_with(self, input, guess, cfg) }
            /// Analogs and outputs at a position the caller already solved.
            pub fn kinematics_at(&self, #input, q: &#unknowns) -> #r_state { #named::kinematics_at(self, input, q) }
            /// Full kinematics at `input`, starting from the declared initial guess.
            pub fn solve(&self, #input) -> #r_state { #named::solve(self, input) }
            /// A lazy sweep from `from` to `to` that never jumps branches (see [`Named::sweep`](::kinloop::Named::sweep)).
            pub fn sweep(&self, from: impl ::core::convert::Into<#inputs>, to: impl ::core::convert::Into<#inputs>, samples: usize, guess: &#unknowns) -> #r_sweep {
                #named::sweep(self, from, to, samples, guess)
            }
            /// The distinct assembly modes at `input` (multi-start Newton).
            pub fn assembly_modes(&self, #input) -> ::std::vec::Vec<#state> { #named::assembly_modes(self, input) }
        }
    }
}

/// `state.motion(omega, eps)`.
fn motion(t: &Types, d: &Dims) -> TokenStream {
    let (rt, name) = (runtime(), &t.name);
    let Types { inputs, state, motion, .. } = t;
    let Dims { n, ni, no, .. } = d;
    quote! {
        impl #state {
            /// True velocities and accelerations for input speeds `omega` and input
            /// accelerations `eps`: `v = v_q omega`, `a = a_q omega^2 + v_q eps` (summed over
            /// inputs for several inputs). For a time input pass `omega = 1`, `eps = 0`.
            pub fn motion(
                &self,
                omega: impl ::core::convert::Into<#inputs>,
                eps: impl ::core::convert::Into<#inputs>,
            ) -> ::core::result::Result<#motion, #rt::Error> {
                let w = ::core::convert::Into::<#inputs>::into(omega).into();
                let e = ::core::convert::Into::<#inputs>::into(eps).into();
                #rt::motion::<#name, #n, #ni, #no>(&self.flat, w, e).map(#motion::from)
            }
        }
    }
}

/// `Mechanism` (the kernels) and `Named` (the types) for the mechanism.
fn mechanism_impl(model: &Model, plan: &Plan, t: &Types) -> TokenStream {
    let (rt, name, names) = (runtime(), &t.name, Names::new(model));
    let Types { inputs, unknowns, outputs, state, .. } = t;
    let Dims { n, ni, no, .. } = Dims::of(plan);
    let position = solver_body(model, plan, &names, Mode::Position, false);
    let fused = solver_body(model, plan, &names, Mode::Fused, false);
    let at = solver_body(model, plan, &names, Mode::At, false);
    let residual = straight_line(model, plan, &names, &plan.residuals, true);
    let outputs_body = straight_line(model, plan, &names, &plan.outputs, true);
    let guess = straight_line(model, plan, &names, &plan.guesses, false);
    let jacobian = jacobian_body(model, plan, &names);
    let lints = kernel_lints();
    let (x, q, g, cfg) = (
        quote!(__x: &[f64; #ni]),
        quote!(__q: &[f64; #n]),
        quote!(__guess: &[f64; #n]),
        quote!(__cfg: &#rt::NewtonConfig),
    );
    let kin = quote!(::core::result::Result<#rt::Kin<#n, #ni, #no>, #rt::Error>);
    quote! {
        #lints
        impl #rt::Mechanism<#n, #ni, #no> for #name {
            const NAME: &'static str = #name::NAME;
            const PARAMS: &'static [&'static str] = &#name::PARAMS;
            const INPUTS: [&'static str; #ni] = #name::INPUTS;
            const UNKNOWNS: [&'static str; #n] = #name::UNKNOWNS;
            const EQUATIONS: [&'static str; #n] = #name::EQUATIONS;
            const OUTPUTS: [&'static str; #no] = #name::OUTPUTS;
            const BLOCKS: &'static [#rt::BlockInfo] = #name::BLOCKS;

            fn param_values(&self) -> ::std::vec::Vec<f64> {
                #name::param_values(self).to_vec()
            }
            fn guess_flat(&self, #x) -> [f64; #n] { #guess }
            fn residual_flat(&self, #x, #q) -> [f64; #n] { #residual }
            fn outputs_flat(&self, #x, #q) -> [f64; #no] { #outputs_body }
            fn jacobian_flat(&self, #x, #q) -> #rt::Jac<#n, #ni> { #jacobian }
            #[inline]
            fn position_flat(&self, #x, #g, #cfg) -> ::core::result::Result<([f64; #n], #rt::SolveReport), #rt::Error> {
                #position
            }
            #[inline]
            fn kinematics_flat(&self, #x, #g, #cfg) -> #kin { #fused }
            fn kinematics_at_flat(&self, #x, #q, #cfg) -> #kin { #at }
        }
        impl #rt::Named<#n, #ni, #no> for #name {
            type Inputs = #inputs;
            type Unknowns = #unknowns;
            type Outputs = #outputs;
            type State = #state;
        }
    }
}
