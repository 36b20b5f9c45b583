//! The residuals of a problem at the search's unknowns and their exact Jacobian: with respect
//! to the design variables from the generated parameter sensitivities, to the free input values
//! from the velocity analogs, to the placement in closed form.

use super::error::SynthesisError;
use super::problem::{Guess, ProblemOf};
use super::resolve::Resolved;
use crate::analysis::ColumnIndex;
use crate::dims::{Dims, KinState};
use crate::error::Error;
use crate::mechanism::kernel::{Q, SensKernel, SensState};
use crate::number::Count;
use std::f64::consts::TAU;

/// Residuals and Jacobian at one point of the search, with the positions solved at every target
/// (the guesses of the next evaluation). A free input moves only its own target's residuals, so
/// the Jacobian is kept in two parts, both linear in the targets (a dense one was `rows x
/// (targets + ...)`, quadratic): `jac`, row-major `rows x globals`, the columns of the unknowns
/// every target shares (the design variables, then the placement's four); and `jin`, one value
/// per row, its derivative by its own target's free input (empty with prescribed inputs).
#[derive(Clone, Debug)]
pub(crate) struct Eval<Q> {
    pub r: Vec<f64>,
    pub jac: Vec<f64>,
    pub jin: Vec<f64>,
    pub qs: Vec<Q>,
}

/// The residuals of a problem and their Jacobian at a point of the search.
#[derive(Clone, Debug, PartialEq)]
pub struct Residuals {
    /// Weighted differences of the mechanism's values from the targets, `width` per target (an
    /// angle's difference reduced to `(-pi, pi]`).
    pub values: Vec<f64>,
    /// `jacobian[k][i] = d values[k] / d z[i]`.
    pub jacobian: Vec<Vec<f64>>,
}

/// A difference of angles reduced to `[-pi, pi]`.
pub(crate) fn wrap(d: f64) -> f64 {
    d - TAU * (d / TAU).round()
}

/// A column's value, its sensitivity to parameter `p`, and its velocity analog.
pub(crate) fn value<S: KinState>(k: &S, c: ColumnIndex) -> f64 {
    match c {
        ColumnIndex::Unknown(u) => k.q()[u],
        ColumnIndex::Output(o) => k.out()[o],
        ColumnIndex::Input(i) => k.x()[i],
    }
}

fn by_param<S: SensState>(s: &S, c: ColumnIndex, p: usize) -> f64 {
    match c {
        ColumnIndex::Unknown(u) => s.q(u, p),
        ColumnIndex::Output(o) => s.out(o, p),
        ColumnIndex::Input(_) => 0.0,
    }
}

fn by_input<S: KinState>(k: &S, c: ColumnIndex) -> f64 {
    match c {
        ColumnIndex::Unknown(u) => k.dq(u)[0],
        ColumnIndex::Output(o) => k.dout(o)[0],
        ColumnIndex::Input(i) => (i == 0) as u8 as f64,
    }
}

impl<K: SensKernel> ProblemOf<K> {
    /// The residuals and their exact Jacobian at the search's unknowns `z` (see [`ProblemOf`] for
    /// their order), the positions solved from the declared guess (or those of
    /// [`ProblemOf::with_guess`], [`ProblemOf::with_guesses`]) at the first target and each from the
    /// one before.
    pub fn residuals(&self, z: &[f64]) -> Result<Residuals, SynthesisError> {
        self.check_point(z)?;
        let e = self.evaluate(z, None)?;
        let (nv, nt, cols) = (self.vars.len(), self.free_inputs(), self.dims());
        let globals = cols - nt;
        let jacobian = (0..e.r.len())
            .map(|k| {
                let jk = &e.jac[k * globals..(k + 1) * globals];
                let mut row = vec![0.0; cols];
                row[..nv].copy_from_slice(&jk[..nv]);
                row[nv + nt..].copy_from_slice(&jk[nv..]);
                if nt > 0 {
                    row[nv + k / self.width] = e.jin[k];
                }
                row
            })
            .collect();
        Ok(Residuals { values: e.r, jacobian })
    }

    /// `z` has one finite value per unknown of the search.
    pub(crate) fn check_point(&self, z: &[f64]) -> Result<(), SynthesisError> {
        if z.len() != self.dims() {
            let (given, unknowns) = (Count(z.len(), "value"), Count(self.dims(), "unknown"));
            return Err(SynthesisError::Mismatch(format!("{given} for {unknowns}")));
        }
        if let Some(v) = z.iter().find(|v| !v.is_finite()) {
            return Err(SynthesisError::InvalidConfig(format!("an unknown of the search is not finite ({v})")));
        }
        Ok(())
    }

    /// The norm of the residuals at the search's unknowns `z`, without their Jacobian (positions
    /// and outputs only, each target's position solved as for [`ProblemOf::residuals`]): the
    /// objective of differential evolution, cheaper than a Jacobian. An error where the design
    /// cannot be assembled at a target.
    pub fn residual_norm(&self, z: &[f64]) -> Result<f64, SynthesisError> {
        self.check_point(z)?;
        Ok(self.norm_at(z)?)
    }

    /// [`ProblemOf::residual_norm`] without the check of `z`.
    pub(crate) fn norm_at(&self, z: &[f64]) -> Result<f64, Error> {
        self.base.with_params(&self.params(z), |m| {
            m.check_param_angles(&self.newton)?;
            self.norm_with(m, z)
        })?
    }

    /// [`ProblemOf::norm_at`] on `m`, the mechanism with `z`'s parameters.
    fn norm_with(&self, m: &K, z: &[f64]) -> Result<f64, Error> {
        let d = m.dims();
        // `q` the target's position, `prev` the one before (swapped, not cloned, per target).
        let (mut q, mut prev, mut out) = (d.q(), d.q(), vec![0.0; d.no()]);
        let inputs = self.input_values(z);
        let at = self.vars.len() + self.free_inputs();
        let (dx, dy, c, sn, s) = match self.placement {
            Some(_) => (z[at], z[at + 1], z[at + 2].cos(), z[at + 2].sin(), z[at + 3]),
            None => (0.0, 0.0, 1.0, 0.0, 1.0),
        };
        // The weighted residuals, their norm taken at the end: squared one by one, those of
        // targets near the largest `f64` overflowed.
        let mut rs = Vec::with_capacity(self.targets.len());
        for (k, x) in inputs.iter().enumerate() {
            // The guesses and Newton's settings of `evaluate` without previous positions.
            let declared;
            let guess: &Q<K> = match (&self.guess, k) {
                (Guess::Every(g), _) => &g[k],
                (_, 1..) => &prev,
                (Guess::First(g), 0) => g,
                (Guess::Declared, 0) => {
                    declared = m.guess(x);
                    &declared
                }
            };
            let cfg = if k == 0 { self.newton } else { self.newton.with_restarts(false) };
            m.position_into(x, guess, &cfg, &mut q, &mut out)?;
            let value = |col: ColumnIndex| match col {
                ColumnIndex::Unknown(u) => q[u],
                ColumnIndex::Output(o) => out[o],
                ColumnIndex::Input(i) => x[i],
            };
            let mut row = k * self.width;
            for &(ch, w) in &self.channels {
                match ch {
                    Resolved::Point(cx, cy) => {
                        let (px, py) = (value(cx), value(cy));
                        let rx = dx + s * (c * px - sn * py) - self.targets[row];
                        let ry = dy + s * (sn * px + c * py) - self.targets[row + 1];
                        rs.extend([w * rx, w * ry]);
                        row += 2;
                    }
                    Resolved::Angle { col, rotates } => {
                        let turn = if self.placement.is_some() && rotates { sn.atan2(c) } else { 0.0 };
                        let r = wrap(value(col) + turn - self.targets[row]);
                        rs.push(w * r);
                        row += 1;
                    }
                    Resolved::Value(col) => {
                        let r = value(col) - self.targets[row];
                        rs.push(w * r);
                        row += 1;
                    }
                }
            }
            std::mem::swap(&mut prev, &mut q);
        }
        Ok(crate::number::norm_of(rs.iter().copied()))
    }

    /// The residuals, Jacobian and positions at `z`, each target's position solved from
    /// `guesses` (the previous evaluation's), or else from the first target's guess and each
    /// from the one before.
    pub(crate) fn evaluate(&self, z: &[f64], guesses: Option<&[Q<K>]>) -> Result<Eval<Q<K>>, Error> {
        // Once per design, not per target: a design whose angle parameter is too large to
        // resolve is refused as one that cannot be assembled is, with the reason.
        self.base.with_params(&self.params(z), |m| {
            m.check_param_angles(&self.newton)?;
            self.evaluate_with(m, z, guesses)
        })?
    }

    /// [`ProblemOf::evaluate`] on `m`, the mechanism with `z`'s parameters.
    fn evaluate_with(&self, m: &K, z: &[f64], guesses: Option<&[Q<K>]>) -> Result<Eval<Q<K>>, Error> {
        let inputs = self.input_values(z);
        let (mut kin, mut sens) = (m.dims().kin(), m.sens());
        // The shared columns (design variables, placement) and the free inputs' apart.
        let (nv, nt) = (self.vars.len(), self.free_inputs());
        let cols = self.dims() - nt;
        let n = inputs.len();
        let mut r = vec![0.0; n * self.width];
        let mut jac = vec![0.0; n * self.width * cols];
        let mut jin = vec![0.0; if nt > 0 { n * self.width } else { 0 }];
        let mut qs: Vec<Q<K>> = Vec::with_capacity(n);
        let place = self.placement.map(|_| {
            let at = nv + nt;
            let (th, s) = (z[at + 2], z[at + 3]);
            (z[at], z[at + 1], th.cos(), th.sin(), s)
        });
        for (k, x) in inputs.iter().enumerate() {
            let declared;
            let guess: &Q<K> = match (guesses, &self.guess, qs.last()) {
                (Some(g), _, _) => &g[k],
                (None, Guess::Every(g), _) => &g[k],
                (None, _, Some(q)) => q,
                (None, Guess::First(g), None) => g,
                (None, Guess::Declared, None) => {
                    declared = m.guess(x);
                    &declared
                }
            };
            // Newton's restarts (roots from turned guesses) only where the assembly mode is
            // chosen: at the first target of a start. Elsewhere a root from a turned guess would
            // be another assembly mode than the guess's; a failed solve rejects the step instead.
            let choose = guesses.is_none() && k == 0;
            let cfg = if choose { self.newton } else { self.newton.with_restarts(false) };
            m.sensitivities_into(x, guess, &cfg, &mut kin, &mut sens)?;
            let mut q = m.dims().q();
            q.as_mut().copy_from_slice(kin.q());
            qs.push(q);
            let mut row = k * self.width;
            for &(ch, w) in &self.channels {
                match ch {
                    Resolved::Point(cx, cy) => {
                        let (px, py) = (value(&kin, cx), value(&kin, cy));
                        let (tx, ty) = (self.targets[row], self.targets[row + 1]);
                        // The placed point d + s R p and the placed derivative s R dp.
                        let (dx, dy, c, sn, s) = place.unwrap_or((0.0, 0.0, 1.0, 0.0, 1.0));
                        let turn = |a: f64, b: f64| (s * (c * a - sn * b), s * (sn * a + c * b));
                        let (mx, my) = turn(px, py);
                        r[row] = w * (dx + mx - tx);
                        r[row + 1] = w * (dy + my - ty);
                        let (jx, jy) = (row * cols, (row + 1) * cols);
                        for (i, b) in self.vars.iter().enumerate() {
                            let (a, bb) = turn(by_param(&sens, cx, b.index), by_param(&sens, cy, b.index));
                            jac[jx + i] = w * a;
                            jac[jy + i] = w * bb;
                        }
                        if nt > 0 {
                            let (a, bb) = turn(by_input(&kin, cx), by_input(&kin, cy));
                            jin[row] = w * a;
                            jin[row + 1] = w * bb;
                        }
                        if place.is_some() {
                            let at = nv;
                            jac[jx + at] = w;
                            jac[jy + at + 1] = w;
                            // d(s R p)/d angle = (-my, mx); d(s R p)/d s = R p = (mx, my) / s.
                            jac[jx + at + 2] = -w * my;
                            jac[jy + at + 2] = w * mx;
                            jac[jx + at + 3] = w * (c * px - sn * py);
                            jac[jy + at + 3] = w * (sn * px + c * py);
                        }
                        row += 2;
                    }
                    Resolved::Angle { col, rotates } => {
                        let turn = match place {
                            Some((_, _, c, sn, _)) if rotates => sn.atan2(c),
                            _ => 0.0,
                        };
                        r[row] = w * wrap(value(&kin, col) + turn - self.targets[row]);
                        let j = row * cols;
                        for (i, b) in self.vars.iter().enumerate() {
                            jac[j + i] = w * by_param(&sens, col, b.index);
                        }
                        if nt > 0 {
                            jin[row] = w * by_input(&kin, col);
                        }
                        if place.is_some() && rotates {
                            jac[j + nv + 2] = w;
                        }
                        row += 1;
                    }
                    Resolved::Value(col) => {
                        r[row] = w * (value(&kin, col) - self.targets[row]);
                        let j = row * cols;
                        for (i, b) in self.vars.iter().enumerate() {
                            jac[j + i] = w * by_param(&sens, col, b.index);
                        }
                        if nt > 0 {
                            jin[row] = w * by_input(&kin, col);
                        }
                        row += 1;
                    }
                }
            }
        }
        Ok(Eval { r, jac, jin, qs })
    }
}
