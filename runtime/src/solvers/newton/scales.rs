//! What a block's solve evaluates and judges in: the evaluation of a block ([`BlockEval`]), and
//! the magnitudes its tests are made in ([`Magnitudes`]: the rows' magnitudes and the unknowns'
//! units), made once for the solve or from each evaluation ([`MagnitudesOf`]).

use crate::solvers::jacobian::BlockJacobian;
use crate::solvers::lu::{RowScales, all_positive_finite};

/// One evaluation of a block: residuals, Jacobian rows, and intermediate values the generated
/// code keeps for later stages (so they are not recomputed after convergence).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct BlockEval<const N: usize, const K: usize, J = [[f64; N]; N]> {
    pub f: [f64; N],
    /// The Jacobian: dense rows, or a sparse block's non-zeros (see [`BlockJacobian`]).
    pub j: J,
    pub keep: [f64; K],
}

/// The magnitudes a block's tests judge it in. The generated code makes them once per solve
/// when they do not depend on the block's unknowns (every loop of links of given lengths), and
/// from each evaluation otherwise (a slider coordinate's magnitude is its own).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Magnitudes<const N: usize> {
    /// The row equilibration by the magnitude of each row: a structural bound of the
    /// equation's terms (for a loop projection, the sum of its link lengths), in the equation's
    /// unit, generated for every equation. Residual `i` is judged relative to it. Where one is
    /// not positive and finite (`degenerate`: a hand-written block that has none, or a
    /// degenerate mechanism whose terms all vanish) the row sums `sum_j |J_ij|` of each
    /// evaluation replace the invalid ones, which is right for angle unknowns only.
    pub(super) rows: RowScales<N>,
    /// The unit of each unknown: one radian for an angle, the magnitude of the rows it appears
    /// in per unit of its Jacobian entry otherwise (a slider coordinate: its loop's lengths). A
    /// step `dz_j` is judged relative to `max(|z_j|, unit_j)`, and the Newton factorisations'
    /// column `j` is multiplied by it where their pivots are measured; a value that is not
    /// positive and finite counts as `1` (replaced here).
    pub(super) unit: [f64; N],
    /// The unknowns whose equations repeat every turn (angles that enter the block through
    /// sines and cosines of whole multiples of themselves): an iteration that carried one more
    /// than half a turn from its guess returns it on the guess's turn, as a closed form does.
    pub(super) turns: [bool; N],
}

impl<const N: usize> Magnitudes<N> {
    /// The row magnitudes `scale` and the units `unit` of the unknowns, checked once.
    #[inline(always)]
    pub fn new(scale: [f64; N], unit: [f64; N]) -> Self {
        Magnitudes { rows: RowScales::new(scale), unit: units(&unit), turns: [false; N] }
    }

    /// These magnitudes, with `turns` marking the unknowns whose equations repeat every turn
    /// (see [`Magnitudes::turns`]).
    #[inline(always)]
    pub fn with_turns(mut self, turns: [bool; N]) -> Self {
        self.turns = turns;
        self
    }

    /// The units of the unknowns the tests use (see [`Magnitudes::unit`]: an invalid one
    /// replaced by `1`), for a caller that checks a solve's steps in the solver's own units.
    #[inline(always)]
    pub fn unit(&self) -> &[f64; N] {
        &self.unit
    }
}

/// Where a block's magnitudes come from: made once for the solve ([`Magnitudes`] itself), or
/// made from each evaluation (a closure).
#[doc(hidden)]
pub trait MagnitudesOf<const N: usize, const K: usize, J> {
    /// The magnitudes of every evaluation, when they are the same for all.
    fn fixed(&self) -> Option<&Magnitudes<N>>;
    /// The magnitudes at the evaluation `ev`.
    fn of(&self, ev: &BlockEval<N, K, J>) -> Magnitudes<N>;
}

impl<const N: usize, const K: usize, J> MagnitudesOf<N, K, J> for Magnitudes<N> {
    #[inline(always)]
    fn fixed(&self) -> Option<&Magnitudes<N>> {
        Some(self)
    }
    #[inline(always)]
    fn of(&self, _ev: &BlockEval<N, K, J>) -> Magnitudes<N> {
        *self
    }
}

impl<const N: usize, const K: usize, J, F: Fn(&BlockEval<N, K, J>) -> Magnitudes<N>> MagnitudesOf<N, K, J> for F {
    #[inline(always)]
    fn fixed(&self) -> Option<&Magnitudes<N>> {
        None
    }
    #[inline(always)]
    fn of(&self, ev: &BlockEval<N, K, J>) -> Magnitudes<N> {
        self(ev)
    }
}

/// The magnitudes `$mags` gives at the evaluation `$ev`: those made once, or made into
/// `$current` (the caller's slot, left uninitialised for fixed magnitudes: nothing is copied).
macro_rules! magnitudes_at {
    ($mags:expr, $ev:expr, $current:ident) => {
        match $mags.fixed() {
            Some(m) => m,
            None => {
                $current = $mags.of($ev);
                &$current
            }
        }
    };
}
pub(super) use magnitudes_at;

/// The row equilibration of the magnitudes `$m` at the evaluation `$ev`: `$m`'s own when its
/// scales are all valid (one branch for the set), otherwise made row by row into `$fallback`
/// (the caller's slot, left uninitialised on the common path).
macro_rules! rows_at {
    ($m:expr, $ev:expr, $fallback:ident) => {
        if $m.rows.degenerate {
            $fallback = fallback_rows(&$m.rows.s, $ev);
            &$fallback
        } else {
            &$m.rows
        }
    };
}
pub(super) use rows_at;

/// `rows_at!` where a generated magnitude is missing or degenerate: the row sum replaces it.
#[cold]
#[inline(never)]
pub(super) fn fallback_rows<const N: usize, const K: usize, J: BlockJacobian<N>>(
    scale: &[f64; N],
    ev: &BlockEval<N, K, J>,
) -> RowScales<N> {
    let mut s = [0.0; N];
    for r in 0..N {
        let given = scale[r];
        s[r] = if given > 0.0 && given < f64::INFINITY { given } else { ev.j.row_abs_sum(r) };
    }
    RowScales::new(s)
}

/// The units of the unknowns (see [`Magnitudes::unit`]): the generated ones when they are all
/// valid (one branch for the set), otherwise `1` for each invalid one.
#[inline(always)]
pub(super) fn units<const N: usize>(unit: &[f64; N]) -> [f64; N] {
    if all_positive_finite(unit) { *unit } else { fallback_units(unit) }
}

/// [`units`] with an invalid unit.
#[cold]
#[inline(never)]
fn fallback_units<const N: usize>(unit: &[f64; N]) -> [f64; N] {
    unit.map(|u| if u > 0.0 && u < f64::INFINITY { u } else { 1.0 })
}

#[cfg(test)]
mod tests {
    use super::super::newton;
    use super::super::test_blocks::{circle, in_place, solve, varying};
    use super::*;
    use crate::solvers::newton::NewtonConfig;

    /// Magnitudes made once for the solve (as the generated code makes those free of the
    /// unknowns) and the same magnitudes read from every evaluation give the same solve, bit
    /// for bit, and so does an invalid scale replaced by the row sums of each evaluation.
    #[test]
    fn magnitudes_made_once_are_those_of_every_evaluation() {
        for scale in [[3.0, 0.25], [0.0, 2.0], [f64::NAN, f64::INFINITY]] {
            let eval = |z: &[f64; 2]| {
                let ev = circle(z);
                varying::<2, 4>(ev.f, ev.j, scale, [1.0, 0.0])
            };
            let cfg = NewtonConfig::default();
            for guess in [[1.0, 1.0], [1.5, 0.5], [1.03, 1.72]] {
                let (each, ev_each) = solve(guess, &cfg, eval).unwrap();
                let once = Magnitudes::new(scale, [1.0, 0.0]);
                let mut ev_once = eval(&guess);
                let s = newton(guess, &mut ev_once, &cfg, in_place(eval), &once).unwrap();
                assert_eq!(s.z.map(f64::to_bits), each.z.map(f64::to_bits), "{scale:?} {guess:?}");
                assert_eq!((s.iterations, s.evaluations), (each.iterations, each.evaluations));
                assert_eq!(
                    s.residual.to_bits(),
                    each.residual.to_bits(),
                    "{scale:?} {guess:?} {} {}",
                    s.residual,
                    each.residual
                );
                assert_eq!(ev_once.f, ev_each.f);
            }
        }
    }
}
