//! `--params a=1.2,b=3`: parameter values overriding the declared defaults.

use crate::numbers::number;
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
        // Said as what it is: the model's answer, "no parameter ``", named no option.
        if name.is_empty() {
            return Err(exit::usage(format!(
                "`{item}` in --params has no name before `=`: write name=value (the parameters of {}: {})",
                model.name(),
                model.params().join(", ")
            )));
        }
        // Twice is a mistake in one of the two (a copied item not renamed): neither wins.
        if given.contains(&name) {
            eprintln!("error: `{name}` is given twice in --params");
            return Err(Failed(exit::USAGE));
        }
        given.push(name);
        // A number too small for a double is refused: `1e-400` would be 0.
        let v = match number(value) {
            Ok(v) if v.is_finite() => v,
            Ok(_) => return Err(exit::usage(format!("the value of `{name}` in --params is not finite"))),
            Err(e) => return Err(exit::usage(format!("the value of `{name}` in --params: {e}"))),
        };
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
