//! Closed-form solutions of the blocks that are classical Assur groups.
//!
//! Newton with an LU solves every nonlinear block in general; a block whose position problem
//! has a closed form is solved by that form instead ([`recognise`](mod@recognise) proves the
//! pattern on the expression graph at compile time; the emitter's `closed_form` writes the
//! straight-line solve):
//!
//! * one unknown angle in one equation `a cos q + b sin q = c` (a rod's angle from one
//!   projection of its loop): two roots by one square root;
//! * two unknown angles of one loop (an RRR dyad): circle intersection;
//! * an unknown length and its angle (`s @ phi == V`, a slotted rocker): `s = ±|V|`;
//! * an angle and a slider coordinate coupled in one block (RRP): the angle from the equation
//!   free of the slider, then the slider linearly.
//!
//! The root is the assembly mode of the guess: the sign of the block's Jacobian determinant at
//! the guess picks it (for a length and its angle, the sign of the guessed length), and angles
//! are unwrapped to the guess's turn, so sweeps (which pass the previous position as the guess)
//! stay on their branch. The analogs still come from the block's Jacobian (one factorisation),
//! which reads the sines and cosines of the unknown angles that the closed form produced.

pub mod recognise;

pub use recognise::{ClosedForm, Recognised, recognise};

/// `|w (cos q, sin q)|²` when it is the same constant for every `q`: `w` constant (an entry
/// `None` where it is not) with orthogonal columns of equal length (a scaled rotation or
/// reflection), as `s (sin q, cos q)` gives. The length of [`ClosedForm::PolarLength`] divides
/// by it in place of `|w(q)|²` (by nothing where it is 1): the emitter and the run-time model
/// both ask here, so both fold the same constants to the same bits.
pub fn constant_norm2(w: [[Option<f64>; 2]; 2]) -> Option<f64> {
    let [[Some(a), Some(b)], [Some(c), Some(d)]] = w else {
        return None;
    };
    let (n0, n1) = (a * a + c * c, b * b + d * d);
    (a * b + c * d == 0.0 && n0 == n1).then_some(n0)
}

#[cfg(test)]
mod tests;
