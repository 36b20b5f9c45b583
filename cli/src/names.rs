//! Names given on the command line (`--point`, `--cam`, `--path`, `--show`), read as the
//! numbers beside them are: spaces around them are not part of them. `--point " follower"` (a
//! name pasted with its space, or a quoted list split by hand) was "no point of that name"
//! while listing `follower` among the points, and `--roller " 10"` read as 10.

/// A name: `text` without the spaces around it. An empty name is kept empty: each command's
/// own check refuses it, listing the names it takes.
pub fn name(text: &str) -> Result<String, String> {
    Ok(text.trim().to_string())
}

#[cfg(test)]
mod tests {
    use super::name;

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
}
