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

#[cfg(test)]
mod tests {
    use super::{is_zero_text, number};

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
