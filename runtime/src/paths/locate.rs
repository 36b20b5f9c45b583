//! Following the solution curve from where a sweep's step could not be made to the event that
//! stopped it ([`trace`]): a limit position (the input reverses, [`Found::Fold`]), located as the
//! root of the input's rate along the curve, or a singular crossing (a block's determinant
//! changes sign while the input advances, [`Found::Crossing`]), located as the root of the
//! determinant and then again from the well-conditioned positions on both sides
//! ([`crossing`](super::crossing)). Where several branches meet (coincident joints, several
//! blocks folding at once) the rank of the augmented Jacobian and of each block's tell a
//! crossing from a fold.
//!
//! Built on the continuation's primitives ([`curve`](super::curve)); run only where a sweep
//! diagnoses a failed step, so it uses nalgebra's dynamic matrices.

use super::crossing::refine;
use super::curve::{
    CurvePoint, Metric, Path, arc_step, f_sigma, illinois, locate_fold, pivot_at, signed_det, singular_range,
    tangent_from_analogs,
};
use crate::dims::{Dims, JacState, KinState, Store};
use crate::mechanism::kernel::{Kernel, Q, X};
use crate::solvers::newton::NewtonConfig;
use nalgebra::{DMatrix, DVector};

/// Whether the augmented Jacobian `[J | dF/dsigma]` at `p` has full rank `N`: its smallest
/// singular value, with rows scaled by their magnitudes and columns by their largest entry, is
/// not negligible. At a limit position `J` alone is singular and the augmented matrix is not
/// (the input cannot go on); where both are singular branches cross.
fn augmented_full_rank<K: Kernel>(m: &K, path: &Path<X<K>>, p: &CurvePoint<Q<K>>) -> bool {
    let n = m.dims().n();
    // No unknowns: no rows, rank 0 is full (and an SVD of the empty matrix panics).
    if n == 0 {
        return true;
    }
    let jac = m.jacobian(&path.at_sigma(p.sigma), &p.q);
    let fs = f_sigma(&jac, path, n);
    let mut a = DMatrix::zeros(n, n + 1);
    for e in 0..n {
        let row = jac.scale(e);
        let row = if row > 0.0 && row.is_finite() { row } else { 1.0 };
        for u in 0..n {
            a[(e, u)] = jac.j(e, u) / row;
        }
        a[(e, n)] = fs[e] / row;
    }
    for c in 0..=n {
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

/// Whether one block of the decomposition is at a limit position of its own at `p`: the first
/// block (in solve order) whose Jacobian is singular there has a full-rank Jacobian augmented by
/// its equations' rate along the path (the path's own and, through the blocks solved before it,
/// theirs), so that block, and with it the input path, cannot advance. Where several blocks fold
/// at once (a five-bar driven by its end effector to where both arms stretch) the whole system's
/// augmented Jacobian loses rank as at a crossing, yet no branch goes on. `false` where the
/// blocks cannot be told from the names (a hand-written mechanism's) or no block folds.
pub(crate) fn block_folds<K: Kernel>(m: &K, path: &Path<X<K>>, p: &CurvePoint<Q<K>>) -> bool {
    let jac = m.jacobian(&path.at_sigma(p.sigma), &p.q);
    let fs = f_sigma(&jac, path, m.dims().n());
    // The rows and columns of the blocks solved so far.
    let (mut rows, mut cols) = (Vec::new(), Vec::new());
    for b in 0..m.block_count() {
        let Some((own_rows, own_cols)) = m.block_rows_cols(b) else { return false };
        if own_rows.len() != own_cols.len() || own_rows.is_empty() {
            return false;
        }
        let k = own_rows.len();
        let a = DMatrix::from_fn(k, k, |i, j| jac.j(own_rows[i], own_cols[j]));
        let scale: Vec<f64> = own_rows.iter().map(|&e| jac.scale(e)).collect();
        let (lo, hi) = singular_range(a.clone(), &scale);
        if hi > 0.0 && lo > FOLD_PIVOT * hi {
            rows.extend(own_rows);
            cols.extend(own_cols);
            continue;
        }
        // The earlier blocks' rates `dq/dsigma` (regular: they were not singular).
        let earlier = DMatrix::from_fn(rows.len(), cols.len(), |i, j| jac.j(rows[i], cols[j]));
        let rhs = DVector::from_fn(rows.len(), |i, _| -fs[rows[i]]);
        let rates = if rows.is_empty() { Some(DVector::zeros(0)) } else { earlier.lu().solve(&rhs) };
        let Some(rates) = rates else { return false };
        let rate = |i: usize| {
            fs[own_rows[i]] + cols.iter().enumerate().map(|(c, &u)| jac.j(own_rows[i], u) * rates[c]).sum::<f64>()
        };
        let augmented = DMatrix::from_fn(k, k + 1, |i, j| if j < k { a[(i, j)] } else { rate(i) });
        let (lo, hi) = singular_range(augmented, &scale);
        return hi > 0.0 && lo > RANK_TOL * hi;
    }
    false
}

/// Relative smallest singular value of a block's scaled Jacobian below which [`block_folds`]
/// counts it singular: that of a limit position located to the rounding of the arclength.
const FOLD_PIVOT: f64 = 1e-6;

/// The point past the branch point `at` that the path tangent at `a` continues to: solved at
/// fixed input from the straight (tangent) prediction, beyond `at` by up to eight times the
/// distance from `a` to it, with the far side's determinant sign.
fn straight_past<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    a: &CurvePoint<Q<K>>,
    at: &CurvePoint<Q<K>>,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<Q<K>>> {
    let rate = a.dsigma();
    let gap = at.sigma - a.sigma;
    if !(rate > 0.0 && gap > 0.0) {
        return None;
    }
    let det_a = signed_det(m, &path.at_sigma(a.sigma), &a.q);
    for k in [1.0, 2.0, 4.0, 8.0] {
        let sigma = at.sigma + k * gap;
        let guess = a.predicted(sigma, metric);
        // From a prediction: a restart would find another branch.
        let Ok(n) = m.kinematics(&path.at_sigma(sigma), &guess, &cfg.with_restarts(false)) else { continue };
        let mut q = guess;
        q.as_mut().copy_from_slice(n.q());
        if (signed_det(m, &path.at_sigma(sigma), &q) > 0.0) == (det_a > 0.0) {
            continue;
        }
        let tangent = tangent_from_analogs(&n, path, metric);
        return Some(CurvePoint { q, sigma, tangent });
    }
    None
}

/// A point of the curve behind `start` (toward lower sigma, not before the path's start) where
/// the Jacobian's pivot ratio is at least `pivot` and the determinant has `start`'s sign, with
/// its tangent oriented as `start`'s and the way back to it along the curve (scaled
/// arclength), or `None`: where a sweep's last position lies within about
/// a ten-millionth of a change point, the trace from it cannot leave it (each step's tangent at
/// a position that close turns too sharply to be accepted), and one from a well-conditioned
/// point behind it passes it. The tangent's prediction where it can be trusted
/// ([`predicted_behind`]), else the curve walked back ([`walked_behind`]).
pub(crate) fn backed_off<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    start: &CurvePoint<Q<K>>,
    pivot: f64,
    cfg: &NewtonConfig,
) -> Option<(CurvePoint<Q<K>>, f64)> {
    let det_start = signed_det(m, &path.at_sigma(start.sigma), &start.q);
    predicted_behind(m, path, metric, start, det_start, pivot, cfg)
        .map(|b| {
            // A straight way: the chord.
            let way = (b.z(metric) - start.z(metric)).norm();
            (b, way)
        })
        .or_else(|| walked_behind(m, path, metric, start, det_start, pivot, cfg))
}

/// [`backed_off`]'s point on `start`'s tangent, `1e-4` to `1e-1` of the input's unit back, not
/// solved: the trace's first corrector brings it onto the curve. Only while the prediction moves
/// the positions by at most a step of the trace ([`MAX_ARC_STEP`]): near a near-kite's change
/// point the angles swing a radian over a ten-thousandth of the input, and a tangent's
/// prediction a thousandth back (eleven radians away) lay nowhere near the curve. Solved at its
/// input instead, the point is a position of the curve wherever the closed form or Newton
/// lands near the prediction, and where a slide passes within 1e-8 of its pivot (a pivot ratio
/// no tolerance resolves) the trace from there took the mirrored branch for a crossing: tried,
/// not kept.
#[allow(clippy::too_many_arguments)]
fn predicted_behind<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    start: &CurvePoint<Q<K>>,
    det_start: f64,
    pivot: f64,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<Q<K>>> {
    let n = m.dims().n();
    for back in [1e-4, 1e-3, 1e-2, 1e-1] {
        let sigma = (start.sigma - back * metric.sigma).max(0.0);
        if sigma >= start.sigma {
            return None;
        }
        let q = start.predicted(sigma, metric);
        let moved = (0..n).map(|u| ((q[u] - start.q[u]) / metric.unit[u]).abs()).fold(0.0, f64::max);
        if moved > MAX_ARC_STEP || moved.is_nan() {
            return None;
        }
        // The analogs at the prediction, for its tangent and pivot ratio.
        let Ok(k) = m.kinematics_at(&path.at_sigma(sigma), &q, cfg) else { continue };
        // On the other side of a determinant's root lies the other branch crossing there.
        let det = signed_det(m, &path.at_sigma(sigma), &q);
        if k.health().min_pivot >= pivot && (det > 0.0) == (det_start > 0.0) {
            let tangent = tangent_from_analogs(&k, path, metric);
            return Some(CurvePoint { q, sigma, tangent });
        }
    }
    None
}

/// [`backed_off`]'s point found by following the curve backward from `start`, as [`trace`]
/// follows it forward (steps from `1e-4` growing by half up to [`MAX_ARC_STEP`], each a
/// [`step_along`]), at most [`WALK_BACK_ARC`] of arclength: the first point
/// whose pivot ratio reaches `pivot`. A near-kite's branch stays nearly singular over the whole
/// swing of its folded links (two and a half radians of arclength walked back before a pivot
/// ratio of 1e-4), with the arclength walked. `None` where the walk meets a determinant's root
/// or a limit position (the input turning forward again) first, or leaves the path.
#[allow(clippy::too_many_arguments)]
fn walked_behind<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    start: &CurvePoint<Q<K>>,
    det_start: f64,
    pivot: f64,
    cfg: &NewtonConfig,
) -> Option<(CurvePoint<Q<K>>, f64)> {
    let mut p = start.clone();
    p.tangent = -p.tangent;
    let (mut ds, mut walked) = (1e-4, 0.0);
    for _ in 0..MAX_TRACE_STEPS {
        if walked >= WALK_BACK_ARC {
            break;
        }
        let Some(b) = step_along(m, path, metric, &p, ds, cfg) else {
            ds *= 0.5;
            if ds < 1e-10 {
                break;
            }
            continue;
        };
        walked += ds;
        ds = (ds * 1.5).min(MAX_ARC_STEP);
        let x = path.at_sigma(b.sigma);
        // Backward, the input decreases along the reversed tangent.
        if (signed_det(m, &x, &b.q) > 0.0) != (det_start > 0.0) || b.dsigma() >= 0.0 || b.sigma < 0.0 {
            break;
        }
        if m.kinematics_at(&x, &b.q, cfg).is_ok_and(|k| k.health().min_pivot >= pivot) {
            let mut behind = b;
            behind.tangent = -behind.tangent;
            return Some((behind, walked));
        }
        p = b;
    }
    None
}

/// One continuation step of length `ds` from `a` along the curve being followed ([`arc_step`]),
/// refused where its tangent turns farther from `a`'s than [`MIN_TURN_COS`] allows: such a step
/// has left the curve (see [`trace`]).
fn step_along<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    a: &CurvePoint<Q<K>>,
    ds: f64,
    cfg: &NewtonConfig,
) -> Option<CurvePoint<Q<K>>> {
    arc_step(m, path, metric, a, ds, cfg).filter(|b| a.tangent.dot(&b.tangent) >= MIN_TURN_COS)
}

/// Longest walk of [`walked_behind`] (scaled coordinates): a whole turn of an angle.
const WALK_BACK_ARC: f64 = std::f64::consts::TAU;

/// What following the curve found.
pub(crate) enum Found<Q> {
    /// A limit position: the input reverses here.
    Fold(CurvePoint<Q>),
    /// The Jacobian's determinant changes sign here while the input keeps advancing; the second
    /// point lies just past it on the smooth continuation.
    Crossing(CurvePoint<Q>, CurvePoint<Q>),
}

/// Follows the curve from `start` (tangent oriented with increasing sigma) as far as `reach`
/// lets it ([`Reach`]; `ds0` and the arclengths in the scaled coordinates of `metric`) and
/// [`MAX_TRACE_STEPS`] steps, watching
/// for a limit position (the tangent's sigma component changing sign) and for a sign change of
/// the Jacobian determinant; locates the first one found (a crossing from the well-conditioned
/// positions on both sides of it where it can, see [`crossing`](super::crossing)).
pub(crate) fn trace<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    start: &CurvePoint<Q<K>>,
    ds0: f64,
    reach: Reach,
    cfg: &NewtonConfig,
) -> Option<Found<Q<K>>> {
    let max_arc = reach.arc;
    if !(ds0 > 0.0 && ds0.is_finite() && max_arc.is_finite()) {
        return None;
    }
    let det_at = |p: &CurvePoint<Q<K>>| signed_det(m, &path.at_sigma(p.sigma), &p.q);
    let mut a = start.clone();
    let mut det_a = det_at(&a);
    let mut ds = ds0.min(MAX_ARC_STEP);
    let mut walked = 0.0;
    for _ in 0..MAX_TRACE_STEPS {
        if walked >= max_arc && !reach.steep_short(start, &a, metric, walked) {
            break;
        }
        // A step whose tangent turns sharply has left the curve being followed: at a branch
        // point (e.g. two coincident joints) the corrector can land on a crossing curve, along
        // which the input may not move at all. A smaller step stays on the curve; a larger one
        // later jumps the branch point onto the curve's smooth continuation.
        let Some(b) = step_along(m, path, metric, &a, ds, cfg) else {
            ds *= 0.5;
            if ds < 1e-14 * (1.0 + max_arc) {
                // The rate at which the input's advance slowed over the walk.
                let rate = (start.dsigma() - a.dsigma()) / walked;
                return fold_at_rounding(m, path, metric, &a, rate).map(Found::Fold);
            }
            continue;
        };
        let det_b = det_at(&b);
        if b.dsigma() <= 0.0 {
            let fold = locate_fold(m, path, metric, &a, ds, b.dsigma(), cfg)?;
            // Where `[J | dF/dsigma]` loses rank too, the input is not stopped: several
            // branches meet (e.g. two coincident joints), and the one the path tangent
            // continues goes on.
            if !augmented_full_rank(m, path, &fold) && !block_folds(m, path, &fold) {
                return straight_past(m, path, metric, &a, &fold, cfg).map(|past| Found::Crossing(fold, past));
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
                    let g = arc_step(m, path, metric, &base, s, cfg).map(|p| det_at(&p));
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
            // Where the corrector fails at the root itself, the nearer of the bracket's ends it
            // solved (by the determinant), not the step's far end: that stood a step beyond the
            // crossing (a near-kite's located 6.3e-4 of the input off, from behind).
            let at = arc_step(m, path, metric, &base, s, cfg).unwrap_or_else(|| {
                [lo, hi]
                    .into_iter()
                    .filter_map(|s| arc_step(m, path, metric, &base, s, cfg))
                    .min_by(|p, r| det_at(p).abs().total_cmp(&det_at(r).abs()))
                    .unwrap_or_else(|| b.clone())
            });
            // Located again from the well-conditioned positions on both sides: the root search
            // leaves a point as loose as the tolerance lets a nearly singular position be (a
            // millionth of a radian), where a crossing's augmented Jacobian keeps its rank.
            let at = refine(m, path, metric, &base, &at, cfg).unwrap_or(at);
            // Where a block folds, the input cannot pass, whatever the determinant of the whole
            // does beyond (several blocks folding at once make a branch point of the whole). A
            // mechanism of one block has no such point: the input passed the sign change with
            // the walk, so it is a crossing, however loosely located (two branches meeting at a
            // small angle, as a near-kite's do, leave a located point a millionth of the input
            // off that looks folded to the rank test). Nor is a point a fold that is not
            // singular to the precision a fold is located to (`fold_pivot`, which the diagnosis
            // asks of a limit position): a near-kite inside a Watt six-bar, its located point
            // looking folded so, was taken for a limit position, refused as one, and the
            // crossing located from behind 6e-4 of the input off or not at all (10 of 6,030
            // random sweeps toward the change point).
            if m.block_count() > 1
                && block_folds(m, path, &at)
                && pivot_at(m, &path.at_sigma(at.sigma), &at.q) < fold_pivot(path, metric, at.sigma)
            {
                return Some(Found::Fold(at));
            }
            return Some(Found::Crossing(at, b));
        }
        walked += ds;
        a = b;
        det_a = det_b;
        ds = (ds * 1.5).min(max_arc).min(MAX_ARC_STEP);
    }
    None
}

/// How far [`trace`] walks along the curve: `arc` of arclength (scaled coordinates), and, where
/// it is steep, possibly farther ([`Reach::steep`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Reach {
    arc: f64,
    steep: bool,
}

impl Reach {
    /// A walk of `arc` of arclength.
    pub(crate) fn arc(arc: f64) -> Self {
        Reach { arc, steep: false }
    }

    /// The same walk going on where the curve is steep (see [`Reach::steep_short`]).
    pub(crate) fn steep(self) -> Self {
        Reach { steep: true, ..self }
    }

    /// Whether a walk from `start` at `a` that has spent its arclength (`walked`) goes on: where
    /// the curve is steep (the angles swing while the input barely moves, as on a near-kite's
    /// branch beside its change point: a hundred-thousandth of the input per unit of
    /// arclength), an arclength of a sample's step covers a millionth of the input, and the
    /// trace stopped a few tenths of a millionth short of a crossing the sweep's last step came
    /// within a millionth of. Such a walk goes on while its input has advanced less than a
    /// sixteenth of its reach `arc` (scaled: the curve, on average, steeper than sixteen units
    /// of an unknown per unit of input), by up to [`STEEP_ARC`] more.
    fn steep_short<Q>(&self, start: &CurvePoint<Q>, a: &CurvePoint<Q>, metric: &Metric<Q>, walked: f64) -> bool {
        let advanced = (a.sigma - start.sigma) / metric.sigma;
        self.steep && walked < self.arc + STEEP_ARC && advanced < self.arc / 16.0
    }
}

/// Longest arclength [`Reach::steep_short`] adds to a walk: two of its longest steps
/// ([`MAX_ARC_STEP`]). The near-kites swept toward their change point needed 0.15 of it (a
/// tenth left four of 29,980 sweeps failing). Farther, a walk reaches where a slide passes
/// within a hundred-millionth of its size from its pivot (a pivot ratio no tolerance
/// resolves), and took the mirrored branch there for a crossing: a whole turn more did, three
/// radians did not.
const STEEP_ARC: f64 = 2.0 * MAX_ARC_STEP;

/// `a`, where the walk stalled, as a limit position located to the inputs' rounding, or
/// `None`. Far out along a path (inputs of fifty thousand turns, doubles 6e-11 apart) the
/// curve cannot be followed closer to a limit position than a few of the inputs' rounding
/// steps: a step's input rounds past the limit, where there is no solution. `a` counts as the
/// limit position where the input's advance along the curve (`dsigma`, slowing by `rate` per
/// unit of arclength over the walk) would stop within four rounding steps: the input left to
/// the limit is `dsigma^2 / (2 rate)` in arclength units, and the Jacobian there is singular to
/// about its square root (see [`fold_pivot`]).
fn fold_at_rounding<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    a: &CurvePoint<Q<K>>,
    rate: f64,
) -> Option<CurvePoint<Q<K>>> {
    let dsigma = a.dsigma();
    if !(dsigma > 0.0 && rate > 0.0 && rate.is_finite()) {
        return None;
    }
    let left = dsigma * dsigma / (2.0 * rate) * metric.sigma;
    let rounding = path.rounding(a.sigma);
    (left <= 4.0 * rounding && pivot_at(m, &path.at_sigma(a.sigma), &a.q) < fold_pivot(path, metric, a.sigma))
        .then(|| a.clone())
}

/// The smallest pivot ratio below which a reversal of the input at `sigma` is a limit position
/// (the Jacobian singular) rather than a kink (regular): `1e-6`, or where the inputs are coarse,
/// ten times the square root of their rounding in the inputs' units: a limit position located
/// to a distance `e` of the input leaves a pivot ratio of a few times `sqrt(e)` (the curve is a
/// parabola there): `1e-6` for inputs up to about fifty radians (3e-6 at a hundred turns),
/// `8e-5` at fifty thousand turns (where the limit located to four of the input's doubles left
/// `1.9e-5`).
pub(crate) fn fold_pivot<X: Store, Q>(path: &Path<X>, metric: &Metric<Q>, sigma: f64) -> f64 {
    (10.0 * (path.rounding(sigma) / metric.sigma).sqrt()).max(1e-6)
}

/// Most steps [`trace`] tries, accepted or not, before it gives up (`None`: the sweep reports
/// its failure as it is). Its walks are short: the reach is at most about two of its longest
/// steps ([`MAX_ARC_STEP`]) past a growth by half from `ds0` (at least a billionth of a
/// natural step: about 50 steps), and a stall halves the step at most about 50 times before its
/// floor; none of the walks of the sweep, analysis and kinematics tests took 50 steps. Where
/// the inputs' rounding rejects steps as fast as they grow (inputs near `4e14`, doubles a
/// sixteenth apart), the floor alone did not bound them: a sweep of the command line ran
/// minutes without end.
const MAX_TRACE_STEPS: usize = 1000;

/// Longest step of [`trace`] (scaled coordinates: a quarter radian of an angle, a quarter of the
/// mechanism's size of a length), however far it may follow the curve: a longer step could pass
/// a limit position and the gap beyond it, or a crossing, in one stride and land on another part
/// of the solution set, where the input happens to advance again.
const MAX_ARC_STEP: f64 = 0.25;

/// Smallest cosine of the angle between the unit tangents at the two ends of an accepted
/// continuation step (about 26 degrees): a smooth curve turns less over a step small against its
/// radius of curvature, a step landing on another curve through a branch point turns more.
const MIN_TURN_COS: f64 = 0.9;
