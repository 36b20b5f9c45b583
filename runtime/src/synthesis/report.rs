//! The report of a search: the best distinct candidates, ranked, and what happened to the
//! other starts; merged across parts of a split search; as a table for CSV.

use super::SynthesisError;
use super::candidate::{Candidate, Defect};
use super::refusal::Refused;
use crate::metrics::GrashofClass;
use crate::table::Table;
use std::ops::Range;

/// The outcome of a search: the best candidates and what happened to the others.
///
/// With the feature `serde` it reads back exactly, non-finite numbers too (a zero-length
/// link's infinite [`Defect::LinkRatio`], a NaN [`Defect::Miss`]): JSON has neither, and a
/// self-describing format gets them as the strings `"inf"`, `"-inf"`, `"NaN"`, where `null`
/// would be `None` in an optional field. `null` for a number that is not optional reads as NaN.
///
/// Fields may be added in any version: outside this crate a report is made with
/// [`SynthesisReport::new`] and its fields set, not with a struct literal, which would break
/// with the next field:
///
/// ```compile_fail,E0639
/// use kinloop_runtime::synthesis::{Rejections, SynthesisReport};
/// let report = SynthesisReport {
///     variables: Vec::new(),
///     bounds: Vec::new(),
///     candidates: Vec::new(),
///     starts: 0..0,
///     seeds: 0,
///     unassembled: 0,
///     refused: Vec::new(),
///     converged: 0,
///     step_tolerance: 0,
///     valid: 0,
///     rejected: Rejections::default(),
///     evaluations: 0,
///     four_bar: false,
/// };
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct SynthesisReport {
    /// The design variables' names, the order of [`Candidate::values`].
    pub variables: Vec<String>,
    /// Their bounds, in the same order.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub bounds: Vec<(f64, f64)>,
    /// The best distinct candidates: valid ones (no defect) first, each group by increasing
    /// RMS error, ties by origin (seeds, then Halton starts, then islands) and then by index.
    pub candidates: Vec<Candidate>,
    /// The starts run (Halton indices, or with differential evolution islands).
    pub starts: Range<usize>,
    /// The seeds run ([`Search::seeds`](super::Search::seeds); with the part of a split search whose starts begin
    /// at `0`).
    pub seeds: usize,
    /// Seeds and starts (with differential evolution: members to polish) at which the design
    /// cannot be assembled at every target (no local solve), or whose angle parameter is too
    /// large to resolve (beyond the problem's `largest_precise_angle`: the error
    /// [`Search::refine`](super::Search::refine) from that start gives). With the local solves
    /// that ran, they count every seed and start (or `polish` per island). By kind:
    /// [`SynthesisReport::refused`].
    pub unassembled: usize,
    /// The [`unassembled`](SynthesisReport::unassembled) by the kind of error that refused
    /// them, one entry per kind met in the order of [`RefusalKind`](super::RefusalKind), each
    /// with its count (they add up to `unassembled`) and its first design and message. (Read
    /// from JSON without it: none.)
    #[cfg_attr(feature = "serde", serde(default))]
    pub refused: Vec<Refused>,
    /// Local solves whose residual met its tolerance ([`LocalConfig::tol`](super::LocalConfig::tol):
    /// [`OptimizerStop::Converged`](crate::analysis::OptimizerStop::Converged)), as a design
    /// that meets its targets exactly does.
    pub converged: usize,
    /// Local solves that stopped on the step tolerance first
    /// ([`LocalConfig::step_tol`](super::LocalConfig::step_tol):
    /// [`OptimizerStop::StepTolerance`](crate::analysis::OptimizerStop::StepTolerance)): the
    /// design moved no further, usually at a local minimum of non-zero residual (a
    /// least-squares fit of more targets than the design can meet stops so: a usable result,
    /// judged by its errors and defects). (Read from JSON without it: none.)
    #[cfg_attr(feature = "serde", serde(default))]
    pub step_tolerance: usize,
    /// Local solves whose result is valid (no defect).
    pub valid: usize,
    /// Candidates rejected, counted by their first defect.
    pub rejected: Rejections,
    /// Evaluations of residuals and Jacobian over all seeds and starts (with differential
    /// evolution, its populations' too).
    pub evaluations: usize,
    /// Whether the problem names the four links of a four-bar
    /// ([`Constraints::with_four_bar`](super::Constraints::with_four_bar)): its
    /// [`table`](SynthesisReport::table) has the four-bar's columns, whatever candidates were
    /// found. (Read from JSON without it: `false`.)
    #[cfg_attr(feature = "serde", serde(default))]
    pub four_bar: bool,
}

impl SynthesisReport {
    /// A report of no search yet over the design variables `variables`, with their `bounds` in
    /// the same order: no candidate, no start, every count zero, no four-bar. Its fields are
    /// public to set (a report assembled by hand, a test):
    ///
    /// ```
    /// use kinloop_runtime::synthesis::SynthesisReport;
    /// let mut report = SynthesisReport::new(vec!["r".into()], vec![(0.5, 2.0)]);
    /// report.four_bar = true;
    /// assert_eq!((report.candidates.len(), report.starts.len(), report.evaluations), (0, 0, 0));
    /// assert!(report.best().is_none());
    /// ```
    pub fn new(variables: Vec<String>, bounds: Vec<(f64, f64)>) -> Self {
        SynthesisReport {
            variables,
            bounds,
            candidates: Vec::new(),
            starts: 0..0,
            seeds: 0,
            unassembled: 0,
            refused: Vec::new(),
            converged: 0,
            step_tolerance: 0,
            valid: 0,
            rejected: Rejections::default(),
            evaluations: 0,
            four_bar: false,
        }
    }

    /// The best valid candidate, if any.
    pub fn best(&self) -> Option<&Candidate> {
        self.candidates.first().filter(|c| c.is_valid())
    }
}

/// How many candidates of a search were rejected, by their first [`Defect`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Rejections {
    /// [`Defect::Order`].
    pub order: usize,
    /// [`Defect::Branch`].
    pub branch: usize,
    /// [`Defect::Circuit`].
    pub circuit: usize,
    /// [`Defect::NoAssembly`].
    pub no_assembly: usize,
    /// [`Defect::NoFullRotation`].
    pub full_rotation: usize,
    /// [`Defect::Transmission`].
    pub transmission: usize,
    /// [`Defect::LinkRatio`].
    pub link_ratio: usize,
    /// [`Defect::Miss`].
    pub miss: usize,
}

impl Rejections {
    /// Counts one candidate rejected by `defect`.
    pub(crate) fn count(&mut self, defect: &Defect) {
        *match defect {
            Defect::Order => &mut self.order,
            Defect::Branch { .. } => &mut self.branch,
            Defect::Circuit { .. } => &mut self.circuit,
            Defect::NoAssembly { .. } => &mut self.no_assembly,
            Defect::NoFullRotation => &mut self.full_rotation,
            Defect::Transmission { .. } => &mut self.transmission,
            Defect::LinkRatio { .. } => &mut self.link_ratio,
            Defect::Miss { .. } => &mut self.miss,
        } += 1;
    }

    /// Adds the counts of `other` (e.g. of another search's report).
    pub fn add(&mut self, other: &Rejections) {
        self.order += other.order;
        self.branch += other.branch;
        self.circuit += other.circuit;
        self.no_assembly += other.no_assembly;
        self.full_rotation += other.full_rotation;
        self.transmission += other.transmission;
        self.link_ratio += other.link_ratio;
        self.miss += other.miss;
    }

    /// All rejected candidates.
    pub fn total(&self) -> usize {
        self.order
            + self.branch
            + self.circuit
            + self.no_assembly
            + self.full_rotation
            + self.transmission
            + self.link_ratio
            + self.miss
    }
}

impl SynthesisReport {
    /// The candidates as a table, one row per candidate in rank order: `start`, `valid` (1 or 0),
    /// the design variables by name, `max_error`, `rms_error`, `min_transmission` (radians; NaN
    /// where not asked), `evaluations` (of its local solve); where the problem names the links
    /// of a four-bar ([`SynthesisReport::four_bar`]) also `grashof` (the class as a number: see
    /// [`grashof_code`]; NaN for a candidate that is no four-bar that moves), `grashof_margin`
    /// and `min_transmission_range` (radians, over the input's range). The columns, and whether
    /// the table can be made, depend on the report's kind and its variables, not on which
    /// candidates were found. Write it with [`Table::write_csv`] or [`Table::save_csv`].
    ///
    /// # Errors
    ///
    /// [`SynthesisError::ReportColumn`] where a design variable is named as one of those
    /// columns (a parameter `start`, or `grashof` of four-bars with named links): the table
    /// would name two columns alike, [`Table::column`] finding the report's alone, and
    /// [`Table::write_csv`] refuses it.
    ///
    /// ```
    /// use kinloop_runtime::synthesis::SynthesisReport;
    /// # fn show(report: &SynthesisReport) -> Result<(), Box<dyn std::error::Error>> {
    /// report.table()?.write_csv(std::io::stdout())?;
    /// # Ok(())
    /// # }
    /// ```
    pub fn table(&self) -> Result<Table, SynthesisError> {
        let four_bar = self.four_bar;
        let mut own = vec!["start", "valid", "max_error", "rms_error", "min_transmission", "evaluations"];
        if four_bar {
            own.extend(["grashof", "grashof_margin", "min_transmission_range"]);
        }
        if let Some(name) = self.variables.iter().find(|v| own.contains(&v.as_str())) {
            return Err(SynthesisError::ReportColumn { name: name.clone() });
        }
        let (first, rest) = own.split_at(2);
        let mut columns: Vec<String> = first.iter().map(|c| c.to_string()).collect();
        columns.extend(self.variables.iter().cloned());
        columns.extend(rest.iter().map(|c| c.to_string()));
        let mut t = Table::new(columns);
        for c in &self.candidates {
            let mut row = vec![c.start as f64, f64::from(u8::from(c.is_valid()))];
            row.extend(&c.values);
            row.extend([c.max_error, c.rms_error, c.min_transmission.unwrap_or(f64::NAN), c.local.evaluations as f64]);
            if four_bar {
                row.extend(
                    c.four_bar.map_or([f64::NAN; 3], |f| [grashof_code(f.class) as f64, f.margin, f.min_transmission]),
                );
            }
            t.push(row);
        }
        Ok(t)
    }
}

/// The number of a Grashof class in the `grashof` column of [`SynthesisReport::table`]:
/// 0 crank-rocker, 1 rocker-crank, 2 double-crank, 3 Grashof double-rocker, 4 change point,
/// 5 non-Grashof triple-rocker.
pub fn grashof_code(class: GrashofClass) -> u8 {
    match class {
        GrashofClass::CrankRocker => 0,
        GrashofClass::RockerCrank => 1,
        GrashofClass::DoubleCrank => 2,
        GrashofClass::DoubleRocker => 3,
        GrashofClass::ChangePoint => 4,
        GrashofClass::TripleRocker => 5,
    }
}

#[cfg(all(test, feature = "serde"))]
mod tests {
    use super::*;
    use crate::analysis::optimize::OptimizerStop;
    use crate::metrics::GrashofClass;
    use crate::synthesis::{FourBarClass, LocalReport, Origin};

    #[test]
    fn a_report_reads_back_from_json() {
        let local = LocalReport { evaluations: 7, iterations: 6, stop: OptimizerStop::Stalled, residual: 0.25 };
        let candidate = Candidate {
            start: 3,
            origin: Origin::Evolution,
            values: vec![1.0, 2.5],
            params: vec![1.0, 2.5, 3.0],
            inputs: vec![vec![0.1], vec![0.7]],
            placement: Some([0.5, -0.5, 0.1, 1.2]),
            positions: vec![vec![0.3, 1.1], vec![0.4, 1.3]],
            errors: vec![0.1, 0.2],
            max_error: 0.2,
            rms_error: 0.158,
            defects: vec![Defect::Circuit { target: 1, at: 2.36 }, Defect::Order],
            min_transmission: None,
            four_bar: Some(FourBarClass { class: GrashofClass::DoubleRocker, margin: -0.1, min_transmission: 0.0 }),
            local,
        };
        let report = SynthesisReport {
            variables: vec!["a".into(), "b".into()],
            bounds: vec![(0.5, 2.0), (1.0, 4.0)],
            candidates: vec![candidate],
            starts: 0..16,
            seeds: 1,
            unassembled: 2,
            refused: vec![crate::synthesis::Refused {
                kind: crate::synthesis::RefusalKind::InvalidArgument,
                count: 2,
                origin: Origin::Halton,
                start: 5,
                point: vec![1.0, 1e80],
                message: "the angle parameter `b` is too large".into(),
            }],
            converged: 10,
            step_tolerance: 3,
            valid: 0,
            rejected: Rejections { order: 1, circuit: 13, ..Rejections::default() },
            evaluations: 140,
            four_bar: true,
        };
        let json = serde_json::to_string(&report).unwrap();
        let back: SynthesisReport = serde_json::from_str(&json).unwrap();
        assert_eq!(back, report);
        assert!(json.contains("\"Stalled\"") && json.contains("\"DoubleRocker\""), "{json}");
        // A report written before the stops on the step were counted apart reads with none.
        let older = json.replace("\"step_tolerance\":3,", "");
        assert_ne!(older, json);
        let read: SynthesisReport = serde_json::from_str(&older).unwrap();
        assert_eq!((read.converged, read.step_tolerance), (10, 0));
    }
}
