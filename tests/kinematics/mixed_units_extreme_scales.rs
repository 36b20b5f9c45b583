//! The distance to a singular position that sweeps judge by (`Health::min_pivot`, the smallest
//! pivot ratio of the analogs' factorisations) is the same in every unit of length, also where
//! an unknown is read by equations of different units: a loop's projections (lengths) and an
//! equation between angles (a gear's ratio, no unit). The located limit positions are too.
//!
//! The Jacobian column of such an unknown holds entries of two units: `-c sin(gamma)` in the
//! loop's rows, `-2` in the gear's. Divided by their largest, as the column-equilibrated
//! factorisation divides them, the loop's entries came out `k` times smaller in a mechanism `k`
//! times smaller: at `k = 1e-9` the measure was `1.8e-9` where it is `1.0` at `k = 1` (no
//! singular position near), and a sweep stopped there as near a singular one.

use kinloop::mechanism;

mechanism! {
    /// A four-bar whose rocker drives a gear pair of ratio 2: the rocker angle `gamma` is solved
    /// with the coupler's in the loop, and read again by the gear's equation.
    pub struct GearedRocker {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, th3 = 3.0;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        eq g: th3 == 2 * gamma;
    }
}

/// Sizes from far below to far above a metre.
const SIZES: [f64; 7] = [1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9];

/// The pivot ratios of two sizes agree to the rounding of their entries: each is a few products
/// and quotients of entries rounded to half an ulp, so a few hundred ulps relatively.
fn same_pivot(p: f64, at_one: f64) -> bool {
    (p - at_one).abs() <= 1e-13 * at_one
}

#[test]
fn a_rocker_read_by_a_gear_is_as_far_from_singular_in_every_unit() {
    let at = |k: f64| GearedRocker { a: k, b: 3.5 * k, c: 3.0 * k, d: 4.0 * k };
    let guess = GearedRockerUnknowns { beta: 0.5, gamma: 1.5, th3: 3.0 };
    let one = at(1.0).kinematics(0.5, &guess).expect("assembles at size 1");
    assert!(one.health.min_pivot > 0.1, "no singular position near: {:e}", one.health.min_pivot);
    for k in SIZES {
        let m = at(k);
        let s = m.kinematics(0.5, &guess).expect("assembles at every size");
        assert!(same_pivot(s.health.min_pivot, one.health.min_pivot), "{k:e}: {:e}", s.health.min_pivot);
        let r = m.sweep(0.5, 0.6, 11, &guess).expect("a sweep").run();
        assert!(r.is_completed(), "{k:e}: {:?}", r.stop);
        assert!((r.states[10].q.gamma - at(1.0).kinematics(0.6, &guess).unwrap().q.gamma).abs() < 1e-14);
    }
}

/// A non-Grashof geared rocker swung to its limit positions: the sweep stops at the same one,
/// and the traced curve turns at both, at every size as at size 1 (to `1e-12`, what the
/// continuation's tolerance pins a located limit position to).
#[test]
fn a_geared_rocker_meets_its_limit_positions_alike_in_every_unit() {
    let at = |k: f64| GearedRocker { a: 3.0 * k, b: 2.0 * k, c: 3.0 * k, d: 4.5 * k };
    let guess = GearedRockerUnknowns { beta: 0.5, gamma: 1.5, th3: 3.0 };
    let limits = |k: f64| {
        let m = at(k);
        let r = m.sweep(0.3, 3.0, 200, &guess).expect("a sweep").run();
        let stop: Vec<f64> = r.events.iter().map(|e| e.x[0]).collect();
        let t = m.trace_curve(0.3, 3.0, &guess, &kinloop::TraceConfig::default()).expect("a traced curve");
        let folds: Vec<f64> = t.folds.iter().map(|e| e.x[0]).collect();
        (stop, folds)
    };
    let (stop, folds) = limits(1.0);
    assert_eq!((stop.len(), folds.len()), (1, 2), "{stop:?} {folds:?}");
    for k in SIZES {
        let (s, f) = limits(k);
        let alike = |a: &[f64], b: &[f64]| a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
        assert!(alike(&s, &stop) && alike(&f, &folds), "{k:e}: {s:?} {f:?}");
    }
}
