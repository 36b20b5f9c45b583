//! Sines and cosines of the arguments a kernel computes before any unknown: the input angles
//! and expressions of inputs and parameters (`phi1 + gamma`).
//!
//! A generated kernel asks an [`InputTrig`] for them, by slot (one per argument). A point solve
//! passes [`Libm`]: the standard library's `sin_cos`. A sweep passes its [`Rotating`] cache: its
//! inputs move by small steps, so the new values are the previous ones rotated by the change of
//! the argument, `sin(a + d) = sin a cos d + cos a sin d`, with `sin d` and `cos d` of the small
//! `d` from short polynomials. That costs a fraction of a libm call. Every [`RESYNC`] rotations,
//! and whenever the argument jumps, libm computes the values afresh, so rounding errors never
//! accumulate beyond a few units in the last place (measured in the tests below).

/// Where a generated kernel gets the sine and cosine of an argument free of the unknowns.
pub trait InputTrig {
    /// `(sin arg, cos arg)`; `slot` identifies the argument within the kernel (the same
    /// expression of the inputs and parameters at every call).
    fn sin_cos(&mut self, slot: usize, arg: f64) -> (f64, f64);
}

/// The standard library's `sin_cos`, for a kernel called without a cache.
#[derive(Clone, Copy, Debug, Default)]
pub struct Libm;

impl InputTrig for Libm {
    #[inline(always)]
    fn sin_cos(&mut self, _slot: usize, arg: f64) -> (f64, f64) {
        arg.sin_cos()
    }
}

/// Largest change of an argument followed by rotation (`2^-5` rad, 1.8 degrees); a larger one
/// is computed by libm. On `|d| <= 2^-5` the polynomials below are exact to far below an ulp:
/// the first omitted terms are `d^9 / 9!` (2.6e-18 of `sin d`) and `d^10 / 10!` (2.5e-22).
pub const MAX_ROTATION: f64 = 0.031_25;

/// Rotations between two libm evaluations of a slot: each rotation adds at most about one unit
/// in the last place to the values (a rotation keeps the error it is given), so a slot is never
/// more than this many units off libm's values.
pub const RESYNC: u32 = 16;

/// Slots a [`Rotating`] cache holds; a kernel's further arguments are computed by libm.
pub const SLOTS: usize = 8;

/// One argument's last values.
#[derive(Clone, Copy, Debug)]
struct Slot {
    arg: f64,
    sin: f64,
    cos: f64,
    /// Rotations since libm last computed the values.
    age: u32,
}

/// A sweep's cache of the sines and cosines of its kernel's input arguments (see the module
/// documentation).
#[derive(Clone, Copy, Debug)]
pub struct Rotating {
    slots: [Slot; SLOTS],
    /// Every value from libm (see [`Rotating::exact`]).
    exact: bool,
}

impl Default for Rotating {
    fn default() -> Self {
        // A NaN argument makes the first call of every slot go to libm.
        Rotating { slots: [Slot { arg: f64::NAN, sin: 0.0, cos: 1.0, age: 0 }; SLOTS], exact: false }
    }
}

impl Rotating {
    /// Whether the following calls take every value from libm: near a singular position the
    /// positions amplify the last bits of the inputs' sines and cosines, and there a few units
    /// in the last place more (a rotation's) would cost precision a point solve has.
    #[inline(always)]
    pub fn exact(&mut self, exact: bool) {
        self.exact = exact;
    }
}

/// `(sin d, cos d - 1)` for `|d| <= MAX_ROTATION` (Taylor polynomials in Horner form; `cos d - 1`
/// keeps the small part of the cosine exact in the rotation).
#[inline(always)]
fn small_sin_cosm1(d: f64) -> (f64, f64) {
    let d2 = d * d;
    let s = d + d * d2 * (-1.0 / 6.0 + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0)));
    let cm1 = d2 * (-0.5 + d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0 + d2 * (1.0 / 40320.0))));
    (s, cm1)
}

impl InputTrig for Rotating {
    #[inline(always)]
    fn sin_cos(&mut self, slot: usize, arg: f64) -> (f64, f64) {
        let Some(s) = self.slots.get_mut(slot) else {
            return arg.sin_cos();
        };
        let d = arg - s.arg;
        if d == 0.0 {
            return (s.sin, s.cos);
        }
        if d.abs() <= MAX_ROTATION && s.age < RESYNC && !self.exact {
            let (sd, cm1) = small_sin_cosm1(d);
            let (sin, cos) = (s.sin, s.cos);
            s.sin = sin + (sin * cm1 + cos * sd);
            s.cos = cos + (cos * cm1 - sin * sd);
            s.age += 1;
        } else {
            // Also a NaN `d`: the first call, or a non-finite argument (libm's NaN, as ever).
            (s.sin, s.cos) = arg.sin_cos();
            s.age = 0;
        }
        s.arg = arg;
        (s.sin, s.cos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift), so the test needs no dependency.
    fn uniform(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Walks of random small steps (forward, backward, repeated, some beyond the rotation
    /// range) over many turns: the rotated values stay within 8e-16 of libm's, a few units in
    /// the last place of values up to 1 (the bound grows with `RESYNC`).
    #[test]
    fn rotated_values_stay_within_a_few_ulps_of_libm() {
        let mut state = 0x9e37_79b9_7f4a_7c15;
        let mut worst = 0.0f64;
        for walk in 0..200 {
            let mut cache = Rotating::default();
            let mut arg = 10.0 * (uniform(&mut state) - 0.5) + walk as f64;
            let scale = [1e-4, 1e-3, 8.7e-3, 0.03, 0.05][walk % 5];
            for _ in 0..2000 {
                let u = uniform(&mut state);
                arg += if u < 0.05 { 0.0 } else { scale * (2.0 * uniform(&mut state) - 0.7) };
                let (s, c) = cache.sin_cos(0, arg);
                let (sl, cl) = arg.sin_cos();
                worst = worst.max((s - sl).abs()).max((c - cl).abs());
            }
        }
        assert!(worst <= 8e-16, "worst deviation from libm {worst:e}");
        assert!(worst > 0.0, "the walks must have rotated");
    }

    /// The first call, a jump, a non-finite argument and slots beyond the cache are libm's own.
    #[test]
    fn first_calls_jumps_and_overflowing_slots_are_libm() {
        let mut cache = Rotating::default();
        assert_eq!(cache.sin_cos(3, 0.7), 0.7f64.sin_cos());
        assert_eq!(cache.sin_cos(3, 0.7 + 2.0 * MAX_ROTATION), (0.7 + 2.0 * MAX_ROTATION).sin_cos());
        assert_eq!(cache.sin_cos(SLOTS, 0.3), 0.3f64.sin_cos());
        let (s, c) = cache.sin_cos(3, f64::NAN);
        assert!(s.is_nan() && c.is_nan());
        // After a NaN the slot recovers with libm's values.
        assert_eq!(cache.sin_cos(3, 0.2), 0.2f64.sin_cos());
        assert_eq!(Libm.sin_cos(0, 1.5), 1.5f64.sin_cos());
    }

    /// An exact cache computes every new argument with libm.
    #[test]
    fn an_exact_cache_is_libm() {
        let (mut exact, mut rotating) = (Rotating::default(), Rotating::default());
        exact.exact(true);
        let mut differs = 0;
        for k in 0..RESYNC {
            let arg = 1.0 + 0.001 * f64::from(k);
            assert_eq!(exact.sin_cos(0, arg), arg.sin_cos());
            differs += usize::from(rotating.sin_cos(0, arg) != arg.sin_cos());
        }
        assert!(differs > 0, "the other cache rotates (and differs in the last bits somewhere)");
    }

    /// Slots are independent, and a repeated argument returns the stored values unchanged.
    #[test]
    fn slots_are_independent_and_repeats_are_free() {
        let mut cache = Rotating::default();
        let a = cache.sin_cos(0, 1.0);
        let b = cache.sin_cos(1, -2.0);
        let a2 = cache.sin_cos(0, 1.001);
        assert_eq!(cache.sin_cos(1, -2.0), b);
        assert_eq!(cache.sin_cos(0, 1.001), a2);
        assert_ne!(a, a2);
        assert!((a2.0 - 1.001f64.sin()).abs() <= 2.3e-16 && (a2.1 - 1.001f64.cos()).abs() <= 2.3e-16);
    }
}
