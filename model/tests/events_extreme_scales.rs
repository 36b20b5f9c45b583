//! Events of a run-time model at every size, as the compiled mechanism's: the limit positions
//! and singular crossings its sweeps locate, its limit report (the input's events and the
//! extremes of output columns), and its sampled extremes, dwells and states beside a crossing,
//! for mechanisms whose lengths are `k` times a unit-size one's, from `1e-300` to `1e300`.
//!
//! The compiled mechanism of the same declaration, stepping with libm's sines and cosines as a
//! model does (`common::Libm`), is the reference at each size: one sweep and one analysis over
//! two kernels that give the same numbers to the bit (`sweeps.rs`, `analysis.rs`; at sizes
//! beyond the closed forms', both solve each position by the runtime's one whole-system Newton,
//! `parity.rs`), so the events and analyses must be equal to the bit. The compiled ones are
//! checked against closed forms at every size in the workspace's `tests/sweeps` and
//! `tests/analysis` (`events_extreme_scales.rs`, `limits_extreme_scales.rs`); here the events'
//! inputs are checked against theirs too, and against the model's own at size 1: the same
//! inputs at every size, to `1e-12` for a limit position (where the continuation's augmented
//! Jacobian is regular, its residual tolerance pins the located point) and to `1e-9` (what an
//! event's input promises) for a crossing.

mod common;

use common::{Libm, read, set};
use kinloop::analysis::{Column, Sampled};
use kinloop::metrics::Limits;
use kinloop::{AtSingular, Event, EventKind, Kin, Mechanism, Sweep, SweepConfig};
use kinloop_fixtures as fx;
use kinloop_fixtures::gear_lever::{GEAR_LEVER_TEXT, GearLever};
use kinloop_model::Model;
use std::f64::consts::{PI, TAU};

/// The sizes: size 1 (the reference) first, below `1e-8`, inside and beyond the closed forms'
/// sizes (`1e±144`) on both sides.
const SCALES: [f64; 7] = [1.0, 1e-12, 1e-100, 1e-300, 1e6, 1e100, 1e300];

/// The end of the sweeps through the change point: short of a whole turn (as the limit report's
/// tests sweep it), the crossing inside; not `TAU`.
#[allow(clippy::approx_constant)]
const TO: f64 = 6.28;

/// A limit position's input at size `k` against size 1's (see the module's documentation).
const FOLD_TOL: f64 = 1e-12;

/// An event's input against its closed form, and a crossing's against size 1's: what
/// [`Event::x`] promises.
const LOCATED: f64 = 1e-9;

/// An event without its block's description (the compiled mechanism's names are constants, the
/// model's its own): kind, input, fraction of the path and positions, compared to the bit.
fn strip(e: &[Event]) -> Vec<(EventKind, Vec<f64>, f64, Vec<f64>)> {
    e.iter().map(|e| (e.kind, e.x.clone(), e.tau, e.q.clone())).collect()
}

/// The four-bar's model with links `dims` times `k`, and the compiled four-bar alike.
fn four_bar(dims: [f64; 4], k: f64) -> (Libm<fx::FourBar>, Model) {
    let [a, b, c, d] = dims.map(|v| v * k);
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", a), ("b", b), ("c", c), ("d", d)]);
    (Libm(fx::FourBar { a, b, c, d }), m)
}

/// The offset slider-crank's model with `dims` times `k`, and the compiled one alike.
fn slider_crank(dims: [f64; 3], k: f64) -> (Libm<fx::SliderCrank>, Model) {
    let [r, l, e] = dims.map(|v| v * k);
    let mut m = read(fx::SLIDER_CRANK_TEXT);
    set(&mut m, &[("r", r), ("l", l), ("e", e)]);
    (Libm(fx::SliderCrank { r, l, e }), m)
}

/// The events and the number of samples of both sweeps over `[from, to]` from `guess`,
/// configured by `cfg`: (compiled, model). Both must end alike (a stop at an event, or every
/// sample).
fn both_events<M: Mechanism<2, 1, NO>, const NO: usize>(
    (compiled, model): &mut (M, Model),
    (from, to): (f64, f64),
    samples: usize,
    guess: [f64; 2],
    cfg: SweepConfig,
) -> ((Vec<Event>, usize), (Vec<Event>, usize)) {
    let c = Sweep::<M, Kin<2, 1, NO>, 2, 1, NO>::new(compiled, [from], [to], samples, guess)
        .unwrap()
        .with_config(cfg)
        .run();
    let r = model.sweep_with(&[from], &[to], samples, &guess, cfg).unwrap().run();
    assert_eq!(c.stop.event().map(|e| e.kind), r.stop.event().map(|e| e.kind), "{:?} {:?}", c.stop, r.stop);
    assert_eq!(c.is_completed(), r.is_completed(), "{:?} {:?}", c.stop, r.stop);
    ((c.events, c.states.len()), (r.events, r.states.len()))
}

/// The model's sweep toward a limit position or through crossings at every size: events equal
/// to the compiled mechanism's to the bit, of the kinds `kinds` at the inputs `exact` (to
/// [`LOCATED`]) and at size 1's (to `same`), after as many samples as at size 1.
#[allow(clippy::too_many_arguments)]
fn events_at_every_scale<M: Mechanism<2, 1, NO>, const NO: usize>(
    what: &str,
    mut at: impl FnMut(f64) -> (M, Model),
    range: (f64, f64),
    samples: usize,
    guess: impl Fn(&M) -> [f64; 2],
    cfg: SweepConfig,
    kinds: &[EventKind],
    exact: &[f64],
    same: f64,
) {
    let mut base = None;
    for k in SCALES {
        let mut pair = at(k);
        let g = guess(&pair.0);
        let ((c, c_samples), (r, r_samples)) = both_events(&mut pair, range, samples, g, cfg);
        assert_eq!(strip(&c), strip(&r), "{what} at size {k:e}");
        assert_eq!(c_samples, r_samples, "{what} at size {k:e}");
        assert_eq!(r.iter().map(|e| e.kind).collect::<Vec<_>>(), kinds, "{what} at size {k:e}: {r:?}");
        let (one, one_samples) = base.get_or_insert_with(|| (r.clone(), r_samples));
        assert_eq!(r_samples, *one_samples, "{what} at size {k:e}: samples");
        for ((e, b), x) in r.iter().zip(one.iter()).zip(exact) {
            assert!((e.x[0] - x).abs() <= LOCATED, "{what} at size {k:e}: {e:?} against {x}");
            assert!((e.x[0] - b.x[0]).abs() <= same, "{what} at size {k:e}: {e:?} against {b:?}");
        }
    }
}

/// The sweeps' events: a four-bar's and a short-rod slider-crank's limit positions of the
/// input (coupler and rocker stretched in line, `|BD| = b + c` by the law of cosines; the rod
/// perpendicular to the guide, `sin phi = (e - l) / r`), a Grashof-equal four-bar's change point
/// at `pi` (a sweep stopping there), a parallelogram's two at `pi` and `2 pi` (a sweep going
/// on through both).
#[test]
fn a_models_sweeps_locate_the_compiled_events_at_every_scale() {
    let stop = SweepConfig::default();
    let [a, b, c, d] = [3.0f64, 2.0, 2.5, 4.0];
    let limit = ((a * a + d * d - (b + c).powi(2)) / (2.0 * a * d)).acos();
    let dims = [a, b, c, d];
    let flat = |m: &Libm<fx::FourBar>| m.guess_flat(&[0.0]);
    let fold = [EventKind::LimitPosition];
    events_at_every_scale("four-bar", |k| four_bar(dims, k), (0.0, PI), 181, flat, stop, &fold, &[limit], FOLD_TOL);
    let [r, l, e] = [1.0f64, 1.2, 0.5];
    let limit = PI - ((e - l) / r).asin();
    let guess = |m: &Libm<fx::SliderCrank>| m.guess_flat(&[0.0]);
    let dims = [r, l, e];
    events_at_every_scale(
        "short rod",
        |k| slider_crank(dims, k),
        (0.0, TAU),
        181,
        guess,
        stop,
        &fold,
        &[limit],
        FOLD_TOL,
    );
    let cross = [EventKind::SingularCrossing];
    let dims = [1.0, 2.0, 2.5, 3.5];
    events_at_every_scale("Grashof-equal", |k| four_bar(dims, k), (0.0, TO), 73, flat, stop, &cross, &[PI], LOCATED);
    let go_on = stop.with_at_singular(AtSingular::Continue);
    let twice = [EventKind::SingularCrossing; 2];
    let parallelogram = |k| four_bar([1.0, 3.0, 1.0, 3.0], k);
    let range = (0.3, 0.3 + TAU);
    events_at_every_scale(
        "parallelogram",
        parallelogram,
        range,
        181,
        |_| [0.0, 0.3],
        go_on,
        &twice,
        &[PI, TAU],
        LOCATED,
    );
}

/// The limit report: a crank-rocker's rocker extremes, an offset slider-crank's dead centres, a
/// Grashof-equal four-bar's `pc.x` across its change point, at every size and at 5 and 73
/// samples: the compiled report to the bit, and the same extremes' inputs as at size 1.
#[test]
fn a_models_limit_reports_are_the_compiled_ones_at_every_scale() {
    fn check<M: Mechanism<2, 1, NO>, const NO: usize>(
        what: &str,
        mut at: impl FnMut(f64) -> (M, Model),
        (from, to): (f64, f64),
        column: &str,
        count: usize,
    ) {
        for samples in [5, 73] {
            let mut base: Option<Vec<f64>> = None;
            for k in SCALES {
                let what = format!("{what}, size {k:e}, {samples} samples");
                let (compiled, mut model) = at(k);
                let guess = compiled.guess_flat(&[from]);
                let columns = [Column::<M>::named(column).unwrap()];
                let c = Limits::new(&compiled, from, to).samples(samples).guess(guess).columns(&columns).run();
                let c = c.unwrap_or_else(|e| panic!("{what}: {e}"));
                let r = model.limits(from, to, samples, &guess, &[column]).unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(
                    (c.reached, &c.outputs, strip(&c.events)),
                    (r.reached, &r.outputs, strip(&r.events)),
                    "{what}"
                );
                let found: Vec<f64> = r.outputs[0].extremes.iter().map(|e| e.x()).collect();
                assert_eq!(found.len(), count, "{what}: {r}");
                let one = base.get_or_insert_with(|| found.clone());
                for (x, b) in found.iter().zip(one.iter()) {
                    // An extreme's input: its velocity analog's root, to the solve's accuracy
                    // over the acceleration analog (at least 0.24 here): well within 1e-10.
                    assert!((x - b).abs() <= 1e-10, "{what}: {r} against {one:?} at size 1");
                }
            }
        }
    }
    check("crank-rocker", |k| four_bar([1.0, 3.5, 3.0, 4.0], k), (0.3, 0.3 + TAU), "gamma", 2);
    check("slider-crank", |k| slider_crank([1.0, 3.2, 0.4], k), (0.3, 0.3 + TAU), "x", 2);
    check("Grashof-equal", |k| four_bar([1.0, 2.0, 2.5, 3.5], k), (0.0, TO), "pc.x", 3);
}

/// A sampled sweep through the Grashof-equal four-bar's change point, and the gear-lever
/// drive's turn: the extremes of `pc.x` (its minimum at the crossing), the states at inputs
/// beside the crossing and away from it, and the gear lever's three dwells, the compiled ones to
/// the bit at every size.
#[test]
fn a_models_sampled_analyses_are_the_compiled_ones_at_every_scale() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let from = -PI / 3.0;
    for k in SCALES {
        let (compiled, mut model) = four_bar([1.0, 2.0, 2.5, 3.5], k);
        let guess = compiled.guess_flat(&[0.0]);
        let c = Sampled::sweep_with(&compiled, 0.0, TO, 73, guess, cfg).unwrap();
        let r = model.sampled_with(&[0.0], &[TO], 73, &guess, cfg).unwrap();
        let extremes = r.extremes("pc.x").unwrap_or_else(|e| panic!("size {k:e}: {e}"));
        assert_eq!(c.extremes(Column::named("pc.x").unwrap()).unwrap(), extremes, "size {k:e}");
        assert!(extremes.len() == 3 && (extremes[1].x() - PI).abs() <= LOCATED, "size {k:e}: {extremes:?}");
        for phi in [PI - 1e-3, PI + 1e-5, PI + 1e-3, 1.0, 5.0] {
            let (a, b) = (c.at(phi).unwrap(), r.at(phi).unwrap_or_else(|e| panic!("size {k:e}, at {phi}: {e}")));
            assert_eq!((a.x.to_vec(), a.q.to_vec(), a.out.to_vec()), (b.x.to_vec(), b.q.to_vec(), b.out.to_vec()));
        }
        let lever = Libm(GearLever { l_c: 2.0 * k, l_p: 1.3 * k, u: 3.0 });
        let mut model = read(GEAR_LEVER_TEXT);
        set(&mut model, &[("l_c", 2.0 * k), ("l_p", 1.3 * k)]);
        let guess = lever.guess_flat(&[from]);
        let c = Sampled::sweep(&lever, from, from + TAU, 721, guess).unwrap();
        let r = model.sampled(&[from], &[from + TAU], 721, &guess).unwrap();
        let dwells = r.dwells("phi").unwrap_or_else(|e| panic!("size {k:e}: {e}"));
        assert_eq!(c.dwells(Column::named("phi").unwrap()).unwrap(), dwells, "size {k:e}");
        assert_eq!(dwells.len(), 3, "size {k:e}: {dwells:?}");
    }
}
