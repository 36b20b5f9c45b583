//! A mechanism of extreme size: where its closed forms leave the range of `f64`, its position
//! solved again by Newton over the whole system, as the compiled mechanism's step does.
//!
//! A closed form works with squares and products of lengths: for lengths about `s`, values
//! about `s²` (a dyad's rescaled coefficients about `s⁴`), which overflow or become subnormal
//! beyond about `1e±150`, and the closed form fails (a non-finite value, a limit position
//! rounded away) where the mechanism is fine. The compiled mechanism's checked step then solves
//! the position again by Newton over the whole system in dimensionless unknowns
//! (`kinloop::__gen::rescue`, the runtime's `extreme_scale`), and the analogs at it; the model
//! does the same here, after a failed step only, with the runtime's own test and solve
//! (`to_rescue`: beyond the closed forms' sizes, or an overflow at any size; `whole_position`:
//! the blocks in turn, as the compiled mechanism's), so that both reach the same position to the
//! bit. Where that solve fails too, its failure is the step's, made the failure of the block
//! holding the equation it names (`in_block`) as the compiled mechanism's is, so that both
//! explain it alike: the error of the same mechanism at size 1 (no assembly where a crank cannot
//! close its loop), not the one the closed forms' squares out of range made of it.

use crate::at::Jacobian;
use crate::blocks::StepFailure;
use crate::model::{Model, StepError};
use kinloop_runtime::generated::{
    AtLimit, BlockEval, BlockFailure, OwnJacobian, SolveReport, closes_in_own_magnitudes, in_block,
    singular_in_own_magnitudes, solve_blocks, to_rescue, turns_culprit, vanished_row, whole_position,
};
use kinloop_runtime::{NewtonConfig, QuantityKind};

impl Model {
    /// The answer to a step at `x` from `guess` that failed with `error`: for a mechanism
    /// outside the closed forms' sizes, its position solved by Newton over the whole system (of
    /// at most 16 unknowns, the dense sizes) and the analogs and outputs at it, in the state;
    /// where Newton fails, its failure in the block holding the equation it names, and where
    /// the analogs fail, theirs; `error` otherwise. Only after a failure: a step of ordinary
    /// size pays nothing.
    #[cold]
    #[inline(never)]
    pub(crate) fn rescue(
        &mut self,
        x: &[f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        error: StepError,
    ) -> Result<(), StepError> {
        let (q, report) = self.solve_rescued(x, guess, cfg, AtLimit::Singular, error)?;
        self.kinematics_at(x, &q, cfg)?;
        self.set_report(report);
        Ok(())
    }

    /// [`Model::rescue`] of a solve of the positions alone (`Model::positions`, the compiled
    /// `position_flat`'s `rescue_position`): the position Newton over the whole system reaches
    /// and its report, with no analogs (at a limit position too, as a closed form gives its
    /// double root: `AtLimit::Position`); where Newton fails, its failure in the block holding
    /// the equation it names; `error` otherwise.
    #[cold]
    #[inline(never)]
    pub(crate) fn rescue_position(
        &mut self,
        x: &[f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        error: StepError,
    ) -> Result<(Vec<f64>, SolveReport), StepError> {
        self.solve_rescued(x, guess, cfg, AtLimit::Position, error)
    }

    /// The position of [`Model::rescue`] and [`Model::rescue_position`], `at_limit` what a limit
    /// position gives (see `whole_position`).
    fn solve_rescued(
        &mut self,
        x: &[f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        at_limit: AtLimit,
        error: StepError,
    ) -> Result<(Vec<f64>, SolveReport), StepError> {
        // A value given that is not finite explains the failure at any size (its error names
        // it), as the compiled mechanism's does; so does an angle guessed too many turns out.
        if !matches!(error, StepError::Block { .. } | StepError::NonFinite)
            || !guess.iter().chain(x).all(|v| v.is_finite())
            || !self.param_values().iter().all(|v| v.is_some_and(f64::is_finite))
            || self.too_many_turns(&error, guess, cfg)
        {
            return Err(error);
        }
        // Beyond the closed forms' sizes, or where one overflowed inside them, as the compiled
        // mechanism's rescue.
        let overflowed =
            matches!(error, StepError::Block { failure: StepFailure::Block(BlockFailure::Overflow { .. }), .. });
        let mut jac = Jacobian::default();
        if self.jacobian(x, guess, &mut jac).is_err() {
            return Err(error);
        }
        // A loop whose lengths are all zero explains the failure at every size, as the compiled
        // rescue finds it (`vanished_row`): the closed forms called it singular.
        if let Some(row) = vanished_row(&jac.scale, &jac.f, &jac.j) {
            return Err(self.whole_failure(BlockFailure::Vanished { row }));
        }
        if !to_rescue(&jac.scale, overflowed) {
            return Err(error);
        }
        macro_rules! whole {
            ($($n:literal)*) => {
                match self.unknowns().len() {
                    $($n => self.solve_whole::<$n>(x, guess, cfg, at_limit, &jac),)*
                    _ => None,
                }
            };
        }
        match whole!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16) {
            // Its loops closed in the position's own magnitudes, as the compiled rescue tests.
            Some(Ok(solved)) if self.closes(x, &solved.0, cfg) => match self.singular_at(x, &solved, cfg, at_limit) {
                // Singular in its own magnitudes, as the compiled rescue tests.
                Some(fail) => Err(self.whole_failure(fail)),
                None => Ok(solved),
            },
            Some(Ok(_)) => Err(error),
            Some(Err(fail)) => Err(self.whole_failure(fail)),
            // More unknowns than the dense sizes: not solved again.
            None => Err(error),
        }
    }

    /// Whether the position `q` at `x` closes its loops in its own magnitudes
    /// (`closes_in_own_magnitudes`, the compiled rescue's test).
    fn closes(&mut self, x: &[f64], q: &[f64], cfg: &NewtonConfig) -> bool {
        let mut own = Jacobian::default();
        self.jacobian(x, q, &mut own).is_ok() && closes_in_own_magnitudes(&own.f, &own.scale, cfg)
    }

    /// For a solve of the positions alone (`at_limit` a position), the first block singular at
    /// the position `solved` reached at `x`, in the position's own magnitudes
    /// (`singular_in_own_magnitudes`, the compiled rescue's test).
    fn singular_at(
        &mut self,
        x: &[f64],
        solved: &(Vec<f64>, SolveReport),
        cfg: &NewtonConfig,
        at_limit: AtLimit,
    ) -> Option<BlockFailure> {
        let (q, report) = solved;
        if at_limit != AtLimit::Position {
            return None;
        }
        let blocks = solve_blocks(self.block_rows_cols.iter().cloned(), &self.closed_form_angles);
        let own = |q: &[f64]| {
            let mut at = Jacobian::default();
            self.jacobian(x, q, &mut at).ok()?;
            Some(OwnJacobian { j: at.j, scale: at.scale, unit: at.unit })
        };
        singular_in_own_magnitudes(q, own, &blocks, report.residual, report.iterations, cfg)
    }

    /// Whether the failure `error` from `guess` is an angle's guessed too many turns out, as its
    /// error says (`turns_culprit`, the compiled mechanism's test): the compiled rescue lets
    /// that error stand.
    fn too_many_turns(&self, error: &StepError, guess: &[f64], cfg: &NewtonConfig) -> bool {
        let StepError::Block { block, failure: StepFailure::Block(f) } = *error else {
            return false;
        };
        let unknowns = self.block_rows_cols.get(block).map_or(&[][..], |(_, cols)| &cols[..]);
        turns_culprit(unknowns.iter().copied(), self.unknown_kinds(), f, guess, cfg).is_some()
    }

    /// The failure `fail` of Newton over the whole system (its row an index into the
    /// equations) as the failure of the block holding that equation, with its row there: the
    /// compiled mechanism's `whole_failure`, by the blocks' equations.
    fn whole_failure(&self, fail: BlockFailure) -> StepError {
        let (block, fail) = in_block(fail, |row| {
            self.block_rows_cols
                .iter()
                .enumerate()
                .find_map(|(b, (rows, _))| Some((b, rows.iter().position(|&r| r == row)?)))
        });
        StepError::Block { block, failure: StepFailure::Block(fail) }
    }

    /// Newton over the whole system of `N` unknowns from `guess`, whose Jacobian is `jac`: the
    /// runtime's own (`whole_position`, the compiled step's, with what a limit position gives,
    /// `at_limit`), the residuals and Jacobian evaluated by the model. The position and the
    /// solve's report, or Newton's failure; `None` where the sizes are not `N` (not reached).
    fn solve_whole<const N: usize>(
        &mut self,
        x: &[f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        at_limit: AtLimit,
        jac: &Jacobian,
    ) -> Option<Result<(Vec<f64>, SolveReport), BlockFailure>> {
        if guess.len() != N || jac.f.len() != N || jac.scale.len() != N || jac.unit.len() != N {
            return None;
        }
        let turns: [bool; N] = std::array::from_fn(|u| self.unknown_kinds()[u] == QuantityKind::Angle);
        // The blocks in solve order, the closed forms' assembly modes kept, as the compiled
        // rescue's.
        let blocks = solve_blocks(self.block_rows_cols.iter().cloned(), &self.closed_form_angles);
        let mut at = Jacobian::default();
        let eval = |q: &[f64; N], ev: &mut BlockEval<N, 0>| {
            // The sizes were checked: not reached. NaN where it were, which Newton refuses.
            if self.jacobian(x, q, &mut at).is_err() {
                ev.f = [f64::NAN; N];
                return;
            }
            ev.f = std::array::from_fn(|e| at.f[e]);
            ev.j = std::array::from_fn(|e| std::array::from_fn(|u| at.j[e * N + u]));
        };
        let guess: [f64; N] = std::array::from_fn(|u| guess[u]);
        let (scale, unit) = (std::array::from_fn(|e| jac.scale[e]), std::array::from_fn(|u| jac.unit[u]));
        Some(
            whole_position(&guess, scale, unit, turns, cfg, at_limit, &blocks, eval)
                .map(|(q, report)| (q.to_vec(), report)),
        )
    }
}
