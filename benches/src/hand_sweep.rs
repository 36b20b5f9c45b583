//! The sweep recipe written by hand, leanest: the floor of a sweep's sample. Along equally
//! spaced inputs, the sines and cosines of the inputs are advanced by rotation through the fixed
//! step (angle addition), and the unknown angles by increments, the short Maclaurin series of
//! `asin` of the cross product of each new sine and cosine with the previous sample's; libm
//! (`sin_cos`, `asin`, `atan2`) computes only the re-synchronised samples: every `period`-th,
//! and the first of every turn. Everything else is the hand closed form's formulas
//! ([`ClosedForm::rods`], [`ClosedForm::assemble`], [`FourBarClosed::pose`],
//! [`FourBarClosed::finish`], [`GearLeverClosed::pose`], [`GearLeverClosed::finish`]), so a
//! sample computes the same twelve numbers, with the closed form's own assembly tests and no
//! other check: no prediction, no determinant signs, no step control
//! ([`crate::hand_check::Checked`] adds the checks kinloop's sweep makes on every step).
//!
//! The loop that drives a sweep along its turns is [`crate::lean::hand_sweep_turns`].

use std::f64::consts::{PI, TAU};

use crate::hand::{FourBarClosed, GearLeverClosed, on_turn};
use crate::rhombic::{ClosedForm, Params};
use crate::sweep::{Failed, Step};

/// Coefficients of the Maclaurin series `asin x = sum c_n x^(2n+1)`,
/// `c_n = (2n)! / (4^n (n!)^2 (2n + 1))`.
pub(crate) const ASIN: [f64; 8] =
    [1.0, 1.0 / 6.0, 3.0 / 40.0, 5.0 / 112.0, 35.0 / 1152.0, 63.0 / 2816.0, 231.0 / 13312.0, 143.0 / 10240.0];

/// `asin x` for a small `x` by the first `TERMS` terms of its series (`TERMS >= 1`); the
/// leading term is added last, so the sum is rounded once at the scale of `x`. The remainder is
/// below `c_TERMS |x|^(2 TERMS + 1) / (1 - x^2)`.
#[inline(always)]
pub fn asin_series<const TERMS: usize>(x: f64) -> f64 {
    let x2 = x * x;
    let mut tail = 0.0;
    for c in ASIN[1..TERMS].iter().rev() {
        tail = tail * x2 + c;
    }
    x + x * (x2 * tail)
}

/// The rotation of a sine and cosine by a fixed angle `h` as a small correction of each:
/// `sin(t + h) = s - (v s - w c)`, `cos(t + h) = c - (v c + w s)` with `w = sin h` and
/// `v = 1 - cos h = 2 sin^2(h / 2)`, both to their full relative precision. The plain form
/// `s cos h + c sin h` multiplies by a `cos h` rounded near 1, whose error (up to 5.5e-17)
/// scales the radius by the same factor every step: a drift that grows with the period. Measured
/// as [`PERIOD`] was (10^6 samples, 20,000 a turn), the plain form's positions deviate by up to
/// 1.3e-14 at a period of 80 and 4.6e-14 at 320 (the gear-lever), this form's by 4.7e-15 and
/// 3.7e-15; it costs two additions more per rotation.
#[derive(Clone, Copy, Debug)]
pub struct Rotation {
    w: f64,
    v: f64,
}

impl Rotation {
    /// The rotation by `h` (radians).
    pub fn new(h: f64) -> Self {
        let half = (0.5 * h).sin();
        Rotation { w: h.sin(), v: 2.0 * half * half }
    }

    /// `(sin(t + h), cos(t + h))` from `(sin t, cos t)`.
    #[inline(always)]
    pub fn turn(&self, s: f64, c: f64) -> (f64, f64) {
        (s - (self.v * s - self.w * c), c - (self.v * c + self.w * s))
    }
}

/// A sweep written by hand over turns of equally spaced inputs: each sample's step and output
/// point with its analogs (`NP` numbers, none for the rhombic drive).
pub trait HandSweep<const N: usize, const NP: usize>: Clone {
    /// Samples per turn: the inputs are `k 2 pi / turn`, `k = 0 .. turn - 1`.
    fn turn(&self) -> usize;
    /// The re-synchronisation period: every `period`-th sample (and the first of every turn) is
    /// computed with libm.
    fn period(&self) -> usize;
    /// The sample at input `x` computed with libm, as the hand closed form computes it; the
    /// carried values are set from it.
    fn sync(&mut self, x: f64) -> Result<(Step<N>, [f64; NP]), Failed>;
    /// The sample one step after the previous one, by rotation and increments.
    fn advance(&mut self) -> Result<(Step<N>, [f64; NP]), Failed>;
    /// The first sample of a sweep, at input `x`: [`HandSweep::sync`], unless the sweep has a
    /// carried state to set up that a sample does not judge (see
    /// [`crate::hand_check::Checked`]).
    #[inline(always)]
    fn start(&mut self, x: f64) -> Result<(Step<N>, [f64; NP]), Failed> {
        self.sync(x)
    }
    /// Whether the next sample must come from libm ([`HandSweep::sync`]) whatever the period:
    /// never, unless the sweep watches its conditioning (see [`crate::hand_check::Checked`]).
    /// A constant `false` costs the sweeps that do not nothing.
    #[inline(always)]
    fn exact_next(&self) -> bool {
        false
    }
}

/// The re-synchronisation period of every sweep here, chosen from the drift measured over 10^6
/// samples against the closed forms (the `hand_sweep` tests' `drift_by_period_and_terms`,
/// largest position deviation relative to `max(1, |value|)`, the three mechanisms): at 720
/// samples a turn 1.2e-15 / 1.6e-15 / 3.8e-15 (rhombic / four-bar / gear-lever) at 320 against
/// 1.3e-15 / 1.9e-15 / 7.9e-15 with a re-synchronisation only at the start of a turn; at 20,000
/// a turn 2.3e-15 / 2.7e-15 / 3.7e-15 at 320, 2.9e-15 / 6.3e-15 / 8.1e-15 at 2000 and up to
/// 1.4e-14 (over the 1e-14 promised) at 20,000. 320 keeps every position within half the
/// promise at both densities; a libm sample every 320 costs about two instructions a sample.
pub const PERIOD: usize = 320;

/// The step of a turn of `turn` samples.
fn step_of_turn(turn: usize) -> f64 {
    TAU / turn as f64
}

/// The rhombic drive's closed form ([`ClosedForm`]) as a sweep: the crank arms' sines and
/// cosines (`phi1` and `phi1 + gamma`) rotated, the rod angles `phi2`, `phi4` advanced by
/// `TERMS` terms of `asin`'s series.
#[derive(Clone, Debug)]
pub struct RhombicSweep<const TERMS: usize = RHOMBIC_TERMS> {
    closed: ClosedForm,
    turn: usize,
    period: usize,
    rotation: Rotation,
    /// `[s1, c1, sa, ca]` of the previous sample.
    crank: [f64; 4],
    /// `[s2, c2, s4, c4]` of the previous sample.
    pub(crate) rods: [f64; 4],
    phi2: f64,
    phi4: f64,
}

/// The series terms of the rod angles' increments: the largest increment along a turn of 720
/// samples is `0.346 h = 0.0031` (the largest `|phi4'|` times the step), where the first
/// neglected term, `5/112 x^7`, is 1e-19 (with 2 terms, `3/40 x^5` is 2e-14, and the angles
/// deviate by up to 1.6e-12 over 10^6 samples).
pub const RHOMBIC_TERMS: usize = 3;

impl<const TERMS: usize> RhombicSweep<TERMS> {
    /// The sweep of the drive `p` over turns of `turn` samples, re-synchronised every `period`;
    /// its first sample is at input 0 ([`HandSweep::sync`] computes it).
    pub fn new(p: &Params, turn: usize, period: usize) -> Self {
        RhombicSweep {
            closed: ClosedForm::new(p),
            turn,
            period,
            rotation: Rotation::new(step_of_turn(turn)),
            crank: [0.0; 4],
            rods: [0.0; 4],
            phi2: 0.0,
            phi4: 0.0,
        }
    }
}

impl<const TERMS: usize> HandSweep<4, 0> for RhombicSweep<TERMS> {
    fn turn(&self) -> usize {
        self.turn
    }

    fn period(&self) -> usize {
        self.period
    }

    #[inline(always)]
    fn sync(&mut self, x: f64) -> Result<(Step<4>, [f64; 0]), Failed> {
        let (s1, c1) = x.sin_cos();
        let (sa, ca) = (x + self.closed.gamma()).sin_cos();
        let rods = self.closed.rods(s1, sa)?;
        (self.phi2, self.phi4) = (rods[0].asin(), PI - rods[2].asin());
        (self.crank, self.rods) = ([s1, c1, sa, ca], rods);
        Ok((self.closed.assemble(self.crank, rods, self.phi2, self.phi4), []))
    }

    #[inline(always)]
    fn advance(&mut self) -> Result<(Step<4>, [f64; 0]), Failed> {
        let [s1, c1, sa, ca] = self.crank;
        let (s1, c1) = self.rotation.turn(s1, c1);
        let (sa, ca) = self.rotation.turn(sa, ca);
        let rods = self.closed.rods(s1, sa)?;
        let [s2, c2, s4, c4] = self.rods;
        // sin(phi_new - phi_old) = s_new c_old - c_new s_old.
        self.phi2 += asin_series::<TERMS>(rods[0] * c2 - rods[1] * s2);
        self.phi4 += asin_series::<TERMS>(rods[2] * c4 - rods[3] * s4);
        (self.crank, self.rods) = ([s1, c1, sa, ca], rods);
        Ok((self.closed.assemble(self.crank, rods, self.phi2, self.phi4), []))
    }
}

/// The four-bar's closed form ([`FourBarClosed`]) as a sweep: the crank's sine and cosine
/// rotated, the coupler's and rocker's angles advanced by `TERMS` terms of `asin`'s series.
#[derive(Clone, Debug)]
pub struct FourBarSweep<const TERMS: usize = FOUR_BAR_TERMS> {
    pub(crate) closed: FourBarClosed,
    turn: usize,
    period: usize,
    rotation: Rotation,
    /// `[s1, c1, sb, cb, sg, cg]` of the previous sample.
    pub(crate) sines: [f64; 6],
    pub(crate) beta: f64,
    gamma: f64,
}

/// The series terms of the angles' increments: the largest increment along a turn of 720
/// samples is `0.534 h = 0.0047` (the largest `|gamma'|` times the step), where the first
/// neglected term, `5/112 x^7`, is 2e-18 (with 2 terms, `3/40 x^5` is 2e-13, and the angles
/// deviate by up to 6e-12 over 10^6 samples).
pub const FOUR_BAR_TERMS: usize = 3;

impl<const TERMS: usize> FourBarSweep<TERMS> {
    /// The sweep of `closed` over turns of `turn` samples, re-synchronised every `period`, its
    /// angles on the turns of `guess` (the previous sample's, as a closed form's sweep has
    /// them); its first sample is at input 0 ([`HandSweep::sync`] computes it).
    pub fn new(closed: FourBarClosed, turn: usize, period: usize, guess: [f64; 2]) -> Self {
        FourBarSweep {
            closed,
            turn,
            period,
            rotation: Rotation::new(step_of_turn(turn)),
            sines: [0.0; 6],
            beta: guess[0],
            gamma: guess[1],
        }
    }
}

impl<const TERMS: usize> HandSweep<2, 6> for FourBarSweep<TERMS> {
    fn turn(&self) -> usize {
        self.turn
    }

    fn period(&self) -> usize {
        self.period
    }

    #[inline(always)]
    fn sync(&mut self, x: f64) -> Result<(Step<2>, [f64; 6]), Failed> {
        let (s1, c1) = x.sin_cos();
        let p = self.closed.pose(s1, c1)?;
        self.beta = on_turn(p.sb.atan2(p.cb), self.beta);
        self.gamma = on_turn(p.sg.atan2(p.cg), self.gamma);
        self.sines = [s1, c1, p.sb, p.cb, p.sg, p.cg];
        Ok(self.closed.finish(&p, self.beta, self.gamma))
    }

    #[inline(always)]
    fn advance(&mut self) -> Result<(Step<2>, [f64; 6]), Failed> {
        let [s1, c1, sb, cb, sg, cg] = self.sines;
        let (s1, c1) = self.rotation.turn(s1, c1);
        let p = self.closed.pose(s1, c1)?;
        // sin(angle_new - angle_old) = s_new c_old - c_new s_old.
        self.beta += asin_series::<TERMS>(p.sb * cb - p.cb * sb);
        self.gamma += asin_series::<TERMS>(p.sg * cg - p.cg * sg);
        self.sines = [s1, c1, p.sb, p.cb, p.sg, p.cg];
        Ok(self.closed.finish(&p, self.beta, self.gamma))
    }
}

/// The gear-lever's closed form ([`GearLeverClosed`]) as a sweep: the carrier's and the planet
/// arm's sines and cosines rotated (by `h` and `(1 - u) h`), the rocker angle advanced by
/// `TERMS` terms of `asin`'s series of the cross product of the pin's directions.
#[derive(Clone, Debug)]
pub struct GearLeverSweep<const TERMS: usize = GEAR_LEVER_TERMS> {
    pub(crate) closed: GearLeverClosed,
    turn: usize,
    period: usize,
    carrier: Rotation,
    arm: Rotation,
    /// `[sa, ca, sk, ck]` of the previous sample.
    sines: [f64; 4],
    /// The previous sample's pin divided by its distance.
    dir: [f64; 2],
    phi: f64,
}

/// The series terms of the rocker angle's increments: the largest increment along a turn of
/// 720 samples is `6.57 h = 0.057` (the largest `|phi'|`, where the pin passes closest to the
/// pivot, times the step), where the first neglected term, `231/13312 x^13`, is 1e-18 (with 5
/// terms, `63/2816 x^11` is 5e-16: measurable in the drift).
pub const GEAR_LEVER_TERMS: usize = 6;

impl<const TERMS: usize> GearLeverSweep<TERMS> {
    /// The sweep of `closed` over turns of `turn` samples, re-synchronised every `period`, the
    /// rocker angle on the turn of `guess[1]`; its first sample is at input 0
    /// ([`HandSweep::sync`] computes it).
    pub fn new(closed: GearLeverClosed, turn: usize, period: usize, guess: [f64; 2]) -> Self {
        let h = step_of_turn(turn);
        GearLeverSweep {
            closed,
            turn,
            period,
            carrier: Rotation::new(h),
            arm: Rotation::new(closed.ratio() * h),
            sines: [0.0; 4],
            dir: [0.0; 2],
            phi: guess[1],
        }
    }
}

impl<const TERMS: usize> HandSweep<2, 6> for GearLeverSweep<TERMS> {
    fn turn(&self) -> usize {
        self.turn
    }

    fn period(&self) -> usize {
        self.period
    }

    #[inline(always)]
    fn sync(&mut self, x: f64) -> Result<(Step<2>, [f64; 6]), Failed> {
        let (sa, ca) = x.sin_cos();
        let (sk, ck) = (self.closed.ratio() * x).sin_cos();
        let q = self.closed.pose(sa, ca, sk, ck)?;
        self.phi = on_turn(q.p[0].atan2(q.p[1]), self.phi);
        self.sines = [sa, ca, sk, ck];
        let inv = 1.0 / q.s;
        self.dir = [q.p[0] * inv, q.p[1] * inv];
        Ok(self.closed.finish(&q, self.phi))
    }

    #[inline(always)]
    fn advance(&mut self) -> Result<(Step<2>, [f64; 6]), Failed> {
        let [sa, ca, sk, ck] = self.sines;
        let (sa, ca) = self.carrier.turn(sa, ca);
        let (sk, ck) = self.arm.turn(sk, ck);
        let q = self.closed.pose(sa, ca, sk, ck)?;
        let inv = 1.0 / q.s;
        let dir = [q.p[0] * inv, q.p[1] * inv];
        // phi = atan2(x, y): sin(phi_new - phi_old) = x_new y_old - y_new x_old (unit vectors).
        self.phi += asin_series::<TERMS>(dir[0] * self.dir[1] - dir[1] * self.dir[0]);
        self.sines = [sa, ca, sk, ck];
        self.dir = dir;
        Ok(self.closed.finish(&q, self.phi))
    }
}
