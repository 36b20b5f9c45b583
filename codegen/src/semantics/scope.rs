//! Names in scope while lowering: declaring, defining in order, and resolving each use, as
//! methods of the [`Lowerer`] over its table of names (the table's types are in `symbols`,
//! below both this file and the lowering).

use super::lower::Lowerer;
use super::symbols::{Symbol, Val};
use crate::front::expr::Expr;
use crate::front::suggest::similar;
use crate::graph::dag::Leaf;
use proc_macro2::Span;
use syn::Ident;
use syn::ext::IdentExt;

/// The key of a name in the table: the identifier without `r#`, as Rust compares them (`r#a`
/// and `a` are one name, and would be one field of the generated types).
pub(super) fn key(name: &Ident) -> String {
    name.unraw().to_string()
}

/// The name of the parameter, input or unknown `leaf`.
pub(super) fn leaf_name(lw: &Lowerer, leaf: Leaf) -> Option<String> {
    let named = |s: &Symbol| match (leaf, s) {
        (Leaf::Param(i), Symbol::Param(j))
        | (Leaf::Input(i), Symbol::Input(j))
        | (Leaf::Unknown(i), Symbol::Unknown(j)) => *j == i,
        _ => false,
    };
    lw.scope.symbols.iter().find(|(_, (s, _))| named(s)).map(|(k, _)| k.clone())
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

impl Lowerer {
    /// Whether `name` is declared as a parameter, input or unknown (not a `let` that stands
    /// for one).
    /// Whether `e` is written in degrees, directly or through a `let` of such a value.
    pub(super) fn in_degrees(&self, e: &Expr) -> bool {
        e.written_in_degrees_with(&|id| self.degree_lets.contains(&key(id)))
    }

    pub(super) fn declares_leaf(&self, name: &Ident) -> bool {
        let leaf = |s: &Symbol| matches!(s, Symbol::Param(_) | Symbol::Input(_) | Symbol::Unknown(_));
        self.scope.symbols.get(&key(name)).is_some_and(|(s, _)| leaf(s))
    }

    /// Reports `name` if it cannot be declared: it is the built-in `pi`, or it names a symbol
    /// already declared that `replaceable` does not accept. Returns whether it was reported.
    fn reject(&mut self, name: &Ident, replaceable: fn(&Symbol) -> bool) -> bool {
        let key = key(name);
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
    pub(super) fn declare(&mut self, name: &Ident, sym: Symbol) -> bool {
        if self.reject(name, |_| false) {
            return false;
        }
        self.scope.symbols.insert(key(name), (sym, name.span()));
        true
    }

    /// Marks a `let`, `point` or `output` name as defined further down, so that a use above
    /// its definition is reported as an ordering mistake rather than an unknown name; `value`
    /// is its definition, whose names are noted to tell a circle from a mere ordering.
    pub(super) fn declare_later(&mut self, name: &Ident, what: &'static str, value: &Expr) {
        if key(name) != "pi" {
            self.scope.symbols.entry(key(name)).or_insert_with(|| (Symbol::Later(what), name.span()));
            value.names_used(self.later_uses.entry(key(name)).or_default());
        }
    }

    /// Lowers the value of the `let`, `point` or `output` called `name`, noting the name as
    /// the one being defined.
    pub(super) fn lower_definition(&mut self, name: &Ident, value: &Expr) -> Option<Val> {
        self.defining = Some(key(name));
        let v = self.lower(value);
        self.defining = None;
        v
    }

    /// The error for `key`, the name of the `what` at `span`, used before that definition:
    /// in its own definition, in that of a name its definition uses (a circle), or merely
    /// above it.
    fn used_before_definition(&self, id: &Ident, what: &str, span: Span) -> syn::Error {
        let key = key(id);
        let instead = "for a value that must satisfy an equation in itself, declare it with `unknowns` and \
                       write that equation as an `eq`";
        let defining = self.defining.as_deref();
        if defining == Some(key.as_str()) {
            return syn::Error::new(
                id.span(),
                format!(
                    "`{key}` is used in its own definition: `{what} {key} = ...;` is computed once, from names \
                     defined above it, and cannot refer to itself; {instead}"
                ),
            );
        }
        if let Some(other) = defining
            && self.later_uses.get(&key).is_some_and(|uses| uses.contains(other))
        {
            let mut e = syn::Error::new(
                id.span(),
                format!(
                    "`{other}` and `{key}` are defined from each other: `{what} {key}` below uses `{other}`, so no \
                     order of the two defines them (each value is computed once, from names above it); {instead}"
                ),
            );
            e.combine(syn::Error::new(span, format!("`{what} {key}` is defined here, from `{other}`")));
            return e;
        }
        // In a guess, moving the definition up helps only if it uses no unknown.
        let caveat = if self.in_guess { " (an initial guess may use it only if it uses no unknown)" } else { "" };
        let mut e = syn::Error::new(
            id.span(),
            format!("`{key}` is used before it is defined; move `{what} {key} = ...;` above this line{caveat}"),
        );
        e.combine(syn::Error::new(span, format!("`{what} {key}` is defined here, after its use")));
        e
    }

    /// The name of unknown `u`, as declared.
    pub(super) fn name_of_unknown(&self, u: usize) -> Option<&str> {
        self.scope
            .symbols
            .iter()
            .find(|(_, (s, _))| matches!(s, Symbol::Unknown(i) if *i as usize == u))
            .map(|(k, _)| k.as_str())
    }

    /// Notes the name of a `loop`, `eq`, `body`, `force` or `torque` item (the first, where
    /// two items share one: that mistake has its own error).
    pub(super) fn declare_label(&mut self, name: &Ident, what: &'static str) {
        self.labels.entry(key(name)).or_insert(what);
    }

    /// Defines a `let`, `point` or `output` name at its position in the body (where its
    /// `Symbol::Later` placeholder stands).
    pub(super) fn define(&mut self, name: &Ident, v: Val) {
        if !self.reject(name, |prev| matches!(prev, Symbol::Later(_))) {
            self.scope.symbols.insert(key(name), (Symbol::Let(v), name.span()));
        }
    }

    /// Marks a name whose definition failed, so its uses add no further errors.
    pub(super) fn poison(&mut self, name: &Ident) {
        let key = key(name);
        if let Some((Symbol::Later(_), _)) | None = self.scope.symbols.get(&key) {
            self.scope.symbols.insert(key, (Symbol::Poisoned, name.span()));
        }
    }

    /// The value of a name where it is used.
    pub(super) fn lookup(&mut self, id: &Ident) -> Option<Val> {
        let key = key(id);
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
            Some((Symbol::Unknown(i), _)) => {
                if self.in_equation
                    && let Some(w) = self.written_in_equations.get_mut(*i as usize)
                {
                    *w = true;
                    self.written_here.insert(*i as usize);
                }
                Some(Val::S(g.leaf(Leaf::Unknown(*i))))
            }
            Some((Symbol::Let(v), _)) => {
                // A vector `let` is a position where a position uses it; a scalar one is judged
                // as the coordinate it is written as.
                if let (Some(place), Val::V(..)) = (&self.lengths, v) {
                    self.let_uses.push((place.clone(), key));
                }
                Some(*v)
            }
            Some((Symbol::Poisoned, _)) => None,
            Some((Symbol::Later(what), span)) => {
                let e = self.used_before_definition(id, what, *span);
                self.errors.push(e);
                None
            }
            None if key == "pi" => Some(Val::S(g.constant(std::f64::consts::PI))),
            None => {
                self.unknown_name(id);
                None
            }
        }
    }

    fn unknown_name(&mut self, id: &Ident) {
        let key = key(id);
        // A built-in function without its call (`output o = sin;`): a declared name spelled
        // alike (`d` for `deg`) is not what was meant.
        if let Some(b) = super::builtins::lookup(&key) {
            self.errors.push(syn::Error::new(
                id.span(),
                format!("`{key}` is a function, not a value: call it, `{}`", b.signature()),
            ));
            return;
        }
        // Rust's and the CSV's spelling of a value that is not finite: a declaration's every
        // number is finite (its unknowns' guesses, defaults, constants), so no name holds one.
        if matches!(key.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity") {
            self.errors.push(syn::Error::new(
                id.span(),
                format!(
                    "`{key}` is not a value a declaration can hold: its numbers are all finite; write a finite \
                     number here"
                ),
            ));
            return;
        }
        // The name of a loop, equation, body or load: declared, but a label rather than a
        // value (`c.x` for a loop `c`), so "unknown name" and "declare it" would mislead.
        if let Some(what) = self.labels.get(&key) {
            self.errors.push(syn::Error::new(
                id.span(),
                format!(
                    "`{key}` is the name of `{what} {key}`, a label, not a value; to use a value here, \
                     name it with `let` above this line (as in `let v = r @ phi;`)"
                ),
            ));
            return;
        }
        // The Greek letter, as a formula writes it: `pi` is the language's name for it.
        if key == "π" {
            self.errors
                .push(syn::Error::new(id.span(), "`π` is not a name of the language: write `pi` for 3.14159..."));
            return;
        }
        // The built-in `pi` for its spellings in other cases (`PI` as in Rust's `f64::consts`),
        // and for no other name: it would be "close" to every two-letter name.
        let pi = key.eq_ignore_ascii_case("pi").then(|| "pi".to_string());
        let names: Vec<String> = self
            .scope
            .symbols
            .iter()
            .filter(|(_, (s, _))| !matches!(s, Symbol::Later(_)))
            .map(|(k, _)| k.clone())
            .chain(pi)
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
    }
}
