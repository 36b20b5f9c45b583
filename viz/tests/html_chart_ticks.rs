//! The interactive pages' charts label their axes readably at every scale: the same four-bar
//! made a million times smaller or a billion times larger has charts whose tick labels are as
//! short as at unit scale (decimals down to steps of 1e-5, a power of ten below and above a
//! million, as the plot module labels its charts), and each label stands at its tick: the
//! curve's first point, read back through the labels, is the closed-form position.
//! The page's SVG is parsed as XML (no browser needed); with headless Chromium (see
//! `tests/browser.rs`) the pages are also opened at several poses, and the charts' cursors,
//! which the page's script places, are read on the same labels.

use kinloop_viz::draw::{Drawing, HtmlConfig, Motion, Pt, html};
use std::f64::consts::TAU;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::{FourBar, four_bar_joints};

#[allow(dead_code)]
mod browser_support;

use browser_support::{Expected, check_in_browser, chromium, svgs};

/// The default four-bar with every length times `scale`.
fn scaled(scale: f64) -> FourBar {
    let m = FourBar::default();
    FourBar { r: scale * m.r, l: scale * m.l, k: scale * m.k, d: scale * m.d, e: scale * m.e, delta: m.delta }
}

/// The page of the four-bar at `scale` over a turn of the crank, charting `p.x`, `p.y` (lengths
/// in metres) and the rocker's angle `gamma` (degrees) against the crank's angle.
fn page(m: &FourBar) -> String {
    let motion = Motion::record(m, m.sweep(0.0, TAU, 73, &m.guess(0.0)).unwrap()).unwrap();
    let drawing = Drawing::new()
        .pivot(Pt::fixed(0.0, 0.0))
        .pivot(Pt::fixed(m.d, 0.0))
        .link([Pt::fixed(0.0, 0.0), Pt::point("b"), Pt::point("c"), Pt::fixed(m.d, 0.0)])
        .trace("p");
    let config = HtmlConfig::new("scaled").show("p.x").show("p.y").show("gamma").with_length_unit("m");
    html(m, &drawing, &motion, &config).unwrap()
}

/// One axis of a chart: each tick label with its pixel (x for the x axis, the tick's y, 4 px
/// above the label's baseline, for the y axis).
fn axis(doc: &roxmltree::Document, class: &str) -> Vec<(String, f64)> {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some(class))
        .map(|n| {
            let label = n.text().expect("a label").to_string();
            let p = if class == "kl-tick-x" {
                n.attribute("x").unwrap().parse::<f64>().unwrap()
            } else {
                n.attribute("y").unwrap().parse::<f64>().unwrap() - 4.0
            };
            (label, p)
        })
        .collect()
}

/// Asserts the labels of one axis are short (at most three significant digits and five digits
/// in all, eight characters with sign and power of ten: `"-0.0005"`, `"0.25e-5"`) and read back to evenly spaced values at evenly
/// spaced pixels (every label at its own tick); returns `(value, pixel)` of each.
fn read_axis(ticks: &[(String, f64)], what: &str) -> Vec<(f64, f64)> {
    assert!(ticks.len() >= 3, "{what}: {ticks:?}");
    let mut out = Vec::new();
    for (label, p) in ticks {
        let (mantissa, _) = label.split_once('e').unwrap_or((label, ""));
        let digits = mantissa.trim_start_matches('-').replace('.', "");
        let significant = digits.trim_start_matches('0').trim_end_matches('0');
        assert!(
            significant.len() <= 3 && digits.len() <= 5 && label.len() <= 8,
            "{what}: label {label:?} is not short ({ticks:?})"
        );
        let v: f64 = label.parse().unwrap_or_else(|_| panic!("{what}: label {label:?} is no number"));
        assert!(v.is_finite(), "{what}: {label:?}");
        out.push((v, *p));
    }
    // Evenly spaced values at evenly spaced pixels: each label is the value of its tick.
    let (dv, dp) = (out[1].0 - out[0].0, out[1].1 - out[0].1);
    assert!(dv > 0.0 && dp != 0.0, "{what}: {ticks:?}");
    for w in out.windows(2) {
        assert!(((w[1].0 - w[0].0) - dv).abs() <= 1e-9 * dv, "{what}: uneven values {ticks:?}");
        assert!(((w[1].1 - w[0].1) - dp).abs() <= 0.15, "{what}: uneven pixels {ticks:?}");
    }
    out
}

/// The value at pixel `p` of an axis, through its first and last label.
fn value_at(t: &[(f64, f64)], p: f64) -> f64 {
    let ((v0, p0), (v1, p1)) = (t[0], t[t.len() - 1]);
    v0 + (p - p0) / (p1 - p0) * (v1 - v0)
}

/// The scales checked: metre, millimetre and micrometre scale in metres, and a billion.
const SCALES: [f64; 4] = [1.0, 1e-3, 1e-6, 1e9];

#[test]
fn chart_labels_are_short_and_at_their_ticks_at_every_scale() {
    for scale in SCALES {
        let m = scaled(scale);
        let text = page(&m);
        let [_, _, p] = four_bar_joints(&m, 0.0);
        let gamma = {
            let [_, c, _] = four_bar_joints(&m, 0.0);
            c[1].atan2(c[0] - m.d).to_degrees()
        };
        let charts: Vec<String> = svgs(&text).into_iter().filter(|s| s.contains("kl-chart")).collect();
        assert_eq!(charts.len(), 3, "scale {scale}: a chart per readout");
        for (chart, (name, first)) in charts.iter().zip([("p.x", p[0]), ("p.y", p[1]), ("gamma", gamma)]) {
            let doc = roxmltree::Document::parse(chart).unwrap();
            let what = format!("scale {scale}, chart {name}");
            let xs = read_axis(&axis(&doc, "kl-tick-x"), &format!("{what}, x"));
            let ys = read_axis(&axis(&doc, "kl-tick-y"), &format!("{what}, y"));
            // The crank's angle over a turn: every 90 degrees.
            assert_eq!(xs.iter().map(|t| t.0).collect::<Vec<_>>(), [0.0, 90.0, 180.0, 270.0, 360.0], "{what}");
            // The curve starts at the crank's angle 0: its point read back through the labels.
            let curve = doc.descendants().find(|n| n.attribute("class") == Some("kl-curve")).unwrap();
            let start: Vec<f64> = curve
                .attribute("points")
                .unwrap()
                .split(' ')
                .next()
                .unwrap()
                .split(',')
                .map(|v| v.parse().unwrap())
                .collect();
            let (x, y) = (value_at(&xs, start[0]), value_at(&ys, start[1]));
            // A tenth of a pixel, and the readouts' five significant digits.
            let per_px = |t: &[(f64, f64)]| ((t[t.len() - 1].0 - t[0].0) / (t[t.len() - 1].1 - t[0].1)).abs();
            assert!(x.abs() <= 0.1 * per_px(&xs), "{what}: x {x}");
            let tol = 0.1 * per_px(&ys) + 1e-4 * first.abs().max(4.0 * scale);
            assert!((y - first).abs() <= tol, "{what}: {y} read back, {first} expected");
        }
    }
}

/// In the browser: at every scale the joints, the readouts and the charts' cursors (placed by
/// the page's script) at several poses, the cursors read on the charts' own tick labels.
#[test]
fn chart_cursors_stand_at_their_labelled_values_in_the_browser() {
    let Some(bin) = chromium() else { return };
    for scale in SCALES {
        let m = scaled(scale);
        let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("four_bar_scale_{scale:e}.html"));
        std::fs::write(&path, page(&m)).unwrap();
        check_in_browser(&bin, &path, &format!("four_bar_scale_{scale:e}"), &[0, 20, 49, 72], |i| {
            let phi = i as f64 * TAU / 72.0;
            let [b, c, p] = four_bar_joints(&m, phi);
            Expected {
                chart_x: phi.to_degrees(),
                joints: vec![("-", [0.0, 0.0]), ("-", [m.d, 0.0]), ("b", b), ("c", c)],
                dots: vec![("p", p)],
                values: vec![
                    ("phi", phi.to_degrees()),
                    ("p.x", p[0]),
                    ("p.y", p[1]),
                    ("gamma", c[1].atan2(c[0] - m.d).to_degrees()),
                ],
            }
        });
    }
}

/// The y tick labels of every chart, at every scale, stand clear of the rotated y title (its
/// glyphs reach about 17 px from the chart's left edge) and inside the chart: a label of seven
/// or eight characters (`"-1.5e-6"`, `"-0.25e-5"`) ran over the title. Widths are estimated
/// at 0.6 em a character (11 px text).
#[test]
fn chart_y_labels_stand_clear_of_the_axis_title() {
    for scale in SCALES {
        let text = page(&scaled(scale));
        for chart in svgs(&text).into_iter().filter(|s| s.contains("kl-chart")) {
            let doc = roxmltree::Document::parse(&chart).unwrap();
            for n in doc.descendants().filter(|n| n.attribute("class") == Some("kl-tick-y")) {
                let label = n.text().unwrap();
                let right: f64 = n.attribute("x").unwrap().parse().unwrap();
                let left = right - 0.6 * 11.0 * label.chars().count() as f64;
                assert!(left >= 18.0, "scale {scale}: label {label:?} from {left} px");
            }
        }
    }
}
