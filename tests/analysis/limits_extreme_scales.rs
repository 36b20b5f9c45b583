//! The analyses that locate events of a motion, at every size: the limit report ([`Limits`]:
//! the input's limit positions and crossings, and the extremes of output columns), the sampled
//! extremes, range and dwells, and the state anywhere in a sampled range, across a singular
//! crossing. A mechanism `k` times as large has the same angles and `k` times the lengths, so
//! each event must lie at the same input with its values scaled. Checked at sizes from `1e-300`
//! to `1e300` (below `1e-8`, where the continuation that locates events once misjudged its
//! residuals, and beyond the closed forms' sizes, `1e±144`, where Newton solves each position)
//! against closed forms derived here and against size 1.
//!
//! Tolerances: an extreme is a root of the column's velocity analog, located to rounding in the
//! input, and that analog is known to the solve's accuracy (`tol::SOLVE` of the size per
//! radian): the root lies within `tol::SOLVE / |v''|`, `4e-12` for the smallest acceleration
//! analog at these extremes (0.24, the crank-rocker's rocker at its maximum, measured), and
//! [`EXTREME_TOL`] leaves a factor 25 (a dwell's ends, roots of `v - level` where `|v'|` is
//! about 1, lie closer still); its value within `tol::SOLVE` of the size (it is stationary
//! there). An event of the input within `tol::LOCATED` of its closed form (what
//! [`kinloop::Event::x`] promises). A state beside a crossing is pinned by Newton's residual
//! tolerance to `tol::SOLVE / p` for its pivot ratio `p` (beyond the closed forms' sizes, where
//! Newton solves it; a closed form is exact to rounding).

use kinloop::analysis::{Column, Extreme, LocalExtreme, Sampled};
use kinloop::events::EventKind;
use kinloop::metrics::{LimitReport, Limits};
use kinloop::{AtSingular, Mechanism, SweepConfig};
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::{FourBar, SliderCrank};
use std::f64::consts::{PI, TAU};

use crate::support::{bisect, circle_point, gear_lever_explicit, tol, wrap};

/// The sizes: size 1 (the reference) first, below `1e-8`, inside and beyond the closed forms'
/// sizes on both sides.
const SCALES: [f64; 7] = [1.0, 1e-12, 1e-100, 1e-300, 1e6, 1e100, 1e300];

/// The end of the sweeps through the change point: short of a whole turn (as the limit report's
/// tests sweep it), the crossing inside; not `TAU`.
#[allow(clippy::approx_constant)]
const TO: f64 = 6.28;

/// An extreme's input against its closed form and against size 1's (see the module's
/// documentation).
const EXTREME_TOL: f64 = 1e-10;

/// The four-bar `dims` (crank `a`, coupler `b`, rocker `c`, frame `d`) at size `k`.
fn four_bar(dims: [f64; 4], k: f64) -> FourBar {
    FourBar { a: dims[0] * k, b: dims[1] * k, c: dims[2] * k, d: dims[3] * k }
}

/// The offset slider-crank `dims` (crank `r`, rod `l`, offset `e`) at size `k`; the fixture's
/// slider lies on the crank's `-x` side.
fn slider_crank(dims: [f64; 3], k: f64) -> SliderCrank {
    SliderCrank { r: dims[0] * k, l: dims[1] * k, e: dims[2] * k }
}

/// `found` (at size `k`, values of dimension `length`) against the closed form's extremes
/// `(kind, input, value at size 1)` and against size 1's `base`: the same count and kinds, the
/// inputs to [`EXTREME_TOL`], the values scaled to `tol::SOLVE` (an angle compared up to whole
/// turns).
fn check_extremes(
    what: &str,
    found: &[LocalExtreme],
    exact: &[(Extreme, f64, f64)],
    base: &[LocalExtreme],
    k: f64,
    length: bool,
) {
    assert_eq!(found.len(), exact.len(), "{what}: {found:?}");
    assert_eq!(found.len(), base.len(), "{what}: {found:?} against {base:?} at size 1");
    for ((e, &(kind, x, value)), b) in found.iter().zip(exact).zip(base) {
        let unit = if length { k } else { 1.0 };
        let v = e.value() / unit;
        let off = |w: f64| if length { v - w } else { wrap(v - w) };
        assert_eq!((e.kind, b.kind), (kind, kind), "{what}: {e:?}");
        assert!((e.x() - x).abs() <= EXTREME_TOL, "{what}: {e:?} against {x}");
        assert!((e.x() - b.x()).abs() <= EXTREME_TOL, "{what}: {e:?} against {b:?} at size 1");
        assert!(off(value).abs() <= tol::SOLVE, "{what}: {e:?} against {value}");
        assert!(off(b.value()).abs() <= tol::SOLVE, "{what}: {e:?} against {b:?} at size 1");
    }
}

/// The limit report of column `column` of `m(k)` over `range` at every size and sample count,
/// checked by `check` against the report at size 1.
fn reports<M: Mechanism<2, 1, NO>, const NO: usize>(
    at: impl Fn(f64) -> M,
    range: (f64, f64),
    column: Column<M>,
    check: impl Fn(&str, &LimitReport, &LimitReport, f64),
) {
    let report = |m: &M, samples: usize| {
        Limits::new(m, range.0, range.1).samples(samples).guess(m.guess_flat(&[range.0])).columns(&[column]).run()
    };
    for samples in [5, 10, 73, 361] {
        let base = report(&at(1.0), samples).unwrap();
        for k in SCALES {
            let what = format!("size {k:e}, {samples} samples");
            let r = report(&at(k), samples).unwrap_or_else(|e| panic!("{what}: {e}"));
            check(&what, &r, &base, k);
        }
    }
}

/// A crank-rocker four-bar (Grashof, the crank shortest: `1 + 4 < 3.5 + 3`) turns fully; its
/// rocker's extremes lie where crank and coupler are collinear. Derivation: at a rocker extreme
/// `dgamma/dphi = 0`, and the coupler's velocity at `C` (perpendicular to the rocker) has no
/// part across the coupler only if `B`'s (perpendicular to the crank) has none: the crank lies
/// along the coupler, stretched (`|AC| = b + a`) or folded (`|AC| = b - a`). In the triangle
/// `A D C` of sides `d`, `c` and `r = b +- a`, the law of cosines gives the angle of `AC` at
/// `A`, `theta = acos((r^2 + d^2 - c^2) / (2 r d))` (`C` above the frame, the fixture's mode),
/// and at `D`, `delta = acos((d^2 + c^2 - r^2) / (2 d c))`, so `gamma = pi - delta`.
/// Stretched, the crank points along `AC` (`phi = theta`), its longest `|AC|` the widest
/// `delta`: the rocker's minimum. Folded, the crank points away from `C` (`phi = theta + pi`):
/// its maximum.
#[test]
fn a_crank_rockers_extremes_at_every_scale() {
    let [a, b, c, d] = [1.0f64, 3.5, 3.0, 4.0];
    let at = |r: f64, turn: f64| {
        let theta = ((r * r + d * d - c * c) / (2.0 * r * d)).acos();
        let delta = ((d * d + c * c - r * r) / (2.0 * d * c)).acos();
        (theta + turn, PI - delta)
    };
    let (stretched, folded) = (at(b + a, 0.0), at(b - a, PI));
    let exact = [(Extreme::Min, stretched.0, stretched.1), (Extreme::Max, folded.0, folded.1)];
    reports(
        |k| four_bar([a, b, c, d], k),
        (0.3, 0.3 + TAU),
        FourBar::COL.gamma,
        |what, r, base, k| {
            assert!(r.events.is_empty(), "{what}: {r}");
            assert_eq!(r.reached, (0.3, 0.3 + TAU), "{what}: {r}");
            check_extremes(what, &r.outputs[0].extremes, &exact, &base.outputs[0].extremes, k, false);
        },
    );
}

/// The offset slider-crank's dead centres (the slider's extremes) lie where crank and rod are
/// collinear. Derivation: the slider `C = (x, e)` is at `|OC| = l + r` from the crank's pivot
/// with the rod stretched along the crank, at `|OC| = l - r` with it folded over the crank; the
/// fixture's slider lies on the `-x` side, so `x = -sqrt((l +- r)^2 - e^2)`. Stretched, the crank
/// points at `C` (`phi = atan2(e, x)`), the farthest `x`: the minimum. Folded, the crank points
/// away from it (`phi = atan2(-e, -x)`, a turn later in the range): the maximum.
#[test]
fn an_offset_slider_cranks_dead_centres_at_every_scale() {
    let [r, l, e] = [1.0f64, 3.2, 0.4];
    let (far, near) = (-((l + r).powi(2) - e * e).sqrt(), -((l - r).powi(2) - e * e).sqrt());
    let exact = [(Extreme::Min, e.atan2(far), far), (Extreme::Max, (-e).atan2(-near) + TAU, near)];
    reports(
        |k| slider_crank([r, l, e], k),
        (0.3, 0.3 + TAU),
        SliderCrank::COL.x,
        |what, rep, base, k| {
            assert!(rep.events.is_empty(), "{what}: {rep}");
            check_extremes(what, &rep.outputs[0].extremes, &exact, &base.outputs[0].extremes, k, true);
        },
    );
}

/// A slider-crank whose rod is too short for the crank to turn (`l < r + e`): the report ends
/// at the input's limit position (`sin phi = (e - l) / r`, the rod perpendicular to the guide,
/// see `tests/sweeps/events_extreme_scales.rs`), reached at the same input at every size, and
/// the slider's one extreme before it is the stretched dead centre of the slider-crank above.
#[test]
fn a_report_ends_at_the_input_s_limit_position_at_every_scale() {
    let [r, l, e] = [1.0f64, 1.2, 0.5];
    let limit = PI - ((e - l) / r).asin();
    let far = -((l + r).powi(2) - e * e).sqrt();
    let exact = [(Extreme::Min, e.atan2(far), far)];
    reports(
        |k| slider_crank([r, l, e], k),
        (0.0, TAU),
        SliderCrank::COL.x,
        |what, rep, base, k| {
            assert_eq!(rep.events.len(), 1, "{what}: {rep}");
            assert_eq!(rep.events[0].kind, EventKind::LimitPosition, "{what}: {rep}");
            assert!((rep.reached.1 - limit).abs() <= tol::LOCATED, "{what}: {rep}");
            assert!((rep.reached.1 - base.reached.1).abs() <= tol::LOCATED, "{what}: {rep} against {base}");
            assert_eq!(rep.reached.1, rep.events[0].x[0], "{what}: {rep}");
            check_extremes(what, &rep.outputs[0].extremes, &exact, &base.outputs[0].extremes, k, true);
        },
    );
}

/// The Grashof-equal four-bar (`a + d = b + c`) whose links lie in line at `phi = pi`, its
/// change point: `C` at `(d - c, 0)`, the nearest the rocker's circle comes to the crank's pivot.
const GRASHOF_EQUAL: [f64; 4] = [1.0, 2.0, 2.5, 3.5];

/// The joint `C`'s `x` has its extremes where `dx_C/dphi = -c sin(gamma) dgamma/dphi` vanishes:
/// at the rocker's extremes (crank and coupler collinear, see the crank-rocker above) and where
/// `C` lies on the frame's line. Stretched (`|AC| = a + b = 3`), the triangle `A D C` gives
/// `x_C = ((a + b)^2 - c^2 + d^2) / (2 d) = 15/7` at `phi = +-acos(x_C / (a + b))`, once on each
/// assembly mode (the sweep changes mode at the crossing); folded (`|AC| = b - a = 1`),
/// `x_C = 1 = d - c` at `phi = pi`, the crossing itself. So: maxima at `acos(5/7)` and
/// `2 pi - acos(5/7)`, the minimum `d - c` at `pi`.
fn grashof_equal_extremes() -> [(Extreme, f64, f64); 3] {
    let [a, b, c, d] = GRASHOF_EQUAL;
    let x = ((a + b).powi(2) - c * c + d * d) / (2.0 * d);
    let phi = (x / (a + b)).acos();
    [(Extreme::Max, phi, x), (Extreme::Min, PI, d - c), (Extreme::Max, TAU - phi, x)]
}

/// The limit report across the change point: at every size and sample count the one crossing
/// at `pi`, and `pc.x`'s extremes as derived, its minimum at the crossing's located input.
#[test]
fn a_report_across_a_change_point_at_every_scale() {
    let exact = grashof_equal_extremes();
    reports(
        |k| four_bar(GRASHOF_EQUAL, k),
        (0.0, TO),
        FourBar::COL.pc.x,
        |what, r, base, k| {
            assert_eq!(r.events.len(), 1, "{what}: {r}");
            assert_eq!(r.events[0].kind, EventKind::SingularCrossing, "{what}: {r}");
            assert!((r.events[0].x[0] - PI).abs() <= tol::LOCATED, "{what}: {r}");
            assert!((r.events[0].x[0] - base.events[0].x[0]).abs() <= tol::LOCATED, "{what}: {r} against {base}");
            assert_eq!(r.reached, (0.0, TO), "{what}: {r}");
            let found = &r.outputs[0].extremes;
            // The extreme at the crossing is reported there, located as the crossing is.
            assert_eq!(found.get(1).map(LocalExtreme::x), Some(r.events[0].x[0]), "{what}: {r}");
            let mut exact = exact;
            exact[1].1 = found[1].x();
            check_extremes(what, found, &exact, &base.outputs[0].extremes, k, true);
        },
    );
}

/// `C` of the Grashof-equal four-bar at `phi` by construction, on the branch the sweep follows:
/// from the circles `(B, b)` and `(D, c)`, left of `B -> D` before the crossing (the fixture's
/// guess) and right after it (its smooth continuation changes mode there). Its coupler and
/// rocker angles and `x`, at size 1.
fn grashof_equal_state(phi: f64) -> [f64; 3] {
    let [a, b, c, d] = GRASHOF_EQUAL;
    let (bx, by) = (a * phi.cos(), a * phi.sin());
    let side = if phi < PI { 1.0 } else { -1.0 };
    let (cx, cy) = circle_point(bx, by, b, d, 0.0, c, side);
    [(cy - by).atan2(cx - bx), cy.atan2(cx - d), cx]
}

/// The sampled analyses across the change point, over a sweep told to pass it: the extremes
/// and range of `pc.x` as the report has them, the dwells of every column as many as at size 1
/// (none: no column reverses against its travel), and the state at inputs beside the crossing
/// and away from it (the construction's, its positions to `tol::SOLVE / p`).
#[test]
fn sampled_analyses_across_a_change_point_at_every_scale() {
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let exact = grashof_equal_extremes();
    let columns = ["beta", "gamma", "pc.x", "pc.y"];
    for samples in [5, 10, 73, 360] {
        let one = four_bar(GRASHOF_EQUAL, 1.0);
        let base = Sampled::sweep_with(&one, 0.0, TO, samples, one.guess_flat(&[0.0]), cfg).unwrap();
        let base_extremes = base.extremes(FourBar::COL.pc.x).unwrap();
        for k in SCALES {
            let what = format!("size {k:e}, {samples} samples");
            let m = four_bar(GRASHOF_EQUAL, k);
            let run = Sampled::sweep_with(&m, 0.0, TO, samples, m.guess_flat(&[0.0]), cfg).unwrap();
            let found = run.extremes(FourBar::COL.pc.x).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!((found[1].x() - PI).abs() <= tol::LOCATED, "{what}: {found:?}");
            let mut exact = exact;
            exact[1].1 = found[1].x();
            check_extremes(&what, &found, &exact, &base_extremes, k, true);
            let range = run.range(FourBar::COL.pc.x).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!((range.min.x - PI).abs() <= tol::LOCATED, "{what}: {range:?}");
            assert!((range.min.value / k - exact[1].2).abs() <= tol::SOLVE, "{what}: {range:?}");
            assert!((range.max.value / k - exact[0].2).abs() <= tol::SOLVE, "{what}: {range:?}");
            for name in columns {
                let c = Column::<FourBar>::named(name).unwrap();
                let dwells = run.dwells(c).unwrap_or_else(|e| panic!("{what}, {name}: {e}"));
                assert_eq!(dwells.len(), base.dwells(c).unwrap().len(), "{what}, {name}: {dwells:?}");
            }
            for phi in [PI - 1e-3, PI - 1e-4, PI + 1e-5, PI + 1e-4, PI + 1e-3, 1.0, 5.0] {
                let s = run.at(phi).unwrap_or_else(|e| panic!("{what}, at {phi}: {e}"));
                let [beta, gamma, x] = grashof_equal_state(phi);
                let bound = tol::SOLVE / s.health.min_pivot;
                assert_eq!(s.x[0], phi, "{what}");
                assert!(wrap(s.q[0] - beta).abs() <= bound, "{what}, at {phi}: {s:?} against {beta}");
                assert!(wrap(s.q[1] - gamma).abs() <= bound, "{what}, at {phi}: {s:?} against {gamma}");
                assert!((s.out[0] / k - x).abs() <= tol::SOLVE * (1.0 + bound), "{what}, at {phi}: {s:?} against {x}");
            }
        }
    }
}

/// The gear-lever drive's rocker at size `k` (paper 001: carrier 2, pin 1.3 times `k`).
fn gear_lever(k: f64) -> GearLever {
    GearLever { l_c: 2.0 * k, l_p: 1.3 * k, u: 3.0 }
}

/// The rocker's angle and velocity analog by paper 001's explicit formulas at carrier angle
/// `alpha` (size 1; the angle wrapped as `atan2` gives it).
fn rocker(alpha: f64) -> (f64, f64) {
    let [phi, omega, ..] = gear_lever_explicit(2.0, 1.3, 3.0, alpha);
    (phi, omega)
}

/// The root of `f` nearest `x` within `0.05` (a tenth of the dwells' shortest span), by
/// bisection where `f` changes sign on a grid of spacing `1e-3` (offset by half a spacing from
/// `x`, which may be the root itself to the last bit).
fn root_near(f: impl Fn(f64) -> f64, x: f64) -> f64 {
    let grid: Vec<f64> = (-50..50).map(|i| x + 1e-3 * (f64::from(i) + 0.5)).collect();
    grid.windows(2)
        .filter(|w| (f(w[0]) < 0.0) != (f(w[1]) < 0.0))
        .map(|w| bisect(&f, w[0], w[1]))
        .min_by(|a, b| (a - x).abs().total_cmp(&(b - x).abs()))
        .unwrap_or_else(|| panic!("no root within 0.05 of {x}"))
}

/// The gear-lever drive's three stops over a carrier turn (the dwells of its rocker), at every
/// size and at 721 and 13 samples: the reversals' extremes at the roots of paper 001's explicit
/// velocity analog, the dwells' ends where the explicit angle reaches the opposite extreme's
/// value (entering the band before the first, leaving it after the second), all at the same
/// carrier angles as at size 1; the swing an angle, the same at every size.
#[test]
fn a_gear_levers_dwells_at_every_scale() {
    let from = -PI / 3.0;
    for samples in [13, 721] {
        let one = gear_lever(1.0);
        let base =
            one.sampled(from, from + TAU, samples, &one.guess(from)).unwrap().dwells(GearLever::COL.phi).unwrap();
        assert_eq!(base.len(), 3, "{base:?}");
        for k in SCALES {
            let what = format!("size {k:e}, {samples} samples");
            let m = gear_lever(k);
            let turn = m.sampled(from, from + TAU, samples, &m.guess(from)).unwrap_or_else(|e| panic!("{what}: {e}"));
            let dwells = turn.dwells(GearLever::COL.phi).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_eq!(dwells.len(), 3, "{what}: {dwells:?}");
            for (dw, b) in dwells.iter().zip(&base) {
                let (x1, x2) = (root_near(|a| rocker(a).1, dw.first.x()), root_near(|a| rocker(a).1, dw.second.x()));
                let (v1, v2) = (rocker(x1).0, rocker(x2).0);
                let x_in = root_near(|a| wrap(rocker(a).0 - v2), dw.start.x);
                let x_out = root_near(|a| wrap(rocker(a).0 - v1), dw.end.x);
                for (got, exact, one) in [
                    (dw.first.x(), x1, b.first.x()),
                    (dw.second.x(), x2, b.second.x()),
                    (dw.start.x, x_in, b.start.x),
                    (dw.end.x, x_out, b.end.x),
                ] {
                    assert!((got - exact).abs() <= EXTREME_TOL, "{what}: {dw:?} at {got} against {exact}");
                    assert!((got - one).abs() <= EXTREME_TOL, "{what}: {dw:?} at {got} against {one} at size 1");
                }
                assert_eq!((dw.first.kind, dw.second.kind), (b.first.kind, b.second.kind), "{what}: {dw:?}");
                assert!((dw.swing() - wrap(v1 - v2).abs()).abs() <= tol::SOLVE, "{what}: {dw:?}");
                assert!((dw.swing() - b.swing()).abs() <= tol::SOLVE, "{what}: {dw:?} against {b:?}");
            }
        }
    }
}

kinloop::mechanism! {
    /// The offset slider-crank with its crank's pivot at `(ax, 0)`: the same motion wherever it
    /// stands, its slider's position moved by `ax`.
    pub struct PlacedSliderCrank {
        params ax, r, l, e;
        input phi;
        unknowns psi = 0, x = ax - l;
        loop oabo: (ax, 0) + r @ phi == (x, e) + l @ psi;
    }
}

/// A slider-crank a millimetre across (crank 1 mm, rod 3 mm, offset 0.5 mm, in metres) wherever
/// it stands, up to the Earth's radius (6.4e6 m, a mechanism in Earth-centred coordinates) and
/// 1e9 m from the origin: the slider's dead centres are located at the closed form's crank
/// angles (`x - ax` is `-sqrt((l -+ r)^2 - e^2)` where crank and rod are collinear), and the
/// slider never rests. A column was judged to stand still where its values stayed within
/// `PERIODIC_TOLERANCE` (1e-9) of their magnitude, 6.4e-3 m here, more than the stroke of 2 mm:
/// the slider had no extremes, its range was the samples' (its minimum 0.036 rad off), and the
/// whole turn was one rest. Its velocity analog, which no offset enlarges, says it moves.
///
/// Tolerances: the dead centres are roots of the analog, located to about the solve's accuracy
/// over the acceleration analog (`EXTREME_TOL`); their values within a few roundings of the
/// position (`8 ulp(ax)`, 7.5e-9 m at the Earth's radius) and the solve's `tol::SOLVE` of the size.
#[test]
fn a_small_slider_crank_far_from_the_origin_has_its_dead_centres() {
    let (r, l, e): (f64, f64, f64) = (1e-3, 3e-3, 5e-4);
    let near = -((l - r) * (l - r) - e * e).sqrt();
    let far = -((l + r) * (l + r) - e * e).sqrt();
    let exact = [(Extreme::Min, e.atan2(far), far), (Extreme::Max, (-e).atan2(-near) + TAU, near)];
    for ax in [0.0, 1.0, 6.4e6, 1e9] {
        let m = PlacedSliderCrank { ax, r, l, e };
        let turn = m.sampled(0.1, 0.1 + TAU, 73, &m.guess(0.1)).unwrap();
        let found = turn.extremes(PlacedSliderCrank::COL.x).unwrap();
        assert_eq!(found.len(), 2, "at {ax:e}: {found:?}");
        let tol = 8.0 * f64::EPSILON * ax + tol::SOLVE * l;
        for (got, &(kind, x, value)) in found.iter().zip(&exact) {
            assert_eq!(got.kind, kind, "at {ax:e}: {got:?}");
            assert!((got.x() - x).abs() <= EXTREME_TOL, "at {ax:e}: {got:?} against {x}");
            assert!((got.value() - (ax + value)).abs() <= tol, "at {ax:e}: {got:?} against {}", ax + value);
        }
        // The range is the extremes' (at 1e9 a sample 0.004 rad from the maximum ties with it to
        // a unit in the last place, 1.2e-7 m, more than the curvature's 5e-9 m between them).
        let range = turn.range(PlacedSliderCrank::COL.x).unwrap();
        assert_eq!(range.extremes, found, "at {ax:e}");
        assert!((range.min.value - found[0].value()).abs() <= tol, "at {ax:e}: {range:?}");
        assert!((range.max.value - found[1].value()).abs() <= tol, "at {ax:e}: {range:?}");
        assert!(turn.rests(PlacedSliderCrank::COL.x).unwrap().is_empty(), "at {ax:e}");
    }
}
