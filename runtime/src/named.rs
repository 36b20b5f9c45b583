//! The named, typed API of a generated mechanism ([`Named`], and [`NamedSensitivities`] where it
//! was declared with sensitivities): `m.solve(phi)`, `s.q.beta`, `m.sweep(..)`, written once for
//! every mechanism on top of its flat kernels ([`Mechanism`], [`Sensitivities`]).
//!
//! Apart from those kernels' traits: the named API reaches every path and analysis of the
//! runtime (sweeps, reachable ranges, curve traces, assembly modes, sampled analyses, a
//! configured mechanism), and they are all written over the kernels, below it.

use crate::analysis::Sampled;
use crate::configured::Configured;
use crate::error::Error;
use crate::kin::{Kin, Sens};
use crate::mechanism::kernel::Compiled;
use crate::mechanism::{Mechanism, Sensitivities, given_position, guess_checked};
use crate::paths::assembles::{ASSEMBLY_SAMPLES, Assembly, assembly_near};
use crate::paths::config::SweepConfig;
use crate::paths::modes::assembly_modes;
use crate::paths::outcome::SweepResult;
use crate::paths::reach::{Reach, reachable};
use crate::paths::sweep::Sweep;
use crate::paths::sweep_at::sweep_at_of;
use crate::paths::trace::{TraceConfig, Traced, trace_curve};
use crate::solvers::newton::{NewtonConfig, SolveReport};

/// The named, typed API of a generated mechanism (`m.solve(phi)`, `s.q.beta`), written once for
/// every mechanism on top of its flat kernels ([`Mechanism`]). Generated types forward their
/// inherent methods here, so calling them needs no import; generic code can use this trait.
pub trait Named<const N: usize, const NI: usize, const NO: usize>: Mechanism<N, NI, NO> + Sized {
    /// `NameInputs`: the input values by name.
    type Inputs: Copy + From<[f64; NI]> + Into<[f64; NI]>;
    /// `NameUnknowns`: positions by name.
    type Unknowns: Copy + From<[f64; N]> + Into<[f64; N]>;
    /// `NameOutputs`: output values by name.
    type Outputs: From<[f64; NO]>;
    /// `NameState`: the kinematic state by name.
    type State: From<Kin<N, NI, NO>>;

    /// Checks that every parameter is finite.
    fn check(&self) -> Result<(), Error> {
        self.check_params()
    }

    /// This mechanism with its own solver configuration (a [`SweepConfig`], or a
    /// [`NewtonConfig`] with the other sweep settings at their defaults), used by every solve,
    /// sweep, reachable range, assembly-mode search and curve trace of the result; validated
    /// here (`Error::InvalidArgument` names the field).
    fn with_config(self, config: impl Into<SweepConfig>) -> Result<Configured<Self>, Error> {
        Configured::new(self, config)
    }

    /// The declared initial guess (assembly mode) at `input`.
    fn guess(&self, input: impl Into<Self::Inputs>) -> Self::Unknowns {
        self.guess_flat(&input.into().into()).into()
    }

    /// Residuals of the scalar equations (named by `EQUATIONS`) at a position.
    fn residual(&self, input: impl Into<Self::Inputs>, q: &Self::Unknowns) -> [f64; N] {
        self.residual_flat(&input.into().into(), &(*q).into())
    }

    /// Output values at a position.
    fn outputs(&self, input: impl Into<Self::Inputs>, q: &Self::Unknowns) -> Self::Outputs {
        self.outputs_flat(&input.into().into(), &(*q).into()).into()
    }

    /// Solves the positions by Newton's method from `guess` (which picks the assembly mode).
    fn position(
        &self,
        input: impl Into<Self::Inputs>,
        guess: &Self::Unknowns,
    ) -> Result<(Self::Unknowns, SolveReport), Error> {
        self.position_with(input, guess, &self.solver_config().newton)
    }

    /// [`Named::position`] with an explicit solver configuration.
    fn position_with(
        &self,
        input: impl Into<Self::Inputs>,
        guess: &Self::Unknowns,
        cfg: &NewtonConfig,
    ) -> Result<(Self::Unknowns, SolveReport), Error> {
        // The generated `position_flat` solves a mechanism outside the closed forms' sizes
        // again itself (`rescue_position`, see `extreme_scale`).
        self.check_param_angles(cfg)?;
        let (x, guess) = (input.into().into(), (*guess).into());
        guess_checked(self, &x, &guess)?;
        let (q, report) = self.position_flat(&x, &guess, cfg)?;
        Ok((q.into(), report))
    }

    /// Positions, velocity and acceleration analogs, and outputs, solved from `guess`.
    fn kinematics(&self, input: impl Into<Self::Inputs>, guess: &Self::Unknowns) -> Result<Self::State, Error> {
        self.kinematics_with(input, guess, &self.solver_config().newton)
    }

    /// [`Named::kinematics`] with an explicit solver configuration.
    #[inline]
    fn kinematics_with(
        &self,
        input: impl Into<Self::Inputs>,
        guess: &Self::Unknowns,
        cfg: &NewtonConfig,
    ) -> Result<Self::State, Error> {
        self.check_param_angles(cfg)?;
        let (x, guess) = (input.into().into(), (*guess).into());
        guess_checked(self, &x, &guess)?;
        self.kinematics_flat(&x, &guess, cfg).map(Self::State::from)
    }

    /// Analogs and outputs at a position the caller already solved.
    fn kinematics_at(&self, input: impl Into<Self::Inputs>, q: &Self::Unknowns) -> Result<Self::State, Error> {
        let (x, q) = (input.into().into(), (*q).into());
        match self.kinematics_at_flat(&x, &q, &self.solver_config().newton) {
            Ok(k) => Ok(k.into()),
            Err(e) => Err(given_position::<Self, N, NI, NO>(&x, &q, e)),
        }
    }

    /// Full kinematics at `input`, starting from the declared initial guess.
    fn solve(&self, input: impl Into<Self::Inputs>) -> Result<Self::State, Error> {
        let x: [f64; NI] = input.into().into();
        let cfg = self.solver_config().newton;
        self.check_param_angles(&cfg)?;
        let guess = self.guess_flat(&x);
        guess_checked(self, &x, &guess)?;
        self.kinematics_flat(&x, &guess, &cfg).map(Self::State::from)
    }

    /// A lazy sweep of `samples` equally spaced inputs from `from` to `to` (both included) that
    /// never jumps branches: see [`Sweep`]. `guess` at `from` picks the assembly mode.
    #[allow(clippy::type_complexity)]
    fn sweep(
        &self,
        from: impl Into<Self::Inputs>,
        to: impl Into<Self::Inputs>,
        samples: usize,
        guess: &Self::Unknowns,
    ) -> Result<Sweep<'_, Self, Self::State, N, NI, NO>, Error> {
        // `Sweep::new` refuses an angle parameter too large to resolve.
        Sweep::new(self, from.into().into(), to.into().into(), samples, (*guess).into())
    }

    /// `samples` equally spaced points of the straight path from `from` to `to`, solved by a
    /// branch-safe sweep from `guess` and kept in memory for analysis by column
    /// (`Name::COL.x`): see [`Sampled`](crate::analysis::Sampled). The path parameter is the
    /// input itself for one input ([`Sampled::sweep`](crate::analysis::Sampled::sweep)), the
    /// fraction of the path for several ([`Sampled::path`](crate::analysis::Sampled::path)).
    fn sampled(
        &self,
        from: impl Into<Self::Inputs>,
        to: impl Into<Self::Inputs>,
        samples: usize,
        guess: &Self::Unknowns,
    ) -> Result<Sampled<'_, Self, N, NO, NI>, Error> {
        Sampled::natural(self, from.into().into(), to.into().into(), samples, (*guess).into())
    }

    /// The states at the given inputs, in their order, followed along the path through them
    /// without jumping branches: each stretch between consecutive inputs is a [`Sweep`] with its
    /// own step control, so inputs may be unevenly spaced, far apart or repeated (measured input
    /// angles, a motion law). `guess` at the first input picks the assembly mode. The first error
    /// stops it; the result keeps the states before it, says why and where it stopped (a limit
    /// position between two inputs is located as in a sweep) and lists the events met
    /// ([`SweepResult::into_result`] for `?`). An angle parameter too large to resolve
    /// ([`Mechanism::check_param_angles`]) stops it before the first input; so do more inputs
    /// than the memory budget of their states holds, a few million (see
    /// [`sweep_at_of`]).
    fn sweep_at<I: Into<Self::Inputs>>(
        &self,
        inputs: impl IntoIterator<Item = I>,
        guess: &Self::Unknowns,
    ) -> SweepResult<Self::State> {
        // Once for the whole list: each stretch between two inputs is a sweep of its own.
        if let Err(e) = self.check_param_angles(&self.solver_config().newton) {
            return SweepResult::new(Vec::new(), Some(e), Vec::new());
        }
        let inputs = inputs.into_iter().map(|input| -> [f64; NI] { input.into().into() });
        sweep_at_of(&Compiled(self), inputs, (*guess).into()).map(Self::State::from)
    }

    /// How far the input can move from `at` towards `at + delta` and `at - delta` on the
    /// assembly mode of `guess` before a limit position, in input values (see
    /// [`reachable`](crate::paths::reach::reachable); `samples` per direction).
    fn reachable(
        &self,
        at: impl Into<Self::Inputs>,
        delta: impl Into<Self::Inputs>,
        guess: &Self::Unknowns,
        samples: usize,
    ) -> Result<Reach<Self::Inputs>, Error> {
        let reach = reachable(self, at.into().into(), delta.into().into(), (*guess).into(), samples)?;
        Ok(reach.map_inputs(Self::Inputs::from))
    }

    /// Where a mechanism of one angle input assembles nearest `at` (where a point solve failed
    /// with [`Error::NoAssembly`], say): point solves from the declared guess at `at` and at a
    /// degree's spacing over the turn about it ([`ASSEMBLY_SAMPLES`]), nearest first (of two as
    /// near, the greater), and from the first that solves the stretch reachable on its assembly
    /// mode (see
    /// [`assembly_near`](crate::paths::assembles::assembly_near)). `None` where the loops close
    /// nowhere on the turn from the declared guess; `Error::NoConvergence` where a sample tried
    /// before the first that solves, or before none, ran out of iterations (the search cannot
    /// tell whether it assembles).
    fn assembly_near(&self, at: impl Into<Self::Inputs>) -> Result<Option<Assembly<Self::Inputs>>, Error> {
        let near = assembly_near(self, at.into().into(), ASSEMBLY_SAMPLES)?;
        Ok(near.map(|a| a.map_inputs(Self::Inputs::from)))
    }

    /// The whole solution curve through `guess` at `from`, first towards `to`, through limit
    /// positions (see [`trace_curve`](crate::paths::trace::trace_curve)).
    fn trace_curve(
        &self,
        from: impl Into<Self::Inputs>,
        to: impl Into<Self::Inputs>,
        guess: &Self::Unknowns,
        opts: &TraceConfig,
    ) -> Result<Traced<N, NI>, Error> {
        trace_curve(self, from.into().into(), to.into().into(), (*guess).into(), opts)
    }

    /// The distinct assembly modes at `input` (multi-start Newton; see
    /// [`assembly_modes`](crate::paths::modes::assembly_modes)), e.g. to pick "elbow up" with
    /// `.into_iter().find(|s| ...)`. Empty where the links cannot close; an error for an input
    /// or a parameter not finite, `Error::Singular` at a limit position (where the modes meet),
    /// and `Error::NoConvergence` where no start solves and some ran out of iterations (the
    /// search cannot tell).
    fn assembly_modes(&self, input: impl Into<Self::Inputs>) -> Result<Vec<Self::State>, Error> {
        let x: [f64; NI] = input.into().into();
        Ok(assembly_modes(self, &x, 64, &self.solver_config().newton)?.into_iter().map(Self::State::from).collect())
    }
}

/// Why `sensitivities` does not compile on a mechanism declared without them: the generated
/// `sensitivities` of such a mechanism requires this trait, which no type implements (its only
/// method would have to return a value of the empty type `Infallible`).
#[diagnostic::on_unimplemented(
    message = "`{Self}` was declared without parameter sensitivities",
    label = "sensitivities are generated only on request",
    note = "add `#[kinloop(sensitivities)]` before `pub struct` in the `mechanism!` declaration of `{Self}`"
)]
pub trait SensitivitiesRequested<I> {
    /// Never called: no type implements this trait.
    fn absurd(self) -> core::convert::Infallible;
}

/// The named sensitivity API of a mechanism declared with `#[kinloop(sensitivities)]`
/// (`sens.dq.x_c.l_p`), forwarded to by its inherent methods.
pub trait NamedSensitivities<const N: usize, const NI: usize, const NO: usize, const NP: usize>:
    Named<N, NI, NO> + Sensitivities<N, NI, NO, NP>
{
    /// `NameSensitivities`: the sensitivities by name.
    type Sens: From<Sens<N, NI, NO, NP>>;

    /// Solves the kinematics from `guess` and the exact sensitivities of positions, analogs and
    /// outputs to every parameter (implicit function theorem on the same factorisations).
    fn sensitivities(
        &self,
        input: impl Into<Self::Inputs>,
        guess: &Self::Unknowns,
    ) -> Result<(Self::State, Self::Sens), Error> {
        let (x, guess) = (input.into().into(), (*guess).into());
        guess_checked(self, &x, &guess)?;
        let (k, s) = self.sensitivities_flat(&x, &guess, &self.solver_config().newton)?;
        Ok((k.into(), s.into()))
    }

    /// [`NamedSensitivities::sensitivities`] at a position the caller already solved.
    fn sensitivities_at(
        &self,
        input: impl Into<Self::Inputs>,
        q: &Self::Unknowns,
    ) -> Result<(Self::State, Self::Sens), Error> {
        let (x, q) = (input.into().into(), (*q).into());
        match self.sensitivities_at_flat(&x, &q, &self.solver_config().newton) {
            Ok((k, s)) => Ok((k.into(), s.into())),
            Err(e) => Err(given_position::<Self, N, NI, NO>(&x, &q, e)),
        }
    }
}

impl<M, const N: usize, const NI: usize, const NO: usize> Named<N, NI, NO> for Configured<M>
where
    M: Named<N, NI, NO>,
{
    type Inputs = M::Inputs;
    type Unknowns = M::Unknowns;
    type Outputs = M::Outputs;
    type State = M::State;
}
