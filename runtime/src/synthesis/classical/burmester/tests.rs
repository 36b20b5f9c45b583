//! Burmester's curves and points against independent references: the two dyads of a known
//! four-bar whose coupler made the poses, mpmath's 50-digit solution of the Cartesian
//! five-pose conditions (`reference/generate.py`), and the circle property of every dyad
//! returned (checked from its pivots and the poses alone).

use super::*;
use crate::synthesis::classical::position::{Closure, Frame};
use crate::{Vec2, deg, metrics::FourBarLinks};

/// A known dyad: fixed pivot, moving pivot in the first pose, crank rotations.
struct Known {
    center: Vec2,
    circle: Vec2,
    rotations: Vec<f64>,
}

/// Poses of the coupler of the four-bar of `reference/generate.py` (ground 4, input 1.5,
/// coupler 4, output 3, coupler point 2.5 from B at 0.6 rad from BC, open closure, turned by
/// 0.25 rad and moved by (0.3, -0.2)) at the input angles `phis` (degrees), with its two dyads.
fn four_bar_poses(phis: &[f64]) -> (Vec<Pose>, [Known; 2]) {
    let frame = Frame { links: FourBarLinks { ground: 4.0, input: 1.5, coupler: 4.0, output: 3.0 } };
    let (turn, origin) = (0.25f64, Vec2::new(0.3, -0.2));
    let place = |v: Vec2| {
        let (s, c) = turn.sin_cos();
        origin + Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
    };
    let (mut poses, mut bs, mut cs, mut psis) = (vec![], vec![], vec![], vec![]);
    for &phi in phis.iter().map(|p| deg(*p)).collect::<Vec<_>>().iter() {
        let psi = [Closure::CounterClockwise, Closure::Clockwise]
            .into_iter()
            .map(|c| frame.output_angle(phi, c).unwrap())
            .find(|&psi| psi.sin() > 0.0)
            .unwrap();
        let (b, c) = (frame.b(phi), frame.c(psi));
        let theta = (c - b).angle();
        let p = b + Vec2::new((theta + 0.6).cos(), (theta + 0.6).sin()) * 2.5;
        let p = place(p);
        poses.push(Pose { point: p, angle: theta + turn });
        bs.push(place(b));
        cs.push(place(c));
        psis.push(psi);
    }
    let input = Known {
        center: place(Vec2::new(0.0, 0.0)),
        circle: bs[0],
        rotations: phis.iter().map(|p| deg(p - phis[0])).collect(),
    };
    let output =
        Known { center: place(frame.d()), circle: cs[0], rotations: psis.iter().map(|p| p - psis[0]).collect() };
    (poses, [input, output])
}

/// A dyad's deviation relative to the problem (or the crank, when longer): what the circle
/// property allows a correct dyad computed in doubles. The pivots come from a linear solve
/// whose conditioning the rotations set; a few hundred roundings of the problem's size.
const DEVIATION: f64 = 1e-10;

#[test]
fn the_four_pose_curve_passes_through_the_known_four_bars_pivots() {
    let (poses, known) = four_bar_poses(&[30.0, 55.0, 80.0, 110.0]);
    let size = check_poses(&poses, 4, "test").unwrap();
    for k in &known {
        let dyads = dyads_at(&poses, k.rotations[1]).unwrap();
        let hit = dyads
            .iter()
            .flatten()
            .find(|d| (d.center - k.center).norm() < 1e-12 * size)
            .unwrap_or_else(|| panic!("no dyad at {:?}: {dyads:?}", k.center));
        assert!((hit.circle - k.circle).norm() < 1e-12 * size);
        for j in 1..4 {
            assert!(angle_difference(hit.rotations[j], k.rotations[j]).abs() < 1e-12);
        }
    }
}

#[test]
fn every_point_of_the_four_pose_curve_keeps_its_circle() {
    let (poses, _) = four_bar_poses(&[30.0, 55.0, 80.0, 110.0]);
    let curve = center_point_curve(&poses, &BurmesterConfig::default()).unwrap();
    // Both branches exist over most of the turn here.
    assert!(curve.points.len() > 720, "{}", curve.points.len());
    assert!(curve.max_deviation <= DEVIATION, "{:e}", curve.max_deviation);
    for p in &curve.points {
        assert!(p.dyad.deviation(&poses) <= DEVIATION * curve.size.max(p.dyad.radius()), "{p:?}");
    }
    assert_eq!(curve.center_points().count(), curve.points.len());
    assert_eq!(curve.circle_points().next(), Some(curve.points[0].dyad.circle));
}

/// `reference/burmester_five_poses.csv`: the poses (17 digits, the problem solved in both) and
/// mpmath's Burmester pairs.
fn reference() -> (Vec<Pose>, Vec<(Vec2, Vec2)>) {
    let (mut poses, mut pairs) = (vec![], vec![]);
    for line in include_str!("../reference/burmester_five_poses.csv").lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let v = |i: usize| f[i].parse::<f64>().unwrap();
        match f[0] {
            "pose" => poses.push(Pose::new(v(1), v(2), v(3))),
            _ => pairs.push((Vec2::new(v(1), v(2)), Vec2::new(v(3), v(4)))),
        }
    }
    (poses, pairs)
}

#[test]
fn five_poses_give_the_four_burmester_pairs_of_the_50_digit_reference() {
    let (poses, pairs) = reference();
    assert_eq!(pairs.len(), 4);
    let found = burmester_points(&poses, &BurmesterConfig::default()).unwrap();
    assert_eq!(found.dyads.len(), 4, "{found:?}");
    assert!(found.max_deviation <= DEVIATION, "{:e}", found.max_deviation);
    // Both sorted by the center's x.
    for (dyad, (center, circle)) in found.dyads.iter().zip(&pairs) {
        let scale = found.size.max(dyad.radius());
        assert!((dyad.center - *center).norm() <= 1e-11 * scale, "{dyad:?} vs {center:?}");
        assert!((dyad.circle - *circle).norm() <= 1e-11 * scale, "{dyad:?} vs {circle:?}");
    }
}

#[test]
fn five_poses_of_a_four_bar_give_its_own_two_dyads_among_the_burmester_points() {
    let (poses, known) = four_bar_poses(&[30.0, 55.0, 80.0, 110.0, 140.0]);
    let found = burmester_points(&poses, &BurmesterConfig::default()).unwrap();
    for k in &known {
        let hit = found.dyads.iter().find(|d| (d.center - k.center).norm() < 1e-11 * found.size);
        let hit = hit.unwrap_or_else(|| panic!("{:?} not among {:?}", k.center, found.dyads));
        assert!((hit.circle - k.circle).norm() < 1e-11 * found.size);
        for j in 1..5 {
            assert!(angle_difference(hit.rotations[j], k.rotations[j]).abs() < 1e-10);
        }
    }
}

/// Millimetres instead of metres, and the whole problem turned and moved: the same dyads,
/// scaled, turned and moved (the tolerances are relative to the problem's size).
#[test]
fn burmester_points_follow_a_change_of_unit_and_placement() {
    let (poses, _) = reference();
    let base = burmester_points(&poses, &BurmesterConfig::default()).unwrap();
    let (k, turn, shift) = (1000.0, 1.0f64, Vec2::new(-250.0, 4000.0));
    let (s, c) = turn.sin_cos();
    let map = |v: Vec2| shift + Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y) * k;
    let moved: Vec<Pose> = poses.iter().map(|p| Pose { point: map(p.point), angle: p.angle + turn }).collect();
    let other = burmester_points(&moved, &BurmesterConfig::default()).unwrap();
    assert_eq!(other.dyads.len(), base.dyads.len());
    for d in &base.dyads {
        let scale = other.size.max(k * d.radius());
        assert!(
            other.dyads.iter().any(|o| (o.center - map(d.center)).norm() < 1e-10 * scale
                && (o.circle - map(d.circle)).norm() < 1e-10 * scale)
        );
    }
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let (poses, _) = reference();
    let cfg = BurmesterConfig::default();
    assert!(matches!(center_point_curve(&poses, &cfg), Err(ClassicalError::Count { given: 5, .. })));
    assert!(matches!(center_point_curve(&poses[..3], &cfg), Err(ClassicalError::Count { given: 3, .. })));
    assert!(matches!(burmester_points(&poses[..4], &cfg), Err(ClassicalError::Count { given: 4, .. })));
    assert!(matches!(burmester_points(&[], &cfg), Err(ClassicalError::Count { given: 0, .. })));
    for bad in [f64::NAN, f64::INFINITY] {
        let mut p = poses.clone();
        p[2].point.y = bad;
        assert!(matches!(burmester_points(&p, &cfg), Err(ClassicalError::NonFinite { .. })));
        assert!(matches!(center_point_curve(&p[..4], &cfg), Err(ClassicalError::NonFinite { .. })));
    }
    let mut same = poses.clone();
    same[4] = same[1];
    assert_eq!(
        burmester_points(&same, &cfg),
        Err(ClassicalError::Coincident { what: "poses", first: 1, second: 4 }).map(|_: ()| unreachable!())
    );
    assert!(matches!(center_point_curve(&poses[..4], &cfg.samples(3)), Err(ClassicalError::BadRange { .. })));
    // More samples than memory holds: an error, not a capacity-overflow panic.
    for huge in [usize::MAX, usize::MAX / 2 + 1] {
        let e = center_point_curve(&poses[..4], &cfg.samples(huge)).unwrap_err();
        assert!(matches!(&e, ClassicalError::BadRange { why, .. } if why.contains("too many")), "{e:?}");
        let e = burmester_points(&poses, &cfg.samples(huge)).unwrap_err();
        assert!(matches!(&e, ClassicalError::BadRange { why, .. } if why.contains("too many")), "{e:?}");
    }
    // Counts memory could hold but no run would finish: refused before the poses are looked
    // at (a trillion samples passed, and ran practically forever).
    for absurd in [crate::analysis::MAX_SAMPLES + 1, 1 << 40] {
        let e = center_point_curve(&poses[..3], &cfg.samples(absurd)).unwrap_err();
        assert!(matches!(&e, ClassicalError::BadRange { why, .. } if why.contains("at most")), "{e:?}");
        let e = burmester_points(&poses[..3], &cfg.samples(absurd)).unwrap_err();
        assert!(matches!(&e, ClassicalError::BadRange { why, .. } if why.contains("at most")), "{e:?}");
    }
    // Poses 2 and 4 both turned about one point from pose 1: a shared pole.
    let q = Vec2::new(2.0, 1.0);
    let about = |a: f64| {
        let (s, c) = a.sin_cos();
        let r = Vec2::new(0.0, 0.0) - q;
        Pose { point: q + Vec2::new(c * r.x - s * r.y, s * r.x + c * r.y), angle: a }
    };
    let shared = [about(0.0), about(0.5), Pose::new(1.0, 3.0, 0.9), about(1.2)];
    assert!(matches!(center_point_curve(&shared, &cfg), Err(ClassicalError::Degenerate(_))));
}

/// `reference/burmester_random.csv`: twelve problems of five poses made by no linkage, with
/// mpmath's Burmester pairs of each.
#[allow(clippy::type_complexity)]
fn random_problems() -> Vec<(Vec<Pose>, Vec<(Vec2, Vec2)>)> {
    let mut problems: Vec<(Vec<Pose>, Vec<(Vec2, Vec2)>)> = Vec::new();
    for line in include_str!("../reference/burmester_random.csv").lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let i: usize = f[0].parse().unwrap();
        if problems.len() <= i {
            problems.push((vec![], vec![]));
        }
        let v = |k: usize| f[k].parse::<f64>().unwrap();
        match f[1] {
            "pose" => problems[i].0.push(Pose::new(v(2), v(3), v(4))),
            _ => problems[i].1.push((Vec2::new(v(2), v(3)), Vec2::new(v(4), v(5)))),
        }
    }
    problems
}

/// Problems with none, two and four Burmester points, many with gaps where the first
/// compatibility linkage cannot close (so that the search crosses its folds): the same pairs
/// as the reference, every one keeping its circle.
#[test]
fn random_five_pose_problems_give_the_reference_burmester_pairs() {
    let problems = random_problems();
    assert_eq!(problems.len(), 12);
    let mut folds = 0;
    for (i, (poses, pairs)) in problems.iter().enumerate() {
        let first = Compatibility::new(poses, [1, 2, 3]).unwrap();
        folds += usize::from((0..720).any(|k| first.closures(k as f64 * TAU / 720.0)[0].is_none()));
        let found = burmester_points(poses, &BurmesterConfig::default()).unwrap();
        assert_eq!(found.dyads.len(), pairs.len(), "problem {i}: {found:?} vs {pairs:?}");
        assert!(found.max_deviation <= DEVIATION, "problem {i}: {:e}", found.max_deviation);
        for (center, circle) in pairs {
            let hit = found.dyads.iter().find(|d| {
                let scale = found.size.max(d.radius());
                (d.center - *center).norm() <= 1e-10 * scale && (d.circle - *circle).norm() <= 1e-10 * scale
            });
            assert!(hit.is_some(), "problem {i}: {center:?} not among {:?}", found.dyads);
        }
    }
    assert!(folds >= 6, "{folds}");
}

/// A Burmester point with a long crank turns it nearly as the body turns (a far circle point is
/// carried nearly as a point of the body), or hardly at all (a far center point: the crank
/// nearly slides): its `beta_2` lies next to the body's own rotation or to zero. Both of those
/// satisfy the compatibility conditions without giving a dyad, and within one sample step of
/// such a solution the second condition's residual vanishes twice and keeps its sign across the
/// step. The references: mpmath's 40-digit solutions of the Cartesian conditions
/// `|k_j - M| = |k_1 - M|` (Newton from many random starts, independent of the rotations).
#[test]
fn burmester_points_next_to_the_degenerate_rotations_are_found() {
    // A crank 18 times the problem's size turning 22.81 degrees to the second pose, the body
    // 22.92 (0.4 rad); and another 18 times the size turning 0.39 degrees.
    let problems = [
        (
            [(0.0, 0.0, 0.0), (1.0, 0.3, 0.4), (1.8, 1.1, 0.9), (2.1, 2.2, 1.6), (2.0, 3.0, 2.0)],
            vec![
                (Vec2::new(-0.1906444455094678, 2.3014434632447087), Vec2::new(2.6904612613342547, 68.09073833989245)),
                (
                    Vec2::new(-0.10524526529716793, 2.155663407246796),
                    Vec2::new(-0.24635339402304407, 2.692007219303523),
                ),
            ],
        ),
        (
            [
                (0.246, 1.748, 0.581),
                (3.224, 3.933, 0.273),
                (2.186, 3.787, 1.119),
                (3.514, 3.164, 0.196),
                (1.726, 2.383, 1.193),
            ],
            vec![
                (
                    Vec2::new(0.4874620627371702, 1.9192866486395948),
                    Vec2::new(-0.4507006413118078, 0.32042525284926204),
                ),
                (Vec2::new(1.3751658348056557, -5.539186254558906), Vec2::new(-1.8821029845804051, -6.661557155203552)),
                (Vec2::new(2.9530044322454647, 4.709988590246466), Vec2::new(0.874543287225142, 4.2223544070955334)),
                (Vec2::new(70.08104775592834, -38.053531565778655), Vec2::new(10.178178212847563, -7.214423349269937)),
            ],
        ),
    ];
    for (i, (poses, pairs)) in problems.iter().enumerate() {
        let poses = poses.map(|(x, y, a)| Pose::new(x, y, a));
        let found = burmester_points(&poses, &BurmesterConfig::default()).unwrap();
        assert_eq!(found.dyads.len(), pairs.len(), "problem {i}: {found:?}");
        assert!(found.max_deviation <= DEVIATION, "problem {i}: {:e}", found.max_deviation);
        for (center, circle) in pairs {
            let hit = found.dyads.iter().any(|d| {
                let scale = found.size.max(d.radius());
                (d.center - *center).norm() <= 1e-10 * scale && (d.circle - *circle).norm() <= 1e-10 * scale
            });
            assert!(hit, "problem {i}: {center:?} not among {:?}", found.dyads);
        }
    }
}

/// Five poses of a body turning about one point (the origin: every pole is there) are
/// degenerate at every size, and found so whatever the size: the minors of the compatibility
/// condition were compared with one another, all rounding, and the same poses gave an error, 1
/// dyad, 3 or 809 by the size they were written in. Beyond the range of doubles (the distance
/// between two poses overflows) the error says so, where it said "a pole in common".
#[test]
fn poses_turning_about_one_point_are_degenerate_at_every_size() {
    let cfg = BurmesterConfig::default();
    for size in [1e-300, 1e-9, 1.0, 3.0, 1e9, 1e100, 1e200, 1e300, 5e307] {
        let poses: Vec<Pose> = (0..5)
            .map(|k| {
                let a = 0.3 * k as f64;
                Pose::new(size * a.cos(), size * a.sin(), a)
            })
            .collect();
        let e = burmester_points(&poses, &cfg).unwrap_err();
        assert!(matches!(&e, ClassicalError::Degenerate(why) if why.contains("a pole in common")), "{size:e}: {e:?}");
    }
    let on_line = |size: f64| (0..5).map(move |k| Pose::new(size * (0.3 * k as f64).cos(), 0.0, 0.3 * k as f64));
    let poses: Vec<Pose> = on_line(f64::MAX).map(|p| Pose { point: Vec2::new(-p.point.x, 0.0), ..p }).collect();
    let far = [poses[0], poses[1], poses[2], poses[3], Pose { point: Vec2::new(f64::MAX, 0.0), ..poses[4] }];
    let e = burmester_points(&far, &cfg).unwrap_err();
    assert!(
        matches!(&e, ClassicalError::Degenerate(why) if why.contains("farther apart than a double holds")),
        "{e:?}"
    );
    // Within doubles, a pair whose crank hardly turns has its pivots beyond them: refused, not
    // returned with NaN pivots. At size 1 its pivots are finite, and every pair found.
    let e = burmester_points(&on_line(f64::MAX).collect::<Vec<_>>(), &cfg).unwrap_err();
    assert!(
        matches!(&e, ClassicalError::NonFinite { what, .. } if what.contains("beyond the range of doubles")),
        "{e:?}"
    );
    let found = burmester_points(&on_line(1.0).collect::<Vec<_>>(), &cfg).unwrap();
    assert!(found.dyads.iter().all(|d| d.center.x.is_finite() && d.circle.y.is_finite()), "{found:?}");
}
