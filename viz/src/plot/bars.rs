//! Bar charts: values at discrete abscissae (the orders of a Fourier series, cases of a
//! study) drawn as bars from zero, grouped when a panel holds several series.

use super::frame::{Frame, TITLE_FONT, WIDTH, left_margin};
use super::series::bounds;
use super::svg::Svg;
use super::ticks::{Ticks, binade};
use super::{Axis, Panel, PlotError, legend};

/// Height of one panel's plot area and the space between panels (x tick labels).
const PANEL_H: f64 = 220.0;
const GAP: f64 = 44.0;

/// Most abscissae ticked one by one when they are whole numbers (orders 1 to 24).
const MAX_WHOLE_TICKS: usize = 24;

/// Part of the space between neighbouring abscissae that a group of bars fills.
const GROUP: f64 = 0.8;

/// Panels of bars over a common x axis, as an SVG document: each series of a panel is one bar
/// per point `(x, y)`, from 0 to `y`, the series of a panel side by side at each `x`. Every
/// value axis includes 0 (bars start there: an amplitude's axis runs from 0, never below it),
/// and whole-number abscissae such as harmonic orders are each ticked.
///
/// As with [`panels_svg`](super::panels_svg), a panel's axis holds one kind: amplitudes in N
/// and in N m go on two panels, and a series of another kind than its panel is
/// [`PlotError::MixedKinds`].
///
/// ```
/// use kinloop_viz::plot::{Axis, Kind, Panel, Series, bar_chart_svg};
/// let orders = |a: &[f64]| a.iter().enumerate().map(|(k, &v)| ((k + 1) as f64, v)).collect();
/// let svg = bar_chart_svg("Harmonics", &Axis::new("order", Kind::Dimensionless), &[
///     Panel::new(Axis::new("force amplitude", Kind::force("N")))
///         .with(Series::new("Fx", Kind::force("N"), orders(&[120.0, 30.0, 4.0]))),
///     Panel::new(Axis::new("moment amplitude", Kind::torque("N m")))
///         .with(Series::new("M", Kind::torque("N m"), orders(&[8.0, 2.0, 0.5]))),
/// ])?;
/// assert_eq!(svg.matches(r#"class="bar""#).count(), 6);
/// # Ok::<(), kinloop_viz::plot::PlotError>(())
/// ```
pub fn bar_chart_svg(title: &str, x: &Axis, panels: &[Panel]) -> Result<String, PlotError> {
    x.check()?;
    for p in panels {
        p.check()?;
    }
    let mut xs: Vec<f64> = panels
        .iter()
        .flat_map(|p| p.series.iter().flat_map(|s| s.points.iter()))
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .map(|&(x, _)| x)
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    if xs.is_empty() {
        return Err(PlotError::Empty { what: "the figure".into() });
    }
    // The narrowest space between neighbouring abscissae sets the width of a group of bars;
    // a lone abscissa gets a unit's (or its own magnitude's) room. Worked out scaled by a
    // power of two `u` (exact), so that neither the spacing nor the room around the bars
    // overflows for abscissae near the ends of the f64 range; the same numbers otherwise.
    let (first, last) = (xs[0], xs[xs.len() - 1]);
    let lone = if xs.len() == 1 { 1.0 } else { 0.0 };
    let u = binade(first.abs().max(last.abs()).max(lone));
    let spacing = xs.windows(2).map(|w| w[1] / u - w[0] / u).filter(|d| *d > 0.0).fold(f64::INFINITY, f64::min);
    let spacing = if spacing.is_finite() { spacing } else { (first / u).abs().max(1.0 / u) };
    let (lo, hi) = (first / u - 0.5 * spacing, last / u + 0.5 * spacing);
    // Whole numbers are ticked one by one only where the axis holds few of them: two bars
    // at orders 0 and a million are no million ticks (each a grid line and a label).
    let whole = xs.len() <= MAX_WHOLE_TICKS
        && xs.iter().all(|v| v.fract() == 0.0 && v.abs() < 1e15)
        && (hi - lo) * u <= 2.0 * MAX_WHOLE_TICKS as f64;
    let xt = if whole && !x.kind.is_angle() {
        Ticks::whole(lo * u, hi * u)
    } else {
        // The ticks' own scale (see `Ticks::new`), kept within the f64 range.
        let b = binade(lo.abs().max(hi.abs()));
        let (unit, b) = if (u * b).is_finite() { (u * b, b) } else { (u, 1.0) };
        let f = x.kind.factor();
        Ticks::scaled(lo / b * f, hi / b * f, unit, f, x.kind.is_angle(), false, 0.0)
    };
    // The spacing as the ticks scale it.
    let spacing_scaled = spacing * (u / xt.unit) * x.kind.factor();
    let legend_w = legend::width(panels.iter().flat_map(|p| p.series.iter().map(|s| s.label.as_str())));
    let top = if title.is_empty() { 16.0 } else { 48.0 };
    // Each panel's slot, longer where its legend is taller (see `panels_svg`).
    let slots = legend::slots(panels, PANEL_H + GAP);
    let mut svg = Svg::new(WIDTH, top + slots.iter().sum::<f64>() + 20.0);
    if !title.is_empty() {
        svg.text("title", WIDTH / 2.0, 30.0, TITLE_FONT, "middle", 0.0, title);
    }
    let mut yts = Vec::with_capacity(panels.len());
    for p in panels {
        let what = || PlotError::Empty { what: format!("the panel `{}`", p.axis.name) };
        let (_, _, y0, y1) = bounds(p.series.iter().flat_map(|s| s.points.iter().copied())).ok_or_else(what)?;
        yts.push(Ticks::new(y0.min(0.0), y1.max(0.0), p.axis.kind.factor(), p.axis.kind.is_angle(), true, 0.03));
    }
    // One left margin for every panel, wide enough for the widest y tick label.
    let left = left_margin(&yts);
    let plot_w = WIDTH - left - 24.0 - if legend_w > 0.0 { legend_w + 16.0 } else { 0.0 };
    for (k, (p, yt)) in panels.iter().zip(yts).enumerate() {
        let frame =
            Frame { x: left, y: top + slots[..k].iter().sum::<f64>(), w: plot_w, h: PANEL_H, xt: xt.clone(), yt };
        svg.open("panel");
        frame.draw(&mut svg, (k + 1 == panels.len()).then_some(x), &p.axis);
        let n = p.series.len() as f64;
        // Pixel width of one bar: the group fills `GROUP` of the narrowest spacing.
        let at = |v: f64| frame.x + frame.xt.frac_scaled(v) * frame.w;
        let bar = (at(spacing_scaled) - at(0.0)).abs() * GROUP / n;
        for (c, s) in p.series.iter().enumerate() {
            for &(bx, by) in s.points.iter().filter(|(x, y)| x.is_finite() && y.is_finite()) {
                let (px, py) = frame.px((bx, by));
                let (_, base) = frame.px((bx, 0.0));
                let left = px + (c as f64 - 0.5 * (n - 1.0)) * bar - 0.5 * bar;
                svg.bar(&s.label, (left, py.min(base)), (bar, (py - base).abs()), legend::color(c));
            }
        }
        let labels: Vec<&str> = p.series.iter().map(|s| s.label.as_str()).collect();
        legend::draw_with(&mut svg, (frame.right() + 16.0, frame.y), &labels, legend_w, legend::Swatch::Square);
        svg.close();
    }
    Ok(svg.finish())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{Kind, Series};

    fn ticks(xs: &[f64]) -> usize {
        let points = xs.iter().map(|&x| (x, 1.0)).collect();
        let panel = Panel::new(Axis::length("y", "mm")).with(Series::new("s", Kind::length("mm"), points));
        let svg = bar_chart_svg("", &Axis::new("order", Kind::Dimensionless), &[panel]).unwrap();
        svg.matches(r#"class="tick""#).count()
    }

    #[test]
    fn whole_abscissae_far_apart_get_a_few_ticks_not_one_each() {
        // Orders 1 to 24: each ticked (and the value axis' ticks).
        let orders: Vec<f64> = (1..=24).map(f64::from).collect();
        let values = ticks(&[1.0]) - 1;
        assert_eq!(ticks(&orders) - values, 24);
        // Two bars a million apart: a readable axis, not a tick at every whole number.
        assert!(ticks(&[0.0, 1e6]) < 40, "{}", ticks(&[0.0, 1e6]));
        assert!(ticks(&[3.0, 1e12]) < 40);
    }
}
