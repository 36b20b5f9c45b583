//! `--params a=1.2,b=3`: parameter values overriding the declared defaults.

use crate::numbers::{is_zero_text, underflow};
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
            eprintln!("error: the value of `{name}` in --params: {}", underflow(value));
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
