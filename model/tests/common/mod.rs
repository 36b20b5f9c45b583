//! What the model's parity tests share: reading a fixture's text, setting its parameters, and a
//! compiled mechanism stepping with libm's sines and cosines as a run-time model does.
// Each test binary uses a part of it.
#![allow(dead_code)]

use kinloop::{Kin, Mechanism};

/// Declares a mechanism with `kinloop::mechanism!` and keeps its text (`#[macro_use] mod common;`
/// makes it visible to the test file).
#[allow(unused_macros)] // Not every test binary declares mechanisms.
macro_rules! declared {
    ($text:ident => $($t:tt)*) => {
        kinloop::mechanism! { $($t)* }
        const $text: &str = stringify!($($t)*);
    };
}
use kinloop_model::Model;

/// The model of a fixture's text (a fixture is valid: a rejection is a test failure).
pub fn read(text: &str) -> Model {
    Model::read("fixture.kl", text).unwrap_or_else(|e| panic!("{e}"))
}

/// Sets the parameters `values` of `m`, each of which must exist.
pub fn set(m: &mut Model, values: &[(&str, f64)]) {
    for (p, v) in values {
        assert!(m.set_param(p, *v), "{p}");
    }
}

/// A compiled mechanism whose sweep steps take libm's sines and cosines, as a run-time model's
/// do: every kernel forwarded except the sweep's fast step (`kinematics_step_sink`), which then
/// keeps its default, `kinematics_flat`.
pub struct Libm<M>(pub M);

impl<M, const N: usize, const NI: usize, const NO: usize> Mechanism<N, NI, NO> for Libm<M>
where
    M: Mechanism<N, NI, NO>,
{
    const NAME: &'static str = M::NAME;
    const PARAMS: &'static [&'static str] = M::PARAMS;
    const INPUTS: [&'static str; NI] = M::INPUTS;
    const UNKNOWNS: [&'static str; N] = M::UNKNOWNS;
    const EQUATIONS: [&'static str; N] = M::EQUATIONS;
    const OUTPUTS: [&'static str; NO] = M::OUTPUTS;
    const BLOCKS: &'static [kinloop::BlockInfo] = M::BLOCKS;
    const INPUT_KINDS: [kinloop::QuantityKind; NI] = M::INPUT_KINDS;
    const UNKNOWN_KINDS: [kinloop::QuantityKind; N] = M::UNKNOWN_KINDS;
    const OUTPUT_KINDS: [kinloop::QuantityKind; NO] = M::OUTPUT_KINDS;
    const FOLLOWERS: [bool; N] = M::FOLLOWERS;
    const CLOSED_FORM_ANGLES: [bool; N] = M::CLOSED_FORM_ANGLES;
    const PIECEWISE: bool = M::PIECEWISE;
    const DRAWING: &'static str = M::DRAWING;
    fn param_values(&self) -> Vec<f64> {
        self.0.param_values()
    }
    fn guess_flat(&self, x: &[f64; NI]) -> [f64; N] {
        self.0.guess_flat(x)
    }
    fn position_flat(
        &self,
        x: &[f64; NI],
        g: &[f64; N],
        c: &kinloop::NewtonConfig,
    ) -> Result<([f64; N], kinloop::SolveReport), kinloop::Error> {
        self.0.position_flat(x, g, c)
    }
    fn kinematics_flat(
        &self,
        x: &[f64; NI],
        g: &[f64; N],
        c: &kinloop::NewtonConfig,
    ) -> Result<Kin<N, NI, NO>, kinloop::Error> {
        self.0.kinematics_flat(x, g, c)
    }
    fn kinematics_at_flat(
        &self,
        x: &[f64; NI],
        q: &[f64; N],
        c: &kinloop::NewtonConfig,
    ) -> Result<Kin<N, NI, NO>, kinloop::Error> {
        self.0.kinematics_at_flat(x, q, c)
    }
    fn outputs_flat(&self, x: &[f64; NI], q: &[f64; N]) -> [f64; NO] {
        self.0.outputs_flat(x, q)
    }
    fn jacobian_flat(&self, x: &[f64; NI], q: &[f64; N]) -> kinloop::Jac<N, NI> {
        self.0.jacobian_flat(x, q)
    }
}

/// The sensitivities forwarded too, for the objectives with gradients over the same sweep.
impl<M, const N: usize, const NI: usize, const NO: usize, const NP: usize> kinloop::Sensitivities<N, NI, NO, NP>
    for Libm<M>
where
    M: kinloop::Sensitivities<N, NI, NO, NP>,
{
    fn params_flat(&self) -> [f64; NP] {
        self.0.params_flat()
    }
    fn with_params_flat(&self, p: [f64; NP]) -> Self {
        Libm(self.0.with_params_flat(p))
    }
    fn sensitivities_flat(
        &self,
        x: &[f64; NI],
        g: &[f64; N],
        c: &kinloop::NewtonConfig,
    ) -> Result<(Kin<N, NI, NO>, kinloop::Sens<N, NI, NO, NP>), kinloop::Error> {
        self.0.sensitivities_flat(x, g, c)
    }
    fn sensitivities_at_flat(
        &self,
        x: &[f64; NI],
        q: &[f64; N],
        c: &kinloop::NewtonConfig,
    ) -> Result<(Kin<N, NI, NO>, kinloop::Sens<N, NI, NO, NP>), kinloop::Error> {
        self.0.sensitivities_at_flat(x, q, c)
    }
}
