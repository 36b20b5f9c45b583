//! Writing SVG text: numbers rounded to 0.1 px, point lists, and animated attributes.

use std::fmt::Write;

/// A coordinate rounded to 0.1 px, as written.
pub(crate) fn round(v: f64) -> f64 {
    // From 2^52 up every f64 is a whole number (nothing to round), and `v * 10` could
    // overflow to infinity.
    if v.abs() >= 4_503_599_627_370_496.0 {
        return v + 0.0;
    }
    // `-0` would print as "-0"; the sum with `0.0` turns it into `+0`.
    (v * 10.0).round() / 10.0 + 0.0
}

/// A coordinate rounded to 0.1 px, without a trailing `.0` (keeps files small).
pub(crate) fn num(v: f64) -> String {
    format!("{}", round(v))
}

/// `x,y x,y ...`
pub(crate) fn points(pts: &[[f64; 2]]) -> String {
    let mut s = String::with_capacity(pts.len() * 12);
    for (i, [x, y]) in pts.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{},{}", num(*x), num(*y));
    }
    s
}

/// `x y` (a translation).
pub(crate) fn pair([x, y]: [f64; 2]) -> String {
    format!("{} {}", num(x), num(y))
}

/// Rotation angles in degrees made continuous (each within 180 of the previous), so an
/// interpolating animation turns the short way instead of spinning back.
pub(crate) fn unwrap_degrees(a: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(a.len());
    for &v in a {
        // In halves, so that angles near the largest f64 do not overflow (the same numbers
        // otherwise: halving is exact).
        out.push(match out.last() {
            Some(&prev) => 2.0 * (0.5 * v - 180.0 * ((0.5 * v - 0.5 * prev) / 180.0).round()),
            None => v,
        });
    }
    out
}

/// How an animated attribute is played: the pass's duration in seconds, and when each key frame
/// is shown (SMIL `keyTimes`, written `0;0.011;...;1`; empty: evenly over the pass).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Timing<'a> {
    pub seconds: f64,
    pub key_times: &'a str,
}

impl Timing<'_> {
    /// The `keyTimes` attribute of an element through `values` key frames: the times when they
    /// are one per key frame (every animated value is), else none (evenly spaced).
    fn key_times(&self, values: usize) -> String {
        if self.key_times.is_empty() || self.key_times.split(';').count() != values {
            return String::new();
        }
        format!(r#" keyTimes="{}""#, self.key_times)
    }

    /// The duration as a SMIL clock value's number of seconds: every digit of it (the
    /// shortest decimal that reads back to it; no exponent for the durations an animation
    /// accepts), not rounded as a coordinate is.
    pub(crate) fn dur(&self) -> String {
        format!("{}", self.seconds)
    }
}

/// Writes `<animate>` of attribute `attr` through `values` (one per key frame), or nothing
/// when every value is the same (the element then keeps its static attribute).
pub(crate) fn animate(out: &mut String, attr: &str, values: &[String], t: Option<Timing<'_>>) {
    let Some(t) = t else { return };
    if values.windows(2).all(|w| w[0] == w[1]) {
        return;
    }
    let _ = write!(
        out,
        r#"<animate attributeName="{attr}" dur="{}s" repeatCount="indefinite" values="{}"{}/>"#,
        t.dur(),
        values.join(";"),
        t.key_times(values.len())
    );
}

/// Writes `<animateTransform>` of `kind` (`translate`, `rotate`) through `values`, or nothing
/// when every value is the same.
pub(crate) fn animate_transform(out: &mut String, kind: &str, values: &[String], t: Option<Timing<'_>>) {
    let Some(t) = t else { return };
    if values.windows(2).all(|w| w[0] == w[1]) {
        return;
    }
    let _ = write!(
        out,
        r#"<animateTransform attributeName="transform" type="{kind}" dur="{}s" repeatCount="indefinite" values="{}"{}/>"#,
        t.dur(),
        values.join(";"),
        t.key_times(values.len())
    );
}
