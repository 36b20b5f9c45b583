//! What a solver kernel computes.

/// What a solver kernel computes (see the documentation of [`kernel`](super)).
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// The positions only.
    Position,
    /// The positions, then their analogs and the outputs.
    Fused,
    /// The analogs and the outputs at a position the caller gives.
    At,
}
