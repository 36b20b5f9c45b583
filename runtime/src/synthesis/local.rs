//! The local solve: Levenberg–Marquardt on the residuals with their exact Jacobian, kept inside
//! the bounds (a variable on a bound that the step would push out is held there for that step),
//! each evaluation solving the positions from the last accepted ones.

use super::problem::ProblemOf;
use super::residuals::Eval;
use crate::analysis::optimize::OptimizerStop;
use crate::error::Error;
use crate::mechanism::kernel::{Q, SensKernel};

/// Settings of the local solve.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct LocalConfig {
    /// Stop after this many evaluations of the residuals and Jacobian (default `100`).
    pub max_evaluations: usize,
    /// Converged when the residual norm is at most `tol` times the size of the targets
    /// (their largest distance from their centroid; default `1e-14`, rounding).
    pub tol: f64,
    /// Converged when an accepted step changes no unknown by more than `step_tol` times its
    /// size (`|dz_i| <= step_tol (|z_i| + step_tol)`; default `1e-13`): a local minimum, whose
    /// residual need not be zero.
    pub step_tol: f64,
    /// Initial damping, relative to the diagonal of `J^T J` (default `1e-3`).
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

    /// The first field out of its range, by name.
    pub(crate) fn invalid_field(&self) -> Option<&'static str> {
        if self.max_evaluations == 0 {
            Some("max_evaluations")
        } else if !(self.tol.is_finite() && self.tol >= 0.0) {
            Some("tol")
        } else if !(self.step_tol.is_finite() && self.step_tol >= 0.0) {
            Some("step_tol")
        } else if !(self.lambda.is_finite() && self.lambda > 0.0) {
            Some("lambda")
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
    /// Why it stopped: [`OptimizerStop::Converged`] when a tolerance was met.
    #[cfg_attr(feature = "serde", serde(with = "stop_serde"))]
    pub stop: OptimizerStop,
    /// The residual norm at the end.
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
        let stop = loop {
            if f <= cfg.tol * self.scale {
                break OptimizerStop::Converged;
            }
            if evaluations >= cfg.max_evaluations {
                break OptimizerStop::MaxEvaluations;
            }
            // Normal equations J^T J and the gradient J^T r, of the residuals in units of the
            // targets' weighted size (by the power of two nearest it: exact, so the same steps
            // bit for bit as unscaled): their squares neither underflow nor overflow whatever
            // the weights. Weights of 1e-200 made them 0, and every start "converged" where it
            // began.
            let unit = 2f64.powi(-(self.scale.log2().round() as i32).clamp(-1000, 1000));
            let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
            let mut g = nalgebra::DVector::<f64>::zeros(n);
            for k in 0..rows {
                let jk = &e.jac[k * n..(k + 1) * n];
                let rk = e.r[k] * unit;
                for i in 0..n {
                    let ji = jk[i] * unit;
                    g[i] += ji * rk;
                    for j in 0..=i {
                        a[(i, j)] += ji * jk[j] * unit;
                    }
                }
            }
            for i in 0..n {
                for j in 0..i {
                    a[(j, i)] = a[(i, j)];
                }
            }
            // Held: on a bound with the descent direction (-g) pointing out.
            let held: Vec<bool> =
                (0..n).map(|i| (z[i] <= lo[i] && g[i] > 0.0) || (z[i] >= hi[i] && g[i] < 0.0)).collect();
            // The floor keeps the damped matrix regular where a column vanishes. Relative to the
            // largest column it swamped a column smaller by 1e6 (an angle's against a length's
            // at a unit of 1e-100, or a length's against an angle's at 1e100): that unknown's
            // steps came out too small to change it, and the solve stopped "converged" there.
            // So it is judged on the unknowns scaled by their widths: the largest change any one
            // makes over its range, `sqrt(a_ii) w_i`, a millionth of it over the unknown's own
            // width, squared.
            let reach = (0..n).filter(|&i| !held[i]).map(|i| a[(i, i)].sqrt() * width[i]).fold(0.0, f64::max);
            let floor = |i: usize| (1e-6 * reach / width[i]).powi(2).min(f64::MAX);
            let mut step = Step::Exhausted;
            while evaluations < cfg.max_evaluations && lambda <= 1e16 {
                let mut damped = a.clone();
                let mut rhs = -g.clone();
                for i in 0..n {
                    if held[i] {
                        damped.row_mut(i).fill(0.0);
                        damped.column_mut(i).fill(0.0);
                        damped[(i, i)] = 1.0;
                        rhs[i] = 0.0;
                    } else {
                        damped[(i, i)] += lambda * a[(i, i)].max(floor(i)).max(f64::MIN_POSITIVE);
                    }
                }
                let Some(dz) = damped.cholesky().map(|c| c.solve(&rhs)) else {
                    lambda *= 10.0;
                    continue;
                };
                let trial: Vec<f64> = (0..n).map(|i| (z[i] + dz[i]).clamp(lo[i], hi[i])).collect();
                let small = (0..n).all(|i| (trial[i] - z[i]).abs() <= cfg.step_tol * (z[i].abs() + cfg.step_tol));
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
                    // No shorter step changes the design either: a local minimum.
                    _ if small => {
                        step = Step::Stationary;
                        break;
                    }
                    _ => lambda *= 10.0,
                }
            }
            match step {
                Step::Accepted { small: false } => {}
                Step::Accepted { small: true } | Step::Stationary => break OptimizerStop::Converged,
                Step::Exhausted if evaluations >= cfg.max_evaluations => break OptimizerStop::MaxEvaluations,
                Step::Exhausted => break OptimizerStop::Stalled,
            }
        };
        let report = LocalReport { evaluations, iterations, stop, residual: f };
        Ok((z, e, report))
    }
}

/// [`OptimizerStop`] as its variant name (it has no serde impls of its own).
#[cfg(feature = "serde")]
mod stop_serde {
    use crate::analysis::optimize::OptimizerStop;
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(stop: &OptimizerStop, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(match stop {
            OptimizerStop::Converged => "Converged",
            OptimizerStop::MaxEvaluations => "MaxEvaluations",
            OptimizerStop::InfeasibleStart => "InfeasibleStart",
            _ => "Stalled",
        })
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<OptimizerStop, D::Error> {
        Ok(match String::deserialize(d)?.as_str() {
            "Converged" => OptimizerStop::Converged,
            "MaxEvaluations" => OptimizerStop::MaxEvaluations,
            "InfeasibleStart" => OptimizerStop::InfeasibleStart,
            _ => OptimizerStop::Stalled,
        })
    }
}
