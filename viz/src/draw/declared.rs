//! The default drawing of a mechanism, from its declaration (see [`Draw`]).

use super::compose::Animation;
use super::error::DrawError;
use super::motion::Motion;
use super::spec::{Drawing, Item, Pt, Scalar};
use super::style::Style;
use super::view::Canvas;
use crate::plot::series::bounds;
use kinloop_runtime::drawing::{Description, Drawable, SegmentKind};
use kinloop_runtime::{Compiled, Mechanism};
use std::sync::Arc;

/// `m.drawing()`: the default drawing of a mechanism, from its declaration. It reads the
/// description `mechanism!` emits ([`Description`]) and draws every loop's links, frame pivots,
/// sliders and rigid plates, and traces the named points, with no point described twice.
///
/// * A plate (links turning together, a declared `body`) is a filled polygon through its
///   joints, a lone link a bar;
/// * a fixed joint that a link or a turning guide starts or ends at is a pivot with hatching;
///   constant vectors between fixed joints (the frame) are not drawn;
/// * a slider on a fixed guide is a block at the vector's end with its hatched guide; on a
///   turning guide (a cylinder, a slotted rocker) the guide is one rigid bar ([`Item::Guide`])
///   and the block slides on it: the bar keeps one length over the motion drawn, a tenth past
///   the block's farthest place and out to the points of the body it is part of (a rocker's
///   tip, see [`kinloop_runtime::drawing::Plate::guides`]);
/// * a vector that is none of these is drawn as a thin dashed construction line between its
///   ends ([`Item::Construction`]), with no joint circles, and a note of the description says
///   so: the drawing never guesses silently. [`DefaultDrawing::notes`] lists the notes;
///   [`DefaultDrawing::into_drawing`] carries them ([`Drawing::notes`]), and the SVG and the
///   interactive page write them under the picture.
///
/// Joints are merged where the macro proves two partial sums equal (see
/// [`kinloop_runtime::drawing`]); points that coincide only numerically (at the inputs 0,
/// solved from the declared guess) stay two joints, with a note.
///
/// ```
/// use kinloop_viz::draw::{Animation, Draw, Motion};
///
/// kinloop::mechanism! {
///     pub struct FourBar {
///         params r = 1.0, l = 3.0, k = 2.5, d = 3.0, e = 1.5, delta = 0.6;
///         input phi;
///         unknowns beta = 0.5, gamma = 1.5;
///         loop obcd: r @ phi + l @ beta == (d, 0) + k @ gamma;
///         point p = r @ phi + e @ (beta + delta);
///     }
/// }
/// let m = FourBar::default();
/// let motion = Motion::record(&m, m.sweep(0.0, std::f64::consts::TAU, 91, &m.guess(0.0))?)?;
/// // Crank, coupler plate carrying P, rocker, two pivots; P traced. Rename a joint, add to it.
/// let drawing = m.drawing().rename("obcd.l1", "B")?.extend(|d| d.joint(kinloop_viz::draw::Pt::fixed(1.0, 1.0)));
/// assert!(drawing.notes().is_empty());
/// assert!(drawing.joint("B").is_ok());
/// let svg = drawing.animate(&motion, &Animation::default())?;
/// assert!(svg.contains("<animate ") && !svg.contains("NaN"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait Draw<const N: usize, const NI: usize, const NO: usize> {
    /// The mechanism drawn as its declaration describes it (see [`Draw`]).
    fn drawing(&self) -> DefaultDrawing;
}

impl<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize> Draw<N, NI, NO> for M {
    fn drawing(&self) -> DefaultDrawing {
        DefaultDrawing::new(self)
    }
}

/// The description and the parameter values it is evaluated with, shared by every point.
struct Source {
    description: Description,
    params: Vec<f64>,
    /// Zero inputs and unknowns: a state to evaluate what depends on the parameters only.
    zero: [Vec<f64>; 2],
}

/// A mechanism's default drawing, to restyle, extend or trim before drawing it: a [`Drawing`]
/// built from the declaration ([`DefaultDrawing::into_drawing`]), with the joints named.
#[derive(Clone)]
pub struct DefaultDrawing {
    source: Arc<Source>,
    names: Vec<String>,
    hidden_joints: Vec<bool>,
    hidden_segments: Vec<bool>,
    untraced: Vec<bool>,
    notes: Vec<String>,
    /// Each plate's joints in the order drawn (around the plate at the reference state).
    plates: Vec<Vec<usize>>,
    /// Style, canvas, and the items and traces added by [`DefaultDrawing::extend`].
    extra: Drawing,
}

impl DefaultDrawing {
    /// The default drawing of `m`. A plate of four or more joints is drawn around its centre
    /// as the mechanism stands at the inputs `0` solved from the declared guess (the reference
    /// state); where that does not solve, in the declared order, with a note.
    pub fn new<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(m: &M) -> DefaultDrawing {
        DefaultDrawing::of(&mut Compiled(m))
    }

    /// The default drawing of any [`Drawable`] mechanism: a compiled one (as
    /// [`DefaultDrawing::new`]) or a `kinloop_model::Model` read at run time, which carries
    /// the same description as the compiled mechanism of its declaration and so draws the same.
    pub fn of<D: Drawable + ?Sized>(m: &mut D) -> DefaultDrawing {
        let (description, mut notes) = match Description::from_text(m.name(), m.description_text()) {
            Ok(d) => (d, Vec::new()),
            Err(e) => (Description::default(), vec![e.to_string()]),
        };
        notes.extend(description.notes.iter().cloned());
        let params = m.param_values();
        let columns = m.columns();
        let (ni, n) = (columns.inputs.len(), columns.unknowns.len());
        let x = vec![0.0; ni];
        let reference = m.reference().and_then(|q| description.evaluate(&params, &x, &q).ok());
        if let Some(v) = &reference {
            notes.extend(coincident(&description, &v.joints));
        }
        let plates = description
            .plates
            .iter()
            .map(|p| match &reference {
                Some(v) if p.joints.len() > 3 => around(&p.joints, &v.joints),
                None if p.joints.len() > 3 => {
                    notes.push(format!(
                        "the mechanism does not assemble at inputs 0 from its guess: the plate through {} is \
                         drawn in the declared order",
                        p.joints.iter().map(|&j| description.joints[j].name.as_str()).collect::<Vec<_>>().join(", ")
                    ));
                    p.joints.clone()
                }
                _ => p.joints.clone(),
            })
            .collect();
        let names = description.joints.iter().map(|j| j.name.clone()).collect();
        let (nj, ns) = (description.joints.len(), description.segments.len());
        DefaultDrawing {
            source: Arc::new(Source { description, params, zero: [x, vec![0.0; n]] }),
            names,
            hidden_joints: vec![false; nj],
            hidden_segments: vec![false; ns],
            untraced: vec![false; nj],
            notes,
            plates,
            extra: Drawing::new(),
        }
    }

    /// The description the drawing is made from.
    pub fn description(&self) -> &Description {
        &self.source.description
    }

    /// What the declaration leaves ambiguous, and how the drawing shows it.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The joints' names (a `point`'s name, or `loop.lK` / `loop.rK`, or as renamed).
    pub fn joint_names(&self) -> &[String] {
        &self.names
    }

    fn index(&self, name: &str) -> Result<usize, DrawError> {
        self.names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| DrawError::UnknownPoint { name: name.to_string(), available: self.names.clone() })
    }

    /// Joint `name` as a point of a drawing, to extend the drawing through it (a gear about
    /// it, a bar to it).
    ///
    /// # Errors
    /// [`DrawError::UnknownPoint`] when no joint has this name.
    pub fn joint(&self, name: &str) -> Result<Pt, DrawError> {
        Ok(self.pt(self.index(name)?))
    }

    /// The angle of the segment declared as `term` (`loop: r @ phi`, as in
    /// [`Description::segments`]), for a slider or gear added through [`DefaultDrawing::extend`].
    ///
    /// # Errors
    /// [`DrawError::InvalidSetting`] when no segment is declared so, or it has no angle.
    pub fn angle(&self, term: &str) -> Result<Scalar, DrawError> {
        let s = self.segment(term)?;
        if self.source.description.segments[s].kind == SegmentKind::Ground {
            return Err(DrawError::InvalidSetting(format!("segment `{term}` is fixed: it has no turning angle")));
        }
        Ok(self.angle_of(s))
    }

    /// The angle of segment `s` at each state (NaN where it has none: a drawing reports it).
    fn angle_of(&self, s: usize) -> Scalar {
        let source = Arc::clone(&self.source);
        Scalar::expr(move |st| {
            source.description.evaluate(&source.params, st.x, st.q).ok().and_then(|v| v.angles[s]).unwrap_or(f64::NAN)
        })
    }

    fn segment(&self, term: &str) -> Result<usize, DrawError> {
        self.source.description.segments.iter().position(|s| s.term == term).ok_or_else(|| {
            let all: Vec<&str> = self.source.description.segments.iter().map(|s| s.term.as_str()).collect();
            DrawError::InvalidSetting(format!("no segment `{term}`; the segments are: {}", all.join("; ")))
        })
    }

    /// Renames joint `from` to `to`: the name by which [`DefaultDrawing::joint`],
    /// [`DefaultDrawing::hide`] and [`DefaultDrawing::joint_names`] know it. The drawing does not
    /// write it: the label drawn at a declared `point` is the point's name, as the motion's
    /// columns name it (an unnamed joint has none); to write another, label the point, as in
    /// `.extend(|d| d.label(Pt::point("p"), "P"))`.
    ///
    /// # Errors
    /// [`DrawError::UnknownPoint`] when no joint is named `from`.
    pub fn rename(mut self, from: &str, to: impl Into<String>) -> Result<DefaultDrawing, DrawError> {
        let i = self.index(from)?;
        self.names[i] = to.into();
        Ok(self)
    }

    /// Leaves out a joint (by name: its pivot, its trace, and every bar, plate corner and
    /// slider through it) or a segment (by its declared term, `loop: r @ phi`: a construction
    /// vector, a slider, a link; a plate of several links goes when all of them are hidden).
    ///
    /// # Errors
    /// [`DrawError::UnknownPoint`] when it names neither.
    pub fn hide(mut self, what: &str) -> Result<DefaultDrawing, DrawError> {
        if let Ok(s) = self.segment(what) {
            self.hidden_segments[s] = true;
        } else {
            let j = self.index(what)?;
            self.hidden_joints[j] = true;
        }
        Ok(self)
    }

    /// Stops tracing the path of named point `name`.
    ///
    /// # Errors
    /// [`DrawError::UnknownPoint`] when no joint has this name.
    pub fn untrace(mut self, name: &str) -> Result<DefaultDrawing, DrawError> {
        let j = self.index(name)?;
        self.untraced[j] = true;
        Ok(self)
    }

    /// Sets colours and sizes.
    pub fn with_style(mut self, style: Style) -> DefaultDrawing {
        self.extra.style = style;
        self
    }

    /// Sets the picture's size and the part of the plane shown.
    pub fn with_canvas(mut self, canvas: Canvas) -> DefaultDrawing {
        self.extra.canvas = canvas;
        self
    }

    /// Adds items and traces drawn over the default ones: `.extend(|d| d.gear(centre, r, 0.0))`;
    /// labels, notes, the length unit and the annotations set there are kept too.
    pub fn extend(mut self, add: impl FnOnce(Drawing) -> Drawing) -> DefaultDrawing {
        self.extra = add(self.extra);
        self
    }

    fn pt(&self, j: usize) -> Pt {
        // A declared `point` is an output of the mechanism: drawn from its columns by name, so
        // that it is labelled, traced and read back (an interactive page names it) as the point.
        let joint = &self.source.description.joints[j];
        if joint.named {
            return Pt::point(joint.name.clone());
        }
        let source = Arc::clone(&self.source);
        Pt::expr(move |st| match source.description.evaluate(&source.params, st.x, st.q) {
            Ok(v) => v.joints[j],
            Err(_) => [f64::NAN; 2],
        })
    }

    /// The drawing: plates and bars, pivots, sliders, traces, then the items added.
    pub fn into_drawing(self) -> Drawing {
        let d = &self.source.description;
        let shown = |j: usize| !self.hidden_joints[j];
        let mut items = Vec::new();
        let mut pivots = vec![false; d.joints.len()];
        for (s, seg) in d.segments.iter().enumerate() {
            if self.hidden_segments[s] || !shown(seg.from) || !shown(seg.to) {
                continue;
            }
            let pivot = |j: usize, pivots: &mut Vec<bool>| pivots[j] |= d.joints[j].ground;
            match seg.kind {
                SegmentKind::Ground => {}
                SegmentKind::Link => {
                    pivot(seg.from, &mut pivots);
                    pivot(seg.to, &mut pivots);
                }
                SegmentKind::Slider { fixed_guide } => {
                    let angle = self.angle_of(s);
                    let angle = if fixed_guide { Scalar::Const(self.constant(&angle)) } else { angle };
                    if !fixed_guide {
                        // The block of a guide turning about a frame point pivots there too (an
                        // inverted slider-crank's rocking block).
                        pivot(seg.from, &mut pivots);
                        pivot(seg.to, &mut pivots);
                        let body = d
                            .plates
                            .iter()
                            .filter(|p| p.guides.contains(&s))
                            .flat_map(|p| p.joints.iter().copied())
                            .filter(|&j| j != seg.from && shown(j))
                            .map(|j| self.pt(j))
                            .collect();
                        let (from, block) = (self.pt(seg.from), self.pt(seg.to));
                        items.push(Item::Guide { from, angle: angle.clone(), block, body });
                    }
                    items.push(Item::Slider { at: self.pt(seg.to), angle });
                }
                // Not a part of the machine: a thin line, with no joint circles to read as a link.
                SegmentKind::Construction => {
                    items.push(Item::Construction { from: self.pt(seg.from), to: self.pt(seg.to) })
                }
            }
        }
        for joints in &self.plates {
            // A plate goes with its links: hidden when every link of it is.
            let mut links = d
                .segments
                .iter()
                .enumerate()
                .filter(|(_, s)| s.kind == SegmentKind::Link && joints.contains(&s.from) && joints.contains(&s.to));
            if links.all(|(s, _)| self.hidden_segments[s]) {
                continue;
            }
            let through: Vec<Pt> = joints.iter().copied().filter(|&j| shown(j)).map(|j| self.pt(j)).collect();
            if through.len() >= 2 {
                items.push(Item::Link { closed: through.len() > 2, through });
            }
        }
        let mut drawing = Drawing::new();
        for (j, _) in pivots.iter().enumerate().filter(|(j, p)| **p && shown(*j)) {
            drawing = drawing.pivot(self.pt(j));
        }
        drawing.items.extend(items);
        for (j, joint) in d.joints.iter().enumerate() {
            if joint.named && !joint.ground && shown(j) && !self.untraced[j] {
                drawing = drawing.trace(self.pt(j));
            }
        }
        // What `extend` set, every field of it kept, with the declaration's items, traces and
        // notes before its own.
        let DefaultDrawing { extra: mut out, notes, .. } = self;
        out.items.splice(0..0, drawing.items);
        out.traces.splice(0..0, drawing.traces);
        out.notes.splice(0..0, notes);
        out
    }

    /// A fixed guide's angle (parameters only: any state gives it).
    fn constant(&self, a: &Scalar) -> f64 {
        let [x, q] = &self.source.zero;
        match a {
            Scalar::Const(v) => *v,
            Scalar::Expr(f) => f(&super::spec::StateRef { x, q, out: &[] }),
        }
    }

    /// [`Drawing::animate`] of the drawing (its notes written below the picture).
    ///
    /// # Errors
    /// As [`Drawing::animate`].
    pub fn animate(&self, motion: &Motion, anim: &Animation) -> Result<String, DrawError> {
        self.clone().into_drawing().animate(motion, anim)
    }

    /// [`Drawing::svg`] of the drawing at pose `pose`, with its notes.
    ///
    /// # Errors
    /// As [`Drawing::svg`].
    pub fn svg(&self, motion: &Motion, pose: usize) -> Result<String, DrawError> {
        self.clone().into_drawing().svg(motion, pose)
    }

    /// [`Drawing::exposures`] of the drawing, with its notes.
    ///
    /// # Errors
    /// As [`Drawing::exposures`].
    pub fn exposures(&self, motion: &Motion, count: usize) -> Result<String, DrawError> {
        self.clone().into_drawing().exposures(motion, count)
    }
}

impl From<DefaultDrawing> for Drawing {
    fn from(d: DefaultDrawing) -> Drawing {
        d.into_drawing()
    }
}

/// Joints at the same place at the reference state though the macro could not prove them one
/// (their sums differ symbolically): said in a note, drawn as two, since a coincidence at one
/// state may be a chance one. Within 1e-9 of the mechanism's size (see [`mechanism_size`]), as far
/// apart as rounding leaves two sums of a few vectors, plus the rounding of the coordinates
/// themselves (16 ulps of the farther joint's distance from the origin): a mechanism translated
/// far from the origin or drawn in any unit of length gets the same notes, where a tolerance
/// of 1e-9 of the distance from the origin called joints a thousandth of a link apart one.
fn coincident(d: &Description, at: &[[f64; 2]]) -> Vec<String> {
    let size = mechanism_size(d, at);
    let magnitude = |p: [f64; 2]| p[0].abs().max(p[1].abs());
    let mut notes = Vec::new();
    for i in 0..at.len() {
        for j in i + 1..at.len() {
            let rounding = 16.0 * f64::EPSILON * magnitude(at[i]).max(magnitude(at[j]));
            if (at[i][0] - at[j][0]).hypot(at[i][1] - at[j][1]) <= 1e-9 * size + rounding {
                notes.push(format!(
                    "joints `{}` and `{}` coincide at inputs 0 but are different sums of the declared vectors: \
                     drawn as two joints",
                    d.joints[i].name, d.joints[j].name
                ));
            }
        }
    }
    notes
}

/// The size of the moving mechanism: the larger side of the box around its moving joints, and
/// at least its longest link (all joints' box if it has neither). Measured between joints, not
/// from the origin: the frame's constant vectors, and a slider's guide from the origin, may
/// place the mechanism anywhere.
fn mechanism_size(d: &Description, at: &[[f64; 2]]) -> f64 {
    // The longer side of the box around the finite points (0 where it overflows).
    let side = |points: &mut dyn Iterator<Item = &[f64; 2]>| {
        let box_side = bounds(points.map(|p| (p[0], p[1]))).map(|(x0, x1, y0, y1)| (x1 - x0).max(y1 - y0));
        box_side.filter(|s| s.is_finite()).unwrap_or(0.0)
    };
    let moving = side(&mut at.iter().zip(&d.joints).filter(|(_, j)| !j.ground).map(|(p, _)| p));
    let link = d
        .segments
        .iter()
        .filter(|s| s.kind == SegmentKind::Link)
        .filter_map(|s| Some((at.get(s.from)?, at.get(s.to)?)))
        .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
        .filter(|l| l.is_finite())
        .fold(0.0, f64::max);
    let size = moving.max(link);
    if size > 0.0 { size } else { side(&mut at.iter()) }
}

/// `joints` ordered by their angle about their centre in `at`.
fn around(joints: &[usize], at: &[[f64; 2]]) -> Vec<usize> {
    let n = joints.len() as f64;
    let c = joints.iter().fold([0.0, 0.0], |c, &j| [c[0] + at[j][0] / n, c[1] + at[j][1] / n]);
    let mut v = joints.to_vec();
    v.sort_by(|&a, &b| {
        let angle = |j: usize| (at[j][1] - c[1]).atan2(at[j][0] - c[0]);
        angle(a).total_cmp(&angle(b))
    });
    v
}
