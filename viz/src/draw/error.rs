//! What can go wrong when drawing a mechanism.

use std::fmt;

/// Why a drawing could not be made. Every mistake in a drawing description or its input is one
/// of these; drawing never panics and never writes a NaN coordinate.
#[derive(Debug)]
#[non_exhaustive]
pub enum DrawError {
    /// A drawing names a point that is not one of the mechanism's `point` outputs.
    UnknownPoint {
        /// The name used in the drawing.
        name: String,
        /// The mechanism's point outputs (columns `p.x`, `p.y` of `Mechanism::OUTPUTS`).
        available: Vec<String>,
    },
    /// There is no pose to draw: the motion is empty.
    EmptyMotion,
    /// A point, angle or radius of the drawing is NaN or infinite at one pose (e.g. a closure
    /// over the state returned NaN).
    NonFinite {
        /// Which part of the drawing (`"point c"`, `"angle of slider 2"`, ...).
        what: String,
        /// Index of the pose in the motion (events count after the samples).
        pose: usize,
    },
    /// A setting outside its valid range (e.g. zero frames or a non-positive width).
    InvalidSetting(String),
    /// The sweep failed before it could be drawn (not a stop at a located event, which is
    /// drawn and marked).
    Sweep(kinloop_runtime::Error),
    /// The SVG could not be rendered to PNG.
    Render(String),
}

impl fmt::Display for DrawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DrawError::UnknownPoint { name, available } if available.is_empty() => {
                write!(f, "no point `{name}`: the mechanism declares no `point` outputs; use `Pt::fixed` or `Pt::expr`")
            }
            DrawError::UnknownPoint { name, available } => {
                write!(f, "no point `{name}`: the mechanism's points are {}", available.join(", "))
            }
            DrawError::EmptyMotion => f.write_str("nothing to draw: the motion has no pose (an empty sweep)"),
            DrawError::NonFinite { what, pose } => write!(f, "{what} is not finite at pose {pose}"),
            DrawError::InvalidSetting(s) => write!(f, "invalid drawing setting: {s}"),
            DrawError::Sweep(e) => write!(f, "the sweep failed: {e}"),
            DrawError::Render(s) => write!(f, "cannot render the SVG: {s}"),
        }
    }
}

impl std::error::Error for DrawError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            DrawError::Sweep(e) => Some(e),
            _ => None,
        }
    }
}

impl From<kinloop_runtime::Error> for DrawError {
    fn from(e: kinloop_runtime::Error) -> Self {
        DrawError::Sweep(e)
    }
}
