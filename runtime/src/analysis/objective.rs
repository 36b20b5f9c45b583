//! Objectives over a whole sweep with exact parameter gradients (for synthesis with
//! [`LevenbergMarquardt`](super::optimize::LevenbergMarquardt)), written once over
//! [`SampledOf`] for any kernel with sensitivities at a kept state: a compiled mechanism's
//! [`Sampled`] (gradients as arrays) and a [`SensKernel`]'s, a run-time model's included
//! (gradients as vectors).
//!
//! * [`Sampled::extremum_with_gradient`]: the maximum or minimum of a quantity over a sampled
//!   range, located as a root of its velocity analog, with the gradient of its value (by the envelope theorem,
//!   `d max / dp = d q / dp` at the extremum, since `dq/dx = 0` there) and of its location
//!   (`dx*/dp = -(d q' / dp) / q''`); at a corner of the motion (a kink, where the analog jumps
//!   from one sign to the other) both follow the corner, where the branches on its two sides
//!   are equal.
//! * [`Sampled::integral_with_gradient`]: the trapezoidal integral of a quantity over the
//!   samples and its exact gradient.

use crate::analysis::column::{column_name, jet_of_input};
use crate::analysis::{Column, ColumnIndex, ColumnOf, Extreme, Sampled, SampledOf};
use crate::dims::{Dims, KinState};
use crate::error::Error;
use crate::kin::{Kin, Sens};
use crate::mechanism::kernel::{Kernel, KinOf, SensKernel, SensState};
use crate::mechanism::{Mechanism, Sensitivities};

/// A located extremum of a quantity over an input range, with parameter gradients `G`
/// (`[f64; NP]` for a compiled mechanism, [`Extremum`]; `Vec<f64>` for a [`SensKernel`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExtremumOf<G> {
    /// Input value at the extremum.
    pub x: f64,
    /// The extreme value.
    pub value: f64,
    /// `d value / d p_k` (envelope theorem; at a kink, along the corner).
    pub grad: G,
    /// `d x / d p_k`: how the extremum moves with the parameters.
    pub x_grad: G,
}

/// A located extremum of a compiled mechanism's quantity, with its `NP` parameter gradients.
pub type Extremum<const NP: usize> = ExtremumOf<[f64; NP]>;

/// (d value/dp_k, d first analog/dp_k) of a column, on a single-input state.
fn column_sens<S: SensState>(s: &S, c: ColumnIndex, k: usize) -> (f64, f64) {
    match c {
        // An input does not depend on the parameters.
        ColumnIndex::Input(_) => (0.0, 0.0),
        ColumnIndex::Unknown(u) => (s.q(u, k), s.dq(u, 0, k)),
        ColumnIndex::Output(o) => (s.out(o, k), s.dout(o, 0, k)),
    }
}

/// The objectives take one input: the extremum's location and the trapezoid's abscissa are it.
fn one_input<K: Kernel>(k: &K) -> Result<(), Error> {
    match k.dims().ni() {
        1 => Ok(()),
        ni => Err(Error::InvalidArgument(format!(
            "the objectives with gradients take a mechanism of one input; `{}` has {ni}",
            k.name()
        ))),
    }
}

/// The error for an extremum at a singular crossing the sweep passed (a change point): there
/// the column has a corner, not a root of its analog, and the crossing itself exists only for
/// parameters on a manifold (a four-bar's `a + d = b + c`), so that the extremum has no
/// gradient; and the Jacobian is singular there, so the sensitivities are not defined. (No
/// state is solved at the crossing: asked for one there, a sweep gives one a pivot band past
/// it, another point with another value, or none, `NearSingular`.)
fn at_crossing<K: Kernel>(k: &K, c: ColumnIndex, which: Extreme, x: f64) -> Error {
    let what = if which == Extreme::Max { "maximum" } else { "minimum" };
    Error::InvalidArgument(format!(
        "the {what} of `{}` lies at a singular crossing the sweep passed (`{}` = {x}), a corner of it: \
         it has no gradient in the parameters there",
        column_name(k, c),
        k.input_name(0)
    ))
}

/// The column on one side of a corner: its jet and its derivatives by every parameter.
struct Side {
    jet: crate::analysis::Jet,
    value_grad: Vec<f64>,
}

/// The gradients of an extremum at a corner where the branch `L` before it meets the branch
/// `R` after it (`left`, `right`: each one's analog `L_x` and parameter derivatives `L_p`).
/// The corner stays where the branches are equal, `L(x, p) = R(x, p)`; differentiating that
/// (implicit function theorem; `L_x != R_x` at a kink) moves it by
/// `dx/dp = -(L_p - R_p) / (L_x - R_x)`, and the value `L(x(p), p)` by
/// `L_p + L_x dx/dp = (L_x R_p - R_x L_p) / (L_x - R_x)`, the same from either branch. The
/// envelope theorem does not apply: the analog does not vanish there.
fn corner_gradients(left: &Side, right: &Side, grad: &mut [f64], x_grad: &mut [f64]) {
    let (lx, rx) = (left.jet.d1, right.jet.d1);
    for (p, (g, xg)) in grad.iter_mut().zip(x_grad.iter_mut()).enumerate() {
        let (lp, rp) = (left.value_grad[p], right.value_grad[p]);
        *xg = -(lp - rp) / (lx - rx);
        *g = (lx * rp - rx * lp) / (lx - rx);
    }
}

impl<K: Kernel> SampledOf<K> {
    /// The one implementation of the extremum with gradients: `sens_at(state, kin, sens)`
    /// writes the kinematics and sensitivities at a state's position into `kin` and `sens`;
    /// `grad` and `x_grad` (one value per parameter) receive the gradients. Returns `(x, value)`.
    fn extremum_by<S: SensState>(
        &self,
        c: ColumnIndex,
        which: Extreme,
        sens: &mut S,
        mut sens_at: impl FnMut(&KinOf<K>, &mut KinOf<K>, &mut S) -> Result<(), Error>,
        grad: &mut [f64],
        x_grad: &mut [f64],
    ) -> Result<(f64, f64), Error> {
        one_input(self.kernel())?;
        let global = self.range(c)?;
        let at = if which == Extreme::Max { global.max } else { global.min };
        if self.is_crossing(at.x) {
            return Err(at_crossing(self.kernel(), c, which, at.x));
        }
        // Anywhere but an end of the range the extremum moves with the parameters: a root of
        // the analog, or a corner of the motion. A corner that falls on a sample is no located
        // extreme (the sample itself, one side's value, is the largest candidate), and taken
        // for an end it kept one side's gradient and did not move (`x_grad = 0`).
        let s = self.path_values();
        let (first, last) = (s[0], s[s.len() - 1]);
        let interior = at.x > first.min(last) && at.x < first.max(last);
        let state = self.at(at.x)?;
        let mut kin = state.clone();
        sens_at(&state, &mut kin, sens)?;
        let jet = jet_of_input(c, &kin);
        for p in 0..grad.len() {
            let (g, dg) = column_sens(sens, c, p);
            grad[p] = g;
            // At an end of the range the analog does not vanish: the extremum stays there.
            x_grad[p] = if interior && jet.d2 != 0.0 { -dg / jet.d2 } else { 0.0 };
        }
        if interior && let Some([left, right]) = self.corner_sides(c, which, jet.x, grad.len(), sens, &mut sens_at)? {
            corner_gradients(&left, &right, grad, x_grad);
        }
        Ok((jet.x, jet.value))
    }

    /// The column on either side of a corner of the motion (a kink) at the located extremum
    /// `x`, or `None` where the extremum is smooth: its velocity analog and parameter
    /// derivatives a few units of rounding before and after `x`, where the analog jumps from
    /// one sign to the other (positive to negative at a maximum) by more than a smooth root's
    /// analog could change over that step.
    ///
    /// The extremum is located to a couple of units of rounding of `x` (see
    /// [`bracketed_root`](super::extremes::bracketed_root), whose floor near `x = 0` is `1e-6`
    /// of a sample spacing), so that the two points straddle the corner; over so short a step
    /// each side's derivatives are those of its branch at the corner to rounding.
    fn corner_sides<S: SensState>(
        &self,
        c: ColumnIndex,
        which: Extreme,
        x: f64,
        np: usize,
        sens: &mut S,
        sens_at: &mut impl FnMut(&KinOf<K>, &mut KinOf<K>, &mut S) -> Result<(), Error>,
    ) -> Result<Option<[Side; 2]>, Error> {
        let s = self.path_values();
        let spacing = (s[s.len() - 1] - s[0]) / (s.len() - 1).max(1) as f64;
        let step = 64.0 * f64::EPSILON * (x.abs() + 1e-6 * spacing);
        let mut side = |at: f64| -> Result<Side, Error> {
            let state = self.at(at)?;
            let mut kin = state.clone();
            sens_at(&state, &mut kin, sens)?;
            let jet = jet_of_input(c, &kin);
            let value_grad = (0..np).map(|p| column_sens(sens, c, p).0).collect();
            Ok(Side { jet, value_grad })
        };
        let (left, right) = (side(x - step)?, side(x + step)?);
        // A smooth root's analog changes by about `d2 * 2 step` across it; a kink's jumps by a
        // part of the analog's own size. The factor 1e3 and the floor of 1e-9 of the largest
        // analog sampled leave rounding and curvature on the smooth side of the line.
        let largest = self.states().iter().map(|k| jet_of_input(c, k).d1.abs()).fold(0.0, f64::max);
        let (l, r) = (left.jet.d1, right.jet.d1);
        let turns = if which == Extreme::Max { l > 0.0 && r < 0.0 } else { l < 0.0 && r > 0.0 };
        let smooth = 1e3 * (left.jet.d2.abs() + right.jet.d2.abs()) * step + 1e-9 * largest;
        Ok((turns && (l - r).abs() > smooth).then_some([left, right]))
    }

    /// The one implementation of the integral with gradient (`sens_at` as for the extremum);
    /// `grad` receives the gradient. Returns the integral.
    fn integral_by<S: SensState>(
        &self,
        c: ColumnIndex,
        sens: &mut S,
        mut sens_at: impl FnMut(&KinOf<K>, &mut KinOf<K>, &mut S) -> Result<(), Error>,
        grad: &mut [f64],
    ) -> Result<f64, Error> {
        one_input(self.kernel())?;
        let states = self.states();
        // The abscissa is the input, not the path's parameter (a fraction of the path for a
        // range given as a path).
        let x = |i: usize| states[i].x()[0];
        let mut kin = states[0].clone();
        let mut value = 0.0;
        grad.fill(0.0);
        for (i, state) in states.iter().enumerate() {
            // Trapezoid weights: half of each neighbouring interval.
            let left = if i > 0 { x(i) - x(i - 1) } else { 0.0 };
            let right = if i + 1 < states.len() { x(i + 1) - x(i) } else { 0.0 };
            let w = 0.5 * (left + right);
            sens_at(state, &mut kin, sens)?;
            value += w * jet_of_input(c, &kin).value;
            for (p, g) in grad.iter_mut().enumerate() {
                *g += w * column_sens(sens, c, p).0;
            }
        }
        Ok(value)
    }
}

impl<K: SensKernel> SampledOf<K> {
    /// The kernel's sensitivities at a kept state's position, through buffers made once.
    fn kernel_sens_at(&self) -> impl FnMut(&KinOf<K>, &mut KinOf<K>, &mut K::Sens) -> Result<(), Error> + '_ {
        let d = self.kernel().dims();
        let (mut x, mut q) = (d.x(), d.q());
        move |state, kin, sens| {
            x.as_mut().copy_from_slice(state.x());
            q.as_mut().copy_from_slice(state.q());
            self.kernel().sensitivities_at_into(&x, &q, &self.config().newton, kin, sens)
        }
    }

    /// The maximum or minimum of the column `col` over the sampled range, with its gradients
    /// by every parameter ([`SensKernel::param_count`] values each, in declaration order): the
    /// compiled [`Sampled::extremum_with_gradient`] for any kernel with sensitivities (a
    /// run-time model declared with `#[kinloop(sensitivities)]`), of a mechanism of one input.
    pub fn extremum_with_gradient(&self, col: impl ColumnOf<K>, which: Extreme) -> Result<ExtremumOf<Vec<f64>>, Error> {
        let c = col.resolve(self.kernel())?;
        let np = self.kernel().param_count();
        let (mut grad, mut x_grad) = (vec![0.0; np], vec![0.0; np]);
        let mut sens = self.kernel().sens();
        let (x, value) = self.extremum_by(c, which, &mut sens, self.kernel_sens_at(), &mut grad, &mut x_grad)?;
        Ok(ExtremumOf { x, value, grad, x_grad })
    }

    /// The trapezoidal integral of the column `col` over the samples and its gradient by every
    /// parameter: the compiled [`Sampled::integral_with_gradient`] for any kernel with
    /// sensitivities, of a mechanism of one input.
    pub fn integral_with_gradient(&self, col: impl ColumnOf<K>) -> Result<(f64, Vec<f64>), Error> {
        let c = col.resolve(self.kernel())?;
        let mut grad = vec![0.0; self.kernel().param_count()];
        let mut sens = self.kernel().sens();
        let value = self.integral_by(c, &mut sens, self.kernel_sens_at(), &mut grad)?;
        Ok((value, grad))
    }
}

impl<M, const N: usize, const NO: usize> Sampled<'_, M, N, NO, 1>
where
    M: Mechanism<N, 1, NO>,
{
    /// The compiled mechanism's sensitivities at a kept state's position.
    fn compiled_sens_at<const NP: usize>(
        &self,
    ) -> impl FnMut(&Kin<N, 1, NO>, &mut Kin<N, 1, NO>, &mut Sens<N, 1, NO, NP>) -> Result<(), Error> + '_
    where
        M: Sensitivities<N, 1, NO, NP>,
    {
        move |state, kin, sens| {
            (*kin, *sens) = self.mechanism().sensitivities_at_flat(&state.x, &state.q, &self.config().newton)?;
            Ok(())
        }
    }

    /// The maximum or minimum of the column `col` (`Name::COL.x_f`) over the sampled range
    /// (located as a root of its velocity analog, as [`Sampled::range`] does) with its parameter
    /// gradients, for a mechanism declared with `#[kinloop(sensitivities)]`. The sensitivities
    /// are solved with the sweep configuration's Newton settings.
    ///
    /// An extremum at an end of the range (where the analog does not vanish) is returned at the
    /// end with `x_grad = 0` and `grad = dq/dp` there. An extremum at a corner of the motion (a
    /// kink: `min`, `max`, `abs` in the declaration, as a uniform-velocity cam law has), between
    /// samples or on one, moves
    /// with the corner, where the branches on its two sides are equal: `x_grad` and `grad` are
    /// that corner's (the implicit function theorem on `L(x, p) = R(x, p)`), not one side's
    /// `dq/dp`. An extremum at a singular crossing the
    /// sweep passed ([`AtSingular::Continue`](crate::AtSingular::Continue), a change point) is
    /// an [`Error::InvalidArgument`]: it is a corner there, which moves or vanishes as the
    /// parameters do, and the sensitivities are singular.
    ///
    /// ```ignore
    /// let turn = m.sampled(0.0, TAU, 73, &m.guess(0.0))?;
    /// let top = turn.extremum_with_gradient(RhombicDrive::COL.x_f, Extreme::Max)?;
    /// ```
    pub fn extremum_with_gradient<const NP: usize>(&self, col: Column<M>, which: Extreme) -> Result<Extremum<NP>, Error>
    where
        M: Sensitivities<N, 1, NO, NP>,
    {
        let c = col.resolve(self.kernel())?;
        let (mut grad, mut x_grad) = ([0.0; NP], [0.0; NP]);
        let mut sens = Sens::ZERO;
        let (x, value) = self.extremum_by(c, which, &mut sens, self.compiled_sens_at(), &mut grad, &mut x_grad)?;
        Ok(Extremum { x, value, grad, x_grad })
    }

    /// The trapezoidal integral of the column `col` (`Name::COL.gap`) over the samples and its
    /// exact parameter gradient (the derivative of the same quadrature), for a mechanism declared
    /// with `#[kinloop(sensitivities)]`. For a periodic quantity sampled over a full period the
    /// trapezoidal rule is spectrally accurate.
    pub fn integral_with_gradient<const NP: usize>(&self, col: Column<M>) -> Result<(f64, [f64; NP]), Error>
    where
        M: Sensitivities<N, 1, NO, NP>,
    {
        let c = col.resolve(self.kernel())?;
        let mut grad = [0.0; NP];
        let mut sens = Sens::ZERO;
        let value = self.integral_by(c, &mut sens, self.compiled_sens_at(), &mut grad)?;
        Ok((value, grad))
    }
}
