//! Parsing a whole declaration: the entry points of the front, from tokens to a checked syntax
//! tree.
//!
//! [`parse_recover`] runs the front's stages in order: the size limits on the raw tokens
//! ([`super::limits`]), the declaration's head (attributes, visibility, name) and its body, one
//! item at a time (`item`), then the names the generated code cannot use ([`super::names`]).
//! It sits above them all and above the tree they share ([`super::syntax`]), so none of them
//! imports it.
//!
//! The parser recovers at `;` after an error, so all syntax errors of a declaration are reported
//! together.

use super::item::{inner_attribute, list_continued, not_struct_doc, parse_item, skip_item};
use super::suggest::similar;
use super::syntax::{Errors, MechanismDef, Options};
use super::{limits, names};
use proc_macro2::{Span, TokenStream};
use syn::parse::{ParseStream, Parser};
use syn::{Attribute, Ident, Token, Visibility};

/// Parses a declaration. Never panics; all syntax errors found are combined into one.
pub fn parse(tokens: TokenStream) -> Result<MechanismDef, syn::Error> {
    match parse_recover(tokens) {
        (Some(def), None) => Ok(def),
        (_, Some(e)) => Err(e),
        (None, None) => Err(syn::Error::new(Span::call_site(), SHAPE)),
    }
}

/// Parses a declaration as far as it goes: the declaration (with the items that parsed) as soon
/// as its name is known, and the combined syntax errors, if any. The partial declaration lets
/// the macro emit fallback items next to the errors.
pub fn parse_recover(tokens: TokenStream) -> (Option<MechanismDef>, Option<syn::Error>) {
    // Before syn sees the tokens: its token buffer recurses into every bracket.
    if let Err(e) = limits::check(&tokens) {
        return (None, Some(e));
    }
    let (def, errors) = parse_tokens(tokens);
    let Some(mut def) = def else { return (None, errors) };
    let (name_ok, problems) = names::check(&mut def);
    let mut all = Errors(errors);
    for e in problems {
        all.push(e);
    }
    (name_ok.then_some(def), all.into_error())
}

/// The parser proper, on tokens whose size and depth [`limits::check`] accepted.
fn parse_tokens(tokens: TokenStream) -> (Option<MechanismDef>, Option<syn::Error>) {
    let mut out = None;
    // The parser stores its own verdict in `out`: syn's end-of-input checks cannot then replace
    // the collected errors by a generic "unexpected token" after recovery skipped some tokens.
    let verdict = (|input: ParseStream| {
        out = Some(parse_def(input));
        skip_all(input);
        Ok(())
    })
    .parse2(tokens);
    match out {
        Some((def, errors)) => (def, errors.into_error()),
        None => (None, Some(verdict.err().unwrap_or_else(|| syn::Error::new(Span::call_site(), SHAPE)))),
    }
}

fn skip_all(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((_, next)) = rest.token_tree() {
            rest = next;
        }
        Ok(((), rest))
    });
}

const SHAPE: &str = "expected a declaration: `pub struct Name { params ...; input ...; unknowns ...; loop ...; }`";

fn parse_def(input: ParseStream) -> (Option<MechanismDef>, Errors) {
    let mut errors = Errors::default();
    let def = parse_def_into(input, &mut errors);
    (def, errors)
}

/// Parses the declaration, pushing every error into `errors`; returns the declaration once its
/// name is known (with the items that parsed), `None` before that.
fn parse_def_into(input: ParseStream, errors: &mut Errors) -> Option<MechanismDef> {
    let fail = |errors: &mut Errors, e: syn::Error| {
        errors.push(e);
        None
    };
    if input.is_empty() {
        return fail(errors, input.error(SHAPE));
    }
    loop {
        match inner_attribute(input) {
            Ok(Some(e)) => errors.push(e),
            Ok(None) => break,
            Err(e) => return fail(errors, e),
        }
    }
    if let Some(span) = macro_around(input) {
        return fail(
            errors,
            syn::Error::new(
                span,
                "write the declaration itself, without `mechanism! { ... }` around it: \
                 `pub struct Name { params ...; input ...; unknowns ...; loop ...; }`",
            ),
        );
    }
    let attrs = match Attribute::parse_outer(input) {
        Ok(a) => a,
        Err(e) => return fail(errors, e),
    };
    let (docs, options) = split_attributes(attrs, errors);
    let vis: Visibility = match input.parse() {
        Ok(v) => v,
        Err(e) => return fail(errors, e),
    };
    if !input.peek(Token![struct]) {
        return fail(errors, input.error(SHAPE));
    }
    if let Err(e) = input.parse::<Token![struct]>() {
        return fail(errors, e);
    }
    let name: Ident = match input.parse() {
        Ok(n) => n,
        Err(_) => return fail(errors, keyword_as_name(input)),
    };
    let mut def = MechanismDef { docs, options, vis, name, items: Vec::new(), body: Span::call_site() };
    def.body = def.name.span();
    if input.peek(Token![<]) {
        errors.push(input.error(
            "a mechanism cannot be generic; remove `<...>`: its parameters are `f64` fields declared with `params`",
        ));
        return Some(def);
    }
    if !input.peek(syn::token::Brace) {
        errors.push(input.error("expected `{` with the mechanism's items: `pub struct Name { params ...; ... }`"));
        return Some(def);
    }
    if let Err(e) = parse_body(input, &mut def, errors) {
        errors.push(e);
    }
    if !input.is_empty() {
        errors.push(
            input.error("unexpected tokens after the mechanism's `{ ... }`; declare one mechanism per `mechanism!`"),
        );
        skip_all(input);
    }
    Some(def)
}

/// The span of `mechanism` when `input` starts with an invocation of the macro
/// (`mechanism!`, `kinloop::mechanism!`): a declaration copied with the macro around it.
fn macro_around(input: ParseStream) -> Option<Span> {
    let fork = input.fork();
    let path = fork.call(syn::Path::parse_mod_style).ok()?;
    let last = path.segments.last()?;
    (last.ident == "mechanism" && fork.peek(Token![!])).then(|| last.ident.span())
}

/// Splits the attributes before a mechanism into its doc comments and its `#[kinloop(...)]`
/// options, pushing an error for any other attribute.
fn split_attributes(attrs: Vec<Attribute>, errors: &mut Errors) -> (Vec<Attribute>, Options) {
    let mut docs = Vec::new();
    let mut options = Options::default();
    for attr in attrs {
        if attr.path().is_ident("doc") {
            match not_struct_doc(&attr) {
                Some(e) => errors.push(e),
                None => docs.push(attr),
            }
        } else if attr.path().is_ident("kinloop") {
            if let Err(e) = attr.parse_nested_meta(|meta| parse_option(&meta, &mut options, errors)) {
                errors.push(quoted_option(&attr).unwrap_or(e));
            }
        } else {
            let msg = if attr.path().is_ident("derive") {
                "remove `#[derive(...)]`: kinloop derives Clone, Copy, Debug and PartialEq itself, \
                 and implements Default when every parameter has a default value"
                    .to_string()
            } else {
                // A misspelt `kinloop` (`kinlop`, `Kinloop`) is named with the word meant.
                let word = attr.path().get_ident().map(Ident::to_string).unwrap_or_default();
                let kinloop = ["kinloop".to_string()];
                let hint = match similar(&word, kinloop.iter()) {
                    Some(k) => format!(" (did you mean `#[{k}(...)]`?)"),
                    None => String::new(),
                };
                format!(
                    "only doc comments (`///`) and `#[kinloop(...)]` options (`dense`, `newton`, `sensitivities`) \
                     are accepted before a mechanism{hint}"
                )
            };
            errors.push(syn::Error::new_spanned(attr.path(), msg));
        }
    }
    (docs, options)
}

/// The options `#[kinloop(...)]` takes.
const OPTIONS: [&str; 3] = ["dense", "newton", "sensitivities"];

/// One option of `#[kinloop(...)]`, recorded with its span. A value given to it (`dense = 1`,
/// `dense(1)`) or an option given twice is reported and the rest still read: syn's own message
/// for the first is a bare "expected `,`", and the second changed nothing without a word.
fn parse_option(meta: &syn::meta::ParseNestedMeta, options: &mut Options, errors: &mut Errors) -> syn::Result<()> {
    let span = meta.path.get_ident().map_or(Span::call_site(), Ident::span);
    let (option, name) = if meta.path.is_ident("dense") {
        (&mut options.dense, "dense")
    } else if meta.path.is_ident("sensitivities") {
        (&mut options.sensitivities, "sensitivities")
    } else if meta.path.is_ident("newton") {
        // Closed-form hook: the option forcing Newton.
        (&mut options.newton, "newton")
    } else {
        // A misspelt option (`Dense`, `newtn`) is named with the option meant.
        let word = meta.path.get_ident().map(Ident::to_string).unwrap_or_default();
        let options: Vec<String> = OPTIONS.iter().map(|o| o.to_string()).collect();
        let hint = match similar(&word, options.iter()) {
            Some(o) => format!(" (did you mean `{o}`?)"),
            None => String::new(),
        };
        return Err(meta.error(format!(
            "unknown kinloop option{hint}; the supported options are `#[kinloop(dense)]`, \
             `#[kinloop(newton)]` and `#[kinloop(sensitivities)]`"
        )));
    };
    if let Some(value) = option_value(meta)? {
        // `dense newton`: the next option without its `,`, not a value of this one.
        let next = value.clone().into_iter().next().and_then(|t| match t {
            proc_macro2::TokenTree::Ident(id) if OPTIONS.contains(&id.to_string().as_str()) => Some(id),
            _ => None,
        });
        let msg = match next {
            Some(next) => format!("options are separated by `,`: write `#[kinloop({name}, {next})]`"),
            None => format!("kinloop options take no value: write `#[kinloop({name})]`"),
        };
        errors.push(syn::Error::new_spanned(value, msg));
    }
    match option {
        Some(_) => errors.push(syn::Error::new(span, format!("the option `{name}` is given twice; keep one"))),
        None => *option = Some(span),
    }
    Ok(())
}

/// The error for an option written as a string, `#[kinloop("dense")]`, saying to write it as a
/// name; syn's own message ("expected ident") names neither. `None` for anything else.
fn quoted_option(attr: &Attribute) -> Option<syn::Error> {
    let syn::Meta::List(list) = &attr.meta else { return None };
    let lit = list.tokens.clone().into_iter().find_map(|t| match t {
        proc_macro2::TokenTree::Literal(lit) => Some(lit),
        _ => None,
    })?;
    let syn::Lit::Str(text) = syn::Lit::new(lit.clone()) else { return None };
    let text = text.value();
    let msg = if OPTIONS.contains(&text.as_str()) {
        format!("an option is a name, not a string: write `#[kinloop({text})]`")
    } else {
        "an option is a name, not a string: `#[kinloop(dense)]`, `#[kinloop(newton)]` or \
         `#[kinloop(sensitivities)]`"
            .to_string()
    };
    Some(syn::Error::new(lit.span(), msg))
}

/// The tokens after an option's name up to the next `,` (a value: `= 1`, `(1)`), consumed;
/// `None` when there are none.
fn option_value(meta: &syn::meta::ParseNestedMeta) -> syn::Result<Option<TokenStream>> {
    let mut value = TokenStream::new();
    while !meta.input.is_empty() && !meta.input.peek(Token![,]) {
        value.extend([meta.input.parse::<proc_macro2::TokenTree>()?]);
    }
    Ok((!value.is_empty()).then_some(value))
}

/// Parses `{ items }`, recovering at `;` after an item's error.
fn parse_body(input: ParseStream, def: &mut MechanismDef, errors: &mut Errors) -> syn::Result<()> {
    let content;
    let brace = syn::braced!(content in input);
    def.body = brace.span.join();
    while !content.is_empty() {
        match list_continued(&content, &mut def.items, errors) {
            Ok(true) => continue,
            Ok(false) => {}
            Err(e) => {
                errors.push(e);
                skip_item(&content);
                continue;
            }
        }
        match parse_item(&content, errors) {
            Ok(item) => def.items.push(item),
            Err(e) => {
                errors.push(e);
                skip_item(&content);
            }
        }
    }
    Ok(())
}

/// The error for what stands where the mechanism's name belongs and is none: a Rust keyword
/// (`pub struct Self`, `pub struct type`), which is said to be one, or anything else.
fn keyword_as_name(input: ParseStream) -> syn::Error {
    match input.fork().call(<Ident as syn::ext::IdentExt>::parse_any) {
        Ok(word) if word == "_" => syn::Error::new(
            word.span(),
            "`_` is Rust's placeholder, not a name, and cannot be the mechanism's name: give it a name, \
             `pub struct Name { ... }`",
        ),
        Ok(word) => syn::Error::new(
            word.span(),
            format!(
                "`{word}` is a Rust keyword and cannot be the mechanism's name, which names the generated types: \
                 choose another name, `pub struct Name {{ ... }}`"
            ),
        ),
        Err(_) => input.error("expected the mechanism's name: `pub struct Name { ... }`"),
    }
}
