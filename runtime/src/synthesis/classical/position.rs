//! The position of a four-bar by intersecting two circles: where the output link's end lies for
//! a given input angle, on either closure. Used to analyse a synthesised function generator
//! without the equation it was synthesised from.

use crate::Vec2;
use crate::metrics::FourBarLinks;

/// Which of the two closures of a four-bar for a given input angle: the coupler's end `C` lies
/// on one side or the other of the line from the input's end `B` to the output's pivot `D`.
///
/// [`CounterClockwise`](Closure::CounterClockwise) when the triangle `B, D, C` turns
/// counter-clockwise (`(D - B) x (C - B) > 0`). A linkage keeps its closure while it moves,
/// unless it passes a position where `B`, `C` and `D` line up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Closure {
    /// `(D - B) x (C - B) > 0`.
    CounterClockwise,
    /// `(D - B) x (C - B) < 0`.
    Clockwise,
}

/// The joints of a four-bar with the input pivot `A` at the origin and the output pivot `D` at
/// `(ground, 0)`: the input's end `B` for the input angle `phi`, and the output's angle for a
/// point `C` on the output link.
pub(crate) struct Frame {
    pub links: FourBarLinks,
}

impl Frame {
    /// The same four-bar with every length divided by the power of two at most the largest
    /// (exact, so the angles are the same): the squares and products of lengths the
    /// constructions below form then stay within the range of doubles at any unit, where those
    /// of lengths beyond about `1e154` overflow and those below `1e-154` underflow. Unchanged
    /// when no length is positive and finite.
    fn unit_sized(&self) -> Frame {
        let l = self.links;
        let largest = [l.ground, l.input, l.coupler, l.output].into_iter().fold(0.0, f64::max);
        if !(largest > 0.0 && largest.is_finite()) {
            return Frame { links: l };
        }
        let unit = crate::number::pow2_at_most(largest);
        let links = FourBarLinks {
            ground: l.ground / unit,
            input: l.input / unit,
            coupler: l.coupler / unit,
            output: l.output / unit,
        };
        Frame { links }
    }

    /// The input's end `B`.
    pub fn b(&self, phi: f64) -> Vec2 {
        let (s, c) = phi.sin_cos();
        Vec2::new(self.links.input * c, self.links.input * s)
    }

    /// The output's pivot `D`.
    pub fn d(&self) -> Vec2 {
        Vec2::new(self.links.ground, 0.0)
    }

    /// The output's end `C` for the output angle `psi`.
    pub fn c(&self, psi: f64) -> Vec2 {
        let (s, c) = psi.sin_cos();
        self.d() + Vec2::new(self.links.output * c, self.links.output * s)
    }

    /// The closure the output angle `psi` is on at the input angle `phi`; `None` when `B`, `D`
    /// and `C` line up to within `sine`: the sine of the angle at `D` between `D -> B` and
    /// `D -> C` is at most `sine` in magnitude (both closures are then the same position, to
    /// that angle), or `B` is on `D`, or a value is not finite.
    pub fn closure(&self, phi: f64, psi: f64, sine: f64) -> Option<Closure> {
        let f = self.unit_sized();
        let (b, d, c) = (f.b(phi), f.d(), f.c(psi));
        // (D - B) x (C - B) = (D - B) x (C - D) = |D - B| |C - D| sin(angle at D).
        let turn = (d - b).cross(c - b);
        let bound = sine * (d - b).norm() * (c - d).norm();
        if turn > bound && bound.is_finite() {
            Some(Closure::CounterClockwise)
        } else if turn < -bound && bound.is_finite() {
            Some(Closure::Clockwise)
        } else {
            None
        }
    }

    /// The output angle at the input angle `phi` on `closure`: `C` is where the circle of
    /// radius `coupler` about `B` meets the circle of radius `output` about `D`. `None` where
    /// they do not meet (the linkage cannot be assembled there).
    pub fn output_angle(&self, phi: f64, closure: Closure) -> Option<f64> {
        let f = self.unit_sized();
        let FourBarLinks { coupler: b, output: c, .. } = f.links;
        let (pb, d) = (f.b(phi), f.d());
        let e = pb - d;
        let l = e.norm();
        if l.is_nan() || l <= 0.0 {
            return None;
        }
        let u = e * (1.0 / l);
        let n = Vec2::new(-u.y, u.x);
        // Distance from D along u to the chord through the two intersections, and the half
        // chord; a half chord negative by rounding only (tangent circles) counts as zero.
        let along = (c * c - b * b + l * l) / (2.0 * l);
        let h2 = c * c - along * along;
        let rounding = 8.0 * f64::EPSILON * (c * c + b * b + l * l);
        if h2 < -rounding || !h2.is_finite() {
            return None;
        }
        let h = h2.max(0.0).sqrt();
        // (D - B) x (C - B) = -l h (n . rotated u = 1): counter-clockwise takes C on the -n side.
        let side = if closure == Closure::CounterClockwise { -h } else { h };
        let pc = d + u * along + n * side;
        Some((pc - d).angle())
    }
}

/// The angle `x - y` wrapped into `(-pi, pi]`.
pub(crate) fn angle_difference(x: f64, y: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let r = (x - y + PI).rem_euclid(TAU) - PI;
    if r == -PI { PI } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> Frame {
        Frame { links: FourBarLinks { ground: 3.2, input: 1.0, coupler: 3.0, output: 2.5 } }
    }

    /// Both closures close the loop (|C - B| = coupler), lie on the sides they are named for,
    /// and are mirror images in the line B-D.
    #[test]
    fn both_closures_close_the_loop_on_their_side() {
        let f = frame();
        for k in 0..24 {
            let phi = k as f64 * std::f64::consts::TAU / 24.0;
            for closure in [Closure::CounterClockwise, Closure::Clockwise] {
                let psi = f.output_angle(phi, closure).unwrap();
                assert!(((f.c(psi) - f.b(phi)).norm() - 3.0).abs() < 1e-14, "{phi} {closure:?}");
                assert_eq!(f.closure(phi, psi, 1e-12), Some(closure));
            }
        }
    }

    /// Coupler and output in line (input 0.75, coupler 0.5, output 0.75, ground 1 at `phi =
    /// 90` degrees: `|B - D| = 1.25 = b + c`, `C = (0.4, 0.45)`): no closure within a sine of
    /// `1e-12`, whichever side rounding puts `C` on; a point off the line by more has one.
    #[test]
    fn no_closure_where_coupler_and_output_lie_in_line() {
        let f = Frame { links: FourBarLinks { ground: 1.0, input: 0.75, coupler: 0.5, output: 0.75 } };
        let (phi, psi) = (std::f64::consts::FRAC_PI_2, 0.45f64.atan2(-0.6));
        assert_eq!(f.closure(phi, psi, 1e-12), None);
        assert_eq!(f.closure(phi, psi + 1e-9, 1e-12), Some(Closure::Clockwise));
        assert_eq!(f.closure(phi, psi - 1e-9, 1e-12), Some(Closure::CounterClockwise));
        assert_eq!(f.closure(phi, f64::NAN, 1e-12), None);
        let on_d = Frame { links: FourBarLinks { ground: 1.0, input: 1.0, coupler: 1.0, output: 1.0 } };
        assert_eq!(on_d.closure(0.0, 1.0, 1e-12), None, "B on D");
    }

    /// The output angle by the law of cosines at the unit scale: the angle at `D` between
    /// `D -> B` and `D -> C` is `acos((c^2 + l^2 - b^2) / (2 c l))`, `l = |B - D|`, turned from
    /// the direction of `D -> B` clockwise for the counter-clockwise closure.
    fn law_of_cosines(l: FourBarLinks, phi: f64, closure: Closure) -> f64 {
        let e = Vec2::new(l.input * phi.cos() - l.ground, l.input * phi.sin());
        let r = e.norm();
        let gamma = ((l.output * l.output + r * r - l.coupler * l.coupler) / (2.0 * l.output * r)).acos();
        if closure == Closure::CounterClockwise { e.angle() - gamma } else { e.angle() + gamma }
    }

    /// Lengths in any unit give the same angles: their squares left the range of doubles, so
    /// that a four-bar of lengths near `1e200` could not be assembled anywhere and one near
    /// `1e-200` came out with its output along the ground at every input (`C` on `D`: every
    /// square underflowed to zero), and one near `1e-160` lost digits to subnormal squares. The
    /// angles agree with the law of cosines at the unit scale to the rounding of the scaling.
    #[test]
    fn output_angles_and_closures_do_not_depend_on_the_unit() {
        let unit = frame().links;
        for scale in [1e-300, 1e-200, 1e-160, 1e-9, 1.0, 1e9, 1e160, 1e200, 1e300] {
            let links = FourBarLinks {
                ground: unit.ground * scale,
                input: unit.input * scale,
                coupler: unit.coupler * scale,
                output: unit.output * scale,
            };
            let f = Frame { links };
            for k in 0..24 {
                let phi = k as f64 * std::f64::consts::TAU / 24.0;
                for closure in [Closure::CounterClockwise, Closure::Clockwise] {
                    let want = law_of_cosines(unit, phi, closure);
                    let psi = f.output_angle(phi, closure);
                    let close = psi.is_some_and(|psi| angle_difference(psi, want).abs() < 1e-13);
                    assert!(close, "scale {scale:e}, phi {phi}, {closure:?}: {psi:?} vs {want}");
                    assert_eq!(f.closure(phi, want, 1e-12), Some(closure), "scale {scale:e}, phi {phi}");
                }
            }
        }
    }

    #[test]
    fn no_angle_where_the_circles_do_not_meet() {
        let f = Frame { links: FourBarLinks { ground: 3.0, input: 1.0, coupler: 0.5, output: 0.5 } };
        assert_eq!(f.output_angle(std::f64::consts::PI, Closure::Clockwise), None);
        let f = Frame { links: FourBarLinks { ground: 1.0, input: 1.0, coupler: 1.0, output: 1.0 } };
        assert_eq!(f.output_angle(0.0, Closure::Clockwise), None, "B on D");
    }

    #[test]
    fn angle_difference_wraps_into_half_open_interval() {
        use std::f64::consts::PI;
        assert!((angle_difference(0.1, 2.0 * PI - 0.1) - 0.2).abs() < 1e-15);
        assert_eq!(angle_difference(PI, 0.0), PI);
        assert_eq!(angle_difference(-PI, 0.0), PI);
        assert!((angle_difference(-3.0, 3.0) - (2.0 * PI - 6.0)).abs() < 1e-15);
    }
}
