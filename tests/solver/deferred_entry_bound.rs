//! Which kernel answers a deferred step: the deferred one, for guesses whose magnitudes sum to
//! at most the configured bound less a margin (`largest_precise_angle(cfg) - 8`), and the
//! checked one beyond it. A step of a sweep past 2545 turns of a closed-form angle (16,000 rad,
//! the bound of the smallest residual tolerance) stays with the deferred kernel under a larger
//! configured bound.
//!
//! Both kernels give the same answer wherever they run, so the answer alone cannot tell them
//! apart. The probe does: a trigonometry whose closed-form angles lie `PROBE` (1e13 rad, beyond
//! the largest configured bound, 4.5e12 at `residual_tol = 1e-3`) off libm's. The deferred
//! kernel does not test the angles it computes (its entry test of the guesses stands for that),
//! so it returns the shifted angles; the checked kernel tests them and reports `TooManyTurns`.

use kinloop::__gen::{ByValue, InputTrig, Kin, Libm, largest_precise_angle};
use kinloop::{Error, Mechanism, NewtonConfig};
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::{FourBar, SliderCrank};
use std::f64::consts::{PI, TAU};

/// How far the probe moves every closed-form angle: beyond every valid configuration's bound.
const PROBE: f64 = 1e13;

/// libm's sines and cosines; every closed-form angle libm's plus [`PROBE`].
struct Probe;

impl InputTrig for Probe {
    fn sin_cos(&mut self, _slot: usize, arg: f64) -> (f64, f64) {
        arg.sin_cos()
    }

    fn angle(&mut self, _slot: usize, _s: f64, _c: f64, exact: impl FnOnce() -> f64) -> f64 {
        exact() + PROBE
    }
}

/// The configuration of the smallest residual tolerance: the bound 16,000 rad (2545 turns).
fn least() -> NewtonConfig {
    NewtonConfig::default().with_residual_tol(16.0 * f64::EPSILON)
}

/// The deferred step at `(x, guess)` with `trig`.
fn deferred<M: Mechanism<N, NI, NO>, T: InputTrig, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    x: [f64; NI],
    guess: [f64; N],
    cfg: &NewtonConfig,
    trig: &mut T,
) -> Result<Kin<N, NI, NO>, Error> {
    m.kinematics_step_sink::<_, _, false>(&x, &guess, cfg, trig, ByValue)
}

/// With libm the deferred step answers exactly what the checked one does (the same `Debug`
/// text: shortest round-trip floats, every field of an error); returns that answer.
fn as_checked<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    x: [f64; NI],
    guess: [f64; N],
    cfg: &NewtonConfig,
) -> Result<Kin<N, NI, NO>, Error> {
    let d = deferred(m, x, guess, cfg, &mut Libm);
    let c = m.kinematics_step_checked(&x, &guess, cfg, &mut Libm, ByValue);
    assert_eq!(format!("{d:?}"), format!("{c:?}"), "{} at {x:?} from {guess:?}", M::NAME);
    d
}

/// Whether the deferred kernel answered (not the checked one it reruns): the probe's shifted
/// angles came back. The checked kernel answers the probe `TooManyTurns` (checked here too).
fn deferred_answered<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    x: [f64; NI],
    guess: [f64; N],
    cfg: &NewtonConfig,
    angle: usize,
) -> bool {
    let checked = m.kinematics_step_checked(&x, &guess, cfg, &mut Probe, ByValue);
    assert!(matches!(checked, Err(Error::TooManyTurns { .. })), "{checked:?}");
    match deferred(m, x, guess, cfg, &mut Probe) {
        Ok(k) => {
            // The probe's angle, within a half turn of the guess moved by PROBE.
            assert!((k.q[angle] - PROBE - guess[angle]).abs() <= 4.0, "{:?} from {guess:?}", k.q);
            true
        }
        d => {
            assert_eq!(format!("{d:?}"), format!("{checked:?}"));
            false
        }
    }
}

/// The gear-lever's pin angle turns with the carrier: 3000 carrier turns put its guess near
/// 18,850 rad, beyond the least bound (16,000) and far within the default one (4.5e6). The
/// deferred kernel answers, with the checked kernel's bits; so does the four-bar, its two
/// angles' guesses summing to 37,700 rad.
#[test]
fn guesses_past_2545_turns_within_the_configured_bound_stay_deferred() {
    let cfg = NewtonConfig::default();
    let m = GearLever::default();
    for k in 0..24 {
        let x = 3000.0 * TAU + k as f64 * TAU / 24.0;
        let mut guess = m.guess_flat(&[0.0]);
        // The pin's angle on the carrier's turn, where a sweep's guess has it.
        guess[1] += 3000.0 * TAU;
        guess = as_checked(&m, [x], guess, &cfg).expect("the gear-lever assembles everywhere").q;
        assert!(guess[1].abs() > 16_000.0 && guess[1].abs() < largest_precise_angle(&cfg) - 8.0, "{guess:?}");
        assert!(deferred_answered(&m, [x], guess, &cfg, 1), "at {x}");
        // The same guess under the least bound: the checked kernel answers, with an error.
        assert!(!deferred_answered(&m, [x], guess, &least(), 1), "at {x}");
        assert!(matches!(as_checked(&m, [x], guess, &least()), Err(Error::TooManyTurns { .. })));
    }
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let guess = m.guess_flat(&[0.7]).map(|g| g + 3000.0 * TAU);
    let k = as_checked(&m, [0.7], guess, &cfg).expect("the crank-rocker assembles");
    assert!(k.q.iter().all(|q| q.abs() > 16_000.0), "{:?}", k.q);
    assert!(deferred_answered(&m, [0.7], guess, &cfg, 0));
}

/// The entry test's edge, on the slider-crank's one closed-form angle (its rod's, unknown 0):
/// a guess at the bound less the margin runs the deferred kernel; the next float above it the
/// checked one, whose answer there (the angle within a half turn of the guess, inside the
/// configured bound) is a state, the deferred step's with libm. Under the least bound and the
/// default one.
#[test]
fn the_entry_test_is_the_configured_bound_less_the_margin() {
    let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
    for cfg in [least(), NewtonConfig::default()] {
        let bound = largest_precise_angle(&cfg) - 8.0;
        let mut guess = m.guess_flat(&[0.3]);
        let x = 0.3;
        guess[0] = bound;
        assert!(deferred_answered(&m, [x], guess, &cfg, 0), "{bound}");
        let k = as_checked(&m, [x], guess, &cfg).expect("within the bound");
        assert!(k.q[0].abs() <= largest_precise_angle(&cfg), "{:?}", k.q);
        guess[0] = bound.next_up();
        assert!(!deferred_answered(&m, [x], guess, &cfg, 0), "{bound}");
        let k = as_checked(&m, [x], guess, &cfg).expect("within the configured bound");
        assert!((k.q[0] - guess[0]).abs() <= PI + 1e-9 && k.q[0].abs() <= largest_precise_angle(&cfg), "{:?}", k.q);
    }
}

/// Beyond the configured bound the deferred step answers the checked kernel's `TooManyTurns`,
/// naming the angle beyond it: 16,100 rad under the least bound, 1e7 under the default.
#[test]
fn guesses_beyond_the_configured_bound_get_the_checked_kernels_error() {
    let m = GearLever::default();
    for (cfg, at) in [(least(), 16_100.0), (NewtonConfig::default(), 1e7)] {
        let mut guess = m.guess_flat(&[0.4]);
        guess[1] += at;
        assert!(!deferred_answered(&m, [0.4], guess, &cfg, 1));
        match as_checked(&m, [0.4], guess, &cfg) {
            Err(Error::TooManyTurns { value, .. }) => {
                assert!(value.abs() > largest_precise_angle(&cfg) && (value - guess[1]).abs() <= 4.0, "{value}")
            }
            other => panic!("{other:?}"),
        }
    }
}
