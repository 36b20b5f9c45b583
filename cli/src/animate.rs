//! `kinloop animate`: the mechanism's default drawing moving through a branch-safe sweep, as an
//! animated SVG or an interactive HTML page, or (`--grid`) over a grid of its inputs as a page
//! with one slider per input, with the drawing code of compiled mechanisms (`kinloop_viz`) over
//! the run-time model.

use crate::cam::{self, FollowerArgs, Found};
use crate::cam_drawn;
use crate::exit::usage;
use crate::solve::{Notes, degrees, in_units, led_by, model_inputs, named, parse_inputs, text_in_units};
use crate::sweep::range_too_long;
use crate::{Failed, exit, samples};
use kinloop_model::{Count, Model};
use kinloop_runtime::{Error, Number, QuantityKind};
use kinloop_viz::draw::{Animation, DefaultDrawing, DrawError, MAX_GRID_CELLS};
use kinloop_viz::html::{HtmlConfig, HtmlError, html_grid_of, html_of};
use std::io::Write;
use std::path::Path;

/// The kind of file written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// An animated SVG (SMIL: plays in browsers, no script).
    Svg,
    /// An interactive page: a slider, play/pause, readouts and their charts.
    Html,
}

impl Format {
    /// The format an output file's extension names (`.svg`, `.html`, `.htm`).
    fn of(path: &Path) -> Option<Format> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "svg" => Some(Format::Svg),
            "html" | "htm" => Some(Format::Html),
            _ => None,
        }
    }
}

/// What `kinloop animate` was asked.
pub struct Request<'a> {
    /// The inputs at the start, one per input.
    pub from: &'a str,
    /// The inputs at the end.
    pub to: &'a str,
    /// `--samples`: the samples of the sweep, both ends included (one count); with `grid`, the
    /// values of each input (one count for all, or one per input). `None`: the defaults.
    pub samples: Option<&'a str>,
    /// A grid of the inputs instead of a sweep, drawn as a page with one slider per input.
    pub grid: bool,
    /// Angles of `--from` and `--to` in degrees.
    pub deg: bool,
    /// Where to write.
    pub out: &'a Path,
    /// The format, when not told by the extension.
    pub format: Option<Format>,
    /// Columns shown as readouts on the page.
    pub show: &'a [String],
    /// The largest number of frames written (key frames of the SVG, poses of the page).
    pub frames: Option<usize>,
    /// The follower's point whose cam is drawn turning with the input (`--cam`).
    pub cam: Option<&'a str>,
    /// The cam's follower (`--guide`, `--roller`, ...: read only with `cam`).
    pub follower: &'a FollowerArgs,
}

/// Sweeps from the declared guess at `from`, draws the motion and writes it to `out`. A sweep
/// that stops at a located limit position or singular crossing is drawn up to there, the
/// mechanism shown at the event as a ghost, and the event listed on standard error; a sweep that
/// fails otherwise writes nothing and fails.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    let format = match (req.format, Format::of(req.out)) {
        (Some(f), _) | (None, Some(f)) => f,
        (None, None) if to_stdout(req.out) => {
            return Err(usage(
                "--out - writes the animation to standard output: give its format, --format svg or html",
            ));
        }
        (None, None) => {
            return Err(usage(format!(
                "cannot tell the format of {} from its extension: name it .svg or .html, or give --format",
                req.out.display()
            )));
        }
    };
    if req.frames.is_some_and(|f| f < 2) {
        return Err(usage("--frames must be at least 2"));
    }
    // An SVG has no readouts or charts: the columns asked for would be dropped in silence.
    if format == Format::Svg && !req.show.is_empty() {
        return Err(usage(
            "--show adds readouts to the interactive page: write it to a .html file (or give --format html), or \
             leave out --show",
        ));
    }
    // A column named twice would be two equal readouts with their charts.
    if let Some((_, col)) = req.show.iter().enumerate().find(|(k, c)| req.show[..*k].contains(c)) {
        return Err(usage(format!("--show {col} is given twice: name each column once")));
    }
    if let (None, Some(option)) = (req.cam, req.follower.any_given()) {
        return Err(usage(format!(
            "{option} describes the follower of a cam: give --cam POINT (the follower's point) to draw the cam, or \
             leave out {option}"
        )));
    }
    something_to_draw(model)?;
    if req.grid {
        if req.cam.is_some() {
            return Err(usage("--cam draws a cam turning with the one input: a sweep, not a --grid"));
        }
        return grid(model, req, format);
    }
    let samples = match req.samples.map(str::trim) {
        None => DEFAULT_SAMPLES,
        // A list is a grid's; one count is read as every count is, its message saying what is
        // wrong with it (a count too large said "is not a count").
        Some(s) if s.contains(',') => {
            return Err(usage(format!("--samples {s} is not a count (a list of counts is for a grid, with --grid)")));
        }
        Some(s) => crate::count::count(s).map_err(|why| usage(format!("--samples {s}: {why}")))?,
    };
    if samples < 2 {
        return Err(usage(format!("an animation needs at least 2 samples, not {samples}")));
    }
    samples::check_at_most(samples, samples::MAX_ANIMATION_SAMPLES)?;
    let name = model.name().to_string();
    let failed = |e: &dyn std::fmt::Display| failed(&name, e);
    let Endpoints { from, to, guess } = endpoints(model, req)?;
    // Said in the command line's terms: the runtime's refusal named its own arguments ("a sweep
    // with several samples needs `to` different from `from`").
    if from == to {
        return Err(usage(format!(
            "--from {} --to {}: an animation moves the mechanism from --from to --to: give --to different from --from",
            req.from, req.to
        )));
    }
    let kinds = model.input_kinds().to_vec();
    let motion = match model.motion(&from, &to, samples, &guess) {
        Ok(motion) => motion,
        // The runtime's refusal of the arguments (`to` equal to `from`, a range of more turns
        // than a sweep follows) is a usage error.
        // So is the start's (a loop whose lengths are all zero), said where it was solved in the
        // units given.
        Err(DrawError::Sweep(e @ Error::InvalidArgument(_))) => {
            return Err(usage(led_by(&name, &name, &text_in_units(model, e, &from, req.deg))));
        }
        Err(DrawError::Sweep(e @ Error::RangeTooLong { .. })) => {
            return Err(range_too_long(&name, &e, req.from, req.to, req.deg).unwrap_or_else(|| failed(&e)));
        }
        Err(DrawError::Sweep(e)) => {
            eprintln!("error: the sweep failed: {}", named(&name, &in_units(e.clone(), &kinds, req.deg)));
            // The notes `sweep` writes under the same error: its advice names the library's
            // settings (`SweepConfig::singular_pivot`, `trace_curve`), the notes the command
            // line's options and commands.
            Notes::of(&e).write();
            crate::assembles::note(model, &e, &from, Some(&to), req.deg);
            return Err(Failed(exit::SOLVE_FAILED));
        }
        Err(e) => return Err(failed(&e)),
    };
    for (k, e) in motion.events.iter().enumerate() {
        let at: Vec<String> = (motion.inputs.iter().zip(&e.pose.x).zip(&kinds))
            .map(|((n, v), k)| match req.deg && *k == QuantityKind::Angle {
                // As `sweep` writes an event's inputs: `{v}` wrote an input of 3e200 in 201 digits.
                true => format!("{n} = {} deg", Number(degrees(*v))),
                false => format!("{n} = {}", Number(*v)),
            })
            .collect();
        let what = event_label(k, motion.events.len(), motion.stopped);
        eprintln!("{what} {} at {}", e.kind, at.join(", "));
    }
    // The cam after the motion: its report (a turn's pressure angle, curvature, undercut) is
    // not written ahead of a range the animation refuses.
    let cam = match req.cam {
        Some(point) => Some((find_cam(model, req, point)?, point)),
        None => None,
    };
    let drawing = noted_drawing(model);
    let drawing = match cam {
        Some((found, point)) => cam_drawn::with_cam(drawing, &found, point),
        None => drawing,
    };
    let mut anim = Animation::default();
    if let Some(f) = req.frames {
        anim.frames = f;
    }
    let frames = match format {
        Format::Svg => anim.frames,
        Format::Html => page_config(&name, req).max_frames,
    };
    let ends = motion.poses.first().zip(motion.poses.last()).map(|(a, b)| (&a.x[..], &b.x[..]));
    if let Some((first, last)) = ends
        && let Some(note) = aliasing(model.inputs(), &kinds, first, last, frames.min(motion.poses.len()))
    {
        eprintln!("note: {note}");
    }
    let text = match format {
        Format::Svg => {
            anim.back_and_forth = motion.stopped;
            drawing.animate(&motion, &anim).map_err(|e| failed(&e))?
        }
        Format::Html => {
            let config = page_config(&name, req).with_back_and_forth(motion.stopped);
            html_of(model, &drawing.into_drawing(), &motion, &config).map_err(|e| match e {
                HtmlError::UnknownColumn { ref name, ref available } => {
                    usage(format!("--show: {e}{}", crate::names::look_alike_after(name, available)))
                }
                e => failed(&e),
            })?
        }
    };
    write_out(req.out, &text)
}

/// The cam of `--cam POINT` over one turn from `--from`, as `kinloop cam` finds it (its checks on
/// standard error).
fn find_cam(model: &mut Model, req: &Request, point: &str) -> Result<Found, Failed> {
    // The start as given (degrees with `--deg`), as `kinloop cam --start` takes it; a model of
    // other than one input is refused by `find`.
    let x = parse_inputs(req.from, model.inputs().len(), "--from")?;
    let start = x.first().copied().unwrap_or(0.0);
    let cam = cam::Request {
        point,
        point_option: "--cam",
        follower: req.follower,
        start,
        samples: cam_drawn::SAMPLES,
        deg: req.deg,
        plot: None,
    };
    let found = cam::find(model, &cam)?;
    // Before its report: a cam the drawing cannot hold is refused in the options' terms.
    cam_drawn::fits(&found, &cam::follower_options(req.follower))?;
    found.report();
    Ok(found)
}

/// The samples of a sweep when `--samples` is not given.
const DEFAULT_SAMPLES: usize = 181;

/// The values of each input of a grid of `ni` inputs when `--samples` is not given: the most
/// whose grid fits the page's `max` poses and the grid's bound ([`MAX_GRID_CELLS`]: `c^ni <=
/// min(max, MAX_GRID_CELLS)`: 26 x 26 or 8 x 8 x 8 of the default 721), at least 2 (a grid of
/// two values per input that does not fit is refused as too many cells). Without the grid's
/// bound, `--frames 200000` chose a grid the grid then refused, and a huge `--frames` counted up
/// to its square root.
fn default_grid_values(ni: usize, max: usize) -> usize {
    let max = max.min(MAX_GRID_CELLS);
    let fits = |c: usize| (0..ni).try_fold(1usize, |p, _| p.checked_mul(c)).is_some_and(|cells| cells <= max);
    let mut c = 2;
    while fits(c + 1) {
        c += 1;
    }
    c
}

/// `kinloop animate --grid`: the model over a grid of its inputs (`Model::grid`, the assembly
/// mode carried from cell to cell), drawn as the interactive page with one slider per input
/// (`html_grid_of`). Only a page: an SVG animation plays one path, not a grid.
fn grid(model: &mut Model, req: &Request, format: Format) -> Result<(), Failed> {
    let name = model.name().to_string();
    let ni = model.inputs().len();
    if ni < 2 {
        return Err(usage(format!(
            "--grid needs a mechanism of two inputs or more: `{name}` has {ni}; animate a sweep without --grid"
        )));
    }
    if format != Format::Html {
        return Err(usage("--grid draws an interactive page: write it to a .html file (or give --format html)"));
    }
    // The page's settings first: its largest number of poses bounds the grid, checked before
    // any cell is solved.
    let config = page_config(&name, req);
    let max = config.max_frames;
    let counts: Vec<usize> = match req.samples {
        None => vec![default_grid_values(ni, max); ni],
        Some(spec) => {
            // Each count read as a count, the one that is not named with what is wrong with it:
            // `9,-1` for two inputs said to give one count per input, as it did.
            let counts = (spec.split(',').map(|v| {
                crate::count::count(v).map_err(|why| usage(format!("--samples {spec}: `{}`: {why}", v.trim())))
            }))
            .collect::<Result<Vec<usize>, Failed>>()?;
            match counts.len() {
                1 => vec![counts[0]; ni],
                n if n == ni => counts,
                _ => {
                    return Err(usage(format!(
                        "--samples {spec}: give one count of values for every input, or one per input ({ni})"
                    )));
                }
            }
        }
    };
    // A grid of no value of an input has no pose to draw (one value, with `--from` and `--to`
    // equal there, draws a grid fixed in that input).
    if let Some(k) = counts.iter().position(|&c| c == 0) {
        let input = &model.inputs()[k];
        return Err(usage(format!("--samples: a grid needs at least one value of input `{input}`, not 0")));
    }
    // The product saturates: a count too large for usize is more cells than any page.
    let cells = counts.iter().fold(1usize, |p, &c| p.saturating_mul(c));
    if cells > max.min(MAX_GRID_CELLS) {
        return Err(usage(too_many_cells(cells, max, req.samples.is_some())));
    }
    let failed = |e: &dyn std::fmt::Display| failed(&name, e);
    let Endpoints { from, to, guess } = endpoints(model, req)?;
    grid_ends(model.inputs(), &from, &to, &counts, req)?;
    let kinds = model.input_kinds().to_vec();
    let grid = model.grid(&from, &to, &counts, &guess);
    let grid = grid.map_err(|e| match e {
        // The counts or ranges refused (no value of an input, equal ends, too many cells, a
        // range no sweep follows: its ends as they were given).
        DrawError::InvalidSetting(_) => usage(format!("{name}: {e}")),
        // So is the first cell's invalid argument (a loop whose lengths are all zero), said
        // where it was solved in the units given.
        DrawError::Sweep(e @ Error::InvalidArgument(_)) => {
            usage(led_by(&name, &name, &DrawError::Sweep(text_in_units(model, e, &from, req.deg))))
        }
        e @ DrawError::GridRange { .. } => {
            let is_angle = |i| kinds.get(i) == Some(&QuantityKind::Angle);
            let e = if req.deg { e.in_degrees(is_angle, degrees) } else { e };
            usage(format!("{name}: {e}"))
        }
        // Where it failed, in the units given, as an animation's sweep says it (in radians
        // with --deg it said `th1 = 1.5707963267948966` of the 90 typed).
        DrawError::Sweep(e) => {
            let notes = Notes::of(&e);
            let failed = failed(&format!("the sweep failed: {}", in_units(e, &kinds, req.deg)));
            notes.write();
            failed
        }
        e => failed(&e),
    })?;
    let unreached = grid.cells.iter().filter(|c| c.is_none()).count();
    if unreached > 0 {
        let (total, are) = (grid.cells.len(), if unreached == 1 { "is" } else { "are" });
        eprintln!(
            "note: {unreached} of {} {are} not reached from the first on its assembly mode (no assembly there, \
             or a limit or singular position on the way)",
            Count(total, "cell")
        );
    }
    let drawing = noted_drawing(model);
    let text = html_grid_of(model, &drawing.into_drawing(), &grid, &config).map_err(|e| match e {
        HtmlError::UnknownColumn { ref name, ref available } => {
            usage(format!("--show: {e}{}", crate::names::look_alike_after(name, available)))
        }
        HtmlError::InvalidSetting(_) => usage(format!("{e} (fewer --samples, or more --frames)")),
        e => failed(&e),
    })?;
    write_out(req.out, &text)
}

/// Why a grid of `cells` cells is refused, more than the page's `max` poses or than the
/// [`MAX_GRID_CELLS`] a grid holds whatever the page (`samples`: whether `--samples` gave the
/// counts), with advice that works when followed: more `--frames` raise the page's bound, never
/// the grid's, past which only fewer values do. Without `--samples` the default grid has two
/// values of each input at least, so that fewer values means one value of some inputs. (More
/// `--frames` were advised past the grid's bound too, and then refused by the grid.)
fn too_many_cells(cells: usize, max: usize, samples: bool) -> String {
    let bound = if cells > MAX_GRID_CELLS {
        format!("the {} a grid holds", Count(MAX_GRID_CELLS, "cell"))
    } else {
        format!("the page's {}", Count(max, "pose"))
    };
    let fewer = "give fewer values with --samples (one value of an input, its --from equal to its --to, fixes it)";
    let advice = match (samples, cells <= MAX_GRID_CELLS) {
        (true, true) => format!("fewer --samples, or --frames {cells} or more"),
        (false, true) => {
            format!("give --frames {cells} or more (the default grid has two values of each input at least)")
        }
        (true, false) => format!("{fewer}; more --frames do not raise it"),
        (false, false) => format!("{fewer}: the default grid has two values of each input at least"),
    };
    format!("a grid of {} is more than {bound}: {advice}", Count(cells, "cell"))
}

/// The ends and counts of each input of a grid agree: several values between equal ends, or
/// one value between different ends, are a usage error saying which input and the options
/// that fix it. The grid's own refusal ("26 values of input `th1` from 0 to the same value")
/// named neither `--samples` nor what to write, where the 26 are the default count.
fn grid_ends(inputs: &[String], from: &[f64], to: &[f64], counts: &[usize], req: &Request) -> Result<(), Failed> {
    // Each input's ends as typed (in degrees with `--deg`), as the options gave them.
    let typed = |spec: &str, k: usize| spec.split(',').nth(k).map_or(String::new(), |v| v.trim().to_string());
    let counts_with = |k: usize, c: usize| {
        let mut v = counts.to_vec();
        v[k] = c;
        v.iter().map(usize::to_string).collect::<Vec<_>>().join(",")
    };
    for (k, input) in inputs.iter().enumerate() {
        let (a, b) = (typed(req.from, k), typed(req.to, k));
        if counts[k] > 1 && from[k] == to[k] {
            return Err(usage(format!(
                "--from and --to give input `{input}` the same value ({a}), where the grid takes {} of it: give \
                 --to another value of `{input}`, or --samples {} for a grid fixed in `{input}`",
                Count(counts[k], "value"),
                counts_with(k, 1)
            )));
        }
        if counts[k] == 1 && from[k] != to[k] {
            return Err(usage(format!(
                "--samples {} gives input `{input}` one value, and --from and --to a range of it ({a} to {b}): \
                 give --samples {} for values over the range, or --to {a} in `{input}` for a grid fixed there",
                req.samples.unwrap_or_default().trim(),
                counts_with(k, 2)
            )));
        }
    }
    Ok(())
}

/// The inputs at `--from` and `--to`, and the declared guess at `--from`.
struct Endpoints {
    from: Vec<f64>,
    to: Vec<f64>,
    /// What a sweep and a grid start from.
    guess: Vec<f64>,
}

/// The request's [`Endpoints`] for the model.
fn endpoints(model: &mut Model, req: &Request) -> Result<Endpoints, Failed> {
    let kinds = model.input_kinds().to_vec();
    let from = model_inputs(req.from, &kinds, req.deg, "--from")?;
    let to = model_inputs(req.to, &kinds, req.deg, "--to")?;
    let mut guess = vec![0.0; model.unknowns().len()];
    model.guess(&from, &mut guess).map_err(|e| failed(model.name(), &e))?;
    Ok(Endpoints { from, to, guess })
}

/// The page's settings of the request: the model's name, `--frames` and `--show`.
fn page_config(name: &str, req: &Request) -> HtmlConfig {
    let mut config = HtmlConfig::new(name);
    if let Some(f) = req.frames {
        config = config.with_max_frames(f);
    }
    for col in req.show {
        config = config.show(col.as_str());
    }
    config
}

/// A usage error where the declaration has nothing to draw: with no loop and no point, its
/// default drawing has no item, no traced point and no label. Found before anything is solved:
/// the sweep (or the grid) ran first and the drawing then failed with exit code 1 as an
/// "invalid drawing setting", a setting no one gave.
fn something_to_draw(model: &mut Model) -> Result<(), Failed> {
    let drawing = model.drawing().into_drawing();
    if drawing.items.is_empty() && drawing.traces.is_empty() && drawing.labels.is_empty() {
        return Err(usage(format!(
            "{} declares no loop and no point: there is nothing to animate; declare the points to draw, \
             `point p = ...;`",
            model.name()
        )));
    }
    Ok(())
}

/// The model's default drawing, its notes (what it could not draw) listed on standard error.
fn noted_drawing(model: &mut Model) -> DefaultDrawing {
    let drawing = model.drawing();
    for n in drawing.notes() {
        eprintln!("note: {n}");
    }
    drawing
}

/// A failure of the model `name` to solve or draw: reported, exit code 1.
fn failed(name: &str, e: &dyn std::fmt::Display) -> Failed {
    eprintln!("error: {name}: {e}");
    Failed(exit::SOLVE_FAILED)
}

/// Writes `text` to `out`, created only now: a failed sweep or drawing leaves no file behind,
/// and neither does a write that fails part way (a full disk, a file size limit): a regular
/// file is removed again rather than left cut short ([`OutFile::write`](crate::output::OutFile::write)),
/// an SVG or page that does not read.
fn write_out(out: &Path, text: &str) -> Result<(), Failed> {
    if to_stdout(out) {
        return crate::output::text(text, "the animation");
    }
    let what = format!("the animation {}", out.display());
    crate::output::created(Some(out), "the animation")?.map_or(Ok(()), |file| {
        file.write(&what, |mut file| file.write_all(text.as_bytes()).and_then(|()| file.flush()))
    })
}

/// Whether `--out` is `-`: standard output, as the usual convention has it (it made a file named
/// `-`). A file of that name is `--out ./-`.
fn to_stdout(out: &Path) -> bool {
    out.as_os_str() == "-"
}

/// Frames of an angle input farther apart than this (a twentieth of a turn, 18 degrees) show
/// a turning link jumping from frame to frame, and more than half a turn apart, standing still
/// or turning backwards (aliasing).
const ALIASING_STEP: f64 = std::f64::consts::TAU / 20.0;

/// A note when `frames` frames evenly over the motion from inputs `first` to `last` are farther
/// apart than [`ALIASING_STEP`] in an angle input: what the step is and what to do.
fn aliasing(inputs: &[String], kinds: &[QuantityKind], first: &[f64], last: &[f64], frames: usize) -> Option<String> {
    let gaps = (frames.max(2) - 1) as f64;
    let (k, step) = (0..first.len().min(last.len()).min(kinds.len()))
        .filter(|&k| kinds[k] == QuantityKind::Angle)
        .map(|k| (k, (last[k] / 2.0 - first[k] / 2.0).abs() / gaps * 2.0))
        .fold(None::<(usize, f64)>, |best, (k, s)| match best {
            Some((_, b)) if b >= s => best,
            _ => Some((k, s)),
        })?;
    (step > ALIASING_STEP).then(|| {
        format!(
            "the frames are {:.1} degrees of {} apart (more than a twentieth of a turn): the mechanism jumps from \
             frame to frame, and may seem to stand still or turn backwards; give more --frames (and --samples), or a shorter range",
            step.to_degrees(),
            inputs.get(k).map_or("the input", String::as_str)
        )
    })
}

/// How the event `k` of `n` is listed: the last one of a sweep that stopped is where it
/// stopped; the others were met and crossed.
fn event_label(k: usize, n: usize, stopped: bool) -> &'static str {
    if stopped && k + 1 == n { "the sweep stopped at a" } else { "event:" }
}

#[cfg(test)]
mod tests {
    use super::{aliasing, default_grid_values, event_label};
    use kinloop_runtime::QuantityKind;

    #[test]
    fn frames_more_than_a_twentieth_of_a_turn_apart_are_noted() {
        let (inputs, angle) = (vec!["phi".to_string()], [QuantityKind::Angle]);
        let turns = |n: f64| [n * std::f64::consts::TAU];
        // A turn in 90 frames: 4 degrees apart. Ten turns: 40 degrees apart.
        assert_eq!(aliasing(&inputs, &angle, &[0.0], &turns(1.0), 90), None);
        let note = aliasing(&inputs, &angle, &[0.0], &turns(10.0), 91).expect("a note");
        assert!(note.starts_with("the frames are 40.0 degrees of phi apart"), "{note}");
        // A length input is no turn.
        assert_eq!(aliasing(&inputs, &[QuantityKind::Length], &[0.0], &[1e6], 2), None);
    }

    /// The default values per input: the largest `c` with `c^ni` cells within the page, by hand.
    #[test]
    fn the_default_grid_is_the_largest_that_fits() {
        // 26^2 = 676 <= 721 < 729 = 27^2; 8^3 = 512 <= 721 < 729 = 9^3; 10^2 = 100.
        assert_eq!(default_grid_values(2, 721), 26);
        assert_eq!(default_grid_values(3, 721), 8);
        assert_eq!(default_grid_values(2, 100), 10);
        assert_eq!(default_grid_values(2, 99), 9);
        // Too few poses for two values per input: 2, refused by the cells' check.
        assert_eq!(default_grid_values(3, 7), 2);
        // More poses than a grid holds: the grid's bound, 316^2 = 99,856 <= 100,000 < 317^2,
        // 46^3 = 97,336 <= 100,000 < 47^3; a huge `--frames` as fast.
        assert_eq!(default_grid_values(2, 200_000), 316);
        assert_eq!(default_grid_values(3, usize::MAX), 46);
    }

    #[test]
    fn only_the_last_event_of_a_stopped_sweep_is_the_stop() {
        let labels: Vec<&str> = (0..3).map(|k| event_label(k, 3, true)).collect();
        assert_eq!(labels, ["event:", "event:", "the sweep stopped at a"]);
        assert!((0..3).all(|k| event_label(k, 3, false) == "event:"));
    }
}
