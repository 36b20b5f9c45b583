//! The seeds and starts a search refused before their local solve (the design cannot be
//! assembled at a target, or its angle parameter is too large to resolve), counted by the kind
//! of error that refused them, each kind with its first design and the error's message: what
//! [`Search::refine`](super::Search::refine) from that start would say, without running it.

use super::candidate::Origin;
use crate::error::Error;
use std::fmt;

/// The kind of error that refused a design before its local solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum RefusalKind {
    /// The design cannot be assembled at a target ([`Error::NoAssembly`]).
    NoAssembly,
    /// A position solve did not converge ([`Error::NoConvergence`]).
    NoConvergence,
    /// A target's position is singular ([`Error::Singular`]): a dead centre or a limit position.
    Singular,
    /// An argument out of its range ([`Error::InvalidArgument`]): an angle parameter too large
    /// to resolve, beyond the problem's
    /// [`largest_precise_angle`](crate::solvers::newton::NewtonConfig::largest_precise_angle).
    InvalidArgument,
    /// A value that is not finite: an expression outside its domain, an overflow or an
    /// underflow ([`Error::Domain`], [`Error::Overflow`], [`Error::Underflow`],
    /// [`Error::NonFinite`]), or residuals that are NaN.
    NotFinite,
    /// Any other error.
    Other,
}

impl RefusalKind {
    /// The kind of `error`.
    pub fn of(error: &Error) -> RefusalKind {
        match error {
            Error::NoAssembly { .. } => RefusalKind::NoAssembly,
            Error::NoConvergence { .. } => RefusalKind::NoConvergence,
            Error::Singular { .. } => RefusalKind::Singular,
            Error::InvalidArgument(_) => RefusalKind::InvalidArgument,
            Error::NonFinite { .. } | Error::Domain { .. } | Error::Overflow { .. } | Error::Underflow { .. } => {
                RefusalKind::NotFinite
            }
            _ => RefusalKind::Other,
        }
    }

    /// The kind in a few words, as the report's [`Display`](fmt::Display) writes it.
    pub fn describe(self) -> &'static str {
        match self {
            RefusalKind::NoAssembly => "cannot be assembled",
            RefusalKind::NoConvergence => "position solve did not converge",
            RefusalKind::Singular => "singular position",
            RefusalKind::InvalidArgument => "argument out of range",
            RefusalKind::NotFinite => "not finite",
            RefusalKind::Other => "other error",
        }
    }
}

/// The seeds and starts of one [`RefusalKind`] a search refused before their local solve: how
/// many, and the first of them (seeds before starts, each by index) with its design and the
/// error's message.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Refused {
    /// The kind of error.
    pub kind: RefusalKind,
    /// How many seeds and starts (with differential evolution, members to polish) it refused.
    pub count: usize,
    /// What kind of start the first one refused was.
    pub origin: Origin,
    /// Its index (the seed's, the Halton start's, the island's).
    pub start: usize,
    /// Where its local solve would have started: the search's unknowns (see
    /// [`ProblemOf`](super::ProblemOf)), its design variables first, in the report's order;
    /// [`Search::refine`](super::Search::refine) from it gives the error again.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub point: Vec<f64>,
    /// The error's message.
    pub message: String,
}

impl Refused {
    /// One design refused by `error`.
    pub(crate) fn one(error: &Error, origin: Origin, start: usize, point: Vec<f64>) -> Refused {
        Refused { kind: RefusalKind::of(error), count: 1, origin, start, point, message: error.to_string() }
    }

    /// Adds `r` to `all` (one entry per kind, in the order of [`RefusalKind`]): its count to
    /// its kind's, and its example where it comes first (seeds before Halton starts, each by
    /// index), so that the parts of a split search add up to the whole's.
    pub(crate) fn add(all: &mut Vec<Refused>, r: Refused) {
        match all.binary_search_by(|e| e.kind.cmp(&r.kind)) {
            Ok(k) => {
                let e = &mut all[k];
                let count = e.count + r.count;
                if (r.origin, r.start) < (e.origin, e.start) {
                    *e = r;
                }
                e.count = count;
            }
            Err(k) => all.insert(k, r),
        }
    }
}

impl fmt::Display for Refused {
    /// One line: the count and kind, the first design refused and the error's message.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let origin = match self.origin {
            Origin::Seed => "seed",
            Origin::Halton => "start",
            Origin::Evolution => "island",
            Origin::Refine => "refinement",
        };
        write!(f, "{} refused ({}), first {origin} {} at [", self.count, self.kind.describe(), self.start)?;
        for (k, v) in self.point.iter().enumerate() {
            write!(f, "{}{}", if k > 0 { ", " } else { "" }, crate::number::Number(*v))?;
        }
        write!(f, "]: {}", self.message)
    }
}
