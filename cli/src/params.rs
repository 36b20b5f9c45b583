//! `--params a=1.2,b=3`: parameter values overriding the declared defaults.

use crate::{Failed, exit};
use kinloop_model::Model;

/// Sets the parameters listed in `list` (`name=value` separated by commas), each at most once.
pub fn apply(model: &mut Model, list: &str) -> Result<(), Failed> {
    let mut given: Vec<&str> = Vec::new();
    for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let Some((name, value)) = item.split_once('=') else {
            eprintln!("error: `{item}` in --params is not `name=value`");
            return Err(Failed(exit::USAGE));
        };
        let (name, value) = (name.trim(), value.trim());
        // Twice is a mistake in one of the two (a copied item not renamed): neither wins.
        if given.contains(&name) {
            eprintln!("error: `{name}` is given twice in --params");
            return Err(Failed(exit::USAGE));
        }
        given.push(name);
        let Ok(v) = value.parse::<f64>() else {
            eprintln!("error: the value of `{name}` in --params, `{value}`, is not a number");
            return Err(Failed(exit::USAGE));
        };
        if !v.is_finite() {
            eprintln!("error: the value of `{name}` in --params is not finite");
            return Err(Failed(exit::USAGE));
        }
        if v == 0.0 && !is_zero_text(value) {
            eprintln!(
                "error: the value of `{name}` in --params, `{value}`, is too small for a 64-bit float and would be 0: \
                 give 0 if 0 is meant, or express the model in other units"
            );
            return Err(Failed(exit::USAGE));
        }
        if !model.set_param(name, v) {
            eprintln!(
                "error: {} has no parameter `{name}` (its parameters: {})",
                model.name(),
                model.params().join(", ")
            );
            return Err(Failed(exit::USAGE));
        }
    }
    Ok(())
}

/// Whether the number `text` (one that parses) is written as zero: no digit but 0 before its
/// exponent. `1e-400` is not, though it parses to 0 (it underflows), as `1e400` overflows.
pub(crate) fn is_zero_text(text: &str) -> bool {
    let mantissa = text.split(['e', 'E']).next().unwrap_or(text);
    !mantissa.chars().any(|c| c.is_ascii_digit() && c != '0')
}

/// Every parameter of `model` has a value: a default, or one given. Otherwise a usage error
/// naming each one missing and how to give it: the declaration leaves it to the command line,
/// and no solve can start without it.
pub fn require_values(model: &Model) -> Result<(), Failed> {
    let missing: Vec<&str> = (model.params().iter().zip(model.param_values()))
        .filter(|(_, v)| v.is_none())
        .map(|(p, _)| p.as_str())
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    let names = missing.iter().map(|p| format!("`{p}`")).collect::<Vec<_>>().join(", ");
    let give = missing.iter().map(|p| format!("{p}=VALUE")).collect::<Vec<_>>().join(",");
    let (what, verb, them) = match missing.len() {
        1 => ("parameter", "has", "it"),
        _ => ("parameters", "have", "them"),
    };
    Err(exit::usage(format!(
        "{}: {what} {names} {verb} no value (the declaration gives {them} no default): give {them} with --params {give}",
        model.name()
    )))
}

#[cfg(test)]
mod tests {
    use super::is_zero_text;

    #[test]
    fn zero_is_told_from_an_underflow() {
        for zero in ["0", "-0", "0.000", "+0e10", "0E-400", ".0"] {
            assert!(is_zero_text(zero), "{zero}");
        }
        for not in ["1e-400", "-2.5E-999", "0.0001e-400", "10e-401"] {
            assert!(!is_zero_text(not), "{not}");
        }
    }
}
