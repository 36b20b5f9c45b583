//! The search is deterministic: the same report on one thread or many, and a search split by
//! start index into parts gives, merged, the report of the whole.

use super::mechanisms::{CouplerFourBar, FOUR_BAR, coupler_point};
use kinloop::synthesis::{Design, LocalConfig, Problem, Search, Task};

/// Local solves cut short, so that the starts end in many different candidates to order.
fn search() -> Search {
    Search::default().with_seed(3).with_local(LocalConfig::default().with_max_evaluations(6))
}

/// An untimed path problem in a wide box.
fn problem() -> Problem<CouplerFourBar, 2, 1, 3, 6> {
    let phis: Vec<f64> = (0..7).map(|k| 0.2 + 0.8 * k as f64).collect();
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(FOUR_BAR, p)).collect();
    let task = Task::path("p", targets).untimed(0.0, std::f64::consts::TAU);
    let design = ["a", "b", "c", "d", "e", "alpha"]
        .iter()
        .zip(FOUR_BAR)
        .fold(Design::new(), |d, (n, v)| d.var(*n, 0.5 * v, 1.5 * v));
    Problem::new(CouplerFourBar::default(), &design, &task).unwrap()
}

#[test]
fn serial_and_parallel_searches_agree() {
    let problem = problem();
    let search = search().with_starts(0..24);
    let serial = search.run(&problem).unwrap();
    // On rayon's global pool (the tests build the runtime with `rayon`: see `Cargo.toml`).
    let parallel = search.par_run(&problem).unwrap();
    assert_eq!(serial, parallel);
    // Every start is accounted for: not assembled, valid, or rejected by its first defect.
    assert_eq!(serial.unassembled + serial.valid + serial.rejected.total(), 24);
    assert!(serial.candidates.len() > 1, "several distinct candidates to order: {}", serial.candidates.len());
    // Another seed, other starts.
    assert_ne!(search.with_seed(4).run(&problem).unwrap(), serial);
}

#[test]
fn a_split_search_merges_into_the_whole() {
    let problem = problem();
    let search = search().with_keep(4);
    let whole = search.clone().with_starts(0..24).run(&problem).unwrap();
    let first = search.clone().with_starts(0..10).run(&problem).unwrap();
    let second = search.clone().with_starts(10..24).run(&problem).unwrap();
    assert_eq!(first.merge(second, &search), whole);
}

/// A search of many more starts than it keeps holds its candidates as keys (their values,
/// error, validity, first defect and evaluations; see the search's `held` module) and solves
/// again the starts it keeps: its report is the one of a search that held every candidate
/// whole. That one is made here by the exact recipe of `SynthesisReport::merge`: parts with
/// `distinct` 0 keeping every candidate (which hold them whole), merged with the search's own
/// settings.
#[test]
fn a_search_that_holds_keys_reports_what_one_holding_whole_candidates_does() {
    let problem = problem();
    let search = search().with_keep(4).with_distinct(1e-3);
    let starts = 4100;
    let held_as_keys = search.clone().with_starts(0..starts).par_run(&problem).unwrap();
    let every = search.clone().with_distinct(0.0).with_keep(usize::MAX);
    let first = every.clone().with_starts(0..starts / 2).par_run(&problem).unwrap();
    let second = every.clone().with_starts(starts / 2..starts).par_run(&problem).unwrap();
    let whole = first.merge(second, &search);
    assert_eq!(held_as_keys, whole);
    assert_eq!(held_as_keys.candidates.len(), 4);
    assert_eq!(held_as_keys.unassembled + held_as_keys.valid + held_as_keys.rejected.total(), starts);
}
