//! The kinematic state of a mechanism at one input value, as flat arrays in declaration order.
//! Generated named structs convert from it; generic code (sweeps, analyses) works on it.
//!
//! Plain data: what needs the mechanism's names ([`Kin::checked_motion`]) is defined with the
//! [`Mechanism`](crate::Mechanism) trait, above this module.

use crate::error::Computed;
use crate::solvers::lu::Factor;
use crate::solvers::newton::SolveReport;

/// The signs of the block determinants along a decomposition: one bit per block, exact for up to
/// [`DetSigns::CAPACITY`] blocks. `mechanism!` refuses more than 256 unknowns, and every block
/// solves at least one, so a generated mechanism never has more blocks; sweeps refuse a
/// hand-written [`Mechanism`](crate::Mechanism) that declares more (`Error::InvalidArgument`),
/// whose further blocks would otherwise go unwatched.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct DetSigns([u64; 4]);

impl DetSigns {
    /// The most blocks whose signs are recorded.
    pub const CAPACITY: usize = 256;

    /// The four words of bits (block `b` is bit `b % 64` of word `b / 64`).
    #[cfg_attr(not(feature = "serde"), allow(dead_code))]
    pub(crate) fn words(&self) -> [u64; 4] {
        self.0
    }

    /// The signs from their four words.
    #[cfg_attr(not(feature = "serde"), allow(dead_code))]
    pub(crate) fn from_words(words: [u64; 4]) -> Self {
        DetSigns(words)
    }

    /// Records block `block` as having a negative determinant (a block at or beyond
    /// [`DetSigns::CAPACITY`] is not recorded: no decomposition the crate accepts has one).
    #[inline]
    pub fn set_negative(&mut self, block: usize) {
        if let Some(word) = self.0.get_mut(block / 64) {
            *word ^= 1u64 << (block % 64);
        }
    }

    /// Whether block `block` has a negative determinant (`false` beyond the capacity).
    pub fn is_negative(&self, block: usize) -> bool {
        self.0.get(block / 64).is_some_and(|w| w >> (block % 64) & 1 == 1)
    }

    /// Whether the signs of the first `blocks` blocks (at most [`DetSigns::CAPACITY`]) agree:
    /// only the words holding them are compared (one for up to 64 blocks; `blocks` is a
    /// mechanism's constant, so the loop unrolls to those words).
    #[inline(always)]
    pub(crate) fn same_for(&self, other: &DetSigns, blocks: usize) -> bool {
        let words = blocks.div_ceil(64).min(4);
        (0..words).all(|w| self.0[w] == other.0[w])
    }

    /// The first block whose sign differs between `self` and `other`.
    pub fn first_difference(&self, other: &DetSigns) -> Option<usize> {
        (0..4).find_map(|w| {
            let d = self.0[w] ^ other.0[w];
            (d != 0).then(|| w * 64 + d.trailing_zeros() as usize)
        })
    }
}

impl std::fmt::Binary for DetSigns {
    /// The bits, most significant block first (without leading zero words).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let top = (0..4).rev().find(|&w| self.0[w] != 0).unwrap_or(0);
        if f.alternate() {
            f.write_str("0b")?;
        }
        write!(f, "{:b}", self.0[top])?;
        for w in (0..top).rev() {
            write!(f, "{:064b}", self.0[w])?;
        }
        Ok(())
    }
}

/// How far each block of the decomposition is from singular, and its assembly mode.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Health {
    /// The blocks whose Jacobian has a negative determinant. A change of these signs along a
    /// sweep means a change of assembly mode or a passage through a singular position.
    pub det_signs: DetSigns,
    /// The smallest pivot ratio over all blocks (`1` is perfectly conditioned, `0` singular) of
    /// the column-equilibrated block Jacobians the analogs are solved with. Each column is
    /// divided by its largest entry, except that the column of an angle whose lever is a
    /// variable length (`s @ theta` with `s` an unknown or an input) is divided by at least the
    /// loop's other lengths: a slide passing near its pivot shows as near singular, as its angle
    /// is only known to about `eps` times their ratio to `s` there. Infinite where no block
    /// was factorised (JSON writes it as `"inf"`, and reads it, or `null`, back as this
    /// infinity).
    #[cfg_attr(
        feature = "serde",
        serde(serialize_with = "crate::floats_serde::serialize", deserialize_with = "crate::kin_serde::min_pivot")
    )]
    pub min_pivot: f64,
    /// The block with that smallest pivot ratio.
    pub weakest_block: usize,
}

impl Default for Health {
    #[inline]
    fn default() -> Self {
        Health { det_signs: DetSigns::default(), min_pivot: f64::INFINITY, weakest_block: 0 }
    }
}

impl Health {
    #[doc(hidden)]
    #[inline]
    pub fn note(&mut self, block: usize, lu: &impl Factor) {
        if lu.negative_det() {
            self.det_signs.set_negative(block);
        }
        // Never NaN: every factorisation reports a NaN pivot as 0, singular.
        let p = lu.pivot_ratio();
        debug_assert!(!p.is_nan(), "a factorisation's pivot ratio is never NaN");
        if p < self.min_pivot {
            self.min_pivot = p;
            self.weakest_block = block;
        }
    }
}

/// Where a kernel puts the state it computes: returned by value ([`ByValue`], a point solve), or
/// written into a state the caller owns (`&mut Kin`, a sweep's spare slot: the fields are stored
/// where the sweep keeps them, with no copy of the whole state afterwards).
#[doc(hidden)]
pub trait KinSink<const N: usize, const NI: usize, const NO: usize> {
    /// What the kernel returns on success.
    type Out;
    /// Puts the state `kin` builds.
    fn put(self, kin: impl FnOnce() -> Kin<N, NI, NO>) -> Self::Out;
}

/// The state returned by value.
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct ByValue;

impl<const N: usize, const NI: usize, const NO: usize> KinSink<N, NI, NO> for ByValue {
    type Out = Kin<N, NI, NO>;
    #[inline(always)]
    fn put(self, kin: impl FnOnce() -> Kin<N, NI, NO>) -> Kin<N, NI, NO> {
        kin()
    }
}

impl<const N: usize, const NI: usize, const NO: usize> KinSink<N, NI, NO> for &mut Kin<N, NI, NO> {
    type Out = ();
    #[inline(always)]
    fn put(self, kin: impl FnOnce() -> Kin<N, NI, NO>) {
        *self = kin();
    }
}

/// Positions, velocity analogs and acceleration analogs of the unknowns and of the outputs.
///
/// `N` unknowns, `NI` inputs, `NO` output columns (each point contributes `x` and `y`).
/// Analogs are partial derivatives with respect to the inputs: `dq[u][i] = d q_u / d x_i`,
/// `d2q[u][i][j] = d2 q_u / d x_i d x_j`.
///
/// With the feature `serde` a state serializes as nested sequences and reads back only into a
/// mechanism of the same sizes, every number as it was, bit for bit (a NaN with its sign and
/// payload). JSON has no NaN nor infinity: it gets them as the strings `"inf"`, `"-inf"`, `"NaN"`
/// (`f64::NAN`), `"-NaN"` (its sign bit set, as arithmetic leaves it on x86-64) or `"NaN(0x..)"`
/// (any other NaN, its bits in hex), as every number of the crate, and reads a number, such a
/// string, or `null` (what earlier versions wrote for them) as NaN, except `health.min_pivot`,
/// infinite when no block was factorised, where `null` reads as that infinity. A compact binary
/// format holds the `f64`s themselves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kin<const N: usize, const NI: usize, const NO: usize> {
    /// Input values (generalized coordinates), in declaration order.
    pub x: [f64; NI],
    /// Positions of the unknowns (angles in radians, lengths in the parameters' unit).
    pub q: [f64; N],
    /// Velocity analogs `dq[u][i] = d q_u / d x_i`.
    pub dq: [[f64; NI]; N],
    /// Acceleration analogs `d2q[u][i][j] = d2 q_u / d x_i d x_j`.
    pub d2q: [[[f64; NI]; NI]; N],
    /// Output columns (a point contributes its `x` and `y`).
    pub out: [f64; NO],
    /// First analogs of the output columns.
    pub dout: [[f64; NI]; NO],
    /// Second analogs of the output columns.
    pub d2out: [[[f64; NI]; NI]; NO],
    /// Diagnostics of the position solve.
    pub report: SolveReport,
    /// Conditioning of the blocks at this position (pivot ratios, determinant signs).
    pub health: Health,
}

/// Exact sensitivities of a kinematic state with respect to the `NP` parameters (the innermost
/// index is the parameter): `q[u][k] = d q_u / d p_k`, `dq[u][i][k] = d(d q_u / d x_i) / d p_k`,
/// `d2q[u][i][j][k]`, and the same for the output columns. Obtained by the implicit function
/// theorem with the factorisations of the kinematic solve (`dq/dp = -J^-1 df/dp`, and likewise
/// for the analogs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sens<const N: usize, const NI: usize, const NO: usize, const NP: usize> {
    /// `d q_u / d p_k`.
    pub q: [[f64; NP]; N],
    /// `d(d q_u / d x_i) / d p_k`.
    pub dq: [[[f64; NP]; NI]; N],
    /// `d(d2 q_u / d x_i d x_j) / d p_k`.
    pub d2q: [[[[f64; NP]; NI]; NI]; N],
    /// `d out_o / d p_k`.
    pub out: [[f64; NP]; NO],
    /// `d(d out_o / d x_i) / d p_k`.
    pub dout: [[[f64; NP]; NI]; NO],
    /// `d(d2 out_o / d x_i d x_j) / d p_k`.
    pub d2out: [[[[f64; NP]; NI]; NI]; NO],
}

impl<const N: usize, const NI: usize, const NO: usize, const NP: usize> Sens<N, NI, NO, NP> {
    /// Every sensitivity zero (a buffer to write into).
    pub const ZERO: Self = Sens {
        q: [[0.0; NP]; N],
        dq: [[[0.0; NP]; NI]; N],
        d2q: [[[[0.0; NP]; NI]; NI]; N],
        out: [[0.0; NP]; NO],
        dout: [[[0.0; NP]; NI]; NO],
        d2out: [[[[0.0; NP]; NI]; NI]; NO],
    };

    /// Every value is finite.
    ///
    /// One test of all values, without a branch per value: the early exits of chained
    /// iterators cost a four-bar's sensitivity solve about 500 instructions (callgrind), a
    /// fifth of it.
    #[doc(hidden)]
    #[inline]
    pub fn all_finite(&self) -> bool {
        let mut finite = true;
        let values = [
            self.q.as_flattened(),
            self.dq.as_flattened().as_flattened(),
            self.d2q.as_flattened().as_flattened().as_flattened(),
            self.out.as_flattened(),
            self.dout.as_flattened().as_flattened(),
            self.d2out.as_flattened().as_flattened().as_flattened(),
        ];
        for part in values {
            for v in part {
                // NaN fails the comparison.
                finite &= v.abs() < f64::INFINITY;
            }
        }
        finite
    }

    /// Name of the first quantity with a non-finite sensitivity.
    #[doc(hidden)]
    pub fn first_non_finite(&self, unknowns: &[&'static str], outputs: &[&'static str]) -> &'static str {
        let f = |v: &f64| !v.is_finite();
        for u in 0..N {
            if self.q[u].iter().any(f)
                || self.dq[u].iter().flatten().any(f)
                || self.d2q[u].iter().flatten().flatten().any(f)
            {
                return unknowns.get(u).copied().unwrap_or("?");
            }
        }
        for o in 0..NO {
            if self.out[o].iter().any(f)
                || self.dout[o].iter().flatten().any(f)
                || self.d2out[o].iter().flatten().flatten().any(f)
            {
                return outputs.get(o).copied().unwrap_or("?");
            }
        }
        "?"
    }
}

/// Residuals and first derivatives of all equations at one point: `f`, `j[e][u] = df_e/dq_u`,
/// `fx[e][i] = df_e/dx_i`, and the magnitude of each equation's terms `scale[e]` (the unit its
/// residual is judged in; see `Magnitudes`; `0` where none is known), with the units of
/// the unknowns and inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jac<const N: usize, const NI: usize> {
    /// Residuals `f_e`.
    pub f: [f64; N],
    /// Jacobian with respect to the unknowns, `j[e][u] = df_e/dq_u`.
    pub j: [[f64; N]; N],
    /// Jacobian with respect to the inputs, `fx[e][i] = df_e/dx_i`.
    pub fx: [[f64; NI]; N],
    /// Magnitude of each equation's terms (the sum of the link lengths of a loop projection):
    /// the scale residuals are judged against, so that tests do not depend on the unit of length.
    pub scale: [f64; N],
    /// The unit of each unknown: one radian for an angle, the magnitude of the rows it appears
    /// in per unit of its Jacobian entry otherwise (a slider coordinate: its loop's lengths).
    /// Continuation measures arclength in these units, so it does not depend on the unit of
    /// length. A value that is not positive and finite counts as `1`.
    pub unit: [f64; N],
    /// The unit of each input, by the same rule (one radian for an angle input).
    pub input_unit: [f64; NI],
}

/// True velocities and accelerations (time derivatives) of unknowns and outputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatMotion<const N: usize, const NO: usize> {
    /// Velocities of the unknowns.
    pub qdot: [f64; N],
    /// Accelerations of the unknowns.
    pub qddot: [f64; N],
    /// Velocities of the output columns.
    pub out_dot: [f64; NO],
    /// Accelerations of the output columns.
    pub out_ddot: [f64; NO],
}

#[inline]
fn chain<const NI: usize>(d: &[f64; NI], d2: &[[f64; NI]; NI], w: &[f64; NI], e: &[f64; NI]) -> (f64, f64) {
    let mut v = 0.0;
    let mut a = 0.0;
    for i in 0..NI {
        v += d[i] * w[i];
        a += d[i] * e[i];
        for j in 0..NI {
            a += d2[i][j] * w[i] * w[j];
        }
    }
    (v, a)
}

impl<const N: usize, const NI: usize, const NO: usize> Kin<N, NI, NO> {
    /// True motion from the analogs: `qdot = sum_i q'_i w_i` and
    /// `qddot = sum_ij q''_ij w_i w_j + sum_i q'_i e_i`, for input speeds `w` and input
    /// accelerations `e` (for a single input: `v = v_q w`, `a = a_q w^2 + v_q e`).
    pub fn motion(&self, omega: &[f64; NI], eps: &[f64; NI]) -> FlatMotion<N, NO> {
        let mut m = FlatMotion { qdot: [0.0; N], qddot: [0.0; N], out_dot: [0.0; NO], out_ddot: [0.0; NO] };
        for u in 0..N {
            (m.qdot[u], m.qddot[u]) = chain(&self.dq[u], &self.d2q[u], omega, eps);
        }
        for o in 0..NO {
            (m.out_dot[o], m.out_ddot[o]) = chain(&self.dout[o], &self.d2out[o], omega, eps);
        }
        m
    }

    /// The kind and index of the first non-finite value, for error messages.
    #[doc(hidden)]
    pub fn first_non_finite(&self) -> Option<(Computed, usize)> {
        let parts = [
            &self.q[..],
            self.dq.as_flattened(),
            self.d2q.as_flattened().as_flattened(),
            &self.out[..],
            self.dout.as_flattened(),
            self.d2out.as_flattened().as_flattened(),
        ];
        first_non_finite_state(parts, NI)
    }

    /// Fast check that every value is finite (one sum; NaN and infinity propagate).
    #[doc(hidden)]
    #[inline]
    pub fn all_finite(&self) -> bool {
        let mut s = 0.0;
        for u in 0..N {
            s += self.q[u];
            for i in 0..NI {
                s += self.dq[u][i];
                for j in 0..NI {
                    s += self.d2q[u][i][j];
                }
            }
        }
        for o in 0..NO {
            s += self.out[o];
            for i in 0..NI {
                s += self.dout[o][i];
                for j in 0..NI {
                    s += self.d2out[o][i][j];
                }
            }
        }
        // A finite sum of finite values; an overflowing sum of huge finite values is re-checked
        // element by element.
        s.is_finite() || self.first_non_finite().is_none()
    }
}

/// The kind and index of the first non-finite value of a state of `ni` inputs given flat
/// (each unknown's or output's analogs contiguous, as a compiled `Kin` lays them out):
/// positions, their velocity and acceleration analogs, then the outputs and theirs.
pub fn first_non_finite_state([q, dq, d2q, out, dout, d2out]: [&[f64]; 6], ni: usize) -> Option<(Computed, usize)> {
    let bad = |v: &[f64]| v.iter().any(|x| !x.is_finite());
    // No analogs without inputs: chunks of one over empty slices.
    let (per1, per2) = (ni.max(1), (ni * ni).max(1));
    let parts: [(Computed, &[f64], usize); 6] = [
        (Computed::Position, q, 1),
        (Computed::VelocityAnalog, dq, per1),
        (Computed::AccelerationAnalog, d2q, per2),
        (Computed::Output, out, 1),
        (Computed::OutputVelocityAnalog, dout, per1),
        (Computed::OutputAccelerationAnalog, d2out, per2),
    ];
    parts.into_iter().find_map(|(what, values, per)| values.chunks(per).position(bad).map(|k| (what, k)))
}

#[cfg(test)]
mod tests {
    use super::DetSigns;

    /// A flip in any one of the 256 blocks is seen and named, also together with a flip in
    /// any other block (nothing folds onto another block's bit).
    #[test]
    fn every_block_up_to_the_capacity_has_its_own_sign() {
        for b in 0..DetSigns::CAPACITY {
            let mut s = DetSigns::default();
            s.set_negative(b);
            assert!(s.is_negative(b));
            assert_eq!(s.first_difference(&DetSigns::default()), Some(b));
            for other in [0, 63, 64, 127, 128, 191, 192, 255].into_iter().filter(|&o| o != b) {
                let mut two = s;
                two.set_negative(other);
                assert!(two.is_negative(b) && two.is_negative(other), "{b} {other}");
                assert_eq!(two.first_difference(&s), Some(other));
            }
        }
    }

    /// Beyond the capacity nothing is recorded: in particular block 256 does not toggle
    /// block 0 (flips in blocks `b` and `b + 256` used to cancel).
    #[test]
    fn a_block_beyond_the_capacity_does_not_alias_block_zero() {
        let mut s = DetSigns::default();
        s.set_negative(0);
        s.set_negative(DetSigns::CAPACITY);
        assert!(s.is_negative(0) && !s.is_negative(DetSigns::CAPACITY));
        assert_eq!(s.first_difference(&DetSigns::default()), Some(0));
    }
}
