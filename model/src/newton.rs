//! A Newton block at run time: the runtime's own `newton` (or `newton_keeping_lu`, where the
//! emitted code keeps the final factorisation for the analogs), with the block's evaluation a
//! run of the tape instead of emitted straight-line code.
//!
//! The evaluation's sines and cosines are rotated from the solve's previous evaluation, as the
//! emitted block's `NearTrig` rotates them (`crate::near`): its slots are made fresh before
//! each solve. On every path that returns a solution the runtime's solver returns the
//! evaluation made by its last call of the evaluation closure (a contract its tests check path
//! by path), so after a solve the registers hold the returned evaluation's values, as the
//! emitted block's locals do ([`write_solution`]: a debug build checks it).

use crate::factor::{Fac, LuSlot};
use crate::near::NearSlots;
use crate::tape::Segment;
use kinloop_runtime::NewtonConfig;
use kinloop_runtime::generated::{BlockEval, BlockFailure, Lu, Magnitudes, SolveReport, newton, newton_keeping_lu};

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

/// Solves the block from the guesses; on return the registers hold the values of the
/// evaluation the runtime's solver returned (what the emitted code reads from it afterwards),
/// and `fac` the kept factorisation when there is one.
pub(crate) fn solve(
    p: &NewtonProg,
    r: &mut [f64],
    guess: &[f64],
    cfg: &NewtonConfig,
    report: &mut SolveReport,
    fac: &mut Fac,
) -> Result<(), BlockFailure> {
    macro_rules! go {
        ($n:literal, $k:literal, $kf:literal) => {
            if p.fixed_mags {
                solve_n::<$n, $kf>(p, r, guess, cfg, report, fac)
            } else {
                solve_n::<$n, $k>(p, r, guess, cfg, report, fac)
            }
        };
    }
    match p.unknowns.len() {
        1 => go!(1, 2, 0),
        2 => go!(2, 4, 0),
        3 => go!(3, 6, 0),
        4 => go!(4, 8, 0),
        5 => go!(5, 10, 0),
        6 => go!(6, 12, 0),
        7 => go!(7, 14, 0),
        8 => go!(8, 16, 0),
        9 => go!(9, 18, 0),
        10 => go!(10, 20, 0),
        11 => go!(11, 22, 0),
        12 => go!(12, 24, 0),
        13 => go!(13, 26, 0),
        14 => go!(14, 28, 0),
        15 => go!(15, 30, 0),
        16 => go!(16, 32, 0),
        // Larger blocks are rejected when the model is built.
        _ => Err(BlockFailure::NonFinite { row: 0, iterations: 0 }),
    }
}

fn read<const N: usize>(r: &[f64], regs: &[u32]) -> [f64; N] {
    std::array::from_fn(|k| r[regs[k] as usize])
}

/// [`solve`] for a block of `N` unknowns keeping `K` values per evaluation (its magnitudes, when
/// they depend on the unknowns: `K = 2N`; otherwise none).
fn solve_n<const N: usize, const K: usize>(
    p: &NewtonProg,
    r: &mut [f64],
    guess: &[f64],
    cfg: &NewtonConfig,
    report: &mut SolveReport,
    fac: &mut Fac,
) -> Result<(), BlockFailure>
where
    Lu<N>: LuSlot<N>,
{
    let z0: [f64; N] = std::array::from_fn(|k| guess[p.unknowns[k]]);
    let turns: [bool; N] = std::array::from_fn(|k| p.turns[k]);
    let fixed = Magnitudes::new(read::<N>(r, &p.scale), read::<N>(r, &p.unit)).with_turns(turns);
    // A fresh `NearTrig` for this solve, as the emitted block makes one.
    p.near.reset(r);
    // Written over the solver's slot, every field, as the emitted block's evaluation is.
    let mut eval = |z: &[f64; N], e: &mut BlockEval<N, K>| {
        for (k, &reg) in p.unknown_regs.iter().enumerate() {
            r[reg as usize] = z[k];
        }
        p.eval.run(r);
        e.f = read::<N>(r, &p.f);
        for (row, out) in e.j.iter_mut().enumerate() {
            *out = read::<N>(r, &p.jac[row * N..]);
        }
        for (k, out) in e.keep.iter_mut().enumerate() {
            *out = if k < N { r[p.scale[k] as usize] } else { r[p.unit[k - N] as usize] };
        }
    };
    let mut ev = BlockEval { f: [0.0; N], j: [[0.0; N]; N], keep: [0.0; K] };
    eval(&z0, &mut ev);
    let per_eval = |e: &BlockEval<N, K>| {
        Magnitudes::new(std::array::from_fn(|k| e.keep[k]), std::array::from_fn(|k| e.keep[N + k])).with_turns(turns)
    };
    let solved = if p.keeps_lu {
        // Written into the block's own slot: the analogs read it there.
        let lu = <Lu<N> as LuSlot<N>>::slot(fac);
        if K == 0 {
            newton_keeping_lu::<N, K>(z0, &mut ev, cfg, &mut eval, &fixed, lu)
        } else {
            newton_keeping_lu::<N, K>(z0, &mut ev, cfg, &mut eval, &per_eval, lu)
        }
    } else if K == 0 {
        newton::<N, K>(z0, &mut ev, cfg, &mut eval, &fixed)
    } else {
        newton::<N, K>(z0, &mut ev, cfg, &mut eval, &per_eval)
    }?;
    report.absorb(&solved);
    write_solution(p, r, (&ev.f, &p.jac, ev.j.as_flattened()), &solved.z);
    Ok(())
}

/// Writes the solution `z` into the block's unknowns' registers, whose other registers hold the
/// returned evaluation: the solver's last, since the runtime's solver returns the evaluation of
/// its last call of the evaluation closure on every path that returns a solution (after a
/// correction at the rounding level, applied without evaluating, that evaluation is the one
/// before the correction, as the emitted block's). A debug build checks that the registers
/// hold the returned residuals `f` and Jacobian values `jac` (in registers `jac_regs`), and
/// that the last evaluated position is `z`, but for such a correction. (In a release build the
/// check would cost every solve a comparison of its Jacobian, for a contract the runtime's tests
/// hold.)
pub(crate) fn write_solution(p: &NewtonProg, r: &mut [f64], (f, jac_regs, jac): (&[f64], &[u32], &[f64]), z: &[f64]) {
    debug_assert!(
        p.f.iter().zip(f).all(|(&reg, v)| r[reg as usize].to_bits() == v.to_bits())
            && jac_regs.iter().zip(jac).all(|(&reg, v)| r[reg as usize].to_bits() == v.to_bits()),
        "the returned evaluation is not the last one made"
    );
    // The correction applied without evaluating is at most 16 units in the last place of the
    // larger of the unknown and its unit (the runtime's `MAX_UNCHECKED_CORRECTION`).
    debug_assert!(
        p.unknown_regs.iter().zip(&p.unit).zip(z).all(|((&reg, &unit), &zk)| {
            let last = r[reg as usize];
            (zk - last).abs() <= 16.0 * f64::EPSILON * last.abs().max(r[unit as usize])
        }),
        "the returned position is not the last evaluated"
    );
    for (k, &reg) in p.unknown_regs.iter().enumerate() {
        r[reg as usize] = z[k];
    }
}

#[cfg(test)]
mod tests {
    use crate::Model;
    use kinloop::Mechanism;
    use kinloop_fixtures as fx;
    use kinloop_runtime::NewtonConfig;
    use std::f64::consts::TAU;

    /// The class IV group (one Newton block of four angles) solved from guesses up to a radian
    /// off its assembly in every angle: line searches, descents and restarts, the solver's rare
    /// paths, which a step from a sweep's prediction never takes. After every solve the
    /// registers hold the returned evaluation at the returned position (`write_solution`'s
    /// checks, live in the tests: without the replay of an earlier evaluation nothing else
    /// would), and positions and analogs are the compiled block's to the bit (the independent
    /// reference: the emitted code reads its own evaluation's locals). Counted: solves with
    /// rejected trials (more evaluations than the iterations and their correction make).
    #[test]
    fn far_guesses_leave_the_returned_evaluation_as_in_the_compiled_block() {
        let compiled = fx::ClassFour::default();
        let mut m = Model::read("class_four.kl", fx::CLASS_FOUR_TEXT).unwrap_or_else(|e| panic!("{e}"));
        let cfg = NewtonConfig::default();
        let (mut seed, mut solved, mut rare) = (0x2545_f491_4f6c_dd1d_u64, 0, 0);
        let mut uniform = || {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut q = compiled.guess_flat(&[0.0]);
        for k in 0..48 {
            let x = [TAU * k as f64 / 48.0];
            q = compiled.kinematics_flat(&x, &q, &cfg).expect("assembles over a turn").q;
            let guess: [f64; 4] = std::array::from_fn(|u| q[u] + uniform());
            let bits = |v: &mut dyn Iterator<Item = f64>| v.map(f64::to_bits).collect::<Vec<u64>>();
            match (compiled.kinematics_flat(&x, &guess, &cfg), m.kinematics(&x, &guess, &cfg)) {
                (Ok(c), Ok(r)) => {
                    assert_eq!(bits(&mut c.q.iter().copied()), bits(&mut r.q.iter().copied()), "q at {x:?}");
                    assert_eq!(bits(&mut c.dq.iter().flatten().copied()), bits(&mut r.dq.iter().copied()), "dq");
                    let d2q = bits(&mut c.d2q.iter().flatten().flatten().copied());
                    assert_eq!(d2q, bits(&mut r.d2q.iter().copied()), "d2q at {x:?}");
                    solved += 1;
                    rare += usize::from(c.report.evaluations > c.report.iterations + 2);
                }
                (Err(_), Err(_)) => {}
                (c, r) => panic!("at {x:?}: compiled {:?}, run time {:?}", c.map(|_| ()), r.map(|_| ())),
            }
        }
        assert!(solved > 24 && rare > 4, "{solved} of 48 solved, {rare} with rejected trials");
        eprintln!("{solved} of 48 solved, {rare} with rejected trials");
    }
}
