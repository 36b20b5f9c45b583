//! A run-time model's parameter sensitivities through the runtime's `SensKernel`: the
//! sensitivities of a state that synthesis and the gradient objectives read ([`ModelSens`]), and
//! the kernel's body over them, written once for the kernel that lends the model
//! ([`ModelKernel`], here) and for the one that threads share (`crate::shared`, from a pool of
//! clones).
//!
//! Apart from synthesis (`crate::synthesis`), which poses its problems over both kernels and so
//! sits above them: the body sits below both, as the body of the model's `Kernel` does
//! (`crate::mechanism`), which the two kernels share the same way.

use crate::mechanism::{Info, ModelKernel};
use crate::model::{State, StepError};
use crate::sensitivities::Sensitivities;
use kinloop_runtime::dims::{Dims, Heap, KinBuf};
use kinloop_runtime::{Error, NewtonConfig, Quantity, SensKernel, SensState};
use std::borrow::Cow;

/// The parameter sensitivities of one state of a model that synthesis and the gradient
/// objectives read (the runtime's `SensState`): those of the positions, the outputs and their
/// first analogs, with the numbers of parameters and inputs that index them. The model's
/// [`Sensitivities`] also hold those of the second analogs, which neither synthesis nor the
/// objectives read and which are therefore not copied.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModelSens {
    /// The number of parameters.
    pub np: usize,
    /// The number of inputs (indexing the analogs' sensitivities).
    pub ni: usize,
    /// The positions' sensitivities, `q[u * np + k]` = ∂q_u/∂p_k (as
    /// [`Sensitivities::q`](crate::Sensitivities::q)).
    pub q: Vec<f64>,
    /// The first analogs' sensitivities, `dq[(u * ni + i) * np + k]` (as
    /// [`Sensitivities::dq`](crate::Sensitivities::dq)).
    pub dq: Vec<f64>,
    /// The outputs' sensitivities, `out[o * np + k]` = ∂out_o/∂p_k (as
    /// [`Sensitivities::out`](crate::Sensitivities::out)).
    pub out: Vec<f64>,
    /// The outputs' first analogs' sensitivities, `dout[(o * ni + i) * np + k]` (as
    /// [`Sensitivities::dout`](crate::Sensitivities::dout)).
    pub dout: Vec<f64>,
}

impl SensState for ModelSens {
    fn q(&self, u: usize, k: usize) -> f64 {
        self.q[u * self.np + k]
    }
    fn out(&self, o: usize, k: usize) -> f64 {
        self.out[o * self.np + k]
    }
    fn dq(&self, u: usize, i: usize, k: usize) -> f64 {
        self.dq[(u * self.ni + i) * self.np + k]
    }
    fn dout(&self, o: usize, i: usize, k: usize) -> f64 {
        self.dout[(o * self.ni + i) * self.np + k]
    }
}

/// The body of the [`SensKernel`] of a model, lent alone ([`ModelKernel`]) or from a pool of
/// clones ([`SharedModelKernel`](crate::SharedModelKernel)), but for `param` and `with_params`:
/// the names from `self.info()`, every kernel called on the model `self.lend` gives.
macro_rules! model_sens_body {
    () => {
        type Sens = ModelSens;
        fn param_count(&self) -> usize {
            self.info().params.len()
        }
        fn param_names(&self) -> Vec<String> {
            self.info().params.clone()
        }
        /// Every parameter finite: the compiled `check_params`'s error otherwise.
        fn check_params(&self) -> Result<(), Error> {
            let info = self.info();
            match (0..info.params.len()).map(|k| (k, self.param(k))).find(|(_, v)| !v.is_finite()) {
                Some((k, value)) => Err(Error::NonFinite {
                    what: Quantity::Parameter,
                    name: Cow::Owned(info.params[k].clone()),
                    value,
                    at: info.location(&vec![0.0; info.sizes.ni()], None),
                }),
                None => Ok(()),
            }
        }
        fn sens(&self) -> ModelSens {
            let np = self.param_count();
            let d = self.info().sizes;
            let (n, ni, no) = (d.n(), d.ni(), d.no());
            let z = |len: usize| vec![0.0; len];
            ModelSens { np, ni, q: z(n * np), dq: z(n * ni * np), out: z(no * np), dout: z(no * ni * np) }
        }
        /// The model's `sensitivities` copied into `kin` and `sens` (all but the second
        /// analogs'; no allocation).
        fn sensitivities_into(
            &self,
            x: &Heap,
            guess: &Heap,
            cfg: &NewtonConfig,
            kin: &mut KinBuf,
            sens: &mut ModelSens,
        ) -> Result<(), Error> {
            self.lend(|m, _| match m.sensitivities(&x.0, &guess.0, cfg) {
                Ok((st, s)) => copy_sens(self.info(), st, s, kin, sens),
                Err(e) => Err(self.info().error(m, e, &x.0, Some(&guess.0), cfg)),
            })
        }
        /// The model's `sensitivities_at` copied into `kin` and `sens` (no allocation).
        fn sensitivities_at_into(
            &self,
            x: &Heap,
            q: &Heap,
            cfg: &NewtonConfig,
            kin: &mut KinBuf,
            sens: &mut ModelSens,
        ) -> Result<(), Error> {
            self.lend(|m, _| match m.sensitivities_at(&x.0, &q.0, cfg) {
                Ok((st, s)) => copy_sens(self.info(), st, s, kin, sens),
                Err(e) => Err(self.info().error(m, e, &x.0, None, cfg)),
            })
        }
        /// The position alone (`Model::positions`, the compiled `position_flat`) and the
        /// outputs there (`Model::outputs_at`, the compiled `outputs_flat`).
        fn position_into(
            &self,
            x: &Heap,
            guess: &Heap,
            cfg: &NewtonConfig,
            q: &mut Heap,
            out: &mut [f64],
        ) -> Result<(), Error> {
            self.lend(|m, _| {
                let solved: Result<(), StepError> = m.positions(&x.0, &guess.0, cfg).map(|p| q.0.copy_from_slice(p));
                match solved.and_then(|()| m.outputs_at(&x.0, &q.0, out)) {
                    Ok(()) => Ok(()),
                    Err(e) => Err(self.info().error(m, e, &x.0, Some(&guess.0), cfg)),
                }
            })
        }
    };
}
pub(crate) use model_sens_body;

impl SensKernel for ModelKernel<'_> {
    model_sens_body!();
    /// The parameter's value (NaN where it has none, which lending the model rules out).
    fn param(&self, k: usize) -> f64 {
        self.model().borrow().param_values()[k].unwrap_or(f64::NAN)
    }
    /// `f` called with the model's parameters set to `p`, its own put back after it (so that
    /// calls nest), also where `f` panics. `p` has one value per parameter
    /// (`Error::InvalidArgument` otherwise, the model untouched).
    fn with_params<R>(&self, p: &[f64], f: impl FnOnce(&Self) -> R) -> Result<R, Error> {
        self.check_param_count(p)?;
        let mut values: Vec<Option<f64>> = p.iter().copied().map(Some).collect();
        self.model().borrow_mut().swap_params(&mut values);
        let restore = Restore { kernel: self, old: values };
        Ok(f(restore.kernel))
    }
}

/// A state and its sensitivities copied into a kernel's buffers.
pub(crate) fn copy_sens(
    info: &Info,
    st: &State,
    s: Option<&Sensitivities>,
    kin: &mut KinBuf,
    sens: &mut ModelSens,
) -> Result<(), Error> {
    // `synthesis_problem` refuses a model without sensitivities; a kernel lent otherwise says why.
    let Some(s) = s else {
        return Err(Error::InvalidArgument(format!("`{}` was declared without parameter sensitivities", info.name)));
    };
    Info::copy_state(st, kin);
    sens.q.copy_from_slice(&s.q);
    sens.dq.copy_from_slice(&s.dq);
    sens.out.copy_from_slice(&s.out);
    sens.dout.copy_from_slice(&s.dout);
    Ok(())
}

/// Puts the lent model's parameters back when dropped: after the evaluation, or while `f`
/// unwinds.
struct Restore<'k, 'a> {
    kernel: &'k ModelKernel<'a>,
    old: Vec<Option<f64>>,
}

impl Drop for Restore<'_, '_> {
    fn drop(&mut self) {
        self.kernel.model().borrow_mut().swap_params(&mut self.old);
    }
}
