//! Following a mechanism along its inputs: sweeps that never jump branches ([`sweep`]),
//! pseudo-arclength continuation through limit positions ([`curve`]), design-space scans
//! ([`scan`]) and the search for assembly modes ([`modes`]).

pub mod curve;
pub mod modes;
pub mod outcome;
pub mod scan;
pub mod sweep;
pub mod trace;
