//! The sweep's results with its stop reason and location, a mechanism-wide solver configuration,
//! `reachable` in input values and `trace_curve`'s options, checked against closed forms (the law
//! of cosines for a four-bar's limit positions) and against the behaviour without them.

use kinloop::dynamics::{Body, Coord, DynamicsError, InverseCycle, MassModel, Rotation, SpeedLaw};
use kinloop::{AtSingular, Error, EventKind, Kin, Named, NewtonConfig, Sweep, SweepConfig, SweepStop, TraceConfig};
use kinloop_fixtures::{FourBar, FourBarInputs, FourBarUnknowns};
use std::f64::consts::PI;

use crate::support::{four_bar_limit, tol};

kinloop::mechanism! {
    /// The four-bar solved by Newton's method (not in closed form), so that the Newton
    /// configuration changes what a solve does.
    #[kinloop(newton)]
    pub struct NewtonFourBar {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

/// A double rocker (`a + d > b + c`): its input stops where coupler and rocker stretch out.
fn rocker() -> FourBar {
    FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 }
}

/// The input at the limit position, `|BD| = b + c`, by the law of cosines.
fn limit(m: &FourBar) -> f64 {
    four_bar_limit(m.a, m.d, m.b + m.c)
}

#[test]
fn a_run_keeps_the_states_and_says_where_it_stopped() {
    let m = rocker();
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let run = m.sweep(0.0, PI, 181, &g).unwrap().run();
    let lim = limit(&m);
    // Every sample below the limit position (spacing pi/180), and only those.
    let below = (0..181).filter(|&i| PI * i as f64 / 180.0 < lim).count();
    assert_eq!(run.states.len(), below);
    assert!(run.states.iter().all(|s| s.input.phi < lim));
    let SweepStop::LimitPosition(ev) = &run.stop else { panic!("{:?}", run.stop) };
    assert_close!(ev.x[0], lim, tol::LOCATED, "{} vs {lim}", ev.x[0]);
    assert_eq!(ev.kind, EventKind::LimitPosition);
    assert_eq!(run.stop.event(), Some(ev));
    assert_eq!(run.events, vec![ev.clone()]);
    assert!(!run.is_completed());
    // The same states and the same error as the lazy iterator.
    let mut lazy = m.sweep(0.0, PI, 181, &g).unwrap();
    let states: Vec<_> = lazy.by_ref().map_while(Result::ok).collect();
    assert_eq!(states, run.states);
    assert_eq!(lazy.events(), &run.events[..]);
    let err = run.into_result().unwrap_err();
    assert!(matches!(err, Error::SweepStopped { kind: EventKind::LimitPosition, .. }), "{err}");
}

#[test]
fn a_complete_run_and_a_failed_one() {
    let crank = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let g = crank.guess(0.0);
    let run = crank.sweep(0.0, 2.0 * PI, 37, &g).unwrap().run();
    assert!(run.is_completed() && run.events.is_empty() && run.stop.event().is_none());
    assert_eq!(run.into_result().unwrap().len(), 37);
    // No assembly at the first input: a failure, no states.
    let far = FourBar { a: 1.0, b: 1.0, c: 1.0, d: 10.0 };
    let run = far.sweep(0.0, 1.0, 3, &g).unwrap().run();
    assert!(run.states.is_empty());
    assert!(matches!(run.stop, SweepStop::Failed(Error::NoAssembly { .. })), "{:?}", run.stop);
}

#[test]
fn a_crossing_stop_is_reported_as_such() {
    // Change-point four-bar: the assembly modes meet at phi = 2 pi.
    let m = FourBar { a: 1.0, b: 3.0, c: 2.0, d: 2.0 };
    let g = m.position(0.5, &FourBarUnknowns { beta: 0.6, gamma: 1.6 }).unwrap().0;
    let run = m.sweep(0.5, 7.0, 66, &g).unwrap().run();
    let SweepStop::SingularCrossing(ev) = &run.stop else { panic!("{:?}", run.stop) };
    assert_close!(ev.x[0], 2.0 * PI, tol::LOCATED, "{:?}", ev.x);
    // Configured on the mechanism to continue, it completes and lists the crossing.
    let cont = m.with_config(SweepConfig::default().with_at_singular(AtSingular::Continue)).unwrap();
    let run = cont.sweep(0.5, 7.0, 66, &g).unwrap().run();
    assert!(run.is_completed(), "{:?}", run.stop);
    assert_eq!(run.states.len(), 66);
    assert_eq!(run.events.len(), 1);
    assert_eq!(run.events[0].kind, EventKind::SingularCrossing);
}

#[test]
fn the_mechanism_configuration_reaches_every_solve() {
    let m = NewtonFourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let far = NewtonFourBarUnknowns { beta: 1.2, gamma: 2.4 };
    // By default Newton converges from the declared and from a far guess.
    assert!(m.solve(0.4).is_ok() && m.kinematics(0.4, &far).is_ok());
    // One iteration is not enough: every solve of the configured mechanism says so.
    let one = m.with_config(NewtonConfig::default().with_max_iterations(1)).unwrap();
    assert_eq!(one.config().newton.max_iterations, 1);
    let no_convergence = |r: Result<NewtonFourBarState, Error>| matches!(r, Err(Error::NoConvergence { .. }));
    assert!(no_convergence(one.solve(0.4)), "{:?}", one.solve(0.4));
    assert!(no_convergence(one.kinematics(0.4, &far)));
    assert!(one.position(0.4, &far).is_err());
    assert!(matches!(one.sweep(0.4, 1.0, 5, &far).unwrap().run().stop, SweepStop::Failed(Error::NoConvergence { .. })));
    assert!(matches!(one.sweep_at([0.4, 0.6], &far).stop, SweepStop::Failed(Error::NoConvergence { .. })));
    assert!(matches!(one.assembly_modes(0.4), Err(Error::NoConvergence { .. })));
    assert!(one.trace_curve(0.4, 1.0, &far, &TraceConfig::default()).is_err());
    // The sampled analyses, the limit search and the inverse dynamics' turn too (they swept
    // with the defaults whatever the mechanism carried).
    let sampled = one.sampled(0.4, 1.0, 5, &far);
    assert!(matches!(sampled, Err(Error::NoConvergence { .. })), "{:?}", sampled.err());
    let limits = kinloop::metrics::Limits::new(&one, 0.4, 1.0).guess(far).run();
    assert!(matches!(limits, Err(Error::NoConvergence { .. })), "{limits:?}");
    let crank = crank_body();
    let model = MassModel::<2, 1, 0>::new().with_body(crank).unwrap();
    let cycle = InverseCycle::new(&one, &model, SpeedLaw::Constant(1.0)).samples(16).guess(far).run();
    let no_convergence = matches!(&cycle, Err(DynamicsError::Kinematics { source: Error::NoConvergence { .. }, .. }));
    assert!(no_convergence, "{:?}", cycle.err());
    assert!(InverseCycle::new(&m, &model, SpeedLaw::Constant(1.0)).samples(16).guess(far).run().is_ok());
    // An explicit configuration still wins over the mechanism's.
    assert!(one.kinematics_with(0.4, &far, &NewtonConfig::default()).is_ok());
    assert!(one.trace_curve(0.4, 1.0, &far, &TraceConfig::default().with_newton(NewtonConfig::default())).is_ok());
    // The residual tolerance of the configuration is the one met: looser tolerance, fewer
    // iterations (and never more) from the same guess.
    let loose = m.with_config(NewtonConfig::default().with_residual_tol(1e-4)).unwrap();
    let (tight_report, loose_report) = (m.position(0.4, &far).unwrap().1, loose.position(0.4, &far).unwrap().1);
    assert!(loose_report.iterations < tight_report.iterations, "{loose_report:?} vs {tight_report:?}");
    assert!(loose_report.residual <= 1e-4, "{loose_report:?}");
    // The parameters are those of the mechanism.
    assert_eq!(one.mechanism().c, 2.5);
    assert_eq!(one.into_inner(), m);
}

#[test]
fn an_invalid_configuration_is_refused_up_front_naming_the_field() {
    let m = rocker();
    let e = m.with_config(NewtonConfig::default().with_residual_tol(f64::NAN)).unwrap_err();
    assert!(e.to_string().contains("newton.residual_tol"), "{e}");
    let e = m.with_config(SweepConfig::default().with_max_step(0.0)).unwrap_err();
    assert!(e.to_string().contains("max_step"), "{e}");
}

#[test]
fn reachable_answers_in_named_input_values() {
    let m = rocker();
    let lim = limit(&m);
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let r = m.reachable(0.0, FourBarInputs { phi: PI }, &g, 91).unwrap();
    assert_close!(r.to.phi, lim, tol::LOCATED, "{r:?} vs +-{lim}");
    assert_close!(r.from.phi, -lim, tol::LOCATED, "{r:?} vs +-{lim}");
    assert!(r.to_event.is_some() && r.from_event.is_some());
    // Within a small range, the ends of the range itself, without events.
    let r = m.reachable(0.2, 0.5, &m.position(0.2, &g).unwrap().0, 11).unwrap();
    assert_close!(r.from.phi, -0.3, 1e-15, "{r:?}");
    assert_close!(r.to.phi, 0.7, 1e-15, "{r:?}");
    assert!(r.from_event.is_none() && r.to_event.is_none());
}

#[test]
fn trace_options_are_validated_naming_the_field() {
    let m = rocker();
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let cases = [
        (TraceConfig::default().with_ds(0.0), "TraceConfig::ds"),
        (TraceConfig::default().with_ds(f64::NAN), "TraceConfig::ds"),
        (TraceConfig::default().with_ds(f64::INFINITY), "TraceConfig::ds"),
        (TraceConfig::default().with_ds(1.5), "TraceConfig::ds"),
        (TraceConfig::default().with_ds(1e-10), "TraceConfig::ds"),
        (TraceConfig::default().with_max_points(0), "TraceConfig::max_points"),
        (TraceConfig::default().with_max_points(kinloop::analysis::MAX_SAMPLES + 1), "TraceConfig::max_points"),
        (TraceConfig::default().with_max_points(usize::MAX), "TraceConfig::max_points"),
        (
            TraceConfig::default().with_newton(NewtonConfig::default().with_max_iterations(10_001)),
            "newton.max_iterations",
        ),
    ];
    for (opts, field) in cases {
        let e = m.trace_curve(0.0, PI, &g, &opts).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument(_)) && e.to_string().contains(field), "{field}: {e}");
    }
    // A range no sweep follows is none a trace follows: refused before the first step (a trace
    // over 1e12 rad walked for as many points as it was allowed), in any unit of the input.
    let opts = TraceConfig::default().with_max_points(kinloop::analysis::MAX_SAMPLES);
    for to in [1e12, -1e12, 1e300] {
        let e = m.trace_curve(0.0, to, &g, &opts).unwrap_err();
        assert!(matches!(e, Error::RangeTooLong { .. }) && e.to_string().contains("trace"), "{to}: {e}");
    }
    // A range shorter than the smallest normal number gives no direction to trace in: the path's
    // parameter overflowed, and this regular start was told the curve "bifurcates or ends" there.
    // A range of 1e-300 is one.
    for to in [5e-324, -1e-310] {
        let e = m.trace_curve(0.0, to, &g, &TraceConfig::default()).unwrap_err();
        let text = e.to_string();
        assert!(matches!(e, Error::InvalidArgument(_)) && text.contains("different from `from`"), "{to:e}: {text}");
    }
    assert!(m.trace_curve(0.0, 1e-300, &g, &TraceConfig::default()).is_ok());
    // A trace of few points stops there.
    let t = m.trace_curve(0.0, PI, &g, &TraceConfig::default().with_max_points(5)).unwrap();
    assert_eq!(t.points.len(), 5);
    assert!(!t.closed && t.truncated, "{t:?}");
    // The whole curve, closed, is not truncated.
    let t = m.trace_curve(0.0, PI, &g, &TraceConfig::default()).unwrap();
    assert!(t.closed && !t.truncated, "{} points", t.points.len());
}

/// A trace keeps every point: a `max_points` whose points would take more than the 1 GiB a
/// sweep's `run()` keeps at most is refused before the first step, with the numbers and the most
/// that fit (a four-bar's point is its input, two positions and the input's rate: 32 bytes,
/// 33,554,432 of them in 1 GiB). `max_points` allowed up to `10^8` points, 3.2 GB of a four-bar
/// and several times that of a larger mechanism, where a failed allocation aborts the process;
/// a curve that closes sooner never showed it. The most that fit are allowed.
#[test]
fn a_trace_whose_points_could_exceed_the_memory_budget_is_refused() {
    let m = rocker();
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let each = size_of::<kinloop::TracedPoint<2, 1>>();
    assert_eq!(each, 32);
    let most = kinloop::paths::collected::MAX_COLLECTED_BYTES / each;
    for max_points in [most + 1, kinloop::analysis::MAX_SAMPLES] {
        let e = match m.trace_curve(0.0, PI, &g, &TraceConfig::default().with_max_points(max_points)) {
            Ok(t) => panic!("{max_points} points allowed: a curve of {} points traced", t.points.len()),
            Err(e) => e,
        };
        let text = e.to_string();
        assert!(matches!(e, Error::InvalidArgument(_)), "{text}");
        assert!(text.contains(&format!("would keep {max_points} points")), "{text}");
        assert!(text.contains(&format!("`TraceConfig::max_points` at most {most}")), "{text}");
    }
    let t = m.trace_curve(0.0, PI, &g, &TraceConfig::default().with_max_points(most)).unwrap();
    assert!(t.closed && !t.truncated, "{} points", t.points.len());
}

#[test]
fn a_scan_uses_each_mechanism_configuration_unless_it_gives_one() {
    use kinloop::{Kin, ScanConfig, scan};
    // The change-point four-bar meets a crossing at 2 pi: configured to continue, its sweep
    // completes; by default it stops there.
    let m = FourBar { a: 1.0, b: 3.0, c: 2.0, d: 2.0 };
    let g = m.position(0.5, &FourBarUnknowns { beta: 0.6, gamma: 1.6 }).unwrap().0;
    let plain = m.with_config(SweepConfig::default()).unwrap();
    let cont = m.with_config(SweepConfig::default().with_at_singular(AtSingular::Continue)).unwrap();
    let spec = ScanConfig::new([0.5], [7.0], 66).start(kinloop::ScanStart::Guess(g.into()));
    let count = |_: &_| 0usize;
    let fold = |n: usize, _: &_, _: &Kin<2, 1, 2>| n + 1;
    let results = scan(&[plain, cont], &spec, count, fold);
    assert!(matches!(results[0], Err(Error::SweepStopped { kind: EventKind::SingularCrossing, .. })), "{results:?}");
    assert_eq!(results[1], Ok(66));
    // A configuration in the spec applies to every set.
    let results = scan(&[plain, cont], &spec.with_config(SweepConfig::default()), count, fold);
    assert!(results.iter().all(Result::is_err), "{results:?}");
}

/// The sweep solves each step into its spare slot and keeps the last accepted state in the
/// other. While sampling, its last state is the sample it returned. At the stop it is the last
/// point it accepted on the way to the limit position: not one of the steps it rejected there
/// (halved ever smaller until it diagnosed the limit, each rejected for a pivot ratio below
/// `singular_pivot` or as a failed solve beyond the limit), so on the sweep's branch, at a
/// pivot ratio it accepts, between the last sample and the limit, and closing the loop.
#[test]
fn rejected_steps_leave_the_last_accepted_state() {
    let m = rocker();
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let mut sweep: Sweep<FourBar, Kin<2, 1, 2>, 2, 1, 2> = Sweep::new(&m, [0.0], [PI], 181, g.into()).unwrap();
    let first = sweep.next_kin().unwrap().unwrap();
    let mut returned = first;
    let err = loop {
        match sweep.next_kin() {
            Some(Ok(k)) => {
                assert_eq!(sweep.last_accepted(), Some(&k));
                returned = k;
            }
            Some(Err(e)) => break e,
            None => panic!("the double rocker cannot turn to pi"),
        }
    };
    assert!(matches!(err, Error::SweepStopped { kind: EventKind::LimitPosition, .. }), "{err}");
    let lim = limit(&m);
    assert!(returned.x[0] < lim && returned.x[0] > lim - PI / 180.0);
    let last = *sweep.last_accepted().unwrap();
    assert!(last.x[0] >= returned.x[0] && last.x[0] < lim, "{} {} {lim}", last.x[0], returned.x[0]);
    assert_eq!(last.health.det_signs, first.health.det_signs);
    assert!(last.health.min_pivot >= SweepConfig::default().singular_pivot, "{:?}", last.health);
    // The loop closes: a phi + b beta = (d, 0) + c gamma.
    let (phi, [beta, gamma]) = (last.x[0], last.q);
    let rx = m.a * phi.cos() + m.b * beta.cos() - m.d - m.c * gamma.cos();
    let ry = m.a * phi.sin() + m.b * beta.sin() - m.c * gamma.sin();
    assert!(rx.abs().max(ry.abs()) < 1e-12 * m.d, "{rx:e} {ry:e}");
}

/// What a program holds prints with `{:?}`: a sweep, a sampled range, a mass model with its
/// loads and a speed law (closures shown as elided), each naming what it is of.
#[test]
fn sweeps_sampled_ranges_mass_models_speed_laws_and_builders_print_with_debug() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let g = m.guess(0.0);
    let sweep = format!("{:?}", m.sweep(0.0, 1.0, 5, &g).unwrap());
    assert!(sweep.starts_with("SweepOf {") && sweep.contains("FourBar") && sweep.contains("samples: 5"), "{sweep}");
    let sampled = format!("{:?}", m.sampled(0.0, 1.0, 5, &g).unwrap());
    assert!(sampled.contains("FourBar") && sampled.contains("states: 5"), "{sampled}");
    let crank = crank_body();
    let model = MassModel::<2, 1, 0>::new()
        .with_body(crank)
        .unwrap()
        .with_torque("brake", Rotation::Input(0), |_: &Kin<2, 1, 0>, _: &[f64; 1]| -1.0)
        .unwrap();
    let model = format!("{model:?}");
    assert!(model.contains("\"crank\"") && model.contains("Torque { name: \"brake\""), "{model}");
    assert_eq!(format!("{:?}", SpeedLaw::Constant(2.0)), "Constant(2.0)");
    let law = |phi: f64| (1.0 + 0.1 * phi.sin(), 0.1 * phi.cos());
    assert_eq!(format!("{:?}", SpeedLaw::Varying(&law)), "Varying(..)");
    let model = MassModel::<2, 1, 2>::new().with_body(crank_body()).unwrap();
    let cycle = format!("{:?}", InverseCycle::new(&m, &model, SpeedLaw::Constant(2.0)).samples(90));
    assert!(cycle.contains("FourBar") && cycle.contains("\"crank\"") && cycle.contains("samples: 90"), "{cycle}");
    let run = format!("{:?}", kinloop::dynamics::Simulation::new(&m, &model).start(0.5, 2.0));
    assert!(run.contains("FourBar") && run.contains("start: [0.5, 2.0]") && run.ends_with(", .. }"), "{run}");
    let limits = format!("{:?}", kinloop::metrics::Limits::new(&m, 0.0, 1.0).samples(7).columns(&[FourBar::COL.gamma]));
    assert!(limits.contains("FourBar") && limits.contains("samples: 7") && limits.contains("gamma"), "{limits}");
}

/// A crank of unit mass and inertia turning with the input, centred on its pivot.
fn crank_body() -> Body {
    Body {
        name: "crank".into(),
        mass: 1.0,
        com: [Coord::Fixed(0.0), Coord::Fixed(0.0)],
        inertia: 1.0,
        rotation: Rotation::Input(0),
    }
}

/// A sweep that stops at a limit position has no item after its error, however often asked,
/// and says so (it told of the samples it would not reach); nor after its last sample. Its
/// upper bound is never below the items that follow.
#[test]
fn a_stopped_sweep_is_fused_and_says_it_has_nothing_left() {
    fn fused<I: std::iter::FusedIterator>(i: I) -> I {
        i
    }
    let m = rocker();
    let sweep = || fused(m.sweep(0.0, limit(&m) + 0.5, 10, &m.guess(0.0)).unwrap());
    // Seven samples before the limit position, and the stop.
    let total = sweep().count();
    assert_eq!(total, 8);
    let mut sweep = sweep();
    let mut items = 0;
    loop {
        let (low, high) = sweep.size_hint();
        let left = total - items;
        assert!(low <= left && high.is_some_and(|h| h >= left), "{items}: {low}, {high:?} for {left} items");
        match sweep.next() {
            Some(Ok(_)) => items += 1,
            Some(Err(e)) => {
                assert!(matches!(e, Error::SweepStopped { kind: EventKind::LimitPosition, .. }), "{e}");
                break;
            }
            None => panic!("the sweep ended without its stop"),
        }
    }
    assert_eq!(items, 7);
    for _ in 0..3 {
        assert_eq!(sweep.size_hint(), (0, Some(0)));
        assert!(sweep.next().is_none());
    }
    let mut whole = m.sweep(0.0, 1.0, 3, &m.guess(0.0)).unwrap();
    assert_eq!(whole.size_hint(), (0, Some(3)));
    assert_eq!(whole.by_ref().filter(Result::is_ok).count(), 3);
    assert_eq!(whole.size_hint(), (0, Some(0)));
    assert!(whole.next().is_none() && whole.next().is_none());
}

/// A range that ends exactly at a limit position or a change point stops there with the event at
/// its end, on the range: located past it by the rounding (the limit position 2e-16 of the path
/// beyond `to`, the crossing 2e-13), its fraction of the path was above 1 and its input outside
/// the range swept, and `reachable` gave an end past the range it searched.
#[test]
fn an_event_at_the_end_of_the_range_lies_on_it() {
    let m = rocker();
    let lim = limit(&m);
    for to in [lim, -lim] {
        for samples in [2, 5] {
            let mut sweep = m.sweep(0.0, to, samples, &m.guess(0.0)).unwrap();
            let stop = sweep.by_ref().find_map(Result::err).expect("stopped");
            assert!(matches!(stop, Error::SweepStopped { kind: EventKind::LimitPosition, .. }), "{stop}");
            let [event] = sweep.events() else { panic!("{:?}", sweep.events()) };
            assert!(event.tau <= 1.0 && (event.tau - 1.0).abs() <= tol::LOCATED, "{to}, {samples}: {event:?}");
            assert!(event.x[0].abs() <= lim, "{to}, {samples}: {event:?}");
        }
        let reach = m.reachable(0.0, to.abs(), &m.guess(0.0), 5).unwrap();
        assert!(reach.from.phi >= -lim && reach.to.phi <= lim, "{reach:?}");
        for event in [reach.from_event, reach.to_event] {
            assert!(event.is_some_and(|e| e.tau <= 1.0), "{to}");
        }
    }
    // A parallelogram's change point at the end of the range.
    let m = FourBar { a: 1.0, b: 3.0, c: 1.0, d: 3.0 };
    for (from, samples) in [(0.5, 5), (PI - 0.5, 2)] {
        let mut sweep = m.sweep(from, PI, samples, &m.guess(from)).unwrap();
        let stop = sweep.by_ref().find_map(Result::err).expect("stopped");
        assert!(matches!(stop, Error::SweepStopped { kind: EventKind::SingularCrossing, .. }), "{stop}");
        let [event] = sweep.events() else { panic!("{:?}", sweep.events()) };
        assert!(event.tau <= 1.0 && event.x[0] <= PI, "{from}: {event:?}");
        assert!((event.x[0] - PI).abs() <= tol::LOCATED, "{from}: {event:?}");
    }
}

/// A sweep iterated up to its stop, then run or tabled, says it stopped, and why: it said
/// `Completed` with no states (and an empty table), of a sweep that met a limit position.
#[test]
fn a_sweep_run_after_its_stop_says_why_it_stopped() {
    let m = rocker();
    let lim = limit(&m);
    let stopped = || {
        let mut sweep = m.sweep(0.0, lim + 0.5, 10, &m.guess(0.0)).unwrap();
        let stop = sweep.by_ref().find_map(Result::err).expect("stopped");
        assert!(matches!(stop, Error::SweepStopped { kind: EventKind::LimitPosition, .. }), "{stop}");
        sweep
    };
    let run = stopped().run();
    assert!(run.states.is_empty());
    let event = run.stop.event().expect("the limit position").clone();
    assert!(matches!(run.stop, SweepStop::LimitPosition(_)), "{:?}", run.stop);
    assert!((event.x[0] - lim).abs() <= tol::LOCATED, "{event:?}");
    assert_eq!(run.events, [event]);
    let err = run.into_result().expect_err("stopped");
    assert!(matches!(err, Error::SweepStopped { kind: EventKind::LimitPosition, .. }), "{err}");
    let err = stopped().table().expect_err("stopped");
    assert!(matches!(err, Error::SweepStopped { kind: EventKind::LimitPosition, .. }), "{err}");
    // An invalid configuration, met by the first item.
    let mut sweep =
        m.sweep(0.0, 1.0, 5, &m.guess(0.0)).unwrap().with_config(SweepConfig::default().with_max_halvings(0));
    assert!(matches!(sweep.next(), Some(Err(Error::InvalidArgument(_)))));
    assert!(matches!(sweep.run().into_result(), Err(Error::InvalidArgument(_))));
    // A sweep run to its end gives no more states, completed.
    let mut sweep = m.sweep(0.0, 1.0, 5, &m.guess(0.0)).unwrap();
    assert_eq!(sweep.by_ref().filter(Result::is_ok).count(), 5);
    let run = sweep.run();
    assert!(run.is_completed() && run.states.is_empty());
}

/// A trace's range is refused as a sweep's: an end that is not finite named, with its value, and
/// a range of finite ends whose length overflows said as such; the one message for all three
/// asked for finite ends of finite ends.
#[test]
fn a_trace_names_what_is_wrong_with_its_range() {
    let m = rocker();
    let o = TraceConfig::default();
    for (from, to, end) in [(0.0, f64::NAN, "to"), (f64::INFINITY, 1.0, "from"), (0.0, f64::NEG_INFINITY, "to")] {
        let err = m.trace_curve(from, to, &m.guess(0.0), &o).expect_err("refused");
        let sweep = m.sweep(from, to, 2, &m.guess(0.0)).expect_err("refused");
        assert_eq!(err.to_string(), sweep.to_string());
        assert!(matches!(&err, Error::NonFinite { name, .. } if name == end), "{err:?}");
    }
    let err = m.trace_curve(-1e308, 1e308, &m.guess(0.0), &o).expect_err("refused");
    let msg = err.to_string();
    assert!(msg.contains("overflows") && !msg.contains("finite `from`"), "{msg}");
    let err = m.trace_curve(0.5, 0.5, &m.guess(0.5), &o).expect_err("refused");
    assert!(err.to_string().contains("`to` different from `from`"), "{err}");
}
