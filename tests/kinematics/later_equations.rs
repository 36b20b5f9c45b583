//! Blocks solved directly (by one division, or one linear solve) whose unknowns enter later
//! equations nonlinearly: `y == sin(x)` after `x == a phi` puts `-cos x` in the column of `x`,
//! a scale known only once `x` is solved. The generated code referred to `x` before solving it
//! and did not compile. Each mechanism against its closed form: positions to the rounding of a
//! solve, the analogs against central differences of the closed form (each declared twice, the
//! second with `#[kinloop(newton)]`).

use crate::support::{richardson, tol};

with_newton_twin! {
    /// `x` by one division, then `y` by one division of a sine of it.
    pub struct SineAfter, SineAfterNewton {
        params a = 0.7;
        input phi;
        unknowns x = 0, y = 0;
        eq e1: x == a * phi;
        eq e2: y == sin(x);
    }
}

with_newton_twin! {
    /// `x` by a linear solve (its coefficient varies with the input), then `y` of a sine of it:
    /// the column of `x` scaled by `cos x`, so `x` is solved by Newton.
    pub struct ScaledAfter, ScaledAfterNewton {
        params a = 0.7;
        input phi;
        unknowns x = 0, y = 0;
        eq e1: (2 + phi * phi) * x == a * phi;
        eq e2: y == sin(x);
    }
}

with_newton_twin! {
    /// An offset slider-crank, the ratio `g = d / x` of its slider's position, and an equation
    /// that divides by the slider: the rod by a closed form or Newton, the slider, `g` and `y`
    /// directly.
    pub struct SliderRatio, SliderRatioNewton {
        params r = 1.0, l = 3.0, e = 0.4, d = 2.0;
        input phi;
        unknowns psi = 0, x = 4, g = 0.5, y = 0;
        loop abc: r @ phi + l @ psi == (x, e);
        eq ratio: g * x == d;
        eq div: r * sin(phi) == y + phi / x;
    }
}

/// `f(phi)` and its first and second derivatives against a state's value and analogs.
fn check(name: &str, phi: f64, value: f64, d1: f64, d2: f64, f: impl Fn(f64) -> f64) {
    let (fd1, fd2) = richardson(&f, phi, 1e-3);
    assert_close!(value, f(phi), rel = tol::SOLVE, "{name} at {phi}");
    assert_close!(d1, fd1, rel = tol::FD_FIRST, "{name}' at {phi}");
    assert_close!(d2, fd2, rel = tol::FD_SECOND, "{name}'' at {phi}");
}

#[test]
fn a_sine_of_an_unknown_solved_before() {
    let a = 0.7;
    let x = |phi: f64| a * phi;
    for phi in [-2.0, -0.3, 0.0, 0.4, 1.9] {
        let s = SineAfter { a }.solve(phi).unwrap();
        check("x", phi, s.q.x, s.dq.x, s.d2q.x, x);
        check("y", phi, s.q.y, s.dq.y, s.d2q.y, |p| x(p).sin());
        let n = SineAfterNewton { a }.solve(phi).unwrap();
        check("y (newton)", phi, n.q.y, n.dq.y, n.d2q.y, |p| x(p).sin());
    }
}

#[test]
fn a_linear_block_scaled_by_a_later_equation_is_solved_by_newton() {
    let a = 0.7;
    let x = |phi: f64| a * phi / (2.0 + phi * phi);
    for phi in [-2.0, -0.3, 0.0, 0.4, 1.9] {
        let s = ScaledAfter { a }.solve(phi).unwrap();
        check("x", phi, s.q.x, s.dq.x, s.d2q.x, x);
        check("y", phi, s.q.y, s.dq.y, s.d2q.y, |p| x(p).sin());
        let n = ScaledAfterNewton { a }.solve(phi).unwrap();
        check("y (newton)", phi, n.q.y, n.dq.y, n.d2q.y, |p| x(p).sin());
    }
    assert!(ScaledAfter::DECOMPOSITION.contains("Newton"), "{}", ScaledAfter::DECOMPOSITION);
}

#[test]
fn a_slider_its_ratio_and_a_division_by_it() {
    let (r, l, e, d) = (1.0, 3.0, 0.4, 2.0);
    // The rod's angle on the slider's side of the guess (cos psi > 0), the slider's position.
    let x = move |phi: f64| {
        let s = (e - r * phi.sin()) / l;
        r * phi.cos() + l * (1.0 - s * s).sqrt()
    };
    for phi in [-2.0, -0.3, 0.0, 0.4, 1.9] {
        let s = SliderRatio { r, l, e, d }.solve(phi).unwrap();
        check("x", phi, s.q.x, s.dq.x, s.d2q.x, x);
        check("g", phi, s.q.g, s.dq.g, s.d2q.g, |p| d / x(p));
        check("y", phi, s.q.y, s.dq.y, s.d2q.y, |p| r * p.sin() - p / x(p));
        let n = SliderRatioNewton { r, l, e, d }.solve(phi).unwrap();
        check("g (newton)", phi, n.q.g, n.dq.g, n.d2q.g, |p| d / x(p));
        check("y (newton)", phi, n.q.y, n.dq.y, n.d2q.y, |p| r * p.sin() - p / x(p));
    }
}
