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
//! So where a checked kernel fails for a mechanism outside [`CLOSED_FORM_SIZES`] (or fails as
//! overflowed inside them: a closed form whose square is a product of four lengths, a length
//! along a direction that is itself a length, overflows from about `1e77`), the position
//! is solved again by Newton over the whole system (its residuals and Jacobian from
//! [`Mechanism::jacobian_flat`](crate::Mechanism::jacobian_flat), from the same guess), and the
//! analogs and outputs at that position by
//! [`Mechanism::kinematics_at_flat`](crate::Mechanism::kinematics_at_flat), whose factorisations
//! are scaled (and for a sensitivity solve, the sensitivities too, by
//! [`Sensitivities::sensitivities_at_flat`](crate::Sensitivities::sensitivities_at_flat); for a
//! solve of the positions alone, [`Mechanism::position_flat`](crate::Mechanism::position_flat),
//! nothing more). Inside the range the kernel's own error stands, an overflow's save: nothing
//! changes for a mechanism of ordinary size, and the hot path pays nothing (this runs only after
//! a failure).
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
//! does the rescue, see [`whole_position`]; not at a singular position that is no limit position,
//! where the closed form fails as singular, see [`singular_in_own_magnitudes`].) Where the
//! iterations run out while the residual still falls, Newton cannot tell a mechanism that does
//! not assemble from one it did not reach, and says so (no convergence). Its tests are made in the magnitudes of the equations and unknowns, so this
//! is the error of the same mechanism at every size. A caller's bad value or an invalid
//! configuration explains the failure at any size: their error stands. Where Newton solves but the
//! analogs at its position fail, theirs.
//!
//! **Its assembly mode is the closed forms'.** A closed form picks one of its two roots by the
//! guess (the sign of its block's Jacobian determinant there); Newton goes wherever it converges,
//! which for a four-bar driven by its rocker was the other assembly mode at about half its inputs,
//! and for the gear-lever's polar length from guesses of either sign, the length of the other sign
//! (the pin's angle half a turn on) at 996 of 2304 solves. So each closed-form block's mode is
//! checked after the solve and mirrored where it differs ([`Block`], see [`whole_position`]): the
//! angles of size 1 at every size.
//!
//! The mechanism is seen through three functions only ([`Whole`]): the entry point that
//! takes a mechanism, `mechanism::rescue`, hands them over, so that this module needs nothing of
//! the mechanism's traits (which call it).

use crate::error::Error;
use crate::kin::Jac;
use crate::kinds::QuantityKind;
use crate::solvers::lu::Lu;
use crate::solvers::newton::{
    BlockEval, BlockFailure, Magnitudes, NewtonConfig, NewtonStop, SolveReport, Solved, newton, row_vanishes,
};
use core::cell::Cell;

mod modes;
mod system;
mod undetermined;
use modes::keep_modes;
pub use system::{AtLimit, Block};
use system::{System, blank_evaluation, scaled_residual};
use undetermined::undetermined_angle;

/// The sizes (largest magnitude of an equation's terms: the sum of a loop's link lengths) at
/// which every closed form computes exactly: `2^-480 .. 2^480`, about `1e-144 .. 1e144`. Their
/// squares, and the products of two of them, stay normal numbers with 60 binary orders of
/// magnitude to spare for link ratios and small offsets.
pub const CLOSED_FORM_SIZES: (f64, f64) = (1.0 / TWO_480, TWO_480);

/// `2^480`, exact.
const TWO_480: f64 = (1u128 << 120) as f64 * (1u128 << 120) as f64 * (1u128 << 120) as f64 * (1u128 << 120) as f64;

/// Whether a failed solve is solved again by Newton ([`rescue`]): where the equation
/// magnitudes `scale` (the finite ones) put the mechanism outside [`CLOSED_FORM_SIZES`], its
/// largest beyond either end, or where the failure `overflowed`, at any size: a closed form whose
/// squares are products of more than two lengths (a length along a direction that is itself a
/// length, its square four lengths) overflows inside those sizes too, from about `1e77` of its
/// unit, where Newton's equations, of the lengths' own magnitude, do not. A run-time model asks
/// the same (`kinloop_runtime::generated::to_rescue`).
#[doc(hidden)]
pub fn to_rescue(scale: &[f64], overflowed: bool) -> bool {
    let size = scale.iter().fold(0.0f64, |s, v| if v.is_finite() { s.max(v.abs()) } else { s });
    overflowed || (size > 0.0 && !(size >= CLOSED_FORM_SIZES.0 && size <= CLOSED_FORM_SIZES.1))
}

/// The first equation whose terms all vanish at every position ([`BlockFailure::Vanished`]),
/// given the whole system's magnitudes `scale`, residuals `f` and Jacobian `j` (its rows one
/// after the other) at a position: its magnitude is exactly zero (a loop's is the sum of its
/// lengths, so every length of the loop is zero; lengths of `1e-200` make it `1e-200` or more),
/// and so are its residual and its every derivative there. Asked after a failed solve only (by
/// the rescue, and by a run-time model's): the closed forms tell such a loop no better than
/// from a dead centre (a dyad of zero links on coincident centres has every angle, as one of
/// equal links does) and reported it singular. A magnitude free of the unknowns bounds the terms
/// at every position, and one that holds a slider coordinate (zero at the position) bounds them
/// where the coordinate is zero: its derivative by that coordinate is not zero, so its row is not
/// taken for one that vanishes.
#[doc(hidden)]
pub fn vanished_row(scale: &[f64], f: &[f64], j: &[f64]) -> Option<usize> {
    let n = scale.len();
    if f.len() != n || j.len() != n * n {
        return None;
    }
    (0..n).find(|&r| row_vanishes(scale[r], f[r], &j[r * n..(r + 1) * n]))
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
/// `m` describes: for a mechanism outside [`CLOSED_FORM_SIZES`] (or an `error` of overflow at
/// any size: see [`to_rescue`]), the position solved by Newton
/// over the whole system and `m`'s result there, or where Newton fails, its failure as `m`'s
/// error (where the result fails, the result's error); otherwise `error`. A value given that
/// is not finite, an angle guessed too many turns out ([`Error::TooManyTurns`]: no solve can
/// give it on its turn to the tolerance), or an invalid configuration explains the failure at
/// any size: `error` stands. (The magnitudes are judged at the guess, so a length guessed far
/// beyond the mechanism's size, `1e150` for a slotted rocker of size 2, puts it outside
/// [`CLOSED_FORM_SIZES`]; Newton then returned an angle `1e7` rad out and a length `1e168` with
/// no error, its residual judged against the guess's magnitudes.)
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
        || matches!(error, Error::NonFinite { .. } | Error::InvalidArgument(_) | Error::TooManyTurns { .. })
        || cfg.invalid_field().is_some()
    {
        return Err(error);
    }
    match jacobian_to_rescue(m, guess, matches!(error, Error::Overflow { .. })) {
        Ok(Some(jac)) => solve_whole(m, guess, cfg, &jac, error),
        Ok(None) => Err(error),
        Err(vanished) => Err((m.fail)(vanished)),
    }
}

/// Whether a position Newton over the whole system reached closes its loops in its own
/// magnitudes: `f` its residuals and `scale` its equations' magnitudes there, the residual
/// within what Newton accepts at its rounding floor (`1000 max(residual_tol, 16 eps)`, see
/// [`NewtonConfig::step_tol`]). The rescue judges its residual in the magnitudes at the guess,
/// which a length guessed far beyond the mechanism's size makes those of that length: the
/// slotted lever of size 2 at its singular position (its lever `6e-17`) from a length's guess
/// of `1e150`, solved from the magnitudes at that guess, came out at a length of `1.2e118`, its
/// loop open by all of it (a residual of its own magnitude). A run-time model tests the same.
#[doc(hidden)]
pub fn closes_in_own_magnitudes(f: &[f64], scale: &[f64], cfg: &NewtonConfig) -> bool {
    let rho = f.iter().zip(scale).fold(0.0f64, |m, (f, s)| m.max(f.abs() / s));
    // A NaN residual fails; a row whose terms all vanish (`0 / 0`) is closed.
    f.iter().all(|f| !f.is_nan()) && rho <= 1000.0 * cfg.residual_tol.max(16.0 * f64::EPSILON)
}

/// A mechanism's Jacobian at a position in that position's own magnitudes, as
/// [`singular_in_own_magnitudes`] reads it: `j` row by row (`j[e * n + u]` for `n` unknowns), its
/// equations' magnitudes `scale` and its unknowns' units `unit` there.
#[doc(hidden)]
pub struct OwnJacobian {
    /// The Jacobian, row by row.
    pub j: Vec<f64>,
    /// The equations' magnitudes.
    pub scale: Vec<f64>,
    /// The unknowns' units (one that is not finite and positive counts as one).
    pub unit: Vec<f64>,
}

/// How far along its null direction, in the block's dimensionless unknowns (radians, fractions
/// of a loop's size), a block singular at a position is tested again (see
/// [`singular_in_own_magnitudes`]). At a limit position the smallest pivot grows in proportion
/// to the distance from the fold, at a rate set by the fold's curvature: `2.1e-5` at `1e-4` on
/// the rocker-driven four-bar of the limit-position tests (rocker 3, coupler 3.5, crank 1, frame
/// 4, by mpmath), `2e5` times `singular_tol`'s default; about a family of near-roots it does not
/// grow at all.
const FOLD_STEP: f64 = 1e-4;

/// The first block of `blocks` singular at the position `q` Newton over the whole system reached
/// from a singular failure taken for a limit position ([`AtLimit::Position`]), in that position's
/// own magnitudes, `own(q)` its Jacobian there ([`OwnJacobian`]; `None` where it cannot be
/// evaluated): the failure the closed forms give at size 1, or `None`. The failure names the
/// block's first equation (a row of the whole system) and carries the position's scaled
/// residual `residual`, its solve's `iterations` and the block's pivot ratio.
///
/// A block's pivot ratio is that of its Jacobian equilibrated as the generated Newton solver
/// equilibrates a block's (rows by their magnitudes, columns by their units), against
/// `cfg.singular_tol`. Below it the block is singular unless the position is a limit position:
/// there, too, the Jacobian is singular (at the fold itself, and the position Newton reaches is
/// only `sqrt(eps)` of the size from it, or closer), but a step of `1e-4` along the block's null
/// direction either way makes the pivot ratio far larger than the tolerance. A position about which it stays
/// singular is one of a family of near-roots, none determined by the data: a dyad whose centres
/// are `1e-13` of its links apart (turning about them) or a slotted lever whose lever is `1e-13`
/// of its loop (the rocker turning about the crank pin), both with a pivot ratio of `5e-14`. The
/// closed forms call those singular at size 1 (`check_centres`, `check_lever`); Newton's least
/// residual was any point of the family, a different one at each size (`1e-3` rad apart).
///
/// `blocks` that do not partition the system into blocks of at most 16 unknowns are taken as one
/// block of the whole system, of at most 16; a larger one is not tested.
#[doc(hidden)]
pub fn singular_in_own_magnitudes(
    q: &[f64],
    mut own: impl FnMut(&[f64]) -> Option<OwnJacobian>,
    blocks: &[Block],
    residual: f64,
    iterations: u32,
    cfg: &NewtonConfig,
) -> Option<BlockFailure> {
    let n = q.len();
    let whole = [Block { rows: (0..n).collect(), cols: (0..n).collect(), closed_form: false }];
    let blocks = if partitions_n(blocks, n) { blocks } else { &whole[..] };
    let at_q = own(q)?;
    blocks.iter().filter(|b| b.cols.len() <= 16).find_map(|b| {
        let lu = block_lu(&at_q, b);
        let pivot_ratio = lu.pivot_ratio();
        if pivot_ratio >= cfg.singular_tol || at_fold(q, &at_q, b, &lu, cfg, &mut own) {
            return None;
        }
        Some(BlockFailure::Singular {
            row: b.rows.first().copied().unwrap_or(0),
            iterations,
            residual,
            pivot_ratio,
            tolerance: cfg.singular_tol,
        })
    })
}

/// Whether `block`, singular at `q` (its Jacobian `at_q`, factorised as `lu`), is regular by
/// `cfg.singular_tol` at [`FOLD_STEP`] along its null direction on either side: a limit position.
fn at_fold(
    q: &[f64],
    at_q: &OwnJacobian,
    block: &Block,
    lu: &Lu<16>,
    cfg: &NewtonConfig,
    own: &mut impl FnMut(&[f64]) -> Option<OwnJacobian>,
) -> bool {
    let w = lu.null_direction();
    let largest = w.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    if !(largest > 0.0 && largest < f64::INFINITY) {
        return false;
    }
    [FOLD_STEP, -FOLD_STEP].into_iter().any(|step| {
        let mut moved = q.to_vec();
        for (i, &u) in block.cols.iter().enumerate() {
            moved[u] += step * w[i] / largest * unit_of(&at_q.unit, u);
        }
        own(&moved).is_some_and(|there| block_lu(&there, block).pivot_ratio() >= cfg.singular_tol)
    })
}

/// The unit of unknown `u` in `unit`: one where it is not finite and positive.
fn unit_of(unit: &[f64], u: usize) -> f64 {
    if unit[u] > 0.0 && unit[u].is_finite() { unit[u] } else { 1.0 }
}

/// The factorisation of `block`'s Jacobian in `own` (of at most 16 unknowns) equilibrated by its
/// rows' magnitudes and its unknowns' units, padded to 16 with rows `z_i = 0` (pivot 1), as
/// [`solve_block`] pads it.
fn block_lu(own: &OwnJacobian, block: &Block) -> Lu<16> {
    let (rows, cols) = (&block.rows[..], &block.cols[..]);
    let n = own.scale.len();
    let sub: [[f64; 16]; 16] = core::array::from_fn(|i| {
        core::array::from_fn(|k| match (rows.get(i), cols.get(k)) {
            (Some(&r), Some(&u)) => own.j[r * n + u],
            (None, None) => f64::from(u8::from(i == k)),
            _ => 0.0,
        })
    });
    let row_scale = core::array::from_fn(|i| rows.get(i).map_or(1.0, |&r| own.scale[r]));
    // `factor_scaled` divides each column by its scale: by one over the unit, as `z = q / unit`.
    let col_scale = core::array::from_fn(|k| cols.get(k).map_or(1.0, |&u| 1.0 / unit_of(&own.unit, u)));
    Lu::<16>::factor_scaled(&sub, row_scale, col_scale)
}

/// The Jacobian at `guess` when the failure is to be rescued ([`to_rescue`]: its magnitudes
/// outside [`CLOSED_FORM_SIZES`], or the failure `overflowed`); or the failure that explains
/// the kernel's at every size, an equation whose terms all vanish ([`vanished_row`]: a loop of
/// lengths all zero, which the kernel called singular or not assembled). Its own function, the Jacobian
/// moved to the heap: for a large mechanism it is big (512 KiB for 256
/// unknowns), and in an unoptimised build a frame keeps every value it made, so the common case
/// (an ordinary size, nothing to rescue) must not share one with the whole-system solve.
#[inline(never)]
fn jacobian_to_rescue<J, A, F, const N: usize, const NI: usize>(
    m: &Whole<J, A, F, N>,
    guess: &[f64; N],
    overflowed: bool,
) -> Result<Option<Box<Jac<N, NI>>>, BlockFailure>
where
    J: Fn(&[f64; N]) -> Jac<N, NI>,
{
    let jac = Box::new((m.jacobian)(guess));
    if let Some(row) = vanished_row(&jac.scale, &jac.f, jac.j.as_flattened()) {
        return Err(BlockFailure::Vanished { row });
    }
    Ok(to_rescue(&jac.scale, overflowed).then_some(jac))
}

/// [`rescue`]'s Newton over the whole system from `guess`, whose Jacobian is `jac`, and `m`'s
/// result at the position it reaches: where Newton fails, its failure as `m`'s error; where the
/// position does not close its loops in its own magnitudes ([`closes_in_own_magnitudes`]), the
/// kernel's `error`.
#[inline(never)]
fn solve_whole<J, A, F, T, const N: usize, const NI: usize>(
    m: &Whole<J, A, F, N>,
    guess: &[f64; N],
    cfg: &NewtonConfig,
    jac: &Jac<N, NI>,
    error: Error,
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
    let own = (m.jacobian)(&q);
    if !closes_in_own_magnitudes(&own.f, &own.scale, cfg) {
        return Err(error);
    }
    // The analogs' solve tests its own pivots; the positions alone are tested here.
    let own_at = |q: &[f64]| {
        let jq = (m.jacobian)(q.try_into().ok()?);
        let j = jq.j.iter().flatten().copied().collect();
        Some(OwnJacobian { j, scale: jq.scale.to_vec(), unit: jq.unit.to_vec() })
    };
    if m.at_limit == AtLimit::Position
        && let Some(fail) = singular_in_own_magnitudes(&q, own_at, &m.blocks, report.residual, report.iterations, cfg)
    {
        return Err((m.fail)(fail));
    }
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
        BlockFailure::Vanished { row } => BlockFailure::Vanished { row: to(row) },
        other @ (BlockFailure::InvalidConfig { .. } | BlockFailure::TooManyTurns { .. }) => other,
    }
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
    let system = System { scale, unit, turns, cfg, at_limit };
    match in_order(guess, &system, blocks, &mut at) {
        Some(solved) => solved,
        None => solve_all(guess, &system, blocks, &mut at),
    }
}

/// [`whole_position`]'s Newton over all `N` unknowns of `system` at once, each closed-form
/// block of `blocks` kept in its assembly mode: a system of one block, and what [`in_order`]
/// solves each block by.
fn solve_all<const N: usize>(
    guess: &[f64; N],
    system: &System<'_, N>,
    blocks: &[Block],
    mut at: impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Result<([f64; N], SolveReport), BlockFailure> {
    let &System { scale, unit, turns, cfg, at_limit } = system;
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
    // An angle the equations do not see has no root to keep a mode of: the block is singular.
    if let Some(fail) = undetermined_angle(&solved, system, blocks, &mut eval) {
        return Err(fail);
    }
    let solved = if blocks.iter().any(|b| b.closed_form) {
        keep_modes(solved, &z0, system, blocks, &mags, &mut eval)?
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
fn in_order<const N: usize>(
    guess: &[f64; N],
    system: &System<'_, N>,
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
        let Walk { to, report: solved } = match solve(&q, block, system, at) {
            Ok(walk) => walk,
            Err(fail) => return Some(Err(fail)),
        };
        q = to;
        report.merge(&solved);
    }
    Some(Ok((q, report)))
}

/// Whether `blocks` partition a system of `N` equations and unknowns into square blocks of 1
/// to 16 unknowns: every row and every column in exactly one block.
fn partitions<const N: usize>(blocks: &[Block]) -> bool {
    partitions_n(blocks, N)
}

/// [`partitions`] for a system of `n` equations and unknowns.
fn partitions_n(blocks: &[Block], n: usize) -> bool {
    let mut rows = vec![false; n];
    let mut cols = vec![false; n];
    let mark = |seen: &mut Vec<bool>, i: usize| i < n && !core::mem::replace(&mut seen[i], true);
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
fn solve_block<const K: usize, const N: usize>(
    q: &[f64; N],
    block: &Block,
    whole: &System<'_, N>,
    at: &mut dyn FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Result<Walk<N>, BlockFailure> {
    let (rows, cols) = (&block.rows[..], &block.cols[..]);
    let n = cols.len();
    let pick = |v: &[f64; N], pad: f64| core::array::from_fn::<f64, K, _>(|i| cols.get(i).map_or(pad, |&u| v[u]));
    let guess = pick(q, 0.0);
    let system = System {
        scale: core::array::from_fn(|i| rows.get(i).map_or(1.0, |&r| whole.scale[r])),
        unit: pick(&whole.unit, 1.0),
        turns: core::array::from_fn(|i| cols.get(i).is_some_and(|&u| whole.turns[u])),
        cfg: whole.cfg,
        at_limit: whole.at_limit,
    };
    let own = [Block { rows: (0..n).collect(), cols: (0..n).collect(), closed_form: block.closed_form }];
    let mut all = blank_evaluation::<N>();
    let mut full = *q;
    // Behind `dyn`, as `at` is: one solver of each size serves every mechanism's blocks.
    let in_block: &mut dyn FnMut(&[f64; K], &mut BlockEval<K, 0>) = &mut |z, ev| {
        for (i, &u) in cols.iter().enumerate() {
            full[u] = z[i];
        }
        at(&full, &mut all);
        for i in 0..K {
            ev.f[i] = rows.get(i).map_or(z[i], |&r| all.f[r]);
            for j in 0..K {
                ev.j[i][j] = match (rows.get(i), cols.get(j)) {
                    (Some(&r), Some(&u)) => all.j[r][u],
                    (Some(_), None) | (None, Some(_)) => 0.0,
                    (None, None) => f64::from(u8::from(i == j)),
                };
            }
        }
    };
    let as_whole = |row: usize| rows.get(row).copied().unwrap_or(rows[0]);
    let (z, report) = solve_all(&guess, &system, &own, in_block).map_err(|fail| with_row(fail, as_whole))?;
    let mut to = *q;
    for (i, &u) in cols.iter().enumerate() {
        to[u] = z[i];
    }
    Ok(Walk { to, report })
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
}
