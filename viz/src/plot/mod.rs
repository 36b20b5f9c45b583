//! Charts of sweep results as SVG: curves against the input ([`line_chart`], stacked
//! [`panels`]), x-y paths with equal scales ([`xy_chart`]) and bars at discrete abscissae such
//! as the orders of harmonics ([`bar_chart`]).
//!
//! Every series states the quantity kind of its values ([`Kind`]): angles (given in radians,
//! shown in degrees, a turn ticked at 0, 90, 180, 270, 360), lengths with their unit, velocity
//! and acceleration analogs, pure numbers. Axis titles carry the unit (`"crank angle φ [°]"`,
//! `"x' [mm/rad]"`), and an axis holds one kind: a series of another kind is an error
//! ([`PlotError::MixedKinds`]); [`Panel::split_by_kind`] gives each kind its own panel (the
//! one rule: two panels, never twin axes, so each value reads against one scale). Dynamics
//! have their kinds too: [`Kind::Torque`], [`Kind::Force`], [`Kind::Speed`],
//! [`Kind::AngularSpeed`], [`Kind::Time`], [`Kind::Energy`], [`Kind::Inertia`],
//! [`Kind::Power`]; a mechanism's columns map to kinds with [`Kind::of_column`].
//!
//! Axes read as an engineer expects: a value axis whose data do not change sign starts (or
//! ends) at 0 rather than being padded across it, a bar chart's value axis always includes 0,
//! and an angle axis over a sampled turn `[0, 2 pi)` ends on its 360 tick.
//!
//! The SVG is written directly, with coordinates to 1/100 pixel (smooth curves, no pixel
//! snapping), points closer than half a pixel merged, curves broken at non-finite points (a
//! sweep that stopped), and legends to the right of the plot area so they never cover data.
//!
//! ```no_run
//! use kinloop_viz::plot::{self, Axis, Kind, Panel, Series};
//! # let (phi, x, dx) = (vec![0.0, 1.0], vec![1.0, 2.0], vec![0.5, 0.4]);
//! let dir = plot::out_dir("slider")?;
//! plot::panels(&dir.join("slider.svg"), "Offset slider-crank", &Axis::angle("crank angle φ"), &[
//!     Panel::new(Axis::length("slider x", "mm")).with(Series::columns("x", Kind::length("mm"), &phi, &x)),
//!     Panel::new(Axis::new("x'", Kind::LengthAnalog("mm".into())))
//!         .with(Series::columns("dx/dφ", Kind::LengthAnalog("mm".into()), &phi, &dx)),
//! ])?;
//! # Ok::<(), plot::PlotError>(())
//! ```

mod bars;
pub(crate) mod digits;
mod error;
mod files;
mod frame;
mod kind;
mod legend;
mod lines;
pub(crate) mod series;
mod svg;
pub(crate) mod ticks;
mod xy;

pub use bars::bar_chart_svg;
pub use error::PlotError;
pub use files::{decimate, figure_dir, out_dir, save};
pub use kind::{Axis, Kind};
pub use lines::{line_chart_svg, panels_svg};
pub use series::{Panel, Series};
pub use xy::xy_chart_svg;

use std::path::Path;

/// [`line_chart_svg`] written to `path`.
pub fn line_chart(path: &Path, title: &str, x: &Axis, y: &Axis, series: &[Series]) -> Result<(), PlotError> {
    save(path, &line_chart_svg(title, x, y, series)?)
}

/// [`panels_svg`] written to `path`.
pub fn panels(path: &Path, title: &str, x: &Axis, panels: &[Panel]) -> Result<(), PlotError> {
    save(path, &panels_svg(title, x, panels)?)
}

/// [`bar_chart_svg`] written to `path`.
pub fn bar_chart(path: &Path, title: &str, x: &Axis, panels: &[Panel]) -> Result<(), PlotError> {
    save(path, &bar_chart_svg(title, x, panels)?)
}

/// [`xy_chart_svg`] written to `path`.
pub fn xy_chart(
    path: &Path,
    title: &str,
    x: &Axis,
    y: &Axis,
    series: &[Series],
    marks: &[(f64, f64)],
) -> Result<(), PlotError> {
    save(path, &xy_chart_svg(title, x, y, series, marks)?)
}
