//! Events located at every size: a mechanism whose lengths are `k` times another's has the same
//! angles and `k` times its lengths (its loop equations are homogeneous of degree one in the
//! lengths), so a sweep of it must stop at the same limit positions and pass the same singular
//! crossings, at the same inputs, with the positions there scaled by `k`. Checked at sizes from
//! `1e-300` to `1e300`: below `1e-8` (where the continuation that locates events once judged
//! its residuals against derivatives per unknown, not per unit of its scaled coordinates) and
//! beyond the closed forms' own sizes (`1e±144`, where each position is solved again by Newton
//! over the whole system), against the sweep at size 1 and against closed forms of the events
//! derived here (law of cosines, collinear links).
//!
//! Tolerances, from what the library promises of an event ([`kinloop::Event::x`]): the input
//! of a limit position or a crossing within `tol::LOCATED` (1e-9) of the input's unit of the
//! true one. At a limit position the continuation's augmented Jacobian `[J | dF/dx]` is
//! regular, so its located point (input and positions together) is pinned by the residual
//! tolerance, relative to the equations' magnitudes: the same point at every size to about
//! that, [`FOLD_TOL`]. A crossing is located from interpolated well-conditioned positions on
//! both sides, to the promise (measured: within 1.1e-12 of `pi` and `2 pi` at every size and
//! sample count here). A sample's position is pinned by Newton's residual tolerance
//! (`tol::SOLVE`, relative) to `tol::SOLVE / p` for its pivot ratio `p` (beyond the closed
//! forms' sizes, where Newton solves it; a closed form is exact to rounding).

use kinloop::{AtSingular, EventKind, Kin, Mechanism, Sweep, SweepConfig, SweepResult, SweepStop};
use kinloop_fixtures::{FourBar, SliderCrank};
use std::f64::consts::{PI, TAU};

use crate::support::{four_bar_limit, tol, wrap};

/// The sizes: size 1 (the reference) first, below `1e-8`, inside and beyond the closed forms'
/// sizes on both sides.
const SCALES: [f64; 7] = [1.0, 1e-12, 1e-100, 1e-300, 1e6, 1e100, 1e300];

/// The end of the sweeps through the change point: short of a whole turn (as the limit report's
/// tests sweep it), the crossing inside; not `TAU`.
#[allow(clippy::approx_constant)]
const TO: f64 = 6.28;

/// The input of a limit position at size `k` against size 1's, and its positions (angles in
/// radians, lengths over `k`): the residual tolerance's pinning of a point where the augmented
/// Jacobian is regular (`1e-12` relative), measured here at a few `1e-16`.
const FOLD_TOL: f64 = 1e-12;

/// The four-bar `dims` (crank `a`, coupler `b`, rocker `c`, frame `d`) at size `k`.
fn four_bar(dims: [f64; 4], k: f64) -> FourBar {
    FourBar { a: dims[0] * k, b: dims[1] * k, c: dims[2] * k, d: dims[3] * k }
}

/// The offset slider-crank `dims` (crank `r`, rod `l`, offset `e`) at size `k`; the fixture's
/// slider lies on the crank's `-x` side.
fn slider_crank(dims: [f64; 3], k: f64) -> SliderCrank {
    SliderCrank { r: dims[0] * k, l: dims[1] * k, e: dims[2] * k }
}

/// The whole sweep of `m` over `[from, to]` in `samples` from `guess`, configured by `cfg`.
fn run<M: Mechanism<2, 1, NO>, const NO: usize>(
    m: &M,
    (from, to): (f64, f64),
    samples: usize,
    guess: [f64; 2],
    cfg: SweepConfig,
) -> SweepResult<Kin<2, 1, NO>> {
    Sweep::<M, Kin<2, 1, NO>, 2, 1, NO>::new(m, [from], [to], samples, guess).unwrap().with_config(cfg).run()
}

/// A sweep toward a limit position of the input at every size: it stops there, its one event
/// a limit position at `limit` (its positions `at_limit`, angles and lengths of a unit-size
/// mechanism: `lengths` says which), after the same samples as at size 1, the same input and
/// the positions scaled.
fn stops_at_every_scale<M: Mechanism<2, 1, NO>, const NO: usize>(
    what: &str,
    at: impl Fn(f64) -> M,
    range: (f64, f64),
    limit: f64,
    at_limit: [f64; 2],
    lengths: [bool; 2],
) {
    // The largest differences from the closed form and from size 1.
    let (mut exact, mut spread) = (0.0f64, 0.0f64);
    for samples in [5, 181] {
        let one = at(1.0);
        let base = run(&one, range, samples, one.guess_flat(&[range.0]), SweepConfig::default());
        for k in SCALES {
            let what = format!("{what}, size {k:e}, {samples} samples");
            let m = at(k);
            let r = run(&m, range, samples, m.guess_flat(&[range.0]), SweepConfig::default());
            let SweepStop::LimitPosition(ev) = &r.stop else { panic!("{what}: {:?}", r.stop) };
            assert_eq!(r.events.len(), 1, "{what}: {:?}", r.events);
            assert_eq!((&r.events[0], ev.kind), (ev, EventKind::LimitPosition), "{what}");
            assert_eq!(r.states.len(), base.states.len(), "{what}: samples before the limit");
            assert!((ev.x[0] - limit).abs() <= tol::LOCATED, "{what}: at {} against {limit}", ev.x[0]);
            let one_x = base.events[0].x[0];
            (exact, spread) = (exact.max((ev.x[0] - limit).abs()), spread.max((ev.x[0] - one_x).abs()));
            assert!((ev.x[0] - one_x).abs() <= FOLD_TOL, "{what}: at {} against {one_x} at size 1", ev.x[0]);
            for u in 0..2 {
                let (got, one_q) = if lengths[u] {
                    (ev.q[u] / k, base.events[0].q[u])
                } else {
                    (wrap(ev.q[u] - at_limit[u]) + at_limit[u], base.events[0].q[u])
                };
                assert!((got - at_limit[u]).abs() <= tol::LOCATED, "{what}: q[{u}] {got} against {}", at_limit[u]);
                assert!((got - one_q).abs() <= FOLD_TOL, "{what}: q[{u}] {got} against {one_q} at size 1");
                (exact, spread) = (exact.max((got - at_limit[u]).abs()), spread.max((got - one_q).abs()));
            }
        }
    }
    eprintln!("{what}'s limit positions over sizes: {exact:.1e} from the closed form, {spread:.1e} from size 1");
}

/// A four-bar that cannot turn its input crank fully (`s + l = 2 + 4 > p + q = 2.5 + 3`) stops
/// at its limit positions, where coupler and rocker lie stretched in line. Derivation: crank
/// `a` at `A = 0` ends at `B = a (cos phi, sin phi)`, the frame's end is `D = (d, 0)`; stretched,
/// `|BD| = b + c`, and the law of cosines in the triangle `ABD` gives
/// `(b + c)^2 = a^2 + d^2 - 2 a d cos phi`, so `phi = +-acos((a^2 + d^2 - (b + c)^2) / (2 a d))`.
/// There `C` lies on `BD`, `b` from `B`: the coupler points from `B` to `D`
/// (`beta = atan2(-B_y, d - B_x)`), the rocker from `D` back to `B` (`gamma = beta + pi`).
#[test]
fn a_four_bars_limit_positions_at_every_scale() {
    let dims: [f64; 4] = [3.0, 2.0, 2.5, 4.0];
    let limit = four_bar_limit(dims[0], dims[3], dims[1] + dims[2]);
    for (range, phi) in [((0.0, PI), limit), ((0.0, -PI), -limit)] {
        let (bx, by) = (dims[0] * phi.cos(), dims[0] * phi.sin());
        let beta = (-by).atan2(dims[3] - bx);
        let at_limit = [beta, beta + PI];
        stops_at_every_scale("four-bar", |k| four_bar(dims, k), range, phi, at_limit, [false, false]);
    }
}

/// An offset slider-crank whose rod is too short for the crank to turn fully (`l < r + e`)
/// stops where the rod stands perpendicular to the guide. Derivation: the loop
/// `r @ phi == (x, e) + l @ psi` in `y` reads `r sin phi - e = l sin psi`, solvable while
/// `|r sin phi - e| <= l`; with `r = 1, l = 1.2, e = 0.5` only `r sin phi - e = -l` is reached,
/// at `sin phi = (e - l) / r`: `phi = asin((e - l) / r)` sweeping down from 0 and
/// `pi - asin((e - l) / r)` sweeping up. There `psi = -pi / 2` (the rod hangs from the slider
/// straight down to the crank pin) and, from the loop in `x`, `x = r cos phi`: a length
/// unknown in the event, scaled by the size.
#[test]
fn a_short_rod_slider_cranks_limit_positions_at_every_scale() {
    let dims: [f64; 3] = [1.0, 1.2, 0.5];
    let low = ((dims[2] - dims[1]) / dims[0]).asin();
    for (range, phi) in [((0.0, TAU), PI - low), ((0.0, -PI), low)] {
        let at_limit = [-PI / 2.0, dims[0] * phi.cos()];
        stops_at_every_scale("short rod", |k| slider_crank(dims, k), range, phi, at_limit, [false, true]);
    }
}

/// A Grashof-equal four-bar (`a + d = b + c`: 1 + 3.5 = 2 + 2.5) has one change point, where
/// all its links lie in line along the frame: at `phi = pi`, `|BD| = a + d = b + c`, so `C`
/// lies on `BD` at `b` from `B = (-a, 0)`, at `(b - a, 0)`: `beta = 0`, `gamma = pi` (at
/// `phi = 0`, `|BD| = d - a = 2.5` is neither `b + c` nor `|b - c|`). A sweep stopping at
/// crossings stops there at every size and sample count, after the same samples.
#[test]
fn a_grashof_equal_four_bar_stops_at_its_change_point_at_every_scale() {
    let dims = [1.0, 2.0, 2.5, 3.5];
    let range = (0.0, TO);
    let mut off = 0.0f64;
    for samples in [5, 73, 360] {
        let one = four_bar(dims, 1.0);
        let base = run(&one, range, samples, one.guess_flat(&[0.0]), SweepConfig::default());
        for k in SCALES {
            let what = format!("size {k:e}, {samples} samples");
            let m = four_bar(dims, k);
            let r = run(&m, range, samples, m.guess_flat(&[0.0]), SweepConfig::default());
            let SweepStop::SingularCrossing(ev) = &r.stop else { panic!("{what}: {:?}", r.stop) };
            assert_eq!(r.events.len(), 1, "{what}: {:?}", r.events);
            assert_eq!(r.events[0].kind, EventKind::SingularCrossing, "{what}");
            assert_eq!(r.states.len(), base.states.len(), "{what}: samples before the crossing");
            assert!((ev.x[0] - PI).abs() <= tol::LOCATED, "{what}: at {}", ev.x[0]);
            off = off.max((ev.x[0] - PI).abs());
            assert!((ev.x[0] - base.events[0].x[0]).abs() <= tol::LOCATED, "{what}: {ev:?} against {base:?}");
            // The positions move at rates of order one along the branch: within the location's
            // bound of the collinear links'.
            assert!(wrap(ev.q[0]).abs() <= tol::LOCATED && wrap(ev.q[1] - PI).abs() <= tol::LOCATED, "{what}: {ev:?}");
            // Every sample before it the one at size 1.
            for (s, b) in r.states.iter().zip(&base.states) {
                for u in 0..2 {
                    let bound = tol::SOLVE / s.health.min_pivot.min(b.health.min_pivot);
                    assert!((s.q[u] - b.q[u]).abs() <= bound, "{what}: {s:?} against {b:?}");
                }
            }
        }
    }
    eprintln!("Grashof-equal four-bar's change point over sizes: {off:.1e} from pi");
}

/// A parallelogram four-bar (`a = c = 1`, `b = d = 3`) passes both its change points in a turn
/// when told to go on: at `phi = pi` (`|BD| = a + d = b + c`) and at `phi = 2 pi`
/// (`|BD| = d - a = b - c`), its links in line. On its parallelogram branch the coupler stays
/// parallel to the frame and the rocker turns with the crank (`beta = 0`, `gamma = phi`
/// exactly: the loop closes for every `phi`), and the sweep goes on along it, the smooth
/// continuation through each crossing, where the kite's branch meets it. At every size and
/// sample count: both crossings, at the same inputs, and every sample on that branch, the
/// number of samples the one asked for.
#[test]
fn a_parallelograms_two_change_points_are_passed_at_every_scale() {
    let dims = [1.0, 3.0, 1.0, 3.0];
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let range = (0.3, 0.3 + TAU);
    let mut off = 0.0f64;
    for samples in [7, 181] {
        let base = run(&four_bar(dims, 1.0), range, samples, [0.0, 0.3], cfg);
        for k in SCALES {
            let what = format!("size {k:e}, {samples} samples");
            let r = run(&four_bar(dims, k), range, samples, [0.0, 0.3], cfg);
            assert!(r.is_completed(), "{what}: {:?}", r.stop);
            assert_eq!(r.states.len(), samples, "{what}");
            let kinds: Vec<EventKind> = r.events.iter().map(|e| e.kind).collect();
            assert_eq!(kinds, [EventKind::SingularCrossing; 2], "{what}: {:?}", r.events);
            for (e, (b, at)) in r.events.iter().zip(base.events.iter().zip([PI, TAU])) {
                assert!((e.x[0] - at).abs() <= tol::LOCATED, "{what}: {e:?}");
                off = off.max((e.x[0] - at).abs());
                assert!((e.x[0] - b.x[0]).abs() <= tol::LOCATED, "{what}: {e:?} against {b:?}");
                assert!(wrap(e.q[0]).abs() <= tol::LOCATED && wrap(e.q[1] - at).abs() <= tol::LOCATED, "{what}: {e:?}");
            }
            for s in &r.states {
                let bound = tol::SOLVE / s.health.min_pivot;
                assert!(wrap(s.q[0]).abs() <= bound && wrap(s.q[1] - s.x[0]).abs() <= bound, "{what}: {s:?}");
            }
        }
    }
    eprintln!("parallelogram's change points over sizes: {off:.1e} from pi and 2 pi");
}

/// The same parallelogram swept into its change point with `singular_pivot` lowered to 1e-9
/// (as to pass a slide brushing its pivot): its one event is the crossing. Within a hair of it
/// the two branches lie closer than a corner's gap, and the sweep's steps hopping between them
/// were taken for kinks (three, within 4e-9 degrees of it); a corner is now told only where the
/// pivot ratio is at least the default's.
#[test]
fn a_lowered_singular_pivot_takes_no_branch_hop_for_a_kink() {
    let cfg = SweepConfig::default().with_singular_pivot(1e-9);
    let (from, to) = (10f64.to_radians(), 370f64.to_radians());
    let r = run(&four_bar([1.0, 3.0, 1.0, 3.0], 1.0), (from, to), 37, [0.0, from], cfg);
    let kinds: Vec<EventKind> = r.events.iter().map(|e| e.kind).collect();
    assert_eq!(kinds, [EventKind::SingularCrossing], "{:?}", r.events);
    assert!((r.events[0].x[0] - PI).abs() <= tol::LOCATED, "{:?}", r.events);
}

/// The same parallelogram with its crank sampled every 10 degrees from 10: samples fall on both
/// change points (180 and 360 degrees, to the rounding of the samples' inputs), where no state
/// has analogs. Told to go on, the sweep gives each such sample as the first well-conditioned
/// state past it, at that state's own input (within a tenth of a degree past the sample), and
/// every other sample at its own input, all on the parallelogram branch; it stopped at the
/// first of them.
#[test]
fn a_parallelogram_sampled_on_its_change_points_goes_on() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let samples = 37;
    let (from, to) = (10f64.to_radians(), 370f64.to_radians());
    for k in [1e-3, 1.0, 1e3] {
        let r = run(&four_bar([1.0, 3.0, 1.0, 3.0], k), (from, to), samples, [0.0, from], cfg);
        assert!(r.is_completed(), "size {k}: {:?}", r.stop);
        assert_eq!(r.states.len(), samples, "size {k}");
        let kinds: Vec<EventKind> = r.events.iter().map(|e| e.kind).collect();
        assert_eq!(kinds, [EventKind::SingularCrossing; 2], "size {k}: {:?}", r.events);
        for (n, s) in r.states.iter().enumerate() {
            let sample = from + (to - from) * n as f64 / (samples - 1) as f64;
            let past = s.x[0] - sample;
            if n == 17 || n == 35 {
                // 180 and 360 degrees: past the change point, by less than a tenth of a degree.
                assert!(past > 0.0 && past < 0.1f64.to_radians(), "size {k}, sample {n}: {s:?}");
            } else {
                assert!(past.abs() <= 4.0 * f64::EPSILON * sample, "size {k}, sample {n}: {s:?}");
            }
            let bound = tol::SOLVE / s.health.min_pivot;
            assert!(wrap(s.q[0]).abs() <= bound && wrap(s.q[1] - s.x[0]).abs() <= bound, "size {k}: {s:?}");
        }
    }
}
