//! Scheduling graph nodes into the scopes of a generated function and rendering them as
//! straight-line `let` statements.
//!
//! A generated solver is a sequence of scopes: per block a *pre* scope (values that do not
//! depend on the block's own unknowns, computed once) and a *loop* scope (inside the Newton
//! evaluation closure), then the analog and output scopes. Each node is computed once, in the
//! first scope that needs it; values computed inside a Newton closure that later scopes need are
//! handed out through the evaluation's `keep` array instead of being recomputed.

use crate::dag::{Func, Graph, Leaf, NodeId, Op};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum ScopeKind {
    /// Straight-line code.
    Plain,
    /// Inside the Newton closure of a block; nodes of lower level go to the scope just before.
    Loop(usize),
}

pub struct ScopeSpec {
    pub kind: ScopeKind,
    pub roots: Vec<NodeId>,
}

pub struct Schedule {
    /// Nodes computed in each scope, in topological order.
    pub lets: Vec<Vec<NodeId>>,
    /// Nodes a loop scope must hand out to other scopes.
    pub exports: Vec<Vec<NodeId>>,
}

pub fn schedule(g: &Graph, level: &[i32], scopes: &[ScopeSpec]) -> Schedule {
    let mut assigned: HashMap<NodeId, usize> = HashMap::new();
    for (s, spec) in scopes.iter().enumerate() {
        let mut stack: Vec<NodeId> = spec.roots.clone();
        while let Some(n) = stack.pop() {
            if assigned.contains_key(&n) || matches!(g.op(n), Op::Const(_) | Op::Leaf(_)) {
                continue;
            }
            let target = match spec.kind {
                ScopeKind::Loop(b) if level[n.index()] < b as i32 && s > 0 => s - 1,
                _ => s,
            };
            assigned.insert(n, target);
            stack.extend(g.op(n).operands());
        }
    }
    // A sine and a cosine of the same argument are computed together (one `sin_cos`) in the
    // earlier of their two scopes; the argument is available there, since one of them already is.
    let cos_of: HashMap<NodeId, NodeId> = assigned
        .keys()
        .filter_map(|&m| match g.op(m) {
            Op::Func(Func::Cos, a) => Some((a, m)),
            _ => None,
        })
        .collect();
    let pairs: Vec<(NodeId, NodeId)> = assigned
        .keys()
        .filter_map(|&n| match g.op(n) {
            Op::Func(Func::Sin, a) => cos_of.get(&a).map(|&m| (n, m)),
            _ => None,
        })
        .collect();
    for (sn, cn) in pairs {
        let first = assigned[&sn].min(assigned[&cn]);
        assigned.insert(sn, first);
        assigned.insert(cn, first);
    }
    let mut lets = vec![Vec::new(); scopes.len()];
    for (&n, &s) in &assigned {
        lets[s].push(n);
    }
    for l in &mut lets {
        l.sort_unstable();
    }
    let mut exports = vec![Vec::new(); scopes.len()];
    let mut export = |n: NodeId, user_scope: usize| {
        if let Some(&s) = assigned.get(&n)
            && s != user_scope
            && matches!(scopes[s].kind, ScopeKind::Loop(_))
            && !exports[s].contains(&n)
        {
            exports[s].push(n);
        }
    };
    for (&m, &t) in &assigned {
        for n in g.op(m).operands() {
            export(n, t);
        }
    }
    for (t, spec) in scopes.iter().enumerate() {
        for &r in &spec.roots {
            export(r, t);
        }
    }
    for e in &mut exports {
        e.sort_unstable();
    }
    Schedule { lets, exports }
}

/// Names of leaves and temporaries in generated code.
pub struct Names {
    pub params: Vec<Ident>,
    pub inputs: Vec<Ident>,
    pub unknowns: Vec<Ident>,
}

impl Names {
    pub fn temp(n: NodeId) -> Ident {
        format_ident!("t{}", n.0)
    }

    pub fn tan(u: usize, i: usize) -> Ident {
        format_ident!("v{}_{}", u, i)
    }

    pub fn tan2(u: usize, i: usize, j: usize) -> Ident {
        let (i, j) = if i <= j { (i, j) } else { (j, i) };
        format_ident!("w{}_{}_{}", u, i, j)
    }

    pub fn sens_q(u: usize, k: usize) -> Ident {
        format_ident!("sq{}_{}", u, k)
    }

    pub fn sens_v(u: usize, i: usize, k: usize) -> Ident {
        format_ident!("sv{}_{}_{}", u, i, k)
    }

    pub fn sens_a(u: usize, i: usize, j: usize, k: usize) -> Ident {
        let (i, j) = if i <= j { (i, j) } else { (j, i) };
        format_ident!("sa{}_{}_{}_{}", u, i, j, k)
    }

    fn leaf(&self, l: Leaf) -> TokenStream {
        match l {
            Leaf::Param(k) => ident_tokens(&self.params[k as usize]),
            Leaf::Input(k) => ident_tokens(&self.inputs[k as usize]),
            Leaf::Unknown(k) => ident_tokens(&self.unknowns[k as usize]),
            Leaf::Tan { unknown, input } => ident_tokens(&Self::tan(unknown as usize, input as usize)),
            Leaf::Tan2 { unknown, i, j } => ident_tokens(&Self::tan2(unknown as usize, i as usize, j as usize)),
            Leaf::SensQ { unknown, param } => ident_tokens(&Self::sens_q(unknown as usize, param as usize)),
            Leaf::SensV { unknown, input, param } => {
                ident_tokens(&Self::sens_v(unknown as usize, input as usize, param as usize))
            }
            Leaf::SensA { unknown, i, j, param } => {
                ident_tokens(&Self::sens_a(unknown as usize, i as usize, j as usize, param as usize))
            }
        }
    }

    /// A node as an operand: a literal, a leaf's local, or a temporary.
    pub fn operand(&self, g: &Graph, n: NodeId) -> TokenStream {
        match g.op(n) {
            Op::Const(bits) => float(f64::from_bits(bits)),
            Op::Leaf(l) => self.leaf(l),
            _ => ident_tokens(&Self::temp(n)),
        }
    }

    /// The expression computing node `n` from its operands.
    pub fn expr(&self, g: &Graph, n: NodeId) -> TokenStream {
        let o = |x: NodeId| self.operand(g, x);
        match g.op(n) {
            Op::Const(_) | Op::Leaf(_) => self.operand(g, n),
            Op::Add(a, b) => {
                let (a, b) = (o(a), o(b));
                quote!(#a + #b)
            }
            Op::Sub(a, b) => {
                let (a, b) = (o(a), o(b));
                quote!(#a - #b)
            }
            Op::Mul(a, b) => {
                let (a, b) = (o(a), o(b));
                quote!(#a * #b)
            }
            Op::Div(a, b) => {
                let (a, b) = (o(a), o(b));
                quote!(#a / #b)
            }
            Op::Neg(a) => {
                let a = o(a);
                quote!(-#a)
            }
            Op::Powi(a, 2) => {
                let a = o(a);
                quote!(#a * #a)
            }
            Op::Powi(a, -1) => {
                let a = o(a);
                quote!(1.0 / #a)
            }
            Op::Powi(a, k) => {
                let a = o(a);
                let k = Literal::i32_unsuffixed(k);
                quote!(#a.powi(#k))
            }
            Op::Powf(a, b) => {
                let (a, b) = (o(a), o(b));
                quote!(#a.powf(#b))
            }
            Op::Func(f, a) => {
                let a = o(a);
                let m = Ident::new(f.method(), Span::call_site());
                quote!(#a.#m())
            }
            Op::Atan2(y, x) => {
                let (y, x) = (o(y), o(x));
                quote!(#y.atan2(#x))
            }
        }
    }

    /// `let tN: f64 = ...;` for each node.
    /// A sine and a cosine of the same argument in one scope become one `sin_cos()` call, at
    /// the position of whichever of the two comes first (both need only their argument).
    pub fn lets(&self, g: &Graph, nodes: &[NodeId]) -> TokenStream {
        let mut sin_cos: HashMap<NodeId, [Option<NodeId>; 2]> = HashMap::new();
        for &n in nodes {
            match g.op(n) {
                Op::Func(Func::Sin, a) => sin_cos.entry(a).or_default()[0] = Some(n),
                Op::Func(Func::Cos, a) => sin_cos.entry(a).or_default()[1] = Some(n),
                _ => {}
            }
        }
        let mut paired = std::collections::HashSet::new();
        let mut out = TokenStream::new();
        for &n in nodes {
            if paired.contains(&n) {
                continue;
            }
            if let Op::Func(Func::Sin | Func::Cos, a) = g.op(n)
                && let Some(&[Some(sn), Some(cn)]) = sin_cos.get(&a)
            {
                paired.insert(sn);
                paired.insert(cn);
                let (s, c) = (Self::temp(sn), Self::temp(cn));
                let arg = self.operand(g, a);
                out.extend(quote!(let (#s, #c): (f64, f64) = #arg.sin_cos();));
                continue;
            }
            let name = Self::temp(n);
            let e = self.expr(g, n);
            out.extend(quote!(let #name: f64 = #e;));
        }
        out
    }
}

fn ident_tokens(id: &Ident) -> TokenStream {
    quote!(#id)
}

/// An `f64` literal; negative values are parenthesised so they can be method receivers.
pub fn float(v: f64) -> TokenStream {
    if v.is_nan() {
        return quote!(f64::NAN);
    }
    if v.is_infinite() {
        return if v > 0.0 { quote!(f64::INFINITY) } else { quote!(f64::NEG_INFINITY) };
    }
    let lit = Literal::f64_suffixed(v.abs());
    if v.is_sign_negative() && v != 0.0 { quote!((-#lit)) } else { quote!(#lit) }
}
