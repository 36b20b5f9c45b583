//! A loop whose lengths are all zero (parameters left at zero, as unset ones are) in every path that solves it: a closed-form block (the four-bar's dyad), a Newton block
//! (its Newton twin, and the class IV group's coupled block), the positions alone, a sweep.
//! Its equations hold at every position, so they determine none, and the error says that the
//! loop's lengths are all zero, which loop, and what to write instead: an invalid argument,
//! not the singular position ("a dead centre or a limit position") that every one of these
//! paths reported. Lengths that are tiny but not zero (`1e-200`) are a mechanism that solves,
//! as it solved before.

use kinloop::{Error, Mechanism, NewtonConfig};
use kinloop_fixtures::class_four::{ClassFour, ClassFourDense};
use kinloop_fixtures::linkages::FourBar;

with_newton_twin! {
    /// The fixtures' four-bar, declared again beside its Newton twin.
    pub struct ZeroFourBar, ZeroFourBarNewton {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

with_newton_twin! {
    /// Two four-bars in a chain, the second driven by the first's rocker: loop `second`'s
    /// lengths may be zero while loop `first` is a working four-bar.
    pub struct Chain, ChainNewton {
        params a, b, c, d, e, f, g, h;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, delta = 0.5, eps = 1.5;
        loop first: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop second: e @ gamma + f @ delta == (h, 0) + g @ eps;
    }
}

/// Asserts that `r` is the error of loop `name`'s lengths all zero: an invalid argument whose
/// message names the loop, says its links have length zero, and says what to do.
#[track_caller]
fn assert_zero_loop<T: std::fmt::Debug>(r: Result<T, Error>, name: &str, at: &str) {
    match r {
        Err(Error::InvalidArgument(m)) => {
            let says = format!("the links of loop `{name}` all have length zero");
            assert!(m.contains(&says), "{at}: {m}");
            assert!(m.contains("give the loop's lengths their values"), "{at}: {m}");
        }
        other => panic!("{at}: {other:?}"),
    }
}

/// The four-bar of lengths all zero, by its closed form and its Newton twin, for the analogs
/// (the checked step and the named `solve`), the positions alone, and a sweep's first sample,
/// at inputs and guesses of every quadrant. The closed form's dyad (links of zero on coincident
/// centres, every angle closing it) and the Newton block (a Jacobian of zero rows) both
/// reported the block's singular position; the sweep that it starts at a singular position.
#[test]
fn a_four_bar_of_zero_lengths_is_told_so() {
    let cfg = NewtonConfig::default();
    let (closed, newton) =
        (ZeroFourBar { a: 0.0, b: 0.0, c: 0.0, d: 0.0 }, ZeroFourBarNewton { a: 0.0, b: 0.0, c: 0.0, d: 0.0 });
    for phi in [0.0, 0.7, 2.5, -2.0] {
        for guess in [[0.5, 1.5], [-2.0, 3.0]] {
            let at = format!("phi {phi}, guess {guess:?}");
            assert_zero_loop(closed.kinematics_flat(&[phi], &guess, &cfg), "abcd", &format!("{at}, closed form"));
            assert_zero_loop(closed.position_flat(&[phi], &guess, &cfg), "abcd", &format!("{at}, closed form"));
            assert_zero_loop(newton.kinematics_flat(&[phi], &guess, &cfg), "abcd", &format!("{at}, Newton"));
            assert_zero_loop(newton.position_flat(&[phi], &guess, &cfg), "abcd", &format!("{at}, Newton"));
        }
    }
    // The fixtures' four-bar, by the named API.
    assert_zero_loop(FourBar { a: 0.0, b: 0.0, c: 0.0, d: 0.0 }.solve(0.3), "abcd", "FourBar::solve");
    let first = |m: &ZeroFourBarNewton| m.sweep(0.0, 1.0, 5, &m.guess(0.0)).and_then(|mut s| s.next().unwrap());
    assert_zero_loop(first(&newton), "abcd", "the sweep's first sample, Newton");
    let first = |m: &ZeroFourBar| m.sweep(0.0, 1.0, 5, &m.guess(0.0)).and_then(|mut s| s.next().unwrap());
    assert_zero_loop(first(&closed), "abcd", "the sweep's first sample, closed form");
}

/// The class IV group with every length zero (its two angles as declared): its block of four
/// unknowns is solved by Newton, decomposed and dense, and reported the singular position.
#[test]
fn a_class_four_group_of_zero_lengths_is_told_so() {
    let cfg = NewtonConfig::default();
    let z = 0.0;
    let blocked = ClassFour { oa: z, xb: z, yb: z, ac: z, ae: z, bd: z, bf: z, cd: z, ef: z, ..ClassFour::default() };
    let dense = ClassFourDense { oa: z, xb: z, yb: z, ac: z, ae: z, bd: z, bf: z, cd: z, ef: z, ..Default::default() };
    for phi in [0.0, 1.0, 4.0] {
        let at = format!("phi {phi}");
        let guess = blocked.guess_flat(&[phi]);
        // The first loop's first equation: every equation of both loops vanishes.
        assert_zero_loop(blocked.kinematics_flat(&[phi], &guess, &cfg), "acdb", &at);
        assert_zero_loop(blocked.position_flat(&[phi], &guess, &cfg), "acdb", &at);
        assert_zero_loop(dense.kinematics_flat(&[phi], &guess, &cfg), "acdb", &format!("{at}, dense"));
    }
}

/// Where only the second loop of a chain has lengths all zero, the error names that loop and
/// its block (the first solves), by the closed forms and by Newton.
#[test]
fn the_loop_whose_lengths_are_zero_is_named() {
    let cfg = NewtonConfig::default();
    let (a, b, c, d) = (1.0, 3.0, 2.5, 3.2);
    let (e, f, g, h) = (0.0, 0.0, 0.0, 0.0);
    let closed = Chain { a, b, c, d, e, f, g, h };
    let newton = ChainNewton { a, b, c, d, e, f, g, h };
    let guess = [0.5, 1.5, 0.5, 1.5];
    for r in [
        closed.kinematics_flat(&[0.7], &guess, &cfg).map(|_| ()),
        newton.kinematics_flat(&[0.7], &guess, &cfg).map(|_| ()),
    ] {
        assert_zero_loop(r.clone(), "second", "chain");
        let Err(Error::InvalidArgument(m)) = r else { unreachable!() };
        assert!(m.contains("(block 1: unknowns delta, eps; equations second.x, second.y)"), "{m}");
    }
}

/// Lengths that are tiny but not zero are no loop of zero lengths: the four-bar and the class IV
/// group with their lengths times `1e-200` (beyond the closed forms' sizes, solved by Newton over
/// the whole system) and `1e-150` solve, to the angles of size 1 within `1e-12` rad (the
/// residual tolerance, relative to the loop's size, as an angle: the solves at both sizes
/// stop within it), as they did before.
#[test]
fn tiny_lengths_are_not_zero() {
    let cfg = NewtonConfig::default();
    let (phi, guess) = (0.7, [0.5, 1.5]);
    let four_bar = |k: f64| ZeroFourBar { a: k, b: 3.0 * k, c: 2.5 * k, d: 3.2 * k };
    let four_bar_newton = |k: f64| ZeroFourBarNewton { a: k, b: 3.0 * k, c: 2.5 * k, d: 3.2 * k };
    let one = four_bar(1.0).position_flat(&[phi], &guess, &cfg).unwrap().0;
    let class_four = crate::degenerate_dyad_links::class_four_at;
    let g4 = ClassFour::default().guess_flat(&[phi]);
    let one4 = class_four(1.0).position_flat(&[phi], &g4, &cfg).unwrap().0;
    for k in [1e-150, 1e-200] {
        for q in [
            four_bar(k).kinematics_flat(&[phi], &guess, &cfg).map(|s| s.q),
            four_bar_newton(k).kinematics_flat(&[phi], &guess, &cfg).map(|s| s.q),
        ] {
            let q = q.unwrap_or_else(|e| panic!("four-bar, size {k:e}: {e}"));
            for (u, (got, want)) in q.iter().zip(one).enumerate() {
                assert!((got - want).abs() <= 1e-12, "four-bar, size {k:e}, unknown {u}: {got} against {want}");
            }
        }
        let q =
            class_four(k).kinematics_flat(&[phi], &g4, &cfg).unwrap_or_else(|e| panic!("class IV, size {k:e}: {e}")).q;
        for (u, (got, want)) in q.iter().zip(one4).enumerate() {
            assert!((got - want).abs() <= 1e-12, "class IV, size {k:e}, unknown {u}: {got} against {want}");
        }
    }
}
