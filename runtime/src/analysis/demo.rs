//! A hand-written mechanism for the runtime's own unit tests (the `mechanism!`
//! macro lives in another crate): the offset slider-crank, with its slider position `x` as the
//! only unknown. Not part of the public API.

use crate::analysis::{Column, ColumnIndex};
use crate::error::Error;
use crate::events::{BlockInfo, Location};
use crate::kin::{Health, Jac, Kin};
use crate::mechanism::Mechanism;
use crate::solvers::newton::{NewtonConfig, NewtonStop, SolveReport};
use std::borrow::Cow;

/// Offset slider-crank: crank `r` about the origin at angle `phi`, rod `l`, slider at `(x, e)`
/// on the right (`x > r cos phi`). Equation `rod`: `(x - r cos phi)^2 + (r sin phi - e)^2 = l^2`.
/// Output `h = x - r cos phi` (the rod's horizontal projection).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderCrank {
    pub r: f64,
    pub l: f64,
    pub e: f64,
}

/// Its typed columns, as `mechanism!` generates them (`SliderCrank::COL.x`).
#[derive(Clone, Copy, Debug)]
pub struct SliderCrankColumns {
    pub phi: Column<SliderCrank>,
    pub x: Column<SliderCrank>,
    pub h: Column<SliderCrank>,
}

impl SliderCrank {
    pub const COL: SliderCrankColumns = SliderCrankColumns {
        phi: Column::__generated(ColumnIndex::Input(0), "phi"),
        x: Column::__generated(ColumnIndex::Unknown(0), "x"),
        h: Column::__generated(ColumnIndex::Output(0), "h"),
    };

    /// The magnitude `rod`'s residual is judged in: its terms are bounded by the squared sum of
    /// the lengths, so `|f| / magnitude` is the same at every size of the mechanism.
    fn magnitude(&self, q: f64) -> f64 {
        (q.abs() + self.r.abs() + self.e.abs()).powi(2) + self.l * self.l
    }

    fn at(&self, phi: f64) -> Box<Location> {
        Location::boxed("SliderCrank", &["phi"], &[phi], None)
    }

    /// The largest and smallest slider positions and the crank angles where they occur, from
    /// the triangle with the crank and the rod collinear.
    pub fn dead_centres(&self) -> [(f64, f64); 2] {
        let outer = ((self.l + self.r).powi(2) - self.e * self.e).sqrt();
        let inner = ((self.l - self.r).powi(2) - self.e * self.e).sqrt();
        [(self.e.atan2(outer), outer), ((-self.e).atan2(-inner), inner)]
    }
}

impl Mechanism<1, 1, 1> for SliderCrank {
    const NAME: &'static str = "SliderCrank";
    const PARAMS: &'static [&'static str] = &["r", "l", "e"];
    const INPUTS: [&'static str; 1] = ["phi"];
    const UNKNOWNS: [&'static str; 1] = ["x"];
    const EQUATIONS: [&'static str; 1] = ["rod"];
    const OUTPUTS: [&'static str; 1] = ["h"];
    const BLOCKS: &'static [BlockInfo] = &[BlockInfo::borrowed(&[Cow::Borrowed("x")], &[Cow::Borrowed("rod")], false)];

    fn param_values(&self) -> Vec<f64> {
        vec![self.r, self.l, self.e]
    }

    fn guess_flat(&self, x: &[f64; 1]) -> [f64; 1] {
        [self.r * x[0].cos() + self.l]
    }

    fn residual_flat(&self, x: &[f64; 1], q: &[f64; 1]) -> [f64; 1] {
        let (s, c) = x[0].sin_cos();
        [(q[0] - self.r * c).powi(2) + (self.r * s - self.e).powi(2) - self.l * self.l]
    }

    fn position_flat(
        &self,
        x: &[f64; 1],
        guess: &[f64; 1],
        cfg: &NewtonConfig,
    ) -> Result<([f64; 1], SolveReport), Error> {
        self.check_params()?;
        let mut q = guess[0];
        for iterations in 0..=cfg.max_iterations {
            let f = self.residual_flat(x, &[q])[0];
            let evaluations = iterations + 1;
            let residual = f.abs() / self.magnitude(q);
            let j = 2.0 * (q - self.r * x[0].cos());
            if residual <= cfg.residual_tol {
                // As the library's Newton does: the last correction, which quadratic
                // convergence makes exact to rounding (the tolerance is relative to the
                // equation's magnitude, about the squared size, so `f` alone may still move
                // the root by `1e-12` of the size).
                if j != 0.0 {
                    q -= f / j;
                }
                let report =
                    SolveReport { iterations, evaluations, residual, termination: NewtonStop::ResidualTolerance };
                return Ok(([q], report));
            }
            if j == 0.0 || !f.is_finite() {
                break;
            }
            q -= f / j;
        }
        let residual = self.residual_flat(x, &[q])[0].abs() / self.magnitude(q);
        Err(Error::NoAssembly { residual, equation: Cow::Borrowed("rod"), at: self.at(x[0]) })
    }

    fn kinematics_flat(&self, x: &[f64; 1], guess: &[f64; 1], cfg: &NewtonConfig) -> Result<Kin<1, 1, 1>, Error> {
        let (q, report) = self.position_flat(x, guess, cfg)?;
        let mut k = self.kinematics_at_flat(x, &q, cfg)?;
        k.report = report;
        Ok(k)
    }

    fn kinematics_at_flat(&self, x: &[f64; 1], q: &[f64; 1], _cfg: &NewtonConfig) -> Result<Kin<1, 1, 1>, Error> {
        let (r, phi) = (self.r, x[0]);
        let (sn, cs) = phi.sin_cos();
        let w = q[0] - r * cs;
        if w.abs() < 1e-12 * self.l {
            return Err(Error::Singular { pivot_ratio: 0.0, tolerance: 1e-12, at: self.at(phi) });
        }
        // w^2 + s^2 = l^2 with s = r sin phi - e: w' = -s s' / w, w'' = -(s'^2 + s s'' + w'^2) / w.
        let (s, s1, s2) = (r * sn - self.e, r * cs, -r * sn);
        let w1 = -s * s1 / w;
        let w2 = -(s1 * s1 + s * s2 + w1 * w1) / w;
        Ok(Kin {
            x: *x,
            q: *q,
            dq: [[-r * sn + w1]],
            d2q: [[[-r * cs + w2]]],
            out: [w],
            dout: [[w1]],
            d2out: [[[w2]]],
            report: SolveReport::given(self.residual_flat(x, q)[0].abs() / self.magnitude(q[0])),
            health: {
                let mut h = Health { min_pivot: 1.0, ..Health::default() };
                if w < 0.0 {
                    h.det_signs.set_negative(0);
                }
                h
            },
        })
    }

    fn outputs_flat(&self, x: &[f64; 1], q: &[f64; 1]) -> [f64; 1] {
        [q[0] - self.r * x[0].cos()]
    }

    fn jacobian_flat(&self, x: &[f64; 1], q: &[f64; 1]) -> Jac<1, 1> {
        let (sn, cs) = x[0].sin_cos();
        let w = q[0] - self.r * cs;
        let s = self.r * sn - self.e;
        // Terms of `w^2 + s^2 - l^2`, each bounded by the squared sum of the lengths.
        let scale = [self.magnitude(q[0])];
        Jac {
            f: self.residual_flat(x, q),
            j: [[2.0 * w]],
            fx: [[2.0 * w * self.r * sn + 2.0 * s * self.r * cs]],
            scale,
            // The slider position is a length: its unit is the row's magnitude per unit of
            // `df/dx` (`2 (|x| + r + e)`), i.e. about the size of the mechanism.
            unit: [scale[0] / (2.0 * (q[0].abs() + self.r.abs() + self.e.abs()))],
            input_unit: [1.0],
        }
    }

    fn check_params(&self) -> Result<(), Error> {
        for (name, value) in [("r", self.r), ("l", self.l), ("e", self.e)] {
            if !value.is_finite() {
                return Err(Error::NonFinite {
                    what: crate::error::Quantity::Parameter,
                    name: Cow::Borrowed(name),
                    value,
                    at: Location::boxed("SliderCrank", &[], &[], None),
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The solve judges its residual in the equation's magnitude, not in absolute units: in
    /// micrometres (`1e-6` of the size) the residuals are `1e-12` of those at size 1, and an
    /// absolute tolerance of `1e-12` stopped an iteration early, answering a position `5e-7` of
    /// itself off. At every size the slider's position is the scale-1 one times the size, to a
    /// few ulps (it is computed by the same iterations, scaled).
    #[test]
    fn positions_are_the_same_at_every_size() {
        let cfg = NewtonConfig::default();
        let at = |k: f64| {
            let m = SliderCrank { r: k, l: 3.0 * k, e: 0.5 * k };
            let x = [0.7];
            m.position_flat(&x, &m.guess_flat(&x), &cfg).map(|(q, rep)| (q[0] / k, rep.residual))
        };
        let (one, _) = at(1.0).unwrap();
        let closed = 0.7f64.cos() + (9.0 - (0.7f64.sin() - 0.5).powi(2)).sqrt();
        assert!((one - closed).abs() <= 4.0 * f64::EPSILON * closed, "{one} against {closed}");
        for k in [1e-6, 1e-3, 1e3, 1e6] {
            let (q, residual) = at(k).unwrap();
            assert!((q - one).abs() <= 4.0 * f64::EPSILON * one, "size {k:e}: {q} against {one}");
            assert!(residual <= cfg.residual_tol, "size {k:e}: residual {residual:e}");
        }
    }
}
