//! Colours and sizes of drawings, in pixels (independent of the mechanism's unit of length).

use super::error::DrawError;
use super::view::MAX_WIDTH;

/// Width in pixels of a construction line ([`Item::Construction`](super::Item::Construction)):
/// thinner than the ghosts' 1.5, so that it reads as no part of the machine at any pose.
pub(crate) const CONSTRUCTION_WIDTH: f64 = 1.0;

/// Dashes of a construction line, in pixels: longer than the events' ghosts' (`5 3`), which
/// are drawn in their own colour too.
pub(crate) const CONSTRUCTION_DASH: &str = "8 4";

/// How a drawing looks. Sizes are pixels (at most a million, the widest canvas); colours are
/// SVG colours.
#[derive(Clone, Debug, PartialEq)]
pub struct Style {
    /// Colour of links, sliders and gears.
    pub ink: String,
    /// Fill of bodies (polygons) and slider blocks.
    pub fill: String,
    /// Width of link strokes.
    pub link_width: f64,
    /// Radius of joint circles.
    pub joint_radius: f64,
    /// Length and height of slider blocks.
    pub block: [f64; 2],
    /// Colours of the traced paths, used in turn.
    pub traces: Vec<String>,
    /// Width of the traced paths.
    pub trace_width: f64,
    /// Colour of the poses drawn at events (limit positions, singular crossings).
    pub event: String,
    /// Colour of the ground (pivots, guides) and its hatching.
    pub ground: String,
}

impl Default for Style {
    fn default() -> Self {
        let s = |c: &str| c.to_string();
        Style {
            ink: s("#1f3b5a"),
            fill: s("#9ec1e0"),
            link_width: 4.0,
            joint_radius: 3.5,
            block: [26.0, 14.0],
            traces: ["#d95f02", "#1b9e77", "#7570b3", "#e7298a", "#66a61e"].map(s).to_vec(),
            trace_width: 1.5,
            event: s("#c0143c"),
            ground: s("#555555"),
        }
    }
}

impl Style {
    /// Sizes must be finite, not negative and at most [`MAX_WIDTH`] pixels, the widest canvas
    /// (a larger stroke, joint or block widens the picture without bound, and a guide is
    /// hatched along a block's whole length), and colours must be writable into an SVG
    /// attribute as they are.
    pub(crate) fn check(&self) -> Result<(), DrawError> {
        let sizes = [
            ("link width", self.link_width),
            ("joint radius", self.joint_radius),
            ("block length", self.block[0]),
            ("block height", self.block[1]),
            ("trace width", self.trace_width),
        ];
        for (what, v) in sizes {
            if !(v.is_finite() && (0.0..=MAX_WIDTH).contains(&v)) {
                return Err(DrawError::InvalidSetting(format!(
                    "style {what} {v} must be finite, not negative and at most {MAX_WIDTH:e} pixels"
                )));
            }
        }
        let colours = [&self.ink, &self.fill, &self.event, &self.ground].into_iter().chain(&self.traces);
        for c in colours {
            if c.contains(['"', '<', '>', '&']) || c.chars().any(char::is_control) {
                return Err(DrawError::InvalidSetting(format!(
                    "style colour {c:?} holds a character that cannot stand in an SVG attribute (\", <, >, & or a \
                     control character)"
                )));
            }
        }
        Ok(())
    }

    /// The colour of trace `k`.
    pub(crate) fn trace(&self, k: usize) -> &str {
        self.traces.get(k % self.traces.len().max(1)).map_or("#d95f02", String::as_str)
    }
}
