//! The sines and cosines of a Newton block's evaluation, rotated from the solve's previous
//! evaluation, as the compiled block computes them.
//!
//! The emitted Newton block computes every `sin_cos` pair of its evaluation (each depends on the
//! block's unknowns) through a `NearSlot` of its own (the runtime's `NearTrig`), fresh at the
//! start of each solve of the block, kept across that solve's evaluations: the guess's values
//! are libm's, each later evaluation's are the previous ones rotated by the change of the
//! argument, or libm's again after a jump or a number of rotations.
//! The values differ from libm's in the last bits, so the model does the same, with the same
//! function (`NearSlot::newton_sin_cos`): the same bits.
//!
//! Each sine and cosine instruction of a block's evaluation segment (`Ins::NearSinCos`) keeps
//! its slot in four registers of its own ([`WIDTH`]: argument, sine, cosine, age), beside the
//! others of the block ([`NearSlots`]); [`NearSlots::reset`] makes them fresh before a solve's
//! first evaluation. The state lives in registers, like every other value of a step: no
//! allocation, and no copy: the solver returns the evaluation it made last (see `newton`), so
//! the values the registers hold after a solve are the returned evaluation's, those the emitted
//! block reads from that evaluation. Any other run of a block's nodes (the analogs at a given position, the
//! Jacobian, the sensitivities) is a segment of its own with libm's `sin_cos`, as the emitted
//! straight-line code there.

use crate::extra::Extra;
use kinloop_runtime::generated::NearSlot;

/// Registers of one slot: its argument, sine, cosine and age (the `u32` in the register's bits:
/// copied, never computed with).
pub(crate) const WIDTH: usize = 4;

/// The rotation slots of one Newton block's evaluation: `slots` slots of [`WIDTH`] registers from
/// `first` on.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NearSlots {
    first: usize,
    /// Registers of the slots: [`WIDTH`] per slot.
    len: usize,
}

impl NearSlots {
    /// `slots` slots in fresh registers of `extra`.
    pub(crate) fn new(extra: &mut Extra, slots: usize) -> NearSlots {
        let len = WIDTH * slots;
        let first = extra.block(len as u32) as usize;
        NearSlots { first, len }
    }

    /// The first register of slot `k` (its argument's).
    pub(crate) fn slot(&self, k: usize) -> u32 {
        (self.first + WIDTH * k) as u32
    }

    /// Makes every slot fresh: the start of a solve, whose guess is evaluated by libm. Only the
    /// arguments are written (`NearSlot::FRESH`'s NaN): a NaN argument sends the next call to
    /// libm whatever the slot's other registers hold, and that call writes them.
    #[inline]
    pub(crate) fn reset(&self, r: &mut [f64]) {
        for s in r[self.first..self.first + self.len].chunks_exact_mut(WIDTH) {
            s[0] = NearSlot::FRESH.arg;
        }
    }

    /// The slots as the registers `r` hold them.
    #[cfg(test)]
    fn live(&self, r: &[f64]) -> Vec<NearSlot> {
        r[self.first..self.first + self.len]
            .chunks_exact(WIDTH)
            .map(|s| NearSlot { arg: s[0], sin: s[1], cos: s[2], age: s[3].to_bits() as u32 })
            .collect()
    }
}

/// `(sin arg, cos arg)` by the slot at `st` (`NearSlot::newton_sin_cos`, as the emitted
/// `NearTrig` computes it), which it updates. The age is kept in its register as the bits of an
/// `f64` (a small integer's bits, a subnormal: only ever copied, never computed with).
///
/// # Safety
/// `st` points to the slot's [`WIDTH`] registers.
#[inline(always)]
pub(crate) unsafe fn sin_cos(st: *mut f64, arg: f64) -> (f64, f64) {
    // SAFETY: the caller's.
    unsafe {
        let mut slot = NearSlot { arg: *st, sin: *st.add(1), cos: *st.add(2), age: (*st.add(3)).to_bits() as u32 };
        let sc = slot.newton_sin_cos(arg);
        *st = slot.arg;
        *st.add(1) = slot.sin;
        *st.add(2) = slot.cos;
        *st.add(3) = f64::from_bits(u64::from(slot.age));
        sc
    }
}

#[cfg(test)]
mod tests {
    use crate::compiled_reference::{assert_same_bits, class_four};
    use kinloop::Mechanism;
    use kinloop_runtime::NewtonConfig;
    use std::f64::consts::TAU;

    /// The class IV group (one Newton block of four unknowns, its sines and cosines rotated)
    /// solved from guesses a little off the solution: the model's positions and analogs are the
    /// compiled mechanism's to the bit. The compiled block is the independent reference (the
    /// emitted straight-line code with its own `NearTrig`); with libm's values in the model
    /// instead, positions and analogs differ from it in the last bits (the first sample's `q`
    /// already). That the rotation is in use: after the solves, slots whose last values were
    /// rotated (age above 0), and among them values other than libm's of the same argument.
    #[test]
    fn a_newton_block_rotates_its_sines_and_cosines_as_the_compiled_one() {
        let (compiled, mut m) = class_four();
        let cfg = NewtonConfig::default();
        let (mut q, mut rotated, mut not_libm) = (compiled.guess_flat(&[0.0]), 0, 0);
        for k in 0..24 {
            let x = [TAU * k as f64 / 24.0];
            q = compiled.kinematics_flat(&x, &q, &cfg).expect("assembles over a turn").q;
            // Off the solution by 1e-4 to 4e-4 rad: Newton's corrections are rotated.
            let guess: [f64; 4] =
                std::array::from_fn(|u| q[u] + 1e-4 * (u as f64 + 1.0) * if u % 2 == 0 { 1.0 } else { -1.0 });
            let c = compiled.kinematics_flat(&x, &guess, &cfg).expect("compiled");
            assert_same_bits(&c, m.kinematics(&x, &guess, &cfg).expect("run time"), &x);
            for p in m.newton_progs() {
                for s in p.near.live(m.registers_view()) {
                    if s.age > 0 {
                        rotated += 1;
                        not_libm += usize::from((s.sin, s.cos) != s.arg.sin_cos());
                    }
                }
            }
        }
        assert!(rotated > 0 && not_libm > 0, "{rotated} slots rotated, {not_libm} of them not libm's");
        eprintln!("{rotated} slots rotated, {not_libm} of them with values other than libm's");
    }
}
