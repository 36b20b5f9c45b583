//! Synthesis on a run-time model: the runtime's one implementation (`kinloop_runtime::synthesis`,
//! written over `SensKernel`) with the model's kernel. A model declared with
//! `#[kinloop(sensitivities)]` gives [`Model::synthesis_problem`], the compiled
//! `Problem::new`'s counterpart; the search (`Search::run`), the local solve and the
//! verification by branch-safe sweeps are the compiled mechanism's code. Where the model's
//! states equal the compiled mechanism's bit for bit (its kinematics and sensitivities do, on
//! the same operations), so do the candidates (`tests/synthesis.rs`). The problem lends the
//! model, one evaluation after the other; [`Model::shared_synthesis_problem`] gives one that
//! threads can share (each evaluation on a clone of the model: `crate::shared`), for
//! `Search::par_run`, with the same report.

use crate::mechanism::{Info, ModelKernel};
use crate::model::{Model, State, StepError};
use crate::sensitivities::Sensitivities;
use crate::shared::SharedModelKernel;
use kinloop_runtime::dims::{Dims, Heap, KinBuf};
use kinloop_runtime::synthesis::{Design, ProblemOf, SynthesisError, Task};
use kinloop_runtime::{Error, Kernel, NewtonConfig, Quantity, SensKernel, SensState, SweepConfig};
use std::borrow::Cow;

/// A synthesis problem over a run-time model ([`Model::synthesis_problem`]): the runtime's
/// `ProblemOf` over the model's kernel, solved by `kinloop_runtime::synthesis::Search` as a
/// compiled mechanism's `Problem` is, one evaluation after the other (it lends the one model:
/// `Search::run`). A problem threads can share, for `Search::par_run`, is a
/// [`SharedModelProblem`].
pub type ModelProblem<'a> = ProblemOf<ModelKernel<'a>>;

/// A synthesis problem over a run-time model that threads can share
/// ([`Model::shared_synthesis_problem`]): the runtime's `ProblemOf` over a
/// [`SharedModelKernel`], each evaluation on its own clone of the model, so that
/// `Search::par_run` (cargo feature `rayon` of `kinloop-runtime`) runs it on all cores, with
/// the report of `Search::run`, bit for bit.
pub type SharedModelProblem = ProblemOf<SharedModelKernel>;

/// The parameter sensitivities of one state of a model that synthesis and the gradient
/// objectives read (the runtime's `SensState`): those of the positions, the outputs and their
/// first analogs, with the numbers of parameters and inputs that index them. The model's
/// [`Sensitivities`] also hold those of the second analogs, which nothing
/// here reads and which are therefore not copied.
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

impl Model {
    /// The synthesis problem of varying `design` of this model (its other parameters keep their
    /// values) to do `task`: the compiled `Problem::new` over the model's kernel, with the
    /// default solver configuration. The model must be declared with
    /// `#[kinloop(sensitivities)]` (`SynthesisError::Unsupported` otherwise) and have a value
    /// for every parameter; the names, bounds and targets are checked as for a compiled
    /// mechanism. The problem lends the model: a search sets its parameters for each
    /// evaluation and puts them back after it, one evaluation after the other
    /// ([`Model::shared_synthesis_problem`] for a search on all cores).
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_runtime::synthesis::{Design, Search, Task};
    /// let text = "#[kinloop(sensitivities)]
    /// pub struct SliderCrank {
    ///     params r = 1, l = 3;
    ///     input phi;
    ///     unknowns beta = 0, s = 4;
    ///     loop rod: r @ phi + l @ beta == (s, 0);
    /// }";
    /// let mut m = Model::read("slider_crank.kl", text).unwrap();
    /// // The slider's positions of a crank of 1.5 and a rod of 4, at three crank angles.
    /// let s = |phi: f64| 1.5 * phi.cos() + (16.0 - (1.5 * phi.sin()).powi(2)).sqrt();
    /// let task = Task::function("s", [(0.2, s(0.2)), (0.9, s(0.9)), (1.6, s(1.6))]);
    /// let design = Design::new().var("r", 0.5, 2.0).var("l", 3.0, 5.0);
    /// let problem = m.synthesis_problem(&design, &task).unwrap();
    /// let report = Search::default().with_starts(0..8).run(&problem).unwrap();
    /// let best = report.best().unwrap();
    /// assert!((best.values[0] - 1.5).abs() < 1e-9 && (best.values[1] - 4.0).abs() < 1e-9);
    /// ```
    pub fn synthesis_problem(&mut self, design: &Design, task: &Task) -> Result<ModelProblem<'_>, SynthesisError> {
        self.check_synthesis()?;
        let kernel = self.kernel(SweepConfig::default())?;
        ProblemOf::over(kernel, design, task)
    }

    /// [`Model::synthesis_problem`] that threads can share ([`SharedModelProblem`]), for
    /// `Search::par_run`: the problem owns a clone of this model (the model is not lent, nor
    /// changed), and each evaluation runs on a clone of that checked out of a pool with the
    /// parameters of its point ([`SharedModelKernel`]). The same checks and errors; the same
    /// report, from `Search::run` or `Search::par_run`, as [`Model::synthesis_problem`]'s.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_runtime::synthesis::{Design, Search, Task};
    /// let text = "#[kinloop(sensitivities)]
    /// pub struct SliderCrank {
    ///     params r = 1, l = 3;
    ///     input phi;
    ///     unknowns beta = 0, s = 4;
    ///     loop rod: r @ phi + l @ beta == (s, 0);
    /// }";
    /// let mut m = Model::read("slider_crank.kl", text).unwrap();
    /// let s = |phi: f64| 1.5 * phi.cos() + (16.0 - (1.5 * phi.sin()).powi(2)).sqrt();
    /// let task = Task::function("s", [(0.2, s(0.2)), (0.9, s(0.9)), (1.6, s(1.6))]);
    /// let design = Design::new().var("r", 0.5, 2.0).var("l", 3.0, 5.0);
    /// let search = Search::default().with_starts(0..8);
    /// let shared = m.shared_synthesis_problem(&design, &task).unwrap();
    /// let report = search.par_run(&shared).unwrap();
    /// assert_eq!(report, search.run(&m.synthesis_problem(&design, &task).unwrap()).unwrap());
    /// let best = report.best().unwrap();
    /// assert!((best.values[0] - 1.5).abs() < 1e-9 && (best.values[1] - 4.0).abs() < 1e-9);
    /// ```
    pub fn shared_synthesis_problem(&self, design: &Design, task: &Task) -> Result<SharedModelProblem, SynthesisError> {
        self.check_synthesis()?;
        let kernel = self.shared_kernel(SweepConfig::default())?;
        ProblemOf::over(kernel, design, task)
    }

    /// `SynthesisError::Unsupported` where the model was declared without sensitivities.
    fn check_synthesis(&self) -> Result<(), SynthesisError> {
        match self.has_sensitivities() {
            true => Ok(()),
            false => Err(SynthesisError::Unsupported(format!(
                "`{}` was declared without parameter sensitivities: add `#[kinloop(sensitivities)]` before \
                 `pub struct`",
                self.name()
            ))),
        }
    }
}

/// The body of the [`SensKernel`] of a model, lent alone ([`ModelKernel`]) or from a pool of
/// clones ([`SharedModelKernel`]), but for `param` and `with_params`:
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

/// The kernel by the model it lends (so that a [`ModelProblem`] is `Debug`, as a compiled
/// `Problem` is: `unwrap_err` on its result).
impl std::fmt::Debug for ModelKernel<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let d = self.dims();
        f.debug_struct("ModelKernel").field("name", &self.name()).field("sizes", &d).finish_non_exhaustive()
    }
}
