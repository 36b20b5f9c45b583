//! A singular crossing located from the well-conditioned positions on both sides of it.
//!
//! [`trace`](super::locate::trace) brackets a crossing by the sign of the determinant at points of
//! the continuation. Those points are only as good as the residual tolerance pins them: where
//! the crossing is a lever through zero (a polar block `s @ theta` whose `s` vanishes) the
//! tolerance leaves the angle loose by `tol L / s`, the arclength constraint turns that into an
//! error of the path coordinate, and the sign changes about `sqrt(tol)` of the input's unit away
//! from the crossing. The column-equilibrated determinant the trace watches is no help there
//! either: equilibration divides the lever out of its angle's column, leaving only a sign.
//!
//! Here the crossing is found again where the solves are well conditioned: positions solved at
//! a few inputs on either side (the smooth branch before the crossing and its continuation past
//! it, each told by its determinant's sign), the determinant of the Jacobian with fixed scalings
//! (a smooth function of the input along the branch, with a simple root at the crossing)
//! interpolated through them, and its root taken. Rare (once per crossing), so it allocates.

use super::curve::{CurvePoint, Metric, Path, illinois, signed_det};
use crate::dims::{Dims, JacState, KinState, Store};
use crate::mechanism::kernel::{Kernel, Q, X, is_angle};
use crate::solvers::newton::NewtonConfig;
use crate::solvers::turns::unwrap_to_turn;
use nalgebra::DMatrix;

/// Samples on each side of the crossing, at `1, 2, 3` spacings from the trace's estimate: an
/// interpolant of degree five, and of degree three through the inner four to check it.
const SIDE: usize = 3;

/// The first spacing of the samples, in the input's unit (a milliradian of an angle input, a
/// thousandth of the mechanism's size of a length). The determinant's interpolation error goes
/// as the sixth power of the samples' span (`1e-17` of its slope over the span here, for a
/// determinant varying on the scale of the unit), and the rounding of the solves as the inverse
/// of their pivot ratio, about the spacing.
const FIRST_SPACING: f64 = 1e-3;

/// Smallest pivot ratio of a sample: a thousand times the sweep's default `singular_pivot`, so
/// that the residual tolerance pins every sample (to `tol / pivot`, `1e-8` of a radian at the
/// default tolerance, and the converged solves far closer). A nearer sample moves the samples
/// out.
const SAMPLE_PIVOT: f64 = 1e-3;

/// How closely (in the input's unit) the two interpolants' roots must agree for the location
/// to be taken. The difference bounds the error of the cubic's root; the quintic's, the one
/// taken, is smaller by the square of the samples' span again. A trace's estimate that is
/// already this close is kept as it is.
const LOCATE_TOL: f64 = 1e-12;

/// Attempts at a spacing (each moving the samples out where they are too close to the crossing
/// for their pivot ratio, or in where they miss the branch or disagree).
const ATTEMPTS: usize = 6;

/// Widest spacing, in the input's unit: beyond it other features of the motion (limit
/// positions, other crossings) are as likely as the crossing's own.
const MAX_SPACING: f64 = 0.05;

/// The crossing near `at` (the trace's estimate, whose near side the curve point `near` is on),
/// from positions solved on both sides of it: `None` where they cannot be solved on the branch,
/// or the interpolants disagree, and `at` itself where it is already within [`LOCATE_TOL`].
pub(crate) fn refine<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    near: &CurvePoint<Q<K>>,
    at: &CurvePoint<Q<K>>,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<Q<K>>> {
    let unit = metric.sigma;
    let near_positive = signed_det(m, &path.at_sigma(near.sigma), &near.q) > 0.0;
    let scales = Scales::at(m, path, metric, near);
    let mut spacing = FIRST_SPACING * unit;
    for _ in 0..ATTEMPTS {
        if !(spacing <= MAX_SPACING * unit && spacing > 0.0) {
            return None;
        }
        // Too close to be well conditioned: out. Off the branch (another feature of the motion
        // within the samples' span) or interpolants disagreeing (the span too wide for them): in.
        let samples = match sample(m, path, metric, near, near_positive, &scales, at.sigma, spacing, cfg) {
            Sampled::Branch(samples) => samples,
            Sampled::TooClose => {
                spacing *= 4.0;
                continue;
            }
            Sampled::Missed => {
                spacing *= 0.25;
                continue;
            }
        };
        let Some((t, q)) = root(&samples, spacing, unit) else {
            spacing *= 0.25;
            continue;
        };
        let sigma = at.sigma + t * spacing;
        if (sigma - at.sigma).abs() <= LOCATE_TOL * unit {
            return Some(at.clone());
        }
        return Some(CurvePoint { q, sigma, tangent: at.tangent.clone() });
    }
    None
}

/// Whether `at` is a root of the determinant seen from `from`, a regular point of the branch
/// before it, in `from`'s fixed scalings: the determinant there is at most half its value at
/// `from`, or, where `from` is itself that near the crossing (a step that failed beside it),
/// at most a thousandth of Hadamard's bound (the product of its columns' lengths: one for
/// orthogonal columns, `|sin|` of their angle for two). A crossing's located point is far
/// nearer its root (its input to `1e-12` of the unit, or the trace's `sqrt` of the tolerance);
/// a point where the trace's sign change was not the crossing's (a Grashof-equal four-bar's
/// change point reported 0.24 rad away, at a regular position) is neither. The comparison with
/// `from` sees a one-entry column vanish (`s^2 == phi^2` at `s = 0`), which the bound does not.
pub(crate) fn is_root<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    from: &CurvePoint<Q<K>>,
    at: &CurvePoint<Q<K>>,
) -> bool {
    let scales = Scales::at(m, path, metric, from);
    let d_from = scales.matrix(m, &path.at_sigma(from.sigma), &from.q).lu().determinant();
    let j_at = scales.matrix(m, &path.at_sigma(at.sigma), &at.q);
    let d_at = j_at.clone().lu().determinant();
    let bound: f64 = j_at.column_iter().map(|c| c.norm()).product();
    // Not comparable (not finite): taken as the trace found it.
    if !(d_from.is_finite() && d_at.is_finite() && bound.is_finite()) {
        return true;
    }
    d_at.abs() <= 0.5 * d_from.abs() || d_at.abs() <= 1e-3 * bound
}

/// Whether `b` is nearer a root of the determinant than `a`, both seen from `from` (a point of
/// the branch before them) in `from`'s fixed scalings, as [`is_root`] sees them; `false` where
/// `b`'s is not finite.
pub(crate) fn nearer_root<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    from: &CurvePoint<Q<K>>,
    b: &CurvePoint<Q<K>>,
    a: &CurvePoint<Q<K>>,
) -> bool {
    let scales = Scales::at(m, path, metric, from);
    let det = |p: &CurvePoint<Q<K>>| scales.det(m, &path.at_sigma(p.sigma), &p.q).abs();
    det(b) <= det(a)
}

/// One position solved on the branch: its offset from the trace's estimate in spacings, and
/// its unknowns (angles on the turn of the prediction).
struct Sample<Q> {
    t: f64,
    q: Q,
    /// The determinant in the fixed [`Scales`].
    det: f64,
}

/// What solving at one spacing gave.
enum Sampled<Q> {
    /// Every sample, on the near side then the far side, nearest first.
    Branch(Vec<Sample<Q>>),
    /// A sample is too close to the crossing to be well conditioned ([`SAMPLE_PIVOT`]).
    TooClose,
    /// A sample failed, or is not on the smooth branch (its determinant's sign, or its distance
    /// from the prediction).
    Missed,
}

/// Solves at `sigma0 + k spacing`, `k = -3..=3` but `0`, from the prediction along `near`'s
/// tangent: the smooth branch on the near side (the determinant's sign `near_positive`) and its
/// continuation past the crossing (the other sign).
#[allow(clippy::too_many_arguments)]
fn sample<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    near: &CurvePoint<Q<K>>,
    near_positive: bool,
    scales: &Scales,
    sigma0: f64,
    spacing: f64,
    cfg: &NewtonConfig,
) -> Sampled<Q<K>> {
    let n = m.dims().n();
    let mut out = Vec::with_capacity(2 * SIDE);
    let offsets = (1..=SIDE).map(|k| -(k as f64)).chain((1..=SIDE).map(|k| k as f64));
    for k in offsets {
        let sigma = sigma0 + k * spacing;
        let x = path.at_sigma(sigma);
        let mut guess = near.q.clone();
        // The predicted change in scaled coordinates bounds how far the solution may be.
        let mut change = 0.0f64;
        for u in 0..n {
            let d = near.dq_dsigma(u, metric) * (sigma - near.sigma);
            guess[u] += d;
            change = change.max((d / metric.unit[u]).abs());
        }
        // From the prediction: a restart would find another branch.
        let Ok(kin) = m.kinematics(&x, &guess, &cfg.with_restarts(false)) else { return Sampled::Missed };
        if kin.health().min_pivot < SAMPLE_PIVOT {
            return Sampled::TooClose;
        }
        let mut q = guess.clone();
        q.as_mut().copy_from_slice(kin.q());
        if (signed_det(m, &x, &q) > 0.0) != (near_positive == (k < 0.0)) {
            return Sampled::Missed;
        }
        // On the prediction's turn, and close to it (as a sweep's corrector is, by default).
        let mut dist = 0.0f64;
        for u in 0..n {
            if is_angle(m, u) {
                q[u] = unwrap_to_turn(q[u], guess[u]);
            }
            dist = dist.max(((q[u] - guess[u]) / metric.unit[u]).abs());
        }
        // NaN is not close.
        let close = dist <= 0.25 * change + 1e-6;
        if !close {
            return Sampled::Missed;
        }
        out.push(Sample { t: (sigma - sigma0) / spacing, det: scales.det(m, &x, &q), q });
    }
    Sampled::Branch(out)
}

/// The fixed scalings of the determinant: rows over their magnitudes at `near`, columns times
/// their units. Fixed, so that the determinant is a smooth function along the branch (a
/// column-equilibrated one is not where a column vanishes with a lever).
struct Scales {
    rows: Vec<f64>,
    cols: Vec<f64>,
}

impl Scales {
    fn at<K: Kernel>(m: &K, path: &Path<X<K>>, metric: &Metric<Q<K>>, near: &CurvePoint<Q<K>>) -> Self {
        let n = m.dims().n();
        let jac = m.jacobian(&path.at_sigma(near.sigma), &near.q);
        let sane = |v: f64| if v > 0.0 && v < f64::INFINITY { v } else { 1.0 };
        Scales { rows: (0..n).map(|e| sane(jac.scale(e))).collect(), cols: (0..n).map(|u| metric.unit[u]).collect() }
    }

    /// The Jacobian at `(x, q)` in these scalings.
    fn matrix<K: Kernel>(&self, m: &K, x: &X<K>, q: &Q<K>) -> DMatrix<f64> {
        let n = self.rows.len();
        let jac = m.jacobian(x, q);
        DMatrix::from_fn(n, n, |e, u| jac.j(e, u) * self.cols[u] / self.rows[e])
    }

    /// The determinant of the Jacobian at `(x, q)` in these scalings.
    fn det<K: Kernel>(&self, m: &K, x: &X<K>, q: &Q<K>) -> f64 {
        self.matrix(m, x, q).lu().determinant()
    }
}

/// The root, in spacings from the trace's estimate, of the determinant interpolated through the
/// samples, and the unknowns interpolated there; `None` unless the quintic's root and the inner
/// cubic's agree within [`LOCATE_TOL`] of `unit` (`spacing` and `unit` in the path coordinate).
fn root<Q: Store>(samples: &[Sample<Q>], spacing: f64, unit: f64) -> Option<(f64, Q)> {
    let t: Vec<f64> = samples.iter().map(|s| s.t).collect();
    let det: Vec<f64> = samples.iter().map(|s| s.det).collect();
    // The nearest samples on either side: the near side's first, the far side's first.
    let (a, b) = (0, SIDE);
    if !(det.iter().all(|d| d.is_finite()) && det[a] * det[b] < 0.0) {
        return None;
    }
    let quintic = Interpolant::through(&t, &det);
    let at = illinois(|x| Some(quintic.at(x)), t[a], t[b], det[a], det[b], ROOT_TOL)?;
    let inner: Vec<usize> = (0..SIDE - 1).chain(SIDE..2 * SIDE - 1).collect();
    let pick = |v: &[f64]| inner.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    let cubic = Interpolant::through(&pick(&t), &pick(&det));
    let check = illinois(|x| Some(cubic.at(x)), t[a], t[b], det[a], det[b], ROOT_TOL)?;
    // NaN does not agree.
    let agree = (at - check).abs() * spacing <= LOCATE_TOL * unit;
    if !agree {
        return None;
    }
    let mut q = samples[0].q.clone();
    for u in 0..q.as_ref().len() {
        let values: Vec<f64> = samples.iter().map(|s| s.q[u]).collect();
        q[u] = Interpolant::through(&t, &values).at(at);
    }
    Some((at, q))
}

/// The root search's tolerance in spacings: far below the rounding of the inputs.
const ROOT_TOL: f64 = 1e-15;

/// The polynomial through points `(t_i, y_i)`, in Newton's divided differences.
struct Interpolant {
    t: Vec<f64>,
    c: Vec<f64>,
}

impl Interpolant {
    fn through(t: &[f64], y: &[f64]) -> Self {
        let mut c = y.to_vec();
        for k in 1..t.len() {
            for i in (k..t.len()).rev() {
                c[i] = (c[i] - c[i - 1]) / (t[i] - t[i - k]);
            }
        }
        Interpolant { t: t.to_vec(), c }
    }

    fn at(&self, x: f64) -> f64 {
        let n = self.c.len();
        (0..n).rev().fold(0.0, |acc, i| acc * (x - self.t[i]) + self.c[i])
    }
}
