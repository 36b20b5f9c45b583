//! Bad input: a clear error naming what is wrong, never a panic.

use super::mechanisms::CouplerFourBar;
use kinloop::synthesis::{Constraints, Design, LocalConfig, PlacementBounds, Problem, Search, SynthesisError, Task};

fn design() -> Design {
    Design::new().var("a", 0.5, 2.0).var("b", 1.0, 5.0)
}

fn three() -> Task {
    Task::path("p", [[1.0, 2.0], [1.5, 2.2], [2.0, 2.1]]).timed([0.0, 0.5, 1.0])
}

fn error(design: &Design, task: &Task) -> SynthesisError {
    Problem::new(CouplerFourBar::default(), design, task).unwrap_err()
}

#[test]
fn names_that_are_not_the_mechanism_s() {
    let e = error(&Design::new().var("length", 0.0, 1.0), &three());
    assert!(matches!(&e, SynthesisError::UnknownVariable { name, .. } if name == "length"), "{e:?}");
    assert!(e.to_string().contains("a, b, c, d, e, alpha"), "the message lists the parameters: {e}");
    let e = error(&design().var("a", 0.1, 0.2), &three());
    assert!(matches!(e, SynthesisError::DuplicateVariable { .. }), "{e:?}");
    let e = error(&Design::new(), &three());
    assert_eq!(e, SynthesisError::NoVariables);
    let task = Task::path("q", [[1.0, 2.0], [1.5, 2.2]]).timed([0.0, 0.5]);
    let e = error(&design(), &task);
    assert!(matches!(&e, SynthesisError::UnknownColumn { name, .. } if name == "q.x"), "{e:?}");
    let e = error(&design(), &Task::function("omega", [(0.0, 1.0), (1.0, 2.0)]));
    assert!(e.to_string().contains("beta, gamma, p.x, p.y, theta"), "{e}");
}

#[test]
fn bounds_that_hold_no_value() {
    // Finite bounds whose width is not (the starts between them would be infinite).
    for (lo, hi) in [(2.0, 1.0), (f64::NAN, 1.0), (0.0, f64::INFINITY), (-1e308, 1e308)] {
        let e = error(&Design::new().var("a", lo, hi), &three());
        assert!(matches!(&e, SynthesisError::BadBounds { name, .. } if name == "a"), "{e:?}");
    }
    // Written short, as every number of a message is (the bounds printed 309 digits each).
    let e = error(&Design::new().var("a", -1e308, 1e308), &three()).to_string();
    assert!(e.contains("[-1e308, 1e308]") && !e.contains("000000"), "{e}");
    let placement = PlacementBounds::translation((-1e308, 1e308), (-1.0, 1.0));
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]; 9]).timed([0.0; 9]).with_placement(placement));
    assert!(matches!(&e, SynthesisError::BadBounds { name, .. } if name == "dx"), "{e:?}");
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]; 3]).untimed(1.0, 0.0));
    assert!(matches!(&e, SynthesisError::BadBounds { name, .. } if name == "input"), "{e:?}");
    // Free inputs within a range of one value: several targets cannot be met in order along one
    // motion (every start would end in an order defect). One target can.
    let e = error(&design(), &Task::path("p", [[1.0, 2.0], [1.5, 2.2], [2.0, 2.1]]).untimed(1.0, 1.0));
    assert!(matches!(&e, SynthesisError::InvalidConfig(m) if m.contains("[1, 1]")), "{e:?}");
    let one = Problem::new(
        CouplerFourBar::default(),
        &Design::new().var("a", 0.5, 2.0),
        &Task::path("p", [[1.0, 2.0]]).untimed(1.0, 1.0),
    );
    assert!(one.is_ok(), "{one:?}");
    let placement = PlacementBounds::translation((0.0, 1.0), (0.0, 1.0)).with_scale((0.0, 2.0));
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]; 9]).timed([0.0; 9]).with_placement(placement));
    assert!(matches!(&e, SynthesisError::BadBounds { name, .. } if name == "scale"), "{e:?}");
}

#[test]
fn targets_that_are_missing_not_finite_or_too_few() {
    let empty: [[f64; 2]; 0] = [];
    assert_eq!(error(&design(), &Task::path("p", empty).timed([])), SynthesisError::NoTargets);
    let e = error(&design(), &Task::path("p", [[1.0, 2.0], [f64::NAN, 2.0]]).timed([0.0, 1.0]));
    assert!(matches!(e, SynthesisError::NonFinite { target: 1, .. }), "{e:?}");
    let e = error(&design(), &Task::path("p", [[1.0, 2.0], [1.0, 2.0]]).timed([0.0, f64::INFINITY]));
    assert!(matches!(e, SynthesisError::NonFinite { what: "the input", target: 1, .. }), "{e:?}");
    // Two points, untimed: four equations for two dimensions and two crank angles is enough;
    // one point is not (two equations, three unknowns).
    let two = Task::path("p", [[1.0, 2.0], [1.5, 2.2]]).untimed(0.0, 1.0);
    assert!(Problem::new(CouplerFourBar::default(), &design(), &two).is_ok());
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]]).untimed(0.0, 1.0));
    assert_eq!(e, SynthesisError::TooFewTargets { residuals: 2, variables: 3 });
    // Timing missing, or of the wrong length.
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]; 3]));
    assert!(matches!(e, SynthesisError::Mismatch(_)), "{e:?}");
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]; 3]).timed([0.0, 1.0]));
    assert!(matches!(e, SynthesisError::Mismatch(_)), "{e:?}");
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]; 3]).timed_inputs(vec![vec![0.0, 1.0]; 3]));
    assert!(matches!(e, SynthesisError::Mismatch(_)), "{e:?}");
    let e = error(&design(), &Task::new(vec![], vec![vec![]; 3]).timed([0.0; 3]));
    assert!(matches!(e, SynthesisError::Mismatch(_)), "{e:?}");
    let e = error(&design(), &three().with_weights(vec![-1.0]));
    assert!(matches!(e, SynthesisError::InvalidConfig(_)), "{e:?}");
}

/// Several targets that are all one point, with free timing: a design through the point meets
/// them all at one input, no motion, and every such candidate had an order defect (an exact fit
/// of four copies of a point ranked invalid below a valid one 0.39 off; a point out of reach
/// gave no valid candidate, "order" its only word). Refused, saying what to give instead; with
/// prescribed inputs (the point held still while the crank turns) and as a single target they
/// stand, and two targets that differ in one value are no copies.
#[test]
fn untimed_targets_all_at_one_point_are_refused() {
    let e = error(&design(), &Task::path("p", [[0.5, 0.9]; 4]).untimed(0.0, std::f64::consts::TAU));
    let SynthesisError::InvalidConfig(why) = &e else { panic!("{e:?}") };
    assert!(why.contains("all 4 targets are one, (0.5, 0.9)") && why.contains("prescribe the inputs"), "{why}");
    let m = CouplerFourBar::default;
    assert!(Problem::new(m(), &design(), &Task::path("p", [[0.5, 0.9]; 4]).timed([0.0, 0.5, 1.0, 1.5])).is_ok());
    assert!(
        Problem::new(m(), &Design::new().var("a", 0.5, 2.0), &Task::path("p", [[0.5, 0.9]]).untimed(0.0, 1.0)).is_ok()
    );
    let apart = Task::path("p", [[0.5, 0.9], [0.5, 0.9], [0.5, 0.9000000000000001]]).untimed(0.0, 1.0);
    assert!(Problem::new(m(), &design(), &apart).is_ok());
}

#[test]
fn settings_and_points_out_of_range() {
    let problem = Problem::new(CouplerFourBar::default(), &design(), &three()).unwrap();
    let search = Search::default().with_local(LocalConfig::default().with_max_evaluations(0));
    let e = search.run(&problem).unwrap_err();
    assert!(
        matches!(&e, SynthesisError::InvalidConfig(m) if m == "local.max_evaluations is 0: it must be at least 1"),
        "{e:?}"
    );
    let search = Search::default().with_local(LocalConfig::default().with_tol(f64::NAN));
    let e = search.run(&problem).unwrap_err();
    assert!(
        matches!(&e, SynthesisError::InvalidConfig(m) if m == "local.tol is NaN: it must be finite and not negative"),
        "{e:?}"
    );
    let e = Search::default().with_distinct(-1.0).run(&problem).unwrap_err();
    assert!(
        matches!(&e, SynthesisError::InvalidConfig(m) if m == "distinct is -1: it must be finite and not negative"),
        "{e:?}"
    );
    assert!(matches!(problem.residuals(&[1.0]), Err(SynthesisError::Mismatch(_))));
    assert!(matches!(problem.residuals(&[1.0, f64::NAN]), Err(SynthesisError::InvalidConfig(_))));
    let c = Constraints::default().with_transmission("beta", "gamma", 2.0);
    assert!(matches!(problem.clone().with_constraints(&c), Err(SynthesisError::InvalidConfig(_))));
    // A transmission angle between a length and an angle is none: refused, naming the column.
    let c = Constraints::default().with_transmission("p.x", "gamma", 0.5);
    let r = problem.clone().with_constraints(&c);
    assert!(matches!(&r, Err(SynthesisError::InvalidConfig(m)) if m.contains("`p.x` is a length")), "{:?}", r.err());
    let c = Constraints::default().with_link_ratio(&["a", "z"], 2.0);
    assert!(matches!(problem.clone().with_constraints(&c), Err(SynthesisError::UnknownVariable { .. })));
    assert!(matches!(problem.clone().with_guesses(vec![[0.0, 0.0]]), Err(SynthesisError::Mismatch(_))));
    // More starts than a report holds: an error before the first, not a capacity-overflow
    // panic.
    let results_only = isize::MAX as usize / 32;
    for search in [
        Search::default().with_starts(0..usize::MAX),
        Search::default().with_starts(1..usize::MAX),
        // Fits a vector of the jobs' results (32 bytes an entry), not one of the candidates
        // held from them.
        Search::default().with_starts(0..results_only),
        // Fits both, not memory (3.2e18 bytes of results): an error before the first, not an
        // abort in the allocator.
        Search::default().with_starts(0..10usize.pow(17)),
        // Inverted: it ran nothing, with `Ok`.
        #[allow(clippy::reversed_empty_ranges)]
        Search::default().with_starts(10..2),
    ] {
        let r = search.run(&problem);
        assert!(matches!(&r, Err(SynthesisError::InvalidConfig(m)) if m.contains("starts")), "{r:?}");
        let r = search.par_run(&problem);
        assert!(matches!(&r, Err(SynthesisError::InvalidConfig(m)) if m.contains("starts")), "{r:?}");
    }
}

#[test]
fn designs_that_never_assemble_are_counted_not_fatal() {
    // The crank far longer than the rest: no start assembles at the targets.
    let design = Design::new().var("a", 50.0, 60.0).var("e", 1.0, 2.0);
    let problem = Problem::new(CouplerFourBar::default(), &design, &three()).unwrap();
    let report = Search::default().with_starts(0..8).run(&problem).unwrap();
    assert_eq!((report.unassembled, report.candidates.len()), (8, 0));
    assert!(report.best().is_none());
    assert!(Search::default().refine(&problem, &[55.0, 1.5]).is_err());
}

/// Designs refused before their local solve are reported by the kind of error, each kind with
/// its count and its first design and message (what `refine` from it says). Before, they were
/// only counted in `unassembled`. Which design is refused for which reason is independent of
/// kinloop: `a` beyond `b + c + d` (here 5.5 + 3) cannot reach the rocker's circle at any crank
/// angle, `a - d > b + c`; `|alpha|` of 1e80 is beyond the largest angle the problem resolves.
#[test]
fn refused_designs_are_reported_by_kind_with_their_first_design() {
    use kinloop::synthesis::{Origin, RefusalKind};
    let design = Design::new().var("a", 0.5, 60.0).var("alpha", -1e80, 1e80);
    let problem = Problem::new(CouplerFourBar::default(), &design, &three()).unwrap();
    // Seeds, in order: angle beyond, unassembled, assembled (1 + 3 >= 2.5 + ... reaches at every
    // angle: |a - d| = 2 and a + d = 4 lie within [|b - c|, b + c] = [0.5, 5.5]), both, unassembled.
    let seeds = vec![vec![1.0, 1e80], vec![55.0, 0.6], vec![1.0, 0.6], vec![50.0, -1e80], vec![58.0, 0.6]];
    let search = Search::default().with_starts(0..0).with_seeds(seeds);
    let report = search.run(&problem).unwrap();
    assert_eq!(report.unassembled, 4, "{report:#?}");
    let kinds: Vec<_> = report.refused.iter().map(|r| (r.kind, r.count, r.origin, r.start)).collect();
    assert_eq!(
        kinds,
        [(RefusalKind::NoAssembly, 2, Origin::Seed, 1), (RefusalKind::InvalidArgument, 2, Origin::Seed, 0)],
        "{report:#?}"
    );
    assert_eq!(
        (report.refused[0].point.as_slice(), report.refused[1].point.as_slice()),
        (&[55.0, 0.6][..], &[1.0, 1e80][..])
    );
    // Each message is the refinement's from that design.
    for r in &report.refused {
        let e = search.refine(&problem, &r.point).unwrap_err();
        assert_eq!(e.to_string(), format!("kinematics failed: {}", r.message));
    }
    assert!(report.refused[1].message.contains("`alpha`"), "{}", report.refused[1].message);
    let shown = report.refused[0].to_string();
    assert!(shown.starts_with("2 refused (cannot be assembled), first seed 1 at [55, 0.6]: "), "{shown}");
    assert_eq!(search.par_run(&problem).unwrap(), report);
}

/// A search that holds its starts as keys (more than 4096) reports the refusals of its parts
/// merged: every start of a crank far too long for the rest refused as unassembled, the first
/// (start 0) the example, solved again where it was held as a key.
#[test]
fn refusals_held_as_keys_are_the_merged_parts_refusals() {
    use kinloop::synthesis::{Origin, RefusalKind};
    let design = Design::new().var("a", 50.0, 60.0).var("e", 1.0, 2.0);
    let problem = Problem::new(CouplerFourBar::default(), &design, &three()).unwrap();
    let search = Search::default().with_keep(1);
    let whole = search.clone().with_starts(0..4200).run(&problem).unwrap();
    let first = search.clone().with_starts(0..2100).run(&problem).unwrap();
    let second = search.clone().with_starts(2100..4200).run(&problem).unwrap();
    let merged = first.merge(second, &search);
    assert_eq!(whole.refused, merged.refused);
    assert_eq!(whole.refused.len(), 1, "{:#?}", whole.refused);
    let r = &whole.refused[0];
    assert_eq!((r.kind, r.count, r.origin, r.start), (RefusalKind::NoAssembly, 4200, Origin::Halton, 0));
    assert_eq!(r.point, search.start(&problem, 0));
}

/// An island none of whose members can be assembled (every crank far too long: `a - d > b + c`)
/// reports its members to polish as refused, by the first members' reason, the first member
/// of its last generation the example (a design that cannot reach, `a - d > b + c`).
#[test]
fn an_island_of_unassembled_members_reports_why() {
    use kinloop::synthesis::{DeConfig, Global, Origin, RefusalKind};
    let design = Design::new().var("a", 50.0, 60.0).var("e", 1.0, 2.0);
    let problem = Problem::new(CouplerFourBar::default(), &design, &three()).unwrap();
    let de = DeConfig::default().with_population(6).with_generations(2).with_polish(2);
    let search = Search::default().with_global(Global::DifferentialEvolution(de)).with_starts(0..1);
    let report = search.run(&problem).unwrap();
    assert_eq!((report.unassembled, report.candidates.len()), (2, 0));
    // The population of 6 and 2 generations of 6 trials, and the 2 members evaluated again for
    // their reasons.
    assert_eq!(report.evaluations, 6 + 2 * 6 + 2);
    let kinds: Vec<_> = report.refused.iter().map(|r| (r.kind, r.count, r.origin, r.start)).collect();
    assert_eq!(kinds, [(RefusalKind::NoAssembly, 2, Origin::Evolution, 0)], "{report:#?}");
    let [a, e] = report.refused[0].point[..] else { panic!("{report:#?}") };
    assert!((50.0..=60.0).contains(&a) && (1.0..=2.0).contains(&e) && a - 3.0 > 3.0 + 2.5, "{a}, {e}");
}

#[test]
fn a_parameter_vector_of_another_length_is_an_error_not_a_panic() {
    use kinloop::{CompiledSens, Error, SensKernel};
    let k = CompiledSens(CouplerFourBar::default());
    for p in [&[1.0][..], &[1.0; 7]] {
        let e = k.with_params(p, |_| unreachable!("not called with a wrong length")).unwrap_err();
        // One value is one: "1 parameter value".
        let values = if p.len() == 1 { "value" } else { "values" };
        let says = format!("{} parameter {values} for the 6 parameters of `CouplerFourBar`", p.len());
        assert!(matches!(&e, Error::InvalidArgument(m) if m.contains(&says)), "{e}");
    }
    let p = [1.1, 2.8, 2.3, 3.2, 1.7, 0.45];
    let seen = k.with_params(&p, |m| (0..6).map(|i| m.param(i)).collect::<Vec<_>>()).unwrap();
    assert_eq!(seen, p);
}

/// Timing whose motion from target to target turns the input more than a sweep follows is
/// refused with the targets and the turns: every candidate's verifying sweep would refuse its
/// range, and each be rejected as if it could not be assembled. Free timing likewise.
#[test]
fn timing_farther_apart_than_a_sweep_follows() {
    let task = Task::path("p", [[1.0, 2.0], [1.5, 2.2], [2.0, 2.1]]).timed([0.0, 0.5, 1e300]);
    let e = error(&design(), &task);
    let m = e.to_string();
    assert!(
        matches!(e, SynthesisError::InvalidConfig(_)) && m.contains("targets 1 and 2") && m.contains("`phi`"),
        "{m}"
    );
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]; 3]).untimed(-1e300, 1e300));
    assert!(matches!(&e, SynthesisError::InvalidConfig(m) if m.contains("turns of input `phi`")), "{e:?}");
    // Farther apart than any double: the bounds themselves are refused.
    let e = error(&design(), &Task::path("p", [[1.0, 2.0]; 3]).untimed(-1e308, 1e308));
    assert!(matches!(&e, SynthesisError::BadBounds { name, .. } if name == "input"), "{e:?}");
    // A million turns less a little is followed.
    let far = std::f64::consts::TAU * 0.99e6;
    assert!(Problem::new(CouplerFourBar::default(), &design(), &three().timed([0.0, 0.5, far])).is_ok());
}

kinloop::mechanism! {
    /// A crank driven by its slider: the slider's position `s` is the input (a length).
    #[kinloop(sensitivities)]
    pub struct SliderDriven {
        params r = 1.0, l = 3.0;
        input s;
        unknowns phi = 0.5, psi = 0;
        loop oabo: r @ phi == (s, 0) + l @ psi;
    }
}

#[test]
fn a_full_rotation_of_a_length_input_is_refused() {
    let design = Design::new().var("r", 0.5, 2.0);
    let task = Task::function("phi", [(2.5, 1.0), (3.0, 0.8), (3.5, 0.5)]);
    let problem = match Problem::new(SliderDriven::default(), &design, &task) {
        Ok(p) => p,
        Err(e) => panic!("{e}"),
    };
    let r = problem.with_constraints(&Constraints::default().with_full_rotation());
    assert!(
        matches!(&r, Err(SynthesisError::InvalidConfig(m)) if m.contains("`s` of `SliderDriven` is a length")),
        "{:?}",
        r.err()
    );
}

/// An angle channel on a length (the slider's position) is refused: compared modulo a turn, a
/// slider 2 pi off its targets met them, with an error depending on the unit of length. A
/// value channel on it is the slider's position.
#[test]
fn an_angle_channel_on_a_length_is_refused() {
    use super::mechanisms::{SLIDER, Slider, slider_x};
    use kinloop::synthesis::Channel;
    let phis = [0.0, 0.7, 1.4, 2.1];
    let targets: Vec<Vec<f64>> = phis.iter().map(|&phi| vec![slider_x(SLIDER, phi) + std::f64::consts::TAU]).collect();
    let r = Design::new().var("r", 0.5, 2.0);
    let task = Task::new(vec![Channel::Angle("x".into())], targets.clone()).timed(phis);
    let e = Problem::new(Slider::default(), &r, &task).unwrap_err();
    assert!(matches!(&e, SynthesisError::Mismatch(m) if m.starts_with("`x` is a length, not an angle")), "{e:?}");
    let task = Task::new(vec![Channel::Value("x".into())], targets).timed(phis);
    assert!(Problem::new(Slider::default(), &r, &task).is_ok());
    // A motion task's angle on a point's coordinate likewise.
    let poses = [[1.0, 2.0, 0.1], [1.5, 2.2, 0.2], [2.0, 2.1, 0.3]];
    let e = error(&design(), &Task::motion("p", "p.x", poses).timed([0.0, 0.5, 1.0]));
    assert!(matches!(&e, SynthesisError::Mismatch(m) if m.starts_with("`p.x` is a length")), "{e:?}");
}

/// A search keeping no candidate is refused: it dropped every candidate found and returned
/// `Ok` with none.
#[test]
fn a_search_that_keeps_none_is_refused() {
    let p = Problem::new(CouplerFourBar::default(), &design(), &three()).unwrap();
    let e = Search::default().with_starts(0..2).with_keep(0).run(&p).unwrap_err();
    assert_eq!(e, SynthesisError::InvalidConfig("keep is 0: it must be at least 1".into()));
}

/// A search of no start and no seed is refused: it returned `Ok` with an empty report, as if the
/// design had no solution (the command line's `--starts` takes at least 1). With a seed and no
/// start, it solves the seed.
#[test]
fn a_search_of_nothing_to_solve_from_is_refused() {
    let p = Problem::new(CouplerFourBar::default(), &design(), &three()).unwrap();
    let e = Search::default().with_starts(0..0).run(&p).unwrap_err();
    assert!(matches!(&e, SynthesisError::InvalidConfig(m) if m.starts_with("starts 0..0 and no seeds")), "{e:?}");
    let e = Search::default().with_starts(5..5).run(&p).unwrap_err();
    assert!(matches!(&e, SynthesisError::InvalidConfig(m) if m.contains("nothing to solve from")), "{e:?}");
    let seed = Search::default().with_starts(0..1).run(&p).unwrap().candidates[0].values.clone();
    let report = Search::default().with_starts(0..0).with_seeds(vec![seed]).run(&p).unwrap();
    assert_eq!((report.seeds, report.candidates.len()), (1, 1));
}
