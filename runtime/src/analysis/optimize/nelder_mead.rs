//! The Nelder–Mead simplex method with the dimension-adaptive coefficients of Gao and Han
//! (2012) (reflection 1, expansion `1 + 2/n`, contraction `3/4 - 1/(2n)`, shrink `1 - 1/n`),
//! restarts from the best point, and evaluation counting. For one variable the coefficients are
//! those of `n = 2`, the standard method's (expansion 2, contraction and shrink 1/2): at `n = 1`
//! the shrink `1 - 1/n` is 0, which collapses the simplex onto its best vertex, a point the
//! search then calls converged wherever it is.
//!
//! Box constraints (each parameter in a range) are best handled by
//! [`NelderMead::minimize_boxed`], which searches unconstrained variables mapped into the box,
//! so optima on a face of the box are reached smoothly. Other constraints (a design that cannot
//! assemble) are expressed by returning `f64::INFINITY` (or NaN, treated alike) from the
//! objective: such points are never accepted, and the simplex contracts away from them. The
//! starting point must be feasible.

use super::{Minimum, OptimizerStop};
use crate::error::Error;
use crate::number::Number;

/// Derivative-free minimiser: the Nelder–Mead simplex method with the dimension-adaptive
/// coefficients of Gao and Han, restarts and evaluation counting. Infeasible points are marked
/// by an infinite (or NaN) objective. The configuration is apart from the problem: build it
/// once, then [`minimize`](NelderMead::minimize) any objective.
///
/// The stop is not relative: both tolerances are absolute, [`NelderMead::f_tol`] in the
/// objective's own unit and [`NelderMead::x_tol`] in the variables' (each coordinate's own,
/// whatever its size), so a problem written in other units needs them scaled as its objective
/// and its variables are. With the defaults (`1e-12`, `1e-9`), a design whose lengths are in
/// metres and about `1e-6` (a mechanism a micrometre across) converges once its simplex is a
/// thousandth of its size, and an objective whose values are all below `1e-12` (squared errors
/// in square metres of that mechanism) meets `f_tol` from the start, the simplex then stopped
/// by `x_tol` alone. Restarts compare the improvement with `f_tol` too. In
/// [`NelderMead::minimize_boxed`] `x_tol` applies to the box's mapped variables (radians of a
/// sine: relative to each box's width, whatever its unit), `f_tol` still to the objective.
///
/// ```
/// use kinloop_runtime::analysis::optimize::NelderMead;
/// // Rosenbrock's valley: minimum 0 at (1, 1).
/// let rosenbrock = |p: &[f64; 2]| (1.0 - p[0]).powi(2) + 100.0 * (p[1] - p[0] * p[0]).powi(2);
/// let m = NelderMead::default().minimize(rosenbrock, [-1.2, 1.0], [0.5, 0.5])?;
/// assert!(m.converged() && (m.x[0] - 1.0).abs() < 1e-6 && (m.x[1] - 1.0).abs() < 1e-6);
/// assert!(m.value < 1e-12 && m.evaluations < 1000);
/// // A tolerance no simplex meets is refused before any evaluation, naming the field.
/// let bad = NelderMead::default().with_tolerances(f64::NAN, 1e-9).minimize(rosenbrock, [-1.2, 1.0], [0.5, 0.5]);
/// assert!(bad.unwrap_err().to_string().contains("NelderMead::f_tol"));
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct NelderMead {
    /// Stop after this many objective evaluations (at least 1; default `2000`). The starting
    /// simplex is evaluated whole, and the last iteration may finish its contraction and shrink:
    /// up to `P + 2` more.
    pub max_evaluations: usize,
    /// Converged when the simplex's objective values differ by at most `f_tol` (in the
    /// objective's unit: an absolute bound, to be scaled with the objective) ...
    pub f_tol: f64,
    /// ... and every vertex lies within `x_tol` (in each coordinate, in its own unit: an absolute
    /// bound, to be scaled with the variables) of the best one (both finite and not negative;
    /// defaults `1e-12` and `1e-9`).
    pub x_tol: f64,
    /// After convergence, rebuild the simplex around the best point (with the initial steps) up
    /// to this many times, until a restart no longer improves the best value by more than
    /// `f_tol` (default `2`). This guards against the simplex collapsing before a minimum.
    pub restarts: usize,
}

impl Default for NelderMead {
    fn default() -> Self {
        NelderMead { max_evaluations: 2000, f_tol: 1e-12, x_tol: 1e-9, restarts: 2 }
    }
}

/// The simplex: vertices and their objective values.
struct Simplex<const P: usize> {
    xs: Vec<[f64; P]>,
    fs: Vec<f64>,
}

impl NelderMead {
    /// Sets [`NelderMead::max_evaluations`].
    pub fn with_max_evaluations(mut self, n: usize) -> Self {
        self.max_evaluations = n;
        self
    }
    /// Sets [`NelderMead::f_tol`] and [`NelderMead::x_tol`].
    pub fn with_tolerances(mut self, f_tol: f64, x_tol: f64) -> Self {
        self.f_tol = f_tol;
        self.x_tol = x_tol;
        self
    }
    /// Sets [`NelderMead::restarts`].
    pub fn with_restarts(mut self, n: usize) -> Self {
        self.restarts = n;
        self
    }

    /// The first field outside its valid range (`max_evaluations` at least 1, `f_tol` and
    /// `x_tol` finite and not negative; NaN is outside every range).
    pub fn invalid_field(&self) -> Option<&'static str> {
        // A NaN or negative tolerance is met by no simplex: the search ran to its budget and
        // reported it as the budget's fault.
        let tol = |t: f64| t.is_finite() && t >= 0.0;
        if self.max_evaluations == 0 {
            Some("max_evaluations")
        } else if !tol(self.f_tol) {
            Some("f_tol")
        } else if !tol(self.x_tol) {
            Some("x_tol")
        } else {
            None
        }
    }

    /// Checks every field: `Error::InvalidArgument` names the first one out of range.
    pub fn validate(&self) -> Result<(), Error> {
        let range = |field| if field == "max_evaluations" { "at least 1" } else { "finite and not negative" };
        crate::error::check_fields("NelderMead", self.invalid_field().map(|f| (f, range(f))), self)
    }

    /// Minimises `f` over `P` variables from `x0`, with an initial simplex of `x0` and the
    /// points `x0 + step[i] e_i`. `value` is `f(x)`; `history` the best value after each round
    /// (the first search and every restart). When `f` is infinite or NaN at every vertex of
    /// that simplex it stops there, [`OptimizerStop::InfeasibleStart`] (after `P + 1`
    /// evaluations).
    ///
    /// Errors: `InvalidArgument`, before any evaluation, for a configuration out of range
    /// ([`NelderMead::validate`]), a start not finite, or a step that is zero or not finite (it
    /// spans no simplex in its coordinate), naming the field or coordinate.
    pub fn minimize<const P: usize>(
        &self,
        mut f: impl FnMut(&[f64; P]) -> f64,
        x0: [f64; P],
        step: [f64; P],
    ) -> Result<Minimum<P>, Error> {
        self.validate()?;
        check_start("NelderMead::minimize", &x0)?;
        // A zero step leaves its coordinate out of the simplex (never searched, and with every
        // step zero the start was "converged"); a step not finite made every trial point NaN.
        if let Some(i) = (0..P).find(|&i| !(step[i].is_finite() && step[i] != 0.0)) {
            return Err(Error::InvalidArgument(format!(
                "NelderMead::minimize: the step of coordinate {i} is {}; steps must be finite and non-zero",
                step[i]
            )));
        }
        let evaluations = std::cell::Cell::new(0usize);
        let mut eval = |x: &[f64; P]| {
            evaluations.set(evaluations.get() + 1);
            let v = f(x);
            if v.is_nan() { f64::INFINITY } else { v }
        };
        let mut best = x0;
        let mut f_best = eval(&x0);
        let mut iterations = 0usize;
        let mut converged;
        let mut restarts_left = self.restarts;
        let mut history = vec![f_best];
        loop {
            let f_start = f_best;
            let mut s = Simplex { xs: vec![best], fs: vec![f_best] };
            for i in 0..P {
                let mut x = best;
                x[i] += step[i];
                s.fs.push(eval(&x));
                s.xs.push(x);
            }
            // Nothing feasible to move from: reflecting between infinities would spend the
            // whole budget and end as if it had run out.
            if P > 0 && s.fs.iter().all(|v| *v == f64::INFINITY) {
                history.push(f_best);
                let (evaluations, termination) = (evaluations.get(), OptimizerStop::InfeasibleStart);
                return Ok(Minimum { x: best, value: f_best, evaluations, iterations, termination, history });
            }
            converged = self.search(&mut s, &mut eval, &evaluations, &mut iterations);
            let i = (0..=P).min_by(|&a, &b| s.fs[a].total_cmp(&s.fs[b])).unwrap_or(0);
            if s.fs[i] < f_best {
                (best, f_best) = (s.xs[i], s.fs[i]);
            }
            history.push(f_best);
            let improved = f_start - f_best > self.f_tol;
            if !converged || restarts_left == 0 || (!improved && restarts_left < self.restarts) {
                break;
            }
            restarts_left -= 1;
        }
        let termination = if converged { OptimizerStop::Converged } else { OptimizerStop::MaxEvaluations };
        Ok(Minimum { x: best, value: f_best, evaluations: evaluations.get(), iterations, termination, history })
    }

    /// Simplex iterations until the tolerances are met (`true`) or the evaluations run out.
    fn search<const P: usize>(
        &self,
        s: &mut Simplex<P>,
        eval: &mut impl FnMut(&[f64; P]) -> f64,
        evaluations: &std::cell::Cell<usize>,
        iterations: &mut usize,
    ) -> bool {
        // No variable: the one point is the minimum (the steps below need a second vertex).
        if P == 0 {
            return true;
        }
        // The centroid is of the `P` best vertices; the coefficients are Gao and Han's at `P`,
        // but at least 2: their shrink `1 - 1/n` is 0 at `n = 1`, and a shrink there put every
        // vertex on the best one (a simplex of no size, "converged" where the slope is not
        // zero: `(x + 0.1)^2 + exp(-((x + 0.25) / 0.15)^2)` stopped at its start, 0, slope
        // -1.18, beside its minimum at 0.066). At `n = 2` they are the standard method's.
        let n = P.max(1) as f64;
        let adaptive = P.max(2) as f64;
        let (alpha, gamma, rho, sigma) = (1.0, 1.0 + 2.0 / adaptive, 0.75 - 0.5 / adaptive, 1.0 - 1.0 / adaptive);
        loop {
            // Order: best first, worst last.
            let mut idx: Vec<usize> = (0..=P).collect();
            idx.sort_by(|&a, &b| s.fs[a].total_cmp(&s.fs[b]));
            s.xs = idx.iter().map(|&i| s.xs[i]).collect();
            s.fs = idx.iter().map(|&i| s.fs[i]).collect();
            let (xs, fs) = (&mut s.xs, &mut s.fs);
            let spread = fs[P] - fs[0];
            let size = xs.iter().flat_map(|x| x.iter().zip(&xs[0]).map(|(a, b)| (a - b).abs())).fold(0.0, f64::max);
            if spread <= self.f_tol && size <= self.x_tol {
                return true;
            }
            if evaluations.get() >= self.max_evaluations {
                return false;
            }
            *iterations += 1;
            let mut c = [0.0; P];
            for x in &xs[..P] {
                for k in 0..P {
                    c[k] += x[k] / n;
                }
            }
            let worst = xs[P];
            let along = |t: f64| {
                let mut y = [0.0; P];
                for k in 0..P {
                    y[k] = c[k] + t * (worst[k] - c[k]);
                }
                y
            };
            let mut ev = |x: &[f64; P]| eval(x);
            let xr = along(-alpha);
            let fr = ev(&xr);
            if fr < fs[0] {
                let xe = along(-alpha * gamma);
                let fe = ev(&xe);
                (xs[P], fs[P]) = if fe < fr { (xe, fe) } else { (xr, fr) };
                continue;
            }
            if fr < fs[P - 1] {
                (xs[P], fs[P]) = (xr, fr);
                continue;
            }
            // Contraction: outside when the reflected point beats the worst, inside otherwise.
            let t = if fr < fs[P] { -alpha * rho } else { rho };
            let xc = along(t);
            let fc = ev(&xc);
            if (fr < fs[P] && fc <= fr) || (fr >= fs[P] && fc < fs[P]) {
                (xs[P], fs[P]) = (xc, fc);
                continue;
            }
            // Shrink towards the best vertex.
            for i in 1..=P {
                for k in 0..P {
                    xs[i][k] = xs[0][k] + sigma * (xs[i][k] - xs[0][k]);
                }
                fs[i] = ev(&xs[i]);
            }
        }
    }

    /// Minimises `f` over the box `lo[i] <= x[i] <= hi[i]` by [`NelderMead::minimize`] on
    /// unconstrained variables `u` with `x = lo + (hi - lo) (1 + sin u) / 2` (the transformation
    /// of MINUIT): every trial point lies in the box, and a minimum on a face of the box is a
    /// smooth minimum in `u`. The initial simplex steps are `0.25` rad in `u` (a quarter of the
    /// range near the centre). `x_tol` applies to `u`: a box resolves `x` to about `1e-16` of its
    /// width, so a box far wider than the minimum's scale hides it (over `[-1e300, 1e300]` every
    /// point near 0 maps to the same few doubles).
    ///
    /// Errors: `InvalidArgument`, before any evaluation, naming the coordinate and its bounds if
    /// a bound is not finite or `lo[i] > hi[i]` (a box that holds no point, or one the sine
    /// cannot map onto), and as [`NelderMead::minimize`] for the configuration and a start not
    /// finite. A finite start outside the box starts from its nearest point in the box.
    ///
    /// ```
    /// use kinloop_runtime::analysis::optimize::NelderMead;
    /// // (x - 2)^2 + (y + 0.5)^2 over [0, 1] x [-1, 1]: the minimum is on the face x = 1.
    /// let f = |p: &[f64; 2]| (p[0] - 2.0).powi(2) + (p[1] + 0.5).powi(2);
    /// let m = NelderMead::default().minimize_boxed(f, [0.5, 0.0], [0.0, -1.0], [1.0, 1.0])?;
    /// assert!((m.x[0] - 1.0).abs() < 1e-9 && (m.x[1] + 0.5).abs() < 1e-6 && m.x[0] <= 1.0);
    /// // A box that holds no point is refused, naming the coordinate.
    /// let bad = NelderMead::default().minimize_boxed(f, [0.5, 0.0], [0.0, 1.0], [1.0, -1.0]);
    /// assert!(bad.unwrap_err().to_string().contains("coordinate 1"));
    /// # Ok::<(), kinloop_runtime::Error>(())
    /// ```
    pub fn minimize_boxed<const P: usize>(
        &self,
        mut f: impl FnMut(&[f64; P]) -> f64,
        x0: [f64; P],
        lo: [f64; P],
        hi: [f64; P],
    ) -> Result<Minimum<P>, Error> {
        self.validate()?;
        check_start("NelderMead::minimize_boxed", &x0)?;
        // Checked here, naming the coordinate: `clamp` panicked with its own words for
        // `lo > hi` or a NaN, and infinite bounds made every trial point NaN.
        // A width beyond the doubles (`-1e308 ..= 1e308`) made the start NaN, and the error
        // blamed the start.
        if let Some(i) = (0..P).find(|&i| !(lo[i] <= hi[i] && (hi[i] - lo[i]).is_finite())) {
            return Err(Error::InvalidArgument(format!(
                "NelderMead::minimize_boxed: the box of coordinate {i}, [{}, {}], needs finite bounds with lo <= hi, \
                 at most the largest double apart",
                Number(lo[i]),
                Number(hi[i])
            )));
        }
        let to_x = |u: &[f64; P]| {
            let mut x = [0.0; P];
            for i in 0..P {
                x[i] = (lo[i] + (hi[i] - lo[i]) * 0.5 * (1.0 + u[i].sin())).clamp(lo[i], hi[i]);
            }
            x
        };
        let mut u0 = [0.0; P];
        for i in 0..P {
            let t = if hi[i] > lo[i] { 2.0 * (x0[i] - lo[i]) / (hi[i] - lo[i]) - 1.0 } else { 0.0 };
            u0[i] = t.clamp(-1.0, 1.0).asin();
        }
        let m = self.minimize(|u| f(&to_x(u)), u0, [0.25; P])?;
        Ok(Minimum { x: to_x(&m.x), ..m })
    }
}

/// A start not finite, as an error naming its coordinate: the objective there is meaningless
/// and every simplex built on it NaN.
fn check_start<const P: usize>(method: &str, x0: &[f64; P]) -> Result<(), Error> {
    match x0.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(Error::InvalidArgument(format!("{method}: coordinate {i} of the start is {}", x0[i]))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rosenbrock_and_a_quadratic_bowl() {
        let mut calls = 0;
        let m = NelderMead::default()
            .minimize(
                |p: &[f64; 2]| {
                    calls += 1;
                    (1.0 - p[0]).powi(2) + 100.0 * (p[1] - p[0] * p[0]).powi(2)
                },
                [-1.2, 1.0],
                [0.5, 0.5],
            )
            .unwrap();
        assert!(m.converged());
        assert!((m.x[0] - 1.0).abs() < 1e-6 && (m.x[1] - 1.0).abs() < 1e-6, "{m:?}");
        assert_eq!(m.evaluations, calls, "every call is counted");

        // A rotated, badly scaled 5-D quadratic with its minimum at c.
        let c = [0.3, -1.0, 2.0, 0.5, -0.25];
        let q = |p: &[f64; 5]| {
            let d: Vec<f64> = (0..5).map(|i| p[i] - c[i]).collect();
            (0..5).map(|i| (i + 1) as f64 * d[i].powi(2)).sum::<f64>() + d[0] * d[1] + 0.5 * d[2] * d[4]
        };
        let m = NelderMead::default().minimize(q, [0.0; 5], [0.5; 5]).unwrap();
        assert!(m.converged(), "{m:?}");
        for i in 0..5 {
            assert!((m.x[i] - c[i]).abs() < 1e-5, "{m:?}");
        }
    }

    #[test]
    fn infeasible_points_are_avoided() {
        // Minimise (x - 2)^2 + y^2 subject to x <= 1: the constrained minimum is (1, 0).
        let f = |p: &[f64; 2]| if p[0] > 1.0 { f64::INFINITY } else { (p[0] - 2.0).powi(2) + p[1] * p[1] };
        let m = NelderMead::default().minimize(f, [0.0, 0.5], [0.3, 0.3]).unwrap();
        assert!(m.x[0] <= 1.0 && (m.x[0] - 1.0).abs() < 1e-6 && m.x[1].abs() < 1e-4, "{m:?}");
        let nan = |p: &[f64; 1]| if p[0] < 0.0 { f64::NAN } else { (p[0] - 0.5).powi(2) };
        let m = NelderMead::default().minimize(nan, [2.0], [1.0]).unwrap();
        assert!((m.x[0] - 0.5).abs() < 1e-6, "{m:?}");
    }

    #[test]
    fn boxed_search_reaches_faces_and_corners() {
        // The unconstrained minimum (2, -3) lies outside [0, 1] x [-1, 1]: the corner (1, -1).
        let f = |p: &[f64; 2]| (p[0] - 2.0).powi(2) + (p[1] + 3.0).powi(2) + 0.1 * p[0] * p[1];
        let m = NelderMead::default().minimize_boxed(f, [0.2, 0.3], [0.0, -1.0], [1.0, 1.0]).unwrap();
        assert!((m.x[0] - 1.0).abs() < 1e-9 && (m.x[1] + 1.0).abs() < 1e-9, "{m:?}");
        // An interior minimum is found as without the box.
        let g = |p: &[f64; 2]| (p[0] - 0.3).powi(2) + 2.0 * (p[1] - 0.7).powi(2);
        let m = NelderMead::default().minimize_boxed(g, [0.9, -0.9], [0.0, -1.0], [1.0, 1.0]).unwrap();
        assert!((m.x[0] - 0.3).abs() < 1e-6 && (m.x[1] - 0.7).abs() < 1e-6, "{m:?}");
    }

    /// A box with `lo > hi` is an error naming the coordinate and its bounds (it was a panic,
    /// and before that `clamp`'s own); an infinite or NaN bound too (it made every trial point
    /// NaN). Nothing is evaluated.
    #[test]
    fn a_box_that_holds_no_point_is_an_error_naming_its_coordinate() {
        let mut calls = 0;
        let mut f = |p: &[f64; 2]| {
            calls += 1;
            p[0] + p[1]
        };
        let inverted = NelderMead::default().minimize_boxed(&mut f, [0.5, 0.5], [0.0, 1.0], [1.0, 0.0]);
        let bad = [
            (inverted, "the box of coordinate 1, [1, 0]"),
            (
                NelderMead::default().minimize_boxed(&mut f, [0.5, 0.5], [f64::NEG_INFINITY, 0.0], [1.0, 1.0]),
                "the box of coordinate 0, [-inf, 1]",
            ),
            (
                NelderMead::default().minimize_boxed(&mut f, [0.5, 0.5], [0.0, 0.0], [1.0, f64::NAN]),
                "the box of coordinate 1, [0, NaN]",
            ),
            // Finite ends farther apart than a double holds: the box named, not the start.
            (
                NelderMead::default().minimize_boxed(&mut f, [0.5, 0.5], [-1e308, 0.0], [1e308, 1.0]),
                "the box of coordinate 0, [-1e308, 1e308]",
            ),
        ];
        for (r, want) in bad {
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains(want)), "{want}: {r:?}");
        }
        assert_eq!(calls, 0, "refused before any evaluation");
    }

    /// No variable: the start is the minimum, whatever the tolerances (the search indexed the
    /// simplex's second vertex, a panic, with tolerances the single vertex could not meet).
    /// One variable, where the search shrinks its simplex (the reflection beyond a bump, the
    /// contraction onto it): Gao and Han's shrink at `n = 1` is 0, which put both vertices on
    /// the best one, and the search stopped there "converged", at its start 0 after 9
    /// evaluations, where the slope is -1.18. The minimum, at 0.0660 (value 0.03938, the root of
    /// `f' = 2 (x + 0.1) - 2 (x + 0.25) / 0.15^2 exp(-((x + 0.25) / 0.15)^2)` by bisection
    /// below), is found to the tolerances, with the first step either way.
    #[test]
    fn one_variable_is_not_collapsed_by_a_shrink() {
        let f = |p: &[f64; 1]| (p[0] + 0.1).powi(2) + (-((p[0] + 0.25) / 0.15).powi(2)).exp();
        let slope = |x: f64| 2.0 * (x + 0.1) - 2.0 * (x + 0.25) / 0.0225 * (-((x + 0.25) / 0.15).powi(2)).exp();
        // The minimum: the slope's root in [0, 0.2] (negative at 0, positive at 0.2), bisected
        // to the doubles.
        let (mut lo, mut hi) = (0.0, 0.2);
        assert!(slope(lo) < 0.0 && slope(hi) > 0.0);
        while hi - lo > 1e-15 {
            let mid = 0.5 * (lo + hi);
            if slope(mid) < 0.0 { lo = mid } else { hi = mid }
        }
        let best = f(&[lo]);
        for step in [1.0, -1.0, 0.5] {
            let m = NelderMead::default().minimize(f, [0.0], [step]).unwrap();
            assert!(m.converged(), "step {step}: {m:?}");
            // Converged is the values within f_tol = 1e-12 of each other: about the minimum,
            // where f'' = 10.3, that is within sqrt(2 f_tol / f'') = 4.4e-7 of it in x.
            assert!((m.x[0] - lo).abs() < 1e-5, "step {step}: {} against {lo}", m.x[0]);
            assert!(m.value - best < 1e-12, "step {step}: {} against {best}", m.value);
        }
    }

    #[test]
    fn no_variable_is_converged_at_the_start() {
        let m = NelderMead::default().with_tolerances(0.0, 0.0).minimize(|_: &[f64; 0]| 2.0, [], []).unwrap();
        assert!(m.converged() && m.value == 2.0, "{m:?}");
    }

    /// A start whose whole simplex is infeasible (NaN or infinite everywhere) stops at once,
    /// saying so: it spent every evaluation of the budget reflecting between infinities. A
    /// start infeasible itself but beside a feasible vertex still searches.
    #[test]
    fn an_infeasible_starting_simplex_stops_at_once() {
        for bad in [f64::NAN, f64::INFINITY] {
            let mut calls = 0;
            let m = NelderMead::default()
                .minimize(
                    |_: &[f64; 3]| {
                        calls += 1;
                        bad
                    },
                    [1.0, 2.0, 3.0],
                    [0.1; 3],
                )
                .unwrap();
            assert_eq!(m.termination, OptimizerStop::InfeasibleStart, "{m:?}");
            assert_eq!((m.evaluations, calls), (4, 4), "the start and one vertex a variable");
            assert_eq!(m.x, [1.0, 2.0, 3.0]);
            assert!(m.value == f64::INFINITY && !m.converged(), "{m:?}");
        }
        let m = NelderMead::default()
            .minimize(|p: &[f64; 1]| if p[0] < 0.0 { f64::NAN } else { p[0] * p[0] }, [-0.1], [0.5])
            .unwrap();
        assert!(m.converged() && m.x[0].abs() < 1e-6, "{m:?}");
    }

    /// Tolerances NaN or negative (which no simplex meets: it ran to the evaluation budget),
    /// steps that span no simplex and starts not finite are refused before any evaluation.
    #[test]
    fn bad_settings_and_starts_are_refused_before_any_evaluation() {
        let nm = NelderMead::default();
        let cases = [
            (nm.with_tolerances(f64::NAN, 1e-9), [1.0, 2.0], [0.5, 0.5]),
            (nm.with_tolerances(1e-12, f64::NAN), [1.0, 2.0], [0.5, 0.5]),
            (nm.with_tolerances(-1e-12, 1e-9), [1.0, 2.0], [0.5, 0.5]),
            (nm.with_tolerances(1e-12, -1e-9), [1.0, 2.0], [0.5, 0.5]),
            (nm.with_max_evaluations(0), [1.0, 2.0], [0.5, 0.5]),
            (nm, [1.0, f64::NAN], [0.5, 0.5]),
            (nm, [1.0, 2.0], [0.5, 0.0]),
            (nm, [1.0, 2.0], [f64::INFINITY, 0.5]),
        ];
        let names = ["NelderMead::f_tol", "NelderMead::x_tol", "NelderMead::f_tol", "NelderMead::x_tol"];
        let names = names.into_iter().chain(["NelderMead::max_evaluations", "coordinate 1 of the start is NaN"]);
        let names = names.chain(["the step of coordinate 1 is 0", "the step of coordinate 0 is inf"]);
        for ((cfg, x0, step), name) in cases.into_iter().zip(names) {
            let mut calls = 0;
            let r = cfg.minimize(
                |p: &[f64; 2]| {
                    calls += 1;
                    (p[0] - 1.0).powi(2) + (p[1] - 3.0).powi(2)
                },
                x0,
                step,
            );
            assert_eq!(calls, 0, "{cfg:?} from {x0:?} by {step:?}");
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains(name)), "{name}: {r:?}");
            if x0[1].is_finite() && step == [0.5, 0.5] {
                // The boxed search refuses the same configurations, by the same check.
                let r = cfg.minimize_boxed(|p: &[f64; 2]| p[0] + p[1], x0, [0.0; 2], [4.0; 2]);
                assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains(name)), "{name}: {r:?}");
            }
        }
        let r = nm.minimize_boxed(|p: &[f64; 1]| p[0], [f64::NAN], [0.0], [1.0]);
        assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("coordinate 0 of the start")), "{r:?}");
    }

    #[test]
    fn the_evaluation_limit_is_respected() {
        let cfg = NelderMead::default().with_max_evaluations(40);
        let m = cfg
            .minimize(
                |p: &[f64; 2]| (1.0 - p[0]).powi(2) + 100.0 * (p[1] - p[0] * p[0]).powi(2),
                [-1.2, 1.0],
                [0.5, 0.5],
            )
            .unwrap();
        assert!(!m.converged());
        assert_eq!(m.termination, OptimizerStop::MaxEvaluations);
        // The last iteration may finish its contraction and shrink: at most P + 2 more.
        assert!(m.evaluations <= 40 + 2 + 2, "{}", m.evaluations);
    }
}
