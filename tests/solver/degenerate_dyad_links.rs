//! A dyad with a link below the rounding of its size, in every path that solves it: the
//! declaration's order of its unknowns (which link is the closed form's first), a coefficient
//! folded to a constant, sizes beyond `1e±77` (the coefficients rescaled), and its Newton twin.
//! Where the loop closes at every angle of the short link, that angle is not determined by the
//! data: the singular position of the block, as the four-bar declared `beta, gamma` with a
//! coupler of `1e-20` reports it. Each case's closing is computed here in plain f64, over 64
//! angles of the short link, independent of the solver.

use crate::support::assert_singular_block_0;
use kinloop::{Error, Mechanism, NewtonConfig};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

with_newton_twin! {
    /// A four-bar whose unknowns are declared rocker first: the closed form's dyad takes the
    /// rocker `c` as its first link and the coupler `b` as its second.
    pub struct GammaFirst, GammaFirstNewton {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns gamma = 1.5, beta = 0.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

with_newton_twin! {
    /// The same four-bar declared coupler first, as the fixtures' `FourBar`.
    pub struct BetaFirst, BetaFirstNewton {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

with_newton_twin! {
    /// A dyad whose first centre `(s, 0)` slides along the frame: the centres' offset has a
    /// zero component, so a coefficient of its equation is folded to a constant.
    pub struct SlideDyad, SlideDyadNewton {
        params b, c, d;
        input s;
        unknowns beta = 0.1, gamma = 3.0;
        loop sbcd: (s, 0) + b @ beta == (d, 0) + c @ gamma;
    }
}

with_newton_twin! {
    /// [`SlideDyad`] declared rocker first.
    pub struct SlideDyadGammaFirst, SlideDyadGammaFirstNewton {
        params b, c, d;
        input s;
        unknowns gamma = 3.0, beta = 0.1;
        loop sbcd: (s, 0) + b @ beta == (d, 0) + c @ gamma;
    }
}

/// The largest miss, relative to `size`, of the loop `p + short @ t == q` over `samples`
/// angles `t`, with `p` and `q` the ends the long links put the short link between.
fn worst_miss(p: [f64; 2], short: f64, q: [f64; 2], size: f64, samples: usize) -> f64 {
    let miss = |t: f64| (p[0] + short * t.cos() - q[0]).hypot(p[1] + short * t.sin() - q[1]);
    (0..samples).map(|k| miss(TAU * k as f64 / samples as f64)).fold(0.0, f64::max) / size
}

/// The four-bar of unit crank, rocker and frame with a coupler of `1e-20` or `1e-300` of them,
/// at a crank angle of `fl(π/3)` (the crank pin `1 - 9.9e-17` from the rocker's pivot) and
/// `π/3 + 1e-12` (`8.7e-13` beyond the rocker's reach, within the default tolerance `1e-12` of
/// the loop's size): with the rocker towards the pin, every coupler angle closes the loop within
/// the tolerance of its size. Declared `beta, gamma` the closed form reports the singular
/// position of block 0. Declared `gamma, beta`, the coupler is the dyad's second link, and the
/// closed form gave the coupler's angle from rounding (`-1.047` rad at `π/3 + 1e-12`, where the
/// links in line were taken for the limit position) or, with the coupler's square underflowed
/// to zero, a `Domain` error on the loop's equation `abcd.x` (the division by the second link's
/// length); at sizes of `1e±100` (its coefficients rescaled) the coupler at `0.52` rad. It is
/// now the same singular position of block 0, at every size, as is the Newton twin's.
#[test]
fn a_coupler_below_the_tolerance_is_singular_whichever_unknown_is_declared_first() {
    let cfg = NewtonConfig::default();
    // Beyond `1e±77` the closed form's coefficients are rescaled.
    for scale in [1.0, 1e-3, 1e3, 1e100, 1e-100] {
        for coupler in [1e-20, 1e-300] {
            for phi in [PI / 3.0, PI / 3.0 + 1e-12] {
                let at = format!("scale {scale}, coupler {coupler:e}, phi {phi}");
                let (a, b, c, d) = (scale, coupler * scale, scale, scale);
                let pin = [a * phi.cos(), a * phi.sin()];
                let gamma = pin[1].atan2(pin[0] - d);
                let rocker_end = [d + c * gamma.cos(), c * gamma.sin()];
                let worst = worst_miss(pin, b, rocker_end, a + b + c + d, 64);
                assert!(worst <= cfg.residual_tol, "{at}: every coupler angle misses by {worst:e} at most");
                let beta_first = BetaFirst { a, b, c, d };
                assert_singular_block_0(beta_first.kinematics_flat(&[phi], &[0.5, 1.5], &cfg), &at);
                let closed = GammaFirst { a, b, c, d };
                let newton = GammaFirstNewton { a, b, c, d };
                let guess = [1.5, 0.5];
                assert_singular_block_0(closed.kinematics_flat(&[phi], &guess, &cfg), &format!("{at}, closed form"));
                assert_singular_block_0(closed.position_flat(&[phi], &guess, &cfg), &format!("{at}, closed form"));
                assert_singular_block_0(newton.kinematics_flat(&[phi], &guess, &cfg), &format!("{at}, Newton"));
                assert_singular_block_0(newton.position_flat(&[phi], &guess, &cfg), &format!("{at}, Newton"));
            }
        }
    }
}

/// A dyad whose first centre slides along the frame (a coefficient folded to a constant), with
/// a rocker, its SECOND link, of `1e-20` or `1e-100` of the coupler, at the slide's position
/// where the coupler's end lies exactly on the rocker's pivot (`|s - d| = b`): every rocker
/// angle closes the loop within `4 eps` of its size. The folded closed form, which has no cold
/// branch for a triangle that closes, returned the rocker at `π/2` (the exact triangle's); at
/// sizes of `1e±100` (rescaled) the same, though the four-bar of the fixtures, crank angle `0`
/// on a frame of 2, was singular. Both, and the four-bar at `fl(π/3)` on a frame of 1 (the pin
/// `9.9e-17` off the pivot) which gave the rocker `0` rad at `1e-100`, are the singular
/// position of block 0.
#[test]
fn a_second_link_below_the_rounding_is_singular_folded_and_rescaled() {
    let cfg = NewtonConfig::default();
    for scale in [1.0, 1e-3, 1e3, 1e100, 1e-100] {
        for rocker in [1e-20, 1e-100] {
            let at = format!("scale {scale:e}, rocker {rocker:e}");
            let (b, c, d, s) = (scale, rocker * scale, 2.0 * scale, scale);
            // The coupler from the slide along the frame, its end on the pivot `(d, 0)`.
            let worst = worst_miss([d, 0.0], c, [d, 0.0], b + c + (s - d).abs(), 64);
            assert!(worst <= 4.0 * f64::EPSILON, "{at}: every rocker angle misses by {worst:e} at most");
            let m = SlideDyad { b, c, d };
            assert_singular_block_0(m.kinematics_flat(&[s], &[0.1, 3.0], &cfg), &format!("{at}, folded"));
            assert_singular_block_0(m.position_flat(&[s], &[0.1, 3.0], &cfg), &format!("{at}, folded"));
            for (frame, phi) in [(2.0, 0.0), (1.0, PI / 3.0)] {
                let at = format!("{at}, four-bar of frame {frame} at {phi}");
                let (a, b, c, d) = (scale, scale, rocker * scale, frame * scale);
                let pin = [a * phi.cos(), a * phi.sin()];
                let beta = (-pin[1]).atan2(d - pin[0]);
                let end = [pin[0] + b * beta.cos(), pin[1] + b * beta.sin()];
                let worst = worst_miss([d, 0.0], c, end, a + b + c + d, 64);
                assert!(worst <= 4.0 * f64::EPSILON, "{at}: every rocker angle misses by {worst:e} at most");
                let m = BetaFirst { a, b, c, d };
                assert_singular_block_0(m.kinematics_flat(&[phi], &[0.5, 1.5], &cfg), &at);
                assert_singular_block_0(m.position_flat(&[phi], &[0.5, 1.5], &cfg), &at);
            }
        }
    }
}

/// The block and the kind of a failure (`None` for a solution): what a verdict at one size
/// must be at every other.
fn verdict<T>(r: &Result<T, Error>) -> Option<(usize, std::mem::Discriminant<Error>)> {
    let e = r.as_ref().err()?;
    Some((e.location().and_then(|l| l.block.as_ref()).map_or(usize::MAX, |(k, _)| *k), std::mem::discriminant(e)))
}

/// The four-bar declared coupler first (the fixtures' `FourBar`) and its Newton twin beyond the
/// closed forms' sizes (`1e±160`, `1e±200`), where a failed step is solved again by Newton over
/// the whole system in the mechanism's own magnitudes: a rocker of `1e-20` of the others at the
/// input where the coupler's end reaches the rocker's pivot (frame 2 at `0`, exactly; frame 1 at
/// `fl(π/3)`, within `1e-16`), and a coupler of `1e-20` on the crank pin that the rocker
/// reaches (frame 1 at `fl(π/3)`, and `π/3 + 1e-12`, `8.7e-13` beyond the rocker's reach). At
/// size 1 every angle of the short link closes the loop within the tolerance of its size
/// (`4 eps` where the pin is on the pivot; plain f64, 64 angles) and the closed form reports
/// the singular position of block 0, for the analogs and the positions alone; every size gives
/// the verdict of size 1, for the Newton twin too. The closed form's analogs at `1e±160` and
/// `1e±200` with the rocker on frame 2 were the rocker at its guess `1.5` rad (a value the data
/// do not determine) and its velocity analog, where size 1 is singular.
#[test]
fn a_link_below_the_rounding_is_singular_beyond_the_closed_forms_sizes() {
    let cfg = NewtonConfig::default();
    // (crank, coupler, rocker, frame, input) at size 1, and the worst miss allowed.
    let cases = [
        (1.0, 1.0, 1e-20, 2.0, 0.0, 4.0 * f64::EPSILON),
        (1.0, 1.0, 1e-20, 1.0, PI / 3.0, 4.0 * f64::EPSILON),
        (1.0, 1e-20, 1.0, 1.0, PI / 3.0, 4.0 * f64::EPSILON),
        (1.0, 1e-20, 1.0, 1.0, PI / 3.0 + 1e-12, cfg.residual_tol),
    ];
    let guess = [0.5, 1.5];
    for (a, b, c, d, phi, within) in cases {
        let pin = [a * phi.cos(), a * phi.sin()];
        let worst = if c < b {
            let beta = (-pin[1]).atan2(d - pin[0]);
            worst_miss([d, 0.0], c, [pin[0] + b * beta.cos(), pin[1] + b * beta.sin()], a + b + c + d, 64)
        } else {
            let gamma = pin[1].atan2(pin[0] - d);
            worst_miss(pin, b, [d + c * gamma.cos(), c * gamma.sin()], a + b + c + d, 64)
        };
        let case = format!("links {a}, {b}, {c}, {d} at {phi}");
        assert!(worst <= within, "{case}: every short-link angle misses by {worst:e} at most");
        let solves = |s: f64| {
            let [a, b, c, d] = [a, b, c, d].map(|l| l * s);
            let (closed, newton) = (BetaFirst { a, b, c, d }, BetaFirstNewton { a, b, c, d });
            [
                verdict(&closed.kinematics_flat(&[phi], &guess, &cfg)),
                verdict(&closed.position_flat(&[phi], &guess, &cfg)),
                verdict(&newton.kinematics_flat(&[phi], &guess, &cfg)),
                verdict(&newton.position_flat(&[phi], &guess, &cfg)),
            ]
        };
        let closed = BetaFirst { a, b, c, d };
        assert_singular_block_0(closed.kinematics_flat(&[phi], &guess, &cfg), &format!("{case}: analogs"));
        assert_singular_block_0(closed.position_flat(&[phi], &guess, &cfg), &format!("{case}: positions"));
        let at_1 = solves(1.0);
        for scale in [1e160, 1e-160, 1e200, 1e-200] {
            assert_eq!(solves(scale), at_1, "{case}, scale {scale:e}: closed form's analogs, positions; Newton's");
        }
    }
}

/// A solve's position `[beta, gamma]` and, for the analogs, their velocity analogs in the
/// same order.
type Solve = Result<([f64; 2], Option<[f64; 2]>), Error>;

/// A dyad whose triangle closes exactly with one link `short` of the others, in every
/// declaration: the slide dyad at `s = 1` on a frame of 2 (its coupler of 1 from the slide ends
/// on the rocker's pivot, or its rocker of 1 from the pivot ends on the slide) and the four-bar
/// of unit crank on a frame of 2 at a crank angle of 0 (the coupler of 1 from the pin ends on
/// the rocker's pivot, or the rocker of 1 on the pin), each with the short link the closed
/// form's first (`first`) or second link, at size `scale`. Returns the solves (closed form's
/// analogs, positions; the Newton twin's analogs, positions), each in the order `[beta,
/// gamma]`, and the worst miss of the loop over 64 angles of the short link relative to its
/// size, computed here in plain f64.
fn exact_triangle_solves(slide: bool, short_coupler: bool, first: bool, short: f64, scale: f64) -> ([Solve; 4], f64) {
    exact_triangle_solves_from(slide, short_coupler, first, short, scale, false)
}

/// [`exact_triangle_solves`], with the long link's guess its angle in the triangle (`pi` for
/// the rocker, `0` for the coupler) where `exact_long` holds: the guess then meets the residual
/// tolerance (the short link's angle moves the loop by rounding only) and Newton corrects it
/// once, without iterating.
fn exact_triangle_solves_from(
    slide: bool,
    short_coupler: bool,
    first: bool,
    short: f64,
    scale: f64,
    exact_long: bool,
) -> ([Solve; 4], f64) {
    let cfg = NewtonConfig::default();
    let (long, short) = (scale, short * scale);
    let (b, c) = if short_coupler { (short, long) } else { (long, short) };
    let d = 2.0 * scale;
    // The pin (the slide's centre or the crank's end) at `(scale, 0)`, the pivot at `(d, 0)`: the
    // long link along the frame between them, the short link between its end and the other.
    let pin = [scale, 0.0];
    let worst = if short_coupler {
        worst_miss(pin, b, [d - c, 0.0], pin[0] + b + c + d, 64)
    } else {
        worst_miss([d, 0.0], c, [pin[0] + b, 0.0], pin[0] + b + c + d, 64)
    };
    // Each mechanism's unknowns (and guesses) in its own order, from and to `[beta, gamma]`.
    let order = |q: [f64; 2]| if first == short_coupler { q } else { [q[1], q[0]] };
    macro_rules! solves {
        ($closed:expr, $newton:expr, $x:expr, $guess:expr) => {{
            let (x, guess) = ([$x], order($guess));
            let analogs = |k: kinloop::Kin<2, 1, _>| (order(k.q), Some(order(k.dq.map(|row| row[0]))));
            let positions = |p: ([f64; 2], _)| (order(p.0), None);
            [
                $closed.kinematics_flat(&x, &guess, &cfg).map(analogs),
                $closed.position_flat(&x, &guess, &cfg).map(positions),
                $newton.kinematics_flat(&x, &guess, &cfg).map(analogs),
                $newton.position_flat(&x, &guess, &cfg).map(positions),
            ]
        }};
    }
    let a = scale;
    let guess = |mut g: [f64; 2]| {
        if exact_long {
            if short_coupler { g[1] = PI } else { g[0] = 0.0 }
        }
        g
    };
    let (sg, fg) = (guess([0.1, 3.0]), guess([0.5, 1.5]));
    let solves = match (slide, first == short_coupler) {
        (true, true) => solves!(SlideDyad { b, c, d }, SlideDyadNewton { b, c, d }, scale, sg),
        (true, false) => solves!(SlideDyadGammaFirst { b, c, d }, SlideDyadGammaFirstNewton { b, c, d }, scale, sg),
        (false, true) => solves!(BetaFirst { a, b, c, d }, BetaFirstNewton { a, b, c, d }, 0.0, fg),
        (false, false) => solves!(GammaFirst { a, b, c, d }, GammaFirstNewton { a, b, c, d }, 0.0, fg),
    };
    (solves, worst)
}

const SOLVES: [&str; 4] =
    ["closed form's analogs", "closed form's positions", "Newton's analogs", "Newton's positions"];

/// A dyad's FIRST link below the rounding of its loop where the triangle closes exactly (see
/// [`exact_triangle_solves`]): every angle of it closes the loop within `4 eps` of its size, so
/// the data do not determine it, and every solve, closed form and Newton twin, analogs and
/// positions alone, reports the singular position of block 0, at sizes `1e-3`, 1 and `1e3` and
/// beyond the closed forms' sizes (`1e±200`). Its equation's `d2` does not cancel there (the
/// short link's own square is below the rounding of `c`, which is then exactly 0), so no cold
/// branch of the closed form saw it: the slide dyad with a coupler of `1e-20` was `Ok([π/2,
/// π])`, the coupler at right angles to nothing; the four-bar the same.
#[test]
fn a_first_link_below_the_rounding_on_an_exact_triangle_is_singular() {
    for slide in [true, false] {
        for short_coupler in [true, false] {
            for short in [1e-20, 1e-100] {
                for scale in [1.0, 1e-3, 1e3, 1e200, 1e-200] {
                    let at = format!("slide {slide}, short coupler {short_coupler}, {short:e}, scale {scale:e}");
                    let (solves, worst) = exact_triangle_solves(slide, short_coupler, true, short, scale);
                    assert!(worst <= 4.0 * f64::EPSILON, "{at}: every short-link angle misses by {worst:e} at most");
                    for (r, what) in solves.into_iter().zip(SOLVES) {
                        assert_singular_block_0(r.map(|s| s.0), &format!("{at}: {what}"));
                    }
                }
            }
        }
    }
}

/// The Newton twin of a dyad whose SECOND link (the closed form's) is below the rounding of its
/// loop where the triangle closes exactly (see [`exact_triangle_solves`]): singular in block 0,
/// as the closed form. The short link's Jacobian column is as long as the link at every angle,
/// below the rounding of the loop's magnitude, so Newton's steps leave its angle near its guess
/// and the iteration converges: the slide dyad with a rocker of `1e-20` was `Ok([1.9e-21,
/// 2.95])`, the four-bar's rocker `1.4999999986` (its guess 1.5) with a velocity analog of
/// `-1`, a value the data do not determine; each a position at `1e±200` as well. From a guess
/// whose long link is exact (it meets the tolerance: Newton corrects it once) as well.
#[test]
fn a_newton_link_below_the_rounding_that_stays_near_its_guess_is_singular() {
    for slide in [true, false] {
        for short_coupler in [true, false] {
            for first in [true, false] {
                for (scale, exact_long) in
                    [1.0, 1e-3, 1e3, 1e200, 1e-200].into_iter().flat_map(|s| [(s, false), (s, true)])
                {
                    let at = format!(
                        "slide {slide}, short coupler {short_coupler}, first {first}, scale {scale:e}, exact {exact_long}"
                    );
                    let (solves, worst) =
                        exact_triangle_solves_from(slide, short_coupler, first, 1e-20, scale, exact_long);
                    assert!(worst <= 4.0 * f64::EPSILON, "{at}: every short-link angle misses by {worst:e} at most");
                    for (r, what) in solves.into_iter().zip(SOLVES).skip(2) {
                        assert_singular_block_0(r.map(|s| s.0), &format!("{at}: {what}"));
                    }
                }
            }
        }
    }
}

/// The positions and velocity analogs `[beta, gamma, dbeta, dgamma]` of [`exact_triangle_solves`]'s
/// dyads with the short link `short` of the others (the scale 1), built here in plain f64 from
/// the isosceles triangle of the long link, the long centres' offset and the short link (apex
/// angle `t = 2 asin(short / 2)`), on the branch whose short-link angle has the sign `side`;
/// the analogs by Cramer's rule from the loop's derivative `P' + i b beta' e^(i beta) = i c
/// gamma' e^(i gamma)` (`P'` the pin's velocity: `(1, 0)` for the slide, `(0, 1)` for the crank
/// at 0).
fn exact_triangle_reference(slide: bool, short_coupler: bool, short: f64, side: f64) -> [f64; 4] {
    let t = 2.0 * (short / 2.0).asin();
    let (beta, gamma, b, c) = if short_coupler {
        // The rocker of 1 from `(2, 0)` to near the pin `(1, 0)`, the coupler across the base.
        (side * (FRAC_PI_2 - t / 2.0), side * (PI - t), short, 1.0)
    } else {
        // The coupler of 1 from the pin to near the pivot, the rocker across the base.
        (side * t, side * (FRAC_PI_2 + t / 2.0), 1.0, short)
    };
    let w = if slide { [1.0, 0.0] } else { [0.0, 1.0] };
    let u = [-b * beta.sin(), b * beta.cos()];
    let v = [c * gamma.sin(), -c * gamma.cos()];
    let cross = |p: [f64; 2], q: [f64; 2]| p[0] * q[1] - p[1] * q[0];
    let det = cross(u, v);
    let minus_w = [-w[0], -w[1]];
    [beta, gamma, cross(minus_w, v) / det, cross(u, minus_w) / det]
}

/// No false alarm: the dyads of [`exact_triangle_solves`] with the short link `1e-8` or `1e-12`
/// of the others, far above the rounding of the loop, every declaration, at sizes `1e-3`, 1
/// and `1e3`: every solve is a position, the closed form's and the Newton twin's, and it is the
/// triangle built in plain f64 ([`exact_triangle_reference`], either branch), its analogs
/// Cramer's rule's. The short link's direction is the difference of positions known to the
/// rounding of the size, so its angle is known to about `eps / short` (and the analogs, which
/// divide by it, to that relative error): within `64 eps / short`. At `1e-10` the Newton twin
/// may also stall at the singular position of the long links in line (reported as block 0's),
/// never at another position.
#[test]
fn a_link_above_the_rounding_on_an_exact_triangle_is_solved() {
    let mut worst = 0.0f64;
    let mut stalled = 0;
    for slide in [true, false] {
        for short_coupler in [true, false] {
            for first in [true, false] {
                for short in [1e-8, 1e-10, 1e-12] {
                    for scale in [1.0, 1e-3, 1e3] {
                        let at = format!(
                            "slide {slide}, short coupler {short_coupler}, first {first}, {short:e}, scale {scale:e}"
                        );
                        let (solves, _) = exact_triangle_solves(slide, short_coupler, first, short, scale);
                        let closed_tol = 64.0 * f64::EPSILON / short;
                        // Newton stops where the loop misses by at most the residual tolerance
                        // of its rows' magnitude (4), which a turn `t` of the short link makes
                        // at least `(2 / pi) short t`: `t` up to `(pi / 2) sqrt(2) 4 tol / short`
                        // (8.9 tol / short: at `1e-12`, any angle).
                        let newton_tol = closed_tol + 16.0 * NewtonConfig::default().residual_tol / short;
                        // At `1e-12` every angle of the short link meets Newton's residual test
                        // (a chord of at most `2e-12` within `1e-12` of the loop's magnitude 4),
                        // which cannot tell them apart (it reports the singular position where
                        // the angle moved turns away): only the closed form is held there. At
                        // `1e-10` Newton may stall where the Jacobian is singular and no step
                        // closes the loop further (the rocker along the coupler, the loop open by
                        // the rocker's length): that is the singular position, which it reported
                        // as a position (the rocker at `3.139` rad for `pi / 2`) before.
                        let newton = (short >= 1e-10).then_some(newton_tol);
                        let may_stall = [false, false, short < 1e-8, short < 1e-8];
                        let tols = [Some(closed_tol), Some(closed_tol), newton, newton];
                        for (((r, what), tol), may_stall) in solves.into_iter().zip(SOLVES).zip(tols).zip(may_stall) {
                            let Some(tol) = tol else { continue };
                            if may_stall && matches!(r, Err(kinloop::Error::Singular { .. })) {
                                assert_singular_block_0(r, &format!("{at}: {what}"));
                                stalled += 1;
                                continue;
                            }
                            let (q, dq) = r.unwrap_or_else(|e| panic!("{at}: {what}: {e}"));
                            // The branch of the short link's angle.
                            let side = if short_coupler { q[1].sin() } else { q[0].sin() }.signum();
                            let want = exact_triangle_reference(slide, short_coupler, short, side);
                            for k in 0..2 {
                                // Angles compared modulo a turn (`pi + 1e-12` is `-pi + 1e-12`).
                                let err = ((q[k] - want[k] + PI).rem_euclid(TAU) - PI).abs();
                                worst = worst.max(err / tol);
                                assert!(err <= tol, "{at}: {what}: q[{k}] {} against {}", q[k], want[k]);
                            }
                            // Dimensionless analogs: per unit crank angle, or per slide over the size.
                            for (k, v) in dq.into_iter().flatten().enumerate() {
                                let got = if slide { v * scale } else { v };
                                let err = (got - want[2 + k]).abs() / want[2 + k].abs().max(1.0);
                                worst = worst.max(err / tol);
                                assert!(err <= tol, "{at}: {what}: dq[{k}] {got} against {}", want[2 + k]);
                            }
                        }
                    }
                }
            }
        }
    }
    println!("worst error over its bound: {worst:e}, {stalled} Newton solves stalled at the singular position");
}

/// The worst miss of the loop `a @ phi + b @ beta == (d, 0) + c @ gamma` at `q = [beta, gamma]`,
/// relative to its magnitude `a + b + c + d` (plain f64).
fn four_bar_miss([a, b, c, d]: [f64; 4], phi: f64, [beta, gamma]: [f64; 2]) -> f64 {
    let x = a * phi.cos() + b * beta.cos() - d - c * gamma.cos();
    let y = a * phi.sin() + b * beta.sin() - c * gamma.sin();
    x.abs().max(y.abs()) / (a + b + c + d)
}

/// The worst miss of the class IV group's two loops at `q = [th1, th2, psi1, psi2]` (the
/// fixture's declaration, in plain f64), relative to each loop's magnitude.
fn class_four_miss(m: &kinloop_fixtures::ClassFour, phi: f64, [th1, th2, psi1, psi2]: [f64; 4]) -> f64 {
    let p = |l: f64, t: f64| [l * t.cos(), l * t.sin()];
    let a = p(m.oa, phi);
    let (ac, cd, bd) = (p(m.ac, th1), p(m.cd, psi1), p(m.bd, th2));
    let (ae, ef, bf) = (p(m.ae, th1 + m.alpha_a), p(m.ef, psi2), p(m.bf, th2 + m.alpha_b));
    let b = [m.xb, m.yb];
    let first = m.oa + m.ac + m.cd + m.bd + m.xb.abs() + m.yb.abs();
    let second = m.oa + m.ae + m.ef + m.bf + m.xb.abs() + m.yb.abs();
    (0..2)
        .map(|k| {
            let one = (a[k] + ac[k] + cd[k] - b[k] - bd[k]).abs() / first;
            one.max((a[k] + ae[k] + ef[k] - b[k] - bf[k]).abs() / second)
        })
        .fold(0.0, f64::max)
}

/// No false alarm on regular mechanisms: the Grashof four-bar (crank 1, coupler 3, rocker 2.5,
/// frame 3.2), by its closed form and its Newton twin, and the fixtures' class IV group (a
/// Newton block of four angles), over a turn of the input (72 steps, each from the last) at
/// sizes `1e-3`, 1 and `1e3`: every step is a position, its loops close within the residual
/// tolerance of their magnitudes (computed here in plain f64), and its velocity analogs are
/// the central differences of the positions (step `h = 1e-5`: truncation `h² q''' / 6`, about
/// `2e-10` for third derivatives up to 10, and rounding `eps / h`, `2e-11`; held to `1e-8` of
/// `max(1, |dq|)`).
#[test]
fn regular_mechanisms_are_solved_at_every_size() {
    let cfg = NewtonConfig::default();
    let h = 1e-5;
    let fd_tol = 1e-8;
    let close = |got: f64, fd: f64| (got - fd).abs() <= fd_tol * fd.abs().max(1.0);
    for scale in [1.0, 1e-3, 1e3] {
        let links = [1.0, 3.0, 2.5, 3.2].map(|l| l * scale);
        let [a, b, c, d] = links;
        let (closed, newton) = (BetaFirst { a, b, c, d }, BetaFirstNewton { a, b, c, d });
        let (mut gc, mut gn) = ([0.5, 1.5], [0.5, 1.5]);
        for i in 0..72 {
            let phi = 0.3 + TAU * i as f64 / 72.0;
            let at = format!("four-bar at size {scale:e}, phi {phi}");
            let kc = closed.kinematics_flat(&[phi], &gc, &cfg).unwrap_or_else(|e| panic!("{at}: closed form: {e}"));
            let kn = newton.kinematics_flat(&[phi], &gn, &cfg).unwrap_or_else(|e| panic!("{at}: Newton: {e}"));
            for (k, what) in [(&kc, "closed form"), (&kn, "Newton")] {
                assert!(four_bar_miss(links, phi, k.q) <= cfg.residual_tol, "{at}: {what}: {:?}", k.q);
            }
            let pos = |m: &dyn Fn(f64) -> [f64; 2]| [m(phi + h), m(phi - h)];
            let [up, down] = pos(&|x| closed.position_flat(&[x], &kc.q, &cfg).unwrap().0);
            for u in 0..2 {
                let fd = (up[u] - down[u]) / (2.0 * h);
                assert!(close(kc.dq[u][0], fd), "{at}: closed form's dq[{u}] {} against {fd}", kc.dq[u][0]);
                assert!(close(kn.dq[u][0], fd), "{at}: Newton's dq[{u}] {} against {fd}", kn.dq[u][0]);
            }
            (gc, gn) = (kc.q, kn.q);
        }
        let m = class_four_at(scale);
        let mut g = m.guess_flat(&[0.3]);
        for i in 0..72 {
            let phi = 0.3 + TAU * i as f64 / 72.0;
            let at = format!("class IV at size {scale:e}, phi {phi}");
            let k = m.kinematics_flat(&[phi], &g, &cfg).unwrap_or_else(|e| panic!("{at}: {e}"));
            let q: [f64; 4] = k.q[..4].try_into().unwrap();
            assert!(class_four_miss(&m, phi, q) <= cfg.residual_tol, "{at}: {q:?}");
            let up = m.position_flat(&[phi + h], &k.q, &cfg).unwrap_or_else(|e| panic!("{at}: {e}")).0;
            let down = m.position_flat(&[phi - h], &k.q, &cfg).unwrap_or_else(|e| panic!("{at}: {e}")).0;
            for u in 0..4 {
                let fd = (up[u] - down[u]) / (2.0 * h);
                assert!(close(k.dq[u][0], fd), "{at}: dq[{u}] {} against {fd}", k.dq[u][0]);
            }
            g = k.q;
        }
    }
}

/// The fixtures' class IV group at size `k`: its lengths times `k`, its ternary links' angles
/// as they are.
pub(crate) fn class_four_at(k: f64) -> kinloop_fixtures::ClassFour {
    let d = kinloop_fixtures::ClassFour::default();
    kinloop_fixtures::ClassFour {
        oa: d.oa * k,
        xb: d.xb * k,
        yb: d.yb * k,
        ac: d.ac * k,
        ae: d.ae * k,
        bd: d.bd * k,
        bf: d.bf * k,
        cd: d.cd * k,
        ef: d.ef * k,
        ..d
    }
}
