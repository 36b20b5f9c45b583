//! A block solved by sparse Newton at run time: the plan's pattern and elimination order as
//! owned tables (the runtime's `SparseTables`, the compiled `SparsePattern`'s), the runtime's own
//! `newton_with` over the block's non-zeros, and the analogs' factorisation with equilibrated
//! columns — what the emitted code does for the block, with the same operations in the same
//! order.
//!
//! The runtime's Newton is written over a block size known when it is compiled. A block of `n`
//! unknowns is solved at the first size `P` of [`block`]'s list padded with unknowns that stay zero
//! (see the runtime's `sparse_lu_dyn` for why every test and every real value is unchanged),
//! its non-zeros in an array of `CAP >= nnz` values; both are chosen once, when the model is
//! built, and the workspace (factor slots, the dense fallback) is allocated then.
//!
//! The evaluation's sines and cosines are rotated as a dense block's are (`crate::near`, see
//! `newton`): the emitted sparse block makes its `NearTrig` the same way.

use crate::newton::{NewtonProg, write_solution};
use kinloop_codegen::plan::sparse::Sparse;
use kinloop_runtime::NewtonConfig;
use kinloop_runtime::generated::{
    BlockEval, BlockFailure, Health, Magnitudes, PaddedJac, PaddedLu, PaddedWork, SolveReport, SparseTables,
    newton_with,
};
use std::fmt;

/// The most unknowns of a block solved by sparse Newton at run time: the language's limit of a
/// mechanism's unknowns, so every sparse block a plan makes is evaluated (its padded evaluation,
/// dense fallback included, lives on the stack as the compiled one does).
pub const MAX_SPARSE: usize = 256;

/// The largest block any solve of the step gathers into a stack buffer.
pub(crate) const MAX_BLOCK: usize = MAX_SPARSE;

/// A sparse block's solver state, of its padded size.
pub(crate) trait SparseBlock: fmt::Debug + Send + Sync {
    /// Solves the block's positions from the guesses (see `dense::solve`: on return the
    /// registers hold the returned evaluation's values and the solution).
    fn newton(
        &self,
        p: &NewtonProg,
        r: &mut [f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        report: &mut SolveReport,
    ) -> Result<(), BlockFailure>;
    /// The analogs' factorisation: the Jacobian in the registers with column `c` divided by
    /// `scale[c]` (`SparseJac::factor_cols`), and row `k` by `rows[k]` first where `rows` is not
    /// empty (a block whose rows have more than one unit).
    fn factor_cols(&mut self, r: &[f64], rows: &[f64], scale: &[f64]);
    /// Solves `J z = rhs` in place with the analogs' factorisation.
    fn solve(&self, rhs: &mut [f64]);
    /// Its pivot ratio.
    fn pivot_ratio(&self) -> f64;
    /// Records its conditioning for block `b`.
    fn note(&self, health: &mut Health, b: usize);
    /// Whether the analogs' factorisation is the dense fallback.
    fn is_dense(&self) -> bool;
    /// A copy of the block's solver (its tables and its factorisations' current values).
    fn boxed_clone(&self) -> Box<dyn SparseBlock>;
}

impl Clone for Box<dyn SparseBlock> {
    fn clone(&self) -> Self {
        self.boxed_clone()
    }
}

/// The tables of the plan's symbolic factorisation.
pub(crate) fn tables(sp: &Sparse) -> SparseTables {
    SparseTables {
        n: sp.diag.len(),
        nlu: sp.nlu,
        row_ptr: sp.row_ptr.clone(),
        col: sp.entries.iter().map(|&(_, c)| c as u16).collect(),
        slot: sp.slot.clone(),
        prow: sp.prow.clone(),
        pcol: sp.pcol.clone(),
        odd: sp.odd,
        diag: sp.diag.clone(),
        l_ptr: sp.l_ptr.clone(),
        l_slot: sp.l_slot.clone(),
        l_row: sp.l_row.clone(),
        u_ptr: sp.u_ptr.clone(),
        u_slot: sp.u_slot.clone(),
        u_col: sp.u_col.clone(),
        upd: sp.upd.clone(),
    }
}

/// The solver of a sparse block with tables `t` whose non-zeros are in registers `entries`
/// (in the tables' order); `None` beyond [`MAX_SPARSE`] unknowns.
pub(crate) fn block(t: SparseTables, entries: Vec<u32>) -> Option<Box<dyn SparseBlock>> {
    let (n, nnz) = (t.n, t.nnz());
    // The padded sizes with the capacities for their non-zeros, smallest first (the plan's
    // density bound, `nnz <= n^2 / 4`, keeps every block within one); the third size is the
    // values kept per evaluation when the magnitudes depend on the unknowns (`2P`).
    macro_rules! first_fitting {
        ($(($p:literal, $c:literal, $k:literal)),*) => {{
            $(if n <= $p && nnz <= $c {
                return Some(Box::new(Padded::<$p, $c, $k>::new(t, entries)));
            })*
            None
        }};
    }
    first_fitting!(
        (16, 64, 32),
        (32, 256, 64),
        (64, 256, 128),
        (64, 1024, 128),
        (128, 512, 256),
        (128, 4096, 256),
        (256, 1024, 512),
        (256, 16384, 512)
    )
}

/// A sparse block padded to `P` unknowns with at most `CAP` non-zeros (`K2 = 2P`).
#[derive(Clone)]
struct Padded<const P: usize, const CAP: usize, const K2: usize> {
    work: PaddedWork<P>,
    lu: PaddedLu<P>,
    entries: Vec<u32>,
}

impl<const P: usize, const CAP: usize, const K2: usize> fmt::Debug for Padded<P, CAP, K2> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "sparse block of {} unknowns padded to {P}", self.work.tables.n)
    }
}

impl<const P: usize, const CAP: usize, const K2: usize> Padded<P, CAP, K2> {
    fn new(t: SparseTables, entries: Vec<u32>) -> Self {
        debug_assert!(t.n <= P && t.nnz() <= CAP && entries.len() == t.nnz());
        Padded { lu: PaddedLu::new(&t), work: PaddedWork::new(t), entries }
    }

    /// [`SparseBlock::newton`] keeping `K` values per evaluation (the magnitudes, `2P`, when they
    /// depend on the unknowns; otherwise none).
    fn solve<const K: usize>(
        &self,
        p: &NewtonProg,
        r: &mut [f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        report: &mut SolveReport,
    ) -> Result<(), BlockFailure> {
        let n = p.unknowns.len();
        // The padding: unknowns at zero, residuals zero, magnitudes one, no turns.
        let padded = |r: &[f64], regs: &[u32], pad: f64| -> [f64; P] {
            std::array::from_fn(|k| if k < n { r[regs[k] as usize] } else { pad })
        };
        let z0: [f64; P] = std::array::from_fn(|k| if k < n { guess[p.unknowns[k]] } else { 0.0 });
        let turns: [bool; P] = std::array::from_fn(|k| k < n && p.turns[k]);
        let fixed = Magnitudes::new(padded(r, &p.scale, 1.0), padded(r, &p.unit, 1.0)).with_turns(turns);
        let (work, entries) = (&self.work, &self.entries);
        // Rotation slots fresh for this solve (see `newton`).
        p.near.reset(r);
        // Written over the solver's slot, every field, as the emitted block's evaluation is (the
        // entries past the block's own stay the zeros the slot is made with).
        let mut eval = |z: &[f64; P], e: &mut BlockEval<P, K, PaddedJac<'_, P, CAP>>| {
            for (k, &reg) in p.unknown_regs.iter().enumerate() {
                r[reg as usize] = z[k];
            }
            p.eval.run(r);
            for (x, &reg) in e.j.v.iter_mut().zip(entries) {
                *x = r[reg as usize];
            }
            for (k, out) in e.keep.iter_mut().enumerate() {
                *out = match (k < P, k % P) {
                    (true, m) if m < n => r[p.scale[m] as usize],
                    (false, m) if m < n => r[p.unit[m] as usize],
                    _ => 1.0,
                };
            }
            e.f = padded(r, &p.f, 0.0);
        };
        let mut ev = BlockEval { f: [0.0; P], j: PaddedJac::new([0.0; CAP], work), keep: [0.0; K] };
        eval(&z0, &mut ev);
        let per_eval = |e: &BlockEval<P, K, PaddedJac<'_, P, CAP>>| {
            Magnitudes::new(std::array::from_fn(|k| e.keep[k]), std::array::from_fn(|k| e.keep[P + k]))
                .with_turns(turns)
        };
        let solved = if K == 0 {
            newton_with::<P, K, _>(z0, &mut ev, cfg, &mut eval, &fixed)
        } else {
            newton_with::<P, K, _>(z0, &mut ev, cfg, &mut eval, &per_eval)
        }?;
        report.absorb(&solved);
        // The magnitudes the solver judged the last evaluation in: asked only by a debug build.
        let mags = || if K == 0 { fixed } else { per_eval(&ev) };
        write_solution(p, r, (&ev.f, entries, &ev.j.v), &solved.z, mags);
        Ok(())
    }
}

impl<const P: usize, const CAP: usize, const K2: usize> SparseBlock for Padded<P, CAP, K2> {
    fn newton(
        &self,
        p: &NewtonProg,
        r: &mut [f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        report: &mut SolveReport,
    ) -> Result<(), BlockFailure> {
        // The magnitudes kept with every evaluation unless made once.
        if p.fixed_mags {
            self.solve::<0>(p, r, guess, cfg, report)
        } else {
            self.solve::<K2>(p, r, guess, cfg, report)
        }
    }

    fn factor_cols(&mut self, r: &[f64], rows: &[f64], scale: &[f64]) {
        let t = &self.work.tables;
        let mut v = [0.0; CAP];
        for (x, &reg) in v.iter_mut().zip(&self.entries) {
            *x = r[reg as usize];
        }
        let col: [f64; P] = std::array::from_fn(|k| if k < t.n { scale[k] } else { 1.0 });
        let row: [f64; P] = std::array::from_fn(|k| if k < rows.len() { rows[k] } else { 1.0 });
        self.lu.factor(t, &v[..t.nnz()], row, col);
    }

    fn solve(&self, rhs: &mut [f64]) {
        self.lu.solve_in_place(&self.work.tables, rhs);
    }

    fn pivot_ratio(&self) -> f64 {
        self.lu.pivot_ratio()
    }

    fn note(&self, health: &mut Health, b: usize) {
        health.note(b, &self.lu);
    }

    fn is_dense(&self) -> bool {
        self.lu.is_dense()
    }

    fn boxed_clone(&self) -> Box<dyn SparseBlock> {
        Box::new(self.clone())
    }
}
