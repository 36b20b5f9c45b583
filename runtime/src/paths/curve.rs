//! Pseudo-arclength continuation of the solution curve `f(q, x(sigma)) = 0` along a straight
//! path in input space, `x(sigma) = from + sigma * u` (`u` the unit direction, `sigma` in input
//! units). The curve is followed in `y = (q, sigma)`, so it passes through limit positions
//! (folds, where the input reverses) where a sweep in the input cannot.
//!
//! **Unit-free.** Arclength, tangents and the corrector's tests are measured in scaled
//! coordinates `z = (q_u / unit_u, sigma / unit_sigma)` with the units the generated code gives
//! every unknown and input ([`Jac::unit`](crate::Jac::unit), [`Jac::input_unit`](crate::Jac::input_unit): one radian for an angle, the
//! mechanism's size for a length), fixed at the start of a trace (`Metric`). A mechanism in
//! metres, millimetres or micrometres is therefore followed with the same steps and its events
//! are located at the same inputs; angles and lengths never mix in one norm.
//!
//! These routines run only on the rare paths (locating an event, tracing a closed curve), so
//! they use nalgebra's dynamic matrices for the `(N + 1)`-sized bordered systems.

use crate::dims::{Dims, JacState, KinState, Store};
use crate::events::{BlockInfo, Event, EventKind};
use crate::mechanism::kernel::{D, Kernel, Q, X};
use crate::solvers::newton::NewtonConfig;
use nalgebra::{DMatrix, DVector};

/// A straight path in input space.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Path<X> {
    pub from: X,
    /// The end, kept as given: the input at `tau = 1` (`from + (to - from)` may round away
    /// from it, far away where `|from|` is much larger than `|to|`).
    pub to: X,
    /// `to - from`.
    pub delta: X,
    /// `|to - from|` (Euclidean).
    pub len: f64,
}

impl<X: Store> Path<X> {
    pub fn new(from: X, to: X) -> Self {
        let mut delta = from.clone();
        let ni = delta.as_ref().len();
        for i in 0..ni {
            delta[i] = to[i] - from[i];
        }
        // Scaled so that a range near the largest `f64` does not overflow its length.
        let big = delta.as_ref().iter().fold(0.0f64, |m, d| m.max(d.abs()));
        let len = if big > 0.0 && big.is_finite() {
            big * delta.as_ref().iter().map(|d| (d / big) * (d / big)).sum::<f64>().sqrt()
        } else {
            big
        };
        Path { from, to, delta, len }
    }

    /// Input at fraction `tau` of the path: exactly `from` at 0 and `to` at 1.
    pub fn at_tau(&self, tau: f64) -> X {
        if tau == 1.0 {
            return self.to.clone();
        }
        let mut x = self.from.clone();
        self.at_tau_into(tau, &mut x);
        x
    }

    /// Input at fraction `tau` of the path, into `x` (a sweep's step: no allocation): `from +
    /// tau (to - from)`, which at `tau = 1` may round off `to` (a sweep's last sample, see
    /// [`SweepOf::new`](crate::SweepOf)): a test of `tau` here costs every sweep sample five
    /// instructions or more, measured.
    #[inline(always)]
    pub fn at_tau_into(&self, tau: f64, x: &mut X) {
        let ni = x.as_ref().len();
        for i in 0..ni {
            x[i] = self.from[i] + tau * self.delta[i];
        }
    }

    /// Input at distance `sigma` along the path.
    pub fn at_sigma(&self, sigma: f64) -> X {
        self.at_tau(sigma / self.len)
    }

    /// How far apart the path's representable inputs lie near `sigma`, in the path coordinate:
    /// the largest of the inputs' distances between neighbouring doubles there, each over the
    /// input's share of the path. A point of the path is known to no better than this (about
    /// `2e-16` of the path's length per radian for inputs near one, `6e-11` at fifty thousand
    /// turns).
    pub fn rounding(&self, sigma: f64) -> f64 {
        let x = self.at_sigma(sigma);
        x.as_ref().iter().zip(self.delta.as_ref()).fold(0.0f64, |r, (&xi, &di)| {
            let apart = xi.abs().next_up() - xi.abs();
            if di != 0.0 { r.max(apart * self.len / di.abs()) } else { r }
        })
    }

    /// The first input whose doubles at `x` are farther apart than [`COARSE_INPUT`] of its
    /// change over a step (`step(delta_i)`, from the path's change `delta_i` of it), with that distance
    /// and that change: there the steps' inputs are rounded by much more than the predictions
    /// and tolerances allow for (an input near `1e17` is a double 16 apart), and a failure is the
    /// inputs', not the mechanism's. Looked at where a sweep or a trace has failed.
    #[cold]
    pub fn coarse_input(&self, x: &[f64], step: impl Fn(f64) -> f64) -> Option<(usize, f64, f64)> {
        x.iter().zip(self.delta.as_ref()).enumerate().find_map(|(i, (&xi, &di))| {
            let apart = xi.abs().next_up() - xi.abs();
            let change = step(di).abs();
            (change > 0.0 && apart > COARSE_INPUT * change).then_some((i, apart, change))
        })
    }
}

/// The largest spacing of an input's doubles, as a fraction of its change over a step, at
/// which a path's steps are solved: beyond it the steps' inputs round by more than the
/// predictions and tolerances allow for, and a failure is blamed on the inputs.
pub(crate) const COARSE_INPUT: f64 = 1e-6;

/// A unit that is not positive and finite counts as one.
pub(crate) fn sane(unit: f64) -> f64 {
    if unit > 0.0 && unit < f64::INFINITY { unit } else { 1.0 }
}

/// The units of the continuation's coordinates: `q_u` is measured in `unit[u]`, the path
/// coordinate `sigma` in `sigma`. Fixed for a whole trace, so that one arclength is used
/// throughout.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Metric<Q> {
    pub unit: Q,
    pub sigma: f64,
    /// The path's length measured in input units, `|delta ./ input_unit|` (`0` for a path of no
    /// length): how far the path goes in the inputs' natural scale (radians for angle inputs).
    pub input_len: f64,
}

impl<Q: Store> Metric<Q> {
    /// The units at `(x, q)` on `path`: the generated units of the unknowns, and for `sigma`
    /// the path's length over its length measured in input units (the input's own unit for a
    /// single input).
    pub fn at<K>(m: &K, path: &Path<X<K>>, x: &X<K>, q: &Q) -> Self
    where
        K: Kernel,
        D<K>: Dims<Q = Q>,
    {
        let d = m.dims();
        let jac = m.jacobian(x, q);
        let mut unit = q.clone();
        for u in 0..d.n() {
            unit[u] = sane(jac.unit(u));
        }
        // `|delta ./ input_unit|`, scaled like `Path::new` so that it cannot overflow.
        let mut scaled = d.x();
        for i in 0..d.ni() {
            scaled[i] = path.delta[i] / sane(jac.input_unit(i));
        }
        let scaled = scaled.as_ref();
        let big = scaled.iter().fold(0.0f64, |m, d| m.max(d.abs()));
        // Infinite where a component overflows (a unit far below the path's length).
        let norm = if big > 0.0 && big.is_finite() {
            big * scaled.iter().map(|d| (d / big) * (d / big)).sum::<f64>().sqrt()
        } else {
            big
        };
        let sigma = if norm > 0.0 { sane(path.len / norm) } else { 1.0 };
        Metric { unit, sigma, input_len: norm }
    }
}

/// The event of kind `kind` at curve point `p` of `path`.
pub(crate) fn event_at<Q: Store, X: Store>(
    kind: EventKind,
    path: &Path<X>,
    p: &CurvePoint<Q>,
    block: Option<(usize, BlockInfo)>,
) -> Event {
    let tau = p.sigma / path.len;
    Event { kind, x: path.at_tau(tau).as_ref().to_vec(), tau, q: p.q.as_ref().to_vec(), block }
}

/// Derivative of `f` along the path per unit `sigma`.
pub(crate) fn f_sigma<J: JacState, X: Store>(jac: &J, path: &Path<X>, n: usize) -> Vec<f64> {
    let ni = path.delta.as_ref().len();
    (0..n).map(|e| (0..ni).map(|i| jac.fx(e, i) * path.delta[i]).sum::<f64>() / path.len).collect()
}

/// The scaled residual of a full system (continuation, event location): each residual relative
/// to the larger of its generated row magnitude `scale` (see `Magnitudes`) and
/// `sum_j |J_ij| unit_j + |fs_i| unit_sigma`, where `fs` holds the row's derivative along the
/// input path and the units are the continuation's (`metric`); the largest of them (NaN when
/// one is NaN). The second keeps the test attainable where every term of a row vanishes at a
/// branch point (e.g. `s^2 - x^2` at the origin), where the continuation's absolute step test
/// stops before a residual relative to the vanishing magnitude is reached.
fn residual_of<J: JacState, Q: Store>(jac: &J, fs: &[f64], metric: &Metric<Q>) -> f64 {
    let n = fs.len();
    let (mut m, mut sum) = (0.0f64, -0.0f64);
    for r in 0..n {
        let s = row_scale(jac, fs, metric, r);
        let a = jac.f(r).abs();
        let x = if a == 0.0 { 0.0 } else { a / s };
        m = if x > m { x } else { m };
        sum += x;
    }
    if sum.is_nan() { f64::NAN } else { m }
}

/// The magnitude [`residual_of`] measures row `r` against: the larger of its generated
/// magnitude and `sum_j |J_rj| unit_j + |fs_r| unit_sigma` (the latter where the former is
/// NaN). The derivatives are taken per unit of the continuation's coordinates, as in the
/// bordered system, so that both are in the row's unit: by a length unknown a loop's derivative
/// is about one whatever the mechanism's size, and unscaled it outweighed the magnitude of a
/// small mechanism's row (2e-10 links: every residual judged against 1, points 1e-8 off the
/// curve).
fn row_scale<J: JacState, Q: Store>(jac: &J, fs: &[f64], metric: &Metric<Q>, r: usize) -> f64 {
    let derivatives =
        (0..fs.len()).map(|u| (jac.j(r, u) * metric.unit[u]).abs()).sum::<f64>() + (fs[r] * metric.sigma).abs();
    let scale = jac.scale(r);
    // NaN in `scale` leaves `derivatives`.
    if scale > derivatives { scale } else { derivatives }
}

/// The residual that the inputs' rounding alone leaves at a point, in [`residual_of`]'s
/// scaling: each row's rate along the path times `rounding`, the distance between the path's
/// neighbouring inputs there ([`Path::rounding`]). Far out along a path (a hundred thousand
/// turns: doubles 1e-10 apart) it exceeds the default tolerance, and no point of the
/// continuation's plane meets that: its steps failed past a crossing.
fn rounding_residual<J: JacState, Q: Store>(jac: &J, fs: &[f64], metric: &Metric<Q>, rounding: f64) -> f64 {
    (0..fs.len()).fold(0.0f64, |m, r| {
        let s = row_scale(jac, fs, metric, r);
        if s > 0.0 { m.max(fs[r].abs() * rounding / s) } else { m }
    })
}

/// The most that [`arc_step`] relaxes its residual tolerance to for the inputs' rounding (a
/// million turns out, doubles 1e-9 apart, leave about 4e-11): where the inputs are coarser
/// still (near 1e15, an eighth apart), a tolerance as loose as their rounding let the
/// corrector settle anywhere near the curve, and its jitter read as limit positions.
const ROUNDING_TOL_CAP: f64 = 1e-9;

/// A point of the curve: positions and path coordinate, with its unit tangent.
#[derive(Clone, Debug)]
pub(crate) struct CurvePoint<Q> {
    pub q: Q,
    pub sigma: f64,
    /// Unit tangent in the scaled coordinates `z` (see [`Metric`]); its last component is
    /// `d (sigma / unit_sigma) / ds`.
    pub tangent: DVector<f64>,
}

impl<Q: Store> CurvePoint<Q> {
    fn n(&self) -> usize {
        self.q.as_ref().len()
    }

    /// The point in scaled coordinates.
    pub fn z(&self, metric: &Metric<Q>) -> DVector<f64> {
        let n = self.n();
        DVector::from_iterator(n + 1, (0..n).map(|u| self.q[u] / metric.unit[u]).chain([self.sigma / metric.sigma]))
    }

    /// The rate of the path coordinate along the curve: positive while the input advances,
    /// zero at a limit position.
    pub fn dsigma(&self) -> f64 {
        self.tangent[self.n()]
    }

    /// `d q_u / d sigma` along the tangent (finite away from limit positions).
    pub fn dq_dsigma(&self, u: usize, metric: &Metric<Q>) -> f64 {
        self.tangent[u] * metric.unit[u] / (self.tangent[self.n()] * metric.sigma)
    }

    /// The positions at `sigma` predicted along the tangent: the guess of a solve at fixed
    /// input that is to stay on this branch.
    pub fn predicted(&self, sigma: f64, metric: &Metric<Q>) -> Q {
        let mut q = self.q.clone();
        for u in 0..self.n() {
            q[u] += self.dq_dsigma(u, metric) * (sigma - self.sigma);
        }
        q
    }
}

/// The physical `(q, sigma)` of scaled coordinates `z`.
fn unscale<Q: Store>(z: &DVector<f64>, metric: &Metric<Q>) -> (Q, f64) {
    let mut q = metric.unit.clone();
    let n = q.as_ref().len();
    for u in 0..n {
        q[u] = z[u] * metric.unit[u];
    }
    (q, z[n] * metric.sigma)
}

/// The bordered Jacobian in scaled coordinates (columns times their units, rows over their
/// magnitudes, so that its entries are dimensionless) with `last_row` appended, and the
/// scaled residuals `-f_e / scale_e` as the first `N` entries of the right-hand side.
fn bordered<J: JacState, Q: Store, X: Store>(
    jac: &J,
    path: &Path<X>,
    metric: &Metric<Q>,
    last_row: &DVector<f64>,
) -> (DMatrix<f64>, DVector<f64>) {
    let n = metric.unit.as_ref().len();
    let fs = f_sigma(jac, path, n);
    let mut a = DMatrix::zeros(n + 1, n + 1);
    let mut rhs = DVector::zeros(n + 1);
    for e in 0..n {
        let row = sane(jac.scale(e));
        for u in 0..n {
            a[(e, u)] = jac.j(e, u) * metric.unit[u] / row;
        }
        a[(e, n)] = fs[e] * metric.sigma / row;
        rhs[e] = -jac.f(e) / row;
    }
    for k in 0..=n {
        a[(n, k)] = last_row[k];
    }
    (a, rhs)
}

/// Unit tangent (scaled coordinates) at `(q, sigma)`, oriented like `prev`.
pub(crate) fn tangent<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    q: &Q<K>,
    sigma: f64,
    prev: &DVector<f64>,
) -> Option<DVector<f64>> {
    let n = m.dims().n();
    let jac = m.jacobian(&path.at_sigma(sigma), q);
    let (a, _) = bordered(&jac, path, metric, prev);
    let mut rhs = DVector::zeros(n + 1);
    rhs[n] = 1.0;
    let t = a.lu().solve(&rhs)?;
    let norm = t.norm();
    (norm.is_finite() && norm > 0.0).then(|| t / norm)
}

/// The unit tangent (scaled coordinates) at `(q, sigma)` where the Jacobian in the unknowns may
/// be singular but the curve is not (a limit position, where `[J, dF/dsigma]` keeps its full
/// rank and the velocity analogs do not exist): the null vector of that matrix, by SVD, its
/// path component made non-negative. With it, the ratio of that matrix's smallest singular
/// value to its largest: about zero at a branch point, where two curves meet and no single
/// tangent exists. `None` where the Jacobian is not finite.
pub(crate) fn tangent_by_null_vector<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    q: &Q<K>,
    sigma: f64,
) -> Option<(DVector<f64>, f64)> {
    let n = m.dims().n();
    let jac = m.jacobian(&path.at_sigma(sigma), q);
    // The bordered matrix with a zero last row: its right singular vector of the zero singular
    // value that row adds spans the null space of `[J, dF/dsigma]` where that has rank `n`.
    let (a, _) = bordered(&jac, path, metric, &DVector::zeros(n + 1));
    if !a.iter().all(|v| v.is_finite()) {
        return None;
    }
    let svd = a.svd(false, true);
    let v_t = svd.v_t?;
    let sv = &svd.singular_values;
    let null = sv.imin();
    let largest = sv.max();
    // The rank of `[J, dF/dsigma]`: its smallest singular value, the padded matrix's second
    // smallest.
    let rest = (0..=n).filter(|&k| k != null).map(|k| sv[k]).fold(f64::INFINITY, f64::min);
    let ratio = if largest > 0.0 { rest / largest } else { 0.0 };
    let mut t: DVector<f64> = v_t.row(null).transpose();
    if t[n] < 0.0 {
        t.neg_mut();
    }
    let norm = t.norm();
    (norm.is_finite() && norm > 0.0).then(|| (t / norm, ratio))
}

/// The tangent (scaled coordinates) at a regular point from the velocity analogs of `k`,
/// oriented with increasing sigma.
pub(crate) fn tangent_from_analogs<S: KinState, Q: Store, X: Store>(
    k: &S,
    path: &Path<X>,
    metric: &Metric<Q>,
) -> DVector<f64> {
    let n = metric.unit.as_ref().len();
    let ni = path.delta.as_ref().len();
    let mut t = DVector::zeros(n + 1);
    for u in 0..n {
        let dq = k.dq(u);
        let dq_dsigma = (0..ni).map(|i| dq[i] * path.delta[i]).sum::<f64>() / path.len;
        t[u] = dq_dsigma * metric.sigma / metric.unit[u];
    }
    t[n] = 1.0;
    let norm = t.norm();
    t / norm
}

/// One pseudo-arclength step of length `ds` (scaled coordinates) from `p`: Euler predictor
/// along the tangent, Newton corrector on `[f(q, sigma); t . (z - z_pred)] = 0`. `None` where
/// the corrector does not converge, or converges farther than [`MAX_STEP_REACH`] times `ds`
/// from `p`: the corrector's plane met the solution set elsewhere, not the curve being followed.
pub(crate) fn arc_step<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    p: &CurvePoint<Q<K>>,
    ds: f64,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<Q<K>>> {
    let n = m.dims().n();
    let z_pred = p.z(metric) + &p.tangent * ds;
    let mut z = z_pred.clone();
    // Whether a converged point lies on the step: a step along a smooth curve ends within about
    // `ds` of its start, give or take how loosely the tolerance pins a position
    // (`loose_position`): what is rejected lies radians or sizes away.
    let start = p.z(metric);
    let reach = MAX_STEP_REACH * ds.abs() + loose_position(cfg, &start);
    let on_step = |z: &DVector<f64>| (z - &start).norm() <= reach;
    // A point meeting the tolerance is corrected once more (free accuracy where Newton
    // converges quadratically, needed near singular points where the tolerance leaves the
    // position loose), then accepted the next time it meets the tolerance.
    let mut corrected = false;
    for _ in 0..cfg.max_iterations.max(8) {
        let (q, sigma) = unscale(&z, metric);
        let jac = m.jacobian(&path.at_sigma(sigma), &q);
        // Each residual relative to its row's magnitude (see `residual_of`), to the
        // tolerance or, where the inputs are coarser, to what their rounding leaves.
        let fs = f_sigma(&jac, path, n);
        let res = residual_of(&jac, &fs, metric);
        if !res.is_finite() {
            return None;
        }
        let tol = cfg
            .residual_tol
            .max((2.0 * rounding_residual(&jac, &fs, metric, path.rounding(sigma))).min(ROUNDING_TOL_CAP));
        let (a, mut g) = bordered(&jac, path, metric, &p.tangent);
        g[n] = -p.tangent.dot(&(&z - &z_pred));
        // Both tests are dimensionless: `g[N]` is a distance in scaled coordinates.
        if res <= tol && g[n].abs() <= cfg.residual_tol * (1.0 + ds.abs()) && corrected {
            return on_step(&z)
                .then(|| tangent(m, path, metric, &q, sigma, &p.tangent))
                .flatten()
                .map(|tangent| CurvePoint { q, sigma, tangent });
        }
        corrected |= res <= tol;
        let dz = a.lu().solve(&g)?;
        if !dz.iter().all(|v| v.is_finite()) {
            return None;
        }
        z += &dz;
        if dz.amax() <= cfg.step_tol * (1.0 + z.amax()) {
            let (q, sigma) = unscale(&z, metric);
            let jac = m.jacobian(&path.at_sigma(sigma), &q);
            // The step is at the rounding floor: accept a residual up to its floor.
            if residual_of(&jac, &f_sigma(&jac, path, n), metric) <= 1e3 * cfg.residual_tol.max(16.0 * f64::EPSILON) {
                return on_step(&z)
                    .then(|| tangent(m, path, metric, &q, sigma, &p.tangent))
                    .flatten()
                    .map(|tangent| CurvePoint { q, sigma, tangent });
            }
        }
    }
    None
}

/// How loosely the corrector's tolerance pins a curve point near `z` (scaled coordinates): near
/// a singular position a residual `tol` leaves it free along the nearly singular direction by
/// about `sqrt(tol / k)` for the residual's curvature `k` there (a five-bar with both arms
/// stretched at once: points 5e-6 apart at one input and the default `1e-12`). A thousand
/// times `sqrt(tol)`, but at most a hundredth of the scaled unit (the mechanism's size), and
/// the step tolerance's share: what lies farther is radians or sizes away.
pub(crate) fn loose_position(cfg: &NewtonConfig, z: &DVector<f64>) -> f64 {
    (1e3 * cfg.residual_tol.max(f64::EPSILON).sqrt()).min(1e-2) + cfg.step_tol * (1.0 + z.amax())
}

/// How far from its start, in multiples of its length, an [`arc_step`] may end. A step that
/// follows a smooth curve ends within its length of its start (about `ds (1 + (k ds)^2 / 8)`
/// for a curvature `k`); near a branch point the corrector's plane, nearly parallel to the
/// curve's plane of the input, can meet the solution set radians away (a Grashof-equal
/// four-bar's change point, whose crossing was then bracketed at a regular position).
const MAX_STEP_REACH: f64 = 2.0;

/// Illinois (modified regula falsi) root of `g` on `[a, b]` with `g(a) g(b) <= 0`.
pub(crate) fn illinois(
    mut g: impl FnMut(f64) -> Option<f64>,
    mut a: f64,
    mut b: f64,
    mut ga: f64,
    mut gb: f64,
    tol: f64,
) -> Option<f64> {
    if ga == 0.0 {
        return Some(a);
    }
    if gb == 0.0 {
        return Some(b);
    }
    let mut side = 0i8;
    for _ in 0..200 {
        let mut c = (a * gb - b * ga) / (gb - ga);
        if !c.is_finite() || c <= a.min(b) || c >= a.max(b) {
            c = 0.5 * (a + b);
        }
        let gc = g(c)?;
        if gc == 0.0 || (b - a).abs() <= tol {
            return Some(c);
        }
        if (gc > 0.0) == (gb > 0.0) {
            b = c;
            gb = gc;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            ga = gc;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
        if (b - a).abs() <= tol {
            return Some(0.5 * (a + b));
        }
    }
    Some(0.5 * (a + b))
}

/// The limit position between `base` (arclength `s = 0`) and the curve point `ds` further on,
/// whose `d sigma / ds` is `dsigma_end` (of the other sign than at `base`): the root of
/// `d sigma / ds` in `s`.
pub(crate) fn locate_fold<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    base: &CurvePoint<Q<K>>,
    ds: f64,
    dsigma_end: f64,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<Q<K>>> {
    let s = illinois(
        |s| arc_step(m, path, metric, base, s, cfg).map(|p| p.dsigma()),
        0.0,
        ds,
        base.dsigma(),
        dsigma_end,
        1e-15 * (1.0 + ds),
    )?;
    arc_step(m, path, metric, base, s, cfg)
}

/// Signed determinant of the column-equilibrated full Jacobian at `(x, q)`.
pub(crate) fn signed_det<K: Kernel>(m: &K, x: &X<K>, q: &Q<K>) -> f64 {
    m.dims().equilibrated(&m.jacobian(x, q)).0
}

/// Smallest pivot of the column-equilibrated full Jacobian at `(x, q)`.
pub(crate) fn pivot_at<K: Kernel>(m: &K, x: &X<K>, q: &Q<K>) -> f64 {
    m.dims().equilibrated(&m.jacobian(x, q)).1
}

/// How near `(x, q)` is to a singular position: the smallest singular value of the
/// column-equilibrated full Jacobian over its largest (0 where it is singular or not finite).
/// Unlike the smallest pivot ([`pivot_at`]), which partial pivoting can leave many times the
/// distance to singularity where a nearly zero row meets the rows of later blocks (a Watt
/// six-bar's four-bar at its change point: a pivot ratio of 2e-6 a hundred-millionth of the
/// input from it, a singular value ratio of 3e-8), it measures that distance whatever the
/// order of the elimination. An SVD: asked on the rare paths, and by a trace only where the
/// pivot is already small.
pub(crate) fn singular_ratio_at<K: Kernel>(m: &K, x: &X<K>, q: &Q<K>) -> f64 {
    let n = m.dims().n();
    let jac = m.jacobian(x, q);
    let (lo, hi) = singular_range(DMatrix::from_fn(n, n, |e, u| jac.j(e, u)), &[]);
    let ratio = lo / hi;
    if ratio.is_finite() { ratio } else { 0.0 }
}

/// The smallest and largest singular values of `a` with its rows over `rows` (the equations'
/// magnitudes; none where `rows` is empty) and each column over its largest entry. A matrix of
/// no rows or no columns (a mechanism without unknowns: its Jacobian is 0 x 0) has no singular
/// direction: `(1, 1)`, where the SVD panicked ("Cannot compute the SVD of an empty matrix",
/// `kinloop trace` of a declaration of outputs alone).
pub(crate) fn singular_range(mut a: DMatrix<f64>, rows: &[f64]) -> (f64, f64) {
    if a.is_empty() {
        return (1.0, 1.0);
    }
    for (e, &row) in rows.iter().enumerate() {
        a.row_mut(e).unscale_mut(if row > 0.0 && row.is_finite() { row } else { 1.0 });
    }
    for c in 0..a.ncols() {
        let big = a.column(c).amax();
        if big > 0.0 {
            a.column_mut(c).unscale_mut(big);
        }
    }
    let sv = a.svd(false, false).singular_values;
    (sv.min(), sv.max())
}
