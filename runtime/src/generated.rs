//! Everything the code expanded by `mechanism!` names, and nothing else.
//!
//! A generated mechanism holds only what depends on its declaration: its named types, its
//! straight-line kernels and its constants. What is the same for every mechanism lives here, once:
//! the named API as default methods of [`Named`](crate::Named) and [`NamedSensitivities`], the cold paths that
//! build errors, and the linear-algebra and Newton pieces the kernels call. The facade re-exports
//! this module as `kinloop::__gen`; it is not meant to be used by hand and may change between
//! versions.

pub use crate::analysis::{Column, ColumnIndex};
pub use crate::dynamics::{Body, Coord, DynamicsError, MassModel, Rotation};
pub use crate::error::Error;
pub use crate::events::BlockInfo;
pub use crate::kin::{ByValue, Health, Jac, Kin, KinSink, Sens, first_non_finite_state};
pub use crate::kinds::QuantityKind;
pub use crate::mechanism::extreme_scale::{
    AtLimit, Block, OwnJacobian, closes_in_own_magnitudes, in_block, singular_in_own_magnitudes, solve_blocks,
    to_rescue, vanished_row, whole_position,
};
pub use crate::mechanism::{Mechanism, Sensitivities};
pub use crate::mechanism::{block_failure, rescue, rescue_position, rescue_sensitivities};
pub use crate::named::{NamedSensitivities, SensitivitiesRequested};
pub use crate::solvers::closed::*;
pub use crate::solvers::deferred::*;
pub use crate::solvers::inverse2::Inverse2;
pub use crate::solvers::jacobian::{BlockFactor, BlockJacobian};
pub use crate::solvers::lu::{Factor, Fixed, Lu, max_abs};
pub use crate::solvers::newton::{
    BlockEval, BlockFailure, Magnitudes, NewtonConfig, SolveReport, Solved, newton, newton_keeping_lu, newton_with,
    newton_with_work,
};
pub use crate::solvers::sparse_lu::{SparseJac, SparseLu, SparsePattern};
pub use crate::solvers::sparse_lu_dyn::{PaddedJac, PaddedLu, PaddedWork, SparseTables};
pub use crate::solvers::sparse_steps::{Pivots, SparseSteps, Tables, scaled};
pub use crate::solvers::turns::*;
pub use crate::trig::{InputTrig, Libm, NearSlot, NearTrig, Preset, add_angles};
pub use crate::vec2::Vec2;
pub use std::borrow::Cow;
/// A compiled mechanism's names in its block descriptions (`Name("beta")`, `Cow::Borrowed`: a
/// constant, nothing allocated; the short name keeps the expansion's lines short).
pub use std::borrow::Cow::Borrowed as Name;

/// A format's serializer and deserializer that write and read every `f64` within a value as the
/// crate's other numbers are (a non-finite one as `"NaN"`, `"inf"`, `"-inf"` in a
/// human-readable format): what the serde impls of generated structs hand their fields to.
#[cfg(feature = "serde")]
pub use crate::floats_serde::within::{De as FloatsDe, Ser as FloatsSer};
/// serde, for the derives of generated types (feature `serde`): users need no serde dependency.
#[cfg(feature = "serde")]
pub use serde;

use crate::error::{Computed, Quantity};
use crate::kin::FlatMotion;
use crate::mechanism::{bad_values, location};

/// The first row holding a non-finite value (cold-path diagnosis of a failed factorisation).
/// Given the rows, not a reference to them: a reference would keep the kernel's Jacobian and
/// right-hand sides in memory on the path where the factorisation passes.
#[cold]
pub fn first_bad_row<const M: usize, const R: usize>(rows: [[f64; M]; R]) -> Option<usize> {
    rows.iter().position(|r| r.iter().any(|v| !v.is_finite()))
}

/// [`block_failure`] of block `block` at `x` from `guess` with `cfg`, as a function of the
/// failure: what a closed-form block maps its failures with (one short line of generated code).
#[inline(always)]
pub fn failure_of<'a, M, const N: usize, const NI: usize, const NO: usize>(
    m: &'a M,
    block: usize,
    x: &'a [f64; NI],
    guess: &'a [f64; N],
    cfg: &'a NewtonConfig,
) -> impl Fn(BlockFailure) -> Error + Copy + 'a
where
    M: Mechanism<N, NI, NO>,
{
    move |fail| block_failure(m, block, fail, x, guess, cfg)
}

/// The error of an invalid configuration `field`, located at block `block` (the first the
/// kernel solves), unless a bad value explains the failure.
#[cold]
#[inline(never)]
pub fn config_failure<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    block: usize,
    field: &'static str,
    x: &[f64; NI],
    guess: &[f64; N],
) -> Error
where
    M: Mechanism<N, NI, NO>,
{
    // The configuration is not read: an invalid one explains nothing else.
    block_failure(m, block, BlockFailure::InvalidConfig { field }, x, guess, &NewtonConfig::default())
}

/// `Ok` for a valid configuration, else the error naming its field out of range (the block's
/// error, at the caller's position): the check that opens `kinematics_at_flat` and
/// `sensitivities_at_flat` (one statement of the expansion, with `?`).
#[inline(always)]
pub fn config_checked_at<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    cfg: &NewtonConfig,
    x: &[f64; NI],
) -> Result<(), Error>
where
    M: Mechanism<N, NI, NO>,
{
    match cfg.invalid_field() {
        Some(field) => Err(config_failure_at(m, 0, field, x)),
        None => Ok(()),
    }
}

/// [`config_failure`] of the analogs at a position the caller gives (`kinematics_at_flat`,
/// `sensitivities_at_flat`), which read the configuration's `singular_tol`: there is no guess,
/// and the position is the caller's, named as such by the named API (a NaN tolerance made
/// every block "singular", a negative one was taken).
#[cold]
#[inline(never)]
fn config_failure_at<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    block: usize,
    field: &'static str,
    x: &[f64; NI],
) -> Error
where
    M: Mechanism<N, NI, NO>,
{
    if let Some(e) = bad_values::<M, N, NI, NO>(m, x, None) {
        return e;
    }
    block_error(BlockFailure::InvalidConfig { field }, location::<M, N, NI, NO>(x, Some(block)))
}

/// The error for a block whose factorisation failed: a bad value, an equation outside its
/// domain (`bad_row`, a non-finite row), or a singular position.
#[cold]
#[inline(never)]
pub fn singular<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    block: usize,
    pivot_ratio: f64,
    cfg: &NewtonConfig,
    x: &[f64; NI],
    bad_row: Option<usize>,
) -> Error
where
    M: Mechanism<N, NI, NO>,
{
    if let Some(e) = bad_values::<M, N, NI, NO>(m, x, None) {
        return e;
    }
    let at = Box::new(location::<M, N, NI, NO>(x, Some(block)));
    if let Some(row) = bad_row {
        let name = M::BLOCKS.get(block).and_then(|b| b.equations.get(row)).cloned().unwrap_or(Cow::Borrowed("?"));
        return Error::Domain { what: Computed::Equation, name, at };
    }
    Error::Singular { pivot_ratio, tolerance: cfg.singular_tol, at }
}

/// The error for a kinematic state holding a non-finite value, unless a bad value explains it.
#[cold]
#[inline(never)]
fn non_finite<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    kin: &Kin<N, NI, NO>,
    guess: Option<&[f64; N]>,
) -> Error
where
    M: Mechanism<N, NI, NO>,
{
    if let Some(e) = bad_values::<M, N, NI, NO>(m, &kin.x, guess) {
        return e;
    }
    let (what, index) = kin.first_non_finite().unwrap_or((Computed::Value, 0));
    let name = if what.is_output() { M::OUTPUTS.get(index) } else { M::UNKNOWNS.get(index) };
    Error::Domain {
        what,
        name: Cow::Borrowed(name.copied().unwrap_or("?")),
        at: Box::new(location::<M, N, NI, NO>(&kin.x, None)),
    }
}

/// The kinematic state `kin` when every value is finite, otherwise the error naming the first
/// bad one. `sum` is the sum of all values, computed by the kernel: when it is finite (the usual
/// case) so is every value, and nothing else is examined.
#[inline(always)]
pub fn checked<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    kin: Kin<N, NI, NO>,
    sum: f64,
    guess: Option<&[f64; N]>,
) -> Result<Kin<N, NI, NO>, Error>
where
    M: Mechanism<N, NI, NO>,
{
    if sum.is_finite() || kin.all_finite() { Ok(kin) } else { Err(non_finite::<M, N, NI, NO>(m, &kin, guess)) }
}

/// The result of a kinematic kernel (a short name keeps the expansions short).
pub type KinResult<const N: usize, const NI: usize, const NO: usize> = Result<Kin<N, NI, NO>, Error>;

/// What a generated `position_flat` returns: the positions and the solve's report, or the
/// error (an alias, so that the expansion says it on one line).
pub type PositionResult<const N: usize> = Result<([f64; N], SolveReport), Error>;

/// [`checked`] with the state built by `kin` where `sink` puts it: when `sum` is finite (the
/// usual case) the state is built directly in the result or in the caller's slot, without the
/// copy that passing a built state would make.
#[inline(always)]
pub fn checked_with<M, S, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    sum: f64,
    guess: Option<&[f64; N]>,
    sink: S,
    kin: impl FnOnce() -> Kin<N, NI, NO>,
) -> Result<S::Out, Error>
where
    M: Mechanism<N, NI, NO>,
    S: KinSink<N, NI, NO>,
{
    if sum.is_finite() { Ok(sink.put(kin)) } else { checked(m, kin(), sum, guess).map(|k| sink.put(|| k)) }
}

/// What a kernel whose checks are deferred does after a failed test and at its end: the part of
/// [`Checks`] that runs the mechanism's kernel, defined here with the `Mechanism` trait (its
/// closed-form steps are the solvers', which know no mechanism).
impl<const CHECKED: bool> Checks<CHECKED> {
    /// The checked kernel's answer from the deferred one's arguments: where a test failed.
    #[inline(always)]
    pub fn rerun<M, T, S, const N: usize, const NI: usize, const NO: usize>(
        self,
        (m, x, guess, cfg, trig): (&M, &[f64; NI], &[f64; N], &NewtonConfig, &mut T),
        sink: S,
    ) -> Result<S::Out, Error>
    where
        M: Mechanism<N, NI, NO>,
        T: InputTrig,
        S: KinSink<N, NI, NO>,
    {
        m.kinematics_step_checked(x, guess, cfg, trig, sink)
    }

    /// The kernel's end, from the kernel's arguments and the state `kin` builds, `sum` the sum of
    /// its values. Checked, [`checked_with`]. Deferred, the state where `sink` puts it when the
    /// end test `accept` holds; otherwise the checked kernel's answer.
    #[inline(always)]
    pub fn finish<M, T, S, const N: usize, const NI: usize, const NO: usize>(
        self,
        (accept, sum): (bool, f64),
        args: (&M, &[f64; NI], &[f64; N], &NewtonConfig, &mut T),
        sink: S,
        kin: impl FnOnce() -> Kin<N, NI, NO>,
    ) -> Result<S::Out, Error>
    where
        M: Mechanism<N, NI, NO>,
        T: InputTrig,
        S: KinSink<N, NI, NO>,
    {
        if CHECKED {
            checked_with(args.0, sum, Some(args.2), sink, kin)
        } else if accept {
            Ok(sink.put(kin))
        } else {
            self.rerun(args, sink)
        }
    }
}

/// Checks the kinematic state `kin` and its sensitivities `sens`: both are returned when every
/// value is finite, otherwise the error naming the first bad one.
#[allow(clippy::type_complexity)]
pub fn checked_sensitivities<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    m: &M,
    kin: Kin<N, NI, NO>,
    sens: Sens<N, NI, NO, NP>,
    guess: Option<&[f64; N]>,
) -> Result<(Kin<N, NI, NO>, Sens<N, NI, NO, NP>), Error>
where
    M: Mechanism<N, NI, NO>,
{
    if !kin.all_finite() {
        return Err(non_finite::<M, N, NI, NO>(m, &kin, guess));
    }
    if !sens.all_finite() {
        return Err(Error::Domain {
            what: Computed::ParameterSensitivity,
            name: Cow::Borrowed(sens.first_non_finite(&M::UNKNOWNS, &M::OUTPUTS)),
            at: Box::new(location::<M, N, NI, NO>(&kin.x, None)),
        });
    }
    Ok((kin, sens))
}

/// True velocities and accelerations of a state of mechanism `M`, after checking that the
/// input speeds `omega` and accelerations `eps` are finite.
pub fn motion<M, const N: usize, const NI: usize, const NO: usize>(
    kin: &Kin<N, NI, NO>,
    omega: [f64; NI],
    eps: [f64; NI],
) -> Result<FlatMotion<N, NO>, Error>
where
    M: Mechanism<N, NI, NO>,
{
    let names = M::INPUTS.iter().chain(M::INPUTS.iter());
    if let Some((name, value)) = names.zip(omega.iter().chain(eps.iter())).find(|(_, v)| !v.is_finite()) {
        let at = Box::new(location::<M, N, NI, NO>(&kin.x, None));
        return Err(Error::NonFinite { what: Quantity::Motion, name: Cow::Borrowed(name), value: *value, at });
    }
    kin.checked_motion::<M>(&omega, &eps)
}

/// The part of a generated mechanism that depends only on its type names and sizes: the
/// inherent named API as one-line forwarders to [`Named`](crate::Named) (so that `m.solve(x)`
/// needs no import),
/// `state.motion(omega, eps)`, and the conversions of the named types to and from nalgebra
/// vectors and [`FlatMotion`]. Invoked once per mechanism by the expansion of `mechanism!`.
#[doc(hidden)]
#[macro_export]
macro_rules! __named_api {
    ($name:ident, $inputs:ident, $unknowns:ident, $outputs:ident, $state:ident, $motion:ident, $n:literal, $ni:literal, $no:literal) => {
        impl $crate::Named<$n, $ni, $no> for $name {
            type Inputs = $inputs;
            type Unknowns = $unknowns;
            type Outputs = $outputs;
            type State = $state;
        }

        /// The named API (see [`Named`](::kinloop::Named), where each method is described).
        impl $name {
            /// The kind of quantity of each input (angle, length, ...), inferred from the
            /// declaration (the units of a table's CSV header).
            pub const INPUT_KINDS: [$crate::QuantityKind; $ni] = <Self as $crate::Mechanism<$n, $ni, $no>>::INPUT_KINDS;
            /// The kind of quantity of each unknown, inferred from the declaration.
            pub const UNKNOWN_KINDS: [$crate::QuantityKind; $n] =
                <Self as $crate::Mechanism<$n, $ni, $no>>::UNKNOWN_KINDS;
            /// The kind of quantity of each output column, inferred from the declaration.
            pub const OUTPUT_KINDS: [$crate::QuantityKind; $no] =
                <Self as $crate::Mechanism<$n, $ni, $no>>::OUTPUT_KINDS;

            /// Checks that every parameter is finite.
            pub fn check(&self) -> ::core::result::Result<(), $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::check(self)
            }

            /// The declared initial guess (assembly mode) at `input`.
            pub fn guess(&self, input: impl ::core::convert::Into<$inputs>) -> $unknowns {
                <Self as $crate::Named<$n, $ni, $no>>::guess(self, input)
            }

            /// Residuals of the scalar equations (named by `EQUATIONS`) at a position.
            pub fn residual(
                &self,
                input: impl ::core::convert::Into<$inputs>,
                unknowns: &$unknowns,
            ) -> [::core::primitive::f64; $n] {
                <Self as $crate::Named<$n, $ni, $no>>::residual(self, input, unknowns)
            }

            /// Output values at a position.
            pub fn outputs(&self, input: impl ::core::convert::Into<$inputs>, unknowns: &$unknowns) -> $outputs {
                <Self as $crate::Named<$n, $ni, $no>>::outputs(self, input, unknowns)
            }

            /// Solves the positions by Newton's method from `guess` (which picks the assembly
            /// mode), with the default [`NewtonConfig`](::kinloop::NewtonConfig).
            pub fn position(
                &self,
                input: impl ::core::convert::Into<$inputs>,
                guess: &$unknowns,
            ) -> ::core::result::Result<($unknowns, $crate::SolveReport), $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::position(self, input, guess)
            }

            /// [`Self::position`] with an explicit solver configuration.
            pub fn position_with(
                &self,
                input: impl ::core::convert::Into<$inputs>,
                guess: &$unknowns,
                cfg: &$crate::NewtonConfig,
            ) -> ::core::result::Result<($unknowns, $crate::SolveReport), $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::position_with(self, input, guess, cfg)
            }

            /// Positions, velocity and acceleration analogs, and outputs, solved from `guess`.
            pub fn kinematics(
                &self,
                input: impl ::core::convert::Into<$inputs>,
                guess: &$unknowns,
            ) -> ::core::result::Result<$state, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::kinematics(self, input, guess)
            }

            /// [`Self::kinematics`] with an explicit solver configuration.
            #[inline]
            pub fn kinematics_with(
                &self,
                input: impl ::core::convert::Into<$inputs>,
                guess: &$unknowns,
                cfg: &$crate::NewtonConfig,
            ) -> ::core::result::Result<$state, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::kinematics_with(self, input, guess, cfg)
            }

            /// Analogs and outputs at a position the caller already solved.
            pub fn kinematics_at(
                &self,
                input: impl ::core::convert::Into<$inputs>,
                unknowns: &$unknowns,
            ) -> ::core::result::Result<$state, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::kinematics_at(self, input, unknowns)
            }

            /// Full kinematics at `input`, starting from the declared initial guess.
            pub fn solve(
                &self,
                input: impl ::core::convert::Into<$inputs>,
            ) -> ::core::result::Result<$state, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::solve(self, input)
            }

            /// A lazy sweep of `samples` equally spaced inputs from `from` to `to` (both
            /// included) that never jumps branches: see [`Sweep`](::kinloop::Sweep). `guess` at
            /// `from` picks the assembly mode.
            #[allow(clippy::type_complexity)]
            pub fn sweep(
                &self,
                from: impl ::core::convert::Into<$inputs>,
                to: impl ::core::convert::Into<$inputs>,
                samples: ::core::primitive::usize,
                guess: &$unknowns,
            ) -> ::core::result::Result<$crate::Sweep<'_, Self, $state, $n, $ni, $no>, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::sweep(self, from, to, samples, guess)
            }

            /// A sweep kept in memory for analysis by column (`Name::COL.x`): extremes, ranges,
            /// dwells, harmonics (see [`Named::sampled`](::kinloop::Named::sampled)).
            pub fn sampled(
                &self,
                from: impl ::core::convert::Into<$inputs>,
                to: impl ::core::convert::Into<$inputs>,
                samples: ::core::primitive::usize,
                guess: &$unknowns,
            ) -> ::core::result::Result<$crate::analysis::Sampled<'_, Self, $n, $no, $ni>, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::sampled(self, from, to, samples, guess)
            }

            /// The states at the given inputs, in their order, without jumping branches (see
            /// [`Named::sweep_at`](::kinloop::Named::sweep_at)); `guess` at the first input
            /// picks the assembly mode.
            pub fn sweep_at<I: ::core::convert::Into<$inputs>>(
                &self,
                inputs: impl ::core::iter::IntoIterator<Item = I>,
                guess: &$unknowns,
            ) -> $crate::SweepResult<$state> {
                <Self as $crate::Named<$n, $ni, $no>>::sweep_at(self, inputs, guess)
            }

            /// This mechanism with its own solver configuration, used by every solve, sweep and
            /// trace of the result (see [`Named::with_config`](::kinloop::Named::with_config)).
            pub fn with_config(
                self,
                config: impl ::core::convert::Into<$crate::SweepConfig>,
            ) -> ::core::result::Result<$crate::Configured<Self>, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::with_config(self, config)
            }

            /// How far the input can move from `at` towards `at + delta` and `at - delta`
            /// before a limit position, in input values (see
            /// [`Named::reachable`](::kinloop::Named::reachable)).
            pub fn reachable(
                &self,
                at: impl ::core::convert::Into<$inputs>,
                delta: impl ::core::convert::Into<$inputs>,
                guess: &$unknowns,
                samples: ::core::primitive::usize,
            ) -> ::core::result::Result<$crate::Reach<$inputs>, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::reachable(self, at, delta, guess, samples)
            }

            /// The whole solution curve through limit positions (see
            /// [`Named::trace_curve`](::kinloop::Named::trace_curve)).
            pub fn trace_curve(
                &self,
                from: impl ::core::convert::Into<$inputs>,
                to: impl ::core::convert::Into<$inputs>,
                guess: &$unknowns,
                opts: &$crate::TraceConfig,
            ) -> ::core::result::Result<$crate::Traced<$n, $ni>, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::trace_curve(self, from, to, guess, opts)
            }

            /// The distinct assembly modes at `input` (multi-start Newton; see
            /// [`Named::assembly_modes`](::kinloop::Named::assembly_modes)), e.g. to pick "elbow up" with
            /// `.into_iter().find(|s| ...)`. Empty where the links cannot close; an error for an
            /// input or a parameter not finite, `Error::Singular` at a limit position, and
            /// `Error::NoConvergence` where no start solves and some ran out of iterations.
            pub fn assembly_modes(
                &self,
                input: impl ::core::convert::Into<$inputs>,
            ) -> ::core::result::Result<::std::vec::Vec<$state>, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::assembly_modes(self, input)
            }

            /// Where a mechanism of one angle input assembles nearest `at`, where it may not:
            /// the stretch between its limit positions, or `None` where its loops close nowhere
            /// on the turn (`Error::NoConvergence` where no sample solves and some ran out of
            /// iterations; see [`Named::assembly_near`](::kinloop::Named::assembly_near)).
            pub fn assembly_near(
                &self,
                at: impl ::core::convert::Into<$inputs>,
            ) -> ::core::result::Result<::core::option::Option<$crate::Assembly<$inputs>>, $crate::Error> {
                <Self as $crate::Named<$n, $ni, $no>>::assembly_near(self, at)
            }
        }

        impl $state {
            /// True velocities and accelerations for input speeds `omega` and input
            /// accelerations `eps`: `v = v_q omega`, `a = a_q omega^2 + v_q eps` (summed over
            /// inputs for several inputs). For a time input pass `omega = 1`, `eps = 0`.
            pub fn motion(
                &self,
                omega: impl ::core::convert::Into<$inputs>,
                eps: impl ::core::convert::Into<$inputs>,
            ) -> ::core::result::Result<$motion, $crate::Error> {
                let __omega = ::core::convert::Into::into(::core::convert::Into::<$inputs>::into(omega));
                let __eps = ::core::convert::Into::into(::core::convert::Into::<$inputs>::into(eps));
                $crate::generated::motion::<$name, $n, $ni, $no>(&self.flat, __omega, __eps).map(|__m| $motion {
                    qdot: ::core::convert::Into::into(__m.qdot),
                    qddot: ::core::convert::Into::into(__m.qddot),
                    out_dot: ::core::convert::Into::into(__m.out_dot),
                    out_ddot: ::core::convert::Into::into(__m.out_ddot),
                })
            }
        }

        impl ::core::convert::From<$crate::nalgebra::SVector<::core::primitive::f64, $n>>
            for $unknowns<::core::primitive::f64>
        {
            fn from(__v: $crate::nalgebra::SVector<::core::primitive::f64, $n>) -> Self {
                ::core::convert::Into::into(<[::core::primitive::f64; $n] as ::core::convert::From<_>>::from(__v))
            }
        }

        impl ::core::convert::From<$unknowns<::core::primitive::f64>>
            for $crate::nalgebra::SVector<::core::primitive::f64, $n>
        {
            fn from(__v: $unknowns<::core::primitive::f64>) -> Self {
                ::core::convert::Into::into(<[::core::primitive::f64; $n] as ::core::convert::From<_>>::from(__v))
            }
        }
    };
}

pub use crate::__named_api as named_api;

/// `NameColumns` and the constant `Name::COL` of a generated mechanism: one typed
/// [`Column`] handle per input, unknown, point coordinate and scalar output, each with its
/// name and its index in the flat arrays (given by the expansion of `mechanism!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __columns {
    ($vis:vis $name:ident, $columns:ident;
     inputs $($i:ident $is:literal $ii:literal),*;
     unknowns $($u:ident $us:literal $ui:literal),*;
     points $($p:ident $px:literal $py:literal $pi:literal),*;
     outputs $($o:ident $os:literal $oi:literal),*) => {
        #[doc = ::core::concat!("The columns of [`", ::core::stringify!($name), "`] as typed handles for the analysis helpers \
            (`kinloop::analysis::Sampled`): `", ::core::stringify!($name), "::COL.name`, `", ::core::stringify!($name), "::COL.point.x`.")]
        #[derive(::core::clone::Clone, ::core::marker::Copy, ::core::fmt::Debug)]
        #[allow(non_snake_case)]
        $vis struct $columns {
            $(#[doc = ::core::concat!("Input `", $is, "`.")] pub $i: $crate::analysis::Column<$name>,)*
            $(#[doc = ::core::concat!("Unknown `", $us, "`.")] pub $u: $crate::analysis::Column<$name>,)*
            $(#[doc = ::core::concat!("Point `", $px, "`, `", $py, "`.")] pub $p: $crate::Vec2<$crate::analysis::Column<$name>>,)*
            $(#[doc = ::core::concat!("Output `", $os, "`.")] pub $o: $crate::analysis::Column<$name>,)*
        }
        impl $name {
            #[doc = ::core::concat!("Every column of [`", ::core::stringify!($name), "`] as a typed analysis handle (see [`",
                ::core::stringify!($columns), "`]).")]
            pub const COL: $columns = {
                use $crate::analysis::{Column as C, ColumnIndex as I};
                $columns {
                    $($i: C::__generated(I::Input($ii), $is),)*
                    $($u: C::__generated(I::Unknown($ui), $us),)*
                    $($p: $crate::Vec2 { x: C::__generated(I::Output($pi), $px), y: C::__generated(I::Output($pi + 1), $py) },)*
                    $($o: C::__generated(I::Output($oi), $os),)*
                }
            };
        }
    };
}
#[doc(hidden)]
pub use crate::__columns as columns;

/// The kinds of quantity of a generated mechanism's columns in its `Mechanism` implementation, by
/// the names of [`QuantityKind`]'s variants: `kinds!(NI [Angle], N [Angle, Length] [true,
/// false], NO [Length])`, the unknowns' followed by which of them a closed-form block gives as
/// angles (`CLOSED_FORM_ANGLES`).
#[doc(hidden)]
#[macro_export]
macro_rules! __kinds {
    ($ni:literal [$($i:ident),*], $n:literal [$($u:ident),*] [$($c:literal),*], $no:literal [$($o:ident),*]) => {
        const INPUT_KINDS: [$crate::QuantityKind; $ni] = [$($crate::QuantityKind::$i),*];
        const UNKNOWN_KINDS: [$crate::QuantityKind; $n] = [$($crate::QuantityKind::$u),*];
        const CLOSED_FORM_ANGLES: [::core::primitive::bool; $n] = [$($c),*];
        const OUTPUT_KINDS: [$crate::QuantityKind; $no] = [$($crate::QuantityKind::$o),*];
    };
}
#[doc(hidden)]
pub use crate::__kinds as kinds;

/// The names and the decomposition of a generated mechanism in its `Mechanism` implementation,
/// from the inherent constants of the same names, and its parameter values as a `Vec`:
/// `mechanism_consts!(Name, N, NI, NO)`, and with `; 5 f` (the parameters that are angles, index
/// and field) `Mechanism::angle_param_beyond`. One line of expansion instead of nine or more.
#[doc(hidden)]
#[macro_export]
macro_rules! __mechanism_consts {
    ($name:ident, $n:literal, $ni:literal, $no:literal) => {
        const NAME: &'static ::core::primitive::str = $name::NAME;
        const PARAMS: &'static [&'static ::core::primitive::str] = &$name::PARAMS;
        const INPUTS: [&'static ::core::primitive::str; $ni] = $name::INPUTS;
        const UNKNOWNS: [&'static ::core::primitive::str; $n] = $name::UNKNOWNS;
        const EQUATIONS: [&'static ::core::primitive::str; $n] = $name::EQUATIONS;
        const OUTPUTS: [&'static ::core::primitive::str; $no] = $name::OUTPUTS;
        const BLOCKS: &'static [$crate::BlockInfo] = $name::BLOCKS;
        fn param_values(&self) -> ::std::vec::Vec<::core::primitive::f64> {
            $name::param_values(self).to_vec()
        }
    };
    // With the parameters that are angles (index and field: `; 5 f`),
    // `Mechanism::angle_param_beyond`: one test per angle parameter, made at a solve's entry,
    // never per step.
    ($name:ident, $n:literal, $ni:literal, $no:literal; $($k:literal $p:ident),+) => {
        $crate::__mechanism_consts!($name, $n, $ni, $no);
        fn angle_param_beyond(
            &self,
            bound: ::core::primitive::f64,
        ) -> ::core::option::Option<::core::primitive::usize> {
            $(if self.$p.abs() > bound && self.$p.is_finite() {
                return ::core::option::Option::Some($k);
            })+
            ::core::option::Option::None
        }
    };
}
#[doc(hidden)]
pub use crate::__mechanism_consts as mechanism_consts;

/// `From<[T; N]>` for a named struct of a generated mechanism (its inputs, unknowns, outputs,
/// the parameters of its sensitivities) and back, in field order, each field bound to the name
/// in parentheses: `array_conversions!(Name, N; a(f0), b(f1))` for fields of type `T`,
/// `array_conversions!(Name, N; points p(o0, o1); scalars s(o2))` for outputs, whose points
/// are `Vec2<T>`, and `array_conversions!(Name, 0;)` for a struct without fields (its
/// `__marker`). One line of expansion instead of a dozen.
#[doc(hidden)]
#[macro_export]
macro_rules! __array_conversions {
    ($ty:ident, 0;) => {
        impl<T> ::core::convert::From<[T; 0]> for $ty<T> {
            #[inline]
            fn from([]: [T; 0]) -> Self {
                $ty { __marker: ::core::marker::PhantomData }
            }
        }
        impl<T> ::core::convert::From<$ty<T>> for [T; 0] {
            #[inline]
            fn from(_: $ty<T>) -> Self {
                []
            }
        }
    };
    ($ty:ident, $n:literal; points $($p:ident($px:ident, $py:ident)),*; scalars $($s:ident($sv:ident)),*) => {
        impl<T> ::core::convert::From<[T; $n]> for $ty<T> {
            #[inline]
            fn from([$($px, $py,)* $($sv,)*]: [T; $n]) -> Self {
                $ty { $($p: $crate::Vec2 { x: $px, y: $py },)* $($s: $sv,)* }
            }
        }
        impl<T> ::core::convert::From<$ty<T>> for [T; $n] {
            #[inline]
            fn from(__v: $ty<T>) -> Self {
                [$(__v.$p.x, __v.$p.y,)* $(__v.$s,)*]
            }
        }
        // By reference too, so that `&m.guess(x)` is the one way to pass a guess, whether the
        // callee takes the named unknowns or an array.
        impl<T: ::core::marker::Copy> ::core::convert::From<&$ty<T>> for [T; $n] {
            #[inline]
            fn from(__v: &$ty<T>) -> Self {
                [$(__v.$p.x, __v.$p.y,)* $(__v.$s,)*]
            }
        }
    };
    ($ty:ident, $n:literal; $($f:ident($b:ident)),+) => {
        $crate::__array_conversions!($ty, $n; points; scalars $($f($b)),+);
    };
}
#[doc(hidden)]
pub use crate::__array_conversions as array_conversions;

/// `from_param_values` of a generated mechanism, in its `impl` block: each field set by name
/// from the values in declaration order, `from_param_values!(N; a 0, b 1)`. No value is bound
/// to a local named like a parameter: a constant of the user's module of that name would turn
/// the binding into a pattern. One line of expansion instead of one per parameter.
#[doc(hidden)]
#[macro_export]
macro_rules! __from_param_values {
    (0;) => {
        /// Builds the mechanism from parameter values in declaration order.
        pub fn from_param_values(_: [::core::primitive::f64; 0]) -> Self {
            Self {}
        }
    };
    ($n:literal; $($f:ident $i:tt),+) => {
        /// Builds the mechanism from parameter values in declaration order.
        pub fn from_param_values(__values: [::core::primitive::f64; $n]) -> Self {
            Self { $($f: __values[$i]),+ }
        }
    };
}
#[doc(hidden)]
pub use crate::__from_param_values as from_param_values;

// The named surface of a declaration `mechanism!` rejected (see `rejected`).
pub use crate::__no_mass_model as no_mass_model;
pub use crate::__rejected_mechanism as rejected_mechanism;
mod rejected;
pub use rejected::{MassModelDeclared, rejected};

// A state's serialized form, by name (see `state_by_name`).
pub use crate::__state_by_name as state_by_name;
mod state_by_name;
pub use state_by_name::StateByName;

// The parallel half of a scan over sets, shared with a run-time model's (see `par_sets`).
#[cfg(feature = "rayon")]
mod par_sets;
#[cfg(feature = "rayon")]
pub use par_sets::par_sets;

// The name-agnostic cores of a failed step's diagnosis (see `diagnosis`).
mod diagnosis;
pub use diagnosis::{block_error, first_bad_value, imprecise_param, turns_culprit, turns_error};
