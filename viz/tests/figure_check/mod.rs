//! The checks every figure of the tests passes, whatever it shows: well-formed SVG; no NaN or
//! infinity in any attribute or text; every axis title ends with its unit in brackets; every
//! tick label is a finite number; a drawing's scale bar says a number and a unit.

/// A value that spells a non-finite number (`NaN`, `inf`, `-inf`, `infinity`, any case).
fn non_finite(s: &str) -> bool {
    s.split(|c: char| !c.is_ascii_alphanumeric())
        .any(|t| matches!(t.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity"))
}

/// A tick label as a number: its mantissa (finite) and decimal exponent (`-12.5`, `1.5e308`,
/// `0.18e310`: labels of an axis at the end of the f64 range may lie beyond it).
fn tick_value(label: &str) -> Option<f64> {
    let label = label.replace('−', "-");
    let (mantissa, exponent) = label.split_once('e').unwrap_or((&label, "0"));
    exponent.parse::<i32>().ok()?;
    mantissa.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// Asserts that `svg` is a sound figure (see the module documentation); returns its tick
/// labels in document order, for the caller's own checks.
pub fn sound(svg: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    let mut ticks = Vec::new();
    for n in doc.descendants() {
        for a in n.attributes() {
            assert!(!non_finite(a.value()), "attribute {}=\"{}\" of <{}>", a.name(), a.value(), n.tag_name().name());
        }
        if let Some(t) = n.text().filter(|_| n.is_text()) {
            assert!(!non_finite(t), "text `{t}`");
        }
        let text = || n.text().unwrap_or("").to_string();
        match n.attribute("class").unwrap_or("") {
            "axis-title x" | "axis-title y" => {
                let title = text();
                let unit = title.rsplit_once(" [").and_then(|(_, u)| u.strip_suffix(']'));
                assert!(unit.is_some_and(|u| !u.is_empty()), "axis title `{title}` names no unit");
            }
            "tick-label x" | "tick-label y" => {
                let label = text();
                assert!(tick_value(&label).is_some(), "tick label `{label}` is no finite number");
                ticks.push(label);
            }
            "scale-bar" => {
                let label = n.descendants().find(|t| t.is_text()).and_then(|t| t.text()).unwrap_or("");
                let (length, unit) = label.split_once(' ').unwrap_or((label, ""));
                assert!(tick_value(length).is_some_and(|v| v > 0.0) && !unit.is_empty(), "scale bar `{label}`");
            }
            _ => {}
        }
    }
    ticks
}
