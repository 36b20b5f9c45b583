//! The evaluation a solve returns is the one made by the LAST call of the evaluation closure,
//! at the returned position (or at the position before a correction at the rounding level,
//! which is applied without evaluating): on every path that returns a solution.
//!
//! The generated code needs only the second half of this: after the solve it reads the values
//! it kept and the Jacobian entries it uses from the returned slot itself, so it is right
//! whichever call made that evaluation, as long as it is one at the returned position. The
//! run-time model needs the first half too: its evaluation writes every value of the block into
//! its registers, which it reads after the solve, and those are the last call's; they are the
//! returned evaluation's only when the slot holds the last call's. That is why the compiled
//! block, reading its slot, is an independent reference for the model, reading its registers.
//!
//! The tests drive the paths of the solver that decide which evaluation is returned (each path
//! the solver's trace names, and a move to the guess's turns kept after its correction was
//! undone), each shown by that trace, on both entry points (`newton` and `newton_keeping_lu`),
//! and check the contract with an evaluation closure that marks each evaluation with its
//! call's number and records the last call's argument: the slot must carry the last call's
//! mark and the values of the block at that argument, the argument must be the returned
//! position, and the solve must count every call (`Solved::evaluations`, the caller's
//! evaluation of the guess included).

use super::config::NewtonConfig;
use super::norms::scaled_step;
use super::report::{NewtonStop, Solved};
use super::scales::{BlockEval, Magnitudes};
use super::step::MAX_UNCHECKED_CORRECTION;
use super::trace::{self, SolvePath};
use super::{newton, newton_keeping_lu};
use crate::solvers::lu::Lu;
use core::cell::Cell;
use core::f64::consts::{FRAC_PI_2, PI};

/// A block's residuals and dense Jacobian at a position.
type Values<const N: usize> = ([f64; N], [[f64; N]; N]);

/// What a solve left: its result, the evaluation in the caller's slot, the number of calls of
/// the evaluation closure and the last one's argument, and the paths the solver took.
struct Run<const N: usize> {
    solved: Result<Solved<N>, super::report::BlockFailure>,
    ev: BlockEval<N, 1>,
    calls: u32,
    last: [f64; N],
    paths: Vec<SolvePath>,
}

/// Solves `block` from `z0` as the generated code does (the guess evaluated into the caller's
/// slot by the same closure), through `newton_keeping_lu` when `keeping_lu`, else `newton`.
fn run<const N: usize>(
    z0: [f64; N],
    cfg: &NewtonConfig,
    mags: &Magnitudes<N>,
    block: impl Fn(&[f64; N]) -> Values<N>,
    keeping_lu: bool,
) -> Run<N> {
    trace::take();
    let (calls, last) = (Cell::new(0u32), Cell::new([f64::NAN; N]));
    // Every evaluation marked with its call's number: a copy of an earlier one carries its mark.
    let mut eval = |z: &[f64; N], ev: &mut BlockEval<N, 1>| {
        let (f, j) = block(z);
        *ev = BlockEval { f, j, keep: [f64::from(calls.get())] };
        calls.set(calls.get() + 1);
        last.set(*z);
    };
    let mut ev = BlockEval { f: [f64::NAN; N], j: [[f64::NAN; N]; N], keep: [f64::NAN] };
    eval(&z0, &mut ev);
    let solved = if keeping_lu {
        newton_keeping_lu(z0, &mut ev, cfg, &mut eval, mags, &mut Lu::unfactored())
    } else {
        newton(z0, &mut ev, cfg, &mut eval, mags)
    };
    Run { solved, ev, calls: calls.get(), last: last.get(), paths: trace::take() }
}

impl<const N: usize> Run<N> {
    /// The solution, after checking the contract on it: the slot holds the last call's
    /// evaluation (its mark, and `block`'s values at its argument, bit for bit), made at the
    /// returned position, or at the one a rounding-level correction moved unevaluated; and the
    /// solve counted every call.
    fn returned(&self, block: impl Fn(&[f64; N]) -> Values<N>, mags: &Magnitudes<N>) -> Solved<N> {
        let s = match &self.solved {
            Ok(s) => *s,
            Err(e) => panic!("{e:?} after {:?}", self.paths),
        };
        assert_eq!(self.ev.keep[0], f64::from(self.calls - 1), "not the last call's evaluation: {:?}", self.paths);
        let (f, j) = block(&self.last);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        assert_eq!(bits(&self.ev.f), bits(&f), "residuals");
        assert_eq!(bits(self.ev.j.as_flattened()), bits(j.as_flattened()), "Jacobian");
        assert_eq!(s.evaluations, self.calls, "evaluations counted: {:?}", self.paths);
        if self.paths.last() == Some(&SolvePath::UncheckedCorrection) {
            let dz: [f64; N] = core::array::from_fn(|c| s.z[c] - self.last[c]);
            let step = scaled_step(&dz, &self.last, &mags.unit);
            // The solver's step `dz` was at most `MAX_UNCHECKED_CORRECTION` of the larger of
            // `|last|` and the unit; `last + dz` rounds by half a unit in the last place of the
            // sum, and the difference here by half one of itself: one more epsilon in all.
            let slack = f64::EPSILON;
            assert!(step <= MAX_UNCHECKED_CORRECTION + slack, "{step:e}: {:?} {:?}", s.z, self.last);
        } else {
            assert_eq!(bits(&s.z), bits(&self.last), "the last evaluation's position: {:?}", self.paths);
        }
        s
    }

    fn took(&self, path: SolvePath) -> usize {
        self.paths.iter().filter(|&&p| p == path).count()
    }
}

/// Both entry points.
const ENTRIES: [bool; 2] = [false, true];

/// `x^2 + y^2 = 4`, `y = x^3`: a regular root near `(1.03, 1.72)`.
fn circle(z: &[f64; 2]) -> Values<2> {
    let [x, y] = *z;
    ([x * x + y * y - 4.0, y - x * x * x], [[2.0 * x, 2.0 * y], [-3.0 * x * x, 1.0]])
}

fn circle_mags() -> Magnitudes<2> {
    Magnitudes::new([8.0, 2.0], [1.0, 1.0])
}

/// `block` with a residual far off at the one position `at` (bit for bit): a trial there is
/// rejected, a correction there undone.
fn spoilt_at<const N: usize>(block: impl Fn(&[f64; N]) -> Values<N>, at: [f64; N]) -> impl Fn(&[f64; N]) -> Values<N> {
    move |z| {
        let (mut f, j) = block(z);
        if z.map(f64::to_bits) == at.map(f64::to_bits) {
            f[0] += 1e-3;
        }
        (f, j)
    }
}

/// Full Newton steps to convergence, and a guess at the root corrected unevaluated (one call),
/// corrected and the correction kept, or undone (the guess evaluated again).
#[test]
fn full_steps_and_corrections_of_a_guess() {
    let (cfg, mags) = (NewtonConfig::default(), circle_mags());
    for keeping_lu in ENTRIES {
        let r = run([1.0, 1.0], &cfg, &mags, circle, keeping_lu);
        let root = r.returned(circle, &mags).z;
        assert!(r.took(SolvePath::FullStep) >= 3 && r.took(SolvePath::SearchAccepted) == 0, "{:?}", r.paths);

        let r = run(root, &cfg, &mags, circle, keeping_lu);
        r.returned(circle, &mags);
        assert_eq!((r.calls, &r.paths[..]), (1, &[SolvePath::UncheckedCorrection][..]));

        let near = [root[0] * (1.0 + 1e-13), root[1]];
        let r = run(near, &cfg, &mags, circle, keeping_lu);
        let kept = r.returned(circle, &mags).z;
        assert_eq!((r.calls, &r.paths[..]), (2, &[SolvePath::CorrectionKept][..]));

        let spoilt = spoilt_at(circle, kept);
        let r = run(near, &cfg, &mags, &spoilt, keeping_lu);
        assert_eq!(r.returned(&spoilt, &mags).z, near);
        assert_eq!((r.calls, &r.paths[..]), (3, &[SolvePath::CorrectionUndone][..]));
    }
}

/// A guess just below 1 corrected unevaluated by a step of exactly `MAX_UNCHECKED_CORRECTION`
/// (the largest applied so): `1 - 2^-53 + 2^-48` is a tie between doubles, rounded to the even
/// `1 + 2^-48`, so the returned position is `2^-48 + 2^-53` (16.5 epsilon) from the evaluated
/// one, the rounding beyond the step that `returned` allows.
#[test]
fn a_correction_rounded_beyond_its_step() {
    let last = 1.0 - f64::EPSILON / 2.0;
    let step = MAX_UNCHECKED_CORRECTION;
    // The residual `-2^-48` at `last`, exactly: the Newton step is `2^-48`.
    let tilted = move |z: &[f64; 1]| ([(z[0] - last) - step], [[1.0]]);
    let (cfg, mags) = (NewtonConfig::default(), Magnitudes::new([1.0], [1.0]));
    for keeping_lu in ENTRIES {
        let r = run([last], &cfg, &mags, tilted, keeping_lu);
        let z = r.returned(tilted, &mags).z[0];
        assert_eq!((r.calls, &r.paths[..]), (1, &[SolvePath::UncheckedCorrection][..]));
        assert_eq!(z, 1.0 + step);
        assert_eq!(z - last, step + f64::EPSILON / 2.0);
    }
}

/// The final correction of an iteration evaluated and kept, or undone (the last iterate
/// evaluated again); and an iteration that cannot meet its tolerance, ended on its step test.
#[test]
fn final_corrections_of_an_iteration() {
    let mags = circle_mags();
    // A loose tolerance: the iteration ends with a correction above the rounding level.
    let loose = NewtonConfig { residual_tol: 1e-8, ..NewtonConfig::default() };
    for keeping_lu in ENTRIES {
        let r = run([1.5, 0.5], &loose, &mags, circle, keeping_lu);
        let kept = r.returned(circle, &mags);
        assert_eq!(r.paths.last(), Some(&SolvePath::CorrectionKept), "{:?}", r.paths);
        assert!(kept.iterations > 0);

        let spoilt = spoilt_at(circle, kept.z);
        let r = run([1.5, 0.5], &loose, &mags, &spoilt, keeping_lu);
        let undone = r.returned(&spoilt, &mags);
        assert_eq!(r.paths.last(), Some(&SolvePath::CorrectionUndone), "{:?}", r.paths);
        assert_ne!(undone.z, kept.z);

        let unreachable = NewtonConfig { residual_tol: 0.0, ..NewtonConfig::default() };
        let r = run([1.5, 0.5], &unreachable, &mags, circle, keeping_lu);
        assert_eq!(r.returned(circle, &mags).termination, NewtonStop::StepTolerance);
    }
}

/// `atan(x - 1) = 0` from 3: the full Newton step overshoots to a larger residual (rejected),
/// half of it is accepted.
#[test]
fn a_line_search() {
    let atan = |z: &[f64; 1]| ([(z[0] - 1.0).atan()], [[1.0 / (1.0 + (z[0] - 1.0).powi(2))]]);
    let (cfg, mags) = (NewtonConfig::default(), Magnitudes::new([1.0], [1.0]));
    for keeping_lu in ENTRIES {
        let r = run([3.0], &cfg, &mags, atan, keeping_lu);
        assert!((r.returned(atan, &mags).z[0] - 1.0).abs() <= f64::EPSILON);
        assert_eq!(r.paths.first(), Some(&SolvePath::SearchAccepted), "{:?}", r.paths);
        assert_eq!(r.took(SolvePath::Descend), 0);
    }
}

/// `z = (1/2, -1/4)`, whose Jacobian (the identity) is reported wrongly at the guess
/// `(3/2, -1/4)`: there every Newton and Gauss-Newton direction it gives raises the residual
/// (its true slope along them is positive), so the full step and its search fail (the guess
/// evaluated again), then the descent's three least damped searches fail (the guess's
/// evaluation copied back after each), and its steepest one succeeds. The directions worked out
/// by hand: Newton's `-B^-1 f = (1, 2)` against `f = (1, 0)`; the damped
/// `-(B^T B + trace)^-1 B^T f = (-0.14, 0.175)`.
#[test]
fn a_descent_after_failed_searches() {
    let (guess, target) = ([1.5, -0.25], [0.5, -0.25]);
    let wrong = move |z: &[f64; 2]| {
        let j = if z == &guess { [[1.0, -1.0], [-1.0, 0.5]] } else { [[1.0, 0.0], [0.0, 1.0]] };
        ([z[0] - target[0], z[1] - target[1]], j)
    };
    let (cfg, mags) = (NewtonConfig::default(), Magnitudes::new([1.0, 1.0], [1.0, 1.0]));
    for keeping_lu in ENTRIES {
        let r = run(guess, &cfg, &mags, wrong, keeping_lu);
        let s = r.returned(wrong, &mags);
        assert!(s.z.iter().zip(target).all(|(z, t)| (z - t).abs() <= f64::EPSILON), "{:?}", s.z);
        let (back, descend) = (SolvePath::CopyBack, SolvePath::Descend);
        let start = [SolvePath::Reevaluated, descend, back, back, back, SolvePath::SearchAccepted];
        assert_eq!(r.paths[..6], start, "{:?}", r.paths);
    }
    // At a guess where the circle's Jacobian is singular (`x y = -1/3`) no Newton step is
    // tried: the descent's first search moves.
    let mags = circle_mags();
    for keeping_lu in ENTRIES {
        let r = run([1.0, -1.0 / 3.0], &cfg, &mags, circle, keeping_lu);
        r.returned(circle, &mags);
        assert_eq!(&r.paths[..2], &[SolvePath::Descend, SolvePath::SearchAccepted], "{:?}", r.paths);
    }
}

/// `x^2 = 2.5e-13` from 1 with a unit magnitude: the residual meets the tolerance while Newton
/// still halves the step (linearly, as toward a singular root), at a Jacobian regular by the
/// tolerance: the iteration goes on past the tolerance to the regular root `5e-7`.
#[test]
fn an_iteration_past_the_tolerance() {
    let near_fold = |z: &[f64; 1]| ([z[0] * z[0] - 2.5e-13], [[2.0 * z[0]]]);
    let (cfg, mags) = (NewtonConfig::default(), Magnitudes::new([1.0], [1.0]));
    for keeping_lu in ENTRIES {
        let r = run([1.0], &cfg, &mags, near_fold, keeping_lu);
        let s = r.returned(near_fold, &mags);
        assert!((s.z[0] - 5e-7).abs() <= 1e-15, "{}", s.z[0]);
        assert!(r.took(SolvePath::PastTolerance) > 0, "{:?}", r.paths);
    }
}

/// A residual just above the tolerance, at its rounding floor, that every step makes worse
/// (a block whose values 1e-6 off everywhere but at the guess): the iteration returns the
/// guess, its correction undone.
#[test]
fn an_iterate_at_its_floor() {
    let guess = [0.75];
    let floor = move |z: &[f64; 1]| ([if z == &guess { 1e-10 } else { 1e-6 }], [[1.0]]);
    let (cfg, mags) = (NewtonConfig::default(), Magnitudes::new([1.0], [1.0]));
    for keeping_lu in ENTRIES {
        let r = run(guess, &cfg, &mags, floor, keeping_lu);
        let s = r.returned(floor, &mags);
        assert_eq!((s.z, s.termination), (guess, NewtonStop::StepTolerance));
        assert_eq!(r.took(SolvePath::AtFloor), 1, "{:?}", r.paths);
    }
}

/// `sin q = 1/2` from near the top of the crank (where the first Newton step is long): an angle
/// carried turns away comes back to the guess's turn, evaluated and corrected there, or, with
/// the corrected position spoilt, kept uncorrected (its residual there within the tolerance: the
/// correction undone, the iterate on the guess's turn evaluated again); and `q^3 = 1000` marked
/// as if it repeated every turn: its move is undone.
#[test]
fn angles_back_on_the_guess_turn() {
    let pin = |z: &[f64; 1]| ([z[0].sin() - 0.5], [[z[0].cos()]]);
    let cfg = NewtonConfig::default();
    let mags = Magnitudes::new([1.5], [1.0]).with_turns([true]);
    for keeping_lu in ENTRIES {
        let mut moved = 0;
        for k in 0..40 {
            let g = FRAC_PI_2 + (k as f64 - 19.5) * 1e-4;
            let r = run([g], &cfg, &mags, pin, keeping_lu);
            assert!((r.returned(pin, &mags).z[0] - g).abs() <= PI);
            moved += r.took(SolvePath::TurnsMoved);
        }
        assert!(moved > 2, "{moved} of 40 solves moved back a turn");

        // The move kept while its correction is undone: the correction's position spoilt.
        let mut kept = 0;
        for k in 0..40 {
            let g = FRAC_PI_2 + (k as f64 - 19.5) * 1e-4;
            let r = run([g], &cfg, &mags, pin, keeping_lu);
            if !r.paths.ends_with(&[SolvePath::TurnsMoved, SolvePath::CorrectionKept]) {
                continue;
            }
            let spoilt = spoilt_at(pin, r.returned(pin, &mags).z);
            let r = run([g], &cfg, &mags, &spoilt, keeping_lu);
            let s = r.returned(&spoilt, &mags);
            assert!(r.paths.ends_with(&[SolvePath::TurnsMoved, SolvePath::CorrectionUndone]), "{:?}", r.paths);
            assert!(
                (s.z[0] - g).abs() <= PI && (s.z[0].sin() - 0.5).abs() <= 1.5 * cfg.residual_tol,
                "{g}: {}",
                s.z[0]
            );
            kept += 1;
        }
        assert!(kept > 2, "{kept} of 40 solves kept their move with the correction undone");

        let cube = |z: &[f64; 1]| ([z[0].powi(3) - 1000.0], [[3.0 * z[0] * z[0]]]);
        let marked = Magnitudes::new([1000.0], [1.0]).with_turns([true]);
        let r = run([1.0], &cfg, &marked, cube, keeping_lu);
        assert!((r.returned(cube, &marked).z[0] - 10.0).abs() <= 8.0 * f64::EPSILON);
        assert_eq!(r.took(SolvePath::TurnsUndone), 1, "{:?}", r.paths);
    }
}

/// `0.2 + 2 t - 2 t^2 = 0` with `t = 1 + cos q`, from just past its fold at `q = pi` (a minimum
/// of the residual that is no root): the iteration stalls there, and the restarts reach the
/// roots; the solve from the nearest returns it.
#[test]
fn restarts() {
    let folded = |z: &[f64; 1]| {
        let t = 1.0 + z[0].cos();
        ([0.2 + 2.0 * t - 2.0 * t * t], [[-z[0].sin() * (2.0 - 4.0 * t)]])
    };
    let cfg = NewtonConfig::default();
    let mags = Magnitudes::new([2.2], [1.0]).with_turns([true]);
    for keeping_lu in ENTRIES {
        for side in [0.04, -0.04] {
            let r = run([PI + side], &cfg, &mags, folded, keeping_lu);
            let s = r.returned(folded, &mags);
            assert!(s.residual <= cfg.residual_tol);
            assert_eq!(r.took(SolvePath::Restart), 3, "{:?}", r.paths);
            assert_eq!(r.took(SolvePath::RestartReturned), 1, "{:?}", r.paths);
        }
    }
}
