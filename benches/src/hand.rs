//! Closed forms written by hand for the linkages whose generated solve is a closed form: the
//! four-bar with its coupler point (circle intersection) and the gear-lever rocker (the polar
//! angle and length of the planet pin). Each computes what the generated kinematics computes:
//! positions, velocity and acceleration analogs of the unknowns and of the output point.

use crate::sweep::{Failed, Step, Stepper};
use kinloop_fixtures::FourBar;
use kinloop_fixtures::gear_lever::GearLever;
use std::f64::consts::TAU;
use std::hint::black_box;

/// The four-bar of the closed-form rows (`closed_form_step`, the criterion groups and the
/// report measure this one).
pub const FOUR_BAR: FourBar = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };

/// The gear-lever drive of the closed-form rows: the fixtures' default.
pub fn gear_lever() -> GearLever {
    GearLever::default()
}

/// `q` moved by whole turns to the turn of `guess` (a sweep's angles stay continuous).
///
/// The turns are rounded by adding and subtracting `1.5 · 2^52` (to the nearest, ties to even;
/// for fewer than 2^51 turns), two additions: `f64::round` is a call of about ten instructions
/// on x86-64 without SSE4.1, and a division by `2π` costs more than a multiplication by its
/// reciprocal. The reference is written as lean as kinloop's own turn (`unwrap_to_turn`).
#[inline]
pub fn on_turn(q: f64, guess: f64) -> f64 {
    const ROUND: f64 = 6_755_399_441_055_744.0;
    q + TAU * ((((guess - q) * (1.0 / TAU)) + ROUND) - ROUND)
}

/// The four-bar of the fixtures (`kinloop_fixtures::FourBar`: crank `a` at the origin, coupler
/// `b`, rocker `c` pivoted at `(d, 0)`, coupler point `pc` = joint C) by circle intersection, on
/// the side of the line B -> D given by `left`. The coupler point and its analogs are computed
/// as the generated code computes them: `step` passes them to `black_box`, the lean harness
/// (`step_summed`, [`crate::lean`]) adds them up with the unknowns'.
#[derive(Clone, Copy, Debug)]
pub struct FourBarClosed {
    /// Crank length.
    pub a: f64,
    /// Coupler length.
    pub b: f64,
    /// Rocker length.
    pub c: f64,
    /// Distance between the frame pivots.
    pub d: f64,
    /// C on the left of B -> D.
    pub left: bool,
}

impl FourBarClosed {
    /// The closed form of the four-bar `m`, on the assembly mode of the rows (C left of B -> D).
    pub fn of(m: &FourBar) -> Self {
        FourBarClosed { a: m.a, b: m.b, c: m.c, d: m.d, left: true }
    }
}

/// The four-bar's joints at one crank position: the crank's sine and cosine, B, the coupler's
/// and the rocker's sines and cosines, and C (the coupler point). Everything of a step but the
/// two angles, which a closed form makes by `atan2` and a hand-written sweep by increments.
#[derive(Clone, Copy, Debug)]
pub struct FourBarPose {
    /// `sin(phi)`, `cos(phi)`.
    pub s1: f64,
    /// See [`FourBarPose::s1`].
    pub c1: f64,
    /// B = `a (cos phi, sin phi)`.
    pub bx: f64,
    /// See [`FourBarPose::bx`].
    pub by: f64,
    /// `cos(beta)`, `sin(beta)`.
    pub cb: f64,
    /// See [`FourBarPose::cb`].
    pub sb: f64,
    /// `cos(gamma)`, `sin(gamma)`.
    pub cg: f64,
    /// See [`FourBarPose::cg`].
    pub sg: f64,
    /// C, the coupler point.
    pub cx: f64,
    /// See [`FourBarPose::cx`].
    pub cy: f64,
}

impl FourBarClosed {
    /// The joints at the crank's sine `s1` and cosine `c1` by circle intersection (the assembly
    /// test `h2 >= 0` protects the square root).
    #[inline(always)]
    pub fn pose(&self, s1: f64, c1: f64) -> Result<FourBarPose, Failed> {
        let (a, b, c) = (self.a, self.b, self.c);
        let (bx, by) = (a * c1, a * s1);
        let (ex, ey) = (self.d - bx, -by);
        let e2 = ex * ex + ey * ey;
        let along = (b * b - c * c + e2) / (2.0 * e2);
        let h2 = b * b / e2 - along * along;
        if h2.is_nan() || h2 < 0.0 {
            return Err(Failed::new("four-bar closed form: no assembly"));
        }
        let h = if self.left { h2.sqrt() } else { -h2.sqrt() };
        // C - B = along (D - B) + h perp(D - B).
        let (ux, uy) = (along * ex - h * ey, along * ey + h * ex);
        let (cb, sb) = (ux / b, uy / b);
        let (cx, cy) = (bx + ux, by + uy);
        let (cg, sg) = ((cx - self.d) / c, cy / c);
        Ok(FourBarPose { s1, c1, bx, by, cb, sb, cg, sg, cx, cy })
    }

    /// The step and the coupler point with its analogs `[x, y, x', y', x'', y'']` from the
    /// joints `p` and the angles `beta`, `gamma`. The hand-written sweep
    /// ([`crate::hand_sweep::FourBarSweep`]) computes with it what [`FourBarClosed::full`]
    /// computes: they differ only in their trigonometry.
    #[inline(always)]
    pub fn finish(&self, p: &FourBarPose, beta: f64, gamma: f64) -> (Step<2>, [f64; 6]) {
        let (a, b, c) = (self.a, self.b, self.c);
        let FourBarPose { s1, c1, bx, by, cb, sb, cg, sg, cx, cy } = *p;
        // a phi' e^{i phi} + b beta' e^{i beta} = c gamma' e^{i gamma}, projected.
        let sbg = sb * cg - cb * sg;
        let w_b = -a * (s1 * cg - c1 * sg) / (b * sbg);
        let w_g = -a * (s1 * cb - c1 * sb) / (c * sbg);
        // R = -a e^{i phi} - b beta'^2 e^{i beta} + c gamma'^2 e^{i gamma}.
        let rx = -bx - b * w_b * w_b * cb + c * w_g * w_g * cg;
        let ry = -by - b * w_b * w_b * sb + c * w_g * w_g * sg;
        let e_b = (rx * cg + ry * sg) / (b * sbg);
        let e_g = (rx * cb + ry * sb) / (c * sbg);
        let point = [
            cx,
            cy,
            -by - b * w_b * sb,
            bx + b * w_b * cb,
            -bx - b * e_b * sb - b * w_b * w_b * cb,
            -by + b * e_b * cb - b * w_b * w_b * sb,
        ];
        (Step { q: [beta, gamma], dq: [w_b, w_g], d2q: [e_b, e_g], iterations: 0 }, point)
    }

    /// The step at crank angle `phi` (angles on the turns of `guess`) and the coupler point with
    /// its analogs `[x, y, x', y', x'', y'']`.
    ///
    /// The formulas of [`FourBarClosed::pose`] and [`FourBarClosed::finish`], written out: the
    /// reference of the closed-form rows stays the code their counts were measured on (composed
    /// of those two, the compiler allocates its registers otherwise: 4 instructions more a step
    /// under callgrind). The `hand_sweep` tests compare the two at every sample.
    #[inline(always)]
    pub fn full(&self, phi: f64, guess: &[f64; 2]) -> Result<(Step<2>, [f64; 6]), Failed> {
        let (a, b, c) = (self.a, self.b, self.c);
        let (s1, c1) = phi.sin_cos();
        let (bx, by) = (a * c1, a * s1);
        let (ex, ey) = (self.d - bx, -by);
        let e2 = ex * ex + ey * ey;
        let along = (b * b - c * c + e2) / (2.0 * e2);
        let h2 = b * b / e2 - along * along;
        if h2.is_nan() || h2 < 0.0 {
            return Err(Failed::new("four-bar closed form: no assembly"));
        }
        let h = if self.left { h2.sqrt() } else { -h2.sqrt() };
        // C - B = along (D - B) + h perp(D - B).
        let (ux, uy) = (along * ex - h * ey, along * ey + h * ex);
        let (cb, sb) = (ux / b, uy / b);
        let (cx, cy) = (bx + ux, by + uy);
        let (cg, sg) = ((cx - self.d) / c, cy / c);
        let beta = on_turn(sb.atan2(cb), guess[0]);
        let gamma = on_turn(sg.atan2(cg), guess[1]);
        // a phi' e^{i phi} + b beta' e^{i beta} = c gamma' e^{i gamma}, projected.
        let sbg = sb * cg - cb * sg;
        let w_b = -a * (s1 * cg - c1 * sg) / (b * sbg);
        let w_g = -a * (s1 * cb - c1 * sb) / (c * sbg);
        // R = -a e^{i phi} - b beta'^2 e^{i beta} + c gamma'^2 e^{i gamma}.
        let rx = -bx - b * w_b * w_b * cb + c * w_g * w_g * cg;
        let ry = -by - b * w_b * w_b * sb + c * w_g * w_g * sg;
        let e_b = (rx * cg + ry * sg) / (b * sbg);
        let e_g = (rx * cb + ry * sb) / (c * sbg);
        let point = [
            cx,
            cy,
            -by - b * w_b * sb,
            bx + b * w_b * cb,
            -bx - b * e_b * sb - b * w_b * w_b * cb,
            -by + b * e_b * cb - b * w_b * w_b * sb,
        ];
        Ok((Step { q: [beta, gamma], dq: [w_b, w_g], d2q: [e_b, e_g], iterations: 0 }, point))
    }
}

impl Stepper<2> for FourBarClosed {
    const WARM: bool = false;

    #[inline(always)]
    fn step(&self, phi: f64, guess: &[f64; 2]) -> Result<Step<2>, Failed> {
        let (step, point) = self.full(phi, guess)?;
        black_box(point);
        Ok(step)
    }

    #[inline(always)]
    fn step_summed(&self, phi: f64, guess: &[f64; 2]) -> Result<(Step<2>, f64), Failed> {
        let (step, p) = self.full(phi, guess)?;
        Ok((step, ((p[0] + p[1]) + (p[2] + p[3])) + (p[4] + p[5])))
    }
}

/// The gear-lever drive of the fixtures (`kinloop_fixtures::gear_lever::GearLever`): the pin
/// `P = l_c (sin a, cos a) + l_p (sin k a, cos k a)` with `k = 1 - u`, the rocker angle
/// `phi = atan2(P_x, P_y)` and the block's distance `s = |P|` (on the side `s > 0`), with the
/// analogs of the polar coordinates; the pin and its analogs go through `black_box` (`step`) or
/// into the lean harness's sum (`step_summed`). Angles are
/// moved to the guess's turn, as a sweep needs (both closed forms here do).
#[derive(Clone, Copy, Debug)]
pub struct GearLeverClosed {
    /// Length of the carrier.
    pub l_c: f64,
    /// Distance of the planet pin from the planet's centre.
    pub l_p: f64,
    /// Gear ratio: the pin's arm on the planet turns by `(1 - u) a` when the carrier turns by
    /// `a`.
    pub u: f64,
}

impl GearLeverClosed {
    /// The closed form of the gear-lever drive `m`.
    pub fn of(m: &GearLever) -> Self {
        GearLeverClosed { l_c: m.l_c, l_p: m.l_p, u: m.u }
    }
}

/// The gear-lever's pin at one carrier position: the pin `p`, its analogs `dp`, `ddp`, and its
/// squared distance `s2` and distance `s` from the rocker's pivot. Everything of a step but the
/// rocker angle, which a closed form makes by `atan2` and a hand-written sweep by increments.
#[derive(Clone, Copy, Debug)]
pub struct GearLeverPose {
    /// The pin.
    pub p: [f64; 2],
    /// Its velocity analog.
    pub dp: [f64; 2],
    /// Its acceleration analog.
    pub ddp: [f64; 2],
    /// `|p|^2`.
    pub s2: f64,
    /// `|p|`.
    pub s: f64,
}

impl GearLeverClosed {
    /// `k = 1 - u`: the planet arm's angle is `k alpha`.
    pub fn ratio(&self) -> f64 {
        1.0 - self.u
    }

    /// The pin at the carrier's sine `sa` and cosine `ca` and the planet arm's `sk`, `ck` (the
    /// test `s2 > 0` protects the division by the distance).
    #[inline(always)]
    pub fn pose(&self, sa: f64, ca: f64, sk: f64, ck: f64) -> Result<GearLeverPose, Failed> {
        let k = 1.0 - self.u;
        let p = [self.l_c * sa + self.l_p * sk, self.l_c * ca + self.l_p * ck];
        let dp = [self.l_c * ca + self.l_p * k * ck, -self.l_c * sa - self.l_p * k * sk];
        let ddp = [-self.l_c * sa - self.l_p * k * k * sk, -self.l_c * ca - self.l_p * k * k * ck];
        let s2 = p[0] * p[0] + p[1] * p[1];
        if s2.is_nan() || s2 <= 0.0 {
            return Err(Failed::new("gear-lever closed form: the pin is on the pivot"));
        }
        Ok(GearLeverPose { p, dp, ddp, s2, s: s2.sqrt() })
    }

    /// The step and the pin with its analogs `[x, y, x', y', x'', y'']` from the pin `q` and the
    /// rocker angle `phi`. The hand-written sweep
    /// ([`crate::hand_sweep::GearLeverSweep`]) computes with it what [`GearLeverClosed::full`]
    /// computes: they differ only in their trigonometry.
    #[inline(always)]
    pub fn finish(&self, q: &GearLeverPose, phi: f64) -> (Step<2>, [f64; 6]) {
        let GearLeverPose { p, dp, ddp, s2, s } = *q;
        let ds = (p[0] * dp[0] + p[1] * dp[1]) / s;
        let dphi = (dp[0] * p[1] - p[0] * dp[1]) / s2;
        let dds = (dp[0] * dp[0] + dp[1] * dp[1] + p[0] * ddp[0] + p[1] * ddp[1] - ds * ds) / s;
        let ddphi = (ddp[0] * p[1] - p[0] * ddp[1]) / s2 - 2.0 * dphi * ds / s;
        let pin = [p[0], p[1], dp[0], dp[1], ddp[0], ddp[1]];
        (Step { q: [s, phi], dq: [ds, dphi], d2q: [dds, ddphi], iterations: 0 }, pin)
    }

    /// The step at carrier angle `alpha` (the rocker angle on the turn of `guess`) and the pin
    /// with its analogs `[x, y, x', y', x'', y'']`.
    ///
    /// The formulas of [`GearLeverClosed::pose`] and [`GearLeverClosed::finish`], written out,
    /// as [`FourBarClosed::full`] (composed of those two: 3 instructions more a step).
    #[inline(always)]
    pub fn full(&self, alpha: f64, guess: &[f64; 2]) -> Result<(Step<2>, [f64; 6]), Failed> {
        let k = 1.0 - self.u;
        let (sa, ca) = alpha.sin_cos();
        let (sk, ck) = (k * alpha).sin_cos();
        let p = [self.l_c * sa + self.l_p * sk, self.l_c * ca + self.l_p * ck];
        let dp = [self.l_c * ca + self.l_p * k * ck, -self.l_c * sa - self.l_p * k * sk];
        let ddp = [-self.l_c * sa - self.l_p * k * k * sk, -self.l_c * ca - self.l_p * k * k * ck];
        let s2 = p[0] * p[0] + p[1] * p[1];
        if s2.is_nan() || s2 <= 0.0 {
            return Err(Failed::new("gear-lever closed form: the pin is on the pivot"));
        }
        let s = s2.sqrt();
        let phi = on_turn(p[0].atan2(p[1]), guess[1]);
        let ds = (p[0] * dp[0] + p[1] * dp[1]) / s;
        let dphi = (dp[0] * p[1] - p[0] * dp[1]) / s2;
        let dds = (dp[0] * dp[0] + dp[1] * dp[1] + p[0] * ddp[0] + p[1] * ddp[1] - ds * ds) / s;
        let ddphi = (ddp[0] * p[1] - p[0] * ddp[1]) / s2 - 2.0 * dphi * ds / s;
        let pin = [p[0], p[1], dp[0], dp[1], ddp[0], ddp[1]];
        Ok((Step { q: [s, phi], dq: [ds, dphi], d2q: [dds, ddphi], iterations: 0 }, pin))
    }
}

impl Stepper<2> for GearLeverClosed {
    const WARM: bool = false;

    #[inline(always)]
    fn step(&self, alpha: f64, guess: &[f64; 2]) -> Result<Step<2>, Failed> {
        let (step, pin) = self.full(alpha, guess)?;
        black_box(pin);
        Ok(step)
    }

    #[inline(always)]
    fn step_summed(&self, alpha: f64, guess: &[f64; 2]) -> Result<(Step<2>, f64), Failed> {
        let (step, p) = self.full(alpha, guess)?;
        Ok((step, ((p[0] + p[1]) + (p[2] + p[3])) + (p[4] + p[5])))
    }
}
