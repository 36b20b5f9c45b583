//! Function generation by Freudenstein's equation.
//!
//! A four-bar with the input pivot `A` at the origin, the output pivot `D` at `(d, 0)`, input
//! link `a = AB`, coupler `b = BC` and output link `c = DC`, the input angle `phi` of `AB` and
//! the output angle `psi` of `DC` both measured counter-clockwise from the direction `A -> D`,
//! closes when `|C - B| = b`. Squaring that distance and dividing by `2 a c` leaves one
//! equation between the two angles in which the lengths enter only through three ratios:
//!
//! `K1 cos(psi) - K2 cos(phi) + K3 = cos(phi - psi)`,
//!
//! `K1 = d / a`, `K2 = d / c`, `K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c)`.
//!
//! It is linear in `K1, K2, K3`: three pairs `(phi_i, psi_i)` (precision points) give a 3x3
//! linear system whose solution makes the linkage pass through them exactly; more pairs give
//! an overdetermined system, solved in the least-squares sense. The lengths follow back from the
//! ratios: with the ground `d = 1`, `a = 1 / K1`, `c = 1 / K2`,
//! `b^2 = a^2 + c^2 + 1 - 2 a c K3`.
//!
//! A negative `a` (or `c`) is the same linkage with that link's angle measured from the
//! opposite direction: adding `pi` to every `phi` changes the signs of `K1` and `K3`, adding
//! `pi` to every `psi` those of `K2` and `K3`. [`freudenstein`] reports such a result as an
//! error naming that remedy rather than silently turning the angles.

use super::error::{ClassicalError, finite};
use super::position::{Closure, Frame, angle_difference};
use crate::metrics::FourBarLinks;
use nalgebra::{DMatrix, DVector};

/// Smallest reciprocal condition number of the Freudenstein system accepted. Its columns
/// (`cos psi`, `-cos phi`, `1`) are all of order one, so the ratio of its singular values is the
/// relative accuracy lost: below `1e-10` the ratios `K` would keep fewer than six digits.
pub const MIN_RCOND: f64 = 1e-10;

/// Two precision points closer than this (radians, in both angles) count as one.
pub const COINCIDENT_ANGLE: f64 = 1e-12;

/// One pair of input and output angles (radians) the linkage is to reach together.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrecisionPoint {
    /// Input angle.
    pub phi: f64,
    /// Output angle.
    pub psi: f64,
}

/// A four-bar function generator from [`freudenstein`].
#[derive(Clone, Debug, PartialEq)]
pub struct FunctionGenerator {
    /// The ratios `[K1, K2, K3]` of Freudenstein's equation.
    pub k: [f64; 3],
    /// The link lengths, with the ground `d = 1` ([`scaled`](Self::scaled) gives other sizes).
    pub links: FourBarLinks,
    /// Root mean square of the equation's residual `K1 cos psi - K2 cos phi + K3 - cos(phi -
    /// psi)` over the precision points: rounding level for three points, the least-squares
    /// misfit for more (dimensionless; see [`output_error`](Self::output_error) for angles).
    pub residual: f64,
    /// The largest absolute residual over the precision points.
    pub max_residual: f64,
    /// Reciprocal condition number of the linear system (smallest over largest singular value).
    pub rcond: f64,
    /// The closure the linkage is on: the one of the first precision point, or, when the
    /// coupler and the output link lie in line there (see [`freudenstein`]), of the first point
    /// after it where they do not.
    pub closure: Closure,
    /// Whether every precision point lies on that same closure (a point where the coupler and
    /// the output link lie in line lies on both). When not, the linkage meets the points only
    /// by being taken apart and reassembled: a branch defect.
    pub one_closure: bool,
}

/// The four-bar function generator through the precision points: the exact solution of
/// Freudenstein's equation for three points, the least-squares one for more.
///
/// The linkage's closure (which side of the line from the input's end `B` to the output's
/// pivot `D` the coupler's end `C` lies on) is read from the precision points in order. At a
/// point where `B`, `C` and `D` lie in line (the coupler and the output link stretched out or
/// folded over each other: a limit position of the input, the transmission angle 0 or 180
/// degrees) both closures are one and the same position, so that point does not decide it:
/// the linkage passes from it into the closure of the next point, and the first point that
/// decides is taken. In line means: the angle at `D` between `D -> B` and `D -> C` has a sine
/// of at most [`COINCIDENT_ANGLE`], or of the fit's relative accuracy `16 eps / rcond` where
/// that is larger (the side the rounding of the lengths puts `C` on is not a closure).
///
/// Errors: fewer than three points; an angle not finite; two points coinciding (within
/// [`COINCIDENT_ANGLE`] in both angles); a singular or ill-conditioned system (reciprocal
/// condition number below [`MIN_RCOND`]); a link length not positive and finite; `B`, `C` and
/// `D` in line at every point ([`ClassicalError::Degenerate`]: the closure is not determined).
///
/// ```
/// use kinloop_runtime::deg;
/// use kinloop_runtime::synthesis::classical::{FunctionMap, chebyshev_points, freudenstein};
/// // y = log10(x) over 1 <= x <= 2: the input turns 90 degrees from 60, the output 90 from 90.
/// let map = FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0))?;
/// let points = map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0)?)?;
/// let g = freudenstein(&points)?;
/// assert_eq!(g.links.ground, 1.0);
/// assert!(g.one_closure);
/// for p in &points {
///     // Analysed by intersecting circles, the linkage meets every point.
///     assert!(g.output_error(*p).unwrap().abs() < 1e-12);
/// }
/// let mm = g.scaled(100.0); // a ground of 100 mm
/// assert!((mm.input / mm.ground - g.links.input).abs() < 1e-15);
/// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
/// ```
pub fn freudenstein(points: &[PrecisionPoint]) -> Result<FunctionGenerator, ClassicalError> {
    if points.len() < 3 {
        return Err(ClassicalError::Count {
            method: "Freudenstein's equation",
            what: "precision points",
            needed: "at least 3",
            given: points.len(),
        });
    }
    for (i, p) in points.iter().enumerate() {
        finite(p.phi, || format!("the input angle of precision point {i}"))?;
        finite(p.psi, || format!("the output angle of precision point {i}"))?;
    }
    coincident(points)?;
    let n = points.len();
    let a = DMatrix::from_fn(n, 3, |i, j| match j {
        0 => points[i].psi.cos(),
        1 => -points[i].phi.cos(),
        _ => 1.0,
    });
    let rhs = DVector::from_fn(n, |i, _| (points[i].phi - points[i].psi).cos());
    let svd = a.clone().svd(true, true);
    let (largest, smallest) = (svd.singular_values.max(), svd.singular_values.min());
    let rcond = smallest / largest;
    if rcond.is_nan() || rcond < MIN_RCOND {
        return Err(ClassicalError::Singular { what: "Freudenstein system", rcond, tolerance: MIN_RCOND });
    }
    let k = svd.solve(&rhs, 0.0).map_err(|why| ClassicalError::Degenerate(why.into()))?;
    let k = [k[0], k[1], k[2]];
    let links = lengths(k)?;
    let misfit = &a * DVector::from_column_slice(&k) - &rhs;
    let residual = (misfit.norm_squared() / n as f64).sqrt();
    let max_residual = misfit.amax();
    let frame = Frame { links };
    let in_line = COINCIDENT_ANGLE.max(16.0 * f64::EPSILON / rcond);
    let closures: Vec<Option<Closure>> = points.iter().map(|p| frame.closure(p.phi, p.psi, in_line)).collect();
    let (closure, one_closure) = common_closure(&closures)?;
    Ok(FunctionGenerator { k, links, residual, max_residual, rcond, closure, one_closure })
}

/// The closure of the first point that has one (`None`: the coupler and the output in line
/// there), and whether every point that has one has the same.
fn common_closure(closures: &[Option<Closure>]) -> Result<(Closure, bool), ClassicalError> {
    let Some(closure) = closures.iter().flatten().next().copied() else {
        return Err(ClassicalError::Degenerate(
            "the coupler and the output link lie in line at every precision point, so the closure (the side \
             of the line from the input's end to the output's pivot the coupler's end lies on) is not \
             determined: add a precision point away from the input's limit positions"
                .into(),
        ));
    };
    Ok((closure, closures.iter().all(|c| c.is_none_or(|c| c == closure))))
}

/// Two points with both angles the same (modulo a turn) within [`COINCIDENT_ANGLE`].
fn coincident(points: &[PrecisionPoint]) -> Result<(), ClassicalError> {
    for (i, p) in points.iter().enumerate() {
        for (j, q) in points.iter().enumerate().skip(i + 1) {
            let same = |x: f64, y: f64| angle_difference(x, y).abs() <= COINCIDENT_ANGLE;
            if same(p.phi, q.phi) && same(p.psi, q.psi) {
                return Err(ClassicalError::Coincident { what: "precision points", first: i, second: j });
            }
        }
    }
    Ok(())
}

/// The link lengths (ground 1) from the ratios, or why they are not a linkage.
fn lengths([k1, k2, k3]: [f64; 3]) -> Result<FourBarLinks, ClassicalError> {
    let (a, c) = (1.0 / k1, 1.0 / k2);
    let bad = |link, value, hint| Err(ClassicalError::BadLength { link, value, hint });
    if !(a.is_finite() && a > 0.0) {
        return bad(
            "input",
            a,
            "measure the input angles from the opposite direction (add 180 degrees to phi0) or change the ranges",
        );
    }
    if !(c.is_finite() && c > 0.0) {
        return bad(
            "output",
            c,
            "measure the output angles from the opposite direction (add 180 degrees to psi0) or change the ranges",
        );
    }
    let b2 = a * a + c * c + 1.0 - 2.0 * a * c * k3;
    // b^2 is a difference of terms of size a^2 + c^2 + 1: below their rounding it is not a length.
    if b2.is_nan() || b2 <= 8.0 * f64::EPSILON * (a * a + c * c + 1.0) {
        return bad(
            "coupler",
            b2,
            "no coupler closes the loop at these points (its square comes out not positive): change the ranges",
        );
    }
    Ok(FourBarLinks { ground: 1.0, input: a, coupler: b2.sqrt(), output: c })
}

impl FunctionGenerator {
    /// The link lengths for a ground link of length `ground` (any unit).
    pub fn scaled(&self, ground: f64) -> FourBarLinks {
        let l = self.links;
        FourBarLinks { ground, input: l.input * ground, coupler: l.coupler * ground, output: l.output * ground }
    }

    /// The output angle of the linkage at the input angle `phi`, on the closure of the first
    /// precision point (found by intersecting the coupler's and the output's circles, not from
    /// Freudenstein's equation). `None` where the linkage cannot be assembled.
    pub fn output_angle(&self, phi: f64) -> Option<f64> {
        Frame { links: self.links }.output_angle(phi, self.closure)
    }

    /// How far the linkage's output angle is from the point's at the point's input angle
    /// (radians, wrapped into `(-pi, pi]`); `None` where it cannot be assembled.
    pub fn output_error(&self, point: PrecisionPoint) -> Option<f64> {
        self.output_angle(point.phi).map(|psi| angle_difference(psi, point.psi))
    }
}

#[cfg(test)]
mod tests;
