//! The global search: local solves from many starts spread over the box of the design variables
//! by a shifted Halton sequence, each verified, ranked. Start `i` depends on the seed and on `i`
//! only, so a search can be split by index range over processes or machines and the reports
//! merged ([`SynthesisReport::merge`]); with the `rayon` feature [`Search::par_run`] runs the
//! starts on all cores with the same result as [`Search::run`].

use super::candidate::{Candidate, Defect};
use super::error::SynthesisError;
use super::halton::Halton;
use super::local::LocalConfig;
use super::problem::{Inputs, Problem};
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

/// The outcome of a search: the best candidates and what happened to the others.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SynthesisReport {
    /// The design variables' names, the order of [`Candidate::values`].
    pub variables: Vec<String>,
    /// Their bounds, in the same order.
    pub bounds: Vec<(f64, f64)>,
    /// The best distinct candidates: valid ones (no defect) first, each group by increasing
    /// RMS error, ties by start index.
    pub candidates: Vec<Candidate>,
    /// The starts run.
    pub starts: Range<usize>,
    /// Starts at which the design cannot be assembled at every target (no local solve).
    pub unassembled: usize,
    /// Local solves that met the tolerance (residual or step).
    pub converged: usize,
    /// Local solves whose result is valid (no defect).
    pub valid: usize,
    /// Candidates rejected, by their first defect: order, branch, circuit, no assembly, full
    /// rotation, transmission angle, link ratio.
    pub rejected: [usize; 7],
    /// Evaluations of residuals and Jacobian over all starts.
    pub evaluations: usize,
}

impl SynthesisReport {
    /// The best valid candidate, if any.
    pub fn best(&self) -> Option<&Candidate> {
        self.candidates.first().filter(|c| c.is_valid())
    }

    /// The reports of two parts of one search (disjoint start ranges of the same problem,
    /// `search` the settings both ran with but for the range) as one: ranked again, duplicates
    /// removed, cut to [`Search::keep`].
    pub fn merge(mut self, other: SynthesisReport, search: &Search) -> SynthesisReport {
        let mut all = std::mem::take(&mut self.candidates);
        all.extend(other.candidates);
        self.candidates = distinct(all, &self.bounds, search);
        self.starts = self.starts.start.min(other.starts.start)..self.starts.end.max(other.starts.end);
        self.unassembled += other.unassembled;
        self.converged += other.converged;
        self.valid += other.valid;
        for (a, b) in self.rejected.iter_mut().zip(other.rejected) {
            *a += b;
        }
        self.evaluations += other.evaluations;
        self
    }
}

/// Valid first, then by RMS error, then by start.
fn rank(c: &mut [Candidate]) {
    c.sort_by(|a, b| {
        b.is_valid().cmp(&a.is_valid()).then(a.rms_error.total_cmp(&b.rms_error)).then(a.start.cmp(&b.start))
    });
}

/// The candidates ranked, without duplicates (a candidate of the same validity whose every
/// value is within `distinct` of the range of one ranked before it), at most `keep`.
fn distinct(mut all: Vec<Candidate>, bounds: &[(f64, f64)], search: &Search) -> Vec<Candidate> {
    rank(&mut all);
    let span: Vec<f64> = bounds.iter().map(|(lo, hi)| (hi - lo).max(f64::MIN_POSITIVE)).collect();
    let mut out: Vec<Candidate> = Vec::new();
    for c in all {
        if out.len() >= search.keep {
            break;
        }
        let same = |o: &Candidate| {
            o.is_valid() == c.is_valid()
                && o.values.iter().zip(&c.values).zip(&span).all(|((a, b), s)| (a - b).abs() <= search.distinct * s)
        };
        if !out.iter().any(same) {
            out.push(c);
        }
    }
    out
}

/// The slot of `rejected` counting a defect.
fn slot(d: &Defect) -> usize {
    match d {
        Defect::Order => 0,
        Defect::Branch { .. } => 1,
        Defect::Circuit { .. } => 2,
        Defect::NoAssembly { .. } => 3,
        Defect::NoFullRotation => 4,
        Defect::Transmission { .. } => 5,
        Defect::LinkRatio { .. } => 6,
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
        self.validate()?;
        let found: Vec<Option<Candidate>> = self.starts.clone().map(|i| self.one(problem, i)).collect();
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
        use rayon::prelude::*;
        self.validate()?;
        let found: Vec<Option<Candidate>> = self.starts.clone().into_par_iter().map(|i| self.one(problem, i)).collect();
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
            rejected: [0; 7],
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
                Some(d) => report.rejected[slot(d)] += 1,
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
