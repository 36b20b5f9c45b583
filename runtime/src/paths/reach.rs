//! How far the input can move on one assembly mode ([`reachable`], answering in input values
//! with [`Reach`]), over any [`Kernel`] ([`reachable_of`]).

use super::outcome::SweepStop;
use super::sweep::SweepOf;
use crate::dims::{Dims, KinState};
use crate::error::{Error, Quantity};
use crate::events::Event;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, Kernel, KinOf, Q, X, check_inputs_finite, check_sizes};
use crate::number::Count;

/// The reachable stretch of the input from a starting value on one assembly mode, in input
/// values, with the limit positions that end it (`None` where the end of the searched range is
/// reached first). `X` is the input type: `[f64; NI]` from [`reachable`], the generated
/// `NameInputs` from [`Named::reachable`](crate::Named::reachable), the kernel's input vector
/// from [`reachable_of`]. Where an end is a limit position the velocity analogs do not exist
/// there: a sweep over the reach starts and ends inside it (a sweep from a limit position is an
/// error that says so), and [`trace_curve`](crate::paths::trace::trace_curve) starts at one.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Reach<X> {
    /// The input where the backward stretch (towards `at - delta`) ends.
    pub from: X,
    /// The input where the forward stretch (towards `at + delta`) ends.
    pub to: X,
    /// The limit position ending the backward stretch.
    pub from_event: Option<Event>,
    /// The limit position ending the forward stretch.
    pub to_event: Option<Event>,
}

impl<X> Reach<X> {
    /// The same reach with the inputs converted (e.g. to named inputs).
    pub fn map_inputs<Y>(self, mut f: impl FnMut(X) -> Y) -> Reach<Y> {
        Reach { from: f(self.from), to: f(self.to), from_event: self.from_event, to_event: self.to_event }
    }
}

/// Finds how far the input can move from `at` towards `at + delta` and `at - delta` on the
/// assembly mode of `guess` before a limit position, sweeping both ways with `samples` samples
/// each (with the mechanism's [`Mechanism::solver_config`]), and answers in input values: a
/// compiled mechanism's [`reachable_of`] (through [`Compiled`]).
///
/// Errors: fewer than 2 samples, more than [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES), a
/// `delta` of zeros, one too small to move `at` (below the spacing of doubles there) or so
/// large that `at ± delta` overflows as [`Error::InvalidArgument`]; `at` or `delta` not finite as
/// [`Error::NonFinite`]; those of the sweeps, except the limit positions that end them (a
/// singular crossing that the configuration stops at is an error).
pub fn reachable<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    at: [f64; NI],
    delta: [f64; NI],
    guess: [f64; N],
    samples: usize,
) -> Result<Reach<[f64; NI]>, Error>
where
    M: Mechanism<N, NI, NO>,
{
    m.check_param_angles(&m.solver_config().newton)?;
    reachable_of(&Compiled(m), at, delta, guess, samples)
}

/// [`reachable`] over any [`Kernel`] (a compiled mechanism's, or one whose sizes are known at
/// run time: `kinloop_model::Model::reachable`), with the kernel's configuration
/// ([`Kernel::solver_config`]); `at`, `delta` and `guess` of the kernel's sizes (a mismatch is
/// an `Error::InvalidArgument`).
pub fn reachable_of<K: Kernel>(
    m: &K,
    at: X<K>,
    delta: X<K>,
    guess: Q<K>,
    samples: usize,
) -> Result<Reach<X<K>>, Error> {
    check_sizes(m, "reachable", &[&at, &delta], &[&guess])?;
    if samples < 2 {
        return Err(Error::InvalidArgument(format!(
            "reachable: {} a side asked for: a stretch needs at least 2 (its ends)",
            Count(samples, "sample")
        )));
    }
    crate::analysis::check_sample_count("samples a side of `reachable`", samples).map_err(Error::InvalidArgument)?;
    let ni = m.dims().ni();
    // Checked here, under the caller's names: the sweeps would call them their ranges' ends.
    check_inputs_finite(m, &at)?;
    if let Some((i, &value)) = delta.as_ref().iter().enumerate().find(|(_, v)| !v.is_finite()) {
        let name = format!("delta of {}", m.input_name(i)).into();
        return Err(Error::NonFinite { what: Quantity::Range, name, value, at: m.location(at.as_ref(), None) });
    }
    if delta.as_ref().iter().all(|&d| d == 0.0) {
        return Err(Error::InvalidArgument(
            "reachable: `delta` is zero: give the step along which to search, each side of `at` (its direction and \
             the distance to search)"
                .into(),
        ));
    }
    // Both finite, `at ± delta` can still overflow (`1e308 + 1e308`): the sweep would call its
    // range infinitely many turns long, of a range the caller never gave. Checked for both
    // sides before either is swept.
    for (i, sign) in (0..ni).flat_map(|i| [(i, -1.0), (i, 1.0)]) {
        if !(at[i] + sign * delta[i]).is_finite() {
            return Err(Error::InvalidArgument(format!(
                "reachable: `at {s} delta` of {name} overflows ({at} {s} {delta} is beyond the largest double); \
                 give a smaller `delta` (the distance to search each side)",
                s = if sign < 0.0 { "-" } else { "+" },
                name = m.input_name(i),
                at = at[i],
                delta = delta[i],
            )));
        }
    }
    // The end of a stretch: `x` copied into an input of the kernel's size.
    let input = |x: &[f64]| {
        let mut v = at.clone();
        v.as_mut().copy_from_slice(x);
        v
    };
    let mut ends = [(at.clone(), None), (at.clone(), None)];
    for (side, sign) in [(0usize, -1.0), (1, 1.0)] {
        let mut to = at.clone();
        for i in 0..ni {
            to[i] += sign * delta[i];
        }
        // A `delta` below the spacing of doubles at `at` moves no input: the sweep would say
        // its `to` equals its `from`, of a range the caller never gave.
        if to.as_ref() == at.as_ref() {
            return Err(Error::InvalidArgument(format!(
                "reachable: `at {} delta` rounds to `at`: `delta` is below the spacing of doubles at `at`; give \
                 a larger `delta` (the distance to search each side)",
                if sign < 0.0 { "-" } else { "+" }
            )));
        }
        // Only the last state is kept (a stretch is its end): no vector of every sample.
        let mut sweep = SweepOf::<&K, KinOf<K>>::over(m, at.clone(), to, samples, guess.clone())?;
        let mut last = at.clone();
        let mut error = None;
        while let Some(r) = sweep.next_ref() {
            match r {
                Ok(k) => last.as_mut().copy_from_slice(k.x()),
                Err(e) => {
                    error = Some(e);
                    break;
                }
            }
        }
        ends[side] = match error {
            None => (last, None),
            // A limit position ends the stretch; any other stop is the error.
            Some(e) => match SweepStop::from_error(&e, sweep.events().last()) {
                SweepStop::LimitPosition(ev) => (input(&ev.x), Some(ev)),
                _ => return Err(e),
            },
        };
    }
    let [(from, from_event), (to, to_event)] = ends;
    Ok(Reach { from, to, from_event, to_event })
}
