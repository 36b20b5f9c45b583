//! `kinloop dynamics`: the inverse dynamics of a one-input machine over a turn of its crank at
//! a constant speed, from the declared bodies, loads and gravity: per angle the reduced moment
//! of inertia and its slope, the generalised force of the loads, the driving torque and the
//! shaking force and moment, as CSV with units; and the flywheel for a coefficient of speed
//! fluctuation. The runtime's inverse cycle and flywheel sizing over the model.
//!
//! Units: masses and lengths in the units of the parameters (`mass unit`, `length unit`), time
//! in the unit of the speed (`time unit`): with kg, m and s, torques in N m and forces in N.

use crate::exit::usage;
use crate::own_columns::{self, Own};
use crate::solve::{Notes, exit_code, in_units, named, point};
use crate::sweep::sample_as_given;
use crate::{Failed, exit, samples};
use kinloop_model::Model;
use kinloop_runtime::dynamics::{Cycle, DynamicsError, Flywheel, MIN_DELTA, SpeedLaw};
use kinloop_runtime::{Error, EventKind, Number, QuantityKind, Table};
use std::path::Path;

/// What `kinloop dynamics` was asked.
pub struct Request<'a> {
    /// The constant input speed (rad per time unit, or degrees with `deg`).
    pub speed: f64,
    /// The input angle the turn starts at.
    pub start: f64,
    /// Equally spaced angles per turn.
    pub samples: usize,
    /// The coefficient of speed fluctuation the flywheel is sized for.
    pub delta: f64,
    /// The frame point the shaking moments are taken about, `x,y`.
    pub about: Option<&'a str>,
    /// Angles (the input, the speed, its slope's denominator) in degrees.
    pub deg: bool,
    /// Where to write the flywheel sizing (standard error otherwise).
    pub flywheel: Option<&'a Path>,
}

const INERTIA: &str = "mass unit length unit^2";
const TORQUE: &str = "mass unit length unit^2/time unit^2";
const FORCE: &str = "mass unit length unit/time unit^2";

/// What `dynamics` and `simulate` add where the motion meets a singular position: the error
/// speaks of sweeps and of the library's names (start a sweep inside the range, trace the
/// curve), where a machine turned by its crank cannot avoid the position.
pub(crate) const LOCKED: &str = "note: a crank turning this machine meets a singular position (a limit position, \
                                 where the linkage locks, or a change point, where two branches cross) that the \
                                 motion cannot pass on one branch: check the lengths, or see the curve it moves on \
                                 with `kinloop trace`";

/// Whether `e` is the motion meeting a singular position: a sweep stopped or started there, or
/// a solve singular there (in a simulation, inside its kinematic error).
pub(crate) fn locks(e: &Error) -> bool {
    match e {
        Error::SweepStopped { kind, .. } => *kind != EventKind::Kink,
        Error::SingularStart { .. } | Error::Singular { .. } => true,
        Error::Dynamics(source) => match source.downcast_ref::<DynamicsError>() {
            Some(DynamicsError::Kinematics { source, .. }) => locks(source),
            _ => false,
        },
        _ => false,
    }
}

/// The message of a body's mass or moment of inertia that is negative or not finite: the
/// declaration's own numbers are checked when it is read, so the value comes from its
/// parameters, which `--params` sets.
pub(crate) fn bad_mass(name: &str, e: &Error) -> String {
    format!("{}; check the parameters it is computed from (--params)", crate::solve::named(name, e))
}

/// The columns `kinloop dynamics` writes beside the input and its slope `d(J)/d(input)` (which
/// no input's name can be): an input of one of these names would name two columns alike.
pub(crate) const CYCLE_COLUMNS: [&str; 8] =
    ["omega", "eps", "J", "load", "torque", "shaking_x", "shaking_y", "shaking_moment"];

/// The usage error of `kinloop COMMAND` (`dynamics`, `simulate`) on a model that is not a
/// machine turned by a crank: without declared dynamics, or with other than one angle input;
/// or whose input has the name of one of the command's own `columns`: its table would name two
/// columns alike, which a CSV reader cannot tell apart (the table's writer refuses it, but only
/// once the whole run is made).
pub(crate) fn check_crank(model: &Model, command: &str, columns: &[&str]) -> Result<(), Failed> {
    let name = model.name();
    if !model.has_dynamics() {
        return Err(usage(format!(
            "{name} declares no bodies, loads or gravity: declare them (`body`, `force`, `torque`, `gravity`) for its dynamics"
        )));
    }
    if model.inputs().len() != 1 || model.input_kinds()[0] != QuantityKind::Angle {
        return Err(usage(format!(
            "kinloop {command} turns a crank: {name} must have one input, an angle (its inputs: {})",
            model.inputs().join(", ")
        )));
    }
    let command = format!("kinloop {command}");
    let own = Own { command: &command, columns, beside: "input's", rename_to: "", written: "its table" };
    own_columns::check(&own, name, [("input", model.inputs()[0].as_str())])
}

/// The frame point of `--about`: two finite numbers.
fn parse_about(spec: Option<&str>) -> Result<[f64; 2], Failed> {
    spec.map_or(Ok([0.0, 0.0]), |spec| point(spec, "--about"))
}

/// Checks the request against the model, runs the cycle and writes the table to standard
/// output and the flywheel sizing to `--flywheel` or standard error.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    let name = model.name().to_string();
    check_crank(model, "dynamics", &CYCLE_COLUMNS)?;
    if req.samples < 8 {
        return Err(usage(format!("--samples {} is too few: a turn needs at least 8", req.samples)));
    }
    samples::check(req.samples)?;
    // Either way round: a crank turning clockwise has its cycle and its flywheel too.
    if !(req.speed.is_finite() && req.speed != 0.0) {
        return Err(usage(format!(
            "--speed {} must be a finite number, not zero (negative for an input turning clockwise)",
            Number(req.speed)
        )));
    }
    if !(MIN_DELTA..2.0).contains(&req.delta) {
        let min = Number(MIN_DELTA);
        // "Between 1e-6 and 2" refused 2 while it seemed to allow it: 2 itself is out (a speed
        // fluctuating from 0, no flywheel to size), as `--help` says.
        return Err(usage(format!("--delta {} must be from {min} to below 2 (e.g. 0.02)", Number(req.delta))));
    }
    if !req.start.is_finite() {
        return Err(usage(format!("--start {} must be a finite number", Number(req.start))));
    }
    if req.deg {
        crate::solve::radians_of(req.start, "--start")?;
    }
    let about = parse_about(req.about)?;
    // Created before the cycle is computed (which may take minutes): a path that cannot be
    // written stops first. Removed again if the command made it and no sizing comes to be
    // written into it.
    let file = crate::output::created(req.flywheel, "the flywheel file")?;
    let (cycle, flywheel) = match cycle_and_flywheel(model, req, about, &name) {
        Ok(found) => found,
        Err(e) => {
            if let Some(file) = file {
                file.abandon();
            }
            return Err(e);
        }
    };
    let angle = if req.deg { 180.0 / std::f64::consts::PI } else { 1.0 };
    let input = model.inputs()[0].clone();
    let table = cycle_table(&cycle, &input, req.deg.then_some(req.start));
    if let Err(e) = crate::output::table(&table, "the table") {
        if let Some(file) = file {
            file.abandon();
        }
        return Err(e);
    }
    crate::output::write_into(file, "the flywheel", |file| write_flywheel(&flywheel, req, angle, file))
}

/// The inverse cycle at the request's speed and the flywheel sized over it.
fn cycle_and_flywheel(
    model: &mut Model,
    req: &Request,
    about: [f64; 2],
    name: &str,
) -> Result<(Cycle, Flywheel), Failed> {
    let angle = if req.deg { 180.0 / std::f64::consts::PI } else { 1.0 };
    let (speed, start) = (req.speed / angle, req.start / angle);
    let mut run = |about: [f64; 2]| {
        model.inverse_cycle(SpeedLaw::Constant(speed)).start(start).samples(req.samples).about(about).run()
    };
    let cycle = run(about);
    // A shaking moment beyond the range of f64 about a point `--about` puts so far out that
    // its lever arm overflows (1e305 away for the shipped engine), where the moments about the
    // origin are within it: the argument's error, said of `--about`. It failed as a solve
    // (exit code 1), advising other units for the model.
    if let Err(e) = &cycle
        && about != [0.0, 0.0]
        && shaking_overflows(e)
        && run([0.0, 0.0]).is_ok()
    {
        return Err(usage(format!(
            "{name}: --about {}: the shaking moment about that point is beyond the range of f64 (its distance from \
             the mechanism times the shaking force): take the moments about a point nearer the mechanism",
            req.about.unwrap_or_default()
        )));
    }
    // The runtime's refusals of the arguments are usage errors; what remains is the model's
    // (see `failed_cycle`).
    let cycle = match cycle {
        Ok(cycle) => cycle,
        Err(e) => {
            // The start's invalid argument (a loop whose lengths are all zero) where it was
            // solved, in the units given.
            let e = crate::solve::text_in_units(model, e, &[start], req.deg);
            let locked = locks(&e);
            let failed = failed_cycle(name, e, locked, model.input_kinds(), req);
            // Where the lengths make the crank a rocker: its stretch.
            if locked && failed.0 == exit::SOLVE_FAILED {
                crate::assembles::rocks_note(model, start, req.deg);
            }
            return Err(failed);
        }
    };
    let flywheel = cycle.flywheel(req.delta).map_err(|e| {
        // Where the machine has no inertia about its input, its speed there does not follow
        // from its energy: the runtime's singular mass, said in the machine's terms, as
        // `simulate` says it (with its angle in the units given).
        match cycle.points.iter().find(|p| p.inertia == 0.0) {
            Some(p) => eprintln!(
                "error: {name}: flywheel: the machine has no inertia about its input at {} = {}{}: its reduced \
                 moment of inertia J is 0 there (the mass matrix is not positive definite), so its speed does not \
                 follow from its energy; give the bodies that move with the input mass or inertia",
                model.inputs()[0],
                Number(p.phi * angle),
                if req.deg { " deg" } else { "" }
            ),
            None => eprintln!("error: {name}: flywheel: {e}"),
        }
        Failed(exit::SOLVE_FAILED)
    })?;
    Ok((cycle, flywheel))
}

/// A failed inverse cycle reported: the runtime's refusals of the arguments (a start angle too
/// large for the samples of a turn to be told apart, more samples than memory holds, a body's
/// mass or inertia that the parameters make negative or not finite) as usage errors; the
/// model's (a limit position on the turn, a load that is not finite) as a failed solve, with
/// the note of a machine that locks (`locked`, [`locks`] of `e`). The input's kinds are `kinds`.
fn failed_cycle(name: &str, e: Error, locked: bool, kinds: &[QuantityKind], req: &Request) -> Failed {
    let dynamics = match &e {
        Error::Dynamics(source) => source.downcast_ref::<DynamicsError>(),
        _ => None,
    };
    match dynamics {
        // The runtime names the angle in the radians it computes in: named as given here.
        Some(DynamicsError::BadValue { what: "start angle", why, .. }) => {
            let unit = if req.deg { " deg" } else { "" };
            return usage(format!("{name}: --start {}{unit}: the start angle {why}", Number(req.start)));
        }
        Some(DynamicsError::BadValue { what: "samples", .. }) => return usage(format!("{name}: {e}")),
        Some(DynamicsError::BadMass { .. }) => return usage(bad_mass(name, &e)),
        _ => {}
    }
    // A sweep stopped on the turn says what goes on in the library's names (`trace_curve`,
    // `AtSingular::Continue`): the notes name the command line's, as under `sweep`'s error.
    let notes = Notes::of(&e);
    // The code of the error as a sweep's or a solve's (a loop whose lengths are all zero is a
    // usage error there, and was a failed solve here).
    let code = exit_code(&e);
    eprintln!("error: {}", named(name, &in_units(e, kinds, req.deg)));
    notes.write();
    if locked {
        eprintln!("{LOCKED}");
    }
    Failed(code)
}

/// Whether `e` is the runtime's shaking force or moment beyond the range of f64.
fn shaking_overflows(e: &Error) -> bool {
    let dynamics = match e {
        Error::Dynamics(source) => source.downcast_ref::<DynamicsError>(),
        _ => None,
    };
    matches!(dynamics, Some(DynamicsError::Overflow { what: "shaking force or moment", .. }))
}

/// The cycle as a table: per angle the input, its speed and acceleration, the reduced inertia
/// `J`, its slope, the load `Q` (the generalised force of the loads and gravity on the input),
/// the driving torque and the shaking force and moment, with units.
///
/// `start_deg`: the start angle in degrees as given, where angles are written in degrees
/// (radians otherwise).
fn cycle_table(cycle: &Cycle, input: &str, start_deg: Option<f64>) -> Table {
    let deg = start_deg.is_some();
    let (angle, a) = if deg { (180.0 / std::f64::consts::PI, "deg") } else { (1.0, "rad") };
    let slope = format!("d(J)/d({input})");
    let [omega, eps, j, rest @ ..] = CYCLE_COLUMNS;
    let columns = [input, omega, eps, j, &slope].into_iter().chain(rest);
    let mut t = Table::new(columns.map(String::from).collect());
    // The angles in degrees of the turn's equally spaced samples, from the start as given (the
    // turn's end, a sample past the last one, not written): as `sweep` writes its samples,
    // `5`, not their radians times `180/π`, `5.000000000000001` (a quarter of the default
    // turn's 360 angles were written so).
    let last = cycle.points.len();
    let input_at = |k: usize, phi: f64| match start_deg {
        Some(start) => sample_as_given(start, start + 360.0, k, last, phi * angle),
        None => phi,
    };
    for (k, p) in cycle.points.iter().enumerate() {
        t.push(vec![
            input_at(k, p.phi),
            p.omega * angle,
            p.eps * angle,
            p.inertia,
            p.inertia_slope / angle,
            p.load,
            p.torque,
            p.shaking.force[0],
            p.shaking.force[1],
            p.shaking.moment,
        ]);
    }
    let (speed, acceleration) = (format!("{a}/time unit"), format!("{a}/time unit^2"));
    t.with_units(&[
        (input, a),
        ("omega", &speed),
        ("eps", &acceleration),
        ("J", INERTIA),
        ("load", TORQUE),
        ("torque", TORQUE),
        ("shaking_x", FORCE),
        ("shaking_y", FORCE),
        ("shaking_moment", TORQUE),
    ])
}

/// The flywheel sizing as a CSV of one row into `file` (`--flywheel`), or one line each on
/// standard error.
fn write_flywheel(f: &Flywheel, req: &Request, angle: f64, file: Option<std::fs::File>) -> std::io::Result<()> {
    let a = if req.deg { "deg" } else { "rad" };
    let speed = format!("{a}/time unit");
    let rows: [(&str, &str, f64); 8] = [
        ("delta", "", req.delta),
        ("mean_torque", TORQUE, f.mean_torque),
        ("energy_swing", TORQUE, f.energy_swing),
        ("total_inertia", INERTIA, f.total_inertia),
        ("mechanism_inertia", INERTIA, f.mechanism_inertia),
        ("flywheel", INERTIA, f.flywheel),
        ("exact_flywheel", INERTIA, f.exact),
        ("start_speed", &speed, f.start_speed * angle),
    ];
    let Some(file) = file else {
        for (name, unit, value) in rows {
            let unit = crate::output::unit_suffix(unit);
            // `+ 0.0` writes a sum of zeros' negative zero (a machine without loads) as `0`.
            eprintln!("flywheel: {name} = {}{unit}", Number(value + 0.0));
        }
        // The energy method neglects the variation of the mechanism's own inertia over the
        // cycle; where the two sizings differ by a tenth, that variation matters (with no
        // loads, a varying inertia alone makes the speed fluctuate) and the reader is told which
        // one holds.
        if (f.flywheel - f.exact).abs() > 0.1 * f.flywheel.max(f.exact) {
            eprintln!(
                "flywheel: note: the energy method's flywheel neglects the variation of the mechanism's inertia \
                 over the cycle, which here changes the result by more than a tenth: size the flywheel by \
                 exact_flywheel"
            );
        }
        return Ok(());
    };
    let mut t = Table::new(rows.iter().map(|(n, _, _)| n.to_string()).collect());
    t.push(rows.iter().map(|(_, _, v)| *v).collect());
    let units: Vec<(&str, &str)> = rows.iter().map(|(n, u, _)| (*n, *u)).collect();
    // As the table is written: a sum of zeros' negative zero (a machine without loads) is `0`,
    // as on standard error.
    crate::csv_rows::write_table(std::io::BufWriter::new(file), &t.with_units(&units))
}
