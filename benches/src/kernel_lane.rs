//! kinloop's generated kernel driven along equally spaced inputs by the hand sweep's
//! trigonometry, with no check and no judgment: what any sweep costs that calls the kernel once
//! a sample, however lean its driver.
//!
//! The kernel is the one kinloop's `Sweep` runs (`kinematics_step_sink` with its checks
//! deferred, writing its state in place). It is given the previous sample's positions as its
//! guess and a [`FixedStepTrig`] in place of the sweep's cache: the recipe of
//! [`crate::hand_sweep`] behind kinloop's `InputTrig` interface. The inputs' sines and cosines
//! are rotated by their fixed step, the unknown angles advanced from the previous sample by a
//! short `asin` series of a cross product, and libm computes the re-synchronised samples. What
//! the driver leaves out is everything a sweep adds to the kernel: the prediction, the branch
//! checks, step control.
//!
//! The numbers it computes are checked against the kernel with libm's sines and cosines
//! (`tests/kernel_lane.rs`), so the count it gives is the floor of a sweep built on the kernel:
//! with the checks of a sample on top, a sweep that reuses the kernel cannot reach what the
//! checked recipe by hand costs ([`crate::hand_check`]). See BENCHMARKS.md.

use std::f64::consts::TAU;

use kinloop::__gen::{ByValue, InputTrig};
use kinloop::{Kin, Mechanism, NewtonConfig};

use crate::hand_sweep::{ASIN, PERIOD, Rotation, asin_series};
use crate::sweep::{Failed, next_input};

/// Slots of a [`FixedStepTrig`]: of the inputs' arguments, of the parameter angles added to
/// them (asked as any argument), and of the unknown angles (a kernel's slot numbers; the benchmarks' mechanisms use
/// fewer). A slot beyond them is computed by libm at every sample.
const SLOTS: usize = 8;

/// The largest term the [`asin_series`] of an angle's increment may leave out (rad): a 64th of
/// an ulp of a one-radian angle. [`FixedStepTrig`] advances an angle by the series where its
/// first neglected term is below this, and asks libm otherwise.
pub const SERIES_TAIL: f64 = 3.5e-18;

/// The largest increment's sine that `terms` terms of [`asin_series`] (1 to 7) advance an angle
/// by: where the first term left out is [`SERIES_TAIL`].
pub fn series_range(terms: usize) -> f64 {
    (SERIES_TAIL / ASIN[terms]).powf(1.0 / (2 * terms + 1) as f64)
}

/// A kernel's sines, cosines and closed-form angles along equally spaced inputs, as the hand
/// sweep computes them (see the module documentation). Each argument's values are rotated by
/// its step, which the lane's first two samples measure (libm computes both); a parameter angle
/// (whose values the kernel adds to an input's, `add_angles`) is libm's at its first call and
/// kept, its argument never changing. Each closed-form angle is the previous sample's plus `TERMS` terms
/// of `asin` of the cross product of the new sine and cosine with the previous, or libm's where
/// that increment is too large for them.
///
/// A kernel that runs a sample twice (its checked re-run, where a deferred test failed) gets
/// the same values both times: an argument the same as the last call's gets its last values,
/// and so does an angle whose sine and cosine are the last call's (its increment is zero).
#[derive(Clone, Debug)]
pub struct FixedStepTrig<const TERMS: usize> {
    /// This sample comes from libm (the first of a turn, and every [`PERIOD`]-th).
    sync: bool,
    /// This sample comes from libm and measures each argument's step: the second of the lane.
    learn: bool,
    /// The steps are measured.
    learned: bool,
    /// Each argument's rotation by its step.
    rotation: [Rotation; SLOTS],
    /// Each argument at the lane's first sample. Its step is measured from there, where the
    /// arguments are their multiples of the first input step (`h`, `(1 - u) h`, exact but for
    /// one rounding of the step): measured later, the difference of two arguments near `2 pi`
    /// would carry their rounding, up to 4.4e-16 rad, into every rotation until the next sync
    /// (measured: the four-bar's positions then deviate by 1.7e-14 from libm's). An argument
    /// with a constant part would carry that part's rounding; the benchmarks' have none.
    first_arg: [f64; SLOTS],
    /// Each argument at the last call, and its sine and cosine.
    arg: [f64; SLOTS],
    sin_cos: [(f64, f64); SLOTS],
    /// Each closed-form angle's sine, cosine and value at the last call.
    angle: [(f64, f64, f64); SLOTS],
    /// The largest increment's sine the series is used for.
    series_range: f64,
}

impl<const TERMS: usize> FixedStepTrig<TERMS> {
    /// A cache whose first sample comes from libm.
    pub fn new() -> Self {
        FixedStepTrig {
            sync: true,
            learn: false,
            learned: false,
            rotation: [Rotation::new(0.0); SLOTS],
            first_arg: [0.0; SLOTS],
            arg: [f64::NAN; SLOTS],
            sin_cos: [(0.0, 1.0); SLOTS],
            angle: [(f64::NAN, f64::NAN, 0.0); SLOTS],
            series_range: series_range(TERMS),
        }
    }

    /// Sets up the next sample: from libm where `sync` holds, and the lane's second.
    #[inline(always)]
    pub fn next_sample(&mut self, sync: bool) {
        self.learn = !self.learned;
        self.learned = true;
        self.sync = sync;
    }
}

impl<const TERMS: usize> Default for FixedStepTrig<TERMS> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const TERMS: usize> InputTrig for FixedStepTrig<TERMS> {
    #[inline(always)]
    fn sin_cos(&mut self, slot: usize, arg: f64) -> (f64, f64) {
        if slot >= SLOTS {
            return arg.sin_cos();
        }
        if arg == self.arg[slot] {
            return self.sin_cos[slot];
        }
        let values = if self.learn {
            self.rotation[slot] = Rotation::new(arg - self.first_arg[slot]);
            arg.sin_cos()
        } else if self.sync {
            if !self.learned {
                self.first_arg[slot] = arg;
            }
            arg.sin_cos()
        } else {
            let (s, c) = self.sin_cos[slot];
            self.rotation[slot].turn(s, c)
        };
        (self.arg[slot], self.sin_cos[slot]) = (arg, values);
        values
    }

    #[inline(always)]
    fn angle(&mut self, slot: usize, s: f64, c: f64, exact: impl FnOnce() -> f64) -> f64 {
        if slot >= SLOTS {
            return exact();
        }
        let (s0, c0, q0) = self.angle[slot];
        if s == s0 && c == c0 {
            return q0;
        }
        // sin(q - q0) = s c0 - c s0.
        let x = s * c0 - c * s0;
        let q = if !(self.sync | self.learn) && x.abs() <= self.series_range {
            q0 + asin_series::<TERMS>(x)
        } else {
            exact()
        };
        self.angle[slot] = (s, c, q);
        q
    }
}

/// Each of `steps` samples after the first (at input 0, from `guess`) of the kernel of `m` over
/// turns of `turn` equally spaced inputs, each from the previous sample's positions with a
/// [`FixedStepTrig`]: `f(acc, state)` folds the states. The first sample of every turn and
/// every [`PERIOD`]-th come from libm, as in the hand sweep.
#[inline(always)]
pub fn kernel_lane_fold<M, A, const N: usize, const NO: usize, const TERMS: usize>(
    m: &M,
    turn: usize,
    guess: [f64; N],
    steps: usize,
    init: A,
    mut f: impl FnMut(A, &Kin<N, 1, NO>) -> A,
) -> Result<A, Failed>
where
    M: Mechanism<N, 1, NO>,
{
    let h = TAU / turn as f64;
    let cfg = NewtonConfig::default();
    let mut trig = FixedStepTrig::<TERMS>::new();
    let mut kin =
        m.kinematics_step_sink::<_, ByValue, false>(&[0.0], &guess, &cfg, &mut trig, ByValue).map_err(Failed::new)?;
    let (mut k, mut age, mut acc) = (0usize, 0usize, init);
    for _ in 0..steps {
        let x = next_input(&mut k, turn, h);
        age += 1;
        let sync = k == 0 || age == PERIOD;
        if sync {
            age = 0;
        }
        trig.next_sample(sync);
        let guess = kin.q;
        // Written in place, as a sweep's kernel writes its state.
        m.kinematics_step_sink::<_, &mut Kin<N, 1, NO>, false>(&[x], &guess, &cfg, &mut trig, &mut kin)
            .map_err(Failed::new)?;
        acc = f(acc, &kin);
    }
    Ok(acc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At the end of its range, the series with `TERMS` terms is within the tail it leaves
    /// out (plus two roundings of the result) of libm's `asin`.
    fn series_at_range<const TERMS: usize>() {
        let x = FixedStepTrig::<TERMS>::new().series_range;
        let left_out = ASIN[TERMS] * x.powi(2 * TERMS as i32 + 1);
        assert!((left_out - SERIES_TAIL).abs() <= 1e-12 * SERIES_TAIL, "{TERMS} terms: {left_out}");
        let err = (asin_series::<TERMS>(x) - x.asin()).abs();
        assert!(err <= 2.0 * SERIES_TAIL + 2.0 * f64::EPSILON * x, "{TERMS} terms at {x}: {err}");
    }

    #[test]
    fn the_series_range_leaves_out_the_tail() {
        series_at_range::<3>();
        series_at_range::<6>();
    }

    #[test]
    fn after_two_libm_samples_values_are_rotated_and_angles_advanced() {
        let mut trig = FixedStepTrig::<3>::new();
        let (h, q) = (1e-3, 0.7f64);
        let mut exact_calls = 0;
        // The sync and the learning sample: libm's values, libm's angles.
        for k in 0..2 {
            let x = h * k as f64;
            assert_eq!(trig.sin_cos(0, 2.0 * x), (2.0 * x).sin_cos());
            let (s, c) = (q + x).sin_cos();
            trig.angle(1, s, c, || {
                exact_calls += 1;
                q + x
            });
            trig.next_sample(false);
        }
        assert_eq!(exact_calls, 2);
        for k in 2..300 {
            let x = h * k as f64;
            // The argument `2 x` rotated by the step it took, `2 h`.
            let rotated = trig.sin_cos(0, 2.0 * x);
            let (s_want, c_want) = (2.0 * x).sin_cos();
            assert!((rotated.0 - s_want).abs() <= 1e-14 && (rotated.1 - c_want).abs() <= 1e-14, "sample {k}");
            // The angle `q + x` by the series of its increment: libm is not asked.
            let (s, c) = (q + x).sin_cos();
            let got = trig.angle(1, s, c, || panic!("libm asked at sample {k}"));
            assert!((got - (q + x)).abs() <= 1e-14, "sample {k}: {got}");
            // A kernel's re-run of the sample gets the same values.
            assert_eq!(trig.sin_cos(0, 2.0 * x), rotated, "re-run of sample {k}");
            assert_eq!(trig.angle(1, s, c, || panic!("libm asked at sample {k}")), got, "re-run of sample {k}");
            trig.next_sample(false);
        }
        // An increment beyond the series' range goes to libm.
        let (s, c) = (q + 1.0).sin_cos();
        assert_eq!(trig.angle(1, s, c, || q + 1.0), q + 1.0);
    }
}
