//! The picture's frame: its size in pixels and the map from mechanism units to pixels.

use super::error::DrawError;

/// Size of the picture and which part of the plane it shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Canvas {
    /// Width of the picture in pixels (default 480).
    pub width: f64,
    /// Room left around everything drawn, in pixels (default 8), when the picture is fitted:
    /// the mechanism is scaled to the width (leaving room for pivot symbols, slider blocks and
    /// labels), then the picture is cropped to the bounding box of every shape, label and
    /// traced path over the whole motion, plus this.
    pub margin: f64,
    /// The rectangle of the plane shown, `[x0, y0, x1, y1]` in mechanism units; `None` (the
    /// default) fits every pose of the motion. With a window, a point `(x, y)` lands on pixel
    /// `((x - x0) / (x1 - x0) * width, (y1 - y) / (x1 - x0) * width)` (Y points up in the
    /// mechanism, down in the picture), and the window's part of the picture is
    /// `(y1 - y0) / (x1 - x0) * width` high, with the strip of annotations (scale bar, input
    /// readout, events) under it.
    pub window: Option<[f64; 4]>,
}

impl Default for Canvas {
    fn default() -> Self {
        Canvas { width: 480.0, margin: 8.0, window: None }
    }
}

/// Fitted pictures are at most this many times as high as wide.
const MAX_ASPECT: f64 = 1.25;

/// Largest width (and, times [`MAX_ASPECT`], height) of a picture in pixels: a larger one is
/// no picture any renderer draws, and its ground hatching would take that many strokes.
pub(crate) const MAX_WIDTH: f64 = 1e6;

/// Pixel coordinates farther than this from the origin are not written (see
/// [`DrawError::OffCanvas`]).
pub(crate) const FAR: f64 = 1e9;

impl Canvas {
    pub(crate) fn check(&self) -> Result<(), DrawError> {
        if !(self.width.is_finite() && self.width > 0.0 && self.width <= MAX_WIDTH) {
            return Err(DrawError::InvalidSetting(format!(
                "canvas width {} must be positive and at most {MAX_WIDTH:e} pixels",
                self.width
            )));
        }
        if !(self.margin.is_finite() && self.margin >= 0.0 && 2.0 * self.margin < self.width) {
            return Err(DrawError::InvalidSetting(format!(
                "canvas margin {} must be at least 0 and less than half the width",
                self.margin
            )));
        }
        if let Some([x0, y0, x1, y1]) = self.window
            && !([x0, y0, x1, y1].iter().all(|v| v.is_finite()) && x1 > x0 && y1 > y0)
        {
            return Err(DrawError::InvalidSetting(format!("window {:?} must have x1 > x0 and y1 > y0", self.window)));
        }
        Ok(())
    }

    /// The view showing `pts` (all finite) with `reserve` pixels more than the margin on each
    /// side (for what is drawn around the points), or the window.
    ///
    /// Differences of coordinates are taken of halves (`x / 2 - x0 / 2`), which cannot
    /// overflow for finite coordinates and, halving being exact, give the same pixels as the
    /// plain difference wherever that one is finite.
    pub(crate) fn view(&self, pts: &[[f64; 2]], reserve: f64) -> Result<View, DrawError> {
        if let Some([x0, y0, x1, y1]) = self.window {
            let scale = 0.5 * self.width / (0.5 * x1 - 0.5 * x0);
            let height = 2.0 * ((0.5 * y1 - 0.5 * y0) * scale);
            if !(scale.is_finite() && height.is_finite() && height > 0.0 && height <= MAX_ASPECT * MAX_WIDTH) {
                return Err(DrawError::InvalidSetting(format!(
                    "window {:?} at {} pixels wide gives a picture {height:e} pixels high \
                     ({scale:e} pixels per unit): it must be more than 0 and at most {:e}",
                    self.window,
                    self.width,
                    MAX_ASPECT * MAX_WIDTH
                )));
            }
            return Ok(View { x0, y1, ox: 0.0, oy: 0.0, scale, width: self.width, height });
        }
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for [x, y] in pts {
            (x0, x1, y0, y1) = (x0.min(*x), x1.max(*x), y0.min(*y), y1.max(*y));
        }
        if x0 > x1 {
            return Err(DrawError::InvalidSetting("the drawing has no item to draw".into()));
        }
        // The reserve leaves at least half the room inside the margins to the mechanism.
        let margin = self.margin + reserve.min(0.25 * self.width - 0.5 * self.margin).max(0.0);
        let (inner, tall) = (self.width - 2.0 * margin, MAX_ASPECT * self.width - 2.0 * margin);
        // Half the extent on each axis.
        let (hx, hy) = (0.5 * x1 - 0.5 * x0, 0.5 * y1 - 0.5 * y0);
        let mut scale = if hx > 0.0 { 0.5 * inner / hx } else { f64::INFINITY };
        if hy > 0.0 {
            scale = scale.min(0.5 * tall / hy);
        }
        if hx == 0.0 && hy == 0.0 {
            // A lone point has no extent to fit: show it at the scale of its distance from the
            // origin (scale-free), or at any scale when it is the origin (or so near it that
            // its scale overflows: every shape sits on the one point, so any scale draws it).
            let r = x0.abs().max(y0.abs());
            scale = if r > 0.0 { inner / (2.0 * r) } else { 1.0 };
            if !scale.is_finite() {
                scale = f64::MAX;
            }
        } else if !scale.is_finite() {
            return Err(DrawError::Unscalable { width: 2.0 * hx, height: 2.0 * hy });
        }
        let ox = margin + 0.5 * inner - hx * scale;
        let height = 2.0 * (hy * scale) + 2.0 * margin;
        Ok(View { x0, y1, ox, oy: margin, scale, width: self.width, height })
    }
}

/// The map from mechanism units to pixels of one picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    x0: f64,
    y1: f64,
    ox: f64,
    oy: f64,
    /// Pixels per mechanism unit.
    pub scale: f64,
    /// Picture width in pixels.
    pub width: f64,
    /// Picture height in pixels.
    pub height: f64,
}

impl View {
    /// The same map shifted by `[dx, dy]` pixels, in a picture of `width` x `height` pixels
    /// (the fitted view cropped to what is drawn).
    pub(crate) fn cropped(&self, [dx, dy]: [f64; 2], width: f64, height: f64) -> View {
        View { ox: self.ox + dx, oy: self.oy + dy, width, height, ..*self }
    }

    /// The pixel of point `(x, y)` (Y up in the mechanism, down in the picture).
    /// Differences are taken of halves, so no finite point overflows on the way (the
    /// pixel itself can be far outside the picture, or infinite, for a point far outside a
    /// window).
    pub fn px(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [
            self.ox + 2.0 * ((0.5 * x - 0.5 * self.x0) * self.scale),
            self.oy + 2.0 * ((0.5 * self.y1 - 0.5 * y) * self.scale),
        ]
    }
}
