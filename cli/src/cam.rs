//! `kinloop cam`: the disc cam that moves a declared follower as the declaration says, by
//! kinematic inversion over one turn of the cam shaft (the runtime's `analysis::cam`): its
//! pitch curve and working profile as CSV with units, the pressure angle and the sharpest point
//! of the profile against the roller on standard error, and the profile drawn with `--plot`.
//! With `--flat`, the cam of a flat-faced follower instead (the envelope of its face): the
//! profile, its radius of curvature, the contact's offset along the face and the pressure angle,
//! with the face's least width and the samples where the profile is not convex.

use crate::cam_drawn::FaceLine;
use crate::exit::usage;
use crate::solve::{in_units, point};
use crate::{Failed, exit, samples};
use kinloop_model::{Count, Model};
use kinloop_runtime::analysis::cam::{
    CamProfile, FlatFace, FlatFaceProfile, FollowerSample, cam_profile, flat_face_profile,
};
use kinloop_runtime::dims::KinState;
use kinloop_runtime::{Error, Number, QuantityKind, Table};
use kinloop_viz::plot::{self, Axis, Kind, Series};
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
    #[arg(long, allow_hyphen_values = true)]
    pub roller: Option<f64>,
    /// A flat-faced follower instead of a roller: its face square to the guide through the
    /// follower's point (`--guide`), or parallel to the arm from the pivot to the point at
    /// `--face-offset` from the pivot (`--rocker`), turned by ANGLE (0 if not given; degrees
    /// with `--deg`); the profile is the face's envelope.
    #[arg(long, value_name = "ANGLE", num_args = 0..=1, default_missing_value = "0", allow_negative_numbers = true)]
    pub flat: Option<f64>,
    /// A rocking flat face's distance from the rocker's pivot, positive on the left of the
    /// face's direction (0: the face through the pivot).
    #[arg(long, value_name = "D", allow_hyphen_values = true)]
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
    /// The cam for the follower asked for.
    pub shape: Shape,
}

/// A cam for a roller (or knife edge), or for a flat face.
pub enum Shape {
    /// For a roller of the radius the profile holds (0: a knife edge).
    Roller(CamProfile),
    /// For a flat face, with where the face lies.
    Flat(FlatFaceProfile, FaceLine),
}

impl Found {
    /// The working profile, in the cam's frame (origin at the pivot).
    pub fn profile(&self) -> &[[f64; 2]] {
        match &self.shape {
            Shape::Roller(cam) => &cam.profile,
            Shape::Flat(cam, _) => &cam.profile,
        }
    }

    /// The cam's checks, on standard error.
    pub fn report(&self) {
        match &self.shape {
            Shape::Roller(cam) => report(cam, &self.inputs, self.deg, cam.roller),
            Shape::Flat(cam, _) => report_flat(cam, &self.inputs, self.deg),
        }
    }
}

/// Sweeps one turn of the cam shaft from `--start`, finds the cam by inversion and writes its
/// table to standard output and its checks to standard error.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    let found = find(model, req)?;
    found.report();
    let (table, curves) = match found.shape {
        Shape::Flat(cam, _) => (flat_table(&cam, &found.inputs, req.deg), vec![("cam profile", cam.profile)]),
        Shape::Roller(cam) => {
            (table(&cam, &found.inputs, req.deg), vec![("pitch curve", cam.pitch), ("cam profile", cam.profile)])
        }
    };
    crate::output::table(&table, "the table")?;
    match req.plot {
        Some(path) => draw(&curves, model.name(), path),
        None => Ok(()),
    }
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
    let face = flat_face(fa, &follower, angle)?;
    let start = req.start / angle;
    let kinds = model.input_kinds().to_vec();
    let failed = |e: Error| {
        eprintln!("error: {name}: {}", in_units(e, &kinds, req.deg));
        Failed(exit::SOLVE_FAILED)
    };
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
    let mut follower_samples = Vec::with_capacity(req.samples);
    for state in sweep {
        let s = state.map_err(failed)?;
        let (x, y) = columns;
        let p = [s.out()[x], s.out()[y]];
        follower_samples.push(FollowerSample {
            cam: [turn * s.x()[0], turn, 0.0],
            point: [p, [s.dout(x)[0], s.dout(y)[0]], [s.d2out(x, 0, 0), s.d2out(y, 0, 0)]],
            direction: follower.direction(p),
        });
    }
    // Each sample's input in the units given, between the ends as given (`86`, not
    // `86.00000000000001` from the radians), as `kinloop sweep` writes its samples.
    let last = (req.samples - 1) as f64;
    let full = if req.deg { 360.0 } else { std::f64::consts::TAU };
    let inputs: Vec<f64> = (0..req.samples).map(|k| req.start + full * k as f64 / last).collect();
    let refused = |e: Error| {
        eprintln!("error: {name}: {e}");
        Failed(exit::SOLVE_FAILED)
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
            Shape::Flat(cam, FaceLine { away, ..line })
        }
        None => Shape::Roller(cam_profile(&follower_samples, pivot, roller).map_err(refused)?),
    };
    Ok(Found { pivot, turn, inputs, deg: req.deg, columns, shape })
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

/// The flat face asked for with `--flat` (and `--face-offset`), `None` for a roller; `angle`
/// converts the given angle to radians by division.
fn flat_face(req: &FollowerArgs, follower: &Follower, angle: f64) -> Result<Option<FlatFace>, Failed> {
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
    let tilt_rad = tilt / angle;
    match *follower {
        Follower::Translating(_) => {
            if req.face_offset.is_some() {
                return Err(usage(
                    "--face-offset places a rocking follower's face from its pivot: a translating one's face passes \
                     through its point (use --rocker X,Y, or declare the face's point)",
                ));
            }
            if tilt_rad.is_nan() || tilt_rad.abs() >= std::f64::consts::FRAC_PI_2 {
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
            if !tilt.is_finite() || !offset.is_finite() {
                return Err(usage(format!(
                    "--flat {} and --face-offset {} must be finite numbers",
                    shown(tilt),
                    shown(offset)
                )));
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

/// The output columns `NAME.x`, `NAME.y` of the point `name`, given to the option `option`.
pub(crate) fn point_columns(model: &Model, name: &str, option: &str) -> Result<(usize, usize), Failed> {
    let outputs = model.outputs();
    let at = |c: &str| outputs.iter().position(|o| o == c);
    match (at(&format!("{name}.x")), at(&format!("{name}.y"))) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => {
            let points: Vec<&str> = outputs.iter().filter_map(|o| o.strip_suffix(".x")).collect();
            Err(usage(format!(
                "{option} {name}: {} has no point of that name (its points: {})",
                model.name(),
                if points.is_empty() { "none".to_string() } else { points.join(", ") }
            )))
        }
    }
}

/// A direction `x,y` of the option `option`: two finite numbers, not both zero.
fn direction(spec: &str, option: &str) -> Result<[f64; 2], Failed> {
    let d = point(spec, option)?;
    if d == [0.0, 0.0] {
        return Err(usage(format!("{option} {spec} has no direction: give a vector along the guide, e.g. 0,1")));
    }
    Ok(d)
}

/// The cam's checks on standard error: the largest pressure angle, the sharpest convex point
/// of the pitch curve and whether the roller undercuts the profile there.
fn report(cam: &CamProfile, inputs: &[f64], deg: bool, roller: f64) {
    let (unit, angle) = if deg { ("°", 180.0 / std::f64::consts::PI) } else { (" rad", 1.0) };
    let (k, alpha) = cam.max_pressure_angle();
    eprintln!("cam: largest pressure angle {}{unit} at {}{unit}", Number(alpha * angle), Number(inputs[k]));
    match cam.min_convex_radius() {
        Some((k, radius)) => eprintln!(
            "cam: sharpest convex point of the pitch curve at {}{unit}: radius of curvature {}, of the profile {}",
            Number(inputs[k]),
            Number(radius),
            Number(cam.profile_radius(k))
        ),
        None => eprintln!("cam: the pitch curve is nowhere convex"),
    }
    let undercut = cam.undercut();
    match (undercut.first(), undercut.last()) {
        (Some(&a), Some(&b)) => eprintln!(
            "cam: UNDERCUT at {} (the first at {}{unit}, the last at {}{unit}): the pitch curve is sharper \
             there than the roller (radius {}); use a smaller roller or a larger cam",
            Count(undercut.len(), "sample"),
            Number(inputs[a]),
            Number(inputs[b]),
            Number(roller)
        ),
        _ => eprintln!("cam: no undercut with a roller of radius {}", Number(roller)),
    }
}

/// A flat-faced follower's checks on standard error: the largest pressure angle, the smallest
/// radius of curvature of the profile, the face's least width and the samples where the profile
/// is not convex.
fn report_flat(cam: &FlatFaceProfile, inputs: &[f64], deg: bool) {
    let (unit, angle) = if deg { ("°", 180.0 / std::f64::consts::PI) } else { (" rad", 1.0) };
    let (k, alpha) = cam.max_pressure_angle();
    eprintln!("cam: largest pressure angle {}{unit} at {}{unit}", Number(alpha * angle), Number(inputs[k]));
    let (k, radius) = cam.min_radius();
    eprintln!("cam: smallest radius of curvature of the profile {} at {}{unit}", Number(radius), Number(inputs[k]));
    let (lo, hi) = cam.offset_range();
    eprintln!(
        "cam: face width at least {} (the contact from {} to {} along the face)",
        Number(cam.face_width()),
        Number(lo),
        Number(hi)
    );
    let bad = cam.not_convex();
    match (bad.first(), bad.last()) {
        (Some(&a), Some(&b)) => eprintln!(
            "cam: NOT CONVEX at {} (the first at {}{unit}, the last at {}{unit}): the face's envelope folds \
             there and a flat face cannot follow the law; use a larger base circle or a gentler law",
            Count(bad.len(), "sample"),
            Number(inputs[a]),
            Number(inputs[b])
        ),
        _ => eprintln!("cam: the profile is convex at every sample"),
    }
}

/// The cam as a table: per sample the input (in the units given), the pitch curve's and the profile's points in the
/// cam's frame, the pitch curve's radius of curvature and the pressure angle.
fn table(cam: &CamProfile, inputs: &[f64], deg: bool) -> Table {
    let (angle, a) = if deg { (180.0 / std::f64::consts::PI, "deg") } else { (1.0, "rad") };
    let columns = ["input", "pitch.x", "pitch.y", "profile.x", "profile.y", "pitch_radius", "pressure_angle"];
    let mut t = Table::new(columns.iter().map(|c| c.to_string()).collect());
    for (k, &x) in inputs.iter().enumerate() {
        let ([px, py], [cx, cy]) = (cam.pitch[k], cam.profile[k]);
        t.push(vec![x, px, py, cx, cy, cam.pitch_radius[k], cam.pressure_angle[k] * angle]);
    }
    let length = QuantityKind::Length.unit();
    t.with_units(&[
        ("input", a),
        ("pitch", length),
        ("profile", length),
        ("pitch_radius", length),
        ("pressure_angle", a),
    ])
}

/// A flat-faced follower's cam as a table: per sample the input (in the units given), the
/// profile's point in the cam's frame, its radius of curvature, the contact's offset along the
/// face and the pressure angle.
fn flat_table(cam: &FlatFaceProfile, inputs: &[f64], deg: bool) -> Table {
    let (angle, a) = if deg { (180.0 / std::f64::consts::PI, "deg") } else { (1.0, "rad") };
    let columns = ["input", "profile.x", "profile.y", "radius", "offset", "pressure_angle"];
    let mut t = Table::new(columns.iter().map(|c| c.to_string()).collect());
    for (k, &x) in inputs.iter().enumerate() {
        let [cx, cy] = cam.profile[k];
        t.push(vec![x, cx, cy, cam.radius[k], cam.offset[k], cam.pressure_angle[k] * angle]);
    }
    let length = QuantityKind::Length.unit();
    t.with_units(&[("input", a), ("profile", length), ("radius", length), ("offset", length), ("pressure_angle", a)])
}

/// The named curves (the pitch curve and the profile, or the profile alone) drawn to `path`
/// (SVG), the cam's pivot marked.
fn draw(curves: &[(&str, Vec<[f64; 2]>)], name: &str, path: &Path) -> Result<(), Failed> {
    let length = Kind::length(QuantityKind::Length.unit());
    let curve = |points: &[[f64; 2]]| points.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>();
    let series: Vec<Series> =
        curves.iter().map(|(label, points)| Series::new(label, length.clone(), curve(points))).collect();
    let title = format!("{name}: the cam by inversion of the follower's motion");
    let svg =
        plot::xy_chart_svg(&title, &Axis::new("x", length.clone()), &Axis::new("y", length), &series, &[(0.0, 0.0)])
            .map_err(|e| {
                eprintln!("error: {name}: cannot draw the cam: {e}");
                Failed(exit::SOLVE_FAILED)
            })?;
    // Written as `animate --out` writes: into a folder that exists (a mistyped folder is an
    // error, not created).
    std::fs::write(path, svg).map_err(|e| {
        eprintln!("error: cannot write the plot {}: {e}", path.display());
        Failed(exit::CANT_CREATE)
    })
}
