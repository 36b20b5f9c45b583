//! Shared by the `draw` tests: mechanisms with their closed-form positions (the independent
//! reference), and rendering SVG to pixels with resvg.

use resvg::{tiny_skia, usvg};

kinloop::mechanism! {
    /// Four-bar: crank `r` at O = (0, 0), coupler BC (`l`) carrying P at `e` from B at angle
    /// `delta` to BC, rocker `k` pivoted at D = (d, 0).
    pub struct FourBar {
        params r = 1.0, l = 3.5, k = 3.0, d = 4.0, e = 2.5, delta = 0.7;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop obcd: r @ phi + l @ beta == (d, 0) + k @ gamma;
        point b = r @ phi;
        point c = (d, 0) + k @ gamma;
        point p = r @ phi + e @ (beta + delta);
    }
}

kinloop::mechanism! {
    /// Offset slider-crank: crank `r` at the origin, rod `l`, slider C on the line y = `e`.
    pub struct SliderCrank {
        params r = 1.0, l = 3.0, e = 0.4;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oabo: r @ phi == (x, e) + l @ psi;
        point b = r @ phi;
        point c = (x, e);
    }
}

kinloop::mechanism! {
    /// A crank `r` at O = (0, 0) whose pin B is tied to the fixed point D = (d, 0) by the
    /// vector `(x, y)`, both coordinates unknown: nothing keeps |BD| constant, so `(x, y)` is no
    /// link but a construction vector. With sensitivities, to be a synthesis' candidate.
    #[kinloop(sensitivities)]
    pub struct Tied {
        params r = 1.0, d = 3.0;
        input phi;
        unknowns x = 2, y = 0;
        loop tie: r @ phi + (x, y) == (d, 0);
        point b = r @ phi;
    }
}

/// Closed form of the four-bar's joints `[B, C, P]` at crank angle `phi`, with C to the left
/// of B->D (the declared assembly mode): C is where the circles (B, l) and (D, k) meet.
pub fn four_bar_joints(m: &FourBar, phi: f64) -> [[f64; 2]; 3] {
    let b = [m.r * phi.cos(), m.r * phi.sin()];
    let v = [m.d - b[0], -b[1]];
    let dist = v[0].hypot(v[1]);
    let along = (m.l * m.l - m.k * m.k + dist * dist) / (2.0 * dist);
    let h = (m.l * m.l - along * along).sqrt();
    let c = [b[0] + (along * v[0] - h * v[1]) / dist, b[1] + (along * v[1] + h * v[0]) / dist];
    let beta = (c[1] - b[1]).atan2(c[0] - b[0]);
    let p = [b[0] + m.e * (beta + m.delta).cos(), b[1] + m.e * (beta + m.delta).sin()];
    [b, c, p]
}

/// Closed form of the slider-crank's slider C at crank angle `phi`, on the declared branch:
/// the loop reads C + l @ psi = B, and the guess `psi = 0` puts C to the left of B
/// (`cos psi > 0`).
pub fn slider_position(m: &SliderCrank, phi: f64) -> [f64; 2] {
    let (s, c) = phi.sin_cos();
    [m.r * c - (m.l * m.l - (m.r * s - m.e).powi(2)).sqrt(), m.e]
}

/// The pixel of `(x, y)` in a picture `width` pixels wide showing `window = [x0, y0, x1, y1]`,
/// computed from the documented rule (not by the library).
pub fn window_px(window: [f64; 4], width: f64, [x, y]: [f64; 2]) -> [f64; 2] {
    let s = width / (window[2] - window[0]);
    [(x - window[0]) * s, (window[3] - y) * s]
}

/// Renders `svg` at its own size: RGBA pixels, width, height.
pub fn render(svg: &str) -> (Vec<u8>, u32, u32) {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).expect("the SVG parses");
    let size = tree.size().to_int_size();
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height()).expect("a picture");
    resvg::render(&tree, tiny_skia::Transform::identity(), &mut pixmap.as_mut());
    (pixmap.data().to_vec(), size.width(), size.height())
}

/// Darkness of pixel `(i, j)` over white paper: 0 white, 255 black (mean of the channels; the
/// pixels are premultiplied, so a transparent one, beyond the picture's last whole pixel, is
/// white).
pub fn ink(rgba: &[u8], width: u32, i: u32, j: u32) -> f64 {
    let k = 4 * (j * width + i) as usize;
    let paper = 255.0 - rgba[k + 3] as f64;
    255.0 - (rgba[k] as f64 + rgba[k + 1] as f64 + rgba[k + 2] as f64) / 3.0 - paper
}

/// The darkness-weighted centre of all ink, in pixel coordinates (pixel `(i, j)` covers
/// `[i, i + 1] x [j, j + 1]`, so its centre is at `i + 0.5`), and the total ink.
pub fn centroid(svg: &str) -> ([f64; 2], f64) {
    let (rgba, w, h) = render(svg);
    let (mut sx, mut sy, mut total) = (0.0, 0.0, 0.0);
    for j in 0..h {
        for i in 0..w {
            let d = ink(&rgba, w, i, j);
            sx += d * (i as f64 + 0.5);
            sy += d * (j as f64 + 0.5);
            total += d;
        }
    }
    ([sx / total, sy / total], total)
}
