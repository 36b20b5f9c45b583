//! Dimensional synthesis with `kinloop::synthesis`, on mechanisms declared here:
//!
//! 1. path generation: a four-bar's coupler point through ten points of an ellipse met in
//!    order along one turn of the crank, the crank angles and the frame's placement free, the
//!    crank required to turn fully with a transmission
//!    angle of at least 30 degrees; the best design's coupler curve is drawn with the targets
//!    (`out/synthesis/coupler_curve.svg`);
//! 2. function generation: `y = log10(x)` on `1 <= x <= 2` (the textbook case), a 60 degree
//!    crank rotation mapped to a 90 degree rocker rotation, five precision points at Chebyshev
//!    spacing, and the structural error over the whole range;
//! 3. the rhombic drive of a Stirling engine (`docs/papers.md`, paper 000): a phase shift and a
//!    stroke ratio, properties of the whole turn rather than targets at given inputs, reached by
//!    Levenberg–Marquardt on their exact gradients (the extremes' sensitivities by the envelope
//!    theorem, their locations by implicit differentiation of the velocity analog).
//!
//! Every candidate returned was verified by a branch-safe sweep through the targets in order.
//!
//! Run with `cargo run --release -p kinloop-examples --example synthesis`. (With the `kinloop`
//! feature `rayon`, `Search::par_run` runs the starts on all cores, with the same report.)

use kinloop::analysis::optimize::LevenbergMarquardt;
use kinloop::synthesis::{Constraints, Design, LocalConfig, PlacementBounds, Problem, Search, Task, chebyshev};
use kinloop::{Error, Extreme, Sensitivities, to_deg};
use kinloop_examples::out_dir;
use std::f64::consts::PI;
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

kinloop::mechanism! {
    /// Asymmetric rhombic drive: crank arms `r_p` and `r_b` joined at the angle `gamma`, centre
    /// at (0, e_p); working rod `l_p` to the piston at (x_c, 0); displacer rod `l_b` to the
    /// displacer at (x_f, de).
    #[kinloop(sensitivities)]
    pub struct Rhombic {
        params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7;
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    path_generation()?;
    function_generation()?;
    phase_shift()?;
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
    // Local solves to convergence (a few need more than the default 100 evaluations).
    let local = LocalConfig::default().with_max_evaluations(400);
    let search = Search::default().with_starts(0..512).with_seed(1).with_keep(5).with_local(local);
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
        report.rejected.order,
        report.rejected.branch,
        report.rejected.circuit,
        report.rejected.no_assembly,
        report.rejected.full_rotation,
        report.rejected.transmission
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
    // The best designs (up to three) drawn over the targets: each mechanism placed and shown at
    // its first target, its coupler curve over a turn of the crank, the targets numbered.
    if !report.candidates.is_empty() {
        let best = &report.candidates[..report.candidates.len().min(3)];
        let config = kinloop::draw::CandidatesConfig::new("p")
            .with_title("Best four-bars: their coupler curves through the ten targets")
            .with_span(TAU);
        let path = out_dir("synthesis").join("coupler_curve.svg");
        std::fs::write(&path, kinloop::draw::candidates(&CouplerFourBar::default(), best, &targets, &config)?)?;
        println!("   wrote {}", path.display());
        // The best one moving through the targets, in a page with a slider.
        let page = kinloop::draw::HtmlConfig::new("Best four-bar through the ten targets").show("p.x").show("p.y");
        let html = kinloop::draw::candidate_page(&CouplerFourBar::default(), &best[0], &targets, &config, &page)?;
        let path = out_dir("synthesis").join("best_candidate.html");
        std::fs::write(&path, html)?;
        println!("   wrote {}", path.display());
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

/// The rhombic drive with its displacer arm `r_b` and the angle `gamma` between the arms set
/// to `x`.
fn rhombic(x: &[f64; 2]) -> Rhombic {
    Rhombic { r_b: x[0], gamma: x[1], ..Rhombic::default() }
}

/// Phase shift (crank angle from the piston's outer dead centre to the displacer's, in
/// (-pi, pi]) and stroke ratio (displacer over piston), with their gradients in `r_b`, `gamma`.
fn characteristics(x: &[f64; 2]) -> Result<([f64; 2], [[f64; 2]; 2]), Error> {
    let m = rhombic(x);
    let turn = m.sampled(0.0, 2.0 * PI, 73, &m.guess(0.0))?;
    let ext = |col, which| turn.extremum_with_gradient(col, which);
    let (c_max, c_min) = (ext(Rhombic::COL.x_c, Extreme::Max)?, ext(Rhombic::COL.x_c, Extreme::Min)?);
    let (f_max, f_min) = (ext(Rhombic::COL.x_f, Extreme::Max)?, ext(Rhombic::COL.x_f, Extreme::Min)?);
    // The piston's outer dead centre is its most negative X_C; the displacer's its largest X_F.
    let phase = (f_max.x - c_min.x + PI).rem_euclid(2.0 * PI) - PI;
    let (s_c, s_f) = (c_max.value - c_min.value, f_max.value - f_min.value);
    let mut jac = [[0.0; 2]; 2];
    for (k, name) in ["r_b", "gamma"].iter().enumerate() {
        let p = Rhombic::PARAMS.iter().position(|n| n == name).ok_or(Error::InvalidArgument((*name).into()))?;
        // d(location)/dp of each extreme, and d(value)/dp by the envelope theorem.
        jac[0][k] = f_max.x_grad[p] - c_min.x_grad[p];
        let (ds_c, ds_f) = (c_max.grad[p] - c_min.grad[p], f_max.grad[p] - f_min.grad[p]);
        jac[1][k] = (ds_f * s_c - s_f * ds_c) / (s_c * s_c);
    }
    Ok(([phase, s_f / s_c], jac))
}

fn phase_shift() -> Result<(), Box<dyn std::error::Error>> {
    let start = [1.2, 0.7];
    let ([phase0, ratio0], _) = characteristics(&start)?;
    let target = [phase0 - 20f64.to_radians(), 1.5];
    println!("3. Rhombic drive: phase shift 20 degrees less than the start's, stroke ratio 1.5");
    println!("   start r_b = 1.2, gamma = 0.7: phase shift {:.4} deg, stroke ratio {ratio0:.6}", to_deg(phase0));
    let residuals = |x: &[f64; 2]| -> Result<([f64; 2], [[f64; 2]; 2]), Error> {
        let (v, j) = characteristics(x)?;
        Ok(([v[0] - target[0], v[1] - target[1]], j))
    };
    let lm = LevenbergMarquardt::default().with_tol(1e-10).minimize(residuals, start)?;
    let ([phase, ratio], _) = characteristics(&lm.x)?;
    println!(
        "   r_b = {:.9}, gamma = {:.9}: phase shift {:.6} deg, ratio {ratio:.9}; |r| = {:.1e} after {} evaluations",
        lm.x[0],
        lm.x[1],
        to_deg(phase),
        lm.value,
        lm.evaluations
    );
    Ok(())
}
