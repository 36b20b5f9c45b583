//! The path generated code reaches the runtime by.
//!
//! `kinloop::mechanism!` is a `macro_rules!` wrapper in the facade that calls the procedural
//! macro with the marker `#![crate = $crate]` before the declaration: `$crate` names the facade
//! whatever the user's crate calls it (a dependency renamed in `Cargo.toml`, a facade of the
//! user's own re-exporting kinloop), which no name the procedural macro could write does. The
//! marker's path is the root of every path of the expansion (`$crate::__gen`); an invocation
//! without it (the code generator called directly, as tests and benchmarks do) names the facade
//! `::kinloop`.

use proc_macro2::{Delimiter, TokenStream, TokenTree};
use quote::quote;
use std::cell::RefCell;

thread_local! {
    /// The facade's path for the expansion in progress on this thread (`None`: `::kinloop`).
    /// Held here rather than passed to every emitter: it is one fact about the whole expansion,
    /// set once where it begins, and the twenty-odd emitters that name the runtime all take it.
    static ROOT: RefCell<Option<TokenStream>> = const { RefCell::new(None) };
}

/// The name kinloop's serde derives give the runtime in the block they emit, by which a type in
/// their `from` and `into` strings names it (`"__kinloop_gen::StateByName<..>"`): a string
/// cannot hold `$crate`, and a type written in tokens there would be broken by the formatter over
/// a line per generic argument.
pub const RUNTIME_ALIAS: &str = "__kinloop_gen";

/// The path generated code uses to reach the runtime: `__gen` of the facade, as the invocation
/// named it (see [`with_root`]).
pub fn runtime() -> TokenStream {
    let root = ROOT.with_borrow(Clone::clone).unwrap_or_else(|| quote!(::kinloop));
    quote!(#root::__gen)
}

/// Runs `f` (one expansion) with `root` as the facade's path, `::kinloop` when it is `None`,
/// and restores the path it found, even if `f` unwinds.
pub fn with_root<R>(root: Option<TokenStream>, f: impl FnOnce() -> R) -> R {
    struct Restore(Option<TokenStream>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            ROOT.with_borrow_mut(|r| *r = previous);
        }
    }
    let _restore = Restore(ROOT.with_borrow_mut(|r| std::mem::replace(r, root)));
    f()
}

/// Splits the wrapper's marker `#![crate = path]` off the front of an invocation: the path, and
/// the declaration after it. An invocation that does not begin with the marker comes back whole.
pub fn split_root(input: TokenStream) -> (Option<TokenStream>, TokenStream) {
    let mut tokens = input.clone().into_iter();
    let marker = match (tokens.next(), tokens.next(), tokens.next()) {
        (Some(TokenTree::Punct(hash)), Some(TokenTree::Punct(bang)), Some(TokenTree::Group(g)))
            if hash.as_char() == '#' && bang.as_char() == '!' && g.delimiter() == Delimiter::Bracket =>
        {
            g.stream()
        }
        _ => return (None, input),
    };
    let mut inside = marker.into_iter();
    match (inside.next(), inside.next()) {
        (Some(TokenTree::Ident(k)), Some(TokenTree::Punct(eq))) if k == "crate" && eq.as_char() == '=' => {
            let path: TokenStream = inside.collect();
            if path.is_empty() { (None, input) } else { (Some(path), tokens.collect()) }
        }
        _ => (None, input),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The marker's path becomes the root of the runtime's path for the expansion, and only for
    /// it; the declaration comes back without the marker.
    #[test]
    fn the_marker_names_the_facade_for_one_expansion() {
        let (root, rest) = split_root(quote!(#![crate = ::kl] pub struct S {}));
        assert_eq!(
            rest.to_string(),
            quote!(
                pub struct S {}
            )
            .to_string()
        );
        let inside = with_root(root, runtime);
        assert_eq!(inside.to_string(), quote!(::kl::__gen).to_string());
        assert_eq!(runtime().to_string(), quote!(::kinloop::__gen).to_string());
    }

    /// Without the marker (or with something else in its place), the invocation is the
    /// declaration, whole, and the facade is `::kinloop`.
    #[test]
    fn without_the_marker_the_declaration_is_whole() {
        for input in [
            quote!(
                pub struct S {}
            ),
            quote!(#![kinloop(dense)] pub struct S {}),
            quote!(#![crate] pub struct S {}),
            quote!(#![crate =] pub struct S {}),
            quote!(
                #[crate = ::kl]
                pub struct S {}
            ),
            quote!(),
        ] {
            let (root, rest) = split_root(input.clone());
            assert!(root.is_none(), "{input}");
            assert_eq!(rest.to_string(), input.to_string());
        }
    }

    /// A ring of `k` four-bar loops closed through a differential: one Newton block of `2k`
    /// unknowns, sparse from 16 on.
    fn ring(k: usize) -> String {
        let unknowns: Vec<String> = (0..k).map(|i| format!("u{i} = 0.6, v{i} = 1.9")).collect();
        let loops: Vec<String> = (0..k)
            .map(|i| {
                let drive = if i == 0 { format!("(0.5 * (phi + v{}))", k - 1) } else { format!("v{}", i - 1) };
                format!("loop l{i}: a @ {drive} + b @ u{i} == (d, 0) + c @ v{i};")
            })
            .collect();
        format!(
            "pub struct Ring {{ params a = 1.0, b = 3.0, c = 2.5, d = 3.2; input phi; unknowns {}; {} }}",
            unknowns.join(", "),
            loops.join(" ")
        )
    }

    /// Every emitter names the runtime by the marker's path: the expansions of declarations that
    /// reach each of them (closed forms, Newton and sparse Newton blocks, several inputs, the
    /// sensitivities, the dynamics, the states' serde conversions, the fallback after an error)
    /// name `::kl::__gen` and never `::kinloop`, in code or in the derives' attributes.
    #[test]
    fn every_path_of_an_expansion_starts_at_the_marker() {
        let declarations = [
            "#[kinloop(sensitivities)] pub struct Crank {
                 params r = 1.0, l = 3.0, m = 2.0, g = 9.81;
                 input phi;
                 unknowns psi = 0, x = r + l;
                 loop oabc: r @ phi + l @ psi == (x, 0);
                 point mid = r @ phi + 0.5 * l @ psi;
                 output gap = x - r;
                 body rod: mass m, com mid, inertia m * l * l / 12, turns psi;
                 force push at mid = (1, 0);
                 gravity (0, -g);
             }"
            .to_string(),
            "#[kinloop(newton)] pub struct FiveBar {
                 params a = 1.0, b = 2.5, c = 2.5, d = 1.0, e = 2.0;
                 inputs th1, th2;
                 unknowns al = 1.2, be = 2.0;
                 loop l: a @ th1 + b @ al == (e, 0) + d @ th2 + c @ be;
                 point p = a @ th1 + b @ al;
             }"
            .to_string(),
            ring(9),
            // Rejected (an unknown name): the fallback declares the named types.
            "pub struct Broken { params r; input phi; unknowns psi = 0; eq e: r * cos(psi) == q; }".to_string(),
        ];
        for (i, decl) in declarations.iter().enumerate() {
            let tokens: TokenStream = format!("#![crate = ::kl] {decl}").parse().unwrap();
            let text = crate::expand(tokens).to_string();
            // All accepted but the last, the rejected one.
            assert_eq!(text.contains("compile_error"), i == 3, "{decl}: {text}");
            // The ring is one sparse Newton block (its pattern is emitted beside the kernels).
            assert_eq!(text.contains("SparsePattern"), i == 2, "{decl}: {text}");
            assert!(text.contains(":: kl :: __gen ::"), "{decl}: {text}");
            assert!(!text.contains(":: kinloop") && !text.contains("\"::kinloop"), "{decl}: {text}");
        }
    }
}
