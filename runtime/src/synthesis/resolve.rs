//! The names of a task resolved against a mechanism: its channels to columns, its timing to
//! input values, and the size of its targets (the unit of the residual tolerance).

use super::error::SynthesisError;
use super::task::{Channel, Timing};
use super::vars::check_bounds;
use crate::analysis::column::column_kind;
use crate::analysis::{ColumnIndex, ColumnOf};
use crate::dims::Dims;
use crate::kinds::QuantityKind;
use crate::mechanism::kernel::Kernel;
use crate::number::Count;

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
                return Err(SynthesisError::Mismatch(format!(
                    "{} of input values for {}",
                    Count(rows.len(), "row"),
                    Count(targets, "target")
                )));
            }
            let mut out = Vec::with_capacity(targets);
            for (k, row) in rows.iter().enumerate() {
                if row.len() != ni {
                    return Err(SynthesisError::Mismatch(format!(
                        "target {k} has {}; the mechanism has {}",
                        Count(row.len(), "input value"),
                        Count(ni, "input")
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

/// The size of a task's targets: the unit of its residuals and the unit of its lengths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TargetSize {
    /// The unit of the weighted residuals, what the search's residual tolerance is relative to:
    /// the weighted size of the lengths among the targets; where there is none, a radian times
    /// the largest weight of an angle channel (a weight scales every residual of an angle-only
    /// task, and the tolerance must scale with them: fixed at 1, a weight of 1e-13 made a start
    /// 0.05 rad off converged); 1 where there is neither.
    pub residual: f64,
    /// The unit of a length of the mechanism, what its positions are compared in: the weighted
    /// size of the lengths among the targets, 1 where there is none (angles compare in radians).
    pub length: f64,
}

/// The sizes of the targets ([`TargetSize`]): the largest distance of the targets' lengths from
/// their centroid. Where all coincide, the largest magnitude of a target's lengths (its
/// distance from the origin, in the mechanism's units: a tolerance of 1 was 1e-14 of a
/// millimetre in millimetres and of a metre in metres).
pub(crate) fn target_size(channels: &[(Resolved, f64)], targets: &[f64], width: usize) -> TargetSize {
    let angle_weight = channels
        .iter()
        .filter(|(c, _)| matches!(c, Resolved::Angle { .. }))
        .map(|&(_, w)| w)
        .fold(None, |m: Option<f64>, w| Some(m.map_or(w, |m| m.max(w))));
    let lengths = length_scale(channels, targets, width);
    TargetSize { residual: lengths.or(angle_weight).unwrap_or(1.0), length: lengths.unwrap_or(1.0) }
}

/// The largest weighted distance of the targets' lengths from their centroid, or else their
/// largest weighted magnitude; `None` where no target is a length or every one is 0.
fn length_scale(channels: &[(Resolved, f64)], targets: &[f64], width: usize) -> Option<f64> {
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
        Some(scale)
    } else if magnitude > 0.0 && magnitude.is_finite() {
        Some(magnitude)
    } else {
        None
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
            let apart = target_size(&point, &[0.0, 0.0, 3.0 * k, 4.0 * k], 2).residual;
            assert!((apart / k - 2.5).abs() < 1e-15, "{k}: {apart}");
            let together = target_size(&value, &[3.4 * k, 3.4 * k], 1).residual;
            assert!((together / k - 3.4).abs() < 1e-15, "{k}: {together}");
            let points = target_size(&point, &[3.0 * k, 4.0 * k, 3.0 * k, 4.0 * k], 2).residual;
            assert!((points / k - 5.0).abs() < 1e-15, "{k}: {points}");
        }
        // Only angles, or every length 0: the radian.
        let angle = [(Resolved::Angle { col: ColumnIndex::Unknown(0), rotates: false }, 1.0)];
        assert_eq!(target_size(&angle, &[0.3, 0.7], 1), TargetSize { residual: 1.0, length: 1.0 });
        assert_eq!(target_size(&value, &[0.0, 0.0], 1), TargetSize { residual: 1.0, length: 1.0 });
        // Weighted angles alone: their residuals are a radian times the weight; lengths still
        // compare in the unit 1.
        let weighted = [(Resolved::Angle { col: ColumnIndex::Unknown(0), rotates: false }, 0.25)];
        assert_eq!(target_size(&weighted, &[0.3, 0.7], 1), TargetSize { residual: 0.25, length: 1.0 });
        // With lengths among the targets, the lengths set the residuals' unit.
        let both = [(Resolved::Value(ColumnIndex::Unknown(2)), 1.0), weighted[0]];
        assert_eq!(target_size(&both, &[0.0, 0.3, 4.0, 0.7], 2), TargetSize { residual: 2.0, length: 2.0 });
    }
}
