//! The cognates of a coupler point (`classical::cognates`) as linkages: the original four-bar
//! and each cognate declared with `kinloop::mechanism!`, each cognate driven by the link that
//! turns as the original's input does, swept through whole turns by kinloop's branch-safe sweep
//! from the angles the cognate reports at the first pose. At every sample the three coupler
//! points coincide. The reference is the original four-bar itself, solved and swept by the same
//! library: the cognates' construction (complex-number loops) is independent of its solver.

use kinloop::Vec2;
use kinloop::synthesis::classical::{FourBar, cognates};
use std::f64::consts::TAU;

kinloop::mechanism! {
    /// A four-bar driven by its input link, from the pivot `(ax, ay)`, with the coupler point at
    /// `e` from `B` and `alpha` from the coupler line.
    pub struct Original {
        params ax, ay, dx, dy, a, b, c, e, alpha;
        input phi;
        unknowns beta = 0, gamma = 1;
        loop abcd: (ax, ay) + a @ phi + b @ beta == (dx, dy) + c @ gamma;
        point p = (ax, ay) + a @ phi + e @ (beta + alpha);
    }
}

kinloop::mechanism! {
    /// A four-bar driven by its coupler, which turns at `phi + shift`.
    pub struct ByCoupler {
        params ax, ay, dx, dy, a, b, c, e, alpha, shift;
        input phi;
        unknowns q_in = 0, q_out = 1;
        loop abcd: (ax, ay) + a @ q_in + b @ (phi + shift) == (dx, dy) + c @ q_out;
        point p = (ax, ay) + a @ q_in + e @ (phi + shift + alpha);
    }
}

kinloop::mechanism! {
    /// A four-bar driven by its output link, which turns at `phi + shift`.
    pub struct ByOutput {
        params ax, ay, dx, dy, a, b, c, e, alpha, shift;
        input phi;
        unknowns q_in = 0, q_cp = 1;
        loop abcd: (ax, ay) + a @ q_in + b @ q_cp == (dx, dy) + c @ (phi + shift);
        point p = (ax, ay) + a @ q_in + e @ (q_cp + alpha);
    }
}

/// The original's coupler point over `turns` of its input from its first pose, and each
/// cognate's over the same input, the cognate started at the angles it reports there; the
/// largest distance between the original's point and a cognate's, relative to the size.
fn largest_gap(f: &FourBar, turns: f64, samples: usize) -> [f64; 2] {
    let [ax, ay, dx, dy, a, b, c, e, alpha] = params_of(f);
    let original = Original { ax, ay, dx, dy, a, b, c, e, alpha };
    let l = f.links;
    let th = f.ground_angle;
    let from = f.inputs[0] + th;
    let to = from + turns * TAU;
    let start = OriginalUnknowns { beta: f.couplers[0] + th, gamma: f.outputs[0] + th };
    let points: Vec<Vec2> = original.sweep(from, to, samples, &start).unwrap().map(|s| s.unwrap().out.p).collect();
    let size = l.ground + l.input + l.coupler + l.output;
    let [first, second] = cognates(f).unwrap();
    let gap = |cognate: Vec<Vec2>| -> f64 {
        assert_eq!(cognate.len(), points.len());
        cognate.iter().zip(&points).map(|(q, p)| (*q - *p).norm()).fold(0.0, f64::max) / size
    };
    // The first cognate's coupler turns as the original's input: `shift` is its coupler's
    // absolute angle less the original's input's, at the first pose (the same at every pose).
    let g1 = first.ground_angle;
    let [ax, ay, dx, dy, a, b, c, e, alpha] = params_of(&first);
    let by_coupler = ByCoupler { ax, ay, dx, dy, a, b, c, e, alpha, shift: first.couplers[0] + g1 - from };
    let start = ByCouplerUnknowns { q_in: first.inputs[0] + g1, q_out: first.outputs[0] + g1 };
    let along_first = by_coupler.sweep(from, to, samples, &start).unwrap().map(|s| s.unwrap().out.p);
    // The second's output link turns as the original's input.
    let g2 = second.ground_angle;
    let [ax, ay, dx, dy, a, b, c, e, alpha] = params_of(&second);
    let by_output = ByOutput { ax, ay, dx, dy, a, b, c, e, alpha, shift: second.outputs[0] + g2 - from };
    let start = ByOutputUnknowns { q_in: second.inputs[0] + g2, q_cp: second.couplers[0] + g2 };
    let along_second = by_output.sweep(from, to, samples, &start).unwrap().map(|s| s.unwrap().out.p);
    [gap(along_first.collect()), gap(along_second.collect())]
}

/// A four-bar's parameters as the declarations take them: its fixed pivots, its links and its
/// coupler point.
fn params_of(g: &FourBar) -> [f64; 9] {
    let (a, o, l) = (g.input_pivot, g.output_pivot, g.links);
    let (e, alpha) = g.coupler_point.unwrap();
    [a.x, a.y, o.x, o.y, l.input, l.coupler, l.output, e, alpha]
}

/// A four-bar at the first pose only, its coupler and output angles by intersecting circles on
/// the side `side` of `B -> D`.
fn four_bar(
    (a, th): (Vec2, f64),
    [ground, input, coupler, output]: [f64; 4],
    point: (f64, f64),
    side: f64,
    phi: f64,
) -> FourBar {
    let dir = |x: f64| Vec2::new(x.cos(), x.sin());
    let d = a + dir(th) * ground;
    let b = a + dir(th + phi) * input;
    let bd = d - b;
    let dist = bd.norm();
    let x = (coupler * coupler - output * output + dist * dist) / (2.0 * dist);
    let h = (coupler * coupler - x * x).sqrt();
    let u = bd * (1.0 / dist);
    let c = b + u * x + Vec2::new(-u.y, u.x) * (side * h);
    FourBar {
        input_pivot: a,
        output_pivot: d,
        ground_angle: th,
        links: kinloop::metrics::FourBarLinks { ground, input, coupler, output },
        coupler_point: Some(point),
        body_angle: 0.0,
        inputs: vec![phi],
        couplers: vec![(c - b).angle() - th],
        outputs: vec![(c - d).angle() - th],
    }
}

/// Crank-rockers (either assembly mode) and a drag link, placed and turned in the plane, at three
/// sizes: through three turns of the original's crank, at 720 samples a turn, each cognate's
/// coupler point stays on the original's to a few hundred roundings of the size.
#[test]
fn cognates_driven_with_the_crank_trace_the_coupler_curve_through_whole_turns() {
    let cases = [
        ([4.0, 1.5, 4.0, 3.0], (2.5, 0.6), 1.0),
        ([4.0, 1.5, 4.0, 3.0], (2.5, 0.6), -1.0),
        ([3.2, 1.0, 3.0, 2.5], (1.2, -1.1), 1.0),
        ([3.2, 1.0, 3.0, 2.5], (4.5, 2.8), -1.0),
        ([1.0, 2.0, 2.5, 3.0], (1.5, 0.3), 1.0),
    ];
    for (n, &(links, (e, alpha), side)) in cases.iter().enumerate() {
        for &(scale, at, th) in
            &[(1.0, Vec2::new(0.0, 0.0), 0.0), (1e-3, Vec2::new(2.0, -1.0), 1.3), (1e4, Vec2::new(-5.0, 3.0), -2.6)]
        {
            let f = four_bar((at * scale, th), links.map(|l| l * scale), (e * scale, alpha), side, 0.4);
            let gaps = largest_gap(&f, 3.0, 3 * 720 + 1);
            assert!(gaps.iter().all(|g| *g < 1e-13), "case {n} at scale {scale}: gaps {gaps:?}");
        }
    }
}

/// The cognates of a rocking four-bar's coupler point trace it where the original moves: over
/// the stretch between its limit positions, each cognate driven by the link that rocks as the
/// original's input does.
#[test]
fn cognates_of_a_rocking_four_bar_trace_its_stretch() {
    // Non-Grashof (no link turns fully): the input rocks about 0 between limit positions at
    // +-1.371 rad (`|B - D| = b + c`: `cos phi = 4.75 / 24`).
    let f = four_bar((Vec2::new(0.0, 0.0), 0.0), [4.0, 3.0, 2.0, 2.5], (0.7, 2.0), 1.0, -0.8);
    let [first, second] = cognates(&f).unwrap();
    let gaps = largest_gap(&f, 1.6 / TAU, 161);
    assert!(gaps.iter().all(|g| *g < 1e-13), "gaps {gaps:?}");
    // The shared third pivot makes with A and D the coupler's triangle, turned and scaled.
    let o = first.output_pivot;
    let (k_abs, k_arg) = (0.7 / 2.0, 2.0);
    assert!(((o - f.input_pivot).norm() - k_abs * 4.0).abs() < 1e-14);
    assert!(((o - f.input_pivot).angle() - k_arg).abs() < 1e-14 && (second.output_pivot - o).norm() < 1e-14);
}
