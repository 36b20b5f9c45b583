//! How a number is written where a reader reads a value (a page's readouts, a drawing's
//! input readout): about five significant digits at every scale, in the style of the axes'
//! labels ([`ticks`](super::ticks)): decimals for ordinary magnitudes, a power of ten for tiny
//! and huge ones, never a negative zero.

use super::Kind;
use super::ticks::decimal;

/// How a readout writes its values: about five significant digits at every scale, in the
/// style of the charts' axes. An interactive page's readouts and a drawing's readout of its
/// inputs both write by it.
///
/// Every value is rounded to a whole multiple `k` of `10^last` (`last`: the place of the last
/// digit shown), then written exactly from `k`: with `max(0, -last)` decimals (`"-0.0123"`,
/// `"12.34"`), or, when `sci`, as its own digits down to `10^last` in a mantissa and a power
/// of ten (`"-5.661e-7"`, `"1.5896e9"`, `"3.2000e-6"`; zero `"0"`). Never a negative zero.
///
/// An interactive page's script writes the values it shows by the same rule from the numbers
/// the page holds, which are these texts (see `html/script.rs`); `tests/html_readouts.rs`
/// checks the two agree in the browser.
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

/// The finest last digit: the place of the smallest normal f64's leading digit (2.2e-308),
/// whose power of ten, 1e308, `Format::units` can still scale by. Values down to about
/// 1e-304 keep their five digits, as at every other scale; smaller ones keep the digits down
/// to 1e-308, and subnormal ones, whose digits are no longer an f64's, read `0`.
const FINEST: i32 = -308;

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

    /// [`Format::of`] for values that span `span` (their largest minus their smallest): also
    /// at least three significant digits of the span, so that values far from zero that differ
    /// little (an input after many turns, a time long after its origin) are told apart rather
    /// than all written alike; at most the sixteen significant digits an f64 holds.
    pub(crate) fn of_range(kind: &Kind, max: f64, span: f64) -> Format {
        let f = Format::of(kind, max);
        if !(max.is_finite() && max > 0.0 && span.is_finite() && span > 0.0) {
            return f;
        }
        let (lg_max, lg_span) = (max.log10().floor() as i32, span.log10().floor() as i32);
        Format { last: f.last.min(lg_span - 2).max(lg_max - 15).max(FINEST), ..f }
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
        // Lengths of about 1e-300 (a mechanism in units 1e300 times too large): five digits,
        // as at every other scale; below the finest place a normal f64 keeps: zero.
        assert_eq!(texts(&m, &[2.725e-300, -1e-300, 0.0]), ["2.7250e-300", "-1.0000e-300", "0"]);
        assert_eq!(texts(&m, &[2.2e-308, 1e-310, 5e-324]), ["2e-308", "0", "0"]);
        assert_eq!(texts(&m, &[1e-310, 5e-324]), ["0", "0"]);
        // Angles in degrees to a hundredth, and as other values from 1e5 degrees.
        assert_eq!(texts(&Kind::Angle, &[359.999, -0.001, 12.5]), ["360.00", "0.00", "12.50"]);
        assert_eq!(texts(&Kind::Angle, &[572957.8, -1432394.5]), ["5.730e5", "-1.4324e6"]);
    }

    #[test]
    fn values_far_from_zero_keep_three_digits_of_their_span() {
        let m = Kind::length("m");
        // A turn after a hundred thousand turns, in degrees: to a degree (three digits of the
        // turn), not to ten thousand degrees (five of the largest value).
        let f = Format::of_range(&Kind::Angle, 5.7296e7 + 360.0, 360.0);
        assert_eq!([f.text(5.7295779513e7), f.text(5.7295779513e7 + 1.0)], ["5.7295780e7", "5.7295781e7"]);
        assert_eq!(Format::of(&Kind::Angle, 5.7296e7 + 360.0).text(5.7295779513e7 + 1.0), "5.7296e7");
        // A span of a tenth of the largest value or more: as `of`.
        assert_eq!(Format::of_range(&m, 4.2, 3.0), Format::of(&m, 4.2));
        assert_eq!(Format::of_range(&Kind::Angle, 360.0, 359.0), Format::of(&Kind::Angle, 360.0));
        // No more than an f64's digits, however small the span.
        assert_eq!(Format::of_range(&m, 1.0, 1e-300).last, -15);
        assert_eq!(Format::of_range(&m, 1.0, 0.0), Format::of(&m, 1.0));
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
