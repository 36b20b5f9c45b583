//! What a search holds of each candidate until its report, and how the report ranks them and
//! drops duplicates.
//!
//! A candidate holds its inputs and positions at every target, its errors and its defects:
//! about 2 KB for a four-bar through eight points. A search holds every candidate until its
//! report, because which ones the report keeps depends on all of them (a duplicate is one near a
//! candidate ranked before it, and the best-ranked may come last). A large search of Halton
//! starts therefore holds of each start's candidate only what the ranking, the de-duplication
//! and the counts read ([`Key`]: its values, error, validity, first defect, evaluations), and
//! solves the starts the report keeps again for their whole candidates: a start depends on its
//! index alone, so the same start gives the same candidate, to the bit. Measured on the
//! README's search (a four-bar's two link lengths through eight points), `kinloop synth` with
//! 20,000 starts took 17 MB where it took 47 MB holding whole candidates, and 200,000 starts take
//! 88 MB (whole candidates, at 2 KB a start, would take about 400 MB).

use super::candidate::{Candidate, Defect, Origin};
use super::refusal::{RefusalKind, Refused};
use crate::analysis::optimize::OptimizerStop;

/// A search holds keys, not whole candidates, past this many Halton starts (and past 64
/// times its `keep`, so that the starts solved again stay a small part of the search's work).
pub(super) const KEYS_FROM: usize = 4096;

/// What ranking and de-duplication read of a candidate.
pub(super) trait Ranked {
    /// Whether the verification found no defect.
    fn valid(&self) -> bool;
    /// The root mean square of the errors.
    fn rms_error(&self) -> f64;
    /// The kind of start.
    fn origin(&self) -> Origin;
    /// The start's index.
    fn start(&self) -> usize;
    /// The design variables' values.
    fn values(&self) -> &[f64];
}

impl Ranked for Candidate {
    fn valid(&self) -> bool {
        self.is_valid()
    }
    fn rms_error(&self) -> f64 {
        self.rms_error
    }
    fn origin(&self) -> Origin {
        self.origin
    }
    fn start(&self) -> usize {
        self.start
    }
    fn values(&self) -> &[f64] {
        &self.values
    }
}

/// What a large search holds of a Halton start's candidate (see the module documentation).
#[derive(Clone, Debug)]
pub(super) struct Key {
    /// The Halton start's index: solved again, it gives the whole candidate.
    pub(super) start: usize,
    values: Vec<f64>,
    rms_error: f64,
    /// The first defect (`None`: valid), as the counts of rejections read it.
    first_defect: Option<Defect>,
    /// The local solve's evaluations and why it stopped, as the report counts them.
    evaluations: usize,
    stop: OptimizerStop,
}

/// A candidate as a search holds it until its report.
#[derive(Clone, Debug)]
pub(super) enum Held {
    /// The whole candidate (boxed: a key is a tenth of its size).
    Whole(Box<Candidate>),
    /// A Halton start's key; the start is solved again if the report keeps it.
    Key(Key),
}

impl Held {
    /// `c` held whole, or as its key where `key` is set and `c` is a Halton start's.
    pub(super) fn of(c: Candidate, key: bool) -> Held {
        if key && c.origin == Origin::Halton {
            Held::Key(Key {
                start: c.start,
                rms_error: c.rms_error,
                first_defect: c.defects.into_iter().next(),
                evaluations: c.local.evaluations,
                stop: c.local.stop,
                values: c.values,
            })
        } else {
            Held::Whole(Box::new(c))
        }
    }

    /// The first defect (`None`: valid).
    pub(super) fn first_defect(&self) -> Option<&Defect> {
        match self {
            Held::Whole(c) => c.defects.first(),
            Held::Key(k) => k.first_defect.as_ref(),
        }
    }

    /// The local solve's evaluations, and why it stopped.
    pub(super) fn local(&self) -> (usize, OptimizerStop) {
        match self {
            Held::Whole(c) => (c.local.evaluations, c.local.stop),
            Held::Key(k) => (k.evaluations, k.stop),
        }
    }
}

impl Ranked for Held {
    fn valid(&self) -> bool {
        self.first_defect().is_none()
    }
    fn rms_error(&self) -> f64 {
        match self {
            Held::Whole(c) => c.rms_error,
            Held::Key(k) => k.rms_error,
        }
    }
    fn origin(&self) -> Origin {
        match self {
            Held::Whole(c) => c.origin,
            Held::Key(_) => Origin::Halton,
        }
    }
    fn start(&self) -> usize {
        match self {
            Held::Whole(c) => c.start,
            Held::Key(k) => k.start,
        }
    }
    fn values(&self) -> &[f64] {
        match self {
            Held::Whole(c) => &c.values,
            Held::Key(k) => &k.values,
        }
    }
}

/// Valid first, then by RMS error, then by origin (seeds first) and start; a stable sort, so
/// the candidates of one start (an island's) keep the order they were found in.
fn rank<T: Ranked>(c: &mut [T]) {
    c.sort_by(|a, b| {
        b.valid()
            .cmp(&a.valid())
            .then(a.rms_error().total_cmp(&b.rms_error()))
            .then(a.origin().cmp(&b.origin()))
            .then(a.start().cmp(&b.start()))
    });
}

/// The candidates ranked, without duplicates (a candidate of the same validity whose every
/// value is within `distinct` of the range of one ranked before it), at most `keep`.
pub(super) fn distinct<T: Ranked>(mut all: Vec<T>, bounds: &[(f64, f64)], distinct: f64, keep: usize) -> Vec<T> {
    rank(&mut all);
    let span: Vec<f64> = bounds.iter().map(|(lo, hi)| (hi - lo).max(f64::MIN_POSITIVE)).collect();
    let mut out: Vec<T> = Vec::new();
    for c in all {
        if out.len() >= keep {
            break;
        }
        let same = |o: &T| {
            o.valid() == c.valid()
                && o.values().iter().zip(c.values()).zip(&span).all(|((a, b), s)| (a - b).abs() <= distinct * s)
        };
        if !out.iter().any(same) {
            out.push(c);
        }
    }
    out
}

/// A refused seed or start as a search holds it until its report: whole, or (a Halton start of
/// a search that holds keys) its kind and index alone, solved again for its design and message
/// where it is the first of its kind.
#[derive(Clone, Debug)]
pub(super) enum HeldRefusal {
    /// The whole refusal (boxed: the kind alone is a fraction of its size).
    Whole(Box<Refused>),
    /// A Halton start's kind.
    Key { kind: RefusalKind, start: usize },
}

impl HeldRefusal {
    /// `r` held whole, or as its kind where `key` is set and `r` is a Halton start's.
    pub(super) fn of(r: Refused, key: bool) -> HeldRefusal {
        if key && r.origin == Origin::Halton {
            HeldRefusal::Key { kind: r.kind, start: r.start }
        } else {
            HeldRefusal::Whole(Box::new(r))
        }
    }

    /// The kind of error that refused it.
    pub(super) fn kind(&self) -> RefusalKind {
        match self {
            HeldRefusal::Whole(r) => r.kind,
            HeldRefusal::Key { kind, .. } => *kind,
        }
    }
}
