//! The runtime's path algorithms on run-time models (curve tracing, the reachable range,
//! `sweep_at`, the assembly modes, scans over parameter sets) against the same algorithms on
//! the compiled mechanisms of the same declarations (the fixtures of `parity.rs`), and each
//! against an independent reference: the closed-form geometry of the four-bar and the
//! slider-crank.
//!
//! One implementation of each algorithm runs over two kernels. Where the operations are the
//! same they agree to the last bit: curve tracing and the assembly-mode search call the
//! kernels' solves and Jacobians only (libm's sines and cosines in both), and the algorithms
//! built on sweeps do so against a compiled mechanism whose sweep steps take libm's sines and
//! cosines too (`Libm`, as in `sweeps.rs`). Against the compiled mechanism's own sweep, whose
//! steps advance the sines and cosines by rotation (a few units in the last place off libm's),
//! they agree to `REL` (`sweeps.rs`'s tolerance).

#[macro_use]
mod common;

use common::{Libm, read, set};
use kinloop::{Event, Kin, Mechanism, NewtonConfig, ScanConfig, ScanStart, TraceConfig};
use kinloop_fixtures as fx;
use kinloop_model::{Model, ParamScanConfig, ParamScanStart};
use kinloop_runtime::dims::KinBuf;
use std::f64::consts::{PI, TAU};

/// Relative agreement with the compiled mechanism's own sweep (see `sweeps.rs`: the kernels'
/// 1e-15 with room for the rotation cache's few ulps amplified by a step's Newton correction).
const REL: f64 = 1e-13;

/// Agreement of a located limit position with its closed form: the continuation locates the
/// fold of `d sigma / ds` to about 1e-15 of the arclength, where the input is stationary; its
/// input is then exact to the square of that, but the position (a square root of the distance
/// to the fold) only to about 3e-8 (sqrt 1e-15). The input is checked to 1e-9, well within.
const FOLD_INPUT: f64 = 1e-9;

/// Agreement of a solved position with the closed form (both to rounding of angles of order
/// one, through an `acos`/`atan2` of well-conditioned arguments away from the limit positions).
const CLOSED_FORM: f64 = 1e-12;

fn four_bar(a: f64, b: f64, c: f64, d: f64) -> (fx::FourBar, Model) {
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", a), ("b", b), ("c", c), ("d", d)]);
    (fx::FourBar { a, b, c, d }, m)
}

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    a.iter().zip(b).map(|(x, y)| (x - y).abs() / scale).fold(0.0, f64::max)
}

/// Every array of a compiled state and a run-time state, flattened in the same order.
fn arrays<const N: usize, const NI: usize, const NO: usize>(c: &Kin<N, NI, NO>) -> Vec<Vec<f64>> {
    let f2 = |v: &[[f64; NI]]| v.iter().flatten().copied().collect::<Vec<f64>>();
    let f3 = |v: &[[[f64; NI]; NI]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
    vec![c.x.to_vec(), c.q.to_vec(), f2(&c.dq), f3(&c.d2q), c.out.to_vec(), f2(&c.dout), f3(&c.d2out)]
}

fn buf_arrays(r: &KinBuf) -> Vec<Vec<f64>> {
    [&r.x, &r.q, &r.dq, &r.d2q, &r.out, &r.dout, &r.d2out].iter().map(|v| v.to_vec()).collect()
}

/// The largest relative difference of two states' arrays (0 exactly when equal to the bit),
/// with their determinant signs equal.
fn state_diff<const N: usize, const NI: usize, const NO: usize>(c: &Kin<N, NI, NO>, r: &KinBuf) -> f64 {
    assert_eq!(c.health.det_signs, r.health.det_signs, "determinant signs at {:?}", c.x);
    arrays(c).iter().zip(buf_arrays(r)).map(|(a, b)| rel_diff(a, &b)).fold(0.0, f64::max)
}

/// An event without its block description (a run-time model's carries none).
fn strip(e: &[Event]) -> Vec<(kinloop::EventKind, Vec<f64>, f64, Vec<f64>)> {
    e.iter().map(|e| (e.kind, e.x.clone(), e.tau, e.q.clone())).collect()
}

/// The four-bar's two assembly modes at input `phi` from the geometry alone: the joint C where
/// the circle of radius `b` about A = a (cos phi, sin phi) meets the circle of radius `c` about
/// D = (d, 0); `(beta, gamma)` for each, `None` where the circles do not meet.
fn four_bar_modes(a: f64, b: f64, c: f64, d: f64, phi: f64) -> Option<[[f64; 2]; 2]> {
    let (ax, ay) = (a * phi.cos(), a * phi.sin());
    let (ux, uy) = (d - ax, -ay);
    let l = ux.hypot(uy);
    let along = (b * b - c * c + l * l) / (2.0 * l);
    let h2 = b * b - along * along;
    if h2 < 0.0 {
        return None;
    }
    let h = h2.sqrt();
    let (ex, ey) = (ux / l, uy / l);
    Some([1.0, -1.0].map(|side| {
        let (cx, cy) = (ax + along * ex - side * h * ey, ay + along * ey + side * h * ex);
        [(cy - ay).atan2(cx - ax), cy.atan2(cx - d)]
    }))
}

/// The distance of two angles modulo whole turns.
fn angle_gap(x: f64, y: f64) -> f64 {
    let g = (x - y).rem_euclid(TAU);
    g.min(TAU - g)
}

/// The distance of `q` from the nearer of the closed-form assembly modes at `phi`.
fn closed_form_gap(dims: (f64, f64, f64, f64), phi: f64, q: &[f64]) -> f64 {
    let (a, b, c, d) = dims;
    let modes = four_bar_modes(a, b, c, d, phi).expect("the loop closes");
    modes.iter().map(|m| angle_gap(m[0], q[0]).max(angle_gap(m[1], q[1]))).fold(f64::INFINITY, f64::min)
}

/// The inputs of a four-bar's limit positions, from the geometry: where the coupler and the
/// output lie in line, `|A - D| = b + c` or `|b - c|`, i.e. `a^2 + d^2 - 2 a d cos(phi)` equal
/// to its square (the angles in `[0, pi]`; the others are their negatives).
fn four_bar_limits(a: f64, b: f64, c: f64, d: f64) -> [f64; 2] {
    let at = |len: f64| ((a * a + d * d - len * len) / (2.0 * a * d)).acos();
    [at((b - c).abs()), at(b + c)]
}

// ---------------------------------------------------------------------------------------------
// Curve tracing

/// A triple rocker (a non-Grashof four-bar: no link turns fully) driven by a rocking link:
/// the input rocks between two limit positions, and the traced curve closes through both.
#[test]
fn traced_curves_equal_the_compiled_ones_to_the_last_bit() {
    let dims = (2.0, 3.0, 2.5, 4.0);
    let (compiled, mut model) = four_bar(dims.0, dims.1, dims.2, dims.3);
    let guess = compiled.guess_flat(&[0.0]);
    let opts = TraceConfig::default().with_ds(0.02);
    let c = compiled.trace_curve(0.0, 3.0, &guess.into(), &opts).unwrap();
    let r = model.trace_curve(&[0.0], &[3.0], &guess, &opts).unwrap();
    assert!(c.closed && r.closed, "closed: compiled {}, run time {}", c.closed, r.closed);
    assert_eq!(c.points.len(), r.points.len());
    for (a, b) in c.points.iter().zip(&r.points) {
        assert_eq!((&a.x[..], &a.q[..], a.input_rate), (&b.x.0[..], &b.q.0[..], b.input_rate));
    }
    assert_eq!(strip(&c.folds), strip(&r.folds));

    // Independently: the two folds at the closed-form limit positions (coupler and output in
    // line, stretched: `|A - D| = b + c` at `phi = +-acos(..)`; `|b - c|` is out of reach), and
    // every point on one of the two closed-form assembly modes at its input.
    let hi = four_bar_limits(dims.0, dims.1, dims.2, dims.3)[1];
    assert_eq!(r.folds.len(), 2, "{:?}", r.folds);
    let mut at: Vec<f64> = r.folds.iter().map(|f| f.x[0]).collect();
    at.sort_by(f64::total_cmp);
    for (found, exact) in at.iter().zip([-hi, hi]) {
        assert!((found - exact).abs() < FOLD_INPUT, "limit position at {found}, closed form {exact}");
    }
    let worst = r.points.iter().map(|p| closed_form_gap(dims, p.x[0], &p.q.0)).fold(0.0, f64::max);
    // Each point is corrected once more after meeting the residual tolerance (1e-12 of the
    // loop's size): rounding-level where the Jacobian is regular (4.8e-14 measured), looser only
    // by the inverse of its smallest singular value at a point near a fold. 1e-9 leaves a point
    // a thousandth of `ds` from a fold room.
    assert!(worst < 1e-9, "largest distance from the closed form {worst:e}");
    eprintln!(
        "traced {} points, limit positions at {at:?} (closed form +-{hi}), {worst:e} from the closed form",
        r.points.len()
    );
}

/// A trace started at a limit position, where no analog exists (a slider-crank whose crank
/// rocks: its rod's `asin` meets 1 exactly, pivot ratio 0), from the positions alone: the
/// run-time model's is the compiled one to the last bit, and the start is its first limit
/// position, the other where `r sin phi - e = -l`.
#[test]
fn a_trace_from_a_limit_position_equals_the_compiled_one() {
    let (r, l, e) = (2.0, 1.5, 0.3);
    let compiled = fx::SliderCrank { r, l, e };
    let mut model = read(fx::SLIDER_CRANK_TEXT);
    set(&mut model, &[("r", r), ("l", l), ("e", e)]);
    let at = ((e + l) / r).asin();
    let guess = [std::f64::consts::FRAC_PI_2, r * at.cos()];
    let unchecked = NewtonConfig::default().with_singular_tol(0.0);
    assert!(compiled.kinematics_with(at, &guess.into(), &unchecked).is_err(), "no analog at the limit");
    let opts = TraceConfig::default().with_ds(0.02);
    let c = compiled.trace_curve(at, -3.0, &guess.into(), &opts).unwrap();
    let t = model.trace_curve(&[at], &[-3.0], &guess, &opts).unwrap();
    assert!(c.closed && t.closed, "closed: compiled {}, run time {}", c.closed, t.closed);
    assert_eq!(c.points.len(), t.points.len());
    for (a, b) in c.points.iter().zip(&t.points) {
        assert_eq!((&a.x[..], &a.q[..], a.input_rate), (&b.x.0[..], &b.q.0[..], b.input_rate));
    }
    assert_eq!(strip(&c.folds), strip(&t.folds));
    let folds: Vec<f64> = t.folds.iter().map(|f| f.x[0]).collect();
    assert_eq!(folds.len(), 2, "{folds:?}");
    assert_eq!(folds[0], at);
    assert!((folds[1] - ((e - l) / r).asin()).abs() < FOLD_INPUT, "{folds:?}");
}

/// With two inputs the path runs through the input plane: the five-bar's trace is the compiled
/// one, point by point.
#[test]
fn a_trace_through_two_inputs_equals_the_compiled_one() {
    let compiled = fx::FiveBar::default();
    let mut model = read(fx::FIVE_BAR_TEXT);
    let (from, to) = ([0.0, 0.4], [TAU, 0.4 + 1.0]);
    let guess = compiled.guess_flat(&from);
    let opts = TraceConfig::default().with_ds(0.05).with_max_points(400);
    let c = kinloop::paths::trace::trace_curve(&compiled, from, to, guess, &opts);
    let r = model.trace_curve(&from, &to, &guess, &opts);
    match (c, r) {
        (Ok(c), Ok(r)) => {
            assert!(c.points.len() > 10, "{} points", c.points.len());
            assert_eq!((c.points.len(), c.closed), (r.points.len(), r.closed));
            for (a, b) in c.points.iter().zip(&r.points) {
                assert_eq!((&a.x[..], &a.q[..], a.input_rate), (&b.x.0[..], &b.q.0[..], b.input_rate));
            }
            assert_eq!(strip(&c.folds), strip(&r.folds));
        }
        (c, r) => panic!("compiled {:?}, run time {:?}", c.map(|t| t.points.len()), r.map(|t| t.points.len())),
    }
}

declared! {
    KINKED_TEXT =>
    /// A slider whose stroke has a corner on purpose: `s = k |phi - 1|`, its velocity analog
    /// jumping from `-k` to `k` at `phi = 1`.
    pub struct Kinked {
        params k = 2.0;
        input phi;
        unknowns s = 0;
        eq kink: s == k * abs(phi - 1);
    }
}

/// A run-time model's trace passes a kink (here through `abs`) as the compiled mechanism's
/// does, point by point, and lists it where the corner is.
#[test]
fn a_trace_passes_a_kink_as_the_compiled_one_does() {
    for k in [2.0, 2e-6] {
        let compiled = Kinked { k };
        let mut model = read(KINKED_TEXT);
        set(&mut model, &[("k", k)]);
        let opts = TraceConfig::default();
        let c = compiled.trace_curve(0.0, 2.0, &compiled.guess_flat(&[0.0]).into(), &opts).unwrap();
        let r = model.trace_curve(&[0.0], &[2.0], &[0.0], &opts).unwrap();
        assert_eq!(c.points.len(), r.points.len(), "k = {k}");
        for (a, b) in c.points.iter().zip(&r.points) {
            assert_eq!((&a.x[..], &a.q[..], a.input_rate), (&b.x.0[..], &b.q.0[..], b.input_rate), "k = {k}");
        }
        assert_eq!(strip(&c.kinks), strip(&r.kinks), "k = {k}");

        // Independently: one kink at the corner (located by bisection to the rounding of the
        // input), and every point on the law to the rounding of a Newton step on a law linear
        // on either side of the corner (a few ulps of its size).
        assert_eq!(r.kinks.len(), 1, "k = {k}: {:?}", r.kinks);
        assert!((r.kinks[0].x[0] - 1.0).abs() <= 1e-12, "k = {k}: the kink at {}", r.kinks[0].x[0]);
        assert!(r.folds.is_empty());
        assert!(r.points.last().unwrap().x.0[0] > 1.9, "k = {k}: the trace goes on past the corner");
        for p in &r.points {
            let phi = p.x.0[0];
            assert!((p.q.0[0] - k * (phi - 1.0).abs()).abs() <= 1e-14 * k, "k = {k}: s({phi}) = {}", p.q.0[0]);
        }
    }
}

/// The gear lever at a tenth of a nanometre (carrier 2e-10, planet pin 1.3e-10): a run-time
/// model's trace is the compiled one, point by point, and every point lies on the closed form
/// (`phi = alpha + atan2(-l_p sin 3 alpha, l_c + l_p cos 3 alpha)`, `s` the pin's distance from
/// O) as it does at unit size. The length `s` enters its loop's rows with a derivative of about
/// one at any size: judged against that instead of the rows' magnitude, the corrector accepted
/// points 1e-8 rad off the curve.
#[test]
fn a_small_gear_levers_trace_is_the_compiled_one_and_on_its_closed_form() {
    let (l_c, l_p) = (2e-10, 1.3e-10);
    let compiled = fx::gear_lever::GearLever { l_c, l_p, u: 3.0 };
    let mut model = read(fx::gear_lever::GEAR_LEVER_TEXT);
    set(&mut model, &[("l_c", l_c), ("l_p", l_p)]);
    let guess = compiled.position(0.0, &compiled.guess(0.0)).unwrap().0;
    let opts = TraceConfig::default();
    let c = compiled.trace_curve(0.0, TAU, &guess, &opts).unwrap();
    let r = model.trace_curve(&[0.0], &[TAU], &[guess.s, guess.phi], &opts).unwrap();
    assert!(c.closed && r.closed, "closed: compiled {}, run time {}", c.closed, r.closed);
    assert_eq!(c.points.len(), r.points.len());
    for (a, b) in c.points.iter().zip(&r.points) {
        assert_eq!((&a.x[..], &a.q[..], a.input_rate), (&b.x.0[..], &b.q.0[..], b.input_rate));
    }
    let mut worst = 0.0f64;
    for p in &r.points {
        let alpha = p.x.0[0];
        let (n, d) = (-l_p * (3.0 * alpha).sin(), l_c + l_p * (3.0 * alpha).cos());
        let phi = alpha + n.atan2(d);
        worst = worst.max((p.q.0[1] - phi).abs()).max((p.q.0[0] - n.hypot(d)).abs() / (l_c + l_p));
    }
    // Each point is corrected once more after meeting the residual tolerance: rounding of the
    // angle (about 5e-15 measured, at this size as at unit size), amplified by the size over the
    // pin's least distance from O (about 5) at most.
    eprintln!("traced {} points of the small gear lever, {worst:.1e} from the closed form", r.points.len());
    assert!(worst < 5e-14, "largest distance from the closed form {worst:e}");
}

// ---------------------------------------------------------------------------------------------
// Reachable ranges

#[test]
fn reachable_ranges_equal_the_compiled_ones_and_the_closed_form() {
    let dims = (1.5, 3.0, 1.0, 3.2);
    let (compiled, mut model) = four_bar(dims.0, dims.1, dims.2, dims.3);
    let guess = compiled.guess_flat(&[1.2]);
    let r = model.reachable(&[1.2], &[1.5], &guess, 41).unwrap();
    // Bit for bit against the compiled mechanism with libm's sines in its steps.
    let l = kinloop::paths::reach::reachable(&Libm(compiled), [1.2], [1.5], guess, 41).unwrap();
    assert_eq!((&l.from[..], &l.to[..]), (&r.from.0[..], &r.to.0[..]));
    let events = |a: &Option<Event>, b: &Option<Event>| strip(a.as_slice()) == strip(b.as_slice());
    assert!(events(&l.from_event, &r.from_event) && events(&l.to_event, &r.to_event), "{l:?}\n{r:?}");
    // Against its own sweep, to the sweeps' agreement.
    let c = compiled.reachable(1.2, 1.5, &guess.into(), 41).unwrap();
    let (c_from, c_to): ([f64; 1], [f64; 1]) = (c.from.into(), c.to.into());
    assert!(rel_diff(&c_from, &r.from.0) <= REL && rel_diff(&c_to, &r.to.0) <= REL, "{c:?}\n{r:?}");

    // Both ends are limit positions, at the closed form's inputs.
    let [lo, hi] = four_bar_limits(dims.0, dims.1, dims.2, dims.3);
    assert!(r.from_event.is_some() && r.to_event.is_some(), "{r:?}");
    assert!((r.from.0[0] - lo).abs() < FOLD_INPUT, "from {} (closed form {lo})", r.from.0[0]);
    assert!((r.to.0[0] - hi).abs() < FOLD_INPUT, "to {} (closed form {hi})", r.to.0[0]);
    eprintln!("reach [{}, {}], closed form [{lo}, {hi}]", r.from.0[0], r.to.0[0]);

    // Within the range: no event, the ends of the searched stretch.
    let r = model.reachable(&[1.2], &[0.1], &guess, 5).unwrap();
    assert!(r.from_event.is_none() && r.to_event.is_none());
    assert_eq!((r.from.0[0], r.to.0[0]), (1.2 - 0.1, 1.2 + 0.1));
}

/// Where a four-bar that cannot be assembled at pi does: the stretch the compiled mechanism
/// finds with libm's sines in its steps, bit for bit, and the closed form's limit positions;
/// where it assembles nowhere, `None` on both.
#[test]
fn where_it_assembles_equals_the_compiled_mechanism_and_the_closed_form() {
    let dims = (1.5, 3.0, 1.0, 3.2);
    let (compiled, mut model) = four_bar(dims.0, dims.1, dims.2, dims.3);
    assert!(model.solve(&[3.0]).is_err());
    let r = model.assembly_near(&[3.0], 360).unwrap().expect("it assembles");
    let l = kinloop::paths::assembles::assembly_near(&Libm(compiled), [3.0], 360).unwrap().expect("it assembles");
    assert_eq!(
        (&l.found[..], &l.reach.from[..], &l.reach.to[..]),
        (&r.found.0[..], &r.reach.from.0[..], &r.reach.to.0[..])
    );
    let [lo, hi] = four_bar_limits(dims.0, dims.1, dims.2, dims.3);
    assert!((r.reach.from.0[0] - lo).abs() < FOLD_INPUT && (r.reach.to.0[0] - hi).abs() < FOLD_INPUT, "{r:?}");
    assert!(!r.turns_fully());
    let (_, mut apart) = four_bar(1.0, 1.0, 1.0, 5.0);
    assert_eq!(apart.assembly_near(&[0.0], 360).unwrap(), None);
    // Inputs not of the model's size: an error, not a panic.
    for at in [&[][..], &[0.0, 1.0][..]] {
        assert!(matches!(model.assembly_near(at, 360), Err(kinloop::Error::InvalidArgument(_))), "{at:?}");
        assert!(matches!(model.assembly_along(at, &[1.0], 9), Err(kinloop::Error::InvalidArgument(_))), "{at:?}");
    }
    // Along a path from outside into the stretch: the compiled mechanism's entry, bit for bit.
    let r = model.assembly_along(&[3.0], &[7.0], 50).unwrap().expect("it enters");
    let l = kinloop::paths::assembles::assembly_along(&Libm(compiled), [3.0], [7.0], 50).unwrap().expect("it enters");
    assert_eq!((l.fraction, &l.at[..], &l.sample[..]), (r.fraction, &r.at.0[..], &r.sample.0[..]));
    // Its links reach between the distances 2 and 4 from the crank pin to the rocker's pivot,
    // on either side of the frame: the first stretch met past pi is the mirror of `[lo, hi]`.
    assert!((r.at.0[0] - (TAU - hi)).abs() < FOLD_INPUT, "{r:?} against {}", TAU - hi);
}

// ---------------------------------------------------------------------------------------------
// States at given inputs

/// Unevenly spaced, repeated and far-apart inputs (a crank-rocker driven by its crank): the
/// states are the compiled ones, and the positions the closed form's on the starting branch.
#[test]
fn states_at_given_inputs_equal_the_compiled_ones_and_the_closed_form() {
    let dims = (1.0, 3.0, 2.5, 3.2);
    let (compiled, mut model) = four_bar(dims.0, dims.1, dims.2, dims.3);
    let inputs = [0.0, 0.01, 0.01, 1.7, 1.75, 4.0, 2.0, 9.0, -3.0];
    let guess = compiled.guess_flat(&[0.0]);
    let r = model.sweep_at(inputs.iter().map(|&x| [x]), &guess).unwrap();
    assert!(r.is_completed(), "{:?}", r.stop);
    assert_eq!(r.states.len(), inputs.len());
    let l = Libm(compiled).sweep_at_flat(&inputs, guess);
    assert_eq!(l.states.len(), r.states.len());
    for (a, b) in l.states.iter().zip(&r.states) {
        assert_eq!(state_diff(a, b), 0.0, "at {:?}", a.x);
    }
    let c = kinloop::paths::sweep_at::sweep_at_of(&kinloop_runtime::Compiled(&compiled), inputs.map(|x| [x]), guess);
    for (a, b) in c.states.iter().zip(&r.states) {
        assert!(state_diff(a, b) <= REL, "at {:?}", a.x);
    }

    // Independently: on one closed-form branch throughout (the one of the start), at the
    // inputs asked for.
    let modes = four_bar_modes(dims.0, dims.1, dims.2, dims.3, 0.0).unwrap();
    let branch = (0..2).min_by(|&i, &j| {
        let gap = |m: [f64; 2]| angle_gap(m[0], r.states[0].q[0]).max(angle_gap(m[1], r.states[0].q[1]));
        gap(modes[i]).total_cmp(&gap(modes[j]))
    });
    let branch = branch.unwrap();
    let mut worst = 0.0f64;
    for (s, &x) in r.states.iter().zip(&inputs) {
        assert_eq!(s.x[0], x);
        let m = four_bar_modes(dims.0, dims.1, dims.2, dims.3, x).unwrap()[branch];
        let gap = angle_gap(m[0], s.q[0]).max(angle_gap(m[1], s.q[1]));
        assert!(gap < CLOSED_FORM, "at {x}: {gap:e} from the closed form");
        worst = worst.max(gap);
    }
    eprintln!("sweep_at: {} states, {worst:e} from the closed form", r.states.len());
}

/// A rocker input meets its limit position between two inputs: the same stop, the same event,
/// the same states before it, in both.
#[test]
fn states_at_given_inputs_stop_at_the_same_limit_position() {
    let dims = (1.5, 3.0, 1.0, 3.2);
    let (compiled, mut model) = four_bar(dims.0, dims.1, dims.2, dims.3);
    let inputs = [1.2, 1.5, 2.5, 1.0];
    let guess = compiled.guess_flat(&[1.2]);
    let r = model.sweep_at(inputs.iter().map(|&x| [x]), &guess).unwrap();
    let l = Libm(compiled).sweep_at_flat(&inputs, guess);
    assert_eq!(r.states.len(), 2);
    assert_eq!(l.states.len(), 2);
    for (a, b) in l.states.iter().zip(&r.states) {
        assert_eq!(state_diff(a, b), 0.0);
    }
    assert_eq!(strip(&l.events), strip(&r.events));
    let ev = r.stop.event().expect("a limit position");
    assert_eq!(ev.kind, kinloop::EventKind::LimitPosition);
    let hi = four_bar_limits(dims.0, dims.1, dims.2, dims.3)[1];
    assert!((ev.x[0] - hi).abs() < FOLD_INPUT, "at {} (closed form {hi})", ev.x[0]);
    assert!(r.into_result().is_err());
}

trait SweepAtFlat {
    fn sweep_at_flat(&self, inputs: &[f64], guess: [f64; 2]) -> kinloop::SweepResult<Kin<2, 1, 2>>;
}

impl<M: Mechanism<2, 1, 2>> SweepAtFlat for Libm<M> {
    fn sweep_at_flat(&self, inputs: &[f64], guess: [f64; 2]) -> kinloop::SweepResult<Kin<2, 1, 2>> {
        kinloop::paths::sweep_at::sweep_at_of(&kinloop_runtime::Compiled(self), inputs.iter().map(|&x| [x]), guess)
    }
}

// ---------------------------------------------------------------------------------------------
// Assembly modes

#[test]
fn assembly_modes_equal_the_compiled_ones_and_the_closed_form() {
    let dims = (1.0, 3.0, 2.5, 3.2);
    let (compiled, mut model) = four_bar(dims.0, dims.1, dims.2, dims.3);
    for phi in [0.0, 0.7, 2.0, 4.5] {
        let c = kinloop::paths::modes::assembly_modes(&compiled, &[phi], 64, &NewtonConfig::default()).unwrap();
        let r = model.assembly_modes(&[phi]).unwrap();
        assert_eq!(c.len(), r.len(), "at {phi}");
        for (a, b) in c.iter().zip(&r) {
            assert_eq!(state_diff(a, b), 0.0, "at {phi}");
        }
        // Independently: elbow up and elbow down, the two intersections of the circles.
        assert_eq!(r.len(), 2, "at {phi}");
        let exact = four_bar_modes(dims.0, dims.1, dims.2, dims.3, phi).unwrap();
        for m in exact {
            let gap =
                r.iter().map(|s| angle_gap(m[0], s.q[0]).max(angle_gap(m[1], s.q[1]))).fold(f64::INFINITY, f64::min);
            assert!(gap < CLOSED_FORM, "at {phi}: mode {m:?} found to {gap:e}");
            eprintln!("assembly mode at {phi}: {gap:e} from the closed form");
        }
    }
    // Where the loop cannot close, none.
    let (_, mut far) = four_bar(1.0, 1.0, 1.0, 5.0);
    assert!(far.assembly_modes(&[0.0]).unwrap().is_empty());
    // The compiled mechanisms' other fixtures: the same modes, bit for bit.
    let mut m = read(fx::FIVE_BAR_TEXT);
    let c = kinloop::paths::modes::assembly_modes(&fx::FiveBar::default(), &[0.3, 0.4], 64, &NewtonConfig::default())
        .unwrap();
    let r = m.assembly_modes(&[0.3, 0.4]).unwrap();
    assert_eq!(c.len(), r.len());
    assert!(c.len() >= 2, "{} modes", c.len());
    for (a, b) in c.iter().zip(&r) {
        assert_eq!(state_diff(a, b), 0.0);
    }
}

// ---------------------------------------------------------------------------------------------
// Scans over parameter sets

/// The slider's stroke of offset slider-cranks: the run-time scan over parameter sets equals
/// the compiled scan over the same designs (to the last bit with libm's sines in both), and the
/// closed form `sqrt((l + r)^2 - e^2) - sqrt((l - r)^2 - e^2)`.
#[test]
fn scans_over_parameter_sets_equal_the_compiled_ones_and_the_closed_form() {
    // The last set cannot be assembled at phi = 0 (offset beyond the crank and rod's reach).
    let sets = [[1.0, 3.0, 0.4], [0.5, 2.0, 0.0], [1.2, 4.0, -0.7], [1.0, 1.5, 3.0]];
    let samples = 721;
    let mut model = read(fx::SLIDER_CRANK_TEXT);
    let init = |_: &[f64]| (f64::INFINITY, f64::NEG_INFINITY);
    let fold = |(lo, hi): (f64, f64), _: &[f64], k: &KinBuf| (lo.min(k.q[1]), hi.max(k.q[1]));
    let spec = ParamScanConfig::new(&[0.0], &[TAU], samples);
    let r = model.scan(&["r", "l", "e"], &sets, &spec, init, fold);

    let designs = sets.map(|[r, l, e]| fx::SliderCrank { r, l, e });
    let cfold = |(lo, hi): (f64, f64), k: &Kin<2, 1, 0>| (lo.min(k.q[1]), hi.max(k.q[1]));
    let libm = designs.map(Libm);
    let l = kinloop::scan(&libm, &ScanConfig::new([0.0], [TAU], samples), |_| init(&[]), |a, _, k| cfold(a, k));
    let c = kinloop::scan(&designs, &ScanConfig::new([0.0], [TAU], samples), |_| init(&[]), |a, _, k| cfold(a, k));
    assert_eq!(r.len(), sets.len());
    for (((r, l), c), set) in r.iter().zip(&l).zip(&c).zip(&sets) {
        match (r, l, c) {
            (Ok(r), Ok(l), Ok(c)) => {
                assert_eq!(r, l, "{set:?}");
                assert!(rel_diff(&[r.0, r.1], &[c.0, c.1]) <= REL, "{set:?}");
                let [cr, cl, ce] = *set;
                let stroke = ((cl + cr).powi(2) - ce * ce).sqrt() - ((cl - cr).powi(2) - ce * ce).sqrt();
                // The sampled extremes lie within half a spacing h of the dead centres, where the
                // slider's position is stationary: inside the true ones by at most
                // max|x''| h^2 / 8 per end, h = 2 pi / 720. `x = r cos(phi) - l cos(psi)` has
                // `|x''|` about `r + r^2 / l` (exactly so without offset), below 4 for these
                // designs (r <= 1.2, r / l <= 1 / 3): 3.8e-5 per end.
                let bound = 2.0 * 4.0 * (TAU / 720.0).powi(2) / 8.0;
                let found = r.1 - r.0;
                assert!(found <= stroke + 1e-12 && stroke - found <= bound, "{set:?}: {found} (closed form {stroke})");
                eprintln!("{set:?}: stroke {found}, closed form {stroke}, bound {bound:e}");
            }
            (Err(r), Err(l), Err(c)) => {
                assert_eq!(std::mem::discriminant(r), std::mem::discriminant(c), "{r:?}\n{c:?}");
                assert_eq!(std::mem::discriminant(r), std::mem::discriminant(l), "{r:?}\n{l:?}");
                assert!(matches!(r, kinloop::Error::NoAssembly { .. }), "{r:?}");
            }
            other => panic!("{set:?}: {other:?}"),
        }
    }
    assert!(r[3].is_err() && r[..3].iter().all(Result::is_ok));
}

/// A guess computed from each set picks the other assembly mode (the slider on the crank's +x
/// side): the same sweeps as the compiled scan's `ScanStart::With`, the same stroke as the
/// closed form's on that side.
#[test]
fn a_scan_started_from_a_guess_of_each_set_is_the_compiled_one() {
    let sets = [[1.0, 3.0, 0.4], [1.2, 4.0, -0.7]];
    let mut model = read(fx::SLIDER_CRANK_TEXT);
    let init = |_: &[f64]| (f64::INFINITY, f64::NEG_INFINITY);
    let fold = |(lo, hi): (f64, f64), _: &[f64], k: &KinBuf| (lo.min(k.q[1]), hi.max(k.q[1]));
    let spec = ParamScanConfig::new(&[0.0], &[TAU], 721).start(ParamScanStart::With(|p| vec![PI, p[1]]));
    let r = model.scan(&["r", "l", "e"], &sets, &spec, init, fold);
    let libm = sets.map(|[r, l, e]| Libm(fx::SliderCrank { r, l, e }));
    let cspec = ScanConfig::new([0.0], [TAU], 721).start(ScanStart::With(|m: &Libm<fx::SliderCrank>| [PI, m.0.l]));
    let cfold = |(lo, hi): (f64, f64), _: &Libm<fx::SliderCrank>, k: &Kin<2, 1, 0>| (lo.min(k.q[1]), hi.max(k.q[1]));
    let c = kinloop::scan(&libm, &cspec, |_| init(&[]), cfold);
    for ((r, c), [cr, cl, ce]) in r.iter().zip(&c).zip(sets) {
        let (r, c) = (r.as_ref().unwrap(), c.as_ref().unwrap());
        assert_eq!(r, c);
        // On the +x side, and the same stroke (see the scan test above for the bound).
        assert!(r.0 > 0.0, "{r:?}");
        let stroke = ((cl + cr).powi(2) - ce * ce).sqrt() - ((cl - cr).powi(2) - ce * ce).sqrt();
        let found = r.1 - r.0;
        assert!(found <= stroke + 1e-12 && stroke - found <= 7.7e-5, "{found} (closed form {stroke})");
    }
}

/// What a parallel scan's test folds each sweep into: the extremes of every unknown, the sum of
/// the velocity analogs and of Newton's iterations (a value that would show any difference of a
/// step's history: a position, an analog or a solve that took another path).
type Folded = (Vec<f64>, Vec<f64>, f64, usize);

fn fold_all(mut a: Folded, _: &[f64], k: &KinBuf) -> Folded {
    for (u, &q) in k.q.iter().enumerate() {
        a.0[u] = a.0[u].min(q);
        a.1[u] = a.1[u].max(q);
    }
    a.2 += k.dq.iter().sum::<f64>();
    a.3 += k.report.iterations as usize;
    a
}

/// The bits of a scan's results: each value's, or the error's text.
fn scan_bits(r: &[Result<Folded, kinloop::Error>]) -> Vec<Result<(Vec<u64>, usize), String>> {
    let bits = |(lo, hi, s, n): &Folded| (lo.iter().chain(hi).chain([s]).map(|v| v.to_bits()).collect(), *n);
    r.iter().map(|r| r.as_ref().map(bits).map_err(|e| format!("{e:?}"))).collect()
}

/// `Model::par_scan` returns `Model::scan`'s results bit for bit and in the same order, over
/// several hundred designs: 360 offset slider-cranks (closed forms; the offsets beyond the
/// rod's reach of the crank fail at a limit position) and 150 class IV linkages (a Newton
/// block, whose iterations are folded too). The model itself is left as it is.
#[test]
fn a_parallel_scan_equals_the_scan_bit_for_bit() {
    let spec = ParamScanConfig::new(&[0.0], &[TAU], 91);
    let mut crank = read(fx::SLIDER_CRANK_TEXT);
    let sets: Vec<[f64; 3]> = (0..360)
        .map(|k| [0.5 + 0.2 * (k % 6) as f64, 1.2 + 0.5 * (k / 6 % 6) as f64, -1.8 + 0.36 * (k / 36) as f64])
        .collect();
    let init = |_: &[f64]| (vec![f64::INFINITY; 2], vec![f64::NEG_INFINITY; 2], 0.0, 0);
    let par = crank.par_scan(&["r", "l", "e"], &sets, &spec, init, fold_all);
    assert_eq!(crank.param_values(), &[None, None, None], "par_scan leaves the model as it is");
    let seq = crank.scan(&["r", "l", "e"], &sets, &spec, init, fold_all);
    let failed = seq.iter().filter(|r| r.is_err()).count();
    assert!(failed > 10 && failed < 300, "{failed} of the designs fail");
    assert_eq!(scan_bits(&par), scan_bits(&seq));

    let mut four = read(fx::CLASS_FOUR_TEXT);
    let sets: Vec<[f64; 2]> = (0..150).map(|k| [4.2 + 0.004 * k as f64, 3.3 + 0.003 * (k % 50) as f64]).collect();
    let init = |_: &[f64]| (vec![f64::INFINITY; 4], vec![f64::NEG_INFINITY; 4], 0.0, 0);
    let par = four.par_scan(&["xb", "ef"], &sets, &spec, init, fold_all);
    let seq = four.scan(&["xb", "ef"], &sets, &spec, init, fold_all);
    assert!(seq.iter().all(Result::is_ok) && seq.iter().all(|r| r.as_ref().unwrap().3 > 91), "Newton iterates");
    assert_eq!(scan_bits(&par), scan_bits(&seq));
    // A name that is not a parameter: the same error in every slot, as the scan's.
    let bad = four.par_scan(&["xb", "length"], &sets[..3], &spec, init, fold_all);
    assert_eq!(scan_bits(&bad), scan_bits(&four.scan(&["xb", "length"], &sets[..3], &spec, init, fold_all)));
}

/// A scan's arguments that cannot be used: an error in each slot, never a panic.
#[test]
fn scan_arguments_that_do_not_fit_are_errors() {
    let mut model = read(fx::SLIDER_CRANK_TEXT);
    let spec = ParamScanConfig::new(&[0.0], &[TAU], 37);
    let sets = [vec![1.0, 3.0, 0.4], vec![1.0, 3.0]];
    let r = model.scan(&["r", "l", "e"], &sets, &spec, |_| 0, |n, _, _| n + 1);
    assert_eq!(r[0].as_ref().ok(), Some(&37));
    assert!(matches!(&r[1], Err(kinloop::Error::InvalidArgument(m)) if m.contains("2 values")), "{:?}", r[1]);
    let r = model.scan(&["r", "length"], &[[1.0, 3.0]], &spec, |_| 0, |n, _, _| n + 1);
    assert!(matches!(&r[0], Err(kinloop::Error::InvalidArgument(m)) if m.contains("`length`")), "{:?}", r[0]);
    let wrong = ParamScanConfig::new(&[0.0, 1.0], &[TAU], 37);
    let r = model.scan(&["r"], &[[1.0]], &wrong, |_| 0, |n, _, _| n + 1);
    assert!(matches!(&r[0], Err(kinloop::Error::InvalidArgument(_))), "{:?}", r[0]);
    let r = model.scan(&["r"], &[[f64::NAN]], &spec, |_| 0, |n, _, _| n + 1);
    assert!(r[0].is_err(), "a parameter that is not finite: {:?}", r[0]);
    // As the compiled scan: one sample of a range to another end (the end was ignored, the
    // start alone folded), more samples than an analysis takes (`usize::MAX` folded for
    // years), an end not finite named as such with one sample too.
    let invalid = |e: &kinloop::Error, what: &str| matches!(e, kinloop::Error::InvalidArgument(m) if m.contains(what));
    for (spec, what) in [
        (ParamScanConfig::new(&[0.0], &[TAU], 1), "at least 2 samples"),
        (ParamScanConfig::new(&[0.0], &[TAU], kinloop::analysis::MAX_SAMPLES + 1), "at most"),
        (ParamScanConfig::new(&[0.0], &[TAU], usize::MAX), "at most"),
    ] {
        let r = model.scan(&["r"], &[[1.0]], &spec, |_| 0, |n, _, _| n + 1);
        assert!(invalid(r[0].as_ref().unwrap_err(), what), "{} samples: {:?}", spec.samples, r[0]);
    }
    let r = model.scan(&["r"], &[[1.0]], &ParamScanConfig::new(&[f64::NAN], &[f64::NAN], 1), |_| 0, |n, _, _| n + 1);
    assert!(matches!(&r[0], Err(kinloop::Error::NonFinite { .. })), "{:?}", r[0]);
    // Ends of another size: named as such, with one sample too.
    let r = model.scan(&["r"], &[[1.0]], &ParamScanConfig::new(&[0.0, 1.0], &[TAU], 1), |_| 0, |n, _, _| n + 1);
    assert!(matches!(&r[0], Err(kinloop::Error::InvalidArgument(m)) if !m.contains("samples")), "{:?}", r[0]);
}

// ---------------------------------------------------------------------------------------------
// Sizes

/// Inputs and guesses of another size than the model's: `InvalidArgument`, never a panic.
#[test]
fn arguments_of_other_sizes_are_invalid() {
    let (_, mut model) = four_bar(1.0, 3.0, 2.5, 3.2);
    let invalid = |e: kinloop::Error| matches!(e, kinloop::Error::InvalidArgument(_));
    let opts = TraceConfig::default();
    assert!(invalid(model.trace_curve(&[0.0], &[1.0], &[0.5], &opts).unwrap_err()));
    assert!(invalid(model.trace_curve(&[0.0, 1.0], &[1.0], &[0.5, 1.5], &opts).unwrap_err()));
    assert!(invalid(model.reachable(&[0.0], &[1.0, 2.0], &[0.5, 1.5], 5).unwrap_err()));
    assert!(invalid(model.reachable(&[0.0], &[1.0], &[0.5], 5).unwrap_err()));
    let r = model.sweep_at([vec![0.0], vec![0.5, 1.0]], &[0.5, 1.5]).unwrap();
    assert_eq!(r.states.len(), 1);
    assert!(invalid(r.into_result().unwrap_err()));
    let r = model.sweep_at([[0.0]], &[0.5]).unwrap();
    assert!(r.states.is_empty() && invalid(r.into_result().unwrap_err()));
    assert!(invalid(model.assembly_modes(&[]).unwrap_err()));
    // A parameter without a value: the model cannot be lent.
    let mut unset = read(fx::FOUR_BAR_TEXT);
    assert!(invalid(unset.assembly_modes(&[0.0]).unwrap_err()));
    assert!(invalid(unset.trace_curve(&[0.0], &[1.0], &[0.5, 1.5], &opts).unwrap_err()));
}

// ---------------------------------------------------------------------------------------------
// Every fixture

/// Every algorithm on one fixture, against the compiled mechanism to the last bit: the
/// assembly modes at `from` and the traced curve from `from` towards `to` (the same kernels),
/// and with libm's sines in the compiled sweep's steps the states at `from`, the middle, `to`
/// and `from` again, the reachable range from `from` a quarter of the way both sides, and a
/// scan of the model's own parameter set (each state's positions summed). Returns what was
/// compared, for the report.
fn every_algorithm<M, const N: usize, const NI: usize, const NO: usize>(
    name: &str,
    compiled: M,
    model: &mut Model,
    from: [f64; NI],
    to: [f64; NI],
) -> String
where
    M: Mechanism<N, NI, NO>,
{
    let cfg = NewtonConfig::default();
    let c = kinloop::paths::modes::assembly_modes(&compiled, &from, 64, &cfg).unwrap();
    let r = model.assembly_modes(&from).unwrap();
    assert_eq!(c.len(), r.len(), "{name}: modes");
    assert!(!r.is_empty(), "{name}: no mode at {from:?}");
    for (a, b) in c.iter().zip(&r) {
        assert_eq!(state_diff(a, b), 0.0, "{name}: a mode");
    }

    let guess = compiled.guess_flat(&from);
    let opts = TraceConfig::default().with_ds(0.05).with_max_points(300);
    let c = kinloop::paths::trace::trace_curve(&compiled, from, to, guess, &opts);
    let r = model.trace_curve(&from, &to, &guess, &opts);
    let points = match (c, r) {
        (Ok(c), Ok(r)) => {
            assert_eq!((c.points.len(), c.closed), (r.points.len(), r.closed), "{name}: trace");
            for (a, b) in c.points.iter().zip(&r.points) {
                assert_eq!((&a.x[..], &a.q[..], a.input_rate), (&b.x.0[..], &b.q.0[..], b.input_rate), "{name}");
            }
            assert_eq!(strip(&c.folds), strip(&r.folds), "{name}: folds");
            r.points.len()
        }
        (Err(c), Err(r)) => {
            assert_eq!(std::mem::discriminant(&c), std::mem::discriminant(&r), "{name}: {c}\n{r}");
            0
        }
        (c, r) => panic!("{name}: compiled {:?}, run time {:?}", c.map(|t| t.points.len()), r.map(|t| t.points.len())),
    };

    let libm = Libm(compiled);
    let mut mid = from;
    for i in 0..NI {
        mid[i] = 0.5 * (from[i] + to[i]);
    }
    let inputs = [from, mid, to, from];
    let c = kinloop::paths::sweep_at::sweep_at_of(&kinloop_runtime::Compiled(&libm), inputs, guess);
    let r = model.sweep_at(inputs, &guess).unwrap();
    assert_eq!(c.states.len(), r.states.len(), "{name}: sweep_at {:?} {:?}", c.stop, r.stop);
    for (a, b) in c.states.iter().zip(&r.states) {
        assert_eq!(state_diff(a, b), 0.0, "{name}: sweep_at");
    }
    assert_eq!(strip(&c.events), strip(&r.events), "{name}: sweep_at's events");

    let mut delta = from;
    for i in 0..NI {
        delta[i] = 0.25 * (to[i] - from[i]);
    }
    let c = kinloop::paths::reach::reachable(&libm, from, delta, guess, 9);
    let r = model.reachable(&from, &delta, &guess, 9);
    match (c, r) {
        (Ok(c), Ok(r)) => {
            assert_eq!((&c.from[..], &c.to[..]), (&r.from.0[..], &r.to.0[..]), "{name}: reach");
            assert_eq!(strip(c.from_event.as_slice()), strip(r.from_event.as_slice()), "{name}");
            assert_eq!(strip(c.to_event.as_slice()), strip(r.to_event.as_slice()), "{name}");
        }
        (Err(c), Err(r)) => assert_eq!(std::mem::discriminant(&c), std::mem::discriminant(&r), "{name}: {c}\n{r}"),
        (c, r) => panic!("{name}: reach: compiled {c:?}, run time {r:?}"),
    }

    let sum = |acc: f64, q: &[f64]| q.iter().fold(acc, |s, v| s + v);
    let spec = ScanConfig::new(from, to, 37);
    let c = kinloop::scan(std::slice::from_ref(&libm), &spec, |_| 0.0, |acc, _, k| sum(acc, &k.q));
    let none: [[f64; 0]; 1] = [[]];
    let r = model.scan(&[], &none, &ParamScanConfig::new(&from, &to, 37), |_| 0.0, |acc, _, k| sum(acc, &k.q));
    match (&c[0], &r[0]) {
        (Ok(c), Ok(r)) => assert_eq!(c.to_bits(), r.to_bits(), "{name}: scan"),
        (Err(c), Err(r)) => assert_eq!(std::mem::discriminant(c), std::mem::discriminant(r), "{name}: {c}\n{r}"),
        (c, r) => panic!("{name}: scan: compiled {c:?}, run time {r:?}"),
    }
    format!(
        "{name}: {} modes, {points} traced points, scan {}",
        model.assembly_modes(&from).unwrap().len(),
        r[0].is_ok()
    )
}

/// Every fixture of `parity.rs`, every algorithm, over a turn of its first input.
#[test]
fn every_fixture_runs_every_algorithm_as_the_compiled_one() {
    let (turn, end) = ([0.0], [TAU]);
    let mut report = Vec::new();
    let mut m = read(fx::RHOMBIC_DRIVE_TEXT);
    report.push(every_algorithm("rhombic drive", fx::RhombicDrive::default(), &mut m, turn, end));
    let mut m = read(fx::SLIDER_CRANK_TEXT);
    set(&mut m, &[("r", 1.0), ("l", 3.0), ("e", 0.4)]);
    report.push(every_algorithm("slider-crank", fx::SliderCrank { r: 1.0, l: 3.0, e: 0.4 }, &mut m, turn, end));
    let mut m = read(fx::FIVE_BAR_TEXT);
    report.push(every_algorithm("five-bar", fx::FiveBar::default(), &mut m, [0.0, 0.4], [TAU, 0.4]));
    let mut m = read(fx::CLASS_FOUR_TEXT);
    report.push(every_algorithm("class IV", fx::ClassFour::default(), &mut m, turn, end));
    let mut m = read(fx::DISPLACER_ROD_DRIVE_TEXT);
    report.push(every_algorithm("displacer-rod drive", fx::DisplacerRodDrive::default(), &mut m, turn, end));
    let mut m = read(fx::WORKING_ROD_DRIVE_TEXT);
    report.push(every_algorithm("working-rod drive", fx::WorkingRodDrive::default(), &mut m, turn, end));
    let mut m = read(fx::gear_lever::GEAR_LEVER_TEXT);
    report.push(every_algorithm("gear lever", fx::gear_lever::GearLever::default(), &mut m, turn, end));
    let mut m = read(fx::roller_edger::ROLLER_EDGER_TEXT);
    report.push(every_algorithm("roller edger", fx::roller_edger::RollerEdger::default(), &mut m, turn, end));
    let mut m = read(fx::balancing::BALANCE_TEXT);
    report.push(every_algorithm("balance", fx::balancing::Balance::default(), &mut m, turn, end));
    let mut m = read(fx::CLASS_FOUR_CORE_TEXT);
    report.push(every_algorithm("class IV core", fx::ClassFourCore::default(), &mut m, turn, end));
    eprintln!("{}", report.join("\n"));
}
