//! Levenberg–Marquardt for small least-squares problems with an exact Jacobian.

use super::{Minimum, OptimizerStop};
use crate::error::Error;

/// Minimiser of `|r(x)|^2` for `R` residuals in `P` variables with the Jacobian supplied by the
/// problem (e.g. from generated sensitivities). Steps solve
/// `(J^T J + lambda diag(J^T J)) dx = -J^T r`; a failed evaluation (e.g. a design that cannot
/// assemble) counts as a rejected step. The norms and the normal equations are scaled by powers
/// of two (exactly), so that nothing is squared out of the range of `f64`: residuals and
/// variables of any magnitude, from about 1e-300 to 1e300, take the same steps relative to their
/// size. The stop is not relative: [`LevenbergMarquardt::tol`] is a residual norm in the
/// residuals' own unit, so a problem written in another unit needs its `tol` scaled as its
/// residuals are (the default `1e-10` accepts as converged the start of a problem whose
/// residuals are smaller than that, closure errors in square metres of a mechanism a
/// micrometre across); a `tol` of `0` runs until no step lowers the norm, the same relative
/// answer in any unit.
///
/// ```
/// use kinloop_runtime::analysis::optimize::LevenbergMarquardt;
/// // x^2 + y^2 = 4, x y = 1 from (2, 0.1).
/// let f = |v: &[f64; 2]| {
///     let [x, y] = *v;
///     Ok(([x * x + y * y - 4.0, x * y - 1.0], [[2.0 * x, 2.0 * y], [y, x]]))
/// };
/// let m = LevenbergMarquardt::default().with_tol(1e-12).minimize(f, [2.0, 0.1]).unwrap();
/// assert!(m.converged() && m.value <= 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct LevenbergMarquardt {
    /// Converged when the residual norm falls to this (finite and not negative; default
    /// `1e-10`), in the residuals' unit: an absolute bound, to be scaled with the residuals.
    pub tol: f64,
    /// Stop after this many evaluations (at least 1, the start's; default `200`).
    pub max_evaluations: usize,
    /// Initial damping (positive and finite; default `1e-3`).
    pub lambda: f64,
}

impl Default for LevenbergMarquardt {
    fn default() -> Self {
        LevenbergMarquardt { tol: 1e-10, max_evaluations: 200, lambda: 1e-3 }
    }
}

/// The residual norm, scaled so that no square leaves the range of `f64` (residuals beyond
/// about 1e154 squared to infinity, and below about 1e-154 to zero).
fn norm<const R: usize>(r: &[f64; R]) -> f64 {
    crate::number::norm_of(r.iter().copied())
}

/// The power of two at most the largest magnitude of `values` (1 when they are all zero), to
/// divide them by exactly.
fn unit_of<'a>(values: impl IntoIterator<Item = &'a f64>) -> f64 {
    let big = values.into_iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    if big > 0.0 && big.is_finite() { crate::number::pow2_at_most(big) } else { 1.0 }
}

/// The normal equations `J^T J` and `-J^T r` of `J / uj` and `r / ur`, with `uj` and `ur` the
/// powers of two of the largest entries of `J` and `r` (also returned): products of entries
/// near 1 neither overflow nor underflow, whatever the scales of the residuals and the
/// variables. Their solution `dx'` is the step scaled by `uj / ur`.
fn normal<const R: usize, const P: usize>(
    r: &[f64; R],
    jac: &[[f64; P]; R],
) -> (nalgebra::DMatrix<f64>, nalgebra::DVector<f64>, f64) {
    let (ur, uj) = (unit_of(r), unit_of(jac.iter().flatten()));
    let mut a = nalgebra::DMatrix::<f64>::zeros(P, P);
    let mut g = nalgebra::DVector::<f64>::zeros(P);
    for i in 0..P {
        for j in 0..P {
            a[(i, j)] = (0..R).map(|k| (jac[k][i] / uj) * (jac[k][j] / uj)).sum();
        }
        g[i] = -(0..R).map(|k| (jac[k][i] / uj) * (r[k] / ur)).sum::<f64>();
    }
    (a, g, ur / uj)
}

/// The first entry `(k, i)` of a Jacobian that is not finite.
fn not_finite<const R: usize, const P: usize>(jac: &[[f64; P]; R]) -> Option<(usize, usize)> {
    (0..R).flat_map(|k| (0..P).map(move |i| (k, i))).find(|&(k, i)| !jac[k][i].is_finite())
}

impl LevenbergMarquardt {
    /// Sets [`LevenbergMarquardt::tol`].
    pub fn with_tol(mut self, tol: f64) -> Self {
        self.tol = tol;
        self
    }
    /// Sets [`LevenbergMarquardt::max_evaluations`].
    pub fn with_max_evaluations(mut self, n: usize) -> Self {
        self.max_evaluations = n;
        self
    }
    /// Sets [`LevenbergMarquardt::lambda`].
    pub fn with_lambda(mut self, lambda: f64) -> Self {
        self.lambda = lambda;
        self
    }

    /// The first field outside its valid range (`tol` finite and not negative,
    /// `max_evaluations` at least 1, `lambda` positive and finite; NaN is outside every range).
    pub fn invalid_field(&self) -> Option<&'static str> {
        // A NaN tolerance or damping fails every comparison: the search stopped at the start as
        // stalled. A damping not positive never grows to reject a step.
        if !(self.tol.is_finite() && self.tol >= 0.0) {
            Some("tol")
        } else if self.max_evaluations == 0 {
            Some("max_evaluations")
        } else if !(self.lambda.is_finite() && self.lambda > 0.0) {
            Some("lambda")
        } else {
            None
        }
    }

    /// Checks every field: `Error::InvalidArgument` names the first one out of range.
    pub fn validate(&self) -> Result<(), Error> {
        let range = |field| match field {
            "tol" => "finite and not negative",
            "max_evaluations" => "at least 1",
            _ => "positive and finite",
        };
        crate::error::check_fields("LevenbergMarquardt", self.invalid_field().map(|f| (f, range(f))), self)
    }

    /// Minimises `|r(x)|^2` from `x0`; `f(x)` returns the residuals and their Jacobian
    /// `J[k][i] = d r_k / d x_i`. An error at `x0` is returned, and so is a residual or an
    /// entry of the Jacobian there that is not finite (`InvalidArgument`); later errors, and
    /// residuals or Jacobians not finite, reject the step. A configuration out of range
    /// ([`LevenbergMarquardt::validate`]) is an `InvalidArgument` before any evaluation.
    pub fn minimize<const R: usize, const P: usize>(
        &self,
        mut f: impl FnMut(&[f64; P]) -> Result<([f64; R], [[f64; P]; R]), Error>,
        x0: [f64; P],
    ) -> Result<Minimum<P>, Error> {
        self.validate()?;
        let (mut r, mut jac) = f(&x0)?;
        // A NaN norm fails every comparison: no step was tried, and the NaN was returned as the
        // value of a stalled search.
        if let Some(k) = r.iter().position(|v| !v.is_finite()) {
            return Err(Error::InvalidArgument(format!("residual {k} at the start {x0:?} is {}", r[k])));
        }
        // A Jacobian not finite makes every step NaN, each rejected: the search was reported
        // stalled at its start, as if the residuals could not be lowered.
        if let Some((k, i)) = not_finite(&jac) {
            return Err(Error::InvalidArgument(format!(
                "the Jacobian's entry d r_{k} / d x_{i} at the start {x0:?} is {}",
                jac[k][i]
            )));
        }
        let mut x = x0;
        let mut evaluations = 1;
        let mut lambda = self.lambda;
        let mut value = norm(&r);
        let mut history = vec![value];
        let mut iterations = 0;
        // Without variables there is no step to take (the normal equations are empty, and
        // nalgebra's LU of an empty matrix panicked): the start is the answer, converged or
        // stalled by its residual.
        let mut stalled = P == 0;
        while value > self.tol && evaluations < self.max_evaluations && !stalled {
            // Scaled (see `normal`): the damping floor below is then relative to the largest
            // column of the Jacobian, at any scale.
            let (a, g, step_unit) = normal(&r, &jac);
            stalled = true;
            while evaluations < self.max_evaluations && lambda <= 1e12 {
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
                    trial[i] += dx[i] * step_unit;
                }
                // A step beyond the range of `f64` is too long: shorter ones are tried.
                if trial.iter().any(|v| !v.is_finite()) {
                    lambda *= 10.0;
                    continue;
                }
                evaluations += 1;
                match f(&trial) {
                    Ok((rt, jt)) if norm(&rt) < value && not_finite(&jt).is_none() => {
                        value = norm(&rt);
                        (x, r, jac) = (trial, rt, jt);
                        lambda = (lambda * 0.3).max(1e-12);
                        stalled = false;
                        break;
                    }
                    _ => lambda *= 10.0,
                }
            }
            if !stalled {
                iterations += 1;
                history.push(value);
            }
        }
        let termination = if value <= self.tol {
            OptimizerStop::Converged
        } else if evaluations >= self.max_evaluations {
            OptimizerStop::MaxEvaluations
        } else {
            OptimizerStop::Stalled
        };
        Ok(Minimum { x, value, evaluations, iterations, termination, history })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_nonlinear_system() {
        // x^2 + y^2 = 4, x y = 1 from (2, 0.1).
        let f = |v: &[f64; 2]| {
            let [x, y] = *v;
            Ok(([x * x + y * y - 4.0, x * y - 1.0], [[2.0 * x, 2.0 * y], [y, x]]))
        };
        let r = LevenbergMarquardt::default().minimize(f, [2.0, 0.1]).unwrap();
        assert!(r.converged(), "{r:?}");
        let [x, y] = r.x;
        assert!((x * x + y * y - 4.0).abs() < 1e-9 && (x * y - 1.0).abs() < 1e-9);
        assert!(r.evaluations < 30);
    }

    /// A problem of no variables answers its start: converged where its residuals are within
    /// the tolerance, stalled otherwise; the empty normal equations' LU panicked.
    #[test]
    fn no_variables_answer_the_start() {
        let lm = LevenbergMarquardt::default();
        let r = lm.minimize(|_: &[f64; 0]| Ok(([1.0, -2.0], [[], []])), []).unwrap();
        assert_eq!((r.value, r.evaluations, r.termination), (5f64.sqrt(), 1, OptimizerStop::Stalled), "{r:?}");
        let r = lm.minimize(|_: &[f64; 0]| Ok(([0.0], [[]])), []).unwrap();
        assert_eq!((r.value, r.termination), (0.0, OptimizerStop::Converged), "{r:?}");
    }

    /// Residuals not finite at the start are an error, not a stalled search of value NaN.
    #[test]
    fn residuals_not_finite_at_the_start_are_an_error() {
        for bad in [f64::NAN, f64::INFINITY] {
            let f = |v: &[f64; 1]| Ok(([v[0] - 1.0, bad], [[1.0], [0.0]]));
            let r = LevenbergMarquardt::default().minimize(f, [0.0]);
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("residual 1")), "{r:?}");
        }
    }

    /// A Jacobian not finite at the start is an error naming its entry, not a search stalled
    /// there; one not finite later rejects the step that reached it.
    #[test]
    fn jacobians_not_finite_are_an_error_at_the_start_and_rejected_later() {
        for bad in [f64::NAN, f64::INFINITY] {
            let f = |v: &[f64; 2]| Ok(([v[0] - 1.0, v[1]], [[1.0, 0.0], [0.0, bad]]));
            let r = LevenbergMarquardt::default().minimize(f, [0.0, 0.5]);
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("d r_1 / d x_1")), "{r:?}");
        }
        // x - 1 = 0 with a Jacobian that is NaN about x = 1.002, where the first step from 3
        // lands (2 / 1.001 at the initial damping): it is rejected, and a more damped one
        // converges. Accepted, it left a search stalled there.
        let f = |v: &[f64; 1]| Ok(([v[0] - 1.0], [[if (v[0] - 1.002).abs() < 5e-4 { f64::NAN } else { 1.0 }]]));
        let r = LevenbergMarquardt::default().minimize(f, [3.0]).unwrap();
        assert!(r.converged() && r.x[0].is_finite(), "{r:?}");
    }

    /// Settings out of range are errors naming them; a NaN tolerance or damping stopped the
    /// search at the start as stalled, a damping of zero or below never rejected a step.
    #[test]
    fn settings_out_of_range_are_errors() {
        let f = |v: &[f64; 1]| Ok(([v[0] - 1.0], [[1.0]]));
        let lm = LevenbergMarquardt::default();
        for (cfg, field) in [
            (lm.with_tol(f64::NAN), "tol"),
            (lm.with_tol(-1.0), "tol"),
            (lm.with_lambda(f64::NAN), "lambda"),
            (lm.with_lambda(0.0), "lambda"),
            (lm.with_lambda(-1.0), "lambda"),
            (lm.with_lambda(f64::INFINITY), "lambda"),
            (lm.with_tol(f64::INFINITY), "tol"),
            (lm.with_max_evaluations(0), "max_evaluations"),
        ] {
            let mut calls = 0;
            let r = cfg.minimize(
                |v: &[f64; 1]| {
                    calls += 1;
                    f(v)
                },
                [0.0],
            );
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains(field)), "{cfg:?}: {r:?}");
            assert_eq!(calls, 0, "refused before any evaluation");
        }
        assert!(lm.with_tol(0.0).minimize(f, [0.0]).unwrap().converged());
    }

    /// The circle-and-hyperbola system of `solves_a_nonlinear_system` with its residuals scaled
    /// by `s_r` and its variables by `s_x` (the Jacobian by `s_r / s_x`), the tolerance with the
    /// residuals.
    fn scaled(s_r: f64, s_x: f64) -> Result<Minimum<2>, Error> {
        let f = |v: &[f64; 2]| {
            let [x, y] = [v[0] / s_x, v[1] / s_x];
            let j = s_r / s_x;
            Ok(([s_r * (x * x + y * y - 4.0), s_r * (x * y - 1.0)], [[j * 2.0 * x, j * 2.0 * y], [j * y, j * x]]))
        };
        LevenbergMarquardt::default().with_tol(1e-10 * s_r).minimize(f, [2.0 * s_x, 0.1 * s_x])
    }

    /// The same relative answer at every scale of the residuals and the variables: squared,
    /// residuals beyond about 1e154 overflowed (the search stalled at its start) and below about
    /// 1e-154 underflowed (it was "converged" at its start); a Jacobian as large or small did
    /// the same to the normal equations. The answer is the unscaled one to 1e-9, well within
    /// what the tolerance 1e-10 (on residuals whose Jacobian is of order 1) pins down.
    #[test]
    fn every_scale_of_residuals_and_variables_gives_the_same_answer() {
        let unscaled = scaled(1.0, 1.0).unwrap();
        assert!(unscaled.converged(), "{unscaled:?}");
        for s in [1e-300, 1e-200, 1e-100, 2f64.powi(-600), 1e100, 2f64.powi(600), 1e200, 1e300] {
            for (s_r, s_x) in [(s, s), (s, 1.0), (1.0, s)] {
                let m = scaled(s_r, s_x).unwrap();
                assert!(m.converged(), "residuals x {s_r:e}, variables x {s_x:e}: {m:?}");
                for i in 0..2 {
                    let x = m.x[i] / s_x;
                    assert!((x - unscaled.x[i]).abs() <= 1e-9 * unscaled.x[i].abs(), "{s_r:e} {s_x:e}: {m:?}");
                }
                assert!(m.value <= 1e-10 * s_r, "{s_r:e} {s_x:e}: {m:?}");
            }
        }
    }

    #[test]
    fn an_inconsistent_system_stalls() {
        // x = 1 and x = 2: the least-squares minimum 1.5 has residual norm 1/sqrt(2).
        let f = |v: &[f64; 1]| Ok(([v[0] - 1.0, v[0] - 2.0], [[1.0], [1.0]]));
        let r = LevenbergMarquardt::default().minimize(f, [0.0]).unwrap();
        assert!(!r.converged());
        assert!((r.x[0] - 1.5).abs() < 1e-9 && (r.value - 0.5f64.sqrt()).abs() < 1e-12, "{r:?}");
    }
}
