//! Legends, placed to the right of the plot area so that they never cover data.

use super::frame::TICK_FONT;
use super::svg::Svg;

/// Colours of successive curves (colour-blind-safe, Okabe–Ito order).
pub(crate) const COLORS: [&str; 7] = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"];

/// The colour of curve `k`.
pub(crate) fn color(k: usize) -> &'static str {
    COLORS[k % COLORS.len()]
}

/// Dash patterns of successive rounds of the colours: the first seven curves solid, the next
/// seven dashed, and so on, so that 35 curves each look different (a curve's colour alone
/// repeats every seven).
const DASHES: [&str; 5] = ["", "8 4", "2 3", "8 3 2 3", "12 3 2 3 2 3"];

/// The dash pattern of curve `k` (empty: solid).
pub(crate) fn dash(k: usize) -> &'static str {
    DASHES[(k / COLORS.len()) % DASHES.len()]
}

/// Approximate width in pixels of `text` at the tick font size (sans-serif averages about
/// 0.6 em per character).
fn text_width(text: &str) -> f64 {
    0.6 * TICK_FONT * text.chars().count() as f64
}

/// Longest label shown in full; longer ones are cut with an ellipsis so the plot keeps its room.
const MAX_CHARS: usize = 40;

/// A label as shown in the legend.
fn shown(label: &str) -> String {
    if label.chars().count() <= MAX_CHARS {
        label.to_string()
    } else {
        label.chars().take(MAX_CHARS - 1).chain(['…']).collect()
    }
}

/// Width of the legend column for these labels (0 when there is nothing to list).
pub(crate) fn width<'a>(labels: impl Iterator<Item = &'a str>) -> f64 {
    let widest = labels
        .filter(|l| !l.is_empty())
        .map(|l| text_width(&shown(l)))
        .fold(None, |m: Option<f64>, w| Some(m.map_or(w, |m| m.max(w))));
    widest.map_or(0.0, |w| w + 48.0)
}

/// Height of the legend of these labels (0 when there is nothing to list).
pub(crate) fn height<'a>(labels: impl Iterator<Item = &'a str>) -> f64 {
    match labels.filter(|l| !l.is_empty()).count() {
        0 => 0.0,
        n => 10.0 + 20.0 * n as f64,
    }
}

/// Room left under a legend before the next panel (or the figure's end).
pub(crate) const BELOW: f64 = 8.0;

/// The height of each panel's slot in a stack of `panels` (the top of its plot area to the
/// next one's): `slot`, or more where the panel's legend needs more.
pub(crate) fn slots(panels: &[super::Panel], slot: f64) -> Vec<f64> {
    panels.iter().map(|p| slot.max(height(p.series.iter().map(|s| s.label.as_str())) + BELOW)).collect()
}

/// What a legend entry shows of its series: a stretch of line (curves) or a filled square
/// (bars).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Swatch {
    Line,
    Square,
}

/// Draws the legend of `labels` (curve `k` in colour `k`) with its top-left corner at `(x, y)`.
pub(crate) fn draw(svg: &mut Svg, at: (f64, f64), labels: &[&str], width: f64) {
    draw_with(svg, at, labels, width, Swatch::Line);
}

/// [`draw`] with entries shown as `swatch`.
pub(crate) fn draw_with(svg: &mut Svg, (x, y): (f64, f64), labels: &[&str], width: f64, swatch: Swatch) {
    let entries: Vec<(usize, &&str)> = labels.iter().enumerate().filter(|(_, l)| !l.is_empty()).collect();
    if entries.is_empty() {
        return;
    }
    svg.open("legend");
    svg.rect("legend-box", (x, y), (width, 10.0 + 20.0 * entries.len() as f64), "white", "#888888");
    for (row, (k, label)) in entries.iter().enumerate() {
        let cy = y + 15.0 + 20.0 * row as f64;
        match swatch {
            Swatch::Line => svg.dashed_line("legend-line", (x + 8.0, cy), (x + 30.0, cy), color(*k), 2.0, dash(*k)),
            Swatch::Square => svg.rect("legend-swatch", (x + 13.0, cy - 6.0), (12.0, 12.0), color(*k), "none"),
        }
        svg.text("legend-label", x + 36.0, cy + 4.0, TICK_FONT, "start", 0.0, &shown(label));
    }
    svg.close();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_labels_are_cut_so_the_legend_stays_narrow() {
        let long = "a".repeat(200);
        assert_eq!(shown(&long).chars().count(), MAX_CHARS);
        assert!(width([long.as_str()].into_iter()) < 0.6 * TICK_FONT * 41.0 + 48.0);
        assert_eq!(width(["", ""].into_iter()), 0.0);
    }
}
