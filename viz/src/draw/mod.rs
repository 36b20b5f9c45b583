//! Drawings and animations of mechanisms, as SVG: see the mechanism move and the curves its
//! points trace.
//!
//! A [`Drawing`] says, at run time, what to draw: links as bars or filled bodies through
//! points, fixed pivots with ground hatching, sliders with their guides, gears as circles,
//! construction lines (thin, dashed, with no joints), and the points whose paths (coupler
//! curves) are traced. A point ([`Pt`]) is one of the mechanism's `point` outputs by name (its
//! output columns `name.x`, `name.y`), a fixed point, or an expression of the state (for
//! joints the declaration does not name). A [`Motion`] records a sweep; the drawing then gives:
//!
//! * [`Drawing::animate`]: an animated SVG (SMIL, no script: it plays in browsers and in a
//!   README on a code host) with the traced paths;
//! * [`Drawing::exposures`]: a static multi-exposure for print;
//! * [`Drawing::svg`]: the mechanism at one pose; the module `png` renders it (feature `png`),
//!   its text drawn with a built-in stroke font;
//! * [`html()`]: an interactive page (slider, play/pause, live readouts, linked charts);
//!   [`html_grid`] for several inputs: one slider per input over a [`GridMotion`], a grid of
//!   the inputs swept carrying one assembly mode, with "not reached on this assembly mode"
//!   where it is not reached.
//!
//! A drawing's notes ([`Drawing::note`]; the default drawing's say what the declaration leaves
//! ambiguous) are written under the picture by every SVG and page. [`candidates()`] draws the
//! best candidates of a synthesis search over their targets (numbered, on axes with units, a
//! legend of rank and largest error).
//!
//! Where a sweep stopped at a limit position or passed a singular crossing, the drawing shows
//! the mechanism at the located event as a dashed ghost, labelled with its kind and input.
//! Sizes of strokes and circles are pixels and the picture is fitted to the motion (or to a
//! [`Canvas::window`]), so a mechanism in metres and the same in millimetres draw alike.
//! Mistakes are [`DrawError`]s: a name that is not a point, an empty motion, a non-finite
//! coordinate.
//!
//! ```
//! use kinloop_viz::draw::{Animation, Drawing, Motion, Pt};
//!
//! kinloop::mechanism! {
//!     /// Four-bar: crank `r` at O = (0, 0), coupler BC (`l`) carrying P, rocker `k` at (d, 0).
//!     pub struct FourBar {
//!         params r = 1.0, l = 3.0, k = 2.5, d = 3.0, e = 1.5, delta = 0.6;
//!         input phi;
//!         unknowns beta = 0.5, gamma = 1.5;
//!         loop obcd: r @ phi + l @ beta == (d, 0) + k @ gamma;
//!         point b = r @ phi;
//!         point c = (d, 0) + k @ gamma;
//!         point p = r @ phi + e @ (beta + delta);
//!     }
//! }
//!
//! let m = FourBar::default();
//! let motion = Motion::record(&m, m.sweep(0.0, std::f64::consts::TAU, 91, &m.guess(0.0))?)?;
//! let drawing = Drawing::new()
//!     .pivot(Pt::fixed(0.0, 0.0))
//!     .pivot(Pt::fixed(m.d, 0.0))
//!     .link([Pt::fixed(0.0, 0.0), Pt::point("b")])
//!     .body(["b", "c", "p"])
//!     .link([Pt::point("c"), Pt::fixed(m.d, 0.0)])
//!     .trace("p");
//! let svg = drawing.animate(&motion, &Animation::default())?;
//! assert!(svg.contains("<animate "));
//!
//! // A name that is not a point of the mechanism is an error, not a panic.
//! let wrong = Drawing::new().trace("q").animate(&motion, &Animation::default());
//! assert!(matches!(wrong, Err(kinloop_viz::draw::DrawError::UnknownPoint { .. })));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod annotate;
mod candidates;
mod compose;
mod declared;
mod error;
mod grid;
#[cfg(feature = "png")]
mod hershey;
mod motion;
#[cfg(feature = "png")]
pub mod png;
pub(crate) mod retrace;
mod scene;
mod shapes;
mod spec;
mod style;
mod svg;
#[cfg(feature = "png")]
mod text_paths;
mod view;

pub use annotate::Annotate;
pub use candidates::{CandidatesConfig, candidate_page, candidates};
pub use compose::Animation;
pub(crate) use compose::{MAX_SECONDS, MIN_SECONDS};
pub use declared::{DefaultDrawing, Draw};
pub use error::DrawError;
pub use grid::{GridMotion, MAX_GRID_CELLS};
pub use motion::{Marked, Motion, Pose};
pub use spec::{Drawing, Item, Pt, Scalar, StateRef};
pub use style::Style;
pub use view::{Canvas, View};
// A turning guide's length over a motion, for the interactive pages.
pub(crate) use scene::{guide_at, guide_spans};
// How a construction line looks, the same on the interactive pages.
pub(crate) use style::{CONSTRUCTION_DASH, CONSTRUCTION_WIDTH};

// Interactive pages of a drawing (`kinloop::draw::html`), from the crate's `html` module.
pub use crate::html::{HtmlConfig, HtmlError, Readout, html, html_grid, html_grid_of, html_of};
