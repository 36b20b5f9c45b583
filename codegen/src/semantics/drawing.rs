//! The vectors of each loop and named point, one by one, for the default drawing: a loop's
//! sides split at their top-level `+` and `-` into terms (through parentheses, negations and
//! the `let`s and `point`s they name), each term lowered to its two coordinates.

use super::lower::Lowerer;
use super::scope::key;
use super::symbols::Val;
use crate::front::expr::{BinOp, Expr};
use crate::front::syntax::{Item, ItemKind};
use crate::graph::dag::{Graph, NodeId};
use std::collections::HashMap;

/// One vector of a chain: `sign * (x, y)`, as written (`text`).
pub struct Term {
    /// `+1` or `-1`: the term is added or subtracted.
    pub sign: f64,
    /// Node of the x coordinate (without the sign).
    pub x: NodeId,
    /// Node of the y coordinate.
    pub y: NodeId,
    /// The term as written, for the drawing's description and notes.
    pub text: String,
}

/// A `loop`: the terms of its left and right side, in order.
pub struct Chain {
    /// The loop's name.
    pub name: String,
    /// Terms of the left side.
    pub left: Vec<Term>,
    /// Terms of the right side.
    pub right: Vec<Term>,
}

/// What the default drawing is made from.
#[derive(Default)]
pub struct DrawingModel {
    /// The graph the terms live in: a copy of the model's (lowering the terms again may add
    /// nodes, which the kernels must not see: their temporaries are named by node).
    pub graph: Graph,
    /// The loops.
    pub loops: Vec<Chain>,
    /// The named points with their terms.
    pub points: Vec<(String, Vec<Term>)>,
    /// The scalar equations (`eq`), which the drawing cannot show.
    pub equations: Vec<String>,
    /// Loops and points with too many vectors to describe (see [`MAX_TERMS`]).
    pub skipped: Vec<String>,
}

/// Most vectors of one side of a loop or one point, and of all loops together, the drawing
/// describes: joints are found by comparing partial sums, which takes the square of a side's
/// length. A mechanism has a handful per loop; a longer one is left out with a note.
pub const MAX_TERMS: usize = 256;
/// Most vectors of all loops together (see [`MAX_TERMS`]).
pub const MAX_ALL_TERMS: usize = 4096;

/// How many `let`s and `point`s a term may expand through, and how deep a side may nest: past
/// them a part is kept as one term (the drawing is then coarser, never wrong).
const MAX_EXPANSION: usize = 16;
const MAX_NESTING: usize = 256;

/// The terms of every loop and named point of `items`, lowered in a copy of `lw`'s graph.
/// Called once the declaration lowered without error, so every term lowers again.
pub(super) fn model(lw: &mut Lowerer, items: &[Item]) -> DrawingModel {
    let saved = lw.graph.clone();
    let errors = std::mem::take(&mut lw.errors);
    let mut defs: HashMap<String, &Expr> = HashMap::new();
    let (mut loops, mut points, mut equations, mut skipped) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut all = 0;
    for item in items {
        match &item.kind {
            ItemKind::Let { name, value } => {
                defs.insert(key(name), value);
            }
            ItemKind::Point { name, value } => {
                let terms = terms_of(lw, value, &defs);
                if terms.len() > MAX_TERMS {
                    skipped.push(format!("point `{name}`"));
                } else {
                    points.push((key(name), terms));
                }
                defs.insert(key(name), value);
            }
            ItemKind::Loop { name, lhs, rhs, .. } => {
                let (left, right) = (terms_of(lw, lhs, &defs), terms_of(lw, rhs, &defs));
                all += left.len() + right.len();
                if left.len().max(right.len()) > MAX_TERMS || all > MAX_ALL_TERMS {
                    skipped.push(format!("loop `{name}`"));
                } else {
                    loops.push(Chain { name: key(name), left, right });
                }
            }
            ItemKind::Eq { name, .. } => equations.push(key(name)),
            _ => {}
        }
    }
    let graph = std::mem::replace(&mut lw.graph, saved);
    lw.errors = errors;
    DrawingModel { graph, loops, points, equations, skipped }
}

fn terms_of(lw: &mut Lowerer, e: &Expr, defs: &HashMap<String, &Expr>) -> Vec<Term> {
    let mut out = Vec::new();
    split(lw, e, 1.0, defs, (0, 0), &mut out);
    out
}

/// Appends the terms of `e` (times `sign`) to `out`; `(expanded, depth)` bound the recursion.
fn split(
    lw: &mut Lowerer,
    e: &Expr,
    sign: f64,
    defs: &HashMap<String, &Expr>,
    at: (usize, usize),
    out: &mut Vec<Term>,
) {
    let (expanded, depth) = at;
    if depth < MAX_NESTING {
        match e {
            Expr::Paren { inner, .. } => return split(lw, inner, sign, defs, (expanded, depth + 1), out),
            Expr::Neg { expr, .. } => return split(lw, expr, -sign, defs, (expanded, depth + 1), out),
            Expr::Binary { op: op @ (BinOp::Add | BinOp::Sub), lhs, rhs, .. } => {
                split(lw, lhs, sign, defs, (expanded, depth + 1), out);
                let s = if *op == BinOp::Add { sign } else { -sign };
                return split(lw, rhs, s, defs, (expanded, depth + 1), out);
            }
            Expr::Num { value, .. } if *value == 0.0 => return,
            Expr::Var(id) if expanded < MAX_EXPANSION => {
                if let Some(def) = defs.get(&key(id)) {
                    return split(lw, def, sign, defs, (expanded + 1, depth + 1), out);
                }
            }
            _ => {}
        }
    }
    if let Some(Val::V(x, y)) = lw.lower(e) {
        out.push(Term { sign, x, y, text: e.show() });
    }
}
