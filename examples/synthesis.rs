//! Dimensional synthesis with `kinloop::synthesis`, on two four-bars declared here:
//!
//! 1. path generation: a coupler point through eight points met in order along one turn of
//!    the crank, the crank angles free, the crank required to turn fully with a transmission
//!    angle of at least 30 degrees;
//! 2. function generation: `y = log10(x)` on `1 <= x <= 2` (the textbook case), a 60 degree
//!    crank rotation mapped to a 90 degree rocker rotation, five precision points at Chebyshev
//!    spacing, and the structural error over the whole range.
//!
//! Every candidate returned was verified by a branch-safe sweep through the targets in order.
//!
//! Run with `cargo run --release -p kinloop-examples --example synthesis` (`--features rayon`
//! on the `kinloop` dependency runs the starts on all cores with `Search::par_run`).

use kinloop::synthesis::{Constraints, Design, PlacementBounds, Problem, Search, Task, chebyshev};
use kinloop::{Sensitivities, to_deg};
use std::f64::consts::TAU;
use std::time::Instant;

kinloop::mechanism! {
    /// Four-bar with a coupler point: crank `a` at the origin, coupler `b`, rocker `c` pivoted at
    /// (d, 0), the point `p` at distance `e` from the crank pin, `alpha` off the coupler's line.
    #[kinloop(sensitivities)]
    pub struct CouplerFourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.0, e = 1.5, alpha = 0.6;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point p = a @ phi + e @ (beta + alpha);
    }
}

kinloop::mechanism! {
    /// Function generator: the crank turns by `t` from its start angle `phi0`; the output is the
    /// rocker's rotation `psi` from its start angle `psi0` (frame d = 1: the function does not
    /// depend on the size).
    #[kinloop(sensitivities)]
    pub struct FunctionGenerator {
        params a = 0.5, b = 1.2, c = 0.9, d = 1.0, phi0 = 1.0, psi0 = 1.5;
        input t;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ (t + phi0) + b @ beta == (d, 0) + c @ gamma;
        output psi = gamma - psi0;
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    path_generation()?;
    function_generation()?;
    Ok(())
}

fn path_generation() -> Result<(), Box<dyn std::error::Error>> {
    // Ten points of an ellipse (semi-axes 1 and 0.5, turned 20 degrees, centred at (2, 2)), in
    // order; the crank's pivot and the frame's direction are free (a placement without scale).
    let targets: Vec<[f64; 2]> = (0..10)
        .map(|k| {
            let (sn, cs) = 20f64.to_radians().sin_cos();
            let (st, ct) = (k as f64 * TAU / 10.0).sin_cos();
            let (x, y) = (ct, 0.5 * st);
            [2.0 + x * cs - y * sn, 2.0 + x * sn + y * cs]
        })
        .collect();
    let placement = PlacementBounds::translation((-5.0, 5.0), (-5.0, 5.0)).with_rotation((-3.2, 3.2));
    let task = Task::path("p", targets.clone()).untimed(0.0, TAU).with_placement(placement);
    let design = Design::new()
        .var("a", 0.2, 2.0)
        .var("b", 0.5, 5.0)
        .var("c", 0.5, 5.0)
        .var("d", 0.5, 8.0)
        .var("e", 0.0, 5.0)
        .var("alpha", -3.2, 3.2);
    let constraints =
        Constraints::default().with_full_rotation().with_transmission("beta", "gamma", 30f64.to_radians());
    let problem = Problem::new(CouplerFourBar::default(), &design, &task)?.with_constraints(&constraints)?;
    let search = Search::default().with_starts(0..512).with_seed(1).with_keep(5);
    let clock = Instant::now();
    let report = search.run(&problem)?;
    let time = clock.elapsed();

    println!("1. A coupler point through {} points, crank angles free ({} unknowns)", targets.len(), problem.dims());
    println!(
        "   {} starts in {:.2} s: {} evaluations (each a position and sensitivity solve at every target),",
        report.starts.len(),
        time.as_secs_f64(),
        report.evaluations
    );
    println!(
        "   {} could not be assembled, {} converged, {} valid; rejected: {} order, {} branch, {} circuit, \
         {} no assembly, {} no full rotation, {} transmission angle",
        report.unassembled,
        report.converged,
        report.valid,
        report.rejected[0],
        report.rejected[1],
        report.rejected[2],
        report.rejected[3],
        report.rejected[4],
        report.rejected[5]
    );
    for (rank, c) in report.candidates.iter().enumerate() {
        let values: Vec<String> =
            report.variables.iter().zip(&c.values).map(|(n, v)| format!("{n} = {v:.4}")).collect();
        println!(
            "   #{rank} (start {}): {}; max error {:.2e}, rms {:.2e}, min transmission {:.1} deg, defects {:?}",
            c.start,
            values.join(", "),
            c.max_error,
            c.rms_error,
            c.min_transmission.map_or(f64::NAN, to_deg),
            c.defects
        );
    }
    println!();
    Ok(())
}

fn function_generation() -> Result<(), Box<dyn std::error::Error>> {
    // x in [1, 2] -> crank rotation t in [0, 60 deg]; y = log10 x in [0, log10 2] -> rocker
    // rotation psi in [0, 90 deg].
    let (dt, dpsi, dy) = (60f64.to_radians(), 90f64.to_radians(), 2f64.log10());
    let t_of = |x: f64| (x - 1.0) * dt;
    let psi_of = |x: f64| x.log10() / dy * dpsi;
    let xs = chebyshev(1.0, 2.0, 5);
    let task = Task::function("psi", xs.iter().map(|&x| (t_of(x), psi_of(x))));
    let design = Design::new()
        .var("a", 0.05, 10.0)
        .var("b", 0.05, 10.0)
        .var("c", 0.05, 10.0)
        .var("phi0", -3.2, 3.2)
        .var("psi0", -3.2, 3.2);
    // Five equations for five unknowns; the best designs have a long coupler (b near its bound):
    // the exact solution lies beyond it, yet their structural error is a hundredth of a degree.
    let problem = Problem::new(FunctionGenerator::default(), &design, &task)?;
    let search = Search::default().with_starts(0..256).with_seed(2).with_keep(3);
    let clock = Instant::now();
    let report = search.run(&problem)?;
    let time = clock.elapsed();
    println!("2. y = log10(x) on [1, 2], five precision points at Chebyshev spacing");
    println!(
        "   {} starts in {:.2} s: {} evaluations, {} valid",
        report.starts.len(),
        time.as_secs_f64(),
        report.evaluations,
        report.valid
    );
    let Some(best) = report.best() else {
        println!("   no valid design");
        return Ok(());
    };
    let values: Vec<String> = report.variables.iter().zip(&best.values).map(|(n, v)| format!("{n} = {v:.6}")).collect();
    println!("   best: {}; error at the precision points {:.1e} rad", values.join(", "), best.max_error);
    // The structural error between the precision points, along one branch-safe sweep.
    let p: [f64; 6] = best.params.as_slice().try_into()?;
    let m = FunctionGenerator::default().with_params_flat(p);
    let q0: [f64; 2] = best.positions[0].as_slice().try_into()?;
    let (n, mut worst) = (101, 0.0f64);
    for (k, s) in m.sweep(0.0, dt, n, &q0.into())?.enumerate() {
        let x = 1.0 + k as f64 / (n - 1) as f64;
        worst = worst.max((s?.out.psi - psi_of(x)).abs());
    }
    println!(
        "   largest structural error over 1 <= x <= 2: {:.3} deg of the rocker, {:.2e} in y",
        to_deg(worst),
        worst / dpsi * dy
    );
    Ok(())
}
