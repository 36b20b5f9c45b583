//! A mechanism's sizes, as literals.

use super::literals::lit;
use crate::plan::Plan;
use proc_macro2::Literal;

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
