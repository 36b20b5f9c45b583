//! Parsing the items of a machine's dynamics: `body`, `force` and `torque` (`gravity` is one
//! expression and parsed with the other items).
//!
//! ```text
//! body crank: mass m1, com s1, inertia j1, turns phi1;
//! body piston: mass m_c, com (x_c, 0);
//! force gas at (x_c, 0) = (p_gas * area, 0);
//! torque load on phi4 = -c4;
//! ```

use super::expr::{Expr, parse_expr, starts_an_item};
use super::syntax::{BodyDef, ItemKind, kw};
use syn::parse::ParseStream;
use syn::{Ident, Token};

const BODY: &str = "`body name: mass m, com point, inertia j, turns angle;`";

/// After `body`: the name, `:` and the clauses.
pub(super) fn parse_body(input: ParseStream) -> syn::Result<BodyDef> {
    if !input.peek(Ident) {
        return Err(input.error(format!("expected the body's name: {BODY}")));
    }
    let name: Ident = input.parse()?;
    if !input.peek(Token![:]) || input.peek(Token![::]) {
        return Err(input.error(format!("expected `:` after the body's name: {BODY}")));
    }
    input.parse::<Token![:]>()?;
    let (mut mass, mut com, mut inertia, mut turns) = (None, None, None, None);
    let mut end;
    loop {
        if !input.peek(Ident) {
            return Err(input.error(format!("expected `mass`, `com`, `inertia` or `turns`: {BODY}")));
        }
        let clause: Ident = input.parse()?;
        let repeated = || syn::Error::new(clause.span(), format!("`{clause}` is given twice for body `{name}`"));
        if input.peek(Token![=]) || input.peek(Token![:]) {
            // `mass = m`, `com: p`: the value follows its keyword directly, as in the form.
            let sign = if input.peek(Token![=]) { "=" } else { ":" };
            return Err(input.error(format!("no `{sign}` after `{clause}`: write `{clause} value`, as in {BODY}")));
        }
        match clause.to_string().as_str() {
            "mass" | "com" | "inertia" => {
                let value = parse_expr(input)?;
                end = value.range().end;
                let slot = match clause.to_string().as_str() {
                    "mass" => &mut mass,
                    "com" => &mut com,
                    _ => &mut inertia,
                };
                if slot.replace(value).is_some() {
                    return Err(repeated());
                }
            }
            "turns" => {
                if !input.peek(Ident) {
                    return Err(input
                        .error("expected the angle the body turns with: `turns phi2` (an input or an angle unknown)"));
                }
                let angle: Ident = input.parse()?;
                end = angle.span();
                if turns.replace(angle).is_some() {
                    return Err(repeated());
                }
            }
            _ => {
                return Err(syn::Error::new(
                    clause.span(),
                    format!(
                        "`{clause}` is not a property of a body; expected `mass`, `com`, `inertia` or `turns`: {BODY}"
                    ),
                ));
            }
        }
        if !input.peek(Token![,]) {
            // `mass m com p`: the next clause without its `,` (not a missing `com`).
            if let Ok(next) = input.fork().parse::<Ident>()
                && matches!(next.to_string().as_str(), "mass" | "com" | "inertia" | "turns")
            {
                return Err(input.error(format!("expected `,` before `{next}`: {BODY}")));
            }
            break;
        }
        let after = input.fork();
        after.parse::<Token![,]>()?;
        if after.is_empty() || starts_an_item(&after) {
            // `com (x, 0),` ending the declaration or before the next item: left for the item's
            // `;` check, which says to write `;` there, not that a clause is missing.
            break;
        }
        input.parse::<Token![,]>()?;
    }
    let missing = |what: &str| syn::Error::new(name.span(), format!("body `{name}` needs its {what}: {BODY}"));
    let mass = mass.ok_or_else(|| missing("`mass`"))?;
    let com = com.ok_or_else(|| missing("centre of mass (`com`)"))?;
    Ok(BodyDef { name, mass, com, inertia, turns, end })
}

/// After `force`: `name at point = vector`.
pub(super) fn parse_force(input: ParseStream) -> syn::Result<ItemKind> {
    const FORCE: &str = "`force name at point = (fx, fy);`";
    // `force at p = ...`: without its name, `at` was read as the name and then missed.
    if input.peek(kw::at) && !input.peek2(kw::at) {
        return Err(
            input.error(format!("expected the force's name before `at` (it appears in error messages): {FORCE}"))
        );
    }
    let name = load_name(input, FORCE)?;
    if !input.peek(kw::at) {
        return Err(input.error(format!("expected `at` and the point the force acts at: {FORCE}")));
    }
    input.parse::<kw::at>()?;
    let at = parse_expr(input)?;
    let value = load_value(input, &name, FORCE)?;
    Ok(ItemKind::Force { name, at, value })
}

/// After `torque`: `name on angle = scalar`.
pub(super) fn parse_torque(input: ParseStream) -> syn::Result<ItemKind> {
    const TORQUE: &str = "`torque name on angle = scalar;`";
    if input.peek(kw::on) && !input.peek2(kw::on) {
        return Err(
            input.error(format!("expected the torque's name before `on` (it appears in error messages): {TORQUE}"))
        );
    }
    let name = load_name(input, TORQUE)?;
    if !input.peek(kw::on) {
        return Err(input.error(format!("expected `on` and the angle the torque acts on: {TORQUE}")));
    }
    input.parse::<kw::on>()?;
    if !input.peek(Ident) {
        return Err(input.error(format!("expected the angle (an input or an angle unknown): {TORQUE}")));
    }
    let on: Ident = input.parse()?;
    let value = load_value(input, &name, TORQUE)?;
    Ok(ItemKind::Torque { name, on, value })
}

fn load_name(input: ParseStream, form: &str) -> syn::Result<Ident> {
    if !input.peek(Ident) {
        return Err(input.error(format!("expected the load's name (it appears in error messages): {form}")));
    }
    input.parse()
}

fn load_value(input: ParseStream, name: &Ident, form: &str) -> syn::Result<Expr> {
    if !input.peek(Token![=]) || input.peek(Token![==]) {
        return Err(input.error(format!("expected `=` and the value of `{name}`: {form}")));
    }
    input.parse::<Token![=]>()?;
    parse_expr(input)
}
