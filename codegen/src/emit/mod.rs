//! Emission of Rust from a [`Plan`]: only what depends on the declaration.
//!
//! * [`schedule`] places each graph node in the scope of a kernel that first needs it (and
//!   pairs a sine with the cosine of the same argument);
//! * [`names`] names the locals and renders nodes as `let` statements;
//! * [`kernel`] emits the straight-line solver kernels (positions, analogs, outputs), with
//!   [`closed_form`] the straight-line solves of closed-form blocks, and [`evaluate`] the
//!   evaluations at a given position (outputs, guesses, Jacobians);
//! * [`surface`] declares the named types (also emitted by the fallback after an error);
//! * [`api`] implements the runtime traits with the kernels and the constants, and forwards the
//!   inherent methods to the runtime's generic code;
//! * [`sensitivities`] adds the sensitivity types and kernels when they were requested;
//! * [`sparse`] emits the tables, straight-line factorisations and Jacobians of large sparse
//!   Newton blocks;
//! * [`describe`] writes the decomposition in words;
//! * [`drawing`] describes the default drawing: the loops' chains of points, classified;
//! * [`dynamics`] builds the declared bodies and loads into the runtime's mass model.
//!
//! What they all share has a module of its own: the generated types' names ([`type_names`]),
//! the sizes ([`dims`]), index literals ([`literals`]), the lints the kernels allow ([`lints`])
//! and the path to the runtime ([`runtime_path`]). Generated code reaches the runtime through
//! `__gen` of the facade only, by the path the invocation gave (`$crate` through the facade's
//! wrapper, so a renamed dependency works) or `::kinloop`.

pub mod api;
pub mod closed_form;
pub mod describe;
pub mod dims;
pub mod drawing;
pub mod dynamics;
pub mod evaluate;
mod group_lets;
pub mod kernel;
pub mod lints;
pub mod literals;
pub mod names;
pub mod runtime_path;
pub mod schedule;
pub mod sensitivities;
pub mod sparse;
pub mod surface;
pub mod type_names;

use crate::plan::Plan;
use crate::semantics::model::Model;
use proc_macro2::TokenStream;
use runtime_path::runtime;
use type_names::Types;

/// Every item of an accepted declaration.
pub fn generate(model: &Model, plan: &Plan) -> TokenStream {
    let types = Types::of(&model.name);
    let mut out = surface::items(&surface::Surface::of_model(model, plan.defaults.clone()), &types);
    out.extend(api::items(model, plan, &types));
    out.extend(sparse::items(plan, &types.plain, &runtime()));
    out.extend(dynamics::items(model, plan, &types));
    if plan.has_sensitivities() {
        out.extend(sensitivities::items(model, plan, &types));
    } else {
        out.extend(sensitivities::absent(&types));
    }
    // Kernels of thousands of temporaries: `let`s regrouped so rustc's debug information fits.
    group_lets::group_lets(out)
}
