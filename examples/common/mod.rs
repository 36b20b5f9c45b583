//! Helpers shared by the examples (the library of the `kinloop-examples` package).
//!
//! The examples draw with `kinloop::plot`, giving each series its quantity kind. What remains
//! here is a small adapter for charts still described by axis labels of the form
//! `"name [unit]"` (`"crank angle [deg]"`, `"torque [Nm]"`): it turns each label into a
//! `kinloop::plot` axis of that quantity, so such an example draws like the others until it
//! states its kinds itself.

use kinloop::plot::{self, Axis, Kind};
use std::path::{Path, PathBuf};

/// Output folder of an example: `$KINLOOP_OUT/<example>` (default `out/<example>`).
///
/// # Panics
/// When the folder cannot be created (`kinloop::plot::out_dir` returns the error instead).
pub fn out_dir(example: &str) -> PathBuf {
    plot::out_dir(example).unwrap_or_else(|e| panic!("{e}"))
}

/// Folder for an example's figures: `$KINLOOP_FIGURES/<example>` when that variable is set
/// (`KINLOOP_FIGURES=docs/figures` regenerates the README gallery), else [`out_dir`].
///
/// # Panics
/// When the folder cannot be created (`kinloop::plot::figure_dir` returns the error instead).
pub fn figure_dir(example: &str) -> PathBuf {
    plot::figure_dir(example).unwrap_or_else(|e| panic!("{e}"))
}

/// One curve of a [`line_chart`], in the units its axis labels name.
pub struct Series<'a> {
    pub label: &'a str,
    pub points: Vec<(f64, f64)>,
}

/// The axis a label `"name [unit]"` describes, and the factor from the label's unit to the
/// plot's (degrees become radians: `kinloop::plot` takes angles in radians and shows degrees).
fn axis_of(label: &str) -> (Axis, f64) {
    let (name, unit) = match label.rsplit_once(" [") {
        Some((name, unit)) if unit.ends_with(']') => (name, &unit[..unit.len() - 1]),
        _ => (label, "-"),
    };
    match unit {
        "deg" | "°" => (Axis::angle(name), 1f64.to_radians()),
        "-" => (Axis::new(name, Kind::Dimensionless), 1.0),
        _ => (Axis::new(name, Kind::Other { quantity: name.to_string(), unit: unit.to_string() }), 1.0),
    }
}

/// Draws curves into an SVG file with a title, axes of the quantities `x_label` and `y_label`
/// name (`"name [unit]"`; a unit `deg` makes an angle axis ticked in degrees) and a legend
/// beside the plot.
pub fn line_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), Box<dyn std::error::Error>> {
    let ((x, sx), (y, sy)) = (axis_of(x_label), axis_of(y_label));
    let curves: Vec<plot::Series> = series
        .iter()
        .map(|s| plot::Series::new(s.label, y.kind.clone(), s.points.iter().map(|&(a, b)| (a * sx, b * sy)).collect()))
        .collect();
    plot::line_chart(path, title, &x, &y, &curves)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_become_axes_of_their_quantity() {
        let (a, s) = axis_of("crank angle [deg]");
        assert_eq!((a.title(), s), ("crank angle [°]".to_string(), std::f64::consts::PI / 180.0));
        assert_eq!(axis_of("torque [Nm]").0.title(), "torque [Nm]");
        assert_eq!(axis_of("ratio").0.kind, Kind::Dimensionless);
    }
}
