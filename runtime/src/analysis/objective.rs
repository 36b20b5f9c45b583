//! Objectives over a whole sweep with exact parameter gradients (for synthesis with
//! [`LevenbergMarquardt`](super::optimize::LevenbergMarquardt)).
//!
//! * [`Sampled::extremum_with_gradient`]: the maximum or minimum of a quantity over a sampled
//!   range, located as a root of its velocity analog, with the gradient of its value (by the envelope theorem,
//!   `d max / dp = d q / dp` at the extremum, since `dq/dx = 0` there) and of its location
//!   (`dx*/dp = -(d q' / dp) / q''`).
//! * [`Sampled::integral_with_gradient`]: the trapezoidal integral of a quantity over the
//!   samples and its exact gradient.

use crate::analysis::{Column, ColumnIndex, Extreme, Sampled};
use crate::error::Error;
use crate::kin::Sens;
use crate::mechanism::{Mechanism, Sensitivities};

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

impl<M, const N: usize, const NO: usize> Sampled<'_, M, N, NO, 1>
where
    M: Mechanism<N, 1, NO>,
{
    /// The maximum or minimum of the column `col` (`Name::COL.x_f`) over the sampled range
    /// (located as a root of its velocity analog, as [`Sampled::range`] does) with its parameter
    /// gradients, for a mechanism declared with `#[kinloop(sensitivities)]`. The sensitivities
    /// are solved with the sweep configuration's Newton settings.
    ///
    /// An extremum at an end of the range (where the analog does not vanish) is returned at the
    /// end with `x_grad = 0` and `grad = dq/dp` there.
    ///
    /// ```ignore
    /// let turn = m.sampled(0.0, TAU, 73, &m.guess(0.0))?;
    /// let top = turn.extremum_with_gradient(RhombicDrive::COL.x_f, Extreme::Max)?;
    /// ```
    pub fn extremum_with_gradient<const NP: usize>(&self, col: Column<M>, which: Extreme) -> Result<Extremum<NP>, Error>
    where
        M: Sensitivities<N, 1, NO, NP>,
    {
        let global = self.range(col)?;
        let at = if which == Extreme::Max { global.max } else { global.min };
        let interior = global.extremes.iter().any(|e| e.at.x == at.x);
        let k = self.at(at.x)?;
        let (k, s) = self.mechanism().sensitivities_at_flat(&k.x, &k.q, &self.config().newton)?;
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

    /// The trapezoidal integral of the column `col` (`Name::COL.gap`) over the samples and its
    /// exact parameter gradient (the derivative of the same quadrature), for a mechanism declared
    /// with `#[kinloop(sensitivities)]`. For a periodic quantity sampled over a full period the
    /// trapezoidal rule is spectrally accurate.
    pub fn integral_with_gradient<const NP: usize>(&self, col: Column<M>) -> Result<(f64, [f64; NP]), Error>
    where
        M: Sensitivities<N, 1, NO, NP>,
    {
        let col = col.check::<N, 1, NO>()?;
        let (states, s) = (self.states(), self.path_values());
        let mut value = 0.0;
        let mut grad = [0.0; NP];
        for (i, k) in states.iter().enumerate() {
            // Trapezoid weights: half of each neighbouring interval.
            let left = if i > 0 { s[i] - s[i - 1] } else { 0.0 };
            let right = if i + 1 < states.len() { s[i + 1] - s[i] } else { 0.0 };
            let w = 0.5 * (left + right);
            let (k, sens) = self.mechanism().sensitivities_at_flat(&k.x, &k.q, &self.config().newton)?;
            let (g, _) = column_sens(&sens, col);
            value += w * col.jet(&k).value;
            for p in 0..NP {
                grad[p] += w * g[p];
            }
        }
        Ok((value, grad))
    }
}
