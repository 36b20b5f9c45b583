//! Small blocks with known roots, and a solve from a guess as the generated code makes it, for
//! the unit tests of the solver's parts.

use super::config::NewtonConfig;
use super::newton;
use super::report::{BlockFailure, Solved};
use super::scales::{BlockEval, Magnitudes};

/// [`newton`] from `z0` with the evaluation made as the generated code makes it (into the
/// caller's slot); the solved block and its final evaluation.
pub(super) fn solve<const N: usize, const K: usize>(
    z0: [f64; N],
    cfg: &NewtonConfig,
    mut eval: impl FnMut(&[f64; N]) -> BlockEval<N, K>,
) -> Result<(Solved<N>, BlockEval<N, K>), BlockFailure> {
    let mut ev = eval(&z0);
    newton(z0, &mut ev, cfg, in_place(eval), &mags).map(|s| (s, ev))
}

/// The evaluation closure the solver takes (one that writes into its slot) from one that
/// returns its evaluation: the tests' blocks are small, and written more plainly returning.
pub(super) fn in_place<const N: usize, const K: usize, J>(
    mut eval: impl FnMut(&[f64; N]) -> BlockEval<N, K, J>,
) -> impl FnMut(&[f64; N], &mut BlockEval<N, K, J>) {
    move |z, ev| *ev = eval(z)
}

/// An evaluation whose magnitudes depend on the unknowns: `scale` and `unit` kept after
/// each other, as the generated code keeps such magnitudes (`K = 2 N`).
pub(super) fn varying<const N: usize, const K: usize>(
    f: [f64; N],
    j: [[f64; N]; N],
    scale: [f64; N],
    unit: [f64; N],
) -> BlockEval<N, K> {
    let mut keep = [0.0; K];
    keep[..N].copy_from_slice(&scale);
    keep[N..2 * N].copy_from_slice(&unit);
    BlockEval { f, j, keep }
}

/// The magnitudes [`varying`] keeps.
pub(super) fn mags<const N: usize, const K: usize>(ev: &BlockEval<N, K>) -> Magnitudes<N> {
    Magnitudes::new(core::array::from_fn(|r| ev.keep[r]), core::array::from_fn(|c| ev.keep[N + c]))
}

pub(super) fn circle(z: &[f64; 2]) -> BlockEval<2, 4> {
    // x^2 + y^2 = 4, y = x^3 (root near (1.03, 1.72), solved numerically).
    let [x, y] = *z;
    varying(
        [x * x + y * y - 4.0, y - x * x * x],
        [[2.0 * x, 2.0 * y], [-3.0 * x * x, 1.0]],
        [x * x + y * y + 4.0, y.abs() + (x * x * x).abs()],
        [1.0; 2],
    )
}

/// `x^2 + y^2 + z^2 = 3`, `x = y z`, `z = x y`: a 3x3 block (the general factorisation)
/// with a regular root at `(1, 1, 1)`.
pub(super) fn sphere(z: &[f64; 3]) -> BlockEval<3, 6> {
    let [x, y, w] = *z;
    varying(
        [x * x + y * y + w * w - 3.0, x - y * w, w - x * y],
        [[2.0 * x, 2.0 * y, 2.0 * w], [1.0, -w, -y], [-y, -x, 1.0]],
        [x * x + y * y + w * w + 3.0, x.abs() + (y * w).abs(), w.abs() + (x * y).abs()],
        [1.0; 3],
    )
}
