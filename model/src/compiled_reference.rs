//! The unit tests' independent reference for a Newton block run by the model: the class IV group
//! (one Newton block of four angles) compiled by the macro, beside the same text read as a
//! model, and the comparison of their kinematics to the bit.

use crate::{Model, State};
use kinloop::Kin;
use kinloop_fixtures as fx;

/// The class IV group compiled, and read from the same text at run time.
pub(crate) fn class_four() -> (fx::ClassFour, Model) {
    let model = Model::read("class_four.kl", fx::CLASS_FOUR_TEXT).unwrap_or_else(|e| panic!("{e}"));
    (fx::ClassFour::default(), model)
}

/// Asserts that the model's positions and their first and second analogs `run` at inputs `x`
/// are the compiled mechanism's `compiled`, bit for bit.
pub(crate) fn assert_same_bits<const N: usize, const NI: usize, const NO: usize>(
    compiled: &Kin<N, NI, NO>,
    run: &State,
    x: &[f64],
) {
    let bits = |v: &mut dyn Iterator<Item = &f64>| v.map(|v| v.to_bits()).collect::<Vec<u64>>();
    assert_eq!(bits(&mut compiled.q.iter()), bits(&mut run.q.iter()), "q at {x:?}");
    assert_eq!(bits(&mut compiled.dq.iter().flatten()), bits(&mut run.dq.iter()), "dq at {x:?}");
    assert_eq!(bits(&mut compiled.d2q.iter().flatten().flatten()), bits(&mut run.d2q.iter()), "d2q at {x:?}");
}
