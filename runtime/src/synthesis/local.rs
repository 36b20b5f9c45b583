//! The local solve: Levenberg–Marquardt on the residuals with their exact Jacobian, kept inside
//! the bounds (a variable on a bound that the step would push out is held there for that step),
//! each evaluation solving the positions from the last accepted ones.

use super::problem::ProblemOf;
use super::residuals::Eval;
use super::resolve::Resolved;
use crate::analysis::optimize::OptimizerStop;
use crate::error::Error;
use crate::mechanism::kernel::{Q, SensKernel};

/// The residuals' rounding, in units in the last place of the largest magnitude they are
/// computed from (`ProblemOf::resolution`): a local solve whose residuals' root mean square is
/// within it is converged whatever its tolerance. Measured on exact fits whose rounding
/// passes the tolerance (Burmester four-bars with a crank 31 times the poses' size, a four-bar
/// 1e4 and 1e6 from the origin): at most 0.52 where they stopped on the step, 1.5 where they
/// converged, so 4 keeps a margin for other platforms' sines and cosines and stays within a
/// few roundings (the default `tol`, `1e-14`, is 45 of the targets' size).
const ROUNDING: f64 = 4.0;

/// Settings of the local solve.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct LocalConfig {
    /// Stop after this many evaluations of the residuals and Jacobian (default `100`).
    pub max_evaluations: usize,
    /// Converged ([`OptimizerStop::Converged`]) when the residuals' root mean square over the
    /// targets (their norm over the square root of the number of targets: a candidate's
    /// [`rms_error`](super::Candidate::rms_error)) is at most `tol` times the size of the targets
    /// (their largest weighted distance from their centroid; a radian times the largest angle
    /// weight where every target is an angle; default `1e-14`, rounding): met where the design
    /// meets its targets exactly, with as many targets as any: an exact fit's rounding is about
    /// `3e-16` of the size per target at 5 targets as at 5000 (measured), where the norm of
    /// its residuals grows with the square root of their number and passed `1e-14` of the size
    /// at about 2000 targets. Also converged where that root mean square is within a few
    /// roundings of the largest magnitude the residuals are computed from (a target's distance
    /// from the origin, a length of the design), which no step can lower: an exact fit 1e4
    /// from the origin, or with a crank 31 times longer than the targets' spread, is rounding
    /// above `tol` of the spread, and was reported stopped on the step.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub tol: f64,
    /// Stopped on the step ([`OptimizerStop::StepTolerance`]) when a damped step changes no
    /// unknown by more than `step_tol` times its size (`|dz_i| <= step_tol (|z_i| + step_tol
    /// w_i)`, `w_i` the width of its bounds, or its magnitude where they are one value: free of
    /// the units of length and angle; default `1e-13`), whether it lowered the residual (and
    /// was taken) or not, and the residuals are not within [`tol`](Self::tol). That says the
    /// solve moves the design no further, not that it is at a local minimum: it usually is one
    /// (whose residual need not be zero: a least-squares fit of more targets than the design
    /// can meet stops so, and its design is the usable answer), but the step is damped, and
    /// under heavy damping (grown by rejected steps, as near where the design stops
    /// assembling) a step that small can stop it where the gradient is not zero.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub step_tol: f64,
    /// Initial damping, relative to the diagonal of `J^T J` (default `1e-3`).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub lambda: f64,
}

impl Default for LocalConfig {
    fn default() -> Self {
        LocalConfig { max_evaluations: 100, tol: 1e-14, step_tol: 1e-13, lambda: 1e-3 }
    }
}

impl LocalConfig {
    /// Sets [`LocalConfig::max_evaluations`].
    pub fn with_max_evaluations(mut self, n: usize) -> Self {
        self.max_evaluations = n;
        self
    }
    /// Sets [`LocalConfig::tol`].
    pub fn with_tol(mut self, tol: f64) -> Self {
        self.tol = tol;
        self
    }
    /// Sets [`LocalConfig::step_tol`].
    pub fn with_step_tol(mut self, tol: f64) -> Self {
        self.step_tol = tol;
        self
    }
    /// Sets [`LocalConfig::lambda`].
    pub fn with_lambda(mut self, lambda: f64) -> Self {
        self.lambda = lambda;
        self
    }

    /// The first field out of its range: its name, its value and its valid range.
    pub(crate) fn invalid_field(&self) -> Option<(&'static str, String, &'static str)> {
        let not_negative = |v: f64| v.is_finite() && v >= 0.0;
        if self.max_evaluations == 0 {
            Some(("max_evaluations", "0".into(), "at least 1"))
        } else if !not_negative(self.tol) {
            Some(("tol", self.tol.to_string(), "finite and not negative"))
        } else if !not_negative(self.step_tol) {
            Some(("step_tol", self.step_tol.to_string(), "finite and not negative"))
        } else if !(self.lambda.is_finite() && self.lambda > 0.0) {
            Some(("lambda", self.lambda.to_string(), "positive and finite"))
        } else {
            None
        }
    }
}

/// What the local solve did.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LocalReport {
    /// Evaluations of residuals and Jacobian (each solves every target's position and its
    /// sensitivities).
    pub evaluations: usize,
    /// Accepted steps.
    pub iterations: usize,
    /// Why it stopped: [`OptimizerStop::Converged`] when the residuals' root mean square met
    /// [`LocalConfig::tol`], [`OptimizerStop::StepTolerance`] when a step changed the design
    /// by less than [`LocalConfig::step_tol`] first (usually at a local minimum of non-zero
    /// residual: usable, judged by its errors), [`OptimizerStop::MaxEvaluations`] when the
    /// evaluations ran out, [`OptimizerStop::Stalled`] when no step lowered the residual at any
    /// damping.
    #[cfg_attr(feature = "serde", serde(with = "stop_serde"))]
    pub stop: OptimizerStop,
    /// The residual norm at the end.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub residual: f64,
}

/// How one round of damped steps ended.
enum Step {
    /// A step lowered the residual (`small`: it hardly changed the design).
    Accepted { small: bool },
    /// A step too small to change the design did not lower the residual.
    Stationary,
    /// The damping or the evaluations ran out.
    Exhausted,
}

/// A local solve's result: the unknowns, their evaluation, and what the solve did.
pub(crate) type Solved<Q> = (Vec<f64>, Eval<Q>, LocalReport);

fn norm(r: &[f64]) -> f64 {
    crate::number::norm_of(r.iter().copied())
}

impl<K: SensKernel> ProblemOf<K> {
    /// Levenberg–Marquardt from `z0` (inside the bounds); an error where `z0` cannot be
    /// evaluated (the design cannot assemble at a target).
    pub(crate) fn local(&self, z0: Vec<f64>, cfg: &LocalConfig) -> Result<Solved<Q<K>>, Error> {
        let (lo, hi) = self.bounds();
        let n = z0.len();
        let mut z = z0;
        let mut e = self.evaluate(&z, None)?;
        let mut f = norm(&e.r);
        let mut evaluations = 1;
        let mut iterations = 0;
        let mut lambda = cfg.lambda;
        let rows = e.r.len();
        // Each unknown's unit for the damping floor: its bounds' width (its own magnitude where
        // the width is zero or overflows), so that the floor compares the unknowns' effects over
        // their ranges, in residual units, whatever the units of length and angle.
        let width: Vec<f64> = (0..n)
            .map(|i| {
                let w = hi[i] - lo[i];
                if w > 0.0 && w.is_finite() { w } else { lo[i].abs().max(hi[i].abs()).max(f64::MIN_POSITIVE) }
            })
            .collect();
        // The unknowns every target shares (the design variables, then the placement's), by
        // index into the shared block `at(i)` of `z`'s, and `shared(i)` back; the free inputs
        // lie between them in `z`.
        let (nv, nt) = (self.vars.len(), self.free_inputs());
        let ng = n - nt;
        let at = |i: usize| if i < nv { i } else { i + nt };
        let shared = |i: usize| if i < nv { i } else { i - nt };
        // The residuals' unit, the targets' weighted size, and each unknown's, its width, by the
        // powers of two nearest them (exact: the same steps bit for bit as unscaled); `column`,
        // the factor of an unknown's column of the Jacobian, is the two's quotient.
        let exponent = |v: f64| (v.log2().round() as i32).clamp(-1000, 1000);
        let unit = 2f64.powi(-exponent(self.scale));
        let per: Vec<f64> = width.iter().map(|&w| 2f64.powi(exponent(w))).collect();
        let column: Vec<f64> =
            width.iter().map(|&w| 2f64.powi((exponent(w) - exponent(self.scale)).clamp(-1020, 1020))).collect();
        // Converged where the residuals' root mean square over the targets is within `tol` of
        // their size. Their norm was compared: each target's rounding adds to it in quadrature,
        // so an exact fit of 2000 targets ended at about 1.6e-14 of the size and never met the
        // default 1e-14, though its rounding per target was that of 5 targets (about 3e-16).
        //
        // Or within the residuals' rounding ([`ROUNDING`] units in the last place of the largest
        // magnitude they are computed from: see `resolution`), which no step can lower: targets
        // 1e4 from the origin, or a crank 30 times longer than their spread, compute every
        // residual from values whose rounding alone passes `tol` of the spread, and exact fits
        // there ended "stopped on the step tolerance".
        let row_weight = self.row_weights();
        // The resolution (a pass over the Jacobian) only where the tolerance alone is not met.
        let met = |f: f64, e: &Eval<Q<K>>, z: &[f64]| {
            self.within_tol(f, cfg.tol) || self.within_rounding(f, e, z, &row_weight)
        };
        let stop = loop {
            if met(f, &e, &z) {
                break OptimizerStop::Converged;
            }
            if evaluations >= cfg.max_evaluations {
                break OptimizerStop::MaxEvaluations;
            }
            // Normal equations J^T J and the gradient J^T r, of the residuals in units of the
            // targets' weighted size and of the unknowns in units of their widths (`unit`,
            // `per`): their squares neither underflow nor overflow whatever the weights and the
            // units. Weights of 1e-200 made them 0, and every start "converged" where it began;
            // lengths near 1e-200 made a length's column squared 1e400, and no step was found.
            //
            // A free input moves only its own target's residuals: J^T J is an arrow, the shared
            // unknowns' block `a` (design variables, placement), each free input's diagonal entry
            // `d` and its coupling `c` to the shared ones. Formed and solved densely it cost the
            // cube of the targets (minutes for 1600 targets per start); the free inputs are
            // eliminated instead (below), at a cost linear in the targets.
            let mut a = nalgebra::DMatrix::<f64>::zeros(ng, ng);
            let mut g = vec![0.0; n];
            let mut d = vec![0.0; nt];
            let mut c = vec![0.0; nt * ng];
            let mut js = vec![0.0; ng];
            for k in 0..rows {
                for (i, js) in js.iter_mut().enumerate() {
                    *js = e.jac[k * ng + i] * column[at(i)];
                }
                let rk = e.r[k] * unit;
                for i in 0..ng {
                    g[at(i)] += js[i] * rk;
                    for j in 0..=i {
                        a[(i, j)] += js[i] * js[j];
                    }
                }
                if nt > 0 {
                    let t = k / self.width;
                    let jt = e.jin[k] * column[nv + t];
                    g[nv + t] += jt * rk;
                    d[t] += jt * jt;
                    for (ct, &jj) in c[t * ng..(t + 1) * ng].iter_mut().zip(&js) {
                        *ct += jt * jj;
                    }
                }
            }
            for i in 0..ng {
                for j in 0..i {
                    a[(j, i)] = a[(i, j)];
                }
            }
            // The diagonal of J^T J, by unknown.
            let diag = |i: usize| if (nv..nv + nt).contains(&i) { d[i - nv] } else { a[(shared(i), shared(i))] };
            // Held: on a bound with the descent direction (-g) pointing out.
            let held: Vec<bool> =
                (0..n).map(|i| (z[i] <= lo[i] && g[i] > 0.0) || (z[i] >= hi[i] && g[i] < 0.0)).collect();
            // The floor keeps the damped matrix regular where a column vanishes. Relative to the
            // largest column it swamped a column smaller by 1e6 (an angle's against a length's
            // at a unit of 1e-100, or a length's against an angle's at 1e100): that unknown's
            // steps came out too small to change it, and the solve stopped "converged" there.
            // So it is judged on the unknowns scaled by their widths: the largest change any one
            // makes over its range, `sqrt(a_ii) w_i`, a millionth of it over the unknown's own
            // width, squared (the width in the unknown's unit `per`: `a` is in those units).
            let reach = (0..n).filter(|&i| !held[i]).map(|i| diag(i).sqrt() * (width[i] / per[i])).fold(0.0, f64::max);
            let floor = |i: usize| (1e-6 * reach / (width[i] / per[i])).powi(2).min(f64::MAX);
            let damp = |i: usize, lambda: f64| lambda * diag(i).max(floor(i)).max(f64::MIN_POSITIVE);
            // A held unknown is coupled to none: its coupling to the free inputs is zero.
            for t in 0..nt {
                for i in 0..ng {
                    if held[nv + t] || held[at(i)] {
                        c[t * ng + i] = 0.0;
                    }
                }
            }
            let mut step = Step::Exhausted;
            while evaluations < cfg.max_evaluations && lambda <= 1e16 {
                // The damped system, a held unknown's row and column those of the identity and
                // its right-hand side zero.
                let mut damped = a.clone();
                let mut rhs = nalgebra::DVector::<f64>::from_fn(ng, |i, _| -g[at(i)]);
                for i in 0..ng {
                    if held[at(i)] {
                        damped.row_mut(i).fill(0.0);
                        damped.column_mut(i).fill(0.0);
                        damped[(i, i)] = 1.0;
                        rhs[i] = 0.0;
                    } else {
                        damped[(i, i)] += damp(at(i), lambda);
                    }
                }
                let held_t = |t: usize| held[nv + t];
                let dd: Vec<f64> = (0..nt).map(|t| if held_t(t) { 1.0 } else { d[t] + damp(nv + t, lambda) }).collect();
                let rt: Vec<f64> = (0..nt).map(|t| if held_t(t) { 0.0 } else { -g[nv + t] }).collect();
                let Some((dg, dt)) = arrow_solve(damped, rhs, &dd, &c, &rt) else {
                    lambda *= 10.0;
                    continue;
                };
                let dz: Vec<f64> = (0..n)
                    .map(|i| match i.checked_sub(nv).filter(|&t| t < nt) {
                        Some(t) => dt[t] * per[i],
                        None => dg[shared(i)] * per[i],
                    })
                    .collect();
                let trial: Vec<f64> = (0..n).map(|i| (z[i] + dz[i]).clamp(lo[i], hi[i])).collect();
                // Relative to each unknown's size, and near zero to its width: an absolute floor
                // of `step_tol` (in the unknown's units) took every step of a design of lengths
                // near 1e-30 for a converged one, and the solve stopped at its first step.
                let small =
                    (0..n).all(|i| (trial[i] - z[i]).abs() <= cfg.step_tol * (z[i].abs() + cfg.step_tol * width[i]));
                evaluations += 1;
                match self.evaluate(&trial, Some(&e.qs)) {
                    Ok(et) if norm(&et.r) < f => {
                        z = trial;
                        f = norm(&et.r);
                        e = et;
                        lambda = (lambda * 0.3).max(1e-15);
                        iterations += 1;
                        step = Step::Accepted { small };
                        break;
                    }
                    // No shorter (more damped) step changes the design either: the solve moves
                    // no further, at a local minimum or where the damping allows no larger step.
                    _ if small => {
                        step = Step::Stationary;
                        break;
                    }
                    _ => lambda *= 10.0,
                }
            }
            match step {
                Step::Accepted { small: false } => {}
                // The design moves no further: converged only where the residual met its
                // tolerance (the small step taken may have brought it there), a stop on the
                // step otherwise; the two were both reported `Converged`.
                Step::Accepted { small: true } | Step::Stationary if met(f, &e, &z) => {
                    break OptimizerStop::Converged;
                }
                Step::Accepted { small: true } | Step::Stationary => break OptimizerStop::StepTolerance,
                Step::Exhausted if evaluations >= cfg.max_evaluations => break OptimizerStop::MaxEvaluations,
                Step::Exhausted => break OptimizerStop::Stalled,
            }
        };
        let report = LocalReport { evaluations, iterations, stop, residual: f };
        Ok((z, e, report))
    }
}

impl<K: SensKernel> ProblemOf<K> {
    /// Whether residuals of norm `norm` meet the tolerance `tol` of the local solve's
    /// convergence test ([`LocalConfig::tol`]): their root mean square over the targets within
    /// `tol` of the targets' size. Cheap (no Jacobian): asked first.
    pub(crate) fn within_tol(&self, norm: f64, tol: f64) -> bool {
        norm / (self.targets() as f64).sqrt() <= tol * self.scale
    }

    /// Whether residuals of norm `norm`, evaluated as `e` at the unknowns `z`, are within their
    /// rounding, the other half of the local solve's convergence test: their root mean square
    /// within [`ROUNDING`] units in the last place of the largest magnitude they are computed
    /// from ([`ProblemOf::resolution`], a pass over the Jacobian), which no step can lower.
    /// `row_weight` is [`ProblemOf::row_weights`].
    pub(crate) fn within_rounding(&self, norm: f64, e: &Eval<Q<K>>, z: &[f64], row_weight: &[f64]) -> bool {
        norm / (self.targets() as f64).sqrt() <= ROUNDING * f64::EPSILON * self.resolution(e, z, row_weight)
    }

    /// Each residual's weight, in the order of one target's residuals (its channels', a point's
    /// twice).
    pub(crate) fn row_weights(&self) -> Vec<f64> {
        self.channels.iter().flat_map(|&(c, w)| std::iter::repeat_n(w, channel_width(c))).collect()
    }

    /// The largest magnitude a residual of `e` (at the unknowns `z`) is computed from, in the
    /// residuals' weighted units: its target's, and each unknown's share `|dr/dz_i z_i|`, what
    /// the residual changes by for a relative change of that unknown (a pivot 1e4 from the
    /// origin moves the point by 1e4 times its rounding, a crank 66 long by 66 times). No
    /// residual is resolved more finely than the rounding of these, so a fit within a few
    /// roundings of them is exact to rounding. The largest share, not their sum, so that
    /// shares near the largest `f64` do not overflow (a few shares are within the margin of
    /// [`ROUNDING`]); one not finite is left out.
    pub(crate) fn resolution(&self, e: &Eval<Q<K>>, z: &[f64], row_weight: &[f64]) -> f64 {
        let (nv, nt) = (self.vars.len(), self.free_inputs());
        let ng = z.len() - nt;
        let at = |i: usize| if i < nv { i } else { i + nt };
        let finite = |v: f64| if v.is_finite() { v } else { 0.0 };
        (0..e.r.len())
            .map(|k| {
                let target = finite((row_weight[k % self.width] * self.targets[k]).abs());
                let shared = (0..ng).map(|i| finite((e.jac[k * ng + i] * z[at(i)]).abs())).fold(0.0, f64::max);
                let input = if nt > 0 { finite((e.jin[k] * z[nv + k / self.width]).abs()) } else { 0.0 };
                target.max(shared).max(input)
            })
            .fold(0.0, f64::max)
    }
}

/// The components a channel takes of each target (a point two, any other one).
fn channel_width(c: Resolved) -> usize {
    match c {
        Resolved::Point(..) => 2,
        Resolved::Angle { .. } | Resolved::Value(_) => 1,
    }
}

/// The solution `(x, y)` of the symmetric arrow system `[[a, c^T], [c, diag(d)]] (x, y) = (b, e)`
/// (`a` the `m x m` block of the unknowns every target shares, its lower triangle read; `c`
/// row-major `d.len() x m`, each free input's coupling to them; `d` the free inputs' diagonal):
/// the free inputs eliminated, the Schur complement `a - c^T diag(d)^-1 c` solved by Cholesky
/// for `x`, then `y = (e - c x) / d`. A cost linear in the free inputs where the dense system's
/// was cubic. `None` where the system is not positive definite (a `d` not positive and finite,
/// or the complement not positive definite), as the dense Cholesky would have failed.
fn arrow_solve(
    mut a: nalgebra::DMatrix<f64>,
    mut b: nalgebra::DVector<f64>,
    d: &[f64],
    c: &[f64],
    e: &[f64],
) -> Option<(nalgebra::DVector<f64>, Vec<f64>)> {
    let m = b.len();
    for (t, &dt) in d.iter().enumerate() {
        if !(dt.is_finite() && dt > 0.0) {
            return None;
        }
        let ct = &c[t * m..(t + 1) * m];
        for i in 0..m {
            let ci = ct[i] / dt;
            b[i] -= ci * e[t];
            for j in 0..=i {
                a[(i, j)] -= ci * ct[j];
            }
        }
    }
    for i in 0..m {
        for j in 0..i {
            a[(j, i)] = a[(i, j)];
        }
    }
    let x = a.cholesky()?.solve(&b);
    let y = d
        .iter()
        .enumerate()
        .map(|(t, &dt)| (e[t] - c[t * m..(t + 1) * m].iter().zip(x.iter()).map(|(p, q)| p * q).sum::<f64>()) / dt)
        .collect();
    Some((x, y))
}

#[cfg(test)]
mod tests {
    use super::arrow_solve;
    use nalgebra::{DMatrix, DVector};

    /// The arrow system's solution is the dense system's: a random-looking positive definite
    /// arrow (three shared unknowns, five free inputs), solved both ways.
    #[test]
    fn arrow_solve_matches_the_dense_solve() {
        let (m, nt) = (3, 5);
        let n = m + nt;
        // J with rows touching the shared columns and one free input each, J^T J an arrow.
        let rows = 2 * nt;
        let mut j = DMatrix::<f64>::zeros(rows, n);
        for r in 0..rows {
            for i in 0..m {
                j[(r, i)] = ((r * 7 + i * 3) as f64 * 0.37).sin();
            }
            j[(r, m + r / 2)] = 1.0 + ((r * 5) as f64 * 0.21).cos();
        }
        let mut full = j.transpose() * &j;
        for i in 0..n {
            full[(i, i)] += 1e-3 * full[(i, i)];
        }
        let rhs = DVector::<f64>::from_fn(n, |i, _| ((i * 11) as f64 * 0.13).cos());
        let dense = full.clone().cholesky().unwrap().solve(&rhs);
        let a = full.view((0, 0), (m, m)).into_owned();
        let d: Vec<f64> = (0..nt).map(|t| full[(m + t, m + t)]).collect();
        let c: Vec<f64> = (0..nt).flat_map(|t| (0..m).map(move |i| (t, i))).map(|(t, i)| full[(m + t, i)]).collect();
        // The matrix is an arrow: no free input couples to another.
        for s in 0..nt {
            for t in 0..nt {
                if s != t {
                    assert_eq!(full[(m + s, m + t)], 0.0);
                }
            }
        }
        let b = rhs.rows(0, m).into_owned();
        let e: Vec<f64> = (0..nt).map(|t| rhs[m + t]).collect();
        let (x, y) = arrow_solve(a, b, &d, &c, &e).unwrap();
        for i in 0..n {
            let got = if i < m { x[i] } else { y[i - m] };
            assert!((got - dense[i]).abs() <= 1e-12 * dense.amax(), "{i}: {got} vs {}", dense[i]);
        }
        // Not positive definite: refused, as the dense Cholesky refuses it.
        let mut bad = d.clone();
        bad[2] = -1.0;
        assert!(
            arrow_solve(full.view((0, 0), (m, m)).into_owned(), rhs.rows(0, m).into_owned(), &bad, &c, &e).is_none()
        );
    }
}

/// [`OptimizerStop`] as its variant name (it has no serde impls of its own).
#[cfg(feature = "serde")]
mod stop_serde {
    use crate::analysis::optimize::OptimizerStop;
    use serde::{Deserialize, Deserializer, Serializer};

    /// Every variant, in the order of [`ACCEPTED`].
    const STOPS: [OptimizerStop; 5] = [
        OptimizerStop::Converged,
        OptimizerStop::MaxEvaluations,
        OptimizerStop::Stalled,
        OptimizerStop::InfeasibleStart,
        OptimizerStop::StepTolerance,
    ];

    /// The names read: any other is an error listing these, not a variant guessed (a typo, or a
    /// variant of a newer version, was read as `Stalled` without a word).
    const ACCEPTED: [&str; 5] = ["Converged", "MaxEvaluations", "Stalled", "InfeasibleStart", "StepTolerance"];

    /// The name of `stop`. The match is exhaustive (in this crate `#[non_exhaustive]` does not
    /// ask for a wildcard), so a new variant does not compile until it is named here; add it to
    /// [`STOPS`] and [`ACCEPTED`] too (a test checks that the three agree).
    fn name(stop: OptimizerStop) -> &'static str {
        match stop {
            OptimizerStop::Converged => "Converged",
            OptimizerStop::MaxEvaluations => "MaxEvaluations",
            OptimizerStop::Stalled => "Stalled",
            OptimizerStop::InfeasibleStart => "InfeasibleStart",
            OptimizerStop::StepTolerance => "StepTolerance",
        }
    }

    pub fn serialize<S: Serializer>(stop: &OptimizerStop, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(name(*stop))
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<OptimizerStop, D::Error> {
        let read = String::deserialize(d)?;
        STOPS
            .into_iter()
            .find(|&stop| name(stop) == read)
            .ok_or_else(|| serde::de::Error::unknown_variant(&read, &ACCEPTED))
    }

    #[cfg(test)]
    mod tests {
        use super::{ACCEPTED, STOPS, name};
        use crate::analysis::optimize::OptimizerStop;
        use crate::synthesis::LocalReport;

        fn report(stop: OptimizerStop) -> LocalReport {
            LocalReport { evaluations: 3, iterations: 2, stop, residual: 0.5 }
        }

        /// Every variant reads back as itself, by the name it is written with (the names are
        /// the variants' own, as `Debug` spells them).
        #[test]
        fn every_stop_reads_back_as_itself() {
            for (stop, written) in STOPS.into_iter().zip(ACCEPTED) {
                assert_eq!(name(stop), written);
                assert_eq!(format!("{stop:?}"), written);
                let json = serde_json::to_string(&report(stop)).unwrap();
                assert!(json.contains(&format!("\"stop\":\"{written}\"")), "{json}");
                assert_eq!(serde_json::from_str::<LocalReport>(&json).unwrap(), report(stop));
            }
        }

        /// A name that is no variant (a typo, another case, a variant of a newer version) is an
        /// error naming it and the accepted names: it was read as `Stalled` without a word.
        #[test]
        fn an_unknown_stop_is_an_error_naming_it_and_the_accepted_names() {
            let json = serde_json::to_string(&report(OptimizerStop::Converged)).unwrap();
            for typo in ["Stallled", "converged", "Diverged", ""] {
                let text = json.replace("\"Converged\"", &format!("\"{typo}\""));
                let err = serde_json::from_str::<LocalReport>(&text).unwrap_err().to_string();
                assert!(err.contains(&format!("unknown variant `{typo}`")), "{err}");
                let names = "`Converged`, `MaxEvaluations`, `Stalled`, `InfeasibleStart`, `StepTolerance`";
                assert!(err.contains(names), "{err}");
            }
        }
    }
}
