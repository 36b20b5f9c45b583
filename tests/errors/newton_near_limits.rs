//! Newton just inside a limit position, and with tolerances at zero: the answer the closed form
//! and the construction give, or an error whose words match its numbers.
//!
//! Just inside a limit position (a fold) the two assembly modes are close twins and Newton
//! approaches either one linearly, each step about half the last, until it is nearer to one than
//! to the other; then it converges quadratically. Stopping at the first linear steps would call
//! a regular position singular.

use crate::support::{angle_apart, four_bar_angles, four_bar_limit};
use kinloop::{Error, NewtonConfig};

kinloop::mechanism! {
    /// A four-bar whose coupler and rocker reach full stretch (`|BD| = b + c`).
    #[kinloop(newton)]
    pub struct StretchFourBar {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

kinloop::mechanism! {
    /// A slider-crank whose rod is shorter than the crank: the crank cannot pass
    /// `r sin phi = l` (with the slider on the crank's line).
    #[kinloop(newton)]
    pub struct ShortRod {
        params r, l, e;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oab: r @ phi + l @ psi == (x, e);
    }
}

const FOUR_BAR: StretchFourBar = StretchFourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };

/// Angles just inside a fold are sensitive to rounding like `eps / sqrt(distance)`, about
/// `1e-10` at a distance of `1e-12`, in the construction as in the solve; `1e-8` keeps a margin
/// of a hundred and still tells the twin assembly modes (`1e-6` apart there) apart.
const NEAR_FOLD: f64 = 1e-8;

#[test]
fn newton_just_inside_a_stretched_four_bar_finds_the_position() {
    let limit = four_bar_limit(FOUR_BAR.a, FOUR_BAR.d, FOUR_BAR.b + FOUR_BAR.c);
    for inside in [1e-12, 1e-10, 1e-8] {
        let phi = limit - inside;
        let s = FOUR_BAR.solve(phi).unwrap_or_else(|e| panic!("{inside} inside the limit: {e}"));
        let StretchFourBar { a, b, c, d } = FOUR_BAR;
        // The assembly mode the solve reached: the nearer of the construction's two.
        let dist = |side: f64| {
            let [beta, gamma] = four_bar_angles(a, b, c, d, phi, side).expect("inside the limit");
            angle_apart(beta, s.q.beta).max(angle_apart(gamma, s.q.gamma))
        };
        let err = dist(1.0).min(dist(-1.0));
        assert!(err < NEAR_FOLD, "{inside} inside the limit: {err:e} from the construction");
    }
}

#[test]
fn newton_just_inside_a_short_rods_limit_finds_the_position() {
    let m = ShortRod { r: 1.0, l: 0.5, e: 0.0 };
    let phi = 0.5f64.asin() - 1e-12;
    let s = m.solve(phi).unwrap_or_else(|e| panic!("{e}"));
    // r sin(phi) + l sin(psi) = 0 and x = r cos(phi) + l cos(psi), on the declared guess's
    // side (cos psi >= 0).
    let psi = (-m.r * phi.sin() / m.l).clamp(-1.0, 1.0).asin();
    assert!(angle_apart(psi, s.q.psi) < NEAR_FOLD, "{} against {psi}", s.q.psi);
    let x = m.r * phi.cos() + m.l * psi.cos();
    assert_close!(s.q.x, x, NEAR_FOLD);
}

#[test]
fn zero_tolerances_at_a_regular_position_converge_to_rounding() {
    let cfg = NewtonConfig::default().with_residual_tol(0.0).with_step_tol(0.0);
    let StretchFourBar { a, b, c, d } = FOUR_BAR;
    for k in -12..=12 {
        let phi = 0.1 * f64::from(k);
        let s = FOUR_BAR.kinematics_with(phi, &FOUR_BAR.guess(phi), &cfg).unwrap_or_else(|e| panic!("{phi}: {e}"));
        let dist = |side: f64| {
            let [beta, gamma] = four_bar_angles(a, b, c, d, phi, side).expect("assembles");
            angle_apart(beta, s.q.beta).max(angle_apart(gamma, s.q.gamma))
        };
        // A regular position, well conditioned: to rounding.
        assert!(dist(1.0).min(dist(-1.0)) < 1e-13, "{phi}");
    }
    let m = ShortRod { r: 1.0, l: 0.5, e: 0.0 };
    for k in -5..=5 {
        let phi = 0.1 * f64::from(k);
        let s = m.kinematics_with(phi, &m.guess(phi), &cfg).unwrap_or_else(|e| panic!("{phi}: {e}"));
        let psi = (-m.r * phi.sin() / m.l).asin();
        assert!(angle_apart(psi, s.q.psi) < 1e-13, "{phi}");
    }
}

#[test]
fn a_singular_error_says_what_its_numbers_say() {
    // At the limit itself and just past it, whatever Newton reports must be true of its own
    // numbers: a pivot ratio called "below the tolerance" is below it.
    let limit = four_bar_limit(FOUR_BAR.a, FOUR_BAR.d, FOUR_BAR.b + FOUR_BAR.c);
    for phi in [limit, limit + 1e-15, limit - 1e-15, limit + 1e-9] {
        match FOUR_BAR.solve(phi) {
            Err(e @ Error::Singular { pivot_ratio, tolerance, .. }) => {
                let text = e.to_string();
                if pivot_ratio < tolerance {
                    assert!(text.contains("below the tolerance"), "{text}");
                } else {
                    assert!(text.contains("only linearly") && !text.contains("below"), "{text}");
                }
            }
            Err(Error::NoAssembly { .. }) | Ok(_) => {}
            Err(e) => panic!("{phi}: {e}"),
        }
    }
}
