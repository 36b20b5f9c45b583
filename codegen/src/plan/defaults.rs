//! The parameters' default values.

use crate::semantics::model::Model;

/// The parameters' default values when every parameter has one that is a finite constant: the
/// one rule for `Default`, used by the generated items and by the fallback after an error.
pub fn param_defaults(values: impl IntoIterator<Item = Option<f64>>) -> Option<Vec<f64>> {
    values.into_iter().map(|v| v.filter(|v| v.is_finite())).collect()
}

/// The defaults of a resolved model's parameters (see [`param_defaults`]).
pub fn model_defaults(model: &Model) -> Option<Vec<f64>> {
    param_defaults(model.params.iter().map(|p| p.value.and_then(|v| model.graph.as_const(v))))
}
