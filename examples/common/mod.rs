//! Helpers shared by the examples (the library of the `kinloop-examples` package): where
//! outputs go, and line charts as SVG.

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::error::Error;
use std::path::PathBuf;

/// Output folder of an example: `$KINLOOP_OUT/<example>` (default `out/<example>`).
pub fn out_dir(example: &str) -> PathBuf {
    let base = std::env::var_os("KINLOOP_OUT").map_or_else(|| PathBuf::from("out"), PathBuf::from);
    let dir = base.join(example);
    std::fs::create_dir_all(&dir).expect("cannot create the output folder");
    dir
}

/// One curve of a chart.
pub struct Series<'a> {
    pub label: &'a str,
    pub points: Vec<(f64, f64)>,
}

const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

/// A chart with `f64` axes in an SVG file.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Smallest and largest x and y of the points whose coordinates are both finite:
/// `(x0, x1, y0, y1)`.
fn bounds<'p>(points: impl Iterator<Item = &'p (f64, f64)>) -> Result<(f64, f64, f64, f64), Box<dyn Error>> {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in points {
        if x.is_finite() && y.is_finite() {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if x0 > x1 {
        return Err("nothing to plot".into());
    }
    Ok((x0, x1, y0, y1))
}

/// Draws the curves in the palette's colours, each decimated to at most `max_points` points,
/// with their legend entries.
fn draw_curves<'b: 'a, 'a>(
    chart: &mut Chart<'a, 'b>,
    series: &[Series],
    max_points: usize,
) -> Result<(), Box<dyn Error>> {
    for (k, s) in series.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        chart
            .draw_series(LineSeries::new(decimate(&s.points, max_points), color.stroke_width(2)))?
            .label(s.label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
    }
    Ok(())
}

/// Draws the legend of the curves at `position`.
fn draw_legend<'b: 'a, 'a>(chart: &mut Chart<'a, 'b>, position: SeriesLabelPosition) -> Result<(), Box<dyn Error>> {
    chart.configure_series_labels().background_style(WHITE.mix(0.85)).border_style(BLACK).position(position).draw()?;
    Ok(())
}

/// A 900 x 520 SVG file with one titled chart over `ranges`, axes labelled `(x, y)` with a
/// y label area `width` pixels wide: the curves, each decimated to at most `max_points` points,
/// the marked points as dots, and the legend upper right.
fn single_chart(
    path: &std::path::Path,
    title: &str,
    (x_label, y_label, width): (&str, &str, u32),
    (xs, ys): (std::ops::Range<f64>, std::ops::Range<f64>),
    (series, max_points): (&[Series], usize),
    marks: &[(f64, f64)],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (900, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(width)
        .build_cartesian_2d(xs, ys)?;
    chart.configure_mesh().x_desc(x_label).y_desc(y_label).draw()?;
    draw_curves(&mut chart, series, max_points)?;
    chart.draw_series(marks.iter().map(|&(x, y)| Circle::new((x, y), 4, BLACK.filled())))?;
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    root.present()?;
    Ok(())
}

/// Draws curves into an SVG file with a title, axis labels and a legend.
pub fn line_chart(
    path: &std::path::Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), Box<dyn Error>> {
    let (x0, x1, y0, y1) = bounds(series.iter().flat_map(|s| &s.points))?;
    let pad = ((y1 - y0) * 0.05).max(1e-9);
    let ranges = (x0..x1, (y0 - pad)..(y1 + pad));
    single_chart(path, title, (x_label, y_label, 70), ranges, (series, usize::MAX), &[])
}

/// Folder for an example's figures: `$KINLOOP_FIGURES/<example>` when that variable is set
/// (`KINLOOP_FIGURES=docs/figures` regenerates the README gallery), else [`out_dir`].
pub fn figure_dir(example: &str) -> PathBuf {
    match std::env::var_os("KINLOOP_FIGURES") {
        Some(base) => {
            let dir = PathBuf::from(base).join(example);
            std::fs::create_dir_all(&dir).expect("cannot create the figure folder");
            dir
        }
        None => out_dir(example),
    }
}

/// At most `max` points of a curve, equally strided, keeping the first and the last (keeps the
/// committed SVGs small).
pub fn decimate(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    if points.len() <= max || max < 2 {
        return points.to_vec();
    }
    let stride = (points.len() - 1).div_ceil(max - 1);
    let mut out: Vec<(f64, f64)> = points.iter().step_by(stride).copied().collect();
    if out.last() != points.last() {
        out.push(points[points.len() - 1]);
    }
    out
}

/// One panel of [`panels`]: its curves, and optional marked points (drawn as circles).
pub struct Panel<'a> {
    pub y_label: &'a str,
    pub series: Vec<Series<'a>>,
    pub marks: Vec<(f64, f64)>,
}

/// Panels stacked vertically over a common x axis (like the papers' multi-curve figures), each
/// with its own y scale and legend (upper left); every curve is decimated to at most 720 points.
pub fn panels(path: &std::path::Path, title: &str, x_label: &str, panels: &[Panel]) -> Result<(), Box<dyn Error>> {
    let (mut x0, mut x1) = (f64::MAX, f64::MIN);
    for p in panels {
        for &(x, _) in p.series.iter().flat_map(|s| s.points.iter()).chain(p.marks.iter()) {
            if x.is_finite() {
                x0 = x0.min(x);
                x1 = x1.max(x);
            }
        }
    }
    if x0 >= x1 {
        return Err("nothing to plot".into());
    }
    let height = 60 + 260 * panels.len() as u32;
    let root = SVGBackend::new(path, (900, height)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let areas = root.split_evenly((panels.len(), 1));
    for (k, (p, area)) in panels.iter().zip(areas.iter()).enumerate() {
        let (mut y0, mut y1) = (f64::MAX, f64::MIN);
        for &(_, y) in p.series.iter().flat_map(|s| s.points.iter()).chain(p.marks.iter()) {
            if y.is_finite() {
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
        if y0 > y1 {
            return Err("nothing to plot in a panel".into());
        }
        let pad = ((y1 - y0) * 0.06).max(1e-9 * y1.abs().max(1.0));
        let last = k + 1 == panels.len();
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(if last { 44 } else { 24 })
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))?;
        let mut mesh = chart.configure_mesh();
        mesh.y_desc(p.y_label);
        if last {
            mesh.x_desc(x_label);
        }
        mesh.draw()?;
        draw_curves(&mut chart, &p.series, 720)?;
        if !p.marks.is_empty() {
            chart.draw_series(p.marks.iter().map(|&(x, y)| Circle::new((x, y), 4, BLACK.filled())))?;
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    }
    root.present()?;
    Ok(())
}

/// An x-y chart with equal scales on both axes (paths of points, a linkage drawn at one
/// position), with optional marked points; every curve is decimated to at most 720 points.
pub fn xy_chart(
    path: &std::path::Path,
    title: &str,
    series: &[Series],
    marks: &[(f64, f64)],
) -> Result<(), Box<dyn Error>> {
    let (x0, x1, y0, y1) = bounds(series.iter().flat_map(|s| &s.points).chain(marks))?;
    // Plot area of about 790 x 400 pixels: widen the narrower range to equal scales.
    let (w, h) = (790.0, 400.0);
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let scale = ((x1 - x0) / w).max((y1 - y0) / h) * 1.08;
    let (hx, hy) = (scale * w / 2.0, scale * h / 2.0);
    let ranges = ((cx - hx)..(cx + hx), (cy - hy)..(cy + hy));
    single_chart(path, title, ("x", "y", 60), ranges, (series, 720), marks)
}
