//! The global search: local solves from many starts spread over the box of the design variables
//! by a shifted Halton sequence (or from the best members of a differential evolution: see
//! [`Global`]), and from given seeds, each verified, ranked. Start `i` (island `i`) depends on
//! the seed and on `i` only, so a search can be split by index range over processes or machines
//! and the reports merged ([`SynthesisReport::merge`](super::SynthesisReport::merge)); with the
//! `rayon` feature [`Search::par_run`] runs on all cores with the same result as [`Search::run`].

use super::candidate::{Candidate, Origin};
use super::error::SynthesisError;
use super::evolution::{DeConfig, Global, IslandRng, best, evolve};
use super::halton::Halton;
use super::held::{Held, HeldRefusal, KEYS_FROM, distinct};
use super::local::LocalConfig;
use super::problem::ProblemOf;
use super::refusal::{RefusalKind, Refused};
use super::report::{Rejections, SynthesisReport};
use super::resolve::Inputs;
use crate::analysis::optimize::OptimizerStop;
use crate::mechanism::kernel::SensKernel;
use std::ops::Range;

/// Settings of a global search, apart from the problem (build once, run on many problems).
///
/// ```
/// use kinloop_runtime::synthesis::{DeConfig, Global, Search};
/// let search = Search::default().with_starts(0..256).with_seed(7).with_keep(5);
/// assert_eq!(search.starts, 0..256);
/// // Differential evolution instead: two islands of 24 members.
/// let de = search.with_global(Global::DifferentialEvolution(DeConfig::default().with_population(24)));
/// let de = de.with_starts(0..2);
/// assert!(matches!(de.global, Global::DifferentialEvolution(c) if c.population == 24));
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct Search {
    /// The indices of the starts to run (default `0..64`): Halton points, or with
    /// [`Global::DifferentialEvolution`] islands. An inverted range (`10..2`) is an error. A
    /// search holds what it found from every start until its report: of more than 4096 Halton
    /// starts (and 64 times [`Search::keep`]), a few hundred bytes a start, and it solves the
    /// starts its report keeps again (the same candidates, to the bit); of fewer, each start's
    /// whole candidate (about 2 KB for a four-bar through eight points).
    pub starts: Range<usize>,
    /// The seed of the Halton sequence's shift and of the evolution's random numbers (default
    /// `0`).
    pub seed: u64,
    /// Where the local solves start from (default [`Global::Halton`]).
    pub global: Global,
    /// Points of the search's unknowns to solve from before the global stage (e.g. classical
    /// closed-form designs; default none). They run with the part of a split search whose
    /// starts begin at `0`, so that the parts merge into the whole.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub seeds: Vec<Vec<f64>>,
    /// The local solve from each start.
    pub local: LocalConfig,
    /// How many candidates the report keeps, best first (default `10`; at least 1).
    pub keep: usize,
    /// Two candidates are one design when every design variable agrees to this, relative to
    /// its range (default `1e-6`); the report keeps the better.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub distinct: f64,
}

impl Default for Search {
    fn default() -> Self {
        Search {
            starts: 0..64,
            seed: 0,
            global: Global::Halton,
            seeds: Vec::new(),
            local: LocalConfig::default(),
            keep: 10,
            distinct: 1e-6,
        }
    }
}

/// One unit of work of a search: a seed, a Halton start, or an island.
#[derive(Clone, Copy)]
enum Job {
    Seed(usize),
    Start(usize),
    Island(usize, DeConfig),
}

/// The candidates of one job (or why one was refused before its local solve) and the
/// evaluations its global stage made beyond their local solves.
type Solved = (Vec<Result<Candidate, Refused>>, usize);

/// [`Solved`] as the search holds it until its report (see [`Held`]).
type Found = (Vec<Result<Held, HeldRefusal>>, usize);

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
    /// Sets [`Search::global`].
    pub fn with_global(mut self, global: Global) -> Self {
        self.global = global;
        self
    }
    /// Sets [`Search::seeds`]: each a point of the search's unknowns (see
    /// [`ProblemOf`]; clamped into their bounds), e.g. a four-bar of
    /// [`classical`](super::classical) mapped onto the declaration's parameters.
    pub fn with_seeds(mut self, seeds: Vec<Vec<f64>>) -> Self {
        self.seeds = seeds;
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

    /// The local solve's settings, the only ones [`Search::refine`] uses: a refinement is not
    /// refused for a start range or `keep` it never reads.
    fn validate_local(&self) -> Result<(), SynthesisError> {
        match self.local.invalid_field() {
            Some((field, value, range)) => {
                Err(SynthesisError::InvalidConfig(format!("local.{field} is {value}: it must be {range}")))
            }
            None => Ok(()),
        }
    }

    fn validate(&self) -> Result<(), SynthesisError> {
        self.validate_local()?;
        if !(self.distinct.is_finite() && self.distinct >= 0.0) {
            return Err(SynthesisError::InvalidConfig(format!(
                "distinct is {}: it must be finite and not negative",
                self.distinct
            )));
        }
        // None kept is no answer: every candidate found would be dropped, with `Ok`.
        if self.keep == 0 {
            return Err(SynthesisError::InvalidConfig("keep is 0: it must be at least 1".into()));
        }
        // Nothing to solve from returned `Ok` with an empty report, as if the design had no
        // solution (the command line's `--starts` takes at least 1). A part of a split search
        // whose range is empty but which holds seeds is not refused: its seeds run where its
        // range begins at 0, and otherwise it merges as nothing.
        if self.starts.is_empty() && self.seeds.is_empty() {
            return Err(SynthesisError::InvalidConfig(format!(
                "starts {:?} and no seeds: the search has nothing to solve from; give at least one start \
                 (`with_starts(0..64)`) or a seed",
                self.starts
            )));
        }
        // An inverted range ran nothing, with `Ok`, and merged into a range it never covered.
        if self.starts.start > self.starts.end {
            return Err(SynthesisError::InvalidConfig(format!(
                "starts {:?} is inverted: write the first index first ({}..{})",
                self.starts, self.starts.end, self.starts.start
            )));
        }
        // Every start's result is held until the report, in a vector of the jobs' results and
        // then of their candidates: more than either holds panicked in the allocator (a capacity
        // overflow). The larger entry bounds both.
        let entry = std::mem::size_of::<Found>().max(std::mem::size_of::<Held>());
        let most = isize::MAX as usize / entry;
        if self.starts.len().saturating_add(self.seeds.len()) > most {
            return Err(SynthesisError::InvalidConfig(format!(
                "starts {:?}: {} starts, more than a report can hold ({most})",
                self.starts,
                self.starts.len()
            )));
        }
        if let Global::DifferentialEvolution(de) = &self.global {
            de.validate()?;
        }
        Ok(())
    }

    /// [`Search::validate`], and every seed a point of `problem`'s unknowns.
    fn validate_for<K>(&self, problem: &ProblemOf<K>) -> Result<(), SynthesisError>
    where
        K: SensKernel,
    {
        self.validate()?;
        problem.check_param_angles()?;
        for (k, seed) in self.seeds.iter().enumerate() {
            // The seed's index in the message, the kind of error kept.
            problem.check_point(seed).map_err(|e| match e {
                SynthesisError::InvalidConfig(m) => SynthesisError::InvalidConfig(format!("seed {k}: {m}")),
                SynthesisError::Mismatch(m) => SynthesisError::Mismatch(format!("seed {k}: {m}")),
                e => e,
            })?;
        }
        Ok(())
    }

    /// The number of jobs of this search: its seeds (with the part whose starts begin at 0)
    /// and its starts.
    fn job_count(&self) -> usize {
        let seeds = if self.starts.start == 0 { self.seeds.len() } else { 0 };
        seeds + self.starts.len()
    }

    /// Job `k` of this search, in the order their candidates are reported: the seeds, then the
    /// starts (or islands). Made as it is run, so that a search of many starts lists none.
    fn job_at(&self, k: usize) -> Job {
        let seeds = self.job_count() - self.starts.len();
        if k < seeds {
            return Job::Seed(k);
        }
        let i = self.starts.start + (k - seeds);
        match self.global {
            Global::Halton => Job::Start(i),
            Global::DifferentialEvolution(de) => Job::Island(i, de),
        }
    }

    /// The starting point `index` of the search: the design variables (and placement) from the
    /// Halton sequence scaled to their box; free inputs evenly spaced over their range, in
    /// order, `lo + (hi - lo) (k + 1/2) / n`.
    pub fn start<K>(&self, problem: &ProblemOf<K>, index: usize) -> Vec<f64>
    where
        K: SensKernel,
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

    /// The local solve from `z0`, verified; refused, with the reason, where `z0` cannot be
    /// evaluated (it cannot be assembled at a target, or its angle parameter is too large).
    fn solve<K>(&self, problem: &ProblemOf<K>, z0: Vec<f64>, origin: Origin, index: usize) -> Result<Candidate, Refused>
    where
        K: SensKernel,
    {
        let refused = |e, z: Vec<f64>| Refused::one(&e, origin, index, z);
        let start = z0.clone();
        let (z, e, report) = problem.local(z0, &self.local).map_err(|e| refused(e, start))?;
        let point = z.clone();
        problem.verify(origin, index, z, e, report).map_err(|e| refused(e, point))
    }

    /// A point clamped into the bounds of the unknowns.
    fn clamped<K>(problem: &ProblemOf<K>, z: &[f64]) -> Vec<f64>
    where
        K: SensKernel,
    {
        let (lo, hi) = problem.bounds();
        z.iter().zip(lo.iter().zip(&hi)).map(|(v, (a, b))| v.clamp(*a, *b)).collect()
    }

    /// One job: a seed's or a start's local solve, or an island's evolution and the local
    /// solves of its best members. `batch` evaluates the residual norms of a generation's
    /// trial vectors (one after the other, or on all cores), `inf` where one cannot be
    /// assembled.
    fn job<K>(&self, problem: &ProblemOf<K>, job: Job, batch: impl Fn(&[Vec<f64>]) -> Vec<f64>) -> Solved
    where
        K: SensKernel,
    {
        match job {
            // A point that cannot be assembled costs its one evaluation.
            Job::Seed(k) => {
                let c = self.solve(problem, Self::clamped(problem, &self.seeds[k]), Origin::Seed, k);
                let unassembled = usize::from(c.is_err());
                (vec![c], unassembled)
            }
            Job::Start(i) => {
                let c = self.solve(problem, self.start(problem, i), Origin::Halton, i);
                let unassembled = usize::from(c.is_err());
                (vec![c], unassembled)
            }
            Job::Island(i, de) => self.island(problem, i, &de, batch),
        }
    }

    /// Island `i`: its population from the Halton points `i * population ..` (free inputs at
    /// random in all members but the first), evolved, its
    /// best `polish` members solved locally (where fewer could be assembled, the first members
    /// that could not stand for the missing ones, refused with their reasons).
    fn island<K>(
        &self,
        problem: &ProblemOf<K>,
        island: usize,
        de: &DeConfig,
        batch: impl Fn(&[Vec<f64>]) -> Vec<f64>,
    ) -> Solved
    where
        K: SensKernel,
    {
        let (lo, hi) = problem.bounds();
        let first = island.saturating_mul(de.population);
        let mut rng = IslandRng::new(self.seed, island);
        // Free inputs: evenly spaced in the first member, drawn at random (in order) in the
        // others, so that the differences of members move them too.
        let (nv, nt) = (problem.vars.len(), problem.free_inputs());
        let mut pop: Vec<Vec<f64>> = (0..de.population)
            .map(|k| {
                let mut z = self.start(problem, first.saturating_add(k));
                if k > 0 && nt > 0 {
                    for j in nv..nv + nt {
                        z[j] = lo[j] + (hi[j] - lo[j]) * rng.uniform();
                    }
                    z[nv..nv + nt].sort_by(f64::total_cmp);
                }
                z
            })
            .collect();
        let mut fit = batch(&pop);
        // The early stop is the local solve's convergence test on the best member: its residuals
        // within `tol` of the targets' size, or within their rounding (judged on its Jacobian, an
        // evaluation more, once per best member). `tol` alone, with no floor, was never met by
        // an exact fit 1e4 from the origin, whose residuals are the rounding of values of that
        // size: the evolution ran every generation there.
        let row_weight = problem.row_weights();
        let (mut judged, mut judgements) = (None::<Vec<f64>>, 0usize);
        let done = |pop: &[Vec<f64>], fit: &[f64]| {
            let finite = (0..fit.len()).filter(|&k| fit[k].is_finite());
            let Some(k) = finite.min_by(|&a, &b| fit[a].total_cmp(&fit[b])) else { return false };
            if problem.within_tol(fit[k], self.local.tol) {
                return true;
            }
            if judged.as_ref() == Some(&pop[k]) {
                return false;
            }
            judged = Some(pop[k].clone());
            judgements += 1;
            problem.evaluate(&pop[k], None).is_ok_and(|e| problem.within_rounding(fit[k], &e, &pop[k], &row_weight))
        };
        let evolved = evolve(&mut pop, &mut fit, (&lo, &hi), de, &mut rng, done, batch);
        let evaluations = de.population + evolved + judgements;
        let chosen = best(&fit, de.polish);
        let mut found: Vec<Result<Candidate, Refused>> =
            chosen.iter().map(|&k| self.solve(problem, pop[k].clone(), Origin::Evolution, island)).collect();
        let missing = de.polish.saturating_sub(found.len());
        let unassembled: Vec<usize> = (0..pop.len()).filter(|&k| !fit[k].is_finite()).take(missing).collect();
        // Each evaluated again for its reason: one evaluation more apiece.
        let evaluations = evaluations + unassembled.len();
        found.extend(unassembled.into_iter().map(|k| Err(Self::refusal(problem, &pop[k], island))));
        (found, evaluations)
    }

    /// Why the member `z` of island `island`, whose residual norm the evolution found not
    /// finite, is refused: the error evaluating it, or its norm not finite.
    fn refusal<K>(problem: &ProblemOf<K>, z: &[f64], island: usize) -> Refused
    where
        K: SensKernel,
    {
        let point = z.to_vec();
        match problem.norm_at(z) {
            Err(e) => Refused::one(&e, Origin::Evolution, island, point),
            Ok(norm) => Refused {
                kind: RefusalKind::NotFinite,
                count: 1,
                origin: Origin::Evolution,
                start: island,
                point,
                message: format!("the residual norm is {norm}"),
            },
        }
    }

    /// The residual norm at `z`, `inf` where the design cannot be assembled at every target:
    /// the objective of the evolution.
    fn norm<K>(problem: &ProblemOf<K>, z: &[f64]) -> f64
    where
        K: SensKernel,
    {
        // A NaN (a position solve that returned one) counts as unassembled too.
        problem.norm_at(z).ok().filter(|v| !v.is_nan()).unwrap_or(f64::INFINITY)
    }

    /// Runs the seeds, then the starts (or islands), one after the other.
    pub fn run<K>(&self, problem: &ProblemOf<K>) -> Result<SynthesisReport, SynthesisError>
    where
        K: SensKernel,
    {
        self.run_with_progress(problem, |_, _| {})
    }

    /// [`Search::run`], calling `progress(done, total)` after each seed, start or island (e.g.
    /// to drive a progress bar on a long search).
    pub fn run_with_progress<K>(
        &self,
        problem: &ProblemOf<K>,
        mut progress: impl FnMut(usize, usize),
    ) -> Result<SynthesisReport, SynthesisError>
    where
        K: SensKernel,
    {
        self.validate_for(problem)?;
        let total = self.job_count();
        let batch = |zs: &[Vec<f64>]| zs.iter().map(|z| Self::norm(problem, z)).collect();
        let keys = self.holds_keys();
        let mut found = self.results_room(total)?;
        found.extend((0..total).map(|k| {
            let f = Self::hold(self.job(problem, self.job_at(k), batch), keys);
            progress(k + 1, total);
            f
        }));
        self.report(problem, found)
    }

    /// [`Search::run`] on all cores (rayon's global pool, or the pool it is called in): the
    /// same report, candidates in the same order. Seeds, starts and islands run in parallel,
    /// and each generation's trial vectors of an island are evaluated in parallel and selected
    /// in member order.
    #[cfg(feature = "rayon")]
    pub fn par_run<K>(&self, problem: &ProblemOf<K>) -> Result<SynthesisReport, SynthesisError>
    where
        K: SensKernel,
        ProblemOf<K>: Sync,
    {
        self.par_run_with_progress(problem, |_, _| {})
    }

    /// [`Search::par_run`], calling `progress(done, total)` from the worker threads after each
    /// seed, start or island (`done` counts those finished, in whatever order they finish).
    /// Each `done` from 1 to `total` is passed once, but two threads' calls can arrive in
    /// either order (`6` before `5`): a progress bar should show the largest `done` seen.
    #[cfg(feature = "rayon")]
    pub fn par_run_with_progress<K>(
        &self,
        problem: &ProblemOf<K>,
        progress: impl Fn(usize, usize) + Sync,
    ) -> Result<SynthesisReport, SynthesisError>
    where
        K: SensKernel,
        ProblemOf<K>: Sync,
    {
        use rayon::prelude::*;
        use std::sync::atomic::{AtomicUsize, Ordering};
        self.validate_for(problem)?;
        let (total, done) = (self.job_count(), AtomicUsize::new(0));
        // `collect` keeps the order of the indices, whatever order they finish in.
        let batch = |zs: &[Vec<f64>]| zs.par_iter().map(|z| Self::norm(problem, z)).collect();
        let keys = self.holds_keys();
        let mut found = self.results_room(total)?;
        found.par_extend((0..total).into_par_iter().map(|k| {
            let f = Self::hold(self.job(problem, self.job_at(k), batch), keys);
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            f
        }));
        self.report(problem, found)
    }

    /// An empty vector with room for the results of `total` jobs, taken before the first runs:
    /// a search of more starts than memory can hold the results of is refused with an error,
    /// where the allocator would abort the program. (The size check of [`Search::validate`]
    /// bounds what a vector can address; this, what the system gives.)
    fn results_room(&self, total: usize) -> Result<Vec<Found>, SynthesisError> {
        let mut found = Vec::new();
        found.try_reserve_exact(total).map_err(|_| {
            SynthesisError::InvalidConfig(format!(
                "starts {:?}: {} starts, more than memory holds the results of ({} bytes a start at least)",
                self.starts,
                self.starts.len(),
                std::mem::size_of::<Found>()
            ))
        })?;
        Ok(found)
    }

    /// Whether this search holds its Halton starts' candidates as keys until its report (see
    /// [`Held`]): a search of many starts, many more than it keeps.
    fn holds_keys(&self) -> bool {
        self.starts.len() > KEYS_FROM.max(self.keep.saturating_mul(64))
    }

    /// A job's candidates as the search holds them: as keys where `keys` is set (see [`Held`]).
    fn hold((candidates, evaluations): Solved, keys: bool) -> Found {
        let held = candidates.into_iter().map(|c| c.map(|c| Held::of(c, keys)).map_err(|r| HeldRefusal::of(r, keys)));
        (held.collect(), evaluations)
    }

    /// Counts, ranks and removes duplicates (in job order, so that the result does not depend
    /// on how the jobs were run); the starts kept that were held as keys are solved again for
    /// their whole candidates.
    fn report<K>(&self, problem: &ProblemOf<K>, found: Vec<Found>) -> Result<SynthesisReport, SynthesisError>
    where
        K: SensKernel,
    {
        let mut report = SynthesisReport {
            variables: problem.names.clone(),
            bounds: problem.vars.iter().map(|b| (b.lo, b.hi)).collect(),
            candidates: Vec::new(),
            starts: self.starts.clone(),
            seeds: if self.starts.start == 0 { self.seeds.len() } else { 0 },
            unassembled: 0,
            refused: Vec::new(),
            converged: 0,
            step_tolerance: 0,
            valid: 0,
            rejected: Rejections::default(),
            evaluations: 0,
            four_bar: problem.checks.four_bar.is_some(),
        };
        let mut all = Vec::new();
        // Per kind, its count and its first refusal (jobs in order: seeds, then by index).
        let mut refused: Vec<(usize, HeldRefusal)> = Vec::new();
        for (candidates, evaluations) in found {
            report.evaluations += evaluations;
            for c in candidates {
                let c = match c {
                    Ok(c) => c,
                    Err(r) => {
                        report.unassembled += 1;
                        match refused.iter_mut().find(|(_, first)| first.kind() == r.kind()) {
                            Some((count, _)) => *count += 1,
                            None => refused.push((1, r)),
                        }
                        continue;
                    }
                };
                let (local_evaluations, stop) = c.local();
                report.evaluations += local_evaluations;
                report.converged += usize::from(stop == OptimizerStop::Converged);
                report.step_tolerance += usize::from(stop == OptimizerStop::StepTolerance);
                match c.first_defect() {
                    None => report.valid += 1,
                    Some(d) => report.rejected.count(d),
                }
                all.push(c);
            }
        }
        let kept = distinct(all, &report.bounds, self.distinct, self.keep);
        report.candidates = kept
            .into_iter()
            .map(|h| match h {
                Held::Whole(c) => Ok(*c),
                Held::Key(k) => {
                    self.solve(problem, self.start(problem, k.start), Origin::Halton, k.start).map_err(|_| {
                        SynthesisError::Mismatch(format!(
                            "start {}, solved again for the report, gave no design where it gave one before: the \
                             problem's solves are not deterministic",
                            k.start
                        ))
                    })
                }
            })
            .collect::<Result<_, _>>()?;
        for (count, first) in refused {
            Refused::add(&mut report.refused, Refused { count, ..self.first_refused(problem, first)? });
        }
        Ok(report)
    }

    /// A kind's first refusal whole: a Halton start held as its kind solved again (refused the
    /// same way: a start depends on its index alone).
    fn first_refused<K>(&self, problem: &ProblemOf<K>, first: HeldRefusal) -> Result<Refused, SynthesisError>
    where
        K: SensKernel,
    {
        match first {
            HeldRefusal::Whole(r) => Ok(*r),
            HeldRefusal::Key { kind, start } => {
                match self.solve(problem, self.start(problem, start), Origin::Halton, start) {
                    Err(r) if r.kind == kind => Ok(r),
                    _ => Err(SynthesisError::Mismatch(format!(
                        "start {start}, solved again for the report, was not refused as it was before: the problem's \
                     solves are not deterministic"
                    ))),
                }
            }
        }
    }

    /// Runs the local solve from `z0` (the search's unknowns, see [`ProblemOf`]; clamped into
    /// their bounds) and verifies its result: e.g. from a classical closed-form design, or to
    /// polish a candidate with other settings. An error where the design cannot be assembled
    /// at every target at `z0`. Of the search's settings it reads (and checks) only
    /// [`Search::local`].
    pub fn refine<K>(&self, problem: &ProblemOf<K>, z0: &[f64]) -> Result<Candidate, SynthesisError>
    where
        K: SensKernel,
    {
        self.validate_local()?;
        problem.check_point(z0)?;
        let (z, e, report) = problem.local(Self::clamped(problem, z0), &self.local)?;
        Ok(problem.verify(Origin::Refine, usize::MAX, z, e, report)?)
    }
}

impl SynthesisReport {
    /// The reports of two parts of one search (disjoint start ranges of the same problem,
    /// `search` the settings both ran with but for the range) as one: ranked again, duplicates
    /// removed, cut to [`Search::keep`].
    ///
    /// The counts, the start range and the best candidate are always the whole search's. The
    /// list of candidates can differ from it: a duplicate is one within
    /// [`Search::distinct`] of a candidate ranked before it, and that does not chain (A near
    /// B and B near C, A not near C): where B and C ran in one part and A in the other, that
    /// part kept B alone, so the merge keeps A alone where the whole keeps A and C. Run the
    /// parts with `distinct` 0 and every candidate kept (`with_keep(usize::MAX)`), then merge
    /// with the search's own settings: that gives the whole search's report exactly.
    pub fn merge(mut self, other: SynthesisReport, search: &Search) -> SynthesisReport {
        let mut all = std::mem::take(&mut self.candidates);
        all.extend(other.candidates);
        self.candidates = distinct(all, &self.bounds, search.distinct, search.keep);
        self.starts = self.starts.start.min(other.starts.start)..self.starts.end.max(other.starts.end);
        self.seeds += other.seeds;
        self.unassembled += other.unassembled;
        for r in other.refused {
            Refused::add(&mut self.refused, r);
        }
        self.converged += other.converged;
        self.step_tolerance += other.step_tolerance;
        self.valid += other.valid;
        self.rejected.add(&other.rejected);
        self.evaluations += other.evaluations;
        // Parts of one problem agree; either names the four-bar where one does.
        self.four_bar |= other.four_bar;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthesis::LocalReport;

    /// A valid candidate of one design variable in `0 ..= 1`, ranked by `rms`.
    fn candidate(start: usize, value: f64, rms: f64) -> Candidate {
        Candidate {
            start,
            origin: Origin::Halton,
            values: vec![value],
            params: vec![value],
            inputs: vec![],
            placement: None,
            positions: vec![],
            errors: vec![rms],
            max_error: rms,
            rms_error: rms,
            defects: vec![],
            min_transmission: None,
            four_bar: None,
            local: LocalReport { evaluations: 1, iterations: 1, stop: OptimizerStop::Converged, residual: rms },
        }
    }

    fn report(starts: Range<usize>, candidates: Vec<Candidate>, search: &Search) -> SynthesisReport {
        let bounds = vec![(0.0, 1.0)];
        let candidates = distinct(candidates, &bounds, search.distinct, search.keep);
        SynthesisReport { candidates, starts, ..SynthesisReport::new(vec!["a".into()], bounds) }
    }

    /// A near B, B near C, A not near C: the whole keeps A and C (B is A's duplicate), the part
    /// holding B and C keeps B alone (C is B's), and their merge A alone. Parts that drop no
    /// candidate (`distinct` 0, every one kept) merge into the whole's list.
    #[test]
    fn a_merge_of_parts_that_dropped_duplicates_can_miss_one_the_whole_keeps() {
        let search = Search::default().with_distinct(0.15).with_keep(10);
        let (a, b, c) = (candidate(0, 0.0, 1.0), candidate(1, 0.1, 2.0), candidate(2, 0.2, 3.0));
        let whole = report(0..3, vec![a.clone(), b.clone(), c.clone()], &search);
        assert_eq!(whole.candidates, [a.clone(), c.clone()]);

        let first = report(0..1, vec![a.clone()], &search);
        let second = report(1..3, vec![b.clone(), c.clone()], &search);
        let merged = first.merge(second, &search);
        assert_eq!(merged.candidates, std::slice::from_ref(&a));
        assert_eq!((merged.best(), merged.starts.clone()), (whole.best(), whole.starts.clone()));

        let all = search.clone().with_distinct(0.0).with_keep(usize::MAX);
        let first = report(0..1, vec![a], &all);
        let second = report(1..3, vec![b, c], &all);
        assert_eq!(first.merge(second, &search), whole);
    }
}
