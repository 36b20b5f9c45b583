//! The parameter sensitivities of a block or of the outputs, by stage (positions, first and
//! second analogs).

use crate::graph::dag::NodeId;

/// Right-hand sides (per row) or values (per output) of the parameter sensitivities, by stage:
/// `q[r][k]`, `v[r][i * np + k]`, `a[r][p * np + k]` for parameter `k`, input `i`, input pair `p`.
pub struct Stages {
    /// Position stage, per parameter.
    pub q: Vec<Vec<NodeId>>,
    /// Velocity-analog stage, per input and parameter.
    pub v: Vec<Vec<NodeId>>,
    /// Acceleration-analog stage, per input pair and parameter.
    pub a: Vec<Vec<NodeId>>,
}
