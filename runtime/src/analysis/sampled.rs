//! [`Sampled`]: a branch-safe sweep kept in memory and analysed column by column.

use super::column::Column;
use super::extremes::{self, GlobalRange, LocalExtreme, global_range, maximize};
use super::{Dwell, Fourier, Jet, Unbalance, dwell, fourier, unbalance};
use crate::error::Error;
use crate::kin::Kin;
use crate::mechanism::Mechanism;
use crate::paths::sweep::{Sweep, SweepConfig};

/// The straight path of a [`Sampled`] in input space and its parameter `s`.
#[derive(Clone, Copy, Debug)]
struct Line<const NI: usize> {
    from: [f64; NI],
    to: [f64; NI],
    /// How far the inputs move per unit of `s`.
    dir: [f64; NI],
    /// `s` is input `k` itself (`Some(k)`) or the fraction of the path (`None`).
    along: Option<usize>,
}

impl<const NI: usize> Line<NI> {
    fn fraction(from: [f64; NI], to: [f64; NI]) -> Self {
        Line { from, to, dir: std::array::from_fn(|i| to[i] - from[i]), along: None }
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
        let dir = std::array::from_fn(|i| if i == k { 1.0 } else { (self.to[i] - self.from[i]) / run });
        Ok(Line { dir, along: Some(k), ..self })
    }

    /// The parameter of the point `x` of the path.
    fn param(&self, x: &[f64; NI]) -> f64 {
        match self.along {
            Some(k) => x[k],
            None => {
                let delta: [f64; NI] = std::array::from_fn(|i| self.to[i] - self.from[i]);
                let dot = |a: &[f64; NI], b: &[f64; NI]| (0..NI).map(|i| a[i] * b[i]).sum::<f64>();
                let off: [f64; NI] = std::array::from_fn(|i| x[i] - self.from[i]);
                dot(&off, &delta) / dot(&delta, &delta)
            }
        }
    }

    /// The inputs at parameter `s`.
    fn point(&self, s: f64) -> [f64; NI] {
        let s0 = self.along.map_or(0.0, |k| self.from[k]);
        let mut x: [f64; NI] = std::array::from_fn(|i| self.from[i] + (s - s0) * self.dir[i]);
        match self.along {
            Some(k) => x[k] = s,
            None if s == 1.0 => x = self.to,
            None => {}
        }
        x
    }
}

/// A branch-safe sweep along a straight path in input space, kept in memory and analysed
/// column by column: extremes located as roots of the velocity analog, dwells, Fourier
/// coefficients, residual unbalance. Between samples the mechanism is solved again (warm-started
/// from the nearest sample and stepped there by a two-sample [`Sweep`], so the refinement never
/// leaves the sweep's branch).
///
/// Columns are the generated typed handles `Name::COL.field` (see [`Column`]); every quantity
/// is a function of the **path parameter** `s`:
///
/// * one input ([`Sampled::sweep`]): `s` is the input itself, the jets' derivatives are the
///   velocity and acceleration analogs;
/// * several inputs ([`Sampled::path`]): the inputs move on the straight line from `from` to
///   `to`, `s` is the fraction of the path (0 at `from`, 1 at `to`), or one chosen input after
///   [`Sampled::along`]; the derivatives along the path are the analog tensors contracted with
///   the path's direction `d` (`dq/ds = dq[u][i] d_i`, `d2q/ds2 = d2q[u][i][j] d_i d_j`).
///
/// The number of inputs `NI` comes last and defaults to one, so that `Sampled<'_, M, N, NO>`
/// is the single-input type (`N` unknowns, `NO` output columns, as in `Mechanism<N, NI, NO>`).
///
/// For [`Sampled::fourier`] and [`Sampled::unbalance`] the range must be one period of the
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
pub struct Sampled<'m, M, const N: usize, const NO: usize, const NI: usize = 1> {
    m: &'m M,
    states: Vec<Kin<N, NI, NO>>,
    /// The path parameter of each state.
    s: Vec<f64>,
    line: Line<NI>,
    cfg: SweepConfig,
}

impl<'m, M, const N: usize, const NO: usize> Sampled<'m, M, N, NO, 1>
where
    M: Mechanism<N, 1, NO>,
{
    /// Sweeps `samples` equally spaced inputs from `from` to `to > from` (both included) from
    /// `guess` at `from` (which picks the assembly mode). The path parameter is the input.
    ///
    /// A declared mechanism's `m.sampled(from, to, samples, &m.guess(from))` is this call with
    /// the named unknowns; this form serves code generic over [`Mechanism`] and hand-written
    /// implementations, as [`Sweep::new`] does beside `m.sweep`.
    pub fn sweep(m: &'m M, from: f64, to: f64, samples: usize, guess: impl Into<[f64; N]>) -> Result<Self, Error> {
        Self::sweep_with(m, from, to, samples, guess, SweepConfig::default())
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
        if from.partial_cmp(&to) != Some(std::cmp::Ordering::Less) {
            return Err(Error::InvalidArgument(format!("Sampled::sweep needs from < to (got {from} .. {to})")));
        }
        Self::path_with(m, [from], [to], samples, guess, cfg)?.reparametrised(|l| l.along(0, M::INPUTS[0]))
    }
}

impl<'m, M, const N: usize, const NO: usize, const NI: usize> Sampled<'m, M, N, NO, NI>
where
    M: Mechanism<N, NI, NO>,
{
    /// Sweeps `samples` equally spaced points of the straight path from inputs `from` to `to`
    /// (both included; arrays or the generated `NameInputs`) from `guess` at `from`. The path
    /// parameter is the fraction of the path, `0 ..= 1`; see [`Sampled::along`] to use an input.
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
        Self::path_with(m, from, to, samples, guess, SweepConfig::default())
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
        let (from, to, guess) = (from.into(), to.into(), guess.into());
        if samples < 3 || from == to {
            return Err(Error::InvalidArgument(format!(
                "Sampled needs from != to and at least 3 samples (got {from:?} .. {to:?}, {samples} samples)"
            )));
        }
        let mut sweep = Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(m, from, to, samples, guess)?.with_config(cfg);
        let mut states = Vec::with_capacity(samples);
        while let Some(k) = sweep.next_kin() {
            states.push(k?);
        }
        let line = Line::fraction(from, to);
        let s = states.iter().map(|k| line.param(&k.x)).collect();
        Ok(Sampled { m, states, s, line, cfg })
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
        let s = Self::path(m, from, to, samples, guess)?;
        if NI == 1 { s.reparametrised(|l| l.along(0, M::INPUTS.first().copied().unwrap_or("?"))) } else { Ok(s) }
    }

    /// The same samples with input `input` (`Name::COL.th1`) as the path parameter: jets are
    /// then derivatives with respect to that input along the path (the other inputs following
    /// it). The input must increase from `from` to `to`.
    pub fn along(self, input: Column<M>) -> Result<Self, Error> {
        match input.check::<N, NI, NO>()?.index() {
            super::ColumnIndex::Input(k) => self.reparametrised(|l| l.along(k, input.name())),
            _ => Err(Error::InvalidArgument(format!("`{}` is not an input of `{}`", input.name(), M::NAME))),
        }
    }

    fn reparametrised(mut self, f: impl FnOnce(Line<NI>) -> Result<Line<NI>, Error>) -> Result<Self, Error> {
        self.line = f(self.line)?;
        self.s = self.states.iter().map(|k| self.line.param(&k.x)).collect();
        Ok(self)
    }

    /// The sampled states, in increasing path parameter.
    pub fn states(&self) -> &[Kin<N, NI, NO>] {
        &self.states
    }

    /// The path parameter of each sampled state (the input values for a single-input sweep).
    pub fn path_values(&self) -> &[f64] {
        &self.s
    }

    /// How far the inputs move per unit of the path parameter.
    pub fn direction(&self) -> [f64; NI] {
        self.line.dir
    }

    /// The inputs at path parameter `s`.
    pub fn inputs_at(&self, s: f64) -> [f64; NI] {
        self.line.point(s)
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &'m M {
        self.m
    }

    /// The sweep configuration the samples were taken with (also used for every refinement).
    pub fn config(&self) -> &SweepConfig {
        &self.cfg
    }

    /// The samples of a column as jets in the path parameter.
    pub fn jets(&self, c: Column<M>) -> Result<Vec<Jet>, Error> {
        let c = c.check::<N, NI, NO>()?;
        Ok(self.states.iter().zip(&self.s).map(|(k, &s)| c.jet_along(k, s, &self.line.dir)).collect())
    }

    /// A column's jet at any path parameter `s` of the range, on the sweep's branch.
    pub fn jet_at(&self, c: Column<M>, s: f64) -> Result<Jet, Error> {
        let c = c.check::<N, NI, NO>()?;
        self.at(s).map(|k| c.jet_along(&k, s, &self.line.dir))
    }

    /// The state at any path parameter `s` of the range (the input for one input), on the
    /// sweep's branch.
    pub fn at(&self, s: f64) -> Result<Kin<N, NI, NO>, Error> {
        let (first, last) = (self.s[0], self.s[self.s.len() - 1]);
        let slack = 1e-9 * (last - first);
        if !(s >= first - slack && s <= last + slack) {
            return Err(Error::InvalidArgument(format!("{s} lies outside the sampled range [{first}, {last}]")));
        }
        // The nearest sample.
        let i = self.s.partition_point(|&v| v < s);
        let j = match (i.checked_sub(1), self.s.get(i)) {
            (Some(j), Some(&v)) if (s - self.s[j]).abs() <= (v - s).abs() => j,
            (_, Some(_)) => i,
            (Some(j), None) => j,
            (None, None) => unreachable!("a Sampled holds at least three states"),
        };
        let near = &self.states[j];
        let x = self.line.point(s);
        // The sample itself (its parameter may differ from `s` in the last bit).
        if self.s[j] == s || near.x == x {
            return Ok(*near);
        }
        let mut step = Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(self.m, near.x, x, 2, near.q)?.with_config(self.cfg);
        let _start = step.next_kin().transpose()?;
        step.next_kin().unwrap_or_else(|| Err(Error::InvalidArgument("empty refinement sweep".into())))
    }

    fn eval(&self, c: Column<M>) -> impl FnMut(f64) -> Result<Jet, Error> + '_ {
        move |s| self.jet_at(c, s)
    }

    /// The local extremes of a column (interior roots of its derivative along the path), in
    /// increasing path parameter; see [`extremes()`](extremes::extremes).
    pub fn extremes(&self, c: Column<M>) -> Result<Vec<LocalExtreme>, Error> {
        extremes::extremes(&self.jets(c)?, self.eval(c))
    }

    /// The global minimum and maximum of a column over the range (interior extremes or ends),
    /// e.g. the dead centres and stroke of a slider; see [`global_range`].
    pub fn range(&self, c: Column<M>) -> Result<GlobalRange, Error> {
        global_range(&self.jets(c)?, self.eval(c))
    }

    /// The dwells of a progressive column; see [`dwell`] for the definition.
    pub fn dwells(&self, c: Column<M>) -> Result<Vec<Dwell>, Error> {
        dwell::dwells(&self.jets(c)?, self.eval(c))
    }

    /// The maximum of a derived quantity `f(state)` (e.g. the magnitude of an acceleration
    /// analog) over the range: the best sample, refined by Brent's derivative-free search
    /// between its neighbours. Returns `(s, f)`. For a minimum, maximise `-f`.
    pub fn peak(&self, f: impl Fn(&Kin<N, NI, NO>) -> f64) -> Result<(f64, f64), Error> {
        self.peak_by(|_, k| f(k))
    }

    /// The maximum of a function of a column's jet along the path (e.g. `|j| j.d2.abs()`, the
    /// largest acceleration analog), located as by [`Sampled::peak`]. Returns `(s, f)`.
    pub fn peak_of(&self, c: Column<M>, f: impl Fn(Jet) -> f64) -> Result<(f64, f64), Error> {
        let c = c.check::<N, NI, NO>()?;
        self.peak_by(|s, k| f(c.jet_along(k, s, &self.line.dir)))
    }

    fn peak_by(&self, f: impl Fn(f64, &Kin<N, NI, NO>) -> f64) -> Result<(f64, f64), Error> {
        let values: Vec<f64> = self.states.iter().zip(&self.s).map(|(k, &s)| f(s, k)).collect();
        let best = (0..values.len()).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap_or(0);
        let lo = self.s[best.saturating_sub(1)];
        let hi = self.s[(best + 1).min(self.s.len() - 1)];
        let (s, v) = maximize(lo, hi, |s| self.at(s).map(|k| f(s, &k)))?;
        // Brent returns an interior point; the sample itself may be better (at an end of the range).
        Ok(if v >= values[best] { (s, v) } else { (self.s[best], values[best]) })
    }

    /// Checks that a column returns to its starting value over the range (one period).
    fn periodic(&self, c: Column<M>) -> Result<Vec<Jet>, Error> {
        let jets = self.jets(c)?;
        let (a, b) = (jets[0].value, jets[jets.len() - 1].value);
        let scale = jets.iter().map(|j| j.value.abs()).fold(1.0, f64::max);
        if (a - b).abs() > 1e-9 * scale {
            return Err(Error::InvalidArgument(format!(
                "`{}` is not periodic over the sweep ({a} at the start, {b} at the end): sweep exactly one cycle",
                c.name()
            )));
        }
        Ok(jets)
    }

    /// Fourier coefficients of a column up to `harmonics`, the sweep being one period (`n + 1`
    /// samples, the last repeating the first); see [`fourier()`](fourier::fourier).
    pub fn fourier(&self, c: Column<M>, harmonics: usize) -> Result<Fourier, Error> {
        let jets = self.periodic(c)?;
        let n = jets.len() - 1;
        let values: Vec<f64> = jets[..n].iter().map(|j| j.value).collect();
        fourier::fourier(&values, jets[0].x, jets[n].x - jets[0].x, harmonics)
    }

    /// The residual of a column after removing its mean and harmonics `1 ..= removed`, and its
    /// largest magnitude over the period (the residual unbalance `D` for `removed = 1`); see
    /// [`unbalance()`](unbalance::unbalance).
    pub fn unbalance(&self, c: Column<M>, removed: usize) -> Result<Unbalance, Error> {
        let jets = self.periodic(c)?;
        unbalance::unbalance(&jets, self.eval(c), removed)
    }
}
