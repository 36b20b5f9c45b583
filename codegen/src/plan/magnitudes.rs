//! Magnitudes: for every equation, a graph node bounding the size of its terms (the unit in
//! which its residual is judged), and for every unknown the unit in which its Newton steps are
//! judged. Both make the runtime's convergence tests independent of the unit of length.
//!
//! **Row magnitude.** `M(e)` bounds `|e|` structurally, term by term, so that it measures the
//! terms and not their (possibly cancelling) sum:
//!
//! | expression            | `M`                                   |
//! |-----------------------|---------------------------------------|
//! | constant `c`          | `|c|`                                 |
//! | length leaf `v`       | `|v|`                                 |
//! | angle leaf `v`        | `1 + |v|` (one radian at least)       |
//! | `a + b`, `a - b`      | `M(a) + M(b)`                         |
//! | `-a`, `|a|`           | `M(a)`                                |
//! | `a * b`               | `M(a) M(b)`                           |
//! | `a / b`               | `M(a) / |b|`                          |
//! | `a ^ n`, `n >= 0`     | `M(a) ^ n`                            |
//! | `sqrt a`              | `sqrt M(a)`                           |
//! | `sin`, `cos`, `signum`| `1`                                   |
//! | `asin`, `atan`        | `pi / 2`                              |
//! | `acos`, `atan2`       | `pi`                                  |
//! | `min`, `max`, `clamp` | the largest of the chosen ones' `M`   |
//! | anything else         | its absolute value                    |
//!
//! A polar vector `l @ th` therefore contributes `|l|` to each of its projections, and a loop's
//! projection gets the sum of its link lengths: it never collapses when the projection itself
//! happens to vanish, and it scales exactly with the unit of length.
//!
//! **Angles.** A leaf (unknown, input or parameter) is an angle when it appears in the argument
//! of a trigonometric function anywhere in the equations; angles carry no unit. Not where each
//! of its appearances there is scaled by a factor that is not a pure number: a rack's travel
//! `x` turning a pinion of radius `rp` by `x / rp`, a gear ratio `k phi`. Such a leaf's unit is
//! the change that turns the argument by one radian (`|rp|`, `1 / |k|`): one radian of `x`
//! would make every tolerance of a rack a micrometre long a million times too coarse.
//!
//! **Unknown units.** An angle unknown's unit is one radian. Any other unknown `q_j` takes the
//! unit `M(f_r) / M(df_r/dq_j)` from the first row `r` of its block in which it appears: a
//! slider coordinate in a loop projection (`df/dq = +-1`) gets the sum of that loop's
//! lengths, a dimensionless ratio `t` in `t l` gets `M(f) / |l|`. The runtime judges a step
//! `dq_j` relative to `max(|q_j|, unit_j)`.
//!
//! **Lever floors.** An analog factorisation divides each Jacobian column by its largest entry.
//! For an angle whose lever is a variable length (`s @ th` with `s` an unknown or an input that
//! is not an angle: a slotted link's slide, the slider of an inverted crank, a cylinder's
//! length) that entry is `|s|`, and dividing by it hides the singular position at `s = 0`,
//! where `th` is undetermined: the column stays of unit size however short `s` gets. Such a
//! column is also scaled by its *lever floor*, the magnitude of each of its block's rows with
//! the variable levers set to zero (the loop's other lengths). The column scale is then
//! `max(|s|, floor)`: unchanged while the slide is longer than the rest of its loop, and the
//! pivot ratio about `|s| / floor` near the pivot, the factor by which the rounding of the
//! loop's lengths is magnified in `th` there.

use super::block_plan::BlockPlan;
use super::closed_form::ClosedForm;
use super::kinds;
use super::solve::Solve;
use crate::graph::dag::{Func, Graph, Leaf, NodeId, Op};
use std::collections::{HashMap, HashSet};

/// A factor by which a leaf is scaled where it appears in a trigonometric argument: a node and
/// whether the leaf is divided by it (`x / rp`: `(rp, true)`).
type Factor = (NodeId, bool);

/// How the classification's walk reaches a node from the trigonometric arguments: unscaled
/// (every factor on the way a pure number), scaled (through a factor that is not), or both.
#[derive(Clone, Copy, Default)]
struct Reach {
    unscaled: bool,
    scaled: bool,
}

/// One way the walk reaches a node scaled: from node `from` (`None`: from a node reached
/// unscaled, so the product of the factors starts at one), through `factor` (`None`: passed
/// through unchanged, as from a sum to its terms).
#[derive(Clone, Copy, PartialEq, Eq)]
struct Step {
    from: Option<NodeId>,
    factor: Option<Factor>,
}

/// Where the walk goes from a node of a trigonometric argument.
enum Next {
    Leaf(Leaf),
    /// Operands reached as the node is: a sum's terms, a product's by a pure number.
    Through(Vec<NodeId>),
    /// Operands reached scaled, each by a factor; and a divisor, whose leaves are all angles
    /// (as everything in an argument was).
    Scaled(Vec<(NodeId, Factor)>, Option<NodeId>),
    /// Anything else (a power, a root, an inverse function): where reached unscaled, every leaf
    /// in it an angle, as everything in an argument was.
    Opaque,
}

/// The walk's step from node `n` (see [`Magnitudes::new`]).
fn next(g: &Graph, n: NodeId) -> Next {
    match g.op(n) {
        Op::Leaf(l) => Next::Leaf(l),
        Op::Add(a, b) | Op::Sub(a, b) => Next::Through(vec![a, b]),
        Op::Neg(a) | Op::Func(Func::Abs | Func::Floor, a) => Next::Through(vec![a]),
        Op::Select(a, b, x, y) => Next::Through(vec![a, b, x, y]),
        Op::Mul(a, b) if kinds::pure_number(g, a, 8) => Next::Through(vec![b]),
        Op::Mul(a, b) if kinds::pure_number(g, b, 8) => Next::Through(vec![a]),
        Op::Div(a, b) if kinds::pure_number(g, b, 8) => Next::Through(vec![a]),
        Op::Mul(a, b) => Next::Scaled(vec![(a, (b, false)), (b, (a, false))], None),
        Op::Div(a, b) => Next::Scaled(vec![(a, (b, true))], Some(b)),
        _ => Next::Opaque,
    }
}

/// Builds the structural magnitudes of expressions of one graph.
pub struct Magnitudes {
    angles: HashSet<Leaf>,
    /// Leaves found in trigonometric arguments only scaled by factors that are not pure
    /// numbers, with their nodes.
    scaled: HashMap<Leaf, NodeId>,
    /// The ways the walk reaches each node it reaches scaled.
    steps: HashMap<NodeId, Vec<Step>>,
    /// The unit built for a node reached scaled (see [`Magnitudes::scaled_unit`]).
    units: HashMap<NodeId, NodeId>,
    memo: HashMap<NodeId, NodeId>,
}

impl Magnitudes {
    /// Classifies the leaves of `residuals` (angles: inside a trigonometric argument, see the
    /// module documentation).
    ///
    /// The walk goes down from the arguments, each node once, in decreasing (topological)
    /// order: whether a node is reached unscaled or scaled, and the ways it is reached scaled,
    /// are known before its operands are visited. A leaf's factors are those of a path from an
    /// argument down to it; the paths are not listed one by one, as shared subexpressions
    /// (`l1 = l0 + l0 k`, `l2 = l1 + l1 k`, ...) make their number exponential in the size of the
    /// declaration. The unit of a scaled leaf, the smallest over them, is built the same way,
    /// node by node (`build_units`).
    pub fn new(g: &Graph, residuals: &[NodeId]) -> Self {
        let order = g.reachable(residuals);
        let mut reach = vec![Reach::default(); g.len()];
        for &n in &order {
            if let Op::Func(Func::Sin | Func::Cos | Func::Tan, a) = g.op(n) {
                reach[a.index()].unscaled = true;
            }
        }
        let (mut angles, mut scaled): (HashSet<Leaf>, HashMap<Leaf, NodeId>) = Default::default();
        let mut steps: HashMap<NodeId, Vec<Step>> = HashMap::new();
        // The nodes all of whose leaves are angles: taken together at the end.
        let mut angle_roots: Vec<NodeId> = Vec::new();
        for &n in order.iter().rev() {
            let r = reach[n.index()];
            if !r.unscaled && !r.scaled {
                continue;
            }
            let mut add_step = |m: NodeId, step: Step| {
                let list = steps.entry(m).or_default();
                if !list.contains(&step) {
                    list.push(step);
                }
            };
            match next(g, n) {
                Next::Leaf(l) => {
                    if r.unscaled {
                        angles.insert(l);
                    }
                    if r.scaled {
                        scaled.insert(l, n);
                    }
                }
                Next::Through(operands) => {
                    for m in operands {
                        reach[m.index()].unscaled |= r.unscaled;
                        if r.scaled {
                            reach[m.index()].scaled = true;
                            add_step(m, Step { from: Some(n), factor: None });
                        }
                    }
                }
                Next::Scaled(operands, divisor) => {
                    for (m, factor) in operands {
                        reach[m.index()].scaled = true;
                        if r.unscaled {
                            add_step(m, Step { from: None, factor: Some(factor) });
                        }
                        if r.scaled {
                            add_step(m, Step { from: Some(n), factor: Some(factor) });
                        }
                    }
                    angle_roots.extend(divisor);
                }
                Next::Opaque if r.unscaled => angle_roots.push(n),
                Next::Opaque => {}
            }
        }
        angles.extend(g.leaves_of(&angle_roots));
        // A leaf also found unscaled is an angle.
        scaled.retain(|l, _| !angles.contains(l));
        Magnitudes { angles, scaled, steps, units: HashMap::new(), memo: HashMap::new() }
    }

    /// The unit of a leaf scaled in its trigonometric arguments (see the module documentation):
    /// the smallest change of it that turns one of them by a radian.
    fn scaled_unit(&mut self, g: &mut Graph, l: Leaf) -> Option<NodeId> {
        let n = *self.scaled.get(&l)?;
        self.build_units(g, n);
        self.units.get(&n).copied()
    }

    /// Builds the unit of node `n`, reached scaled, and of the nodes it is reached from: over
    /// the paths from an argument down to a node, the smallest product of the sizes of its
    /// factors (`|rp|` for a divisor, `1 / M(k)` for a factor), each path's product taken from
    /// the argument down. The factors are not negative, so the smallest over the ways a node
    /// is reached of (the smallest product down to where it is reached from) times the last
    /// factor is that smallest product: a node's unit needs only those of the nodes it is
    /// reached from, and is the same number (rounding is monotonic) as the minimum over its
    /// paths one by one.
    fn build_units(&mut self, g: &mut Graph, n: NodeId) {
        let order = self.unbuilt(n);
        for m in order {
            let steps = self.steps.get(&m).cloned().unwrap_or_default();
            let mut unit: Option<NodeId> = None;
            for step in steps {
                let base = match step.from {
                    Some(p) => match self.units.get(&p) {
                        Some(&u) => u,
                        None => continue,
                    },
                    None => g.one(),
                };
                let u = match step.factor {
                    None => base,
                    Some((by, true)) => {
                        let size = g.func(Func::Abs, by);
                        g.mul(base, size)
                    }
                    Some((by, false)) => {
                        let size = self.of(g, by);
                        g.div(base, size)
                    }
                };
                unit = Some(match unit {
                    Some(v) => g.min(v, u),
                    None => u,
                });
            }
            if let Some(u) = unit {
                self.units.insert(m, u);
            }
        }
    }

    /// The nodes whose units [`Magnitudes::build_units`] needs for `n` and has not built, each
    /// after every node it is reached from (decreasing ids: these are users of it).
    fn unbuilt(&self, n: NodeId) -> Vec<NodeId> {
        let mut seen: HashSet<NodeId> = HashSet::new();
        let mut stack = vec![n];
        let mut out = Vec::new();
        while let Some(m) = stack.pop() {
            if self.units.contains_key(&m) || !seen.insert(m) {
                continue;
            }
            out.push(m);
            stack.extend(self.steps.get(&m).into_iter().flatten().filter_map(|s| s.from));
        }
        out.sort_unstable_by(|a, b| b.cmp(a));
        out
    }

    /// Whether unknown `u` is an angle.
    pub fn is_angle_unknown(&self, u: usize) -> bool {
        self.angles.contains(&Leaf::Unknown(u as u16))
    }

    /// The magnitude node of `root` (see the module documentation for the rule).
    pub fn of(&mut self, g: &mut Graph, root: NodeId) -> NodeId {
        // Ids are a topological order: every operand's magnitude exists before its user's.
        for n in self.unmemoised(g, root) {
            let m = self.node(g, n);
            self.memo.insert(n, m);
        }
        self.memo[&root]
    }

    /// The nodes below `root` (itself included) that have no magnitude yet, in increasing
    /// (topological) order. The walk stops at a node that has one: so do all the nodes below
    /// it ([`Magnitudes::of`] builds every operand's first), and a magnitude costs only the
    /// nodes it adds, not a walk of the whole graph per query.
    fn unmemoised(&self, g: &Graph, root: NodeId) -> Vec<NodeId> {
        let mut seen: HashSet<NodeId> = HashSet::new();
        let mut stack = vec![root];
        let mut out = Vec::new();
        while let Some(n) = stack.pop() {
            if self.memo.contains_key(&n) || !seen.insert(n) {
                continue;
            }
            out.push(n);
            stack.extend(g.op(n).operands());
        }
        out.sort_unstable();
        out
    }

    fn node(&self, g: &mut Graph, n: NodeId) -> NodeId {
        let m = |a: NodeId| self.memo[&a];
        match g.op(n) {
            Op::Const(bits) => g.constant(f64::from_bits(bits).abs()),
            Op::Leaf(l) if self.angles.contains(&l) => {
                let (abs, one) = (g.func(Func::Abs, n), g.one());
                g.add(one, abs)
            }
            Op::Leaf(_) => g.func(Func::Abs, n),
            Op::Add(a, b) | Op::Sub(a, b) => g.add(m(a), m(b)),
            Op::Neg(a) | Op::Func(Func::Abs, a) => m(a),
            Op::Mul(a, b) => g.mul(m(a), m(b)),
            Op::Div(a, b) => {
                let den = g.func(Func::Abs, b);
                g.div(m(a), den)
            }
            Op::Powi(a, k) if k >= 0 => g.powi(m(a), k),
            Op::Func(Func::Sqrt, a) => g.func(Func::Sqrt, m(a)),
            Op::Func(Func::Sin | Func::Cos | Func::Signum, _) => g.one(),
            Op::Func(Func::Asin | Func::Atan, _) => g.constant(std::f64::consts::FRAC_PI_2),
            Op::Func(Func::Acos, _) | Op::Atan2(..) => g.constant(std::f64::consts::PI),
            // The result is `x` or `y`: bounded by the larger of their magnitudes.
            Op::Select(_, _, x, y) => g.max(m(x), m(y)),
            Op::Powi(..) | Op::Powf(..) | Op::Func(..) => g.func(Func::Abs, n),
        }
    }

    /// The unit of input `i` over the full system (continuation measures arclength in it): one
    /// radian for an angle, otherwise `M(f_r) / M(df_r/dx_i)` from the first equation `r` whose
    /// input derivative `fx[r][i]` is not structurally zero (one when there is none).
    pub fn input_unit(&mut self, g: &mut Graph, residuals: &[NodeId], fx: &[Vec<NodeId>], i: usize) -> NodeId {
        if self.angles.contains(&Leaf::Input(i as u16)) {
            return g.one();
        }
        if let Some(unit) = self.scaled_unit(g, Leaf::Input(i as u16)) {
            return unit;
        }
        match (0..residuals.len()).find(|&r| !g.is_zero(fx[r][i])) {
            Some(r) => {
                let (f, d) = (self.of(g, residuals[r]), self.of(g, fx[r][i]));
                g.div(f, d)
            }
            None => g.one(),
        }
    }

    /// The row magnitudes and unknown units of one block: `(scale per row, unit per unknown)`.
    pub fn block(&mut self, g: &mut Graph, bp: &BlockPlan) -> (Vec<NodeId>, Vec<NodeId>) {
        let scale: Vec<NodeId> = bp.f.iter().map(|&f| self.of(g, f)).collect();
        let unit = (0..bp.unknowns.len())
            .map(|c| {
                if let Some(unit) = self.scaled_unit(g, Leaf::Unknown(bp.unknowns[c] as u16)) {
                    return unit;
                }
                let row = (0..bp.f.len()).find(|&r| !g.is_zero(bp.jac[r][c]));
                match row {
                    Some(r) if !self.is_angle_unknown(bp.unknowns[c]) => {
                        let d = self.of(g, bp.jac[r][c]);
                        g.div(scale[r], d)
                    }
                    _ => g.one(),
                }
            })
            .collect();
        (scale, unit)
    }

    /// The lever floors of a block's columns (see the module documentation): per block
    /// column, the nodes its column scale takes beyond its Jacobian entries. Empty unless the
    /// column is an angle's and its entries depend on unknowns or inputs that are not angles
    /// (the levers); then one node per block row the angle appears in, that row's magnitude with
    /// the levers set to zero, less those that cannot be the largest.
    pub fn lever_floors(&mut self, g: &mut Graph, bp: &BlockPlan) -> Vec<Vec<NodeId>> {
        (0..bp.unknowns.len())
            .map(|c| {
                if !self.is_angle_unknown(bp.unknowns[c]) {
                    return Vec::new();
                }
                let levers: Vec<Leaf> = g
                    .leaves_of(&bp.col_scale[c])
                    .into_iter()
                    .filter(|l| matches!(l, Leaf::Unknown(_) | Leaf::Input(_)) && !self.angles.contains(l))
                    .collect();
                if levers.is_empty() {
                    return Vec::new();
                }
                let zero = g.zero();
                let rows: Vec<usize> = (0..bp.f.len()).filter(|&r| !g.is_zero(bp.jac[r][c])).collect();
                let rows: Vec<NodeId> = rows.into_iter().map(|r| self.of(g, bp.f[r])).collect();
                let floors = g.substitute(&rows, &|l| levers.contains(&l).then_some(zero));
                // A floor that is zero (a loop of levers only), or a term of another floor (a
                // loop's X projection lacks the Y offsets its Y projection adds), changes no
                // column's maximum.
                let kept: Vec<NodeId> = floors.iter().copied().filter(|&f| !g.is_zero(f)).collect();
                let mut out: Vec<NodeId> = Vec::new();
                for (i, &f) in kept.iter().enumerate() {
                    let dominated =
                        kept.iter().enumerate().any(|(j, &o)| j != i && (term_of(g, f, o) || (o == f && j < i)));
                    if !dominated {
                        out.push(f);
                    }
                }
                out
            })
            .collect()
    }

    /// The magnitude of the terms of the one equation `a cos q + b sin q = c` a closed form of
    /// one angle is solved from, built from its rows' magnitudes ([`Magnitudes::block`]'s
    /// `scale`, which the block's angle leaves out: it appears only in sines and cosines): an
    /// angle equation's row's; for an angle and a slider, whose equation is the combination
    /// `d1 f0 - d0 f1` of its rows free of the slider (`d` the slider's coefficients), `M(d1)
    /// M(f0) + M(d0) M(f1)` with the slider set to zero in each (its terms cancel, they make no
    /// coefficient). For a slider-crank's rod angle from `e + r sin phi - l sin psi`, the sum
    /// `|e| + |r| + |l|`: the same number in every unit, as Newton's residual is measured.
    /// `None` for the other blocks.
    pub fn closed_form_terms(&mut self, g: &mut Graph, bp: &BlockPlan) -> Option<NodeId> {
        let Solve::ClosedForm(rec) = &bp.solve else { return None };
        match rec.form {
            // The rows' magnitudes are there once `block` has run; without them, no size (the
            // cold path then judges in the equation's own coefficients, as before).
            ClosedForm::AngleEquation { .. } => bp.scale.first().copied(),
            ClosedForm::AngleSlider { slider, d, .. } => {
                let zero = g.zero();
                let free = g.substitute(&bp.scale, &|l| (l == Leaf::Unknown(slider as u16)).then_some(zero));
                let [f0, f1] = free[..] else { return None };
                let (m0, m1) = (self.of(g, d[0]), self.of(g, d[1]));
                let (t0, t1) = (g.mul(m1, f0), g.mul(m0, f1));
                Some(g.add(t0, t1))
            }
            ClosedForm::Dyad { .. } | ClosedForm::PolarLength { .. } => None,
        }
    }
}

/// Whether `f` is one of the terms of the sum `sum` (a magnitude is a sum of non-negative
/// terms, so such an `f` is never larger than `sum`).
fn term_of(g: &Graph, f: NodeId, sum: NodeId) -> bool {
    match g.op(sum) {
        Op::Add(a, b) => a == f || b == f || term_of(g, f, a) || term_of(g, f, b),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The X projection of `x + l cos(th) - c` : magnitude `|x| + |l| + |c|`, whatever `th`
    /// (also where the projection itself vanishes); `th` is an angle, `x` and `l` are not.
    #[test]
    fn loop_projection_gets_sum_of_lengths() {
        let mut g = Graph::new();
        let (x, l, th) = (g.leaf(Leaf::Unknown(0)), g.leaf(Leaf::Param(0)), g.leaf(Leaf::Unknown(1)));
        let c = g.leaf(Leaf::Param(1));
        let cos = g.func(Func::Cos, th);
        let lc = g.mul(l, cos);
        let s = g.add(x, lc);
        let f = g.add(s, c);
        let mut mags = Magnitudes::new(&g, &[f]);
        assert!(mags.is_angle_unknown(1) && !mags.is_angle_unknown(0));
        let m = mags.of(&mut g, f);
        let at = |x: f64, l: f64, c: f64, th: f64| {
            g.eval(&[m, f], &|leaf| match leaf {
                Leaf::Unknown(0) => x,
                Leaf::Unknown(1) => th,
                Leaf::Param(0) => l,
                _ => c,
            })
        };
        // The projection vanishes (cos = 0, x = c) but its magnitude does not.
        let v = at(2.0, 3.0, -2.0, std::f64::consts::FRAC_PI_2);
        assert_eq!(v[0], 2.0 + 3.0 + 2.0);
        assert!(v[1].abs() < 1e-15);
        // Lengths a million times smaller: the magnitude scales with them (to rounding).
        let w = at(-1.5e-6, 3.0e-6, 2.0e-6, 0.3);
        assert!((w[0] - 6.5e-6).abs() <= 4.0 * f64::EPSILON * 6.5e-6, "{w:?}");
    }

    /// `rc cos(x / rp) + cos(2 phi) + cos(k y)`: `phi` (scaled by a number) is an angle, one
    /// radian; `x` (over a parameter, a rack's travel) and `y` (times one, a gear ratio) are
    /// not, their units the change that turns their argument by a radian, `|rp|` and `1 / |k|`;
    /// `y` also found unscaled elsewhere would be an angle.
    #[test]
    fn a_leaf_scaled_in_its_argument_takes_the_unit_that_turns_it_a_radian() {
        let mut g = Graph::new();
        let (x, phi, y) = (g.leaf(Leaf::Input(0)), g.leaf(Leaf::Input(1)), g.leaf(Leaf::Input(2)));
        let (rp, rc, k) = (g.leaf(Leaf::Param(0)), g.leaf(Leaf::Param(1)), g.leaf(Leaf::Param(2)));
        let two = g.constant(2.0);
        let args = [g.div(x, rp), g.mul(two, phi), g.mul(k, y)];
        let [a, b, c] = args.map(|a| g.func(Func::Cos, a));
        let ra = g.mul(rc, a);
        let sum = g.add(ra, b);
        let f = g.add(sum, c);
        let mut mags = Magnitudes::new(&g, &[f]);
        let fx: Vec<Vec<NodeId>> = vec![vec![f, f, f]];
        let units: Vec<NodeId> = (0..3).map(|i| mags.input_unit(&mut g, &[f], &fx, i)).collect();
        let v = g.eval(&units, &|leaf| match leaf {
            Leaf::Param(0) => -0.25,
            Leaf::Param(2) => 4.0,
            _ => 1.0,
        });
        assert_eq!(v, [0.25, 1.0, 0.25]);
        // `y` unscaled in another argument: an angle, one radian.
        let cy = g.func(Func::Cos, y);
        let f2 = g.add(f, cy);
        let mut mags = Magnitudes::new(&g, &[f2]);
        let unit = mags.input_unit(&mut g, &[f2], &[vec![f2, f2, f2]], 2);
        assert!(g.is_one(unit));
    }

    /// The slotted rocker `(0, h) + r @ phi - s @ th = 0` (unknowns `s`, `th`): the angle's
    /// column, whose lever `s` is an unknown, gets one floor (the Y projection's `|h| + |r|`;
    /// the X projection's `|r|` is a term of it), the length's column none. So does the angle
    /// of a lever that is an input (a cylinder's length); a fixed lever `l @ th` gets none.
    /// `min`/`max` are bounded by the larger magnitude of the two arguments, whichever is
    /// chosen.
    #[test]
    fn min_and_max_get_the_larger_magnitude() {
        let mut g = Graph::new();
        let (x, l) = (g.leaf(Leaf::Unknown(0)), g.leaf(Leaf::Param(0)));
        let two = g.constant(2.0);
        let two_l = g.mul(two, l);
        let lo = g.min(x, two_l);
        let hi = g.max(x, two_l);
        let mut mags = Magnitudes::new(&g, &[lo, hi]);
        let (ml, mh) = (mags.of(&mut g, lo), mags.of(&mut g, hi));
        for (xv, lv) in [(1.0, 3.0), (-7.0, 3.0), (5.0, -1.0), (0.0, 0.0)] {
            let v = g.eval(&[ml, mh], &|leaf| if leaf == Leaf::Unknown(0) { xv } else { lv });
            let want = f64::max(f64::abs(xv), 2.0 * f64::abs(lv));
            assert_eq!(v, [want, want], "x = {xv}, l = {lv}");
        }
    }

    #[test]
    fn only_an_angle_with_a_variable_lever_gets_a_floor() {
        use crate::structure::Block;
        // The lever: 0 the unknown `s`, 1 the parameter `l`, 2 the input `len`.
        let plan_of = |lever: u8| {
            let mut g = Graph::new();
            let (s, th) = (g.leaf(Leaf::Unknown(0)), g.leaf(Leaf::Unknown(1)));
            let (h, r, l, phi) =
                (g.leaf(Leaf::Param(0)), g.leaf(Leaf::Param(1)), g.leaf(Leaf::Param(2)), g.leaf(Leaf::Input(0)));
            let len = g.leaf(Leaf::Input(1));
            let lever = [s, l, len][lever as usize];
            let (cp, sp, ct, st) =
                (g.func(Func::Cos, phi), g.func(Func::Sin, phi), g.func(Func::Cos, th), g.func(Func::Sin, th));
            let (rc, rs, lc, ls) = (g.mul(r, cp), g.mul(r, sp), g.mul(lever, ct), g.mul(lever, st));
            let fx = g.sub(rc, lc);
            let hy = g.add(h, rs);
            let mut fy = g.sub(hy, ls);
            if lever != s {
                // `s` must still appear: a slider along Y beside the lever.
                fy = g.add(fy, s);
            }
            let residuals = [fx, fy];
            let (jac, _) = super::super::positions::full_jacobians(&mut g, &residuals, 2, 2);
            let blk = Block { unknowns: vec![0, 1], equations: vec![0, 1] };
            let pos = super::super::positions::block(&mut g, &blk, &residuals, &jac);
            let bp = super::super::BlockPlan::new(&blk, pos, super::super::solve::Solve::Newton);
            let mut mags = Magnitudes::new(&g, &residuals);
            let floors = mags.lever_floors(&mut g, &bp);
            (g, floors)
        };
        // The floor is the Y projection's magnitude without the lever: `|h| + |r|`, plus `|s|`
        // where `s` is a slider beside an input lever.
        for (lever, want) in [(0, 5.0), (2, 6.0)] {
            let (g, floors) = plan_of(lever);
            assert!(floors[0].is_empty(), "the slide's own column");
            assert_eq!(floors[1].len(), 1, "one floor for the angle");
            let v = g.eval(&floors[1], &|leaf| match leaf {
                Leaf::Param(0) => -2.0,
                Leaf::Param(1) => 3.0,
                Leaf::Unknown(0) => -1.0,
                _ => f64::NAN,
            });
            assert_eq!(v, vec![want], "lever {lever}");
        }
        let (_, floors) = plan_of(1);
        assert!(floors.iter().all(Vec::is_empty));
    }

    /// The classification as first written, one walk state per path from an argument down to
    /// a node (exponential in shared subexpressions): the reference the per-node walk must
    /// agree with on graphs small enough for it. `(angles, factor lists per scaled leaf)`.
    fn per_path(g: &Graph, residuals: &[NodeId]) -> (HashSet<Leaf>, HashMap<Leaf, Vec<Vec<Factor>>>) {
        let mut stack: Vec<(NodeId, Vec<Factor>)> = Vec::new();
        for n in g.reachable(residuals) {
            if let Op::Func(Func::Sin | Func::Cos | Func::Tan, a) = g.op(n) {
                stack.push((a, Vec::new()));
            }
        }
        let (mut angles, mut scaled): (HashSet<Leaf>, HashMap<Leaf, Vec<Vec<Factor>>>) = Default::default();
        let mut seen: HashSet<(NodeId, Vec<Factor>)> = HashSet::new();
        while let Some((n, factors)) = stack.pop() {
            if !seen.insert((n, factors.clone())) {
                continue;
            }
            let scale = |by: NodeId, divides: bool| [factors.clone(), vec![(by, divides)]].concat();
            match g.op(n) {
                Op::Leaf(l) if factors.is_empty() => _ = angles.insert(l),
                Op::Leaf(l) => scaled.entry(l).or_default().push(factors),
                Op::Add(a, b) | Op::Sub(a, b) => stack.extend([(a, factors.clone()), (b, factors)]),
                Op::Neg(a) | Op::Func(Func::Abs | Func::Floor, a) => stack.push((a, factors)),
                Op::Select(a, b, x, y) => stack.extend([a, b, x, y].map(|m| (m, factors.clone()))),
                Op::Mul(a, b) if kinds::pure_number(g, a, 8) => stack.push((b, factors)),
                Op::Mul(a, b) if kinds::pure_number(g, b, 8) => stack.push((a, factors)),
                Op::Div(a, b) if kinds::pure_number(g, b, 8) => stack.push((a, factors)),
                Op::Mul(a, b) => stack.extend([(a, scale(b, false)), (b, scale(a, false))]),
                Op::Div(a, b) => {
                    stack.push((a, scale(b, true)));
                    angles.extend(g.leaves_of(&[b]));
                }
                _ if factors.is_empty() => angles.extend(g.leaves_of(&[n])),
                _ => {}
            }
        }
        scaled.retain(|l, _| !angles.contains(l));
        (angles, scaled)
    }

    /// Distinct values for every leaf, of both signs.
    fn value(leaf: Leaf) -> f64 {
        let (k, sign) = match leaf {
            Leaf::Param(k) => (k, 1.0),
            Leaf::Input(k) => (k + 20, -1.0),
            Leaf::Unknown(k) => (k + 40, 1.0),
            _ => (60, -1.0),
        };
        sign * (0.37 + 0.61 * f64::from(k))
    }

    /// Checks that the per-node walk classifies the leaves of `residual` as the per-path walk
    /// does, and that the unit of every scaled leaf is the smallest product over its paths
    /// (to the bit, at [`value`]).
    fn agrees_with_per_path(g: &mut Graph, residual: NodeId) {
        let (angles, per_path_scaled) = per_path(g, &[residual]);
        let mut mags = Magnitudes::new(g, &[residual]);
        assert_eq!(mags.angles, angles);
        let mut leaves: Vec<Leaf> = mags.scaled.keys().copied().collect();
        leaves.sort_by_key(|l| format!("{l:?}"));
        let mut want: Vec<Leaf> = per_path_scaled.keys().copied().collect();
        want.sort_by_key(|l| format!("{l:?}"));
        assert_eq!(leaves, want);
        for (l, lists) in per_path_scaled {
            let unit = mags.scaled_unit(g, l).expect("a scaled leaf's unit");
            let mut products = Vec::new();
            for factors in lists {
                let mut u = g.one();
                for (by, divides) in factors {
                    u = if divides {
                        let size = g.func(Func::Abs, by);
                        g.mul(u, size)
                    } else {
                        let size = mags.of(g, by);
                        g.div(u, size)
                    };
                }
                products.push(u);
            }
            let got = g.eval(&[unit], &value)[0];
            let smallest = g.eval(&products, &value).into_iter().fold(f64::INFINITY, f64::min);
            assert_eq!(got.to_bits(), smallest.to_bits(), "{l:?}: {got} against {smallest}");
        }
    }

    /// `l0 = a phi`, `l_i = l_(i-1) + l_(i-1) (phi + i)`, residual `q - sin(l_n) phi`: every
    /// `l_i` is used twice by the next, so `phi` is reached along `2^n` paths, each scaled by
    /// other factors.
    fn shared_products(g: &mut Graph, n: u32) -> NodeId {
        let (a, phi, q) = (g.leaf(Leaf::Param(0)), g.leaf(Leaf::Input(0)), g.leaf(Leaf::Unknown(0)));
        let mut l = g.mul(a, phi);
        for i in 1..=n {
            let c = g.constant(f64::from(i));
            let shifted = g.add(phi, c);
            let scaled = g.mul(l, shifted);
            l = g.add(l, scaled);
        }
        let s = g.func(Func::Sin, l);
        let sp = g.mul(s, phi);
        g.sub(q, sp)
    }

    /// `l0 = a phi`, `l_i = sin(l_(i-1)) cos(l_(i-1)) + l_(i-1) phi`: trigonometric functions
    /// nested `n` deep, their arguments shared.
    fn nested_arguments(g: &mut Graph, n: u32) -> NodeId {
        let (a, phi, q) = (g.leaf(Leaf::Param(0)), g.leaf(Leaf::Input(0)), g.leaf(Leaf::Unknown(0)));
        let mut l = g.mul(a, phi);
        for _ in 1..=n {
            let (s, c) = (g.func(Func::Sin, l), g.func(Func::Cos, l));
            let sc = g.mul(s, c);
            let lp = g.mul(l, phi);
            l = g.add(sc, lp);
        }
        let s = g.func(Func::Sin, l);
        g.sub(q, s)
    }

    #[test]
    fn the_per_node_walk_agrees_with_the_per_path_walk() {
        for n in 0..=7 {
            let mut g = Graph::new();
            let f = shared_products(&mut g, n);
            agrees_with_per_path(&mut g, f);
            let mut g = Graph::new();
            let f = nested_arguments(&mut g, n);
            agrees_with_per_path(&mut g, f);
        }
        // Every kind of step: sums, negations, absolute values, floors, selections, products
        // and quotients by pure numbers and by other nodes, divisors, opaque nodes (a root, a
        // nested function), a leaf reached both scaled and unscaled (`y`), one reached scaled
        // along several paths with different factors (`x`).
        let mut g = Graph::new();
        let [x, y, z, phi] = [0, 1, 2, 3].map(|i| g.leaf(Leaf::Unknown(i)));
        let [rp, k, m, a, b] = [0, 1, 2, 3, 4].map(|i| g.leaf(Leaf::Param(i)));
        let (two, half) = (g.constant(2.0), g.constant(0.5));
        let x_rp = g.div(x, rp);
        let ym = g.mul(y, m);
        let sum = g.add(x, ym);
        let k_sum = g.mul(k, sum);
        let ab = g.add(a, b);
        let y_ab = g.div(y, ab);
        let two_phi = g.mul(two, phi);
        let neg = g.neg(y_ab);
        let third = g.sub(two_phi, neg);
        let root = g.func(Func::Sqrt, z);
        let root_x = g.mul(root, x);
        let cos_y = g.func(Func::Cos, y);
        let floor = g.func(Func::Floor, cos_y);
        let abs = g.func(Func::Abs, root_x);
        let lo = g.min(abs, floor);
        let fourth = g.div(lo, half);
        let x_k = g.div(x, k);
        let x_k_m = g.mul(x_k, m);
        let args = [x_rp, k_sum, third, fourth, x_k_m];
        let mut f = g.zero();
        for (i, arg) in args.into_iter().enumerate() {
            let t = g.func([Func::Sin, Func::Cos, Func::Tan][i % 3], arg);
            f = g.add(f, t);
        }
        agrees_with_per_path(&mut g, f);
    }

    /// The chain of shared products 40 deep (`2^40` paths down to `phi`, scaled) and 800 nested
    /// arguments: the classification and the input's unit take a bounded number of nodes per
    /// node of the declaration (the walk visits each node once, and a node's unit is built from
    /// those it is reached from).
    #[test]
    fn shared_subexpressions_are_walked_once() {
        for (n, build) in [(40, shared_products as fn(&mut Graph, u32) -> NodeId), (800, nested_arguments)] {
            let mut g = Graph::new();
            let f = build(&mut g, n);
            let before = g.len();
            let mut mags = Magnitudes::new(&g, &[f]);
            let steps: usize = mags.steps.values().map(Vec::len).sum();
            assert!(steps <= 2 * before, "{steps} steps over {before} nodes");
            mags.input_unit(&mut g, &[f], &[vec![f]], 0);
            assert!(g.len() <= 8 * before, "{} nodes from {before}", g.len());
        }
    }
}
