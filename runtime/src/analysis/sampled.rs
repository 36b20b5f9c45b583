//! [`Sampled`]: a branch-safe sweep kept in memory and analysed column by column, written once
//! over any [`Kernel`] ([`SampledOf`]): a compiled mechanism's, through [`Compiled`], or a
//! mechanism's read at run time.

use super::column::{ColumnOf, column_kind, column_name, jet_along};
use super::extremes::{self, GlobalRange, LocalExtreme, maximize};
use super::{ColumnIndex, Dwell, Fourier, Jet, Rest, Unbalance, dwell, fourier, rest, unbalance};
use crate::Kernel;
use crate::dims::{Dims, KinState, Store};
use crate::error::Error;
use crate::events::EventKind;
use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, KinOf, Q, X, check_sizes};
use crate::number::{Count, pow2_at_most};
use crate::paths::collected::check_collected;
use crate::paths::config::SweepConfig;
use crate::paths::curve::{Metric, Path};
use crate::paths::sweep::{MAX_INPUT_STEP, SweepOf, check_finite};
use std::borrow::Cow;

/// The straight path of a [`SampledOf`] in input space and its parameter `s`.
#[derive(Clone, Debug)]
struct Line<V> {
    from: V,
    to: V,
    /// How far the inputs move per unit of `s`.
    dir: V,
    /// `s` is input `k` itself (`Some(k)`) or the fraction of the path (`None`).
    along: Option<usize>,
}

impl<V: Store> Line<V> {
    fn fraction(from: V, to: V) -> Self {
        let mut dir = from.clone();
        for (i, d) in dir.as_mut().iter_mut().enumerate() {
            *d = to[i] - from[i];
        }
        Line { from, to, dir, along: None }
    }

    fn ni(&self) -> usize {
        self.from.as_ref().len()
    }

    /// The same path with input `k` as its parameter (it must increase along the path).
    fn along(self, k: usize, name: &str) -> Result<Self, Error> {
        let run = self.to[k] - self.from[k];
        if run.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(Error::InvalidArgument(format!(
                "input `{name}` must increase along the path to be its parameter (it goes from {} to {})",
                self.from[k], self.to[k]
            )));
        }
        let mut dir = self.dir.clone();
        for (i, d) in dir.as_mut().iter_mut().enumerate() {
            *d = if i == k { 1.0 } else { (self.to[i] - self.from[i]) / run };
        }
        Ok(Line { dir, along: Some(k), ..self })
    }

    /// The parameter of the point `x` of the path.
    fn param(&self, x: &[f64]) -> f64 {
        match self.along {
            Some(k) => x[k],
            None => {
                // The run and the offset in units of the power of two at most the run's largest
                // component (exact): their products, squares of lengths, underflowed for inputs
                // below about 1e-154 of their unit (a path through two sliders of a tiny
                // mechanism), and the fractions came out subnormal-rounded, then NaN.
                let ni = self.ni();
                let largest = (0..ni).map(|i| (self.to[i] - self.from[i]).abs()).fold(0.0, f64::max);
                let unit = if largest > 0.0 && largest.is_finite() { pow2_at_most(largest) } else { 1.0 };
                let delta = |i: usize| (self.to[i] - self.from[i]) / unit;
                let off = |i: usize| (x[i] - self.from[i]) / unit;
                (0..ni).map(|i| off(i) * delta(i)).sum::<f64>() / (0..ni).map(|i| delta(i) * delta(i)).sum::<f64>()
            }
        }
    }

    /// The inputs at parameter `s`.
    fn point(&self, s: f64) -> V {
        let s0 = self.along.map_or(0.0, |k| self.from[k]);
        let mut x = self.from.clone();
        for (i, v) in x.as_mut().iter_mut().enumerate() {
            *v = self.from[i] + (s - s0) * self.dir[i];
        }
        match self.along {
            Some(k) => x[k] = s,
            None if s == 1.0 => x = self.to.clone(),
            None => {}
        }
        x
    }
}

/// The most points a search for extremes solves between samples farther apart than a sweep's
/// natural step ([`SampledOf::extremes`], `range`, `dwells`, `peak`): the natural steps over
/// about 10,000 turns of an angle input. Each is a state kept while the search runs; farther
/// apart, the samples are refused with the count that would do.
pub const MAX_SEARCH_POINTS: usize = 1 << 18;

/// The fewest samples (at least 3), both ends included, with which a search for extremes
/// ([`SampledOf::range`], `extremes`, `dwells`, `peak`) over the straight path from `from` to `to`
/// solves at most [`MAX_SEARCH_POINTS`] points between them: the path's length measured as the
/// sweep measures it (in its inputs' units at `guess`), cut into equal gaps. Known before any
/// step, so that a caller can refuse a range too long for its samples before sweeping it (the
/// search refuses it too, after the sweep). Beyond [`MAX_SAMPLES`](super::MAX_SAMPLES) where no
/// count a sampled sweep takes will do, `usize::MAX` where the count is not finite (ends so far
/// apart that the path's length overflows). Ends that are not finite are [`Error::NonFinite`],
/// as a sweep refuses them. A length input whose unit depends on the position may need a few
/// more, measured at the solved start.
///
/// Up to [`MAX_SEARCH_POINTS`] natural steps (about 10,000 turns of an angle input) any count
/// will do; from twice that on, one sample per natural step, a quarter radian of an angle input.
pub fn samples_to_search<K: Kernel>(k: &K, from: &X<K>, to: &X<K>, guess: &Q<K>) -> Result<usize, Error> {
    check_sizes(k, "a search's samples", &[from, to], &[guess])?;
    check_finite("from", from.as_ref(), k)?;
    check_finite("to", to.as_ref(), k)?;
    let path = Path::new(from.clone(), to.clone());
    let natural = Metric::at(k, &path, from, guess).input_len / MAX_INPUT_STEP;
    Ok(least_search_samples(natural))
}

/// The fewest samples (at least 3) whose equal gaps over a path of `natural` natural steps need
/// at most [`MAX_SEARCH_POINTS`] points between them: `g` gaps need `g (ceil(natural / g) - 1)`
/// (each gap cut into `ceil(natural / g)` parts), the fewest for the most parts `c` a gap may
/// be cut into, `g = ceil(natural / c)`. Measured a millionth longer: a gap of exactly `c`
/// natural steps whose samples round apart a hair farther is cut into `c + 1`.
fn least_search_samples(natural: f64) -> usize {
    let l = natural * (1.0 + 1e-6);
    let max = MAX_SEARCH_POINTS as f64;
    if !l.is_finite() || l >= 1e18 {
        return usize::MAX;
    }
    if l <= max {
        return 3;
    }
    // Past `l / (l - max)` parts, `g (c - 1) >= l - l / c` exceeds `max`; down to one part (no
    // point between), which always fits. At most `max` iterations, off any step's path.
    let mut c = (l / (l - max)).floor();
    while c > 1.0 {
        let g = (l / c).ceil();
        if g * (c - 1.0) <= max {
            return (g as usize + 1).max(3);
        }
        c -= 1.0;
    }
    (l.ceil() as usize + 1).max(3)
}

/// The value of column `c` in the state `st`.
fn column_value<S: KinState>(c: ColumnIndex, st: &S) -> f64 {
    match c {
        ColumnIndex::Input(i) => st.x()[i],
        ColumnIndex::Unknown(u) => st.q()[u],
        ColumnIndex::Output(o) => st.out()[o],
    }
}

/// About the bytes a [`SampledOf`] over `k` keeps per sample, and that its analyses hold per
/// sample beside it while they search: the state (its own size and what it holds on the heap)
/// and its path parameter, then a search's grid entry (a state's size, borrowed or not) and
/// parameter, and a column's jet. What [`check_sampled_memory`] budgets.
pub(crate) fn sampled_bytes_each<K: Kernel>(k: &K) -> usize {
    fn grid_entry<'a, T: Clone + 'a>() -> usize {
        size_of::<Cow<'a, T>>()
    }
    let state = size_of::<KinOf<K>>() + k.dims().kin().heap_bytes();
    state + size_of::<f64>() + grid_entry::<KinOf<K>>() + size_of::<f64>() + size_of::<Jet>()
}

/// `Err(Error::InvalidArgument)` when a [`SampledOf`] of `samples` samples over `k` would keep
/// more than [`MAX_COLLECTED_BYTES`](crate::paths::collected::MAX_COLLECTED_BYTES) (with what its
/// analyses hold beside it, [`sampled_bytes_each`]), before any step: its states are kept until
/// it is dropped, and a failed allocation aborts the process. `what` is what the caller called,
/// in words (the sampled sweep, or an analysis that keeps one: "the limit search").
pub(crate) fn check_sampled_memory<K: Kernel>(k: &K, samples: usize, what: &str) -> Result<(), Error> {
    let instead = "take fewer samples (the analyses solve the points between samples farther apart than a sweep's \
                   natural step themselves: `analysis::samples_to_search` gives the fewest that search a range), or \
                   iterate a `Sweep` and keep only what you need";
    check_collected(what, "states", samples, sampled_bytes_each(k), instead)
}

/// The points where a search for extremes looks ([`SampledOf::search`]): the samples,
/// borrowed, and the points solved between those farther apart than a sweep's natural step.
struct Search<'a, K: Kernel> {
    /// Path parameters, increasing.
    s: Vec<f64>,
    states: Vec<Cow<'a, KinOf<K>>>,
    /// The singular crossings between points of the grid, in increasing path parameter.
    gaps: Vec<Gap<K>>,
}

/// A singular crossing (change point) the samples' sweep passed, between the grid points `at`
/// and `at + 1` of a [`Search`]: the points nearest the crossing either side that a sweep still
/// reaches on its branch (about its pivot band, [`SweepConfig::singular_pivot`], away), between
/// which nothing is solved. No step lands closer: the residual tolerance no longer pins the
/// branch there, and a column's analogs are not defined at the crossing itself.
struct Gap<K: Kernel> {
    at: usize,
    /// The crossing's path parameter.
    s: f64,
    /// The state at the crossing (its positions located by the sweep, its analogs not to be
    /// trusted), where the outputs can be evaluated there.
    state: Option<KinOf<K>>,
}

/// A singular crossing the sweep of a [`SampledOf`] passed: its inputs and positions.
#[derive(Clone, Debug)]
struct Crossing<K: Kernel> {
    x: X<K>,
    q: Q<K>,
}

/// A compiled mechanism's [`SampledOf`]: the number of inputs `NI` comes last and defaults to
/// one, so that `Sampled<'_, M, N, NO>` is the single-input type (`N` unknowns, `NO` output
/// columns, as in `Mechanism<N, NI, NO>`).
pub type Sampled<'m, M, const N: usize, const NO: usize, const NI: usize = 1> = SampledOf<Compiled<'m, M, N, NI, NO>>;

/// A branch-safe sweep along a straight path in input space, kept in memory and analysed
/// column by column: extremes located as roots of the velocity analog, dwells, Fourier
/// coefficients, residual unbalance. Between samples the mechanism is solved again (warm-started
/// from the nearest sample and stepped there by a two-sample [`Sweep`](crate::Sweep), so the refinement never
/// leaves the sweep's branch).
///
/// Written once over any [`Kernel`] (lent by reference to the sweeps it solves with): [`Sampled`] is a compiled
/// mechanism's, `kinloop_model::Model::sampled` a run-time model's.
///
/// Columns are the generated typed handles `Name::COL.field` (see [`Column`](super::Column)), or for any
/// kernel names known at run time (`"beta"`) or [`ColumnIndex`]es ([`ColumnOf`]); every
/// quantity is a function of the **path parameter** `s`:
///
/// * one input ([`Sampled::sweep`]): `s` is the input itself, the jets' derivatives are the
///   velocity and acceleration analogs;
/// * several inputs ([`Sampled::path`]): the inputs move on the straight line from `from` to
///   `to`, `s` is the fraction of the path (0 at `from`, 1 at `to`), or one chosen input after
///   [`SampledOf::along`]; the derivatives along the path are the analog tensors contracted with
///   the path's direction `d` (`dq/ds = dq[u][i] d_i`, `d2q/ds2 = d2q[u][i][j] d_i d_j`).
///
/// Every state is kept, and the analyses hold about as much again while they search: samples
/// whose states would exceed [`MAX_COLLECTED_BYTES`](crate::paths::collected::MAX_COLLECTED_BYTES)
/// (1 GiB) are refused before any step, with the numbers (at a few hundred bytes a state, a few
/// million samples; the analyses solve the points between samples farther apart than a sweep's
/// natural step themselves, so that fewer samples lose no extreme).
///
/// For [`SampledOf::fourier`] and [`SampledOf::unbalance`] the range must be one period of the
/// quantity (e.g. one crank turn, `samples - 1` equal intervals, the last sample repeating the
/// first).
///
/// ```ignore
/// use kinloop_runtime::analysis::{Extreme, Sampled};
/// use std::f64::consts::TAU;
/// let m = SliderCrank { r: 1.0, l: 3.0, e: 0.0 };            // a centred slider-crank
/// let turn = Sampled::sweep(&m, 0.0, TAU, 37, [4.0])?;
/// // Dead centres at 0 and 180 degrees (the first at the start of the range is not interior).
/// let e = turn.extremes(SliderCrank::COL.x)?;
/// assert_eq!(e.len(), 1);
/// assert_eq!(e[0].kind, Extreme::Min);
/// assert!((e[0].x() - TAU / 2.0).abs() < 1e-10 && (e[0].value() - 2.0).abs() < 1e-12);
/// // The largest acceleration analog |x''| = r + r^2/l at the outer dead centre.
/// let (at, peak) = turn.peak_of(SliderCrank::COL.x, |j| j.d2.abs())?;
/// assert!((peak - (1.0 + 1.0 / 3.0)).abs() < 1e-12 && at.cos() > 1.0 - 1e-12);
/// // After the first harmonic, what remains is mostly the second, about r^2 / (4 l) cos 2 phi.
/// let r = turn.unbalance(SliderCrank::COL.x, 1)?;
/// assert!((r.max_abs - 1.0 / 12.0).abs() < 5e-3);
/// // Any state of the range, on the sweep's branch.
/// assert!((turn.at(1.0)?.q[0] - (1f64.cos() + (9.0 - 1f64.sin().powi(2)).sqrt())).abs() < 1e-12);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub struct SampledOf<K: Kernel> {
    k: K,
    states: Vec<KinOf<K>>,
    /// The path parameter of each state.
    s: Vec<f64>,
    line: Line<X<K>>,
    cfg: SweepConfig,
    /// The singular crossings the sweep passed (with [`AtSingular::Continue`](crate::AtSingular::Continue)), in order.
    crossings: Vec<Crossing<K>>,
}

/// The mechanism, the range, the number of states and of crossings, and the configuration (not
/// the states themselves, which the accessors give).
impl<K: Kernel> std::fmt::Debug for SampledOf<K> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SampledOf")
            .field("mechanism", &self.k.name())
            .field("from", &self.line.from.as_ref())
            .field("to", &self.line.to.as_ref())
            .field("states", &self.states.len())
            .field("crossings", &self.crossings.len())
            .field("cfg", &self.cfg)
            .finish_non_exhaustive()
    }
}

impl<'m, M, const N: usize, const NO: usize> Sampled<'m, M, N, NO, 1>
where
    M: Mechanism<N, 1, NO>,
{
    /// Sweeps `samples` equally spaced inputs from `from` to `to > from` (both included) from
    /// `guess` at `from` (which picks the assembly mode). The path parameter is the input.
    /// At least 3 and at most [`MAX_SAMPLES`](super::MAX_SAMPLES) samples (every state is
    /// kept): others are an [`Error::InvalidArgument`], as a count whose states no memory holds;
    /// so, before any step, are samples whose states (with what the analyses hold beside them)
    /// would exceed [`MAX_COLLECTED_BYTES`](crate::paths::collected::MAX_COLLECTED_BYTES).
    ///
    /// The mechanism's solver configuration ([`Mechanism::solver_config`]: the defaults, or the
    /// one a [`Configured`](crate::Configured) mechanism carries) sweeps and refines.
    ///
    /// A declared mechanism's `m.sampled(from, to, samples, &m.guess(from))` is this call with
    /// the named unknowns; this form serves code generic over [`Mechanism`] and hand-written
    /// implementations, as [`Sweep::new`](crate::Sweep::new) does beside `m.sweep`.
    pub fn sweep(m: &'m M, from: f64, to: f64, samples: usize, guess: impl Into<[f64; N]>) -> Result<Self, Error> {
        Self::sweep_with(m, from, to, samples, guess, m.solver_config())
    }

    /// [`Sampled::sweep`] with a sweep configuration (also used for every refinement).
    pub fn sweep_with(
        m: &'m M,
        from: f64,
        to: f64,
        samples: usize,
        guess: impl Into<[f64; N]>,
        cfg: SweepConfig,
    ) -> Result<Self, Error> {
        m.check_param_angles(&cfg.newton)?;
        SampledOf::input_with(Compiled(m), [from], [to], samples, guess.into(), cfg)
    }
}

impl<'m, M, const N: usize, const NO: usize, const NI: usize> Sampled<'m, M, N, NO, NI>
where
    M: Mechanism<N, NI, NO>,
{
    /// Sweeps `samples` equally spaced points of the straight path from inputs `from` to `to`
    /// (both included; arrays or the generated `NameInputs`) from `guess` at `from`. The path
    /// parameter is the fraction of the path, `0 ..= 1`; see [`SampledOf::along`] to use an input.
    ///
    /// ```ignore
    /// // A five-bar driven by both cranks at once, th2 turning half as fast as th1.
    /// let run = Sampled::path(&m, [0.0, 1.0], [PI, 1.0 + PI / 2.0], 91, guess)?.along(FiveBar::COL.th1)?;
    /// let reach = run.range(FiveBar::COL.p.x)?;   // extremes of d(p.x)/d(th1) along the path
    /// ```
    pub fn path(
        m: &'m M,
        from: impl Into<[f64; NI]>,
        to: impl Into<[f64; NI]>,
        samples: usize,
        guess: impl Into<[f64; N]>,
    ) -> Result<Self, Error> {
        Self::path_with(m, from, to, samples, guess, m.solver_config())
    }

    /// [`Sampled::path`] with a sweep configuration (also used for every refinement).
    pub fn path_with(
        m: &'m M,
        from: impl Into<[f64; NI]>,
        to: impl Into<[f64; NI]>,
        samples: usize,
        guess: impl Into<[f64; N]>,
        cfg: SweepConfig,
    ) -> Result<Self, Error> {
        m.check_param_angles(&cfg.newton)?;
        SampledOf::path_over(Compiled(m), from.into(), to.into(), samples, guess.into(), cfg, &mut |_| ())
    }

    /// [`Sampled::path`] with the input as the parameter when there is one input (as
    /// [`Sampled::sweep`]).
    pub(crate) fn natural(
        m: &'m M,
        from: [f64; NI],
        to: [f64; NI],
        samples: usize,
        guess: [f64; N],
    ) -> Result<Self, Error> {
        m.check_param_angles(&m.solver_config().newton)?;
        SampledOf::over(Compiled(m), from, to, samples, guess, m.solver_config())
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &'m M {
        self.k.0
    }
}

impl<K: Kernel> SampledOf<K> {
    /// Sweeps `samples` equally spaced points of the straight path from inputs `from` to `to`
    /// (both included, of the kernel's sizes) from `guess` at `from`, with the sweep
    /// configuration `cfg` (also used for every refinement): the path parameter is the input
    /// when there is one (which must then increase), the fraction of the path otherwise (see
    /// [`SampledOf::along`]). The errors of [`Sampled::sweep`] (the samples' memory among
    /// them).
    pub fn over(k: K, from: X<K>, to: X<K>, samples: usize, guess: Q<K>, cfg: SweepConfig) -> Result<Self, Error> {
        Self::over_reporting(k, from, to, samples, guess, cfg, |_| ())
    }

    /// [`SampledOf::over`], telling `progress` how many samples are taken after each (for a
    /// progress bar on long work).
    pub fn over_reporting(
        k: K,
        from: X<K>,
        to: X<K>,
        samples: usize,
        guess: Q<K>,
        cfg: SweepConfig,
        mut progress: impl FnMut(usize),
    ) -> Result<Self, Error> {
        if k.dims().ni() == 1 {
            Self::input_reporting(k, from, to, samples, guess, cfg, &mut progress)
        } else {
            Self::path_over(k, from, to, samples, guess, cfg, &mut progress)
        }
    }

    /// One input from `from` to `to`, the path parameter the input ([`Sampled::sweep_with`]).
    pub(crate) fn input_with(
        k: K,
        from: X<K>,
        to: X<K>,
        samples: usize,
        guess: Q<K>,
        cfg: SweepConfig,
    ) -> Result<Self, Error> {
        Self::input_reporting(k, from, to, samples, guess, cfg, &mut |_| ())
    }

    /// [`SampledOf::input_with`], telling `progress` the samples taken.
    fn input_reporting(
        k: K,
        from: X<K>,
        to: X<K>,
        samples: usize,
        guess: Q<K>,
        cfg: SweepConfig,
        progress: &mut impl FnMut(usize),
    ) -> Result<Self, Error> {
        check_sizes(&k, "a sampled sweep", &[&from, &to], &[&guess])?;
        if k.dims().ni() != 1 {
            return Err(Error::InvalidArgument(format!(
                "a sampled sweep of one input: `{}` has {}",
                k.name(),
                k.dims().ni()
            )));
        }
        if from[0].partial_cmp(&to[0]) != Some(std::cmp::Ordering::Less) {
            return Err(Error::InvalidArgument(format!(
                "a sampled sweep of `{}` over its input `{}` needs from < to (got {} .. {})",
                k.name(),
                k.input_name(0),
                from[0],
                to[0]
            )));
        }
        Self::path_over(k, from, to, samples, guess, cfg, progress)?.reparametrised(|l, k| l.along(0, k.input_name(0)))
    }

    /// The samples of the path, its parameter the fraction of the path.
    fn path_over(
        k: K,
        from: X<K>,
        to: X<K>,
        samples: usize,
        guess: Q<K>,
        cfg: SweepConfig,
        progress: &mut impl FnMut(usize),
    ) -> Result<Self, Error> {
        if samples < 3 || from.as_ref() == to.as_ref() {
            return Err(Error::InvalidArgument(format!(
                "Sampled needs from != to and at least 3 samples (got {:?} .. {:?}, {})",
                from.as_ref(),
                to.as_ref(),
                Count(samples, "sample")
            )));
        }
        super::check_sample_count("samples", samples).map_err(Error::InvalidArgument)?;
        check_sampled_memory(&k, samples, "the sampled sweep")?;
        let mut states = Vec::new();
        states
            .try_reserve_exact(samples)
            .map_err(|e| Error::InvalidArgument(format!("{samples} samples: no room for their states ({e})")))?;
        let crossings = {
            let mut sweep =
                SweepOf::<&K, KinOf<K>>::over(&k, from.clone(), to.clone(), samples, guess)?.with_config(cfg);
            while let Some(state) = sweep.next_kin() {
                states.push(state?);
                progress(states.len());
            }
            let d = k.dims();
            sweep
                .events()
                .iter()
                .filter(|e| e.kind == EventKind::SingularCrossing)
                .map(|e| {
                    let (mut x, mut q) = (d.x(), d.q());
                    x.as_mut().copy_from_slice(&e.x);
                    q.as_mut().copy_from_slice(&e.q);
                    Crossing { x, q }
                })
                .collect()
        };
        let line = Line::fraction(from, to);
        let s = states.iter().map(|st| line.param(st.x())).collect();
        Ok(SampledOf { k, states, s, line, cfg, crossings })
    }

    /// The same samples with input `input` (`Name::COL.th1`, or its name) as the path
    /// parameter: jets are then derivatives with respect to that input along the path (the
    /// other inputs following it). The input must increase from `from` to `to`.
    pub fn along(self, input: impl ColumnOf<K>) -> Result<Self, Error> {
        match input.resolve(&self.k)? {
            ColumnIndex::Input(i) => self.reparametrised(|l, k| l.along(i, k.input_name(i))),
            c => Err(Error::InvalidArgument(format!(
                "`{}` is not an input of `{}`",
                column_name(&self.k, c),
                self.k.name()
            ))),
        }
    }

    fn reparametrised(mut self, f: impl FnOnce(Line<X<K>>, &K) -> Result<Line<X<K>>, Error>) -> Result<Self, Error> {
        self.line = f(self.line, &self.k)?;
        self.s = self.states.iter().map(|st| self.line.param(st.x())).collect();
        Ok(self)
    }

    /// The sampled states, in increasing path parameter.
    pub fn states(&self) -> &[KinOf<K>] {
        &self.states
    }

    /// The path parameter of each sampled state (the input values for a single-input sweep).
    pub fn path_values(&self) -> &[f64] {
        &self.s
    }

    /// How far the inputs move per unit of the path parameter.
    pub fn direction(&self) -> X<K> {
        self.line.dir.clone()
    }

    /// The inputs at path parameter `s`.
    pub fn inputs_at(&self, s: f64) -> X<K> {
        self.line.point(s)
    }

    /// The kernel the samples were taken of.
    pub fn kernel(&self) -> &K {
        &self.k
    }

    /// The sweep configuration the samples were taken with (also used for every refinement).
    pub fn config(&self) -> &SweepConfig {
        &self.cfg
    }

    /// The name of a column (as the kernel names it).
    pub fn column_name(&self, c: impl ColumnOf<K>) -> Result<&str, Error> {
        c.resolve(&self.k).map(|c| column_name(&self.k, c))
    }

    /// The samples of a column as jets in the path parameter.
    pub fn jets(&self, c: impl ColumnOf<K>) -> Result<Vec<Jet>, Error> {
        let c = c.resolve(&self.k)?;
        Ok(self.jets_of(c))
    }

    fn jets_of(&self, c: ColumnIndex) -> Vec<Jet> {
        self.states.iter().zip(&self.s).map(|(st, &s)| jet_along(c, st, s, self.line.dir.as_ref())).collect()
    }

    /// A column's jet at any path parameter `s` of the range, on the sweep's branch.
    pub fn jet_at(&self, c: impl ColumnOf<K>, s: f64) -> Result<Jet, Error> {
        let c = c.resolve(&self.k)?;
        self.jet_of(c, s)
    }

    fn jet_of(&self, c: ColumnIndex, s: f64) -> Result<Jet, Error> {
        self.at(s).map(|st| jet_along(c, &st, s, self.line.dir.as_ref()))
    }

    /// Whether the path parameter `s` is that of a singular crossing the sweep passed (where
    /// [`SampledOf::range`] puts an extreme reached at the crossing itself).
    pub(crate) fn is_crossing(&self, s: f64) -> bool {
        self.crossings.iter().any(|c| self.line.param(c.x.as_ref()) == s)
    }

    /// The state at any path parameter `s` of the range (the input for one input), on the
    /// sweep's branch.
    pub fn at(&self, s: f64) -> Result<KinOf<K>, Error> {
        self.at_near(s, &self.s, |j| &self.states[j])
    }

    /// The state at `s`, stepped there from the nearest of the states `state(j)` at the path
    /// parameters `at` (increasing; the samples, or a search grid's points).
    fn at_near<'a>(&self, s: f64, at: &[f64], state: impl Fn(usize) -> &'a KinOf<K>) -> Result<KinOf<K>, Error>
    where
        KinOf<K>: 'a,
    {
        let (first, last) = (self.s[0], self.s[self.s.len() - 1]);
        let slack = 1e-9 * (last - first);
        if !(s >= first - slack && s <= last + slack) {
            return Err(Error::InvalidArgument(format!("{s} lies outside the sampled range [{first}, {last}]")));
        }
        // The nearest state.
        let i = at.partition_point(|&v| v < s);
        let j = match (i.checked_sub(1), at.get(i)) {
            (Some(j), Some(&v)) if (s - at[j]).abs() <= (v - s).abs() => j,
            (_, Some(_)) => i,
            (Some(j), None) => j,
            (None, None) => unreachable!("a Sampled holds at least three states"),
        };
        let near = state(j);
        let x = self.line.point(s);
        // The state itself (its parameter may differ from `s` in the last bit).
        if at[j] == s || near.x() == x.as_ref() {
            return Ok(near.clone());
        }
        let (mut from, mut guess) = (self.k.dims().x(), self.k.dims().q());
        from.as_mut().copy_from_slice(near.x());
        guess.as_mut().copy_from_slice(near.q());
        let mut step = SweepOf::<&K, KinOf<K>>::over(&self.k, from, x, 2, guess)?.with_config(self.cfg);
        // The start (the state itself), looked at in place: a refinement allocates nothing more.
        step.next_ref().transpose()?;
        step.next_kin().unwrap_or_else(|| Err(Error::InvalidArgument("empty refinement sweep".into())))
    }

    /// Where a search for extremes looks at a column: the samples and, between two samples
    /// farther apart than a sweep's natural step ([`MAX_INPUT_STEP`] in the inputs' units, as
    /// the sweep's own metric measures it), equally spaced points at most that far apart,
    /// solved by one sweep through each such gap. Samples a turn apart have the same state at
    /// each and no sign change of an analog between them however the quantity moves in
    /// between: only points the sweep itself would step to bracket its extremes. Sampled at
    /// least that densely (the usual case), the samples alone, borrowed.
    fn search(&self) -> Result<Search<'_, K>, Error> {
        let (first, last) = (self.s[0], self.s[self.s.len() - 1]);
        // The path's length in the inputs' units, as the sweep measured it from its start.
        let path = Path::new(self.line.from.clone(), self.line.to.clone());
        let mut q = self.k.dims().q();
        q.as_mut().copy_from_slice(self.states[0].q());
        let per_param = Metric::at(&self.k, &path, &self.line.from, &q).input_len / (last - first);
        // Per gap, the parts it is cut into (1: none; not finite where the path's length
        // overflows the inputs' units: the samples alone).
        let parts: Vec<usize> = self
            .s
            .windows(2)
            .map(|w| {
                let parts = ((w[1] - w[0]) * per_param / MAX_INPUT_STEP).ceil();
                if parts > 1.0 && parts.is_finite() { parts.min(f64::from(u32::MAX)) as usize } else { 1 }
            })
            .collect();
        let between: usize = parts.iter().map(|n| n - 1).sum();
        if between > MAX_SEARCH_POINTS {
            // The fewest samples that would do, from the path's length in natural steps (and
            // more than these, should the samples' own gaps, moved by a crossing, need more).
            let natural = per_param * (last - first) / MAX_INPUT_STEP;
            let least = least_search_samples(natural).max(self.s.len() + 1);
            let advice = if least <= super::MAX_SAMPLES {
                format!("give at least {least} samples, or a shorter range")
            } else {
                format!(
                    "the range is too long to search: it would need {least} samples, more than the {} a sampled \
                     sweep takes; give a shorter range",
                    super::MAX_SAMPLES
                )
            };
            return Err(Error::InvalidArgument(format!(
                "the samples are too far apart to search between: {between} points a sweep's natural step \
                 apart would be solved between them, more than the {MAX_SEARCH_POINTS} a search keeps; {advice}"
            )));
        }
        let mut grid = Search { s: vec![first], states: vec![Cow::Borrowed(&self.states[0])], gaps: Vec::new() };
        for (i, w) in self.s.windows(2).enumerate() {
            if parts[i] > 1 {
                let n = parts[i];
                let (start, end) = (&self.states[i], &self.states[i + 1]);
                let (mut from, mut to, mut guess) = (self.k.dims().x(), self.k.dims().x(), self.k.dims().q());
                from.as_mut().copy_from_slice(start.x());
                to.as_mut().copy_from_slice(end.x());
                guess.as_mut().copy_from_slice(start.q());
                let mut gap = SweepOf::<&K, KinOf<K>>::over(&self.k, from, to, n + 1, guess)?.with_config(self.cfg);
                // The gap's ends are the samples themselves.
                gap.next_ref().transpose()?;
                for j in 1..n {
                    let state =
                        gap.next_kin().unwrap_or_else(|| Err(Error::InvalidArgument("a gap's sweep ended".into())))?;
                    grid.s.push(w[0] + (w[1] - w[0]) * (j as f64 / n as f64));
                    grid.states.push(Cow::Owned(state));
                }
            }
            grid.s.push(w[1]);
            grid.states.push(Cow::Borrowed(&self.states[i + 1]));
        }
        let mut crossings: Vec<(f64, &Crossing<K>)> =
            self.crossings.iter().map(|c| (self.line.param(c.x.as_ref()), c)).collect();
        crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (s, c) in crossings {
            self.part_at(&mut grid, s, c);
        }
        Ok(grid)
    }

    /// Parts the grid at the crossing `c` (path parameter `s`): the points nearest it either
    /// side that a sweep reaches from the grid's neighbours of the crossing join the grid, and
    /// the interval between them is a [`Gap`]. A crossing at a grid point or beyond its ends, or
    /// within a gap already made, parts nothing.
    fn part_at(&self, grid: &mut Search<'_, K>, s: f64, c: &Crossing<K>) {
        let i = grid.s.partition_point(|&v| v <= s);
        if i == 0 || i == grid.s.len() || grid.s[i - 1] == s || grid.gaps.iter().any(|g| g.at == i - 1) {
            return;
        }
        let before = self.toward(&grid.states[i - 1], grid.s[i - 1], s);
        let after = self.toward(&grid.states[i], grid.s[i], s);
        let mut at = i - 1;
        if let Some((v, state)) = before {
            at = i;
            grid.s.insert(at, v);
            grid.states.insert(at, Cow::Owned(state));
        }
        if let Some((v, state)) = after {
            grid.s.insert(at + 1, v);
            grid.states.insert(at + 1, Cow::Owned(state));
        }
        // The outputs at the crossing's own positions: its pivot is at the rounding there, below
        // any singular tolerance, and only the values are read.
        let state = self.k.kinematics_at(&c.x, &c.q, &self.cfg.newton.with_singular_tol(0.0)).ok();
        grid.gaps.push(Gap { at, s, state });
    }

    /// The state nearest the crossing at path parameter `to` that sweeps reach from `start` (at
    /// `from`, on one side of it) on their branch: steps halving the distance left, until one
    /// fails (within the crossing's pivot band, see [`SweepConfig::singular_pivot`]) or passes an
    /// event (the crossing itself, located a little off). `None` where even the first fails.
    /// About `log2` of the distance over the band's width steps (some twenty), at each crossing.
    fn toward(&self, start: &KinOf<K>, from: f64, to: f64) -> Option<(f64, KinOf<K>)> {
        let d = self.k.dims();
        let mut reached: Option<(f64, KinOf<K>)> = None;
        let mut gap = from - to;
        // At most the doubles between `from` and `to`.
        for _ in 0..64 {
            gap *= 0.5;
            let s = to + gap;
            let cur = reached.as_ref().map_or(start, |r| &r.1);
            if s == to || s == self.line.param(cur.x()) {
                break;
            }
            let (mut x0, mut guess) = (d.x(), d.q());
            x0.as_mut().copy_from_slice(cur.x());
            guess.as_mut().copy_from_slice(cur.q());
            let Ok(sweep) = SweepOf::<&K, KinOf<K>>::over(&self.k, x0, self.line.point(s), 2, guess) else { break };
            let mut sweep = sweep.with_config(self.cfg);
            if !matches!(sweep.next_ref(), Some(Ok(_))) {
                break;
            }
            match sweep.next_kin() {
                Some(Ok(state)) if sweep.events().is_empty() => reached = Some((s, state)),
                _ => break,
            }
        }
        reached
    }

    /// A column's jets at the points of `grid`, and its jet anywhere in the range stepped from
    /// the nearest of them (a step no longer than the grid's spacing: the cost of a search stays
    /// linear in the range).
    ///
    /// With them, the column at each crossing the grid is parted at ([`Gap`]), as
    /// [`extremes::Corner`]s: its value from the state at the crossing (from the nearer side's
    /// Taylor polynomial where that state's outputs cannot be evaluated, the side a pivot band
    /// away), its analogs interpolated across the gap (the velocity analog linearly, the
    /// acceleration analog as the velocity analog's difference quotient over it).
    fn search_jets<'a>(
        &'a self,
        c: ColumnIndex,
        grid: &'a Search<'a, K>,
    ) -> (Vec<Jet>, Vec<extremes::Corner>, impl FnMut(f64) -> Result<Jet, Error> + 'a) {
        let (jets, corners) = self.grid_jets(c, grid);
        let eval = move |s: f64| {
            self.at_near(s, &grid.s, |j| &grid.states[j]).map(|st| jet_along(c, &st, s, self.line.dir.as_ref()))
        };
        (jets, corners, eval)
    }

    /// A column's jets at the points of `grid` and its corners at the crossings the grid is
    /// parted at (see [`SampledOf::search_jets`]).
    fn grid_jets(&self, c: ColumnIndex, grid: &Search<'_, K>) -> (Vec<Jet>, Vec<extremes::Corner>) {
        let dir = self.line.dir.as_ref();
        let jets: Vec<Jet> = grid.s.iter().zip(&grid.states).map(|(&s, st)| jet_along(c, &**st, s, dir)).collect();
        let corners = grid
            .gaps
            .iter()
            .map(|g| {
                let (l, r) = (jets[g.at], jets[g.at + 1]);
                let near = if g.s - l.x <= r.x - g.s { l } else { r };
                let h = g.s - near.x;
                let taylor = near.value + h * (near.d1 + 0.5 * h * near.d2);
                let value = g
                    .state
                    .as_ref()
                    .map(|st| jet_along(c, st, g.s, dir).value)
                    .filter(|v| v.is_finite())
                    .unwrap_or(taylor);
                let slope = (r.d1 - l.d1) / (r.x - l.x);
                let at = Jet { x: g.s, value, d1: l.d1 + slope * (g.s - l.x), d2: slope };
                extremes::Corner { after: g.at, at }
            })
            .collect();
        (jets, corners)
    }

    /// The local extremes of a column (interior roots of its derivative along the path), in
    /// increasing path parameter; see [`extremes()`](extremes::extremes). Between samples
    /// farther apart than a sweep's natural step, the sign changes are looked for at points
    /// that close, solved on the sweep's branch: samples a turn apart do not hide them. A
    /// column that stands still to the rounding of what it is computed from (a parallelogram's
    /// coupler angle) has none: the sign changes of its analog are rounding.
    pub fn extremes(&self, c: impl ColumnOf<K>) -> Result<Vec<LocalExtreme>, Error> {
        let c = c.resolve(&self.k)?;
        self.searched(c, |jets, corners, eval| {
            if self.stands_still(c, jets, corners) {
                Ok(Vec::new())
            } else {
                extremes::extremes_across(jets, corners, eval)
            }
        })
    }

    /// Whether a column stands still over a search's points (`jets`, and the `corners` at the
    /// crossings among them): all its values within its rounding (see
    /// [`SampledOf::rounding_tolerance`]), as its return to its start is judged. Its velocity
    /// analog is then rounding too, and the sign changes of that noise are no extremes: a
    /// parallelogram's coupler angle, zero at every crank angle, had
    /// thirty "extremes" a turn, at crank angles the rounding chose.
    ///
    /// And its velocity analog says so too, where its kind has a scale of motion (see
    /// [`SampledOf::motion_scale`]): the analog's largest magnitude over the range's length
    /// within the same tolerance of it. The values' tolerance grew with their magnitude, and a
    /// small mechanism far from the origin moved by less than it (a slider-crank a millimetre
    /// across in Earth-centred coordinates, 6.4e6 m out, strokes 2 mm where the tolerance was
    /// 6.4 mm): its slider "stood still", without extremes, one rest a turn. The analogs are
    /// free of the offset, and a column that stands still has analogs at their rounding.
    fn stands_still(&self, c: ColumnIndex, jets: &[Jet], corners: &[extremes::Corner]) -> bool {
        let values = || jets.iter().chain(corners.iter().map(|k| &k.at)).map(|j| j.value);
        let (lo, hi) = values().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if hi - lo > self.rounding_tolerance(c, values()) {
            return false;
        }
        let Some(scale) = self.motion_scale(c) else { return true };
        let (first, last) = (self.s[0], self.s[self.s.len() - 1]);
        // Not at the points beside a singular crossing, where the positions are pinned only to
        // about 1e-10 and the analogs not to be trusted (a parallelogram's coupler angle has
        // analogs of 7e-5 a millionth of a radian from its change points, 1e-14 elsewhere).
        let beside = |i: usize| corners.iter().any(|k| i == k.after || i == k.after + 1);
        let analog = (0..jets.len()).filter(|&i| !beside(i)).map(|i| jets[i].d1.abs()).fold(0.0, f64::max);
        analog * (last - first) <= unbalance::PERIODIC_TOLERANCE * scale
    }

    /// How far a column of `c`'s kind moves over the range when it moves at all, the scale
    /// against which [`SampledOf::stands_still`] judges its analog: `pi` for an angle, 1 for a
    /// pure number, the mechanism's size for a length (the largest range of any length column
    /// over the samples: its offset from the origin left out). `None` for other kinds, and for
    /// a length where no length column moves: the values alone judge those.
    fn motion_scale(&self, c: ColumnIndex) -> Option<f64> {
        match column_kind(&self.k, c) {
            QuantityKind::Angle => Some(std::f64::consts::PI),
            QuantityKind::Dimensionless => Some(1.0),
            QuantityKind::Length => Some(self.length_range()).filter(|&v| v > 0.0),
            _ => None,
        }
    }

    /// Column `c` as a search between the samples sees it ([`SampledOf::extremes`]), handed to
    /// `f`: its jets at the search's points, the crossings among them, and its jet anywhere in
    /// the range. What every analysis that locates an event of a column between samples looks
    /// at: the samples alone miss two events within one spacing (a turn in three samples).
    pub(crate) fn searched<R>(
        &self,
        c: ColumnIndex,
        f: impl FnOnce(&[Jet], &[extremes::Corner], &mut dyn FnMut(f64) -> Result<Jet, Error>) -> Result<R, Error>,
    ) -> Result<R, Error> {
        let grid = self.search()?;
        let (jets, corners, mut eval) = self.search_jets(c, &grid);
        f(&jets, &corners, &mut eval)
    }

    /// Two columns as a search between the samples sees them ([`SampledOf::searched`]), handed
    /// to `f`: each one's jets at the search's points and its corners at the crossings among
    /// them, and both jets anywhere in the range (from one state): for an analysis of two
    /// columns at once (the transmission angle's coupler and follower).
    pub(crate) fn searched_pair<R>(
        &self,
        a: ColumnIndex,
        b: ColumnIndex,
        f: impl FnOnce(
            [(&[Jet], &[extremes::Corner]); 2],
            &mut dyn FnMut(f64) -> Result<(Jet, Jet), Error>,
        ) -> Result<R, Error>,
    ) -> Result<R, Error> {
        let grid = self.search()?;
        let ((ja, ca), (jb, cb)) = (self.grid_jets(a, &grid), self.grid_jets(b, &grid));
        let dir = self.line.dir.as_ref();
        let mut at = |s: f64| {
            self.at_near(s, &grid.s, |j| &grid.states[j])
                .map(|st| (jet_along(a, &st, s, dir), jet_along(b, &st, s, dir)))
        };
        f([(&ja, &ca), (&jb, &cb)], &mut at)
    }

    /// The global minimum and maximum of a column over the range (interior extremes, or samples: the ends among them),
    /// e.g. the dead centres and stroke of a slider; see [`global_range`](extremes::global_range). The interior
    /// extremes are looked for as [`SampledOf::extremes`] looks for them.
    pub fn range(&self, c: impl ColumnOf<K>) -> Result<GlobalRange, Error> {
        let c = c.resolve(&self.k)?;
        self.searched(c, |jets, corners, eval| {
            let found = if self.stands_still(c, jets, corners) {
                Vec::new()
            } else {
                extremes::extremes_across(jets, corners, eval)?
            };
            Ok(extremes::range_with(found, jets, corners))
        })
    }

    /// The dwells of a progressive column; see [`dwell`] for the definition. Between samples
    /// farther apart than a sweep's natural step, looked for as [`SampledOf::extremes`] looks.
    /// A column with no net travel is an error: one that returns to its start within
    /// [`NO_TRAVEL`](dwell::NO_TRAVEL) of its range, or within the rounding of what it is
    /// computed from (as [`SampledOf::fourier`] judges it periodic).
    pub fn dwells(&self, c: impl ColumnOf<K>) -> Result<Vec<Dwell>, Error> {
        let c = c.resolve(&self.k)?;
        // A column that stands still in exact arithmetic moves by its rounding alone, whose
        // travel against its range (rounding too) decided whether it was progressive: judged
        // as its return to its start is (see `periodic`), it has no net travel.
        self.searched(c, |jets, corners, eval| {
            let values = jets.iter().chain(corners.iter().map(|k| &k.at)).map(|j| j.value);
            let still = self.rounding_tolerance(c, values);
            dwell::dwells_across(jets, corners, eval, still)
        })
    }

    /// The rests of a column: where it stands exactly still (its velocity analog exactly zero
    /// over a stretch, as a cam follower's in the dwells of its law); see [`rest`] for the
    /// definition. Each end is located between the samples by bisection, to the spacing of the
    /// input's doubles (an end at a singular crossing the sweep passed, to the width of the
    /// crossing's band, where nothing is solved); a rest reaching an end of the range is cut
    /// there. A rest may run across a crossing.
    ///
    /// Unlike [`SampledOf::dwells`], for any output: a cam follower that rises, dwells, returns
    /// and dwells has no net travel, so no dwell by that definition, but two rests a turn.
    ///
    /// A column that stands still over the whole range to its rounding (all its values within
    /// [`PERIODIC_TOLERANCE`](unbalance::PERIODIC_TOLERANCE) of how far what it is computed
    /// from moves, as [`SampledOf::extremes`] judges it: a point's coordinate on a line of symmetry, zero in
    /// exact arithmetic) is one rest, the whole range. Its values are rounding, and its
    /// velocity analog, exactly zero over some stretches and a rounding's size over others,
    /// made it "stand still" in fragments, at values apart by their rounding.
    pub fn rests(&self, c: impl ColumnOf<K>) -> Result<Vec<Rest>, Error> {
        let c = c.resolve(&self.k)?;
        self.searched(c, |jets, corners, eval| {
            if let (true, Some(&start), Some(&end)) = (self.stands_still(c, jets, corners), jets.first(), jets.last()) {
                return Ok(vec![Rest { start, end }]);
            }
            rest::rests_across(jets, corners, eval)
        })
    }

    /// The maximum of a derived quantity `f(state)` (e.g. the magnitude of an acceleration
    /// analog) over the range: the best sample (and point between samples farther apart than
    /// a sweep's natural step, as [`SampledOf::extremes`] looks), refined by Brent's
    /// derivative-free search between its neighbours. Returns `(s, f)`. For a minimum, maximise `-f`. A value of `f`
    /// not finite, at a sample or in the search, is an `InvalidArgument`. Beside a singular
    /// crossing the sweep passed nothing is solved within the crossing's band: a peak at the
    /// crossing is located to the band's width, at its nearer side.
    pub fn peak(&self, f: impl Fn(&KinOf<K>) -> f64) -> Result<(f64, f64), Error> {
        self.peak_by(|_, k| f(k))
    }

    /// The maximum of a function of a column's jet along the path (e.g. `|j| j.d2.abs()`, the
    /// largest acceleration analog), located as by [`SampledOf::peak`]. Returns `(s, f)`.
    pub fn peak_of(&self, c: impl ColumnOf<K>, f: impl Fn(Jet) -> f64) -> Result<(f64, f64), Error> {
        let c = c.resolve(&self.k)?;
        self.peak_by(|s, k| f(jet_along(c, k, s, self.line.dir.as_ref())))
    }

    fn peak_by(&self, f: impl Fn(f64, &KinOf<K>) -> f64) -> Result<(f64, f64), Error> {
        // The samples, and points between those farther apart than a sweep's natural step.
        let grid = self.search()?;
        let (at, values): (&[f64], Vec<f64>) =
            (&grid.s, grid.s.iter().zip(&grid.states).map(|(&s, k)| f(s, k)).collect());
        // As `maximize` refuses a value not finite: an infinite sample was returned as the peak,
        // and a NaN with its sign bit set, ordered below every number, was passed over.
        if let Some(j) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::InvalidArgument(format!("the quantity is {} at the sample {}", values[j], at[j])));
        }
        // Every local maximum of the samples is refined, not only the best sample: the peak
        // may lie beside another one that ties with it or nearly (over a full turn the first
        // and the last sample are equal, and the peak just after the first was missed where
        // the last was refined).
        let last = values.len() - 1;
        let local = |j: usize| (j == 0 || values[j] >= values[j - 1]) && (j == last || values[j] >= values[j + 1]);
        let mut best = (f64::NAN, f64::NEG_INFINITY);
        // Nothing is solved across a singular crossing's gap (within its band, where the search
        // failed): a neighbour beyond one is not searched towards, so that a peak at the crossing
        // is located to the gap's width, at its nearer side.
        let gap_after = |i: usize| grid.gaps.iter().any(|g| g.at == i);
        for j in (0..values.len()).filter(|&j| local(j)) {
            let lo = if j == 0 || gap_after(j - 1) { at[j] } else { at[j - 1] };
            let hi = if j == last || gap_after(j) { at[j] } else { at[j + 1] };
            if lo == hi {
                if values[j] > best.1 {
                    best = (at[j], values[j]);
                }
                continue;
            }
            let (s, v) = maximize(lo, hi, |s| self.at_near(s, at, |k| &grid.states[k]).map(|k| f(s, &k)))?;
            // Brent returns an interior point; the sample itself may be better (at an end of
            // the range).
            let here = if v >= values[j] { (s, v) } else { (at[j], values[j]) };
            if here.1 > best.1 {
                best = here;
            }
        }
        Ok(best)
    }

    /// Checks that a column returns to its starting value over the range (one period).
    /// The jets are the column's at the equally spaced points of the range (see
    /// [`SampledOf::on_grid`]), as Fourier sums weigh them.
    fn periodic(&self, c: ColumnIndex) -> Result<Vec<Jet>, Error> {
        let mut jets = self.jets_of(c);
        self.on_grid(c, &mut jets)?;
        let (a, b) = (jets[0].value, jets[jets.len() - 1].value);
        if (a - b).abs() > self.rounding_tolerance(c, jets.iter().map(|j| j.value)) {
            return Err(Error::InvalidArgument(format!(
                "`{}` is not periodic over the sweep ({a} at the start, {b} at the end): sweep exactly one cycle",
                column_name(&self.k, c)
            )));
        }
        Ok(jets)
    }

    /// Moves the jets of samples the sweep did not take at their equally spaced points back to
    /// them. A sweep cannot land on a singular crossing it passes (within about 1e-7 of it, where
    /// no solve pins the branch): the first well-conditioned point past it, up to a thousandth
    /// of the input further on, stands for that sample. Fourier sums weigh every sample as if at
    /// its point: a crank at 180 degrees of a change-point four-bar, sampled every 10 degrees,
    /// moved the mean of its joint's `x` by 1.3e-8. The column there is its value at the
    /// crossing (as [`SampledOf::extremes`] takes it, the positions the sweep located there),
    /// moved to the point by the slope of the point's side; elsewhere it is solved there.
    fn on_grid(&self, c: ColumnIndex, jets: &mut [Jet]) -> Result<(), Error> {
        let n = jets.len() - 1;
        let (first, last) = (self.s[0], self.s[n]);
        let point = |j: usize| if j == n { last } else { first + (last - first) * (j as f64 / n as f64) };
        // The sweep's own inputs round differently from `point`: off by more than that.
        let off: Vec<usize> = (0..=n).filter(|&j| (jets[j].x - point(j)).abs() > 1e-9 * (last - first)).collect();
        if off.is_empty() {
            return Ok(());
        }
        let grid = self.search()?;
        let (at, corners) = self.grid_jets(c, &grid);
        for j in off {
            let s = point(j);
            jets[j] = match corners.iter().find(|k| at[k.after].x <= s && s <= at[k.after + 1].x) {
                // The crossing's own value, moved by the tangent of the point's side (the
                // side's acceleration analog is not to be trusted so near the crossing).
                Some(k) => {
                    let side = if s <= k.at.x { at[k.after] } else { at[k.after + 1] };
                    Jet { x: s, value: k.at.value + (s - k.at.x) * side.d1, ..side }
                }
                None => self.jet_of(c, s)?,
            };
        }
        Ok(())
    }

    /// The tolerance within which a column's values are one value (its return to its start, its
    /// standing still, a net travel that is none): its rounding. A column that stands still in
    /// exact arithmetic (a parallelogram's coupler angle, a point's coordinate on a line of
    /// symmetry) is rounding alone, some 1e-16 of the quantities it is solved from: against its
    /// own size that noise is all there is, and a turn of it was "not periodic". So the
    /// tolerance is [`PERIODIC_TOLERANCE`](unbalance::PERIODIC_TOLERANCE) of how far what it is
    /// computed from moves, whatever the column's own value:
    ///
    /// * an angle: `pi`, the size of any angle (its rounding is absolute, a few ulps of the
    ///   angles summed and the `atan2`s taken, whatever the angle's own value);
    /// * a length: the largest range of any length column over the samples, how far the
    ///   mechanism moves (not an absolute floor: the unit of length is the user's, and a
    ///   mechanism a micrometre across is judged as one a metre across; nor where it stands:
    ///   the largest magnitude of any length, the floor this was, grew with the mechanism's
    ///   distance from the origin, and a slider-crank a millimetre across 6.4e6 m out took half
    ///   a turn for a period, its tolerance 6.4 mm);
    /// * a pure number (a ratio of lengths, a sine): 1, as an angle; its rounding is absolute
    ///   too, a few ulps of the sines and ratios of size one it is computed from, in any unit of
    ///   length (a ratio that is zero in exact arithmetic, the height of a centred slider's pin
    ///   over its rod, was rounding judged against itself: "not periodic");
    /// * anything else (a time, a quantity whose kind is not inferred, an area): its own size;
    ///   kinloop does not know what it is computed from (one that is zero in exact arithmetic is
    ///   rounding judged against itself, and does not stand still);
    ///
    /// and beside it [`ROUNDING`](unbalance::ROUNDING) of the magnitude of the values, the
    /// column's own and, for a length, any length column's: what a double far from the origin
    /// resolves.
    fn rounding_tolerance(&self, c: ColumnIndex, values: impl Iterator<Item = f64>) -> f64 {
        let own = values.map(f64::abs).fold(0.0, f64::max);
        let (motion, magnitude) = match column_kind(&self.k, c) {
            QuantityKind::Angle => (std::f64::consts::PI, own),
            QuantityKind::Length => (self.length_range(), own.max(self.length_scale())),
            QuantityKind::Dimensionless => (1.0, own),
            _ => (own, own),
        };
        unbalance::PERIODIC_TOLERANCE * motion + unbalance::ROUNDING * magnitude
    }

    /// The largest magnitude of any length column (input, unknown or output) over the samples:
    /// where the mechanism stands, in its own unit of length (0 without length columns).
    fn length_scale(&self) -> f64 {
        self.length_columns()
            .flat_map(|c| self.states.iter().map(move |st| column_value(c, st).abs()))
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    }

    /// The largest range (largest less smallest value) of any length column over the samples:
    /// how far the mechanism's lengths move, wherever it stands (0 without length columns).
    fn length_range(&self) -> f64 {
        self.length_columns()
            .map(|c| {
                let values = self.states.iter().map(|st| column_value(c, st)).filter(|v| v.is_finite());
                let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
                if hi >= lo { hi - lo } else { 0.0 }
            })
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    }

    /// The length columns (inputs, unknowns, outputs) of the kernel.
    fn length_columns(&self) -> impl Iterator<Item = ColumnIndex> + '_ {
        let d = self.k.dims();
        (0..d.ni())
            .map(ColumnIndex::Input)
            .chain((0..d.n()).map(ColumnIndex::Unknown))
            .chain((0..d.no()).map(ColumnIndex::Output))
            .filter(|&c| column_kind(&self.k, c) == QuantityKind::Length)
    }

    /// Fourier coefficients of a column up to `harmonics`, the sweep being one period (`n + 1`
    /// samples, the last repeating the first); see [`fourier()`](fourier::fourier).
    pub fn fourier(&self, c: impl ColumnOf<K>, harmonics: usize) -> Result<Fourier, Error> {
        let jets = self.periodic(c.resolve(&self.k)?)?;
        let n = jets.len() - 1;
        let values: Vec<f64> = jets[..n].iter().map(|j| j.value).collect();
        fourier::fourier(&values, jets[0].x, jets[n].x - jets[0].x, harmonics)
    }

    /// The residual of a column after removing its mean and harmonics `1 ..= removed`, and its
    /// largest magnitude over the period (the residual unbalance `D` for `removed = 1`); see
    /// [`unbalance()`](unbalance::unbalance).
    pub fn unbalance(&self, c: impl ColumnOf<K>, removed: usize) -> Result<Unbalance, Error> {
        let c = c.resolve(&self.k)?;
        let jets = self.periodic(c)?;
        let tolerance = self.rounding_tolerance(c, jets.iter().map(|j| j.value));
        // The residual's extremes are looked for as `extremes` looks for a column's: across a
        // singular crossing the sweep passed, at the crossing, not by a refinement stepping
        // into its band (which failed the whole call with `NearSingular`).
        self.searched(c, |search, corners, eval| {
            unbalance::unbalance_across(&jets, search, corners, eval, removed, tolerance)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::demo::SliderCrank;
    use crate::paths::collected::MAX_COLLECTED_BYTES;
    use std::f64::consts::TAU;

    /// Samples whose states would exceed the memory budget (a few million, well within
    /// `MAX_SAMPLES`) are refused before any step, saying so and what to do: the guess, not a
    /// number, fails the first step, so the refusal is the first thing done. At the budget the
    /// sweep starts, and that first step's failure is the error. Without the budget such a count
    /// was swept, every state kept, until memory ran out.
    #[test]
    fn a_sampled_sweep_beyond_the_memory_budget_is_refused_up_front() {
        let m = SliderCrank { r: 1.0, l: 2.5, e: 0.7 };
        let each = sampled_bytes_each(&Compiled(&m));
        // The state is counted with what the analyses hold beside it.
        assert!(each > 2 * size_of::<KinOf<Compiled<'_, SliderCrank, 1, 1, 1>>>(), "{each}");
        let fits = MAX_COLLECTED_BYTES / each;
        assert!(fits < crate::analysis::MAX_SAMPLES);
        let err = Sampled::sweep(&m, 0.0, TAU, fits + 1, [f64::NAN]).expect_err("refused");
        let msg = err.to_string();
        assert!(matches!(err, Error::InvalidArgument(_)), "{err:?}");
        let numbers = format!("the sampled sweep would keep {} states of {each} bytes", fits + 1);
        for what in [numbers.as_str(), "fewer samples", "samples_to_search"] {
            assert!(msg.contains(what), "{what:?} not in {msg}");
        }
        let err = Sampled::sweep(&m, 0.0, TAU, fits, [f64::NAN]).expect_err("a guess not a number");
        assert!(!err.to_string().contains("would keep"), "{err}");
    }

    /// The points a search solves between `g` equal gaps over `l` natural steps.
    fn between(l: f64, g: f64) -> f64 {
        g * ((l / g).ceil() - 1.0)
    }

    /// The count advised fits the search, even a hair longer, and one fewer does not the
    /// millionth longer path it allows for (where more than three are needed); beyond twice the points kept, one sample per natural step.
    /// The advice was one sample per natural step however few would do, and beyond the
    /// samples a sweep takes said nothing of it.
    #[test]
    fn the_fewest_samples_to_search_fit_and_one_fewer_does_not() {
        let max = MAX_SEARCH_POINTS as f64;
        for l in [10.0, max, max + 0.5, max + 1.0, 1.3 * max, 1.5 * max, 1.99 * max, 2.0 * max, 2.5 * max, 2.5e7] {
            let n = least_search_samples(l);
            let g = (n - 1) as f64;
            assert!(between(l * (1.0 + 5e-7), g) <= max, "{l}: {n} samples");
            if n > 3 {
                assert!(between(l * (1.0 + 1e-6), g - 1.0) > max, "{l}: {n} samples, one fewer fits");
            }
            if l > 2.0 * max {
                assert_eq!(n as f64, (l * (1.0 + 1e-6)).ceil() + 1.0, "{l}");
            }
        }
        assert_eq!(least_search_samples(f64::INFINITY), usize::MAX);
        assert_eq!(least_search_samples(f64::NAN), usize::MAX);
    }
    /// Ends that are not finite are refused as a sweep refuses them (`Error::NonFinite`, naming
    /// the end), where the count was `usize::MAX`, which a caller read as a range too long for
    /// any sample count.
    #[test]
    fn the_samples_to_search_refuse_ends_not_finite() {
        let m = SliderCrank { r: 1.0, l: 2.5, e: 0.7 };
        let k = Compiled(&m);
        let guess = m.guess_flat(&[0.0]);
        for (from, to, end) in [(f64::NAN, 1.0, "from"), (0.0, f64::INFINITY, "to"), (f64::NEG_INFINITY, 0.0, "from")] {
            match samples_to_search(&k, &[from], &[to], &guess) {
                Err(Error::NonFinite { name, .. }) => assert_eq!(name, end, "{from} to {to}"),
                other => panic!("{from} to {to}: {other:?}"),
            }
        }
        assert_eq!(samples_to_search(&k, &[0.0], &[1.0], &guess).unwrap(), 3);
    }
}
