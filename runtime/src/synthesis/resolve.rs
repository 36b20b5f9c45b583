//! The names of a task resolved against a mechanism: its channels to columns, its timing to
//! input values, and the size of its targets (the unit of the residual tolerance).

use super::error::SynthesisError;
use super::task::{Channel, Timing};
use super::vars::check_bounds;
use crate::analysis::{ColumnIndex, ColumnOf};
use crate::dims::Dims;
use crate::kinds::QuantityKind;
use crate::mechanism::kernel::Kernel;

/// A target channel resolved to the mechanism's columns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Resolved {
    /// A point's x and y columns; moved by the placement.
    Point(ColumnIndex, ColumnIndex),
    /// An angle column: compared modulo a turn; turned by the placement (`rotates`) or not (a
    /// function generator's output angle).
    Angle { col: ColumnIndex, rotates: bool },
    /// A scalar column.
    Value(ColumnIndex),
}

/// The timing resolved: the inputs of every target, or free inputs within bounds.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Inputs<X> {
    Prescribed(Vec<X>),
    Free { lo: f64, hi: f64 },
}

/// A channel's columns.
pub(crate) fn resolve_channel<K: Kernel>(m: &K, c: &Channel) -> Result<Resolved, SynthesisError> {
    Ok(match c {
        Channel::Point(name) => {
            Resolved::Point(scalar_column(m, &format!("{name}.x"))?, scalar_column(m, &format!("{name}.y"))?)
        }
        Channel::Angle(name) => {
            let col = scalar_column(m, name)?;
            // Compared modulo a turn: a length's error would be taken modulo 2 pi of its unit
            // (a slider 2 pi off met its target), and depend on the unit of length.
            if let kind @ (QuantityKind::Length | QuantityKind::Dimensionless) = column_kind(m, col) {
                return Err(SynthesisError::Mismatch(format!(
                    "`{name}` is a {}, not an angle: an angle channel is compared modulo a turn; give it as a value \
                     (`Channel::Value`)",
                    if kind == QuantityKind::Length { "length" } else { "pure number" }
                )));
            }
            Resolved::Angle { col, rotates: true }
        }
        Channel::Value(name) => {
            let col = scalar_column(m, name)?;
            if column_kind(m, col) == QuantityKind::Angle {
                Resolved::Angle { col, rotates: false }
            } else {
                Resolved::Value(col)
            }
        }
    })
}

/// The kind of column `col` of `m`.
pub(crate) fn column_kind<K: Kernel>(m: &K, col: ColumnIndex) -> QuantityKind {
    match col {
        ColumnIndex::Unknown(u) => m.unknown_kind(u),
        ColumnIndex::Output(o) => m.output_kind(o),
        ColumnIndex::Input(i) => m.input_kind(i),
    }
}

/// An unknown or output column by name (the analysis's lookup; an input is no target column).
pub(crate) fn scalar_column<K: Kernel>(m: &K, name: &str) -> Result<ColumnIndex, SynthesisError> {
    match ColumnOf::resolve(name, m) {
        Ok(c @ (ColumnIndex::Unknown(_) | ColumnIndex::Output(_))) => Ok(c),
        _ => {
            let d = m.dims();
            let unknowns = (0..d.n()).map(|u| m.unknown_name(u));
            let outputs = (0..d.no()).map(|o| m.output_name(o));
            Err(SynthesisError::UnknownColumn {
                name: name.to_string(),
                mechanism: m.name().to_string().into(),
                columns: unknowns.chain(outputs).collect::<Vec<_>>().join(", "),
            })
        }
    }
}

/// The timing checked against the targets and the mechanism's inputs (`d` its sizes).
pub(crate) fn resolve_timing<D: Dims>(d: D, timing: &Timing, targets: usize) -> Result<Inputs<D::X>, SynthesisError> {
    let ni = d.ni();
    match timing {
        Timing::Unset => Err(SynthesisError::Mismatch(
            "the task has no timing: give the inputs (`timed`) or their range (`untimed`)".into(),
        )),
        Timing::Prescribed(rows) => {
            if rows.len() != targets {
                return Err(SynthesisError::Mismatch(format!("{} input values for {targets} targets", rows.len())));
            }
            let mut out = Vec::with_capacity(targets);
            for (k, row) in rows.iter().enumerate() {
                if row.len() != ni {
                    return Err(SynthesisError::Mismatch(format!(
                        "target {k} has {} input values; the mechanism has {ni}",
                        row.len()
                    )));
                }
                if let Some(&v) = row.iter().find(|v| !v.is_finite()) {
                    return Err(SynthesisError::NonFinite { what: "the input", target: k, value: v });
                }
                let mut x = d.x();
                x.as_mut().copy_from_slice(row);
                out.push(x);
            }
            Ok(Inputs::Prescribed(out))
        }
        &Timing::Free { lo, hi } => {
            if ni != 1 {
                return Err(SynthesisError::Unsupported(format!(
                    "free timing moves one input; the mechanism has {ni} (prescribe the inputs)"
                )));
            }
            check_bounds("input", lo, hi)?;
            // Every free input would be `lo`: targets met in order along one motion need
            // distinct inputs, so each start would end in an order defect.
            if lo == hi && targets > 1 {
                return Err(SynthesisError::InvalidConfig(format!(
                    "free timing within [{lo}, {hi}] gives every one of the {targets} targets the same input: \
                     give a range the motion can run through, or prescribe the inputs (`timed`)"
                )));
            }
            Ok(Inputs::Free { lo, hi })
        }
    }
}

/// The largest distance of the targets' lengths from their centroid: what the residual
/// tolerance is relative to. Where all coincide, the largest magnitude of a target's lengths
/// (its distance from the origin, in the mechanism's units: a tolerance of 1 was 1e-14 of a
/// millimetre in millimetres and of a metre in metres); 1 where none is a length (angles) or
/// every one is 0.
pub(crate) fn target_scale(channels: &[(Resolved, f64)], targets: &[f64], width: usize) -> f64 {
    let (mut scale, mut magnitude): (f64, f64) = (0.0, 0.0);
    let mut at = 0;
    for (c, w) in channels {
        let cols: &[usize] = match c {
            Resolved::Point(..) => &[0, 1],
            Resolved::Value(_) => &[0],
            Resolved::Angle { .. } => &[],
        };
        let n = targets.len() / width;
        // Each target divided by `n` before the sum, and the distances as norms: the sum and the
        // squares of targets near the largest `f64` overflowed, and the scale fell back to 1.
        let mean = |j: usize| (0..n).map(|k| targets[k * width + at + j] / n as f64).sum::<f64>();
        let means: Vec<f64> = cols.iter().map(|&j| mean(j)).collect();
        for k in 0..n {
            let d = crate::number::norm_of(cols.iter().zip(&means).map(|(&j, m)| targets[k * width + at + j] - m));
            scale = scale.max(w * d);
            magnitude = magnitude.max(w * crate::number::norm_of(cols.iter().map(|&j| targets[k * width + at + j])));
        }
        at += match c {
            Resolved::Point(..) => 2,
            _ => 1,
        };
    }
    if scale > 0.0 && scale.is_finite() {
        scale
    } else if magnitude > 0.0 && magnitude.is_finite() {
        magnitude
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tolerance's scale is a length of the targets in every case, so that a task in other
    /// units is the same task: coinciding targets too (a function generator asked for the same
    /// slider position twice), by their magnitude.
    #[test]
    fn the_targets_scale_follows_their_units() {
        let point = [(Resolved::Point(ColumnIndex::Output(0), ColumnIndex::Output(1)), 1.0)];
        let value = [(Resolved::Value(ColumnIndex::Unknown(2)), 1.0)];
        for k in [1.0, 1e3, 1e-6, 1e-9] {
            let apart = target_scale(&point, &[0.0, 0.0, 3.0 * k, 4.0 * k], 2);
            assert!((apart / k - 2.5).abs() < 1e-15, "{k}: {apart}");
            let together = target_scale(&value, &[3.4 * k, 3.4 * k], 1);
            assert!((together / k - 3.4).abs() < 1e-15, "{k}: {together}");
            let points = target_scale(&point, &[3.0 * k, 4.0 * k, 3.0 * k, 4.0 * k], 2);
            assert!((points / k - 5.0).abs() < 1e-15, "{k}: {points}");
        }
        // Only angles, or every length 0: the radian.
        let angle = [(Resolved::Angle { col: ColumnIndex::Unknown(0), rotates: false }, 1.0)];
        assert_eq!(target_scale(&angle, &[0.3, 0.7], 1), 1.0);
        assert_eq!(target_scale(&value, &[0.0, 0.0], 1), 1.0);
    }
}
