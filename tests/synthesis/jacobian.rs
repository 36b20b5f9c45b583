//! The residuals' Jacobian (generated sensitivities for the dimensions, velocity analogs for the
//! free crank angles, closed forms for the placement) against central differences of the
//! residuals themselves; the residual norm without the Jacobian against the residuals'.
//!
//! Reference: central differences with steps h and h/2 combined by one Richardson step
//! (truncation ~h^4, ~1e-13 at h = 1e-3 for these unit-size, smooth residuals); the positions are
//! solved to a residual of 1e-14, which the differences divide by h: ~1e-11. `tol::FD_FIRST`
//! (1e-9) leaves a factor of a hundred, while a wrong term shows at O(1).

use super::mechanisms::{CouplerFourBar, FOUR_BAR, coupler_point};
use crate::support::tol;
use kinloop::synthesis::{Design, PlacementBounds, Problem, Task};

/// Compares every entry of the Jacobian at `z` with differences of the residuals.
fn check<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    problem: &Problem<M, N, NI, NO, NP>,
    z: &[f64],
) where
    M: kinloop::Sensitivities<N, NI, NO, NP> + Clone,
{
    let at = problem.residuals(z).unwrap();
    // The residual norm without the Jacobian (the evolution's objective) solves the same
    // positions from the same guesses: the same norm to a few roundings.
    let norm = at.values.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert_close!(problem.residual_norm(z).unwrap(), norm, rel = 1e-13, "residual norm");
    let h = 1e-3;
    for i in 0..z.len() {
        let values = |step: f64| {
            let mut y = z.to_vec();
            y[i] += step;
            problem.residuals(&y).unwrap().values
        };
        let (hi, lo, hi2, lo2) = (values(h), values(-h), values(h / 2.0), values(-h / 2.0));
        for k in 0..at.values.len() {
            let d1 = (hi[k] - lo[k]) / (2.0 * h);
            let d2 = (hi2[k] - lo2[k]) / h;
            let fd = (4.0 * d2 - d1) / 3.0;
            assert_close!(at.jacobian[k][i], fd, rel = tol::FD_FIRST, "d r{k} / d z{i}");
        }
    }
}

/// Every dimension of the four-bar as a design variable, in a wide box.
fn design() -> Design {
    ["a", "b", "c", "d", "e", "alpha"].iter().fold(Design::new(), |d, n| d.var(*n, -10.0, 10.0))
}

#[test]
fn path_with_free_timing_and_placement() {
    let phis = [0.4, 1.1, 1.9, 2.6, 3.5, 4.4, 5.1, 5.8, 6.0, 6.1];
    let targets: Vec<[f64; 2]> = phis.iter().map(|&p| coupler_point(FOUR_BAR, p)).collect();
    let bounds =
        PlacementBounds::translation((-5.0, 5.0), (-5.0, 5.0)).with_rotation((-4.0, 4.0)).with_scale((0.1, 10.0));
    let task = Task::fit("p", targets).untimed(0.0, 7.0).with_placement(bounds);
    let problem = Problem::new(CouplerFourBar::default(), &design(), &task).unwrap();
    // Dimensions, the crank angles (off the targets'), and a placement with every term at work.
    let mut z = vec![1.05, 3.1, 2.45, 3.0, 1.6, 0.5];
    z.extend(phis.iter().map(|p| p + 0.05));
    z.extend([0.3, -0.2, 0.7, 1.3]);
    assert_eq!(z.len(), problem.dims());
    check(&problem, &z);
}

#[test]
fn motion_with_prescribed_timing_and_placement() {
    // Poses of the coupler (point and angle), targets off the mechanism so the residuals are
    // not small; the placement turns the angle too.
    let poses = [[1.0, 2.0, 0.5], [0.5, 2.5, 0.9], [0.0, 2.2, 1.4], [-0.3, 1.5, 2.0]];
    let bounds =
        PlacementBounds::translation((-5.0, 5.0), (-5.0, 5.0)).with_rotation((-4.0, 4.0)).with_scale((0.1, 10.0));
    let task = Task::motion("p", "theta", poses).timed([0.3, 0.9, 1.6, 2.4]).with_placement(bounds);
    let problem = Problem::new(CouplerFourBar::default(), &design(), &task).unwrap();
    let z = [1.05, 3.1, 2.45, 3.0, 1.6, 0.5, 0.3, -0.2, 0.7, 1.3];
    check(&problem, &z);
}
