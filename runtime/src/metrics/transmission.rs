//! The transmission angle of a loop: the acute angle between the coupler and the follower it
//! drives. Near zero the coupler pushes along the follower and cannot turn it (a dead point);
//! designers keep its minimum above about 40 degrees.

use crate::Kernel;
use crate::analysis::column::{column_kind, column_name};
use crate::analysis::extremes::{Corner, extremes_across};
use crate::analysis::{ColumnOf, Jet, SampledOf, bracketed_root};
use crate::error::Error;
use crate::kinds::QuantityKind;
use crate::paths::sweep::MAX_TURNS;
use std::f64::consts::{FRAC_PI_2, PI};

/// The acute angle, in `[0, pi/2]`, between the line of the coupler (at angle `coupler`) and
/// the line of the follower (at angle `follower`), both in radians from any common reference.
///
/// Lines, not directions: the transmission angle does not change when a link is measured from
/// its other end (an angle plus `pi`). NaN where an angle, or their difference, is not finite:
/// no line to measure from.
///
/// ```
/// use kinloop_runtime::metrics::transmission_angle;
/// use std::f64::consts::PI;
/// assert!((transmission_angle(0.2, 0.2 + PI / 3.0) - PI / 3.0).abs() < 1e-15);
/// // 120 degrees between the links is a 60 degree transmission angle.
/// assert!((transmission_angle(0.2, 0.2 + 2.0 * PI / 3.0) - PI / 3.0).abs() < 1e-15);
/// ```
pub fn transmission_angle(coupler: f64, follower: f64) -> f64 {
    let d = (follower - coupler).rem_euclid(PI);
    // `max` takes the number beside a NaN: an angle not finite read as 0, a dead point.
    if d.is_nan() {
        return f64::NAN;
    }
    d.min(PI - d).max(0.0)
}

/// A transmission angle and the input where it occurs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngleAt {
    /// Input value.
    pub x: f64,
    /// Transmission angle there, in `[0, pi/2]` radians.
    pub angle: f64,
}

/// The transmission angle over a sweep: its located minimum and maximum, and the dead points
/// (coupler and follower collinear) crossed.
#[derive(Clone, Debug, PartialEq)]
pub struct TransmissionRange {
    /// The smallest transmission angle over the range (the design figure of merit).
    pub min: AngleAt,
    /// The largest transmission angle over the range.
    pub max: AngleAt,
    /// Inputs where coupler and follower are collinear (transmission angle zero), increasing.
    pub dead_points: Vec<f64>,
}

/// The relative angle `follower - coupler` as a jet.
fn difference(c: &Jet, f: &Jet) -> Jet {
    Jet { x: c.x, value: f.value - c.value, d1: f.d1 - c.d1, d2: f.d2 - c.d2 }
}

/// The transmission angle over a sweep from the jets of the coupler and follower angles sampled
/// at the same increasing inputs; `eval` gives both jets at any input of the range.
///
/// The transmission angle is a fold of the relative angle `d = follower - coupler`, monotone
/// wherever `d` is monotone and between multiples of `pi/2`. So its extremes lie at the ends,
/// at the extremes of `d` (roots of its velocity analog, located by
/// [`extremes()`](crate::analysis::extremes::extremes)) or where `d` crosses a multiple of
/// `pi/2` (located by [`bracketed_root`]): all are evaluated exactly. As for extremes, two
/// events closer than one sample spacing are not separated: sample finely enough.
///
/// Errors (`InvalidArgument`): samples of other inputs or not increasing, a value not finite,
/// a relative angle too large to tell its quarter turns apart (beyond `2^52` of them), or one
/// turning more than [`MAX_TURNS`] turns over the samples.
pub fn transmission_range(
    coupler: &[Jet],
    follower: &[Jet],
    eval: impl FnMut(f64) -> Result<(Jet, Jet), Error>,
) -> Result<TransmissionRange, Error> {
    transmission_range_across(coupler, follower, [&[], &[]], eval)
}

/// [`transmission_range`] with the coupler's and the follower's `corners` (the singular
/// crossings between samples, see `extremes_across`, at the same places for both): an extreme
/// of the relative angle across a corner is at the corner, as is a multiple of `pi/2` it crosses
/// there (at a change point coupler and follower may lie flat, a dead point, at the crossing
/// itself), located without evaluating inside it, where the mechanism cannot be solved.
fn transmission_range_across(
    coupler: &[Jet],
    follower: &[Jet],
    corners: [&[Corner]; 2],
    mut eval: impl FnMut(f64) -> Result<(Jet, Jet), Error>,
) -> Result<TransmissionRange, Error> {
    if coupler.len() != follower.len() || coupler.iter().zip(follower).any(|(c, f)| c.x != f.x) {
        return Err(Error::InvalidArgument("coupler and follower must be sampled at the same inputs".into()));
    }
    let d: Vec<Jet> = coupler.iter().zip(follower).map(|(c, f)| difference(c, f)).collect();
    let corners: Vec<Corner> = corners[0]
        .iter()
        .zip(corners[1])
        .map(|(c, f)| Corner { after: c.after, at: difference(&c.at, &f.at) })
        .collect();
    let mut eval_d = |x: f64| eval(x).map(|(c, f)| difference(&c, &f));
    let mut candidates: Vec<Jet> = d.clone();
    candidates.extend(extremes_across(&d, &corners, &mut eval_d)?.into_iter().map(|e| e.at));
    candidates.extend(corners.iter().map(|c| c.at));
    let mut dead_points = Vec::new();
    // A sample exactly on a multiple of pi/2 (a dead point only when the multiple is even).
    for j in &d {
        let k = j.value / FRAC_PI_2;
        if k.fract() == 0.0 && k.rem_euclid(2.0) == 0.0 {
            dead_points.push(j.x);
        }
    }
    check_turns(&d)?;
    for (i, w) in d.windows(2).enumerate() {
        let (lo, hi) = (w[0].value.min(w[1].value), w[0].value.max(w[1].value));
        let corner = corners.iter().find(|c| c.after == i);
        // Multiples of pi/2 strictly inside the interval's values.
        let mut k = (lo / FRAC_PI_2).floor() + 1.0;
        while k * FRAC_PI_2 < hi {
            let level = k * FRAC_PI_2;
            let root = match corner {
                Some(c) => c.at,
                None => bracketed_root(w[0], w[1], |j| (j.value - level, j.d1), &mut eval_d)?,
            };
            if k.rem_euclid(2.0) == 0.0 {
                dead_points.push(root.x);
            }
            candidates.push(Jet { value: level, ..root });
            k += 1.0;
        }
    }
    let at = |j: &Jet| AngleAt { x: j.x, angle: transmission_angle(0.0, j.value) };
    let mut min = at(&candidates[0]);
    let mut max = min;
    for c in candidates.iter().map(at) {
        if c.angle < min.angle {
            min = c;
        }
        if c.angle > max.angle {
            max = c;
        }
    }
    dead_points.sort_by(f64::total_cmp);
    dead_points.dedup();
    Ok(TransmissionRange { min, max, dead_points })
}

/// Refuses, before any is located, a relative angle whose multiples of `pi/2` the search
/// cannot step through: beyond `2^52` quarter turns consecutive multiples are the same `f64`
/// (the search would never end), and a relative angle turning more than a sweep follows
/// ([`MAX_TURNS`] turns) over the samples would take hours of root finding.
fn check_turns(d: &[Jet]) -> Result<(), Error> {
    let quarters = |v: f64| (v / FRAC_PI_2).floor();
    if let Some(j) = d.iter().find(|j| quarters(j.value).abs() >= 2f64.powi(52)) {
        return Err(Error::InvalidArgument(format!(
            "the relative angle of follower and coupler is {} rad at x = {}, too large to tell its quarter turns apart",
            j.value, j.x
        )));
    }
    let turns = d.windows(2).map(|w| (quarters(w[1].value) - quarters(w[0].value)).abs()).sum::<f64>() / 4.0;
    if turns > MAX_TURNS {
        return Err(Error::InvalidArgument(format!(
            "the relative angle of follower and coupler turns {turns:.3e} times over the samples, more than the {MAX_TURNS:e} turns of a sweep"
        )));
    }
    Ok(())
}

impl<K: Kernel> SampledOf<K> {
    /// The transmission angle's range ([`transmission_range`]) over a sampled sweep, the coupler
    /// and follower angles given by their columns (`Name::COL.beta`, `Name::COL.gamma`, or their
    /// names), as functions of the path parameter (the input, for one input).
    ///
    /// Errors (`InvalidArgument`): a column the mechanism knows is not an angle (a length, a
    /// ratio: `Name::COL.p.x`), or the same column twice; those of [`transmission_range`].
    pub fn transmission(
        &self,
        coupler: impl ColumnOf<K>,
        follower: impl ColumnOf<K>,
    ) -> Result<TransmissionRange, Error> {
        let (coupler, follower) = (coupler.resolve(self.kernel())?, follower.resolve(self.kernel())?);
        // Of a length the "angle" was a number of length units, and of one column twice the
        // relative angle zero: either gave a range as `Ok` (every sample a dead point for the
        // latter). A column of a kind not inferred may be an angle, and is taken as one.
        let k = self.kernel();
        for c in [coupler, follower] {
            let kind = column_kind(k, c);
            if matches!(kind, QuantityKind::Length | QuantityKind::Dimensionless) {
                return Err(Error::InvalidArgument(format!(
                    "the transmission angle is between two link angles, and `{}` of `{}` is {}: give the \
                     coupler's and the follower's angle columns",
                    column_name(k, c),
                    k.name(),
                    if kind == QuantityKind::Length { "a length" } else { "a dimensionless number" }
                )));
            }
        }
        if coupler == follower {
            return Err(Error::InvalidArgument(format!(
                "the transmission angle is between two link angles, and both are `{}` of `{}`: give the coupler's \
                 and the follower's angle columns",
                column_name(k, coupler),
                k.name()
            )));
        }
        // Between the samples as `extremes` looks: the samples alone missed a maximum between
        // two of them (a turn in four samples gave 1.551 for pi / 2); across the singular
        // crossings the sweep passed as `extremes` does too (the search stepped into a change
        // point's singular band and failed).
        self.searched_pair(coupler, follower, |[(cj, cc), (fj, fc)], at| {
            transmission_range_across(cj, fj, [cc, fc], at)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::test_rng::Rng;

    /// Four-bar `a @ phi + b @ beta == (d, 0) + c @ gamma`, open assembly, in closed form:
    /// the diagonal from B to D and the triangle B-C-D.
    fn four_bar(a: f64, b: f64, c: f64, d: f64, phi: f64) -> Option<(f64, f64)> {
        let (bx, by) = (a * phi.cos(), a * phi.sin());
        let (ex, ey) = (d - bx, -by);
        let e = ex.hypot(ey);
        let cos_t = (b * b + e * e - c * c) / (2.0 * b * e);
        if !(-1.0..=1.0).contains(&cos_t) {
            return None;
        }
        let beta = ey.atan2(ex) + cos_t.acos();
        let (cx, cy) = (bx + b * beta.cos(), by + b * beta.sin());
        Some((beta, (cy).atan2(cx - d)))
    }

    #[test]
    fn transmission_angle_matches_the_law_of_cosines_for_random_four_bars() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut checked = 0;
        for _ in 0..2000 {
            let (a, b, c, d) =
                (rng.uniform(0.2, 3.0), rng.uniform(0.2, 3.0), rng.uniform(0.2, 3.0), rng.uniform(0.2, 3.0));
            let phi = rng.uniform(-7.0, 7.0);
            let scale = 10f64.powf(rng.uniform(-6.0, 3.0));
            let Some((beta, gamma)) = four_bar(a * scale, b * scale, c * scale, d * scale, phi) else { continue };
            // Interior angle at C between the coupler and the rocker (independent of the angles).
            let cos_mu = (b * b + c * c - a * a - d * d + 2.0 * a * d * phi.cos()) / (2.0 * b * c);
            let expected = cos_mu.abs().min(1.0).acos();
            let got = transmission_angle(beta, gamma);
            // acos loses accuracy near mu = 0 (slope 1/sin mu): compare cosines there.
            assert!((got.cos() - cos_mu.abs()).abs() < 1e-12, "{a} {b} {c} {d} {phi}: {got} vs {expected}");
            assert!((0.0..=FRAC_PI_2).contains(&got));
            checked += 1;
        }
        assert!(checked > 500, "too few assemblable designs: {checked}");
    }

    #[test]
    fn transmission_range_locates_the_minimum_of_a_known_relative_angle() {
        // d(x) = 1 + 0.7 sin x: its minimum 0.3 (at 3 pi/2) is the smallest transmission angle
        // and it crosses pi/2 (the largest, pi/2) at x = asin((pi/2 - 1)/0.7).
        let coupler = |x: f64| Jet { x, value: 0.5 * x, d1: 0.5, d2: 0.0 };
        let follower =
            |x: f64| Jet { x, value: 1.0 + 0.5 * x + 0.7 * x.sin(), d1: 0.5 + 0.7 * x.cos(), d2: -0.7 * x.sin() };
        let xs: Vec<f64> = (0..=40).map(|i| i as f64 * std::f64::consts::TAU / 40.0).collect();
        let (c, f): (Vec<Jet>, Vec<Jet>) = xs.iter().map(|&x| (coupler(x), follower(x))).unzip();
        let r = transmission_range(&c, &f, |x| Ok((coupler(x), follower(x)))).unwrap();
        assert!((r.min.angle - 0.3).abs() < 1e-15 && (r.min.x - 1.5 * PI).abs() < 1e-7, "{r:?}");
        assert!((r.max.angle - FRAC_PI_2).abs() < 1e-15);
        let first = ((FRAC_PI_2 - 1.0) / 0.7).asin();
        assert!((r.max.x - first).abs() < 1e-12 || (r.max.x - (PI - first)).abs() < 1e-12, "{r:?}");
        assert!(r.dead_points.is_empty());
    }

    #[test]
    fn dead_points_are_where_the_relative_angle_crosses_a_multiple_of_pi() {
        // d(x) = x - 1 crosses 0 at x = 1 and pi at 1 + pi.
        let f = |x: f64| Jet { x, value: x - 1.0, d1: 1.0, d2: 0.0 };
        let zero = |x: f64| Jet { x, ..Jet::default() };
        let xs: Vec<f64> = (0..=30).map(|i| i as f64 * 0.2).collect();
        let (c, fo): (Vec<Jet>, Vec<Jet>) = xs.iter().map(|&x| (zero(x), f(x))).unzip();
        let r = transmission_range(&c, &fo, |x| Ok((zero(x), f(x)))).unwrap();
        assert_eq!(r.dead_points.len(), 2);
        assert!((r.dead_points[0] - 1.0).abs() < 1e-15 && (r.dead_points[1] - 1.0 - PI).abs() < 1e-14);
        assert_eq!(r.min.angle, 0.0);
    }

    /// A relative angle whose quarter turns cannot be stepped through is refused, not searched:
    /// at 1e17 rad consecutive multiples of pi/2 are one `f64` (the search never ended), and
    /// 1e12 rad between two samples is 6e11 quarter turns to locate (hours).
    #[test]
    fn relative_angles_beyond_the_search_are_refused() {
        let zero = |x: f64| Jet { x, ..Jet::default() };
        for (start, rate) in [(1e17, 64.0), (0.0, 1e12)] {
            let f = |x: f64| Jet { x, value: start + rate * x, d1: rate, d2: 0.0 };
            let r = transmission_range(&[zero(0.0), zero(1.0)], &[f(0.0), f(1.0)], |x| Ok((zero(x), f(x))));
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("relative angle")), "{r:?}");
        }
    }

    /// An angle that is not finite has no line: the transmission angle is NaN, not 0 (a dead
    /// point, the worst a design can have), which it read as.
    #[test]
    fn an_angle_not_finite_has_no_transmission_angle() {
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(transmission_angle(v, 0.3).is_nan(), "{v}");
            assert!(transmission_angle(0.3, v).is_nan(), "{v}");
        }
        // Finite angles whose difference overflows: no line either.
        assert!(transmission_angle(-f64::MAX, f64::MAX).is_nan());
        assert_eq!(transmission_angle(-0.0, 0.0), 0.0);
    }

    #[test]
    fn mismatched_samples_are_an_error() {
        let j = |x: f64| Jet { x, ..Jet::default() };
        let r = transmission_range(&[j(0.0), j(1.0)], &[j(0.0), j(2.0)], |x| Ok((j(x), j(x))));
        assert!(matches!(r, Err(Error::InvalidArgument(_))));
    }
}
