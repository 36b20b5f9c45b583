//! The four-bar's sweep loop as the macro would emit it, written by hand from the four-bar's
//! expansion: the kernel's own formulas and kinloop's run-time pieces (the deferred dyad roots,
//! `Inverse2` for the analogs, its pivot ratio and determinant sign as the block's health),
//! with the carried values as the loop's locals and the sweep's checks of every sample
//! ([`crate::hand_check::Checked`]). It measures what an emitted closed-form sweep path would
//! cost with kinloop's pieces, against the checked recipe by hand (the hand closed form's own
//! formulas) and the general `Sweep`. Not a library path: the numbers are checked against the
//! kernel with libm (`tests/kernel_lane.rs`), the cost measured by `closed_form_step`'s
//! `four-bar-lane-sketch`.
//!
//! What it carries from sample to sample, as an emitted loop would: the crank's sine and cosine
//! (rotated by the fixed step), the angles' sines, cosines and values (advanced by the
//! increments' series, or by libm's `atan2` where an increment leaves the series' range), and
//! the positions, from which the dyad's branch flag is taken at every sample as the kernel takes
//! it from its guess.
//!
//! With `LEAN`, the changes such a path could make to those pieces without changing its
//! formulas, measured rather than estimated: the dyad's branch flag taken from the positions at
//! the libm samples only and carried between them; the circles intersected by the plain root
//! formula (`dyad_roots_deferred`, without the dyad's cancellation test, which a path that hands
//! every sample near a limit position to the general step need not make); and the analogs solved
//! by the dyad's own determinant, `b c sin(beta - gamma)` (its columns' norms are the constant
//! link lengths `b` and `c`, so `|sin(beta - gamma)|` is its pivot ratio), in place of
//! `Inverse2`, whose pivot ratio divides by the columns' largest entries. The same numbers to
//! the rounding.

use kinloop::__gen::{Factor, Inverse2, dyad_of_deferred, dyad_roots_deferred, reduce_turn, unwrap_to_turn};
use kinloop_fixtures::FourBar;

use crate::hand_check::Branch;
use crate::hand_sweep::{HandSweep, Rotation, asin_series};
use crate::kernel_lane::series_range;
use crate::sweep::{Failed, Step};

/// The four-bar's emitted sweep loop, sketched (see the module documentation); `LEAN` carries
/// the branch flag, intersects the circles by the plain root formula and solves the analogs by
/// the dyad's own determinant.
#[derive(Clone, Debug)]
pub struct FourBarLaneSketch<const TERMS: usize, const LEAN: bool = false> {
    m: FourBar,
    turn: usize,
    period: usize,
    rotation: Rotation,
    /// `[s_phi, c_phi, sin beta, cos beta, sin gamma, cos gamma]` of the previous sample.
    sines: [f64; 6],
    q: [f64; 2],
    /// The analogs' block at the last sample: its determinant's sign and pivot ratio.
    negative_det: bool,
    pivot: f64,
    /// The largest increment's sine the series is used for.
    range: f64,
    /// `NewtonConfig::singular_tol`'s default, the kernel's end test of the pivot.
    singular_tol: f64,
    /// The dyad's branch flag of the last libm sample (`LEAN`).
    flip: bool,
}

impl<const TERMS: usize, const LEAN: bool> FourBarLaneSketch<TERMS, LEAN> {
    /// The sweep of `m` over turns of `turn` samples, libm every `period`, from the angles
    /// `guess` (the branch).
    pub fn new(m: FourBar, turn: usize, period: usize, guess: [f64; 2]) -> Self {
        FourBarLaneSketch {
            m,
            turn,
            period,
            rotation: Rotation::new(std::f64::consts::TAU / turn as f64),
            sines: [0.0; 6],
            q: guess,
            negative_det: false,
            pivot: 0.0,
            range: series_range(TERMS),
            singular_tol: kinloop::NewtonConfig::default().singular_tol,
            flip: false,
        }
    }

    /// A sample from the crank's sine and cosine: the kernel's formulas; the angles by `angle`
    /// from their new sines and cosines.
    #[inline(always)]
    fn sample(
        &mut self,
        (sin_phi, cos_phi): (f64, f64),
        sync: bool,
        angle: impl Fn(&Self, usize, f64, f64) -> f64,
    ) -> Result<(Step<2>, [f64; 6]), Failed> {
        let FourBar { a, b, c, d } = self.m;
        // The dyad's branch flag from the previous positions, as the kernel's from its guess
        // (`LEAN`: at the libm samples only, carried between them).
        let flip = if !LEAN {
            (b * -c) * reduce_turn(self.q[1] - self.q[0]) < 0.0
        } else if sync {
            self.flip = (b * -c) * reduce_turn(self.q[1] - self.q[0]) < 0.0;
            self.flip
        } else {
            self.flip
        };
        let a_cos_phi = a * cos_phi;
        let a_sin_phi = a * sin_phi;
        let neg_c = -c;
        let t53 = a_cos_phi - d;
        let l1 = neg_c * neg_c;
        let cc = 0.5 * ((l1 - b * b) - (t53 * t53 + a_sin_phi * a_sin_phi));
        let dyad = [b * t53, b * a_sin_phi, t53, a_sin_phi, b * b, l1];
        // `LEAN`: the circles intersected by the plain root formula (`a² + b² - c²` as it comes),
        // without the dyad's cancellation test and its triangle of the lengths.
        let (cos_beta, sin_beta) =
            if LEAN { dyad_roots_deferred(dyad[0], dyad[1], cc, flip) } else { dyad_of_deferred(dyad, cc, flip) };
        let vx = t53 + b * cos_beta;
        let vy = a_sin_phi + b * sin_beta;
        let il1 = -1.0 / l1;
        let cos_gamma = neg_c * vx * il1;
        let sin_gamma = neg_c * vy * il1;
        let q_beta = angle(self, 0, sin_beta, cos_beta);
        let q_gamma = angle(self, 1, sin_gamma, cos_gamma);
        let b_cos_beta = b * cos_beta;
        let b_sin_beta = b * sin_beta;
        let j = [[-b_sin_beta, c * sin_gamma], [b_cos_beta, -(c * cos_gamma)]];
        let lu =
            if LEAN { Analogs::dyad(&j, b * c, sin_beta * cos_gamma - cos_beta * sin_gamma) } else { Analogs::of(&j) };
        let neg_a_cos_phi = -a_cos_phi;
        let [dq_beta, dq_gamma] = lu.solve([a_sin_phi, neg_a_cos_phi]);
        let t70 = sin_beta * dq_beta;
        let t72 = cos_beta * dq_beta;
        let t86 = dq_beta * t72;
        let t87 = dq_beta * t70;
        let t94 = dq_gamma * (cos_gamma * dq_gamma);
        let t95 = dq_gamma * (sin_gamma * dq_gamma);
        let r0 = -((neg_a_cos_phi - b * t86) + c * t94);
        let r1 = -((-a_sin_phi - b * t87) + c * t95);
        let [d2q_beta, d2q_gamma] = lu.solve([r0, r1]);
        let point = [
            a_cos_phi + b_cos_beta,
            a_sin_phi + b_sin_beta,
            -a_sin_phi - b * t70,
            a_cos_phi + b * t72,
            neg_a_cos_phi - b * (t86 + sin_beta * d2q_beta),
            b * (cos_beta * d2q_beta - t87) - a_sin_phi,
        ];
        // The kernel's end test: every value finite (a failed root is NaN) and the block not
        // singular (a factorisation reports a NaN pivot ratio as 0).
        let sum = ((d2q_gamma + point[0]) + (point[2] + point[4])) + ((point[1] + point[3]) + point[5]);
        let sum = sum + (q_beta + q_gamma) + (dq_beta + dq_gamma) + d2q_beta;
        if !sum.is_finite() || lu.pivot_ratio() < self.singular_tol {
            return Err(Failed::new("four-bar lane: the kernel's end test failed"));
        }
        self.sines = [sin_phi, cos_phi, sin_beta, cos_beta, sin_gamma, cos_gamma];
        self.q = [q_beta, q_gamma];
        self.negative_det = lu.negative_det();
        self.pivot = lu.pivot_ratio();
        Ok((Step { q: self.q, dq: [dq_beta, dq_gamma], d2q: [d2q_beta, d2q_gamma], iterations: 0 }, point))
    }
}

impl<const TERMS: usize, const LEAN: bool> HandSweep<2, 6> for FourBarLaneSketch<TERMS, LEAN> {
    fn turn(&self) -> usize {
        self.turn
    }

    fn period(&self) -> usize {
        self.period
    }

    #[inline(always)]
    fn sync(&mut self, x: f64) -> Result<(Step<2>, [f64; 6]), Failed> {
        self.sample(x.sin_cos(), true, |lane, u, s, c| unwrap_to_turn(s.atan2(c), lane.q[u]))
    }

    #[inline(always)]
    fn advance(&mut self) -> Result<(Step<2>, [f64; 6]), Failed> {
        let [s, c, ..] = self.sines;
        let sc = self.rotation.turn(s, c);
        self.sample(sc, false, |lane, u, s, c| {
            let (s0, c0) = (lane.sines[2 + 2 * u], lane.sines[3 + 2 * u]);
            let x = s * c0 - c * s0;
            if x.abs() <= lane.range {
                lane.q[u] + asin_series::<TERMS>(x)
            } else {
                unwrap_to_turn(s.atan2(c), lane.q[u])
            }
        })
    }
}

/// The health the general sweep judges: the block's determinant sign and pivot ratio, as the
/// kernel notes them.
impl<const TERMS: usize, const LEAN: bool> Branch<2, 6> for FourBarLaneSketch<TERMS, LEAN> {
    const ANGLES: [bool; 2] = [true, true];

    #[inline(always)]
    fn health(&self, _step: &Step<2>, _unit: f64) -> (u8, f64) {
        (u8::from(self.negative_det), self.pivot)
    }

    fn judged_units(&self) -> [f64; 2] {
        [1.0; 2]
    }
}

/// The sketch's 2x2 analog block: kinloop's `Inverse2`, or (`LEAN`) the dyad's own inverse by
/// its determinant `b c sin(beta - gamma)`, its pivot ratio `|sin(beta - gamma)|`.
enum Analogs {
    Inverse(Inverse2),
    Dyad { j: [[f64; 2]; 2], inv_det: f64, pivot: f64, negative: bool },
}

impl Analogs {
    #[inline(always)]
    fn of(j: &[[f64; 2]; 2]) -> Self {
        Analogs::Inverse(Inverse2::in_cols(j, [[], []]))
    }

    /// The block `j` of a dyad whose columns' norms multiply to `lengths` (`b c`), with
    /// `sin(beta - gamma) = sin_diff`: `det j = lengths sin_diff`.
    #[inline(always)]
    fn dyad(j: &[[f64; 2]; 2], lengths: f64, sin_diff: f64) -> Self {
        let det = lengths * sin_diff;
        Analogs::Dyad { j: *j, inv_det: 1.0 / det, pivot: sin_diff.abs(), negative: det < 0.0 }
    }

    /// Solves `j z = r` (Cramer's rule by the reciprocal determinant, for the dyad).
    #[inline(always)]
    fn solve(&self, r: [f64; 2]) -> [f64; 2] {
        match self {
            Analogs::Inverse(lu) => {
                let [[z0], [z1]] = lu.solve_cols([[r[0]], [r[1]]]);
                [z0, z1]
            }
            Analogs::Dyad { j, inv_det, .. } => {
                [(r[0] * j[1][1] - j[0][1] * r[1]) * inv_det, (j[0][0] * r[1] - r[0] * j[1][0]) * inv_det]
            }
        }
    }

    #[inline(always)]
    fn pivot_ratio(&self) -> f64 {
        match self {
            Analogs::Inverse(lu) => lu.pivot_ratio(),
            // NaN (a failed root) is 0, as `Inverse2` reports it.
            Analogs::Dyad { pivot, .. } => {
                if pivot.is_nan() {
                    0.0
                } else {
                    *pivot
                }
            }
        }
    }

    #[inline(always)]
    fn negative_det(&self) -> bool {
        match self {
            Analogs::Inverse(lu) => lu.negative_det(),
            Analogs::Dyad { negative, .. } => *negative,
        }
    }
}
