//! The columns a command writes of its own beside a mechanism's names (`omega` beside a
//! crank's input, `kind` and `tau` beside an event's inputs and unknowns): a name of the
//! mechanism among them would name two columns alike in one header, which a CSV reader finds
//! by name (the runtime's reader refuses such a header; others take the first). One check for
//! every command, made before the run rather than after it.

use crate::{Failed, exit};

/// A command's own columns and the words of its refusal of a name among them.
pub(crate) struct Own<'a> {
    /// The command, with its option where the columns are that option's file
    /// (`kinloop sweep --events`).
    pub command: &'a str,
    /// The columns it writes of its own.
    pub columns: &'a [&'a str],
    /// Whose columns they are written beside (`input's`, `design variables'`).
    pub beside: &'a str,
    /// What renaming achieves, after `in its declaration` (`""`, `" to vary it"`).
    pub rename_to: &'a str,
    /// What would name two columns alike (`its table`, `the events file`).
    pub written: &'a str,
}

/// Refuses the first of `names`, each `(what, name)` (`("input", "phi")`), that is one of
/// `own`'s columns: a usage error naming it and asking to rename it in the declaration of
/// `mechanism`.
pub(crate) fn check<'n>(
    own: &Own,
    mechanism: &str,
    names: impl IntoIterator<Item = (&'n str, &'n str)>,
) -> Result<(), Failed> {
    match names.into_iter().find(|(_, name)| own.columns.contains(name)) {
        Some((what, name)) => Err(exit::usage(format!(
            "{} writes a column `{name}` of its own beside the {}: rename the {what} `{name}` of {mechanism} in its \
             declaration{}, or {} would name two columns `{name}`",
            own.command, own.beside, own.rename_to, own.written
        ))),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::{Own, check};

    const OWN: Own = Own {
        command: "kinloop sweep --events",
        columns: &["kind", "tau"],
        beside: "inputs' and unknowns'",
        rename_to: "",
        written: "the events file",
    };

    /// The first name among the columns is refused; names beside them (a prefix, another
    /// case) are not.
    #[test]
    fn a_name_among_the_command_s_columns_is_refused() {
        assert!(check(&OWN, "FourBar", [("input", "phi"), ("unknown", "kinds"), ("unknown", "Tau")]).is_ok());
        assert!(check(&OWN, "FourBar", [("input", "phi"), ("unknown", "tau"), ("unknown", "kind")]).is_err());
    }
}
