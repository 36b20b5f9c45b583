//! Pseudo-arclength continuation of the solution curve `f(q, x(sigma)) = 0` along a straight
//! path in input space, `x(sigma) = from + sigma * u` (`u` the unit direction, `sigma` in input
//! units). The curve is followed in `y = (q, sigma)`, so it passes through limit positions
//! (folds, where the input reverses) where a sweep in the input cannot.
//!
//! These routines run only on the rare paths (locating an event, tracing a closed curve), so
//! they use nalgebra's dynamic matrices for the `(N + 1)`-sized bordered systems.

use crate::events::{BlockInfo, Event, EventKind};
use crate::kin::Jac;
use crate::mechanism::Mechanism;
use crate::solvers::lu::Lu;
use crate::solvers::newton::{NewtonConfig, system_residual};
use nalgebra::{DMatrix, DVector};

/// A straight path in input space.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Path<const NI: usize> {
    pub from: [f64; NI],
    /// `to - from`.
    pub delta: [f64; NI],
    /// `|to - from|` (Euclidean).
    pub len: f64,
}

impl<const NI: usize> Path<NI> {
    pub fn new(from: [f64; NI], to: [f64; NI]) -> Self {
        let mut delta = [0.0; NI];
        for i in 0..NI {
            delta[i] = to[i] - from[i];
        }
        // Scaled so that a range near the largest `f64` does not overflow its length.
        let big = delta.iter().fold(0.0f64, |m, d| m.max(d.abs()));
        let len = if big > 0.0 && big.is_finite() {
            big * delta.iter().map(|d| (d / big) * (d / big)).sum::<f64>().sqrt()
        } else {
            big
        };
        Path { from, delta, len }
    }

    /// Input at fraction `tau` of the path.
    pub fn at_tau(&self, tau: f64) -> [f64; NI] {
        let mut x = self.from;
        for i in 0..NI {
            x[i] += tau * self.delta[i];
        }
        x
    }

    /// Input at distance `sigma` along the path.
    pub fn at_sigma(&self, sigma: f64) -> [f64; NI] {
        self.at_tau(sigma / self.len)
    }
}

/// The event of kind `kind` at curve point `p` of `path`.
pub(crate) fn event_at<const N: usize, const NI: usize>(
    kind: EventKind,
    path: &Path<NI>,
    p: &CurvePoint<N>,
    block: Option<(usize, BlockInfo)>,
) -> Event {
    let tau = p.sigma / path.len;
    Event { kind, x: path.at_tau(tau).to_vec(), tau, q: p.q.to_vec(), block }
}

/// Derivative of `f` along the path per unit `sigma`.
fn f_sigma<const N: usize, const NI: usize>(jac: &Jac<N, NI>, path: &Path<NI>) -> [f64; N] {
    let mut out = [0.0; N];
    for e in 0..N {
        out[e] = (0..NI).map(|i| jac.fx[e][i] * path.delta[i]).sum::<f64>() / path.len;
    }
    out
}

/// A point of the curve: positions and path coordinate, with its unit tangent.
#[derive(Clone, Debug)]
pub(crate) struct CurvePoint<const N: usize> {
    pub q: [f64; N],
    pub sigma: f64,
    /// Unit tangent in `(q, sigma)`; its last component is `d sigma / ds`.
    pub tangent: DVector<f64>,
}

impl<const N: usize> CurvePoint<N> {
    pub fn y(&self) -> DVector<f64> {
        DVector::from_iterator(N + 1, self.q.iter().copied().chain([self.sigma]))
    }

    /// `d sigma / ds`: positive while the input advances, zero at a limit position.
    pub fn dsigma(&self) -> f64 {
        self.tangent[N]
    }
}

fn bordered<const N: usize, const NI: usize>(
    jac: &Jac<N, NI>,
    path: &Path<NI>,
    last_row: &DVector<f64>,
) -> DMatrix<f64> {
    let fs = f_sigma(jac, path);
    let mut a = DMatrix::zeros(N + 1, N + 1);
    for e in 0..N {
        for u in 0..N {
            a[(e, u)] = jac.j[e][u];
        }
        a[(e, N)] = fs[e];
    }
    for k in 0..=N {
        a[(N, k)] = last_row[k];
    }
    a
}

/// Unit tangent at `(q, sigma)`, oriented like `prev`.
pub(crate) fn tangent<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    path: &Path<NI>,
    q: &[f64; N],
    sigma: f64,
    prev: &DVector<f64>,
) -> Option<DVector<f64>>
where
    M: Mechanism<N, NI, NO>,
{
    let jac = m.jacobian_flat(&path.at_sigma(sigma), q);
    let a = bordered(&jac, path, prev);
    let mut rhs = DVector::zeros(N + 1);
    rhs[N] = 1.0;
    let t = a.lu().solve(&rhs)?;
    let norm = t.norm();
    (norm.is_finite() && norm > 0.0).then(|| t / norm)
}

/// The tangent at a regular point from the velocity analogs, oriented with increasing sigma.
pub(crate) fn tangent_from_analogs<const N: usize, const NI: usize>(
    dq: &[[f64; NI]; N],
    path: &Path<NI>,
) -> DVector<f64> {
    let mut t = DVector::zeros(N + 1);
    for u in 0..N {
        t[u] = (0..NI).map(|i| dq[u][i] * path.delta[i]).sum::<f64>() / path.len;
    }
    t[N] = 1.0;
    let n = t.norm();
    t / n
}

/// One pseudo-arclength step of length `ds` from `p`: Euler predictor along the tangent, Newton
/// corrector on `[f(q, sigma); t . (y - y_pred)] = 0`.
pub(crate) fn arc_step<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    path: &Path<NI>,
    p: &CurvePoint<N>,
    ds: f64,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<N>>
where
    M: Mechanism<N, NI, NO>,
{
    let y_pred = p.y() + &p.tangent * ds;
    let mut y = y_pred.clone();
    // A point meeting the tolerance is corrected once more (free accuracy where Newton
    // converges quadratically, needed near singular points where the tolerance leaves the
    // position loose), then accepted the next time it meets the tolerance.
    let mut corrected = false;
    for _ in 0..cfg.max_iterations.max(8) {
        let mut q = [0.0; N];
        q.copy_from_slice(&y.as_slice()[..N]);
        let sigma = y[N];
        let jac = m.jacobian_flat(&path.at_sigma(sigma), &q);
        // Each residual relative to its row's magnitude (see `system_residual`).
        let res = system_residual(&jac.f, &jac.j, &f_sigma(&jac, path), &jac.scale);
        if !res.is_finite() {
            return None;
        }
        let mut g = DVector::zeros(N + 1);
        for e in 0..N {
            g[e] = -jac.f[e];
        }
        g[N] = -p.tangent.dot(&(&y - &y_pred));
        if res <= cfg.residual_tol && g[N].abs() <= cfg.residual_tol * (1.0 + ds.abs()) && corrected {
            let tangent = tangent(m, path, &q, sigma, &p.tangent)?;
            return Some(CurvePoint { q, sigma, tangent });
        }
        corrected |= res <= cfg.residual_tol;
        let a = bordered(&jac, path, &p.tangent);
        let dy = a.lu().solve(&g)?;
        if !dy.iter().all(|v| v.is_finite()) {
            return None;
        }
        y += &dy;
        if dy.amax() <= cfg.step_tol * (1.0 + y.amax()) {
            let mut q = [0.0; N];
            q.copy_from_slice(&y.as_slice()[..N]);
            let jac = m.jacobian_flat(&path.at_sigma(y[N]), &q);
            // The step is at the rounding floor: accept a residual up to its floor.
            if system_residual(&jac.f, &jac.j, &f_sigma(&jac, path), &jac.scale)
                <= 1e3 * cfg.residual_tol.max(16.0 * f64::EPSILON)
            {
                let tangent = tangent(m, path, &q, y[N], &p.tangent)?;
                return Some(CurvePoint { q, sigma: y[N], tangent });
            }
        }
    }
    None
}

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
fn locate_fold<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    path: &Path<NI>,
    base: &CurvePoint<N>,
    ds: f64,
    dsigma_end: f64,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<N>>
where
    M: Mechanism<N, NI, NO>,
{
    let s = illinois(
        |s| arc_step(m, path, base, s, cfg).map(|p| p.dsigma()),
        0.0,
        ds,
        base.dsigma(),
        dsigma_end,
        1e-15 * (1.0 + ds),
    )?;
    arc_step(m, path, base, s, cfg)
}

/// Whether the augmented Jacobian `[J | dF/dsigma]` at `p` has full rank `N`: its smallest
/// singular value, with rows scaled by their magnitudes and columns by their largest entry, is
/// not negligible. At a limit position `J` alone is singular and the augmented matrix is not
/// (the input cannot go on); where both are singular branches cross.
fn augmented_full_rank<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    path: &Path<NI>,
    p: &CurvePoint<N>,
) -> bool
where
    M: Mechanism<N, NI, NO>,
{
    let jac = m.jacobian_flat(&path.at_sigma(p.sigma), &p.q);
    let fs = f_sigma(&jac, path);
    let mut a = DMatrix::zeros(N, N + 1);
    for e in 0..N {
        let row = jac.scale[e];
        let row = if row > 0.0 && row.is_finite() { row } else { 1.0 };
        for u in 0..N {
            a[(e, u)] = jac.j[e][u] / row;
        }
        a[(e, N)] = fs[e] / row;
    }
    for c in 0..=N {
        let big = a.column(c).amax();
        if big > 0.0 {
            a.column_mut(c).unscale_mut(big);
        }
    }
    let sv = a.svd(false, false).singular_values;
    let (lo, hi) = (sv.min(), sv.max());
    // A fold located to about the rounding of `s` leaves a smallest singular value of order
    // one; a crossing, one of the order of the distance to it (`sqrt(eps)` at most).
    hi > 0.0 && lo > RANK_TOL * hi
}

/// Relative singular value below which the augmented Jacobian is rank deficient.
const RANK_TOL: f64 = 1e-6;

/// The point past the branch point `at` that the path tangent at `a` continues to: solved at
/// fixed input from the straight (tangent) prediction, beyond `at` by up to eight times the
/// distance from `a` to it, with the far side's determinant sign.
fn straight_past<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    path: &Path<NI>,
    a: &CurvePoint<N>,
    at: &CurvePoint<N>,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<N>>
where
    M: Mechanism<N, NI, NO>,
{
    let rate = a.dsigma();
    let gap = at.sigma - a.sigma;
    if !(rate > 0.0 && gap > 0.0) {
        return None;
    }
    let det_a = signed_det(m, &path.at_sigma(a.sigma), &a.q);
    for k in [1.0, 2.0, 4.0, 8.0] {
        let sigma = at.sigma + k * gap;
        let mut guess = a.q;
        for u in 0..N {
            guess[u] += a.tangent[u] / rate * (sigma - a.sigma);
        }
        let Ok(n) = m.kinematics_flat(&path.at_sigma(sigma), &guess, cfg) else { continue };
        if (signed_det(m, &path.at_sigma(sigma), &n.q) > 0.0) == (det_a > 0.0) {
            continue;
        }
        let tangent = tangent_from_analogs(&n.dq, path);
        return Some(CurvePoint { q: n.q, sigma, tangent });
    }
    None
}

/// What following the curve found.
pub(crate) enum Found<const N: usize> {
    /// A limit position: the input reverses here.
    Fold(CurvePoint<N>),
    /// The Jacobian's determinant changes sign here while the input keeps advancing; the second
    /// point lies just past it on the smooth continuation.
    Crossing(CurvePoint<N>, CurvePoint<N>),
}

/// Follows the curve from `start` (tangent oriented with increasing sigma) for at most
/// `max_arc` of arclength, watching for a limit position (the tangent's sigma component changing
/// sign) and for a sign change of the Jacobian determinant; locates the first one found.
pub(crate) fn trace<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    path: &Path<NI>,
    start: &CurvePoint<N>,
    ds0: f64,
    max_arc: f64,
    cfg: &NewtonConfig,
) -> Option<Found<N>>
where
    M: Mechanism<N, NI, NO>,
{
    if !(ds0 > 0.0 && ds0.is_finite() && max_arc.is_finite()) {
        return None;
    }
    let det_at = |p: &CurvePoint<N>| signed_det(m, &path.at_sigma(p.sigma), &p.q);
    let mut a = start.clone();
    let mut det_a = det_at(&a);
    let mut ds = ds0;
    let mut walked = 0.0;
    while walked < max_arc {
        // A step whose tangent turns sharply has left the curve being followed: at a branch
        // point (e.g. two coincident joints) the corrector can land on a crossing curve, along
        // which the input may not move at all. A smaller step stays on the curve; a larger one
        // later jumps the branch point onto the curve's smooth continuation.
        let Some(b) = arc_step(m, path, &a, ds, cfg).filter(|b| a.tangent.dot(&b.tangent) >= MIN_TURN_COS) else {
            ds *= 0.5;
            if ds < 1e-14 * (1.0 + max_arc) {
                return None;
            }
            continue;
        };
        let det_b = det_at(&b);
        if b.dsigma() <= 0.0 {
            let fold = locate_fold(m, path, &a, ds, b.dsigma(), cfg)?;
            // Where `[J | dF/dsigma]` loses rank too, the input is not stopped: several
            // branches meet (e.g. two coincident joints), and the one the path tangent
            // continues goes on.
            if !augmented_full_rank(m, path, &fold) {
                return straight_past(m, path, &a, &fold, cfg).map(|past| Found::Crossing(fold, past));
            }
            return Some(Found::Fold(fold));
        }
        if (det_a > 0.0) != (det_b > 0.0) && det_a != 0.0 {
            // Near a crossing the bordered system is itself nearly singular and a corrector may
            // fail: the root search then settles for the bracket it has.
            let base = a.clone();
            let (mut lo, mut hi) = (0.0, ds);
            let s = illinois(
                |s| {
                    let g = arc_step(m, path, &base, s, cfg).map(|p| det_at(&p));
                    if let Some(v) = g {
                        if (v > 0.0) == (det_a > 0.0) { lo = s } else { hi = s }
                    }
                    g
                },
                0.0,
                ds,
                det_a,
                det_b,
                1e-15 * (1.0 + ds),
            )
            .unwrap_or(0.5 * (lo + hi));
            let at = arc_step(m, path, &base, s, cfg).unwrap_or_else(|| b.clone());
            return Some(Found::Crossing(at, b));
        }
        walked += ds;
        a = b;
        det_a = det_b;
        ds = (ds * 1.5).min(max_arc);
    }
    None
}

/// Smallest cosine of the angle between the unit tangents at the two ends of an accepted
/// continuation step (about 26 degrees): a smooth curve turns less over a step small against its
/// radius of curvature, a step landing on another curve through a branch point turns more.
const MIN_TURN_COS: f64 = 0.9;

/// Signed determinant of the column-equilibrated full Jacobian at `(x, q)`.
pub(crate) fn signed_det<M, const N: usize, const NI: usize, const NO: usize>(m: &M, x: &[f64; NI], q: &[f64; N]) -> f64
where
    M: Mechanism<N, NI, NO>,
{
    equilibrated(m, x, q).det()
}

/// Smallest pivot of the column-equilibrated full Jacobian at `(x, q)`.
pub(crate) fn pivot_at<M, const N: usize, const NI: usize, const NO: usize>(m: &M, x: &[f64; NI], q: &[f64; N]) -> f64
where
    M: Mechanism<N, NI, NO>,
{
    equilibrated(m, x, q).pivot_ratio()
}

fn equilibrated<M, const N: usize, const NI: usize, const NO: usize>(m: &M, x: &[f64; NI], q: &[f64; N]) -> Lu<N>
where
    M: Mechanism<N, NI, NO>,
{
    let jac = m.jacobian_flat(x, q);
    let mut scale = [0.0f64; N];
    for row in &jac.j {
        for u in 0..N {
            scale[u] = scale[u].max(row[u].abs());
        }
    }
    Lu::<N>::factor_cols(&jac.j, scale)
}

/// One point of a traced solution curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TracedPoint<const N: usize, const NI: usize> {
    /// Input values.
    pub x: [f64; NI],
    /// Positions of the unknowns.
    pub q: [f64; N],
    /// `d sigma / ds`: positive while the input advances along the path, negative after a limit
    /// position reversed it.
    pub input_rate: f64,
}

/// A solution curve traced by pseudo-arclength continuation.
#[derive(Clone, Debug, PartialEq)]
pub struct Traced<const N: usize, const NI: usize> {
    /// Points along the curve, about `ds` apart.
    pub points: Vec<TracedPoint<N, NI>>,
    /// The limit positions passed (where the input reversed), located precisely.
    pub folds: Vec<Event>,
    /// The curve closed on itself (it came back to its first point).
    pub closed: bool,
}

/// Traces the whole solution curve through `guess` at input `from`, moving first towards `to`,
/// by pseudo-arclength continuation in `(q, input)`: unlike a sweep it passes limit positions,
/// where the input reverses, so a mechanism whose input cannot make a full turn (a non-Grashof
/// four-bar driven by a rocking link) yields its complete closed curve. Stops when the curve
/// closes, leaves the segment between `from - (to - from)` and `to`, or after `max_points`.
/// Allocates (it returns a `Vec`); use [`Sweep`](crate::Sweep) in hot loops.
pub fn trace_curve<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    from: [f64; NI],
    to: [f64; NI],
    guess: [f64; N],
    ds: f64,
    max_points: usize,
    cfg: &NewtonConfig,
) -> Result<Traced<N, NI>, crate::Error>
where
    M: Mechanism<N, NI, NO>,
{
    cfg.validate()?;
    let path = Path::new(from, to);
    if !path.len.is_finite() || path.len.is_nan() || path.len <= 0.0 || ds.is_nan() || ds <= 0.0 || !ds.is_finite() {
        return Err(crate::Error::InvalidArgument(
            "trace_curve needs `to` different from `from` and a positive, finite `ds`".into(),
        ));
    }
    let k0 = m.kinematics_flat(&from, &guess, cfg)?;
    let start = CurvePoint { q: k0.q, sigma: 0.0, tangent: tangent_from_analogs(&k0.dq, &path) };
    let start_y = start.y();
    let point = |p: &CurvePoint<N>| TracedPoint { x: path.at_sigma(p.sigma), q: p.q, input_rate: p.dsigma() };
    let mut out = Traced { points: vec![point(&start)], folds: Vec::new(), closed: false };
    let mut p = start;
    let mut walked = 0.0;
    let mut step = ds;
    while out.points.len() < max_points {
        let Some(next) = arc_step(m, &path, &p, step, cfg) else {
            step *= 0.5;
            if step < ds * 1e-6 {
                return Err(crate::Error::Branch {
                    message: "pseudo-arclength continuation cannot proceed (the curve bifurcates or ends here)".into(),
                    at: crate::Location::boxed(M::NAME, &M::INPUTS, &path.at_sigma(p.sigma), None),
                });
            }
            continue;
        };
        if (p.dsigma() > 0.0) != (next.dsigma() > 0.0)
            && let Some(f) = locate_fold(m, &path, &p, step, next.dsigma(), cfg)
        {
            out.folds.push(event_at(EventKind::LimitPosition, &path, &f, None));
        }
        walked += step;
        let back = (next.y() - &start_y).norm();
        p = next;
        if p.sigma > path.len * (1.0 + 1e-12) || p.sigma < -path.len * (1.0 + 1e-12) {
            break;
        }
        if walked > 3.0 * ds && back < 0.75 * ds {
            out.closed = true;
            break;
        }
        out.points.push(point(&p));
        step = ds;
    }
    Ok(out)
}
