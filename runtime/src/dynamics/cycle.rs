//! Inverse dynamics of a one-input machine over a turn of its input: the driving torque for a
//! given speed law, the shaking force and moment, their harmonics, and flywheel sizing.

use super::error::DynamicsError;
use super::eval::{Shaking, checked_drive_into};
use super::model::MassModel;
use super::state::AnalogState;
use crate::analysis::fourier::{Fourier, fourier};
use crate::dims::{Dims, KinState};
use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, Kernel};
use crate::paths::collected::{MAX_COLLECTED_BYTES, within};
use crate::paths::sweep::SweepOf;
use std::f64::consts::TAU;

/// How the input turns over the cycle.
#[derive(Clone, Copy)]
pub enum SpeedLaw<'a> {
    /// Constant input speed `omega` (rad per unit time).
    Constant(f64),
    /// `phi -> (omega, d omega / d phi)`; the input acceleration is `omega d omega / d phi`.
    Varying(&'a dyn Fn(f64) -> (f64, f64)),
}

/// A constant speed's value; a varying speed's law, a closure, is not shown.
impl std::fmt::Debug for SpeedLaw<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SpeedLaw::Constant(omega) => f.debug_tuple("Constant").field(omega).finish(),
            SpeedLaw::Varying(_) => f.debug_tuple("Varying").finish_non_exhaustive(),
        }
    }
}

impl SpeedLaw<'_> {
    /// `(omega, eps)` at input angle `phi`.
    pub fn at(&self, phi: f64) -> (f64, f64) {
        match self {
            SpeedLaw::Constant(w) => (*w, 0.0),
            SpeedLaw::Varying(f) => {
                let (w, dw) = f(phi);
                (w, w * dw)
            }
        }
    }
}

/// The dynamics at one input angle of the cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CyclePoint {
    /// Input angle.
    pub phi: f64,
    /// Input speed.
    pub omega: f64,
    /// Input acceleration.
    pub eps: f64,
    /// Reduced moment of inertia `J(phi)`.
    pub inertia: f64,
    /// `dJ/dphi`.
    pub inertia_slope: f64,
    /// Generalised force of loads and gravity, `Q` (a torque on the input).
    pub load: f64,
    /// Driving torque `M = J eps + 1/2 J' omega^2 - Q`.
    pub torque: f64,
    /// Shaking force and moment on the frame.
    pub shaking: Shaking,
}

/// Inverse dynamics at `samples` equally spaced angles of one turn `[phi0, phi0 + 2 pi)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Cycle {
    /// The points, in increasing angle.
    pub points: Vec<CyclePoint>,
}

/// The smallest coefficient of speed fluctuation [`Cycle::flywheel`] sizes a flywheel for.
/// [`Flywheel::exact`] is a difference of energies over the samples (the kinetic energies at the
/// fluctuation's extreme speeds less the work), each rounded to about 1e-16 of itself, divided by
/// `delta`: at `delta` the flywheel is off by about `1e-16 / delta` of the inertia in the cycle,
/// the flywheel's and the mechanism's (as it was when found by bisection on the fluctuation, a
/// difference of the largest and the smallest speed: measured on the engine of the command
/// line's examples, 1e-4 of the flywheel at `delta = 1e-12`; at `1e-300` it came out 13 orders
/// of magnitude below the energy method's). From 1e-6 that is below the trapezoidal work's own
/// error (about 1e-7), and far below any machine's: flywheels are sized for 0.002 (generators)
/// to 0.2 (crushers).
pub const MIN_DELTA: f64 = 1e-6;

/// Sizing of a flywheel by the energy method; see [`Cycle::flywheel`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flywheel {
    /// The constant driving torque that balances the loads over the cycle, `-mean Q`.
    pub mean_torque: f64,
    /// Largest swing of the work of the driving torque and the loads, `dE_max`.
    pub energy_swing: f64,
    /// Reduced inertia the machine needs in total, `dE_max / (delta omega_m^2)`.
    pub total_inertia: f64,
    /// Mean reduced inertia of the mechanism itself over the cycle.
    pub mechanism_inertia: f64,
    /// Inertia to add on the input shaft by the classical energy method: `total - mechanism`, or
    /// 0 when the mechanism suffices. The method treats the mechanism's inertia as its mean, so
    /// where that varies over the turn by a sizeable part of the total, a machine with this
    /// flywheel fluctuates by more than `delta`: [`Flywheel::exact`] is the one that meets it.
    pub flywheel: f64,
    /// The inertia to add by the energy equation with the mechanism's variable inertia kept (the
    /// speed fluctuation is `delta` on the steady cycle); see [`Cycle::flywheel`].
    pub exact: f64,
    /// The input speed at the cycle's first angle on the steady cycle with the
    /// [`Flywheel::exact`] flywheel (a start for a simulation of that cycle), of the sign of the
    /// cycle's speeds.
    pub start_speed: f64,
}

/// Inverse dynamics over a turn of a one-input machine, set up by name and run by
/// [`InverseCycle::run`]: solves the kinematics at `samples` equally spaced angles of one turn
/// from the start angle (on the assembly branch of the guess) and evaluates the mass model and
/// the speed law there.
///
/// ```text
/// let cycle = InverseCycle::new(&drive, &drive.mass_model()?, SpeedLaw::Constant(omega))
///     .start(0.0)             // phi0: the first angle of the turn
///     .samples(3600)          // angles per turn
///     .guess(drive.guess(0.0))
///     .about([0.0, drive.e_p]) // frame point for the shaking moment
///     .run()?;
/// ```
///
/// Without a call to each setter: the turn from angle 0 (`start`), 360 samples (`samples`), from
/// the mechanism's declared guess at the start (`guess`), shaking moments about the origin
/// (`about`).
#[must_use = "an inverse cycle does nothing until `run`"]
pub struct InverseCycle<'a, M, const N: usize, const NO: usize> {
    m: &'a M,
    model: &'a MassModel<N, 1, NO>,
    law: SpeedLaw<'a>,
    phi0: f64,
    samples: usize,
    guess: Option<[f64; N]>,
    about: [f64; 2],
}

/// The mechanism by its type, the mass model, the speed law and the settings.
impl<M, const N: usize, const NO: usize> std::fmt::Debug for InverseCycle<'_, M, N, NO> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InverseCycle")
            .field("mechanism", &std::any::type_name::<M>())
            .field("model", self.model)
            .field("law", &self.law)
            .field("start", &self.phi0)
            .field("samples", &self.samples)
            .field("guess", &self.guess)
            .field("about", &self.about)
            .finish()
    }
}

impl<'a, M, const N: usize, const NO: usize> InverseCycle<'a, M, N, NO>
where
    M: Mechanism<N, 1, NO>,
{
    /// The inverse dynamics of mechanism `m` with mass model `model` driven at the speed law
    /// `law` (see the type's documentation for what it starts with).
    pub fn new(m: &'a M, model: &'a MassModel<N, 1, NO>, law: SpeedLaw<'a>) -> Self {
        InverseCycle { m, model, law, phi0: 0.0, samples: 360, guess: None, about: [0.0, 0.0] }
    }

    /// The turn covers `[phi0, phi0 + 2 pi)`.
    pub fn start(mut self, phi0: f64) -> Self {
        self.phi0 = phi0;
        self
    }

    /// Equally spaced angles per turn (at least 8).
    pub fn samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// The positions that choose the assembly branch at the start: the mechanism's named
    /// unknowns (`m.guess(phi0)`) or their array.
    pub fn guess(mut self, guess: impl Into<[f64; N]>) -> Self {
        self.guess = Some(guess.into());
        self
    }

    /// The frame point the shaking moments are taken about.
    pub fn about(mut self, about: [f64; 2]) -> Self {
        self.about = about;
        self
    }

    /// Runs the inverse dynamics over the turn.
    ///
    /// Errors: an input known not to be an angle (a piston's position: a turn of it would be
    /// `2 pi` of the unit of length) as [`DynamicsError::InputNotAngle`]; fewer than 8 samples,
    /// more than memory holds, a start angle so large that the doubles near it are more than a
    /// millionth of the samples' spacing apart (the steps between the samples could not be told
    /// apart), or a speed law that is not finite as
    /// [`DynamicsError::BadValue`]; a kinematic failure over the turn (a limit position: the
    /// input cannot turn), or an angle parameter too large to resolve (beyond the configuration's
    /// `largest_precise_angle`, refused before the turn), as [`DynamicsError::Kinematics`]; the
    /// model's own errors.
    pub fn run(self) -> Result<Cycle, DynamicsError> {
        self.m.check_param_angles(&self.m.solver_config().newton).map_err(DynamicsError::kin)?;
        let guess = self.guess.unwrap_or_else(|| self.m.guess_flat(&[self.phi0]));
        let (model, about) = (self.model, self.about);
        Cycle::over_turn(Compiled(self.m), self.phi0, self.samples, guess, self.law, |k, omega, eps| {
            let d = model.dynamics(k, &[omega])?;
            let shaking = model.shaking(k, &[omega], &[eps], about)?;
            let gamma = d.gamma.as_flattened().as_flattened();
            CyclePoint::of(k.x[0], omega, eps, d.mass.as_flattened(), gamma, &d.forces, shaking)
        })
        // The mass model's errors carry the input's value; the mechanism knows its name.
        .map_err(|e| e.with_input_names(&M::INPUTS))
    }
}

/// The kinematic states of one turn of the input of a one-input mechanism `k` (any
/// [`Kernel`]: a compiled one through [`Compiled`], a run-time model's): `samples` equally
/// spaced angles of `[phi0, phi0 + 2 pi)`, swept from `guess` at `phi0` (the turn's end is
/// swept too, so that a limit position anywhere on the turn is found), with the kernel's
/// configuration ([`Kernel::solver_config`]: the defaults, or a
/// [`Configured`](crate::Configured) mechanism's). The states [`InverseCycle::run`] evaluates
/// (it visits them as the sweep makes them, [`each_turn_state`], and keeps none), with its
/// errors; a mechanism with other than one input is [`DynamicsError::SizeMismatch`], one whose
/// input is known not to be an angle (a length) [`DynamicsError::InputNotAngle`], and samples
/// whose states would exceed [`MAX_COLLECTED_BYTES`] (1 GiB) [`DynamicsError::BadValue`],
/// refused before the turn ([`each_turn_state`] keeps none).
pub fn turn_states<K: Kernel>(
    k: K,
    phi0: f64,
    samples: usize,
    guess: <K::Dims as Dims>::Q,
) -> Result<Vec<<K::Dims as Dims>::Kin>, DynamicsError> {
    let bytes_each = size_of::<<K::Dims as Dims>::Kin>() + k.dims().kin().heap_bytes();
    check_kept(
        samples,
        bytes_each,
        "more states than are kept in memory at most (1 GiB, \
         `paths::collected::MAX_COLLECTED_BYTES`): visit them with `each_turn_state`, which keeps none",
    )?;
    let mut states = Vec::with_capacity(crate::mechanism::kernel::reserve_for(samples));
    each_turn_state(k, phi0, samples, guess, |state| states.push(state.clone()))?;
    Ok(states)
}

/// [`turn_states`] without keeping them: `visit` is given each of the turn's `samples` states
/// in order, lent where the sweep keeps it, as the sweep makes it. The sweep goes on to the
/// turn's end after the last state visited, and its errors are [`turn_states`]' (a kinematic
/// failure after some states were visited is still an error: a turn that cannot be completed
/// has no cycle).
pub fn each_turn_state<K: Kernel>(
    k: K,
    phi0: f64,
    samples: usize,
    guess: <K::Dims as Dims>::Q,
    mut visit: impl FnMut(&<K::Dims as Dims>::Kin),
) -> Result<(), DynamicsError> {
    let d = k.dims();
    if d.ni() != 1 {
        return Err(DynamicsError::SizeMismatch { what: "inputs of a one-input cycle", expected: 1, given: d.ni() });
    }
    // A turn is 2 pi of the input: of an angle, a period of the machine; of a length (a piston
    // driving a crank), 2 pi of whatever unit the lengths are in, another stretch of motion in
    // metres than in millimetres (a limit position "reached" in one, a cycle of nonsense
    // harmonics in the other). An input of a kind not inferred (a hand-written mechanism's)
    // is taken at its word.
    let kind = k.input_kind(0);
    if matches!(kind, QuantityKind::Length | QuantityKind::Dimensionless) {
        return Err(DynamicsError::InputNotAngle { input: k.input_name(0).to_owned().into(), kind });
    }
    if samples < 8 {
        return Err(DynamicsError::BadValue { what: "samples", value: samples as f64, why: "need at least 8" });
    }
    // More points than an analysis takes: a cycle keeps a point a sample, and 2^40 samples grew
    // them until the process was killed; more than an allocation can hold would panic in the
    // allocator (a capacity overflow).
    if samples > crate::analysis::MAX_SAMPLES {
        return Err(DynamicsError::BadValue {
            what: "samples",
            value: samples as f64,
            why: "more than an analysis takes (`analysis::MAX_SAMPLES`)",
        });
    }
    // The samples of the turn must be told apart, and the sweep's steps between them solved: at
    // a huge start angle the spacing of f64 numbers is no longer small against the step, the
    // steps' inputs round away from where they are predicted, and the sweep fails on them. The
    // bound is the sweep's own (beyond it the sweep's error would be the input's coarseness):
    // refused here, the error names the start angle. A start within a turn of zero is never
    // refused: the count of samples, not the start, makes a step that fine (billions a turn),
    // and the sweep judges it.
    let step = TAU / samples as f64;
    let bound = (crate::paths::curve::COARSE_INPUT * step).max(super::error::spacing(2.0 * TAU));
    if !(phi0.is_finite() && super::error::spacing(phi0.abs() + TAU) <= bound) {
        return Err(DynamicsError::BadValue {
            what: "start angle",
            value: phi0,
            why: "must be finite and small enough for the angles of a turn's samples, and of the steps between them, to \
                  be told apart (reduce it modulo a turn)",
        });
    }
    let (mut from, mut to) = (d.x(), d.x());
    from[0] = phi0;
    to[0] = phi0 + TAU;
    let cfg = k.solver_config();
    let mut sweep = SweepOf::<K, <K::Dims as Dims>::Kin>::over(k, from, to, samples + 1, guess)
        .map_err(DynamicsError::kin)?
        .with_config(cfg);
    let mut visited = 0;
    while let Some(state) = sweep.next_ref() {
        let state = state.map_err(DynamicsError::kin)?;
        // The turn's end (the first state of the next turn) is swept, not visited.
        if visited < samples {
            visit(state);
            visited += 1;
        }
    }
    Ok(())
}

/// `samples` items of `bytes_each` bytes kept one per sample, refused as
/// [`DynamicsError::BadValue`] (`why`) beyond [`MAX_COLLECTED_BYTES`]: up to
/// [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES) samples are taken, and a cycle of `10^8` points
/// (8 GB) or states (tens of GB) grew until an allocation failed and aborted the process. Refused
/// before the turn is swept; fewer samples than `MAX_SAMPLES` are refused by this alone.
fn check_kept(samples: usize, bytes_each: usize, why: &'static str) -> Result<(), DynamicsError> {
    if within(samples, bytes_each, MAX_COLLECTED_BYTES) {
        Ok(())
    } else {
        Err(DynamicsError::BadValue { what: "samples", value: samples as f64, why })
    }
}

/// The point of state `k` at the speed law's speed and acceleration there; a speed law that is
/// not finite is [`DynamicsError::BadValue`].
fn point_at<S: AnalogState>(
    k: &S,
    law: SpeedLaw<'_>,
    point: &mut impl FnMut(&S, f64, f64) -> Result<CyclePoint, DynamicsError>,
) -> Result<CyclePoint, DynamicsError> {
    let phi = k.inputs()[0];
    let (omega, eps) = law.at(phi);
    for value in [omega, eps] {
        if !value.is_finite() {
            return Err(DynamicsError::BadValue { what: "speed law", value, why: "must be finite" });
        }
    }
    point(k, omega, eps)
}

impl CyclePoint {
    /// The point at input angle `phi`, speed `omega` and acceleration `eps` from one input's
    /// dynamics (`mass`, `gamma`, `forces` of one entry each, as [`Dynamics`](super::Dynamics)
    /// or [`DynamicsBuf`](super::DynamicsBuf) hold them) and the shaking there: the reduced
    /// inertia, its slope, the load and the checked driving torque.
    pub fn of(
        phi: f64,
        omega: f64,
        eps: f64,
        mass: &[f64],
        gamma: &[f64],
        forces: &[f64],
        shaking: Shaking,
    ) -> Result<CyclePoint, DynamicsError> {
        for (what, given) in
            [("mass matrix entries", mass.len()), ("coefficients", gamma.len()), ("forces", forces.len())]
        {
            if given != 1 {
                return Err(DynamicsError::SizeMismatch { what, expected: 1, given });
            }
        }
        let mut torque = [0.0];
        checked_drive_into(mass, gamma, forces, &[phi], &[omega], &[eps], &mut torque)?;
        Ok(CyclePoint {
            phi,
            omega,
            eps,
            inertia: mass[0],
            inertia_slope: 2.0 * gamma[0],
            load: forces[0],
            torque: torque[0],
            shaking,
        })
    }
}

impl Cycle {
    /// The cycle of the one-input `states` (of a turn, e.g. [`turn_states`]) at the speed law
    /// `law`: `point` gives the point of each state at its speed and acceleration (see
    /// [`CyclePoint::of`]). A speed law that is not finite is [`DynamicsError::BadValue`]. The
    /// harmonics and the flywheel need the states of one turn, equally spaced and without its
    /// end (which repeats the start): of other states they are [`DynamicsError::BadValue`].
    pub fn over_states<S: AnalogState>(
        states: &[S],
        law: SpeedLaw<'_>,
        mut point: impl FnMut(&S, f64, f64) -> Result<CyclePoint, DynamicsError>,
    ) -> Result<Cycle, DynamicsError> {
        let points = states.iter().map(|k| point_at(k, law, &mut point)).collect::<Result<_, _>>()?;
        Ok(Cycle { points })
    }

    /// [`Cycle::over_states`] of the states of one turn of `k` ([`turn_states`]' arguments),
    /// each evaluated as the sweep makes it: none is kept, so the memory is the points'. The
    /// errors are the same, in the same order of precedence: a kinematic failure anywhere on
    /// the turn before the first error of `point` or of the speed law.
    pub fn over_turn<K: Kernel>(
        k: K,
        phi0: f64,
        samples: usize,
        guess: <K::Dims as Dims>::Q,
        law: SpeedLaw<'_>,
        mut point: impl FnMut(&<K::Dims as Dims>::Kin, f64, f64) -> Result<CyclePoint, DynamicsError>,
    ) -> Result<Cycle, DynamicsError> {
        check_kept(
            samples,
            size_of::<CyclePoint>(),
            "more points than a cycle keeps in memory at most (1 GiB, \
             `paths::collected::MAX_COLLECTED_BYTES`): take fewer samples (a turn's harmonics and flywheel need \
             far fewer than millions)",
        )?;
        let mut points = Vec::with_capacity(crate::mechanism::kernel::reserve_for(samples));
        let mut failed = None;
        each_turn_state(k, phi0, samples, guess, |k| {
            // After a point's error the turn is still swept: its kinematic errors come first.
            if failed.is_none() {
                match point_at(k, law, &mut point) {
                    Ok(p) => points.push(p),
                    Err(e) => failed = Some(e),
                }
            }
        })?;
        match failed {
            Some(e) => Err(e),
            None => Ok(Cycle { points }),
        }
    }

    /// The Fourier series of `f` over the cycle's points, computed on the values divided by a
    /// power of two near their largest magnitude (exact) and scaled back, so that
    /// coefficients are found whenever they are representable.
    fn series(&self, f: impl Fn(&CyclePoint) -> f64, harmonics: usize) -> Result<Fourier, DynamicsError> {
        let samples = self.points.len();
        // (Saturating: a count near `usize::MAX` is too many, not an overflow.)
        if harmonics.saturating_mul(2) >= samples {
            return Err(DynamicsError::TooManyHarmonics { harmonics, samples });
        }
        let v: Vec<f64> = self.points.iter().map(f).collect();
        let phi0 = self.points[0].phi;
        for value in v.iter().copied().chain([phi0]) {
            if !value.is_finite() {
                return Err(DynamicsError::BadValue { what: "cycle value", value, why: "must be finite" });
            }
        }
        self.check_turn()?;
        let big = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let unit = if big > 0.0 { crate::number::pow2_at_most(big) } else { 1.0 };
        let scaled: Vec<f64> = v.iter().map(|x| x / unit).collect();
        // Every precondition of `fourier` is checked above; should it still refuse, say so.
        let s = fourier(&scaled, phi0, TAU, harmonics).map_err(|_| DynamicsError::BadValue {
            what: "cycle for a Fourier series",
            value: samples as f64,
            why: "refused by the Fourier analysis",
        })?;
        let back = |c: f64| c * unit;
        let series = Fourier {
            a0: back(s.a0),
            a: s.a.iter().map(|&c| back(c)).collect(),
            b: s.b.iter().map(|&c| back(c)).collect(),
            ..s
        };
        if series.a.iter().chain(&series.b).chain([&series.a0]).all(|c| c.is_finite()) {
            Ok(series)
        } else {
            Err(DynamicsError::Overflow { what: "Fourier coefficients", x: Vec::new(), names: Vec::new() })
        }
    }

    /// Fourier series of the driving torque up to `harmonics` (the mean is `a0`). The points
    /// must be one turn's samples, equally spaced (see [`Cycle::over_states`]), else
    /// [`DynamicsError::BadValue`]; so for [`Cycle::shaking_harmonics`] and [`Cycle::flywheel`].
    pub fn torque_harmonics(&self, harmonics: usize) -> Result<Fourier, DynamicsError> {
        self.series(|p| p.torque, harmonics)
    }

    /// Fourier series of the shaking force components `x`, `y` and of the shaking moment.
    pub fn shaking_harmonics(&self, harmonics: usize) -> Result<[Fourier; 3], DynamicsError> {
        Ok([
            self.series(|p| p.shaking.force[0], harmonics)?,
            self.series(|p| p.shaking.force[1], harmonics)?,
            self.series(|p| p.shaking.moment, harmonics)?,
        ])
    }

    /// Mean driving torque over the cycle: the mean of the samples' torques (finite for finite
    /// torques, even where their sum overflows).
    ///
    /// Over a whole steady cycle the inertia term of the torque, `1/2 J'(phi) omega^2`, has mean
    /// zero, and this is the constant torque that balances the loads, [`Flywheel::mean_torque`]
    /// (`-mean Q`, which has no inertia term). Sampled coarsely, the samples' mean of that term
    /// is not zero (it aliases: 0.3 % of a slider-crank's mean torque at 8 samples a turn,
    /// rounding alone at 72): for the balancing torque of a coarse cycle use
    /// [`Cycle::flywheel`]'s.
    ///
    /// The points must be one turn's samples, equally spaced (see [`Cycle::over_states`]), as
    /// for the harmonics (whose `a0` this is) and the flywheel, with the same error, a
    /// [`DynamicsError::BadValue`] naming the first angle out of place: a cycle of a sweep over
    /// the closed turn, its last state repeating the first, counts that state twice (a
    /// slider-crank's mean torque came out -0.470 where the turn's is 0). A cycle without points,
    /// or with a torque that is not finite, is [`DynamicsError::BadValue`] too.
    ///
    /// ```
    /// use kinloop_runtime::dynamics::{Cycle, CyclePoint, DynamicsError, Shaking};
    /// // Eight samples of a turn of a torque `1 + cos phi`: its mean is 1.
    /// let point = |j: usize| {
    ///     let phi = std::f64::consts::TAU * j as f64 / 8.0;
    ///     let shaking = Shaking { force: [0.0, 0.0], moment: 0.0 };
    ///     CyclePoint::of(phi, 1.0, 0.0, &[1.0], &[0.0], &[-1.0 - phi.cos()], shaking).unwrap()
    /// };
    /// let turn = Cycle { points: (0..8).map(point).collect() };
    /// assert!((turn.mean_torque()? - 1.0).abs() < 1e-15);
    /// // The turn's end, which repeats its start, is not one of its samples.
    /// let closed = Cycle { points: (0..=8).map(point).collect() };
    /// assert!(matches!(closed.mean_torque(), Err(DynamicsError::BadValue { what: "cycle angle", .. })));
    /// # Ok::<(), DynamicsError>(())
    /// ```
    pub fn mean_torque(&self) -> Result<f64, DynamicsError> {
        for p in &self.points {
            if !p.torque.is_finite() {
                return Err(DynamicsError::BadValue { what: "cycle value", value: p.torque, why: "must be finite" });
            }
        }
        self.check_turn()?;
        Ok(mean(self.points.iter().map(|p| p.torque)))
    }

    /// Flywheel for a coefficient of speed fluctuation `delta = (omega_max - omega_min) /
    /// omega_m` by the energy method, with `omega_m` the mean speed of the cycle's law.
    ///
    /// A constant driving torque `M_m = -mean Q` balances the loads over a steady cycle. The
    /// work `E(phi) = int (M_m + Q) dphi` (trapezoidal rule over the samples) swings by
    /// `dE_max = max E - min E`, and the kinetic energy `1/2 J omega^2` must absorb it with
    /// `omega` within `omega_m (1 ± delta / 2)`, so `J_total = dE_max / (delta omega_m^2)`. The
    /// mechanism supplies its mean reduced inertia; the flywheel provides the rest. The
    /// mechanism's inertia variation is thereby neglected (its error is of the order of
    /// `(J_max - J_min) / J_total` in delta; a simulation with [`Simulation`](super::Simulation)
    /// checks the result). Loads depending on speed are taken at the law's speeds.
    ///
    /// [`Flywheel::exact`] keeps the variable inertia: on a steady cycle the energy equation
    /// `1/2 (J_fly + J(phi)) omega(phi)^2 = E_0 + E(phi)` gives the speed at every angle; `E_0` is
    /// set so that `(omega_max + omega_min) / 2 = omega_m`, and `J_fly` so that the fluctuation
    /// is `delta`, both over the samples (`J_fly` in closed form from the samples' energies and
    /// inertias, `E_0` by a safeguarded Newton iteration: a few passes over the samples).
    ///
    /// The input may turn either way: a crank turning clockwise (every speed negative) has the
    /// flywheel of the same law turning counter-clockwise, the energy equation holding along
    /// the angle whichever way it runs (`omega_m` is then the mean of the speeds' magnitudes,
    /// and [`Flywheel::start_speed`] negative).
    ///
    /// `delta` lies in `[MIN_DELTA, 2)` ([`MIN_DELTA`]); outside it the error is
    /// [`DynamicsError::BadValue`], as it is for a law whose speed is zero at an angle or not of
    /// one sign at every angle (a flywheel is sized for an input that keeps turning one way). A
    /// machine that needs no flywheel but has no inertia about its input at an angle (its speed
    /// there does not follow from its energy) is [`DynamicsError::SingularMass`] at that angle.
    pub fn flywheel(&self, delta: f64) -> Result<Flywheel, DynamicsError> {
        if !(MIN_DELTA..2.0).contains(&delta) {
            return Err(DynamicsError::BadValue {
                what: "coefficient of speed fluctuation",
                value: delta,
                why: "must lie in [1e-6, 2)",
            });
        }
        for p in &self.points {
            for (what, value) in [("cycle load", p.load), ("cycle speed", p.omega), ("cycle inertia", p.inertia)] {
                if !value.is_finite() {
                    return Err(DynamicsError::BadValue { what, value, why: "must be finite" });
                }
            }
            if p.inertia < 0.0 {
                return Err(DynamicsError::BadValue {
                    what: "cycle inertia",
                    value: p.inertia,
                    why: "must not be negative",
                });
            }
        }
        self.check_turn()?;
        // The energy method sizes a flywheel for an input that keeps turning one way: every speed
        // of the law of the first one's sign, none zero. Tested speed by speed, not on the mean
        // alone: a law that turns back had its flywheel sized, and one whose mean is zero passed
        // or failed by the sign of the mean's rounding (a flywheel of 8e35 at 360 samples, an
        // error at 720 or in other units). Either way round: the energy equation
        // `1/2 J omega^2 = E_0 + E(phi)` holds along the angle whichever way the input runs, and
        // is even in the speed, so a clockwise crank (every speed negative, which was refused)
        // is sized on the speeds' magnitudes, its start speed given the law's sign.
        let sign = self.points[0].omega.signum();
        if let Some(p) = self.points.iter().find(|p| sign * p.omega <= 0.0) {
            return Err(DynamicsError::BadValue {
                what: "cycle speed",
                value: p.omega,
                why: "must be of one sign, not zero, at every angle (the input turning one way)",
            });
        }
        let mean_torque = -mean(self.points.iter().map(|p| p.load));
        let omega_m = mean(self.points.iter().map(|p| sign * p.omega));
        let work = self.work(mean_torque);
        let lo = work.iter().copied().fold(f64::INFINITY, f64::min);
        let energy_swing = work.iter().copied().fold(f64::NEG_INFINITY, f64::max) - lo;
        let overflow = |what| DynamicsError::Overflow { what, x: Vec::new(), names: Vec::new() };
        if !energy_swing.is_finite() {
            return Err(overflow("work of the loads over the cycle"));
        }
        let (exact, levels) =
            self.exact_flywheel(&work, omega_m, delta).ok_or_else(|| overflow("exact flywheel inertia"))?;
        // Without a flywheel, a machine without inertia about its input at an angle has no speed
        // there that follows from its energy (reported as an overflow of the sizing, `0 / 0`).
        if let Some(p) = self.points.iter().find(|p| exact + p.inertia == 0.0) {
            return Err(DynamicsError::SingularMass { x: vec![p.phi], pivot: 0.0, names: Vec::new() });
        }
        let (e0, _) = self.energy_level(&work, exact, omega_m, levels);
        let total_inertia = energy_swing / (delta * omega_m * omega_m);
        let mechanism_inertia = mean(self.points.iter().map(|p| p.inertia));
        let f = Flywheel {
            mean_torque,
            energy_swing,
            total_inertia,
            mechanism_inertia,
            flywheel: (total_inertia - mechanism_inertia).max(0.0),
            exact,
            // The level is reduced by omega_m^2 (see `exact_flywheel`), and so is this speed; its
            // sign is the law's.
            start_speed: sign
                * omega_m
                * (2.0 * (e0 + work[0] / omega_m / omega_m) / (exact + self.points[0].inertia)).sqrt(),
        };
        let values = [f.mean_torque, f.total_inertia, f.mechanism_inertia, f.flywheel, f.exact, f.start_speed];
        if values.iter().all(|v| v.is_finite()) { Ok(f) } else { Err(overflow("flywheel sizing")) }
    }

    /// The points one turn's samples: point `j` of `n` at the first one's angle plus `j 2 pi / n`
    /// (to a thousandth of that spacing; the sweep of a turn puts them there to a millionth), else
    /// [`DynamicsError::BadValue`] naming the first angle out of place. The harmonics and the
    /// flywheel's work take the points as such a turn: a cycle made by [`Cycle::over_states`]
    /// of a sweep over the closed turn `[phi0, phi0 + 2 pi]` (its last state repeating the
    /// first) was one of `n + 1` points, every harmonic and the work off by about `1 / n`, as
    /// `Ok`; of part of a turn, or of points left out, the same. A cycle without points is no
    /// turn either (its mean is 0 / 0).
    fn check_turn(&self) -> Result<(), DynamicsError> {
        let Some(first) = self.points.first() else {
            return Err(DynamicsError::BadValue { what: "cycle points", value: 0.0, why: "need at least one" });
        };
        let step = TAU / self.points.len() as f64;
        let misplaced = self.points.iter().enumerate().find(|&(j, p)| {
            let off = p.phi - (first.phi + j as f64 * step);
            // (A NaN angle is out of place too.)
            off.is_nan() || off.abs() > 1e-3 * step
        });
        match misplaced {
            Some((_, p)) => Err(DynamicsError::BadValue {
                what: "cycle angle",
                value: p.phi,
                why: "the points must be one turn's samples, equally spaced from the first (as `turn_states` gives \
                      them): a sweep over the closed turn repeats its first angle at its end, leave that state out",
            }),
            None => Ok(()),
        }
    }

    /// The work `E(phi_j) = int_0^phi_j (M_m + Q) dphi` of a constant driving torque `M_m` and
    /// the loads at the samples (trapezoidal rule).
    fn work(&self, mean_torque: f64) -> Vec<f64> {
        let h = TAU / self.points.len() as f64;
        let mut e = 0.0;
        let mut work = Vec::with_capacity(self.points.len());
        for (j, p) in self.points.iter().enumerate() {
            work.push(e);
            let next = &self.points[(j + 1) % self.points.len()];
            e += 0.5 * h * (2.0 * mean_torque + p.load + next.load);
        }
        work
    }

    /// The smallest flywheel giving fluctuation `delta` (0 when the mechanism alone stays within
    /// it), with the energy levels its steady cycle may have, both found in one pass over the
    /// samples; `None` when no finite flywheel does (the energies overflow).
    ///
    /// Energies are taken reduced by `omega_m^2` (inertias then): `u = E / omega_m^2`, `e0 =
    /// E_0 / omega_m^2`. The fluctuation falls as the flywheel grows, and with the mean speed
    /// centred it is at most `delta` exactly when some level keeps every speed within `[omega_b,
    /// omega_a] = omega_m (1 ∓ delta / 2)` (raising the level raises every speed, lowering it
    /// lowers every speed: a fluctuation beyond `delta` has a speed outside the band at every
    /// level). By the energy equation that is, at every sample,
    /// `(J_fly + J) k_b <= e0 + u <= (J_fly + J) k_a` with `k = (omega / omega_m)^2 / 2`, so
    /// `J_fly k_b + A <= e0 <= J_fly k_a + B` with `A = max (J k_b - u)`, `B = min (J k_a - u)`:
    /// a level exists from `J_fly (k_a - k_b) = J_fly delta >= A - B` on. The flywheel is
    /// `(A - B) / delta` (or 0), where the band of levels closes to the steady cycle's.
    ///
    /// This is the flywheel at which the fluctuation computed over the samples crosses `delta`
    /// (what a bisection on it found, at a pass over the samples per step of the flywheel and of
    /// the level: thousands). Its rounding: `A - B` cancels terms of the size of `J` and `u`
    /// (`u` swings by about `J_total delta`), an error of about `eps (1 + J / (J_fly delta))`
    /// of the flywheel, where the bisection's difference of the largest and smallest speed
    /// lost `eps / delta` (see [`MIN_DELTA`]).
    fn exact_flywheel(&self, work: &[f64], omega_m: f64, delta: f64) -> Option<(f64, [f64; 2])> {
        let k_a = 0.5 * (1.0 + 0.5 * delta) * (1.0 + 0.5 * delta);
        let k_b = 0.5 * (1.0 - 0.5 * delta) * (1.0 - 0.5 * delta);
        let (mut a, mut b) = (f64::NEG_INFINITY, f64::INFINITY);
        for (p, w) in self.points.iter().zip(work) {
            // Divided twice, not by `omega_m^2`: the square may overflow where the energies do not.
            let u = w / omega_m / omega_m;
            a = a.max(p.inertia * k_b - u);
            b = b.min(p.inertia * k_a - u);
        }
        if !(a.is_finite() && b.is_finite()) {
            return None;
        }
        let fly = ((a - b) / delta).max(0.0);
        if !fly.is_finite() {
            return None;
        }
        let levels = if fly > 0.0 {
            // The band has closed (up to rounding): its middle is the steady cycle's level.
            let mid = 0.5 * ((fly * k_b + a) + (fly * k_a + b));
            [mid, mid]
        } else {
            [a, b]
        };
        if levels.iter().all(|e| e.is_finite()) { Some((fly, levels)) } else { None }
    }

    /// The reduced energy level `e0 = E_0 / omega_m^2` of the steady cycle with flywheel `j_fly`
    /// (see [`Cycle::exact_flywheel`]), at which `(omega_max + omega_min) / 2 = omega_m`, within
    /// `levels` (which hold it: the band of levels keeping the speeds within `delta`), and the
    /// passes over the samples it took.
    ///
    /// The mean of the largest and the smallest speed grows with the level, and near it follows
    /// the two samples that hold them: Newton's method on it (its slope from those two), kept
    /// within a bracket that every pass narrows, and bisection when a step leaves the bracket or
    /// does not halve it (where the samples holding the extremes change). It stops where a step
    /// is below the rounding of the level's sums `e0 + u` (about `eps (|e0| + |u|)`: the speeds
    /// computed there are the same to rounding), or when the bracket has no double inside, or
    /// after [`MAX_LEVEL_PASSES`] (bisection alone reaches the rounding well before). Smooth
    /// cycles take a handful of passes, where bisection to the doubles' resolution took 80.
    fn energy_level(&self, work: &[f64], j_fly: f64, omega_m: f64, levels: [f64; 2]) -> (f64, usize) {
        let [mut lo, mut hi] = levels;
        if lo >= hi {
            return (lo, 0);
        }
        let mut e = 0.5 * (lo + hi);
        // The last step and the one before it (the bracket's width before any).
        let (mut step, mut step_before) = (hi - lo, hi - lo);
        for pass in 1..=MAX_LEVEL_PASSES {
            // One pass: the largest and smallest `(e0 + u) / (J_fly + J)` (half the squared speed
            // relative to omega_m^2), and where they are.
            let (mut top, mut bottom) = ((f64::NEG_INFINITY, 0), (f64::INFINITY, 0));
            for (j, (p, w)) in self.points.iter().zip(work).enumerate() {
                let r = (e + w / omega_m / omega_m) / (j_fly + p.inertia);
                if r > top.0 {
                    top = (r, j);
                }
                if r < bottom.0 {
                    bottom = (r, j);
                }
            }
            let speed = |r: f64| (2.0 * r).max(0.0).sqrt();
            let (s_a, s_b) = (speed(top.0), speed(bottom.0));
            let excess = 0.5 * (s_a + s_b) - 1.0;
            if excess == 0.0 {
                return (e, pass);
            }
            if excess < 0.0 {
                lo = e
            } else {
                hi = e
            }
            // d omega / d e0 = 1 / ((J_fly + J) omega), relative to omega_m.
            let slope_of = |s: f64, j: usize| 1.0 / ((j_fly + self.points[j].inertia) * s);
            let slope = 0.5 * (slope_of(s_a, top.1) + slope_of(s_b, bottom.1));
            let newton = e - excess / slope;
            let u_of = |j: usize| (work[j] / omega_m / omega_m).abs();
            let rounding = 4.0 * f64::EPSILON * (e.abs() + u_of(top.1).max(u_of(bottom.1)));
            // Newton's step is taken inside the bracket and when it is at most half the step
            // before the last (else Newton's method is not converging: it bisects).
            let converging = newton > lo && newton < hi && 2.0 * (newton - e).abs() <= step_before;
            let next = if converging { newton } else { 0.5 * (lo + hi) };
            if (next - e).abs() <= rounding || next <= lo || next >= hi {
                return (next.clamp(lo, hi), pass);
            }
            (step_before, step) = (step, (next - e).abs());
            e = next;
        }
        (e, MAX_LEVEL_PASSES)
    }
}

/// The most passes over the samples [`Cycle::energy_level`] makes: bisection alone halves a
/// bracket of the size of the energies to their rounding in about 60.
const MAX_LEVEL_PASSES: usize = 100;

/// The mean of `values`: the plain sum divided by the count, or, when that sum overflows,
/// the sum of the values each divided by the count (the mean of finite values is always
/// representable). NaN for no values.
fn mean(values: impl Iterator<Item = f64> + Clone) -> f64 {
    let n = values.clone().count() as f64;
    let plain = values.clone().sum::<f64>() / n;
    if plain.is_finite() || n == 0.0 { plain } else { values.map(|v| v / n).sum() }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod streamed_tests;
