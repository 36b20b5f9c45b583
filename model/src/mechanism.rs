//! A run-time model as the runtime's size-agnostic [`Kernel`]: its sweep is the runtime's own
//! ([`SweepOf`]), with events and `table()`, over boxed slices of the sizes read
//! ([`Sizes`]).

use crate::at::Jacobian;
use crate::blocks::StepFailure;
use crate::model::{Model, State, StepError};
use kinloop_runtime::dims::{Dims, JacBuf, KinBuf, Sizes};
use kinloop_runtime::generated::{
    BlockFailure, block_error, first_bad_value, first_non_finite_state, turns_culprit, turns_error,
};
use kinloop_runtime::paths::sweep::SweepOf;
use kinloop_runtime::{BlockInfo, Error, Kernel, Location, NewtonConfig, Quantity, QuantityKind, SweepConfig};
use std::borrow::Cow;
use std::cell::RefCell;

/// A [`Model`] lent to the runtime's algorithms as a [`Kernel`] (see [`Model::kernel`]): the
/// model's names, kinds and structure copied once, its kernels called through the model's own
/// workspace (a step allocates nothing).
pub struct ModelKernel<'a> {
    model: RefCell<&'a mut Model>,
    jac: RefCell<Jacobian>,
    sizes: Sizes,
    name: String,
    inputs: Vec<String>,
    unknowns: Vec<String>,
    outputs: Vec<String>,
    input_kinds: Vec<QuantityKind>,
    unknown_kinds: Vec<QuantityKind>,
    output_kinds: Vec<QuantityKind>,
    judged: Vec<usize>,
    closed_form_angles: Vec<bool>,
    block_rows_cols: Vec<(Vec<usize>, Vec<usize>)>,
    block_infos: Vec<BlockInfo>,
    config: SweepConfig,
}

impl Model {
    /// This model as a [`Kernel`] with the solver configuration `config`, for the runtime's
    /// generic algorithms. Every parameter must have a value (`Error::InvalidArgument` names
    /// the first that has none).
    pub fn kernel(&mut self, config: SweepConfig) -> Result<ModelKernel<'_>, Error> {
        if let Some(k) = self.first_unset() {
            let unset = StepError::UnsetParam(self.params()[k].to_string());
            return Err(Error::InvalidArgument(format!("{unset}, in `{}`", self.name())));
        }
        config.validate()?;
        let sizes = Sizes { n: self.unknowns().len(), ni: self.inputs().len(), no: self.outputs().len() };
        Ok(ModelKernel {
            sizes,
            name: self.name().to_string(),
            inputs: self.inputs().to_vec(),
            unknowns: self.unknowns().to_vec(),
            outputs: self.outputs().to_vec(),
            input_kinds: self.input_kinds().to_vec(),
            unknown_kinds: self.unknown_kinds().to_vec(),
            output_kinds: self.output_kinds().to_vec(),
            judged: (0..sizes.n).filter(|&u| !self.followers[u]).collect(),
            closed_form_angles: self.closed_form_angles.clone(),
            block_rows_cols: self.block_rows_cols.clone(),
            block_infos: self.block_infos.clone(),
            jac: RefCell::new(Jacobian::default()),
            model: RefCell::new(self),
            config,
        })
    }

    /// A lazy, branch-safe sweep of `samples` equally spaced inputs from `from` to `to` (both
    /// included) from `guess` at `from`, with the default solver configuration: the runtime's
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
        self.sweep_with(from, to, samples, guess, SweepConfig::default())
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

impl<'a> ModelKernel<'a> {
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
                            Error::Domain { what: "equation", name, at }
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
                let (what, index) = first_non_finite_state(parts, st.x.len()).unwrap_or(("value", 0));
                let names = if what.starts_with("output") { &self.outputs } else { &self.unknowns };
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

    /// The model lent (the synthesis sets its parameters through it).
    pub(crate) fn model(&self) -> &RefCell<&'a mut Model> {
        &self.model
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
}

impl Kernel for ModelKernel<'_> {
    type Dims = Sizes;
    fn dims(&self) -> Sizes {
        self.sizes
    }
    fn name(&self) -> &str {
        &self.name
    }
    fn input_name(&self, i: usize) -> &str {
        &self.inputs[i]
    }
    fn unknown_name(&self, u: usize) -> &str {
        &self.unknowns[u]
    }
    fn output_name(&self, o: usize) -> &str {
        &self.outputs[o]
    }
    fn input_kind(&self, i: usize) -> QuantityKind {
        self.input_kinds[i]
    }
    fn unknown_kind(&self, u: usize) -> QuantityKind {
        self.unknown_kinds[u]
    }
    fn output_kind(&self, o: usize) -> QuantityKind {
        self.output_kinds[o]
    }
    fn block_count(&self) -> usize {
        self.block_rows_cols.len()
    }
    /// The block's description with the model's own names (the compiled mechanism's
    /// `BLOCKS`, owned).
    fn block_info(&self, b: usize) -> Option<BlockInfo> {
        self.block_infos.get(b).cloned()
    }
    fn block_rows_cols(&self, b: usize) -> Option<(Vec<usize>, Vec<usize>)> {
        self.block_rows_cols.get(b).cloned()
    }
    fn judged(&self) -> &[usize] {
        &self.judged
    }
    fn closed_form_angle(&self, u: usize) -> bool {
        self.closed_form_angles[u]
    }
    fn location(&self, x: &[f64], block: Option<usize>) -> Box<Location> {
        Box::new(Location {
            mechanism: Cow::Owned(self.name.clone()),
            inputs: self.inputs.iter().map(|n| Cow::Owned(n.clone())).zip(x.iter().copied()).collect(),
            block: block.and_then(|b| self.block_info(b).map(|info| (b, info))),
        })
    }
    fn solver_config(&self) -> SweepConfig {
        self.config
    }
    /// The model's declared guess (`Model::guess`); NaN where it cannot be computed, which the
    /// kernel's checks rule out (its parameters are set, `x` is of its size where an algorithm
    /// checked it): a solve from it then fails, as from a compiled guess outside its domain.
    fn guess(&self, x: &kinloop_runtime::dims::Heap) -> kinloop_runtime::dims::Heap {
        let mut out = self.sizes.q();
        if self.model.borrow_mut().guess(&x.0, &mut out.0).is_err() {
            out.0.fill(f64::NAN);
        }
        out
    }
    fn kinematics(
        &self,
        x: &kinloop_runtime::dims::Heap,
        guess: &kinloop_runtime::dims::Heap,
        cfg: &NewtonConfig,
    ) -> Result<KinBuf, Error> {
        let mut m = self.model.borrow_mut();
        let st = m.kinematics(&x.0, &guess.0, cfg).map(drop);
        self.owned(&m, st, &x.0, Some(&guess.0), cfg)
    }
    fn kinematics_at(
        &self,
        x: &kinloop_runtime::dims::Heap,
        q: &kinloop_runtime::dims::Heap,
        cfg: &NewtonConfig,
    ) -> Result<KinBuf, Error> {
        let mut m = self.model.borrow_mut();
        let st = m.kinematics_at(&x.0, &q.0, cfg).map(drop);
        self.owned(&m, st, &x.0, None, cfg)
    }
    fn jacobian(&self, x: &kinloop_runtime::dims::Heap, q: &kinloop_runtime::dims::Heap) -> JacBuf {
        let mut m = self.model.borrow_mut();
        let mut jac = self.jac.borrow_mut();
        let mut out = JacBuf::zeros(self.sizes);
        match m.jacobian(&x.0, &q.0, &mut jac) {
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
    /// The model's step (`Model::kinematics`, libm's sines and cosines: a run-time model has no
    /// trigonometry cache) copied into `into`.
    fn step_into<T: kinloop_runtime::generated::InputTrig>(
        &self,
        x: &kinloop_runtime::dims::Heap,
        guess: &kinloop_runtime::dims::Heap,
        cfg: &NewtonConfig,
        _trig: &mut T,
        into: &mut KinBuf,
    ) -> Result<(), Error> {
        let mut m = self.model.borrow_mut();
        match m.kinematics(&x.0, &guess.0, cfg).map(drop) {
            Ok(()) => {
                Self::copy_state(m.state(), into);
                Ok(())
            }
            Err(e) => Err(self.error(&m, e, &x.0, Some(&guess.0), cfg)),
        }
    }
}
