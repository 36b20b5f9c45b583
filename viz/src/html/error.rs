//! What can go wrong when writing an interactive page.

use crate::draw::DrawError;
use std::fmt;

/// Why an interactive page could not be written. The page never holds a NaN or an infinite
/// number: every non-finite value is one of these errors.
#[derive(Debug)]
#[non_exhaustive]
pub enum HtmlError {
    /// The drawing cannot be drawn over the motion (an unknown point, an empty motion, a
    /// non-finite coordinate, a bad style or canvas).
    Draw(DrawError),
    /// A readout names a column the mechanism does not have.
    UnknownColumn {
        /// The name asked for.
        name: String,
        /// The mechanism's inputs, unknowns and output columns.
        available: Vec<String>,
    },
    /// A value of the page (a readout, a coordinate) is NaN or infinite at one pose.
    NonFinite {
        /// Which value (`"readout gamma"`, `"point of item 2"`).
        what: String,
        /// Index of the pose in the motion (events count after the samples).
        pose: usize,
    },
    /// A setting outside its valid range (no frames, a non-positive duration, a label that
    /// cannot be written).
    InvalidSetting(String),
}

impl fmt::Display for HtmlError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            HtmlError::Draw(e) => write!(f, "cannot draw the mechanism: {e}"),
            HtmlError::UnknownColumn { name, available } => {
                write!(f, "no column `{name}`: the mechanism's columns are {}", available.join(", "))
            }
            HtmlError::NonFinite { what, pose } => write!(f, "{what} is not finite at pose {pose}"),
            HtmlError::InvalidSetting(s) => write!(f, "invalid page setting: {s}"),
        }
    }
}

impl std::error::Error for HtmlError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            HtmlError::Draw(e) => Some(e),
            _ => None,
        }
    }
}

impl From<DrawError> for HtmlError {
    fn from(e: DrawError) -> Self {
        HtmlError::Draw(e)
    }
}

/// Into kinloop's one error type (as [`DrawError`] does): a failed sweep is that sweep's
/// error again, anything else [`kinloop_runtime::Error::Figure`], from which `downcast_ref`
/// gives this back.
impl From<HtmlError> for kinloop_runtime::Error {
    fn from(e: HtmlError) -> Self {
        match e {
            HtmlError::Draw(d) => d.into(),
            other => kinloop_runtime::Error::Figure(kinloop_runtime::Source::new(other)),
        }
    }
}
