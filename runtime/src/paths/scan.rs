//! Design-space scans: one [`Sweep`](crate::Sweep) per parameter set, each reduced to a value by
//! a fold.
//!
//! A scan runs the same sweep (input range, samples, configuration) over every mechanism of a
//! slice — the parameter sets of a design study — and folds each sweep's states into one value
//! (a stroke, the largest transmission angle, the peak of an acceleration analog, ...) without
//! keeping the states: a scan allocates its result vector and nothing else per set or per sample
//! (unless `init` or `fold` do; errors carry a boxed location). [`scan`] runs the sets one after
//! the other; `par_scan` (cargo feature `rayon`) runs them on all cores with rayon's work
//! stealing and returns bitwise the same results in the same order.
//!
//! Each set succeeds or fails on its own: a parameter set that cannot be assembled, that meets a
//! limit position before the end of the range, whose parameters are not finite, or whose angle
//! parameter is too large to resolve ([`Mechanism::check_param_angles`], checked once a set)
//! gives an [`Error`] in its slot and the others go on. A set whose sweep fails at any sample yields that
//! error, not the fold of the samples before it.
//!
//! One set's sweep and fold is written once, over any [`Kernel`] ([`fold_sweep_of`]): a run-time
//! model's scan over parameter sets (`kinloop_model::Model::scan`) is the same. The parallel
//! distribution is written once too (a hidden helper: a workspace per rayon job, a run-time model's
//! clone for `kinloop_model::Model::par_scan`).
//!
//! The `kinloop` facade crate has a runnable example (its documentation, "Design-space scans").

use crate::error::Error;
use crate::kin::Kin;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, Kernel, KinOf, Q, X};
use crate::paths::config::SweepConfig;
use crate::paths::sweep::SweepOf;
use std::fmt;

/// How each sweep of a scan starts: the initial guess at the start of the range, which picks
/// the assembly mode (branch) the sweep then follows.
pub enum ScanStart<M, const N: usize> {
    /// Each mechanism's declared initial guess at the start of the range
    /// ([`Mechanism::guess_flat`]; the `unknowns q = guess` of the declaration).
    Declared,
    /// The same guess (unknowns in declaration order) for every mechanism.
    Guess([f64; N]),
    /// A guess computed from each mechanism (e.g. from its link lengths); a closure that
    /// captures nothing converts to this function pointer.
    With(fn(&M) -> [f64; N]),
}

impl<M, const N: usize> Clone for ScanStart<M, N> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M, const N: usize> Copy for ScanStart<M, N> {}

impl<M, const N: usize> fmt::Debug for ScanStart<M, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScanStart::Declared => f.write_str("Declared"),
            ScanStart::Guess(g) => f.debug_tuple("Guess").field(g).finish(),
            ScanStart::With(_) => f.write_str("With(..)"),
        }
    }
}

impl<M, const N: usize> ScanStart<M, N> {
    /// The initial guess of mechanism `m` at input `from`.
    pub fn guess<const NI: usize, const NO: usize>(&self, m: &M, from: &[f64; NI]) -> [f64; N]
    where
        M: Mechanism<N, NI, NO>,
    {
        match self {
            ScanStart::Declared => m.guess_flat(from),
            ScanStart::Guess(g) => *g,
            ScanStart::With(f) => f(m),
        }
    }
}

/// What every sweep of a scan does: `samples` equally spaced inputs from `from` to `to` (both
/// included, as in [`Sweep::new`](crate::Sweep::new)), starting as `start` says, with `config`
/// (or each mechanism's own, [`Mechanism::solver_config`]). Built with [`ScanConfig::new`] and
/// the builder methods.
#[non_exhaustive]
pub struct ScanConfig<M, const N: usize, const NI: usize> {
    /// Inputs at the first sample.
    pub from: [f64; NI],
    /// Inputs at the last sample.
    pub to: [f64; NI],
    /// Number of samples (at least 1; at least 2 when `to` differs from `from`; at most
    /// [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES): others make each design's result an
    /// `Error::InvalidArgument`).
    pub samples: usize,
    /// The initial guess at `from`.
    pub start: ScanStart<M, N>,
    /// The sweeps' configuration; `None` (default): each mechanism's own
    /// ([`Mechanism::solver_config`]: the defaults, or a [`Configured`](crate::Configured)
    /// mechanism's).
    pub config: Option<SweepConfig>,
}

impl<M, const N: usize, const NI: usize> Clone for ScanConfig<M, N, NI> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M, const N: usize, const NI: usize> Copy for ScanConfig<M, N, NI> {}

impl<M, const N: usize, const NI: usize> fmt::Debug for ScanConfig<M, N, NI> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ScanConfig")
            .field("from", &self.from)
            .field("to", &self.to)
            .field("samples", &self.samples)
            .field("start", &self.start)
            .field("config", &self.config)
            .finish()
    }
}

impl<M, const N: usize, const NI: usize> ScanConfig<M, N, NI> {
    /// Sweeps of `samples` inputs from `from` to `to`, each starting from the mechanism's
    /// declared guess ([`ScanStart::Declared`]), with each mechanism's configuration.
    pub fn new(from: [f64; NI], to: [f64; NI], samples: usize) -> Self {
        ScanConfig { from, to, samples, start: ScanStart::Declared, config: None }
    }

    /// Replaces the starting guess policy.
    pub fn start(mut self, start: ScanStart<M, N>) -> Self {
        self.start = start;
        self
    }

    /// Gives every sweep this configuration (instead of each mechanism's own).
    pub fn with_config(mut self, config: SweepConfig) -> Self {
        self.config = Some(config);
        self
    }
}

/// One parameter set: its sweep folded into one value.
fn scan_one<M, A, I, F, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    spec: &ScanConfig<M, N, NI>,
    init: &I,
    fold: &F,
) -> Result<A, Error>
where
    M: Mechanism<N, NI, NO>,
    I: Fn(&M) -> A,
    F: Fn(A, &M, &Kin<N, NI, NO>) -> A,
{
    // Before the guess, which may be the user's function of the mechanism.
    check_samples(&spec.from, &spec.to, spec.samples)?;
    // Each design's own parameters: one whose angle is too large to resolve is that set's error.
    m.check_param_angles(&spec.config.unwrap_or_else(|| m.solver_config()).newton)?;
    let guess = spec.start.guess::<NI, NO>(m, &spec.from);
    fold_sweep_of(
        Compiled(m),
        spec.from,
        spec.to,
        spec.samples,
        guess,
        spec.config,
        || init(m),
        |acc, k| fold(acc, m, k),
    )
}

/// The sample count of a scan's sweeps. One sample is the start alone: a range to another end
/// would be ignored. A count beyond what an analysis takes would fold for years
/// (`usize::MAX`). Ends not finite, or of another size than each other, are left to the sweep,
/// which names them: a NaN end differs from itself, and was said to need 2 samples.
fn check_samples(from: &[f64], to: &[f64], samples: usize) -> Result<(), Error> {
    let comparable = from.len() == to.len() && from.iter().chain(to).all(|v| v.is_finite());
    if samples < 2 && comparable && from != to {
        return Err(Error::InvalidArgument(format!(
            "a scan from {from:?} to {to:?} needs at least 2 samples (its ends); {samples} asked for"
        )));
    }
    crate::analysis::check_sample_count("samples of a scan", samples).map_err(Error::InvalidArgument)
}

/// One set of a scan over any [`Kernel`] (a compiled mechanism's, or a run-time model's with
/// one parameter set: `kinloop_model::Model::scan`): the sweep of `samples` inputs from `from`
/// to `to` from `guess` at `from`, with `config` (or the kernel's own,
/// [`Kernel::solver_config`]), its states folded in order into the accumulator, which starts
/// as `init()` once the sweep is made (`acc = fold(acc, &state)`, each state lent where the
/// sweep keeps it). The sweep's error,
/// where it fails at any sample, rather than the fold of the samples before it; an
/// [`Error::InvalidArgument`] before the sweep for one sample with `to` not `from` (the range
/// would be ignored) or more than [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES).
#[allow(clippy::too_many_arguments)]
pub fn fold_sweep_of<K: Kernel, A>(
    m: K,
    from: X<K>,
    to: X<K>,
    samples: usize,
    guess: Q<K>,
    config: Option<SweepConfig>,
    init: impl FnOnce() -> A,
    mut fold: impl FnMut(A, &KinOf<K>) -> A,
) -> Result<A, Error> {
    check_samples(from.as_ref(), to.as_ref(), samples)?;
    let mut sweep = SweepOf::<K, KinOf<K>>::over(m, from, to, samples, guess)?;
    if let Some(config) = config {
        sweep = sweep.with_config(config);
    }
    let mut acc = init();
    while let Some(k) = sweep.next_ref() {
        acc = fold(acc, k?);
    }
    Ok(acc)
}

/// Sweeps every mechanism of `mechanisms` as `spec` says and folds each sweep into one value,
/// one set after the other.
///
/// For each mechanism `m`, the accumulator starts as `init(m)` and every state of the sweep, in
/// order, updates it: `acc = fold(acc, m, &state)`. The result has one slot per mechanism, in
/// the same order: the final accumulator, or the error that ended that set's sweep (it cannot
/// be assembled at `from`, meets a limit position, has non-finite parameters, ...; an invalid
/// `spec` gives every set the same error). A failing set never stops the others. Never panics
/// (unless `init` or `fold` does).
///
/// No table is built: apart from the result vector (and errors, whose location is boxed), a
/// scan allocates nothing. The states are the flat [`Kin`] (unknowns and outputs in declaration
/// order, as in `Name::UNKNOWNS` and `Name::OUTPUTS`); `NameState::from(*k)` names them.
pub fn scan<M, A, I, F, const N: usize, const NI: usize, const NO: usize>(
    mechanisms: &[M],
    spec: &ScanConfig<M, N, NI>,
    init: I,
    fold: F,
) -> Vec<Result<A, Error>>
where
    M: Mechanism<N, NI, NO>,
    I: Fn(&M) -> A,
    F: Fn(A, &M, &Kin<N, NI, NO>) -> A,
{
    mechanisms.iter().map(|m| scan_one(m, spec, &init, &fold)).collect()
}

/// [`scan`] on all cores: the parameter sets are distributed over rayon's global thread pool
/// (work stealing, so sets with slow sweeps do not hold the others up).
///
/// The results are bitwise identical to [`scan`]'s and in the same order: each set is computed
/// by the same code from the same inputs, independently of the others. Requires the cargo
/// feature `rayon`. Run it inside [`rayon::ThreadPool::install`] to choose the number of
/// threads.
#[cfg(feature = "rayon")]
pub fn par_scan<M, A, I, F, const N: usize, const NI: usize, const NO: usize>(
    mechanisms: &[M],
    spec: &ScanConfig<M, N, NI>,
    init: I,
    fold: F,
) -> Vec<Result<A, Error>>
where
    M: Mechanism<N, NI, NO> + Sync,
    A: Send,
    I: Fn(&M) -> A + Sync + Send,
    F: Fn(A, &M, &Kin<N, NI, NO>) -> A + Sync + Send,
{
    crate::generated::par_sets(mechanisms, || (), |_, m| scan_one(m, spec, &init, &fold))
}
