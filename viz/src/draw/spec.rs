//! What to draw: a run-time description of the mechanism's links, pivots, sliders and gears,
//! through points named after the mechanism's outputs, fixed points or expressions of the state.

use super::annotate::Annotate;
use super::style::Style;
use super::view::Canvas;
use std::fmt;
use std::sync::Arc;

/// The state of the mechanism at one pose, as flat slices in declaration order: what
/// [`Pt::expr`] and [`Scalar::expr`] closures read.
#[derive(Clone, Copy, Debug)]
pub struct StateRef<'a> {
    /// Input values (`Mechanism::INPUTS` order).
    pub x: &'a [f64],
    /// Unknowns (`Mechanism::UNKNOWNS` order).
    pub q: &'a [f64],
    /// Output columns (`Mechanism::OUTPUTS` order).
    pub out: &'a [f64],
}

pub(crate) type PointFn = Arc<dyn Fn(&StateRef) -> [f64; 2] + Send + Sync>;
type ScalarFn = Arc<dyn Fn(&StateRef) -> f64 + Send + Sync>;

/// A point of the drawing, in the mechanism's own units.
#[derive(Clone)]
pub enum Pt {
    /// A `point` output of the mechanism, by name (its output columns `name.x`, `name.y`).
    Point(String),
    /// A fixed point.
    Fixed([f64; 2]),
    /// An expression of the state (for joints the declaration does not name as points).
    Expr(PointFn),
}

impl Pt {
    /// The mechanism's `point` output `name`.
    pub fn point(name: impl Into<String>) -> Pt {
        Pt::Point(name.into())
    }

    /// A fixed point `(x, y)`.
    pub fn fixed(x: f64, y: f64) -> Pt {
        Pt::Fixed([x, y])
    }

    /// A point computed from the state, e.g. a crank pin `|s| [r * s.x[0].cos(), r * s.x[0].sin()]`.
    pub fn expr(f: impl Fn(&StateRef) -> [f64; 2] + Send + Sync + 'static) -> Pt {
        Pt::Expr(Arc::new(f))
    }

    /// How the point is named in error messages.
    pub(crate) fn describe(&self) -> String {
        match self {
            Pt::Point(n) => format!("point `{n}`"),
            Pt::Fixed([x, y]) => format!("fixed point ({x}, {y})"),
            Pt::Expr(_) => "point expression".to_string(),
        }
    }
}

impl fmt::Debug for Pt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe())
    }
}

impl From<&str> for Pt {
    fn from(name: &str) -> Pt {
        Pt::point(name)
    }
}

impl From<[f64; 2]> for Pt {
    fn from(p: [f64; 2]) -> Pt {
        Pt::Fixed(p)
    }
}

/// An angle (radians, counter-clockwise from the X axis) or another scalar of the drawing:
/// constant or computed from the state.
#[derive(Clone)]
pub enum Scalar {
    /// A constant.
    Const(f64),
    /// An expression of the state.
    Expr(ScalarFn),
}

impl Scalar {
    /// A scalar computed from the state, e.g. a rocker angle `|s| s.q[1]`.
    pub fn expr(f: impl Fn(&StateRef) -> f64 + Send + Sync + 'static) -> Scalar {
        Scalar::Expr(Arc::new(f))
    }
}

impl fmt::Debug for Scalar {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Scalar::Const(v) => write!(f, "Const({v})"),
            Scalar::Expr(_) => f.write_str("Expr(..)"),
        }
    }
}

impl From<f64> for Scalar {
    fn from(v: f64) -> Scalar {
        Scalar::Const(v)
    }
}

/// Corners of a [`Drawing::circle`]: a chord of a 96th of a turn lies within
/// `1 - cos(pi / 96)`, 0.05 %, of the radius.
const CIRCLE_CORNERS: usize = 96;

/// One element of a drawing (see the builder methods of [`Drawing`]). More kinds may be
/// added: a `match` over it outside this crate needs a wildcard arm.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum Item {
    /// A rigid link through points: a bar for two points, a chain of bars or, `closed`, a
    /// filled polygon (a ternary link). Each point gets a joint circle.
    Link {
        /// The points the link joins.
        through: Vec<Pt>,
        /// Fill the polygon through the points.
        closed: bool,
    },
    /// A fixed pivot (frame joint) with ground hatching.
    Pivot {
        /// The pivot's position.
        at: Pt,
    },
    /// A slider block at `at` on a guide in direction `angle`. A constant angle draws the
    /// guide (ground line with hatching) over the whole stroke; a moving guide (a rocker) is
    /// drawn as a link by the caller.
    Slider {
        /// The block's position.
        at: Pt,
        /// Direction of the guide (radians).
        angle: Scalar,
    },
    /// A guide that turns (a slotted rocker, a cylinder): one bar from `from` along `angle`,
    /// of the same length at every pose. It reaches, over the whole motion drawn, a tenth past
    /// the farthest place of the block sliding on it and as far as every point of `body` (the
    /// points rigid with it: a rocker's tip), each measured along the guide; it starts at
    /// `from` unless the block or the body reach behind it. The block is drawn by a
    /// [`Item::Slider`].
    Guide {
        /// The joint the guide turns about.
        from: Pt,
        /// Its direction (radians).
        angle: Scalar,
        /// The block sliding on it.
        block: Pt,
        /// Points of the body the guide is part of.
        body: Vec<Pt>,
    },
    /// A gear as its pitch circle of `radius` about `centre`, with a radius marking its turn
    /// `angle`.
    Gear {
        /// The gear's centre.
        centre: Pt,
        /// Its pitch radius.
        radius: f64,
        /// Its turn angle (radians).
        angle: Scalar,
    },
    /// A rigid outline carried by a turning body: a cam's profile, a roller's rim, a link's
    /// true shape. `points` are in the body's own frame (mechanism units, about `centre`), turned
    /// by `angle` and drawn as a closed outline, lightly filled. A cam's profile from
    /// [`cam_profile`](kinloop_runtime::analysis::cam::cam_profile) is such an outline about the
    /// cam's pivot, turned by the cam's angle.
    Outline {
        /// Where the body's frame has its origin.
        centre: Pt,
        /// The outline's corners in the body's frame, at least 2.
        points: Vec<[f64; 2]>,
        /// The body's turn (radians).
        angle: Scalar,
    },
    /// A lone joint circle.
    Joint {
        /// The joint's position.
        at: Pt,
    },
    /// A construction line from `from` to `to`: a vector of the declaration that is no part of
    /// the machine (neither a link, a slider nor the frame, see
    /// [`SegmentKind::Construction`](kinloop_runtime::drawing::SegmentKind::Construction)),
    /// drawn as a thin dashed line with no joint circles, so that it does not read as a link.
    Construction {
        /// Where the line starts.
        from: Pt,
        /// Where it ends.
        to: Pt,
    },
}

/// A drawing description: what to draw of a mechanism, at any pose.
///
/// Items are drawn in the order added (later ones on top), then every joint circle on top of
/// all. Sizes of strokes, circles and blocks are in pixels, so the picture does not depend on
/// the mechanism's unit of length. By default ([`Annotate`]) joints at named points carry
/// their names, and a strip under the picture holds a scale bar, the inputs at the pose shown
/// (angles in degrees) and the events' labels.
#[derive(Clone, Debug, Default)]
pub struct Drawing {
    /// The elements, in drawing order.
    pub items: Vec<Item>,
    /// Points whose paths (coupler curves) are traced over the motion.
    pub traces: Vec<Pt>,
    /// Size of the picture and the part of the plane shown.
    pub canvas: Canvas,
    /// Colours and sizes.
    pub style: Style,
    /// Labels written beside points, `(point, text)`: a label at a named point replaces that
    /// joint's automatic label (an empty text removes it).
    pub labels: Vec<(Pt, String)>,
    /// The unit of the mechanism's lengths, written on the scale bar and in the readout of
    /// length inputs (`None`: the runtime's generic "length unit").
    pub length_unit: Option<String>,
    /// Which annotations are written (joint labels, scale bar, input readout).
    pub annotate: Annotate,
    /// Notes about the drawing (what it shows in a way the reader should know: a vector the
    /// default drawing could not classify, joints that coincide only numerically), written as
    /// lines `note: ...` in the strip under the picture (wrapped to its width, at most eight
    /// lines a note) and under an interactive page's picture.
    pub notes: Vec<String>,
}

impl Drawing {
    /// An empty drawing.
    pub fn new() -> Drawing {
        Drawing::default()
    }

    /// A bar or chain of bars through `through`.
    pub fn link<P: Into<Pt>>(mut self, through: impl IntoIterator<Item = P>) -> Drawing {
        self.items.push(Item::Link { through: through.into_iter().map(Into::into).collect(), closed: false });
        self
    }

    /// A rigid body drawn as the filled polygon through `corners` (a ternary link, a crank
    /// with two arms).
    pub fn body<P: Into<Pt>>(mut self, corners: impl IntoIterator<Item = P>) -> Drawing {
        self.items.push(Item::Link { through: corners.into_iter().map(Into::into).collect(), closed: true });
        self
    }

    /// A fixed pivot with ground hatching.
    pub fn pivot(mut self, at: impl Into<Pt>) -> Drawing {
        self.items.push(Item::Pivot { at: at.into() });
        self
    }

    /// A slider block at `at` moving along direction `angle` (radians from the X axis).
    pub fn slider(mut self, at: impl Into<Pt>, angle: impl Into<Scalar>) -> Drawing {
        self.items.push(Item::Slider { at: at.into(), angle: angle.into() });
        self
    }

    /// A turning guide from `from` along `angle`, long enough for `block` and `body` over the
    /// whole motion (see [`Item::Guide`]): a slotted rocker, with the block on it added by
    /// [`Drawing::slider`].
    pub fn guide<P: Into<Pt>>(
        mut self,
        from: impl Into<Pt>,
        angle: impl Into<Scalar>,
        block: impl Into<Pt>,
        body: impl IntoIterator<Item = P>,
    ) -> Drawing {
        let body = body.into_iter().map(Into::into).collect();
        self.items.push(Item::Guide { from: from.into(), angle: angle.into(), block: block.into(), body });
        self
    }

    /// A gear: pitch circle of `radius` (mechanism units) about `centre`, turned by `angle`.
    pub fn gear(mut self, centre: impl Into<Pt>, radius: f64, angle: impl Into<Scalar>) -> Drawing {
        self.items.push(Item::Gear { centre: centre.into(), radius, angle: angle.into() });
        self
    }

    /// A rigid outline of `points` (mechanism units, in the body's frame about `centre`),
    /// turned by `angle`: a cam's profile, a roller's rim ([`Drawing::circle`]).
    pub fn outline(mut self, centre: impl Into<Pt>, points: Vec<[f64; 2]>, angle: impl Into<Scalar>) -> Drawing {
        self.items.push(Item::Outline { centre: centre.into(), points, angle: angle.into() });
        self
    }

    /// A circle of `radius` (mechanism units) about `centre`: a roller, a disc. An outline of 96
    /// corners, 0.05 % of the radius off the circle at most.
    pub fn circle(self, centre: impl Into<Pt>, radius: f64) -> Drawing {
        let points = (0..CIRCLE_CORNERS)
            .map(|k| {
                let (s, c) = (std::f64::consts::TAU * k as f64 / CIRCLE_CORNERS as f64).sin_cos();
                [radius * c, radius * s]
            })
            .collect();
        self.outline(centre, points, 0.0)
    }

    /// A construction line from `from` to `to`: thin and dashed, with no joint circles (see
    /// [`Item::Construction`]).
    pub fn construction(mut self, from: impl Into<Pt>, to: impl Into<Pt>) -> Drawing {
        self.items.push(Item::Construction { from: from.into(), to: to.into() });
        self
    }

    /// A joint circle at `at`.
    pub fn joint(mut self, at: impl Into<Pt>) -> Drawing {
        self.items.push(Item::Joint { at: at.into() });
        self
    }

    /// Sets the picture's size and the part of the plane shown.
    pub fn with_canvas(mut self, canvas: Canvas) -> Drawing {
        self.canvas = canvas;
        self
    }

    /// Sets colours and sizes.
    pub fn with_style(mut self, style: Style) -> Drawing {
        self.style = style;
        self
    }

    /// Writes `text` beside `at` (a joint's name, a fixed point's letter). At a named point it
    /// replaces the automatic label (its name); an empty `text` removes that label.
    pub fn label(mut self, at: impl Into<Pt>, text: impl Into<String>) -> Drawing {
        self.labels.push((at.into(), text.into()));
        self
    }

    /// Names the unit of the mechanism's lengths (`"mm"`), for the scale bar and the readout.
    pub fn length_unit(mut self, unit: impl Into<String>) -> Drawing {
        self.length_unit = Some(unit.into());
        self
    }

    /// Sets which annotations are written.
    pub fn with_annotate(mut self, annotate: Annotate) -> Drawing {
        self.annotate = annotate;
        self
    }

    /// Adds a note, written under the picture (`note: text`) by every SVG of the drawing and by
    /// its interactive page. An SVG wraps it to the picture's width (a long note does not widen
    /// the picture) and cuts it with `…` past eight lines.
    ///
    /// ```
    /// use kinloop_viz::draw::{Drawing, Pt};
    /// let d = Drawing::new().link([Pt::fixed(0.0, 0.0), Pt::point("b")]).note("the crank is drawn shortened");
    /// assert_eq!(d.notes(), ["the crank is drawn shortened"]);
    /// ```
    pub fn note(mut self, text: impl Into<String>) -> Drawing {
        self.notes.push(text.into());
        self
    }

    /// The notes, in the order added.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Traces the path of `at` over the motion (a coupler curve).
    pub fn trace(mut self, at: impl Into<Pt>) -> Drawing {
        self.traces.push(at.into());
        self
    }
}
