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

mechanism! {
    /// A geared five-bar: its two rocker angles are tied by a gear pair of ratio 2, so the loop
    /// and the gear's equation are one block of three unknowns whose rows have two units.
    pub struct GearedFiveBar {
        params a, b, c, d, e;
        input th1;
        unknowns phi2 = 1.0, th2 = 0.8, phi3 = 1.6;
        loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3;
        eq gear: phi3 == 2 * th2;
    }
}

mechanism! {
    /// Eight four-bars closed into a ring through a gear pair: the last rocker turns the first
    /// crank's gear at half its angle. One block of 17 unknowns, factorised sparse, whose rows
    /// have two units.
    pub struct GearedRing {
        params a, b, c, d;
        input phi;
        unknowns
            u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
            u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9, w = 0.95;
        loop l0: a @ (0.5 * (phi + w)) + b @ u0 == (d, 0) + c @ v0;
        loop l1: a @ v0 + b @ u1 == (d, 0) + c @ v1;
        loop l2: a @ v1 + b @ u2 == (d, 0) + c @ v2;
        loop l3: a @ v2 + b @ u3 == (d, 0) + c @ v3;
        loop l4: a @ v3 + b @ u4 == (d, 0) + c @ v4;
        loop l5: a @ v4 + b @ u5 == (d, 0) + c @ v5;
        loop l6: a @ v5 + b @ u6 == (d, 0) + c @ v6;
        loop l7: a @ v6 + b @ u7 == (d, 0) + c @ v7;
        eq gear: w == 0.5 * v7;
    }
}

/// Sizes from far below to far above a metre.
const SIZES: [f64; 7] = [1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9];

/// The pivot ratios of two sizes agree to the rounding of their entries: each is a few products
/// and quotients of entries rounded to half an ulp, so a few hundred ulps relatively.
fn same_pivot(p: f64, at_one: f64) -> bool {
    (p - at_one).abs() <= 1e-13 * at_one
}

/// At every size of [`SIZES`], the mechanism `$at(k)` solved from `$guess` at the input 0.5 has
/// the smallest pivot ratio of size 1 (which is above `$floor`: no singular position near), and
/// its sweep to 0.6 completes.
macro_rules! alike_in_every_unit {
    ($at:expr, $guess:expr, $floor:expr) => {{
        let (at, guess) = ($at, $guess);
        let one = at(1.0).kinematics(0.5, &guess).expect("assembles at size 1").health.min_pivot;
        assert!(one > $floor, "a singular position near: {one:e}");
        for k in SIZES {
            let m = at(k);
            let pivot = m.kinematics(0.5, &guess).expect("assembles at every size").health.min_pivot;
            assert!(same_pivot(pivot, one), "{k:e}: {pivot:e}");
            let r = m.sweep(0.5, 0.6, 11, &guess).expect("a sweep").run();
            assert!(r.is_completed(), "{k:e}: {:?}", r.stop);
        }
    }};
}

#[test]
fn a_rocker_read_by_a_gear_is_as_far_from_singular_in_every_unit() {
    let at = |k: f64| GearedRocker { a: k, b: 3.5 * k, c: 3.0 * k, d: 4.0 * k };
    let guess = GearedRockerUnknowns { beta: 0.5, gamma: 1.5, th3: 3.0 };
    alike_in_every_unit!(at, guess, 0.1);
    // The angles themselves were right at every size before as now.
    let gamma = at(1.0).kinematics(0.6, &guess).unwrap().q.gamma;
    for k in SIZES {
        assert!((at(k).kinematics(0.6, &guess).unwrap().q.gamma - gamma).abs() < 1e-14, "{k:e}");
    }
}

#[test]
fn a_loop_and_a_gear_in_one_block_are_as_far_from_singular_in_every_unit() {
    let at = |k: f64| GearedFiveBar { a: k, b: 2.5 * k, c: 2.2 * k, d: 1.5 * k, e: 1.2 * k };
    alike_in_every_unit!(at, GearedFiveBarUnknowns { phi2: 1.0, th2: 0.8, phi3: 1.6 }, 0.1);
}

#[test]
fn a_sparse_block_of_loops_and_a_gear_is_as_far_from_singular_in_every_unit() {
    let at = |k: f64| GearedRing { a: k, b: 3.0 * k, c: 2.5 * k, d: 3.2 * k };
    // Every coupler at 0.6 and rocker at 1.9, the gear's angle half the last rocker's.
    let mut guess = [0.6, 1.9].repeat(8);
    guess.push(0.95);
    let guess = GearedRingUnknowns::from(<[f64; 17]>::try_from(guess).expect("17 unknowns"));
    alike_in_every_unit!(at, guess, 0.01);
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
