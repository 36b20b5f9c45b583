//! `kinloop animate`: the mechanism's default drawing moving through a branch-safe sweep, as an
//! animated SVG or an interactive HTML page, with the drawing code of compiled mechanisms
//! (`kinloop_viz`) over the run-time model.

use crate::exit::usage;
use crate::solve::model_inputs;
use crate::{Failed, exit, samples};
use kinloop_model::Model;
use kinloop_runtime::{Error, QuantityKind};
use kinloop_viz::draw::{Animation, DrawError};
use kinloop_viz::html::{HtmlConfig, HtmlError, html_of};
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
    /// Samples, both ends included.
    pub samples: usize,
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
}

/// Sweeps from the declared guess at `from`, draws the motion and writes it to `out`. A sweep
/// that stops at a located limit position or singular crossing is drawn up to there, the
/// mechanism shown at the event as a ghost, and the event listed on standard error; a sweep that
/// fails otherwise writes nothing and fails.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    let format = match (req.format, Format::of(req.out)) {
        (Some(f), _) | (None, Some(f)) => f,
        (None, None) => {
            return Err(usage(format!(
                "cannot tell the format of {} from its extension: name it .svg or .html, or give --format",
                req.out.display()
            )));
        }
    };
    if req.samples < 2 {
        return Err(usage(format!("an animation needs at least 2 samples, not {}", req.samples)));
    }
    samples::check(req.samples)?;
    if req.frames.is_some_and(|f| f < 2) {
        return Err(usage("--frames must be at least 2"));
    }
    let kinds = model.input_kinds().to_vec();
    let from = model_inputs(req.from, &kinds, req.deg, "--from")?;
    let to = model_inputs(req.to, &kinds, req.deg, "--to")?;
    let name = model.name().to_string();
    let failed = |e: &dyn std::fmt::Display| {
        eprintln!("error: {name}: {e}");
        Failed(exit::SOLVE_FAILED)
    };
    let mut guess = vec![0.0; model.unknowns().len()];
    model.guess(&from, &mut guess).map_err(|e| failed(&e))?;
    let motion = model.motion(&from, &to, req.samples, &guess).map_err(|e| match e {
        // The runtime's refusal of the arguments (`to` equal to `from`) is a usage error.
        DrawError::Sweep(e @ Error::InvalidArgument(_)) => usage(format!("{name}: {e}")),
        e => failed(&e),
    })?;
    for (k, e) in motion.events.iter().enumerate() {
        let at: Vec<String> = (motion.inputs.iter().zip(&e.pose.x).zip(&kinds))
            .map(|((n, v), k)| match req.deg && *k == QuantityKind::Angle {
                true => format!("{n} = {} deg", v.to_degrees()),
                false => format!("{n} = {v}"),
            })
            .collect();
        let what = event_label(k, motion.events.len(), motion.stopped);
        eprintln!("{what} {} at {}", e.kind, at.join(", "));
    }
    let drawing = model.drawing();
    for n in drawing.notes() {
        eprintln!("note: {n}");
    }
    let text = match format {
        Format::Svg => {
            let mut anim = Animation::default();
            if let Some(f) = req.frames {
                anim.frames = f;
            }
            anim.back_and_forth = motion.stopped;
            drawing.animate(&motion, &anim).map_err(|e| failed(&e))?
        }
        Format::Html => {
            let mut config = HtmlConfig::new(&name).with_back_and_forth(motion.stopped);
            if let Some(f) = req.frames {
                config = config.with_max_frames(f);
            }
            for col in req.show {
                config = config.show(col.as_str());
            }
            html_of(model, &drawing.into_drawing(), &motion, &config).map_err(|e| match e {
                HtmlError::UnknownColumn { .. } => usage(format!("--show: {e}")),
                e => failed(&e),
            })?
        }
    };
    // Created once the figure is made: a failed sweep or drawing leaves no file behind.
    let mut file = std::fs::File::create(req.out).map_err(|e| {
        eprintln!("error: cannot create {}: {e}", req.out.display());
        Failed(exit::CANT_CREATE)
    })?;
    file.write_all(text.as_bytes()).map_err(|e| {
        eprintln!("error: cannot write {}: {e}", req.out.display());
        Failed(exit::IO_ERR)
    })
}

/// How the event `k` of `n` is listed: the last one of a sweep that stopped is where it
/// stopped; the others were met and crossed.
fn event_label(k: usize, n: usize, stopped: bool) -> &'static str {
    if stopped && k + 1 == n { "the sweep stopped at" } else { "event:" }
}

#[cfg(test)]
mod tests {
    use super::event_label;

    #[test]
    fn only_the_last_event_of_a_stopped_sweep_is_the_stop() {
        let labels: Vec<&str> = (0..3).map(|k| event_label(k, 3, true)).collect();
        assert_eq!(labels, ["event:", "event:", "the sweep stopped at"]);
        assert!((0..3).all(|k| event_label(k, 3, false) == "event:"));
    }
}
