//! Objectives over a whole sweep with exact parameter gradients, and a small
//! Levenberg–Marquardt solver for synthesis.
//!
//! * [`extremum`]: the maximum or minimum of a quantity over an input range, located as a root
//!   of its velocity analog, with the gradient of its value (by the envelope theorem,
//!   `d max / dp = d q / dp` at the extremum, since `dq/dx = 0` there) and of its location
//!   (`dx*/dp = -(d q' / dp) / q''`).
//! * [`integral`]: the trapezoidal integral of a quantity over a sweep and its exact gradient.
//! * [`levenberg_marquardt`]: least squares on residuals with a Jacobian, e.g. from the above.

use crate::analysis::{Column, Sampled};
use crate::error::Error;
use crate::kin::{Kin, Sens};
use crate::mechanism::Sensitivities;
use crate::newton::NewtonConfig;
use crate::sweep::{Sweep, SweepConfig};

/// Which extremum to find.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extreme {
    Max,
    Min,
}

/// A located extremum of a quantity over an input range, with parameter gradients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extremum<const NP: usize> {
    /// Input value at the extremum.
    pub x: f64,
    /// The extreme value.
    pub value: f64,
    /// `d value / d p_k` (envelope theorem).
    pub grad: [f64; NP],
    /// `d x / d p_k`: how the extremum moves with the parameters.
    pub x_grad: [f64; NP],
}

/// (d value/dp, d first analog/dp) of a column.
fn column_sens<const N: usize, const NO: usize, const NP: usize>(
    s: &Sens<N, 1, NO, NP>,
    c: Column,
) -> ([f64; NP], [f64; NP]) {
    match c {
        Column::Unknown(u) => (s.q[u], s.dq[u][0]),
        Column::Output(o) => (s.out[o], s.dout[o][0]),
    }
}

/// Finds the maximum or minimum of the unknown or output `name` over `range` (a branch-safe
/// sweep of `samples` points from `guess`; the extremes are roots of the velocity analog located
/// by [`Sampled::range`](crate::analysis::Sampled::range)) and returns it with its parameter
/// gradients.
///
/// An extremum at an end of the range (where the analog does not vanish) is returned at the end
/// with `x_grad = 0` and `grad = dq/dp` there.
pub fn extremum<M, const N: usize, const NO: usize, const NP: usize>(
    m: &M,
    name: &str,
    which: Extreme,
    range: std::ops::RangeInclusive<f64>,
    samples: usize,
    guess: [f64; N],
    cfg: &NewtonConfig,
) -> Result<Extremum<NP>, Error>
where
    M: Sensitivities<N, 1, NO, NP>,
{
    let col = Column::named::<M, N, 1, NO>(name)?;
    let sweep_cfg = SweepConfig { newton: *cfg, ..SweepConfig::default() };
    let sampled = Sampled::sweep_with(m, *range.start(), *range.end(), samples.max(3), guess, sweep_cfg)?;
    let global = sampled.range(name)?;
    let at = if which == Extreme::Max { global.max } else { global.min };
    let interior = global.extremes.iter().any(|e| e.at.x == at.x);
    let k = sampled.at(at.x)?;
    let (k, s) = m.sensitivities_at_flat(&k.x, &k.q, cfg)?;
    let jet = col.jet(&k);
    let (grad, dgrad) = column_sens(&s, col);
    let mut x_grad = [0.0; NP];
    if interior && jet.d2 != 0.0 {
        for p in 0..NP {
            x_grad[p] = -dgrad[p] / jet.d2;
        }
    }
    Ok(Extremum { x: jet.x, value: jet.value, grad, x_grad })
}

/// The trapezoidal integral of the unknown or output `name` over a sweep of `samples` points
/// from `from` to `to`, and its exact parameter gradient (the derivative of the same quadrature).
/// For a periodic quantity over a full period the trapezoidal rule is spectrally accurate.
pub fn integral<M, const N: usize, const NO: usize, const NP: usize>(
    m: &M,
    name: &str,
    from: f64,
    to: f64,
    samples: usize,
    guess: [f64; N],
    cfg: &NewtonConfig,
) -> Result<(f64, [f64; NP]), Error>
where
    M: Sensitivities<N, 1, NO, NP>,
{
    let col = Column::named::<M, N, 1, NO>(name)?;
    let samples = samples.max(2);
    let h = (to - from) / (samples - 1) as f64;
    let mut value = 0.0;
    let mut grad = [0.0; NP];
    let mut sweep = Sweep::<M, Kin<N, 1, NO>, N, 1, NO>::new(m, [from], [to], samples, guess)?;
    let mut i = 0;
    while let Some(k) = sweep.next_kin() {
        let k = k?;
        let w = if i == 0 || i == samples - 1 { 0.5 * h } else { h };
        let (_, s) = m.sensitivities_at_flat(&k.x, &k.q, cfg)?;
        let v = col.jet(&k).value;
        let (g, _) = column_sens(&s, col);
        value += w * v;
        for p in 0..NP {
            grad[p] += w * g[p];
        }
        i += 1;
    }
    Ok((value, grad))
}

/// Settings of [`levenberg_marquardt`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LmConfig {
    /// Stop when the residual norm falls below this (default `1e-10`).
    pub tol: f64,
    /// Stop after this many evaluations (default `200`).
    pub max_evaluations: usize,
    /// Initial damping (default `1e-3`).
    pub lambda: f64,
}

impl Default for LmConfig {
    fn default() -> Self {
        LmConfig { tol: 1e-10, max_evaluations: 200, lambda: 1e-3 }
    }
}

/// Result of [`levenberg_marquardt`]: the solution and its diagnostics.
#[derive(Clone, Debug, PartialEq)]
pub struct LmResult<const P: usize> {
    pub x: [f64; P],
    /// Euclidean norm of the residuals at `x`.
    pub residual: f64,
    /// Accepted steps.
    pub iterations: usize,
    /// Residual-and-Jacobian evaluations (each one full objective evaluation).
    pub evaluations: usize,
    /// The norm after every accepted step (for printing the convergence).
    pub history: Vec<f64>,
    /// `true` when the norm reached `tol`.
    pub converged: bool,
}

/// Minimises `|r(x)|^2` for `R` residuals in `P` variables by Levenberg–Marquardt, with the
/// Jacobian supplied by `f` (e.g. from generated sensitivities). Steps solve
/// `(J^T J + lambda diag(J^T J)) dx = -J^T r`; a failed evaluation (e.g. a design that cannot
/// assemble) counts as a rejected step.
pub fn levenberg_marquardt<const R: usize, const P: usize>(
    mut f: impl FnMut(&[f64; P]) -> Result<([f64; R], [[f64; P]; R]), Error>,
    x0: [f64; P],
    cfg: &LmConfig,
) -> Result<LmResult<P>, Error> {
    let norm = |r: &[f64; R]| r.iter().map(|v| v * v).sum::<f64>().sqrt();
    let (mut r, mut jac) = f(&x0)?;
    let mut x = x0;
    let mut evaluations = 1;
    let mut lambda = cfg.lambda;
    let mut history = vec![norm(&r)];
    let mut iterations = 0;
    while norm(&r) > cfg.tol && evaluations < cfg.max_evaluations {
        // Normal equations (P is small).
        let mut a = nalgebra::DMatrix::<f64>::zeros(P, P);
        let mut g = nalgebra::DVector::<f64>::zeros(P);
        for i in 0..P {
            for j in 0..P {
                a[(i, j)] = (0..R).map(|k| jac[k][i] * jac[k][j]).sum();
            }
            g[i] = -(0..R).map(|k| jac[k][i] * r[k]).sum::<f64>();
        }
        let mut accepted = false;
        while !accepted && evaluations < cfg.max_evaluations {
            let mut damped = a.clone();
            for i in 0..P {
                damped[(i, i)] += lambda * a[(i, i)].max(1e-12);
            }
            let Some(dx) = damped.lu().solve(&g) else {
                lambda *= 10.0;
                continue;
            };
            let mut trial = x;
            for i in 0..P {
                trial[i] += dx[i];
            }
            evaluations += 1;
            match f(&trial) {
                Ok((rt, jt)) if norm(&rt) < norm(&r) => {
                    x = trial;
                    r = rt;
                    jac = jt;
                    lambda = (lambda * 0.3).max(1e-12);
                    accepted = true;
                }
                _ => lambda *= 10.0,
            }
            if lambda > 1e12 {
                break;
            }
        }
        if !accepted {
            break;
        }
        iterations += 1;
        history.push(norm(&r));
    }
    let residual = norm(&r);
    Ok(LmResult { x, residual, iterations, evaluations, history, converged: residual <= cfg.tol })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lm_solves_a_nonlinear_system() {
        // x^2 + y^2 = 4, x y = 1 from (2, 0.1).
        let f = |v: &[f64; 2]| {
            let [x, y] = *v;
            Ok(([x * x + y * y - 4.0, x * y - 1.0], [[2.0 * x, 2.0 * y], [y, x]]))
        };
        let r = levenberg_marquardt(f, [2.0, 0.1], &LmConfig::default()).unwrap();
        assert!(r.converged, "{r:?}");
        let [x, y] = r.x;
        assert!((x * x + y * y - 4.0).abs() < 1e-9 && (x * y - 1.0).abs() < 1e-9);
        assert!(r.evaluations < 30);
    }
}
