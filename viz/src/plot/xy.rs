//! x-y charts with equal scales on both axes: paths of points, a linkage at one position.

use super::frame::{Frame, LEFT, TITLE_FONT, WIDTH, left_margin};
use super::series::bounds;
use super::svg::Svg;
use super::ticks::{Ticks, binade};
use super::{Axis, Kind, PlotError, Series, legend};

/// Largest plot area height in pixels.
const MAX_H: f64 = 460.0;

/// An x-y chart of `series` and marked points with equal scales on both axes (a circle looks
/// round), as an SVG document. Both axes must hold the same kind (e.g. lengths in mm), and so
/// must every curve.
///
/// ```
/// use kinloop_viz::plot::{Axis, Kind, Series, xy_chart_svg};
/// let circle: Vec<(f64, f64)> = (0..=90).map(|i| (i as f64 / 90.0 * std::f64::consts::TAU).sin_cos()).collect();
/// let mm = Kind::length("mm");
/// let svg = xy_chart_svg("Path", &Axis::length("x", "mm"), &Axis::length("y", "mm"),
///                        &[Series::new("coupler point", mm, circle)], &[(0.0, 0.0)])?;
/// assert!(svg.contains("y [mm]"));
/// # Ok::<(), kinloop_viz::plot::PlotError>(())
/// ```
pub fn xy_chart_svg(
    title: &str,
    x: &Axis,
    y: &Axis,
    series: &[Series],
    marks: &[(f64, f64)],
) -> Result<String, PlotError> {
    x.check()?;
    y.check()?;
    if x.kind != y.kind {
        return Err(PlotError::UnequalAxes { x: x.kind.clone(), y: y.kind.clone() });
    }
    if let Some(s) = series.iter().find(|s| s.kind != x.kind) {
        return Err(PlotError::MixedKinds {
            axis: x.name.clone(),
            expected: Box::new(x.kind.clone()),
            series: s.label.clone(),
            found: Box::new(s.kind.clone()),
        });
    }
    let (x0, x1, y0, y1) = bounds(series.iter().flat_map(|s| s.points.iter()).chain(marks).copied())
        .ok_or(PlotError::Empty { what: "the figure".into() })?;
    let k = &x.kind;
    // Scaled (see `Ticks`): both axes by one power of two, so the spans, centres and the
    // common scale below cannot overflow, and subnormal data keep their precision.
    let unit = binade(x0.abs().max(x1.abs()).max(y0.abs()).max(y1.abs()));
    let n = |v: f64| v / unit * k.factor();
    let (x0, x1, y0, y1) = (n(x0), n(x1), n(y0), n(y1));
    let legend_w = legend::width(series.iter().map(|s| s.label.as_str()));
    // Laid out with the usual left margin, then again with a wider one where the y tick
    // labels need it (values of many digits).
    let area = |left: f64| {
        let w = WIDTH - left - 24.0 - if legend_w > 0.0 { legend_w + 16.0 } else { 0.0 };
        plot_area((x0, x1, y0, y1), unit, k, w)
    };
    let (mut left, (mut w, mut h, mut xt, mut yt)) = (LEFT, area(LEFT));
    if left_margin([&yt]) > LEFT {
        left = left_margin([&yt]);
        (w, h, xt, yt) = area(left);
    }
    let top = if title.is_empty() { 16.0 } else { 48.0 };
    // Taller where the legend is taller than the plot area and the room under it.
    let legend_h = legend::height(series.iter().map(|s| s.label.as_str()));
    let mut svg = Svg::new(WIDTH, top + (h + 64.0).max(legend_h + legend::BELOW));
    if !title.is_empty() {
        svg.text("title", WIDTH / 2.0, 30.0, TITLE_FONT, "middle", 0.0, title);
    }
    let frame = Frame { x: left, y: top, w, h, xt, yt };
    svg.open("panel");
    frame.draw(&mut svg, Some(x), y);
    svg.clip("area0", (frame.x, frame.y), (frame.w, frame.h));
    for (c, s) in series.iter().enumerate() {
        svg.curve(&s.label, s.points.iter().map(|&p| frame.px(p)), (legend::color(c), legend::dash(c)), "area0");
    }
    for &m in marks.iter().filter(|(x, y)| x.is_finite() && y.is_finite()) {
        svg.dot("mark", frame.px(m), 4.0, "black");
    }
    let labels: Vec<&str> = series.iter().map(|s| s.label.as_str()).collect();
    legend::draw(&mut svg, (frame.right() + 16.0, frame.y), &labels, legend_w);
    svg.close();
    Ok(svg.finish())
}

/// The plot area of an x-y chart of data in `(x0, x1, y0, y1)` (scaled by `unit` and shown
/// units of `k`) `w` pixels wide: its height and the ticks of both axes, one scale on both.
fn plot_area((x0, x1, y0, y1): (f64, f64, f64, f64), unit: f64, k: &Kind, w: f64) -> (f64, f64, Ticks, Ticks) {
    // Scaled shown units per pixel, with a margin, from the axis that needs more.
    let mut span = ((x1 - x0) / w).max((y1 - y0) / MAX_H);
    if span == 0.0 {
        // A lone point: a window of a fifth of its distance from the origin on either side
        // (scale-free: a nonzero scaled coordinate is at least 1).
        span = x0.abs().max(y0.abs()).max(1.0) * 0.2 / w;
    }
    // A window narrower than the spacing of doubles at its centre maps every point to one
    // coordinate (0/0 in pixels): at least 2^-40 of the largest scaled coordinate, about 1e-12
    // relative, far below what a drawing can show.
    let largest = x0.abs().max(x1.abs()).max(y0.abs()).max(y1.abs());
    span = span.max(largest * (-40f64).exp2() / w);
    let scale = 1.08 * span;
    let h = ((y1 - y0) / scale * 1.08).clamp(MAX_H / 2.0, MAX_H);
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (hx, hy) = (scale * w / 2.0, scale * h / 2.0);
    // The step from the range; the range itself kept as is (not taken to a tick), so that both
    // axes keep the one scale.
    let step = Ticks::scaled(cx - hx, cx + hx, unit, k.factor(), k.is_angle(), false, 0.0);
    let xt = Ticks::with_step(cx - hx, cx + hx, &step);
    // The same step on both axes: equal scales read best with equal grid squares.
    let yt = Ticks::with_step(cy - hy, cy + hy, &xt);
    (w, h, xt, yt)
}
