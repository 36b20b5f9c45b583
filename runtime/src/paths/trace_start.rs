//! Where a trace starts: the solved state at its first input, or a limit position there.
//!
//! A sweep that stops at a limit position names its input, and a trace is what goes on from it;
//! but there the velocity analogs do not exist and a point solve fails as singular. The
//! positions do exist: a closed form computes them (its root's discriminant is zero, or
//! rounded to it), and the curve's tangent is the null vector of `[J, dF/dsigma]`. A block
//! solved by Newton's method reaches a limit position only linearly (it reports that as
//! singular, its positions known to about the square root of the rounding): there the limit
//! position is located from a regular point beside it, as the trace locates those it passes.

use super::curve::{CurvePoint, Metric, Path, arc_step, locate_fold, tangent_by_null_vector, tangent_from_analogs};
use crate::dims::{Dims, KinState};
use crate::error::Error;
use crate::mechanism::kernel::{Kernel, KinOf, Q, X};
use crate::solvers::newton::NewtonConfig;
use nalgebra::DVector;

/// The start's positions and path coordinate, and its state where the analogs exist (the
/// point solve's error where they do not: `Singular` at a limit position, `Domain` where an
/// analog left `f64`'s range).
pub(super) struct Start<K: Kernel> {
    pub q: Q<K>,
    pub sigma: f64,
    pub analogs: Result<KinOf<K>, Error>,
}

/// How far beside a limit position a Newton block's start is solved, in the scaled path
/// coordinate (about radians of an angle input): far enough for a regular solve (a pivot ratio
/// of about its square root), near enough that the limit position is a short step on.
const BESIDE: f64 = 1e-6;

/// The start of a trace along `path` from `guess` (see the module's documentation). Errors: the
/// point solve's, where no limit position is there to start from.
pub(super) fn start<K: Kernel>(m: &K, path: &Path<X<K>>, guess: &Q<K>, cfg: &NewtonConfig) -> Result<Start<K>, Error> {
    let from = &path.from;
    match m.kinematics(from, guess, cfg) {
        Ok(k0) => {
            let mut q = guess.clone();
            q.as_mut().copy_from_slice(k0.q());
            Ok(Start { q, sigma: 0.0, analogs: Ok(k0) })
        }
        Err(e @ Error::Singular { .. }) => match m.positions(from, guess, &cfg.with_singular_tol(0.0)) {
            Ok(q) => Ok(Start { q, sigma: 0.0, analogs: Err(e) }),
            Err(_) => match limit_beside(m, path, guess, cfg) {
                Some(p) => Ok(Start { q: p.q, sigma: p.sigma, analogs: Err(e) }),
                None => Err(e),
            },
        },
        // A value the trace does not use left `f64`'s range (the acceleration analogs by a
        // length input, about `1 / size²`, in a mechanism below about `1e-154` in size): the
        // positions stand, and the tangent is taken from the Jacobian (see `tangent`).
        Err(e @ Error::Domain { .. }) => match m.positions(from, guess, cfg) {
            Ok(q) => Ok(Start { q, sigma: 0.0, analogs: Err(e) }),
            Err(_) => Err(e),
        },
        Err(e) => Err(e),
    }
}

/// The start's unit tangent (scaled coordinates) at `(q, sigma)`: from the analogs, or where
/// they are not to be had (a limit position, or an analog beyond `f64`'s range) the null
/// vector of `[J, dF/dsigma]`, where that has full rank. At a branch point (two curves through
/// the start: the ratio of that matrix's smallest singular value to its largest below
/// `branch_ratio`), or where the Jacobian is not finite, the point solve's error.
pub(super) fn tangent<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    (q, sigma): (&Q<K>, f64),
    analogs: Result<KinOf<K>, Error>,
    branch_ratio: f64,
) -> Result<DVector<f64>, Error> {
    match analogs {
        Ok(k0) => Ok(tangent_from_analogs(&k0, path, metric)),
        Err(e) => tangent_by_null_vector(m, path, metric, q, sigma)
            .filter(|(_, ratio)| *ratio >= branch_ratio)
            .map(|(t, _)| t)
            .ok_or(e),
    }
}

/// The limit position at (within the rounding of) the path's start, located from a regular
/// point [`BESIDE`] it on whichever side the curve lies: the root of the input's rate along the
/// curve between that point and a step past the limit position. `None` where neither side
/// solves, or no step from it passes a limit position near the start.
fn limit_beside<K: Kernel>(m: &K, path: &Path<X<K>>, guess: &Q<K>, cfg: &NewtonConfig) -> Option<CurvePoint<Q<K>>> {
    let units = Metric::at(m, path, &path.from, guess);
    [BESIDE, -BESIDE].into_iter().find_map(|side| {
        let sigma = side * units.sigma;
        let x = path.at_sigma(sigma);
        let k = m.kinematics(&x, guess, cfg).ok()?;
        let mut q = guess.clone();
        q.as_mut().copy_from_slice(k.q());
        let metric = Metric::at(m, path, &x, &q);
        let mut tangent = tangent_from_analogs(&k, path, &metric);
        // Towards the start, where the input turns back.
        if tangent[m.dims().n()] * side > 0.0 {
            tangent.neg_mut();
        }
        let beside = CurvePoint { q, sigma, tangent };
        // The limit position lies about twice the scaled distance to the start over the input's
        // rate along the curve there (the input's change is quadratic in the arclength); steps
        // up to eight times that find the input turned back.
        let reach = 2.0 * (sigma / metric.sigma).abs() / beside.dsigma().abs();
        // Finite analogs leave the rate positive; the test keeps the doubling below finite.
        if !(reach > 0.0 && reach.is_finite()) {
            return None;
        }
        let mut ds = 2.0 * reach;
        while ds <= 8.0 * reach {
            if let Some(past) = arc_step(m, path, &metric, &beside, ds, cfg)
                && past.dsigma() * beside.dsigma() < 0.0
            {
                // Between the point beside the start and the start, give or take the rounding.
                return locate_fold(m, path, &metric, &beside, ds, past.dsigma(), cfg)
                    .filter(|limit| limit.sigma.abs() <= sigma.abs());
            }
            ds *= 2.0;
        }
        None
    })
}
