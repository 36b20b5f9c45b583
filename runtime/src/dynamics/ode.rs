//! The explicit Runge–Kutta method of Dormand and Prince, order 5 with an embedded order-4
//! error estimate, adaptive steps, and Shampine's order-4 dense output (Hairer, Nørsett and
//! Wanner, *Solving Ordinary Differential Equations I*, section II.5 and II.6), on fixed-size
//! state arrays.
//!
//! Why not a crate: the established pure-Rust integrators either pin another nalgebra major
//! version (compiling a second copy of it into every build of the workspace) or take a
//! right-hand side that cannot fail, whereas here every evaluation solves the kinematics, which
//! fails at a limit or singular position and must stop the integration with that typed error.
//! The method is short; it works on `[f64; D]` so a step allocates nothing, and it is tested
//! against closed-form solutions in `tests/dynamics/simulation.rs`.

use super::error::DynamicsError;

/// Tolerances and limits of [`dopri5`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct OdeConfig {
    /// Relative tolerance per step: more than [`MIN_RTOL`] (ten units of rounding), as Hairer's
    /// `DOPRI5` asks, so that a step's error can be told from the rounding of the state.
    pub rtol: f64,
    /// Absolute tolerance per step (in the units of the state).
    pub atol: f64,
    /// Largest step (infinity for none).
    pub h_max: f64,
    /// Most steps (accepted and rejected) before [`DynamicsError::TooManySteps`] (default ten
    /// million). A recorded run ([`Simulation::run`](super::Simulation::run)) keeps each accepted
    /// step, 96 bytes: at most 0.96 GB at the default, spent before the error where the span is
    /// beyond the budget. A run that needs only what passes keeps nothing
    /// ([`Simulation::run_steps`](super::Simulation::run_steps)).
    pub max_steps: usize,
}

/// The smallest relative tolerance [`dopri5`] accepts (exclusive): ten units of rounding
/// (Hairer, Nørsett and Wanner's `DOPRI5` refuses no more than that, "tolerances are too small").
/// Below it, with an absolute tolerance as small, the error estimate is the rounding of the
/// state, which no step shortens: a smooth motion was stopped at its start as a singular one
/// ("is this a limit position?") or as a component too large to change ("start from a smaller
/// value"), both at `1e-20` and `1e-300`.
pub const MIN_RTOL: f64 = 10.0 * f64::EPSILON;

impl Default for OdeConfig {
    fn default() -> Self {
        OdeConfig { rtol: 1e-10, atol: 1e-10, h_max: f64::INFINITY, max_steps: 10_000_000 }
    }
}

impl OdeConfig {
    /// Sets [`OdeConfig::rtol`] and [`OdeConfig::atol`].
    pub fn with_tolerances(mut self, rtol: f64, atol: f64) -> Self {
        self.rtol = rtol;
        self.atol = atol;
        self
    }
    /// Sets [`OdeConfig::h_max`].
    pub fn with_h_max(mut self, h_max: f64) -> Self {
        self.h_max = h_max;
        self
    }
    /// Sets [`OdeConfig::max_steps`].
    pub fn with_max_steps(mut self, n: usize) -> Self {
        self.max_steps = n;
        self
    }
}

/// One accepted step, with its dense-output interpolant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DenseStep<const D: usize> {
    /// Start of the step.
    pub t0: f64,
    /// Step size.
    pub h: f64,
    /// Shampine's interpolation coefficients, the states at both ends first: `y0`, `y1`, then
    /// the three of the correction (see `dense`).
    r: [[f64; D]; 5],
}

impl<const D: usize> DenseStep<D> {
    /// The state at `t` inside the step (order-4 accurate; exact at both ends: `at(t0)` is
    /// the state the step started from and `at(t1())` the state it reached, to the last bit).
    ///
    /// The interpolant `y0 + s dy + s (1 - s) P(s)` (`s` the fraction of the step, `dy = y1 -
    /// y0`) is evaluated from the nearer end: in the step's second half as `y1 - (1 - s) (dy -
    /// s P(s))`, with `1 - s` taken from the time left to `t1()`. From `y0` alone the end came
    /// out as `y0 + dy`, which rounds off `y1` (where the two differ in magnitude or sign), and
    /// `s` at `t1()` as `(t0 + h - t0) / h`, which rounds off 1: most steps of a harmonic
    /// oscillator ended off the state they reached, by up to a few `1e-15`.
    pub fn at(&self, t: f64) -> [f64; D] {
        let s = (t - self.t0) / self.h;
        let r = &self.r;
        let mut y = [0.0; D];
        if s <= 0.5 {
            let s1 = 1.0 - s;
            for i in 0..D {
                let dy = r[1][i] - r[0][i];
                y[i] = r[0][i] + s * (dy + s1 * (r[2][i] + s * (r[3][i] + s1 * r[4][i])));
            }
        } else {
            // Zero at `t1()` exactly, whatever `t0 + h` rounded to.
            let s1 = (self.t1() - t) / self.h;
            let s = 1.0 - s1;
            for i in 0..D {
                let dy = r[1][i] - r[0][i];
                y[i] = r[1][i] - s1 * (dy - s * (r[2][i] + s * (r[3][i] + s1 * r[4][i])));
            }
        }
        y
    }

    /// End of the step.
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }
}

const C: [f64; 5] = [1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0];
const A2: [f64; 1] = [1.0 / 5.0];
const A3: [f64; 2] = [3.0 / 40.0, 9.0 / 40.0];
const A4: [f64; 3] = [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0];
const A5: [f64; 4] = [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0];
const A6: [f64; 5] = [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0];
/// Weights of the order-5 solution (k2 has weight 0).
const B: [f64; 6] = [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0];
/// Error weights (difference of the order-5 and order-4 solutions), k1 ..= k7.
const E: [f64; 7] =
    [71.0 / 57600.0, 0.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0];
/// Shampine's dense-output weights, k1 ..= k7.
const DENSE: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// `y + h sum_s a_s k_s`.
#[inline]
fn combine<const D: usize>(y: &[f64; D], h: f64, a: &[f64], k: &[[f64; D]; 7]) -> [f64; D] {
    let mut out = *y;
    for i in 0..D {
        let mut s = 0.0;
        for (j, aj) in a.iter().enumerate() {
            s += aj * k[j][i];
        }
        out[i] += h * s;
    }
    out
}

/// Weighted RMS norm of `v` with scales `atol + rtol max(|y0|, |y1|)`: finite wherever the
/// norm is. Where the squares of the ratios overflow (a derivative beyond 1e154 of its
/// tolerance's scale) or underflow, the same norm is taken of the ratios over the largest: an
/// overflowing norm made the first step `0.01 / inf = 0`, a "singular motion" at the start of a
/// motion that is merely fast.
pub(super) fn norm<const D: usize>(v: &[f64; D], y0: &[f64; D], y1: &[f64; D], cfg: &OdeConfig) -> f64 {
    let ratio = |i: usize| v[i] / (cfg.atol + cfg.rtol * y0[i].abs().max(y1[i].abs()));
    let s: f64 = (0..D).map(|i| ratio(i).powi(2)).sum();
    if s.is_nan() || (s.is_finite() && s >= f64::MIN_POSITIVE) {
        return (s / D as f64).sqrt();
    }
    let big = (0..D).fold(0.0f64, |m, i| m.max(ratio(i).abs()));
    if !(big > 0.0 && big.is_finite()) {
        return big;
    }
    let scaled: f64 = (0..D).map(|i| (ratio(i) / big).powi(2)).sum();
    big * (scaled / D as f64).sqrt()
}

/// Integrates `y' = f(t, y)` from `(t0, y0)` to `t_end > t0`. After every accepted step,
/// `on_step(step, y_end)` is called; it returns `true` to stop there. Returns the time and the
/// state reached. An error of `f` or `on_step` stops the integration and is returned, except
/// where `f` fails at a stage or end of a step that the step threw far off the motion (every
/// component far from the tangent at the accepted state: a step too large for the motion),
/// which rejects the step for a smaller one, as a state that is not finite does (here every
/// component is judged; a simulation judges a failed kinematic solve on the input's angle
/// alone, on which the solve depends). A step longer than the last one accepted (the error
/// control's guess, grown from that step's estimate) whose stage or end fails is first retried
/// at the last accepted length, before the failure is judged: a grown step's trial can land
/// past a position the motion never reaches, not far enough from its tangent to count as thrown
/// off. A step that cannot change a component of the state by a change larger than the
/// absolute tolerance (the component's value is too large to register it), once the error
/// control no longer lengthens the steps at its largest rate, is
/// [`DynamicsError::CannotAdvance`].
/// A step that collapses below the resolution of the time where it is (a few units in the last
/// place of `t`, whatever the span) is [`DynamicsError::StepTooSmall`]; a span that needs more
/// than [`OdeConfig::max_steps`] steps is [`DynamicsError::TooManySteps`]. A start time, end
/// time or tolerance out of range, or a state or derivative at the start that is not finite,
/// is [`DynamicsError::BadValue`].
pub fn dopri5<const D: usize>(
    f: impl FnMut(f64, &[f64; D]) -> Result<[f64; D], DynamicsError>,
    t0: f64,
    y0: [f64; D],
    t_end: f64,
    cfg: &OdeConfig,
    on_step: impl FnMut(&DenseStep<D>, &[f64; D]) -> Result<bool, DynamicsError>,
) -> Result<(f64, [f64; D]), DynamicsError> {
    dopri5_judged(f, |_| [true; D], t0, y0, t_end, cfg, on_step)
}

/// [`dopri5`], where a failed evaluation is judged thrown off the motion on the components
/// `depends(error)` marks alone: those the evaluation that failed with `error` depends on. A
/// simulation's kinematic solve depends on the position, not on the speed: a trial position
/// far from its tangent was thrown off by a step too large, whatever the trial speed (judged
/// on both, a step of a loose tolerance that threw the position of a swinging crank past its
/// limit, away from where it was heading, ended the run there with the mechanism said not to
/// assemble, at a position the motion never nears).
pub(crate) fn dopri5_judged<const D: usize>(
    mut f: impl FnMut(f64, &[f64; D]) -> Result<[f64; D], DynamicsError>,
    depends: impl Fn(&DynamicsError) -> [bool; D],
    t0: f64,
    y0: [f64; D],
    t_end: f64,
    cfg: &OdeConfig,
    mut on_step: impl FnMut(&DenseStep<D>, &[f64; D]) -> Result<bool, DynamicsError>,
) -> Result<(f64, [f64; D]), DynamicsError> {
    check_config(t0, t_end, cfg)?;
    // A start not finite is no motion to integrate: every step was rejected until it fell
    // below the time's resolution, reported as a singular motion at `t0`.
    let bad_start = |what, v: &[f64; D]| match v.iter().find(|v| !v.is_finite()) {
        Some(&value) => Err(DynamicsError::BadValue { what, value, why: "must be finite" }),
        None => Ok(()),
    };
    bad_start("initial state", &y0)?;
    let (mut t, mut y) = (t0, y0);
    let mut k = [[0.0; D]; 7];
    k[0] = f(t, &y)?;
    bad_start("derivative at the start", &k[0])?;
    // The derivative's size in the tolerances: beyond f64 it leaves no step to start with (the
    // first step would be `0.01 / inf = 0`, a "singular motion" at the start).
    let d1 = norm(&k[0], &y, &y, cfg);
    if d1.is_infinite() {
        let value = k[0].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        return Err(DynamicsError::BadValue {
            what: "derivative at the start",
            value,
            why: "is beyond the range of f64 against the tolerances: express the model in other units",
        });
    }
    // At least twice the time's resolution at the start (and within the span, which is longer
    // than that: `check_config`): a millionth of a span of subnormal times (`--time 1e-320`)
    // was a first step below it, or 0, and a motion with nothing singular about it was reported
    // singular at its start.
    let first = initial_step(&y, d1, t_end - t0, cfg).max(2.0 * step_floor(t0, t0));
    let mut h = first.min(cfg.h_max).min(t_end - t0);
    // The last accepted step's length (none yet): a longer step is the error control's guess.
    let mut accepted_h = f64::INFINITY;
    for _ in 0..cfg.max_steps {
        // The step ends the span where it reaches its end or falls short of it by no more than
        // the time's rounding there: the sliver such a step left (steps of `h_max` summing a few
        // units in the last place short of a multiple of it, 1.0069999999999997 for 1.007) was
        // a step below `step_floor`, and a smooth motion was reported singular at its end. The
        // last step is then longer than the one proposed by at most that rounding.
        let last = t + h >= t_end - step_floor(t0, t_end);
        if last {
            h = t_end - t;
        }
        if h <= step_floor(t0, t) {
            return Err(DynamicsError::StepTooSmall { t, h });
        }
        // The stages and the step's end are trial states: where one fails that the step threw
        // off the motion (see `thrown_off`), the step was too large, and a smaller one may keep
        // inside the range where `f` holds; any other failure is the motion's own.
        let mut failed = None;
        for (s, a) in [&A2[..], &A3, &A4, &A5, &A6].into_iter().enumerate() {
            let trial = combine(&y, h, a, &k);
            match f(t + C[s] * h, &trial) {
                Ok(ks) => k[s + 1] = ks,
                Err(e) => {
                    failed = Some((trial, C[s] * h, e));
                    break;
                }
            }
        }
        if let Some((trial, dt, e)) = failed {
            // A grown step is retried at the length the error control accepted last.
            if h > accepted_h {
                h = accepted_h;
                continue;
            }
            if thrown_off(&trial, &y, dt, &k[0], cfg, depends(&e)) {
                h *= 0.2;
                continue;
            }
            return Err(e);
        }
        let y1 = combine(&y, h, &B, &k);
        // A state that overflows is no step (the error norm can miss it: an infinite state
        // makes its own scale infinite); a smaller one may stay finite.
        if !y1.iter().all(|v| v.is_finite()) {
            h *= 0.2;
            continue;
        }
        let t1 = if last { t_end } else { t + h };
        k[6] = match f(t1, &y1) {
            Ok(k6) => k6,
            Err(_) if h > accepted_h => {
                h = accepted_h;
                continue;
            }
            Err(e) if thrown_off(&y1, &y, h, &k[0], cfg, depends(&e)) => {
                h *= 0.2;
                continue;
            }
            Err(e) => return Err(e),
        };
        let err = norm(&combine(&[0.0; D], h, &E, &k), &y, &y1, cfg);
        if !err.is_finite() {
            h *= 0.2;
            continue;
        }
        let grow = if err == 0.0 { MAX_GROWTH } else { (0.9 * err.powf(-0.2)).clamp(0.2, MAX_GROWTH) };
        if err > 1.0 {
            h *= grow.min(1.0);
            continue;
        }
        // A component the step should move by more than the absolute tolerance but that stays
        // where it is: its value is so large that the change is below the spacing of f64
        // numbers there. Its error looks small (relative to the huge value), so the step would
        // be accepted and the component would never move. Not while the step is still growing
        // at the largest rate towards the length the tolerances allow (not the last step, not
        // at the largest step): a first step taken from a tiny absolute tolerance (a start at
        // rest, or a speed of 0, at an `atol` of 1e-20) is many orders of magnitude shorter than
        // that, and a change it loses is gained a few steps later. Taken as stuck there, a
        // plain oscillator at `rtol` 1e-10 and `atol` 1e-20 stopped at t = 3e-11.
        let change = combine(&[0.0; D], h, &B, &k);
        let growing = !last && grow >= MAX_GROWTH && h < cfg.h_max;
        if let Some(i) = (0..D).find(|&i| !growing && y1[i] == y[i] && change[i].abs() > cfg.atol) {
            return Err(DynamicsError::CannotAdvance { t, component: i, value: y[i], change: change[i] });
        }
        let step = dense(t, h, &y, &y1, &k);
        (t, y) = (t1, y1);
        k[0] = k[6];
        if on_step(&step, &y)? || last {
            return Ok((t, y));
        }
        accepted_h = h;
        h = (h * grow).min(cfg.h_max);
    }
    Err(DynamicsError::TooManySteps { steps: cfg.max_steps, t, t_end })
}

/// The largest factor by which one accepted step grows the next (the error control's bound,
/// reached where the error estimate is far below the tolerances).
const MAX_GROWTH: f64 = 5.0;

/// Whether a trial state `trial`, `dt` after the accepted state `y` whose derivative is `dy`,
/// was thrown off the motion by a step too large for it: every component departs from the
/// tangent `y + dt dy` by more than the tangent's own change (and the tolerance). The step's
/// higher-order terms then outweigh its first-order one, a step far larger than the error
/// control accepts, and the trial says nothing of where the motion goes (a crank thrown to
/// 3.6 rad from 0.19 in a step, moving at 0.05 rad per time unit). A component between the
/// accepted value and twice the tangent's change may be the motion arriving where the
/// evaluation fails (a crank decelerating into its limit position, or a position one unit in
/// the last place short of it): retried with smaller steps, such a motion is integrated past,
/// or stuck at, its limit instead of stopping there. Which components a failure depends on is
/// not known in general, so one such component of those `judged` (the components the failure
/// may depend on; see [`dopri5_judged`]) keeps the failure (and a state of no judged components
/// has no motion to be thrown off). A departure that is not finite is thrown off.
fn thrown_off<const D: usize>(
    trial: &[f64; D],
    y: &[f64; D],
    dt: f64,
    dy: &[f64; D],
    cfg: &OdeConfig,
    judged: [bool; D],
) -> bool {
    judged.contains(&true)
        && (0..D).filter(|&i| judged[i]).all(|i| {
            let tangent = dt * dy[i];
            let tol = cfg.atol + cfg.rtol * trial[i].abs().max(y[i].abs());
            let departure = (trial[i] - y[i] - tangent).abs();
            departure.is_nan() || departure > tangent.abs() + tol
        })
}

/// The smallest step that still moves the time at `t` of an integration started at `t0`:
/// 8 units of rounding of the largest time on the way (the time only grows, so that is `|t|`
/// or `|t0|`; each `t + h` is rounded there, so the time carries that much error). A step
/// below it adds nothing the time can hold: the step has collapsed. It depends on where the
/// integration is, not on how far it is to go: a floor growing with the span (as
/// `8 eps (t_end - t0)` would) rejects at `t = 0` every step of a long simulation (a span of
/// 1e12 puts it at 1.8e-3) and calls a smooth motion singular. `f64::MIN_POSITIVE` keeps it
/// positive at `t = 0`, where any positive normal step moves the time: a motion that is
/// singular there makes the step collapse to it, a few hundred rejections of at least a fifth
/// each.
fn step_floor(t0: f64, t: f64) -> f64 {
    8.0 * f64::EPSILON * t.abs().max(t0.abs()).max(f64::MIN_POSITIVE)
}

/// Shampine's interpolant of the step from `(t, y0)` to `y1`.
fn dense<const D: usize>(t: f64, h: f64, y0: &[f64; D], y1: &[f64; D], k: &[[f64; D]; 7]) -> DenseStep<D> {
    let mut r = [[0.0; D]; 5];
    for i in 0..D {
        let dy = y1[i] - y0[i];
        let b = h * k[0][i] - dy;
        r[0][i] = y0[i];
        r[1][i] = y1[i];
        r[2][i] = b;
        r[3][i] = dy - h * k[6][i] - b;
        r[4][i] = h * DENSE.iter().zip(k).map(|(d, ks)| d * ks[i]).sum::<f64>();
    }
    DenseStep { t0: t, h, r }
}

fn check_config(t0: f64, t_end: f64, cfg: &OdeConfig) -> Result<(), DynamicsError> {
    let bad = |what, value, why| Err(DynamicsError::BadValue { what, value, why });
    if !(t0.is_finite() && t_end.is_finite() && t_end > t0) {
        return bad("end time", t_end, "must be finite and after the start");
    }
    // A span no step can take (within the time's rounding at its ends) is no motion, not a
    // singular one: every step would fall below the floor at once.
    if t_end - t0 <= step_floor(t0, t_end) {
        return bad(
            "end time",
            t_end,
            "must be farther from the start than the rounding of the time there (8 units in the last place)",
        );
    }
    if !(cfg.rtol > MIN_RTOL && cfg.rtol.is_finite()) {
        return bad("relative tolerance", cfg.rtol, "must be finite and more than 2.2e-15 (ten units of rounding)");
    }
    if !(cfg.atol > 0.0 && cfg.atol.is_finite()) {
        return bad("absolute tolerance", cfg.atol, "must be positive and finite");
    }
    if cfg.h_max.is_nan() || cfg.h_max <= 0.0 {
        return bad("largest step", cfg.h_max, "must be positive");
    }
    Ok(())
}

/// A first step from the size of the state and of its derivative (Hairer's heuristic without
/// the second trial evaluation): the time in which the state changes by a hundredth of its
/// size, or, from a state at rest (zero, in the tolerances' units), by a hundredth of the
/// absolute tolerance. A millionth of the span where the state does not change. `d1` is the
/// derivative's [`norm`] at `y`.
///
/// From rest the step is not a millionth of the span: over a long span that is a step of
/// thousands of time units, whose stages ask for the motion far beyond where it can be
/// evaluated (a crank turned a million times in one stage, its accelerations beyond f64).
fn initial_step<const D: usize>(y: &[f64; D], d1: f64, span: f64, cfg: &OdeConfig) -> f64 {
    let d0 = norm(y, y, y, cfg);
    let h = if d1 < 1e-5 {
        1e-6 * span
    } else if d0 < 1e-5 {
        (0.01 / d1).min(1e-6 * span)
    } else {
        0.01 * d0 / d1
    };
    h.min(cfg.h_max).min(span)
}
