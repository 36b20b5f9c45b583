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
//! angles' guesses: against the configured bound less a margin ([`largest_deferred_guess`]).
//! Where a test fails, the kernel runs again with every check on the way, which returns the
//! error the checked kernel reports (with its block, input and guess), or the state where every
//! check passes after all (a limit position rounded past, see
//! [`root_offset`]; an angle whose guess lies within the margin of
//! the configured bound). The tests are conservative only: they never accept what a check
//! rejects (`tests/solver/deferred_checks.rs` compares the two kernels where every check fails).
//!
//! Measured with callgrind (`benches/callgrind.sh`, 720 samples a turn), a `Sweep` sample of the
//! rhombic drive took 76 fewer instructions (756 to 680), the gear-lever's 55 (664 to 609) and
//! the four-bar's 40 (666 to 626): tested on the way, each check cost a branch, a closure and
//! the values its error needs kept alive.

use super::closed::{
    check_closed, dyad_of, dyad_of_deferred, dyad_roots, dyad_roots_deferred, dyad_roots_in, folded_dyad_root_offset,
    folded_root_offset, folded_root_offset_in, largest_precise_angle, polar_norm, polar_norm_deferred, root_offset,
    root_offset_deferred,
};
use super::newton::{BlockFailure, NewtonConfig};

/// How far below the configured bound ([`largest_precise_angle`]) a deferred kernel's
/// closed-form angles' guesses must stay ([`largest_deferred_guess`]).
///
/// A closed-form angle lies within `π` of its guess (moved to the guess's turn, or `asin` on the
/// guess's side of the vertical and turn). A sweep's cache may instead advance it from an
/// anchor, by less than `asin(1/8)`; the anchor is libm's angle, within `π` of the guess of an
/// earlier call, which passed the same test under the same configuration (the sweep forgets its
/// anchors when its configuration changes). Either way the angle is within `π + asin(1/8)`
/// (3.27) of a guess at most [`largest_deferred_guess`], so at most the configured bound: the
/// checked kernel's test of the angles would pass. The margin of 8 leaves room to spare.
pub const GUESS_MARGIN: f64 = 8.0;

/// The largest sum of the magnitudes of its closed-form angles' guesses a deferred kernel
/// accepts on entry under `cfg`: [`largest_precise_angle`] less [`GUESS_MARGIN`] (4.5e6 rad,
/// 700,000 turns, by default; 15,992 rad, 2545 turns, at the smallest residual tolerance,
/// 16 eps). Larger ones go to the checked kernel, which tests the angles themselves.
#[inline(always)]
pub fn largest_deferred_guess(cfg: &NewtonConfig) -> f64 {
    largest_precise_angle(cfg) - GUESS_MARGIN
}

/// [`largest_deferred_guess`] at the smallest residual tolerance (16 eps), the least of all:
/// `1000 · 16 eps / eps - 8`, 15,992 rad (2545 turns).
pub const LEAST_DEFERRED_GUESS: f64 = 16_000.0 - GUESS_MARGIN;

/// How a kernel tests: every check on the way (`CHECKED`), or deferred to its end. The kernel
/// binds it once (`__mode`) and asks it for its closed-form steps, which are then the checked
/// ones or the deferred ones (see [`root_offset_deferred`]), and for what follows a failed test
/// (`rerun` and `finish`, which run the mechanism's kernel: defined with the `Mechanism` trait,
/// in `generated`, above the solvers).
#[derive(Clone, Copy, Debug)]
pub struct Checks<const CHECKED: bool>;

impl<const CHECKED: bool> Checks<CHECKED> {
    /// [`root_offset`], or deferred [`root_offset_deferred`] (never
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

    /// [`folded_root_offset`], or deferred as [`Checks::root_offset`] (a coefficient's square
    /// out of range leaves a trace that is not finite, and the checked step rescales).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn folded_root_offset(
        self,
        d2: f64,
        r2: f64,
        a: f64,
        b: f64,
        c: f64,
        flip: bool,
        cfg: &NewtonConfig,
    ) -> Result<f64, BlockFailure> {
        if CHECKED { folded_root_offset(d2, r2, a, b, c, flip, cfg) } else { self.root_offset(d2, r2, c, flip, cfg) }
    }

    /// [`folded_root_offset_in`], or deferred as [`Checks::root_offset`] (`terms` not called).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn folded_root_offset_in(
        self,
        d2: f64,
        r2: f64,
        a: f64,
        b: f64,
        c: f64,
        flip: bool,
        cfg: &NewtonConfig,
        terms: impl FnOnce() -> f64,
    ) -> Result<f64, BlockFailure> {
        if CHECKED {
            folded_root_offset_in(d2, r2, a, b, c, flip, cfg, terms)
        } else {
            self.root_offset(d2, r2, c, flip, cfg)
        }
    }

    /// [`dyad_roots_in`], or deferred [`dyad_roots_deferred`] (`terms` not called).
    #[inline(always)]
    pub fn dyad_roots_in(
        self,
        a: f64,
        b: f64,
        c: f64,
        flip: bool,
        cfg: &NewtonConfig,
        terms: impl FnOnce() -> f64,
    ) -> Result<(f64, f64), BlockFailure> {
        if CHECKED { dyad_roots_in(a, b, c, flip, cfg, terms) } else { Ok(dyad_roots_deferred(a, b, c, flip)) }
    }

    /// [`folded_dyad_root_offset`], or deferred as [`Checks::root_offset`] (as
    /// [`Checks::folded_root_offset`]).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn folded_dyad_root_offset(
        self,
        d2: f64,
        r2: f64,
        a: f64,
        b: f64,
        c: f64,
        links: [f64; 4],
        flip: bool,
        cfg: &NewtonConfig,
    ) -> Result<f64, BlockFailure> {
        if CHECKED {
            folded_dyad_root_offset(d2, r2, a, b, c, links, flip, cfg)
        } else {
            self.root_offset(d2, r2, c, flip, cfg)
        }
    }

    /// [`dyad_roots`], or deferred [`dyad_roots_deferred`].
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

    /// [`dyad_of`], or deferred [`dyad_of_deferred`].
    #[inline(always)]
    pub fn dyad_of(self, dyad: [f64; 6], c: f64, flip: bool, cfg: &NewtonConfig) -> Result<(f64, f64), BlockFailure> {
        if CHECKED { dyad_of(dyad, c, flip, cfg) } else { Ok(dyad_of_deferred(dyad, c, flip)) }
    }

    /// [`polar_norm`], or deferred [`polar_norm_deferred`].
    #[inline(always)]
    pub fn polar_norm(self, d2: f64, e0: f64, e1: f64, cfg: &NewtonConfig) -> Result<f64, BlockFailure> {
        if CHECKED { polar_norm(d2, e0, e1, cfg) } else { Ok(polar_norm_deferred(d2)) }
    }

    /// [`check_closed`], or deferred nothing (the kernel's end tests
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
    /// may lead to angles too large to be accurate under `cfg` (beyond
    /// [`largest_deferred_guess`]), or are NaN: the kernel then answers as the checked one. (A
    /// sweep's cache may advance an angle without reading its guess, so a NaN guess must not get
    /// that far.)
    // The negated comparison is the point: true for NaN, and one instruction per step less than
    // `> || is_nan()` as compiled (callgrind).
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    #[inline(always)]
    pub fn far(self, magnitudes: f64, cfg: &NewtonConfig) -> bool {
        // `!(magnitudes <= largest_deferred_guess(cfg))`, tested in two: the bound is the larger
        // of `LEAST_DEFERRED_GUESS` and the same formula of the unclamped tolerance (rounding is
        // monotone, so the maximum passes through it; `1000 / eps` is exact, so one product
        // rounds as the two of `largest_precise_angle` do). Nearly every step passes the constant,
        // without reading the configuration: tested at once, the bound cost a sweep's sample 4
        // instructions (callgrind, 720 samples a turn: the rhombic drive's, the four-bar's and
        // the gear-lever's), tested in two at most 1 (the rhombic drive's; the others' none).
        !CHECKED
            && !(magnitudes <= LEAST_DEFERRED_GUESS)
            && !(magnitudes <= cfg.residual_tol * (1000.0 / f64::EPSILON) - GUESS_MARGIN)
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

    /// The configurations the tests below range over: the smallest residual tolerance (16 eps)
    /// and below it (clamped to 16 eps), a sweep's default, the default, the largest valid.
    fn configs() -> [NewtonConfig; 6] {
        [16.0 * f64::EPSILON, 0.0, 1e-300, 1e-14, 1e-12, 1e-3]
            .map(|tol| NewtonConfig { residual_tol: tol, ..NewtonConfig::default() })
    }

    /// A closed-form angle lies within `π` of its guess (to the rounding of the guess's
    /// magnitude), whichever way it is formed: `asin` on the guess's side, `atan2` or `acos`
    /// moved to the guess's turn (the anchored form of a sweep's cache returns an angle within
    /// `asin(1/8)` of an anchor, one of these). Over guesses up to the bound of each
    /// configuration and random angles: every angle passes the checked kernel's test.
    #[test]
    fn a_closed_form_angle_from_an_accepted_guess_passes_the_configured_bound() {
        use crate::solvers::closed::{acos_on_side, asin_near};
        use crate::solvers::turns::{reduce_turn, unwrap_to_turn};
        use core::f64::consts::{FRAC_PI_2, PI};
        let mut rng = Rng(0x0123_4567_89ab_cdef);
        for cfg in configs() {
            let (bound, limit) = (largest_deferred_guess(&cfg), largest_precise_angle(&cfg));
            let mut worst = 0.0f64;
            for k in 0..40_000 {
                // Every fourth guess in the last turn below the bound, where the angles are
                // largest.
                let g = if k % 4 == 0 { bound - rng.uniform(0.0, 6.3) } else { rng.uniform(-1.0, 1.0) * bound };
                let g = if k % 2 == 0 { g } else { -g };
                let t = rng.uniform(-PI, PI);
                let (s, c) = t.sin_cos();
                let r = reduce_turn(g);
                for q in [
                    asin_near(s, r.abs() < FRAC_PI_2, r, g),
                    unwrap_to_turn(s.atan2(c), g),
                    unwrap_to_turn(acos_on_side(c, s), g),
                ] {
                    worst = worst.max((q - g).abs());
                    // An anchor's advance adds at most asin(1/8).
                    assert!(q.abs() + (0.125f64).asin() <= limit, "{q} from {g} under {limit}");
                }
            }
            // The rounding of a guess's turn: a few units in the last place of the bound.
            let rounding = 8.0 * bound * f64::EPSILON;
            assert!(worst <= PI + rounding && worst > PI - 1e-3, "{worst} under {limit}");
        }
    }

    /// The entry test: a guess sum up to the bound passes, the next float above it and NaN do
    /// not; the bound lies the margin below the configured one, which is 16,000 rad (2545 turns)
    /// at the smallest residual tolerance and 4.5e6 (700,000 turns) by default; a checked kernel
    /// never reruns.
    #[test]
    fn the_entry_test_is_the_configured_bound_less_the_margin() {
        for cfg in configs() {
            let bound = largest_deferred_guess(&cfg);
            assert_eq!(bound, largest_precise_angle(&cfg) - GUESS_MARGIN);
            // The margin exceeds the half turn and an anchor's advance, with room for rounding.
            assert!(bound + core::f64::consts::PI + (0.125f64).asin() + 1.0 < largest_precise_angle(&cfg));
            let deferred = Checks::<false>;
            for m in [0.0, 1.0, 15_992.0, bound] {
                assert!(!deferred.far(m, &cfg), "{m} under {bound}");
            }
            for m in [bound.next_up(), 2.0 * bound, f64::INFINITY, f64::NAN] {
                assert!(deferred.far(m, &cfg), "{m} under {bound}");
                assert!(!Checks::<true>.far(m, &cfg));
            }
        }
        let least = NewtonConfig { residual_tol: 16.0 * f64::EPSILON, ..NewtonConfig::default() };
        assert_eq!(largest_precise_angle(&least), 16_000.0);
        assert!(Checks::<false>.far(16_000.0 - 7.9, &least));
        let default = NewtonConfig::default();
        assert_close(largest_deferred_guess(&default), 1e-9 / f64::EPSILON - 8.0);
        assert!(!Checks::<false>.far(4.5e6, &default) && Checks::<false>.far(4.6e6, &default));
    }

    /// The entry test in two is the test against [`largest_deferred_guess`]: at the bound's
    /// neighbours and at random magnitudes, under tolerances from zero (and subnormal) to the
    /// largest valid, 16 eps and its neighbours among them.
    #[test]
    fn the_entry_test_in_two_is_the_test_against_the_bound() {
        let mut rng = Rng(0x5851_f42d_4c95_7f2d);
        let eps16 = 16.0 * f64::EPSILON;
        let mut tols =
            vec![0.0, f64::from_bits(1), 1e-300, eps16.next_down(), eps16, eps16.next_up(), 1e-14, 1e-12, 1e-3];
        tols.extend((0..200).map(|_| 10f64.powf(rng.uniform(-17.0, -3.0))));
        assert_eq!(LEAST_DEFERRED_GUESS, largest_deferred_guess(&NewtonConfig::default().with_residual_tol(eps16)));
        for tol in tols {
            let cfg = NewtonConfig::default().with_residual_tol(tol);
            let bound = largest_deferred_guess(&cfg);
            let mut ms = vec![0.0, bound, bound.next_up(), bound.next_down(), LEAST_DEFERRED_GUESS.next_up(), f64::NAN];
            ms.extend((0..200).map(|_| bound * rng.uniform(0.0, 2.0)));
            for m in ms {
                // `far` is the negation of `m <= bound`: true for NaN too.
                let within = m <= bound;
                assert_eq!(Checks::<false>.far(m, &cfg), !within, "{m} under {tol:e}");
            }
        }
    }

    /// `a` equal to `b` to a few units in the last place.
    fn assert_close(a: f64, b: f64) {
        assert!((a - b).abs() <= 4.0 * f64::EPSILON * b.abs(), "{a} against {b}");
    }
}
