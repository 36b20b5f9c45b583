//! Differential evolution (Storn and Price's DE/rand/1/bin) as the global stage of a memetic
//! search: a population evolves over the box of the search's unknowns on the residual norm,
//! then its best members are polished by the local solve and verified like every candidate.
//!
//! A search with this strategy runs *islands*: island `i` of [`Search::starts`](super::Search::starts) is one
//! population, started from the Halton points `i * population .. (i + 1) * population` and
//! evolved with random numbers drawn from the seed and `i` only. So, like the Halton multistart,
//! a search splits by island range over processes and merges, and a parallel run (the
//! population's trial vectors evaluated on all cores, selected in index order) gives the report
//! of a serial one.

use super::error::SynthesisError;
use super::halton::{splitmix64, unit};

/// The global stage of a [`Search`](super::Search): where its local solves start from.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Global {
    /// One local solve from each point of a shifted Halton sequence over the box (each start
    /// an index of [`Search::starts`](super::Search::starts)).
    #[default]
    Halton,
    /// Differential evolution on the residual norm, its best members polished by the local
    /// solve (each index of [`Search::starts`](super::Search::starts) one island: one population).
    DifferentialEvolution(DeConfig),
}

/// Settings of differential evolution (DE/rand/1/bin): every generation, each member `x_k` of
/// the population meets a trial vector whose components are, with probability `cr` (and at
/// least one), `x_r1 + f (x_r2 - x_r3)` of three other members drawn at random, and its own
/// otherwise; the trial replaces the member when its residual norm is not larger.
///
/// ```
/// use kinloop_runtime::synthesis::{DeConfig, Global, Search};
/// let de = DeConfig::default().with_population(24).with_generations(40).with_f(0.6).with_cr(0.9);
/// let search = Search::default().with_global(Global::DifferentialEvolution(de)).with_starts(0..2);
/// assert_eq!(search.starts, 0..2); // two islands
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct DeConfig {
    /// Members of the population (at least 4: a member and three others; at most
    /// [`DeConfig::MAX_POPULATION`]; default `32`).
    pub population: usize,
    /// Generations (default `40`; `0` only polishes the best of the Halton points). The
    /// evolution stops early when its best member meets the local solve's convergence test
    /// (see [`LocalConfig::tol`](super::LocalConfig::tol): its residuals' root mean square within
    /// `tol` of the targets' size, or within their rounding, judged on that member's Jacobian,
    /// one evaluation more each time the best member changes). With the population, at most
    /// [`DeConfig::MAX_EVALUATIONS`] evaluations.
    pub generations: usize,
    /// The differential weight, in `(0, 2]` (default `0.7`).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub f: f64,
    /// The crossover probability, in `[0, 1]` (default `0.9`).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub cr: f64,
    /// How many of the best members (lowest residual norm, ties by index) the local solve
    /// polishes, each one candidate (at least 1, at most the population; default `3`).
    pub polish: usize,
}

impl Default for DeConfig {
    fn default() -> Self {
        DeConfig { population: 32, generations: 40, f: 0.7, cr: 0.9, polish: 3 }
    }
}

impl DeConfig {
    /// The most members of a population (`10^6`): each holds a point of the search's unknowns
    /// and the whole population is evaluated at once.
    pub const MAX_POPULATION: usize = 1_000_000;
    /// The most evaluations an island may be asked for, `population * (generations + 1)`
    /// (`10^9`: hours of position solves); more is refused rather than run practically forever.
    pub const MAX_EVALUATIONS: usize = 1_000_000_000;

    /// Sets [`DeConfig::population`].
    pub fn with_population(mut self, population: usize) -> Self {
        self.population = population;
        self
    }
    /// Sets [`DeConfig::generations`].
    pub fn with_generations(mut self, generations: usize) -> Self {
        self.generations = generations;
        self
    }
    /// Sets [`DeConfig::f`].
    pub fn with_f(mut self, f: f64) -> Self {
        self.f = f;
        self
    }
    /// Sets [`DeConfig::cr`].
    pub fn with_cr(mut self, cr: f64) -> Self {
        self.cr = cr;
        self
    }
    /// Sets [`DeConfig::polish`].
    pub fn with_polish(mut self, polish: usize) -> Self {
        self.polish = polish;
        self
    }

    /// A field out of its range, as an error naming it.
    pub(crate) fn validate(&self) -> Result<(), SynthesisError> {
        let bad = |field: &str, why: &str| Err(SynthesisError::InvalidConfig(format!("de.{field} {why}")));
        if self.population < 4 {
            return bad("population", &format!("is {}: DE/rand/1 needs at least 4 members", self.population));
        }
        if self.population > Self::MAX_POPULATION {
            return bad(
                "population",
                &format!("is {}: at most {} (`DeConfig::MAX_POPULATION`)", self.population, Self::MAX_POPULATION),
            );
        }
        let evaluations = self.population.saturating_mul(self.generations.saturating_add(1));
        if evaluations > Self::MAX_EVALUATIONS {
            return bad(
                "generations",
                &format!(
                    "is {}: {} members over it make more than the {} evaluations an island makes at most \
                     (`DeConfig::MAX_EVALUATIONS`)",
                    self.generations,
                    self.population,
                    Self::MAX_EVALUATIONS
                ),
            );
        }
        if !(self.f.is_finite() && self.f > 0.0 && self.f <= 2.0) {
            return bad("f", &format!("is {}: the differential weight must lie in (0, 2]", self.f));
        }
        if !(self.cr.is_finite() && (0.0..=1.0).contains(&self.cr)) {
            return bad("cr", &format!("is {}: the crossover probability must lie in [0, 1]", self.cr));
        }
        if self.polish == 0 || self.polish > self.population {
            return bad("polish", &format!("is {}: it must lie in 1..={}", self.polish, self.population));
        }
        Ok(())
    }
}

/// The random numbers of one island: SplitMix64 from a state drawn from the seed and the
/// island's index (so that islands are independent and addressable).
pub(crate) struct IslandRng(u64);

impl IslandRng {
    pub(crate) fn new(seed: u64, island: usize) -> Self {
        let mut s = seed ^ 0xD1B5_4A32_D192_ED03u64.wrapping_mul(island as u64 + 1);
        IslandRng(splitmix64(&mut s))
    }
    /// Uniform in `[0, 1)`.
    pub(crate) fn uniform(&mut self) -> f64 {
        unit(splitmix64(&mut self.0))
    }
    /// Uniform in `0..n`.
    fn below(&mut self, n: usize) -> usize {
        ((self.uniform() * n as f64) as usize).min(n - 1)
    }
}

/// The trial vectors of one generation (in member order), DE/rand/1/bin: a mutant component
/// outside the box is put at random between the bound it crossed and the member's value (the
/// member is inside, so the trial is too).
pub(crate) fn trials(pop: &[Vec<f64>], lo: &[f64], hi: &[f64], cfg: &DeConfig, rng: &mut IslandRng) -> Vec<Vec<f64>> {
    let np = pop.len();
    let d = lo.len();
    (0..np)
        .map(|k| {
            let mut pick = |taken: &[usize]| loop {
                let r = rng.below(np);
                if r != k && !taken.contains(&r) {
                    break r;
                }
            };
            let r1 = pick(&[]);
            let r2 = pick(&[r1]);
            let r3 = pick(&[r1, r2]);
            let jrand = rng.below(d.max(1));
            (0..d)
                .map(|j| {
                    let cross = rng.uniform() < cfg.cr || j == jrand;
                    if !cross {
                        return pop[k][j];
                    }
                    let v = pop[r1][j] + cfg.f * (pop[r2][j] - pop[r3][j]);
                    let u = rng.uniform();
                    if v < lo[j] {
                        lo[j] + u * (pop[k][j] - lo[j])
                    } else if v > hi[j] {
                        hi[j] - u * (hi[j] - pop[k][j])
                    } else {
                        v
                    }
                })
                .collect()
        })
        .collect()
}

/// The evolution of one island: from the population `pop` (its residual norms `fit`, an
/// unassembled member `inf`), `generations` rounds of trials evaluated by `batch` and selected
/// in member order; stops early, before a generation, when `done(pop, fit)` says the population
/// is good enough. Returns the number of evaluations made by `batch`.
pub(crate) fn evolve(
    pop: &mut [Vec<f64>],
    fit: &mut [f64],
    bounds: (&[f64], &[f64]),
    cfg: &DeConfig,
    rng: &mut IslandRng,
    mut done: impl FnMut(&[Vec<f64>], &[f64]) -> bool,
    batch: impl Fn(&[Vec<f64>]) -> Vec<f64>,
) -> usize {
    let mut evaluations = 0;
    for _ in 0..cfg.generations {
        if done(pop, fit) {
            break;
        }
        let t = trials(pop, bounds.0, bounds.1, cfg, rng);
        let ft = batch(&t);
        evaluations += t.len();
        for (k, (x, f)) in t.into_iter().zip(ft).enumerate() {
            // `<=` (not `<`): a trial as good moves the population across plateaus, and an
            // unassembled member (`inf`) is replaced by any trial.
            if f <= fit[k] || fit[k].is_nan() {
                pop[k] = x;
                fit[k] = f;
            }
        }
    }
    evaluations
}

/// The indices of the `n` best members with a finite norm, best first, ties by index.
pub(crate) fn best(fit: &[f64], n: usize) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..fit.len()).filter(|&k| fit[k].is_finite()).collect();
    idx.sort_by(|&a, &b| fit[a].total_cmp(&fit[b]).then(a.cmp(&b)));
    idx.truncate(n);
    idx
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's function in 2-D, minimum 0 at (1, 1): DE alone (no local solve) gets close,
    /// a check of the operators independent of any mechanism.
    #[test]
    fn de_minimises_rosenbrock() {
        let f = |z: &[f64]| (1.0 - z[0]).powi(2) + 100.0 * (z[1] - z[0] * z[0]).powi(2);
        let (lo, hi) = (vec![-2.0, -1.0], vec![2.0, 3.0]);
        let mut rng = IslandRng::new(5, 0);
        let mut pop: Vec<Vec<f64>> =
            (0..30).map(|_| (0..2).map(|j| lo[j] + (hi[j] - lo[j]) * rng.uniform()).collect()).collect();
        let mut fit: Vec<f64> = pop.iter().map(|z| f(z)).collect();
        let cfg = DeConfig::default().with_population(30).with_generations(300).with_f(0.7).with_cr(0.9);
        let exact = |_: &[Vec<f64>], fit: &[f64]| fit.iter().any(|&v| v <= 0.0);
        let n = evolve(&mut pop, &mut fit, (&lo, &hi), &cfg, &mut rng, exact, |b| b.iter().map(|z| f(z)).collect());
        // At most every generation; fewer where a member reaches 0 exactly (the early stop).
        assert!(n <= 30 * 300 && n % 30 == 0, "{n}");
        let k = best(&fit, 1)[0];
        assert!(fit[k] < 1e-10, "{} at {:?}", fit[k], pop[k]);
        assert!((pop[k][0] - 1.0).abs() < 1e-4 && (pop[k][1] - 1.0).abs() < 1e-4, "{:?}", pop[k]);
        for z in &pop {
            assert!((0..2).all(|j| (lo[j]..=hi[j]).contains(&z[j])), "kept inside the box: {z:?}");
        }
    }

    #[test]
    fn trials_differ_from_their_member_in_at_least_one_component() {
        let mut rng = IslandRng::new(1, 3);
        let pop: Vec<Vec<f64>> = (0..6).map(|k| vec![k as f64 * 0.1; 3]).collect();
        let cfg = DeConfig::default().with_cr(0.0);
        let t = trials(&pop, &[0.0; 3], &[1.0; 3], &cfg, &mut rng);
        for (x, p) in t.iter().zip(&pop) {
            assert_eq!(x.iter().zip(p).filter(|(a, b)| a != b).count(), 1, "cr = 0: exactly the forced one");
        }
    }

    #[test]
    fn islands_draw_other_numbers() {
        let (mut a, mut b) = (IslandRng::new(7, 0), IslandRng::new(7, 1));
        assert_ne!(a.uniform(), b.uniform());
        let (mut c, mut d) = (IslandRng::new(7, 1), IslandRng::new(7, 1));
        assert_eq!(c.uniform(), d.uniform());
    }
}
