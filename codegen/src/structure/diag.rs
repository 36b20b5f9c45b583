//! Warnings from a procedural macro on stable Rust.
//!
//! `proc_macro::Diagnostic` (real warnings) is unstable. The stable way is to make the compiler
//! issue a lint at the user's span: the macro emits a `#[deprecated(note = "...")]` associated
//! constant on the mechanism's type and uses it once, with the offending token's span, in an
//! anonymous `const _` item. The compiler then prints
//!
//! ```text
//! warning: use of deprecated associated constant `FourBar::unused_parameter_m`: parameter `m` is used in no loop, ...
//!  --> src/main.rs:4:22
//!   |
//! 4 |         params a, b, m;
//!   |                      ^
//! ```
//!
//! It is an ordinary lint: it never fails a build by itself (unless the crate denies
//! `deprecated`), and `#[allow(deprecated)]` on the enclosing module silences it. Only
//! diagnostics that leave the mechanism well posed are warnings; everything else is an error.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{quote, quote_spanned};

/// A warning at one span.
pub struct Warning {
    /// Where the compiler points: the offending token in the declaration.
    pub span: Span,
    /// Name of the deprecated constant, shown first by the compiler (a valid identifier).
    pub tag: String,
    /// The text after the constant's name: what is wrong and what to do.
    pub message: String,
}

/// Items that make the compiler print `warnings`, attached to the mechanism's type `owner`
/// (which must be defined next to them).
pub fn to_tokens(warnings: &[Warning], owner: &Ident) -> TokenStream {
    let mut taken = std::collections::HashSet::new();
    warnings
        .iter()
        .enumerate()
        .map(|(k, w)| {
            // Associated constants of one type need distinct names.
            let mut tag = sanitize(&w.tag);
            if !taken.insert(tag.clone()) {
                tag = format!("{tag}_{k}");
                taken.insert(tag.clone());
            }
            let def = Ident::new(&tag, Span::call_site());
            // The whole path carries the warning's span, so the compiler underlines just it.
            let used = Ident::new(&tag, w.span);
            let mut ty = owner.clone();
            ty.set_span(w.span);
            let note = &w.message;
            let use_it = quote_spanned!(w.span=> #ty::#used);
            // The impl is outside any `const _` block so that the compiler names the constant
            // `Owner::tag` (inside, it would print `_::<impl Owner>::tag`).
            quote! {
                impl #owner {
                    #[deprecated(note = #note)]
                    #[allow(non_upper_case_globals)]
                    const #def: () = ();
                }
                const _: () = #use_it;
            }
        })
        .collect()
}

/// An identifier from `tag`: ASCII letters, digits and `_` kept, anything else (the `r#` of a
/// raw identifier, non-ASCII letters) replaced by `_`.
fn sanitize(tag: &str) -> String {
    let s: String = tag.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) || s == "_" { format!("w_{s}") } else { s }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_become_identifiers() {
        assert_eq!(sanitize("unused_parameter_r#type"), "unused_parameter_r_type");
        assert_eq!(sanitize("1a"), "w_1a");
        assert_eq!(sanitize(""), "w_");
        assert_eq!(sanitize("unused_parameter_λ"), "unused_parameter__");
        // Every sanitized tag is accepted by `Ident::new` (which panics otherwise).
        for t in ["", "_", "1", "r#x", "λ", "a b", "unused_parameter_x"] {
            let _ = Ident::new(&sanitize(t), Span::call_site());
        }
    }
}
