//! The document: the picture, the controls, the readouts and charts, the numbers of every
//! frame (JSON), the style sheet and the script, in one file.

use super::HtmlError;
use super::chart::Map;
use super::frames::{Frames, Slot};
use super::readouts::Channel;
use super::{css, script};
use crate::escape::escape;
use std::fmt::Write;

/// A finite number as JSON (the shortest text that reads back to it).
fn number(v: f64, what: &str) -> Result<String, HtmlError> {
    if v.is_finite() {
        Ok(format!("{}", v + 0.0))
    } else {
        Err(HtmlError::NonFinite { what: what.to_string(), pose: 0 })
    }
}

/// What the page is made of.
pub(crate) struct Parts<'a> {
    pub title: &'a str,
    /// The drawing's notes, written under the picture.
    pub notes: &'a [String],
    pub frames: &'a Frames,
    pub channels: &'a [Channel],
    /// The picture (SVG).
    pub figure: String,
    /// Each chart: the channel it shows, its SVG and its map.
    pub charts: Vec<(usize, String, Map)>,
    /// Charts are against the first channel (one input), or against the path.
    pub against_input: bool,
    /// Each event: its kind (for the mark's class), where it sits on the slider (fractional
    /// frame index; a click on its mark shows the nearest frame) and its label.
    pub events: Vec<(String, f64, String)>,
    pub seconds: f64,
    pub back_and_forth: bool,
    pub autoplay: bool,
    /// A grid's page: one slider per input over its cells.
    pub grid: Option<GridPart>,
}

/// What a grid's page holds besides the frames.
pub(crate) struct GridPart {
    /// Cells along each input.
    pub counts: Vec<usize>,
    /// For every cell (the first input fastest), its frame, or -1 where the grid did not reach it.
    pub cells: Vec<i64>,
    /// The inputs' names, labelling the sliders.
    pub inputs: Vec<String>,
}

/// The numbers of every frame and how the script reads them, as JSON.
fn data(p: &Parts) -> Result<String, HtmlError> {
    let fr = p.frames;
    let mut s = String::from("{\"frames\":[");
    for (i, f) in fr.frames.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        s.push('[');
        for (j, v) in f.iter().enumerate() {
            if j > 0 {
                s.push(',');
            }
            let _ = write!(s, "{v}");
        }
        s.push(']');
    }
    s.push_str("],\"items\":[");
    let mut o = 0;
    for (k, slot) in fr.slots.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        let (kind, n) = match slot {
            Slot::Link { n, .. } => ("link", *n),
            Slot::Pivot => ("pivot", 1),
            Slot::Slider { .. } => ("slider", 1),
            Slot::Gear { .. } => ("gear", 1),
            Slot::Outline { .. } => ("outline", 1),
            Slot::Joint => ("joint", 1),
            // Bars between two ends: the script moves their points as a link's.
            Slot::Guide | Slot::Construction => ("link", 2),
        };
        let _ = write!(s, r#"{{"t":"{kind}","o":{o},"n":{n}}}"#);
        o += slot.len();
    }
    let _ = write!(s, r#"],"traces":{{"o":{},"n":{}}},"ch":["#, fr.traces_at, fr.paths.len());
    for (k, c) in p.channels.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        // Each value written as its readout shows it (a JSON number), with the readout's
        // format, by which the script writes it again.
        let _ = write!(
            s,
            r#"{{"last":{},"sci":{},"v":[{}]}}"#,
            c.format.last,
            c.format.sci,
            c.values.iter().map(|v| c.text(*v)).collect::<Vec<_>>().join(",")
        );
    }
    s.push_str("],\"charts\":[");
    for (k, (ch, _, map)) in p.charts.iter().enumerate() {
        if k > 0 {
            s.push(',');
        }
        let what = "chart scale";
        let _ = write!(
            s,
            r#"{{"y":{ch},"x":{},"map":[{},{},{},{}]}}"#,
            if p.against_input { 0 } else { -1 },
            number(map.x[0], what)?,
            number(map.x[1], what)?,
            number(map.y[0], what)?,
            number(map.y[1], what)?
        );
    }
    s.push(']');
    if let Some(g) = &p.grid {
        let list = |v: Vec<String>| v.join(",");
        let _ = write!(
            s,
            r#","grid":{{"n":[{}],"cell":[{}]}}"#,
            list(g.counts.iter().map(usize::to_string).collect()),
            list(g.cells.iter().map(i64::to_string).collect())
        );
    }
    let _ = write!(
        s,
        r#","seconds":{},"bf":{},"autoplay":{}}}"#,
        number(p.seconds, "duration")?,
        p.back_and_forth,
        p.autoplay
    );
    Ok(s)
}

/// The whole page.
pub(crate) fn document(p: &Parts) -> Result<String, HtmlError> {
    let n = p.frames.frames.len();
    let title = escape(p.title);
    let mut s = String::with_capacity(64 * 1024);
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<meta name=\"generator\" content=\"kinloop\">\n<title>{title}</title>\n<style>{}</style>\n</head>\n<body>\n<main class=\"kl\">\n<h1>{title}</h1>\n<div class=\"kl-row\">\n<figure class=\"kl-figure\">\n{}\n",
        css::CSS,
        p.figure
    );
    // Play moves through the frames (on a grid, along the first input's values): where there
    // is one, it has nothing to play, and the button is disabled rather than doing nothing.
    let playable = match &p.grid {
        Some(g) => g.counts.first().is_some_and(|&c| c > 1),
        None => n > 1,
    };
    let play = format!(
        "<button id=\"kl-play\" type=\"button\" aria-pressed=\"false\"{}>Play</button>",
        if playable { "" } else { " disabled" }
    );
    if let Some(g) = &p.grid {
        let _ = write!(s, "<div class=\"kl-controls kl-grid\">{play}<div class=\"kl-sliders\">");
        for (k, (name, count)) in g.inputs.iter().zip(&g.counts).enumerate() {
            let name = escape(name);
            let _ = write!(
                s,
                "<label class=\"kl-axis\"><span>{name}</span><input id=\"kl-slider-{k}\" class=\"kl-slider\" data-axis=\"{k}\" type=\"range\" min=\"0\" max=\"{}\" step=\"1\" value=\"0\" aria-label=\"{name}\"></label>",
                count - 1
            );
        }
        s.push_str("</div></div>\n<p id=\"kl-status\" class=\"kl-status\" role=\"status\" aria-live=\"polite\"></p>\n");
    } else {
        let _ = write!(
            s,
            "<div class=\"kl-controls\">{play}<div class=\"kl-track\"><input id=\"kl-slider\" type=\"range\" min=\"0\" max=\"{}\" step=\"1\" value=\"0\" aria-label=\"pose along the motion\"><div class=\"kl-marks\">",
            n - 1
        );
    }
    for (kind, at, label) in &p.events {
        let f = at / (n - 1).max(1) as f64;
        let _ = write!(
            s,
            r#"<span class="kl-mark kl-{kind}" style="left:calc(8px + (100% - 16px) * {})" title="{}" data-at="{}"></span>"#,
            number((f * 1e4).round() / 1e4, "event position")?,
            escape(label),
            at.round()
        );
    }
    if p.grid.is_none() {
        s.push_str("</div></div></div>\n");
    }
    if !p.events.is_empty() {
        s.push_str("<ul class=\"kl-events\">");
        for (kind, at, label) in &p.events {
            let _ = write!(
                s,
                r#"<li data-at="{}"><span class="kl-key kl-{kind}"></span>{}</li>"#,
                at.round(),
                escape(label)
            );
        }
        s.push_str("</ul>\n");
    }
    for note in p.notes {
        let _ = writeln!(s, "<p class=\"kl-drawing-note\">note: {}</p>", escape(note));
    }
    s.push_str("</figure>\n<section class=\"kl-side\">\n<table class=\"kl-readouts\"><tbody>");
    for (k, c) in p.channels.iter().enumerate() {
        let _ = write!(
            s,
            r#"<tr class="kl-readout" data-ch="{k}"><th scope="row">{}</th><td class="kl-value" id="kl-v{k}">{}</td><td class="kl-unit">{}</td></tr>"#,
            escape(&c.label),
            c.text(c.values[0]),
            escape(&c.unit())
        );
    }
    s.push_str("</tbody></table>\n<div class=\"kl-charts\">");
    for (_, svg, _) in &p.charts {
        s.push_str(svg);
    }
    let about = match &p.grid {
        Some(g) => format!(
            "{n} of {} cells of a grid of the inputs ({}), computed by kinloop: from the first cell, each cell reached by a branch-safe sweep from a neighbour already solved, so that one assembly mode is carried throughout; where no sweep reached a cell on it (the mechanism cannot be assembled there, or a limit or singular position lies on the way), the page says so. Drag the sliders or use the arrow keys.",
            g.cells.len(),
            g.counts.iter().map(usize::to_string).collect::<Vec<_>>().join(" x "),
        ),
        None => {
            let poses = if n == 1 { "pose" } else { "poses" };
            format!("{n} {poses} of a branch-safe sweep, computed by kinloop; drag the slider or use the arrow keys.")
        }
    };
    let _ = write!(
        s,
        "</div>\n</section>\n</div>\n<p class=\"kl-note\">{about} Coordinates are drawn to 0.1 px, readouts to the digits shown.</p>\n</main>\n<script type=\"application/json\" id=\"kl-data\">{}</script>\n<script>{}</script>\n</body>\n</html>\n",
        data(p)?,
        script::SCRIPT
    );
    Ok(s)
}
