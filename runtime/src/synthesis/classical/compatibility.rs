//! The compatibility condition of four poses: which crank rotations admit a dyad.
//!
//! For four poses the three dyad equations `W a_j + Z z_j = d_j` (`a_j = e^{i beta_j} - 1`,
//! `z_j = e^{i alpha_j} - 1`, `d_j = P_j - P_1`) have two unknowns, so they have a solution
//! only when the 3x3 complex determinant `det [a_j, z_j, d_j]` vanishes. Expanded along the
//! column of the unknown rotations it reads
//!
//! `D_1 + D_2 e^{i beta_2} + D_3 e^{i beta_3} + D_4 e^{i beta_4} = 0`,
//!
//! with `D_2, D_3, D_4` the signed 2x2 minors of the known columns `[z, d]` and
//! `D_1 = -(D_2 + D_3 + D_4)`. It is the loop equation of a four-bar (the compatibility
//! linkage) with links `|D_k|`: for a chosen `beta_2` the two unknown sides `D_3 e^{i beta_3}`
//! and `D_4 e^{i beta_4}` must add up to the known `T = -D_1 - D_2 e^{i beta_2}`, a triangle
//! with two solutions (mirror images in `T`) where its sides allow one.

use super::dyad::{Pose, complex};
use super::error::ClassicalError;
use nalgebra::Complex;

/// A minor smaller than this fraction of the largest one counts as zero.
const ZERO_MINOR: f64 = 1e-12;

/// The compatibility condition of the first pose and three others.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Compatibility {
    /// `D_1 .. D_4`, scaled so that the largest has magnitude one.
    pub d: [Complex<f64>; 4],
}

impl Compatibility {
    /// The condition of the poses `0` and `others` (indices into `poses`).
    ///
    /// Errors: `D_3` or `D_4` zero (poses with a shared pole, where the triangle has no
    /// definite sides), or every minor zero.
    pub fn new(poses: &[Pose], others: [usize; 3]) -> Result<Compatibility, ClassicalError> {
        let p1 = complex(poses[0].point);
        let col = |j: usize| {
            let z = Complex::from_polar(1.0, poses[j].angle - poses[0].angle) - 1.0;
            (z, complex(poses[j].point) - p1)
        };
        let [(zi, di), (zj, dj), (zk, dk)] = others.map(col);
        let d2 = zj * dk - zk * dj;
        let d3 = -(zi * dk - zk * di);
        let d4 = zi * dj - zj * di;
        let d1 = -(d2 + d3 + d4);
        let largest = [d1, d2, d3, d4].iter().map(|c| c.norm()).fold(0.0, f64::max);
        // A minor is zero against the size of its terms, not against the other minors: where
        // every pose turns about one point (`d_j = s z_j`) all minors are the rounding of their
        // terms, and compared with each other they were zero or not by chance (the same poses
        // gave an error, 1 dyad or 809 by the size they were written in).
        let terms = |a: Complex<f64>, b: Complex<f64>, c: Complex<f64>, e: Complex<f64>| {
            a.norm() * b.norm() + c.norm() * e.norm()
        };
        let size = terms(zj, dk, zk, dj).max(terms(zi, dk, zk, di)).max(terms(zi, dj, zj, di));
        let zero = |c: Complex<f64>| c.norm() <= ZERO_MINOR * size.max(largest);
        if !(size.is_finite() && largest > 0.0) || zero(d3) || zero(d4) {
            return Err(ClassicalError::Degenerate(format!(
                "poses 0, {}, {} and {} have a pole in common (a point of the body that stays in place between \
                 two pairs of them), a special case the center-point curve's construction does not cover",
                others[0], others[1], others[2]
            )));
        }
        Ok(Compatibility { d: [d1, d2, d3, d4].map(|c| c / largest) })
    }

    /// The rotations `(beta_3, beta_4)` that go with `beta_2`, on each of the two closures of
    /// the compatibility linkage (`None` where its sides do not close at this `beta_2`).
    pub fn closures(&self, beta2: f64) -> [Option<(f64, f64)>; 2] {
        let [d1, d2, d3, d4] = self.d;
        let t = -d1 - d2 * Complex::from_polar(1.0, beta2);
        let (r3, r4, len) = (d3.norm(), d4.norm(), t.norm());
        if len.is_nan() || len <= 0.0 {
            return [None, None];
        }
        let cos_gamma = (r3 * r3 + len * len - r4 * r4) / (2.0 * r3 * len);
        if cos_gamma.is_nan() || cos_gamma.abs() > 1.0 {
            return [None, None];
        }
        let gamma = cos_gamma.acos();
        [gamma, -gamma].map(|g| {
            let u = Complex::from_polar(r3, t.arg() + g);
            let v = t - u;
            Some(((u / d3).arg(), (v / d4).arg()))
        })
    }

    /// The condition's residual for the rotations `beta_2, beta_3, beta_4` (zero where a dyad
    /// exists).
    #[cfg(test)]
    pub fn residual(&self, betas: [f64; 3]) -> Complex<f64> {
        let [d1, d2, d3, d4] = self.d;
        d1 + d2 * Complex::from_polar(1.0, betas[0])
            + d3 * Complex::from_polar(1.0, betas[1])
            + d4 * Complex::from_polar(1.0, betas[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poses() -> [Pose; 4] {
        [Pose::new(0.0, 0.0, 0.0), Pose::new(1.0, 0.2, 0.4), Pose::new(1.6, 1.0, 0.9), Pose::new(1.1, 2.0, 1.5)]
    }

    /// Both closures satisfy the condition, and the body's own rotations (the trivial solution,
    /// where the first two columns of the determinant are equal) satisfy it too: the minors are
    /// those of the determinant.
    #[test]
    fn closures_satisfy_the_condition_and_so_does_the_trivial_solution() {
        let c = Compatibility::new(&poses(), [1, 2, 3]).unwrap();
        let mut closed = 0;
        for k in 0..72 {
            let beta2 = k as f64 * std::f64::consts::TAU / 72.0;
            for (b3, b4) in c.closures(beta2).into_iter().flatten() {
                assert!(c.residual([beta2, b3, b4]).norm() < 1e-14, "{beta2}");
                closed += 1;
            }
        }
        assert!(closed > 0);
        let p = poses();
        let trivial = [1, 2, 3].map(|j| p[j].angle - p[0].angle);
        assert!(c.residual(trivial).norm() < 1e-15);
    }
}
