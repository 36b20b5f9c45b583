//! Generation of the user-facing items: the parameter struct, named structs for inputs,
//! unknowns and outputs (generic over the element type so analogs reuse them), the kinematic
//! state, the inherent API and the `Mechanism` trait impl.

use crate::emit::Names;
use crate::model::Model;
use crate::plan::Plan;
use crate::solver::{Mode, default_literals, jacobian_body, solver_body, straight_line};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use syn::Attribute;
use syn::ext::IdentExt;

fn doc_or(docs: &[Attribute], fallback: String) -> TokenStream {
    if docs.is_empty() { quote!(#[doc = #fallback]) } else { quote!(#(#docs)*) }
}

fn plain(id: &Ident) -> String {
    id.unraw().to_string()
}

pub fn generate(model: &Model, plan: &Plan) -> TokenStream {
    let rt = quote!(::kinloop::__private);
    let name = &model.name;
    let name_s = plain(name);
    let vis = &model.vis;
    let inputs_ty = format_ident!("{}Inputs", name_s);
    let unknowns_ty = format_ident!("{}Unknowns", name_s);
    let outputs_ty = format_ident!("{}Outputs", name_s);
    let state_ty = format_ident!("{}State", name_s);
    let motion_ty = format_ident!("{}Motion", name_s);

    let n = plan.n;
    let ni = plan.ni;
    let np = model.params.len();
    let no = plan.outputs.len();
    let (nl, nil, npl, nol) = (lit(n), lit(ni), lit(np), lit(no));

    let names = Names {
        params: model.params.iter().map(|p| format_ident!("p_{}", plain(&p.name))).collect(),
        inputs: model.inputs.iter().map(|p| format_ident!("x_{}", plain(&p.name))).collect(),
        unknowns: model.unknowns.iter().map(|p| format_ident!("q_{}", plain(&p.name))).collect(),
    };

    // ---------------------------------------------------------------- parameter struct
    let docs = &model.docs;
    let pfields = model.params.iter().map(|p| {
        let d = doc_or(&p.docs, format!("Parameter `{}`.", plain(&p.name)));
        let f = &p.name;
        quote!(#d pub #f: f64,)
    });
    let pnames: Vec<_> = model.params.iter().map(|p| &p.name).collect();
    let pstrs: Vec<String> = model.params.iter().map(|p| plain(&p.name)).collect();
    let default_impl = match &plan.defaults {
        Some(values) if !values.is_empty() => {
            let v = default_literals(values);
            quote! {
                impl ::core::default::Default for #name {
                    /// The parameter values declared in the mechanism.
                    fn default() -> Self {
                        #name { #(#pnames: #v),* }
                    }
                }
            }
        }
        _ => quote!(),
    };

    // ---------------------------------------------------------------- named structs
    let input_names: Vec<&Ident> = model.inputs.iter().map(|i| &i.name).collect();
    let input_strs: Vec<String> = input_names.iter().map(|i| plain(i)).collect();
    let unknown_names: Vec<&Ident> = model.unknowns.iter().map(|u| &u.name).collect();
    let unknown_strs: Vec<String> = unknown_names.iter().map(|u| plain(u)).collect();
    let input_docs = model.inputs.iter().map(|i| doc_or(&i.docs, format!("Input `{}`.", plain(&i.name))));
    let unknown_docs = model.unknowns.iter().map(|u| doc_or(&u.docs, format!("Unknown `{}`.", plain(&u.name))));
    let inputs_struct = named_struct(
        vis,
        &inputs_ty,
        &format!(
            "Inputs (generalized coordinates) of [`{name_s}`]. With `T = f64` the input values; \
             for a mechanism with several inputs, analogs hold one `{name_s}Inputs` of partial \
             derivatives per quantity."
        ),
        &input_names,
        &input_docs.collect::<Vec<_>>(),
    );
    let unknowns_struct = named_struct(
        vis,
        &unknowns_ty,
        &format!(
            "Unknowns of [`{name_s}`] by name: positions (`T = f64`), and their velocity and \
             acceleration analogs in [`{name_s}State`]."
        ),
        &unknown_names,
        &unknown_docs.collect::<Vec<_>>(),
    );
    let single_from = if ni == 1 {
        let i0 = input_names[0];
        quote! {
            impl ::core::convert::From<f64> for #inputs_ty<f64> {
                fn from(v: f64) -> Self {
                    #inputs_ty { #i0: v }
                }
            }
        }
    } else {
        quote!()
    };
    let nalgebra_from = quote! {
        impl ::core::convert::From<#rt::nalgebra::SVector<f64, #nl>> for #unknowns_ty<f64> {
            fn from(v: #rt::nalgebra::SVector<f64, #nl>) -> Self {
                let a: [f64; #nl] = v.into();
                a.into()
            }
        }
        impl ::core::convert::From<#unknowns_ty<f64>> for #rt::nalgebra::SVector<f64, #nl> {
            fn from(v: #unknowns_ty<f64>) -> Self {
                let a: [f64; #nl] = v.into();
                a.into()
            }
        }
    };

    // Outputs: points are Vec2<T>, scalars T; flat order is x, y per point then scalars.
    let mut out_fields = Vec::new();
    let mut out_from = Vec::new();
    let mut out_into = Vec::new();
    let mut flat_idents = Vec::new();
    let mut k = 0usize;
    for p in &model.points {
        let f = &p.name;
        let d = doc_or(&p.docs, format!("Point `{}`.", plain(f)));
        out_fields.push(quote!(#d pub #f: #rt::Vec2<T>,));
        let (a, b) = (format_ident!("o{}", k), format_ident!("o{}", k + 1));
        out_from.push(quote!(#f: #rt::Vec2 { x: #a, y: #b }));
        out_into.push(quote!(v.#f.x));
        out_into.push(quote!(v.#f.y));
        flat_idents.push(a);
        flat_idents.push(b);
        k += 2;
    }
    for s in &model.scalars {
        let f = &s.name;
        let d = doc_or(&s.docs, format!("Output `{}`.", plain(f)));
        out_fields.push(quote!(#d pub #f: T,));
        let a = format_ident!("o{}", k);
        out_from.push(quote!(#f: #a));
        out_into.push(quote!(v.#f));
        flat_idents.push(a);
        k += 1;
    }
    if k == 0 {
        out_fields.push(quote!(#[doc(hidden)] pub __marker: ::core::marker::PhantomData<T>,));
        out_from.push(quote!(__marker: ::core::marker::PhantomData));
    }
    let outputs_doc = format!(
        "Named outputs of [`{name_s}`] (points and scalar outputs); with `T = f64` their values, \
         in [`{name_s}State`] also their analogs."
    );
    let outputs_struct = quote! {
        #[doc = #outputs_doc]
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        #[allow(non_snake_case)]
        #vis struct #outputs_ty<T = f64> {
            #(#out_fields)*
        }
        impl<T> ::core::convert::From<[T; #nol]> for #outputs_ty<T> {
            #[allow(non_snake_case)]
            fn from([#(#flat_idents),*]: [T; #nol]) -> Self {
                #outputs_ty { #(#out_from),* }
            }
        }
        impl<T> ::core::convert::From<#outputs_ty<T>> for [T; #nol] {
            fn from(v: #outputs_ty<T>) -> Self {
                [#(#out_into),*]
            }
        }
    };

    // Analog element types: scalars for one input, per-input structs for several.
    let (v_ty, a_ty, conv_v, conv_a) = if ni == 1 {
        (quote!(f64), quote!(f64), quote!(|r: [f64; 1]| r[0]), quote!(|r: [[f64; 1]; 1]| r[0][0]))
    } else {
        (
            quote!(#inputs_ty<f64>),
            quote!(#inputs_ty<#inputs_ty<f64>>),
            quote!(#inputs_ty::<f64>::from),
            quote!(|r: [[f64; #nil]; #nil]| #inputs_ty::from(r.map(#inputs_ty::<f64>::from))),
        )
    };
    let analog_doc = if ni == 1 {
        format!("`d/d{}`", input_strs[0])
    } else {
        "partial derivatives: `dq.u.i` is `d u / d i`".to_string()
    };
    let state_doc = format!(
        "Kinematic state of [`{name_s}`] at one input value: positions, velocity analogs \
         ({analog_doc}), acceleration analogs, and the same for every output."
    );
    let motion_doc = format!("True velocities and accelerations of [`{name_s}`] (time derivatives).");
    let state_struct = quote! {
        #[doc = #state_doc]
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #state_ty {
            /// The input values.
            pub input: #inputs_ty,
            /// Positions of the unknowns.
            pub q: #unknowns_ty,
            /// Velocity analogs (first derivatives with respect to the inputs).
            pub dq: #unknowns_ty<#v_ty>,
            /// Acceleration analogs (second derivatives with respect to the inputs).
            pub d2q: #unknowns_ty<#a_ty>,
            /// Output values.
            pub out: #outputs_ty,
            /// Velocity analogs of the outputs.
            pub dout: #outputs_ty<#v_ty>,
            /// Acceleration analogs of the outputs.
            pub d2out: #outputs_ty<#a_ty>,
            /// Diagnostics of the position solve.
            pub report: #rt::SolveReport,
            /// Conditioning and assembly mode of each block.
            pub health: #rt::Health,
            /// The same values as flat arrays in declaration order (for generic code).
            pub flat: #rt::Kin<#nl, #nil, #nol>,
        }
        impl ::core::convert::From<#rt::Kin<#nl, #nil, #nol>> for #state_ty {
            #[inline]
            fn from(k: #rt::Kin<#nl, #nil, #nol>) -> Self {
                #state_ty {
                    input: #inputs_ty::from(k.x),
                    q: #unknowns_ty::from(k.q),
                    dq: #unknowns_ty::from(k.dq.map(#conv_v)),
                    d2q: #unknowns_ty::from(k.d2q.map(#conv_a)),
                    out: #outputs_ty::from(k.out),
                    dout: #outputs_ty::from(k.dout.map(#conv_v)),
                    d2out: #outputs_ty::from(k.d2out.map(#conv_a)),
                    report: k.report,
                    health: k.health,
                    flat: k,
                }
            }
        }
        #[allow(clippy::all, clippy::pedantic, clippy::nursery)]
        impl #state_ty {
            /// True velocities and accelerations for input speeds `omega` and input
            /// accelerations `eps`: `v = v_q omega`, `a = a_q omega^2 + v_q eps` (summed over
            /// inputs for several inputs). For a time input pass `omega = 1`, `eps = 0`.
            pub fn motion(
                &self,
                omega: impl ::core::convert::Into<#inputs_ty>,
                eps: impl ::core::convert::Into<#inputs_ty>,
            ) -> ::core::result::Result<#motion_ty, #rt::Error> {
                let w: [f64; #nil] = omega.into().into();
                let e: [f64; #nil] = eps.into().into();
                for (name, v) in [#(#input_strs),*].iter().chain([#(#input_strs),*].iter()).zip(w.iter().chain(e.iter())) {
                    if !v.is_finite() {
                        return Err(#rt::Error::NonFinite {
                            what: #rt::Quantity::Motion,
                            name,
                            value: *v,
                            at: ::std::boxed::Box::new(#rt::Location {
                                mechanism: #name_s,
                                inputs: [#(#input_strs),*].iter().copied().zip(self.flat.x).collect(),
                                block: None,
                            }),
                        });
                    }
                }
                let m = self.flat.motion(&w, &e);
                Ok(#motion_ty {
                    qdot: m.qdot.into(),
                    qddot: m.qddot.into(),
                    out_dot: m.out_dot.into(),
                    out_ddot: m.out_ddot.into(),
                })
            }
        }
        #[doc = #motion_doc]
        #[derive(Clone, Copy, Debug, PartialEq)]
        #vis struct #motion_ty {
            /// Velocities of the unknowns.
            pub qdot: #unknowns_ty,
            /// Accelerations of the unknowns.
            pub qddot: #unknowns_ty,
            /// Velocities of the outputs.
            pub out_dot: #outputs_ty,
            /// Accelerations of the outputs.
            pub out_ddot: #outputs_ty,
        }
    };

    // ---------------------------------------------------------------- constants
    let eq_strs: Vec<String> = model.equations.iter().map(|e| e.name.clone()).collect();
    let out_strs = model.output_names();
    let decomposition = crate::describe::decomposition(model, plan);
    let blocks = plan.blocks.iter().map(|b| {
        let us = b.unknowns.iter().map(|&u| &unknown_strs[u]);
        let es = b.equations.iter().map(|&e| &eq_strs[e]);
        let linear = b.linear;
        quote!(#rt::BlockInfo { unknowns: &[#(#us),*], equations: &[#(#es),*], linear: #linear })
    });

    // ---------------------------------------------------------------- solver functions
    let pos_body = solver_body(model, plan, &names, Mode::Position, &rt);
    let fused_body = solver_body(model, plan, &names, Mode::Fused, &rt);
    let at_body = solver_body(model, plan, &names, Mode::At, &rt);
    let residual_body = straight_line(model, plan, &names, &plan.residuals, true);
    let outputs_body = straight_line(model, plan, &names, &plan.outputs, true);
    let guess_body = straight_line(model, plan, &names, &plan.guesses, false);
    let jacobian = jacobian_body(model, plan, &names, &rt);
    let sens_items = crate::sens_items::generate(model, plan, &names, &rt);

    let param_vals = pnames.iter().map(|p| quote!(self.#p));
    let from_params = pnames.iter().enumerate().map(|(k, p)| {
        let k = lit(k);
        quote!(#p: v[#k])
    });

    let lints = solver_lints();

    let inputs_arg = quote!(input: impl ::core::convert::Into<#inputs_ty>);
    let to_x = quote!(let __x: [f64; #nil] = ::core::convert::Into::<#inputs_ty>::into(input).into(););
    let err = quote!(#rt::Error);

    let params_struct = params_struct(docs, vis, name, pfields);

    quote! {
        #params_struct
        #default_impl
        #inputs_struct
        #single_from
        #unknowns_struct
        #nalgebra_from
        #outputs_struct
        #state_struct
        #sens_items

        #[allow(clippy::all, clippy::pedantic, clippy::nursery)]
        impl #name {
            /// The mechanism's type name.
            pub const NAME: &'static str = #name_s;
            /// Parameter names, in declaration order.
            pub const PARAMS: [&'static str; #npl] = [#(#pstrs),*];
            /// Input names.
            pub const INPUTS: [&'static str; #nil] = [#(#input_strs),*];
            /// Unknown names.
            pub const UNKNOWNS: [&'static str; #nl] = [#(#unknown_strs),*];
            /// Scalar equation names: `loop.x` and `loop.y` for each loop, the `eq` names.
            pub const EQUATIONS: [&'static str; #nl] = [#(#eq_strs),*];
            /// Output columns: `point.x`, `point.y` for each point, then scalar outputs.
            pub const OUTPUTS: [&'static str; #nol] = [#(#out_strs),*];
            /// The block-triangular decomposition of the equations, in solve order.
            pub const BLOCKS: &'static [#rt::BlockInfo] = &[#(#blocks),*];
            /// The decomposition in words: counts and mobility, then one line per block in
            /// solve order (Newton or linear, size, unknowns `<-` equations).
            pub const DECOMPOSITION: &'static str = #decomposition;

            /// Parameter values in declaration order.
            pub fn param_values(&self) -> [f64; #npl] {
                [#(#param_vals),*]
            }

            /// Builds the mechanism from parameter values in declaration order.
            pub fn from_param_values(v: [f64; #npl]) -> Self {
                #name { #(#from_params),* }
            }

            /// Checks that every parameter is finite.
            pub fn check(&self) -> ::core::result::Result<(), #err> {
                match self.__bad_values(&[0.0; #nil], None) {
                    Some(e) => Err(e),
                    None => Ok(()),
                }
            }

            /// The declared initial guess (assembly mode) at `input`.
            pub fn guess(&self, #inputs_arg) -> #unknowns_ty {
                #to_x
                self.__guess(&__x).into()
            }

            /// Residuals of the scalar equations (named by [`Self::EQUATIONS`]) at a position.
            pub fn residual(&self, #inputs_arg, q: &#unknowns_ty) -> [f64; #nl] {
                #to_x
                self.__residual(&__x, &(*q).into())
            }

            /// Solves the positions by Newton's method from `guess` (which picks the assembly
            /// mode), with the default [`NewtonConfig`](::kinloop::NewtonConfig).
            pub fn position(&self, #inputs_arg, guess: &#unknowns_ty) -> ::core::result::Result<(#unknowns_ty, #rt::SolveReport), #err> {
                self.position_with(input, guess, &#rt::NewtonConfig::default())
            }

            /// [`Self::position`] with an explicit solver configuration.
            pub fn position_with(&self, #inputs_arg, guess: &#unknowns_ty, cfg: &#rt::NewtonConfig) -> ::core::result::Result<(#unknowns_ty, #rt::SolveReport), #err> {
                #to_x
                let (q, report) = self.__position(&__x, &(*guess).into(), cfg)?;
                Ok((q.into(), report))
            }

            /// Positions, velocity and acceleration analogs, and outputs, solved from `guess`.
            pub fn kinematics(&self, #inputs_arg, guess: &#unknowns_ty) -> ::core::result::Result<#state_ty, #err> {
                self.kinematics_with(input, guess, &#rt::NewtonConfig::default())
            }

            /// [`Self::kinematics`] with an explicit solver configuration.
            #[inline]
            pub fn kinematics_with(&self, #inputs_arg, guess: &#unknowns_ty, cfg: &#rt::NewtonConfig) -> ::core::result::Result<#state_ty, #err> {
                #to_x
                self.__kinematics(&__x, &(*guess).into(), cfg).map(#state_ty::from)
            }

            /// Analogs and outputs at a position the caller already solved.
            pub fn kinematics_at(&self, #inputs_arg, q: &#unknowns_ty) -> ::core::result::Result<#state_ty, #err> {
                #to_x
                self.__kinematics_at(&__x, &(*q).into(), &#rt::NewtonConfig::default()).map(#state_ty::from)
            }

            /// Full kinematics at `input`, starting from the declared initial guess.
            pub fn solve(&self, #inputs_arg) -> ::core::result::Result<#state_ty, #err> {
                #to_x
                let g = self.__guess(&__x);
                self.__kinematics(&__x, &g, &#rt::NewtonConfig::default()).map(#state_ty::from)
            }

            /// A lazy sweep of `samples` equally spaced inputs from `from` to `to` (both included)
            /// that never jumps branches: see [`Sweep`](::kinloop::Sweep). `guess` at `from`
            /// picks the assembly mode.
            pub fn sweep(
                &self,
                from: impl ::core::convert::Into<#inputs_ty>,
                to: impl ::core::convert::Into<#inputs_ty>,
                samples: usize,
                guess: &#unknowns_ty,
            ) -> ::core::result::Result<#rt::Sweep<'_, Self, #state_ty, #nl, #nil, #nol>, #err> {
                let from: [f64; #nil] = ::core::convert::Into::<#inputs_ty>::into(from).into();
                let to: [f64; #nil] = ::core::convert::Into::<#inputs_ty>::into(to).into();
                #rt::Sweep::new(self, from, to, samples, (*guess).into())
            }

            /// The distinct assembly modes at `input` (multi-start Newton; see
            /// [`assembly_modes`](::kinloop::assembly_modes)), e.g. to pick "elbow up" with
            /// `.into_iter().find(|s| ...)`.
            pub fn assembly_modes(&self, #inputs_arg) -> ::std::vec::Vec<#state_ty> {
                #to_x
                #rt::assembly_modes(self, &__x, 64, &#rt::NewtonConfig::default()).into_iter().map(#state_ty::from).collect()
            }

            /// Output values at a position.
            pub fn outputs(&self, #inputs_arg, q: &#unknowns_ty) -> #outputs_ty {
                #to_x
                self.__outputs(&__x, &(*q).into()).into()
            }

            #lints
            #[inline]
            fn __position(&self, __x: &[f64; #nil], __guess: &[f64; #nl], __cfg: &#rt::NewtonConfig) -> ::core::result::Result<([f64; #nl], #rt::SolveReport), #err> {
                #pos_body
            }

            #lints
            #[inline]
            fn __kinematics(&self, __x: &[f64; #nil], __guess: &[f64; #nl], __cfg: &#rt::NewtonConfig) -> ::core::result::Result<#rt::Kin<#nl, #nil, #nol>, #err> {
                #fused_body
            }

            #lints
            fn __kinematics_at(&self, __x: &[f64; #nil], __q: &[f64; #nl], __cfg: &#rt::NewtonConfig) -> ::core::result::Result<#rt::Kin<#nl, #nil, #nol>, #err> {
                #at_body
            }

            #lints
            fn __residual(&self, __x: &[f64; #nil], __q: &[f64; #nl]) -> [f64; #nl] {
                #residual_body
            }

            #lints
            fn __outputs(&self, __x: &[f64; #nil], __q: &[f64; #nl]) -> [f64; #nol] {
                #outputs_body
            }

            #lints
            fn __guess(&self, __x: &[f64; #nil]) -> [f64; #nl] {
                #guess_body
            }

            #lints
            fn __jacobian(&self, __x: &[f64; #nil], __q: &[f64; #nl]) -> #rt::Jac<#nl, #nil> {
                #jacobian
            }

            #[cold]
            #[inline(never)]
            fn __location(&self, __x: &[f64; #nil], block: ::core::option::Option<usize>) -> #rt::Location {
                #rt::Location {
                    mechanism: Self::NAME,
                    inputs: Self::INPUTS.iter().copied().zip(__x.iter().copied()).collect(),
                    block: block.and_then(|b| Self::BLOCKS.get(b).map(|i| (b, *i))),
                }
            }

            /// The first non-finite parameter, input or guess, as an error.
            #[cold]
            #[inline(never)]
            fn __bad_values(&self, __x: &[f64; #nil], __guess: ::core::option::Option<&[f64; #nl]>) -> ::core::option::Option<#err> {
                let at = || ::std::boxed::Box::new(self.__location(__x, None));
                if let Some((name, value)) = #rt::first_non_finite(&Self::PARAMS, &self.param_values()) {
                    return Some(#rt::Error::NonFinite { what: #rt::Quantity::Parameter, name, value, at: at() });
                }
                if let Some((name, value)) = #rt::first_non_finite(&Self::INPUTS, __x) {
                    return Some(#rt::Error::NonFinite { what: #rt::Quantity::Input, name, value, at: at() });
                }
                if let Some(g) = __guess {
                    if let Some((name, value)) = #rt::first_non_finite(&Self::UNKNOWNS, g) {
                        return Some(#rt::Error::NonFinite { what: #rt::Quantity::Guess, name, value, at: at() });
                    }
                }
                None
            }

            #[cold]
            #[inline(never)]
            fn __block_failure(&self, block: usize, fail: #rt::BlockFailure, __x: &[f64; #nil], __guess: &[f64; #nl]) -> #err {
                if let Some(e) = self.__bad_values(__x, Some(__guess)) {
                    return e;
                }
                #rt::block_error(fail, self.__location(__x, Some(block)))
            }

            #[cold]
            #[inline(never)]
            fn __singular(&self, block: usize, pivot_ratio: f64, cfg: &#rt::NewtonConfig, __x: &[f64; #nil], bad_row: ::core::option::Option<usize>) -> #err {
                if let Some(e) = self.__bad_values(__x, None) {
                    return e;
                }
                let at = ::std::boxed::Box::new(self.__location(__x, Some(block)));
                if let Some(row) = bad_row {
                    let name = Self::BLOCKS.get(block).and_then(|b| b.equations.get(row)).copied().unwrap_or("?");
                    return #rt::Error::Domain { what: "equation", name, at };
                }
                #rt::Error::Singular { pivot_ratio, tolerance: cfg.singular_tol, at }
            }

            #[cold]
            #[inline(never)]
            fn __non_finite(&self, kin: &#rt::Kin<#nl, #nil, #nol>, __x: &[f64; #nil], __guess: ::core::option::Option<&[f64; #nl]>) -> #err {
                if let Some(e) = self.__bad_values(__x, __guess) {
                    return e;
                }
                let (what, index) = kin.first_non_finite().unwrap_or(("value", 0));
                let name = if what.starts_with("output") {
                    Self::OUTPUTS.get(index).copied()
                } else {
                    Self::UNKNOWNS.get(index).copied()
                };
                #rt::Error::Domain {
                    what,
                    name: name.unwrap_or("?"),
                    at: ::std::boxed::Box::new(self.__location(__x, None)),
                }
            }
        }

        #[allow(clippy::all, clippy::pedantic, clippy::nursery)]
        impl #rt::Mechanism<#nl, #nil, #nol> for #name {
            const NAME: &'static str = #name_s;
            const PARAMS: &'static [&'static str] = &[#(#pstrs),*];
            const INPUTS: [&'static str; #nil] = [#(#input_strs),*];
            const UNKNOWNS: [&'static str; #nl] = [#(#unknown_strs),*];
            const EQUATIONS: [&'static str; #nl] = [#(#eq_strs),*];
            const OUTPUTS: [&'static str; #nol] = [#(#out_strs),*];
            const BLOCKS: &'static [#rt::BlockInfo] = #name::BLOCKS;

            fn param_values(&self) -> ::std::vec::Vec<f64> {
                #name::param_values(self).to_vec()
            }
            fn guess_flat(&self, x: &[f64; #nil]) -> [f64; #nl] {
                self.__guess(x)
            }
            fn residual_flat(&self, x: &[f64; #nil], q: &[f64; #nl]) -> [f64; #nl] {
                self.__residual(x, q)
            }
            #[inline]
            fn position_flat(&self, x: &[f64; #nil], guess: &[f64; #nl], cfg: &#rt::NewtonConfig) -> ::core::result::Result<([f64; #nl], #rt::SolveReport), #err> {
                self.__position(x, guess, cfg)
            }
            #[inline]
            fn kinematics_flat(&self, x: &[f64; #nil], guess: &[f64; #nl], cfg: &#rt::NewtonConfig) -> ::core::result::Result<#rt::Kin<#nl, #nil, #nol>, #err> {
                self.__kinematics(x, guess, cfg)
            }
            fn kinematics_at_flat(&self, x: &[f64; #nil], q: &[f64; #nl], cfg: &#rt::NewtonConfig) -> ::core::result::Result<#rt::Kin<#nl, #nil, #nol>, #err> {
                self.__kinematics_at(x, q, cfg)
            }
            fn outputs_flat(&self, x: &[f64; #nil], q: &[f64; #nl]) -> [f64; #nol] {
                self.__outputs(x, q)
            }
            fn jacobian_flat(&self, x: &[f64; #nil], q: &[f64; #nl]) -> #rt::Jac<#nl, #nil> {
                self.__jacobian(x, q)
            }
            fn check_params(&self) -> ::core::result::Result<(), #err> {
                self.check()
            }
        }
    }
}

pub(crate) fn lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

/// The parameter struct: the declaration's docs, visibility and name, with the `fields`.
pub(crate) fn params_struct(
    docs: &[Attribute],
    vis: &syn::Visibility,
    name: &Ident,
    fields: impl Iterator<Item = TokenStream>,
) -> TokenStream {
    quote! {
        #(#docs)*
        #[derive(Clone, Copy, Debug, PartialEq)]
        #[allow(non_snake_case)]
        #vis struct #name {
            #(#fields)*
        }
    }
}

/// Lints allowed on the generated solver functions (straight-line code with generated names).
pub(crate) fn solver_lints() -> TokenStream {
    quote!(#[allow(
        unused_variables,
        unused_mut,
        non_snake_case,
        clippy::all,
        clippy::pedantic,
        clippy::nursery
    )])
}

/// A struct generic over its element type `T` with one field per name, and its conversions
/// from and to `[T; n]` in field order.
pub(crate) fn named_struct(
    vis: &syn::Visibility,
    ty: &Ident,
    doc: &str,
    fields: &[&Ident],
    docs: &[TokenStream],
) -> TokenStream {
    let n = lit(fields.len());
    let bind: Vec<Ident> = (0..fields.len()).map(|k| Ident::new(&format!("f{k}"), Span::call_site())).collect();
    // A struct without fields still mentions `T`.
    let (marker, marker_init) = if fields.is_empty() {
        (
            quote!(#[doc(hidden)] pub __marker: ::core::marker::PhantomData<T>,),
            quote!(__marker: ::core::marker::PhantomData),
        )
    } else {
        (quote!(), quote!())
    };
    quote! {
        #[doc = #doc]
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        #[allow(non_snake_case)]
        #vis struct #ty<T = f64> {
            #(#docs pub #fields: T,)*
            #marker
        }
        impl<T> ::core::convert::From<[T; #n]> for #ty<T> {
            #[inline]
            fn from([#(#bind),*]: [T; #n]) -> Self {
                #ty { #(#fields: #bind,)* #marker_init }
            }
        }
        impl<T> ::core::convert::From<#ty<T>> for [T; #n] {
            #[inline]
            fn from(v: #ty<T>) -> Self {
                [#(v.#fields),*]
            }
        }
    }
}
