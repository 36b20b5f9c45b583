//! Hostile inputs to plots and drawings: NaN, infinities, zeros, the ends of the f64 range,
//! empty and short vectors, poses of the wrong length, settings out of range. Every entry
//! returns a typed error or an SVG in which no attribute and no text holds `NaN` or `inf`; none
//! panics.

use kinloop_viz::draw::{Animation, Canvas, Drawing, Marked, Motion, Pose, Pt, Scalar};
use kinloop_viz::plot::{Axis, Kind, Panel, Series, line_chart_svg, panels_svg, xy_chart_svg};
use proptest::prelude::*;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;
mod figure_check;

use draw_support::FourBar;

/// A hostile number: NaN, infinities, zeros, the ends of the f64 range, or an ordinary one.
fn hostile() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(f64::MAX),
        Just(-f64::MAX),
        Just(f64::MIN_POSITIVE),
        Just(5e-324),
        Just(-1e-320),
        Just(1e300),
        Just(-1e300),
        Just(1e-300),
        -10.0..10.0f64,
        any::<f64>(),
    ]
}

/// A finite number, often at an end of the f64 range.
fn extreme() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![Just(f64::MAX), Just(-f64::MAX), Just(1e300), Just(-1e-320), Just(5e-324), -5.0..5.0f64]
}

/// Mostly an ordinary number, else a hostile one.
fn mostly(lo: f64, hi: f64) -> impl Strategy<Value = f64> + Clone {
    prop_oneof![6 => lo..hi, 1 => hostile()]
}

fn points(max: usize) -> impl Strategy<Value = Vec<(f64, f64)>> {
    proptest::collection::vec((hostile(), hostile()), 0..max)
}

/// `svg` is well-formed and none of its attribute values or texts holds `NaN` or `inf` (the
/// labels given by the tests hold neither).
fn assert_finite(svg: &str) {
    figure_check::sound(svg);
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("{e}: {svg}"));
    for n in doc.descendants() {
        let bad = |s: &str| s.contains("NaN") || s.contains("inf");
        for a in n.attributes() {
            assert!(!bad(a.value()), "{}=\"{}\" in {svg}", a.name(), a.value());
        }
        assert!(!n.text().is_some_and(bad), "text {:?} in {svg}", n.text());
    }
}

/// `n` values, `n` mostly `usual` (a pose of the right length, to be drawn), else any of
/// `0..max`.
fn values(usual: usize, max: usize, v: impl Strategy<Value = f64> + Clone) -> impl Strategy<Value = Vec<f64>> {
    prop_oneof![12 => Just(usual), 1 => 0..max].prop_flat_map(move |n| proptest::collection::vec(v.clone(), n))
}

fn kind(angle: bool) -> Kind {
    if angle { Kind::Angle } else { Kind::length("mm") }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn hostile_plots_are_errors_or_finite_svg(
        a in points(6),
        b in points(4),
        marks in points(3),
        angle in any::<bool>(),
        y_angle in any::<bool>(),
    ) {
        let (xk, yk) = (kind(angle), kind(y_angle));
        let (x, y) = (Axis::new("x", xk.clone()), Axis::new("y", yk.clone()));
        let series = [Series::new("a", yk.clone(), a.clone()), Series::new("b", yk.clone(), b.clone())];
        if let Ok(svg) = line_chart_svg("t", &x, &y, &series) {
            assert_finite(&svg);
        }
        let panels = [
            Panel::new(y.clone()).with(series[0].clone()).with_marks(marks.clone()),
            Panel::new(Axis::new("z", xk.clone())).with(Series::new("c", xk.clone(), b.clone())),
        ];
        if let Ok(svg) = panels_svg("", &x, &panels) {
            assert_finite(&svg);
        }
        let same = [Series::new("a", xk.clone(), a), Series::new("b", xk.clone(), b)];
        if let Ok(svg) = xy_chart_svg("t", &x, &Axis::new("y", xk), &same, &marks) {
            assert_finite(&svg);
        }
    }

    #[test]
    fn hostile_drawings_are_errors_or_finite_svg(
        poses in proptest::collection::vec(
            (values(1, 3, mostly(-5.0, 5.0)), values(2, 4, mostly(-5.0, 5.0)), values(6, 9, mostly(-5.0, 5.0))),
            0..5,
        ),
        event in proptest::option::of((values(1, 3, mostly(-5.0, 5.0)), values(6, 9, mostly(-5.0, 5.0)))),
        fixed in proptest::array::uniform4(extreme()),
        slider_angle in mostly(-4.0, 4.0),
        gear in (mostly(-5.0, 5.0), mostly(0.0, 2.0), mostly(-4.0, 4.0)),
        canvas in (mostly(10.0, 800.0), mostly(0.0, 30.0),
                   proptest::option::of((mostly(-6.0, 6.0), mostly(-6.0, 6.0), mostly(0.5, 12.0), mostly(0.5, 12.0)))),
        anim in (prop_oneof![8 => 2usize..6, 1 => 0usize..2], mostly(0.1, 10.0), any::<bool>()),
        pose in 0usize..6,
        count in 0usize..5,
    ) {
        let mut motion = Motion::empty::<FourBar, 2, 1, 6>();
        for (x, q, out) in poses {
            motion.push(Pose { x, q, out });
        }
        if let Some((x, out)) = event {
            let pose = Pose { x, q: vec![0.5, 1.5], out };
            motion.events.push(Marked { kind: kinloop::EventKind::LimitPosition, pose });
            motion.stopped = true;
        }
        let (width, margin, window) = canvas;
        let window = window.map(|(x0, y0, w, h)| [x0, y0, x0 + w, y0 + h]);
        let d = Drawing::new()
            .with_canvas(Canvas { width, margin, window })
            .pivot(Pt::fixed(fixed[0], fixed[1]))
            .joint(Pt::fixed(fixed[2], fixed[3]))
            .link(["b", "c", "p"])
            .body([Pt::point("b"), Pt::expr(|s| [s.x.first().copied().unwrap_or(0.0), 1.0]), Pt::fixed(0.0, 0.0)])
            .slider("c", slider_angle)
            .slider(Pt::point("c"), Scalar::expr(|s| s.q.first().copied().unwrap_or(f64::NAN)))
            .gear(Pt::fixed(gear.0, 0.0), gear.1, gear.2)
            .joint("p")
            .trace("p");
        let animation = Animation { frames: anim.0, seconds: anim.1, back_and_forth: anim.2 };
        if let Ok(svg) = d.svg(&motion, pose) {
            assert_finite(&svg);
        }
        if let Ok(svg) = d.animate(&motion, &animation) {
            assert_finite(&svg);
        }
        if let Ok(svg) = d.exposures(&motion, count) {
            assert_finite(&svg);
        }
        if let Ok(v) = d.view(&motion) {
            prop_assert!([v.scale, v.width, v.height].iter().all(|c| c.is_finite()), "{v:?}");
            prop_assert!(v.px([0.0, 0.0]).iter().all(|c| c.is_finite()), "{v:?}");
        }
        if let Ok(keys) = d.key_poses(&motion, &animation) {
            prop_assert!(keys.iter().all(|&k| k < motion.poses.len() + motion.events.len()));
        }
    }
}

/// Names, labels, units, notes and titles holding characters that XML forbids even as
/// entities (control characters other than tab, line feed and carriage return; U+FFFE and
/// U+FFFF) still give well-formed SVG: each such character is written as U+FFFD; markup
/// characters are entities; the rest of the text is kept.
#[test]
fn characters_xml_forbids_in_names_give_well_formed_svg() {
    let odd = "a\u{0}b\u{1}\u{8}\u{b}\u{c}\u{1f}\u{7f}\u{fffe}\u{ffff}<&>\"'\t\n]]>--</script>φ";
    let mm = Kind::length(odd);
    let (x, y) = (Axis::new(odd, mm.clone()), Axis::new("y", mm.clone()));
    let series = [Series::new(odd, mm.clone(), vec![(0.0, 1.0), (1.0, 2.0)])];
    let charts = [
        line_chart_svg(odd, &x, &y, &series).unwrap(),
        xy_chart_svg(odd, &x, &Axis::new(odd, mm.clone()), &series, &[]).unwrap(),
        kinloop_viz::plot::bar_chart_svg(odd, &x, &[Panel::new(y.clone()).with(series[0].clone())]).unwrap(),
    ];
    let m = FourBar::default();
    let motion = Motion::record(&m, m.sweep(0.0, std::f64::consts::TAU, 13, &m.guess(0.0)).unwrap()).unwrap();
    let d = Drawing::new().link(["b", "c"]).label("p", odd).note(odd).length_unit(odd).trace("p");
    let drawings = [
        d.svg(&motion, 0).unwrap(),
        d.animate(&motion, &Animation::default()).unwrap(),
        d.exposures(&motion, 3).unwrap(),
    ];
    for svg in charts.iter().chain(&drawings) {
        let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("{e}"));
        let text: String = doc.descendants().filter_map(|n| n.text()).collect();
        assert!(text.contains("a\u{fffd}b\u{fffd}"), "{text:?}");
        assert!(text.contains("<&>\"'") && text.contains("]]>--</script>φ"), "{text:?}");
    }
}

/// Bars at abscissae near the ends of the f64 range (their spacing, or the half spacing of
/// room around them, overflows), at subnormal ones, and at a lone one: finite SVG, every bar
/// as wide as the narrowest spacing allows and within the plot area, ticks that read back.
#[test]
fn bar_charts_at_extreme_abscissae_are_finite() {
    let n = Kind::force("N");
    let order = Axis::new("order", Kind::Dimensionless);
    for xs in [
        vec![-f64::MAX, f64::MAX],
        vec![f64::MAX],
        vec![-f64::MAX],
        vec![0.5 * f64::MAX, f64::MAX],
        vec![-1e308, 0.0, 1e308],
        vec![5e-324, 1e-323],
        vec![5e-324],
        vec![1e300],
        vec![-3.0, 7.5],
    ] {
        let points: Vec<(f64, f64)> = xs.iter().enumerate().map(|(k, &x)| (x, 1.0 + k as f64)).collect();
        let panel = Panel::new(Axis::new("f", n.clone())).with(Series::new("a", n.clone(), points));
        let svg = kinloop_viz::plot::bar_chart_svg("b", &order, &[panel]).unwrap();
        assert_finite(&svg);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let area = doc.descendants().find(|e| e.attribute("class") == Some("plot-area")).unwrap();
        let attr = |e: &roxmltree::Node, a: &str| e.attribute(a).unwrap().parse::<f64>().unwrap();
        let (left, right) = (attr(&area, "x"), attr(&area, "x") + attr(&area, "width"));
        let bars: Vec<_> = doc.descendants().filter(|e| e.attribute("class") == Some("bar")).collect();
        assert_eq!(bars.len(), xs.len(), "{xs:?}");
        for b in &bars {
            let (x, w) = (attr(b, "x"), attr(b, "width"));
            assert!(w > 1.0 && x >= left - 0.01 && x + w <= right + 0.01, "{xs:?}: bar {x} + {w} in {left}..{right}");
        }
    }
}
