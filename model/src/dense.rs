//! A dense Newton block at run time: the runtime's own `newton` (or `newton_keeping_lu`, where
//! the emitted code keeps the final factorisation for the analogs), dispatched over the block
//! size once per call, with the block's evaluation a run of the tape instead of emitted
//! straight-line code, and the kept factorisation written into the block's own slot
//! ([`Fac`]).
//!
//! Apart from the block's program and the returned evaluation's contract (`crate::newton`),
//! which a block solved by sparse Newton shares (`crate::sparse`): this solve writes into the
//! block's factorisation slot, and that slot holds a sparse block's solver, so the solve sits
//! above the factorisations and the sparse solver below them.

use crate::factor::{Fac, LuSlot};
use crate::newton::{NewtonProg, write_solution};
use kinloop_runtime::NewtonConfig;
use kinloop_runtime::generated::{BlockEval, BlockFailure, Lu, Magnitudes, SolveReport, newton, newton_keeping_lu};

/// Solves the block from the guesses; on return the registers hold the values of the
/// evaluation the runtime's solver returned (the values the emitted code reads from that
/// evaluation afterwards), and `fac` the kept factorisation when there is one.
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
    // The magnitudes the solver judged the last evaluation in: asked only by a debug build.
    let mags = || if K == 0 { fixed } else { per_eval(&ev) };
    write_solution(p, r, (&ev.f, &p.jac, ev.j.as_flattened()), &solved.z, mags);
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::compiled_reference::{assert_same_bits, class_four};
    use crate::{StepError, StepFailure};
    use kinloop::{Error, Mechanism};
    use kinloop_runtime::NewtonConfig;
    use kinloop_runtime::generated::BlockFailure;
    use std::f64::consts::TAU;

    /// The class IV group (one Newton block of four angles) solved from guesses up to a radian
    /// off its assembly in every angle, which a step from a sweep's prediction never is. After
    /// every solve `write_solution`'s checks hold (live in the tests' debug build), and positions
    /// and analogs are the compiled block's to the bit: the independent reference, since the
    /// emitted code reads what it keeps from the returned evaluation, the model from the
    /// registers its last evaluation wrote. Counted: the solves with more evaluations than the
    /// iterations, the guess's and a checked correction's make (a rejected trial, an iterate
    /// evaluated again, an undone correction, a move to the guess's turns or a restart: the
    /// report does not tell which, and no more than that is claimed of them).
    ///
    /// And one guess known to drive the restarts (the one of the solver tests'
    /// `a_stalled_guess_assembles_in_its_own_mode_and_starts_a_sweep`): with restarts off the
    /// iteration stalls in a fold (compiled and model both report no assembly, the one failure
    /// that restarts), so with them on the solution returned is a restart's.
    #[test]
    fn far_guesses_leave_the_returned_evaluation_as_in_the_compiled_block() {
        let (compiled, mut m) = class_four();
        let cfg = NewtonConfig::default();
        let (mut seed, mut solved, mut extra) = (0x2545_f491_4f6c_dd1d_u64, 0, 0);
        let mut uniform = || {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut q = compiled.guess_flat(&[0.0]);
        for k in 0..48 {
            let x = [TAU * k as f64 / 48.0];
            q = compiled.kinematics_flat(&x, &q, &cfg).expect("assembles over a turn").q;
            let guess: [f64; 4] = std::array::from_fn(|u| q[u] + uniform());
            match (compiled.kinematics_flat(&x, &guess, &cfg), m.kinematics(&x, &guess, &cfg)) {
                (Ok(c), Ok(r)) => {
                    assert_same_bits(&c, r, &x);
                    solved += 1;
                    extra += usize::from(c.report.evaluations > c.report.iterations + 2);
                }
                (Err(_), Err(_)) => {}
                (c, r) => panic!("at {x:?}: compiled {:?}, run time {:?}", c.map(|_| ()), r.map(|_| ())),
            }
        }
        assert!(solved > 24 && extra > 4, "{solved} of 48 solved, {extra} with more evaluations");

        let (x, stalls) = (
            [0.001],
            [0.769_901_552_615_186, 2.469_494_962_272_225_5, -1.565_244_534_929_787_4, -0.072_132_133_502_123_44],
        );
        let once = cfg.with_restarts(false);
        let alone =
            (compiled.kinematics_flat(&x, &stalls, &once).map(|_| ()), m.kinematics(&x, &stalls, &once).map(|_| ()));
        let stalled = |e: &StepError| {
            matches!(e, StepError::Block { failure: StepFailure::Block(BlockFailure::NoAssembly { .. }), .. })
        };
        assert!(matches!(&alone, (Err(Error::NoAssembly { .. }), Err(e)) if stalled(e)), "{alone:?}");
        let c = compiled.kinematics_flat(&x, &stalls, &cfg).expect("the restarts assemble it");
        assert_same_bits(&c, m.kinematics(&x, &stalls, &cfg).expect("the restarts assemble it"), &x);
    }

    /// A guess where the class IV group's Newton block has an exactly singular Jacobian: with
    /// `th1`, `th2` and `psi1` zero, the row of loop `acdb`'s `x` projection (its entries are
    /// its links' sines, `-ac sin th1`, `bd sin th2`, `-cd sin psi1` and 0) is zero at every
    /// input, so the guess's pivot is 0 and no Newton step can be made: with restarts off, what
    /// solves it is the descent (see the solver's `a_descent_after_failed_searches`). The
    /// model's descent runs on the tape's evaluations, its registers written by each trial: the
    /// compiled block's solve is the independent reference, to the bit, at inputs over a turn;
    /// and the positions close both loops, their residuals (evaluated apart from the solve)
    /// within the solver's tolerance of the loops' sizes.
    #[test]
    fn a_singular_guess_descends_as_in_the_compiled_block() {
        let (compiled, mut m) = class_four();
        let cfg = NewtonConfig::default().with_restarts(false);
        let singular = [0.0, 0.0, 0.0, -1.0];
        let mut solved = 0;
        for k in 0..24 {
            let x = [TAU * k as f64 / 24.0];
            let jac = compiled.jacobian_flat(&x, &singular);
            assert!(jac.j.iter().any(|row| row.iter().all(|&v| v == 0.0)), "at {x:?}: {:?}", jac.j);
            match (compiled.kinematics_flat(&x, &singular, &cfg), m.kinematics(&x, &singular, &cfg)) {
                (Ok(c), Ok(r)) => {
                    assert_same_bits(&c, r, &x);
                    let at = compiled.jacobian_flat(&x, &c.q);
                    let closed = at.f.iter().zip(at.scale).all(|(f, s)| f.abs() <= cfg.residual_tol * s);
                    assert!(closed, "at {x:?}: residuals {:?} against sizes {:?}", at.f, at.scale);
                    solved += 1;
                }
                (Err(_), Err(_)) => {}
                (c, r) => panic!("at {x:?}: compiled {:?}, run time {:?}", c.map(|k| k.q), r.map(|s| s.q.clone())),
            }
        }
        assert!(solved >= 20, "{solved} of 24 solved from the singular guess");
    }
}
