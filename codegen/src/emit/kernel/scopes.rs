//! The scopes of a solver kernel: per block, the graph nodes its position solve, its analogs
//! and its sensitivities compute, then the outputs'; the scheduler places every node in the
//! first scope that needs it.

use super::mode::Mode;
use crate::emit::schedule::{ScopeKind, ScopeSpec};
use crate::graph::dag::NodeId;
use crate::plan::solve::Solve;
use crate::plan::{BlockPlan, Plan, Stages};

/// Scope indices of a solver kernel, per block.
#[derive(Default)]
pub(super) struct Scopes {
    pub(super) specs: Vec<ScopeSpec>,
    pub(super) residual: Option<usize>,
    pub(super) pre: Vec<usize>,
    pub(super) newton: Vec<usize>,
    pub(super) vel: Vec<usize>,
    pub(super) acc: Vec<usize>,
    pub(super) sens: [Vec<usize>; 3],
    pub(super) out: usize,
}

impl Scopes {
    fn push(&mut self, kind: ScopeKind, roots: Vec<NodeId>) -> usize {
        self.specs.push(ScopeSpec { kind, roots });
        self.specs.len() - 1
    }
}

/// Whether a dense Newton block's analogs (the fused kernel's) reuse the factorisation of
/// its final correction: when every non-zero entry of its unknowns' Jacobian columns is one
/// of the block's own entries, the column magnitudes the analogs equilibrate by are known
/// inside the block's evaluation, so the runtime can factorise exactly as the analogs
/// would (a later block's entry in such a column would not be known yet). Not a sparse
/// block: the ring of coupled loops ends every solve with a final correction above the
/// rounding level, which is evaluated again, so a kept factorisation was made again there,
/// and moving a sparse one cost more than it saved (measured on the ring).
pub(super) fn keeps_lu(mode: Mode, bp: &BlockPlan) -> bool {
    let dense_newton = match bp.solve {
        Solve::Newton => true,
        Solve::Fixed { .. } | Solve::Linear { .. } | Solve::ClosedForm(_) | Solve::NewtonSparse(_) => false,
    };
    mode == Mode::Fused
        && dense_newton
        && bp.lever_floor.iter().all(Vec::is_empty)
        && bp
            .col_scale
            .iter()
            .enumerate()
            .all(|(c, col)| col.iter().all(|e| bp.jac.iter().any(|row| row.get(c) == Some(e))))
}

/// A sensitivity stage's right-hand sides per row.
pub(super) fn stage_rows(s: &Stages, stage: usize) -> &Vec<Vec<NodeId>> {
    [&s.q, &s.v, &s.a][stage]
}

/// The scopes of a kernel in `mode` (with the sensitivities' when `sens`), in the order the
/// kernel runs them.
pub(super) fn plan_scopes(plan: &Plan, mode: Mode, sens: bool) -> Scopes {
    let mut s = Scopes::default();
    if mode == Mode::At {
        s.residual = Some(s.push(ScopeKind::Plain, plan.residuals.clone()));
    } else {
        for (b, bp) in plan.blocks.iter().enumerate() {
            // Per block: what is computed before its solve, and inside its Newton evaluation.
            let (pre, newton) = match &bp.solve {
                // The right-hand side: a constant coefficient needs no scale (a later equation's
                // entry in its column may depend on the unknown, known only after the solve).
                Solve::Fixed { rhs, .. } => (vec![*rhs], vec![]),
                // The matrix, the right-hand side and the column magnitudes of the factorisation.
                Solve::Linear { .. } => {
                    let rhs = bp.solve.linear_rhs().unwrap_or_default().iter().copied();
                    let matrix = bp.jac.concat().into_iter().chain(rhs);
                    let scales =
                        bp.col_scale.concat().into_iter().chain(bp.lever_floor.concat()).chain(bp.row_scale.clone());
                    (matrix.chain(scales).collect(), vec![])
                }
                // The coefficients; a position-only solve also tests its levers against their
                // floors (see `closed_block`).
                Solve::ClosedForm(c) => {
                    let mut pre = c.form.coefficients();
                    if mode == Mode::Position {
                        pre.extend(bp.lever_floor.concat());
                    }
                    (pre, vec![])
                }
                Solve::Newton | Solve::NewtonSparse(_) => {
                    let scales = bp.scale.iter().chain(&bp.unit).copied();
                    (Vec::new(), bp.f.iter().copied().chain(bp.jac.concat()).chain(scales).collect())
                }
            };
            let p = s.push(ScopeKind::Plain, pre);
            s.pre.push(p);
            let l = s.push(ScopeKind::Loop(b), newton);
            s.newton.push(l);
        }
    }
    if mode == Mode::Position {
        return s;
    }
    for bp in &plan.blocks {
        let mut roots = bp.vel.concat();
        // A block that keeps its factorisation needs no column magnitudes of its own.
        if !keeps_lu(mode, bp) {
            roots.extend(bp.col_scale.concat());
            roots.extend(bp.lever_floor.concat());
            roots.extend(&bp.row_scale);
        }
        // The Jacobian, where no position solve evaluated it for this kernel.
        let jacobian = match bp.solve {
            // No Newton evaluation to reuse.
            Solve::ClosedForm(_) => true,
            Solve::Fixed { .. } | Solve::Linear { .. } | Solve::Newton | Solve::NewtonSparse(_) => mode == Mode::At,
        };
        if jacobian {
            roots.extend(bp.jac.concat());
        }
        let v = s.push(ScopeKind::Plain, roots);
        s.vel.push(v);
    }
    for bp in &plan.blocks {
        let a = s.push(ScopeKind::Plain, bp.acc.concat());
        s.acc.push(a);
    }
    let mut out: Vec<NodeId> =
        plan.outputs.iter().copied().chain(plan.out_d1.concat()).chain(plan.out_d2.concat()).collect();
    if sens {
        for stage in 0..3 {
            for bp in &plan.blocks {
                let roots = bp.sens.as_ref().map(|st| stage_rows(st, stage).concat()).unwrap_or_default();
                let k = s.push(ScopeKind::Plain, roots);
                s.sens[stage].push(k);
            }
        }
        if let Some(os) = &plan.out_sens {
            out.extend(os.q.concat().into_iter().chain(os.v.concat()).chain(os.a.concat()));
        }
    }
    s.out = s.push(ScopeKind::Plain, out);
    s
}
