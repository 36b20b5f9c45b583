//! The cognates of a four-bar's coupler point: the two other four-bars whose coupler points
//! trace the same curve (the Roberts–Chebyshev theorem).
//!
//! In complex numbers, with the input link `r1 = B - A`, the coupler `r3 = C - B`, the output
//! link `r4 = C - D` and the coupler point `P = B + k r3` (`k` fixed in the coupler: the point's
//! distance from `B` over the coupler's length, turned by its angle from the line `B -> C`), the
//! loop is `A + r1 + r3 = D + r4`. Multiplying it by `k`, and by `m = 1 - k`, gives two more
//! loops through `P` whose links are the original's turned and scaled, with a third fixed pivot
//! `O = A + k (D - A)` (the triangle `A D O` is similar to the coupler's `B C P`):
//!
//! * about `A`: `A + k r3 + k r1 = O + k r4`, coupler point `P = A + k r3 + r1`;
//! * about `D`: `D - m r3 + m r4 = O + m r1`, coupler point `P = D - m r3 + r4`.
//!
//! Each link of a cognate is a link of the original turned by a fixed angle, so it turns as that
//! link does: the first cognate's input link as the original's coupler, its coupler as the
//! original's input link and its output link as the original's; the second's input link as the
//! original's coupler, its coupler as the original's output link and its output link as the
//! original's input link.

use super::dyad::{complex, vec2};
use super::error::{ClassicalError, finite};
use super::four_bar::FourBar;
use super::position::angle_difference;
use crate::metrics::FourBarLinks;
use crate::number::Count;
use nalgebra::Complex;
use std::f64::consts::PI;

/// A cognate whose link (or the distance of the coupler point from a joint) is shorter than
/// this fraction of the four-bar's size (the sum of its links) has collapsed: the coupler point
/// is on a joint, and its path a circle.
const COLLAPSED: f64 = 1e-12;

/// The largest difference, as a fraction of the four-bar's size, between its ground length and
/// the distance of its fixed pivots: their roundings agree far closer (a length typed to nine
/// digits beside pivots typed to nine passes), a different ground does not.
const GROUND_AGREES: f64 = 1e-9;

/// The two cognates of the four-bar `f`'s coupler point (the Roberts–Chebyshev theorem): the
/// four-bars whose coupler points trace the same curve as `f`'s, found in closed form from `f`'s
/// pivots, links and coupler point. The first turns about `f`'s input pivot `A`, the second about
/// its output pivot `D`; both share a third fixed pivot `O`, which makes with `A` and `D` a
/// triangle similar to the coupler's (`B`, `C` and the coupler point). A cognate is an
/// alternative for a path found by synthesis whose pivots or transmission do not suit: the same
/// path from other pivots and links.
///
/// Each cognate is a [`FourBar`] in the same conventions as `f`, with its link angles at `f`'s
/// precision points or poses, where its coupler point is `f`'s:
///
/// | | input pivot | output pivot | input link turns as `f`'s | coupler as `f`'s | output link as `f`'s |
/// |---|---|---|---|---|---|
/// | first | `A` | `O` | coupler | input link | output link |
/// | second | `D` | `O` | coupler | output link | input link |
///
/// So the first's `inputs` are `f`'s `couplers` (unwrapped from the first as `f`'s inputs are),
/// its `couplers` `f`'s `inputs` and its `outputs` `f`'s `outputs`; the second's `inputs` are
/// `f`'s `couplers`, its `couplers` `f`'s `outputs` less a half turn and its `outputs` `f`'s
/// `inputs` less a half turn (each within `(-pi, pi]`). Driven as `f` is driven (by its input
/// link), a cognate's input is `f`'s coupler, which rocks where `f`'s input turns fully: to move
/// a cognate through the whole curve, drive the link that turns as `f`'s input does. A cognate
/// carries the coupler point, not the body: its coupler turns as another link of `f`, so it
/// does not keep a body's angle, and its `body_angle` is `0`.
///
/// Errors ([`ClassicalError`]): `f` without a coupler point (a function generator); a value
/// that is not finite; a link length that is not positive; a ground length that is not the
/// fixed pivots' distance (within `1e-9` of the four-bar's size); angle lists of different
/// lengths; a coupler, input or output link of no length, or fixed pivots that coincide (within
/// `1e-12` of the four-bar's size), where the four-bar moves only as one body, if at all; the
/// coupler point on the joint `B` or `C` (as near), where its path is a circle about `A` or `D`
/// and a cognate collapses.
///
/// ```
/// use kinloop_runtime::Vec2;
/// use kinloop_runtime::metrics::FourBarLinks;
/// use kinloop_runtime::synthesis::classical::{FourBar, cognates};
/// // Ground 4, input 1.5, coupler 4, output 3; the coupler point 2.5 from B at 0.6 rad from BC.
/// let f = FourBar {
///     input_pivot: Vec2::new(0.0, 0.0),
///     output_pivot: Vec2::new(4.0, 0.0),
///     ground_angle: 0.0,
///     links: FourBarLinks { ground: 4.0, input: 1.5, coupler: 4.0, output: 3.0 },
///     coupler_point: Some((2.5, 0.6)),
///     body_angle: 0.0,
///     inputs: vec![],
///     couplers: vec![],
///     outputs: vec![],
/// };
/// let [first, second] = cognates(&f)?;
/// // The third pivot is shared; the first cognate's input link is the point's distance from B,
/// // the second's its distance from C.
/// assert!((first.output_pivot - second.output_pivot).norm() < 1e-12);
/// assert!((first.links.input - 2.5).abs() < 1e-12);
/// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
/// ```
pub fn cognates(f: &FourBar) -> Result<[FourBar; 2], ClassicalError> {
    let Some((distance, angle)) = f.coupler_point else {
        return Err(ClassicalError::Degenerate(
            "the four-bar has no coupler point (a function generator): cognates trace a coupler point's curve".into(),
        ));
    };
    let FourBarLinks { ground, input, coupler, output } = f.links;
    for (what, v) in [
        ("the input pivot's x", f.input_pivot.x),
        ("the input pivot's y", f.input_pivot.y),
        ("the output pivot's x", f.output_pivot.x),
        ("the output pivot's y", f.output_pivot.y),
        ("the ground length", ground),
        ("the input link's length", input),
        ("the coupler's length", coupler),
        ("the output link's length", output),
        ("the coupler point's distance", distance),
        ("the coupler point's angle", angle),
    ] {
        finite(v, || what.to_string())?;
    }
    for (what, list) in [("input", &f.inputs), ("coupler", &f.couplers), ("output", &f.outputs)] {
        for (j, &v) in list.iter().enumerate() {
            finite(v, || format!("the {what} angle at point {j}"))?;
        }
    }
    // A cognate's links are the original's scaled: a length that is not positive makes none.
    for (link, length) in [("input", input), ("coupler", coupler), ("output", output)] {
        if length <= 0.0 {
            return Err(ClassicalError::Degenerate(format!(
                "the {link} link's length is {length}: a four-bar's links have positive lengths"
            )));
        }
    }
    let n = f.inputs.len();
    if f.couplers.len() != n || f.outputs.len() != n {
        return Err(ClassicalError::BadRange {
            what: "four-bar angles",
            why: format!(
                "{n} input, {} coupler and {}: give one of each per precision point or pose",
                f.couplers.len(),
                Count(f.outputs.len(), "output angle")
            ),
        });
    }
    let size = ground.abs() + input + coupler + output;
    let tiny = COLLAPSED * size;
    if coupler <= tiny {
        return Err(ClassicalError::Degenerate(format!(
            "the coupler's length {coupler} is no length against the four-bar's size {size}: the coupler point's \
             place on it is not defined"
        )));
    }
    // A crank of no length holds its joint on its fixed pivot, and the four-bar cannot move (the
    // other links and the ground make a rigid triangle): its coupler point traces no curve, and
    // a cognate's link of `k` or `1 - k` times that length has none either (the first cognate's
    // coupler, which `cognates` itself refuses, or the second's output link). Fixed pivots
    // that coincide turn the whole four-bar about them as one body, the point's path a circle,
    // and both cognates' ground has no length.
    let pivots = (f.output_pivot - f.input_pivot).norm();
    for (what, length) in
        [("input link", input), ("output link", output), ("ground (between the fixed pivots)", pivots)]
    {
        if length <= tiny {
            return Err(ClassicalError::Degenerate(format!(
                "the {what} has a length of {length}, no length against the four-bar's size {size}: the \
                 four-bar cannot move but as one body, and a cognate collapses"
            )));
        }
    }
    // The pivots place the ground, and `links.ground` says its length again: read only here,
    // so that a four-bar described two ways is not answered for one of them in silence.
    if (ground - pivots).abs() > GROUND_AGREES * size {
        return Err(ClassicalError::Degenerate(format!(
            "the ground length {ground} is not the distance {pivots} between the fixed pivots: give the four-bar's \
             `links.ground` as `(output_pivot - input_pivot).norm()`"
        )));
    }
    // `P = B + k (C - B)`: `k` the coupler point in the coupler's own frame.
    let k = Complex::from_polar(distance / coupler, angle);
    let m = 1.0 - k;
    for (joint, length) in [("B", distance.abs()), ("C", m.norm() * coupler)] {
        if length <= tiny {
            return Err(ClassicalError::Degenerate(format!(
                "the coupler point is on the joint {joint} ({length} from it, against the four-bar's size {size}): \
                 its path is a circle about a fixed pivot, and a cognate collapses"
            )));
        }
    }
    let (a, d) = (f.input_pivot, f.output_pivot);
    let third = a + vec2(k * complex(d - a));
    let wrap = |x: f64| angle_difference(x, 0.0);
    let unwrapped = |list: &[f64]| -> Vec<f64> {
        let Some(&first) = list.first() else { return Vec::new() };
        let first = wrap(first);
        list.iter().map(|&x| first + angle_difference(x, first)).collect()
    };
    let shifted = |list: &[f64]| -> Vec<f64> { list.iter().map(|&x| wrap(x - PI)).collect() };
    let about_input = FourBar {
        input_pivot: a,
        output_pivot: third,
        ground_angle: (third - a).angle(),
        links: FourBarLinks {
            ground: (third - a).norm(),
            input: distance.abs(),
            coupler: k.norm() * input,
            output: k.norm() * output,
        },
        // `P - A1 = r1 = (C1 - A1) / k`: the original input link's length, at `-arg k`.
        coupler_point: Some((input, wrap(-k.arg()))),
        body_angle: 0.0,
        inputs: unwrapped(&f.couplers),
        couplers: f.inputs.iter().map(|&x| wrap(x)).collect(),
        outputs: f.outputs.iter().map(|&x| wrap(x)).collect(),
    };
    let about_output = FourBar {
        input_pivot: d,
        output_pivot: third,
        ground_angle: (third - d).angle(),
        links: FourBarLinks {
            ground: (third - d).norm(),
            input: m.norm() * coupler,
            coupler: m.norm() * output,
            output: m.norm() * input,
        },
        // `P - B2 = r4 = (C2 - B2) / m`: the original output link's length, at `-arg m`.
        coupler_point: Some((output, wrap(-m.arg()))),
        body_angle: 0.0,
        inputs: unwrapped(&f.couplers),
        couplers: shifted(&f.outputs),
        outputs: shifted(&f.inputs),
    };
    Ok([about_input, about_output])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec2;

    const TAU: f64 = 2.0 * PI;

    /// The point `p` of a four-bar's coupler in the plane when its links stand at the angles
    /// `(input, coupler)` from the ground line: for the tests, which rebuild each cognate's joints
    /// from its own description.
    fn coupler_point_at(f: &FourBar, input: f64, coupler: f64) -> (Vec2, Vec2) {
        let dir = |x: f64| Vec2::new(x.cos(), x.sin());
        let b = f.input_pivot + dir(f.ground_angle + input) * f.links.input;
        let (e, alpha) = f.coupler_point.unwrap();
        (b, b + dir(f.ground_angle + coupler + alpha) * e)
    }

    /// A four-bar at the input angles `phis` (from the ground line), its joints found here by
    /// intersecting circles on one side of `B -> D`, with its coupler point; and the coupler
    /// point's place in the plane at each angle.
    fn built(
        (a, th): (Vec2, f64),
        links: FourBarLinks,
        point: (f64, f64),
        side: f64,
        phis: &[f64],
    ) -> (FourBar, Vec<Vec2>) {
        let dir = |x: f64| Vec2::new(x.cos(), x.sin());
        let d = a + dir(th) * links.ground;
        let (mut inputs, mut couplers, mut outputs, mut points) = (vec![], vec![], vec![], vec![]);
        for &phi in phis {
            let b = a + dir(th + phi) * links.input;
            let bd = d - b;
            let dist = bd.norm();
            let x = (links.coupler.powi(2) - links.output.powi(2) + dist * dist) / (2.0 * dist);
            let h = (links.coupler.powi(2) - x * x).sqrt();
            assert!(h.is_finite(), "the test's four-bar does not close at {phi}");
            let u = bd * (1.0 / dist);
            let c = b + u * x + Vec2::new(-u.y, u.x) * (side * h);
            let beta = (c - b).angle();
            points.push(b + dir(beta + point.1) * point.0);
            inputs.push(phi);
            couplers.push(angle_difference(beta, th));
            outputs.push(angle_difference((c - d).angle(), th));
        }
        let f = FourBar {
            input_pivot: a,
            output_pivot: d,
            ground_angle: th,
            links,
            coupler_point: Some(point),
            body_angle: 0.0,
            inputs,
            couplers,
            outputs,
        };
        (f, points)
    }

    /// Every cognate, rebuilt from its own pivots, lengths and angles alone, closes (its output
    /// link meets its coupler at the coupler's length, along the coupler's angle) and puts its
    /// coupler point on the original's at every angle.
    fn assert_traces(g: &FourBar, points: &[Vec2], size: f64) {
        let dir = |x: f64| Vec2::new(x.cos(), x.sin());
        for (j, p) in points.iter().enumerate() {
            let (b, at) = coupler_point_at(g, g.inputs[j], g.couplers[j]);
            let c = g.output_pivot + dir(g.ground_angle + g.outputs[j]) * g.links.output;
            let gap = (c - (b + dir(g.ground_angle + g.couplers[j]) * g.links.coupler)).norm();
            assert!(gap <= 1e-13 * size, "the cognate does not close at {j}: gap {gap}\n{g:?}");
            assert!((at - *p).norm() <= 1e-13 * size, "cognate point {at:?} against {p:?} at {j}\n{g:?}");
        }
    }

    /// Four-bars of several kinds (crank-rockers and drag links in either assembly mode, a
    /// non-Grashof rocker over its stretch), with coupler points off the coupler line, on it
    /// beyond `C` and on it behind `B`, placed and turned in the plane at two sizes: both
    /// cognates trace the coupler point at every sampled angle, share the third pivot, and make
    /// with `A` and `D` a triangle similar to the coupler's.
    #[test]
    fn both_cognates_trace_the_coupler_point() {
        let cases = [
            // (ground, input, coupler, output), (distance from B, angle from BC), side, phis
            ((4.0, 1.5, 4.0, 3.0), (2.5, 0.6), 1.0, (0.0, TAU)),
            ((4.0, 1.5, 4.0, 3.0), (2.5, 0.6), -1.0, (0.0, TAU)),
            ((3.2, 1.0, 3.0, 2.5), (1.2, -1.1), 1.0, (0.0, TAU)),
            ((1.0, 2.0, 2.5, 3.0), (4.0, 0.0), 1.0, (0.0, TAU)),
            ((1.0, 2.0, 2.5, 3.0), (1.0, PI), -1.0, (0.0, TAU)),
            ((4.0, 3.0, 2.0, 2.5), (0.7, 2.0), 1.0, (-0.8, 0.8)),
        ];
        for (n, &((g, i, c, o), point, side, (from, to))) in cases.iter().enumerate() {
            for &(a, th, scale) in &[(Vec2::new(0.0, 0.0), 0.0, 1.0), (Vec2::new(-3.0, 7.5), 2.2, 1e3)] {
                let links = FourBarLinks { ground: g * scale, input: i * scale, coupler: c * scale, output: o * scale };
                let phis: Vec<f64> = (0..=36).map(|s| from + (to - from) * s as f64 / 36.0).collect();
                let (f, points) = built((a * scale, th), links, (point.0 * scale, point.1), side, &phis);
                let size = (g + i + c + o) * scale;
                let [first, second] = cognates(&f).unwrap_or_else(|e| panic!("case {n}: {e}"));
                assert_traces(&first, &points, size);
                assert_traces(&second, &points, size);
                assert_eq!((first.input_pivot, second.input_pivot), (f.input_pivot, f.output_pivot));
                assert_eq!(first.output_pivot, second.output_pivot);
                // The pivots' triangle is the coupler's, turned and scaled: (O - A) / (D - A) = k.
                let k = Complex::from_polar(point.0 / c, point.1);
                let ratio = complex(first.output_pivot - f.input_pivot) / complex(f.output_pivot - f.input_pivot);
                assert!((ratio - k).norm() < 1e-13, "case {n}: {ratio} against {k}");
            }
        }
    }

    /// A cognate's own first cognate is the four-bar it came from: the same pivots, links,
    /// coupler point and angles (the construction, applied twice, comes back).
    #[test]
    fn the_first_cognate_of_the_first_cognate_is_the_original() {
        let links = FourBarLinks { ground: 4.0, input: 1.5, coupler: 4.0, output: 3.0 };
        let phis: Vec<f64> = (0..12).map(|s| 0.5 * s as f64).collect();
        let (f, _) = built((Vec2::new(0.3, -0.2), 0.4), links, (2.5, 0.6), 1.0, &phis);
        let [first, _] = cognates(&f).unwrap();
        let [back, _] = cognates(&first).unwrap();
        let close = |x: f64, y: f64| (x - y).abs() < 1e-12;
        assert!(
            (back.input_pivot - f.input_pivot).norm() < 1e-12 && (back.output_pivot - f.output_pivot).norm() < 1e-12
        );
        assert!(close(back.ground_angle, f.ground_angle), "{back:?}");
        let (l, m) = (back.links, f.links);
        assert!(close(l.ground, m.ground) && close(l.input, m.input) && close(l.coupler, m.coupler));
        assert!(close(l.output, m.output));
        let ((e, alpha), (e0, alpha0)) = (back.coupler_point.unwrap(), f.coupler_point.unwrap());
        assert!(close(e, e0) && close(alpha, alpha0), "{back:?}");
        for j in 0..phis.len() {
            assert!(close(angle_difference(back.inputs[j], f.inputs[j]), 0.0));
            assert!(close(angle_difference(back.couplers[j], f.couplers[j]), 0.0));
            assert!(close(angle_difference(back.outputs[j], f.outputs[j]), 0.0));
        }
    }

    /// The first cognate's input angles are unwrapped from the first as a turning input's are:
    /// the original's coupler angles, which may cross the half turn, stay within a half turn
    /// of the first.
    #[test]
    fn a_cognates_input_angles_stay_within_a_half_turn_of_the_first() {
        let mut f = built(
            (Vec2::new(0.0, 0.0), 0.0),
            FourBarLinks { ground: 4.0, input: 1.5, coupler: 4.0, output: 3.0 },
            (2.5, 0.6),
            1.0,
            &[0.0],
        )
        .0;
        f.inputs = vec![0.1, 0.2];
        f.couplers = vec![3.1, -3.1];
        f.outputs = vec![0.5, 0.6];
        let [first, second] = cognates(&f).unwrap();
        assert!((first.inputs[0] - 3.1).abs() < 1e-15, "{:?}", first.inputs);
        assert!((first.inputs[1] - (TAU - 3.1)).abs() < 1e-15, "{:?}", first.inputs);
        assert_eq!(first.inputs, second.inputs);
        assert!((second.couplers[0] - (0.5 - PI)).abs() < 1e-15 && (second.outputs[1] - (0.2 - PI)).abs() < 1e-15);
    }

    #[test]
    fn a_four_bar_a_cognate_cannot_come_from_is_refused() {
        let base = built(
            (Vec2::new(0.0, 0.0), 0.0),
            FourBarLinks { ground: 4.0, input: 1.5, coupler: 4.0, output: 3.0 },
            (2.5, 0.6),
            1.0,
            &[0.2, 0.4],
        )
        .0;
        let refused = |change: &dyn Fn(&mut FourBar), says: &str| {
            let mut f = base.clone();
            change(&mut f);
            let e = cognates(&f).unwrap_err();
            assert!(e.to_string().contains(says), "{e}");
        };
        refused(&|f| f.coupler_point = None, "no coupler point");
        refused(&|f| f.coupler_point = Some((0.0, 0.6)), "on the joint B");
        refused(&|f| f.coupler_point = Some((4.0, 0.0)), "on the joint C");
        refused(&|f| f.coupler_point = Some((4.0 + 1e-14, 1e-16)), "on the joint C");
        refused(&|f| f.links.coupler = 0.0, "the coupler link's length is 0");
        refused(&|f| f.links.input = -1.5, "the input link's length is -1.5");
        // A crank of no length (the four-bar immobile), or fixed pivots that coincide: the
        // cognates had a link of no length (a coupler `cognates` refuses) or no ground.
        refused(&|f| f.links.coupler = 1e-13, "the coupler's length 0.0000000000001 is no length");
        refused(&|f| f.links.input = 1e-13, "the input link has a length of");
        refused(&|f| f.links.output = 1e-13, "the output link has a length of");
        refused(&|f| f.output_pivot = f.input_pivot, "the ground (between the fixed pivots) has a length of 0");
        refused(&|f| f.links.ground = 4.1, "the ground length 4.1 is not the distance 4 between the fixed pivots");
        refused(&|f| f.links.output = f64::NAN, "the output link's length is not finite");
        refused(&|f| f.input_pivot.y = f64::INFINITY, "the input pivot's y is not finite");
        refused(&|f| f.couplers[1] = f64::NAN, "the coupler angle at point 1 is not finite");
        refused(&|f| f.outputs.push(0.1), "2 input, 2 coupler and 3 output angles");
        // The coupler point a hair off its joint is a cognate, if a small one.
        let mut f = base.clone();
        f.coupler_point = Some((1e-9, 0.6));
        assert!(cognates(&f).is_ok());
    }
}
