//! Text made safe inside an SVG or HTML element or attribute: one escaping for the charts
//! ([`plot`](crate::plot)), the drawings ([`draw`](crate::draw)) and the pages
//! ([`html`](crate::html)), which put the same names and labels in all three.

/// `s` with `&`, `<`, `>` and `"` written as entities: safe in a text node and in a
/// double-quoted attribute.
pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::escape;

    #[test]
    fn markup_characters_become_entities() {
        assert_eq!(escape(r#"a < b && c > "d""#), "a &lt; b &amp;&amp; c &gt; &quot;d&quot;");
        assert_eq!(escape("&lt;"), "&amp;lt;");
        assert_eq!(escape("plain"), "plain");
    }
}
