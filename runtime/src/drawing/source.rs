//! What a drawing reads from a mechanism, whether compiled or read at run time ([`Drawable`]):
//! the description, the parameter values, the names and kinds of the columns, a reference
//! state and the outputs at a position. The drawings, motions and interactive pages are
//! written once over it.

use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::Compiled;
use crate::solvers::newton::NewtonConfig;

/// The names and quantity kinds of a mechanism's columns, in declaration order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Columns {
    /// The inputs' names.
    pub inputs: Vec<String>,
    /// The inputs' kinds.
    pub input_kinds: Vec<QuantityKind>,
    /// The unknowns' names.
    pub unknowns: Vec<String>,
    /// The unknowns' kinds.
    pub unknown_kinds: Vec<QuantityKind>,
    /// The output columns' names (`p.x`, `p.y` for a point).
    pub outputs: Vec<String>,
    /// The output columns' kinds.
    pub output_kinds: Vec<QuantityKind>,
}

impl Columns {
    /// The columns of compiled mechanism `M` (its constants).
    pub fn of<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>() -> Columns {
        let names = |s: &[&str]| s.iter().map(|s| s.to_string()).collect();
        Columns {
            inputs: names(&M::INPUTS),
            input_kinds: M::INPUT_KINDS.to_vec(),
            unknowns: names(&M::UNKNOWNS),
            unknown_kinds: M::UNKNOWN_KINDS.to_vec(),
            outputs: names(&M::OUTPUTS),
            output_kinds: M::OUTPUT_KINDS.to_vec(),
        }
    }
}

/// A mechanism as its drawings read it: a compiled one through [`Compiled`], a
/// `kinloop_model::Model` read at run time through its own implementation. Both give the
/// description `mechanism!` emits for their declaration (the same text, from the same
/// function of the macro's pipeline), so one drawing code draws either.
pub trait Drawable {
    /// The mechanism's name.
    fn name(&self) -> &str;
    /// The default drawing's description in the text format of [`super::FORMAT`]
    /// ([`Mechanism::DRAWING`]); empty for a mechanism that describes none.
    fn description_text(&self) -> &str;
    /// The parameter values in declaration order (`NaN` for one that has no value).
    fn param_values(&self) -> Vec<f64>;
    /// The names and kinds of the inputs, unknowns and output columns.
    fn columns(&self) -> Columns;
    /// The reference state: the unknowns at the inputs `0` solved from the declared guess with
    /// the default Newton configuration; `None` where that does not solve.
    fn reference(&mut self) -> Option<Vec<f64>>;
    /// The output columns at the position `(x, q)` ([`Mechanism::outputs_flat`]); `None` when a
    /// slice has the wrong length or the outputs cannot be evaluated.
    fn outputs_at(&mut self, x: &[f64], q: &[f64]) -> Option<Vec<f64>>;
}

impl<M, const N: usize, const NI: usize, const NO: usize> Drawable for Compiled<'_, M, N, NI, NO>
where
    M: Mechanism<N, NI, NO>,
{
    fn name(&self) -> &str {
        M::NAME
    }
    fn description_text(&self) -> &str {
        M::DRAWING
    }
    fn param_values(&self) -> Vec<f64> {
        self.0.param_values()
    }
    fn columns(&self) -> Columns {
        Columns::of::<M, N, NI, NO>()
    }
    fn reference(&mut self) -> Option<Vec<f64>> {
        let x = [0.0; NI];
        let (q, _) = self.0.position_flat(&x, &self.0.guess_flat(&x), &NewtonConfig::default()).ok()?;
        Some(q.to_vec())
    }
    fn outputs_at(&mut self, x: &[f64], q: &[f64]) -> Option<Vec<f64>> {
        let (x, q) = (<[f64; NI]>::try_from(x).ok()?, <[f64; N]>::try_from(q).ok()?);
        Some(self.0.outputs_flat(&x, &q).to_vec())
    }
}
