//! Dynamics of the rhombic drive of `examples/rhombic_drive.rs`, sized as a small Stirling
//! engine (crank radius 20 mm, bore 40 mm) with plausible masses and a Schmidt-type gas model:
//! the gas pressure follows from the compression and expansion volumes, which the working
//! piston and the displacer set, so the force on the piston is a function of the state.
//!
//! The engine is declared once, with its masses and its gas force, in `mechanism!`
//! (`kinloop_fixtures::StirlingEngine`: the fixtures' rhombic drive plus `body` and `force`
//! items); `drive.mass_model()` gives the model every computation below runs on.
//!
//! It computes, from the same kinematic analogs the kinematic example prints:
//! * the driving torque over a turn at 1500 rpm, `M = J eps + 1/2 J' omega^2 - Q`;
//! * the shaking force on the frame and its first two harmonics, and the shaking moment;
//! * the flywheel for a coefficient of speed fluctuation delta = 1/50 (energy method and the
//!   energy equation with the variable inertia kept), checked by a simulation of the cycle;
//! * the run-up of the cold engine (no temperature difference: the gas acts as a spring) from
//!   rest under an induction-motor-like characteristic `M = M_s (1 - omega / omega_s)`.
//!
//! Run with `cargo run --release -p kinloop-examples --example rhombic_dynamics`. It prints tables and writes CSV
//! and SVG charts into `out/rhombic_dynamics/` (the charts into
//! `$KINLOOP_FIGURES/rhombic_dynamics/` when that variable is set).

use kinloop::Mechanism;
use kinloop::Table;
use kinloop::dynamics::{Cycle, CyclePoint, InverseCycle, Load, RunConfig, Simulation, SpeedLaw, Trajectory};
use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop_examples::{figure_dir, out_dir};
use kinloop_fixtures::StirlingEngine;
use std::f64::consts::{PI, TAU};

/// The example's drive scaled to metres (crank radius 20 mm), with its masses (kg) and moments
/// of inertia (kg m^2; the rods as slender bars), no gas yet: the declaration of
/// [`StirlingEngine`] (the fixtures' rhombic drive plus its bodies and gas force).
fn engine() -> StirlingEngine {
    let s = 0.02;
    let d = StirlingEngine::default();
    let (l_p, l_b) = (s * d.l_p, s * d.l_b);
    let rod = |l: f64, m: f64| m * l * l / 12.0;
    StirlingEngine {
        r_p: s * d.r_p,
        r_b: s * d.r_b,
        l_p,
        l_b,
        e_p: s * d.e_p,
        de: s * d.de,
        l_as1: s * d.l_as1,
        l_cs2: s * d.l_cs2,
        l_fs4: s * d.l_fs4,
        m_crank: 0.8,
        j_crank: 2e-4,
        m_rod2: 0.15,
        j_rod2: rod(l_p, 0.15),
        m_rod4: 0.18,
        j_rod4: rod(l_b, 0.18),
        m_piston: 0.45,
        m_displacer: 0.3,
        ..d
    }
}

/// The engine with its Schmidt-type gas (bore 40 mm, dead volumes 30 cm^3, cold end at 320 K,
/// hot end at `t_hot`): the volumes are zero-based at the extreme positions of the piston and
/// the displacer over a turn, and the amount of gas is set for the mean pressure
/// `mean_pressure`, which is also the buffer pressure on the piston's other side.
fn with_gas(
    drive: StirlingEngine,
    t_hot: f64,
    mean_pressure: f64,
) -> Result<StirlingEngine, Box<dyn std::error::Error>> {
    let sweep = drive.sampled(0.0, TAU, 721, &drive.guess(0.0))?;
    let xs = |u: usize| sweep.states().iter().map(move |k| k.q[u]);
    let (xc, xf) = (index(&StirlingEngine::UNKNOWNS, "x_c"), index(&StirlingEngine::UNKNOWNS, "x_f"));
    let unit = StirlingEngine {
        area: PI * 0.04 * 0.04 / 4.0,
        t_hot,
        t_cold: 320.0,
        dead: 3e-5,
        x_c_min: xs(xc).fold(f64::INFINITY, f64::min),
        x_f_max: xs(xf).fold(f64::NEG_INFINITY, f64::max),
        x_f_min: xs(xf).fold(f64::INFINITY, f64::min),
        mass_r: 1.0,
        buffer: 0.0,
        ..drive
    };
    // The declared gas force over the area is the pressure; with m R = 1, its mean over a turn
    // gives the m R of the mean pressure asked for.
    let model = unit.mass_model()?;
    let Some(Load::Force { law, .. }) = model.loads().first() else { return Err("the gas force is declared".into()) };
    let mean = sweep.states().iter().map(|k| law(k, &[0.0])[0] / unit.area).sum::<f64>() / 721.0;
    Ok(StirlingEngine { mass_r: mean_pressure / mean, buffer: mean_pressure, ..unit })
}

fn index(names: &[&str], name: &str) -> usize {
    names.iter().position(|n| *n == name).expect("a declared name")
}

/// The hot engine (900 K, mean pressure 1 MPa) and its inverse dynamics over a turn at the
/// constant speed `omega`, at 3600 crank angles (the example prints every 300th).
pub fn hot_cycle(omega: f64) -> Result<(StirlingEngine, Cycle), Box<dyn std::error::Error>> {
    let drive = with_gas(engine(), 900.0, 1.0e6)?;
    let hot = drive.mass_model()?;
    let cycle = InverseCycle::new(&drive, &hot, SpeedLaw::Constant(omega))
        .samples(3600)
        .guess(drive.guess_flat(&[0.0]))
        .about([0.0, drive.e_p])
        .run()?;
    Ok((drive, cycle))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let omega = 1500.0 * TAU / 60.0;
    let (drive, cycle) = hot_cycle(omega)?;
    let hot = drive.mass_model()?;
    let guess = drive.guess_flat(&[0.0]);
    print_cycle(&cycle, omega)?;

    let fw = cycle.flywheel(1.0 / 50.0)?;
    println!(
        "\nflywheel for delta = 1/50: energy swing {:.3} J, mean mechanism inertia {:.3e} kg m2;\n  \
         energy method {:.4e} kg m2, energy equation (variable J kept) {:.4e} kg m2",
        fw.energy_swing, fw.mechanism_inertia, fw.flywheel, fw.exact
    );
    // The energy method takes J as its mean; here 1/2 (J_max - J_min) omega^2 is of the order of
    // the gas work's swing, so only the energy equation gives the fluctuation asked for.
    let check = Simulation::new(&drive, &hot)
        .start(0.0, fw.start_speed)
        .guess(guess)
        .drive(|_, _, _| fw.mean_torque)
        .config(RunConfig::default().with_flywheel(fw.exact))
        .stop_when(|_, y| y[0] >= 2.0 * TAU)
        .run(1.0)?;
    let speeds: Vec<f64> = check
        .steps
        .iter()
        .flat_map(|s| (0..10).map(move |k| s.at(s.t0 + s.h * k as f64 / 10.0)))
        .filter(|y| y[0] >= TAU)
        .map(|y| y[1])
        .collect();
    let (hi, lo) = speeds.iter().fold((f64::MIN, f64::MAX), |(h, l), &w| (h.max(w), l.min(w)));
    println!(
        "  simulated steady cycle with it: delta = {:.5}, mean speed {:.2} rad/s ({:.2} target)",
        (hi - lo) / omega,
        (hi + lo) / 2.0,
        omega
    );

    let run = run_up(omega, fw.exact)?;
    write_outputs(&cycle, &run)
}

/// The table every 30 degrees, the mean torque and the harmonics of the shaking force.
fn print_cycle(cycle: &Cycle, omega: f64) -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "Rhombic drive as a Stirling engine at 1500 rpm (crank radius 20 mm, mean pressure 1 MPa, 900 K / 320 K)\n"
    );
    println!(
        "{:>6} {:>12} {:>12} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "phi", "J [kg m2]", "dJ/dphi", "Q [Nm]", "M [Nm]", "Fx [N]", "Fy [N]", "Msh [Nm]"
    );
    for p in cycle.points.iter().step_by(300) {
        println!(
            "{:>5.0}° {:>12.4e} {:>12.4e} {:>10.3} {:>10.3} {:>10.2} {:>10.2} {:>10.3}",
            p.phi.to_degrees(),
            p.inertia,
            p.inertia_slope,
            p.load,
            p.torque,
            p.shaking.force[0],
            p.shaking.force[1],
            p.shaking.moment
        );
    }
    let torque = cycle.torque_harmonics(4)?;
    println!("\nmean driving torque {:.4} Nm (indicated power {:.1} W)", torque.a0, -torque.a0 * omega);
    let [fx, fy, msh] = cycle.shaking_harmonics(2)?;
    println!(
        "shaking force harmonics (amplitudes): x {:.2} N, {:.2} N; y {:.2} N, {:.2} N; moment {:.3}, {:.3} Nm",
        fx.amplitude(1),
        fx.amplitude(2),
        fy.amplitude(1),
        fy.amplitude(2),
        msh.amplitude(1),
        msh.amplitude(2)
    );
    Ok(())
}

/// Run-up of the cold engine (no temperature difference: the gas is a spring) from rest under
/// the motor `M = M_s (1 - omega / omega_s)`, with the flywheel `j_fly`, for 3 s.
fn run_up(omega_s: f64, j_fly: f64) -> Result<Trajectory, Box<dyn std::error::Error>> {
    let drive = &with_gas(engine(), 320.0, 1.0e6)?;
    let cold = drive.mass_model()?;
    let m_s = 6.0;
    let motor = move |_: f64, _: f64, w: f64| m_s * (1.0 - w / omega_s);
    let cfg = RunConfig::default().with_flywheel(j_fly);
    let run = Simulation::new(drive, &cold)
        .start(0.0, 0.0)
        .guess(drive.guess_flat(&[0.0]))
        .drive(motor)
        .config(cfg)
        .run(3.0)?;
    let t95 = run.steps.iter().find(|s| s.at(s.t1())[1] >= 0.95 * omega_s).map_or(f64::NAN, |s| s.t1());
    println!("\nrun-up from rest (cold engine, flywheel above, motor {m_s} Nm stall, {omega_s:.1} rad/s synchronous):");
    println!(
        "  95 % of synchronous speed after {t95:.2} s; at {:.0} s: {:.2} rad/s, {:.0} turns, {} steps",
        run.t_end,
        run.end[1],
        run.end[0] / TAU,
        run.steps.len()
    );
    Ok(run)
}

fn write_outputs(
    cycle: &kinloop::dynamics::Cycle,
    run: &kinloop::dynamics::Trajectory,
) -> Result<(), Box<dyn std::error::Error>> {
    let data = out_dir("rhombic_dynamics");
    let mut t = Table::new(["phi", "J", "dJ_dphi", "Q", "M", "Fx", "Fy", "Msh"].map(String::from).to_vec());
    for p in &cycle.points {
        t.push(vec![
            p.phi,
            p.inertia,
            p.inertia_slope,
            p.load,
            p.torque,
            p.shaking.force[0],
            p.shaking.force[1],
            p.shaking.moment,
        ]);
    }
    t.save_csv(data.join("cycle.csv"))?;
    let mut r = Table::new(["t", "phi", "omega"].map(String::from).to_vec());
    let samples = 3000;
    for k in 0..=samples {
        let time = run.t_end * k as f64 / samples as f64;
        let [phi, w] = run.at(time);
        r.push(vec![time, phi, w]);
    }
    r.save_csv(data.join("runup.csv"))?;

    let dir = figure_dir("rhombic_dynamics");
    let crank = Axis::angle("crank angle φ1");
    let over_turn = |label: &str, kind: &Kind, f: &dyn Fn(&CyclePoint) -> f64| {
        Series::new(label, kind.clone(), cycle.points.iter().step_by(5).map(|p| (p.phi, f(p))).collect())
    };
    let (torque, force) = (Kind::torque("N m"), Kind::force("N"));
    plot::line_chart(
        &dir.join("torque.svg"),
        "Driving torque at 1500 rpm",
        &crank,
        &Axis::new("torque", torque.clone()),
        &[over_turn("driving torque M", &torque, &|p| p.torque), over_turn("gas torque Q", &torque, &|p| p.load)],
    )?;
    plot::line_chart(
        &dir.join("shaking.svg"),
        "Shaking force on the frame at 1500 rpm",
        &crank,
        &Axis::new("force", force.clone()),
        &[over_turn("Fx", &force, &|p| p.shaking.force[0]), over_turn("Fy", &force, &|p| p.shaking.force[1])],
    )?;
    // Amplitudes of the harmonics as bars: forces [N] and the moment [N m] on two panels (an
    // axis never mixes units), each from 0.
    let [fx, fy, msh] = cycle.shaking_harmonics(8)?;
    let orders = |label: &str, kind: &Kind, h: &kinloop::analysis::Fourier| {
        Series::new(label, kind.clone(), (1..=8).map(|n| (n as f64, h.amplitude(n))).collect())
    };
    plot::bar_chart(
        &dir.join("shaking_harmonics.svg"),
        "Harmonics of the shaking force and moment at 1500 rpm",
        &Axis::new("order (multiple of the crank speed)", Kind::Dimensionless),
        &[
            Panel::new(Axis::new("force amplitude", force.clone()))
                .with(orders("Fx", &force, &fx))
                .with(orders("Fy", &force, &fy)),
            Panel::new(Axis::new("moment amplitude", torque.clone())).with(orders("shaking moment", &torque, &msh)),
        ],
    )?;
    let speed: Vec<(f64, f64)> = (0..=600)
        .map(|k| {
            let time = run.t_end * k as f64 / 600.0;
            (time, run.at(time)[1])
        })
        .collect();
    plot::line_chart(
        &dir.join("runup.svg"),
        "Run-up from rest under the motor",
        &Axis::new("time t", Kind::time("s")),
        &Axis::new("crank speed ω", Kind::AngularSpeed),
        &[Series::new("ω", Kind::AngularSpeed, speed)],
    )?;
    println!("\nwrote cycle.csv and runup.csv to {} and 4 charts to {}", data.display(), dir.display());
    Ok(())
}
