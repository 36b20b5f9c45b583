//! Units of a table's columns, derived from the units of the base quantities: the column
//! `d(x_c)/d(phi)` of a length `x_c [mm]` and an angle `phi [rad]` is in `mm/rad`.

/// The unit of column `column` given base units `(name, unit)`, or `""` when a quantity in it
/// has none. A point output `p` gives its unit to `p.x` and `p.y`.
pub(crate) fn derive(column: &str, base: &[(&str, &str)]) -> String {
    let unit_of = |name: &str| {
        let stem = name.split_once('.').map_or(name, |(p, _)| p);
        // An empty unit is none: the column's kind is not known.
        base.iter().find(|(n, _)| *n == name || *n == stem).map(|(_, u)| *u).filter(|u| !u.is_empty())
    };
    if let Some((num, den)) = analog(column) {
        let Some(top) = unit_of(num) else { return String::new() };
        let parts: Option<Vec<&str>> = den.iter().map(|d| unit_of(d)).collect();
        return match parts.as_deref() {
            Some([a]) => format!("{top}/{a}"),
            // Two inputs of the same unit (two angles): the square of it.
            Some([a, b]) if a == b => format!("{top}/{a}^2"),
            Some([a, b]) => format!("{top}/({a} {b})"),
            _ => String::new(),
        };
    }
    unit_of(column).unwrap_or("").to_string()
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

/// The header field of a column: `name [unit]`, or `name` without a unit.
pub(crate) fn header(name: &str, unit: &str) -> String {
    if unit.is_empty() { name.to_string() } else { format!("{name} [{unit}]") }
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
    fn header_fields_split_back() {
        for (name, unit) in [("phi", "rad"), ("d(x_c)/d(phi)", "mm/rad"), ("w", ""), ("a [b", "")] {
            assert_eq!(split_header(&header(name, unit)), (name.to_string(), unit.to_string()));
        }
    }
}
