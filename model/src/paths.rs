//! The runtime's path algorithms on a run-time model: each is the runtime's one implementation
//! over its [`Kernel`] (here [`ModelKernel`](crate::ModelKernel), from
//! [`Model::kernel`]), the compiled mechanisms' through `Compiled`: curve tracing
//! (`trace_curve_of`), the reachable range (`reachable_of`), where it assembles near an input
//! (`assembly_near_of`), the states at given inputs
//! (`sweep_at_of`), the assembly modes (`assembly_modes_of`) and scans over parameter sets
//! (`fold_sweep_of`, one set's sweep).
//!
//! Each entry point lends the model with its solver configuration (`Model::sweep_config`); the generic
//! functions take a kernel of any configuration (`m.kernel(config)`).

use crate::count::Count;
use crate::model::Model;
use kinloop_runtime::dims::{Heap, KinBuf};
use kinloop_runtime::paths::assembles::{Assembly, PathEntry, assembly_along_of, assembly_near_of};
use kinloop_runtime::paths::modes::assembly_modes_of;
use kinloop_runtime::paths::reach::reachable_of;
use kinloop_runtime::paths::scan::fold_sweep_of;
use kinloop_runtime::paths::sweep_at::sweep_at_of;
use kinloop_runtime::paths::trace::{TracedOf, max_trace_points, trace_curve_of};
use kinloop_runtime::{Error, Kernel, Reach, SweepConfig, SweepResult, TraceConfig};

/// A vector of the model's sizes from a slice (checked by the algorithm it is given to).
fn heap(v: &[f64]) -> Heap {
    Heap(v.into())
}

/// A run-time model's traced solution curve: positions and inputs in boxed slices.
pub type ModelTraced = TracedOf<Heap, Heap>;

impl Model {
    /// The whole solution curve through `guess` at `from`, first towards `to`, through limit
    /// positions: the runtime's `trace_curve` over this model (see
    /// [`trace_curve_of`]), with the model's solver configuration ([`Model::sweep_config`]; or
    /// [`TraceConfig::newton`]).
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_runtime::TraceConfig;
    /// // A triple rocker (no link turns fully): the input rocks between two limit positions.
    /// let text = "pub struct FourBar {
    ///     params a = 2, b = 3, c = 2.5, d = 4;
    ///     input phi;
    ///     unknowns psi = 0.6, theta = 1.9;
    ///     loop abcd: a @ phi + b @ psi == (d, 0) + c @ theta;
    /// }";
    /// let mut m = Model::read("rocker.kl", text).unwrap();
    /// let traced = m.trace_curve(&[0.0], &[3.0], &[0.6, 1.9], &TraceConfig::default()).unwrap();
    /// assert!(traced.closed && traced.folds.len() == 2);
    /// ```
    pub fn trace_curve(
        &mut self,
        from: &[f64],
        to: &[f64],
        guess: &[f64],
        opts: &TraceConfig,
    ) -> Result<ModelTraced, Error> {
        let k = self.kernel(self.sweep_config)?;
        trace_curve_of(&k, heap(from), heap(to), heap(guess), opts)
    }

    /// The most points a trace of this model keeps within the memory budget
    /// ([`max_trace_points`]): the largest [`TraceConfig::max_points`]
    /// [`Model::trace_curve`] accepts for it.
    pub fn max_trace_points(&mut self) -> Result<usize, Error> {
        Ok(max_trace_points(&self.kernel(self.sweep_config)?))
    }

    /// How far the input can move from `at` towards `at + delta` and `at - delta` on the
    /// assembly mode of `guess` before a limit position, in input values, sweeping both ways
    /// with `samples` samples each: the runtime's `reachable` over this model (see
    /// [`reachable_of`]), with the model's solver configuration ([`Model::sweep_config`]).
    pub fn reachable(
        &mut self,
        at: &[f64],
        delta: &[f64],
        guess: &[f64],
        samples: usize,
    ) -> Result<Reach<Heap>, Error> {
        let k = self.kernel(self.sweep_config)?;
        reachable_of(&k, heap(at), heap(delta), heap(guess), samples)
    }

    /// Where a model of one angle input assembles nearest the input `at` (where a point solve
    /// failed with `Error::NoAssembly`, say): point solves from the declared guess at `at` and
    /// at `samples` angles of the turn about it, nearest first (of two as near, the greater),
    /// and from the first that solves the stretch reachable on its assembly mode, a turn each
    /// way: the runtime's
    /// `assembly_near` over this model (see [`assembly_near_of`]), with the model's solver
    /// configuration ([`Model::sweep_config`]). `None` where no sample solves; `Error::NoConvergence`
    /// where a sample tried before the first that solves, or before none, ran out of iterations
    /// (the search cannot tell whether it assembles).
    ///
    /// ```
    /// use kinloop_model::Model;
    /// // Coupler and rocker (2.5 + 1.5) fall short of frame and crank (3.2 + 1) in line.
    /// let text = "pub struct FourBar {
    ///     params a = 1, b = 2.5, c = 1.5, d = 3.2;
    ///     input phi;
    ///     unknowns beta = 0.5, gamma = 1.5;
    ///     loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    /// }";
    /// let mut m = Model::read("four_bar.kl", text).unwrap();
    /// assert!(m.solve(&[3.14]).is_err());
    /// let near = m.assembly_near(&[3.14], 360).unwrap().expect("it assembles somewhere");
    /// // Coupler and rocker stretched out, by the law of cosines: |A + a e(phi) - D| = b + c.
    /// let limit = ((1.0 + 3.2f64.powi(2) - 4.0f64.powi(2)) / (2.0 * 3.2)).acos();
    /// assert!((near.reach.to[0] - limit).abs() < 1e-9 && (near.reach.from[0] + limit).abs() < 1e-9);
    /// assert!(!near.turns_fully());
    /// ```
    pub fn assembly_near(&mut self, at: &[f64], samples: usize) -> Result<Option<Assembly<Heap>>, Error> {
        let k = self.kernel(self.sweep_config)?;
        assembly_near_of(&k, heap(at), samples)
    }

    /// Where the model first assembles along the straight path from `from` to `to`, any number
    /// of inputs: point solves from the declared guess at `from` and at `samples` equally spaced
    /// inputs up to `to`, the entry located between the last that fails and the first that
    /// solves; the runtime's `assembly_along` over this model (see [`assembly_along_of`]), with
    /// the model's solver configuration ([`Model::sweep_config`]). `None` where no sample solves;
    /// `Error::NoConvergence` where a sample before the first that solves, or before none, ran
    /// out of iterations (the search cannot tell whether the path enters there).
    pub fn assembly_along(
        &mut self,
        from: &[f64],
        to: &[f64],
        samples: usize,
    ) -> Result<Option<PathEntry<Heap>>, Error> {
        let k = self.kernel(self.sweep_config)?;
        assembly_along_of(&k, heap(from), heap(to), samples)
    }

    /// The states at the given inputs, in their order, followed along the path through them
    /// without jumping branches (each stretch between consecutive inputs a sweep of its own):
    /// the runtime's `sweep_at` over this model (see
    /// [`sweep_at_of`]), with the model's solver configuration ([`Model::sweep_config`]). The
    /// result keeps the states before a stop, says why and where it stopped
    /// and lists the events met; the error here is that of lending the model (a parameter
    /// without a value).
    pub fn sweep_at<I: AsRef<[f64]>>(
        &mut self,
        inputs: impl IntoIterator<Item = I>,
        guess: &[f64],
    ) -> Result<SweepResult<KinBuf>, Error> {
        let k = self.kernel(self.sweep_config)?;
        Ok(sweep_at_of(&k, inputs.into_iter().map(|x| heap(x.as_ref())), heap(guess)))
    }

    /// The distinct assembly modes at input `x` (multi-start Newton from the declared guess and
    /// 64 starts around it), sorted by their determinant signs: the runtime's `assembly_modes`
    /// over this model (see
    /// [`assembly_modes_of`]), with the
    /// model's solver configuration. `Error::InvalidArgument` for an `x` of another size than
    /// the model's inputs, `Error::NonFinite` for an input or a parameter not finite,
    /// `Error::Singular` at a limit position (where the modes meet), `Error::NoConvergence` where
    /// no start solves and some ran out of iterations (the search cannot tell).
    pub fn assembly_modes(&mut self, x: &[f64]) -> Result<Vec<KinBuf>, Error> {
        if x.len() != self.inputs().len() {
            return Err(Error::InvalidArgument(format!(
                "assembly_modes of `{}` needs {}, not {}",
                self.name(),
                Count(self.inputs().len(), "input"),
                x.len()
            )));
        }
        let k = self.kernel(self.sweep_config)?;
        let cfg = k.solver_config().newton;
        assembly_modes_of(&k, &heap(x), 64, &cfg)
    }

    /// A design-space scan over parameter sets: for each set of `sets` (values of the
    /// parameters named `params`, in that order; the others keep theirs), the model's sweep as
    /// `spec` says, its states folded into one value: `acc = init(set)`, then
    /// `acc = fold(acc, set, &state)` for every state in order. The runtime's scan over this
    /// model, one set after the other (see
    /// [`fold_sweep_of`]): the compiled
    /// mechanisms' `scan` over the same parameter values gives the same results.
    ///
    /// One slot per set, in order: the final accumulator, or the error that ended that set's
    /// sweep (it cannot be assembled at `from`, meets a limit position, a parameter is not
    /// finite, the set has another number of values than `params`); a failing set never stops
    /// the others. A name that is not a parameter gives every set the same error. The model
    /// keeps the last set's values.
    ///
    /// ```
    /// use kinloop_model::{Model, ParamScanConfig};
    /// use kinloop_runtime::dims::KinBuf;
    /// let text = "pub struct SliderCrank {
    ///     params r = 1, l = 3;
    ///     input phi;
    ///     unknowns beta = 0, s = 4;
    ///     loop rod: r @ phi + l @ beta == (s, 0);
    /// }";
    /// let mut m = Model::read("slider_crank.kl", text).unwrap();
    /// let spec = ParamScanConfig::new(&[0.0], &[std::f64::consts::TAU], 73);
    /// // The stroke of each crank radius: twice the radius.
    /// let init = |_: &[f64]| (f64::MAX, f64::MIN);
    /// let fold = |(lo, hi): (f64, f64), _: &[f64], k: &KinBuf| (lo.min(k.q[1]), hi.max(k.q[1]));
    /// let strokes = m.scan(&["r"], &[[0.5], [1.0]], &spec, init, fold);
    /// let (lo, hi) = strokes[1].clone().unwrap();
    /// assert!((hi - lo - 2.0).abs() < 1e-9);
    /// ```
    pub fn scan<P: AsRef<[f64]>, A>(
        &mut self,
        params: &[&str],
        sets: &[P],
        spec: &ParamScanConfig,
        init: impl Fn(&[f64]) -> A,
        fold: impl Fn(A, &[f64], &KinBuf) -> A,
    ) -> Vec<Result<A, Error>> {
        if let Some(e) = self.unknown_param(params) {
            return sets.iter().map(|_| Err(e.clone())).collect();
        }
        sets.iter().map(|set| self.scan_one(params, set.as_ref(), spec, &init, &fold)).collect()
    }

    /// [`Model::scan`] on all cores (cargo feature `rayon`): the sets are distributed over
    /// rayon's global thread pool by the runtime's distribution (the compiled `par_scan`'s), each
    /// rayon job scanning its sets on its own clone of this model, made once per job (at most
    /// about sixteen per thread), not per set. This model is left as it is.
    ///
    /// The results are bitwise those of [`Model::scan`] and in the same order: a set's result
    /// is computed from its values alone (every parameter scanned is set, the other parameters
    /// are this model's, and a step depends on nothing a previous one left in the workspace).
    /// Run it inside `rayon::ThreadPool::install` to choose the number of threads.
    ///
    /// ```
    /// use kinloop_model::{Model, ParamScanConfig};
    /// use kinloop_runtime::dims::KinBuf;
    /// let text = "pub struct SliderCrank {
    ///     params r = 1, l = 3;
    ///     input phi;
    ///     unknowns beta = 0, s = 4;
    ///     loop rod: r @ phi + l @ beta == (s, 0);
    /// }";
    /// let mut m = Model::read("slider_crank.kl", text).unwrap();
    /// let spec = ParamScanConfig::new(&[0.0], &[std::f64::consts::TAU], 73);
    /// let sets: Vec<[f64; 1]> = (1..=40).map(|k| [0.05 * k as f64]).collect();
    /// let init = |_: &[f64]| (f64::MAX, f64::MIN);
    /// let fold = |(lo, hi): (f64, f64), _: &[f64], k: &KinBuf| (lo.min(k.q[1]), hi.max(k.q[1]));
    /// let par = m.par_scan(&["r"], &sets, &spec, init, fold);
    /// assert_eq!(par, m.scan(&["r"], &sets, &spec, init, fold));
    /// ```
    #[cfg(feature = "rayon")]
    pub fn par_scan<P: AsRef<[f64]> + Sync, A: Send>(
        &self,
        params: &[&str],
        sets: &[P],
        spec: &ParamScanConfig,
        init: impl Fn(&[f64]) -> A + Sync + Send,
        fold: impl Fn(A, &[f64], &KinBuf) -> A + Sync + Send,
    ) -> Vec<Result<A, Error>> {
        if let Some(e) = self.unknown_param(params) {
            return sets.iter().map(|_| Err(e.clone())).collect();
        }
        let one = |m: &mut Model, set: &P| m.scan_one(params, set.as_ref(), spec, &init, &fold);
        kinloop_runtime::generated::par_sets(sets, || self.clone(), one)
    }

    /// The error of a scan over `params` when one of them is not a parameter of this model.
    fn unknown_param(&self, params: &[&str]) -> Option<Error> {
        let name = params.iter().find(|&&p| !self.params().iter().any(|q| q == p))?;
        Some(Error::InvalidArgument(format!("`{}` has no parameter `{name}` to scan", self.name())))
    }

    /// One set of [`Model::scan`].
    fn scan_one<A>(
        &mut self,
        params: &[&str],
        set: &[f64],
        spec: &ParamScanConfig,
        init: &impl Fn(&[f64]) -> A,
        fold: &impl Fn(A, &[f64], &KinBuf) -> A,
    ) -> Result<A, Error> {
        if set.len() != params.len() {
            return Err(Error::InvalidArgument(format!(
                "a parameter set of {} for the {} scanned",
                Count(set.len(), "value"),
                Count(params.len(), "parameter")
            )));
        }
        for (name, &value) in params.iter().zip(set) {
            self.set_param(name, value);
        }
        let k = self.kernel(spec.config)?;
        let from = heap(&spec.from);
        let guess = match &spec.start {
            ParamScanStart::Declared => k.guess(&from),
            ParamScanStart::Guess(g) => heap(g),
            ParamScanStart::With(f) => heap(&f(set)),
        };
        fold_sweep_of(k, from, heap(&spec.to), spec.samples, guess, None, || init(set), |acc, s| fold(acc, set, s))
    }
}

/// How each sweep of a [`Model::scan`] starts: the initial guess at the start of the range,
/// which picks the assembly mode (branch) the sweep then follows (the compiled scans'
/// `ScanStart`, for parameter sets).
#[derive(Clone, Debug)]
pub enum ParamScanStart {
    /// Each set's declared initial guess at the start of the range (the `unknowns q = guess`
    /// of the declaration, with the set's parameter values).
    Declared,
    /// The same guess (unknowns in declaration order) for every set.
    Guess(Vec<f64>),
    /// A guess computed from each set's values (in the order of the parameters scanned); a
    /// closure that captures nothing converts to this function pointer.
    With(fn(&[f64]) -> Vec<f64>),
}

/// What every sweep of a [`Model::scan`] does: `samples` equally spaced inputs from `from` to
/// `to` (both included, as in [`Model::sweep`]), starting as `start` says, with `config`.
/// Built with [`ParamScanConfig::new`] and the builder methods.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct ParamScanConfig {
    /// Inputs at the first sample.
    pub from: Vec<f64>,
    /// Inputs at the last sample.
    pub to: Vec<f64>,
    /// Number of samples (at least 1; at least 2 when `to` differs from `from`; at most
    /// `kinloop_runtime::analysis::MAX_SAMPLES`: others make each set's result an
    /// `Error::InvalidArgument`).
    pub samples: usize,
    /// The initial guess at `from` (default: each set's declared guess there).
    pub start: ParamScanStart,
    /// The sweeps' configuration (default: the defaults).
    pub config: SweepConfig,
}

impl ParamScanConfig {
    /// Sweeps of `samples` inputs from `from` to `to`, from each set's declared guess
    /// ([`ParamScanStart::Declared`]), with the default configuration.
    pub fn new(from: &[f64], to: &[f64], samples: usize) -> Self {
        let (from, to) = (from.to_vec(), to.to_vec());
        ParamScanConfig { from, to, samples, start: ParamScanStart::Declared, config: SweepConfig::default() }
    }

    /// Replaces the starting guess policy.
    pub fn start(mut self, start: ParamScanStart) -> Self {
        self.start = start;
        self
    }

    /// Gives every sweep this configuration.
    pub fn with_config(mut self, config: SweepConfig) -> Self {
        self.config = config;
        self
    }
}
