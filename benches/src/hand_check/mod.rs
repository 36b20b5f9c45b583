//! The sweep recipe written by hand ([`crate::hand_sweep`]) WITH the checks kinloop's `Sweep`
//! makes on every step to stay on its branch: what those checks cost a hand author, against the
//! recipe without them. [`Checked`] wraps a hand sweep and judges each of its samples as
//! `Sweep::judge` judges a step, with kinloop's constants and `SweepConfig`'s defaults:
//!
//! * the prediction of each judged unknown from the previous sample's position, slope and
//!   curvature (the trapezoid of the two slopes), and its predicted slope;
//! * the determinant sign of every block the same as at the first sample (`Flip`);
//! * the smallest pivot ratio at least [`SINGULAR_PIVOT`]; below [`ROTATE_MIN_PIVOT`] the next
//!   sample comes from libm ([`HandSweep::exact_next`]) instead of the rotation;
//! * the slopes within `max_slope_err` of their prediction, and the slope-change bound (`long`);
//! * the closed-form angles within [`ANGLE_CAP`] of their prediction, and where a judged unknown
//!   is not such an angle (the gear-lever's length), every judged position within `max_dist`.
//!
//! A failed check ends the sweep with an error (where kinloop would halve the step) and records
//! which checks failed ([`Checked::fired`]). The checks read the sample and never write it: a
//! checked sweep computes the same numbers, bit for bit, as the sweep it wraps.
//!
//! The judged unknowns are kinloop's (`Mechanism::FOLLOWERS`, `CLOSED_FORM_ANGLES`; the
//! `hand_check` tests compare): the rhombic drive's rod angles `phi2`, `phi4` (its sliders
//! follow them), the four-bar's `beta`, `gamma`, the gear-lever's `s` and `phi`; in all three
//! they are a step's first two unknowns. The blocks' determinants and pivot ratios come from the
//! closed forms' own quantities ([`Branch::health`]).

use std::f64::consts::TAU;

use crate::hand_sweep::{FourBarSweep, GearLeverSweep, HandSweep, RhombicSweep};
use crate::sweep::{Failed, Step};

/// kinloop's `MAX_SLOPE_CHANGE`: the largest change of the judged slopes over a step, relative
/// to the largest slope (plus the floor of one unit per unit of input).
pub const MAX_SLOPE_CHANGE: f64 = 0.25;
/// kinloop's `ANGLE_CAP`: the largest distance (radians) of a closed-form angle from its
/// prediction.
pub const ANGLE_CAP: f64 = 1.0;
/// kinloop's `ROTATE_MIN_PIVOT`: below this smallest pivot ratio the next sample's sines and
/// cosines come from libm.
pub const ROTATE_MIN_PIVOT: f64 = 0.1;
/// `SweepConfig::corrector_rel`'s default.
pub const CORRECTOR_REL: f64 = 0.25;
/// `SweepConfig::corrector_abs`'s default.
pub const CORRECTOR_ABS: f64 = 1e-6;
/// `SweepConfig::singular_pivot`'s default.
pub const SINGULAR_PIVOT: f64 = 1e-6;

/// The bits of [`Checked::fired`]: which checks the failed sample failed.
pub mod fired {
    /// A block's determinant sign differs from the first sample's.
    pub const FLIP: u8 = 1;
    /// The smallest pivot ratio is below [`super::SINGULAR_PIVOT`].
    pub const PIVOT: u8 = 2;
    /// A judged position is farther than `max_dist` from its prediction.
    pub const DIST: u8 = 4;
    /// A judged slope is farther than `max_slope_err` from its prediction.
    pub const SLOPE: u8 = 8;
    /// A closed-form angle is farther than [`super::ANGLE_CAP`] from its prediction.
    pub const TURN: u8 = 16;
    /// The step is longer than the slope-change bound allows.
    pub const LONG: u8 = 32;
}

/// What a hand sweep gives the checks besides its samples: which of the judged unknowns (a
/// step's first two) are closed-form angles, its blocks' determinant signs and smallest pivot
/// ratio at the last sample, and the unit of its judged unknowns.
pub trait Branch<const N: usize, const NP: usize>: HandSweep<N, NP> {
    /// Per judged unknown (`q[0]`, `q[1]`): an angle a closed form gives (kinloop's
    /// `CLOSED_FORM_ANGLES`), judged within [`ANGLE_CAP`] of its prediction.
    const ANGLES: [bool; 2];
    /// Whether the judged positions are judged within `max_dist` of their prediction: where a
    /// judged unknown is not a closed-form angle (kinloop's `positions_judged`).
    const POSITIONS_JUDGED: bool = !(Self::ANGLES[0] & Self::ANGLES[1]);
    /// At the last sample (`step`): the determinant signs of the blocks (bit `b` set where block
    /// `b`'s determinant is negative) and the smallest pivot ratio of the blocks, each block's
    /// determinant over the product of its columns' norms; `unit` is [`Branch::pivot_unit`],
    /// computed once by the caller.
    fn health(&self, step: &Step<N>, unit: f64) -> (u8, f64);
    /// A constant of the pivot ratio that [`Branch::health`] is given rather than computing it
    /// every sample (the reciprocal of a lever floor; 1 where there is none).
    fn pivot_unit(&self) -> f64 {
        1.0
    }
    /// The units of the judged unknowns (kinloop's, one radian for an angle): the changes,
    /// distances and slopes of each are measured in its unit, as kinloop's judge measures them.
    fn judged_units(&self) -> [f64; 2];
}

/// A hand sweep `S` with kinloop's checks on every sample after its first (see the module
/// documentation). Its samples are `S`'s.
#[derive(Clone, Debug)]
pub struct Checked<S> {
    inner: S,
    /// The judged unknowns' positions, slopes and curvatures at the previous sample.
    q: [f64; 2],
    dq: [f64; 2],
    d2q: [f64; 2],
    /// The determinant signs of the first sample (kinloop carries them from its first sample).
    signs: u8,
    /// The last sample's smallest pivot ratio was below [`ROTATE_MIN_PIVOT`].
    exact: bool,
    /// The input step.
    h: f64,
    /// `corrector_abs` in the slopes' units: kinloop divides it by the length of a turn's path,
    /// `h (turn - 1)` (its sweep of a turn ends at the turn's last sample).
    slope_abs: f64,
    /// [`MAX_SLOPE_CHANGE`] times one unit per unit of input.
    slope_floor: f64,
    /// The reciprocals of [`Branch::judged_units`].
    inv_unit: [f64; 2],
    /// [`Branch::pivot_unit`].
    pivot_unit: f64,
    /// The checks the last failed sample failed ([`fired`]'s bits; 0 while none has failed).
    fired: u8,
    /// Samples that came from libm because the previous pivot ratio was small.
    exact_samples: usize,
}

/// The measures a sample is judged by, and their bounds (kinloop's `Prediction` and `judge`).
#[derive(Clone, Copy, Debug)]
struct Measures {
    signs: u8,
    pivot: f64,
    dist: f64,
    max_dist: f64,
    turn: f64,
    slope_err: f64,
    max_slope_err: f64,
    long: bool,
}

impl<S> Checked<S> {
    /// The sweep `s` with the checks; its first sample ([`HandSweep::start`]) sets the carried
    /// signs, as a sweep's first sample does.
    pub fn new<const N: usize, const NP: usize>(s: S) -> Self
    where
        S: Branch<N, NP>,
    {
        let turn = s.turn();
        let h = TAU / turn as f64;
        let span = h * (turn - 1) as f64;
        let slope_floor = MAX_SLOPE_CHANGE;
        let pivot_unit = s.pivot_unit();
        let inv_unit = s.judged_units().map(|u| 1.0 / u);
        Checked {
            inner: s,
            q: [0.0; 2],
            dq: [0.0; 2],
            d2q: [0.0; 2],
            signs: 0,
            exact: false,
            h,
            slope_abs: CORRECTOR_ABS / span,
            slope_floor,
            inv_unit,
            pivot_unit,
            fired: 0,
            exact_samples: 0,
        }
    }

    /// The checks the failed sample failed ([`fired`]'s bits), 0 while every sample passed.
    pub fn fired(&self) -> u8 {
        self.fired
    }

    /// The samples taken from libm because the previous sample's pivot ratio was below
    /// [`ROTATE_MIN_PIVOT`].
    pub fn exact_samples(&self) -> usize {
        self.exact_samples
    }

    /// The wrapped sweep, to change its carried state (the tests force a jump with it).
    pub fn inner_mut(&mut self) -> &mut S {
        &mut self.inner
    }

    /// Keeps the judged unknowns of the accepted sample `step` for the next prediction.
    #[inline(always)]
    fn keep<const N: usize>(&mut self, step: &Step<N>) {
        self.q = [step.q[0], step.q[1]];
        self.dq = [step.dq[0], step.dq[1]];
        self.d2q = [step.d2q[0], step.d2q[1]];
    }

    /// The measures of `step` against the prediction from the previous sample (kinloop's
    /// `predict` and `judge`, with one input: the step `h`, the slopes `q'`).
    #[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what makes a NaN too long
    #[inline(always)]
    fn measure<const N: usize, const NP: usize>(&self, step: &Step<N>) -> Measures
    where
        S: Branch<N, NP>,
    {
        let h = self.h;
        let (mut change, mut slope_change, mut slope) = (0.0f64, 0.0f64, 0.0f64);
        let (mut dist, mut turn, mut slope_err) = (0.0f64, 0.0f64, 0.0f64);
        for u in 0..2 {
            let slope0 = self.dq[u];
            // The slope's change over the step, and the unknown's by the trapezoid of the slopes.
            let bend = self.d2q[u] * h;
            let slope1 = slope0 + bend;
            let du = (0.5 * h) * (slope0 + slope1);
            let e = (step.q[u] - (self.q[u] + du)).abs();
            // In the unknown's unit (an angle's, one, is not multiplied by: kinloop's).
            let w = |v: f64| if S::ANGLES[u] { v } else { v * self.inv_unit[u] };
            change = change.max(w(du.abs()));
            slope_change = slope_change.max(w(bend.abs()));
            slope = slope.max(w(slope0.abs()));
            if S::POSITIONS_JUDGED {
                dist = dist.max(w(e));
            }
            if S::ANGLES[u] {
                turn = turn.max(e);
            }
            slope_err = slope_err.max(w((step.dq[u] - slope1).abs()));
        }
        let (signs, pivot) = self.inner.health(step, self.pivot_unit);
        Measures {
            signs,
            pivot,
            dist,
            max_dist: CORRECTOR_REL * change + CORRECTOR_ABS,
            turn,
            slope_err,
            max_slope_err: CORRECTOR_REL * (slope_change + 0.1 * slope) + self.slope_abs,
            // Negated: a NaN is too long.
            long: !(slope_change <= MAX_SLOPE_CHANGE * slope + self.slope_floor),
        }
    }

    /// Judges `step` (every check, one branch when all hold) and keeps it when it passes.
    #[inline(always)]
    fn judge<const N: usize, const NP: usize>(&mut self, step: &Step<N>) -> Result<(), Failed>
    where
        S: Branch<N, NP>,
    {
        let m = self.measure(step);
        let far = (m.pivot < SINGULAR_PIVOT)
            | (S::POSITIONS_JUDGED & (m.dist > m.max_dist))
            | (m.slope_err > m.max_slope_err)
            | (m.turn > ANGLE_CAP)
            | m.long;
        if (m.signs != self.signs) | far {
            return Err(self.fail(m));
        }
        self.keep(step);
        self.exact = m.pivot < ROTATE_MIN_PIVOT;
        Ok(())
    }

    /// Records which checks `m` fails.
    #[cold]
    #[inline(never)]
    fn fail(&mut self, m: Measures) -> Failed {
        let bit = |fails: bool, b: u8| if fails { b } else { 0 };
        self.fired = bit(m.signs != self.signs, fired::FLIP)
            | bit(m.pivot < SINGULAR_PIVOT, fired::PIVOT)
            | bit(m.dist > m.max_dist, fired::DIST)
            | bit(m.slope_err > m.max_slope_err, fired::SLOPE)
            | bit(m.turn > ANGLE_CAP, fired::TURN)
            | bit(m.long, fired::LONG);
        Failed::new(format!("checked hand sweep: the sample fails the checks {:#08b} ({m:?})", self.fired))
    }
}

impl<S: Branch<N, NP>, const N: usize, const NP: usize> HandSweep<N, NP> for Checked<S> {
    fn turn(&self) -> usize {
        self.inner.turn()
    }

    fn period(&self) -> usize {
        self.inner.period()
    }

    #[inline(always)]
    fn start(&mut self, x: f64) -> Result<(Step<N>, [f64; NP]), Failed> {
        let (step, point) = self.inner.start(x)?;
        let (signs, pivot) = self.inner.health(&step, self.pivot_unit);
        self.signs = signs;
        self.exact = pivot < ROTATE_MIN_PIVOT;
        self.keep(&step);
        Ok((step, point))
    }

    #[inline(always)]
    fn sync(&mut self, x: f64) -> Result<(Step<N>, [f64; NP]), Failed> {
        if self.exact {
            self.exact_samples += 1;
        }
        let (step, point) = self.inner.sync(x)?;
        self.judge(&step)?;
        Ok((step, point))
    }

    #[inline(always)]
    fn advance(&mut self) -> Result<(Step<N>, [f64; NP]), Failed> {
        let (step, point) = self.inner.advance()?;
        self.judge(&step)?;
        Ok((step, point))
    }

    #[inline(always)]
    fn exact_next(&self) -> bool {
        self.exact
    }
}

/// The rhombic drive: kinloop's blocks are each rod's angle (a scalar block on its loop's Y
/// projection) and its slider (a follower: a constant matrix). The rod angle's block has the
/// Jacobian `-l cos(phi)`, its column in the loop `l (sin phi, -cos phi)` of norm `l`: the
/// determinant's sign is the rod cosine's (`c2 > 0`, `c4 < 0` on the drive's branch) and the
/// pivot ratio is `|cos phi|` (kinloop's, over the column's largest entry, is
/// `|cos| / max(|sin|, |cos|)`: the same zero, the rod across its slide).
impl<const TERMS: usize> Branch<4, 0> for RhombicSweep<TERMS> {
    const ANGLES: [bool; 2] = [true, true];

    #[inline(always)]
    fn health(&self, _step: &Step<4>, _unit: f64) -> (u8, f64) {
        let [_, c2, _, c4] = self.rods;
        (u8::from(c2.is_sign_negative()) | (u8::from(c4.is_sign_negative()) << 1), c2.abs().min(c4.abs()))
    }
    fn judged_units(&self) -> [f64; 2] {
        [1.0; 2]
    }
}

/// The four-bar: one block, the dyad `(beta, gamma)` with the Jacobian columns `b (-sin beta,
/// cos beta)` and `c (sin gamma, -cos gamma)`, whose determinant is `b c sin(beta - gamma)`: its
/// sign is `sin(beta - gamma)`'s and the pivot ratio over the columns' norms `b c` is
/// `|sin(beta - gamma)|`, the transmission angle's sine (kinloop's, over the columns' largest
/// entries, differs by at most a factor 2 and has the same zeros: the change points).
impl<const TERMS: usize> Branch<2, 6> for FourBarSweep<TERMS> {
    const ANGLES: [bool; 2] = [true, true];

    #[inline(always)]
    fn health(&self, _step: &Step<2>, _unit: f64) -> (u8, f64) {
        let [_, _, sb, cb, sg, cg] = self.sines;
        let sbg = sb * cg - cb * sg;
        (u8::from(sbg.is_sign_negative()), sbg.abs())
    }
    fn judged_units(&self) -> [f64; 2] {
        [1.0; 2]
    }
}

/// The gear-lever: one block, `(s, phi)` with the columns `(sin phi, cos phi)` and
/// `s (cos phi, -sin phi)`, whose determinant is `-s`: its sign is that of `s`, and the pivot
/// ratio is `s` over the phi column's lever floor, the loop's other lengths `l_c + l_p` (as
/// kinloop raises that column's scale to its lever floor, so that the pin passing near the pivot,
/// where `phi` is undetermined, shows as singular: over its own norm `s` the ratio would be 1
/// everywhere). The length `s` is judged (kinloop: not a closed-form angle), in kinloop's unit of
/// a slide, its loop's lengths `l_c + l_p + s` at the sweep's start (kinloop takes its units
/// there): at input 0, where `s = l_c + l_p`, twice `l_c + l_p`.
impl<const TERMS: usize> Branch<2, 6> for GearLeverSweep<TERMS> {
    const ANGLES: [bool; 2] = [false, true];

    #[inline(always)]
    fn health(&self, step: &Step<2>, unit: f64) -> (u8, f64) {
        let s = step.q[0];
        (u8::from(s.is_sign_negative()), s.abs() * unit)
    }

    /// `1 / (l_c + l_p)`, the reciprocal of the rocker column's lever floor.
    fn pivot_unit(&self) -> f64 {
        1.0 / (self.closed.l_c + self.closed.l_p)
    }

    fn judged_units(&self) -> [f64; 2] {
        // The slide's: the loop's lengths with the slide's at input 0, where every sweep here
        // starts; the rocker's, one radian.
        [2.0 * (self.closed.l_c + self.closed.l_p), 1.0]
    }
}

#[cfg(test)]
mod tests;
