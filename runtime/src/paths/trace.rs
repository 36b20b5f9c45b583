//! Tracing a whole solution curve through its limit positions ([`trace_curve`], configured by
//! [`TraceConfig`]), over any [`Kernel`] ([`trace_curve_of`]).

use super::collected::{MAX_COLLECTED_BYTES, check_collected};
use super::curve::{
    CurvePoint, Metric, Path, arc_step, event_at, locate_fold, loose_position, pivot_at, signed_det, singular_ratio_at,
    tangent_from_analogs,
};
use super::sweep::{check_finite, range_too_long};
use super::trace_kink::{MAX_TURN, past_kink, turn};
use super::trace_start;
use crate::dims::{Dims, KinState, Store};
use crate::error::Error;
use crate::events::{Event, EventKind};
use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, Kernel, Q, X, check_sizes, is_angle};
use crate::number::sign;
use crate::solvers::newton::NewtonConfig;
use nalgebra::DVector;
use std::f64::consts::TAU;

/// Options of [`trace_curve`], built from the default with the `with_*` methods.
///
/// ```
/// use kinloop_runtime::{NewtonConfig, TraceConfig};
/// let opts = TraceConfig::default().with_ds(0.02).with_max_points(10_000);
/// assert!(opts.validate().is_ok());
/// let bad = TraceConfig::default().with_ds(-1.0);
/// assert!(bad.validate().unwrap_err().to_string().contains("TraceConfig::ds"));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct TraceConfig {
    /// Arclength between points (default `0.01`), measured in scaled coordinates: angles in
    /// radians, lengths in units of the mechanism's size (the magnitude of the loops they
    /// appear in), so the spacing does not depend on the unit of length. `0.01` gives points
    /// about 0.01 rad apart on a curve dominated by angles. From [`TraceConfig::MIN_DS`] to
    /// [`TraceConfig::MAX_DS`]. The longest step: where the curve's tangent would turn by more
    /// than a tenth of a radian over it, steps are shorter (see [`TracedOf::points`]).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub ds: f64,
    /// Most points returned (default `100_000`; at most
    /// [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES), the most an analysis holds, and no more
    /// than fit in [`MAX_COLLECTED_BYTES`], 1 GiB,
    /// for the mechanism traced: about 33 million points of a four-bar, which
    /// [`trace_curve`] checks before its first step).
    pub max_points: usize,
    /// The corrector's Newton configuration; `None` (default): the mechanism's
    /// ([`Mechanism::solver_config`]).
    pub newton: Option<NewtonConfig>,
}

impl Default for TraceConfig {
    fn default() -> Self {
        TraceConfig { ds: 0.01, max_points: 100_000, newton: None }
    }
}

impl TraceConfig {
    /// The shortest step allowed: a step is halved down to a millionth of itself near a limit
    /// position or a kink, and below this the halvings reach the rounding of the coordinates.
    pub const MIN_DS: f64 = 1e-9;

    /// The longest step allowed, a radian of the scaled coordinates: longer steps pass over
    /// the curve's features and back (a four-bar's rocking crank traced with steps of 3 listed
    /// each of its limit positions two or three times), where every step up to this one was
    /// seen to trace random four-bars as the default step does. A long step sees less of the
    /// curve: of 3,294 random class IV groups and triads, one at a step of 0.1, four at 0.5 and
    /// five at 1 listed other limit positions than at the default step, each having passed a
    /// pair of them closer together than a step (see [`TracedOf::folds`]).
    pub const MAX_DS: f64 = 1.0;

    /// Sets [`TraceConfig::ds`].
    pub fn with_ds(mut self, ds: f64) -> Self {
        self.ds = ds;
        self
    }
    /// Sets [`TraceConfig::max_points`].
    pub fn with_max_points(mut self, n: usize) -> Self {
        self.max_points = n;
        self
    }
    /// Sets [`TraceConfig::newton`].
    pub fn with_newton(mut self, newton: NewtonConfig) -> Self {
        self.newton = Some(newton);
        self
    }

    /// The first field outside its valid range (`ds` from [`TraceConfig::MIN_DS`] to
    /// [`TraceConfig::MAX_DS`], `max_points` from 1 to
    /// [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES), and the Newton configuration's ranges, as
    /// `newton.<field>`).
    pub fn invalid_field(&self) -> Option<String> {
        if !(Self::MIN_DS..=Self::MAX_DS).contains(&self.ds) {
            Some("ds".into())
        } else if !(1..=crate::analysis::MAX_SAMPLES).contains(&self.max_points) {
            Some("max_points".into())
        } else {
            self.newton.and_then(|n| n.invalid_field()).map(|f| format!("newton.{f}"))
        }
    }

    /// Checks every field: `Error::InvalidArgument` names the first one out of range and states
    /// its valid range.
    pub fn validate(&self) -> Result<(), Error> {
        let field = self.invalid_field().map(|field| {
            let range = match field.strip_prefix("newton.") {
                Some(newton) => NewtonConfig::valid_range(newton).to_string(),
                None if field == "ds" => format!("[{:e}, {}]", Self::MIN_DS, Self::MAX_DS),
                None => format!("1..={}", crate::analysis::MAX_SAMPLES),
            };
            (field, range)
        });
        crate::error::check_fields("TraceConfig", field.as_ref().map(|(f, r)| (f, r.as_str())), self)
    }
}

/// One point of a traced solution curve, its inputs in `X` and positions in `Q`: arrays for a
/// compiled mechanism ([`TracedPoint`]), boxed slices ([`Heap`](crate::dims::Heap)) for a
/// mechanism whose sizes are known at run time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TracedPointOf<Q, X> {
    /// Input values.
    pub x: X,
    /// Positions of the unknowns.
    pub q: Q,
    /// The rate of the input along the curve (the path coordinate's share of the unit tangent,
    /// in scaled coordinates): positive while the input advances along the path, negative after
    /// a limit position reversed it, zero at one.
    pub input_rate: f64,
}

/// One point of a compiled mechanism's traced solution curve (`N` unknowns, `NI` inputs).
pub type TracedPoint<const N: usize, const NI: usize> = TracedPointOf<[f64; N], [f64; NI]>;

/// A solution curve traced by pseudo-arclength continuation ([`trace_curve_of`]), its points'
/// positions in `Q` and inputs in `X` (see [`TracedPointOf`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TracedOf<Q, X> {
    /// Points along the curve, about `ds` apart where its tangent turns by less than a tenth
    /// of a radian over `ds`; closer where it turns more, a step at most a tenth of the
    /// curve's radius of curvature (in scaled coordinates: a four-bar's curve, of radius about
    /// one, is traced in steps of about 0.06 at `ds` of 1). See [`TracedOf::kinks`] for the
    /// corners, each of which is a point too.
    pub points: Vec<TracedPointOf<Q, X>>,
    /// The limit positions passed (where the input reversed), located precisely. Two limit
    /// positions closer together along the curve than a step (the input reverses and resumes
    /// within one step: a crank driving a class IV group that locks over a few ten-thousandths
    /// of a radian) can be passed unlisted, as a pair: the trace sees the curve at its points.
    /// A sweep driven by the input does not pass them (it stops at the first).
    pub folds: Vec<Event>,
    /// The kinks passed ([`EventKind::Kink`]): corners of the curve, where its velocity analogs
    /// jump with the Jacobian regular (`abs`, `min`, `max`, `clamp` in the equations), located
    /// within rounding of the input. The input goes on across a kink in the direction it had;
    /// [`TracedOf::points`] holds the corner too. A corner at the trace's start or at an end of
    /// its segment is not listed: the curve traced holds one of its sides only.
    pub kinks: Vec<Event>,
    /// The branch points passed ([`EventKind::SingularCrossing`]): where the curve followed
    /// crosses another (a four-bar at a change point, all its links in line), the Jacobian
    /// singular with the input going on. The trace goes on along the smooth continuation, the
    /// curve its tangent carries on; the event is the point next to the crossing (the first
    /// past it, or where the corrector cannot reach past it in a short step, the last before
    /// it), within a ten-thousandth of [`TraceConfig::ds`] of it (scaled coordinates). A curve
    /// that comes back through a branch point (after limit positions, along the other curve
    /// through it) lists it each time it passes. Where two curves only come
    /// close (a four-bar near a change point), the trace is not taken across the gap: it
    /// follows its own curve round its limit positions, however narrow the gap.
    pub crossings: Vec<Event>,
    /// The curve closed on itself: it came back to its first point, its angles to within whole
    /// turns (a crank-rocker driven by its rocker closes after one rocking, its crank a turn
    /// on; driven by its crank, after a turn of the crank: where the path moves one angle
    /// input, its whole turns count too), with the input moving as it did there (not the other
    /// assembly mode passing near it), a step passing over it (not another stretch of the
    /// curve passing within a step of it).
    pub closed: bool,
    /// The trace stopped at [`TraceConfig::max_points`], before the curve closed or left the
    /// segment: the curve goes on past its last point.
    pub truncated: bool,
}

/// A compiled mechanism's traced solution curve ([`trace_curve`]).
pub type Traced<const N: usize, const NI: usize> = TracedOf<[f64; N], [f64; NI]>;

/// Traces the whole solution curve through `guess` at input `from`, moving first towards `to`,
/// by pseudo-arclength continuation in `(q, input)`: unlike a sweep it passes limit positions,
/// where the input reverses, so a mechanism whose input cannot make a full turn (a non-Grashof
/// four-bar driven by a rocking link) yields its complete closed curve. Like a sweep it passes
/// kinks (corners of the curve where the Jacobian is regular: a cam law written with `clamp`),
/// with the input going on in its direction and on the same branch, and lists them in
/// [`TracedOf::kinks`]; a corner where the tangent turns by less than about a tenth of a radian
/// (scaled coordinates) is passed as a smooth point and not listed. It does not go on past a
/// jump in the positions (`floor`) of more than a tenth of [`TraceConfig::ds`] (scaled
/// coordinates): that is a `Branch` error. It never steps from its curve onto another: where
/// two come within less than a step of each other (a four-bar near a change point) it follows
/// its own round its limit position however narrow the gap, and where two cross (at the change
/// point) it goes on along the curve its tangent carries on and lists the crossing in
/// [`TracedOf::crossings`]. It may start at a limit position, where the velocity analogs do not
/// exist (the input where a sweep stopped, [`Error::SweepStopped`]): its tangent there is the
/// null vector of `[J, dF/dx]`, and the start is the first of [`TracedOf::folds`] (where a
/// Newton block reaches it only linearly, the limit position is located from beside it, and the
/// trace starts there, within the rounding of `from`). At a branch point, where two curves meet,
/// the first solve's `Singular` error stands. Stops when the curve
/// closes, leaves the segment between `from - (to - from)` and `to`, or after
/// [`TraceConfig::max_points`] (then [`TracedOf::truncated`] says so). Arclength is measured in scaled coordinates (see
/// [`TraceConfig::ds`]): the same points in any unit of length.
/// Allocates (it returns a `Vec`); use [`Sweep`](crate::Sweep) in hot loops.
///
/// A compiled mechanism's [`trace_curve_of`] (through [`Compiled`]).
///
/// Errors: `InvalidArgument` for invalid options (naming the field), a
/// [`TraceConfig::max_points`] whose points would take more than
/// [`MAX_COLLECTED_BYTES`] (with the numbers), or
/// `to == from` (or within the smallest normal number of it), or a range `to - from` that
/// overflows; `NonFinite` naming `from` or `to` where one is not finite; the errors of the first solve at
/// `from`, but for an analog beyond `f64`'s range (the acceleration analogs by a length input in
/// a mechanism below about `1e-154` in size), which the trace does not use; `Branch` where the continuation cannot proceed (the
/// curve ends or jumps, or branches meet, where no step however short stays on it).
pub fn trace_curve<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    from: [f64; NI],
    to: [f64; NI],
    guess: [f64; N],
    opts: &TraceConfig,
) -> Result<Traced<N, NI>, Error>
where
    M: Mechanism<N, NI, NO>,
{
    // `trace_curve_of` refuses an angle parameter too large to resolve.
    trace_curve_of(&Compiled(m), from, to, guess, opts)
}

/// [`trace_curve`] over any [`Kernel`]: a compiled mechanism's ([`Compiled`]) or one whose sizes
/// are known at run time (`kinloop_model::Model::trace_curve`). `from`, `to` and `guess` of the
/// kernel's sizes (a mismatch is an `Error::InvalidArgument`); the corrector's configuration is
/// [`TraceConfig::newton`], or the kernel's ([`Kernel::solver_config`]), whose
/// `largest_precise_angle` an angle parameter must not exceed ([`Kernel::check_param_angles`]).
pub fn trace_curve_of<K: Kernel>(
    m: &K,
    from: X<K>,
    to: X<K>,
    guess: Q<K>,
    opts: &TraceConfig,
) -> Result<TracedOf<Q<K>, X<K>>, Error> {
    opts.validate()?;
    check_sizes(m, "trace_curve", &[&from, &to], &[&guess])?;
    let cfg = opts.newton.unwrap_or(m.solver_config().newton);
    cfg.validate()?;
    m.check_param_angles(&cfg)?;
    // Named as a sweep names them: the end that is not finite, and a range whose length
    // overflows (of finite ends, which the one message for all three called not finite).
    check_finite("from", from.as_ref(), m)?;
    check_finite("to", to.as_ref(), m)?;
    let path = Path::new(from.clone(), to);
    if !path.len.is_finite() {
        return Err(Error::InvalidArgument(
            "trace_curve: the range `to - from` overflows (its length is not finite); give ends closer together".into(),
        ));
    }
    // A range shorter than the smallest normal number gives no direction either: the path's
    // parameter, `sigma / len`, overflows, and a regular start was told the curve branches there.
    if path.len < f64::MIN_POSITIVE {
        return Err(Error::InvalidArgument(
            "trace_curve needs `to` different from `from` (by at least 2.2e-308, the smallest normal number)".into(),
        ));
    }
    // A start at a limit position (where a sweep that stopped there says it is) has positions
    // but no velocity analogs: see `trace_start`.
    let trace_start::Start { q, sigma, analogs } = trace_start::start(m, &path, &guess, &cfg)?;
    let metric = Metric::at(m, &path, &from, &q);
    // A range no sweep follows is none a trace follows either: refused before the first step,
    // as a sweep refuses it (a trace over 1e12 rad walked for as many points as it was allowed).
    if let Some(e) = range_too_long(&metric, path.len, || m.location(from.as_ref(), None)) {
        return Err(e);
    }
    // Every point is kept: refused before the first step where they could exceed the memory
    // budget (after the range, whose refusal says more of a trace that could never end).
    check_point_budget(m, opts.max_points)?;
    // Not at a branch point, where two curves meet: there the point solve's error stands.
    let tangent = trace_start::tangent(m, &path, &metric, (&q, sigma), analogs, CROSSING_SINGULAR)?;
    // At a limit position, or within about the square of this of one (scaled): listed there.
    let singular_start = tangent[m.dims().n()].abs() < CROSSING_SINGULAR;
    let start = CurvePoint { tangent, q, sigma };
    let (start_z, start_dsigma) = (start.z(&metric), start.dsigma());
    // Per scaled coordinate, the whole turn of an angle unknown, and of the path's coordinate
    // where the path turns one angle input (0 for the others): the curve has closed when it
    // comes back to its start to within whole turns of those. A crank's curve closes after a
    // turn of the crank; where several inputs move, a turn of one is no turn of the others.
    let moving: Vec<usize> = (0..m.dims().ni()).filter(|&i| path.delta[i] != 0.0).collect();
    let input_turn = match moving[..] {
        [i] if m.input_kind(i) == QuantityKind::Angle => TAU * (path.len / path.delta[i].abs()) / metric.sigma,
        _ => 0.0,
    };
    let turns: Vec<f64> = (0..m.dims().n())
        .map(|u| if is_angle(m, u) { TAU / metric.unit[u] } else { 0.0 })
        .chain([input_turn])
        .collect();
    let point =
        |p: &CurvePoint<Q<K>>| TracedPointOf { x: path.at_sigma(p.sigma), q: p.q.clone(), input_rate: p.dsigma() };
    let mut out = TracedOf {
        points: vec![point(&start)],
        folds: Vec::new(),
        kinks: Vec::new(),
        crossings: Vec::new(),
        closed: false,
        truncated: false,
    };
    // The curve's orientation at a point is the sign of `det J` (the Jacobian in the unknowns)
    // times the input's direction along the tangent: the determinant of the bordered matrix
    // `[J, dF/dsigma; t^T]` is `det J` times the tangent's input component times a positive factor,
    // and it keeps its sign along a smooth curve, through limit positions too (there both factors
    // change sign). It changes sign at a branch point, where a step passes onto the crossing curve's
    // continuation, and across the gap between two curves that come close, where a step lands on
    // the other curve: the trace's test that no step jumps.
    let orientation = |p: &CurvePoint<Q<K>>| sign(signed_det(m, &path.at_sigma(p.sigma), &p.q)) * sign(p.dsigma());
    // At a limit position both factors are the rounding's: the first step sets the orientation.
    let mut side = if singular_start { 0.0 } else { orientation(&start) };
    // Past either end of the segment from `from - (to - from)` to `to` (its rounding aside).
    let left_path = |p: &CurvePoint<Q<K>>| p.sigma.abs() > path.len * (1.0 + 1e-12);
    let start_fold = singular_start.then(|| event_at(EventKind::LimitPosition, &path, &start, None));
    let (ds, mut p, mut walked) = (opts.ds, start, 0.0);
    let floor = ds * 1e-6;
    let pivot = m.solver_config().singular_pivot;
    let mut step = ds;
    // The shortest step tried from `p` that landed on the curve past a change of its
    // orientation (a branch point, or a gap jumped), for where no shorter step can be made.
    let mut crossed: Option<CurvePoint<Q<K>>> = None;
    // `p` lies just past a crossing the trace passed.
    let mut just_crossed = false;
    // The last point the trace accepted away from any branch point (a singular value ratio of
    // at least `CROSSING_SINGULAR`), and the orientation there.
    let mut anchor: Option<(CurvePoint<Q<K>>, f64)> = None;
    // The arclength walked where each crossing and each limit position was listed.
    let (mut crossed_at, mut folded_at) = (Vec::new(), Vec::new());
    // A start at a limit position is the first one listed; the step that leaves it (the input
    // turning back from the rounding's direction) and the step that closes the curve on it
    // (the input turning there again) do not list it twice.
    if let Some(fold) = start_fold {
        out.folds.push(fold);
        folded_at.push(0.0);
    }
    // How loosely the start is pinned, and whether the trace has been farther from it than four
    // times that (then a step that passes over the start closes the curve).
    let (close_slack, mut away) = (loose_position(&cfg, &start_z), false);
    loop {
        if out.points.len() >= opts.max_points {
            out.truncated = true;
            break;
        }
        let stepped = arc_step(m, &path, &metric, &p, step, &cfg).filter(|n| stays_on_curve(&p, n, step, &metric));
        // A step that changed the curve's orientation passed a branch point, or jumped the gap
        // between two curves that come close: shorter steps follow the curve round its own
        // limit position, and at the smallest step the branch point is a crossing, passed.
        let next = stepped.and_then(|n| {
            let o = orientation(&n);
            if side * o >= 0.0 {
                Some((n, o))
            } else if 0.5 * step < floor {
                out.crossings.push(event_at(EventKind::SingularCrossing, &path, &n, None));
                crossed_at.push(walked);
                just_crossed = true;
                Some((n, o))
            } else {
                crossed = Some(n);
                None
            }
        });
        let Some((next, o)) = next else {
            step *= 0.5;
            if step < floor {
                // No step however short: a kink just ahead (the last step tried, twice the
                // floor at most, crossed it), a branch point whose curves the corrector cannot
                // tell apart there, or the end of the curve. Beside a branch point (the singular
                // value ratio below `CROSSING_SINGULAR`) the bordered system is singular too and the
                // corrector fails at every short step: the crossing is passed by the shortest
                // step that landed past it, else by a solve at fixed input along the tangent;
                // where the trace stands just past a crossing, it moves on by such a solve; and
                // where neither leaves the branch point, by a step over it from the last point
                // before it that was away from it (`jumped_past`). A
                // Grashof-equal four-bar whose coupler and rocker fold onto each other at its
                // change point (`a + c = b + d`, `a > d`) stopped there: 704 of 1,000 random
                // near-kites and 497 of 1,000 others, traced through it.
                let near_branch_point = singular_ratio_at(m, &path.at_sigma(p.sigma), &p.q) < CROSSING_SINGULAR;
                let (past, event, listed_past) = if let Some(k) =
                    past_kink(m, &path, &metric, &p, 2.0 * floor, &cfg, pivot)
                {
                    (k.point, Some(k.event), true)
                } else if let Some(c) =
                    crossed.take().filter(|c| near_branch_point && (c.z(&metric) - p.z(&metric)).dot(&p.tangent) > 0.0)
                {
                    // Listed where the trace stands, next to the branch point: the point past
                    // it may lie a few thousandths of arclength on.
                    (c, Some(event_at(EventKind::SingularCrossing, &path, &p, None)), false)
                } else if let Some(c) =
                    past_crossing(m, &path, &metric, &p, 2.0 * floor, &cfg, -side, false, &orientation)
                {
                    let event = event_at(EventKind::SingularCrossing, &path, &c, None);
                    (c, Some(event), true)
                } else if let Some(c) = (just_crossed && near_branch_point)
                    .then(|| past_crossing(m, &path, &metric, &p, 2.0 * floor, &cfg, side, true, &orientation))
                    .flatten()
                {
                    (c, None, true)
                } else if let Some(c) = anchor
                    .as_ref()
                    .filter(|_| near_branch_point)
                    .and_then(|(a, o)| jumped_past(m, &path, &metric, a, *o, &p, ds, &cfg, &orientation))
                {
                    (c, Some(event_at(EventKind::SingularCrossing, &path, &p, None)), false)
                } else {
                    let x = path.at_sigma(p.sigma);
                    let at = m.location(x.as_ref(), None);
                    // Against a whole step's change of each input.
                    return Err(match path.coarse_input(x.as_ref(), |di| ds * metric.sigma * di / path.len) {
                        Some((i, apart, step)) => {
                            let name = m.input_name(i).to_string();
                            Error::InputTooCoarse { walk: "trace", input: i, name, apart, step, at }
                        }
                        None => Error::Branch {
                            message: "pseudo-arclength continuation cannot proceed (the curve bifurcates or ends here)"
                                .into(),
                            at,
                        },
                    });
                };
                // The walk to the event: where it is listed, before or past the branch point.
                let walked_before = walked;
                walked += (past.z(&metric) - p.z(&metric)).norm();
                let listed_at_walk = if listed_past { walked } else { walked_before };
                let first_step = out.points.len() == 1;
                p = past;
                crossed = None;
                if left_path(&p) {
                    break;
                }
                // A corner at the trace's start or at an end of its segment (within the rounding
                // `left_path` allows) is not one the curve traced passes through: one side of it
                // only is traced, and the state there carries one side's analogs or the other's
                // (`abs` takes its derivative at 0 as +1), so that it was listed one way and not
                // the other, once 2 ulps past the end of the segment. Not listed; a corner just
                // past the end is the curve's point at the end itself.
                let kink = matches!(&event, Some(e) if e.kind == EventKind::Kink);
                let event = match event {
                    Some(e) if kink => {
                        let at_end = p.sigma.abs() >= path.len * (1.0 - 1e-12);
                        if at_end && p.sigma.abs() > path.len {
                            let sigma = path.len.copysign(p.sigma);
                            let Ok(q) = m.positions(&path.at_sigma(sigma), &p.q, &cfg) else { break };
                            p = CurvePoint { q, sigma, tangent: p.tangent };
                        }
                        let at_start = first_step && p.sigma.abs() <= path.len * 1e-12;
                        (!at_end && !at_start).then_some(e)
                    }
                    event => event,
                };
                // Past a crossing, or moved on from one (no event): beside it still.
                just_crossed = !kink;
                match event {
                    Some(event) if event.kind == EventKind::Kink => out.kinks.push(event),
                    Some(event) => {
                        out.crossings.push(event);
                        crossed_at.push(listed_at_walk);
                    }
                    None => {}
                }
                out.points.push(point(&p));
                side = orientation(&p);
                step = ds;
            }
            continue;
        };
        let leaving_start = singular_start && out.points.len() == 1;
        let fold = if (p.dsigma() > 0.0) != (next.dsigma() > 0.0) && !leaving_start {
            locate_fold(m, &path, &metric, &p, step, next.dsigma(), &cfg)
        } else {
            None
        };
        let folded_walk = walked;
        walked += step;
        let back = distance_in_turns(&next.z(&metric), &start_z, &turns);
        if away_from_branch_points(m, &path.at_sigma(next.sigma), &next.q) {
            anchor = Some((next.clone(), o));
        }
        let before = std::mem::replace(&mut p, next);
        // A point past a branch point found from an earlier point is kept while the trace
        // creeps toward the branch point in short steps (it is used only if still ahead).
        if step >= ds {
            crossed = None;
        }
        // A crossing passed by this step set `just_crossed` above; any other step moved on.
        just_crossed = just_crossed && side * o < 0.0;
        if o != 0.0 {
            side = o;
        }
        // Back at the start, and the input moving as it did there: after an odd number of limit
        // positions the curve can pass near its start on the other assembly mode (within a
        // step of it where the two modes come close, or with a long step), the input moving the
        // other way; that is not the curve closing. Nor is coming near it: the step just made
        // must pass over the start (`start_on_step`), once the trace has been away from it
        // (the first steps leave from it; a curve can be smaller than a step). Tested before
        // leaving the segment: a crank traced over one turn closes at its end.
        // Where the step that closes the curve passes a limit position after the start too, that
        // limit position is the first one the trace listed.
        let closing =
            (away && back <= ds && (before.dsigma() * start_dsigma >= 0.0 || p.dsigma() * start_dsigma >= 0.0))
                .then(|| start_on_step(&before, &p, &metric, &start_z, &turns, close_slack))
                .flatten();
        // A limit position beyond the segment's end, passed by the step that leaves the segment,
        // is not on the curve traced (one 2e-3 of the input past `to` was listed, where no point
        // was). One a step passes and comes back into the segment from is: the trace goes on.
        if let Some(f) = fold
            && !(left_path(&f) && left_path(&p))
            && closing.is_none_or(|at| !singular_start && along_step(&before, &p, &metric, &f.z(&metric)) < at)
        {
            out.folds.push(event_at(EventKind::LimitPosition, &path, &f, None));
            folded_at.push(folded_walk);
        }
        if closing.is_some() {
            out.closed = true;
            break;
        }
        away |= back > 4.0 * close_slack;
        if left_path(&p) {
            break;
        }
        out.points.push(point(&p));
        step = ds;
    }
    // A reversal of the input located within the crossing's precision of a crossing the trace
    // passed is the corrector's wandering beside the branch point (its positions singular to
    // the rounding there), not a limit position: over a thousand random near-kites traced
    // through their change point, 394 listed one, a few billionths of the input from it. So is
    // a second crossing listed there (the trace passed the branch point, wandered back beside
    // it, and a step from before it passed it again). Beside means at the same input and a few
    // steps on along the trace: a curve that comes back to the same input after two limit
    // positions (a Watt six-bar's dyad folding on either side of its four-bar's change point)
    // passes the branch point again, along the other curve through it, a crossing of its own
    // (466 of 2,000 random such six-bars lost it when the input alone was compared). Measured
    // over random near-kites and six-bars, the wandering's events lay at most 4.1 steps of
    // arclength apart, a second pass at least 459 (see `BESIDE_WALK`).
    let beside = |(a, wa): (&Event, f64), (b, wb): (&Event, f64)| {
        (a.tau - b.tau).abs() * path.len / metric.sigma <= 1e-4 * ds && (wa - wb).abs() <= BESIDE_WALK * ds
    };
    let mut crossings: Vec<(Event, f64)> = Vec::new();
    for (c, w) in out.crossings.drain(..).zip(crossed_at) {
        if !crossings.last().is_some_and(|(l, lw)| beside((l, *lw), (&c, w))) {
            crossings.push((c, w));
        }
    }
    let folds = out.folds.drain(..).zip(folded_at);
    out.folds =
        folds.filter(|(f, w)| !crossings.iter().any(|(c, cw)| beside((c, *cw), (f, *w)))).map(|(f, _)| f).collect();
    out.crossings = crossings.into_iter().map(|(c, _)| c).collect();
    Ok(out)
}

/// The most points of `m`'s trace that fit in
/// [`MAX_COLLECTED_BYTES`], the memory a collector
/// keeps at most: the largest [`TraceConfig::max_points`] [`trace_curve_of`] accepts for `m`
/// (about 33 million points of a four-bar), for a caller that states the limit in its own terms
/// (a command line's option) before it traces.
pub fn max_trace_points<K: Kernel>(m: &K) -> usize {
    MAX_COLLECTED_BYTES / trace_point_bytes(m).max(1)
}

/// The bytes one point of `m`'s trace keeps: the point itself, and its positions and inputs
/// where they are on the heap (a run-time model's, whose states then hold heap bytes too; a
/// compiled mechanism's arrays are inline).
fn trace_point_bytes<K: Kernel>(m: &K) -> usize {
    let d = m.dims();
    let heap = if d.kin().heap_bytes() > 0 { (d.n() + d.ni()) * size_of::<f64>() } else { 0 };
    size_of::<TracedPointOf<Q<K>, X<K>>>() + heap
}

/// `Err(Error::InvalidArgument)` where `max_points` points of `m`'s trace would take more than
/// [`MAX_COLLECTED_BYTES`], with the numbers and
/// the most points that fit ([`max_trace_points`]). A trace keeps every point, and `max_points`
/// may be as large as [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES): a four-bar's `10^8` points
/// are 3.2 GB, a run-time model's several times that (each point's positions and inputs on the
/// heap), and a failed allocation aborts the process where a sweep's `run()` refuses the same
/// before its first step.
fn check_point_budget<K: Kernel>(m: &K, max_points: usize) -> Result<(), Error> {
    let instead = format!(
        "give `TraceConfig::max_points` at most {} (this mechanism's points that fit), and trace a long curve in \
         parts, each from the last point of the one before",
        max_trace_points(m)
    );
    let (what, bytes_each) = ("points (up to `TraceConfig::max_points`)", trace_point_bytes(m));
    check_collected("`trace_curve`", what, max_points, bytes_each, &instead)
}

/// The point just past a branch point ahead of the curve point `p`, within the arclength
/// `reach` (scaled coordinates), where no step of the trace can be made: the two curves meet
/// or pass within the rounding there, and the corrector's plane meets both. The straight
/// prediction along `p`'s tangent, solved at a fixed input `reach` to 32 times `reach` on (no
/// restart: a restart would find another branch; nearer, the position may be singular to the
/// rounding), with the curve's orientation of the sign `beyond` (see `trace_curve_of`: the
/// other side's to pass a crossing, the present one's to move on from one just passed) and
/// within the arclength of the prediction (a curve that passes the other within the rounding
/// lies that far from the straight line, no farther): the nearest such point, or with
/// `farthest` the farthest. `None` where `p`'s Jacobian is not nearly singular (a singular value
/// ratio below `CROSSING_SINGULAR`: no branch point is there) or no such point is found (the curve
/// ends).
#[allow(clippy::too_many_arguments)]
fn past_crossing<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    p: &CurvePoint<Q<K>>,
    reach: f64,
    cfg: &NewtonConfig,
    beyond: f64,
    farthest: bool,
    orientation: &impl Fn(&CurvePoint<Q<K>>) -> f64,
) -> Option<CurvePoint<Q<K>>> {
    let dir = sign(p.dsigma());
    let singular = singular_ratio_at(m, &path.at_sigma(p.sigma), &p.q) < CROSSING_SINGULAR;
    if dir == 0.0 || beyond == 0.0 || !singular {
        return None;
    }
    let cfg = cfg.with_restarts(false);
    let mut ks = [1.0, 2.0, 4.0, 8.0, 16.0, 32.0];
    if farthest {
        ks.reverse();
    }
    for k in ks {
        let arc = k * reach;
        let sigma = p.sigma + dir * arc * metric.sigma;
        let guess = p.predicted(sigma, metric);
        let Ok(solved) = m.kinematics(&path.at_sigma(sigma), &guess, &cfg) else { continue };
        let predicted = CurvePoint { q: guess.clone(), sigma, tangent: p.tangent.clone() }.z(metric);
        let mut q = guess;
        q.as_mut().copy_from_slice(solved.q());
        let tangent = tangent_from_analogs(&solved, path, metric) * dir;
        let past = CurvePoint { q, sigma, tangent };
        if orientation(&past) * beyond > 0.0 && (past.z(metric) - predicted).norm() <= arc {
            return Some(past);
        }
    }
    None
}

/// The point past the branch point beside `p`, reached by one continuation step from `anchor`
/// (a point before it, away from it, of orientation `side`) over the branch point: steps of
/// twice to 256 times the distance from `anchor` to `p` (at most `ds`, but four times that
/// distance at least: a near-kite's anchor lay up to 1.5 `ds` back), the first that stays on
/// the curve (see [`stays_on_curve`]), lands ahead of `p` and has the other orientation. Beside
/// a branch point the corrector's points wander with the rounding of a singular position (the
/// input reverses back and forth within a few billionths), and neither a short step nor a solve
/// at fixed input along the wandering tangent leaves it; a step from before it does, as a
/// sweep's trace jumps a branch point onto the curve's smooth continuation.
#[allow(clippy::too_many_arguments)]
fn jumped_past<K: Kernel>(
    m: &K,
    path: &Path<X<K>>,
    metric: &Metric<Q<K>>,
    anchor: &CurvePoint<Q<K>>,
    side: f64,
    p: &CurvePoint<Q<K>>,
    ds: f64,
    cfg: &NewtonConfig,
    orientation: &impl Fn(&CurvePoint<Q<K>>) -> f64,
) -> Option<CurvePoint<Q<K>>> {
    let (za, zp) = (anchor.z(metric), p.z(metric));
    let gap = (&zp - &za).norm();
    // NaN is no gap.
    if gap.is_nan() || gap <= 0.0 || side == 0.0 {
        return None;
    }
    let mut step = 2.0 * gap;
    while step <= (256.0 * gap).min(ds).max(4.0 * gap) {
        if let Some(n) = arc_step(m, path, metric, anchor, step, cfg)
            && stays_on_curve(anchor, &n, step, metric)
            && orientation(&n) * side < 0.0
            && (n.z(metric) - &zp).dot(&anchor.tangent) > 0.0
        {
            return Some(n);
        }
        step *= 2.0;
    }
    None
}

/// The largest ratio of the Jacobian's smallest singular value to its largest (columns
/// equilibrated, [`singular_ratio_at`]) at a point next to a branch point that the trace passes
/// straight (see [`past_crossing`]): the Jacobian is singular there, and within the trace's
/// smallest step of it the ratio is of that step's order, far below this. Not the smallest
/// pivot, which partial pivoting can leave above it there: a Watt six-bar stopped beside its
/// four-bar's change point with a pivot ratio of 2e-6 (17 of 2,000 random ones on a near-kite).
const CROSSING_SINGULAR: f64 = 1e-6;

/// Whether the Jacobian at `(x, q)` is away from every branch point: a singular value ratio of
/// at least [`CROSSING_SINGULAR`]. Asked at every point the trace accepts, so the SVD is made
/// only where the smallest pivot is below a thousandth: a pivot overstates the distance to a
/// singular position by the growth of the elimination (sixty times in the six-bar of
/// `CROSSING_SINGULAR`), not by a thousand; the SVD at every point took a trace of a Watt
/// six-bar from 2.2 to 3.7 microseconds a point.
fn away_from_branch_points<K: Kernel>(m: &K, x: &X<K>, q: &Q<K>) -> bool {
    pivot_at(m, x, q) >= 1e-3 || singular_ratio_at(m, x, q) >= CROSSING_SINGULAR
}

/// How far apart along the trace, in steps of [`TraceConfig::ds`], two events at the same curve
/// point are the corrector's wandering beside a branch point and not two passes through it: the
/// wandering's events lay at most 2.5 steps apart over the random near-kites and six-bars first
/// measured, and 4.1 in one of about 12,000 near-kites of a wider run (listed as two crossings
/// 5.6e-9 of the input apart, where the bound was 4); a second pass at least 459. Each event's
/// walk is taken where it is listed: a crossing listed where the trace stood, before a step over
/// the branch point 13 steps long, was counted past that step, 19 steps from the crossing
/// listed beside it, and listed twice.
const BESIDE_WALK: f64 = 16.0;

/// The distance between the scaled points `z` and `z0` with each coordinate's difference
/// reduced by whole multiples of its turn in `turns` (where it is not 0).
fn distance_in_turns(z: &DVector<f64>, z0: &DVector<f64>, turns: &[f64]) -> f64 {
    difference_in_turns(z, z0, turns).norm()
}

/// `z - z0` with each coordinate reduced by whole multiples of its turn in `turns` (where it is
/// not 0).
fn difference_in_turns(z: &DVector<f64>, z0: &DVector<f64>, turns: &[f64]) -> DVector<f64> {
    let mut d = z - z0;
    for (v, &t) in d.iter_mut().zip(turns) {
        if t > 0.0 && t.is_finite() {
            *v -= t * (*v / t).round();
        }
    }
    d
}

/// Where the step from `p` to `next` passed over the trace's start `start_z` (scaled, to within
/// whole turns of `turns`), as a fraction of the step's chord, within `slack`: the start lies
/// between the step's ends along its chord and no farther from the chord than the arc between
/// them can bow (a quarter of the largest turn of the tangent a step may make, [`MAX_TURN`],
/// times the chord: twice the sagitta of a circular arc that turns that much). `None` where it
/// did not. Nearness alone is no closing: traced with steps of half a radian and more, random
/// class IV groups and triads came within a step of their start a little short of a limit
/// position that turns the curve back (the start lies past the input's reversal, on another
/// stretch of the curve) and were reported closed there (2 of 3,113 at `ds = 0.5`, 9 at
/// `ds = 1`), when a step's end within three quarters of a step of the start closed the curve.
fn start_on_step<Q: Store>(
    p: &CurvePoint<Q>,
    next: &CurvePoint<Q>,
    metric: &Metric<Q>,
    start_z: &DVector<f64>,
    turns: &[f64],
    slack: f64,
) -> Option<f64> {
    let z = p.z(metric);
    let to_start = difference_in_turns(start_z, &z, turns);
    let chord = next.z(metric) - &z;
    let len = chord.norm();
    if len == 0.0 {
        return (to_start.norm() <= slack).then_some(0.0);
    }
    let along = to_start.dot(&chord) / len;
    let off = (&to_start - &chord * (along / len)).norm();
    ((-slack..=len + slack).contains(&along) && off <= 0.25 * MAX_TURN * len + slack).then_some(along / len)
}

/// The fraction of the chord from `p` to `next` at which the point `z` (scaled) projects on it.
fn along_step<Q: Store>(p: &CurvePoint<Q>, next: &CurvePoint<Q>, metric: &Metric<Q>, z: &DVector<f64>) -> f64 {
    let start = p.z(metric);
    let chord = next.z(metric) - &start;
    (z - &start).dot(&chord) / chord.norm_squared().max(f64::MIN_POSITIVE)
}

/// Whether the step of length `step` (scaled coordinates) from `p` to `next` stays on the curve
/// it follows: the unit tangent turns by at most [`MAX_TURN`] (more is a step too long for the
/// curve's curvature, or one across a corner: see `trace_kink`), and the corrector moved the
/// prediction by at most `MAX_TURN` times the step. On a smooth curve that turns by `MAX_TURN`
/// the prediction is off by about half that; farther is another piece of the solution set,
/// across a jump in the positions (as `floor` makes one), which the corrector's plane, square
/// to the tangent, may meet however short the step. Refused, the step is halved, and at the
/// smallest step the jump is no kink (its positions are not continuous): the trace stops there.
fn stays_on_curve<Q: Store>(p: &CurvePoint<Q>, next: &CurvePoint<Q>, step: f64, metric: &Metric<Q>) -> bool {
    let predicted = p.z(metric) + &p.tangent * step;
    turn(&p.tangent, &next.tangent) <= MAX_TURN && (next.z(metric) - predicted).norm() <= MAX_TURN * step
}
