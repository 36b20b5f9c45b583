//! Traces started where a sweep stopped, at a limit position, over random linkages: four-bars in
//! closed form and by Newton's method (which reaches a limit position only linearly), and
//! offset slider-cranks whose rod's `asin` meets 1 there. Each trace starts at the limit
//! position the sweep located (listed first), closes its curve through it, and lists the other
//! limit positions where the geometry puts them: a four-bar's where coupler and rocker stretch
//! or fold in line (`|BD| = b + c` or `|b - c|`, the law of cosines), a slider-crank's where
//! `r sin phi - e = +-l`. Every point lies on the loop.
//!
//! Tolerances: a limit position is located to the rounding of the arclength (`tol::LOCATED`,
//! 1e-9 rad, is far above it); a point is a corrected Newton solution, on the loop to the
//! solver's tolerance relative to the links' size (`1e-10`), but the start, the point solve's
//! positions at a double root (`1e-8`, see `traced_folds`).

use kinloop::{Error, EventKind, Named, TraceConfig};
use kinloop_fixtures::{FourBar, SliderCrank};
use std::f64::consts::{PI, TAU};

use crate::support::{Xorshift, four_bar_limit, tol};
use crate::sweep_api::NewtonFourBar;

/// The limit position a sweep of a turn from `x0` stops at, with its positions; `None` where
/// the sweep does not start or turns fully.
fn stopped_at<M: Named<2, 1, NO>, const NO: usize>(m: &M, x0: f64) -> Option<(f64, [f64; 2])>
where
    M::Inputs: From<f64>,
    M::Unknowns: From<[f64; 2]> + Into<[f64; 2]>,
{
    let (g, _) = m.position(x0, &m.guess(x0)).ok()?;
    let mut sweep = m.sweep(x0, x0 + TAU, 361, &g).ok()?;
    let Some(Error::SweepStopped { kind: EventKind::LimitPosition, .. }) = sweep.by_ref().find_map(Result::err) else {
        return None;
    };
    let ev = sweep.events().last()?;
    Some((ev.x[0], <[f64; 2]>::try_from(&ev.q[..]).ok()?))
}

/// The folds of a trace from the limit position `at` (positions `q`) of `m`, after checking that
/// it closed, lists `at` first, and keeps every point on the loop (`residual` of each point, in
/// a mechanism whose longest link is `size`).
fn traced_folds<M: Named<2, 1, NO>, const NO: usize>(m: &M, at: f64, q: [f64; 2], size: f64, case: &str) -> Vec<f64>
where
    M::Inputs: From<f64>,
    M::Unknowns: From<[f64; 2]> + Into<[f64; 2]>,
{
    // The segment from `at - 10` to `at + 10` holds every curve of these linkages.
    let t = m.trace_curve(at, at - 10.0, &q.into(), &TraceConfig::default().with_ds(0.02)).expect(case);
    assert!(t.closed, "{case}: the curve closes");
    let folds: Vec<f64> = t.folds.iter().map(|f| f.x[0]).collect();
    assert_eq!(folds.first(), Some(&at), "{case}: the start is listed first: {folds:?}");
    assert_eq!(folds.len() % 2, 0, "{case}: a closed curve turns back an even number of times: {folds:?}");
    for (k, p) in t.points.iter().enumerate() {
        // The start is the point solve's at the limit position's input: a closed form's root
        // there is a double root, its positions known to about the square root of the rounding
        // (a slider-crank's `asin` of `1 - 3e-16` is 2.6e-8 from a right angle, and its cosine,
        // by a square root of `1 - s^2`, off by as much: up to `sqrt(8 eps) = 4.2e-8` times the
        // rod's length in the loop). Every later point is corrected onto the curve.
        let bound = if k == 0 { 5e-8 * size } else { 1e-10 };
        let r = m.residual(p.x[0], &p.q.into());
        assert!(r.iter().all(|v| v.abs() < bound), "{case}: off the loop at point {k}, {p:?}: {r:?}");
    }
    folds
}

/// Whether `x` is, to the location's tolerance, one of `limits` or its negative, modulo turns.
fn among(x: f64, limits: &[f64]) -> bool {
    limits.iter().filter(|l| !l.is_nan()).any(|l| {
        [*l, -*l].iter().any(|l| {
            let d = (x - l).rem_euclid(TAU);
            d.min(TAU - d) < tol::LOCATED
        })
    })
}

#[test]
fn traces_from_where_four_bar_sweeps_stopped_close_through_the_law_of_cosines_limits() {
    let mut cases = Xorshift(12345);
    let mut traced = 0;
    while traced < 30 {
        let [a, b, c, d] = [(); 4].map(|_| 0.5 + 3.0 * cases.unit());
        let x0 = TAU * cases.unit() - PI;
        let limits = [four_bar_limit(a, d, b + c), four_bar_limit(a, d, (b - c).abs())];
        let (closed_form, size) = (FourBar { a, b, c, d }, a.max(b).max(c).max(d));
        let Some((at, q)) = stopped_at(&closed_form, x0) else { continue };
        traced += 1;
        let case = format!("{closed_form:?} from {x0}");
        for folds in [
            traced_folds(&closed_form, at, q, size, &case),
            traced_folds(&NewtonFourBar { a, b, c, d }, at, q, size, &case),
        ] {
            assert!(folds.iter().all(|&x| among(x, &limits)), "{case}: {folds:?} against +-{limits:?}");
        }
    }
}

#[test]
fn traces_from_where_slider_crank_sweeps_stopped_close_through_their_limits() {
    let mut cases = Xorshift(987);
    let mut traced = 0;
    while traced < 30 {
        let (r, l, e) = (0.5 + 3.0 * cases.unit(), 0.5 + 3.0 * cases.unit(), 2.0 * cases.unit() - 1.0);
        let x0 = TAU * cases.unit() - PI;
        let m = SliderCrank { r, l, e };
        let Some((at, q)) = stopped_at(&m, x0) else { continue };
        traced += 1;
        let case = format!("{m:?} from {x0}");
        // `sin phi = (e +- l) / r`: `asin` and its supplement.
        let limits: Vec<f64> = [(e + l) / r, (e - l) / r].into_iter().flat_map(|s| [s.asin(), PI - s.asin()]).collect();
        let folds = traced_folds(&m, at, q, r.max(l), &case);
        let on_limit = |x: f64| {
            limits.iter().filter(|l| !l.is_nan()).any(|l| {
                let d = (x - l).rem_euclid(TAU);
                d.min(TAU - d) < tol::LOCATED
            })
        };
        assert!(folds.iter().all(|&x| on_limit(x)), "{case}: {folds:?} against {limits:?}");
    }
}
