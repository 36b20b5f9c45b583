//! The global search: local solves from many starts spread over the box of the design variables
//! by a shifted Halton sequence, each verified, ranked. Start `i` depends on the seed and on `i`
//! only, so a search can be split by index range over processes or machines and the reports
//! merged ([`SynthesisReport::merge`](super::SynthesisReport::merge)); with the `rayon` feature [`Search::par_run`] runs the
//! starts on all cores with the same result as [`Search::run`].

use super::candidate::Candidate;
use super::error::SynthesisError;
use super::halton::Halton;
use super::local::LocalConfig;
use super::problem::Problem;
use super::report::{Rejections, SynthesisReport, distinct};
use super::resolve::Inputs;
use crate::mechanism::Sensitivities;
use std::ops::Range;

/// Settings of a global search, apart from the problem (build once, run on many problems).
///
/// ```
/// use kinloop_runtime::synthesis::Search;
/// let search = Search::default().with_starts(0..256).with_seed(7).with_keep(5);
/// assert_eq!(search.starts, 0..256);
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Search {
    /// The indices of the starts to run (default `0..64`).
    pub starts: Range<usize>,
    /// The seed of the Halton sequence's shift (default `0`).
    pub seed: u64,
    /// The local solve from each start.
    pub local: LocalConfig,
    /// How many candidates the report keeps, best first (default `10`).
    pub keep: usize,
    /// Two candidates are one design when every design variable agrees to this, relative to
    /// its range (default `1e-6`); the report keeps the better.
    pub distinct: f64,
}

impl Default for Search {
    fn default() -> Self {
        Search { starts: 0..64, seed: 0, local: LocalConfig::default(), keep: 10, distinct: 1e-6 }
    }
}

impl Search {
    /// Sets [`Search::starts`].
    pub fn with_starts(mut self, starts: Range<usize>) -> Self {
        self.starts = starts;
        self
    }
    /// Sets [`Search::seed`].
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }
    /// Sets [`Search::local`].
    pub fn with_local(mut self, local: LocalConfig) -> Self {
        self.local = local;
        self
    }
    /// Sets [`Search::keep`].
    pub fn with_keep(mut self, keep: usize) -> Self {
        self.keep = keep;
        self
    }
    /// Sets [`Search::distinct`].
    pub fn with_distinct(mut self, distinct: f64) -> Self {
        self.distinct = distinct;
        self
    }

    fn validate(&self) -> Result<(), SynthesisError> {
        if let Some(field) = self.local.invalid_field() {
            return Err(SynthesisError::InvalidConfig(format!("local.{field}")));
        }
        if !(self.distinct.is_finite() && self.distinct >= 0.0) {
            return Err(SynthesisError::InvalidConfig("distinct".into()));
        }
        Ok(())
    }

    /// The starting point `index` of the search: the design variables (and placement) from the
    /// Halton sequence scaled to their box; free inputs evenly spaced over their range, in
    /// order, `lo + (hi - lo) (k + 1/2) / n`.
    pub fn start<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
        &self,
        problem: &Problem<M, N, NI, NO, NP>,
        index: usize,
    ) -> Vec<f64>
    where
        M: Sensitivities<N, NI, NO, NP> + Clone,
    {
        let (lo, hi) = problem.bounds();
        let nv = problem.vars.len();
        let nt = problem.free_inputs();
        let sampled: Vec<usize> = (0..nv).chain(nv + nt..lo.len()).collect();
        let u = Halton::new(sampled.len(), self.seed).point(index as u64);
        let mut z: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| 0.5 * (a + b)).collect();
        for (&i, t) in sampled.iter().zip(&u) {
            z[i] = lo[i] + (hi[i] - lo[i]) * t;
        }
        if let Inputs::Free { lo: a, hi: b } = problem.inputs {
            for k in 0..nt {
                z[nv + k] = a + (b - a) * (k as f64 + 0.5) / nt as f64;
            }
        }
        z
    }

    /// One start: its local solve, verified (`None` where the start cannot be assembled).
    fn one<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
        &self,
        problem: &Problem<M, N, NI, NO, NP>,
        index: usize,
    ) -> Option<Candidate>
    where
        M: Sensitivities<N, NI, NO, NP> + Clone,
    {
        let z0 = self.start(problem, index);
        let (z, e, report) = problem.local(z0, &self.local).ok()?;
        Some(problem.verify(index, z, e, report))
    }

    /// Runs the starts one after the other.
    pub fn run<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
        &self,
        problem: &Problem<M, N, NI, NO, NP>,
    ) -> Result<SynthesisReport, SynthesisError>
    where
        M: Sensitivities<N, NI, NO, NP> + Clone,
    {
        self.run_with_progress(problem, |_, _| {})
    }

    /// [`Search::run`], calling `progress(done, total)` after each start (e.g. to drive a
    /// progress bar on a long search).
    pub fn run_with_progress<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
        &self,
        problem: &Problem<M, N, NI, NO, NP>,
        mut progress: impl FnMut(usize, usize),
    ) -> Result<SynthesisReport, SynthesisError>
    where
        M: Sensitivities<N, NI, NO, NP> + Clone,
    {
        self.validate()?;
        let total = self.starts.len();
        let found: Vec<Option<Candidate>> = self
            .starts
            .clone()
            .enumerate()
            .map(|(k, i)| {
                let c = self.one(problem, i);
                progress(k + 1, total);
                c
            })
            .collect();
        Ok(self.report(problem, found))
    }

    /// [`Search::run`] on all cores (rayon's global pool, or the pool it is called in): the
    /// same report, candidates in the same order.
    #[cfg(feature = "rayon")]
    pub fn par_run<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
        &self,
        problem: &Problem<M, N, NI, NO, NP>,
    ) -> Result<SynthesisReport, SynthesisError>
    where
        M: Sensitivities<N, NI, NO, NP> + Clone + Sync,
    {
        self.par_run_with_progress(problem, |_, _| {})
    }

    /// [`Search::par_run`], calling `progress(done, total)` from the worker threads after each
    /// start (`done` counts the starts finished, in whatever order they finish).
    #[cfg(feature = "rayon")]
    pub fn par_run_with_progress<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
        &self,
        problem: &Problem<M, N, NI, NO, NP>,
        progress: impl Fn(usize, usize) + Sync,
    ) -> Result<SynthesisReport, SynthesisError>
    where
        M: Sensitivities<N, NI, NO, NP> + Clone + Sync,
    {
        use rayon::prelude::*;
        use std::sync::atomic::{AtomicUsize, Ordering};
        self.validate()?;
        let (total, done) = (self.starts.len(), AtomicUsize::new(0));
        let found: Vec<Option<Candidate>> = self
            .starts
            .clone()
            .into_par_iter()
            .map(|i| {
                let c = self.one(problem, i);
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
                c
            })
            .collect();
        Ok(self.report(problem, found))
    }

    /// Counts, ranks and removes duplicates (in start order, so that the result does not
    /// depend on how the starts were run).
    fn report<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
        &self,
        problem: &Problem<M, N, NI, NO, NP>,
        found: Vec<Option<Candidate>>,
    ) -> SynthesisReport
    where
        M: Sensitivities<N, NI, NO, NP> + Clone,
    {
        let mut report = SynthesisReport {
            variables: problem.names.clone(),
            bounds: problem.vars.iter().map(|b| (b.lo, b.hi)).collect(),
            candidates: Vec::new(),
            starts: self.starts.clone(),
            unassembled: 0,
            converged: 0,
            valid: 0,
            rejected: Rejections::default(),
            evaluations: 0,
        };
        let mut all = Vec::new();
        for c in found {
            let Some(c) = c else {
                report.unassembled += 1;
                continue;
            };
            report.evaluations += c.local.evaluations;
            report.converged += usize::from(c.local.stop == crate::analysis::optimize::OptimizerStop::Converged);
            match c.defects.first() {
                None => report.valid += 1,
                Some(d) => report.rejected.count(d),
            }
            all.push(c);
        }
        report.evaluations += report.unassembled;
        report.candidates = distinct(all, &report.bounds, self);
        report
    }

    /// Runs the local solve from `z0` (the search's unknowns, see [`Problem`]; clamped into
    /// their bounds) and verifies its result: e.g. from a classical closed-form design, or to
    /// polish a candidate with other settings. An error where the design cannot be assembled
    /// at every target at `z0`.
    pub fn refine<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
        &self,
        problem: &Problem<M, N, NI, NO, NP>,
        z0: &[f64],
    ) -> Result<Candidate, SynthesisError>
    where
        M: Sensitivities<N, NI, NO, NP> + Clone,
    {
        self.validate()?;
        problem.check_point(z0)?;
        let (lo, hi) = problem.bounds();
        let z0 = z0.iter().zip(lo.iter().zip(&hi)).map(|(v, (a, b))| v.clamp(*a, *b)).collect();
        let (z, e, report) = problem.local(z0, &self.local)?;
        Ok(problem.verify(usize::MAX, z, e, report))
    }
}
