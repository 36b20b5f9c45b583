//! Generation of the straight-line solver functions (flat arrays in, flat arrays out).
//!
//! Three variants share one scheduler:
//! * `Position`: blocks solved in BLT order (Newton per nonlinear block, one linear solve per
//!   linear block);
//! * `Fused`: the same, then velocity and acceleration analogs with one factorisation per block
//!   (the Newton evaluation's Jacobian at the solution is reused, linear blocks reuse their
//!   position factorisation), then the outputs and their analogs;
//! * `At`: analogs and outputs at a position given by the caller.

use crate::dag::NodeId;
use crate::emit::{Names, ScopeKind, ScopeSpec, float, schedule};
use crate::model::Model;
use crate::plan::{Plan, pair_index, pairs};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Position,
    Fused,
    At,
}

fn lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}

/// The body of a solver function with arguments `__x`, `__guess`/`__q` and `__cfg`.
pub fn solver_body(model: &Model, plan: &Plan, names: &Names, mode: Mode, rt: &TokenStream) -> TokenStream {
    solver_body_with(model, plan, names, mode, false, rt)
}

/// [`solver_body`], optionally followed by the parameter sensitivities (returning
/// `(Kin, Sens)`), which reuse each block's factorisation.
pub fn solver_body_with(
    model: &Model,
    plan: &Plan,
    names: &Names,
    mode: Mode,
    sens: bool,
    rt: &TokenStream,
) -> TokenStream {
    let g = &model.graph;
    let nb = plan.blocks.len();
    let mut scopes: Vec<ScopeSpec> = Vec::new();
    let mut push = |kind: ScopeKind, roots: Vec<NodeId>| {
        scopes.push(ScopeSpec { kind, roots });
        scopes.len() - 1
    };
    let res_idx = (mode == Mode::At).then(|| push(ScopeKind::Plain, plan.residuals.clone()));
    let mut pre_idx = vec![0; nb];
    let mut loop_idx = vec![0; nb];
    if mode != Mode::At {
        for (b, bp) in plan.blocks.iter().enumerate() {
            let (pre_roots, loop_roots) = if bp.linear {
                (
                    bp.jac.concat().into_iter().chain(bp.f0.iter().copied()).chain(bp.col_scale.concat()).collect(),
                    Vec::new(),
                )
            } else {
                (Vec::new(), bp.f.iter().copied().chain(bp.jac.concat()).collect())
            };
            pre_idx[b] = push(ScopeKind::Plain, pre_roots);
            loop_idx[b] = push(ScopeKind::Loop(b), loop_roots);
        }
    }
    let mut vel_idx = vec![0; nb];
    let mut acc_idx = vec![0; nb];
    let mut sens_idx = [vec![0; nb], vec![0; nb], vec![0; nb]];
    let mut out_idx = 0;
    if mode != Mode::Position {
        for (b, bp) in plan.blocks.iter().enumerate() {
            let mut roots = bp.vel.concat();
            roots.extend(bp.col_scale.concat());
            if mode == Mode::At {
                roots.extend(bp.jac.concat());
            }
            vel_idx[b] = push(ScopeKind::Plain, roots);
        }
        for (b, bp) in plan.blocks.iter().enumerate() {
            acc_idx[b] = push(ScopeKind::Plain, bp.acc.concat());
        }
        if sens {
            for (b, bp) in plan.blocks.iter().enumerate() {
                sens_idx[0][b] = push(ScopeKind::Plain, bp.sens_q.concat());
            }
            for (b, bp) in plan.blocks.iter().enumerate() {
                sens_idx[1][b] = push(ScopeKind::Plain, bp.sens_v.concat());
            }
            for (b, bp) in plan.blocks.iter().enumerate() {
                sens_idx[2][b] = push(ScopeKind::Plain, bp.sens_a.concat());
            }
        }
        let mut roots: Vec<NodeId> =
            plan.outputs.iter().copied().chain(plan.out_d1.concat()).chain(plan.out_d2.concat()).collect();
        if sens {
            roots.extend(plan.out_sq.concat().into_iter().chain(plan.out_sv.concat()).chain(plan.out_sa.concat()));
        }
        out_idx = push(ScopeKind::Plain, roots);
    }
    let sched = schedule(g, &plan.level, &scopes);
    let op = |n: NodeId| names.operand(g, n);
    // A 1x1 linear block with a constant, non-zero, finite coefficient.
    let fixed = |bp: &crate::plan::BlockPlan| -> Option<f64> {
        if !bp.linear || bp.unknowns.len() != 1 {
            return None;
        }
        g.as_const(bp.jac[0][0]).filter(|c| *c != 0.0 && c.is_finite())
    };
    let col_scales = |bp: &crate::plan::BlockPlan| -> Vec<TokenStream> {
        bp.col_scale
            .iter()
            .map(|col| {
                let c = col.iter().map(|&x| op(x));
                quote!(#rt::max_abs([#(#c),*]))
            })
            .collect()
    };
    let neg = |n: NodeId| {
        let o = names.operand(g, n);
        quote!(-(#o))
    };

    let mut body = TokenStream::new();
    let inputs = &names.inputs;
    let params = &names.params;
    let fields: Vec<_> = model.params.iter().map(|p| &p.name).collect();
    body.extend(quote! {
        let [#(#inputs),*] = *__x;
        #(let #params: f64 = self.#fields;)*
    });
    let q_all = &names.unknowns;
    if let Some(r) = res_idx {
        let lets = names.lets(g, &sched.lets[r]);
        let res = plan.residuals.iter().map(|&n| op(n));
        body.extend(quote! {
            let [#(#q_all),*] = *__q;
            #lets
            let __report = #rt::SolveReport::given(#rt::max_abs([#(#res),*]));
        });
    } else {
        body.extend(quote!(let mut __report = #rt::SolveReport::direct();));
    }

    // Positions, block by block.
    if mode != Mode::At {
        for (b, bp) in plan.blocks.iter().enumerate() {
            let n = lit(bp.unknowns.len());
            let bl = lit(b);
            let qs: Vec<_> = bp.unknowns.iter().map(|&u| &names.unknowns[u]).collect();
            let pre = names.lets(g, &sched.lets[pre_idx[b]]);
            body.extend(pre);
            let jrows: Vec<TokenStream> = bp
                .jac
                .iter()
                .map(|row| {
                    let r = row.iter().map(|&x| op(x));
                    quote!([#(#r),*])
                })
                .collect();
            if let Some(c) = fixed(bp) {
                // A constant, non-zero coefficient: one division, never singular.
                let lu = format_ident!("__lu{}", b);
                let c = float(c);
                let rhs = neg(bp.f0[0]);
                body.extend(quote! {
                    let #lu = #rt::Fixed(#c);
                    let [#(#qs),*] = #lu.solve([#rhs]);
                });
            } else if bp.linear {
                let lu = format_ident!("__lu{}", b);
                let scale = col_scales(bp);
                let aug_rows = bp.jac.iter().zip(&bp.f0).map(|(row, &f0)| {
                    let r = row.iter().map(|&x| op(x));
                    let f = op(f0);
                    quote!([#(#r,)* #f])
                });
                let rhs = bp.f0.iter().map(|&f| neg(f));
                body.extend(quote! {
                    let #lu = #rt::Lu::<#n>::factor_cols(&[#(#jrows),*], [#(#scale),*]);
                    if !(#lu.pivot_ratio() >= __cfg.singular_tol) {
                        return Err(self.__singular(#bl, #lu.pivot_ratio(), __cfg, __x, #rt::first_bad_row(&[#(#aug_rows),*])));
                    }
                    let [#(#qs),*] = #lu.solve([#(#rhs),*]);
                });
            } else {
                let s = format_ident!("__s{}", b);
                let l = loop_idx[b];
                let inner = names.lets(g, &sched.lets[l]);
                let exports: Vec<_> = sched.exports[l].iter().map(|&n| Names::temp(n)).collect();
                let k = lit(exports.len());
                let guess = bp.unknowns.iter().map(|&u| {
                    let u = lit(u);
                    quote!(__guess[#u])
                });
                let f = bp.f.iter().map(|&x| op(x));
                // The block's evaluation is one closure: called here at the guess (in a
                // warm-started sweep the guess usually meets the tolerance; LLVM inlines this
                // call) and handed to the out-of-line iteration only when it does not.
                let ev = format_ident!("__eval{}", b);
                body.extend(quote! {
                    let #ev = |__z: &[f64; #n]| -> #rt::BlockEval<#n, #k> {
                        let [#(#qs),*] = *__z;
                        #inner
                        #rt::BlockEval { f: [#(#f),*], j: [#(#jrows),*], scale: [0.0; #n], keep: [#(#exports),*] }
                    };
                    let __z0: [f64; #n] = [#(#guess),*];
                    let #s = match #rt::newton::<#n, #k>(__z0, __cfg, #ev) {
                        Ok(s) => s,
                        Err(e) => return Err(self.__block_failure(#bl, e, __x, __guess)),
                    };
                    __report.absorb(&#s);
                    let [#(#qs),*] = #s.z;
                    let [#(#exports),*] = #s.eval.keep;
                });
            }
        }
        if mode == Mode::Position {
            body.extend(quote!(Ok(([#(#q_all),*], __report))));
            return body;
        }
    }

    // Velocity analogs: one factorisation per block, reused below for accelerations.
    let ni = plan.ni;
    body.extend(quote!(let mut __health = #rt::Health::default();));
    for (b, bp) in plan.blocks.iter().enumerate() {
        let n = lit(bp.unknowns.len());
        let bl = lit(b);
        let lu = format_ident!("__lu{}", b);
        let rv = format_ident!("__rv{}", b);
        body.extend(names.lets(g, &sched.lets[vel_idx[b]]));
        let rows = bp.vel.iter().map(|row| {
            let r = row.iter().map(|&x| neg(x));
            quote!([#(#r),*])
        });
        body.extend(quote!(let #rv: [[f64; #ni]; #n] = [#(#rows),*];));
        let fixed_block = fixed(bp);
        if let (Mode::At, Some(c)) = (mode, fixed_block) {
            let c = float(c);
            body.extend(quote!(let #lu = #rt::Fixed(#c);));
        }
        let need_factor = (mode == Mode::At || !bp.linear) && fixed_block.is_none();
        if need_factor {
            let j = if mode == Mode::At {
                let jrows = bp.jac.iter().map(|row| {
                    let r = row.iter().map(|&x| op(x));
                    quote!([#(#r),*])
                });
                quote!([#(#jrows),*])
            } else {
                let s = format_ident!("__s{}", b);
                quote!(#s.eval.j)
            };
            let scale = col_scales(bp);
            body.extend(quote! {
                let __j: [[f64; #n]; #n] = #j;
                let #lu = #rt::Lu::<#n>::factor_cols(&__j, [#(#scale),*]);
                if !(#lu.pivot_ratio() >= __cfg.singular_tol) {
                    return Err(self.__singular(#bl, #lu.pivot_ratio(), __cfg, __x, #rt::first_bad_row(&__j).or(#rt::first_bad_row(&#rv))));
                }
            });
        }
        let vs = bp.unknowns.iter().map(|&u| {
            let v = (0..ni).map(|i| Names::tan(u, i));
            quote!([#(#v),*])
        });
        body.extend(quote! {
            __health.note(#bl, &#lu);
            let [#(#vs),*] = #lu.solve_cols(#rv);
        });
    }
    let np = pairs(ni);
    let npl = lit(np.len());
    for (b, bp) in plan.blocks.iter().enumerate() {
        let n = lit(bp.unknowns.len());
        let lu = format_ident!("__lu{}", b);
        body.extend(names.lets(g, &sched.lets[acc_idx[b]]));
        let rows = bp.acc.iter().map(|row| {
            let r = row.iter().map(|&x| neg(x));
            quote!([#(#r),*])
        });
        let ws = bp.unknowns.iter().map(|&u| {
            let w = np.iter().map(|&(i, j)| Names::tan2(u, i, j));
            quote!([#(#w),*])
        });
        body.extend(quote! {
            let __ra: [[f64; #npl]; #n] = [#(#rows),*];
            let [#(#ws),*] = #lu.solve_cols(__ra);
        });
    }
    // Parameter sensitivities: the same factorisations, one more set of right-hand sides per
    // stage (positions, first analogs, second analogs), blocks in order.
    let npar = plan.np;
    if sens {
        type Rows = dyn Fn(&crate::plan::BlockPlan) -> &Vec<Vec<NodeId>>;
        let stages: [(&Rows, Vec<(usize, usize)>); 3] = [
            (&|bp| &bp.sens_q, vec![(0, 0)]),
            (&|bp| &bp.sens_v, (0..ni).map(|i| (i, 0)).collect()),
            (&|bp| &bp.sens_a, pairs(ni)),
        ];
        for (stage, (rows_of, slots)) in stages.iter().enumerate() {
            let width = lit(slots.len() * npar);
            for (b, bp) in plan.blocks.iter().enumerate() {
                let n = lit(bp.unknowns.len());
                let lu = format_ident!("__lu{}", b);
                body.extend(names.lets(g, &sched.lets[sens_idx[stage][b]]));
                let rows = rows_of(bp).iter().map(|row| {
                    let r = row.iter().map(|&x| neg(x));
                    quote!([#(#r),*])
                });
                let binds = bp.unknowns.iter().map(|&u| {
                    let ids = slots.iter().flat_map(|&(i, j)| {
                        (0..npar).map(move |k| match stage {
                            0 => Names::sens_q(u, k),
                            1 => Names::sens_v(u, i, k),
                            _ => Names::sens_a(u, i, j, k),
                        })
                    });
                    quote!([#(#ids),*])
                });
                body.extend(quote! {
                    let __rs: [[f64; #width]; #n] = [#(#rows),*];
                    let [#(#binds),*] = #lu.solve_cols(__rs);
                });
            }
        }
    }
    body.extend(names.lets(g, &sched.lets[out_idx]));

    let dq = (0..plan.n).map(|u| {
        let v = (0..ni).map(|i| Names::tan(u, i));
        quote!([#(#v),*])
    });
    let d2q = (0..plan.n).map(|u| {
        let rows = (0..ni).map(|i| {
            let w = (0..ni).map(|j| Names::tan2(u, i, j));
            quote!([#(#w),*])
        });
        quote!([#(#rows),*])
    });
    let out = plan.outputs.iter().map(|&o| op(o));
    let dout = plan.out_d1.iter().map(|row| {
        let r = row.iter().map(|&x| op(x));
        quote!([#(#r),*])
    });
    let d2out = plan.out_d2.iter().map(|row| {
        let rows = (0..ni).map(|i| {
            let r = (0..ni).map(|j| op(row[pair_index(ni, i, j)]));
            quote!([#(#r),*])
        });
        quote!([#(#rows),*])
    });
    let guess_arg = if mode == Mode::At { quote!(None) } else { quote!(Some(__guess)) };
    let kin = quote! {
        #rt::Kin {
            x: *__x,
            q: [#(#q_all),*],
            dq: [#(#dq),*],
            d2q: [#(#d2q),*],
            out: [#(#out),*],
            dout: [#(#dout),*],
            d2out: [#(#d2out),*],
            report: __report,
            health: __health,
        }
    };
    if !sens {
        // One sum tells whether every value is finite (NaN and infinity propagate); the state is
        // built once, in the return value, and examined value by value only on the cold path.
        let mut terms: Vec<TokenStream> = q_all.iter().map(|q| quote!(#q)).collect();
        for u in 0..plan.n {
            for i in 0..ni {
                let v = Names::tan(u, i);
                terms.push(quote!(#v));
                for j in 0..ni {
                    let w = Names::tan2(u, i, j);
                    terms.push(quote!(#w));
                }
            }
        }
        for (o, &out_node) in plan.outputs.iter().enumerate() {
            terms.push(op(out_node));
            terms.extend(plan.out_d1[o].iter().map(|&n| op(n)));
            terms.extend(plan.out_d2[o].iter().map(|&n| op(n)));
        }
        let sum = balanced_sum(terms);
        body.extend(quote! {
            let __sum: f64 = #sum;
            if !__sum.is_finite() {
                let __kin = #kin;
                if !__kin.all_finite() {
                    return Err(self.__non_finite(&__kin, __x, #guess_arg));
                }
            }
            Ok(#kin)
        });
        return body;
    }
    body.extend(quote! {
        let __kin = #kin;
        if !__kin.all_finite() {
            return Err(self.__non_finite(&__kin, __x, #guess_arg));
        }
    });
    let ks: Vec<usize> = (0..npar).collect();
    let sq = (0..plan.n).map(|u| {
        let v = ks.iter().map(|&k| Names::sens_q(u, k));
        quote!([#(#v),*])
    });
    let sv = (0..plan.n).map(|u| {
        let rows = (0..ni).map(|i| {
            let v = ks.iter().map(|&k| Names::sens_v(u, i, k));
            quote!([#(#v),*])
        });
        quote!([#(#rows),*])
    });
    let sa = (0..plan.n).map(|u| {
        let rows = (0..ni).map(|i| {
            let cols = (0..ni).map(|j| {
                let v = ks.iter().map(|&k| Names::sens_a(u, i, j, k));
                quote!([#(#v),*])
            });
            quote!([#(#cols),*])
        });
        quote!([#(#rows),*])
    });
    let osq = plan.out_sq.iter().map(|row| {
        let v = row.iter().map(|&x| op(x));
        quote!([#(#v),*])
    });
    let osv = plan.out_sv.iter().map(|row| {
        let rows = (0..ni).map(|i| {
            let v = (0..npar).map(|k| op(row[i * npar + k]));
            quote!([#(#v),*])
        });
        quote!([#(#rows),*])
    });
    let osa = plan.out_sa.iter().map(|row| {
        let rows = (0..ni).map(|i| {
            let cols = (0..ni).map(|j| {
                let p = pair_index(ni, i, j);
                let v = (0..npar).map(|k| op(row[p * npar + k]));
                quote!([#(#v),*])
            });
            quote!([#(#cols),*])
        });
        quote!([#(#rows),*])
    });
    body.extend(quote! {
        let __sens = #rt::Sens {
            q: [#(#sq),*],
            dq: [#(#sv),*],
            d2q: [#(#sa),*],
            out: [#(#osq),*],
            dout: [#(#osv),*],
            d2out: [#(#osa),*],
        };
        if !__sens.all_finite() {
            return Err(#rt::Error::Domain {
                what: "parameter sensitivity of",
                name: __sens.first_non_finite(&Self::UNKNOWNS, &Self::OUTPUTS),
                at: ::std::boxed::Box::new(self.__location(__x, None)),
            });
        }
        Ok((__kin, __sens))
    });
    body
}

/// `a + b + ...` as a balanced tree: its depth (the latency of the dependent additions) grows
/// like the logarithm of the number of terms instead of linearly.
fn balanced_sum(mut terms: Vec<TokenStream>) -> TokenStream {
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

/// Straight-line evaluation of some roots (residual, outputs, guesses); returns an array.
pub fn straight_line(model: &Model, plan: &Plan, names: &Names, roots: &[NodeId], bind_q: bool) -> TokenStream {
    let g = &model.graph;
    let sched = schedule(g, &plan.level, &[ScopeSpec { kind: ScopeKind::Plain, roots: roots.to_vec() }]);
    let lets = names.lets(g, &sched.lets[0]);
    let inputs = &names.inputs;
    let params = &names.params;
    let fields: Vec<_> = model.params.iter().map(|p| &p.name).collect();
    let q = &names.unknowns;
    let bind = if bind_q { quote!(let [#(#q),*] = *__q;) } else { quote!() };
    let vals = roots.iter().map(|&n| names.operand(g, n));
    quote! {
        let [#(#inputs),*] = *__x;
        #(let #params: f64 = self.#fields;)*
        #bind
        #lets
        [#(#vals),*]
    }
}

/// Residuals, full Jacobian and input derivatives at `(x, q)`, as a `Jac`.
pub fn jacobian_body(model: &Model, plan: &Plan, names: &Names, rt: &TokenStream) -> TokenStream {
    let g = &model.graph;
    let roots: Vec<NodeId> =
        plan.residuals.iter().copied().chain(plan.jac_full.concat()).chain(plan.fx_full.concat()).collect();
    let sched = schedule(g, &plan.level, &[ScopeSpec { kind: ScopeKind::Plain, roots }]);
    let lets = names.lets(g, &sched.lets[0]);
    let inputs = &names.inputs;
    let params = &names.params;
    let fields: Vec<_> = model.params.iter().map(|p| &p.name).collect();
    let q = &names.unknowns;
    let op = |n: NodeId| names.operand(g, n);
    let f = plan.residuals.iter().map(|&n| op(n));
    let rows = |m: &Vec<Vec<NodeId>>| -> Vec<TokenStream> {
        m.iter()
            .map(|row| {
                let r = row.iter().map(|&n| op(n));
                quote!([#(#r),*])
            })
            .collect()
    };
    let (j, fx) = (rows(&plan.jac_full), rows(&plan.fx_full));
    quote! {
        let [#(#inputs),*] = *__x;
        #(let #params: f64 = self.#fields;)*
        let [#(#q),*] = *__q;
        #lets
        #rt::Jac { f: [#(#f),*], j: [#(#j),*], fx: [#(#fx),*] }
    }
}

/// The value of each parameter default as a literal.
pub fn default_literals(values: &[f64]) -> Vec<TokenStream> {
    values.iter().map(|&v| float(v)).collect()
}
