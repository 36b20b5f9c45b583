//! The states at given inputs, followed along the path through them without jumping branches
//! ([`sweep_at_of`]: each stretch between consecutive inputs a sweep of its own).

use super::collected::{MAX_COLLECTED_BYTES, check_collected_within};
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
/// ([`SweepResult::into_result`] for `?`): a kink at an input between two others once, at that
/// input, and none at the first or the last input, as a sweep lists none at its ends. An input
/// of the list that is not finite stops it there with [`Error::NonFinite`] naming the input (the
/// states before it kept).
///
/// Each state is at its own input but where the configuration says
/// [`AtSingular::Continue`](crate::AtSingular::Continue): there an input at a singular crossing,
/// or so near it that no solve pins the branch, gives the first well-conditioned state past the
/// crossing, at that state's own input (`Kin::x`, a little past the crossing), as a sweep's
/// sample is; compare `Kin::x` with the input where that matters.
///
/// Over any [`Kernel`], with its configuration ([`Kernel::solver_config`]): a compiled
/// mechanism's ([`Named::sweep_at`](crate::Named::sweep_at)) or one whose sizes are known at run
/// time (`kinloop_model::Model::sweep_at`). An input or a guess of another size than the
/// kernel's stops it with `Error::InvalidArgument`.
///
/// Every state is kept: inputs whose states would exceed
/// [`MAX_COLLECTED_BYTES`] (1 GiB, a few million states)
/// are refused with `Error::InvalidArgument` and the numbers, before any solve where the
/// iterator tells their count (a list, a range), else where the states kept reach it (they are
/// kept, the result stopped there). Give such inputs in parts, each part starting at the last
/// input of the one before with its state's positions as the guess.
pub fn sweep_at_of<K: Kernel>(m: &K, inputs: impl IntoIterator<Item = X<K>>, guess: Q<K>) -> SweepResult<KinOf<K>> {
    sweep_at_within(m, inputs, guess, MAX_COLLECTED_BYTES)
}

/// [`sweep_at_of`] keeping at most `budget` bytes of states (tested with a small one).
fn sweep_at_within<K: Kernel>(
    m: &K,
    inputs: impl IntoIterator<Item = X<K>>,
    guess: Q<K>,
    budget: usize,
) -> SweepResult<KinOf<K>> {
    let (mut states, mut events) = (Vec::new(), Vec::new());
    let inputs = inputs.into_iter();
    // A state's own size and its arrays on the heap (a run-time model's).
    let bytes_each = size_of::<KinOf<K>>() + m.dims().kin().heap_bytes();
    let instead = "give the inputs in parts, each starting at the last input of the one before with its state's \
                   positions as the guess";
    // The states the budget holds; more are refused up front where the iterator knows it has
    // more (its lower bound), else as the next state would pass it.
    let most = budget / bytes_each.max(1);
    if let Err(e) = check_collected_within("`sweep_at`", "states", inputs.size_hint().0, bytes_each, instead, budget) {
        return SweepResult::new(states, Some(e), events);
    }
    // A corner the last stretch met at its end, the input of the last state kept: listed only
    // where the path goes on from there.
    let mut joint: Option<Event> = None;
    // Whether the path came to that input from another (it is not the path's first).
    let mut arrived = false;
    for x in inputs {
        if states.len() == most {
            let count = most + 1;
            let e = check_collected_within("`sweep_at`", "states (counted so far)", count, bytes_each, instead, budget);
            return SweepResult::new(states, e.err(), events);
        }
        if let Err(e) = check_sizes(m, "sweep_at", &[&x], &[&guess]) {
            return SweepResult::new(states, Some(e), events);
        }
        // An input of the list not finite is named as an input (a stretch's sweep would call it
        // its range's end `to`, which the caller never gave), where the list reaches it.
        if let Err(e) = check_inputs_finite(m, &x) {
            return SweepResult::new(states, Some(e), events);
        }
        // Whether the path moves on from the last state kept (not at a repeated input).
        let moved = states.last().is_some_and(|p| p.x() != x.as_ref());
        // From the last state kept (none before the first input).
        let none = || (Vec::new(), [None, None]);
        let (result, (met, [at_start, at_end])) = match states.last() {
            Some(p) if p.x() == x.as_ref() => (Ok(p.clone()), none()),
            Some(p) => {
                // From the last state, in the kernel's storage.
                let (mut from, mut q) = (x.clone(), guess.clone());
                from.as_mut().copy_from_slice(p.x());
                q.as_mut().copy_from_slice(p.q());
                match SweepOf::<&K, KinOf<K>>::over(m, from, x.clone(), 2, q) {
                    Ok(sweep) => {
                        let (k, met) = stretch_end(sweep);
                        (k.map(|k| at_input(m, k, &x)), met)
                    }
                    Err(e) => (Err(e), none()),
                }
            }
            None => match SweepOf::<&K, KinOf<K>>::over(m, x.clone(), x, 1, guess.clone()) {
                Ok(sweep) => stretch_end(sweep),
                Err(e) => (Err(e), none()),
            },
        };
        // A corner at the input the stretch started from lies between it and the stretch before,
        // inside the path through the inputs: listed once, at that input, whichever of the two
        // saw it (the state there carries one side's analogs: the stretch on the other side sees
        // the jump). The path's own ends are not listed, as a sweep lists neither of its own.
        if moved
            && let Some(mut corner) = joint.take().or(at_start.filter(|_| arrived))
            && let Some(p) = states.last()
        {
            corner.x = p.x().to_vec();
            corner.q = p.q().to_vec();
            events.push(corner);
        }
        events.extend(met);
        match result {
            Ok(k) => {
                // A repeated input keeps the corner at its input.
                if moved {
                    joint = at_end;
                    arrived = true;
                }
                states.push(k);
            }
            Err(e) => return SweepResult::new(states, Some(e), events),
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

/// What a stretch's sweep met: its events, and a corner of the path at its start and at its end
/// (see [`SweepOf::corners_at_ends`]).
type Met = (Vec<Event>, [Option<Event>; 2]);

/// The last state of a sweep run to its end, or its error, with what it met.
fn stretch_end<K: Kernel>(mut sweep: SweepOf<K, KinOf<K>>) -> (Result<KinOf<K>, Error>, Met) {
    let mut last = None;
    while let Some(r) = sweep.next_kin() {
        let stop = r.is_err();
        last = Some(r);
        if stop {
            break;
        }
    }
    let last = last.unwrap_or_else(|| Err(Error::InvalidArgument("a sweep without samples".into())));
    (last, (sweep.events().to_vec(), sweep.corners_at_ends().clone()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::demo::SliderCrank;
    use crate::mechanism::Mechanism;
    use crate::mechanism::kernel::Compiled;

    const M: SliderCrank = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };

    /// The bytes a state of `M` takes.
    fn each() -> usize {
        size_of::<KinOf<Compiled<'static, SliderCrank, 1, 1, 1>>>()
    }

    /// Inputs whose states would exceed the budget are refused before any solve where the
    /// iterator tells their count, and where it does not, once the states kept reach it (those
    /// kept, the result stopped there with the numbers); within it every input is solved.
    /// Without a budget a list of `10^8` inputs kept every state until memory ran out.
    #[test]
    fn inputs_beyond_the_memory_budget_are_refused() {
        let k = Compiled(&M);
        let g = M.guess_flat(&[0.0]);
        let budget = 10 * each();
        let inputs = |n: usize| (0..n).map(|i| [0.1 * i as f64]);
        let r = sweep_at_within(&k, inputs(11), g, budget);
        assert!(r.states.is_empty());
        let msg = r.into_result().expect_err("refused").to_string();
        let numbers = format!("`sweep_at` would keep 11 states of {} bytes", each());
        assert!(msg.contains(&numbers) && msg.contains("in parts"), "{msg}");
        // An iterator that does not tell its count: the ten states that fit, then the refusal.
        let mut n = 0;
        let unknown = std::iter::from_fn(|| (n < 11).then(|| (n += 1, [0.1 * n as f64]).1));
        let r = sweep_at_within(&k, unknown, g, budget);
        assert_eq!(r.states.len(), 10);
        let msg = r.into_result().expect_err("refused").to_string();
        assert!(msg.contains("would keep 11 states (counted so far)"), "{msg}");
        assert_eq!(sweep_at_within(&k, inputs(10), g, budget).into_result().unwrap().len(), 10);
        // The real budget: more than a few million states is refused before any solve (the
        // guess, not a number, would fail the first).
        let r = sweep_at_of(&k, inputs(MAX_COLLECTED_BYTES / each() + 1), [f64::NAN]);
        assert!(r.into_result().expect_err("refused").to_string().contains("`sweep_at` would keep"));
    }
}
