//! Poses of a moving body and the dyads that guide it: a crank turning about a fixed pivot (the
//! center point) with its other end (the circle point) jointed to the body.
//!
//! In complex numbers, with the body's point `P_j` and angle `theta_j` in pose `j`, the dyad is
//! two vectors fixed in their links: `W` from the center point `M` to the circle point, turning
//! with the crank, and `Z` from the circle point to `P`, turning with the body. Going from the
//! first pose to pose `j` the body turns by `alpha_j = theta_j - theta_1`, the crank by
//! `beta_j`, and the loop `M + W + Z = P` gives the dyad equations
//!
//! `W (e^{i beta_j} - 1) + Z (e^{i alpha_j} - 1) = P_j - P_1`, `j = 2 .. n`.
//!
//! For chosen crank rotations they are linear in `W` and `Z`.

use super::error::{ClassicalError, finite};
use super::freudenstein::COINCIDENT_ANGLE;
use super::position::angle_difference;
use crate::Vec2;
use nalgebra::{Complex, DMatrix, DVector};

/// Two poses whose points are closer than this fraction of the problem's size (and whose
/// angles are within [`COINCIDENT_ANGLE`]) count as one.
const COINCIDENT_POINT: f64 = 1e-12;

/// Smallest reciprocal condition number of a dyad's linear system accepted: below it the crank
/// rotations are (nearly) the body's own, where `W` and `Z` are not determined.
const DYAD_RCOND: f64 = 1e-9;

/// A position of a moving body: where its point is and which way it faces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// The body's point.
    pub point: Vec2,
    /// The body's angle (radians, counter-clockwise), e.g. the direction of a line on it.
    pub angle: f64,
}

impl Pose {
    /// The pose with the point `(x, y)` and the angle `angle`.
    pub const fn new(x: f64, y: f64, angle: f64) -> Pose {
        Pose { point: Vec2::new(x, y), angle }
    }
}

/// A dyad that takes a body through its poses: its fixed pivot, its moving pivot in the first
/// pose, and how far its crank turns from the first pose to each.
#[derive(Clone, Debug, PartialEq)]
pub struct Dyad {
    /// The fixed pivot (center point).
    pub center: Vec2,
    /// The moving pivot on the body in the first pose (circle point).
    pub circle: Vec2,
    /// The crank's rotation from the first pose to each pose (`0` for the first), radians.
    pub rotations: Vec<f64>,
}

impl Dyad {
    /// The crank's length `|circle - center|`.
    pub fn radius(&self) -> f64 {
        (self.circle - self.center).norm()
    }

    /// The moving pivot when the body is in `pose`: the circle point carried with the body from
    /// the `first` pose (the one the dyad's `circle` is given in), keeping its place relative to
    /// the body's point and angle.
    pub fn circle_point_in(&self, first: &Pose, pose: &Pose) -> Vec2 {
        carried(self.circle, first, pose)
    }

    /// The largest distance, over the poses, between the moving pivot's distance from the
    /// center point and the crank's length: zero (to rounding) when the dyad truly guides the
    /// body through the poses. Computed from the center and circle points and the poses only,
    /// so it checks a dyad however it was found.
    pub fn deviation(&self, poses: &[Pose]) -> f64 {
        let r = self.radius();
        poses.iter().map(|p| ((self.circle_point_in(&poses[0], p) - self.center).norm() - r).abs()).fold(0.0, f64::max)
    }
}

/// The point `q`, given in pose `from`, carried with the body into pose `to`.
pub(crate) fn carried(q: Vec2, from: &Pose, to: &Pose) -> Vec2 {
    let (s, c) = (to.angle - from.angle).sin_cos();
    let r = q - from.point;
    to.point + Vec2::new(c * r.x - s * r.y, s * r.x + c * r.y)
}

pub(crate) fn complex(v: Vec2) -> Complex<f64> {
    Complex::new(v.x, v.y)
}

pub(crate) fn vec2(z: Complex<f64>) -> Vec2 {
    Vec2::new(z.re, z.im)
}

/// Checks that there are `needed` poses, finite and distinct, and returns the problem's size:
/// the largest distance between two of their points.
pub(crate) fn check_poses(poses: &[Pose], needed: usize, method: &'static str) -> Result<f64, ClassicalError> {
    if poses.len() != needed {
        let needed = if needed == 4 { "exactly 4" } else { "exactly 5" };
        return Err(ClassicalError::Count { method, what: "poses", needed, given: poses.len() });
    }
    for (j, p) in poses.iter().enumerate() {
        finite(p.point.x, || format!("the x of pose {j}"))?;
        finite(p.point.y, || format!("the y of pose {j}"))?;
        finite(p.angle, || format!("the angle of pose {j}"))?;
    }
    let mut size = 0.0f64;
    for p in poses {
        for q in poses {
            size = size.max((p.point - q.point).norm());
        }
    }
    for (i, p) in poses.iter().enumerate() {
        for (j, q) in poses.iter().enumerate().skip(i + 1) {
            let near = (p.point - q.point).norm() <= COINCIDENT_POINT * size;
            if near && angle_difference(p.angle, q.angle).abs() <= COINCIDENT_ANGLE {
                return Err(ClassicalError::Coincident { what: "poses", first: i, second: j });
            }
        }
    }
    if !size.is_finite() {
        return Err(ClassicalError::Degenerate(
            "the poses lie farther apart than a double holds (the distance between two overflows): give their \
             points in a larger unit"
                .into(),
        ));
    }
    if size == 0.0 {
        return Err(ClassicalError::Degenerate(
            "every pose has the same point: the body only turns about it, which any crank pivoted there does".into(),
        ));
    }
    if poses.iter().all(|p| angle_difference(p.angle, poses[0].angle).abs() <= COINCIDENT_ANGLE) {
        return Err(ClassicalError::Degenerate(
            "the body keeps its angle (it only translates): the dyad equations do not determine the moving pivot"
                .into(),
        ));
    }
    Ok(size)
}

/// The dyad for the crank rotations `betas` (one per pose, the first `0`), by solving the dyad
/// equations for `W` and `Z` (least squares when there are more than two; they are consistent
/// when the rotations satisfy the compatibility conditions). `None` when the system is
/// (nearly) singular, as where the crank turns with the body.
pub(crate) fn solve_dyad(poses: &[Pose], betas: &[f64]) -> Option<Dyad> {
    let n = poses.len() - 1;
    let p1 = complex(poses[0].point);
    let mut m = DMatrix::zeros(2 * n, 4);
    let mut rhs = DVector::zeros(2 * n);
    for j in 1..=n {
        let a = Complex::from_polar(1.0, betas[j]) - 1.0;
        let z = Complex::from_polar(1.0, poses[j].angle - poses[0].angle) - 1.0;
        let d = complex(poses[j].point) - p1;
        let (re, im) = (2 * (j - 1), 2 * (j - 1) + 1);
        // Unknowns (W.re, W.im, Z.re, Z.im): the real and imaginary parts of w a + z z_j = d.
        m[(re, 0)] = a.re;
        m[(re, 1)] = -a.im;
        m[(re, 2)] = z.re;
        m[(re, 3)] = -z.im;
        m[(im, 0)] = a.im;
        m[(im, 1)] = a.re;
        m[(im, 2)] = z.im;
        m[(im, 3)] = z.re;
        rhs[re] = d.re;
        rhs[im] = d.im;
    }
    let svd = m.svd(true, true);
    let (largest, smallest) = (svd.singular_values.max(), svd.singular_values.min());
    if smallest.is_nan() || smallest < DYAD_RCOND * largest {
        return None;
    }
    let x = svd.solve(&rhs, 0.0).ok()?;
    let (w, z) = (Complex::new(x[0], x[1]), Complex::new(x[2], x[3]));
    let circle = p1 - z;
    let center = circle - w;
    let rotations = betas.iter().map(|&b| angle_difference(b, 0.0)).collect();
    Some(Dyad { center: vec2(center), circle: vec2(circle), rotations })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Poses made by a known crank and body: the solve recovers the crank's pivots, and the
    /// deviation (computed without the solve) is at rounding level; a wrong pivot deviates.
    #[test]
    fn recovers_a_known_dyad_from_its_rotations() {
        let (m, w, z) = (Complex::new(0.4, -1.1), Complex::new(1.3, 0.7), Complex::new(0.9, 2.2));
        let betas = [0.0, 0.4, 0.9, 1.3];
        let alphas = [0.0, -0.2, 0.35, 0.1];
        let poses: Vec<Pose> = betas
            .iter()
            .zip(alphas)
            .map(|(&b, a)| {
                let p = m + w * Complex::from_polar(1.0, b) + z * Complex::from_polar(1.0, a);
                Pose::new(p.re, p.im, 0.3 + a)
            })
            .collect();
        let dyad = solve_dyad(&poses, &betas).unwrap();
        assert!((dyad.center - vec2(m)).norm() < 1e-14);
        assert!((dyad.circle - vec2(m + w)).norm() < 1e-14);
        assert!(dyad.deviation(&poses) < 1e-14);
        assert!((dyad.radius() - w.norm()).abs() < 1e-14);
        let wrong = Dyad { center: dyad.center + Vec2::new(1e-3, 0.0), ..dyad };
        assert!(wrong.deviation(&poses) > 1e-5);
    }

    /// Rotations equal to the body's own leave W and Z undetermined.
    #[test]
    fn the_bodys_own_rotations_give_no_dyad() {
        let poses = [Pose::new(0.0, 0.0, 0.0), Pose::new(1.0, 0.0, 0.5), Pose::new(1.0, 1.0, 1.0)];
        assert_eq!(solve_dyad(&poses, &[0.0, 0.5, 1.0]), None);
    }

    #[test]
    fn pose_checks() {
        let ok =
            [Pose::new(0.0, 0.0, 0.0), Pose::new(1.0, 0.0, 0.5), Pose::new(1.0, 1.0, 1.0), Pose::new(0.0, 2.0, 1.2)];
        assert_eq!(check_poses(&ok, 4, "test"), Ok(5f64.sqrt()));
        assert!(matches!(check_poses(&ok[..3], 4, "test"), Err(ClassicalError::Count { given: 3, .. })));
        let mut nan = ok;
        nan[2].angle = f64::NAN;
        assert!(matches!(check_poses(&nan, 4, "test"), Err(ClassicalError::NonFinite { .. })));
        let mut same = ok;
        same[3] = Pose::new(1.0, 0.0, 0.5 + std::f64::consts::TAU);
        assert_eq!(
            check_poses(&same, 4, "test"),
            Err(ClassicalError::Coincident { what: "poses", first: 1, second: 3 })
        );
        let turning = [0.0, 0.4, 0.8, 1.2].map(|a| Pose::new(1.0, 2.0, a));
        assert!(matches!(check_poses(&turning, 4, "test"), Err(ClassicalError::Degenerate(_))));
        let sliding = [0.0, 1.0, 2.0, 3.5].map(|x| Pose::new(x, x * x, 0.3));
        assert!(matches!(check_poses(&sliding, 4, "test"), Err(ClassicalError::Degenerate(_))));
    }
}
