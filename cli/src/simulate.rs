//! `kinloop simulate`: the forward simulation of a one-input machine from its declared bodies,
//! loads and gravity, `(J + J_fly) phi'' + 1/2 J' phi'^2 = M + Q`, under a constant driving
//! torque, from a start angle and speed: the input angle and speed at equally spaced times, as
//! CSV with units. The runtime's integration (`Model::simulation`, the compiled `Simulation`'s)
//! over the model; the values between the integrator's steps come from its dense output.
//!
//! Units as `kinloop dynamics`'s: masses and lengths in the parameters' units, time in the
//! unit of the speed.

use crate::dynamics::check_crank;
use crate::exit::usage;
use crate::{Failed, exit, samples};
use kinloop_model::Model;
use kinloop_runtime::dynamics::{DynamicsError, RunConfig, Trajectory};
use kinloop_runtime::{Error, Table};

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
    let angle = if req.deg { 180.0 / std::f64::consts::PI } else { 1.0 };
    let torque = req.torque;
    let run = model
        .simulation()
        .start(req.start / angle, req.speed / angle)
        .drive(move |_, _, _| torque)
        .config(RunConfig::default().with_flywheel(req.flywheel))
        .run(req.time)
        .map_err(|e| failure(&name, e))?;
    let input = model.inputs()[0].clone();
    let table = trajectory_table(&run, req, &input, angle);
    table.write_csv(std::io::stdout().lock()).map_err(|e| {
        eprintln!("error: cannot write the table: {e}");
        Failed(exit::IO_ERR)
    })
}

/// A failed simulation: a start so far out that no step can move it is a bad argument (a
/// usage error); the rest is the model's (a parameter without a value, a limit position or a
/// singular motion reached, a load that is not finite).
fn failure(name: &str, e: Error) -> Failed {
    let bad_argument = match &e {
        Error::Dynamics(source) => {
            matches!(source.downcast_ref::<DynamicsError>(), Some(DynamicsError::CannotAdvance { .. }))
        }
        _ => false,
    };
    if bad_argument {
        return usage(format!("{name}: {e}"));
    }
    eprintln!("error: {name}: {e}");
    Failed(exit::SOLVE_FAILED)
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
