//! `Sampled` along a straight path through the input space of a two-input mechanism (the
//! five-bar): the jets along the path against central finite differences of positions solved
//! independently (circle intersection) at nearby points of the path, extremes located on the
//! path against a dense scan of the same construction, and the path parameter's two choices
//! (fraction of the path, one input).

use crate::support::{five_bar_joint, richardson, tol};
use kinloop::Error;
use kinloop::analysis::{Column, Jet, Sampled};
use kinloop_fixtures::FiveBar;

const M: FiveBar = FiveBar { a: 1.0, b: 2.5, c: 2.2, d: 1.5, e: 1.2 };
const FROM: [f64; 2] = [0.4, 1.6];
const TO: [f64; 2] = [2.6, 0.5];

/// The inputs at fraction `s` of the path.
fn inputs(s: f64) -> [f64; 2] {
    [FROM[0] + s * (TO[0] - FROM[0]), FROM[1] + s * (TO[1] - FROM[1])]
}

/// Columns of the five-bar at inputs `x` by construction: C on the left of B -> D, the link
/// angles from it. Returns `[phi2, phi3, pc.x, pc.y, spread, th2]`.
fn construction(x: [f64; 2]) -> [f64; 6] {
    let (cx, cy, p2, p3) = five_bar_joint(&M, x[0], x[1], 1.0);
    [p2, p3, cx, cy, p3 - p2, x[1]]
}

fn columns() -> [Column<FiveBar>; 6] {
    let c = FiveBar::COL;
    [c.phi2, c.phi3, c.pc.x, c.pc.y, c.spread, c.th2]
}

fn path() -> Sampled<'static, FiveBar, 2, 3, 2> {
    Sampled::path(&M, FROM, TO, 41, M.guess(FROM)).unwrap()
}

/// Lengths scale with the links, angles are of order one: one scale for the tolerances.
const SCALE: f64 = 2.5;

#[test]
fn jets_along_the_path_match_finite_differences_of_the_construction() {
    let run = path();
    // Samples and points between them, as fractions of the path.
    for s in [0.05, 0.2, 0.3125, 0.5, 0.61, 0.8, 0.95] {
        for (k, c) in columns().into_iter().enumerate() {
            let jet = run.jet_at(c, s).unwrap();
            let f = |s: f64| construction(inputs(s))[k];
            // h = 1e-3 of the path: Richardson's truncation ~h^4, the values' rounding 1e-16/h for the
            // slope, 1e-16/h^2 amplified by the extrapolation for the curvature (measured 2e-10, 8e-9).
            let (d1, d2) = richardson(f, s, 1e-3);
            assert_close!(jet.value, f(s), tol::SOLVE * SCALE, "{c} at {s}: {} vs {}", jet.value, f(s));
            assert_close!(jet.d1, d1, tol::FD_FIRST * SCALE, "{c}' at {s}: {} vs {d1}", jet.d1);
            assert_close!(jet.d2, d2, 1e-7 * SCALE, "{c}'' at {s}: {} vs {d2}", jet.d2);
        }
    }
    // The input th2 moves linearly along the path: its jet is exact.
    let j = run.jet_at(FiveBar::COL.th2, 0.3).unwrap();
    assert_eq!((j.d1, j.d2), (TO[1] - FROM[1], 0.0));
}

#[test]
fn an_input_as_the_parameter_rescales_the_derivatives() {
    let by_fraction = path();
    let by_th1 = path().along(FiveBar::COL.th1).unwrap();
    let run = TO[0] - FROM[0];
    assert_eq!(by_th1.path_values()[0], FROM[0]);
    assert_eq!(by_th1.path_values()[40], TO[0]);
    assert_eq!(by_th1.direction()[0], 1.0);
    for (a, b) in by_fraction.jets(FiveBar::COL.pc.y).unwrap().iter().zip(by_th1.jets(FiveBar::COL.pc.y).unwrap()) {
        assert_eq!(a.value, b.value);
        assert_close!(b.x, FROM[0] + a.x * run, 1e-15 * TO[0]);
        assert_close!(b.d1 * run, a.d1, 1e-13 * SCALE);
        assert_close!(b.d2 * run * run, a.d2, tol::SOLVE * SCALE);
    }
    // States between samples are the same point of the path whatever the parameter.
    let (s, x) = (0.37, FROM[0] + 0.37 * run);
    let (a, b) = (by_fraction.at(s).unwrap(), by_th1.at(x).unwrap());
    assert_close!(a.q[0], b.q[0], tol::SOLVE);
    assert_close!(a.x[1], b.x[1], tol::ULPS);
}

#[test]
fn extremes_on_the_path_match_a_dense_scan_of_the_construction() {
    let run = path();
    for (k, c) in columns().into_iter().enumerate().take(5) {
        let range = run.range(c).unwrap();
        // A dense scan of the construction (independent of the solver).
        let f = |s: f64| construction(inputs(s))[k];
        let n = 20_000;
        let (mut lo, mut hi) = ((0.0, f(0.0)), (0.0, f(0.0)));
        for i in 0..=n {
            let s = i as f64 / n as f64;
            let v = f(s);
            if v < lo.1 {
                lo = (s, v);
            }
            if v > hi.1 {
                hi = (s, v);
            }
        }
        // The scan's value is within (spacing^2 |f''| / 8) of the true extreme: ~1e-9.
        assert!((range.max.value - hi.1).abs() < 1e-8 * SCALE && range.max.value >= hi.1 - 1e-12, "{c} max");
        assert!((range.min.value - lo.1).abs() < 1e-8 * SCALE && range.min.value <= lo.1 + 1e-12, "{c} min");
        for e in run.extremes(c).unwrap() {
            // An interior extreme: the slope of the construction along the path vanishes there.
            let (d1, _) = richardson(f, e.x(), 1e-3);
            assert_close!(d1, 0.0, 1e-8 * SCALE, "{c} at {}: slope {d1}", e.x());
            assert_close!(e.value(), f(e.x()), tol::SOLVE * SCALE);
        }
    }
    assert!(!run.extremes(FiveBar::COL.pc.y).unwrap().is_empty(), "the path was chosen to pass a peak of pc.y");
}

#[test]
fn a_peak_of_a_jet_along_the_path() {
    let run = path();
    // Largest |d2(pc.x)/ds2| along the path, against a dense scan of the construction's second
    // derivative by finite differences (independent of the solver and of the jets).
    let (s, v) = run.peak_of(FiveBar::COL.pc.x, |j: Jet| j.d2.abs()).unwrap();
    let pc_x = |s: f64| construction(inputs(s))[2];
    // Richardson's curvature at h = 1e-3 of the path is good to about 1e-8 here (see the jets'
    // test); the scan's spacing of 1/2000 misses the peak by at most spacing^2 |f''''| / 8 of
    // |f''|'s own scale, far below that.
    let fd = 1e-7 * SCALE;
    let n = 2000;
    let (at, best) = (0..=n)
        .map(|i| {
            let s = i as f64 / n as f64;
            (s, richardson(pc_x, s, 1e-3).1.abs())
        })
        .fold((0.0, 0.0f64), |a, b| if b.1 > a.1 { b } else { a });
    assert!(v >= best - fd && v <= best * (1.0 + 1e-4) + fd, "{v} vs the construction's {best} at {at}");
    // The peak is where the construction's curvature is that large.
    assert!((0.0..=1.0).contains(&s));
    assert_close!(richardson(pc_x, s, 1e-3).1.abs(), v, fd, "at {s} (the scan's peak at {at})");
}

#[test]
fn invalid_paths_and_parameters_are_typed_errors() {
    let g = M.guess(FROM);
    assert!(matches!(Sampled::path(&M, FROM, FROM, 11, g), Err(Error::InvalidArgument(_))));
    assert!(matches!(Sampled::path(&M, FROM, TO, 2, g), Err(Error::InvalidArgument(_))));
    // th2 decreases along this path: it cannot be the parameter; an unknown never can.
    assert!(matches!(path().along(FiveBar::COL.th2), Err(Error::InvalidArgument(_))));
    assert!(matches!(path().along(FiveBar::COL.phi2), Err(Error::InvalidArgument(_))));
    assert!(matches!(path().at(1.5), Err(Error::InvalidArgument(_))));
    // The dynamic fallback finds the same handles, and names the columns when it cannot.
    assert_eq!(Column::<FiveBar>::named("pc.y").unwrap(), FiveBar::COL.pc.y);
    assert_eq!(Column::<FiveBar>::named("th1").unwrap(), FiveBar::COL.th1);
    let e = Column::<FiveBar>::named("pc.z").unwrap_err().to_string();
    assert!(e.contains("pc.x, pc.y, spread") && e.contains("th1, th2"), "{e}");
}

kinloop::mechanism! {
    /// Two sliders `u` and `v` (lengths) driving a point `(x, y)` with `y = (u^2 + v^2) / l`,
    /// written as `(u / l) u + (v / l) v` so that no length is squared: every term and analog
    /// along a path is of the order of the size in any unit of length (the second analog is
    /// `2 |d|^2 / l` for a path's direction `d`), and the mechanism can be scaled to any size.
    pub struct SliderSquares {
        params l;
        inputs u, v;
        unknowns x = 0, y = 0;
        loop p: (x, y) == (u, u / l * u + v / l * v);
    }
}

/// A path through two length inputs at every size from 1 to `1e-300`: from `(1, 2) k` to
/// `(3, -1) k`, where `u^2 + v^2 = (5 - 8 s + 13 s^2) k^2` has its minimum at the fraction
/// `s = 4/13` of the path, `y = 49/13 k` there. The path's parameter was the inputs' offset
/// dotted with the path's run over the run's square, which underflows below about `1e-154`:
/// at `1e-160` the fractions were off by 3e-4 of themselves (subnormal), at `1e-200` and below
/// NaN, and the analyses lost the minimum (an error, or none found over NaN samples). Each
/// sample's fraction is `j / 20` to rounding, and the minimum lies at `4/13` with `y = 49/13 k`
/// (the analog is linear in `s`, its root found to rounding; the value exact to rounding).
#[test]
fn a_path_through_tiny_length_inputs_keeps_its_parameter() {
    for k in [1.0, 1e-100, 1e-160, 1e-200, 1e-300] {
        let m = SliderSquares { l: k };
        let (from, to) = ([k, 2.0 * k], [3.0 * k, -k]);
        let run = Sampled::path(&m, from, to, 21, m.guess(from)).unwrap();
        for (j, s) in run.path_values().iter().enumerate() {
            assert!((s - j as f64 / 20.0).abs() <= 1e-15, "size {k:e}: sample {j} at {s}");
        }
        let found = run.extremes(SliderSquares::COL.y).unwrap();
        let [min] = found.as_slice() else { panic!("size {k:e}: {found:?}") };
        assert_eq!(min.kind, kinloop::analysis::Extreme::Min, "size {k:e}: {min:?}");
        assert!((min.x() - 4.0 / 13.0).abs() <= 1e-14, "size {k:e}: {min:?}");
        assert!((min.value() / k - 49.0 / 13.0).abs() <= 1e-14, "size {k:e}: {min:?}");
        let range = run.range(SliderSquares::COL.y).unwrap();
        assert_eq!(range.min, min.at, "size {k:e}");
    }
}
