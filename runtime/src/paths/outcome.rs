//! A whole sweep's results with the reason it stopped and where ([`SweepResult`], [`SweepStop`]).

use crate::error::Error;
use crate::events::{Event, EventKind};

/// Why a sweep ended.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SweepStop {
    /// Every sample was computed.
    Completed,
    /// A limit position (the input cannot advance on this assembly mode), located precisely:
    /// [`Event::x`] is the input where it happens, [`Event::q`] the position there.
    LimitPosition(Event),
    /// A singular crossing (a change point where branches meet) that the sweep was configured
    /// to stop at ([`AtSingular::Stop`](crate::AtSingular::Stop)), located precisely.
    SingularCrossing(Event),
    /// Another error: invalid arguments, no assembly at the first input, a branch that cannot
    /// be followed, no convergence.
    Failed(Error),
}

impl SweepStop {
    /// The stop for the error `e` that ended a sweep, whose last recorded event is `last`.
    pub(crate) fn from_error(e: &Error, last: Option<&Event>) -> Self {
        match (e, last) {
            (Error::SweepStopped { kind: EventKind::LimitPosition, .. }, Some(ev)) => {
                SweepStop::LimitPosition(ev.clone())
            }
            (Error::SweepStopped { kind: EventKind::SingularCrossing, .. }, Some(ev)) => {
                SweepStop::SingularCrossing(ev.clone())
            }
            _ => SweepStop::Failed(e.clone()),
        }
    }

    /// Whether every sample was computed.
    pub fn is_completed(&self) -> bool {
        matches!(self, SweepStop::Completed)
    }

    /// The event that stopped the sweep (a limit position or a singular crossing).
    pub fn event(&self) -> Option<&Event> {
        match self {
            SweepStop::LimitPosition(ev) | SweepStop::SingularCrossing(ev) => Some(ev),
            _ => None,
        }
    }
}

/// The states of a whole sweep, why it ended, and the singular positions it met.
///
/// Unlike collecting the iterator into a `Result<Vec<_>, _>`, the states computed before a stop
/// are kept: a sweep of a rocker that meets its limit position returns the samples up to it and
/// the located limit position.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SweepResult<S> {
    /// The samples computed, in order (up to the stop).
    pub states: Vec<S>,
    /// Why the sweep ended.
    pub stop: SweepStop,
    /// Every singular position met, in order (also the crossings passed with
    /// [`AtSingular::Continue`](crate::AtSingular::Continue), which do not stop a sweep).
    pub events: Vec<Event>,
    /// The error that stopped the sweep, for [`SweepResult::into_result`].
    error: Option<Error>,
}

impl<S> SweepResult<S> {
    /// A result from its parts; `error` is what stopped the sweep (`None`: completed).
    pub(crate) fn new(states: Vec<S>, error: Option<Error>, events: Vec<Event>) -> Self {
        let stop = match &error {
            None => SweepStop::Completed,
            Some(e) => SweepStop::from_error(e, events.last()),
        };
        SweepResult { states, stop, events, error }
    }

    /// Whether every sample was computed.
    pub fn is_completed(&self) -> bool {
        self.stop.is_completed()
    }

    /// The states if every sample was computed, otherwise the error that stopped the sweep
    /// (for `?`; [`Error::SweepStopped`] names the input of a limit position).
    pub fn into_result(self) -> Result<Vec<S>, Error> {
        match self.error {
            None => Ok(self.states),
            Some(e) => Err(e),
        }
    }

    /// The states converted, with the same stop and events.
    pub(crate) fn map<T>(self, f: impl FnMut(S) -> T) -> SweepResult<T> {
        SweepResult {
            states: self.states.into_iter().map(f).collect(),
            stop: self.stop,
            events: self.events,
            error: self.error,
        }
    }
}
