//! Counts given on the command line (`--samples`, `--starts`, `--max-points`, ...), read with a
//! message in the command line's terms: Rust's own (`invalid digit found in string`) says
//! nothing of what to write, for `-3` or `2.5` alike.

/// A count: a whole number written in decimal digits, 0 or more. Its bounds (at least 1 or 3,
/// at most a limit) are the commands' checks, which name them.
pub fn count(text: &str) -> Result<usize, String> {
    // One example for every count (samples, starts, jobs, frames): a small one, which reads
    // as a count of any of them (`--jobs 2.5` was told "such as 361").
    whole(text, "a count", "10")
}

/// A seed (`synth --seed`): a whole number written in decimal digits, from 0 to the largest
/// 64-bit one, read as a count is (spaces around it allowed, what is wrong said in words:
/// Rust's own message was "invalid digit found in string" for ` 5`, `-1` and `1.5` alike).
pub fn seed(text: &str) -> Result<u64, String> {
    whole(text, "a seed", "7")
}

/// A whole number of type `T` in `text` (trimmed), or what is wrong with it, naming the number
/// as `what` and giving `example`.
fn whole<T: std::str::FromStr>(text: &str, what: &str, example: &str) -> Result<T, String> {
    let digits = text.trim();
    if let Ok(n) = digits.parse::<T>() {
        return Ok(n);
    }
    Err(match digits.parse::<f64>() {
        Ok(v) if v < 0.0 => format!("{what} cannot be negative: give a whole number such as {example}"),
        Ok(v) if v.is_finite() && v.fract() == 0.0 && digits.bytes().all(|b| b.is_ascii_digit()) => {
            format!("{digits} is beyond any {} this command takes", what.trim_start_matches("a "))
        }
        Ok(_) => format!("{what} is a whole number written in digits, such as {example}"),
        Err(_) => format!("not a number: {what} is a whole number written in digits, such as {example}"),
    })
}

#[cfg(test)]
mod tests {
    use super::{count, seed};

    /// A seed is read as a count is, up to the largest 64-bit number.
    #[test]
    fn seeds_and_what_is_not_one() {
        assert_eq!(seed(" 5 "), Ok(5));
        assert_eq!(seed("18446744073709551615"), Ok(u64::MAX));
        for (text, says) in [
            ("-1", "a seed cannot be negative"),
            ("1.5", "a seed is a whole number written in digits, such as 7"),
            ("x", "not a number"),
            ("18446744073709551616", "beyond any seed"),
        ] {
            let e = seed(text).expect_err(text);
            assert!(e.contains(says), "{text}: {e}");
        }
    }

    /// Whole numbers in digits are counts; anything else is refused saying what to write.
    #[test]
    fn counts_and_what_is_not_one() {
        assert_eq!(count("361"), Ok(361));
        assert_eq!(count(" 0 "), Ok(0));
        assert_eq!(count("+7"), Ok(7));
        for (text, says) in [
            ("-3", "cannot be negative"),
            ("-0.5", "cannot be negative"),
            ("2.5", "a whole number written in digits, such as 10"),
            ("1e3", "a whole number written in digits"),
            ("inf", "a whole number written in digits"),
            ("NaN", "a whole number written in digits"),
            ("lots", "not a number"),
            ("", "not a number"),
            ("99999999999999999999999", "beyond any count"),
        ] {
            let e = count(text).expect_err(text);
            assert!(e.contains(says), "{text}: {e}");
        }
    }
}
