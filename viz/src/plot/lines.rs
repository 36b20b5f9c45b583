//! Line charts: curves against a common x axis, in one or several stacked panels, each panel
//! with its own value axis of one quantity kind.

use super::frame::{Frame, TITLE_FONT, WIDTH, left_margin};
use super::series::bounds;
use super::svg::Svg;
use super::ticks::Ticks;
use super::{Axis, Panel, PlotError, Series, legend};

/// Height of one panel's plot area and the space between panels (x tick labels).
const PANEL_H: f64 = 250.0;
const GAP: f64 = 44.0;

/// A line chart of `series` (all of the kind of `y`) against `x`, as an SVG document.
///
/// ```
/// use kinloop_viz::plot::{Axis, Kind, Series, line_chart_svg};
/// let phi: Vec<f64> = (0..=72).map(|i| i as f64 * std::f64::consts::TAU / 72.0).collect();
/// let x: Vec<f64> = phi.iter().map(|p| 30.0 * p.cos() + 90.0).collect();
/// let svg = line_chart_svg(
///     "Slider",
///     &Axis::angle("crank angle φ"),
///     &Axis::length("slider position x", "mm"),
///     &[Series::columns("x", Kind::length("mm"), &phi, &x)],
/// )?;
/// assert!(svg.contains("crank angle φ [°]") && svg.contains(">270<"));
/// # Ok::<(), kinloop_viz::plot::PlotError>(())
/// ```
pub fn line_chart_svg(title: &str, x: &Axis, y: &Axis, series: &[Series]) -> Result<String, PlotError> {
    let panel = Panel { axis: y.clone(), series: series.to_vec(), marks: Vec::new() };
    panels_svg(title, x, std::slice::from_ref(&panel))
}

/// Panels stacked over a common x axis, each with its own value axis, curves, marked points
/// and legend (right of its plot area), as an SVG document.
///
/// Errors: a curve whose kind differs from its panel's axis ([`PlotError::MixedKinds`]), a
/// figure or panel without a finite point ([`PlotError::Empty`]).
pub fn panels_svg(title: &str, x: &Axis, panels: &[Panel]) -> Result<String, PlotError> {
    x.check()?;
    for p in panels {
        p.check()?;
    }
    let all = panels.iter().flat_map(|p| p.series.iter().flat_map(|s| s.points.iter()).chain(p.marks.iter()));
    let (x0, x1, _, _) = bounds(all.copied()).ok_or_else(|| PlotError::Empty { what: "the figure".into() })?;
    let xt = Ticks::new(x0, x1, x.kind.factor(), x.kind.is_angle(), false, 0.0);
    let legend_w = legend::width(panels.iter().flat_map(|p| p.series.iter().map(|s| s.label.as_str())));
    let top = if title.is_empty() { 16.0 } else { 48.0 };
    // Each panel's slot, from the top of its plot area to the next one's: longer where its
    // legend is taller than the slot, so that every legend stays in the picture.
    let slots = legend::slots(panels, PANEL_H + GAP);
    let height = top + slots.iter().sum::<f64>() + 20.0;
    let mut svg = Svg::new(WIDTH, height);
    if !title.is_empty() {
        svg.text("title", WIDTH / 2.0, 30.0, TITLE_FONT, "middle", 0.0, title);
    }
    let mut yts = Vec::with_capacity(panels.len());
    for p in panels {
        let what = || PlotError::Empty { what: format!("the panel `{}`", p.axis.name) };
        let (_, _, y0, y1) =
            bounds(p.series.iter().flat_map(|s| s.points.iter()).chain(&p.marks).copied()).ok_or_else(what)?;
        yts.push(Ticks::new(y0, y1, p.axis.kind.factor(), p.axis.kind.is_angle(), true, 0.03));
    }
    // One left margin for every panel, wide enough for the widest y tick label.
    let left = left_margin(&yts);
    let plot_w = WIDTH - left - 24.0 - if legend_w > 0.0 { legend_w + 16.0 } else { 0.0 };
    for (k, (p, yt)) in panels.iter().zip(yts).enumerate() {
        let frame =
            Frame { x: left, y: top + slots[..k].iter().sum::<f64>(), w: plot_w, h: PANEL_H, xt: xt.clone(), yt };
        draw_panel(&mut svg, &frame, k, p, (k + 1 == panels.len()).then_some(x), legend_w);
    }
    Ok(svg.finish())
}

/// Draws one panel into its frame.
fn draw_panel(svg: &mut Svg, frame: &Frame, k: usize, p: &Panel, x_title: Option<&Axis>, legend_w: f64) {
    svg.open("panel");
    frame.draw(svg, x_title, &p.axis);
    let clip = format!("area{k}");
    svg.clip(&clip, (frame.x, frame.y), (frame.w, frame.h));
    for (c, s) in p.series.iter().enumerate() {
        svg.curve(&s.label, s.points.iter().map(|&pt| frame.px(pt)), (legend::color(c), legend::dash(c)), &clip);
    }
    for &m in p.marks.iter().filter(|(x, y)| x.is_finite() && y.is_finite()) {
        svg.dot("mark", frame.px(m), 4.0, "black");
    }
    let labels: Vec<&str> = p.series.iter().map(|s| s.label.as_str()).collect();
    legend::draw(svg, (frame.right() + 16.0, frame.y), &labels, legend_w);
    svg.close();
}
