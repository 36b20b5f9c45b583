//! A run-time model as a kernel that threads can share ([`SharedModelKernel`]): a model is one
//! workspace (its registers and factorisations written by every step), so each evaluation
//! checks a clone out of a pool, sets its parameters, runs on it alone and gives it back. What
//! `Search::par_run` needs of a synthesis problem ([`Model::shared_synthesis_problem`]).
//!
//! A step's result depends on its parameters, inputs, guess and configuration only: the
//! parameters' registers are written and the nodes of the parameters alone computed when they
//! are set, and a step writes the inputs' registers, every block's factorisation and the state
//! before reading them. So a clone checked out with the parameters of an evaluation computes what
//! any other would, whatever it ran before (`tests/synthesis.rs`: a search on all cores equals
//! the search one evaluation after another, bit for bit).

use crate::at::Jacobian;
use crate::mechanism::{Info, model_kernel_body};
use crate::model::{Model, StepError};
use crate::sens_kernel::{ModelSens, copy_sens, model_sens_body};
use kinloop_runtime::dims::{Dims, Heap, KinBuf};
use kinloop_runtime::{Error, Kernel, NewtonConfig, Quantity, SensKernel, SweepConfig};
use std::borrow::Cow;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

/// A [`Model`] as a [`Kernel`] (and, declared with `#[kinloop(sensitivities)]`, a
/// [`SensKernel`]) that threads can share: `Send + Sync`, each evaluation run on a clone of the
/// model checked out of a pool (made on demand, so at most one per evaluation running at a
/// time) and given back after it. [`SensKernel::with_params`] checks out a clone with the
/// parameters asked for, as a compiled mechanism's kernel gives `f` a copy with them; its other
/// methods run on a clone with the kernel's own parameters, those of the model it was made from
/// ([`Model::shared_kernel`]).
///
/// A clone whose evaluation panicked is dropped, not given back (its workspace may be half
/// written); a failed evaluation's clone is given back, its parameters set anew by the next
/// evaluation that checks it out.
///
/// ```
/// use kinloop_model::Model;
/// use kinloop_runtime::{Kernel, SensKernel, SweepConfig};
/// let text = "#[kinloop(sensitivities)]
/// pub struct SliderCrank {
///     params r = 1, l = 3;
///     input phi;
///     unknowns beta = 0, s = 4;
///     loop rod: r @ phi + l @ beta == (s, 0);
/// }";
/// let m = Model::read("slider_crank.kl", text).unwrap();
/// let k = m.shared_kernel(SweepConfig::default()).unwrap();
/// let x = kinloop_runtime::dims::Heap(vec![0.0].into());
/// let guess = k.guess(&x);
/// let cfg = kinloop_runtime::NewtonConfig::default();
/// // Two threads, each with its own parameters, on one kernel.
/// let (s1, s2) = std::thread::scope(|scope| {
///     let run = |p: [f64; 2]| {
///         let (k, x, guess, cfg) = (&k, &x, &guess, &cfg);
///         scope.spawn(move || k.with_params(&p, |k| k.kinematics(x, guess, cfg).unwrap().q[1]).unwrap())
///     };
///     let (a, b) = (run([1.0, 3.0]), run([1.5, 4.0]));
///     (a.join().unwrap(), b.join().unwrap())
/// });
/// assert!((s1 - 4.0).abs() < 1e-12 && (s2 - 5.5).abs() < 1e-12);
/// ```
pub struct SharedModelKernel {
    info: Arc<Info>,
    pool: Arc<Pool>,
    /// The parameters every evaluation on this kernel runs with: the model's, or inside
    /// `with_params` those it was called with.
    params: Vec<f64>,
    /// Inside `with_params`: the clone checked out for the call (a mutex, so that the kernel
    /// handed to the call stays `Sync`; only that call's thread locks it, once per kernel call).
    lent: Option<Mutex<Box<Lent>>>,
}

/// The clones of a model waiting to be checked out, and the model they are cloned from.
struct Pool {
    model: Model,
    /// Boxed: a model is kilobytes, moved in and out of the list on every call.
    #[allow(clippy::vec_box)]
    free: Mutex<Vec<Box<Lent>>>,
    /// The clones made so far.
    clones: AtomicUsize,
}

/// A clone of the model and its scratch Jacobian.
struct Lent {
    model: Model,
    jac: Jacobian,
}

impl Pool {
    /// The free list, also after a thread panicked while holding it (it only ever pushes or pops
    /// a whole clone, so the list is whole).
    #[allow(clippy::vec_box)] // see `Pool::free`
    fn free(&self) -> MutexGuard<'_, Vec<Box<Lent>>> {
        self.free.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// A clone with the parameters `p` (one per parameter): a free one, or a new one.
    fn check_out(&self, p: &[f64]) -> Box<Lent> {
        let free = self.free().pop();
        let mut lent = free.unwrap_or_else(|| {
            self.clones.fetch_add(1, Ordering::Relaxed);
            Box::new(Lent { model: self.model.clone(), jac: Jacobian::default() })
        });
        // Loaded unless the clone holds them already, to the bit: the kernel's own evaluations
        // outside `with_params` (a sweep's steps) then neither allocate nor load anything.
        let held = lent.model.param_values().iter().zip(p).all(|(v, p)| v.map(f64::to_bits) == Some(p.to_bits()));
        if !held {
            let mut values: Vec<Option<f64>> = p.iter().copied().map(Some).collect();
            lent.model.swap_params(&mut values);
        }
        lent
    }

    /// Gives `lent` back after its evaluation. (A clone whose evaluation panicked is never
    /// given back: it is dropped while the panic unwinds, for the panic may have stopped a step
    /// half way through its workspace.)
    fn give_back(&self, lent: Box<Lent>) {
        self.free().push(lent);
    }
}

impl Model {
    /// This model as a [`Kernel`] that threads can share ([`SharedModelKernel`]), with the
    /// solver configuration `config`: the model is cloned, each evaluation runs on a clone of
    /// that. Every parameter must have a value (`Error::InvalidArgument` names the first that
    /// has none).
    pub fn shared_kernel(&self, config: SweepConfig) -> Result<SharedModelKernel, Error> {
        let info = Arc::new(Info::of(self, config)?);
        let params = self.param_values().iter().map(|v| v.unwrap_or(f64::NAN)).collect();
        let pool = Arc::new(Pool { model: self.clone(), free: Mutex::new(Vec::new()), clones: AtomicUsize::new(0) });
        Ok(SharedModelKernel { info, pool, params, lent: None })
    }
}

impl SharedModelKernel {
    /// How many clones of the model its pool has made so far (shared by this kernel's clones
    /// and the kernels `with_params` hands out): the most evaluations that ran at the same
    /// time, plus one for each evaluation that panicked (its clone is dropped). Each holds the
    /// model's workspace.
    pub fn clones(&self) -> usize {
        self.pool.clones.load(Ordering::Relaxed)
    }

    /// What the kernel copied from the model.
    fn info(&self) -> &Info {
        &self.info
    }

    /// `f` called with a model of this kernel's parameters and a scratch Jacobian: the clone
    /// checked out by `with_params`, or one checked out for the call.
    fn lend<R>(&self, f: impl FnOnce(&mut Model, &mut Jacobian) -> R) -> R {
        match &self.lent {
            Some(lent) => {
                let mut lent = lent.lock().unwrap_or_else(PoisonError::into_inner);
                let Lent { model, jac } = &mut **lent;
                f(model, jac)
            }
            None => {
                let mut lent = self.pool.check_out(&self.params);
                let r = f(&mut lent.model, &mut lent.jac);
                self.pool.give_back(lent);
                r
            }
        }
    }
}

/// A kernel of the same model and parameters (its evaluations on clones of the same pool).
impl Clone for SharedModelKernel {
    fn clone(&self) -> Self {
        let (info, pool) = (Arc::clone(&self.info), Arc::clone(&self.pool));
        SharedModelKernel { info, pool, params: self.params.clone(), lent: None }
    }
}

impl Kernel for SharedModelKernel {
    model_kernel_body!();
}

impl SensKernel for SharedModelKernel {
    model_sens_body!();
    /// The parameter's value (NaN where the model had none, which making the kernel rules out).
    fn param(&self, k: usize) -> f64 {
        self.params[k]
    }
    /// `f` called with a kernel over a clone of the model with the parameters `p`, checked out
    /// of the pool for the call and given back after it (dropped where `f` panics): this kernel
    /// and its parameters are never changed, so calls on other threads and nested calls each
    /// have their own clone. `p` has one value per parameter (`Error::InvalidArgument`
    /// otherwise).
    fn with_params<R>(&self, p: &[f64], f: impl FnOnce(&Self) -> R) -> Result<R, Error> {
        self.check_param_count(p)?;
        let lent = self.pool.check_out(p);
        let (info, pool) = (Arc::clone(&self.info), Arc::clone(&self.pool));
        let kernel = SharedModelKernel { info, pool, params: p.to_vec(), lent: Some(Mutex::new(lent)) };
        let r = f(&kernel);
        // A clone whose step panicked (its lock poisoned, the panic caught inside `f`) is
        // dropped, as one whose `f` unwinds is.
        if let Some(Ok(lent)) = kernel.lent.map(Mutex::into_inner) {
            self.pool.give_back(lent);
        }
        Ok(r)
    }
}

/// The kernel by its model's name and sizes (so that a problem over it is `Debug`, as a compiled
/// `Problem` is: `unwrap_err` on its result).
impl std::fmt::Debug for SharedModelKernel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let info = self.info();
        let mut d = f.debug_struct("SharedModelKernel");
        d.field("name", &info.name).field("sizes", &info.sizes).field("params", &self.params).finish_non_exhaustive()
    }
}
