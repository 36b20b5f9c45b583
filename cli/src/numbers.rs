//! Numbers given on the command line (`--speed`, `--roller`, `--about 1,2`, ...), read as
//! Rust's `f64` reads them, but with spaces around them allowed and a number too small for a
//! double refused: `1e-400` reads as 0 (it underflows), so `--roller 1e-400` became a knife
//! edge and `--speed 1e-400` a machine at rest, without a word. `1e400` reads as infinity, which
//! every command's own checks refuse, naming what the option takes.

/// A number: what `f64`'s parsing reads of `text` trimmed, unless `text` is written non-zero
/// and reads as 0 (see the module's documentation).
pub fn number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let v = t.parse::<f64>().map_err(|_| format!("`{t}` is not a number"))?;
    if v == 0.0 && !is_zero_text(t) {
        return Err(underflow(t));
    }
    Ok(v)
}

/// The message for `text`, written non-zero, that reads as 0.
fn underflow(text: &str) -> String {
    format!(
        "`{text}` is too small for a 64-bit float and would be 0: give 0 if 0 is meant, or express the model in \
         other units"
    )
}

/// Whether the number `text` (one that parses) is written as zero: no digit but 0 before its
/// exponent. `1e-400` is not, though it parses to 0 (it underflows), as `1e400` overflows.
fn is_zero_text(text: &str) -> bool {
    let mantissa = text.split(['e', 'E']).next().unwrap_or(text);
    !mantissa.chars().any(|c| c.is_ascii_digit() && c != '0')
}

/// The point `s / last` of the way from `a` to `b` (`s` from 0 to `last`, at least 1) as the
/// decimals they are written in (the shortest that read back to them: `0.1`, `360.1`): their
/// exact value there, rounded once to the nearest double. The samples between ends given on the
/// command line are written so: `30.1` between `0.1` and `360.1`, the ends themselves, where the
/// doubles' `(a (last - s) + b s) / last` rounds four times, and wrote `30.100000000000005`,
/// `0.10000000000000002` and `360.1000000000001`. That formula where the decimals do not fit
/// the exact arithmetic (ends many orders of magnitude apart, not finite).
pub fn between(a: f64, b: f64, s: usize, last: usize) -> f64 {
    exactly_between(a, b, s, last).unwrap_or_else(|| {
        let (s, last) = (s as f64, last as f64);
        (a * (last - s) + b * s) / last
    })
}

/// [`between`] in exact arithmetic: `None` where the numbers do not fit in it.
fn exactly_between(a: f64, b: f64, s: usize, last: usize) -> Option<f64> {
    let ((ma, ea), (mb, eb)) = (decimal(a)?, decimal(b)?);
    // Both over the smaller power of ten: `n 10^e / last` is the point.
    let e = ea.min(eb);
    let scaled = |m: i128, ex: i32| m.checked_mul(10i128.checked_pow(u32::try_from(ex - e).ok()?)?);
    let (ma, mb) = (scaled(ma, ea)?, scaled(mb, eb)?);
    let (s, last) = (i128::try_from(s).ok()?, i128::try_from(last).ok()?.max(1));
    let n = ma.checked_mul(last.checked_sub(s)?)?.checked_add(mb.checked_mul(s)?)?;
    Some(quotient_as_double(n, last, e))
}

/// `f64`'s shortest decimal of `v` as an integer and a power of ten (`-33.3` is `-333 10^-1`),
/// `None` for a number that is not finite.
fn decimal(v: f64) -> Option<(i128, i32)> {
    if !v.is_finite() {
        return None;
    }
    let text = format!("{v:e}");
    let (mantissa, exponent) = text.split_once('e')?;
    let fraction = mantissa.split_once('.').map_or(0, |(_, f)| f.len());
    let digits: i128 = mantissa.replace('.', "").parse().ok()?;
    Some((digits, exponent.parse::<i32>().ok()? - i32::try_from(fraction).ok()?))
}

/// `n 10^e / d` (`d` positive) rounded once to the nearest double: written in decimal, its
/// quotient and forty digits of its remainder, a last `1` standing for any remainder left
/// (the text then rounds as the exact value does: a value halfway between two doubles is a
/// decimal of at most as many digits as `d` has factors two, which forty digits hold whole),
/// and read by Rust's parser, which rounds correctly.
fn quotient_as_double(n: i128, d: i128, e: i32) -> f64 {
    let (q, mut r) = (n / d, (n % d).abs());
    let mut text = format!("{}{}.", if n < 0 { "-" } else { "" }, q.unsigned_abs());
    for _ in 0..40 {
        r *= 10;
        text.push(char::from(b'0' + (r / d) as u8));
        r %= d;
    }
    if r != 0 {
        text.push('1');
    }
    text.push_str(&format!("e{e}"));
    text.parse().unwrap_or(f64::NAN)
}

/// `v` rounded to `digits` significant digits (the decimal rounding of `v`'s exact value, as
/// `{:e}` writes it), for the numbers of a note: a located value carries the rounding of its
/// search or of a conversion (82 degrees from radians written `82.00000000000001`, a rest's end
/// at `149.9999995` degrees for 150), below what a designer reads or types. Zero, the
/// infinities and NaN as they are.
pub fn significant(v: f64, digits: usize) -> f64 {
    format!("{v:.*e}", digits.saturating_sub(1)).parse().unwrap_or(v)
}

#[cfg(test)]
mod tests {
    use super::{between, is_zero_text, number, significant};

    /// Rounded decimals, whatever the magnitude, and the values that have none as they are.
    #[test]
    fn significant_digits_round_the_decimal() {
        assert_eq!(significant(82.00000000000001, 15), 82.0);
        assert_eq!(significant(138.0518454577004, 15), 138.0518454577);
        assert_eq!(significant(149.9999995, 6), 150.0);
        assert_eq!(significant(-0.000123456789, 6), -0.000123457);
        assert_eq!(significant(5e-324, 6), 5e-324);
        assert_eq!(significant(f64::MAX, 6), 1.79769e308);
        assert_eq!(significant(-0.0, 6).to_bits(), (-0.0f64).to_bits());
        assert_eq!(significant(f64::NEG_INFINITY, 6), f64::NEG_INFINITY);
        assert!(significant(f64::NAN, 6).is_nan());
    }

    /// The samples between decimal ends are the nearest doubles to the decimals they stand
    /// for (each against the double that decimal reads as, an independent parse), the ends the
    /// ends themselves; ends that the exact arithmetic cannot hold take the doubles' formula.
    #[test]
    fn samples_between_decimals_are_those_decimals() {
        let cases: [(f64, f64, usize, &[&str]); 5] = [
            (
                0.1,
                360.1,
                12,
                &[
                    "0.1", "30.1", "60.1", "90.1", "120.1", "150.1", "180.1", "210.1", "240.1", "270.1", "300.1",
                    "330.1", "360.1",
                ],
            ),
            (0.7, 1.3, 6, &["0.7", "0.8", "0.9", "1", "1.1", "1.2", "1.3"]),
            (-33.3, -30.3, 3, &["-33.3", "-32.3", "-31.3", "-30.3"]),
            (-0.3, 0.3, 2, &["-0.3", "0", "0.3"]),
            (1e-300, 3e-300, 4, &["1e-300", "1.5e-300", "2e-300", "2.5e-300", "3e-300"]),
        ];
        for (a, b, last, want) in cases {
            for (s, w) in want.iter().enumerate() {
                assert_eq!(between(a, b, s, last), w.parse::<f64>().expect("a number"), "{a}..{b} sample {s}");
            }
        }
        // A third of the way: 0.1 + 0.1 = 0.2 exactly, whose double is not 0.1's plus 0.1's.
        assert_eq!(between(0.1, 0.4, 1, 3), 0.2);
        // Ends 600 orders of magnitude apart: the formula's.
        assert_eq!(between(1e-300, 1e300, 1, 2), 0.5e300);
        assert_eq!(between(0.0, f64::INFINITY, 1, 2), f64::INFINITY);
    }

    #[test]
    fn zero_is_told_from_an_underflow() {
        for zero in ["0", "-0", "0.000", "+0e10", "0E-400", ".0"] {
            assert!(is_zero_text(zero), "{zero}");
        }
        for not in ["1e-400", "-2.5E-999", "0.0001e-400", "10e-401"] {
            assert!(!is_zero_text(not), "{not}");
        }
    }

    /// Numbers read as `f64` reads them, trimmed; an underflow and a non-number are refused
    /// saying what they are.
    #[test]
    fn numbers_and_what_is_not_one() {
        assert_eq!(number("2.5"), Ok(2.5));
        assert_eq!(number(" -1e-300 "), Ok(-1e-300));
        assert_eq!(number("5e-324"), Ok(5e-324));
        assert_eq!(number("-0"), Ok(0.0));
        assert_eq!(number("1e400"), Ok(f64::INFINITY));
        assert!(number("NaN").is_ok_and(f64::is_nan));
        for (text, says) in
            [("1e-400", "too small for a 64-bit float"), ("-3e-325", "would be 0"), ("fast", "not a number")]
        {
            let e = number(text).expect_err(text);
            assert!(e.contains(says), "{text}: {e}");
        }
    }
}
