//! Names given on the command line (`--point`, `--cam`, `--path`, `--show`), read as the
//! numbers beside them are: spaces around them are not part of them. `--point " follower"` (a
//! name pasted with its space, or a quoted list split by hand) was "no point of that name"
//! while listing `follower` among the points, and `--roller " 10"` read as 10.

/// A name: `text` without the spaces around it. An empty name is kept empty: each command's
/// own check refuses it, listing the names it takes.
pub fn name(text: &str) -> Result<String, String> {
    Ok(text.trim().to_string())
}

/// What is wrong with `name`, none of `known`, where it holds letters of another script that
/// look like Latin ones (`а`, U+0430, Cyrillic, for `a`: a keyboard left on another layout, a
/// name pasted from a document): each such letter with its code point and the one it
/// resembles, and the name to write where that is one of `known`. Empty otherwise. Without it
/// "no parameter `а`" stood beside a list holding `a`, the two alike. Every option that takes a
/// declared name (`--params`, `--vary`, `--columns`, `--point`, `--path`, `--show`) says it.
pub fn look_alike(name: &str, known: &[impl AsRef<str>]) -> String {
    let mut letters: Vec<String> = Vec::new();
    let mut latin = String::with_capacity(name.len());
    for c in name.chars() {
        match kinloop_model::latin_lookalike(c) {
            Some((l, script)) => {
                let said = format!("`{c}` (U+{:04X}) is a {script} letter that looks like the Latin `{l}`", c as u32);
                if !letters.contains(&said) {
                    letters.push(said);
                }
                latin.push(l);
            }
            None => latin.push(c),
        }
    }
    if letters.is_empty() {
        return String::new();
    }
    let write = if known.iter().any(|k| k.as_ref() == latin) { format!("; write `{latin}`") } else { String::new() };
    format!(": {}{write}", letters.join(", "))
}

/// [`look_alike`] said after a message that ends with its list of names: in parentheses, or
/// nothing.
pub fn look_alike_after(name: &str, known: &[impl AsRef<str>]) -> String {
    match look_alike(name, known).strip_prefix(": ") {
        Some(said) => format!(" ({said})"),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::{look_alike, name};

    /// Spaces and tabs around a name go; those inside it stay (no name has them, and the
    /// command's check then names what it takes).
    #[test]
    fn spaces_around_a_name_are_not_part_of_it() {
        assert_eq!(name(" follower"), Ok("follower".to_string()));
        assert_eq!(name("pc.x\t "), Ok("pc.x".to_string()));
        assert_eq!(name("beta"), Ok("beta".to_string()));
        assert_eq!(name("  "), Ok(String::new()));
        assert_eq!(name("a b"), Ok("a b".to_string()));
    }

    /// Each look-alike letter is named once with the one it resembles; the name to write is
    /// given only where it is one of those known, and a name of ASCII or of letters of their own
    /// has nothing to add.
    #[test]
    fn look_alike_letters_are_named_and_the_name_meant_given() {
        let known = ["a", "phi0", "lift"];
        assert_eq!(
            look_alike("\u{430}", &known),
            ": `\u{430}` (U+0430) is a Cyrillic letter that looks like the Latin `a`; write `a`"
        );
        assert_eq!(
            look_alike("ph\u{456}0", &known),
            ": `\u{456}` (U+0456) is a Cyrillic letter that looks like the Latin `i`; write `phi0`"
        );
        // Not known once written in Latin letters (Greek omicron twice): the letter is still
        // named, once.
        assert_eq!(
            look_alike("\u{3bf}\u{3bf}", &known),
            ": `\u{3bf}` (U+03BF) is a Greek letter that looks like the Latin `o`"
        );
        assert_eq!(look_alike("b", &known), "");
        assert_eq!(look_alike("\u{3b1}", &known), "");
    }
}
