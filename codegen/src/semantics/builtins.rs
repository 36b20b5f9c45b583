//! The one table of built-in functions: name, arguments (how many, scalar or vector), result
//! and how each is lowered. Lowering, arity and argument checks, did-you-mean suggestions and
//! the function list in error messages all read [`BUILTINS`]; a test checks that the crate
//! documentation lists every entry.

use crate::graph::dag::Func;

/// Whether a value is a scalar or a planar vector.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Kind {
    /// A real number.
    Scalar,
    /// A planar vector `(x, y)`.
    Vector,
}

impl Kind {
    /// The kind's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Scalar => "scalar",
            Kind::Vector => "vector",
        }
    }
}

/// How a call is turned into graph nodes.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Lowering {
    /// An elementary function of one scalar.
    Unary(Func),
    /// `atan2(y, x)`.
    Atan2,
    /// `pow(base, exponent)`: an integer literal exponent becomes `powi`.
    Pow,
    /// `sqrt(a^2 + b^2)`.
    Hypot,
    /// Length of a vector.
    Norm,
    /// Direction angle of a vector, `atan2(y, x)`.
    Angle,
    /// The dot product of two vectors.
    Dot,
    /// The z component of the cross product.
    Cross,
    /// A vector turned by an angle.
    Rot,
    /// An angle written in degrees, in radians: `x * (pi / 180)`.
    Degrees,
    /// `min(a, b)`: exactly one of the arguments (the first at a tie), NaN when one is NaN.
    Min,
    /// `max(a, b)`: exactly one of the arguments (the first at a tie), NaN when one is NaN.
    Max,
    /// `clamp(x, lo, hi)` = `min(max(x, lo), hi)`; constant bounds with `lo > hi` are an error.
    Clamp,
    /// `wrap(x, period)` = `x - period * floor(x / period)`, `x` reduced by whole periods into
    /// `[0, period)` (`period` itself within rounding); a constant `period` must be positive.
    Wrap,
}

/// One built-in function.
#[derive(Debug)]
pub struct Builtin {
    /// The name a declaration calls it by.
    pub name: &'static str,
    /// The arguments: their names (shown in the signature) and kinds. The arity is their number.
    pub args: &'static [(&'static str, Kind)],
    /// The kind of the result. The lowering produces it; the table states it so that it reads
    /// as the list of signatures, and the tests check it.
    #[cfg_attr(not(test), expect(dead_code, reason = "the lowering determines the result's kind"))]
    pub result: Kind,
    /// How a call is lowered into the graph.
    pub lowering: Lowering,
}

const fn unary(name: &'static str, f: Func) -> Builtin {
    Builtin { name, args: &[("x", Kind::Scalar)], result: Kind::Scalar, lowering: Lowering::Unary(f) }
}

const S: Kind = Kind::Scalar;
const V: Kind = Kind::Vector;

/// Every function a declaration may call, scalar functions first, in the order the
/// documentation lists them.
pub static BUILTINS: &[Builtin] = &[
    unary("sin", Func::Sin),
    unary("cos", Func::Cos),
    unary("tan", Func::Tan),
    unary("asin", Func::Asin),
    unary("acos", Func::Acos),
    unary("atan", Func::Atan),
    Builtin { name: "atan2", args: &[("y", S), ("x", S)], result: S, lowering: Lowering::Atan2 },
    unary("sqrt", Func::Sqrt),
    unary("exp", Func::Exp),
    unary("ln", Func::Ln),
    unary("abs", Func::Abs),
    Builtin { name: "pow", args: &[("base", S), ("exponent", S)], result: S, lowering: Lowering::Pow },
    Builtin { name: "hypot", args: &[("a", S), ("b", S)], result: S, lowering: Lowering::Hypot },
    Builtin { name: "deg", args: &[("degrees", S)], result: S, lowering: Lowering::Degrees },
    Builtin { name: "min", args: &[("a", S), ("b", S)], result: S, lowering: Lowering::Min },
    Builtin { name: "max", args: &[("a", S), ("b", S)], result: S, lowering: Lowering::Max },
    Builtin { name: "clamp", args: &[("x", S), ("lo", S), ("hi", S)], result: S, lowering: Lowering::Clamp },
    unary("floor", Func::Floor),
    Builtin { name: "wrap", args: &[("x", S), ("period", S)], result: S, lowering: Lowering::Wrap },
    Builtin { name: "norm", args: &[("vector", V)], result: S, lowering: Lowering::Norm },
    Builtin { name: "dot", args: &[("vector", V), ("vector", V)], result: S, lowering: Lowering::Dot },
    Builtin { name: "cross", args: &[("vector", V), ("vector", V)], result: S, lowering: Lowering::Cross },
    Builtin { name: "angle", args: &[("vector", V)], result: S, lowering: Lowering::Angle },
    Builtin { name: "rot", args: &[("vector", V), ("angle", S)], result: V, lowering: Lowering::Rot },
];

/// Names often tried for which the table has another spelling, with what to write instead.
pub const HINTS: &[(&str, &str)] = &[
    ("log", "the natural logarithm is `ln`"),
    ("powi", "write `x ^ n` or `pow(x, y)`"),
    ("powf", "write `x ^ n` or `pow(x, y)`"),
    ("sqr", "write `x ^ 2`"),
    ("atan2d", "angles are in radians: write `atan2(y, x)` (and `deg(30)` for 30 degrees)"),
    ("sind", "angles are in radians: write `sin(deg(30))` for the sine of 30 degrees"),
    ("cosd", "angles are in radians: write `cos(deg(30))` for the cosine of 30 degrees"),
    ("tand", "angles are in radians: write `tan(deg(30))` for the tangent of 30 degrees"),
    ("degrees", "write `deg(30)` for 30 degrees in radians"),
    ("radians", "angles are in radians already; `deg(30)` converts 30 degrees"),
    ("fmod", "write `wrap(x, period)` for `x` reduced by whole periods into `[0, period)`"),
    ("rem_euclid", "write `wrap(x, period)` for `x` reduced by whole periods into `[0, period)`"),
    ("mod", "write `wrap(x, period)` for `x` reduced by whole periods into `[0, period)`"),
    // Functions of other libraries one edit or two from a built-in of another meaning (`tanh`
    // from `tan`, `sign` from `sin`, `sec` from `deg`): the nearest name would be a wrong
    // function that compiles, so each says how it is written.
    ("sinh", "write `(exp(x) - exp(-x)) / 2`"),
    ("cosh", "write `(exp(x) + exp(-x)) / 2`"),
    ("tanh", "write `(exp(x) - exp(-x)) / (exp(x) + exp(-x))`"),
    ("sign", "write `x / abs(x)` for the sign of an `x` that is never zero"),
    ("sgn", "write `x / abs(x)` for the sign of an `x` that is never zero"),
    ("signum", "write `x / abs(x)` for the sign of an `x` that is never zero"),
    ("cbrt", "write `pow(x, 1 / 3)` for the cube root of an `x` that is not negative"),
    ("cot", "write `1 / tan(x)`"),
    ("sec", "write `1 / cos(x)`"),
    ("csc", "write `1 / sin(x)`"),
    ("exp2", "write `pow(2, x)`"),
    ("log10", "write `ln(x) / ln(10)`"),
    ("log2", "write `ln(x) / ln(2)`"),
    ("ceil", "write `-floor(-x)`"),
    ("round", "write `floor(x + 0.5)`"),
    ("rad", "angles are in radians already; `deg(30)` converts 30 degrees"),
    ("to_radians", "angles are in radians already; `deg(30)` converts 30 degrees"),
    ("cosine", "write `cos(x)`"),
    ("tangent", "write `tan(x)`"),
];

/// The built-in function called `name`.
pub fn lookup(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

impl Builtin {
    /// The number of arguments.
    pub fn arity(&self) -> usize {
        self.args.len()
    }

    /// Takes a vector argument (listed with the vector functions).
    pub fn takes_vector(&self) -> bool {
        self.args.iter().any(|(_, k)| *k == Kind::Vector)
    }

    /// How a call is written: `atan2(y, x)`.
    pub fn signature(&self) -> String {
        let args: Vec<&str> = self.args.iter().map(|(n, _)| *n).collect();
        format!("{}({})", self.name, args.join(", "))
    }
}

/// The names of the functions for messages: `sin, cos, ...; for vectors: norm, ...`.
pub fn listing() -> String {
    let names = |vector: bool| {
        BUILTINS.iter().filter(|b| b.takes_vector() == vector).map(|b| b.name).collect::<Vec<_>>().join(", ")
    };
    format!("{}; for vectors: {}", names(false), names(true))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_found() {
        for (k, b) in BUILTINS.iter().enumerate() {
            assert!(BUILTINS[..k].iter().all(|o| o.name != b.name), "`{}` twice", b.name);
            assert!(std::ptr::eq(lookup(b.name).expect("found"), b));
            assert!(!b.args.is_empty() && b.arity() <= 3, "`{}`", b.name);
        }
        assert!(lookup("log").is_none());
        // A hint is only for names the table does not have.
        assert!(HINTS.iter().all(|(n, _)| lookup(n).is_none()));
    }

    #[test]
    fn signatures_and_kinds() {
        let sig = |n: &str| lookup(n).map(Builtin::signature);
        assert_eq!(sig("atan2").as_deref(), Some("atan2(y, x)"));
        assert_eq!(sig("rot").as_deref(), Some("rot(vector, angle)"));
        assert_eq!(sig("sin").as_deref(), Some("sin(x)"));
        assert_eq!(sig("clamp").as_deref(), Some("clamp(x, lo, hi)"));
        assert_eq!(sig("wrap").as_deref(), Some("wrap(x, period)"));
        assert_eq!(lookup("floor").map(|b| b.lowering), Some(Lowering::Unary(Func::Floor)));
        let rot = lookup("rot").expect("rot");
        assert_eq!((rot.args[0].1, rot.args[1].1, rot.result), (V, S, V));
        // The vector functions are exactly those that take a vector; only `rot` returns one.
        let returns_vector: Vec<&str> = BUILTINS.iter().filter(|b| b.result == V).map(|b| b.name).collect();
        assert_eq!(returns_vector, ["rot"]);
    }

    #[test]
    fn listing_keeps_scalar_and_vector_groups() {
        assert_eq!(
            listing(),
            "sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, ln, abs, pow, hypot, deg, min, max, clamp, \
             floor, wrap; \
             for vectors: norm, dot, cross, angle, rot"
        );
    }

    /// The user documentation (the language reference and the README) names every built-in
    /// function.
    #[test]
    fn documentation_lists_every_builtin() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
        for file in ["src/language.rs", "README.md"] {
            let text = std::fs::read_to_string(format!("{root}/{file}")).expect("readable documentation");
            for b in BUILTINS {
                let listed = text.split(|c: char| !c.is_ascii_alphanumeric()).any(|w| w == b.name);
                assert!(listed, "{file} does not mention the built-in function `{}`", b.name);
            }
        }
    }
}
