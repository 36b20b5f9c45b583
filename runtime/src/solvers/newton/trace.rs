//! Which paths of the solver a solve took, recorded in the unit tests only: the tests of the
//! returned evaluation (`returned_evaluation`) check with it that each drives the path it is
//! about. Outside the tests [`note`] is empty and inlined away.

/// A path of the solver that decides which evaluation a solve returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum SolvePath {
    /// A correction at the rounding level applied without evaluating (at the guess or at the
    /// end of an iteration): the one position returned that is not the last evaluated.
    UncheckedCorrection,
    /// A final correction evaluated and kept.
    CorrectionKept,
    /// A final correction evaluated and undone: the iterate evaluated again.
    CorrectionUndone,
    /// A full Newton step accepted.
    FullStep,
    /// A backtracking search accepted a trial.
    SearchAccepted,
    /// A rejected full step whose search failed: the iterate evaluated again.
    Reevaluated,
    /// The descent entered.
    Descend,
    /// A failed search of the descent: the iterate's evaluation copied back.
    CopyBack,
    /// An iteration continued past the tolerance, reached linearly at a regular Jacobian.
    PastTolerance,
    /// No step decreased a residual at its rounding floor: the iterate returned as it is.
    AtFloor,
    /// Angles moved back to the guess's turns and evaluated there.
    TurnsMoved,
    /// The move to the guess's turns undone: the iterate evaluated again.
    TurnsUndone,
    /// A restart's iteration (from a quarter or half turn of one angle).
    Restart,
    /// The solve from the restarts' nearest root on the guess's turns.
    RestartReturned,
}

#[cfg(test)]
std::thread_local! {
    static TAKEN: core::cell::RefCell<Vec<SolvePath>> = const { core::cell::RefCell::new(Vec::new()) };
}

/// Records that the solve took `path` (in the unit tests; nothing otherwise).
#[inline(always)]
pub(super) fn note(path: SolvePath) {
    #[cfg(test)]
    TAKEN.with(|t| t.borrow_mut().push(path));
    #[cfg(not(test))]
    let _ = path;
}

/// The paths recorded on this thread since the last call, in order.
#[cfg(test)]
pub(super) fn take() -> Vec<SolvePath> {
    TAKEN.with(|t| core::mem::take(&mut *t.borrow_mut()))
}
