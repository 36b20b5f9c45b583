//! Objectives over a whole sweep with exact parameter gradients (for synthesis with
//! [`LevenbergMarquardt`](super::optimize::LevenbergMarquardt)).
//!
//! * [`extremum`]: the maximum or minimum of a quantity over an input range, located as a root
//!   of its velocity analog, with the gradient of its value (by the envelope theorem,
//!   `d max / dp = d q / dp` at the extremum, since `dq/dx = 0` there) and of its location
//!   (`dx*/dp = -(d q' / dp) / q''`).
//! * [`integral`]: the trapezoidal integral of a quantity over a sweep and its exact gradient.

use crate::analysis::{Column, ColumnIndex, Extreme, Sampled};
use crate::error::Error;
use crate::kin::{Kin, Sens};
use crate::mechanism::Sensitivities;
use crate::paths::sweep::{Sweep, SweepConfig};
use crate::solvers::newton::NewtonConfig;

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
fn column_sens<M, const N: usize, const NO: usize, const NP: usize>(
    s: &Sens<N, 1, NO, NP>,
    c: Column<M>,
) -> ([f64; NP], [f64; NP]) {
    match c.index() {
        // An input does not depend on the parameters.
        ColumnIndex::Input(_) => ([0.0; NP], [0.0; NP]),
        ColumnIndex::Unknown(u) => (s.q[u], s.dq[u][0]),
        ColumnIndex::Output(o) => (s.out[o], s.dout[o][0]),
    }
}

/// Finds the maximum or minimum of the column `col` (`Name::COL.x_f`) over `range` (a branch-safe
/// sweep of `samples` points from `guess`; the extremes are roots of the velocity analog located
/// by [`Sampled::range`](crate::analysis::Sampled::range)) and returns it with its parameter
/// gradients.
///
/// An extremum at an end of the range (where the analog does not vanish) is returned at the end
/// with `x_grad = 0` and `grad = dq/dp` there.
#[allow(clippy::too_many_arguments)] // the range as `from, to`, as every other call takes it
pub fn extremum<M, const N: usize, const NO: usize, const NP: usize>(
    m: &M,
    col: Column<M>,
    which: Extreme,
    from: f64,
    to: f64,
    samples: usize,
    guess: impl Into<[f64; N]>,
    cfg: &NewtonConfig,
) -> Result<Extremum<NP>, Error>
where
    M: Sensitivities<N, 1, NO, NP>,
{
    let sweep_cfg = SweepConfig { newton: *cfg, ..SweepConfig::default() };
    let sampled = Sampled::sweep_with(m, from, to, samples.max(3), guess, sweep_cfg)?;
    let global = sampled.range(col)?;
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

/// The trapezoidal integral of the column `col` (`Name::COL.gap`) over a sweep of `samples` points
/// from `from` to `to`, and its exact parameter gradient (the derivative of the same quadrature).
/// For a periodic quantity over a full period the trapezoidal rule is spectrally accurate.
pub fn integral<M, const N: usize, const NO: usize, const NP: usize>(
    m: &M,
    col: Column<M>,
    from: f64,
    to: f64,
    samples: usize,
    guess: impl Into<[f64; N]>,
    cfg: &NewtonConfig,
) -> Result<(f64, [f64; NP]), Error>
where
    M: Sensitivities<N, 1, NO, NP>,
{
    let col = col.check::<N, 1, NO>()?;
    let samples = samples.max(2);
    let h = (to - from) / (samples - 1) as f64;
    let mut value = 0.0;
    let mut grad = [0.0; NP];
    let mut sweep = Sweep::<M, Kin<N, 1, NO>, N, 1, NO>::new(m, [from], [to], samples, guess.into())?;
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
