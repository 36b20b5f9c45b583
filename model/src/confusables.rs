//! What to write instead of a character typed or pasted from a document that starts no token:
//! a typographic sign that looks like an operator (`−`, `×`, `≤`, a curly quote), or a sign of
//! mathematical notation the declaration language writes otherwise (`°`, `²`, `√`, `½`), or a
//! full-width sign from an East Asian keyboard (`（`, `；`). The compiler names such a character
//! with the ASCII one it looks like; a `.kl` file deserves the same help, in the declaration
//! language's terms.
//!
//! And the Latin letter that a letter of another script looks like ([`latin_lookalike`]): such a
//! letter starts a name, a name of its own, which a reader told "no parameter `а`" beside `a`
//! cannot tell from the one meant.

/// The help for the character `c`, which starts no token, or `None` where there is none to give
/// (a character that looks like no operator).
pub(crate) fn help(c: char) -> Option<String> {
    if let Some(what) = invisible(c) {
        return Some(format!("U+{:04X} ({what}) is invisible in most editors: remove it", c as u32));
    }
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

/// The Latin letter that `c`, a letter of another script, looks like in common fonts, with the
/// name of its script: `Some(('a', "Cyrillic"))` for `а` (U+0430). A name typed with such a
/// letter (a keyboard left on another layout, a name pasted from a document) is another name
/// that reads the same: "no parameter `а`" beside a list holding `a` says nothing of why.
/// `None` for an ASCII character and for a letter that reads as itself (Greek `α`, `β`, whose
/// shapes are their own, may well be meant).
///
/// The letters are those of Unicode's confusables (UTS #39) that look like a Latin letter in
/// a sans-serif face: the Cyrillic and Greek letters drawn alike, and the full-width Latin
/// letters of East Asian keyboards.
///
/// ```
/// use kinloop_model::latin_lookalike;
/// assert_eq!(latin_lookalike('\u{430}'), Some(('a', "Cyrillic")));
/// assert_eq!(latin_lookalike('\u{39f}'), Some(('O', "Greek")));
/// assert_eq!(latin_lookalike('a'), None);
/// assert_eq!(latin_lookalike('\u{3b1}'), None); // alpha: a letter of its own
/// ```
pub fn latin_lookalike(c: char) -> Option<(char, &'static str)> {
    let latin = match c {
        // Cyrillic, small and capital.
        '\u{430}' => 'a',
        '\u{435}' => 'e',
        '\u{43e}' => 'o',
        '\u{440}' => 'p',
        '\u{441}' => 'c',
        '\u{443}' => 'y',
        '\u{445}' => 'x',
        '\u{455}' => 's',
        '\u{456}' => 'i',
        '\u{458}' => 'j',
        '\u{4bb}' => 'h',
        '\u{501}' => 'd',
        '\u{51b}' => 'q',
        '\u{51d}' => 'w',
        '\u{405}' => 'S',
        '\u{406}' => 'I',
        '\u{408}' => 'J',
        '\u{410}' => 'A',
        '\u{412}' => 'B',
        '\u{415}' => 'E',
        '\u{41a}' => 'K',
        '\u{41c}' => 'M',
        '\u{41d}' => 'H',
        '\u{41e}' => 'O',
        '\u{420}' => 'P',
        '\u{421}' => 'C',
        '\u{422}' => 'T',
        '\u{423}' => 'Y',
        '\u{425}' => 'X',
        // Greek: omicron and nu small, and the capitals drawn as Latin ones.
        '\u{3bf}' => 'o',
        '\u{3bd}' => 'v',
        '\u{391}' => 'A',
        '\u{392}' => 'B',
        '\u{395}' => 'E',
        '\u{396}' => 'Z',
        '\u{397}' => 'H',
        '\u{399}' => 'I',
        '\u{39a}' => 'K',
        '\u{39c}' => 'M',
        '\u{39d}' => 'N',
        '\u{39f}' => 'O',
        '\u{3a1}' => 'P',
        '\u{3a4}' => 'T',
        '\u{3a5}' => 'Y',
        '\u{3a7}' => 'X',
        // Full-width Latin letters (U+FF21 to U+FF3A, U+FF41 to U+FF5A): 0xFEE0 above ASCII.
        '\u{ff21}'..='\u{ff3a}' | '\u{ff41}'..='\u{ff5a}' => {
            return char::from_u32(c as u32 - 0xfee0).map(|l| (l, "full-width"));
        }
        _ => return None,
    };
    let script = if ('\u{370}'..='\u{3ff}').contains(&c) { "Greek" } else { "Cyrillic" };
    Some((latin, script))
}

/// What a character most editors do not show is, where `c` is one: a zero-width space or
/// joiner, a byte order mark (which only starts a file), a soft hyphen, a control of the text's
/// direction, a variation selector. Between tokens the compiler refuses one as an unknown start
/// of token, naming a character that cannot be seen; the joiners and the variation selectors
/// continue a name, which is then another name that prints alike.
pub(crate) fn invisible(c: char) -> Option<&'static str> {
    Some(match c {
        '\u{ad}' => "soft hyphen",
        '\u{200b}' => "zero width space",
        '\u{200c}' => "zero width non-joiner",
        '\u{200d}' => "zero width joiner",
        '\u{2060}' => "word joiner",
        '\u{2061}'..='\u{2064}' => "invisible operator",
        '\u{feff}' => "zero width no-break space, the byte order mark",
        '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' => "control of the text's direction",
        '\u{180b}'..='\u{180d}' | '\u{180f}' | '\u{fe00}'..='\u{fe0f}' | '\u{e0100}'..='\u{e01ef}' => {
            "variation selector"
        }
        _ => return None,
    })
}

/// `name` as it reads: each letter [`latin_lookalike`] knows replaced by the Latin one it looks
/// like and each character most editors do not show ([`invisible`]) left out, with those
/// characters described (`` `а` (U+0430) is a Cyrillic letter that looks like the Latin `a` ``,
/// `the name holds U+200D (zero width joiner), which most editors do not show`, each once); `None`
/// where `name` holds none.
pub(crate) fn latin_name(name: &str) -> Option<(String, String)> {
    let mut said: Vec<String> = Vec::new();
    let mut latin = String::with_capacity(name.len());
    for c in name.chars() {
        let this = if let Some((l, script)) = latin_lookalike(c) {
            latin.push(l);
            format!("`{c}` (U+{:04X}) is a {script} letter that looks like the Latin `{l}`", c as u32)
        } else if let Some(what) = invisible(c) {
            format!("the name holds U+{:04X} ({what}), which most editors do not show", c as u32)
        } else {
            latin.push(c);
            continue;
        };
        if !said.contains(&this) {
            said.push(this);
        }
    }
    (!said.is_empty()).then(|| (latin, said.join(", ")))
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

    /// Every look-alike letter is a letter of its script that is not ASCII, named with the
    /// ASCII letter of its case; the letters that read as themselves have none.
    #[test]
    fn look_alike_letters_name_the_latin_letter_of_their_case() {
        use super::latin_lookalike;
        let all = ('\u{370}'..='\u{52f}').chain('\u{ff00}'..='\u{ffef}');
        let found: Vec<(char, char, &str)> =
            all.filter_map(|c| latin_lookalike(c).map(|(l, script)| (c, l, script))).collect();
        assert_eq!(found.len(), 29 + 16 + 52, "{found:?}");
        for (c, l, script) in found {
            assert!(c.is_alphabetic() && l.is_ascii_alphabetic(), "{c} {l}");
            assert_eq!(c.is_uppercase(), l.is_ascii_uppercase(), "{c} (U+{:04X}) as {l}", c as u32);
            assert!(["Cyrillic", "Greek", "full-width"].contains(&script), "{c}: {script}");
        }
        assert_eq!(latin_lookalike('\u{430}'), Some(('a', "Cyrillic")));
        assert_eq!(latin_lookalike('\u{3bf}'), Some(('o', "Greek")));
        assert_eq!(latin_lookalike('\u{ff41}'), Some(('a', "full-width")));
        assert_eq!(latin_lookalike('\u{ff3a}'), Some(('Z', "full-width")));
        for own in ['a', 'Z', '_', '\u{3b1}', '\u{3b2}', '\u{3c6}', '\u{436}', '\u{ff10}', '\u{ff3f}'] {
            assert_eq!(latin_lookalike(own), None, "{own}");
        }
    }
}
