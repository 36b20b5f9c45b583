//! The readouts' values at every frame, in the units shown (angles in degrees), rounded to
//! the digits shown, and how they are written: [`Format`], whose rule the page's script
//! repeats to write the value of each frame as this module writes the first.

use super::HtmlError;
use super::config::{HtmlConfig, Readout, Value};
use super::frames::{pose, state};
use crate::draw::{Motion, Scalar};
use crate::plot::Kind;
use crate::plot::ticks::decimal;
use kinloop_runtime::QuantityKind;
use kinloop_runtime::drawing::Columns;

/// The largest magnitude of a readout (shown units).
const LARGEST: f64 = 1e100;

/// How a readout writes its values: about five significant digits at every scale, in the
/// style of the charts' axes.
///
/// Every value is rounded to a whole multiple `k` of `10^last` (`last`: the place of the last
/// digit shown), then written exactly from `k`: with `max(0, -last)` decimals (`"-0.0123"`,
/// `"12.34"`), or, when `sci`, as its own digits down to `10^last` in a mantissa and a power
/// of ten (`"-5.661e-7"`, `"1.5896e9"`, `"3.2000e-6"`; zero `"0"`). Never a negative zero.
///
/// The page's script writes the values it shows by the same rule from the numbers the page
/// holds, which are these texts (see `script.rs`); `tests/html_readouts.rs` checks the two
/// agree in the browser.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Format {
    /// The place of the last digit shown: values are multiples of `10^last`.
    pub last: i32,
    /// Written with a power of ten rather than decimals.
    pub sci: bool,
}

/// Magnitudes written with decimals: from about 1e-4 to 1e5 (a readout's largest value);
/// beyond, a power of ten, as the charts' axes label tiny and huge values.
const DECIMALS: std::ops::Range<f64> = 1e-4..1e5;

/// The finest last digit: values below about `1e-295` read `0` (their digits beyond are not
/// those of a normal f64 any more).
const FINEST: i32 = -300;

impl Format {
    /// The format of a readout of kind `kind` whose values reach `max` in magnitude (shown
    /// units): angles (degrees) to a hundredth of a degree, anything else to five significant
    /// digits of `max`; with decimals for `max` in `[1e-4, 1e5)` (and zero), a power of ten
    /// otherwise. Angles of 1e5 degrees or more are written as other values are.
    pub(crate) fn of(kind: &Kind, max: f64) -> Format {
        if !(max.is_finite() && max > 0.0) {
            return Format { last: if kind.is_angle() { -2 } else { -4 }, sci: false };
        }
        if kind.is_angle() && max < DECIMALS.end {
            return Format { last: -2, sci: false };
        }
        let lg = max.log10().floor() as i32;
        Format { last: (lg - 4).max(FINEST), sci: !DECIMALS.contains(&max) }
    }

    /// `v` as a whole number of `10^last` (rounded to nearest; `0` for a negative zero).
    fn units(&self, v: f64) -> i128 {
        let r = self.last;
        let scaled = if r >= 0 { v / 10f64.powi(r) } else { v * 10f64.powi(-r) };
        scaled.round() as i128
    }

    /// `v` rounded to the digits shown, as written.
    pub(crate) fn text(&self, v: f64) -> String {
        let k = self.units(v);
        if !self.sci {
            // Decimals only: `last` is at most 0 for a largest value below 1e5.
            return decimal(k, self.last);
        }
        if k == 0 {
            return "0".into();
        }
        // The power of ten of the leading digit; the mantissa keeps every digit down to
        // `10^last`.
        let e = self.last + k.unsigned_abs().to_string().len() as i32 - 1;
        format!("{}e{e}", decimal(k, self.last - e))
    }

    /// `v` rounded to the digits shown: the number its text reads.
    pub(crate) fn rounded(&self, v: f64) -> f64 {
        self.text(v).parse().unwrap_or(v)
    }
}

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

/// The inputs' readouts (each replaced by a readout of the config naming it), then the
/// config's other readouts, at the frames `poses` and at the motion's events.
pub(crate) fn channels(
    c: &Columns,
    config: &HtmlConfig,
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
    let mut out = Vec::with_capacity(list.len());
    for r in list {
        let (label, kind, get): (String, Kind, Box<dyn Fn(usize) -> f64>) = match &r.value {
            Value::Column(name) => {
                let (src, inferred) = column(c, name, &config.length_unit)?;
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
                    "readout `{label}` is {v:e} at pose {i}: more than {LARGEST:e} cannot be charted"
                )));
            }
            shown.push(v);
        }
        let max = shown.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let format = Format::of(&kind, max);
        let mut values: Vec<f64> = shown.into_iter().map(|v| format.rounded(v)).collect();
        let at_events = values.split_off(poses.len());
        out.push(Channel { label, kind, format, values, at_events, chart: r.chart });
    }
    Ok(out)
}

/// Input channel `c` made to read the values `axis` (library units) of a grid's axis: shown
/// units, with the digits those need.
pub(crate) fn on_axis(c: &mut Channel, axis: &[f64]) {
    let shown: Vec<f64> = axis.iter().map(|v| c.kind.shown(*v)).collect();
    let max = shown.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    c.format = Format::of(&c.kind, max);
    c.values = shown.into_iter().map(|v| c.format.rounded(v)).collect();
    c.at_events.clear();
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(kind: &Kind, values: &[f64]) -> Vec<String> {
        let max = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let f = Format::of(kind, max);
        values.iter().map(|v| f.text(*v)).collect()
    }

    #[test]
    fn five_significant_digits_with_decimals_or_a_power_of_ten() {
        let m = Kind::length("m");
        // Ordinary magnitudes: decimals, as before.
        assert_eq!(texts(&m, &[4.2, -0.0123, 0.0]), ["4.2000", "-0.0123", "0.0000"]);
        assert_eq!(texts(&m, &[4.2e-3, -1.5e-4]), ["0.0042000", "-0.0001500"]);
        assert_eq!(texts(&m, &[12345.6, 7.0]), ["12346", "7"]);
        // Micrometres and a billion: a power of ten, each value with its own.
        assert_eq!(texts(&m, &[4.0e-6, -5.661e-7, 3.2e-6, 0.0]), ["4.0000e-6", "-5.661e-7", "3.2000e-6", "0"]);
        assert_eq!(texts(&m, &[1589571631.0, -4e9, 0.4]), ["1.5896e9", "-4.0000e9", "0"]);
        assert_eq!(texts(&m, &[1e100, -3.3e99]), ["1.0000e100", "-3.300e99"]);
        // Rounding up to the next power of ten keeps the digits down to the same place.
        assert_eq!(texts(&m, &[9.99996e-6, 1e-6]), ["1.00000e-5", "1.0000e-6"]);
        // Below the finest place a normal f64 keeps: zero.
        assert_eq!(texts(&m, &[1e-310, 5e-324]), ["0", "0"]);
        // Angles in degrees to a hundredth, and as other values from 1e5 degrees.
        assert_eq!(texts(&Kind::Angle, &[359.999, -0.001, 12.5]), ["360.00", "0.00", "12.50"]);
        assert_eq!(texts(&Kind::Angle, &[572957.8, -1432394.5]), ["5.730e5", "-1.4324e6"]);
    }

    #[test]
    fn never_a_negative_zero_and_rounding_twice_changes_nothing() {
        let m = Kind::length("m");
        for (max, v) in [(3.0, -1e-9), (3.0, -0.0), (4e-6, -1e-12), (4e9, -0.4), (1e-310, -1e-310)] {
            let f = Format::of(&m, max);
            let t = f.text(v);
            assert!(!t.starts_with('-'), "{v:e} of at most {max:e} reads {t}");
        }
        for max in [1.0, 4e-3, 4e-6, 4e9, 1e100, 2e-300] {
            let f = Format::of(&m, max);
            for k in 0..200 {
                let v = max * (k as f64 / 100.0 - 1.0) * std::f64::consts::FRAC_1_SQRT_2;
                let r = f.rounded(v);
                assert_eq!(f.text(r), f.text(v), "{v:e}");
                assert_eq!(f.rounded(r), r);
                let t = f.text(v);
                let (mantissa, exp) = t.split_once('e').unwrap_or((&t, "0"));
                let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
                let exp: i32 = exp.parse().unwrap();
                assert_eq!(exp - decimals, if t == "0" { 0 } else { f.last }, "{t}");
                assert!((r - v).abs() <= 0.5 * 10f64.powi(f.last) * (1.0 + 1e-9), "{v:e}: {t}");
            }
        }
    }
}
