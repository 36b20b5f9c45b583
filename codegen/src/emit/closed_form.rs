//! The straight-line closed-form solve of one recognised block.
//!
//! Every form reduces to one equation `a cos q + b sin q = c` in one angle, whose two roots are
//! `(cos q, sin q) = (a c ∓ b d, b c ± a d) / (a² + b²)` with `d = sqrt(a² + b² - c²)`: the cosine
//! and sine come from the equation itself (no `sin_cos` of the solution), `q` from one `atan2`
//! (one `asin` or `acos` when a coefficient is zero), moved by whole turns to the guess's turn.
//! The root is chosen so that the derivative `h'` of the angle equation (proportional, with a
//! fixed sign, to the block's Jacobian determinant) has the sign it has at the guess. With
//! `h = a cos q + b sin q - c`, `h' = ∓ d` at the two roots.
//!
//! What is the same for every block (the root, the unwrap to the guess's turn, the checks and
//! their failures) is a call of the runtime's `solvers::closed` functions, which perform the
//! operations this code would, in the same order; only the coefficients, specific to the
//! block, are emitted inline (with their constants folded).

use super::names::float;
use crate::graph::dag::{Graph, NodeId};
use crate::plan::Plan;
use crate::plan::closed_form::{ClosedForm, Recognised, constant_norm2};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashSet;

/// What the solve of block `block` needs from the surrounding generated function.
pub struct Context<'a> {
    /// The expression graph, for the coefficients that are constants.
    pub graph: &'a Graph,
    /// A coefficient node as an operand (a literal, a leaf or a temporary computed before).
    pub op: &'a dyn Fn(NodeId) -> TokenStream,
    /// Names of all unknowns; the solve binds the block's own.
    pub unknowns: &'a [Ident],
    /// The name to bind a graph node (the `sin`/`cos` of an angle) that later code reads, or
    /// `None` when nothing reads it.
    pub bind: &'a dyn Fn(NodeId) -> Option<Ident>,
    /// The block's index, for its errors.
    pub block: usize,
    /// Path of the runtime's hidden re-exports.
    pub rt: &'a TokenStream,
    /// The kernel has a sweep's cache `__trig` to ask the angles of (see [`angle_of`]).
    pub trig: bool,
    /// A position-only solve: no analogs follow, whose factorisation's pivot ratio would report
    /// a position the data do not determine, so the solve tests for it itself (see
    /// [`lever_checks`]).
    pub position_only: bool,
    /// For an angle unknown whose lever is a variable length: its lever floor (see the plan's
    /// `magnitudes`).
    pub lever_floor: &'a dyn Fn(usize) -> Option<TokenStream>,
    /// The kernel's checks are switched by its constant `__CHECKED`, through its mode `__mode`
    /// (the runtime's `Checks`, see `solvers::deferred`); with `__CHECKED` false the solve tests
    /// nothing. The solve then also binds `__check{block}`, the sum of its sines and cosines and
    /// of the guesses only comparisons read, whose finiteness the kernel's end tests.
    pub deferred: bool,
    /// For a form solved from one equation of its angle alone (an angle equation, an angle and
    /// a slider), a closure computing the magnitude of that equation's terms (the plan's
    /// `BlockPlan::terms`) from the leaves, which the runtime's `folded_root_offset_in` and
    /// `dyad_roots_in` call only where the root fails, to judge a miss of its limit position.
    pub terms: Option<TokenStream>,
}

/// A value of the generated code: a constant known at expansion time or an expression. The
/// arithmetic below folds constants and drops the terms of zero coefficients (the compiler may
/// not: `0.0 * x` is not `0.0` for every `x`), so a link along an axis costs no multiplications.
#[derive(Clone)]
enum V {
    C(f64),
    E(TokenStream),
}

impl V {
    /// The constant, if this is one.
    fn constant(&self) -> Option<f64> {
        match self {
            V::C(c) => Some(*c),
            V::E(_) => None,
        }
    }
}

impl quote::ToTokens for V {
    fn to_tokens(&self, out: &mut TokenStream) {
        match self {
            V::C(c) => out.extend(float(*c)),
            V::E(t) => out.extend(t.clone()),
        }
    }
}

fn neg(a: &V) -> V {
    match a {
        V::C(x) => V::C(-x),
        V::E(t) => V::E(quote!((-#t))),
    }
}

fn mul(a: &V, b: &V) -> V {
    match (a, b) {
        (V::C(x), V::C(y)) => V::C(x * y),
        (V::C(z), _) | (_, V::C(z)) if *z == 0.0 => V::C(0.0),
        (V::C(o), e) | (e, V::C(o)) if *o == 1.0 => e.clone(),
        (V::C(m), e) | (e, V::C(m)) if *m == -1.0 => neg(e),
        _ => V::E(quote!((#a * #b))),
    }
}

fn add(a: &V, b: &V) -> V {
    match (a, b) {
        (V::C(x), V::C(y)) => V::C(x + y),
        (V::C(z), e) | (e, V::C(z)) if *z == 0.0 => e.clone(),
        _ => V::E(quote!((#a + #b))),
    }
}

fn sub(a: &V, b: &V) -> V {
    match (a, b) {
        (V::C(x), V::C(y)) => V::C(x - y),
        (e, V::C(z)) if *z == 0.0 => e.clone(),
        (V::C(z), e) if *z == 0.0 => neg(e),
        _ => V::E(quote!((#a - #b))),
    }
}

fn abs(a: &V) -> V {
    match a {
        V::C(x) => V::C(x.abs()),
        V::E(t) => V::E(quote!(#t.abs())),
    }
}

/// `a · x` for pairs `(a, x)`.
fn dot(terms: &[(&V, &V)]) -> V {
    terms.iter().fold(V::C(0.0), |acc, (a, x)| add(&acc, &mul(a, x)))
}

/// Binds a non-constant value to a local `name` (emitted into `out`).
fn bind(out: &mut TokenStream, name: &str, v: V) -> V {
    match v {
        V::C(_) => v,
        V::E(t) => {
            let id = format_ident!("{}", name);
            out.extend(quote!(let #id: ::core::primitive::f64 = #t;));
            V::E(quote!(#id))
        }
    }
}

fn local(name: &str) -> V {
    let id = format_ident!("{}", name);
    V::E(quote!(#id))
}

impl Context<'_> {
    fn v(&self, n: NodeId) -> V {
        match self.graph.as_const(n) {
            Some(c) => V::C(c),
            None => V::E((self.op)(n)),
        }
    }

    fn m(&self, m: &[[NodeId; 2]; 2]) -> [[V; 2]; 2] {
        m.map(|r| r.map(|n| self.v(n)))
    }
}

/// The `let` statements solving the block: binds its unknowns (and the bound sines and
/// cosines), returns a `NoAssembly` error from the enclosing function when there is no real
/// root, a `Singular` one when every angle is a root. Inside the solve, `__fail` adds the
/// block's location to a runtime `BlockFailure`.
pub fn solve(rec: &Recognised, cx: &Context) -> TokenStream {
    let body: TokenStream = match &rec.form {
        ClosedForm::AngleEquation { angle, a, b, c } => angle_equation(&cx.v(*a), &cx.v(*b), &cx.v(*c), *angle, cx),
        ClosedForm::Dyad { angles, m, reflect, e } => dyad(m, *reflect, e, *angles, cx),
        ClosedForm::PolarLength { angle, length, w, e } => polar(w, e, *angle, &guess_of(*length), cx),
        ClosedForm::AngleSlider { angle, m, d, e, .. } => angle_slider(m, d, e, *angle, cx),
    };
    // Unknowns: the angles, then the slider or length; then each angle's cosine and sine.
    let mut outs: Vec<TokenStream> = Vec::new();
    for u in rec.form.solve_order() {
        let q = &cx.unknowns[u];
        outs.push(quote!(#q));
    }
    for [s, c] in &rec.sin_cos {
        for n in [c, s] {
            outs.push(match (cx.bind)(*n) {
                Some(t) => quote!(#t),
                None => quote!(_),
            });
        }
    }
    let bl = Literal::usize_unsuffixed(cx.block);
    let rt = cx.rt;
    // The guess only picks the branch and the turn, through comparisons that a NaN would
    // silently answer. An angle's guess reaches the angle (moved to the guess's turn, it is
    // non-finite too) and `check_closed` rejects it; a length's or a slider's is checked first.
    let guess_check = rec.form.other_unknown().map(|_| {
        let guesses = rec.form.solve_order().into_iter().map(guess_of);
        quote!(#rt::check_guess(#(#guesses)+*).map_err(__fail)?;)
    });
    let angles = Literal::usize_unsuffixed(rec.form.angles().len());
    if cx.deferred {
        // Deferred, no test on the way: a failure leaves a non-finite output (see `root`), and
        // a non-finite length's or slider's guess a non-finite check sum. The unknowns are in
        // the state, whose sum the kernel's end tests: the check sums the sines and cosines.
        // (The angles' magnitudes are tested on their guesses, at the kernel's entry.)
        let check = format_ident!("__check{}", cx.block);
        let trig = (outs.len() - 2 * rec.sin_cos.len()..outs.len()).map(Literal::usize_unsuffixed);
        let guesses: Vec<TokenStream> = rec.form.other_unknown().map(guess_of).into_iter().collect();
        let guess_check = guess_check.map(|c| quote!(if __CHECKED { #c }));
        return quote! {
            let ([#(#outs),*], #check) = {
                let __fail = #rt::failure_of(self, #bl, __x, __guess, __cfg);
                #guess_check
                #body
                __mode.check_closed(&__out, #angles, __cfg).map_err(__fail)?;
                (__out, #(__out[#trig])+* #(+ #guesses)*)
            };
        };
    }
    let levers = lever_checks(&rec.form, cx);
    // The closure only captures references: it is `Copy`, one per block. A non-finite guess
    // makes the guesses' sum non-finite.
    quote! {
        let [#(#outs),*] = {
            let __fail = #rt::failure_of(self, #bl, __x, __guess, __cfg);
            #guess_check
            #levers
            #body
            #rt::check_closed(&__out, #angles, __cfg).map_err(__fail)?;
            __out
        };
    }
}

/// The tests of a position-only solve (see [`Context::position_only`]) for a position the data
/// do not determine, where the analogs' pivot ratio would be below the tolerance: an angle's
/// lever vector (whose length is the magnitude of the angle's Jacobian column) against its lever
/// floor, when it has one; and a dyad's centres against its links (centres that coincide leave
/// the dyad free to turn about them).
fn lever_checks(form: &ClosedForm, cx: &Context) -> TokenStream {
    let mut out = TokenStream::new();
    if !cx.position_only {
        return out;
    }
    let rt = cx.rt;
    for (u, [x, y]) in form.levers() {
        if let Some(floor) = (cx.lever_floor)(u) {
            let (x, y) = (cx.v(x), cx.v(y));
            out.extend(quote!(#rt::check_lever(#x, #y, #floor, __cfg).map_err(__fail)?;));
        }
    }
    if let Some((e, links)) = form.centres() {
        let link = |[x, y]: [NodeId; 2]| {
            let (x, y) = (cx.v(x), cx.v(y));
            add(&mul(&x, &x), &mul(&y, &y))
        };
        let (l0, l1) = (link(links[0]), link(links[1]));
        let (e0, e1) = (cx.v(e[0]), cx.v(e[1]));
        out.extend(quote!(#rt::check_centres(#e0, #e1, #l0, #l1, __cfg).map_err(__fail)?;));
    }
    out
}

/// Binds `__cq`, `__sq`: the root of `a cos q + b sin q = c` with `h' = -d < 0`, or with
/// `h' = d > 0` when `flip` holds. With no constant coefficient this is the runtime's
/// `dyad_roots` (`dyad_of` given a dyad's `links`, its centres' offset and its links' squared
/// lengths `[e0, e1, l0², l1²]`, from which its `d2` is recomputed where `a² + b² - c²`
/// cancels); otherwise the same formulas with the constants folded (a dyad's offset by
/// `folded_dyad_root_offset`, given its links as `dyad_of` is).
fn root(out: &mut TokenStream, a: &V, b: &V, c: &V, flip: &TokenStream, links: Option<[&V; 4]>, cx: &Context) {
    let rt = cx.rt;
    if let (V::E(_), V::E(_), V::E(_)) = (a, b, c) {
        let call = match (links, cx.deferred) {
            (Some([e0, e1, l0, l1]), deferred) => {
                let f = if deferred { quote!(__mode.dyad_of) } else { quote!(#rt::dyad_of) };
                out.extend(quote!(let __dyad: [::core::primitive::f64; 6] = [#a, #b, #e0, #e1, #l0, #l1];));
                quote!(#f(__dyad, #c, #flip, __cfg))
            }
            (None, deferred) => match (&cx.terms, deferred) {
                (Some(terms), true) => quote!(__mode.dyad_roots_in(#a, #b, #c, #flip, __cfg, #terms)),
                (Some(terms), false) => quote!(#rt::dyad_roots_in(#a, #b, #c, #flip, __cfg, #terms)),
                (None, true) => quote!(__mode.dyad_roots(#a, #b, #c, #flip, __cfg)),
                (None, false) => quote!(#rt::dyad_roots(#a, #b, #c, #flip, __cfg)),
            },
        };
        out.extend(quote!(let (__cq, __sq) = #call.map_err(__fail)?;));
        return;
    }
    let r2 = bind(out, "__r2", add(&mul(a, a), &mul(b, b)));
    let d2 = sub(&r2, &mul(c, c));
    // Deferred, a root that does not exist is NaN; a zero radius gives `0 · ∞` below, NaN too.
    // Given the coefficients too: where their squares leave the range of `f64` it rescales. A
    // dyad's gives its links too, for the residual of a dyad that cannot be assembled (the
    // gap of its lengths, as `dyad_of`'s).
    let root_offset = match links {
        Some([e0, e1, l0, l1]) => {
            let d2 = quote!(#rt::dyad_d2(#d2, #r2, [#e0, #e1, #l0, #l1]));
            let f =
                if cx.deferred { quote!(__mode.folded_dyad_root_offset) } else { quote!(#rt::folded_dyad_root_offset) };
            quote! {
                let __d: ::core::primitive::f64 =
                    #f(#d2, #r2, #a, #b, #c, [#e0, #e1, #l0, #l1], #flip, __cfg).map_err(__fail)?;
            }
        }
        None => {
            let f = match (&cx.terms, cx.deferred) {
                (Some(_), true) => quote!(__mode.folded_root_offset_in),
                (Some(_), false) => quote!(#rt::folded_root_offset_in),
                (None, true) => quote!(__mode.folded_root_offset),
                (None, false) => quote!(#rt::folded_root_offset),
            };
            let terms = cx.terms.as_ref().map(|t| quote!(, #t));
            quote!(let __d: ::core::primitive::f64 = #f(#d2, #r2, #a, #b, #c, #flip, __cfg #terms).map_err(__fail)?;)
        }
    };
    let d = local("__d");
    let zero = |v: &V| matches!(v, V::C(z) if *z == 0.0);
    // With one coefficient zero the formulas divide by the other, not by its square: `b sin q
    // = c` gives `(cos q, sin q) = (-d / b, c / b)`, `a cos q = c` gives `(c / a, d / a)`. The
    // value free of the square root is bound before it, ahead of the checked kernel's test of
    // the root: in one basic block with the other, LLVM multiplies the two as one vector, and
    // the angle's libm call (given that value) then waits for the square root (measured in
    // paired CPU time: the rhombic drive's point step takes 8 % longer so).
    if zero(a) {
        let ib = bind(out, "__ib", V::E(quote!((1.0 / #b))));
        let sq = mul(c, &ib);
        out.extend(quote!(let __sq: ::core::primitive::f64 = #sq; #root_offset));
        let cq = neg(&mul(&d, &ib));
        out.extend(quote!(let __cq: ::core::primitive::f64 = #cq;));
    } else if zero(b) {
        let ia = bind(out, "__ia", V::E(quote!((1.0 / #a))));
        let cq = mul(c, &ia);
        out.extend(quote!(let __cq: ::core::primitive::f64 = #cq; #root_offset));
        let sq = mul(&d, &ia);
        out.extend(quote!(let __sq: ::core::primitive::f64 = #sq;));
    } else {
        out.extend(root_offset);
        let inv = bind(out, "__inv", V::E(quote!((1.0 / #r2))));
        let cq = mul(&sub(&mul(a, c), &mul(b, &d)), &inv);
        let sq = mul(&add(&mul(b, c), &mul(a, &d)), &inv);
        out.extend(quote!(let __cq: ::core::primitive::f64 = #cq; let __sq: ::core::primitive::f64 = #sq;));
    }
}

/// `angle` moved by whole turns to the turn of `guess`.
fn on_turn(angle: TokenStream, guess: &TokenStream, cx: &Context) -> TokenStream {
    let rt = cx.rt;
    quote!(#rt::unwrap_to_turn(#angle, #guess))
}

/// The angle of unknown `u` with sine `s` and cosine `c`, which `exact` computes (by libm, on
/// the turn of the guess `__guess[u]`). In a sweep's kernel it is asked of the cache `__trig`,
/// which may advance it from its last exact value instead (`InputTrig::angle`).
fn angle_of(u: usize, s: TokenStream, c: TokenStream, exact: TokenStream, cx: &Context) -> TokenStream {
    if !cx.trig {
        return exact;
    }
    let k = Literal::usize_unsuffixed(u);
    quote!(__trig.angle(#k, #s, #c, || #exact))
}

/// `atan2(s, c)` of unknown `u`, moved by whole turns to the turn of its guess.
fn unwrapped(u: usize, s: TokenStream, c: TokenStream, cx: &Context) -> TokenStream {
    let g = guess_of(u);
    angle_of(u, s.clone(), c.clone(), on_turn(quote!(#s.atan2(#c)), &g, cx), cx)
}

/// The guess of unknown `u`.
fn guess_of(u: usize) -> TokenStream {
    let u = Literal::usize_unsuffixed(u);
    quote!(__guess[#u])
}

/// The sign rule for one angle: `h' = b cos g - a sin g > 0` at the guess `g`. With one
/// coefficient zero only the sign of the other function matters, read off `g` reduced to one
/// turn (no libm call; at the boundaries the guess sits on a limit position where both roots
/// meet). Otherwise `h'` from libm-free sines and cosines, whose error is below
/// `(|a| + |b|) δ`, when it exceeds three times that, else from libm's (the runtime's
/// `sign_at_guess`).
fn flip_at_guess(a: &V, b: &V, g: &TokenStream, cx: &Context) -> TokenStream {
    let zero = |v: &V| matches!(v, V::C(z) if *z == 0.0);
    let rt = cx.rt;
    if zero(a) {
        quote!((#b > 0.0) == (#rt::reduce_turn(#g).abs() < ::core::f64::consts::FRAC_PI_2))
    } else if zero(b) {
        quote!((#a > 0.0) == (#rt::reduce_turn(#g) < 0.0))
    } else {
        // The sign from libm-free sines and cosines when it is certain (beyond their error
        // bound), otherwise from libm's: the same decision either way.
        let bound = add(&abs(a), &abs(b));
        quote! {
            #rt::sign_at_guess(#g, 3.0 * #bound, |(__sg, __cg)| #b * __cg - #a * __sg) > 0.0
        }
    }
}

fn angle_equation(a: &V, b: &V, c: &V, u: usize, cx: &Context) -> TokenStream {
    let zero = |v: &V| matches!(v, V::C(z) if *z == 0.0);
    let rt = cx.rt;
    let g = &guess_of(u);
    if zero(a) {
        // `b sin q = c`: the root's cosine has the sign of the guess's (`h' = b cos q` keeps
        // its sign), so `asin` of the sine on the guess's side of the vertical, moved to its
        // turn by the reduction the sign rule made (the rule of `flip_at_guess`).
        let mut out = quote! {
            let __r: ::core::primitive::f64 = #rt::reduce_turn(#g);
            let __right: ::core::primitive::bool = __r.abs() < ::core::f64::consts::FRAC_PI_2;
            let __flip: ::core::primitive::bool = (#b > 0.0) == __right;
        };
        root(&mut out, a, b, c, &quote!(__flip), None, cx);
        // A sweep's cache advances it from its anchor, as every other closed-form angle: on the
        // rhombic drive that executed 62 fewer instructions a sample than libm's `asin` when it
        // was measured, though it waits for the cosine (the root's square root) where `asin`
        // needs only the sine, and took about as long in time.
        let exact = quote!(#rt::asin_near(__sq, __right, __r, #g));
        let q = angle_of(u, quote!(__sq), quote!(__cq), exact, cx);
        out.extend(quote!(let __out: [::core::primitive::f64; 3] = [#q, __cq, __sq];));
        return out;
    }
    let flip = flip_at_guess(a, b, g, cx);
    let mut out = quote!(let __flip: ::core::primitive::bool = #flip;);
    root(&mut out, a, b, c, &quote!(__flip), None, cx);
    // `a cos q = c`: `acos` of the cosine on the sine's side (cheaper than `atan2`).
    let q = if zero(b) {
        let exact = on_turn(quote!(#rt::acos_on_side(__cq, __sq)), g, cx);
        angle_of(u, quote!(__sq), quote!(__cq), exact, cx)
    } else {
        unwrapped(u, quote!(__sq), quote!(__cq), cx)
    };
    out.extend(quote!(let __out: [::core::primitive::f64; 3] = [#q, __cq, __sq];));
    out
}

/// Circle intersection: `|e + m0 c0| = |m1 c1| = l1` is linear in `c0 = (cos q0, sin q0)`:
/// `(m0ᵀ e) · c0 = (l1² - l0² - |e|²) / 2`; then `c1 = -m1ᵀ (e + m0 c0) / l1²`. At the roots
/// the determinant is `-ε1 h'` (`ε` = +1 for a rotation, -1 for a reflection); at the guess it
/// is `ε0 ε1 (u0 × u1)` with `u_i = m_i c_i`, so the root keeps `-h'` of the sign `ε0 (u0 × u1)`.
///
/// The cross product is one function of one angle: `u0 × u1 = c0ᵀ K c1` with `K = m0ᵀ J m1`
/// (`J` the quarter turn `[[0, 1], [-1, 0]]`) a scaled rotation when `m0`, `m1` are both
/// rotations or both reflections (`K11 = K00`, `K10 = -K01`), a scaled reflection otherwise, so
/// `u0 × u1 = K00 cos σ + K01 sin σ` with `σ = q1 - q0`, or `σ = q1 + q0` respectively: its
/// sign is that of [`flip_at_guess`]'s rule for one angle (no `sin_cos` at all when `K00` or
/// `K01` is zero, as for links without a constant offset angle). A sign read off `σ` reduced
/// to one turn can differ from libm's only where the guess is singular to rounding (parallel
/// links), where neither assembly mode is the guess's.
fn dyad(
    m: &[[[NodeId; 2]; 2]; 2],
    reflect: [bool; 2],
    e: &[NodeId; 2],
    angles: [usize; 2],
    cx: &Context,
) -> TokenStream {
    let (g0, g1) = (guess_of(angles[0]), guess_of(angles[1]));
    let (a, b) = (cx.m(&m[0]), cx.m(&m[1]));
    let e = e.map(|n| cx.v(n));
    let k = |i: usize, j: usize| sub(&mul(&a[0][i], &b[1][j]), &mul(&a[1][i], &b[0][j]));
    let (k00, k01) = (k(0, 0), k(0, 1));
    let sigma = if reflect[0] == reflect[1] { quote!((#g1 - #g0)) } else { quote!((#g1 + #g0)) };
    // The root keeps `-h'` of the sign `ε0 (u0 × u1)`: `flip` when `ε0 (u0 × u1) < 0`, i.e.
    // when `h'(σ) = b cos σ - a sin σ > 0` with `(a, b) = ±(K01, -K00)`.
    let (ca, cb) = if reflect[0] { (neg(&k01), k00) } else { (k01, neg(&k00)) };
    let rt = cx.rt;
    let flip = if matches!(cb, V::C(z) if z == 0.0) {
        // `h' = -a sin σ`: `σ` reduced to one turn has the sign of its sine (the product is
        // zero, no flip, for parallel links, where the sine is zero too).
        quote!(((#ca) * #rt::reduce_turn(#sigma)) < 0.0)
    } else {
        flip_at_guess(&ca, &cb, &sigma, cx)
    };
    let mut out = quote! {
        let __flip: ::core::primitive::bool = #flip;
    };
    let ca = bind(&mut out, "__a", dot(&[(&a[0][0], &e[0]), (&a[1][0], &e[1])]));
    let cb = bind(&mut out, "__b", dot(&[(&a[0][1], &e[0]), (&a[1][1], &e[1])]));
    let l0 = dot(&[(&a[0][0], &a[0][0]), (&a[1][0], &a[1][0])]);
    let l1 = bind(&mut out, "__l1", dot(&[(&b[0][0], &b[0][0]), (&b[1][0], &b[1][0])]));
    let ee = dot(&[(&e[0], &e[0]), (&e[1], &e[1])]);
    let cc = bind(&mut out, "__c", mul(&V::C(0.5), &sub(&sub(&l1, &l0), &ee)));
    root(&mut out, &ca, &cb, &cc, &quote!(__flip), Some([&e[0], &e[1], &l0, &l1]), cx);
    let (cq, sq) = (local("__cq"), local("__sq"));
    let vx = bind(&mut out, "__vx", add(&e[0], &dot(&[(&a[0][0], &cq), (&a[0][1], &sq)])));
    let vy = bind(&mut out, "__vy", add(&e[1], &dot(&[(&a[1][0], &cq), (&a[1][1], &sq)])));
    let il1 = bind(&mut out, "__il1", V::E(quote!((-1.0 / #l1))));
    let c1 = mul(&dot(&[(&b[0][0], &vx), (&b[1][0], &vy)]), &il1);
    let s1 = mul(&dot(&[(&b[0][1], &vx), (&b[1][1], &vy)]), &il1);
    let q0 = unwrapped(angles[0], quote!(__sq), quote!(__cq), cx);
    let q1 = unwrapped(angles[1], quote!(__s1), quote!(__c1), cx);
    out.extend(quote! {
        let __c1: ::core::primitive::f64 = #c1;
        let __s1: ::core::primitive::f64 = #s1;
        let __out: [::core::primitive::f64; 6] = [#q0, #q1, __cq, __sq, __c1, __s1];
    });
    out
}

/// `s w(q) + e = 0`: `w(q) ∥ e` gives `q` up to a half turn, `s = -(w·e) / |w|²`; the half turn
/// that keeps the guessed length's sign. The angle is `atan2` of the unnormalised direction
/// `(-a, b)`, called at once in a point step (it need not wait for the normalisation's division
/// and square root, which only the sine, cosine and length read), turned by a half turn when
/// the length's sign flips the direction.
fn polar(w: &[[NodeId; 2]; 2], e: &[NodeId; 2], u: usize, gs: &TokenStream, cx: &Context) -> TokenStream {
    let w = cx.m(w);
    let e = e.map(|n| cx.v(n));
    let mut out = TokenStream::new();
    let a = bind(&mut out, "__a", sub(&mul(&w[0][0], &e[1]), &mul(&w[1][0], &e[0])));
    let b = bind(&mut out, "__b", sub(&mul(&w[0][1], &e[1]), &mul(&w[1][1], &e[0])));
    let r2 = add(&mul(&a, &a), &mul(&b, &b));
    let (e0, e1, rt) = (&e[0], &e[1], cx.rt);
    // Not folded: `-a` keeps the sign of a zero, as the run-time model's `-a` does.
    let direction = quote!((-(#a)).atan2(#b));
    // A sweep's kernel asks its cache for the angle, which calls libm only when it must.
    let q0 = if cx.trig {
        direction
    } else {
        out.extend(quote!(let __q0: ::core::primitive::f64 = #direction;));
        quote!(__q0)
    };
    let f = if cx.deferred { quote!(__mode.polar_norm) } else { quote!(#rt::polar_norm) };
    out.extend(quote!(let __ir: ::core::primitive::f64 = #f(#r2, #e0, #e1, __cfg).map_err(__fail)?;));
    let ir = local("__ir");
    let (c0, s0) = (mul(&b, &ir), neg(&mul(&a, &ir)));
    out.extend(quote!(let (mut __cq, mut __sq): (::core::primitive::f64, ::core::primitive::f64) = (#c0, #s0);));
    let (cq, sq) = (local("__cq"), local("__sq"));
    let w0 = bind(&mut out, "__w0", dot(&[(&w[0][0], &cq), (&w[0][1], &sq)]));
    let w1 = bind(&mut out, "__w1", dot(&[(&w[1][0], &cq), (&w[1][1], &sq)]));
    let num = dot(&[(&w0, &e[0]), (&w1, &e[1])]);
    let s = match constant_norm2(w.each_ref().map(|r| r.each_ref().map(V::constant))) {
        // `w` a unit rotation or reflection: `|w(q)|² = 1`, nothing to divide by.
        Some(1.0) => neg(&num),
        Some(k2) => {
            let k2 = V::C(k2);
            V::E(quote!((-#num / #k2)))
        }
        None => {
            let den = dot(&[(&w0, &w0), (&w1, &w1)]);
            V::E(quote!((-#num / #den)))
        }
    };
    let exact = on_turn(quote!(#rt::half_turn_if(#q0, __flip)), &guess_of(u), cx);
    let q = angle_of(u, quote!(__sq), quote!(__cq), exact, cx);
    out.extend(quote! {
        let mut __s: ::core::primitive::f64 = #s;
        let __flip: ::core::primitive::bool = __s * #gs < 0.0;
        if __flip {
            __s = -__s;
            __cq = -__cq;
            __sq = -__sq;
        }
        let __out: [::core::primitive::f64; 4] = [#q, __s, __cq, __sq];
    });
    out
}

/// `m c + d s + e = 0`: the combination `d1 row0 - d0 row1` is free of `s` (and its derivative
/// in `q` is the block's determinant); then `s` by projection on `d`.
fn angle_slider(m: &[[NodeId; 2]; 2], d: &[NodeId; 2], e: &[NodeId; 2], u: usize, cx: &Context) -> TokenStream {
    let m = cx.m(m);
    let d = d.map(|n| cx.v(n));
    let e = e.map(|n| cx.v(n));
    let mut out = TokenStream::new();
    let a = bind(&mut out, "__a", sub(&mul(&d[1], &m[0][0]), &mul(&d[0], &m[1][0])));
    let b = bind(&mut out, "__b", sub(&mul(&d[1], &m[0][1]), &mul(&d[0], &m[1][1])));
    let c = bind(&mut out, "__c", sub(&mul(&d[0], &e[1]), &mul(&d[1], &e[0])));
    let flip = flip_at_guess(&a, &b, &guess_of(u), cx);
    out.extend(quote!(let __flip: ::core::primitive::bool = #flip;));
    root(&mut out, &a, &b, &c, &quote!(__flip), None, cx);
    let (cq, sq) = (local("__cq"), local("__sq"));
    let r0 = add(&dot(&[(&m[0][0], &cq), (&m[0][1], &sq)]), &e[0]);
    let r1 = add(&dot(&[(&m[1][0], &cq), (&m[1][1], &sq)]), &e[1]);
    let num = dot(&[(&d[0], &r0), (&d[1], &r1)]);
    let den = dot(&[(&d[0], &d[0]), (&d[1], &d[1])]);
    let q = unwrapped(u, quote!(__sq), quote!(__cq), cx);
    out.extend(quote! {
        let __s: ::core::primitive::f64 = -#num / #den;
        let __out: [::core::primitive::f64; 4] = [#q, __s, __cq, __sq];
    });
    out
}

/// Removes the `sin`/`cos` nodes of closed-form angles from the scheduled `let`s (their solve
/// defines them) and returns those that were scheduled (some later code reads them).
pub fn take_trig(plan: &Plan, lets: &mut [Vec<NodeId>]) -> HashSet<NodeId> {
    let provided: HashSet<NodeId> =
        plan.blocks.iter().filter_map(|bp| bp.solve.closed_form()).flat_map(|c| c.sin_cos.concat()).collect();
    let mut bound = HashSet::new();
    for l in lets {
        l.retain(|n| {
            let p = provided.contains(n);
            if p {
                bound.insert(*n);
            }
            !p
        });
    }
    bound
}
