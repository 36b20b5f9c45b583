//! A motion over a rectangular grid of inputs, for mechanisms with several inputs: every cell
//! solved by branch-safe sweeps that carry one assembly mode from the grid's first cell, the
//! cells that cannot be reached so marked.

use super::error::DrawError;
use super::motion::{Motion, Pose};
use kinloop_runtime::paths::sweep::MAX_TURNS;
use kinloop_runtime::{Error, Kin, Mechanism, Sweep};

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
    /// The poses of the cells that were reached, in the order solved (breadth first from the
    /// first cell). Its events are empty: the page marks none.
    pub motion: Motion,
    /// The input values along each axis (`count` values evenly spaced from `from` to `to`).
    pub axes: Vec<Vec<f64>>,
    /// For every cell, the index of its pose in `motion.poses`, or `None` where no sweep from a
    /// reached neighbour reached it on the assembly mode carried from the first cell: the
    /// mechanism cannot be assembled there, or a limit position or a singular position lies
    /// on the way, or at the cell itself (see [`GridMotion::record`]).
    pub cells: Vec<Option<usize>>,
}

/// Whether a sweep's error refuses its arguments (a range too long, an invalid argument) rather
/// than reporting where the mechanism goes.
fn refused(e: &Error) -> bool {
    matches!(e, Error::RangeTooLong { .. } | Error::InvalidArgument(_))
}

/// `count` values evenly spaced from `from` to `to` (as a sweep samples them).
fn spaced(from: f64, to: f64, count: usize) -> Vec<f64> {
    if count == 1 {
        return vec![from];
    }
    (0..count).map(|k| from + (to - from) * (k as f64 / (count - 1) as f64)).collect()
}

impl GridMotion {
    /// Solves mechanism `m` over the grid of `counts[k]` inputs evenly spaced from `from[k]`
    /// to `to[k]` (both included) on each axis, starting from `guess` at `from` (the guess
    /// picks the assembly mode).
    ///
    /// The assembly mode is carried continuously: from the first cell, every cell reached
    /// passes its state to its neighbours along each axis by a branch-safe sweep between the
    /// two (breadth first, in cell order). A sweep that meets a limit position or cannot be
    /// continued passes nothing, and a cell no neighbour reaches is marked unreachable: `None`
    /// in [`GridMotion::cells`]. Cells beyond a limit position on one line are so reached
    /// around it where the mechanism can be assembled there on the same mode. An unreachable
    /// cell is not one where the mechanism cannot be assembled: it may be one where it can, but
    /// every way to it from a reached neighbour passes a limit position or a singular position
    /// (where a sweep stops), or where it is singular itself (a five-bar whose cranks' pins
    /// coincide, its links free to turn about them).
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
    /// to `to`, a count of one with `from` not `to` (one value is `from` alone), non-finite
    /// ends, more than [`MAX_GRID_CELLS`] cells, or a range along an input
    /// that the grid's sweeps, over all its lines along that input, would follow for more than
    /// the [`MAX_TURNS`](kinloop_runtime::paths::sweep::MAX_TURNS) turns of one sweep;
    /// [`DrawError::Sweep`] when the mechanism cannot be assembled at the first cell, or when a
    /// sweep between two cells refuses its range.
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
        let sweep = |from: &[f64], to: &[f64], samples: usize, guess: &[f64]| {
            let (Ok(from), Ok(to), Ok(guess)) =
                (<[f64; NI]>::try_from(from), <[f64; NI]>::try_from(to), <[f64; N]>::try_from(guess))
            else {
                return Err(Error::InvalidArgument("a grid's sweep of another size".into()));
            };
            let sweep = Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(m, from, to, samples, guess)?;
            Ok(sweep.last().map(|k| k.map(|k| Pose::from(&k))))
        };
        GridMotion::record_by(Motion::empty::<M, N, NI, NO>(), &from, &to, &counts, &guess, sweep)
    }

    /// [`GridMotion::record`] of any mechanism, compiled or read at run time: `motion` is an
    /// empty motion of the mechanism ([`Motion::of`]), and `sweep(from, to, samples, guess)`
    /// makes its branch-safe sweep (for a `kinloop_model::Model`, `Model::sweep`) and returns
    /// its last item (`None` for a sweep of no item).
    ///
    /// # Errors
    /// As [`GridMotion::record`], and [`DrawError::InvalidSetting`] when `from`, `to`, `counts`
    /// do not have one value per input of the motion.
    pub fn record_by<F>(
        motion: Motion,
        from: &[f64],
        to: &[f64],
        counts: &[usize],
        guess: &[f64],
        mut sweep: F,
    ) -> Result<GridMotion, DrawError>
    where
        F: FnMut(&[f64], &[f64], usize, &[f64]) -> Result<Option<Result<Pose, Error>>, Error>,
    {
        let ni = motion.inputs.len();
        if ni == 0 {
            return Err(DrawError::InvalidSetting("the mechanism has no input to make a grid of".into()));
        }
        if from.len() != ni || to.len() != ni || counts.len() != ni {
            return Err(DrawError::InvalidSetting(format!(
                "a grid of {ni} inputs needs {ni} values in `from`, `to` and `counts` (given {}, {}, {})",
                from.len(),
                to.len(),
                counts.len()
            )));
        }
        for k in 0..ni {
            let name = &motion.inputs[k];
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
            // One value is `from` alone: a range to another end would be ignored, as a sweep
            // of one sample refuses it.
            if counts[k] == 1 && from[k] != to[k] {
                return Err(DrawError::InvalidSetting(format!(
                    "one value of input `{name}` from {} to {}: the range would be ignored; give 2 values or \
                     more, or the same value at both ends for a grid fixed in `{name}`",
                    from[k], to[k]
                )));
            }
        }
        let cells = counts.iter().try_fold(1usize, |p, &c| p.checked_mul(c)).filter(|&n| n <= MAX_GRID_CELLS);
        let Some(cells) = cells else {
            return Err(DrawError::InvalidSetting(format!(
                "a grid of {counts:?} values has more than {MAX_GRID_CELLS} cells"
            )));
        };
        let axes: Vec<Vec<f64>> = (0..ni).map(|k| spaced(from[k], to[k], counts[k])).collect();
        let mut grid = GridMotion { motion, axes, cells: vec![None; cells] };
        grid.flood(&mut sweep, from, guess)?;
        Ok(grid)
    }

    /// The input values of cell `cell`.
    fn inputs(&self, cell: usize) -> Vec<f64> {
        let mut rest = cell;
        self.axes
            .iter()
            .map(|axis| {
                let i = rest % axis.len();
                rest /= axis.len();
                axis[i]
            })
            .collect()
    }

    /// Solves the first cell at `from` from `guess`, then every cell reached from a reached
    /// neighbour by a sweep of two samples (branch-safe: its steps in between are its own).
    fn flood<F>(&mut self, sweep: &mut F, from: &[f64], guess: &[f64]) -> Result<(), DrawError>
    where
        F: FnMut(&[f64], &[f64], usize, &[f64]) -> Result<Option<Result<Pose, Error>>, Error>,
    {
        let first = sweep(from, from, 1, guess)
            .map_err(DrawError::Sweep)?
            .ok_or_else(|| DrawError::InvalidSetting("the first cell's sweep has no sample".into()))?
            .map_err(DrawError::Sweep)?;
        self.check_travel(sweep, &first)?;
        let mut states: Vec<Option<Pose>> = vec![None; self.cells.len()];
        states[0] = Some(first);
        let mut queue = std::collections::VecDeque::from([0usize]);
        while let Some(cell) = queue.pop_front() {
            let Some(k) = states[cell].clone() else { continue };
            self.cells[cell] = Some(self.motion.poses.len());
            let mut stride = 1;
            for a in 0..self.axes.len() {
                let len = self.axes[a].len();
                let i = (cell / stride) % len;
                let next = [(i > 0).then(|| cell - stride), (i + 1 < len).then(|| cell + stride)];
                for n in next.into_iter().flatten() {
                    if states[n].is_some() {
                        continue;
                    }
                    let to = self.inputs(n);
                    match sweep(&k.x, &to, 2, &k.q) {
                        Ok(Some(Ok(state))) => {
                            states[n] = Some(state);
                            queue.push_back(n);
                        }
                        // A sweep that refuses its arguments says nothing of the mechanism: not
                        // an unreachable cell but a grid no sweep can follow.
                        Err(e) | Ok(Some(Err(e))) if refused(&e) => return Err(DrawError::Sweep(e)),
                        _ => {}
                    }
                }
                stride *= len;
            }
            self.motion.push(k);
        }
        Ok(())
    }

    /// Refuses, before any neighbour is swept, a grid whose sweeps would travel along an input
    /// farther in all than one sweep follows ([`MAX_TURNS`] turns, in the sweep's own units of
    /// the inputs; [`DrawError::GridRange`]): its lines along that input, each the input's whole
    /// range, measured by a sweep of that length from the first cell, which refuses a range too
    /// long before it takes a step. Without it a wide range made every cell a sweep of up to a million turns (hours),
    /// or, beyond that, unreachable, as if the mechanism could not be assembled there.
    fn check_travel<F>(&self, sweep: &mut F, first: &Pose) -> Result<(), DrawError>
    where
        F: FnMut(&[f64], &[f64], usize, &[f64]) -> Result<Option<Result<Pose, Error>>, Error>,
    {
        let cells = self.cells.len();
        for (a, axis) in self.axes.iter().enumerate() {
            let (Some(&lo), Some(&hi)) = (axis.first(), axis.last()) else { continue };
            if axis.len() < 2 {
                continue;
            }
            let lines = cells / axis.len();
            let travel = (hi - lo) * lines as f64;
            let mut to = first.x.clone();
            to[a] += travel;
            let name = &self.motion.inputs[a];
            let refused = |turns: f64, max_turns: f64| {
                let name = name.clone();
                Err(DrawError::GridRange { input: a, name, lo, hi, lines, turns, max_turns, degrees: false })
            };
            match sweep(&first.x, &to, 1, &first.q) {
                Err(Error::RangeTooLong { turns, max_turns, .. })
                | Ok(Some(Err(Error::RangeTooLong { turns, max_turns, .. }))) => return refused(turns, max_turns),
                // A length the sweep cannot measure (not finite in the sweep's units).
                Err(Error::InvalidArgument(_)) | Ok(Some(Err(Error::InvalidArgument(_)))) => {
                    return refused(f64::INFINITY, MAX_TURNS);
                }
                _ => {}
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
