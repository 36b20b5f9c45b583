//! The entry of a solver kernel: the solve report it starts, the configuration check when no
//! Newton block makes it, and a deferred kernel's mode and test of its guesses.

use super::bindings::bind_q;
use super::finish::balanced_sum;
use super::generator::Kernel;
use crate::emit::literals::lit;
use crate::emit::runtime_path::runtime;
use crate::plan::Plan;
use proc_macro2::TokenStream;
use quote::quote;

/// Without a Newton block nothing else reads the configuration, which is
/// still checked (an invalid one is an error whichever way the blocks are solved). Empty when a
/// Newton block checks it.
pub fn closed_config_check(plan: &Plan) -> TokenStream {
    let rt = runtime();
    if plan.blocks.iter().any(|b| b.solve.is_newton()) {
        return TokenStream::new();
    }
    match plan.blocks.iter().position(|b| b.solve.closed_form().is_some()) {
        Some(b) => {
            let b = lit(b);
            quote! {
                if let ::core::option::Option::Some(field) = __cfg.invalid_field() {
                    return ::core::result::Result::Err(#rt::config_failure(self, #b, field, __x, __guess));
                }
            }
        }
        None => TokenStream::new(),
    }
}

impl Kernel<'_> {
    /// The solve report: the caller's position's residual (mode `At`), or filled by the blocks.
    pub(super) fn start(&self) -> TokenStream {
        let rt = &self.rt;
        match self.scopes.residual {
            Some(r) => {
                let (q, lets) = (bind_q(self.names, &self.used), self.lets(r));
                let res = self.names.operands(self.g, &self.plan.residuals);
                // The analogs' singularity tests read `singular_tol`: an invalid configuration
                // is named here as a solve names it (a NaN tolerance failed every block). One
                // statement, the `if` in the runtime: the expansion is a line longer, not five.
                let check = if self.plan.blocks.is_empty() {
                    TokenStream::new()
                } else {
                    quote!(#rt::config_checked_at(self, __cfg, __x)?;)
                };
                quote! {
                    #check
                    #q
                    #lets
                    let __report = #rt::SolveReport::given(#rt::max_abs([#(#res),*]));
                }
            }
            // Only Newton blocks add to the report.
            None if !self.plan.blocks.iter().any(|b| b.solve.is_newton()) => {
                // A sweep's kernel is given the configuration the sweep checked once.
                let mut out =
                    if self.names.sweep_kernel() { TokenStream::new() } else { closed_config_check(self.plan) };
                out.extend(quote!(let __report = #rt::SolveReport::direct();));
                out
            }
            None => quote!(let mut __report = #rt::SolveReport::direct();),
        }
    }

    /// The entry of a deferred kernel: its mode `__mode`, and the test of the closed-form
    /// angles' guesses (`Checks::far`), where the checked kernel answers instead. A closed-form
    /// angle lies within `π` of its guess, so the test bounds the angles themselves by values
    /// known on entry, against the configured bound less a margin (`largest_deferred_guess`;
    /// against a constant, the least bound of all, every sample of the gear-lever's sweep past
    /// 2545 turns ran the checked kernel: 665 instructions instead of 574). Tested at the end,
    /// on the angles, the same test made the gear-lever's sweep take up to 40 % longer (160
    /// against 115 ns a step, 5 instructions more).
    pub(super) fn deferred_entry(&self) -> TokenStream {
        let rt = &self.rt;
        let mode = quote!(let __mode = #rt::Checks::<__CHECKED>;);
        let angles: Vec<TokenStream> = self
            .plan
            .blocks
            .iter()
            .filter_map(|bp| bp.solve.closed_form())
            .flat_map(|c| c.form.angles())
            .map(|u| {
                let u = lit(u);
                quote!(__guess[#u].abs())
            })
            .collect();
        if angles.is_empty() {
            return mode;
        }
        let magnitudes = balanced_sum(angles);
        quote! {
            #mode
            if __mode.far(#magnitudes, __cfg) {
                return __mode.rerun((self, __x, __guess, __cfg, __trig), __sink);
            }
        }
    }
}
