//! A mechanism of extreme size: where its closed forms leave the range of `f64`, its position
//! solved again by Newton over the whole system, as the compiled mechanism's step does.
//!
//! A closed form works with squares and products of lengths: for lengths about `s`, values
//! about `s²` (a dyad's rescaled coefficients about `s⁴`), which overflow or become subnormal
//! beyond about `1e±150`, and the closed form fails (a non-finite value, a limit position
//! rounded away) where the mechanism is fine. The compiled mechanism's checked step then solves
//! the position again by Newton over the whole system in dimensionless unknowns
//! (`kinloop::__gen::rescue`, the runtime's `extreme_scale`), and the analogs at it; the model
//! does the same here, with the runtime's Newton and magnitudes, after a failed step only.

use crate::at::Jacobian;
use crate::model::{Model, StepError};
use kinloop_runtime::generated::{BlockEval, Magnitudes, SolveReport, newton};
use kinloop_runtime::{NewtonConfig, QuantityKind};

/// `2^480`, exact: every closed form computes exactly for equation magnitudes from `2^-480` to
/// `2^480` (about `1e±144`; the runtime's `CLOSED_FORM_SIZES`).
const TWO_480: f64 = (1u128 << 120) as f64 * (1u128 << 120) as f64 * (1u128 << 120) as f64 * (1u128 << 120) as f64;

/// Whether equation magnitudes `scale` (the finite ones) put the mechanism outside the sizes at
/// which the closed forms compute exactly: its largest beyond either end.
fn outside_closed_form_sizes(scale: &[f64]) -> bool {
    let size = scale.iter().fold(0.0f64, |s, v| if v.is_finite() { s.max(v.abs()) } else { s });
    size > 0.0 && !(1.0 / TWO_480..=TWO_480).contains(&size)
}

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

    /// Newton over the whole system of `N` unknowns from `guess`, whose Jacobian is `jac`, in
    /// dimensionless unknowns `z = q / unit` (radians for an angle, fractions of its loop's size
    /// for a length): the columns are then of one magnitude, as a generated Newton block has
    /// them. The position and the solve's report, or `None` where Newton fails.
    fn solve_whole<const N: usize>(
        &mut self,
        x: &[f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        jac: &Jacobian,
    ) -> Option<(Vec<f64>, SolveReport)> {
        if jac.f.len() != N || jac.scale.len() != N || jac.unit.len() != N {
            return None;
        }
        let unit: [f64; N] = std::array::from_fn(|u| {
            let v = jac.unit[u];
            if v > 0.0 && v.is_finite() { v } else { 1.0 }
        });
        let turns: [bool; N] = std::array::from_fn(|u| self.unknown_kinds()[u] == QuantityKind::Angle);
        let mags = Magnitudes::new(std::array::from_fn(|e| jac.scale[e]), [1.0; N]).with_turns(turns);
        let q_of = move |z: &[f64; N]| -> [f64; N] { std::array::from_fn(|u| z[u] * unit[u]) };
        let mut at = Jacobian::default();
        let mut eval = |z: &[f64; N], ev: &mut BlockEval<N, 0>| {
            // The sizes were checked: not reached. NaN where it were, which Newton refuses.
            if self.jacobian(x, &q_of(z), &mut at).is_err() {
                ev.f = [f64::NAN; N];
                return;
            }
            ev.f = std::array::from_fn(|e| at.f[e]);
            ev.j = std::array::from_fn(|e| std::array::from_fn(|u| at.j[e * N + u] * unit[u]));
        };
        let z0: [f64; N] = std::array::from_fn(|u| guess[u] / unit[u]);
        let mut ev: BlockEval<N, 0> = BlockEval { f: [0.0; N], j: [[0.0; N]; N], keep: [] };
        eval(&z0, &mut ev);
        let solved = newton(z0, &mut ev, cfg, eval, &mags).ok()?;
        let mut report = SolveReport::direct();
        report.absorb(&solved);
        Some((q_of(&solved.z).to_vec(), report))
    }
}
