//! Following a mechanism along its inputs: sweeps that never jump branches ([`sweep`], configured
//! by [`config`]) and their results with the reason they stopped ([`outcome`]), pseudo-arclength continuation through
//! limit positions and kinks ([`curve`], [`trace`]), the states at given inputs ([`sweep_at`]), the reachable
//! input range ([`reach`]) and where a mechanism assembles near an input ([`assembles`]), design-space
//! scans ([`scan`]) and the search for assembly modes ([`modes`]); the memory budget of what keeps a state per
//! sample ([`collected`]).

pub mod assembles;
pub mod collected;
pub mod config;
mod crossing;
pub mod curve;
mod kink;
mod locate;
pub mod modes;
pub mod outcome;
pub mod reach;
pub mod scan;
pub mod sweep;
pub mod sweep_at;
pub mod trace;
mod trace_kink;
mod trace_start;
