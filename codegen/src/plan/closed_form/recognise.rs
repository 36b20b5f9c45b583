//! Recognition of closed-form blocks on the expression graph.
//!
//! A block is rewritten with the cosine and sine of each candidate angle `q` replaced by two
//! placeholder leaves `C` and `S`: every `cos(±q + k)` and `sin(±q + k)` whose argument has the
//! derivative `±1` in `q` (proven symbolically: the graph's derivative is the constant) becomes
//! the rotation `C cos k ∓ S sin k`, ... with `k = arg(q = 0)`. If `q` is left anywhere else (a
//! bare `q`, `sin(2 q)`, `sin(q1 - q2)`), the block is not a closed form. The rewritten
//! residuals are then shown affine in the placeholders (and in a slider) by their symbolic
//! first derivatives, which must be free of the placeholders and of the block's unknowns, so
//! the coefficients read off are exact: a pattern is accepted only when it holds identically,
//! never by the look of the source. Anything else keeps Newton.

use crate::graph::dag::{Func, Graph, Leaf, NodeId, Op};
use crate::structure::Block;
use std::collections::HashMap;

/// The closed form of one block, with the graph nodes of its coefficients. Rows are the
/// block's equations in order; `(cos q, sin q)` is the column of an angle.
#[derive(Clone, Debug, PartialEq)]
pub enum ClosedForm {
    /// One angle in one equation `a cos q + b sin q = c`.
    AngleEquation { angle: usize, a: NodeId, b: NodeId, c: NodeId },
    /// Two angles of one loop: `m[0] (cos q0, sin q0) + m[1] (cos q1, sin q1) + e = 0`, each
    /// `m[i]` a scaled rotation or (`reflect[i]`) a scaled reflection, i.e. a vector of constant
    /// length turning with `q_i`: an RRR dyad, solved by circle intersection.
    Dyad { angles: [usize; 2], m: [[[NodeId; 2]; 2]; 2], reflect: [bool; 2], e: [NodeId; 2] },
    /// A length and its angle: `s w(q) + e = 0` with `w = w (cos q, sin q)` (rows).
    PolarLength { angle: usize, length: usize, w: [[NodeId; 2]; 2], e: [NodeId; 2] },
    /// An angle and a slider: `m (cos q, sin q) + d s + e = 0`.
    AngleSlider { angle: usize, slider: usize, m: [[NodeId; 2]; 2], d: [NodeId; 2], e: [NodeId; 2] },
}

impl ClosedForm {
    /// How the block is solved, for `DECOMPOSITION`.
    pub fn describe(&self) -> &'static str {
        match self {
            ClosedForm::AngleEquation { .. } => "closed form, angle equation",
            ClosedForm::Dyad { .. } => "closed form, RRR dyad",
            ClosedForm::PolarLength { .. } => "closed form, length and angle",
            ClosedForm::AngleSlider { .. } => "closed form, angle and slider",
        }
    }

    /// The graph nodes the solve reads (all free of the block's unknowns).
    pub fn coefficients(&self) -> Vec<NodeId> {
        match self {
            ClosedForm::AngleEquation { a, b, c, .. } => vec![*a, *b, *c],
            ClosedForm::Dyad { m, e, .. } => m.iter().flatten().flatten().chain(e).copied().collect(),
            ClosedForm::PolarLength { w, e, .. } => w.iter().flatten().chain(e).copied().collect(),
            ClosedForm::AngleSlider { m, d, e, .. } => m.iter().flatten().chain(d).chain(e).copied().collect(),
        }
    }

    /// The angle unknowns, in the order the solve produces their cosines and sines.
    pub fn angles(&self) -> Vec<usize> {
        match self {
            ClosedForm::AngleEquation { angle, .. }
            | ClosedForm::PolarLength { angle, .. }
            | ClosedForm::AngleSlider { angle, .. } => vec![*angle],
            ClosedForm::Dyad { angles, .. } => angles.to_vec(),
        }
    }

    /// Per angle, the nodes `[x, y]` of its lever vector, whose length is the magnitude of the
    /// angle's Jacobian column: what a position-only solve tests against the angle's lever
    /// floor (a lever that vanishes leaves the angle undetermined).
    pub fn levers(&self) -> Vec<(usize, [NodeId; 2])> {
        match self {
            ClosedForm::AngleEquation { angle, a, b, .. } => vec![(*angle, [*a, *b])],
            ClosedForm::Dyad { angles, m, .. } => (0..2).map(|i| (angles[i], [m[i][0][0], m[i][1][0]])).collect(),
            // `s w(q) = -e`: the lever `s` is as long as the offset (`w` a rotation).
            ClosedForm::PolarLength { angle, e, .. } => vec![(*angle, *e)],
            ClosedForm::AngleSlider { angle, m, .. } => vec![(*angle, [m[0][0], m[1][0]])],
        }
    }

    /// A dyad's centres' offset `e` and its two links' vectors `[x, y]` (the first column of
    /// each `m[i]`, as long as the link): centres that coincide leave the dyad free to turn
    /// about them. `None` for the other forms.
    pub fn centres(&self) -> Option<([NodeId; 2], [[NodeId; 2]; 2])> {
        match self {
            ClosedForm::Dyad { m, e, .. } => Some((*e, [[m[0][0][0], m[0][1][0]], [m[1][0][0], m[1][1][0]]])),
            _ => None,
        }
    }

    /// The unknown that is not an angle: a length or a slider, solved after its angle.
    pub fn other_unknown(&self) -> Option<usize> {
        match self {
            ClosedForm::PolarLength { length, .. } => Some(*length),
            ClosedForm::AngleSlider { slider, .. } => Some(*slider),
            ClosedForm::AngleEquation { .. } | ClosedForm::Dyad { .. } => None,
        }
    }

    /// The block's unknowns in the order the solve gives them: the angles (in
    /// [`ClosedForm::angles`] order), then the length or slider.
    pub fn solve_order(&self) -> Vec<usize> {
        self.angles().into_iter().chain(self.other_unknown()).collect()
    }
}

/// A recognised block: its form and, per angle (in [`ClosedForm::angles`] order), the graph's
/// `sin(q)` and `cos(q)` nodes, which the solve defines from its solution instead of calling
/// `sin_cos` on the angle.
#[derive(Clone, Debug, PartialEq)]
pub struct Recognised {
    /// The block's closed form.
    pub form: ClosedForm,
    /// Per angle: the graph's `[sin q, cos q]` nodes, defined by the solve.
    pub sin_cos: Vec<[NodeId; 2]>,
}

/// Placeholder leaf `k` (cosines and sines of the angles while a block is rewritten):
/// parameter indices no declaration reaches. They never reach generated code: every
/// coefficient is verified free of them.
fn placeholder(k: u16) -> Leaf {
    Leaf::Param(u16::MAX - k)
}

/// The closed form of a nonlinear `block` with residuals `f` (its equations in order), if it
/// has one. Adds nodes to the graph (coefficients, derivatives), never changes existing ones.
pub fn recognise(g: &mut Graph, block: &Block, f: &[NodeId], n_params: usize) -> Option<Recognised> {
    if n_params + 8 >= u16::MAX as usize {
        return None;
    }
    let us = &block.unknowns;
    let form = match (us.len(), f.len()) {
        (1, 1) => angle_equation(g, us[0], f[0]),
        (2, 2) => dyad(g, us, f)
            .or_else(|| angle_and_other(g, us[0], us[1], f))
            .or_else(|| angle_and_other(g, us[1], us[0], f)),
        _ => None,
    }?;
    let sin_cos = form
        .angles()
        .into_iter()
        .map(|u| {
            let q = g.leaf(Leaf::Unknown(u as u16));
            [g.func(Func::Sin, q), g.func(Func::Cos, q)]
        })
        .collect();
    Some(Recognised { form, sin_cos })
}

/// An angle being rewritten: its unknown and the placeholders of its cosine and sine.
#[derive(Clone, Copy)]
struct Angle {
    unknown: usize,
    cos: Leaf,
    sin: Leaf,
}

fn angle(k: u16, unknown: usize) -> Angle {
    Angle { unknown, cos: placeholder(2 * k), sin: placeholder(2 * k + 1) }
}

fn partial(g: &mut Graph, root: NodeId, leaf: Leaf) -> NodeId {
    let one = g.one();
    g.tangent(&[root], &|l| (l == leaf).then_some(one))[0]
}

fn free_of(g: &Graph, node: NodeId, leaves: &[Leaf]) -> bool {
    !g.leaves_of(&[node]).iter().any(|l| leaves.contains(l))
}

fn set_zero(g: &mut Graph, root: NodeId, leaves: &[Leaf]) -> NodeId {
    let zero = g.zero();
    g.substitute(&[root], &|l| leaves.contains(&l).then_some(zero))[0]
}

/// `roots` with every `sin`/`cos` of `±q + k` rewritten over the placeholders of `angles`;
/// `None` when an angle occurs in any other way or an argument involves a block unknown
/// (`block`) beyond its one angle.
fn rewrite(g: &mut Graph, roots: &[NodeId], angles: &[Angle], block: &[usize]) -> Option<Vec<NodeId>> {
    let is_angle = |u: u16| angles.iter().any(|a| a.unknown == u as usize);
    let mut memo: HashMap<NodeId, Option<NodeId>> = HashMap::new();
    for n in g.reachable(roots) {
        let new = match g.op(n) {
            Op::Leaf(Leaf::Unknown(u)) if is_angle(u) => None,
            Op::Const(_) | Op::Leaf(_) => Some(n),
            Op::Func(f @ (Func::Sin | Func::Cos), arg)
                if g.leaves_of(&[arg]).iter().any(|l| matches!(l, Leaf::Unknown(u) if is_angle(*u))) =>
            {
                trig(g, f == Func::Sin, arg, angles, block)
            }
            // A `min`/`max` or a `floor` of the block's unknowns is no closed form: kept as it
            // is only when it is free of them (a coefficient, e.g. a cam law of the input
            // reduced by whole turns).
            Op::Select(..) | Op::Func(Func::Floor, _) => {
                let unknowns = g.leaves_of(&[n]);
                let moves = unknowns
                    .iter()
                    .any(|l| matches!(l, Leaf::Unknown(u) if is_angle(*u) || block.contains(&(*u as usize))));
                if moves { None } else { Some(n) }
            }
            op => {
                let m: Vec<Option<NodeId>> = op.operands().map(|o| memo[&o]).collect();
                if m.iter().any(Option::is_none) {
                    None
                } else {
                    let x = |i: usize| m[i].unwrap_or(n);
                    Some(match op {
                        Op::Add(..) => g.add(x(0), x(1)),
                        Op::Sub(..) => g.sub(x(0), x(1)),
                        Op::Mul(..) => g.mul(x(0), x(1)),
                        Op::Div(..) => g.div(x(0), x(1)),
                        Op::Neg(_) => g.neg(x(0)),
                        Op::Powi(_, k) => g.powi(x(0), k),
                        Op::Powf(..) => g.powf(x(0), x(1)),
                        Op::Func(f, _) => g.func(f, x(0)),
                        Op::Atan2(..) => g.atan2(x(0), x(1)),
                        Op::Const(_) | Op::Leaf(_) | Op::Select(..) => n,
                    })
                }
            }
        };
        memo.insert(n, new);
    }
    roots.iter().map(|r| memo[r]).collect()
}

/// `sin(arg)` (`sine`) or `cos(arg)` over the placeholders, for `arg = ±q + k` with `k` free
/// of the block's unknowns.
fn trig(g: &mut Graph, sine: bool, arg: NodeId, angles: &[Angle], block: &[usize]) -> Option<NodeId> {
    let mut found: Option<(Angle, f64)> = None;
    for a in angles {
        let d = partial(g, arg, Leaf::Unknown(a.unknown as u16));
        match g.as_const(d) {
            Some(0.0) => {}
            Some(s) if (s == 1.0 || s == -1.0) && found.is_none() => found = Some((*a, s)),
            _ => return None,
        }
    }
    let (a, sign) = found?;
    let k = set_zero(g, arg, &[Leaf::Unknown(a.unknown as u16)]);
    let unknowns: Vec<Leaf> = block.iter().map(|&u| Leaf::Unknown(u as u16)).collect();
    if !free_of(g, k, &unknowns) {
        return None;
    }
    let (c, s) = (g.leaf(a.cos), g.leaf(a.sin));
    // sin(±q) = ±S, cos(±q) = C; then the rotation by k.
    let s = if sign < 0.0 { g.neg(s) } else { s };
    if g.is_zero(k) {
        return Some(if sine { s } else { c });
    }
    let (sk, ck) = (g.func(Func::Sin, k), g.func(Func::Cos, k));
    let (c_ck, s_sk, s_ck, c_sk) = (g.mul(c, ck), g.mul(s, sk), g.mul(s, ck), g.mul(c, sk));
    Some(if sine { g.add(s_ck, c_sk) } else { g.sub(c_ck, s_sk) })
}

/// The coefficients of the placeholders `vars` in `row`, when `row` is affine in them with
/// coefficients free of `vars` and of `forbidden`; with the constant term.
fn affine(g: &mut Graph, row: NodeId, vars: &[Leaf], forbidden: &[Leaf]) -> Option<(Vec<NodeId>, NodeId)> {
    let all: Vec<Leaf> = vars.iter().chain(forbidden).copied().collect();
    let mut coef = Vec::new();
    for &v in vars {
        let d = partial(g, row, v);
        if !free_of(g, d, &all) {
            return None;
        }
        coef.push(d);
    }
    let e = set_zero(g, row, vars);
    free_of(g, e, &all).then_some((coef, e))
}

fn angle_equation(g: &mut Graph, u: usize, f: NodeId) -> Option<ClosedForm> {
    let a = angle(0, u);
    let r = rewrite(g, &[f], &[a], &[u])?[0];
    let (coef, e) = affine(g, r, &[a.cos, a.sin], &[Leaf::Unknown(u as u16)])?;
    if g.is_zero(coef[0]) && g.is_zero(coef[1]) {
        return None;
    }
    let c = g.neg(e);
    Some(ClosedForm::AngleEquation { angle: u, a: coef[0], b: coef[1], c })
}

/// `Some(reflect)` when the 2x2 `m` is structurally a scaled rotation (`false`) or reflection
/// (`true`), not zero.
fn orthogonal(g: &mut Graph, m: [[NodeId; 2]; 2]) -> Option<bool> {
    if g.is_zero(m[0][0]) && g.is_zero(m[1][0]) {
        return None;
    }
    let (n01, n11) = (g.neg(m[0][1]), g.neg(m[1][1]));
    if m[0][0] == m[1][1] && n01 == m[1][0] {
        Some(false)
    } else if m[0][0] == n11 && m[0][1] == m[1][0] {
        Some(true)
    } else {
        None
    }
}

fn dyad(g: &mut Graph, us: &[usize], f: &[NodeId]) -> Option<ClosedForm> {
    let angles = [angle(0, us[0]), angle(1, us[1])];
    let rows = rewrite(g, f, &angles, us)?;
    let vars = [angles[0].cos, angles[0].sin, angles[1].cos, angles[1].sin];
    let forbidden: Vec<Leaf> = us.iter().map(|&u| Leaf::Unknown(u as u16)).collect();
    let (c0, e0) = affine(g, rows[0], &vars, &forbidden)?;
    let (c1, e1) = affine(g, rows[1], &vars, &forbidden)?;
    let m0 = [[c0[0], c0[1]], [c1[0], c1[1]]];
    let m1 = [[c0[2], c0[3]], [c1[2], c1[3]]];
    let reflect = [orthogonal(g, m0)?, orthogonal(g, m1)?];
    Some(ClosedForm::Dyad { angles: [us[0], us[1]], m: [m0, m1], reflect, e: [e0, e1] })
}

/// An angle `q` and another unknown `s` (a slider or a length) coupled in two equations.
fn angle_and_other(g: &mut Graph, q: usize, s: usize, f: &[NodeId]) -> Option<ClosedForm> {
    let a = angle(0, q);
    let rows = rewrite(g, f, &[a], &[q, s])?;
    let sl = Leaf::Unknown(s as u16);
    let vars = [a.cos, a.sin, sl];
    let slider = (|| {
        let (c0, e0) = affine(g, rows[0], &vars, &[])?;
        let (c1, e1) = affine(g, rows[1], &vars, &[])?;
        if g.is_zero(c0[2]) && g.is_zero(c1[2]) {
            return None;
        }
        let m = [[c0[0], c0[1]], [c1[0], c1[1]]];
        Some(ClosedForm::AngleSlider { angle: q, slider: s, m, d: [c0[2], c1[2]], e: [e0, e1] })
    })();
    slider.or_else(|| polar(g, q, s, &rows, a))
}

/// `row = s (A cos q + B sin q) + e` for both rows, with `A`, `B`, `e` free of `q` and `s`.
fn polar(g: &mut Graph, q: usize, s: usize, rows: &[NodeId], a: Angle) -> Option<ClosedForm> {
    let sl = Leaf::Unknown(s as u16);
    let all = [a.cos, a.sin, sl];
    let mut w = [[g.zero(); 2]; 2];
    let mut e = [g.zero(); 2];
    for (r, &row) in rows.iter().enumerate() {
        let ds = partial(g, row, sl);
        let (coef, d0) = affine(g, ds, &[a.cos, a.sin], &[sl])?;
        let e_r = set_zero(g, row, &[sl]);
        if !g.is_zero(d0) || !free_of(g, e_r, &all) {
            return None;
        }
        w[r] = [coef[0], coef[1]];
        e[r] = e_r;
    }
    if w.iter().flatten().all(|&n| g.is_zero(n)) {
        return None;
    }
    Some(ClosedForm::PolarLength { angle: q, length: s, w, e })
}
