//! Named tolerances: each magnitude says what error it admits and why that error is the one to
//! expect. A check whose error has another cause keeps its own literal with its own reason.
//! Every tolerance is for unit-size mechanisms (links of about 1); a check multiplies it by the
//! size of what it compares where that is not 1.

/// Rounding of a few operations: the same quantity computed twice with a handful of roundings
/// between the two, or a converged position against an exact reference. About 45 ulps of 1.0,
/// the rounding floor of a loop equation whose magnitude is a few link lengths.
pub const ULPS: f64 = 1e-14;

/// Rounding of a solve: one quantity from two different computations (a closed form against
/// Newton, the library against a closed form written in the test, a decomposed against a dense
/// solve). Newton's default residual tolerance is 1e-12, and its final correction leaves the
/// positions within about that (times a condition number near 1) of the exact root; analogs
/// reuse the Jacobian and inherit the same relative error.
pub const SOLVE: f64 = 1e-12;

/// A first derivative (velocity analog, gradient) against central differences of positions
/// combined by one Richardson step (`support::richardson`, step h ~ 1e-3): truncation
/// ~h^4/480 |f^(5)| ~ 1e-15, rounding ~e/h ~ 1e-10 for position errors e ~ 1e-13; 1e-9 leaves a
/// factor of ten for derivatives of a few units.
pub const FD_FIRST: f64 = 1e-9;

/// A second derivative (acceleration analog) against the same differences: rounding ~5e/h^2 ~
/// 5e-7 for e ~ 1e-13 and h ~ 1e-3, so 1e-6.
pub const FD_SECOND: f64 = 1e-6;
