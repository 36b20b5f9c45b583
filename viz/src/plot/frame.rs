//! The plot area of one panel: its pixel rectangle, the ticks of both axes and the mapping from
//! data to pixels; draws the frame, grid, tick labels and axis titles.

use super::Axis;
use super::svg::Svg;
use super::ticks::Ticks;

/// Canvas width in pixels.
pub(crate) const WIDTH: f64 = 900.0;
/// Left margin: y tick labels and the rotated y title (more where the labels are wider, see
/// [`left_margin`]).
pub(crate) const LEFT: f64 = 96.0;
/// Font sizes of the title, axis titles and tick labels.
pub(crate) const TITLE_FONT: f64 = 20.0;
pub(crate) const AXIS_FONT: f64 = 14.0;
pub(crate) const TICK_FONT: f64 = 12.0;

/// Approximate width in pixels of a tick label (sans-serif averages about 0.6 em a character).
fn label_width(label: &str) -> f64 {
    0.6 * TICK_FONT * label.chars().count() as f64
}

/// Room left of the y tick labels for the rotated y title, and between a label and its tick.
const TITLE_ROOM: f64 = 30.0;
const LABEL_GAP: f64 = 8.0;

/// The left margin for value axes with ticks `ys`: [`LEFT`], or more where the widest label
/// (a value of many digits) would reach the axis title or the picture's edge.
pub(crate) fn left_margin<'t>(ys: impl IntoIterator<Item = &'t Ticks>) -> f64 {
    let widest =
        ys.into_iter().flat_map(|t| t.values.iter().map(move |&(_, k)| label_width(&t.label(k)))).fold(0.0, f64::max);
    // At most a third of the figure (labels have at most about twenty digits).
    LEFT.max((TITLE_ROOM + widest + LABEL_GAP).ceil()).min(WIDTH / 3.0)
}

/// Which ticks of an axis are labelled: every `n`-th.
struct Every {
    n: i128,
    /// The ticks whose index `k` is a multiple of `n`, or else those at positions `0, n, 2n...`.
    on_multiples: bool,
}

impl Every {
    /// Whether tick `k`, at position `i` along the axis, is labelled.
    fn labels(&self, i: usize, k: i128) -> bool {
        if self.on_multiples { k.rem_euclid(self.n) == 0 } else { (i as i128).rem_euclid(self.n) == 0 }
    }
}

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

    /// Which x ticks are labelled: all, or where neighbouring labels would run into each other
    /// (values of many digits), every `n`-th, so that they stand apart.
    fn x_labels_every(&self) -> Every {
        let widest = self.xt.values.iter().map(|&(_, k)| label_width(&self.xt.label(k))).fold(0.0, f64::max);
        let gap = match self.xt.values.as_slice() {
            [a, b, ..] => (self.xt.frac_scaled(b.0) - self.xt.frac_scaled(a.0)) * self.w,
            _ => f64::INFINITY,
        };
        let n = if gap > 0.0 { ((widest + LABEL_GAP) / gap).ceil().clamp(1.0, 1e6) as i128 } else { 1 };
        // On the multiples of `n` (zero among them) where there are any, else from the first.
        let on_multiples = self.xt.values.iter().any(|&(_, k)| k.rem_euclid(n) == 0);
        Every { n, on_multiples }
    }

    /// Draws grid lines, the frame, tick labels and the axis titles (`x_title` only when given:
    /// stacked panels name the shared x axis once, under the last).
    pub fn draw(&self, svg: &mut Svg, x_title: Option<&Axis>, y: &Axis) {
        let (x0, y0, x1, y1) = (self.x, self.y, self.x + self.w, self.y + self.h);
        let every = self.x_labels_every();
        for (i, &(v, k)) in self.xt.values.iter().enumerate() {
            let px = x0 + self.xt.frac_scaled(v) * self.w;
            svg.line("grid", (px, y0), (px, y1), "#e3e3e3", 1.0);
            svg.line("tick", (px, y1), (px, y1 + 5.0), "black", 1.0);
            if every.labels(i, k) {
                svg.text("tick-label x", px, y1 + 19.0, TICK_FONT, "middle", 0.0, &self.xt.label(k));
            }
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
