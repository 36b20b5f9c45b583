//! PNG frames of drawings, rendered with resvg (feature `png`). For slides and documents that
//! cannot show SVG. Text (labels, readouts, a chart's ticks and titles) is drawn with a built-in
//! stroke font, so no font is loaded and every machine renders the same pixels.

use super::compose::Animation;
use super::error::DrawError;
use super::motion::Motion;
use super::spec::Drawing;
use super::text_paths::outline;
use resvg::{tiny_skia, usvg};

/// Renders an SVG document (a drawing, or a chart of `kinloop_viz::plot`) to PNG bytes at
/// `zoom` times its size in pixels, its text drawn with the built-in stroke font.
pub fn render(svg: &str, zoom: f32) -> Result<Vec<u8>, DrawError> {
    if !(zoom.is_finite() && zoom > 0.0) {
        return Err(DrawError::InvalidSetting(format!("zoom {zoom} must be positive")));
    }
    let svg = outline(svg).map_err(DrawError::Render)?;
    let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).map_err(|e| DrawError::Render(e.to_string()))?;
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
