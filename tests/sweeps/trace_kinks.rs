//! Kinks traced: pseudo-arclength continuation passes a corner that a declaration holds on
//! purpose (`abs`, `clamp`) on the same branch, with the input going on, and lists it; a limit
//! position is still turned round and never taken for one; the end of a curve still stops it.
//! `reachable` and `sweep_at`, built on sweeps, pass a kink too.

use kinloop::{Error, EventKind, TraceConfig};
use kinloop_fixtures::FourBar;
use std::f64::consts::{PI, TAU};

use crate::support::tol;
use crate::sweep_kinks::{Kinked, UniformRise};
use crate::sweeps::limit_angles;

kinloop::mechanism! {
    /// A curve that ends: `s = sqrt(phi)` has no solution below `phi = 0`.
    pub struct Ending {
        params k;
        input phi;
        unknowns s = 1;
        eq root: s == k * sqrt(phi);
    }
}

kinloop::mechanism! {
    /// A slider that jumps: `s = k floor(phi)`, a step of `k` at every whole `phi`, with the
    /// curve's tangent the same on either side.
    pub struct Jumping {
        params k;
        input phi;
        unknowns s = 0;
        eq step: s == k * floor(phi);
    }
}

/// How far a traced point may lie from a law that is linear on either side of its corners, in
/// units of the law's size: the corrector's last Newton step on a linear law lands on it to the
/// rounding of its few operations (a few ulps of the size), and the state solved at a corner
/// is such a Newton solve too.
const ON_LAW: f64 = 1e-14;

/// How far a kink may lie from its corner, in the input (radians): it is located by bisection
/// down to the rounding of the input, far below this.
const AT_CORNER: f64 = 1e-12;

#[test]
fn the_abs_slider_is_traced_across_its_kink_at_every_scale() {
    // Metres, micrometres and a millionfold: the same corner at the same input, the same points.
    let mut inputs: Option<Vec<f64>> = None;
    for k in [2.0, 2e-6, 2e6] {
        let m = Kinked { k };
        let t = m.trace_curve(0.0, 2.0, &m.guess(0.0), &TraceConfig::default()).unwrap();
        assert!(t.folds.is_empty() && !t.closed && !t.truncated, "k = {k}: {:?}", t.folds);
        for p in &t.points {
            let phi = p.x[0];
            assert!((p.q[0] - k * (phi - 1.0).abs()).abs() <= ON_LAW * k, "k = {k}: s({phi}) = {}", p.q[0]);
            // The input goes on across the corner: it never reverses.
            assert!(p.input_rate > 0.0, "k = {k}: the input reversed at {phi}");
        }
        assert!(t.points.windows(2).all(|w| w[1].x[0] > w[0].x[0]), "k = {k}");
        // From the start to the end of the segment (the last point within a step of it).
        assert_eq!(t.points[0].x[0], 0.0);
        let last = t.points.last().unwrap().x[0];
        assert!(last > 1.9 && last <= 2.0, "k = {k}: the trace ended at {last}");
        assert_eq!(t.kinks.len(), 1, "k = {k}: {:?}", t.kinks);
        let kink = &t.kinks[0];
        assert_eq!(kink.kind, EventKind::Kink);
        assert!((kink.x[0] - 1.0).abs() <= AT_CORNER, "k = {k}: the kink at {}", kink.x[0]);
        assert!(kink.q[0].abs() <= ON_LAW * k, "k = {k}: s = {} at the kink", kink.q[0]);
        assert!(t.points.iter().any(|p| p.x[0] == kink.x[0]), "k = {k}: the corner is a point of the curve");
        // The steps are measured in scaled coordinates: the same inputs whatever the unit.
        let xs: Vec<f64> = t.points.iter().map(|p| p.x[0]).collect();
        match &inputs {
            None => inputs = Some(xs),
            Some(first) => {
                assert_eq!(first.len(), xs.len(), "k = {k}");
                assert!(first.iter().zip(&xs).all(|(a, b)| (a - b).abs() <= 1e-12), "k = {k}");
            }
        }
    }
    // Back across the corner: traced from the far side, towards smaller inputs.
    let m = Kinked { k: 2.0 };
    let t = m.trace_curve(2.0, 0.0, &m.guess(2.0), &TraceConfig::default()).unwrap();
    assert_eq!(t.kinks.len(), 1, "{:?}", t.kinks);
    assert!((t.kinks[0].x[0] - 1.0).abs() <= AT_CORNER, "the kink at {}", t.kinks[0].x[0]);
    assert!(t.points.windows(2).all(|w| w[1].x[0] < w[0].x[0]));
    assert!(t.points.iter().all(|p| (p.q[0] - 2.0 * (p.x[0] - 1.0).abs()).abs() <= ON_LAW * 2.0));
}

/// A corner exactly at the start of a trace or at the end of its segment is not one the curve
/// traced passes through: no trace lists it, whichever way it goes, at every scale, and none
/// ends outside its segment. Traced down to it, it was listed 2 ulps past the end, where the
/// last point lay too; traced up to it or from it downwards, it was listed at the end.
#[test]
fn a_kink_at_an_end_of_the_trace_is_not_listed() {
    for k in [2.0, 2e-6, 2e6] {
        let m = Kinked { k };
        for (from, to) in [(1.0, 0.0), (1.0, 2.0), (0.0, 1.0), (2.0, 1.0)] {
            let t = m.trace_curve(from, to, &m.guess(from), &TraceConfig::default()).unwrap();
            assert!(t.kinks.is_empty(), "k = {k}, {from} to {to}: {:?}", t.kinks);
            assert!(t.folds.is_empty() && t.crossings.is_empty() && !t.truncated, "k = {k}, {from} to {to}");
            let toward = |x: f64| (x - from) * (to - from).signum();
            for p in &t.points {
                let phi = p.x[0];
                assert!(toward(phi) >= 0.0 && toward(phi) <= toward(to), "k = {k}, {from} to {to}: a point at {phi}");
                assert!((p.q[0] - k * (phi - 1.0).abs()).abs() <= ON_LAW * k, "k = {k}: s({phi}) = {}", p.q[0]);
            }
            let last = t.points.last().unwrap().x[0];
            assert!(toward(last) > toward(to) - 0.02, "k = {k}, {from} to {to}: the trace ended at {last}");
            // Traced to the corner, it ends there.
            if to == 1.0 {
                assert_eq!(last, 1.0, "k = {k}, from {from}");
            }
        }
    }
}

kinloop::mechanism! {
    /// A lever `r` tilted by a slider's travel `x` through a corner: `sin(th) = |x - r| / (2 r)`,
    /// its slope `d th / dx` (about `1 / r`) jumping at `x = r`.
    pub struct TiltedByTravel {
        params r;
        input x;
        unknowns th = 0.3;
        eq tilt: r * sin(th) == 0.5 * abs(x - r);
    }
}

/// The kink is located at its corner at every size: the abs slider's (a length, its slopes
/// about the size) from `2e-300` to `2e300`, and the tilted lever's (an angle by a length input,
/// its slopes about the reciprocal of the size) up to `1e300`. The bisection that locates the
/// corner told its sides by the product of two slopes, which underflowed to zero below about
/// `1e-154` (the slider) or above `1e154` (the lever): every state was taken for the near
/// side, and the corner listed at the end of the step across it, about 1e-7 of the input past
/// it (8e-8 for the slider at `2e-300`). (The lever below `1e-154`:
/// `the_tilted_lever_below_the_accelerations_range_is_traced_as_at_size_1`.)
#[test]
fn a_kink_is_located_at_its_corner_at_every_size() {
    for k in [2e-300, 2e-160, 2e160, 2e300] {
        let m = Kinked { k };
        let t = m.trace_curve(0.0, 2.0, &m.guess(0.0), &TraceConfig::default()).unwrap();
        assert_eq!(t.kinks.len(), 1, "k = {k:e}: {:?}", t.kinks);
        assert!((t.kinks[0].x[0] - 1.0).abs() <= AT_CORNER, "k = {k:e}: the kink at {}", t.kinks[0].x[0]);
        for p in &t.points {
            let phi = p.x[0];
            assert!((p.q[0] - k * (phi - 1.0).abs()).abs() <= ON_LAW * k, "k = {k:e}: s({phi}) = {:e}", p.q[0]);
        }
    }
    for r in [1.0, 1e160, 1e300] {
        let m = TiltedByTravel { r };
        let x0 = 0.2 * r;
        let g = m.position(x0, &m.guess(x0)).unwrap().0;
        let t = m.trace_curve(x0, 1.8 * r, &g, &TraceConfig::default()).unwrap();
        assert_eq!(t.kinks.len(), 1, "r = {r:e}: {:?}", t.kinks);
        let corner = t.kinks[0].x[0] / r;
        assert!((corner - 1.0).abs() <= AT_CORNER, "r = {r:e}: the kink at {corner} of r");
        for p in &t.points {
            let x = p.x[0] / r;
            let off = p.q[0].sin() - 0.5 * (x - 1.0).abs();
            assert!(off.abs() <= tol::SOLVE, "r = {r:e}: sin(th) at {x} of r off the law by {off:e}");
        }
    }
}

#[test]
fn a_uniform_velocity_cam_law_is_traced_through_its_four_kinks() {
    let m = UniformRise { h: 12.0, a: 0.5, b: 1.2, c: 1.0 };
    let law = |phi: f64| {
        let ramp = |t: f64| m.h * t.clamp(0.0, 1.0);
        ramp((phi - m.a) / m.b) - ramp((phi - m.a - m.b - m.c) / m.b)
    };
    let t = m.trace_curve(0.0, TAU, &m.guess(0.0), &TraceConfig::default()).unwrap();
    assert!(t.folds.is_empty() && !t.closed && !t.truncated);
    for p in &t.points {
        let phi = p.x[0];
        assert!((p.q[0] - law(phi)).abs() <= ON_LAW * m.h, "s({phi}) = {} against {}", p.q[0], law(phi));
        assert!(p.input_rate > 0.0, "the input reversed at {phi}");
    }
    assert!(t.points.last().unwrap().x[0] > TAU - 0.1);
    let ends = [m.a, m.a + m.b, m.a + m.b + m.c, m.a + 2.0 * m.b + m.c];
    let at: Vec<f64> = t.kinks.iter().map(|e| e.x[0]).collect();
    assert_eq!(at.len(), 4, "{at:?}");
    for (at, end) in at.iter().zip(ends) {
        assert!((at - end).abs() <= AT_CORNER, "a kink at {at}, the ramp's end at {end}");
    }
    assert!(t.kinks.iter().all(|e| e.kind == EventKind::Kink));
}

#[test]
fn four_bars_are_traced_round_their_limit_positions_with_no_kink() {
    // A triple rocker of ordinary proportions, and one whose slopes change so fast towards its
    // limit positions that a sweep once took one for a corner (see `sweep_kinks.rs`).
    let rockers = [
        FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 },
        FourBar { a: 2.5300282018132223, b: 0.3, c: 2.453389628923286, d: 0.3 },
    ];
    for m in rockers {
        let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
        let t = m.trace_curve(0.0, PI, &g, &TraceConfig::default()).unwrap();
        assert!(t.closed, "{m:?}: the curve closes on itself");
        assert!(t.kinks.is_empty(), "{m:?}: {:?}", t.kinks);
        assert_eq!(t.folds.len(), 2, "{m:?}: {:?}", t.folds);
        let lim = limit_angles(&m).into_iter().fold(0.0f64, f64::max);
        let mut at: Vec<f64> = t.folds.iter().map(|f| f.x[0]).collect();
        at.sort_by(f64::total_cmp);
        assert_close!(at[0], -lim, tol::LOCATED, "{m:?}: {at:?} vs +-{lim}");
        assert_close!(at[1], lim, tol::LOCATED, "{m:?}: {at:?} vs +-{lim}");
        for p in &t.points {
            assert!(m.residual(p.x[0], &p.q.into()).iter().all(|v| v.abs() < 1e-10), "{m:?} at {}", p.x[0]);
        }
    }
}

#[test]
fn the_end_of_a_curve_still_stops_the_trace() {
    // `sqrt` ends the curve at phi = 0, with the Jacobian in `s` regular there: no kink.
    let m = Ending { k: 1.0 };
    let e = m.trace_curve(1.0, -1.0, &m.guess(1.0), &TraceConfig::default()).unwrap_err();
    match e {
        Error::Branch { message, .. } => assert!(message.contains("cannot proceed"), "{message}"),
        e => panic!("{e:?}"),
    }
}

#[test]
fn a_jump_in_the_positions_still_stops_the_trace() {
    // The positions jump by `k` at phi = 2: past it lies another piece of the solution set, a
    // finite distance from the curve followed, and the trace must not land on it (the
    // corrector's plane, square to the dwell, meets it however short the step). Started where
    // `s` is not zero, so that the trace's unit of `s` (taken from the equation's terms at the
    // start) is the law's size.
    for k in [2.0, 2e-6, 2e6] {
        let m = Jumping { k };
        let t = m.trace_curve(1.5, 2.5, &m.guess(1.5), &TraceConfig::default());
        match t {
            Err(Error::Branch { message, .. }) => assert!(message.contains("cannot proceed"), "{message}"),
            t => panic!("k = {k}: {:?}", t.map(|t| t.points.last().map(|p| (p.x[0], p.q[0])))),
        }
    }
}

#[test]
fn reachable_passes_a_kink() {
    // No limit position on the slider: the input reaches both ends of the range.
    for k in [2.0, 2e-6, 2e6] {
        let m = Kinked { k };
        let r = m.reachable(0.5, 1.0, &m.guess(0.5), 5).unwrap();
        assert_eq!((r.from.phi, r.to.phi), (-0.5, 1.5), "k = {k}");
        assert!(r.from_event.is_none() && r.to_event.is_none(), "k = {k}: {r:?}");
    }
}

#[test]
fn sweep_at_passes_a_kink_and_lists_it() {
    for k in [2.0, 2e-6, 2e6] {
        let m = Kinked { k };
        let inputs = [0.0, 0.25, 1.7, 2.0];
        let run = m.sweep_at(inputs, &m.guess(0.0));
        assert!(run.is_completed(), "k = {k}: {:?}", run.stop);
        assert_eq!(run.states.len(), inputs.len());
        for (st, phi) in run.states.iter().zip(inputs) {
            assert_eq!(st.input.phi, phi);
            assert!((st.q.s - k * (phi - 1.0).abs()).abs() <= ON_LAW * k, "k = {k}: s({phi}) = {}", st.q.s);
        }
        assert_eq!(run.events.len(), 1, "k = {k}: {:?}", run.events);
        assert_eq!(run.events[0].kind, EventKind::Kink);
        assert!((run.events[0].x[0] - 1.0).abs() < tol::LOCATED, "k = {k}: the kink at {}", run.events[0].x[0]);
    }
}

/// The tilted lever below about `1e-154` in size, where its acceleration analogs (about
/// `1 / r^2`) leave `f64`: traced across its corner as at size 1, though the states that judge
/// the corner cannot have them. It stopped at the corner with `Branch`, "the curve bifurcates or
/// ends here" (at `x = 0.99999998 r`). The references are independent of the trace at these
/// sizes: the corner at `x = r` and `sin(th) = |x - r| / (2 r)` in closed form, and the points
/// of the trace at size 1 (`r = 1`): the equation is the same in units of `r`, so the same
/// points, each solved to the rounding of `th` (about 0.3 rad) from inputs scaled by `r`, which
/// rounds them by an ulp: within a few eps of `th` (seen: 1.3) and of `x / r` (seen: 3).
#[test]
fn the_tilted_lever_below_the_accelerations_range_is_traced_as_at_size_1() {
    let trace = |r: f64| {
        let m = TiltedByTravel { r };
        let x0 = 0.2 * r;
        let g = m.position(x0, &m.guess(x0)).unwrap().0;
        m.trace_curve(x0, 1.8 * r, &g, &TraceConfig::default()).unwrap_or_else(|e| panic!("r = {r:e}: {e}"))
    };
    let one = trace(1.0);
    const FEW_EPS: f64 = 8.0 * f64::EPSILON;
    for r in [1e-160, 1e-200, 1e-300] {
        let t = trace(r);
        assert_eq!(t.kinks.len(), 1, "r = {r:e}: {:?}", t.kinks);
        let corner = t.kinks[0].x[0] / r;
        assert!((corner - 1.0).abs() <= AT_CORNER, "r = {r:e}: the kink at {corner} of r");
        assert_eq!(t.points.len(), one.points.len(), "r = {r:e}");
        for (p, p1) in t.points.iter().zip(&one.points) {
            let x = p.x[0] / r;
            assert!((x - p1.x[0]).abs() <= FEW_EPS, "r = {r:e}: x = {x} of r, {} at size 1", p1.x[0]);
            assert!((p.q[0] - p1.q[0]).abs() <= FEW_EPS, "r = {r:e}: th = {} at {x}, {} at size 1", p.q[0], p1.q[0]);
            let off = p.q[0].sin() - 0.5 * (x - 1.0).abs();
            assert!(off.abs() <= tol::SOLVE, "r = {r:e}: sin(th) at {x} of r off the law by {off:e}");
        }
    }
}
