//! The plot area of one panel: its pixel rectangle, the ticks of both axes and the mapping from
//! data to pixels; draws the frame, grid, tick labels and axis titles.

use super::Axis;
use super::svg::Svg;
use super::ticks::Ticks;

/// Canvas width in pixels.
pub(crate) const WIDTH: f64 = 900.0;
/// Left margin: y tick labels and the rotated y title.
pub(crate) const LEFT: f64 = 96.0;
/// Font sizes of the title, axis titles and tick labels.
pub(crate) const TITLE_FONT: f64 = 20.0;
pub(crate) const AXIS_FONT: f64 = 14.0;
pub(crate) const TICK_FONT: f64 = 12.0;

/// The plot area of one panel.
pub(crate) struct Frame {
    /// Top-left corner and size in pixels.
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
    /// The ticks of both axes (and their scales, which convert values to shown units).
    pub xt: Ticks,
    pub yt: Ticks,
}

impl Frame {
    /// The pixel position of a data point (values in the library's units).
    pub fn px(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (self.x + self.xt.frac(x) * self.w, self.y + self.h - self.yt.frac(y) * self.h)
    }

    /// The right edge of the plot area.
    pub fn right(&self) -> f64 {
        self.x + self.w
    }

    /// Draws grid lines, the frame, tick labels and the axis titles (`x_title` only when given:
    /// stacked panels name the shared x axis once, under the last).
    pub fn draw(&self, svg: &mut Svg, x_title: Option<&Axis>, y: &Axis) {
        let (x0, y0, x1, y1) = (self.x, self.y, self.x + self.w, self.y + self.h);
        for &(v, k) in &self.xt.values {
            let px = x0 + self.xt.frac_scaled(v) * self.w;
            svg.line("grid", (px, y0), (px, y1), "#e3e3e3", 1.0);
            svg.line("tick", (px, y1), (px, y1 + 5.0), "black", 1.0);
            svg.text("tick-label x", px, y1 + 19.0, TICK_FONT, "middle", 0.0, &self.xt.label(k));
        }
        for &(v, k) in &self.yt.values {
            let py = y1 - self.yt.frac_scaled(v) * self.h;
            svg.line("grid", (x0, py), (x1, py), "#e3e3e3", 1.0);
            svg.line("tick", (x0 - 5.0, py), (x0, py), "black", 1.0);
            svg.text("tick-label y", x0 - 8.0, py + 4.0, TICK_FONT, "end", 0.0, &self.yt.label(k));
        }
        svg.rect("plot-area", (x0, y0), (self.w, self.h), "none", "black");
        svg.text("axis-title y", 22.0, y0 + self.h / 2.0, AXIS_FONT, "middle", -90.0, &y.title());
        if let Some(xa) = x_title {
            svg.text("axis-title x", x0 + self.w / 2.0, y1 + 42.0, AXIS_FONT, "middle", 0.0, &xa.title());
        }
    }
}
