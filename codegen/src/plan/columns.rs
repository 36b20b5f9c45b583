//! Rows from the columns the passes differentiate one at a time.

use crate::graph::dag::NodeId;

/// Rows from columns: `columns[c][r]` becomes `rows[r][c]` (every pass differentiates one
/// column at a time: one input, one parameter).
pub fn rows_from_columns(rows: usize, columns: impl IntoIterator<Item = Vec<NodeId>>) -> Vec<Vec<NodeId>> {
    let mut out = vec![Vec::new(); rows];
    for col in columns {
        for (r, node) in col.into_iter().enumerate() {
            out[r].push(node);
        }
    }
    out
}
