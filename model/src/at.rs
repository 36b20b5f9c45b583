//! Evaluations at a position the caller gives (no solve): residuals, outputs, and the residuals
//! with the full Jacobians and the magnitudes of the equations, unknowns and inputs (what
//! continuation and event location read: the compiled mechanism's `jacobian_flat`).

use crate::tape::{Builder, Segment, Unavailable};
use kinloop_codegen::graph::dag::{Leaf, NodeId, Op};
use kinloop_codegen::plan::Plan;

/// The residuals, the Jacobians `df/dq`, `df/dx` and the magnitudes at one position, flat.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Jacobian {
    /// Residuals `f[e]`.
    pub f: Vec<f64>,
    /// `j[e * n + u] = df_e / dq_u`.
    pub j: Vec<f64>,
    /// `fx[e * ni + i] = df_e / dx_i`.
    pub fx: Vec<f64>,
    /// The magnitude of each equation's terms.
    pub scale: Vec<f64>,
    /// The unit of each unknown.
    pub unit: Vec<f64>,
    /// The unit of each input.
    pub input_unit: Vec<f64>,
}

/// The segments of the evaluations at a position, each on its own (the unknowns given).
#[derive(Clone)]
pub(crate) struct AtProg {
    pub(crate) unknown_regs: Vec<Option<u32>>,
    residual: Segment,
    residual_regs: Vec<u32>,
    outputs: Segment,
    output_regs: Vec<u32>,
    jacobian: Segment,
    /// Registers of `f`, `j`, `fx`, `scale`, `unit`, `input_unit`, in that order.
    jacobian_regs: [Vec<u32>; 6],
}

fn regs(v: &[NodeId]) -> Vec<u32> {
    v.iter().map(|n| n.0).collect()
}

impl AtProg {
    pub(crate) fn build(plan: &Plan) -> Result<AtProg, Unavailable> {
        let g = &plan.graph;
        let unknown_regs: Vec<Option<u32>> =
            (0..plan.n).map(|u| g.find(Op::Leaf(Leaf::Unknown(u as u16))).map(|n| n.0)).collect();
        let segment = |roots: &[NodeId]| {
            let mut b = Builder::new(g);
            b.provide(unknown_regs.iter().flatten().map(|&r| NodeId(r)));
            b.segment(roots, None)
        };
        let jac_parts: [Vec<NodeId>; 6] = [
            plan.residuals.clone(),
            plan.jac_full.concat(),
            plan.fx_full.concat(),
            plan.scale_full.clone(),
            plan.unit_full.clone(),
            plan.input_unit.clone(),
        ];
        Ok(AtProg {
            residual: segment(&plan.residuals)?,
            residual_regs: regs(&plan.residuals),
            outputs: segment(&plan.outputs)?,
            output_regs: regs(&plan.outputs),
            jacobian: segment(&jac_parts.concat())?,
            jacobian_regs: jac_parts.map(|p| regs(&p)),
            unknown_regs,
        })
    }

    fn load(&self, r: &mut [f64], q: &[f64]) {
        for (u, reg) in self.unknown_regs.iter().enumerate() {
            if let Some(reg) = reg {
                r[*reg as usize] = q[u];
            }
        }
    }

    /// The number of residuals (the declared equations).
    pub(crate) fn residuals(&self) -> usize {
        self.residual_regs.len()
    }

    pub(crate) fn residual(&self, r: &mut [f64], q: &[f64], out: &mut [f64]) {
        self.load(r, q);
        self.residual.run(r);
        for (o, &reg) in out.iter_mut().zip(&self.residual_regs) {
            *o = r[reg as usize];
        }
    }

    pub(crate) fn outputs(&self, r: &mut [f64], q: &[f64], out: &mut [f64]) {
        self.load(r, q);
        self.outputs.run(r);
        for (o, &reg) in out.iter_mut().zip(&self.output_regs) {
            *o = r[reg as usize];
        }
    }

    pub(crate) fn jacobian(&self, r: &mut [f64], q: &[f64], out: &mut Jacobian) {
        self.load(r, q);
        self.jacobian.run(r);
        let fields = [&mut out.f, &mut out.j, &mut out.fx, &mut out.scale, &mut out.unit, &mut out.input_unit];
        for (field, regs) in fields.into_iter().zip(&self.jacobian_regs) {
            field.clear();
            field.extend(regs.iter().map(|&reg| r[reg as usize]));
        }
    }
}
