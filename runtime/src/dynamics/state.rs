//! The kinematic state as the dynamics reads it, whatever way its sizes are known: a compiled
//! mechanism's [`Kin`] (arrays) or a run-time model's [`KinBuf`] (slices). The formulas of the
//! dynamics are written once over this trait.

use super::model::{Coord, Rotation};
use crate::dims::KinState;
#[cfg(doc)]
use crate::{dims::KinBuf, kin::Kin};

/// Positions, analogs and outputs of one kinematic state, by index.
pub trait AnalogState {
    /// The inputs (their count is the number of inputs).
    fn inputs(&self) -> &[f64];
    /// The positions of the unknowns.
    fn unknowns(&self) -> &[f64];
    /// The output columns.
    fn outputs(&self) -> &[f64];
    /// `d q_u / d x_i`.
    fn unknown_d1(&self, u: usize, i: usize) -> f64;
    /// `d2 q_u / d x_i d x_j`.
    fn unknown_d2(&self, u: usize, i: usize, j: usize) -> f64;
    /// `d out_o / d x_i`.
    fn output_d1(&self, o: usize, i: usize) -> f64;
    /// `d2 out_o / d x_i d x_j`.
    fn output_d2(&self, o: usize, i: usize, j: usize) -> f64;
    /// The first number of the state that is not finite (inputs, positions, their analogs,
    /// outputs, theirs), if any.
    fn non_finite(&self) -> Option<f64>;
}

/// Every kinematic state of the generic algorithms ([`Kin`], [`KinBuf`]) is one the dynamics
/// reads: the same numbers, by index.
impl<S: KinState> AnalogState for S {
    #[inline(always)]
    fn inputs(&self) -> &[f64] {
        self.x()
    }
    #[inline(always)]
    fn unknowns(&self) -> &[f64] {
        self.q()
    }
    #[inline(always)]
    fn outputs(&self) -> &[f64] {
        self.out()
    }
    #[inline(always)]
    fn unknown_d1(&self, u: usize, i: usize) -> f64 {
        self.dq(u)[i]
    }
    #[inline(always)]
    fn unknown_d2(&self, u: usize, i: usize, j: usize) -> f64 {
        self.d2q(u, i, j)
    }
    #[inline(always)]
    fn output_d1(&self, o: usize, i: usize) -> f64 {
        self.dout(o)[i]
    }
    #[inline(always)]
    fn output_d2(&self, o: usize, i: usize, j: usize) -> f64 {
        self.d2out(o, i, j)
    }
    fn non_finite(&self) -> Option<f64> {
        let (n, ni, no) = (self.q().len(), self.x().len(), self.out().len());
        let pairs = move || (0..ni).flat_map(move |i| (0..ni).map(move |j| (i, j)));
        let dq = (0..n).flat_map(|u| self.dq(u).iter().copied());
        let d2q = (0..n).flat_map(|u| pairs().map(move |(i, j)| self.d2q(u, i, j)));
        let dout = (0..no).flat_map(|o| self.dout(o).iter().copied());
        let d2out = (0..no).flat_map(|o| pairs().map(move |(i, j)| self.d2out(o, i, j)));
        let positions = self.x().iter().chain(self.q()).copied();
        positions
            .chain(dq)
            .chain(d2q)
            .chain(self.out().iter().copied())
            .chain(dout)
            .chain(d2out)
            .find(|v| !v.is_finite())
    }
}

/// The value of coordinate `c` in state `k`.
#[inline(always)]
pub(crate) fn value<S: AnalogState + ?Sized>(k: &S, c: Coord) -> f64 {
    match c {
        Coord::Output(o) => k.outputs()[o],
        Coord::Unknown(u) => k.unknowns()[u],
        Coord::Fixed(v) => v,
    }
}

/// `d c / d x_i`.
#[inline(always)]
pub(crate) fn d1<S: AnalogState + ?Sized>(k: &S, c: Coord, i: usize) -> f64 {
    match c {
        Coord::Output(o) => k.output_d1(o, i),
        Coord::Unknown(u) => k.unknown_d1(u, i),
        Coord::Fixed(_) => 0.0,
    }
}

/// `d2 c / d x_i d x_j`.
#[inline(always)]
pub(crate) fn d2<S: AnalogState + ?Sized>(k: &S, c: Coord, i: usize, j: usize) -> f64 {
    match c {
        Coord::Output(o) => k.output_d2(o, i, j),
        Coord::Unknown(u) => k.unknown_d2(u, i, j),
        Coord::Fixed(_) => 0.0,
    }
}

/// `d angle / d x_i` of a body's angle (1 for the input it turns with).
#[inline(always)]
pub(crate) fn w1<S: AnalogState + ?Sized>(k: &S, r: Rotation, i: usize) -> f64 {
    match r {
        Rotation::Unknown(u) => k.unknown_d1(u, i),
        Rotation::Input(input) => {
            if input == i {
                1.0
            } else {
                0.0
            }
        }
        Rotation::None => 0.0,
    }
}

/// `d2 angle / d x_i d x_j` of a body's angle (0 for an input).
#[inline(always)]
pub(crate) fn w2<S: AnalogState + ?Sized>(k: &S, r: Rotation, i: usize, j: usize) -> f64 {
    match r {
        Rotation::Unknown(u) => k.unknown_d2(u, i, j),
        Rotation::Input(_) | Rotation::None => 0.0,
    }
}
