//! The closed-form blocks whose only other check is their Newton twin (`closed_form.rs`: the two
//! share the generated loop equations, so a misread declaration passes there) against
//! constructions written here from the declarations by hand: positions in both assembly modes
//! over a turn, and the velocity and acceleration analogs differentiated by hand.
//!
//! Positions within `tol::SOLVE` (the closed form against a closed form written in the test);
//! analogs within `ANALOGS`, relative.

use crate::closed_form::{EllipticRocker, HalfUnitRocker, OffsetDyad, SlottedRocker, TiltedSlider};
use crate::support::{angle_apart, four_bar_jets, tol};
use kinloop::{Mechanism, NewtonConfig};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The analogs against the hand-differentiated ones, relative to their size (absolute below 1):
/// both are a handful of operations on positions exact to rounding, and nothing here comes near
/// a fold (the dyad's links stay 46 degrees or more from a line, the rod 60 degrees from the
/// slide's normal, the crank pin 0.8 from the rocker's pivot): a few ulps, with a margin of ten.
const ANALOGS: f64 = 1e-13;

/// Each unknown's position, velocity and acceleration analog, in declaration order.
type Jets = [[f64; 3]; 2];

/// `m` over a turn of its input, in each of two assembly modes of `jets` (`jets(phi, mode)`;
/// `angles[u]` says which unknowns are angles): every point solve (from the previous position,
/// the first from the reference's 0.05 off) against the reference.
fn check<M: Mechanism<2, 1, NO>, const NO: usize>(m: &M, jets: impl Fn(f64, usize) -> Jets, angles: [bool; 2]) {
    let cfg = NewtonConfig::default();
    for mode in 0..2 {
        let mut guess = jets(0.0, mode).map(|j| j[0] + 0.05);
        for i in 0..=72 {
            let phi = TAU * i as f64 / 72.0;
            let at = format!("{} mode {mode} at {phi}", M::NAME);
            let k = m.kinematics_flat(&[phi], &guess, &cfg).unwrap_or_else(|e| panic!("{at}: {e}"));
            guess = k.q;
            let want = jets(phi, mode);
            for u in 0..2 {
                let name = M::UNKNOWNS[u];
                let [q, dq, d2q] = want[u];
                let off = if angles[u] { angle_apart(k.q[u], q) } else { (k.q[u] - q).abs() };
                assert!(off <= tol::SOLVE, "{at}: {name} {} against {q} ({off:e})", k.q[u]);
                assert_close!(k.dq[u][0], dq, rel = ANALOGS, "{at}: d{name}");
                assert_close!(k.d2q[u][0][0], d2q, rel = ANALOGS, "{at}: d2{name}");
            }
        }
    }
}

/// `(0, h) + r @ phi == s * (cos(theta), k sin(theta))`: with `Q = (P.x, P.y / k)` for the crank
/// pin P, `s = |Q|` (mode 0; mode 1 `-|Q|`, the angle half a turn on) and `theta` the direction of
/// `Q`, differentiated by hand: `theta' = Q x Q' / |Q|^2`, `theta'' = Q x Q'' / |Q|^2 - 2 theta'
/// (Q . Q') / |Q|^2`, `|Q|' = Q . Q' / |Q|`, `|Q|'' = (Q' . Q' + Q . Q'' - |Q|'^2) / |Q|`. (Exact
/// derivatives: near `phi = 3 pi / 2`, where the pin passes closest to the pivot, central
/// differences of the positions lose 1e-9 to truncation.)
fn rocker(r: f64, h: f64, k: f64, phi: f64, mode: usize) -> Jets {
    let (sin, cos) = phi.sin_cos();
    let q = [r * cos, (h + r * sin) / k];
    let dq = [-r * sin, r * cos / k];
    let d2q = [-r * cos, -r * sin / k];
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
    let n2 = dot(q, q);
    let theta1 = cross(q, dq) / n2;
    let theta2 = cross(q, d2q) / n2 - 2.0 * theta1 * dot(q, dq) / n2;
    let len = n2.sqrt();
    let len1 = dot(q, dq) / len;
    let len2 = (dot(dq, dq) + dot(q, d2q) - len1 * len1) / len;
    let sign = if mode == 0 { 1.0 } else { -1.0 };
    let theta = q[1].atan2(q[0]) + if mode == 0 { 0.0 } else { PI };
    [[sign * len, sign * len1, sign * len2], [theta, theta1, theta2]]
}

#[test]
fn slotted_rockers_match_the_crank_pin_in_polar_form() {
    let m = SlottedRocker::default();
    check(&m, |phi, mode| rocker(m.r, m.h, 1.0, phi, mode), [false, true]);
    // `(2 s) @ theta`: the length is half the pin's distance.
    let m = HalfUnitRocker::default();
    let half = |phi, mode| {
        let [s, theta] = rocker(m.r, m.h, 1.0, phi, mode);
        [s.map(|v| 0.5 * v), theta]
    };
    check(&m, half, [false, true]);
    // `s * (cos(theta), 2 sin(theta))`: P.y / 2 in place of P.y.
    let m = EllipticRocker::default();
    check(&m, |phi, mode| rocker(m.r, m.h, 2.0, phi, mode), [false, true]);
}

/// `r @ phi == x @ tilt + e @ (tilt + pi / 2) + l @ psi`, turned by `-tilt` (`a = phi - tilt`,
/// `w = psi - tilt`): across the slide `l sin(w) = r sin(a) - e`, the rod on the crank's side of
/// the slide's normal (mode 0) or across it (mode 1); along it `x = r cos(a) - l cos(w)`.
/// Differentiated by hand: `l cos(w) w' = r cos(a)`, `l cos(w) w'' = l sin(w) w'^2 - r sin(a)`,
/// `x' = -r sin(a) + l sin(w) w'`, `x'' = -r cos(a) + l cos(w) w'^2 + l sin(w) w''`.
#[test]
fn a_tilted_slider_crank_matches_its_projections() {
    let m = TiltedSlider::default();
    let (r, l) = (m.r, m.l);
    let jets = |phi: f64, mode: usize| {
        let (sa, ca) = (phi - m.tilt).sin_cos();
        let across = ((r * sa - m.e) / l).asin();
        let w = if mode == 0 { across } else { PI - across };
        let (sw, cw) = w.sin_cos();
        let w1 = r * ca / (l * cw);
        let w2 = (l * sw * w1 * w1 - r * sa) / (l * cw);
        let x = [r * ca - l * cw, -r * sa + l * sw * w1, -r * ca + l * cw * w1 * w1 + l * sw * w2];
        [[m.tilt + w, w1, w2], x]
    };
    check(&m, jets, [true, false]);
}

/// `a @ phi + b @ (u + alpha) == (d, 0) + c * (sin(v + delta), cos(v + delta))`: a four-bar with
/// coupler angle `beta = u + alpha` and rocker angle `gamma = pi / 2 - (v + delta)`, C from the
/// circles (B, b) and (D, c) on either side of B -> D, differentiated by hand
/// (`support::four_bar_jets`); `u` moves as `beta`, `v` as `-gamma`.
#[test]
fn an_offset_and_reflected_dyad_matches_the_circle_construction() {
    let m = OffsetDyad::default();
    let jets = |phi: f64, mode: usize| {
        let side = if mode == 0 { 1.0 } else { -1.0 };
        let [[beta, beta1, beta2], [gamma, gamma1, gamma2]] =
            four_bar_jets(m.a, m.b, m.c, m.d, phi, side).expect("a crank-rocker assembles");
        [[beta - m.alpha, beta1, beta2], [FRAC_PI_2 - m.delta - gamma, -gamma1, -gamma2]]
    };
    check(&m, jets, [true, true]);
}
