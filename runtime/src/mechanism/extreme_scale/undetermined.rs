//! An angle the data do not determine, found at a root the rescue's Newton reached: the verdict
//! the regular solvers give such a block at ordinary sizes (the closed-form dyad's short link,
//! Newton's angle that turned away and closes at every value), in the equations' own magnitudes.

use super::system::{Block, System, blank_evaluation};
use crate::solvers::newton::{BlockEval, BlockFailure, Solved};

/// How far an angle is turned from its root to probe whether the equations see it: 2 rad, as
/// the generated Newton solver's own probe (no whole fraction of a turn, where an equation that
/// repeats every half or third of a turn would close again; a chord of `2 sin 1 = 1.68` times
/// the angle's link).
const PROBE_TURN: f64 = 2.0;

/// The largest change of a row's residual, over its magnitude, that the probe's turn may make
/// for the angle to count as not determined: the rounding of the row's sum evaluated again (a
/// few units in the last place of its largest terms), the bound within which the tests find
/// every angle of such a link closing its loop. A link of `eps` of its loop's size moves a row
/// by at most `1.68 eps` of it (the closed form's short link is one no longer than `eps` of the
/// dyad's size); one of `1e-14` of a unit four-bar (rows of magnitude about 3) by up to
/// `5.6e-15 / 3`, `8.4 eps`: seen.
const UNSEEN: f64 = 4.0 * f64::EPSILON;

/// The singular failure of the system `system` at the root `solved` (in its units) where an
/// angle of it is one the equations do not see: turned by [`PROBE_TURN`] alone, the residuals
/// `eval` gives change by no more than [`UNSEEN`] of their magnitudes (a link below the
/// rounding of its loop, every angle of which closes it). The failure names the first row of
/// the block of `blocks` holding that angle (row 0 where none does), with a pivot ratio of 0,
/// as the closed form reports such a block (see `short_link`); `None` where every angle is
/// seen. At sizes of `1e±200` the whole-system Newton, its columns scaled to their magnitudes,
/// converged with such an angle where its guess left it (the rocker of `1e-20` of a four-bar at
/// `1.49999` rad from `1.5`), where size 1 is singular. One evaluation per angle, after a
/// solve that converged: the rescue runs only after a failed step.
#[cold]
#[inline(never)]
pub(super) fn undetermined_angle<const N: usize>(
    solved: &Solved<N>,
    system: &System<'_, N>,
    blocks: &[Block],
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Option<BlockFailure> {
    let &System { scale, unit, turns, cfg, .. } = system;
    let mut ev = blank_evaluation::<N>();
    eval(&solved.z, &mut ev);
    let at_root = ev.f;
    let unseen = (0..N).filter(|&u| turns[u]).find(|&u| {
        let mut probe = solved.z;
        probe[u] += PROBE_TURN / unit[u];
        eval(&probe, &mut ev);
        // Written so that a NaN counts as seen.
        (0..N).all(|r| (ev.f[r] - at_root[r]).abs() <= UNSEEN * scale[r])
    })?;
    let row = blocks.iter().find(|b| b.cols.contains(&unseen)).and_then(|b| b.rows.first().copied());
    Some(BlockFailure::Singular {
        row: row.unwrap_or(0),
        iterations: solved.iterations,
        residual: solved.residual,
        pivot_ratio: 0.0,
        tolerance: cfg.singular_tol,
    })
}
