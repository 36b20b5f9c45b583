//! Samples landing beside a change point: a Grashof-equal four-bar (`a + d = b + c`, here
//! `1 + 3.5 = 2 + 2.5`) has one at `phi = pi` (mod `2 pi`), where all its links lie in line and
//! its two assembly modes meet. Swept over two turns with [`AtSingular::Continue`], from starts
//! `1e-9` to `1e-5` rad on either side of whole turns (so that a sample falls that far before or
//! after each crossing) and at several sample counts, every sample is produced on the smooth
//! continuation through both crossings, each recorded once.
//!
//! The reference is the circle intersection derived here, independently of the library, in a
//! form that stays accurate at the change point (the law of cosines loses half the digits
//! there): with `B = a (cos phi, sin phi)`, `D = (d, 0)` and `L = |BD|`, the coupler points at
//! `beta = psi + s theta_B` and the rocker at `gamma = psi + pi - s theta_D`, `psi` the
//! direction of `B -> D`, `s = +-1` the assembly mode (`C` left or right of `B -> D`), and the
//! triangle's angles at `B` and `D` from the half-angle formulas
//! `tan(theta_B / 2) = sqrt((h - b)(h - L) / (h (h - c)))` (and `b`, `c` swapped for `theta_D`),
//! `h = (b + c + L) / 2`. The small factor `h - L = (b + c - L) / 2` is computed as
//! `((b + c)^2 - L^2) / (2 (b + c + L))`, where `(b + c)^2 - L^2 = 4 a d cos^2(phi / 2)` for
//! `a + d = b + c` (from `L^2 = (a + d)^2 - 2 a d (1 + cos phi)`), exact to rounding. Both
//! `theta`s vanish in proportion to `phi - pi`, so the smooth continuation through the change
//! point is the other assembly mode: `s` turns over at every crossing passed.

use kinloop::analysis::Sampled;
use kinloop::{AtSingular, EventKind, Kin, Sweep, SweepConfig};
use kinloop_fixtures::FourBar;
use std::f64::consts::{PI, TAU};

use crate::support::{four_bar_angles, tol, wrap};

/// The sizes: 1, `1e-3` and `2^-20` (about `1e-6`). At each the lengths are exactly
/// Grashof-equal in `f64` (checked: `a + d == b + c` with no rounding); `2.5e-6` and `1e-6`
/// scaled are not (their doubles' sums differ by `2e-22`, a gap of `5e-17` of the size), a
/// mechanism that is not the one this test's reference describes.
const SCALES: [f64; 3] = [1.0, 1e-3, 1.0 / 1_048_576.0];

/// The sample counts over the two turns: the samples `4 pi / (n - 1)` apart, each count with
/// samples on both change points (`n - 1` a multiple of four), at those offsets from them.
const COUNTS: [usize; 4] = [5, 9, 73, 145];

/// The Grashof-equal four-bar at size `k`.
fn four_bar(k: f64) -> FourBar {
    let m = FourBar { a: k, b: 2.0 * k, c: 2.5 * k, d: 3.5 * k };
    // Exactly Grashof-equal: the two sums, each as its rounded value and the exact remainder.
    assert_eq!(two_sum(m.b, m.c), two_sum(m.a, m.d), "size {k}: not exactly Grashof-equal");
    m
}

/// `x + y` as its rounded value and the rounding's error, exactly (Knuth's two-sum): two sums
/// are equal where both parts are.
fn two_sum(x: f64, y: f64) -> (f64, f64) {
    let s = x + y;
    let v = s - x;
    (s, (x - (s - v)) + (y - v))
}

/// `[beta, gamma]` in assembly mode `s` at `phi` (see the module's derivation).
fn reference(m: &FourBar, phi: f64, s: f64) -> [f64; 2] {
    let (a, b, c, d) = (m.a, m.b, m.c, m.d);
    let (bx, by) = (a * phi.cos(), a * phi.sin());
    let (ux, uy) = (d - bx, -by);
    let l = ux.hypot(uy);
    let psi = uy.atan2(ux);
    let half = (0.5 * phi).cos();
    let gap = 4.0 * a * d * half * half / (2.0 * (b + c + l));
    let h = 0.5 * (b + c + l);
    let theta = |near: f64, far: f64| {
        let (h_near, h_far) = (0.5 * (far + l - near), 0.5 * (near + l - far));
        2.0 * (h_near * gap / (h * h_far)).sqrt().atan()
    };
    [psi + s * theta(b, c), psi + PI - s * theta(c, b)]
}

/// The assembly mode the sweep is expected on at `phi`, having started in `s0` at `from`: turned
/// over at every change point (`pi + 2 pi n`) in `(from, phi)`.
fn mode_at(s0: f64, from: f64, phi: f64) -> f64 {
    let passed = |x: f64| ((x - PI) / TAU).floor();
    if (passed(phi) - passed(from)) as i64 % 2 == 0 { s0 } else { -s0 }
}

/// The largest distance, modulo turns, of the angles `q` from `r`.
fn apart(q: &[f64; 2], r: &[f64; 2]) -> f64 {
    wrap(q[0] - r[0]).abs().max(wrap(q[1] - r[1]).abs())
}

/// The reference agrees with the library-independent construction of the test support (the
/// circles' intersection by the law of cosines) away from the change point, where that is
/// accurate; the modes `+1` and `-1` are its sides `+1` and `-1`.
#[test]
fn the_reference_is_the_circle_intersection() {
    let m = four_bar(1.0);
    for i in 0..=60 {
        let phi = -PI + 0.1 + i as f64 * (TAU - 0.2) / 60.0;
        for s in [1.0, -1.0] {
            let want = four_bar_angles(m.a, m.b, m.c, m.d, phi, s).expect("assembles away from the change point");
            let got = reference(&m, phi, s);
            assert!(apart(&got, &want) <= tol::SOLVE, "phi {phi}, mode {s}: {got:?} against {want:?}");
        }
    }
}

/// Every sample of a sweep over two turns through the change points, from starts a hair to
/// either side of a whole turn: each at its own input and on the smooth continuation, or,
/// where it lies within the crossing's band (its state's pivot ratio below
/// `SweepConfig::singular_pivot`, where no solve pins the branch), the first well-conditioned
/// state past the crossing at that state's own input, as `AtSingular::Continue` documents. A
/// sample 2e-8 to 2e-7 rad past the change point stopped the sweep with `NearSingular` (the
/// state landed on there, within the band, could not be stepped from), and one 1e-7 before it
/// recorded the crossing twice (the state landed on lay before the crossing).
///
/// Tolerances: a position is pinned by Newton's residual tolerance to `tol::SOLVE` over its
/// pivot ratio (and is the nearer of the two modes, whose distance apart is what tells the
/// branch); a crossing is located within `tol::LOCATED`; a state standing for a sample in the
/// band lies past the crossing and within a hundredth of a radian of it (measured: at most
/// `2.2e-3`), short of the next sample.
#[test]
fn samples_beside_a_change_point_are_all_produced_on_the_branch() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let mut offsets = vec![0.0];
    for e in -9..=-5 {
        for mantissa in [1.0, 2.0, 5.0] {
            let off = mantissa * 10f64.powi(e);
            offsets.extend([off, -off]);
        }
    }
    let mut farthest = 0.0f64;
    for k in SCALES {
        let m = four_bar(k);
        for &off in &offsets {
            let (from, to) = (off, off + 2.0 * TAU);
            for s0 in [1.0, -1.0] {
                let guess = reference(&m, from, s0);
                for samples in COUNTS {
                    let what = format!("size {k:e}, start {off:e}, mode {s0}, {samples} samples");
                    let r = Sweep::<_, Kin<2, 1, 2>, 2, 1, 2>::new(&m, [from], [to], samples, guess)
                        .unwrap()
                        .with_config(cfg)
                        .run();
                    assert!(r.is_completed(), "{what}: {:?}", r.stop);
                    assert_eq!(r.states.len(), samples, "{what}");
                    let kinds: Vec<EventKind> = r.events.iter().map(|e| e.kind).collect();
                    assert_eq!(kinds, [EventKind::SingularCrossing; 2], "{what}: {:?}", r.events);
                    for (e, at) in r.events.iter().zip([PI, 3.0 * PI]) {
                        assert!((e.x[0] - at).abs() <= tol::LOCATED, "{what}: {e:?}");
                    }
                    let spacing = (to - from) / (samples - 1) as f64;
                    for (n, st) in r.states.iter().enumerate() {
                        let sample = from + spacing * n as f64;
                        let past = st.x[0] - sample;
                        if past.abs() > 4.0 * f64::EPSILON * sample.abs().max(1.0) {
                            // Standing for a sample in the band: past the crossing, well
                            // conditioned, short of the next sample.
                            let crossing = PI + TAU * ((st.x[0] - PI) / TAU).floor();
                            assert!(
                                st.x[0] > crossing && st.x[0] - crossing < 1e-2 && past > 0.0 && past < spacing,
                                "{what}, sample {n} at {sample}: {st:?}"
                            );
                            assert!(st.health.min_pivot >= 100.0 * cfg.singular_pivot, "{what}, sample {n}: {st:?}");
                            farthest = farthest.max(st.x[0] - crossing);
                        }
                        let pivot = st.health.min_pivot;
                        assert!(pivot >= cfg.singular_pivot, "{what}, sample {n}: {st:?}");
                        let s = mode_at(s0, from, st.x[0]);
                        let (want, other) = (reference(&m, st.x[0], s), reference(&m, st.x[0], -s));
                        let q = [st.q[0], st.q[1]];
                        assert!(
                            apart(&q, &want) <= tol::SOLVE / pivot && apart(&q, &want) < apart(&q, &other),
                            "{what}, sample {n} at {}: {q:?} against {want:?} (the other mode {other:?})",
                            st.x[0]
                        );
                    }
                    // The reported call: the same sweep, kept whole.
                    let run = Sampled::sweep_with(&m, from, to, samples, guess, cfg)
                        .unwrap_or_else(|e| panic!("{what}: {e}"));
                    assert_eq!(run.states().len(), samples, "{what}");
                }
            }
        }
    }
    eprintln!("a state standing for a sample in a crossing's band: at most {farthest:.1e} past it");
}

/// A crank-rocker nearer a change point than the residual tolerance can tell apart, as
/// `EventKind::SingularCrossing` documents: `a + d = 4` and `b + c = 4 + 2^-44` (exact in
/// `f64`, a Grashof margin of `2^-44 / 8`, about `7e-15`), so that at `phi = pi` its coupler and
/// rocker come within `sqrt(2 * 2^-44)`, about `3.4e-7` rad, of lying in line, below the
/// default `singular_pivot`. The sweep meets a `SingularCrossing` there rather than turning
/// fully, and with `AtSingular::Continue` ends the turn in the other assembly mode (the
/// reference's other side). A triple rocker as near (`b + c = 4 - 2^-44`) meets a crossing
/// rather than its limit position; one `2^10` times farther (`1.1e-5` rad from in line) turns
/// fully, with no event. In any unit: at sizes 1 and `2^-20`, exact scalings.
///
/// Tolerances: the crossing is at `pi` to within the square root of the residual tolerance
/// (`1e-6`, as `Event::x` says of branches meeting at so small an angle); the end state is
/// pinned by the residual tolerance to `tol::SOLVE` over its pivot ratio, far from singular.
#[test]
fn a_crank_rocker_within_the_residual_tolerance_of_a_change_point_meets_a_crossing() {
    let stop = SweepConfig::default();
    let through = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let (from, to) = (0.1, 0.1 + TAU);
    for k in [1.0, 1.0 / 1_048_576.0] {
        let four_bar = |excess: f64| FourBar { a: k, b: 2.0 * k, c: (2.0 + excess) * k, d: 3.0 * k };
        let sweep = |m: &FourBar, cfg: SweepConfig| {
            let guess = four_bar_angles(m.a, m.b, m.c, m.d, from, 1.0).expect("assembles at the start");
            Sweep::<_, Kin<2, 1, 2>, 2, 1, 2>::new(m, [from], [to], 37, guess).unwrap().with_config(cfg).run()
        };
        for excess in [2f64.powi(-44), -(2f64.powi(-44))] {
            let m = four_bar(excess);
            let r = sweep(&m, stop);
            let what = format!("size {k:e}, b + c - a - d = {excess:e} of the size");
            let kinds: Vec<EventKind> = r.events.iter().map(|e| e.kind).collect();
            assert_eq!(kinds, [EventKind::SingularCrossing], "{what}: {:?}", r.stop);
            assert!((r.events[0].x[0] - PI).abs() < 1e-6, "{what}: {:?}", r.events);
        }
        let m = four_bar(2f64.powi(-44));
        let r = sweep(&m, through);
        assert!(r.is_completed(), "size {k:e}: {:?}", r.stop);
        let end = r.states.last().expect("a state per sample");
        let other = four_bar_angles(m.a, m.b, m.c, m.d, to, -1.0).expect("assembles at the end");
        let pivot = end.health.min_pivot;
        assert!(apart(&[end.q[0], end.q[1]], &other) <= tol::SOLVE / pivot, "size {k:e}: {end:?} against {other:?}");
        let far = sweep(&four_bar(2f64.powi(-34)), stop);
        assert!(far.is_completed() && far.events.is_empty(), "size {k:e}: {:?}, {:?}", far.stop, far.events);
    }
}
