//! Names the generated code cannot use, rejected with one error each instead of the pages of
//! compiler errors they would cause in the expansion.
//!
//! The mechanism's name becomes a type next to the user's code, and the generated code names
//! the primitive `f64`, the crates `core` and `kinloop`, and a type parameter `T`: a mechanism
//! called `f64` or `T` would shadow them. Every declared name becomes a field or an identifier
//! of the generated code, so a keyword that the parser lets through (`gen`, reserved since the
//! 2024 edition) cannot be one. A raw identifier (`r#gen`) is always accepted.

use super::syntax::{DeclKind, ItemKind, MechanismDef};
use syn::Ident;
use syn::ext::IdentExt;

/// Primitive types: the generated code uses `f64` and the others must not be shadowed either.
const PRIMITIVES: &[&str] = &[
    "bool", "char", "str", "f16", "f32", "f64", "f128", "i8", "i16", "i32", "i64", "i128", "isize", "u8", "u16", "u32",
    "u64", "u128", "usize",
];

/// Crates the generated code refers to, or that user code expects to find under these names.
const CRATES: &[&str] = &["kinloop", "core", "std", "alloc"];

/// Type parameters of the generated companion types (`NameInputs<T>`, ...).
const TYPE_PARAMETERS: &[&str] = &["T"];

/// Keywords syn accepts as identifiers but a current edition does not.
const RESERVED: &[&str] = &["gen"];

/// Tuple and unit variants of the standard prelude: the generated code binds declared names as
/// variables (`let [r, l] = ...`), and Rust does not let a binding shadow a variant, raw or not.
const PRELUDE_VARIANTS: &[(&str, &str)] =
    &[("Some", "Option"), ("None", "Option"), ("Ok", "Result"), ("Err", "Result")];

/// Why `name` cannot name the mechanism, with what to write instead.
pub fn mechanism_name_problem(name: &Ident) -> Option<String> {
    if let Some(m) = reserved_problem(name, "the mechanism") {
        return Some(m);
    }
    // `r#f64` names the same type as `f64`.
    let s = name.unraw().to_string();
    let camel = camel_case(&s);
    let kind = if PRIMITIVES.contains(&s.as_str()) {
        "a primitive type that the generated code uses"
    } else if CRATES.contains(&s.as_str()) {
        "the name of a crate that the generated code refers to"
    } else if TYPE_PARAMETERS.contains(&s.as_str()) {
        "the type parameter of the generated types (`NameInputs<T>`, ...)"
    } else {
        return None;
    };
    Some(format!("a mechanism cannot be called `{s}`: it is {kind}; choose another name, e.g. `{camel}Mechanism`"))
}

/// Why a declared name (parameter, input, unknown, `let`, `point`, `output`, `loop` or `eq`
/// name) cannot be used, with what to write instead.
pub fn reserved_problem(name: &Ident, what: &str) -> Option<String> {
    let plain = name.unraw().to_string();
    if let Some((v, ty)) = PRELUDE_VARIANTS.iter().find(|(v, _)| *v == plain) {
        let instead = if what == "the mechanism" { format!("{v}Mechanism") } else { v.to_lowercase() };
        return Some(format!(
            "`{v}` is the prelude's variant `{ty}::{v}` and cannot name {what}: the generated code binds declared \
             names as variables and refers to `{v}`, which such a name would shadow; choose another name such as \
             `{instead}`"
        ));
    }
    let s = name.to_string();
    RESERVED.contains(&s.as_str()).then(|| {
        format!(
            "`{s}` is a reserved keyword in Rust 2024 and cannot name {what} in the generated code; \
             choose another name such as `{s}_`, or write the raw identifier `r#{s}`"
        )
    })
}

/// `f64` -> `F64`, `kinloop` -> `Kinloop`: a start for a suggested name.
fn camel_case(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

/// What a declaration item's name is, for messages (`None` for `params`, `input`, `unknowns`).
fn item_name(kind: &ItemKind) -> Option<(&Ident, &'static str)> {
    match kind {
        ItemKind::Decls(..) => None,
        ItemKind::Let { name, .. } => Some((name, "a `let`")),
        ItemKind::Point { name, .. } => Some((name, "a `point`")),
        ItemKind::Output { name, .. } => Some((name, "an `output`")),
        ItemKind::Loop { name, .. } => Some((name, "a `loop`")),
        ItemKind::Eq { name, .. } => Some((name, "an `eq`")),
        ItemKind::Body(_) | ItemKind::Force { .. } | ItemKind::Torque { .. } | ItemKind::Gravity { .. } => None,
    }
}

fn decl_what(kind: DeclKind) -> &'static str {
    match kind {
        DeclKind::Params => "a parameter",
        DeclKind::Inputs => "an input",
        DeclKind::Unknowns => "an unknown",
    }
}

/// One error per name of `def` that cannot be used. The declarations and items with such a
/// name are removed from `def`, so that the fallback items emitted next to the errors do not
/// use the name either. Returns whether the mechanism's own name is usable (without it, no
/// fallback item can be emitted at all).
pub fn check(def: &mut MechanismDef) -> (bool, Vec<syn::Error>) {
    let mut errors: Vec<syn::Error> = Vec::new();
    let name_ok = match mechanism_name_problem(&def.name) {
        Some(m) => {
            errors.push(syn::Error::new(def.name.span(), m));
            false
        }
        None => true,
    };
    def.items.retain_mut(|item| {
        if let ItemKind::Decls(kind, decls) = &mut item.kind {
            let what = decl_what(*kind);
            decls.retain(|d| match reserved_problem(&d.name, what) {
                Some(m) => {
                    errors.push(syn::Error::new(d.name.span(), m));
                    false
                }
                None => true,
            });
            return true;
        }
        match item_name(&item.kind).and_then(|(name, what)| Some((name, reserved_problem(name, what)?))) {
            Some((name, m)) => {
                errors.push(syn::Error::new(name.span(), m));
                false
            }
            None => true,
        }
    });
    (name_ok, errors)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proc_macro2::Span;

    fn ident(s: &str) -> Ident {
        match s.strip_prefix("r#") {
            Some(raw) => Ident::new_raw(raw, Span::call_site()),
            None => Ident::new(s, Span::call_site()),
        }
    }

    #[test]
    fn every_primitive_crate_and_type_parameter_is_refused_as_mechanism_name() {
        for s in PRIMITIVES.iter().chain(CRATES).chain(TYPE_PARAMETERS) {
            let m = mechanism_name_problem(&ident(s)).unwrap_or_else(|| panic!("`{s}` accepted"));
            assert!(m.starts_with(&format!("a mechanism cannot be called `{s}`")), "{m}");
            // The suggestion is itself a valid, accepted name.
            let suggested = m.rsplit('`').nth(1).expect("a suggested name");
            assert!(mechanism_name_problem(&ident(suggested)).is_none(), "{suggested}");
        }
        assert_eq!(camel_case("f64"), "F64");
        assert_eq!(camel_case(""), "");
    }

    #[test]
    fn reserved_words_are_refused_everywhere_but_raw_identifiers_pass() {
        let m = reserved_problem(&ident("gen"), "a parameter").expect("refused");
        assert!(m.contains("`gen_`") && m.contains("`r#gen`"), "{m}");
        assert!(reserved_problem(&ident("r#gen"), "a parameter").is_none());
        assert!(mechanism_name_problem(&ident("r#gen")).is_none());
        assert!(mechanism_name_problem(&ident("r#f64")).is_some(), "a raw `f64` still shadows the type");
        for variant in ["Some", "None", "Ok", "Err", "r#Some"] {
            let m = reserved_problem(&ident(variant), "a parameter").expect("refused");
            assert!(m.contains("choose another name such as `"), "{m}");
            assert!(mechanism_name_problem(&ident(variant)).expect("refused").contains("Mechanism`"), "{variant}");
        }
        for fine in ["generator", "Gen", "phi", "F64", "kinloop_arm", "Tt", "some", "ok", "Okay", "Nonempty"] {
            assert!(reserved_problem(&ident(fine), "a parameter").is_none(), "{fine}");
            assert!(mechanism_name_problem(&ident(fine)).is_none(), "{fine}");
        }
    }
}
