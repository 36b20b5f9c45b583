//! The declared dynamics as a method `mass_model(&self)` building the runtime's `MassModel`.
//!
//! Masses, moments of inertia, constant coordinates and gravity are expressions of the
//! parameters, computed once when the model is built. Force and torque laws are closures of
//! straight-line code reading the inputs and unknowns from the kinematic state; they own copies
//! of the parameters they use, so the model does not borrow the mechanism. Their virtual power
//! uses the analogs of the points they act at, which the state already holds.

use super::dims::Dims;
use super::lints::kernel_lints;
use super::literals::lit;
use super::names::Names;
use super::runtime_path::runtime;
use super::schedule::{ScopeKind, ScopeSpec, schedule};
use super::type_names::Types;
use crate::graph::dag::{Graph, Leaf, NodeId};
use crate::plan::Plan;
use crate::semantics::dynamics::{AngleModel, BodyModel, CoordModel, ForceModel, TorqueModel};
use crate::semantics::model::Model;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::ext::IdentExt;

/// What the pieces of `mass_model` share: the graph, operand names and the runtime path.
struct Ctx<'a> {
    rt: TokenStream,
    g: &'a Graph,
    names: Names,
    /// The type of the state the load laws read, `&Kin<N, NI, NO>`.
    kin: TokenStream,
    ni: TokenStream,
}

/// `mass_model` when the declaration has dynamics items, else [`absent`].
pub fn items(model: &Model, plan: &Plan, t: &Types) -> TokenStream {
    let d = &model.dynamics;
    if !d.is_declared() {
        return absent(t);
    }
    let (rt, name) = (runtime(), &t.name);
    let Dims { n, ni, no, .. } = Dims::of(plan);
    let mut names = Names::new(model, plan);
    let params: Vec<_> = model.params.iter().map(|p| format_ident!("__p_{}", p.name.unraw().to_string())).collect();
    names.params = params.iter().map(|p| quote!(#p)).collect();
    let kin = quote!(&#rt::Kin<#n, #ni, #no>);
    let cx = Ctx { rt: rt.clone(), g: &plan.graph, names, kin, ni: quote!(#ni) };
    let constants = constant_nodes(model);
    let mut all = constants.clone();
    all.extend(d.forces.iter().flat_map(|f| f.value));
    all.extend(d.torques.iter().map(|t| t.value));
    let bind = cx.g.leaves_of(&all).into_iter().filter_map(|l| match l {
        Leaf::Param(k) => {
            let (local, field) = (&params[k as usize], &model.params[k as usize].name);
            Some(quote!(let #local: ::core::primitive::f64 = self.#field;))
        }
        _ => None,
    });
    let constant_lets = lets(cx.g, &cx.names, &constants);
    let gravity = d.gravity.map(|[x, y]| {
        let (x, y) = (cx.names.operand(cx.g, x), cx.names.operand(cx.g, y));
        quote!(let __model = __model.with_gravity([#x, #y])?;)
    });
    let (bodies, forces, torques) = (bodies(&cx, model), forces(&cx, model), torques(&cx, model));
    let lints = kernel_lints();
    quote! {
        #lints
        impl #name {
            /// The declared bodies, loads and gravity as a mass model of `kinloop::dynamics`
            /// (reduced inertia, inverse dynamics, shaking forces, flywheel, simulation), with
            /// this mechanism's parameter values.
            ///
            /// # Errors
            ///
            /// A mass or moment of inertia that is negative or not finite, or a gravity that is
            /// not finite, with these parameter values.
            pub fn mass_model(&self) -> ::core::result::Result<#rt::MassModel<#n, #ni, #no>, #rt::DynamicsError> {
                #(#bind)*
                #constant_lets
                let __model = #rt::MassModel::<#n, #ni, #no>::new();
                #gravity
                #(#bodies)*
                #(#forces)*
                #(#torques)*
                ::core::result::Result::Ok(__model)
            }
        }
    }
}

/// The nodes computed once when the model is built: gravity, masses, inertias and constant
/// coordinates.
fn constant_nodes(model: &Model) -> Vec<NodeId> {
    let d = &model.dynamics;
    let mut constants: Vec<NodeId> = d.gravity.iter().flatten().copied().collect();
    for b in &d.bodies {
        constants.extend([b.mass, b.inertia]);
        constants.extend(b.com.iter().filter_map(fixed));
    }
    constants.extend(d.forces.iter().flat_map(|f| f.at.iter().filter_map(fixed)));
    constants
}

/// A coordinate of a centre of mass or load point as the runtime's `Coord`.
fn coord(cx: &Ctx, c: &CoordModel) -> TokenStream {
    let rt = &cx.rt;
    match *c {
        CoordModel::Output(c) => {
            let c = lit(c);
            quote!(#rt::Coord::Output(#c))
        }
        CoordModel::Unknown(u) => {
            let u = lit(u);
            quote!(#rt::Coord::Unknown(#u))
        }
        CoordModel::Fixed(v) => {
            let v = cx.names.operand(cx.g, v);
            quote!(#rt::Coord::Fixed(#v))
        }
    }
}

/// One `with_body` per declared body.
fn bodies(cx: &Ctx, model: &Model) -> Vec<TokenStream> {
    let (rt, g) = (&cx.rt, cx.g);
    let body = |b: &BodyModel| {
        let (bname, mass, inertia) = (&b.name, cx.names.operand(g, b.mass), cx.names.operand(g, b.inertia));
        let (px, py, rotation) = (coord(cx, &b.com[0]), coord(cx, &b.com[1]), angle(b.turns));
        quote! {
            let __model = __model.with_body(#rt::Body {
                name: ::std::borrow::Cow::Borrowed(#bname), mass: #mass, com: [#px, #py], inertia: #inertia, rotation: #rotation,
            })?;
        }
    };
    model.dynamics.bodies.iter().map(body).collect()
}

/// One `with_force` per declared force, its law a closure of straight-line code.
fn forces(cx: &Ctx, model: &Model) -> Vec<TokenStream> {
    let (g, kin, ni) = (cx.g, &cx.kin, &cx.ni);
    let force = |f: &ForceModel| {
        let (fname, px, py) = (&f.name, coord(cx, &f.at[0]), coord(cx, &f.at[1]));
        let (outside, inside) = law(g, &cx.names, &f.value);
        let [fx, fy] = f.value.map(|v| cx.names.operand(g, v));
        quote! {
            #outside
            let __model = __model.with_force(
                #fname,
                [#px, #py],
                move |__k: #kin, _: &[::core::primitive::f64; #ni]| -> [::core::primitive::f64; 2] {
                    #inside
                    [#fx, #fy]
                },
            )?;
        }
    };
    model.dynamics.forces.iter().map(force).collect()
}

/// One `with_torque` per declared torque, its law a closure of straight-line code.
fn torques(cx: &Ctx, model: &Model) -> Vec<TokenStream> {
    let (g, kin, ni) = (cx.g, &cx.kin, &cx.ni);
    let torque = |t: &TorqueModel| {
        let (tname, on) = (&t.name, angle(t.on));
        let (outside, inside) = law(g, &cx.names, &[t.value]);
        let value = cx.names.operand(g, t.value);
        quote! {
            #outside
            let __model = __model.with_torque(#tname, #on, move |__k: #kin, _: &[::core::primitive::f64; #ni]|
                -> ::core::primitive::f64 {
                #inside
                #value
            })?;
        }
    };
    model.dynamics.torques.iter().map(torque).collect()
}

fn fixed(c: &CoordModel) -> Option<NodeId> {
    match c {
        CoordModel::Fixed(n) => Some(*n),
        _ => None,
    }
}

fn angle(a: AngleModel) -> TokenStream {
    let rt = runtime();
    match a {
        AngleModel::Unknown(u) => {
            let u = lit(u);
            quote!(#rt::Rotation::Unknown(#u))
        }
        AngleModel::Input(i) => {
            let i = lit(i);
            quote!(#rt::Rotation::Input(#i))
        }
        AngleModel::None => quote!(#rt::Rotation::None),
    }
}

/// Straight-line code computing `roots` from the state `__k`: `(outside, inside)`. What
/// depends on the parameters only is computed once, outside the closure (which captures it);
/// inside, the inputs and unknowns are read from the state and the rest is computed.
fn law(g: &Graph, names: &Names, roots: &[NodeId]) -> (TokenStream, TokenStream) {
    let reads = g.leaves_of(roots).into_iter().filter_map(|l| match l {
        Leaf::Input(i) => {
            let (local, i) = (&names.inputs[i as usize], lit(i as usize));
            Some(quote!(let #local: ::core::primitive::f64 = __k.x[#i];))
        }
        Leaf::Unknown(u) => {
            let (local, u) = (&names.unknowns[u as usize], lit(u as usize));
            Some(quote!(let #local: ::core::primitive::f64 = __k.q[#u];))
        }
        _ => None,
    });
    let level = vec![0; g.len()];
    let sched = schedule(g, &level, &[ScopeSpec { kind: ScopeKind::Plain, roots: roots.to_vec() }]);
    let (inside, _): (Vec<NodeId>, Vec<NodeId>) = sched.lets[0].iter().partition(|&&n| depends_on_state(g, n));
    // The parameter-only operands of the state-dependent nodes (and parameter-only roots).
    let hoisted: Vec<NodeId> = inside
        .iter()
        .flat_map(|&n| g.op(n).operands().collect::<Vec<_>>())
        .chain(roots.iter().copied())
        .filter(|&n| !depends_on_state(g, n))
        .collect();
    let inside_lets = names.lets(g, &sched, &inside);
    (lets(g, names, &hoisted), quote!(#(#reads)* #inside_lets))
}

fn depends_on_state(g: &Graph, n: NodeId) -> bool {
    g.leaves_of(&[n]).iter().any(|l| matches!(l, Leaf::Input(_) | Leaf::Unknown(_)))
}

/// `let` statements for the nodes `roots` need, in order, each once.
fn lets(g: &Graph, names: &Names, roots: &[NodeId]) -> TokenStream {
    let level = vec![0; g.len()];
    let sched = schedule(g, &level, &[ScopeSpec { kind: ScopeKind::Plain, roots: roots.to_vec() }]);
    names.lets(g, &sched, &sched.lets[0])
}

/// `mass_model` of a mechanism declared without dynamics items: a method that says, where it is
/// called, what to declare (the runtime's macro).
pub fn absent(t: &Types) -> TokenStream {
    let (rt, name) = (runtime(), &t.name);
    quote!(#rt::no_mass_model!(#name);)
}
