//! The few operations on plane vectors (`[x, y]`), and on the samples' angles, that the cam's
//! inversions share.

use crate::number::pow2_at_most;

/// `v` of unit length, `None` for a zero vector (scaled first, so that no length overflows).
pub(super) fn unit(v: [f64; 2]) -> Option<[f64; 2]> {
    let m = v[0].abs().max(v[1].abs());
    if m == 0.0 {
        return None;
    }
    let w = [v[0] / m, v[1] / m];
    let l = norm(w);
    Some([w[0] / l, w[1] / l])
}

/// A power of two near the largest of the lengths `values` (1 if all are zero): the lengths
/// divided by it (exactly) lie near 1, so that products of them neither overflow nor underflow
/// at any scale.
pub(super) fn length_unit<'a>(values: impl IntoIterator<Item = &'a f64>) -> f64 {
    let big = values.into_iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    if big > 0.0 { pow2_at_most(big) } else { 1.0 }
}

/// `v` divided by `unit`: divided, not multiplied by the reciprocal, whose overflow for a
/// subnormal unit would lose the vector.
pub(super) fn per_unit(v: [f64; 2], unit: f64) -> [f64; 2] {
    [v[0] / unit, v[1] / unit]
}

pub(super) fn norm(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

pub(super) fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

pub(super) fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

pub(super) fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

pub(super) fn scale(s: f64, v: [f64; 2]) -> [f64; 2] {
    [s * v[0], s * v[1]]
}

/// The quarter turn `J v`: `(x, y) -> (-y, x)`.
pub(super) fn quarter(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

/// The rotation by `a` as `(cos a, sin a)`.
pub(super) fn rotate(a: f64) -> (f64, f64) {
    let (s, c) = a.sin_cos();
    (c, s)
}

pub(super) fn apply((c, s): (f64, f64), v: [f64; 2]) -> [f64; 2] {
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// The largest of `angles` (non-negative), with its sample: `(0, 0)` for none.
pub(super) fn largest(angles: &[f64]) -> (usize, f64) {
    angles.iter().copied().enumerate().fold((0, 0.0), |best, (k, a)| if a > best.1 { (k, a) } else { best })
}
