//! The exit codes of `kinloop` (those above 2 are the BSD `sysexits` conventions).

/// A solve failed (no assembly, singular position, ...).
pub const SOLVE_FAILED: u8 = 1;
/// Wrong arguments, a parameter without a value, or parameters that leave a loop's lengths all
/// zero (as unset ones are) (also clap's code for its own usage errors).
pub const USAGE: u8 = 2;
/// The declaration is rejected: its diagnostics are on standard error.
pub const DATA_ERR: u8 = 65;
/// The file cannot be read.
pub const NO_INPUT: u8 = 66;
/// The declaration uses what the run-time evaluator does not evaluate yet.
pub const UNAVAILABLE: u8 = 69;
/// An output file (`--events`) cannot be created.
pub const CANT_CREATE: u8 = 73;
/// Writing an output (the table, the events) failed.
pub const IO_ERR: u8 = 74;

/// A usage error: writes `message` on standard error and fails with [`USAGE`].
pub fn usage(message: impl std::fmt::Display) -> crate::Failed {
    eprintln!("error: {message}");
    crate::Failed(USAGE)
}
