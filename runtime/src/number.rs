//! How kinloop writes a number for people and files: the shortest digits that read back to the
//! same `f64`, positional for ordinary magnitudes and in exponent notation beyond them. One
//! function for every place that writes numbers (a table's CSV, the location of an error), so
//! that they agree; the power of two that scales a number exactly ([`pow2_at_most`]), and the
//! Euclidean norm of values at any scale by it ([`norm_of`]). A leaf: it imports nothing from
//! the crate.

use std::fmt;

/// The smallest magnitude written in exponent notation at the large end. From 2^53 (about
/// 9.007e15) on, doubles are integers spaced 2 or more apart, and the shortest digits that
/// identify one are at most 17 significant ones: positionally, 1e16 already needs trailing
/// zeros that carry no information (`10000000000000000`), and 1e300 needs 301 digits. Below it,
/// an integer-valued double is written as the integer, as it reads (the same cut as Python's
/// `repr`).
const LARGE: f64 = 1e16;

/// The largest magnitude written in exponent notation at the small end (exclusive): `1e-5`
/// itself is still `0.00001`, four zeros after the point, which a reader counts at a glance;
/// below it the leading zeros outnumber the significant digits of most values (2e-17 would be
/// sixteen zeros and then `2`), and 5e-324 would be 323 zeros.
const SMALL: f64 = 1e-5;

/// `v` written as [`fmt::Display`] writes it for an ordinary magnitude (`0.1`, `-2.5`, `150`,
/// `1234567.875`), in exponent notation (`1e300`, `2.08e-17`, `-1.5e16`, `5e-324`) for
/// `|v| >= 1e16` or `0 < |v| < 1e-5`; both the shortest digits that read back (`str::parse`)
/// to the same bits. Zero, infinities and NaN are written as Rust writes them (`0`, `-0`, `inf`,
/// `-inf`, `NaN`). Of the shortest texts the one closest to the value, and where the value lies
/// exactly halfway between two, the one whose last digit is even (as Python's `repr`; Rust's
/// own `{}` takes the larger). Formatting flags (width, precision) are not applied: the digits
/// are the number's own.
///
/// ```
/// use kinloop_runtime::Number;
/// assert_eq!(Number(0.1).to_string(), "0.1");
/// assert_eq!(Number(1234567.875).to_string(), "1234567.875");
/// assert_eq!(Number(1e300).to_string(), "1e300");
/// assert_eq!(Number(-2.08e-17).to_string(), "-2.08e-17");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Number(pub f64);

impl Number {
    /// Appends the number's text to `out`, as [`fmt::Display`] writes it, without going through
    /// the formatting machinery: what a long table written row by row calls for each field.
    ///
    /// ```
    /// use kinloop_runtime::Number;
    /// let mut line = String::from("x,");
    /// Number(-2.5).push_to(&mut line);
    /// assert_eq!(line, "x,-2.5");
    /// ```
    pub fn push_to(self, out: &mut String) {
        let mut digits = ryu::Buffer::new();
        out.push_str(self.text(&mut digits));
    }

    /// The text, in `buffer` when the number is finite. Ryu's shortest digits, the closest to
    /// the value of those that read back (what Rust's own `{}` and `{:e}` write, measured to the
    /// bit in this module's tests), are laid out at the same cut as [`SMALL`] and [`LARGE`]
    /// (positional for `1e-5 <= |v| < 1e16`, exponent notation beyond, its exponent without a
    /// `+`): only an integer's `.0` (and zero's) is dropped, as Rust writes `150`, `-0`. About
    /// four times faster than Rust's formatting, which spends most of a long CSV's time.
    fn text(self, buffer: &mut ryu::Buffer) -> &str {
        let v = self.0;
        if !v.is_finite() {
            return if v.is_nan() {
                "NaN"
            } else if v > 0.0 {
                "inf"
            } else {
                "-inf"
            };
        }
        let s = buffer.format_finite(v);
        // Ryu changes notation where the shortest digits cross a power of ten, as the cut is.
        debug_assert_eq!(s.contains('e'), v != 0.0 && !(SMALL..LARGE).contains(&v.abs()), "{s}");
        s.strip_suffix(".0").unwrap_or(s)
    }
}

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut digits = ryu::Buffer::new();
        f.write_str(self.text(&mut digits))
    }
}

/// A count `n` of the regular noun `noun` (given in the singular) as a message writes it: `1
/// iteration`, `0 iterations`, `2 iterations`. The noun takes an `s` for any count but one, so a
/// message reads right whatever the count (`did not converge in 1 iteration`, never `in 1
/// iterations`). Public so that the run-time reader and the command line write their counts as
/// the library's messages do (`kinloop_model::Count` is this type).
///
/// ```
/// use kinloop_runtime::Count;
/// assert_eq!(Count(1, "input").to_string(), "1 input");
/// assert_eq!(Count(0, "value").to_string(), "0 values");
/// assert_eq!(Count(3, "unknown").to_string(), "3 unknowns");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Count<'a>(pub usize, pub &'a str);

impl fmt::Display for Count<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Count(n, noun) = *self;
        write!(f, "{n} {noun}{}", if n == 1 { "" } else { "s" })
    }
}

/// The sign of `v`, `0` at zero and at NaN: the macro graph's `sign` (its constant folder's), and
/// "no orientation to compare" where the paths compare signs.
pub(crate) fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The largest power of two not above `m` (positive, finite): dividing by it is exact, so a
/// computation at any scale can be made near 1 and scaled back.
pub(crate) fn pow2_at_most(m: f64) -> f64 {
    let bits = m.to_bits();
    if m.is_normal() {
        f64::from_bits(bits & 0x7ff0_0000_0000_0000)
    } else {
        f64::from_bits(1u64 << (63 - bits.leading_zeros()))
    }
}

/// The Euclidean norm of `values`, each divided by the power of two at most the largest first
/// (exact) so that no square leaves the range of `f64`: the residuals of targets near `1e308`
/// have squares beyond it. NaN if a value is NaN, infinite if one is infinite.
pub(crate) fn norm_of(values: impl IntoIterator<Item = f64> + Clone) -> f64 {
    let mut big = 0.0f64;
    for v in values.clone() {
        // `f64::max` passes over a NaN: kept here instead.
        if v.is_nan() || v.abs() > big {
            big = v.abs();
        }
        if big.is_nan() {
            return big;
        }
    }
    if big == 0.0 || big == f64::INFINITY {
        return big;
    }
    let unit = pow2_at_most(big);
    values.into_iter().map(|v| (v / unit) * (v / unit)).sum::<f64>().sqrt() * unit
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the plain formula where it holds, and exactly scaled beyond it.
    #[test]
    fn norms_of_values_whose_squares_leave_f64() {
        assert_eq!(norm_of([3.0, 4.0]), 5.0);
        assert_eq!(norm_of([0.0; 3]), 0.0);
        assert_eq!(norm_of(std::iter::empty::<f64>()), 0.0);
        for k in [-1074, -600, 600, 970] {
            let s = 2f64.powi(k);
            assert_eq!(norm_of([3.0 * s, -4.0 * s]), 5.0 * s, "{k}");
        }
        assert!(norm_of([1.0, f64::NAN, 1e308]).is_nan() && norm_of([f64::NAN, f64::INFINITY]).is_nan());
        assert_eq!(norm_of([1.0, f64::NEG_INFINITY]), f64::INFINITY);
    }

    fn number(v: f64) -> String {
        Number(v).to_string()
    }

    /// Reads `s` back and checks it is `v`, bit for bit (any NaN for a NaN).
    fn reads_back(v: f64, s: &str) {
        let back: f64 = s.parse().unwrap_or_else(|e| panic!("`{s}` (written for {v:?}) does not parse: {e}"));
        assert!(
            back.to_bits() == v.to_bits() || (v.is_nan() && back.is_nan()),
            "`{s}` reads back as {back:?}, not {v:?}"
        );
    }

    /// Checks the form of `v`'s text: the positional text of today inside the range, exponent
    /// notation outside, no more characters than the shortest digits need.
    fn form(v: f64, s: &str) {
        let a = v.abs();
        if a.is_finite() && a != 0.0 && !(SMALL..LARGE).contains(&a) {
            assert!(s.contains('e'), "{v:?} written `{s}`: exponent notation expected");
            // Mantissa digits and an exponent of at most three digits and its sign: a double
            // needs at most 17 significant digits.
            assert!(s.len() <= 1 + 17 + 1 + 1 + 4, "{v:?} written `{s}`: too long");
            // The digits Rust's own formatting writes: an implementation independent of ryu.
            as_rust_writes(v, s, &format!("{v:e}"));
        } else {
            as_rust_writes(v, s, &v.to_string());
        }
        let mut pushed = String::from("x");
        Number(v).push_to(&mut pushed);
        assert_eq!(pushed[1..], *s, "{v:?}: push_to writes what Display writes");
    }

    /// `ours` is what Rust writes, `rust`, or both are the shortest digits and `v` lies exactly
    /// halfway between them: there ryu writes the even last digit (as Python's `repr` does),
    /// Rust the larger one. The exact decimal value of `v` (Rust's formatting with enough
    /// digits is exact: a double has at most 767 significant ones) decides the tie.
    fn as_rust_writes(v: f64, ours: &str, rust: &str) {
        if ours == rust {
            return;
        }
        let split = |t: &str| t.split_once('e').map_or((t.to_string(), String::new()), |(m, e)| (m.into(), e.into()));
        let ((m_ours, e_ours), (m_rust, e_rust)) = (split(ours), split(rust));
        let n = m_ours.len();
        assert!(
            e_ours == e_rust && m_rust.len() == n && m_ours[..n - 1] == m_rust[..n - 1],
            "{v:?} written `{ours}`, by Rust `{rust}`: not the same shortest digits"
        );
        let digit = |m: &str| m.as_bytes()[n - 1] - b'0';
        let (d_ours, d_rust) = (digit(&m_ours), digit(&m_rust));
        assert!(d_ours % 2 == 0 && d_ours.abs_diff(d_rust) == 1, "{v:?} written `{ours}`, by Rust `{rust}`: not a tie");
        // The exact value's significant digits: the shorter texts' common ones, the lower last
        // digit, then a 5 and nothing else.
        let significant = |t: &str| {
            let digits: String = t.split('e').next().unwrap_or("").chars().filter(char::is_ascii_digit).collect();
            digits.trim_start_matches('0').to_string()
        };
        let exact = significant(&format!("{:.800e}", v.abs()));
        let shortest = significant(&m_ours);
        let below = format!("{}{}5", &shortest[..shortest.len() - 1], d_ours.min(d_rust));
        assert!(
            exact.starts_with(&below) && exact[below.len()..].bytes().all(|b| b == b'0'),
            "{v:?} written `{ours}`, by Rust `{rust}`: its exact value {exact} is not halfway"
        );
    }

    fn check(v: f64) {
        let s = number(v);
        reads_back(v, &s);
        form(v, &s);
    }

    #[test]
    fn the_examples_read_as_documented() {
        assert_eq!(number(1e300), "1e300");
        assert_eq!(number(1e-300), "1e-300");
        assert_eq!(number(2.08e-17), "2.08e-17");
        assert_eq!(number(-1.5e16), "-1.5e16");
        assert_eq!(number(5e-324), "5e-324");
        assert_eq!(number(f64::MAX), "1.7976931348623157e308");
        // Ordinary numbers as Display writes them.
        assert_eq!(number(0.1), "0.1");
        assert_eq!(number(150.0), "150");
        assert_eq!(number(-2.5), "-2.5");
        assert_eq!(number(1e-5), "0.00001");
        assert_eq!(number(9999999999999998.0), "9999999999999998");
        assert_eq!(number(0.1 + 0.2), "0.30000000000000004");
        // Exactly halfway between two shortest texts: the even last digit (Rust's `{}` writes
        // `...305.13`).
        assert_eq!(number(-(153117458836305.0 + 0.125)), "-153117458836305.12");
        // The specials as Rust writes them, as today.
        assert_eq!(number(0.0), "0");
        assert_eq!(number(-0.0), "-0");
        assert_eq!(number(f64::INFINITY), "inf");
        assert_eq!(number(f64::NEG_INFINITY), "-inf");
        assert_eq!(number(f64::NAN), "NaN");
        // The Display wrapper writes the same.
        assert_eq!(format!("x = {}", Number(1e300)), "x = 1e300");
    }

    #[test]
    fn every_number_written_reads_back_to_its_bits() {
        let mut special = vec![
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::EPSILON,
            1.0 / 3.0,
            std::f64::consts::PI,
        ];
        // The subnormals: the least, the largest, and some between.
        special.extend([f64::from_bits(1), f64::from_bits(2), f64::from_bits(0x000f_ffff_ffff_ffff)]);
        special.extend((0..52).map(|k| f64::from_bits(1u64 << k)));
        // Both sides of both cuts, and every power of ten.
        for cut in [SMALL, LARGE] {
            special.extend([cut, cut.next_down(), cut.next_up()]);
        }
        special.extend((-324..=308).map(|e| format!("1e{e}").parse::<f64>().unwrap_or(0.0)));
        for v in special {
            check(v);
            check(-v);
        }
        // Random bit patterns (every exponent, every sign, NaNs with payloads).
        let mut rng = crate::test_rng::Rng(0x9e37_79b9_7f4a_7c15);
        for _ in 0..200_000 {
            let hi = (rng.uniform(0.0, 1.0) * (1u64 << 32) as f64) as u64;
            let lo = (rng.uniform(0.0, 1.0) * (1u64 << 32) as f64) as u64;
            check(f64::from_bits(hi << 32 | lo));
        }
        // Random magnitudes spread over the decades around the cuts.
        for _ in 0..100_000 {
            let v = 10f64.powf(rng.uniform(-30.0, 30.0)) * rng.uniform(-1.0, 1.0);
            check(v);
        }
    }
}
