//! A Newton block at run time: its program ([`NewtonProg`]: the registers the iteration reads
//! and the segment of the tape that evaluates them, instead of emitted straight-line code) and
//! the contract on the evaluation the solver returns ([`write_solution`]), shared by the dense
//! solve (`crate::dense`: the runtime's own `newton` or `newton_keeping_lu`) and the sparse one
//! (`crate::sparse`: its `newton_with`). Below both, and below the factorisations, which hold
//! the sparse block's solver and which the dense solve writes into.
//!
//! The evaluation's sines and cosines are rotated from the solve's previous evaluation, as the
//! emitted block's `NearTrig` rotates them (`crate::near`): its slots are made fresh before
//! each solve. Every evaluation writes its values into the registers, which the model reads
//! after the solve: they are the values of the evaluation the solver returns because on every
//! path that returns a solution that is the one made by its last call of the evaluation closure
//! (a contract the runtime's tests check path by path; [`write_solution`]: a debug build checks
//! it too). The emitted block needs no such contract: it reads what it keeps from the returned
//! evaluation itself. So the compiled block is an independent reference for the model: the two
//! agree to the bit only if the registers hold the returned evaluation (`crate::dense`'s tests).

use crate::near::NearSlots;
use crate::tape::Segment;
use kinloop_runtime::generated::Magnitudes;

/// What the Newton iteration of one block reads: registers of its unknowns, residuals,
/// Jacobian (row-major), magnitudes, and the segment that evaluates them.
#[derive(Clone)]
pub(crate) struct NewtonProg {
    /// The block's evaluation: every node of its residuals, Jacobian and magnitudes that
    /// depends on its unknowns.
    pub(crate) eval: Segment,
    /// The rotation slots of the evaluation's sines and cosines.
    pub(crate) near: NearSlots,
    pub(crate) unknowns: Vec<usize>,
    pub(crate) unknown_regs: Vec<u32>,
    pub(crate) f: Vec<u32>,
    pub(crate) jac: Vec<u32>,
    pub(crate) scale: Vec<u32>,
    pub(crate) unit: Vec<u32>,
    pub(crate) turns: Vec<bool>,
    /// The magnitudes do not depend on the block's unknowns: made once per solve.
    pub(crate) fixed_mags: bool,
    /// The final factorisation is kept for the analogs (the emitter's `keeps_lu`).
    pub(crate) keeps_lu: bool,
}

/// Writes the solution `z` into the block's unknowns' registers, whose other registers hold the
/// values of the solver's last evaluation (the registers are written by every evaluation). A
/// debug build checks that this is the evaluation the solver returned: that the registers hold
/// its residuals `f` and Jacobian values `jac` (in registers `jac_regs`), and that the last
/// evaluated position is `z` but for a correction at the rounding level, which the solver
/// applies without evaluating, judged as the solver judged it, in the units of `mags` (the
/// magnitudes the solver used, an invalid unit replaced; asked only by the check). In a release
/// build the check would cost every solve a comparison of its Jacobian, for a contract the
/// runtime's tests hold.
pub(crate) fn write_solution<const N: usize>(
    p: &NewtonProg,
    r: &mut [f64],
    (f, jac_regs, jac): (&[f64], &[u32], &[f64]),
    z: &[f64; N],
    mags: impl FnOnce() -> Magnitudes<N>,
) {
    debug_assert!(
        p.f.iter().zip(f).all(|(&reg, v)| r[reg as usize].to_bits() == v.to_bits())
            && jac_regs.iter().zip(jac).all(|(&reg, v)| r[reg as usize].to_bits() == v.to_bits()),
        "the returned evaluation is not the last one made"
    );
    debug_assert!(
        {
            let unit = *mags().unit();
            p.unknown_regs.iter().enumerate().all(|(k, &reg)| near_correction(r[reg as usize], z[k], unit[k]))
        },
        "the returned position is not the last evaluated"
    );
    for (k, &reg) in p.unknown_regs.iter().enumerate() {
        r[reg as usize] = z[k];
    }
}

/// Whether `z` is the last evaluated value `last` of an unknown of unit `unit` (the solver's),
/// or a correction of it that the solver applies without evaluating: a step of at most 16 units
/// in the last place of the larger of `|last|` and the unit (the runtime's
/// `MAX_UNCHECKED_CORRECTION`), to which rounding `last + dz` and the difference here add at
/// most one more.
fn near_correction(last: f64, z: f64, unit: f64) -> bool {
    (z - last).abs() <= (16.0 + 1.0) * f64::EPSILON * last.abs().max(unit)
}

#[cfg(test)]
mod tests {
    use super::near_correction;
    use kinloop_runtime::generated::Magnitudes;

    /// `write_solution`'s test of the returned position, by hand. A unit that is not valid
    /// (here 0) counts as 1 in the solver, which may then correct `0.25` by 16 epsilon
    /// unevaluated: 64 epsilon of `|z|`, beyond the bound in the raw unit. And the largest such
    /// correction of `1 - 2^-53`, `2^-48`, lands on a tie rounded to the even `1 + 2^-48`:
    /// `2^-48 + 2^-53` away, half an epsilon beyond the step.
    #[test]
    fn the_returned_position_is_judged_in_the_solvers_units_to_its_rounding() {
        let unit = Magnitudes::new([1.0], [0.0]).unit()[0];
        assert_eq!(unit, 1.0);
        let (last, step) = (0.25, 16.0 * f64::EPSILON);
        assert!(near_correction(last, last + step, unit) && !near_correction(last, last + step, 0.0));
        assert!(!near_correction(last, last + 18.0 * f64::EPSILON, unit));
        let last = 1.0 - f64::EPSILON / 2.0;
        let z = last + step;
        assert_eq!((z, z - last), (1.0 + step, step + f64::EPSILON / 2.0));
        assert!(near_correction(last, z, 1.0) && (z - last).abs() > step);
    }
}
