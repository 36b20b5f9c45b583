//! Kinks: a declaration with a corner on purpose (`abs`, `clamp`) is swept through it, the
//! corner recorded as an event where it is, every sample on the closed form.

use kinloop::EventKind;

kinloop::mechanism! {
    /// A slider whose position has a kink (abs): its velocity analog jumps at phi = 1.
    pub struct Kinked {
        params k;
        input phi;
        unknowns s = 0;
        eq kink: s == k * abs(phi - 1);
    }
}

kinloop::mechanism! {
    /// A follower lifted at uniform velocity: rise `h` from `a` over `b`, dwell, return over `b`
    /// from `a + b + c`, dwell. Its velocity analog jumps at the four ends of the ramps, where
    /// the acceleration is unbounded (the law designers avoid for that shock, and sweep to see
    /// it).
    pub struct UniformRise {
        params h, a, b, c;
        input phi;
        unknowns s = 0;
        eq lift: s == h * clamp((phi - a) / b, 0, 1) - h * clamp((phi - a - b - c) / b, 0, 1);
    }
}

kinloop::mechanism! {
    /// A rocker driven through a rod by a follower that rises by `h` at uniform velocity from
    /// `a` over `b` (a cam-linkage drive on the law of `UniformRise`): its angles come from the
    /// dyad's closed form, their velocity analogs jump at the ramp's ends; with a ramp of no
    /// width (`b = 0`) the follower steps by `h` at `a`.
    pub struct RampRocker {
        params h, a, b, l, c, dx, dy, y0;
        input phi;
        unknowns gamma = 1.6, psi = -0.25;
        let s = h * clamp((phi - a) / b, 0, 1);
        loop rod: (0, y0 + s) + l @ gamma == (dx, dy) + c @ psi;
    }
}

/// A [`RampRocker`] of the dwell cam's proportions, `scale` times as large, whose ramp rises
/// from 0.5 over `b` radians.
fn ramp_rocker(scale: f64, b: f64) -> RampRocker {
    RampRocker {
        h: 20.0 * scale,
        a: 0.5,
        b,
        l: 70.0 * scale,
        c: 40.0 * scale,
        dx: -40.0 * scale,
        dy: 140.0 * scale,
        y0: 60.0 * scale,
    }
}

/// How far the loop of `m` is from closing at the state `st` with the follower lifted by `s`:
/// the distance between the rod's end and the rocker's pin.
fn loop_gap(m: &RampRocker, st: &RampRockerState, s: f64) -> f64 {
    let (g, p) = (st.q.gamma, st.q.psi);
    let gap_x = m.l * g.cos() - m.dx - m.c * p.cos();
    let gap_y = m.y0 + s + m.l * g.sin() - m.dy - m.c * p.sin();
    gap_x.hypot(gap_y)
}

#[test]
fn closed_form_angles_past_the_kinks_of_a_ramp_are_on_the_loop() {
    for scale in [1e-6, 1.0, 1e6] {
        let m = ramp_rocker(scale, 1.0);
        let mut sweep = m.sweep(0.0, 2.0, 9, &m.guess(0.0)).unwrap();
        for st in sweep.by_ref() {
            let st = st.unwrap();
            // The loop closes at every sample: the follower's pin where the law puts it.
            let s = m.h * ((st.input.phi - m.a) / m.b).clamp(0.0, 1.0);
            let gap = loop_gap(&m, &st, s);
            assert!(gap <= 1e-13 * m.l, "{scale} at {}: {gap}", st.input.phi);
        }
        let kinks: Vec<f64> = sweep.events().iter().filter(|e| e.kind == EventKind::Kink).map(|e| e.x[0]).collect();
        assert_eq!(kinks.len(), 2, "{scale}: {:?}", sweep.events());
        for (at, end) in kinks.iter().zip([0.5, 1.5]) {
            assert!((at - end).abs() < 1e-9, "{scale}: a kink at {at}, the ramp's end at {end}");
        }
    }
}

/// A law of zero width steps the follower by `h` between two samples, its velocity analogs zero
/// on both sides: the dyad's closed form gives the angles on either side on the same assembly
/// mode, and nothing but their distance from the prediction tells. The sweep stops at the step
/// (it passed it unseen, the angles jumping by half a radian between two samples), and says
/// what may step.
#[test]
fn a_law_that_steps_stops_the_sweep_where_it_steps() {
    for scale in [1e-6, 1.0, 1e6] {
        let m = ramp_rocker(scale, 0.0);
        let items: Vec<_> = m.sweep(0.05, 1.05, 11, &m.guess(0.05)).unwrap().collect();
        // The samples below the step, 0.05 to 0.45, and then the stop.
        assert_eq!(items.len(), 6, "{scale}");
        assert!(items[..5].iter().all(Result::is_ok), "{scale}");
        let Some(Err(stopped)) = items.last() else { panic!("{scale}: the sweep went on") };
        let kinloop::Error::Branch { message, at } = &stopped else { panic!("{scale}: {stopped:?}") };
        assert!(message.contains("piecewise function"), "{message}");
        assert!((at.inputs[0].1 - m.a).abs() < 1e-9, "{scale}: stopped at {at:?}");
    }
}

#[test]
fn a_kink_between_samples_is_swept_through_and_recorded() {
    // Micrometres and metres: the same kink at the same input.
    for k in [2.0, 2e-6, 2e6] {
        let m = Kinked { k };
        let states: Vec<_> = m.sweep(0.0, 2.0, 8, &m.guess(0.0)).unwrap().collect::<Result<_, _>>().unwrap();
        assert_eq!(states.len(), 8);
        for st in &states {
            let phi = st.input.phi;
            assert!((st.q.s - k * (phi - 1.0).abs()).abs() <= 1e-15 * k, "k = {k}: s({phi}) = {}", st.q.s);
            assert_eq!(st.dq.s, k * (phi - 1.0).signum(), "k = {k} at {phi}");
        }
        let sweep = {
            let mut sw = m.sweep(0.0, 2.0, 8, &m.guess(0.0)).unwrap();
            for st in sw.by_ref() {
                st.unwrap();
            }
            sw
        };
        let kinks: Vec<_> = sweep.events().iter().filter(|e| e.kind == EventKind::Kink).collect();
        assert_eq!(kinks.len(), 1, "k = {k}: {:?}", sweep.events());
        assert!((kinks[0].x[0] - 1.0).abs() < 1e-9, "k = {k}: the kink at {}", kinks[0].x[0]);
        assert_eq!(sweep.events().len(), 1);
    }
}

#[test]
fn a_kink_on_a_sample_is_swept_through() {
    // The analog at the corner itself is one side's (or the other's, by how the derivative of
    // `abs` at zero is taken): either way the sweep goes on, with every sample on the law.
    let m = Kinked { k: 2.0 };
    for samples in [3, 5, 9, 17] {
        let states: Vec<_> = m.sweep(0.0, 2.0, samples, &m.guess(0.0)).unwrap().collect::<Result<_, _>>().unwrap();
        assert_eq!(states.len(), samples);
        for st in &states {
            assert!((st.q.s - 2.0 * (st.input.phi - 1.0).abs()).abs() <= 1e-15, "{samples} samples");
        }
    }
}

#[test]
fn a_uniform_velocity_cam_law_sweeps_a_whole_turn() {
    use std::f64::consts::TAU;
    let m = UniformRise { h: 12.0, a: 0.5, b: 1.2, c: 1.0 };
    let law = |phi: f64| {
        let ramp = |t: f64| m.h * t.clamp(0.0, 1.0);
        ramp((phi - m.a) / m.b) - ramp((phi - m.a - m.b - m.c) / m.b)
    };
    let mut sweep = m.sweep(0.0, TAU, 361, &m.guess(0.0)).unwrap();
    let mut n = 0;
    for st in sweep.by_ref() {
        let st = st.unwrap();
        let phi = st.input.phi;
        assert!((st.q.s - law(phi)).abs() <= 1e-14 * m.h, "s({phi}) = {} against {}", st.q.s, law(phi));
        n += 1;
    }
    assert_eq!(n, 361);
    let ends = [m.a, m.a + m.b, m.a + m.b + m.c, m.a + 2.0 * m.b + m.c];
    let kinks: Vec<f64> = sweep.events().iter().filter(|e| e.kind == EventKind::Kink).map(|e| e.x[0]).collect();
    assert_eq!(kinks.len(), 4, "{kinks:?}");
    for (at, end) in kinks.iter().zip(ends) {
        assert!((at - end).abs() < 1e-9, "a kink at {at}, the ramp's end at {end}");
    }
}

#[test]
fn a_limit_position_is_no_kink() {
    use kinloop_fixtures::FourBar;
    use std::f64::consts::TAU;
    // Its slopes grow without bound towards the limit, and over the sweep's smallest step they
    // change by a finite amount with the positions continuous and the pivot above the sweep's
    // threshold: a corner by those tests alone (this four-bar was recorded as one).
    let m = FourBar { a: 2.5300282018132223, b: 0.3, c: 2.453389628923286, d: 0.3 };
    let phi0 = 0.7156732456026534;
    let modes = m.assembly_modes(phi0).unwrap();
    assert_eq!(modes.len(), 2);
    for mode in modes {
        let mut sweep = m.sweep(phi0, phi0 + TAU, 9, &mode.q).unwrap();
        let stopped = sweep.by_ref().find_map(Result::err);
        assert!(
            matches!(stopped, Some(kinloop::Error::SweepStopped { kind: EventKind::LimitPosition, .. })),
            "{stopped:?}"
        );
        assert!(sweep.events().iter().all(|e| e.kind == EventKind::LimitPosition), "{:?}", sweep.events());
    }
}

/// A step of random size and direction at a random input, swept at random sample counts (from
/// two samples to four hundred over three radians, either way) and sizes: the sweep stops at the
/// step every time, never past it; a steep ramp in its place (a width of a thousandth to a
/// tenth of a radian) is no step, and is swept through with every sample on the loop.
#[test]
fn a_step_of_a_law_stops_every_sweep_at_it_and_a_steep_ramp_none() {
    let mut rng = crate::support::Xorshift(0x2545_f491_4f6c_dd1d);
    let (mut stopped, mut ramps) = (0, 0);
    for case in 0..200 {
        let scale = [1e-6, 1.0, 1e6][case % 3];
        let lift = if rng.unit() < 0.5 { -1.0 } else { 1.0 } * 0.05 * 400f64.powf(rng.unit());
        let a = 0.3 + 2.4 * rng.unit();
        let samples = 2 + (399.0 * rng.unit().powi(2)) as usize;
        let (from, to) = if rng.unit() < 0.5 { (0.0, 3.0) } else { (3.0, 0.0) };
        // A sample on the step itself stands on one side of it or the other: not this test's.
        let spacing = 3.0 / (samples - 1) as f64;
        if ((a - from).abs() / spacing).fract().min(1.0 - ((a - from).abs() / spacing).fract()) < 1e-6 {
            continue;
        }
        let ramp = rng.unit() < 0.3;
        let width = if ramp { 10f64.powf(-3.0 + 2.0 * rng.unit()) } else { 0.0 };
        let m = RampRocker { h: lift * scale, a, ..ramp_rocker(scale, width) };
        let what = format!("case {case}: {m:?}, {samples} samples from {from} to {to}");
        let items: Vec<_> = m.sweep(from, to, samples, &m.guess(from)).unwrap().collect();
        let on_loop = |st: &RampRockerState| {
            let s =
                m.h * if ramp { ((st.input.phi - m.a) / m.b).clamp(0.0, 1.0) } else { f64::from(st.input.phi >= m.a) };
            loop_gap(&m, st, s) <= 1e-12 * m.l
        };
        if ramp {
            assert_eq!(items.len(), samples, "{what}: {:?}", items.last());
            assert!(items.iter().all(|st| st.as_ref().is_ok_and(on_loop)), "{what}");
            ramps += 1;
            continue;
        }
        let (last, before) = items.split_last().expect("a first sample");
        match last {
            Err(kinloop::Error::Branch { message, at }) => {
                assert!(message.contains("piecewise function"), "{what}: {message}");
                assert!((at.inputs[0].1 - a).abs() < 1e-9, "{what}: stopped at {at:?}");
            }
            // The search for the step landed on it: `(phi - a) / 0` is `0 / 0` there.
            Err(kinloop::Error::Domain { at, .. }) => assert_eq!(at.inputs[0].1, a, "{what}"),
            last => panic!("{what}: {last:?}"),
        }
        for st in before {
            let st = st.as_ref().expect("samples before the step");
            assert!((st.input.phi < a) == (from < a) && on_loop(st), "{what}: {st:?}");
        }
        stopped += 1;
    }
    assert!(stopped >= 100 && ramps >= 40, "{stopped} steps, {ramps} ramps");
}

/// A corner exactly at an end of the range is at an end of the path swept, one of its sides
/// only within the range: no sweep lists it, whichever way it goes, at every scale (the state
/// at the corner carries the analogs of `abs` at 0 taken as +1). A sweep from the corner listed
/// it at `1 - 9e-14` going down and not going up; one to it, at 1 coming up and not coming down.
#[test]
fn a_kink_at_an_end_of_the_range_is_listed_by_no_sweep() {
    for k in [2.0, 2e-6, 2e6] {
        let m = Kinked { k };
        for (from, to) in [(1.0, 0.0), (1.0, 2.0), (0.0, 1.0), (2.0, 1.0)] {
            for samples in [2, 5] {
                let mut sweep = m.sweep(from, to, samples, &m.guess(from)).unwrap();
                let states: Vec<_> = sweep.by_ref().collect::<Result<_, _>>().unwrap();
                assert_eq!(states.len(), samples, "k = {k}, {from} to {to}");
                for st in &states {
                    let phi = st.input.phi;
                    assert!((st.q.s - k * (phi - 1.0).abs()).abs() <= 1e-15 * k, "k = {k}: s({phi}) = {}", st.q.s);
                }
                assert!(sweep.events().is_empty(), "k = {k}, {from} to {to}, {samples}: {:?}", sweep.events());
            }
        }
        // A hundredth of the input inside either end, the corner is the range's, though a sweep
        // of few halvings (the smallest step a sixteenth of a quarter radian) brackets it within
        // its first or its last step (two smallest steps long at most).
        let coarse = kinloop::SweepConfig::default().with_max_halvings(4);
        for (from, to) in [(0.99, 2.0), (1.01, 0.0), (0.0, 1.01), (2.0, 0.99)] {
            let mut sweep = m.sweep(from, to, 2, &m.guess(from)).unwrap().with_config(coarse);
            assert_eq!(sweep.by_ref().filter(Result::is_ok).count(), 2, "k = {k}, {from} to {to}");
            let kinks = sweep.events();
            assert_eq!(kinks.len(), 1, "k = {k}, {from} to {to}: {kinks:?}");
            assert!((kinks[0].x[0] - 1.0).abs() <= 2.0 * 0.25 / 16.0, "k = {k}, {from} to {to}: {kinks:?}");
        }
    }
}

/// A corner at an input of `sweep_at` between two others lies inside the path through them:
/// listed once, at that input, whichever way the path goes; at the path's first or last input,
/// as at a sweep's end, not at all.
#[test]
fn sweep_at_lists_a_kink_at_an_input_once_whichever_way() {
    for k in [2.0, 2e-6, 2e6] {
        let m = Kinked { k };
        for inputs in [&[0.0, 1.0, 2.0][..], &[2.0, 1.0, 0.0], &[0.0, 1.0, 1.0, 2.0], &[2.0, 1.0, 1.0, 0.0]] {
            let run = m.sweep_at(inputs.iter().copied(), &m.guess(inputs[0]));
            assert!(run.is_completed(), "k = {k}: {:?}", run.stop);
            assert_eq!(run.states.len(), inputs.len());
            assert_eq!(run.events.len(), 1, "k = {k}, {inputs:?}: {:?}", run.events);
            let kink = &run.events[0];
            assert_eq!((kink.kind, kink.x[0]), (EventKind::Kink, 1.0), "k = {k}, {inputs:?}");
            assert!(kink.q[0].abs() <= 1e-15 * k, "k = {k}, {inputs:?}: s = {} at the kink", kink.q[0]);
        }
        for inputs in [[1.0, 2.0], [2.0, 1.0], [0.0, 1.0], [1.0, 0.0]] {
            let run = m.sweep_at(inputs, &m.guess(inputs[0]));
            assert!(run.is_completed(), "k = {k}: {:?}", run.stop);
            assert!(run.events.is_empty(), "k = {k}, {inputs:?}: {:?}", run.events);
        }
    }
}
