//! Dimensional synthesis with `kinloop::synthesis`, on mechanisms declared here:
//!
//! 1. path generation: a four-bar's coupler point through ten points of an ellipse met in
//!    order along one turn of the crank, the crank angles and the frame's placement free, the
//!    crank required to turn fully with a transmission
//!    angle of at least 30 degrees; the best three designs' coupler curves are drawn with the
//!    targets (`out/synthesis/coupler_curve.svg`), and the best one moves through them on an
//!    interactive page (`out/synthesis/best_candidate.html`); the best design's two cognates
//!    (other pivots and links for the same coupler curve) are listed;
//! 2. function generation: `y = log10(x)` on `1 <= x <= 2` (the textbook case), a 60 degree
//!    crank rotation mapped to a 90 degree rocker rotation, five precision points at Chebyshev
//!    spacing, and the structural error over the whole range;
//! 3. the rhombic drive of a Stirling engine (`docs/papers.md`, paper 000): a phase shift and a
//!    stroke ratio, properties of the whole turn rather than targets at given inputs, reached by
//!    Levenberg–Marquardt on their exact gradients (the extremes' sensitivities by the envelope
//!    theorem, their locations by implicit differentiation of the velocity analog);
//! 4. a timed path only a six-bar makes: twelve points of a Stephenson six-bar at crank angles
//!    30 degrees apart, found again by the six-bar and missed by the best four-bar found
//!    (`docs/synthesis-literature.md`).
//!
//! Every candidate returned was verified by a branch-safe sweep through the targets in order.
//!
//! Run with `cargo run --release -p kinloop-examples --example synthesis`. (With the `kinloop`
//! feature `rayon`, `Search::par_run` runs the starts on all cores, with the same report.)

use kinloop::analysis::optimize::{LevenbergMarquardt, Minimum};
use kinloop::metrics::{FourBarLinks, grashof};
use kinloop::synthesis::classical::{FourBar, cognates};
use kinloop::synthesis::{
    Candidate, Constraints, Design, LocalConfig, PlacementBounds, Problem, Search, Task, chebyshev,
};
use kinloop::{Error, Extreme, Sensitivities, Vec2, to_deg};
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
    six_bar_versus_four_bar()?;
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
        "   {} could not be assembled, {} converged, {} stopped by the step tolerance, {} valid; rejected: {} order, \
         {} branch, {} circuit, {} no assembly, {} no full rotation, {} transmission angle",
        report.unassembled,
        report.converged,
        report.step_tolerance,
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
        print_cognates(&best[0])?;
    }
    println!();
    Ok(())
}

/// The two cognates of a `CouplerFourBar` design (the Roberts–Chebyshev theorem: other pivots
/// and links whose coupler point traces the same curve), their fixed pivots placed among the
/// targets as the design is, with the Grashof class of each (which link of it turns fully).
fn print_cognates(design: &Candidate) -> Result<(), Box<dyn std::error::Error>> {
    let [a, b, c, d, e, alpha] = design.params[..] else {
        return Err("a CouplerFourBar has six parameters".into());
    };
    let f = FourBar {
        input_pivot: Vec2::new(0.0, 0.0),
        output_pivot: Vec2::new(d, 0.0),
        ground_angle: 0.0,
        links: FourBarLinks { ground: d, input: a, coupler: b, output: c },
        coupler_point: Some((e, alpha)),
        body_angle: 0.0,
        inputs: design.inputs.iter().map(|x| x[0]).collect(),
        couplers: design.positions.iter().map(|q| q[0]).collect(),
        outputs: design.positions.iter().map(|q| q[1]).collect(),
    };
    // The placement maps the declaration's frame onto the targets': `(dx, dy) + s R(angle) p`.
    let [dx, dy, angle, scale] = design.placement.unwrap_or([0.0, 0.0, 0.0, 1.0]);
    let (sn, cs) = angle.sin_cos();
    let placed = |p: Vec2| Vec2::new(dx + scale * (cs * p.x - sn * p.y), dy + scale * (sn * p.x + cs * p.y));
    println!("   the best design's cognates (the same coupler curve from other pivots):");
    for (about, g) in ["the crank's pivot", "the rocker's pivot"].iter().zip(cognates(&f)?) {
        let (p, q, l) = (placed(g.input_pivot), placed(g.output_pivot), g.links);
        println!(
            "     about {about}: fixed pivots ({:.4}, {:.4}) and ({:.4}, {:.4}); input {:.4}, coupler {:.4}, \
             output {:.4} (a {})",
            p.x,
            p.y,
            q.x,
            q.y,
            scale * l.input,
            scale * l.coupler,
            scale * l.output,
            grashof(l)?.class
        );
    }
    Ok(())
}

fn function_generation() -> Result<(), Box<dyn std::error::Error>> {
    // x in [1, 2] -> crank rotation t in [0, 60 deg]; y = log10 x in [0, log10 2] -> rocker
    // rotation psi in [0, 90 deg].
    let (dt, dpsi, dy) = (60f64.to_radians(), 90f64.to_radians(), 2f64.log10());
    let t_of = |x: f64| (x - 1.0) * dt;
    let psi_of = |x: f64| x.log10() / dy * dpsi;
    let xs = chebyshev(1.0, 2.0, 5)?;
    let task = Task::function("psi", xs.iter().map(|&x| (t_of(x), psi_of(x))));
    let design = Design::new()
        .var("a", 0.05, 10.0)
        .var("b", 0.05, 10.0)
        .var("c", 0.05, 10.0)
        .var("phi0", -3.2, 3.2)
        .var("psi0", -3.2, 3.2);
    // Five equations for five unknowns; the best designs have a long coupler (b near its bound),
    // yet their structural error is a hundredth of a degree. The exact solution (a = 3.06,
    // b = 6.37, c = 8.53, phi0 = 0.536, psi0 = 1.012) lies inside the bounds, on the other
    // assembly mode than the declared guess solves at the first target: `with_guess([1.162,
    // 1.0668])` finds it.
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
        // The design's rocker may sit whole turns from the targets (the search compares
        // angles modulo a turn): the error is the difference reduced to a half turn.
        let d = s?.out.psi - psi_of(x);
        worst = worst.max(((d + PI).rem_euclid(TAU) - PI).abs());
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
pub fn rhombic(x: &[f64; 2]) -> Rhombic {
    Rhombic { r_b: x[0], gamma: x[1], ..Rhombic::default() }
}

/// Phase shift (crank angle from the piston's outer dead centre to the displacer's, in
/// (-pi, pi]) and stroke ratio (displacer over piston), with their gradients in `r_b`, `gamma`.
pub fn characteristics(x: &[f64; 2]) -> Result<([f64; 2], [[f64; 2]; 2]), Error> {
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

/// The start's phase shift and stroke ratio, the target (a phase shift 20 degrees less, a stroke
/// ratio of 1.5), and the Levenberg–Marquardt minimum of the misses.
pub fn phase_shift_design() -> Result<([f64; 2], [f64; 2], Minimum<2>), Error> {
    let ([phase0, ratio0], _) = characteristics(&START)?;
    let target = [phase0 - 20f64.to_radians(), 1.5];
    let residuals = |x: &[f64; 2]| -> Result<([f64; 2], [[f64; 2]; 2]), Error> {
        let (v, j) = characteristics(x)?;
        Ok(([v[0] - target[0], v[1] - target[1]], j))
    };
    let lm = LevenbergMarquardt::default().with_tol(1e-10).minimize(residuals, START)?;
    Ok(([phase0, ratio0], target, lm))
}

/// The rhombic drive's start: `r_b = 1.2`, `gamma = 0.7`.
pub const START: [f64; 2] = [1.2, 0.7];

fn phase_shift() -> Result<(), Box<dyn std::error::Error>> {
    let ([phase0, ratio0], _, lm) = phase_shift_design()?;
    println!("3. Rhombic drive: phase shift 20 degrees less than the start's, stroke ratio 1.5");
    println!("   start r_b = 1.2, gamma = 0.7: phase shift {:.4} deg, stroke ratio {ratio0:.6}", to_deg(phase0));
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

kinloop::mechanism! {
    /// Stephenson six-bar: a four-bar (crank `a` at the origin, coupler `b`, rocker `c` at
    /// (d, 0), coupler point P at `e`, `alpha` off the coupler) and a dyad from P (link `f`) to
    /// the ground pivot (gx, gy) (link `g`); the traced point `r` on the dyad's first link, `h`
    /// from P.
    #[kinloop(sensitivities)]
    pub struct StephensonSixBar {
        params a = 1.0, b = 3.2, c = 2.4, d = 3.1, e = 1.7, alpha = 0.45, f = 2.2, g = 2.6, gx = 0.8,
               gy = 4.6, h = 3.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, delta = 0.3, eps = -1.0;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop peg: a @ phi + e @ (beta + alpha) + f @ delta == (gx, gy) + g @ eps;
        point r = a @ phi + e @ (beta + alpha) + h @ delta;
    }
}

kinloop::mechanism! {
    /// The general four-bar of path synthesis: crank pivot at (x0, y0), frame `r1` at the angle
    /// `th0`, crank `r2` at `th2 + th2s` from the frame, coupler `r3`, rocker `r4`, the coupler
    /// point `rcx` along the coupler and `rcy` across it.
    #[kinloop(sensitivities)]
    pub struct PathFourBar {
        params r1 = 3.0, r2 = 1.0, r3 = 3.0, r4 = 2.5, rcx = 1.0, rcy = 1.0, x0 = 0.0, y0 = 0.0,
               th0 = 0.0, th2s = 0.0;
        input th2;
        unknowns th3 = 0.5, th4 = 1.5;
        loop abcd: r2 @ (th2 + th2s) + r3 @ th3 == (r1, 0) + r4 @ th4;
        point p = (x0, y0) + r2 @ (th2 + th2s + th0) + rcx @ (th3 + th0) + rcy @ (th3 + th0 + pi / 2);
    }
}

/// A timed path only a six-bar makes: twelve points of a Stephenson six-bar's traced point at
/// crank angles 30 degrees apart (one turn). The six-bar's eleven dimensions are found again;
/// the best four-bar (nine dimensions and the crank's start angle free, same targets, same
/// timing, either assembly mode) misses them measurably. The error is the literature's sum of
/// squared distances (`docs/synthesis-literature.md`).
fn six_bar_versus_four_bar() -> Result<(), Box<dyn std::error::Error>> {
    let truth = StephensonSixBar::default();
    let phis: Vec<f64> = (0..12).map(|k| 0.2 + k as f64 * TAU / 12.0).collect();
    let q0 = truth.guess(phis[0]);
    let mut targets = Vec::new();
    for s in truth.sweep(phis[0], phis[0] + TAU, 361, &q0)?.step_by(30).take(12) {
        let r = s?.out.r;
        targets.push([r.x, r.y]);
    }
    let sse = |c: &kinloop::synthesis::Candidate| c.errors.iter().map(|e| e * e).sum::<f64>();
    // The path's size: the largest distance of a target from their centroid.
    let count = targets.len() as f64;
    let (cx, cy) =
        (targets.iter().map(|t| t[0]).sum::<f64>() / count, targets.iter().map(|t| t[1]).sum::<f64>() / count);
    let extent = targets.iter().map(|t| (t[0] - cx).hypot(t[1] - cy)).fold(0.0, f64::max);
    println!("4. A timed path of a Stephenson six-bar: 12 points, crank angles 30 degrees apart");

    // The six-bar: its dimensions within 15 % of the truth's.
    let names = ["a", "b", "c", "d", "e", "alpha", "f", "g", "gx", "gy", "h"];
    let design = names.iter().zip(truth.params_flat()).fold(Design::new(), |d, (n, v)| {
        let (lo, hi) = (0.85 * v, 1.15 * v);
        d.var(*n, lo.min(hi), lo.max(hi))
    });
    let task = Task::path("r", targets.clone()).timed(phis.clone());
    let problem = Problem::new(StephensonSixBar::default(), &design, &task)?;
    let clock = Instant::now();
    let report = Search::default().with_starts(0..32).with_seed(1).run(&problem)?;
    let six = report.best().map(sse);
    println!(
        "   six-bar (11 dimensions, 32 starts, {:.2} s): sum of squared distances {:.2e}",
        clock.elapsed().as_secs_f64(),
        six.unwrap_or(f64::NAN)
    );

    // The best four-bar of a wide box, on each assembly mode.
    let design = Design::new()
        .var("r1", 0.2, 20.0)
        .var("r2", 0.2, 20.0)
        .var("r3", 0.2, 20.0)
        .var("r4", 0.2, 20.0)
        .var("rcx", -20.0, 20.0)
        .var("rcy", -20.0, 20.0)
        .var("x0", -20.0, 20.0)
        .var("y0", -20.0, 20.0)
        .var("th0", 0.0, TAU)
        .var("th2s", 0.0, TAU);
    let task = Task::path("p", targets).timed(phis);
    let search = Search::default()
        .with_starts(0..2048)
        .with_seed(1)
        .with_keep(1)
        .with_local(LocalConfig::default().with_max_evaluations(400));
    let clock = Instant::now();
    let mut best: Option<kinloop::synthesis::Candidate> = None;
    for guess in [[0.5, 1.5], [-0.5, -1.5]] {
        let problem = Problem::new(PathFourBar::default(), &design, &task)?.with_guess(guess)?;
        if let Some(c) = search.run(&problem)?.best()
            && best.as_ref().is_none_or(|b| sse(c) < sse(b))
        {
            best = Some(c.clone());
        }
    }
    let time = clock.elapsed().as_secs_f64();
    match best {
        Some(c) => {
            let values: Vec<String> = ["r1", "r2", "r3", "r4", "rcx", "rcy", "x0", "y0", "th0", "th2s"]
                .iter()
                .zip(&c.values)
                .map(|(n, v)| format!("{n} = {v:.4}"))
                .collect();
            println!(
                "   best four-bar (10 variables, 2 x 2048 starts, {time:.2} s): sum of squared distances {:.3e}, \
                 largest distance {:.3} ({:.1} % of the path's size)",
                sse(&c),
                c.max_error,
                100.0 * c.max_error / extent
            );
            println!("     {}", values.join(", "));
        }
        None => println!("   no valid four-bar ({time:.2} s)"),
    }
    Ok(())
}
