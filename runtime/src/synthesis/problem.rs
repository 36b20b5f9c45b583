//! A synthesis problem: a mechanism with sensitivities (any [`SensKernel`]: a compiled
//! mechanism through [`CompiledSens`], a run-time model through its kernel), its design
//! variables, a task and constraints, checked and resolved against the mechanism's names once,
//! when it is built.

use super::constraints::Constraints;
use super::error::SynthesisError;
use super::resolve::{Inputs, Resolved, resolve_channel, resolve_timing, scalar_column, target_size};
use super::task::{Channel, PlacementBounds, Task};
use super::vars::{Bound, Design, check_bounds, param_index};
use crate::analysis::ColumnIndex;
use crate::analysis::column::column_kind;
use crate::dims::Dims;
use crate::kinds::QuantityKind;
use crate::mechanism::Sensitivities;
use crate::mechanism::kernel::{CompiledSens, Kernel, Q, SensKernel, X};
use crate::number::Count;
use crate::paths::config::SweepConfig;
use crate::solvers::newton::NewtonConfig;
use std::borrow::Cow;

/// Where the first evaluation of a local solve starts its position solves.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Guess<Q> {
    /// The declared guess at the first target, each next target from the one before.
    Declared,
    /// This position at the first target, each next target from the one before.
    First(Q),
    /// A position at every target.
    Every(Vec<Q>),
}

/// The constraints resolved to indices.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Checks {
    pub full_rotation: bool,
    /// Coupler and follower columns, and the smallest angle allowed.
    pub transmission: Option<(ColumnIndex, ColumnIndex, f64)>,
    /// Parameter indices and the largest ratio allowed.
    pub link_ratio: Option<(Vec<usize>, f64)>,
    /// Parameter indices of ground, input, coupler and output.
    pub four_bar: Option<[usize; 4]>,
    /// The largest error accepted at a target.
    pub max_error: Option<f64>,
}

/// A synthesis problem over a compiled mechanism type `M` (declared with
/// `#[kinloop(sensitivities)]`): [`ProblemOf`] over [`CompiledSens`]. Built with
/// [`Problem::new`]; everything else is [`ProblemOf`]'s.
pub type Problem<M, const N: usize, const NI: usize, const NO: usize, const NP: usize> =
    ProblemOf<CompiledSens<M, N, NI, NO, NP>>;

/// A synthesis problem over any mechanism with sensitivities ([`SensKernel`]: a compiled one
/// through [`CompiledSens`], the alias [`Problem`]; a run-time model through its kernel): the
/// mechanism whose parameters not varied keep their values, the design variables, the task,
/// the constraints, and the solver settings of its analyses. Solved by a
/// [`Search`](super::Search).
///
/// The search's unknowns are, in order: the design variables; with [`Timing::Free`](super::Timing::Free) the input
/// value of every target; with a placement its translation `dx`, `dy`, rotation and scale.
#[derive(Clone, Debug)]
pub struct ProblemOf<K: Kernel> {
    pub(crate) base: K,
    pub(crate) names: Vec<String>,
    pub(crate) vars: Vec<Bound>,
    pub(crate) channels: Vec<(Resolved, f64)>,
    /// Components per target.
    pub(crate) width: usize,
    /// Target values, `width` per target.
    pub(crate) targets: Vec<f64>,
    pub(crate) inputs: Inputs<X<K>>,
    pub(crate) placement: Option<PlacementBounds>,
    pub(crate) checks: Checks,
    /// The positions the first evaluation starts from: at the first target, or at every one.
    pub(crate) guess: Guess<Q<K>>,
    pub(crate) newton: NewtonConfig,
    pub(crate) sweep: SweepConfig,
    /// The size of the targets (their largest weighted distance from their centroid; a
    /// radian times the largest angle weight without lengths): the unit of the search's
    /// residual tolerance.
    pub(crate) scale: f64,
    /// The unit positions' lengths are compared in (the same size of the lengths, 1 without).
    pub(crate) length: f64,
}

impl<M, const N: usize, const NI: usize, const NO: usize, const NP: usize> Problem<M, N, NI, NO, NP>
where
    M: Sensitivities<N, NI, NO, NP> + Clone,
{
    /// The problem of varying `design` of `mechanism` (whose other parameters stay) to do
    /// `task`. Every name is checked against the mechanism, every value for being finite, the
    /// bounds for holding a value, and the targets for giving at least as many equations as
    /// the search has unknowns.
    pub fn new(mechanism: M, design: &Design, task: &Task) -> Result<Self, SynthesisError> {
        ProblemOf::over(CompiledSens(mechanism), design, task)
    }
}

impl<K: SensKernel> ProblemOf<K> {
    /// The problem of varying `design` of the mechanism `kernel` (whose other parameters stay)
    /// to do `task` ([`Problem::new`] over any [`SensKernel`]).
    pub fn over(kernel: K, design: &Design, task: &Task) -> Result<Self, SynthesisError> {
        kernel.check_params()?;
        let params = kernel.param_names();
        let vars = design.resolve(kernel.name(), &params)?;
        let names = design.variables().iter().map(|v| v.name.clone()).collect();
        if task.channels.is_empty() {
            return Err(SynthesisError::Mismatch(
                "the task has no channel: nothing to compare the targets with".into(),
            ));
        }
        if task.weights.len() != task.channels.len() {
            return Err(SynthesisError::Mismatch(format!(
                "{} for {}",
                Count(task.weights.len(), "weight"),
                Count(task.channels.len(), "channel")
            )));
        }
        let mut channels = Vec::with_capacity(task.channels.len());
        for (c, &w) in task.channels.iter().zip(&task.weights) {
            if !(w.is_finite() && w > 0.0) {
                return Err(SynthesisError::InvalidConfig(format!("the weight {w} must be positive and finite")));
            }
            channels.push((resolve_channel(&kernel, c)?, w));
        }
        let width: usize = task.channels.iter().map(Channel::width).sum();
        if task.targets.is_empty() {
            return Err(SynthesisError::NoTargets);
        }
        let mut targets = Vec::with_capacity(width * task.targets.len());
        for (k, row) in task.targets.iter().enumerate() {
            if row.len() != width {
                return Err(SynthesisError::Mismatch(format!(
                    "target {k} has {}; the channels take {width}",
                    Count(row.len(), "value")
                )));
            }
            if let Some(&v) = row.iter().find(|v| !v.is_finite()) {
                return Err(SynthesisError::NonFinite { what: "a value", target: k, value: v });
            }
            targets.extend_from_slice(row);
        }
        let inputs = resolve_timing(kernel.dims(), &task.timing, task.targets.len())?;
        check_turns(&kernel, &inputs)?;
        one_motion(&inputs, &task.targets)?;
        if let Some(p) = &task.placement {
            for (name, (lo, hi)) in [("dx", p.dx), ("dy", p.dy), ("angle", p.angle), ("scale", p.scale)] {
                check_bounds(name, lo, hi)?;
            }
            if p.scale.0 <= 0.0 {
                return Err(SynthesisError::BadBounds { name: "scale".into(), lo: p.scale.0, hi: p.scale.1 });
            }
        }
        let size = target_size(&channels, &targets, width);
        let p = ProblemOf {
            base: kernel,
            names,
            vars,
            channels,
            width,
            targets,
            inputs,
            placement: task.placement,
            checks: Checks::default(),
            guess: Guess::Declared,
            newton: default_newton(),
            sweep: SweepConfig::default(),
            scale: size.residual,
            length: size.length,
        };
        let (residuals, variables) = (p.targets.len(), p.dims());
        if residuals < variables && !design.is_underdetermined() {
            return Err(SynthesisError::TooFewTargets { residuals, variables });
        }
        Ok(p)
    }

    /// The problem with `constraints` checked on every candidate (names resolved here).
    pub fn with_constraints(mut self, constraints: &Constraints) -> Result<Self, SynthesisError> {
        let mut checks = Checks { full_rotation: constraints.full_rotation, ..Checks::default() };
        let ni = self.base.dims().ni();
        if constraints.full_rotation && ni != 1 {
            return Err(SynthesisError::Unsupported(format!(
                "full rotation is checked for a mechanism with one input; `{}` has {ni}",
                self.base.name()
            )));
        }
        // A full rotation is a turn of an angle: a length or a ratio swept over 2 pi of its unit
        // would be judged by a constraint that means nothing for it.
        if constraints.full_rotation && ni == 1 {
            let kind = self.base.input_kind(0);
            if matches!(kind, QuantityKind::Length | QuantityKind::Dimensionless) {
                return Err(SynthesisError::InvalidConfig(format!(
                    "full rotation is a turn of an angle input: `{}` of `{}` is a {}",
                    self.base.input_name(0),
                    self.base.name(),
                    if kind == QuantityKind::Length { "length" } else { "pure number" }
                )));
            }
        }
        if let Some(t) = &constraints.transmission {
            let c = scalar_column(&self.base, &t.coupler)?;
            let f = scalar_column(&self.base, &t.follower)?;
            // The angle between two links: a column inferred as a length (or a ratio) is none.
            for (name, column) in [(&t.coupler, c), (&t.follower, f)] {
                let kind = column_kind(&self.base, column);
                if matches!(kind, QuantityKind::Length | QuantityKind::Dimensionless) {
                    return Err(SynthesisError::InvalidConfig(format!(
                        "the transmission angle is between two links' angle columns: `{name}` is a {}, not an angle",
                        if kind == QuantityKind::Length { "length" } else { "pure number" }
                    )));
                }
            }
            if !(t.min.is_finite() && (0.0..=std::f64::consts::FRAC_PI_2).contains(&t.min)) {
                return Err(SynthesisError::InvalidConfig(format!(
                    "the smallest transmission angle {} must lie in [0, pi/2]",
                    t.min
                )));
            }
            checks.transmission = Some((c, f, t.min));
        }
        let params = self.base.param_names();
        if let Some(r) = &constraints.link_ratio {
            let mut idx = Vec::new();
            for name in &r.links {
                let i = param_index(self.base.name(), &params, name)?;
                if idx.contains(&i) {
                    return Err(SynthesisError::DuplicateVariable { name: name.clone() });
                }
                idx.push(i);
            }
            if idx.len() < 2 || !(r.max.is_finite() && r.max >= 1.0) {
                return Err(SynthesisError::InvalidConfig(
                    "a link ratio bound needs at least two links and a finite largest ratio >= 1".into(),
                ));
            }
            checks.link_ratio = Some((idx, r.max));
        }
        if let Some(max) = constraints.max_error {
            if !(max.is_finite() && max > 0.0) {
                return Err(SynthesisError::InvalidConfig(format!(
                    "max_error is {max}: it must be finite and positive (the largest error accepted at a target)"
                )));
            }
            checks.max_error = Some(max);
        }
        if let Some(f) = &constraints.four_bar {
            let mut idx = [0; 4];
            for (k, name) in [&f.ground, &f.input, &f.coupler, &f.output].into_iter().enumerate() {
                idx[k] = param_index(self.base.name(), &params, name)?;
                if idx[..k].contains(&idx[k]) {
                    return Err(SynthesisError::DuplicateVariable { name: name.clone() });
                }
            }
            checks.four_bar = Some(idx);
        }
        self.checks = checks;
        Ok(self)
    }

    /// The position at the first target that picks the assembly mode (by default the
    /// mechanism's declared guess there). A guess of another size than the unknowns, or not
    /// finite, is refused here, as [`ProblemOf::with_guesses`] refuses one (accepted, every start
    /// ended unassembled, with nothing said of the guess).
    pub fn with_guess(mut self, guess: <K::Dims as Dims>::Q) -> Result<Self, SynthesisError> {
        self.check_guess(&guess)?;
        self.guess = Guess::First(guess);
        Ok(self)
    }

    /// A position at every target, to start the first evaluation of every local solve from
    /// (e.g. from a design whose assembly mode at each target is known); one per target.
    pub fn with_guesses(mut self, guesses: Vec<<K::Dims as Dims>::Q>) -> Result<Self, SynthesisError> {
        if guesses.len() != self.targets() {
            let guesses = if guesses.len() == 1 { "1 guess".into() } else { format!("{} guesses", guesses.len()) };
            return Err(SynthesisError::Mismatch(format!("{guesses} for {}", Count(self.targets(), "target"))));
        }
        guesses.iter().try_for_each(|g| self.check_guess(g))?;
        self.guess = Guess::Every(guesses);
        Ok(self)
    }

    /// A guess of the unknowns' size, every value finite.
    fn check_guess(&self, guess: &<K::Dims as Dims>::Q) -> Result<(), SynthesisError> {
        let (n, given) = (self.base.dims().n(), guess.as_ref().len());
        if given != n {
            return Err(SynthesisError::Mismatch(format!(
                "a guess of {} for {}",
                Count(given, "value"),
                Count(n, "unknown")
            )));
        }
        if guess.as_ref().iter().any(|v| !v.is_finite()) {
            return Err(SynthesisError::InvalidConfig("a guess is not finite".into()));
        }
        Ok(())
    }

    /// The Newton configuration of every position solve (by default a residual tolerance of
    /// `1e-14` and a step tolerance of `1e-16`: positions to rounding, so that the targets
    /// can be met to rounding).
    pub fn with_newton(mut self, newton: NewtonConfig) -> Result<Self, SynthesisError> {
        newton.validate()?;
        self.newton = newton;
        Ok(self)
    }

    /// The configuration of the verifying sweeps.
    pub fn with_sweep(mut self, sweep: SweepConfig) -> Result<Self, SynthesisError> {
        sweep.validate()?;
        self.sweep = sweep;
        Ok(self)
    }

    /// The names of the design variables, in order.
    pub fn variable_names(&self) -> &[String] {
        &self.names
    }

    /// Number of targets.
    pub fn targets(&self) -> usize {
        self.targets.len() / self.width
    }

    /// Number of unknowns of the search (design variables, free inputs, placement).
    pub fn dims(&self) -> usize {
        self.vars.len() + self.free_inputs() + if self.placement.is_some() { 4 } else { 0 }
    }

    /// Number of free input values (one per target with free timing, else none).
    pub(crate) fn free_inputs(&self) -> usize {
        match self.inputs {
            Inputs::Free { .. } => self.targets(),
            Inputs::Prescribed(_) => 0,
        }
    }

    /// Lower and upper bounds of every unknown of the search.
    pub(crate) fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut lo, mut hi): (Vec<f64>, Vec<f64>) = self.vars.iter().map(|b| (b.lo, b.hi)).unzip();
        if let Inputs::Free { lo: a, hi: b } = self.inputs {
            lo.extend(std::iter::repeat_n(a, self.targets()));
            hi.extend(std::iter::repeat_n(b, self.targets()));
        }
        if let Some(p) = &self.placement {
            for (a, b) in [p.dx, p.dy, p.angle, p.scale] {
                lo.push(a);
                hi.push(b);
            }
        }
        (lo, hi)
    }

    /// Refuses a problem none of whose designs solves the declared equations: an angle
    /// parameter beyond the [`largest_precise_angle`](NewtonConfig::largest_precise_angle) of
    /// the problem's Newton configuration at every point of the box (a parameter not varied, or
    /// a design variable both of whose bounds lie beyond it). Checked at the design variables'
    /// values nearest zero: where those are refused, every design is. (A design refused among
    /// others is refused at its evaluation, as one that cannot be assembled is.)
    pub(crate) fn check_param_angles(&self) -> Result<(), SynthesisError> {
        let nearest: Vec<f64> = self.vars.iter().map(|b| 0.0f64.clamp(b.lo, b.hi)).collect();
        Ok(self.base.with_params(&self.params(&nearest), |m| m.check_param_angles(&self.newton))??)
    }

    /// The parameters with the design variables of `z`.
    pub(crate) fn params(&self, z: &[f64]) -> Vec<f64> {
        let mut p: Vec<f64> = (0..self.base.param_count()).map(|k| self.base.param(k)).collect();
        for (b, v) in self.vars.iter().zip(z) {
            p[b.index] = *v;
        }
        p
    }

    /// The inputs of every target for the unknowns `z` (prescribed ones borrowed: no copy per
    /// evaluation).
    pub(crate) fn input_values(&self, z: &[f64]) -> Cow<'_, [X<K>]> {
        match &self.inputs {
            Inputs::Prescribed(x) => Cow::Borrowed(x),
            Inputs::Free { .. } => {
                let nv = self.vars.len();
                Cow::Owned(z[nv..nv + self.targets()].iter().map(|&v| self.input_point(v)).collect())
            }
        }
    }

    /// The input point with every input `v` (free timing: one input).
    pub(crate) fn input_point(&self, v: f64) -> X<K> {
        let mut x = self.base.dims().x();
        x.as_mut().fill(v);
        x
    }
}

/// The Newton configuration of a problem's position solves unless [`ProblemOf::with_newton`]
/// sets another: a residual tolerance of `1e-14` and a step tolerance of `1e-16`, positions to
/// rounding, so that the targets can be met to rounding. Its
/// [`largest_precise_angle`](NewtonConfig::largest_precise_angle), the largest angle parameter a
/// search accepts, is therefore tighter than a sweep's by default: a program that takes the
/// parameters from its user can say so in its own terms before it searches.
///
/// ```
/// use kinloop_runtime::NewtonConfig;
/// use kinloop_runtime::synthesis::default_newton;
/// let largest = default_newton().largest_precise_angle();
/// assert!(largest > 4e4 && largest < 5e4);
/// assert!(largest < NewtonConfig::default().largest_precise_angle());
/// ```
pub fn default_newton() -> NewtonConfig {
    NewtonConfig::default().with_residual_tol(1e-14).with_step_tol(1e-16)
}

/// Refuses free timing of several targets that are all one (every value of every target
/// equal): they ask only that the mechanism pass through that one, and a design that does
/// meets them all at one input, which is no motion, the order defect of every such candidate.
/// A search of four copies of a point a design of the box passes through ranked an exact fit
/// (error 6e-16) as invalid for "order", below a valid one that missed by 0.39; of a point none
/// reaches, it found no valid candidate and said only "order". (Prescribed inputs are kept: a
/// point held still while the input turns, a dwell, is a task.)
fn one_motion<X>(inputs: &Inputs<X>, targets: &[Vec<f64>]) -> Result<(), SynthesisError> {
    if !matches!(inputs, Inputs::Free { .. }) || targets.len() < 2 || targets.iter().any(|t| *t != targets[0]) {
        return Ok(());
    }
    let values: Vec<String> = targets[0].iter().map(|v| crate::number::Number(*v).to_string()).collect();
    Err(SynthesisError::InvalidConfig(format!(
        "all {} targets are one, ({}): with free timing they ask only that the mechanism pass through it, and a \
         design that does meets them all at one input, no motion; give targets along the motion, or prescribe the \
         inputs (`timed`) to hold it there while the input moves",
        targets.len(),
        values.join(", ")
    )))
}

/// Refuses timing whose motion from target to target turns an angle input more than a sweep
/// follows ([`MAX_TURNS`](crate::paths::sweep::MAX_TURNS)): every candidate's verifying sweep
/// would refuse its range, and each be rejected as if it could not be assembled there. Turns are
/// taken of each end first, so that ends near the largest `f64` do not overflow. (A length
/// input's turns depend on the mechanism's size at the candidate; its sweep's refusal is the
/// candidate's.)
fn check_turns<K: Kernel>(kernel: &K, inputs: &Inputs<X<K>>) -> Result<(), SynthesisError> {
    use crate::paths::sweep::MAX_TURNS;
    use std::f64::consts::TAU;
    let name = |i: usize| kernel.input_name(i).to_string();
    let angle = |i: usize| kernel.input_kind(i) == crate::QuantityKind::Angle;
    let too_far = |a: f64, b: f64| (b / TAU - a / TAU).abs() > MAX_TURNS;
    match inputs {
        Inputs::Prescribed(rows) => {
            for (k, w) in rows.windows(2).enumerate() {
                let (a, b) = (w[0].as_ref(), w[1].as_ref());
                if let Some(i) = (0..a.len()).find(|&i| angle(i) && too_far(a[i], b[i])) {
                    return Err(SynthesisError::InvalidConfig(format!(
                        "targets {k} and {} are {:.3e} turns of input `{}` apart, more than the {MAX_TURNS:e} turns \
                         a sweep follows from one to the next: give inputs closer together (reduce a periodic \
                         input by whole turns)",
                        k + 1,
                        (b[i] / TAU - a[i] / TAU).abs(),
                        name(i)
                    )));
                }
            }
        }
        &Inputs::Free { lo, hi } => {
            if angle(0) && too_far(lo, hi) {
                return Err(SynthesisError::InvalidConfig(format!(
                    "free timing within [{lo}, {hi}] spans {:.3e} turns of input `{}`, more than the {MAX_TURNS:e} \
                     turns a sweep follows: give a shorter range",
                    hi / TAU - lo / TAU,
                    name(0)
                )));
            }
        }
    }
    Ok(())
}
