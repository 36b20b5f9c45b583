//! Branch points traced: pseudo-arclength continuation near a four-bar's change point, where
//! two solution curves meet (at the change point) or come within a gap far narrower than a
//! step (near it). The trace must follow its own curve, never step across the gap onto the
//! other, and must pass a true crossing on the curve its tangent carries on, saying so.
//!
//! The four-bar `a = 1, b = 3, c = 2.5` with the frame `d = b + c - a + eps`: at `eps = 0`
//! (all four in binary: the sums exact) the links lie in line at `phi = pi`, a change point.
//! For `eps > 0` the crank cannot turn (s + l > p + q): its curve turns back at limit
//! positions `pi - delta` where coupler and rocker lie in line, `delta` of order `sqrt(eps)`,
//! and the crank's other curve, past `pi + delta`, lies across a gap of `2 delta`. For
//! `eps < 0` it turns fully and its two curves pass each other across such a gap, each
//! changing its slope there. The default step `ds = 0.01` is far wider than those gaps: a
//! straight step lands on the other curve (the trace did so for `eps` below about `1e-6`).
//!
//! Then random four-bars, Grashof and not, traced over a turn of the crank from a random start:
//! every limit position where the law of cosines puts it, the assembly mode changing at limit
//! positions only, and the trace closed (its angles within whole turns) or out of its segment.

use kinloop::{EventKind, TraceConfig};
use kinloop_fixtures::{FourBar, FourBarUnknowns};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

use crate::support::{four_bar_joint, tol};

/// The four-bar `eps` from its change point, in the unit `unit`.
fn near_change_point(eps: f64, unit: f64) -> FourBar {
    let (a, b, c) = (1.0, 3.0, 2.5);
    FourBar { a: a * unit, b: b * unit, c: c * unit, d: (b + c - a + eps) * unit }
}

/// The crank's limit position below `pi` of `m` (`eps > 0`), where coupler and rocker lie in
/// line: `|BD| = b + c` with `B` the crank's tip. `1 + cos(phi) = ((a + d)^2 - (b + c)^2) /
/// (2 a d)`, from the difference of the sums rather than the cosine, which near `-1` would
/// lose the digits of `delta` (`pi - phi = 2 asin(sqrt((1 + cos phi) / 2))`).
fn limit_below_pi(m: &FourBar) -> f64 {
    let (sum, other) = (m.a + m.d, m.b + m.c);
    let one_plus_cos = (sum - other) * (sum + other) / (2.0 * m.a * m.d);
    PI - 2.0 * (0.5 * one_plus_cos).sqrt().asin()
}

/// The assembly mode at a traced state: the side of the coupler the rocker lies on,
/// `sin(gamma - beta)`. It changes sign only where coupler and rocker lie in line (a limit
/// position, or the change point).
fn mode(q: &[f64; 2]) -> f64 {
    (q[1] - q[0]).sin()
}

/// Every traced state satisfies the loop equations to the solver's tolerance (relative to the
/// mechanism's size).
fn on_the_curve(m: &FourBar, t: &kinloop::Traced<2, 1>, unit: f64) {
    for p in &t.points {
        let r = m.residual(p.x[0], &p.q.into());
        assert!(r.iter().all(|v| v.abs() <= 1e-10 * unit), "{m:?} at {}: {r:?}", p.x[0]);
    }
}

#[test]
fn near_a_change_point_the_trace_turns_at_its_limit_position_and_never_steps_across() {
    for unit in [1e-3, 1.0, 1e3] {
        for eps in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
            let m = near_change_point(eps, unit);
            let lim = limit_below_pi(&m);
            let g = m.position(0.5, &m.guess(0.5)).unwrap().0;
            let t = m.trace_curve(0.5, 0.5 + PI, &g, &TraceConfig::default()).unwrap();
            on_the_curve(&m, &t, unit);
            assert!(t.crossings.is_empty() && t.kinks.is_empty(), "eps {eps:e}: {t:?}");
            // The limit position below pi, where the trace turns back; the other lies below
            // the segment traced (`-pi + delta < 0.5 - pi`).
            assert_eq!(t.folds.len(), 1, "eps {eps:e}, unit {unit:e}: {:?}", t.folds);
            assert_close!(t.folds[0].x[0], lim, tol::LOCATED, "eps {eps:e}, unit {unit:e}");
            // Never past it: a state beyond `pi - delta` lies on the other curve.
            let beyond = t.points.iter().map(|p| p.x[0]).fold(f64::MIN, f64::max);
            assert!(beyond <= lim + tol::LOCATED, "eps {eps:e}: a state at {beyond}, past the limit {lim}");
            // One mode up to the limit position, the other after it (the input reversed).
            let turned = t.points.iter().position(|p| p.input_rate < 0.0).unwrap();
            let (before, after) = t.points.split_at(turned);
            let first = mode(&before[0].q).signum();
            assert!(before.iter().all(|p| mode(&p.q).signum() == first), "eps {eps:e}");
            assert!(after.iter().all(|p| mode(&p.q).signum() == -first), "eps {eps:e}");
        }
    }
}

#[test]
fn near_a_change_point_a_turning_crank_keeps_its_assembly_mode() {
    // eps < 0: the crank turns fully, its two curves passing each other within the gap; the
    // trace keeps to its own, in one assembly mode over the whole turn.
    for eps in [-1e-4, -1e-8, -1e-12] {
        let m = near_change_point(eps, 1.0);
        let g = m.position(0.5, &m.guess(0.5)).unwrap().0;
        let t = m.trace_curve(0.5, 0.5 + PI, &g, &TraceConfig::default()).unwrap();
        on_the_curve(&m, &t, 1.0);
        assert!(t.folds.is_empty() && t.crossings.is_empty(), "eps {eps:e}: {t:?}");
        assert!(t.points.iter().all(|p| p.input_rate > 0.0), "eps {eps:e}: the input reversed");
        assert!(t.points.last().unwrap().x[0] > PI + 0.4, "eps {eps:e}: it went on past pi");
        let first = mode(&t.points[0].q).signum();
        let switched = t.points.iter().find(|p| mode(&p.q).signum() != first);
        assert!(switched.is_none(), "eps {eps:e}: the mode changed at {:?}", switched.map(|p| p.x[0]));
    }
}

#[test]
fn at_a_change_point_the_trace_passes_the_crossing_and_lists_it() {
    // eps = 0: the curves cross at phi = pi, all links in line. The trace goes on along the
    // curve its tangent carries on, which changes the assembly mode there, and lists the
    // crossing, within a ten-thousandth of a step (`ds = 0.01`) of pi.
    for unit in [1e-3, 1.0, 1e3] {
        let m = near_change_point(0.0, unit);
        let g = m.position(0.5, &m.guess(0.5)).unwrap().0;
        let t = m.trace_curve(0.5, 0.5 + PI, &g, &TraceConfig::default());
        let t = t.unwrap_or_else(|e| panic!("unit {unit:e}: {e}"));
        on_the_curve(&m, &t, unit);
        assert!(t.folds.is_empty() && t.kinks.is_empty(), "unit {unit:e}: {t:?}");
        assert_eq!(t.crossings.len(), 1, "unit {unit:e}: {:?}", t.crossings);
        let crossing = &t.crossings[0];
        assert_eq!(crossing.kind, EventKind::SingularCrossing);
        assert!((crossing.x[0] - PI).abs() <= 1e-6, "unit {unit:e}: the crossing at {}", crossing.x[0]);
        assert!(t.points.iter().all(|p| p.input_rate > 0.0), "unit {unit:e}: the input reversed");
        let first = mode(&t.points[0].q).signum();
        for p in &t.points {
            // Off the change point (a step either side), each side in its own mode.
            if (p.x[0] - PI).abs() > 1e-3 {
                let expected = if p.x[0] < PI { first } else { -first };
                assert_eq!(mode(&p.q).signum(), expected, "unit {unit:e} at {}", p.x[0]);
            }
        }
    }
}

/// The crank angles in `[0, pi]` of the four-bar `m`'s limit positions, where coupler and
/// rocker lie in line (`|BD| = b + c` or `|b - c|`, by the law of cosines), the ones it has.
fn limit_angles(m: &FourBar) -> Vec<f64> {
    let cosines = [m.b + m.c, (m.b - m.c).abs()].map(|r| (m.a * m.a + m.d * m.d - r * r) / (2.0 * m.a * m.d));
    cosines.into_iter().filter(|c| c.abs() < 1.0).map(f64::acos).collect()
}

/// The distance from `x` to the nearer of `l` and `-l`, modulo a turn.
fn turn_distance(x: f64, l: f64) -> f64 {
    let d = |y: f64| {
        let r = (x - y).rem_euclid(TAU);
        r.min(TAU - r)
    };
    d(l).min(d(-l))
}

proptest! {
    #![proptest_config(crate::support::fixed_seed(3, 24))]

    #[test]
    fn random_four_bars_are_traced_with_their_limit_positions_and_one_mode_between(
        lengths in prop::array::uniform4(0.2f64..3.2),
        start in -PI..PI,
    ) {
        let [a, b, c, d] = lengths;
        let m = FourBar { a, b, c, d };
        let g = m.position(start, &m.guess(start));
        prop_assume!(g.is_ok());
        let g = g.unwrap().0;
        // The default step and the longest allowed (with which the curve passes near its start
        // on the other assembly mode, a step from it: not the curve closing).
        for ds in [TraceConfig::default().ds, TraceConfig::MAX_DS] {
        let t = m.trace_curve(start, start + PI, &g, &TraceConfig::default().with_ds(ds)).unwrap();
        on_the_curve(&m, &t, 1.0);
        prop_assert!(t.crossings.is_empty() && t.kinks.is_empty(), "{:?}", t);
        // It closes (its angles within whole turns: a crank-rocker driven by its rocker comes
        // back with its crank a turn on) or leaves the input's segment, long before the most
        // points (a few hundred to a thousand at the default step, up to 2,271 over some 5,000
        // random four-bars of a wider run).
        prop_assert!(!t.truncated && t.points.len() < 4000, "{} points", t.points.len());
        let limits = limit_angles(&m);
        for fold in &t.folds {
            let near = limits.iter().map(|&l| turn_distance(fold.x[0], l)).fold(f64::INFINITY, f64::min);
            prop_assert!(near <= tol::LOCATED, "a fold at {} against the limits {:?}", fold.x[0], limits);
        }
        // Coupler and rocker lie in line only at limit positions: the mode changes there only
        // (on a closed curve, between its last point and its first too: the step that closes
        // it can pass a limit position).
        let ends = t.closed.then(|| [t.points[t.points.len() - 1], t.points[0]]);
        let changes = t.points.windows(2).chain(ends.as_ref().map(|e| &e[..]))
            .filter(|w| (mode(&w[0].q) > 0.0) != (mode(&w[1].q) > 0.0))
            .count();
        prop_assert_eq!(changes, t.folds.len(), "folds at {:?}", t.folds.iter().map(|f| f.x[0]).collect::<Vec<_>>());
        }
    }
}

/// A rocking crank traced with the longest step: after its first limit position the curve
/// passes within a step of its start on the other assembly mode, the crank moving the other
/// way. That is not the curve closing (it was taken for it, and the second limit position was
/// never reached): the trace goes on through the second and closes where it started, the crank
/// moving as it did.
#[test]
fn a_curve_closes_only_where_it_started_moving_as_it_started() {
    let m = FourBar { a: 3.648, b: 3.23, c: 3.561, d: 3.293 };
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let t = m.trace_curve(0.0, PI, &g, &TraceConfig::default().with_ds(TraceConfig::MAX_DS)).unwrap();
    let limits = limit_angles(&m);
    assert_eq!(limits.len(), 1, "one limit angle in [0, pi], met at plus and minus it: {limits:?}");
    let mut folds: Vec<f64> = t.folds.iter().map(|f| f.x[0]).collect();
    folds.sort_by(f64::total_cmp);
    assert!(t.closed && folds.len() == 2, "closed {}, folds at {folds:?}", t.closed);
    assert!((folds[0] + limits[0]).abs() <= tol::LOCATED && (folds[1] - limits[0]).abs() <= tol::LOCATED, "{folds:?}");
}

/// A crank-rocker driven by its crank: its curve closes after one turn of the crank (the input's
/// whole turns count, as the angles' do), traced towards three turns or exactly one; it passes
/// no limit position, its crank goes round once and its angles come back to their start.
#[test]
fn a_cranks_curve_closes_after_one_turn() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let g = m.position(0.3, &m.guess(0.3)).unwrap().0;
    for to in [0.3 + 3.0 * TAU, 0.3 + TAU] {
        let t = m.trace_curve(0.3, to, &g, &TraceConfig::default()).unwrap();
        assert!(t.closed && !t.truncated && t.folds.is_empty(), "to {to}: closed {}", t.closed);
        let last = t.points.last().unwrap();
        // The last point listed is within a step (0.01 in the scaled coordinates) of closing.
        assert!((0.3 + TAU - last.x[0]).abs() < 0.02, "to {to}: the last point at {}", last.x[0]);
        assert!(t.points.iter().all(|p| p.input_rate > 0.0), "to {to}: the crank turned back");
        let start: [f64; 2] = g.into();
        for (u, (a, b)) in last.q.iter().zip(&start).enumerate() {
            assert!((a - b).abs() < 0.02, "to {to}: unknown {u} at {a} against {b}");
        }
    }
}

/// Far out, where the crank angle's doubles are a hundredth of a radian apart and more (1e14 and
/// on) against steps of 0.01, a trace completes or fails saying the input is too coarse, not
/// that the curve bifurcates or ends. A trace that completes has followed the crank-rocker's
/// curve: from its start to the end of its segment, every point's joint C (through the
/// coupler and through the rocker) where the construction puts it at the point's own input, on
/// the start's assembly mode (the crank turns without a limit position, so the mode never
/// changes).
#[test]
fn a_trace_far_out_completes_or_says_the_input_is_coarse() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let size = m.a + m.b + m.c + m.d;
    let mut completed = Vec::new();
    for from in [1e9, 1e12, 1e14, 1e15, 1e16] {
        let g = m.position(from, &m.guess(from)).unwrap().0;
        // The start's assembly mode: the side of B -> D that C lies on.
        let side = mode(&g.into()).signum();
        match m.trace_curve(from, from + PI, &g, &TraceConfig::default()) {
            Ok(t) => {
                let (first, last) = (t.points[0].x[0], t.points[t.points.len() - 1].x[0]);
                // From the start to within a step (0.01 in the scaled coordinates) of the end.
                assert!(first == from && (from + PI - last).abs() < 0.02, "{from}: traced {first} to {last}");
                completed.push(from);
                for p in &t.points {
                    let phi = p.x[0];
                    let (cx, cy) = four_bar_joint(m.a, m.b, m.c, m.d, phi, side).expect("a crank-rocker closes");
                    let via_b = (m.a * phi.cos() + m.b * p.q[0].cos(), m.a * phi.sin() + m.b * p.q[0].sin());
                    let via_d = (m.d + m.c * p.q[1].cos(), m.c * p.q[1].sin());
                    // The corrector relaxes its residual for the inputs' rounding (to 1e-9 at
                    // most): a point lies on the curve at an input within a few of its doubles'
                    // spacing (`eps |phi|` each) of the one listed, which moves C by at most
                    // `a / sin(mu)` times that, 1.4 `a` here (the transmission angle `mu` stays
                    // above 46 degrees): the tolerance allows about three spacings (measured:
                    // residuals of 1.4e-9 at 1e9 and 1.9e-9 at 1e12, 1e-15 near the origin).
                    let tol = 1e-9 * size + 4.0 * f64::EPSILON * phi.abs() * m.a;
                    for (x, y) in [via_b, via_d] {
                        let off = (x - cx).hypot(y - cy);
                        assert!(off <= tol, "{from}: at {phi} C = ({x}, {y}), construction ({cx}, {cy})");
                    }
                }
            }
            Err(e @ kinloop::Error::InputTooCoarse { .. }) => {
                let message = e.to_string();
                assert!(
                    message.contains("input `phi` is a double") && message.contains("whole turns"),
                    "{from}: {message}"
                )
            }
            Err(e) => panic!("{from}: {e}"),
        }
    }
    // Where the doubles are at most 1.2e-4 apart: the check above is not idle.
    assert!(completed.starts_with(&[1e9, 1e12]), "completed from {completed:?}");
}

/// Traces the Grashof-equal four-bar `[a, b, c, d]` (`a + c = b + d` to the rounding of the
/// sums, `d < a`: a drag-link whose coupler and rocker fold onto each other at `phi = 0`) over a
/// turn from `from` (on the assembly mode `side` of `circles`) through its change point at
/// `2 pi`: the trace passes the crossing, lists it within 1e-6 of the input (the trace's event
/// lies next to it, within a ten-thousandth of a step), and goes on in the other assembly mode.
fn traced_through_a_folded_change_point([a, b, c, d]: [f64; 4], side: f64, from: f64) {
    let m = FourBar { a, b, c, d };
    let (cx, cy) =
        crate::sweep_any_step::circles(a * from.cos(), a * from.sin(), b, d, 0.0, c, side).expect("the loop closes");
    let g = FourBarUnknowns { beta: (cy - a * from.sin()).atan2(cx - a * from.cos()), gamma: cy.atan2(cx - d) };
    let at = format!("a = {a}, from {from}");
    let t = m.trace_curve(from, from + TAU, &g, &TraceConfig::default()).unwrap_or_else(|e| panic!("{at}: {e}"));
    on_the_curve(&m, &t, 1.0);
    assert!(t.folds.is_empty() && t.kinks.is_empty(), "{at}: {t:?}");
    assert_eq!(t.crossings.len(), 1, "{at}: {:?}", t.crossings);
    let crossing = t.crossings[0].x[0];
    assert!((crossing - TAU).abs() <= 1e-6, "{at}: the crossing at {crossing}");
    let first = mode(&t.points[0].q).signum();
    for p in t.points.iter().filter(|p| (p.x[0] - crossing).abs() > 1e-2) {
        let expected = if p.x[0] < crossing { first } else { -first };
        assert_eq!(mode(&p.q).signum(), expected, "{at}: the mode at {}", p.x[0]);
    }
}

/// Four-bars whose coupler and rocker fold onto each other at the change point: near-kites
/// (`a - d = b - c` a hundredth of `a` or less, the first four) and two farther from a kite.
/// The trace stopped beside the change point ("cannot proceed"): the bordered system is
/// singular there too, the corrector failed at every short step, and a solve at fixed input
/// along the tangent found no point past it (or, once past, no way on from beside it; the
/// last: none, where only a step from before the change point leaves it). Over a thousand
/// random near-kites, 704 stopped so; over a thousand others, 497.
/// A near-kite whose corrector wandered 4.1 steps along the trace beside its change point,
/// where the wandering's events were judged beside each other up to 4: its crossing was listed
/// twice, 5.6e-9 of the input apart (found by a wider run of the random near-kites below).
#[test]
fn a_crossing_passed_while_wandering_beside_it_is_listed_once() {
    let (a, b, eps) = (
        1.628428552610771f64,
        1.628428552610771 * 2.2784590075530566,
        1.628428552610771 * 10f64.powf(-3.4741174571708764),
    );
    traced_through_a_folded_change_point([a, b, b - eps, a - eps], -1.0, 6.158540854410354);
}

/// A near-kite whose trace listed its crossing where it stood beside the branch point, then
/// stepped over it from the last point away from it (a step 13 of the trace's long): the walk
/// to that second listing was counted past the step, 19 steps from the first, and the crossing
/// was listed twice, 6e-9 of the input apart (found by a wider run of the random near-kites
/// below). An event's walk is now taken where it is listed: 1.5e-5 steps apart.
#[test]
fn a_crossing_listed_before_a_step_over_it_is_listed_once() {
    let a = 0.6352379835224309f64;
    let (b, eps) = (a * 3.7179756315729873, a * 10f64.powf(-3.939055416494993));
    traced_through_a_folded_change_point([a, b, b - eps, a - eps], -1.0, 2.456448804613307);
}

#[test]
fn a_folded_change_point_is_traced_through() {
    let cases: [([f64; 4], f64, f64); 6] = [
        ([1.266607216279367, 3.7755612711144795, 3.774674238389521, 1.2657201835544085], 1.0, 4.263126909498022),
        ([0.9461714217277681, 1.9862596795146599, 1.979999941290055, 0.9399116835031632], -1.0, 0.7495583467309817),
        ([1.5312443409941043, 4.338593097409808, 4.323713033456575, 1.516364277040872], 1.0, 4.879737032517155),
        ([1.0795666169118014, 1.4096455274386548, 1.40904957929016, 1.0789706687633067], -1.0, 4.053037443221149),
        ([1.0786805406893472, 3.742719712503189, 3.067518891907576, 0.40347972009373356], -1.0, 5.078501798990166),
        ([0.8730408074981932, 3.1245159611887936, 2.987373378525431, 0.7358982248348305], -1.0, 1.5751926257196416),
    ];
    for (lengths, side, from) in cases {
        traced_through_a_folded_change_point(lengths, side, from);
    }
}

proptest! {
    #![proptest_config(crate::support::fixed_seed(3, 48))]

    /// Random near-kite drag-links (as `near_kites_swept_at_any_density_cross_at_their_change_point`
    /// sweeps them) traced over a turn through their change point (before the trace passed such
    /// branch points, 704 of 1,000 stopped beside it; with the step over it from before it
    /// limited to a step's length, 3 of 1,000, one of them among these cases).
    #[test]
    fn random_near_kites_are_traced_through_their_change_point(
        a in 0.3f64..3.0,
        ratio in 1.2f64..4.0,
        log_eps in -4.0f64..-2.0,
        left in any::<bool>(),
        from in 0.1f64..(TAU - 0.1),
    ) {
        let (b, eps) = (a * ratio, a * 10f64.powf(log_eps));
        traced_through_a_folded_change_point([a, b, b - eps, a - eps], if left { 1.0 } else { -1.0 }, from);
    }
}

/// Offset slider-cranks whose rod is as long as the crank and the offset together (`l = r + e`):
/// at `phi = 3 pi / 2` crank and rod lie in line across the slide, a change point, where the
/// rod's side of the crank (`cos psi`) changes. Traced over a turn through it, the trace
/// stopped beside it ("cannot proceed"; 205 of 1,000 random such slider-cranks, none since).
#[test]
fn a_slider_crank_change_point_is_traced_through() {
    use crate::sweep_any_step::{Slider, SliderUnknowns};
    let cases: [(f64, f64, f64, f64, f64); 2] = [
        (0.6733424979912712, 0.19179325193419622, 0.6975511910205574, -0.281970995489115, 1.347032012909056),
        (0.539797774272353, 1.3612131446550568, 0.27235256809235286, 2.4475313508330236, -0.941319360734955),
    ];
    for (r, e, from, psi, x) in cases {
        let m = Slider { r, l: r + e, e };
        let at = format!("r = {r}, e = {e}");
        let t = m
            .trace_curve(from, from + TAU, &SliderUnknowns { psi, x }, &TraceConfig::default())
            .unwrap_or_else(|err| panic!("{at}: {err}"));
        for p in &t.points {
            let res = m.residual(p.x[0], &p.q.into());
            assert!(res.iter().all(|v| v.abs() <= 1e-10 * (m.r + m.l + m.e)), "{at} at {}: {res:?}", p.x[0]);
        }
        assert!(t.folds.is_empty() && t.kinks.is_empty(), "{at}: {t:?}");
        assert_eq!(t.crossings.len(), 1, "{at}: {:?}", t.crossings);
        let crossing = t.crossings[0].x[0];
        assert!((crossing - 1.5 * PI).abs() <= 1e-6, "{at}: the crossing at {crossing}");
        let first = t.points[0].q[0].cos().signum();
        for p in t.points.iter().filter(|p| (p.x[0] - crossing).abs() > 1e-2) {
            let expected = if p.x[0] < crossing { first } else { -first };
            assert_eq!(p.q[0].cos().signum(), expected, "{at}: the rod's side at {}", p.x[0]);
        }
    }
}

kinloop::mechanism! {
    /// Stephenson six-bar: the four-bar above, and a dyad driven from its coupler by `p` at
    /// `alpha` to it, links `e` (from the coupler's point) and `f` (from G = (gx, gy)).
    pub struct Stephenson {
        params a, b, c, d, p, alpha, e, f, gx, gy;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, delta = 0.5, eps = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop pfg: a @ phi + p @ (beta + alpha) + e @ delta == (gx, gy) + f @ eps;
    }
}

/// A six-bar `[a, b, c, d, .., gx, gy]` whose four-bar is a near-kite (`a + c = b + d` to the
/// rounding), traced from `from` toward `to` with `guess`: its points on the curve, and its
/// crossings, `count` of them, at its four-bar's change point (a whole turn of the input).
fn six_bar_traced(
    name: &str,
    t: Result<kinloop::Traced<4, 1>, kinloop::Error>,
    residual: impl Fn(f64, [f64; 4]) -> [f64; 4],
    count: usize,
) -> kinloop::Traced<4, 1> {
    let t = t.unwrap_or_else(|e| panic!("{name}: {e}"));
    for p in &t.points {
        let res = residual(p.x[0], p.q);
        assert!(res.iter().all(|v| v.abs() <= 1e-9), "{name} at {}: {res:?}", p.x[0]);
    }
    assert_eq!(t.crossings.len(), count, "{name}: {:?}", t.crossings);
    for c in &t.crossings {
        let off = c.x[0] - (c.x[0] / TAU).round() * TAU;
        assert!(off.abs() <= 1e-6, "{name}: a crossing at {}", c.x[0]);
    }
    t
}

/// Watt and Stephenson six-bars whose four-bar is a near-kite, traced through its change point.
/// They stopped beside it ("cannot proceed"; 43 of 4,000 random Watt six-bars so made, 35 of
/// 4,000 Stephenson ones): the trace tells a branch point by how near singular the whole
/// Jacobian is, and the smallest pivot of its elimination, where the four-bar's nearly zero row
/// meets the dyad's rows, stayed above the bound there (2e-6 a hundred-millionth of the input
/// from the change point, the singular values' ratio 3e-8), so none of the ways past a branch
/// point was tried.
#[test]
fn a_six_bars_four_bar_change_point_is_traced_through() {
    use crate::sweep_any_step::{SixBar, SixBarNewton};
    let watts: [([f64; 10], [f64; 4], f64, f64); 2] = [
        (
            [
                2.7271721244664917,
                0.47100562663913276,
                0.4516519817553889,
                2.707818479582748,
                0.35223135603588784,
                0.4499273047290573,
                1.9476723172619461,
                2.2718108484536823,
                -0.964593455652003,
                0.8054823132996933,
            ],
            [2.0709249575975046, -2.3256745418654887, -2.9309080499118667, -0.7501344955547973],
            -0.27565728485292773,
            6.0075280223266585,
        ),
        (
            [
                2.096455602014397,
                0.819153638369505,
                0.8083809800624524,
                2.0856829437073445,
                1.9480364302208353,
                -1.0367669487722826,
                2.4013303271727713,
                1.294904902754636,
                3.6033927130559364,
                -0.5621897503913109,
            ],
            [2.6176249555246005, -2.905264017575623, -0.8475019841511426, 3.017627355977954],
            -0.28981212343627405,
            -6.57299743061586,
        ),
    ];
    let opts = TraceConfig::default();
    for ([a, b, c, d, c2, alpha, e, f, gx, gy], guess, from, to) in watts {
        let m = SixBar { a, b, c, d, c2, alpha, e, f, gx, gy };
        let n = SixBarNewton { a, b, c, d, c2, alpha, e, f, gx, gy };
        let residual = |x: f64, q: [f64; 4]| m.residual(x, &q.into());
        six_bar_traced(&format!("Watt a = {a}"), m.trace_curve(from, to, &guess.into(), &opts), residual, 2);
        six_bar_traced(&format!("Watt a = {a}, Newton"), n.trace_curve(from, to, &guess.into(), &opts), residual, 2);
    }
    let [a, b, c, d, p, alpha, e, f, gx, gy] = [
        0.3211863764131118,
        1.4302680292108163,
        1.4292016762981896,
        0.3201200235004852,
        0.49228111640727823,
        1.9549298984191,
        1.5660772350185532,
        2.47737160350349,
        -1.2726774962543193,
        -1.0968747257721818,
    ];
    let m = Stephenson { a, b, c, d, p, alpha, e, f, gx, gy };
    let guess = [2.1663171675327373, 2.4930283961507835, -0.30573183472819265, -0.04199298957799924];
    let t = m.trace_curve(-1.6224726947705845, -7.9056580019501705, &guess.into(), &opts);
    six_bar_traced("Stephenson", t, |x, q| m.residual(x, &q.into()), 1);
}

/// A Watt six-bar whose dyad folds on either side of its four-bar's change point: its curve
/// passes the change point, turns at a limit position, passes it again (along the other curve
/// through the branch point, the positions the same to within a turn of the rocker), and turns
/// again. Both passes are crossings; the second was dropped as the corrector's wandering beside
/// the first, for its input was the same (466 of 2,000 random such six-bars lost one so).
#[test]
fn a_change_point_passed_twice_is_listed_twice() {
    use crate::sweep_any_step::SixBar;
    let [a, b, c, d, c2, alpha, e, f, gx, gy] = [
        1.7859889328043355,
        0.6081190513241579,
        0.6060849468898956,
        1.7839548283700732,
        0.4877743727701365,
        2.5656260028037448,
        3.0070073073704617,
        0.7513990798648118,
        3.3859746287292936,
        -2.5854206606413763,
    ];
    let m = SixBar { a, b, c, d, c2, alpha, e, f, gx, gy };
    let guess = [-2.7506211479362737, 2.9468700506931054, -1.2827248757020007, -2.1286628318626395];
    let t = m.trace_curve(0.19668695380575585, -6.08649835337383, &guess.into(), &TraceConfig::default());
    let t = six_bar_traced("Watt", t, |x, q| m.residual(x, &q.into()), 2);
    assert_eq!(t.folds.len(), 2, "{:?}", t.folds);
    assert!(t.closed, "the curve closes after its two limit positions");
}

/// A four-bar whose limit position lies 2.3e-3 of the input past the end of the segment traced
/// (`to`): the step that leaves the segment passes it with the longest step, and it was listed,
/// a limit position on no point of the curve traced. With `to` past it, it is listed, where
/// coupler and rocker lie in line. Another's lies 9e-4 past the segment's other end, and the
/// longest step passes it and comes back into the segment: the trace goes on, and lists it.
#[test]
fn a_limit_position_past_the_segments_end_is_not_listed() {
    let m = FourBar { a: 1.1092378867210653, b: 2.2886841306697563, c: 1.5444704921117398, d: 1.0299213853426523 };
    let start = -2.4337946450957926;
    let limit = limit_angles(&m)[0] - TAU;
    assert!(limit < start - PI && limit > start - PI - 1e-3, "{limit}");
    let g = m.position(start, &m.guess(start)).unwrap().0;
    let t = m.trace_curve(start, start + PI, &g, &TraceConfig::default().with_ds(TraceConfig::MAX_DS)).unwrap();
    assert!(t.closed, "{t:?}");
    assert!(t.folds.iter().any(|f| (f.x[0] - limit).abs() <= tol::LOCATED), "{:?}", t.folds);

    let m = FourBar { a: 1.3697209244230626, b: 2.548996946419844, c: 0.9467509258072133, d: 1.5930004647101867 };
    let start = 2.0054319428049556;
    let limit = TAU - limit_angles(&m)[0];
    assert!(limit > start + PI && limit < start + PI + 3e-3, "{limit}");
    let g = m.position(start, &m.guess(start)).unwrap().0;
    for ds in [TraceConfig::default().ds, TraceConfig::MAX_DS] {
        let t = m.trace_curve(start, start + PI, &g, &TraceConfig::default().with_ds(ds)).unwrap();
        assert!(t.folds.is_empty(), "ds {ds}: {:?}", t.folds);
        let t = m.trace_curve(start, start + PI + 0.1, &g, &TraceConfig::default().with_ds(ds)).unwrap();
        assert!(t.folds.first().is_some_and(|f| (f.x[0] - limit).abs() <= tol::LOCATED), "ds {ds}: {:?}", t.folds);
    }
}
