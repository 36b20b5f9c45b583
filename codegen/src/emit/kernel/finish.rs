//! The end of a solver kernel: the state (`Kin`, and `Sens` with the sensitivities) built from
//! the locals, and the one test of its finiteness that accepts it.

use super::generator::Kernel;
use super::mode::Mode;
use crate::graph::dag::NodeId;
use crate::plan::finite::{self, Term, Value};
use crate::plan::{Stages, pair_index};
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

impl Kernel<'_> {
    /// The `Kin` value from the locals.
    pub(super) fn kin(&self) -> TokenStream {
        let (plan, names, rt, ni) = (self.plan, self.names, &self.rt, self.plan.ni);
        let q = &names.unknowns;
        let dq = (0..plan.n).map(|u| {
            let v = (0..ni).map(|i| names.tan(u, i));
            quote!([#(#v),*])
        });
        let d2q = (0..plan.n).map(|u| {
            let rows = (0..ni).map(|i| {
                let w = (0..ni).map(|j| names.tan2(u, i, j));
                quote!([#(#w),*])
            });
            quote!([#(#rows),*])
        });
        let out = names.operands(self.g, &plan.outputs);
        let dout = names.rows(self.g, &plan.out_d1);
        let d2: Vec<TokenStream> = plan.out_d2.iter().map(|row| self.by_pairs(row, 1, 0)).collect();
        quote! {
            #rt::Kin {
                x: *__x,
                q: [#(#q),*],
                dq: [#(#dq),*],
                d2q: [#(#d2q),*],
                out: [#(#out),*],
                dout: #dout,
                d2out: [#(#d2),*],
                report: __report,
                health: __health,
            }
        }
    }

    /// `[[row[p(i, j) * stride + k]]]` over input pairs, as an `ni x ni` array.
    fn by_pairs(&self, row: &[NodeId], stride: usize, k: usize) -> TokenStream {
        let ni = self.plan.ni;
        let rows = (0..ni).map(|i| {
            let r = (0..ni).map(|j| self.op(row[pair_index(ni, i, j) * stride + k]));
            quote!([#(#r),*])
        });
        quote!([#(#rows),*])
    }

    /// Returns the state; one sum tells whether every value is finite (NaN and infinity
    /// propagate), and the state is examined value by value only on the cold path (in the
    /// runtime's `checked`). The usual path returns the state itself (passed through `checked`,
    /// the ~200-byte state was copied once more).
    pub(super) fn finish(&self) -> TokenStream {
        let (sum, checks) = self.finite_sum();
        if self.deferred {
            return self.finish_deferred(sum, checks);
        }
        let (kin, rt, guess) = (self.kin(), &self.rt, self.guess_arg());
        // The state is built where it goes on the hot path: in the returned value, or in a
        // sweep's slot (`__sink`). A state built once and passed to the check is copied into the
        // result: a memcpy per step.
        let sink = if self.names.sweep_kernel() { quote!(__sink) } else { quote!(#rt::ByValue) };
        quote! {
            let __sum: ::core::primitive::f64 = #sum;
            #rt::checked_with(self, __sum, #guess, #sink, || #kin)
        }
    }

    /// The sum of the state's values whose finiteness the kernel tests, and (deferred) the
    /// closed-form blocks' check sums it tests too. In the fused kernel, only the values whose
    /// finiteness the others' does not imply (see `plan::finite`); a sum of the whole state
    /// elsewhere.
    fn finite_sum(&self) -> (TokenStream, Vec<TokenStream>) {
        let (plan, names) = (self.plan, self.names);
        let value = |v: Value| match v {
            Value::Q(u) => {
                let q = &names.unknowns[u];
                quote!(#q)
            }
            Value::Dq(u, i) => {
                let v = names.tan(u, i);
                quote!(#v)
            }
            Value::D2q(u, i, j) => {
                let w = names.tan2(u, i, j);
                quote!(#w)
            }
            Value::Node(n) => self.op(n),
        };
        let mut terms: Vec<(Option<Term>, TokenStream)> =
            finite::state_terms(plan).into_iter().map(|(t, v)| (t, value(v))).collect();
        let first_check = terms.len();
        if self.deferred {
            for b in (0..plan.blocks.len()).filter(|&b| plan.blocks[b].solve.closed_form().is_some()) {
                let check = format_ident!("__check{}", b);
                terms.push((Some(Term::Check(b)), quote!(#check)));
            }
        }
        let keep = self.kept_terms(&terms);
        let (mut sum, mut checks) = (Vec::new(), Vec::new());
        for (k, ((_, t), kept)) in terms.into_iter().zip(keep).enumerate() {
            if kept {
                if k < first_check { sum.push(t) } else { checks.push(t) }
            }
        }
        (balanced_sum(sum), checks)
    }

    /// Per term of [`Kernel::finite_sum`], whether the sum includes it: in the fused kernel
    /// each value once, and only when the others' finiteness does not imply its own; elsewhere
    /// all.
    fn kept_terms(&self, terms: &[(Option<Term>, TokenStream)]) -> Vec<bool> {
        if self.mode != Mode::Fused {
            return vec![true; terms.len()];
        }
        finite::kept(self.plan, terms, finite::BUDGET)
    }

    /// The end of a kernel whose checks are switched by `__CHECKED`: with it, the checked
    /// kernel's end (`sum` is [`Kernel::finite_sum`]'s). Otherwise the state is accepted
    /// when `sum` and the closed-form blocks' check sums `checks` are finite and the smallest
    /// pivot ratio is at least `singular_tol`; else the checked kernel answers.
    fn finish_deferred(&self, sum: TokenStream, mut checks: Vec<TokenStream>) -> TokenStream {
        let kin = self.kin();
        checks.push(quote!(__sum));
        let all = balanced_sum(checks);
        quote! {
            let __sum: ::core::primitive::f64 = #sum;
            let __accept: ::core::primitive::bool = (#all).is_finite() && __health.min_pivot >= __cfg.singular_tol;
            __mode.finish((__accept, __sum), (self, __x, __guess, __cfg, __trig), __sink, || #kin)
        }
    }

    /// Returns the state and its sensitivities, checked.
    pub(super) fn finish_sensitivities(&self) -> TokenStream {
        let (plan, names, rt) = (self.plan, self.names, &self.rt);
        let (ni, npar) = (plan.ni, plan.np);
        let params = |f: &dyn Fn(usize) -> Ident| {
            let v = (0..npar).map(f);
            quote!([#(#v),*])
        };
        let sq = (0..plan.n).map(|u| params(&|k| names.sens_q(u, k)));
        let sv = (0..plan.n).map(|u| {
            let rows = (0..ni).map(|i| params(&|k| names.sens_v(u, i, k)));
            quote!([#(#rows),*])
        });
        let sa = (0..plan.n).map(|u| {
            let rows = (0..ni).map(|i| {
                let cols = (0..ni).map(|j| params(&|k| names.sens_a(u, i, j, k)));
                quote!([#(#cols),*])
            });
            quote!([#(#rows),*])
        });
        let empty = Stages { q: Vec::new(), v: Vec::new(), a: Vec::new() };
        let os = plan.out_sens.as_ref().unwrap_or(&empty);
        let osq = names.rows(self.g, &os.q);
        let osv = os.v.iter().map(|row| {
            let rows = (0..ni).map(|i| {
                let v = names.operands(self.g, &row[i * npar..(i + 1) * npar]);
                quote!([#(#v),*])
            });
            quote!([#(#rows),*])
        });
        let osa = os.a.iter().map(|row| {
            let rows = (0..ni).map(|i| {
                let cols = (0..ni).map(|j| {
                    let p = pair_index(ni, i, j);
                    let v = names.operands(self.g, &row[p * npar..(p + 1) * npar]);
                    quote!([#(#v),*])
                });
                quote!([#(#cols),*])
            });
            quote!([#(#rows),*])
        });
        let (kin, guess) = (self.kin(), self.guess_arg());
        quote! {
            let __sens = #rt::Sens { q: [#(#sq),*], dq: [#(#sv),*], d2q: [#(#sa),*], out: #osq, dout: [#(#osv),*], d2out: [#(#osa),*] };
            #rt::checked_sensitivities(self, #kin, __sens, #guess)
        }
    }
}

/// `a + b + ...` as a balanced tree: its depth (the latency of the dependent additions) grows
/// like the logarithm of the number of terms instead of linearly.
pub(super) fn balanced_sum(mut terms: Vec<TokenStream>) -> TokenStream {
    if terms.is_empty() {
        return quote!(0.0);
    }
    while terms.len() > 1 {
        let mut next = Vec::with_capacity(terms.len().div_ceil(2));
        let mut it = terms.into_iter();
        while let Some(a) = it.next() {
            next.push(match it.next() {
                Some(b) => quote!((#a + #b)),
                None => a,
            });
        }
        terms = next;
    }
    terms.pop().unwrap_or_else(|| quote!(0.0))
}
