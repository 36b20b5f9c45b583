//! Closed-form blocks at every representable scale. A mechanism whose lengths are `k` times
//! another's has the same angles and `k` times its lengths; the closed forms compute with
//! squares and products of lengths, which leave the range of `f64` beyond about `k = 1e±77`
//! (a dyad's coefficients squared) or `1e±154` (a length squared). The Newton twin of each
//! mechanism (`#[kinloop(newton)]`, scale-free by construction) is the independent reference
//! here besides scale 1: at every scale from `1e-300` to `1e300` both give the scale-1 angles
//! to `1e-14` rad and lengths to `1e-14` of the scaled size, for point solves, analogs and
//! sweeps — never an error, a non-finite value or a silently imprecise position.

// The loops walk parallel fixed-size arrays (states, dimensions) by one index.
#![allow(clippy::needless_range_loop)]

use kinloop::{Kin, Mechanism, NewtonConfig, Sens, Sensitivities, Sweep};

use kinloop_fixtures::{FourBarSens, RhombicDrive, RhombicDriveDense};

use crate::support::{four_bar_jets, gear_lever_explicit, tol, wrap};

with_newton_twin! {
    /// Four-bar (RRR dyad) with a coupler point.
    pub struct FourBar, FourBarNewton {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point pc = a @ phi + b @ beta;
    }
}

with_newton_twin! {
    /// Offset slider-crank (angle equation, then the slider).
    pub struct SliderCrank, SliderCrankNewton {
        params r, l, e;
        input phi;
        unknowns psi = 0, x = -l;
        loop oabo: r @ phi == (x, e) + l @ psi;
    }
}

with_newton_twin! {
    /// Five four-bars in series, each driven by the rocker of the one before: ten unknowns,
    /// more than a sweep inlines, so `kinloop::mechanism!` emits its `kinematics_flat` as a
    /// kernel of its own (five closed-form dyads in sequence).
    pub struct FourBarChain, FourBarChainNewton {
        params a, b, c, d;
        input phi;
        unknowns b1 = 0.5, g1 = 1.5, b2 = 0.5, g2 = 1.5, b3 = 0.5, g3 = 1.5, b4 = 0.5, g4 = 1.5,
                 b5 = 0.5, g5 = 1.5;
        loop l1: a @ phi + b @ b1 == (d, 0) + c @ g1;
        loop l2: a @ g1 + b @ b2 == (d, 0) + c @ g2;
        loop l3: a @ g2 + b @ b3 == (d, 0) + c @ g3;
        loop l4: a @ g3 + b @ b4 == (d, 0) + c @ g4;
        loop l5: a @ g4 + b @ b5 == (d, 0) + c @ g5;
        point p5 = (d, 0) + c @ g5;
    }
}

with_newton_twin! {
    /// The gear-lever drive's polar length (`kinloop_fixtures::gear_lever`): a pin on a carrier
    /// and a planet, read as the distance `s` and angle `phi` of a block on a rocker. The
    /// closed form's angle is `atan2` of the pin's unnormalised coordinates, which stay in
    /// range wherever their squares do. Newton's block mixes a length and an angle: the pivots
    /// of its singularity tests are measured in the unknowns' units.
    pub struct PolarPin, PolarPinNewton {
        params l_c, l_p, u;
        input alpha;
        unknowns s = l_c + l_p, phi = 0;
        let pin = (l_c * sin(alpha), l_c * cos(alpha))
                + (l_p * sin((1 - u) * alpha), l_p * cos((1 - u) * alpha));
        loop oab: pin == s * (sin(phi), cos(phi));
        point b = pin;
    }
}

/// The gear-lever's pin at size `k` (carrier 2, planet pin 1.3 times `k`; the ratio is no
/// length).
fn polar_pin(k: f64) -> PolarPin {
    PolarPin { l_c: 2.0 * k, l_p: 1.3 * k, u: 3.0 }
}

fn polar_pin_newton(k: f64) -> PolarPinNewton {
    PolarPinNewton { l_c: 2.0 * k, l_p: 1.3 * k, u: 3.0 }
}

/// A rhombic drive at size `k`: every parameter a length but the crank's angle `gamma` and the
/// centre of mass's `psi_s1`.
fn rhombic_at<M: Sensitivities<4, 1, 7, NP> + Default, const NP: usize>(k: f64) -> M {
    let d = M::default();
    let mut p = d.params_flat();
    for (name, v) in M::PARAMS.iter().zip(p.iter_mut()) {
        if !["gamma", "psi_s1"].contains(name) {
            *v *= k;
        }
    }
    d.with_params_flat(p)
}

/// The rhombic drive solved as one dense Newton block at size `k`.
fn rhombic_dense(k: f64) -> RhombicDriveDense {
    rhombic_at(k)
}

/// The chain at size `k` (every four-bar's links 1, 3.5, 3, 4 times `k`).
fn chain(k: f64) -> FourBarChain {
    FourBarChain { a: k, b: 3.5 * k, c: 3.0 * k, d: 4.0 * k }
}

fn chain_newton(k: f64) -> FourBarChainNewton {
    FourBarChainNewton { a: k, b: 3.5 * k, c: 3.0 * k, d: 4.0 * k }
}

/// The four-bar at size `k` (link lengths 1, 3.5, 3, 4 times `k`).
fn four_bar(k: f64) -> FourBar {
    FourBar { a: k, b: 3.5 * k, c: 3.0 * k, d: 4.0 * k }
}

fn four_bar_newton(k: f64) -> FourBarNewton {
    FourBarNewton { a: k, b: 3.5 * k, c: 3.0 * k, d: 4.0 * k }
}

/// The slider-crank at size `k`.
fn slider_crank(k: f64) -> SliderCrank {
    SliderCrank { r: k, l: 3.2 * k, e: 0.4 * k }
}

fn slider_crank_newton(k: f64) -> SliderCrankNewton {
    SliderCrankNewton { r: k, l: 3.2 * k, e: 0.4 * k }
}

/// Every tenth power of ten from `1e-300` to `1e300`, and powers of two next to the ends of
/// the closed forms' own range (`2^±480`) and of `f64`'s.
fn scales() -> Vec<f64> {
    let mut k: Vec<f64> = (-30..=30).map(|e| 10f64.powi(10 * e)).collect();
    k.extend([2f64.powi(480), 2f64.powi(481), 2f64.powi(-480), 2f64.powi(-481), 2f64.powi(1000), 2f64.powi(-1000)]);
    k
}

/// Largest difference of the state at scale `k` from the one at scale 1 (`got` and `base`),
/// in radians for angles and in fractions of the size `k` for lengths (`lengths[u]`, the
/// outputs all lengths): positions, and velocity and acceleration analogs, of the unknowns and
/// of the outputs.
fn difference<const N: usize, const NO: usize>(
    got: &Kin<N, 1, NO>,
    base: &Kin<N, 1, NO>,
    lengths: [bool; N],
    k: f64,
) -> f64 {
    let mut worst = 0.0f64;
    let mut see = |g: f64, b: f64, s: f64| {
        let d = (g / s - b).abs();
        worst = worst.max(if d.is_nan() { f64::INFINITY } else { d });
    };
    for u in 0..N {
        let s = if lengths[u] { k } else { 1.0 };
        see(got.q[u], base.q[u], s);
        see(got.dq[u][0], base.dq[u][0], s);
        see(got.d2q[u][0][0], base.d2q[u][0][0], s);
    }
    for o in 0..NO {
        see(got.out[o], base.out[o], k);
        see(got.dout[o][0], base.dout[o][0], k);
        see(got.d2out[o][0][0], base.d2out[o][0][0], k);
    }
    worst
}

/// Point solves at 12 inputs of a turn from the declared guess, at every scale: the largest
/// difference from scale 1 (which must solve), or the first error with its scale.
fn point_solves<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    at: impl Fn(f64) -> M,
    lengths: [bool; N],
) -> f64 {
    point_solves_at(at, lengths, &scales())
}

/// [`point_solves`] at the scales `ks`.
fn point_solves_at<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    at: impl Fn(f64) -> M,
    lengths: [bool; N],
    ks: &[f64],
) -> f64 {
    let cfg = NewtonConfig::default();
    let one = at(1.0);
    let mut worst = 0.0f64;
    for &k in ks {
        let m = at(k);
        for i in 0..12 {
            let x = [0.3 + i as f64 * 0.5];
            let base = one.kinematics_flat(&x, &one.guess_flat(&x), &cfg).unwrap();
            let got = m
                .kinematics_flat(&x, &m.guess_flat(&x), &cfg)
                .unwrap_or_else(|e| panic!("{} at size {k:e}: {e}", M::NAME));
            worst = worst.max(difference(&got, &base, lengths, k));
        }
    }
    worst
}

/// A sweep of a turn in 73 samples at every scale against the one at scale 1: the largest
/// difference over all samples.
fn sweeps<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(at: impl Fn(f64) -> M, lengths: [bool; N]) -> f64 {
    sweeps_at(at, lengths, &scales())
}

/// [`sweeps`] at the scales `ks`.
fn sweeps_at<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    at: impl Fn(f64) -> M,
    lengths: [bool; N],
    ks: &[f64],
) -> f64 {
    let run = |m: &M| -> Vec<Kin<N, 1, NO>> {
        Sweep::<M, Kin<N, 1, NO>, N, 1, NO>::new(m, [0.3], [0.3 + std::f64::consts::TAU], 73, m.guess_flat(&[0.3]))
            .unwrap()
            .map(|k| k.unwrap_or_else(|e| panic!("{}: {e}", M::NAME)))
            .collect()
    };
    let base = run(&at(1.0));
    let mut worst = 0.0f64;
    for &k in ks {
        let got = run(&at(k));
        assert_eq!(got.len(), base.len(), "{} at size {k:e}", M::NAME);
        for (g, b) in got.iter().zip(&base) {
            worst = worst.max(difference(g, b, lengths, k));
        }
    }
    worst
}

/// `1e-14` rad or of the size: the scaled parameters' own rounding (`k` times a length is
/// rounded, 1.1e-16 relative) amplified by the mechanism's condition, as in `units.rs`.
const SCALE_TOL: f64 = 1e-14;

/// [`SCALE_TOL`] of the polar pin's analogs' largest magnitude, about 30 at its inputs (the pin
/// passes near the rocker's pivot): the differences are absolute.
const POLAR_TOL: f64 = 30.0 * SCALE_TOL;

#[test]
fn four_bar_solves_at_every_scale() {
    let closed = point_solves(four_bar, [false, false]);
    let newton = point_solves(four_bar_newton, [false, false]);
    eprintln!("four-bar point solves over scales: closed form {closed:.1e}, Newton {newton:.1e}");
    assert!(closed <= SCALE_TOL && newton <= SCALE_TOL, "{closed:e} {newton:e}");
    let swept = sweeps(four_bar, [false, false]);
    assert!(swept <= SCALE_TOL, "four-bar sweeps differ by {swept:e}");
}

#[test]
fn slider_crank_solves_at_every_scale() {
    let closed = point_solves(slider_crank, [false, true]);
    let newton = point_solves(slider_crank_newton, [false, true]);
    eprintln!("slider-crank point solves over scales: closed form {closed:.1e}, Newton {newton:.1e}");
    assert!(closed <= SCALE_TOL && newton <= SCALE_TOL, "{closed:e} {newton:e}");
    let swept = sweeps(slider_crank, [false, true]);
    assert!(swept <= SCALE_TOL, "slider-crank sweeps differ by {swept:e}");
}

/// The polar length's angle is `atan2` of the pin's coordinates as they are, not normalised:
/// at every size where the normalisation's squares stay in range (up to `2^±509`, and `2^-511`,
/// whose squares are just normal), the scale-1 angles. The reference is the scale-1 solve,
/// checked here against paper 001's explicit polar coordinates of the pin, and the Newton twin
/// at every size (next test).
#[test]
fn a_polar_length_solves_at_every_scale_of_its_closed_form() {
    let one = polar_pin(1.0);
    let cfg = NewtonConfig::default();
    for i in 0..12 {
        let x = [0.3 + i as f64 * 0.5];
        let k = one.kinematics_flat(&x, &one.guess_flat(&x), &cfg).unwrap();
        let [phi, omega, _, s, ds, _] = gear_lever_explicit(2.0, 1.3, 3.0, x[0]);
        assert_close!(wrap(k.q[1] - phi), 0.0, tol::ULPS, "phi at {x:?}");
        assert_close!(k.q[0], s, tol::ULPS, "s at {x:?}");
        assert_close!(k.dq[1][0], omega, tol::ULPS * omega.abs().max(1.0), "phi' at {x:?}");
        assert_close!(k.dq[0][0], ds, tol::ULPS * ds.abs().max(1.0), "s' at {x:?}");
    }
    let mut ks: Vec<f64> = scales().into_iter().filter(|k| k.log2().abs() <= 509.0).collect();
    ks.extend([2f64.powi(509), 2f64.powi(-509), 2f64.powi(-511)]);
    let closed = point_solves_at(polar_pin, [true, false], &ks);
    eprintln!("polar pin point solves over scales: closed form {closed:.1e}");
    assert!(closed <= POLAR_TOL, "{closed:e}");
    let swept = sweeps_at(polar_pin, [true, false], &ks);
    assert!(swept <= POLAR_TOL, "polar pin sweeps differ by {swept:e}");
}

/// Newton's block of a length and an angle (the polar pin declared `#[kinloop(newton)]`) at
/// every size from `1e-300` to `1e300` and `2^±1000`: the scale-1 solve, from the declared
/// guess, for point solves and sweeps. Its Jacobian's length column holds pure numbers (the
/// direction) and its angle column lengths: a singularity test in the rows' units alone saw a
/// pivot shrink as one over the size and, from about `1e13` up to about `1e143` (beyond, the
/// whole system's rescale took over), refused every Newton step (the iteration stalled, "the
/// links cannot reach"); measured in the unknowns' units it is the same at every size.
#[test]
fn a_newton_block_of_a_length_and_an_angle_solves_at_every_scale() {
    // Its own scale-1 solve is the closed form's (an independent solver), in the closed form's
    // mode: from the declared guess Newton reaches, at some inputs, the same pin with the
    // length negative and the angle half a turn away (the other mode of `s (sin phi, cos phi)`).
    let cfg = NewtonConfig::default();
    let (closed, newton) = (polar_pin(1.0), polar_pin_newton(1.0));
    for i in 0..12 {
        let x = [0.3 + i as f64 * 0.5];
        let c = closed.kinematics_flat(&x, &closed.guess_flat(&x), &cfg).unwrap();
        let mut n = newton.kinematics_flat(&x, &newton.guess_flat(&x), &cfg).unwrap();
        if n.q[0].signum() != c.q[0].signum() {
            (n.q[0], n.dq[0][0], n.d2q[0][0][0]) = (-n.q[0], -n.dq[0][0], -n.d2q[0][0][0]);
            n.q[1] += std::f64::consts::PI;
        }
        n.q[1] = c.q[1] + wrap(n.q[1] - c.q[1]);
        assert!(difference(&n, &c, [true, false], 1.0) <= POLAR_TOL, "{x:?}: {n:?} {c:?}");
    }
    let solved = point_solves(polar_pin_newton, [true, false]);
    eprintln!("polar pin point solves over scales: Newton {solved:.1e}");
    assert!(solved <= POLAR_TOL, "{solved:e}");
    let swept = sweeps(polar_pin_newton, [true, false]);
    assert!(swept <= POLAR_TOL, "polar pin Newton sweeps differ by {swept:e}");
}

/// A mechanism of more unknowns than a sweep inlines has its own `kinematics_flat`; a failure
/// of its closed forms at an extreme size is rescued there too (and in its sweeps, which call
/// it).
#[test]
fn a_chain_of_ten_unknowns_solves_at_every_scale() {
    let closed = point_solves(chain, [false; 10]);
    let newton = point_solves(chain_newton, [false; 10]);
    eprintln!("four-bar chain point solves over scales: closed form {closed:.1e}, Newton {newton:.1e}");
    assert!(closed <= SCALE_TOL && newton <= SCALE_TOL, "{closed:e} {newton:e}");
    let swept = sweeps(chain, [false; 10]);
    assert!(swept <= SCALE_TOL, "chain sweeps differ by {swept:e}");
}

/// The reference the scale test above measures every scale against: the chain at scale 1,
/// closed form and Newton, stage by stage against a four-bar by hand (`support::four_bar_jets`) driven by the rocker of
/// the stage before (its analogs by the crank by the chain rule: `q' = q_x x'`, `q'' = q_xx
/// x'^2 + q_x x''`), each stage in the assembly mode the solve reached. Positions to
/// `tol::SOLVE`, and the analogs to `tol::SOLVE` relative: Newton's positions may stop that far
/// from the root, and the analogs inherit their error (measured: within 3e-15 for both).
#[test]
fn a_chain_of_ten_unknowns_matches_four_bars_in_series() {
    let cfg = NewtonConfig::default();
    let m = chain(1.0);
    let newton = chain_newton(1.0);
    for i in 0..12 {
        let phi = 0.3 + i as f64 * 0.5;
        let closed = m.kinematics_flat(&[phi], &m.guess_flat(&[phi]), &cfg);
        let twin = newton.kinematics_flat(&[phi], &newton.guess_flat(&[phi]), &cfg);
        for (path, k) in [("closed form", closed), ("Newton", twin)] {
            let k = k.unwrap_or_else(|e| panic!("{path} at {phi}: {e}"));
            // The stage's input: its position and analogs by the chain's crank.
            let mut input = [phi, 1.0, 0.0];
            for stage in 0..5 {
                let solved = [2 * stage, 2 * stage + 1];
                let by_hand = |side: f64| four_bar_jets(m.a, m.b, m.c, m.d, input[0], side).expect("a crank-rocker");
                let apart = |side: f64| {
                    let want = by_hand(side);
                    solved.iter().zip(&want).map(|(&u, w)| wrap(k.q[u] - w[0]).abs()).fold(0.0, f64::max)
                };
                let side = if apart(1.0) <= apart(-1.0) { 1.0 } else { -1.0 };
                // Each angle's jets by the crank; the rocker's drive the next stage.
                let want =
                    by_hand(side).map(|[q, qx, qxx]| [q, qx * input[1], qxx * input[1] * input[1] + qx * input[2]]);
                for (&u, [q, dq, d2q]) in solved.iter().zip(want) {
                    let at = format!("{path} at {phi}: {}", FourBarChain::UNKNOWNS[u]);
                    assert!(wrap(k.q[u] - q).abs() <= tol::SOLVE, "{at}: {} against {q}", k.q[u]);
                    assert_close!(k.dq[u][0], dq, rel = tol::SOLVE, "{at}'");
                    assert_close!(k.d2q[u][0][0], d2q, rel = tol::SOLVE, "{at}''");
                }
                input = want[1];
            }
        }
    }
}

/// The rhombic drive solved as one dense Newton block (`RhombicDriveDense`): its rods' angles
/// beside the piston's and the displacer's positions, whose Jacobian columns hold pure numbers
/// where the angles' hold lengths. At every size its point solves and sweeps are the scale-1
/// ones (which `tests/papers` checks against the paper's closed form).
#[test]
fn a_dense_block_of_lengths_and_angles_solves_at_every_scale() {
    let solved = point_solves(rhombic_dense, [false, false, true, true]);
    eprintln!("rhombic drive, one dense block, point solves over scales: {solved:.1e}");
    assert!(solved <= SCALE_TOL, "{solved:e}");
    let swept = sweeps(rhombic_dense, [false, false, true, true]);
    assert!(swept <= SCALE_TOL, "rhombic drive dense sweeps differ by {swept:e}");
}

/// The rhombic drive as declared: four closed-form blocks in turn (the rods' angles, then the
/// piston's and the displacer's positions), which the rescue beyond the closed forms' sizes
/// solves in turn too. At every size its point solves and sweeps are the scale-1 ones.
#[test]
fn a_mechanism_of_four_closed_form_blocks_solves_at_every_scale() {
    let solved = point_solves(rhombic_at::<RhombicDrive, _>, [false, false, true, true]);
    eprintln!("rhombic drive, four blocks, point solves over scales: {solved:.1e}");
    assert!(solved <= SCALE_TOL, "{solved:e}");
    let swept = sweeps(rhombic_at::<RhombicDrive, _>, [false, false, true, true]);
    assert!(swept <= SCALE_TOL, "rhombic drive sweeps differ by {swept:e}");
}

with_newton_twin! {
    /// A rocker driven by a cylinder whose length is the input (an RRR dyad with the input as a
    /// link, the frame's vector `(d, 0)`: a coefficient folded to zero).
    pub struct Cylinder, CylinderNewton {
        params c, d;
        input s;
        unknowns th = 1.5, ph = 2.0;
        loop l: c @ th == (d, 0) + s @ ph;
    }
}

/// A length input scales with the mechanism: at every scale, the cylinder's angles at `k`
/// times its lengths, the analogs by the input `1 / k` and `1 / k²` times the scale-1 ones
/// (each solve against its own at scale 1: from the declared guess Newton finds the other
/// assembly mode at some inputs). The folded dyad computed `a²` of coefficients that are
/// products of two lengths without rescaling: beyond `1e±77` it failed (not finite at 1e100, no
/// assembly at 1e-100). The acceleration analogs by the input, about `1 / k²` rad per unit of
/// length squared, are beyond `f64` below about `1e-154` and subnormal above about `1e154`:
/// the scales from `1e-150` to `1e150`.
#[test]
fn a_length_input_solves_at_every_scale() {
    let cfg = NewtonConfig::default();
    let closed = |k: f64, x: f64| Cylinder { c: k, d: 2.0 * k }.kinematics_flat(&[x], &[1.5, 2.0], &cfg);
    let newton = |k: f64, x: f64| CylinderNewton { c: k, d: 2.0 * k }.kinematics_flat(&[x], &[1.5, 2.0], &cfg);
    let mut worst = [0.0f64; 2];
    for k in scales().into_iter().filter(|&k| (1e-150..=1e150).contains(&k)) {
        for (path, solve) in [("closed form", &closed as &dyn Fn(f64, f64) -> _), ("Newton", &newton)] {
            for s0 in [1.2, 1.5, 2.0, 2.7] {
                let base = solve(1.0, s0).unwrap();
                let got = solve(k, s0 * k).unwrap_or_else(|e| panic!("{path} at size {k:e}, s = {s0}: {e}"));
                for u in 0..2 {
                    // Relative to the value where it exceeds 1 (the acceleration analogs reach 3.5).
                    let rel = |g: f64, b: f64| (g - b).abs() / b.abs().max(1.0);
                    let d = [
                        rel(got.q[u], base.q[u]),
                        rel(got.dq[u][0] * k, base.dq[u][0]),
                        rel(got.d2q[u][0][0] * k * k, base.d2q[u][0][0]),
                    ];
                    let w = &mut worst[usize::from(path == "Newton")];
                    *w = d.into_iter().fold(*w, |m, v| if v.is_nan() { f64::INFINITY } else { m.max(v) });
                }
            }
        }
    }
    eprintln!("cylinder over scales: closed form {:.1e}, Newton {:.1e}", worst[0], worst[1]);
    assert!(worst[0] <= SCALE_TOL && worst[1] <= SCALE_TOL, "{worst:?}");
}

/// The cylinder's jets by hand from `c e(th) = d + s e(ph)`: C on the circles (O, c) and
/// (D, s), D = (d, 0), on side `side` of O -> D (+1 above); differentiating by `s` and taking
/// the components along and across `e(ph)` (`w = th - ph`): `th' = -1 / (c sin w)`, `ph' = c th'
/// cos(w) / s`, `th'' = (s ph'^2 - c th'^2 cos w) / (c sin w)`, `ph'' = (c th'' cos w - c th'^2
/// sin w - 2 ph') / s`. `[th, ph]`, each `[position, first, second]`.
fn cylinder_by_hand(c: f64, d: f64, s: f64, side: f64) -> [[f64; 3]; 2] {
    let (cx, cy) = crate::support::circle_point(0.0, 0.0, c, d, 0.0, s, side);
    let (th, ph) = (cy.atan2(cx), cy.atan2(cx - d));
    let (sw, cw) = (th - ph).sin_cos();
    let th1 = -1.0 / (c * sw);
    let ph1 = c * th1 * cw / s;
    let th2 = (s * ph1 * ph1 - c * th1 * th1 * cw) / (c * sw);
    let ph2 = (c * th2 * cw - c * th1 * th1 * sw - 2.0 * ph1) / s;
    [[th, th1, th2], [ph, ph1, ph2]]
}

/// The reference the scale test above measures every scale against: the cylinder at scale 1,
/// closed form and Newton, against the triangle O-C-D and its analogs by the input length
/// differentiated by hand, in the assembly mode each solve reaches, over the strokes that
/// assemble (`1 < s < 3`; the ends are folds, where `sin w` vanishes, so 1.1 to 2.9). Positions
/// to `tol::SOLVE`, and the analogs relative: a handful of operations on the positions with
/// `|sin w| >= 0.35` here, they inherit the positions' error (measured: up to 4e-14, Newton's,
/// whose positions stop within its residual tolerance).
#[test]
fn a_length_input_matches_its_triangle() {
    let cfg = NewtonConfig::default();
    let (c, d) = (1.0, 2.0);
    for i in 0..=36 {
        let s = 1.1 + 1.8 * i as f64 / 36.0;
        let closed = Cylinder { c, d }.kinematics_flat(&[s], &[1.5, 2.0], &cfg);
        let newton = CylinderNewton { c, d }.kinematics_flat(&[s], &[1.5, 2.0], &cfg);
        for (path, k) in [("closed form", closed), ("Newton", newton)] {
            let k = k.unwrap_or_else(|e| panic!("{path} at s = {s}: {e}"));
            // The mode the solve reached: C above or below the line of the pivots.
            let side = if k.q[0].sin() >= 0.0 { 1.0 } else { -1.0 };
            let want = cylinder_by_hand(c, d, s, side);
            for u in 0..2 {
                let [q, dq, d2q] = want[u];
                assert!(wrap(k.q[u] - q).abs() <= tol::SOLVE, "{path} at s = {s}: q[{u}] {} against {q}", k.q[u]);
                assert_close!(k.dq[u][0], dq, rel = tol::SOLVE, "{path} at s = {s}: dq[{u}]");
                assert_close!(k.d2q[u][0][0], d2q, rel = tol::SOLVE, "{path} at s = {s}: d2q[{u}]");
            }
        }
    }
}

/// Links of very different lengths in one dyad: a parallelogram four-bar of crank and rocker 1
/// on a coupler and frame of `k` (`a = c = 1`, `b = d = k`), whose rocker on its parallelogram
/// branch turns with the crank, `gamma = phi` exactly, and whose coupler stays parallel to the
/// frame. The closed form's rocker is that angle to the data's own rounding (the frame's end at
/// `cos phi - k` is a double `eps k` apart, so `gamma` is known to about `eps k` of the unit
/// link), as the Newton twin's is. It solved the long coupler's angle first from a near
/// tangent circle intersection: `eps / sin` of the dyad's thin angle (`~1 / k`), which left the
/// rocker 2.6e-10 rad off at `k = 2e3`, 2.9e-4 at `2e6` and radians off at `2e9` with a
/// healthy pivot ratio, no error and a loop residual of 33 unit links.
#[test]
fn a_dyad_of_a_short_and_a_long_link_keeps_the_short_links_angle() {
    for k in [2e3, 2e6, 2e9, 2e12] {
        let m = FourBar { a: 1.0, b: k, c: 1.0, d: k };
        let twin = FourBarNewton { a: 1.0, b: k, c: 1.0, d: k };
        for phi in [-2.8, -1.1, 0.3, 1.7, 2.9] {
            // The parallelogram branch: beta = 0, gamma = phi.
            let closed = m.kinematics(phi, &FourBarUnknowns { beta: 0.0, gamma: phi }).unwrap();
            let newton = twin.kinematics(phi, &FourBarNewtonUnknowns { beta: 0.0, gamma: phi }).unwrap();
            // Four roundings of the frame's end, `eps k` each, over the unit link.
            let known = 4.0 * f64::EPSILON * k;
            for (path, q) in
                [("closed form", [closed.q.beta, closed.q.gamma]), ("Newton", [newton.q.beta, newton.q.gamma])]
            {
                assert!(
                    wrap(q[1] - phi).abs() <= known,
                    "k {k:e}, phi {phi}, {path}: gamma {} (off {:e})",
                    q[1],
                    q[1] - phi
                );
                // The coupler's angle, its offset over its own length `k`.
                assert!(wrap(q[0]).abs() <= known / k, "k {k:e}, phi {phi}, {path}: beta {}", q[0]);
            }
            // A regular position: its analogs are the parallelogram's, `dgamma/dphi = 1` and
            // the other three 0. Each path's analogs are exact ones at its own position, whose
            // rocker direction (the sine and cosine its Jacobian reads) is `delta <= known` off;
            // by the velocity equations (`s = |sin phi|`, the coupler's terms over `k`):
            // `dgamma = sin(phi - beta) / sin(gamma - beta)`, off by `delta / s`, and `dbeta`,
            // `cos gamma dgamma - cos phi` over `k`, by `delta (1 + 1 / s) / k`; the acceleration
            // equations' right-hand side `e(phi) - e(gamma) dgamma^2 + k e(beta) dbeta^2` is
            // `delta (1 + 2 / s)` from zero, so `d2gamma` is within that over `s` and `d2beta`
            // within `delta (1 + 2 / s) (1 + 1 / s) / k`. Seen (`known` = 1.8e-12 to 1.8e-3), in
            // `known` at phi = 2.9 (the bounds in brackets): the closed form's `dgamma` 1.25 off
            // (4.2), `dbeta` 1.23 / k (5.2), `d2gamma` 10.2 (39), `d2beta` 10.2 / k (49); the
            // Newton twin's all below 1e-3.
            let s = phi.sin().abs();
            let bounds = [
                (known / s, known * (1.0 + 1.0 / s) / k),
                (known * (1.0 + 2.0 / s) / s, known * (1.0 + 2.0 / s) * (1.0 + 1.0 / s) / k),
            ];
            for (path, kin) in [("closed form", &closed.flat), ("Newton", &newton.flat)] {
                let [beta, gamma] = [0, 1];
                let (d, d2) = (kin.dq, kin.d2q);
                assert_close!(d[gamma][0], 1.0, <= bounds[0].0, "k {k:e}, phi {phi}, {path}: dgamma");
                assert_close!(d[beta][0], 0.0, <= bounds[0].1, "k {k:e}, phi {phi}, {path}: dbeta");
                assert_close!(d2[gamma][0][0], 0.0, <= bounds[1].0, "k {k:e}, phi {phi}, {path}: d2gamma");
                assert_close!(d2[beta][0][0], 0.0, <= bounds[1].1, "k {k:e}, phi {phi}, {path}: d2beta");
            }
        }
        // A sweep's kernel (its checks deferred) solves the same dyad, between the change
        // points at 0 and pi (the links in line).
        let guess = FourBarUnknowns { beta: 0.0, gamma: 0.2 };
        for st in m.sweep(0.2, 2.9, 23, &guess).unwrap() {
            let st = st.unwrap();
            let (phi, gamma) = (st.input.phi, st.q.gamma);
            assert!(wrap(gamma - phi).abs() <= 4.0 * f64::EPSILON * k, "k {k:e}, sweep at {phi}: gamma {gamma}");
        }
    }
}

/// A traced curve (pseudo-arclength continuation) of the polar pin stays on the curve at every
/// size: each point's angle is paper 001's explicit `phi` at its input to `TRACE_TOL` rad and
/// its length the explicit `s` to `TRACE_TOL` of the size, and the trace takes the same points
/// (its arclength is measured in the unknowns' units) and closes after the same turn. The
/// corrector judged each row against `sum |J_ru| + |f_sigma|` when that exceeded the row's
/// magnitude: by the length `s` a loop's derivative is a direction (about one whatever the
/// size), so below a size of about `1e-8` every residual was judged against one, the predictor
/// met the tolerance as it stood, and each point was one correction from it: `1e-8` rad off the
/// curve at `2e-10`, and at every smaller size.
#[test]
fn a_traced_polar_pin_stays_on_its_curve_at_every_scale() {
    use std::f64::consts::TAU;
    // Newton's residual test is met and the point corrected once more (quadratic convergence:
    // the error is rounding); the angle's rounding is amplified by the size over the pin's
    // least distance from O (3.3 / 0.7, about 5): up to 7e-15 rad, 1e-15 of the size and 8e-15
    // rad of the inputs were seen over these scales (1e-8 rad before, from 1e-10 down).
    const TRACE_TOL: f64 = 5.0 * tol::ULPS;
    let opts = kinloop::TraceConfig::default();
    let trace = |k: f64| {
        let m = polar_pin(k);
        let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
        m.trace_curve(0.0, TAU, &g, &opts).unwrap()
    };
    let reference = trace(1.0);
    for k in [1.0, 1e-10, 1e-30, 1e-100, 1e10, 1e100] {
        let t = trace(k);
        assert!(t.closed && !t.truncated && t.folds.is_empty(), "k={k:e}: {} points", t.points.len());
        assert_eq!(t.points.len(), reference.points.len(), "k={k:e}");
        let (mut angle, mut length, mut input) = (0.0f64, 0.0f64, 0.0f64);
        for (p, r) in t.points.iter().zip(&reference.points) {
            let [phi, _, _, s, _, _] = gear_lever_explicit(2.0, 1.3, 3.0, p.x[0]);
            angle = angle.max(wrap(p.q[1] - phi).abs());
            length = length.max((p.q[0] / k - s).abs() / 3.3);
            input = input.max((p.x[0] - r.x[0]).abs());
        }
        eprintln!("traced polar pin at {k:e}: angles {angle:.1e}, lengths {length:.1e}, inputs {input:.1e}");
        assert!(angle <= TRACE_TOL && length <= TRACE_TOL, "k={k:e}: angles {angle:e}, lengths {length:e} off");
        assert!(input <= TRACE_TOL, "k={k:e}: inputs {input:e} from scale 1's");
    }
}

/// The four-bar with sensitivities at size `k` (link lengths 1, 3.5, 3, 4 times `k`).
fn four_bar_sens(k: f64) -> FourBarSens {
    FourBarSens { a: k, b: 3.5 * k, c: 3.0 * k, d: 4.0 * k }
}

/// Every sensitivity of the four-bar (2 angles, 1 input, 2 lengths out, 4 lengths as
/// parameters), each times the power of `k` that makes it the one at scale 1: an angle's
/// sensitivity to a length, and its analogs' (the input is an angle), scale as `1 / k`; a
/// length's to a length as 1.
fn unit_sensitivities(s: &Sens<2, 1, 2, 4>, k: f64) -> Vec<f64> {
    let angles = s.q.iter().chain(s.dq.iter().map(|d| &d[0])).chain(s.d2q.iter().map(|d| &d[0][0]));
    let lengths = s.out.iter().chain(s.dout.iter().map(|d| &d[0])).chain(s.d2out.iter().map(|d| &d[0][0]));
    angles.flatten().map(|v| v * k).chain(lengths.flatten().copied()).collect()
}

/// The scales at which the closed form's squared lengths leave `f64` (beyond `1e±155`): the
/// four-bar's compiled sensitivity solve failed at each, with a singular position at 1e-200,
/// no assembly at 1e-160 (a residual of 7.4e-320) and an equation not finite at 1e200, where
/// its `kinematics_flat`, `sensitivities_at_flat` and the run-time model all solved.
const SENSITIVITY_SCALES: [f64; 5] = [1e-300, 1e-200, 1e-160, 1e200, 1e300];

/// The compiled `sensitivities_flat` at sizes beyond the closed forms' is rescued as
/// `kinematics_flat` is: the sensitivities at the position Newton over the whole system finds,
/// equal to `sensitivities_at_flat` there and to the scale-1 ones scaled. Tolerance: the
/// rescued position is the scale-1 one to `SCALE_TOL` (rad), and a sensitivity is a smooth
/// function of the position whose derivatives are of the order of the sensitivities themselves
/// away from a singular position (a few units here): `10 SCALE_TOL`, relative to the value
/// where it exceeds 1.
#[test]
fn four_bar_sensitivities_solve_at_every_scale() {
    let cfg = NewtonConfig::default();
    let one = four_bar_sens(1.0);
    let mut worst = 0.0f64;
    for k in SENSITIVITY_SCALES {
        let m = four_bar_sens(k);
        for i in 0..12 {
            let x = [0.3 + i as f64 * 0.5];
            let (base_kin, base) = one.sensitivities_flat(&x, &one.guess_flat(&x), &cfg).unwrap();
            let (kin, sens) = m
                .sensitivities_flat(&x, &m.guess_flat(&x), &cfg)
                .unwrap_or_else(|e| panic!("sensitivities at size {k:e}, phi {}: {e}", x[0]));
            worst = worst.max(difference(&kin, &base_kin, [false, false], k));
            for (g, b) in unit_sensitivities(&sens, k).into_iter().zip(unit_sensitivities(&base, 1.0)) {
                let d = (g - b).abs() / b.abs().max(1.0);
                worst = worst.max(if d.is_nan() { f64::INFINITY } else { d });
            }
            // The same as at the position it solved, and its kinematics `kinematics_flat`'s.
            let (kin_at, at) = m.sensitivities_at_flat(&x, &kin.q, &cfg).unwrap();
            let plain = m.kinematics_flat(&x, &m.guess_flat(&x), &cfg).unwrap();
            assert_eq!((kin.q, kin.dq, kin.out), (plain.q, plain.dq, plain.out), "size {k:e}, phi {}", x[0]);
            assert_eq!((kin.d2q, kin.d2out), (kin_at.d2q, kin_at.d2out), "size {k:e}, phi {}", x[0]);
            assert_eq!(sens, at, "size {k:e}, phi {}", x[0]);
        }
    }
    eprintln!("four-bar sensitivities over scales: {worst:.1e}");
    assert!(worst <= 10.0 * SCALE_TOL, "{worst:e}");
}

/// A four-bar that cannot be assembled (its frame longer than the other three links together)
/// fails at every scale, and `sensitivities_flat` reports the error `kinematics_flat` does: no
/// assembly at scale 1, and beyond the closed forms' sizes, where the rescue's Newton fails
/// too, Newton's failure, no assembly as well (not what the closed forms' overflow or underflow
/// made of it).
#[test]
fn a_four_bar_that_cannot_be_assembled_keeps_its_error_in_a_sensitivity_solve() {
    let cfg = NewtonConfig::default();
    for k in [1.0].into_iter().chain(SENSITIVITY_SCALES) {
        let m = FourBarSens { a: k, b: 1.5 * k, c: k, d: 4.0 * k };
        let x = [1.7];
        let sens = m.sensitivities_flat(&x, &m.guess_flat(&x), &cfg).unwrap_err();
        let kin = m.kinematics_flat(&x, &m.guess_flat(&x), &cfg).unwrap_err();
        assert_eq!(sens.to_string(), kin.to_string(), "size {k:e}");
        assert!(matches!(sens, kinloop::Error::NoAssembly { .. }), "size {k:e}: {sens}");
    }
}

/// The sizes beyond the closed forms' (`1e±144`) at which a four-bar that cannot close its loop
/// was reported singular (`1e-300`, `1e-200`: the squared lengths subnormal or zero) or its
/// equation not finite (`1e200`, `1e300`: overflowed), and at `1e-160` as no assembly with a
/// residual of `1e-319`, the closed form's squares' units: every one the rescue's Newton over
/// the whole system failed at too, and whose failure it did not report.
const UNASSEMBLED_SCALES: [f64; 5] = [1e-300, 1e-200, 1e-160, 1e200, 1e300];

/// A four-bar whose crank is too long to close the loop at some inputs (frame 3, crank 2,
/// coupler 1.5, rocker 2, times `k`): at `phi = 3` the crank's end is 4.98 from the rocker's
/// pivot, beyond the coupler and the rocker together (3.5); at `phi = 0.3` it assembles.
fn crank_too_long(k: f64) -> [f64; 4] {
    [2.0 * k, 1.5 * k, 2.0 * k, 3.0 * k]
}

/// The error of a four-bar that cannot close its loop at the input is the one it has at size
/// 1, whatever its size: no assembly, in its loop's block, at the input it failed at. The
/// closed form says so at size 1; the generated Newton solver (the twin) says so at every
/// size, and so must the rescue where its own Newton over the whole system fails, for a point
/// step and a sensitivity solve, and for the chain's kernel of its own. The variants are
/// compared, not the messages: a residual is measured differently by a closed form and by
/// Newton. The chain's block too: its first loop, as its blocks solved in turn name it (Newton
/// over its five loops at once stalled where their residuals balanced, and named the loop whose
/// residual was largest there, a later one, which one depending on the size).
#[test]
fn a_four_bar_whose_crank_cannot_close_fails_alike_at_every_scale() {
    use kinloop::Error;
    use std::mem::discriminant;
    let cfg = NewtonConfig::default();
    let x = [3.0];
    let kind =
        |e: &Error| (discriminant(e), e.location().map(|at| (at.inputs.clone(), at.block.as_ref().map(|b| b.0))));
    let closed = |k: f64| {
        let [a, b, c, d] = crank_too_long(k);
        FourBar { a, b, c, d }.kinematics_flat(&x, &FourBar { a, b, c, d }.guess_flat(&x), &cfg)
    };
    let one = closed(1.0).unwrap_err();
    assert!(matches!(one, Error::NoAssembly { .. }), "at size 1: {one:?}");
    let want = kind(&one);
    assert_eq!(want.1, Some((vec![("phi".into(), 3.0)], Some(0))), "{one:?}");
    for k in [1.0].into_iter().chain(UNASSEMBLED_SCALES) {
        let [a, b, c, d] = crank_too_long(k);
        // Not a mechanism broken at every input: it assembles at 0.3 at this size.
        assert!(closed(k).is_err() && FourBar { a, b, c, d }.kinematics_flat(&[0.3], &[0.5, 1.5], &cfg).is_ok());
        let twin = FourBarNewton { a, b, c, d };
        let sens = FourBarSens { a, b, c, d };
        let chain = FourBarChain { a, b, c, d };
        let got = [
            ("closed form", closed(k).map(drop)),
            ("Newton twin", twin.kinematics_flat(&x, &twin.guess_flat(&x), &cfg).map(drop)),
            ("sensitivities", sens.sensitivities_flat(&x, &sens.guess_flat(&x), &cfg).map(drop)),
            ("chain", chain.kinematics_flat(&x, &chain.guess_flat(&x), &cfg).map(drop)),
        ];
        for (path, e) in got {
            let e = e.expect_err(path);
            assert_eq!(kind(&e), want, "{path} at size {k:e}: {e:?}");
        }
    }
}

/// Positions alone (`position_flat`) of `at(k)` at 12 inputs of a turn from the declared guess,
/// at each scale of `ks`: the largest difference from scale 1 (which must solve), in radians
/// for angles and in fractions of the size `k` for lengths (`lengths[u]`), or the first error
/// with its scale. Each position is also the one `kinematics_flat` and the named `position`
/// solve there, to the bit (the same solve, with or without analogs).
fn position_solves_at<M, const N: usize, const NO: usize>(at: impl Fn(f64) -> M, lengths: [bool; N], ks: &[f64]) -> f64
where
    M: kinloop::Named<N, 1, NO>,
{
    let cfg = NewtonConfig::default();
    let one = at(1.0);
    let mut worst = 0.0f64;
    for &k in ks {
        let m = at(k);
        for i in 0..12 {
            let x = [0.3 + i as f64 * 0.5];
            let (base, _) = one.position_flat(&x, &one.guess_flat(&x), &cfg).unwrap();
            let (q, _) = m
                .position_flat(&x, &m.guess_flat(&x), &cfg)
                .unwrap_or_else(|e| panic!("{} positions at size {k:e}, input {}: {e}", M::NAME, x[0]));
            for u in 0..N {
                let d = (q[u] / if lengths[u] { k } else { 1.0 } - base[u]).abs();
                worst = worst.max(if d.is_nan() { f64::INFINITY } else { d });
            }
            let kin = m.kinematics_flat(&x, &m.guess_flat(&x), &cfg).unwrap();
            assert_eq!(q, kin.q, "{} at size {k:e}, input {}", M::NAME, x[0]);
            let named: [f64; N] = m.position(x, &m.guess_flat(&x).into()).unwrap().0.into();
            assert_eq!(q, named, "{} at size {k:e}, input {}", M::NAME, x[0]);
        }
    }
    worst
}

/// The sizes at which the positions alone were not rescued: the four-bar's `position_flat`
/// failed at every input, singular at `1e-300` and `1e-200` (squared lengths subnormal or
/// zero) and its equation not finite at `1e200` and `1e300` (overflowed), where
/// `kinematics_flat` and the named `position` solved.
const POSITION_SCALES: [f64; 4] = [1e-300, 1e-200, 1e200, 1e300];

/// The positions alone of the gear-lever's polar length at every size are size 1's, and those
/// of `kinematics_flat` to the bit: its closed form normalises the pin's direction by the
/// square root of its squared length, which overflows from about `1.3e154` (at `1e155` the
/// pin's coordinates are about `3e155`), and `position_flat` took the overflowed square for a
/// direction of length 0: the length `-0.0` and an angle, its loop open by the pin's whole
/// length, with no error, at `1e160`, `1e200` and `1e300` (`kinematics_flat`, whose analogs
/// then fail, was rescued).
#[test]
fn positions_alone_of_a_polar_length_solve_at_every_scale() {
    let polar = position_solves_at(polar_pin, [true, false], &[1e-300, 1e-200, 1e155, 1e160, 1e200, 1e300]);
    eprintln!("positions alone over scales: polar pin {polar:.1e}");
    assert!(polar <= POLAR_TOL, "{polar:e}");
}

kinloop::mechanism! {
    /// The gear-lever's pin read as a ratio `s` of a rod of length `l` and its angle `phi`: a
    /// length along a turning direction whose direction carries a length, so that the closed
    /// form's squared direction is a product of four lengths.
    pub struct ScaledPolar {
        params l_c, l_p, u, l;
        input alpha;
        unknowns s = 1.0, phi = 0;
        let pin = (l_c * sin(alpha), l_c * cos(alpha))
                + (l_p * sin((1 - u) * alpha), l_p * cos((1 - u) * alpha));
        loop oab: pin == s * (l * sin(phi), l * cos(phi));
    }
}

fn scaled_polar(k: f64) -> ScaledPolar {
    ScaledPolar { l_c: 2.0 * k, l_p: 1.3 * k, u: 3.0, l: 2.5 * k }
}

/// A closed form whose squares are products of four lengths overflows from about `1e77` of its
/// unit, inside the sizes the rescue is made for (`1e±144`): there its overflow is answered by
/// Newton as beyond them, and the ratio and the angle are size 1's, the point solves and the
/// positions alone, at every size up to `1e300`. From `1e77` to `1e140` both failed, said to
/// leave the equation's domain (`Error::Domain`), a mechanism that is fine.
#[test]
fn a_closed_form_of_four_lengths_solves_where_its_squares_overflow() {
    assert!(ScaledPolar::DECOMPOSITION.contains("closed form, length and angle"), "{}", ScaledPolar::DECOMPOSITION);
    let ks = [1e60, 1e77, 1e80, 1e100, 1e140, 1e160, 1e300];
    let solved = point_solves_at(scaled_polar, [false, false], &ks);
    let alone = position_solves_at(scaled_polar, [false, false], &ks);
    eprintln!("scaled polar over scales: point solves {solved:.1e}, positions alone {alone:.1e}");
    assert!(solved <= POLAR_TOL && alone <= POLAR_TOL, "{solved:e} {alone:e}");
}

/// The compiled `position_flat` (the positions alone, what a synthesis objective without
/// derivatives and a drawing's reference state solve) is rescued beyond the closed forms' sizes
/// as `kinematics_flat` is: the four-bar's, the slider-crank's (a length among the unknowns)
/// and the ten-unknown chain's positions at every size are the scale-1 ones, angles equal and
/// lengths scaled, to [`SCALE_TOL`] (the scaled parameters' rounding through the mechanism's
/// condition, as for the point solves).
#[test]
fn positions_alone_solve_at_every_scale() {
    let four = position_solves_at(four_bar, [false, false], &POSITION_SCALES);
    let slider = position_solves_at(slider_crank, [false, true], &POSITION_SCALES);
    let chain = position_solves_at(chain, [false; 10], &POSITION_SCALES);
    eprintln!("positions alone over scales: four-bar {four:.1e}, slider-crank {slider:.1e}, chain {chain:.1e}");
    assert!(four <= SCALE_TOL && slider <= SCALE_TOL && chain <= SCALE_TOL, "{four:e} {slider:e} {chain:e}");
    // A synthesis objective without derivatives solves through `position_flat`
    // (`SensKernel::position_into`): the same positions and the outputs there.
    use kinloop::SensKernel;
    let cfg = NewtonConfig::default();
    let one = kinloop::CompiledSens(four_bar_sens(1.0));
    for k in POSITION_SCALES {
        let m = kinloop::CompiledSens(four_bar_sens(k));
        let x = [1.3];
        let (mut q, mut out) = ([0.0; 2], [0.0; 2]);
        let (mut q1, mut out1) = ([0.0; 2], [0.0; 2]);
        one.position_into(&x, &one.0.guess_flat(&x), &cfg, &mut q1, &mut out1).unwrap();
        m.position_into(&x, &m.0.guess_flat(&x), &cfg, &mut q, &mut out)
            .unwrap_or_else(|e| panic!("position_into at size {k:e}: {e}"));
        for u in 0..2 {
            assert!((q[u] - q1[u]).abs() <= SCALE_TOL, "size {k:e}: {q:?} against {q1:?}");
            assert!((out[u] / k - out1[u]).abs() <= SCALE_TOL * 5.0, "size {k:e}: {out:?} against {out1:?}");
        }
    }
}

/// A four-bar that cannot close its loop at the input fails in `position_flat` with the error it
/// has at size 1, at every size: no assembly, in its loop's block, at that input; the same error
/// as `kinematics_flat`'s (the same Newton over the whole system fails, whatever is computed
/// after it). Before, the closed form's error stood: singular at `1e-300` and `1e-200`, the
/// equation not finite at `1e200` and `1e300`. At an input where it assembles, the positions
/// alone solve at every size.
#[test]
fn positions_alone_of_a_four_bar_that_cannot_close_fail_alike_at_every_scale() {
    use kinloop::Error;
    let cfg = NewtonConfig::default();
    let one = {
        let [a, b, c, d] = crank_too_long(1.0);
        FourBar { a, b, c, d }
    };
    let base = one.position_flat(&[0.3], &one.guess_flat(&[0.3]), &cfg).unwrap().0;
    for k in [1.0].into_iter().chain(POSITION_SCALES) {
        let [a, b, c, d] = crank_too_long(k);
        let m = FourBar { a, b, c, d };
        let x = [3.0];
        let e = m.position_flat(&x, &m.guess_flat(&x), &cfg).unwrap_err();
        assert!(matches!(e, Error::NoAssembly { .. }), "size {k:e}: {e:?}");
        let at = e.location().map(|at| (at.inputs.clone(), at.block.as_ref().map(|b| b.0)));
        assert_eq!(at, Some((vec![("phi".into(), 3.0)], Some(0))), "size {k:e}: {e:?}");
        let kin = m.kinematics_flat(&x, &m.guess_flat(&x), &cfg).unwrap_err();
        assert_eq!(e.to_string(), kin.to_string(), "size {k:e}");
        let (q, _) =
            m.position_flat(&[0.3], &m.guess_flat(&[0.3]), &cfg).unwrap_or_else(|e| panic!("size {k:e}, phi 0.3: {e}"));
        assert!((q[0] - base[0]).abs() <= SCALE_TOL && (q[1] - base[1]).abs() <= SCALE_TOL, "size {k:e}: {q:?}");
    }
}

/// The residual of an error, where it is no assembly.
fn no_assembly_residual(e: &kinloop::Error) -> f64 {
    match e {
        kinloop::Error::NoAssembly { residual, .. } => *residual,
        other => panic!("no assembly expected: {other:?}"),
    }
}

/// A closed form that cannot be assembled reports a residual free of the units, as Newton's
/// is (its residual over the magnitude of its equation's terms), so that the same mechanism
/// reads the same at every size, close to what Newton says of it. A dyad (the four-bar whose
/// crank cannot close at `phi = 3`; the cylinder whose rocker and stroke are too unequal for
/// the pivots' distance, its second coefficient folded to zero): how far its links fall short
/// of closing the triangle with their centres' distance `|AD|`, over the dyad's size
/// `b + c + |AD|`. A slider's angle equation (the offset slider-crank whose rod cannot reach
/// the line at `phi = -1`): `|c| - l` over the sum of the lengths in the equation, `r + l + e`,
/// `c` the offset the rod must span (over `|c| + l`, 1.8 % from Newton's, before its misses
/// were judged in the magnitude of its terms). Each to `SCALE_TOL` of the value derived here
/// at size 1 (the lengths' rounding), at sizes 1, `1e-100` and `1e100`; each within 2 % of the
/// Newton twin's at the same size, which is the same gap's component in its worst equation
/// over that equation's magnitude (a frame's length apart: 0.3 % here; the slider-crank's the
/// same measure, 4e-6 apart). The dyads reported the gap in
/// the units of their coefficients, products of two lengths: 4.08 at size 1 and 4.08e200 at
/// `1e100` ("the loop residual stalls at 4.08e200"), 3.5 times the size squared for the
/// cylinder; the slider-crank its gap in lengths, 2.64 times the size.
#[test]
fn a_closed_form_that_cannot_be_assembled_reports_a_residual_free_of_its_size() {
    let cfg = NewtonConfig::default();
    // The four-bar: the crank's end `A = 2 (cos 3, sin 3)` and the rocker's pivot `D = (3, 0)`,
    // coupler 1.5 and rocker 2.
    let ad = (2.0 * 3f64.cos() - 3.0).hypot(2.0 * 3f64.sin());
    let four_bar_gap = (ad - 3.5) / (ad + 3.5);
    // The cylinder: pivots 2 apart, rocker 1, stroke 4: the stroke 1 too long.
    let cylinder_gap = (4.0 - 1.0 - 2.0) / (4.0 + 1.0 + 2.0);
    // The slider-crank: crank 1, rod 3.2, line at 5: `l sin psi = sin(-1) - 5`.
    let offset = ((-1f64).sin() - 5.0).abs();
    let slider_gap = (offset - 3.2) / (1.0 + 3.2 + 5.0);
    for k in [1.0, 1e-100, 1e100] {
        let [a, b, c, d] = crank_too_long(k);
        let (m, twin) = (FourBar { a, b, c, d }, FourBarNewton { a, b, c, d });
        let (cy, cy_twin) = (Cylinder { c: k, d: 2.0 * k }, CylinderNewton { c: k, d: 2.0 * k });
        let sc = SliderCrank { r: k, l: 3.2 * k, e: 5.0 * k };
        let sc_twin = SliderCrankNewton { r: k, l: 3.2 * k, e: 5.0 * k };
        let cases = [
            (
                "four-bar",
                m.kinematics_flat(&[3.0], &m.guess_flat(&[3.0]), &cfg).map(drop),
                twin.kinematics_flat(&[3.0], &twin.guess_flat(&[3.0]), &cfg).map(drop),
                four_bar_gap,
            ),
            (
                "cylinder",
                cy.kinematics_flat(&[4.0 * k], &[1.5, 2.0], &cfg).map(drop),
                cy_twin.kinematics_flat(&[4.0 * k], &[1.5, 2.0], &cfg).map(drop),
                cylinder_gap,
            ),
            (
                "slider-crank",
                sc.kinematics_flat(&[-1.0], &sc.guess_flat(&[-1.0]), &cfg).map(drop),
                sc_twin.kinematics_flat(&[-1.0], &sc_twin.guess_flat(&[-1.0]), &cfg).map(drop),
                slider_gap,
            ),
        ];
        for (what, closed, newton, want) in cases {
            let (closed, newton) = (closed.unwrap_err(), newton.unwrap_err());
            let (got, by_newton) = (no_assembly_residual(&closed), no_assembly_residual(&newton));
            eprintln!("{what} at size {k:e}: closed form {got:.6}, Newton {by_newton:.6}, gap {want:.6}");
            assert!((got - want).abs() <= SCALE_TOL, "{what} at size {k:e}: {closed}");
            assert!((got - by_newton).abs() <= 0.02 * by_newton, "{what} at size {k:e}: {closed}\n{newton}");
        }
    }
}

with_newton_twin! {
    /// The offset slider-crank of `units.rs`'s `RodLength`: the slider's position `x` from the
    /// rod's length squared alone, a Newton block of one length whose equation's terms are
    /// squared lengths. Its magnitude, `(|x| + |r|)^2 + (|r| + |e|)^2 + |l|^2`, is about
    /// `39 k^2` at size `k`: subnormal below about `k = 1e-155`, zero below about `1e-162`.
    pub struct RodSquared, RodSquaredNewton {
        params r, l, e;
        input phi;
        unknowns x = l;
        eq rod: (x - r * cos(phi)) ^ 2 + (r * sin(phi) - e) ^ 2 == l * l;
    }
}

/// The rod-length slider-crank's links (crank, rod, offset) at size 1.
const ROD: (f64, f64, f64) = (1.0, 3.2, 0.4);

/// The slider's position at size 1 on the declared branch (the guess `x = l` lies beside the
/// root ahead of the crank): `r cos phi + sqrt(l^2 - (r sin phi - e)^2)`.
fn rod_closed_form(phi: f64) -> f64 {
    let (r, l, e) = ROD;
    r * phi.cos() + (l * l - (r * phi.sin() - e).powi(2)).sqrt()
}

/// How far a solved slider position may be from the closed form, in fractions of the size `k`.
/// Newton accepts a residual of `residual_tol` of the magnitude `M` and evaluates it to its
/// rounding, itself at most `residual_tol` of `M` wherever a solve may succeed: the true
/// residual at the result is at most `2 residual_tol M`. The residual's derivative is
/// `2 (x - r cos phi) = 2 sqrt(l^2 - (r sin phi - e)^2)`, at least `2 sqrt(l^2 - (r + e)^2) k`
/// = `5.75 k`, and `M` at most `((r + l) + r)^2 + (r + e)^2 + l^2` = `39.3 k^2`: the position is
/// off by at most `2 residual_tol 39.3 / 5.75`, `1.4e-11` of the size with the default
/// tolerance, and the parameters' own rounding (1e-16). Where the magnitude is a normal number
/// the residual is rounded to `eps`, and the final correction takes the position there
/// ([`SCALE_TOL`], as `units.rs` finds at sizes from 1e-9 to 1e9).
fn rod_tolerance(k: f64) -> f64 {
    let (r, l, e) = ROD;
    let most = (2.0 * r + l).powi(2) + (r + e).powi(2) + l * l;
    let least_slope = 2.0 * (l * l - (r + e).powi(2)).sqrt();
    let normal = most * k * k * f64::EPSILON >= f64::MIN_POSITIVE;
    if normal { SCALE_TOL } else { 2.0 * NewtonConfig::default().residual_tol * most / least_slope + SCALE_TOL }
}

/// The positions of a mechanism as declared and of its Newton twin at input `phi` from their
/// declared guesses, each by its state (`kinematics_flat`) and by its positions alone
/// (`position_flat`), named for the assertions' messages.
fn declared_and_newton<M: Mechanism<N, 1, NO>, T: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    plain: &M,
    newton: &T,
    phi: f64,
    cfg: &NewtonConfig,
) -> [(&'static str, Result<[f64; N], kinloop::Error>); 4] {
    let (g_plain, g_newton) = (plain.guess_flat(&[phi]), newton.guess_flat(&[phi]));
    [
        ("as declared", plain.kinematics_flat(&[phi], &g_plain, cfg).map(|s| s.q)),
        ("Newton", newton.kinematics_flat(&[phi], &g_newton, cfg).map(|s| s.q)),
        ("as declared, positions", plain.position_flat(&[phi], &g_plain, cfg).map(|(q, _)| q)),
        ("Newton, positions", newton.position_flat(&[phi], &g_newton, cfg).map(|(q, _)| q)),
    ]
}

/// Whether `err` is the refusal of an equation whose terms are too large for `f64`, naming the
/// equation `name`, with a message that says so and what to do.
fn is_overflow(err: &kinloop::Error, name: &str) -> bool {
    let text = err.to_string();
    let said = [format!("`{name}`").as_str(), "too large", "f64", "larger unit", "smaller numbers"]
        .iter()
        .all(|part| text.contains(part));
    assert!(said, "{text}");
    matches!(err, kinloop::Error::Overflow { what: kinloop::Computed::Equation, name: n, .. } if n == name)
}

/// A Newton equation whose terms leave the range of `f64` (squared lengths of a mechanism of
/// size `k`) is solved to its tolerance or refused, never answered wrong. The slider-crank by its
/// rod's length squared, at 12 inputs of a turn, both as declared and `#[kinloop(newton)]`, its
/// state and its positions alone: at sizes 1, `1e±150` and `2e153` (normal magnitudes, the
/// largest `1.6e308`) and `1e-156` (a subnormal magnitude, about `2e-311`, still fine enough:
/// doubles `4.9e-324` apart are `2e-13` of it, below the residual tolerance) the closed form to
/// [`rod_tolerance`]; at `1e-160` (a magnitude of `3e-319`, resolved to `1.6e-5` of itself),
/// `1e-200` and `1e-300` (zero: every term underflowed) an [`kinloop::Error::Underflow`] naming
/// the equation; at `3.5e153` (a magnitude beyond `f64::MAX`, `1.8e308`, about `4.8e308`,
/// where at some inputs the terms themselves are not), `1e160`, `1e200` and `1e300` (terms
/// beyond `f64::MAX`) an [`kinloop::Error::Overflow`] naming the equation. At `1e-160` Newton
/// accepted positions `4e-5` of the size off, and at `1e-200` and below returned the guess
/// unchanged (a residual of exactly zero, judged against the Jacobian's row sum), with no
/// error; from `1e160` the equation was said to leave its domain (`inf - inf` is NaN), and at
/// `3.5e153` the loops not to close (a residual `1e138` relative to a row sum that is a
/// length).
#[test]
fn an_equation_of_squared_lengths_is_solved_to_its_tolerance_or_refused_at_every_scale() {
    use kinloop::Error;
    let (r, l, e) = ROD;
    let cfg = NewtonConfig::default();
    let solved = [1.0, 1e-150, 1e150, 2e153, 1e-156];
    let underflows = [1e-160, 1e-200, 1e-300];
    let overflows = [3.5e153, 1e160, 1e200, 1e300];
    for k in solved.into_iter().chain(underflows).chain(overflows) {
        let (plain, newton) =
            (RodSquared { r: r * k, l: l * k, e: e * k }, RodSquaredNewton { r: r * k, l: l * k, e: e * k });
        let tol = rod_tolerance(k);
        let mut worst = 0.0f64;
        for i in 0..12 {
            let phi = 0.3 + i as f64 * 0.5;
            for (path, got) in declared_and_newton(&plain, &newton, phi, &cfg) {
                match got {
                    Ok(q) => {
                        let off = (q[0] / k - rod_closed_form(phi)).abs() / (r + l + e);
                        assert!(off <= tol, "{path} at size {k:e}, phi {phi}: x / k = {}, {off:e} off", q[0] / k);
                        assert!(solved.contains(&k), "{path} at size {k:e}, phi {phi}: solved, {off:e} off");
                        worst = worst.max(off);
                    }
                    Err(err @ Error::Underflow { .. }) if underflows.contains(&k) => {
                        let text = err.to_string();
                        assert!(text.contains("`rod`") && text.contains("too small"), "{text}");
                    }
                    Err(err) if overflows.contains(&k) && is_overflow(&err, "rod") => {}
                    Err(err) => panic!("{path} at size {k:e}, phi {phi}: {err}"),
                }
            }
        }
        if solved.contains(&k) {
            eprintln!("rod length squared at size {k:e}: largest difference from the closed form {worst:.1e}");
        }
    }
}

with_newton_twin! {
    /// A four-bar's coupler pin `(bx, by)` from the squared lengths of its coupler and rocker
    /// alone (crank `a` at angle `phi`, coupler `b`, rocker `c`, frame `d`): a Newton block of
    /// two lengths whose equations' terms are squared lengths, about `57 k^2` at size `k`.
    pub struct PinSquared, PinSquaredNewton {
        params a, b, c, d;
        input phi;
        unknowns bx = d, by = b;
        eq coupler: (bx - a * cos(phi)) ^ 2 + (by - a * sin(phi)) ^ 2 == b * b;
        eq rocker: (bx - d) ^ 2 + by ^ 2 == c * c;
    }
}

/// The coupler pin at size 1 (links 1, 3.5, 3, 4: a crank-rocker whose pin never folds onto a
/// link, the coupler and rocker's angle between 33 and 114 degrees), the circles' intersection
/// on the left of the crank pin to the rocker's pivot (where the guess lies).
fn pin_closed_form(phi: f64) -> (f64, f64) {
    let (a, b, c, d) = (1.0, 3.5, 3.0, 4.0);
    let (ax, ay) = (a * phi.cos(), a * phi.sin());
    let (ux, uy) = (d - ax, -ay);
    let dist = ux.hypot(uy);
    // Along the crank pin to the pivot, and across it to the left.
    let along = (dist * dist + b * b - c * c) / (2.0 * dist);
    let across = (b * b - along * along).sqrt();
    (ax + (along * ux - across * uy) / dist, ay + (along * uy + across * ux) / dist)
}

/// The four-bar whose coupler pin is declared by squared lengths is solved to the closed form at
/// sizes 1 and `1e150`, and refused with an [`kinloop::Error::Overflow`] naming its first
/// equation beyond the sizes where their terms fit in `f64` (`1e160`, `1e200`, `1e300`), its
/// state and its positions, as declared and `#[kinloop(newton)]`, at 12 inputs of a turn. It
/// was said to leave its domain there.
#[test]
fn a_four_bar_of_squared_lengths_is_solved_or_refused_as_too_large() {
    let cfg = NewtonConfig::default();
    for k in [1.0, 1e150, 1e160, 1e200, 1e300] {
        let (a, b, c, d) = (k, 3.5 * k, 3.0 * k, 4.0 * k);
        let (plain, newton) = (PinSquared { a, b, c, d }, PinSquaredNewton { a, b, c, d });
        for i in 0..12 {
            let phi = 0.3 + i as f64 * 0.5;
            for (path, got) in declared_and_newton(&plain, &newton, phi, &cfg) {
                match got {
                    Ok(q) => {
                        // In fractions of the size. The pin's transmission angle keeps the
                        // block well conditioned: its position is its equations' rounding (a
                        // few eps of the magnitude) over a slope of the size, as the slider's
                        // ([`SCALE_TOL`]).
                        let (x, y) = pin_closed_form(phi);
                        let off = (q[0] / k - x).abs().max((q[1] / k - y).abs());
                        assert!(k <= 1e150 && off <= SCALE_TOL, "{path} at size {k:e}, phi {phi}: {off:e} off");
                    }
                    Err(err) if k > 1e150 && is_overflow(&err, "coupler") => {}
                    Err(err) => panic!("{path} at size {k:e}, phi {phi}: {err}"),
                }
            }
        }
    }
}

/// A sweep of the rod-length slider-crank at `1e-300` and `1e-160` stops at its first sample
/// with [`kinloop::Error::Underflow`], at `1e160` and `1e300` with [`kinloop::Error::Overflow`],
/// locating no event: at `1e-300` it returned the guess at every sample (or, where the step
/// failed, took the noise of the residual for a singular crossing); at `1e160` and `1e300` it
/// said the equation left its domain. At size 1 the same sweep follows the closed form.
#[test]
fn a_sweep_of_an_equation_out_of_the_range_of_f64_is_refused() {
    let (r, l, e) = ROD;
    for k in [1.0, 1e-160, 1e-300, 1e160, 1e300] {
        let m = RodSquaredNewton { r: r * k, l: l * k, e: e * k };
        let mut s = Sweep::<RodSquaredNewton, Kin<1, 1, 0>, 1, 1, 0>::new(
            &m,
            [0.3],
            [0.3 + std::f64::consts::TAU],
            73,
            m.guess_flat(&[0.3]),
        )
        .unwrap();
        let states: Vec<_> = s.by_ref().collect();
        assert!(s.events().is_empty(), "size {k:e}: events {:?}", s.events());
        if k == 1.0 {
            assert_eq!(states.len(), 73);
            for st in states {
                let st = st.unwrap();
                let off = (st.q[0] - rod_closed_form(st.x[0])).abs() / (r + l + e);
                assert!(off <= SCALE_TOL, "phi {}: {off:e} off", st.x[0]);
            }
        } else {
            let refused = match states.as_slice() {
                [Err(kinloop::Error::Underflow { .. })] => k < 1.0,
                [Err(err)] => k > 1.0 && is_overflow(err, "rod"),
                _ => false,
            };
            assert!(refused, "size {k:e}: {:?}", states.iter().take(3).collect::<Vec<_>>());
        }
    }
}

/// A mechanism whose lengths are subnormal (below `2.2e-308`, with fewer bits than a double's)
/// is refused as too small for `f64`, naming an equation and telling the user to take a smaller
/// unit; nothing else. Its equations' magnitudes and their derivatives are both below
/// `2^-1024`, where their reciprocals overflow, so no residual can be equilibrated: a four-bar
/// of lengths about `1e-310` was said not to assemble (a residual of `0.117`, its positions and
/// its state), and the rhombic drive's velocity analogs not to be finite (an expression outside
/// its domain), where both solve in a smaller unit. Down to about `3e-309`, where the
/// magnitudes are normal again, they solve with size 1's angles.
#[test]
fn a_mechanism_of_subnormal_lengths_is_refused_as_too_small() {
    let cfg = NewtonConfig::default();
    let too_small = |r: Result<(), kinloop::Error>, what: &str| match r {
        Err(e @ kinloop::Error::Underflow { magnitude, least, .. }) => {
            let text = e.to_string();
            assert!(magnitude < least && text.contains("give the lengths in a smaller unit"), "{what}: {text}");
        }
        other => panic!("{what}: {other:?}"),
    };
    for x in [0.3, 2.0, -1.7] {
        for k in [1e-310, 5e-310, 1e-315] {
            let m = four_bar(k);
            let g = m.guess_flat(&[x]);
            too_small(m.position_flat(&[x], &g, &cfg).map(drop), &format!("four-bar positions at {k:e}, {x}"));
            too_small(m.kinematics_flat(&[x], &g, &cfg).map(drop), &format!("four-bar state at {k:e}, {x}"));
            let m = four_bar_newton(k);
            too_small(m.kinematics_flat(&[x], &g, &cfg).map(drop), &format!("Newton four-bar at {k:e}, {x}"));
            let m: RhombicDrive = rhombic_at(k);
            let g = m.guess_flat(&[x]);
            too_small(m.kinematics_flat(&[x], &g, &cfg).map(drop), &format!("rhombic drive at {k:e}, {x}"));
            too_small(rhombic_dense(k).kinematics_flat(&[x], &g, &cfg).map(drop), &format!("dense at {k:e}, {x}"));
        }
        let one = four_bar(1.0).kinematics_flat(&[x], &four_bar(1.0).guess_flat(&[x]), &cfg).unwrap();
        for k in [3e-309, 1e-308] {
            let m = four_bar(k);
            let q = m.kinematics_flat(&[x], &m.guess_flat(&[x]), &cfg).unwrap().q;
            // The lengths keep 50 and 52 of their bits: the angles within a few ulps of theirs.
            assert!((0..2).all(|u| (q[u] - one.q[u]).abs() <= 1e-13), "{k:e}, {x}: {q:?} against {:?}", one.q);
        }
    }
}

/// A four-bar whose coupler and rocker together fall short of the frame pivot at every input
/// (crank 1, frame 3: the crank's end is 2 to 4 from the rocker's pivot, the coupler and rocker
/// reach 1.51) cannot be assembled at any size. Its dyad's coefficients are products of two
/// lengths: with one link short (0.01) the first two are small and the third, `(c² - b² -
/// |e|²) / 2`, is about `-3 k²`, whose square overflows near `k = 1e77` though theirs do not.
/// There it was taken for a limit position (both sides of the tolerance test infinite) and a
/// position returned; in closed form it is no assembly at every size, as Newton's twin says.
#[test]
fn a_four_bar_whose_links_cannot_reach_fails_where_a_coefficient_squared_overflows() {
    use kinloop::Error;
    let cfg = NewtonConfig::default();
    for (b, c) in [(0.01, 1.5), (1.5, 0.01)] {
        for k in [1.0, 1e-77, 1e77, 1.2e77, 1e100] {
            let m = FourBar { a: k, b: b * k, c: c * k, d: 3.0 * k };
            let twin = FourBarNewton { a: k, b: b * k, c: c * k, d: 3.0 * k };
            for x in [[0.3], [2.0]] {
                let closed = m.position_flat(&x, &m.guess_flat(&x), &cfg).map(|(q, _)| q);
                let newton = twin.position_flat(&x, &twin.guess_flat(&x), &cfg).map(|(q, _)| q);
                for (solver, got) in [("closed form", closed), ("Newton", newton)] {
                    let e = got.expect_err(&format!("{solver}, b {b}, c {c}, size {k:e}, phi {x:?}: assembled"));
                    assert!(matches!(e, Error::NoAssembly { .. }), "{solver}, size {k:e}: {e:?}");
                }
            }
        }
    }
}

/// A four-bar near its change point (frame `1 + 1e-8` of the crank, coupler and rocker twice
/// it) at a crank angle of 0, regular there (its analogs' pivot ratio about `5e-9`, above
/// `singular_tol`), has its kinematics at every size: between about `1e154` and `1e157` the
/// product of its analog block's column magnitudes overflowed while the determinant did not,
/// and the block was reported singular with pivot ratio 0 at those sizes alone. The reference
/// is the state at size 1, scaled: angles and angle analogs the same.
#[test]
fn a_four_bar_near_its_change_point_has_its_kinematics_at_every_size() {
    let cfg = NewtonConfig::default();
    let at = |k: f64| {
        let m = FourBar { a: k, b: 2.0 * k, c: 2.0 * k, d: (1.0 + 1e-8) * k };
        m.kinematics_flat(&[0.0], &m.guess_flat(&[0.0]), &cfg)
    };
    let unit = at(1.0).expect("regular at size 1");
    for k in [1e150, 1e154, 2e154, 1e155, 1e156, 1e157, 1e158] {
        let got = at(k).unwrap_or_else(|e| panic!("size {k:e}: {e}"));
        for u in 0..2 {
            // The position's conditioning (pivot ratio 5e-9) amplifies the roundings of the
            // scaled lengths: 1e-6 relative leaves room for that, far below a branch's distance.
            let (q0, q) = (unit.q[u], got.q[u]);
            assert!((q - q0).abs() <= 1e-6 * q0.abs().max(1.0), "size {k:e}, q{u}: {q} against {q0}");
            let (v0, v) = (unit.dq[u][0], got.dq[u][0]);
            assert!((v - v0).abs() <= 1e-6 * v0.abs().max(1.0), "size {k:e}, dq{u}: {v} against {v0}");
        }
    }
}
