//! PNG frames of drawings, rendered with resvg (feature `png`). For slides and documents that
//! cannot show SVG. Text (labels, readouts, a chart's ticks and titles) is drawn with a built-in
//! stroke font, so no font is loaded and every machine renders the same pixels.

use super::compose::Animation;
use super::error::DrawError;
use super::motion::Motion;
use super::spec::Drawing;
use super::text_paths::outline;
use resvg::{tiny_skia, usvg};

/// Most pixels of one PNG render (2^27, e.g. 16384 x 8192: half a gigabyte of pixels being
/// drawn). A larger picture (a drawing's canvas of a million pixels, a large zoom) is
/// [`DrawError::InvalidSetting`] before anything is allocated.
pub const MAX_PIXELS: u64 = 1 << 27;

/// Renders an SVG document (a drawing, or a chart of `kinloop_viz::plot`) to PNG bytes at
/// `zoom` times its size in pixels, its text drawn with the built-in stroke font.
///
/// Errors: a zoom that is not positive and finite, or a picture of more than [`MAX_PIXELS`]
/// pixels at that zoom ([`DrawError::InvalidSetting`]); a document that is not SVG
/// ([`DrawError::Render`]).
pub fn render(svg: &str, zoom: f32) -> Result<Vec<u8>, DrawError> {
    if !(zoom.is_finite() && zoom > 0.0) {
        return Err(DrawError::InvalidSetting(format!("zoom {zoom} must be positive")));
    }
    let svg = outline(svg).map_err(DrawError::Render)?;
    let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).map_err(|e| DrawError::Render(e.to_string()))?;
    // The size at this zoom, counted before any pixel is allocated (in f64: no overflow).
    let (w, h) = (tree.size().width() as f64 * zoom as f64, tree.size().height() as f64 * zoom as f64);
    if w.ceil() * h.ceil() > MAX_PIXELS as f64 {
        return Err(DrawError::InvalidSetting(format!(
            "a render of {w:.0} x {h:.0} pixels (zoom {zoom}) is more than {MAX_PIXELS} pixels: use a smaller zoom or canvas"
        )));
    }
    let size = tree.size().to_int_size().scale_by(zoom).ok_or_else(|| DrawError::Render("empty picture".into()))?;
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| DrawError::Render(format!("cannot allocate {}x{} pixels", size.width(), size.height())))?;
    resvg::render(&tree, tiny_skia::Transform::from_scale(zoom, zoom), &mut pixmap.as_mut());
    pixmap.encode_png().map_err(|e| DrawError::Render(e.to_string()))
}

/// The key frames of the animation `anim` of `motion` as PNG images (one still per key
/// frame, forward only), at `zoom` times the drawing's size.
pub fn frames(d: &Drawing, motion: &Motion, anim: &Animation, zoom: f32) -> Result<Vec<Vec<u8>>, DrawError> {
    d.key_poses(motion, anim)?.into_iter().map(|pose| render(&d.svg(motion, pose)?, zoom)).collect()
}
