//! A classical result as a whole four-bar: its pivots, link lengths, coupler point and the
//! angles of its links at every precision point or pose, to map onto the parameters and
//! unknowns of a declared four-bar and use as a seed of the general search
//! ([`Search::with_seeds`](crate::synthesis::Search::with_seeds)).

use super::dyad::{Dyad, Pose};
use super::error::ClassicalError;
use super::freudenstein::{FunctionGenerator, PrecisionPoint};
use super::position::angle_difference;
use crate::Vec2;
use crate::metrics::FourBarLinks;

/// A four-bar in the plane. Its own frame has the input pivot `A` at the origin and the output
/// pivot `D` on the positive x axis at distance `links.ground`; in the plane, `A` is at
/// [`input_pivot`](Self::input_pivot) and the line `A -> D` at [`ground_angle`](Self::ground_angle).
/// The input link `AB`, coupler `BC` and output link `DC` have the angles
/// [`inputs`](Self::inputs), [`couplers`](Self::couplers), [`outputs`](Self::outputs) at each
/// precision point or pose, all measured from the line `A -> D`.
///
/// Declared as `a @ (phi + th) + b @ beta == g @ th + c @ gamma` with `A` at `(ax, ay)`, it is
/// `a = links.input`, `b = links.coupler`, `c = links.output`, `g = links.ground`, `th =
/// ground_angle`, `(ax, ay) = input_pivot`, and at pose `j`: `phi = inputs[j]`,
/// `beta = couplers[j] + th`, `gamma = outputs[j] + th`.
#[derive(Clone, Debug, PartialEq)]
pub struct FourBar {
    /// The input link's fixed pivot `A`.
    pub input_pivot: Vec2,
    /// The output link's fixed pivot `D`.
    pub output_pivot: Vec2,
    /// The direction of the ground line `A -> D` (radians).
    pub ground_angle: f64,
    /// The link lengths.
    pub links: FourBarLinks,
    /// The coupler point (of a motion generator): its distance from `B` and its angle from the
    /// coupler line `B -> C` (radians); `None` for a function generator.
    pub coupler_point: Option<(f64, f64)>,
    /// The body's angle (of the poses) minus the coupler line's `B -> C` (radians; `0` for a
    /// function generator).
    pub body_angle: f64,
    /// The input link's angle at each precision point or pose, from the ground line: the first
    /// in `(-pi, pi]`, each other the first plus the input's rotation to it, in `(-pi, pi]`.
    pub inputs: Vec<f64>,
    /// The coupler's angle `B -> C` at each, from the ground line.
    pub couplers: Vec<f64>,
    /// The output link's angle `D -> C` at each, from the ground line.
    pub outputs: Vec<f64>,
}

impl FourBar {
    /// The function generator `g` through its precision `points` (those it was synthesised
    /// from): `A` at the origin, `D` at `(1, 0)`, the input and output angles those of the
    /// points, the coupler's from its joints.
    ///
    /// ```
    /// use kinloop_runtime::deg;
    /// use kinloop_runtime::synthesis::classical::{FourBar, FunctionMap, chebyshev_points, freudenstein};
    /// let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0))?;
    /// let points = map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0)?)?;
    /// let g = freudenstein(&points)?;
    /// let four_bar = FourBar::from_function_generator(&g, &points)?;
    /// // A seed `[a, b, c]` for a declaration `a @ phi + b @ beta == (d, 0) + c @ psi`, d = 1:
    /// let seed = vec![four_bar.links.input, four_bar.links.coupler, four_bar.links.output];
    /// assert_eq!(seed[0], g.links.input);
    /// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
    /// ```
    pub fn from_function_generator(
        g: &FunctionGenerator,
        points: &[PrecisionPoint],
    ) -> Result<FourBar, ClassicalError> {
        let l = g.links;
        let mut couplers = Vec::with_capacity(points.len());
        for (i, p) in points.iter().enumerate() {
            let b = Vec2::new(l.input * p.phi.cos(), l.input * p.phi.sin());
            let c = Vec2::new(l.ground + l.output * p.psi.cos(), l.output * p.psi.sin());
            // The linkage closes at its precision points only to the misfit of a least-squares
            // fit: the coupler's direction is still defined unless B and C coincide.
            if (c - b).norm() <= 1e-12 * (l.ground + l.input + l.output) {
                return Err(ClassicalError::Degenerate(format!(
                    "the coupler's joints coincide at precision point {i}: its angle is not defined"
                )));
            }
            couplers.push((c - b).angle());
        }
        Ok(FourBar {
            input_pivot: Vec2::new(0.0, 0.0),
            output_pivot: Vec2::new(l.ground, 0.0),
            ground_angle: 0.0,
            links: l,
            coupler_point: None,
            body_angle: 0.0,
            inputs: points.iter().map(|p| p.phi).collect(),
            couplers,
            outputs: points.iter().map(|p| p.psi).collect(),
        })
    }

    /// The four-bar of two dyads that guide a body through `poses` (e.g. two of
    /// [`burmester_points`](super::burmester_points)): `input`'s crank is the input link, `output`'s
    /// the output link, the body the coupler, its point the coupler point.
    ///
    /// Errors: fewer than two poses; the two fixed pivots or the two moving pivots coinciding,
    /// or a crank of zero length (relative to the poses' size): no four-bar.
    pub fn from_dyads(input: &Dyad, output: &Dyad, poses: &[Pose]) -> Result<FourBar, ClassicalError> {
        if poses.len() < 2 {
            return Err(ClassicalError::Count {
                method: "a four-bar from two dyads",
                what: "poses",
                needed: "at least 2",
                given: poses.len(),
            });
        }
        let size = poses
            .iter()
            .flat_map(|p| poses.iter().map(move |q| (p.point - q.point).norm()))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let (a, d, b1, c1) = (input.center, output.center, input.circle, output.circle);
        let tiny = 1e-12 * size;
        for (what, len) in [
            ("the fixed pivots coincide", (d - a).norm()),
            ("the moving pivots coincide", (c1 - b1).norm()),
            ("the input crank has no length", (b1 - a).norm()),
            ("the output crank has no length", (c1 - d).norm()),
        ] {
            if len.is_nan() || len <= tiny {
                return Err(ClassicalError::Degenerate(format!("{what}: the two dyads make no four-bar")));
            }
        }
        let ground_angle = (d - a).angle();
        let links = FourBarLinks {
            ground: (d - a).norm(),
            input: (b1 - a).norm(),
            coupler: (c1 - b1).norm(),
            output: (c1 - d).norm(),
        };
        let p1 = poses[0].point;
        let coupler1 = (c1 - b1).angle();
        let coupler_point = ((p1 - b1).norm(), angle_difference((p1 - b1).angle(), coupler1));
        let from_ground = |v: Vec2| angle_difference(v.angle(), ground_angle);
        let first = from_ground(b1 - a);
        let mut inputs = Vec::with_capacity(poses.len());
        let mut couplers = Vec::with_capacity(poses.len());
        let mut outputs = Vec::with_capacity(poses.len());
        for pose in poses {
            let (b, c) = (input.circle_point_in(&poses[0], pose), output.circle_point_in(&poses[0], pose));
            inputs.push(first + angle_difference(from_ground(b - a), first));
            couplers.push(from_ground(c - b));
            outputs.push(from_ground(c - d));
        }
        Ok(FourBar {
            input_pivot: a,
            output_pivot: d,
            ground_angle,
            links,
            coupler_point: Some(coupler_point),
            body_angle: angle_difference(poses[0].angle, coupler1),
            inputs,
            couplers,
            outputs,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Poses of the coupler of a four-bar built here by circle intersection: the two dyads
    /// read off it give the four-bar back, angles and all.
    #[test]
    fn two_dyads_of_a_known_four_bar_give_it_back() {
        let (a, th, g, la, lb, lc) = (Vec2::new(0.7, -0.4), 0.3f64, 4.0, 1.5, 4.0, 3.0);
        let (e, alpha, tau) = (2.5, 0.6, 0.25);
        let d = a + Vec2::new(g * th.cos(), g * th.sin());
        let phis = [0.5, 0.9, 1.4, 1.9, 2.4];
        let mut poses = Vec::new();
        let mut truth = Vec::new();
        for &phi in &phis {
            let b = a + Vec2::new(la * (phi + th).cos(), la * (phi + th).sin());
            // C: the intersection of the circles about B (lb) and D (lc) on the left of B -> D.
            let bd = d - b;
            let dist = bd.norm();
            let x = (lb * lb - lc * lc + dist * dist) / (2.0 * dist);
            let h = (lb * lb - x * x).sqrt();
            let u = bd * (1.0 / dist);
            let c = b + u * x + Vec2::new(-u.y, u.x) * h;
            let beta = (c - b).angle();
            let p = b + Vec2::new(e * (beta + alpha).cos(), e * (beta + alpha).sin());
            poses.push(Pose { point: p, angle: beta + tau });
            truth.push((b, c, beta));
        }
        let betas: Vec<f64> = phis.iter().map(|p| p - phis[0]).collect();
        let input = Dyad { center: a, circle: truth[0].0, rotations: betas.clone() };
        let output = Dyad { center: d, circle: truth[0].1, rotations: betas };
        let f = FourBar::from_dyads(&input, &output, &poses).unwrap();
        let close = |x: f64, y: f64| (x - y).abs() < 1e-13;
        assert!(close(f.links.ground, g) && close(f.links.input, la) && close(f.links.coupler, lb));
        assert!(close(f.links.output, lc) && close(f.ground_angle, th));
        let (pe, pa) = f.coupler_point.unwrap();
        assert!(close(pe, e) && close(pa, alpha) && close(f.body_angle, tau), "{f:?}");
        for (k, phi) in phis.iter().enumerate() {
            assert!(close(f.inputs[k], *phi), "{:?}", f.inputs);
            assert!(close(f.couplers[k] + th, truth[k].2));
        }
        let same = FourBar::from_dyads(&input, &input, &poses);
        assert!(matches!(same, Err(ClassicalError::Degenerate(_))));
    }
}
