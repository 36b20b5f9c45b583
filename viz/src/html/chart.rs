//! Small charts of a readout against the input, with a cursor the page moves with the slider.

use super::readouts::Channel;
use crate::escape::escape;
use crate::plot::ticks::{Ticks, decimal};
use std::fmt::Write;

/// Plot area insets in pixels: left (tick labels and the y title; more for wider labels, see
/// [`TITLE_ROOM`]), right, top, bottom (tick labels and the x title).
const LEFT: f64 = 58.0;
const RIGHT: f64 = 12.0;
const TOP: f64 = 10.0;
const BOTTOM: f64 = 38.0;

/// A pixel coordinate to a tenth of a pixel (as the drawing), without a trailing `.0`.
pub(crate) fn px(v: f64) -> String {
    let r = (v * 10.0).round() / 10.0 + 0.0;
    format!("{r}")
}

/// Room at the chart's left edge for the rotated y title (its glyphs reach about 17 px), and
/// the gap between a y tick label and the plot area: the left inset holds both and the widest
/// label (estimated at 0.6 em a character of the charts' 11 px text).
const TITLE_ROOM: f64 = 19.0;
const LABEL_GAP: f64 = 5.0;

/// Approximate width in pixels of a tick label (0.6 em a character of the charts' 11 px text).
fn label_width(label: &str) -> f64 {
    0.6 * 11.0 * label.chars().count() as f64
}

/// About this many intervals between ticks on each axis: fewer than the plot module's larger
/// charts, so that the labels of a small chart stay apart.
const INTERVALS: f64 = 5.0;

/// A chart's axis: its range widened to whole steps, and its ticks (shown units).
pub(crate) struct Axis {
    pub lo: f64,
    pub hi: f64,
    /// The tick values and their labels.
    pub ticks: Vec<(f64, String)>,
}

/// The axis of values in `[lo, hi]` (shown units, degrees when `degrees`), about
/// [`INTERVALS`] steps, the range widened to whole steps: the plot module's steps (1, 2, 2.5
/// or 5 times a power of ten; for degrees a division of a turn) and labels (the decimals the
/// step needs, a power of ten for very small or large values).
pub(crate) fn axis(lo: f64, hi: f64, degrees: bool) -> Axis {
    let t = Ticks::widened(lo, hi, degrees, INTERVALS);
    // The scaled values times their power of two: exact, and finite (readouts are at most
    // 1e100).
    let ticks = t.values.iter().map(|&(v, k)| (v * t.unit, t.label(k))).collect();
    Axis { lo: t.lo * t.unit, hi: t.hi * t.unit, ticks }
}

/// Room above the plot area for the offset of an axis labelled by differences
/// ([`offset_axis`]): a line of the charts' 11 px text.
const OFFSET_ROOM: f64 = 14.0;

/// [`axis`] of values in `[lo, hi]` labelled as differences from its lowest tick, and that
/// tick's value written as the offset to add (`"+2.5000000000e0"`): for values whose labels
/// would be too wide (many digits each, values far from zero that vary little).
pub(crate) fn offset_axis(lo: f64, hi: f64, degrees: bool) -> (String, Axis) {
    let t = Ticks::widened(lo, hi, degrees, INTERVALS);
    let base = t.values.first().map_or(0, |&(_, k)| k);
    // The offset with its own power of ten (`"+999.999999996"`, `"+1.000000002e7"`), exactly
    // from its integer as the ticks' labels.
    let value = base * t.mant as i128;
    let digits = value.unsigned_abs().to_string().len() as i32;
    let lead = t.exp + digits - 1;
    let offset = if value == 0 || (-4..6).contains(&lead) {
        decimal(value, t.exp)
    } else {
        format!("{}e{lead}", decimal(value, t.exp - lead))
    };
    let offset = if offset.starts_with('-') { offset } else { format!("+{offset}") };
    let ticks = t.values.iter().map(|&(v, k)| (v * t.unit, t.difference_label(k, base))).collect();
    (offset, Axis { lo: t.lo * t.unit, hi: t.hi * t.unit, ticks })
}

/// A chart's map from shown values to pixels: `px = a + b v` on each axis.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Map {
    pub x: [f64; 2],
    pub y: [f64; 2],
}

/// An axis title: `"name [unit]"`.
fn title(c: &Channel) -> String {
    format!("{} [{}]", c.label, c.kind.unit())
}

/// The chart `k` of `y` against `x` (channels at every frame; `None`: against the fraction of
/// the path, for several inputs), `size` pixels, with dashed lines at the events `events` (x
/// values, shown units); and its map.
pub(crate) fn chart(k: usize, x: Option<&Channel>, y: &Channel, events: &[f64], size: [f64; 2]) -> (String, Map) {
    let n = y.values.len();
    let xs: Vec<f64> = match x {
        Some(c) => c.values.clone(),
        None => (0..n).map(|i| i as f64 / (n.max(2) - 1) as f64).collect(),
    };
    let fold = |v: &[f64]| v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(*v), b.max(*v)));
    let (x0, x1) = fold(&xs);
    let (y0, y1) = fold(&y.values);
    let xt = axis(x0, x1, x.is_some_and(|c| c.kind.is_angle()));
    let mut yt = axis(y0, y1, y.kind.is_angle());
    let [w, h] = size;
    let room =
        |a: &Axis| TITLE_ROOM + a.ticks.iter().map(|(_, label)| label_width(label)).fold(0.0, f64::max) + LABEL_GAP;
    // Labels of values far from zero that vary little (many digits each) wider than a third
    // of the chart: labelled as differences from the lowest tick, written above the plot area.
    let offset = if room(&yt) > w / 3.0 {
        let (o, shifted) = offset_axis(y0, y1, y.kind.is_angle());
        yt = shifted;
        Some(o)
    } else {
        None
    };
    let l = LEFT.max(room(&yt).ceil()).min(w / 3.0);
    let top = if offset.is_some() { TOP + OFFSET_ROOM } else { TOP };
    let (l, r, t, b) = (l, w - RIGHT, top, h - BOTTOM);
    let bx = (r - l) / (xt.hi - xt.lo);
    let by = (b - t) / (yt.hi - yt.lo);
    let map = Map { x: [l - xt.lo * bx, bx], y: [b + yt.lo * by, -by] };
    let (fx, fy) = (|v: f64| map.x[0] + map.x[1] * v, |v: f64| map.y[0] + map.y[1] * v);
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" class="kl-chart" data-chart="{k}" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="11">"#,
        w = px(w),
        h = px(h)
    );
    let _ = write!(s, r#"<rect width="{}" height="{}" fill="white"/>"#, px(w), px(h));
    // Where neighbouring x labels (values of many digits) would run into each other, every
    // n-th tick is labelled, from the first.
    let widest_x = xt.ticks.iter().map(|(_, label)| label_width(label)).fold(0.0, f64::max);
    let every = match xt.ticks.as_slice() {
        [a, b, ..] if fx(b.0) > fx(a.0) => ((widest_x + 6.0) / (fx(b.0) - fx(a.0))).ceil().clamp(1.0, 1e6) as usize,
        _ => 1,
    };
    let inside_x = |p: f64| p >= l - 0.05 && p <= r + 0.05;
    for (i, (v, label)) in xt.ticks.iter().filter(|(v, _)| inside_x(fx(*v))).enumerate() {
        let p = px(fx(*v));
        let _ =
            write!(s, r##"<line class="kl-grid" x1="{p}" y1="{}" x2="{p}" y2="{}" stroke="#e3e3e3"/>"##, px(t), px(b));
        if i % every == 0 {
            let _ = write!(
                s,
                r#"<text class="kl-tick-x" x="{p}" y="{}" text-anchor="middle">{label}</text>"#,
                px(b + 14.0)
            );
        }
    }
    if let Some(o) = &offset {
        let _ = write!(
            s,
            r#"<text class="kl-tick-offset" x="{}" y="{}" text-anchor="start">{}</text>"#,
            px(l),
            px(t - 5.0),
            escape(o)
        );
    }
    // Ticks are multiples of a step, within rounding of the axis' ends: one a rounding beyond
    // them is not drawn, rather than drawn out of the plot area.
    let inside_y = |p: f64| p >= t - 0.05 && p <= b + 0.05;
    for (v, label) in yt.ticks.iter().filter(|(v, _)| inside_y(fy(*v))) {
        let p = px(fy(*v));
        let _ = write!(
            s,
            r##"<line class="kl-grid" x1="{}" y1="{p}" x2="{}" y2="{p}" stroke="#e3e3e3"/><text class="kl-tick-y" x="{}" y="{}" text-anchor="end">{label}</text>"##,
            px(l),
            px(r),
            px(l - LABEL_GAP),
            px(fy(*v) + 4.0)
        );
    }
    let _ = write!(
        s,
        r#"<rect class="kl-plot-area" x="{}" y="{}" width="{}" height="{}" fill="none" stroke="black"/>"#,
        px(l),
        px(t),
        px(r - l),
        px(b - t)
    );
    let x_title = x.map_or_else(|| "path [-]".to_string(), title);
    let _ = write!(
        s,
        r#"<text class="kl-axis-x" x="{}" y="{}" text-anchor="middle">{}</text><text class="kl-axis-y" x="14" y="{}" text-anchor="middle" transform="rotate(-90 14 {})">{}</text>"#,
        px((l + r) / 2.0),
        px(h - 6.0),
        escape(&x_title),
        px((t + b) / 2.0),
        px((t + b) / 2.0),
        escape(&title(y))
    );
    for v in events {
        let p = px(fx(*v));
        let _ = write!(
            s,
            r##"<line class="kl-chart-event" x1="{p}" y1="{}" x2="{p}" y2="{}" stroke="#c0143c" stroke-dasharray="4 3"/>"##,
            px(t),
            px(b)
        );
    }
    let mut pts = String::new();
    let mut last = String::new();
    for (xv, yv) in xs.iter().zip(&y.values) {
        // The axes cover the values: clamped, a point is moved by rounding at most.
        let p = format!("{},{}", px(fx(*xv).clamp(l, r)), px(fy(*yv).clamp(t, b)));
        if p != last {
            if !pts.is_empty() {
                pts.push(' ');
            }
            pts.push_str(&p);
            last = p;
        }
    }
    let _ = write!(
        s,
        r##"<polyline class="kl-curve" points="{pts}" fill="none" stroke="#1f77b4" stroke-width="1.5" stroke-linejoin="round"/>"##
    );
    let (cx, cy) = (px(fx(xs[0]).clamp(l, r)), px(fy(y.values[0]).clamp(t, b)));
    let _ = write!(
        s,
        r##"<line class="kl-cursor" x1="{cx}" y1="{}" x2="{cx}" y2="{}" stroke="#444"/><circle class="kl-cursor-dot" cx="{cx}" cy="{cy}" r="3.5" fill="#1f77b4" stroke="white"/></svg>"##,
        px(t),
        px(b)
    );
    (s, map)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(a: &Axis) -> Vec<&str> {
        a.ticks.iter().map(|(_, l)| l.as_str()).collect()
    }

    #[test]
    fn a_turn_is_ticked_every_90_degrees_up_to_360() {
        let t = axis(0.0, 360.0, true);
        assert_eq!(labels(&t), ["0", "90", "180", "270", "360"]);
        assert_eq!((t.lo, t.hi), (0.0, 360.0));
        // A sampled turn ends on the 360 tick; smaller ranges on divisions of a turn.
        assert_eq!(labels(&axis(0.0, 355.0, true)), ["0", "90", "180", "270", "360"]);
        assert_eq!(labels(&axis(0.0, 180.0, true)), ["0", "45", "90", "135", "180"]);
        assert_eq!(labels(&axis(-30.0, 40.0, true)), ["-30", "-15", "0", "15", "30", "45"]);
        assert_eq!(labels(&axis(0.0, 12.0, true)), ["0", "5", "10", "15"]);
        assert_eq!(labels(&axis(0.0, 4.0, true)), ["0", "1", "2", "3", "4"]);
    }

    #[test]
    fn decimal_steps_cover_the_data_with_their_digits() {
        let t = axis(-0.013, 0.0415, false);
        assert_eq!(labels(&t), ["-0.02", "0.00", "0.02", "0.04", "0.06"]);
        let t = axis(2.0, 2.0, false);
        assert!(t.lo < 2.0 && t.hi > 2.0);
        let t = axis(0.0, 12.5, false);
        assert_eq!(labels(&t), ["0.0", "2.5", "5.0", "7.5", "10.0", "12.5"]);
        assert_eq!(labels(&axis(0.0, 1.0, false)), ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
    }

    #[test]
    fn tiny_and_huge_values_are_labelled_with_a_power_of_ten() {
        let t = axis(-1.0e-6, 1.4e-6, false);
        assert_eq!(labels(&t), ["-1.0e-6", "-0.5e-6", "0", "0.5e-6", "1.0e-6", "1.5e-6"]);
        assert_eq!((t.lo, t.hi), (-1.0e-6, 1.5e-6));
        let t = axis(-0.9e9, 1.4e9, false);
        assert_eq!(labels(&t), ["-1.0e9", "-0.5e9", "0", "0.5e9", "1.0e9", "1.5e9"]);
        // Millimetres in metres: decimals still.
        assert_eq!(
            labels(&axis(-1.0e-3, 1.4e-3, false)),
            ["-0.0010", "-0.0005", "0.0000", "0.0005", "0.0010", "0.0015"]
        );
        // Each label reads back to its tick's value.
        for t in [axis(-1.0e-6, 1.4e-6, false), axis(-0.9e9, 1.4e9, false), axis(3e-100, 7e-100, false)] {
            for (v, l) in &t.ticks {
                let read: f64 = l.parse().unwrap();
                assert!((read - v).abs() <= 1e-12 * (t.hi - t.lo), "{l} at {v}");
            }
        }
    }
}
