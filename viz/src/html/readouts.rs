//! The readouts' values at every frame, in the units shown (angles in degrees), rounded to
//! the digits shown, and how they are written: [`Format`], whose rule the page's script
//! repeats to write the value of each frame as this module writes the first.

use super::HtmlError;
use super::config::{HtmlConfig, Readout, Value};
use super::frames::{pose, state};
use crate::draw::{Motion, Scalar};
use crate::plot::Kind;
use crate::plot::digits::Format;
use kinloop_runtime::QuantityKind;
use kinloop_runtime::drawing::Columns;

/// The largest magnitude of a readout (shown units).
const LARGEST: f64 = 1e100;

/// A readout whose values spread by at most this fraction of their magnitude (see
/// [`flattened`]) is constant up to rounding, and is shown as constant: one value, a flat
/// chart. An f64 holds a value to half an ulp (1.1e-16 of it); a column the solver and the
/// output expressions compute carries a few ulps from each operation and the last Newton step
/// (a link's length through the loop, the same pose reached twice: spreads of some tens of
/// ulps). A thousand ulps (2.2e-13 of the magnitude) is well above that noise, and below any
/// variation a mechanism computed in f64 can claim: a spread any larger is drawn, at any scale
/// (lengths of 1e-9 mm that vary by a tenth of themselves are a curve).
const NOISE: f64 = 1e3 * f64::EPSILON;

/// One readout, evaluated.
pub(crate) struct Channel {
    /// What the page calls it.
    pub label: String,
    /// Its kind (unit, degrees for angles).
    pub kind: Kind,
    /// How its values are written.
    pub format: Format,
    /// The value at each frame, in shown units, rounded to the digits shown.
    pub values: Vec<f64>,
    /// The value at each event of the motion, likewise.
    pub at_events: Vec<f64>,
    /// Charted against the input.
    pub chart: bool,
}

impl Channel {
    /// The unit written after the value (none for a pure number or an unknown kind).
    pub(crate) fn unit(&self) -> String {
        let u = self.kind.unit();
        if u == "-" { String::new() } else { u }
    }

    /// Value `v` (shown units) as the page writes it.
    pub(crate) fn text(&self, v: f64) -> String {
        self.format.text(v)
    }

    /// Value `v` (shown units) with its unit, as a label in running text writes it: a space
    /// before a unit (`3.0000 mm`, `1.2e-6 m/rad`), none before the degree sign (`12.50°`).
    pub(crate) fn text_with_unit(&self, v: f64) -> String {
        match self.unit() {
            u if u.is_empty() => self.text(v),
            u if u == "°" => format!("{}°", self.text(v)),
            u => format!("{} {u}", self.text(v)),
        }
    }
}

/// Where a column's value sits in a pose.
#[derive(Clone, Copy)]
enum Source {
    Input(usize),
    Unknown(usize),
    Output(usize),
}

fn kind_of(k: QuantityKind, length_unit: &str) -> Kind {
    match k {
        QuantityKind::Angle => Kind::Angle,
        QuantityKind::Length => Kind::length(length_unit),
        QuantityKind::Dimensionless => Kind::Dimensionless,
        _ => Kind::Other { quantity: "value".into(), unit: "-".into() },
    }
}

/// The column `name` of a mechanism of columns `c`, with its inferred kind.
fn column(c: &Columns, name: &str, unit: &str) -> Result<(Source, Kind), HtmlError> {
    if let Some(i) = c.inputs.iter().position(|n| *n == name) {
        return Ok((Source::Input(i), kind_of(c.input_kinds[i], unit)));
    }
    if let Some(i) = c.unknowns.iter().position(|n| *n == name) {
        return Ok((Source::Unknown(i), kind_of(c.unknown_kinds[i], unit)));
    }
    if let Some(i) = c.outputs.iter().position(|n| *n == name) {
        return Ok((Source::Output(i), kind_of(c.output_kinds[i], unit)));
    }
    let available = c.inputs.iter().chain(&c.unknowns).chain(&c.outputs).cloned().collect();
    Err(HtmlError::UnknownColumn { name: name.to_string(), available })
}

/// `shown`, the values of a readout of kind `kind` (shown units), made one value (the middle of
/// their range) when they spread by no more than rounding: [`NOISE`] of their magnitude, the
/// largest value's, and at least `floor`, the size of what a value of the kind is computed from
/// ([`rounding_floor`]): an angle is computed to the ulps of the angles it is computed from,
/// whatever its own size (an angle that is zero up to rounding reads 1e-14 degrees), a length
/// to the ulps of the mechanism's lengths. That one value is 0 where it is within rounding of
/// `floor` of zero: a length or a ratio zero in exact arithmetic (a centred slider's pin on its
/// line) read its rounding, `1.1102e-16` at one frame and `0` at the next.
fn flattened(shown: &mut [f64], floor: f64) {
    let (lo, hi) = shown.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(*v), b.max(*v)));
    let magnitude = lo.abs().max(hi.abs()).max(floor);
    // Halves: no overflow for any finite range.
    if hi >= lo && hi / 2.0 - lo / 2.0 <= NOISE / 2.0 * magnitude {
        let middle = lo / 2.0 + hi / 2.0;
        shown.fill(if middle.abs() <= NOISE * floor { 0.0 } else { middle });
    }
}

/// The size of what a readout of kind `kind` is computed from, in shown units, against which
/// its rounding is judged ([`flattened`]): a turn for an angle, the mechanism's largest length
/// over the motion (`length`) for a length, 1 for a pure number (a ratio, a sine), and 0 for
/// anything else (its own size alone).
fn rounding_floor(kind: &Kind, length: f64) -> f64 {
    match kind {
        Kind::Angle => 360.0,
        Kind::Length(_) => length,
        Kind::Dimensionless => 1.0,
        _ => 0.0,
    }
}

/// The largest magnitude of any length column (input, unknown or output) over the motion's
/// poses: the mechanism's size in its unit of length (0 without length columns).
fn length_scale(c: &Columns, motion: &Motion) -> f64 {
    let is_length = |k: &QuantityKind| *k == QuantityKind::Length;
    let pick = |kinds: &[QuantityKind], values: &[f64]| {
        kinds.iter().zip(values).filter(|(k, v)| is_length(k) && v.is_finite()).fold(0.0f64, |m, (_, v)| m.max(v.abs()))
    };
    motion.poses.iter().fold(0.0, |m, p| {
        m.max(pick(&c.input_kinds, &p.x)).max(pick(&c.unknown_kinds, &p.q)).max(pick(&c.output_kinds, &p.out))
    })
}

/// The inputs' readouts (each replaced by a readout of the config naming it), then the
/// config's other readouts, at the frames `poses` and at the motion's events.
pub(crate) fn channels(
    c: &Columns,
    config: &HtmlConfig,
    length_unit: &str,
    motion: &Motion,
    poses: &[usize],
) -> Result<Vec<Channel>, HtmlError> {
    let names_input = |r: &Readout| match &r.value {
        Value::Column(col) => c.inputs.iter().position(|n| n == col),
        Value::Expr(_) => None,
    };
    let mut list: Vec<Readout> = c
        .inputs
        .iter()
        .enumerate()
        .map(|(i, n)| {
            config
                .readouts
                .iter()
                .find(|r| names_input(r) == Some(i))
                .cloned()
                .unwrap_or_else(|| Readout::column(n.as_str()).without_chart())
        })
        .collect();
    list.extend(config.readouts.iter().filter(|r| names_input(r).is_none()).cloned());
    let all: Vec<usize> =
        poses.iter().copied().chain(motion.poses.len()..motion.poses.len() + motion.events.len()).collect();
    let length = length_scale(c, motion);
    let mut out = Vec::with_capacity(list.len());
    for r in list {
        let (label, kind, get): (String, Kind, Box<dyn Fn(usize) -> f64>) = match &r.value {
            Value::Column(name) => {
                let (src, inferred) = column(c, name, length_unit)?;
                let get = move |i: usize| {
                    let p = pose(motion, i);
                    match src {
                        Source::Input(k) => p.x.get(k),
                        Source::Unknown(k) => p.q.get(k),
                        Source::Output(k) => p.out.get(k),
                    }
                    .copied()
                    .unwrap_or(f64::NAN)
                };
                (r.label.clone().unwrap_or_else(|| name.clone()), r.kind.clone().unwrap_or(inferred), Box::new(get))
            }
            Value::Expr(s) => {
                let s = s.clone();
                let get = move |i: usize| match &s {
                    Scalar::Const(v) => *v,
                    Scalar::Expr(f) => f(&state(pose(motion, i))),
                };
                let label = r.label.clone().unwrap_or_else(|| "value".into());
                (label, r.kind.clone().unwrap_or(Kind::Dimensionless), Box::new(get))
            }
        };
        let mut shown = Vec::with_capacity(all.len());
        for &i in &all {
            let v = kind.shown(get(i));
            if !v.is_finite() {
                return Err(HtmlError::NonFinite { what: format!("readout `{label}`"), pose: i });
            }
            // Charts divide by the range of the values: beyond this they could overflow.
            if v.abs() > LARGEST {
                return Err(HtmlError::InvalidSetting(format!(
                    "readout `{label}` is {v:e} at pose {i}: a page charts values up to {LARGEST:e} in the units \
                     shown; express the mechanism in larger units"
                )));
            }
            shown.push(v);
        }
        flattened(&mut shown, rounding_floor(&kind, length));
        let format = format_of(&kind, &shown);
        let mut values: Vec<f64> = shown.into_iter().map(|v| format.rounded(v)).collect();
        let at_events = values.split_off(poses.len());
        out.push(Channel { label, kind, format, values, at_events, chart: r.chart });
    }
    Ok(out)
}

/// The format of a readout of kind `kind` taking the values `shown`: the digits of their
/// largest magnitude, and of their span ([`Format::of_range`]).
fn format_of(kind: &Kind, shown: &[f64]) -> Format {
    let max = shown.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let (lo, hi) = shown.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(*v), b.max(*v)));
    Format::of_range(kind, max, hi - lo)
}

/// Input channel `c` made to read the values `axis` (library units) of a grid's axis: shown
/// units, with the digits those need.
pub(crate) fn on_axis(c: &mut Channel, axis: &[f64]) {
    let shown: Vec<f64> = axis.iter().map(|v| c.kind.shown(*v)).collect();
    c.format = format_of(&c.kind, &shown);
    c.values = shown.into_iter().map(|v| c.format.rounded(v)).collect();
    c.at_events.clear();
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channel(kind: Kind, max: f64) -> Channel {
        let format = Format::of(&kind, max);
        Channel { label: "v".into(), kind, format, values: vec![], at_events: vec![], chart: false }
    }

    #[test]
    fn a_unit_follows_its_value_after_a_space_and_the_degree_sign_without() {
        assert_eq!(channel(Kind::length("mm"), 3.0).text_with_unit(3.0), "3.0000 mm");
        assert_eq!(channel(Kind::length("m"), 4e-6).text_with_unit(-5.661e-7), "-5.661e-7 m");
        assert_eq!(channel(Kind::Angle, 360.0).text_with_unit(12.5), "12.50°");
        assert_eq!(channel(Kind::Dimensionless, 2.0).text_with_unit(1.5), "1.5000");
    }
}
