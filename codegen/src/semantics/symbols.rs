//! What names and expressions stand for once lowered: the value of a lowered expression
//! ([`Val`]), what a name in scope is ([`Symbol`]) and the table of the names in scope
//! ([`Scope`]).
//!
//! These types are the bottom of the semantics, apart from the code that uses them: the
//! lowering (`lower`) keeps a [`Scope`] in its state and returns [`Val`]s, and the resolution of
//! names (`scope`) reads and writes the table through that state; this file imports neither.

use crate::graph::dag::NodeId;
use proc_macro2::Span;
use std::collections::HashMap;

/// The type of a lowered expression.
#[derive(Clone, Copy)]
pub enum Val {
    /// A scalar: one node.
    S(NodeId),
    /// A vector: the nodes of its x and y components.
    V(NodeId, NodeId),
}

impl Val {
    pub(super) fn kind_name(self) -> &'static str {
        match self {
            Val::S(_) => "scalar",
            Val::V(..) => "vector",
        }
    }
}

/// What a name in scope stands for.
#[derive(Clone, Copy)]
pub(super) enum Symbol {
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

/// The names in scope, each with what it stands for and the span that declared it.
#[derive(Default)]
pub(super) struct Scope {
    pub(super) symbols: HashMap<String, (Symbol, Span)>,
}
