//! The checked model of a mechanism: names resolved, vector/scalar types checked, and every
//! equation and output lowered to nodes of one expression [`Graph`].

use crate::dag::{Func, Graph, Leaf, NodeId};
use crate::expr::{BinOp, Component, Expr, SpanRange};
use crate::syntax::{Decl, DeclKind, Errors, ItemKind, MechanismDef, Options};
use proc_macro2::Span;
use std::collections::HashMap;
use syn::{Attribute, Ident, Visibility};

/// Most unknowns (and equations) one mechanism may declare.
pub const MAX_UNKNOWNS: usize = 256;
/// Most inputs one mechanism may declare.
pub const MAX_INPUTS: usize = 6;

pub struct Named {
    pub docs: Vec<Attribute>,
    pub name: Ident,
    /// Default value (params) or initial guess (unknowns).
    pub value: Option<NodeId>,
    /// Index of the declaring item (`params ...;`, `unknowns ...;`) in the body: names of one
    /// item are neighbours in the source, so a diagnostic can underline several at once.
    pub item: usize,
}

pub struct Equation {
    /// `loop_name.x`, `loop_name.y` or the `eq` name.
    pub name: String,
    /// The `loop` or `eq` item's name (shared by a loop's two projections).
    pub item: Ident,
    /// Declared with `loop` (a vector equation) rather than `eq`.
    pub is_loop: bool,
    /// The loop or equation item, for errors about it.
    pub range: SpanRange,
    pub residual: NodeId,
}

pub struct Point {
    pub docs: Vec<Attribute>,
    pub name: Ident,
    pub x: NodeId,
    pub y: NodeId,
}

pub struct Scalar {
    pub docs: Vec<Attribute>,
    pub name: Ident,
    pub value: NodeId,
}

/// What the rest of the macro works on.
pub struct Model {
    pub docs: Vec<Attribute>,
    pub options: Options,
    pub vis: Visibility,
    pub name: Ident,
    pub body: Span,
    pub params: Vec<Named>,
    pub inputs: Vec<Named>,
    pub unknowns: Vec<Named>,
    pub equations: Vec<Equation>,
    pub points: Vec<Point>,
    pub scalars: Vec<Scalar>,
    pub graph: Graph,
    /// Parameters and inputs that nothing uses (reported as errors by the structure analysis).
    pub used_params: Vec<bool>,
    pub used_inputs: Vec<bool>,
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

    pub fn output_names(&self) -> Vec<String> {
        let mut v = Vec::new();
        for p in &self.points {
            v.push(format!("{}.x", p.name));
            v.push(format!("{}.y", p.name));
        }
        v.extend(self.scalars.iter().map(|s| s.name.to_string()));
        v
    }
}

/// The type of a lowered expression.
#[derive(Clone, Copy)]
enum Val {
    S(NodeId),
    V(NodeId, NodeId),
}

#[derive(Clone, Copy)]
enum Symbol {
    Param(u16),
    Input(u16),
    Unknown(u16),
    Let(Val),
    /// Declared later in the body by the item with this keyword (`let`, `point`, `output`):
    /// using it now is an ordering mistake.
    Later(&'static str),
    /// Its definition had an error (already reported): uses stay silent.
    Poisoned,
}

struct Scope {
    symbols: HashMap<String, (Symbol, Span)>,
}

pub const SCALAR_FUNCTIONS: &[&str] =
    &["sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "ln", "abs", "pow", "hypot"];
pub const VECTOR_FUNCTIONS: &[&str] = &["norm", "dot", "cross", "angle", "rot"];

fn one_arg(name: &str) -> Option<Func> {
    Some(match name {
        "sin" => Func::Sin,
        "cos" => Func::Cos,
        "tan" => Func::Tan,
        "asin" => Func::Asin,
        "acos" => Func::Acos,
        "atan" => Func::Atan,
        "sqrt" => Func::Sqrt,
        "exp" => Func::Exp,
        "ln" => Func::Ln,
        "abs" => Func::Abs,
        _ => return None,
    })
}

/// Suggests a declared name close to a misspelt one (at most 2 edits, a swap of neighbours
/// counting as one). Ties are broken by name so the message is deterministic.
pub fn similar<'a>(name: &str, candidates: impl Iterator<Item = &'a String>) -> Option<&'a String> {
    // The distance is quadratic in the lengths: long names get no suggestion.
    const LONGEST: usize = 64;
    if name.chars().count() > LONGEST {
        return None;
    }
    candidates
        .filter(|c| c.chars().count() <= LONGEST)
        .map(|c| (edit_distance(name, c), c))
        .filter(|(d, c)| *d <= 2 && *d < c.chars().count().max(name.chars().count()))
        .min_by(|a, b| a.0.cmp(&b.0).then_with(|| a.1.cmp(b.1)))
        .map(|(_, c)| c)
}

/// Optimal string alignment distance (Levenshtein plus adjacent transpositions).
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1).min(d[i][j - 1] + 1).min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}

struct Lowerer {
    graph: Graph,
    scope: Scope,
    errors: Errors,
    used_params: Vec<bool>,
    used_inputs: Vec<bool>,
}

/// Builds the model; all semantic errors found are returned together.
pub fn build(def: MechanismDef) -> Result<Model, syn::Error> {
    let MechanismDef { docs, options, vis, name, items, body } = def;
    let mut lw = Lowerer {
        graph: Graph::new(),
        scope: Scope { symbols: HashMap::new() },
        errors: Errors::default(),
        used_params: Vec::new(),
        used_inputs: Vec::new(),
    };

    // Pass 1: global declarations (params, inputs, unknowns) and the names declared later.
    let mut params: Vec<&Decl> = Vec::new();
    let mut inputs: Vec<&Decl> = Vec::new();
    let mut unknowns: Vec<&Decl> = Vec::new();
    // Declaration item of each declared name, keyed by the `Decl`'s address.
    let mut item_of: HashMap<*const Decl, usize> = HashMap::new();
    for (item_index, item) in items.iter().enumerate() {
        if let ItemKind::Decls(kind, decls) = &item.kind {
            for d in decls {
                let list = match kind {
                    DeclKind::Params => &mut params,
                    DeclKind::Inputs => &mut inputs,
                    DeclKind::Unknowns => &mut unknowns,
                };
                let idx = list.len() as u16;
                let sym = match kind {
                    DeclKind::Params => Symbol::Param(idx),
                    DeclKind::Inputs => Symbol::Input(idx),
                    DeclKind::Unknowns => Symbol::Unknown(idx),
                };
                if lw.declare(&d.name, sym) {
                    item_of.insert(d as *const Decl, item_index);
                    list.push(d);
                }
            }
        }
    }
    if inputs.len() > MAX_INPUTS {
        lw.errors.push(syn::Error::new(
            inputs[MAX_INPUTS].name.span(),
            format!("kinloop supports at most {MAX_INPUTS} inputs per mechanism"),
        ));
        inputs.truncate(MAX_INPUTS);
    }
    if unknowns.len() > MAX_UNKNOWNS {
        lw.errors.push(syn::Error::new(
            unknowns[MAX_UNKNOWNS].name.span(),
            format!("kinloop supports at most {MAX_UNKNOWNS} unknowns per mechanism"),
        ));
        unknowns.truncate(MAX_UNKNOWNS);
    }
    if inputs.is_empty() {
        lw.errors.push(syn::Error::new(
            name.span(),
            format!(
                "mechanism `{name}` declares no input; add the generalized coordinate, e.g. `input phi1;` \
                 (or `input t;` for a time-driven mechanism)"
            ),
        ));
    }
    lw.used_params = vec![false; params.len()];
    lw.used_inputs = vec![false; inputs.len()];
    for item in &items {
        let later = match &item.kind {
            ItemKind::Let { name, .. } => Some((name, "let")),
            ItemKind::Point { name, .. } => Some((name, "point")),
            ItemKind::Output { name, .. } => Some((name, "output")),
            _ => None,
        };
        if let Some((n, what)) = later.filter(|(n, _)| *n != "pi") {
            lw.scope.symbols.entry(n.to_string()).or_insert_with(|| (Symbol::Later(what), n.span()));
        }
    }

    // Pass 2: values in order.
    let mut param_out = Vec::new();
    for d in &params {
        let value = d.value.as_ref().and_then(|e| lw.constant(e, "a parameter's default value"));
        param_out.push(named(d, value, &item_of));
    }
    let input_out: Vec<Named> = inputs.iter().map(|d| named(d, None, &item_of)).collect();

    let mut unknown_guess: Vec<Option<NodeId>> = vec![None; unknowns.len()];
    let mut equations = Vec::new();
    let mut points = Vec::new();
    let mut scalars = Vec::new();
    let mut seen_item_names: HashMap<String, Span> = HashMap::new();
    for item in &items {
        match &item.kind {
            ItemKind::Decls(DeclKind::Unknowns, decls) => {
                for d in decls {
                    let Some(idx) = unknowns.iter().position(|u| std::ptr::eq(*u, d)) else { continue };
                    if let Some(e) = &d.value {
                        unknown_guess[idx] = lw.guess(e);
                    }
                }
            }
            ItemKind::Decls(..) => {}
            ItemKind::Let { name, value } => match lw.lower(value) {
                Some(v) => lw.define(name, v),
                None => lw.poison(name),
            },
            ItemKind::Point { name, value } => match lw.lower(value) {
                Some(Val::V(x, y)) => {
                    lw.define(name, Val::V(x, y));
                    points.push(Point { docs: item.docs.clone(), name: name.clone(), x, y });
                }
                Some(Val::S(_)) => {
                    lw.poison(name);
                    lw.errors.push(value.range().error(format!(
                        "`point {name}` needs a vector, but this is a scalar; for a scalar output write `output {name} = ...;`"
                    )));
                }
                None => lw.poison(name),
            },
            ItemKind::Output { name, value } => match lw.lower(value) {
                Some(Val::S(v)) => {
                    lw.define(name, Val::S(v));
                    scalars.push(Scalar { docs: item.docs.clone(), name: name.clone(), value: v });
                }
                Some(Val::V(..)) => {
                    lw.poison(name);
                    lw.errors.push(value.range().error(format!(
                        "`output {name}` needs a scalar, but this is a vector; for a vector output write `point {name} = ...;`"
                    )));
                }
                None => lw.poison(name),
            },
            ItemKind::Loop { name, lhs, rhs, eq } | ItemKind::Eq { name, lhs, rhs, eq } => {
                let is_loop = matches!(item.kind, ItemKind::Loop { .. });
                let key = name.to_string();
                if let Some(prev) = seen_item_names.insert(key.clone(), name.span()) {
                    let mut e = syn::Error::new(
                        name.span(),
                        format!("the name `{key}` is given to two loops or equations; rename one of them"),
                    );
                    e.combine(syn::Error::new(prev, format!("`{key}` is first used as a name here")));
                    lw.errors.push(e);
                    continue;
                }
                let range = item.range();
                let (l, r) = lw.lower_equation(lhs, rhs);
                let (Some(l), Some(r)) = (l, r) else { continue };
                match (is_loop, l, r) {
                    (true, Val::V(lx, ly), Val::V(rx, ry)) => {
                        let fx = lw.graph.sub(lx, rx);
                        let fy = lw.graph.sub(ly, ry);
                        let item = name.clone();
                        equations.push(Equation { name: format!("{key}.x"), item, is_loop, range, residual: fx });
                        let item = name.clone();
                        equations.push(Equation { name: format!("{key}.y"), item, is_loop, range, residual: fy });
                    }
                    (false, Val::S(a), Val::S(b)) => {
                        let f = lw.graph.sub(a, b);
                        equations.push(Equation { name: key, item: name.clone(), is_loop, range, residual: f });
                    }
                    (true, Val::S(_), Val::S(_)) => lw.errors.push(range.error(format!(
                        "`loop {name}` equates two scalars; a loop is a vector equation `vector == vector` \
                         (write `eq {name}: ... == ...;` for a scalar equation)"
                    ))),
                    (false, Val::V(..), Val::V(..)) => lw.errors.push(range.error(format!(
                        "`eq {name}` equates two vectors; an `eq` is one scalar equation \
                         (write `loop {name}: ... == ...;` for a vector loop: two scalar equations)"
                    ))),
                    (_, l, _) => {
                        let (side, other) =
                            if matches!(l, Val::V(..)) { ("vector", "scalar") } else { ("scalar", "vector") };
                        let help = if is_loop {
                            "a `loop` equates two vectors, e.g. `r @ phi == (x, 0) + l @ psi`"
                        } else {
                            "an `eq` equates two scalars; take a component with `.x`/`.y` or a length with `norm(..)`"
                        };
                        lw.errors.push(syn::Error::new(
                            *eq,
                            format!(
                                "the left side is a {side} but the right side is a {other}; both sides of `==` \
                                 must have the same type\nhelp: {help}"
                            ),
                        ));
                    }
                }
            }
        }
    }
    if lw.graph.overflowed() {
        lw.errors.push(syn::Error::new(name.span(), "the mechanism's expressions are too large for kinloop"));
    }

    let unknown_out = unknowns.iter().zip(unknown_guess).map(|(d, value)| named(d, value, &item_of)).collect();
    let Lowerer { graph, errors, used_params, used_inputs, .. } = lw;
    errors.finish(Model {
        docs,
        options,
        vis,
        name,
        body,
        params: param_out,
        inputs: input_out,
        unknowns: unknown_out,
        equations,
        points,
        scalars,
        graph,
        used_params,
        used_inputs,
    })
}

fn named(d: &Decl, value: Option<NodeId>, item_of: &HashMap<*const Decl, usize>) -> Named {
    let item = item_of.get(&(d as *const Decl)).copied().unwrap_or(0);
    Named { docs: d.docs.clone(), name: d.name.clone(), value, item }
}

impl Lowerer {
    /// Reports `name` if it cannot be declared: it is the built-in `pi`, or it names a symbol
    /// already declared that `replaceable` does not accept. Returns whether it was reported.
    fn reject(&mut self, name: &Ident, replaceable: fn(&Symbol) -> bool) -> bool {
        let key = name.to_string();
        if key == "pi" {
            self.errors
                .push(syn::Error::new(name.span(), "`pi` is the built-in constant 3.14159...; choose another name"));
            return true;
        }
        match self.scope.symbols.get(&key) {
            Some((prev, span)) if !replaceable(prev) => {
                let what = describe(*prev);
                let mut e = syn::Error::new(
                    name.span(),
                    format!("`{key}` is already declared as {what}; names must be unique, rename one of them"),
                );
                e.combine(syn::Error::new(*span, format!("`{key}` is first declared here")));
                self.errors.push(e);
                true
            }
            _ => false,
        }
    }

    /// Registers a global name; reports a duplicate and returns false.
    fn declare(&mut self, name: &Ident, sym: Symbol) -> bool {
        if self.reject(name, |_| false) {
            return false;
        }
        self.scope.symbols.insert(name.to_string(), (sym, name.span()));
        true
    }

    /// Defines a `let`, `point` or `output` name at its position in the body (where its
    /// `Symbol::Later` placeholder stands).
    fn define(&mut self, name: &Ident, v: Val) {
        if !self.reject(name, |prev| matches!(prev, Symbol::Later(_))) {
            self.scope.symbols.insert(name.to_string(), (Symbol::Let(v), name.span()));
        }
    }

    /// Marks a name whose definition failed, so its uses add no further errors.
    fn poison(&mut self, name: &Ident) {
        let key = name.to_string();
        if let Some((Symbol::Later(_), _)) | None = self.scope.symbols.get(&key) {
            self.scope.symbols.insert(key, (Symbol::Poisoned, name.span()));
        }
    }

    fn constant(&mut self, e: &Expr, what: &str) -> Option<NodeId> {
        let v = self.lower_scalar(e, what)?;
        if !self.graph.leaves_of(&[v]).is_empty() || self.graph.as_const(v).is_none() {
            self.errors.push(e.range().error(format!(
                "{what} must be a constant: write a number such as `2.5` or `pi / 4` \
                 (it cannot use parameters, inputs or unknowns)"
            )));
            return None;
        }
        Some(v)
    }

    fn guess(&mut self, e: &Expr) -> Option<NodeId> {
        let v = self.lower_scalar(e, "an initial guess")?;
        if self.graph.leaves_of(&[v]).iter().any(|l| matches!(l, Leaf::Unknown(_))) {
            self.errors.push(e.range().error(
                "an initial guess cannot use unknowns (they are what is being solved); \
                 write a number or an expression of parameters and inputs, e.g. `= 0.5` or `= l + r`",
            ));
            return None;
        }
        Some(v)
    }

    fn lower_scalar(&mut self, e: &Expr, what: &str) -> Option<NodeId> {
        match self.lower(e)? {
            Val::S(v) => Some(v),
            Val::V(..) => {
                self.errors.push(e.range().error(format!("{what} must be a scalar, but this is a vector")));
                None
            }
        }
    }

    /// Lowers both sides of an equation; a literal `0` facing a vector is the zero vector.
    fn lower_equation(&mut self, lhs: &Expr, rhs: &Expr) -> (Option<Val>, Option<Val>) {
        let zero_like = |g: &mut Graph, v: Val| {
            let z = g.zero();
            match v {
                Val::S(_) => Val::S(z),
                Val::V(..) => Val::V(z, z),
            }
        };
        match (lhs.is_literal_zero(), rhs.is_literal_zero()) {
            (true, false) => {
                let r = self.lower(rhs);
                (r.map(|v| zero_like(&mut self.graph, v)), r)
            }
            (false, true) => {
                let l = self.lower(lhs);
                (l, l.map(|v| zero_like(&mut self.graph, v)))
            }
            _ => (self.lower(lhs), self.lower(rhs)),
        }
    }

    fn lower(&mut self, e: &Expr) -> Option<Val> {
        let g = &mut self.graph;
        Some(match e {
            Expr::Num { value, .. } => Val::S(g.constant(*value)),
            Expr::Var(id) => return self.lookup(id),
            Expr::Paren { inner, .. } => return self.lower(inner),
            Expr::Neg { expr, .. } => match self.lower(expr)? {
                Val::S(a) => Val::S(self.graph.neg(a)),
                Val::V(x, y) => Val::V(self.graph.neg(x), self.graph.neg(y)),
            },
            Expr::Tuple { x, y, .. } => {
                let xs = self.lower_component(x);
                let ys = self.lower_component(y);
                Val::V(xs?, ys?)
            }
            Expr::Field { base, component, name } => match self.lower(base)? {
                Val::V(x, y) => Val::S(if *component == Component::X { x } else { y }),
                Val::S(_) => {
                    self.errors.push(syn::Error::new(
                        name.span(),
                        format!(
                            "`.{name}` takes a component of a vector, but `{}` is a scalar; remove `.{name}`",
                            short(&base.show())
                        ),
                    ));
                    return None;
                }
            },
            Expr::Binary { op, op_span, lhs, rhs } => {
                let l = self.lower(lhs);
                let r = self.lower(rhs);
                let (l, r) = (l?, r?);
                return self.binary(*op, *op_span, lhs, rhs, l, r);
            }
            Expr::Call { func, args, close } => return self.call(func, args, *close),
        })
    }

    fn lower_component(&mut self, e: &Expr) -> Option<NodeId> {
        match self.lower(e)? {
            Val::S(v) => Some(v),
            Val::V(..) => {
                self.errors.push(e.range().error("a vector's component must be a scalar; `(x, y)` takes two numbers"));
                None
            }
        }
    }

    fn lookup(&mut self, id: &Ident) -> Option<Val> {
        let key = id.to_string();
        let g = &mut self.graph;
        match self.scope.symbols.get(&key) {
            Some((Symbol::Param(i), _)) => {
                self.used_params[*i as usize] = true;
                Some(Val::S(g.leaf(Leaf::Param(*i))))
            }
            Some((Symbol::Input(i), _)) => {
                if let Some(u) = self.used_inputs.get_mut(*i as usize) {
                    *u = true;
                }
                Some(Val::S(g.leaf(Leaf::Input(*i))))
            }
            Some((Symbol::Unknown(i), _)) => Some(Val::S(g.leaf(Leaf::Unknown(*i)))),
            Some((Symbol::Let(v), _)) => Some(*v),
            Some((Symbol::Poisoned, _)) => None,
            Some((Symbol::Later(what), span)) => {
                let mut e = syn::Error::new(
                    id.span(),
                    format!("`{key}` is used before it is defined; move `{what} {key} = ...;` above this line"),
                );
                e.combine(syn::Error::new(*span, format!("`{what} {key}` is defined here, after its use")));
                self.errors.push(e);
                None
            }
            None if key == "pi" => Some(Val::S(g.constant(std::f64::consts::PI))),
            None => {
                let names: Vec<String> = self
                    .scope
                    .symbols
                    .iter()
                    .filter(|(_, (s, _))| !matches!(s, Symbol::Later(_)))
                    .map(|(k, _)| k.clone())
                    .collect();
                let hint = match similar(&key, names.iter()) {
                    Some(s) => format!("; did you mean `{s}`?"),
                    None => String::new(),
                };
                self.errors.push(syn::Error::new(
                    id.span(),
                    format!(
                        "unknown name `{key}`{hint} (declare it with `params`, `input`, `unknowns` or `let` before using it)"
                    ),
                ));
                None
            }
        }
    }

    fn binary(&mut self, op: BinOp, op_span: Span, lhs: &Expr, rhs: &Expr, l: Val, r: Val) -> Option<Val> {
        let g = &mut self.graph;
        let res = match (op, l, r) {
            (BinOp::Add, Val::S(a), Val::S(b)) => Val::S(g.add(a, b)),
            (BinOp::Add, Val::V(ax, ay), Val::V(bx, by)) => Val::V(g.add(ax, bx), g.add(ay, by)),
            (BinOp::Sub, Val::S(a), Val::S(b)) => Val::S(g.sub(a, b)),
            (BinOp::Sub, Val::V(ax, ay), Val::V(bx, by)) => Val::V(g.sub(ax, bx), g.sub(ay, by)),
            (BinOp::Add | BinOp::Sub, _, _) => {
                let verb = if op == BinOp::Add { "add" } else { "subtract" };
                let mut msg = format!(
                    "cannot {verb} a {} and a {}: both sides of `{}` must be scalars or both vectors",
                    kind(l),
                    kind(r),
                    op.symbol()
                );
                if let (Expr::Binary { op: BinOp::Polar, lhs: len, rhs: angle, .. }, Val::V(..), Val::S(_)) =
                    (lhs, l, r)
                {
                    let fixed = format!("{} @ ({} {} {})", len.show(), angle.show(), op.symbol(), rhs.show());
                    let example = if fixed.len() <= 60 { fixed } else { "r @ (phi + gamma)".to_string() };
                    msg.push_str(&format!(
                        "\nhelp: `@` binds tighter than `+` and `-`, so an angle that is a sum needs \
                         parentheses: write `{example}`"
                    ));
                }
                self.errors.push(syn::Error::new(op_span, msg));
                return None;
            }
            (BinOp::Mul, Val::S(a), Val::S(b)) => Val::S(g.mul(a, b)),
            (BinOp::Mul, Val::S(a), Val::V(x, y)) | (BinOp::Mul, Val::V(x, y), Val::S(a)) => {
                Val::V(g.mul(a, x), g.mul(a, y))
            }
            (BinOp::Mul, Val::V(..), Val::V(..)) => {
                self.errors.push(syn::Error::new(
                    op_span,
                    "cannot multiply two vectors with `*`; write `dot(a, b)` or `cross(a, b)`",
                ));
                return None;
            }
            (BinOp::Div, Val::S(a), Val::S(b)) => Val::S(g.div(a, b)),
            (BinOp::Div, Val::V(x, y), Val::S(a)) => Val::V(g.div(x, a), g.div(y, a)),
            (BinOp::Div, _, Val::V(..)) => {
                self.errors.push(rhs.range().error("cannot divide by a vector; the divisor must be a scalar"));
                return None;
            }
            (BinOp::Pow, Val::S(a), Val::S(b)) => {
                if let Some(n) = integer_exponent(rhs) {
                    Val::S(g.powi(a, n))
                } else {
                    Val::S(g.powf(a, b))
                }
            }
            (BinOp::Pow, _, _) => {
                self.errors.push(syn::Error::new(
                    op_span,
                    "`^` raises a scalar to a scalar power; for the length of a vector write `norm(v)`",
                ));
                return None;
            }
            (BinOp::Polar, Val::S(len), Val::S(angle)) => {
                let c = g.func(Func::Cos, angle);
                let s = g.func(Func::Sin, angle);
                Val::V(g.mul(len, c), g.mul(len, s))
            }
            (BinOp::Polar, _, _) => {
                let side = if matches!(l, Val::V(..)) { lhs } else { rhs };
                self.errors.push(side.range().error(
                    "`@` builds a vector from a scalar length and a scalar angle (`length @ angle`), but this is \
                     a vector; to turn a vector by an angle write `rot(v, angle)`",
                ));
                return None;
            }
        };
        Some(res)
    }

    fn call(&mut self, func: &Ident, args: &[Expr], close: Span) -> Option<Val> {
        let name = func.to_string();
        let known = SCALAR_FUNCTIONS.contains(&name.as_str()) || VECTOR_FUNCTIONS.contains(&name.as_str());
        if !known {
            let all: Vec<String> = SCALAR_FUNCTIONS.iter().chain(VECTOR_FUNCTIONS).map(|s| (*s).to_string()).collect();
            let hint = match name.as_str() {
                "log" => "; the natural logarithm is `ln`".to_string(),
                "powi" | "powf" => "; write `x ^ n` or `pow(x, y)`".to_string(),
                "sqr" => "; write `x ^ 2`".to_string(),
                "atan2d" | "sind" | "cosd" => "; angles are in radians (write `30 * pi / 180`)".to_string(),
                _ => match similar(&name, all.iter()) {
                    Some(s) => format!("; did you mean `{s}`?"),
                    None => String::new(),
                },
            };
            self.errors.push(syn::Error::new(
                func.span(),
                format!(
                    "unsupported function `{name}`{hint}\navailable functions: {}; for vectors: {}",
                    SCALAR_FUNCTIONS.join(", "),
                    VECTOR_FUNCTIONS.join(", ")
                ),
            ));
            return None;
        }
        let (arity, signature) = match name.as_str() {
            "atan2" => (2, "atan2(y, x)"),
            "pow" => (2, "pow(base, exponent)"),
            "hypot" => (2, "hypot(a, b)"),
            "dot" => (2, "dot(vector, vector)"),
            "cross" => (2, "cross(vector, vector)"),
            "rot" => (2, "rot(vector, angle)"),
            "norm" => (1, "norm(vector)"),
            "angle" => (1, "angle(vector)"),
            _ => (1, ""),
        };
        if args.len() != arity {
            let sig = if signature.is_empty() { format!("{name}(x)") } else { signature.to_string() };
            let span = args.get(arity).map_or(close, |a| a.range().start);
            self.errors.push(syn::Error::new(
                span,
                format!(
                    "`{name}` takes {arity} argument{}: `{sig}`, but {} {} given",
                    if arity == 1 { "" } else { "s" },
                    args.len(),
                    if args.len() == 1 { "was" } else { "were" }
                ),
            ));
            return None;
        }
        let vals: Vec<Option<Val>> = args.iter().map(|a| self.lower(a)).collect();
        let vals: Vec<Val> = vals.into_iter().collect::<Option<_>>()?;
        let want_vector: &[bool] = match name.as_str() {
            "dot" | "cross" => &[true, true],
            "rot" => &[true, false],
            "norm" | "angle" => &[true],
            _ => &[false, false],
        };
        let mut ok = true;
        for ((v, a), &want) in vals.iter().zip(args).zip(want_vector) {
            let is_vec = matches!(v, Val::V(..));
            if is_vec != want {
                ok = false;
                let (got, hint) = if is_vec {
                    (
                        "vector",
                        format!(
                            "`{name}` takes a scalar here; take a component with `.x`/`.y` or the length with `norm(..)`"
                        ),
                    )
                } else {
                    ("scalar", format!("`{name}` takes a vector here, e.g. `(x, y)` or `r @ angle`"))
                };
                self.errors.push(a.range().error(format!("this argument is a {got}: {hint}")));
            }
        }
        if !ok {
            return None;
        }
        let g = &mut self.graph;
        let s = |v: Val| match v {
            Val::S(a) => a,
            Val::V(x, _) => x,
        };
        let vxy = |v: Val| match v {
            Val::V(x, y) => (x, y),
            Val::S(a) => (a, a),
        };
        Some(match name.as_str() {
            "atan2" => Val::S(g.atan2(s(vals[0]), s(vals[1]))),
            "pow" => Val::S(if let Some(n) = integer_exponent(&args[1]) {
                g.powi(s(vals[0]), n)
            } else {
                g.powf(s(vals[0]), s(vals[1]))
            }),
            "hypot" => {
                let a2 = g.powi(s(vals[0]), 2);
                let b2 = g.powi(s(vals[1]), 2);
                let sum = g.add(a2, b2);
                Val::S(g.func(Func::Sqrt, sum))
            }
            "norm" => {
                let (x, y) = vxy(vals[0]);
                let x2 = g.powi(x, 2);
                let y2 = g.powi(y, 2);
                let sum = g.add(x2, y2);
                Val::S(g.func(Func::Sqrt, sum))
            }
            "angle" => {
                let (x, y) = vxy(vals[0]);
                Val::S(g.atan2(y, x))
            }
            "dot" => {
                let ((ax, ay), (bx, by)) = (vxy(vals[0]), vxy(vals[1]));
                let p = g.mul(ax, bx);
                let q = g.mul(ay, by);
                Val::S(g.add(p, q))
            }
            "cross" => {
                let ((ax, ay), (bx, by)) = (vxy(vals[0]), vxy(vals[1]));
                let p = g.mul(ax, by);
                let q = g.mul(ay, bx);
                Val::S(g.sub(p, q))
            }
            "rot" => {
                let (x, y) = vxy(vals[0]);
                let t = s(vals[1]);
                let (c, sn) = (g.func(Func::Cos, t), g.func(Func::Sin, t));
                let xc = g.mul(x, c);
                let ys = g.mul(y, sn);
                let xs = g.mul(x, sn);
                let yc = g.mul(y, c);
                Val::V(g.sub(xc, ys), g.add(xs, yc))
            }
            other => match one_arg(other) {
                Some(f) => Val::S(g.func(f, s(vals[0]))),
                None => return None,
            },
        })
    }
}

/// Largest integer exponent turned into `powi`; larger ones stay `powf`. The bound keeps the
/// exponents of the derivatives (`n - 1`, `n - 2`) far from `i32` overflow.
pub const MAX_INTEGER_EXPONENT: i64 = 1024;

/// An exponent written as an integer literal (possibly negated) becomes `powi`.
fn integer_exponent(e: &Expr) -> Option<i32> {
    match e {
        Expr::Num { integer: Some(n), .. } if n.abs() <= MAX_INTEGER_EXPONENT => i32::try_from(*n).ok(),
        Expr::Neg { expr, .. } => integer_exponent(expr).map(|n| -n),
        Expr::Paren { inner, .. } => integer_exponent(inner),
        _ => None,
    }
}

/// At most 40 characters of `s`, for quoting source in messages.
fn short(s: &str) -> String {
    if s.chars().count() <= 40 { s.to_string() } else { format!("{}...", s.chars().take(40).collect::<String>()) }
}

fn kind(v: Val) -> &'static str {
    match v {
        Val::S(_) => "scalar",
        Val::V(..) => "vector",
    }
}

fn describe(s: Symbol) -> &'static str {
    match s {
        Symbol::Param(_) => "a parameter",
        Symbol::Input(_) => "an input",
        Symbol::Unknown(_) => "an unknown",
        Symbol::Let(_) => "a named value",
        Symbol::Later("let") => "a `let`",
        Symbol::Later("point") => "a `point`",
        Symbol::Later(_) => "an `output`",
        Symbol::Poisoned => "a named value",
    }
}
