//! Figures for [kinloop](https://docs.rs/kinloop): charts of sweep results ([`plot`]) and
//! drawings and animations of the mechanism itself ([`draw`]), written as SVG, and
//! interactive pages in which the mechanism moves with a slider ([`html`]).
//!
//! Reached through the `kinloop` facade with its features `plot` and `draw`.

#![warn(missing_docs)]

pub mod draw;
pub mod html;
pub mod plot;
