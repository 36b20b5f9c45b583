//! The order in which input pairs (and second analogs) are stored.

/// Input pairs `(i, j)` with `i <= j`, in the order second analogs are stored.
pub fn pairs(ni: usize) -> Vec<(usize, usize)> {
    (0..ni).flat_map(|i| (i..ni).map(move |j| (i, j))).collect()
}

/// Index of the input pair `(i, j)` (in either order) among [`pairs`].
pub fn pair_index(ni: usize, i: usize, j: usize) -> usize {
    let (i, j) = if i <= j { (i, j) } else { (j, i) };
    pairs(ni).iter().position(|&p| p == (i, j)).unwrap_or(0)
}
