//! The machine's dynamics in the model: bodies, forces, torques and gravity, their expressions
//! lowered into the one graph, their points and angles resolved against the kinematic state.
//!
//! Items are lowered in body order (`Pending`); their points are resolved once every output
//! is known (`Pending::resolve`): a point coordinate is an unknown (a slider's
//! coordinate), a constant of the parameters, or a column of a declared `point` or `output`.
//! Anything else would need its own analogs, so the message asks to declare it as a `point`.

use super::lower::{Lowerer, Place};
use super::polar::Angles;
use super::scope::{key, leaf_name};
use super::symbols::{Symbol, Val};
use crate::front::expr::{Expr, SpanRange};
use crate::front::suggest::similar;
use crate::front::syntax::BodyDef;
use crate::graph::dag::{Graph, Leaf, NodeId, Op};
use proc_macro2::Span;
use std::collections::HashMap;
use syn::Ident;

/// A coordinate of a point, read from the kinematic state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CoordModel {
    /// Output column.
    Output(usize),
    /// Unknown.
    Unknown(usize),
    /// A constant: an expression of the parameters.
    Fixed(NodeId),
}

/// The angle a body turns with or a torque acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AngleModel {
    /// The unknown with this index (an angle of the loops).
    Unknown(usize),
    /// The input with this index.
    Input(usize),
    /// No angle: a body that only slides.
    None,
}

/// A rigid body: its mass and inertia, where its centre of mass is, what it turns with.
pub struct BodyModel {
    /// The body's name (for messages at run time).
    pub name: String,
    /// Expressions of the parameters.
    pub mass: NodeId,
    /// Moment of inertia about the centre of mass (the constant zero when not declared).
    pub inertia: NodeId,
    /// The centre of mass's coordinates.
    pub com: [CoordModel; 2],
    /// The angle the body turns with.
    pub turns: AngleModel,
}

/// A force at a point.
pub struct ForceModel {
    /// The force's name.
    pub name: String,
    /// The point it acts at.
    pub at: [CoordModel; 2],
    /// Expressions of parameters, inputs and unknowns.
    pub value: [NodeId; 2],
}

/// A torque on an input or an angle unknown.
pub struct TorqueModel {
    /// The torque's name.
    pub name: String,
    /// The angle it acts on.
    pub on: AngleModel,
    /// The torque, an expression of parameters, inputs and unknowns.
    pub value: NodeId,
}

/// The dynamics declared with a mechanism (empty when none is).
#[derive(Default)]
pub struct DynamicsModel {
    /// The rigid bodies.
    pub bodies: Vec<BodyModel>,
    /// The forces.
    pub forces: Vec<ForceModel>,
    /// The torques.
    pub torques: Vec<TorqueModel>,
    /// Expressions of the parameters.
    pub gravity: Option<[NodeId; 2]>,
}

impl DynamicsModel {
    /// Whether anything of the dynamics is declared (then `mass_model` is generated).
    pub fn is_declared(&self) -> bool {
        !(self.bodies.is_empty() && self.forces.is_empty() && self.torques.is_empty() && self.gravity.is_none())
    }
}

/// A point lowered, waiting for the outputs to be known.
struct PendingPoint {
    x: NodeId,
    y: NodeId,
    /// Its number among the positions of the dynamics (`Place::Dynamics`).
    id: usize,
    range: SpanRange,
    /// The source, for the message that asks to declare it as a point.
    shown: String,
}

struct PendingBody {
    name: Ident,
    mass: NodeId,
    inertia: NodeId,
    com: PendingPoint,
    turns: AngleModel,
}

/// Dynamics items lowered in body order.
#[derive(Default)]
pub(super) struct Pending {
    bodies: Vec<PendingBody>,
    forces: Vec<(Ident, PendingPoint, [NodeId; 2])>,
    torques: Vec<TorqueModel>,
    gravity: Option<[NodeId; 2]>,
    /// Angles named by `turns` and `on`, checked against the equations once all are lowered.
    angles: Vec<(Ident, AngleModel)>,
    /// The bodies' names and the loads' (forces and torques) names, each where first declared:
    /// the mass model reports a body or a load by its name, so each names one.
    body_names: HashMap<String, Span>,
    load_names: HashMap<String, Span>,
}

/// Reports `name` if `names` has it already (`what` is the kind of item, plural, for the
/// message); records it otherwise. Returns whether it is new.
fn unique(lw: &mut Lowerer, names: &mut HashMap<String, Span>, name: &Ident, what: &str) -> bool {
    let key = super::scope::key(name);
    match names.get(&key) {
        Some(first) => {
            let mut e = syn::Error::new(
                name.span(),
                format!("the name `{key}` is given to two {what}; names must be unique, rename one of them"),
            );
            e.combine(syn::Error::new(*first, format!("`{key}` is first used as a name here")));
            lw.errors.push(e);
            false
        }
        None => {
            names.insert(key, name.span());
            true
        }
    }
}

impl Pending {
    pub(super) fn body(&mut self, lw: &mut Lowerer, b: &BodyDef) {
        if !unique(lw, &mut self.body_names, &b.name, "bodies") {
            return;
        }
        let mass = parameter_value(lw, &b.mass, "the mass");
        let inertia = match &b.inertia {
            // A moment of inertia counts only through the angle the body turns with: without
            // `turns` it would be dropped without a word (a forgotten `turns` gave dynamics
            // without the body's rotation).
            Some(e) if b.turns.is_none() => {
                lw.errors.push(e.range().error(format!(
                    "body `{}` has a moment of inertia but no `turns`: add `turns ANGLE` (the input or angle \
                     unknown it rotates with), or remove `inertia` for a body that only slides",
                    b.name
                )));
                None
            }
            Some(e) => parameter_value(lw, e, "the moment of inertia"),
            None => Some(lw.graph.zero()),
        };
        let com = point(lw, &b.com, "a centre of mass");
        let turns = match &b.turns {
            Some(a) => angle(lw, a, "turns"),
            None => Some(AngleModel::None),
        };
        if let Some(a) = &b.turns {
            self.angles.extend(turns.map(|t| (a.clone(), t)));
        }
        if let (Some(mass), Some(inertia), Some(com), Some(turns)) = (mass, inertia, com, turns) {
            self.bodies.push(PendingBody { name: b.name.clone(), mass, inertia, com, turns });
        }
    }

    pub(super) fn force(&mut self, lw: &mut Lowerer, name: &Ident, at: &Expr, value: &Expr) {
        if !unique(lw, &mut self.load_names, name, "loads (forces and torques)") {
            return;
        }
        let at = point(lw, at, "the point a force acts at");
        let value =
            match load_law(lw, value) {
                Some(Val::V(x, y)) => Some([x, y]),
                Some(Val::S(_)) => {
                    lw.errors.push(value.range().error(format!(
                        "force `{name}` needs a vector `(fx, fy)` or `f @ angle`, but this is a scalar"
                    )));
                    None
                }
                None => None,
            };
        if let (Some(at), Some(value)) = (at, value) {
            self.forces.push((name.clone(), at, value));
        }
    }

    pub(super) fn torque(&mut self, lw: &mut Lowerer, name: &Ident, on: &Ident, value: &Expr) {
        if !unique(lw, &mut self.load_names, name, "loads (forces and torques)") {
            return;
        }
        let angle = angle(lw, on, "on");
        self.angles.extend(angle.map(|a| (on.clone(), a)));
        let value = match load_law(lw, value) {
            Some(Val::S(v)) => Some(v),
            Some(Val::V(..)) => {
                lw.errors.push(value.range().error(format!("torque `{name}` needs a scalar, but this is a vector")));
                None
            }
            None => None,
        };
        if let (Some(on), Some(value)) = (angle, value) {
            self.torques.push(TorqueModel { name: key(name), on, value });
        }
    }

    pub(super) fn gravity(&mut self, lw: &mut Lowerer, value: &Expr, keyword: Span) {
        if self.gravity.is_some() {
            lw.errors.push(syn::Error::new(keyword, "`gravity` is given twice; keep one"));
            return;
        }
        match lw.lower(value) {
            Some(Val::V(x, y)) if depends_on_state(&lw.graph, &[x, y]) => lw.errors.push(
                value
                    .range()
                    .error("gravity must be an expression of parameters (it cannot change with inputs or unknowns)"),
            ),
            Some(Val::V(x, y)) => self.gravity = Some([x, y]),
            Some(Val::S(_)) => lw.errors.push(
                value
                    .range()
                    .error("gravity is a vector, e.g. `gravity (0, -g);` with y pointing up, but this is a scalar"),
            ),
            None => {}
        }
    }

    /// Resolves the points against the output columns (`outputs`) and checks the angles that
    /// `turns` and `on` name. Both ask `angles`, the unit check's verdicts: an angle of `turns`
    /// or `on` is one by [`Angles::is_angle`], and a coordinate of a point is refused as an
    /// angle where [`Angles::why`] finds one (in degrees too, and not the angle of a term found
    /// swapped).
    pub(super) fn resolve(self, lw: &mut Lowerer, outputs: &[NodeId], angles: &mut Angles) -> DynamicsModel {
        let columns: HashMap<NodeId, usize> = outputs.iter().enumerate().rev().map(|(c, &n)| (n, c)).collect();
        for (id, a) in &self.angles {
            let leaf = match a {
                AngleModel::Unknown(u) => Leaf::Unknown(*u as u16),
                AngleModel::Input(i) => Leaf::Input(*i as u16),
                AngleModel::None => continue,
            };
            // The one test of an angle, that of the unit check: a body that turns with an
            // unknown an `eq` sets to `2 * psi` (a gear's angle) turns by so many radians, as
            // with `psi`; a guess in degrees declares an angle (`unknowns w = deg(30);`), which
            // the check of a centre of mass refuses there as one. The angle of a term found
            // swapped is one here (`l` in `psi @ l`: the term is the one mistake told); that of
            // a term whose length is in degrees (`s` in `th @ s`) is none, as for the unit check,
            // which tells that term and says `s` is as likely its length.
            if !angles.is_angle(&lw.graph, leaf) {
                let error = not_an_angle(lw, id, leaf, angles.angle_but_for_its_place(&lw.graph, leaf));
                lw.errors.push(error);
            }
        }
        // Why a coordinate that is an unknown is an angle, `Some(true)` if its value is in
        // degrees.
        let mut angle_of = |lw: &Lowerer, leaf: Leaf| {
            let name = leaf_name(lw, leaf).unwrap_or_default();
            angles.why(&lw.graph, leaf, &name).map(|_| angles.in_degrees(leaf))
        };
        let mut coords = |lw: &mut Lowerer, p: &PendingPoint, what: &str| -> Option<[CoordModel; 2]> {
            let nodes = [p.x, p.y];
            // Refused by [`super::polar`] where it is written: in a `let` or point this position
            // uses, or as an expression here (`2 * psi`). An unknown written bare here is this
            // check's to judge, even if the same one is refused at another position.
            let refused = |lw: &Lowerer, n: NodeId| {
                lw.refused_positions.contains(&n) && !lw.left_to_dynamics.contains(&(p.id, n))
            };
            // A coordinate that is an angle unknown puts the point at so many radians: a body's
            // mass there counted in mass rad^2 beside the others' mass length^2, and results
            // that changed with the unit of length, without a word. Each such coordinate is
            // told, once per name: an angle of the mechanism, or one whose guess is in degrees.
            let mut found: Vec<(Leaf, bool)> = Vec::new();
            for n in nodes {
                let Op::Leaf(leaf @ Leaf::Unknown(_)) = lw.graph.op(n) else { continue };
                if refused(lw, n) || found.iter().any(|f| f.0 == leaf) {
                    continue;
                }
                found.extend(angle_of(lw, leaf).map(|degrees| (leaf, degrees)));
            }
            for &(leaf, degrees) in &found {
                let name = leaf_name(lw, leaf).unwrap_or_default();
                let why = if degrees { " (its value is written in degrees)" } else { "" };
                lw.errors.push(p.range.error(format!(
                    "{what} is a point of lengths, but `{name}` is an angle{why}: write a length for that \
                     coordinate (a slider's unknown, a constant, or a declared point)"
                )));
            }
            // A coordinate told (here, or refused where it is written: an angle input, `2 * psi`)
            // is the one mistake of this point: declaring the point would not mend it.
            let told =
                |lw: &Lowerer, n: NodeId| refused(lw, n) || found.iter().any(|&(l, _)| lw.graph.op(n) == Op::Leaf(l));
            if nodes.iter().any(|&n| told(lw, n)) {
                return None;
            }
            // The other coordinates are read from the state, or not read.
            let unread: Vec<NodeId> = nodes.into_iter().filter(|&n| coord(&lw.graph, &columns, n).is_none()).collect();
            if unread.is_empty() {
                return match [coord(&lw.graph, &columns, p.x), coord(&lw.graph, &columns, p.y)] {
                    [Some(x), Some(y)] => Some([x, y]),
                    _ => None,
                };
            }
            // The mass model reads no input (the runtime's `Coord` has no such coordinate): a
            // point that moves with one is declared, and read as the output it then is.
            let input = unread.iter().find_map(|&n| input_name(lw, n));
            let why = input.map(|i| format!(", and `{i}` is an input")).unwrap_or_default();
            lw.errors.push(p.range.error(format!(
                "{what} must be a declared point, or `(x, y)` of unknowns, outputs and constants{why}: \
                 declare it with `point name = {};` and write its name here",
                p.shown
            )));
            None
        };
        let mut model = DynamicsModel { gravity: self.gravity, torques: self.torques, ..Default::default() };
        for b in self.bodies {
            if let Some(com) = coords(lw, &b.com, "a centre of mass") {
                let (name, mass, inertia, turns) = (key(&b.name), b.mass, b.inertia, b.turns);
                model.bodies.push(BodyModel { name, mass, inertia, com, turns });
            }
        }
        for (name, at, value) in self.forces {
            if let Some(at) = coords(lw, &at, "the point a force acts at") {
                model.forces.push(ForceModel { name: key(&name), at, value });
            }
        }
        model
    }
}

/// The law of a force or a torque, lowered with its sums noted for the check that none puts an
/// angle beside a length ([`super::polar`]), as an `output`'s are: `x + psi` changes with the
/// unit of length in a load as much as in a reported value. That is the one unit check a law can
/// have: kinloop knows lengths and angles, not force, mass or time, and a law's parameters (a
/// stiffness, a pressure, an area) carry no declared unit, so whether it is a force or a torque
/// at all cannot be judged.
fn load_law(lw: &mut Lowerer, value: &Expr) -> Option<Val> {
    lw.noting_sums(|lw| lw.lower(value))
}

/// A mass or a moment of inertia: a scalar of the parameters, not a negative constant.
fn parameter_value(lw: &mut Lowerer, e: &Expr, what: &str) -> Option<NodeId> {
    let v = match lw.lower(e)? {
        Val::S(v) => v,
        Val::V(..) => {
            lw.errors.push(e.range().error(format!("{what} of a body is a scalar, but this is a vector")));
            return None;
        }
    };
    if depends_on_state(&lw.graph, &[v]) {
        lw.errors.push(e.range().error(format!(
            "{what} of a body must be an expression of parameters (it cannot change with inputs or unknowns)"
        )));
        return None;
    }
    match lw.graph.as_const(v) {
        Some(c) if c < 0.0 || !c.is_finite() => {
            lw.errors.push(e.range().error(format!(
                "{what} of a body cannot be {c}: it must be finite and not negative; write its magnitude"
            )));
            None
        }
        _ => Some(v),
    }
}

fn point(lw: &mut Lowerer, e: &Expr, what: &'static str) -> Option<PendingPoint> {
    let id = lw.dynamics_positions;
    lw.dynamics_positions += 1;
    match lw.lower_in(Place::Dynamics(what, id), |lw| lw.lower(e))? {
        Val::V(x, y) => Some(PendingPoint { x, y, id, range: e.range(), shown: e.show() }),
        Val::S(_) => {
            lw.errors.push(e.range().error(format!(
                "{what} is a point (a vector), but this is a scalar: write a declared `point` or `(x, y)`"
            )));
            None
        }
    }
}

/// The input or unknown `id` names (`clause` is `turns` or `on`, for the message).
fn angle(lw: &mut Lowerer, id: &Ident, clause: &str) -> Option<AngleModel> {
    let found = lw.scope.symbols.get(&super::scope::key(id)).map(|(s, _)| *s);
    let what = match found {
        Some(Symbol::Unknown(u)) => return Some(AngleModel::Unknown(u as usize)),
        Some(Symbol::Input(i)) => return Some(AngleModel::Input(i as usize)),
        Some(Symbol::Param(_)) => "a parameter",
        Some(Symbol::Let(_) | Symbol::Later(_) | Symbol::Poisoned) => "a named value",
        None => "not declared",
    };
    // A misspelt input or unknown (`turns bet`) is named with the one meant, as in expressions.
    let hint = found.is_none().then(|| {
        let angles: Vec<String> = lw
            .scope
            .symbols
            .iter()
            .filter(|(_, (s, _))| matches!(s, Symbol::Unknown(_) | Symbol::Input(_)))
            .map(|(k, _)| k.clone())
            .collect();
        similar(&key(id), angles.iter()).map(|s| format!(" (did you mean `{s}`?)"))
    });
    let hint = hint.flatten().unwrap_or_default();
    lw.errors.push(syn::Error::new(
        id.span(),
        format!("`{clause} {id}`: `{id}` is {what}{hint}; `{clause}` takes an input or an angle unknown"),
    ));
    None
}

/// Why a name written as a length elsewhere is no angle where it would be one elsewhere.
const BY_PLACE: &str = "; it is written as a length elsewhere (a coordinate of a position or the length of `@`), \
                        where only a whole multiple of it in a sine or an inverse trigonometric function in an `eq` \
                        would make it an angle";

/// The error for `id`, the input or unknown `leaf` that `turns` or `on` names, which is no angle;
/// `by_place` if it is none only because it is written as a length elsewhere.
fn not_an_angle(lw: &Lowerer, id: &Ident, leaf: Leaf, by_place: bool) -> syn::Error {
    // The example of an angle the `eq` sets it to is named apart from it.
    let other = if key(id) == "psi" { "beta" } else { "psi" };
    let place = if by_place { BY_PLACE } else { "" };
    syn::Error::new(
        id.span(),
        format!(
            "`{id}` is not an angle: it is the angle of no `@`, sin, cos or tan of the mechanism (as in `l @ {id}`, \
             `sin(2 * {id} + gamma)`; not scaled, as in `sin({id} / l)`), and no `eq` sets it to an angle (as \
             `{id} == atan2(dy, dx)` does, or `{id} == 2 * {other}` with `{other}` an angle){place}; a body that only \
             slides has no `turns`, a torque acts on an angle{}",
            swapped_hint(lw, leaf)
        ),
    )
}

/// For an input or unknown named as an angle (`turns`, `on`) that is the length of a polar term,
/// `psi @ l`, what most likely happened: the term's length and angle are swapped.
fn swapped_hint(lw: &Lowerer, leaf: Leaf) -> String {
    match lw.named_lengths.iter().find(|t| t.leaf == Some(leaf) && !t.constant_angle) {
        Some(t) => format!(
            "\nhelp: `{0} @ {1}` has `{0}` as the length of `@`, which takes `length @ angle`: if `{0}` is \
             the angle, write `{1} @ {0}`",
            t.length, t.angle
        ),
        None => String::new(),
    }
}

/// The name of the input `n` is, if it is one.
fn input_name(lw: &Lowerer, n: NodeId) -> Option<String> {
    let Op::Leaf(leaf @ Leaf::Input(_)) = lw.graph.op(n) else { return None };
    leaf_name(lw, leaf)
}

fn depends_on_state(g: &Graph, roots: &[NodeId]) -> bool {
    g.leaves_of(roots).iter().any(|l| matches!(l, Leaf::Input(_) | Leaf::Unknown(_)))
}

fn coord(g: &Graph, columns: &HashMap<NodeId, usize>, n: NodeId) -> Option<CoordModel> {
    match g.op(n) {
        Op::Leaf(Leaf::Unknown(u)) => Some(CoordModel::Unknown(u as usize)),
        _ if !depends_on_state(g, &[n]) => Some(CoordModel::Fixed(n)),
        _ => columns.get(&n).map(|&c| CoordModel::Output(c)),
    }
}
