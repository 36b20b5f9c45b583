//! Animated SVG: well-formed XML with the expected key frames, traced paths on the closed-form
//! coupler curve, events drawn at the closed-form limit position, and the same picture for a
//! mechanism in metres and in millimetres.

use kinloop::{AtSingular, EventKind, SweepConfig};
use kinloop_viz::draw::{Animation, Annotate, Canvas, Drawing, Motion, Pt, Scalar};
use std::f64::consts::{PI, TAU};

#[allow(dead_code)] // not every test uses every helper
mod draw_support;
mod figure_check;

/// Parses a drawing after the checks every figure passes (`figure_check::sound`).
fn checked(svg: &str) -> Result<roxmltree::Document<'_>, roxmltree::Error> {
    figure_check::sound(svg);
    roxmltree::Document::parse(svg)
}

use draw_support::{FourBar, FourBarUnknowns, four_bar_joints, window_px};

const WINDOW: [f64; 4] = [-2.0, -2.0, 6.0, 5.0];
const WIDTH: f64 = 400.0;

fn four_bar_drawing(m: &FourBar) -> Drawing {
    let (o, d) = ([0.0, 0.0], [m.d, 0.0]);
    Drawing::new()
        .pivot(o)
        .pivot(d)
        .link([Pt::from(o), Pt::point("b")])
        .body(["b", "c", "p"])
        .link([Pt::point("c"), Pt::from(d)])
        .trace("p")
}

fn motion(m: &FourBar, to: f64, samples: usize) -> Motion {
    Motion::record(m, m.sweep(0.0, to, samples, &m.guess(0.0)).unwrap()).unwrap()
}

/// Pairs of numbers `x,y x,y` or `x y;x y` as points.
fn pairs(s: &str, sep: char) -> Vec<[f64; 2]> {
    s.split(sep)
        .filter(|p| !p.is_empty())
        .map(|p| {
            let v: Vec<f64> = p.split([',', ' ']).map(|n| n.parse().expect("a number")).collect();
            [v[0], v[1]]
        })
        .collect()
}

#[test]
fn the_animation_is_well_formed_with_its_key_frames() {
    let m = FourBar::default();
    let mo = motion(&m, TAU, 361);
    let anim = Animation { frames: 90, seconds: 5.0, back_and_forth: false };
    let svg = four_bar_drawing(&m).animate(&mo, &anim).unwrap();
    let doc = checked(&svg).expect("well-formed XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(root.tag_name().namespace(), Some("http://www.w3.org/2000/svg"));
    assert!(!svg.contains("script") && !svg.contains("NaN"));
    // The moving parts (the readout's texts take turns: each is shown for its key frame).
    let animations: Vec<_> = doc
        .descendants()
        .filter(|n| matches!(n.tag_name().name(), "animate" | "animateTransform"))
        .filter(|n| n.attribute("attributeName") != Some("visibility"))
        .collect();
    // Moving: the crank, the body and the rocker (points), the joints B, C, P (twice: the
    // crank's end and the body's corner; the body's and the rocker's C), the trace's dot.
    assert!(animations.len() >= 8, "{} animated attributes", animations.len());
    for a in &animations {
        assert_eq!(a.attribute("values").unwrap().split(';').count(), 90, "{a:?}");
        assert_eq!(a.attribute("dur"), Some("5s"));
        assert_eq!(a.attribute("repeatCount"), Some("indefinite"));
    }
    // Forward and back: 2 k - 1 key frames.
    let both = four_bar_drawing(&m).animate(&mo, &Animation { back_and_forth: true, ..anim }).unwrap();
    let doc = checked(&both).unwrap();
    let a = doc.descendants().find(|n| n.tag_name().name() == "animate").unwrap();
    assert_eq!(a.attribute("values").unwrap().split(';').count(), 179);
}

#[test]
fn key_frames_follow_the_closed_form_motion() {
    // A lone joint at P with a fixed window: its translations are the closed-form pixels of P
    // at the key frames' inputs, which are spread evenly over the samples.
    let m = FourBar::default();
    let mo = motion(&m, TAU, 361);
    let canvas = Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() };
    let anim = Animation { frames: 61, ..Animation::default() };
    let d = Drawing::new().with_canvas(canvas).joint("p");
    let svg = d.animate(&mo, &anim).unwrap();
    let doc = checked(&svg).unwrap();
    let a = doc.descendants().find(|n| n.tag_name().name() == "animateTransform").unwrap();
    let values = pairs(a.attribute("values").unwrap(), ';');
    let keys = d.key_poses(&mo, &anim).unwrap();
    assert_eq!((values.len(), keys.len(), keys[0], keys[60]), (61, 61, 0, 360));
    for (v, &k) in values.iter().zip(&keys) {
        assert_eq!(k % 6, 0, "360 intervals in 60 steps");
        let want = window_px(WINDOW, WIDTH, four_bar_joints(&m, mo.poses[k].x[0])[2]);
        // Written rounded to 0.1 px: at most 0.05 px off, plus rounding of the decimal.
        assert!((v[0] - want[0]).abs() <= 0.0501 && (v[1] - want[1]).abs() <= 0.0501, "{v:?} vs {want:?}");
    }
}

#[test]
fn the_traced_path_is_the_closed_form_coupler_curve() {
    let m = FourBar::default();
    let mo = motion(&m, TAU, 121);
    let canvas = Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() };
    let svg = four_bar_drawing(&m).with_canvas(canvas).animate(&mo, &Animation::default()).unwrap();
    let doc = checked(&svg).unwrap();
    let trace = doc.descendants().find(|n| n.attribute("class") == Some("trace")).expect("a traced path");
    let pts = pairs(trace.attribute("points").unwrap(), ' ');
    // Every sample (none falls on the same 0.1 px as its neighbour on this curve).
    assert_eq!(pts.len(), 121);
    for (i, p) in pts.iter().enumerate() {
        let phi = TAU * i as f64 / 120.0;
        let want = window_px(WINDOW, WIDTH, four_bar_joints(&m, phi)[2]);
        assert!((p[0] - want[0]).abs() <= 0.0501 && (p[1] - want[1]).abs() <= 0.0501, "sample {i}: {p:?} vs {want:?}");
    }
}

#[test]
fn a_limit_position_is_drawn_and_marked_where_the_closed_form_puts_it() {
    // Non-Grashof: the crank stops where coupler and rocker are collinear, |BD| = l + k.
    let m = FourBar { r: 3.0, l: 2.0, k: 2.5, d: 4.0, e: 1.2, delta: 0.9 };
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let mo = Motion::record(&m, m.sweep(0.0, PI, 91, &g).unwrap()).unwrap();
    assert!(mo.stopped);
    assert_eq!(mo.events.len(), 1);
    assert_eq!(mo.events[0].kind, EventKind::LimitPosition);
    let limit = ((m.r * m.r + m.d * m.d - (m.l + m.k).powi(2)) / (2.0 * m.r * m.d)).acos();
    let b = [m.r * limit.cos(), m.r * limit.sin()];
    let c = [m.d + m.k * (b[0] - m.d) / (m.l + m.k), m.k * b[1] / (m.l + m.k)];
    let window = [-3.0, -2.0, 6.0, 5.0];
    let canvas = Canvas { width: WIDTH, window: Some(window), ..Canvas::default() };
    let d = Drawing::new().with_canvas(canvas).joint("c");
    let anim = Animation { frames: 30, back_and_forth: true, ..Animation::default() };
    let svg = d.animate(&mo, &anim).unwrap();
    let doc = checked(&svg).unwrap();
    let event = doc.descendants().find(|n| n.attribute("class") == Some("event")).expect("the event is drawn");
    let label = event.descendants().find(|n| n.tag_name().name() == "text").unwrap().text().unwrap();
    // Angles are read out in degrees (two decimals, 0.00017 rad).
    assert_eq!(label, format!("limit position at phi = {:.2}°", limit.to_degrees()));
    let ghost = event.descendants().find(|n| n.tag_name().name() == "circle").unwrap();
    let at = ghost.attribute("transform").unwrap().trim_start_matches("translate(").trim_end_matches(')');
    let at = pairs(at, ';')[0];
    let want = window_px(window, WIDTH, c);
    assert!((at[0] - want[0]).abs() <= 0.0501 && (at[1] - want[1]).abs() <= 0.0501, "{at:?} vs {want:?}");
    // The animation goes to the event and back: its middle key frame is the event's pose.
    let moving = doc.descendants().find(|n| n.tag_name().name() == "animateTransform").unwrap();
    let values = pairs(moving.attribute("values").unwrap(), ';');
    assert_eq!(values.len(), 59);
    assert_eq!(values[29], at);
    assert_eq!(values[0], values[58]);
}

#[test]
fn a_singular_crossing_passed_is_drawn_where_the_links_fold() {
    // Change point (r + l = k + d): at phi = 2 pi the links fold flat, B = (1, 0) and
    // C = (4, 0) (|BC| = 3, |CD| = 2 with D = (2, 0)). The sweep passes it and goes on.
    let m = FourBar { r: 1.0, l: 3.0, k: 2.0, d: 2.0, e: 1.0, delta: 0.5 };
    let g = m.position(0.5, &FourBarUnknowns { beta: 0.6, gamma: 1.6 }).unwrap().0;
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let mo = Motion::record(&m, m.sweep(0.5, 7.0, 66, &g).unwrap().with_config(cfg)).unwrap();
    assert!(!mo.stopped);
    assert_eq!(mo.poses.len(), 66);
    let crossings: Vec<_> = mo.events.iter().filter(|e| e.kind == EventKind::SingularCrossing).collect();
    assert_eq!(crossings.len(), 1, "{:?}", mo.events);
    let window = [-2.0, -4.0, 6.0, 4.0];
    let canvas = Canvas { width: WIDTH, window: Some(window), ..Canvas::default() };
    let svg = Drawing::new().with_canvas(canvas).joint("c").animate(&mo, &Animation::default()).unwrap();
    let doc = checked(&svg).unwrap();
    let event = doc.descendants().find(|n| n.attribute("class") == Some("event")).expect("the crossing is drawn");
    let label = event.descendants().find(|n| n.tag_name().name() == "text").unwrap().text().unwrap();
    assert_eq!(label, "singular crossing at phi = 360.00°");
    let ghost = event.descendants().find(|n| n.tag_name().name() == "circle").unwrap();
    let at = ghost.attribute("transform").unwrap().trim_start_matches("translate(").trim_end_matches(')');
    let want = window_px(window, WIDTH, [4.0, 0.0]);
    // The crossing is located to the sweep's tolerance (about 1e-9 rad here), far below 0.05 px.
    assert!(pairs(at, ';')[0].iter().zip(want).all(|(a, w)| (a - w).abs() <= 0.0501), "{at} vs {want:?}");
}

/// Every number of an SVG document, in order.
fn numbers(svg: &str) -> Vec<f64> {
    svg.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-')).filter_map(|t| t.parse::<f64>().ok()).collect()
}

#[test]
fn metres_and_millimetres_draw_alike() {
    let m = FourBar::default();
    let mm = FourBar { r: 1e3 * m.r, l: 1e3 * m.l, k: 1e3 * m.k, d: 1e3 * m.d, e: 1e3 * m.e, ..m };
    // The scale bars differ as the units do: the same bar, 1000 times the number.
    let bar = |d: &Drawing, m: &FourBar| -> f64 {
        let svg = d.svg(&motion(m, TAU, 19), 0).unwrap();
        let doc = checked(&svg).unwrap();
        let g = doc.descendants().find(|n| n.attribute("class") == Some("scale-bar")).expect("a scale bar");
        let text = g.descendants().find(|n| n.is_text()).unwrap().text().unwrap();
        text.split(' ').next().unwrap().parse().unwrap()
    };
    assert_eq!(bar(&four_bar_drawing(&mm), &mm), 1e3 * bar(&four_bar_drawing(&m), &m));
    let no_bar = Annotate { scale_bar: false, ..Annotate::default() };
    let a = four_bar_drawing(&m).with_annotate(no_bar).animate(&motion(&m, TAU, 181), &Animation::default()).unwrap();
    let b = four_bar_drawing(&mm).with_annotate(no_bar).animate(&motion(&mm, TAU, 181), &Animation::default()).unwrap();
    let (na, nb) = (numbers(&a), numbers(&b));
    assert_eq!(na.len(), nb.len());
    // Pixels agree up to the 0.1 px rounding of a coordinate lying on a rounding boundary.
    let worst = na.iter().zip(&nb).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    assert!(worst <= 0.1 + 1e-9, "largest difference {worst} px");
    println!("{} numbers, largest difference {worst} px", na.len());
}

#[test]
fn the_committed_animations_are_well_formed_and_small() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/animations");
    let mut animated = 0;
    for entry in std::fs::read_dir(&dir).expect("docs/animations") {
        let path = entry.unwrap().path();
        let svg = std::fs::read_to_string(&path).unwrap();
        let doc = checked(&svg).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(doc.root_element().tag_name().name(), "svg");
        assert!(!svg.contains("script") && !svg.contains("NaN") && !svg.contains("inf"), "{}", path.display());
        // Small enough to embed in a README: labels, the scale bar and a readout per key frame
        // brought the largest (the roller edger, two loops and a trace) to about 75 KiB.
        assert!(svg.len() < 96 * 1024, "{}: {} bytes", path.display(), svg.len());
        // The motion's animations; the readout's texts take turns by discrete visibility
        // switches of two or three values each, which are not key frames of the motion.
        let motion = |n: &roxmltree::Node| {
            matches!(n.tag_name().name(), "animate" | "animateTransform")
                && n.attribute("attributeName") != Some("visibility")
        };
        for a in doc.descendants().filter(motion) {
            // 60 to 90 key frames a pass (fewer when a sweep stops early), twice less one when
            // played forward and back.
            let n = a.attribute("values").unwrap().split(';').count();
            assert!((60..=179).contains(&n), "{}: {n} key frames", path.display());
            animated += 1;
        }
    }
    assert!(animated > 0);
}

#[test]
fn a_multi_exposure_shows_evenly_spread_distinct_poses() {
    // A full turn ends where it began: that pose is shown once, so four exposures of 361
    // samples show samples 0, 120, 239 and 359 (evenly spread over the 360 distinct ones).
    let m = FourBar::default();
    let mo = motion(&m, TAU, 361);
    let canvas = Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() };
    let svg = Drawing::new().with_canvas(canvas).joint("p").exposures(&mo, 4).unwrap();
    let doc = checked(&svg).unwrap();
    let faint = doc.descendants().filter(|n| n.attribute("opacity").is_some()).count();
    let circles: Vec<[f64; 2]> = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "circle")
        .map(|n| {
            pairs(n.attribute("transform").unwrap().trim_start_matches("translate(").trim_end_matches(')'), ';')[0]
        })
        .collect();
    assert_eq!((faint, circles.len()), (3, 4));
    for (at, k) in circles.iter().zip([0, 120, 239, 359]) {
        let want = window_px(WINDOW, WIDTH, four_bar_joints(&m, TAU * k as f64 / 360.0)[2]);
        assert!(
            (at[0] - want[0]).abs() <= 0.0501 && (at[1] - want[1]).abs() <= 0.0501,
            "sample {k}: {at:?} vs {want:?}"
        );
    }
}

#[test]
fn the_animated_trace_grows_with_the_traced_point() {
    // The trace is redrawn in full colour as a dash as long as the path, shifted so that at
    // each key frame it covers the curve up to the traced point: the offset is the dash length
    // minus the closed-form curve's arclength (in pixels) up to that key frame's input.
    let m = FourBar::default();
    let mo = motion(&m, TAU, 361);
    let canvas = Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() };
    let anim = Animation { frames: 46, ..Animation::default() };
    let d = four_bar_drawing(&m).with_canvas(canvas);
    let svg = d.animate(&mo, &anim).unwrap();
    let doc = checked(&svg).unwrap();
    let traced = doc.descendants().find(|n| n.attribute("class") == Some("traced")).expect("the growing trace");
    let dash: Vec<f64> = traced.attribute("stroke-dasharray").unwrap().split(' ').map(|v| v.parse().unwrap()).collect();
    assert_eq!(dash[0], dash[1]);
    let offsets: Vec<f64> = traced
        .children()
        .find(|n| n.tag_name().name() == "animate")
        .unwrap()
        .attribute("values")
        .unwrap()
        .split(';')
        .map(|v| v.parse().unwrap())
        .collect();
    let keys = d.key_poses(&mo, &anim).unwrap();
    assert_eq!(offsets.len(), keys.len());
    let px: Vec<[f64; 2]> =
        (0..361).map(|i| window_px(WINDOW, WIDTH, four_bar_joints(&m, TAU * i as f64 / 360.0)[2])).collect();
    let mut along = vec![0.0];
    for w in px.windows(2) {
        along.push(along.last().unwrap() + (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]));
    }
    assert!(dash[0] >= along[360] && dash[0] <= along[360] + 2.5, "dash {} for a curve of {} px", dash[0], along[360]);
    for (o, &k) in offsets.iter().zip(&keys) {
        // The written polyline's points are rounded to 0.1 px, which changes its length by
        // well under a pixel over 360 segments (the rounding errors mostly cancel).
        assert!((dash[0] - o - along[k]).abs() < 1.0, "key {k}: drawn {} px of {} px", dash[0] - o, along[k]);
    }
}

#[test]
fn joints_are_labelled_and_the_readout_follows_the_input_in_degrees() {
    // In a window: each named point's label group moves with its joint (the closed-form pixel
    // of B, C, P at every key frame), a fixed point is labelled by hand, and the readout shows
    // each key frame's crank angle in degrees, one text per key frame, in turn.
    let m = FourBar::default();
    let mo = motion(&m, TAU, 37);
    let canvas = Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() };
    let anim = Animation { frames: 13, ..Animation::default() };
    let d = four_bar_drawing(&m).with_canvas(canvas).label(Pt::fixed(0.0, 0.0), "A").label("c", "C").length_unit("m");
    let svg = d.animate(&mo, &anim).unwrap();
    let doc = checked(&svg).unwrap();
    let keys = d.key_poses(&mo, &anim).unwrap();
    let groups: Vec<_> = doc.descendants().filter(|n| n.attribute("class") == Some("joint-label")).collect();
    let texts: Vec<&str> =
        groups.iter().map(|g| g.descendants().find(|n| n.is_text()).unwrap().text().unwrap()).collect();
    // b and p by name, c renamed, the pivot A added; no other label.
    assert_eq!(texts, ["b", "C", "p", "A"]);
    for (g, joint) in groups.iter().zip([0, 1, 2]) {
        let moving = g.children().find(|n| n.tag_name().name() == "animateTransform").unwrap();
        for (v, &k) in pairs(moving.attribute("values").unwrap(), ';').iter().zip(&keys) {
            let want = window_px(WINDOW, WIDTH, four_bar_joints(&m, mo.poses[k].x[0])[joint]);
            assert!((v[0] - want[0]).abs() <= 0.0501 && (v[1] - want[1]).abs() <= 0.0501, "{v:?} vs {want:?}");
        }
    }
    let readout: Vec<_> = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "text" && n.parent().and_then(|p| p.attribute("class")) == Some("readout"))
        .collect();
    assert_eq!(readout.len(), keys.len());
    for (t, &k) in readout.iter().zip(&keys) {
        // 37 samples over a turn: 10 degrees apart.
        assert_eq!(t.text().unwrap(), format!("phi = {:.1}°", 10.0 * k as f64));
    }
    // Only the first is shown to a static renderer; each is shown for its key frame's turn.
    assert_eq!(readout.iter().filter(|t| t.attribute("visibility") == Some("visible")).count(), 1);
    let times = |t: &roxmltree::Node| {
        t.children().find(|n| n.tag_name().name() == "animate").unwrap().attribute("keyTimes").unwrap().to_string()
    };
    assert_eq!(times(&readout[6]), "0;0.45833;0.54167");
}

#[test]
fn a_fitted_drawing_is_cropped_to_its_ink_with_the_margin() {
    // Without a window, the picture ends a margin beyond what is drawn: the mechanism's
    // pixels (rendered) reach to within the margin and a few pixels of each edge, and no
    // shape is cut by one.
    let m = FourBar::default();
    let mo = motion(&m, TAU, 13);
    // A small picture: few pixels to render.
    let canvas = Canvas { width: 240.0, ..Canvas::default() };
    let d = four_bar_drawing(&m).with_annotate(Annotate::none()).with_canvas(canvas);
    let svg = d.svg(&mo, 0).unwrap();
    checked(&svg).unwrap();
    let view = d.view(&mo).unwrap();
    // The traced path is drawn over the whole turn; at pose 0 the rest is the mechanism there:
    // the ink's box over the motion is that of the exposures of every pose.
    let all = d.exposures(&mo, 13).unwrap();
    let (rgba, w, h) = draw_support::render(&all);
    assert_eq!((w as f64, h as f64), (view.width.ceil(), view.height.ceil()));
    let (mut x0, mut y0, mut x1, mut y1) = (u32::MAX, u32::MAX, 0, 0);
    for j in 0..h {
        for i in 0..w {
            if draw_support::ink(&rgba, w, i, j) > 8.0 {
                (x0, y0, x1, y1) = (x0.min(i), y0.min(j), x1.max(i), y1.max(j));
            }
        }
    }
    let margin = kinloop_viz::draw::Canvas::default().margin;
    let gaps = [x0 as f64, y0 as f64, w as f64 - 1.0 - x1 as f64, h as f64 - 1.0 - y1 as f64];
    // The ink's box is estimated from the shapes' sizes (strokes, symbols), a pixel or two
    // generous: each gap is the margin to within 3 px, never less than half of it.
    for g in gaps {
        assert!(g >= 0.5 * margin && g <= margin + 3.0, "gaps {gaps:?} for a margin of {margin}");
    }
}

/// A cam-like outline on the crank: its corners, written once in the body's frame, moved by the
/// group's translation and turned by its rotation at each key frame, land on the closed form's
/// corners (the crank's angle turning the body-frame corners about O) in the window's pixels.
#[test]
fn an_outline_turns_with_its_body() {
    let m = FourBar::default();
    let mo = motion(&m, TAU, 361);
    let canvas = Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() };
    let corners = vec![[1.2, 0.0], [0.0, 0.6], [-0.4, -0.3]];
    let anim = Animation { frames: 37, ..Animation::default() };
    let d = Drawing::new().with_canvas(canvas).outline([0.0, 0.0], corners.clone(), Scalar::expr(|s| s.x[0]));
    let svg = d.animate(&mo, &anim).unwrap();
    let doc = checked(&svg).unwrap();
    let polygon = doc.descendants().find(|n| n.tag_name().name() == "polygon").expect("the outline");
    let body = pairs(polygon.attribute("points").unwrap(), ' ');
    assert_eq!(body.len(), 3);
    // The body's centre stays at O: its group's translation is written once, not animated.
    let rotated = polygon.parent().unwrap();
    let moved = rotated.parent().unwrap();
    let translate = moved.attribute("transform").unwrap();
    assert!(
        translate.starts_with("translate(") && !moved.children().any(|n| n.tag_name().name() == "animateTransform")
    );
    let at = pairs(translate.trim_start_matches("translate(").trim_end_matches(')'), ';')[0];
    assert_eq!(at, window_px(WINDOW, WIDTH, [0.0, 0.0]));
    let turn = rotated.children().find(|n| n.tag_name().name() == "animateTransform").expect("the body turns");
    let turns: Vec<&str> = turn.attribute("values").unwrap().split(';').collect();
    let keys = d.key_poses(&mo, &anim).unwrap();
    assert_eq!((turns.len(), keys.len()), (37, 37));
    for (k, &pose) in keys.iter().enumerate() {
        let phi = mo.poses[pose].x[0];
        // SVG's rotate turns clockwise on screen by its degrees (the y axis points down).
        let deg: f64 = turns[k].parse().unwrap();
        let (s, c) = deg.to_radians().sin_cos();
        for (b, w) in body.iter().zip(&corners) {
            let on_screen = [at[0] + c * b[0] - s * b[1], at[1] + s * b[0] + c * b[1]];
            let (sp, cp) = phi.sin_cos();
            let world = [cp * w[0] - sp * w[1], sp * w[0] + cp * w[1]];
            let want = window_px(WINDOW, WIDTH, world);
            // Corners and translations written to 0.1 px, the angle to 0.01 degree (unwrapped).
            for i in 0..2 {
                assert!((on_screen[i] - want[i]).abs() <= 0.15, "pose {pose}: {on_screen:?} vs {want:?}");
            }
        }
    }
}

#[test]
fn a_circle_is_an_outline_at_its_radius_and_outlines_are_checked() {
    let d = Drawing::new().circle([1.0, 2.0], 0.5);
    let Some(kinloop_viz::draw::Item::Outline { points, .. }) = d.items.first() else { panic!("{:?}", d.items) };
    assert_eq!(points.len(), 96);
    assert!(points.iter().all(|p| (p[0].hypot(p[1]) - 0.5).abs() <= 1e-15));
    let m = FourBar::default();
    let mo = motion(&m, 1.0, 5);
    for (corners, says) in [(vec![[0.0, 0.0]], "at least 2"), (vec![[0.0, 0.0], [f64::NAN, 1.0]], "not finite")] {
        let e = Drawing::new().outline([0.0, 0.0], corners, 0.0).svg(&mo, 0).unwrap_err();
        assert!(e.to_string().contains(says), "{e}");
    }
}

/// Every animated attribute of an animation lasts the seconds asked, to the digit: a quarter
/// of a second was written `dur="0.3s"` (rounded to a tenth as a coordinate), and a few
/// hundredths `dur="0s"` (an animation SMIL does not play). Durations no animation can show
/// (below a millisecond) or beyond a billion seconds are errors.
#[test]
fn an_animation_lasts_the_seconds_asked() {
    let m = FourBar::default();
    let mo = motion(&m, TAU, 25);
    let d = four_bar_drawing(&m);
    for (seconds, dur) in [(0.25, "0.25s"), (0.04, "0.04s"), (1.125, "1.125s"), (6.0, "6s"), (3600.0, "3600s")] {
        let svg = d.animate(&mo, &Animation { seconds, ..Animation::default() }).unwrap();
        let doc = checked(&svg).unwrap();
        let durs: Vec<&str> = doc.descendants().filter_map(|n| n.attribute("dur")).collect();
        assert!(!durs.is_empty() && durs.iter().all(|d| *d == dur), "{seconds} s: {durs:?}");
    }
    for seconds in [1e-4, 5e-324, 2e9, 1e300] {
        let r = d.animate(&mo, &Animation { seconds, ..Animation::default() });
        assert!(
            matches!(r, Err(kinloop_viz::draw::DrawError::InvalidSetting(_))),
            "{seconds} s: {:?}",
            r.map(|s| s.len())
        );
    }
}

/// An input angle of a hundred thousand degrees or more is read out as a page's readout
/// writes it (five significant digits and a power of ten), not with every digit of its
/// degrees: a crank turned 1e300 radians wrote a readout three hundred digits long, which
/// widened the picture to hold it.
#[test]
fn huge_input_angles_are_read_out_with_a_power_of_ten() {
    let m = FourBar::default();
    let mo = motion(&m, TAU, 5);
    let d = Drawing::new().link(["b", "c", "p"]);
    let mut one = mo.clone();
    one.poses.truncate(1);
    let narrow = d.view(&one).unwrap().width;
    for (phi, text) in [(1e300, "phi = 5.7296e301°"), (1e4, "phi = 5.7296e5°"), (-3e5, "phi = -1.7189e7°")] {
        // The pose of the crank at 0, read out at `phi` (the drawing draws the outputs).
        let mut huge = one.clone();
        huge.poses[0].x[0] = phi;
        let svg = d.svg(&huge, 0).unwrap();
        let doc = checked(&svg).unwrap();
        let readout = doc
            .descendants()
            .find(|n| n.tag_name().name() == "text" && n.parent().and_then(|p| p.attribute("class")) == Some("readout"))
            .unwrap();
        assert_eq!(readout.text().unwrap(), text);
        assert!(d.view(&huge).unwrap().width <= narrow, "{phi}");
    }
}

/// A sweep far from the origin of its input (a crank after a hundred thousand turns): the
/// animated readout writes each key frame's input with the digits that tell them apart, as a
/// page's readouts do; with five significant digits of the largest value, every key frame
/// read `phi = 5.7296e7°`.
#[test]
fn a_readout_far_from_zero_tells_its_key_frames_apart() {
    let m = FourBar::default();
    let start = 1e6;
    let mo = Motion::record(&m, m.sweep(start, start + TAU, 37, &m.guess(start)).unwrap()).unwrap();
    let anim = Animation { frames: 13, ..Animation::default() };
    let svg = Drawing::new().link(["b", "c", "p"]).animate(&mo, &anim).unwrap();
    let doc = checked(&svg).unwrap();
    let mut texts: Vec<&str> = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "text" && n.parent().and_then(|p| p.attribute("class")) == Some("readout"))
        .map(|n| n.text().unwrap())
        .collect();
    assert_eq!(texts.len(), 13);
    texts.dedup();
    assert_eq!(texts.len(), 13, "{texts:?}");
}

#[test]
fn the_input_turns_at_constant_speed_whatever_the_key_frames_picked() {
    // 181 samples over a turn in 90 key frames: steps of 2 and 3 samples (4 and 6 degrees).
    // Every animation is timed by the key frames' input: key frame k at phi_k / 2 pi of the
    // pass, and the readout's text shown from halfway from the previous key frame to halfway
    // to the next.
    let m = FourBar::default();
    let mo = motion(&m, TAU, 181);
    let anim = Animation::default();
    let d = four_bar_drawing(&m);
    let svg = d.animate(&mo, &anim).unwrap();
    let doc = checked(&svg).unwrap();
    let keys = d.key_poses(&mo, &anim).unwrap();
    assert_eq!(keys.len(), 90);
    let want: Vec<f64> = keys.iter().map(|&k| mo.poses[k].x[0] / TAU).collect();
    let steps: Vec<usize> = keys.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(steps.contains(&2) && steps.contains(&3), "uneven samples per key frame: {steps:?}");
    let animations: Vec<_> =
        doc.descendants().filter(|n| matches!(n.tag_name().name(), "animate" | "animateTransform")).collect();
    let mut timed = 0;
    for a in &animations {
        if a.attribute("attributeName") == Some("visibility") {
            continue;
        }
        let times: Vec<f64> =
            a.attribute("keyTimes").expect("key times").split(';').map(|t| t.parse().unwrap()).collect();
        assert_eq!(times.len(), want.len());
        for (t, w) in times.iter().zip(&want) {
            assert!((t - w).abs() <= 0.5e-5 + 1e-12, "key time {t} for phi at {w} of the turn");
        }
        timed += 1;
    }
    assert!(timed >= 5, "{timed} animations");
    // The readout of key frame 24 (after a step of 3 samples): from halfway back to halfway on.
    let readout: Vec<_> = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "text" && n.parent().and_then(|p| p.attribute("class")) == Some("readout"))
        .collect();
    let k = 24;
    let times = readout[k].children().find(|n| n.tag_name().name() == "animate").unwrap();
    let times: Vec<f64> = times.attribute("keyTimes").unwrap().split(';').map(|t| t.parse().unwrap()).collect();
    let (from, to) = ((want[k - 1] + want[k]) / 2.0, (want[k] + want[k + 1]) / 2.0);
    assert!((times[1] - from).abs() <= 0.5e-5 + 1e-12 && (times[2] - to).abs() <= 0.5e-5 + 1e-12, "{times:?}");
}

/// The points of the SVG elements of class `class` (a polyline's `points`, a path's `d`).
fn points_of(svg: &str, class: &str) -> Vec<[f64; 2]> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.attribute("class") == Some(class))
        .flat_map(|n| {
            let text = n.attribute("points").or(n.attribute("d")).unwrap_or("").replace(['M', 'L'], " ");
            text.split_whitespace()
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    [x.parse().unwrap(), y.parse().unwrap()]
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The picture of an interactive page (its `<svg id="kl-drawing">`).
fn drawing_of(page: &str) -> String {
    let at = page.find(r#"<svg xmlns="http://www.w3.org/2000/svg" id="kl-drawing""#).expect("a picture");
    let end = at + page[at..].find("</svg>").expect("closed") + "</svg>".len();
    page[at..end].to_string()
}

#[test]
fn a_sweep_of_many_turns_writes_its_curve_about_once() {
    // A hundred turns, sampled as one (every 5 degrees) and with samples drifting from turn to
    // turn: the traced coupler curve is written about once, not a hundred times, and covers
    // every point of the single turn's curve.
    let m = FourBar::default();
    // Without joint labels, which frame a drawing but not a page's picture: both then map the
    // plane to the same pixels.
    let d = four_bar_drawing(&m).with_annotate(Annotate::none());
    let one = points_of(&d.svg(&motion(&m, TAU, 73), 0).unwrap(), "trace");
    for samples in [7201, 7001] {
        let mo = motion(&m, 100.0 * TAU, samples);
        let html = kinloop_viz::draw::html(&m, &d, &mo, &kinloop_viz::draw::HtmlConfig::new("turns")).unwrap();
        for (what, pts) in [
            ("svg", points_of(&d.animate(&mo, &Animation::default()).unwrap(), "trace")),
            ("page", points_of(&drawing_of(&html), "kl-trace")),
        ] {
            let bound = if samples == 7201 { one.len() + 2 } else { samples / 10 };
            assert!(
                pts.len() <= bound,
                "{samples} samples, {what}: {} points against {} for one turn",
                pts.len(),
                one.len()
            );
            // Every point of the one turn's curve within a tenth of a pixel of a point written
            // (the same samples: the curve looks the same).
            if samples == 7201 {
                for p in &one {
                    let near =
                        pts.iter().any(|q| (q[0] - p[0]).abs() <= 0.1 + 1e-9 && (q[1] - p[1]).abs() <= 0.1 + 1e-9);
                    assert!(near, "{what}: {p:?} of the turn's curve is not drawn");
                }
            }
        }
    }
}
