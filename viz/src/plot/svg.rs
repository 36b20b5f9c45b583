//! A minimal SVG writer: shapes with fractional coordinates (no pixel snapping, so curves are
//! smooth), escaped text, and curves thinned to what the resolution can show.

use crate::escape::escape;
use std::fmt::Write;

/// A coordinate with two decimals (1/100 pixel), trailing zeros dropped.
pub(crate) fn num(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// ` stroke-dasharray="..."` for a dash array, nothing for a solid stroke.
fn dash_attribute(dash: &str) -> String {
    if dash.is_empty() { String::new() } else { format!(r#" stroke-dasharray="{dash}""#) }
}

/// An SVG document being written.
pub(crate) struct Svg {
    pub out: String,
}

/// Gaps between kept points of a curve below this many pixels are not drawn separately.
const THIN_PX: f64 = 0.5;

impl Svg {
    /// A document of `width` x `height` pixels (also its view box) on a white background.
    pub fn new(width: f64, height: f64) -> Svg {
        let (w, h) = (num(width), num(height));
        let mut out = String::new();
        let _ = write!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif">"#
        );
        let _ = write!(out, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
        Svg { out }
    }

    /// Text at `(x, y)`; `anchor` is `start`, `middle` or `end`; `rotate` in degrees.
    #[allow(clippy::too_many_arguments)]
    pub fn text(&mut self, class: &str, x: f64, y: f64, size: f64, anchor: &str, rotate: f64, text: &str) {
        let transform = if rotate != 0.0 {
            format!(r#" transform="rotate({} {} {})""#, num(rotate), num(x), num(y))
        } else {
            String::new()
        };
        let _ = write!(
            self.out,
            r#"<text class="{class}" x="{}" y="{}" font-size="{}" text-anchor="{anchor}"{transform}>{}</text>"#,
            num(x),
            num(y),
            num(size),
            escape(text)
        );
    }

    /// A straight line.
    pub fn line(&mut self, class: &str, from: (f64, f64), to: (f64, f64), stroke: &str, width: f64) {
        self.dashed_line(class, from, to, stroke, width, "");
    }

    /// A straight line dashed by `dash` (an SVG dash array; empty: solid).
    pub fn dashed_line(
        &mut self,
        class: &str,
        (x0, y0): (f64, f64),
        (x1, y1): (f64, f64),
        stroke: &str,
        width: f64,
        dash: &str,
    ) {
        let _ = write!(
            self.out,
            r#"<line class="{class}" x1="{}" y1="{}" x2="{}" y2="{}" stroke="{stroke}" stroke-width="{}"{}/>"#,
            num(x0),
            num(y0),
            num(x1),
            num(y1),
            num(width),
            dash_attribute(dash)
        );
    }

    /// A rectangle.
    pub fn rect(&mut self, class: &str, (x, y): (f64, f64), (w, h): (f64, f64), fill: &str, stroke: &str) {
        let _ = write!(
            self.out,
            r#"<rect class="{class}" x="{}" y="{}" width="{}" height="{}" fill="{fill}" stroke="{stroke}"/>"#,
            num(x),
            num(y),
            num(w),
            num(h)
        );
    }

    /// A bar of series `label`: a filled rectangle without outline.
    pub fn bar(&mut self, label: &str, (x, y): (f64, f64), (w, h): (f64, f64), fill: &str) {
        let _ = write!(
            self.out,
            r#"<rect class="bar" data-label="{}" x="{}" y="{}" width="{}" height="{}" fill="{fill}"/>"#,
            escape(label),
            num(x),
            num(y),
            num(w),
            num(h)
        );
    }

    /// A dot of radius `r`.
    pub fn dot(&mut self, class: &str, (x, y): (f64, f64), r: f64, fill: &str) {
        let _ = write!(
            self.out,
            r#"<circle class="{class}" cx="{}" cy="{}" r="{}" fill="{fill}"/>"#,
            num(x),
            num(y),
            num(r)
        );
    }

    /// A polyline through pixel points, broken at non-finite points and thinned: a point closer
    /// than half a pixel to the last drawn one is skipped (the last point of a run is kept);
    /// stroked in a colour and a dash array (empty: solid). A run that draws no stroke of its
    /// own, a lone sample between gaps (failed samples) or samples all within half a pixel of
    /// the first, is a dot of the curve's colour: a path of one point, or of no length, is not
    /// stroked, and that sample would not be shown at all.
    pub fn curve(
        &mut self,
        label: &str,
        points: impl Iterator<Item = (f64, f64)>,
        (stroke, dash): (&str, &str),
        clip: &str,
    ) {
        let mut d = String::new();
        let mut last: Option<(f64, f64)> = None;
        let mut pending: Option<(f64, f64)> = None;
        // The first point of the run being written, and whether the run has drawn a stroke.
        let mut first = (0.0, 0.0);
        let mut stroked = false;
        let mut dots = Vec::new();
        for (x, y) in points {
            if !(x.is_finite() && y.is_finite()) {
                if let Some(p) = pending.take() {
                    let _ = write!(d, " L{},{}", num(p.0), num(p.1));
                }
                if last.take().is_some() && !stroked {
                    dots.push(first);
                }
                continue;
            }
            match last {
                None => {
                    let _ = write!(d, " M{},{}", num(x), num(y));
                    last = Some((x, y));
                    (first, stroked) = ((x, y), false);
                }
                Some((lx, ly)) if (x - lx).hypot(y - ly) < THIN_PX => pending = Some((x, y)),
                Some(_) => {
                    let _ = write!(d, " L{},{}", num(x), num(y));
                    last = Some((x, y));
                    pending = None;
                    stroked = true;
                }
            }
        }
        if let Some(p) = pending {
            let _ = write!(d, " L{},{}", num(p.0), num(p.1));
        }
        if last.is_some() && !stroked {
            dots.push(first);
        }
        let _ = write!(
            self.out,
            r#"<path class="curve" data-label="{}" d="{}" fill="none" stroke="{stroke}" stroke-width="2" stroke-linejoin="round"{} clip-path="url(#{clip})"/>"#,
            escape(label),
            d.trim_start(),
            dash_attribute(dash)
        );
        // Twice the curve's width across: a sample, seen as one.
        for (x, y) in dots {
            let _ = write!(
                self.out,
                r#"<circle class="curve-dot" data-label="{}" cx="{}" cy="{}" r="2" fill="{stroke}" clip-path="url(#{clip})"/>"#,
                escape(label),
                num(x),
                num(y)
            );
        }
    }

    /// A clipping rectangle named `id`.
    pub fn clip(&mut self, id: &str, (x, y): (f64, f64), (w, h): (f64, f64)) {
        let _ = write!(
            self.out,
            r#"<clipPath id="{id}"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath>"#,
            num(x),
            num(y),
            num(w),
            num(h)
        );
    }

    /// Opens a group.
    pub fn open(&mut self, class: &str) {
        let _ = write!(self.out, r#"<g class="{class}">"#);
    }

    /// Closes a group.
    pub fn close(&mut self) {
        self.out.push_str("</g>");
    }

    /// The finished document.
    pub fn finish(mut self) -> String {
        self.out.push_str("</svg>\n");
        self.out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_fractions_and_drop_trailing_zeros() {
        assert_eq!(num(12.3456), "12.35");
        assert_eq!(num(12.0), "12");
        assert_eq!(num(-0.001), "0");
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }

    #[test]
    fn curves_break_at_gaps_and_thin_dense_points() {
        let mut s = Svg::new(10.0, 10.0);
        let pts = [(0.0, 0.0), (0.1, 0.1), (0.2, 0.2), (3.0, 3.0), (f64::NAN, 1.0), (5.0, 5.0), (6.0, 6.0)];
        s.curve("c", pts.into_iter(), ("black", ""), "k");
        assert!(s.out.contains(r#"d="M0,0 L3,3 M5,5 L6,6""#), "{}", s.out);
    }
}
