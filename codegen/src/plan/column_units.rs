//! Column magnitudes in one unit: the entries of a block's Jacobian columns that lie in rows of
//! another unit, weighed into the unit of the block's own rows.
//!
//! An analog factorisation divides each of the block's columns by the largest magnitude of the
//! unknown's whole Jacobian column (see `kinloop_runtime::Inverse2`), the rows of later blocks
//! included, and its smallest pivot is the distance to a singular position a sweep judges by.
//! The entries of one column are comparable only where their rows have one unit: a four-bar's
//! rocker angle `gamma` read again by a gear pair `th3 == 2 gamma` has `-c sin(gamma)` (a
//! length) in the loop's rows and `-2` (no unit) in the gear's. Divided by `2`, the loop's
//! entries came out `k` times smaller in a mechanism `k` times smaller, and so did the pivot:
//! `1.8e-9` at `k = 1e-9` where it is `1` at `k = 1`, and a sweep stopped there as near a singular
//! position.
//!
//! An entry in a row of another unit is therefore weighed by the magnitude of the block's own
//! rows over that row's magnitude (see [`super::magnitudes`]): a change of unit, from the row's
//! terms to the block's, which makes the column's entries alike and its largest one the same in
//! every unit of length. Rows of the block's own unit are left as they are (most mechanisms have
//! only those, and their factorisations are unchanged), and so are rows whose unit the
//! dimensions do not tell (a cam's law through `clamp`): the magnitude of such a row may hold
//! terms its entries do not (a law's NaN, where its Jacobian entries are finite), and weighing
//! by it changed the dwell cam's sweeps.
//!
//! A block whose own rows have more than one unit (a loop and a gear's equation solved
//! together: a geared five-bar) cannot be made unit-free by its columns alone, whatever they are
//! divided by. Its factorisation divides each row by its magnitude first
//! ([`BlockPlan::row_scale`]), and each column by the largest of its entries over their rows'
//! magnitudes, later blocks' rows included. Where such a block has a lever floor (a magnitude of
//! one of its rows, in that row's unit, which the floors no longer tell), it is left as it is.

use super::block_plan::BlockPlan;
use super::magnitudes::Magnitudes;
use crate::graph::dag::{Graph, NodeId};

/// Weighs the entries of `bp`'s column magnitudes that lie in rows of another unit than the
/// block's own (`power[e]`: equation `e`'s power of length, `None` where not inferred, which is
/// never weighed) into the block's unit, in place, or gives a block of rows of several units its
/// row scales (see the module documentation). `jac_full` holds the rows of the full Jacobian,
/// `residuals` every equation's residual.
pub fn weigh(
    g: &mut Graph,
    mags: &mut Magnitudes,
    bp: &mut BlockPlan,
    jac_full: &[Vec<NodeId>],
    residuals: &[NodeId],
    power: &[Option<i32>],
) {
    let own = match own_power(bp, power) {
        Some(own) => own,
        None if mixed(bp, power) && bp.lever_floor.iter().all(Vec::is_empty) => {
            return by_rows(g, mags, bp, jac_full, residuals);
        }
        None => return,
    };
    let foreign = |e: usize| !bp.equations.contains(&e) && power[e].is_some_and(|p| p != own);
    let reaches_foreign =
        bp.unknowns.iter().any(|&u| (0..jac_full.len()).any(|e| foreign(e) && !g.is_zero(jac_full[e][u])));
    if !reaches_foreign {
        return;
    }
    // The block's unit: the sum of its rows' magnitudes (each of that unit; the sum stays clear
    // of a row whose terms happen to be small).
    let own_magnitude = bp.scale.iter().copied().reduce(|a, b| g.add(a, b)).unwrap_or_else(|| g.one());
    for (c, &u) in bp.unknowns.iter().enumerate() {
        bp.col_scale[c] = column(g, jac_full, u, |g, e, entry| {
            if !foreign(e) {
                return entry;
            }
            let row_magnitude = mags.of(g, residuals[e]);
            let weight = g.div(own_magnitude, row_magnitude);
            g.mul(entry, weight)
        });
    }
}

/// Whether `bp` has rows of more than one unit, each inferred.
fn mixed(bp: &BlockPlan, power: &[Option<i32>]) -> bool {
    let Some(&first) = bp.equations.first() else { return false };
    bp.equations.iter().all(|&e| power[e].is_some()) && bp.equations.iter().any(|&e| power[e] != power[first])
}

/// A block of rows of several units: each row divided by its magnitude, each column's entries
/// over their rows' magnitudes.
fn by_rows(g: &mut Graph, mags: &mut Magnitudes, bp: &mut BlockPlan, jac_full: &[Vec<NodeId>], residuals: &[NodeId]) {
    for (c, &u) in bp.unknowns.iter().enumerate() {
        bp.col_scale[c] = column(g, jac_full, u, |g, e, entry| {
            let row_magnitude = match bp.equations.iter().position(|&own| own == e) {
                Some(r) => bp.scale[r],
                None => mags.of(g, residuals[e]),
            };
            g.div(entry, row_magnitude)
        });
    }
    bp.row_scale = bp.scale.clone();
}

/// The non-zero entries of unknown `u`'s column of the full Jacobian, in row order, each as
/// `entry(g, row, node)` makes it.
fn column(
    g: &mut Graph,
    jac_full: &[Vec<NodeId>],
    u: usize,
    mut entry: impl FnMut(&mut Graph, usize, NodeId) -> NodeId,
) -> Vec<NodeId> {
    let mut out = Vec::new();
    for (e, row) in jac_full.iter().enumerate() {
        if !g.is_zero(row[u]) {
            out.push(entry(g, e, row[u]));
        }
    }
    out
}

/// The power of length shared by every row of `bp`, if they share one.
fn own_power(bp: &BlockPlan, power: &[Option<i32>]) -> Option<i32> {
    let first = power[*bp.equations.first()?]?;
    bp.equations.iter().all(|&e| power[e] == Some(first)).then_some(first)
}

#[cfg(test)]
mod tests {
    use crate::graph::dag::Op;

    /// The plan of a declaration.
    fn plan_of(src: &str) -> crate::plan::Plan {
        crate::plan_declaration(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}")).plan
    }

    /// A four-bar whose rocker turns a gear: the rocker's column reaches the gear's row (no unit)
    /// from the loop's (lengths), and that entry is weighed; the coupler's column reaches only
    /// the loop's rows, and nothing is.
    #[test]
    fn an_entry_in_a_row_of_another_unit_is_weighed() {
        let plan = plan_of(
            "pub struct G { params a, b, c, d; input phi; unknowns beta = 0.5, gamma = 1.5, th3 = 3.0;
                loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma; eq g: th3 == 2 * gamma; }",
        );
        let loop_block = &plan.blocks[0];
        let gamma = loop_block.unknowns.iter().position(|&u| u == 1).expect("gamma in the loop's block");
        let beta = 1 - gamma;
        assert_eq!(loop_block.col_scale[beta], vec![plan.jac_full[0][0], plan.jac_full[1][0]]);
        let column = &loop_block.col_scale[gamma];
        assert_eq!(column[..2], [plan.jac_full[0][1], plan.jac_full[1][1]], "the loop's own entries");
        assert_eq!(column.len(), 3);
        // The gear's entry `-2`, times a weight.
        let Op::Mul(entry, _) = plan.graph.op(column[2]) else { panic!("not weighed: {:?}", plan.graph.op(column[2])) };
        assert_eq!(entry, plan.jac_full[2][1]);
    }

    /// A row whose unit the dimensions do not tell (a square of an angle) is not weighed: its
    /// magnitude may hold terms its entries do not.
    #[test]
    fn an_entry_in_a_row_of_no_known_unit_is_not() {
        let plan = plan_of(
            "pub struct G { params a, b, c, d; input phi; unknowns beta = 0.5, gamma = 1.5, th3 = 3.0;
                loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma; eq g: th3 == gamma * gamma; }",
        );
        let loop_block = &plan.blocks[0];
        for column in &loop_block.col_scale {
            assert!(column.iter().all(|&e| plan.jac_full.iter().any(|row| row.contains(&e))), "{column:?}");
        }
        assert!(loop_block.row_scale.is_empty());
    }

    /// A Watt chain: the first dyad's coupler column reaches the second loop's rows, which are
    /// lengths as its own are: nothing is weighed.
    #[test]
    fn an_entry_in_a_row_of_the_same_unit_is_not() {
        let plan = plan_of(
            "pub struct W { params a = 1, b = 3, c = 2.5, d = 3, e = 2, f = 2.5, g = 1.5;
                input phi; unknowns beta = 0.6, gamma = 1.5, delta = 0.4, eps = 1.6;
                loop first: a @ phi + b @ beta == (d, 0) + c @ gamma;
                loop second: a @ phi + e @ (beta + 0.3) + f @ delta == (d + 1, 0) + g @ eps; }",
        );
        for bp in &plan.blocks {
            for column in &bp.col_scale {
                assert!(column.iter().all(|&e| plan.jac_full.iter().any(|row| row.contains(&e))), "{column:?}");
            }
        }
    }
}
