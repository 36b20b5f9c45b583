//! Whole pictures: a pose, a multi-exposure, an animation; built from the same layers.

use super::error::DrawError;
use super::motion::Motion;
use super::scene::{Scene, Shape};
use super::shapes::{Pen, dot, guide, item, joints};
use super::spec::Drawing;
use super::svg::{Timing, animate, escape, num, round};
use super::view::View;
use std::fmt::Write;

/// How an animation plays (see [`Drawing::animate`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Animation {
    /// Largest number of key frames taken from the motion (evenly spaced, always including the
    /// first and the last pose; default 90).
    pub frames: usize,
    /// Duration of one pass in seconds (default 4).
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

impl Animation {
    fn check(&self) -> Result<(), DrawError> {
        if self.frames < 2 {
            return Err(DrawError::InvalidSetting(format!(
                "an animation needs at least 2 frames, not {}",
                self.frames
            )));
        }
        if !(self.seconds.is_finite() && self.seconds > 0.0) {
            return Err(DrawError::InvalidSetting(format!("animation duration {} s must be positive", self.seconds)));
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

/// The shapes of item `k` at poses `keys`.
fn at_keys<'s>(scene: &'s Scene, keys: &[usize], k: usize) -> Vec<&'s Shape> {
    keys.iter().map(|&i| &scene.frames[i][k]).collect()
}

struct Layers<'a> {
    d: &'a Drawing,
    motion: &'a Motion,
    scene: Scene,
}

impl Layers<'_> {
    fn items(&self) -> usize {
        self.scene.frames[0].len()
    }

    /// The traced paths over the whole motion, consecutive equal pixels merged. Animated
    /// (`keys` and `timing`), each is drawn faint in full and again in full colour as far as
    /// the traced point has come at each key frame (a dash as long as the path, shifted).
    fn traces(&self, out: &mut String, anim: Option<(&[usize], Timing)>) {
        let path = self.scene.path(self.motion);
        for t in 0..self.d.traces.len() {
            let (pts, along) = self.trace_points(&path, t);
            let (colour, width) = (self.d.style.trace(t), num(self.d.style.trace_width));
            let opacity = if anim.is_some() { r#" opacity="0.35""# } else { "" };
            let _ = write!(
                out,
                r#"<polyline class="trace" points="{pts}" fill="none" stroke="{colour}" stroke-width="{width}" stroke-linejoin="round"{opacity}/>"#
            );
            let Some((keys, timing)) = anim else { continue };
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

    /// The points of trace `t` along `path` as written (rounded, consecutive equal ones
    /// merged), and for every pose of the scene the length of that polyline up to it.
    fn trace_points(&self, path: &[usize], t: usize) -> (String, Vec<f64>) {
        let mut pts = String::new();
        let mut along = vec![0.0; self.scene.frames.len()];
        let (mut length, mut prev) = (0.0, None::<[f64; 2]>);
        for &i in path {
            let [x, y] = self.scene.traced[i][t].map(round);
            if prev != Some([x, y]) {
                if let Some([px, py]) = prev {
                    length += (x - px).hypot(y - py);
                    pts.push(' ');
                }
                let _ = write!(pts, "{x},{y}");
                prev = Some([x, y]);
            }
            along[i] = length;
        }
        (pts, along)
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

    /// Each event's pose as a dashed ghost, with a label saying what and where.
    fn events(&self, out: &mut String) {
        let style = &self.d.style;
        let pen = Pen { style, ink: &style.event, fill: "none", ghost: true, dashed: true, timing: None };
        for (j, e) in self.motion.events.iter().enumerate() {
            let _ = write!(out, r#"<g class="event">"#);
            self.mechanism(out, &[self.scene.samples + j], &pen);
            let at: Vec<String> =
                self.motion.inputs.iter().zip(&e.pose.x).map(|(n, v)| format!("{n} = {v:.4}")).collect();
            let _ = write!(
                out,
                r#"<text x="8" y="{}" font-family="sans-serif" font-size="12" fill="{}">{} at {}</text></g>"#,
                16 + 15 * j,
                style.event,
                e.kind,
                escape(&at.join(", "))
            );
        }
    }

    fn document(&self, body: &str) -> String {
        let View { width, height, .. } = self.scene.view;
        let (w, h) = (num(width), num(height));
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}"><rect width="{w}" height="{h}" fill="white"/>{body}</svg>"#
        )
    }

    fn pen(&self, timing: Option<Timing>) -> Pen<'_> {
        let style = &self.d.style;
        Pen { style, ink: &style.ink, fill: &style.fill, ghost: false, dashed: false, timing }
    }
}

impl Drawing {
    fn layers<'a>(&'a self, motion: &'a Motion) -> Result<Layers<'a>, DrawError> {
        Ok(Layers { d: self, motion, scene: Scene::new(self, motion)? })
    }

    /// The map from mechanism units to pixels this drawing uses for `motion` (fitted to every
    /// pose, or the canvas window).
    pub fn view(&self, motion: &Motion) -> Result<View, DrawError> {
        Ok(Scene::new(self, motion)?.view)
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
        let mut keys = keys(&l.scene.path(motion), anim);
        if anim.back_and_forth && keys.len() > 1 {
            let back: Vec<usize> = keys.iter().rev().skip(1).copied().collect();
            keys.extend(back);
        }
        let pen = l.pen(Some(Timing { seconds: anim.seconds }));
        let mut body = String::new();
        l.traces(&mut body, Some((&keys, Timing { seconds: anim.seconds })));
        l.ground(&mut body);
        l.events(&mut body);
        l.mechanism(&mut body, &keys, &pen);
        l.trace_dots(&mut body, &keys, &pen);
        Ok(l.document(&body))
    }
}
