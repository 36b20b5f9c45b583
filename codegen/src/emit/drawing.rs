//! The default drawing's description (`Mechanism::DRAWING`): the chain of points of every loop
//! (the partial sums of its vectors), each vector classified, joints merged where their sums
//! are the same, the rigid plates, and notes where the declaration leaves the picture
//! ambiguous. Emitted as one string constant in the runtime's text format
//! (`kinloop_runtime::drawing`): a table the runtime reads and a tape it evaluates, which keeps
//! the generated code one line long.
//!
//! Joints are merged symbolically only: two partial sums are one joint when they add the same
//! vectors (hash-consed nodes, so the same expression wherever written) the same number of
//! times, in any order, and a loop's two ends are one joint. Points that coincide only at
//! run time stay two joints.

use crate::graph::dag::{Func, Graph, Leaf, NodeId, Op};
use crate::semantics::drawing::{DrawingModel, Term};
use crate::semantics::dynamics::AngleModel;
use crate::semantics::model::Model;
use proc_macro2::{Literal, TokenStream};
use quote::quote;
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write;

/// `const DRAWING: &'static str = "...";` of the `Mechanism` implementation.
pub fn constant(model: &Model) -> TokenStream {
    let text = Literal::string(&description(model));
    quote!(const DRAWING: &'static ::core::primitive::str = #text;)
}

/// An angle's turning part: the node it turns with, and the direction.
type Turn = (bool, NodeId);

/// How a vector is drawn (see the runtime's `SegmentKind`).
#[derive(Clone, Copy, PartialEq)]
enum Class {
    Ground,
    Link(Turn),
    /// A prismatic pair: on a fixed guide (`None`), or on a guide turning with this turn.
    Slider(Option<Turn>),
    Construction,
}

/// The direction of a vector, when it has one: `theta`, or `pi/2 - theta` for a vector written
/// `(l sin theta, l cos theta)`.
#[derive(Clone, Copy)]
enum Angle {
    Of(NodeId, bool),
    Const(f64),
}

struct Classified {
    class: Class,
    angle: Option<Angle>,
}

/// The graph with, for every node, whether it depends on an input or an unknown (worked out
/// once, in one pass: node ids are a topological order).
struct Moving<'a> {
    g: &'a Graph,
    moving: Vec<bool>,
}

impl<'a> Moving<'a> {
    fn new(g: &'a Graph) -> Moving<'a> {
        let mut moving = vec![false; g.len()];
        for i in 0..g.len() {
            let op = g.op(NodeId(i as u32));
            moving[i] = match op {
                Op::Leaf(l) => matches!(l, Leaf::Input(_) | Leaf::Unknown(_)),
                _ => op.operands().any(|a| moving[a.index()]),
            };
        }
        Moving { g, moving }
    }

    fn moves(&self, n: NodeId) -> bool {
        self.moving[n.index()]
    }
}

/// `l * f(theta)` (or `f(theta)`) with `f` a sine or cosine: `(l, f, theta)`.
fn trig_factor(g: &Graph, n: NodeId) -> Option<(Option<NodeId>, Func, NodeId)> {
    let trig = |m: NodeId| match g.op(m) {
        Op::Func(f @ (Func::Sin | Func::Cos), t) => Some((f, t)),
        _ => None,
    };
    if let Some((f, t)) = trig(n) {
        return Some((None, f, t));
    }
    if let Op::Mul(a, b) = g.op(n) {
        if let Some((f, t)) = trig(b) {
            return Some((Some(a), f, t));
        }
        if let Some((f, t)) = trig(a) {
            return Some((Some(b), f, t));
        }
    }
    None
}

/// The part of `theta` that turns: constant summands and negations stripped.
fn turn(m: &Moving, mut n: NodeId, mut positive: bool) -> Turn {
    loop {
        n = match m.g.op(n) {
            Op::Add(a, b) if !m.moves(b) => a,
            Op::Add(a, b) if !m.moves(a) => b,
            Op::Sub(a, b) if !m.moves(b) => a,
            Op::Sub(a, b) if !m.moves(a) => {
                positive = !positive;
                b
            }
            Op::Neg(a) => {
                positive = !positive;
                a
            }
            _ => return (positive, n),
        }
    }
}

fn classify(m: &Moving, t: &Term) -> Classified {
    let (g, moves) = (m.g, |n| m.moves(n));
    let (mx, my) = (moves(t.x), moves(t.y));
    if !mx && !my {
        return Classified { class: Class::Ground, angle: None };
    }
    if let (Some((lx, fx, tx)), Some((ly, fy, ty))) = (trig_factor(g, t.x), trig_factor(g, t.y))
        && lx == ly
        && tx == ty
        && fx != fy
    {
        let swapped = fx == Func::Sin;
        let length_moves = lx.is_some_and(moves);
        let class = match (length_moves, moves(tx)) {
            (false, _) => Class::Link(turn(m, tx, !swapped)),
            (true, true) => Class::Slider(Some(turn(m, tx, !swapped))),
            (true, false) => Class::Slider(None),
        };
        return Classified { class, angle: Some(Angle::Of(tx, swapped)) };
    }
    match (mx, my) {
        (true, false) => Classified { class: Class::Slider(None), angle: Some(Angle::Const(0.0)) },
        (false, true) => {
            Classified { class: Class::Slider(None), angle: Some(Angle::Const(std::f64::consts::FRAC_PI_2)) }
        }
        _ => Classified { class: Class::Construction, angle: None },
    }
}

/// A partial sum: how often each vector is added (cancelled ones removed).
type Key = Vec<((NodeId, NodeId), i32)>;

/// A sum of vectors, each added (`1.0`) or subtracted (`-1.0`) on top of its own sign.
type Sum<'a> = Vec<(f64, &'a Term)>;

fn key(terms: &[(f64, &Term)]) -> Key {
    let mut m: BTreeMap<(NodeId, NodeId), i32> = BTreeMap::new();
    for (s, t) in terms {
        *m.entry((t.x, t.y)).or_default() += if s * t.sign > 0.0 { 1 } else { -1 };
    }
    m.into_iter().filter(|&(_, c)| c != 0).collect()
}

/// `terms` added to `base`.
fn plus<'a>(base: &Sum<'a>, terms: &'a [Term]) -> Sum<'a> {
    base.iter().copied().chain(terms.iter().map(|t| (1.0, t))).collect()
}

/// The joints under construction: one per distinct partial sum, merged into classes.
struct Points<'a> {
    keys: HashMap<Key, usize>,
    /// Generated name, the sum, and the names of the points declared as this sum.
    info: Vec<(String, Sum<'a>, Vec<String>)>,
    parent: Vec<usize>,
}

impl<'a> Points<'a> {
    fn get(&mut self, sum: Sum<'a>, name: String) -> usize {
        let k = key(&sum);
        if let Some(&i) = self.keys.get(&k) {
            return i;
        }
        let i = self.info.len();
        self.keys.insert(k, i);
        self.info.push((name, sum, Vec::new()));
        self.parent.push(i);
        i
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        let (lo, hi) = (a.min(b), a.max(b));
        self.parent[hi] = lo;
    }
}

/// The tape: each graph node once, operands first, as the runtime's entries.
#[derive(Default)]
struct Tape {
    entries: Vec<String>,
    memo: HashMap<NodeId, usize>,
}

impl Tape {
    fn push(&mut self, e: String) -> usize {
        self.entries.push(e);
        self.entries.len() - 1
    }

    fn constant(&mut self, v: f64) -> usize {
        self.push(format!("c:{v:?}"))
    }

    fn node(&mut self, g: &Graph, root: NodeId) -> usize {
        for n in g.reachable(&[root]) {
            if self.memo.contains_key(&n) {
                continue;
            }
            let m = |a: NodeId| self.memo[&a];
            let e = match g.op(n) {
                Op::Const(bits) => format!("c:{:?}", f64::from_bits(bits)),
                Op::Leaf(Leaf::Param(i)) => format!("p:{i}"),
                Op::Leaf(Leaf::Input(i)) => format!("x:{i}"),
                Op::Leaf(Leaf::Unknown(i)) => format!("q:{i}"),
                // Analogs and sensitivities never occur in a declaration's terms.
                Op::Leaf(_) => "c:NaN".to_string(),
                Op::Add(a, b) => format!("add:{},{}", m(a), m(b)),
                Op::Sub(a, b) => format!("sub:{},{}", m(a), m(b)),
                Op::Mul(a, b) => format!("mul:{},{}", m(a), m(b)),
                Op::Div(a, b) => format!("div:{},{}", m(a), m(b)),
                Op::Neg(a) => format!("neg:{}", m(a)),
                Op::Powi(a, k) => format!("powi:{},{k}", m(a)),
                Op::Powf(a, b) => format!("powf:{},{}", m(a), m(b)),
                Op::Func(f, a) => format!("{}:{}", f.method(), m(a)),
                Op::Atan2(a, b) => format!("atan2:{},{}", m(a), m(b)),
                Op::Select(a, b, x, y) => format!("select:{},{},{},{}", m(a), m(b), m(x), m(y)),
            };
            let i = self.push(e);
            self.memo.insert(n, i);
        }
        self.memo[&root]
    }

    /// The entries of a sum of terms' coordinates (`x` or `y`).
    fn sum(&mut self, g: &Graph, terms: &Sum, y: bool) -> usize {
        let mut acc: Option<usize> = None;
        for (s, t) in terms {
            let v = self.node(g, if y { t.y } else { t.x });
            acc = Some(match (acc, s * t.sign > 0.0) {
                (None, true) => v,
                (None, false) => self.push(format!("neg:{v}")),
                (Some(a), true) => self.push(format!("add:{a},{v}")),
                (Some(a), false) => self.push(format!("sub:{a},{v}")),
            });
        }
        acc.unwrap_or_else(|| self.constant(0.0))
    }

    /// The entry of a vector's direction (a half turn more when it is subtracted).
    fn angle(&mut self, g: &Graph, a: Angle, sign: f64) -> usize {
        let base = match a {
            Angle::Const(v) => self.constant(v),
            Angle::Of(t, false) => self.node(g, t),
            Angle::Of(t, true) => {
                let (q, t) = (self.constant(std::f64::consts::FRAC_PI_2), self.node(g, t));
                self.push(format!("sub:{q},{t}"))
            }
        };
        if sign > 0.0 {
            return base;
        }
        let pi = self.constant(std::f64::consts::PI);
        self.push(format!("add:{base},{pi}"))
    }
}

/// One step of a chain: from joint, to joint, the term and its loop.
struct Step<'a> {
    from: usize,
    to: usize,
    term: &'a Term,
    label: String,
}

/// Where a loop's chains start. Loops are drawn in one frame: each from the origin, unless a
/// link of the loop is a link of an earlier loop, whose start then fixes this loop's (a loop
/// written from its own frame pivot, as a second loop often is).
fn start<'a>(pts: &Points<'a>, mv: &Moving, steps: &[Step<'a>], sides: [&'a [Term]; 2]) -> Sum<'a> {
    for terms in sides {
        for (i, t) in terms.iter().enumerate() {
            if !matches!(classify(mv, t).class, Class::Link(_)) {
                continue;
            }
            let Some(prev) = steps.iter().find(|s| (s.term.x, s.term.y) == (t.x, t.y)) else { continue };
            let same = (prev.term.sign > 0.0) == (t.sign > 0.0);
            let at = &pts.info[if same { prev.from } else { prev.to }].1;
            // at - (the terms before t)
            return at.iter().copied().chain(terms[..i].iter().map(|t| (-1.0, t))).collect();
        }
    }
    Vec::new()
}

/// The description in the runtime's text format.
pub fn description(model: &Model) -> String {
    let dm: &DrawingModel = &model.drawing;
    let g = &dm.graph;
    let mv = Moving::new(g);
    let mut notes: Vec<String> = Vec::new();
    let mut pts = Points { keys: HashMap::new(), info: Vec::new(), parent: Vec::new() };
    // The origin is the first joint, whether or not a loop starts there.
    // (A name no identifier takes where a point is called `origin`.)
    let origin = if dm.points.iter().any(|(n, _)| n == "origin") { "(origin)" } else { "origin" };
    pts.get(Vec::new(), origin.to_string());
    let mut steps: Vec<Step> = Vec::new();
    for l in &dm.loops {
        let base = start(&pts, &mv, &steps, [&l.left, &l.right]);
        let first = pts.get(base.clone(), format!("{}.start", l.name));
        let mut ends = [first; 2];
        for (side, (tag, terms)) in [("l", &l.left), ("r", &l.right)].into_iter().enumerate() {
            let mut prev = first;
            for k in 0..terms.len() {
                let at = pts.get(plus(&base, &terms[..=k]), format!("{}.{tag}{}", l.name, k + 1));
                let label = format!("{}: {}{}", l.name, if terms[k].sign > 0.0 { "" } else { "-" }, terms[k].text);
                steps.push(Step { from: prev, to: at, term: &terms[k], label });
                prev = at;
            }
            ends[side] = prev;
        }
        pts.union(ends[0], ends[1]);
    }
    if dm.loops.is_empty() {
        notes.push("the declaration has no loop: it describes no chain of points to draw".to_string());
    }
    for what in &dm.skipped {
        notes.push(format!("{what} has too many vectors to describe: the drawing leaves it out"));
    }
    for e in &dm.equations {
        notes.push(format!("equation `{e}` is a scalar equation: the drawing does not show it"));
    }
    // Named points: the joint of their sum, and where they hang from (the longest prefix of
    // their terms that is a joint, and the turn of the rest, when all of it is links turning
    // alike).
    let mut hangs: Vec<(usize, Option<(usize, Turn)>)> = Vec::new();
    for (name, terms) in &dm.points {
        let none = Vec::new();
        let base = (0..terms.len()).rev().find_map(|k| pts.keys.get(&key(&plus(&none, &terms[..k]))).map(|&b| (b, k)));
        let at = pts.get(plus(&none, terms), name.clone());
        pts.info[at].2.push(name.clone());
        let turn = base.and_then(|(b, k)| {
            let turns: Vec<Class> = terms[k..].iter().map(|t| classify(&mv, t).class).collect();
            match turns.first() {
                Some(&Class::Link(t)) if turns.iter().all(|c| *c == Class::Link(t)) => Some((b, t)),
                _ => None,
            }
        });
        hangs.push((at, turn));
    }
    // Joint classes, in order of their first member.
    let n = pts.info.len();
    let roots: Vec<usize> = (0..n).map(|i| pts.find(i)).collect();
    let mut index = vec![usize::MAX; n];
    let mut members: Vec<Vec<usize>> = Vec::new();
    for i in 0..n {
        if roots[i] == i {
            index[i] = members.len();
            members.push(Vec::new());
        }
        members[index[roots[i]]].push(i);
    }
    let joint = |i: usize| index[roots[i]];
    // Each joint's coordinates: a member's sum of constant vectors where there is one (a
    // frame pivot), else its first member's; then through constant vectors, from a fixed
    // joint to the next.
    let is_fixed = |sum: &Sum| sum.iter().all(|(_, t)| !mv.moves(t.x) && !mv.moves(t.y));
    let mut coords: Vec<(Sum, bool)> = members
        .iter()
        .map(|m| match m.iter().find(|&&i| is_fixed(&pts.info[i].1)) {
            Some(&i) => (pts.info[i].1.clone(), true),
            None => (pts.info[m[0]].1.clone(), false),
        })
        .collect();
    let classes: Vec<Classified> = steps.iter().map(|s| classify(&mv, s.term)).collect();
    loop {
        let mut changed = false;
        for (s, c) in steps.iter().zip(&classes) {
            let (a, b) = (joint(s.from), joint(s.to));
            if c.class != Class::Ground || coords[a].1 == coords[b].1 {
                continue;
            }
            let (from, to, sign) = if coords[a].1 { (a, b, 1.0) } else { (b, a, -1.0) };
            let mut sum = coords[from].0.clone();
            sum.push((sign, s.term));
            coords[to] = (sum, true);
            changed = true;
        }
        if !changed {
            break;
        }
    }
    let mut tape = Tape::default();
    let mut joint_lines = Vec::new();
    for (m, (sum, ground)) in members.iter().zip(&coords) {
        let all: Vec<&String> = m.iter().flat_map(|&i| &pts.info[i].2).collect();
        let named = all.first().map(|n| n.to_string());
        if all.len() > 1 {
            let others: Vec<String> = all[1..].iter().map(|n| format!("`{n}`")).collect();
            notes.push(format!(
                "points `{}` and {} are one joint (the same sum of vectors): drawn once, named `{}`",
                all[0],
                others.join(", "),
                all[0]
            ));
        }
        let (x, y) = (tape.sum(g, sum, false), tape.sum(g, sum, true));
        let name = named.clone().unwrap_or_else(|| pts.info[m[0]].0.clone());
        let kind = if *ground { "g" } else { "m" };
        joint_lines.push(format!("j {name} {kind} {} {x} {y}\n", if named.is_some() { "n" } else { "-" }));
    }
    // Segments, each once; links grouped into plates by their turn and shared joints.
    let mut seen: HashMap<(usize, usize, NodeId, NodeId, bool), ()> = HashMap::new();
    let mut seg_lines = Vec::new();
    let mut links: Vec<(Turn, usize, usize)> = Vec::new();
    // Turning guides: their turn, the joint they turn about, their segment.
    let mut guides: Vec<(Turn, usize, usize)> = Vec::new();
    for (s, c) in steps.iter().zip(&classes) {
        let (a, b) = (joint(s.from), joint(s.to));
        if a == b || seen.insert((a, b, s.term.x, s.term.y, s.term.sign > 0.0), ()).is_some() {
            continue;
        }
        let kind = match c.class {
            Class::Ground => "ground",
            Class::Link(t) => {
                links.push((t, a, b));
                "link"
            }
            Class::Slider(None) => "slider-fixed",
            Class::Slider(Some(t)) => {
                guides.push((t, a, seg_lines.len()));
                "slider-turning"
            }
            Class::Construction => {
                notes.push(format!(
                    "`{}` is neither a link (`length @ angle` of constant length), a slider (one moving \
                     coordinate, or a varying length) nor fixed: drawn as a construction line",
                    s.label
                ));
                "construction"
            }
        };
        let angle = c.angle.map_or("-".to_string(), |an| tape.angle(g, an, s.term.sign).to_string());
        seg_lines.push(format!("s {a} {b} {kind} {angle} {}\n", s.label));
    }
    let mut plates = plates(&links);
    for (p, (at, hang)) in dm.points.iter().zip(&hangs) {
        let at = joint(*at);
        let home = hang.and_then(|(b, t)| {
            let b = joint(b);
            plates.iter().position(|(pt, js)| *pt == t && js.contains(&b)).or_else(|| {
                // Reached from a turning guide's joint by vectors turning with the guide (the tip
                // of a slotted rocker): on the guide's body, a plate of its own so far.
                (at != b && guides.iter().any(|&(gt, g, _)| gt == t && g == b)).then(|| {
                    plates.push((t, vec![b]));
                    plates.len() - 1
                })
            })
        });
        match home {
            Some(i) => {
                if !plates[i].1.contains(&at) {
                    plates[i].1.push(at);
                }
            }
            None if plates.iter().any(|(_, js)| js.contains(&at)) || members[at].len() > 1 || coords[at].1 => {}
            None => notes.push(format!(
                "point `{}` is on no link of the loops (the vectors from the nearest joint do not turn \
                 with a link there): drawn as a lone point",
                p.0
            )),
        }
    }
    let mut plate_names: Vec<Option<String>> = vec![None; plates.len()];
    for b in &model.dynamics.bodies {
        let (leaf, angle) = match b.turns {
            AngleModel::Unknown(i) => (Leaf::Unknown(i as u16), &model.unknowns[i].name),
            AngleModel::Input(i) => (Leaf::Input(i as u16), &model.inputs[i].name),
            AngleModel::None => continue,
        };
        match plates.iter().position(|((pos, n), _)| *pos && g.op(*n) == Op::Leaf(leaf)) {
            Some(i) if plate_names[i].is_none() => plate_names[i] = Some(b.name.clone()),
            _ => notes.push(format!(
                "body `{}` turns with `{angle}`, but no link of the loops turns with it alone: not drawn as a plate",
                b.name
            )),
        }
    }
    let mut out = format!("kinloop-drawing 1\nt {}\n", tape.entries.join(" "));
    joint_lines.iter().chain(&seg_lines).for_each(|l| out.push_str(l));
    for ((_, js), name) in plates.iter().zip(&plate_names) {
        let js: Vec<String> = js.iter().map(usize::to_string).collect();
        let _ = writeln!(out, "p {} {}", name.as_deref().unwrap_or("-"), js.join(" "));
    }
    // A turning guide is rigid with the plate that turns alike about its joint: the drawing
    // makes the guide as long as that body reaches.
    for &(t, g, s) in &guides {
        if let Some(p) = plates.iter().position(|(pt, js)| *pt == t && js.contains(&g)) {
            let _ = writeln!(out, "g {p} {s}");
        }
    }
    for n in notes {
        let _ = writeln!(out, "n {n}");
    }
    out.pop();
    out
}

/// Links that turn alike and share a joint, grouped: each plate's turn and joints.
fn plates(links: &[(Turn, usize, usize)]) -> Vec<(Turn, Vec<usize>)> {
    let mut out: Vec<(Turn, Vec<usize>)> = Vec::new();
    for &(t, a, b) in links {
        let hits: Vec<usize> =
            (0..out.len()).filter(|&i| out[i].0 == t && (out[i].1.contains(&a) || out[i].1.contains(&b))).collect();
        let mut js = Vec::new();
        for &i in hits.iter().rev() {
            let (_, more) = out.remove(i);
            js.splice(0..0, more);
        }
        for j in [a, b] {
            if !js.contains(&j) {
                js.push(j);
            }
        }
        out.insert(hits.first().copied().unwrap_or(out.len()), (t, js));
    }
    out
}
