//! Units of a table's columns, derived from the units of the base quantities: the column
//! `d(x_c)/d(phi)` of a length `x_c [mm]` and an angle `phi [rad]` is in `mm/rad`.

/// The unit of column `column` given base units `(name, unit)`, or `""` when a quantity in it
/// has none. A point output `p` gives its unit to `p.x` and `p.y`.
pub(crate) fn derive(column: &str, base: &[(&str, &str)]) -> String {
    let unit_of = |name: &str| unit_of(name, base);
    if let Some((num, den)) = analog(column) {
        let Some(top) = unit_of(num) else { return String::new() };
        let parts: Option<Vec<&str>> = den.iter().map(|d| unit_of(d)).collect();
        return match parts.as_deref() {
            Some([a]) => format!("{top}/{}", divisor(a)),
            // Two inputs of the same unit (two angles): the square of it.
            Some([a, b]) if a == b => format!("{top}/{}^2", factor(a)),
            Some([a, b]) => format!("{top}/({} {})", factor(a), factor(b)),
            _ => String::new(),
        };
    }
    unit_of(column).unwrap_or("").to_string()
}

/// The power of the radian in the unit of column `column`, given the units of the base
/// quantities `(name, unit)` (as [`derive`] takes them): 1 for an angle (`rad`), 0 for another
/// known unit (`mm`, `1`, `unit of t`), and for an analog its quantity's power less its
/// inputs' (`d(x_c)/d(phi)` in `mm/rad` is -1, `d(beta)/d(phi)` in `rad/rad` 0,
/// `d2(x_c)/d(phi)^2` -2). `None` where a unit it needs is not known.
pub(crate) fn radian_power(column: &str, base: &[(&str, &str)]) -> Option<i32> {
    let power = |name: &str| unit_of(name, base).map(|u| i32::from(u == "rad"));
    match analog(column) {
        Some((num, den)) => den.iter().try_fold(power(num)?, |p, d| Some(p - power(d)?)),
        None => power(column),
    }
}

/// `v`, of a unit with the radian to the power `power`, with degrees in place of radians:
/// times `180/pi` per radian in the numerator, divided by it per radian in the denominator
/// (one rounding per factor: an angle's is [`to_deg`](crate::to_deg)'s, bit for bit).
pub(crate) fn in_degrees(v: f64, power: i32) -> f64 {
    let step = if power > 0 { crate::to_deg } else { crate::deg };
    (0..power.unsigned_abs()).fold(v, |v, _| step(v))
}

/// A unit as a factor of a product or power in a derived one: in parentheses where it is
/// written in words (an input of no known kind is in `unit of t`): `rad/unit of t^2` read as
/// per the unit of `t^2`; and where it is itself a quotient, product or power (a unit given as
/// `m/s`, `N*m`, `m^2`): `mm/m/s^2` read as per metre and per second squared, `(m/s)^2` meant.
fn factor(unit: &str) -> String {
    if unit.contains([' ', '/', '*', '^']) { format!("({unit})") } else { unit.to_string() }
}

/// A unit as the divisor of a derived one, alone after `/`: in parentheses where it is itself
/// a quotient or a product (`mm/(m/s)`, which `mm/m/s` would read as mm per metre per second);
/// one in words (`rad/unit of t`) or a power (`mm/m^2`) reads as meant without them.
fn divisor(unit: &str) -> String {
    if unit.contains(['/', '*']) { format!("({unit})") } else { unit.to_string() }
}

/// The unit of quantity `name` among the base units (a point `p` gives its unit to `p.x` and
/// `p.y`), `None` when it has none: an empty unit is none, the column's kind is not known.
fn unit_of<'a>(name: &str, base: &[(&str, &'a str)]) -> Option<&'a str> {
    let stem = name.split_once('.').map_or(name, |(p, _)| p);
    base.iter().find(|(n, _)| *n == name || *n == stem).map(|(_, u)| *u).filter(|u| !u.is_empty())
}

/// Whether `column` is an analog column (`d(n)/d(i)`, `d2(n)/...`) rather than a base quantity.
pub(crate) fn is_analog(column: &str) -> bool {
    analog(column).is_some()
}

/// The input of `d(i)`.
fn inner(s: &str) -> Option<&str> {
    s.strip_prefix("d(")?.strip_suffix(')')
}

/// The quantity and the inputs of an analog column: `d(n)/d(i)`, `d2(n)/d(i)^2`,
/// `d2(n)/d(i)d(j)`.
fn analog(column: &str) -> Option<(&str, Vec<&str>)> {
    let (order, rest) = if let Some(r) = column.strip_prefix("d2(") { (2, r) } else { (1, column.strip_prefix("d(")?) };
    let (num, den) = rest.split_once(")/")?;
    let inputs = match order {
        1 => vec![inner(den)?],
        _ => match den.strip_suffix("^2") {
            Some(squared) => vec![inner(squared)?; 2],
            None => {
                let (a, b) = den.split_once(")d(")?;
                vec![a.strip_prefix("d(")?, b.strip_suffix(')')?]
            }
        },
    };
    Some((num, inputs))
}

/// The header field of a column: `name [unit]`, or `name` without a unit; [`read_header`]
/// reads back exactly this name and unit.
///
/// The reader takes the text after the last ` [` of a field ending in `]` as the unit. So a
/// name that itself ends like `a [b]`, or ends in white space, gets an empty unit written
/// (`a [b] []`: the trimming stops at the `]`), and a unit holding ` [` cannot be written at
/// all (the reader would cut it there); nor can a name that begins with white space (the
/// reader trims it off, as it does the spaces of `phi, x`): an `InvalidInput` error naming
/// the column.
pub(crate) fn header(name: &str, unit: &str) -> std::io::Result<String> {
    let invalid = |message: String| Err(std::io::Error::new(std::io::ErrorKind::InvalidInput, message));
    if unit.contains(" [") {
        return invalid(format!(
            "the unit `{unit}` of column `{name}` holds ` [`, which the CSV header cannot tell from the start of the unit"
        ));
    }
    if name.trim_start() != name {
        return invalid(format!("the column name `{name}` begins with white space, which reading the CSV trims off"));
    }
    let bare = unit.is_empty() && name.trim_end() == name && split_header(name).0 == name;
    Ok(if bare { name.to_string() } else { format!("{name} [{unit}]") })
}

/// The name and unit of a header field as read from a CSV: [`split_header`] of the field
/// without white space at its ends, as numbers are read (`phi, x [mm]` has the column `x`). The
/// end is trimmed before the split and the name's start after it: an empty name with a unit,
/// ` [mm]`, keeps the space that marks the unit.
pub(crate) fn read_header(field: &str) -> (String, String) {
    let (name, unit) = split_header(field.trim_end());
    match name.trim_start() {
        trimmed if trimmed.len() == name.len() => (name, unit),
        trimmed => (trimmed.to_string(), unit),
    }
}

/// Splits a header field `name [unit]` into its name and unit (`""` when there is none).
pub(crate) fn split_header(field: &str) -> (String, String) {
    match field.strip_suffix(']').and_then(|f| f.rsplit_once(" [")) {
        Some((name, unit)) => (name.to_string(), unit.to_string()),
        None => (field.to_string(), String::new()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &[(&str, &str)] = &[("phi", "rad"), ("th", "rad"), ("t", "s"), ("x_c", "mm"), ("pc", "mm")];

    #[test]
    fn analog_units_follow_the_quotient() {
        assert_eq!(derive("phi", BASE), "rad");
        assert_eq!(derive("x_c", BASE), "mm");
        assert_eq!(derive("pc.y", BASE), "mm");
        assert_eq!(derive("d(x_c)/d(phi)", BASE), "mm/rad");
        assert_eq!(derive("d2(x_c)/d(phi)^2", BASE), "mm/rad^2");
        assert_eq!(derive("d2(pc.x)/d(phi)d(th)", BASE), "mm/rad^2");
        assert_eq!(derive("d2(pc.x)/d(phi)d(t)", BASE), "mm/(rad s)");
        assert_eq!(derive("d(beta)/d(phi)", BASE), "");
        assert_eq!(derive("beta", BASE), "");
    }

    #[test]
    fn radian_powers_follow_the_quotient() {
        let base = &[("phi", "rad"), ("th", "rad"), ("t", "unit of t"), ("x_c", "mm"), ("pc", "mm"), ("r", "1")];
        for (column, power) in [
            ("phi", 1),
            ("x_c", 0),
            ("pc.y", 0),
            ("r", 0),
            ("d(x_c)/d(phi)", -1),
            ("d(phi)/d(th)", 0),
            ("d2(x_c)/d(phi)^2", -2),
            ("d2(pc.x)/d(phi)d(t)", -1),
            ("d2(th)/d(t)^2", 1),
            ("d(r)/d(phi)", -1),
        ] {
            assert_eq!(radian_power(column, base), Some(power), "{column}");
        }
        assert_eq!(radian_power("beta", base), None);
        assert_eq!(radian_power("d(x_c)/d(beta)", base), None);
        assert_eq!(in_degrees(std::f64::consts::PI, 1), 180.0);
        assert_eq!(in_degrees(180.0, -1), std::f64::consts::PI);
        assert_eq!(in_degrees(-2.5, 0), -2.5);
    }

    /// A unit given as a quotient, product or power is in parentheses where the derived unit
    /// would read otherwise: `mm/m/s` is mm per metre per second, not per `m/s`.
    #[test]
    fn compound_units_are_in_parentheses() {
        let base = &[("x", "mm"), ("v", "m/s"), ("f", "N*m"), ("a", "m^2"), ("phi", "rad")];
        assert_eq!(derive("d(x)/d(v)", base), "mm/(m/s)");
        assert_eq!(derive("d2(x)/d(v)^2", base), "mm/(m/s)^2");
        assert_eq!(derive("d2(x)/d(phi)d(v)", base), "mm/(rad (m/s))");
        assert_eq!(derive("d(x)/d(f)", base), "mm/(N*m)");
        assert_eq!(derive("d(x)/d(a)", base), "mm/m^2");
        assert_eq!(derive("d2(x)/d(a)^2", base), "mm/(m^2)^2");
        assert_eq!(derive("d2(x)/d(phi)^2", base), "mm/rad^2");
        // A quotient on top reads as meant: (m/s) per rad.
        assert_eq!(derive("d(v)/d(phi)", base), "m/s/rad");
    }

    /// A unit written in words is in parentheses as a factor of a power or a product:
    /// `rad/unit of t^2` read as per the unit of `t^2`.
    #[test]
    fn units_in_words_are_factors_in_parentheses() {
        let base = &[("phi", "rad"), ("t", "unit of t"), ("s", "unit of s"), ("p", "length unit")];
        assert_eq!(derive("d(phi)/d(t)", base), "rad/unit of t");
        assert_eq!(derive("d2(phi)/d(t)^2", base), "rad/(unit of t)^2");
        assert_eq!(derive("d2(p.x)/d(t)d(s)", base), "length unit/((unit of t) (unit of s))");
        assert_eq!(derive("d2(p.x)/d(phi)d(t)", base), "length unit/(rad (unit of t))");
        assert_eq!(derive("d2(p.x)/d(phi)^2", base), "length unit/rad^2");
        assert_eq!(derive("t", base), "unit of t");
    }

    #[test]
    fn header_fields_split_back() {
        for (name, unit) in [("phi", "rad"), ("d(x_c)/d(phi)", "mm/rad"), ("w", ""), ("a [b", "")] {
            assert_eq!(split_header(&header(name, unit).unwrap()), (name.to_string(), unit.to_string()));
        }
    }

    #[test]
    fn names_and_units_with_brackets_round_trip_or_are_refused() {
        // Names that read like `name [unit]` themselves, units with brackets, empty ones.
        // Names that end in white space, which the reader trims from the field.
        let names = ["a [b]", "a []", "a [b] [c]", "[x]", "[ ", "]", "", "a [", "p [m] ", "x\n[y]", "x ", "t\t"];
        let units = ["", "b", "]", "[", "m]", "[m", "kg/(m s)^2", "a]b"];
        for name in names {
            for unit in units {
                let field = header(name, unit).unwrap();
                assert_eq!(read_header(&field), (name.to_string(), unit.to_string()), "{field:?}");
            }
        }
        // Through a whole table written and read as CSV.
        let mut t = crate::Table::new(names.iter().map(|n| n.to_string()).collect());
        t.units = names.iter().enumerate().map(|(k, _)| units[k % units.len()].to_string()).collect();
        t.push(vec![1.0; names.len()]);
        let mut csv = Vec::new();
        t.write_csv(&mut csv).unwrap();
        assert_eq!(crate::Table::read_csv(&csv[..]).unwrap(), t, "{}", String::from_utf8_lossy(&csv));
        // A unit holding ` [` cannot be told from the unit's start: refused, naming it.
        let err = header("w", "a [b").unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
        assert!(err.to_string().contains("unit `a [b` of column `w`"), "{err}");
        // A name that begins with white space would lose it: refused, naming it.
        let err = header(" [", "").unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
        assert!(err.to_string().contains("column name ` [` begins with white space"), "{err}");
        t.units[0] = "x [y]".into();
        assert_eq!(t.write_csv(Vec::new()).unwrap_err().kind(), std::io::ErrorKind::InvalidInput);
    }
}
