//! The pieces a solver kernel is generated from, and their small accessors.

use super::mode::Mode;
use super::scopes::Scopes;
use crate::emit::names::Names;
use crate::emit::schedule::Schedule;
use crate::graph::dag::{Graph, Leaf, NodeId};
use crate::plan::{BlockPlan, Plan};
use proc_macro2::{Ident, TokenStream};
use quote::quote;
use std::collections::HashSet;

/// The pieces of a solver kernel being generated.
pub(super) struct Kernel<'a> {
    pub(super) plan: &'a Plan,
    pub(super) g: &'a Graph,
    pub(super) names: &'a Names,
    pub(super) mode: Mode,
    pub(super) sched: Schedule,
    pub(super) scopes: Scopes,
    pub(super) rt: TokenStream,
    /// Checks switched by the kernel's constant `__CHECKED`, deferred to its end when it is
    /// false (see [`deferred_body`](super::deferred_body)).
    pub(super) deferred: bool,
    /// The leaves the kernel reads.
    pub(super) used: HashSet<Leaf>,
    /// The `sin`/`cos` nodes that closed-form solves define.
    pub(super) closed_trig: HashSet<NodeId>,
}

impl Kernel<'_> {
    pub(super) fn lets(&self, scope: usize) -> TokenStream {
        self.names.lets(self.g, &self.sched, &self.sched.lets[scope])
    }

    pub(super) fn op(&self, n: NodeId) -> TokenStream {
        self.names.operand(self.g, n)
    }

    pub(super) fn unknowns_of(&self, bp: &BlockPlan) -> Vec<&Ident> {
        bp.unknowns.iter().map(|&u| &self.names.unknowns[u]).collect()
    }

    pub(super) fn guess_arg(&self) -> TokenStream {
        if self.mode == Mode::At {
            quote!(::core::option::Option::None)
        } else {
            quote!(::core::option::Option::Some(__guess))
        }
    }
}
