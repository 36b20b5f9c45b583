//! The best candidates of a synthesis search drawn over their targets: each candidate's
//! mechanism at its first target, the path its point traces, the targets numbered in order,
//! on axes in the targets' units, with a legend of rank and largest error.

use super::annotate::text_width;
use super::declared::Draw;
use super::error::DrawError;
use super::motion::{Motion, Pose};
use super::spec::{Drawing, Item, Pt, Scalar, StateRef};
use super::style::{CONSTRUCTION_DASH, CONSTRUCTION_WIDTH};
use super::svg::num;
use crate::escape::escape;
use crate::html::{HtmlConfig, HtmlError, html_marked};
use crate::plot::ticks::{Ticks, binade};
use kinloop_runtime::synthesis::Candidate;
use kinloop_runtime::{Kin, Sensitivities, Sweep};
use std::fmt::Write;
use std::sync::Arc;

/// Colours of the candidates, best first (a qualitative palette, distinct in print).
const PALETTE: [&str; 6] = ["#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#a6761d"];

/// Plot area insets in pixels: left (tick labels, the y title), right, top (the title),
/// bottom (tick labels, the x title).
const INSETS: [f64; 4] = [62.0, 16.0, 30.0, 44.0];
/// Height of one legend line.
const LEGEND_LINE: f64 = 16.0;

/// How [`candidates`] draws: the traced point, the motion swept, the size, the unit.
#[derive(Clone, Debug, PartialEq)]
pub struct CandidatesConfig {
    /// The mechanism's `point` whose path the targets prescribe (the task's point).
    pub point: String,
    /// The figure's title.
    pub title: String,
    /// The unit of lengths, written on the axes and after the errors (default the runtime's
    /// generic "length unit").
    pub length_unit: String,
    /// How far the first input is swept from its value at the first target, in its units (a
    /// turn, `TAU`, for a crank); `None` (the default): from the first target's inputs through
    /// each target's in turn to the last's.
    pub span: Option<f64>,
    /// Samples of the traced path (default 361; split over the stretches between targets).
    pub samples: usize,
    /// Largest width and height of the plot area in pixels (default 560 x 420); the area
    /// keeps the plane's proportions (one scale on both axes).
    pub size: [f64; 2],
}

impl CandidatesConfig {
    /// A figure of the path of point `point`, with the defaults otherwise.
    pub fn new(point: &str) -> CandidatesConfig {
        CandidatesConfig {
            point: point.to_string(),
            title: "Synthesis candidates".to_string(),
            length_unit: kinloop_runtime::LENGTH_UNIT.to_string(),
            span: None,
            samples: 361,
            size: [560.0, 420.0],
        }
    }

    /// Sets the title.
    pub fn with_title(mut self, title: &str) -> CandidatesConfig {
        self.title = title.to_string();
        self
    }

    /// Sets the unit of lengths.
    pub fn with_length_unit(mut self, unit: &str) -> CandidatesConfig {
        self.length_unit = unit.to_string();
        self
    }

    /// Sweeps the first input by `span` from the first target (a full turn: `TAU`).
    pub fn with_span(mut self, span: f64) -> CandidatesConfig {
        self.span = Some(span);
        self
    }

    /// Sets the number of samples of the traced paths.
    pub fn with_samples(mut self, samples: usize) -> CandidatesConfig {
        self.samples = samples;
        self
    }

    fn check(&self) -> Result<(), DrawError> {
        let bad = |s: String| Err(DrawError::InvalidSetting(s));
        if self.samples < 2 {
            return bad(format!("a traced path needs at least 2 samples, not {}", self.samples));
        }
        if self.span.is_some_and(|s| !(s.is_finite() && s != 0.0)) {
            return bad(format!("span {:?} must be finite and not zero", self.span));
        }
        let [w, h] = self.size;
        if !(w.is_finite() && h.is_finite() && (100.0..=4000.0).contains(&w) && (100.0..=4000.0).contains(&h)) {
            return bad(format!("plot size {w} x {h} must be 100..4000 pixels each way"));
        }
        Ok(())
    }
}

/// A candidate's placement `p -> d + s R(angle) p` (the identity without one).
#[derive(Clone, Copy)]
struct Placement([f64; 4]);

impl Placement {
    fn of(c: &Candidate) -> Placement {
        Placement(c.placement.unwrap_or([0.0, 0.0, 0.0, 1.0]))
    }

    fn point(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        let [dx, dy, angle, s] = self.0;
        let (sn, cs) = angle.sin_cos();
        [dx + s * (cs * x - sn * y), dy + s * (sn * x + cs * y)]
    }

    /// The motion with its points' output columns moved (its named points are drawn from them).
    fn motion(&self, mut motion: Motion) -> Result<Motion, DrawError> {
        for name in motion.point_names() {
            let (ix, iy) = motion.point_columns(&name)?;
            for pose in &mut motion.poses {
                [pose.out[ix], pose.out[iy]] = self.point([pose.out[ix], pose.out[iy]]);
            }
        }
        Ok(motion)
    }

    /// The drawing moved: fixed points and expressions mapped, angles turned, radii scaled
    /// (named points are read from the moved motion).
    fn drawing(&self, mut d: Drawing) -> Drawing {
        let place = *self;
        let [_, _, turn, scale] = self.0;
        let pt = |p: Pt| match p {
            Pt::Point(n) => Pt::Point(n),
            Pt::Fixed(xy) => Pt::Fixed(place.point(xy)),
            Pt::Expr(f) => Pt::Expr(Arc::new(move |s: &StateRef| place.point(f(s)))),
        };
        let angle = |a: Scalar| match a {
            Scalar::Const(v) => Scalar::Const(v + turn),
            Scalar::Expr(f) => Scalar::expr(move |s| f(s) + turn),
        };
        d.items = std::mem::take(&mut d.items)
            .into_iter()
            .map(|item| match item {
                Item::Link { through, closed } => Item::Link { through: through.into_iter().map(pt).collect(), closed },
                Item::Pivot { at } => Item::Pivot { at: pt(at) },
                Item::Slider { at, angle: a } => Item::Slider { at: pt(at), angle: angle(a) },
                Item::Guide { from, angle: a, block, body } => Item::Guide {
                    from: pt(from),
                    angle: angle(a),
                    block: pt(block),
                    body: body.into_iter().map(pt).collect(),
                },
                Item::Gear { centre, radius, angle: a } => {
                    Item::Gear { centre: pt(centre), radius: radius * scale, angle: angle(a) }
                }
                Item::Outline { centre, points, angle: a } => Item::Outline {
                    centre: pt(centre),
                    points: points.into_iter().map(|[x, y]| [x * scale, y * scale]).collect(),
                    angle: angle(a),
                },
                Item::Joint { at } => Item::Joint { at: pt(at) },
                Item::Construction { from, to } => Item::Construction { from: pt(from), to: pt(to) },
            })
            .collect();
        d.traces = std::mem::take(&mut d.traces).into_iter().map(pt).collect();
        d.labels = std::mem::take(&mut d.labels).into_iter().map(|(p, t)| (pt(p), t)).collect();
        d
    }
}

/// One candidate evaluated: its mechanism's shapes at the first target and its path, in the
/// targets' plane.
struct Drawn {
    /// Links (points, closed), pivots, sliders (centre, angle), gears (centre, radius),
    /// joints.
    shapes: Vec<Shape>,
    path: Vec<[f64; 2]>,
    /// The motion stopped before its end (a limit position, a failed step).
    cut: bool,
}

enum Shape {
    Link(Vec<[f64; 2]>, bool),
    Pivot([f64; 2]),
    Slider([f64; 2], f64),
    /// A turning guide's ends.
    Guide([[f64; 2]; 2]),
    Gear([f64; 2], f64),
    /// An outline's corners where they are.
    Outline(Vec<[f64; 2]>),
    Joint([f64; 2]),
    /// A construction line's ends.
    Construction([[f64; 2]; 2]),
}

fn finite(p: [f64; 2], what: &str, rank: usize) -> Result<[f64; 2], DrawError> {
    if p[0].is_finite() && p[1].is_finite() {
        Ok(p)
    } else {
        Err(DrawError::NonFinite { what: format!("{what} of candidate {rank}"), pose: 0 })
    }
}

/// Point `p` of the drawing at `pose`, in the mechanism's plane.
fn point(p: &Pt, pose: &Pose, motion: &Motion) -> Result<[f64; 2], DrawError> {
    let state = StateRef { x: &pose.x, q: &pose.q, out: &pose.out };
    Ok(match p {
        Pt::Point(name) => {
            let (ix, iy) = motion.point_columns(name)?;
            [pose.out[ix], pose.out[iy]]
        }
        Pt::Fixed(xy) => *xy,
        Pt::Expr(f) => f(&state),
    })
}

fn scalar(s: &Scalar, pose: &Pose) -> f64 {
    match s {
        Scalar::Const(v) => *v,
        Scalar::Expr(f) => f(&StateRef { x: &pose.x, q: &pose.q, out: &pose.out }),
    }
}

/// The states of the motion of `m` through the candidate's targets (or over `span`).
fn motion<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    m: &M,
    c: &Candidate,
    config: &CandidatesConfig,
) -> Result<Motion, DrawError>
where
    M: Sensitivities<N, NI, NO, NP>,
{
    let input = |k: usize| -> Result<[f64; NI], DrawError> {
        <[f64; NI]>::try_from(c.inputs[k].as_slice()).map_err(|_| {
            DrawError::InvalidSetting(format!("the candidate's inputs have {} values, not {NI}", c.inputs[k].len()))
        })
    };
    if c.inputs.is_empty() || c.positions.is_empty() {
        return Err(DrawError::InvalidSetting("the candidate has no target inputs or positions".into()));
    }
    let q0 = <[f64; N]>::try_from(c.positions[0].as_slice()).map_err(|_| {
        DrawError::InvalidSetting(format!("the candidate's positions have {} values, not {N}", c.positions[0].len()))
    })?;
    let from = input(0)?;
    // The stretches swept: over `span`, or from target to target.
    let mut stretches = Vec::new();
    match config.span {
        Some(span) => {
            let mut to = from;
            to[0] += span;
            stretches.push((from, to, config.samples));
        }
        None => {
            let pieces = (c.inputs.len() - 1).max(1);
            let each = (config.samples / pieces).max(2);
            for k in 1..c.inputs.len() {
                stretches.push((input(k - 1)?, input(k)?, each));
            }
        }
    }
    let mut motion = Motion::empty::<M, N, NI, NO>();
    // The mechanism at the first target, then the stretches.
    for k in Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(m, from, from, 1, q0)? {
        motion.push(&k?);
    }
    let mut q = q0;
    for (a, b, samples) in stretches {
        if a == b {
            continue;
        }
        let sweep = Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(m, a, b, samples, q)?;
        // Each stretch starts where the previous one ended: that pose once.
        for k in sweep.skip(1) {
            match k {
                Ok(k) => {
                    q = k.q;
                    motion.push(&k);
                }
                // A candidate with a defect may meet a limit position (or fail) between its
                // targets: its path is drawn as far as it goes, and the legend says so.
                Err(_) => {
                    motion.stopped = true;
                    return Ok(motion);
                }
            }
        }
    }
    Ok(motion)
}

/// Candidate `c` (ranked `rank`) drawn: `m` with its parameters, its default drawing at the
/// first target, the path of the point over the motion; placed.
fn drawn<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    m: &M,
    c: &Candidate,
    rank: usize,
    config: &CandidatesConfig,
) -> Result<Drawn, DrawError>
where
    M: Sensitivities<N, NI, NO, NP>,
{
    let params = <[f64; NP]>::try_from(c.params.as_slice()).map_err(|_| {
        DrawError::InvalidSetting(format!("candidate {rank} has {} parameters; `{}` has {NP}", c.params.len(), M::NAME))
    })?;
    let m = m.with_params_flat(params);
    let motion = motion(&m, c, config)?;
    let place = Placement::of(c);
    let (ix, iy) = motion.point_columns(&config.point)?;
    let path = motion
        .poses
        .iter()
        .map(|p| finite(place.point([p.out[ix], p.out[iy]]), &format!("point `{}`", config.point), rank))
        .collect::<Result<Vec<_>, _>>()?;
    let drawing: Drawing = m.drawing().into_drawing();
    let pose = motion.poses.first().ok_or(DrawError::EmptyMotion)?;
    let at = |p: &Pt| finite(place.point(point(p, pose, &motion)?), &p.describe(), rank);
    let turn = c.placement.map_or(0.0, |p| p[2]);
    let scale = c.placement.map_or(1.0, |p| p[3]);
    let spans = super::scene::guide_spans(&drawing, &motion)?;
    let mut shapes = Vec::new();
    for (k, item) in drawing.items.iter().enumerate() {
        shapes.push(match item {
            Item::Guide { .. } => {
                let span = spans[k].unwrap_or_default();
                let ends = super::scene::guide_at(item, span, &motion, pose, 0)?.unwrap_or_default();
                Shape::Guide([at(&Pt::Fixed(ends[0]))?, at(&Pt::Fixed(ends[1]))?])
            }
            Item::Link { through, closed } => Shape::Link(through.iter().map(at).collect::<Result<_, _>>()?, *closed),
            Item::Pivot { at: p } => Shape::Pivot(at(p)?),
            Item::Slider { at: p, angle } => Shape::Slider(at(p)?, scalar(angle, pose) + turn),
            Item::Gear { centre, radius, .. } => Shape::Gear(at(centre)?, radius * scale),
            Item::Outline { centre, points, angle } => {
                // The body's frame placed as the candidate is, then turned by its angle.
                let ([cx, cy], (s, c)) = (at(centre)?, (scalar(angle, pose) + turn).sin_cos());
                let corner = |[x, y]: [f64; 2]| {
                    let (x, y) = (x * scale, y * scale);
                    finite([cx + c * x - s * y, cy + s * x + c * y], "an outline's corner", rank)
                };
                Shape::Outline(points.iter().copied().map(corner).collect::<Result<_, _>>()?)
            }
            Item::Joint { at: p } => Shape::Joint(at(p)?),
            Item::Construction { from, to } => Shape::Construction([at(from)?, at(to)?]),
        });
    }
    Ok(Drawn { shapes, path, cut: motion.stopped })
}

/// `M` with the parameters of candidate `c` (ranked `rank`).
fn with_params<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    m: &M,
    c: &Candidate,
    rank: usize,
) -> Result<M, DrawError>
where
    M: Sensitivities<N, NI, NO, NP>,
{
    let params = <[f64; NP]>::try_from(c.params.as_slice()).map_err(|_| {
        DrawError::InvalidSetting(format!("candidate {rank} has {} parameters; `{}` has {NP}", c.params.len(), M::NAME))
    })?;
    Ok(m.with_params_flat(params))
}

/// An interactive page ([`html`](crate::html::html)) of candidate `c`: its mechanism (the
/// default drawing of `m` with the candidate's parameters, moved by its placement into the
/// targets' plane) moving through the targets (or over [`CandidatesConfig::span`]), with the
/// targets marked and numbered from 1 over the picture. Readouts of points (`p.x`) are in the
/// targets' plane too.
///
/// # Errors
/// As [`candidates`] (through [`HtmlError::Draw`]) and as [`html`](crate::html::html).
pub fn candidate_page<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    m: &M,
    c: &Candidate,
    targets: &[[f64; 2]],
    config: &CandidatesConfig,
    page: &HtmlConfig,
) -> Result<String, HtmlError>
where
    M: Sensitivities<N, NI, NO, NP>,
{
    config.check()?;
    if targets.is_empty() {
        return Err(DrawError::InvalidSetting("a candidate's page needs its targets".into()).into());
    }
    if let Some(t) = targets.iter().find(|t| !(t[0].is_finite() && t[1].is_finite())) {
        return Err(DrawError::NonFinite { what: format!("target {t:?}"), pose: 0 }.into());
    }
    let m = with_params(m, c, 0)?;
    let place = Placement::of(c);
    let motion = place.motion(motion(&m, c, config)?)?;
    let drawing = place.drawing(m.drawing().into_drawing());
    // The picture fitted to the targets too (drawn as joints there for the fit only).
    let mut fit = drawing.clone();
    fit.items.extend(targets.iter().map(|t| Item::Joint { at: Pt::Fixed(*t) }));
    let view = fit.page_view(&motion)?;
    html_marked(&kinloop_runtime::Compiled(&m), &drawing, &motion, page, targets, Some(view))
}

/// The figure's map from the plane to pixels: `x -> x0 + s x`, `y -> y0 - s y`.
struct Map {
    x0: f64,
    y0: f64,
    s: f64,
}

impl Map {
    fn px(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [self.x0 + self.s * x, self.y0 - self.s * y]
    }
    fn pts(&self, pts: &[[f64; 2]]) -> String {
        pts.iter()
            .map(|p| {
                let [x, y] = self.px(*p);
                format!("{},{}", num(x), num(y))
            })
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// The best candidates of a synthesis search drawn over their targets, as an SVG: for each
/// candidate (in the order given: a [`SynthesisReport`]'s are best first, ranked `#0`, `#1`,
/// ...) its mechanism at its first target (the default drawing, [`Draw`], of `m` with the
/// candidate's [`Candidate::params`], moved by its placement), the path of
/// [`CandidatesConfig::point`] over the motion through its targets (a branch-safe sweep from
/// the first target's position); the targets marked and numbered in order from 1; axes in the
/// targets' units (one scale on both); a legend with each candidate's rank and largest error
/// (`#0  max error 2.1e-4 length unit`, and "not valid" where its verification found a
/// defect).
///
/// Candidates are drawn last-ranked first, so the best is on top. The SVG holds no NaN.
///
/// [`SynthesisReport`]: kinloop_runtime::synthesis::SynthesisReport
///
/// ```no_run
/// # use kinloop_viz::draw::{CandidatesConfig, candidates};
/// # fn run<M: kinloop::Sensitivities<2, 1, 2, 6>>(m: &M, report: &kinloop::synthesis::SynthesisReport, targets: &[[f64; 2]]) -> Result<(), kinloop_viz::draw::DrawError> {
/// let best = &report.candidates[..report.candidates.len().min(3)];
/// let config = CandidatesConfig::new("p").with_title("Best three four-bars").with_span(std::f64::consts::TAU);
/// std::fs::write("candidates.svg", candidates(m, best, targets, &config)?).unwrap();
/// # Ok(()) }
/// ```
///
/// # Errors
/// [`DrawError::InvalidSetting`] for no candidate, no target, more candidates than colours
/// (six), a candidate that does not fit `M` or a setting out of range;
/// [`DrawError::UnknownPoint`] when `M` has no such point; [`DrawError::Sweep`] when a
/// candidate's motion cannot be swept; [`DrawError::NonFinite`] for a non-finite point.
pub fn candidates<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    m: &M,
    candidates: &[Candidate],
    targets: &[[f64; 2]],
    config: &CandidatesConfig,
) -> Result<String, DrawError>
where
    M: Sensitivities<N, NI, NO, NP>,
{
    config.check()?;
    if candidates.is_empty() || targets.is_empty() {
        return Err(DrawError::InvalidSetting("a figure of candidates needs a candidate and a target".into()));
    }
    if candidates.len() > PALETTE.len() {
        return Err(DrawError::InvalidSetting(format!(
            "{} candidates: at most {} are drawn in one figure",
            candidates.len(),
            PALETTE.len()
        )));
    }
    if let Some(t) = targets.iter().find(|t| !(t[0].is_finite() && t[1].is_finite())) {
        return Err(DrawError::NonFinite { what: format!("target {t:?}"), pose: 0 });
    }
    let drawn =
        candidates.iter().enumerate().map(|(rank, c)| drawn(m, c, rank, config)).collect::<Result<Vec<_>, _>>()?;
    // The extent of everything drawn, widened to whole ticks.
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut add = |p: &[f64; 2]| {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    };
    targets.iter().for_each(&mut add);
    for d in &drawn {
        d.path.iter().for_each(&mut add);
        for s in &d.shapes {
            match s {
                Shape::Link(pts, _) | Shape::Outline(pts) => pts.iter().for_each(&mut add),
                Shape::Guide(pts) | Shape::Construction(pts) => pts.iter().for_each(&mut add),
                Shape::Pivot(p) | Shape::Slider(p, _) | Shape::Joint(p) => add(p),
                Shape::Gear(c, r) => {
                    add(&[c[0] - r, c[1] - r]);
                    add(&[c[0] + r, c[1] + r]);
                }
            }
        }
    }
    // The same range on both axes' steps: the larger extent decides the tick step.
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if !(span.is_finite() && span > 1e-300) {
        return Err(DrawError::Unscalable { width: hi[0] - lo[0], height: hi[1] - lo[1] });
    }
    let pad = 0.03 * span;
    let (xt, yt) = axes([lo[0] - pad, hi[0] + pad], [lo[1] - pad, hi[1] + pad]);
    // The axes' ends in the plane's units (the ticks hold them divided by a power of two).
    let (x_lo, x_hi, y_lo, y_hi) = (xt.lo * xt.unit, xt.hi * xt.unit, yt.lo * yt.unit, yt.hi * yt.unit);
    if ![x_lo, x_hi, y_lo, y_hi].iter().all(|v| v.is_finite()) {
        return Err(DrawError::Unscalable { width: hi[0] - lo[0], height: hi[1] - lo[1] });
    }
    let [w_max, h_max] = config.size;
    let s = (w_max / (x_hi - x_lo)).min(h_max / (y_hi - y_lo));
    let (pw, ph) = ((x_hi - x_lo) * s, (y_hi - y_lo) * s);
    let [left, right, top, bottom] = INSETS;
    let map = Map { x0: left - x_lo * s, y0: top + ph + y_lo * s, s };
    let legend_top = top + ph + bottom;
    let legend: Vec<String> = candidates
        .iter()
        .zip(&drawn)
        .enumerate()
        .map(|(rank, (c, d))| legend_text(rank, c, d, &config.length_unit))
        .collect();
    let widest = legend.iter().map(|t| text_width(t)).fold(text_width(TARGETS), f64::max);
    let width = (left + pw + right).max(left + 28.0 + widest + right);
    let height = legend_top + LEGEND_LINE * (candidates.len() + 1) as f64 + 4.0;
    let unit = escape(&config.length_unit);
    let mut out = String::new();
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="11"><rect width="{w}" height="{h}" fill="white"/>"#,
        w = num(width),
        h = num(height)
    );
    let _ = write!(
        out,
        r#"<text class="title" x="{}" y="18" font-size="13" font-weight="600">{}</text>"#,
        num(left),
        escape(&config.title)
    );
    // Axes: grid lines, tick labels, titles with their unit.
    let (x_left, x_right, y_top, y_bottom) = (left, left + pw, top, top + ph);
    for &(v, k) in &xt.values {
        let (x, label) = (num(map.px([v * xt.unit, 0.0])[0]), escape(&xt.label(k)));
        let _ = write!(
            out,
            r##"<line class="grid" x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="#e6e6e6"/><text class="tick-x" x="{x}" y="{}" text-anchor="middle">{label}</text>"##,
            num(y_top),
            num(y_bottom),
            num(y_bottom + 14.0)
        );
    }
    for &(v, k) in &yt.values {
        let (y, label) = (map.px([0.0, v * yt.unit])[1], escape(&yt.label(k)));
        let _ = write!(
            out,
            r##"<line class="grid" x1="{}" y1="{}" x2="{}" y2="{}" stroke="#e6e6e6"/><text class="tick-y" x="{}" y="{}" text-anchor="end">{label}</text>"##,
            num(x_left),
            num(y),
            num(x_right),
            num(y),
            num(x_left - 5.0),
            num(y + 4.0)
        );
    }
    let _ = write!(
        out,
        r#"<rect class="plot-area" x="{}" y="{}" width="{}" height="{}" fill="none" stroke="black"/><text class="axis-x" x="{}" y="{}" text-anchor="middle">x [{unit}]</text><text class="axis-y" x="14" y="{}" text-anchor="middle" transform="rotate(-90 14 {})">y [{unit}]</text>"#,
        num(x_left),
        num(y_top),
        num(pw),
        num(ph),
        num((x_left + x_right) / 2.0),
        num(y_bottom + 32.0),
        num((y_top + y_bottom) / 2.0),
        num((y_top + y_bottom) / 2.0)
    );
    // The candidates, worst first: the best on top.
    for (rank, d) in drawn.iter().enumerate().rev() {
        let colour = PALETTE[rank];
        let _ = write!(out, r#"<g class="candidate" data-rank="{rank}">"#);
        let _ = write!(
            out,
            r#"<polyline class="path" data-rank="{rank}" points="{}" fill="none" stroke="{colour}" stroke-width="1.5" stroke-linejoin="round" opacity="0.8"/>"#,
            map.pts(&d.path)
        );
        let mut joints = Vec::new();
        for shape in &d.shapes {
            match shape {
                Shape::Link(pts, closed) => {
                    let tag = if *closed { "polygon" } else { "polyline" };
                    let fill = if *closed { colour } else { "none" };
                    let _ = write!(
                        out,
                        r#"<{tag} class="link" points="{}" fill="{fill}" fill-opacity="0.15" stroke="{colour}" stroke-width="2.5" stroke-linejoin="round" stroke-linecap="round"/>"#,
                        map.pts(pts)
                    );
                    joints.extend(pts.iter().copied());
                }
                Shape::Guide(pts) => {
                    let _ = write!(
                        out,
                        r#"<polyline class="link" points="{}" fill="none" stroke="{colour}" stroke-width="2.5" stroke-linecap="round"/>"#,
                        map.pts(pts)
                    );
                }
                // Thin and dashed, with no joint circles: no part of the machine.
                Shape::Construction(pts) => {
                    let _ = write!(
                        out,
                        r#"<polyline class="construction" points="{}" fill="none" stroke="{colour}" stroke-width="{}" stroke-dasharray="{CONSTRUCTION_DASH}"/>"#,
                        map.pts(pts),
                        num(CONSTRUCTION_WIDTH)
                    );
                }
                Shape::Outline(pts) => {
                    let _ = write!(
                        out,
                        r#"<polygon class="outline" points="{}" fill="{colour}" fill-opacity="0.1" stroke="{colour}" stroke-width="1.5" stroke-linejoin="round"/>"#,
                        map.pts(pts)
                    );
                }
                Shape::Pivot(p) => {
                    let [x, y] = map.px(*p);
                    let _ = write!(
                        out,
                        r#"<path class="pivot" d="M{},{}l-7,11h14z" fill="white" stroke="{colour}" stroke-width="1.5"/>"#,
                        num(x),
                        num(y)
                    );
                }
                Shape::Slider(p, angle) => {
                    let [x, y] = map.px(*p);
                    let _ = write!(
                        out,
                        r#"<rect class="slider" x="-11" y="-6" width="22" height="12" transform="translate({} {}) rotate({})" fill="white" stroke="{colour}" stroke-width="1.5"/>"#,
                        num(x),
                        num(y),
                        num(-(angle % std::f64::consts::TAU).to_degrees())
                    );
                }
                Shape::Gear(c, r) => {
                    let [x, y] = map.px(*c);
                    let _ = write!(
                        out,
                        r#"<circle class="gear" cx="{}" cy="{}" r="{}" fill="none" stroke="{colour}" stroke-dasharray="3 3"/>"#,
                        num(x),
                        num(y),
                        num((r * map.s).min(1e6))
                    );
                }
                Shape::Joint(p) => joints.push(*p),
            }
        }
        for p in joints {
            let [x, y] = map.px(p);
            let _ = write!(
                out,
                r#"<circle class="joint" cx="{}" cy="{}" r="3" fill="white" stroke="{colour}" stroke-width="1.5"/>"#,
                num(x),
                num(y)
            );
        }
        out.push_str("</g>");
    }
    // The targets, numbered in order from 1.
    out.push_str(r#"<g class="targets">"#);
    for (i, t) in targets.iter().enumerate() {
        let [x, y] = map.px(*t);
        let _ = write!(
            out,
            r##"<circle class="target" data-index="{i}" cx="{}" cy="{}" r="4.5" fill="none" stroke="#111" stroke-width="1.5"/><text class="target-label" data-index="{i}" x="{}" y="{}" font-size="11" fill="#111" stroke="white" stroke-width="3" paint-order="stroke">{}</text>"##,
            num(x),
            num(y),
            num(x + 6.0),
            num(y - 6.0),
            i + 1
        );
    }
    out.push_str("</g>");
    // The legend.
    for (rank, text) in legend.iter().enumerate() {
        let y = legend_top + LEGEND_LINE * rank as f64;
        let _ = write!(
            out,
            r#"<g class="legend" data-rank="{rank}"><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="3"/><text x="{}" y="{}">{}</text></g>"#,
            num(left),
            num(y - 4.0),
            num(left + 22.0),
            num(y - 4.0),
            PALETTE[rank],
            num(left + 28.0),
            num(y),
            escape(text)
        );
    }
    let y = legend_top + LEGEND_LINE * candidates.len() as f64;
    let _ = write!(
        out,
        r##"<g class="legend-targets"><circle cx="{}" cy="{}" r="4.5" fill="none" stroke="#111" stroke-width="1.5"/><text x="{}" y="{}">{TARGETS}</text></g>"##,
        num(left + 11.0),
        num(y - 4.0),
        num(left + 28.0),
        num(y)
    );
    out.push_str("</svg>");
    Ok(out)
}

/// The ticks of the two axes over `[x0, x1]` and `[y0, y1]` (the plane's units): one step on
/// both (the one of the larger range), so that the grid's squares are square on the one scale,
/// each range widened to whole steps. The labels are the plot module's: as many decimals as
/// the step needs (`"0.0005"`), a power of ten for very small or large values (`"2e-6"`).
fn axes([x0, x1]: [f64; 2], [y0, y1]: [f64; 2]) -> (Ticks, Ticks) {
    // Scaled by one power of two (exact), as the plot module holds its ticks.
    let unit = binade(x0.abs().max(x1.abs()).max(y0.abs()).max(y1.abs()));
    let (x0, x1, y0, y1) = (x0 / unit, x1 / unit, y0 / unit, y1 / unit);
    let wider = if x1 - x0 >= y1 - y0 { (x0, x1) } else { (y0, y1) };
    let step = Ticks::scaled(wider.0, wider.1, unit, 1.0, false, true, 0.0);
    // Integer multiples of the step, ends within rounding of a tick taken to it.
    let widened = |lo: f64, hi: f64| {
        let slack = 1e-9;
        let (lo, hi) = ((lo / step.step + slack).floor() * step.step, (hi / step.step - slack).ceil() * step.step);
        Ticks::with_step(lo, hi, &step)
    };
    (widened(x0, x1), widened(y0, y1))
}

/// What the legend says of the targets.
const TARGETS: &str = "targets, numbered in the order met";

/// `#0  max error 2.10e-4 mm`, and what is wrong with the candidate.
fn legend_text(rank: usize, c: &Candidate, d: &Drawn, unit: &str) -> String {
    let error = if c.max_error.is_finite() { format!("{:.2e}", c.max_error) } else { "not finite".into() };
    let mut text = format!("#{rank}  max error {error} {unit}");
    if !c.is_valid() {
        let _ = write!(text, ", not valid ({} defects)", c.defects.len());
    }
    if d.cut {
        text.push_str(", its motion stops short (a limit position or a failed step)");
    }
    text
}
