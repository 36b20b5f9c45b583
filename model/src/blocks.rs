//! Each block of the plan as the run-time step executes it: its position solve (as the plan's
//! `Solve` says), then its velocity and acceleration analogs on one factorisation, in the order
//! and with the factorisations the emitted fused kernel uses.

use crate::closed::ClosedProg;
use crate::count::Count;
use crate::dense;
use crate::factor::{Fac, MAX_DENSE, max_abs};
use crate::levers::Levers;
use crate::newton::NewtonProg;
use crate::tape::Segment;
use kinloop_runtime::NewtonConfig;
use kinloop_runtime::generated::{BlockFailure, Factor, Fixed, Health, Inverse2, Lu, SolveReport};

/// Why a step failed in a block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepFailure {
    /// The position solve failed (no assembly, no convergence, singular, non-finite, ...).
    Block(BlockFailure),
    /// The block's Jacobian is singular at the position: pivot ratio below the configuration's
    /// `singular_tol` (the analogs are not determined).
    Singular {
        /// The pivot ratio of the equilibrated Jacobian.
        pivot_ratio: f64,
    },
}

impl std::fmt::Display for StepFailure {
    /// What failed, by the block's row (the evaluator's record: [`Model::explain`] names the
    /// equation).
    ///
    /// [`Model::explain`]: crate::Model::explain
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            StepFailure::Singular { pivot_ratio } => {
                write!(f, "singular position: the analogs' pivot ratio is {pivot_ratio:e}")
            }
            StepFailure::Block(BlockFailure::NonFinite { row, .. }) => {
                write!(f, "a value of the block's row {row} left its functions' domain (not finite)")
            }
            StepFailure::Block(BlockFailure::NoConvergence { row, iterations, residual }) => write!(
                f,
                "no convergence after {}: the residual is {residual:e} in the block's row {row}",
                Count(iterations as usize, "iteration")
            ),
            StepFailure::Block(BlockFailure::NoAssembly { row, residual, .. }) => {
                write!(f, "the loops cannot close here: the residual stalls at {residual:e} in the block's row {row}")
            }
            StepFailure::Block(BlockFailure::Singular { pivot_ratio, tolerance, .. }) => {
                write!(f, "singular position: pivot ratio {pivot_ratio:e} below {tolerance:e}")
            }
            StepFailure::Block(BlockFailure::InvalidConfig { field }) => {
                write!(f, "solver configuration: `{field}` is out of range")
            }
            StepFailure::Block(BlockFailure::TooManyTurns { value }) => {
                write!(f, "an angle of {value:e} rad is too many turns out to be solved precisely")
            }
            StepFailure::Block(BlockFailure::Underflow { row, magnitude, least }) => write!(
                f,
                "the terms of the block's row {row} are too small for f64: magnitude {magnitude:e}, below {least:e}"
            ),
            StepFailure::Block(BlockFailure::Overflow { row }) => {
                write!(f, "the terms of the block's row {row} are too large for f64: their magnitude overflows")
            }
            StepFailure::Block(BlockFailure::Vanished { row }) => {
                write!(f, "every term of the block's row {row} is zero: it holds at every position")
            }
        }
    }
}

/// How a block's positions are solved at run time.
#[derive(Clone)]
pub(crate) enum How {
    /// One division by a constant coefficient.
    Fixed { coefficient: f64, rhs: u32 },
    /// One linear solve with the block's Jacobian.
    Linear { rhs: Vec<u32> },
    /// The closed form, compiled: it leaves the unknowns and the angles' sines and cosines in
    /// their registers.
    Closed(ClosedProg),
    /// Newton.
    Newton(NewtonProg),
}

/// Where a block's analogs take their factorisation from and whether they test it, decided when
/// the model is built (from the block's solve and size), so that the step matches once per
/// block and stage instead of on the solve, the size and the factorisation's kind in turn.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Analog {
    /// A constant coefficient (the block's slot holds it from the build on): not tested.
    Fixed(Fixed),
    /// One unknown whose entry is among its column's entries: `Lu::<1>::factor_in_col` from
    /// the graph, tested.
    InCol,
    /// One unknown factorised by the position solve (a linear block): not tested again.
    KeptOne,
    /// Two unknowns: the 2x2 inverse from the graph (`Inverse2::in_cols_floored`), tested.
    Two,
    /// Factorised from the graph by the emitter's rule for its size, tested.
    Graph,
    /// Factorised by the position solve (a linear block of two unknowns or more): not tested
    /// again.
    Kept,
    /// A Newton block's Jacobian factorised by columns, tested.
    Cols,
    /// A Newton block whose final correction's factorisation is kept, tested.
    NewtonLu,
}

impl Analog {
    /// The analogs of a step (`at`: of an evaluation at a given position, where every block but
    /// a fixed one factorises its Jacobian from the graph) for a block of `n` unknowns solved
    /// as `how`, `in_col` when its one entry is among its column's, `by_rows` when its rows are
    /// equilibrated before its columns (rows of several units: never the 2x2 inverse).
    pub(crate) fn of(how: &How, n: usize, in_col: bool, by_rows: bool, at: bool) -> Analog {
        match (how, at) {
            (How::Fixed { coefficient, .. }, _) => Analog::Fixed(Fixed(*coefficient)),
            (_, true) | (How::Closed(_), false) => match (n, in_col) {
                (1, true) => Analog::InCol,
                (2, _) if !by_rows => Analog::Two,
                _ => Analog::Graph,
            },
            (How::Linear { .. }, false) => {
                if n == 1 {
                    Analog::KeptOne
                } else {
                    Analog::Kept
                }
            }
            (How::Newton(p), false) => {
                if p.keeps_lu {
                    Analog::NewtonLu
                } else {
                    Analog::Cols
                }
            }
        }
    }
}

/// One block of the step.
#[derive(Clone)]
pub(crate) struct BlockProg {
    pub(crate) unknowns: Vec<usize>,
    /// Registers of the unknowns' leaves (`None`: no node reads the unknown).
    pub(crate) unknown_regs: Vec<Option<u32>>,
    /// What is computed before the position solve (coefficients, right-hand sides, the
    /// magnitudes that do not depend on the block's unknowns).
    pub(crate) pre: Segment,
    pub(crate) how: How,
    /// The Jacobian, row-major.
    pub(crate) jac: Vec<u32>,
    /// Per column: its entries in the full Jacobian, then its lever floors (`max_abs` of them
    /// equilibrates the column).
    pub(crate) col: Vec<Vec<u32>>,
    /// Per column: its lever floors only.
    pub(crate) floors: Vec<Vec<u32>>,
    /// Per row, what the factorisation divides it by before the columns, where the block's rows
    /// have more than one unit (the plan's `row_scale`); empty where only the columns are
    /// equilibrated.
    pub(crate) rows: Vec<u32>,
    /// A block of two unknowns whose columns have entries beyond the block (rows of later
    /// blocks): per column, those entries.
    pub(crate) beyond: Option<[Vec<u32>; 2]>,
    /// A 1x1 block whose entry is among its column's entries: the position of the entry there.
    pub(crate) in_col: Option<usize>,
    pub(crate) vel: Segment,
    /// `vel[r * ni + i]`.
    pub(crate) vel_rows: Vec<u32>,
    pub(crate) tan_regs: Vec<Option<u32>>,
    pub(crate) acc: Segment,
    /// `acc[r * pairs + p]`.
    pub(crate) acc_rows: Vec<u32>,
    pub(crate) tan2_regs: Vec<Option<u32>>,
    /// The velocity analogs' solves, gathered and scattered by flat tables.
    pub(crate) vel_cols: Columns,
    /// The acceleration analogs' solves.
    pub(crate) acc_cols: Columns,
    /// The analogs' factorisation in a step.
    pub(crate) analog: Analog,
    /// The analogs' factorisation at a given position.
    pub(crate) analog_at: Analog,
}

/// The right-hand sides of a block's analog solves, one column per input (or input pair), as
/// one flat table made once: per column `c` and block row or unknown `k` (entry `c * n + k`),
/// the register of the right-hand side, the place of the solution in the state's array, and the
/// register the solution is written to (the scratch register when no node reads it). The hot
/// loop then has no nested index arithmetic and no branch per value.
#[derive(Clone, Debug, Default)]
pub(crate) struct Columns {
    /// `[right-hand side's register, place in the state's array, solution's register]`.
    t: Vec<[u32; 3]>,
}

impl Columns {
    /// The tables of `cols` columns for a block of `unknowns`: `rows[row * cols + c]` the
    /// right-hand sides, `regs[k * cols + c]` the solutions' registers, `scratch` the register
    /// written in place of a missing one.
    pub(crate) fn new(unknowns: &[usize], cols: usize, rows: &[u32], regs: &[Option<u32>], scratch: u32) -> Columns {
        let n = unknowns.len();
        let mut t = Vec::with_capacity(cols * n);
        for c in 0..cols {
            for k in 0..n {
                t.push([rows[k * cols + c], (unknowns[k] * cols + c) as u32, regs[k * cols + c].unwrap_or(scratch)]);
            }
        }
        Columns { t }
    }

    /// Solves every column on `fac` and writes the solutions into `out` and the registers.
    #[inline(always)]
    fn solve(&self, n: usize, r: &mut [f64], fac: &Fac, out: &mut [f64]) {
        if n == 1 {
            self.solve1(r, fac, out);
        } else {
            self.solve_n(n, r, fac, out);
        }
    }

    /// [`Columns::solve`] for one unknown: the runtime's 1x1 solve on each value, no gathering.
    /// The factorisation's kind is matched once, not per value.
    #[inline(always)]
    fn solve1(&self, r: &mut [f64], fac: &Fac, out: &mut [f64]) {
        match fac {
            Fac::Fixed(f) => self.fixed(*f, r, out),
            Fac::L1(lu) => self.lu1(lu, r, out),
            other => self.each1(r, out, |b| other.solve1(b)),
        }
    }

    /// [`Columns::solve`] on a constant coefficient (`Fixed::solve`: one division).
    #[inline(always)]
    fn fixed(&self, f: Fixed, r: &mut [f64], out: &mut [f64]) {
        let c = f.0;
        self.each1(r, out, |b| b / c)
    }

    /// [`Columns::solve`] on a 1x1 LU (`Lu::<1>::solve`: one multiplication).
    #[inline(always)]
    fn lu1(&self, lu: &Lu<1>, r: &mut [f64], out: &mut [f64]) {
        self.each1(r, out, |b| lu.solve([b])[0])
    }

    /// [`Columns::solve`] on a 2x2 inverse, inlined in the block's step.
    #[inline(always)]
    fn two(&self, inv: &Inverse2, r: &mut [f64], out: &mut [f64]) {
        self.each2(r, out, |b| inv.solve(b))
    }

    /// `z = solve(rhs)` for each column of a block of two unknowns.
    #[inline(always)]
    fn each2(&self, r: &mut [f64], out: &mut [f64], solve: impl Fn([f64; 2]) -> [f64; 2]) {
        if let [a, b] = self.t[..] {
            // One column (one input): no loop, whose set-up costs more than its one pass.
            solve2_into(r, out, a, b, &solve);
            return;
        }
        for t in self.t.chunks_exact(2) {
            solve2_into(r, out, t[0], t[1], &solve);
        }
    }

    /// `z = solve(rhs)` for each value of a block of one unknown.
    #[inline(always)]
    fn each1(&self, r: &mut [f64], out: &mut [f64], solve: impl Fn(f64) -> f64) {
        if let [[s, d, g]] = self.t[..] {
            // One value (one input): no loop.
            let z = solve(r[s as usize]);
            out[d as usize] = z;
            r[g as usize] = z;
            return;
        }
        for &[s, d, g] in &self.t {
            let z = solve(r[s as usize]);
            out[d as usize] = z;
            r[g as usize] = z;
        }
    }

    /// [`Columns::solve`] for `n` unknowns: two straight (the dyads' blocks), up to
    /// [`MAX_DENSE`] through an array of that size, larger (sparse) blocks through one of
    /// theirs. No array of the largest size is zeroed for a small block.
    #[inline(never)]
    fn solve_n(&self, n: usize, r: &mut [f64], fac: &Fac, out: &mut [f64]) {
        if n == 2 {
            self.each2(r, out, |b| fac.solve2(b));
        } else if n <= MAX_DENSE {
            self.solve_in(&mut [0.0; MAX_DENSE][..n], r, fac, out);
        } else {
            self.solve_in(&mut [0.0; crate::sparse::MAX_BLOCK][..n], r, fac, out);
        }
    }

    /// [`Columns::solve`] through the array `z` of the block's size.
    #[inline(always)]
    fn solve_in(&self, z: &mut [f64], r: &mut [f64], fac: &Fac, out: &mut [f64]) {
        let n = z.len();
        if n == 0 {
            return;
        }
        for t in self.t.chunks_exact(n) {
            for (zk, &[s, _, _]) in z.iter_mut().zip(t) {
                *zk = r[s as usize];
            }
            fac.solve(z);
            for (&zk, &[_, d, g]) in z.iter().zip(t) {
                out[d as usize] = zk;
                r[g as usize] = zk;
            }
        }
    }
}

/// One column of a block of two unknowns: the right-hand sides from registers `s0`, `s1`
/// solved, the solutions written to `out[d0]`, `out[d1]` and registers `g0`, `g1`. (A function,
/// not a closure: called from two places, a closure was not inlined, 94 instructions a
/// four-bar step.)
#[inline(always)]
fn solve2_into(
    r: &mut [f64],
    out: &mut [f64],
    [s0, d0, g0]: [u32; 3],
    [s1, d1, g1]: [u32; 3],
    solve: &impl Fn([f64; 2]) -> [f64; 2],
) {
    let z = solve([r[s0 as usize], r[s1 as usize]]);
    out[d0 as usize] = z[0];
    out[d1 as usize] = z[1];
    r[g0 as usize] = z[0];
    r[g1 as usize] = z[1];
}

/// What a block's stage works on: the registers, its factorisation, the configuration.
pub(crate) struct Work<'a> {
    pub(crate) r: &'a mut [f64],
    pub(crate) fac: &'a mut Fac,
    pub(crate) cfg: &'a NewtonConfig,
}

/// Whether a pivot ratio fails the configuration's test: below it, or NaN.
#[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is what lets NaN through
fn singular(pivot_ratio: f64, cfg: &NewtonConfig) -> bool {
    !(pivot_ratio >= cfg.singular_tol)
}

/// The velocity's verdict on a factorisation `f` of block `b` made from the graph: singular by
/// the configuration's test, or noted in the step's health.
#[inline(always)]
fn accept(b: usize, f: &impl Factor, cfg: &NewtonConfig, health: &mut Health) -> Result<(), StepFailure> {
    let pivot_ratio = f.pivot_ratio();
    if singular(pivot_ratio, cfg) {
        return Err(StepFailure::Singular { pivot_ratio });
    }
    health.note(b, f);
    Ok(())
}

impl BlockProg {
    fn set_unknowns(&self, r: &mut [f64], q: &mut [f64], values: &[f64]) {
        for (k, &u) in self.unknowns.iter().enumerate() {
            q[u] = values[k];
            if let Some(reg) = self.unknown_regs[k] {
                r[reg as usize] = values[k];
            }
        }
    }

    /// The factorisation of the Jacobian evaluated from the graph, by the emitter's rule: the
    /// scalar in its column (inlined: a few operations), the 2x2 inverse, or the
    /// column-equilibrated LU.
    #[inline(always)]
    fn factor_from_graph(&self, r: &[f64], fac: &mut Fac) {
        if let (1, Some(_)) = (self.unknowns.len(), self.in_col) {
            fac.set_in_col(r[self.jac[0] as usize], self.col_max(r, 0));
        } else {
            self.factor_larger(r, fac);
        }
    }

    /// [`BlockProg::factor_from_graph`] of a block of two unknowns or more, or of one whose
    /// entry is not among its column's (the one-unknown block with its entry in its column is
    /// handled inline there).
    #[inline(never)]
    fn factor_larger(&self, r: &[f64], fac: &mut Fac) {
        match self.unknowns.len() {
            2 if self.rows.is_empty() => fac.put_inverse2(self.inverse2(r)),
            _ => self.factor_cols(r, fac),
        }
    }

    /// The 2x2 inverse of the Jacobian in the registers, equilibrated by its columns' entries
    /// beyond the block and their lever floors (`Fac::inverse2`).
    #[inline(always)]
    fn inverse2(&self, r: &[f64]) -> Inverse2 {
        let v = |regs: &[u32]| max_abs(regs.iter().map(|&k| r[k as usize]));
        let j =
            [[r[self.jac[0] as usize], r[self.jac[1] as usize]], [r[self.jac[2] as usize], r[self.jac[3] as usize]]];
        let beyond = self.beyond.as_ref().map(|[b0, b1]| [v(b0), v(b1)]);
        let floor = |c: usize| match self.floors[c].as_slice() {
            [] => None,
            [one] => Some(r[*one as usize]),
            many => Some(v(many)),
        };
        Fac::inverse2(&j, beyond, [floor(0), floor(1)])
    }

    /// `Lu::factor_cols` of the Jacobian in the registers (`Lu::factor_scaled` where the block
    /// has row scales).
    fn factor_cols(&self, r: &[f64], fac: &mut Fac) {
        // No array of the sparse capacity zeroed for a dense block.
        if self.unknowns.len() <= MAX_DENSE {
            self.factor_cols_sized::<MAX_DENSE>(r, fac);
        } else {
            self.factor_cols_sized::<{ crate::sparse::MAX_BLOCK }>(r, fac);
        }
    }

    /// [`BlockProg::factor_cols`] with its scales in arrays of capacity `CAP`: none zeroed for
    /// row scales where the block has none (its rows share one unit, as most blocks' do).
    #[inline(always)]
    fn factor_cols_sized<const CAP: usize>(&self, r: &[f64], fac: &mut Fac) {
        let n = self.unknowns.len();
        let scale = &mut [0.0; CAP][..n];
        if self.rows.is_empty() {
            self.factor_cols_in(r, fac, scale, &mut []);
        } else {
            self.factor_cols_in(r, fac, scale, &mut [0.0; CAP][..n]);
        }
    }

    /// [`BlockProg::factor_cols`] with the column scales computed into `scale` and the row
    /// scales into `rows` (empty where the block has none).
    #[inline(always)]
    fn factor_cols_in(&self, r: &[f64], fac: &mut Fac, scale: &mut [f64], rows: &mut [f64]) {
        let n = scale.len();
        for (c, s) in scale.iter_mut().enumerate() {
            *s = max_abs(self.col[c].iter().map(|&k| r[k as usize]));
        }
        for (s, &k) in rows.iter_mut().zip(&self.rows) {
            *s = r[k as usize];
        }
        if let Fac::Sparse(s) = fac {
            // The non-zeros, read from the registers by the block's own tables.
            s.factor_cols(r, rows, scale);
            return;
        }
        // The matrix is read from the registers straight into the size's array.
        fac.factor_cols(n, |k| r[self.jac[k] as usize], rows, scale);
    }

    /// Solves the block's positions; writes them into `q` and the registers. With `levers` (a
    /// position-only solve of a closed form), its tests after the coefficients are computed.
    ///
    /// Inlined, as the velocity and acceleration below: the step's hot path, which the compiler
    /// stopped inlining once the positions-only solve became a second caller (about 400
    /// instructions a step more on the rhombic drive, callgrind).
    #[inline(always)]
    pub(crate) fn position(
        &self,
        w: Work<'_>,
        q: &mut [f64],
        guess: &[f64],
        report: &mut SolveReport,
        levers: Option<&Levers>,
    ) -> Result<(), StepFailure> {
        let Work { r, fac, cfg } = w;
        self.pre.run(r);
        match &self.how {
            How::Fixed { coefficient, rhs } => {
                // The block's slot holds `Fixed(coefficient)` from the model's build on.
                let f = kinloop_runtime::generated::Fixed(*coefficient);
                self.set_unknowns(r, q, &f.solve([r[*rhs as usize]]));
            }
            How::Linear { rhs } => {
                self.factor_from_graph(r, fac);
                if singular(fac.pivot_ratio(), cfg) {
                    return Err(StepFailure::Singular { pivot_ratio: fac.pivot_ratio() });
                }
                let mut z = [0.0; crate::factor::MAX_DENSE];
                for (k, &reg) in rhs.iter().enumerate() {
                    z[k] = r[reg as usize];
                }
                let n = rhs.len();
                fac.solve(&mut z[..n]);
                self.set_unknowns(r, q, &z[..n]);
            }
            How::Closed(p) => {
                // A position-only solve's tests, before the solve as in the compiled one.
                if let Some(levers) = levers {
                    levers.check(r, guess, cfg).map_err(StepFailure::Block)?;
                }
                p.run(r, guess, cfg).map_err(StepFailure::Block)?;
                for &(u, reg) in &p.unknowns {
                    q[u] = r[reg as usize];
                }
            }
            How::Newton(p) => {
                match fac {
                    Fac::Sparse(s) => s.newton(p, r, guess, cfg, report),
                    _ => dense::solve(p, r, guess, cfg, report, fac),
                }
                .map_err(StepFailure::Block)?;
                for (k, &u) in self.unknowns.iter().enumerate() {
                    q[u] = r[p.unknown_regs[k] as usize];
                }
            }
        }
        Ok(())
    }

    /// The velocity analogs `dq[u * ni + i]`, factorising the Jacobian where the position solve
    /// did not (the factorisation is kept in `fac` for the accelerations), as the block's
    /// [`Analog`] says.
    ///
    /// With `at` (the emitter's mode `At`: analogs at a position the caller gives, no position
    /// solve before), `at` is the segment to run, and every block but a fixed one factorises
    /// its Jacobian from the graph and tests it.
    #[inline(always)]
    pub(crate) fn velocity(
        &self,
        b: usize,
        w: Work<'_>,
        dq: &mut [f64],
        health: &mut Health,
        at: Option<&Segment>,
    ) -> Result<(), StepFailure> {
        let Work { r, fac, cfg } = w;
        let analog = self.stage(&self.vel, at, r);
        let tested = match analog {
            // The slot holds `Fixed(coefficient)` from the model's build on: nothing to factor,
            // and its conditioning is the constant's.
            Analog::Fixed(f) => {
                health.note(b, &f);
                self.vel_cols.fixed(f, r, dq);
                return Ok(());
            }
            Analog::InCol => {
                // Kept for the accelerations (and the sensitivities), even when it fails.
                let lu = fac.set_in_col(r[self.jac[0] as usize], self.col_max(r, 0));
                accept(b, &lu, cfg, health)?;
                self.vel_cols.lu1(&lu, r, dq);
                return Ok(());
            }
            Analog::KeptOne => {
                // A linear block of one unknown leaves its `L1` (`set_in_col` or
                // `factor_cols(1)`): the general path below is never reached from here.
                if let Fac::L1(lu) = fac {
                    health.note(b, lu);
                    self.vel_cols.lu1(lu, r, dq);
                    return Ok(());
                }
                debug_assert!(false, "a linear 1x1 block without its L1 factorisation");
                false
            }
            Analog::Two => {
                let inv = self.inverse2(r);
                fac.put_inverse2(inv);
                accept(b, &inv, cfg, health)?;
                self.vel_cols.two(&inv, r, dq);
                return Ok(());
            }
            Analog::Graph => {
                self.factor_larger(r, fac);
                true
            }
            Analog::Kept => false,
            Analog::Cols => {
                self.factor_cols(r, fac);
                true
            }
            Analog::NewtonLu => true,
        };
        match fac.conditioning() {
            Some(c) => {
                if tested && singular(c.pivot_ratio, cfg) {
                    return Err(StepFailure::Singular { pivot_ratio: c.pivot_ratio });
                }
                health.note(b, &c);
            }
            None => {
                if tested && singular(fac.pivot_ratio(), cfg) {
                    return Err(StepFailure::Singular { pivot_ratio: fac.pivot_ratio() });
                }
                fac.note(health, b);
            }
        }
        self.vel_cols.solve(self.unknowns.len(), r, fac, dq);
        Ok(())
    }

    /// The acceleration analogs `d2q[u * pairs + p]` on the velocity's factorisation.
    /// (With `at`, that segment instead of the step's: see [`BlockProg::velocity`].)
    #[inline(always)]
    pub(crate) fn acceleration(&self, r: &mut [f64], d2q: &mut [f64], fac: &Fac, at: Option<&Segment>) {
        let analog = self.stage(&self.acc, at, r);
        match (analog, fac) {
            (Analog::Fixed(f), _) => self.acc_cols.fixed(f, r, d2q),
            (Analog::InCol | Analog::KeptOne, Fac::L1(lu)) => self.acc_cols.lu1(lu, r, d2q),
            (Analog::Two, Fac::Inverse2(inv)) => self.acc_cols.two(inv, r, d2q),
            _ => self.acc_cols.solve(self.unknowns.len(), r, fac, d2q),
        }
    }

    /// Runs the stage's segment (`own`, or with `at` that one) and gives the block's analogs'
    /// factorisation in that mode.
    #[inline(always)]
    fn stage(&self, own: &Segment, at: Option<&Segment>, r: &mut [f64]) -> Analog {
        match at {
            Some(seg) => {
                seg.run(r);
                self.analog_at
            }
            None => {
                own.run(r);
                self.analog
            }
        }
    }

    /// The largest magnitude of column `c`'s entries and lever floors (its equilibration).
    #[inline(always)]
    fn col_max(&self, r: &[f64], c: usize) -> f64 {
        max_abs(self.col[c].iter().map(|&k| r[k as usize]))
    }
}
