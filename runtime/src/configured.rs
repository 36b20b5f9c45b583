//! A mechanism with its own solver configuration ([`Configured`]).

use crate::error::Error;
use crate::events::BlockInfo;
use crate::kin::{Jac, Kin, KinSink};
use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::paths::config::SweepConfig;
use crate::solvers::newton::{NewtonConfig, SolveReport};
use crate::trig::InputTrig;

/// A mechanism that carries its solver configuration: every solve, sweep, sampled analysis,
/// limit search, reachable range, assembly-mode search, curve trace, scan and inverse-dynamics
/// cycle of it uses that configuration wherever no explicit one is given. Made by `m.with_config(cfg)` ([`Named::with_config`](crate::Named::with_config)), which validates the
/// configuration once.
///
/// It implements [`Mechanism`] and [`Named`](crate::Named) like the mechanism itself; its named methods are
/// those of the [`Named`](crate::Named) trait (bring it into scope with `use kinloop::Named;`). The
/// mechanism's parameters are read through [`Configured::mechanism`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Configured<M> {
    mechanism: M,
    config: SweepConfig,
}

impl<M> Configured<M> {
    /// `mechanism` with the configuration `config`; `Error::InvalidArgument` names the first
    /// field out of range (see [`SweepConfig::validate`]).
    pub fn new(mechanism: M, config: impl Into<SweepConfig>) -> Result<Self, Error> {
        let config = config.into();
        config.validate()?;
        Ok(Configured { mechanism, config })
    }

    /// The mechanism (its parameters).
    pub fn mechanism(&self) -> &M {
        &self.mechanism
    }

    /// The configuration it carries.
    pub fn config(&self) -> &SweepConfig {
        &self.config
    }

    /// The mechanism without its configuration.
    pub fn into_inner(self) -> M {
        self.mechanism
    }
}

impl<M, const N: usize, const NI: usize, const NO: usize> Mechanism<N, NI, NO> for Configured<M>
where
    M: Mechanism<N, NI, NO>,
{
    const NAME: &'static str = M::NAME;
    const PARAMS: &'static [&'static str] = M::PARAMS;
    const INPUTS: [&'static str; NI] = M::INPUTS;
    const UNKNOWNS: [&'static str; N] = M::UNKNOWNS;
    const EQUATIONS: [&'static str; N] = M::EQUATIONS;
    const OUTPUTS: [&'static str; NO] = M::OUTPUTS;
    const BLOCKS: &'static [BlockInfo] = M::BLOCKS;
    const INPUT_KINDS: [QuantityKind; NI] = M::INPUT_KINDS;
    const UNKNOWN_KINDS: [QuantityKind; N] = M::UNKNOWN_KINDS;
    const OUTPUT_KINDS: [QuantityKind; NO] = M::OUTPUT_KINDS;
    const FOLLOWERS: [bool; N] = M::FOLLOWERS;
    const CLOSED_FORM_ANGLES: [bool; N] = M::CLOSED_FORM_ANGLES;
    const PIECEWISE: bool = M::PIECEWISE;

    fn solver_config(&self) -> SweepConfig {
        self.config
    }
    fn param_values(&self) -> Vec<f64> {
        self.mechanism.param_values()
    }
    fn guess_flat(&self, x: &[f64; NI]) -> [f64; N] {
        self.mechanism.guess_flat(x)
    }
    fn residual_flat(&self, x: &[f64; NI], q: &[f64; N]) -> [f64; N] {
        self.mechanism.residual_flat(x, q)
    }
    fn position_flat(
        &self,
        x: &[f64; NI],
        guess: &[f64; N],
        cfg: &NewtonConfig,
    ) -> Result<([f64; N], SolveReport), Error> {
        self.mechanism.position_flat(x, guess, cfg)
    }
    #[inline]
    fn kinematics_flat(&self, x: &[f64; NI], guess: &[f64; N], cfg: &NewtonConfig) -> Result<Kin<N, NI, NO>, Error> {
        self.mechanism.kinematics_flat(x, guess, cfg)
    }
    #[inline]
    fn kinematics_step_sink<T: InputTrig, S: KinSink<N, NI, NO>, const CHECKED: bool>(
        &self,
        x: &[f64; NI],
        guess: &[f64; N],
        cfg: &NewtonConfig,
        trig: &mut T,
        sink: S,
    ) -> Result<S::Out, Error> {
        self.mechanism.kinematics_step_sink::<T, S, CHECKED>(x, guess, cfg, trig, sink)
    }
    fn kinematics_at_flat(&self, x: &[f64; NI], q: &[f64; N], cfg: &NewtonConfig) -> Result<Kin<N, NI, NO>, Error> {
        self.mechanism.kinematics_at_flat(x, q, cfg)
    }
    fn outputs_flat(&self, x: &[f64; NI], q: &[f64; N]) -> [f64; NO] {
        self.mechanism.outputs_flat(x, q)
    }
    fn jacobian_flat(&self, x: &[f64; NI], q: &[f64; N]) -> Jac<N, NI> {
        self.mechanism.jacobian_flat(x, q)
    }
    fn check_params(&self) -> Result<(), Error> {
        self.mechanism.check_params()
    }
    fn angle_param_beyond(&self, bound: f64) -> Option<usize> {
        self.mechanism.angle_param_beyond(bound)
    }
}
