//! A mechanism read at run time: the plan turned into the tape and block programs once, then
//! evaluated step by step without allocating.

use crate::at::{AtProg, Jacobian};
use crate::blocks::{Analog, BlockProg, Columns, How, StepFailure, Work};
use crate::closed::ClosedProg;
use crate::dynamics_prog::DynamicsProg;
use crate::extra::Extra;
use crate::factor::{Fac, MAX_DENSE};
use crate::finite::{Finite, all_finite};
use crate::gather::Gather;
use crate::levers::Levers;
use crate::newton::NewtonProg;
use crate::sensitivities::{SensProg, Sensitivities};
use crate::source::{self, Diagnostics};
use crate::sparse::{self, MAX_SPARSE};
use crate::tape::{Builder, Segment, registers, statics};
use kinloop_codegen::Planned;
use kinloop_codegen::graph::dag::{Leaf, NodeId, Op};
use kinloop_codegen::plan::kinds::{self, Kind};
use kinloop_codegen::plan::solve::Solve;
use kinloop_codegen::plan::{BlockPlan, Plan, pairs};
use kinloop_runtime::generated::{Health, SolveReport};
use kinloop_runtime::{BlockInfo, NewtonConfig, QuantityKind, SweepConfig};
use std::fmt;

/// Why a text could not become a [`Model`].
#[derive(Debug)]
pub enum ReadError {
    /// The declaration was rejected: the macro's own messages, at their places in the text.
    Rejected(Diagnostics),
    /// The declaration is valid but uses what the run-time evaluator does not evaluate yet.
    Unsupported(String),
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadError::Rejected(d) => write!(f, "{d}"),
            ReadError::Unsupported(what) => write!(f, "not evaluated at run time: {what}"),
        }
    }
}

impl std::error::Error for ReadError {}

/// Why one step failed.
#[derive(Clone, Debug, PartialEq)]
pub enum StepError {
    /// A parameter without a default value was not given one.
    UnsetParam(String),
    /// A given slice has the wrong length.
    Size {
        /// What was given (`inputs`, `guess`).
        what: &'static str,
        /// The length expected.
        expected: usize,
        /// The length given.
        given: usize,
    },
    /// The solver configuration has a field out of range.
    InvalidConfig(&'static str),
    /// An angle parameter is beyond the configuration's `largest_precise_angle` (`bound`): an
    /// angle added to it is lost to rounding (see `Mechanism::check_param_angles`).
    ImpreciseParam {
        /// The parameter's name.
        param: String,
        /// Its value.
        value: f64,
        /// The bound.
        bound: f64,
    },
    /// A parameter or an input of [`Model::solve`] or [`Model::kinematics_at`] is not finite:
    /// what the compiled `solve` and `kinematics_at_flat` name (`Error::NonFinite`) before a
    /// block fails on it or the state computed from it is not finite.
    NotFinite {
        /// `"parameter"` or `"input"`.
        what: &'static str,
        /// Its name.
        name: String,
        /// Its value.
        value: f64,
    },
    /// A block failed.
    Block {
        /// The block's index in solve order.
        block: usize,
        /// What failed.
        failure: StepFailure,
    },
    /// A value of the state is not finite (a parameter or input outside the functions' domains).
    NonFinite,
    /// An unknown of a position given to [`Model::kinematics_at`] is not finite.
    NonFinitePosition {
        /// The unknown's name.
        unknown: String,
        /// The value given.
        value: f64,
    },
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StepError::UnsetParam(p) => write!(f, "parameter `{p}` has no value (it has no default: give one)"),
            StepError::Size { what, expected, given } => write!(f, "{given} {what} given, {expected} expected"),
            StepError::InvalidConfig(field) => write!(f, "solver configuration: `{field}` is out of range"),
            StepError::ImpreciseParam { param, value, bound } => write!(
                f,
                "parameter `{param}` is an angle of {value:e} rad, beyond {bound:e} rad, the largest angle \
                 solved to the residual tolerance; reduce it by whole turns"
            ),
            StepError::NotFinite { what, name, value } => {
                write!(f, "{what} `{name}` is not finite ({value}): give it a finite value")
            }
            StepError::Block { block, failure } => {
                write!(f, "block {block}: {failure} (`Model::explain` names its unknowns and equations)")
            }
            StepError::NonFinite => write!(f, "a value of the state is not finite"),
            StepError::NonFinitePosition { unknown, value } => {
                write!(f, "the given position of `{unknown}` is not finite ({value})")
            }
        }
    }
}

impl std::error::Error for StepError {}

/// A kinematic state: positions, their first and second analogs, the outputs and theirs, for
/// `n` unknowns, `ni` inputs and `no` output columns, flat (the const-generic runtime's `Kin`
/// with its sizes known at run time).
#[derive(Clone, Debug)]
pub struct State {
    /// Inputs.
    pub x: Vec<f64>,
    /// Positions of the unknowns.
    pub q: Vec<f64>,
    /// `dq[u * ni + i] = d q_u / d x_i`.
    pub dq: Vec<f64>,
    /// `d2q[(u * ni + i) * ni + j] = d2 q_u / d x_i d x_j`.
    pub d2q: Vec<f64>,
    /// Output columns (a point gives its `x` and `y`).
    pub out: Vec<f64>,
    /// `dout[o * ni + i]`.
    pub dout: Vec<f64>,
    /// `d2out[(o * ni + i) * ni + j]`.
    pub d2out: Vec<f64>,
    /// The position solve's report.
    pub report: SolveReport,
    /// Conditioning of the blocks (pivot ratios, determinant signs).
    pub health: Health,
}

/// A mechanism read at run time (see the crate documentation).
///
/// A model is one mutable workspace (its parameters and the registers and factorisations each
/// step writes); `clone` makes an independent one with the same parameters, e.g. one per thread.
#[derive(Clone)]
pub struct Model {
    name: String,
    decomposition: String,
    /// The default drawing's description (the compiled `Mechanism::DRAWING`).
    pub(crate) drawing: String,
    warnings: Option<Diagnostics>,
    params: Vec<String>,
    param_values: Vec<Option<f64>>,
    /// The first parameter without a value (kept by `load_params`).
    first_unset: Option<usize>,
    param_regs: Vec<Option<u32>>,
    inputs: Vec<String>,
    input_regs: Vec<Option<u32>>,
    unknowns: Vec<String>,
    outputs: Vec<String>,
    input_kinds: Vec<QuantityKind>,
    unknown_kinds: Vec<QuantityKind>,
    output_kinds: Vec<QuantityKind>,
    /// The parameters that are angles (by index), whose size `angle_param_beyond` bounds.
    angle_params: Vec<usize>,
    /// What each parameter is, for the unit its values are written in.
    param_kinds: Vec<QuantityKind>,
    /// Per unknown: whether it follows the others (the compiled `Mechanism::FOLLOWERS`).
    pub(crate) followers: Vec<bool>,
    /// Per unknown: whether a closed form gives it as an angle (`CLOSED_FORM_ANGLES`).
    pub(crate) closed_form_angles: Vec<bool>,
    /// Whether the positions may jump (the compiled `Mechanism::PIECEWISE`).
    pub(crate) piecewise: bool,
    /// Per block in solve order: its equations (rows) and unknowns (columns).
    pub(crate) block_rows_cols: Vec<(Vec<usize>, Vec<usize>)>,
    /// Per block in solve order: its description with the model's names (the compiled
    /// mechanism's `BLOCKS`, owned), for its errors and events.
    pub(crate) block_infos: Vec<BlockInfo>,
    /// The nodes of the parameters alone, run when they are set.
    statics: Segment,
    guess: Segment,
    guess_regs: Vec<u32>,
    blocks: Vec<BlockProg>,
    outputs_seg: Segment,
    out_regs: Gather,
    out_d1_regs: Gather,
    out_d2_regs: Gather,
    instructions: usize,
    // The workspace of a step: written by every step, never reallocated.
    regs: Vec<f64>,
    facs: Vec<Fac>,
    state: State,
    at: AtProg,
    at_kin: AtKin,
    sens: Option<SensProg>,
    sens_state: Option<Sensitivities>,
    pair_d2: Vec<f64>,
    /// `pair_of[i * ni + j]`: the index of the input pair `(i, j)` among the pairs `i <= j`.
    pair_of: Vec<usize>,
    /// The declared bodies, loads and gravity (`None`: none declared).
    pub(crate) dynamics: Option<DynamicsProg>,
    /// Per block: a closed form's tests in a position-only solve ([`Model::positions`]).
    levers: Vec<Option<Levers>>,
    /// What the step's finiteness test adds up.
    finite: Finite,
    /// The configuration of the sweeps and analyses that take none ([`Model::sweep_config`]).
    pub(crate) sweep_config: SweepConfig,
}

fn kind(k: Kind) -> QuantityKind {
    match k {
        Kind::Angle => QuantityKind::Angle,
        Kind::Length => QuantityKind::Length,
        Kind::Dimensionless => QuantityKind::Dimensionless,
        _ => QuantityKind::Other,
    }
}

impl Model {
    /// Reads a declaration from its text (`name` names it in diagnostics, e.g. the file name):
    /// the macro's front end, checks, structure analysis and plan, then the run-time program.
    pub fn read(name: &str, text: &str) -> Result<Model, ReadError> {
        let tokens = source::tokens(name, text).map_err(ReadError::Rejected)?;
        // Kept for the messages of a rejection, which look at the names (a clone shares them).
        let kept = tokens.clone();
        let planned = kinloop_codegen::plan_declaration(tokens)
            .map_err(|e| ReadError::Rejected(Diagnostics::from_syn(name, text, e, &kept)))?;
        let warnings = Diagnostics::warnings(name, text, &planned.warnings);
        let mut m = Model::from_planned(planned)?;
        m.warnings = warnings;
        Ok(m)
    }

    /// The decomposition of the declaration `text` (counts, mobility, the blocks in solve order
    /// and how each is solved), as [`Model::decomposition`] gives it, also where the run-time
    /// evaluator does not evaluate the declaration ([`ReadError::Unsupported`]): the structure
    /// that says which block is too large. [`ReadError::Rejected`] for a declaration the macro
    /// rejects.
    pub fn decomposition_of(name: &str, text: &str) -> Result<String, ReadError> {
        let tokens = source::tokens(name, text).map_err(ReadError::Rejected)?;
        // Kept for the messages of a rejection, which look at the names (a clone shares them).
        let kept = tokens.clone();
        let planned = kinloop_codegen::plan_declaration(tokens)
            .map_err(|e| ReadError::Rejected(Diagnostics::from_syn(name, text, e, &kept)))?;
        Ok(kinloop_codegen::decomposition(&planned))
    }

    /// The warnings of the declaration (unused parameters), as the macro gives them.
    pub fn warnings(&self) -> Option<&Diagnostics> {
        self.warnings.as_ref()
    }

    /// Builds the run-time program of a planned declaration.
    pub fn from_planned(planned: Planned) -> Result<Model, ReadError> {
        let decomposition = kinloop_codegen::decomposition(&planned);
        let drawing = kinloop_codegen::drawing(&planned);
        let Planned { model, plan, .. } = planned;
        let g = &plan.graph;
        let unsupported = |what: String| Err(ReadError::Unsupported(what));
        for (b, bp) in plan.blocks.iter().enumerate() {
            let (n, sparse) = (bp.unknowns.len(), matches!(bp.solve, Solve::NewtonSparse(_)));
            if sparse && n > MAX_SPARSE {
                return unsupported(format!(
                    "block {b} is solved by sparse Newton with {n} unknowns (at most {MAX_SPARSE})"
                ));
            }
            if !sparse && n > MAX_DENSE {
                // Named as `kinloop check` names the block: a linear block is one linear solve.
                let how =
                    if matches!(bp.solve, Solve::Linear { .. }) { "as one linear system" } else { "by dense Newton" };
                return unsupported(format!(
                    "block {b} has {n} unknowns solved together {how}, more than the {MAX_DENSE} \
                     the run-time evaluator solves together: leave out `#[kinloop(dense)]` if the declaration has \
                     it (it solves every unknown in one block), declare the loops so that at most {MAX_DENSE} \
                     unknowns close together (`kinloop check` shows the blocks), or compile the \
                     declaration with `kinloop::mechanism!`, whose code has no such limit"
                ));
            }
        }
        let find = |l: Leaf| g.find(Op::Leaf(l)).map(|n| n.0);
        let (n, ni, np) = (plan.n, plan.ni, plan.np);
        let npairs = pairs(ni).len();
        let internal = |e: crate::tape::Unavailable| ReadError::Unsupported(format!("the plan reads {:?} early", e.0));

        // The declared guesses, evaluated on their own.
        let guess = Builder::new(g).segment(&plan.guesses, None).map_err(internal)?;
        let guess_regs = plan.guesses.iter().map(|n| n.0).collect();

        let mut tape = Builder::new(g);
        let mut blocks: Vec<BlockProg> = Vec::with_capacity(plan.blocks.len());
        // The closed forms' registers, after the graph's and the scratch register below.
        let mut extra = Extra::new(g.len() as u32 + 1);
        for (b, bp) in plan.blocks.iter().enumerate() {
            blocks.push(position_program(&plan, b, bp, &mut tape, &mut extra).map_err(internal)?);
        }
        for (b, bp) in plan.blocks.iter().enumerate() {
            let prog = &mut blocks[b];
            let mut roots: Vec<NodeId> = bp.vel.concat();
            let keeps = matches!(&prog.how, How::Newton(p) if p.keeps_lu);
            if !keeps {
                roots.extend(bp.col_scale.concat());
                roots.extend(bp.lever_floor.concat());
                roots.extend(&bp.row_scale);
            }
            roots.extend(bp.jac.concat());
            prog.vel = tape.segment(&roots, None).map_err(internal)?;
            let tans: Vec<Option<u32>> = bp
                .unknowns
                .iter()
                .flat_map(|&u| (0..ni).map(move |i| (u, i)))
                .map(|(u, i)| find(Leaf::Tan { unknown: u as u16, input: i as u16 }))
                .collect();
            tape.provide(tans.iter().flatten().map(|&k| NodeId(k)));
            prog.tan_regs = tans;
        }
        for (b, bp) in plan.blocks.iter().enumerate() {
            let prog = &mut blocks[b];
            prog.acc = tape.segment(&bp.acc.concat(), None).map_err(internal)?;
            let tan2: Vec<Option<u32>> = bp
                .unknowns
                .iter()
                .flat_map(|&u| pairs(ni).into_iter().map(move |p| (u, p)))
                .map(|(u, (i, j))| find(Leaf::Tan2 { unknown: u as u16, i: i as u16, j: j as u16 }))
                .collect();
            tape.provide(tan2.iter().flatten().map(|&k| NodeId(k)));
            prog.tan2_regs = tan2;
        }
        // One register past the graph's: where the analogs no node reads are written.
        let scratch = g.len() as u32;
        for prog in &mut blocks {
            prog.vel_cols = Columns::new(&prog.unknowns, ni, &prog.vel_rows, &prog.tan_regs, scratch);
            prog.acc_cols = Columns::new(&prog.unknowns, npairs, &prog.acc_rows, &prog.tan2_regs, scratch);
        }
        let out_roots: Vec<NodeId> =
            plan.outputs.iter().copied().chain(plan.out_d1.concat()).chain(plan.out_d2.concat()).collect();
        let outputs_seg = tape.segment(&out_roots, None).map_err(internal)?;
        let sens = SensProg::build(&plan, &mut tape).map_err(internal)?;
        let at = AtProg::build(&plan).map_err(internal)?;
        let at_kin = at_kinematics(&plan, &blocks, &out_roots).map_err(internal)?;
        let dynamics = DynamicsProg::build(&model.dynamics, &plan).map_err(internal)?;
        let levers =
            (0..plan.blocks.len()).map(|b| Levers::build(&plan, b)).collect::<Result<_, _>>().map_err(internal)?;
        let instructions = guess.len()
            + outputs_seg.len()
            + blocks
                .iter()
                .map(|p| {
                    p.pre.len()
                        + p.vel.len()
                        + p.acc.len()
                        + match &p.how {
                            How::Newton(nw) => nw.eval.len(),
                            _ => 0,
                        }
                })
                .sum::<usize>();

        let k = kinds::classify(&model, g, &plan.residuals, &plan.outputs);
        let name_of = |i: &proc_macro2::Ident| syn::ext::IdentExt::unraw(i).to_string();
        let param_values: Vec<Option<f64>> = match &plan.defaults {
            Some(d) => d.iter().map(|&v| Some(v)).collect(),
            None => model.params.iter().map(|p| p.value.and_then(|v| g.as_const(v))).collect(),
        };
        let no = plan.outputs.len();
        // What the emitter writes as `FOLLOWERS`, `CLOSED_FORM_ANGLES` and `PIECEWISE`, from the
        // same plan.
        let followers = kinloop_codegen::plan::followers::followers(&plan.graph, &plan.blocks, n);
        let closed_form_angles = kinloop_codegen::plan::closed_form_angles(&plan);
        let piecewise = kinloop_codegen::plan::piecewise(&plan);
        let block_rows_cols = plan.blocks.iter().map(|bp| (bp.equations.clone(), bp.unknowns.clone())).collect();
        // Named as the emitter names `BLOCKS`: unknowns by their declared names, equations by
        // theirs (`loop.x`, `loop.y`, an `eq` name).
        let block_infos = plan
            .blocks
            .iter()
            .map(|bp| {
                let unknowns = bp.unknowns.iter().map(|&u| name_of(&model.unknowns[u].name)).collect();
                let equations = bp.equations.iter().map(|&e| model.equations[e].name.clone()).collect();
                BlockInfo::owned(unknowns, equations, bp.solve.is_linear())
            })
            .collect();
        let state = State {
            x: vec![0.0; ni],
            q: vec![0.0; n],
            dq: vec![0.0; n * ni],
            d2q: vec![0.0; n * ni * ni],
            out: vec![0.0; no],
            dout: vec![0.0; no * ni],
            d2out: vec![0.0; no * ni * ni],
            report: SolveReport::direct(),
            health: Health::default(),
        };
        let sens_state = sens.as_ref().map(|p| p.empty(n, no));
        // Each block's factorisation slot; a sparse block's solver with its workspace.
        let mut facs = Vec::with_capacity(blocks.len());
        for (b, bp) in plan.blocks.iter().enumerate() {
            facs.push(match &bp.solve {
                Solve::NewtonSparse(sp) => {
                    let entries = sp.entries.iter().map(|&(r, c)| bp.jac[r][c].0).collect();
                    let block = sparse::block(sparse::tables(sp), entries).ok_or_else(|| {
                        // The plan's density bound keeps the non-zeros within a quarter of
                        // the padded square: not reached.
                        ReadError::Unsupported(format!(
                            "block {b}: {} non-zeros, beyond the capacity of a sparse block of {} unknowns",
                            sp.entries.len(),
                            bp.unknowns.len()
                        ))
                    })?;
                    Fac::Sparse(block)
                }
                // Never changes: written once, not by every step.
                Solve::Fixed { coefficient, .. } => Fac::Fixed(kinloop_runtime::generated::Fixed(*coefficient)),
                _ => Fac::for_size(bp.unknowns.len()),
            });
        }
        let mut m = Model {
            sweep_config: SweepConfig::default(),
            at,
            at_kin,
            sens,
            sens_state,
            name: name_of(&model.name),
            decomposition,
            drawing,
            warnings: None,
            params: model.params.iter().map(|p| name_of(&p.name)).collect(),
            param_values,
            first_unset: None,
            param_regs: (0..np).map(|k| find(Leaf::Param(k as u16))).collect(),
            inputs: model.inputs.iter().map(|p| name_of(&p.name)).collect(),
            input_regs: (0..ni).map(|k| find(Leaf::Input(k as u16))).collect(),
            unknowns: model.unknowns.iter().map(|p| name_of(&p.name)).collect(),
            outputs: model.output_names(),
            input_kinds: k.inputs.iter().map(|&x| kind(x)).collect(),
            unknown_kinds: k.unknowns.iter().map(|&x| kind(x)).collect(),
            output_kinds: k.outputs.iter().map(|&x| kind(x)).collect(),
            angle_params: (0..k.params.len()).filter(|&p| k.params[p] == Kind::Angle).collect(),
            param_kinds: k.params.iter().map(|&x| kind(x)).collect(),
            followers,
            closed_form_angles,
            piecewise,
            block_rows_cols,
            block_infos,
            statics: statics(g),
            guess,
            guess_regs,
            facs,
            blocks,
            outputs_seg,
            out_regs: Gather::new(plan.outputs.iter().map(|n| n.0).collect()),
            out_d1_regs: Gather::new(plan.out_d1.concat().iter().map(|n| n.0).collect()),
            out_d2_regs: Gather::new(plan.out_d2.concat().iter().map(|n| n.0).collect()),
            instructions,
            regs: {
                let mut r = registers(g);
                r.resize(extra.len(), 0.0);
                extra.write_constants(&mut r);
                r
            },
            state,
            pair_d2: vec![0.0; n.max(no) * npairs],
            pair_of: (0..ni * ni).map(|ij| kinloop_codegen::plan::pair_index(ni, ij / ni, ij % ni)).collect(),
            dynamics,
            levers,
            finite: Finite::build(&plan),
        };
        m.load_params();
        Ok(m)
    }

    /// The registers (the parameters' nodes hold their values once they are set).
    pub(crate) fn registers_view(&self) -> &[f64] {
        &self.regs
    }

    /// The programs of the Newton blocks, block by block.
    #[cfg(test)]
    pub(crate) fn newton_progs(&self) -> Vec<crate::newton::NewtonProg> {
        self.blocks
            .iter()
            .filter_map(|b| match &b.how {
                How::Newton(p) => Some(p.clone()),
                _ => None,
            })
            .collect()
    }

    /// The registers and the dynamics program, borrowed together.
    pub(crate) fn regs_and_dynamics(&mut self) -> (&mut [f64], Option<&mut DynamicsProg>) {
        (&mut self.regs, self.dynamics.as_mut())
    }

    /// Writes the parameters' registers and computes what depends on them alone. Every change
    /// of a parameter goes through here (the registers must follow it), so the first unset
    /// parameter is found here too, not on every step.
    fn load_params(&mut self) {
        self.first_unset = self.param_values.iter().position(Option::is_none);
        for (k, reg) in self.param_regs.iter().enumerate() {
            if let Some(reg) = reg {
                self.regs[*reg as usize] = self.param_values[k].unwrap_or(f64::NAN);
            }
        }
        self.statics.run(&mut self.regs);
    }

    /// The state the last step wrote (where a failed step stopped, its values so far).
    pub(crate) fn state(&self) -> &State {
        &self.state
    }

    /// The first row of block `b`'s system holding a non-finite value after its factorisation
    /// failed, as the compiled step diagnoses it (`first_bad_row`): a linear block's position
    /// solve reads its rows with their right-hand sides; the analogs (`at`: at a given position,
    /// where a linear block is tested too) the Jacobian's rows, then the velocity's.
    pub(crate) fn bad_row(&self, b: usize, at: bool) -> Option<usize> {
        let prog = self.blocks.get(b)?;
        let r = &self.regs;
        let bad = |k: &u32| !r[*k as usize].is_finite();
        let mut rows = prog.jac.chunks(prog.unknowns.len().max(1));
        match (&prog.how, at) {
            (How::Linear { rhs }, false) => rows.zip(rhs).position(|(row, k)| row.iter().any(bad) || bad(k)),
            _ => rows
                .position(|row| row.iter().any(bad))
                .or_else(|| prog.vel_rows.chunks(self.inputs.len().max(1)).position(|row| row.iter().any(bad))),
        }
    }

    /// The mechanism's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The decomposition in words: counts, mobility, and how each block is solved (the
    /// compiled mechanism's `DECOMPOSITION`).
    pub fn decomposition(&self) -> &str {
        &self.decomposition
    }

    /// Parameter names, in declaration order.
    pub fn params(&self) -> &[String] {
        &self.params
    }

    /// Parameter values (`None`: no default and not set).
    pub fn param_values(&self) -> &[Option<f64>] {
        &self.param_values
    }

    /// Sets parameter `name`; `false` when there is no such parameter.
    pub fn set_param(&mut self, name: &str, value: f64) -> bool {
        match self.params.iter().position(|p| p == name) {
            Some(k) => {
                self.param_values[k] = Some(value);
                self.load_params();
                true
            }
            None => false,
        }
    }

    /// Exchanges the parameters' values (one per parameter, in declaration order) with `values`
    /// and loads them, as [`Model::set_param`] does one: the whole set at once, without a name
    /// lookup (synthesis sets and puts back every parameter per evaluation).
    pub(crate) fn swap_params(&mut self, values: &mut Vec<Option<f64>>) {
        debug_assert_eq!(values.len(), self.param_values.len());
        std::mem::swap(&mut self.param_values, values);
        self.load_params();
    }

    /// Input names.
    pub fn inputs(&self) -> &[String] {
        &self.inputs
    }

    /// Unknown names.
    pub fn unknowns(&self) -> &[String] {
        &self.unknowns
    }

    /// Output column names (`p.x`, `p.y` for a point `p`, then the scalar outputs).
    pub fn outputs(&self) -> &[String] {
        &self.outputs
    }

    /// What each parameter is (angle, length, ...), as the macro infers it: an angle parameter
    /// is in radians, whatever a command line writes angles in.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_runtime::QuantityKind;
    /// let text = "pub struct Crank { params r = 1, l = 3, tilt = 0.1; input phi; unknowns psi = 0, x = 3; \
    ///             loop a: r @ (phi + tilt) == (x, 0) + l @ psi; }";
    /// let m = Model::read("crank.kl", text).expect("the crank reads");
    /// assert_eq!(m.param_kinds(), [QuantityKind::Length, QuantityKind::Length, QuantityKind::Angle]);
    /// ```
    pub fn param_kinds(&self) -> &[QuantityKind] {
        &self.param_kinds
    }

    /// What each input is (angle, length, ...), as the macro infers it.
    pub fn input_kinds(&self) -> &[QuantityKind] {
        &self.input_kinds
    }

    /// What each unknown is.
    pub fn unknown_kinds(&self) -> &[QuantityKind] {
        &self.unknown_kinds
    }

    /// What each output column is.
    pub fn output_kinds(&self) -> &[QuantityKind] {
        &self.output_kinds
    }

    /// The number of blocks.
    pub fn block_count(&self) -> usize {
        self.blocks.len()
    }

    /// The number of instructions of one step's tape (all segments, each Newton evaluation
    /// counted once).
    pub fn instructions(&self) -> usize {
        self.instructions
    }

    /// Whether the last step factorised block `block`'s analogs by the dense fallback (a
    /// static pivot of its sparse elimination order was weak: below a tenth of its column in
    /// the active submatrix, as in the compiled mechanism); `None` for a block not solved by
    /// sparse Newton.
    pub fn dense_fallback(&self, block: usize) -> Option<bool> {
        match self.facs.get(block)? {
            Fac::Sparse(s) => Some(s.is_dense()),
            _ => None,
        }
    }

    /// The registers of one step: one per graph node, then the closed forms' constants and
    /// intermediate values.
    pub fn registers(&self) -> usize {
        self.regs.len()
    }

    /// The first angle parameter whose value is finite and larger in magnitude than `bound`
    /// (the compiled mechanism's `angle_param_beyond`), by its index in [`Model::params`]. With
    /// `bound` a configuration's `NewtonConfig::largest_precise_angle`, the parameter every solve
    /// with that configuration refuses ([`StepError::ImpreciseParam`], `Error::InvalidArgument`
    /// from a kernel): a program that takes the parameters from its user can say so in its own
    /// terms before it solves.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_runtime::NewtonConfig;
    /// let text = "pub struct Lever {
    ///     params r = 1, tilt = 0.3;
    ///     input phi;
    ///     point p = r @ (phi + tilt);
    /// }";
    /// let mut m = Model::read("lever.kl", text).unwrap();
    /// let bound = NewtonConfig::default().largest_precise_angle();
    /// assert_eq!(m.angle_param_beyond(bound), None);
    /// m.set_param("tilt", 1e17);
    /// assert_eq!(m.angle_param_beyond(bound), Some(1));
    /// // A length is no angle: however large, it is not one of these.
    /// m.set_param("tilt", 0.3);
    /// m.set_param("r", 1e17);
    /// assert_eq!(m.angle_param_beyond(bound), None);
    /// ```
    pub fn angle_param_beyond(&self, bound: f64) -> Option<usize> {
        let beyond = |v: f64| v.abs() > bound && v.is_finite();
        self.angle_params.iter().copied().find(|&k| self.param_values[k].is_some_and(beyond))
    }

    /// The first parameter without a value, kept by `load_params` (every change of a parameter
    /// goes through it), so that a check costs no scan of the parameters.
    pub(crate) fn first_unset(&self) -> Option<usize> {
        self.first_unset
    }

    fn check_ready(&self, x: &[f64]) -> Result<(), StepError> {
        if let Some(k) = self.first_unset {
            return Err(StepError::UnsetParam(self.params[k].clone()));
        }
        if x.len() != self.inputs.len() {
            return Err(StepError::Size { what: "inputs", expected: self.inputs.len(), given: x.len() });
        }
        Ok(())
    }

    fn load_inputs(&mut self, x: &[f64]) {
        for (i, reg) in self.input_regs.iter().enumerate() {
            if let Some(reg) = reg {
                self.regs[*reg as usize] = x[i];
            }
        }
    }

    /// The declared initial guess at inputs `x`, into `out` (one value per unknown).
    pub fn guess(&mut self, x: &[f64], out: &mut [f64]) -> Result<(), StepError> {
        self.check_ready(x)?;
        if out.len() != self.unknowns.len() {
            return Err(StepError::Size { what: "guess", expected: self.unknowns.len(), given: out.len() });
        }
        self.load_inputs(x);
        self.guess.run(&mut self.regs);
        for (o, &reg) in out.iter_mut().zip(&self.guess_regs) {
            *o = self.regs[reg as usize];
        }
        Ok(())
    }

    /// Positions, velocity and acceleration analogs and outputs at inputs `x`, solved from
    /// `guess` with `cfg`: the compiled mechanism's `kinematics_flat`. No allocation.
    pub fn kinematics(&mut self, x: &[f64], guess: &[f64], cfg: &NewtonConfig) -> Result<&State, StepError> {
        let error = match self.solve_positions(x, guess, cfg, false) {
            Ok(()) => match self.analogs::<false>(cfg) {
                Ok(()) => return Ok(&self.state),
                Err(e) => e,
            },
            Err(e) => e,
        };
        // A mechanism of extreme size is solved again, as the compiled step solves it.
        self.rescue(x, guess, cfg, error)?;
        Ok(&self.state)
    }

    /// Every block's unknowns at inputs `x` solved from `guess` with `cfg` into the state (its
    /// inputs, report and health reset first), after the arguments and settings are checked:
    /// the position half of [`Model::kinematics`] and all of [`Model::positions`], which asks
    /// the closed forms' lever tests (`lever_tests`) where the analogs would find the fault.
    #[inline(always)]
    fn solve_positions(
        &mut self,
        x: &[f64],
        guess: &[f64],
        cfg: &NewtonConfig,
        lever_tests: bool,
    ) -> Result<(), StepError> {
        self.check_ready(x)?;
        if guess.len() != self.unknowns.len() {
            return Err(StepError::Size { what: "guess", expected: self.unknowns.len(), given: guess.len() });
        }
        if let Some(field) = cfg.invalid_field() {
            return Err(StepError::InvalidConfig(field));
        }
        if let ([Some(reg)], [d], [v]) = (&self.input_regs[..], &mut self.state.x[..], x) {
            // One input (most mechanisms): into its register and the state with no loop and no
            // call of `memcpy` (which `copy_from_slice` of a slice of unknown length is).
            self.regs[*reg as usize] = *v;
            *d = *v;
        } else {
            self.load_inputs(x);
            self.state.x.copy_from_slice(x);
        }
        let st = &mut self.state;
        st.report = SolveReport::direct();
        st.health = Health::default();
        let (regs, q, report) = (&mut self.regs[..], &mut st.q[..], &mut st.report);
        for (b, (prog, fac)) in self.blocks.iter().zip(self.facs.iter_mut()).enumerate() {
            let levers = if lever_tests { self.levers[b].as_ref() } else { None };
            let w = Work { r: &mut *regs, fac, cfg };
            prog.position(w, q, guess, report, levers).map_err(|failure| StepError::Block { block: b, failure })?;
        }
        Ok(())
    }

    /// Positions only, at inputs `x` solved from `guess` with `cfg`: every block's unknowns, no
    /// analogs and no outputs (the compiled mechanism's `position_flat`). A closed form tests
    /// itself for a position its data do not determine (a lever short against its floor, a
    /// dyad on coincident centres), as there; a position where only the analogs are singular (a
    /// limit position) is solved. A mechanism beyond the closed forms' sizes whose closed form
    /// fails is solved again by Newton over the whole system, as by [`Model::kinematics`]. No
    /// allocation outside that rescue.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_runtime::NewtonConfig;
    /// let text = "pub struct FourBar {
    ///     params a = 1, b = 3, c = 2.5, d = 3.2;
    ///     input phi;
    ///     unknowns psi = 0.6, theta = 1.9;
    ///     loop abcd: a @ phi + b @ psi == (d, 0) + c @ theta;
    /// }";
    /// let mut m = Model::read("four_bar.kl", text).unwrap();
    /// let q = m.positions(&[0.5], &[0.6, 1.9], &NewtonConfig::default()).unwrap().to_vec();
    /// assert_eq!(q, m.kinematics(&[0.5], &[0.6, 1.9], &NewtonConfig::default()).unwrap().q);
    /// ```
    pub fn positions(&mut self, x: &[f64], guess: &[f64], cfg: &NewtonConfig) -> Result<&[f64], StepError> {
        if let Err(error) = self.solve_positions(x, guess, cfg, true) {
            // A mechanism of extreme size is solved again, as the compiled `position_flat`
            // solves it (the inputs were checked: the rescue runs after a block's failure).
            let (q, report) = self.rescue_position(x, guess, cfg, error)?;
            self.state.x.copy_from_slice(x);
            self.state.q.copy_from_slice(&q);
            self.set_report(report);
        }
        Ok(&self.state.q)
    }

    fn check_at(&mut self, x: &[f64], q: &[f64]) -> Result<(), StepError> {
        self.check_ready(x)?;
        if q.len() != self.unknowns.len() {
            return Err(StepError::Size { what: "unknowns", expected: self.unknowns.len(), given: q.len() });
        }
        self.load_inputs(x);
        Ok(())
    }

    /// The residuals of the equations at `(x, q)`, in declaration order, into `out` (the
    /// compiled mechanism's `residual_flat`).
    pub fn residual(&mut self, x: &[f64], q: &[f64], out: &mut [f64]) -> Result<(), StepError> {
        self.check_at(x, q)?;
        if out.len() != self.at.residuals() {
            return Err(StepError::Size { what: "residual places", expected: self.at.residuals(), given: out.len() });
        }
        self.at.residual(&mut self.regs, q, out);
        Ok(())
    }

    /// The output columns at `(x, q)` into `out` (the compiled mechanism's `outputs_flat`).
    pub fn outputs_at(&mut self, x: &[f64], q: &[f64], out: &mut [f64]) -> Result<(), StepError> {
        self.check_at(x, q)?;
        if out.len() != self.outputs.len() {
            return Err(StepError::Size { what: "output places", expected: self.outputs.len(), given: out.len() });
        }
        self.at.outputs(&mut self.regs, q, out);
        Ok(())
    }

    /// The residuals, the full Jacobians and the magnitudes at `(x, q)` into `out` (the compiled
    /// mechanism's `jacobian_flat`; `out`'s vectors are reused).
    pub fn jacobian(&mut self, x: &[f64], q: &[f64], out: &mut Jacobian) -> Result<(), StepError> {
        self.check_at(x, q)?;
        self.at.jacobian(&mut self.regs, q, out);
        Ok(())
    }

    /// The analogs and outputs after the positions (`AT`: of the evaluation at a given position,
    /// [`Model::kinematics_at`]), and the state's finiteness test. One instance per mode: the
    /// step's choices between the two fold away (about 100 instructions a rhombic-drive step
    /// when the mode was an argument).
    fn analogs<const AT: bool>(&mut self, cfg: &NewtonConfig) -> Result<(), StepError> {
        let at = AT;
        let ni = self.inputs.len();
        let st = &mut self.state;
        // Slices taken once: their addresses and lengths stay in registers through the blocks.
        let (regs, dq, health) = (&mut self.regs[..], &mut st.dq[..], &mut st.health);
        for (b, (prog, fac)) in self.blocks.iter().zip(self.facs.iter_mut()).enumerate() {
            let w = Work { r: &mut *regs, fac, cfg };
            prog.velocity(b, w, dq, health, at.then(|| &self.at_kin.vel[b]))
                .map_err(|failure| StepError::Block { block: b, failure })?;
        }
        let np = ni * (ni + 1) / 2;
        // One input: one pair, the pairs' array is the full one; the analogs go straight there.
        let acc_out = if ni == 1 { &mut st.d2q[..] } else { &mut self.pair_d2[..] };
        for (b, (prog, fac)) in self.blocks.iter().zip(&self.facs).enumerate() {
            prog.acceleration(regs, acc_out, fac, at.then(|| &self.at_kin.acc[b]));
        }
        // Pairs (i <= j) to the full symmetric second analogs.
        let pair_of = &self.pair_of;
        let full = |pair_vals: &[f64], rows: usize, out: &mut [f64]| {
            for (row, pairs) in out.chunks_exact_mut(ni * ni).zip(pair_vals.chunks_exact(np)).take(rows) {
                for (o, &p) in row.iter_mut().zip(pair_of) {
                    *o = pairs[p];
                }
            }
        };
        if ni != 1 {
            full(&self.pair_d2, self.unknowns.len(), &mut st.d2q);
        }
        if at { &self.at_kin.out } else { &self.outputs_seg }.run(&mut self.regs);
        // A slice: its address and length stay in registers through the copies below.
        let r: &[f64] = &self.regs;
        self.out_regs.run(r, &mut st.out);
        self.out_d1_regs.run(r, &mut st.dout);
        if ni == 1 {
            self.out_d2_regs.run(r, &mut st.d2out);
        } else {
            self.out_d2_regs.run(r, &mut self.pair_d2);
            full(&self.pair_d2, self.outputs.len(), &mut st.d2out);
        }
        // The compiled step's test: one sum of the values the others' finiteness does not
        // cover, the whole state examined only when it is not finite. At a given position
        // (whose unknowns no solve checked) the whole state, as the compiled `At` kernel.
        let all = || [&st.q, &st.dq, &st.d2q, &st.out, &st.dout, &st.d2out].iter().all(|v| all_finite(v));
        let finite = if at {
            all()
        } else {
            let by_sum = self.finite.sum(r, &st.q, &st.dq, &st.d2q).is_finite();
            // The analysis left values out of the sum: every debug step checks that their
            // finiteness did follow from the sum's.
            debug_assert!(!by_sum || all(), "the finiteness sum is finite, a value it left out is not");
            by_sum || all()
        };
        if !finite {
            return Err(StepError::NonFinite);
        }
        Ok(())
    }

    /// Analogs and outputs at a position `q` the caller already solved (the compiled
    /// mechanism's `kinematics_at_flat`): the report carries the residual there, every block's
    /// Jacobian is factorised from the graph. No allocation. A parameter or an input not finite
    /// is [`StepError::NotFinite`], an unknown of `q` not finite [`StepError::NonFinitePosition`],
    /// a configuration out of range [`StepError::InvalidConfig`].
    pub fn kinematics_at(&mut self, x: &[f64], q: &[f64], cfg: &NewtonConfig) -> Result<&State, StepError> {
        self.check_at(x, q)?;
        // A parameter or an input not finite first, as the compiled step's bad-value test
        // names it: the state computed from it was "a value of the state is not finite".
        self.finite_values(x)?;
        // The caller's position, not a solve's: a value not finite there is the caller's to
        // mend, where the step would call it a singular Jacobian or an equation not finite.
        if let Some(u) = q.iter().position(|v| !v.is_finite()) {
            return Err(StepError::NonFinitePosition { unknown: self.unknowns[u].clone(), value: q[u] });
        }
        // The analogs read `singular_tol`: a NaN one made every block singular.
        if let Some(field) = cfg.invalid_field() {
            return Err(StepError::InvalidConfig(field));
        }
        for (u, reg) in self.at.unknown_regs.iter().enumerate() {
            if let Some(reg) = reg {
                self.regs[*reg as usize] = q[u];
            }
        }
        self.at_kin.residual.run(&mut self.regs);
        let residual = crate::factor::max_abs(self.at_kin.residual_regs.iter().map(|&r| self.regs[r as usize]));
        let st = &mut self.state;
        st.x.copy_from_slice(x);
        st.q.copy_from_slice(q);
        st.report = SolveReport::given(residual);
        st.health = Health::default();
        self.analogs::<true>(cfg)?;
        Ok(&self.state)
    }

    /// The position solve's report of the state (a solve that gave the position to
    /// [`Model::kinematics_at`] its own).
    pub(crate) fn set_report(&mut self, report: SolveReport) {
        self.state.report = report;
    }

    /// Whether the declaration asks for parameter sensitivities (`#[kinloop(sensitivities)]`).
    pub fn has_sensitivities(&self) -> bool {
        self.sens.is_some()
    }

    /// [`Model::kinematics`] and the sensitivities of the state to every parameter, on the same
    /// factorisations (the compiled mechanism's `sensitivities_flat`); `None` in place of the
    /// sensitivities when the declaration did not ask for them. No allocation.
    pub fn sensitivities(
        &mut self,
        x: &[f64],
        guess: &[f64],
        cfg: &NewtonConfig,
    ) -> Result<(&State, Option<&Sensitivities>), StepError> {
        self.kinematics(x, guess, cfg)?;
        self.sensitivities_here()
    }

    /// [`Model::kinematics_at`] and the sensitivities of the state to every parameter, at a
    /// position `q` the caller already solved (the compiled mechanism's
    /// `sensitivities_at_flat`); `None` in place of the sensitivities when the declaration did
    /// not ask for them. No allocation.
    pub fn sensitivities_at(
        &mut self,
        x: &[f64],
        q: &[f64],
        cfg: &NewtonConfig,
    ) -> Result<(&State, Option<&Sensitivities>), StepError> {
        self.kinematics_at(x, q, cfg)?;
        self.sensitivities_here()
    }

    /// The sensitivities of the state just computed, on its factorisations (checked finite).
    fn sensitivities_here(&mut self) -> Result<(&State, Option<&Sensitivities>), StepError> {
        if let (Some(p), Some(s)) = (&self.sens, &mut self.sens_state) {
            p.run(&mut self.regs, &self.facs, s);
            let all = [&s.q, &s.dq, &s.d2q, &s.out, &s.dout, &s.d2out];
            if !all.iter().all(|v| v.iter().all(|x| x.is_finite())) {
                return Err(StepError::NonFinite);
            }
        }
        Ok((&self.state, self.sens_state.as_ref()))
    }

    /// The first parameter or input (at `x`) not finite, as [`StepError::NotFinite`]:
    /// parameters first, then inputs, as the compiled step's bad-value test looks for one.
    fn finite_values(&self, x: &[f64]) -> Result<(), StepError> {
        let params = self.params.iter().zip(&self.param_values).filter_map(|(p, v)| Some(("parameter", p, (*v)?)));
        let inputs = self.inputs.iter().zip(x).map(|(i, v)| ("input", i, *v));
        match params.chain(inputs).find(|(.., v)| !v.is_finite()) {
            Some((what, name, value)) => Err(StepError::NotFinite { what, name: name.clone(), value }),
            None => Ok(()),
        }
    }

    /// [`Model::kinematics`] from the declared initial guess with the default configuration
    /// (the compiled mechanism's `solve`). An angle parameter beyond the configuration's
    /// `largest_precise_angle` is [`StepError::ImpreciseParam`], as the compiled `solve` refuses it;
    /// a parameter or an input not finite is [`StepError::NotFinite`], named as the compiled
    /// `solve` names it (the step's own error would be the first block's, failing on it).
    pub fn solve(&mut self, x: &[f64]) -> Result<&State, StepError> {
        let bound = NewtonConfig::default().largest_precise_angle();
        if let Some(k) = self.angle_param_beyond(bound) {
            let (param, value) = (self.params[k].clone(), self.param_values[k].unwrap_or(f64::NAN));
            return Err(StepError::ImpreciseParam { param, value, bound });
        }
        self.finite_values(x)?;
        let mut guess = vec![0.0; self.unknowns.len()];
        self.guess(x, &mut guess)?;
        self.kinematics(x, &guess, &NewtonConfig::default())
    }
}

/// The position part of block `b`'s program, its segments appended to `tape` in the order the
/// step runs them.
fn position_program(
    plan: &Plan,
    b: usize,
    bp: &BlockPlan,
    tape: &mut Builder<'_>,
    extra: &mut Extra,
) -> Result<BlockProg, crate::tape::Unavailable> {
    let g = &plan.graph;
    let find = |l: Leaf| g.find(Op::Leaf(l));
    let nb = bp.unknowns.len();
    let unknown_nodes: Vec<Option<NodeId>> = bp.unknowns.iter().map(|&u| find(Leaf::Unknown(u as u16))).collect();
    let regs = |v: &[NodeId]| v.iter().map(|n| n.0).collect::<Vec<u32>>();
    let jac = regs(&bp.jac.concat());
    let col: Vec<Vec<u32>> =
        (0..nb).map(|c| bp.col_scale[c].iter().chain(&bp.lever_floor[c]).map(|n| n.0).collect()).collect();
    let floors: Vec<Vec<u32>> = bp.lever_floor.iter().map(|f| regs(f)).collect();
    let rows = regs(&bp.row_scale);
    // A block of two unknowns: its columns' entries in the rows of later blocks, when any.
    let beyond: Option<[Vec<u32>; 2]> = (nb == 2)
        .then(|| {
            [0, 1].map(|c| {
                let own = [bp.jac[0][c], bp.jac[1][c]];
                bp.col_scale[c].iter().filter(|e| !own.contains(e)).map(|n| n.0).collect::<Vec<u32>>()
            })
        })
        .filter(|b| b.iter().any(|c| !c.is_empty()));
    let in_col = (nb == 1).then(|| bp.col_scale[0].iter().position(|&e| e == bp.jac[0][0])).flatten();
    let level_below = |n: NodeId| plan.level[n.index()] < b as i32;
    let (pre, how) = match &bp.solve {
        Solve::Fixed { coefficient, rhs } => {
            (tape.segment(&[*rhs], None)?, How::Fixed { coefficient: *coefficient, rhs: rhs.0 })
        }
        Solve::Linear { rhs } => {
            let roots: Vec<NodeId> = bp
                .jac
                .concat()
                .into_iter()
                .chain(rhs.iter().copied())
                .chain(bp.col_scale.concat())
                .chain(bp.lever_floor.concat())
                .chain(bp.row_scale.iter().copied())
                .collect();
            (tape.segment(&roots, None)?, How::Linear { rhs: regs(rhs) })
        }
        Solve::ClosedForm(rec) => {
            let pre = tape.segment(&rec.form.coefficients(), None)?;
            let sin_cos: Vec<[Option<u32>; 2]> = rec.sin_cos.iter().map(|[s, c]| [Some(s.0), Some(c.0)]).collect();
            tape.provide(rec.sin_cos.concat());
            let prog = ClosedProg::build(&rec.form, g, &sin_cos, extra);
            let prog = match bp.terms {
                Some(terms) => prog.with_terms(terms_segment(plan, b, terms)?, terms.0),
                None => prog,
            };
            (pre, How::Closed(prog))
        }
        Solve::Newton | Solve::NewtonSparse(_) => {
            // Every unknown of a Newton block is read by its equations: its leaf is in the graph.
            if let Some(k) = unknown_nodes.iter().position(Option::is_none) {
                return Err(crate::tape::Unavailable(Leaf::Unknown(bp.unknowns[k] as u16)));
            }
            let roots: Vec<NodeId> =
                bp.f.iter()
                    .copied()
                    .chain(bp.jac.concat())
                    .chain(bp.scale.iter().copied())
                    .chain(bp.unit.iter().copied())
                    .collect();
            // What does not depend on the block's unknowns is computed once, before the solve.
            let pre = tape.segment(&roots, Some(&level_below))?;
            tape.provide(unknown_nodes.iter().flatten().copied());
            // Its sines and cosines rotated from the solve's previous evaluation (`crate::near`).
            let (eval, near) = tape.near_segment(&roots, extra)?;
            let fixed_mags = bp.scale.iter().chain(&bp.unit).all(|m| level_below(*m));
            let prog = NewtonProg {
                eval,
                near,
                unknowns: bp.unknowns.clone(),
                unknown_regs: unknown_nodes.iter().map(|n| n.map_or(u32::MAX, |n| n.0)).collect(),
                f: regs(&bp.f),
                jac: jac.clone(),
                scale: regs(&bp.scale),
                unit: regs(&bp.unit),
                turns: bp.turns.clone(),
                fixed_mags,
                keeps_lu: keeps_lu(bp),
            };
            (pre, How::Newton(prog))
        }
    };
    tape.provide(unknown_nodes.iter().flatten().copied());
    let analog = |at: bool| Analog::of(&how, nb, in_col.is_some(), !rows.is_empty(), at);
    let (analog, analog_at) = (analog(false), analog(true));
    Ok(BlockProg {
        unknowns: bp.unknowns.clone(),
        unknown_regs: unknown_nodes.iter().map(|n| n.map(|n| n.0)).collect(),
        pre,
        how,
        jac,
        col,
        floors,
        rows,
        beyond,
        in_col,
        vel: Segment::default(),
        vel_rows: bp.vel.concat().iter().map(|n| n.0).collect(),
        tan_regs: Vec::new(),
        acc: Segment::default(),
        acc_rows: bp.acc.concat().iter().map(|n| n.0).collect(),
        tan2_regs: Vec::new(),
        vel_cols: Default::default(),
        acc_cols: Default::default(),
        analog,
        analog_at,
    })
}

/// The segment computing `terms`, the magnitude of closed-form block `b`'s equation's terms
/// (the plan's `BlockPlan::terms`), where its root fails: from what the earlier blocks' solves
/// wrote (their unknowns, a closed form's sines and cosines) and the block's coefficients, the
/// rest with the operations of the step's own segments (as the position-only tests', see
/// `crate::levers`), so the value the compiled solve computes there.
fn terms_segment(plan: &Plan, b: usize, terms: NodeId) -> Result<Segment, crate::tape::Unavailable> {
    let g = &plan.graph;
    let mut tape = Builder::new(g);
    for earlier in &plan.blocks[..b] {
        tape.provide(earlier.unknowns.iter().filter_map(|&u| g.find(Op::Leaf(Leaf::Unknown(u as u16)))));
        if let Solve::ClosedForm(r) = &earlier.solve {
            tape.provide(r.sin_cos.concat());
        }
    }
    if let Solve::ClosedForm(rec) = &plan.blocks[b].solve {
        tape.provide(rec.form.coefficients());
    }
    tape.segment(&[terms], None)
}

/// Whether a dense Newton block's analogs reuse the factorisation of its final correction:
/// the emitter's rule for the fused kernel (every non-zero entry of the block's Jacobian
/// columns is one of the block's own entries, and no column has a lever floor), which decides
/// whether the compiled kernel calls `newton_keeping_lu`.
fn keeps_lu(bp: &BlockPlan) -> bool {
    matches!(bp.solve, Solve::Newton)
        && bp.lever_floor.iter().all(Vec::is_empty)
        && bp
            .col_scale
            .iter()
            .enumerate()
            .all(|(c, col)| col.iter().all(|e| bp.jac.iter().any(|row| row.get(c) == Some(e))))
}

impl State {
    /// The state as one table row, in the order of [`Model::columns`] (the runtime's
    /// `Table::kin_row`): inputs; unknowns, their first analogs, their second analogs (pairs
    /// `i <= j`); the same for the output columns.
    pub fn row(&self) -> Vec<f64> {
        let ni = self.x.len();
        let mut row = self.x.clone();
        for (values, d1, d2) in [(&self.q, &self.dq, &self.d2q), (&self.out, &self.dout, &self.d2out)] {
            row.extend(values);
            row.extend(d1.iter());
            for u in 0..values.len() {
                for i in 0..ni {
                    for j in i..ni {
                        row.push(d2[(u * ni + i) * ni + j]);
                    }
                }
            }
        }
        row
    }
}

impl Model {
    /// The names of a state's table columns (the runtime's `Table::kin_columns`): `phi`, `psi`,
    /// `d(psi)/d(phi)`, `d2(psi)/d(phi)^2`, `d2(n)/d(i)d(j)`, ...
    pub fn columns(&self) -> Vec<String> {
        let mut c = self.inputs.clone();
        for names in [&self.unknowns, &self.outputs] {
            c.extend(names.iter().cloned());
            for n in names {
                for i in &self.inputs {
                    c.push(format!("d({n})/d({i})"));
                }
            }
            for n in names {
                for (a, i) in self.inputs.iter().enumerate() {
                    for j in &self.inputs[a..] {
                        c.push(if i == j { format!("d2({n})/d({i})^2") } else { format!("d2({n})/d({i})d({j})") });
                    }
                }
            }
        }
        c
    }

    /// The base quantities with their kinds: inputs, unknowns and output columns (a point's
    /// `p.x`, `p.y`), for units.
    pub fn quantities(&self) -> Vec<(&str, QuantityKind)> {
        let names = self.inputs.iter().chain(&self.unknowns).chain(&self.outputs);
        let kinds = self.input_kinds.iter().chain(&self.unknown_kinds).chain(&self.output_kinds);
        names.map(String::as_str).zip(kinds.copied()).collect()
    }
}

/// The segments of [`Model::kinematics_at`]: the residuals at the given position, then per
/// block the analogs' right-hand sides and Jacobian, then the outputs (the emitter's mode `At`).
#[derive(Clone)]
struct AtKin {
    residual: Segment,
    residual_regs: Vec<u32>,
    vel: Vec<Segment>,
    acc: Vec<Segment>,
    out: Segment,
}

fn at_kinematics(plan: &Plan, blocks: &[BlockProg], out_roots: &[NodeId]) -> Result<AtKin, crate::tape::Unavailable> {
    let g = &plan.graph;
    let mut tape = Builder::new(g);
    tape.provide((0..plan.n).filter_map(|u| g.find(Op::Leaf(Leaf::Unknown(u as u16)))));
    let residual = tape.segment(&plan.residuals, None)?;
    let mut vel = Vec::with_capacity(blocks.len());
    for (bp, prog) in plan.blocks.iter().zip(blocks) {
        let roots: Vec<NodeId> =
            [bp.vel.concat(), bp.col_scale.concat(), bp.lever_floor.concat(), bp.row_scale.clone(), bp.jac.concat()]
                .concat();
        vel.push(tape.segment(&roots, None)?);
        tape.provide(prog.tan_regs.iter().flatten().map(|&r| NodeId(r)));
    }
    let mut acc = Vec::with_capacity(blocks.len());
    for (bp, prog) in plan.blocks.iter().zip(blocks) {
        acc.push(tape.segment(&bp.acc.concat(), None)?);
        tape.provide(prog.tan2_regs.iter().flatten().map(|&r| NodeId(r)));
    }
    let out = tape.segment(out_roots, None)?;
    Ok(AtKin { residual, residual_regs: plan.residuals.iter().map(|n| n.0).collect(), vel, acc, out })
}
