//! The report as a table (read back from its CSV by the `csv` crate, independently of the
//! runtime's reader), and the progress of a search.

use super::mechanisms::{Slider, slider_x};
use kinloop::synthesis::{Design, Problem, Search, SynthesisError, SynthesisReport, Task};
use std::cell::RefCell;
use std::sync::Mutex;

fn problem() -> Problem<Slider, 2, 1, 0, 3> {
    let p = [1.1, 3.4, 0.35];
    let task = Task::function("x", (0..5).map(|k| 0.5 * k as f64).map(|phi| (phi, slider_x(p, phi))));
    let design = Design::new().var("r", 0.5, 2.0).var("l", 2.0, 5.0).var("e", -1.0, 1.0);
    Problem::new(Slider::default(), &design, &task).unwrap()
}

#[test]
fn the_table_holds_every_candidate() {
    let report = Search::default().with_starts(0..8).run(&problem()).unwrap();
    let mut csv = Vec::new();
    report.table().unwrap().write_csv(&mut csv).unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_slice());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header, ["start", "valid", "r", "l", "e", "max_error", "rms_error", "min_transmission", "evaluations"]);
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), report.candidates.len());
    for (row, c) in rows.iter().zip(&report.candidates) {
        let v = |k: usize| row[k].parse::<f64>().unwrap();
        assert_eq!((v(0), v(1)), (c.start as f64, if c.is_valid() { 1.0 } else { 0.0 }));
        assert_eq!([v(2), v(3), v(4), v(5)], [c.values[0], c.values[1], c.values[2], c.max_error]);
        assert!(v(7).is_nan(), "no transmission angle was asked for");
    }
}

#[test]
fn progress_counts_every_start() {
    let problem = problem();
    let search = Search::default().with_starts(4..10);
    let seen = RefCell::new(Vec::new());
    search.run_with_progress(&problem, |done, total| seen.borrow_mut().push((done, total))).unwrap();
    assert_eq!(seen.into_inner(), (1..=6).map(|k| (k, 6)).collect::<Vec<_>>());
    let seen = Mutex::new(Vec::new());
    search.par_run_with_progress(&problem, |done, total| seen.lock().unwrap().push((done, total))).unwrap();
    let mut seen = seen.into_inner().unwrap();
    seen.sort();
    assert_eq!(seen, (1..=6).map(|k| (k, 6)).collect::<Vec<_>>());
}

/// A report of no candidate over the design variables `variables`.
fn report_of(variables: &[&str]) -> SynthesisReport {
    four_bar_report_of(variables, false)
}

/// A report of no candidate over `variables`, of a problem that names its four-bar's links
/// where `four_bar` is set.
fn four_bar_report_of(variables: &[&str], four_bar: bool) -> SynthesisReport {
    let names = variables.iter().map(|v| v.to_string()).collect();
    let mut report = SynthesisReport::new(names, vec![(0.0, 1.0); variables.len()]);
    report.four_bar = four_bar;
    report
}

/// A design variable named as a column of the table's own is refused, naming it: the table
/// named two columns alike, `column` finding the report's alone and `write_csv` refusing it.
/// A column present only for four-bars with named links (`grashof`) is a name like any other
/// where the problem names none, and refused where it names them, whether or not a candidate
/// was found: the table's columns, and whether it can be made, are the report's kind's alone.
/// (Before, `grashof` was accepted for a four-bar problem of no candidate, or none that moves.)
#[test]
fn a_design_variable_named_as_a_column_of_the_table_is_refused() {
    for name in ["start", "valid", "max_error", "rms_error", "min_transmission", "evaluations"] {
        let e = report_of(&["r", name]).table().unwrap_err();
        assert_eq!(e, SynthesisError::ReportColumn { name: name.to_string() });
        assert!(e.to_string().contains(&format!("the design variable `{name}`")), "{e}");
    }
    let table = report_of(&["r", "grashof"]).table().unwrap();
    assert_eq!(table.columns[..4], ["start", "valid", "r", "grashof"]);
    for name in ["grashof", "grashof_margin", "min_transmission_range"] {
        let e = four_bar_report_of(&["r", name], true).table().unwrap_err();
        assert_eq!(e, SynthesisError::ReportColumn { name: name.to_string() });
    }
    let table = four_bar_report_of(&["r"], true).table().unwrap();
    let columns = [
        "start",
        "valid",
        "r",
        "max_error",
        "rms_error",
        "min_transmission",
        "evaluations",
        "grashof",
        "grashof_margin",
        "min_transmission_range",
    ];
    assert_eq!(table.columns, columns);
}
