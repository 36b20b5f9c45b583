//! Lowering expressions into the graph, with the vector/scalar type checks of operators, and the
//! state of model building ([`Lowerer`]). The values it returns and the table of names it keeps
//! are declared in `symbols`; the names it meets are resolved by the methods of `scope`.

use super::symbols::{Scope, Val};
use crate::front::expr::{BinOp, Component, Expr, SpanRange};
use crate::front::syntax::Errors;
use crate::graph::dag::{Func, Graph, Leaf, NodeId, Op};
use proc_macro2::Span;

/// The state of model building: the graph being built, the names in scope and the errors found.
pub struct Lowerer {
    pub(super) graph: Graph,
    pub(super) scope: Scope,
    pub(super) errors: Errors,
    pub(super) used_params: Vec<bool>,
    pub(super) used_inputs: Vec<bool>,
    /// Set while a `loop` or `eq` is lowered: the unknowns named there are noted in
    /// `written_in_equations`.
    pub(super) in_equation: bool,
    /// Whether each unknown is named in a `loop` or `eq` (where its terms may still cancel).
    pub(super) written_in_equations: Vec<bool>,
    /// The unknowns named in the `loop` or `eq` being lowered, by index (where its terms may
    /// still cancel): an equation left with no unknown says which it named.
    pub(super) written_here: std::collections::BTreeSet<usize>,
    /// The names of the `loop`, `eq`, `body`, `force` and `torque` items, with their keyword:
    /// labels, not values, so that a use of one as a value says so.
    pub(super) labels: std::collections::HashMap<String, &'static str>,
    /// Set while an unknown's initial guess is lowered: a name defined further down may be
    /// moved above it only if it uses no unknown, which its error says.
    pub(super) in_guess: bool,
    /// The polar terms whose length varies, for the check that it is not an angle (`th @ s` for
    /// `s @ th`, `(2 * phi) @ 0`), made once the whole mechanism is lowered ([`super::polar`]).
    pub(super) named_lengths: Vec<NamedLength>,
    /// Set while an item whose vectors are positions is lowered (a `loop`, a `point`, a vector
    /// `let`, a force's point, a centre of mass): the coordinates of its Cartesian vectors are
    /// lengths.
    pub(super) lengths: Option<Place>,
    /// The coordinates of Cartesian vectors in such items that are a bare name, for the check
    /// that the name is not an angle (`(x, phi)`), made with the polar terms' ([`super::polar`]).
    pub(super) named_coordinates: Vec<NamedCoordinate>,
    /// The `let`s named while such an item is lowered, with the item: a vector `let` is a
    /// position only where a loop or point (or such a `let`) uses it.
    pub(super) let_uses: Vec<(Place, String)>,
    /// The scalar sums, differences and `eq`s of the items that shape the solution (a `loop`,
    /// an `eq`, a `let`) and of the values reported (a `point`, an `output`), for the check
    /// that they do not put an angle beside a length ([`super::polar`]): such a value changes
    /// with the unit of length wherever it is written, inline or named by a `let`.
    pub(super) scalar_pairs: Vec<ScalarPair>,
    /// The vectors built from two coordinates that vary (a tuple, a sum of vectors, a vector
    /// scaled) outside a position, for the check that one is not an angle where the other is a
    /// length ([`super::polar`]): `norm((x, psi))` and `dot((x, psi), u)` change with the unit of
    /// length as `x + psi` does; and each coordinate of a sum of vectors, whose two terms are
    /// side by side as a scalar sum's are. A position's coordinates are judged each instead.
    pub(super) vector_pairs: Vec<VectorPair>,
    /// Set while a `let`, a `point` or an `output` is lowered: its sums are noted in
    /// `scalar_pairs`, as an equation's are.
    pub(super) notes_sums: bool,
    /// The coordinates refused as angles by [`super::polar`], checked before the dynamics so
    /// that a centre of mass or a force's point that has one is not reported again.
    pub(super) refused_positions: std::collections::HashSet<NodeId>,
    /// The unknowns written bare as a coordinate of a position of the dynamics, by the
    /// position's number: an angle there is refused by the dynamics' own check, whether or not
    /// the same unknown is refused elsewhere.
    pub(super) left_to_dynamics: std::collections::HashSet<(usize, NodeId)>,
    /// How many positions of the dynamics are lowered: the number of the next.
    pub(super) dynamics_positions: usize,
    /// The `let`, `point` or `output` whose value is being lowered: a use of its own name
    /// there is a definition in terms of itself, not a definition further down.
    pub(super) defining: Option<String>,
    /// The names each `let`, `point` and `output` uses in its value: a use of one further down
    /// whose value uses the name being defined is a circle, which moving it up cannot mend.
    pub(super) later_uses: std::collections::HashMap<String, std::collections::HashSet<String>>,
    /// The scalar `let`s whose value is written in degrees (`let tilt = 2 * deg(15);`): a
    /// constant in the graph, an angle where it is written as a length, as `deg(30)` is.
    pub(super) degree_lets: std::collections::HashSet<String>,
}

/// A polar term whose length varies (a name, `2 * phi`, a scalar `let`, `norm(v)`) or is written
/// in degrees (`deg(3) @ psi`), noted while it is lowered for the check that the length is not
/// an angle ([`super::polar`]).
pub(super) struct NamedLength {
    /// The length's leaf where it is a bare name of a parameter, input or unknown; `None` for
    /// an expression, judged by its kind.
    pub(super) leaf: Option<Leaf>,
    /// Whether the length is written in degrees there (`deg(3)`, `2 * deg(15)`).
    pub(super) degrees: bool,
    /// The length lowered.
    pub(super) node: NodeId,
    /// The angle lowered.
    pub(super) angle_node: NodeId,
    /// The term's two coordinates lowered (`len cos(angle)`, `len sin(angle)`): set aside when
    /// what the rest of the mechanism says of its angle is asked.
    pub(super) products: [NodeId; 2],
    /// The whole term `length @ angle`.
    pub(super) term: SpanRange,
    /// The length as written.
    pub(super) length: String,
    /// The length as a factor of a product, parenthesised where it is an operation.
    pub(super) factor: String,
    /// The angle as written, parenthesised where it is an operation (so that the swap reads
    /// as one term).
    pub(super) angle: String,
    /// Whether the angle is a constant (`x @ 0`): then it is no length swapped with the name.
    pub(super) constant_angle: bool,
}

impl NamedLength {
    /// The term `lhs @ rhs` (lowered to `len @ angle`, its coordinates `products`), unless its
    /// length is a constant not written in `degrees`. `declared` tells a name of a parameter,
    /// input or unknown from a `let` that stands for one.
    pub(super) fn of(
        declared: &dyn Fn(&syn::Ident) -> bool,
        g: &Graph,
        (lhs, rhs): (&Expr, &Expr),
        [len, angle]: [NodeId; 2],
        products: [NodeId; 2],
        degrees: bool,
    ) -> Option<Self> {
        let leaf = match (bare(lhs), g.op(len)) {
            _ if degrees => None,
            (Expr::Var(name), Op::Leaf(l @ (Leaf::Param(_) | Leaf::Input(_) | Leaf::Unknown(_)))) if declared(name) => {
                Some(l)
            }
            _ if g.as_const(len).is_some() => return None,
            _ => None,
        };
        let constant_angle = g.as_const(angle).is_some();
        let term = lhs.range().to(rhs.range());
        Some(NamedLength {
            leaf,
            degrees,
            node: len,
            angle_node: angle,
            products,
            term,
            length: bare(lhs).show(),
            factor: operand(lhs),
            angle: operand(rhs),
            constant_angle,
        })
    }
}

/// Two scalars a sum, a difference, an `eq` or a `min`, `max` or `clamp` puts side by side,
/// noted for the check that one is not an angle where the other is a length ([`super::polar`]).
pub(super) struct ScalarPair {
    /// The sum, difference or equation as written.
    pub(super) range: SpanRange,
    /// Its source.
    pub(super) shown: String,
    /// What it does: "adds", "subtracts", "equates", "compares", "combines".
    pub(super) verb: &'static str,
    /// Each side lowered, with its source.
    pub(super) sides: [(NodeId, String); 2],
    /// The source of each side as a factor of a product, parenthesised where it is an operation.
    pub(super) factors: [String; 2],
}

impl ScalarPair {
    /// The pair `lhs`, `rhs` (lowered to `l`, `r`) of the operation `verb` over `range`, unless
    /// a side is a constant, which is of the other's kind.
    pub(super) fn of(
        g: &Graph,
        range: SpanRange,
        verb: &'static str,
        (lhs, rhs): (&Expr, &Expr),
        l: Val,
        r: Val,
    ) -> Option<Self> {
        let (Val::S(a), Val::S(b)) = (l, r) else { return None };
        if g.as_const(a).is_some() || g.as_const(b).is_some() {
            return None;
        }
        let factors = [operand(lhs), operand(rhs)];
        let (lhs, rhs) = (bare(lhs).show(), bare(rhs).show());
        let shown = match verb {
            "adds" => format!("{lhs} + {rhs}"),
            "subtracts" => format!("{lhs} - {rhs}"),
            _ => format!("{lhs} == {rhs}"),
        };
        Some(ScalarPair { range, shown: short(&shown), verb, sides: [(a, lhs), (b, rhs)], factors })
    }

    /// Two arguments of a function of two quantities of one kind (the call written as `call`,
    /// doing `verb`): `min`, `max` or `clamp`, which return one of them, a length or an angle by
    /// the input ("compares"); `atan2`, `hypot` and `wrap`, whose value is a length's or an
    /// angle's only where both are ("combines"). Noted as [`ScalarPair::of`] notes a sum's terms.
    pub(super) fn compared(
        g: &Graph,
        (range, call, verb): (SpanRange, &str, &'static str),
        args: (&Expr, &Expr),
        l: Val,
        r: Val,
    ) -> Option<Self> {
        Self::of(g, range, verb, args, l, r).map(|p| ScalarPair { shown: short(call), ..p })
    }
}

/// A vector whose two coordinates vary, noted where it is built outside a position (`(x, psi)`
/// given to `norm` or `dot`, `(x, 0) + (0, psi)`) for the check that it does not put an angle
/// beside a length ([`super::polar`]), as a sum's terms are judged.
pub(super) struct VectorPair {
    /// The two coordinates, side by side, as the vector is written ("combines").
    pub(super) pair: ScalarPair,
    /// The vector `let` it is written in: where a loop or point takes the `let` as a position,
    /// its coordinates are judged each, and the vector is not told again.
    pub(super) within: Option<String>,
    /// The coordinates of the vectors it is built from (the operands of a sum or a scaling): a
    /// vector built from one that mixes the two is that one mistake, told once.
    pub(super) parts: Vec<[NodeId; 2]>,
    /// For one coordinate of a sum or difference of vectors (`x + psi` of `(x, 0) + (psi, 0)`,
    /// the two terms in `pair`), the sum's coordinates: the sum is told once, whichever of its
    /// coordinates or the vector itself mixes the two; `None` for the vector itself.
    pub(super) sum: Option<[NodeId; 2]>,
}

/// An item whose Cartesian vectors have lengths for coordinates.
#[derive(Clone)]
pub(super) enum Place {
    /// A `loop`, which adds lengths.
    Loop,
    /// A `point`, a position.
    Point,
    /// The `let` of this name: a position if a loop, a point or such a `let` uses it.
    Let(String),
    /// A position of the dynamics, described so (`the point a force acts at`), with its number
    /// among them: a coordinate written there is told apart from one of a `let` it uses.
    Dynamics(&'static str, usize),
}

impl Place {
    /// What a coordinate here is, for the message: "a coordinate of ...".
    pub(super) fn describe(&self) -> String {
        match self {
            Place::Loop => "a vector in a loop, which adds lengths".to_string(),
            Place::Point => "a point, which is a position in lengths".to_string(),
            Place::Let(name) => format!("`{name}`, a vector that a loop or point takes as lengths"),
            Place::Dynamics(what, _) => format!("{what}, a position in lengths"),
        }
    }
}

/// What a noted coordinate is, for the check that it is not an angle.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Coordinate {
    /// A bare name of a parameter, input or unknown.
    Name(Leaf),
    /// A value written in degrees there (`(x, deg(5))`).
    Degrees,
    /// Any other expression that varies, lowered to this node (`phi + 0.0`, `2 * phi`, a scalar
    /// `let`, `dot(u, v)`): judged by its kind, not by how it is written.
    Expr(NodeId),
}

/// A coordinate of a Cartesian vector in a `loop`, `point`, `let`, or a position of the
/// dynamics, noted while it is lowered for the check that it is not an angle
/// ([`super::polar`]).
pub(super) struct NamedCoordinate {
    /// What the coordinate is.
    pub(super) what: Coordinate,
    /// The coordinate lowered.
    pub(super) node: NodeId,
    /// The item the vector is written in.
    pub(super) place: Place,
    /// The coordinate as written.
    pub(super) range: SpanRange,
    /// The coordinate as written, for the message.
    pub(super) name: String,
    /// The coordinate as a factor of a product, parenthesised where it is an operation.
    pub(super) factor: String,
}

impl NamedCoordinate {
    /// The coordinate `e` (lowered to `n`) of a vector in `place`; `None` for a constant not
    /// written in `degrees`, which is a length as written. `declared` tells a name of a
    /// parameter, input or unknown from a `let` that stands for one.
    fn of(
        declared: &dyn Fn(&syn::Ident) -> bool,
        g: &Graph,
        place: &Place,
        (e, n): (&Expr, NodeId),
        degrees: bool,
    ) -> Option<Self> {
        let what = match (bare(e), g.op(n)) {
            _ if degrees => Coordinate::Degrees,
            (Expr::Var(name), Op::Leaf(l @ (Leaf::Param(_) | Leaf::Input(_) | Leaf::Unknown(_)))) if declared(name) => {
                Coordinate::Name(l)
            }
            _ if g.as_const(n).is_some() => return None,
            _ => Coordinate::Expr(n),
        };
        Some(NamedCoordinate {
            what,
            node: n,
            place: place.clone(),
            range: e.range(),
            name: bare(e).show(),
            factor: operand(e),
        })
    }
}

/// `e` without its enclosing parentheses.
fn bare(e: &Expr) -> &Expr {
    match e {
        Expr::Paren { inner, .. } => bare(inner),
        _ => e,
    }
}

/// The coordinate `component` of the vector `e` as written, and as a factor of a product: the
/// coordinate itself in a tuple (`psi` of `(psi, 0)`), else the vector's component (`v.x`,
/// `(2 * u).y`), whose factor is left empty for the message to name the angle it is made from.
fn coordinate_of(e: &Expr, component: Component) -> (String, String) {
    let field = if component == Component::X { "x" } else { "y" };
    match bare(e) {
        Expr::Tuple { x, y, .. } => {
            let c = if component == Component::X { x } else { y };
            (bare(c).show(), operand(c))
        }
        v @ (Expr::Var(_) | Expr::Field { .. } | Expr::Call { .. }) => (format!("{}.{field}", v.show()), String::new()),
        v => (format!("({}).{field}", v.show()), String::new()),
    }
}

/// `e` as source text for an operand of `@` in a message, parenthesised where it is an
/// operation, so that a swapped term reads as one.
fn operand(e: &Expr) -> String {
    match bare(e) {
        e @ (Expr::Binary { .. } | Expr::Neg { .. }) => format!("({})", e.show()),
        e => e.show(),
    }
}

/// Largest integer exponent turned into `powi`; larger ones stay `powf`. The bound keeps the
/// exponents of the derivatives (`n - 1`, `n - 2`) far from `i32` overflow.
pub const MAX_INTEGER_EXPONENT: i64 = 1024;

/// An exponent written as an integer literal (possibly negated) becomes `powi`.
pub(super) fn integer_exponent(e: &Expr) -> Option<i32> {
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

impl Lowerer {
    pub(super) fn new() -> Self {
        Lowerer {
            graph: Graph::new(),
            scope: Scope::default(),
            errors: Errors::default(),
            used_params: Vec::new(),
            used_inputs: Vec::new(),
            in_equation: false,
            written_in_equations: Vec::new(),
            written_here: Default::default(),
            labels: Default::default(),
            in_guess: false,
            named_lengths: Vec::new(),
            lengths: None,
            named_coordinates: Vec::new(),
            let_uses: Vec::new(),
            refused_positions: Default::default(),
            left_to_dynamics: Default::default(),
            dynamics_positions: 0,
            scalar_pairs: Vec::new(),
            vector_pairs: Vec::new(),
            notes_sums: false,
            defining: None,
            later_uses: Default::default(),
            degree_lets: Default::default(),
        }
    }

    /// `f` run with the coordinates of Cartesian vectors taken as lengths of `place`.
    pub(super) fn lower_in<T>(&mut self, place: Place, f: impl FnOnce(&mut Self) -> T) -> T {
        let outer = self.lengths.replace(place);
        let v = f(self);
        self.lengths = outer;
        v
    }

    /// `f` run with its sums noted in `scalar_pairs`, as an equation's are (a `let`, a `point`,
    /// an `output`, a force's or a torque's law).
    pub(super) fn noting_sums<T>(&mut self, f: impl FnOnce(&mut Self) -> T) -> T {
        let outer = std::mem::replace(&mut self.notes_sums, true);
        let v = f(self);
        self.notes_sums = outer;
        v
    }

    /// A constant scalar (a parameter's default value).
    pub(super) fn constant(&mut self, e: &Expr, what: &str) -> Option<NodeId> {
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

    /// An unknown's initial guess: any scalar that does not use unknowns.
    pub(super) fn guess(&mut self, e: &Expr) -> Option<NodeId> {
        self.in_guess = true;
        let v = self.lower_scalar(e, "an initial guess");
        self.in_guess = false;
        let v = v?;
        let used: Vec<String> = self
            .graph
            .leaves_of(&[v])
            .into_iter()
            .filter_map(|l| match l {
                Leaf::Unknown(u) => Some(format!("`{}`", self.name_of_unknown(u as usize)?)),
                _ => None,
            })
            .collect();
        if !used.is_empty() {
            // Name them: through a `let` or an output, the guess may not name them itself.
            self.errors.push(e.range().error(format!(
                "an initial guess cannot use unknowns (they are what is being solved), and this one \
                 depends on {}; write a number or an expression of parameters and inputs, e.g. `= 0.5` \
                 or `= l + r`",
                used.join(", ")
            )));
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
    pub(super) fn lower_equation(&mut self, lhs: &Expr, rhs: &Expr) -> (Option<Val>, Option<Val>) {
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

    pub(super) fn lower(&mut self, e: &Expr) -> Option<Val> {
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
                let xs = self.lower_coordinate(x);
                let ys = self.lower_coordinate(y);
                let v = Val::V(xs?, ys?);
                self.note_vector(e, v, Vec::new());
                v
            }
            Expr::Field { base, component, name } => return self.field(base, *component, name),
            Expr::Binary { op, op_span, lhs, rhs } => {
                let before = [self.named_coordinates.len(), self.let_uses.len()];
                let vectors_before = self.vector_pairs.len();
                let l = self.lower(lhs);
                let between = [self.named_coordinates.len(), self.let_uses.len()];
                let r = self.lower(rhs);
                let (l, r) = (l?, r?);
                self.unnote_scaled(*op, (l, r), (before, between), (lhs, rhs));
                if *op == BinOp::Div && self.is_constant_zero(r) {
                    let divisor = if rhs.is_literal_zero() {
                        String::new()
                    } else {
                        format!("`{}` is always 0, so ", short(&rhs.show()))
                    };
                    self.errors.push(rhs.range().error(format!(
                        "division by zero: {divisor}`{}` has no finite value; divide by a value that is not zero",
                        short(&e.show())
                    )));
                    return None;
                }
                let Some(res) = self.binary(*op, *op_span, (lhs, rhs), l, r) else {
                    // A vector as an operand of `@` (`a @ (phi, 1)`) is no position, as the
                    // vectors `norm` and `dot` take are none: its coordinates are not told to be
                    // lengths too (nor of one kind), a second error for the one mistake the type
                    // error names.
                    if *op == BinOp::Polar {
                        self.named_coordinates.truncate(before[0]);
                        self.let_uses.truncate(before[1]);
                        self.vector_pairs.truncate(vectors_before);
                    }
                    return None;
                };
                let verb = match op {
                    BinOp::Add => Some("adds"),
                    BinOp::Sub => Some("subtracts"),
                    _ => None,
                };
                // A sum of vectors or a vector scaled builds a vector of the coordinates it
                // gives (`(x, 0) + (0, psi)` is `(x, psi)`); a polar term's are lengths. Each
                // coordinate of a sum of vectors is a sum too (`(x, 0) + (psi, 0)` is
                // `(x + psi, 0)`).
                if *op != BinOp::Polar {
                    let parts = [l, r].into_iter().filter_map(|v| match v {
                        Val::V(x, y) => Some([x, y]),
                        Val::S(_) => None,
                    });
                    self.note_vector(e, res, parts.collect());
                    if let Some(verb) = verb {
                        self.note_coordinate_sums(e, verb, (lhs, rhs), [l, r, res]);
                    }
                }
                if self.in_equation || self.notes_sums {
                    let pair = verb.and_then(|v| ScalarPair::of(&self.graph, e.range(), v, (lhs, rhs), l, r));
                    self.scalar_pairs.extend(pair);
                }
                return self.finite(e.range(), &|| e.show(), &[l, r], res);
            }
            Expr::Call { func, args, close } => return self.call(func, args, *close),
        })
    }

    /// A vector times or over a scalar that is not a constant (`l * (phi, 0)`) has coordinates
    /// of that scalar's kind, a length times an angle as `(l * phi, 0)` is: the coordinates and
    /// the `let`s noted in the vector (from `before` to `between` on the left, from `between`
    /// on the right, counted in both lists) are no longer bare coordinates there. A vector of
    /// constants (a direction, `(0, 1)`) times such a scalar has the scalar for a coordinate
    /// (`phi * (0, 1)` is `(0, phi)`): it is noted as one, unless it holds vectors or vector
    /// `let`s noted themselves.
    fn unnote_scaled(&mut self, op: BinOp, vals: (Val, Val), counts: ([usize; 2], [usize; 2]), sides: (&Expr, &Expr)) {
        let (l, r) = vals;
        let (before, between) = counts;
        let varies = |g: &Graph, v: Val| matches!(v, Val::S(n) if g.as_const(n).is_none());
        if !matches!(op, BinOp::Mul | BinOp::Div) {
            return;
        }
        let now = [self.named_coordinates.len(), self.let_uses.len()];
        let (vector, scalar, [c, u], scalar_noted) = if matches!(l, Val::V(..)) && varies(&self.graph, r) {
            (l, (r, sides.1), [before[0]..between[0], before[1]..between[1]], now != between)
        } else if matches!(r, Val::V(..)) && varies(&self.graph, l) {
            (r, (l, sides.0), [between[0]..now[0], between[1]..now[1]], between != before)
        } else {
            return;
        };
        self.named_coordinates.drain(c);
        self.let_uses.drain(u);
        let constant =
            matches!(vector, Val::V(x, y) if self.graph.as_const(x).is_some() && self.graph.as_const(y).is_some());
        if let (BinOp::Mul, true, false, Some(place), (Val::S(n), e)) =
            (op, constant, scalar_noted, self.lengths.clone(), scalar)
        {
            let degrees = self.in_degrees(e);
            let noted = NamedCoordinate::of(&|id| self.declares_leaf(id), &self.graph, &place, (e, n), degrees);
            self.named_coordinates.extend(noted);
        }
    }

    /// A coordinate `e` of a vector: lowered, and noted where the vector is a position, unless
    /// the vectors and vector `let`s it holds were noted themselves (`((phi, 0).x, 0)`, `v.x`).
    fn lower_coordinate(&mut self, e: &Expr) -> Option<NodeId> {
        let before = [self.named_coordinates.len(), self.let_uses.len()];
        let n = self.lower_component(e)?;
        let inner = [self.named_coordinates.len(), self.let_uses.len()] != before;
        if let (Some(place), false) = (&self.lengths, inner) {
            let degrees = self.in_degrees(e);
            let noted = NamedCoordinate::of(&|id| self.declares_leaf(id), &self.graph, place, (e, n), degrees);
            self.named_coordinates.extend(noted);
        }
        Some(n)
    }

    /// Notes the vector `v` that `e` builds (a tuple, or a sum or scaling of the vectors whose
    /// coordinates are `parts`) for the check that its coordinates are not an angle and a length,
    /// where sums are noted and the vector is no position: a loop's, a point's or the dynamics'
    /// coordinates are judged each ([`super::polar`]), a vector `let`'s where a loop or point
    /// takes it. A constant coordinate is of the other's kind, as a constant term of a sum is.
    fn note_vector(&mut self, e: &Expr, v: Val, parts: Vec<[NodeId; 2]>) {
        let within = match &self.lengths {
            None => None,
            Some(Place::Let(name)) => Some(name.clone()),
            Some(_) => return,
        };
        let Val::V(x, y) = v else { return };
        if !(self.in_equation || self.notes_sums)
            || self.graph.as_const(x).is_some()
            || self.graph.as_const(y).is_some()
        {
            return;
        }
        let shown = short(&bare(e).show());
        // A coordinate not written as one (of `(x, 0) + (0, psi)`) is named as the vector's
        // component; the length to write for it is then named after the angle it is made from.
        let (sides, factors) = match bare(e) {
            Expr::Tuple { x: ex, y: ey, .. } => {
                ([(x, bare(ex).show()), (y, bare(ey).show())], [operand(ex), operand(ey)])
            }
            _ => ([(x, format!("({shown}).x")), (y, format!("({shown}).y"))], [String::new(), String::new()]),
        };
        let pair = ScalarPair { range: e.range(), shown, verb: "combines", sides, factors };
        self.vector_pairs.push(VectorPair { pair, within, parts, sum: None });
    }

    /// Notes each coordinate of the sum or difference of vectors `e` (doing `verb`: its operands
    /// `sides`, lowered with the result to `vals`) whose two terms vary, for the check that one
    /// is not an angle where the other is a length: `norm((x, 0) + (psi, 0))` changes with the
    /// unit of length as `norm((x + psi, 0))` does, though neither vector it adds mixes the two.
    /// Noted where [`Self::note_vector`] notes vectors, for the same reasons: a position's
    /// coordinates are judged each (`psi` of `point p = (x, 0) + (psi, 0);` is told as one).
    fn note_coordinate_sums(&mut self, e: &Expr, verb: &'static str, sides: (&Expr, &Expr), vals: [Val; 3]) {
        let within = match &self.lengths {
            None => None,
            Some(Place::Let(name)) => Some(name.clone()),
            Some(_) => return,
        };
        let [Val::V(lx, ly), Val::V(rx, ry), Val::V(sx, sy)] = vals else { return };
        if !(self.in_equation || self.notes_sums) {
            return;
        }
        let shown = short(&bare(e).show());
        for (component, [a, b]) in [(Component::X, [lx, rx]), (Component::Y, [ly, ry])] {
            // A constant term is of the other's kind, as in a scalar sum.
            if self.graph.as_const(a).is_some() || self.graph.as_const(b).is_some() {
                continue;
            }
            let ((l_shown, l_factor), (r_shown, r_factor)) =
                (coordinate_of(sides.0, component), coordinate_of(sides.1, component));
            let pair = ScalarPair {
                range: e.range(),
                shown: shown.clone(),
                verb,
                sides: [(a, l_shown), (b, r_shown)],
                factors: [l_factor, r_factor],
            };
            let (parts, sum) = (vec![[lx, ly], [rx, ry]], Some([sx, sy]));
            self.vector_pairs.push(VectorPair { pair, within: within.clone(), parts, sum });
        }
    }

    /// Whether `v` is the scalar constant zero.
    fn is_constant_zero(&self, v: Val) -> bool {
        matches!(v, Val::S(n) if self.graph.as_const(n) == Some(0.0))
    }

    /// The `result` of an expression (at `range`, written as `show` gives it) whose `operands`
    /// are all constants is a constant too, unless its value is not finite (the graph folds only
    /// finite values): such a value is reported here, at the innermost expression that has it,
    /// instead of failing every solve at run time.
    pub(super) fn finite(
        &mut self,
        range: SpanRange,
        show: &dyn Fn() -> String,
        operands: &[Val],
        result: Val,
    ) -> Option<Val> {
        let constant = |g: &Graph, v: &Val| match *v {
            Val::S(n) => g.as_const(n).is_some(),
            Val::V(x, y) => g.as_const(x).is_some() && g.as_const(y).is_some(),
        };
        if !operands.iter().all(|v| constant(&self.graph, v)) || constant(&self.graph, &result) {
            return Some(result);
        }
        let nodes = match result {
            Val::S(n) => vec![n],
            Val::V(x, y) => vec![x, y],
        };
        let value = self.graph.eval(&nodes, &|_| f64::NAN).into_iter().find(|v| !v.is_finite()).unwrap_or(f64::NAN);
        let shown = short(&show());
        let why = if value.is_nan() {
            "it is NaN (an argument outside the function's domain, such as `sqrt` or `ln` of a negative number, \
             or `asin`/`acos` beyond ±1)"
        } else {
            "it is infinite (beyond the largest f64, about 1.8e308, or at a pole such as `ln(0)` or `0 ^ -1`)"
        };
        self.errors.push(
            range.error(format!("`{shown}` has no finite value: {why}; write an expression whose value is finite")),
        );
        None
    }

    fn field(&mut self, base: &Expr, component: Component, name: &syn::Ident) -> Option<Val> {
        match self.lower(base)? {
            Val::V(x, y) => Some(Val::S(if component == Component::X { x } else { y })),
            Val::S(_) => {
                self.errors.push(syn::Error::new(
                    name.span(),
                    format!(
                        "`.{name}` takes a component of a vector, but `{}` is a scalar; remove `.{name}`",
                        short(&base.show())
                    ),
                ));
                None
            }
        }
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

    /// A binary operator on lowered operands `l` and `r` (written as `sides`).
    fn binary(&mut self, op: BinOp, op_span: Span, sides: (&Expr, &Expr), l: Val, r: Val) -> Option<Val> {
        let g = &mut self.graph;
        let res = match (op, l, r) {
            (BinOp::Add, Val::S(a), Val::S(b)) => Val::S(g.add(a, b)),
            (BinOp::Add, Val::V(ax, ay), Val::V(bx, by)) => Val::V(g.add(ax, bx), g.add(ay, by)),
            (BinOp::Sub, Val::S(a), Val::S(b)) => Val::S(g.sub(a, b)),
            (BinOp::Sub, Val::V(ax, ay), Val::V(bx, by)) => Val::V(g.sub(ax, bx), g.sub(ay, by)),
            (BinOp::Mul, Val::S(a), Val::S(b)) => Val::S(g.mul(a, b)),
            (BinOp::Mul, Val::S(a), Val::V(x, y)) | (BinOp::Mul, Val::V(x, y), Val::S(a)) => {
                Val::V(g.mul(a, x), g.mul(a, y))
            }
            (BinOp::Div, Val::S(a), Val::S(b)) => Val::S(g.div(a, b)),
            (BinOp::Div, Val::V(x, y), Val::S(a)) => Val::V(g.div(x, a), g.div(y, a)),
            (BinOp::Pow, Val::S(a), Val::S(b)) => match integer_exponent(sides.1) {
                Some(n) => Val::S(g.powi(a, n)),
                None => Val::S(g.powf(a, b)),
            },
            (BinOp::Polar, Val::S(len), Val::S(angle)) => {
                let c = g.func(Func::Cos, angle);
                let s = g.func(Func::Sin, angle);
                let products = [g.mul(len, c), g.mul(len, s)];
                let degrees = self.in_degrees(sides.0);
                let declared = |id: &syn::Ident| self.declares_leaf(id);
                let noted = NamedLength::of(&declared, &self.graph, sides, [len, angle], products, degrees);
                self.named_lengths.extend(noted);
                Val::V(products[0], products[1])
            }
            _ => {
                let e = binary_type_error(op, op_span, sides, l, r);
                self.errors.push(e);
                return None;
            }
        };
        Some(res)
    }
}

/// The polar term `len @ angle` that ends `e`, through a chain of sums and differences: in
/// `(0, -d) + s @ th + delta` the scalar `delta` meets `(0, -d) + s @ th`, whose last term is
/// the polar vector the writer most likely meant to turn by `th + delta`.
fn last_polar(e: &Expr) -> Option<(&Expr, &Expr)> {
    match e {
        Expr::Binary { op: BinOp::Polar, lhs, rhs, .. } => Some((lhs, rhs)),
        Expr::Binary { op: BinOp::Add | BinOp::Sub, rhs, .. } => last_polar(rhs),
        _ => None,
    }
}

/// The error for operands of the wrong types, with what to write instead.
fn binary_type_error(op: BinOp, op_span: Span, (lhs, rhs): (&Expr, &Expr), l: Val, r: Val) -> syn::Error {
    match op {
        BinOp::Add | BinOp::Sub => {
            let verb = if op == BinOp::Add { "add" } else { "subtract" };
            let mut msg = format!(
                "cannot {verb} a {} and a {}: both sides of `{}` must be scalars or both vectors",
                l.kind_name(),
                r.kind_name(),
                op.symbol()
            );
            // `+ 0` after a vector is the zero vector mistyped as a scalar, not an angle offset.
            let zero = matches!(rhs, Expr::Num { value, .. } if *value == 0.0);
            if let (Some((len, angle)), Val::V(..), Val::S(_), false) = (last_polar(lhs), l, r, zero) {
                let fixed = format!("{} @ ({} {} {})", len.show(), angle.show(), op.symbol(), rhs.show());
                let example = if fixed.len() <= 60 { fixed } else { "r @ (phi + gamma)".to_string() };
                msg.push_str(&format!(
                    "\nhelp: `@` binds tighter than `+` and `-`, so an angle that is a sum needs \
                     parentheses: write `{example}`"
                ));
            }
            syn::Error::new(op_span, msg)
        }
        BinOp::Mul => {
            syn::Error::new(op_span, "cannot multiply two vectors with `*`; write `dot(a, b)` or `cross(a, b)`")
        }
        BinOp::Div => rhs.range().error("cannot divide by a vector; the divisor must be a scalar"),
        BinOp::Pow => syn::Error::new(
            op_span,
            "`^` raises a scalar to a scalar power; for the length of a vector write `norm(v)`",
        ),
        BinOp::Polar => {
            let side = if matches!(l, Val::V(..)) { lhs } else { rhs };
            side.range().error(
                "`@` builds a vector from a scalar length and a scalar angle (`length @ angle`), but this is \
                 a vector; to turn a vector by an angle write `rot(v, angle)`",
            )
        }
    }
}
