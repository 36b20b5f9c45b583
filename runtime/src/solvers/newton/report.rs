//! What a solve gives, apart from the iteration itself: a solved block ([`Solved`]) or why it
//! failed ([`BlockFailure`]), and the diagnostics of a position solve ([`SolveReport`]), with why
//! it stopped ([`NewtonStop`]).

/// A converged block. Its evaluation is the caller's (see [`newton`]): at `z`, or (after a
/// correction at the rounding level, applied without a new evaluation) at a point within a few
/// rounding units of `z`.
///
/// [`newton`]: super::newton
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Solved<const N: usize> {
    pub z: [f64; N],
    pub iterations: u32,
    pub evaluations: u32,
    pub residual: f64,
    pub termination: NewtonStop,
}

/// Why a block failed; the generated code adds the location and names.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BlockFailure {
    /// A residual or Jacobian entry is not finite; `row` is the block row.
    NonFinite { row: usize, iterations: u32 },
    /// The iteration cap was reached while the residual still decreased.
    NoConvergence { row: usize, iterations: u32, residual: f64 },
    /// The iteration stalled at a stationary point of the squared residual that is not a root
    /// (no descent direction, scaled residual clearly non-zero): the loops cannot close there.
    /// `evaluations` counts the block's evaluations (restarts after it add theirs).
    NoAssembly { row: usize, iterations: u32, evaluations: u32, residual: f64 },
    /// The Jacobian is singular at (or the iteration converged only linearly to) a root: a
    /// singular position, where the solution is not determined to working accuracy.
    Singular { row: usize, iterations: u32, residual: f64, pivot_ratio: f64, tolerance: f64 },
    /// A configuration field is out of range (see [`NewtonConfig::invalid_field`]).
    ///
    /// [`NewtonConfig::invalid_field`]: super::NewtonConfig::invalid_field
    InvalidConfig { field: &'static str },
    /// A closed form's angle is `value`, on its guess's turn so many turns out that the spacing
    /// of doubles there exceeds what the tolerance accepts (see
    /// [`largest_precise_angle`](crate::solvers::closed::largest_precise_angle)). The generated
    /// code names the angle by its guess; it also reports Newton's failure from such a guess as
    /// this (see `block_failure`).
    TooManyTurns { value: f64 },
    /// Row `row`'s magnitude (`magnitude`, the block's given one where the solve ended) is
    /// below `least`, the smallest whose residual can be judged to the tolerance, or
    /// underflowed to zero where the row's terms do not vanish (see `scales::unjudged`).
    Underflow { row: usize, magnitude: f64, least: f64 },
    /// Row `row`'s terms are too large for `f64`: its magnitude overflowed to infinity, with a
    /// residual that is finite, or a Jacobian entry times its unknown that overflows (see
    /// `scales::overflowed`).
    Overflow { row: usize },
    /// Every term of row `row` is zero and so is its derivative by every unknown: its magnitude
    /// (the sum of its lengths) is exactly zero, not underflowed. The equation holds at every
    /// position and determines none: a loop whose lengths are all zero (parameters left unset).
    /// Told from a singular position, whose equations vanish at one position only, where the
    /// magnitudes are found degenerate (see `scales::unjudged_row`) or a failed solve is
    /// diagnosed (see `vanished_row`).
    Vanished { row: usize },
}

/// Why a solve stopped successfully.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum NewtonStop {
    /// Every block was solved in closed form (linear blocks only).
    Direct,
    /// The scaled residual fell below `residual_tol`.
    ResidualTolerance,
    /// The scaled Newton step fell below `step_tol` (the residual is at its rounding floor).
    StepTolerance,
    /// The position was given by the caller, not solved (`kinematics_at`).
    Given,
}

/// Diagnostics of a position solve, summed over the blocks of the decomposition.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SolveReport {
    /// Newton iterations over all blocks (0 when the guess already satisfied the equations and
    /// only its correction was applied).
    pub iterations: u32,
    /// Residual evaluations over all blocks (including line-search trials).
    pub evaluations: u32,
    /// Largest scaled residual (`|f_i| / scale_i`) over the iterated blocks, before the last
    /// correction; for a given position (`kinematics_at`), the largest unscaled residual.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub residual: f64,
    /// The weakest reason any block stopped (`StepTolerance` over `ResidualTolerance` over
    /// `Direct`).
    pub termination: NewtonStop,
}

impl SolveReport {
    #[doc(hidden)]
    pub fn direct() -> Self {
        SolveReport { iterations: 0, evaluations: 0, residual: 0.0, termination: NewtonStop::Direct }
    }

    #[doc(hidden)]
    pub fn given(residual: f64) -> Self {
        SolveReport { iterations: 0, evaluations: 1, residual, termination: NewtonStop::Given }
    }

    /// The report of two solves as one (a mechanism's blocks solved in turn): their iterations
    /// and evaluations summed, the larger residual, the weaker stop.
    pub(crate) fn merge(&mut self, other: &SolveReport) {
        self.iterations += other.iterations;
        self.evaluations += other.evaluations;
        self.residual = self.residual.max(other.residual);
        self.termination = self.termination.max(other.termination);
    }

    #[doc(hidden)]
    #[inline]
    pub fn absorb<const N: usize>(&mut self, s: &Solved<N>) {
        self.iterations += s.iterations;
        self.evaluations += s.evaluations;
        self.residual = self.residual.max(s.residual);
        self.termination = self.termination.max(s.termination);
    }
}
