//! `kinloop cam`: the disc cam that moves a declared follower as the declaration says, by
//! kinematic inversion over one turn of the cam shaft (the runtime's `analysis::cam`): its
//! pitch curve and working profile as CSV with units, the pressure angle and the sharpest point
//! of the profile against the roller on standard error, and the profile drawn with `--plot`.
//! With `--flat`, the cam of a flat-faced follower instead (the envelope of its face): the
//! profile, its radius of curvature, the contact's offset along the face and the pressure angle,
//! with the face's least width and the samples where the profile is not convex.

use crate::cam_drawn::FaceLine;
use crate::exit::usage;
use crate::numbers::between;
use crate::output::OutFile;
use crate::solve::{point, radians_of, solve_failed, start_failed};
use crate::{Failed, exit, samples};
use kinloop_model::{Count, Model};
use kinloop_runtime::analysis::cam::{
    CamExtremes, CamProfile, FlatFace, FlatFaceExtremes, FlatFaceProfile, FollowerSample, cam_extremes, cam_profile,
    flat_face_extremes, flat_face_profile,
};
use kinloop_runtime::dims::{KinBuf, KinState};
use kinloop_runtime::{Error, Number, QuantityKind, Table};
use kinloop_viz::plot::{self, Axis, Kind, Series};
use std::io::Write;
use std::path::Path;

/// How the cam's follower moves and what touches the cam: the options `kinloop cam` and
/// `kinloop animate --cam` share.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct FollowerArgs {
    /// A translating follower: the direction of its guide, `x,y`.
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true)]
    pub guide: Option<String>,
    /// A rocking follower: the pivot of its arm, `x,y`.
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true)]
    pub rocker: Option<String>,
    /// The cam's pivot, `x,y` (0,0 if not given).
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true)]
    pub pivot: Option<String>,
    /// The roller's radius (0: a knife edge, the default).
    #[arg(long, allow_hyphen_values = true, value_parser = crate::numbers::number)]
    pub roller: Option<f64>,
    /// A flat-faced follower instead of a roller: its face square to the guide through the
    /// follower's point (`--guide`), or parallel to the arm from the pivot to the point at
    /// `--face-offset` from the pivot (`--rocker`), turned by ANGLE (0 if not given; degrees
    /// with `--deg`); the profile is the face's envelope.
    #[arg(long, value_name = "ANGLE", num_args = 0..=1, default_missing_value = "0", allow_negative_numbers = true, value_parser = crate::numbers::number)]
    pub flat: Option<f64>,
    /// A rocking flat face's distance from the rocker's pivot, positive on the left of the
    /// face's direction (0: the face through the pivot).
    #[arg(long, value_name = "D", allow_hyphen_values = true, value_parser = crate::numbers::number)]
    pub face_offset: Option<f64>,
    /// The cam turns clockwise as the input grows (counter-clockwise otherwise).
    #[arg(long)]
    pub clockwise: bool,
}

impl FollowerArgs {
    /// The first of the options given, by its name: what a command that draws no cam refuses.
    pub fn any_given(&self) -> Option<&'static str> {
        [
            (self.guide.is_some(), "--guide"),
            (self.rocker.is_some(), "--rocker"),
            (self.pivot.is_some(), "--pivot"),
            (self.roller.is_some(), "--roller"),
            (self.flat.is_some(), "--flat"),
            (self.face_offset.is_some(), "--face-offset"),
            (self.clockwise, "--clockwise"),
        ]
        .into_iter()
        .find_map(|(given, name)| given.then_some(name))
    }
}

/// What `kinloop cam` was asked.
pub struct Request<'a> {
    /// The follower's point: a `point` of the declaration (the roller's centre).
    pub point: &'a str,
    /// The option that named the point, for the message where there is no such point.
    pub point_option: &'static str,
    /// How the follower moves and what touches the cam.
    pub follower: &'a FollowerArgs,
    /// The cam shaft's angle at the first sample (in the units of `deg`).
    pub start: f64,
    /// Samples over the turn, both ends included.
    pub samples: usize,
    /// Angles in degrees.
    pub deg: bool,
    /// Where to draw the pitch curve and the profile (SVG).
    pub plot: Option<&'a Path>,
}

/// The cam found by inversion ([`find`]): its pivot, its sense of turning, its shape and the
/// inputs of its samples in the units given.
pub struct Found {
    /// The cam's pivot, in the fixed frame.
    pub pivot: [f64; 2],
    /// The cam's angle per unit of input: 1 counter-clockwise, -1 clockwise.
    pub turn: f64,
    /// Each sample's input in the units given, between the ends as given (`86`, not
    /// `86.00000000000001` from the radians), as `kinloop sweep` writes its samples.
    pub inputs: Vec<f64>,
    /// Angles in degrees.
    pub deg: bool,
    /// The output columns of the follower's point (`NAME.x`, `NAME.y`).
    pub columns: (usize, usize),
    /// The cam for the follower asked for, with its checks.
    pub shape: Shape,
}

/// A cam for a roller (or knife edge), or for a flat face, each with its checks located
/// between the samples on the sweep's branch (what the summary on standard error reports).
pub enum Shape {
    /// For a roller of the radius the profile holds (0: a knife edge).
    Roller(CamProfile, CamExtremes),
    /// For a flat face, with where the face lies.
    Flat(FlatFaceProfile, FaceLine, FlatFaceExtremes),
}

impl Found {
    /// The working profile, in the cam's frame (origin at the pivot).
    pub fn profile(&self) -> &[[f64; 2]] {
        match &self.shape {
            Shape::Roller(cam, _) => &cam.profile,
            Shape::Flat(cam, ..) => &cam.profile,
        }
    }

    /// The cam's checks, on standard error.
    pub fn report(&self) {
        match &self.shape {
            Shape::Roller(cam, checks) => report(cam, checks, &self.inputs, self.deg),
            Shape::Flat(cam, _, checks) => report_flat(cam, checks, &self.inputs, self.deg),
        }
    }
}

/// Sweeps one turn of the cam shaft from `--start`, finds the cam by inversion and writes its
/// table to standard output, its checks to standard error and its drawing to `--plot`.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    // The drawing is SVG: a name of another format's extension (`cam.png`) held SVG.
    if let Some(ext) = req.plot.and_then(Path::extension).filter(|e| !e.eq_ignore_ascii_case("svg")) {
        return Err(usage(format!(
            "--plot {}: the drawing is SVG, not .{}: name it .svg",
            req.plot.unwrap_or(Path::new("")).display(),
            ext.to_string_lossy()
        )));
    }
    input_column(model)?;
    // The plot's file created first, as `--events` and `--flywheel` are: a path that cannot be
    // written stops before any output. Removed again if no drawing comes to be written into it.
    let plot = crate::output::created(req.plot, "the plot")?;
    written(model, req, plot)
}

/// [`run`] once the plot's file (if any) is created: the cam found, its drawing made, then the
/// table written and the drawing into `plot`.
fn written(model: &mut Model, req: &Request, plot: Option<OutFile>) -> Result<(), Failed> {
    let found = match find(model, req) {
        Ok(found) => found,
        Err(e) => {
            if let Some(plot) = plot {
                plot.abandon();
            }
            return Err(e);
        }
    };
    found.report();
    let input = &model.inputs()[0];
    let (table, curves) = match found.shape {
        Shape::Flat(cam, ..) => (flat_table(&cam, input, &found.inputs, req.deg), vec![("cam profile", cam.profile)]),
        Shape::Roller(cam, _) => {
            (table(&cam, input, &found.inputs, req.deg), vec![("pitch curve", cam.pitch), ("cam profile", cam.profile)])
        }
    };
    let svg = match plot {
        Some(file) => match draw(&curves, model.name()) {
            Ok(svg) => Some((file, svg)),
            Err(e) => {
                file.abandon();
                return Err(e);
            }
        },
        None => None,
    };
    if let Err(e) = crate::output::table(&table, "the table") {
        if let Some((file, _)) = svg {
            file.abandon();
        }
        return Err(e);
    }
    let Some((file, svg)) = svg else { return Ok(()) };
    let what = format!("the plot {}", req.plot.unwrap_or(Path::new("")).display());
    file.write(&what, |mut file| file.write_all(svg.as_bytes()).and_then(|()| file.flush()))
}

/// Sweeps one turn of the cam shaft from `req.start` and finds the cam by inversion of the
/// follower's motion (`req.plot` is not read).
pub fn find(model: &mut Model, req: &Request) -> Result<Found, Failed> {
    let name = model.name().to_string();
    one_angle_input(model)?;
    if req.samples < 3 {
        return Err(usage(format!("--samples {} is too few: a turn needs at least 3", req.samples)));
    }
    samples::check(req.samples)?;
    let fa = req.follower;
    let roller = fa.roller.unwrap_or(0.0);
    if !(roller >= 0.0 && roller.is_finite()) {
        return Err(usage(format!("--roller {} must be a finite number, not negative", Number(roller))));
    }
    if !req.start.is_finite() {
        return Err(usage(format!("--start {} must be a finite number", Number(req.start))));
    }
    // Degrees so many turns out that their radians round by more than a solve's precision are
    // refused, as the other commands refuse them: the cam was found at the rounded inputs.
    if req.deg {
        crate::solve::radians_of(req.start, "--start")?;
    }
    let columns = point_columns(model, req.point, req.point_option)?;
    let follower = match (fa.guide.as_deref(), fa.rocker.as_deref()) {
        (Some(g), None) => Follower::Translating(direction(g, "--guide")?),
        (None, Some(r)) => Follower::Rocking(point(r, "--rocker")?),
        _ => {
            return Err(usage(
                "give the follower's motion: --guide X,Y (the direction of a translating follower's guide) or \
                 --rocker X,Y (the pivot of a rocking follower's arm), not both",
            ));
        }
    };
    let pivot = point(fa.pivot.as_deref().unwrap_or("0,0"), "--pivot")?;
    let angle = if req.deg { 180.0 / std::f64::consts::PI } else { 1.0 };
    let face = flat_face(fa, &follower, req.deg)?;
    let start = req.start / angle;
    let kinds = model.input_kinds().to_vec();
    let failed = |e: Error| solve_failed(&name, e, &kinds, req.deg);
    let mut guess = vec![0.0; model.unknowns().len()];
    model.guess(&[start], &mut guess).map_err(|e| {
        eprintln!("error: {name}: {e}");
        Failed(exit::SOLVE_FAILED)
    })?;
    let turn = if fa.clockwise { -1.0 } else { 1.0 };
    let end = start + std::f64::consts::TAU;
    // Far out, a turn is lost to rounding (the start is finite): the sweep would be told `to`
    // equals `from`.
    if end - start <= 6.0 {
        return Err(usage(format!(
            "a turn of the cam from {} is lost to rounding at that size: start it nearer 0",
            Number(req.start)
        )));
    }
    let sweep = model.sweep(&[start], &[end], req.samples, &guess).map_err(|e| match e {
        Error::InvalidArgument(_) => usage(format!("{name}: {e}")),
        e => failed(e),
    })?;
    let sample_of = |s: &KinBuf| {
        let (x, y) = columns;
        let p = [s.out()[x], s.out()[y]];
        FollowerSample {
            cam: [turn * s.x()[0], turn, 0.0],
            point: [p, [s.dout(x)[0], s.dout(y)[0]], [s.d2out(x, 0, 0), s.d2out(y, 0, 0)]],
            direction: follower.direction(p),
        }
    };
    let mut follower_samples = Vec::with_capacity(req.samples);
    // Each sample's input (radians) and unknowns: where the checks between the samples start
    // their steps from.
    let (mut xs, mut qs) = (Vec::with_capacity(req.samples), Vec::new());
    let mut stopped = None;
    for state in sweep {
        let s = match state {
            Ok(s) => s,
            Err(e) => {
                stopped = Some(e);
                break;
            }
        };
        follower_samples.push(sample_of(&s));
        xs.push(s.x()[0]);
        qs.extend_from_slice(s.q());
    }
    // The sweep, done, gives the model back: where it could not start, where it assembles.
    if let Some(e) = stopped {
        return Err(start_failed(model, &name, e, (&[start], None), req.deg));
    }
    // Each sample's input in the units given, between the ends as given (`86`, not
    // `86.00000000000001` from the radians), as `kinloop sweep` writes its samples: in degrees
    // the decimals of the ends' ([`between`]: `21.7`, not `21.700000000000003`, the sample
    // `--start 0.1` and 101 samples put there).
    let last = req.samples - 1;
    let inputs: Vec<f64> = match req.deg {
        true => (0..req.samples).map(|k| between(req.start, req.start + 360.0, k, last)).collect(),
        false => (0..req.samples).map(|k| req.start + std::f64::consts::TAU * k as f64 / last as f64).collect(),
    };
    let points: Vec<[f64; 2]> = follower_samples.iter().map(|s| s.point[0]).collect();
    let sample = |k: usize| format!("sample {k} (input {}{})", Number(inputs[k]), if req.deg { " deg" } else { "" });
    let point_name = format!("the follower's point `{}`", req.point);
    if let Follower::Rocking(a) = follower {
        apart(&points, a, &format!("--rocker {}", fa.rocker.as_deref().unwrap_or_default()), &point_name, &sample)?;
    }
    let pivot_option = match fa.pivot.as_deref() {
        Some(p) => format!("--pivot {p}"),
        None => "the cam's pivot 0,0 (--pivot not given)".to_string(),
    };
    apart(&points, pivot, &pivot_option, &point_name, &sample)?;
    follows(&points, &follower, fa, &point_name)?;
    // The profile's refusals are of the follower given for this motion (a flat face through the
    // cam's pivot, an offset beyond what f64 relates to the arm, a face that stops turning
    // against the cam), as the checks above are: usage errors naming the options and the
    // sample's input, not the library's function with exit code 1 ("invalid argument:
    // flat_face_profile: at sample 77 ...").
    let refused = |e: Error| match e {
        Error::InvalidArgument(why) => {
            let why = ["flat_face_profile: ", "cam_profile: "]
                .iter()
                .fold(why.as_str(), |w, p| w.strip_prefix(p).unwrap_or(w));
            usage(format!(
                "{name}: no cam for the follower given ({}): {}",
                follower_options(fa),
                with_inputs(why, &sample)
            ))
        }
        e => {
            eprintln!("error: {name}: {e}");
            Failed(exit::SOLVE_FAILED)
        }
    };
    // The checks between the samples: the follower's sample at any input, stepped there on the
    // sweep's branch from the nearest sample (as `kinloop extremes` refines an extreme).
    let n = qs.len() / xs.len().max(1);
    let mut eval = |x: f64| -> Result<FollowerSample, Error> {
        let i = xs.partition_point(|&v| v < x);
        let k = match i.checked_sub(1) {
            Some(j) if i == xs.len() || x - xs[j] <= xs[i] - x => j,
            _ => i,
        };
        if xs[k] == x {
            return Ok(follower_samples[k]);
        }
        let mut step = model.sweep(&[xs[k]], &[x], 2, &qs[k * n..(k + 1) * n])?;
        let state = step.nth(1).unwrap_or_else(|| Err(Error::InvalidArgument("an empty refinement sweep".into())))?;
        Ok(sample_of(&state))
    };
    let between = |e: Error| match e {
        Error::InvalidArgument(why) => usage(format!(
            "{name}: no cam for the follower given ({}): between the samples: {}",
            follower_options(fa),
            ["flat_face_profile: ", "cam_profile: "].iter().fold(why.as_str(), |w, p| w.strip_prefix(p).unwrap_or(w))
        )),
        e => failed(e),
    };
    let shape = match face {
        Some(face) => {
            let guide = match follower {
                Follower::Translating(g) => g,
                Follower::Rocking(_) => [0.0, 0.0],
            };
            let cam = flat_face_profile(&follower_samples, pivot, face).map_err(refused)?;
            // The first sample's side for all: the face cannot pass through the cam's pivot.
            let line = FaceLine { face, guide, away: 1.0 };
            let away = follower_samples.first().map_or(1.0, |s| line.side_away(s.point[0], pivot));
            let checks = flat_face_extremes(&xs, &follower_samples, pivot, face, &mut eval).map_err(between)?;
            Shape::Flat(cam, FaceLine { away, ..line }, checks)
        }
        None => {
            let cam = cam_profile(&follower_samples, pivot, roller).map_err(refused)?;
            Shape::Roller(cam, cam_extremes(&xs, &follower_samples, pivot, roller, &mut eval).map_err(between)?)
        }
    };
    Ok(Found { pivot, turn, inputs, deg: req.deg, columns, shape })
}

/// The follower's options as given (`--rocker -40,140 --flat --face-offset -135`), the cam's
/// pivot with them, for a message about the cam they make.
pub(crate) fn follower_options(fa: &FollowerArgs) -> String {
    let mut given = Vec::new();
    let mut push = |option: &str, value: Option<String>| given.push(format!("{option} {}", value.unwrap_or_default()));
    if let Some(g) = &fa.guide {
        push("--guide", Some(g.clone()));
    }
    if let Some(r) = &fa.rocker {
        push("--rocker", Some(r.clone()));
    }
    if let Some(r) = fa.roller {
        push("--roller", Some(Number(r).to_string()));
    }
    if let Some(t) = fa.flat {
        push("--flat", Some(Number(t).to_string()));
    }
    if let Some(d) = fa.face_offset {
        push("--face-offset", Some(Number(d).to_string()));
    }
    match &fa.pivot {
        Some(p) => push("--pivot", Some(p.clone())),
        None => given.push("the cam's pivot 0,0".to_string()),
    }
    given.join(", ")
}

/// `text` with each `sample K` followed by its input (`sample(K)`: `sample 77 (input 1.34)`).
fn with_inputs(text: &str, sample: &dyn Fn(usize) -> String) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("sample ") {
        out += &rest[..at];
        let after = &rest[at + "sample ".len()..];
        let digits = after.bytes().take_while(u8::is_ascii_digit).count();
        match after[..digits].parse::<usize>() {
            Ok(k) if !after[digits..].starts_with('\'') => out += &sample(k),
            _ => out += &rest[at..at + "sample ".len() + digits],
        }
        rest = &after[digits..];
    }
    out + rest
}

/// The names of the columns the table writes of its own beside the input (and the curves' names
/// its points' columns are named by): an input named as one of them would name two columns
/// alike, or take a curve's unit.
const OWN_COLUMNS: [&str; 6] = ["pitch", "profile", "pitch_radius", "radius", "offset", "pressure_angle"];

/// Refuses an input named as one of the table's own columns ([`OWN_COLUMNS`]), before the
/// sweep: its name heads the table's first column, as every command's table names it.
fn input_column(model: &Model) -> Result<(), Failed> {
    let own = crate::own_columns::Own {
        command: "kinloop cam",
        columns: &OWN_COLUMNS,
        beside: "input's",
        rename_to: "",
        written: "its table",
    };
    let inputs = model.inputs().iter().map(|n| ("input", n.as_str()));
    crate::own_columns::check(&own, model.name(), inputs)
}

/// Refuses a model whose inputs are not one angle: the cam turns with the one input.
fn one_angle_input(model: &Model) -> Result<(), Failed> {
    if model.inputs().len() != 1 || model.input_kinds()[0] != QuantityKind::Angle {
        return Err(usage(format!(
            "a cam turns with the input: {} must have one input, an angle (its inputs: {})",
            model.name(),
            model.inputs().join(", ")
        )));
    }
    Ok(())
}

/// The flat face asked for with `--flat` (and `--face-offset`), `None` for a roller; its tilt
/// given in degrees with `deg`.
fn flat_face(req: &FollowerArgs, follower: &Follower, deg: bool) -> Result<Option<FlatFace>, Failed> {
    let Some(tilt) = req.flat else {
        return match req.face_offset {
            Some(_) => Err(usage("--face-offset places a flat face: give it with --flat")),
            None => Ok(None),
        };
    };
    if req.roller.is_some() {
        return Err(usage("give --roller R (a roller follower) or --flat (a flat-faced one), not both"));
    }
    let shown = |v: f64| Number(v).to_string();
    // Said as what it is: `--flat nan` was told to tilt the face less than a quarter turn.
    if !tilt.is_finite() {
        return Err(usage(format!("--flat {}: the face's tilt must be a finite angle (0 if square)", shown(tilt))));
    }
    // Degrees so many turns out that their radians round by more than a solve's precision are
    // refused as `--start` refuses them: `--flat 1e300 --deg` tilted a rocking face by the
    // rounding's angle without a word.
    let tilt_rad = if deg { radians_of(tilt, "--flat")? } else { tilt };
    match *follower {
        Follower::Translating(_) => {
            if req.face_offset.is_some() {
                return Err(usage(
                    "--face-offset places a rocking follower's face from its pivot: a translating one's face passes \
                     through its point (use --rocker X,Y, or declare the face's point)",
                ));
            }
            if tilt_rad.abs() >= std::f64::consts::FRAC_PI_2 {
                return Err(usage(format!(
                    "--flat {}: a translating follower's face must be tilted less than a quarter turn from square to \
                     its guide",
                    shown(tilt)
                )));
            }
            Ok(Some(FlatFace::Translating { tilt: tilt_rad }))
        }
        Follower::Rocking(pivot) => {
            let offset = req.face_offset.unwrap_or(0.0);
            if !offset.is_finite() {
                return Err(usage(format!("--face-offset {} must be a finite number", shown(offset))));
            }
            Ok(Some(FlatFace::Rocking { pivot, offset, tilt: tilt_rad }))
        }
    }
}

/// How the follower's point can move: along a guide, or square to its rocker's arm.
enum Follower {
    /// Along the direction given.
    Translating([f64; 2]),
    /// About the pivot given.
    Rocking([f64; 2]),
}

impl Follower {
    /// The direction the point `p` can move in.
    fn direction(&self, p: [f64; 2]) -> [f64; 2] {
        match *self {
            Follower::Translating(d) => d,
            Follower::Rocking(a) => [-(p[1] - a[1]), p[0] - a[0]],
        }
    }
}

/// The largest deviation of the follower's point from the motion the follower allows, as a
/// fraction of the motion's size (the stroke along a guide, the distance from a rocker's pivot),
/// that is still taken for that motion. The points are the sweep's: solved to 1e-12 of the
/// terms of their loops (`NewtonConfig::residual_tol`), at worst to the 1e-9 that Newton accepts
/// as the rounding floor near a limit position, so a point declared on its guide (or its arc)
/// is off it by at most about 1e-9 of the mechanism's lengths. A cam's stroke is at least a
/// thousandth of those lengths, so 1e-6 of the stroke is above that rounding: what tells a
/// pivot at the point, and the line or arc the point moves on (whose follower is then named to
/// the digits that pass [`follows`]).
const MOTION_TOL: f64 = 1e-6;

/// Refuses a `centre` (a rocker's pivot, the cam's pivot, given by `option`) at the follower's
/// point at some sample (`sample` names it): a rocker's arm has no direction there, and the cam
/// would have no radius. "At" is within [`MOTION_TOL`] of the point's largest distance from it.
fn apart(
    points: &[[f64; 2]],
    centre: [f64; 2],
    option: &str,
    point: &str,
    sample: &dyn Fn(usize) -> String,
) -> Result<(), Failed> {
    let distance = |p: &[f64; 2]| (p[0] - centre[0]).hypot(p[1] - centre[1]);
    let reach = points.iter().map(distance).fold(0.0, f64::max);
    let Some(k) = points.iter().position(|p| distance(p) <= MOTION_TOL * reach) else { return Ok(()) };
    let what = match option.starts_with("--rocker") {
        true => "the pivot of a rocking follower's arm is off the point's path: give the pivot the arm turns about",
        false => "the cam turns about a pivot the point stays away from: give a --pivot inside the point's path",
    };
    Err(usage(format!(
        "{option} is at {point} at {}: {what} (the point {})",
        sample(k),
        Motion::of(points).described()
    )))
}

/// The largest deviation of the follower's point from the follower given, as a fraction of the
/// motion's size, that [`follows`] accepts. A follower a little off the point's motion (a guide
/// typed to three or four digits, `0.7071,0.7071`; a pivot measured off a drawing) turns the
/// contact's normal against the follower by about that fraction in radians: the pressure angle
/// by at most a milliradian (0.06 degrees) here, below what a cam's design reads from it. A
/// follower given wrong is off by a sizeable fraction of the motion.
const FOLLOWER_TOL: f64 = 1e-3;

/// Refuses a follower whose motion is not the point's (within [`FOLLOWER_TOL`]): a guide the
/// point does not move along, a pivot it does not keep its distance from. The cam found would
/// be for the motion declared, its pressure angles for the follower given: nonsense.
fn follows(points: &[[f64; 2]], follower: &Follower, fa: &FollowerArgs, point: &str) -> Result<(), Failed> {
    let p0 = points[0];
    let (option, off, size) = match *follower {
        Follower::Translating(g) => {
            let n = g[0].hypot(g[1]);
            let across = |p: &[f64; 2]| ((p[0] - p0[0]) * g[1] - (p[1] - p0[1]) * g[0]).abs() / n;
            let stroke = points.iter().map(|p| (p[0] - p0[0]).hypot(p[1] - p0[1])).fold(0.0, f64::max);
            let off = points.iter().map(across).fold(0.0, f64::max);
            (format!("--guide {}", fa.guide.as_deref().unwrap_or_default()), off, stroke)
        }
        Follower::Rocking(a) => {
            let radii: Vec<f64> = points.iter().map(|p| (p[0] - a[0]).hypot(p[1] - a[1])).collect();
            let (lo, hi) = radii.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| (lo.min(r), hi.max(r)));
            (format!("--rocker {}", fa.rocker.as_deref().unwrap_or_default()), hi - lo, hi)
        }
    };
    if off <= FOLLOWER_TOL * size {
        return Ok(());
    }
    let how = match follower {
        Follower::Translating(_) => "does not move along this guide: it leaves the guide's line by",
        Follower::Rocking(_) => "does not turn about this pivot: its distance from it varies by",
    };
    let motion = Motion::of(points);
    Err(usage(format!(
        "{option}: {point} {how} {} over {}: it {}; give {}",
        Number(off),
        match follower {
            Follower::Translating(_) => format!("a stroke of {}", Number(size)),
            Follower::Rocking(_) => format!("a distance of {}", Number(size)),
        },
        motion.described(),
        motion.follower()
    )))
}

/// How a point moves over the samples, within [`MOTION_TOL`]: what [`follows`] says where the
/// follower given is not its motion.
enum Motion {
    /// It does not move.
    Still,
    /// Along a line, in the direction given (a unit vector).
    Line([f64; 2]),
    /// On an arc about the centre given, of the radius given.
    Arc([f64; 2], f64),
    /// Along a curve that is neither.
    Curve,
}

impl Motion {
    /// The motion of `points`: the line of the chord from the first to the farthest, or the
    /// circle through those and the point farthest from that line.
    fn of(points: &[[f64; 2]]) -> Motion {
        let p0 = points[0];
        let from = |p: &[f64; 2]| [p[0] - p0[0], p[1] - p0[1]];
        let far = |f: &dyn Fn(&[f64; 2]) -> f64| {
            points.iter().map(|p| (f(p), *p)).fold((0.0, p0), |best, c| if c.0 > best.0 { c } else { best })
        };
        let (stroke, pf) = far(&|p| from(p)[0].hypot(from(p)[1]));
        if stroke == 0.0 {
            return Motion::Still;
        }
        let u = [from(&pf)[0] / stroke, from(&pf)[1] / stroke];
        let (off, pm) = far(&|p| (u[0] * from(p)[1] - u[1] * from(p)[0]).abs());
        if off <= MOTION_TOL * stroke {
            // The sign that makes the larger component positive: `0,1`, not `-0,-1`.
            let s = if u[0].abs() > u[1].abs() { u[0].signum() } else { u[1].signum() };
            return Motion::Line([s * u[0] + 0.0, s * u[1] + 0.0]);
        }
        // The circumcentre of p0, pf and pm, relative to p0, in units of the stroke: the squares
        // of the points' distances overflowed (or underflowed) for a mechanism of 1e150 (1e-110)
        // units, and an arc read as "neither a line nor an arc".
        let (b, c) = (from(&pf).map(|v| v / stroke), from(&pm).map(|v| v / stroke));
        let d = 2.0 * (b[0] * c[1] - b[1] * c[0]);
        let (bb, cc) = (b[0] * b[0] + b[1] * b[1], c[0] * c[0] + c[1] * c[1]);
        let o = [stroke * ((c[1] * bb - b[1] * cc) / d), stroke * ((b[0] * cc - c[0] * bb) / d)];
        let r = o[0].hypot(o[1]);
        let centre = [p0[0] + o[0], p0[1] + o[1]];
        let off = points.iter().map(|p| ((p[0] - centre[0]).hypot(p[1] - centre[1]) - r).abs()).fold(0.0, f64::max);
        if r.is_finite() && off <= MOTION_TOL * r { Motion::Arc(centre, r) } else { Motion::Curve }
    }

    /// The motion in words, after "the point".
    fn described(&self) -> String {
        match self {
            Motion::Still => "does not move".into(),
            Motion::Line(u) => format!("moves along the line of direction {}", pair(*u, 1.0)),
            Motion::Arc(c, r) => format!("moves on an arc about {} of radius {}", pair(*c, *r), rounded(*r, *r)),
            Motion::Curve => "moves along a curve that is neither a line nor an arc".into(),
        }
    }

    /// The follower to give for the motion.
    fn follower(&self) -> String {
        match self {
            Motion::Line(u) => format!("--guide {} (a translating follower)", pair(*u, 1.0)),
            Motion::Arc(c, r) => format!("--rocker {} (a rocking follower)", pair(*c, *r)),
            Motion::Still | Motion::Curve => {
                "the point of a follower: one that moves along a line (--guide) or on an arc (--rocker)".into()
            }
        }
    }
}

/// `x,y` rounded to [`rounded`] of `scale`.
fn pair(v: [f64; 2], scale: f64) -> String {
    format!("{},{}", rounded(v[0], scale), rounded(v[1], scale))
}

/// `v` with the digits that [`MOTION_TOL`] of `scale` tells apart and one more (nine
/// significant of `scale`): `0,1` for a direction found as `[1e-17, 1]`, `-40,140` for a pivot
/// found as `-39.99999999999997,140`; given back, it passes the check. Far from unit size (a
/// `scale` beyond a thousandth to a billion) in `e` notation, as numbers are written elsewhere:
/// positional notation wrote a hundred digits for a mechanism of 1e100 units.
fn rounded(v: f64, scale: f64) -> String {
    let magnitude = scale.abs().log10().floor();
    if (-3.0..=9.0).contains(&magnitude) {
        let decimals = (8.0 - magnitude).max(0.0) as usize;
        let text = format!("{v:.decimals$}");
        let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { &text };
        return if text == "-0" { "0".into() } else { text.into() };
    }
    // The significant digits of `v` that nine of `scale` keep; none where `v` is below them.
    let digits = 8.0 + if v == 0.0 { magnitude } else { v.abs().log10().floor() } - magnitude;
    if digits.is_nan() || digits < 0.0 {
        return "0".into();
    }
    let text = format!("{v:.*e}", digits.min(16.0) as usize);
    text.parse::<f64>().map_or(text, |r| Number(r + 0.0).to_string())
}

/// The output columns `NAME.x`, `NAME.y` of the point `name`, given to the option `option`.
pub(crate) fn point_columns(model: &Model, name: &str, option: &str) -> Result<(usize, usize), Failed> {
    let outputs = model.outputs();
    let at = |c: &str| outputs.iter().position(|o| o == c);
    match (at(&format!("{name}.x")), at(&format!("{name}.y"))) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => {
            let points: Vec<&str> = outputs.iter().filter_map(|o| o.strip_suffix(".x")).collect();
            // Given nothing (an unset shell variable): said so, where `{option} {name}: ... has
            // no point of that name` read `--point : ...`.
            if name.trim().is_empty() && !points.is_empty() {
                let what = format!("the name of a point of {} (its points: {})", model.name(), points.join(", "));
                return Err(crate::solve::empty(option, &what));
            }
            // A mechanism of no point: "its points: none" said nothing of how to have one.
            if points.is_empty() {
                return Err(usage(format!(
                    "{option} {name}: {} declares no point: declare it in the declaration, `point {name} = ...;` \
                     (a sum of the loops' vectors, e.g. `r @ phi`)",
                    model.name()
                )));
            }
            Err(usage(format!(
                "{option} {name}: {} has no point of that name{} (its points: {})",
                model.name(),
                crate::names::look_alike(name, &points),
                points.join(", ")
            )))
        }
    }
}

/// A direction `x,y` of the option `option`: two finite numbers, not both zero, as the unit
/// vector along them. Only the direction counts: taken to unit length (by its larger component
/// first, which neither overflows nor underflows), the products formed with it stay in range
/// whatever size it was given at (`1e308,1e308` overflowed the point's distance from the
/// guide's line to `inf`; `1e-320,1e-320`, subnormal, lost digits of it).
fn direction(spec: &str, option: &str) -> Result<[f64; 2], Failed> {
    let d = point(spec, option)?;
    if d == [0.0, 0.0] {
        return Err(usage(format!("{option} {spec} has no direction: give a vector along the guide, e.g. 0,1")));
    }
    let m = d[0].abs().max(d[1].abs());
    let d = [d[0] / m, d[1] / m];
    let n = d[0].hypot(d[1]);
    Ok([d[0] / n, d[1] / n])
}

/// The cam's checks on standard error: the largest pressure angle, the sharpest convex point
/// of the pitch curve and whether the roller undercuts the profile, each located between the
/// samples (`checks`); the samples where it is undercut (`cam`'s).
fn report(cam: &CamProfile, checks: &CamExtremes, inputs: &[f64], deg: bool) {
    let (unit, angle) = if deg { ("°", 180.0 / std::f64::consts::PI) } else { (" rad", 1.0) };
    let roller = checks.roller;
    let alpha = checks.max_pressure_angle;
    eprintln!("cam: largest pressure angle {}{unit} at {}{unit}", Number(alpha.value * angle), Number(alpha.x * angle));
    match checks.min_convex_radius {
        Some(sharpest) => eprintln!(
            "cam: sharpest convex point of the pitch curve at {}{unit}: radius of curvature {}, of the profile {}",
            Number(sharpest.x * angle),
            Number(sharpest.value),
            Number(sharpest.value - roller)
        ),
        None => eprintln!("cam: the pitch curve is nowhere convex"),
    }
    let undercut = cam.undercut();
    let advice = "use a smaller roller or a larger cam";
    match (undercut.first(), undercut.last(), checks.min_convex_radius) {
        (Some(&a), Some(&b), _) => eprintln!(
            "cam: UNDERCUT at {} (the first at {}{unit}, the last at {}{unit}): the pitch curve is sharper \
             there than the roller (radius {}); {advice}",
            Count(undercut.len(), "sample"),
            Number(inputs[a]),
            Number(inputs[b]),
            Number(roller)
        ),
        (_, _, Some(sharpest)) if checks.undercut() => eprintln!(
            "cam: UNDERCUT between the samples, at {}{unit} (no sample falls where it is): the pitch curve is \
             sharper there than the roller (radius {}); {advice}",
            Number(sharpest.x * angle),
            Number(roller)
        ),
        _ => eprintln!("cam: no undercut with a roller of radius {}", Number(roller)),
    }
}

/// A flat-faced follower's checks on standard error: the largest pressure angle, the smallest
/// radius of curvature of the profile and the face's least width, each located between the
/// samples (`checks`); the samples where the profile is not convex (`cam`'s).
fn report_flat(cam: &FlatFaceProfile, checks: &FlatFaceExtremes, inputs: &[f64], deg: bool) {
    let (unit, angle) = if deg { ("°", 180.0 / std::f64::consts::PI) } else { (" rad", 1.0) };
    let alpha = checks.max_pressure_angle;
    eprintln!("cam: largest pressure angle {}{unit} at {}{unit}", Number(alpha.value * angle), Number(alpha.x * angle));
    let sharpest = checks.min_radius;
    eprintln!(
        "cam: smallest radius of curvature of the profile {} at {}{unit}",
        Number(sharpest.value),
        Number(sharpest.x * angle)
    );
    eprintln!(
        "cam: face width at least {} (the contact from {} to {} along the face)",
        Number(checks.face_width()),
        Number(checks.min_offset.value),
        Number(checks.max_offset.value)
    );
    let bad = cam.not_convex();
    let advice = "a flat face cannot follow the law; use a larger base circle or a gentler law";
    match (bad.first(), bad.last()) {
        (Some(&a), Some(&b)) => eprintln!(
            "cam: NOT CONVEX at {} (the first at {}{unit}, the last at {}{unit}): the face's envelope folds \
             there and {advice}",
            Count(bad.len(), "sample"),
            Number(inputs[a]),
            Number(inputs[b])
        ),
        _ if !checks.convex() => eprintln!(
            "cam: NOT CONVEX between the samples, at {}{unit} (no sample falls where it is): the face's envelope \
             folds there and {advice}",
            Number(sharpest.x * angle)
        ),
        _ => eprintln!("cam: the profile is convex at every sample and between them"),
    }
}

/// The cam as a table: per sample the input `input` (in the units given, under its name as every
/// command's table has it, where it was `input`), the pitch curve's and the profile's points in
/// the cam's frame, the pitch curve's radius of curvature and the pressure angle.
fn table(cam: &CamProfile, input: &str, inputs: &[f64], deg: bool) -> Table {
    let (angle, a) = if deg { (180.0 / std::f64::consts::PI, "deg") } else { (1.0, "rad") };
    let columns = [input, "pitch.x", "pitch.y", "profile.x", "profile.y", "pitch_radius", "pressure_angle"];
    let mut t = Table::new(columns.iter().map(|c| c.to_string()).collect());
    for (k, &x) in inputs.iter().enumerate() {
        let ([px, py], [cx, cy]) = (cam.pitch[k], cam.profile[k]);
        t.push(vec![x, px, py, cx, cy, cam.pitch_radius[k], cam.pressure_angle[k] * angle]);
    }
    let length = QuantityKind::Length.unit();
    t.with_units(&[(input, a), ("pitch", length), ("profile", length), ("pitch_radius", length), ("pressure_angle", a)])
}

/// A flat-faced follower's cam as a table: per sample the input `input` (in the units given, as
/// [`table`] has it), the profile's point in the cam's frame, its radius of curvature, the
/// contact's offset along the face and the pressure angle.
fn flat_table(cam: &FlatFaceProfile, input: &str, inputs: &[f64], deg: bool) -> Table {
    let (angle, a) = if deg { (180.0 / std::f64::consts::PI, "deg") } else { (1.0, "rad") };
    let columns = [input, "profile.x", "profile.y", "radius", "offset", "pressure_angle"];
    let mut t = Table::new(columns.iter().map(|c| c.to_string()).collect());
    for (k, &x) in inputs.iter().enumerate() {
        let [cx, cy] = cam.profile[k];
        t.push(vec![x, cx, cy, cam.radius[k], cam.offset[k], cam.pressure_angle[k] * angle]);
    }
    let length = QuantityKind::Length.unit();
    t.with_units(&[(input, a), ("profile", length), ("radius", length), ("offset", length), ("pressure_angle", a)])
}

/// The named curves (the pitch curve and the profile, or the profile alone) drawn as SVG, the
/// cam's pivot marked.
fn draw(curves: &[(&str, Vec<[f64; 2]>)], name: &str) -> Result<String, Failed> {
    let length = Kind::length(QuantityKind::Length.unit());
    let curve = |points: &[[f64; 2]]| points.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>();
    let series: Vec<Series> =
        curves.iter().map(|(label, points)| Series::new(label, length.clone(), curve(points))).collect();
    let title = format!("{name}: the cam by inversion of the follower's motion");
    plot::xy_chart_svg(&title, &Axis::new("x", length.clone()), &Axis::new("y", length), &series, &[(0.0, 0.0)])
        .map_err(|e| {
            eprintln!("error: {name}: cannot draw the cam: {e}");
            Failed(exit::SOLVE_FAILED)
        })
}
