//! What to write instead of a character typed or pasted from a document that starts no token:
//! a typographic sign that looks like an operator (`−`, `×`, `≤`, a curly quote), or a sign of
//! mathematical notation the declaration language writes otherwise (`°`, `²`, `√`, `½`), or a
//! full-width sign from an East Asian keyboard (`（`, `；`). The compiler names such a character
//! with the ASCII one it looks like; a `.kl` file deserves the same help, in the declaration
//! language's terms.

/// The help for the character `c`, which starts no token, or `None` where there is none to give
/// (a character that looks like no operator).
pub(crate) fn help(c: char) -> Option<String> {
    let looks_like = |ascii: &str, write: &str| format!("`{c}` (U+{:04X}) looks like `{ascii}`; {write}", c as u32);
    let same = |ascii: &str| looks_like(ascii, &format!("write `{ascii}`"));
    // No comparison in a declaration: an equation is `lhs == rhs`, a bound `min`, `max` or
    // `clamp`; the advice to write `<=` would lead to the next error.
    let no_comparison = |ascii: &str| {
        looks_like(
            ascii,
            "a declaration has no comparisons: an equation is written `lhs == rhs`, a bound with `min`, `max` or \
             `clamp`",
        )
    };
    Some(match c {
        '\u{2212}' | '\u{2010}' | '\u{2011}' | '\u{2012}' | '\u{2013}' | '\u{2014}' | '\u{fe63}' | '\u{ff0d}' => {
            same("-")
        }
        '\u{00d7}' | '\u{00b7}' | '\u{2219}' | '\u{22c5}' | '\u{2217}' => same("*"),
        '\u{00f7}' | '\u{2215}' | '\u{2044}' => same("/"),
        '\u{ff0b}' => same("+"),
        '\u{2264}' => no_comparison("<="),
        '\u{2265}' => no_comparison(">="),
        '\u{2260}' => no_comparison("!="),
        '\u{201c}' | '\u{201d}' | '\u{201e}' | '\u{201f}' => same("\""),
        '\u{2018}' | '\u{2019}' | '\u{201a}' | '\u{201b}' => {
            looks_like("'", "a declaration has no character literals: write `\"` around a text")
        }
        '\u{00b0}' => format!(
            "`{c}` (U+00B0) is no operator: write an angle in degrees as `deg(30)` (30 degrees, in radians), or in \
             radians"
        ),
        '\u{00b2}' => power(c, 2),
        '\u{00b3}' => power(c, 3),
        '\u{00b9}' => power(c, 1),
        '\u{2070}' => power(c, 0),
        '\u{2074}'..='\u{2079}' => power(c, c as u32 - 0x2070),
        '\u{207b}' => format!(
            "`{c}` (U+207B) is no operator: write a negative power as `x ^ -1` or `pow(x, -1)`, a reciprocal as `1 / x`"
        ),
        '\u{221a}' => format!("`{c}` (U+221A) is no operator: write a square root as `sqrt(x)`"),
        '\u{00bd}' => fraction(c, 1, 2),
        '\u{00bc}' => fraction(c, 1, 4),
        '\u{00be}' => fraction(c, 3, 4),
        '\u{2153}' => fraction(c, 1, 3),
        '\u{2154}' => fraction(c, 2, 3),
        // An equation's sign, typed with an East Asian keyboard: the equation is `lhs == rhs`.
        '\u{ff1d}' => looks_like("=", "an equation is written `lhs == rhs`"),
        // The rest of the full-width forms of ASCII signs and digits (U+FF01 to U+FF5E, each
        // 0xFEE0 above its ASCII character); their letters are letters, names of their own.
        '\u{ff01}'..='\u{ff5e}' => match char::from_u32(c as u32 - 0xfee0) {
            Some(ascii) if !ascii.is_ascii_alphabetic() => same(&ascii.to_string()),
            _ => return None,
        },
        _ => return None,
    })
}

/// The help for the vulgar fraction `c`, `numerator / denominator`.
fn fraction(c: char, numerator: u32, denominator: u32) -> String {
    format!("`{c}` (U+{:04X}) is no number: write `{numerator} / {denominator}`", c as u32)
}

/// The help for the superscript digit `c`, the power `n`.
fn power(c: char, n: u32) -> String {
    format!("`{c}` (U+{:04X}) is no operator: write a power as `x ^ {n}` or `pow(x, {n})`", c as u32)
}

#[cfg(test)]
mod tests {
    use super::help;

    /// Each sign is told what to write, in the declaration language's terms.
    #[test]
    fn signs_are_told_what_to_write() {
        assert_eq!(help('\u{2212}').as_deref(), Some("`\u{2212}` (U+2212) looks like `-`; write `-`"));
        assert_eq!(help('×').as_deref(), Some("`×` (U+00D7) looks like `*`; write `*`"));
        assert!(help('°').is_some_and(|h| h.contains("`deg(30)`")));
        assert!(help('²').is_some_and(|h| h.contains("`x ^ 2`")));
        assert!(help('≤').is_some_and(|h| h.contains("no comparisons")));
        assert!(help('⁴').is_some_and(|h| h.contains("`x ^ 4`")));
        assert!(help('⁰').is_some_and(|h| h.contains("`x ^ 0`")));
        assert!(help('⁻').is_some_and(|h| h.contains("`x ^ -1`")));
        assert!(help('√').is_some_and(|h| h.contains("`sqrt(x)`")));
        assert!(help('½').is_some_and(|h| h.contains("`1 / 2`")));
        assert!(help('⅔').is_some_and(|h| h.contains("`2 / 3`")));
        // Full-width signs and digits are their ASCII characters; the equals sign is told the
        // equation's `==`.
        assert_eq!(help('（').as_deref(), Some("`（` (U+FF08) looks like `(`; write `(`"));
        assert_eq!(help('；').as_deref(), Some("`；` (U+FF1B) looks like `;`; write `;`"));
        assert_eq!(help('３').as_deref(), Some("`３` (U+FF13) looks like `3`; write `3`"));
        assert!(help('＝').is_some_and(|h| h.contains("`lhs == rhs`")));
        assert_eq!(help('€'), None);
    }
}
