//! The units proof: the same mechanisms with every length multiplied by `k` from `1e-9` to `1e9`
//! give the same angles and angle analogs, lengths (and length analogs) multiplied by `k`, the
//! same events at the same inputs, and sensitivities scaled by the units of what they relate.
//!
//! The reference of each figure is the same computation at `k = 1`: multiplying every length by
//! `k` leaves every angle of a mechanism unchanged and multiplies every length by `k` (the loop
//! equations are homogeneous of degree one in the lengths), so any difference beyond the
//! rounding of the scaled parameters is a unit-dependent test in the solver. Limit positions are
//! also checked against the law of cosines.
//!
//! Tolerances: `1e-14` absolute in radians (about 20 ulps of an angle below pi, room for the
//! rounding of `k` times each parameter amplified by the mechanism's condition), `1e-14` of the
//! mechanism's size for lengths, and `1e-12` for the inputs at events.

// The loops walk several parallel fixed-size arrays (states, dimensions) by one index.
#![allow(clippy::needless_range_loop)]

use kinloop::{Error, EventKind, Kin, Mechanism, NewtonConfig, Sensitivities, SweepConfig};
use kinloop_fixtures::{ClassFour, DisplacerRodDrive, FiveBar, FourBar, SliderCrank};
use std::f64::consts::PI;

use crate::support::{four_bar_limit, tol};

const SCALES: [f64; 7] = [1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9];
const ANGLE_TOL: f64 = 1e-14;
const LENGTH_TOL: f64 = 1e-14;
const EVENT_TOL: f64 = 1e-12;

/// What a quantity is: an angle (the same at every scale, power 0 of `k`) or a length (power 1).
#[derive(Clone, Copy, PartialEq)]
enum Dim {
    A,
    L,
}
use Dim::{A, L};

impl Dim {
    fn power(self) -> i32 {
        if self == L { 1 } else { 0 }
    }
}

/// Error of `got` (at scale `k`, of dimension `dim`) against `base` (at scale 1): in radians for
/// angles (relative to the value above one radian), in units of `size` for lengths.
fn err(dim: Dim, k: f64, got: f64, base: f64, size: f64) -> f64 {
    match dim {
        A => (got - base).abs() / base.abs().max(1.0),
        L => (got / k - base).abs() / size,
    }
}

/// Largest error over positions, analogs and outputs of two states (all inputs are angles, so
/// analogs have the dimension of their quantity).
fn kin_err<const N: usize, const NI: usize, const NO: usize>(
    k: f64,
    got: &Kin<N, NI, NO>,
    base: &Kin<N, NI, NO>,
    q: &[Dim; N],
    out: &[Dim; NO],
    size: f64,
) -> f64 {
    let mut m = 0.0f64;
    for u in 0..N {
        m = m.max(err(q[u], k, got.q[u], base.q[u], size));
        for i in 0..NI {
            m = m.max(err(q[u], k, got.dq[u][i], base.dq[u][i], size));
            for j in 0..NI {
                m = m.max(err(q[u], k, got.d2q[u][i][j], base.d2q[u][i][j], size));
            }
        }
    }
    for o in 0..NO {
        m = m.max(err(out[o], k, got.out[o], base.out[o], size));
        for i in 0..NI {
            m = m.max(err(out[o], k, got.dout[o][i], base.dout[o][i], size));
        }
    }
    m
}

/// One mechanism of the proof: how to build it at scale `k`, the dimensions of its unknowns and
/// outputs, its size (sum of its lengths at `k = 1`) and where to solve it.
struct Case<M, const N: usize, const NI: usize, const NO: usize> {
    name: &'static str,
    at: fn(f64) -> M,
    q: [Dim; N],
    out: [Dim; NO],
    size: f64,
    inputs: Vec<[f64; NI]>,
    sweep: ([f64; NI], [f64; NI], usize),
}

/// Guess at scale `k` from the one at scale 1 (lengths scaled).
fn scale_guess<const N: usize>(g: [f64; N], dims: &[Dim; N], k: f64) -> [f64; N] {
    let mut s = g;
    for u in 0..N {
        if dims[u] == L {
            s[u] *= k;
        }
    }
    s
}

/// Point solves from the declared guess and from a guess 0.05 rad / 2 % off, at every scale;
/// returns the largest error.
fn point_solves<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    c: &Case<M, N, NI, NO>,
) -> f64 {
    let cfg = NewtonConfig::default();
    let one = (c.at)(1.0);
    let mut worst = 0.0f64;
    for x in &c.inputs {
        let base = one.kinematics_flat(x, &one.guess_flat(x), &cfg).unwrap();
        let off = base.q.map(|v| v * 1.02 + 0.05);
        let base_off = one.kinematics_flat(x, &off, &cfg).unwrap();
        for k in SCALES {
            let m = (c.at)(k);
            let got = m.kinematics_flat(x, &m.guess_flat(x), &cfg).unwrap_or_else(|e| panic!("{} k={k}: {e}", c.name));
            worst = worst.max(kin_err(k, &got, &base, &c.q, &c.out, c.size));
            let got = m.kinematics_flat(x, &scale_guess(off, &c.q, k), &cfg).unwrap();
            worst = worst.max(kin_err(k, &got, &base_off, &c.q, &c.out, c.size));
        }
    }
    worst
}

/// A sweep at every scale: every sample and every event compared with the sweep at scale 1.
/// Returns the largest state error and the largest event input difference.
fn sweeps<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    c: &Case<M, N, NI, NO>,
) -> (f64, f64) {
    let run = |k: f64| {
        let m = (c.at)(k);
        let (from, to, n) = c.sweep;
        let mut s = kinloop::Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(&m, from, to, n, m.guess_flat(&from)).unwrap();
        let states: Vec<Result<Kin<N, NI, NO>, Error>> = s.by_ref().collect();
        (states, s.events().to_vec())
    };
    let (base, base_events) = run(1.0);
    let (mut worst, mut worst_event) = (0.0f64, 0.0f64);
    for k in SCALES {
        let (got, events) = run(k);
        assert_eq!(got.len(), base.len(), "{} k={k}: samples", c.name);
        for (g, b) in got.iter().zip(&base) {
            match (g, b) {
                (Ok(g), Ok(b)) => worst = worst.max(kin_err(k, g, b, &c.q, &c.out, c.size)),
                (Err(_), Err(_)) => {}
                _ => panic!("{} k={k}: {g:?} vs {b:?}", c.name),
            }
        }
        assert_eq!(events.len(), base_events.len(), "{} k={k}: {events:?}", c.name);
        for (e, b) in events.iter().zip(&base_events) {
            assert_eq!(e.kind, b.kind);
            for (x, y) in e.x.iter().zip(&b.x) {
                worst_event = worst_event.max((x - y).abs());
            }
        }
    }
    (worst, worst_event)
}

fn check<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(c: &Case<M, N, NI, NO>) {
    let p = point_solves(c);
    let (s, e) = sweeps(c);
    eprintln!("{}: point solves {p:.1e}, sweeps {s:.1e}, events {e:.1e}", c.name);
    assert!(p <= ANGLE_TOL.max(LENGTH_TOL), "{}: point solves differ by {p:e}", c.name);
    assert!(s <= ANGLE_TOL.max(LENGTH_TOL), "{}: sweeps differ by {s:e}", c.name);
    assert!(e <= EVENT_TOL, "{}: events differ by {e:e}", c.name);
}

fn four_bar(k: f64) -> FourBar {
    FourBar { a: 1.0 * k, b: 3.5 * k, c: 3.0 * k, d: 4.0 * k }
}

fn slider_crank(k: f64) -> SliderCrank {
    SliderCrank { r: 1.0 * k, l: 3.2 * k, e: 0.4 * k }
}

fn six_bar(k: f64) -> DisplacerRodDrive {
    let d = DisplacerRodDrive::default();
    DisplacerRodDrive {
        r: d.r * k,
        l_b: d.l_b * k,
        l_fd: d.l_fd * k,
        gamma_b: d.gamma_b,
        l_p: d.l_p * k,
        e_p: d.e_p * k,
        de: d.de * k,
    }
}

/// The class IV group's parameters: lengths except the two ternary links' angles.
const CLASS_FOUR_PARAMS: [Dim; 11] = [L, L, L, L, L, A, L, L, A, L, L];

fn class_four(k: f64) -> ClassFour {
    let d = ClassFour::default();
    let mut p = d.params_flat();
    for (v, dim) in p.iter_mut().zip(CLASS_FOUR_PARAMS) {
        *v *= k.powi(dim.power());
    }
    d.with_params_flat(p)
}

const FIVE_BAR_PARAMS: [Dim; 5] = [L; 5];

fn five_bar(k: f64) -> FiveBar {
    let d = FiveBar::default();
    d.with_params_flat(d.params_flat().map(|v| v * k))
}

fn turn(n: usize) -> Vec<[f64; 1]> {
    (0..n).map(|i| [0.3 + 2.0 * PI * i as f64 / n as f64]).collect()
}

#[test]
fn four_bar_with_coupler_point_is_unit_free() {
    check(&Case {
        name: "four-bar",
        at: four_bar,
        q: [A, A],
        out: [L, L],
        size: 11.5,
        inputs: turn(12),
        sweep: ([0.3], [0.3 + 2.0 * PI], 73),
    });
}

#[test]
fn offset_slider_crank_is_unit_free() {
    check(&Case {
        name: "slider-crank",
        at: slider_crank,
        q: [A, L],
        out: [],
        size: 4.6,
        inputs: turn(12),
        sweep: ([0.3], [0.3 + 2.0 * PI], 73),
    });
}

#[test]
fn two_loop_six_bar_is_unit_free() {
    let d = DisplacerRodDrive::default();
    let size = d.r + d.l_b + d.l_fd + d.l_p + d.e_p + d.de;
    check(&Case {
        name: "six-bar",
        at: six_bar,
        q: [A, L, A, L],
        out: [L, L],
        size,
        inputs: turn(12),
        sweep: ([0.3], [0.3 + 2.0 * PI], 73),
    });
}

#[test]
fn class_four_group_is_unit_free() {
    let p = ClassFour::default().params_flat();
    let size: f64 = p.iter().zip(CLASS_FOUR_PARAMS).filter(|(_, d)| *d == L).map(|(v, _)| v.abs()).sum();
    check(&Case {
        name: "class IV",
        at: class_four,
        q: [A; 4],
        out: [L; 8],
        size,
        inputs: turn(12),
        sweep: ([0.3], [0.3 + 2.0 * PI], 73),
    });
}

/// Sensitivities `d v / d p` at scale `k` times `k^(dim p - dim v)` equal those at scale 1.
fn sensitivities_err<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    at: fn(f64) -> M,
    x: [f64; NI],
    q: &[Dim; N],
    params: &[Dim; NP],
) -> f64
where
    M: Sensitivities<N, NI, NO, NP>,
{
    let cfg = NewtonConfig::default();
    let one = at(1.0);
    let (_, base) = one.sensitivities_flat(&x, &one.guess_flat(&x), &cfg).unwrap();
    let mut worst = 0.0f64;
    for k in SCALES {
        let m = at(k);
        let (_, s) = m.sensitivities_flat(&x, &m.guess_flat(&x), &cfg).unwrap();
        for u in 0..N {
            let big = base.q[u].iter().fold(1.0f64, |a, v| a.max(v.abs()));
            for p in 0..NP {
                let back = s.q[u][p] * k.powi(params[p].power() - q[u].power());
                worst = worst.max((back - base.q[u][p]).abs() / big);
                for i in 0..NI {
                    let back = s.dq[u][i][p] * k.powi(params[p].power() - q[u].power());
                    worst = worst.max((back - base.dq[u][i][p]).abs() / big.max(base.dq[u][i][p].abs()));
                }
            }
        }
    }
    worst
}

#[test]
fn declared_sensitivities_scale_with_their_units() {
    let c4 = sensitivities_err(class_four, [0.8], &[A; 4], &CLASS_FOUR_PARAMS);
    let f5 = sensitivities_err(five_bar, [2.0, 1.0], &[A; 2], &FIVE_BAR_PARAMS);
    eprintln!("sensitivities: class IV {c4:.1e}, five-bar {f5:.1e}");
    assert!(c4 <= ANGLE_TOL && f5 <= ANGLE_TOL, "class IV {c4:e}, five-bar {f5:e}");
}

/// Non-Grashof four-bar: the limit position is where coupler and rocker stretch out (law of
/// cosines), at the same input at every scale.
#[test]
fn limit_position_is_located_at_the_same_input_at_every_scale() {
    let (a, b, c, d): (f64, f64, f64, f64) = (3.0, 2.0, 2.5, 4.0);
    let exact = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    let mut found = Vec::new();
    for k in SCALES {
        let m = FourBar { a: a * k, b: b * k, c: c * k, d: d * k };
        let g = m.guess_flat(&[0.0]);
        let mut s = kinloop::Sweep::<FourBar, Kin<2, 1, 2>, 2, 1, 2>::new(&m, [0.0], [PI], 181, g)
            .unwrap()
            .with_config(SweepConfig::default());
        let stop = s.by_ref().find_map(|r| r.err());
        assert!(matches!(stop, Some(Error::SweepStopped { kind: EventKind::LimitPosition, .. })), "k={k}: {stop:?}");
        found.push(s.events()[0].x[0]);
    }
    let spread = found.iter().map(|x| (x - found[3]).abs()).fold(0.0, f64::max);
    let off = found.iter().map(|x| (x - exact).abs()).fold(0.0, f64::max);
    eprintln!("limit positions: spread over scales {spread:.1e}, off the law of cosines {off:.1e}");
    assert!(spread <= EVENT_TOL, "{found:?}");
    // Located to about sqrt(eps) in the input (the curve is flat there in phi).
    assert!(off <= 1e-9, "{found:?} vs {exact}");
}

kinloop::mechanism! {
    /// Offset slider-crank by the rod-length equation alone: one equation in the slider
    /// position `x`, a block of one length unknown (whose Jacobian row sum says nothing about
    /// the equation's unit).
    pub struct RodLength {
        params r, l, e;
        input phi;
        unknowns x = l;
        eq rod: (x - r * cos(phi)) ^ 2 + (r * sin(phi) - e) ^ 2 == l * l;
    }
}

/// A one-unknown block in a length: from guesses `1e-4` relative off, the slider position at
/// every scale equals `k` times the closed form `r cos phi + sqrt(l^2 - (r sin phi - e)^2)`.
#[test]
fn one_length_unknown_block_is_unit_free() {
    let (r, l, e) = (1.0f64, 3.2f64, 0.4f64);
    let mut worst = 0.0f64;
    for k in SCALES {
        let m = RodLength { r: r * k, l: l * k, e: e * k };
        for i in 0..12 {
            let phi = 0.3 + 2.0 * PI * i as f64 / 12.0;
            let exact = r * phi.cos() + (l * l - (r * phi.sin() - e).powi(2)).sqrt();
            for off in [1e-4, -1e-4, 1e-9] {
                let got = m.kinematics_flat(&[phi], &[exact * k * (1.0 + off)], &NewtonConfig::default()).unwrap();
                worst = worst.max((got.q[0] / k - exact).abs() / (r + l + e));
            }
        }
    }
    eprintln!("one length unknown: {worst:.1e}");
    assert!(worst <= LENGTH_TOL, "{worst:e}");
}

kinloop::mechanism! {
    /// Non-Grashof four-bar (rocking input) with the abscissa of its coupler point as a length
    /// unknown: the continuation's tangent and arclength combine the angle input, two angle
    /// unknowns and a length, which must not be weighed in the unit of length.
    pub struct RockerWithPoint {
        params a, b, c, d, p;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, xp = a;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        eq px: xp == a * cos(phi) + p * cos(beta);
    }
}

fn rocker(k: f64) -> RockerWithPoint {
    RockerWithPoint { a: 3.0 * k, b: 2.0 * k, c: 2.5 * k, d: 4.0 * k, p: 1.2 * k }
}

/// The law of cosines: the rocker's limit positions are at `+-phi_lim`, where coupler and
/// rocker stretch out (`|BD| = b + c`).
fn rocker_limit() -> f64 {
    let (a, b, c, d) = (3.0f64, 2.0, 2.5, 4.0);
    four_bar_limit(a, d, b + c)
}

/// The largest difference between two traces: angles and inputs absolute, the length `xp`
/// divided by the scale and relative to the mechanism's size.
fn trace_diff(t: &kinloop::Traced<3, 1>, k: f64, r: &kinloop::Traced<3, 1>) -> f64 {
    let size = 3.0 + 2.0 + 2.5 + 4.0 + 1.2;
    let mut worst = 0.0f64;
    for (p, q) in t.points.iter().zip(&r.points) {
        worst = worst.max((p.x[0] - q.x[0]).abs()).max((p.q[0] - q.q[0]).abs()).max((p.q[1] - q.q[1]).abs());
        worst = worst.max((p.q[2] / k - q.q[2]).abs() / size);
    }
    for (f, g) in t.folds.iter().zip(&r.folds) {
        worst = worst.max((f.x[0] - g.x[0]).abs());
    }
    worst
}

/// `trace_curve` follows the same closed curve with the same points (arclength in scaled
/// coordinates) and finds the same limit positions at every scale.
#[test]
fn traced_curve_is_unit_free() {
    let opts = kinloop::TraceConfig::default().with_ds(0.02);
    let trace = |k: f64| {
        let m = rocker(k);
        let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
        m.trace_curve(0.0, PI, &g, &opts).unwrap()
    };
    let reference = trace(1.0);
    assert!(reference.closed && reference.folds.len() == 2, "{} points", reference.points.len());
    let lim = rocker_limit();
    for f in &reference.folds {
        assert_close!(f.x[0].abs(), lim, tol::LOCATED, "{:?} vs +-{lim}", f.x);
    }
    let mut worst = 0.0f64;
    for k in SCALES {
        let t = trace(k);
        assert!(t.closed && t.folds.len() == 2, "k={k}");
        assert_eq!(t.points.len(), reference.points.len(), "k={k}");
        worst = worst.max(trace_diff(&t, k, &reference));
    }
    eprintln!("traced curve over scales: {worst:.1e}");
    assert!(worst <= EVENT_TOL, "{worst:e}");
}

/// Event location (the sweep's continuation to its limit position) and `reachable` give the
/// same inputs at every scale, also with a length among the unknowns.
#[test]
fn limit_positions_and_reach_are_unit_free_with_a_length_unknown() {
    let (mut stops, mut reaches) = (Vec::new(), Vec::new());
    for k in SCALES {
        let m = rocker(k);
        let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
        let run = m.sweep(0.0, PI, 181, &g).unwrap().run();
        match &run.stop {
            kinloop::SweepStop::LimitPosition(ev) => stops.push(ev.x[0]),
            other => panic!("k={k}: {other:?}"),
        }
        let reach = m.reachable(0.0, PI, &g, 91).unwrap();
        reaches.push((reach.from.phi, reach.to.phi));
    }
    let lim = rocker_limit();
    let spread = stops.iter().map(|x| (x - stops[3]).abs()).fold(0.0, f64::max);
    let reach_spread =
        reaches.iter().map(|r| (r.0 - reaches[3].0).abs().max((r.1 - reaches[3].1).abs())).fold(0.0, f64::max);
    eprintln!("limit positions over scales: sweep {spread:.1e}, reachable {reach_spread:.1e}");
    assert!(spread <= EVENT_TOL && reach_spread <= EVENT_TOL, "{stops:?} {reaches:?}");
    // Located to about sqrt(eps) in the input (the curve is flat there in phi).
    assert!((stops[3] - lim).abs() <= 1e-9 && (reaches[3].1 - lim).abs() <= 1e-9 && (reaches[3].0 + lim).abs() <= 1e-9);
}

kinloop::mechanism! {
    /// A crank turned by a rack: the rack's travel `x` (a length) turns the pinion, and the
    /// crank on it, by `x / rp`; the crank drives a slider.
    pub struct RackCrank {
        params rp = 0.5, rc = 1.0, l = 3.0;
        input x;
        unknowns psi = 0, xs = 4;
        loop crank: rc @ (x / rp) + l @ psi == (xs, 0);
    }
}

kinloop::mechanism! {
    /// A four-bar that cannot turn fully, its crank turned by a rack (`x / rp`).
    pub struct RackFourBar {
        params rp = 0.5, a = 3.0, b = 2.0, c = 2.5, d = 4.0;
        input x;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ (x / rp) + b @ beta == (d, 0) + c @ gamma;
    }
}

/// A length input that enters a trigonometric argument scaled by a length (`x / rp`, a rack
/// turning a pinion) is judged in its own unit, not as an angle: at every size, the slider's
/// ten dead centres over five turns of the pinion (sampled a turn apart and more) and the
/// four-bar's limit position by the law of cosines. Judged in radians of `x`, a mechanism a
/// micrometre across found no extremes (its six samples looked closer than a sweep's step)
/// and its four-bar's sweep failed with "cannot stay on its branch".
#[test]
fn a_length_input_in_a_trigonometric_argument_is_unit_free() {
    let limit = (4.75f64 / 24.0).acos(); // |a e^(i th) - d| = b + c
    for k in SCALES {
        let m = RackCrank { rp: 0.5 * k, rc: k, l: 3.0 * k };
        let from = 0.1 * k;
        let run = kinloop::analysis::Sampled::sweep(&m, from, from + 5.0 * PI * k, 6, m.guess(from)).unwrap();
        let range = run.range(RackCrank::COL.xs).unwrap();
        assert!(
            (range.min.value / k - 2.0).abs() < 1e-13 && (range.max.value / k - 4.0).abs() < 1e-13,
            "{k}: {range:?}"
        );
        let extremes = run.extremes(RackCrank::COL.xs).unwrap();
        assert_eq!(extremes.len(), 10, "{k}: {extremes:?}");
        for e in &extremes {
            // At the dead centres, the pinion at a multiple of pi.
            let turns = e.x() / (0.5 * k) / PI;
            assert!((turns - turns.round()).abs() < 1e-9, "{k}: {e:?}");
        }
        let m = RackFourBar { rp: 0.5 * k, a: 3.0 * k, b: 2.0 * k, c: 2.5 * k, d: 4.0 * k };
        let to = 0.5 * k * PI / 2.0;
        let stop = m.sweep(0.0, to, 11, &m.guess(0.0)).unwrap().run();
        let kinloop::SweepStop::LimitPosition(event) = stop.stop else { panic!("{k}: {:?}", stop.stop) };
        assert!((event.x[0] / (0.5 * k) - limit).abs() < EVENT_TOL, "{k}: {event:?}");
    }
}
