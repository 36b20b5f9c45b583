//! Serialize and Deserialize of the crate's numbers (feature `serde`), exactly whatever their
//! values: one convention for every type that holds them (a [`Table`](crate::Table)'s rows, a
//! state and a named state, a [`Vec2`](crate::Vec2), a solve report, an event, a synthesis
//! task, report and configuration, the structs `mechanism!` generates).
//!
//! Tables hold NaN where a value is not known, states an infinite smallest pivot where no block
//! was factorised, synthesis reports infinities and NaN where a candidate is degenerate (the
//! ratio of a zero-length link). JSON has neither: serde_json writes them as `null`, which does
//! not read back as an `f64`, and which in an `Option<f64>` is `None`. A self-describing format
//! (`is_human_readable`) therefore gets a non-finite number as a string, so that an infinity
//! stays an infinity and `Some(inf)` is not read as `None`: `inf`, `-inf`, and a NaN with its
//! bits, `NaN` (`f64::NAN`), `-NaN` (its sign bit set, as `0.0 / 0.0` leaves it on x86-64) or any
//! other as `NaN(0x..)` (its 64 bits in hex); a compact binary format holds the `f64` itself.
//! Reading takes a number, such a string, or `null` (what earlier writers wrote for any
//! non-finite number) as NaN; where the field is an `Option`, `null` is `None`, as it always was.
//!
//! Types of known shape go through [`Floats`]; values of a generic type (a `Vec2<T>`'s
//! components, a named state's fields) through [`within`], which applies the same convention to
//! every `f64` inside any value.

pub(crate) mod within;

use serde::de::{DeserializeOwned, Deserializer, Error, Visitor};
use serde::{Deserialize, Serialize, Serializer};

/// One number as written and read by this module.
#[derive(Clone, Copy)]
pub(crate) struct Float(f64);

impl Serialize for Float {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let v = self.0;
        if v.is_finite() || !s.is_human_readable() {
            s.serialize_f64(v)
        } else if v.is_nan() {
            s.serialize_str(&nan_text(v))
        } else {
            // `inf` or `-inf`: what `f64::from_str` reads back.
            s.serialize_str(&v.to_string())
        }
    }
}

/// The bits of the NaN `f64::NAN` is, written `"NaN"`.
const QUIET_NAN: u64 = 0x7ff8_0000_0000_0000;

/// The sign bit of an `f64`.
const SIGN: u64 = 1 << 63;

/// The text of the NaN `v`, from which [`nan_of_text`] reads back its bits: `"NaN"` for
/// `f64::NAN`, `"-NaN"` for it with the sign bit set (what `0.0 / 0.0` gives on x86-64 and what
/// most arithmetic that makes a NaN there leaves), and any other NaN by its bits
/// (`"NaN(0x7ff0000000000001)"`). Rust prints every NaN as `NaN`, which read back as
/// `f64::NAN`: a NaN computed at run time came back from JSON with its sign bit cleared.
fn nan_text(v: f64) -> String {
    match v.to_bits() {
        QUIET_NAN => "NaN".into(),
        b if b == QUIET_NAN | SIGN => "-NaN".into(),
        b => format!("NaN({b:#018x})"),
    }
}

/// Whether `v` names an infinity as `f64::from_str` reads one (`inf`, `infinity`, any case, with
/// a sign or none), rather than a decimal too large for `f64`.
fn is_infinity_word(v: &str) -> bool {
    let word = v.strip_prefix(['+', '-']).unwrap_or(v);
    word.eq_ignore_ascii_case("inf") || word.eq_ignore_ascii_case("infinity")
}

/// The NaN written by [`nan_text`] as `"NaN(0x..)"` (its 64 bits in hex), or `None` where `v`
/// is not of that form or its bits are not a NaN's.
fn nan_of_text(v: &str) -> Option<f64> {
    let hex = v.strip_prefix("NaN(0x")?.strip_suffix(')')?;
    // `from_str_radix` takes a leading `+`: sixteen hex digits exactly.
    if hex.len() != 16 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let v = f64::from_bits(u64::from_str_radix(hex, 16).ok()?);
    v.is_nan().then_some(v)
}

impl<'de> Deserialize<'de> for Float {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Float, D::Error> {
        // A self-describing format says what it holds (a number, a string, `null`); a compact
        // binary one holds the `f64` that was written, and must be asked for it.
        if d.is_human_readable() { d.deserialize_any(FloatVisitor) } else { d.deserialize_f64(FloatVisitor) }
    }
}

struct FloatVisitor;

impl Visitor<'_> for FloatVisitor {
    type Value = Float;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a number, \"inf\", \"-inf\", \"NaN\", or null for NaN")
    }
    fn visit_f64<E>(self, v: f64) -> Result<Float, E> {
        Ok(Float(v))
    }
    // Whole numbers as JSON writes them when written by hand (`1`, not `1.0`).
    fn visit_i64<E>(self, v: i64) -> Result<Float, E> {
        Ok(Float(v as f64))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Float, E> {
        Ok(Float(v as f64))
    }
    fn visit_str<E: Error>(self, v: &str) -> Result<Float, E> {
        // `f64::from_str` reads `"NaN"` and `"-NaN"` with their sign bits. A decimal beyond
        // `f64`'s range (`"1e400"`) it reads as an infinity, which no writer meant: refused, as
        // the format refuses such a number written as one ("number out of range").
        v.parse::<f64>()
            .ok()
            .filter(|f| !f.is_infinite() || is_infinity_word(v))
            .or_else(|| nan_of_text(v))
            .map(Float)
            .ok_or_else(|| E::invalid_value(serde::de::Unexpected::Str(v), &self))
    }
    fn visit_unit<E>(self) -> Result<Float, E> {
        Ok(Float(f64::NAN))
    }
    fn visit_none<E>(self) -> Result<Float, E> {
        Ok(Float(f64::NAN))
    }
}

/// A value made of numbers, with its form of [`Float`]s.
pub(crate) trait Floats: Sized {
    /// The same shape with every `f64` a [`Float`].
    type Repr: Serialize + DeserializeOwned;
    fn to_repr(&self) -> Self::Repr;
    fn from_repr(r: Self::Repr) -> Self;
}

impl Floats for f64 {
    type Repr = Float;
    fn to_repr(&self) -> Float {
        Float(*self)
    }
    fn from_repr(r: Float) -> f64 {
        r.0
    }
}

impl<T: Floats> Floats for Vec<T> {
    type Repr = Vec<T::Repr>;
    fn to_repr(&self) -> Self::Repr {
        self.iter().map(T::to_repr).collect()
    }
    fn from_repr(r: Self::Repr) -> Self {
        r.into_iter().map(T::from_repr).collect()
    }
}

impl<T: Floats> Floats for Option<T> {
    type Repr = Option<T::Repr>;
    fn to_repr(&self) -> Self::Repr {
        self.as_ref().map(T::to_repr)
    }
    fn from_repr(r: Self::Repr) -> Self {
        r.map(T::from_repr)
    }
}

impl Floats for [f64; 4] {
    type Repr = [Float; 4];
    fn to_repr(&self) -> Self::Repr {
        self.map(Float)
    }
    fn from_repr(r: Self::Repr) -> Self {
        r.map(|f| f.0)
    }
}

impl Floats for (f64, f64) {
    type Repr = (Float, Float);
    fn to_repr(&self) -> Self::Repr {
        (Float(self.0), Float(self.1))
    }
    fn from_repr(r: Self::Repr) -> Self {
        (r.0.0, r.1.0)
    }
}

/// For `#[serde(with = "floats")]`.
pub(crate) fn serialize<T: Floats, S: Serializer>(v: &T, s: S) -> Result<S::Ok, S::Error> {
    v.to_repr().serialize(s)
}

/// For `#[serde(with = "floats")]`.
pub(crate) fn deserialize<'de, T: Floats, D: Deserializer<'de>>(d: D) -> Result<T, D::Error> {
    T::Repr::deserialize(d).map(T::from_repr)
}

/// For `#[serde(serialize_with = "floats_serde::serialize_rows")]` on a table's rows: as
/// [`serialize`], without a copy of the rows (a table can be large).
pub(crate) fn serialize_rows<S: Serializer>(rows: &[Vec<f64>], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(rows.iter().map(|r| Row(r)))
}

struct Row<'a>(&'a [f64]);

impl Serialize for Row<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.iter().map(|&v| Float(v)))
    }
}
