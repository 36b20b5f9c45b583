//! kinloop's own `Serialize` and `Deserialize` derives, which the structs `mechanism!` generates
//! name (`kinloop::__gen::{Serialize, Deserialize}` with the facade's feature `serde`): serde's
//! impls, with every value handed to the format through the runtime's number adapter
//! (`kinloop::__gen::FloatsSer`, `FloatsDe`). A generated struct written alone then writes a
//! non-finite number as the string Rust prints (`"NaN"`, `"inf"`, `"-inf"`) and reads it back,
//! as it already did inside a state, where serde's plain derive wrote JSON's `null`, which did
//! not read back as the number written.
//!
//! Why a derive and not an attribute per field: the expansion of `mechanism!` is bounded in size
//! and stays as it was; the work is done where the derive expands.
//!
//! How: serde's own derive on a hidden twin of the struct, declared `remote` for it, does the
//! field-by-field work with serde's exact semantics (names, `skip`, missing fields); the impl
//! emitted here calls the twin's functions with the format's serializer or deserializer wrapped
//! in the adapter. A field the struct does not have is an error naming it and the fields it has
//! (the twin denies unknown fields): with serde's default, a parameter set with a misspelt
//! parameter (`r_pp` beside `r_p`) was read without a word. A container `into` (`from`) is
//! honoured directly: the converted value is written (read) through the same adapter.
//!
//! The derives take what `mechanism!` generates and nothing else: a struct with named fields,
//! type parameters only, the container arguments `runtime`, `from`, `into` and the field argument
//! `skip`. Anything else is a compile error naming it, never a panic.
//!
//! `runtime = path` is where the generated code finds the runtime (`kinloop::__gen` as the
//! invocation of `mechanism!` named it: `$crate::__gen` through the facade's wrapper, so a
//! renamed dependency works), and the derives with it serde (`path::serde`) and the adapter:
//! a path in tokens, not in serde's string, which cannot hold `$crate`. What takes strings names
//! the two by aliases that the emitted block declares: the types of `from` and `into` the runtime
//! as `__kinloop_gen` (see `RUNTIME_ALIAS`), serde's own derive on the twin serde as
//! `__kinloop_serde`.

use crate::emit::runtime_path::RUNTIME_ALIAS;
use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::ext::IdentExt;
use syn::{Attribute, Data, DeriveInput, Fields, GenericParam, Ident, LitStr, Type};

/// `#[derive(FloatsSerialize)]`: `Serialize` with every number through `FloatsSer`.
pub fn derive_serialize(input: TokenStream) -> TokenStream {
    derive(input, Direction::Serialize)
}

/// `#[derive(FloatsDeserialize)]`: `Deserialize` with every number through `FloatsDe`.
pub fn derive_deserialize(input: TokenStream) -> TokenStream {
    derive(input, Direction::Deserialize)
}

#[derive(Clone, Copy, PartialEq)]
enum Direction {
    Serialize,
    Deserialize,
}

fn derive(input: TokenStream, dir: Direction) -> TokenStream {
    match syn::parse2::<DeriveInput>(input).and_then(|d| Shape::of(&d).map(|s| s.emit(dir))) {
        Ok(tokens) => tokens,
        Err(e) => e.to_compile_error(),
    }
}

/// The alias of serde in the block the derives emit, for serde's own derive on the twin, which
/// takes paths as strings.
const SERDE_ALIAS: &str = "__kinloop_serde";

/// The container's `serde` arguments the derives honour.
struct Container {
    /// Where the runtime is (`runtime = path`; `::kinloop::__gen` otherwise): the adapter's
    /// module, and serde's parent.
    runtime: TokenStream,
    /// serde, as the impls name it: `runtime::serde`.
    krate: TokenStream,
    from: Option<Type>,
    into: Option<Type>,
}

/// One field: its name, type and whether serde skips it.
struct Field {
    name: Ident,
    ty: Type,
    skip: bool,
}

/// What the derives read of the struct.
struct Shape<'a> {
    input: &'a DeriveInput,
    container: Container,
    fields: Vec<Field>,
}

impl<'a> Shape<'a> {
    fn of(input: &'a DeriveInput) -> syn::Result<Shape<'a>> {
        let unsupported = |msg: &str| Err(syn::Error::new_spanned(&input.ident, msg));
        let named = match &input.data {
            Data::Struct(s) => match &s.fields {
                Fields::Named(named) => named,
                _ => return unsupported("kinloop's serde derives take a struct with named fields"),
            },
            _ => return unsupported("kinloop's serde derives take a struct with named fields"),
        };
        if input.generics.params.iter().any(|p| !matches!(p, GenericParam::Type(_))) {
            return unsupported("kinloop's serde derives take type parameters only");
        }
        let fields = named.named.iter().map(field).collect::<syn::Result<_>>()?;
        Ok(Shape { input, container: container(&input.attrs)?, fields })
    }

    fn emit(&self, dir: Direction) -> TokenStream {
        let body = match (dir, &self.container.into, &self.container.from) {
            (Direction::Serialize, Some(into), _) => self.serialize_into(into),
            (Direction::Deserialize, _, Some(from)) => self.deserialize_from(from),
            _ => self.through_twin(dir),
        };
        // In an anonymous constant: the twin's name cannot clash with the user's. serde's derive
        // writes primitive types bare (`&str`, `usize`), which an item of the user's module
        // named like one would shadow (`type str = [u8];`): imported here, they are the
        // primitives again, since a block's own names come before its module's.
        quote! {
            const _: () = {
                #[allow(unused_imports)]
                use ::core::primitive::{
                    bool, char, f32, f64, i8, i16, i32, i64, i128, isize, str, u8, u16, u32, u64, u128, usize,
                };
                #body
            };
        }
    }

    /// The impl's generic parameters (without defaults), `'de` first for `Deserialize`.
    fn impl_params(&self, dir: Direction) -> TokenStream {
        let params = self.input.generics.type_params().map(|p| {
            let (name, bounds) = (&p.ident, &p.bounds);
            if bounds.is_empty() { quote!(#name) } else { quote!(#name: #bounds) }
        });
        match dir {
            Direction::Serialize => quote!(<#(#params),*>),
            Direction::Deserialize => quote!(<'de, #(#params),*>),
        }
    }

    /// `Name<T, ..>`.
    fn self_ty(&self) -> TokenStream {
        let name = &self.input.ident;
        let params: Vec<&Ident> = self.input.generics.type_params().map(|p| &p.ident).collect();
        if params.is_empty() { quote!(#name) } else { quote!(#name<#(#params),*>) }
    }

    /// The struct's own where-clause predicates, each followed by a comma.
    fn own_predicates(&self) -> TokenStream {
        let preds = self.input.generics.where_clause.iter().flat_map(|w| w.predicates.iter());
        quote!(#(#preds,)*)
    }

    /// The trait implemented, as named in the impl.
    fn trait_path(&self, dir: Direction) -> TokenStream {
        let krate = &self.container.krate;
        match dir {
            Direction::Serialize => quote!(#krate::Serialize),
            Direction::Deserialize => quote!(#krate::Deserialize<'de>),
        }
    }

    /// The type parameters that need the trait: those a field serde does not skip mentions (as
    /// serde's derive infers its bounds).
    fn bounded(&self) -> Vec<&Ident> {
        let kept: Vec<&Type> = self.fields.iter().filter(|f| !f.skip).map(|f| &f.ty).collect();
        self.input
            .generics
            .type_params()
            .map(|p| &p.ident)
            .filter(|p| kept.iter().any(|ty| mentions(quote!(#ty), p)))
            .collect()
    }

    /// The impl: the twin's remote functions, handed the adapter.
    fn through_twin(&self, dir: Direction) -> TokenStream {
        let Shape { input, container, .. } = self;
        let (krate, runtime) = (&container.krate, &container.runtime);
        let alias = Ident::new(SERDE_ALIAS, Span::call_site());
        let twin = Ident::new("__KinloopSerdeTwin", Span::call_site());
        let (name, generics) = (&input.ident, &input.generics);
        let where_clause = &generics.where_clause;
        let remote = name.to_string();
        let rename = name.unraw().to_string();
        let trait_path = self.trait_path(dir);
        let bounded = self.bounded();
        // The twin's bounds are strings to serde: they name serde by the alias.
        let twin_trait = match dir {
            Direction::Serialize => quote!(#alias::Serialize),
            Direction::Deserialize => quote!(#alias::Deserialize<'de>),
        };
        let bound_text = bounded.iter().map(|p| format!("{p}: {}", quote!(#twin_trait))).collect::<Vec<_>>().join(", ");
        let (derive, bound_arg, deny) = match dir {
            Direction::Serialize => (quote!(#alias::Serialize), quote!(serialize = #bound_text), quote!()),
            Direction::Deserialize => {
                (quote!(#alias::Deserialize), quote!(deserialize = #bound_text), quote!(, deny_unknown_fields))
            }
        };
        let fields = self.fields.iter().map(|f| {
            let (n, ty) = (&f.name, &f.ty);
            let skip = f.skip.then(|| quote!(#[serde(skip)]));
            quote!(#skip #n: #ty)
        });
        let (params, self_ty, preds, a) = (self.impl_params(dir), self.self_ty(), self.own_predicates(), runtime);
        let method = match dir {
            Direction::Serialize => quote! {
                fn serialize<__S: #krate::Serializer>(&self, __serializer: __S)
                    -> ::core::result::Result<__S::Ok, __S::Error> {
                    #twin::serialize(self, #a::FloatsSer(__serializer))
                }
            },
            Direction::Deserialize => quote! {
                fn deserialize<__D: #krate::Deserializer<'de>>(__deserializer: __D)
                    -> ::core::result::Result<Self, __D::Error> {
                    #twin::deserialize(#a::FloatsDe(__deserializer))
                }
            },
        };
        quote! {
            use #krate as #alias;
            #[derive(#derive)]
            #[serde(crate = #SERDE_ALIAS, remote = #remote, rename = #rename, bound(#bound_arg) #deny)]
            #[allow(dead_code, non_snake_case, non_camel_case_types)]
            struct #twin #generics #where_clause { #(#fields),* }
            #[automatically_derived]
            impl #params #trait_path for #self_ty where #preds #(#bounded: #trait_path),* {
                #method
            }
        }
    }

    /// `Serialize` through `into`: the converted value, written through the adapter.
    fn serialize_into(&self, into: &Type) -> TokenStream {
        let (krate, a) = (&self.container.krate, &self.container.runtime);
        let (params, self_ty, preds) = (self.impl_params(Direction::Serialize), self.self_ty(), self.own_predicates());
        let alias = Ident::new(RUNTIME_ALIAS, Span::call_site());
        quote! {
            use #a as #alias;
            #[automatically_derived]
            impl #params #krate::Serialize for #self_ty
            where #preds Self: ::core::clone::Clone + ::core::convert::Into<#into>, #into: #krate::Serialize {
                fn serialize<__S: #krate::Serializer>(&self, __serializer: __S)
                    -> ::core::result::Result<__S::Ok, __S::Error> {
                    let __v: #into = ::core::convert::Into::into(::core::clone::Clone::clone(self));
                    #krate::Serialize::serialize(&__v, #a::FloatsSer(__serializer))
                }
            }
        }
    }

    /// `Deserialize` through `from`: the value read through the adapter, converted.
    fn deserialize_from(&self, from: &Type) -> TokenStream {
        let (krate, a) = (&self.container.krate, &self.container.runtime);
        let (params, self_ty, preds) =
            (self.impl_params(Direction::Deserialize), self.self_ty(), self.own_predicates());
        let alias = Ident::new(RUNTIME_ALIAS, Span::call_site());
        quote! {
            use #a as #alias;
            #[automatically_derived]
            impl #params #krate::Deserialize<'de> for #self_ty
            where #preds Self: ::core::convert::From<#from>, #from: #krate::Deserialize<'de> {
                fn deserialize<__D: #krate::Deserializer<'de>>(__deserializer: __D)
                    -> ::core::result::Result<Self, __D::Error> {
                    let __v = <#from as #krate::Deserialize<'de>>::deserialize(#a::FloatsDe(__deserializer))?;
                    ::core::result::Result::Ok(::core::convert::From::from(__v))
                }
            }
        }
    }
}

/// `ty` names the type parameter `p` somewhere within.
fn mentions(ty: TokenStream, p: &Ident) -> bool {
    ty.into_iter().any(|t| match t {
        proc_macro2::TokenTree::Ident(i) => &i == p,
        proc_macro2::TokenTree::Group(g) => mentions(g.stream(), p),
        _ => false,
    })
}

/// The container's `serde` arguments: `runtime = path` in tokens, `from` and `into` types in
/// strings (naming the runtime `__kinloop_gen`); any other is an error.
fn container(attrs: &[Attribute]) -> syn::Result<Container> {
    let mut runtime = quote!(::kinloop::__gen);
    let (mut from, mut into) = (None, None);
    for attr in attrs.iter().filter(|a| a.path().is_ident("serde")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("runtime") {
                let path: syn::Path = meta.value()?.parse()?;
                runtime = quote!(#path);
            } else if meta.path.is_ident("from") {
                // `LitStr::parse`: a string that is no type is an error at the string.
                from = Some(meta.value()?.parse::<LitStr>()?.parse()?);
            } else if meta.path.is_ident("into") {
                into = Some(meta.value()?.parse::<LitStr>()?.parse()?);
            } else {
                return Err(meta.error("kinloop's serde derives take `runtime`, `from` and `into` on the struct"));
            }
            Ok(())
        })?;
    }
    Ok(Container { krate: quote!(#runtime::serde), runtime, from, into })
}

/// A field, with its `serde` argument `skip`; any other is an error.
fn field(f: &syn::Field) -> syn::Result<Field> {
    let name = f.ident.clone().ok_or_else(|| syn::Error::new_spanned(&f.ty, "a field without a name"))?;
    let mut skip = false;
    for attr in f.attrs.iter().filter(|a| a.path().is_ident("serde")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("skip") {
                skip = true;
                Ok(())
            } else {
                Err(meta.error("kinloop's serde derives take `skip` on a field"))
            }
        })?;
    }
    Ok(Field { name, ty: f.ty.clone(), skip })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message of the one `compile_error!` `out` is, or `None` when it is not one.
    fn error_of(out: &TokenStream) -> Option<String> {
        let text = out.to_string();
        text.contains("compile_error").then_some(text)
    }

    /// Each shape the derives do not take is a compile error saying what they take, in both
    /// directions, never a panic nor an impl that would fail to compile in the user's crate.
    #[test]
    fn what_the_derives_do_not_take_is_a_compile_error_naming_it() {
        let cases = [
            (
                quote!(
                    enum E {
                        A(f64),
                    }
                ),
                "a struct with named fields",
            ),
            (
                quote!(
                    struct T(f64);
                ),
                "a struct with named fields",
            ),
            (
                quote!(
                    struct U;
                ),
                "a struct with named fields",
            ),
            (
                quote!(
                    struct L<'a> {
                        x: &'a f64,
                    }
                ),
                "type parameters only",
            ),
            (
                quote!(
                    struct C<const N: usize> {
                        x: [f64; N],
                    }
                ),
                "type parameters only",
            ),
            (
                quote!(
                    #[serde(deny_unknown_fields)]
                    struct D {
                        x: f64,
                    }
                ),
                "`runtime`, `from` and `into`",
            ),
            (
                quote!(
                    #[serde(runtime = "not a path")]
                    struct P {
                        x: f64,
                    }
                ),
                "expected",
            ),
            (
                quote!(
                    #[serde(from)]
                    struct F {
                        x: f64,
                    }
                ),
                "expected `=`",
            ),
            (
                quote!(
                    struct R {
                        #[serde(rename = "y")]
                        x: f64,
                    }
                ),
                "`skip` on a field",
            ),
            (quote!(not an item), "expected"),
        ];
        for (input, says) in cases {
            for out in [derive_serialize(input.clone()), derive_deserialize(input.clone())] {
                let msg = error_of(&out).unwrap_or_else(|| panic!("{input}: no error but {out}"));
                assert!(msg.contains(says), "{input}: {msg}");
            }
        }
    }

    /// A generated struct's shapes expand to impls (no error): generic with a skipped marker,
    /// plain, and converted through `from`/`into`; the values go through the adapter.
    #[test]
    fn the_shapes_mechanism_generates_expand_through_the_adapter() {
        let krate = quote!(#[serde(runtime = ::kinloop::__gen)]);
        let inputs = [
            quote!(#krate struct O<T = f64> { #[doc(hidden)] #[serde(skip)] pub __marker: ::core::marker::PhantomData<T>, }),
            quote!(#krate #[allow(non_snake_case)] struct P { /// doc
                pub r#a: f64, pub B: f64 }),
            quote!(
                #[serde(runtime = ::kinloop::__gen, from = "X<A>", into = "X<A>")]
                struct S {
                    pub q: f64,
                }
            ),
        ];
        for input in inputs {
            let (ser, de) = (derive_serialize(input.clone()), derive_deserialize(input.clone()));
            assert!(error_of(&ser).is_none() && error_of(&de).is_none(), "{input}: {ser} {de}");
            assert!(ser.to_string().contains("FloatsSer"), "{ser}");
            assert!(de.to_string().contains("FloatsDe"), "{de}");
        }
    }

    /// A type parameter gets the trait bound only where a field serde writes mentions it: the
    /// struct without fields but its skipped marker serializes for any `T`, as serde's derive
    /// infers.
    #[test]
    fn only_parameters_of_written_fields_are_bounded() {
        let marker = quote!(
            struct O<T = f64> {
                #[serde(skip)]
                pub m: ::core::marker::PhantomData<T>,
            }
        );
        let text = derive_serialize(marker).to_string();
        assert!(text.contains("bound (serialize = \"\")"), "{text}");
        let point = quote!(
            struct V<T = f64> {
                pub p: Vec2<T>,
            }
        );
        let text = derive_serialize(point).to_string();
        assert!(text.contains("bound (serialize = \"T: __kinloop_serde :: Serialize\")"), "{text}");
    }

    /// Every path the impls name starts at `runtime`: under another name than `kinloop` (a
    /// renamed dependency, reached through `$crate`), nothing of the output names `::kinloop`,
    /// and serde's derive on the twin gets serde by the alias the block declares.
    #[test]
    fn every_path_starts_at_the_runtime_given() {
        let inputs = [
            quote!(
                #[serde(runtime = ::kl::__gen)]
                struct O<T = f64> {
                    #[serde(skip)]
                    pub m: ::core::marker::PhantomData<T>,
                }
            ),
            quote!(
                #[serde(runtime = ::kl::__gen, from = "__kinloop_gen::X<A>", into = "__kinloop_gen::X<A>")]
                struct S {
                    pub q: f64,
                }
            ),
        ];
        for input in &inputs {
            for out in [derive_serialize(input.clone()), derive_deserialize(input.clone())] {
                let text = out.to_string();
                assert!(error_of(&out).is_none(), "{text}");
                assert!(!text.contains(":: kinloop") && !text.contains("\"::kinloop"), "{text}");
                assert!(text.contains(":: kl :: __gen :: Floats"), "{text}");
                assert!(text.contains(":: kl :: __gen :: serde ::"), "{text}");
            }
        }
        let twin = derive_serialize(inputs[0].clone()).to_string();
        assert!(twin.contains("use :: kl :: __gen :: serde as __kinloop_serde"), "{twin}");
        assert!(twin.contains("crate = \"__kinloop_serde\""), "{twin}");
        // `from` and `into` name the runtime by the alias the impls' block declares.
        for out in [derive_serialize(inputs[1].clone()), derive_deserialize(inputs[1].clone())] {
            let text = out.to_string();
            assert!(text.contains("use :: kl :: __gen as __kinloop_gen"), "{text}");
            assert!(text.contains("__kinloop_gen :: X < A >"), "{text}");
        }
    }
}
