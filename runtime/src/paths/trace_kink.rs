//! Passing a kink in pseudo-arclength continuation ([`past_kink`], for [`trace`](super::trace)).
//!
//! A corner of the solution curve (`abs`, `min`, `max`, `clamp` in the equations) shows in the
//! continuation as a jump of its unit tangent in `(q, sigma)`: however short the step, the
//! tangent past the corner differs from the one before by a finite turn, where on a smooth
//! curve, through a limit position too, the turn shrinks with the step (the curvature times
//! it). So the trace halves a step whose tangent turns by more than [`MAX_TURN`], and a step
//! that cannot be made however short is judged here.
//!
//! The continuation cannot judge it in its own coordinates. It orients each tangent like the
//! one before, the rule that takes it round a limit position; at a corner sharper than a right
//! angle in the scaled coordinates (`abs` of a steep slope) the tangent so oriented points back
//! along the far side, the input reversing as at a limit position, and the corrector's plane,
//! square to the tangent before the corner, meets the far side behind the corner or not at
//! all. Across a corner the unknowns may well reverse (the slider of `abs` comes back), but the
//! input goes on: it is the input's direction that a corner keeps and a limit position
//! reverses.
//!
//! What tells them apart is the Jacobian in the unknowns. Where it is regular at both ends of
//! the step and inside it (pivots above the solver's threshold, the same determinant signs),
//! the curve is there the graph of a function `q(sigma)` of the path coordinate (the implicit
//! function theorem): no limit position lies on it (one needs a singular Jacobian), so the
//! curve goes on with the input moving the same way, and the question becomes the sweep's,
//! asked in its parameterisation by the input and answered by the same predicates (see
//! [`kink`]): the state a short step on in the input is continuous with this one (not another
//! solution a finite distance away), and states inside the step have one side's slopes `dq /
//! dsigma` (a corner, not the smoothly growing slopes of a limit position close by). At a limit
//! position the Jacobian is singular and the tangent turns smoothly: the turn shrinks with the
//! step, the continuation turns round it as it always did, and were it judged here, the pivots
//! and the slopes inside, between the sides', would refuse it.
//!
//! The judges read a state's positions, slopes, pivots and determinant signs, no acceleration.
//! Where the kernel's kinematics fail for an acceleration analog alone (by a length input about
//! `1 / size²`, beyond `f64` in a mechanism below about `1e-154` in size, whose trace needs
//! none), the states are taken from the positions and the Jacobian instead (see [`Route`]): the
//! kink is passed as at size 1, where it stopped the trace as a branch point.

use super::curve::{CurvePoint, Metric, Path, f_sigma};
use super::kink;
use crate::dims::{Dims, JacState, KinState, Store};
use crate::error::Error;
use crate::events::{Event, EventKind};
use crate::kin::DetSigns;
use crate::mechanism::kernel::{Kernel, Q, X};
use crate::solvers::newton::NewtonConfig;
use nalgebra::{DMatrix, DVector};
use std::borrow::Cow;

/// The largest turn of the unit tangent (scaled coordinates, as the chord between the two unit
/// vectors) over one step of the trace: a step that turns it more is halved. On a smooth curve
/// it bounds the step to about `MAX_TURN` over the curvature (radius `0.1` in scaled
/// coordinates at the default `ds` of `0.01`, sharper than any fold of a linkage the default
/// resolves); at a corner no step is short enough, and the corner is judged by [`past_kink`]. A
/// corner whose tangents differ by less (slopes that change by less than about a tenth, in
/// scaled coordinates) is passed as a smooth point is.
pub(crate) const MAX_TURN: f64 = 0.1;

/// The turn of the unit tangent from `before` to `after`: the chord between them.
pub(crate) fn turn(before: &DVector<f64>, after: &DVector<f64>) -> f64 {
    (after - before).norm()
}

/// Bisection steps locating a corner within the step across it: `2^-60` of it is far below the
/// rounding of the path coordinate, where the bisection stops first.
const LOCATE_STEPS: usize = 60;

/// A kink of the solution curve passed: the event where it is and the curve point there, on
/// the far side, from which the trace goes on.
pub(crate) struct Passed<Q> {
    /// [`EventKind::Kink`] at the corner (within rounding of its input).
    pub event: Event,
    /// The curve point at the corner with the far side's tangent, oriented so that the input
    /// keeps its direction.
    pub point: CurvePoint<Q>,
}

/// The kink just ahead of the curve point `p` of `path`, within arclength `reach` (scaled
/// coordinates, see [`Metric`]) along the curve, passed; `None` where no kink is there (see
/// the module's documentation): a singular or nearly singular position at either end or
/// inside, another assembly mode, an input that rounds to `p`'s, a step that cannot be solved,
/// or slopes that are not one side's or the other's. `pivot` is the smallest pivot ratio of a
/// regular position (the kernel's `SweepConfig::singular_pivot`), here at least
/// [`kink::KINK_PIVOT`].
pub(crate) fn past_kink<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    p: &CurvePoint<Q<K>>,
    reach: f64,
    cfg: &NewtonConfig,
    pivot: f64,
) -> Option<Passed<Q<K>>> {
    let d = m.dims();
    let dir = p.dsigma().signum();
    if p.dsigma() == 0.0 || !dir.is_finite() {
        return None;
    }
    // The step in the input: along the curve the path coordinate changes by no more than the
    // arclength (scaled), so twice `reach` in it is past the corner.
    let h = dir * 2.0 * reach * metric.sigma;
    let at = |frac: f64| path.at_sigma(p.sigma + frac * h);
    // Every state by the kernel's kinematics, or where those fail at the start for an
    // acceleration analog alone (beyond `f64` by a length input in a mechanism below about
    // `1e-154` in size), every one by its positions and Jacobian: the judges read no
    // acceleration, and states of one route are compared with states of the same.
    let (route, before) = match m.kinematics(&at(0.0), &p.q, cfg) {
        Ok(k) => (Route::Kinematics, Judged::of(&k, &p.q, path)),
        Err(e) if acceleration_beyond_range(&e).is_some() => {
            (Route::Jacobian, judged(m, path, &at(0.0), &p.q, cfg, Route::Jacobian)?)
        }
        Err(_) => return None,
    };
    let solve = |frac: f64, guess: &Q<K>| judged(m, path, &at(frac), guess, cfg, route);
    if at(1.0).as_ref() == at(0.0).as_ref() {
        return None;
    }
    // Predicted along this side's tangent: off by the slopes' jump times part of the step.
    let mut guess = p.q.clone();
    for u in 0..d.n() {
        guess[u] = before.q[u] + before.slopes[u] * h;
    }
    let after = solve(1.0, &guess)?;
    let signs = before.signs;
    let blocks = route.blocks(m);
    let pivot = pivot.max(kink::KINK_PIVOT);
    let regular = |k: &Judged<Q<K>>| k.pivot >= pivot && k.signs.same_for(&signs, blocks);
    if !regular(&before) || !regular(&after) {
        return None;
    }
    // Each unknown in its unit, the slopes per unit of the path coordinate, the step's.
    let unit = |u: usize| metric.unit[u];
    let sides = m.judged().iter().map(|&u| kink::Side {
        change: (after.q[u] - before.q[u]) / unit(u),
        slope_before: before.slopes[u] / unit(u),
        slope_after: after.slopes[u] / unit(u),
    });
    if !kink::continuous(sides, h) {
        return None;
    }
    let slopes = |inside: &Judged<Q<K>>| -> Vec<kink::Slopes> {
        m.judged()
            .iter()
            .map(|&u| kink::Slopes {
                before: before.slopes[u] / unit(u),
                after: after.slopes[u] / unit(u),
                inside: inside.slopes[u] / unit(u),
            })
            .collect()
    };
    // Probed at a third and two thirds, should one land on the corner itself.
    for frac in [1.0 / 3.0, 2.0 / 3.0] {
        let inside = solve(frac, &p.q)?;
        if !regular(&inside) || !kink::one_sided(&slopes(&inside)) {
            return None;
        }
    }
    let (sigma, corner) = locate(m, (p.sigma, h), (&before, &after), unit, regular, solve)?;
    let mut tangent = corner.tangent(metric);
    tangent *= dir;
    let q = corner.q;
    let x = path.at_sigma(sigma);
    let event = Event {
        kind: EventKind::Kink,
        x: x.as_ref().to_vec(),
        tau: sigma / path.len,
        q: q.as_ref().to_vec(),
        block: None,
    };
    Some(Passed { event, point: CurvePoint { q, sigma, tangent } })
}

/// The corner between `before` (at `sigma0`) and `after` (at `sigma0 + h`), by bisection on the
/// side whose slopes a state solved in between has (one side's or the other's, as the probes
/// found): the path coordinate of the first state found on the far side, within rounding of the
/// corner, and that state. `unit(u)` is unknown `u`'s unit (see [`Metric`]).
fn locate<K: Kernel>(
    m: &K,
    (sigma0, h): (f64, f64),
    (before, after): (&Judged<Q<K>>, &Judged<Q<K>>),
    unit: impl Fn(usize) -> f64,
    regular: impl Fn(&Judged<Q<K>>) -> bool,
    solve: impl Fn(f64, &Q<K>) -> Option<Judged<Q<K>>>,
) -> Option<(f64, Judged<Q<K>>)> {
    // The unknown whose slope jumps most, in its unit (an angle's and a length's slopes compared
    // as they were, their order changed with the unit of length), tells the sides apart (its
    // jump is at least `kink::MIN_JUMP` of the steeper slope; the probes put every slope within
    // `kink::ONE_SIDED` of it from one side).
    let jump = |u: usize| after.slopes[u] - before.slopes[u];
    let scaled = |u: usize| (jump(u) / unit(u)).abs();
    let u = m.judged().iter().copied().max_by(|&a, &b| scaled(a).total_cmp(&scaled(b)))?;
    let middle = 0.5 * (after.slopes[u] + before.slopes[u]);
    // The side of a slope by its sign against the jump's: their product, in the slopes' own
    // units, is the square of a size's reciprocal or of a size, and underflowed to zero for a
    // mechanism below about `1e-154` in size (a length's slopes) or above `1e154` (an angle's
    // by a length input), which put every state on the near side and the corner at the step's
    // end, up to 1e-7 of the input off.
    let far_side = |k: &Judged<Q<K>>| (k.slopes[u] - middle) * jump(u).signum() > 0.0;
    let (mut lo, mut hi, mut far) = (0.0f64, 1.0f64, after.clone());
    // Solved from the nearest state found on the far side.
    let mut guess = far.q.clone();
    for _ in 0..LOCATE_STEPS {
        let mid = 0.5 * (lo + hi);
        if sigma0 + mid * h == sigma0 + lo * h || sigma0 + mid * h == sigma0 + hi * h {
            break;
        }
        let k = solve(mid, &guess)?;
        if !regular(&k) {
            return None;
        }
        if far_side(&k) {
            hi = mid;
            guess.as_mut().copy_from_slice(k.q.as_ref());
            far = k;
        } else {
            lo = mid;
        }
    }
    Some((sigma0 + hi * h, far))
}

/// `d q_u / d sigma` of the state `k` on `path`: its velocity analogs along the path's
/// direction.
fn slope<S: KinState, X: crate::dims::Store>(k: &S, path: &Path<X>, u: usize) -> f64 {
    let dq = k.dq(u);
    (0..dq.len()).map(|i| dq[i] * path.delta[i]).sum::<f64>() / path.len
}

/// The acceleration analog beyond `f64`'s range that made a state's kinematics fail (its
/// unknown's or output's name), where that is the failure: by a length input the acceleration
/// analogs are about `1 / size²`, beyond `f64` in a mechanism below about `1e-154` in size,
/// whose positions and velocity analogs are fine.
fn acceleration_beyond_range(e: &Error) -> Option<Cow<'static, str>> {
    match e {
        Error::Domain { what, name, .. } | Error::Overflow { what, name, .. } if what.is_acceleration() => {
            Some(name.clone())
        }
        _ => None,
    }
}

/// How [`past_kink`] solves the states it judges.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Route {
    /// The kernel's kinematics: its blocks' pivots and determinant signs.
    Kinematics,
    /// The positions, and the slopes from the Jacobian (`J dq/dsigma = -dF/dsigma`): the whole
    /// column-equilibrated Jacobian's smallest pivot and determinant sign (one "block").
    Jacobian,
}

impl Route {
    /// The blocks whose determinant signs a state of this route records.
    fn blocks<K: Kernel>(self, m: &K) -> usize {
        match self {
            Route::Kinematics => m.block_count(),
            Route::Jacobian => 1,
        }
    }
}

/// What [`past_kink`] reads of a state: its positions, each unknown's slope `d q_u / d sigma`
/// along the path, its smallest pivot ratio and its determinants' signs.
#[derive(Clone)]
struct Judged<Q> {
    q: Q,
    slopes: Vec<f64>,
    pivot: f64,
    signs: DetSigns,
}

impl<Q: Store> Judged<Q> {
    /// What the kinematics `k` (solved from `guess`, of its type) say of a state on `path`.
    fn of<S: KinState, X: Store>(k: &S, guess: &Q, path: &Path<X>) -> Judged<Q> {
        let mut q = guess.clone();
        q.as_mut().copy_from_slice(k.q());
        let slopes = (0..q.as_ref().len()).map(|u| slope(k, path, u)).collect();
        Judged { q, slopes, pivot: k.health().min_pivot, signs: k.health().det_signs }
    }

    /// The unit tangent (scaled coordinates) from the slopes, with increasing sigma: as
    /// [`tangent_from_analogs`](super::curve::tangent_from_analogs) makes it from a state's
    /// analogs.
    fn tangent(&self, metric: &Metric<Q>) -> DVector<f64> {
        let n = self.slopes.len();
        let mut t = DVector::zeros(n + 1);
        for (u, s) in self.slopes.iter().enumerate() {
            t[u] = s * metric.sigma / metric.unit[u];
        }
        t[n] = 1.0;
        let norm = t.norm();
        t / norm
    }
}

/// The state at `x` solved from `guess` by `route`; `None` where it cannot be solved (or its
/// Jacobian is singular or not finite).
fn judged<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    x: &X<K>,
    guess: &Q<K>,
    cfg: &NewtonConfig,
    route: Route,
) -> Option<Judged<Q<K>>> {
    let n = m.dims().n();
    match route {
        Route::Kinematics => m.kinematics(x, guess, cfg).ok().map(|k| Judged::of(&k, guess, path)),
        Route::Jacobian => {
            let q = m.positions(x, guess, cfg).ok()?;
            let jac = m.jacobian(x, &q);
            let (det, pivot) = m.dims().equilibrated(&jac);
            let mut signs = DetSigns::default();
            if det < 0.0 {
                signs.set_negative(0);
            }
            let a = DMatrix::from_fn(n, n, |e, u| jac.j(e, u));
            let rhs = -DVector::from_vec(f_sigma(&jac, path, n));
            let slopes = a.lu().solve(&rhs)?;
            slopes.iter().all(|v| v.is_finite()).then(|| Judged {
                q,
                slopes: slopes.iter().copied().collect(),
                pivot,
                signs,
            })
        }
    }
}
