//! The peers of kinloop for the rhombic drive of paper 000 (kinloop itself is in
//! [`crate::kinloop_variants`]): the published closed form, a hand-written Newton exploiting the
//! two independent loops, and a dense 4x4 Newton whose Jacobian comes from hand-written
//! derivatives, from num-dual, or from finite differences.
//!
//! Every Newton here stops at `max |f| <= 1e-12` (kinloop's default), starts from the guess the
//! sweep hands it, and returns the same outputs: the 4 positions, 4 velocity analogs and 4
//! acceleration analogs, with the number of iterations.

use std::f64::consts::PI;

use crate::libm::sin_cos;
use nalgebra::{SMatrix, SVector};
use num_dual::{Dual2, DualNum, DualSVec64};

use crate::decls::RhombicDrive;
use crate::linalg::max_abs;
use crate::sweep::{Failed, Step, Stepper};

/// Residual tolerance of every Newton (kinloop's default `residual_tol`).
pub const TOL: f64 = 1e-12;
/// Iteration cap of the peers' Newtons (kinloop's default `max_iterations`).
pub const MAX_ITERATIONS: u32 = 50;

/// Parameters of the drive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Crank arm AB of the working piston.
    pub r_p: f64,
    /// Crank arm AD of the displacer.
    pub r_b: f64,
    /// Working rod BC.
    pub l_p: f64,
    /// Displacer rod DF.
    pub l_b: f64,
    /// Height of the crank centre A above the working piston's line.
    pub e_p: f64,
    /// Height of the displacer's line above the working piston's.
    pub de: f64,
    /// Angle between the two crank arms (radians).
    pub gamma: f64,
}

/// The gallery's dimensions: r_p=1.0, r_b=1.2, l_p=3.0, l_b=3.5, e_p=0.5, de=0.9, gamma=0.7.
pub const PARAMS: Params = Params { r_p: 1.0, r_b: 1.2, l_p: 3.0, l_b: 3.5, e_p: 0.5, de: 0.9, gamma: 0.7 };

/// The assembly mode at `phi1 = 0` (the declared guess: rods to the left of the pistons).
pub fn initial_guess(p: &Params) -> [f64; 4] {
    [0.0, PI, -p.l_p, p.l_b]
}

impl Params {
    /// The kinloop mechanism with these dimensions.
    pub fn kinloop(&self) -> RhombicDrive {
        RhombicDrive {
            r_p: self.r_p,
            r_b: self.r_b,
            l_p: self.l_p,
            l_b: self.l_b,
            e_p: self.e_p,
            de: self.de,
            gamma: self.gamma,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The published closed form (the limit).

/// The closed form of paper 000 written by hand, with the ratios and the sine and cosine of the
/// crank arms' angle `gamma` precomputed once: `sin(phi2) = lambda_P (k_P + sin(phi1))`,
/// `phi4 = pi - asin(...)` (the continuous branch), the second arm's `sin(phi1 + gamma)` and
/// `cos(phi1 + gamma)` by angle addition from the first's, cosines by square roots, and the
/// paper's analog formulas. It ignores the warm start. One libm `sincos` a step, not two: angle
/// addition is what a closed form written for speed does with a constant angle (about 134
/// instructions a step fewer; [`ClosedFormLibmSum`] is the form with the second call), and its
/// values are within about 1.5 units in the last place of the exact sum's, closer than libm's of
/// the rounded sum `phi1 + gamma` (rounded by up to 4.4e-16 rad near `2 pi`).
#[derive(Clone, Copy, Debug)]
pub struct ClosedForm {
    lam_p: f64,
    k_p: f64,
    lam_b: f64,
    k_b: f64,
    l_p: f64,
    l_b: f64,
    gamma: f64,
    sin_gamma: f64,
    cos_gamma: f64,
}

impl ClosedForm {
    /// Precomputes the ratios of the drive `p`.
    pub fn new(p: &Params) -> Self {
        let e_b = p.e_p - p.de;
        ClosedForm {
            lam_p: p.r_p / p.l_p,
            k_p: p.e_p / p.r_p,
            lam_b: p.r_b / p.l_b,
            k_b: e_b / p.r_b,
            l_p: p.l_p,
            l_b: p.l_b,
            gamma: p.gamma,
            sin_gamma: p.gamma.sin(),
            cos_gamma: p.gamma.cos(),
        }
    }
}

impl ClosedForm {
    /// The rods' sines and cosines `[s2, c2, s4, c4]` from the crank arms' sines `s1 = sin(phi1)`
    /// and `sa = sin(phi1 + gamma)` (the assembly test `|s| < 1` protects the square roots).
    #[inline(always)]
    pub fn rods(&self, s1: f64, sa: f64) -> Result<[f64; 4], Failed> {
        let s2 = self.lam_p * (self.k_p + s1);
        let s4 = self.lam_b * (self.k_b + sa);
        if !(s2.abs() < 1.0 && s4.abs() < 1.0) {
            return Err(Failed::new("closed form: the drive cannot be assembled"));
        }
        Ok([s2, (1.0 - s2 * s2).sqrt(), s4, -(1.0 - s4 * s4).sqrt()])
    }

    /// The step from the crank arms' sines and cosines `[s1, c1, sa, ca]`, the rods' (see
    /// [`ClosedForm::rods`]) and the rod angles `phi2`, `phi4`: the paper's formulas for the
    /// sliders and every analog. [`Stepper::step`] and the hand-written sweep
    /// ([`crate::hand_sweep::RhombicSweep`]) share it: they differ only in their trigonometry.
    #[inline(always)]
    pub fn assemble(&self, crank: [f64; 4], rods: [f64; 4], phi2: f64, phi4: f64) -> Step<4> {
        let [s1, c1, sa, ca] = crank;
        let [s2, c2, s4, c4] = rods;
        let x_c = self.l_p * (self.lam_p * c1 - c2);
        let x_f = self.l_b * (self.lam_b * ca - c4);
        let u21 = self.lam_p * c1 / c2;
        let u41 = self.lam_b * ca / c4;
        let v_c = self.l_p * (u21 * s2 - self.lam_p * s1);
        let v_f = self.l_b * (u41 * s4 - self.lam_b * sa);
        let e2 = (u21 * u21 * s2 - self.lam_p * s1) / c2;
        let e4 = (u41 * u41 * s4 - self.lam_b * sa) / c4;
        let a_c = self.l_p * (e2 * s2 + u21 * u21 * c2 - self.lam_p * c1);
        let a_f = self.l_b * (e4 * s4 + u41 * u41 * c4 - self.lam_b * ca);
        Step { q: [phi2, phi4, x_c, x_f], dq: [u21, u41, v_c, v_f], d2q: [e2, e4, a_c, a_f], iterations: 0 }
    }

    /// The angle between the crank arms (radians).
    pub fn gamma(&self) -> f64 {
        self.gamma
    }
}

impl Stepper<4> for ClosedForm {
    const WARM: bool = false;

    #[inline(always)]
    fn step(&self, phi1: f64, _guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        let (s1, c1) = sin_cos(phi1);
        let (sg, cg) = (self.sin_gamma, self.cos_gamma);
        let (sa, ca) = (s1 * cg + c1 * sg, c1 * cg - s1 * sg);
        let rods = self.rods(s1, sa)?;
        let phi2 = rods[0].asin();
        let phi4 = PI - rods[2].asin();
        Ok(self.assemble([s1, c1, sa, ca], rods, phi2, phi4))
    }
}

/// [`ClosedForm`] with the second crank arm's sine and cosine from libm, `sin_cos(phi1 + gamma)`,
/// as the paper writes them: two `sincos` calls a step, the libm calls kinloop's point step
/// makes (it keeps nothing between steps). A row of its own beside the leaner reference.
#[derive(Clone, Copy, Debug)]
pub struct ClosedFormLibmSum(pub ClosedForm);

impl Stepper<4> for ClosedFormLibmSum {
    const WARM: bool = false;

    #[inline(always)]
    fn step(&self, phi1: f64, _guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        let c = &self.0;
        let (s1, c1) = sin_cos(phi1);
        let (sa, ca) = sin_cos(phi1 + c.gamma);
        let rods = c.rods(s1, sa)?;
        let phi2 = rods[0].asin();
        let phi4 = PI - rods[2].asin();
        Ok(c.assemble([s1, c1, sa, ca], rods, phi2, phi4))
    }
}

// ---------------------------------------------------------------------------------------------
// Hand-written Newton exploiting the two independent loops.

/// Scalar Newton on `f(t)`; `eval` returns `(f, f', sin t, cos t)` so the caller keeps them.
#[inline(always)]
fn newton1(mut t: f64, eval: impl Fn(f64) -> (f64, f64, f64, f64)) -> Result<(f64, f64, f64, u32), Failed> {
    let mut iterations = 0;
    loop {
        let (f, df, s, c) = eval(t);
        if f.abs() <= TOL {
            return Ok((t, s, c, iterations));
        }
        if !f.is_finite() || df == 0.0 || iterations >= MAX_ITERATIONS {
            return Err(Failed::new("two-loop Newton: no convergence"));
        }
        t -= f / df;
        iterations += 1;
    }
}

/// What an expert writes by hand knowing the structure: a scalar Newton on each loop's Y
/// projection for the rod angle, the slider from the X projection, and the analogs from the
/// implicitly differentiated projections.
#[derive(Clone, Copy, Debug)]
pub struct TwoLoopNewton {
    /// The drive's dimensions.
    pub p: Params,
}

impl Stepper<4> for TwoLoopNewton {
    #[inline]
    fn step(&self, phi1: f64, guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        let p = &self.p;
        let (s1, c1) = sin_cos(phi1);
        let (sa, ca) = sin_cos(phi1 + p.gamma);
        // Working group: e_p + r_p sin(phi1) = l_p sin(phi2); x_c = r_p cos(phi1) - l_p cos(phi2).
        let yb = p.e_p + p.r_p * s1;
        let (phi2, s2, c2, it2) = newton1(guess[0], |t| {
            let (s, c) = sin_cos(t);
            (yb - p.l_p * s, -p.l_p * c, s, c)
        })?;
        // Displacer group: e_p + r_b sin(phi1 + gamma) = de + l_b sin(phi4).
        let yd = p.e_p - p.de + p.r_b * sa;
        let (phi4, s4, c4, it4) = newton1(guess[1], |t| {
            let (s, c) = sin_cos(t);
            (yd - p.l_b * s, -p.l_b * c, s, c)
        })?;
        let (rs1, rc1, rsa, rca) = (p.r_p * s1, p.r_p * c1, p.r_b * sa, p.r_b * ca);
        let (ls2, lc2, ls4, lc4) = (p.l_p * s2, p.l_p * c2, p.l_b * s4, p.l_b * c4);
        let x_c = rc1 - lc2;
        let x_f = rca - lc4;
        // d/dphi1 of the Y projections: r cos = l cos(phi) phi'.
        let u2 = rc1 / lc2;
        let u4 = rca / lc4;
        let v_c = ls2 * u2 - rs1;
        let v_f = ls4 * u4 - rsa;
        // Second derivatives: -r sin = -l sin(phi) phi'^2 + l cos(phi) phi''.
        let e2 = (ls2 * u2 * u2 - rs1) / lc2;
        let e4 = (ls4 * u4 * u4 - rsa) / lc4;
        let a_c = lc2 * u2 * u2 + ls2 * e2 - rc1;
        let a_f = lc4 * u4 * u4 + ls4 * e4 - rca;
        Ok(Step { q: [phi2, phi4, x_c, x_f], dq: [u2, u4, v_c, v_f], d2q: [e2, e4, a_c, a_f], iterations: it2 + it4 })
    }
}

// ---------------------------------------------------------------------------------------------
// Dense 4x4 Newton: hand-written Jacobian, num-dual, finite differences.

type M4 = SMatrix<f64, 4, 4>;
type V4 = SVector<f64, 4>;

/// The four scalar equations (declaration order `oabco.x, oabco.y, oadff1o.x, oadff1o.y`,
/// unknowns `phi2, phi4, x_c, x_f`), generic over the number type for num-dual.
#[inline(always)]
pub fn residual<D: DualNum<Primitive = f64> + Copy>(p: &Params, phi1: D, q: [D; 4]) -> [D; 4] {
    let [phi2, phi4, x_c, x_f] = q;
    let (s1, c1) = phi1.sin_cos();
    let (sa, ca) = (phi1 + p.gamma).sin_cos();
    let (s2, c2) = phi2.sin_cos();
    let (s4, c4) = phi4.sin_cos();
    [
        c1 * p.r_p - x_c - c2 * p.l_p,
        s1 * p.r_p + p.e_p - s2 * p.l_p,
        ca * p.r_b - x_f - c4 * p.l_b,
        sa * p.r_b + (p.e_p - p.de) - s4 * p.l_b,
    ]
}

/// The Newton loop of the dense peers. `eval(z)` gives the residual, the Jacobian and whatever
/// else the peer computes with them (`X`); returns the root, the evaluation there, and the
/// iteration count. The caller factorises the final Jacobian once for both analogs.
#[inline(always)]
fn dense_newton<X>(
    z0: [f64; 4],
    mut eval: impl FnMut(&[f64; 4]) -> ([f64; 4], M4, X),
) -> Result<([f64; 4], M4, X, u32), Failed> {
    let mut z = z0;
    let mut iterations = 0;
    loop {
        let (f, j, x) = eval(&z);
        let res = max_abs(&f);
        if res <= TOL {
            return Ok((z, j, x, iterations));
        }
        if !res.is_finite() || iterations >= MAX_ITERATIONS {
            return Err(Failed::new("dense Newton: no convergence"));
        }
        let dz = j.lu().solve(&-V4::from(f)).ok_or_else(|| Failed::new("dense Newton: singular Jacobian"))?;
        for u in 0..4 {
            z[u] += dz[u];
        }
        iterations += 1;
    }
}

/// Velocity and acceleration analogs from one LU of the Jacobian: `J q' = -df/dphi1` and
/// `J q'' = -D2f[(q', 1), (q', 1)]`, the latter computed by `second(q')`.
#[inline(always)]
fn dense_analogs(
    j: &M4,
    f_phi: [f64; 4],
    second: impl FnOnce(&[f64; 4]) -> [f64; 4],
) -> Result<([f64; 4], [f64; 4]), Failed> {
    let lu = j.lu();
    let dq: [f64; 4] = lu.solve(&-V4::from(f_phi)).ok_or_else(|| Failed::new("singular Jacobian"))?.into();
    let d2q: [f64; 4] = lu.solve(&-V4::from(second(&dq))).ok_or_else(|| Failed::new("singular Jacobian"))?.into();
    Ok((dq, d2q))
}

/// Dense 4x4 Newton with the Jacobian, `df/dphi1` and the second-order term derived by hand.
#[derive(Clone, Copy, Debug)]
pub struct DenseHandJacobian {
    /// The drive's dimensions.
    pub p: Params,
}

impl Stepper<4> for DenseHandJacobian {
    #[inline]
    fn step(&self, phi1: f64, guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        let p = &self.p;
        let (s1, c1) = sin_cos(phi1);
        let (sa, ca) = sin_cos(phi1 + p.gamma);
        let (z, j, (s2, c2, s4, c4), iterations) = dense_newton(*guess, |z| {
            let [phi2, phi4, x_c, x_f] = *z;
            let (s2, c2) = sin_cos(phi2);
            let (s4, c4) = sin_cos(phi4);
            let f = [
                p.r_p * c1 - x_c - p.l_p * c2,
                p.e_p + p.r_p * s1 - p.l_p * s2,
                p.r_b * ca - x_f - p.l_b * c4,
                p.e_p - p.de + p.r_b * sa - p.l_b * s4,
            ];
            #[rustfmt::skip]
            let j = M4::new(
                p.l_p * s2, 0.0, -1.0, 0.0,
                -p.l_p * c2, 0.0, 0.0, 0.0,
                0.0, p.l_b * s4, 0.0, -1.0,
                0.0, -p.l_b * c4, 0.0, 0.0,
            );
            (f, j, (s2, c2, s4, c4))
        })?;
        let f_phi = [-p.r_p * s1, p.r_p * c1, -p.r_b * sa, p.r_b * ca];
        let (dq, d2q) = dense_analogs(&j, f_phi, |dq| {
            let (w2, w4) = (dq[0] * dq[0], dq[1] * dq[1]);
            [
                -p.r_p * c1 + p.l_p * c2 * w2,
                -p.r_p * s1 + p.l_p * s2 * w2,
                -p.r_b * ca + p.l_b * c4 * w4,
                -p.r_b * sa + p.l_b * s4 * w4,
            ]
        })?;
        Ok(Step { q: z, dq, d2q, iterations })
    }
}

/// Dense 4x4 Newton driven by num-dual: each evaluation seeds the four unknowns and the input in
/// a `DualSVec64<5>` (`num_dual::jacobian`), giving `f`, `J` and `df/dphi1` at once; the
/// second-order term `D2f[(q', 1), (q', 1)]` is one `Dual2` evaluation along `(q', 1)`.
#[derive(Clone, Copy, Debug)]
pub struct DenseNumDual {
    /// The drive's dimensions.
    pub p: Params,
}

impl Stepper<4> for DenseNumDual {
    #[inline]
    fn step(&self, phi1: f64, guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        let p = &self.p;
        let (z, j, f_phi, iterations) = dense_newton(*guess, |z| {
            let x = SVector::<f64, 5>::new(z[0], z[1], z[2], z[3], phi1);
            let (f, jac) = num_dual::jacobian(
                |x: SVector<DualSVec64<5>, 5>| SVector::from(residual(p, x[4], [x[0], x[1], x[2], x[3]])),
                &x,
            );
            let j: M4 = jac.fixed_view::<4, 4>(0, 0).into_owned();
            let f_phi: [f64; 4] = jac.column(4).into_owned().into();
            (f.into(), j, f_phi)
        })?;
        let (dq, d2q) = dense_analogs(&j, f_phi, |dq| {
            let q = std::array::from_fn(|u| Dual2::new(z[u], dq[u], 0.0));
            residual(p, Dual2::new(phi1, 1.0, 0.0), q).map(|d| d.v2)
        })?;
        Ok(Step { q: z, dq, d2q, iterations })
    }
}

/// Dense 4x4 Newton with a forward-difference Jacobian (steps `sqrt(eps) max(1, |z|)`),
/// `df/dphi1` by a forward difference and the second-order term by a central second
/// difference along `(q', 1)`.
#[derive(Clone, Copy, Debug)]
pub struct DenseFiniteDifference {
    /// The drive's dimensions.
    pub p: Params,
}

impl Stepper<4> for DenseFiniteDifference {
    #[inline]
    fn step(&self, phi1: f64, guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        let p = &self.p;
        let sqrt_eps = f64::EPSILON.sqrt();
        let (z, j, f, iterations) = dense_newton(*guess, |z| {
            let f = residual::<f64>(p, phi1, *z);
            let mut j = M4::zeros();
            for c in 0..4 {
                let mut zc = *z;
                zc[c] += sqrt_eps * z[c].abs().max(1.0);
                let h = zc[c] - z[c];
                let fc = residual::<f64>(p, phi1, zc);
                for r in 0..4 {
                    j[(r, c)] = (fc[r] - f[r]) / h;
                }
            }
            (f, j, f)
        })?;
        let hp = sqrt_eps * phi1.abs().max(1.0);
        let phi_h = phi1 + hp;
        let f_h = residual::<f64>(p, phi_h, z);
        let hp = phi_h - phi1;
        let f_phi = std::array::from_fn(|r| (f_h[r] - f[r]) / hp);
        let (dq, d2q) = dense_analogs(&j, f_phi, |dq| {
            // eps^(1/4) balances truncation (~e^2) against rounding (~eps/e^2).
            let e = f64::EPSILON.sqrt().sqrt() / max_abs(dq).max(1.0);
            let plus = residual::<f64>(p, phi1 + e, std::array::from_fn(|u| z[u] + e * dq[u]));
            let minus = residual::<f64>(p, phi1 - e, std::array::from_fn(|u| z[u] - e * dq[u]));
            std::array::from_fn(|r| (plus[r] - 2.0 * f[r] + minus[r]) / (e * e))
        })?;
        Ok(Step { q: z, dq, d2q, iterations })
    }
}
