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
//! Generated code reaches the runtime through `::kinloop::__gen` only.

pub mod api;
pub mod closed_form;
pub mod describe;
pub mod drawing;
pub mod dynamics;
pub mod evaluate;
mod group_lets;
pub mod kernel;
pub mod names;
pub mod schedule;
pub mod sensitivities;
pub mod sparse;
pub mod surface;

use crate::plan::Plan;
use crate::semantics::model::Model;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// The path generated code uses to reach the runtime.
pub fn runtime() -> TokenStream {
    quote!(::kinloop::__gen)
}

pub(crate) fn lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

/// The names of the generated types of mechanism `name`.
pub struct Types {
    /// The mechanism's name as declared (the parameter struct).
    pub name: Ident,
    /// The name without `r#`, for messages and derived names.
    pub plain: String,
    /// `NameInputs`.
    pub inputs: Ident,
    /// `NameUnknowns`.
    pub unknowns: Ident,
    /// `NameOutputs`.
    pub outputs: Ident,
    /// `NameState`.
    pub state: Ident,
    /// `NameMotion`.
    pub motion: Ident,
    /// `NameColumns`: the typed column handles of `Name::COL`.
    pub columns: Ident,
    /// `NameParams` (one value per parameter, in the sensitivities).
    pub params: Ident,
    /// `NameSensitivities`.
    pub sens: Ident,
}

impl Types {
    /// The type names of mechanism `name`.
    pub fn of(name: &Ident) -> Types {
        let plain = names::plain(name);
        let t = |suffix: &str| format_ident!("{}{}", plain, suffix);
        Types {
            name: name.clone(),
            inputs: t("Inputs"),
            unknowns: t("Unknowns"),
            outputs: t("Outputs"),
            state: t("State"),
            motion: t("Motion"),
            columns: t("Columns"),
            params: t("Params"),
            sens: t("Sensitivities"),
            plain,
        }
    }
}

/// The sizes of a mechanism as literals: unknowns, inputs, outputs, parameters.
pub struct Dims {
    /// Number of unknowns (and scalar equations).
    pub n: Literal,
    /// Number of inputs.
    pub ni: Literal,
    /// Number of outputs.
    pub no: Literal,
    /// Number of parameters.
    pub np: Literal,
}

impl Dims {
    /// The sizes of `plan`.
    pub fn of(plan: &Plan) -> Dims {
        Dims { n: lit(plan.n), ni: lit(plan.ni), no: lit(plan.outputs.len()), np: lit(plan.np) }
    }
}

/// Lints allowed on the kernels, each because of what the generator writes: locals named after
/// the user's names (`q_X_C`), and the user's literals, which may look like an approximation of
/// a constant (`3.14`).
pub(crate) fn kernel_lints() -> TokenStream {
    quote!(#[allow(non_snake_case, clippy::approx_constant)])
}

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
