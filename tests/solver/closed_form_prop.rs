//! Property tests of the closed-form blocks over thousands of random four-bars (Grashof or
//! not), offset slider-cranks and two-dyad six-bars, in both assembly modes of every dyad, on
//! coarse sweeps (8 to 36 samples a turn): the closed-form path never jumps branch (the sign of
//! each dyad's cross product, i.e. of its Jacobian determinant, stays that of the start), its
//! positions equal an independent construction (circle intersection, `asin`) written here, its
//! limit positions equal the law-of-cosines closed form within 1e-9, and its samples and events
//! are those of the Newton twin (`#[kinloop(newton)]`).

use kinloop::{Error, Event, EventKind, SweepConfig};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

use crate::support::{circle_point, four_bar_angles, newton_to_rounding, wrap};

with_newton_twin! {
    pub struct FourBar, FourBarNewton {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

with_newton_twin! {
    pub struct SliderCrank, SliderCrankNewton {
        params r, l, e;
        input phi;
        unknowns psi = 0, x = 1;
        loop oabo: r @ phi == (x, e) + l @ psi;
    }
}

with_newton_twin! {
    pub struct SixBar, SixBarNewton {
        params a, b, c, d, c2, delta, e, f, g, h;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, eps = 0.3, eta = 1.8;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop second: (d, 0) + c2 @ (gamma + delta) + e @ eps == (f, g) + h @ eta;
    }
}

/// The Newton twin iterates to rounding level, so both paths may be compared tightly.
fn newton_sweep() -> SweepConfig {
    SweepConfig::default().with_newton(newton_to_rounding())
}

/// A sweep's samples (input, positions) until it stops, its events, and whether it stopped.
type Run = (Vec<(f64, Vec<f64>)>, Vec<Event>, bool);

/// Runs a sweep to its end and collects what it produced.
macro_rules! run {
    ($m:expr, $from:expr, $to:expr, $n:expr, $g:expr, $cfg:expr) => {{
        let mut sweep = $m.sweep($from, $to, $n, &($g).into()).unwrap().with_config($cfg);
        let mut samples = Vec::new();
        let mut stopped = false;
        for s in &mut sweep {
            match s {
                Ok(s) => samples.push((s.flat.x[0], s.flat.q.to_vec())),
                Err(Error::SweepStopped { .. }) => {
                    stopped = true;
                    break;
                }
                Err(e) => panic!("sweep failed: {e}"),
            }
        }
        (samples, sweep.events().to_vec(), stopped) as Run
    }};
}

/// The closed-form path and the Newton path produced the same samples and the same events.
fn same_runs(a: &Run, b: &Run) -> Result<(), TestCaseError> {
    prop_assert_eq!(a.0.len(), b.0.len(), "samples");
    prop_assert_eq!(a.2, b.2, "stopped");
    for ((xa, qa), (xb, qb)) in a.0.iter().zip(&b.0) {
        prop_assert_eq!(xa, xb);
        for (u, v) in qa.iter().zip(qb) {
            prop_assert!((u - v).abs() <= 1e-9 * v.abs().max(1.0), "at {}: {:?} vs Newton {:?}", xa, qa, qb);
        }
    }
    prop_assert_eq!(a.1.len(), b.1.len(), "events");
    for (ea, eb) in a.1.iter().zip(&b.1) {
        prop_assert_eq!(ea.kind, eb.kind);
        prop_assert!((ea.x[0] - eb.x[0]).abs() <= 1e-9, "event at {} vs Newton {}", ea.x[0], eb.x[0]);
    }
    Ok(())
}

/// The first crank angle after `from` where coupler and rocker are collinear (`|BD| = b ± c`).
fn next_limit(a: f64, b: f64, c: f64, d: f64, from: f64) -> Option<f64> {
    let mut best: Option<f64> = None;
    for r in [b + c, (b - c).abs()] {
        let cos = (a * a + d * d - r * r) / (2.0 * a * d);
        if cos.abs() < 1.0 {
            for root in [cos.acos(), -cos.acos()] {
                let ahead = from + (root - from).rem_euclid(TAU);
                best = Some(best.map_or(ahead, |x: f64| x.min(ahead)));
            }
        }
    }
    best
}

proptest! {
    #![proptest_config(ProptestConfig { failure_persistence: None, max_global_rejects: 50_000, ..ProptestConfig::with_cases(1500) })]

    #[test]
    fn four_bars(
        a in 0.3f64..4.0, b in 0.3f64..4.0, c in 0.3f64..4.0, d in 0.3f64..4.0,
        phi0 in 0.0f64..TAU, n in 8usize..=36, left in any::<bool>(),
    ) {
        let side = if left { 1.0 } else { -1.0 };
        let start = four_bar_angles(a, b, c, d, phi0, side);
        prop_assume!(start.is_some());
        let [beta0, gamma0] = start.unwrap_or_default();
        // Away from a limit position at the start: the mode is well defined there.
        prop_assume!((gamma0 - beta0).sin().abs() > 1e-3);
        let (m, w) = (FourBar { a, b, c, d }, FourBarNewton { a, b, c, d });
        let g = [beta0, gamma0];
        let closed = run!(m, phi0, phi0 + TAU, n + 1, g, SweepConfig::default());
        let newton = run!(w, phi0, phi0 + TAU, n + 1, g, newton_sweep());
        same_runs(&closed, &newton)?;
        let mode = (gamma0 - beta0).sin().signum();
        for (phi, q) in &closed.0 {
            // No branch jump: the determinant's sign (b c sin(gamma - beta)) is the start's.
            prop_assert_eq!((q[1] - q[0]).sin().signum(), mode, "branch jump at {}", phi);
            let [beta, gamma] = four_bar_angles(a, b, c, d, *phi, side).unwrap_or([f64::NAN; 2]);
            prop_assert!(wrap(q[0] - beta).abs() < 1e-9 && wrap(q[1] - gamma).abs() < 1e-9,
                "at {}: {:?} vs construction ({}, {})", phi, q, beta, gamma);
        }
        match next_limit(a, b, c, d, phi0) {
            Some(lim) if lim < phi0 + TAU - 1e-6 && lim > phi0 + 1e-6 => {
                let ev = closed.1.first();
                prop_assert!(ev.is_some_and(|e| e.kind == EventKind::LimitPosition), "{:?}", closed.1);
                let x = ev.map_or(f64::NAN, |e| e.x[0]);
                prop_assert!((x - lim).abs() < 1e-9, "limit at {} vs law of cosines {}", x, lim);
            }
            Some(_) => {}
            None => prop_assert!(!closed.2 && closed.0.len() == n + 1, "{:?}", closed.1),
        }
    }

    #[test]
    fn offset_slider_cranks(
        r in 0.3f64..3.0, l in 0.3f64..4.0, e in -1.5f64..1.5, phi0 in 0.0f64..TAU, n in 8usize..=36,
        right in any::<bool>(),
    ) {
        let s0 = (r * phi0.sin() - e) / l;
        prop_assume!(s0.abs() < 0.999);
        // Rod to the right of the crank pin (cos psi < 0, slider beyond) or to the left.
        let psi_at = |phi: f64| {
            let s = ((r * phi.sin() - e) / l).asin();
            if right { PI - s } else { s }
        };
        let psi0 = psi_at(phi0);
        let g = [psi0, r * phi0.cos() - l * psi0.cos()];
        let (m, w) = (SliderCrank { r, l, e }, SliderCrankNewton { r, l, e });
        let closed = run!(m, phi0, phi0 + TAU, n + 1, g, SweepConfig::default());
        let newton = run!(w, phi0, phi0 + TAU, n + 1, g, newton_sweep());
        same_runs(&closed, &newton)?;
        for (phi, q) in &closed.0 {
            prop_assert_eq!(q[0].cos().signum(), psi0.cos().signum(), "branch jump at {}", phi);
            let psi = psi_at(*phi);
            let x = r * phi.cos() - l * psi.cos();
            prop_assert!(wrap(q[0] - psi).abs() < 1e-9 && (q[1] - x).abs() < 1e-9 * l.max(r),
                "at {}: {:?} vs ({}, {})", phi, q, psi, x);
        }
        // Limit positions: |r sin(phi) - e| = l, the first one ahead of phi0.
        let mut lim: Option<f64> = None;
        for k in [1.0f64, -1.0] {
            let s = (e + k * l) / r;
            if s.abs() < 1.0 {
                for root in [s.asin(), PI - s.asin()] {
                    let ahead = phi0 + (root - phi0).rem_euclid(TAU);
                    lim = Some(lim.map_or(ahead, |x: f64| x.min(ahead)));
                }
            }
        }
        if let Some(lim) = lim.filter(|x| *x < phi0 + TAU - 1e-6) {
            let x = closed.1.first().map_or(f64::NAN, |e| e.x[0]);
            prop_assert!((x - lim).abs() < 1e-9, "limit at {} vs closed form {}", x, lim);
        }
    }

    #[test]
    fn two_dyad_six_bars(
        a in 0.5f64..1.2, b in 2.5f64..3.5, c in 2.0f64..3.0, d in 2.8f64..3.6, c2 in 0.5f64..1.5,
        delta in -1.0f64..1.0, e in 2.0f64..3.5, f in 3.5f64..5.0, g in 0.0f64..1.5, h in 1.5f64..3.0,
        n in 8usize..=36, left in any::<bool>(), up in any::<bool>(),
    ) {
        // The first dyad by circle intersection; the second's start from the same construction.
        let side = if left { 1.0 } else { -1.0 };
        let start = four_bar_angles(a, b, c, d, 0.0, side);
        prop_assume!(start.is_some());
        let [beta0, gamma0] = start.unwrap_or_default();
        let (px, py) = (d + c2 * (gamma0 + delta).cos(), c2 * (gamma0 + delta).sin());
        let dist = (f - px).hypot(g - py);
        prop_assume!(dist < e + h && dist > (e - h).abs());
        let (ex, ey) = circle_point(px, py, e, f, g, h, if up { 1.0 } else { -1.0 });
        let (eps0, eta0) = ((ey - py).atan2(ex - px), (ey - g).atan2(ex - f));
        prop_assume!((gamma0 - beta0).sin().abs() > 1e-3 && (eta0 - eps0).sin().abs() > 1e-3);
        let m = SixBar { a, b, c, d, c2, delta, e, f, g, h };
        let w = SixBarNewton { a, b, c, d, c2, delta, e, f, g, h };
        let guess = [beta0, gamma0, eps0, eta0];
        let closed = run!(m, 0.0, TAU, n + 1, guess, SweepConfig::default());
        let newton = run!(w, 0.0, TAU, n + 1, guess, newton_sweep());
        same_runs(&closed, &newton)?;
        let modes = ((gamma0 - beta0).sin().signum(), (eta0 - eps0).sin().signum());
        for (phi, q) in &closed.0 {
            prop_assert_eq!(((q[1] - q[0]).sin().signum(), (q[3] - q[2]).sin().signum()), modes, "at {}", phi);
        }
    }
}
