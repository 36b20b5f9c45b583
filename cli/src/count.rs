//! Counts given on the command line (`--samples`, `--starts`, `--max-points`, ...), read with a
//! message in the command line's terms: Rust's own (`invalid digit found in string`) says
//! nothing of what to write, for `-3` or `2.5` alike.

/// A count: a whole number written in decimal digits, 0 or more. Its bounds (at least 1 or 3,
/// at most a limit) are the commands' checks, which name them.
pub fn count(text: &str) -> Result<usize, String> {
    let digits = text.trim();
    if let Ok(n) = digits.parse::<usize>() {
        return Ok(n);
    }
    Err(match digits.parse::<f64>() {
        Ok(v) if v < 0.0 => "a count cannot be negative: give a whole number such as 361".into(),
        Ok(v) if v.is_finite() && v.fract() == 0.0 && digits.bytes().all(|b| b.is_ascii_digit()) => {
            format!("{digits} is beyond any count this command takes")
        }
        Ok(_) => "a count is a whole number written in digits, such as 361".into(),
        Err(_) => "not a number: a count is a whole number written in digits, such as 361".into(),
    })
}

#[cfg(test)]
mod tests {
    use super::count;

    /// Whole numbers in digits are counts; anything else is refused saying what to write.
    #[test]
    fn counts_and_what_is_not_one() {
        assert_eq!(count("361"), Ok(361));
        assert_eq!(count(" 0 "), Ok(0));
        assert_eq!(count("+7"), Ok(7));
        for (text, says) in [
            ("-3", "cannot be negative"),
            ("-0.5", "cannot be negative"),
            ("2.5", "a whole number written in digits"),
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
