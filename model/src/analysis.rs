//! The runtime's analyses of sampled sweeps and its limit report on a run-time model: the one
//! implementation ([`SampledOf`], `limits_of`), over the model's [`Kernel`](kinloop_runtime::Kernel).
//!
//! A model declared with `#[kinloop(sensitivities)]` gets the objectives with parameter
//! gradients on its [`ModelSampled`] as well (`extremum_with_gradient`,
//! `integral_with_gradient`: the runtime's one implementation, over `SensKernel`), each
//! gradient a vector with one value per parameter in declaration order.
//!
//! ```
//! use kinloop_model::Model;
//! use kinloop_runtime::Extreme;
//! let text = "#[kinloop(sensitivities)]
//! pub struct SliderCrank {
//!     params r = 1, l = 3;
//!     input phi;
//!     unknowns beta = 0, s = 4;
//!     loop rod: r @ phi + l @ beta == (s, 0);
//! }";
//! let mut m = Model::read("slider_crank.kl", text).unwrap();
//! // From -1 rad, so that both dead centres (0 and pi) are interior.
//! let turn = m.sampled(&[-1.0], &[std::f64::consts::TAU - 1.0], 73, &[0.0, 4.0]).unwrap();
//! let (top, bottom) = (turn.extremum_with_gradient("s", Extreme::Max).unwrap(),
//!                      turn.extremum_with_gradient("s", Extreme::Min).unwrap());
//! // The stroke of a centred slider-crank is 2 r: its gradient by r is 2, by l zero.
//! let stroke_grad = [top.grad[0] - bottom.grad[0], top.grad[1] - bottom.grad[1]];
//! assert!((top.value - bottom.value - 2.0).abs() < 1e-12);
//! assert!((stroke_grad[0] - 2.0).abs() < 1e-12 && stroke_grad[1].abs() < 1e-12);
//! ```
//!
//! A [`SampledOf`] keeps its kernel and lends it by reference to the sweeps it solves with
//! (the samples and every refinement between them): `&ModelKernel` is a kernel too.

use crate::mechanism::ModelKernel;
use crate::model::Model;
use kinloop_runtime::analysis::{SampledOf, samples_to_search};
use kinloop_runtime::dims::Heap;
use kinloop_runtime::metrics::{LimitReport, limits_of};
use kinloop_runtime::{Error, SweepConfig};

/// A sweep of a run-time model kept in memory and analysed column by column (the runtime's
/// [`SampledOf`]: extremes, ranges, dwells, harmonics, unbalance, time ratio, transmission
/// angle), its columns named as the model names them (`"psi"`, `"pc.x"`). Made by
/// [`Model::sampled`].
pub type ModelSampled<'a> = SampledOf<ModelKernel<'a>>;

impl Model {
    /// Sweeps `samples` equally spaced points of the straight path from inputs `from` to `to`
    /// (both included) from `guess` at `from`, with the model's solver configuration ([`Model::sweep_config`]), and keeps
    /// them for analysis by column: the runtime's [`SampledOf`] over this model, the same
    /// implementation a compiled mechanism's `m.sampled(..)` runs. The path parameter is the
    /// input when there is one (it must then increase), the fraction of the path otherwise.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// let text = "pub struct SliderCrank {
    ///     params r = 1, l = 3;
    ///     input phi;
    ///     unknowns psi = 0, x = 4;
    ///     loop oabo: r @ phi == (x, 0) + l @ psi;
    /// }";
    /// let mut m = Model::read("slider_crank.kl", text).unwrap();
    /// let turn = m.sampled(&[0.0], &[std::f64::consts::TAU], 37, &[0.0, 4.0]).unwrap();
    /// let x = turn.range("x").unwrap();
    /// // The stroke of a centred slider-crank: twice the crank.
    /// assert!((x.span() - 2.0).abs() < 1e-12);
    /// ```
    pub fn sampled(
        &mut self,
        from: &[f64],
        to: &[f64],
        samples: usize,
        guess: &[f64],
    ) -> Result<ModelSampled<'_>, Error> {
        self.sampled_with(from, to, samples, guess, self.sweep_config)
    }

    /// [`Model::sampled`] with the sweep configuration `config` (also used for every
    /// refinement).
    pub fn sampled_with(
        &mut self,
        from: &[f64],
        to: &[f64],
        samples: usize,
        guess: &[f64],
        config: SweepConfig,
    ) -> Result<ModelSampled<'_>, Error> {
        self.sampled_reporting(from, to, samples, guess, config, |_| ())
    }

    /// [`Model::sampled_with`], telling `progress` how many samples are taken after each (for
    /// a progress bar on long sweeps).
    pub fn sampled_reporting(
        &mut self,
        from: &[f64],
        to: &[f64],
        samples: usize,
        guess: &[f64],
        config: SweepConfig,
        progress: impl FnMut(usize),
    ) -> Result<ModelSampled<'_>, Error> {
        let k = self.kernel(config)?;
        let v = |s: &[f64]| Heap(s.into());
        SampledOf::over_reporting(k, v(from), v(to), samples, v(guess), config, progress)
    }

    /// The fewest samples with which a search for extremes over the path from `from` to `to`
    /// (its length measured at `guess`) fits between them: the runtime's
    /// [`samples_to_search`](kinloop_runtime::analysis::samples_to_search), known before any
    /// step, so that a range too long for the samples asked for is refused before the sweep.
    pub fn samples_to_search(&mut self, from: &[f64], to: &[f64], guess: &[f64]) -> Result<usize, Error> {
        let k = self.kernel(self.sweep_config)?;
        let v = |s: &[f64]| Heap(s.into());
        samples_to_search(&k, &v(from), &v(to), &v(guess))
    }

    /// Dead centres and limit positions of a single-input model over its input from `from` to
    /// `to` (either direction), `samples` equally spaced inputs from `guess` at `from`: the
    /// input's limit positions and singular crossings (the sweep's events; a limit position
    /// ends the range) and the located extremes of the columns named `columns` over the range
    /// reached. The runtime's `limits_of`, as a compiled mechanism's `Limits::run`.
    pub fn limits(
        &mut self,
        from: f64,
        to: f64,
        samples: usize,
        guess: &[f64],
        columns: &[&str],
    ) -> Result<LimitReport, Error> {
        let k = self.kernel(self.sweep_config)?;
        limits_of(k, from, to, samples, Heap(guess.into()), columns)
    }
}
