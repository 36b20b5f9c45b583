//! Calls of built-in functions: checked and lowered from the table in [`super::builtins`].

use super::builtins::{self, Builtin, HINTS, Kind, Lowering};
use super::lower::{Lowerer, ScalarPair, integer_exponent};
use super::symbols::Val;
use crate::front::expr::{Expr, SpanRange};
use crate::front::suggest::similar;
use crate::graph::dag::{Func, Graph, NodeId};
use proc_macro2::Span;
use syn::Ident;

impl Lowerer {
    pub(super) fn call(&mut self, func: &Ident, args: &[Expr], close: Span) -> Option<Val> {
        let Some(builtin) = builtins::lookup(&func.to_string()) else {
            let declared = self.scope.symbols.contains_key(&super::scope::key(func));
            if declared && let Some(first) = args.first() {
                // `h (1 - cos(phi))`: a declared name before parentheses is a product.
                let shown = args.iter().map(Expr::show).collect::<Vec<_>>().join(", ");
                self.errors.push(syn::Error::new(
                    func.span(),
                    format!(
                        "`{func}` is a declared name, not a function: write `{func} * ({})` for a product",
                        if args.len() == 1 { first.show() } else { shown }
                    ),
                ));
                return None;
            }
            if func == "pi" {
                self.errors.push(pi_called(func, args));
                return None;
            }
            self.errors.push(unsupported(func));
            return None;
        };
        if args.len() != builtin.arity() {
            self.errors.push(wrong_arity(builtin, args, close));
            return None;
        }
        // The vectors a function takes are no positions (`dot(u, v)` multiplies them, `norm`
        // measures one): the value it gives is judged where it is written. `rot` gives its
        // vector back turned, a position still.
        let positions = if builtin.lowering == Lowering::Rot { self.lengths.clone() } else { None };
        let outer = std::mem::replace(&mut self.lengths, positions);
        let vals: Vec<Option<Val>> = args.iter().map(|a| self.lower(a)).collect();
        self.lengths = outer;
        let vals: Vec<Val> = vals.into_iter().collect::<Option<_>>()?;
        if let Some(e) = swapped_arguments(builtin, func, args, &vals) {
            self.errors.push(e);
            return None;
        }
        let mut ok = true;
        for ((v, a), (_, want)) in vals.iter().zip(args).zip(builtin.args) {
            let got = if matches!(v, Val::V(..)) { Kind::Vector } else { Kind::Scalar };
            if got != *want {
                ok = false;
                self.errors.push(wrong_kind(builtin, a, got));
            }
        }
        if !ok {
            return None;
        }
        if builtin.lowering == Lowering::Clamp {
            let bound = |k: usize| match vals[k] {
                Val::S(n) => self.graph.as_const(n),
                Val::V(..) => None,
            };
            if let (Some(lo), Some(hi)) = (bound(1), bound(2))
                && lo > hi
            {
                self.errors.push(args[1].range().error(format!(
                    "`clamp(x, lo, hi)` needs `lo <= hi`, but `lo` is {lo:?} and `hi` is {hi:?}; \
                     swap the bounds (with `lo > hi` the result would always be `hi`)"
                )));
                return None;
            }
        }
        if builtin.lowering == Lowering::Wrap
            && let Val::S(n) = vals[1]
            && let Some(period) = self.graph.as_const(n)
            && !(period > 0.0 && period.is_finite())
        {
            self.errors.push(args[1].range().error(format!(
                "`wrap(x, period)` needs a positive, finite `period`, but it is {period:?}; \
                 for a turn write `wrap(phi, 2 * pi)`"
            )));
            return None;
        }
        let exponent = args.get(1).and_then(integer_exponent);
        let result = lower_builtin(&mut self.graph, builtin.lowering, &vals, exponent);
        let range = SpanRange { start: func.span(), end: close };
        let show = || format!("{func}({})", args.iter().map(Expr::show).collect::<Vec<_>>().join(", "));
        // `max(x, psi)` is a length or an angle by the input, and `atan2(x, psi)`,
        // `hypot(x, psi)` and `wrap(x, psi)` change with the unit of length, as `x + psi` mixes
        // the two: their arguments are judged as a sum's terms (a constant is of the other's
        // kind).
        let verb = match builtin.lowering {
            Lowering::Min | Lowering::Max | Lowering::Clamp => Some("compares"),
            Lowering::Atan2 | Lowering::Hypot | Lowering::Wrap => Some("combines"),
            _ => None,
        };
        if let Some(verb) = verb.filter(|_| self.in_equation || self.notes_sums) {
            let shown = show();
            for k in 1..args.len() {
                let pair =
                    ScalarPair::compared(&self.graph, (range, &shown, verb), (&args[0], &args[k]), vals[0], vals[k]);
                self.scalar_pairs.extend(pair);
            }
        }
        self.finite(range, &show, &vals, result)
    }
}

/// `pi()` or `pi(x)`: `pi` is the built-in constant, so this is neither an unsupported function
/// (with a suggestion of a function named alike, `min`) nor a product of a declared name.
fn pi_called(func: &Ident, args: &[Expr]) -> syn::Error {
    let write = match args {
        [x] => format!("`pi * ({})` for a product", x.show()),
        _ => "`pi`".to_string(),
    };
    syn::Error::new(func.span(), format!("`pi` is a constant, not a function: write {write}"))
}

fn unsupported(func: &Ident) -> syn::Error {
    let name = func.to_string();
    let all: Vec<String> = builtins::BUILTINS.iter().map(|b| b.name.to_string()).collect();
    let hint = match HINTS.iter().find(|(n, _)| *n == name) {
        Some((_, h)) => format!("; {h}"),
        None => match similar(&name, all.iter()) {
            Some(s) => format!("; did you mean `{s}`?"),
            None => String::new(),
        },
    };
    syn::Error::new(
        func.span(),
        format!("unsupported function `{name}`{hint}\navailable functions: {}", builtins::listing()),
    )
}

fn wrong_arity(b: &Builtin, args: &[Expr], close: Span) -> syn::Error {
    let arity = b.arity();
    let span = args.get(arity).map_or(close, |a| a.range().start);
    // `norm(x, y)`: the two components of the vector it takes, without their parentheses.
    let vector = match (b.args, args) {
        ([(_, Kind::Vector)], [x, y]) => {
            format!("; for the vector of the two write `{}(({}, {}))`", b.name, x.show(), y.show())
        }
        _ => String::new(),
    };
    syn::Error::new(
        span,
        format!(
            "`{}` takes {arity} argument{}: `{}`, but {} {} given{vector}",
            b.name,
            if arity == 1 { "" } else { "s" },
            b.signature(),
            args.len(),
            if args.len() == 1 { "was" } else { "were" }
        ),
    )
}

/// The error for the two arguments of a function that takes a vector and a scalar given the
/// other way round, `rot(phi, v)`: one mistake, where each argument of the wrong kind was one.
fn swapped_arguments(b: &Builtin, func: &Ident, args: &[Expr], vals: &[Val]) -> Option<syn::Error> {
    let kind = |v: &Val| if matches!(v, Val::V(..)) { Kind::Vector } else { Kind::Scalar };
    let ([(_, first), (_, second)], [a, c]) = (b.args, vals) else { return None };
    if first == second || kind(a) != *second || kind(c) != *first {
        return None;
    }
    let range = SpanRange { start: args[0].range().start, end: args[1].range().end };
    Some(range.error(format!(
        "`{}` takes `{}`: the arguments are the other way round, write `{func}({}, {})`",
        b.name,
        b.signature(),
        args[1].show(),
        args[0].show()
    )))
}

fn wrong_kind(b: &Builtin, arg: &Expr, got: Kind) -> syn::Error {
    let name = b.name;
    let hint = match got {
        Kind::Vector => {
            format!("`{name}` takes a scalar here; take a component with `.x`/`.y` or the length with `norm(..)`")
        }
        Kind::Scalar => format!("`{name}` takes a vector here, e.g. `(x, y)` or `r @ angle`"),
    };
    arg.range().error(format!("this argument is a {}: {hint}", got.name()))
}

/// The nodes of a call whose arguments have the kinds the table gives. `exponent` is the
/// second argument when it is written as an integer literal (`pow(x, 3)` becomes `powi`).
fn lower_builtin(g: &mut Graph, how: Lowering, vals: &[Val], exponent: Option<i32>) -> Val {
    let s = |k: usize| match vals[k] {
        Val::S(a) | Val::V(a, _) => a,
    };
    let v = |k: usize| match vals[k] {
        Val::V(x, y) => (x, y),
        Val::S(a) => (a, a),
    };
    Val::S(match how {
        Lowering::Unary(f) => g.func(f, s(0)),
        Lowering::Atan2 => g.atan2(s(0), s(1)),
        Lowering::Pow => match exponent {
            Some(n) => g.powi(s(0), n),
            None => g.powf(s(0), s(1)),
        },
        Lowering::Hypot => length(g, s(0), s(1)),
        Lowering::Norm => length(g, v(0).0, v(0).1),
        Lowering::Angle => g.atan2(v(0).1, v(0).0),
        Lowering::Dot => {
            let ((ax, ay), (bx, by)) = (v(0), v(1));
            let p = g.mul(ax, bx);
            let q = g.mul(ay, by);
            g.add(p, q)
        }
        Lowering::Cross => {
            let ((ax, ay), (bx, by)) = (v(0), v(1));
            let p = g.mul(ax, by);
            let q = g.mul(ay, bx);
            g.sub(p, q)
        }
        Lowering::Rot => return rotate(g, v(0), s(1)),
        Lowering::Degrees => {
            let per_degree = g.constant(std::f64::consts::PI / 180.0);
            g.mul(s(0), per_degree)
        }
        Lowering::Min => g.min(s(0), s(1)),
        Lowering::Max => g.max(s(0), s(1)),
        Lowering::Clamp => {
            let low = g.max(s(0), s(1));
            g.min(low, s(2))
        }
        Lowering::Wrap => {
            let turns = g.div(s(0), s(1));
            let whole = g.func(Func::Floor, turns);
            let back = g.mul(s(1), whole);
            g.sub(s(0), back)
        }
    })
}

/// `sqrt(a^2 + b^2)`.
fn length(g: &mut Graph, a: NodeId, b: NodeId) -> NodeId {
    let a2 = g.powi(a, 2);
    let b2 = g.powi(b, 2);
    let sum = g.add(a2, b2);
    g.func(Func::Sqrt, sum)
}

/// The vector `(x, y)` turned by the angle `t`.
fn rotate(g: &mut Graph, (x, y): (NodeId, NodeId), t: NodeId) -> Val {
    let (c, sn) = (g.func(Func::Cos, t), g.func(Func::Sin, t));
    let xc = g.mul(x, c);
    let ys = g.mul(y, sn);
    let xs = g.mul(x, sn);
    let yc = g.mul(y, c);
    Val::V(g.sub(xc, ys), g.add(xs, yc))
}
