//! The finished plan of a mechanism, which owns the expression graph.

use super::block_plan::BlockPlan;
use super::stages::Stages;
use crate::graph::dag::{Graph, NodeId};

/// The finished plan; it owns the graph every `NodeId` refers to.
pub struct Plan {
    /// The finished expression graph.
    pub graph: Graph,
    /// Number of unknowns (and scalar equations).
    pub n: usize,
    /// Number of inputs.
    pub ni: usize,
    /// Number of parameters.
    pub np: usize,
    /// The blocks in solve order.
    pub blocks: Vec<BlockPlan>,
    /// Residuals of all equations, in declaration order.
    pub residuals: Vec<NodeId>,
    /// Output columns: each point's x and y, then each scalar output.
    pub outputs: Vec<NodeId>,
    /// `out_d1[o][i]`.
    pub out_d1: Vec<Vec<NodeId>>,
    /// `out_d2[o][p]` for input pair `p`.
    pub out_d2: Vec<Vec<NodeId>>,
    /// Output sensitivities, when requested.
    pub out_sens: Option<Stages>,
    /// Declared initial guesses (0 when not declared).
    pub guesses: Vec<NodeId>,
    /// The full Jacobian `jac_full[e][u] = d f_e / d q_u` (for continuation and event location).
    pub jac_full: Vec<Vec<NodeId>>,
    /// `fx_full[e][i] = d f_e / d x_i`.
    pub fx_full: Vec<Vec<NodeId>>,
    /// `scale_full[e]`: the magnitude of equation `e`'s terms (see
    /// [`magnitudes`](super::magnitudes)).
    pub scale_full: Vec<NodeId>,
    /// `unit_full[u]`: the unit of unknown `u` (its block's, see
    /// [`magnitudes`](super::magnitudes)).
    pub unit_full: Vec<NodeId>,
    /// `input_unit[i]`: the unit of input `i` (see
    /// [`magnitudes::Magnitudes::input_unit`](super::magnitudes::Magnitudes::input_unit)).
    pub input_unit: Vec<NodeId>,
    /// Parameter defaults, when every parameter has one.
    pub defaults: Option<Vec<f64>>,
    /// Per node: highest block whose unknowns it depends on (`-1`: none).
    pub level: Vec<i32>,
}

impl Plan {
    /// Whether the parameter sensitivities were requested.
    pub fn has_sensitivities(&self) -> bool {
        self.out_sens.is_some()
    }
}
