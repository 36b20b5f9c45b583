//! `kinloop cam`: the disc cam that moves a declared follower as the declaration says, by
//! kinematic inversion over one turn of the cam shaft (the runtime's `analysis::cam`): its
//! pitch curve and working profile as CSV with units, the pressure angle and the sharpest point
//! of the profile against the roller on standard error, and the profile drawn with `--plot`.

use crate::exit::usage;
use crate::solve::{in_units, point};
use crate::{Failed, exit, samples};
use kinloop_model::Model;
use kinloop_runtime::analysis::cam::{CamProfile, FollowerSample, cam_profile};
use kinloop_runtime::dims::KinState;
use kinloop_runtime::{Error, Number, QuantityKind, Table};
use kinloop_viz::plot::{self, Axis, Kind, Series};
use std::path::Path;

/// What `kinloop cam` was asked.
pub struct Request<'a> {
    /// The follower's point: a `point` of the declaration (the roller's centre).
    pub point: &'a str,
    /// The direction of a translating follower's guide, `x,y`.
    pub guide: Option<&'a str>,
    /// The pivot of a rocking follower's arm, `x,y`.
    pub rocker: Option<&'a str>,
    /// The cam's pivot, `x,y`.
    pub pivot: &'a str,
    /// The roller's radius (0: a knife edge).
    pub roller: f64,
    /// The cam shaft's angle at the first sample.
    pub start: f64,
    /// Samples over the turn, both ends included.
    pub samples: usize,
    /// The cam turns clockwise as the input grows.
    pub clockwise: bool,
    /// Angles in degrees.
    pub deg: bool,
    /// Where to draw the pitch curve and the profile (SVG).
    pub plot: Option<&'a Path>,
}

/// Sweeps one turn of the cam shaft from `--start`, finds the cam by inversion and writes its
/// table to standard output and its checks to standard error.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    let name = model.name().to_string();
    if model.inputs().len() != 1 || model.input_kinds()[0] != QuantityKind::Angle {
        return Err(usage(format!(
            "kinloop cam turns the cam with the input: {name} must have one input, an angle (its inputs: {})",
            model.inputs().join(", ")
        )));
    }
    if req.samples < 3 {
        return Err(usage(format!("--samples {} is too few: a turn needs at least 3", req.samples)));
    }
    samples::check(req.samples)?;
    if !(req.roller >= 0.0 && req.roller.is_finite()) {
        return Err(usage(format!("--roller {} must be a finite number, not negative", Number(req.roller))));
    }
    if !req.start.is_finite() {
        return Err(usage(format!("--start {} must be a finite number", Number(req.start))));
    }
    let columns = point_columns(model, req.point)?;
    let follower = match (req.guide, req.rocker) {
        (Some(g), None) => Follower::Translating(direction(g, "--guide")?),
        (None, Some(r)) => Follower::Rocking(point(r, "--rocker")?),
        _ => {
            return Err(usage(
                "give the follower's motion: --guide X,Y (the direction of a translating follower's guide) or \
                 --rocker X,Y (the pivot of a rocking follower's arm), not both",
            ));
        }
    };
    let pivot = point(req.pivot, "--pivot")?;
    let angle = if req.deg { 180.0 / std::f64::consts::PI } else { 1.0 };
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
    let turn = if req.clockwise { -1.0 } else { 1.0 };
    let end = start + std::f64::consts::TAU;
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
    let cam = cam_profile(&follower_samples, pivot, req.roller).map_err(|e| {
        eprintln!("error: {name}: {e}");
        Failed(exit::SOLVE_FAILED)
    })?;
    report(&cam, &inputs, req);
    let table = table(&cam, &inputs, req.deg);
    table.write_csv(std::io::stdout().lock()).map_err(|e| {
        eprintln!("error: cannot write the table: {e}");
        Failed(exit::IO_ERR)
    })?;
    match req.plot {
        Some(path) => draw(&cam, &name, path),
        None => Ok(()),
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

/// The output columns `NAME.x`, `NAME.y` of the point `name`.
fn point_columns(model: &Model, name: &str) -> Result<(usize, usize), Failed> {
    let outputs = model.outputs();
    let at = |c: &str| outputs.iter().position(|o| o == c);
    match (at(&format!("{name}.x")), at(&format!("{name}.y"))) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => {
            let points: Vec<&str> = outputs.iter().filter_map(|o| o.strip_suffix(".x")).collect();
            Err(usage(format!(
                "--point {name}: {} has no point of that name (its points: {})",
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
fn report(cam: &CamProfile, inputs: &[f64], req: &Request) {
    let (unit, angle) = if req.deg { ("°", 180.0 / std::f64::consts::PI) } else { (" rad", 1.0) };
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
            "cam: UNDERCUT at {} samples (the first at {}{unit}, the last at {}{unit}): the pitch curve is sharper \
             there than the roller (radius {}); use a smaller roller or a larger cam",
            undercut.len(),
            Number(inputs[a]),
            Number(inputs[b]),
            Number(req.roller)
        ),
        _ => eprintln!("cam: no undercut with a roller of radius {}", Number(req.roller)),
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

/// The pitch curve and the profile drawn to `path` (SVG), the cam's pivot marked.
fn draw(cam: &CamProfile, name: &str, path: &Path) -> Result<(), Failed> {
    let length = Kind::length(QuantityKind::Length.unit());
    let curve = |points: &[[f64; 2]]| points.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>();
    let series = [
        Series::new("pitch curve", length.clone(), curve(&cam.pitch)),
        Series::new("cam profile", length.clone(), curve(&cam.profile)),
    ];
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
