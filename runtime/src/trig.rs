//! Sines and cosines that a kernel need not take from libm: those of the arguments it computes
//! before any unknown (the input angles, expressions of inputs and parameters: `phi1 + gamma`),
//! and, in a Newton block's later evaluations, those of its unknowns' angles ([`NearTrig`]).
//!
//! A generated kernel asks an [`InputTrig`] for them, by slot (one per argument). A point solve
//! passes [`Libm`]: the standard library's `sin_cos`. A sweep passes its [`Rotating`] cache: its
//! inputs move by small steps, so the new values are the previous ones rotated by the change of
//! the argument, `sin(a + d) = sin a cos d + cos a sin d`, with `sin d` and `cos d` of the small
//! `d` from short polynomials (at equally spaced samples `d` repeats up to rounding, and the last
//! step's values are reused with a first-order correction, to far below an ulp). That costs a
//! fraction of a libm call. Every [`RESYNC`] rotations, and whenever the argument jumps, libm
//! computes the values afresh, so rounding errors never accumulate beyond a few units in the
//! last place (measured in the tests below). An argument that is such an angle plus a parameter
//! angle or a constant (`phi1 + gamma`) is not rotated a second time: its values come by angle
//! addition from the angle's and the offset's ([`add_angles`]): every generated function computes
//! such a sum so (the offset's sine and cosine are of its own slot, which a sweep's cache computes
//! once, and which a caller's loop over the inputs computes once), and so does the run-time
//! model, so that a point solve, a sweep's sample and the model agree on them.
//!
//! A closed-form block gets the sine and cosine of its unknown angle from its equation, and the
//! angle itself from libm's `atan2`, `acos` or `asin`. In a sweep the cache gives it instead as
//! `q_a + asin(sin(q - q_a))` from an anchor `q_a` that libm computed, by a short polynomial (the
//! difference stays small for several steps). Each angle is one anchor's plus one well
//! conditioned correction, so nothing accumulates: the angles are within a few ulps of libm's.
//!
//! A Newton block's evaluation asks its solve's [`NearTrig`] for the sines and cosines of its
//! angles: the guess's evaluation seeds it with libm's, and each later one (Newton's
//! corrections are small, soon very small) rotates the previous values, at most
//! [`NEWTON_RESYNC`] times before libm again. Nothing carries over from one solve to the next.

use core::cell::UnsafeCell;

/// Where a generated kernel gets the sine and cosine of an argument free of the unknowns.
pub trait InputTrig {
    /// `(sin arg, cos arg)`; `slot` identifies the argument within the kernel (the same
    /// expression of the inputs and parameters at every call).
    fn sin_cos(&mut self, slot: usize, arg: f64) -> (f64, f64);

    /// The angle of a closed-form block's unknown `slot` (its index among the unknowns), whose
    /// sine `s` and cosine `c` the block has just computed: `exact()` (libm's `acos`, `asin` or
    /// `atan2`, moved to the turn of the unknown's guess), or that same angle obtained otherwise.
    /// The default is `exact()`; a sweep's cache (`Rotating`) computes it from an earlier exact
    /// angle of the same unknown, on that angle's turn.
    #[inline(always)]
    fn angle(&mut self, slot: usize, s: f64, c: f64, exact: impl FnOnce() -> f64) -> f64 {
        let _ = (slot, s, c);
        exact()
    }
}

/// `(sin(a + b), cos(a + b))` from `a`'s sine and cosine and `b`'s, as generated code computes
/// the sine and cosine of a sum of an input angle and a parameter angle (`phi1 + gamma`):
/// `sin(a + b) = sin a cos b + cos a sin b`, `cos(a + b) = cos a cos b - sin a sin b`. Given
/// exact values, within 1.5 units in the last place of the exact sum's, closer than libm's of
/// the rounded sum `a + b` (whose rounding moves the argument by up to half an ulp of it; see the
/// tests).
#[inline(always)]
pub fn add_angles((sin_a, cos_a): (f64, f64), (sin_b, cos_b): (f64, f64)) -> (f64, f64) {
    (sin_a * cos_b + cos_a * sin_b, cos_a * cos_b - sin_a * sin_b)
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

/// Rotations between two libm evaluations of a Newton block's argument ([`NearTrig`]): a solve
/// warm-started from a near position evaluates its block two to four times after the guess, so
/// these are rotated; a long iteration (near a singular position, where the positions amplify
/// the last bits of the sines) goes back to libm after them, its values never more than a few
/// units in the last place off libm's.
pub const NEWTON_RESYNC: u32 = 4;

/// Slots a [`Rotating`] cache holds; a kernel's further arguments are computed by libm.
pub const SLOTS: usize = 8;

/// Largest `|sin(q - q_a)|` over which an unknown's angle `q` is advanced from its anchor `q_a`
/// (`2^-3`, about 7 degrees); beyond it libm computes the angle and it becomes the new anchor.
/// On `|x| <= 2^-3` the polynomial of `asin x` in [`small_asin`] is within 2.1e-19 of it. (On
/// half this range a polynomial one term shorter does better still, 1.1e-20, but the angles
/// are re-anchored by libm twice as often: measured with callgrind at 720 samples a turn, the
/// gear-lever's sample cost 6 instructions more, the four-bar's 2 more, the rhombic drive's 2
/// fewer; see BENCHMARKS.md.)
pub const ANCHOR_RANGE: f64 = 0.125;

/// One argument's last sine and cosine, from which the next are rotated: a slot of a sweep's
/// `Rotating` cache (whose input slots also reuse their last step, see `Rotating`), or of a
/// Newton block's [`NearTrig`] ([`NearSlot::newton_sin_cos`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearSlot {
    /// The argument of the last call.
    pub arg: f64,
    /// Its sine.
    pub sin: f64,
    /// Its cosine.
    pub cos: f64,
    /// Rotations since libm last computed the values.
    pub age: u32,
}

impl NearSlot {
    /// A slot whose first call goes to libm (its NaN argument makes any change unbounded).
    pub const FRESH: NearSlot = NearSlot { arg: f64::NAN, sin: 0.0, cos: 1.0, age: 0 };

    /// `(sin arg, cos arg)` of a Newton block's evaluation (what [`NearTrig`] computes; the
    /// run-time model calls it for the same bits): the stored values when `arg` is the last
    /// call's; rotated from them by the change `d` when `|d| <= MAX_ROTATION` (`2^-5`) and
    /// fewer than `NEWTON_RESYNC` (4) rotations followed libm's last values; otherwise libm's,
    /// after which the slot's age is 0. A rotation's values are within about one unit in the
    /// last place of those it starts from, so a slot stays within `NEWTON_RESYNC` units of libm's
    /// (see the tests).
    #[inline(always)]
    pub fn newton_sin_cos(&mut self, arg: f64) -> (f64, f64) {
        let d = arg - self.arg;
        if d == 0.0 {
            return (self.sin, self.cos);
        }
        if d.abs() <= MAX_ROTATION && self.age < NEWTON_RESYNC {
            let (sd, cm1) = small_sin_cosm1(d);
            self.rotate(sd, cm1);
        } else {
            // Also a NaN `d`: the first call, or a non-finite argument (libm's NaN, as ever).
            (self.sin, self.cos) = arg.sin_cos();
            self.age = 0;
        }
        self.arg = arg;
        (self.sin, self.cos)
    }

    /// `(sin arg, cos arg)` of a sweep's input slot, whose last step computed by the
    /// polynomials is `base`: the stored values when `arg` is the last call's; rotated from
    /// them by the change `d` when `|d| <=` [`MAX_ROTATION`] and fewer than [`RESYNC`]
    /// rotations followed libm's last values, a step within `base`'s bound of it by the base's
    /// corrected values ([`StepBase::reuse`]), any other by the polynomials, which become the
    /// base ([`StepBase::rebase`]); otherwise libm's, after which the slot's age is `libm_age`
    /// (asked only there; `RESYNC` keeps every later call on libm). The reused step is tested
    /// first: such a step is neither 0 nor beyond [`MAX_ROTATION`], so it is rotated after the
    /// same two tests as any (`d` not 0, fewer than [`RESYNC`] rotations) and saves the range
    /// test and the polynomials. A rotation's values are within about one unit in the last
    /// place of those it starts from, so a slot stays within [`RESYNC`] units of libm's (see
    /// the tests).
    #[inline(always)]
    fn sin_cos_stepped(&mut self, arg: f64, libm_age: impl FnOnce() -> u32, base: &mut StepBase) -> (f64, f64) {
        // `d == 0` but for two equal infinities (whose `d` is NaN, libm's NaN values, which the
        // slot then holds): the same values, one subtraction fewer for an argument that does
        // not change (a parameter angle's, added to an input's by [`add_angles`]).
        if arg == self.arg {
            return (self.sin, self.cos);
        }
        let d = arg - self.arg;
        let young = self.age < RESYNC;
        let e = d - base.d;
        // NaN (no base, or a non-finite `d`) fails the comparison.
        if young && e.abs() <= base.tol {
            let (sd, cm1) = base.reuse(e);
            self.rotate(sd, cm1);
        } else if young && d.abs() <= MAX_ROTATION {
            let (sd, cm1) = base.rebase(d);
            self.rotate(sd, cm1);
        } else {
            (self.sin, self.cos) = arg.sin_cos();
            // Asked after libm's call: nothing it needs is then kept across the call.
            self.age = libm_age();
        }
        self.arg = arg;
        (self.sin, self.cos)
    }

    /// Rotates the values by the change whose `(sin d, cos d - 1)` are `(sd, cm1)`.
    #[inline(always)]
    fn rotate(&mut self, sd: f64, cm1: f64) {
        let (sin, cos) = (self.sin, self.cos);
        self.sin = sin + (sin * cm1 + cos * sd);
        self.cos = cos + (cos * cm1 - sin * sd);
        self.age += 1;
    }
}

/// The sines and cosines of the arguments of one Newton block's evaluation that depend on its
/// unknowns, one [`NearSlot`] per argument, made fresh for each solve of the block.
///
/// The first evaluation of a solve (the guess) calls libm; each later one is near the one
/// before (Newton's corrections shrink quadratically: after the guess's they are far below
/// `MAX_ROTATION`), so its values are the previous ones rotated by the change of the
/// argument, at a fraction of a libm call, within a few units in the last place of libm's. A
/// trial far from the last evaluation (a restart, a long line-search step) calls libm. Nothing
/// carries over from one solve to the next, so nothing accumulates along a sweep.
///
/// ```
/// use kinloop_runtime::generated::NearTrig;
/// let trig = NearTrig::<1>::new();
/// let (s0, _) = trig.sin_cos(0, 0.7); // libm
/// let (s1, c1) = trig.sin_cos(0, 0.7 + 1e-3); // rotated from 0.7's values
/// assert_eq!(s0, 0.7f64.sin());
/// assert!((s1 - 0.701f64.sin()).abs() <= 2e-16 && (c1 - 0.701f64.cos()).abs() <= 2e-16);
/// ```
pub struct NearTrig<const S: usize> {
    // Cells, so that asking the cache takes only `&self`: the guess's evaluation, made in
    // place, seeds it through a shared reference, and the solver's closure (`Fn`, owning the
    // cache after that) rotates it.
    slots: [UnsafeCell<NearSlot>; S],
}

impl<const S: usize> NearTrig<S> {
    /// Every slot fresh: the first call of each goes to libm.
    #[inline(always)]
    pub fn new() -> Self {
        NearTrig { slots: [const { UnsafeCell::new(NearSlot::FRESH) }; S] }
    }

    /// `(sin arg, cos arg)` of argument `slot` ([`NearSlot::newton_sin_cos`]).
    #[inline(always)]
    pub fn sin_cos(&self, slot: usize, arg: f64) -> (f64, f64) {
        // SAFETY: no other reference to the slot exists while this one lives, and none
        // outlives the call: `NearTrig` is not `Sync` (its `UnsafeCell`s), so no other thread
        // reaches it; `newton_sin_cos` calls nothing but libm, so nothing re-enters this cache;
        // the index is checked before the reference is made. (Cells would be safe, but a
        // `Cell`'s `get` and `set` copy the whole slot at every call: measured, 36 instructions
        // a class IV step.)
        let s = unsafe { &mut *self.slots[slot].get() };
        s.newton_sin_cos(arg)
    }

    /// `(sin arg, cos arg)` from libm, kept in `slot` for the next call: what
    /// [`NearTrig::sin_cos`] gives and leaves on a fresh slot, without its tests. The generated
    /// code seeds every slot in the guess's evaluation, which is then the plain libm evaluation
    /// and four stores an argument.
    #[inline(always)]
    pub fn seed(&self, slot: usize, arg: f64) -> (f64, f64) {
        // SAFETY: as in `sin_cos` (libm is all this calls).
        let s = unsafe { &mut *self.slots[slot].get() };
        let (sin, cos) = arg.sin_cos();
        *s = NearSlot { arg, sin, cos, age: 0 };
        (sin, cos)
    }
}

impl<const S: usize> core::fmt::Debug for NearTrig<S> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("NearTrig").field("slots", &S).finish_non_exhaustive()
    }
}

impl<const S: usize> Default for NearTrig<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// Largest change `e` of a slot's argument step, relative to the step `d0` whose sine and
/// cosine the slot's [`StepBase`] holds, over which those values are reused with a first-order
/// correction (`2^-30`): see [`StepBase::reuse`].
const STEP_REUSE: f64 = 1.0 / (1u64 << 30) as f64;

/// The last step of a sweep's input slot whose `(sin d0, cos d0 - 1)` the polynomials
/// ([`small_sin_cosm1`]) computed. At equally spaced samples the argument changes by the same
/// step at every sample up to the rounding of the arguments (a few units in the last place of
/// the argument: `|d - d0|` about `1e-15` against steps of `8.7e-3` at 720 samples a turn,
/// `6.3e-6` at a million), so the next step's values follow from these by a first-order
/// correction, at about half the polynomials' cost.
#[derive(Clone, Copy, Debug)]
struct StepBase {
    /// The step `d0` (NaN: none yet, every step goes to the polynomials).
    d: f64,
    /// `sin d0`.
    sin: f64,
    /// `cos d0 - 1`.
    cosm1: f64,
    /// `cos d0`, `1 + cosm1` rounded.
    cos: f64,
    /// The largest `|d - d0|` corrected from this base: `STEP_REUSE |d0|`, or 0 near
    /// [`MAX_ROTATION`] (see [`StepBase::rebase`]; NaN: no base).
    tol: f64,
}

impl StepBase {
    /// No base: the next step goes to the polynomials.
    const NONE: StepBase = StepBase { d: f64::NAN, sin: 0.0, cosm1: 0.0, cos: 1.0, tol: f64::NAN };

    /// `(sin d, cos d - 1)` of the step `d = d0 + e` from the base `d0`, for `|e|` within the
    /// bound, `rho |d0|` at most, `rho = 2^-30` ([`STEP_REUSE`]; `e = d - d0` is exact: the two
    /// steps are within a factor two of each other). By the addition formulas, with
    /// `s0 = sin d0`, `c0 = cos d0`, `m0 = c0 - 1`:
    ///
    /// * `sin d = s0 + e c0 + r_s`, `r_s = s0 (cos e - 1) + c0 (sin e - e)`, so
    ///   `|r_s| <= |s0| e^2 / 2 + |e|^3 / 6 <= |d0|^3 (rho^2 / 2 + rho^3 / 6)`, where
    ///   `|sin d| >= 0.999 |d0|`: `r_s` is at most about `d0^2 (rho^2 / 2) / 0.999`, that is
    ///   `1.001 * 2^-61 d0^2` (about `2^-71` at most) of `sin d`;
    /// * `cos d - 1 = m0 - s0 e + r_c`, `r_c = c0 (cos e - 1) - s0 (sin e - e)`, so
    ///   `|r_c| <= e^2 / 2 + |s0| |e|^3 / 6 <= d0^2 (rho^2 / 2 + rho^3 / 6)`, where
    ///   `|cos d - 1| >= 0.999 d0^2 / 2`: `r_c` is below `2^-59.9` of `cos d - 1`.
    ///
    /// The omitted terms are thus below `2^-59.9` of each value, where an ulp is at least
    /// `2^-53` of it: under a hundredth of an ulp, at every step length (the bounds are
    /// relative: at a million samples a turn, `d` about `6e-6` and `cos d - 1` about `2e-11`,
    /// as at 720). The correction adds one rounding (half a unit of `EPSILON` times the value;
    /// the rounding of `c0 = 1 + m0` weighs `2^-30` of that) to the base's, which the
    /// polynomials computed (within about 0.5 of those units of `sin d`, 1.25 of `cos d - 1`):
    /// the values are within about 1.0 and 1.75 units (measured against double-double values
    /// in the tests: 0.90 and 1.32). In the rotation they weigh `|d| <= 2^-5` against the
    /// rotated values, whose error they leave unchanged to far below an ulp (the tests measure
    /// the rotated values against libm). Corrections never chain: a base is only ever the
    /// polynomials' values.
    #[inline(always)]
    fn reuse(&self, e: f64) -> (f64, f64) {
        (self.sin + e * self.cos, self.cosm1 - self.sin * e)
    }

    /// The polynomials' `(sin d, cos d - 1)` of a step `0 < |d| <= MAX_ROTATION`, which becomes
    /// the base. Its bound is `2^-30 |d|`, or 0 (only `d` itself is reused) where a step within
    /// that could exceed [`MAX_ROTATION`]: every step reused is within the polynomials' range.
    #[inline(always)]
    fn rebase(&mut self, d: f64) -> (f64, f64) {
        let (sin, cosm1) = small_sin_cosm1(d);
        let tol = if d.abs() <= MAX_ROTATION * (1.0 - 2.0 * STEP_REUSE) { STEP_REUSE * d.abs() } else { 0.0 };
        *self = StepBase { d, sin, cosm1, cos: 1.0 + cosm1, tol };
        (sin, cosm1)
    }
}

/// An unknown's angle as libm last computed it, with the sine and cosine it was computed from.
#[derive(Clone, Copy, Debug)]
struct Anchor {
    q: f64,
    sin: f64,
    cos: f64,
}

impl Anchor {
    /// No anchor: a zero sine and cosine send every angle to libm.
    const INVALID: Anchor = Anchor { q: f64::NAN, sin: 0.0, cos: 0.0 };
}

/// A sweep's cache of the sines and cosines of its kernel's input arguments, and of the anchors
/// of its closed-form angles (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub struct Rotating {
    /// Each slot's last values, and its last step computed by the polynomials (reused for the
    /// next steps of the same length: a sweep's equally spaced samples).
    slots: [(NearSlot, StepBase); SLOTS],
    anchors: [Anchor; SLOTS],
    /// Every value from libm (see [`Rotating::exact`]): while it holds, every slot is kept at
    /// the age that sends it to libm and every anchor is invalid, so the per-call paths need not
    /// test it.
    exact: bool,
}

impl Default for Rotating {
    fn default() -> Self {
        // A NaN argument makes the first call of every slot go to libm.
        // A zero anchor (sine and cosine both 0) sends the first call of every angle to libm.
        Rotating { slots: [(NearSlot::FRESH, StepBase::NONE); SLOTS], anchors: [Anchor::INVALID; SLOTS], exact: false }
    }
}

impl Rotating {
    /// Whether the following calls take every value from libm: near a singular position the
    /// positions amplify the last bits of the inputs' sines and cosines, and there a few units
    /// in the last place more (a rotation's) would cost precision a point solve has.
    #[inline(always)]
    pub fn exact(&mut self, exact: bool) {
        self.exact = exact;
        if exact {
            self.send_to_libm();
        }
    }

    /// Sends the next call of every slot and angle to libm: rare (near singular positions), so
    /// out of the sweep's loop. A slot's NaN argument sends even its last argument, asked
    /// again, to libm (its stored values may be rotated ones); its age keeps every later call
    /// there.
    #[cold]
    #[inline(never)]
    fn send_to_libm(&mut self) {
        for (s, _) in &mut self.slots {
            s.arg = f64::NAN;
            s.age = RESYNC;
        }
        self.forget_anchors();
    }

    /// Drops every anchor: the next call of every angle goes to libm, on its guess's turn. A
    /// sweep calls it after a step it did not accept, where an anchor may have been the cause
    /// (see [`InputTrig::angle`]).
    #[cold]
    #[inline(never)]
    pub fn forget_anchors(&mut self) {
        self.anchors = [Anchor::INVALID; SLOTS];
    }
}

/// libm's sines and cosines, but for the slots `slots`, whose values the caller computed:
/// `kinematics_flat` of a mechanism whose kernel asks for the sine and cosine of a parameter
/// (the fixed part of a sum such as `phi1 + gamma`) computes them before it calls the kernel,
/// so that a caller's loop that borrows the mechanism computes them once even where the
/// compiler keeps the kernel out of line (called from several places). The same values as the
/// kernel's own call of libm, to the bit.
#[derive(Clone, Copy, Debug)]
pub struct Preset<const K: usize> {
    /// The kernel's slots whose values are given.
    pub slots: [usize; K],
    /// Their `(sin, cos)`, in the order of `slots`.
    pub values: [(f64, f64); K],
}

impl<const K: usize> InputTrig for Preset<K> {
    #[inline(always)]
    fn sin_cos(&mut self, slot: usize, arg: f64) -> (f64, f64) {
        for k in 0..K {
            if self.slots[k] == slot {
                return self.values[k];
            }
        }
        arg.sin_cos()
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

/// `asin x` for `|x| <= ANCHOR_RANGE`: `x + x^3 p(x^2)` with `p` the degree-5 Chebyshev
/// approximation of `(asin x - x) / x^3` on the range (coefficients from
/// `runtime/reference/small_asin.py`, mpmath at 50 digits: the polynomial with these doubles is
/// within 2.1e-19 of `asin x` on the range, where the Taylor series to `x^15`, one term longer,
/// is within 5e-18). In Horner form.
#[inline(always)]
fn small_asin(x: f64) -> f64 {
    let x2 = x * x;
    let p = 0.166_666_666_666_666_57
        + x2 * (0.075_000_000_000_475_33
            + x2 * (0.044_642_856_788_276_65
                + x2 * (0.030_382_041_082_465_04 + x2 * (0.022_360_274_967_086_82 + x2 * 0.018_023_552_753_717_71))));
    x + x * x2 * p
}

impl InputTrig for Rotating {
    #[inline(always)]
    fn sin_cos(&mut self, slot: usize, arg: f64) -> (f64, f64) {
        let Some((s, base)) = self.slots.get_mut(slot) else {
            return arg.sin_cos();
        };
        // An exact cache stays at the age that calls libm. (Asked only where libm is called:
        // passed as a value, the test of `exact` came before each slot's first test, measured
        // 4 instructions a slot and step.)
        let exact = &self.exact;
        s.sin_cos_stepped(arg, || if *exact { RESYNC } else { 0 }, base)
    }

    /// `q = q_a + asin(x)` from the slot's anchor `q_a`, with `x = sin(q - q_a) = s cos q_a -
    /// c sin q_a` (well conditioned: its rounding is about an ulp of 1, whatever the angle), when
    /// `|x| < ANCHOR_RANGE y` with `y = cos(q - q_a)` (one comparison for both conditions: `|x|`
    /// within [`ANCHOR_RANGE`], and `q` on the anchor's side, `y > 0`). The anchor is libm's
    /// angle, so errors do not accumulate: the result is within a few ulps of libm's. Otherwise,
    /// and when exact (near a singular position, where a rod's cosine is small and carries the
    /// root's rounding), libm's, which becomes the anchor.
    ///
    /// The result is on the anchor's turn, which libm chose from an earlier guess (`exact` moves
    /// its angle to the turn of its own call's guess). In a sweep the two turns agree: an angle
    /// leaves the anchor's range, and gets a new anchor, long before it has turned a whole turn.
    /// Should they ever differ, the angle lies a turn from its prediction: the sweep rejects the
    /// step (it caps the distance of every `Mechanism::CLOSED_FORM_ANGLES` angle from its
    /// prediction) and forgets the anchors ([`Rotating::forget_anchors`]) before it tries again.
    /// Testing the guess here cost every angle of every step 5 instructions.
    #[inline(always)]
    fn angle(&mut self, slot: usize, s: f64, c: f64, exact: impl FnOnce() -> f64) -> f64 {
        let Some(a) = self.anchors.get_mut(slot) else {
            return exact();
        };
        let x = s * a.cos - c * a.sin;
        let y = c * a.cos + s * a.sin;
        // NaN fails the comparison.
        if x.abs() < ANCHOR_RANGE * y {
            return a.q + small_asin(x);
        }
        let q = exact();
        // An exact cache keeps no anchor.
        if q.is_finite() && !self.exact {
            *a = Anchor { q, sin: s, cos: c };
        }
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;

    /// Walks of random small steps (forward, backward, repeated, some beyond the rotation
    /// range) over many turns: the rotated values stay within 8e-16 of libm's, a few units in
    /// the last place of values up to 1 (the bound grows with `RESYNC`).
    #[test]
    fn rotated_values_stay_within_a_few_ulps_of_libm() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut worst = 0.0f64;
        for walk in 0..200 {
            let mut cache = Rotating::default();
            let mut arg = 10.0 * (rng.uniform(0.0, 1.0) - 0.5) + walk as f64;
            let scale = [1e-4, 1e-3, 8.7e-3, 0.03, 0.05][walk % 5];
            for _ in 0..2000 {
                let u = rng.uniform(0.0, 1.0);
                arg += if u < 0.05 { 0.0 } else { scale * (2.0 * rng.uniform(0.0, 1.0) - 0.7) };
                let (s, c) = cache.sin_cos(0, arg);
                let (sl, cl) = arg.sin_cos();
                worst = worst.max((s - sl).abs()).max((c - cl).abs());
            }
        }
        assert!(worst <= 8e-16, "worst deviation from libm {worst:e}");
        assert!(worst > 0.0, "the walks must have rotated");
    }

    /// Equally spaced arguments, as a sweep's samples give them (`k` times a fraction of the
    /// range), over up to 300 turns, at 720 to a million a turn: within 8e-16 of libm's,
    /// nothing accumulates. Each step is classified: libm's (the slot's age back to 0, its
    /// values libm's to the bit), a rebase (the base's step changed: the polynomials), or a
    /// reuse of the slot's [`StepBase`] (neither). libm computes one step in `RESYNC + 1`, and
    /// nearly all the others reuse the base, even at a million a turn, where the arguments'
    /// rounding weighs most against the step (measured: 94.1 % of the steps reused at every
    /// spacing, 16 in 17; one rebase, the first rotation).
    #[test]
    fn equally_spaced_arguments_stay_within_a_few_ulps_of_libm() {
        let mut worst = 0.0f64;
        for (n, turns) in [(720usize, 3.0), (20_000, 2.0), (1000, 300.0), (1_000_000, 1.0)] {
            let mut cache = Rotating::default();
            let len = core::f64::consts::TAU * turns;
            let spacing = 1.0 / (n as f64 * turns - 1.0);
            let (mut steps, mut libm, mut rebased, mut reused) = (0usize, 0usize, 0usize, 0usize);
            for k in 0..(n as f64 * turns) as usize {
                let arg = 0.3 + (k as f64 * spacing) * len;
                let base_before = cache.slots[0].1.d.to_bits();
                let (s, c) = cache.sin_cos(0, arg);
                let (sl, cl) = arg.sin_cos();
                worst = worst.max((s - sl).abs()).max((c - cl).abs());
                if k == 0 {
                    continue;
                }
                steps += 1;
                if cache.slots[0].0.age == 0 {
                    assert_eq!((s.to_bits(), c.to_bits()), (sl.to_bits(), cl.to_bits()), "libm's step {k}");
                    libm += 1;
                } else if cache.slots[0].1.d.to_bits() != base_before {
                    rebased += 1;
                } else {
                    reused += 1;
                }
            }
            let share = |count: usize| count as f64 / steps as f64;
            assert!(
                share(reused) >= 0.93,
                "{n} a turn: {reused} of {steps} steps reused ({libm} libm, {rebased} rebased)"
            );
            // Every `RESYNC + 1`-th step, up to the partial cycle at the end.
            let cycle = RESYNC as usize + 1;
            assert!(steps / cycle <= libm && libm <= steps / cycle + 1, "{n} a turn: {libm} of {steps} steps libm's");
        }
        assert!(worst <= 8e-16, "worst deviation from libm {worst:e}");
    }

    /// `(hi, lo)`: a double-double, the unevaluated sum `hi + lo` with `|lo| <= ulp(hi) / 2`,
    /// for the high-precision references below (about 106 bits).
    type Dd = (f64, f64);

    /// `a + b` normalized, for `|a| >= |b|` (or `a` 0).
    fn quick_two_sum(a: f64, b: f64) -> Dd {
        let s = a + b;
        (s, b - (s - a))
    }

    /// `a + b` in double-double (no cancellation among the terms summed here: each term of the
    /// series is below a 6000th of the one before).
    fn dd_add(a: Dd, b: Dd) -> Dd {
        let s = a.0 + b.0;
        let v = s - a.0;
        let e = (a.0 - (s - v)) + (b.0 - v);
        quick_two_sum(s, e + a.1 + b.1)
    }

    /// `a b` in double-double (the exact product of the high parts by a fused multiply-add).
    fn dd_mul(a: Dd, b: Dd) -> Dd {
        let p = a.0 * b.0;
        let e = a.0.mul_add(b.0, -p);
        quick_two_sum(p, e + (a.0 * b.1 + a.1 * b.0))
    }

    /// `a / n` in double-double, for a small integer `n`.
    fn dd_div(a: Dd, n: f64) -> Dd {
        let q = a.0 / n;
        let r = (-q).mul_add(n, a.0) + a.1;
        quick_two_sum(q, r / n)
    }

    /// `(sin d, cos d - 1)` to about 106 bits for `|d| <= MAX_ROTATION`: their Taylor series in
    /// double-double, summed until the terms are below `2^-110` of the first (at `|d| = 2^-5`
    /// the term of `d^25` is `1e-46` of `d`).
    fn reference_sin_cosm1(d: f64) -> (Dd, Dd) {
        let d2 = (d * d, d.mul_add(d, -(d * d)));
        let (mut sin, mut sin_term) = ((d, 0.0), (d, 0.0));
        let (mut cosm1, mut cos_term) = (dd_div((-d2.0, -d2.1), 2.0), dd_div((-d2.0, -d2.1), 2.0));
        for k in 1..=12 {
            let k = f64::from(k);
            sin_term = dd_div(dd_mul(sin_term, (-d2.0, -d2.1)), (2.0 * k) * (2.0 * k + 1.0));
            sin = dd_add(sin, sin_term);
            cos_term = dd_div(dd_mul(cos_term, (-d2.0, -d2.1)), (2.0 * k + 1.0) * (2.0 * k + 2.0));
            cosm1 = dd_add(cosm1, cos_term);
        }
        (sin, cosm1)
    }

    /// `|got - want| / (EPSILON |want|)`: the error in units of `EPSILON` of the value (an ulp
    /// of it is between half and one of these units; a correct rounding is within 0.5).
    fn units(got: f64, want: Dd) -> f64 {
        ((got - want.0) - want.1).abs() / (f64::EPSILON * want.0.abs())
    }

    /// The double-double reference against libm's `sin` (within an ulp, as libm is) and against
    /// `cos d - 1 = -2 sin^2(d / 2)` evaluated in doubles (within the 1.5 units of that
    /// evaluation's roundings and libm's), and its series against an identity the polynomials
    /// do not use: `sin^2 d + (cos d - 1)^2 + 2 (cos d - 1) = 0` to about `2^-100` of `d^2`.
    #[test]
    fn the_double_double_reference_is_sin_and_cos_minus_one() {
        for k in 0..=200 {
            let magnitude = 1e-8 * (MAX_ROTATION / 1e-8).powf(f64::from(k) / 200.0);
            for d in [magnitude, -magnitude] {
                let (sin, cosm1) = reference_sin_cosm1(d);
                assert!(units(d.sin(), sin) <= 1.0, "sin {d:e}: {}", units(d.sin(), sin));
                let half = (0.5 * d).sin();
                assert!(units(-2.0 * half * half, cosm1) <= 1.6, "cos - 1 {d:e}");
                let sum = dd_add(dd_add(dd_mul(sin, sin), dd_mul(cosm1, cosm1)), (2.0 * cosm1.0, 2.0 * cosm1.1));
                assert!((sum.0 + sum.1).abs() <= 2f64.powi(-100) * d * d, "identity at {d:e}: {sum:?}");
            }
        }
    }

    /// A step within `2^-30` of the base's (both signs, nearly up to the bound), for bases from
    /// `1e-8` to [`MAX_ROTATION`] of either sign, against `sin d` and `cos d - 1` in
    /// double-double ([`reference_sin_cosm1`]). The polynomials' `sin d` is its final addition's
    /// rounding (half a unit of `EPSILON sin d`) and a rounding of the small term `d^3 / 6`
    /// (`1.6e-4` of the value at most); the reuse adds one rounding (half a unit) and the
    /// product `e cos d0` (`2^-30` of the value) and omits `2^-61` of it: within 1.01 units
    /// (measured: 0.90, the polynomials 0.49). The polynomials' `cos d - 1` is the rounding of
    /// `d^2` (half a unit), of the polynomial factor near `-1/2` (a quarter) and of their
    /// product (half); the reuse adds half a unit: within 1.76 (measured: 1.32, the polynomials
    /// 1.08). The base's bound
    /// keeps every step reused within [`MAX_ROTATION`]; away from it, the bound is `2^-30 |d0|`.
    #[test]
    fn reused_steps_are_within_two_units_of_sin_and_cos_minus_one() {
        let (mut worst, mut worst_polynomials) = ([0.0f64; 2], [0.0f64; 2]);
        let magnitudes = (0..=400).map(|k| 1e-8 * (MAX_ROTATION / 1e-8).powf(f64::from(k) / 400.0));
        // The largest bases, where a step `2^-30` longer would exceed `MAX_ROTATION`.
        let near_max =
            [1.0, 1.0 - 2f64.powi(-40), 1.0 - 2f64.powi(-31), 1.0 - 2f64.powi(-29)].map(|f| MAX_ROTATION * f);
        for magnitude in magnitudes.chain(near_max) {
            for d0 in [magnitude, -magnitude] {
                let mut base = StepBase::NONE;
                assert_eq!(base.rebase(d0), small_sin_cosm1(d0));
                assert!(d0.abs() + base.tol <= MAX_ROTATION, "bound {:e} of the step {d0:e}", base.tol);
                if d0.abs() <= 0.99 * MAX_ROTATION {
                    assert_eq!(base.tol, STEP_REUSE * d0.abs());
                }
                for f in [0.0, 0.3, -0.3, 0.999, -0.999] {
                    let d = d0 + f * base.tol;
                    let e = d - d0;
                    assert!(e.abs() <= base.tol && d.abs() <= MAX_ROTATION);
                    let (s, cm1) = base.reuse(e);
                    let (want_s, want_cm1) = reference_sin_cosm1(d);
                    worst = [worst[0].max(units(s, want_s)), worst[1].max(units(cm1, want_cm1))];
                    let (ps, pcm1) = small_sin_cosm1(d);
                    worst_polynomials =
                        [worst_polynomials[0].max(units(ps, want_s)), worst_polynomials[1].max(units(pcm1, want_cm1))];
                }
            }
        }
        assert!(worst[0] <= 1.01 && worst[1] <= 1.76, "worst {worst:?} units (polynomials: {worst_polynomials:?})");
    }

    /// A slot's steps: the first rotation and a step beyond the base's bound rebase it, a step
    /// within it keeps it; the values stay libm's to a few ulps throughout.
    #[test]
    fn a_slot_rebases_beyond_the_bound_and_reuses_within() {
        let mut cache = Rotating::default();
        let mut arg = 0.4;
        cache.sin_cos(0, arg);
        assert!(cache.slots[0].1.d.is_nan(), "libm's first values leave no base");
        for (step, rebased) in [(0.01, true), (0.01, false), (0.01 * (1.0 + 1e-6), true), (0.01 * (1.0 + 1e-6), false)]
        {
            let before = cache.slots[0].1.d;
            let next = arg + step;
            let (s, c) = cache.sin_cos(0, next);
            assert_eq!(cache.slots[0].1.d != before, rebased, "step {step} after {before}");
            assert!((s - next.sin()).abs() <= 4e-16 && (c - next.cos()).abs() <= 4e-16);
            arg = next;
        }
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

    /// Equal steps of a cache that then becomes exact: its slot's base and young age would
    /// reuse the next steps; every value is libm's to the bit instead (where a cache that stays
    /// rotating differs in the last bits somewhere).
    #[test]
    fn an_exact_cache_is_libm() {
        let (mut exact, mut rotating) = (Rotating::default(), Rotating::default());
        let arg = |k: u32| 1.0 + 0.001 * f64::from(k);
        for k in 0..4 {
            assert_eq!(exact.sin_cos(0, arg(k)), rotating.sin_cos(0, arg(k)));
        }
        exact.exact(true);
        let mut differs = 0;
        for k in 4..4 + 3 * RESYNC {
            assert_eq!(exact.sin_cos(0, arg(k)), arg(k).sin_cos(), "step {k}");
            differs += usize::from(rotating.sin_cos(0, arg(k)) != arg(k).sin_cos());
        }
        assert!(differs > 0, "the other cache rotates (and differs in the last bits somewhere)");
    }

    /// A slot rotated a few equal steps, whose last values are not libm's to the bit: made
    /// exact, it gives libm's values for that same argument asked again (not the rotated ones
    /// it holds), and for the arguments after it.
    #[test]
    fn an_exact_cache_recomputes_the_last_argument() {
        let mut found = false;
        for start in 0..100 {
            let arg = |k: u32| 0.2 + 0.05 * f64::from(start) + 0.004 * f64::from(k);
            let mut cache = Rotating::default();
            let mut last = (0.0, 0.0);
            for k in 0..5 {
                last = cache.sin_cos(0, arg(k));
            }
            if last == arg(4).sin_cos() {
                continue;
            }
            found = true;
            cache.exact(true);
            assert_eq!(cache.sin_cos(0, arg(4)), arg(4).sin_cos(), "the same argument, from {start}");
            for k in 5..5 + RESYNC {
                assert_eq!(cache.sin_cos(0, arg(k)), arg(k).sin_cos(), "step {k} from {start}");
            }
        }
        assert!(found, "some rotated values differ from libm's in their last bits");
    }

    /// Equal steps: libm's first values, the polynomials' step, reused steps; after every
    /// [`RESYNC`] rotations (all reused after the first cycle: the base outlives libm's calls)
    /// the next equal step is libm's value to the bit, the slot's age back to 0.
    #[test]
    fn equal_steps_go_back_to_libm_after_resync_rotations() {
        let mut cache = Rotating::default();
        let arg = |k: u32| -0.7 + 0.01 * f64::from(k);
        let cycle = RESYNC + 1;
        let mut reused = 0;
        for k in 0..4 * cycle {
            let base_before = cache.slots[0].1.d.to_bits();
            let values = cache.sin_cos(0, arg(k));
            let age = cache.slots[0].0.age;
            if k % cycle == 0 {
                assert_eq!(values, arg(k).sin_cos(), "step {k}");
                assert_eq!(age, 0, "step {k}");
            } else {
                assert_eq!(age, k % cycle, "step {k} rotates");
                reused += usize::from(k > cycle && cache.slots[0].1.d.to_bits() == base_before);
            }
        }
        assert_eq!(reused, 3 * RESYNC as usize, "every rotation after the first cycle reused the base");
    }

    /// libm's angle of `(s, c)` on the turn of `guess` (what a kernel's `exact` computes).
    fn libm_angle(s: f64, c: f64, guess: f64) -> f64 {
        let q = s.atan2(c);
        q + core::f64::consts::TAU * ((guess - q) / core::f64::consts::TAU).round()
    }

    /// Walks of an angle over many turns, forward and backward, in steps from 1e-4 to beyond the
    /// anchor's range, with the guess a little off the angle (a sweep's prediction): the advanced
    /// angles stay within 2 units of `EPSILON max(|q|, 1)` of libm's (measured: 1.01; angles reach
    /// about 150 here), within 4.5e-16 below 1 (measured 2.2e-16), on the same turn, and most calls
    /// are advanced (measured: 91 %).
    #[test]
    fn advanced_angles_stay_within_a_few_ulps_of_libm() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mut worst_small = 0.0f64;
        let (mut worst, mut advanced, mut calls) = (0.0f64, 0usize, 0usize);
        for walk in 0..200 {
            let mut cache = Rotating::default();
            let mut q = 20.0 * (rng.uniform(0.0, 1.0) - 0.5) + walk as f64 * 0.3;
            let scale = [1e-4, 1e-3, 8.7e-3, 0.03, 0.2][walk % 5];
            for _ in 0..2000 {
                q += scale * (2.0 * rng.uniform(0.0, 1.0) - 0.8);
                let (s, c) = q.sin_cos();
                let guess = q + 1e-3 * (rng.uniform(0.0, 1.0) - 0.5);
                let mut exact_called = false;
                let got = cache.angle(2, s, c, || {
                    exact_called = true;
                    libm_angle(s, c, guess)
                });
                let want = libm_angle(s, c, guess);
                worst = worst.max((got - want).abs() / (f64::EPSILON * want.abs().max(1.0)));
                advanced += usize::from(!exact_called);
                if want.abs() < 1.0 {
                    worst_small = worst_small.max((got - want).abs());
                }
                calls += 1;
            }
        }
        assert!(worst <= 2.0, "worst deviation from libm {worst} units");
        assert!(advanced > calls / 2, "{advanced} of {calls} calls advanced");
        assert!(worst_small <= 4.5e-16, "worst deviation of angles below 1: {worst_small:e}");
    }

    /// The anchor's polynomial against libm's `asin` over its whole range (both signs, the ends
    /// included): within an ulp of `asin x` (its own error is within 2.1e-19; the rest is the
    /// rounding of its evaluation and of libm's), and odd.
    #[test]
    fn the_anchor_polynomial_is_libm_asin_on_its_range() {
        let mut worst = 0.0f64;
        for k in 0..=20_000 {
            let x = ANCHOR_RANGE * f64::from(k) / 20_000.0;
            for x in [x, -x] {
                let (got, want) = (small_asin(x), x.asin());
                worst = worst.max((got - want).abs() / (f64::EPSILON * want.abs()).max(f64::MIN_POSITIVE));
            }
            assert_eq!(small_asin(-x), -small_asin(x));
        }
        assert!(worst <= 1.0, "worst deviation from libm {worst} ulps (of EPSILON |asin x|)");
    }

    /// The first call, a jump beyond the anchor's range, forgotten anchors, an exact cache, a
    /// slot beyond the cache and a NaN are all libm's own (the `exact` closure's). A small step
    /// stays on its anchor's turn.
    #[test]
    fn angles_fall_back_to_libm_where_they_cannot_be_advanced() {
        let mut cache = Rotating::default();
        let at = |q: f64| q.sin_cos();
        let (s, c) = at(0.5);
        assert_eq!(cache.angle(0, s, c, || 0.5), 0.5);
        // Advanced: within an ulp or two of 0.51, without calling `exact`.
        let (s, c) = at(0.51);
        let q = cache.angle(0, s, c, || f64::NAN);
        assert!((q - 0.51).abs() < 4e-16, "{q}");
        // A jump of 0.3 rad: `exact`, which becomes the anchor.
        let (s, c) = at(0.81);
        assert_eq!(cache.angle(0, s, c, || 0.81), 0.81);
        // A small step: on the anchor's turn, without `exact`.
        let (s, c) = at(0.82);
        let q = cache.angle(0, s, c, || f64::NAN);
        assert!((q - 0.82).abs() < 4e-16, "{q}");
        // Forgotten anchors, a slot beyond the cache: `exact`.
        cache.forget_anchors();
        assert_eq!(cache.angle(0, s, c, || -9.0), -9.0);
        assert_eq!(cache.angle(SLOTS, s, c, || 3.0), 3.0);
        // A NaN sine goes to `exact`, and does not become the anchor.
        assert!(cache.angle(1, f64::NAN, c, || f64::NAN).is_nan());
        assert_eq!(cache.angle(1, s, c, || 5.0), 5.0);
        // An exact cache always asks `exact`.
        cache.exact(true);
        let (s, c) = at(0.821);
        assert_eq!(cache.angle(1, s, c, || 11.0), 11.0);
        // Libm asks `exact` too.
        assert_eq!(Libm.angle(0, s, c, || 13.0), 13.0);
    }

    /// A sum of angles `a + b` by [`add_angles`] from libm's values of each: within 3.4e-16 (1.5
    /// units in the last place of 1; measured 2.2e-16) of the sine and cosine of the exact sum,
    /// which is `s + e` by the two-sum of `a` and `b`, so `sin(s) + e cos(s)` to far below an
    /// ulp. Libm's values
    /// of the rounded sum `s` are off by up to `|e|` (measured 8.9e-16 here): the angle addition
    /// is closer.
    #[test]
    fn sums_of_angles_are_within_two_ulps() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (mut worst, mut worst_libm) = (0.0f64, 0.0f64);
        for _ in 0..20_000 {
            let b = 8.0 * (rng.uniform(0.0, 1.0) - 0.5);
            for _ in 0..3 {
                let a = 20.0 * (rng.uniform(0.0, 1.0) - 0.5);
                let s = a + b;
                let e = (a - (s - (s - a))) + (b - (s - a));
                let (rs, rc) = (s.sin() + e * s.cos(), s.cos() - e * s.sin());
                let (ss, cs) = add_angles(a.sin_cos(), b.sin_cos());
                worst = worst.max((ss - rs).abs()).max((cs - rc).abs());
                worst_libm = worst_libm.max((s.sin() - rs).abs()).max((s.cos() - rc).abs());
            }
        }
        assert!(worst <= 3.4e-16, "worst deviation {worst:e} (libm of the rounded sum: {worst_libm:e})");
    }

    /// A Newton block's slots: the first call of a solve is libm's to the bit; corrections
    /// shrinking as Newton's do are rotated, within a few units in the last place of libm's; a
    /// jump (a restart) is libm's again; [`NEWTON_RESYNC`] rotations at most between two libm
    /// calls.
    #[test]
    fn near_trig_follows_newton_corrections_within_a_few_ulps() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mut worst = 0.0f64;
        for _ in 0..500 {
            let trig = NearTrig::<2>::new();
            let mut z = 20.0 * (rng.uniform(0.0, 1.0) - 0.5);
            let first = trig.sin_cos(1, z);
            assert_eq!(first, z.sin_cos(), "the first call of a solve is libm's");
            let mut step = 0.02 * (rng.uniform(0.0, 1.0) - 0.5);
            for _ in 0..6 {
                z += step;
                step = step * step * 10.0;
                let (s, c) = trig.sin_cos(1, z);
                let (sl, cl) = z.sin_cos();
                worst = worst.max((s - sl).abs()).max((c - cl).abs());
            }
            let jump = z + 0.5;
            assert_eq!(trig.sin_cos(1, jump), jump.sin_cos(), "a jump is libm's");
        }
        assert!(worst <= 4e-16, "worst deviation from libm {worst:e}");
        assert!(worst > 0.0, "the corrections must have rotated");
        let trig = NearTrig::<1>::new();
        let mut libm_calls = 0;
        for k in 0..40 {
            let arg = 1.0 + 1e-3 * k as f64;
            if trig.sin_cos(0, arg) == arg.sin_cos() && unsafe { (*trig.slots[0].get()).age } == 0 {
                libm_calls += 1;
            }
        }
        assert!(
            libm_calls >= 40 / (NEWTON_RESYNC as usize + 1),
            "a slot goes back to libm every NEWTON_RESYNC rotations"
        );
    }

    /// A preset slot gives the caller's values whatever the argument; every other slot libm's.
    #[test]
    fn preset_slots_give_their_values_and_others_libm() {
        let mut t = Preset { slots: [1, 3], values: [0.7f64.sin_cos(), (0.25, 0.75)] };
        assert_eq!(t.sin_cos(1, 0.7), 0.7f64.sin_cos());
        assert_eq!(t.sin_cos(3, 0.1), (0.25, 0.75));
        assert_eq!(t.sin_cos(0, 0.4), 0.4f64.sin_cos());
        assert_eq!(t.sin_cos(2, -1.3), (-1.3f64).sin_cos());
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
