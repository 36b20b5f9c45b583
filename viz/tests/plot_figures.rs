//! Figures parsed back from their SVG: tick labels and axis titles with units, curves placed
//! where the labelled ticks say (positions read from the drawn tick labels, not from the
//! library's mapping), legends that cover no data, smooth (fractional) coordinates, errors for
//! mixed quantity kinds.

use kinloop_viz::plot::{
    Axis, Kind, Panel, PlotError, Series, bar_chart_svg, line_chart_svg, panels_svg, xy_chart_svg,
};
use std::f64::consts::TAU;

mod figure_check;

/// What a test reads from a figure: per panel, its plot area, tick labels with their pixel
/// positions, axis titles, legend boxes, curves (as pixel points) and marks.
#[derive(Default, Debug)]
struct Parsed {
    areas: Vec<[f64; 4]>,
    x_ticks: Vec<Vec<(String, f64)>>,
    y_ticks: Vec<Vec<(String, f64)>>,
    titles: Vec<String>,
    legends: Vec<[f64; 4]>,
    curves: Vec<Vec<Vec<(f64, f64)>>>,
    marks: Vec<(f64, f64)>,
}

fn attr(n: roxmltree::Node, name: &str) -> f64 {
    n.attribute(name).unwrap_or_else(|| panic!("missing {name}")).parse().unwrap()
}

/// Subpaths of an SVG path made of `M x,y` and `L x,y` commands.
fn subpaths(d: &str) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    for cmd in d.split_whitespace() {
        let (op, xy) = cmd.split_at(1);
        let (x, y) = xy.split_once(',').unwrap();
        let p = (x.parse().unwrap(), y.parse().unwrap());
        match op {
            "M" => out.push(vec![p]),
            "L" => out.last_mut().unwrap().push(p),
            _ => panic!("unexpected path command {cmd}"),
        }
    }
    out
}

/// Parses a figure, after the checks every figure passes (`figure_check::sound`).
fn parse(svg: &str) -> Parsed {
    figure_check::sound(svg);
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    let mut p = Parsed::default();
    for panel in doc.descendants().filter(|n| n.attribute("class") == Some("panel")) {
        let (mut xt, mut yt, mut curves) = (Vec::new(), Vec::new(), Vec::new());
        for n in panel.descendants().filter(|n| n.is_element()) {
            let text = || n.text().unwrap_or("").to_string();
            match n.attribute("class").unwrap_or("") {
                "plot-area" => p.areas.push([attr(n, "x"), attr(n, "y"), attr(n, "width"), attr(n, "height")]),
                "tick-label x" => xt.push((text(), attr(n, "x"))),
                // The label's baseline sits 4 px below its tick.
                "tick-label y" => yt.push((text(), attr(n, "y") - 4.0)),
                "axis-title x" | "axis-title y" => p.titles.push(text()),
                "legend-box" => p.legends.push([attr(n, "x"), attr(n, "y"), attr(n, "width"), attr(n, "height")]),
                "curve" => curves.extend(subpaths(n.attribute("d").unwrap())),
                "mark" => p.marks.push((attr(n, "cx"), attr(n, "cy"))),
                _ => {}
            }
        }
        p.x_ticks.push(xt);
        p.y_ticks.push(yt);
        p.curves.push(curves);
    }
    p
}

/// The linear map from shown values to pixels defined by the first and last labelled ticks.
fn axis_map(ticks: &[(String, f64)]) -> impl Fn(f64) -> f64 {
    let (a, b) = (&ticks[0], &ticks[ticks.len() - 1]);
    let (va, vb): (f64, f64) = (a.0.parse().unwrap(), b.0.parse().unwrap());
    let (pa, pb) = (a.1, b.1);
    move |v| pa + (v - va) / (vb - va) * (pb - pa)
}

fn labels(ticks: &[(String, f64)]) -> Vec<&str> {
    ticks.iter().map(|t| t.0.as_str()).collect()
}

fn inside(r: &[f64; 4], (x, y): (f64, f64)) -> bool {
    x >= r[0] && x <= r[0] + r[2] && y >= r[1] && y <= r[1] + r[3]
}

fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3]
}

/// An offset slider-crank in millimetres over one turn in closed form: the slider position,
/// its velocity analog, and the rod angle.
fn slider_crank() -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let (r, l, e) = (40.0, 120.0, 10.0);
    let phi: Vec<f64> = (0..=360).map(|i| i as f64 * TAU / 360.0).collect();
    let psi: Vec<f64> = phi.iter().map(|p| ((e - r * p.sin()) / l).asin()).collect();
    let x: Vec<f64> = phi.iter().zip(&psi).map(|(p, s)| r * p.cos() + l * s.cos()).collect();
    let dx: Vec<f64> = phi.iter().zip(&psi).map(|(p, s)| -r * p.sin() - r * p.cos() * s.tan()).collect();
    (phi, x, dx, psi)
}

fn mm() -> Kind {
    Kind::length("mm")
}

#[test]
fn a_turn_is_ticked_in_degrees_and_every_axis_names_its_unit() {
    let (phi, x, dx, psi) = slider_crank();
    let svg = panels_svg(
        "Offset slider-crank",
        &Axis::angle("crank angle φ"),
        &[
            Panel::new(Axis::length("slider position x", "mm")).with(Series::columns("x", mm(), &phi, &x)),
            Panel::new(Axis::new("x'", Kind::LengthAnalog("mm".into()))).with(Series::columns(
                "dx/dφ",
                Kind::LengthAnalog("mm".into()),
                &phi,
                &dx,
            )),
            Panel::new(Axis::angle("rod angle ψ")).with(Series::columns("ψ", Kind::Angle, &phi, &psi)),
        ],
    )
    .unwrap();
    // Kept under the build directory to be looked at (rendered by any SVG viewer).
    let look = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("plot/slider_crank.svg");
    kinloop_viz::plot::save(&look, &svg).unwrap();
    let p = parse(&svg);
    assert_eq!(p.areas.len(), 3);
    for ticks in &p.x_ticks {
        assert_eq!(labels(ticks), ["0", "90", "180", "270", "360"]);
    }
    // Titles: one per value axis, and the shared x axis once (under the last panel).
    assert_eq!(p.titles, ["slider position x [mm]", "x' [mm/rad]", "rod angle ψ [°]", "crank angle φ [°]"]);
    // The rod angle swings asin((e ± r) / l): -14.5 .. 24.6 degrees, ticked in degree steps.
    let rod: Vec<f64> = p.y_ticks[2].iter().map(|t| t.0.parse().unwrap()).collect();
    let step = rod[1] - rod[0];
    assert!([5.0, 10.0, 15.0].contains(&step), "{rod:?}");
    assert!(rod[0] <= -14.4 && rod[rod.len() - 1] >= 24.6, "{rod:?}");
}

#[test]
fn curves_lie_where_the_labelled_ticks_put_them_with_fractional_coordinates() {
    let (phi, x, _, _) = slider_crank();
    let svg = line_chart_svg(
        "",
        &Axis::angle("crank angle φ"),
        &Axis::length("x", "mm"),
        &[Series::columns("x", mm(), &phi, &x)],
    )
    .unwrap();
    let p = parse(&svg);
    let (mx, my) = (axis_map(&p.x_ticks[0]), axis_map(&p.y_ticks[0]));
    let curve = &p.curves[0];
    assert_eq!(curve.len(), 1);
    // Every drawn point is a sample (thinning only drops points): find it by its x pixel and
    // compare with the sample's value through the tick labels' own scale. Coordinates carry
    // 1/100 pixel (rounding 0.005), the tick labels' positions the same.
    let nearest = |px: f64| {
        (0..phi.len())
            .min_by(|&a, &b| (mx(phi[a].to_degrees()) - px).abs().total_cmp(&(mx(phi[b].to_degrees()) - px).abs()))
            .unwrap()
    };
    for &(px, py) in &curve[0] {
        let i = nearest(px);
        assert!((mx(phi[i].to_degrees()) - px).abs() < 0.011, "x pixel {px}");
        assert!((my(x[i]) - py).abs() < 0.011, "y pixel {py} vs {}", my(x[i]));
    }
    let fractional = curve[0].iter().filter(|(x, y)| x.fract() != 0.0 || y.fract() != 0.0).count();
    assert!(fractional > curve[0].len() / 2, "curve snapped to whole pixels");
    assert!(curve[0].len() > 100, "a smooth turn keeps many points: {}", curve[0].len());
}

#[test]
fn no_legend_covers_data() {
    let (phi, x, _, _) = slider_crank();
    let shifted: Vec<f64> = x.iter().map(|v| v + 30.0).collect();
    let svg = line_chart_svg(
        "Two strokes",
        &Axis::angle("crank angle φ"),
        &Axis::length("x", "mm"),
        &[Series::columns("slider", mm(), &phi, &x), Series::columns("slider + 30 mm", mm(), &phi, &shifted)],
    )
    .unwrap();
    let circle: Vec<(f64, f64)> =
        (0..=200).map(|i| (i as f64 * TAU / 200.0).sin_cos()).map(|(s, c)| (40.0 * c, 40.0 * s)).collect();
    let crank = [Series::new("crank pin", mm(), circle)];
    let xy = xy_chart_svg("Path", &Axis::length("x", "mm"), &Axis::length("y", "mm"), &crank, &[(0.0, 0.0)]).unwrap();
    kinloop_viz::plot::save(&std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("plot/crank_pin.svg"), &xy)
        .unwrap();
    for p in [parse(&svg), parse(&xy)] {
        assert!(!p.legends.is_empty());
        for legend in &p.legends {
            assert!(p.areas.iter().all(|a| !overlap(a, legend)), "legend {legend:?} over a plot area");
            let mut points = p.curves.iter().flatten().flatten().chain(&p.marks);
            assert!(points.all(|&q| !inside(legend, q)), "legend covers data");
        }
    }
}

#[test]
fn an_xy_chart_draws_both_axes_to_one_scale() {
    // Ellipses of several widths: some windows end just short of a tick, which a chart of
    // curves would take to the tick, and an x-y chart must not (its scales stay equal).
    for a in (0..12).map(|k| 240.0 + 10.0 * k as f64) {
        let ellipse: Vec<(f64, f64)> =
            (0..=200).map(|i| (i as f64 * TAU / 200.0).sin_cos()).map(|(s, c)| (a * c, 0.8 * a * s)).collect();
        let series = [Series::new("e", mm(), ellipse)];
        let p = parse(&xy_chart_svg("", &Axis::length("x", "mm"), &Axis::length("y", "mm"), &series, &[]).unwrap());
        let (mx, my) = (axis_map(&p.x_ticks[0]), axis_map(&p.y_ticks[0]));
        let (px_per_mm_x, px_per_mm_y) = (mx(100.0) - mx(0.0), my(0.0) - my(100.0));
        // Tick positions are written to 1/100 pixel over about 700 pixels.
        assert!((px_per_mm_x - px_per_mm_y).abs() < 1e-4 * px_per_mm_x, "{a}: {px_per_mm_x} vs {px_per_mm_y}");
    }
}

#[test]
fn a_gap_in_a_sweep_breaks_the_curve() {
    let pts = vec![(0.0, 1.0), (0.5, 2.0), (1.0, f64::NAN), (1.5, 2.0), (2.0, 1.0)];
    let series = [Series::new("k", Kind::Dimensionless, pts)];
    let p = parse(&line_chart_svg("", &Axis::angle("φ"), &Axis::of(Kind::Dimensionless), &series).unwrap());
    assert_eq!(p.curves[0].len(), 2);
    assert_eq!(p.titles, ["ratio [-]", "φ [°]"]);
}

#[test]
fn mixing_quantity_kinds_on_one_axis_is_an_error() {
    let (phi, x, _, psi) = slider_crank();
    let series = vec![Series::columns("x", mm(), &phi, &x), Series::columns("ψ", Kind::Angle, &phi, &psi)];
    let err = line_chart_svg("", &Axis::angle("φ"), &Axis::length("x", "mm"), &series).unwrap_err();
    assert!(matches!(err, PlotError::MixedKinds { ref series, .. } if series == "ψ"), "{err}");
    assert!(err.to_string().contains("own panel"));
    // The remedy: one panel per kind.
    let panels = Panel::split_by_kind(series.clone());
    assert_eq!(panels.len(), 2);
    let p = parse(&panels_svg("", &Axis::angle("φ"), &panels).unwrap());
    assert_eq!(p.titles, ["length [mm]", "angle [°]", "φ [°]"]);
    // Lengths in two units are two kinds, and an x-y chart needs one kind on both axes.
    assert!(matches!(
        xy_chart_svg("", &Axis::length("x", "mm"), &Axis::length("y", "m"), &series[..1], &[]),
        Err(PlotError::UnequalAxes { .. })
    ));
    // Units written into an axis name (the old harmonics chart's "amplitude [N], [Nm]") are
    // refused: the title adds the one unit of the axis's kind.
    let amplitude = Axis::new("amplitude [N], [Nm]", Kind::force("N"));
    let err = line_chart_svg("", &Axis::angle("φ"), &amplitude, &[]).unwrap_err();
    assert!(matches!(err, PlotError::UnitInName { ref axis } if axis == "amplitude [N], [Nm]"), "{err}");
    assert!(matches!(
        xy_chart_svg("", &Axis::length("x [mm]", "mm"), &Axis::length("y", "mm"), &series[..1], &[]),
        Err(PlotError::UnitInName { .. })
    ));
    let nothing = [Series::new("nan", Kind::Angle, vec![(f64::NAN, 0.0)])];
    assert!(matches!(
        line_chart_svg("", &Axis::angle("φ"), &Axis::of(Kind::Angle), &nothing),
        Err(PlotError::Empty { .. })
    ));
}

/// The value of tick label `l` (`m` or `me<e>`) times `2^s`, computed without leaving the
/// f64 range (the label itself may lie beyond it, or among the subnormals). Zero is `"0"`
/// on any axis, and stays zero whatever `2^s`.
fn label_times_pow2(l: &str, s: i32) -> f64 {
    let (m, e) = l.split_once('e').map_or((l, 0), |(m, e)| (m, e.parse().unwrap()));
    let m = m.parse::<f64>().unwrap();
    if m == 0.0 { 0.0 } else { m * 10f64.powf(e as f64 + s as f64 * std::f64::consts::LOG10_2) }
}

/// Every attribute value and text of `svg` is free of `NaN` and `inf`.
fn all_finite(svg: &str) -> bool {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    doc.descendants().all(|n| {
        let bad = |s: &str| s.contains("NaN") || s.contains("inf");
        !n.attributes().any(|a| bad(a.value())) && !n.text().is_some_and(bad)
    })
}

#[test]
fn ranges_at_the_ends_of_the_f64_range_are_drawn_on_their_labelled_scales() {
    // y over almost all of f64 (its width overflows), x over a subnormal span: each point
    // lies where the tick labels say, read in units scaled by 2^s so that the labels'
    // values stay representable.
    let cases = [
        (vec![0.0, 1.0, 2.0], vec![-1e308, 3e307, 1e308], 0, -10),
        (vec![0.0, 4e-321, 1e-320], vec![1.0, 2.0, 3.0], 1070, 0),
        (vec![-f64::MAX, 0.0, f64::MAX], vec![f64::MIN_POSITIVE, 0.0, 5e-324], -10, 1074),
    ];
    for (xs, ys, sx, sy) in cases {
        let series = Series::columns("c", mm(), &xs, &ys);
        let svg = line_chart_svg("", &Axis::length("x", "mm"), &Axis::length("y", "mm"), &[series]).unwrap();
        assert!(all_finite(&svg), "{svg}");
        let p = parse(&svg);
        let scaled = |t: &[(String, f64)], s: i32| -> Vec<(String, f64)> {
            t.iter().map(|(l, px)| (label_times_pow2(l, s).to_string(), *px)).collect()
        };
        let (xt, yt) = (scaled(&p.x_ticks[0], sx), scaled(&p.y_ticks[0], sy));
        assert!(xt.len() >= 3 && yt.len() >= 3, "{:?} {:?}", labels(&p.x_ticks[0]), labels(&p.y_ticks[0]));
        let (fx, fy) = (axis_map(&xt), axis_map(&yt));
        let drawn = &p.curves[0][0];
        assert_eq!(drawn.len(), xs.len());
        for ((x, y), (px, py)) in xs.iter().zip(&ys).zip(drawn) {
            // Times 2^s in two exact halves (2^s alone can overflow).
            let times = |v: f64, s: i32| v * 2f64.powi(s / 2) * 2f64.powi(s - s / 2);
            let (ex, ey) = (fx(times(*x, sx)), fy(times(*y, sy)));
            assert!(
                (ex - px).abs() < 0.05 && (ey - py).abs() < 0.05,
                "({x:e}, {y:e}) at ({px}, {py}), labels say ({ex}, {ey})"
            );
        }
    }
    // Angles whose degrees overflow, and an x-y chart over the whole f64 plane.
    let svg = line_chart_svg(
        "",
        &Axis::angle("φ"),
        &Axis::angle("ψ"),
        &[Series::columns("c", Kind::Angle, &[-1e307, 1e307], &[f64::MAX, -f64::MAX])],
    )
    .unwrap();
    assert!(all_finite(&svg), "{svg}");
    let corners = vec![(-f64::MAX, -f64::MAX), (f64::MAX, f64::MAX)];
    let svg = xy_chart_svg(
        "",
        &Axis::length("x", "mm"),
        &Axis::length("y", "mm"),
        &[Series::new("c", mm(), corners)],
        &[(5e-324, 0.0)],
    )
    .unwrap();
    assert!(all_finite(&svg), "{svg}");
    let lone = xy_chart_svg("", &Axis::length("x", "mm"), &Axis::length("y", "mm"), &[], &[(1e-320, 0.0)]).unwrap();
    assert!(all_finite(&lone), "{lone}");
}

/// A chart's error goes through `?` into kinloop's one error type as `Error::Figure`, from which
/// it comes back typed.
#[test]
fn plot_errors_convert_into_kinloops_error() {
    fn chart_of_nothing() -> Result<String, kinloop_runtime::Error> {
        let nothing = [Series::new("nan", Kind::Angle, vec![(f64::NAN, 0.0)])];
        Ok(line_chart_svg("", &Axis::angle("φ"), &Axis::of(Kind::Angle), &nothing)?)
    }
    let e = chart_of_nothing().unwrap_err();
    let kinloop_runtime::Error::Figure(source) = &e else { panic!("{e:?}") };
    assert!(matches!(source.downcast_ref::<PlotError>(), Some(PlotError::Empty { .. })), "{e:?}");
}

/// Points whose spread on one axis is below the spacing of doubles at their position on the
/// other (a subnormal x spread beside a y of the smallest normal number) still draw on finite
/// pixels: the equal-scale window is never narrower than the doubles can resolve.
#[test]
fn an_xy_window_below_the_spacing_of_doubles_draws_finite() {
    let tiny = Series::new("a", Kind::length("mm"), vec![(0.0, f64::MIN_POSITIVE), (5e-324, f64::MIN_POSITIVE)]);
    let svg = xy_chart_svg("t", &Axis::length("x", "mm"), &Axis::length("y", "mm"), &[tiny], &[]).unwrap();
    assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
}

/// The bars of each panel: `(label, x centre, top, bottom)` in pixels.
fn bars(svg: &str) -> Vec<Vec<(String, f64, f64, f64)>> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.attribute("class") == Some("panel"))
        .map(|panel| {
            panel
                .descendants()
                .filter(|n| n.attribute("class") == Some("bar"))
                .map(|n| {
                    let (x, y, w, h) = (attr(n, "x"), attr(n, "y"), attr(n, "width"), attr(n, "height"));
                    (n.attribute("data-label").unwrap().to_string(), x + w / 2.0, y, y + h)
                })
                .collect()
        })
        .collect()
}

#[test]
fn harmonics_are_bars_from_zero_on_one_panel_per_unit() {
    // Amplitudes of a force's and a moment's harmonics, orders 1 to 8: two units, two panels.
    let force: Vec<(f64, f64)> = (1..=8).map(|n| (n as f64, 5800.0 / (n * n) as f64)).collect();
    let force_y: Vec<(f64, f64)> = (1..=8).map(|n| (n as f64, 2400.0 / n as f64)).collect();
    let moment: Vec<(f64, f64)> = (1..=8).map(|n| (n as f64, 12.0 + n as f64)).collect();
    let (newton, newton_metre) = (Kind::force("N"), Kind::torque("N m"));
    let svg = bar_chart_svg(
        "Harmonics",
        &Axis::new("order", Kind::Dimensionless),
        &[
            Panel::new(Axis::new("force amplitude", newton.clone()))
                .with(Series::new("Fx", newton.clone(), force.clone()))
                .with(Series::new("Fy", newton.clone(), force_y)),
            Panel::new(Axis::new("moment amplitude", newton_metre.clone())).with(Series::new(
                "M",
                newton_metre,
                moment.clone(),
            )),
        ],
    )
    .unwrap();
    let look = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("plot/harmonics.svg");
    kinloop_viz::plot::save(&look, &svg).unwrap();
    let p = parse(&svg);
    assert_eq!(p.titles, ["force amplitude [N]", "moment amplitude [N m]", "order [-]"]);
    // Every order ticked; both value axes start at 0 (no axis below zero for an amplitude).
    for ticks in &p.x_ticks {
        assert_eq!(labels(ticks), ["1", "2", "3", "4", "5", "6", "7", "8"]);
    }
    for ticks in &p.y_ticks {
        assert_eq!(ticks[0].0, "0", "{:?}", labels(ticks));
    }
    let b = bars(&svg);
    assert_eq!((b[0].len(), b[1].len()), (16, 8));
    // Each bar from the 0 tick to its amplitude on the labelled scale, centred on its order
    // (a group of two side by side: their middle on the order's tick).
    for (k, values) in [(0, &force), (1, &moment)] {
        let (y_of, x_of) = (axis_map(&p.y_ticks[k]), axis_map(&p.x_ticks[k]));
        let first: Vec<_> = b[k].iter().filter(|bar| bar.0 == if k == 0 { "Fx" } else { "M" }).collect();
        for (bar, &(order, amplitude)) in first.iter().zip(values.iter()) {
            assert!(
                (bar.3 - y_of(0.0)).abs() < 0.02 && (bar.2 - y_of(amplitude)).abs() < 0.02,
                "{bar:?} vs {amplitude}"
            );
            if k == 1 {
                assert!((bar.1 - x_of(order)).abs() < 0.02, "{bar:?} vs order {order}");
            }
        }
    }
    // Fx and Fy of one order straddle its tick.
    let x_of = axis_map(&p.x_ticks[0]);
    assert!((0.5 * (b[0][0].1 + b[0][8].1) - x_of(1.0)).abs() < 0.02);
    // A moment on the force panel is refused: an axis never mixes units.
    let mixed =
        Panel::new(Axis::new("amplitude", Kind::force("N"))).with(Series::new("M", Kind::torque("N m"), moment));
    assert!(matches!(bar_chart_svg("", &Axis::of(Kind::Dimensionless), &[mixed]), Err(PlotError::MixedKinds { .. })));
}

#[test]
fn a_sampled_turn_is_ticked_to_360_and_amplitudes_start_at_zero() {
    // 72 samples over [0, 2 pi): the last at 355 degrees; the axis still ends on 360.
    let phi: Vec<f64> = (0..72).map(|i| i as f64 * TAU / 72.0).collect();
    let amplitude: Vec<f64> = phi.iter().map(|p| 100.0 + 5700.0 * p.sin().powi(2)).collect();
    let speed: Vec<f64> = phi.iter().map(|p| 157.0 + 3.0 * p.cos()).collect();
    let svg = panels_svg(
        "",
        &Axis::angle("crank angle φ"),
        &[
            Panel::new(Axis::new("force amplitude", Kind::force("N"))).with(Series::columns(
                "|F|",
                Kind::force("N"),
                &phi,
                &amplitude,
            )),
            Panel::new(Axis::new("crank speed", Kind::AngularSpeed)).with(Series::columns(
                "ω",
                Kind::AngularSpeed,
                &phi,
                &speed,
            )),
        ],
    )
    .unwrap();
    let p = parse(&svg);
    assert_eq!(labels(&p.x_ticks[1]), ["0", "90", "180", "270", "360"]);
    // The amplitude's axis is not padded below zero: from 0 (its data are all positive).
    assert_eq!(p.y_ticks[0][0].0, "0", "{:?}", labels(&p.y_ticks[0]));
    assert!(p.y_ticks[0].iter().all(|t| !t.0.starts_with('-')));
    // The speed near 157 rad/s is not dragged down to 0: only the pad stops at zero.
    assert!(p.y_ticks[1][0].0.parse::<f64>().unwrap() >= 150.0, "{:?}", labels(&p.y_ticks[1]));
    assert_eq!(p.titles, ["force amplitude [N]", "crank speed [rad/s]", "crank angle φ [°]"]);
}

#[test]
fn dynamics_quantities_have_kinds_with_their_units() {
    let cases = [
        (Kind::torque("N m"), "torque [N m]"),
        (Kind::force("kN"), "force [kN]"),
        (Kind::speed("m/s"), "speed [m/s]"),
        (Kind::AngularSpeed, "angular speed [rad/s]"),
        (Kind::time("s"), "time [s]"),
        (Kind::energy("J"), "energy [J]"),
        (Kind::inertia("kg m²"), "moment of inertia [kg m²]"),
        (Kind::power("W"), "power [W]"),
    ];
    let t: Vec<f64> = (0..=10).map(|i| i as f64 * 0.1).collect();
    for (kind, title) in cases {
        let y: Vec<f64> = t.iter().map(|v| 2.0 * v).collect();
        let svg = line_chart_svg(
            "",
            &Axis::of(Kind::time("s")),
            &Axis::of(kind.clone()),
            &[Series::columns("y", kind, &t, &y)],
        )
        .unwrap();
        assert_eq!(parse(&svg).titles, [title, "time [s]"]);
    }
}

/// The height of a figure (its `<svg height>`).
fn figure_height(svg: &str) -> f64 {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    attr(doc.root_element(), "height")
}

/// Legends of many series (more than a plot area's height of entries) stay in the picture, and
/// the legends of stacked panels do not overlap: the figure grows to hold them.
#[test]
fn legends_of_many_series_stay_in_the_picture() {
    let flat =
        |k: usize, kind: Kind| Series::new(&format!("series {k}"), kind, vec![(0.0, k as f64), (1.0, k as f64 + 0.5)]);
    let many = |n: usize, kind: Kind| (0..n).map(|k| flat(k, kind.clone())).collect::<Vec<_>>();
    let x = Axis::new("x", mm());
    let n = Kind::force("N");
    let figures = [
        line_chart_svg("", &x, &Axis::new("y", mm()), &many(40, mm())).unwrap(),
        panels_svg(
            "Panels",
            &x,
            &[
                Panel { series: many(30, mm()), ..Panel::new(Axis::new("y", mm())) },
                Panel { series: many(3, n.clone()), ..Panel::new(Axis::new("f", n.clone())) },
                Panel { series: many(20, n.clone()), ..Panel::new(Axis::new("g", n.clone())) },
            ],
        )
        .unwrap(),
        xy_chart_svg("", &x, &Axis::new("y", mm()), &many(60, mm()), &[]).unwrap(),
        bar_chart_svg(
            "Bars",
            &Axis::new("order", Kind::Dimensionless),
            &[
                Panel { series: many(25, n.clone()), ..Panel::new(Axis::new("f", n.clone())) },
                Panel { series: many(2, n.clone()), ..Panel::new(Axis::new("g", n.clone())) },
            ],
        )
        .unwrap(),
    ];
    for svg in &figures {
        let p = parse(svg);
        let height = figure_height(svg);
        for l in &p.legends {
            assert!(l[1] >= 0.0 && l[1] + l[3] <= height, "legend {l:?} in a figure {height} high");
        }
        for (i, a) in p.legends.iter().enumerate() {
            for b in &p.legends[i + 1..] {
                assert!(!overlap(a, b), "legends {a:?} and {b:?} overlap");
            }
        }
        // Each panel's plot area keeps its place above the next panel's.
        for w in p.areas.windows(2) {
            assert!(w[0][1] + w[0][3] < w[1][1], "{:?}", p.areas);
        }
    }
}

/// More series than colours: each curve is told apart from every other by its colour and dash
/// (the colours repeat every seven series, the eighth drawn as the first was), and each legend
/// entry's swatch shows its curve's colour and dash.
#[test]
fn curves_beyond_the_colours_are_told_apart_by_their_dashes() {
    let series: Vec<Series> =
        (0..20).map(|k| Series::new(&format!("s{k}"), mm(), vec![(0.0, k as f64), (1.0, k as f64 + 0.5)])).collect();
    let x = Axis::new("x", mm());
    for svg in [
        line_chart_svg("", &x, &Axis::new("y", mm()), &series).unwrap(),
        xy_chart_svg("", &x, &Axis::new("y", mm()), &series, &[]).unwrap(),
    ] {
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let look = |n: &roxmltree::Node| {
            (n.attribute("stroke").unwrap().to_string(), n.attribute("stroke-dasharray").unwrap_or("").to_string())
        };
        let curves: Vec<_> =
            doc.descendants().filter(|n| n.attribute("class") == Some("curve")).map(|n| look(&n)).collect();
        let swatches: Vec<_> =
            doc.descendants().filter(|n| n.attribute("class") == Some("legend-line")).map(|n| look(&n)).collect();
        assert_eq!(curves.len(), 20);
        assert_eq!(curves, swatches);
        for (i, a) in curves.iter().enumerate() {
            assert!(!curves[i + 1..].contains(a), "curve {i} looks like a later one: {a:?}");
        }
        // The first seven are solid, as they were.
        assert!(curves[..7].iter().all(|(_, dash)| dash.is_empty()));
    }
}

/// Tick labels of many digits (a range of a few ulps at 1e6, labelled to its last digit) are
/// readable: x labels do not run into each other (some ticks go unlabelled instead), y labels
/// fit between the picture's left edge (with the rotated axis title) and the plot area. Widths
/// are estimated as the library estimates text: 0.6 em a character.
#[test]
fn long_tick_labels_neither_overlap_nor_leave_the_picture() {
    let narrow: Vec<(f64, f64)> = (0..10).map(|i| (1e6 + i as f64 * 1.2e-10, 1e6 + i as f64 * 2.4e-10)).collect();
    let x = Axis::new("x", mm());
    let figures = [
        line_chart_svg("", &x, &Axis::new("y", mm()), &[Series::new("a", mm(), narrow.clone())]).unwrap(),
        panels_svg(
            "",
            &x,
            &[Panel::new(Axis::new("y", mm())).with(Series::new("a", mm(), narrow.clone())), {
                let wide: Vec<(f64, f64)> = narrow.iter().map(|&(x, _)| (x, 1.0)).collect();
                Panel::new(Axis::new("z", mm())).with(Series::new("b", mm(), wide))
            }],
        )
        .unwrap(),
        xy_chart_svg("", &x, &Axis::new("y", mm()), &[Series::new("a", mm(), narrow.clone())], &[]).unwrap(),
    ];
    let width = |label: &str| 0.6 * 12.0 * label.chars().count() as f64;
    for svg in &figures {
        let p = parse(svg);
        let doc = roxmltree::Document::parse(svg).unwrap();
        for (k, xt) in p.x_ticks.iter().enumerate() {
            for w in xt.windows(2) {
                let (a, b) = (&w[0], &w[1]);
                assert!(
                    a.1 + 0.5 * width(&a.0) < b.1 - 0.5 * width(&b.0),
                    "panel {k}: x labels {a:?} and {b:?} overlap"
                );
            }
            assert!(k + 1 < p.x_ticks.len() || xt.len() >= 2, "{xt:?}");
        }
        for n in doc.descendants().filter(|n| n.attribute("class") == Some("tick-label y")) {
            let (label, right) = (n.text().unwrap(), attr(n, "x"));
            assert!(right - width(label) >= 30.0, "y label {label} from {} px", right - width(label));
        }
        // Every curve still in its plot area.
        for (area, curves) in p.areas.iter().zip(&p.curves) {
            assert!(curves.iter().flatten().all(|&pt| inside(area, pt)), "{area:?}");
        }
    }
}

/// A sample between gaps (the samples before and after it failed) is shown, and so is a run
/// of samples that all fall on one pixel: each was written as a path of no length (`M x,y`
/// alone, or to a point within half a pixel), which no renderer strokes, and the figure showed
/// no data where there was some. Checked on the rendered pixels, at every finite sample.
#[test]
fn a_lone_sample_between_gaps_is_drawn() {
    use resvg::{tiny_skia, usvg};
    let nan = f64::NAN;
    // Away from the plot area's frame, which a sample on it would be hidden under.
    let lone = vec![(1.0, 1.0), (2.0, nan), (3.0, 2.0), (4.0, nan), (5.0, 1.5), (5.0 + 1e-9, 1.5), (6.0, nan)];
    let solid = vec![(0.0, 0.0), (7.0, 3.0)];
    let (x, y) = (Axis::new("x", mm()), Axis::new("y", mm()));
    let series = [Series::new("lone", mm(), lone.clone()), Series::new("line", mm(), solid)];
    for svg in [line_chart_svg("", &x, &y, &series).unwrap(), xy_chart_svg("", &x, &y, &series, &[]).unwrap()] {
        // Where the samples are: the ends of the solid curve (the last one drawn) fix the map
        // from values to pixels.
        let line = parse(&svg).curves[0].last().unwrap().clone();
        let (a, b) = (line[0], line[line.len() - 1]);
        let px = |(vx, vy): (f64, f64)| (a.0 + (b.0 - a.0) * vx / 7.0, a.1 + (b.1 - a.1) * vy / 3.0);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let curve = doc.descendants().find(|n| n.attribute("data-label") == Some("lone")).unwrap();
        let stroke = curve.attribute("stroke").unwrap();
        let hex = |k: usize| u8::from_str_radix(&stroke[1 + 2 * k..3 + 2 * k], 16).unwrap();
        let want = [hex(0), hex(1), hex(2)];
        let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).unwrap();
        let size = tree.size().to_int_size();
        let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height()).unwrap();
        resvg::render(&tree, tiny_skia::Transform::identity(), &mut pixmap.as_mut());
        for s in lone.iter().filter(|s| s.1.is_finite()) {
            // The pixel under the sample has the curve's colour (within anti-aliasing), not the
            // white paper or a grey grid line.
            let (i, j) = px(*s);
            let c = pixmap.pixel(i as u32, j as u32).unwrap();
            let at = [c.red(), c.green(), c.blue()];
            assert!(at.iter().zip(&want).all(|(a, b)| a.abs_diff(*b) <= 40), "sample {s:?}: {at:?}, curve {want:?}");
        }
    }
}
