//! Sweeps whose samples are close together: the limit positions, singular crossings and kinks
//! found at a few samples are found at hundreds of thousands too, wherever in the range they
//! lie, and with the finest step the configuration allows (`max_halvings` 60). A step finer
//! than the doubles near the sweep's path coordinate resolve is a step of no length: the sweep
//! must diagnose there, not take it.

use super::sweep_kinks::Kinked;
use kinloop::{AtSingular, EventKind, SweepConfig, SweepStop};
use kinloop_fixtures::FourBar;

/// The crank angle of a non-Grashof four-bar's limit position where coupler and rocker stretch
/// in line, the crank pin `b + c` from the rocker's pivot: `cos phi = (a^2 + d^2 - (b + c)^2) /
/// (2 a d)`, by the law of cosines.
fn stretched_limit(a: f64, b: f64, c: f64, d: f64) -> f64 {
    ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos()
}

#[test]
fn a_limit_position_is_found_at_any_sample_count() {
    // Non-Grashof (3 + 4 > 2 + 2.5): the crank stops where coupler and rocker stretch in line.
    for scale in [1.0, 1e-3, 1e3] {
        let m = FourBar { a: 3.0 * scale, b: 2.0 * scale, c: 2.5 * scale, d: 4.0 * scale };
        let limit = stretched_limit(3.0, 2.0, 2.5, 4.0);
        let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
        for samples in [10, 10_000, 20_000, 66_000, 200_000] {
            let stop = m.sweep(0.0, 2.0, samples, &g).unwrap().run().stop;
            let SweepStop::LimitPosition(event) = &stop else { panic!("scale {scale}, {samples} samples: {stop:?}") };
            assert!((event.x[0] - limit).abs() < 1e-12, "{samples} samples: at {} not {limit}", event.x[0]);
        }
        // Two samples, the finest steps allowed, the limit late or early in the range.
        let fine = SweepConfig::default().with_max_halvings(60);
        for (from, to) in [(1.3, 1.4), (1.3715, 3.0), (0.0, limit + 1e-9)] {
            let g = m.position(from, &g).unwrap().0;
            let stop = m.sweep(from, to, 2, &g).unwrap().with_config(fine).run().stop;
            let SweepStop::LimitPosition(event) = &stop else { panic!("{from}..{to}: {stop:?}") };
            assert!((event.x[0] - limit).abs() < 1e-12, "{from}..{to}: at {}", event.x[0]);
        }
    }
}

#[test]
fn a_change_point_is_crossed_at_any_sample_count() {
    // A change-point four-bar (the shortest and longest links' sum equals the other two's:
    // 1 + 3 = 2 + 2): its links fold flat at phi = 2 pi, where the sweep crosses the singular
    // position and goes on.
    let m = FourBar { a: 1.0, b: 3.0, c: 2.0, d: 2.0 };
    let g = m.position(0.5, &m.guess(0.5)).unwrap().0;
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    for samples in [20, 20_000, 66_000] {
        let mut sweep = m.sweep(0.5, 7.0, samples, &g).unwrap().with_config(cfg);
        let run = sweep.by_ref().collect::<Result<Vec<_>, _>>();
        let states = run.unwrap_or_else(|e| panic!("{samples} samples: {e}"));
        assert_eq!(states.len(), samples);
        let crossings: Vec<_> = sweep.events().iter().filter(|e| e.kind == EventKind::SingularCrossing).collect();
        assert_eq!(crossings.len(), 1, "{samples} samples: {:?}", sweep.events());
        assert!((crossings[0].x[0] - std::f64::consts::TAU).abs() < 1e-9, "{:?}", crossings[0].x);
    }
}

#[test]
fn a_kink_is_passed_at_any_sample_count() {
    // The kink at phi = 1, early, in the middle and late in the range.
    let m = Kinked { k: 2.0 };
    for (from, to) in [(0.0, 2.0), (-0.7, 1.01), (0.99, 3.0)] {
        for samples in [9, 100_000] {
            let mut sweep = m.sweep(from, to, samples, &m.guess(from)).unwrap();
            let run = sweep.by_ref().collect::<Result<Vec<_>, _>>();
            let states = run.unwrap_or_else(|e| panic!("{from}..{to}, {samples} samples: {e}"));
            assert_eq!(states.len(), samples);
            let kinks: Vec<_> = sweep.events().iter().filter(|e| e.kind == EventKind::Kink).collect();
            assert_eq!(kinks.len(), 1, "{from}..{to}, {samples} samples: {:?}", sweep.events());
            assert!((kinks[0].x[0] - 1.0).abs() < 1e-9, "the kink at {}", kinks[0].x[0]);
        }
    }
}

#[test]
fn a_reach_is_found_at_any_sample_count_and_absurd_counts_are_refused() {
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let limit = stretched_limit(3.0, 2.0, 2.5, 4.0);
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    for samples in [2, 91, 20_000, 200_000] {
        let reach = m.reachable(0.0, 2.0, &g, samples).unwrap_or_else(|e| panic!("{samples} samples: {e}"));
        assert!((reach.to.phi - limit).abs() < 1e-12 && (reach.from.phi + limit).abs() < 1e-12, "{reach:?}");
        assert!(reach.to_event.is_some() && reach.from_event.is_some());
    }
    // No stretch has fewer than its two ends; more than an analysis takes is refused before
    // the first step (u32::MAX ran for minutes, holding every state).
    for samples in [0, 1, kinloop::analysis::MAX_SAMPLES + 1, u32::MAX as usize, usize::MAX] {
        let r = m.reachable(0.0, 2.0, &g, samples);
        assert!(matches!(r, Err(kinloop::Error::InvalidArgument(_))), "{samples}: {r:?}");
    }
}
