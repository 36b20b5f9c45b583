//! Burmester's curves and points: the dyads that guide a body through four or five poses.
//!
//! Four poses leave one crank rotation free: each `beta_2` gives up to two solutions of the
//! compatibility condition ([`super::compatibility`]), each solution one dyad. The fixed pivots
//! of all of them trace the center-point curve, their moving pivots (in the first pose) the
//! circle-point curve. Five poses impose two such conditions (poses 1-2-3-4 and 1-2-3-5) on the
//! rotations `beta_2 .. beta_5`: four real equations in four unknowns, whose isolated solutions
//! are the Burmester points, at most four (the two center-point curves are cubics that meet in
//! nine points, five of which are the poles shared by both and the two circular points at
//! infinity).

use super::compatibility::Compatibility;
use super::dyad::{Dyad, Pose, check_poses, solve_dyad};
use super::error::ClassicalError;
use super::position::angle_difference;
use crate::Vec2;
use nalgebra::{Complex, Matrix4, Vector4};
use std::f64::consts::TAU;

/// How finely the crank rotation `beta_2` is sampled over a turn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BurmesterConfig {
    /// Samples of `beta_2` over a full turn: the points of a curve, or the grid on which the
    /// Burmester points are bracketed before Newton's method refines them (default 720, half a
    /// degree). Two Burmester points closer than one step can be missed. At most
    /// [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES).
    pub samples: usize,
}

impl Default for BurmesterConfig {
    fn default() -> Self {
        BurmesterConfig { samples: 720 }
    }
}

impl BurmesterConfig {
    /// Sets [`samples`](Self::samples).
    pub fn samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    fn check(&self) -> Result<(), ClassicalError> {
        if self.samples < 8 {
            return Err(ClassicalError::BadRange {
                what: "number of samples",
                why: format!("{}: a turn takes at least 8", self.samples),
            });
        }
        // Two curve points a sample: more than a vector holds panicked on its capacity
        // (`2 * samples` overflowing first in a debug build).
        if self.samples > isize::MAX as usize / (2 * std::mem::size_of::<CurvePoint>()) {
            return Err(ClassicalError::BadRange {
                what: "number of samples",
                why: format!("{}: too many to hold in memory", self.samples),
            });
        }
        // Fewer that memory holds would still take practically forever.
        crate::analysis::check_sample_count("samples of a turn", self.samples)
            .map_err(|why| ClassicalError::BadRange { what: "number of samples", why })
    }
}

/// One point of the center-point and circle-point curves.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePoint {
    /// The crank rotation from the first pose to the second that it belongs to.
    pub beta2: f64,
    /// Which of the two solutions at that `beta2` (`0` or `1`).
    pub branch: u8,
    /// The dyad: its `center` is on the center-point curve, its `circle` on the circle-point
    /// curve.
    pub dyad: Dyad,
}

/// The center-point and circle-point curves of four poses, from [`center_point_curve`].
#[derive(Clone, Debug, PartialEq)]
pub struct BurmesterCurve {
    /// The points, by `beta2` and then by branch. Where a branch has no real solution, or its
    /// dyad is undetermined (the crank turning with the body), it has no point: the curves
    /// have gaps there, and the center-point curve runs off to infinity near the latter.
    pub points: Vec<CurvePoint>,
    /// The problem's size: the largest distance between two of the poses' points.
    pub size: f64,
    /// The largest [`Dyad::deviation`] over the points, divided by `size` and the larger of one
    /// and the crank's length over `size` (rounding level for a correct curve).
    pub max_deviation: f64,
}

impl BurmesterCurve {
    /// The center points (fixed pivots), in the order of [`points`](Self::points).
    pub fn center_points(&self) -> impl Iterator<Item = Vec2> + '_ {
        self.points.iter().map(|p| p.dyad.center)
    }

    /// The circle points (moving pivots in the first pose), in the order of
    /// [`points`](Self::points).
    pub fn circle_points(&self) -> impl Iterator<Item = Vec2> + '_ {
        self.points.iter().map(|p| p.dyad.circle)
    }
}

/// The Burmester points of five poses, from [`burmester_points`].
#[derive(Clone, Debug, PartialEq)]
pub struct BurmesterPoints {
    /// The dyads through all five poses (none, two or four; in the exceptional cases where two
    /// coincide or the search misses one, another count), ordered by their center point's x.
    pub dyads: Vec<Dyad>,
    /// The problem's size: the largest distance between two of the poses' points.
    pub size: f64,
    /// The largest [`Dyad::deviation`] over the dyads, relative as in
    /// [`BurmesterCurve::max_deviation`].
    pub max_deviation: f64,
}

/// The center-point and circle-point curves of four poses, sampled at
/// [`config.samples`](BurmesterConfig::samples) crank rotations `beta_2` over a turn.
///
/// Errors: not exactly four poses; a value not finite; two poses the same; every point the
/// same or every angle the same; poses sharing a pole (see [`ClassicalError::Degenerate`]).
///
/// ```
/// use kinloop_runtime::synthesis::classical::{BurmesterConfig, Pose, center_point_curve};
/// let poses = [
///     Pose::new(0.0, 0.0, 0.0),
///     Pose::new(1.0, 0.2, 0.4),
///     Pose::new(1.6, 1.0, 0.9),
///     Pose::new(1.1, 2.0, 1.5),
/// ];
/// let curve = center_point_curve(&poses, &BurmesterConfig::default().samples(360))?;
/// assert!(!curve.points.is_empty());
/// for p in &curve.points {
///     // Each dyad keeps its moving pivot on a circle about its fixed pivot in every pose.
///     let scale = curve.size.max(p.dyad.radius());
///     assert!(p.dyad.deviation(&poses) <= 1e-10 * scale);
/// }
/// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
/// ```
pub fn center_point_curve(poses: &[Pose], config: &BurmesterConfig) -> Result<BurmesterCurve, ClassicalError> {
    config.check()?;
    let size = check_poses(poses, 4, "the center-point curve")?;
    let condition = Compatibility::new(poses, [1, 2, 3])?;
    // Reserved up to a bound, the vector growing past it: a huge count fails, if it does, in
    // the work rather than on one allocation.
    let mut points = Vec::with_capacity(2 * config.samples.min(1 << 16));
    for k in 0..config.samples {
        let beta2 = k as f64 * TAU / config.samples as f64;
        for (branch, closure) in condition.closures(beta2).into_iter().enumerate() {
            let Some((beta3, beta4)) = closure else { continue };
            if let Some(dyad) = solve_dyad(poses, &[0.0, beta2, beta3, beta4]) {
                points.push(CurvePoint { beta2, branch: branch as u8, dyad });
            }
        }
    }
    let max_deviation = max_deviation(points.iter().map(|p| &p.dyad), poses, size);
    Ok(BurmesterCurve { points, size, max_deviation })
}

/// The dyads of the center-point curve at one crank rotation `beta_2` (one per branch), for
/// poses already checked.
#[cfg(test)]
pub(crate) fn dyads_at(poses: &[Pose], beta2: f64) -> Result<[Option<Dyad>; 2], ClassicalError> {
    let condition = Compatibility::new(poses, [1, 2, 3])?;
    Ok(condition.closures(beta2).map(|c| c.and_then(|(b3, b4)| solve_dyad(poses, &[0.0, beta2, b3, b4]))))
}

/// The Burmester points of five poses: every dyad that guides the body through all five.
///
/// The first compatibility condition's solutions are sampled over `beta_2`
/// ([`config.samples`](BurmesterConfig::samples) a turn, on both branches); where the second
/// condition changes sign along them a root is bracketed, then refined by Newton's method on
/// both conditions together (four real equations in `beta_2 .. beta_5`). The solutions where
/// every crank rotation equals the body's own, or is zero, satisfy both conditions but
/// determine no dyad, and are dropped; the sample steps holding them are searched again more
/// finely, since a Burmester point with a long crank (turning nearly as the body does, or
/// hardly at all) lies close to one of them.
///
/// Errors: not exactly five poses, and the errors of [`center_point_curve`] (for poses 1-4 and
/// 1, 2, 3, 5).
///
/// ```
/// use kinloop_runtime::synthesis::classical::{BurmesterConfig, Pose, burmester_points};
/// let poses = [
///     Pose::new(0.0, 0.0, 0.0),
///     Pose::new(1.0, 0.2, 0.4),
///     Pose::new(1.6, 1.0, 0.9),
///     Pose::new(1.1, 2.0, 1.5),
///     Pose::new(0.3, 2.4, 2.0),
/// ];
/// let found = burmester_points(&poses, &BurmesterConfig::default())?;
/// assert!(found.dyads.len() <= 4);
/// for dyad in &found.dyads {
///     assert!(dyad.deviation(&poses) <= 1e-10 * found.size.max(dyad.radius()));
/// }
/// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
/// ```
pub fn burmester_points(poses: &[Pose], config: &BurmesterConfig) -> Result<BurmesterPoints, ClassicalError> {
    config.check()?;
    let size = check_poses(poses, 5, "Burmester's five-pose synthesis")?;
    let first = Compatibility::new(poses, [1, 2, 3])?;
    let second = Compatibility::new(poses, [1, 2, 4])?;
    let trivial: Vec<f64> = poses.iter().map(|p| p.angle - poses[0].angle).collect();
    let mut dyads: Vec<Dyad> = Vec::new();
    for seed in brackets(&first, &second, config.samples, trivial[1]) {
        let Some(betas) = newton(&first, &second, seed) else { continue };
        let all = [0.0, betas[0], betas[1], betas[2], betas[3]];
        let is_trivial = (1..5).all(|j| angle_difference(all[j], trivial[j]).abs() < 1e-6);
        let known = dyads.iter().any(|d| (1..5).all(|j| angle_difference(d.rotations[j], all[j]).abs() < 1e-9));
        if is_trivial || known {
            continue;
        }
        if let Some(dyad) = solve_dyad(poses, &all) {
            dyads.push(dyad);
        }
    }
    // A crank that hardly turns has its pivots about the size over its rotation away: near the
    // largest doubles they lie beyond them (NaN and infinite pivots were returned as `Ok`).
    let beyond = dyads.iter().flat_map(|d| [d.center, d.circle]).find(|p| !(p.x.is_finite() && p.y.is_finite()));
    if let Some(p) = beyond {
        let value = if p.x.is_finite() { p.y } else { p.x };
        return Err(ClassicalError::NonFinite {
            what: "a Burmester pair's pivot (beyond the range of doubles at this size: give the poses' points in a \
                   larger unit)"
                .into(),
            value,
        });
    }
    dyads.sort_by(|a, b| a.center.x.total_cmp(&b.center.x));
    let max_deviation = max_deviation(dyads.iter(), poses, size);
    Ok(BurmesterPoints { dyads, size, max_deviation })
}

/// Starting rotations `[beta_2, beta_3, beta_4, beta_5]` wherever the second condition's
/// residual (the length of its known sides minus its last side) changes sign between
/// neighbouring samples along the first condition's solutions. Where the first condition's
/// solutions stop at a `beta_2` (its linkage is stretched flat), its two branches meet, so the
/// chain runs out along one branch and back along the other.
///
/// The residual also vanishes where no dyad is determined: at the body's own rotation
/// `alpha_2` and at no rotation (`0`: every crank rotation zero, also a solution of both
/// conditions). A Burmester point with a long crank lies close to one of them (a far circle
/// point is carried nearly as the body turns, so its crank turns nearly as the body; a far
/// center point's crank nearly slides, hardly turning). Two roots within one step keep the
/// residual's sign across it, and a bracket whose better end is the degenerate solution starts
/// Newton's method there: so a step holding `alpha_2` or `0` is searched again on a grid halving
/// towards it (down to `2^-40` of the step), and a fold's step on a finer grid out to the fold
/// and back.
fn brackets(first: &Compatibility, second: &Compatibility, samples: usize, alpha2: f64) -> Vec<[f64; 4]> {
    let beta2 = |k: usize| k as f64 * TAU / samples as f64;
    let grid: Vec<[Option<(f64, f64)>; 2]> = (0..samples).map(|k| first.closures(beta2(k))).collect();
    let exists = |k: usize| grid[k % samples][0].is_some();
    // Chains of (sample, branch), each closed (its last element neighbours its first).
    let mut chains: Vec<Vec<(usize, usize)>> = Vec::new();
    if (0..samples).all(exists) {
        chains.extend((0..2).map(|b| (0..samples).map(|k| (k, b)).collect()));
    } else {
        let start = (0..samples).find(|&k| !exists(k)).unwrap_or(0);
        let mut k = start + 1;
        while k <= start + samples {
            if !exists(k) {
                k += 1;
                continue;
            }
            let first_k = k;
            while k < start + samples && exists(k + 1) {
                k += 1;
            }
            let arc: Vec<usize> = (first_k..=k).map(|i| i % samples).collect();
            let mut chain: Vec<(usize, usize)> = arc.iter().map(|&i| (i, 0)).collect();
            chain.extend(arc.iter().rev().map(|&i| (i, 1)));
            chains.push(chain);
            k += 1;
        }
    }
    // The starting rotations and the second condition's residual at `b2` on a first-condition
    // solution `(b3, b4)`.
    let at = |b2: f64, (b3, b4): (f64, f64)| {
        let [e1, e2, e3, e5] = second.d;
        let known = e1 + e2 * Complex::from_polar(1.0, b2) + e3 * Complex::from_polar(1.0, b3);
        let b5 = (-known / e5).arg();
        ([b2, b3, b4, b5], known.norm() - e5.norm())
    };
    // A sample on `branch` at `b2`: the branch, the starting rotations, the residual.
    let on = |b2: f64, branch: usize| first.closures(b2)[branch].map(|c| (branch, at(b2, c)));
    let seed = |(k, b): (usize, usize)| grid[k][b].map(|c| (b, at(beta2(k), c)));
    let step = TAU / samples as f64;
    let mut seeds = Vec::new();
    // Where the residual changes sign from one sample to the next, the better end starts
    // Newton's method; between two samples of one branch the change is first narrowed by
    // bisection, so that Newton's method starts at the root rather than at a degenerate
    // solution close to it.
    let mut bracket = |(b0, (s0, f0)): (usize, ([f64; 4], f64)), (b1, (s1, f1)): (usize, ([f64; 4], f64))| {
        if f0 != 0.0 && f0.signum() == f1.signum() {
            return;
        }
        let (mut lo, mut hi) = ((s0, f0), (s1, f1));
        if b0 == b1 && f0 != 0.0 && f1 != 0.0 {
            let span = angle_difference(s1[0], s0[0]);
            let (mut a, mut b) = (0.0, 1.0);
            for _ in 0..60 {
                let t = 0.5 * (a + b);
                let Some((_, m)) = on(s0[0] + t * span, b0) else { break };
                if m.1.signum() == lo.1.signum() {
                    (lo, a) = (m, t);
                } else {
                    (hi, b) = (m, t);
                }
            }
        }
        seeds.push(if lo.1.abs() <= hi.1.abs() { lo.0 } else { hi.0 });
    };
    // The rotation `t` from sample `k`, when the step from `k` towards `t`'s side holds
    // alpha_2 or 0 (a sample on one is held by the steps on both sides).
    let held = |k: usize, after: bool| {
        [alpha2, 0.0].into_iter().find_map(|a| {
            let t = angle_difference(a, beta2(k));
            let inside = if after { (0.0..=step).contains(&t) } else { (-step..=0.0).contains(&t) };
            inside.then_some(t)
        })
    };
    // Rotations from a sample into the step on its `after` side (or the other), increasing
    // away from it: halving towards a held degenerate rotation, and for a fold (whose place in
    // the step is not known) also every 1/32 of the step.
    let fine = |k: usize, after: bool, fold: bool| {
        let sign = if after { 1.0 } else { -1.0 };
        let mut t: Vec<f64> = Vec::new();
        if let Some(off) = held(k, after) {
            let off = off.abs();
            t.extend((1..=40).flat_map(|j| [off - step * 0.5f64.powi(j), off + step * 0.5f64.powi(j)]));
        }
        if fold {
            t.extend((1..32).map(|j| step * j as f64 / 32.0));
        }
        t.retain(|&t| t > 0.0 && t < step);
        t.sort_by(f64::total_cmp);
        t.into_iter().map(move |t| beta2(k) + sign * t)
    };
    for chain in &chains {
        for i in 0..chain.len() {
            let (p, q) = (chain[i], chain[(i + 1) % chain.len()]);
            let (Some(s0), Some(s1)) = (seed(p), seed(q)) else { continue };
            let mut run = vec![s0];
            if p.0 == q.0 && p.1 != q.1 {
                // A fold: out along branch p.1 beyond sample k (after it from branch 0, before
                // it from branch 1) and back along branch q.1.
                let (k, after) = (p.0, p.1 == 0);
                run.extend(fine(k, after, true).filter_map(|b2| on(b2, p.1)));
                let back: Vec<f64> = fine(k, after, true).collect();
                run.extend(back.into_iter().rev().filter_map(|b2| on(b2, q.1)));
            } else if p.1 == q.1 && held(p.0, (p.0 + 1) % samples == q.0).is_some() {
                // A step along one branch holding alpha_2 or 0.
                run.extend(fine(p.0, (p.0 + 1) % samples == q.0, false).filter_map(|b2| on(b2, p.1)));
            }
            run.push(s1);
            for w in run.windows(2) {
                bracket(w[0], w[1]);
            }
        }
    }
    seeds
}

/// Newton's method on both compatibility conditions, from `x = [beta_2, beta_3, beta_4,
/// beta_5]`: `None` when it does not converge to rounding level in 50 steps or meets a
/// singular Jacobian.
fn newton(first: &Compatibility, second: &Compatibility, mut x: [f64; 4]) -> Option<[f64; 4]> {
    let [a1, a2, a3, a4] = first.d;
    let [b1, b2, b3, b5] = second.d;
    let i: Complex<f64> = Complex::i();
    for _ in 0..50 {
        let e = x.map(|b| Complex::from_polar(1.0, b));
        let ra = a1 + a2 * e[0] + a3 * e[1] + a4 * e[2];
        let rb = b1 + b2 * e[0] + b3 * e[1] + b5 * e[3];
        let f = Vector4::new(ra.re, ra.im, rb.re, rb.im);
        // Each condition's coefficients are scaled to a largest magnitude of one: a residual
        // of a few roundings of the sum of four unit terms is converged.
        if f.amax() <= 32.0 * f64::EPSILON {
            return Some(x.map(|b| angle_difference(b, 0.0)));
        }
        let (ca, cb) = (
            [a2 * e[0], a3 * e[1], a4 * e[2], Complex::new(0.0, 0.0)],
            [b2 * e[0], b3 * e[1], Complex::new(0.0, 0.0), b5 * e[3]],
        );
        let jac = Matrix4::from_fn(|r, c| {
            let d: Complex<f64> = i * if r < 2 { ca[c] } else { cb[c] };
            if r % 2 == 0 { d.re } else { d.im }
        });
        let step = jac.lu().solve(&f)?;
        if !step.iter().all(|s| s.is_finite()) {
            return None;
        }
        // Where rounding keeps the residual just above the bound, a step at the angles'
        // rounding level with a small residual is converged too.
        if step.amax() <= 16.0 * f64::EPSILON * TAU && f.amax() <= 1e-12 {
            return Some(x.map(|b| angle_difference(b, 0.0)));
        }
        for k in 0..4 {
            x[k] -= step[k];
        }
    }
    None
}

/// The largest deviation of the dyads through the poses, relative to the problem's size (or to
/// the crank, when it is longer: a far fixed pivot is found to the same relative accuracy).
fn max_deviation<'a>(dyads: impl Iterator<Item = &'a Dyad>, poses: &[Pose], size: f64) -> f64 {
    dyads.map(|d| d.deviation(poses) / size.max(d.radius())).fold(0.0, f64::max)
}

#[cfg(test)]
mod tests;
