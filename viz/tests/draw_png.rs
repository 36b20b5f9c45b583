//! PNG renders (feature `png`, on in these tests through the facade's dev-dependency): one
//! frame per key frame, at the zoomed size, each showing the joint on the zoomed closed-form
//! pixel; and text drawn where the SVG writes it.
#![cfg(feature = "png")]

use kinloop_viz::draw::{Animation, Annotate, Canvas, DrawError, Drawing, Motion, png};
use resvg::tiny_skia::Pixmap;
use std::f64::consts::TAU;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;
mod figure_check;

use draw_support::{FourBar, four_bar_joints, window_px};

#[test]
fn png_frames_show_the_joint_on_its_closed_form_pixel() {
    let m = FourBar::default();
    let mo = Motion::record(&m, m.sweep(0.0, TAU, 25, &m.guess(0.0)).unwrap()).unwrap();
    let window = [-2.0, -2.0, 6.0, 5.0];
    // Without annotations: the ink measured is the joint's alone.
    let canvas = Canvas { width: 200.0, window: Some(window), ..Canvas::default() };
    let d = Drawing::new().with_canvas(canvas).with_annotate(Annotate::none()).joint("p");
    let anim = Animation { frames: 7, ..Animation::default() };
    let zoom = 2.0;
    let frames = png::frames(&d, &mo, &anim, zoom).unwrap();
    let keys = d.key_poses(&mo, &anim).unwrap();
    assert_eq!(frames.len(), 7);
    for (bytes, &k) in frames.iter().zip(&keys) {
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        let img = Pixmap::decode_png(bytes).unwrap();
        assert_eq!((img.width(), img.height()), (400, 350));
        let (mut sx, mut sy, mut total) = (0.0, 0.0, 0.0);
        for (n, px) in img.pixels().iter().enumerate() {
            let ink = 255.0 - (px.red() as f64 + px.green() as f64 + px.blue() as f64) / 3.0;
            let (i, j) = (n % 400, n / 400);
            (sx, sy, total) = (sx + ink * (i as f64 + 0.5), sy + ink * (j as f64 + 0.5), total + ink);
        }
        let want = window_px(window, 200.0, four_bar_joints(&m, mo.poses[k].x[0])[2]).map(|v| v * zoom as f64);
        let got = [sx / total, sy / total];
        // 0.1 px rounding of the SVG, doubled by the zoom, and the centroid's few hundredths.
        assert!((got[0] - want[0]).hypot(got[1] - want[1]) < 0.5, "pose {k}: {got:?} vs {want:?}");
    }
    assert!(matches!(png::render("<svg", 1.0), Err(DrawError::Render(_))));
    assert!(matches!(png::render("", f32::NAN), Err(DrawError::InvalidSetting(_))));
}

/// Ink (darkness summed over the channels' mean) in the pixel box `[x0, x1) x [y0, y1)` of a
/// decoded PNG, at `zoom` pixels per SVG pixel.
fn ink_in(img: &Pixmap, zoom: f64, [x0, y0, x1, y1]: [f64; 4]) -> f64 {
    let w = img.width() as usize;
    let (i0, i1) = ((x0 * zoom).floor().max(0.0) as usize, ((x1 * zoom).ceil() as usize).min(w));
    let (j0, j1) = ((y0 * zoom).floor().max(0.0) as usize, ((y1 * zoom).ceil() as usize).min(img.height() as usize));
    let mut total = 0.0;
    for j in j0..j1 {
        for i in i0..i1 {
            let px = img.pixels()[j * w + i];
            total += 255.0 - (px.red() as f64 + px.green() as f64 + px.blue() as f64) / 3.0;
        }
    }
    total
}

/// The `(x, y)` of the first `<text>` of class `class` (or inside a group of that class).
fn text_at(svg: &str, class: &str) -> (f64, f64, &'static str, String) {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let node = doc
        .descendants()
        .find(|n| n.tag_name().name() == "text" && n.ancestors().any(|a| a.attribute("class") == Some(class)))
        .unwrap_or_else(|| panic!("no text of class {class}"));
    let num = |a: &str| node.attribute(a).unwrap().parse::<f64>().unwrap();
    let anchor = match node.ancestors().find_map(|n| n.attribute("text-anchor")) {
        Some("middle") => "middle",
        Some("end") => "end",
        _ => "start",
    };
    (num("x"), num("y"), anchor, node.text().unwrap_or_default().to_string())
}

/// Writes a render for a person to look at (under the build's target folder, never committed).
fn keep(name: &str, bytes: &[u8]) {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("png-text");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(name), bytes).unwrap();
}

#[test]
fn png_text_is_drawn_where_the_svg_puts_it() {
    // The readout and the scale bar's label of a drawing, the tick labels and axis title of a
    // chart: each box where the SVG writes text holds ink in the PNG, and the same box of the
    // picture without its text (the `<text>` elements removed from the SVG) holds none.
    let m = FourBar::default();
    let mo = Motion::record(&m, m.sweep(0.0, TAU, 25, &m.guess(0.0)).unwrap()).unwrap();
    let d = Drawing::new()
        .pivot([0.0, 0.0])
        .link([kinloop_viz::draw::Pt::fixed(0.0, 0.0), "b".into(), "c".into()])
        .length_unit("mm");
    let svg = d.svg(&mo, 3).unwrap();
    let chart = {
        use kinloop_viz::plot::{Axis, Kind, Series, line_chart_svg};
        let phi: Vec<f64> = (0..72).map(|i| i as f64 * TAU / 72.0).collect();
        let x: Vec<f64> = phi.iter().map(|p| 30.0 * p.cos()).collect();
        line_chart_svg(
            "",
            &Axis::angle("crank angle φ"),
            &Axis::length("x", "mm"),
            &[Series::columns("x", Kind::length("mm"), &phi, &x)],
        )
        .unwrap()
    };
    let zoom = 1.0;
    let without_text = |s: &str| {
        let doc = roxmltree::Document::parse(s).unwrap();
        let mut out = s.to_string();
        let mut ranges: Vec<_> =
            doc.descendants().filter(|n| n.tag_name().name() == "text").map(|n| n.range()).collect();
        ranges.reverse();
        for r in ranges {
            out.replace_range(r, "");
        }
        out
    };
    figure_check::sound(&svg);
    figure_check::sound(&chart);
    for (name, svg, boxes) in [
        ("drawing.png", &svg, vec![text_at(&svg, "readout"), text_at(&svg, "scale-bar")]),
        ("chart.png", &chart, vec![text_at(&chart, "tick-label x"), text_at(&chart, "axis-title x")]),
    ] {
        // Through the facade's feature `png`, which forwards this crate's.
        let png = kinloop::draw::png::render(svg, zoom as f32).unwrap();
        keep(name, &png);
        let with = Pixmap::decode_png(&png).unwrap();
        let bare = Pixmap::decode_png(&png::render(&without_text(svg), zoom as f32).unwrap()).unwrap();
        for (x, y, anchor, text) in boxes {
            // A line of 12-14 px text: from the baseline up a cap height, across a few glyphs
            // on the side of x its anchor says.
            let (x0, x1) = match anchor {
                "middle" => (x - 10.0, x + 10.0),
                "end" => (x - 21.0, x - 1.0),
                _ => (x + 1.0, x + 21.0),
            };
            let area = [x0, y - 9.0, x1, y + 1.0];
            let (a, b) = (ink_in(&with, zoom, area), ink_in(&bare, zoom, area));
            assert!(a > 255.0 * 10.0 && b < 1e-9, "{name}: `{text}` at ({x}, {y}): ink {a} with text, {b} without");
        }
    }
}

/// A render that would need more pixels than `png::MAX_PIXELS` is a typed error before any
/// pixel is allocated: a canvas a million pixels wide, or a chart zoomed ten thousand times,
/// asked for terabytes (and aborted the process when the allocation failed).
#[test]
fn renders_too_large_to_allocate_are_errors() {
    let m = FourBar::default();
    let mo = Motion::record(&m, m.sweep(0.0, TAU, 7, &m.guess(0.0)).unwrap()).unwrap();
    let wide = Drawing::new().with_canvas(Canvas { width: 1e6, ..Canvas::default() }).link(["b", "c", "p"]);
    let svg = wide.svg(&mo, 0).unwrap();
    let too_large = |r: Result<Vec<u8>, DrawError>| match r {
        Err(DrawError::InvalidSetting(s)) => assert!(s.contains("pixels"), "{s}"),
        other => panic!("{:?}", other.map(|b| b.len())),
    };
    too_large(png::render(&svg, 1.0));
    let small = Drawing::new().link(["b", "c", "p"]).svg(&mo, 0).unwrap();
    too_large(png::render(&small, 1e4));
    too_large(png::render(&small, f32::MAX));
    assert!(png::render(&small, 2.0).is_ok());
}
