//! Figures for [kinloop](https://docs.rs/kinloop): charts of sweep results ([`plot`]) and
//! drawings and animations of the mechanism itself ([`draw`]), written as SVG, and
//! interactive pages in which the mechanism moves with a slider, or with one slider per input
//! over a grid of several inputs ([`html`]); synthesis candidates drawn over their targets
//! ([`draw::candidates`]).
//!
//! Reached through the `kinloop` facade with its features `plot` and `draw`.

#![warn(missing_docs)]

pub mod draw;
mod escape;
pub mod html;
pub mod plot;
