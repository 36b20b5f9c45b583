//! PNG frames (feature `png`): one per key frame, at the zoomed size, each showing the joint on
//! the zoomed closed-form pixel. Run with `cargo test -p kinloop-viz --features png`.
#![cfg(feature = "png")]

use kinloop_viz::draw::{Animation, Annotate, Canvas, DrawError, Drawing, Motion, png};
use resvg::tiny_skia::Pixmap;
use std::f64::consts::TAU;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

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
