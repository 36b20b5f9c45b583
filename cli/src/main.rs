//! `kinloop`: mechanisms declared in text files (`.kl`, the language of `mechanism!`), checked
//! and solved at run time by `kinloop-model`.
//!
//! ```text
//! kinloop check four_bar.kl                      # structure: counts, mobility, blocks
//! kinloop solve four_bar.kl --at 30 --deg --params a=1,b=3,c=2.5,d=3.2   # one state as CSV
//! kinloop solve four_bar.kl --at 0 --at 0.5 --params a=1.2,b=3,c=2.5,d=3.2
//! kinloop sweep four_bar.kl --from 0 --to 360 --samples 73 --deg --params a=1,b=3,c=2.5,d=3.2
//! kinloop dynamics engine.kl --speed 150 --delta 0.02 --flywheel flywheel.csv
//! kinloop simulate engine.kl --speed 150 --torque 2.5 --flywheel 0.05 --time 0.5
//! kinloop extremes slider_crank.kl --params r=1,l=3,e=0.4 --from 0 --to 360 --deg --table   # min and max
//! kinloop trace four_bar.kl --params a=3,b=2,c=2.5,d=4 --from 0 --to 180 --deg   # through limit positions
//! kinloop cam dwell_cam.kl --point follower --guide 0,1 --roller 10 --plot cam_profile.svg
//! kinloop cam dwell_cam.kl --point follower --guide 0,1 --flat --deg   # a flat-faced follower
//! kinloop animate rhombic_drive.kl --from 0 --to 360 --samples 91 --deg --out rhombic.svg
//! kinloop animate dwell_cam.kl --from 0 --to 360 --deg --cam follower --guide 0,1 --roller 10 --out cam.svg
//! kinloop animate five_bar.kl --grid --from 0,0.4 --to 3,3 --samples 9,7 --out five_bar.html
//! kinloop synth coupler_four_bar.kl --targets points.csv --path p --vary a=0.5..2,b=2..4 --starts 64
//! ```
//!
//! Long sweeps (from 2000 samples) and long searches (from 256 starts) show a progress bar on
//! standard error when it is a terminal.
//!
//! Exit codes ([`exit`]): 0 success, 1 a solve failed (for `synth`: no valid candidate), 2 a
//! usage error (a parameter without a value, or parameters that leave a loop's lengths all
//! zero, too), 65 the declaration is rejected (diagnostics on standard error), 66 the file
//! cannot be read, 69 the declaration uses what the run-time evaluator does not evaluate yet,
//! 73 the `--events` file (or the `animate --out`, `dynamics --flywheel` or `cam --plot` file)
//! cannot be created, 74 an output cannot be written (the help and the version too; a closed
//! standard output too, found before anything is done).

// Std's `eprintln!` and `eprint!` panic where standard error cannot be written (its reader
// gone: `kinloop sweep ... 2>&1 | head -1`), and the panic message is lost with it: exit code
// 101 instead of the command's own. These, defined before the modules and so used by all of
// them, write and let a failed write go: the message cannot reach anyone, the exit code still
// tells the outcome.
macro_rules! eprintln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}
macro_rules! eprint {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stderr(), $($arg)*);
    }};
}

mod animate;
mod assembles;
mod cam;
mod cam_drawn;
mod count;
mod csv_rows;
mod dynamics;
mod exit;
mod extremes;
mod names;
mod numbers;
mod output;
mod own_columns;
mod params;
mod progress;
mod report;
mod samples;
mod simulate;
mod solve;
mod sweep;
mod synth;
mod targets;
mod trace;

use clap::{Parser, Subcommand};
use kinloop_model::source::MAX_SOURCE_BYTES;
use kinloop_model::{Model, ReadError};
use kinloop_runtime::AtSingular;
use std::io::{IsTerminal, Read};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Mechanisms declared in text files, checked and solved at run time.
#[derive(Parser)]
#[command(name = "kinloop", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The declaration a command reads, and its parameters.
#[derive(clap::Args)]
struct Declaration {
    /// The declaration (`.kl`).
    file: PathBuf,
    /// Parameter values, `name=value` separated by commas (overriding the defaults), in the
    /// declaration's units: an angle parameter in radians, with or without `--deg`.
    #[arg(long, value_name = "NAME=VALUE,...")]
    params: Option<String>,
}

/// How a command that sweeps keeps to its branch.
#[derive(clap::Args)]
struct Branch {
    /// The smallest pivot ratio a sweep accepts (from 0 to below 1; default 1e-6): lower it for a
    /// mechanism meant to pass this close to a singular position (a slide brushing its pivot), as
    /// a sweep that stops there says. A lower value also weakens the test that finds change
    /// points (where two branches cross): a sweep may then pass one unnoticed and go on on the
    /// other branch, so lower it only over a range that holds none
    #[arg(long, value_name = "RATIO", allow_hyphen_values = true, value_parser = crate::numbers::number)]
    singular_pivot: Option<f64>,
    /// At a singular crossing (a change point, where two branches cross) a sweep records it and
    /// goes on along the smooth continuation of its curve, as a trace does, instead of stopping
    #[arg(long)]
    through_crossings: bool,
}

impl Declaration {
    /// The declaration read, checked and planned ([`load`]).
    fn load(&self) -> Result<Model, Failed> {
        load(&self.file, self.params.as_deref())
    }

    /// The declaration read for a command that solves ([`solvable`]).
    fn solvable(&self) -> Result<Model, Failed> {
        solvable(&self.file, self.params.as_deref())
    }

    /// [`Declaration::solvable`] for a command that sweeps, its sweeps configured by `branch`.
    fn solvable_on(&self, branch: &Branch) -> Result<Model, Failed> {
        let mut model = self.solvable()?;
        if branch.through_crossings {
            let config = model.sweep_config().with_at_singular(AtSingular::Continue);
            // The configuration in force is valid, and the choice at a crossing is any.
            let _ = model.set_sweep_config(config);
        }
        if let Some(ratio) = branch.singular_pivot {
            let config = model.sweep_config().with_singular_pivot(ratio);
            if model.set_sweep_config(config).is_err() {
                // Written as numbers are elsewhere: `{ratio}` wrote 1e308 in 309 digits.
                let ratio = kinloop_runtime::Number(ratio);
                return Err(exit::usage(format!("--singular-pivot {ratio} must be at least 0 and below 1")));
            }
        }
        Ok(model)
    }
}

// Every option that takes a number allows values that start with `-`: a negative number is
// then the option's value, refused by the option's own check, where clap would call it an
// unexpected argument and suggest `-- -1` (which makes it a file name).
/// What to do with the mechanism.
#[derive(Subcommand)]
enum Command {
    /// Checks a declaration and reports its structure, and how far its input moves.
    ///
    /// Checks a declaration and reports its structure: counts, mobility, the blocks in solve
    /// order and how each is solved; for one input angle and every parameter given, how far the
    /// input moves from 0 (whether it turns fully or rocks between two limit positions).
    Check {
        #[command(flatten)]
        decl: Declaration,
    },
    /// Solves positions, analogs and outputs at given inputs, as CSV with units.
    ///
    /// Solves positions, velocity and acceleration analogs and outputs at given inputs, from
    /// the declared initial guess, and writes them as CSV with units.
    Solve {
        #[command(flatten)]
        decl: Declaration,
        /// The inputs of one state, separated by commas (one value per input); repeat for more
        /// states (each solved from the declared guess; where one fails, the others are written
        /// and the exit code is 1, or 2 where a failure is a usage error: a loop whose lengths
        /// are all zero).
        #[arg(long, required = true, value_name = "X,...", allow_hyphen_values = true)]
        at: Vec<String>,
        /// Angles in degrees (inputs given and values written); otherwise radians.
        #[arg(long)]
        deg: bool,
    },
    /// Sweeps the inputs from `--from` to `--to` without jumping branches, as CSV with units.
    ///
    /// Sweeps the inputs along the straight path from `--from` to `--to` without jumping
    /// branches, from the declared initial guess at `--from`, and writes the states as CSV
    /// with units; the singular positions met (limit positions, crossings) are listed on
    /// standard error or written to `--events`. Each state is written as soon as it is solved
    /// and none is kept, so the memory does not grow with `--samples`; a sweep that stops (a
    /// limit position) has written the states before the stop, and fails; one whose standard
    /// output closes (`| head`) stops at the next state, exit code 74.
    Sweep {
        #[command(flatten)]
        decl: Declaration,
        #[command(flatten)]
        branch: Branch,
        /// The inputs at the start, separated by commas (one value per input).
        #[arg(long, value_name = "X,...", allow_hyphen_values = true)]
        from: String,
        /// The inputs at the end.
        #[arg(long, value_name = "X,...", allow_hyphen_values = true)]
        to: String,
        /// Samples, equally spaced, both ends included (at least 2, or 1 where `--to` equals
        /// `--from`; at most 10000000).
        #[arg(long, default_value_t = 361, allow_hyphen_values = true, value_parser = count::count)]
        samples: usize,
        /// Angles in degrees (inputs given and values written); otherwise radians.
        #[arg(long)]
        deg: bool,
        /// Writes the events as CSV to this file (`kind,tau [1],` inputs, unknowns) instead of
        /// listing them on standard error; an input or unknown named `kind` or `tau` is refused.
        #[arg(long, value_name = "FILE")]
        events: Option<PathBuf>,
    },
    /// Traces the whole solution curve, past limit positions, as CSV with units.
    ///
    /// Traces the whole solution curve through the declared initial guess at `--from` by
    /// pseudo-arclength continuation, first towards `--to`: unlike `sweep` it passes limit
    /// positions, where the input reverses, so a linkage whose input cannot turn fully (a
    /// non-Grashof four-bar) gives its closed curve; `--from` may be a limit position (where a
    /// sweep stopped), listed as the first one passed. Writes the points (inputs, unknowns,
    /// outputs) as CSV with units, about `--ds` apart (closer where the curve turns by more than
    /// a tenth of a radian over `--ds`), and lists the limit positions, kinks and
    /// crossings passed on standard error or in `--events`. Stops where the curve closes (back
    /// at its start, its angles within whole turns, a turning input's too, the input moving as it
    /// started: a crank's curve closes after a turn), where it
    /// leaves the inputs' segment from `from - (to - from)` to `to`, or after `--max-points`.
    Trace {
        #[command(flatten)]
        decl: Declaration,
        #[command(flatten)]
        branch: Branch,
        /// The inputs at the start, separated by commas (one value per input).
        #[arg(long, value_name = "X,...", allow_hyphen_values = true)]
        from: String,
        /// The inputs the trace moves towards first.
        #[arg(long, value_name = "X,...", allow_hyphen_values = true)]
        to: String,
        /// Arclength between points, in radians of an angle and in units of the mechanism's
        /// size of a length (from 1e-9 to 1).
        #[arg(long, default_value_t = 0.01, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        ds: f64,
        /// The most points written (at least 1, at most 10000000). Unlike `sweep`, every point
        /// is kept until the trace ends (they are written then): about 100 B a point for a
        /// four-bar, some 1 GB at the most.
        #[arg(long, default_value_t = 100_000, allow_hyphen_values = true, value_parser = count::count)]
        max_points: usize,
        /// Angles in degrees (inputs given and values written); otherwise radians.
        #[arg(long)]
        deg: bool,
        /// Writes the events as CSV to this file (`kind,tau [1],` inputs, unknowns) instead of
        /// listing them on standard error; an input or unknown named `kind` or `tau` is refused.
        #[arg(long, value_name = "FILE")]
        events: Option<PathBuf>,
    },
    /// Inverse dynamics over a turn: driving torque, shaking force and moment, flywheel.
    ///
    /// The inverse dynamics of a one-input machine from its declared bodies, loads and
    /// gravity, over a turn of its input at a constant speed: per angle the reduced moment of
    /// inertia and its slope, the load on the input, the driving torque and the shaking force
    /// and moment, as CSV with units (masses and lengths in the parameters' units, time in the
    /// speed's); and the flywheel for a coefficient of speed fluctuation, listed on standard
    /// error or written to `--flywheel`.
    Dynamics {
        #[command(flatten)]
        decl: Declaration,
        #[command(flatten)]
        branch: Branch,
        /// The constant input speed, in rad (or degrees with `--deg`) per time unit: negative for
        /// an input turning clockwise (the flywheel's start speed then negative too).
        #[arg(long, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        speed: f64,
        /// The input angle the turn starts at.
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        start: f64,
        /// Equally spaced angles per turn (at least 8, at most 10000000).
        #[arg(long, default_value_t = 360, allow_hyphen_values = true, value_parser = count::count)]
        samples: usize,
        /// The coefficient of speed fluctuation `(omega_max - omega_min) / omega_mean` the
        /// flywheel is sized for (from 1e-6 to below 2).
        #[arg(long, default_value_t = 0.02, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        delta: f64,
        /// The frame point the shaking moments are taken about, `x,y` (the origin otherwise).
        #[arg(long, value_name = "X,Y", allow_hyphen_values = true)]
        about: Option<String>,
        /// Angles in degrees (the start, the input, the speed); otherwise radians.
        #[arg(long)]
        deg: bool,
        /// Writes the flywheel sizing as CSV to this file instead of listing it on standard
        /// error.
        #[arg(long, value_name = "FILE")]
        flywheel: Option<PathBuf>,
    },
    /// Forward simulation under a constant driving torque, from a start angle and speed.
    ///
    /// The forward simulation of a one-input machine from its declared bodies, loads and
    /// gravity under a constant driving torque, from a start angle and speed: the input angle
    /// and speed at equally spaced times, as CSV with units (masses and lengths in the
    /// parameters' units, time in the speed's). A limit position reached fails.
    Simulate {
        #[command(flatten)]
        decl: Declaration,
        #[command(flatten)]
        branch: Branch,
        /// The input speed at time 0, in rad (or degrees with `--deg`) per time unit.
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        speed: f64,
        /// The input angle at time 0.
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        start: f64,
        /// The time simulated (positive).
        #[arg(long, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        time: f64,
        /// The constant driving torque on the input.
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        torque: f64,
        /// The moment of inertia of a flywheel on the input shaft.
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        flywheel: f64,
        /// Equally spaced times written, both ends included (at least 2, at most 10000000).
        #[arg(long, default_value_t = 101, allow_hyphen_values = true, value_parser = count::count)]
        samples: usize,
        /// The integrator's step budget (at least 1): a `--time` that needs more steps stops
        /// with a usage error, so the budget bounds the time the run takes. No step is kept
        /// (each row is read from its step as the run passes it): the memory is that of the
        /// `--samples` rows, whatever the number of steps.
        #[arg(long, value_name = "N", default_value_t = simulate::MAX_STEPS, allow_hyphen_values = true, value_parser = count::count)]
        max_steps: usize,
        /// Angles in degrees (the start, the speed, the input written); otherwise radians.
        #[arg(long)]
        deg: bool,
    },
    /// The disc cam that moves the follower as declared: pitch curve, profile, pressure angle.
    ///
    /// The disc cam that moves a follower as the declaration says, by kinematic inversion over
    /// one turn of the cam shaft (the input): its pitch curve and profile in the cam's frame,
    /// the pitch curve's radius of curvature and the pressure angle as CSV; the largest
    /// pressure angle, the sharpest point and whether the roller undercuts it on standard
    /// error. With `--flat`, a flat-faced follower: the profile, its radius of curvature, the
    /// contact's offset along the face and the pressure angle; the face's least width and the
    /// samples where the profile is not convex on standard error.
    Cam {
        #[command(flatten)]
        decl: Declaration,
        #[command(flatten)]
        branch: Branch,
        /// The follower's point: a `point` of the declaration (the roller's centre, or the knife
        /// edge).
        #[arg(long, value_parser = crate::names::name)]
        point: String,
        #[command(flatten)]
        follower: cam::FollowerArgs,
        /// The cam shaft's angle at the first sample.
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = crate::numbers::number)]
        start: f64,
        /// Samples over the turn, equally spaced, both ends included (at least 3, at most
        /// 10000000).
        #[arg(long, default_value_t = 361, allow_hyphen_values = true, value_parser = count::count)]
        samples: usize,
        /// Angles in degrees (given and written); otherwise radians.
        #[arg(long)]
        deg: bool,
        /// Draw the pitch curve and the profile into this SVG file.
        #[arg(long, value_name = "PATH")]
        plot: Option<PathBuf>,
    },
    /// The smallest and largest value of each unknown and output over a sweep.
    ///
    /// Sweeps the inputs along the straight path from `--from` to `--to` as `sweep` does and
    /// writes the smallest and largest value of each unknown and output with the inputs where
    /// it happens: an interior extreme located as a root of the velocity analog between
    /// samples, on the sweep's branch; otherwise an end of the range. CSV with units, or a
    /// table. A sweep that stops (a limit position) fails. A column that stands exactly still
    /// over stretches (a cam follower's dwells) has them noted on standard error.
    Extremes {
        #[command(flatten)]
        decl: Declaration,
        #[command(flatten)]
        branch: Branch,
        /// The inputs at the start, separated by commas (one value per input).
        #[arg(long, value_name = "X,...", allow_hyphen_values = true)]
        from: String,
        /// The inputs at the end (past `--from` for one input).
        #[arg(long, value_name = "X,...", allow_hyphen_values = true)]
        to: String,
        /// Samples, equally spaced, both ends included (at least 3, at most 10000000). Unlike
        /// `sweep`, every state is kept until the extremes are located (the search between
        /// samples starts from them): about 0.7 KB a sample for a four-bar, some 7 GB at the
        /// most. An extreme is located between samples to the rounding whatever their number
        /// (a root of the velocity analog where its sign changes between two samples), so more
        /// samples are needed only where a column turns twice within one spacing.
        #[arg(long, default_value_t = 361, allow_hyphen_values = true, value_parser = count::count)]
        samples: usize,
        /// Angles in degrees (inputs given and values written); otherwise radians.
        #[arg(long)]
        deg: bool,
        /// The unknowns and outputs to report, separated by commas (all of them otherwise).
        #[arg(long, value_name = "NAME,...")]
        columns: Option<String>,
        /// A table aligned in columns instead of CSV.
        #[arg(long)]
        table: bool,
    },
    /// Draws the mechanism moving: an animated SVG or an interactive HTML page.
    ///
    /// Draws the mechanism from its declaration moving through a branch-safe sweep from
    /// `--from` to `--to` (from the declared initial guess at `--from`), and writes an animated
    /// SVG or an interactive HTML page (slider, play/pause, readouts and charts). A sweep that
    /// stops at a limit position is drawn up to there, plays back and forth, and the event is
    /// listed on standard error. With `--grid`, a mechanism of several inputs over the grid of
    /// its inputs, as a page with one slider per input.
    Animate {
        #[command(flatten)]
        decl: Declaration,
        #[command(flatten)]
        branch: Branch,
        /// The inputs at the start, separated by commas (one value per input).
        #[arg(long, value_name = "X,...", allow_hyphen_values = true)]
        from: String,
        /// The inputs at the end.
        #[arg(long, value_name = "X,...", allow_hyphen_values = true)]
        to: String,
        /// Samples, equally spaced, both ends included (default 181, at least 2, at most 100000); with
        /// `--grid`, the values of each input: one count for all or one per input (default: the
        /// most whose grid fits the page's frames, 26 per input for two inputs, 8 for three).
        #[arg(long, value_name = "N[,N...]", allow_hyphen_values = true)]
        samples: Option<String>,
        /// A grid of the inputs from `--from` to `--to` instead of a sweep (a mechanism of two
        /// inputs or more), drawn as an interactive page with one slider per input (`.html`).
        #[arg(long)]
        grid: bool,
        /// Angles in degrees (inputs given); otherwise radians.
        #[arg(long)]
        deg: bool,
        /// The file written: its extension (`.svg`, `.html`) tells the format unless `--format`
        /// does; `-` is standard output (with `--format`).
        #[arg(long, value_name = "FILE")]
        out: PathBuf,
        /// The format written, whatever the extension of `--out`.
        #[arg(long, value_enum)]
        format: Option<animate::Format>,
        /// A column shown as a readout with its chart on the HTML page (repeat for more).
        #[arg(long, value_name = "COLUMN", value_parser = crate::names::name)]
        show: Vec<String>,
        /// The largest number of frames written: key frames of the SVG (default 90), poses of
        /// the page (default 721).
        #[arg(long, allow_hyphen_values = true, value_parser = count::count)]
        frames: Option<usize>,
        /// Draws the disc cam that moves this point of the declaration (a follower's roller
        /// centre, or its knife edge), turning with the one input: found by inversion of the
        /// point's motion over one turn from `--from`, as `kinloop cam` finds it, for the
        /// follower the options below describe (a roller or flat face drawn with it).
        #[arg(long, value_name = "POINT", value_parser = crate::names::name)]
        cam: Option<String>,
        #[command(flatten)]
        follower: cam::FollowerArgs,
    },
    /// Dimensional synthesis: the design variables for which a point or an output meets targets.
    ///
    /// Dimensional synthesis: finds values of the design variables (`--vary`) for which the
    /// point `--path` passes through the targets, or the output of `--function` takes them, by
    /// Levenberg–Marquardt from `--starts` Halton starts on all cores (`--jobs`); verifies every
    /// candidate by a branch-safe sweep through the targets in order, and writes the ranked
    /// candidates with their defects (branch, circuit, order) as a table or CSV. Exit code 1
    /// when no candidate is valid. The declaration needs `#[kinloop(sensitivities)]`.
    Synth {
        /// The declaration (`.kl`), with `#[kinloop(sensitivities)]`.
        file: PathBuf,
        /// The targets, CSV: rows `x,y` (a path, inputs free along `--range`), `input,x,y` (a
        /// path at given inputs) or `input,output` (a function), numbers separated by commas
        /// (`.` the decimal point; quoted or not); `#` comments and a first line of names (a
        /// header) are skipped, numbers separated otherwise (`1;2`) are an error. A header's
        /// angle unit (`phi [deg]`, as `sweep --deg` writes it) must agree with `--deg`.
        #[arg(long, value_name = "FILE")]
        targets: PathBuf,
        /// The point whose path goes through the targets.
        #[arg(long, value_name = "POINT", conflicts_with = "function", value_parser = crate::names::name)]
        path: Option<String>,
        /// The function generated: the input and the unknown or output that follows it.
        #[arg(long, value_name = "INPUT:OUTPUT")]
        function: Option<String>,
        /// The design variables with their bounds, in the declaration's units (parameters, not
        /// converted by `--deg`); they need no value of their own (no default, none in
        /// `--params`).
        #[arg(long, value_name = "NAME=LO..HI,...", allow_hyphen_values = true)]
        vary: String,
        /// The input range of path targets without inputs (a full turn of an angle otherwise).
        #[arg(long, value_name = "LO..HI", allow_hyphen_values = true)]
        range: Option<String>,
        /// Halton starts of the local solve (at least 1, at most 1000000).
        #[arg(long, default_value_t = 64, allow_hyphen_values = true, value_parser = count::count)]
        starts: usize,
        /// The seed of the starts' sequence.
        #[arg(long, default_value_t = 0, allow_hyphen_values = true, value_parser = count::seed)]
        seed: u64,
        /// The most candidates written (at least 1): the best distinct designs the starts
        /// reached, valid ones first, each group by increasing RMS error. Fewer are written
        /// where the starts reached fewer distinct designs (one within a millionth of every
        /// variable's range of a design ranked before it is the same).
        #[arg(long, default_value_t = 10, allow_hyphen_values = true, value_parser = count::count)]
        keep: usize,
        /// Threads of the search (all cores by default, at most 1024); 1 runs the starts one after
        /// another. The candidates are the same whatever the number.
        #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = count::count)]
        jobs: Option<usize>,
        /// Angles in degrees (inputs, angle outputs, the range); otherwise radians.
        #[arg(long)]
        deg: bool,
        /// Parameter values, `name=value` separated by commas (the fixed ones; overriding the
        /// defaults), in the declaration's units: an angle parameter in radians, with or without
        /// `--deg`.
        #[arg(long, value_name = "NAME=VALUE,...")]
        params: Option<String>,
        /// CSV instead of a table.
        #[arg(long)]
        csv: bool,
        /// The largest error accepted at any target, in the unit the errors are written (a
        /// path's in its length unit, a function's in its output's: degrees for an angle with
        /// `--deg`): a candidate that misses a target by more is not valid (defect `miss`).
        /// Without it the best fit is valid however far it misses.
        #[arg(long, value_name = "ERROR", allow_hyphen_values = true, value_parser = crate::numbers::number)]
        max_error: Option<f64>,
    },
}

impl Command {
    /// What the command writes to standard output (`None`: nothing, its output goes to a
    /// file), as its failure to write names it.
    fn output(&self) -> Option<&'static str> {
        match self {
            Command::Check { .. } => Some("the report"),
            Command::Synth { .. } => Some("the candidates"),
            Command::Extremes { .. } => Some("the extremes"),
            Command::Animate { .. } => None,
            _ => Some("the table"),
        }
    }

    /// The files the command reads, and the files it writes by name with the option naming
    /// each.
    fn files(&self) -> (Vec<&Path>, Vec<(&'static str, &Path)>) {
        fn named<'a>(option: &'static str, path: &'a Option<PathBuf>) -> Vec<(&'static str, &'a Path)> {
            path.iter().map(|p| (option, p.as_path())).collect()
        }
        match self {
            Command::Sweep { decl, events, .. } | Command::Trace { decl, events, .. } => {
                (vec![&decl.file], named("--events", events))
            }
            Command::Dynamics { decl, flywheel, .. } => (vec![&decl.file], named("--flywheel", flywheel)),
            Command::Cam { decl, plot, .. } => (vec![&decl.file], named("--plot", plot)),
            // `--out -` is standard output, not a file.
            Command::Animate { decl, out, .. } if out.as_os_str() == "-" => (vec![&decl.file], Vec::new()),
            Command::Animate { decl, out, .. } => (vec![&decl.file], vec![("--out", out.as_path())]),
            Command::Check { decl }
            | Command::Solve { decl, .. }
            | Command::Simulate { decl, .. }
            | Command::Extremes { decl, .. } => (vec![&decl.file], Vec::new()),
            Command::Synth { file, targets, .. } => (vec![file, targets], Vec::new()),
        }
    }
}

/// The command line's arguments, a negative number after `--flat` joined to it
/// (`--flat=-inf`). `--flat` takes an optional angle, so it cannot take every value that starts
/// with `-` (it would take the next option for its angle), and clap takes only some negative
/// numbers for one: `--flat -inf` or `--flat -1e-400` was "unexpected argument '-i'", with the
/// advice to pass it after `--`, which makes it a file name. Joined, the angle is read as every
/// number is, and refused by the option's own checks.
fn arguments() -> Vec<std::ffi::OsString> {
    let mut args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    let negative = |a: &std::ffi::OsString| a.to_str().is_some_and(|v| v.starts_with('-') && v.parse::<f64>().is_ok());
    let mut k = 0;
    // What follows `--` is files, not options.
    while k + 1 < args.len() && args[k] != "--" {
        if args[k] == "--flat" && negative(&args[k + 1]) {
            let angle = args.remove(k + 1);
            args[k].push("=");
            args[k].push(angle);
        }
        k += 1;
    }
    args
}

/// A failure with its exit code; the message is already written.
pub struct Failed(pub u8);

fn main() -> ExitCode {
    // Found before `main`: output that would be lost is refused before anything is done.
    let closed = output::stdout_closed();
    // Not `Cli::parse`: its help and version that cannot be written would succeed.
    let cli = match Cli::try_parse_from(arguments()) {
        Ok(cli) => cli,
        Err(e) => return ExitCode::from(output::parser_stop(&e, closed)),
    };
    if let (true, Some(what)) = (closed, cli.command.output()) {
        return ExitCode::from(output::failed(what, output::closed_error()).0);
    }
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failed(code)) => ExitCode::from(code),
    }
}

fn run(cli: Cli) -> Result<(), Failed> {
    let (read, written) = cli.command.files();
    output::not_dash(&written)?;
    output::not_read(&read, &written)?;
    output::not_standard_output(&written)?;
    match cli.command {
        Command::Check { decl } => {
            let mut model = match decl.load() {
                Ok(model) => model,
                // Not evaluated at run time (said on standard error): its structure still says
                // which block is too large.
                Err(failed @ Failed(exit::UNAVAILABLE)) => {
                    let text = read_text(&decl.file)?;
                    if let Ok(structure) = Model::decomposition_of(&decl.file.display().to_string(), &text) {
                        output::text(&format!("{structure}\n"), "the report")?;
                    }
                    return Err(failed);
                }
                Err(failed) => return Err(failed),
            };
            // Written, not printed: `print!` panics where standard output cannot be written.
            output::text(&report::structure(&mut model), "the report")
        }
        Command::Solve { decl, at, deg } => {
            let mut model = decl.solvable()?;
            solve::run(&mut model, &at, deg)
        }
        Command::Sweep { decl, branch, from, to, samples, deg, events } => {
            let mut model = decl.solvable_on(&branch)?;
            let req = sweep::Request { from: &from, to: &to, samples, deg, events: events.as_deref() };
            sweep::run(&mut model, &req)
        }
        Command::Trace { decl, branch, from, to, ds, max_points, deg, events } => {
            let mut model = decl.solvable_on(&branch)?;
            let req = trace::Request { from: &from, to: &to, ds, max_points, deg, events: events.as_deref() };
            trace::run(&mut model, &req)
        }
        Command::Dynamics { decl, branch, speed, start, samples, delta, about, deg, flywheel } => {
            let mut model = decl.solvable_on(&branch)?;
            let req = dynamics::Request {
                speed,
                start,
                samples,
                delta,
                about: about.as_deref(),
                deg,
                flywheel: flywheel.as_deref(),
            };
            dynamics::run(&mut model, &req)
        }
        Command::Simulate { decl, branch, speed, start, time, torque, flywheel, samples, max_steps, deg } => {
            let mut model = decl.solvable_on(&branch)?;
            let req = simulate::Request { start, speed, time, torque, flywheel, samples, deg, max_steps };
            simulate::run(&mut model, &req)
        }
        Command::Cam { decl, branch, point, follower, start, samples, deg, plot } => {
            let mut model = decl.solvable_on(&branch)?;
            let req = cam::Request {
                point: &point,
                point_option: "--point",
                follower: &follower,
                start,
                samples,
                deg,
                plot: plot.as_deref(),
            };
            cam::run(&mut model, &req)
        }
        Command::Extremes { decl, branch, from, to, samples, deg, columns, table } => {
            let mut model = decl.solvable_on(&branch)?;
            let req = extremes::Request { from: &from, to: &to, samples, deg, columns: columns.as_deref(), table };
            extremes::run(&mut model, &req)
        }
        Command::Animate { decl, branch, from, to, samples, grid, deg, out, format, show, frames, cam, follower } => {
            let mut model = decl.solvable_on(&branch)?;
            let samples = samples.as_deref();
            let cam = cam.as_deref();
            let req = animate::Request {
                from: &from,
                to: &to,
                samples,
                grid,
                deg,
                out: &out,
                format,
                show: &show,
                frames,
                cam,
                follower: &follower,
            };
            animate::run(&mut model, &req)
        }
        Command::Synth {
            file,
            targets,
            path,
            function,
            vary,
            range,
            starts,
            seed,
            keep,
            jobs,
            deg,
            params,
            csv,
            max_error,
        } => {
            // Not yet complete: the design variables need no value of their own.
            let mut model = load(&file, params.as_deref())?;
            let req = synth::Request {
                targets: &targets,
                path: path.as_deref(),
                function: function.as_deref(),
                vary: &vary,
                range: range.as_deref(),
                starts,
                seed,
                keep,
                jobs,
                deg,
                csv,
                params: params.as_deref(),
                max_error,
            };
            synth::run(&mut model, &req)
        }
    }
}

/// Reads, checks and plans the declaration in `file`, with the parameters `params`; writes the
/// diagnostics (with a caret, coloured on a terminal) on failure and the warnings.
fn load(file: &Path, params: Option<&str>) -> Result<Model, Failed> {
    let text = read_text(file)?;
    let color = std::io::stderr().is_terminal();
    let mut model = match Model::read(&file.display().to_string(), &text) {
        Ok(m) => m,
        Err(ReadError::Rejected(d)) => {
            // The macro's words about its invocation and its Rust types said for a file.
            eprint!("{}", d.for_text().render(color));
            return Err(Failed(exit::DATA_ERR));
        }
        Err(e @ ReadError::Unsupported(_)) => {
            eprintln!("error: {e}");
            return Err(Failed(exit::UNAVAILABLE));
        }
    };
    if let Some(w) = model.warnings() {
        eprint!("{}", w.render(color));
    }
    if let Some(p) = params {
        params::apply(&mut model, p)?;
    }
    Ok(model)
}

/// [`load`] for a command that solves: every parameter needs a value, from the declaration's
/// defaults or from `params` (a usage error naming those missing otherwise).
fn solvable(file: &Path, params: Option<&str>) -> Result<Model, Failed> {
    let model = load(file, params)?;
    params::require_values(&model)?;
    params::require_precise_angles(&model)?;
    Ok(model)
}

/// The text of `file`, read up to one byte past the most a declaration may have
/// ([`MAX_SOURCE_BYTES`]): a large file named by mistake (a table, a device that never ends)
/// is refused after a megabyte, not read whole into memory and echoed in the diagnostic.
fn read_text(file: &Path) -> Result<String, Failed> {
    read_at_most(file, MAX_SOURCE_BYTES, || {
        eprintln!(
            "error: {} has more than {MAX_SOURCE_BYTES} bytes, more than a declaration read at run time may have \
             (a declaration is a few kilobytes)",
            file.display()
        );
        Failed(exit::DATA_ERR)
    })
}

/// The text of `file`, read up to one byte past `max` bytes: a larger file is refused there
/// with the failure `too_large` reports. A file that cannot be read, or is not UTF-8 text
/// (the place of its first byte that is not named), is [`exit::NO_INPUT`].
pub(crate) fn read_at_most(file: &Path, max: usize, too_large: impl FnOnce() -> Failed) -> Result<String, Failed> {
    let cannot = |e: std::io::Error| {
        // `-` is standard input by the usual convention, which no file option reads: "No such
        // file or directory" alone said nothing of it.
        match e.kind() == std::io::ErrorKind::NotFound && file.as_os_str() == "-" {
            true => eprintln!(
                "error: cannot read -: there is no file of that name, and `-` is not standard input here: name the \
                 file to read (or /dev/stdin for standard input)"
            ),
            false => eprintln!("error: cannot read {}: {e}", file.display()),
        }
        Failed(exit::NO_INPUT)
    };
    let mut bytes = Vec::new();
    let limit = max as u64 + 1;
    std::fs::File::open(file).and_then(|f| f.take(limit).read_to_end(&mut bytes)).map_err(cannot)?;
    if bytes.len() > max {
        return Err(too_large());
    }
    String::from_utf8(bytes).map_err(|e| {
        // Where the first byte that is not UTF-8 is: a binary, or text in another encoding.
        let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
        let start = good.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1);
        let column = String::from_utf8_lossy(&good[start..]).chars().count() + 1;
        let why = format!("it is not UTF-8 text (line {line}, column {column}): save it as UTF-8");
        cannot(std::io::Error::other(why))
    })
}
