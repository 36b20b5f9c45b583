//! The size-agnostic view of a mechanism that the runtime's sweep, its event location and its
//! table are written over ([`Kernel`]): compiled mechanisms through [`Compiled`] (arrays,
//! constants, the macro's inlined kernel: the code of before), run-time models by their own
//! implementation (`kinloop-model`).

use crate::dims::{Dims, Fixed};
use crate::error::{Error, Quantity};
use crate::events::{BlockInfo, Location};
use crate::kin::{Jac, Kin, Sens};
use crate::kinds::QuantityKind;
use crate::mechanism::{Mechanism, Sensitivities, given_position, guess_checked};
use crate::number::Count;
use crate::paths::config::SweepConfig;
use crate::solvers::newton::NewtonConfig;
use crate::trig::InputTrig;

/// The storage of kernel `K`'s sizes.
pub(crate) type D<K> = <K as Kernel>::Dims;
/// A vector of the unknowns' size of kernel `K`.
pub(crate) type Q<K> = <D<K> as Dims>::Q;
/// A vector of the inputs' size of kernel `K`.
pub(crate) type X<K> = <D<K> as Dims>::X;
/// The kinematic state of kernel `K`.
pub(crate) type KinOf<K> = <D<K> as Dims>::Kin;

/// A mechanism as the generic algorithms see it, whatever way its sizes are known ([`Dims`]):
/// its names, kinds and structure as methods, and its flat kernels over the storage of its
/// [`Dims`]. Compiled mechanisms implement it through [`Compiled`] (whose methods return their
/// constants and forward to their kernels, so that nothing changes after inlining); a
/// `kinloop_model::Model` through its own implementation.
pub trait Kernel {
    /// How the sizes are known, and the storage of each shape.
    type Dims: Dims;
    /// The sizes.
    fn dims(&self) -> Self::Dims;
    /// The mechanism's name.
    fn name(&self) -> &str;
    /// The name of input `i`.
    fn input_name(&self, i: usize) -> &str;
    /// The name of unknown `u`.
    fn unknown_name(&self, u: usize) -> &str;
    /// The name of output column `o`.
    fn output_name(&self, o: usize) -> &str;
    /// The kind of quantity of input `i`.
    fn input_kind(&self, i: usize) -> QuantityKind;
    /// The kind of quantity of unknown `u`.
    fn unknown_kind(&self, u: usize) -> QuantityKind;
    /// The kind of quantity of output column `o`.
    fn output_kind(&self, o: usize) -> QuantityKind;
    /// The number of blocks of the decomposition.
    fn block_count(&self) -> usize;
    /// The static description of block `b` (a compiled mechanism's [`Mechanism::BLOCKS`]);
    /// `None` for a mechanism whose names are known only at run time.
    fn block_info(&self, b: usize) -> Option<BlockInfo>;
    /// The rows (equations) and columns (unknowns) of block `b`, in declaration order; `None`
    /// where they cannot be told.
    fn block_rows_cols(&self, b: usize) -> Option<(Vec<usize>, Vec<usize>)>;
    /// The unknowns a sweep judges its steps by: all but the followers
    /// ([`Mechanism::FOLLOWERS`]), in order.
    fn judged(&self) -> &[usize];
    /// Whether unknown `u` is an angle given by a closed form ([`Mechanism::CLOSED_FORM_ANGLES`]).
    fn closed_form_angle(&self, u: usize) -> bool;
    /// Whether the positions may jump ([`Mechanism::PIECEWISE`]): a sweep then judges the
    /// distance of every position from its prediction, closed-form angles' too. `false` by
    /// default.
    #[inline(always)]
    fn piecewise(&self) -> bool {
        false
    }
    /// Where an error happened: the mechanism, the inputs `x` by name, and block `block`.
    fn location(&self, x: &[f64], block: Option<usize>) -> Box<Location>;
    /// The solver configuration used where none is given ([`Mechanism::solver_config`]).
    fn solver_config(&self) -> SweepConfig;
    /// No angle parameter beyond the [`largest_precise_angle`](NewtonConfig::largest_precise_angle)
    /// of `cfg` (a compiled mechanism's [`Mechanism::check_param_angles`], whose error names
    /// the parameter, its value and the bound): a mechanism whose angle parameter is so large
    /// that an angle added to it is lost to rounding solves other equations than the declared
    /// ones. Every algorithm over a kernel asks it once at its start (a sweep at its first
    /// sample), never per step. By default none is (a hand-written kernel, which declares no
    /// angle parameters).
    fn check_param_angles(&self, cfg: &NewtonConfig) -> Result<(), Error> {
        let _ = cfg;
        Ok(())
    }
    /// The declared initial guess at input `x` ([`Mechanism::guess_flat`]): the assembly mode
    /// an assembly-mode search and a scan start from.
    fn guess(&self, x: &<Self::Dims as Dims>::X) -> <Self::Dims as Dims>::Q;
    /// Positions, analogs and outputs solved from `guess` ([`Mechanism::kinematics_flat`]).
    fn kinematics(
        &self,
        x: &<Self::Dims as Dims>::X,
        guess: &<Self::Dims as Dims>::Q,
        cfg: &NewtonConfig,
    ) -> Result<<Self::Dims as Dims>::Kin, Error>;
    /// Positions alone solved from `guess` ([`Mechanism::position_flat`]): where the velocity
    /// analogs do not exist (a limit position) the positions still do.
    fn positions(
        &self,
        x: &<Self::Dims as Dims>::X,
        guess: &<Self::Dims as Dims>::Q,
        cfg: &NewtonConfig,
    ) -> Result<<Self::Dims as Dims>::Q, Error>;
    /// Analogs and outputs at a given position ([`Mechanism::kinematics_at_flat`]).
    fn kinematics_at(
        &self,
        x: &<Self::Dims as Dims>::X,
        q: &<Self::Dims as Dims>::Q,
        cfg: &NewtonConfig,
    ) -> Result<<Self::Dims as Dims>::Kin, Error>;
    /// Residuals and Jacobians at `(x, q)` ([`Mechanism::jacobian_flat`]).
    fn jacobian(&self, x: &<Self::Dims as Dims>::X, q: &<Self::Dims as Dims>::Q) -> <Self::Dims as Dims>::Jac;
    /// A sweep's step: [`Kernel::kinematics`] written into `into`, the sines and cosines of the
    /// input arguments possibly from `trig`, checks possibly deferred
    /// ([`Mechanism::kinematics_step_sink`]). `cfg` must be valid.
    fn step_into<T: InputTrig>(
        &self,
        x: &<Self::Dims as Dims>::X,
        guess: &<Self::Dims as Dims>::Q,
        cfg: &NewtonConfig,
        trig: &mut T,
        into: &mut <Self::Dims as Dims>::Kin,
    ) -> Result<(), Error>;
}

/// A compiled mechanism seen as a [`Kernel`]: a reference, zero cost (every method returns a
/// constant of [`Mechanism`] or forwards to its kernel, inlined).
pub struct Compiled<'m, M, const N: usize, const NI: usize, const NO: usize>(pub &'m M);

impl<M, const N: usize, const NI: usize, const NO: usize> Clone for Compiled<'_, M, N, NI, NO> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M, const N: usize, const NI: usize, const NO: usize> Copy for Compiled<'_, M, N, NI, NO> {}

/// The indices of the unknowns that do not follow the others, in order.
pub(crate) struct Judged<const N: usize> {
    index: [usize; N],
    len: usize,
}

impl<const N: usize> Judged<N> {
    pub(crate) const fn of(followers: [bool; N]) -> Self {
        let (mut index, mut len, mut u) = ([0; N], 0, 0);
        while u < N {
            if !followers[u] {
                index[len] = u;
                len += 1;
            }
            u += 1;
        }
        Judged { index, len }
    }

    #[inline(always)]
    pub(crate) fn as_slice(&self) -> &[usize] {
        &self.index[..self.len]
    }
}

impl<M, const N: usize, const NI: usize, const NO: usize> Compiled<'_, M, N, NI, NO>
where
    M: Mechanism<N, NI, NO>,
{
    /// The unknowns a step is judged by, as a constant list the judge's loops unroll over.
    const JUDGED: Judged<N> = Judged::of(M::FOLLOWERS);
}

/// The body of the kernel of a compiled mechanism, borrowed ([`Compiled`]) or owned
/// ([`CompiledSens`]): every method forwards to the mechanism's constants and generated
/// functions (`self.0` is the mechanism or a reference to it).
macro_rules! compiled_kernel_body {
    () => {
        type Dims = Fixed<N, NI, NO>;
        #[inline(always)]
        fn dims(&self) -> Fixed<N, NI, NO> {
            Fixed
        }
        fn name(&self) -> &str {
            M::NAME
        }
        fn input_name(&self, i: usize) -> &str {
            M::INPUTS[i]
        }
        fn unknown_name(&self, u: usize) -> &str {
            M::UNKNOWNS[u]
        }
        fn output_name(&self, o: usize) -> &str {
            M::OUTPUTS[o]
        }
        fn input_kind(&self, i: usize) -> QuantityKind {
            M::INPUT_KINDS[i]
        }
        #[inline(always)]
        fn unknown_kind(&self, u: usize) -> QuantityKind {
            M::UNKNOWN_KINDS[u]
        }
        fn output_kind(&self, o: usize) -> QuantityKind {
            M::OUTPUT_KINDS[o]
        }
        #[inline(always)]
        fn block_count(&self) -> usize {
            M::BLOCKS.len()
        }
        fn block_info(&self, b: usize) -> Option<BlockInfo> {
            M::BLOCKS.get(b).cloned()
        }
        fn block_rows_cols(&self, b: usize) -> Option<(Vec<usize>, Vec<usize>)> {
            let info = M::BLOCKS.get(b)?;
            let rows: Option<Vec<usize>> =
                info.equations.iter().map(|e| M::EQUATIONS.iter().position(|n| n == e)).collect();
            let cols: Option<Vec<usize>> =
                info.unknowns.iter().map(|u| M::UNKNOWNS.iter().position(|n| n == u)).collect();
            Some((rows?, cols?))
        }
        #[inline(always)]
        fn judged(&self) -> &[usize] {
            const { &Self::JUDGED }.as_slice()
        }
        #[inline(always)]
        fn closed_form_angle(&self, u: usize) -> bool {
            M::CLOSED_FORM_ANGLES[u]
        }
        #[inline(always)]
        fn piecewise(&self) -> bool {
            M::PIECEWISE
        }
        fn location(&self, x: &[f64], block: Option<usize>) -> Box<Location> {
            Location::boxed(M::NAME, &M::INPUTS, x, block.and_then(|b| M::BLOCKS.get(b).map(|info| (b, info.clone()))))
        }
        #[inline(always)]
        fn solver_config(&self) -> SweepConfig {
            self.0.solver_config()
        }
        fn check_param_angles(&self, cfg: &NewtonConfig) -> Result<(), Error> {
            self.0.check_param_angles(cfg)
        }
        #[inline(always)]
        fn guess(&self, x: &[f64; NI]) -> [f64; N] {
            self.0.guess_flat(x)
        }
        #[inline(always)]
        fn kinematics(&self, x: &[f64; NI], guess: &[f64; N], cfg: &NewtonConfig) -> Result<Kin<N, NI, NO>, Error> {
            guess_checked::<M, N, NI, NO>(&self.0, x, guess)?;
            self.0.kinematics_flat(x, guess, cfg)
        }
        fn positions(&self, x: &[f64; NI], guess: &[f64; N], cfg: &NewtonConfig) -> Result<[f64; N], Error> {
            guess_checked::<M, N, NI, NO>(&self.0, x, guess)?;
            self.0.position_flat(x, guess, cfg).map(|(q, _)| q)
        }
        #[inline(always)]
        fn kinematics_at(&self, x: &[f64; NI], q: &[f64; N], cfg: &NewtonConfig) -> Result<Kin<N, NI, NO>, Error> {
            self.0.kinematics_at_flat(x, q, cfg).map_err(|e| given_position::<M, N, NI, NO>(x, q, e))
        }
        #[inline(always)]
        fn jacobian(&self, x: &[f64; NI], q: &[f64; N]) -> Jac<N, NI> {
            self.0.jacobian_flat(x, q)
        }
        #[inline(always)]
        fn step_into<T: InputTrig>(
            &self,
            x: &[f64; NI],
            guess: &[f64; N],
            cfg: &NewtonConfig,
            trig: &mut T,
            into: &mut Kin<N, NI, NO>,
        ) -> Result<(), Error> {
            self.0.kinematics_step_sink::<T, _, false>(x, guess, cfg, trig, into)
        }
    };
}

impl<'m, M, const N: usize, const NI: usize, const NO: usize> Kernel for Compiled<'m, M, N, NI, NO>
where
    M: Mechanism<N, NI, NO>,
{
    compiled_kernel_body!();
}

/// A kernel lent: the algorithms that run several sweeps over one mechanism (the reachable
/// range's two, `sweep_at`'s stretches) lend it to each (every method forwards, inlined).
impl<K: Kernel> Kernel for &K {
    type Dims = K::Dims;
    #[inline(always)]
    fn dims(&self) -> K::Dims {
        (**self).dims()
    }
    fn name(&self) -> &str {
        (**self).name()
    }
    fn input_name(&self, i: usize) -> &str {
        (**self).input_name(i)
    }
    fn unknown_name(&self, u: usize) -> &str {
        (**self).unknown_name(u)
    }
    fn output_name(&self, o: usize) -> &str {
        (**self).output_name(o)
    }
    fn input_kind(&self, i: usize) -> QuantityKind {
        (**self).input_kind(i)
    }
    #[inline(always)]
    fn unknown_kind(&self, u: usize) -> QuantityKind {
        (**self).unknown_kind(u)
    }
    fn output_kind(&self, o: usize) -> QuantityKind {
        (**self).output_kind(o)
    }
    #[inline(always)]
    fn block_count(&self) -> usize {
        (**self).block_count()
    }
    fn block_info(&self, b: usize) -> Option<BlockInfo> {
        (**self).block_info(b)
    }
    fn block_rows_cols(&self, b: usize) -> Option<(Vec<usize>, Vec<usize>)> {
        (**self).block_rows_cols(b)
    }
    #[inline(always)]
    fn judged(&self) -> &[usize] {
        (**self).judged()
    }
    #[inline(always)]
    fn closed_form_angle(&self, u: usize) -> bool {
        (**self).closed_form_angle(u)
    }
    #[inline(always)]
    fn piecewise(&self) -> bool {
        (**self).piecewise()
    }
    fn location(&self, x: &[f64], block: Option<usize>) -> Box<Location> {
        (**self).location(x, block)
    }
    #[inline(always)]
    fn solver_config(&self) -> SweepConfig {
        (**self).solver_config()
    }
    fn check_param_angles(&self, cfg: &NewtonConfig) -> Result<(), Error> {
        (**self).check_param_angles(cfg)
    }
    #[inline(always)]
    fn guess(&self, x: &X<K>) -> Q<K> {
        (**self).guess(x)
    }
    #[inline(always)]
    fn kinematics(&self, x: &X<K>, guess: &Q<K>, cfg: &NewtonConfig) -> Result<KinOf<K>, Error> {
        (**self).kinematics(x, guess, cfg)
    }
    fn positions(&self, x: &X<K>, guess: &Q<K>, cfg: &NewtonConfig) -> Result<Q<K>, Error> {
        (**self).positions(x, guess, cfg)
    }
    #[inline(always)]
    fn kinematics_at(&self, x: &X<K>, q: &Q<K>, cfg: &NewtonConfig) -> Result<KinOf<K>, Error> {
        (**self).kinematics_at(x, q, cfg)
    }
    #[inline(always)]
    fn jacobian(&self, x: &X<K>, q: &Q<K>) -> <K::Dims as Dims>::Jac {
        (**self).jacobian(x, q)
    }
    #[inline(always)]
    fn step_into<T: InputTrig>(
        &self,
        x: &X<K>,
        guess: &Q<K>,
        cfg: &NewtonConfig,
        trig: &mut T,
        into: &mut KinOf<K>,
    ) -> Result<(), Error> {
        (**self).step_into(x, guess, cfg, trig, into)
    }
}

/// The room reserved up front for `samples` states or points: at most `1 << 16`, the vector
/// growing past it, so that a huge count (given on a command line, say) fails, if it does, in
/// the work rather than aborting the process on one allocation it cannot make.
pub(crate) fn reserve_for(samples: usize) -> usize {
    samples.min(1 << 16)
}

/// Checks that the inputs `xs` and the unknowns `qs` given to algorithm `what` have kernel
/// `m`'s sizes (always so for a compiled mechanism's arrays: the test folds away): an
/// `Error::InvalidArgument` naming the sizes otherwise.
pub(crate) fn check_sizes<K: Kernel>(m: &K, what: &str, xs: &[&X<K>], qs: &[&Q<K>]) -> Result<(), Error> {
    let d = m.dims();
    let inputs_fit = xs.iter().all(|&x| x.as_ref().len() == d.ni());
    if inputs_fit && qs.iter().all(|&q| q.as_ref().len() == d.n()) {
        return Ok(());
    }
    Err(Error::InvalidArgument(format!(
        "{what} of `{}` needs {} at each input point and {} in a guess",
        m.name(),
        Count(d.ni(), "input"),
        Count(d.n(), "unknown")
    )))
}

/// The first of the inputs `x` given to an algorithm that is not finite, as
/// `Error::NonFinite` of [`Quantity::Input`] naming the input: checked where the algorithm
/// would otherwise meet it under another name (a sweep's range end `to`).
pub(crate) fn check_inputs_finite<K: Kernel>(m: &K, x: &X<K>) -> Result<(), Error> {
    match x.as_ref().iter().enumerate().find(|(_, v)| !v.is_finite()) {
        Some((i, &value)) => Err(Error::NonFinite {
            what: Quantity::Input,
            name: m.input_name(i).to_string().into(),
            value,
            at: m.location(x.as_ref(), None),
        }),
        None => Ok(()),
    }
}

/// The parameter sensitivities of a state as the generic synthesis reads them: [`Sens`] when
/// compiled, a run-time model's flat buffer.
pub trait SensState: Clone + std::fmt::Debug {
    /// `d q_u / d p_k`: the sensitivity of unknown `u` to parameter `k`.
    fn q(&self, u: usize, k: usize) -> f64;
    /// `d out_o / d p_k`: the sensitivity of output column `o` to parameter `k`.
    fn out(&self, o: usize, k: usize) -> f64;
    /// `d (d q_u / d x_i) / d p_k`: the sensitivity of unknown `u`'s first analog by input `i`
    /// to parameter `k`.
    fn dq(&self, u: usize, i: usize, k: usize) -> f64;
    /// `d (d out_o / d x_i) / d p_k`: the sensitivity of output column `o`'s first analog by
    /// input `i` to parameter `k`.
    fn dout(&self, o: usize, i: usize, k: usize) -> f64;
}

impl<const N: usize, const NI: usize, const NO: usize, const NP: usize> SensState for Sens<N, NI, NO, NP> {
    #[inline(always)]
    fn q(&self, u: usize, k: usize) -> f64 {
        self.q[u][k]
    }
    #[inline(always)]
    fn out(&self, o: usize, k: usize) -> f64 {
        self.out[o][k]
    }
    #[inline(always)]
    fn dq(&self, u: usize, i: usize, k: usize) -> f64 {
        self.dq[u][i][k]
    }
    #[inline(always)]
    fn dout(&self, o: usize, i: usize, k: usize) -> f64 {
        self.dout[o][i][k]
    }
}

/// The error of [`SensKernel::with_params`] given `got` values for the `want` parameters of
/// mechanism `name` ([`SensKernel::check_param_count`]).
fn wrong_param_count(got: usize, want: usize, name: &str) -> Error {
    Error::InvalidArgument(format!(
        "{} for the {} of `{name}`",
        Count(got, "parameter value"),
        Count(want, "parameter")
    ))
}

/// A [`Kernel`] whose parameters can be varied, with the parameter sensitivities of its states:
/// what synthesis (`synthesis::ProblemOf`) is written over. A compiled mechanism declared with
/// sensitivities through [`CompiledSens`]; a `kinloop_model::Model` through its kernel.
pub trait SensKernel: Kernel {
    /// The sensitivities of one state.
    type Sens: SensState;
    /// The number of parameters.
    fn param_count(&self) -> usize;
    /// The parameters' names, in declaration order.
    fn param_names(&self) -> Vec<String>;
    /// The value of parameter `k`.
    fn param(&self, k: usize) -> f64;
    /// Every parameter is finite (the mechanism's `check_params`).
    fn check_params(&self) -> Result<(), Error>;
    /// `f` called with this kernel's parameters set to `p` (one value per parameter, in
    /// declaration order): a compiled mechanism gives `f` a copy with those values (so that a
    /// kernel shared between threads is never changed); a kernel over one workspace (a run-time
    /// model) sets them for the call and puts its own back after it (also where `f` fails or
    /// panics). `Error::InvalidArgument` where `p` has another length than
    /// [`SensKernel::param_count`] (and `f` is not called).
    fn with_params<R>(&self, p: &[f64], f: impl FnOnce(&Self) -> R) -> Result<R, Error>;
    /// `p` holds one value per parameter: the length [`SensKernel::with_params`] demands, with
    /// its error.
    fn check_param_count(&self, p: &[f64]) -> Result<(), Error> {
        match p.len() == self.param_count() {
            true => Ok(()),
            false => Err(wrong_param_count(p.len(), self.param_count(), self.name())),
        }
    }
    /// Sensitivities of the right sizes, zero (the buffer [`SensKernel::sensitivities_into`]
    /// writes into).
    fn sens(&self) -> Self::Sens;
    /// The kinematics solved from `guess` ([`Kernel::kinematics`]) into `kin`, and the
    /// sensitivities of its positions and outputs to every parameter into `sens`
    /// ([`Sensitivities::sensitivities_flat`]), on the same factorisations. No allocation.
    fn sensitivities_into(
        &self,
        x: &<Self::Dims as Dims>::X,
        guess: &<Self::Dims as Dims>::Q,
        cfg: &NewtonConfig,
        kin: &mut <Self::Dims as Dims>::Kin,
        sens: &mut Self::Sens,
    ) -> Result<(), Error>;
    /// The same at a position `q` the caller already solved ([`Kernel::kinematics_at`] and
    /// [`Sensitivities::sensitivities_at_flat`]): what an objective over a kept sweep needs at
    /// one of its states. No allocation.
    fn sensitivities_at_into(
        &self,
        x: &<Self::Dims as Dims>::X,
        q: &<Self::Dims as Dims>::Q,
        cfg: &NewtonConfig,
        kin: &mut <Self::Dims as Dims>::Kin,
        sens: &mut Self::Sens,
    ) -> Result<(), Error>;
    /// The position solved from `guess` into `q` and the output columns there into `out`
    /// ([`Mechanism::position_flat`] and [`Mechanism::outputs_flat`]): what an objective
    /// without derivatives needs.
    fn position_into(
        &self,
        x: &<Self::Dims as Dims>::X,
        guess: &<Self::Dims as Dims>::Q,
        cfg: &NewtonConfig,
        q: &mut <Self::Dims as Dims>::Q,
        out: &mut [f64],
    ) -> Result<(), Error>;
}

/// A compiled mechanism declared with sensitivities, owned, as a [`SensKernel`] (its [`Kernel`]
/// methods those of [`Compiled`]): the kernel of the compiled synthesis API
/// (`synthesis::Problem`).
#[derive(Clone, Debug)]
pub struct CompiledSens<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(pub M);

impl<M, const N: usize, const NI: usize, const NO: usize, const NP: usize> CompiledSens<M, N, NI, NO, NP>
where
    M: Mechanism<N, NI, NO>,
{
    /// The unknowns a step is judged by (as [`Compiled`]'s).
    const JUDGED: Judged<N> = Judged::of(M::FOLLOWERS);
}

impl<M, const N: usize, const NI: usize, const NO: usize, const NP: usize> Kernel for CompiledSens<M, N, NI, NO, NP>
where
    M: Mechanism<N, NI, NO>,
{
    compiled_kernel_body!();
}

impl<M, const N: usize, const NI: usize, const NO: usize, const NP: usize> SensKernel for CompiledSens<M, N, NI, NO, NP>
where
    M: Sensitivities<N, NI, NO, NP> + Clone,
{
    type Sens = Sens<N, NI, NO, NP>;
    fn param_count(&self) -> usize {
        NP
    }
    fn param_names(&self) -> Vec<String> {
        M::PARAMS.iter().map(|p| p.to_string()).collect()
    }
    fn param(&self, k: usize) -> f64 {
        self.0.params_flat()[k]
    }
    fn check_params(&self) -> Result<(), Error> {
        self.0.check_params()
    }
    /// `f` called with a copy of the mechanism with the parameters `p`
    /// ([`Sensitivities::with_params_flat`]); `p` must have `NP` values.
    #[inline]
    fn with_params<R>(&self, p: &[f64], f: impl FnOnce(&Self) -> R) -> Result<R, Error> {
        let flat: [f64; NP] = p.try_into().map_err(|_| wrong_param_count(p.len(), NP, self.name()))?;
        Ok(f(&CompiledSens(self.0.with_params_flat(flat))))
    }
    fn sens(&self) -> Sens<N, NI, NO, NP> {
        Sens::ZERO
    }
    #[inline]
    fn sensitivities_into(
        &self,
        x: &[f64; NI],
        guess: &[f64; N],
        cfg: &NewtonConfig,
        kin: &mut Kin<N, NI, NO>,
        sens: &mut Sens<N, NI, NO, NP>,
    ) -> Result<(), Error> {
        (*kin, *sens) = self.0.sensitivities_flat(x, guess, cfg)?;
        Ok(())
    }
    #[inline]
    fn sensitivities_at_into(
        &self,
        x: &[f64; NI],
        q: &[f64; N],
        cfg: &NewtonConfig,
        kin: &mut Kin<N, NI, NO>,
        sens: &mut Sens<N, NI, NO, NP>,
    ) -> Result<(), Error> {
        (*kin, *sens) = self.0.sensitivities_at_flat(x, q, cfg).map_err(|e| given_position::<M, N, NI, NO>(x, q, e))?;
        Ok(())
    }
    #[inline]
    fn position_into(
        &self,
        x: &[f64; NI],
        guess: &[f64; N],
        cfg: &NewtonConfig,
        q: &mut [f64; N],
        out: &mut [f64],
    ) -> Result<(), Error> {
        (*q, _) = self.0.position_flat(x, guess, cfg)?;
        out.copy_from_slice(&self.0.outputs_flat(x, q));
        Ok(())
    }
}

/// Whether unknown `u` of `m` is an angle, measured in radians by a sweep's tests and the
/// location of its events: a closed form's angle, or an unknown of the kind.
#[inline(always)]
pub(crate) fn is_angle<K: Kernel>(m: &K, u: usize) -> bool {
    m.closed_form_angle(u) || m.unknown_kind(u) == QuantityKind::Angle
}
