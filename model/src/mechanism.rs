//! A run-time model as the runtime's size-agnostic [`Kernel`]: its sweep is the runtime's own
//! ([`SweepOf`]), with events and `table()`, over boxed slices of the sizes read
//! ([`Sizes`]).

use crate::at::Jacobian;
use crate::blocks::StepFailure;
use crate::model::{Model, State, StepError};
use kinloop_runtime::dims::{Dims, Heap, JacBuf, KinBuf, Sizes};
use kinloop_runtime::generated::{
    BlockFailure, block_error, first_bad_value, first_non_finite_state, imprecise_param, turns_culprit, turns_error,
};
use kinloop_runtime::paths::sweep::SweepOf;
use kinloop_runtime::{
    BlockInfo, Computed, Error, Kernel, Location, NewtonConfig, Quantity, QuantityKind, SweepConfig,
};
use std::borrow::Cow;
use std::cell::RefCell;

/// A [`Model`] lent to the runtime's algorithms as a [`Kernel`] (see [`Model::kernel`]): the
/// model's names, kinds and structure copied once, its kernels called through the model's own
/// workspace (a step allocates nothing).
pub struct ModelKernel<'a> {
    model: RefCell<&'a mut Model>,
    jac: RefCell<Jacobian>,
    info: Info,
}

/// What a kernel over a model copies from it once: its names, kinds, structure and the solver
/// configuration; and what a kernel does with a model it holds (its errors, its states copied
/// out). Shared by the kernel lending one model ([`ModelKernel`]) and the one lending clones
/// from a pool ([`SharedModelKernel`](crate::SharedModelKernel)).
pub(crate) struct Info {
    pub(crate) sizes: Sizes,
    pub(crate) name: String,
    pub(crate) params: Vec<String>,
    pub(crate) inputs: Vec<String>,
    pub(crate) unknowns: Vec<String>,
    pub(crate) outputs: Vec<String>,
    pub(crate) input_kinds: Vec<QuantityKind>,
    pub(crate) unknown_kinds: Vec<QuantityKind>,
    pub(crate) output_kinds: Vec<QuantityKind>,
    pub(crate) judged: Vec<usize>,
    pub(crate) closed_form_angles: Vec<bool>,
    pub(crate) piecewise: bool,
    pub(crate) block_rows_cols: Vec<(Vec<usize>, Vec<usize>)>,
    pub(crate) block_infos: Vec<BlockInfo>,
    pub(crate) config: SweepConfig,
}

impl Info {
    /// `model`'s names, kinds and structure, with the solver configuration `config`. Every
    /// parameter must have a value (`Error::InvalidArgument` names the first that has none).
    pub(crate) fn of(model: &Model, config: SweepConfig) -> Result<Info, Error> {
        if let Some(k) = model.first_unset() {
            let unset = StepError::UnsetParam(model.params()[k].to_string());
            return Err(Error::InvalidArgument(format!("{unset}, in `{}`", model.name())));
        }
        config.validate()?;
        let bound = config.newton.largest_precise_angle();
        if let Some(k) = model.angle_param_beyond(bound) {
            let value = model.param_values()[k].unwrap_or(f64::NAN);
            return Err(imprecise_param(model.name(), &model.params()[k], value, bound));
        }
        let sizes = Sizes { n: model.unknowns().len(), ni: model.inputs().len(), no: model.outputs().len() };
        Ok(Info {
            sizes,
            name: model.name().to_string(),
            params: model.params().to_vec(),
            inputs: model.inputs().to_vec(),
            unknowns: model.unknowns().to_vec(),
            outputs: model.outputs().to_vec(),
            input_kinds: model.input_kinds().to_vec(),
            unknown_kinds: model.unknown_kinds().to_vec(),
            output_kinds: model.output_kinds().to_vec(),
            judged: (0..sizes.n).filter(|&u| !model.followers[u]).collect(),
            closed_form_angles: model.closed_form_angles.clone(),
            piecewise: model.piecewise,
            block_rows_cols: model.block_rows_cols.clone(),
            block_infos: model.block_infos.clone(),
            config,
        })
    }
}

impl Model {
    /// The solver configuration of the model's sweeps and analyses that take none: `sweep`,
    /// `sampled`, `limits`, `trace_curve`, `reachable`, `sweep_at`, `assembly_modes`, `motion`,
    /// `grid`, the inverse cycle and the simulation, synthesis problems (the `_with` variants and
    /// `kernel` take their own). The defaults until [`Model::set_sweep_config`], as a compiled
    /// mechanism has them until `with_config`.
    pub fn sweep_config(&self) -> SweepConfig {
        self.sweep_config
    }

    /// Sets [`Model::sweep_config`], e.g. a lower `singular_pivot` for a mechanism meant to pass
    /// close to a singular position (a slide brushing its pivot). A configuration with a field
    /// out of range is `Error::InvalidArgument` naming it, and the model keeps its own.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_runtime::SweepConfig;
    /// let text = "pub struct Rocker {
    ///     params h = 1.00000001, r = 1;
    ///     input phi;
    ///     unknowns s = 2, theta = 1.5;
    ///     loop slot: (0, h) + r @ phi == s @ theta;
    /// }";
    /// let mut m = Model::read("rocker.kl", text).unwrap();
    /// m.set_sweep_config(SweepConfig::default().with_singular_pivot(1e-9)).unwrap();
    /// assert_eq!(m.sweep_config().singular_pivot, 1e-9);
    /// assert!(m.set_sweep_config(SweepConfig::default().with_singular_pivot(-1.0)).is_err());
    /// assert_eq!(m.sweep_config().singular_pivot, 1e-9);
    /// ```
    pub fn set_sweep_config(&mut self, config: SweepConfig) -> Result<(), Error> {
        config.validate()?;
        self.sweep_config = config;
        Ok(())
    }

    /// This model as a [`Kernel`] with the solver configuration `config`, for the runtime's
    /// generic algorithms. Every parameter must have a value (`Error::InvalidArgument` names
    /// the first that has none).
    pub fn kernel(&mut self, config: SweepConfig) -> Result<ModelKernel<'_>, Error> {
        let info = Info::of(self, config)?;
        Ok(ModelKernel { model: RefCell::new(self), jac: RefCell::new(Jacobian::default()), info })
    }

    /// Why [`Model::kinematics`] at `x` from `guess` with `cfg` failed with `e`, as a compiled
    /// mechanism says it: the same step again through the model's [`Kernel`], whose error names
    /// the mechanism, the inputs, the failed block's unknowns and equations and what failed
    /// (``the mechanism cannot be assembled in `Cyl` at s = 2.27 (block 0: unknowns th, psi;
    /// equations c.x, c.y): ...``). A [`StepError`] is the evaluator's record of the failure,
    /// by block and row; this is its explanation (the command line's).
    ///
    /// ```
    /// use kinloop_model::Model;
    /// // Not a Grashof crank: it cannot reach phi = 3.
    /// let text = "pub struct FourBar {
    ///     params a = 3, b = 2, c = 2.5, d = 4;
    ///     input phi;
    ///     unknowns beta = 0.5, gamma = 1.5;
    ///     loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    /// }";
    /// let mut m = Model::read("four_bar.kl", text).unwrap();
    /// let e = m.solve(&[3.0]).unwrap_err();
    /// let explained = m.explain(&[3.0], &[0.5, 1.5], &Default::default(), e).to_string();
    /// assert!(explained.contains("cannot be assembled in `FourBar` at phi = 3"), "{explained}");
    /// ```
    pub fn explain(&mut self, x: &[f64], guess: &[f64], cfg: &NewtonConfig, e: StepError) -> Error {
        // Values of the wrong count: the step's own error says so.
        if x.len() != self.inputs().len() || guess.len() != self.unknowns().len() {
            return Error::InvalidArgument(e.to_string());
        }
        // A position given to `kinematics_at` not finite: no step from a guess to run again.
        if let StepError::NonFinitePosition { .. } = e {
            return match Info::of(self, self.sweep_config) {
                Ok(info) => info.error(self, e, x, None, cfg),
                Err(no_info) => no_info,
            };
        }
        // A parameter without a value: no kernel, and its error says so.
        let kernel = match self.kernel(self.sweep_config) {
            Ok(kernel) => kernel,
            Err(no_kernel) => return no_kernel,
        };
        let (x, guess) = (Heap(x.into()), Heap(guess.into()));
        match kernel.kinematics(&x, &guess, cfg) {
            Err(explained) => explained,
            // The same step on the same model fails alike: not reached.
            Ok(_) => Error::InvalidArgument(e.to_string()),
        }
    }

    /// A lazy, branch-safe sweep of `samples` equally spaced inputs from `from` to `to` (both
    /// included) from `guess` at `from`, with the model's solver configuration ([`Model::sweep_config`]): the runtime's
    /// [`Sweep`](kinloop_runtime::Sweep) (events, `next_ref`, `table()`, `run`) over this
    /// model. Its states are [`KinBuf`]s.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// let text = "pub struct FourBar {
    ///     params a = 1, b = 3, c = 2.5, d = 3.2;
    ///     input phi;
    ///     unknowns psi = 0.6, theta = 1.9;
    ///     loop abcd: a @ phi + b @ psi == (d, 0) + c @ theta;
    /// }";
    /// let mut m = Model::read("four_bar.kl", text).unwrap();
    /// let table = m.sweep(&[0.0], &[6.283185307179586], 37, &[0.6, 1.9]).unwrap().table().unwrap();
    /// assert_eq!(table.column("psi").unwrap().len(), 37);
    /// ```
    pub fn sweep(
        &mut self,
        from: &[f64],
        to: &[f64],
        samples: usize,
        guess: &[f64],
    ) -> Result<SweepOf<ModelKernel<'_>, KinBuf>, Error> {
        self.sweep_with(from, to, samples, guess, self.sweep_config)
    }

    /// [`Model::sweep`] with the solver configuration `config`.
    pub fn sweep_with(
        &mut self,
        from: &[f64],
        to: &[f64],
        samples: usize,
        guess: &[f64],
        config: SweepConfig,
    ) -> Result<SweepOf<ModelKernel<'_>, KinBuf>, Error> {
        let k = self.kernel(config)?;
        let v = |s: &[f64]| kinloop_runtime::dims::Heap(s.into());
        SweepOf::over(k, v(from), v(to), samples, v(guess))
    }
}

impl Info {
    /// The error of a failed step of `m` at `x` from `guess` (`None`: at a given position), with
    /// the model's names: what the compiled mechanism's step returns for the same failure
    /// (`generated::block_failure`, `singular` and `non_finite`, the runtime's own), its
    /// location naming the model, its inputs and the failed block's unknowns and equations. As
    /// there, a non-finite parameter, input or guess explains a failure first; an angle guessed
    /// too many turns out is named; a non-finite state names its first bad value.
    pub(crate) fn error(&self, m: &Model, e: StepError, x: &[f64], guess: Option<&[f64]>, cfg: &NewtonConfig) -> Error {
        match e {
            // A failed factorisation: a bad value, an equation outside its domain (a non-finite
            // row), or a singular position (the compiled `singular`).
            StepError::Block { block, failure: StepFailure::Singular { pivot_ratio } } => {
                self.bad_values(m, x, None).unwrap_or_else(|| {
                    let at = self.location(x, Some(block));
                    match m.bad_row(block, guess.is_none()) {
                        Some(row) => {
                            let equations = self.block_infos.get(block).map(|b| b.equations.clone());
                            let name = equations.and_then(|e| e.get(row).cloned()).unwrap_or(Cow::Borrowed("?"));
                            Error::Domain { what: Computed::Equation, name, at }
                        }
                        None => Error::Singular { pivot_ratio, tolerance: cfg.singular_tol, at },
                    }
                })
            }
            StepError::Block { block, failure: StepFailure::Block(f) } => {
                if let Some(e) = self.bad_values(m, x, guess) {
                    return e;
                }
                let at = *self.location(x, Some(block));
                let unknowns = self.block_rows_cols.get(block).map_or(&[][..], |(_, cols)| &cols[..]);
                match guess.and_then(|g| turns_culprit(unknowns.iter().copied(), &self.unknown_kinds, f, g, cfg)) {
                    Some((u, value)) => {
                        let name = u.map_or(Cow::Borrowed("?"), |u| Cow::Owned(self.unknowns[u].clone()));
                        turns_error(name, value, at)
                    }
                    None => block_error(f, at),
                }
            }
            StepError::NonFinite => self.bad_values(m, x, guess).unwrap_or_else(|| {
                let st = m.state();
                let parts = [&st.q[..], &st.dq, &st.d2q, &st.out, &st.dout, &st.d2out];
                let (what, index) = first_non_finite_state(parts, st.x.len()).unwrap_or((Computed::Value, 0));
                let names = if what.is_output() { &self.outputs } else { &self.unknowns };
                let name = names.get(index).map_or(Cow::Borrowed("?"), |n| Cow::Owned(n.clone()));
                Error::Domain { what, name, at: self.location(x, None) }
            }),
            // Arguments the compiled mechanism's types or checks rule out before a step.
            e @ (StepError::UnsetParam(_) | StepError::Size { .. }) => {
                Error::InvalidArgument(format!("{e}, {}", self.location(x, None)))
            }
            StepError::InvalidConfig(field) => {
                block_error(BlockFailure::InvalidConfig { field }, *self.location(x, None))
            }
            StepError::ImpreciseParam { param, value, bound } => imprecise_param(&self.name, &param, value, bound),
            // A parameter or an input not finite, named by `Model::solve`: the compiled error.
            e @ StepError::NotFinite { .. } => {
                self.bad_values(m, x, None).unwrap_or_else(|| Error::InvalidArgument(e.to_string()))
            }
            StepError::NonFinitePosition { unknown, value } => {
                self.bad_values(m, x, None).unwrap_or_else(|| Error::NonFinite {
                    what: Quantity::Position,
                    name: Cow::Owned(unknown),
                    value,
                    at: self.location(x, None),
                })
            }
        }
    }

    /// The first non-finite parameter, input or guess, as the compiled `bad_values` finds it.
    fn bad_values(&self, m: &Model, x: &[f64], guess: Option<&[f64]>) -> Option<Error> {
        let params = m.param_values().iter().map(|v| v.unwrap_or(f64::NAN));
        let (what, index, value) = first_bad_value(params, x, guess)?;
        let names = match what {
            Quantity::Parameter => m.params(),
            Quantity::Input => &self.inputs[..],
            _ => &self.unknowns[..],
        };
        let name = names.get(index).map_or(Cow::Borrowed("?"), |n| Cow::Owned(n.clone()));
        Some(Error::NonFinite { what, name, value, at: self.location(x, None) })
    }

    /// Where a step at `x` failed (in `block`): the model's name, its inputs and the block.
    pub(crate) fn location(&self, x: &[f64], block: Option<usize>) -> Box<Location> {
        Box::new(Location {
            mechanism: Cow::Owned(self.name.clone()),
            inputs: self.inputs.iter().map(|n| Cow::Owned(n.clone())).zip(x.iter().copied()).collect(),
            block: block.and_then(|b| self.block_infos.get(b).cloned().map(|info| (b, info))),
        })
    }

    /// The model's state into `into`.
    pub(crate) fn copy_state(st: &State, into: &mut KinBuf) {
        into.x.copy_from_slice(&st.x);
        into.q.copy_from_slice(&st.q);
        into.dq.copy_from_slice(&st.dq);
        into.d2q.copy_from_slice(&st.d2q);
        into.out.copy_from_slice(&st.out);
        into.dout.copy_from_slice(&st.dout);
        into.d2out.copy_from_slice(&st.d2out);
        into.report = st.report;
        into.health = st.health;
    }

    /// The state of a step of `m` (`Ok`: its state is `m`'s) as an owned buffer, or its error.
    fn owned(
        &self,
        m: &Model,
        st: Result<(), StepError>,
        x: &[f64],
        guess: Option<&[f64]>,
        cfg: &NewtonConfig,
    ) -> Result<KinBuf, Error> {
        let mut k = self.sizes.kin();
        match st {
            Ok(()) => {
                Self::copy_state(m.state(), &mut k);
                Ok(k)
            }
            Err(e) => Err(self.error(m, e, x, guess, cfg)),
        }
    }

    /// `m`'s declared guess (`Model::guess`); NaN where it cannot be computed.
    pub(crate) fn guess(&self, m: &mut Model, x: &Heap) -> Heap {
        let mut out = self.sizes.q();
        if m.guess(&x.0, &mut out.0).is_err() {
            out.0.fill(f64::NAN);
        }
        out
    }

    /// `m`'s kinematics at `x` from `guess`, owned.
    pub(crate) fn kinematics(
        &self,
        m: &mut Model,
        x: &Heap,
        guess: &Heap,
        cfg: &NewtonConfig,
    ) -> Result<KinBuf, Error> {
        let st = m.kinematics(&x.0, &guess.0, cfg).map(drop);
        self.owned(m, st, &x.0, Some(&guess.0), cfg)
    }

    /// `m`'s positions at `x` from `guess` (`Model::positions`), owned.
    pub(crate) fn positions(&self, m: &mut Model, x: &Heap, guess: &Heap, cfg: &NewtonConfig) -> Result<Heap, Error> {
        let mut out = self.sizes.q();
        match m.positions(&x.0, &guess.0, cfg) {
            Ok(q) => {
                out.0.copy_from_slice(q);
                Ok(out)
            }
            Err(e) => Err(self.error(m, e, &x.0, Some(&guess.0), cfg)),
        }
    }

    /// `m`'s kinematics at a given position `q`, owned.
    pub(crate) fn kinematics_at(&self, m: &mut Model, x: &Heap, q: &Heap, cfg: &NewtonConfig) -> Result<KinBuf, Error> {
        let st = m.kinematics_at(&x.0, &q.0, cfg).map(drop);
        self.owned(m, st, &x.0, None, cfg)
    }

    /// `m`'s residuals, Jacobians and magnitudes at `(x, q)`, through the scratch `jac`.
    pub(crate) fn jacobian(&self, m: &mut Model, jac: &mut Jacobian, x: &Heap, q: &Heap) -> JacBuf {
        let mut out = JacBuf::zeros(self.sizes);
        match m.jacobian(&x.0, &q.0, jac) {
            Ok(()) => {
                out.f.copy_from_slice(&jac.f);
                out.j.copy_from_slice(&jac.j);
                out.fx.copy_from_slice(&jac.fx);
                out.scale.copy_from_slice(&jac.scale);
                out.unit.copy_from_slice(&jac.unit);
                out.input_unit.copy_from_slice(&jac.input_unit);
            }
            // Sizes and parameters were checked when the kernel was made: not reached. NaN
            // where it were, as a compiled kernel's values outside their domain.
            Err(_) => out.f.fill(f64::NAN),
        }
        out
    }

    /// `m`'s step at `x` from `guess` copied into `into` (no allocation).
    pub(crate) fn step_into(
        &self,
        m: &mut Model,
        x: &Heap,
        guess: &Heap,
        cfg: &NewtonConfig,
        into: &mut KinBuf,
    ) -> Result<(), Error> {
        match m.kinematics(&x.0, &guess.0, cfg).map(drop) {
            Ok(()) => {
                Self::copy_state(m.state(), into);
                Ok(())
            }
            Err(e) => Err(self.error(m, e, &x.0, Some(&guess.0), cfg)),
        }
    }
}

impl<'a> ModelKernel<'a> {
    /// The model lent (the synthesis sets its parameters through it).
    pub(crate) fn model(&self) -> &RefCell<&'a mut Model> {
        &self.model
    }

    /// What the kernel copied from the model.
    pub(crate) fn info(&self) -> &Info {
        &self.info
    }

    /// `f` called with the model lent and the kernel's scratch Jacobian.
    pub(crate) fn lend<R>(&self, f: impl FnOnce(&mut Model, &mut Jacobian) -> R) -> R {
        f(&mut self.model.borrow_mut(), &mut self.jac.borrow_mut())
    }
}

/// The body of the [`Kernel`] of a model, lent alone ([`ModelKernel`]) or from a pool of clones
/// ([`SharedModelKernel`](crate::SharedModelKernel)): the names, kinds and structure from
/// `self.info()`, every kernel called on the model `self.lend` gives.
macro_rules! model_kernel_body {
    () => {
        type Dims = kinloop_runtime::dims::Sizes;
        fn dims(&self) -> kinloop_runtime::dims::Sizes {
            self.info().sizes
        }
        fn name(&self) -> &str {
            &self.info().name
        }
        fn input_name(&self, i: usize) -> &str {
            &self.info().inputs[i]
        }
        fn unknown_name(&self, u: usize) -> &str {
            &self.info().unknowns[u]
        }
        fn output_name(&self, o: usize) -> &str {
            &self.info().outputs[o]
        }
        fn input_kind(&self, i: usize) -> kinloop_runtime::QuantityKind {
            self.info().input_kinds[i]
        }
        fn unknown_kind(&self, u: usize) -> kinloop_runtime::QuantityKind {
            self.info().unknown_kinds[u]
        }
        fn output_kind(&self, o: usize) -> kinloop_runtime::QuantityKind {
            self.info().output_kinds[o]
        }
        fn block_count(&self) -> usize {
            self.info().block_rows_cols.len()
        }
        /// The block's description with the model's own names (the compiled mechanism's
        /// `BLOCKS`, owned).
        fn block_info(&self, b: usize) -> Option<kinloop_runtime::BlockInfo> {
            self.info().block_infos.get(b).cloned()
        }
        fn block_rows_cols(&self, b: usize) -> Option<(Vec<usize>, Vec<usize>)> {
            self.info().block_rows_cols.get(b).cloned()
        }
        fn judged(&self) -> &[usize] {
            &self.info().judged
        }
        fn closed_form_angle(&self, u: usize) -> bool {
            self.info().closed_form_angles[u]
        }
        fn piecewise(&self) -> bool {
            self.info().piecewise
        }
        fn location(&self, x: &[f64], block: Option<usize>) -> Box<kinloop_runtime::Location> {
            self.info().location(x, block)
        }
        /// No angle parameter beyond the bound of `cfg`: the compiled `check_param_angles`'s
        /// error otherwise.
        fn check_param_angles(&self, cfg: &kinloop_runtime::NewtonConfig) -> Result<(), kinloop_runtime::Error> {
            let bound = cfg.largest_precise_angle();
            self.lend(|m, _| match m.angle_param_beyond(bound) {
                None => Ok(()),
                Some(k) => {
                    let value = m.param_values()[k].unwrap_or(f64::NAN);
                    Err(kinloop_runtime::generated::imprecise_param(&self.info().name, &m.params()[k], value, bound))
                }
            })
        }
        fn solver_config(&self) -> kinloop_runtime::SweepConfig {
            self.info().config
        }
        /// The model's declared guess (`Model::guess`); NaN where it cannot be computed, which
        /// the kernel's checks rule out (its parameters are set, `x` is of its size where an
        /// algorithm checked it): a solve from it then fails, as from a compiled guess outside
        /// its domain.
        fn guess(&self, x: &kinloop_runtime::dims::Heap) -> kinloop_runtime::dims::Heap {
            self.lend(|m, _| self.info().guess(m, x))
        }
        fn kinematics(
            &self,
            x: &kinloop_runtime::dims::Heap,
            guess: &kinloop_runtime::dims::Heap,
            cfg: &kinloop_runtime::NewtonConfig,
        ) -> Result<kinloop_runtime::dims::KinBuf, kinloop_runtime::Error> {
            self.lend(|m, _| self.info().kinematics(m, x, guess, cfg))
        }
        fn positions(
            &self,
            x: &kinloop_runtime::dims::Heap,
            guess: &kinloop_runtime::dims::Heap,
            cfg: &kinloop_runtime::NewtonConfig,
        ) -> Result<kinloop_runtime::dims::Heap, kinloop_runtime::Error> {
            self.lend(|m, _| self.info().positions(m, x, guess, cfg))
        }
        fn kinematics_at(
            &self,
            x: &kinloop_runtime::dims::Heap,
            q: &kinloop_runtime::dims::Heap,
            cfg: &kinloop_runtime::NewtonConfig,
        ) -> Result<kinloop_runtime::dims::KinBuf, kinloop_runtime::Error> {
            self.lend(|m, _| self.info().kinematics_at(m, x, q, cfg))
        }
        fn jacobian(
            &self,
            x: &kinloop_runtime::dims::Heap,
            q: &kinloop_runtime::dims::Heap,
        ) -> kinloop_runtime::dims::JacBuf {
            self.lend(|m, jac| self.info().jacobian(m, jac, x, q))
        }
        /// The model's step (`Model::kinematics`, libm's sines and cosines of the inputs: a
        /// run-time model has no sweep's trigonometry cache) copied into `into`.
        fn step_into<T: kinloop_runtime::generated::InputTrig>(
            &self,
            x: &kinloop_runtime::dims::Heap,
            guess: &kinloop_runtime::dims::Heap,
            cfg: &kinloop_runtime::NewtonConfig,
            _trig: &mut T,
            into: &mut kinloop_runtime::dims::KinBuf,
        ) -> Result<(), kinloop_runtime::Error> {
            self.lend(|m, _| self.info().step_into(m, x, guess, cfg, into))
        }
    };
}
pub(crate) use model_kernel_body;

impl Kernel for ModelKernel<'_> {
    model_kernel_body!();
}
