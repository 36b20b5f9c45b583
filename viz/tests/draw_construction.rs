//! A vector of a declaration that is neither a link, a slider nor the frame (a construction
//! vector, `SegmentKind::Construction`) is drawn as a thin dashed line with no joint circles of
//! its own: in the SVG, in its pixels (the PNG renders that SVG), on the interactive page and
//! in a figure of synthesis candidates.
//! A thick bar with joints would read as a physical link the mechanism does not have.

use kinloop::synthesis::{Design, Problem, Search, Task};
use kinloop_viz::draw::{Animation, CandidatesConfig, Canvas, Draw, HtmlConfig, Motion, Style, candidates, html};
use std::f64::consts::TAU;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::{Tied, render, window_px};

const WINDOW: [f64; 4] = [-2.0, -2.0, 4.0, 2.0];
const WIDTH: f64 = 300.0;
/// Pixel coordinates are written with one decimal: half a tenth of a pixel of rounding.
const PX: f64 = 0.05 + 1e-9;

/// B (the crank pin) and D (the fixed end of the construction vector) at crank angle `phi`.
fn ends(m: &Tied, phi: f64) -> [[f64; 2]; 2] {
    [[m.r * phi.cos(), m.r * phi.sin()], [m.d, 0.0]]
}

fn one_pose(m: &Tied, phi: f64) -> Motion {
    let mut one = Motion::empty::<Tied, 2, 1, 2>();
    one.push(&m.solve(phi).unwrap().flat);
    one
}

fn points(v: &str) -> Vec<[f64; 2]> {
    let n: Vec<f64> = v.split([' ', ',']).map(|c| c.parse().expect("a number")).collect();
    n.chunks(2).map(|c| [c[0], c[1]]).collect()
}

fn near(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() <= PX && (a[1] - b[1]).abs() <= PX
}

#[test]
fn a_construction_vector_is_a_thin_dashed_line_without_joint_circles() {
    let m = Tied::default();
    let style = Style::default();
    for phi in [0.5, 2.0, 4.0] {
        let d = m.drawing().with_canvas(Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() });
        assert!(d.notes().iter().any(|n| n.contains("`tie: (x, y)`") && n.contains("construction line")));
        let svg = d.svg(&one_pose(&m, phi), 0).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let lines: Vec<_> = doc.descendants().filter(|n| n.attribute("class") == Some("construction")).collect();
        assert_eq!(lines.len(), 1, "{svg}");
        let px = |w| window_px(WINDOW, WIDTH, w);
        let [b, dd] = ends(&m, phi).map(px);
        let at = points(lines[0].attribute("points").unwrap());
        assert!(at.len() == 2 && near(at[0], b) && near(at[1], dd), "{at:?}, B {b:?}, D {dd:?}");
        assert_eq!(lines[0].attribute("stroke-width"), Some("1"));
        assert!(lines[0].attribute("stroke-dasharray").is_some());
        // The crank alone is a bar, in the links' width.
        let bars: Vec<_> = doc
            .descendants()
            .filter(|n| n.has_tag_name("polyline") && n.attribute("class").is_none())
            .map(|n| (n.attribute("stroke-width").unwrap().to_string(), points(n.attribute("points").unwrap())))
            .collect();
        assert_eq!(bars.len(), 1, "{bars:?}");
        assert_eq!(bars[0].0, style.link_width.to_string());
        // Joint circles at O and B (the crank's), none at D, which only the construction reaches.
        let joint_r = style.joint_radius.to_string();
        let circles: Vec<[f64; 2]> = doc
            .descendants()
            .filter(|n| n.has_tag_name("circle") && n.attribute("r") == Some(joint_r.as_str()))
            .map(|n| {
                let t = n.attribute("transform").unwrap().strip_prefix("translate(").unwrap();
                points(t.strip_suffix(')').unwrap())[0]
            })
            .collect();
        assert_eq!(circles.len(), 2, "{circles:?}");
        assert!(circles.iter().all(|c| !near(*c, dd)), "a joint circle at D: {circles:?}");
    }
}

/// Animated, the line moves with the crank pin; in a multi-exposure it stays thin in every
/// exposure, as at the events' ghosts.
#[test]
fn a_construction_line_moves_and_stays_thin_in_every_layer() {
    let m = Tied::default();
    let motion = Motion::record(&m, m.sweep(0.0, TAU, 37, &m.guess(0.0)).unwrap()).unwrap();
    let d = m.drawing().into_drawing();
    let animated = d.animate(&motion, &Animation::default()).unwrap();
    let doc = roxmltree::Document::parse(&animated).unwrap();
    let line = doc.descendants().find(|n| n.attribute("class") == Some("construction")).expect("a construction line");
    let moves = line.children().find(|c| c.has_tag_name("animate")).expect("animated");
    assert_eq!(moves.attribute("attributeName"), Some("points"));
    let exposures = d.exposures(&motion, 4).unwrap();
    let doc = roxmltree::Document::parse(&exposures).unwrap();
    let widths: Vec<&str> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("construction"))
        .map(|n| n.attribute("stroke-width").unwrap())
        .collect();
    assert_eq!(widths, ["1"; 4]);
}

/// The rendered pixels: across the line, ink at most two pixels wide (a link's bar is four),
/// and gaps along it (dashes).
#[test]
fn a_construction_line_renders_thin_and_dashed() {
    let m = Tied::default();
    let phi = 2.0;
    let d = m.drawing().with_canvas(Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() });
    let svg = d.svg(&one_pose(&m, phi), 0).unwrap();
    let (rgba, w, h) = render(&svg);
    let inked = |[x, y]: [f64; 2]| {
        let (x, y) = (x.floor() as i64, y.floor() as i64);
        if x < 0 || y < 0 || x >= i64::from(w) || y >= i64::from(h) {
            return false;
        }
        let i = 4 * (y as usize * w as usize + x as usize);
        rgba[i..i + 3].iter().any(|&c| c < 200)
    };
    let [b, dd] = ends(&m, phi).map(|p| window_px(WINDOW, WIDTH, p));
    let len = (dd[0] - b[0]).hypot(dd[1] - b[1]);
    let (u, n) = ([(dd[0] - b[0]) / len, (dd[1] - b[1]) / len], [(b[1] - dd[1]) / len, (dd[0] - b[0]) / len]);
    let (mut widest, mut gaps, mut dashes) = (0.0f64, 0, 0);
    // Along the middle of the line, away from the joint circle at B and the label there.
    for k in 0..=140 {
        let s = len * (0.2 + 0.6 * k as f64 / 140.0);
        let c = [b[0] + s * u[0], b[1] + s * u[1]];
        let across: Vec<f64> =
            (-16..=16).map(|j| 0.5 * j as f64).filter(|&t| inked([c[0] + t * n[0], c[1] + t * n[1]])).collect();
        match (across.first(), across.last()) {
            (Some(lo), Some(hi)) => {
                widest = widest.max(hi - lo);
                dashes += 1;
            }
            _ => gaps += 1,
        }
    }
    assert!(widest <= 2.0, "ink {widest} pixels across the construction line");
    assert!(dashes > 20 && gaps > 20, "{dashes} samples on a dash, {gaps} in a gap");
}

/// The interactive page draws the line as its own kind of shape, thin and dashed, that its
/// script moves as a bar, with no joint circles.
#[test]
fn the_page_draws_a_construction_line_without_joints() {
    let m = Tied::default();
    let motion = Motion::record(&m, m.sweep(0.0, TAU, 37, &m.guess(0.0)).unwrap()).unwrap();
    let page = html(&m, &m.drawing().into_drawing(), &motion, &HtmlConfig::new("tied")).unwrap();
    let start = page.find(r#"<svg xmlns="http://www.w3.org/2000/svg" id="kl-drawing""#).unwrap();
    let svg = &page[start..start + page[start..].find("</svg>").unwrap() + "</svg>".len()];
    let doc = roxmltree::Document::parse(svg).unwrap();
    let lines: Vec<_> =
        doc.descendants().filter(|n| n.attribute("class") == Some("kl-shape kl-construction")).collect();
    assert_eq!(lines.len(), 1, "{svg}");
    assert_eq!(lines[0].attribute("stroke-width"), Some("1"));
    assert!(lines[0].attribute("stroke-dasharray").is_some());
    let k = lines[0].attribute("data-item").unwrap();
    let joints: Vec<&str> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("kl-joint"))
        .map(|n| n.attribute("data-item").unwrap())
        .collect();
    assert_eq!(joints.len(), 2, "the crank's two joints: {joints:?}");
    assert!(!joints.contains(&k), "a joint circle on the construction line: {joints:?}");
    // The script moves it as a bar through two points.
    let k: usize = k.parse().unwrap();
    let items = page.split(r#""items":["#).nth(1).unwrap().split(']').next().unwrap();
    let item = items.split("},").nth(k).unwrap();
    assert!(item.starts_with(r#"{"t":"link","#) && item.contains(r#""n":2"#), "{items}");
}

/// A synthesis' candidate is drawn from its default drawing: the construction vector is a thin
/// dashed line there too, and only the crank has joint circles.
#[test]
fn a_candidate_draws_its_construction_vector_as_a_thin_line() {
    let targets: Vec<[f64; 2]> = (0..6).map(|k| k as f64).map(|phi| [1.5 * phi.cos(), 1.5 * phi.sin()]).collect();
    let design = Design::new().var("r", 0.5, 2.5);
    let task = Task::path("b", targets.clone()).untimed(0.0, TAU);
    let problem = Problem::new(Tied::default(), &design, &task).unwrap();
    let report = Search::default().with_starts(0..4).with_seed(1).with_keep(1).run(&problem).unwrap();
    let best = &report.candidates[..1];
    assert!(best[0].is_valid() && best[0].max_error < 1e-6, "{:?}", best[0]);
    let svg = candidates(&Tied::default(), best, &targets, &CandidatesConfig::new("b")).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let class = |c: &str| doc.descendants().filter(|n| n.attribute("class") == Some(c)).collect::<Vec<_>>();
    let lines = class("construction");
    assert_eq!(lines.len(), 1, "{svg}");
    assert_eq!(lines[0].attribute("stroke-width"), Some("1"));
    assert!(lines[0].attribute("stroke-dasharray").is_some());
    assert_eq!(class("link").len(), 1, "the crank alone is a bar");
    assert_eq!(class("joint").len(), 2, "the crank's joints alone");
}
