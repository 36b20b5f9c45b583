//! The program of a run-time model's declared dynamics items (bodies, loads and gravity): the
//! registers of their parameter-only nodes and the segment of the load expressions, built with
//! the model and evaluated as the compiled mechanism's `mass_model` evaluates them.
//!
//! Masses, moments of inertia, constant coordinates and gravity are nodes of the parameters
//! alone: their registers hold them once the parameters are set (the tape's statics, the
//! operations the emitted `mass_model` performs), and [`DynamicsProg::mass_model`] reads them
//! into the runtime's [`MassModelBuf`], whose checks are the compiled `MassModel`'s. The force
//! and torque expressions are a segment of their own over the inputs and unknowns of a given
//! state (the emitted load closures read `x` and `q` from the state and compute the rest), run
//! over the model's registers by [`DynamicsProg::loads`]: no allocation.
//!
//! A part of the model, built by `Model::read` and held in it as its closed forms' and blocks'
//! programs are, so apart from the model's dynamics (`crate::dynamics`), which is written over
//! the model.

use crate::tape::{Builder, Segment, Unavailable};
use kinloop_codegen::dynamics::{AngleModel, CoordModel, DynamicsModel};
use kinloop_codegen::graph::dag::{Leaf, NodeId, Op};
use kinloop_codegen::plan::Plan;
use kinloop_runtime::dims::Sizes;
use kinloop_runtime::dynamics::{AnalogState, Body, Coord, DynamicsError, MassModelBuf, Rotation};

/// A coordinate as the plan gives it: a state column or the register of a constant.
#[derive(Clone, Copy, Debug)]
enum Col {
    Output(usize),
    Unknown(usize),
    Fixed(u32),
}

#[derive(Clone)]
struct BodyItem {
    name: String,
    mass: u32,
    inertia: u32,
    com: [Col; 2],
    turns: Rotation,
}

#[derive(Clone)]
enum LoadItem {
    Force { name: String, at: [Col; 2], value: [u32; 2] },
    Torque { name: String, on: Rotation, value: u32 },
}

/// The program of the declared dynamics items (see the [module documentation](self)): what the
/// model keeps of them, read by its dynamics (`crate::dynamics`).
#[derive(Clone)]
pub(crate) struct DynamicsProg {
    bodies: Vec<BodyItem>,
    /// Forces, then torques: the order the emitted `mass_model` adds them in.
    loads: Vec<LoadItem>,
    gravity: Option<[u32; 2]>,
    /// The load values from the registers of the inputs and unknowns.
    segment: Segment,
    input_regs: Vec<Option<u32>>,
    unknown_regs: Vec<Option<u32>>,
    /// The load values of the last evaluation, in [`MassModelBuf::load_values`] order.
    values: Vec<f64>,
}

fn col(c: &CoordModel) -> Col {
    match *c {
        CoordModel::Output(o) => Col::Output(o),
        CoordModel::Unknown(u) => Col::Unknown(u),
        CoordModel::Fixed(n) => Col::Fixed(n.0),
    }
}

fn rotation(a: AngleModel) -> Rotation {
    match a {
        AngleModel::Unknown(u) => Rotation::Unknown(u),
        AngleModel::Input(i) => Rotation::Input(i),
        AngleModel::None => Rotation::None,
    }
}

impl DynamicsProg {
    /// The program of the declared items `d` of `plan`; `None` when nothing is declared.
    pub(crate) fn build(d: &DynamicsModel, plan: &Plan) -> Result<Option<DynamicsProg>, Unavailable> {
        if !d.is_declared() {
            return Ok(None);
        }
        let g = &plan.graph;
        let find = |l: Leaf| g.find(Op::Leaf(l)).map(|n| n.0);
        let bodies = d
            .bodies
            .iter()
            .map(|b| BodyItem {
                name: b.name.clone(),
                mass: b.mass.0,
                inertia: b.inertia.0,
                com: [col(&b.com[0]), col(&b.com[1])],
                turns: rotation(b.turns),
            })
            .collect();
        let forces = d.forces.iter().map(|f| LoadItem::Force {
            name: f.name.clone(),
            at: [col(&f.at[0]), col(&f.at[1])],
            value: [f.value[0].0, f.value[1].0],
        });
        let torques =
            d.torques.iter().map(|t| LoadItem::Torque { name: t.name.clone(), on: rotation(t.on), value: t.value.0 });
        let loads: Vec<LoadItem> = forces.chain(torques).collect();
        let unknown_regs: Vec<Option<u32>> = (0..plan.n).map(|u| find(Leaf::Unknown(u as u16))).collect();
        let roots: Vec<NodeId> =
            d.forces.iter().flat_map(|f| f.value).chain(d.torques.iter().map(|t| t.value)).collect();
        let mut tape = Builder::new(g);
        tape.provide(unknown_regs.iter().flatten().map(|&r| NodeId(r)));
        let segment = tape.segment(&roots, None)?;
        Ok(Some(DynamicsProg {
            bodies,
            values: vec![0.0; roots.len()],
            loads,
            gravity: d.gravity.map(|[x, y]| [x.0, y.0]),
            segment,
            input_regs: (0..plan.ni).map(|i| find(Leaf::Input(i as u16))).collect(),
            unknown_regs,
        }))
    }

    /// The mass model with the parameters' values in `regs`.
    pub(crate) fn mass_model(&self, regs: &[f64], sizes: Sizes) -> Result<MassModelBuf, DynamicsError> {
        let r = |k: u32| regs[k as usize];
        let coord = |c: Col| match c {
            Col::Output(o) => Coord::Output(o),
            Col::Unknown(u) => Coord::Unknown(u),
            Col::Fixed(k) => Coord::Fixed(r(k)),
        };
        let mut m = MassModelBuf::new(sizes);
        if let Some([x, y]) = self.gravity {
            m = m.with_gravity([r(x), r(y)])?;
        }
        for b in &self.bodies {
            m = m.with_body(Body {
                name: b.name.clone().into(),
                mass: r(b.mass),
                com: [coord(b.com[0]), coord(b.com[1])],
                inertia: r(b.inertia),
                rotation: b.turns,
            })?;
        }
        for l in &self.loads {
            m = match l {
                LoadItem::Force { name, at, .. } => m.with_force(name.clone(), [coord(at[0]), coord(at[1])])?,
                LoadItem::Torque { name, on, .. } => m.with_torque(name.clone(), *on)?,
            };
        }
        Ok(m)
    }

    /// The load values at state `k` (its inputs and unknowns into the registers, the
    /// segment run): no allocation.
    pub(crate) fn loads<S: AnalogState + ?Sized>(&mut self, regs: &mut [f64], k: &S) -> &[f64] {
        for (reg, &x) in self.input_regs.iter().zip(k.inputs()) {
            if let Some(reg) = reg {
                regs[*reg as usize] = x;
            }
        }
        for (reg, &q) in self.unknown_regs.iter().zip(k.unknowns()) {
            if let Some(reg) = reg {
                regs[*reg as usize] = q;
            }
        }
        self.segment.run(regs);
        let mut k = 0;
        for l in &self.loads {
            let regs_of: &[u32] = match l {
                LoadItem::Force { value, .. } => value,
                LoadItem::Torque { value, .. } => std::slice::from_ref(value),
            };
            for &reg in regs_of {
                self.values[k] = regs[reg as usize];
                k += 1;
            }
        }
        &self.values
    }
}
