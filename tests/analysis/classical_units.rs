//! The classical synthesis in any unit of length. A change of unit by a power of two is exact in
//! doubles, and every result comes out scaled to the bit from 2^-1000 to 2^1000: no threshold,
//! coefficient or root finder in the Burmester curves and points, the four-bar of two dyads or
//! the cognates depends on the unit. A decimal change (metres to micrometres, 1e-6) rounds the
//! poses in the new unit, and the Burmester pairs then move as far as poses changed in their last
//! digit move them: the problem's conditioning, not the code's. A pair with a crank 18 times the
//! problem's size moves by about 1e-9 of the size, 7e-11 of its crank, either way.

use kinloop::Vec2;
use kinloop::synthesis::classical::{
    BurmesterConfig, Dyad, FourBar, Pose, burmester_points, center_point_curve, cognates,
};

/// Five poses each, from the Burmester unit tests (`runtime/src/synthesis/classical/burmester/`):
/// mpmath's 50-digit reference problem (`reference/burmester_five_poses.csv`: four pairs, one
/// with a crank 31 times the size), and the two with a pair next to the degenerate crank
/// rotations (`tests.rs`: its crank 18 times the size).
fn problems() -> [[Pose; 5]; 3] {
    [
        [
            Pose::new(1.7344890208828374, 3.3218133557255403, 0.8257329578321473),
            Pose::new(1.5015550311071153, 3.611397293510579, 0.6986787589002955),
            Pose::new(0.9977726427202075, 3.6605765664011773, 0.6404757049257437),
            Pose::new(0.2905897108488712, 3.3947314183621464, 0.6296594965142271),
            Pose::new(-0.31365482817045515, 2.8384405837630804, 0.6710341737790019),
        ],
        [(0.0, 0.0, 0.0), (1.0, 0.3, 0.4), (1.8, 1.1, 0.9), (2.1, 2.2, 1.6), (2.0, 3.0, 2.0)]
            .map(|(x, y, a)| Pose::new(x, y, a)),
        [
            (0.246, 1.748, 0.581),
            (3.224, 3.933, 0.273),
            (2.186, 3.787, 1.119),
            (3.514, 3.164, 0.196),
            (1.726, 2.383, 1.193),
        ]
        .map(|(x, y, a)| Pose::new(x, y, a)),
    ]
}

/// The poses with their points multiplied by `s` (a change of unit), their angles kept.
fn scaled(poses: &[Pose], s: f64) -> Vec<Pose> {
    poses.iter().map(|p| Pose { point: p.point * s, angle: p.angle }).collect()
}

/// A four-bar with every length and point multiplied by `s`, its angles kept.
fn scaled_four_bar(f: &FourBar, s: f64) -> FourBar {
    let l = f.links;
    FourBar {
        input_pivot: f.input_pivot * s,
        output_pivot: f.output_pivot * s,
        links: kinloop::metrics::FourBarLinks {
            ground: l.ground * s,
            input: l.input * s,
            coupler: l.coupler * s,
            output: l.output * s,
        },
        coupler_point: f.coupler_point.map(|(e, angle)| (e * s, angle)),
        ..f.clone()
    }
}

#[test]
fn every_result_is_scaled_to_the_bit_by_a_power_of_two_unit() {
    let cfg = BurmesterConfig::default();
    for (n, poses) in problems().iter().enumerate() {
        let base = burmester_points(poses, &cfg).unwrap();
        assert!(base.dyads.len() >= 2, "problem {n}: {base:?}");
        let curve = center_point_curve(&poses[..4], &cfg.samples(120)).unwrap();
        let four_bar = FourBar::from_dyads(&base.dyads[0], &base.dyads[1], poses).unwrap();
        let [first, second] = cognates(&four_bar).unwrap();
        for e in [-1000, -500, -20, 20, 500, 1000] {
            let s = 2f64.powi(e);
            let poses = scaled(poses, s);
            let found = burmester_points(&poses, &cfg).unwrap();
            let want: Vec<Dyad> =
                base.dyads.iter().map(|d| Dyad { center: d.center * s, circle: d.circle * s, ..d.clone() }).collect();
            assert_eq!(found.dyads, want, "problem {n}, 2^{e}");
            assert_eq!((found.size, found.max_deviation), (base.size * s, base.max_deviation), "problem {n}, 2^{e}");
            let c = center_point_curve(&poses[..4], &cfg.samples(120)).unwrap();
            assert_eq!(c.points.len(), curve.points.len(), "problem {n}, 2^{e}");
            for (p, q) in c.points.iter().zip(&curve.points) {
                assert_eq!((p.beta2, p.branch), (q.beta2, q.branch));
                assert_eq!((p.dyad.center, p.dyad.circle), (q.dyad.center * s, q.dyad.circle * s), "2^{e}");
                assert_eq!(p.dyad.rotations, q.dyad.rotations);
            }
            let f = FourBar::from_dyads(&found.dyads[0], &found.dyads[1], &poses).unwrap();
            assert_eq!(f, scaled_four_bar(&four_bar, s), "problem {n}, 2^{e}");
            let [g, h] = cognates(&f).unwrap();
            assert_eq!((g, h), (scaled_four_bar(&first, s), scaled_four_bar(&second, s)), "problem {n}, 2^{e}");
        }
    }
}

/// The largest distance of `found`'s pairs (divided by `s`) from the nearest of `base`'s, relative
/// to the problem's size or the crank where longer; infinite when the counts differ.
fn moved(base: &[Dyad], found: &[Dyad], s: f64, size: f64) -> f64 {
    if base.len() != found.len() {
        return f64::INFINITY;
    }
    let apart = |d: &Dyad, b: &Dyad| {
        let (c, k) = (d.center * (1.0 / s) - b.center, d.circle * (1.0 / s) - b.circle);
        c.norm().max(k.norm()) / size.max(b.radius())
    };
    base.iter().map(|b| found.iter().map(|d| apart(d, b)).fold(f64::INFINITY, f64::min)).fold(0.0, f64::max)
}

#[test]
fn a_decimal_unit_moves_the_burmester_pairs_as_far_as_the_poses_last_digits_do() {
    let cfg = BurmesterConfig::default();
    for (n, poses) in problems().iter().enumerate() {
        let base = burmester_points(poses, &cfg).unwrap();
        // Every coordinate changed by up to an ulp, eight ways: how far rounding the poses alone
        // moves the pairs.
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut ulps = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        };
        let sensitivity = (0..8)
            .map(|_| {
                let nudged: Vec<Pose> = poses
                    .iter()
                    .map(|p| {
                        let (x, y) =
                            (p.point.x * (1.0 + f64::EPSILON * ulps()), p.point.y * (1.0 + f64::EPSILON * ulps()));
                        Pose { point: Vec2::new(x, y), ..*p }
                    })
                    .collect();
                moved(&base.dyads, &burmester_points(&nudged, &cfg).unwrap().dyads, 1.0, base.size)
            })
            .fold(0.0, f64::max);
        for s in [1e-6, 1e-3, 1e3, 1e6] {
            let found = burmester_points(&scaled(poses, s), &cfg).unwrap();
            let d = moved(&base.dyads, &found.dyads, s, base.size);
            assert!(d <= 1e-10, "problem {n}, {s:e}: {d:e}");
            assert!(d <= 4.0 * sensitivity.max(f64::EPSILON), "problem {n}, {s:e}: {d:e} against {sensitivity:e}");
        }
    }
}
