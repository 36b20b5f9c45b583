//! The mechanism's implementation of the runtime traits (`Mechanism` with the kernels, `Named`
//! with the named types), its constants, and its inherent methods: one-line forwarders into the
//! runtime's generic code, so that `m.solve(x)` needs no import.

use super::dims::Dims;
use super::evaluate::{jacobian_body, straight_line};
use super::kernel::{Mode, closed_config_check, deferred_body, solver_body};
use super::lints::kernel_lints;
use super::literals::lit;
use super::names::Names;
use super::runtime_path::runtime;
use super::type_names::Types;
use crate::plan::Plan;
use crate::plan::kinds::Kind;
use crate::semantics::model::Model;
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;

/// Every item implementing the mechanism.
pub fn items(model: &Model, plan: &Plan, t: &Types) -> TokenStream {
    let mut out = constants(model, plan, t);
    out.extend(forwarders(t, &Dims::of(plan)));
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
    let pindex = (0..pnames.len()).map(proc_macro2::Literal::usize_unsuffixed);
    let istrs = strs(model.inputs.iter().map(|p| &p.name).collect());
    let ustrs = strs(model.unknowns.iter().map(|p| &p.name).collect());
    let estrs: Vec<String> = model.equations.iter().map(|e| e.name.clone()).collect();
    let ostrs = model.output_names();
    let decomposition = super::describe::decomposition(model, plan);
    let blocks = plan.blocks.iter().map(|b| {
        let us = b.unknowns.iter().map(|&u| &ustrs[u]);
        let es = b.equations.iter().map(|&e| &estrs[e]);
        let linear = b.solve.is_linear();
        quote!(#rt::BlockInfo::borrowed(&[#(#rt::Name(#us)),*], &[#(#rt::Name(#es)),*], #linear))
    });
    quote! {
        impl #name {
            /// The mechanism's type name.
            pub const NAME: &'static ::core::primitive::str = #plain;
            /// Parameter names, in declaration order.
            pub const PARAMS: [&'static ::core::primitive::str; #np] = [#(#pstrs),*];
            /// Input names.
            pub const INPUTS: [&'static ::core::primitive::str; #ni] = [#(#istrs),*];
            /// Unknown names.
            pub const UNKNOWNS: [&'static ::core::primitive::str; #n] = [#(#ustrs),*];
            /// Scalar equation names: `loop.x` and `loop.y` for each loop, the `eq` names.
            pub const EQUATIONS: [&'static ::core::primitive::str; #n] = [#(#estrs),*];
            /// Output columns: `point.x`, `point.y` for each point, then scalar outputs.
            pub const OUTPUTS: [&'static ::core::primitive::str; #no] = [#(#ostrs),*];
            /// The block-triangular decomposition of the equations, in solve order.
            pub const BLOCKS: &'static [#rt::BlockInfo] = &[#(#blocks),*];
            /// The decomposition in words: counts and mobility, then one line per block in
            /// solve order (closed form, Newton or linear, unknowns `<-` equations).
            pub const DECOMPOSITION: &'static ::core::primitive::str = #decomposition;

            /// Parameter values in declaration order.
            pub fn param_values(&self) -> [::core::primitive::f64; #np] {
                [#(self.#pnames),*]
            }

            #rt::from_param_values!(#np; #(#pnames #pindex),*);
        }
    }
}

/// `INPUT_KINDS`, `UNKNOWN_KINDS`, `CLOSED_FORM_ANGLES`, `OUTPUT_KINDS` of the `Mechanism`
/// implementation: the kind of quantity of every column (see [`crate::plan::kinds`]) by its
/// name, and which unknowns a closed-form block gives as angles, written out by the runtime's
/// macro (the inherent constants forward to them); and the tail of `mechanism_consts!` that
/// lists the parameters that are angles (`; 5 f`, empty where none is).
fn kind_constants(model: &Model, plan: &Plan) -> (TokenStream, TokenStream) {
    let rt = runtime();
    let Dims { n, ni, no, .. } = Dims::of(plan);
    let kinds = crate::plan::kinds::classify(model, &plan.graph, &plan.residuals, &plan.outputs);
    let closed = crate::plan::closed_form_angles(plan);
    let list = |ks: &[Kind]| {
        let names = ks.iter().map(|k| {
            let name = match k {
                Kind::Angle => "Angle",
                Kind::Length => "Length",
                Kind::Dimensionless => "Dimensionless",
                Kind::Other => "Other",
            };
            Ident::new(name, Span::call_site())
        });
        quote!([#(#names),*])
    };
    let (i, u, o) = (list(&kinds.inputs), list(&kinds.unknowns), list(&kinds.outputs));
    // The parameters that are angles, for `Mechanism::angle_param_beyond`, which the runtime's
    // `mechanism_consts!` writes from them: a few tokens of its line, not a method of the
    // expansion's (whose every line a reader of it reads).
    let angles: Vec<_> =
        model.params.iter().zip(&kinds.params).enumerate().filter(|(_, (_, k))| **k == Kind::Angle).collect();
    let (ks, names) = (angles.iter().map(|(k, _)| lit(*k)), angles.iter().map(|(_, (p, _))| &p.name));
    let angle_params = if angles.is_empty() { TokenStream::new() } else { quote!(; #(#ks #names),*) };
    (quote!(#rt::kinds!(#ni #i, #n #u [#(#closed),*], #no #o);), angle_params)
}

/// `FOLLOWERS` of the `Mechanism` implementation (see [`crate::plan::followers`]), when an
/// unknown follows the others (the default says none does).
fn followers_constant(plan: &Plan) -> TokenStream {
    let n = super::literals::lit(plan.n);
    let follows = crate::plan::followers::followers(&plan.graph, &plan.blocks, plan.n);
    if follows.iter().any(|&f| f) {
        quote!(const FOLLOWERS: [::core::primitive::bool; #n] = [#(#follows),*];)
    } else {
        TokenStream::new()
    }
}

/// `PIECEWISE` of the `Mechanism` implementation (see [`crate::plan::piecewise`]), where the
/// positions may jump (the default says they do not).
fn piecewise_constant(plan: &Plan) -> TokenStream {
    if crate::plan::piecewise(plan) {
        quote!(
            const PIECEWISE: ::core::primitive::bool = true;
        )
    } else {
        TokenStream::new()
    }
}

/// The inherent named API (forwarders to the runtime's `Named`), `state.motion` and the
/// conversions that depend only on the type names: one invocation of the runtime's macro.
fn forwarders(t: &Types, d: &Dims) -> TokenStream {
    let rt = runtime();
    let Types { name, inputs, unknowns, outputs, state, motion, .. } = t;
    let Dims { n, ni, no, .. } = d;
    quote!(#rt::named_api!(#name, #inputs, #unknowns, #outputs, #state, #motion, #n, #ni, #no);)
}

/// Mechanisms with at most this many unknowns have their kernel inlined into a sweep's step.
const SWEEP_INLINE_MAX_UNKNOWNS: usize = 8;

/// `Mechanism` for the mechanism: its constants and kernels (the residuals are those of
/// `jacobian_flat`).
fn mechanism_impl(model: &Model, plan: &Plan, t: &Types) -> TokenStream {
    let (rt, name, names) = (runtime(), &t.name, Names::new(model, plan));
    let Dims { n, ni, no, .. } = Dims::of(plan);
    // The positions alone, their failure at an extreme size rescued as `kinematics_flat`'s
    // is (`extreme_scale`), with no analogs.
    let position_ret = quote!(#rt::PositionResult<#n>);
    let position =
        rescued(solver_body(plan, &names, Mode::Position, false), &position_ret, quote!(#rt::rescue_position));
    let at = solver_body(plan, &names, Mode::At, false);
    let outputs_body = straight_line(plan, &names, &plan.outputs, true);
    let guess = straight_line(plan, &names, &plan.guesses, false);
    let jacobian = jacobian_body(plan, &names);
    let lints = kernel_lints();
    let (kinds, angle_params) = kind_constants(model, plan);
    let followers = followers_constant(plan);
    let piecewise = piecewise_constant(plan);
    let drawing = super::drawing::constant(model);
    let (x, q, g, cfg) = (
        quote!(__x: &[::core::primitive::f64; #ni]),
        quote!(__q: &[::core::primitive::f64; #n]),
        quote!(__guess: &[::core::primitive::f64; #n]),
        quote!(__cfg: &#rt::NewtonConfig),
    );
    let kin = quote!(#rt::KinResult<#n, #ni, #no>);
    // A small mechanism's kernel is always inlined into a sweep's step (the sweep's loop holds
    // it: no call, the state written in place); `kinematics_flat` is the same kernel, inlined
    // where the compiler chooses. A large one is not copied.
    // The sweep's kernel asks its cache for the sines and cosines free of the unknowns (it
    // advances them by rotation); `kinematics_flat` gives it libm (and a failure at an extreme
    // size its rescue, `Mechanism::kinematics_step_rescued_with`). Its checks are switched by
    // `__CHECKED`: `kinematics_flat` tests on the way; the sweep's step defers the tests to the
    // end, where a failed one hands the step to the checked kernel, out of line
    // (`Mechanism::kinematics_step_checked`).
    let fused_fns = if plan.n <= SWEEP_INLINE_MAX_UNKNOWNS {
        let kernel_names = names.with_input_trig(plan);
        let fused = deferred_body(plan, &kernel_names);
        // The sweep's kernel is given a configuration checked once per sweep.
        let check = closed_config_check(plan);
        // The sines and cosines of parameters the kernel asks for (the fixed part of a sum such
        // as `phi1 + gamma`) are computed here, before the call, so that a caller's loop that
        // borrows the mechanism computes them once even where the compiler keeps the kernel out
        // of line; the kernel gets them through `Preset`, the same values to the bit.
        // (Without such values, libm's for every slot.) The kernel itself is left to the
        // compiler to inline (`kinematics_step_rescued_with`).
        let preset = kernel_names.parameter_slots(&plan.graph);
        let trig = if preset.is_empty() {
            quote!(#rt::Libm)
        } else {
            let slots = preset.iter().map(|(slot, _)| lit(*slot));
            let args = preset.iter().map(|(_, arg)| arg);
            quote!(#rt::Preset { slots: [#(#slots),*], values: [#((#args).sin_cos()),*] })
        };
        let flat = quote! {
            #[inline(always)]
            fn kinematics_flat(&self, #x, #g, #cfg) -> #kin {
                #check
                self.kinematics_step_rescued_with(__x, __guess, __cfg, &mut #trig)
            }
        };
        quote! {
            #[inline(always)]
            fn kinematics_step_sink<
                T: #rt::InputTrig,
                S: #rt::KinSink<#n, #ni, #no>,
                const __CHECKED: ::core::primitive::bool,
            >(
                &self, #x, #g, #cfg, __trig: &mut T, __sink: S,
            ) -> ::core::result::Result<S::Out, #rt::Error> { #fused }
            #flat
        }
    } else {
        // The kernel's failure at an extreme size goes to the rescue (`extreme_scale`), as a
        // small mechanism's does through `kinematics_step_rescued_with`.
        let fused = rescued(solver_body(plan, &names, Mode::Fused, false), &kin, quote!(#rt::rescue));
        quote! {
            #[inline]
            fn kinematics_flat(&self, #x, #g, #cfg) -> #kin { #fused }
        }
    };
    quote! {
        #lints
        impl #rt::Mechanism<#n, #ni, #no> for #name {
            #rt::mechanism_consts!(#name, #n, #ni, #no #angle_params);
            #kinds
            #followers
            #piecewise
            #drawing
            fn guess_flat(&self, #x) -> [::core::primitive::f64; #n] { #guess }
            fn outputs_flat(&self, #x, #q) -> [::core::primitive::f64; #no] { #outputs_body }
            fn jacobian_flat(&self, #x, #q) -> #rt::Jac<#n, #ni> { #jacobian }
            #[inline]
            fn position_flat(&self, #x, #g, #cfg) -> #position_ret { #position }
            #fused_fns
            fn kinematics_at_flat(&self, #x, #q, #cfg) -> #kin { #at }
        }
    }
}

/// The checked kernel `body` (of a function of `__x`, `__guess` and `__cfg` returning `ret`, a
/// `Result`) with its failure handed to `rescue` (`kinloop::__gen::rescue` or
/// `rescue_sensitivities`: cold, out of line), which solves the position again where the
/// mechanism's size is beyond the closed forms' (`extreme_scale`) and otherwise returns the
/// kernel's error. What `kinematics_flat` of a mechanism too large for a sweep to inline,
/// every `sensitivities_flat` and every `position_flat` (`rescue_position`) are.
pub(super) fn rescued(body: TokenStream, ret: &TokenStream, rescue: TokenStream) -> TokenStream {
    quote! {
        // A closure, so that the kernel's early returns land here.
        #[allow(clippy::redundant_closure_call)]
        let __solved = (|| -> #ret { #body })();
        match __solved {
            ::core::result::Result::Err(__e) => #rescue(self, __x, __guess, __cfg, __e),
            __ok => __ok,
        }
    }
}
