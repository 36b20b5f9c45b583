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
    /// degree). Two Burmester points closer than one step can be missed.
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
        Ok(())
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
    let mut points = Vec::with_capacity(2 * config.samples);
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
/// both conditions together (four real equations in `beta_2 .. beta_5`). The solution where
/// every crank rotation equals the body's own satisfies both conditions but determines no dyad,
/// and is dropped.
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
    for seed in brackets(&first, &second, config.samples) {
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
    dyads.sort_by(|a, b| a.center.x.total_cmp(&b.center.x));
    let max_deviation = max_deviation(dyads.iter(), poses, size);
    Ok(BurmesterPoints { dyads, size, max_deviation })
}

/// Starting rotations `[beta_2, beta_3, beta_4, beta_5]` wherever the second condition's
/// residual (the length of its known sides minus its last side) changes sign between
/// neighbouring samples along the first condition's solutions. Where the first condition's
/// solutions stop at a `beta_2` (its linkage is stretched flat), its two branches meet, so the
/// chain runs out along one branch and back along the other.
fn brackets(first: &Compatibility, second: &Compatibility, samples: usize) -> Vec<[f64; 4]> {
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
    let seed = |(k, b): (usize, usize)| {
        let (b3, b4) = grid[k][b]?;
        let b2 = beta2(k);
        let [e1, e2, e3, e5] = second.d;
        let known = e1 + e2 * Complex::from_polar(1.0, b2) + e3 * Complex::from_polar(1.0, b3);
        let b5 = (-known / e5).arg();
        Some(([b2, b3, b4, b5], known.norm() - e5.norm()))
    };
    let mut seeds = Vec::new();
    for chain in &chains {
        for i in 0..chain.len() {
            let (Some((s0, f0)), Some((s1, f1))) = (seed(chain[i]), seed(chain[(i + 1) % chain.len()])) else {
                continue;
            };
            if f0 == 0.0 || f0.signum() != f1.signum() {
                seeds.push(if f0.abs() <= f1.abs() { s0 } else { s1 });
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
