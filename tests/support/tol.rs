//! Named tolerances: each magnitude says what error it admits and why that error is the one to
//! expect. A check whose error has another cause keeps its own literal, with its reason beside
//! it. The tolerances are for unit-size mechanisms (links of about 1); a check multiplies one by
//! the size of what it compares where that is not 1.

/// Rounding of a few operations: one quantity computed twice with a handful of roundings
/// between the two, or a converged position against an exact reference. About 45 ulps of 1.0,
/// the rounding floor of a loop equation whose magnitude is a few link lengths.
pub const ULPS: f64 = 1e-14;

/// Rounding of a solve: one quantity from two different computations (the library against a
/// closed form written in the test, a closed form against Newton, a decomposed against a dense
/// solve). Newton's default residual tolerance is 1e-12 and its final correction leaves the
/// positions within about that (times a condition number near 1) of the exact root; the analogs
/// reuse the Jacobian and inherit the same error. Also the bound on a loop's residual (relative
/// to unit-size links) after a solve with the default configuration.
pub const SOLVE: f64 = 1e-12;

/// A first derivative (velocity analog, gradient) against central differences of positions
/// combined by one Richardson step (`support::richardson`) at h = 1e-3 to 1e-2: truncation
/// ~h^4/480 |f^(5)| (~1e-10 at h = 1e-2), rounding ~e/h (~1e-10 for position errors e = 1e-13 at
/// h = 1e-3, ~5e-11 for e = 5e-13 at h = 1e-2). 1e-9 leaves a factor of ten. Also a second
/// derivative against the same differences of the velocity analogs, its first derivative: the
/// analogs are exact at their positions, so their errors are the positions' (times a Jacobian's
/// condition), as small as e.
pub const FD_FIRST: f64 = 1e-9;

/// A second derivative (acceleration analog) against the same differences: rounding ~5e/h^2
/// (~5e-7 for e = 1e-13 at h = 1e-3, ~3e-8 for e = 5e-13 at h = 1e-2), so 1e-6.
pub const FD_SECOND: f64 = 1e-6;

/// An event located by a sweep against its closed form (a limit position where the input
/// reverses along the solution curve, found by continuation; a change point at a root of a
/// determinant): the location stops on tolerances of its own, well above rounding but far
/// below this, which is about 6e-8 degrees of a crank.
pub const LOCATED: f64 = 1e-9;
