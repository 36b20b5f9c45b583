//! Names of the locals in generated code, and the `let` statements that compute graph nodes.
//!
//! Leaves read like the quantities they hold: `self.a` (parameter `a`), `x_phi` (input), `q_beta`
//! (unknown), `dq_beta_phi` (`d beta / d phi`), `d2q_beta_phi_phi`, and for the sensitivities
//! to parameter `a` `sq_beta_a`, `sdq_beta_phi_a`, `sd2q_beta_phi_phi_a`. Should two such names
//! coincide (names containing underscores can), the derived names fall back to indices
//! (`dq0_1`). Temporaries that are a declared quantity are named after it: the residual of
//! `loop abcd` on X is `r_abcd_x`, its derivative by `beta` `j_abcd_x_beta`, by input `phi`
//! `fx_abcd_x_phi`, the x coordinate of `point p` `out_p_x`, its analogs `dout_p_x_phi` and
//! `d2out_p_x_phi_phi`, the value of `let e` `let_e` (a constant `e` of the module around the
//! macro would turn a local named `e` into a pattern). Other temporaries, and derivatives that
//! other values are computed from, are named by their form where it is short (`cos_phi`,
//! `a_cos_phi`); the rest are `t` and their node number.

use super::schedule::Schedule;
use crate::graph::angle_sums::angle_sum;
use crate::graph::dag::{Func, Graph, Leaf, NodeId, Op};
use crate::plan::Plan;
use crate::semantics::model::Model;
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::{HashMap, HashSet};
use syn::ext::IdentExt;

/// Names of leaves and temporaries in generated code.
#[derive(Clone)]
pub struct Names {
    /// The mechanism's name without `r#` (module-level items derived from it: a sparse
    /// block's tables and steps).
    pub mechanism: String,
    /// Parameters are read from the mechanism where they are used (`self.a`).
    pub params: Vec<TokenStream>,
    /// Locals holding the inputs (`x_phi`).
    pub inputs: Vec<Ident>,
    /// Locals holding the unknowns (`q_beta`).
    pub unknowns: Vec<Ident>,
    /// Plain names of unknowns, inputs and parameters, for the derived names.
    u: Vec<String>,
    i: Vec<String>,
    p: Vec<String>,
    /// Derived names are readable (no two coincide).
    readable: bool,
    /// Temporaries named after the declared quantity they are.
    roles: HashMap<NodeId, Ident>,
    /// Sines whose argument is free of the unknowns, with their slot: in a sweep's kernel their
    /// `sin_cos` is asked of the sweep's cache `__trig` (see [`Names::with_input_trig`]).
    trig_slots: HashMap<NodeId, usize>,
    /// A sweep's kernel: closed-form angles are asked of `__trig` too.
    sweep_kernel: bool,
}

/// How a Newton block's evaluation asks its `NearTrig` for a sine and cosine
/// ([`Names::lets_near`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NearCall {
    /// The guess's evaluation: libm's values, kept in the slot (`seed`).
    Seed,
    /// A later evaluation: the slot's values rotated where the argument moved little
    /// (`sin_cos`).
    Rotate,
}

/// An identifier without `r#`: the one spelling of a name in derived identifiers (the
/// mechanism's types, its sparse blocks' items, the kernels' temporaries).
pub(crate) fn plain(id: &Ident) -> String {
    id.unraw().to_string()
}

fn lower(i: usize, j: usize) -> (usize, usize) {
    if i <= j { (i, j) } else { (j, i) }
}

impl Names {
    /// The names of `model`'s leaves, and of the temporaries named after the quantities in `plan`.
    pub fn new(model: &Model, plan: &Plan) -> Names {
        let u: Vec<String> = model.unknowns.iter().map(|x| plain(&x.name)).collect();
        let i: Vec<String> = model.inputs.iter().map(|x| plain(&x.name)).collect();
        let p: Vec<String> = model.params.iter().map(|x| plain(&x.name)).collect();
        let mut names = Names {
            mechanism: plain(&model.name),
            params: model
                .params
                .iter()
                .map(|x| {
                    let f = &x.name;
                    quote!(self.#f)
                })
                .collect(),
            inputs: i.iter().map(|s| format_ident!("x_{}", s)).collect(),
            unknowns: u.iter().map(|s| format_ident!("q_{}", s)).collect(),
            u,
            i,
            p,
            readable: true,
            roles: HashMap::new(),
            trig_slots: HashMap::new(),
            sweep_kernel: false,
        };
        names.readable = names.distinct();
        names.roles = roles(model, plan);
        names
    }

    /// These names for a sweep's kernel: every sine and cosine computed together whose argument
    /// depends on no unknown (the inputs' angles, `phi + gamma`, parameter angles) is asked of
    /// the kernel's `__trig: &mut impl InputTrig`, one slot per argument, so that a sweep can
    /// advance it by rotation instead of calling libm. The angles of closed-form blocks are asked
    /// of it too (see [`Names::sweep_kernel`]).
    pub fn with_input_trig(&self, plan: &Plan) -> Names {
        let g = &plan.graph;
        // A sum of angles computed by angle addition asks nothing of the cache.
        let sines = (0..g.len()).map(|k| NodeId(k as u32)).filter(|&n| match g.op(n) {
            Op::Func(Func::Sin, a) => {
                plan.level[a.index()] < 0 && !matches!(g.op(a), Op::Const(_)) && angle_sum(g, n).is_none()
            }
            _ => false,
        });
        Names { trig_slots: sines.enumerate().map(|(slot, n)| (n, slot)).collect(), sweep_kernel: true, ..self.clone() }
    }

    /// The slots of a sweep's kernel (see [`Names::with_input_trig`]) whose argument is a
    /// parameter, with that parameter (`self.gamma`), in the order of the slots: the values
    /// `kinematics_flat` computes before it calls the kernel (`Preset`), so that a caller's loop
    /// computes them once even where the kernel is out of line.
    pub fn parameter_slots(&self, g: &Graph) -> Vec<(usize, TokenStream)> {
        let mut slots: Vec<(usize, TokenStream)> = self
            .trig_slots
            .iter()
            .filter_map(|(&sn, &slot)| match g.op(sn) {
                Op::Func(Func::Sin, a) if matches!(g.op(a), Op::Leaf(Leaf::Param(_))) => {
                    Some((slot, self.operand(g, a)))
                }
                _ => None,
            })
            .collect();
        slots.sort_by_key(|&(slot, _)| slot);
        slots
    }

    /// Names of a sweep's kernel (made by [`Names::with_input_trig`]): its closed-form blocks ask
    /// `__trig` for their angles, by the unknown's index.
    pub fn sweep_kernel(&self) -> bool {
        self.sweep_kernel
    }

    /// Whether the readable derived names are all distinct.
    fn distinct(&self) -> bool {
        let (nu, ni, np) = (self.u.len(), self.i.len(), self.p.len());
        let mut seen = HashSet::new();
        let mut all = true;
        for u in 0..nu {
            for i in 0..ni {
                all &= seen.insert(self.tan(u, i).to_string());
                for j in i..ni {
                    all &= seen.insert(self.tan2(u, i, j).to_string());
                    all &= (0..np).all(|k| seen.insert(self.sens_a(u, i, j, k).to_string()));
                }
                all &= (0..np).all(|k| seen.insert(self.sens_v(u, i, k).to_string()));
            }
            all &= (0..np).all(|k| seen.insert(self.sens_q(u, k).to_string()));
        }
        all
    }

    /// The local holding node `n`: its role's name, or `t` and its number.
    pub fn temp(&self, n: NodeId) -> Ident {
        self.roles.get(&n).cloned().unwrap_or_else(|| format_ident!("t{}", n.0))
    }

    /// `d q_u / d x_i`.
    pub fn tan(&self, u: usize, i: usize) -> Ident {
        if self.readable { format_ident!("dq_{}_{}", self.u[u], self.i[i]) } else { format_ident!("dq{}_{}", u, i) }
    }

    /// `d2 q_u / d x_i d x_j`.
    pub fn tan2(&self, u: usize, i: usize, j: usize) -> Ident {
        let (i, j) = lower(i, j);
        if self.readable {
            format_ident!("d2q_{}_{}_{}", self.u[u], self.i[i], self.i[j])
        } else {
            format_ident!("d2q{}_{}_{}", u, i, j)
        }
    }

    /// `d q_u / d p_k`.
    pub fn sens_q(&self, u: usize, k: usize) -> Ident {
        if self.readable { format_ident!("sq_{}_{}", self.u[u], self.p[k]) } else { format_ident!("sq{}_{}", u, k) }
    }

    /// `d (d q_u / d x_i) / d p_k`.
    pub fn sens_v(&self, u: usize, i: usize, k: usize) -> Ident {
        if self.readable {
            format_ident!("sdq_{}_{}_{}", self.u[u], self.i[i], self.p[k])
        } else {
            format_ident!("sdq{}_{}_{}", u, i, k)
        }
    }

    /// `d (d2 q_u / d x_i d x_j) / d p_k`.
    pub fn sens_a(&self, u: usize, i: usize, j: usize, k: usize) -> Ident {
        let (i, j) = lower(i, j);
        if self.readable {
            format_ident!("sd2q_{}_{}_{}_{}", self.u[u], self.i[i], self.i[j], self.p[k])
        } else {
            format_ident!("sd2q{}_{}_{}_{}", u, i, j, k)
        }
    }

    fn leaf(&self, l: Leaf) -> TokenStream {
        let us = |x: u16| x as usize;
        let id = match l {
            Leaf::Param(k) => return self.params[us(k)].clone(),
            Leaf::Input(k) => self.inputs[us(k)].clone(),
            Leaf::Unknown(k) => self.unknowns[us(k)].clone(),
            Leaf::Tan { unknown, input } => self.tan(us(unknown), us(input)),
            Leaf::Tan2 { unknown, i, j } => self.tan2(us(unknown), us(i), us(j)),
            Leaf::SensQ { unknown, param } => self.sens_q(us(unknown), us(param)),
            Leaf::SensV { unknown, input, param } => self.sens_v(us(unknown), us(input), us(param)),
            Leaf::SensA { unknown, i, j, param } => self.sens_a(us(unknown), us(i), us(j), us(param)),
        };
        quote!(#id)
    }

    /// A node as an operand: a literal, a leaf's local, or a temporary.
    pub fn operand(&self, g: &Graph, n: NodeId) -> TokenStream {
        match g.op(n) {
            Op::Const(bits) => float(f64::from_bits(bits)),
            Op::Leaf(l) => self.leaf(l),
            _ => {
                let id = self.temp(n);
                quote!(#id)
            }
        }
    }

    /// Operands of several nodes, e.g. for an array literal.
    pub fn operands<'a>(&'a self, g: &'a Graph, nodes: &'a [NodeId]) -> impl Iterator<Item = TokenStream> + 'a {
        nodes.iter().map(move |&n| self.operand(g, n))
    }

    /// Nested rows `[[a, b], [c, d]]` of node operands.
    pub fn rows(&self, g: &Graph, rows: &[Vec<NodeId>]) -> TokenStream {
        let r = rows.iter().map(|row| {
            let v = self.operands(g, row);
            quote!([#(#v),*])
        });
        quote!([#(#r),*])
    }

    /// The expression computing node `n` from its operands.
    pub fn expr(&self, g: &Graph, n: NodeId) -> TokenStream {
        let o = |x: NodeId| self.operand(g, x);
        match g.op(n) {
            Op::Const(_) | Op::Leaf(_) => self.operand(g, n),
            Op::Add(a, b) => binary(o(a), quote!(+), o(b)),
            Op::Sub(a, b) => binary(o(a), quote!(-), o(b)),
            Op::Mul(a, b) => binary(o(a), quote!(*), o(b)),
            Op::Div(a, b) => binary(o(a), quote!(/), o(b)),
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
                let (a, k) = (o(a), Literal::i32_unsuffixed(k));
                quote!(#a.powi(#k))
            }
            Op::Powf(a, b) => method(o(a), "powf", Some(o(b))),
            Op::Func(f, a) => method(o(a), f.method(), None),
            Op::Atan2(y, x) => method(o(y), "atan2", Some(o(x))),
            // `graph::dag::select`: the chosen operand itself, NaN when `a` and `b` do not compare.
            Op::Select(a, b, x, y) => {
                let (a, b, x, y) = (o(a), o(b), o(x), o(y));
                quote!(if #a <= #b { #x } else if #b < #a { #y } else { ::core::primitive::f64::NAN })
            }
        }
    }

    /// Node `root` as one block expression computing it from the leaves: a `let` of each node
    /// below it in order (named as [`Names::temp`] names it, shadowing any binding of the same
    /// node outside, which holds the same value), then `root`. For a value read only on a cold
    /// path, which no schedule computes beforehand.
    pub fn standalone(&self, g: &Graph, root: NodeId) -> TokenStream {
        let lets =
            g.reachable(&[root]).into_iter().filter(|&n| !matches!(g.op(n), Op::Const(_) | Op::Leaf(_))).map(|n| {
                let (id, e) = (self.temp(n), self.expr(g, n));
                quote!(let #id: ::core::primitive::f64 = #e;)
            });
        let value = self.operand(g, root);
        quote!({ #(#lets)* #value })
    }

    /// `let tN: f64 = ...;` for each node, in order. A sine and a cosine paired by the schedule
    /// become one `sin_cos()` call, at the place of whichever of the two comes first.
    pub fn lets(&self, g: &Graph, sched: &Schedule, nodes: &[NodeId]) -> TokenStream {
        self.lets_with(g, sched, nodes, None).0
    }

    /// [`Names::lets`] of a Newton block's evaluation: each `sin_cos` pair is asked of the
    /// solve's cache `near` (a `NearTrig`, one slot per pair, numbered in order), as `call`
    /// says. Also returns the number of slots.
    pub fn lets_near(
        &self,
        g: &Graph,
        sched: &Schedule,
        nodes: &[NodeId],
        near: &Ident,
        call: NearCall,
    ) -> (TokenStream, usize) {
        let method = Ident::new(
            match call {
                NearCall::Seed => "seed",
                NearCall::Rotate => "sin_cos",
            },
            Span::call_site(),
        );
        self.lets_with(g, sched, nodes, Some((near, &method)))
    }

    fn lets_with(
        &self,
        g: &Graph,
        sched: &Schedule,
        nodes: &[NodeId],
        near: Option<(&Ident, &Ident)>,
    ) -> (TokenStream, usize) {
        let mut slots = 0;
        let mut done = HashSet::new();
        let mut out = TokenStream::new();
        for &n in nodes {
            if sched.sums.contains_key(&n) {
                if let Some(sum) = self.angle_sum(g, sched, n, nodes, &mut done, (near, &mut slots)) {
                    out.extend(sum);
                }
                continue;
            }
            if let Some(&pair) = sched.sin_cos.get(&n) {
                if done.insert(pair.0) {
                    out.extend(self.pair(g, pair, near, &mut slots));
                }
                continue;
            }
            let (name, e) = (self.temp(n), self.expr(g, n));
            out.extend(quote!(let #name: ::core::primitive::f64 = #e;));
        }
        (out, slots)
    }

    /// `let (s, c) = ...;` of a sine and cosine `(sn, cn)` of one argument: asked of the sweep's
    /// cache where it has a slot for them, of a Newton block's `near` cache (its next slot), or
    /// libm's.
    fn pair(
        &self,
        g: &Graph,
        (sn, cn): (NodeId, NodeId),
        near: Option<(&Ident, &Ident)>,
        slots: &mut usize,
    ) -> TokenStream {
        let (s, c) = (self.temp(sn), self.temp(cn));
        let arg = match g.op(sn) {
            Op::Func(_, a) => self.operand(g, a),
            _ => self.operand(g, sn),
        };
        match (self.trig_slots.get(&sn), near) {
            (Some(&slot), _) => {
                let slot = Literal::usize_unsuffixed(slot);
                quote!(let (#s, #c): (::core::primitive::f64, ::core::primitive::f64) = __trig.sin_cos(#slot, #arg);)
            }
            (None, Some((near, method))) => {
                let slot = Literal::usize_unsuffixed(*slots);
                *slots += 1;
                quote!(let (#s, #c): (::core::primitive::f64, ::core::primitive::f64) = #near.#method(#slot, #arg);)
            }
            (None, None) => quote!(let (#s, #c): (::core::primitive::f64, ::core::primitive::f64) = #arg.sin_cos();),
        }
    }

    /// The sine and cosine of a sum of angles `a + b` (`n` one of them, see
    /// `graph::angle_sums`): by angle addition (`add_angles`) from `a`'s values and `b`'s, which
    /// are nodes of their own (`b`'s, of the parameters alone, are computed once by a caller's
    /// loop over the inputs, and kept by a sweep's cache). A sine or cosine without its partner
    /// takes its part of the same pair of values. `a`'s and `b`'s pairs are emitted first when
    /// they come later in the same scope (the schedule put them no later), `a`'s by angle
    /// addition too where `a` is such a sum. `None` when `n`'s pair is already emitted.
    fn angle_sum(
        &self,
        g: &Graph,
        sched: &Schedule,
        n: NodeId,
        nodes: &[NodeId],
        done: &mut HashSet<NodeId>,
        (near, slots): (Option<(&Ident, &Ident)>, &mut usize),
    ) -> Option<TokenStream> {
        let sum = sched.sums.get(&n)?;
        let pair = sched.sin_cos.get(&n).copied();
        if pair.is_some_and(|(sn, _)| !done.insert(sn)) {
            return None;
        }
        let mut out = TokenStream::new();
        for (s, c) in [(sum.sin_a, sum.cos_a), (sum.sin_b, sum.cos_b)] {
            // A constant `b`'s values are constants, never in `nodes`; `a` may be a sum itself
            // (`phi + gamma + delta` from `phi + gamma`), whose pair comes from its own parts.
            if !nodes.contains(&s) {
                continue;
            }
            if sched.sums.contains_key(&s) {
                out.extend(self.angle_sum(g, sched, s, nodes, done, (near, &mut *slots)));
            } else if done.insert(s) {
                out.extend(self.pair(g, (s, c), near, slots));
            }
        }
        let [s_a, c_a, s_b, c_b] = [sum.sin_a, sum.cos_a, sum.sin_b, sum.cos_b].map(|m| self.operand(g, m));
        let rt = super::runtime_path::runtime();
        let values = quote!(#rt::add_angles((#s_a, #c_a), (#s_b, #c_b)));
        out.extend(match pair {
            Some((sn, cn)) => {
                let (s, c) = (self.temp(sn), self.temp(cn));
                quote!(let (#s, #c): (::core::primitive::f64, ::core::primitive::f64) = #values;)
            }
            None => {
                let (name, part) = (self.temp(n), Literal::usize_unsuffixed(usize::from(!sum.sine)));
                quote!(let #name: ::core::primitive::f64 = #values.#part;)
            }
        });
        Some(out)
    }
}

/// Names of the temporaries (see the module docs), each name given once. A declared quantity
/// names its node: should two quantities spell the same (`eq a_x` next to `loop a`), the later
/// one stays anonymous. A Jacobian entry or an input derivative that other values are computed
/// from is a term several roles share: it is named by its form where that is short
/// (`a_cos_phi`), so that a residual or an output computed from it does not read as computed
/// from a derivative. So is every other temporary with a short form; the rest are `t` and their
/// node number.
fn roles(model: &Model, plan: &Plan) -> HashMap<NodeId, Ident> {
    let g = &plan.graph;
    // Equation and output names may hold raw identifiers (`r#match.x`).
    let snake = |s: &str| s.replace("r#", "").replace('.', "_");
    let u: Vec<String> = model.unknowns.iter().map(|x| plain(&x.name)).collect();
    let i: Vec<String> = model.inputs.iter().map(|x| plain(&x.name)).collect();
    let p: Vec<String> = model.params.iter().map(|x| plain(&x.name)).collect();
    // With `true`: a derivative's role, which gives way to the node's form when others read it.
    let mut named: Vec<(NodeId, String, bool)> = Vec::new();
    for (e, eq) in model.equations.iter().enumerate() {
        let eqn = snake(&eq.name);
        named.push((plan.residuals[e], format!("r_{eqn}"), false));
        named.extend(plan.jac_full[e].iter().zip(&u).map(|(&n, u)| (n, format!("j_{eqn}_{u}"), true)));
        named.extend(plan.fx_full[e].iter().zip(&i).map(|(&n, i)| (n, format!("fx_{eqn}_{i}"), true)));
    }
    let outs = model.output_names();
    for (o, name) in outs.iter().enumerate() {
        let name = snake(name);
        named.push((plan.outputs[o], format!("out_{name}"), false));
        named.extend(plan.out_d1[o].iter().zip(&i).map(|(&n, i)| (n, format!("dout_{name}_{i}"), false)));
        let second = crate::plan::pairs(i.len()).into_iter().map(|(a, b)| format!("d2out_{name}_{}_{}", i[a], i[b]));
        named.extend(plan.out_d2[o].iter().copied().zip(second).map(|(n, s)| (n, s, false)));
    }
    let forms = forms(g, &u, &i, &p);
    let read = read_by_others(plan);
    let mut taken = HashSet::new();
    let mut roles = HashMap::new();
    let mut give = |n: NodeId, name: &str, roles: &mut HashMap<NodeId, Ident>| {
        let anonymous = matches!(g.op(n), Op::Const(_) | Op::Leaf(_)) || roles.contains_key(&n);
        if !anonymous && syn::parse_str::<Ident>(name).is_ok() && taken.insert(name.to_string()) {
            roles.insert(n, Ident::new(name, Span::call_site()));
        }
    };
    let by_form = |n: NodeId, derivative: bool| derivative && read.contains(&n) && forms[n.index()].is_some();
    for (n, name, derivative) in &named {
        if !by_form(*n, *derivative) {
            give(*n, name, &mut roles);
        }
    }
    // A `let`'s value is named after it, prefixed so that it reads as no name of another kind
    // and no constant of the user's module (`const e: f64`) makes its binding a pattern.
    for (n, name) in &model.lets {
        give(*n, &format!("let_{name}"), &mut roles);
    }
    for (k, form) in forms.iter().enumerate() {
        if let Some(form) = form {
            give(NodeId(k as u32), form, &mut roles);
        }
    }
    // A shared derivative whose form's name was taken keeps its role's.
    for (n, name, _) in &named {
        give(*n, name, &mut roles);
    }
    roles
}

/// Per node, the name of its form where it is short: a function of a declared name
/// (`cos_phi`), a product of such (`a_cos_phi`), a negation (`neg_a`), a square (`a_sq`).
/// `None` for the rest, for names longer than a glance, and for names that begin like a leaf's
/// local or a role's (`q_`, `j_`, ...), for which they could be taken.
fn forms(g: &Graph, u: &[String], i: &[String], p: &[String]) -> Vec<Option<String>> {
    const LONGEST: usize = 24;
    const LOOK_ALIKE: [&str; 11] = ["_", "x_", "q_", "dq", "d2q", "sq_", "sdq", "sd2q", "r_", "j_", "fx_"];
    let mut forms: Vec<Option<String>> = Vec::with_capacity(g.len());
    for k in 0..g.len() {
        // Operands come before the nodes made of them.
        let part = |n: NodeId| if n.index() < k { forms[n.index()].clone() } else { None };
        let form = match g.op(NodeId(k as u32)) {
            Op::Leaf(Leaf::Param(x)) => p.get(x as usize).cloned(),
            Op::Leaf(Leaf::Input(x)) => i.get(x as usize).cloned(),
            Op::Leaf(Leaf::Unknown(x)) => u.get(x as usize).cloned(),
            op => {
                let form = match op {
                    Op::Func(f, a) => part(a).map(|a| format!("{}_{a}", f.method())),
                    Op::Mul(a, b) => part(a).zip(part(b)).map(|(a, b)| format!("{a}_{b}")),
                    Op::Neg(a) => part(a).map(|a| format!("neg_{a}")),
                    Op::Powi(a, 2) => part(a).map(|a| format!("{a}_sq")),
                    _ => None,
                };
                form.filter(|f| f.len() <= LONGEST && !LOOK_ALIKE.iter().any(|l| f.starts_with(l)))
            }
        };
        forms.push(form);
    }
    forms
}

/// The nodes other nodes are computed from, among everything the plan computes.
fn read_by_others(plan: &Plan) -> HashSet<NodeId> {
    let g = &plan.graph;
    let mut roots: Vec<NodeId> = Vec::new();
    let mut add = |rows: &[Vec<NodeId>]| roots.extend(rows.iter().flatten().copied());
    add(&plan.jac_full);
    add(&plan.fx_full);
    add(&plan.out_d1);
    add(&plan.out_d2);
    for bp in &plan.blocks {
        add(&bp.vel);
        add(&bp.acc);
        add(&bp.col_scale);
        add(&bp.lever_floor);
        if let Some(st) = &bp.sens {
            add(&st.q);
            add(&st.v);
            add(&st.a);
        }
    }
    if let Some(st) = &plan.out_sens {
        add(&st.q);
        add(&st.v);
        add(&st.a);
    }
    let singles = [&plan.residuals, &plan.outputs, &plan.guesses, &plan.scale_full, &plan.unit_full, &plan.input_unit];
    roots.extend(singles.into_iter().flatten().copied());
    for bp in &plan.blocks {
        roots.extend(bp.scale.iter().chain(&bp.unit).copied());
        roots.extend(bp.solve.linear_rhs().unwrap_or_default());
        if let Some(rec) = bp.solve.closed_form() {
            roots.extend(rec.form.coefficients());
        }
    }
    g.reachable(&roots).into_iter().flat_map(|n| g.op(n).operands().collect::<Vec<_>>()).collect()
}

fn binary(a: TokenStream, op: TokenStream, b: TokenStream) -> TokenStream {
    quote!(#a #op #b)
}

fn method(receiver: TokenStream, name: &str, arg: Option<TokenStream>) -> TokenStream {
    let m = Ident::new(name, Span::call_site());
    quote!(#receiver.#m(#arg))
}

/// An `f64` literal; negative values are parenthesised so they can be method receivers.
pub fn float(v: f64) -> TokenStream {
    if v.is_nan() {
        return quote!(::core::primitive::f64::NAN);
    }
    if v.is_infinite() {
        return if v > 0.0 {
            quote!(::core::primitive::f64::INFINITY)
        } else {
            quote!(::core::primitive::f64::NEG_INFINITY)
        };
    }
    let lit = Literal::f64_suffixed(v.abs());
    if v.is_sign_negative() && v != 0.0 { quote!((-#lit)) } else { quote!(#lit) }
}

/// A finite `f64` literal as a function argument: negative values without parentheses.
pub fn float_arg(v: f64) -> TokenStream {
    let lit = Literal::f64_suffixed(v.abs());
    if v.is_sign_negative() && v != 0.0 { quote!(-#lit) } else { quote!(#lit) }
}
