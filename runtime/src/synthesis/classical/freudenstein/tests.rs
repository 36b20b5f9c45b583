//! Freudenstein's equation against independent references: mpmath's 50-digit solution of the
//! same system (`reference/generate.py`), a forward analysis of the synthesised linkage by
//! intersecting circles (and mpmath's, by Newton on the loop equations), and known linkages
//! whose sampled angles must give their lengths back.

use super::*;
use crate::deg;
use crate::synthesis::classical::{FunctionMap, chebyshev_points, structural_error};

/// `reference/freudenstein_log10.csv`: `case,name,value`.
fn reference(case: &str, name: &str) -> f64 {
    include_str!("../reference/freudenstein_log10.csv")
        .lines()
        .find_map(|l| {
            let mut f = l.split(',');
            (f.next() == Some(case) && f.next() == Some(name)).then(|| f.next().unwrap().parse().unwrap())
        })
        .unwrap_or_else(|| panic!("no reference {case} {name}"))
}

/// The reference's ranges: log10 over 1 ..= 2 onto phi = 60 + 90 (x - 1) degrees and
/// psi = 90 + 90 log10(x) / log10(2) degrees.
fn log10_map() -> FunctionMap {
    FunctionMap::new(f64::log10, 1.0, 2.0, deg(60.0), deg(90.0), deg(90.0), deg(90.0)).unwrap()
}

/// Relative agreement of a double computation with a 17-digit reference of a well-conditioned
/// 3x3 system (reciprocal condition number about 1e-2 here): a few hundred roundings.
const REL: f64 = 1e-13;

#[test]
fn log10_at_three_chebyshev_points_matches_the_50_digit_solution() {
    let map = log10_map();
    let xs = chebyshev_points(3, 1.0, 2.0).unwrap();
    for (i, x) in xs.iter().enumerate() {
        assert!((x - reference("exact", &format!("x{i}"))).abs() < 1e-15);
    }
    let points = map.precision_points(f64::log10, &xs).unwrap();
    let g = freudenstein(&points).unwrap();
    for (i, k) in g.k.iter().enumerate() {
        let r = reference("exact", &format!("k{}", i + 1));
        assert!((k - r).abs() <= REL * r.abs(), "K{}: {k} vs {r}", i + 1);
    }
    let l = g.links;
    for (value, name) in [(l.input, "input"), (l.coupler, "coupler"), (l.output, "output")] {
        let r = reference("exact", name);
        assert!((value - r).abs() <= REL * r, "{name}: {value} vs {r}");
    }
    assert_eq!(l.ground, 1.0);
    assert!(g.residual < 1e-15 && g.max_residual < 1e-15, "{g:?}");
    assert!(g.one_closure);
    // Forward analysis by intersecting circles reaches every precision point.
    for p in &points {
        let e = g.output_error(*p).unwrap();
        assert!(e.abs() < 1e-12, "{p:?}: {e:e}");
    }
}

/// The linkage's output between the points, by intersecting circles here and by Newton on the
/// loop equations in the reference, and the structural error it makes.
#[test]
fn log10_structural_error_matches_the_reference_analysis() {
    let map = log10_map();
    let points = map.precision_points(f64::log10, &chebyshev_points(3, 1.0, 2.0).unwrap()).unwrap();
    let g = freudenstein(&points).unwrap();
    let mut worst: f64 = 0.0;
    for j in 0..=10 {
        let x = 1.0 + j as f64 / 10.0;
        let psi = g.output_angle(map.phi(x)).unwrap();
        let r = reference("exact", &format!("psi_at_{j}"));
        assert!(angle_difference(psi, r).abs() < 1e-12, "x {x}: {psi} vs {r}");
        worst = worst.max((r - map.psi(x.log10())).abs());
    }
    let e = structural_error(&g, &map, f64::log10, 11).unwrap();
    assert_eq!((e.samples, e.unassembled), (11, 0));
    assert!((e.max - worst).abs() < 1e-12, "{} vs {worst}", e.max);
    // A finer sampling finds no larger error than the reference's grid: the largest is at the
    // end x = 1 (0.886 degrees of output, 0.0030 in y), which both grids hold.
    let fine = structural_error(&g, &map, f64::log10, 1001).unwrap();
    assert!((fine.max - e.max).abs() < 1e-15 && fine.at_x == 1.0, "{fine:?}");
    assert!((fine.max_y - fine.max * 2f64.log10() / deg(90.0)).abs() < 1e-15);
}

#[test]
fn log10_least_squares_over_six_points_matches_the_50_digit_solution() {
    let map = log10_map();
    let xs: Vec<f64> = (0..6).map(|j| reference("least_squares", &format!("x{j}"))).collect();
    let g = freudenstein(&map.precision_points(f64::log10, &xs).unwrap()).unwrap();
    for (i, k) in g.k.iter().enumerate() {
        let r = reference("least_squares", &format!("k{}", i + 1));
        assert!((k - r).abs() <= REL * r.abs(), "K{}: {k} vs {r}", i + 1);
    }
    let norm = reference("least_squares", "residual_norm");
    assert!((g.residual * 6f64.sqrt() - norm).abs() <= 1e-12 * norm, "{} vs {norm}", g.residual);
    for j in 0..=10 {
        let x = 1.0 + j as f64 / 10.0;
        let r = reference("least_squares", &format!("psi_at_{j}"));
        assert!(angle_difference(g.output_angle(map.phi(x)).unwrap(), r).abs() < 1e-12, "x {x}");
    }
}

/// Angles sampled from a known linkage (by intersecting circles) give its lengths back, on
/// either closure, exactly from three points and with a rounding-level residual from eight.
#[test]
fn a_known_linkage_is_recovered_from_its_own_angles() {
    let known = FourBarLinks { ground: 1.0, input: 0.45, coupler: 1.3, output: 0.9 };
    let frame = Frame { links: known };
    for closure in [Closure::CounterClockwise, Closure::Clockwise] {
        for phis in [vec![0.3, 1.1, 2.0], (0..8).map(|k| 0.2 + 0.35 * k as f64).collect()] {
            let points: Vec<PrecisionPoint> = phis
                .iter()
                .map(|&phi| PrecisionPoint { phi, psi: frame.output_angle(phi, closure).unwrap() })
                .collect();
            let g = freudenstein(&points).unwrap();
            let l = g.links;
            for (got, want) in [(l.input, 0.45), (l.coupler, 1.3), (l.output, 0.9)] {
                assert!((got - want).abs() < 1e-12, "{closure:?} {}: {got} vs {want}", phis.len());
            }
            assert_eq!(g.closure, closure);
            assert!(g.one_closure && g.max_residual < 1e-14, "{g:?}");
        }
    }
}

/// The lengths are for a ground of one: `scaled` multiplies them all.
#[test]
fn scaled_multiplies_every_length() {
    let map = log10_map();
    let g = freudenstein(&map.precision_points(f64::log10, &[1.1, 1.5, 1.9]).unwrap()).unwrap();
    let s = g.scaled(250.0);
    assert_eq!(s.ground, 250.0);
    assert!((s.input - 250.0 * g.links.input).abs() < 1e-12);
    assert!((s.coupler - 250.0 * g.links.coupler).abs() < 1e-12);
    assert!((s.output - 250.0 * g.links.output).abs() < 1e-12);
}

/// Points met only on the other closure are reported, not hidden.
#[test]
fn points_on_two_closures_are_a_branch_defect() {
    let frame = Frame { links: FourBarLinks { ground: 1.0, input: 0.45, coupler: 1.3, output: 0.9 } };
    let point = |phi, c| PrecisionPoint { phi, psi: frame.output_angle(phi, c).unwrap() };
    let g = freudenstein(&[
        point(0.3, Closure::CounterClockwise),
        point(1.1, Closure::Clockwise),
        point(2.0, Closure::CounterClockwise),
    ])
    .unwrap();
    assert!(!g.one_closure, "{g:?}");
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let p = |phi, psi| PrecisionPoint { phi, psi };
    let good = [p(0.3, 1.0), p(0.8, 1.4), p(1.3, 1.9)];
    assert!(matches!(freudenstein(&good[..2]), Err(ClassicalError::Count { given: 2, .. })));
    assert!(matches!(freudenstein(&[]), Err(ClassicalError::Count { given: 0, .. })));
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut points = good;
        points[1].psi = bad;
        assert!(matches!(freudenstein(&points), Err(ClassicalError::NonFinite { .. })));
    }
    let same = [good[0], good[1], p(0.3 + std::f64::consts::TAU, 1.0)];
    assert_eq!(freudenstein(&same), Err(ClassicalError::Coincident { what: "precision points", first: 0, second: 2 }));
    // Same input angle, output angles of the same cosine: two equal rows.
    let singular = [p(0.5, 0.7), p(0.5, -0.7), p(1.2, 0.3)];
    assert!(matches!(freudenstein(&singular), Err(ClassicalError::Singular { .. })), "{:?}", freudenstein(&singular));
    // The log10 design with every input angle turned half a turn: a negative input length.
    let map = log10_map();
    let mut turned = map.precision_points(f64::log10, &[1.1, 1.5, 1.9]).unwrap();
    turned.iter_mut().for_each(|q| q.phi += std::f64::consts::PI);
    assert!(matches!(freudenstein(&turned), Err(ClassicalError::BadLength { link: "input", .. })));
    let mut turned = map.precision_points(f64::log10, &[1.1, 1.5, 1.9]).unwrap();
    turned.iter_mut().for_each(|q| q.psi += std::f64::consts::PI);
    assert!(matches!(freudenstein(&turned), Err(ClassicalError::BadLength { link: "output", .. })));
    // Ratios whose coupler would be imaginary (not reachable from three real points).
    assert!(matches!(lengths([1.0, 1.0, 5.0]), Err(ClassicalError::BadLength { link: "coupler", .. })));
    assert!(matches!(lengths([0.0, 1.0, 0.5]), Err(ClassicalError::BadLength { link: "input", .. })));
}

/// Input 0.75, coupler 0.5, output 0.75 (ground 1): at `phi = 90` degrees `|B - D| = 1.25 =
/// b + c`, so the coupler and the output lie in line (`C = (0.4, 0.45)`, the input at the end
/// of its travel, both closures the same position). The other points, at smaller input angles,
/// are on one closure: that is the linkage's, whichever it is, and every point lies on it.
#[test]
fn a_first_point_with_coupler_and_output_in_line_takes_the_closure_of_the_others() {
    use std::f64::consts::FRAC_PI_2;
    let known = FourBarLinks { ground: 1.0, input: 0.75, coupler: 0.5, output: 0.75 };
    let frame = Frame { links: known };
    // The toggle position in closed form: C on B-D at b from B.
    let toggle = PrecisionPoint { phi: FRAC_PI_2, psi: 0.45f64.atan2(-0.6) };
    assert!(((frame.c(toggle.psi) - frame.b(toggle.phi)).norm() - 0.5).abs() < 1e-15);
    for closure in [Closure::CounterClockwise, Closure::Clockwise] {
        let point = |phi| PrecisionPoint { phi, psi: frame.output_angle(phi, closure).unwrap() };
        for points in [
            vec![toggle, point(FRAC_PI_2 - 0.4), point(FRAC_PI_2 - 0.8)],
            vec![toggle, point(FRAC_PI_2 - 0.3), point(FRAC_PI_2 - 0.7), point(FRAC_PI_2 - 1.1)],
            // In line at a later point: no branch defect either.
            vec![point(FRAC_PI_2 - 0.8), toggle, point(FRAC_PI_2 - 0.4)],
        ] {
            let g = freudenstein(&points).unwrap();
            for (got, want) in [(g.links.input, 0.75), (g.links.coupler, 0.5), (g.links.output, 0.75)] {
                assert!((got - want).abs() < 1e-12, "{closure:?}: {got} vs {want}");
            }
            assert_eq!(g.closure, closure, "{} points", points.len());
            assert!(g.one_closure, "{g:?}");
            for p in &points {
                // At the limit position the circles touch: the output angle moves as the square
                // root of the lengths' rounding there (about 1e-8 rad), as the first power
                // elsewhere.
                let tolerance = if *p == toggle { 1e-6 } else { 1e-12 };
                assert!(g.output_error(*p).unwrap().abs() < tolerance, "{closure:?} {p:?}");
            }
        }
    }
}

/// No precision point with a closure: an error naming why, not a closure picked by default.
#[test]
fn a_closure_undetermined_at_every_point_is_an_error() {
    let (ccw, cw) = (Some(Closure::CounterClockwise), Some(Closure::Clockwise));
    assert_eq!(common_closure(&[None, cw, ccw]), Ok((Closure::Clockwise, false)));
    assert_eq!(common_closure(&[None, ccw, None, ccw]), Ok((Closure::CounterClockwise, true)));
    let e = common_closure(&[None, None, None]).unwrap_err();
    assert!(
        matches!(e, ClassicalError::Degenerate(ref why) if why.contains("in line at every precision point")),
        "{e}"
    );
}
