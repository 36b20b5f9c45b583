//! Rendered drawings put each joint, slider block and gear on the pixel where the closed-form
//! position of the mechanism puts it. Frames are rendered with resvg; the expected pixel comes
//! from the closed form and the documented window rule, not from the library.

use kinloop_viz::draw::{Annotate, Canvas, Drawing, Motion, Pt, Scalar};
use std::f64::consts::TAU;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::{FourBar, SliderCrank, centroid, four_bar_joints, ink, render, slider_position, window_px};

const WINDOW: [f64; 4] = [-2.0, -2.0, 6.0, 5.0];
const WIDTH: f64 = 400.0;

fn canvas() -> Canvas {
    Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() }
}

/// A drawing in the window without annotations: the ink measured is the mechanism's alone.
fn bare() -> Drawing {
    Drawing::new().with_canvas(canvas()).with_annotate(Annotate::none())
}

/// The slider-crank's slider runs over x in [-4, -2] (left of the crank).
const SLIDER_WINDOW: [f64; 4] = [-6.0, -2.0, 2.0, 3.0];

fn four_bar_motion(m: &FourBar, samples: usize) -> Motion {
    Motion::record(m, m.sweep(0.0, TAU, samples, &m.guess(0.0)).unwrap()).unwrap()
}

/// Coordinates are written rounded to 0.1 px (at most 0.05 px off), and the ink centroid of
/// a symmetric anti-aliased circle or block is its centre to a few hundredths of a pixel;
/// 0.25 px is well inside the one pixel asked for and far below a joint's 3.5 px radius.
const TOL_PX: f64 = 0.25;

fn assert_near(got: [f64; 2], want: [f64; 2], what: &str) -> f64 {
    let err = (got[0] - want[0]).hypot(got[1] - want[1]);
    assert!(err < TOL_PX, "{what}: drawn at {got:?}, closed form at {want:?} ({err:.3} px off)");
    err
}

#[test]
fn each_joint_lands_on_its_closed_form_pixel() {
    let m = FourBar::default();
    let motion = four_bar_motion(&m, 13);
    let joints = [Pt::point("b"), Pt::point("c"), Pt::point("p")];
    let mut worst = 0.0f64;
    for (i, pose) in motion.poses.iter().enumerate() {
        let exact = four_bar_joints(&m, pose.x[0]);
        for (j, joint) in joints.iter().enumerate() {
            let svg = bare().joint(joint.clone()).svg(&motion, i).unwrap();
            let (c, total) = centroid(&svg);
            assert!(total > 0.0, "joint {joint:?} is drawn");
            worst = worst.max(assert_near(c, window_px(WINDOW, WIDTH, exact[j]), &format!("pose {i}, {joint:?}")));
        }
    }
    println!("largest joint offset: {worst:.3} px");
}

#[test]
fn joints_of_the_full_drawing_sit_on_their_pixels() {
    // The whole four-bar: links, a body, pivots, a trace. A joint circle is drawn on top of the
    // links with a white centre and a dark ring of radius 3.5 px.
    let m = FourBar::default();
    let motion = four_bar_motion(&m, 7);
    let (o, d) = ([0.0, 0.0], [m.d, 0.0]);
    let drawing = bare()
        .pivot(o)
        .pivot(d)
        .link([Pt::from(o), Pt::point("b")])
        .body(["b", "c", "p"])
        .link([Pt::point("c"), Pt::from(d)])
        .trace("p");
    for (i, pose) in motion.poses.iter().enumerate() {
        let (rgba, w, _) = render(&drawing.svg(&motion, i).unwrap());
        for (j, p) in four_bar_joints(&m, pose.x[0]).into_iter().enumerate() {
            let [x, y] = window_px(WINDOW, WIDTH, p);
            let k = 4 * (y as u32 * w + x as u32) as usize;
            let [red, green, blue] = [rgba[k], rgba[k + 1], rgba[k + 2]];
            if j == 2 {
                // The traced point P carries the trace's orange dot (#d95f02).
                assert!(
                    red > 180 && green < 140 && blue < 60,
                    "pose {i}: P's dot at ({x}, {y}) is {:?}",
                    [red, green, blue]
                );
            } else {
                assert!(ink(&rgba, w, x as u32, y as u32) < 60.0, "pose {i}, joint {j}: a light centre at ({x}, {y})");
            }
            for (dx, dy) in [(3.5, 0.0), (-3.5, 0.0), (0.0, 3.5), (0.0, -3.5)] {
                let d = ink(&rgba, w, (x + dx) as u32, (y + dy) as u32);
                assert!(d > 100.0, "pose {i}, joint {j}: the ring at ({}, {}) is dark ({d})", x + dx, y + dy);
            }
        }
    }
}

#[test]
fn slider_blocks_and_gears_land_on_their_pixels() {
    let m = SliderCrank::default();
    let motion = Motion::record(&m, m.sweep(0.0, TAU, 9, &m.guess(0.0)).unwrap()).unwrap();
    for (i, pose) in motion.poses.iter().enumerate() {
        let want = window_px(SLIDER_WINDOW, WIDTH, slider_position(&m, pose.x[0]));
        let canvas = || Canvas { window: Some(SLIDER_WINDOW), ..canvas() };
        // A guide turning with the state has no ground line: the block alone.
        let block = bare().with_canvas(canvas()).slider("c", Scalar::expr(|s| 0.3 * s.x[0]));
        assert_near(centroid(&block.svg(&motion, i).unwrap()).0, want, &format!("slider block, pose {i}"));
        // A fixed gear of radius 1 about C: teeth and pitch circle symmetric about it (a
        // turning gear's spoke would pull the centroid off the centre).
        let gear = bare().with_canvas(canvas()).gear("c", 1.0, 0.0);
        assert_near(centroid(&gear.svg(&motion, i).unwrap()).0, want, &format!("gear, pose {i}"));
    }
}

#[test]
fn fixed_points_and_expressions_land_on_their_pixels() {
    let m = FourBar::default();
    let motion = four_bar_motion(&m, 5);
    let r = m.r;
    let crank_pin = Pt::expr(move |s| [r * s.x[0].cos(), r * s.x[0].sin()]);
    for (i, pose) in motion.poses.iter().enumerate() {
        let svg = bare().joint(crank_pin.clone()).svg(&motion, i).unwrap();
        assert_near(centroid(&svg).0, window_px(WINDOW, WIDTH, four_bar_joints(&m, pose.x[0])[0]), "expression");
        let svg = bare().joint(Pt::fixed(m.d, 0.0)).svg(&motion, i).unwrap();
        assert_near(centroid(&svg).0, window_px(WINDOW, WIDTH, [m.d, 0.0]), "fixed point");
    }
}
