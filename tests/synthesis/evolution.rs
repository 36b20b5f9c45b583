//! Differential evolution as the global stage: a known answer (dimensions hidden in closed-form
//! samples, found again), the same report on one thread or many, a search split by island range
//! merging into the whole, and bad settings refused with a typed error.

use super::known_answers::{FOUR_BAR_NAMES, check_recovered, design};
use super::mechanisms::{CouplerFourBar, FOUR_BAR, coupler_point};
use kinloop::synthesis::{DeConfig, Design, Global, LocalConfig, Origin, Problem, Search, SynthesisError, Task};

/// Five coupler points of the known four-bar at prescribed crank angles.
fn timed_path(spread: f64) -> Problem<CouplerFourBar, 2, 1, 3, 6> {
    let phis: Vec<f64> = (0..5).map(|k| 0.3 + 1.1 * k as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(FOUR_BAR, p)).collect();
    let task = Task::path("p", targets).timed(phis);
    Problem::new(CouplerFourBar::default(), &design(&FOUR_BAR_NAMES, &FOUR_BAR, spread), &task).unwrap()
}

fn de(population: usize, generations: usize, polish: usize) -> Global {
    Global::DifferentialEvolution(
        DeConfig::default().with_population(population).with_generations(generations).with_polish(polish),
    )
}

#[test]
fn the_evolution_alone_approaches_the_known_four_bar() {
    // Local solves of a single evaluation (no step): the candidate is the evolution's best
    // member as it is. Over 60 generations its residual falls far below the best of its
    // initial Halton points' (measured with seed 2: 0.79 at generation 0, 0.06 at 40, 0.005 at
    // 100), and it nears the truth.
    let problem = timed_path(0.4);
    let best = |generations| {
        let search = Search::default()
            .with_global(de(16, generations, 1))
            .with_local(LocalConfig::default().with_max_evaluations(1))
            .with_starts(0..1)
            .with_seed(2);
        search.run(&problem).unwrap().candidates[0].clone()
    };
    let (initial, evolved) = (best(0), best(60));
    assert!(evolved.local.residual < 0.05 * initial.local.residual, "{:?} vs {:?}", evolved.local, initial.local);
    for (got, want) in evolved.values.iter().zip(FOUR_BAR) {
        assert!((got - want).abs() < 0.1 * want.abs(), "{:?}", evolved.values);
    }
}

#[test]
fn differential_evolution_finds_a_known_four_bar() {
    // One island of 16 members over a box of +-40 % around the truth, 30 generations, its best
    // two members polished by Levenberg-Marquardt.
    let problem = timed_path(0.4);
    let search = Search::default().with_global(de(16, 30, 2)).with_starts(0..1).with_seed(2);
    let report = search.run(&problem).unwrap();
    check_recovered(&report, &FOUR_BAR, 1.0);
    let best = report.best().unwrap();
    assert_eq!((best.origin, best.start), (Origin::Evolution, 0));
    // The evolution's evaluations are counted beside the local solves': at least the initial
    // population.
    assert!(report.evaluations >= 16 + best.local.evaluations, "{}", report.evaluations);
    assert_eq!(report.unassembled + report.valid + report.rejected.total(), 2, "polish = 2 per island");
}

/// An untimed path in a wide box, local solves cut short: many different candidates to order.
fn wide() -> (Problem<CouplerFourBar, 2, 1, 3, 6>, Search) {
    let phis: Vec<f64> = (0..7).map(|k| 0.2 + 0.8 * k as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(FOUR_BAR, p)).collect();
    let task = Task::path("p", targets).untimed(0.0, std::f64::consts::TAU);
    let design = FOUR_BAR_NAMES.iter().zip(FOUR_BAR).fold(Design::new(), |d, (n, v)| d.var(*n, 0.5 * v, 1.5 * v));
    let problem = Problem::new(CouplerFourBar::default(), &design, &task).unwrap();
    let mut seed = FOUR_BAR.map(|v| 1.1 * v).to_vec();
    seed.extend(phis.iter().map(|p| p + 0.05));
    let search = Search::default()
        .with_seed(5)
        .with_global(de(8, 4, 2))
        .with_seeds(vec![seed])
        .with_local(LocalConfig::default().with_max_evaluations(6));
    (problem, search)
}

#[test]
fn serial_and_parallel_evolutions_agree() {
    let (problem, search) = wide();
    let search = search.with_starts(0..3);
    let serial = search.run(&problem).unwrap();
    let parallel = search.par_run(&problem).unwrap();
    assert_eq!(serial, parallel);
    assert_eq!(serial.seeds, 1);
    // Every local solve is accounted for: one seed and two members of each of three islands.
    assert_eq!(serial.unassembled + serial.valid + serial.rejected.total(), 1 + 3 * 2);
    assert!(serial.candidates.len() > 1, "{}", serial.candidates.len());
    assert!(serial.candidates.iter().any(|c| c.origin == Origin::Seed));
    assert_ne!(search.with_seed(6).run(&problem).unwrap(), serial, "another seed, other islands");
}

#[test]
fn an_evolution_split_by_island_merges_into_the_whole() {
    let (problem, search) = wide();
    let search = search.with_keep(4);
    let whole = search.clone().with_starts(0..3).run(&problem).unwrap();
    let first = search.clone().with_starts(0..1).run(&problem).unwrap();
    let second = search.clone().with_starts(1..3).run(&problem).unwrap();
    // The seeds run with the part that begins at island 0 only.
    assert_eq!((first.seeds, second.seeds), (1, 0));
    assert_eq!(first.merge(second, &search), whole);
}

#[test]
fn bad_evolution_settings_are_refused() {
    let problem = timed_path(0.3);
    let bad = [
        (DeConfig::default().with_population(3), "de.population"),
        (DeConfig::default().with_f(0.0), "de.f"),
        (DeConfig::default().with_f(2.5), "de.f"),
        (DeConfig::default().with_f(f64::NAN), "de.f"),
        (DeConfig::default().with_cr(-0.1), "de.cr"),
        (DeConfig::default().with_cr(1.5), "de.cr"),
        (DeConfig::default().with_polish(0), "de.polish"),
        (DeConfig::default().with_population(8).with_polish(9), "de.polish"),
        // A population no memory holds (the largest `usize` panicked on its capacity), and runs
        // of more evaluations than any finishes.
        (DeConfig::default().with_population(usize::MAX), "de.population"),
        (DeConfig::default().with_population(DeConfig::MAX_POPULATION + 1), "de.population"),
        (DeConfig::default().with_generations(usize::MAX), "de.generations"),
        (
            DeConfig::default().with_population(1000).with_generations(DeConfig::MAX_EVALUATIONS / 1000),
            "de.generations",
        ),
    ];
    for (cfg, field) in bad {
        let search = Search::default().with_global(Global::DifferentialEvolution(cfg)).with_starts(0..1);
        let e = search.run(&problem).unwrap_err();
        assert!(matches!(&e, SynthesisError::InvalidConfig(m) if m.starts_with(field)), "{cfg:?}: {e}");
        assert_eq!(search.par_run(&problem).unwrap_err(), e);
    }
    // A seed that is no point of the problem's unknowns.
    let e = Search::default().with_seeds(vec![vec![1.0; 5]]).run(&problem).unwrap_err();
    assert!(matches!(&e, SynthesisError::Mismatch(m) if m.contains("seed 0")), "{e}");
    let e = Search::default().with_seeds(vec![vec![f64::NAN; 6]]).run(&problem).unwrap_err();
    assert!(matches!(&e, SynthesisError::InvalidConfig(m) if m.contains("seed 0") && m.contains("not finite")), "{e}");
}

/// The evolution stops early where its best member meets the targets to rounding, wherever the
/// mechanism stands: five timed points of a four-bar whose crank pivot is `(s, s)`, every design
/// variable held at the truth (bounds of one value), so that every member of the population is
/// the exact design from its first generation. Its residuals are then the rounding of values of
/// magnitude `s`, about `2e-16 s` each, which passes `tol` (`1e-14`) times the targets' spread
/// (about 2) from `s = 1e2` on: the early stop compared the residual norm with that alone, and at
/// `s = 1e4` and `1e6` the evolution ran all its 50 generations (`8 * 51 = 408` evaluations)
/// where at `s = 0` it stopped at once. It stops as the local solve's convergence test does, on
/// the residuals' root mean square within `tol` of the spread or within a few roundings of the
/// magnitudes they are computed from: the initial population's 8 evaluations and at most one
/// more, the Jacobian of its best member that judges the latter.
#[test]
fn the_evolution_stops_at_an_exact_fit_far_from_the_origin() {
    use super::mechanisms::PlacedFourBar;
    let phis: Vec<f64> = (0..5).map(|k| 0.3 + 1.1 * k as f64).collect();
    let truth = FOUR_BAR;
    for s in [0.0, 1e4, 1e6] {
        let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(truth, p).map(|v| v + s)).collect();
        let task = Task::path("p", targets).timed(phis.clone());
        let design =
            ["a", "b", "c", "g", "e", "alpha"].iter().zip(truth).fold(Design::new(), |d, (n, v)| d.var(*n, v, v));
        let m = PlacedFourBar { ax: s, ay: s, ..PlacedFourBar::default() };
        let problem = Problem::new(m, &design, &task).unwrap();
        let report = Search::default().with_global(de(8, 50, 1)).with_starts(0..1).run(&problem).unwrap();
        let best = report.best().unwrap_or_else(|| panic!("at {s:e}: {report:#?}"));
        assert!(best.max_error <= 1e-13 * s.max(1.0), "at {s:e}: {best:?}");
        // The evaluations of the evolution: the report's less the polishing local solve's.
        let evolution = report.evaluations - best.local.evaluations;
        assert!((8..=9).contains(&evolution), "at {s:e}: {evolution} evaluations in the evolution");
    }
}
