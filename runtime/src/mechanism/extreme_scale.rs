//! Closed-form blocks at sizes where their squared lengths leave the range of `f64`.
//!
//! A closed form works with squares and products of lengths (`a² + b²` of a dyad, `l²` of an
//! angle equation): for a mechanism whose lengths are about `s`, those are about `s²` (the
//! dyad's rescaled coefficients about `s⁴`, see
//! [`dyad_roots`](crate::solvers::closed::dyad_roots)). Beyond about `1e±150` they overflow or
//! become subnormal, and the closed form fails (a non-finite value, a limit position rounded
//! away, no assembly) where the mechanism is fine: the same mechanism in other units solves.
//! Newton's method judges every residual and step in the magnitudes of the equations and
//! unknowns (see [`newton`](crate::solvers::newton)) and works at every representable size.
//!
//! So where a checked kernel fails for a mechanism outside [`CLOSED_FORM_SIZES`], the position
//! is solved again by Newton over the whole system (its residuals and Jacobian from
//! [`Mechanism::jacobian_flat`](crate::Mechanism::jacobian_flat), from the same guess), and the
//! analogs and outputs at that position by
//! [`Mechanism::kinematics_at_flat`](crate::Mechanism::kinematics_at_flat), whose factorisations
//! are scaled (and for a sensitivity solve, the sensitivities too, by
//! [`Sensitivities::sensitivities_at_flat`](crate::Sensitivities::sensitivities_at_flat); for a
//! solve of the positions alone, [`Mechanism::position_flat`](crate::Mechanism::position_flat),
//! nothing more). Inside the range the kernel's own error stands: nothing changes for a
//! mechanism of ordinary size, and the hot path pays nothing (this runs only after a failure).
//!
//! **Its blocks in turn.** Newton over every unknown at once needs a guess close enough for all
//! the blocks together; the generated solver and the closed forms solve one block at a time,
//! each from its guess with the blocks before it solved. So the rescue solves the blocks in that
//! order too (see [`whole_position`]): a chain of four-bars, each driven by the last one's
//! rocker, solves wherever it does at size 1, and fails where it does, in the same block.
//!
//! **Its failure is the mechanism's.** Where Newton fails, the mechanism has no
//! position there (or none Newton can reach from the guess), and the kernel's own error says
//! the wrong thing: computed with squares out of range, it calls a four-bar whose crank cannot
//! close the loop singular (at `1e-200`) or its equation not finite (at `1e200`), where the same
//! four-bar at size 1 cannot be assembled. So the error is Newton's own failure in the first
//! block that fails, made the error of that block ([`in_block`]), as a failure of the generated
//! Newton solver is: no assembly where the residual stalls at a minimum that is no root, a singular
//! position where the root it reaches has a singular Jacobian, an equation not finite where it
//! leaves its domain. (Save for a solve of the positions alone at a limit position of the input, a
//! root Newton reaches only linearly: the closed form gives its double root there at size 1, and so
//! does the rescue, see [`whole_position`].) Where the iterations run out while the residual still
//! falls, Newton cannot tell a mechanism that does not assemble from one it did not reach, and says
//! so (no convergence). Its tests are made in the magnitudes of the equations and unknowns, so this
//! is the error of the same mechanism at every size. A caller's bad value or an invalid
//! configuration explains the failure at any size: their error stands. Where Newton solves but the
//! analogs at its position fail, theirs.
//!
//! **Its assembly mode is the closed forms'.** A closed form picks one of its two roots by the
//! guess (the sign of its block's Jacobian determinant there); Newton goes wherever it
//! converges, which for a four-bar driven by its rocker was the other assembly mode at about half
//! its inputs, and for the gear-lever's polar length from guesses of either sign, the length of
//! the other sign (the pin's angle half a turn on) at 996 of 2304 solves. So each closed-form block's mode is checked after the solve and mirrored where it
//! differs ([`Block`], see [`whole_position`]): the angles of size 1 at every size.
//!
//! The mechanism is seen through three functions only ([`Whole`]): the entry point that
//! takes a mechanism, `mechanism::rescue`, hands them over, so that this module needs nothing of
//! the mechanism's traits (which call it).

use crate::error::Error;
use crate::kin::Jac;
use crate::kinds::QuantityKind;
use crate::solvers::newton::{
    BlockEval, BlockFailure, Magnitudes, NewtonConfig, NewtonStop, SolveReport, Solved, newton,
};
use crate::solvers::turns::unwrap_to_turn;
use core::cell::Cell;
use core::f64::consts::PI;

/// The sizes (largest magnitude of an equation's terms: the sum of a loop's link lengths) at
/// which every closed form computes exactly: `2^-480 .. 2^480`, about `1e-144 .. 1e144`. Their
/// squares, and the products of two of them, stay normal numbers with 60 binary orders of
/// magnitude to spare for link ratios and small offsets.
pub const CLOSED_FORM_SIZES: (f64, f64) = (1.0 / TWO_480, TWO_480);

/// `2^480`, exact.
const TWO_480: f64 = (1u128 << 120) as f64 * (1u128 << 120) as f64 * (1u128 << 120) as f64 * (1u128 << 120) as f64;

/// Whether equation magnitudes `scale` (the finite ones) put the mechanism outside
/// [`CLOSED_FORM_SIZES`]: its largest beyond either end. A run-time model asks the same
/// (`kinloop_runtime::generated::outside_closed_form_sizes`).
#[doc(hidden)]
pub fn outside_closed_form_sizes(scale: &[f64]) -> bool {
    let size = scale.iter().fold(0.0f64, |s, v| if v.is_finite() { s.max(v.abs()) } else { s });
    size > 0.0 && !(size >= CLOSED_FORM_SIZES.0 && size <= CLOSED_FORM_SIZES.1)
}

/// What the rescue needs of a mechanism: the kinds of its unknowns (which are angles, whose
/// equations repeat every turn), and at input `x`, the whole system's residuals and Jacobian at
/// a position (`jacobian`: [`Mechanism::jacobian_flat`](crate::Mechanism::jacobian_flat)) and
/// the result at a solved one with the report of its solve (`at`: the analogs and outputs of
/// [`Mechanism::kinematics_at_flat`](crate::Mechanism::kinematics_at_flat), or those and the
/// sensitivities of
/// [`Sensitivities::sensitivities_at_flat`](crate::Sensitivities::sensitivities_at_flat)), and
/// the error of a failure of Newton over the whole system (`fail`: the generated solver's
/// error of the block holding the equation it names, see [`in_block`]), and what a limit
/// position gives (`at_limit`: the position for a solve of the positions alone, the singular
/// failure for one of the analogs, see [`AtLimit`]).
pub(crate) struct Whole<J, A, F, const N: usize> {
    pub(crate) kinds: [QuantityKind; N],
    pub(crate) blocks: Vec<Block>,
    pub(crate) at_limit: AtLimit,
    pub(crate) jacobian: J,
    pub(crate) at: A,
    pub(crate) fail: F,
}

/// The answer to a checked kernel's failure `error` at input `x` from `guess`, for the mechanism
/// `m` describes: for a mechanism outside [`CLOSED_FORM_SIZES`], the position solved by Newton
/// over the whole system and `m`'s result there, or where Newton fails, its failure as `m`'s
/// error (where the result fails, the result's error); otherwise `error`. A value given that
/// is not finite, or an invalid configuration, explains the failure at any size: `error`
/// stands.
pub(crate) fn rescue<J, A, F, T, const N: usize, const NI: usize>(
    m: &Whole<J, A, F, N>,
    x: &[f64; NI],
    guess: &[f64; N],
    cfg: &NewtonConfig,
    error: Error,
) -> Result<T, Error>
where
    J: Fn(&[f64; N]) -> Jac<N, NI>,
    A: Fn(&[f64; N], SolveReport) -> Result<T, Error>,
    F: Fn(BlockFailure) -> Error,
{
    if !guess.iter().chain(x.iter()).all(|v| v.is_finite())
        || matches!(error, Error::NonFinite { .. } | Error::InvalidArgument(_))
        || cfg.invalid_field().is_some()
    {
        return Err(error);
    }
    match jacobian_outside(m, guess) {
        Some(jac) => solve_whole(m, guess, cfg, &jac),
        None => Err(error),
    }
}

/// The Jacobian at `guess` when its magnitudes put the mechanism outside
/// [`CLOSED_FORM_SIZES`]. Its own function, the Jacobian moved to the heap: for a large
/// mechanism it is big (512 KiB for 256 unknowns), and in an unoptimised build a frame keeps
/// every value it made, so the common case (an ordinary size, nothing to rescue) must not
/// share one with the whole-system solve.
#[inline(never)]
fn jacobian_outside<J, A, F, const N: usize, const NI: usize>(
    m: &Whole<J, A, F, N>,
    guess: &[f64; N],
) -> Option<Box<Jac<N, NI>>>
where
    J: Fn(&[f64; N]) -> Jac<N, NI>,
{
    let jac = Box::new((m.jacobian)(guess));
    outside_closed_form_sizes(&jac.scale).then_some(jac)
}

/// [`rescue`]'s Newton over the whole system from `guess`, whose Jacobian is `jac`, and `m`'s
/// result at the position it reaches: where Newton fails, its failure as `m`'s error.
#[inline(never)]
fn solve_whole<J, A, F, T, const N: usize, const NI: usize>(
    m: &Whole<J, A, F, N>,
    guess: &[f64; N],
    cfg: &NewtonConfig,
    jac: &Jac<N, NI>,
) -> Result<T, Error>
where
    J: Fn(&[f64; N]) -> Jac<N, NI>,
    A: Fn(&[f64; N], SolveReport) -> Result<T, Error>,
    F: Fn(BlockFailure) -> Error,
{
    let turns = m.kinds.map(|k| k == QuantityKind::Angle);
    let at = |q: &[f64; N], ev: &mut BlockEval<N, 0>| {
        let jq = (m.jacobian)(q);
        ev.f = jq.f;
        ev.j = jq.j;
    };
    let (q, report) =
        whole_position(guess, jac.scale, jac.unit, turns, cfg, m.at_limit, &m.blocks, at).map_err(&m.fail)?;
    (m.at)(&q, report)
}

/// A failure `fail` of Newton over the whole system (its row an index into all the equations,
/// in declaration order) as the failure of one block of the decomposition: the block and the
/// failure with its row that equation's row in the block, where `block_of(row)` gives the
/// block holding equation `row` and its row there. What the generated code and a run-time
/// model make the block's error of, so that it names the equation and the block as a block's
/// own failure does (the block 0 and the row as it is where no block holds it, not reached).
#[doc(hidden)]
pub fn in_block(fail: BlockFailure, block_of: impl Fn(usize) -> Option<(usize, usize)>) -> (usize, BlockFailure) {
    let mut block = 0;
    let fail = with_row(fail, |row| {
        let (b, row) = block_of(row).unwrap_or((0, row));
        block = b;
        row
    });
    (block, fail)
}

/// `fail` with its row `row` made `to(row)` (a failure that names no row as it is).
fn with_row(fail: BlockFailure, mut to: impl FnMut(usize) -> usize) -> BlockFailure {
    match fail {
        BlockFailure::NonFinite { row, iterations } => BlockFailure::NonFinite { row: to(row), iterations },
        BlockFailure::NoConvergence { row, iterations, residual } => {
            BlockFailure::NoConvergence { row: to(row), iterations, residual }
        }
        BlockFailure::NoAssembly { row, iterations, evaluations, residual } => {
            BlockFailure::NoAssembly { row: to(row), iterations, evaluations, residual }
        }
        BlockFailure::Singular { row, iterations, residual, pivot_ratio, tolerance } => {
            BlockFailure::Singular { row: to(row), iterations, residual, pivot_ratio, tolerance }
        }
        BlockFailure::Underflow { row, magnitude, least } => BlockFailure::Underflow { row: to(row), magnitude, least },
        BlockFailure::Overflow { row } => BlockFailure::Overflow { row: to(row) },
        other @ (BlockFailure::InvalidConfig { .. } | BlockFailure::TooManyTurns { .. }) => other,
    }
}

/// What Newton over the whole system gives at a limit position of the input (a root it reaches
/// only linearly, where two assembly modes meet and the Jacobian is singular), where a closed
/// form gives its double root: the position, for a solve of the positions alone (the compiled
/// `position_flat`, the run-time model's `positions`), as the closed form does at size 1; or
/// Newton's singular failure, for a solve of the analogs, as the closed form's analogs fail
/// there (they are not determined: see [`whole_position`]).
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AtLimit {
    /// The position, to the rounding of the residual (see [`whole_position`]).
    Position,
    /// Newton's [`BlockFailure::Singular`].
    Singular,
}

/// The position of a mechanism of `N` unknowns solved by Newton over the whole system from
/// `guess`: `scale` its equations' magnitudes and `unit` its unknowns' units at the guess (a
/// unit that is not finite and positive counts as one), `turns` which unknowns are angles, and
/// `at(q, ev)` writing the residuals and the Jacobian at `q` into `ev` (a residual NaN where they
/// cannot be evaluated, which Newton refuses). The iteration runs in dimensionless unknowns
/// `z = q / unit` (radians for an angle, fractions of its loop's size for a length), so that the
/// columns of the Jacobian are of one magnitude, as a block of the generated Newton solver has
/// them. The position and the solve's report, or Newton's failure (its row an index into the
/// whole system's equations). What a compiled mechanism's [`rescue`] and a run-time model's
/// solve, to the same bits.
///
/// **Its blocks.** `blocks` are the mechanism's blocks in solve order (see [`solve_blocks`]).
/// Two or more are solved in turn ([`in_order`]), each as the whole system of one block is, and
/// the first one's failure is the failure. Each closed-form block is left in the assembly mode
/// its closed form picks from `guess` at any ordinary size, where Newton reached the other (see
/// `keep_modes`).
///
/// **At a limit position.** Newton approaches a root where the Jacobian is singular (a limit
/// position, where two assembly modes meet) only linearly, each step about half the last, and fails
/// there as singular: on a four-bar driven by its rocker (rocker 3, coupler 3.5, crank 1, frame 4)
/// the residual meets its tolerance `1e-6` rad from the root, and the steps past it (which tell a
/// root just inside the limit from a singular one) leave its coupler `4e-8` to `6e-8` rad from it,
/// its loop open by `4.5 eps` of its size. A closed form gives that position at size 1, its double
/// root to about the square root of the rounding. So for [`AtLimit::Position`] the solve is made
/// again from the evaluated position of least residual, with tolerances 0 and no restarts
/// (`limit_position`): down to the rounding of the residual, where the position is known to about
/// `sqrt(eps)` of the size. Where it converges (a root just inside the limit, told from its twin
/// across the fold) that root, otherwise the position of least residual evaluated, where it meets
/// the residual tolerance. For [`AtLimit::Singular`] the failure stands: the analogs at a position
/// that close to the fold are not determined (they grow as one over its distance from it, known
/// only to that distance's rounding), and the closed form's fail as singular there too.
#[doc(hidden)]
#[allow(clippy::too_many_arguments)]
pub fn whole_position<const N: usize>(
    guess: &[f64; N],
    scale: [f64; N],
    unit: [f64; N],
    turns: [bool; N],
    cfg: &NewtonConfig,
    at_limit: AtLimit,
    blocks: &[Block],
    mut at: impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Result<([f64; N], SolveReport), BlockFailure> {
    let unit = unit.map(|u| if u > 0.0 && u.is_finite() { u } else { 1.0 });
    match in_order(guess, scale, unit, turns, cfg, at_limit, blocks, &mut at) {
        Some(solved) => solved,
        None => solve_all(guess, scale, unit, turns, cfg, at_limit, blocks, &mut at),
    }
}

/// [`whole_position`]'s Newton over all `N` unknowns at once (`unit` positive and finite), each
/// closed-form block of `blocks` kept in its assembly mode: what it solves first, and what
/// [`in_order`] solves each block by.
#[allow(clippy::too_many_arguments)]
fn solve_all<const N: usize>(
    guess: &[f64; N],
    scale: [f64; N],
    unit: [f64; N],
    turns: [bool; N],
    cfg: &NewtonConfig,
    at_limit: AtLimit,
    blocks: &[Block],
    mut at: impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Result<([f64; N], SolveReport), BlockFailure> {
    let mags = Magnitudes::new(scale, [1.0; N]).with_turns(turns);
    let q_of = |z: &[f64; N]| core::array::from_fn::<f64, N, _>(|u| z[u] * unit[u]);
    // The evaluated position of least scaled residual, `max_r |f_r| / scale_r` (a NaN never
    // least), and the count of evaluations: what a limit position is solved again from and
    // reported with (`limit_position`). Read only after a failure; they change no step.
    let least = Cell::new((f64::INFINITY, [0.0; N]));
    let evaluations = Cell::new(0u32);
    // Written over the solver's slot, as the generated blocks' evaluations are.
    let mut eval = |z: &[f64; N], ev: &mut BlockEval<N, 0>| {
        at(&q_of(z), ev);
        for row in &mut ev.j {
            for u in 0..N {
                row[u] *= unit[u];
            }
        }
        let rho = scaled_residual(&ev.f, &scale);
        // Written so that a NaN residual is never the least.
        if rho < least.get().0 && ev.f.iter().all(|f| !f.is_nan()) {
            least.set((rho, *z));
        }
        evaluations.set(evaluations.get() + 1);
    };
    let z0 = core::array::from_fn::<f64, N, _>(|u| guess[u] / unit[u]);
    let mut ev = blank_evaluation::<N>();
    eval(&z0, &mut ev);
    let solved = match newton(z0, &mut ev, cfg, &mut eval, &mags) {
        Ok(solved) => solved,
        Err(fail @ BlockFailure::Singular { .. }) if at_limit == AtLimit::Position => {
            limit_position(fail, &least, &evaluations, cfg, &mags, &mut eval)?
        }
        Err(fail) => return Err(fail),
    };
    let solved = if blocks.iter().any(|b| b.closed_form) {
        keep_modes(solved, &z0, unit, scale, turns, blocks, cfg, &mags, &mut eval)?
    } else {
        solved
    };
    let mut report = SolveReport::direct();
    report.absorb(&solved);
    Ok((q_of(&solved.z), report))
}

/// [`whole_position`] block by block, in solve order: each block's unknowns solved from the
/// guess with the blocks before it at their roots and those after it at the guess, as the
/// generated solver and the closed forms solve them at any ordinary size. Newton over all the
/// unknowns at once needs a guess close enough for every block together: on 108 chains of five
/// four-bars, each driven by the last one's rocker, at 12 inputs and 4 sizes, it failed in 66 of
/// 5184 solves where size 1 solves, left an angle a turn off in 16, and named another block or
/// error than size 1 in 2054 of the failures. Tried first, with the blocks in turn only where it
/// failed, it still gave another assembly mode or turn in 28 of 10368 solves (at 24 inputs) and
/// solved 21 where size 1 fails: its restarts, and its solve again after a block mirrored onto
/// its mode (`keep_modes`), move the blocks before that one. Its failure is the first failing
/// block's, the one the same mechanism names at size 1. `None` where `blocks` does not
/// partition the system into blocks of at most 16 unknowns (the dense sizes), or is a single
/// block: then the whole system is solved at once.
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn in_order<const N: usize>(
    guess: &[f64; N],
    scale: [f64; N],
    unit: [f64; N],
    turns: [bool; N],
    cfg: &NewtonConfig,
    at_limit: AtLimit,
    blocks: &[Block],
    at: &mut impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Option<Result<([f64; N], SolveReport), BlockFailure>> {
    if !partitions::<N>(blocks) || blocks.len() < 2 {
        return None;
    }
    let at: &mut dyn FnMut(&[f64; N], &mut BlockEval<N, 0>) = at;
    let mut q = *guess;
    let mut report = SolveReport::direct();
    for block in blocks {
        let solve = match block.cols.len() {
            1 => solve_block::<1, N>,
            2 => solve_block::<2, N>,
            _ => solve_block::<16, N>,
        };
        let Walk { to, report: solved } = match solve(&q, block, scale, unit, turns, cfg, at_limit, at) {
            Ok(walk) => walk,
            Err(fail) => return Some(Err(fail)),
        };
        q = to;
        report.iterations += solved.iterations;
        report.evaluations += solved.evaluations;
        report.residual = report.residual.max(solved.residual);
        report.termination = report.termination.max(solved.termination);
    }
    Some(Ok((q, report)))
}

/// Whether `blocks` partition a system of `N` equations and unknowns into square blocks of 1
/// to 16 unknowns: every row and every column in exactly one block.
fn partitions<const N: usize>(blocks: &[Block]) -> bool {
    let mut rows = [false; N];
    let mut cols = [false; N];
    let mark = |seen: &mut [bool; N], i: usize| i < N && !core::mem::replace(&mut seen[i], true);
    let square = blocks.iter().all(|b| {
        (1..=16).contains(&b.cols.len())
            && b.rows.len() == b.cols.len()
            && b.rows.iter().all(|&r| mark(&mut rows, r))
            && b.cols.iter().all(|&u| mark(&mut cols, u))
    });
    square && rows.iter().chain(&cols).all(|&seen| seen)
}

/// The whole system's position after one block of [`in_order`] and that block's solve report.
struct Walk<const N: usize> {
    to: [f64; N],
    report: SolveReport,
}

/// `block` of the whole system solved from the position `q` (its own unknowns' guesses, the
/// other unknowns held), as a system of `K` unknowns by [`solve_all`]: the block's `n <= K`
/// equations and unknowns first, then `K - n` padding rows `z_i = 0` from `z_i = 0`, whose
/// residual and step are zero at every iteration (so that three block sizes, 1, 2 and 16, serve
/// every block without a solver instantiated for each). A failure's row is the whole system's.
#[allow(clippy::too_many_arguments)]
fn solve_block<const K: usize, const N: usize>(
    q: &[f64; N],
    block: &Block,
    scale: [f64; N],
    unit: [f64; N],
    turns: [bool; N],
    cfg: &NewtonConfig,
    at_limit: AtLimit,
    at: &mut dyn FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Result<Walk<N>, BlockFailure> {
    let (rows, cols) = (&block.rows[..], &block.cols[..]);
    let n = cols.len();
    let pick = |v: &[f64; N], pad: f64| core::array::from_fn::<f64, K, _>(|i| cols.get(i).map_or(pad, |&u| v[u]));
    let guess = pick(q, 0.0);
    let scale = core::array::from_fn(|i| rows.get(i).map_or(1.0, |&r| scale[r]));
    let turns = core::array::from_fn(|i| cols.get(i).is_some_and(|&u| turns[u]));
    let own = [Block { rows: (0..n).collect(), cols: (0..n).collect(), closed_form: block.closed_form }];
    let mut whole = blank_evaluation::<N>();
    let mut full = *q;
    // Behind `dyn`, as `at` is: one solver of each size serves every mechanism's blocks.
    let in_block: &mut dyn FnMut(&[f64; K], &mut BlockEval<K, 0>) = &mut |z, ev| {
        for (i, &u) in cols.iter().enumerate() {
            full[u] = z[i];
        }
        at(&full, &mut whole);
        for i in 0..K {
            ev.f[i] = rows.get(i).map_or(z[i], |&r| whole.f[r]);
            for j in 0..K {
                ev.j[i][j] = match (rows.get(i), cols.get(j)) {
                    (Some(&r), Some(&u)) => whole.j[r][u],
                    (Some(_), None) | (None, Some(_)) => 0.0,
                    (None, None) => f64::from(u8::from(i == j)),
                };
            }
        }
    };
    let as_whole = |row: usize| rows.get(row).copied().unwrap_or(rows[0]);
    let (z, report) = solve_all(&guess, scale, pick(&unit, 1.0), turns, cfg, at_limit, &own, in_block)
        .map_err(|fail| with_row(fail, as_whole))?;
    let mut to = *q;
    for (i, &u) in cols.iter().enumerate() {
        to[u] = z[i];
    }
    Ok(Walk { to, report })
}

/// A block of a mechanism's decomposition as [`whole_position`] sees it: its equations
/// (indices into the whole system's, in the block's order), its unknowns, and whether it is a
/// closed-form block whose root is kept in the assembly mode the closed form picks from the
/// guess: one angle (`a cos q + b sin q = c`), a dyad's two angles (two links of fixed lengths
/// closing a loop), or an angle and a length (a length along a turning direction, or a slider).
/// Made by [`solve_blocks`].
#[doc(hidden)]
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    /// The block's equations, as rows of the whole system.
    pub rows: Vec<usize>,
    /// The block's unknowns, as columns of the whole system.
    pub cols: Vec<usize>,
    /// Whether its assembly mode is kept (see `keep_modes`).
    pub closed_form: bool,
}

/// The blocks of a mechanism, in solve order, as [`whole_position`] takes them: `blocks` each
/// block's rows and columns (of the whole system), `closed_form_angles` which unknowns closed
/// forms give as angles (`Mechanism::CLOSED_FORM_ANGLES`). A square block of one or two
/// unknowns, one of them such an angle, is a closed form (an angle equation, a dyad, a length
/// and its angle, an angle and a slider), which picks its root by the sign of the block's
/// Jacobian determinant at the guess (see `keep_modes`).
/// What the compiled rescue and a run-time model both give [`whole_position`].
#[doc(hidden)]
pub fn solve_blocks(
    blocks: impl IntoIterator<Item = (Vec<usize>, Vec<usize>)>,
    closed_form_angles: &[bool],
) -> Vec<Block> {
    blocks
        .into_iter()
        .map(|(rows, cols)| {
            let closed_form = (1..=2).contains(&cols.len())
                && rows.len() == cols.len()
                && cols.iter().any(|&u| closed_form_angles.get(u).copied().unwrap_or(false));
            Block { rows, cols, closed_form }
        })
        .collect()
}

/// The sign of the determinant of `block`'s diagonal block of the Jacobian in `ev` (0 where it
/// is zero or not a number): each row divided by its largest entry first, so that the products
/// of lengths about `1e±200` neither overflow nor underflow (a positive factor keeps the sign).
fn det_sign<const N: usize>(ev: &BlockEval<N, 0>, block: &Block) -> f64 {
    let row = |r: usize| {
        let v: [f64; 2] = core::array::from_fn(|i| block.cols.get(i).map_or(0.0, |&u| ev.j[r][u]));
        let m = v[0].abs().max(v[1].abs());
        if m > 0.0 { v.map(|x| x / m) } else { v }
    };
    let det = match block.rows[..] {
        [r] => row(r)[0],
        [r0, r1] => {
            let (a, b) = (row(r0), row(r1));
            a[0] * b[1] - a[1] * b[0]
        }
        _ => 0.0,
    };
    if det > 0.0 {
        1.0
    } else if det < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// [`whole_position`]'s `solved` with each closed-form block of `blocks` (in solve order) in
/// the assembly mode its closed form picks from the guess `z0` at size 1. A closed form's root
/// is the one whose block Jacobian's determinant has the sign it has at the guess (the blocks
/// before it solved): for `a cos q + b sin q = c` the root where `h' = b cos q - a sin q` has
/// the sign of `h'` at the guess, for a dyad the one whose links' cross product has the sign of
/// the guess's, for a length `s` along a turning direction `w(q)` (`s w(q) + e = 0`) the one
/// whose length has the guess's sign (the determinant is `s` times `w × w'`, of one sign), and
/// for an angle and a slider (`m (cos q, sin q) + d s + e = 0`) the root of the slider-free
/// combination `d1 row0 - d0 row1`, an angle equation whose `h'` is the determinant
/// (`codegen/src/emit/closed_form.rs`); the determinant vanishes only at a limit
/// position, where the two modes meet. Newton goes wherever it converges: a four-bar driven by
/// its rocker, from its declared guess, reached the other mode at about half its inputs. So
/// where a block's sign differs from the guess's, its other root is taken (the mirror image,
/// found from the block's residuals alone: [`mirror`]) and Newton solved again from there: the
/// blocks up to it are at their roots, and the whole Jacobian is block-triangular, so its steps
/// solve the blocks after it and leave those. Where a sign is zero (a limit position), nothing
/// changes.
#[cold]
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn keep_modes<const N: usize>(
    mut solved: Solved<N>,
    z0: &[f64; N],
    unit: [f64; N],
    scale: [f64; N],
    turns: [bool; N],
    blocks: &[Block],
    cfg: &NewtonConfig,
    mags: &Magnitudes<N>,
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Result<Solved<N>, BlockFailure> {
    let mut ev = blank_evaluation::<N>();
    for block in blocks.iter().filter(|b| b.closed_form) {
        let z = solved.z;
        let mut at_guess = z;
        for &u in &block.cols {
            at_guess[u] = z0[u];
        }
        eval(&at_guess, &mut ev);
        let want = det_sign(&ev, block);
        eval(&z, &mut ev);
        let have = det_sign(&ev, block);
        solved.evaluations += 2;
        if want == 0.0 || have == 0.0 || want == have {
            continue;
        }
        // `mirror`'s evaluations and the one at its image below, counted as they are made.
        let mut counted = |z: &[f64; N], ev: &mut BlockEval<N, 0>| {
            solved.evaluations += 1;
            eval(z, ev);
        };
        let mirrored = mirror(&z, z0, unit, turns, scale, cfg, block, &mut counted);
        let Some(mirrored) = mirrored else { continue };
        counted(&mirrored, &mut ev);
        // The whole system solved already (the block the last, or those after it unmoved): the
        // mirror image itself. Newton's last correction, applied even at a root, is about the
        // rounding of the residual over the determinant, which near a limit position is
        // `1e-7` rad where the two modes are closer than that (measured on the four-bar driven
        // by its rocker at its limit: its coupler moved by `6e-7` rad).
        let rho = scaled_residual(&ev.f, &scale);
        if rho <= cfg.residual_tol {
            solved = Solved { z: mirrored, residual: rho, ..solved };
            continue;
        }
        let again = newton(mirrored, &mut ev, cfg, &mut *eval, mags)?;
        solved = Solved {
            iterations: solved.iterations + again.iterations,
            evaluations: solved.evaluations + again.evaluations,
            ..again
        };
    }
    Ok(solved)
}

/// The other root of `block` at `z` (a root of the whole system, in units `unit`, `turns` its
/// angles), with its angles on the turns of the guess `z0`, the other unknowns as they are: `None`
/// where it is not finite. Every closed form is linear in the sines and cosines of its angles,
/// so the residuals at `z` and with an angle half a turn on give the block's terms without
/// knowing its coefficients, in the equations' own magnitudes (no products of lengths, which
/// leave `f64` at these sizes). One angle, `f(q) = A cos q + B sin q - C`: with `P = (f(q) -
/// f(q + π)) / 2 = A cos q + B sin q` and `Q = f'(q) = B cos q - A sin q`, `atan2(Q, P)` is the
/// turn from `q` to the axis `atan2(B, A)` the two roots are symmetric about, so the other root
/// is `q + 2 atan2(Q, P)`. A dyad, `F = E + w0(q0) + w1(q1)` with `w_i` a link turning with its
/// angle (`w_i = (F(q) - F(q_i + π)) / 2`, turning one way or the other, `ε_i` the sign of `w_i
/// × dw_i/dq_i`): the other root is the mirror image across the line of `E`, each `w_i`
/// reflected, each angle turned by `2 ε_i (angle(E) - angle(w_i))`. An angle `q` with a length
/// `s`: along a turning direction (`s w(q) + e = 0`, `w(q + π) = -w(q)`) the other root is `(q +
/// π, -s)`, which its residuals (`scale`, `cfg`'s tolerance) tell; with a slider of fixed
/// direction `d` (`m (cos q, sin q) + d s + e = 0`) the angle's other root is the one angle
/// equation's of `d1 F0 - d0 F1` (`d` the slider's Jacobian column, rows normalised as in
/// [`det_sign`]), its length left to Newton's solve from there.
#[allow(clippy::too_many_arguments)]
fn mirror<const N: usize>(
    z: &[f64; N],
    z0: &[f64; N],
    unit: [f64; N],
    turns: [bool; N],
    scale: [f64; N],
    cfg: &NewtonConfig,
    block: &Block,
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Option<[f64; N]> {
    let mut ev = blank_evaluation::<N>();
    eval(z, &mut ev);
    let (f, j) = (ev.f, ev.j);
    // The residuals with angle `u` half a turn on and, where `negated` names one, that unknown
    // negated.
    let mut turned = |u: usize, negated: Option<usize>, ev: &mut BlockEval<N, 0>| {
        let mut half = *z;
        half[u] += PI / unit[u];
        if let Some(s) = negated {
            half[s] = -z[s];
        }
        eval(&half, ev);
        ev.f
    };
    // The block's terms that turn with angle `u`: half the difference of the residuals at `z`
    // and with `u` half a turn on (halved first, so that nothing overflows).
    let halves = |g: [f64; N]| {
        let half_difference = |r: usize| f[r] / 2.0 - g[r] / 2.0;
        [half_difference(block.rows[0]), block.rows.get(1).map_or(0.0, |&r| half_difference(r))]
    };
    // The turn from angle `u` to the other root of the angle equation `g`, given `g`'s turning
    // terms `p` and its derivative `dg` (by `z[u]`).
    let other_angle = |u: usize, p: f64, dg: f64| z[u] + 2.0 * (dg / unit[u]).atan2(p) / unit[u];
    let mut out = *z;
    match (&block.rows[..], &block.cols[..]) {
        (&[r], &[u]) => {
            let p = halves(turned(u, None, &mut ev))[0];
            out[u] = other_angle(u, p, j[r][u]);
        }
        (&[r0, r1], &[u0, u1]) if turns[u0] && turns[u1] => {
            let w = [halves(turned(u0, None, &mut ev)), halves(turned(u1, None, &mut ev))];
            let e = [f[r0] - w[0][0] - w[1][0], f[r1] - w[0][1] - w[1][1]];
            let to_e = e[1].atan2(e[0]);
            for (i, &u) in [u0, u1].iter().enumerate() {
                // The sign of `w × dw/dq` from the row-normalised values (see `det_sign`).
                let m = w[i][0].abs().max(w[i][1].abs());
                let d = [j[r0][u], j[r1][u]];
                let n = d[0].abs().max(d[1].abs());
                if !(m > 0.0 && n > 0.0) {
                    return None;
                }
                let cross = (w[i][0] / m) * (d[1] / n) - (w[i][1] / m) * (d[0] / n);
                let eps = if cross > 0.0 { 1.0 } else { -1.0 };
                out[u] = z[u] + eps * 2.0 * (to_e - w[i][1].atan2(w[i][0])) / unit[u];
            }
        }
        (&[r0, r1], &[c0, c1]) if turns[c0] != turns[c1] => {
            let (u, s) = if turns[c0] { (c0, c1) } else { (c1, c0) };
            let g = turned(u, Some(s), &mut ev);
            if g[r0].abs() / scale[r0] <= cfg.residual_tol && g[r1].abs() / scale[r1] <= cfg.residual_tol {
                out[u] = z[u] + PI / unit[u];
                out[s] = -z[s];
            } else {
                let n = j[r0][s].abs().max(j[r1][s].abs());
                if n.is_nan() || n == 0.0 {
                    return None;
                }
                let d = [j[r0][s] / n, j[r1][s] / n];
                let w = halves(turned(u, None, &mut ev));
                out[u] = other_angle(u, d[1] * w[0] - d[0] * w[1], d[1] * j[r0][u] - d[0] * j[r1][u]);
            }
        }
        _ => return None,
    }
    for &u in block.cols.iter().filter(|&&u| turns[u]) {
        out[u] = unwrap_to_turn(out[u] * unit[u], z0[u] * unit[u]) / unit[u];
    }
    out.iter().all(|v| v.is_finite()).then_some(out)
}

/// [`whole_position`]'s positions where Newton's solve failed as singular (`fail`), at a limit
/// position or beside one: solved again from the evaluated position of least residual
/// (`least`; `evaluations` counts them, both updated by `eval`) with tolerances 0 and no
/// restarts (a root reached from a turned guess would be another assembly mode), so that the
/// iteration runs down to the rounding of the residual. Where it converges, the root (just
/// inside the limit, told from its twin across the fold); where it fails too (the root is a
/// double one to working accuracy), the position of least residual over both solves, if it
/// meets `cfg`'s residual tolerance (as a closed form's double root within the tolerance of
/// the limit is the position); otherwise `fail`.
#[cold]
#[inline(never)]
fn limit_position<const N: usize>(
    fail: BlockFailure,
    least: &Cell<(f64, [f64; N])>,
    evaluations: &Cell<u32>,
    cfg: &NewtonConfig,
    mags: &Magnitudes<N>,
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Result<Solved<N>, BlockFailure> {
    let iterations = |f: &BlockFailure| match *f {
        BlockFailure::Singular { iterations, .. }
        | BlockFailure::NoAssembly { iterations, .. }
        | BlockFailure::NoConvergence { iterations, .. }
        | BlockFailure::NonFinite { iterations, .. } => iterations,
        _ => 0,
    };
    let (rho, z) = least.get();
    if !rho.is_finite() {
        return Err(fail);
    }
    let fine = cfg.with_residual_tol(0.0).with_step_tol(0.0).with_restarts(false);
    let mut ev = blank_evaluation::<N>();
    eval(&z, &mut ev);
    let again = match newton(z, &mut ev, &fine, &mut *eval, mags) {
        Ok(mut solved) => {
            solved.iterations += iterations(&fail);
            solved.evaluations = evaluations.get();
            return Ok(solved);
        }
        Err(again) => again,
    };
    let (rho, z) = least.get();
    if rho <= cfg.residual_tol {
        return Ok(Solved {
            z,
            iterations: iterations(&fail) + iterations(&again),
            evaluations: evaluations.get(),
            residual: rho,
            termination: NewtonStop::StepTolerance,
        });
    }
    Err(fail)
}

/// An evaluation to be written by the caller's closure (its values are never read first).
fn blank_evaluation<const N: usize>() -> BlockEval<N, 0> {
    BlockEval { f: [0.0; N], j: [[0.0; N]; N], keep: [] }
}

/// The largest residual over its row's magnitude: the measure the rescue's tolerance applies to.
fn scaled_residual<const N: usize>(f: &[f64; N], scale: &[f64; N]) -> f64 {
    (0..N).fold(0.0f64, |m, r| m.max(f[r].abs() / scale[r]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A failure in row 3 of a system whose blocks hold rows `[0, 1]`, `[4]` and `[2, 3]` is
    /// the third block's, in its row 1; a failure that names no row stays as it is.
    #[test]
    fn a_whole_systems_failure_is_its_equations_blocks() {
        let blocks: [&[usize]; 3] = [&[0, 1], &[4], &[2, 3]];
        let block_of = |row: usize| {
            blocks.iter().enumerate().find_map(|(b, rows)| Some((b, rows.iter().position(|&r| r == row)?)))
        };
        let fail = BlockFailure::NoAssembly { row: 3, iterations: 7, evaluations: 9, residual: 0.25 };
        assert_eq!(
            in_block(fail, block_of),
            (2, BlockFailure::NoAssembly { row: 1, iterations: 7, evaluations: 9, residual: 0.25 })
        );
        let fail = BlockFailure::NonFinite { row: 4, iterations: 2 };
        assert_eq!(in_block(fail, block_of), (1, BlockFailure::NonFinite { row: 0, iterations: 2 }));
        let fail =
            BlockFailure::Singular { row: 1, iterations: 3, residual: 1e-12, pivot_ratio: 1e-13, tolerance: 1e-10 };
        assert_eq!(in_block(fail, block_of).0, 0);
        let fail = BlockFailure::NoConvergence { row: 2, iterations: 50, residual: 1e-3 };
        assert_eq!(
            in_block(fail, block_of),
            (2, BlockFailure::NoConvergence { row: 0, iterations: 50, residual: 1e-3 })
        );
        let fail = BlockFailure::InvalidConfig { field: "max_iterations" };
        assert_eq!(in_block(fail, block_of), (0, fail));
    }

    /// `cos q = c`, a crank's end reaching a line at `c`: a limit position of `c` at 1, where
    /// the two roots `±acos c` meet at 0. Its scale `|cos q| + |c|`, `q` an angle from 0.5.
    fn reach(c: f64, at_limit: AtLimit) -> Result<([f64; 1], SolveReport), BlockFailure> {
        let at = |q: &[f64; 1], ev: &mut BlockEval<1, 0>| {
            ev.f = [q[0].cos() - c];
            ev.j = [[-q[0].sin()]];
        };
        whole_position(&[0.5], [1.0 + c.abs()], [1.0], [true], &NewtonConfig::default(), at_limit, &[], at)
    }

    /// At a limit position Newton reaches the double root only linearly and fails as singular;
    /// for the positions alone it is the position, to the residual's rounding: `q^2 / 2` within
    /// `3 eps` of the scale 2, `|q| <= sqrt(12 eps)`. Just inside (`c = 1 - 1e-13`, the roots
    /// `9e-7` apart, within the residual tolerance of each other) the root itself, to its
    /// rounding over the slope (`eps / sin q`), not a point between the two. Beyond by less than
    /// the tolerance (`1e-14`) the fold, as a closed form's limit rounded past; beyond by more
    /// (`1e-6`), no position.
    #[test]
    fn a_limit_position_is_the_position_of_the_positions_alone() {
        for c in [1.0, 1.0 - 1e-13, 1.0 + 1e-14] {
            let fail = reach(c, AtLimit::Singular).unwrap_err();
            assert!(matches!(fail, BlockFailure::Singular { .. }), "c = {c}: {fail:?}");
            let (q, report) = reach(c, AtLimit::Position).unwrap_or_else(|f| panic!("c = {c}: {f:?}"));
            let root = c.min(1.0).acos();
            let within = if c < 1.0 { 4.0 * f64::EPSILON / root.sin() } else { (12.0 * f64::EPSILON).sqrt() };
            assert!((q[0] - root).abs() <= within, "c = {c}: {} against {root}", q[0]);
            assert!(report.residual <= NewtonConfig::default().residual_tol, "c = {c}: {report:?}");
        }
        assert!(reach(1.0 + 1e-6, AtLimit::Position).is_err());
    }

    /// `2 cos q + sin q = 1` times `1e200` (terms whose squares leave `f64`): roots `π/2` (where
    /// `h' = cos q - 2 sin q < 0`) and `-atan(3/4)` (`h' > 0`). From guesses where `h' > 0` the
    /// closed form's root is the second, from those where `h' < 0` the first, whichever Newton
    /// reaches (`modes` names the block): from `0.44`, just short of the axis `atan(1/2)` where
    /// `h'` changes sign, Newton alone reached `π/2`.
    #[test]
    fn an_angle_equation_keeps_the_guess_s_root() {
        let k = 1e200;
        let at = |q: &[f64; 1], ev: &mut BlockEval<1, 0>| {
            ev.f = [2.0 * k * q[0].cos() + k * q[0].sin() - k];
            ev.j = [[-2.0 * k * q[0].sin() + k * q[0].cos()]];
        };
        let modes = [Block { rows: vec![0], cols: vec![0], closed_form: true }];
        let (up, down) = (core::f64::consts::FRAC_PI_2, -(0.75f64).atan());
        for g in [-2.0, -1.0, 0.0, 0.3, 0.4, 0.44, 0.48, 0.52, 0.6, 1.0, 2.0, 3.0] {
            let root = unwrap_to_turn(if f64::cos(g) - 2.0 * f64::sin(g) > 0.0 { down } else { up }, g);
            let (q, _) =
                whole_position(&[g], [4.0 * k], [1.0], [true], &NewtonConfig::default(), AtLimit::Singular, &modes, at)
                    .unwrap_or_else(|f| panic!("from {g}: {f:?}"));
            // On the guess's turn, as the closed form's, within a few ulps: the rounding of terms
            // of magnitude 4 over `|h'| = sqrt(5)` at either root.
            assert!((q[0] - root).abs() < 1e-14, "from {g}: {} against {root}", q[0]);
        }
    }

    /// The same angle equation with a slider `s` of fixed direction, times `1e200`:
    /// `F0 = 2 cos q + sin q - 1`, `F1 = cos q - sin q / 2 + s`, mixed (`G0 = F0 + F1 / 2`,
    /// `G1 = F1 - 0.3 F0`, so that both rows hold `s`: `m (cos q, sin q) + d s + e = 0`). The
    /// slider-free combination is `F0` again, and the determinant `1.15 F0'`: the closed form's
    /// root is the one of `F0` where `h'` has the guess's sign, `s` from `F1`. From 900 guesses
    /// (`q` every 0.02 rad of a turn, `s` 0, 3 or -3) Newton alone reached the other root from
    /// 55 (`closed_form` off; at least 10 asserted below, so that the test is of the mirror).
    #[test]
    fn an_angle_and_a_slider_keep_the_guess_s_root() {
        let k = 1e200;
        let at = |z: &[f64; 2], ev: &mut BlockEval<2, 0>| {
            let (c, s) = (z[0].cos(), z[0].sin());
            let f = [2.0 * c + s - 1.0, c - s / 2.0 + z[1]];
            let df = [[-2.0 * s + c, 0.0], [-s - c / 2.0, 1.0]];
            ev.f = [k * (f[0] + f[1] / 2.0), k * (f[1] - 0.3 * f[0])];
            ev.j = [
                [k * (df[0][0] + df[1][0] / 2.0), k * df[1][1] / 2.0],
                [k * (df[1][0] - 0.3 * df[0][0]), k * df[1][1]],
            ];
        };
        let (up, down) = (core::f64::consts::FRAC_PI_2, -(0.75f64).atan());
        let solve = |guess: [f64; 2], closed_form: bool| {
            let blocks = [Block { rows: vec![0, 1], cols: vec![0, 1], closed_form }];
            let cfg = NewtonConfig::default();
            whole_position(&guess, [6.0 * k; 2], [1.0, 1.0], [true, false], &cfg, AtLimit::Singular, &blocks, at)
                .unwrap_or_else(|f| panic!("from {guess:?}: {f:?}"))
                .0
        };
        let mut other = 0;
        for s0 in [0.0, 3.0, -3.0] {
            for i in 0..300 {
                let g = -3.0 + 0.02 * f64::from(i);
                let root = unwrap_to_turn(if f64::cos(g) - 2.0 * f64::sin(g) > 0.0 { down } else { up }, g);
                let q = solve([g, s0], true);
                // The root's rounding over `|h'| = sqrt(5)`, and the slider's from it.
                assert!((q[0] - root).abs() < 1e-14, "from {g}, {s0}: {} against {root}", q[0]);
                let s = -(root.cos() - root.sin() / 2.0);
                assert!((q[1] - s).abs() < 1e-14, "from {g}, {s0}: {} against {s}", q[1]);
                other += usize::from((solve([g, s0], false)[0] - root).abs() > 0.1);
            }
        }
        assert!(other >= 10, "{other} solves in the other mode with the modes not kept");
    }

    /// A dyad's rows in any order and sign: the four-bar's loop `a e^(i phi) + b e^(i beta) =
    /// (d, 0) + c e^(i gamma)` (crank 1, coupler 3.5, rocker 3, frame 4, at `phi = 1`) times
    /// `1e200`, its rows given as `(x, y)`, `(y, x)`, `(-x, y)` and `(-y, -x)`. The mirror reflects
    /// the links across the line of the centres' offset and turns each angle by twice its
    /// distance from it, with signs read from the rows (`det_sign`): a reflection or a negation
    /// of the rows flips both the angles' differences and the links' turning signs, so that the
    /// image is the same. From 49 guesses over a turn of each angle, each ordering gives the root
    /// whose determinant has the guess's sign (both roots by the circles' intersection), where
    /// Newton alone reached the other from 22 (at least 10 asserted: the mirror is tried).
    #[test]
    fn a_dyad_keeps_the_guess_s_root_whatever_its_rows() {
        let k = 1e200;
        let (a, b, c, d, phi) = (1.0, 3.5, 3.0, 4.0, 1.0f64);
        // The loop's residual and its derivatives by `beta` and `gamma`, as `(x, y)`.
        let loop_at = |z: &[f64; 2]| {
            let f =
                [a * phi.cos() + b * z[0].cos() - d - c * z[1].cos(), a * phi.sin() + b * z[0].sin() - c * z[1].sin()];
            let j = [[-b * z[0].sin(), c * z[1].sin()], [b * z[0].cos(), -c * z[1].cos()]];
            (f, j)
        };
        // The two roots: the coupler's end `p` on both circles, about the crank's end `A` (radius
        // `b`) and the rocker's pivot `D` (radius `c`).
        let (ax, ay) = (a * phi.cos(), a * phi.sin());
        let (ex, ey) = (d - ax, -ay);
        let e = ex.hypot(ey);
        let along = (b * b - c * c + e * e) / (2.0 * e);
        let across = (b * b - along * along).sqrt();
        let roots = [1.0, -1.0].map(|side: f64| {
            let (px, py) = (ax + (along * ex - side * across * ey) / e, ay + (along * ey + side * across * ex) / e);
            [(py - ay).atan2(px - ax), py.atan2(px - d)]
        });
        let det = |rows: [(usize, f64); 2], z: &[f64; 2]| {
            let (_, j) = loop_at(z);
            let r = rows.map(|(i, sign)| j[i].map(|v| sign * v));
            r[0][0] * r[1][1] - r[0][1] * r[1][0]
        };
        for rows in [[(0, 1.0), (1, 1.0)], [(1, 1.0), (0, 1.0)], [(0, -1.0), (1, 1.0)], [(1, -1.0), (0, -1.0)]] {
            let at = |z: &[f64; 2], ev: &mut BlockEval<2, 0>| {
                let (f, j) = loop_at(z);
                ev.f = rows.map(|(i, sign)| k * sign * f[i]);
                ev.j = rows.map(|(i, sign)| j[i].map(|v| k * sign * v));
            };
            let mut other = 0;
            let grid = (0..49).map(|i| [f64::from(i / 7) - 2.9, f64::from(i % 7) - 3.1]);
            for guess in grid {
                let want = det(rows, &guess).signum();
                let root = roots.iter().find(|r| det(rows, r).signum() == want).expect("a root of each sign");
                let root = [0, 1].map(|u| unwrap_to_turn(root[u], guess[u]));
                let solve = |closed_form: bool| {
                    let blocks = [Block { rows: vec![0, 1], cols: vec![0, 1], closed_form }];
                    let cfg = NewtonConfig::default();
                    whole_position(&guess, [11.5 * k; 2], [1.0; 2], [true; 2], &cfg, AtLimit::Singular, &blocks, at)
                        .unwrap_or_else(|f| panic!("rows {rows:?} from {guess:?}: {f:?}"))
                        .0
                };
                let q = solve(true);
                // The angles' rounding through the dyad's determinant (its links 3.5 and 3
                // about 0.4 rad from folding): a few ulps.
                let off = |q: [f64; 2]| (q[0] - root[0]).abs().max((q[1] - root[1]).abs());
                assert!(off(q) < 1e-13, "rows {rows:?} from {guess:?}: {q:?} against {root:?}");
                other += usize::from(off(solve(false)) > 0.1);
            }
            assert!(other >= 10, "rows {rows:?}: {other} solves in the other mode with the modes not kept");
        }
    }
}
