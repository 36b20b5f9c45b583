//! What a drawing writes besides the mechanism, as an engineer's figure has it: joint labels,
//! a scale bar, a readout of the inputs at the pose shown, and the events' labels; and the
//! sizes of text, to fit the picture to everything drawn.

use crate::plot::Kind;
use crate::plot::digits::Format;
use kinloop_runtime::{LENGTH_UNIT, QuantityKind};

/// Which annotations a drawing writes (all by default). Turning them off leaves the mechanism
/// alone in the picture (for pixel-exact comparisons, or a figure annotated elsewhere).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Annotate {
    /// Label each joint at a named point of the mechanism ([`Pt::point`](super::Pt::point))
    /// with its name; labels given with [`Drawing::label`](super::Drawing::label) are written
    /// either way.
    pub joint_labels: bool,
    /// A scale bar under the picture: a round length (1, 2 or 5 times a power of ten) with its
    /// unit ([`Drawing::length_unit`](super::Drawing::length_unit)).
    pub scale_bar: bool,
    /// The inputs at the pose shown (angles in degrees), under the picture; animated with it.
    pub readout: bool,
}

impl Default for Annotate {
    fn default() -> Self {
        Annotate { joint_labels: true, scale_bar: true, readout: true }
    }
}

impl Annotate {
    /// No annotation but the events' labels (which say why a ghost is drawn).
    pub fn none() -> Annotate {
        Annotate { joint_labels: false, scale_bar: false, readout: false }
    }
}

/// Font size of labels and annotations, in pixels.
pub(crate) const FONT: f64 = 12.0;
/// Height of one line of the strip under the picture.
pub(crate) const LINE: f64 = 17.0;
/// Distance of a joint label from its joint's centre, in pixels.
pub(crate) const LABEL_OFFSET: f64 = 9.0;

/// Approximate width in pixels of `text` at [`FONT`] (sans-serif averages about 0.6 em).
pub(crate) fn text_width(text: &str) -> f64 {
    0.6 * FONT * text.chars().count() as f64
}

/// Angles (in degrees) from this magnitude on are read out with a power of ten, as a page's
/// readouts write them ([`Format`]).
const ANGLE_DIGITS: f64 = 1e5;

/// The value of one input as read out: an angle in degrees (`decimals` places; from 1e5
/// degrees on, five significant digits and a power of ten), a length with
/// its unit, anything else as a plain number; a length or a number as an interactive page's
/// readout writes it ([`Format`]): five significant digits of `largest` (the input's largest
/// magnitude over the poses, so that every pose's value has the same digits), with decimals
/// for ordinary magnitudes and a power of ten for tiny and huge ones.
///
/// `span` is the input's span over the poses (largest minus smallest value): values far from
/// zero that vary little keep at least three significant digits of it ([`Format::of_range`]),
/// so that the poses read differently.
pub(crate) fn input_value(
    kind: Option<&QuantityKind>,
    v: f64,
    (largest, span): (f64, f64),
    unit: Option<&str>,
    decimals: usize,
) -> String {
    let short = |v: f64| Format::of_range(&Kind::Dimensionless, largest.max(v.abs()), span).text(v);
    match kind {
        Some(QuantityKind::Angle) if v.to_degrees().is_finite() => {
            let deg = v.to_degrees();
            // Every pose's value in one format: that of the input's largest magnitude.
            let most = Some(largest.to_degrees()).filter(|m| m.is_finite()).unwrap_or(0.0).max(deg.abs());
            if most < ANGLE_DIGITS {
                // A small negative angle rounds to zero: written "0.0°", never "-0.0°".
                let text = format!("{deg:.decimals$}");
                let text = match text.strip_prefix('-') {
                    Some(zero) if zero.bytes().all(|b| b == b'0' || b == b'.') => zero.to_string(),
                    _ => text,
                };
                format!("{text}°")
            } else {
                // As a page's readout: five significant digits and a power of ten, not every
                // digit of a huge angle.
                format!("{}°", Format::of_range(&Kind::Angle, most, span.to_degrees()).text(deg))
            }
        }
        // Beyond about 1e306 radians the degrees overflow: say the radians.
        Some(QuantityKind::Angle) => format!("{v:e} rad"),
        Some(QuantityKind::Length) => format!("{} {}", short(v), unit.unwrap_or(LENGTH_UNIT)),
        _ => short(v),
    }
}

/// `phi = 12.5°, s = 3.0000 mm`: the inputs `names` at values `x`, each written to the digits of
/// its `largest` magnitude and span over the poses ([`input_value`]).
pub(crate) fn readout(
    names: &[String],
    kinds: &[QuantityKind],
    x: &[f64],
    largest: &[(f64, f64)],
    unit: Option<&str>,
    decimals: usize,
) -> String {
    let parts: Vec<String> = names
        .iter()
        .zip(x)
        .enumerate()
        .map(|(i, (n, v))| {
            let largest = largest.get(i).copied().unwrap_or((0.0, 0.0));
            format!("{n} = {}", input_value(kinds.get(i), *v, largest, unit, decimals))
        })
        .collect();
    parts.join(", ")
}

/// The scale bar for `scale` pixels per unit of length: the largest round length (1, 2 or 5
/// times a power of ten) at most `room` pixels long, with its label in `unit`; `None` when no
/// round length is representable (a scale at the ends of the f64 range).
pub(crate) fn scale_bar(scale: f64, room: f64, unit: Option<&str>) -> Option<(f64, String)> {
    let most = room / scale;
    if !(most.is_finite() && most > 0.0) {
        return None;
    }
    let e = most.log10().floor() as i32;
    let (mant, e) =
        [(5, e), (2, e), (1, e), (5, e - 1)].into_iter().find(|&(m, e)| m as f64 * 10f64.powi(e) <= most)?;
    let length = mant as f64 * 10f64.powi(e);
    let px = length * scale;
    if !(px.is_finite() && px > 0.0) {
        return None;
    }
    let text =
        if (-4..=5).contains(&e) { format!("{:.*}", (-e).max(0) as usize, length) } else { format!("{mant}e{e}") };
    Some((px, format!("{text} {}", unit.unwrap_or(LENGTH_UNIT))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_bars_are_round_lengths_with_their_unit() {
        // 3 pixels per mm, 120 pixels of room: 40 mm fit, the bar is 20 mm.
        let (px, text) = scale_bar(3.0, 120.0, Some("mm")).unwrap();
        assert_eq!((px, text.as_str()), (60.0, "20 mm"));
        let (px, text) = scale_bar(2000.0, 120.0, Some("m")).unwrap();
        assert_eq!(text, "0.05 m");
        assert!((px - 100.0).abs() < 1e-9);
        assert_eq!(scale_bar(1.0, 120.0, None).unwrap().1, format!("100 {LENGTH_UNIT}"));
        assert_eq!(scale_bar(1e-300, 300.0, Some("m")).unwrap().1, "2e302 m");
        assert!(scale_bar(f64::INFINITY, 100.0, None).is_none());
    }

    #[test]
    fn angles_read_out_in_degrees() {
        let names = ["phi".to_string(), "s".to_string()];
        let kinds = [QuantityKind::Angle, QuantityKind::Length];
        let text = readout(&names, &kinds, &[1.3716, 2.5], &[(6.0, 0.0), (4.0, 0.0)], Some("mm"), 2);
        assert_eq!(text, "phi = 78.59°, s = 2.5000 mm");
        assert_eq!(input_value(None, 1e-9, (0.0, 0.0), None, 1), "1.0000e-9");
        // Five significant digits of the input's largest magnitude, as a page's readouts: the
        // same digits at every pose (no negative zero).
        let length = Some(&QuantityKind::Length);
        let texts = [0.0, 0.05, 0.15, 0.5].map(|v| input_value(length, v, (0.5, 0.0), Some("m"), 1));
        assert_eq!(texts, ["0.00000 m", "0.05000 m", "0.15000 m", "0.50000 m"]);
        assert_eq!(input_value(length, 25.0, (30.0, 0.0), Some("m"), 1), "25.000 m");
        assert_eq!(input_value(length, 250_000.0, (300_000.0, 0.0), Some("mm"), 1), "2.5000e5 mm");
        assert_eq!(input_value(length, -0.0, (3.0, 0.0), Some("mm"), 1), "0.0000 mm");
        // An angle just below zero reads as zero, as every other readout does.
        let angle = Some(&QuantityKind::Angle);
        assert_eq!(input_value(angle, -1e-4, (0.1, 0.2), None, 1), "0.0°");
        assert_eq!(input_value(angle, -4e-5, (0.1, 0.2), None, 2), "0.00°");
        assert_eq!(input_value(angle, -0.0, (0.1, 0.2), None, 1), "0.0°");
        assert_eq!(input_value(angle, -1e-3, (0.1, 0.2), None, 1), "-0.1°");
        // A value beyond the largest given (an event's, located between poses) keeps its digits.
        assert_eq!(input_value(None, 123.456, (2.0, 0.0), None, 1), "123.46");
    }
}
