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
//!   [`HtmlConfig::length_unit`];
//! * a chart of each readout against the input (against the fraction of the path for several
//!   inputs), whose cursor follows the slider;
//! * the sweep's events (limit positions, singular crossings) marked on the slider's track and
//!   on the charts, and the mechanism drawn there as a dashed ghost.
//!
//! With several inputs the motion is a sweep along a straight path in input space: the slider
//! moves along that path and every input has its readout.
//!
//! The page is deterministic (the same inputs give the same bytes: no time stamp, no random
//! identifier) and holds no NaN or infinite number: a non-finite value is an [`HtmlError`].
//!
//! **Rounding.** The page holds, for every pose, the drawn points in tenths of a pixel and the
//! angles of sliders and gears in tenths of a degree (the resolution of the SVG drawings:
//! a picture 600 pixels wide resolves 1/6000 of the mechanism's extent), and the readouts to the digits shown: a hundredth of a degree for
//! angles, five significant digits of the largest value for anything else. The drawing's
//! scale (`data-scale`, pixels per unit) and the pixel of the origin (`data-origin`) are
//! attributes of its `<svg id="kl-drawing">`, so coordinates read from the page map back to
//! the mechanism's units. At most [`HtmlConfig::max_frames`] poses are written (721 by
//! default, about 30 to 60 kB for the gallery's mechanisms).
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

mod chart;
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

use crate::draw::{Drawing, Item, Motion, Pt};
use kinloop_runtime::Mechanism;

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
/// With more poses than [`HtmlConfig::max_frames`], that many are written, evenly spread
/// over the motion (the first and the last kept); the traced paths keep every pose.
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
    let _ = m;
    config.check()?;
    if motion.inputs != M::INPUTS || motion.outputs != M::OUTPUTS {
        return Err(HtmlError::InvalidSetting(format!(
            "the motion (inputs {:?}) is not a motion of the mechanism {} (inputs {:?})",
            motion.inputs,
            M::NAME,
            M::INPUTS
        )));
    }
    let fr = frames::Frames::new(drawing, motion, config.max_frames)?;
    let channels = readouts::channels::<M, N, NI, NO>(config, motion, &fr.poses)?;
    let against_input = NI == 1;
    let labels: Vec<String> = motion
        .events
        .iter()
        .enumerate()
        .map(|(j, e)| {
            let at: Vec<String> = channels[..NI]
                .iter()
                .map(|c| format!("{} = {}{}", c.label, c.text(c.at_events[j]), c.unit()))
                .collect();
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
    let figure = figure::figure(&fr, &drawing.style, 0, &joint_names(drawing), &traces, &labels);
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
    })
}
