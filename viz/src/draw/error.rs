//! What can go wrong when drawing a mechanism.

use kinloop_runtime::Number;
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
    /// A pose of the motion does not fit the motion's columns: a hand-pushed [`Pose`] with
    /// fewer (or more) input or output values than the motion names, or with another number
    /// of unknowns than its first pose.
    ///
    /// [`Pose`]: super::Pose
    MalformedPose {
        /// Index of the pose in the motion (events count after the samples).
        pose: usize,
        /// Which values: `"input"`, `"unknown"` or `"output column"`.
        part: &'static str,
        /// How many the pose has.
        len: usize,
        /// How many the motion needs.
        expected: usize,
    },
    /// A point, angle or radius of the drawing is NaN or infinite at one pose (e.g. a closure
    /// over the state returned NaN).
    NonFinite {
        /// Which part of the drawing (`"point c"`, `"angle of slider 2"`, ...).
        what: String,
        /// Index of the pose in the motion (events count after the samples).
        pose: usize,
    },
    /// A point maps to a pixel farther than a billion pixels from the picture (a window far
    /// smaller than the mechanism): its coordinates would not survive the SVG's number
    /// formats and renderers.
    OffCanvas {
        /// Which part of the drawing (`"point c"`, `"radius of item 2 (gear)"`, ...).
        what: String,
        /// Index of the pose in the motion (events count after the samples).
        pose: usize,
    },
    /// The drawing's extent is too small to be fitted: more pixels per unit of length than
    /// an `f64` holds (a mechanism spanning less than about 1e-305 units).
    Unscalable {
        /// Width of the extent, in the mechanism's units.
        width: f64,
        /// Height of the extent, in the mechanism's units.
        height: f64,
    },
    /// A setting outside its valid range (e.g. zero frames or a non-positive width).
    InvalidSetting(String),
    /// A grid whose lines along one input travel farther in all than a sweep follows (or than a
    /// sweep can measure): refused before any cell is swept.
    GridRange {
        /// The input's index among the mechanism's inputs.
        input: usize,
        /// The input's name.
        name: String,
        /// The first end of the input's range: in the mechanism's units (radians of an angle),
        /// or in degrees where `degrees` is set.
        lo: f64,
        /// The last end of the input's range, in the units of `lo`.
        hi: f64,
        /// The grid's lines along the input (the cells of the other inputs), each the whole range.
        lines: usize,
        /// The turns of the inputs the lines travel in all; infinite where no sweep can measure
        /// the length.
        turns: f64,
        /// The most turns a sweep follows.
        max_turns: f64,
        /// Whether `lo` and `hi` are written in degrees ([`DrawError::in_degrees`]).
        degrees: bool,
    },
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
            DrawError::MalformedPose { pose, part, len, expected } => write!(
                f,
                "pose {pose} has {len} {part} values but the motion needs {expected}: a pose must have one value per column"
            ),
            DrawError::NonFinite { what, pose } => write!(f, "{what} is not finite at pose {pose}"),
            DrawError::OffCanvas { what, pose } => write!(
                f,
                "{what} at pose {pose} lies more than 1e9 pixels outside the picture: widen the canvas window"
            ),
            DrawError::Unscalable { width, height } => write!(
                f,
                "the drawing spans only {width:e} x {height:e} units: too small to scale to pixels in f64; \
                 express the mechanism in a smaller unit of length"
            ),
            DrawError::InvalidSetting(s) => write!(f, "invalid drawing setting: {s}"),
            DrawError::GridRange { name, lo, hi, lines, turns, max_turns, degrees, .. } => {
                let units = if *degrees { "degrees" } else { "the mechanism's units: radians of an angle" };
                let (lo, hi) = (Number(*lo), Number(*hi));
                write!(
                    f,
                    "the grid sweeps input `{name}` over its range {lo} to {hi} ({units}) on each of its {lines} lines, "
                )?;
                if turns.is_finite() {
                    write!(
                        f,
                        "{turns:.3e} turns of the inputs in all, more than the {max_turns:e} turns a sweep follows: give \
                         `{name}` a shorter range, or the other inputs fewer values"
                    )
                } else {
                    write!(f, "a length no sweep can measure: give `{name}` a shorter range")
                }
            }
            DrawError::Sweep(e) => write!(f, "the sweep failed: {e}"),
            DrawError::Render(s) => write!(f, "cannot render the SVG: {s}"),
        }
    }
}

impl DrawError {
    /// This error with the values of inputs it names written in degrees, by `to_degrees` (as
    /// [`f64::to_degrees`]), where `is_angle` says the input (by its index) is an angle: for a
    /// caller that reads angles in degrees (the command line's `--deg`), so that its user reads
    /// them as they were given. Other errors are returned as they are.
    pub fn in_degrees(mut self, is_angle: impl Fn(usize) -> bool, to_degrees: impl Fn(f64) -> f64) -> Self {
        if let DrawError::GridRange { input, lo, hi, degrees, .. } = &mut self
            && !*degrees
            && is_angle(*input)
        {
            (*lo, *hi, *degrees) = (to_degrees(*lo), to_degrees(*hi), true);
        }
        self
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

/// Into kinloop's one error type, so that code making drawings and running analyses uses `?`
/// throughout: a failed sweep is that sweep's error again, anything else
/// [`kinloop_runtime::Error::Figure`], from which `downcast_ref` gives this back.
impl From<DrawError> for kinloop_runtime::Error {
    fn from(e: DrawError) -> Self {
        match e {
            DrawError::Sweep(e) => e,
            other => kinloop_runtime::Error::Figure(kinloop_runtime::Source::new(other)),
        }
    }
}
