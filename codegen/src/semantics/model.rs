//! The checked model of a mechanism: names resolved, vector/scalar types checked, and every
//! equation and output lowered to nodes of one expression graph.

use super::drawing::DrawingModel;
use super::dynamics::{DynamicsModel, Pending};
use super::lower::{Lowerer, Place, ScalarPair};
use super::symbols::{Symbol, Val};
use crate::front::expr::{Expr, SpanRange};
use crate::front::syntax::{Decl, DeclKind, Item, ItemKind, MechanismDef, Options};
use crate::graph::dag::{Graph, Leaf, NodeId};
use proc_macro2::Span;
use std::collections::HashMap;
use syn::ext::IdentExt;
use syn::{Attribute, Ident, Visibility};

/// Most unknowns (and equations) one mechanism may declare. Every block of the decomposition
/// solves at least one unknown, so this also bounds the blocks: the runtime records the sign of
/// every block's determinant in 256 bits (`DetSigns`), exactly, and must not see more blocks.
pub const MAX_UNKNOWNS: usize = 256;
/// Most inputs one mechanism may declare.
pub const MAX_INPUTS: usize = 6;

/// A declared parameter, input or unknown.
pub struct Named {
    /// Its doc comments, copied onto the generated field that holds it.
    pub docs: Vec<Attribute>,
    /// The name as written, with its span for diagnostics.
    pub name: Ident,
    /// Default value (params) or initial guess (unknowns).
    pub value: Option<NodeId>,
    /// Index of the declaring item (`params ...;`, `unknowns ...;`) in the body: names of one
    /// item are neighbours in the source, so a diagnostic can underline several at once.
    pub item: usize,
    /// Whether its default value or guess is written in degrees (`params alpha = deg(30);`,
    /// `unknowns psi = deg(-20);`): it is then an angle, and the kinds of quantity follow from
    /// it ([`crate::plan::kinds`]).
    pub in_degrees: bool,
}

/// One scalar equation: a projection of a `loop` (x or y) or an `eq`.
pub struct Equation {
    /// `loop_name.x`, `loop_name.y` or the `eq` name.
    pub name: String,
    /// The `loop` or `eq` item's name (shared by a loop's two projections).
    pub item: Ident,
    /// Declared with `loop` (a vector equation) rather than `eq`.
    pub is_loop: bool,
    /// The loop or equation item, for errors about it.
    pub range: SpanRange,
    /// Node of the residual `lhs - rhs`: the equation holds where it is zero.
    pub residual: NodeId,
    /// The unknowns its source names, by index: the residual may depend on fewer (their terms
    /// cancel, as in `x - x` or `x * 0`).
    pub written: Vec<usize>,
}

/// A `point` output: a named point of the mechanism, two output columns (`name.x`, `name.y`).
pub struct Point {
    /// Its doc comments, copied onto the generated field.
    pub docs: Vec<Attribute>,
    /// The point's name.
    pub name: Ident,
    /// Node of the x coordinate, an expression of parameters, inputs and unknowns.
    pub x: NodeId,
    /// Node of the y coordinate.
    pub y: NodeId,
}

/// An `output`: a named scalar of the mechanism, one output column.
pub struct Scalar {
    /// Its doc comments, copied onto the generated field.
    pub docs: Vec<Attribute>,
    /// The output's name.
    pub name: Ident,
    /// Node of its value, an expression of parameters, inputs and unknowns.
    pub value: NodeId,
}

/// What the rest of the macro works on: the declaration with its names resolved, and every
/// equation and output a node of one expression graph.
pub struct Model {
    /// The doc comments on the declaration, copied onto the generated struct.
    pub docs: Vec<Attribute>,
    /// The `#[kinloop(...)]` options.
    pub options: Options,
    /// The visibility of the declared struct, given to every generated type.
    pub vis: Visibility,
    /// The mechanism's name: the generated struct, and the prefix of its other types.
    pub name: Ident,
    /// Span of the `{ ... }` body, for errors about what is missing from it.
    pub body: Span,
    /// The design parameters (`params`), in declaration order.
    pub params: Vec<Named>,
    /// The inputs (`input`, `inputs`): the driven coordinates, one per degree of freedom.
    pub inputs: Vec<Named>,
    /// The unknowns, solved from the equations for given parameters and inputs.
    pub unknowns: Vec<Named>,
    /// The scalar equations, two per loop, in declaration order.
    pub equations: Vec<Equation>,
    /// The `point` outputs.
    pub points: Vec<Point>,
    /// The `output` scalars.
    pub scalars: Vec<Scalar>,
    /// The hash-consed expression graph every node above lives in.
    pub graph: Graph,
    /// Whether each parameter is used (an unused one is a warning, not an error).
    pub used_params: Vec<bool>,
    /// Whether each input is used (an unused input is an error of the structure analysis).
    pub used_inputs: Vec<bool>,
    /// Whether each unknown is named in a `loop` or `eq`: one that is, and is in none once the
    /// terms are simplified, cancels there (`x - x`), which its error says.
    pub written_in_equations: Vec<bool>,
    /// Bodies, loads and gravity (`body`, `force`, `torque`, `gravity`), if declared.
    pub dynamics: DynamicsModel,
    /// The node of each `let`, with the let's name (`v_x`, `v_y` for a vector `let v`), in
    /// declaration order: the generated code names the temporary after it.
    pub lets: Vec<(NodeId, String)>,
    /// The loops and points vector by vector, for the default drawing.
    pub drawing: DrawingModel,
}

impl Model {
    /// Output columns in order: each point's x and y, then each scalar output.
    pub fn output_nodes(&self) -> Vec<NodeId> {
        let mut v = Vec::new();
        for p in &self.points {
            v.push(p.x);
            v.push(p.y);
        }
        v.extend(self.scalars.iter().map(|s| s.value));
        v
    }

    /// Names of the output columns, in the order of [`Model::output_nodes`]: `p.x`, `p.y` for
    /// a point `p`, the name for a scalar.
    pub fn output_names(&self) -> Vec<String> {
        let mut v = Vec::new();
        for p in &self.points {
            // Without `r#`, as the inputs' and unknowns' names: `r#fn` is the column `fn`.
            let name = p.name.unraw();
            v.push(format!("{name}.x"));
            v.push(format!("{name}.y"));
        }
        v.extend(self.scalars.iter().map(|s| s.name.unraw().to_string()));
        v
    }
}

/// Most distinct scalar operations the declaration itself may lower to (before
/// differentiation). Expansion time and generated code grow linearly with it (about 0.4 ms and
/// 250 bytes of code per operation in an unoptimised build, where proc macros usually run):
/// the limit keeps expansion near two seconds and the code near a megabyte, and is sixty times
/// what a class IV mechanism with its output points needs (81). Beyond it the declaration is
/// rejected, at the item that crosses it.
pub const MAX_MODEL_NODES: usize = 5_000;

/// The declared names of the body (pass 1).
struct Globals<'a> {
    params: Vec<&'a Decl>,
    inputs: Vec<&'a Decl>,
    unknowns: Vec<&'a Decl>,
    /// Declaration item of each declared name, keyed by the `Decl`'s address.
    item_of: HashMap<*const Decl, usize>,
    /// Some `input` was written, even if every one was refused (a duplicate name already
    /// reported): then "declares no input" would be a second, false error.
    input_written: bool,
}

/// What lowering the items in order produces (pass 2).
#[derive(Default)]
struct Lowered {
    unknown_guess: Vec<Option<NodeId>>,
    equations: Vec<Equation>,
    points: Vec<Point>,
    scalars: Vec<Scalar>,
    /// Names of the `loop` and `eq` items seen so far, where first given.
    item_names: HashMap<String, Span>,
    dynamics: Pending,
    lets: Vec<(NodeId, String)>,
}

/// Builds the model; all semantic errors found are returned together.
pub(crate) fn build(def: MechanismDef) -> Result<Model, syn::Error> {
    let MechanismDef { docs, options, vis, name, items, body } = def;
    let mut lw = Lowerer::new();
    let mut globals = declare_globals(&mut lw, &items);
    check_counts(&mut lw, &mut globals, &name);
    lw.used_params = vec![false; globals.params.len()];
    lw.used_inputs = vec![false; globals.inputs.len()];
    lw.written_in_equations = vec![false; globals.unknowns.len()];
    for item in &items {
        match &item.kind {
            ItemKind::Let { name, value } => lw.declare_later(name, "let", value),
            ItemKind::Point { name, value } => lw.declare_later(name, "point", value),
            ItemKind::Output { name, value } => lw.declare_later(name, "output", value),
            ItemKind::Loop { name, .. } => lw.declare_label(name, "loop"),
            ItemKind::Eq { name, .. } => lw.declare_label(name, "eq"),
            ItemKind::Body(body) => lw.declare_label(&body.name, "body"),
            ItemKind::Force { name, .. } => lw.declare_label(name, "force"),
            ItemKind::Torque { name, .. } => lw.declare_label(name, "torque"),
            _ => {}
        }
    }
    let params = globals
        .params
        .iter()
        .map(|d| {
            let value = d.value.as_ref().and_then(|e| lw.constant(e, "a parameter's default value"));
            named(d, value, &globals.item_of)
        })
        .collect();
    let inputs = globals.inputs.iter().map(|d| named(d, None, &globals.item_of)).collect();
    let mut out = Lowered { unknown_guess: vec![None; globals.unknowns.len()], ..Lowered::default() };
    for item in &items {
        lower_item(&mut lw, &globals, item, &mut out);
        if lw.graph.len() > MAX_MODEL_NODES {
            lw.errors.push(item.range().error(format!(
                "the declaration is too large: up to here it takes more than {MAX_MODEL_NODES} distinct \
                 operations, the most kinloop accepts; split the mechanism into smaller ones"
            )));
            break;
        }
    }
    if lw.graph.overflowed() {
        lw.errors.push(syn::Error::new(name.span(), "the mechanism's expressions are too large for kinloop"));
    }
    let residuals: Vec<NodeId> = out.equations.iter().map(|e| e.residual).collect();
    let columns: Vec<NodeId> =
        out.points.iter().flat_map(|p| [p.x, p.y]).chain(out.scalars.iter().map(|s| s.value)).collect();
    let degrees = in_degrees(&globals);
    let mut angles = super::polar::Angles::new(&residuals, &columns, degrees);
    // The polar terms first, so that the angle of one found swapped is taken for the length it
    // is everywhere else; then the coordinates, so that the dynamics does not report one refused
    // there again. Their errors after the dynamics', in the order of the checks.
    super::polar::note_places(&lw, &mut angles);
    let terms = super::polar::terms(&lw, &mut angles);
    let refused = super::polar::coordinates(&mut lw, &mut angles);
    let dynamics = std::mem::take(&mut out.dynamics).resolve(&mut lw, &columns, &mut angles);
    terms.into_iter().chain(refused).for_each(|e| lw.errors.push(e));
    super::polar::sums(&mut lw, &mut angles);
    // The drawing lowers the terms again: only a declaration without errors lowers cleanly.
    let drawing = if lw.errors.is_empty() { super::drawing::model(&mut lw, &items) } else { DrawingModel::default() };
    let unknowns =
        globals.unknowns.iter().zip(out.unknown_guess).map(|(d, value)| named(d, value, &globals.item_of)).collect();
    let Lowerer { graph, errors, used_params, used_inputs, written_in_equations, .. } = lw;
    let (equations, points, scalars, lets) = (out.equations, out.points, out.scalars, out.lets);
    errors.finish(Model {
        docs,
        options,
        vis,
        name,
        body,
        params,
        inputs,
        unknowns,
        equations,
        points,
        scalars,
        graph,
        used_params,
        used_inputs,
        written_in_equations,
        dynamics,
        lets,
        drawing,
    })
}

/// Pass 1: the global declarations (params, inputs, unknowns), duplicates reported.
fn declare_globals<'a>(lw: &mut Lowerer, items: &'a [Item]) -> Globals<'a> {
    let mut g = Globals {
        params: Vec::new(),
        inputs: Vec::new(),
        unknowns: Vec::new(),
        item_of: HashMap::new(),
        input_written: false,
    };
    for (item_index, item) in items.iter().enumerate() {
        let ItemKind::Decls(kind, decls) = &item.kind else { continue };
        g.input_written |= matches!(kind, DeclKind::Inputs) && !decls.is_empty();
        for d in decls {
            let list = match kind {
                DeclKind::Params => &mut g.params,
                DeclKind::Inputs => &mut g.inputs,
                DeclKind::Unknowns => &mut g.unknowns,
            };
            let idx = list.len() as u16;
            let sym = match kind {
                DeclKind::Params => Symbol::Param(idx),
                DeclKind::Inputs => Symbol::Input(idx),
                DeclKind::Unknowns => Symbol::Unknown(idx),
            };
            if lw.declare(&d.name, sym) {
                g.item_of.insert(d as *const Decl, item_index);
                list.push(d);
            }
        }
    }
    g
}

/// The limits on inputs and unknowns, and the one input every mechanism needs.
fn check_counts(lw: &mut Lowerer, g: &mut Globals, name: &Ident) {
    if g.inputs.len() > MAX_INPUTS {
        lw.errors.push(syn::Error::new(
            g.inputs[MAX_INPUTS].name.span(),
            format!(
                "kinloop supports at most {MAX_INPUTS} inputs per mechanism: declare the others as `params` (a parameter can \
                 be set before each solve) or split the mechanism"
            ),
        ));
        g.inputs.truncate(MAX_INPUTS);
    }
    if g.unknowns.len() > MAX_UNKNOWNS {
        lw.errors.push(syn::Error::new(
            g.unknowns[MAX_UNKNOWNS].name.span(),
            format!(
                "kinloop supports at most {MAX_UNKNOWNS} unknowns per mechanism (so at most {MAX_UNKNOWNS} blocks, \
                 each tracked for a change of assembly mode); split the mechanism into smaller ones"
            ),
        ));
        g.unknowns.truncate(MAX_UNKNOWNS);
    }
    if !g.input_written {
        lw.errors.push(syn::Error::new(
            name.span(),
            format!(
                "mechanism `{name}` declares no input; add the generalized coordinate, e.g. `input phi1;` \
                 (or `input t;` for a time-driven mechanism)"
            ),
        ));
    }
}

/// The parameters and unknowns whose values are written in degrees: angles.
fn in_degrees(g: &Globals) -> Vec<Leaf> {
    let written = |list: &[&Decl]| -> Vec<u16> {
        let degrees = |d: &&Decl| d.value.as_ref().is_some_and(Expr::written_in_degrees);
        list.iter().enumerate().filter(|(_, d)| degrees(d)).map(|(i, _)| i as u16).collect()
    };
    let params = written(&g.params).into_iter().map(Leaf::Param);
    params.chain(written(&g.unknowns).into_iter().map(Leaf::Unknown)).collect()
}

fn named(d: &Decl, value: Option<NodeId>, item_of: &HashMap<*const Decl, usize>) -> Named {
    let item = item_of.get(&(d as *const Decl)).copied().unwrap_or(0);
    let in_degrees = d.value.as_ref().is_some_and(Expr::written_in_degrees);
    Named { docs: d.docs.clone(), name: d.name.clone(), value, item, in_degrees }
}

/// Pass 2: one item at its place in the body.
fn lower_item(lw: &mut Lowerer, g: &Globals, item: &Item, out: &mut Lowered) {
    match &item.kind {
        ItemKind::Decls(DeclKind::Unknowns, decls) => {
            for d in decls.iter().filter(|d| d.value.is_some()) {
                let Some(idx) = g.unknowns.iter().position(|u| std::ptr::eq(*u, d)) else { continue };
                out.unknown_guess[idx] = d.value.as_ref().and_then(|e| lw.guess(e));
            }
        }
        ItemKind::Decls(..) => {}
        ItemKind::Let { name, value } => {
            let place = Place::Let(super::scope::key(name));
            let lowered = lw.noting_sums(|lw| lw.lower_in(place, |lw| lw.lower_definition(name, value)));
            if matches!(lowered, Some(Val::S(_))) && lw.in_degrees(value) {
                lw.degree_lets.insert(super::scope::key(name));
            }
            match lowered {
                Some(v) => {
                    let plain = name.unraw().to_string();
                    match v {
                        Val::S(n) => out.lets.push((n, plain)),
                        Val::V(x, y) => out.lets.extend([(x, format!("{plain}_x")), (y, format!("{plain}_y"))]),
                    }
                    lw.define(name, v)
                }
                None => lw.poison(name),
            }
        }
        ItemKind::Point { name, value } => {
            lw.noting_sums(|lw| lower_point(lw, item, name, value, out));
        }
        ItemKind::Output { name, value } => {
            lw.noting_sums(|lw| lower_output(lw, item, name, value, out));
        }
        ItemKind::Loop { name, lhs, rhs, eq } | ItemKind::Eq { name, lhs, rhs, eq } => {
            lw.in_equation = true;
            lw.written_here.clear();
            let place = matches!(item.kind, ItemKind::Loop { .. }).then_some(Place::Loop);
            lw.lengths = place;
            lower_equation_item(lw, item, name, (lhs, rhs, *eq), out);
            lw.in_equation = false;
            lw.lengths = None;
        }
        ItemKind::Body(b) => out.dynamics.body(lw, b),
        ItemKind::Force { name, at, value } => out.dynamics.force(lw, name, at, value),
        ItemKind::Torque { name, on, value } => out.dynamics.torque(lw, name, on, value),
        ItemKind::Gravity { value } => out.dynamics.gravity(lw, value, item.keyword),
    }
}

fn lower_point(lw: &mut Lowerer, item: &Item, name: &Ident, value: &Expr, out: &mut Lowered) {
    match lw.lower_in(Place::Point, |lw| lw.lower_definition(name, value)) {
        Some(Val::V(x, y)) => {
            lw.define(name, Val::V(x, y));
            out.points.push(Point { docs: item.docs.clone(), name: name.clone(), x, y });
        }
        Some(Val::S(_)) => {
            lw.poison(name);
            lw.errors.push(value.range().error(format!(
                "`point {name}` needs a vector, but this is a scalar; for a scalar output write `output {name} = ...;`"
            )));
        }
        None => lw.poison(name),
    }
}

fn lower_output(lw: &mut Lowerer, item: &Item, name: &Ident, value: &Expr, out: &mut Lowered) {
    match lw.lower_definition(name, value) {
        Some(Val::S(v)) => {
            lw.define(name, Val::S(v));
            out.scalars.push(Scalar { docs: item.docs.clone(), name: name.clone(), value: v });
        }
        Some(Val::V(..)) => {
            lw.poison(name);
            lw.errors.push(value.range().error(format!(
                "`output {name}` needs a scalar, but this is a vector; for a vector output write `point {name} = ...;`"
            )));
        }
        None => lw.poison(name),
    }
}

/// A `loop` (two scalar equations) or an `eq` (one).
fn lower_equation_item(lw: &mut Lowerer, item: &Item, name: &Ident, eq: (&Expr, &Expr, Span), out: &mut Lowered) {
    let (lhs, rhs, eq_span) = eq;
    let is_loop = matches!(item.kind, ItemKind::Loop { .. });
    let key = super::scope::key(name);
    if let Some(prev) = out.item_names.insert(key.clone(), name.span()) {
        let mut e = syn::Error::new(
            name.span(),
            format!("the name `{key}` is given to two loops or equations; rename one of them"),
        );
        e.combine(syn::Error::new(prev, format!("`{key}` is first used as a name here")));
        lw.errors.push(e);
        return;
    }
    let range = item.range();
    let (Some(l), Some(r)) = lw.lower_equation(lhs, rhs) else { return };
    let written: Vec<usize> = lw.written_here.iter().copied().collect();
    let mut push = |eq_name: String, residual: NodeId| {
        let written = written.clone();
        out.equations.push(Equation { name: eq_name, item: name.clone(), is_loop, range, residual, written })
    };
    match (is_loop, l, r) {
        (true, Val::V(lx, ly), Val::V(rx, ry)) => {
            let fx = lw.graph.sides_difference(lx, rx);
            let fy = lw.graph.sides_difference(ly, ry);
            push(format!("{key}.x"), fx);
            push(format!("{key}.y"), fy);
        }
        (false, Val::S(a), Val::S(b)) => {
            let pair = ScalarPair::of(&lw.graph, lhs.range().to(rhs.range()), "equates", (lhs, rhs), l, r);
            lw.scalar_pairs.extend(pair);
            let f = lw.graph.sides_difference(a, b);
            push(key, f);
        }
        _ => lw.errors.push(equation_type_error(is_loop, name, (range, eq_span), l, r)),
    }
}

/// Both sides of `==` lowered, but with types that fit neither a `loop` nor an `eq`.
fn equation_type_error(is_loop: bool, name: &Ident, (range, eq): (SpanRange, Span), l: Val, r: Val) -> syn::Error {
    match (is_loop, l, r) {
        (true, Val::S(_), Val::S(_)) => range.error(format!(
            "`loop {name}` equates two scalars; a loop is a vector equation `vector == vector` \
             (write `eq {name}: ... == ...;` for a scalar equation)"
        )),
        (false, Val::V(..), Val::V(..)) => range.error(format!(
            "`eq {name}` equates two vectors; an `eq` is one scalar equation \
             (write `loop {name}: ... == ...;` for a vector loop: two scalar equations)"
        )),
        _ => {
            let help = if is_loop {
                "a `loop` equates two vectors, e.g. `r @ phi == (x, 0) + l @ psi`"
            } else {
                "an `eq` equates two scalars; take a component with `.x`/`.y` or a length with `norm(..)`"
            };
            syn::Error::new(
                eq,
                format!(
                    "the left side is a {} but the right side is a {}; both sides of `==` \
                     must have the same type\nhelp: {help}",
                    l.kind_name(),
                    r.kind_name()
                ),
            )
        }
    }
}
