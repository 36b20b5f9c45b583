//! The picture's frame: its size in pixels and the map from mechanism units to pixels.

use super::error::DrawError;

/// Size of the picture and which part of the plane it shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Canvas {
    /// Width of the picture in pixels (default 480).
    pub width: f64,
    /// Room left around the mechanism, in pixels (default 24), when it is fitted.
    pub margin: f64,
    /// The rectangle of the plane shown, `[x0, y0, x1, y1]` in mechanism units; `None` (the
    /// default) fits every pose of the motion. With a window, a point `(x, y)` lands on pixel
    /// `((x - x0) / (x1 - x0) * width, (y1 - y) / (x1 - x0) * width)` (Y points up in the
    /// mechanism, down in the picture), and the height is `(y1 - y0) / (x1 - x0) * width`.
    pub window: Option<[f64; 4]>,
}

impl Default for Canvas {
    fn default() -> Self {
        Canvas { width: 480.0, margin: 24.0, window: None }
    }
}

/// Fitted pictures are at most this many times as high as wide.
const MAX_ASPECT: f64 = 1.25;

impl Canvas {
    pub(crate) fn check(&self) -> Result<(), DrawError> {
        if !(self.width.is_finite() && self.width > 0.0) {
            return Err(DrawError::InvalidSetting(format!("canvas width {} must be positive", self.width)));
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

    /// The view showing `pts` (or the window).
    pub(crate) fn view(&self, pts: &[[f64; 2]]) -> Result<View, DrawError> {
        if let Some([x0, y0, x1, y1]) = self.window {
            let scale = self.width / (x1 - x0);
            return Ok(View { x0, y1, ox: 0.0, oy: 0.0, scale, width: self.width, height: (y1 - y0) * scale });
        }
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for [x, y] in pts {
            (x0, x1, y0, y1) = (x0.min(*x), x1.max(*x), y0.min(*y), y1.max(*y));
        }
        if x0 > x1 {
            return Err(DrawError::InvalidSetting("the drawing has no item to draw".into()));
        }
        let (inner, tall) = (self.width - 2.0 * self.margin, MAX_ASPECT * self.width - 2.0 * self.margin);
        let (dx, dy) = (x1 - x0, y1 - y0);
        let mut scale = if dx > 0.0 { inner / dx } else { f64::INFINITY };
        if dy > 0.0 {
            scale = scale.min(tall / dy);
        }
        if !scale.is_finite() {
            // A lone point has no extent to fit: show it at the scale of its distance from the
            // origin (scale-free), or at any scale when it is the origin.
            let r = x0.abs().max(y0.abs());
            scale = if r > 0.0 { inner / (2.0 * r) } else { 1.0 };
        }
        let ox = self.margin + (inner - dx * scale) / 2.0;
        let height = dy * scale + 2.0 * self.margin;
        Ok(View { x0, y1, ox, oy: self.margin, scale, width: self.width, height })
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
    /// The pixel of point `(x, y)` (Y up in the mechanism, down in the picture).
    pub fn px(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [self.ox + (x - self.x0) * self.scale, self.oy + (self.y1 - y) * self.scale]
    }
}
