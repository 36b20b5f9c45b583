//! Text made safe inside an SVG or HTML element or attribute: one escaping for the charts
//! ([`plot`](crate::plot)), the drawings ([`draw`](crate::draw)) and the pages
//! ([`html`](crate::html)), which put the same names and labels in all three.

/// `s` with `&`, `<`, `>` and `"` written as entities: safe in a text node and in a
/// double-quoted attribute. A character that XML does not allow at all, not even as an
/// entity (a control character other than tab, line feed and carriage return; U+FFFE,
/// U+FFFF), is written as U+FFFD, the replacement character: the document stays well-formed
/// and shows that something was there.
pub(crate) fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\t' | '\n' | '\r' => out.push(c),
            '\u{0}'..='\u{1f}' | '\u{fffe}' | '\u{ffff}' => out.push('\u{fffd}'),
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::escape;

    #[test]
    fn markup_characters_become_entities() {
        assert_eq!(escape(r#"a < b && c > "d""#), "a &lt; b &amp;&amp; c &gt; &quot;d&quot;");
        assert_eq!(escape("&lt;"), "&amp;lt;");
        assert_eq!(escape("plain"), "plain");
        assert_eq!(escape("a\u{0}\u{1b}\t\n\r\u{ffff}φ"), "a\u{fffd}\u{fffd}\t\n\r\u{fffd}φ");
    }
}
