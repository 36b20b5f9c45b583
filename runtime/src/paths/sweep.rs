//! Sweeps over an input range that never jump branches.
//!
//! A [`Sweep`] produces the kinematic state at `samples` equally spaced inputs between `from`
//! and `to` (a straight path in input space; for one input simply a range). Between samples it
//! steps adaptively: each step predicts the position with the generated analogs (second-order
//! Taylor, `q + q' h + q'' h^2 / 2`) and corrects with Newton, so in the common case a step
//! costs one evaluation and at most one Newton iteration.
//!
//! **Branch safety.** The branch is identified by the signs of the block Jacobians'
//! determinants (the assembly mode of each block). A step is accepted only when the corrected
//! position keeps those signs and lies close to its prediction (where every unknown judged is
//! an angle a closed form gives, unique once its assembly mode and turn are known: on its
//! prediction's turn), with velocity
//! analogs close to theirs (the unknowns that merely follow the others,
//! [`Mechanism::FOLLOWERS`], are judged through those they follow); otherwise the step is
//! halved. When
//! a step cannot be made however small, the sweep finds out why:
//! * a **limit position** (the input cannot advance: a fold of the solution curve), located by
//!   following the curve by pseudo-arclength continuation to the point where the input reverses;
//! * a **singular crossing** (a block's determinant changes sign with solutions on both sides: a
//!   change point / bifurcation), located as the root of the determinant along the path;
//! * a **kink** (a corner of the solution curve where the Jacobian is regular: a function with a
//!   corner in the equations, `abs`, `min`, `max` or `clamp`, as a uniform-velocity cam law has),
//!   told from a jump by positions that stay continuous over the smallest step while the slopes
//!   jump, one side's slopes inside it (see `kink`).
//!
//! Each is recorded as an [`Event`]. At a limit position or a crossing the sweep then stops with
//! [`Error::SweepStopped`] naming the input value (or, with [`AtSingular::Continue`], passes a
//! crossing and goes on); past a kink it goes on. A step that cannot be made for any other
//! reason (a jump in the solution, as `floor` makes) is an [`Error::Branch`]. It never continues
//! silently on another branch. A jump is seen where a step meets it: one smaller than the
//! corrector's bound on a step ([`SweepConfig::corrector_rel`] of the step's predicted change)
//! is stepped over, the more easily the longer the steps, each sample still a solution on the
//! branch followed. Of 49 random cam rockers whose dwell law does not close over its turn (the
//! follower jumps as the cam angle wraps) and whose sweeps of 4,000 steps a turn refused the
//! jump, sweeps of two to eight samples a turn stepped over it in 54 of 196 (jumps of 2e-6 to
//! 3e-2 of the lift).
//!
//! **Steps, whatever the samples.** The samples asked for are the output grid, never the step:
//! a step is at most [`SweepConfig::max_step`] of the sample spacing, and also at most a quarter
//! of the inputs' natural unit ([`MAX_INPUT_STEP`]: a quarter radian of an angle input, a quarter
//! of the mechanism's size of a length), and the largest change its prediction makes to a judged
//! unknown's slope is at most a quarter of the largest slope plus a quarter unit per unit of
//! input ([`MAX_SLOPE_CHANGE`]). Approaching a limit position the slopes grow as the inverse
//! square root of the distance to it, so that bound shortens the steps before it, and no step
//! passes it and an interval beyond it where the loops cannot close to land on another part of
//! the motion: two samples over a turn meet the same branch and the same first limit position as
//! two thousand.
//!
//! **Range.** A sweep follows at most [`MAX_TURNS`] turns of its inputs (the path's length in
//! their units over `2 pi`): longer, its steps would number beyond use, and the doubles of inputs
//! that large (`0.125` apart at `1e15`) could not resolve them. A longer range is refused up
//! front: the sweep's first item is [`Error::RangeTooLong`], with the numbers. Within it, where
//! an input's doubles are farther apart than a millionth of its change between samples (a range
//! far out, finely sampled), a step that fails there is [`Error::InputTooCoarse`], naming the
//! input: its steps' inputs round away from where they are predicted.
//!
//! The iterator allocates nothing per step (events are rare and allocate). Its collecting
//! methods, [`SweepOf::run`] and [`SweepOf::table`], keep every state, and refuse up front a
//! sweep whose states would exceed
//! [`MAX_COLLECTED_BYTES`](super::collected::MAX_COLLECTED_BYTES); iterating has no such bound.

use super::collected::check_collected;
use super::config::{AtSingular, SweepConfig};
use super::crossing;
use super::curve::{self, CurvePoint, Metric, Path};
use super::locate::{self, Found, Reach};
use super::outcome::SweepResult;
use crate::dims::{Dims, KinState, Square, Store};
use crate::error::{Computed, Error, Quantity};
use crate::events::{Event, EventKind, Location};
use crate::kin::{DetSigns, Kin};
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, D, Kernel, KinOf, Q, X, check_sizes, is_angle};
use crate::paths::kink;
use crate::solvers::newton::NewtonConfig;
use crate::table::Table;
use crate::trig::Rotating;
use std::marker::PhantomData;

/// The reserve of a sweep's step budget: the attempts (steps accepted or not) it may take, beyond
/// four for each step of the largest length, to advance by one stride, the sample spacing or the
/// inputs' natural step ([`MAX_INPUT_STEP`]), the shorter (see [`SweepOf::max_attempts`]).
///
/// The budget is counted in windows of that many attempts, each of which must advance the sweep
/// by a stride (or reach the next sample): proportional to the input actually covered, so that a
/// sweep that advances is never stopped for the length of the range between two samples, and one
/// that does not is stopped after one window, whatever the samples. Per sample interval, as it
/// was, the budget failed the dwell cam (whose corners take about thirteen times the natural
/// steps a turn) over 1,080 turns between two samples, and let a sweep that stalled in two
/// samples over a million turns take 1e8 attempts before it stopped.
const ATTEMPTS_RESERVE: u64 = 100_000;

/// Largest step of the inputs, in their units (radians for an angle input, the mechanism's size
/// for a length), whatever the sample spacing: the number of samples asked for is the output
/// grid, never the step. A step over a whole turn could pass, in one stride, an interval of
/// inputs where the loops cannot close and land on another, disconnected part of the motion.
pub const MAX_INPUT_STEP: f64 = 0.25;

/// Largest change, relative to the largest slope, of the judged unknowns' slopes that a step's
/// prediction may make (`max |q'' dt| <= MAX_SLOPE_CHANGE (max |q'| + 1)`, each slope in its
/// unknown's unit per unit of input): the predictor's error bound.
/// Approaching a limit position, where the unknowns of the block that folds go as the square
/// root of the distance to it (and their slopes outgrow every other), the slopes' relative change
/// over a step is the step over twice that distance; at a quarter, no step goes more than halfway
/// to the limit position, let alone across the gap beyond it. Judged by the maxima the
/// prediction computes anyway, with the solved step (a step too long is rare: only where the
/// samples are far apart or a limit position is near).
pub const MAX_SLOPE_CHANGE: f64 = 0.25;

/// Most turns (`2 pi` units of the inputs, see [`MAX_INPUT_STEP`]) a sweep follows: at most
/// about 2.5e7 steps, and where the inputs reach `2 pi 1e6` their doubles are `1e-9` apart,
/// fine against the steps. A longer range is refused before any step is made (the sweep's first
/// item is [`Error::RangeTooLong`]) rather than followed with steps that the doubles of its
/// inputs, or of the path's fraction, can no longer resolve.
pub const MAX_TURNS: f64 = 1e6;

/// The largest step, against the step scale, across which a kink next to an end of the range is
/// taken to lie at that end (and is not listed, see [`SweepOf::past_kink`]): far above the
/// default smallest step (`2^-40`), far below any step a configuration of few halvings stops at.
const END_CORNER: f64 = 1e-9;

/// The inputs' sines and cosines are advanced by rotation (a few units in the last place off
/// libm's) only from a position whose smallest pivot ratio is at least this: there the positions
/// amplify them at most about tenfold, staying within `1e-14` of the loop's size. Nearer a
/// singular position they come from libm, as in a point solve.
const ROTATE_MIN_PIVOT: f64 = 0.1;

/// How far above `SweepConfig::singular_pivot` the first sample's smallest pivot ratio may be
/// for a sweep that cannot take its first step, however small, to have started at a singular
/// position ([`Error::SingularStart`]). Near a limit position the pivot ratio goes as the root
/// of the distance to it, and the smallest step is `2^-max_halvings` of the step scale (about
/// `1e-13` rad at a quarter radian): a start a hair inside the limit (a four-bar's `4e-14` rad,
/// its pivot ratio `1.1e-6`) passes the start's test, but its analogs change over that step by
/// more than any step's prediction allows. It was reported as a branch the sweep cannot stay
/// on, which read as a fault of the mechanism, and `assembly_near` did not pass over it.
const START_PIVOT_MARGIN: f64 = 100.0;

/// Largest distance (radians) of a `Mechanism::CLOSED_FORM_ANGLES` angle from its prediction in
/// an accepted step. A step this long is far too coarse for the prediction anyway; a limit that
/// holds where `max_dist` is not computed (every judged unknown a closed-form angle) or is
/// large (a long predicted change), and that an angle on the wrong turn (2 pi off) always
/// exceeds.
const ANGLE_CAP: f64 = 1.0;

/// A step's prediction (see `Sweep::predict`), kept in the sweep and rewritten every step.
struct Prediction<Q> {
    q: Q,
    /// The predicted slopes at the new point: `dq/dtau`, or with one input `dq/dx` (see
    /// `Sweep::predict`).
    slope1: Q,
    /// How far the solved position may be from `q`, in the unknowns' units: `corrector_rel`
    /// times the largest predicted change of an unknown, plus `corrector_abs` (set only where a
    /// position is judged, see `positions_judged`).
    max_dist: f64,
    /// How far the solved slopes may be from `slope1`, in the unknowns' units: `corrector_rel`
    /// times the largest change of a slope plus a tenth of the largest slope, plus
    /// `corrector_abs` (per unit of the path, or of the input).
    max_slope_err: f64,
    /// The step is longer than the predictor's error bound allows ([`MAX_SLOPE_CHANGE`]).
    long: bool,
}

/// Why a step was not accepted.
enum Outcome {
    Accept,
    Flip,
    Far,
    /// The solve failed (its error is the solve's result).
    Fail,
}

/// A lazy sweep of a compiled mechanism `M` of `N` unknowns, `NI` inputs and `NO` output
/// columns: [`SweepOf`] over [`Compiled`] (see the crate documentation, "Sweeps"). Items are
/// `Result<S, Error>` with `S` the state type (the generated `NameState`, or the flat [`Kin`]).
pub type Sweep<'m, M, S, const N: usize, const NI: usize, const NO: usize> = SweepOf<Compiled<'m, M, N, NI, NO>, S>;

/// A lazy sweep over any [`Kernel`]: a compiled mechanism's ([`Sweep`]) or a mechanism's read
/// at run time. Items are `Result<S, Error>` with `S` the state type (one the kernel's state
/// converts into). The one implementation of the sweep, its events and its table.
///
/// An error ends the sweep: after it, as after the last sample, every item is `None` (the
/// iterator is fused), and [`Iterator::size_hint`] says so; [`SweepOf::run`] and
/// [`SweepOf::table`] asked after it give that error. Until then its upper bound is the
/// samples left and its lower bound zero, since any step may stop the sweep.
pub struct SweepOf<K: Kernel, S> {
    m: K,
    d: K::Dims,
    cfg: SweepConfig,
    path: Path<X<K>>,
    /// `delta[i] delta[j]` of the path's direction, for the curvature of every prediction.
    delta2: <D<K> as Dims>::XX,
    /// The input of the step being made (written in place: no allocation per step).
    x_step: X<K>,
    /// The prediction of the step being made (written in place).
    pred: Prediction<Q<K>>,
    /// The absolute term of the slopes' bound (`corrector_abs`) in the units the judge compares
    /// slopes in: the path's, or with one input the input's (see [`Sweep::predict`]).
    slope_abs: f64,
    samples: usize,
    /// Sample spacing as a fraction of the path, and the step bounds derived from it and the
    /// configuration (computed once: they are needed every step).
    spacing: f64,
    h_max: f64,
    h_min: f64,
    /// The largest step in the inputs' natural scale ([`MAX_INPUT_STEP`]) as a fraction of the
    /// path (infinite for a path of no length).
    h_nat: f64,
    /// `MAX_SLOPE_CHANGE` times one unit of an unknown per unit of input, in the units the
    /// slopes are compared in (see [`Sweep::predict`]); set with `h_nat`.
    slope_floor: f64,
    /// Per unknown, the reciprocal of its unit (the generated one, as [`Metric`] reads it: one
    /// for an angle, its loop's size for a length). The prediction and the judgment measure
    /// each judged unknown's change, distance and slopes in its unit, so that their maxima
    /// weigh a length as an angle and the bounds are the same in any unit of length (see
    /// [`in_unit`]).
    inv_unit: Q<K>,
    /// The attempts a window of the step budget holds (see [`ATTEMPTS_RESERVE`]): the reserve,
    /// and four per step of the largest length that a stride ([`SweepOf::scale`]) takes.
    max_attempts: u64,
    /// Where the window of the step budget under way began, `(sample, tau)`: set when a window
    /// is spent (off the steps' path); a sample's first window begins at the sample before.
    window: (usize, f64),
    next: usize,
    guess: Q<K>,
    /// Whether the first sample may restart (the configuration's `restarts`; the steps' own
    /// configuration, `cfg.newton`, has them off).
    first_restarts: bool,
    /// The first sample's position: the continuation that locates events measures arclength
    /// in the units there (fixed for the sweep, and taken where the sweep is regular: at a
    /// singular position a unit derived from the terms' magnitudes can degenerate).
    first_q: Q<K>,
    /// The last accepted state (`states[at]`, valid once `started`) and the slot the next step
    /// is solved into: an accepted step only flips `at`, where moving the ~180-byte state into
    /// place would copy it at every step (nor is either slot an `Option`, for the same reason).
    states: [KinOf<K>; 2],
    at: bool,
    started: bool,
    tau: f64,
    h: f64,
    signs: DetSigns,
    /// The sines and cosines of the kernel's input arguments, advanced by rotation from step to
    /// step (libm only to re-synchronise: see [`Rotating`]).
    trig: Rotating,
    /// A configuration or range error found by `with_config`, returned by the first `next`.
    invalid: Option<Error>,
    /// A range longer than [`MAX_TURNS`], found by `new` and returned by the first `next`.
    too_long: Option<Error>,
    events: Vec<Event>,
    /// A corner of the path at its start and at its end (within the smallest step), not listed
    /// among the events: the range holds one of its sides only (see [`SweepOf::past_kink`]).
    corners_at_ends: [Option<Event>; 2],
    /// The error that ended the sweep, once it did: what a `run` or a `table` asked after it
    /// says (none of the samples it did not reach is to come).
    stopped_by: Option<Error>,
    done: bool,
    /// `started && !done && invalid.is_none()`: the steady state, where a sample needs one test
    /// of this rather than one of each.
    stepping: bool,
    _s: PhantomData<fn() -> S>,
}

/// The mechanism, the range, the samples taken of those asked for, the events so far and the
/// configuration (not the carried state of the steps).
impl<K: Kernel, S> core::fmt::Debug for SweepOf<K, S> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SweepOf")
            .field("mechanism", &self.m.name())
            .field("from", &self.path.from.as_ref())
            .field("delta", &self.path.delta.as_ref())
            .field("samples", &self.samples)
            .field("taken", &self.next)
            .field("events", &self.events)
            .field("done", &self.done)
            .field("cfg", &self.cfg)
            .finish_non_exhaustive()
    }
}

/// A crossing the trace located, and the point just past it on the smooth continuation.
type CrossingPair<Q> = (CurvePoint<Q>, CurvePoint<Q>);

/// Whether a point `p` the trace from `start` found lies where it can: on the swept path, and
/// within the trace's `reach` of the start (see [`SweepOf::diagnose`]).
fn found_within<Q, X: Store>(
    path: &Path<X>,
    metric: &Metric<Q>,
    start: &CurvePoint<Q>,
    p: &CurvePoint<Q>,
    reach: f64,
) -> bool {
    let slack = 1e-12 * path.len;
    (-slack..=path.len + slack).contains(&p.sigma)
        && (p.sigma - start.sigma).abs() <= (12.0 * reach + 0.25) * metric.sigma
}

/// The event of kind `kind` at the point `p` the sweep's diagnosis located on `path`, on the swept
/// range: one located past an end by no more than the rounding [`found_within`] allows (a limit
/// position or a crossing at `to` itself, located 2e-16 and 2e-13 of the path beyond it) is at
/// that end. Outside, its fraction of the path above 1 and its input past `to`, it read as an
/// event beyond the range that the sweep never reached, and `reachable` gave an end past the
/// range it searched.
fn event_on_path<Q: Store, X: Store>(
    kind: EventKind,
    path: &Path<X>,
    p: &CurvePoint<Q>,
    block: Option<(usize, crate::events::BlockInfo)>,
) -> Event {
    let mut event = curve::event_at(kind, path, p, block);
    if !(0.0..=1.0).contains(&event.tau) {
        event.tau = event.tau.clamp(0.0, 1.0);
        event.x = path.at_tau(event.tau).as_ref().to_vec();
    }
    event
}

/// `Err(Error::NonFinite)` naming the end `what` of a range where a value of `v` is not finite.
pub(crate) fn check_finite<K: Kernel>(what: &'static str, v: &[f64], m: &K) -> Result<(), Error> {
    match v.iter().find(|x| !x.is_finite()) {
        Some(&value) => {
            Err(Error::NonFinite { what: Quantity::Range, name: what.into(), value, at: m.location(&[], None) })
        }
        None => Ok(()),
    }
}

impl<'m, M, S, const N: usize, const NI: usize, const NO: usize> SweepOf<Compiled<'m, M, N, NI, NO>, S>
where
    M: Mechanism<N, NI, NO>,
    S: From<Kin<N, NI, NO>>,
{
    /// A sweep of `samples` equally spaced inputs from `from` to `to` (both included), starting
    /// from `guess` at `from` (the guess picks the assembly mode), with the mechanism's solver
    /// configuration ([`Mechanism::solver_config`]: the defaults, or the one a
    /// [`Configured`](crate::Configured) mechanism carries). The last sample is at
    /// `from + 1 (to - from)`, which may round a unit in the last place off `to`, or more where
    /// `|from|` is far larger than `|to|` (`sweep_at` lands on its inputs exactly). One sample
    /// is the state at `from` alone, with the range to `to` checked as a longer sweep's is (a
    /// range too long for a sweep is refused before any step: a program's test of a range it
    /// means to sweep). More than [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES) intervals
    /// between the samples are [`Error::InvalidArgument`]. An angle parameter beyond the configuration's
    /// [`largest_precise_angle`](crate::NewtonConfig::largest_precise_angle) is refused here
    /// ([`Mechanism::check_param_angles`]), once, not at each sample.
    pub fn new(m: &'m M, from: [f64; NI], to: [f64; NI], samples: usize, guess: [f64; N]) -> Result<Self, Error> {
        m.check_param_angles(&m.solver_config().newton)?;
        SweepOf::over(Compiled(m), from, to, samples, guess)
    }
}

impl<K, S> SweepOf<K, S>
where
    K: Kernel,
    S: From<KinOf<K>>,
{
    /// [`Sweep::new`] over any kernel: `from`, `to` and `guess` of the kernel's sizes (a
    /// mismatch is an `Error::InvalidArgument`). An angle parameter beyond the
    /// [`largest_precise_angle`](crate::NewtonConfig::largest_precise_angle) of the sweep's
    /// configuration ([`Kernel::check_param_angles`]) is the first item's error.
    pub fn over(m: K, from: X<K>, to: X<K>, samples: usize, guess: Q<K>) -> Result<Self, Error> {
        let d = m.dims();
        check_sizes(&m, "a sweep", &[&from, &to], &[&guess])?;
        check_finite("from", from.as_ref(), &m)?;
        check_finite("to", to.as_ref(), &m)?;
        if samples == 0 {
            return Err(Error::InvalidArgument("a sweep needs at least one sample".into()));
        }
        // More than an analysis holds would step for years, and `run` or `table` would keep
        // every state until memory ran out (`usize::MAX` samples ran without end). Counted in
        // intervals, as `Jet::sample` counts them: a turn of `MAX_SAMPLES` samples is swept with
        // its end (`dynamics::turn_states`).
        crate::analysis::check_sample_count("intervals between a sweep's samples", samples - 1)
            .map_err(Error::InvalidArgument)?;
        if m.block_count() > DetSigns::CAPACITY {
            return Err(Error::InvalidArgument(format!(
                "`{}` has {} blocks; a sweep watches the assembly mode of at most {} (split the mechanism)",
                m.name(),
                m.block_count(),
                DetSigns::CAPACITY
            )));
        }
        let path = Path::new(from.clone(), to);
        if !path.len.is_finite() {
            return Err(Error::InvalidArgument(
                "the sweep's range `to - from` overflows (its length is not finite)".into(),
            ));
        }
        if samples > 1 && (path.len.is_nan() || path.len <= 0.0) {
            return Err(Error::InvalidArgument("a sweep with several samples needs `to` different from `from`".into()));
        }
        // The units at the start's guess (once per sweep: a sweep of a few samples, as every
        // stretch of `sweep_at` is, should not pay for more).
        let metric = Metric::at(&m, &path, &from, &guess);
        let too_long = range_too_long(&metric, path.len, || m.location(from.as_ref(), None));
        let spacing = if samples > 1 { 1.0 / (samples - 1) as f64 } else { 1.0 };
        let mut delta2 = d.xx();
        for i in 0..d.ni() {
            for j in 0..d.ni() {
                delta2.set(i, j, path.delta[i] * path.delta[j]);
            }
        }
        let config = m.solver_config();
        let mut sweep = SweepOf {
            m,
            d,
            cfg: SweepConfig::default(),
            x_step: d.x(),
            pred: Prediction { q: d.q(), slope1: d.q(), max_dist: 0.0, max_slope_err: 0.0, long: false },
            path,
            delta2,
            slope_abs: 0.0,
            samples,
            spacing,
            h_max: 0.0,
            h_min: 0.0,
            h_nat: f64::INFINITY,
            slope_floor: 0.0,
            inv_unit: d.q(),
            max_attempts: ATTEMPTS_RESERVE,
            window: (0, 0.0),
            next: 0,
            first_q: guess.clone(),
            guess,
            first_restarts: true,
            states: [d.kin(), d.kin()],
            at: false,
            started: false,
            tau: 0.0,
            h: 0.0,
            signs: DetSigns::default(),
            trig: Rotating::default(),
            invalid: None,
            too_long,
            events: Vec::new(),
            corners_at_ends: [None, None],
            stopped_by: None,
            done: false,
            stepping: false,
            _s: PhantomData,
        };
        sweep.set_natural_bounds(&metric);
        Ok(sweep.with_config(config))
    }

    /// Replaces the configuration.
    ///
    /// An invalid configuration (see [`SweepConfig::validate`]) makes the first item an
    /// [`Error::InvalidArgument`] naming the field.
    pub fn with_config(mut self, cfg: SweepConfig) -> Self {
        match cfg.validate() {
            Ok(()) => {
                self.cfg = cfg;
                // The cache's anchors come from guesses the deferred kernel accepted under the
                // old configuration's bound (`largest_deferred_guess`), which may be larger.
                self.trig.forget_anchors();
                self.first_restarts = cfg.newton.restarts;
                self.cfg.newton.restarts = false;
                self.invalid = None;
                self.set_step_bounds();
            }
            Err(e) => self.invalid = Some(e),
        }
        self.stepping = self.started && !self.done && self.invalid.is_none();
        self
    }

    fn set_step_bounds(&mut self) {
        self.h_max = (self.spacing * self.cfg.max_step).min(self.h_nat);
        self.h_min = self.scale() * 0.5f64.powi(self.cfg.max_halvings.min(i32::MAX as u32) as i32);
        // Four attempts per step a stride needs at the largest step, and the fixed reserve
        // (finite: `h_max` is at least `MIN_MAX_STEP` of the spacing or `h_nat`).
        let steps = (self.scale() / self.h_max).ceil();
        self.max_attempts = ATTEMPTS_RESERVE + if steps.is_finite() { (4.0 * steps).min(1e15) as u64 } else { 0 };
        // A slope in input units is the path's divided by `|delta|` (infinite for a path of no
        // length, which takes no step).
        self.slope_abs =
            if self.d.ni() == 1 { self.cfg.corrector_abs / self.path.delta[0].abs() } else { self.cfg.corrector_abs };
    }

    /// The step scale as a fraction of the path: the sample spacing, or the natural step where
    /// that is shorter.
    fn scale(&self) -> f64 {
        self.spacing.min(self.h_nat)
    }

    /// The natural step bounds ([`MAX_INPUT_STEP`], [`MAX_SLOPE_CHANGE`]) from the units of
    /// `metric`, and the step bounds with them.
    fn set_natural_bounds(&mut self, metric: &Metric<Q<K>>) {
        let input_len = metric.input_len;
        // (A range too long in these units was refused by `new`.)
        self.h_nat = if input_len > 0.0 && input_len.is_finite() { MAX_INPUT_STEP / input_len } else { f64::INFINITY };
        // One unit of an unknown per unit of input, in the slopes' units: per fraction of the
        // path `input_len` units, per unit of a single input that over `|delta|`.
        let per = if self.d.ni() == 1 { input_len / self.path.delta[0].abs() } else { input_len };
        let floor = MAX_SLOPE_CHANGE * per;
        self.slope_floor = if floor.is_finite() { floor } else { 0.0 };
        self.set_units(metric);
        self.set_step_bounds();
    }

    /// [`SweepOf::inv_unit`] from `metric`'s units; an angle's is one, as [`in_unit`] takes it.
    fn set_units(&mut self, metric: &Metric<Q<K>>) {
        for u in 0..self.d.n() {
            // A unit is positive and finite (`Metric`); one so small that its reciprocal
            // overflows (a mechanism of `1e-308` in its unit) is judged in its own unit.
            let w = 1.0 / metric.unit[u];
            self.inv_unit[u] = if w < f64::INFINITY && !is_angle(&self.m, u) { w } else { 1.0 };
        }
    }

    /// Singular positions met so far.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// A corner of the path met at the start of the range and at its end, within the sweep's
    /// smallest step of it, each at the end itself: not among [`SweepOf::events`], where a corner
    /// is one the range passes through. `sweep_at` lists one at an input between two sweeps.
    pub(crate) fn corners_at_ends(&self) -> &[Option<Event>; 2] {
        &self.corners_at_ends
    }

    /// The last accepted state (the last sample, or the last point before a stop). (Not named
    /// `last`: a sweep is an iterator, and method syntax would find `Iterator::last`, which
    /// consumes it.)
    pub fn last_accepted(&self) -> Option<&KinOf<K>> {
        self.started.then_some(self.cur())
    }

    /// The last accepted state.
    #[inline(always)]
    fn cur(&self) -> &KinOf<K> {
        &self.states[usize::from(self.at)]
    }

    /// The last accepted state, to replace it (the first sample, a state past a crossing).
    fn cur_mut(&mut self) -> &mut KinOf<K> {
        &mut self.states[usize::from(self.at)]
    }

    /// The slot the last step was solved into (the state judged last).
    fn spare(&self) -> &KinOf<K> {
        &self.states[usize::from(!self.at)]
    }

    /// Runs the whole sweep: the states up to where it ended, why and where it ended, and the
    /// singular positions met (see [`SweepResult`]).
    ///
    /// Every state is kept: a sweep whose remaining samples' states would take more than
    /// [`MAX_COLLECTED_BYTES`](super::collected::MAX_COLLECTED_BYTES) (1 GiB) is refused before
    /// any step, its result empty and stopped by an [`Error::InvalidArgument`] with the numbers
    /// (where the allocation would abort the process). Iterate such a sweep instead (`for s in
    /// sweep`, or a fold), which keeps only what the caller keeps and has no such bound, or take
    /// fewer samples.
    ///
    /// A sweep already stopped by an error (iterated up to it) gives no states, stopped by that
    /// error, with the events it met: the samples it did not reach are not to come.
    pub fn run(mut self) -> SweepResult<S> {
        if let Some(e) = self.stopped_by.take() {
            return SweepResult::new(Vec::new(), Some(e), self.events);
        }
        let bytes_each = size_of::<S>() + self.cur().heap_bytes();
        let instead = "iterate the sweep instead (`for s in sweep`, or a fold, keeps only what you keep), or take fewer \
                       samples";
        let left = self.samples - self.next;
        if let Err(e) = check_collected("the sweep's `run()`", "states", left, bytes_each, instead) {
            return SweepResult::new(Vec::new(), Some(e), Vec::new());
        }
        // Bounded: a sweep of a huge sample count grows its vector as it goes.
        let mut states = Vec::with_capacity(self.samples.min(1 << 16));
        let mut error = None;
        while let Some(r) = self.next_kin() {
            match r {
                Ok(k) => states.push(S::from(k)),
                Err(e) => {
                    error = Some(e);
                    break;
                }
            }
        }
        SweepResult::new(states, error, self.events)
    }

    /// Runs the whole sweep into a [`Table`] (CSV-ready, named columns, inferred units: see
    /// [`Table::with_units_of`]).
    ///
    /// Every row is kept: a sweep whose remaining samples' rows would take more than
    /// [`MAX_COLLECTED_BYTES`](super::collected::MAX_COLLECTED_BYTES) (1 GiB) is an
    /// [`Error::InvalidArgument`] with the numbers, before any step. Iterate such a sweep instead
    /// (`for s in sweep`, writing each row as it comes), or take fewer samples.
    ///
    /// A sweep already stopped by an error (iterated up to it) gives that error.
    pub fn table(mut self) -> Result<Table, Error> {
        if let Some(e) = self.stopped_by.take() {
            return Err(e);
        }
        let columns = Table::kernel_columns(&self.m);
        // A row is its own vector: the values and the vector's header.
        let bytes_each = size_of::<Vec<f64>>() + columns.len() * size_of::<f64>();
        let instead =
            "iterate the sweep instead (`for s in sweep`, writing each row as it comes), or take fewer samples";
        check_collected("the sweep's `table()`", "rows", self.samples - self.next, bytes_each, instead)?;
        let mut t = Table::new(columns);
        while let Some(k) = self.next_ref() {
            t.push(k?.table_row());
        }
        Ok(t.with_kernel_units(&self.m))
    }

    fn location(&self, x: &[f64], block: Option<usize>) -> Box<Location> {
        self.m.location(x, block)
    }

    /// The prediction for a step of `dt` (a fraction of the path) from `k`, with the analogs
    /// along the path it uses: `slope = q' d` and `curv = d^T q'' d` give the second-order
    /// Taylor prediction `q + slope dt + curv dt^2 / 2` and, for [`Sweep::judge`], the expected
    /// slope at the new point `slope + curv dt` and the bounds of both deviations. Computed once
    /// per step.
    ///
    /// With one input the slopes are taken in the input's units instead (`q'` itself, with the
    /// step `dx = dt d`): the same prediction and the same tests, the slopes and their bound
    /// divided by `|d|`, without the three products by `d` per unknown and step.
    ///
    /// Written into the sweep's own prediction (`pred`), from its last accepted state.
    #[inline(always)]
    fn predict(&mut self, dt: f64) {
        let (mut change, mut slope_change, mut slope) = (0.0f64, 0.0f64, 0.0f64);
        let k = &self.states[usize::from(self.at)];
        let p = &mut self.pred;
        let (d, path, inv_unit) = (self.d, &self.path, &self.inv_unit);
        let ni = d.ni();
        p.q.as_mut().copy_from_slice(k.q());
        // With one input (a constant), `dt` becomes the input's step.
        let dt = if ni == 1 { dt * path.delta[0] } else { dt };
        // A follower is neither predicted (no solve uses its guess) nor judged.
        for &u in self.m.judged() {
            let slope0 = slope_of(d, path, k.dq(u));
            let curv = if ni == 1 {
                k.d2q(u, 0, 0)
            } else {
                let d2 = &self.delta2;
                (0..ni).fold(-0.0, |c, i| (0..ni).fold(c, |c, j| c + k.d2q(u, i, j) * d2.at(i, j)))
            };
            // The slope's change over the step, and the unknown's change by the trapezoid of
            // the two slopes: `dt (slope0 + curv dt / 2)` with one multiplication fewer.
            let turn = curv * dt;
            let s1 = slope0 + turn;
            let du = (0.5 * dt) * (slope0 + s1);
            p.q[u] += du;
            // The maxima in the unknowns' units.
            change = change.max(in_unit(&self.m, inv_unit, u, du.abs()));
            slope_change = slope_change.max(in_unit(&self.m, inv_unit, u, turn.abs()));
            slope = slope.max(in_unit(&self.m, inv_unit, u, slope0.abs()));
            p.slope1[u] = s1;
        }
        let rel = self.cfg.corrector_rel;
        if positions_judged(&self.m) {
            p.max_dist = rel * change + self.cfg.corrector_abs;
        }
        p.max_slope_err = rel * (slope_change + 0.1 * slope) + self.slope_abs;
        p.long = too_long(slope_change, MAX_SLOPE_CHANGE * slope + self.slope_floor);
    }

    /// Judges the state `n` solved from the prediction `p`.
    ///
    /// Positions must land near their prediction (where every judged unknown is an angle a
    /// closed form gives, only within a radian, on the prediction's turn: see
    /// [`positions_judged`]), and the velocity analogs near theirs: a kink
    /// in the analogs means the corrector slid onto another branch through a singular position
    /// (e.g. at a change point) even if the positions are close.
    #[inline(always)]
    fn judge(&self, n: &KinOf<K>, p: &Prediction<Q<K>>) -> Outcome {
        let (mut dist, mut turn, mut slope_err) = (0.0f64, 0.0f64, 0.0f64);
        let nq = n.q();
        // Once per step, not per unknown: a constant for a compiled mechanism, but a run-time
        // model's `judged` and `closed_form_angle` are table lookups.
        let judge_positions = positions_judged(&self.m);
        // Followers are smooth functions of the judged unknowns (see `Mechanism::FOLLOWERS`).
        for &u in self.m.judged() {
            let e = (nq[u] - p.q[u]).abs();
            // Constants after unrolling (see `positions_judged`): where every judged unknown is
            // a closed-form angle, `dist` is not computed and `turn` costs one comparison.
            if judge_positions {
                dist = dist.max(in_unit(&self.m, &self.inv_unit, u, e));
            }
            if self.m.closed_form_angle(u) {
                turn = turn.max(e);
            }
            let off = (slope_of(self.d, &self.path, n.dq(u)) - p.slope1[u]).abs();
            slope_err = slope_err.max(in_unit(&self.m, &self.inv_unit, u, off));
        }
        let health = n.health();
        if !health.det_signs.same_for(&self.signs, self.m.block_count()) {
            Outcome::Flip
        } else if (health.min_pivot < self.cfg.singular_pivot)
            | (judge_positions & (dist > p.max_dist))
            | (slope_err > p.max_slope_err)
            | (turn > ANGLE_CAP)
            | p.long
        {
            // One test of every bound, without a branch per bound (all hold in the usual step):
            // * the pivot: too close to a singular position for the analogs (and thus the branch
            //   identity) to be trusted: within the residual tolerance the solution can slide
            //   onto a crossing branch (told apart from a far step by that state's pivot, should
            //   the step become the last one tried: a separate outcome costs every step an
            //   instruction);
            // * `dist`: a position the corrector took far from its prediction (Newton can
            //   converge to another root); not judged where every judged unknown is a
            //   closed-form angle, see `positions_judged`;
            // * `turn`: an angle the cache advanced from an anchor on another turn (see
            //   `InputTrig::angle`), however large the predicted changes make `max_dist`;
            // * `long`: a step longer than the predictor's error bound (`MAX_SLOPE_CHANGE`).
            Outcome::Far
        } else {
            Outcome::Accept
        }
    }

    /// The first sample, solved from the guess (kept as the last accepted state).
    fn first_sample(&mut self) -> Result<(), Error> {
        let newton = self.cfg.newton.with_restarts(self.first_restarts);
        match self.m.kinematics(&self.path.from, &self.guess, &newton) {
            Ok(k) => {
                self.started = true;
                self.stepping = true;
                self.first_q.as_mut().copy_from_slice(k.q());
                // A length's unit depends on the position (a slide's loop includes the slide):
                // taken again at the solved first sample, not at the caller's guess, which may
                // be far off. (An angle's is one: nothing to take for a sweep of angles.)
                if self.m.judged().iter().any(|&u| !is_angle(&self.m, u)) {
                    let metric = Metric::at(&self.m, &self.path, &self.path.from, &self.first_q);
                    self.set_units(&metric);
                }
                self.signs = k.health().det_signs;
                *self.cur_mut() = k;
                self.h = self.h_max;
                self.next = 1;
                Ok(())
            }
            Err(e) => {
                let e = match e {
                    // Where a sweep stopped (a limit position located to the rounding) the pivot
                    // ratio is below even the point solve's tolerance: the same start as the end
                    // of a reachable range, said as such (see `diagnose`), with the pivot ratio
                    // of the analogs there, which `singular_pivot` is compared with.
                    Error::Singular { at, .. } => {
                        let pivot_ratio = self.start_pivot(&newton);
                        Error::SingularStart { pivot_ratio, singular_pivot: self.cfg.singular_pivot, at }
                    }
                    e => e,
                };
                Err(self.stopped(e))
            }
        }
    }

    /// The smallest pivot ratio of the analogs' factorisations ([`Health::min_pivot`](crate::Health),
    /// the measure `SweepConfig::singular_pivot` is compared with) at the first sample, where its
    /// point solve found the position singular: its positions solved alone, and the analogs
    /// there, or the ratio of the block their factorisation found singular. The point solve's
    /// own ratio is another measure (Newton's factorisations scale their rows by the rows'
    /// magnitudes, a closed form measures its lever), which no `singular_pivot` is compared
    /// with: a slider-crank started at its limit position reported 0 there, "below
    /// `singular_pivot`", whatever `singular_pivot` was. Both are taken with a `singular_tol` of
    /// 0, which judges no pivot singular but a zero one. 0 where the positions are not solved
    /// alone either (not determined there: a rhombus four-bar folded flat, whose coupler closes
    /// the loop at every angle), the Jacobian singular in every measure. Out of the steps' path:
    /// once, at a start that fails.
    #[cold]
    #[inline(never)]
    fn start_pivot(&self, newton: &NewtonConfig) -> f64 {
        let cfg = newton.with_singular_tol(0.0);
        let Ok(q) = self.m.positions(&self.path.from, &self.guess, &cfg) else { return 0.0 };
        match self.m.kinematics_at(&self.path.from, &q, &cfg) {
            Ok(k) => k.health().min_pivot,
            Err(Error::Singular { pivot_ratio, .. }) => pivot_ratio,
            Err(_) => 0.0,
        }
    }

    /// A window of the step budget is spent ([`ATTEMPTS_RESERVE`]): `Ok` where the sweep
    /// advanced by a stride over it (a new window begins here), otherwise the error that stops
    /// it. Off the steps' path: once per `max_attempts` attempts.
    #[cold]
    #[inline(never)]
    fn window_spent(&mut self) -> Result<(), Error> {
        // A sample's first window began at the sample before (`tau` there; later than that only
        // past a crossing that resumed beyond its sample, which counts a little of the way
        // before this sample in its first window).
        let start = if self.window.0 == self.next { self.window.1 } else { (self.next - 1) as f64 * self.spacing };
        let advanced = self.tau - start;
        if advanced >= self.scale() {
            self.window = (self.next, self.tau);
            return Ok(());
        }
        Err(self.out_of_steps(advanced))
    }

    /// The error of a sweep that spent a window of its step budget advancing by `advanced` (of
    /// the path, less than a stride): where it advanced, said so, with what to do.
    #[cold]
    fn out_of_steps(&self, advanced: f64) -> Error {
        let x = self.path.at_tau(self.tau);
        if let Some(e) = self.coarse_error(x.as_ref(), None) {
            return e;
        }
        let n = self.max_attempts;
        let stride = if self.spacing <= self.h_nat {
            "the way to the next sample"
        } else {
            "a quarter of the inputs' unit (a quarter radian of an angle input; the sample spacing where that is \
             shorter)"
        };
        let message = if advanced > 0.0 {
            format!(
                "the sweep advanced too slowly to go on: its last {n} steps (four per step of the largest length, \
                 and a reserve) took it {:.3} % of {stride}, which each such window of steps must cover: its steps \
                 keep being rejected or cut far below their largest length (the solution curve is too rough here \
                 for them); sample more densely (each interval between samples closer than a quarter unit has \
                 {n} steps of its own) or sweep a shorter range about here",
                100.0 * advanced / self.scale()
            )
        } else {
            format!(
                "the sweep made no progress in {n} steps (four per step of the largest length, and a reserve): \
                 its steps keep being rejected or cut to nothing here"
            )
        };
        Error::Branch { message, at: self.location(x.as_ref(), None) }
    }

    /// Ends the sweep: no further sample.
    fn stop(&mut self) {
        self.done = true;
        self.stepping = false;
    }

    /// Ends the sweep with the error `e`, kept for a `run` or a `table` asked after it.
    #[cold]
    fn stopped(&mut self, e: Error) -> Error {
        self.stop();
        self.stopped_by = Some(e.clone());
        e
    }

    /// [`Sweep::next_ref`] outside the steady state: the end, the configuration's error, or the
    /// first sample.
    #[cold]
    fn next_unstarted(&mut self) -> Option<Result<&KinOf<K>, Error>> {
        if self.done || self.next >= self.samples {
            return None;
        }
        if let Some(e) = self.invalid.take().or_else(|| self.too_long.take()) {
            return Some(Err(self.stopped(e)));
        }
        // Once a sweep, under the configuration it runs with (a sweep over any kernel, made by
        // `over` and configured after: the kernel-level algorithms have no other entry).
        if let Err(e) = self.m.check_param_angles(&self.cfg.newton) {
            return Some(Err(self.stopped(e)));
        }
        Some(self.first_sample().map(|()| self.cur()))
    }

    /// The next sample as a flat state (a copy of [`Sweep::next_ref`]'s). Inlined as it is.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn next_kin(&mut self) -> Option<Result<KinOf<K>, Error>> {
        self.next_ref().map(|r| r.cloned())
    }

    /// The next sample, lent: the sweep's own copy of the state, valid until the next call
    /// (reading it where it lies saves copying the state of every sample). The same states as
    /// [`Sweep::next_kin`] and the iterator.
    ///
    /// Always inlined, as [`Sweep::next_kin`] and the iterator's `next` are: a sweep's step is the
    /// body of its caller's loop, and the compiler keeps so large a function out of line when it
    /// may (the iterator's `next` even where a single loop calls it). Out of line, the carried
    /// values and the state go through memory and the caller's reads of the state wait for the
    /// stores just made: measured on the benchmarks' closed-form mechanisms, a `for` loop over a
    /// sweep's items took 1.3x–1.5x the time of the same loop with the step inlined, and about 100
    /// more instructions a sample (the state's copy among them). Not so in a build with debug
    /// assertions, which is not optimised: there a copy of the step at every caller would only slow
    /// the build.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn next_ref(&mut self) -> Option<Result<&KinOf<K>, Error>> {
        if !self.stepping {
            return self.next_unstarted();
        }
        if self.next >= self.samples {
            return None;
        }
        // Through `i64`: one conversion instruction, where `usize` to `f64` takes several (the
        // same value: a sample index is far below 2^53).
        let target = if self.next + 1 == self.samples { 1.0 } else { self.next as i64 as f64 * self.spacing };
        let mut successes = 0u32;
        let mut attempts = 0u64;
        while self.tau < target {
            attempts += 1;
            if attempts > self.max_attempts {
                // A window of the budget spent: going on only where it advanced by a stride.
                if let Err(e) = self.window_spent() {
                    return Some(Err(self.stopped(e)));
                }
                attempts = 1;
            }
            let remaining = target - self.tau;
            // Within a hair of the target, land on it: a full step computed in floating point
            // may fall short by an ulp and leave a needless tiny step.
            let lands = remaining <= self.h * (1.0 + 1e-9);
            let (step, tau_new) = if lands { (remaining, target) } else { (self.h, self.tau + self.h) };
            // Solved into the spare slot and judged there: an accepted state is not moved (every
            // copy of the ~180-byte state is a memcpy on the per-step path).
            self.predict(tau_new - self.tau);
            self.path.at_tau_into(tau_new, &mut self.x_step);
            self.trig.exact(self.cur().health().min_pivot < ROTATE_MIN_PIVOT);
            let spare = usize::from(!self.at);
            let solved =
                self.m.step_into(&self.x_step, &self.pred.q, &self.cfg.newton, &mut self.trig, &mut self.states[spare]);
            let outcome = match &solved {
                Ok(()) => self.judge(&self.states[spare], &self.pred),
                Err(_) => Outcome::Fail,
            };
            match outcome {
                Outcome::Accept => {
                    self.tau = tau_new;
                    self.at = !self.at;
                    successes += 1;
                    if successes >= 2 {
                        self.h = (self.h * 2.0).min(self.h_max);
                    }
                    if lands {
                        // At the target (`tau_new` is `target` itself): the loop's test, known.
                        break;
                    }
                }
                outcome => {
                    successes = 0;
                    self.h = step * 0.5;
                    // The next attempt takes its closed-form angles from libm, on the turns of
                    // its guess: an anchor may have put one a turn away.
                    self.trig.forget_anchors();
                    // Below the doubles' resolution at `tau` a step has no length: taken, it
                    // would be accepted as it stands (the same state), double, fail again, and
                    // never reach `h_min` where that is finer still (a fine sampling or many
                    // halvings, the obstacle late in the range).
                    if self.h < self.h_min || self.tau + self.h == self.tau {
                        // The step cannot be made however small: find out why.
                        let k = self.cur().clone();
                        match self.diagnose(&k, tau_new, target, outcome, solved.err()) {
                            Ok(n) => {
                                // Passed a kink, or a singular crossing (AtSingular::Continue);
                                // `diagnose` set `tau` to where the sweep resumes.
                                self.signs = n.health().det_signs;
                                *self.cur_mut() = n;
                                self.h = self.h_max;
                            }
                            Err(e) => return Some(Err(self.stopped(e))),
                        }
                    }
                }
            }
        }
        self.next += 1;
        Some(Ok(self.cur()))
    }

    /// Where [`SweepOf::diagnose`] traces the curve once more from behind its start: a
    /// well-conditioned point (see `locate::backed_off`), the trace's first step, its reach
    /// (`reach` from `start`) longer by the way back in the input, and the way back along the
    /// curve.
    fn behind(
        &self,
        path: &Path<X<K>>,
        metric: &Metric<Q<K>>,
        start: &CurvePoint<Q<K>>,
        reach: f64,
    ) -> Option<(CurvePoint<Q<K>>, f64, f64, f64)> {
        let (b, way) = locate::backed_off(&self.m, path, metric, start, self.well_pinned(), &self.cfg.newton)?;
        let back = (start.sigma - b.sigma) / metric.sigma;
        Some((b, 0.25 * back, reach + back, way))
    }

    /// The pivot ratio from which a position counts as well pinned for the diagnosis: a
    /// hundred times `singular_pivot`, where the trace's refinement of a crossing can start.
    fn well_pinned(&self) -> f64 {
        100.0 * self.cfg.singular_pivot
    }

    /// A crossing located by the trace from behind `start` (see [`SweepOf::behind`]), with the
    /// point past it, or `None` where that trace finds none within its reach. That reach is not
    /// lengthened where the curve is steep ([`Reach::steep`], as the diagnosis's traces): over the
    /// near-kites swept toward their change point, the crossings located farther than a
    /// millionth of the input from it went from 511 to 557 of 14,150 with it.
    fn crossing_from_behind(
        &self,
        path: &Path<X<K>>,
        metric: &Metric<Q<K>>,
        start: &CurvePoint<Q<K>>,
        reach: f64,
    ) -> Option<CrossingPair<Q<K>>> {
        let (b, ds, reach, _) = self.behind(path, metric, start, reach)?;
        match locate::trace(&self.m, path, metric, &b, ds, Reach::arc(reach), &self.cfg.newton)? {
            Found::Crossing(at, past)
                if found_within(path, metric, start, &at, reach)
                    && crossing::is_root(&self.m, path, metric, &b, &at) =>
            {
                Some((at, past))
            }
            _ => None,
        }
    }

    /// After a crossing: follows the curve from `p` until the Jacobian is well conditioned again
    /// (so the analogs can be trusted) without passing the sample at `target`; sets `tau` there.
    /// `p`'s tangent is in the scaled coordinates of `metric`; `far` are the assembly modes past
    /// the crossing, those of the branch followed on.
    fn resume_past(
        &mut self,
        mut p: CurvePoint<Q<K>>,
        target: f64,
        far: DetSigns,
        metric: &Metric<Q<K>>,
    ) -> Option<KinOf<K>> {
        let path = self.path.clone();
        let newton = self.cfg.newton;
        let end = target * path.len;
        // In the continuation's scaled arclength (see `Metric`).
        let mut ds = 0.01 * self.scale() * path.len / metric.sigma;
        // Whether the sample is still to be landed on: not once a landing failed.
        let mut landing = true;
        for _ in 0..200 {
            // The point past the crossing may itself lie beyond the sample (it is up to eight of
            // the trace's steps on): the sample is landed on, not passed. Resumed there, the
            // sweep gave the state of the point past as the sample's (a refinement 1e-5 past a
            // four-bar's change point returned the state 7e-4 past it, as if at 1e-5).
            if landing && p.sigma >= end {
                if let Some(k) = self.land_on(&p, target, far, metric) {
                    return Some(k);
                }
                landing = false;
            }
            // A sample at the crossing itself (within its band, where no solve pins the branch
            // and the analogs are not defined) cannot be landed on: the first well-conditioned
            // point past it stands for it, at its own input, as before. Also where the curve's
            // step passed it: a sample exactly at a parallelogram's change point (a crank at
            // 180 degrees, sampled every 10) stopped the sweep.
            if let Ok(k) = self.m.kinematics_at(&path.at_sigma(p.sigma), &p.q, &newton)
                && k.health().min_pivot >= self.cfg.singular_pivot * 100.0
            {
                self.tau = p.sigma / path.len;
                return Some(k);
            }
            let next = curve::arc_step(&self.m, &path, metric, &p, ds, &newton)?;
            if landing && next.sigma >= end {
                if let Some(k) = self.land_on(&p, target, far, metric) {
                    return Some(k);
                }
                landing = false;
            }
            p = next;
            // Not beyond the natural step (see `MAX_INPUT_STEP`), in the scaled coordinates.
            ds = (ds * 1.5).min(MAX_INPUT_STEP);
        }
        None
    }

    /// The state at the sample `target`, solved from the point `p` of the curve beside it (its
    /// prediction along the curve's tangent the guess); sets `tau` there. `None` where that state
    /// is not one a step could accept past the crossing: its pivot ratio below
    /// [`SweepConfig::singular_pivot`] (within the crossing's band, where the residual tolerance
    /// no longer pins the branch and the two branches lie closer than the prediction's error), or
    /// its assembly modes not `far`, the far side's (the other branch, or a sample before the
    /// crossing). Landed on there, the sweep gave a state on either branch, and its next step
    /// failed: a Grashof-equal four-bar sampled 2e-8 to 2e-7 rad past its change point stopped
    /// with `NearSingular`, and one sampled 1e-7 before it recorded the crossing twice.
    fn land_on(&mut self, p: &CurvePoint<Q<K>>, target: f64, far: DetSigns, metric: &Metric<Q<K>>) -> Option<KinOf<K>> {
        let guess = p.predicted(target * self.path.len, metric);
        let k = self.m.kinematics(&self.path.at_tau(target), &guess, &self.cfg.newton).ok()?;
        let health = k.health();
        // (A NaN pivot ratio is not pinned.)
        let pinned = health.min_pivot >= self.cfg.singular_pivot;
        if !pinned || !health.det_signs.same_for(&far, self.m.block_count()) {
            return None;
        }
        self.tau = target;
        Some(k)
    }

    /// Explains a step that cannot be made: a kink, a limit position, a singular crossing, or
    /// another failure (`failure`: the solve's error when `outcome` is [`Outcome::Fail`]).
    /// Returns the state past a kink, or past a crossing when configured to continue through it.
    fn diagnose(
        &mut self,
        k: &KinOf<K>,
        tau_new: f64,
        target: f64,
        outcome: Outcome,
        failure: Option<Error>,
    ) -> Result<KinOf<K>, Error> {
        let path = self.path.clone();
        let newton = self.cfg.newton;
        // Where the input's doubles are too coarse for the step, the diagnosis's traces are as
        // coarse: their steps' inputs round away, and a turning crank near 1e17 was taken for a
        // limit position. The failure is the input's, said before any event is looked for.
        if let Some(e) = self.coarse_error(path.at_tau(tau_new).as_ref(), Some(k.health().weakest_block)) {
            return Err(e);
        }
        // An equation whose terms are too small or too large for `f64` is judged nowhere near
        // here: the diagnosis's traces would judge it as the step did, and take the noise of its
        // residual for a crossing (or find no point to trace). Said as it is.
        if let Some(e @ (Error::Underflow { .. } | Error::Overflow { what: Computed::Equation, .. })) = failure {
            return Err(e);
        }
        // A corner of the curve, not a failure: the sweep goes on past it.
        if matches!(outcome, Outcome::Far)
            && let Some(n) = self.past_kink(k, tau_new)
        {
            return Ok(n);
        }
        let weakest = k.health().weakest_block;
        let m = &self.m;
        let block_of = |b: usize| m.block_info(b).map(|info| (b, info));

        // Follow the smooth continuation of the curve by arclength from the last good point: it
        // passes limit positions (the input reverses) and singular crossings (a determinant
        // changes sign) that no step in the input can pass.
        // Arclength in scaled coordinates (see `Metric`): the same steps in any unit of length.
        let metric = Metric::at(&self.m, &path, &path.from, &self.first_q);
        let tangent = curve::tangent_from_analogs(k, &path, &metric);
        let mut q = self.d.q();
        q.as_mut().copy_from_slice(k.q());
        let start = CurvePoint { q, sigma: self.tau * path.len, tangent };
        let ds0 = ((tau_new - self.tau) * path.len).max(1e-9 * path.len) / metric.sigma;
        let reach = (self.scale() * path.len / metric.sigma).max(ds0 * 8.0);
        // What the trace finds lies on the swept path and within its reach of the start: it
        // walks at most `reach` along the curve (each step at most `reach`), a point past a
        // branch point lies at most eight steps beyond, and the crossing's refinement samples
        // within a few twentieths of the input's unit. Farther, the corrector's plane met the
        // solution set elsewhere (near a change point within the rounding, crossings were
        // located radians outside the swept range): no event, and the step's failure is
        // reported as it is.
        let within = |p: &CurvePoint<Q<K>>, reach: f64| found_within(&path, &metric, &start, p, reach);
        // Traced from the last good point, then, where that finds nothing, once more from a
        // well-conditioned point behind it (see `SweepOf::behind`): a sweep whose steps came
        // within a ten-millionth of a change point failed there. A crossing found from a last
        // good point that is itself nearly singular is located again from behind, where the
        // trace's refinement can start (only a crossing: from behind, the curve's turn at a
        // near-kite's change point was taken for a limit position).
        // Each trace: its start, first step, reach along the curve, and the reach in the input
        // that bounds where what it finds may lie. Along a steep curve each walks farther than
        // its reach (see `Reach::steep`): a near-kite's branch beside its change point moves its
        // input a hundred-thousandth per unit of arclength, and sweeps of 361 samples that came
        // within a millionth of the crossing failed there, both traces spent short of it.
        let mut from = Some((start.clone(), ds0, reach, reach));
        let mut backed = false;
        while let Some((start_at, ds, arc, reach)) = from.take() {
            match locate::trace(&self.m, &path, &metric, &start_at, ds, Reach::arc(arc).steep(), &newton) {
                Some(Found::Fold(located) | Found::Crossing(located, _)) if !within(&located, reach) => {}
                // A true limit position is singular; a reversal where the Jacobian is regular is a
                // kink of a non-smooth curve (e.g. through `abs`), reported below as a branch error.
                Some(Found::Fold(fold))
                    if curve::pivot_at(&self.m, &path.at_sigma(fold.sigma), &fold.q)
                        < locate::fold_pivot(&path, &metric, fold.sigma) =>
                {
                    let ev = event_on_path(EventKind::LimitPosition, &path, &fold, block_of(weakest));
                    let at = self.location(&ev.x, Some(weakest));
                    self.events.push(ev);
                    return Err(Error::SweepStopped { kind: EventKind::LimitPosition, at });
                }
                // A crossing is a root of the determinant: where the located point is not one, the
                // trace's sign change was not the crossing's, and the step's failure is reported
                // instead of a wrong event.
                Some(Found::Crossing(at, past)) if crossing::is_root(&self.m, &path, &metric, &start_at, &at) => {
                    // From a last good point itself near the crossing, the refinement cannot
                    // start and the root stands a few millionths off: located again from behind,
                    // and kept where the determinant is nearer zero there. Near-kites' crossings
                    // were located from behind on the near-folded branch past the change point,
                    // 6e-4 of the input off (its transmission angle's sine 2e-4, the first
                    // location's at the rounding): over 14,150 random sweeps toward their change
                    // point, this took the crossings located farther than a millionth from it
                    // from 511 to 389, the farthest from 6.3e-4 to 4.7e-6.
                    let near = k.health().min_pivot < self.well_pinned();
                    let (at, past) = if near && !backed {
                        match self.crossing_from_behind(&path, &metric, &start, reach) {
                            Some(again) if crossing::nearer_root(&self.m, &path, &metric, &start, &again.0, &at) => {
                                again
                            }
                            _ => (at, past),
                        }
                    } else {
                        (at, past)
                    };
                    // The block whose determinant sign differs on the far side.
                    let beyond = self.m.kinematics_at(&path.at_sigma(past.sigma), &past.q, &newton).ok();
                    let flipped =
                        beyond.and_then(|n| n.health().det_signs.first_difference(&self.signs)).unwrap_or(weakest);
                    self.events.push(event_on_path(EventKind::SingularCrossing, &path, &at, block_of(flipped)));
                    // The assembly modes past the crossing: the near side's with the flipped block's
                    // turned over.
                    let mut far = self.signs;
                    far.set_negative(flipped);
                    if self.cfg.at_singular == AtSingular::Continue
                        && let Some(n) = self.resume_past(past, target, far, &metric)
                    {
                        return Ok(n);
                    }
                    let x = self.events[self.events.len() - 1].x.clone();
                    return Err(Error::SweepStopped {
                        kind: EventKind::SingularCrossing,
                        at: self.location(&x, Some(flipped)),
                    });
                }
                _ => {}
            }
            if !backed {
                backed = true;
                // The trace from behind walks the way back to `start` before it goes on, and
                // that way is measured along the curve (the arclength walked back, or the chord
                // to a predicted point), not in the input: where two branches meet at a small
                // angle (a near-kite's change point) the angles swing a radian over a
                // ten-thousandth of the input, and a reach longer only by the input's way back
                // stopped short of the crossing (a sweep of 361 samples failed there in one
                // near-kite of eighteen; with this and the walk back of `locate::backed_off`,
                // one of 250). Only here: crossings located again from behind
                // (`crossing_from_behind`) were located more loosely by the longer walk.
                from = self
                    .behind(&path, &metric, &start, reach)
                    .map(|(b, ds, reach_back, way_back)| (b, ds, reach + way_back, reach_back));
            }
        }

        // Anything else: report the failure where it happened.
        let x = path.at_tau(tau_new);
        Err(match (outcome, failure) {
            (Outcome::Fail, Some(e)) => e,
            // A first sample below `singular_pivot` is a singular start, as that field says,
            // whatever the trial step met: a start 1e-13 rad inside a four-bar's limit position
            // (pivot ratio 2.7e-7) was told it "passes within" one a step on and to lower
            // `singular_pivot`, the advice for a slide brushing its pivot.
            _ if self.tau == 0.0 && k.health().min_pivot < self.cfg.singular_pivot => Error::SingularStart {
                pivot_ratio: k.health().min_pivot,
                singular_pivot: self.cfg.singular_pivot,
                at: self.location(path.from.as_ref(), Some(weakest)),
            },
            (Outcome::Far, _) if self.spare().health().min_pivot < self.cfg.singular_pivot => Error::NearSingular {
                pivot_ratio: self.spare().health().min_pivot,
                singular_pivot: self.cfg.singular_pivot,
                at: self.location(x.as_ref(), Some(weakest)),
            },
            // From a first sample at a singular position (the end of a reachable range, where a
            // sweep that stopped there put it): no step in the input leaves it on one branch,
            // its analogs being the rounding's. Said as such, with what to do instead. So too
            // from one a hair inside it (see `START_PIVOT_MARGIN`).
            _ if self.tau == 0.0 && k.health().min_pivot < START_PIVOT_MARGIN * self.cfg.singular_pivot => {
                Error::SingularStart {
                    pivot_ratio: k.health().min_pivot,
                    singular_pivot: self.cfg.singular_pivot,
                    at: self.location(path.from.as_ref(), Some(weakest)),
                }
            }
            _ => self.coarse_error(x.as_ref(), Some(weakest)).unwrap_or_else(|| {
                let mut message = String::from(
                    "the sweep cannot stay on its branch: however small the step, the solution jumps or its velocity \
                     analogs do (the solution curve is not smooth here, or steps land on another solution)",
                );
                // Where the equations hold a piecewise function, the likeliest cause is one
                // that steps here (a law of zero width): said, with where to look.
                if self.m.piecewise() {
                    message.push_str(
                        "; the equations hold a piecewise function (`floor`, `wrap`, `min`, `max`, `clamp`, \
                         `atan2` or `angle`) of the inputs or unknowns: one that steps here makes the positions \
                         jump (a `clamp((t - t0) / w, 0, 1)` whose width `w` is 0)",
                    );
                }
                Error::Branch { message, at: self.location(x.as_ref(), Some(weakest)) }
            }),
        })
    }

    /// The error of a sweep whose steps fail at inputs `x` too coarse for them (see
    /// [`SweepOf::coarse_input`]), naming the input; `None` where the inputs are fine.
    #[cold]
    fn coarse_error(&self, x: &[f64], block: Option<usize>) -> Option<Error> {
        let (i, apart, step) = self.coarse_input(x)?;
        let name = self.m.input_name(i).to_string();
        Some(Error::InputTooCoarse { walk: "sweep", input: i, name, apart, step, at: self.location(x, block) })
    }

    /// The state past a kink of the solution curve between the last accepted state `k` and the
    /// state the smallest step solved at `tau_new` (the spare slot), with the kink recorded as an
    /// event and `tau` set there; `None` where the step is not across a kink (see [`kink`]): a
    /// state near a singular position, with another determinant sign, past inputs that round,
    /// or a distance its slopes do not explain.
    #[cold]
    fn past_kink(&mut self, k: &KinOf<K>, tau_new: f64) -> Option<KinOf<K>> {
        let n = self.spare();
        let pivot = self.cfg.singular_pivot.max(kink::KINK_PIVOT);
        let regular = k.health().min_pivot >= pivot && n.health().min_pivot >= pivot;
        if !regular || !n.health().det_signs.same_for(&self.signs, self.m.block_count()) {
            return None;
        }
        let x = self.path.at_tau(tau_new);
        if self.coarse_input(x.as_ref()).is_some() {
            return None;
        }
        // In the slopes' parameter (see `predict`): the input's step with one input.
        let dt = tau_new - self.tau;
        let step = if self.d.ni() == 1 { dt * self.path.delta[0] } else { dt };
        let (m, d, path, inv_unit) = (&self.m, self.d, &self.path, &self.inv_unit);
        let sides = m.judged().iter().map(|&u| kink::Side {
            change: in_unit(m, inv_unit, u, n.q()[u] - k.q()[u]),
            slope_before: in_unit(m, inv_unit, u, slope_of(d, path, k.dq(u))),
            slope_after: in_unit(m, inv_unit, u, slope_of(d, path, n.dq(u))),
        });
        if !kink::continuous(sides, step) {
            return None;
        }
        // A state inside the step has one side's slopes at a corner, not a fold's between them
        // (see `kink`): probed at a third and two thirds, should one land on the corner itself.
        // Each is solved from the positions interpolated between the step's ends, not from the
        // last state's: within a hair of a limit position the equations change over the step by
        // less than the solver's tolerance, a guess is taken as it stands, and from the last
        // state's positions the state inside had the last state's slopes, one side's, as a
        // corner's (a slider's single unknown, whose pivot ratio is always 1, recorded kinks
        // within 1e-13 of its limit position before the limit itself).
        let n = n.clone();
        let mut g = self.d.q();
        for frac in [1.0 / 3.0, 2.0 / 3.0] {
            for (gu, (&a, &b)) in g.as_mut().iter_mut().zip(k.q().iter().zip(n.q())) {
                *gu = a + frac * (b - a);
            }
            let inside = self.m.kinematics(&self.path.at_tau(self.tau + frac * dt), &g, &self.cfg.newton).ok()?;
            let (m, d, path, inv_unit) = (&self.m, self.d, &self.path, &self.inv_unit);
            let slope = |s: &KinOf<K>, u: usize| in_unit(m, inv_unit, u, slope_of(d, path, s.dq(u)));
            let slopes: Vec<kink::Slopes> = m
                .judged()
                .iter()
                .map(|&u| kink::Slopes { before: slope(k, u), after: slope(&n, u), inside: slope(&inside, u) })
                .collect();
            if !inside.health().det_signs.same_for(&self.signs, m.block_count()) || !kink::one_sided(&slopes) {
                return None;
            }
        }
        // A corner within the smallest step of an end of the range (at most `END_CORNER` of the
        // step scale: a configuration of few halvings brackets it no finer, and lists it as any
        // other) lies at that end, and the range holds one of its sides only: not a corner of
        // the path swept. Which side's analogs the state at the corner carries is the equations'
        // own choice (`abs` takes its derivative at 0 as +1), and whether a step met the jump
        // went by it: a sweep from the corner listed a kink a hair inside one way and none the
        // other, and so did a sweep to it. Kept aside at the end itself: a corner at an input of
        // `sweep_at` lies between two of its sweeps.
        let fine = dt <= END_CORNER * self.scale();
        let end = if fine && self.tau == 0.0 {
            Some((0, self.path.from.as_ref().to_vec(), k.q().to_vec()))
        } else if fine && tau_new == 1.0 {
            Some((1, x.as_ref().to_vec(), n.q().to_vec()))
        } else {
            None
        };
        match end {
            Some((end, x, q)) => {
                let tau = end as f64;
                self.corners_at_ends[end] = Some(Event { kind: EventKind::Kink, x, tau, q, block: None });
            }
            None => {
                let (x, q) = (x.as_ref().to_vec(), n.q().to_vec());
                self.events.push(Event { kind: EventKind::Kink, x, tau: tau_new, q, block: None });
            }
        }
        self.tau = tau_new;
        Some(n)
    }

    /// [`Path::coarse_input`] against the samples' spacing.
    #[cold]
    fn coarse_input(&self, x: &[f64]) -> Option<(usize, f64, f64)> {
        let intervals = self.samples.checked_sub(1).filter(|&n| n > 0)? as f64;
        self.path.coarse_input(x, |di| di / intervals)
    }
}

/// [`Error::RangeTooLong`] where a path of length `len` (in the path's parameter) measured by
/// `metric` is more than [`MAX_TURNS`] turns of its inputs, located `at`: a sweep and a trace
/// follow no longer one.
pub(crate) fn range_too_long<Q>(metric: &Metric<Q>, len: f64, at: impl FnOnce() -> Box<Location>) -> Option<Error> {
    let turns = if len > 0.0 { metric.input_len / std::f64::consts::TAU } else { 0.0 };
    // Within `1e-10` of the limit, the rounding of inputs given as the limit (a million turns
    // in degrees, converted to radians; the command line's span allowed, written to eight
    // significant digits within `1e-11`) is not refused.
    let over = turns > MAX_TURNS * (1.0 + 1e-10) || turns.is_nan();
    over.then(|| Error::RangeTooLong { turns, max_turns: MAX_TURNS, at: at() })
}

/// Whether a judged unknown of `m` is not a closed-form angle ([`Kernel::closed_form_angle`]),
/// or the positions may jump ([`Kernel::piecewise`]): then the distance of every judged
/// position from its prediction is tested (each in its unit, the angles' too); otherwise not.
/// A constant after inlining for a compiled mechanism.
///
/// A closed-form angle needs no such test. Its block's equations have two roots a turn (two
/// intersections, mirror images of each other: a dyad's elbow up and down, a rod on either
/// side of its slide) whose Jacobian determinants have opposite signs, or one (a polar
/// angle). Given the assembly mode, the determinant's sign (tested first, `Flip`), and the
/// turn (the angle within [`ANGLE_CAP`] of its prediction, tested with the far bounds), the
/// angle is therefore the one root the smooth continuation reaches, however far the
/// prediction was: nothing for a distance test to find. What else a step can do wrong is
/// tested as before: a root past a singular position where the sign does not change (a kink:
/// the slopes' test), a step across a limit position (no root: the solve fails) or beyond the
/// gap after it (the slope-change bound, `long`). The prediction still picks the branch and
/// the turn; those tests judge what it picked.
///
/// That argument takes the equations to be continuous in the inputs. Through a piecewise
/// function (`floor`, `wrap`, `clamp` of an infinite argument, the cut of `atan2`) they may
/// step between two samples, the velocity analogs alike on both sides (a cam law of zero
/// width, its follower stepping from one dwell to the next): only the distance from the
/// prediction tells, so there it is tested, and the jump stops the sweep (however small its
/// steps, the positions land off their prediction) instead of passing unseen.
#[inline(always)]
fn positions_judged<K: Kernel>(m: &K) -> bool {
    m.piecewise() || m.judged().iter().any(|&u| !m.closed_form_angle(u))
}

/// `v`, a change, distance or slope of unknown `u` as the kernel gives it, measured in `u`'s
/// unit (times `inv_unit[u]`, see [`SweepOf::inv_unit`]). An angle's unit is one radian: its
/// value as it is, with no product (constants after unrolling for a compiled mechanism, so that
/// a sweep whose judged unknowns are all angles pays nothing).
#[inline(always)]
fn in_unit<K: Kernel>(m: &K, inv_unit: &Q<K>, u: usize, v: f64) -> f64 {
    if is_angle(m, u) { v } else { v * inv_unit[u] }
}

/// Whether a predicted slope change `turn` exceeds `bound`, or either is NaN: one comparison.
/// (`f64::max` drops a NaN, so the maxima in `turn` and `bound` are NaN only where the step or
/// the floor is.)
#[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what makes a NaN too long
#[inline(always)]
fn too_long(turn: f64, bound: f64) -> bool {
    !(turn <= bound)
}

/// The slope along the path of an unknown with velocity analogs `dq`: `dq d`, or with one
/// input `dq` itself (see [`Sweep::predict`]). Sums start from -0.0, the additive identity: the
/// first addition folds away (from 0.0 it is an `addsd` per sum, which `0.0 + -0.0 = 0.0`
/// keeps).
#[inline(always)]
fn slope_of<D: Dims>(d: D, path: &Path<D::X>, dq: &[f64]) -> f64 {
    let ni = d.ni();
    if ni == 1 { dq[0] } else { (0..ni).fold(-0.0, |s, i| s + dq[i] * path.delta[i]) }
}

impl<K, S> Iterator for SweepOf<K, S>
where
    K: Kernel,
    S: From<KinOf<K>>,
{
    type Item = Result<S, Error>;

    /// Inlined as [`Sweep::next_ref`] is.
    #[cfg_attr(debug_assertions, inline)]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn next(&mut self) -> Option<Self::Item> {
        self.next_kin().map(|r| r.map(S::from))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        // A sweep stopped by an error has no item left, whatever samples it did not reach.
        let left = if self.done { 0 } else { self.samples.saturating_sub(self.next) };
        (0, Some(left))
    }
}

/// After its last sample or an error, `next` is `None` for ever (see [`SweepOf`]).
impl<K, S> std::iter::FusedIterator for SweepOf<K, S>
where
    K: Kernel,
    S: From<KinOf<K>>,
{
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::demo::SliderCrank;
    use crate::events::BlockInfo;
    use crate::kin::Jac;
    use crate::solvers::newton::{NewtonConfig, SolveReport};
    use std::borrow::Cow;

    /// A hand-written mechanism claiming more blocks than the determinant signs can track.
    struct TooManyBlocks(SliderCrank);

    const BLOCK: BlockInfo = BlockInfo::borrowed(&[Cow::Borrowed("x")], &[Cow::Borrowed("rod")], false);

    impl Mechanism<1, 1, 1> for TooManyBlocks {
        const NAME: &'static str = "TooManyBlocks";
        const PARAMS: &'static [&'static str] = SliderCrank::PARAMS;
        const INPUTS: [&'static str; 1] = SliderCrank::INPUTS;
        const UNKNOWNS: [&'static str; 1] = SliderCrank::UNKNOWNS;
        const EQUATIONS: [&'static str; 1] = SliderCrank::EQUATIONS;
        const OUTPUTS: [&'static str; 1] = SliderCrank::OUTPUTS;
        const BLOCKS: &'static [BlockInfo] = &[BLOCK; DetSigns::CAPACITY + 1];

        fn param_values(&self) -> Vec<f64> {
            self.0.param_values()
        }
        fn guess_flat(&self, x: &[f64; 1]) -> [f64; 1] {
            self.0.guess_flat(x)
        }
        fn position_flat(
            &self,
            x: &[f64; 1],
            g: &[f64; 1],
            c: &NewtonConfig,
        ) -> Result<([f64; 1], SolveReport), Error> {
            self.0.position_flat(x, g, c)
        }
        fn kinematics_flat(&self, x: &[f64; 1], g: &[f64; 1], c: &NewtonConfig) -> Result<Kin<1, 1, 1>, Error> {
            self.0.kinematics_flat(x, g, c)
        }
        fn kinematics_at_flat(&self, x: &[f64; 1], q: &[f64; 1], c: &NewtonConfig) -> Result<Kin<1, 1, 1>, Error> {
            self.0.kinematics_at_flat(x, q, c)
        }
        fn outputs_flat(&self, x: &[f64; 1], q: &[f64; 1]) -> [f64; 1] {
            self.0.outputs_flat(x, q)
        }
        fn jacobian_flat(&self, x: &[f64; 1], q: &[f64; 1]) -> Jac<1, 1> {
            self.0.jacobian_flat(x, q)
        }
    }

    /// The lent states are the iterator's, sample by sample, and the end is the same.
    #[test]
    fn lent_states_are_the_iterated_ones() {
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let g = m.guess_flat(&[0.0]);
        let owned: Vec<Kin<1, 1, 1>> =
            Sweep::<_, Kin<1, 1, 1>, 1, 1, 1>::new(&m, [0.0], [6.0], 200, g).unwrap().map(Result::unwrap).collect();
        let mut sweep = Sweep::<_, Kin<1, 1, 1>, 1, 1, 1>::new(&m, [0.0], [6.0], 200, g).unwrap();
        let mut lent = Vec::new();
        while let Some(k) = sweep.next_ref() {
            lent.push(*k.unwrap());
        }
        assert_eq!(owned.len(), 200);
        assert_eq!(lent.len(), 200);
        for (a, b) in owned.iter().zip(&lent) {
            assert_eq!((a.x, a.q, a.dq, a.d2q, a.out), (b.x, b.q, b.dq, b.d2q, b.out));
        }
    }

    /// A sweep of `10^8` intervals (allowed: `analysis::MAX_SAMPLES`) whose states would take
    /// tens of GB is refused by `run` and `table` before any step, saying so and what to do;
    /// iterated, the same sweep steps.
    #[test]
    fn collecting_a_sweep_beyond_the_memory_budget_is_refused_up_front() {
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let g = m.guess_flat(&[0.0]);
        let samples = crate::analysis::MAX_SAMPLES + 1;
        let sweep = || Sweep::<_, Kin<1, 1, 1>, 1, 1, 1>::new(&m, [0.0], [6.0], samples, g).unwrap();
        let run = sweep().run();
        assert!(run.states.is_empty() && run.events.is_empty());
        let err = run.into_result().expect_err("refused");
        let msg = err.to_string();
        assert!(matches!(err, Error::InvalidArgument(_)), "{err:?}");
        let each = size_of::<Kin<1, 1, 1>>();
        for what in [format!("{samples} states of {each} bytes"), "`for s in sweep`".into(), "fewer samples".into()] {
            assert!(msg.contains(&what), "{what:?} not in {msg}");
        }
        let err = sweep().table().expect_err("refused");
        assert!(matches!(&err, Error::InvalidArgument(msg) if msg.contains(&format!("{samples} rows"))), "{err}");
        // Streaming is not bounded by the budget.
        let first: Vec<_> = sweep().take(3).map(Result::unwrap).collect();
        assert_eq!(first.len(), 3);
        // Once most of a sweep is iterated, what remains is collected.
        let mut s = Sweep::<_, Kin<1, 1, 1>, 1, 1, 1>::new(&m, [0.0], [6.0], 201, g).unwrap();
        s.by_ref().take(101).for_each(|k| assert!(k.is_ok()));
        assert_eq!(s.run().into_result().unwrap().len(), 100);
    }

    /// Under the budget a sweep collects every sample, into states and into a table.
    #[test]
    fn a_sweep_within_the_memory_budget_collects() {
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let g = m.guess_flat(&[0.0]);
        let sweep = || Sweep::<_, Kin<1, 1, 1>, 1, 1, 1>::new(&m, [0.0], [6.0], 200, g).unwrap();
        assert_eq!(sweep().run().into_result().unwrap().len(), 200);
        assert_eq!(sweep().table().unwrap().rows.len(), 200);
    }

    /// Beyond 256 blocks a change of assembly mode could go unseen: such a sweep is refused.
    #[test]
    fn a_sweep_of_more_blocks_than_the_signs_track_is_refused() {
        let m = TooManyBlocks(SliderCrank { r: 1.0, l: 3.0, e: 0.5 });
        let g = m.guess_flat(&[0.0]);
        let err = Sweep::<_, Kin<1, 1, 1>, 1, 1, 1>::new(&m, [0.0], [1.0], 3, g).expect_err("refused");
        assert!(matches!(&err, Error::InvalidArgument(msg) if msg.contains("257 blocks")), "{err}");
        // The same mechanism with its real single block sweeps.
        assert!(Sweep::<_, Kin<1, 1, 1>, 1, 1, 1>::new(&m.0, [0.0], [1.0], 3, g).is_ok());
    }
}
