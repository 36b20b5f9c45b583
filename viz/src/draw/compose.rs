//! Whole pictures: a pose, a multi-exposure, an animation; built from the same layers.

use super::annotate::{FONT, LINE, readout, scale_bar, text_width};
use super::error::DrawError;
use super::motion::Motion;
use super::retrace::unretraced;
use super::scene::{Scene, Shape};
use super::shapes::{Pen, dot, guide, item, joints};
use super::spec::Drawing;
use super::svg::{Timing, animate, animate_transform, num, pair, round};
use super::view::View;
use crate::escape::escape;
use std::fmt::Write;

/// How an animation plays (see [`Drawing::animate`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Animation {
    /// Largest number of key frames taken from the motion (evenly spaced, always including the
    /// first and the last pose; default 90). Each is shown at its distance along the motion in
    /// input space, as a fraction of the pass (SMIL `keyTimes`): the inputs move at constant
    /// speed, also where the motion's poses do not divide evenly into the key frames.
    pub frames: usize,
    /// Duration of one pass in seconds (default 4), from a millisecond to a billion seconds;
    /// written as given (`dur="0.25s"`).
    pub seconds: f64,
    /// Play forward then backward (for a motion that stops at a limit position, where the real
    /// mechanism turns back); the key frames are then `2 k - 1` for `k` poses.
    pub back_and_forth: bool,
}

impl Default for Animation {
    fn default() -> Self {
        Animation { frames: 90, seconds: 4.0, back_and_forth: false }
    }
}

/// The shortest and longest durations of a pass, in seconds: below a millisecond no frame is
/// seen; beyond a billion seconds (thirty years) nothing moves.
pub(crate) const MIN_SECONDS: f64 = 1e-3;
pub(crate) const MAX_SECONDS: f64 = 1e9;

impl Animation {
    fn check(&self) -> Result<(), DrawError> {
        if self.frames < 2 {
            return Err(DrawError::InvalidSetting(format!(
                "an animation needs at least 2 frames, not {}",
                self.frames
            )));
        }
        if !(MIN_SECONDS..=MAX_SECONDS).contains(&self.seconds) {
            return Err(DrawError::InvalidSetting(format!(
                "animation duration {} s must be from {MIN_SECONDS} s to {MAX_SECONDS:e} s",
                self.seconds
            )));
        }
        Ok(())
    }
}

/// The poses of `path` shown by the forward key frames of `anim`.
fn keys(path: &[usize], anim: &Animation) -> Vec<usize> {
    spread(path.len(), anim.frames).into_iter().map(|k| path[k]).collect()
}

/// `count` indices evenly spread over `0..n`, first and last included.
fn spread(n: usize, count: usize) -> Vec<usize> {
    if count >= n {
        return (0..n).collect();
    }
    if count <= 1 {
        return vec![n - 1];
    }
    (0..count).map(|i| (i as f64 * (n - 1) as f64 / (count - 1) as f64).round() as usize).collect()
}

/// When each of the key frames `keys` (poses, along `path`) is shown, as a fraction of the
/// pass: its distance along the path in input space over the whole path's, so that the inputs
/// move at constant speed whatever the poses picked (181 samples in 90 key frames are steps of
/// 2 and 3 samples); by the key frame's number where the inputs do not move.
fn key_times(motion: &Motion, path: &[usize], keys: &[usize]) -> Vec<f64> {
    let poses: Vec<&[f64]> = motion.all_poses().map(|p| &p.x[..]).collect();
    let x = |i: usize| poses.get(i).copied().unwrap_or(&[]);
    let mut along = vec![0.0f64; path.iter().max().map_or(0, |m| m + 1)];
    let mut total = 0.0f64;
    for w in path.windows(2) {
        // Differences of halves: no overflow for any finite inputs.
        let step = x(w[0]).iter().zip(x(w[1])).map(|(a, b)| b / 2.0 - a / 2.0).fold(0.0f64, f64::hypot);
        total += step;
        along[w[1]] = total;
    }
    let n = keys.len();
    if !(total.is_finite() && total > 0.0) || n < 2 {
        return (0..n).map(|k| k as f64 / (n.max(2) - 1) as f64).collect();
    }
    keys.iter().map(|&i| along[i] / total).collect()
}

/// The shapes of item `k` at poses `keys`.
fn at_keys<'s>(scene: &'s Scene, keys: &[usize], k: usize) -> Vec<&'s Shape> {
    keys.iter().map(|&i| &scene.frames[i][k]).collect()
}

struct Layers<'a> {
    d: &'a Drawing,
    motion: &'a Motion,
    scene: Scene,
    /// Top of the strip of annotations under the mechanism, in pixels.
    strip: f64,
    /// The scale bar: its length in pixels and its label.
    bar: Option<(f64, String)>,
    /// Per input, its largest magnitude and its span over the poses: a readout writes every
    /// pose's value to the same digits.
    largest: Vec<(f64, f64)>,
    /// The notes as written, wrapped to the picture's width: each line, and whether it
    /// continues a note (indented by the width of `note: `).
    note_lines: Vec<(String, bool)>,
}

/// Decimals of the degrees in the readout (what a slider shows) and in the events' labels
/// (where a limit position lies, to compare with a calculation).
const READOUT_DECIMALS: usize = 1;
const EVENT_DECIMALS: usize = 2;

impl Layers<'_> {
    fn items(&self) -> usize {
        self.scene.frames[0].len()
    }

    /// The traced paths over the whole motion, consecutive equal pixels merged and segments
    /// that retrace ones already drawn left out (a sweep of many turns: one pass of the curve,
    /// not one a turn; see [`unretraced`]). Animated (`keys` and `timing`), each is drawn faint
    /// in full and again in full colour as far as the traced point has come at each key frame
    /// (a dash as long as the path, shifted), over its first piece: the whole path unless it
    /// retraces itself, and then its first pass.
    fn traces(&self, out: &mut String, anim: Option<(&[usize], Timing<'_>)>) {
        let path = self.scene.path(self.motion);
        for t in 0..self.d.traces.len() {
            let (pieces, along) = self.trace_points(&path, t);
            let (colour, width) = (self.d.style.trace(t), num(self.d.style.trace_width));
            let opacity = if anim.is_some() { r#" opacity="0.35""# } else { "" };
            let look =
                format!(r#"fill="none" stroke="{colour}" stroke-width="{width}" stroke-linejoin="round"{opacity}"#);
            match pieces.as_slice() {
                [pts] => {
                    let _ = write!(out, r#"<polyline class="trace" points="{pts}" {look}/>"#);
                }
                // A path that retraces itself, in pieces: one element (a polyline each would
                // outweigh their few points).
                _ => {
                    let d: Vec<String> = pieces.iter().map(|pts| format!("M{}", pts.replace(' ', "L"))).collect();
                    let _ = write!(out, r#"<path class="trace" d="{}" {look}/>"#, d.concat());
                }
            }
            let (Some((keys, timing)), Some(pts)) = (anim, pieces.first()) else { continue };
            let dash = (along.iter().fold(0.0f64, |m, s| m.max(*s)) + 1.0).ceil();
            let offsets: Vec<String> = keys.iter().map(|&k| num(dash - along[k])).collect();
            let _ = write!(
                out,
                r#"<polyline class="traced" points="{pts}" fill="none" stroke="{colour}" stroke-width="{width}" stroke-linejoin="round" stroke-dasharray="{d} {d}" stroke-dashoffset="{}">"#,
                offsets[0],
                d = num(dash)
            );
            animate(out, "stroke-dashoffset", &offsets, Some(timing));
            out.push_str("</polyline>");
        }
    }

    /// The pieces of trace `t` along `path` as written (rounded to a tenth of a pixel,
    /// [`unretraced`]), and for every pose of the scene the length of the first piece up to
    /// it (its whole length once the path has left it).
    fn trace_points(&self, path: &[usize], t: usize) -> (Vec<String>, Vec<f64>) {
        let rounded: Vec<[f64; 2]> = path.iter().map(|&i| self.scene.traced[i][t].map(round)).collect();
        // Rounded coordinates are equal as numbers exactly when their bits are (no -0: `round`
        // writes +0).
        let (pieces, at) = unretraced(rounded.iter().map(|p| p.map(f64::to_bits)));
        let as_f64 = |p: &[u64; 2]| p.map(f64::from_bits);
        let mut first = vec![0.0];
        if let Some(piece) = pieces.first() {
            for w in piece.windows(2) {
                let ([x0, y0], [x1, y1]) = (as_f64(&w[0]), as_f64(&w[1]));
                first.push(first[first.len() - 1] + (x1 - x0).hypot(y1 - y0));
            }
        }
        let mut along = vec![0.0; self.scene.frames.len()];
        let mut length = 0.0;
        for (&i, at) in path.iter().zip(&at) {
            if let Some((0, j)) = at {
                length = first[*j];
            }
            along[i] = length;
        }
        let pieces = pieces
            .iter()
            .map(|piece| {
                let mut pts = String::with_capacity(piece.len() * 12);
                for (k, p) in piece.iter().enumerate() {
                    let [x, y] = as_f64(p);
                    let _ = write!(pts, "{}{x},{y}", if k > 0 { " " } else { "" });
                }
                pts
            })
            .collect();
        (pieces, along)
    }

    /// Guides of sliders on fixed directions, over every pose.
    fn ground(&self, out: &mut String) {
        let all: Vec<usize> = (0..self.scene.frames.len()).collect();
        for k in 0..self.items() {
            let size = [self.scene.view.width, self.scene.view.height];
            guide(out, &self.d.style, &at_keys(&self.scene, &all, k), size);
        }
    }

    /// The mechanism at poses `keys` (one pose: static; several: animated with `timing`).
    fn mechanism(&self, out: &mut String, keys: &[usize], pen: &Pen) {
        for k in 0..self.items() {
            item(out, pen, &at_keys(&self.scene, keys, k));
        }
        for k in 0..self.items() {
            joints(out, pen, &at_keys(&self.scene, keys, k));
        }
    }

    /// Moving dots on the traced points.
    fn trace_dots(&self, out: &mut String, keys: &[usize], pen: &Pen) {
        for t in 0..self.d.traces.len() {
            let at: Vec<[f64; 2]> = keys.iter().map(|&i| self.scene.traced[i][t]).collect();
            let c = self.d.style.trace(t);
            dot(out, pen, &at, 2.5, c, c);
        }
    }

    /// Each event's pose as a dashed ghost, with a label in the strip saying what and where
    /// (angles in degrees).
    fn events(&self, out: &mut String) {
        let style = &self.d.style;
        let pen = Pen { style, ink: &style.event, fill: "none", ghost: true, dashed: true, timing: None };
        for j in 0..self.motion.events.len() {
            let _ = write!(out, r#"<g class="event">"#);
            self.mechanism(out, &[self.scene.samples + j], &pen);
            let _ = write!(
                out,
                r#"<text class="event-label" x="{}" y="{}" font-size="{FONT}" fill="{}">{}</text></g>"#,
                num(self.d.canvas.margin),
                num(self.line_y(self.first_event_line() + j)),
                style.event,
                escape(&self.event_label(j))
            );
        }
    }

    /// The drawing's notes after the events' labels, wrapped to the picture's width: one
    /// `<text class="note">` a line (each a line of its own in a PNG's stroke font too, which
    /// sets a `<text>` on one line), a note's later lines indented under its text.
    fn notes(&self, out: &mut String) {
        let first = self.first_event_line() + self.motion.events.len();
        for (k, (line, continued)) in self.note_lines.iter().enumerate() {
            let indent = if *continued { text_width(NOTE_PREFIX) } else { 0.0 };
            let _ = write!(
                out,
                r#"<text class="note" x="{}" y="{}" font-size="{FONT}" fill="{NOTE}">{}</text>"#,
                num(self.d.canvas.margin + indent),
                num(self.line_y(first + k)),
                escape(line)
            );
        }
    }

    /// `limit position at phi = 78.59°`.
    fn event_label(&self, j: usize) -> String {
        let e = &self.motion.events[j];
        let unit = self.d.length_unit.as_deref();
        format!(
            "{} at {}",
            e.kind,
            readout(&self.motion.inputs, &self.motion.input_kinds, &e.pose.x, &self.largest, unit, EVENT_DECIMALS)
        )
    }

    /// The readout of the inputs at pose `i`.
    fn readout_text(&self, i: usize) -> String {
        let x = &self.motion.all_poses().nth(i).map_or(&[][..], |p| &p.x[..]);
        let unit = self.d.length_unit.as_deref();
        readout(&self.motion.inputs, &self.motion.input_kinds, x, &self.largest, unit, READOUT_DECIMALS)
    }

    /// Whether the strip's first line holds the scale bar and the readout.
    fn first_line(&self) -> bool {
        self.bar.is_some() || (self.d.annotate.readout && !self.motion.inputs.is_empty())
    }

    fn first_event_line(&self) -> usize {
        usize::from(self.first_line())
    }

    /// The baseline of line `k` of the strip.
    fn line_y(&self, k: usize) -> f64 {
        self.strip + LINE * k as f64 + FONT
    }

    /// Where the readout starts: after the scale bar and its label (its width estimated, with
    /// room for wider faces such as the stroke font of PNG renders).
    fn readout_x(&self) -> f64 {
        let pad = self.d.canvas.margin;
        match &self.bar {
            Some((px, label)) => pad + px + 6.0 + text_width(label) + 28.0,
            None => pad,
        }
    }

    /// The scale bar and its label on the strip's first line.
    fn scale_bar(&self, out: &mut String) {
        let Some((px, label)) = &self.bar else { return };
        let (x0, y) = (self.d.canvas.margin, self.line_y(0) - 4.0);
        let ink = &self.d.style.ink;
        let _ = write!(
            out,
            r#"<g class="scale-bar"><path d="M{},{}V{}H{}V{}" fill="none" stroke="{ink}" stroke-width="1.5"/><text x="{}" y="{}" font-size="{FONT}" fill="{ink}">{}</text></g>"#,
            num(x0),
            num(y - 5.0),
            num(y),
            num(x0 + px),
            num(y - 5.0),
            num(x0 + px + 6.0),
            num(self.line_y(0)),
            escape(label)
        );
    }

    /// The inputs at the poses `keys` (one: static; several: each key frame's text shown in
    /// its turn, with `timing`, at `times`: a fraction of the pass for each key frame).
    fn readout(&self, out: &mut String, keys: &[usize], timing: Option<(Timing<'_>, &[f64])>) {
        if !self.d.annotate.readout || self.motion.inputs.is_empty() {
            return;
        }
        let (x, y, ink) = (num(self.readout_x()), num(self.line_y(0)), &self.d.style.ink);
        let _ = write!(out, r#"<g class="readout" font-size="{FONT}" fill="{ink}">"#);
        let n = keys.len();
        for (k, &i) in keys.iter().enumerate() {
            let shown = if k == 0 { "visible" } else { "hidden" };
            let _ = write!(out, r#"<text x="{x}" y="{y}" visibility="{shown}">{}"#, escape(&self.readout_text(i)));
            if let (Some((t, times)), true) = (timing, n > 1) {
                // Key frame k is shown at times[k] of the pass: its text from halfway from the
                // previous key frame to halfway to the next.
                let (from, to) =
                    ((times[k.saturating_sub(1)] + times[k]) / 2.0, (times[k] + times[(k + 1).min(n - 1)]) / 2.0);
                let (values, times) = if k == 0 {
                    ("visible;hidden".to_string(), format!("0;{}", frac(to)))
                } else if k + 1 == n {
                    ("hidden;visible".to_string(), format!("0;{}", frac(from)))
                } else {
                    ("hidden;visible;hidden".to_string(), format!("0;{};{}", frac(from), frac(to)))
                };
                let _ = write!(
                    out,
                    r#"<animate attributeName="visibility" calcMode="discrete" dur="{}s" repeatCount="indefinite" values="{values}" keyTimes="{times}"/>"#,
                    t.dur()
                );
            }
            out.push_str("</text>");
        }
        out.push_str("</g>");
    }

    /// The labels of the joints, following them over the key frames; a white halo keeps a
    /// label legible where it crosses a link or a path.
    fn labels(&self, out: &mut String, keys: &[usize], timing: Option<Timing<'_>>) {
        let ink = &self.d.style.ink;
        for (j, label) in self.scene.labels.iter().enumerate() {
            let values: Vec<String> = keys.iter().map(|&i| pair(self.scene.labelled[i][j])).collect();
            let _ = write!(out, r#"<g class="joint-label" transform="translate({})">"#, values[0]);
            animate_transform(out, "translate", &values, timing);
            let _ = write!(
                out,
                r#"<text x="{}" y="{}" font-size="{FONT}" text-anchor="{}" fill="{ink}" stroke="white" stroke-width="3" stroke-linejoin="round" paint-order="stroke">{}</text></g>"#,
                num(label.offset[0]),
                num(label.offset[1] + 0.35 * FONT),
                label.anchor,
                escape(&label.text)
            );
        }
    }

    fn document(&self, body: &str) -> String {
        let View { width, height, .. } = self.scene.view;
        let (w, h) = (num(width), num(height));
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif"><rect width="{w}" height="{h}" fill="white"/>{body}</svg>"#
        )
    }

    fn pen<'p>(&'p self, timing: Option<Timing<'p>>) -> Pen<'p> {
        let style = &self.d.style;
        Pen { style, ink: &style.ink, fill: &style.fill, ghost: false, dashed: false, timing }
    }
}

/// The colour of notes: apart from the ink and the events' red.
pub(crate) const NOTE: &str = "#a0522d";

/// What a note's first line starts with.
const NOTE_PREFIX: &str = "note: ";

/// The fewest characters a line of a note holds: a picture narrower than that (a mechanism
/// drawn small, no readout) is widened to hold them, whatever the notes' lengths; narrower,
/// a note would be a column of a word or two a line.
const NOTE_MIN_CHARS: usize = 40;

/// The most lines a note takes: a note says in a sentence or two what the drawing shows
/// otherwise than the reader would think; past this it is cut, ending with `…`, so that the
/// picture's height does not grow with the note's length (its whole text stays in
/// [`Drawing::notes`] and on the page).
const NOTE_MAX_LINES: usize = 8;

/// `note` as written (`note: text`) in lines of at most `chars` characters (at least
/// [`NOTE_MIN_CHARS`]), the later ones [`NOTE_PREFIX`]'s length shorter (they are indented by
/// its width): broken at spaces, a word longer than a line broken within it, runs of
/// spaces (and line breaks) made one. At most [`NOTE_MAX_LINES`], the last then ending with `…`.
/// Each line with whether it continues the note.
fn wrapped(note: &str, chars: usize) -> Vec<(String, bool)> {
    let chars = chars.max(NOTE_MIN_CHARS);
    let later = chars - NOTE_PREFIX.chars().count();
    let mut lines: Vec<Vec<char>> = Vec::new();
    let mut line: Vec<char> = NOTE_PREFIX.chars().collect();
    // Nothing on the line yet but the prefix, or nothing at all: no space before the next word.
    let mut fresh = true;
    for word in note.split_whitespace() {
        let mut word: Vec<char> = word.chars().collect();
        loop {
            let room = if lines.is_empty() { chars } else { later };
            let gap = usize::from(!fresh);
            let fits = room.saturating_sub(line.len() + gap);
            // The word here, or on the next line where it fits on one: otherwise as much of it
            // as fits here, the rest on the next (a fresh line always takes some of it).
            if word.len() <= fits || (fresh || word.len() > later) && fits > 0 {
                let here = word.len().min(fits);
                line.extend(std::iter::repeat_n(' ', gap).chain(word.drain(..here)));
                fresh = false;
                if word.is_empty() {
                    break;
                }
            }
            lines.push(std::mem::take(&mut line));
            fresh = true;
        }
    }
    lines.push(line);
    if lines.len() > NOTE_MAX_LINES {
        lines.truncate(NOTE_MAX_LINES);
        let last = &mut lines[NOTE_MAX_LINES - 1];
        last.truncate(later - 1);
        while last.last() == Some(&' ') {
            last.pop();
        }
        last.push('\u{2026}');
    }
    lines.into_iter().enumerate().map(|(k, l)| (l.into_iter().collect(), k > 0)).collect()
}

/// A key time (a fraction of the pass) as written.
fn frac(t: f64) -> String {
    format!("{:.5}", t.clamp(0.0, 1.0))
}

impl Drawing {
    fn layers<'a>(&'a self, motion: &'a Motion) -> Result<Layers<'a>, DrawError> {
        let scene = Scene::new(self, motion)?;
        let strip = scene.view.height;
        // The scale bar: a round length of at most a third of the mechanism's picture.
        let room = (scene.view.width / 3.0).max(60.0);
        let bar =
            if self.annotate.scale_bar { scale_bar(scene.view.scale, room, self.length_unit.as_deref()) } else { None };
        let largest = (0..motion.inputs.len())
            .map(|k| {
                let values = || motion.all_poses().filter_map(|p| p.x.get(k).copied());
                let (lo, hi) = values().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
                (values().fold(0.0f64, |m, v| m.max(v.abs())), hi - lo)
            })
            .collect();
        let mut l = Layers { d: self, motion, scene, strip, bar, largest, note_lines: Vec::new() };
        // The strip under the mechanism: the scale bar and readout, then one line per event,
        // then the notes; the picture is widened (when fitted) to hold the readout and the
        // events' labels, and the notes are wrapped to its width: a long note made the picture
        // as wide as its text, the mechanism a sliver at the side of a 10 000-pixel picture.
        let pad = self.canvas.margin;
        let mut need: f64 = 0.0;
        if l.first_line() {
            let widest = (0..l.scene.frames.len()).map(|i| text_width(&l.readout_text(i))).fold(0.0, f64::max);
            let readout = if self.annotate.readout { widest } else { 0.0 };
            need = l.readout_x() + readout + pad;
        }
        for j in 0..motion.events.len() {
            need = need.max(2.0 * pad + text_width(&l.event_label(j)));
        }
        if !self.notes.is_empty() {
            need = need.max(2.0 * pad + text_width(&"m".repeat(NOTE_MIN_CHARS)));
        }
        if self.canvas.window.is_none() {
            l.scene.view.width = l.scene.view.width.max(need.ceil());
        }
        // As many characters as the estimate of their width puts within the margins.
        let chars = ((l.scene.view.width - 2.0 * pad) / text_width("m")).floor().max(0.0) as usize;
        l.note_lines = self.notes.iter().flat_map(|n| wrapped(n, chars)).collect();
        let lines = l.first_event_line() + motion.events.len() + l.note_lines.len();
        if lines > 0 {
            l.scene.view.height += LINE * lines as f64 + 0.5 * LINE;
        }
        Ok(l)
    }

    /// The map from mechanism units to pixels this drawing uses for `motion` (fitted to every
    /// pose and cropped to what is drawn, or the canvas window), with the size of the whole
    /// picture (the strip of annotations included).
    pub fn view(&self, motion: &Motion) -> Result<View, DrawError> {
        Ok(self.layers(motion)?.scene.view)
    }

    /// The map from mechanism units to pixels of an interactive page's picture of `motion`: as
    /// [`Drawing::view`], but cropped to the items and traced paths alone, without the joint
    /// labels and the strip of annotations under the picture (scale bar, readout, events'
    /// labels, notes), which the page does not draw over its picture: it writes the readouts,
    /// the events and the notes as text of its own beside and under it.
    pub(crate) fn page_view(&self, motion: &Motion) -> Result<View, DrawError> {
        Ok(Scene::unlabelled(self, motion)?.view)
    }

    /// The mechanism at one pose (`pose` indexes the samples, then the events) as a static SVG,
    /// with the traced paths and the events. For print, slides and PNG frames.
    pub fn svg(&self, motion: &Motion, pose: usize) -> Result<String, DrawError> {
        let l = self.layers(motion)?;
        if pose >= l.scene.frames.len() {
            return Err(DrawError::InvalidSetting(format!(
                "pose {pose} out of range: the motion has {} poses",
                l.scene.frames.len()
            )));
        }
        let mut body = String::new();
        l.traces(&mut body, None);
        l.ground(&mut body);
        l.events(&mut body);
        l.mechanism(&mut body, &[pose], &l.pen(None));
        l.trace_dots(&mut body, &[pose], &l.pen(None));
        l.labels(&mut body, &[pose], None);
        l.scale_bar(&mut body);
        l.readout(&mut body, &[pose], None);
        l.notes(&mut body);
        Ok(l.document(&body))
    }

    /// A static multi-exposure for print: the mechanism at `count` poses evenly spread over the
    /// motion, earlier ones fainter, with the traced paths and the events.
    pub fn exposures(&self, motion: &Motion, count: usize) -> Result<String, DrawError> {
        if count == 0 {
            return Err(DrawError::InvalidSetting("a multi-exposure needs at least one pose".into()));
        }
        let l = self.layers(motion)?;
        let mut path = l.scene.path(motion);
        // A closed motion (a full turn) ends where it began: show that pose once.
        if path.len() > 1 && l.scene.same_look(path[0], path[path.len() - 1]) {
            path.pop();
        }
        let keys = spread(path.len(), count);
        let mut body = String::new();
        l.traces(&mut body, None);
        l.ground(&mut body);
        l.events(&mut body);
        // Earlier poses as thin outlines, fainter the earlier; the last one in full.
        let style = &self.style;
        let outline = Pen { style, ink: &style.ink, fill: "none", ghost: true, dashed: false, timing: None };
        for (j, &k) in keys.iter().enumerate() {
            if j + 1 == keys.len() {
                l.mechanism(&mut body, &[path[k]], &l.pen(None));
            } else {
                let _ = write!(body, r#"<g opacity="{:.2}">"#, 0.25 + 0.5 * (j + 1) as f64 / keys.len() as f64);
                l.mechanism(&mut body, &[path[k]], &outline);
                body.push_str("</g>");
            }
        }
        // Labelled at the pose drawn in full; the readout says which it is.
        if let Some(&last) = keys.last() {
            l.labels(&mut body, &[path[last]], None);
            l.readout(&mut body, &[path[last]], None);
        }
        l.scale_bar(&mut body);
        l.notes(&mut body);
        Ok(l.document(&body))
    }

    /// The poses shown by the key frames of `anim` (forward pass), as indices for
    /// [`Drawing::svg`].
    pub fn key_poses(&self, motion: &Motion, anim: &Animation) -> Result<Vec<usize>, DrawError> {
        anim.check()?;
        Ok(keys(&Scene::new(self, motion)?.path(motion), anim))
    }

    /// An animated SVG of the motion (SMIL `<animate>`/`<animateTransform>`, no script: plays
    /// in browsers and in rendered READMEs; a static renderer shows the first key frame), with
    /// the traced paths, a dot moving on each, and the events' poses marked.
    pub fn animate(&self, motion: &Motion, anim: &Animation) -> Result<String, DrawError> {
        anim.check()?;
        let l = self.layers(motion)?;
        let path = l.scene.path(motion);
        let mut keys = keys(&path, anim);
        let mut times = key_times(motion, &path, &keys);
        if anim.back_and_forth && keys.len() > 1 {
            let back: Vec<usize> = keys.iter().rev().skip(1).copied().collect();
            keys.extend(back);
            // Forward in the first half of the pass, back in the second.
            let back: Vec<f64> = times.iter().rev().skip(1).map(|t| 1.0 - t / 2.0).collect();
            times.iter_mut().for_each(|t| *t /= 2.0);
            times.extend(back);
        }
        let written: Vec<String> = times.iter().map(|t| frac(*t)).collect();
        let key_times = written.join(";");
        let timing = Some(Timing { seconds: anim.seconds, key_times: &key_times });
        let pen = l.pen(timing);
        let mut body = String::new();
        l.traces(&mut body, timing.map(|t| (&keys[..], t)));
        l.ground(&mut body);
        l.events(&mut body);
        l.mechanism(&mut body, &keys, &pen);
        l.trace_dots(&mut body, &keys, &pen);
        l.labels(&mut body, &keys, timing);
        l.scale_bar(&mut body);
        l.readout(&mut body, &keys, timing.map(|t| (t, &times[..])));
        l.notes(&mut body);
        Ok(l.document(&body))
    }
}
