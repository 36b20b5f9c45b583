//! `kinloop simulate`: the forward simulation of a one-input machine from its declared bodies,
//! loads and gravity, `(J + J_fly) phi'' + 1/2 J' phi'^2 = M + Q`, under a constant driving
//! torque, from a start angle and speed: the input angle and speed at equally spaced times, as
//! CSV with units. The runtime's integration (`Model::simulation`, the compiled `Simulation`'s)
//! over the model; the values between the integrator's steps come from its dense output.
//!
//! Units as `kinloop dynamics`'s: masses and lengths in the parameters' units, time in the
//! unit of the speed.
//!
//! Memory: the integration hands each accepted step to the table as it is made
//! (`ModelSimulation::run_steps`) and keeps none; the table reads the rows whose times the step
//! covers from its dense output ([`Rows`]), the values sampling the whole trajectory afterwards
//! (`Trajectory::at`) gives, bit for bit. So the run takes the memory of its `--samples` rows,
//! however many steps it makes. The step budget `--max-steps` ([`MAX_STEPS`] by default) is
//! passed to the integrator, which stops when it is spent: it bounds the time a run takes,
//! whatever `--time` asks for.

use crate::dynamics::{LOCKED, bad_mass, check_crank, locks};
use crate::exit::usage;
use crate::numbers::between;
use crate::solve::{degrees, in_units, text_in_units};
use crate::{Failed, samples};
use kinloop_model::{Count, Model};
use kinloop_runtime::dynamics::{DenseStep, DynamicsError, RunConfig};
use kinloop_runtime::{Error, Number, QuantityKind, Table};

/// The default step budget of the integration (`--max-steps`): a run of at most seconds (the
/// shipped engine at 150 rad/s takes about 60 steps a turn, a million steps in about four
/// seconds of a release build), where the runtime's own default (ten million) is meant for a
/// program that chose it. It bounds the time, not the memory: no step is kept.
pub const MAX_STEPS: usize = 1_000_000;

/// The columns the command writes beside the input's angle: the time and the input's speed
/// (the table is `t`, the input, `omega`). An input of one of these names would name two
/// columns alike.
const COLUMNS: [&str; 2] = ["t", "omega"];

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
    check_crank(model, "simulate", &COLUMNS)?;
    if req.samples < 2 {
        return Err(usage(format!("--samples {} is too few: the start and the end at least", req.samples)));
    }
    samples::check(req.samples)?;
    for (option, value) in [("--start", req.start), ("--speed", req.speed), ("--torque", req.torque)] {
        if !value.is_finite() {
            return Err(usage(format!("{option} {value} must be a finite number")));
        }
    }
    if req.deg {
        crate::solve::radians_of(req.start, "--start")?;
    }
    if !(req.time.is_finite() && req.time > 0.0) {
        return Err(usage(format!("--time {} must be a positive number", Number(req.time))));
    }
    if !(req.flywheel.is_finite() && req.flywheel >= 0.0) {
        return Err(usage(format!("--flywheel {} must be a finite number, not negative", Number(req.flywheel))));
    }
    if req.max_steps == 0 {
        return Err(usage(format!("--max-steps 0 allows no step: give at least 1 (the default is {MAX_STEPS})")));
    }
    let angle = if req.deg { 180.0 / std::f64::consts::PI } else { 1.0 };
    let kinds = model.input_kinds().to_vec();
    let table = simulate_table(model, req, angle);
    // A failure of the start's solve (a loop whose lengths are all zero) said where it was
    // solved, in the units given.
    let mut table =
        table.map_err(|e| failure(&name, text_in_units(model, e, &[req.start / angle], req.deg), &kinds, req))?;
    // The first row is the start, at time 0: its angle and speed as given, as `solve` writes
    // the inputs given, not their radians times `180/π` (`--start 30 --deg` was written
    // `29.999999999999996`). In radians the same numbers.
    if let Some(start) = table.rows.first_mut() {
        (start[1], start[2]) = (req.start, req.speed);
    }
    crate::output::table(&table, "the table")
}

/// Simulates the request (checked) and gives its table: the time, the input and its speed at
/// `req.samples` equally spaced times from 0 to `--time`, from the dense output of the steps as
/// they pass those times (no step kept), with units; `angle` converts radians to the unit
/// written.
fn simulate_table(model: &mut Model, req: &Request, angle: f64) -> Result<Table, Error> {
    let input = model.inputs()[0].clone();
    let last = req.samples - 1;
    // The ends exactly: the start and the time reached (`--time`: the run is never ended
    // early, and its last step ends there). The times between as the decimals they stand for
    // (`between`, as `sweep` writes its inputs): `--time 0.3 --samples 4` wrote the second
    // time `0.09999999999999999`, the product `0.3 * 1 / 3` rounded twice.
    let time = req.time;
    let at = move |k: usize| if k == last { time } else { between(0.0, time, k, last) };
    let mut rows = Rows::new(req.samples, at, input, req.deg, angle);
    let torque = req.torque;
    let (_, end) = model
        .simulation()
        .start(req.start / angle, req.speed / angle)
        .drive(move |_, _, _| torque)
        .config(config(req))
        .run_steps(req.time, |step, _| {
            rows.step(step);
            false
        })?;
    Ok(rows.finish(end))
}

/// The rows of the table, read from each step's dense output as the steps pass their times:
/// row `k` at time `at(k)` (not decreasing in `k`) from the first step that ends at or after
/// it, the time clamped to the step, and the rows after the last step from that step (a time
/// beyond its end by a rounding of `t0 + h`): what `Trajectory::at` gives at those times once
/// the run is over, bit for bit, without the trajectory.
struct Rows<F> {
    /// The rows to write.
    count: usize,
    /// The time of row `k`.
    at: F,
    /// The next row to read.
    next: usize,
    /// The last step seen.
    last: Option<DenseStep<2>>,
    /// The angle's unit: the factor from radians, and its name.
    angle: (f64, &'static str),
    input: String,
    table: Table,
}

impl<F: Fn(usize) -> f64> Rows<F> {
    /// The table of the time, the input named `input` and its speed, in degrees with `deg`
    /// (`angle` the factor from radians).
    fn new(count: usize, at: F, input: String, deg: bool, angle: f64) -> Self {
        let table = Table::new(vec![COLUMNS[0].into(), input.clone(), COLUMNS[1].into()]);
        let unit = if deg { "deg" } else { "rad" };
        Rows { count, at, next: 0, last: None, angle: (angle, unit), input, table }
    }

    /// Reads the rows whose times `step` reaches (those not after its end).
    fn step(&mut self, step: &DenseStep<2>) {
        while self.next < self.count {
            let t = (self.at)(self.next);
            if step.t1() < t {
                break;
            }
            self.push(t, step.at(t.clamp(step.t0, step.t1())));
        }
        self.last = Some(*step);
    }

    /// The table, the rows beyond the last step's end read from it (or the state `end` reached,
    /// where no step was made).
    fn finish(mut self, end: [f64; 2]) -> Table {
        while self.next < self.count {
            let t = (self.at)(self.next);
            let y = self.last.map_or(end, |s| s.at(t.clamp(s.t0, s.t1())));
            self.push(t, y);
        }
        let (a, input) = (self.angle.1, self.input.as_str());
        let speed = format!("{a}/time unit");
        self.table.with_units(&[("t", "time unit"), (input, a), ("omega", &speed)])
    }

    fn push(&mut self, t: f64, [phi, omega]: [f64; 2]) {
        let angle = self.angle.0;
        self.table.push(vec![t, phi * angle, omega * angle]);
        self.next += 1;
    }
}

/// The runtime's settings of the request: its flywheel and its step budget, the rest the
/// runtime's defaults.
fn config(req: &Request) -> RunConfig {
    let cfg = RunConfig::default();
    let ode = cfg.ode.with_max_steps(req.max_steps);
    cfg.with_ode(ode).with_flywheel(req.flywheel)
}

/// A failed simulation: a start so far out that no step can move it, a `--time` too short for
/// a step or that needs more steps than `--max-steps`, or a body's mass or inertia made
/// negative by the parameters,
/// is a bad argument (a usage error); the rest is the model's (a limit position or a singular
/// motion reached, a load that is not finite), its input (of kind `kinds`) and speed written in
/// degrees with `deg`, as the table writes them.
fn failure(name: &str, e: Error, kinds: &[QuantityKind], req: &Request) -> Failed {
    let deg = req.deg;
    let dynamics = match &e {
        Error::Dynamics(source) => source.downcast_ref::<DynamicsError>(),
        _ => None,
    };
    match dynamics {
        Some(&DynamicsError::TooManySteps { steps, t, t_end }) => {
            return usage(budget_spent(name, steps, t, t_end, implied_turns(req)));
        }
        // A `--time` too short for any step (below about 4e-323, a few subnormals: the time's
        // rounding there is as large as the span): the argument's error, named by its option.
        // It failed as a solve, exit code 1, saying "invalid end time".
        Some(&DynamicsError::BadValue { what: "end time", value, why }) => {
            return usage(format!("{name}: --time {}: {why}", Number(value)));
        }
        // A body's mass or inertia comes from the parameters given (the declaration's own
        // numbers are checked when it is read): a bad argument, as a parameter that is not
        // finite is.
        Some(DynamicsError::BadMass { .. }) => return usage(bad_mass(name, &e)),
        // The runtime names the state's component by its index, in the radians it integrates
        // in: named here (the input angle, component 0, and its speed, 1), in degrees where they
        // were given so.
        Some(&DynamicsError::CannotAdvance { t, component, value, change, .. }) => {
            let what = if component == 0 { "the input angle" } else { "the input speed" };
            let (value, change, unit) = match deg {
                true => (degrees(value), change.to_degrees(), " deg"),
                false => (value, change, ""),
            };
            return usage(format!(
                "{name}: the integration cannot advance at t = {}: a step changes {what} (= {}{unit}) by {:e}{unit}, \
                 less than half the spacing of f64 numbers there, so the change is lost; start from a smaller value \
                 (an angle modulo a turn)",
                Number(t),
                Number(value),
                change
            ));
        }
        _ => {}
    }
    let locked = locks(&e);
    // The code of the error as a sweep's or a solve's (a loop whose lengths are all zero, in
    // the kinematics of the start, is a usage error there, and was a failed solve here).
    let code = crate::solve::exit_code(&e);
    eprintln!("error: {}", crate::solve::named(name, &in_units(e, kinds, deg)));
    if locked {
        eprintln!("{LOCKED}");
    }
    Failed(code)
}

/// The turns of the input that `--speed` and `--time` imply at that speed, for a message that
/// names them as the cause of a span of too many steps: the clause saying so, `None` under a
/// turn (where the steps are the machine's own motion's, not the speed's: from rest, say).
fn implied_turns(req: &Request) -> Option<String> {
    let radians = if req.deg { req.speed.to_radians() } else { req.speed };
    let turns = radians.abs() * req.time / std::f64::consts::TAU;
    let count = match turns {
        n if n < 1.0 || n.is_nan() => return None,
        n if n.is_finite() => format!("about {} turns", significant(n)),
        _ => "more turns than a number holds".to_string(),
    };
    Some(format!("--speed {} over --time {} is {count} of the input", Number(req.speed), Number(req.time)))
}

/// The message of a simulation that spent its step budget before `--time`: the options to
/// change (the runtime's own message names its library setting), at the pace so far the steps
/// the whole span needs, and where the speed turns the input at least once over the span
/// (`turns`, from [`implied_turns`]), the turns that make those steps, with a lower `--speed`
/// among the remedies (at `--speed 1e30` only it and a shorter `--time` help).
fn budget_spent(name: &str, steps: usize, t: f64, t_end: f64, turns: Option<String>) -> String {
    let need = if t > 0.0 { steps as f64 * (t_end / t) } else { f64::INFINITY };
    // More steps than any count `--max-steps` takes (`--time 1e308`): raising it cannot reach
    // the end, and the message said to.
    let pace = if need.is_finite() {
        format!("; at that pace the whole span needs about {} steps", significant(need))
    } else {
        String::new()
    };
    let (cause, shorter) = match &turns {
        Some(turns) => (format!(" ({turns})"), "lower --speed or simulate a shorter --time"),
        None => (String::new(), "simulate a shorter --time"),
    };
    let advice = if need <= usize::MAX as f64 {
        match turns {
            Some(_) => "raise --max-steps, lower --speed, or simulate a shorter --time".to_string(),
            None => "raise --max-steps, or simulate a shorter --time".to_string(),
        }
    } else if need.is_finite() {
        format!("more than any --max-steps (at most {}): {shorter}", usize::MAX)
    } else {
        format!("{shorter} (no --max-steps reaches it at that pace)")
    };
    format!(
        "{name}: the simulation made its budget of {} (--max-steps) and reached only t = {} of \
         --time {}{pace}{cause}: {advice}",
        Count(steps, "step"),
        significant(t),
        Number(t_end)
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

#[cfg(test)]
mod tests {
    use super::*;
    use kinloop_runtime::dynamics::Trajectory;

    /// The shipped engine under a constant torque with a flywheel (the model of
    /// `tests/simulate.rs`'s first test).
    fn engine() -> Model {
        Model::read("engine.kl", include_str!("../mechanisms/engine.kl")).expect("the shipped engine")
    }

    fn request(samples: usize, deg: bool) -> Request {
        let angle = if deg { 180.0 / std::f64::consts::PI } else { 1.0 };
        let (start, speed) = (0.3 * angle, 150.0 * angle);
        Request { start, speed, time: 0.2, torque: 2.5, flywheel: 0.05, samples, deg, max_steps: MAX_STEPS }
    }

    /// The recorded trajectory of the request, as the command ran it before it streamed.
    fn trajectory(model: &mut Model, req: &Request, angle: f64) -> Trajectory {
        let torque = req.torque;
        model
            .simulation()
            .start(req.start / angle, req.speed / angle)
            .drive(move |_, _, _| torque)
            .config(config(req))
            .run(req.time)
            .expect("a run")
    }

    /// The table sampled from the whole recorded trajectory, as the command wrote it before it
    /// streamed: the times from the time reached, each value `Trajectory::at`.
    fn table_of(run: &Trajectory, req: &Request, input: &str, angle: f64) -> Table {
        let a = if req.deg { "deg" } else { "rad" };
        let mut t = Table::new(vec![COLUMNS[0].into(), input.into(), COLUMNS[1].into()]);
        let last = req.samples - 1;
        for k in 0..req.samples {
            let time = if k == last { run.t_end } else { between(0.0, run.t_end, k, last) };
            let [phi, omega] = run.at(time);
            t.push(vec![time, phi * angle, omega * angle]);
        }
        let speed = format!("{a}/time unit");
        t.with_units(&[("t", "time unit"), (input, a), ("omega", &speed)])
    }

    /// Every value of two tables as bits (with their columns and units): equal only if the
    /// tables are the same to the last bit.
    fn bits(t: &Table) -> (&[String], &[String], Vec<u64>) {
        (&t.columns, &t.units, t.rows.iter().flatten().map(|v| v.to_bits()).collect())
    }

    /// The streamed table is the one sampled from the recorded trajectory, bit for bit: few
    /// samples and many (several in a step), in radians and in degrees.
    #[test]
    fn the_streamed_table_is_the_recorded_trajectory_s() {
        let mut model = engine();
        for deg in [false, true] {
            let angle = if deg { 180.0 / std::f64::consts::PI } else { 1.0 };
            let run = trajectory(&mut model, &request(2, deg), angle);
            let steps = run.steps.len();
            assert!(steps > 20, "{steps} steps");
            for samples in [2, 3, 41, steps, steps + 1, 2 * steps - 1, 10 * steps + 3] {
                let req = request(samples, deg);
                let streamed = simulate_table(&mut model, &req, angle).expect("a run");
                let want = table_of(&run, &req, "phi", angle);
                assert_eq!(streamed.rows.len(), samples);
                assert_eq!(bits(&streamed), bits(&want), "{samples} samples, degrees {deg}");
            }
        }
    }

    /// Rows at the times where the steps meet (each step's start, its end `t0 + h`, the next
    /// one's start, a time a rounding beyond them) and inside the steps read what
    /// `Trajectory::at` reads there, bit for bit: the step a time on a boundary is read from,
    /// and the rows past the last step's end.
    #[test]
    fn rows_on_the_steps_boundaries_are_the_trajectory_s() {
        let mut model = engine();
        let run = trajectory(&mut model, &request(2, false), 1.0);
        let mut times = vec![0.0];
        for s in &run.steps {
            times.extend([s.t0, s.t0 + 0.3 * s.h, s.t1(), s.t1().next_up()]);
        }
        times.extend([run.t_end, run.t_end.next_up(), 2.0 * run.t_end]);
        times.sort_by(f64::total_cmp);
        let mut rows = Rows::new(times.len(), |k| times[k], "phi".into(), false, 1.0);
        for s in &run.steps {
            rows.step(s);
        }
        let table = rows.finish(run.end);
        for (row, &t) in table.rows.iter().zip(&times) {
            let want = run.at(t);
            assert_eq!([row[0], row[1], row[2]].map(f64::to_bits), [t, want[0], want[1]].map(f64::to_bits), "at {t}");
        }
        assert_eq!(table.rows.len(), times.len());
        // No step: every row is the state reached.
        let rows = Rows::new(3, |k| k as f64, "phi".into(), false, 1.0);
        let table = rows.finish([1.0, 2.0]);
        assert!(table.rows.iter().all(|r| r[1..] == [1.0, 2.0]));
    }

    /// A singular motion met with `--deg` names the input and its speed in degrees (per time
    /// unit), as the table writes them: a quarter turn and half a turn per time unit.
    #[test]
    fn a_singular_motion_is_written_in_degrees_with_deg() {
        use std::f64::consts::{FRAC_PI_2, PI};
        let motion = DynamicsError::SingularMotion {
            t: 1.0,
            h: 1e-17,
            x: vec![FRAC_PI_2],
            speed: vec![PI],
            names: vec!["phi".into()],
        };
        let text = in_units(Error::from(motion.clone()), &[QuantityKind::Angle], true).to_string();
        assert!(text.contains("at phi = 90, speed 180 (t = 1)"), "{text}");
        let text = in_units(Error::from(motion), &[QuantityKind::Angle], false).to_string();
        assert!(text.contains("at phi = 1.5707963267948966, speed 3.141592653589793 "), "{text}");
    }

    /// A spent budget says which options to change and the steps the span needs, no longer
    /// memory.
    #[test]
    fn a_spent_budget_names_the_options() {
        let m = budget_spent("Engine", 1000, 0.5, 10.0, None);
        for what in ["budget of 1000 steps", "about 20000 steps", "raise --max-steps", "shorter --time"] {
            assert!(m.contains(what), "`{what}` missing: {m}");
        }
        assert!(!m.contains("memory"), "{m}");
    }

    /// A span that needs more steps than any `--max-steps` takes (`--time 1e20`, or `1e308`
    /// whose count overflows) says to simulate a shorter time, not to raise the budget.
    #[test]
    fn a_span_beyond_any_budget_says_to_shorten_the_time() {
        for t_end in [1e20, 1e308] {
            let m = budget_spent("Engine", 1_000_000, 102.0, t_end, None);
            assert!(m.contains("simulate a shorter --time"), "{t_end}: {m}");
            assert!(!m.contains("raise --max-steps"), "{t_end}: {m}");
        }
        assert!(budget_spent("Engine", 1_000_000, 102.0, 1e20, None).contains("about 9.80e23 steps"));
    }

    /// The turns `--speed` and `--time` imply are named as the cause (1e30 rad for 1 unit:
    /// 1e30 / 2 pi = 1.59e29, closed form; 1e300 by 1e300 beyond any double, in words); under a
    /// turn (from rest) they are not, the pace being the machine's own.
    #[test]
    fn the_turns_the_speed_implies_are_named() {
        let mut req = request(2, false);
        (req.speed, req.time) = (1e30, 1.0);
        let named = implied_turns(&req);
        assert_eq!(named.as_deref(), Some("--speed 1e30 over --time 1 is about 1.59e29 turns of the input"));
        let m = budget_spent("Engine", 1000, 6e-29, 1.0, named);
        assert!(m.ends_with(": lower --speed or simulate a shorter --time"), "{m}");
        (req.speed, req.time) = (1e300, 1e300);
        assert!(implied_turns(&req).is_some_and(|s| s.contains("is more turns than a number holds")));
        (req.speed, req.time) = (0.0, 1e12);
        assert_eq!(implied_turns(&req), None);
    }
}
