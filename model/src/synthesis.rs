//! Synthesis on a run-time model: the runtime's one implementation (`kinloop_runtime::synthesis`,
//! written over `SensKernel`) with the model's kernel (its `SensKernel`: `crate::sens_kernel`,
//! below this file, as is the kernel threads share). A model declared with
//! `#[kinloop(sensitivities)]` gives [`Model::synthesis_problem`], the compiled
//! `Problem::new`'s counterpart; the search (`Search::run`), the local solve and the
//! verification by branch-safe sweeps are the compiled mechanism's code. Where the model's
//! states equal the compiled mechanism's bit for bit (its kinematics and sensitivities do, on
//! the same operations), so do the candidates (`tests/synthesis.rs`). The problem lends the
//! model, one evaluation after the other; [`Model::shared_synthesis_problem`] gives one that
//! threads can share (each evaluation on a clone of the model: `crate::shared`), for
//! `Search::par_run`, with the same report.

use crate::mechanism::ModelKernel;
use crate::model::Model;
use crate::shared::SharedModelKernel;
use kinloop_runtime::Kernel;
use kinloop_runtime::synthesis::{Design, ProblemOf, SynthesisError, Task};

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

impl Model {
    /// The synthesis problem of varying `design` of this model (its other parameters keep their
    /// values) to do `task`: the compiled `Problem::new` over the model's kernel, with the
    /// model's solver configuration. The model must be declared with
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
        let kernel = self.kernel(self.sweep_config)?;
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
        let kernel = self.shared_kernel(self.sweep_config)?;
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

/// The kernel by the model it lends (so that a [`ModelProblem`] is `Debug`, as a compiled
/// `Problem` is: `unwrap_err` on its result).
impl std::fmt::Debug for ModelKernel<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let d = self.dims();
        f.debug_struct("ModelKernel").field("name", &self.name()).field("sizes", &d).finish_non_exhaustive()
    }
}
