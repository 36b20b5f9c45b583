//! A motion over a rectangular grid of inputs, for mechanisms with several inputs: every cell
//! solved by branch-safe sweeps that carry one assembly mode from the grid's first cell, the
//! cells that cannot be reached so marked.

use super::error::DrawError;
use super::motion::Motion;
use kinloop_runtime::{Kin, Mechanism, Sweep};

/// Largest number of cells a grid may have: a page holds at most a few thousand poses, and a
/// grid beyond this is a mistake in its counts rather than a wish.
pub const MAX_GRID_CELLS: usize = 100_000;

/// The poses of a mechanism over a rectangular grid of its inputs (see
/// [`GridMotion::record`]), for an interactive page with one slider per input
/// ([`html_grid`](crate::html::html_grid)).
///
/// Cells are numbered with the first input fastest: cell `i0 + n0 * (i1 + n1 * i2 ...)` is at
/// `axes[0][i0], axes[1][i1], ...`.
#[derive(Clone, Debug, PartialEq)]
pub struct GridMotion {
    /// The poses of the cells that were reached, in the order solved (rows along the first
    /// input). Its events are empty: a row ends at a limit position (the cells after it are
    /// unreachable) and the page marks none.
    pub motion: Motion,
    /// The input values along each axis (`count` values evenly spaced from `from` to `to`).
    pub axes: Vec<Vec<f64>>,
    /// For every cell, the index of its pose in `motion.poses`, or `None` where the mechanism
    /// cannot be assembled (on the assembly mode carried from the first cell).
    pub cells: Vec<Option<usize>>,
}

/// `count` values evenly spaced from `from` to `to` (as a sweep samples them).
fn spaced(from: f64, to: f64, count: usize) -> Vec<f64> {
    if count == 1 {
        return vec![from];
    }
    (0..count).map(|k| from + (to - from) * (k as f64 / (count - 1) as f64)).collect()
}

/// The states of a sweep of `m` from `x` along axis `a` over `values` (the other inputs as in
/// `x`), from `guess`: each sample's state, `None` from the first that fails or meets a limit
/// position on. The first sample's error is returned when `first` (the grid's start).
fn line<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    x: [f64; NI],
    a: usize,
    values: &[f64],
    guess: [f64; N],
    first: bool,
) -> Result<Vec<Option<Kin<N, NI, NO>>>, DrawError>
where
    M: Mechanism<N, NI, NO>,
{
    let (mut from, mut to) = (x, x);
    from[a] = values[0];
    to[a] = values[values.len() - 1];
    let mut out = Vec::with_capacity(values.len());
    let sweep = Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(m, from, to, values.len(), guess);
    match sweep {
        Ok(mut sweep) => {
            while let Some(k) = sweep.next_kin() {
                match k {
                    Ok(k) => out.push(Some(k)),
                    Err(e) if first && out.is_empty() => return Err(DrawError::Sweep(e)),
                    // A limit position (`Error::SweepStopped`) or a failed step: the rest of the
                    // line is not reached on this assembly mode.
                    Err(_) => break,
                }
            }
        }
        Err(e) => return Err(DrawError::Sweep(e)),
    }
    out.resize(values.len(), None);
    Ok(out)
}

impl GridMotion {
    /// Solves mechanism `m` over the grid of `counts[k]` inputs evenly spaced from `from[k]`
    /// to `to[k]` (both included) on each axis, starting from `guess` at `from` (the guess
    /// picks the assembly mode).
    ///
    /// The assembly mode is carried continuously: a branch-safe sweep along the last input
    /// from the first cell gives the start of each slice; each slice is filled the same way
    /// down to rows along the first input, each row started from the state at its first
    /// cell, itself swept from the previous row's first cell. Where a sweep meets a limit
    /// position or cannot be continued, the cells after it on that line (and the rows started
    /// from them) are marked unreachable: `None` in [`GridMotion::cells`].
    ///
    /// ```
    /// use kinloop::Mechanism;
    /// use kinloop_viz::draw::GridMotion;
    ///
    /// kinloop::mechanism! {
    ///     /// A five-bar: cranks `th1` at (0, 0) and `th2` at (e, 0), links meeting at `p`.
    ///     pub struct FiveBar {
    ///         params a = 1.0, b = 2.5, c = 2.5, d = 1.0, e = 2.0;
    ///         inputs th1, th2;
    ///         unknowns al = 1.2, be = 2.0;
    ///         loop l: a @ th1 + b @ al == (e, 0) + d @ th2 + c @ be;
    ///         point p = a @ th1 + b @ al;
    ///     }
    /// }
    /// let m = FiveBar::default();
    /// let from = [0.0, 0.5];
    /// let grid = GridMotion::record(&m, from, [3.0, 3.0], [7, 5], m.guess_flat(&from))?;
    /// assert_eq!(grid.cells.len(), 35);
    /// assert_eq!(grid.axes[1], [0.5, 1.125, 1.75, 2.375, 3.0]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`DrawError::InvalidSetting`] for a count of zero, a count above one with `from` equal
    /// to `to`, non-finite ends, or more than [`MAX_GRID_CELLS`] cells;
    /// [`DrawError::Sweep`] when the mechanism cannot be assembled at the first cell.
    pub fn record<M, const N: usize, const NI: usize, const NO: usize>(
        m: &M,
        from: [f64; NI],
        to: [f64; NI],
        counts: [usize; NI],
        guess: [f64; N],
    ) -> Result<GridMotion, DrawError>
    where
        M: Mechanism<N, NI, NO>,
    {
        if NI == 0 {
            return Err(DrawError::InvalidSetting(format!("`{}` has no input to make a grid of", M::NAME)));
        }
        for k in 0..NI {
            let name = M::INPUTS[k];
            if counts[k] == 0 {
                return Err(DrawError::InvalidSetting(format!("the grid has no value of input `{name}`")));
            }
            if !(from[k].is_finite() && to[k].is_finite()) {
                return Err(DrawError::InvalidSetting(format!(
                    "input `{name}` from {} to {} is not a finite range",
                    from[k], to[k]
                )));
            }
            if counts[k] > 1 && from[k] == to[k] {
                return Err(DrawError::InvalidSetting(format!(
                    "{} values of input `{name}` from {} to the same value",
                    counts[k], from[k]
                )));
            }
        }
        let cells = counts.iter().try_fold(1usize, |p, &c| p.checked_mul(c)).filter(|&n| n <= MAX_GRID_CELLS);
        let Some(cells) = cells else {
            return Err(DrawError::InvalidSetting(format!(
                "a grid of {counts:?} values has more than {MAX_GRID_CELLS} cells"
            )));
        };
        let axes: Vec<Vec<f64>> = (0..NI).map(|k| spaced(from[k], to[k], counts[k])).collect();
        let mut grid = GridMotion { motion: Motion::empty::<M, N, NI, NO>(), axes, cells: vec![None; cells] };
        grid.fill(m, NI - 1, from, guess, 0, true)?;
        Ok(grid)
    }

    /// Fills the sub-grid of axes `0..=a` whose first cell (number `base`) is at `x`, swept
    /// from `guess` there.
    fn fill<M, const N: usize, const NI: usize, const NO: usize>(
        &mut self,
        m: &M,
        a: usize,
        x: [f64; NI],
        guess: [f64; N],
        base: usize,
        first: bool,
    ) -> Result<(), DrawError>
    where
        M: Mechanism<N, NI, NO>,
    {
        let stride: usize = self.axes[..a].iter().map(Vec::len).product();
        let values = self.axes[a].clone();
        let states = line(m, x, a, &values, guess, first)?;
        for (j, state) in states.into_iter().enumerate() {
            let Some(k) = state else { break };
            let cell = base + j * stride;
            if a == 0 {
                self.cells[cell] = Some(self.motion.poses.len());
                self.motion.push(&k);
            } else {
                self.fill(m, a - 1, k.x, k.q, cell, first && j == 0)?;
            }
        }
        Ok(())
    }

    /// The numbers of cells along each axis.
    pub fn counts(&self) -> Vec<usize> {
        self.axes.iter().map(Vec::len).collect()
    }

    /// The cell at indices `at` (one per axis), or `None` when an index is out of range.
    pub fn cell(&self, at: &[usize]) -> Option<usize> {
        if at.len() != self.axes.len() {
            return None;
        }
        let mut cell = 0;
        for (&i, axis) in at.iter().zip(&self.axes).rev() {
            if i >= axis.len() {
                return None;
            }
            cell = cell * axis.len() + i;
        }
        Some(cell)
    }

    /// The rows along the first input: for each, the runs of consecutive reachable cells, as
    /// indices of their poses (the traced paths drawn on a page).
    pub(crate) fn runs(&self) -> Vec<Vec<usize>> {
        let n0 = self.axes[0].len();
        let mut runs = Vec::new();
        for row in self.cells.chunks(n0) {
            let mut run = Vec::new();
            for c in row {
                match c {
                    Some(i) => run.push(*i),
                    None if !run.is_empty() => runs.push(std::mem::take(&mut run)),
                    None => {}
                }
            }
            if !run.is_empty() {
                runs.push(run);
            }
        }
        runs
    }
}
