//! Point solves at a limit position of the input, beyond the closed forms' sizes. A four-bar
//! driven by its rocker and an offset slider-crank whose rod is too short for the crank to turn
//! have inputs with limit positions, where two assembly modes meet: a closed form's discriminant
//! is zero there (its double root) and the Jacobian singular. At size 1 the closed forms give
//! the position there (`position_flat`), and `kinematics_flat` reports the analogs singular
//! where the position is the double root. At sizes beyond `1e±144` the closed forms' squares
//! leave `f64` and the rescue solves the position by Newton over the whole system
//! (`runtime/src/mechanism/extreme_scale.rs`), which reaches a double root only linearly and
//! failed there as singular: the four-bar's `position_flat` at its limit, and up to about
//! `1e-14` rad inside it, at every size from `1e-300` to `1e300`, where size 1 gave the
//! position.
//!
//! **How well a position at a limit is determined.** Along the fold's null direction (the
//! coupler turning by `t` with the crank following, or the slider's rod by `t`) the loop's gap
//! is `g - kappa t^2 / 2`: `g` the gap at the fold, which the input opens at a rate `slope` per
//! radian inside the limit, and `kappa` the gap's curvature. A solve's position closes the gap
//! (the loop's equation across the fold, whose gradient vanishes there) to the rounding of its
//! terms, about `eps M` for a loop of magnitude `M` (the sum of its lengths), up to a factor 3
//! for the sines, the products and the scaled lengths' own rounding: its `t` satisfies
//! `|kappa t^2 / 2 - g| <= 3 eps M`. Two such positions on the same side of
//! the fold (the same assembly mode) are at most `sqrt(12 eps M / kappa)` apart
//! (`|sqrt(u + e1) - sqrt(u + e2)| <= sqrt(|e1 - e2|)`); within a few units in the last place of
//! the limit, where the two modes are that close themselves, each lies within
//! `sqrt(2 (g + 3 eps M) / kappa)` of the fold, twice that apart: the square root of the
//! rounding, about `1e-7` rad here, not `eps`. The other unknown moves in proportion (`ratio`).
//! The closed forms at size 1 are checked against independent constructions to the same bounds.

use kinloop::{Error, NewtonConfig};
use kinloop_fixtures::SliderCrank;
use std::f64::consts::PI;

use crate::support::{circle_point, four_bar_angles};

kinloop::mechanism! {
    /// A four-bar driven by its rocker `a` (the input `phi`): coupler `b` at `beta`, crank `c`
    /// at `gamma` about `D = (d, 0)`. No outputs: every value of its state is an angle or an
    /// analog of one, the same at every size.
    pub struct RockerDriven {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

/// The sizes beyond the closed forms' (`1e±144`).
pub(crate) const SIZES: [f64; 6] = [1e-300, 1e-200, 1e-160, 1e160, 1e200, 1e300];

/// The rocker-driven four-bar at size 1: Grashof (`c + d = 5 <= a + b = 6.5`) with the crank
/// `c` shortest, so the rocker `a` swings between the positions where coupler and crank lie in
/// line, `|BD| = b + c` (stretched) and `|BD| = b - c` (folded), `B` the rocker's end.
pub(crate) const ROCKER: [f64; 4] = [3.0, 3.5, 1.0, 4.0];

/// The offset slider-crank at size 1 (crank, rod, offset): the rod too short for the crank to
/// turn (`l < r + e`).
const SLIDER: [f64; 3] = [1.0, 1.2, 0.5];

/// How closely a position closes its loop, in `eps` of the loop's magnitude: at the double
/// nearest a root, each of the residual's terms (a length times a sine or cosine, or a length)
/// is within an ulp of itself for the sine or cosine and half of one for the product, and its
/// three additions add half an ulp of the magnitude each: `3 eps M`; the position's own
/// rounding (half an ulp of an angle below 4, `eps`) moves it by at most `(b + c) eps`, `0.4
/// eps M` here. The closed forms' positions at size 1 close their loops to `0.3 eps M`,
/// Newton's iterated to the rounding to `0.5`; Newton's stopped `4e-8` rad from the root,
/// `4.5`.
const ROUNDING: f64 = 3.5;

/// A limit position of a mechanism's input and what determines a position there (see the
/// module's documentation).
struct Limit {
    what: &'static str,
    /// The input's limit, from its closed form (`acos` or `asin`, within an ulp of the exact
    /// one).
    x: f64,
    /// The side on which the mechanism assembles: `1.0` above `x`, `-1.0` below.
    inward: f64,
    /// How fast the gap at the fold opens, per radian of input inside the limit.
    slope: f64,
    /// The gap's curvature along the fold's null direction, per radian squared of the first
    /// unknown.
    kappa: f64,
    /// The loop's magnitude, the sum of its lengths.
    magnitude: f64,
    /// How far each unknown moves along the null direction per radian of the first (for a
    /// length, in fractions of the size).
    ratio: [f64; 2],
    /// A guess on one assembly mode, and that mode's position at an input by an independent
    /// construction (at the limit or beyond its rounding, the fold).
    guess: [f64; 2],
    reference: fn(f64) -> [f64; 2],
}

impl Limit {
    /// The inputs: the limit, one and two units in the last place inside it (where the two
    /// assembly modes are as close as the rounding can tell), `1e-14` inside (where the rescue
    /// failed too, its Newton not telling the modes apart at its tolerances), and `1e-12` and
    /// `1e-10` inside, each with how far inside it is.
    fn inputs(&self) -> Vec<(f64, f64)> {
        let step = |x: f64| if self.inward > 0.0 { x.next_up() } else { x.next_down() };
        let (one, two) = (step(self.x), step(step(self.x)));
        let mut xs = vec![self.x, one, two];
        xs.extend([1e-14, 1e-12, 1e-10].map(|d| self.x + self.inward * d));
        xs.into_iter().map(|x| (x, (x - self.x).abs())).collect()
    }

    /// The largest gap at the fold at an input `inside` from the limit: the input's own distance
    /// and the limit's rounding (two units in the last place of its input), and the rounding
    /// of the loop's terms.
    fn gap(&self, inside: f64) -> f64 {
        let ulp = self.x.abs() * f64::EPSILON;
        self.slope * (inside + 2.0 * ulp) + 3.0 * f64::EPSILON * self.magnitude
    }

    /// Whether the two assembly modes at an input `inside` from the limit are apart by more
    /// than the rounding can blur: Newton iterated to the rounding tells them apart once
    /// quadratic convergence shows (a step a tenth of the one before) above the rounding, where
    /// the mode it converges to is nearer than an eighth of their distance: `g >= 16 (3 eps M)`.
    /// Called so with a factor 20 to spare.
    fn apart(&self, inside: f64) -> bool {
        let blurred = 16.0 * 3.0 * f64::EPSILON * self.magnitude / self.slope;
        inside >= 20.0 * blurred
    }

    /// How far the first unknown of two solves at an input `inside` from the limit may be
    /// apart: on one mode, `sqrt(12 eps M / kappa)`; where the modes are blurred, either one,
    /// each within `sqrt(2 g / kappa)` of the fold.
    fn bound(&self, inside: f64) -> f64 {
        let eps_m = f64::EPSILON * self.magnitude;
        if self.apart(inside) {
            (12.0 * eps_m / self.kappa).sqrt()
        } else {
            2.0 * (2.0 * self.gap(inside) / self.kappa).sqrt()
        }
    }

    /// Whether the two modes at an input `inside` from the limit close the loop to the residual
    /// tolerance everywhere between them (the gap at the fold, `slope inside`, within the
    /// tolerance of the magnitude), so that Newton at that tolerance cannot tell either from the
    /// fold: there a point solve of the analogs may report the position singular (its Newton
    /// reaches it linearly), as the closed form does at the limit.
    fn within_tolerance(&self, inside: f64) -> bool {
        self.slope * inside <= NewtonConfig::default().residual_tol * self.magnitude
    }
}

/// The four-bar's four limit positions at size 1: `|BD| = r` (`b + c` stretched, `b - c`
/// folded) at `phi = +-acos((a^2 + d^2 - r^2) / (2 a d))`, on each of the two modes (`side`, of
/// `four_bar_angles`). At the fold `C` lies on the line `BD`; turning the coupler by `t` moves
/// `C` by `b t` across it and the crank by `(b / c) t`. Along `BD` the coupler's end comes back
/// by `b t^2 / 2` and the crank's by `(b^2 / c) t^2 / 2`, toward `B` stretched and away from it
/// folded: `kappa = b (b + c) / c` stretched, `b (b - c) / c` folded. `|BD|^2 = a^2 + d^2 - 2 a d
/// cos phi`, so the gap opens at `a d |sin phi| / |BD|` per radian.
fn rocker_limits() -> Vec<Limit> {
    let [a, b, c, d] = ROCKER;
    let mut limits = Vec::new();
    for (what, r, kappa, inward) in
        [("stretched", b + c, b * (b + c) / c, -1.0), ("folded", b - c, b * (b - c) / c, 1.0)]
    {
        let x = ((a * a + d * d - r * r) / (2.0 * a * d)).acos();
        for (sign, side) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let x = sign * x;
            let inward = sign * inward;
            // A guess on the mode, a tenth of a radian inside the limit: the position a sweep
            // would have come from.
            let guess = four_bar_angles(a, b, c, d, x + inward * 0.1, side).expect("inside the limit");
            let reference: fn(f64) -> [f64; 2] =
                if side > 0.0 { |x| rocker_reference(x, 1.0) } else { |x| rocker_reference(x, -1.0) };
            limits.push(Limit {
                what,
                x,
                inward,
                slope: a * d * x.sin().abs() / r,
                kappa,
                magnitude: a + b + c + d,
                ratio: [1.0, b / c],
                guess,
                reference,
            });
        }
    }
    limits
}

/// The slider-crank's two limit positions at size 1: `r sin phi - e = -l`, the rod across the
/// slider's line (`psi = -pi / 2`), at `phi = pi + asin((l - e) / r)` (assembling below it) and
/// `2 pi - asin((l - e) / r)` (above it), from the declared guess. Turning the rod by `t` from
/// there leaves its end `l t^2 / 2` short of the line (`kappa = l`) and moves the slider by
/// `l t`; the crank's end moves across the line at `r |cos phi|` per radian. Reference: `psi =
/// asin((r sin phi - e) / l)`, the declared guess's mode (`cos psi >= 0`), and `x = r cos phi -
/// l cos psi`, in fractions of the size.
fn slider_limits() -> Vec<Limit> {
    let [r, l, e] = SLIDER;
    let reach = ((l - e) / r).asin();
    let reference: fn(f64) -> [f64; 2] = |x| {
        let [r, l, e] = SLIDER;
        let psi = ((r * x.sin() - e) / l).clamp(-1.0, 1.0).asin();
        [psi, r * x.cos() - l * psi.cos()]
    };
    [(PI + reach, -1.0), (2.0 * PI - reach, 1.0)]
        .into_iter()
        .map(|(x, inward)| Limit {
            what: "slider-crank",
            x,
            inward,
            slope: r * x.cos().abs(),
            kappa: l,
            magnitude: r + l + e,
            ratio: [1.0, l],
            guess: [0.0, -l],
            reference,
        })
        .collect()
}

/// The rocker-driven four-bar's angles at `phi` on the mode `side` (of `four_bar_angles`), from
/// the circles about `B` and `D`: at a limit rounded past, the fold (`circle_point` takes the
/// intersection's offset from the line `BD` as 0 where the circles just miss).
fn rocker_reference(phi: f64, side: f64) -> [f64; 2] {
    let [a, b, c, d] = ROCKER;
    let (bx, by) = (a * phi.cos(), a * phi.sin());
    let (cx, cy) = circle_point(bx, by, b, d, 0.0, c, side);
    [(cy - by).atan2(cx - bx), cy.atan2(cx - d)]
}

/// Largest difference of the unknowns `q` (at size `k`; lengths `lengths`) from `base` (at size
/// 1), each over its share `ratio` of the null direction: in radians of the first unknown.
fn distance(q: &[f64; 2], base: &[f64; 2], lengths: [bool; 2], ratio: [f64; 2], k: f64) -> f64 {
    (0..2).fold(0.0f64, |m, u| {
        let d = (q[u] / if lengths[u] { k } else { 1.0 } - base[u]).abs() / ratio[u];
        m.max(if d.is_nan() { f64::INFINITY } else { d })
    })
}

/// Every limit of `limits` at every input of [`Limit::inputs`]: at size 1 the closed form's
/// position, checked against the construction, and its kinematics; at each size of
/// [`SIZES`], `at(k)`'s positions (`position_flat`, and the named `position` to the bit) within
/// [`Limit::bound`] of size 1's, and its kinematics as size 1's: singular where size 1's is;
/// where size 1's solves, the same positions and velocity analogs, unless the modes are within
/// the residual tolerance of the fold ([`Limit::within_tolerance`]: then it may be singular) or
/// the analogs' acceleration terms at size `k` leave `f64` (a length times a squared velocity
/// analog beyond `f64::MAX`: then an analog not finite). The largest position difference seen,
/// as a fraction of its bound.
fn check<M>(at: impl Fn(f64) -> M, limits: &[Limit], lengths: [bool; 2], closes: bool) -> f64
where
    M: kinloop::Named<2, 1, 0>,
{
    let cfg = NewtonConfig::default();
    let one = at(1.0);
    let mut worst = 0.0f64;
    // The guess at size `k`: its lengths scaled.
    let scaled = |g: [f64; 2], k: f64| [0, 1].map(|u| if lengths[u] { g[u] * k } else { g[u] });
    for lim in limits {
        let guess = lim.guess;
        for (x, inside) in lim.inputs() {
            let what = format!("{} limit {} of {} from {guess:?}, {inside:e} inside", lim.what, lim.x, M::NAME);
            let bound = lim.bound(inside);
            let (base, _) = one.position_flat(&[x], &guess, &cfg).unwrap_or_else(|e| panic!("{what} at size 1: {e}"));
            let reference = (lim.reference)(x);
            let off = distance(&base, &reference, [false; 2], lim.ratio, 1.0);
            assert!(off <= bound, "{what}: size 1 {base:?}, the construction {reference:?}: {off:e} > {bound:e}");
            // The loop's residual at size `k` at the position `q`, in `eps` of its magnitude.
            let residual = |m: &M, q: &[f64; 2], k: f64| {
                let f = m.residual_flat(&[x], q).iter().fold(0.0f64, |m, f| m.max(f.abs()));
                f / (f64::EPSILON * lim.magnitude * k)
            };
            if closes {
                let r = residual(&one, &base, 1.0);
                assert!(r <= ROUNDING, "{what}: size 1 {base:?}, residual {r} eps of the loop");
            }
            let base_kin = one.kinematics_flat(&[x], &guess, &cfg);
            if let Err(e) = &base_kin {
                assert!(matches!(e, Error::Singular { .. }), "{what} at size 1: {e}");
            }
            for k in SIZES {
                let (m, guess) = (at(k), scaled(guess, k));
                let (q, _) =
                    m.position_flat(&[x], &guess, &cfg).unwrap_or_else(|e| panic!("{what} at size {k:e}: {e}"));
                let off = distance(&q, &base, lengths, lim.ratio, k);
                assert!(off <= bound, "{what} at size {k:e}: {q:?} against {base:?} at size 1: {off:e} > {bound:e}");
                worst = worst.max(off / bound);
                if closes {
                    let r = residual(&m, &q, k);
                    assert!(r <= ROUNDING, "{what} at size {k:e}: {q:?}, residual {r} eps of the loop");
                }
                let named: [f64; 2] = m.position([x], &guess.into()).unwrap().0.into();
                assert_eq!(q, named, "{what} at size {k:e}");
                let kin = m.kinematics_flat(&[x], &guess, &cfg);
                match (&base_kin, kin) {
                    (Err(_), Err(e)) => assert!(matches!(e, Error::Singular { .. }), "{what} at size {k:e}: {e}"),
                    (Err(e), Ok(s)) => panic!("{what} at size {k:e}: solved {:?}, singular at size 1: {e}", s.q),
                    (Ok(b), Ok(s)) => {
                        let off = distance(&s.q, &b.q, lengths, lim.ratio, k);
                        assert!(off <= bound, "{what} at size {k:e}: {:?} against {:?}: {off:e}", s.q, b.q);
                        // Near the fold a velocity analog is about one over the distance `t`
                        // from it (`t = sqrt(2 slope inside / kappa)`), so a position `bound`
                        // off moves it by `bound / t` of itself; twice that for the analogs'
                        // own rounding. Where the modes are blurred `t` is not known.
                        if lim.apart(inside) {
                            let t = (2.0 * lim.slope * inside / lim.kappa).sqrt();
                            for (u, &length) in lengths.iter().enumerate() {
                                let scale = if length { k } else { 1.0 };
                                let (v, v1) = (s.dq[u][0] / scale, b.dq[u][0]);
                                let rel = (v - v1).abs() / v1.abs();
                                assert!(rel <= 2.0 * bound / t, "{what} at size {k:e}: analog {u} {v} against {v1}");
                            }
                        }
                    }
                    (Ok(b), Err(e)) => {
                        let most = b.dq.iter().fold(0.0f64, |m, d| m.max(d[0].abs()));
                        let overflows = k * lim.magnitude * most * most > f64::MAX;
                        let allowed = match e {
                            Error::Singular { .. } => lim.within_tolerance(inside),
                            Error::Domain { what: quantity, .. } => overflows && quantity.is_acceleration(),
                            _ => false,
                        };
                        assert!(allowed, "{what} at size {k:e}: {e}, where size 1 solves");
                    }
                }
            }
        }
    }
    worst
}

/// The rocker-driven four-bar at each of its four limit positions, on each assembly mode.
/// `position_flat` failed as singular at the limit and up to `1e-14` inside it, at every size
/// beyond the closed forms' (Newton over the whole system stopped its coupler `4e-8` to `6e-8`
/// rad from the double root, still halving its steps).
#[test]
fn a_four_bar_at_its_inputs_limit_solves_as_at_size_one() {
    let [a, b, c, d] = ROCKER;
    let at = |k: f64| RockerDriven { a: a * k, b: b * k, c: c * k, d: d * k };
    let worst = check(at, &rocker_limits(), [false, false], true);
    eprintln!("rocker-driven four-bar at its limits over sizes: positions within {worst:.2} of their bound");
}

/// The offset slider-crank at its input's two limit positions: its rod's angle is a closed form
/// free of squares (an arcsine), whose positions need no rescue at any size; its analogs do.
#[test]
fn a_slider_crank_at_its_inputs_limit_solves_as_at_size_one() {
    let [r, l, e] = SLIDER;
    let at = |k: f64| SliderCrank { r: r * k, l: l * k, e: e * k };
    // Its closed form takes the slider from the rod's cosine (the root's square root) and the
    // rod's angle from the arcsine of its rounded sine: at the fold, a cosine of about `2e-8`,
    // that rounding moves the angle by `eps / 2e-8`, `5e-9` rad. Each unknown is within its
    // bound, but the loop along the slider's line, steep in the angle there, is left `5e-10` of
    // the size open at size 1: its residual is not checked.
    let worst = check(at, &slider_limits(), [false, true], false);
    eprintln!("slider-crank at its limits over sizes: positions within {worst:.2} of their bound");
}
