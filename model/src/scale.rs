//! A mechanism of extreme size: where its closed forms leave the range of `f64`, its position
//! solved again by Newton over the whole system, as the compiled mechanism's step does.
//!
//! A closed form works with squares and products of lengths: for lengths about `s`, values
//! about `s²` (a dyad's rescaled coefficients about `s⁴`), which overflow or become subnormal
//! beyond about `1e±150`, and the closed form fails (a non-finite value, a limit position
//! rounded away) where the mechanism is fine. The compiled mechanism's checked step then solves
//! the position again by Newton over the whole system in dimensionless unknowns
//! (`kinloop::__gen::rescue`, the runtime's `extreme_scale`), and the analogs at it; the model
//! does the same here, after a failed step only, with the runtime's own size test and
//! whole-system solve (`outside_closed_form_sizes`, `whole_position`), so that both reach the
//! same position to the bit.

use crate::at::Jacobian;
use crate::model::{Model, StepError};
use kinloop_runtime::generated::{BlockEval, SolveReport, outside_closed_form_sizes, whole_position};
use kinloop_runtime::{NewtonConfig, QuantityKind};

impl Model {
    /// The answer to a step at `x` from `guess` that failed with `error`: for a mechanism
    /// outside the closed forms' sizes, its position solved by Newton over the whole system (of
    /// at most 16 unknowns, the dense sizes) and the analogs and outputs at it, in the state;
    /// `error` otherwise, and where that fails too. Only after a failure: a step of ordinary
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
        if !matches!(error, StepError::Block { .. } | StepError::NonFinite)
            || !guess.iter().chain(x).all(|v| v.is_finite())
        {
            return Err(error);
        }
        let mut jac = Jacobian::default();
        if self.jacobian(x, guess, &mut jac).is_err() || !outside_closed_form_sizes(&jac.scale) {
            return Err(error);
        }
        macro_rules! whole {
            ($($n:literal)*) => {
                match self.unknowns().len() {
                    $($n => self.solve_whole::<$n>(x, guess, cfg, &jac),)*
                    _ => None,
                }
            };
        }
        let Some((q, report)) = whole!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16) else {
            return Err(error);
        };
        if self.kinematics_at(x, &q, cfg).is_err() {
            return Err(error);
        }
        self.set_report(report);
        Ok(())
    }

    /// Newton over the whole system of `N` unknowns from `guess`, whose Jacobian is `jac`: the
    /// runtime's own (`whole_position`, the compiled step's), the residuals and Jacobian
    /// evaluated by the model. The position and the solve's report, or `None` where Newton
    /// fails.
    fn solve_whole<const N: usize>(
        &mut self,
        x: &[f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        jac: &Jacobian,
    ) -> Option<(Vec<f64>, SolveReport)> {
        if guess.len() != N || jac.f.len() != N || jac.scale.len() != N || jac.unit.len() != N {
            return None;
        }
        let turns: [bool; N] = std::array::from_fn(|u| self.unknown_kinds()[u] == QuantityKind::Angle);
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
        let (q, report) = whole_position(&guess, scale, unit, turns, cfg, eval)?;
        Some((q.to_vec(), report))
    }
}
