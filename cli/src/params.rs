//! `--params a=1.2,b=3`: parameter values overriding the declared defaults.

use crate::numbers::number;
use crate::{Failed, exit};
use kinloop_model::Model;
use kinloop_runtime::Number;

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
                "error: {} has no parameter `{name}`{} (its parameters: {})",
                model.name(),
                crate::names::look_alike(name, model.params()),
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

/// Every angle parameter of `model` is within the largest angle its solves take precisely
/// (`NewtonConfig::largest_precise_angle` of its configuration). Otherwise a usage error naming
/// the parameter and how to give it: every solve refuses it (an angle added to it is lost to
/// rounding), with the library's advice, `phi0.rem_euclid(TAU)`, which a command line cannot
/// follow, and exit code 1 as if a solve had failed.
pub fn require_precise_angles(model: &Model) -> Result<(), Failed> {
    match imprecise_angle(model) {
        Some(why) => Err(exit::usage(format!("{}: {why}", model.name()))),
        None => Ok(()),
    }
}

/// Why the first angle parameter of `model` beyond the largest angle its solves take precisely
/// cannot be solved with, in the command line's terms; `None` where there is none.
pub fn imprecise_angle(model: &Model) -> Option<String> {
    imprecise_angle_within(model, model.sweep_config().newton.largest_precise_angle())
}

/// [`imprecise_angle`] against `bound`, the largest angle a solver of its own takes precisely
/// (a synthesis's, tighter than a sweep's).
pub fn imprecise_angle_within(model: &Model, bound: f64) -> Option<String> {
    let k = model.angle_param_beyond(bound)?;
    let (name, value) = (&model.params()[k], model.param_values()[k]?);
    // The distance to the next double away from zero: what an angle added to it is rounded to.
    let spacing = f64::from_bits(value.abs().to_bits() + 1) - value.abs();
    Some(format!(
        "parameter `{name}` is an angle of {} rad, beyond {} rad, the largest angle solved precisely: doubles \
         there are {} rad apart, so an angle added to it is lost to rounding; give it less whole turns, within \
         {} rad (--params {name}=VALUE, in radians)",
        Number(value),
        Number(bound),
        Number(spacing),
        Number(bound)
    ))
}
