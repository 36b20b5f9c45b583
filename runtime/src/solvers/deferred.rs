//! The closed-form steps of a kernel whose checks are deferred to its end: the switch between
//! the checked steps and those without their tests ([`Checks`]; both forms are in
//! [`closed`](super::closed)), and the bound its entry tests the angles' guesses against.
//!
//! A sweep's step runs a generated kernel that tests nothing on the way (a point step runs the
//! same kernel with its checks on the way, `CHECKED`): every closed-form root is taken as if it
//! existed, every analog block is solved whatever its pivot.
//! Each failure the checked kernel would report leaves a trace the kernel's end sees:
//! - a root that does not exist is the square root of a negative number (or a division by a zero
//!   radius): NaN, which reaches the block's sines and cosines;
//! - a non-finite coefficient or guess makes the block's outputs (or their check sum) non-finite;
//! - a singular analog block has a pivot ratio below `singular_tol`, which the state's
//!   [`Health`](crate::Health) records as its smallest.
//!
//! So one test at the end (a sum finite, the smallest pivot at least `singular_tol`) accepts a
//! step only where every one of those checks would have passed, and the state is then what the
//! checked kernel computes: the same operations in the same order.
//! The sum holds the state's values and the blocks' check sums that the others do not imply
//! finite (the macro's `plan::finite`: the sliders' second analogs of the rhombic drive are
//! computed from its rods' angles, sines, cosines and analogs, which the sum then leaves out).
//! The one check left, an angle too many turns out to be accurate, is made on entry, on the
//! angles' guesses ([`SURELY_PRECISE_GUESS`]). Where a test fails, the kernel runs again with
//! every check on the way, which returns the error the checked kernel reports (with its block,
//! input and guess), or the state where every check passes after all (a limit position rounded
//! past, see [`root_offset`](super::closed::root_offset); an angle between the conservative
//! bound and the configured one). The tests are conservative only: they never accept what a
//! check rejects (`tests/solver/deferred_checks.rs` compares the two kernels where every check fails).
//!
//! Measured with callgrind (`benches/callgrind.sh`, 720 samples a turn), a `Sweep` sample of the
//! rhombic drive took 76 fewer instructions (756 to 680), the gear-lever's 55 (664 to 609) and
//! the four-bar's 40 (666 to 626): tested on the way, each check cost a branch, a closure and
//! the values its error needs kept alive.

use super::closed::{
    check_closed, dyad_roots, dyad_roots_deferred, polar_norm, polar_norm_deferred, root_offset, root_offset_deferred,
};
use super::newton::{BlockFailure, NewtonConfig};

/// An angle this large or smaller is accurate on its turn under every configuration: the least
/// [`largest_precise_angle`](super::closed::largest_precise_angle) of all, that of the smallest
/// residual tolerance it admits (16 eps): `1000 · 16 eps / eps`.
pub const SURELY_PRECISE_ANGLE: f64 = 16_000.0;

/// A closed-form angle whose guess is this large or smaller is within [`SURELY_PRECISE_ANGLE`]:
/// the angle lies within `π` of its guess (moved to the guess's turn, or `asin` on the guess's
/// side of the vertical and turn). A sweep's cache may instead advance it from an anchor, by
/// less than `asin(1/8)`; the anchor is libm's angle, within `π` of the guess of an earlier
/// call, which passed this test. The margin of 8 leaves room to spare. A deferred kernel tests
/// its closed-form angles' guesses against it on entry, without reading the configuration;
/// larger ones (2545 turns) go to the checked kernel, which tests the angles against the
/// configured bound.
pub const SURELY_PRECISE_GUESS: f64 = SURELY_PRECISE_ANGLE - 8.0;

/// How a kernel tests: every check on the way (`CHECKED`), or deferred to its end. The kernel
/// binds it once (`__mode`) and asks it for its closed-form steps, which are then the checked
/// ones or the deferred ones (see [`root_offset_deferred`]), and for what follows a failed test
/// (`rerun` and `finish`, which run the mechanism's kernel: defined with the `Mechanism` trait,
/// in `generated`, above the solvers).
#[derive(Clone, Copy, Debug)]
pub struct Checks<const CHECKED: bool>;

impl<const CHECKED: bool> Checks<CHECKED> {
    /// [`root_offset`](super::closed::root_offset), or deferred [`root_offset_deferred`] (never
    /// a failure).
    #[inline(always)]
    pub fn root_offset(self, d2: f64, r2: f64, c: f64, flip: bool, cfg: &NewtonConfig) -> Result<f64, BlockFailure> {
        if CHECKED {
            root_offset(d2, r2, c, flip, cfg)
        } else {
            // A subnormal `r2`, which the checked step refuses, leaves a NaN trace.
            Ok(root_offset_deferred(if r2 >= f64::MIN_POSITIVE { d2 } else { f64::NAN }, flip))
        }
    }

    /// [`dyad_roots`](super::closed::dyad_roots), or deferred [`dyad_roots_deferred`].
    #[inline(always)]
    pub fn dyad_roots(
        self,
        a: f64,
        b: f64,
        c: f64,
        flip: bool,
        cfg: &NewtonConfig,
    ) -> Result<(f64, f64), BlockFailure> {
        if CHECKED { dyad_roots(a, b, c, flip, cfg) } else { Ok(dyad_roots_deferred(a, b, c, flip)) }
    }

    /// [`polar_norm`](super::closed::polar_norm), or deferred [`polar_norm_deferred`].
    #[inline(always)]
    pub fn polar_norm(self, d2: f64, e0: f64, e1: f64, cfg: &NewtonConfig) -> Result<f64, BlockFailure> {
        if CHECKED { polar_norm(d2, e0, e1, cfg) } else { Ok(polar_norm_deferred(d2)) }
    }

    /// [`check_closed`](super::closed::check_closed), or deferred nothing (the kernel's end tests
    /// the block's check sum, its entry the angles' guesses).
    #[inline(always)]
    pub fn check_closed<const K: usize>(
        self,
        out: &[f64; K],
        angles: usize,
        cfg: &NewtonConfig,
    ) -> Result<(), BlockFailure> {
        if CHECKED { check_closed(out, angles, cfg) } else { Ok(()) }
    }

    /// Deferred, whether the closed-form angles' guesses, whose magnitudes sum to `magnitudes`,
    /// may lead to angles too large to be accurate (beyond [`SURELY_PRECISE_GUESS`]), or are NaN:
    /// the kernel then answers as the checked one. (A sweep's cache may advance an angle without
    /// reading its guess, so a NaN guess must not get that far.)
    // The negated comparison is the point: true for NaN, and one instruction per step less than
    // `> || is_nan()` as compiled (callgrind).
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    #[inline(always)]
    pub fn far(self, magnitudes: f64) -> bool {
        !CHECKED && !(magnitudes <= SURELY_PRECISE_GUESS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::closed::largest_precise_angle;
    use crate::test_rng::Rng;

    /// Where the checked step succeeds the deferred one gives the same bits; where it fails the
    /// deferred one gives a non-finite value (the trace the kernel's end test sees). Over random
    /// coefficients, many of them without a root, with zero and non-finite ones mixed in.
    #[test]
    fn a_deferred_step_equals_the_checked_one_or_leaves_a_non_finite_trace() {
        let cfg = NewtonConfig::default();
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let special = [0.0, -0.0, f64::NAN, f64::INFINITY, -f64::INFINITY];
        let pick = |rng: &mut Rng| {
            let k = rng.uniform(0.0, 1.0);
            if k < 0.1 {
                special[(rng.uniform(0.0, 5.0) as usize).min(4)]
            } else {
                10f64.powf(rng.uniform(-3.0, 3.0)) * rng.uniform(-1.0, 1.0)
            }
        };
        let (mut roots, mut failures) = (0, 0);
        for n in 0..200_000 {
            let (a, b, c) = (pick(&mut rng), pick(&mut rng), pick(&mut rng));
            let flip = n % 2 == 0;
            let r2 = a * a + b * b;
            match root_offset(r2 - c * c, r2, c, flip, &cfg) {
                Ok(d) if r2 - c * c >= 0.0 => assert_eq!(d.to_bits(), root_offset_deferred(r2 - c * c, flip).to_bits()),
                // A limit position rounded past: the checked kernel's own answer.
                Ok(_) => assert!(root_offset_deferred(r2 - c * c, flip).is_nan()),
                Err(_) => {}
            }
            match dyad_roots(a, b, c, flip, &cfg) {
                Ok((cq, sq)) if r2 - c * c >= 0.0 => {
                    roots += 1;
                    let (dc, ds) = dyad_roots_deferred(a, b, c, flip);
                    assert_eq!((cq.to_bits(), sq.to_bits()), (dc.to_bits(), ds.to_bits()), "{a} {b} {c}");
                }
                Ok(_) => assert!(dyad_roots_deferred(a, b, c, flip).0.is_nan()),
                Err(_) => {
                    failures += 1;
                    let (dc, ds) = dyad_roots_deferred(a, b, c, flip);
                    assert!(!(dc + ds).is_finite(), "{a} {b} {c}: {dc} {ds}");
                }
            }
            match polar_norm(r2, a, b, &cfg) {
                Ok(ir) => assert_eq!(ir.to_bits(), polar_norm_deferred(r2).to_bits()),
                // The direction `(a, b)` scaled by the norm, as the generated code forms it.
                Err(_) => {
                    let ir = polar_norm_deferred(r2);
                    assert!(!(a * ir + b * ir).is_finite(), "{a} {b}: {ir}");
                }
            }
        }
        assert!(roots > 10_000 && failures > 10_000, "{roots} roots, {failures} failures");
    }

    /// A closed-form angle lies within `π` of its guess (to rounding), whichever way it is
    /// formed: `asin` on the guess's side, `atan2` or `acos` moved to the guess's turn (the
    /// anchored form of a sweep's cache returns an angle within 1 of the guess, or one of
    /// these). Over guesses up to the bound and random angles.
    #[test]
    fn a_closed_form_angle_lies_within_a_half_turn_of_its_guess() {
        use crate::solvers::closed::{acos_on_side, asin_near, reduce_turn, unwrap_to_turn};
        use core::f64::consts::{FRAC_PI_2, PI};
        let mut rng = Rng(0x0123_4567_89ab_cdef);
        let mut worst = 0.0f64;
        for _ in 0..200_000 {
            let g = rng.uniform(-1.0, 1.0) * SURELY_PRECISE_GUESS;
            let t = rng.uniform(-PI, PI);
            let (s, c) = t.sin_cos();
            let r = reduce_turn(g);
            for q in [
                asin_near(s, r.abs() < FRAC_PI_2, r, g),
                unwrap_to_turn(s.atan2(c), g),
                unwrap_to_turn(acos_on_side(c, s), g),
            ] {
                worst = worst.max((q - g).abs());
                assert!(q.abs() <= SURELY_PRECISE_ANGLE, "{q} from {g}");
            }
        }
        assert!(worst <= PI + 1e-11 && worst > PI - 1e-3, "{worst}");
    }

    /// The bound is the least of the configured ones: at the smallest residual tolerance, and
    /// below it (clamped to 16 eps).
    #[test]
    fn the_surely_precise_angle_is_the_least_configured_bound() {
        for tol in [16.0 * f64::EPSILON, 1e-300, 0.0, 1e-12, 1e-6] {
            let cfg = NewtonConfig { residual_tol: tol, ..NewtonConfig::default() };
            assert!(SURELY_PRECISE_ANGLE <= largest_precise_angle(&cfg), "{tol:e}");
        }
        let least = NewtonConfig { residual_tol: 16.0 * f64::EPSILON, ..NewtonConfig::default() };
        assert_eq!(SURELY_PRECISE_ANGLE, largest_precise_angle(&least));
    }
}
