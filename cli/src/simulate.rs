//! `kinloop simulate`: the forward simulation of a one-input machine from its declared bodies,
//! loads and gravity, `(J + J_fly) phi'' + 1/2 J' phi'^2 = M + Q`, under a constant driving
//! torque, from a start angle and speed: the input angle and speed at equally spaced times, as
//! CSV with units. The runtime's integration (`Model::simulation`, the compiled `Simulation`'s)
//! over the model; the values between the integrator's steps come from its dense output.
//!
//! Units as `kinloop dynamics`'s: masses and lengths in the parameters' units, time in the
//! unit of the speed.
//!
//! Memory: the integration keeps every accepted step with its dense output (the values at the
//! written times are read from it once the run has reached its end), [`STEP_BYTES`] a step. The
//! step budget `--max-steps` ([`MAX_STEPS`] by default) is passed to the integrator, which stops
//! when it is spent: the steps kept are at most that many, whatever `--time` asks for.

use crate::dynamics::check_crank;
use crate::exit::usage;
use crate::{Failed, exit, samples};
use kinloop_model::Model;
use kinloop_runtime::dynamics::{DenseStep, DynamicsError, RunConfig, Trajectory};
use kinloop_runtime::{Error, Table};

/// The default step budget of the integration (`--max-steps`): about 100 MB of steps kept
/// ([`STEP_BYTES`] each), where the runtime's own default (ten million, a gigabyte) is meant
/// for a program that chose it. The shipped engine at 150 rad/s takes about 60 steps a turn.
pub const MAX_STEPS: usize = 1_000_000;

/// The memory a step of the trajectory takes while the simulation runs.
pub const STEP_BYTES: usize = std::mem::size_of::<DenseStep<2>>();

/// What `kinloop simulate` was asked.
pub struct Request {
    /// The input angle at time 0.
    pub start: f64,
    /// The input speed at time 0 (rad, or degrees with `deg`, per time unit).
    pub speed: f64,
    /// The simulated time.
    pub time: f64,
    /// The constant driving torque on the input.
    pub torque: f64,
    /// The moment of inertia of a flywheel on the input shaft.
    pub flywheel: f64,
    /// Equally spaced times written, both ends included.
    pub samples: usize,
    /// Angles (the start, the speed, the input written) in degrees.
    pub deg: bool,
    /// The integrator's step budget (accepted and rejected steps), at least 1.
    pub max_steps: usize,
}

/// Checks the request against the model, simulates and writes the table to standard output.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    let name = model.name().to_string();
    check_crank(model, "simulate")?;
    if req.samples < 2 {
        return Err(usage(format!("--samples {} is too few: the start and the end at least", req.samples)));
    }
    samples::check(req.samples)?;
    for (option, value) in [("--start", req.start), ("--speed", req.speed), ("--torque", req.torque)] {
        if !value.is_finite() {
            return Err(usage(format!("{option} {value} must be a finite number")));
        }
    }
    if !(req.time.is_finite() && req.time > 0.0) {
        return Err(usage(format!("--time {} must be a positive number", req.time)));
    }
    if !(req.flywheel.is_finite() && req.flywheel >= 0.0) {
        return Err(usage(format!("--flywheel {} must be a finite number, not negative", req.flywheel)));
    }
    if req.max_steps == 0 {
        return Err(usage(format!("--max-steps 0 allows no step: give at least 1 (the default is {MAX_STEPS})")));
    }
    let angle = if req.deg { 180.0 / std::f64::consts::PI } else { 1.0 };
    let torque = req.torque;
    let run = model
        .simulation()
        .start(req.start / angle, req.speed / angle)
        .drive(move |_, _, _| torque)
        .config(config(req))
        .run(req.time)
        .map_err(|e| failure(&name, e))?;
    let input = model.inputs()[0].clone();
    let table = trajectory_table(&run, req, &input, angle);
    table.write_csv(std::io::stdout().lock()).map_err(|e| {
        eprintln!("error: cannot write the table: {e}");
        Failed(exit::IO_ERR)
    })
}

/// The runtime's settings of the request: its flywheel and its step budget, the rest the
/// runtime's defaults.
fn config(req: &Request) -> RunConfig {
    let cfg = RunConfig::default();
    let ode = cfg.ode.with_max_steps(req.max_steps);
    cfg.with_ode(ode).with_flywheel(req.flywheel)
}

/// A failed simulation: a start so far out that no step can move it, or a `--time` that needs
/// more steps than `--max-steps`, is a bad argument (a usage error); the rest is the model's (a
/// parameter without a value, a limit position or a singular motion reached, a load that is not
/// finite).
fn failure(name: &str, e: Error) -> Failed {
    let dynamics = match &e {
        Error::Dynamics(source) => source.downcast_ref::<DynamicsError>(),
        _ => None,
    };
    match dynamics {
        Some(&DynamicsError::TooManySteps { steps, t, t_end }) => return usage(budget_spent(name, steps, t, t_end)),
        Some(DynamicsError::CannotAdvance { .. }) => return usage(format!("{name}: {e}")),
        _ => {}
    }
    eprintln!("error: {name}: {e}");
    Failed(exit::SOLVE_FAILED)
}

/// The message of a simulation that spent its step budget before `--time`: the options to
/// change (the runtime's own message names its library setting), and at the pace so far the
/// steps the whole span needs with the memory they take.
fn budget_spent(name: &str, steps: usize, t: f64, t_end: f64) -> String {
    let need = if t > 0.0 { steps as f64 * (t_end / t) } else { f64::INFINITY };
    let pace = if need.is_finite() {
        format!(
            "; at that pace the whole span needs about {} steps, {} of memory",
            significant(need),
            bytes(need * STEP_BYTES as f64)
        )
    } else {
        String::new()
    };
    format!(
        "{name}: the simulation made its budget of {steps} steps (--max-steps) and reached only t = {} of \
         --time {t_end}{pace}: raise --max-steps (each step takes {STEP_BYTES} bytes of memory until the end), \
         or simulate a shorter --time",
        significant(t)
    )
}

/// `v` (not negative) to about three significant digits: `1.23e-3`, `0.123`, `12.3`, `12345`,
/// `1.23e9`.
fn significant(v: f64) -> String {
    match v {
        v if v >= 1e6 => format!("{v:.2e}"),
        v if v >= 100.0 => format!("{v:.0}"),
        v if v >= 10.0 => format!("{v:.1}"),
        v if v >= 1.0 => format!("{v:.2}"),
        v if v >= 0.01 || v == 0.0 => format!("{v:.3}"),
        v => format!("{v:.2e}"),
    }
}

/// A number of bytes in kB, MB, GB or TB.
fn bytes(b: f64) -> String {
    const UNITS: [(&str, f64); 4] = [("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)];
    match UNITS.iter().find(|(_, scale)| b >= *scale) {
        Some((unit, scale)) => format!("{} {unit}", significant(b / scale)),
        None => format!("{b:.0} bytes"),
    }
}

/// The time, the input and its speed at `req.samples` equally spaced times from 0 to the time
/// reached, from the dense output, with units.
fn trajectory_table(run: &Trajectory, req: &Request, input: &str, angle: f64) -> Table {
    let a = if req.deg { "deg" } else { "rad" };
    let mut t = Table::new(vec!["t".into(), input.into(), "omega".into()]);
    let last = req.samples - 1;
    for k in 0..req.samples {
        // The ends exactly: the start and the time reached.
        let time = if k == last { run.t_end } else { run.t_end * k as f64 / last as f64 };
        let [phi, omega] = run.at(time);
        t.push(vec![time, phi * angle, omega * angle]);
    }
    let speed = format!("{a}/time unit");
    t.with_units(&[("t", "time unit"), (input, a), ("omega", &speed)])
}
