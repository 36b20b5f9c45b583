//! Dead centres and limit positions along a sweep, in one report.
//!
//! Two kinds of special positions matter to a designer:
//!
//! * **limit positions of the input** (the input cannot advance: a dead centre seen from the
//!   input, where a non-Grashof crank stops) and **singular crossings** (change points): the
//!   sweep's [`Event`]s, located by continuation;
//! * **limit positions of an output** (an extreme of a slider or rocker: a dead centre seen
//!   from the output, where the output cannot drive the input): the located extremes of the
//!   output's column.

use crate::analysis::column::column_name;
use crate::analysis::{Column, ColumnOf, LocalExtreme, SampledOf, check_sampled_memory};
use crate::dims::{Dims, KinState};
use crate::error::Error;
use crate::events::{Event, EventKind};
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, Kernel, KinOf, Q};
use crate::paths::config::{AtSingular, SweepConfig};
use crate::paths::sweep::SweepOf;
use std::fmt;

/// The located extremes (limit positions) of one output column.
#[derive(Clone, Debug, PartialEq)]
pub struct OutputLimits {
    /// The unknown or output column.
    pub column: String,
    /// Its interior extremes, in increasing input.
    pub extremes: Vec<LocalExtreme>,
}

/// Dead centres and limit positions of one sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct LimitReport {
    /// The input range actually swept, from `from`: to `to` when the sweep went through, to the
    /// located limit position of the input where one ended it. A sweep that stops for any other
    /// reason gives no report but its error (see [`Limits::run`]).
    pub reached: (f64, f64),
    /// Events of the sweep: a limit position of the input ends it; singular crossings are
    /// passed (and listed).
    pub events: Vec<Event>,
    /// Extremes of each requested column over the reached range.
    pub outputs: Vec<OutputLimits>,
}

impl LimitReport {
    /// The limit positions of the input (where the sweep could not advance).
    pub fn input_limits(&self) -> impl Iterator<Item = &Event> {
        self.events.iter().filter(|e| e.kind == EventKind::LimitPosition)
    }
}

impl fmt::Display for LimitReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let deg = |x: f64| x.to_degrees();
        writeln!(
            f,
            "swept input {:.4} .. {:.4} rad ({:.2} .. {:.2} deg)",
            self.reached.0,
            self.reached.1,
            deg(self.reached.0),
            deg(self.reached.1)
        )?;
        for e in &self.events {
            writeln!(f, "  {} of the input at {:.6} rad ({:.3} deg)", e.kind, e.x[0], deg(e.x[0]))?;
        }
        for o in &self.outputs {
            for e in &o.extremes {
                let kind = if e.kind == crate::analysis::Extreme::Max { "maximum" } else { "minimum" };
                writeln!(
                    f,
                    "  limit position of {}: {kind} {:.9e} at {:.6} rad ({:.3} deg)",
                    o.column,
                    e.value(),
                    e.x(),
                    deg(e.x())
                )?;
            }
        }
        Ok(())
    }
}

/// A search for the dead centres and limit positions of a single-input mechanism over a range
/// of its input, set up by name and run by [`Limits::run`]:
///
/// ```text
/// let report = Limits::new(&m, 0.0, TAU)      // the input range, either direction
///     .samples(361)                            // equally spaced inputs
///     .guess(m.guess(0.0))                     // the assembly mode at the start
///     .columns(&[FourBar::COL.gamma])          // outputs whose limit positions to locate
///     .run()?;
/// ```
///
/// Without a call to each setter: 361 samples (`samples`), the mechanism's declared guess at the
/// start (`guess`), no output columns (`columns`).
#[must_use = "a limit search does nothing until `run`"]
pub struct Limits<'a, M, const N: usize> {
    m: &'a M,
    from: f64,
    to: f64,
    samples: usize,
    guess: Option<[f64; N]>,
    columns: &'a [Column<M>],
}

/// The mechanism by its type, the range, the samples, the guess and the columns.
impl<M, const N: usize> fmt::Debug for Limits<'_, M, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Limits")
            .field("mechanism", &std::any::type_name::<M>())
            .field("from", &self.from)
            .field("to", &self.to)
            .field("samples", &self.samples)
            .field("guess", &self.guess)
            .field("columns", &self.columns)
            .finish()
    }
}

impl<'a, M, const N: usize> Limits<'a, M, N> {
    /// The limits of mechanism `m` over the input range from `from` to `to` (either direction).
    pub fn new<const NO: usize>(m: &'a M, from: f64, to: f64) -> Self
    where
        M: Mechanism<N, 1, NO>,
    {
        Limits { m, from, to, samples: 361, guess: None, columns: &[] }
    }

    /// Equally spaced inputs of the sweep (both ends included; from 2 to
    /// [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES), and with columns no more than their
    /// states fit in [`MAX_COLLECTED_BYTES`](crate::paths::collected::MAX_COLLECTED_BYTES), a
    /// few million; else [`Limits::run`] is an error).
    pub fn samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// The positions that choose the assembly mode at the start: the mechanism's named unknowns
    /// (`m.guess(from)`) or their array.
    pub fn guess(mut self, guess: impl Into<[f64; N]>) -> Self {
        self.guess = Some(guess.into());
        self
    }

    /// The unknown or output columns (`Name::COL.x_c`) whose extremes to locate over the range
    /// reached.
    pub fn columns(mut self, columns: &'a [Column<M>]) -> Self {
        self.columns = columns;
        self
    }

    /// Sweeps the range, passing singular crossings, and reports the input's limit positions and
    /// crossings (the sweep's events) and the located extremes of the columns over the range
    /// reached. A limit position of the input ends the range; it is reported, not an error.
    ///
    /// A limit position of the input ends the range reached there (the extremes are located up to
    /// it, whatever the samples: those between the last sample and the limit too). Errors: a
    /// start that cannot be assembled, a column outside the mechanism, samples whose states,
    /// kept to locate the columns' extremes, would exceed
    /// [`MAX_COLLECTED_BYTES`](crate::paths::collected::MAX_COLLECTED_BYTES) (before the sweep,
    /// `Error::InvalidArgument` with the numbers), and a sweep that stops
    /// before the end for another reason than a limit position of the input: its error (it
    /// passes within [`SweepConfig::singular_pivot`] of a singular position and finds neither
    /// a limit position nor a crossing there, `Error::NearSingular`; a crossing it cannot
    /// pass; a step that fails), with no report of the range before it.
    pub fn run<const NO: usize>(self) -> Result<LimitReport, Error>
    where
        M: Mechanism<N, 1, NO>,
    {
        self.m.check_param_angles(&self.m.solver_config().newton)?;
        let guess = self.guess.unwrap_or_else(|| self.m.guess_flat(&[self.from]));
        limits_of(Compiled(self.m), self.from, self.to, self.samples, guess, self.columns)
    }
}

/// The search behind [`Limits::run`], over any [`Kernel`] of one input (a
/// compiled mechanism's [`Compiled`], a run-time model's): sweeps from `guess` at `from` to
/// `to` (either direction) in `samples` equally spaced inputs, passing singular crossings, and
/// reports the input's limit positions and crossings and the located extremes of `columns`
/// (typed handles, names or indices, see [`ColumnOf`]) over the range reached. A column `k`
/// does not have is an error, even where the range reached is the start alone; so is a sweep
/// that stops for another reason than a limit position of the input (see [`Limits::run`]).
pub fn limits_of<K: Kernel, C: ColumnOf<K>>(
    k: K,
    from: f64,
    to: f64,
    samples: usize,
    guess: Q<K>,
    columns: &[C],
) -> Result<LimitReport, Error> {
    // The samples are swept, then the range reached sampled again in memory: a count beyond the
    // limit of the latter is refused before the former, which would sweep it for nothing.
    crate::analysis::check_sample_count("samples", samples).map_err(Error::InvalidArgument)?;
    // One sample is the start alone: the range would be neither swept nor searched.
    if samples < 2 {
        return Err(Error::InvalidArgument(format!(
            "a limit search over a range needs at least 2 samples (its ends); {samples} asked for"
        )));
    }
    let d = k.dims();
    let columns = columns
        .iter()
        .map(|&c| c.resolve(&k).map(|i| (i, column_name(&k, i).to_string())))
        .collect::<Result<Vec<_>, Error>>()?;
    if d.ni() != 1 {
        return Err(Error::InvalidArgument(format!("the limits of `{}` need one input (it has {})", k.name(), d.ni())));
    }
    // The columns' extremes are located over the range reached sampled again in memory, every
    // state kept: samples whose states would exceed the memory budget are refused before the
    // sweep, as the search the caller asked for (the sampled sweep refused them after the
    // sweep, in the words of an analysis the caller never called). At most `samples` are kept.
    if !columns.is_empty() {
        let what = "the limit search (its columns' extremes are located over every sample's state)";
        check_sampled_memory(&k, samples.max(3), what)?;
    }
    let input = |v: f64| {
        let mut x = d.x();
        x[0] = v;
        x
    };
    // The kernel's configuration (a `Configured` mechanism's), passing singular crossings.
    let cfg = SweepConfig { at_singular: AtSingular::Continue, ..k.solver_config() };
    let (mut last, mut last_q, mut count) = (from, guess.clone(), 0usize);
    let mut limit = None;
    let events = {
        let mut sweep =
            SweepOf::<&K, KinOf<K>>::over(&k, input(from), input(to), samples, guess.clone())?.with_config(cfg);
        while let Some(step) = sweep.next_ref() {
            match step {
                Ok(st) => {
                    last = st.x()[0];
                    if !columns.is_empty() {
                        last_q.as_mut().copy_from_slice(st.q());
                    }
                    count += 1;
                }
                Err(Error::SweepStopped { kind: EventKind::LimitPosition, .. }) => {
                    limit = sweep.events().last().map(|e| e.x[0]);
                    break;
                }
                Err(e) => return Err(e),
            }
        }
        sweep.events().to_vec()
    };
    // A limit position of the input ends the range there, not at the last sample before it:
    // the extremes between that sample and the limit are the motion's too (with few samples a
    // rocker's extreme there was missed, with many found: the report depended on the count).
    // The range sampled again stops a millionth of that last interval short of the limit, where
    // the positions still solve on the branch (at the limit the analogs are infinite); its last
    // state is reached from the last sample by a sweep, on the branch.
    let reached = limit.unwrap_or(last);
    let (end, end_q) = match limit {
        Some(x) if !columns.is_empty() => {
            let end = x - 1e-6 * (x - last);
            match SweepOf::<&K, KinOf<K>>::over(&k, input(last), input(end), 2, last_q.clone())
                .map(|s| s.with_config(cfg).run())
            {
                Ok(run) if run.is_completed() => {
                    let mut q = last_q.clone();
                    if let Some(st) = run.states.last() {
                        q.as_mut().copy_from_slice(st.q());
                    }
                    (end, q)
                }
                // Where even that fails, the range the sweep's samples reached.
                _ => (last, last_q),
            }
        }
        _ => (last, last_q),
    };
    let count = if end == last { count } else { count + 1 };
    // The samples over the reached range kept in memory to locate the extremes (at least three,
    // as a sampled range needs: the two reached and their midpoint). A range that is the start
    // alone has no interior extreme, and without columns there is nothing to locate. A range
    // swept downward is sampled upward from its far end (the state reached there the guess).
    let range = if count < 2 || columns.is_empty() {
        None
    } else if from < end {
        Some(SampledOf::input_with(k, input(from), input(end), count.max(3), guess, cfg)?)
    } else {
        Some(SampledOf::input_with(k, input(end), input(from), count.max(3), end_q, cfg)?)
    };
    let outputs = columns
        .into_iter()
        .map(|(c, column)| {
            let extremes = match &range {
                Some(range) => range.extremes(c)?,
                None => Vec::new(),
            };
            Ok(OutputLimits { column, extremes })
        })
        .collect::<Result<_, Error>>()?;
    Ok(LimitReport { reached: (from, reached), events, outputs })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::Extreme;
    use crate::analysis::demo::SliderCrank;
    use std::f64::consts::TAU;

    /// Samples whose states, kept to locate the columns' extremes, would exceed the memory
    /// budget are refused before the sweep, in the words of the limit search: they were swept
    /// (some seconds) and then refused by the sampled sweep the search keeps them in, an
    /// analysis the caller never called. Without columns nothing is kept, and the same count is
    /// swept: its guess, not a number, fails the first step.
    #[test]
    fn a_limit_search_beyond_the_memory_budget_is_refused_before_the_sweep_in_its_words() {
        use crate::analysis::sampled_bytes_each;
        use crate::paths::collected::MAX_COLLECTED_BYTES;
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let samples = MAX_COLLECTED_BYTES / sampled_bytes_each(&Compiled(&m)) + 1;
        let search = || Limits::new(&m, 0.0, 1e-3).samples(samples);
        let err = search().guess([3.9]).columns(&[SliderCrank::COL.x]).run().expect_err("refused");
        let msg = err.to_string();
        assert!(matches!(err, Error::InvalidArgument(_)), "{err:?}");
        let words = "the limit search (its columns' extremes are located over every sample's state) would keep";
        let words = format!("{words} {samples} states");
        assert!(msg.contains(&words) && msg.contains("fewer samples"), "{msg}");
        assert!(!msg.contains("sampled sweep") && !msg.contains("run()"), "{msg}");
        let err = search().guess([f64::NAN]).run().expect_err("a guess not a number");
        assert!(!err.to_string().contains("would keep"), "{err}");
    }

    /// A sample count beyond `analysis::MAX_SAMPLES` is refused before the sweep: the largest
    /// `usize` swept practically forever.
    #[test]
    fn absurd_sample_counts_are_refused() {
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        for samples in [crate::analysis::MAX_SAMPLES + 1, usize::MAX] {
            let r = Limits::new(&m, 0.0, TAU).samples(samples).guess([3.9]).run();
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("at most")), "{samples}: {r:?}");
        }
        // One sample, or none, searches nothing (one gave the start alone, no event, `Ok`).
        for samples in [0, 1] {
            let r = Limits::new(&m, 0.0, TAU).samples(samples).guess([3.9]).run();
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("at least 2")), "{samples}: {r:?}");
        }
    }

    #[test]
    fn dead_centres_of_a_slider_crank_against_the_collinear_triangles() {
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let r = Limits::new(&m, 0.3, 0.3 + TAU).samples(73).guess([3.9]).columns(&[SliderCrank::COL.x]).run().unwrap();
        assert!(r.events.is_empty());
        assert_eq!(r.reached, (0.3, 0.3 + TAU));
        let [(x_out, outer), (x_in, inner)] = m.dead_centres();
        let e = &r.outputs[0].extremes;
        assert_eq!(e.len(), 2, "{r}");
        // The inner dead centre's angle lies in (-pi, 0): one turn later in this range.
        assert_eq!(e[0].kind, Extreme::Min);
        assert!((e[0].x() - (x_in + TAU)).abs() < 1e-10 && (e[0].value() - inner).abs() < 1e-12, "{r}");
        assert!((e[1].x() - (x_out + TAU)).abs() < 1e-10 && (e[1].value() - outer).abs() < 1e-12, "{r}");
        assert!(r.to_string().contains("limit position of x: minimum"));
    }

    /// A start a hundredth of a radian from the input's limit, with samples a tenth apart: the
    /// limit (the rod stretched along the vertical, `sin phi = (e - l) / r`) is reported, alone
    /// (no kink beside it), and ends the range reached; the slider moves monotonically up to
    /// it, no extreme. A column outside the mechanism is still an error there.
    #[test]
    fn a_limit_before_the_second_sample_is_reported() {
        let m = SliderCrank { r: 1.0, l: 1.2, e: 0.5 };
        let limit = ((m.e - m.l) / m.r).asin();
        let from = limit + 0.01;
        let guess = [m.r * from.cos() + (m.l * m.l - (m.r * from.sin() - m.e).powi(2)).sqrt()];
        let r =
            Limits::new(&m, from, from - 1.0).samples(11).guess(guess).columns(&[SliderCrank::COL.x]).run().unwrap();
        assert_eq!(r.reached.0, from, "{r}");
        assert!((r.reached.1 - limit).abs() < 1e-12, "{r}");
        assert_eq!(r.events.len(), 1, "{r}");
        let limits: Vec<&Event> = r.input_limits().collect();
        assert_eq!(limits.len(), 1, "{r}");
        assert!((limits[0].x[0] - limit).abs() < 1e-12, "{r}");
        assert!(r.outputs[0].extremes.is_empty(), "{r}");
        let bad = Column::__generated(crate::analysis::ColumnIndex::Unknown(3), "bad");
        assert!(matches!(
            Limits::new(&m, from, from - 1.0).samples(11).guess(guess).columns(&[bad]).run(),
            Err(Error::InvalidArgument(_))
        ));
    }

    /// Beside a limit position the sweep records the limit alone, at every start and sample
    /// count: within 1e-13 of it the slider's equation changes over a step by less than the
    /// solver's tolerance, and its single unknown's pivot ratio is 1 whatever the position, so
    /// steps there passed for corners of the curve (two or three kinks before the limit, at 3
    /// and 11 samples from a start 0.01 to 0.05 before it).
    #[test]
    fn no_kink_is_recorded_beside_a_limit_position() {
        let m = SliderCrank { r: 1.0, l: 1.2, e: 0.5 };
        let limit = ((m.e - m.l) / m.r).asin();
        for off in [0.001, 0.01, 0.02, 0.05] {
            for samples in [3, 11, 101, 1001] {
                let from = limit + off;
                let guess = [m.r * from.cos() + (m.l * m.l - (m.r * from.sin() - m.e).powi(2)).sqrt()];
                let mut sweep =
                    crate::Sweep::<_, crate::Kin<1, 1, 1>, 1, 1, 1>::new(&m, [from], [from - 1.0], samples, guess)
                        .unwrap();
                while let Some(step) = sweep.next_ref() {
                    if step.is_err() {
                        break;
                    }
                }
                let events: Vec<_> = sweep.events().iter().map(|e| (e.kind, e.x[0])).collect();
                assert!(
                    events.len() == 1 && events[0].0 == EventKind::LimitPosition && (events[0].1 - limit).abs() < 1e-12,
                    "{off} from the limit, {samples} samples: {events:?}"
                );
            }
        }
    }

    /// The same dead centres found sweeping the input downward over one turn: the range is
    /// reported as swept (from the start down) and the extremes match the collinear triangles.
    #[test]
    fn dead_centres_found_sweeping_downward() {
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let r = Limits::new(&m, 0.3 + TAU, 0.3).samples(73).guess([3.9]).columns(&[SliderCrank::COL.x]).run().unwrap();
        assert!(r.events.is_empty(), "{r}");
        // The last sample is the start less 72 steps of TAU / 72: equal to 0.3 up to rounding.
        assert_eq!(r.reached.0, 0.3 + TAU);
        assert!((r.reached.1 - 0.3).abs() < 1e-12, "{r}");
        let [(x_out, outer), (x_in, inner)] = m.dead_centres();
        let e = &r.outputs[0].extremes;
        assert_eq!(e.len(), 2, "{r}");
        assert_eq!(e[0].kind, Extreme::Min);
        assert!((e[0].x() - (x_in + TAU)).abs() < 1e-10 && (e[0].value() - inner).abs() < 1e-12, "{r}");
        assert!((e[1].x() - (x_out + TAU)).abs() < 1e-10 && (e[1].value() - outer).abs() < 1e-12, "{r}");
        // Without columns a downward range is reported too.
        let r = Limits::new(&m, 1.0, 0.0).samples(11).guess([3.9]).run().unwrap();
        assert_eq!(r.reached.0, 1.0);
        assert!(r.reached.1.abs() < 1e-12, "{r}");
        assert!(r.outputs.is_empty());
    }

    #[test]
    fn a_column_outside_the_mechanism_is_an_error() {
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let bad = Column::__generated(crate::analysis::ColumnIndex::Unknown(3), "bad");
        assert!(matches!(
            Limits::new(&m, 0.0, 1.0).samples(5).guess([3.9]).columns(&[bad]).run(),
            Err(Error::InvalidArgument(_))
        ));
    }
}
