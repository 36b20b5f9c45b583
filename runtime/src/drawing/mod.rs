//! What a mechanism's declaration says about how it looks: the chain of points of every loop,
//! each vector between two of them classified, the named points, the rigid plates, and notes
//! where the declaration cannot be drawn unambiguously. `mechanism!` emits it
//! ([`Mechanism::DRAWING`]); `kinloop::draw` turns it into a drawing.
//!
//! * Each loop's sides are chains of points: the partial sums of their vectors, from the origin
//!   to the loop's closing point, where both sides meet. Points with the same partial sum (the
//!   same vectors, in any order, after cancelling a vector added and subtracted) are one
//!   [`Joint`], across loops too; a loop's two ends are one joint. This is decided
//!   symbolically, by the macro: points that coincide only numerically stay apart.
//! * Loops are drawn in one frame: each from the origin, unless one of its links is a link of
//!   an earlier loop (the same `l @ q`): then the loop starts where that link puts it (a second
//!   loop written from its own frame pivot). A joint that a constant vector joins to a fixed
//!   joint is fixed too.
//! * A vector `l @ q` of constant length turning with an input or unknown angle is a
//!   [`SegmentKind::Link`]; a constant vector (parameters and numbers only) is
//!   [`SegmentKind::Ground`]; a Cartesian vector with one coordinate that moves, or a polar one
//!   of varying length, is a [`SegmentKind::Slider`] (along its axis or its angle); anything
//!   else is [`SegmentKind::Construction`], with a note.
//! * Links that turn with the same angle (up to a constant offset) and share a joint are one
//!   [`Plate`]; a named point reached from a plate's joint by vectors turning with the plate
//!   belongs to it; a plate whose angle a declared `body` turns with takes the body's name.
//! * A slider's turning guide (a slotted rocker `s @ theta`) is rigid with what turns alike
//!   about the joint it starts from: a plate of links there, or the named points reached from
//!   that joint by vectors turning with the guide (the rocker's tip), which make a plate of
//!   their own. That plate lists the guide ([`Plate::guides`]); a drawing draws the guide as
//!   one bar reaching the block and the plate's joints.
//!
//! A mechanism read at run time (`kinloop_model::Model`) carries the same text, written by the
//! same function of the macro's pipeline; [`Drawable`] is what a drawing reads from either kind
//! of mechanism (implemented by [`Compiled`](crate::Compiled) and by the model), so that
//! `kinloop_viz` draws both with one code.
//!
//! With `mechanism!`, `Description::of::<Name, N, NI, NO>()` reads a mechanism's; here one
//! written out, of a crank `r @ phi` from the origin (the tape evaluates the parameter `r`,
//! the input `phi` and `r cos phi`, `r sin phi`):
//!
//! ```
//! use kinloop_runtime::drawing::{Description, SegmentKind};
//!
//! let d = Description::parse(
//!     "kinloop-drawing 1\n\
//!      t c:0 p:0 x:0 cos:2 mul:1,3 sin:2 mul:1,5\n\
//!      j origin g - 0 0\n\
//!      j crank.l1 m - 4 6\n\
//!      s 0 1 link 2 crank: r @ phi",
//! )?;
//! assert_eq!(d.segments[0].kind, SegmentKind::Link);
//! let at = d.evaluate(&[2.0], &[0.5], &[])?;
//! assert_eq!(at.joints[d.joint("crank.l1").unwrap()], [2.0 * 0.5f64.cos(), 2.0 * 0.5f64.sin()]);
//! assert_eq!(at.angles[0], Some(0.5));
//! # Ok::<(), kinloop_runtime::Error>(())
//! ```

mod parse;
mod source;
mod tape;

use crate::error::Error;
use crate::mechanism::Mechanism;
pub use source::{Columns, Drawable};
use std::fmt;
use tape::TapeOp;
pub use tape::Values;

/// The version line the macro writes first: a description in another format is refused.
pub const FORMAT: &str = "kinloop-drawing 1";

/// A point of the drawing: a loop's partial sum, a named point, or both.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The `point`'s name, or `loop.lK` / `loop.rK` (the `K`-th point of the loop's left or
    /// right chain), or `origin`.
    pub name: String,
    /// It depends on parameters only: a fixed point of the frame.
    pub ground: bool,
    /// It is a declared `point` (whose path a drawing traces).
    pub named: bool,
    x: usize,
    y: usize,
}

/// How a vector of a loop is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SegmentKind {
    /// A rigid link: constant length, turning with an input or unknown.
    Link,
    /// A constant vector: part of the frame.
    Ground,
    /// A prismatic pair: a Cartesian vector with one moving coordinate, or a polar vector of
    /// varying length; its end slides along the segment's angle.
    Slider {
        /// The guide does not turn (an axis, or a constant angle); else it turns with the
        /// segment's angle (a slotted rocker, a cylinder).
        fixed_guide: bool,
    },
    /// A vector that is neither (a rotated vector, both coordinates moving): drawn as a thin
    /// line, with a note.
    Construction,
}

/// One vector of a loop, between two joints.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// Index of the joint it starts from.
    pub from: usize,
    /// Index of the joint it ends at.
    pub to: usize,
    /// How it is drawn.
    pub kind: SegmentKind,
    /// The vector as declared (`r @ phi`, `(x_c, 0)`), with its loop: `obcd: r @ phi`.
    pub term: String,
    angle: Option<usize>,
}

/// Joints that move as one rigid body.
#[derive(Clone, Debug, PartialEq)]
pub struct Plate {
    /// The declared `body` that turns with it, if any.
    pub name: Option<String>,
    /// Its joints, at least two.
    pub joints: Vec<usize>,
    /// The sliders on a turning guide (indices of [`Description::segments`]) whose guide is
    /// part of this body: it turns with the plate about the segment's first joint.
    pub guides: Vec<usize>,
}

/// The drawing a declaration describes (see the [module documentation](self)).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Description {
    /// The points.
    pub joints: Vec<Joint>,
    /// The vectors of the loops, each once.
    pub segments: Vec<Segment>,
    /// The rigid bodies.
    pub plates: Vec<Plate>,
    /// What the declaration leaves ambiguous, and how the drawing shows it.
    pub notes: Vec<String>,
    tape: Vec<TapeOp>,
}

impl Description {
    /// The description `mechanism!` emitted for `M`. A mechanism written by hand has none: it
    /// gets an empty description with a note saying so.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the text is not a description of this format (never for
    /// one `mechanism!` emitted with this version of kinloop).
    pub fn of<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>() -> Result<Description, Error>
    {
        Description::from_text(M::NAME, M::DRAWING)
    }

    /// The description `text` of mechanism `name` ([`Drawable::description_text`]), as
    /// [`Description::of`] reads a compiled mechanism's: an empty text is an empty description
    /// with a note saying so.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when the text is not a description of this format.
    pub fn from_text(name: &str, text: &str) -> Result<Description, Error> {
        if text.is_empty() {
            return Ok(Description {
                joints: Vec::new(),
                segments: Vec::new(),
                plates: Vec::new(),
                notes: vec![format!("`{name}` was not declared with `mechanism!`: it describes no drawing")],
                tape: Vec::new(),
            });
        }
        Description::parse(text)
    }

    /// The index of the joint `name`.
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }

    /// The joints' coordinates and the segments' angles at a state, from the parameter values
    /// (`Mechanism::param_values`), inputs and unknowns in declaration order.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when a slice is shorter than the description needs.
    pub fn evaluate(&self, params: &[f64], x: &[f64], q: &[f64]) -> Result<Values, Error> {
        let v = tape::run(&self.tape, params, x, q)?;
        let joints = self.joints.iter().map(|j| [v[j.x], v[j.y]]).collect();
        let angles = self.segments.iter().map(|s| s.angle.map(|a| v[a])).collect();
        Ok(Values { joints, angles })
    }
}

impl fmt::Display for SegmentKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SegmentKind::Link => "link",
            SegmentKind::Ground => "ground",
            SegmentKind::Slider { fixed_guide: true } => "slider on a fixed guide",
            SegmentKind::Slider { fixed_guide: false } => "slider on a turning guide",
            SegmentKind::Construction => "construction",
        })
    }
}

/// The description in words, one line per joint, segment, plate and note: what the snapshot
/// tests pin.
impl fmt::Display for Description {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for j in &self.joints {
            let what = match (j.ground, j.named) {
                (true, true) => "fixed, named",
                (true, false) => "fixed",
                (false, true) => "moving, named",
                (false, false) => "moving",
            };
            writeln!(f, "joint {} ({what})", j.name)?;
        }
        for s in &self.segments {
            let (a, b) = (&self.joints[s.from].name, &self.joints[s.to].name);
            writeln!(f, "{} {a} -> {b}: {}", s.kind, s.term)?;
        }
        for p in &self.plates {
            let names: Vec<&str> = p.joints.iter().map(|&j| self.joints[j].name.as_str()).collect();
            write!(f, "plate {}: {}", p.name.as_deref().unwrap_or("-"), names.join(", "))?;
            for &s in &p.guides {
                write!(f, "; the guide of {}", self.segments[s].term)?;
            }
            writeln!(f)?;
        }
        for n in &self.notes {
            writeln!(f, "note: {n}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::demo::SliderCrank;

    #[test]
    fn a_hand_written_mechanism_describes_no_drawing_and_says_so() {
        let d = Description::of::<SliderCrank, 1, 1, 1>().unwrap();
        assert!(d.joints.is_empty() && d.segments.is_empty());
        assert_eq!(d.notes.len(), 1);
        assert!(d.notes[0].contains("not declared with `mechanism!`"), "{:?}", d.notes);
        assert_eq!(d.evaluate(&[], &[], &[]).unwrap().joints, Vec::<[f64; 2]>::new());
    }
}
