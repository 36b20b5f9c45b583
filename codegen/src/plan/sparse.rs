//! The symbolic factorisation of a large sparse Newton block: which entries of its Jacobian are
//! structurally non-zero, an order of pivots that keeps the factors sparse, and the index tables
//! of the runtime's sparse LU (`kinloop_runtime::SparseLu`), from which the emitter writes the
//! numeric factorisation as straight-line code (`crate::emit::sparse`).
//!
//! Pivots are the pairs of a perfect matching of rows to columns (a zero-free diagonal), chosen
//! one at a time by least Markowitz cost `(r - 1)(c - 1)` (`r`, `c`: non-zeros of the pivot's row
//! and column in the active submatrix, fill included), ties to the lowest row: the classical
//! fill-reducing heuristic. A ring of four-bar loops closed through a differential (3 non-zeros
//! per row) factorises with fill along one column only: the code and the work grow linearly with
//! the number of loops instead of with its square (dense) or cube (dense LU).

use crate::graph::dag::{Graph, NodeId};
use crate::structure::maximum_matching;
use std::collections::{BTreeSet, HashMap};

/// Blocks with fewer unknowns keep the dense factorisation (fully unrolled, faster when small).
pub const MIN_SIZE: usize = 16;

/// The sparse path is taken when the factor holds at most this fraction of `n^2` entries.
const MAX_DENSITY: f64 = 0.25;

/// The tables of a sparse block (see `kinloop_runtime::SparsePattern` for their meaning).
#[derive(Debug)]
pub struct Sparse {
    /// Structural non-zeros `(row, column)` in block coordinates, by rows: the order of the
    /// values the generated code writes.
    pub entries: Vec<(usize, usize)>,
    pub row_ptr: Vec<u32>,
    pub slot: Vec<u32>,
    pub prow: Vec<u16>,
    pub pcol: Vec<u16>,
    pub odd: bool,
    pub diag: Vec<u32>,
    pub l_ptr: Vec<u32>,
    pub l_slot: Vec<u32>,
    pub l_row: Vec<u16>,
    pub u_ptr: Vec<u32>,
    pub u_slot: Vec<u32>,
    pub u_col: Vec<u16>,
    pub upd: Vec<u32>,
    /// Number of slots of the factor.
    pub nlu: usize,
}

/// The elimination: pivots in order, and per pivot the rows below it (`lower`) and the
/// columns right of it (`upper`) that hold non-zeros in the active submatrix, in block
/// coordinates.
struct Elimination {
    pivots: Vec<(usize, usize)>,
    lower: Vec<Vec<usize>>,
    upper: Vec<Vec<usize>>,
}

/// The sparse tables of a Newton block with Jacobian `jac`, when it is large and sparse enough.
pub fn analyse(g: &Graph, jac: &[Vec<NodeId>]) -> Option<Sparse> {
    let n = jac.len();
    if n < MIN_SIZE || n > u16::MAX as usize || jac.iter().any(|r| r.len() != n) {
        return None;
    }
    let rows: Vec<BTreeSet<usize>> = jac.iter().map(|r| (0..n).filter(|&c| !g.is_zero(r[c])).collect()).collect();
    let m = maximum_matching(&rows, n);
    if !m.is_perfect() {
        return None;
    }
    let matched: Vec<usize> = m.eq_to_unknown.iter().map(|u| u.unwrap_or(0)).collect();
    let elim = eliminate(rows.clone(), &matched);
    let factor: usize = n + elim.lower.iter().chain(&elim.upper).map(Vec::len).sum::<usize>();
    if factor as f64 > MAX_DENSITY * (n * n) as f64 {
        return None;
    }
    Some(tables(&rows, &elim))
}

/// Markowitz elimination on the matched pairs (see the module documentation).
fn eliminate(mut rows: Vec<BTreeSet<usize>>, matched: &[usize]) -> Elimination {
    let n = rows.len();
    let mut cols: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); n];
    for (r, row) in rows.iter().enumerate() {
        for &c in row {
            cols[c].insert(r);
        }
    }
    let mut done = vec![false; n];
    let mut e = Elimination { pivots: Vec::new(), lower: Vec::new(), upper: Vec::new() };
    for _ in 0..n {
        let cost = |r: usize| (rows[r].len() - 1) * (cols[matched[r]].len() - 1);
        let Some(r) = (0..n).filter(|&r| !done[r]).min_by_key(|&r| (cost(r), r)) else { break };
        let c = matched[r];
        done[r] = true;
        let lower: Vec<usize> = cols[c].iter().copied().filter(|&i| i != r).collect();
        let upper: Vec<usize> = rows[r].iter().copied().filter(|&j| j != c).collect();
        // The pivot's row and column leave the active submatrix; every row below gains the
        // pivot row's pattern (fill).
        for &j in &upper {
            cols[j].remove(&r);
        }
        for &i in &lower {
            rows[i].remove(&c);
            for &j in &upper {
                rows[i].insert(j);
                cols[j].insert(i);
            }
        }
        cols[c].clear();
        rows[r].clear();
        e.pivots.push((r, c));
        e.lower.push(lower);
        e.upper.push(upper);
    }
    e
}

/// Whether a permutation (`p[k]` = image of `k`) is odd.
fn odd(p: &[usize]) -> bool {
    let mut seen = vec![false; p.len()];
    let mut odd = false;
    for s in 0..p.len() {
        let mut k = s;
        let mut len = 0;
        while !seen[k] {
            seen[k] = true;
            k = p[k];
            len += 1;
        }
        // A cycle of even length is an odd permutation.
        if len > 0 && len % 2 == 0 {
            odd = !odd;
        }
    }
    odd
}

/// Slots and index tables of an elimination, in pivot coordinates.
fn tables(rows: &[BTreeSet<usize>], e: &Elimination) -> Sparse {
    let n = rows.len();
    let (mut row_at, mut col_at) = (vec![0usize; n], vec![0usize; n]);
    for (k, &(r, c)) in e.pivots.iter().enumerate() {
        row_at[r] = k;
        col_at[c] = k;
    }
    let mut slots: HashMap<(usize, usize), u32> = HashMap::new();
    let mut slot_of = |i: usize, j: usize| {
        let next = slots.len() as u32;
        *slots.entry((i, j)).or_insert(next)
    };
    let mut s = Sparse {
        entries: Vec::new(),
        row_ptr: vec![0],
        slot: Vec::new(),
        prow: e.pivots.iter().map(|p| p.0 as u16).collect(),
        pcol: e.pivots.iter().map(|p| p.1 as u16).collect(),
        odd: odd(&e.pivots.iter().map(|p| p.0).collect::<Vec<_>>())
            ^ odd(&e.pivots.iter().map(|p| p.1).collect::<Vec<_>>()),
        diag: (0..n).map(|k| slot_of(k, k)).collect(),
        l_ptr: vec![0],
        l_slot: Vec::new(),
        l_row: Vec::new(),
        u_ptr: vec![0],
        u_slot: Vec::new(),
        u_col: Vec::new(),
        upd: Vec::new(),
        nlu: 0,
    };
    for (k, (lower, upper)) in e.lower.iter().zip(&e.upper).enumerate() {
        let li: Vec<usize> = lower.iter().map(|&r| row_at[r]).collect();
        let uj: Vec<usize> = upper.iter().map(|&c| col_at[c]).collect();
        for &i in &li {
            s.l_slot.push(slot_of(i, k));
            s.l_row.push(i as u16);
        }
        for &j in &uj {
            s.u_slot.push(slot_of(k, j));
            s.u_col.push(j as u16);
        }
        for &i in &li {
            for &j in &uj {
                s.upd.push(slot_of(i, j));
            }
        }
        s.l_ptr.push(s.l_slot.len() as u32);
        s.u_ptr.push(s.u_slot.len() as u32);
    }
    for (r, row) in rows.iter().enumerate() {
        for &c in row {
            s.entries.push((r, c));
            s.slot.push(slot_of(row_at[r], col_at[c]));
        }
        s.row_ptr.push(s.entries.len() as u32);
    }
    s.nlu = slots.len();
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The structure of a ring of `k` four-bar loops: rows `2i`, `2i + 1` (loop `i`) hold the
    /// coupler `2i`, the rocker `2i + 1` and the previous loop's rocker.
    fn ring(k: usize) -> Vec<BTreeSet<usize>> {
        (0..2 * k).map(|r| [r & !1, r | 1, (2 * (r / 2) + 2 * k - 1) % (2 * k)].into_iter().collect()).collect()
    }

    #[test]
    fn a_ring_factorises_with_linear_fill() {
        for k in [8, 16, 32, 64] {
            let rows = ring(k);
            let matched: Vec<usize> = (0..2 * k).collect();
            let e = eliminate(rows.clone(), &matched);
            let s = tables(&rows, &e);
            // 3 entries per row, fill along one column: a bounded number per row.
            assert!(s.nlu <= 6 * 2 * k, "{k} loops: {} slots", s.nlu);
            assert!(s.upd.len() <= 8 * 2 * k, "{k} loops: {} updates", s.upd.len());
            assert_eq!(s.entries.len(), 3 * 2 * k);
        }
    }

    #[test]
    fn every_update_targets_an_entry_of_the_active_submatrix() {
        let rows = ring(8);
        let e = eliminate(rows.clone(), &(0..16).collect::<Vec<_>>());
        let s = tables(&rows, &e);
        // All slots are in range.
        assert!(s.slot.iter().chain(&s.upd).chain(&s.l_slot).chain(&s.u_slot).all(|&x| (x as usize) < s.nlu));
        // Slots are distinct per position: every table's positions, in pivot coordinates, rebuilt
        // from the permutations and the factors' patterns (the entries of the matrix; the
        // diagonal; per pivot `k` its column of L, its row of U, and the updates, each row of
        // that L column against each column of that U row, in that order): one slot is one
        // position and one position one slot, and every slot is some position's.
        let n = rows.len();
        let (mut row_at, mut col_at) = (vec![0; n], vec![0; n]);
        for k in 0..n {
            (row_at[s.prow[k] as usize], col_at[s.pcol[k] as usize]) = (k, k);
        }
        let mut at: Vec<((usize, usize), u32)> = Vec::new();
        at.extend(s.entries.iter().zip(&s.slot).map(|(&(r, c), &x)| ((row_at[r], col_at[c]), x)));
        at.extend(s.diag.iter().enumerate().map(|(k, &x)| ((k, k), x)));
        let mut upd = s.upd.iter();
        for k in 0..n {
            let l = s.l_ptr[k] as usize..s.l_ptr[k + 1] as usize;
            let u = s.u_ptr[k] as usize..s.u_ptr[k + 1] as usize;
            at.extend(l.clone().map(|t| ((s.l_row[t] as usize, k), s.l_slot[t])));
            at.extend(u.clone().map(|t| ((k, s.u_col[t] as usize), s.u_slot[t])));
            for i in l.map(|t| s.l_row[t] as usize) {
                for j in u.clone().map(|t| s.u_col[t] as usize) {
                    at.push(((i, j), *upd.next().expect("an update per pair")));
                }
            }
        }
        assert!(upd.next().is_none(), "an update for no pair");
        let (mut slot_at, mut position_of) = (HashMap::new(), HashMap::new());
        for (p, x) in at {
            assert_eq!(*slot_at.entry(p).or_insert(x), x, "position {p:?} in two slots");
            assert_eq!(*position_of.entry(x).or_insert(p), p, "slot {x} at two positions");
        }
        assert_eq!(position_of.len(), s.nlu, "a slot of no position");
        let mut prow = s.prow.clone();
        prow.sort_unstable();
        assert_eq!(prow, (0..16).collect::<Vec<u16>>());
    }

    #[test]
    fn parity_of_permutations() {
        assert!(!odd(&[0, 1, 2]));
        assert!(odd(&[1, 0, 2]));
        assert!(!odd(&[1, 2, 0]));
        // (0 3)(1 2)(4 5): three transpositions.
        assert!(odd(&[3, 2, 1, 0, 5, 4]));
    }
}
