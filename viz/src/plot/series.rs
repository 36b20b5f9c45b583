//! What a chart draws: curves (series) and marked points, grouped on value axes (panels).

use super::{Axis, Kind, PlotError};
use kinloop_runtime::{ColumnKey, Table};

/// One curve: a label for the legend, the quantity kind of its values and its points `(x, y)`.
/// A point with a non-finite coordinate breaks the curve (a sweep that stopped, a gap).
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Kind of the `y` values (for an x-y chart, of both coordinates).
    pub kind: Kind,
    /// The points `(x, y)`.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A curve through `points`.
    pub fn new(label: &str, kind: Kind, points: Vec<(f64, f64)>) -> Series {
        Series { label: label.to_string(), kind, points }
    }

    /// A curve of the column `y` against the column `x` (e.g. an output against the input of
    /// a sweep); the shorter column sets the length.
    pub fn columns(label: &str, kind: Kind, x: &[f64], y: &[f64]) -> Series {
        Series::new(label, kind, x.iter().copied().zip(y.iter().copied()).collect())
    }

    /// A curve of column `y` against column `x` of a sweep's [`Table`], each a mechanism's typed
    /// column (`Name::COL.x`) or a name as in
    /// `Table::kin_columns`: `"phi"`, `"x"`, `"d(x)/d(phi)"`, `"p.x"`), labelled `y`.
    ///
    /// ```
    /// use kinloop_runtime::Table;
    /// use kinloop_viz::plot::{Kind, Series};
    /// let mut t = Table::new(vec!["phi".into(), "x".into()]);
    /// t.push(vec![0.0, 4.0]);
    /// t.push(vec![0.1, 3.9]);
    /// let s = Series::from_table(&t, "phi", "x", Kind::length("mm"))?;
    /// assert_eq!(s.points, [(0.0, 4.0), (0.1, 3.9)]);
    /// assert!(Series::from_table(&t, "phi", "y", Kind::length("mm")).is_err());
    /// # Ok::<(), kinloop_viz::plot::PlotError>(())
    /// ```
    pub fn from_table(table: &Table, x: impl ColumnKey, y: impl ColumnKey, kind: Kind) -> Result<Series, PlotError> {
        let (x, y) = (x.column_name(), y.column_name());
        let column = |name: &str| {
            table
                .column(name)
                .ok_or_else(|| PlotError::MissingColumn { name: name.to_string(), available: table.columns.clone() })
        };
        Ok(Series::columns(y, kind, &column(x)?, &column(y)?))
    }
}

/// A value axis with its curves and marked points (drawn as dots): one panel of a figure.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// The value axis.
    pub axis: Axis,
    /// The curves on it.
    pub series: Vec<Series>,
    /// Marked points `(x, y)`.
    pub marks: Vec<(f64, f64)>,
}

impl Panel {
    /// An empty panel with value axis `axis`.
    pub fn new(axis: Axis) -> Panel {
        Panel { axis, series: Vec::new(), marks: Vec::new() }
    }

    /// Adds a curve.
    pub fn with(mut self, series: Series) -> Panel {
        self.series.push(series);
        self
    }

    /// Adds marked points (extremes, events).
    pub fn with_marks(mut self, marks: impl IntoIterator<Item = (f64, f64)>) -> Panel {
        self.marks.extend(marks);
        self
    }

    /// One panel per quantity kind, in order of first appearance, each axis named after its
    /// kind (`"length [mm]"`), so that no axis mixes kinds.
    pub fn split_by_kind(series: Vec<Series>) -> Vec<Panel> {
        let mut panels: Vec<Panel> = Vec::new();
        for s in series {
            match panels.iter_mut().find(|p| p.axis.kind == s.kind) {
                Some(p) => p.series.push(s),
                None => panels.push(Panel::new(Axis::of(s.kind.clone())).with(s)),
            }
        }
        panels
    }

    /// Checks the axis' name and that every curve holds the axis' kind.
    pub(crate) fn check(&self) -> Result<(), PlotError> {
        self.axis.check()?;
        match self.series.iter().find(|s| s.kind != self.axis.kind) {
            Some(s) => Err(PlotError::MixedKinds {
                axis: self.axis.name.clone(),
                expected: Box::new(self.axis.kind.clone()),
                series: s.label.clone(),
                found: Box::new(s.kind.clone()),
            }),
            None => Ok(()),
        }
    }
}

/// The smallest and largest finite coordinates of `points`: `(x0, x1, y0, y1)`; `None` when no
/// point is finite.
pub(crate) fn bounds(points: impl Iterator<Item = (f64, f64)>) -> Option<(f64, f64, f64, f64)> {
    let mut b: Option<(f64, f64, f64, f64)> = None;
    for (x, y) in points.filter(|(x, y)| x.is_finite() && y.is_finite()) {
        b = Some(match b {
            None => (x, x, y, y),
            Some((x0, x1, y0, y1)) => (x0.min(x), x1.max(x), y0.min(y), y1.max(y)),
        });
    }
    b
}
