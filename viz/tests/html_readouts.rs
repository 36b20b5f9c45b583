//! The interactive pages' readouts show about five significant digits at every scale: the
//! same four-bar at metre, millimetre and micrometre scale (in metres) and a billion times
//! larger reads short values (decimals for ordinary magnitudes, a power of ten such as
//! `"-5.661e-7"` for tiny or huge ones; angles to a hundredth of a degree), each within its
//! last digit of the closed form. The page holds every readout's text as Rust writes it (the
//! values of its data are those texts); with headless Chromium (see `tests/browser.rs`) the
//! page's script, which writes the readouts as the slider moves, is checked to write the very
//! same text at every frame, for these pages and for pages of awkward values (negative zero,
//! values rounding to zero, subnormals, the largest readouts, angles of many turns).

use kinloop_viz::draw::{Drawing, HtmlConfig, Motion, Pt, Readout, html};
use kinloop_viz::plot::Kind;
use std::f64::consts::TAU;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::{FourBar, four_bar_joints};

#[allow(dead_code)]
mod browser_support;

use browser_support::{chromium, probe_lines, resolution, run_chromium, url};

/// The default four-bar with every length times `scale`.
fn scaled(scale: f64) -> FourBar {
    let m = FourBar::default();
    FourBar { r: scale * m.r, l: scale * m.l, k: scale * m.k, d: scale * m.d, e: scale * m.e, delta: m.delta }
}

/// Poses of the sweep (a turn of the crank, every 5 degrees).
const POSES: usize = 73;

/// The crank's angle at frame `i`.
fn phi(i: usize) -> f64 {
    i as f64 * TAU / (POSES - 1) as f64
}

/// The page of `m` over a turn of the crank, with `config`.
fn page(m: &FourBar, config: &HtmlConfig) -> String {
    let motion = Motion::record(m, m.sweep(0.0, TAU, POSES, &m.guess(0.0)).unwrap()).unwrap();
    let drawing = Drawing::new()
        .pivot(Pt::fixed(0.0, 0.0))
        .pivot(Pt::fixed(m.d, 0.0))
        .link([Pt::fixed(0.0, 0.0), Pt::point("b"), Pt::point("c"), Pt::fixed(m.d, 0.0)])
        .trace("p");
    html(m, &drawing, &motion, config).unwrap()
}

/// The readouts' texts as the page's HTML holds them (written by Rust): each channel's label,
/// its text in the table (the first frame's) and its values in the page's data, verbatim.
fn rust_texts(page: &str) -> Vec<(String, String, Vec<String>)> {
    let table_at = page.find("<table class=\"kl-readouts\">").expect("readouts");
    let table_end = table_at + page[table_at..].find("</table>").expect("closed table") + "</table>".len();
    let table = roxmltree::Document::parse(&page[table_at..table_end]).expect("the readouts parse as XML");
    let rows: Vec<(String, String)> = table
        .descendants()
        .filter(|n| n.has_tag_name("tr"))
        .map(|tr| {
            let cell = |tag: &str| tr.children().find(|c| c.has_tag_name(tag)).and_then(|c| c.text()).unwrap_or("");
            (cell("th").to_string(), cell("td").to_string())
        })
        .collect();
    let data = page.split(r#""ch":["#).nth(1).expect("the channels' data");
    let values: Vec<Vec<String>> = data
        .split(r#""v":["#)
        .skip(1)
        .take(rows.len())
        .map(|r| r.split(']').next().unwrap().split(',').map(str::to_string).collect())
        .collect();
    assert_eq!(values.len(), rows.len(), "a channel per readout");
    rows.into_iter().zip(values).map(|((l, t), v)| (l, t, v)).collect()
}

/// `text` is a short readout: at most six significant digits (five, or six where a value
/// rounds up to the next power of ten), eleven characters with sign, point and power of ten,
/// never a negative zero, and a number.
fn assert_short(text: &str, what: &str) -> f64 {
    let (mantissa, _) = text.split_once('e').unwrap_or((text, ""));
    let digits = mantissa.trim_start_matches('-').replace('.', "");
    let significant = digits.trim_start_matches('0');
    assert!(significant.len() <= 6 && text.len() <= 11, "{what}: {text:?} is not short");
    let v: f64 = text.parse().unwrap_or_else(|_| panic!("{what}: {text:?} is no number"));
    assert!(v.is_finite(), "{what}: {text:?}");
    assert!(!(text.starts_with('-') && v == 0.0), "{what}: {text:?} is a negative zero");
    v
}

/// The scales checked: metre, millimetre and micrometre scale in metres, and a billion.
const SCALES: [f64; 4] = [1.0, 1e-3, 1e-6, 1e9];

#[test]
fn readouts_have_five_significant_digits_at_every_scale() {
    for scale in SCALES {
        let m = scaled(scale);
        let config = HtmlConfig::new("scaled").show("p.x").show("p.y").show("gamma").with_length_unit("m");
        let text = page(&m, &config);
        let channels = rust_texts(&text);
        let labels: Vec<&str> = channels.iter().map(|c| c.0.as_str()).collect();
        assert_eq!(labels, ["phi", "p.x", "p.y", "gamma"], "scale {scale}");
        for (label, first, values) in &channels {
            let what = format!("scale {scale}, {label}");
            assert_eq!(values.len(), POSES, "{what}");
            assert_eq!(first, &values[0], "{what}: the table shows the first frame's text");
            let largest = values.iter().map(|t| assert_short(t, &what).abs()).fold(0.0, f64::max);
            for (i, t) in values.iter().enumerate() {
                let [_, c, p] = four_bar_joints(&m, phi(i));
                let exact = match label.as_str() {
                    "phi" => phi(i).to_degrees(),
                    "p.x" => p[0],
                    "p.y" => p[1],
                    _ => c[1].atan2(c[0] - m.d).to_degrees(),
                };
                let shown: f64 = t.parse().unwrap();
                let res = resolution(t);
                // Within half the last digit (and the solver's and float's noise, far below).
                let angle = label == "phi" || label == "gamma";
                let noise = if angle { 1e-9 } else { 1e-10 * scale };
                assert!((shown - exact).abs() <= 0.5 * res + noise, "{what} frame {i}: {t} shows {exact}");
                if angle {
                    assert_eq!(res, 0.01, "{what}: {t}: angles to a hundredth of a degree");
                    assert!(!t.contains('e'), "{what}: {t}: degrees as decimals");
                } else if shown != 0.0 {
                    // Five significant digits of the channel's largest value, a power of
                    // ten outside the ordinary magnitudes.
                    assert!(res <= 1e-4 * largest * (1.0 + 1e-9) && res > 1e-5 * largest, "{what}: {t} ({largest})");
                    assert_eq!(t.contains('e') || t == "0", !(1e-4..1e5).contains(&largest), "{what}: {t} ({largest})");
                }
            }
        }
    }
}

/// Opens `page` at every frame in headless Chromium and asserts that the script writes each
/// readout exactly as the page's data (Rust) holds it; returns how many texts were compared.
fn js_writes_rusts_texts(bin: &std::path::Path, page: &str, name: &str) -> usize {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.html"));
    std::fs::write(&path, page).unwrap();
    let channels = rust_texts(page);
    let frames: Vec<String> = (0..POSES).map(|i| i.to_string()).collect();
    let dom = run_chromium(bin, &url(&path, &format!("probe={}", frames.join(","))), &["--dump-dom"]);
    let mut compared = 0;
    for line in probe_lines(&dom).iter().filter(|l| l.what == "value") {
        let ch: usize = line.get("ch").parse().unwrap();
        let rust = &channels[ch].2[line.frame];
        assert_eq!(
            line.get("text"),
            rust,
            "{name}: frame {} readout {}: JS and Rust differ",
            line.frame,
            channels[ch].0
        );
        compared += 1;
    }
    assert_eq!(compared, POSES * channels.len(), "{name}: every readout at every frame");
    compared
}

#[test]
fn the_script_writes_the_readouts_as_rust_does_in_the_browser() {
    let Some(bin) = chromium() else { return };
    for scale in SCALES {
        let m = scaled(scale);
        let config = HtmlConfig::new("scaled").show("p.x").show("p.y").show("gamma").with_length_unit("m");
        js_writes_rusts_texts(&bin, &page(&m, &config), &format!("readouts_scale_{scale:e}"));
    }
}

/// Awkward values, one per frame in turn (lengths, or angles in radians when `angle`).
fn awkward(values: &'static [f64], angle: bool) -> HtmlConfig {
    let pick = move |s: &kinloop_viz::draw::StateRef| {
        let i = (s.x[0] / TAU * (POSES - 1) as f64).round() as usize;
        values[i % values.len()]
    };
    let kind = if angle { Kind::Angle } else { Kind::length("m") };
    HtmlConfig::new("awkward").with_readout(Readout::expr("v", kind, pick).without_chart())
}

/// Sets of values a readout may meet: zeros of either sign and values rounding to zero among
/// ordinary ones, micrometres, a billion and more, subnormals, lengths of about 1e-300, the
/// largest readouts allowed, values rounding up to the next power of ten, angles of a fraction
/// of a hundredth of a degree and of many turns.
const AWKWARD: [(&[f64], bool); 10] = [
    (&[0.0, -0.0, -1e-9, 1e-9, 3.0, -2.99999, -0.00004, 2.5], false),
    (&[-0.0, -4e-6, 5.661e-7, -5.661e-7, 1e-12, -1e-15, 9.99996e-6, 0.0], false),
    (&[1589571631.0, -4e9, 0.4, -0.4, 123456789.0, -99999.5, 0.0], false),
    (&[5e-324, -1e-310, 0.0, -0.0, 2.2e-308], false),
    (&[2.725e-300, -1e-300, 0.0, 1.5e-304], false),
    (&[1e100, -3.3e99, 7.0, -0.0, 1e95], false),
    (&[99999.7, -0.01, 12.5, 0.0], false),
    (&[0.00012, -0.0000999, 3e-5, 0.0], false),
    (&[0.0, -1e-5, 1e-5, -0.0, 1.0, -3.0, TAU], true),
    (&[1e4, -2.5e4, 0.1, -0.0, -1e-6], true),
];

#[test]
fn awkward_values_read_the_same_in_rust_and_in_the_browser() {
    let m = FourBar::default();
    let pages: Vec<String> = AWKWARD.iter().map(|(v, angle)| page(&m, &awkward(v, *angle))).collect();
    for (k, (p, (values, angle))) in pages.iter().zip(AWKWARD).enumerate() {
        let channels = rust_texts(p);
        let (_, first, texts) = channels.last().unwrap();
        assert_eq!(first, &texts[0]);
        let shown_units = |v: f64| if angle { v.to_degrees() } else { v };
        let largest = values.iter().fold(0.0f64, |m, v| m.max(shown_units(*v).abs()));
        for (i, t) in texts.iter().enumerate() {
            let what = format!("set {k} frame {i}");
            let shown = assert_short(t, &what);
            let v = shown_units(values[i % values.len()]);
            // A bare "0" (with a power of ten for the others) is within five significant
            // digits of the largest value, or below 1e-300.
            let half = if t == "0" { (0.5e-4 * largest).max(1e-300) } else { 0.5 * resolution(t) };
            assert!((shown - v).abs() <= half * (1.0 + 1e-9), "{what}: {t} shows {v:e}");
        }
    }
    let Some(bin) = chromium() else { return };
    for (k, p) in pages.iter().enumerate() {
        js_writes_rusts_texts(&bin, p, &format!("readouts_awkward_{k}"));
    }
}

/// The charts of `page`, each parsed as XML.
fn charts(page: &str) -> Vec<String> {
    page.split("<svg")
        .filter(|s| s.contains(r#"class="kl-chart""#))
        .map(|s| format!("<svg{}", s.split("</svg>").next().unwrap()) + "</svg>")
        .collect()
}

/// Asserts that nothing of chart `svg` is drawn outside its plot area (gridlines, y ticks,
/// the curve and the cursor's dot), and that its y tick labels (about 0.6 em a character of
/// 11 px text, right-aligned) stay right of the y title's 19 px; returns the curve's points.
fn assert_inside(svg: &str, what: &str) -> Vec<[f64; 2]> {
    let doc = roxmltree::Document::parse(svg).expect("a chart parses as XML");
    let class = |c: &'static str| doc.descendants().filter(move |n| n.attribute("class") == Some(c));
    let f = |n: &roxmltree::Node, a: &str| n.attribute(a).unwrap().parse::<f64>().unwrap();
    let area = class("kl-plot-area").next().expect("a plot area");
    let (x0, y0) = (f(&area, "x"), f(&area, "y"));
    let (x1, y1) = (x0 + f(&area, "width"), y0 + f(&area, "height"));
    let inside = |x: f64, y: f64| x >= x0 - 0.05 && x <= x1 + 0.05 && y >= y0 - 0.05 && y <= y1 + 0.05;
    for g in class("kl-grid") {
        for (x, y) in [(f(&g, "x1"), f(&g, "y1")), (f(&g, "x2"), f(&g, "y2"))] {
            assert!(inside(x, y), "{what}: gridline at ({x}, {y}) outside the plot area");
        }
    }
    for t in class("kl-tick-y") {
        let label = t.text().unwrap();
        assert!(inside(x0, f(&t, "y") - 4.0), "{what}: tick {label} outside the plot area");
        let left = f(&t, "x") - 0.6 * 11.0 * label.chars().count() as f64;
        assert!(left >= 19.0, "{what}: tick label {label} reaches {left} px, over the y title");
    }
    let curve: Vec<[f64; 2]> = class("kl-curve")
        .next()
        .expect("a curve")
        .attribute("points")
        .unwrap()
        .split(' ')
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            [x.parse().unwrap(), y.parse().unwrap()]
        })
        .collect();
    for [x, y] in &curve {
        assert!(inside(*x, *y), "{what}: curve point ({x}, {y}) outside the plot area");
    }
    let dot = class("kl-cursor-dot").next().expect("a cursor");
    assert!(inside(f(&dot, "cx"), f(&dot, "cy")), "{what}: cursor outside the plot area");
    curve
}

/// Values that are constant up to rounding at frame `i`: `v` give or take a few ulps.
fn noisy(v: f64, i: usize) -> f64 {
    v + v.abs().max(f64::MIN_POSITIVE) * f64::EPSILON * [0.0, 3.0, -2.0, 5.0, -4.0][i % 5]
}

#[test]
fn a_column_constant_up_to_rounding_reads_and_charts_as_constant() {
    let frame = |s: &kinloop_viz::draw::StateRef| (s.x[0] / TAU * (POSES - 1) as f64).round() as usize;
    let config = HtmlConfig::new("constant")
        // A length through the loop, and an angle that is zero up to rounding (1e-14 degrees).
        .with_readout(Readout::expr("rod", Kind::length("mm"), move |s| noisy(2.5, frame(s))))
        .with_readout(Readout::expr("ang", Kind::Angle, move |s| [0.0, 1e-16, -1.1e-16, 2e-16][frame(s) % 4]))
        .with_readout(Readout::expr("deg", Kind::Angle, move |s| noisy(9.594f64.to_radians(), frame(s))))
        // Lengths of a nanometre that vary: drawn, at any scale.
        .with_readout(Readout::expr("tiny", Kind::length("mm"), move |s| 1e-9 * (1.0 + 0.1 * s.x[0].sin())))
        // Far from zero and varying by 4e-12 of themselves: drawn, labels that fit.
        .with_readout(Readout::expr("far", Kind::length("mm"), move |s| 1000.0 + 4e-9 * s.x[0].sin()));
    let p = page(&FourBar::default(), &config);
    let channels = rust_texts(&p);
    for (name, want) in [("rod", "2.5000"), ("ang", "0.00"), ("deg", "9.59")] {
        let (_, first, values) = channels.iter().find(|c| c.0 == name).unwrap();
        assert_eq!(first, want, "{name}");
        assert!(values.iter().all(|v| v == want), "{name}: {values:?}");
    }
    let charts = charts(&p);
    assert_eq!(charts.len(), 5);
    for (k, svg) in charts.iter().enumerate() {
        let curve = assert_inside(svg, &format!("chart {k}"));
        let ys: Vec<f64> = curve.iter().map(|p| p[1]).collect();
        let spread =
            ys.iter().fold(f64::NEG_INFINITY, |a, b| a.max(*b)) - ys.iter().fold(f64::INFINITY, |a, b| a.min(*b));
        if k < 3 {
            assert_eq!(spread, 0.0, "chart {k} of a constant: a flat line");
        } else {
            assert!(spread > 50.0, "chart {k} of values that vary: a curve ({spread} px)");
        }
    }
    // The far values' axis is labelled by differences from an offset above the plot area.
    let doc = roxmltree::Document::parse(&charts[4]).unwrap();
    let offset = doc.descendants().find(|n| n.attribute("class") == Some("kl-tick-offset")).expect("an offset");
    let offset: f64 = offset.text().unwrap().parse().unwrap();
    assert!((offset - 1000.0).abs() < 1e-8, "{offset}");
}

kinloop::mechanism! {
    /// A centred slider-crank with its pin `c` as a point and the pin's height over the rod as
    /// a ratio: both zero in exact arithmetic (the pin stays on the slider's line), rounding
    /// alone when computed.
    pub struct CentredPin {
        params r, l;
        input phi;
        unknowns psi = 0, x = -l;
        loop oabo: r @ phi == (x, 0) + l @ psi;
        point c = r @ phi - l @ psi;
        output h = (r * sin(phi) - l * sin(psi)) / l;
    }
}

/// A length or a pure number that is zero in exact arithmetic reads one zero (`0.0000`) at
/// every frame, at every scale: its rounding is judged against what it is computed from (the
/// mechanism's largest length, the size one of a pure number), as an angle's against a turn.
/// Judged against its own size, rounding, the pin's height read values such as `1.1102e-16`
/// that changed from frame to frame, charted as a curve.
#[test]
fn a_length_or_ratio_zero_up_to_rounding_reads_zero() {
    use kinloop_viz::draw::Draw;
    for scale in SCALES {
        let m = CentredPin { r: scale, l: 3.0 * scale };
        let motion = Motion::record(&m, m.sweep(0.1, 0.1 + TAU, POSES, &m.guess(0.1)).unwrap()).unwrap();
        let config = HtmlConfig::new("pin").show("c.y").show("h").show("c.x");
        let p = html(&m, &m.drawing().into_drawing(), &motion, &config).unwrap();
        for (label, _, values) in rust_texts(&p) {
            match label.as_str() {
                "c.y" | "h" => assert!(
                    values.iter().all(|v| v == &values[0] && v.parse::<f64>() == Ok(0.0)),
                    "scale {scale}, {label}: {values:?}"
                ),
                // The pin's x, the slider's position: it moves, and reads so.
                "c.x" => assert!(values.iter().any(|v| v != &values[0]), "scale {scale}: {values:?}"),
                _ => {}
            }
        }
    }
}

/// The units written after the length readouts of a page (`<td class="kl-unit">`), in order.
fn units(page: &str) -> Vec<&str> {
    page.split(r#"<td class="kl-unit">"#).skip(1).map(|r| r.split('<').next().unwrap()).collect()
}

/// A page's lengths are in the drawing's unit where the page's configuration names none: a
/// drawing given `mm` (its scale bar's unit) had its page's readouts and charts in "length
/// unit" unless the same unit was given to the page too. A unit the page's configuration
/// names is the page's, whatever the drawing's.
#[test]
fn a_page_takes_its_drawings_length_unit_unless_it_names_its_own() {
    let m = FourBar::default();
    let motion = Motion::record(&m, m.sweep(0.0, TAU, POSES, &m.guess(0.0)).unwrap()).unwrap();
    let drawing = Drawing::new().pivot(Pt::fixed(0.0, 0.0)).link([Pt::fixed(0.0, 0.0), Pt::point("b")]);
    let config = HtmlConfig::new("units").show("p.x").show("gamma");
    let in_mm = html(&m, &drawing.clone().length_unit("mm"), &motion, &config).unwrap();
    assert_eq!(units(&in_mm)[1..], ["mm", "°"], "{:?}", units(&in_mm));
    assert!(in_mm.contains("p.x [mm]"), "the chart's axis names the unit too");
    let own = html(&m, &drawing.clone().length_unit("mm"), &motion, &config.clone().with_length_unit("in")).unwrap();
    assert_eq!(units(&own)[1..], ["in", "°"]);
    let none = html(&m, &drawing, &motion, &config).unwrap();
    assert_eq!(units(&none)[1..], ["length unit", "°"]);
}
