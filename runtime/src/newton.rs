//! Damped Newton's method for one square block, with diagnostics.
//!
//! The configuration ([`NewtonConfig`]) is separate from the problem (the block's generated
//! evaluation closure) and the outcome carries its diagnostics ([`SolveReport`]): iterations,
//! evaluations, final residual and why it stopped.

use crate::lu::{Lu, max_abs};

/// Tolerances and limits of the Newton solver.
///
/// ```
/// use kinloop_runtime::NewtonConfig;
/// let cfg = NewtonConfig::default().with_residual_tol(1e-10).with_max_iterations(20);
/// assert_eq!(cfg.max_iterations, 20);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonConfig {
    /// Converged when the largest residual magnitude `max |f|` is at most this (default `1e-12`).
    pub residual_tol: f64,
    /// Also converged when a full Newton step is at most `step_tol * (1 + max |q|)` (default
    /// `1e-13`): the residual is then at the rounding floor of the problem's scale.
    pub step_tol: f64,
    /// Iteration cap per block (default `50`).
    pub max_iterations: u32,
    /// A block whose row-equilibrated pivot ratio falls below this is singular (default `1e-10`).
    pub singular_tol: f64,
    /// Smallest damping factor of the backtracking line search (default `2^-12`).
    pub min_damping: f64,
}

impl Default for NewtonConfig {
    fn default() -> Self {
        NewtonConfig {
            residual_tol: 1e-12,
            step_tol: 1e-13,
            max_iterations: 50,
            singular_tol: 1e-10,
            min_damping: 1.0 / 4096.0,
        }
    }
}

impl NewtonConfig {
    /// Sets [`NewtonConfig::residual_tol`].
    pub fn with_residual_tol(mut self, tol: f64) -> Self {
        self.residual_tol = tol;
        self
    }
    /// Sets [`NewtonConfig::step_tol`].
    pub fn with_step_tol(mut self, tol: f64) -> Self {
        self.step_tol = tol;
        self
    }
    /// Sets [`NewtonConfig::max_iterations`].
    pub fn with_max_iterations(mut self, n: u32) -> Self {
        self.max_iterations = n;
        self
    }
    /// Sets [`NewtonConfig::singular_tol`].
    pub fn with_singular_tol(mut self, tol: f64) -> Self {
        self.singular_tol = tol;
        self
    }
}

/// Why a solve stopped successfully.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[non_exhaustive]
pub enum Termination {
    /// Every block was solved in closed form (linear blocks only).
    Direct,
    /// The residual fell below `residual_tol`.
    ResidualTolerance,
    /// The Newton step fell below `step_tol` (the residual is at its rounding floor).
    StepTolerance,
    /// The position was given by the caller, not solved (`kinematics_at`).
    Given,
}

/// Diagnostics of a position solve, summed over the blocks of the decomposition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveReport {
    /// Newton iterations over all blocks (0 when the guess already satisfied the equations).
    pub iterations: u32,
    /// Residual evaluations over all blocks (including line-search trials).
    pub evaluations: u32,
    /// Largest final residual magnitude over the iterated blocks.
    pub residual: f64,
    /// The weakest reason any block stopped (`StepTolerance` over `ResidualTolerance` over
    /// `Direct`).
    pub termination: Termination,
}

impl SolveReport {
    #[doc(hidden)]
    pub fn direct() -> Self {
        SolveReport { iterations: 0, evaluations: 0, residual: 0.0, termination: Termination::Direct }
    }

    #[doc(hidden)]
    pub fn given(residual: f64) -> Self {
        SolveReport { iterations: 0, evaluations: 1, residual, termination: Termination::Given }
    }

    #[doc(hidden)]
    #[inline]
    pub fn absorb<const N: usize, const K: usize>(&mut self, s: &Solved<N, K>) {
        self.iterations += s.iterations;
        self.evaluations += s.evaluations;
        self.residual = self.residual.max(s.residual);
        self.termination = self.termination.max(s.termination);
    }
}

/// One evaluation of a block: residuals, Jacobian rows, and intermediate values the generated
/// code keeps for later stages (so they are not recomputed after convergence).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct BlockEval<const N: usize, const K: usize> {
    pub f: [f64; N],
    pub j: [[f64; N]; N],
    pub keep: [f64; K],
}

/// A converged block.
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Solved<const N: usize, const K: usize> {
    pub z: [f64; N],
    /// The evaluation at `z` (its Jacobian is reused for the analogs).
    pub eval: BlockEval<N, K>,
    pub iterations: u32,
    pub evaluations: u32,
    pub residual: f64,
    pub termination: Termination,
}

impl<const N: usize, const K: usize> Solved<N, K> {
    /// The guess itself met the tolerance (residual `res`): no iteration.
    #[doc(hidden)]
    #[inline(always)]
    pub fn at_guess(z: [f64; N], eval: BlockEval<N, K>, res: f64) -> Self {
        Solved { z, eval, iterations: 0, evaluations: 1, residual: res, termination: Termination::ResidualTolerance }
    }
}

/// Why a block failed; the generated code adds the location and names.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BlockFailure {
    /// A residual or Jacobian entry is not finite; `row` is the block row.
    NonFinite {
        row: usize,
        iterations: u32,
    },
    NoConvergence {
        row: usize,
        iterations: u32,
        residual: f64,
    },
    /// The Jacobian is singular away from a root, or no step decreases the residual.
    NoAssembly {
        row: usize,
        iterations: u32,
        residual: f64,
    },
}

fn argmax_abs<const N: usize>(f: &[f64; N]) -> usize {
    let mut k = 0;
    for r in 1..N {
        if f[r].abs() > f[k].abs() || f[r].is_nan() {
            k = r;
        }
    }
    k
}

fn first_non_finite<const N: usize, const K: usize>(ev: &BlockEval<N, K>) -> Option<usize> {
    (0..N).find(|&r| !ev.f[r].is_finite() || ev.j[r].iter().any(|v| !v.is_finite()))
}

fn sum_sq<const N: usize>(f: &[f64; N]) -> f64 {
    f.iter().map(|v| v * v).sum()
}

/// Solves one block from the guess `z0`. In the common warm-started case this costs one
/// evaluation: the guess already satisfies the tolerance and no iteration is made. That check is
/// inlined into the generated code; the iteration itself is a separate function.
#[doc(hidden)]
#[inline(always)]
pub fn newton<const N: usize, const K: usize>(
    z0: [f64; N],
    cfg: &NewtonConfig,
    mut eval: impl FnMut(&[f64; N]) -> BlockEval<N, K>,
) -> Result<Solved<N, K>, BlockFailure> {
    let ev = eval(&z0);
    let res = max_abs(ev.f);
    // `max_abs` propagates NaN, which fails this test.
    if res <= cfg.residual_tol {
        return Ok(Solved::at_guess(z0, ev, res));
    }
    iterate(z0, ev, cfg, eval)
}

/// Newton iterations from `z0`, whose evaluation `ev0` did not meet the tolerance. The
/// generated code evaluates the guess inline and calls this only when it must iterate.
#[doc(hidden)]
#[inline(never)]
pub fn iterate<const N: usize, const K: usize>(
    z0: [f64; N],
    ev0: BlockEval<N, K>,
    cfg: &NewtonConfig,
    mut eval: impl FnMut(&[f64; N]) -> BlockEval<N, K>,
) -> Result<Solved<N, K>, BlockFailure> {
    let mut z = z0;
    let mut ev = ev0;
    let mut evaluations = 1u32;
    let mut iterations = 0u32;
    loop {
        let res = max_abs(ev.f);
        // `max_abs` propagates NaN, which fails this test.
        if res <= cfg.residual_tol {
            return Ok(Solved {
                z,
                eval: ev,
                iterations,
                evaluations,
                residual: res,
                termination: Termination::ResidualTolerance,
            });
        }
        if let Some(row) = first_non_finite(&ev) {
            return Err(BlockFailure::NonFinite { row, iterations });
        }
        if iterations >= cfg.max_iterations {
            return Err(BlockFailure::NoConvergence { row: argmax_abs(&ev.f), iterations, residual: res });
        }
        let mut scale = [0.0; N];
        for (r, s) in scale.iter_mut().enumerate() {
            *s = max_abs(ev.j[r]);
        }
        let lu = Lu::factor(&ev.j, scale);
        if lu.pivot_ratio() <= cfg.singular_tol * 1e-3 {
            return Err(BlockFailure::NoAssembly { row: argmax_abs(&ev.f), iterations, residual: res });
        }
        let mut neg_f = ev.f;
        for v in &mut neg_f {
            *v = -*v;
        }
        let dz = lu.solve(neg_f);
        let step = max_abs(dz);
        if !step.is_finite() {
            return Err(BlockFailure::NoAssembly { row: argmax_abs(&ev.f), iterations, residual: res });
        }
        if step <= cfg.step_tol * (1.0 + max_abs(z)) {
            return Ok(Solved {
                z,
                eval: ev,
                iterations,
                evaluations,
                residual: res,
                termination: Termination::StepTolerance,
            });
        }
        // Backtracking on the squared residual norm (Armijo with c = 1e-4).
        let phi0 = sum_sq(&ev.f);
        let mut t = 1.0f64;
        loop {
            let mut trial = z;
            for r in 0..N {
                trial[r] += t * dz[r];
            }
            let ev_t = eval(&trial);
            evaluations += 1;
            let phi = sum_sq(&ev_t.f);
            if phi <= (1.0 - 2e-4 * t) * phi0 {
                z = trial;
                ev = ev_t;
                break;
            }
            t *= 0.5;
            if t < cfg.min_damping {
                // No step along the Newton direction reduces the residual: a stationary point of
                // |f|^2 that is not a root.
                return Err(BlockFailure::NoAssembly {
                    row: argmax_abs(&ev.f),
                    iterations: iterations + 1,
                    residual: res,
                });
            }
        }
        iterations += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(z: &[f64; 2]) -> BlockEval<2, 0> {
        // x^2 + y^2 = 4, y = x^3  (root near (1.26, 1.97)... solved numerically)
        let [x, y] = *z;
        BlockEval { f: [x * x + y * y - 4.0, y - x * x * x], j: [[2.0 * x, 2.0 * y], [-3.0 * x * x, 1.0]], keep: [] }
    }

    #[test]
    fn converges_quadratically_and_reports() {
        let s = newton([1.0, 1.0], &NewtonConfig::default(), circle).unwrap();
        assert!(s.residual <= 1e-12);
        assert!(s.iterations > 0 && s.iterations < 10, "{}", s.iterations);
        let [x, y] = s.z;
        assert!((x * x + y * y - 4.0).abs() < 1e-12 && (y - x.powi(3)).abs() < 1e-12);
        // Warm start: no iteration at all.
        let again = newton(s.z, &NewtonConfig::default(), circle).unwrap();
        assert_eq!(again.iterations, 0);
        assert_eq!(again.evaluations, 1);
    }

    #[test]
    fn impossible_system_is_no_assembly_not_a_hang() {
        // x^2 + 1 = 0 has no real root: Newton heads for the minimum at x = 0 where J = 0.
        let f = |z: &[f64; 1]| BlockEval { f: [z[0] * z[0] + 1.0], j: [[2.0 * z[0]]], keep: [] };
        let e = newton([0.7], &NewtonConfig::default(), f).unwrap_err();
        assert!(matches!(e, BlockFailure::NoAssembly { .. } | BlockFailure::NoConvergence { .. }), "{e:?}");
    }

    #[test]
    fn nan_is_reported() {
        let f = |z: &[f64; 1]| BlockEval { f: [z[0].sqrt() - 1.0], j: [[0.5 / z[0].sqrt()]], keep: [] };
        let e = newton([-1.0], &NewtonConfig::default(), f).unwrap_err();
        assert!(matches!(e, BlockFailure::NonFinite { row: 0, .. }));
    }

    #[test]
    fn iteration_cap_is_respected() {
        let cfg = NewtonConfig::default().with_max_iterations(1);
        let e = newton([10.0, 10.0], &cfg, circle).unwrap_err();
        assert!(matches!(e, BlockFailure::NoConvergence { iterations: 1, .. }), "{e:?}");
    }
}
