//! The sweep recipe written by hand (`kinloop_bench::hand_sweep`: inputs' sines and cosines
//! rotated, angles advanced by a short `asin` series, libm only to re-synchronise) against the
//! hand closed forms evaluated with libm at every sample: an independent check of the rotation
//! and the increments, since the closed form computes every sample from scratch (`sin_cos`,
//! `asin`, `atan2`) and carries nothing from one sample to the next.
//!
//! Tolerances, relative to `max(1, |value|)`: positions (the unknowns and the output point) 1e-14,
//! the recipe's promise. Analogs: the same formulas as the closed form's, evaluated on sines and
//! cosines of angles that differ from those libm is given by a few 1e-15 rad (libm's arguments
//! are rounded, `h k` and `(1 - u) h k` up to `|x| = 4 pi`; the rotation has its own rounding),
//! so an analog `q'` or `q''` is defined only to that angle times `|q''|` or `|q'''|` (see
//! [`ANGLE_ROUNDING`]): 1e-13 for the rhombic drive and the four-bar (`|q'''|` below 10), 3e-12
//! for the gear-lever, whose rocker's third derivative reaches 675 where the pin passes closest
//! to the pivot (checked by `analog_tolerances_cover_the_third_derivatives`). The bound leaves out
//! what the rotation itself carries between re-synchronisations (the positions' deviation, up to
//! 4e-15); measured over 10^6 samples at 720 and 20,000 a turn, the largest analog deviations
//! are 3.0e-15 (rhombic drive), 4.7e-15 (four-bar) and 4.2e-13 (gear-lever): under a twentieth
//! of the tolerance for the first two, a seventh for the gear-lever.

use std::f64::consts::TAU;

use kinloop_bench::hand::{FOUR_BAR, FourBarClosed, GearLeverClosed, gear_lever};
use kinloop_bench::hand_sweep::{
    FOUR_BAR_TERMS, FourBarSweep, GEAR_LEVER_TERMS, GearLeverSweep, HandSweep, PERIOD, RHOMBIC_TERMS, RhombicSweep,
    asin_series,
};
use kinloop_bench::lean::hand_sweep_fold;
use kinloop_bench::rhombic::{self, ClosedForm};
use kinloop_bench::sweep::{Failed, Step, Stepper, rel_err};

/// Positions: the recipe's promise.
const POSITION_TOL: f64 = 1e-14;
/// Analogs of the rhombic drive and the four-bar (see the module documentation).
const ANALOG_TOL: f64 = 1e-13;
/// Analogs of the gear-lever (see the module documentation).
const GEAR_LEVER_ANALOG_TOL: f64 = 3e-12;
/// A bound of the difference of the angles whose sines and cosines the two paths compute (rad):
/// four rounding errors of the largest argument libm is given, `|(1 - u) x| <= 4 pi` (half an ulp
/// there is 8.9e-16).
const ANGLE_ROUNDING: f64 = 4.0 * 8.9e-16;

/// Largest deviations `[positions, analogs]` of a hand sweep from its closed form over `steps`
/// samples after the first; the numbers of a sample are `q`, the point's first two (positions),
/// and `dq`, `d2q`, the point's last four (analogs).
fn deviation<S: HandSweep<N, NP>, const N: usize, const NP: usize>(
    s: S,
    reference: impl Fn(f64, &[f64; N]) -> Result<(Step<N>, [f64; NP]), Failed>,
    guess0: [f64; N],
    steps: usize,
) -> [f64; 2] {
    let (mut prev, _) = reference(0.0, &guess0).unwrap();
    let dev = hand_sweep_fold(s, steps, [0.0f64; 2], |mut dev, x, got, point| {
        let (want, want_point) = reference(x, &prev.q).unwrap();
        prev = want;
        let positions = (0..N).map(|u| rel_err(got.q[u], want.q[u]));
        let analogs = (0..N).flat_map(|u| [rel_err(got.dq[u], want.dq[u]), rel_err(got.d2q[u], want.d2q[u])]);
        let (pp, pa) = (0..NP).map(|i| (i, rel_err(point[i], want_point[i]))).partition::<Vec<_>, _>(|(i, _)| *i < 2);
        for d in positions.chain(pp.into_iter().map(|(_, d)| d)) {
            dev[0] = dev[0].max(if d.is_nan() { f64::INFINITY } else { d });
        }
        for d in analogs.chain(pa.into_iter().map(|(_, d)| d)) {
            dev[1] = dev[1].max(if d.is_nan() { f64::INFINITY } else { d });
        }
        dev
    });
    dev.unwrap()
}

fn rhombic_dev<const T: usize>(turn: usize, period: usize, steps: usize) -> [f64; 2] {
    let p = rhombic::PARAMS;
    let closed = ClosedForm::new(&p);
    let guess0 = rhombic::initial_guess(&p);
    deviation(RhombicSweep::<T>::new(&p, turn, period), |x, g| closed.step(x, g).map(|s| (s, [])), guess0, steps)
}

fn four_bar_guess() -> [f64; 2] {
    FOUR_BAR.solve(0.0).unwrap().q.into()
}

fn four_bar_dev<const T: usize>(turn: usize, period: usize, steps: usize) -> [f64; 2] {
    let closed = FourBarClosed::of(&FOUR_BAR);
    let g = four_bar_guess();
    deviation(FourBarSweep::<T>::new(closed, turn, period, g), |x, g| closed.full(x, g), g, steps)
}

fn gear_lever_guess() -> [f64; 2] {
    gear_lever().solve(0.0).unwrap().q.into()
}

fn gear_lever_dev<const T: usize>(turn: usize, period: usize, steps: usize) -> [f64; 2] {
    let closed = GearLeverClosed::of(&gear_lever());
    let g = gear_lever_guess();
    deviation(GearLeverSweep::<T>::new(closed, turn, period, g), |x, g| closed.full(x, g), g, steps)
}

fn assert_within(name: &str, dev: [f64; 2], analog_tol: f64) {
    assert!(dev[0] <= POSITION_TOL && dev[1] <= analog_tol, "{name}: positions {:e}, analogs {:e}", dev[0], dev[1]);
}

/// Every hand sweep over `steps` samples of turns of `turn` within the tolerances.
fn all_within(turn: usize, steps: usize) {
    assert_within(&format!("rhombic, {turn}"), rhombic_dev::<RHOMBIC_TERMS>(turn, PERIOD, steps), ANALOG_TOL);
    let dev = four_bar_dev::<FOUR_BAR_TERMS>(turn, PERIOD, steps);
    assert_within(&format!("four-bar, {turn}"), dev, ANALOG_TOL);
    let dev = gear_lever_dev::<GEAR_LEVER_TERMS>(turn, PERIOD, steps);
    assert_within(&format!("gear-lever, {turn}"), dev, GEAR_LEVER_ANALOG_TOL);
}

/// The largest third derivative of the unknowns along a turn: central differences of the
/// acceleration analogs `d2q(x)` (step 1e-4: truncation ~1e-8 relative), 20,000 points.
fn max_third<const N: usize>(d2q: impl Fn(f64) -> [f64; N]) -> f64 {
    let (n, e) = (20_000, 1e-4);
    (0..n)
        .flat_map(|k| {
            let x = TAU * k as f64 / n as f64;
            let (plus, minus) = (d2q(x + e), d2q(x - e));
            (0..N).map(move |u| ((plus[u] - minus[u]) / (2.0 * e)).abs())
        })
        .fold(0.0, f64::max)
}

/// The analog tolerances: the largest third derivative of each mechanism's unknowns along a
/// turn times [`ANGLE_ROUNDING`] is within its tolerance (below 10 for the rhombic drive and
/// the four-bar, about 675 for the gear-lever).
#[test]
fn analog_tolerances_cover_the_third_derivatives() {
    let rhombic = ClosedForm::new(&rhombic::PARAMS);
    let four = FourBarClosed::of(&FOUR_BAR);
    let gear = GearLeverClosed::of(&gear_lever());
    let thirds = [
        ("rhombic", max_third(|x| rhombic.step(x, &[0.0; 4]).unwrap().d2q), ANALOG_TOL),
        ("four-bar", max_third(|x| four.full(x, &[0.0; 2]).unwrap().0.d2q), ANALOG_TOL),
        ("gear-lever", max_third(|x| gear.full(x, &[0.0; 2]).unwrap().0.d2q), GEAR_LEVER_ANALOG_TOL),
    ];
    for (name, third, tol) in thirds {
        assert!(third * ANGLE_ROUNDING <= tol, "{name}: largest third derivative {third}");
    }
    assert!(thirds[0].1 < 10.0 && thirds[1].1 < 10.0, "{thirds:?}");
    assert!(thirds[2].1 > 600.0 && thirds[2].1 < 700.0, "{thirds:?}");
}

/// The series against libm's `asin` over the increments' range (up to 0.06): within the first
/// neglected term over `1 - x^2` (the remainder's bound), plus the rounding of both (a few ulps
/// of `x`).
#[test]
fn asin_series_is_within_its_remainder() {
    for i in -600..=600 {
        let x = f64::from(i) * 1e-4;
        let check = |terms: usize, got: f64, first_neglected: f64| {
            let bound = first_neglected / (1.0 - x * x) + 4.0 * f64::EPSILON * x.abs();
            assert!((got - x.asin()).abs() <= bound, "{terms} terms at {x}: {got} vs {}", x.asin());
        };
        check(3, asin_series::<3>(x), 5.0 / 112.0 * x.abs().powi(7));
        check(6, asin_series::<6>(x), 231.0 / 13312.0 * x.abs().powi(13));
    }
}

/// 20 turns of 720 samples and one of 20,000 (a second or two in debug mode).
#[test]
fn hand_sweeps_match_the_closed_forms() {
    for (turn, steps) in [(720, 20 * 720), (20_000, 20_000)] {
        all_within(turn, steps);
    }
}

/// 10^6 samples at each density (1389 turns of 720, 50 of 20,000).
#[test]
#[ignore = "10^6 samples per sweep: run in release mode"]
fn hand_sweeps_match_the_closed_forms_over_a_million_samples() {
    for turn in [720, 20_000] {
        all_within(turn, 1_000_000);
    }
}

/// The drift behind the choice of period and series terms: the largest deviations over 10^6
/// samples for several periods and term counts
/// (`cargo test --release -p kinloop-bench --test hand_sweep -- --ignored --nocapture drift`).
#[test]
#[ignore = "a table of measurements: run in release mode with --nocapture"]
fn drift_by_period_and_terms() {
    let steps = 1_000_000;
    for turn in [720, 20_000] {
        for period in [80, 160, 320, 720, 2000, 20_000] {
            let row =
                |name: &str, d: [f64; 2]| println!("{name} turn {turn} period {period}: {:.1e} {:.1e}", d[0], d[1]);
            row("rhombic T2", rhombic_dev::<2>(turn, period, steps));
            row("rhombic T3", rhombic_dev::<3>(turn, period, steps));
            row("four-bar T2", four_bar_dev::<2>(turn, period, steps));
            row("four-bar T3", four_bar_dev::<3>(turn, period, steps));
            row("gear-lever T4", gear_lever_dev::<4>(turn, period, steps));
            row("gear-lever T5", gear_lever_dev::<5>(turn, period, steps));
            row("gear-lever T6", gear_lever_dev::<6>(turn, period, steps));
        }
    }
}

/// A hand sweep whose libm samples are counted: the loop the counts measure
/// ([`hand_sweep_fold`]) must re-synchronise every `PERIOD` samples and at the first of every
/// turn, or the floor it measures would be cheaper than the recipe whose drift is tested.
#[derive(Clone)]
struct Counted<S> {
    inner: S,
    syncs: std::rc::Rc<std::cell::Cell<usize>>,
}

impl<S: HandSweep<N, NP>, const N: usize, const NP: usize> HandSweep<N, NP> for Counted<S> {
    fn turn(&self) -> usize {
        self.inner.turn()
    }
    fn period(&self) -> usize {
        self.inner.period()
    }
    fn sync(&mut self, x: f64) -> Result<(Step<N>, [f64; NP]), Failed> {
        self.syncs.set(self.syncs.get() + 1);
        self.inner.sync(x)
    }
    fn advance(&mut self) -> Result<(Step<N>, [f64; NP]), Failed> {
        self.inner.advance()
    }
}

/// The libm samples of 3 turns: the first sample, and then every `PERIOD`-th since the last
/// libm sample or the first of every turn, whichever comes first.
#[test]
fn hand_sweeps_resynchronise_every_period_and_every_turn() {
    for turn in [720usize, 20_000] {
        let steps = 3 * turn;
        let syncs = std::rc::Rc::new(std::cell::Cell::new(0));
        let s =
            Counted { inner: RhombicSweep::<RHOMBIC_TERMS>::new(&rhombic::PARAMS, turn, PERIOD), syncs: syncs.clone() };
        hand_sweep_fold(s, steps, (), |(), _, _, _| ()).unwrap();
        // Independently: walk the samples' indices in the turn.
        let (mut want, mut since) = (1usize, 0usize);
        for i in 1..=steps {
            since += 1;
            if i % turn == 0 || since == PERIOD {
                want += 1;
                since = 0;
            }
        }
        assert_eq!(syncs.get(), want, "{turn} a turn");
        assert!(want >= 3 * turn / PERIOD, "{want} libm samples in 3 turns of {turn}");
    }
}
