//! Why a figure could not be made.

use super::{Axis, Kind};
use std::fmt;

/// Why a figure could not be made.
#[derive(Debug)]
#[non_exhaustive]
pub enum PlotError {
    /// No finite point to plot (in the figure, or in the named panel).
    Empty {
        /// The figure or panel.
        what: String,
    },
    /// A series of another quantity kind than its axis: put it on its own axis (a panel).
    MixedKinds {
        /// Name of the axis.
        axis: String,
        /// The axis's kind.
        expected: Box<Kind>,
        /// Label of the series.
        series: String,
        /// The series's kind.
        found: Box<Kind>,
    },
    /// An axis name holding a bracketed unit (`"amplitude [N], [Nm]"`): the title adds the
    /// unit of the axis's kind, so such a name either repeats it or claims units the axis does
    /// not hold (an axis mixing units).
    UnitInName {
        /// The axis's name.
        axis: String,
    },
    /// An x-y chart with equal scales needs the same kind (and unit) on both axes.
    UnequalAxes {
        /// Kind of the x axis.
        x: Kind,
        /// Kind of the y axis.
        y: Kind,
    },
    /// A table has no column of that name.
    MissingColumn {
        /// The name asked for.
        name: String,
        /// The table's columns.
        available: Vec<String>,
    },
    /// Writing the file (or creating its folder) failed.
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlotError::Empty { what } => write!(f, "nothing to plot in {what}: no point has finite coordinates"),
            PlotError::MixedKinds { axis, expected, series, found } => write!(
                f,
                "series `{series}` holds {found} but axis `{axis}` holds {expected}: \
                 an axis holds one quantity kind; give the series its own panel"
            ),
            PlotError::UnitInName { axis } => write!(
                f,
                "axis name `{axis}` holds a unit in brackets: name the quantity alone, the title adds \
                 the unit of its kind; quantities in different units go on separate panels"
            ),
            PlotError::UnequalAxes { x, y } => {
                write!(f, "an x-y chart draws both axes to one scale, so both must hold one kind (x: {x}, y: {y})")
            }
            PlotError::MissingColumn { name, available } => {
                write!(f, "no column `{name}` in the table (columns: {})", available.join(", "))
            }
            PlotError::Io { path, source } => write!(f, "cannot write `{}`: {source}", path.display()),
        }
    }
}

impl std::error::Error for PlotError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PlotError::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Into kinloop's one error type, so that code making charts and running analyses uses `?`
/// throughout: [`kinloop_runtime::Error::Figure`], from which `downcast_ref` gives this back.
impl From<PlotError> for kinloop_runtime::Error {
    fn from(e: PlotError) -> Self {
        kinloop_runtime::Error::Figure(kinloop_runtime::Source::new(e))
    }
}

impl Axis {
    /// Refuses a name with a bracketed unit in it ([`PlotError::UnitInName`]): the axis writes
    /// its unit itself. Beside the error it gives, so that the axes' vocabulary needs nothing of
    /// the errors.
    pub(crate) fn check(&self) -> Result<(), PlotError> {
        match self.name.find('[') {
            Some(open) if self.name[open..].contains(']') => Err(PlotError::UnitInName { axis: self.name.clone() }),
            _ => Ok(()),
        }
    }
}
