//! Interactive pages: one self-contained `.html` file (inline SVG, a style sheet and a small
//! script; no server, no network) in which the mechanism moves through a precomputed sweep.
//!
//! [`html`] takes a [`Drawing`] and the [`Motion`] of a branch-safe sweep (as the SVG
//! animations do) and writes a page with
//!
//! * the mechanism at the slider's pose, with its traced paths and a dot on each traced point;
//! * a slider over the poses of the motion and a play/pause button (a full turn starts again,
//!   [`HtmlConfig::back_and_forth`] plays a motion that stops at a limit position forward and
//!   back);
//! * live readouts of every input and of the columns chosen with [`HtmlConfig::show`] (or any
//!   [`Readout`]), with their units: angles in degrees, lengths in
//!   [`HtmlConfig::length_unit`] (the drawing's own unit where the page names none);
//! * a chart of each readout against the input (against the fraction of the path for several
//!   inputs), whose cursor follows the slider;
//! * the sweep's events (limit positions, singular crossings) marked on the slider's track and
//!   on the charts, listed under the picture (a click shows the mechanism there), and the
//!   mechanism drawn there as a dashed ghost (no label over the picture, which would cover
//!   the mechanism).
//!
//! With several inputs the motion is either a sweep along a straight path in input space
//! ([`html`]: one slider moves along that path and every input has its readout), or a grid of
//! the inputs ([`html_grid`] over a [`GridMotion`]: one slider per input, the mechanism at
//! the sliders' cell, "not reached on this assembly mode" where no sweep of the grid reached
//! a cell on the assembly mode carried from its first cell).
//!
//! The page is deterministic (the same inputs give the same bytes: no time stamp, no random
//! identifier) and holds no NaN or infinite number: a non-finite value is an [`HtmlError`].
//!
//! **Rounding.** The page holds, for every pose, the drawn points in tenths of a pixel and the
//! angles of sliders and gears in tenths of a degree (the resolution of the SVG drawings:
//! a picture 600 pixels wide resolves 1/6000 of the mechanism's extent), and the readouts to the digits shown: a hundredth of a degree for
//! angles, five significant digits of the largest value for anything else (for values far from
//! zero that vary little, such as an input after many turns, more: at least three significant
//! digits of their span), written as the charts' axes are labelled: with decimals for ordinary magnitudes (a largest value from
//! about 1e-4 to 1e5: `"-0.0123"`), with a power of ten beyond (`"-5.661e-7"`, `"1.5896e9"`;
//! zero `"0"`), never as a negative zero. A readout whose values spread by no more than f64
//! rounding (a thousand ulps of their magnitude, and at least of what its kind is computed
//! from: a turn for an angle, the mechanism's largest length for a length, 1 for a pure number:
//! a length computed through the loop, an angle that is zero up to rounding) is shown as
//! constant: one value, to five significant digits, and a flat chart; 0 where that value is
//! within the same rounding of zero (a centred slider's pin height). A chart's axis whose labels would be
//! too wide (values far from zero that vary little) is labelled by differences from the offset
//! written above it (`+999.999999996`). The drawing's
//! scale (`data-scale`, pixels per unit) and the pixel of the origin (`data-origin`) are
//! attributes of its `<svg id="kl-drawing">`, so coordinates read from the page map back to
//! the mechanism's units. The picture is framed to the mechanism and its traced paths over
//! the motion (the scale of the SVG drawings), without their joint labels and strip of
//! annotations: the page writes its readouts, events and notes beside and under it. At most
//! [`HtmlConfig::max_frames`] poses are written (721 by default, about 30 to 60 kB for the
//! gallery's mechanisms). The traced paths go through every pose, but a segment already drawn
//! (between the same points, to a tenth of a pixel) is written once: a sweep of a thousand
//! turns does not write its curve a thousand times.
//!
//! ```
//! use kinloop_viz::draw::{Drawing, Motion, Pt};
//! use kinloop_viz::html::{HtmlConfig, html};
//!
//! kinloop::mechanism! {
//!     pub struct FourBar {
//!         params r = 1.0, l = 3.0, k = 2.5, d = 3.0;
//!         input phi;
//!         unknowns beta = 0.5, gamma = 1.5;
//!         loop obcd: r @ phi + l @ beta == (d, 0) + k @ gamma;
//!         point b = r @ phi;
//!         point c = (d, 0) + k @ gamma;
//!     }
//! }
//!
//! let m = FourBar::default();
//! let motion = Motion::record(&m, m.sweep(0.0, std::f64::consts::TAU, 73, &m.guess(0.0))?)?;
//! let drawing = Drawing::new()
//!     .pivot(Pt::fixed(0.0, 0.0))
//!     .pivot(Pt::fixed(m.d, 0.0))
//!     .link([Pt::fixed(0.0, 0.0), Pt::point("b"), Pt::point("c"), Pt::fixed(m.d, 0.0)])
//!     .trace("c");
//! let config = HtmlConfig::new("Four-bar").show(FourBar::COL.gamma).with_length_unit("mm");
//! let page = html(&m, &drawing, &motion, &config)?;
//! assert!(page.starts_with("<!DOCTYPE html>") && page.contains(r#"id="kl-slider""#));
//! assert!(!page.contains("NaN"));
//! // No address out of the page: the only one is the SVG namespace.
//! assert_eq!(page.matches("http").count(), page.matches("http://www.w3.org/2000/svg").count());
//!
//! // A column the mechanism does not have is an error.
//! let wrong = html(&m, &drawing, &motion, &HtmlConfig::new("x").show("delta"));
//! assert!(matches!(wrong, Err(kinloop_viz::html::HtmlError::UnknownColumn { .. })));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub(crate) mod chart;
mod config;
mod css;
mod error;
mod figure;
mod frames;
mod page;
mod readouts;
mod script;

pub use config::{HtmlConfig, Readout, Value};
pub use error::HtmlError;

use crate::draw::{Drawing, GridMotion, Item, Motion, Pt};
use kinloop_runtime::drawing::{Columns, Drawable};
use kinloop_runtime::{Compiled, Mechanism};

/// The names of the joints of each item (the `point` outputs among its points).
fn joint_names(d: &Drawing) -> Vec<Vec<Option<String>>> {
    let name = |p: &Pt| if let Pt::Point(n) = p { Some(n.clone()) } else { None };
    d.items
        .iter()
        .map(|item| match item {
            Item::Link { through, .. } => through.iter().map(name).collect(),
            Item::Joint { at } => vec![name(at)],
            _ => Vec::new(),
        })
        .collect()
}

/// An interactive page of `drawing` moving through `motion` (a sweep of mechanism `m`,
/// recorded with [`Motion::record`]): see the [module documentation](self). The mechanism
/// gives the names and quantity kinds of its columns (the readouts' units).
///
/// With more poses than [`HtmlConfig::max_frames`], at most that many are written, in equal
/// steps along the motion (the first and the last kept); the traced paths keep every pose (a segment
/// that retraces one already drawn written once).
///
/// Errors: the drawing's own ([`HtmlError::Draw`]: an unknown point, an empty motion, a
/// non-finite coordinate), a readout naming no column of `M` ([`HtmlError::UnknownColumn`]),
/// a non-finite readout ([`HtmlError::NonFinite`]), a setting out of range or a motion of
/// another mechanism ([`HtmlError::InvalidSetting`]).
pub fn html<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    drawing: &Drawing,
    motion: &Motion,
    config: &HtmlConfig,
) -> Result<String, HtmlError>
where
    M: Mechanism<N, NI, NO>,
{
    html_of(&Compiled(m), drawing, motion, config)
}

/// [`html`] of any [`Drawable`] mechanism: a compiled one, or a `kinloop_model::Model` read
/// at run time (whose motion is recorded with [`Motion::of`] and [`Motion::follow`]).
///
/// # Errors
/// As [`html`].
pub fn html_of<D: Drawable + ?Sized>(
    m: &D,
    drawing: &Drawing,
    motion: &Motion,
    config: &HtmlConfig,
) -> Result<String, HtmlError> {
    html_marked(m, drawing, motion, config, &[], None)
}

/// [`html`] with fixed points `marks` marked and numbered over the picture, in `view` (fitted
/// to the drawing over the motion when `None`).
pub(crate) fn html_marked<D: Drawable + ?Sized>(
    m: &D,
    drawing: &Drawing,
    motion: &Motion,
    config: &HtmlConfig,
    marks: &[[f64; 2]],
    view: Option<crate::draw::View>,
) -> Result<String, HtmlError> {
    config.check()?;
    let columns = m.columns();
    if let Some(err) = not_of("motion", motion, &columns, m.name()) {
        return Err(err);
    }
    let ni = columns.inputs.len();
    let path = frames::path(motion);
    let fr = frames::Frames::build(drawing, motion, frames::spread(&path, config.max_frames), &[path], view)?;
    let channels = readouts::channels(&columns, config, config.length_unit_of(drawing), motion, &fr.poses)?;
    let against_input = ni == 1;
    let labels: Vec<String> = motion
        .events
        .iter()
        .enumerate()
        .map(|(j, e)| {
            let at: Vec<String> =
                channels[..ni].iter().map(|c| format!("{} = {}", c.label, c.text_with_unit(c.at_events[j]))).collect();
            format!("{} at {}", e.kind, at.join(", "))
        })
        .collect();
    let positions = frames::event_positions(motion, &fr.poses);
    let events: Vec<(String, f64, String)> = motion
        .events
        .iter()
        .zip(&positions)
        .zip(&labels)
        .map(|((e, at), label)| (e.kind.to_string().replace(' ', "-"), *at, label.clone()))
        .collect();
    let last = (fr.frames.len() - 1).max(1) as f64;
    let mut charts = Vec::new();
    for (k, c) in channels.iter().enumerate().filter(|(_, c)| c.chart) {
        let x = against_input.then(|| &channels[0]);
        let at: Vec<f64> =
            if against_input { channels[0].at_events.clone() } else { positions.iter().map(|p| p / last).collect() };
        let (svg, map) = chart::chart(charts.len(), x, c, &at, config.chart_size);
        charts.push((k, svg, map));
    }
    let traces: Vec<Option<String>> =
        drawing.traces.iter().map(|p| if let Pt::Point(n) = p { Some(n.clone()) } else { None }).collect();
    let figure = figure::figure(&fr, &drawing.style, 0, &joint_names(drawing), &traces, &labels, marks);
    page::document(&page::Parts {
        title: &config.title,
        notes: &drawing.notes,
        frames: &fr,
        channels: &channels,
        figure,
        charts,
        against_input,
        events,
        seconds: config.seconds,
        back_and_forth: config.back_and_forth,
        autoplay: config.autoplay,
        grid: None,
    })
}

/// An interactive page of `drawing` over a grid of the inputs of mechanism `m` (recorded with
/// [`GridMotion::record`]): one slider per input, a readout of every input, the mechanism at
/// the sliders' cell; where the grid did not reach a cell the mechanism is hidden (its frame
/// pivots stay), the other readouts show a dash and the page says "not reached on this assembly
/// mode": the mechanism cannot be assembled there, or it can but a limit position or a singular
/// position lies on the way from every reached neighbour, or at the cell itself (see
/// [`GridMotion::record`]); the grid does not tell these apart.
/// The traced
/// points' paths are drawn along every row of reachable cells. Play moves the first input
/// along its row. The readouts have no charts (a chart against one input would hold for one
/// row only).
///
/// Every cell is written: a grid of more cells than [`HtmlConfig::max_frames`] is an error
/// (fewer values per input, or a larger `max_frames`), so the page's size stays bounded.
///
/// ```
/// use kinloop::Mechanism;
/// use kinloop_viz::draw::{Draw, GridMotion};
/// use kinloop_viz::html::{HtmlConfig, html_grid};
///
/// kinloop::mechanism! {
///     pub struct FiveBar {
///         params a = 1.0, b = 2.5, c = 2.5, d = 1.0, e = 2.0;
///         inputs th1, th2;
///         unknowns al = 1.2, be = 2.0;
///         loop l: a @ th1 + b @ al == (e, 0) + d @ th2 + c @ be;
///         point p = a @ th1 + b @ al;
///     }
/// }
/// let m = FiveBar::default();
/// let grid = GridMotion::record(&m, [0.0, 0.0], [3.0, 3.0], [13, 13], m.guess_flat(&[0.0, 0.0]))?;
/// let page = html_grid(&m, &m.drawing().into_drawing(), &grid, &HtmlConfig::new("Five-bar"))?;
/// assert!(page.contains(r#"id="kl-slider-0""#) && page.contains(r#"id="kl-slider-1""#));
/// assert!(!page.contains("NaN"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`html`], and [`HtmlError::InvalidSetting`] for a grid of another mechanism, of more
/// cells than [`HtmlConfig::max_frames`], or (its fields set by hand) with an input of no value
/// or cells that do not match its axes and poses.
pub fn html_grid<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    drawing: &Drawing,
    grid: &GridMotion,
    config: &HtmlConfig,
) -> Result<String, HtmlError>
where
    M: Mechanism<N, NI, NO>,
{
    html_grid_of(&Compiled(m), drawing, grid, config)
}

/// [`html_grid`] of any [`Drawable`] mechanism (a compiled one, or a `kinloop_model::Model`
/// read at run time).
///
/// # Errors
/// As [`html_grid`].
pub fn html_grid_of<D: Drawable + ?Sized>(
    m: &D,
    drawing: &Drawing,
    grid: &GridMotion,
    config: &HtmlConfig,
) -> Result<String, HtmlError> {
    config.check()?;
    let columns = m.columns();
    let motion = &grid.motion;
    let counts = grid.counts();
    if let Some(err) = not_of("grid", motion, &columns, m.name()) {
        return Err(err);
    }
    if counts.len() != columns.inputs.len() {
        return Err(HtmlError::InvalidSetting(format!(
            "the grid has {} axes, not one for each input of the mechanism {} (inputs {:?})",
            counts.len(),
            m.name(),
            columns.inputs
        )));
    }
    // A grid whose fields were set by hand can have an axis of no value (no cell at all).
    if let Some(k) = counts.iter().position(|&c| c == 0) {
        return Err(HtmlError::InvalidSetting(format!("the grid has no value of input `{}`", columns.inputs[k])));
    }
    if grid.cells.len() != counts.iter().product::<usize>()
        || grid.cells.iter().flatten().any(|&i| i >= motion.poses.len())
    {
        return Err(HtmlError::InvalidSetting("the grid's cells do not match its axes and poses".into()));
    }
    if grid.cells.len() > config.max_frames {
        return Err(HtmlError::InvalidSetting(format!(
            "a grid of {} cells is more than the page's {} poses (max_frames): fewer values per input or a larger \
             max_frames",
            grid.cells.len(),
            config.max_frames
        )));
    }
    let fr = frames::Frames::build(drawing, motion, (0..motion.poses.len()).collect(), &grid.runs(), None)?;
    let mut channels = readouts::channels(&columns, config, config.length_unit_of(drawing), motion, &fr.poses)?;
    for (c, axis) in channels.iter_mut().zip(&grid.axes) {
        readouts::on_axis(c, axis);
    }
    let traces: Vec<Option<String>> =
        drawing.traces.iter().map(|p| if let Pt::Point(n) = p { Some(n.clone()) } else { None }).collect();
    let first = grid.cells[0].unwrap_or(0);
    let figure = figure::figure(&fr, &drawing.style, first, &joint_names(drawing), &traces, &[], &[]);
    let cells = grid.cells.iter().map(|c| c.map_or(-1, |i| i as i64)).collect();
    page::document(&page::Parts {
        title: &config.title,
        notes: &drawing.notes,
        frames: &fr,
        channels: &channels,
        figure,
        charts: Vec::new(),
        against_input: false,
        events: Vec::new(),
        seconds: config.seconds,
        back_and_forth: config.back_and_forth,
        autoplay: config.autoplay,
        grid: Some(page::GridPart { counts, cells, inputs: columns.inputs.clone() }),
    })
}

/// The error for a `what` ("motion", "grid") recorded from another mechanism than `name`, whose
/// columns are `columns`: it names the part that differs, the inputs or the output columns (a
/// motion of the same inputs but other points was said to differ in its inputs, printing the
/// same list twice); `None` where both agree.
fn not_of(what: &str, motion: &Motion, columns: &Columns, name: &str) -> Option<HtmlError> {
    let (part, had, wanted) = if motion.inputs != columns.inputs {
        ("inputs", &motion.inputs, &columns.inputs)
    } else if motion.outputs != columns.outputs {
        ("output columns", &motion.outputs, &columns.outputs)
    } else {
        return None;
    };
    Some(HtmlError::InvalidSetting(format!(
        "the {what} ({part} {had:?}) is not a {what} of the mechanism {name} ({part} {wanted:?})"
    )))
}
