//! The states at given inputs, followed along the path through them without jumping branches
//! ([`sweep_at_of`]: each stretch between consecutive inputs a sweep of its own).

use super::outcome::SweepResult;
use super::sweep::SweepOf;
use crate::dims::Dims;
use crate::dims::KinState;
use crate::error::Error;
use crate::events::Event;
use crate::mechanism::kernel::{Kernel, KinOf, Q, X, check_inputs_finite, check_sizes};

/// The states at `inputs`, in their order, followed along the path through them without
/// jumping branches: each stretch between consecutive inputs is a [`Sweep`](crate::Sweep) with
/// its own step control, so inputs may be unevenly spaced, far apart or repeated (measured input
/// angles, a motion law). `guess` at the first input picks the assembly mode. The first error
/// stops it; the result keeps the states before it, says why and where it stopped (a limit
/// position between two inputs is located as in a sweep) and lists the events met
/// ([`SweepResult::into_result`] for `?`). An input of the list that is not finite stops it
/// there with [`Error::NonFinite`] naming the input (the states before it kept).
///
/// Over any [`Kernel`], with its configuration ([`Kernel::solver_config`]): a compiled
/// mechanism's ([`Named::sweep_at`](crate::Named::sweep_at)) or one whose sizes are known at run
/// time (`kinloop_model::Model::sweep_at`). An input or a guess of another size than the
/// kernel's stops it with `Error::InvalidArgument`.
pub fn sweep_at_of<K: Kernel>(m: &K, inputs: impl IntoIterator<Item = X<K>>, guess: Q<K>) -> SweepResult<KinOf<K>> {
    let (mut states, mut events) = (Vec::new(), Vec::new());
    for x in inputs {
        if let Err(e) = check_sizes(m, "sweep_at", &[&x], &[&guess]) {
            return SweepResult::new(states, Some(e), events);
        }
        // An input of the list not finite is named as an input (a stretch's sweep would call it
        // its range's end `to`, which the caller never gave), where the list reaches it.
        if let Err(e) = check_inputs_finite(m, &x) {
            return SweepResult::new(states, Some(e), events);
        }
        // From the last state kept (none before the first input).
        let stretch = match states.last() {
            Some(p) if p.x() == x.as_ref() => Ok((p.clone(), Vec::new())),
            Some(p) => {
                // From the last state, in the kernel's storage.
                let (mut from, mut q) = (x.clone(), guess.clone());
                from.as_mut().copy_from_slice(p.x());
                q.as_mut().copy_from_slice(p.q());
                SweepOf::<&K, KinOf<K>>::over(m, from, x.clone(), 2, q)
                    .map_err(|e| (e, Vec::new()))
                    .and_then(stretch_end)
                    .map(|(k, met)| (at_input(m, k, &x), met))
            }
            None => SweepOf::<&K, KinOf<K>>::over(m, x.clone(), x, 1, guess.clone())
                .map_err(|e| (e, Vec::new()))
                .and_then(stretch_end),
        };
        match stretch {
            Ok((k, met)) => {
                events.extend(met);
                states.push(k);
            }
            Err((e, met)) => {
                events.extend(met);
                return SweepResult::new(states, Some(e), events);
            }
        }
    }
    SweepResult::new(states, None, events)
}

/// The state `k` a stretch's sweep ended on, at the input `x` asked for itself: the sweep's
/// end `from + 1 (x - from)` may round off `x`, far off where `|from|` is much larger (from
/// `1e6` to `1e-10`, the state at `1.164e-10`). Solved again at `x` from `k`, a step of that
/// rounding; where that fails (no solve so near can), `k`.
fn at_input<K: Kernel>(m: &K, k: KinOf<K>, x: &X<K>) -> KinOf<K> {
    if k.x() == x.as_ref() {
        return k;
    }
    let mut guess = m.dims().q();
    guess.as_mut().copy_from_slice(k.q());
    m.kinematics(x, &guess, &m.solver_config().newton).unwrap_or(k)
}

/// The last state of a sweep run to its end, with the events it met; its error otherwise.
#[allow(clippy::type_complexity)]
fn stretch_end<K: Kernel>(sweep: SweepOf<K, KinOf<K>>) -> Result<(KinOf<K>, Vec<Event>), (Error, Vec<Event>)> {
    let run = sweep.run();
    let events = run.events.clone();
    match run.into_result() {
        Ok(mut states) => match states.pop() {
            Some(k) => Ok((k, events)),
            None => Err((Error::InvalidArgument("a sweep without samples".into()), events)),
        },
        Err(e) => Err((e, events)),
    }
}
