//! Why an iteration failed: a residual or Jacobian that is not finite (or terms too large for
//! `f64`), a root reached only linearly or where no step decreases the residual (singular), a
//! stall away from every root (no assembly), or the iteration cap.

use super::config::NewtonConfig;
use super::report::BlockFailure;
use super::scales::{BlockEval, Magnitudes, overflowed};
use super::state::Iter;
use crate::solvers::jacobian::BlockJacobian;

/// A scaled residual above this at a stall means the loops do not close there (not merely a
/// root reached slowly): far above any rounding floor, far below the residual of a mechanism
/// that visibly cannot assemble.
pub(super) const STALL_RESIDUAL: f64 = 1e-8;

pub(super) fn argmax_scaled<const N: usize>(f: &[f64; N], s: &[f64; N]) -> usize {
    let mut k = 0;
    let mut best = -1.0;
    for r in 0..N {
        let v = f[r].abs() / s[r];
        if v > best || v.is_nan() {
            k = r;
            best = if v.is_nan() { f64::INFINITY } else { v };
        }
    }
    k
}

/// Where a residual is not finite, the first row with a residual or Jacobian entry that is
/// not: one test for the residuals, and the search only when it fails. The Jacobian is tested
/// where the iteration stops ([`jacobian_non_finite`]): a non-finite entry on the way can at
/// worst spoil a step, which the descent test and the final checks catch.
#[inline(always)]
pub(super) fn residual_non_finite<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
) -> Option<usize> {
    let mut finite = true;
    for r in 0..N {
        finite &= ev.f[r].abs() < f64::INFINITY;
    }
    if finite { None } else { non_finite_row(ev) }
}

/// Where a Jacobian entry is not finite, the first row with a residual or Jacobian entry that
/// is not (one test for the matrix).
#[inline(always)]
pub(super) fn jacobian_non_finite<const N: usize, const K: usize, J: BlockJacobian<N>>(
    ev: &BlockEval<N, K, J>,
) -> Option<usize> {
    if ev.j.finite() { None } else { non_finite_row(ev) }
}

/// [`residual_non_finite`] and [`jacobian_non_finite`] where an entry is not finite.
#[cold]
#[inline(never)]
fn non_finite_row<const N: usize, const K: usize, J: BlockJacobian<N>>(ev: &BlockEval<N, K, J>) -> Option<usize> {
    (0..N).find(|&r| !ev.f[r].is_finite() || !ev.j.row_finite(r))
}

/// The failure of a block whose row `row` holds a residual or Jacobian entry that is not finite
/// at the evaluation `ev` of `z`, after `iterations`, in that evaluation's magnitudes `m`: terms
/// too large for `f64` where its magnitude overflowed with them ([`BlockFailure::Overflow`], see
/// [`overflowed`]: squared lengths beyond about `1e154`, whose difference is `inf - inf`),
/// otherwise an expression outside its domain ([`BlockFailure::NonFinite`]). Out of line: it is
/// reached only where the residual or the Jacobian already failed its test.
#[cold]
#[inline(never)]
pub(super) fn non_finite<const N: usize, const K: usize, J: BlockJacobian<N>>(
    row: usize,
    iterations: u32,
    m: &Magnitudes<N>,
    ev: &BlockEval<N, K, J>,
    z: &[f64; N],
) -> BlockFailure {
    if overflowed(m.rows.s[row], row, ev, z) {
        BlockFailure::Overflow { row }
    } else {
        BlockFailure::NonFinite { row, iterations }
    }
}

impl<const N: usize, const K: usize, J: BlockJacobian<N>> Iter<'_, N, K, J> {
    /// The failure of a root reached with linear convergence.
    #[cold]
    #[inline(never)]
    pub(super) fn singular(&self, rho: f64, pivot: f64, s: &[f64; N], cfg: &NewtonConfig) -> BlockFailure {
        BlockFailure::Singular {
            row: argmax_scaled(&self.ev.f, s),
            iterations: self.iterations,
            residual: rho,
            pivot_ratio: if pivot.is_nan() { 0.0 } else { pivot },
            tolerance: cfg.singular_tol,
        }
    }

    /// The failure at the iteration cap: over the second half of the iterations the residual
    /// did not even halve (it crawls into a minimum that is not a root), or it still decreased.
    #[cold]
    #[inline(never)]
    pub(super) fn capped(&self, rho: f64, s: &[f64; N], cfg: &NewtonConfig) -> BlockFailure {
        if let Some(row) = jacobian_non_finite(self.ev) {
            return BlockFailure::NonFinite { row, iterations: self.iterations };
        }
        let row = argmax_scaled(&self.ev.f, s);
        let iterations = self.iterations;
        if cfg.max_iterations >= 8 && rho > STALL_RESIDUAL && rho > 0.5 * self.rho_mark {
            return BlockFailure::NoAssembly { row, iterations, evaluations: self.evaluations, residual: rho };
        }
        BlockFailure::NoConvergence { row, iterations, residual: rho }
    }

    /// Why no step decreases the residual: at a root the Jacobian is singular (a singular
    /// position); away from one the loops cannot close here.
    #[cold]
    #[inline(never)]
    pub(super) fn stalled(&self, rho: f64, pivot: f64, s: &[f64; N], cfg: &NewtonConfig) -> BlockFailure {
        if let Some(row) = jacobian_non_finite(self.ev) {
            return BlockFailure::NonFinite { row, iterations: self.iterations };
        }
        let row = argmax_scaled(&self.ev.f, s);
        let iterations = self.iterations;
        if rho <= STALL_RESIDUAL && pivot > cfg.singular_tol {
            // Near a root whose Jacobian is regular, no step decreases the residual: rounding
            // keeps it above the tolerance. Not a singular position.
            BlockFailure::NoConvergence { row, iterations, residual: rho }
        } else if rho <= STALL_RESIDUAL {
            let pivot_ratio = if pivot.is_nan() { 0.0 } else { pivot };
            BlockFailure::Singular { row, iterations, residual: rho, pivot_ratio, tolerance: cfg.singular_tol }
        } else {
            BlockFailure::NoAssembly { row, iterations, evaluations: self.evaluations, residual: rho }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::newton_keeping_lu;
    use super::super::test_blocks::{circle, in_place, mags, solve, varying};
    use crate::solvers::lu::Lu;
    use crate::solvers::newton::{BlockFailure, NewtonConfig};

    #[test]
    fn impossible_system_is_no_assembly_not_a_hang() {
        // x^2 + 1 = 0 has no real root: Newton heads for the minimum at x = 0 where J = 0.
        let f = |z: &[f64; 1]| varying::<1, 2>([z[0] * z[0] + 1.0], [[2.0 * z[0]]], [z[0] * z[0] + 1.0], [1.0]);
        let e = solve([0.7], &NewtonConfig::default(), f).unwrap_err();
        assert!(matches!(e, BlockFailure::NoAssembly { .. }), "{e:?}");
    }

    #[test]
    fn nan_is_reported() {
        let f = |z: &[f64; 1]| varying::<1, 2>([z[0].sqrt() - 1.0], [[0.5 / z[0].sqrt()]], [0.0], [1.0]);
        let e = solve([-1.0], &NewtonConfig::default(), f).unwrap_err();
        assert!(matches!(e, BlockFailure::NonFinite { row: 0, .. }));
    }

    /// A Jacobian that is not finite where the iteration stops is reported, although the
    /// residuals are finite: at a root (`x^(1/3)` at 0, where `d/dx` is infinite) and where no
    /// step can be taken (a NaN slope).
    #[test]
    fn a_jacobian_not_finite_where_it_stops_is_reported() {
        let cube_root = |z: &[f64; 2]| {
            varying::<2, 4>(
                [z[0].cbrt(), z[1] - 1.0],
                [[1.0 / (3.0 * z[0].cbrt().powi(2)), 0.0], [0.0, 1.0]],
                [1.0, 1.0],
                [1.0; 2],
            )
        };
        let e = solve([0.0, 2.0], &NewtonConfig::default(), cube_root).unwrap_err();
        assert!(matches!(e, BlockFailure::NonFinite { row: 0, .. }), "{e:?}");
        // The same where the final correction is made with the analogs' factorisation (which
        // vouches for a finite Jacobian only through a positive pivot ratio).
        let (mut ev, mut kept) = (cube_root(&[0.0, 2.0]), Lu::unfactored());
        let e = newton_keeping_lu([0.0, 2.0], &mut ev, &NewtonConfig::default(), in_place(cube_root), &mags, &mut kept);
        assert!(matches!(e, Err(BlockFailure::NonFinite { row: 0, .. })), "{e:?}");
        // A 3x3 block (the general factorisation, whose column magnitudes are not screened):
        // an infinite or NaN entry, anywhere, at a root the guess already meets.
        for (r, c, bad) in [(0, 0, f64::INFINITY), (2, 1, f64::NAN), (1, 2, f64::NEG_INFINITY), (2, 2, f64::NAN)] {
            let block = move |z: &[f64; 3]| {
                let mut j = [[2.0, 0.5, 0.0], [0.0, 3.0, 1.0], [1.0, 0.0, 4.0]];
                j[r][c] = bad;
                varying::<3, 6>([z[0] - 1.0, z[1] - 2.0, z[2] - 3.0], j, [1.0; 3], [1.0; 3])
            };
            let (mut ev, mut kept) = (block(&[1.0, 2.0, 3.0]), Lu::unfactored());
            let e = newton_keeping_lu(
                [1.0, 2.0, 3.0],
                &mut ev,
                &NewtonConfig::default(),
                in_place(block),
                &mags,
                &mut kept,
            );
            assert!(matches!(e, Err(BlockFailure::NonFinite { row, .. }) if row == r), "{r} {c}: {e:?}");
        }
        let nan_slope = |z: &[f64; 2]| {
            varying::<2, 4>([z[0] - 3.0, z[1] - 1.0], [[1.0, 0.0], [f64::NAN, 1.0]], [1.0, 1.0], [1.0; 2])
        };
        let e = solve([0.0, 0.0], &NewtonConfig::default(), nan_slope).unwrap_err();
        assert!(matches!(e, BlockFailure::NonFinite { row: 1, iterations: 0 }), "{e:?}");
    }

    #[test]
    fn iteration_cap_is_respected() {
        let cfg = NewtonConfig::default().with_max_iterations(1);
        let e = solve([10.0, 10.0], &cfg, circle).unwrap_err();
        assert!(matches!(e, BlockFailure::NoConvergence { iterations: 1, .. }), "{e:?}");
    }

    /// `x^2 = 0`: the Jacobian vanishes at the root, Newton halves the error each step. The
    /// root must come back as singular, not as an inaccurate success.
    #[test]
    fn singular_root_reached_linearly_is_singular() {
        let f = |z: &[f64; 1]| varying::<1, 2>([z[0] * z[0]], [[2.0 * z[0]]], [1.0], [1.0]);
        let e = solve([1.0], &NewtonConfig::default(), f).unwrap_err();
        assert!(matches!(e, BlockFailure::Singular { .. }), "{e:?}");
    }
}
