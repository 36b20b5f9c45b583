//! A candidate design: its values, how well it meets each target, what its verification found,
//! and what its local solve did.

use super::local::LocalReport;
use crate::metrics::GrashofClass;

/// Where a candidate's local solve started.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Origin {
    /// A point given with [`Search::with_seeds`](super::Search::with_seeds) (e.g. a classical
    /// closed-form design); [`Candidate::start`] is its index among the seeds.
    Seed,
    /// A point of the Halton sequence; [`Candidate::start`] is its index.
    Halton,
    /// One of the best members of a differential evolution; [`Candidate::start`] is its island.
    Evolution,
    /// The point given to [`Search::refine`](super::Search::refine).
    Refine,
}

/// A four-bar candidate's Grashof class and smallest transmission angle, from its four link
/// lengths (named by [`Constraints::with_four_bar`](super::Constraints::with_four_bar)) in closed form.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FourBarClass {
    /// The Grashof class ([`crate::metrics::grashof()`]), named from the input's point of view.
    pub class: GrashofClass,
    /// `(s + l) - (p + q)` over the sum of the four lengths: negative for a Grashof linkage,
    /// zero at a change point, positive for a triple rocker.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub margin: f64,
    /// The smallest transmission angle (radians, acute) over the input's whole range of motion:
    /// for an input that turns fully, the smaller at the two positions where the input lies
    /// along the ground line, `acos |b^2 + c^2 - (d -+ a)^2| / 2bc`; zero where the input only
    /// rocks (at its limit positions coupler and follower lie in line).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub min_transmission: f64,
}

/// Why a candidate is not a valid design, as its verification found.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Defect {
    /// The free inputs of the targets are not strictly monotone (for an angle input free over at
    /// least a turn: not in cyclic order within one turn either): the targets are not met in the
    /// given order along one motion within the inputs' range (an order defect).
    Order,
    /// The sweep from the previous target reaches target `target` on another assembly mode
    /// than the one the targets were met on, or passes a singular crossing (a change point)
    /// on the way: the design meets the target only by switching assembly mode (a branch
    /// defect).
    Branch {
        /// The first target not reached on the first target's assembly mode.
        target: usize,
    },
    /// The sweep from the previous target meets a limit position at input `at` before target
    /// `target`: the targets lie on different circuits, or the motion must reverse (a circuit
    /// defect).
    Circuit {
        /// The first target not reached.
        target: usize,
        /// The input value of the limit position (the first input).
        #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
        at: f64,
    },
    /// The mechanism cannot be moved from the previous target to target `target` (the sweep
    /// failed: no assembly, no convergence).
    NoAssembly {
        /// The first target not reached.
        target: usize,
    },
    /// The input does not turn fully on the candidate's assembly mode.
    NoFullRotation,
    /// The smallest transmission angle over the motion checked is below the bound.
    Transmission {
        /// The smallest transmission angle found (radians).
        #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
        min: f64,
    },
    /// Target `target` is met with an error above
    /// [`Constraints::max_error`](super::Constraints::max_error): the first such target.
    Miss {
        /// The first target missed by more than the bound.
        target: usize,
        /// Its error (see [`Candidate::errors`]).
        #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
        error: f64,
    },
    /// The longest of the bounded links is more than the bound times the shortest.
    LinkRatio {
        /// The ratio found.
        #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
        ratio: f64,
    },
}

/// Errors of a candidate: per target, the norm of its weighted residual components (a point's
/// distance from its target, an angle's difference modulo a turn).
///
/// With the feature `serde` it reads back exactly, non-finite numbers too (see
/// [`SynthesisReport`](super::SynthesisReport)).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Candidate {
    /// The index of the start it was found from (see [`Candidate::origin`]: the Halton index,
    /// the seed's index, the island's; `usize::MAX` for [`Search::refine`](super::Search::refine)).
    pub start: usize,
    /// What kind of start it was found from.
    pub origin: Origin,
    /// The design variables' values, in the problem's order.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub values: Vec<f64>,
    /// Every parameter of the mechanism, in declaration order.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub params: Vec<f64>,
    /// The input values at which the targets are met (the prescribed ones, or the solved free
    /// ones; free angles in cyclic order, over a range of at least a turn, unwrapped by whole
    /// turns into one monotone motion).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub inputs: Vec<Vec<f64>>,
    /// The placement `[dx, dy, angle, scale]`, where the task has one.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub placement: Option<[f64; 4]>,
    /// The position (unknowns) at each target.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub positions: Vec<Vec<f64>>,
    /// The error at each target.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub errors: Vec<f64>,
    /// The largest error.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub max_error: f64,
    /// The root mean square of the errors.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub rms_error: f64,
    /// What the verification found wrong (empty: a valid design).
    pub defects: Vec<Defect>,
    /// The smallest transmission angle over the motion checked (radians), where the
    /// constraints name the coupler and the follower.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub min_transmission: Option<f64>,
    /// Grashof class and smallest transmission angle over the input's range, where the
    /// constraints name the four links of a four-bar.
    pub four_bar: Option<FourBarClass>,
    /// What the local solve did.
    pub local: LocalReport,
}

impl Candidate {
    /// Whether the verification found no defect.
    pub fn is_valid(&self) -> bool {
        self.defects.is_empty()
    }
}
