//! Parsing one item of a declaration's body (`params ...;`, `let ...;`, `loop ...;`, ...), with
//! the messages that say what to write instead, and the recovery that skips a broken item.
//! The dynamics' items are parsed in `dynamics`; the declaration around the items in
//! `declaration`.

use super::dynamics::{parse_body, parse_force, parse_torque};
use super::expr::{Expr, SpanRange, misplaced_doc_comment, parse_expr, starts_an_item};
use super::syntax::{Decl, DeclKind, Errors, Item, ItemKind, kw};
use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{Attribute, Ident, Token, Visibility};

/// Parses one item. A missing `;` after a complete item is pushed to `errors` and the item is
/// kept, so the next item is parsed normally.
pub(super) fn parse_item(input: ParseStream, errors: &mut Errors) -> syn::Result<Item> {
    if input.peek(Token![;]) {
        // Left for the recovery, which skips to just after it.
        return Err(input.error("unexpected `;`: the item before it is already ended by its own `;`; remove this one"));
    }
    while let Some(e) = inner_attribute(input)? {
        errors.push(e);
    }
    let attrs = Attribute::parse_outer(input)?;
    if input.is_empty()
        && let Some(last) = attrs.last()
    {
        return Err(syn::Error::new_spanned(
            last,
            "this doc comment documents no item: none follows it; remove it, or write a plain comment with `//`",
        ));
    }
    let mut docs = Vec::new();
    for attr in attrs {
        if !attr.path().is_ident("doc") {
            // Said, and the item read all the same: its names keep their fields in the fallback
            // types, so the code that uses them adds no error of its own.
            errors.push(syn::Error::new_spanned(
                &attr,
                "only doc comments (`///`) are accepted before an item; remove this attribute",
            ));
            continue;
        }
        match not_a_doc_comment(&attr) {
            Some(e) => errors.push(e),
            None => docs.push(attr),
        }
    }
    if input.peek(Token![pub]) {
        // `pub point p = ...`, as a Rust field or item is written: said, then the item is read
        // as if the visibility were not there, so that its names keep their fields.
        let vis: Visibility = input.parse()?;
        let tokens = quote::ToTokens::to_token_stream(&vis);
        errors.push(syn::Error::new_spanned(&tokens, format!("remove `{}`: {VISIBILITY}", written(&tokens))));
    }
    let keyword = input.span();
    let look = input.lookahead1();
    let kind = if look.peek(kw::params) || look.peek(kw::param) {
        skip_keyword(input)?;
        ItemKind::Decls(DeclKind::Params, parse_decls(input, DeclKind::Params, errors)?)
    } else if look.peek(kw::input) || look.peek(kw::inputs) {
        skip_keyword(input)?;
        ItemKind::Decls(DeclKind::Inputs, parse_decls(input, DeclKind::Inputs, errors)?)
    } else if look.peek(kw::unknowns) || look.peek(kw::unknown) {
        skip_keyword(input)?;
        ItemKind::Decls(DeclKind::Unknowns, parse_decls(input, DeclKind::Unknowns, errors)?)
    } else if look.peek(Token![let]) {
        input.parse::<Token![let]>()?;
        let (name, value) = parse_binding(input, "let")?;
        ItemKind::Let { name, value }
    } else if look.peek(kw::point) {
        input.parse::<kw::point>()?;
        let (name, value) = match named_value(input, "point", errors)? {
            Named::Parsed(name, value) => (name, value),
            Named::Broken(name, value) => return Ok(Item { docs, keyword, kind: ItemKind::Point { name, value } }),
        };
        ItemKind::Point { name, value }
    } else if look.peek(kw::output) {
        input.parse::<kw::output>()?;
        let (name, value) = match named_value(input, "output", errors)? {
            Named::Parsed(name, value) => (name, value),
            Named::Broken(name, value) => return Ok(Item { docs, keyword, kind: ItemKind::Output { name, value } }),
        };
        ItemKind::Output { name, value }
    } else if look.peek(Token![loop]) {
        input.parse::<Token![loop]>()?;
        let (name, lhs, rhs, eq) = parse_equation(input, "loop")?;
        ItemKind::Loop { name, lhs, rhs, eq }
    } else if look.peek(kw::eq) {
        input.parse::<kw::eq>()?;
        let (name, lhs, rhs, eq) = parse_equation(input, "eq")?;
        ItemKind::Eq { name, lhs, rhs, eq }
    } else if look.peek(kw::body) {
        input.parse::<kw::body>()?;
        ItemKind::Body(parse_body(input)?)
    } else if look.peek(kw::force) {
        input.parse::<kw::force>()?;
        parse_force(input)?
    } else if look.peek(kw::torque) {
        input.parse::<kw::torque>()?;
        parse_torque(input)?
    } else if look.peek(kw::gravity) {
        input.parse::<kw::gravity>()?;
        if input.peek(Token![=]) && !input.peek(Token![==]) {
            // `gravity = (0, -g);`: the item gives its vector as `force` and `torque` give
            // theirs, but has no name to give it to.
            return Err(input.error("`gravity` takes its vector without `=`: write `gravity (0, -g);`"));
        }
        let value = parse_expr(input)?;
        if input.peek(Token![,]) {
            // `gravity 0, -g;`: the components without the parentheses of a vector.
            return Err(value
                .range()
                .error("gravity is one vector: write its components in parentheses, as in `gravity (0, -g);`"));
        }
        ItemKind::Gravity { value }
    } else {
        let mut err = look.error();
        let mut recovered = None;
        // Rust's own keywords too (`const`, `fn`): syn's message for them lists its peeks.
        if let Ok(id) = input.fork().call(<Ident as syn::ext::IdentExt>::parse_any) {
            let meant = meant_keyword(&id);
            let hint = meant.as_ref().map(|k| format!(" (did you mean `{k}`?)")).unwrap_or_default();
            err = if hint.is_empty() && equation_ahead(input) {
                // `y == 2 * x;`: an equation without its keyword and name, not a misspelt item.
                syn::Error::new(
                    id.span(),
                    format!(
                        "`{id}` does not start an item: an equation starts with `eq` and its name, \
                         `eq name: lhs == rhs;` (`loop name: lhs == rhs;` for vectors)"
                    ),
                )
            } else {
                syn::Error::new(id.span(), format!("`{id}` does not start an item{hint}; {ITEMS}"))
            };
            recovered = meant.and_then(|k| declared_as(input, &k));
        }
        match recovered {
            Some(kind) => {
                errors.push(err);
                kind
            }
            None => return Err(err),
        }
    };
    let item = Item { docs, keyword, kind };
    if let Err(e) = expect_semicolon(input, &item) {
        errors.push(e);
        // Go on at the next item; anything else before it belongs to this broken item.
        if !starts_an_item(input) {
            skip_item(input);
        }
    }
    Ok(item)
}

/// The error for a `doc` attribute that is not what a doc comment becomes, `#[doc = "text"]`:
/// the docs pass to the generated items as written, and rustc refuses `#[doc = 1]` there with
/// a message about code the user did not write. `None` for a doc comment.
pub(super) fn not_a_doc_comment(attr: &Attribute) -> Option<syn::Error> {
    if let syn::Meta::NameValue(nv) = &attr.meta
        && let syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(_), .. }) = &nv.value
    {
        return None;
    }
    Some(syn::Error::new_spanned(
        attr,
        "this `doc` attribute is not a doc comment: write the documentation as a doc comment, `/// ...`",
    ))
}

/// [`not_a_doc_comment`] for an attribute on the mechanism's struct, which passes to the
/// generated struct as written: Rust's other documentation attributes are also taken there
/// (`#[doc(hidden)]`, `#[doc = include_str!("..")]`).
pub(super) fn not_struct_doc(attr: &Attribute) -> Option<syn::Error> {
    match &attr.meta {
        syn::Meta::List(_) => None,
        syn::Meta::NameValue(nv) if matches!(nv.value, syn::Expr::Macro(_)) => None,
        _ => not_a_doc_comment(attr),
    }
}

/// An inner doc comment (`//!` or `/*! ... */`, which the compiler turns into `#![doc = ...]`) or inner
/// attribute (`#![...]`) at the front of `input`: consumed, and the error that says what to
/// write instead. syn's own message for it ("expected square brackets") names neither.
pub(super) fn inner_attribute(input: ParseStream) -> syn::Result<Option<syn::Error>> {
    if !(input.peek(Token![#]) && input.peek2(Token![!])) {
        return Ok(None);
    }
    let pound = input.parse::<Token![#]>()?;
    input.parse::<Token![!]>()?;
    let is_doc = if input.peek(syn::token::Bracket) {
        let content;
        syn::bracketed!(content in input);
        let is_doc = content.peek(kw::doc);
        content.parse::<proc_macro2::TokenStream>()?;
        is_doc
    } else {
        false
    };
    // A block comment `/*! ... */` is the same attribute as a line's `//!`: its source text
    // tells which was written (none where the tokens have no source, as in a macro's output).
    let block = pound.span.source_text().is_some_and(|t| t.starts_with("/*!"));
    let what = match (is_doc, block) {
        (true, true) => "an inner doc comment (`/*! ... */`)",
        (true, false) => "an inner doc comment (`//!`)",
        (false, _) => "an inner attribute (`#![...]`)",
    };
    Ok(Some(syn::Error::new(
        pound.span,
        format!(
            "{what} is not accepted in a declaration; document the mechanism or an item with `///` \
             before it, or write a plain comment with `//`"
        ),
    )))
}

/// A name after a `params`, `input` or `unknowns` list that a `;` ended, as in `unknowns psi =
/// 0.5; x = 1;`: a `;` written for the `,` between names. Its error says to write the `,` ("does
/// not start an item" named no fix), and the names up to the next `;` join the list, so that
/// they keep their fields in the fallback items. Returns whether `input` started so.
pub(super) fn list_continued(input: ParseStream, items: &mut [Item], errors: &mut Errors) -> syn::Result<bool> {
    let Some(Item { kind: ItemKind::Decls(kind, decls), .. }) = items.last_mut() else { return Ok(false) };
    let Some(last) = decls.last().map(|d| d.name.clone()) else { return Ok(false) };
    if starts_an_item(input) {
        return Ok(false);
    }
    let Some((name, rest)) = input.cursor().ident() else { return Ok(false) };
    let declared = match rest.punct() {
        Some((p, after)) => match p.as_char() {
            ',' | ';' => true,
            '=' => after.punct().is_none_or(|(q, _)| q.as_char() != '='),
            _ => false,
        },
        None => false,
    };
    if !declared {
        return Ok(false);
    }
    let keyword = match kind {
        DeclKind::Params => "params",
        DeclKind::Inputs => "inputs",
        DeclKind::Unknowns => "unknowns",
    };
    errors.push(syn::Error::new(
        name.span(),
        format!(
            "`{name}` does not start an item: to declare it with the `{keyword}` before, separate the names \
             with `,`, not `;` (`{keyword} ..., {last}, {name}`)"
        ),
    ));
    decls.extend(parse_decls(input, *kind, errors)?);
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
    } else if !starts_an_item(input) {
        skip_item(input);
    }
    Ok(true)
}

/// Whether the tokens up to the next `;` hold a `==` (outside brackets): an equation.
fn equation_ahead(input: ParseStream) -> bool {
    let mut cursor = input.cursor();
    while let Some((tt, next)) = cursor.token_tree() {
        match &tt {
            proc_macro2::TokenTree::Punct(p) if p.as_char() == ';' => return false,
            proc_macro2::TokenTree::Punct(p)
                if p.as_char() == '='
                    && p.spacing() == proc_macro2::Spacing::Joint
                    && next.punct().is_some_and(|(q, _)| q.as_char() == '=') =>
            {
                return true;
            }
            _ => {}
        }
        cursor = next;
    }
    false
}

/// The words that start an item, for did-you-mean suggestions.
const KEYWORDS: &[&str] = &[
    "params", "input", "inputs", "unknowns", "let", "loop", "eq", "point", "output", "body", "force", "torque",
    "gravity",
];

/// Words of other languages for an item's keyword, with the keyword to write.
const KEYWORD_ALIASES: &[(&str, &str)] =
    &[("parameters", "params"), ("const", "params"), ("var", "unknowns"), ("equation", "eq"), ("constraint", "eq")];

/// The keyword meant by `word`, a misspelt one (`lop` for `loop`) or another language's word
/// for one (`parameters` for `params`); `None` for a word like none of them.
fn meant_keyword(word: &Ident) -> Option<String> {
    let word = word.to_string();
    let keywords: Vec<String> = KEYWORDS.iter().map(|k| k.to_string()).collect();
    let alias = KEYWORD_ALIASES.iter().find(|(a, _)| a.eq_ignore_ascii_case(&word)).map(|(_, k)| k.to_string());
    alias.or_else(|| super::suggest::similar(&word, keywords.iter()).cloned())
}

/// The item after a misspelt keyword (`parms r, l;`, `ouput gap = x;`), read as the keyword
/// `meant` would start it where that item declares fields of the generated types (a list of
/// names, a `point`, an `output`) and reads without a mistake up to its `;`: `input` is then
/// advanced past it, to the `;`. The names keep their fields in the fallback types, so the code
/// that uses them adds no error of its own. `None` (and `input` untouched) otherwise: the item
/// is skipped, as before, without guessing at what else its tokens meant.
fn declared_as(input: ParseStream, meant: &str) -> Option<ItemKind> {
    use syn::parse::discouraged::Speculative;
    let fork = input.fork();
    fork.call(<Ident as syn::ext::IdentExt>::parse_any).ok()?;
    let mut errors = Errors::default();
    let kind = match meant {
        "params" => ItemKind::Decls(DeclKind::Params, parse_decls(&fork, DeclKind::Params, &mut errors).ok()?),
        "input" | "inputs" => {
            ItemKind::Decls(DeclKind::Inputs, parse_decls(&fork, DeclKind::Inputs, &mut errors).ok()?)
        }
        "unknowns" => ItemKind::Decls(DeclKind::Unknowns, parse_decls(&fork, DeclKind::Unknowns, &mut errors).ok()?),
        "point" => {
            let (name, value) = parse_binding(&fork, "point").ok()?;
            ItemKind::Point { name, value }
        }
        "output" => {
            let (name, value) = parse_binding(&fork, "output").ok()?;
            ItemKind::Output { name, value }
        }
        _ => return None,
    };
    if !errors.is_empty() || !fork.peek(Token![;]) {
        return None;
    }
    input.advance_to(&fork);
    Some(kind)
}

const ITEMS: &str = "an item starts with `params`, `input`, `inputs`, `unknowns`, `let`, `loop`, `eq`, `point`, `output`, \
     `body`, `force`, `torque` or `gravity`";

fn skip_keyword(input: ParseStream) -> syn::Result<()> {
    input.parse::<Ident>().map(drop)
}

fn expect_semicolon(input: ParseStream, item: &Item) -> syn::Result<()> {
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
        Ok(())
    } else if let Some(e) = not_in_the_language(input) {
        Err(e)
    } else if let Some(e) = misplaced_doc_comment(input) {
        // Passed over, so that the recovery goes on from what follows it.
        let _ = Attribute::parse_outer(input);
        Err(e)
    } else if input.peek(Token![=]) {
        Err(input.error("unexpected `=`: equations are written with `==`"))
    } else if comma_before_item(input) {
        // `params a, b, input phi;`: the `,` stands for the `;`. It is consumed, so that the
        // next item is parsed (and its names declared) as written.
        let comma = input.parse::<Token![,]>()?;
        let next = match input.cursor().token_tree() {
            Some((tt, _)) => format!(", before `{}`, which starts the next item", short(&tt.to_string())),
            None => " (the last item ends with its `;` too)".to_string(),
        };
        Err(syn::Error::new(
            comma.span,
            format!("expected `;` at the end of this `{}` item, found `,`: write `;` here{next}", item_keyword(item)),
        ))
    } else {
        // Underline the end of the item that lacks its `;`, not the next item.
        let next = match input.cursor().token_tree() {
            // A doc comment is `#` and a bracket to the parser, which the user did not write.
            Some(_) if input.peek(Token![#]) && !input.peek2(Token![!]) => {
                " (before the doc comment of the next item)".to_string()
            }
            Some((tt, _)) => format!(" (before `{}`)", short(&tt.to_string())),
            None => String::new(),
        };
        Err(SpanRange::single(item.range().end)
            .error(format!("expected `;` at the end of this `{}` item{next}", item_keyword(item))))
    }
}

/// The keyword that starts `item`, as the user writes it.
fn item_keyword(item: &Item) -> &'static str {
    match &item.kind {
        ItemKind::Decls(DeclKind::Params, _) => "params",
        ItemKind::Decls(DeclKind::Inputs, _) => "input",
        ItemKind::Decls(DeclKind::Unknowns, _) => "unknowns",
        ItemKind::Let { .. } => "let",
        ItemKind::Loop { .. } => "loop",
        ItemKind::Eq { .. } => "eq",
        ItemKind::Point { .. } => "point",
        ItemKind::Output { .. } => "output",
        ItemKind::Body(_) => "body",
        ItemKind::Force { .. } => "force",
        ItemKind::Torque { .. } => "torque",
        ItemKind::Gravity { .. } => "gravity",
    }
}

/// Whether `input` is at a `,` written for the `;` that ends an item: an item's keyword follows
/// it, itself followed by what starts that item (`input phi`, `point p = ..`, `loop c: ..`),
/// not by what follows a declared name. So `params a, force, mass;` still declares a parameter
/// named `force`, while `params a, b, input phi;` ends the parameters before `input`. A `,`
/// that ends the body (`unknowns psi, x,` before `}`, as a Rust struct's last field) is one too:
/// no name follows it.
fn comma_before_item(input: ParseStream) -> bool {
    let fork = input.fork();
    if fork.parse::<Token![,]>().is_err() {
        return false;
    }
    if fork.is_empty() {
        return true;
    }
    if fork.peek(Token![#]) || !starts_an_item(&fork) {
        return false;
    }
    if fork.peek(Token![let]) || fork.peek(Token![loop]) {
        // Keywords of Rust, never a name.
        return true;
    }
    if fork.call(<Ident as syn::ext::IdentExt>::parse_any).is_err() {
        return false;
    }
    !(fork.is_empty() || fork.peek(Token![,]) || fork.peek(Token![;]) || fork.peek(Token![=]) || fork.peek(Token![:]))
}

/// At most 24 characters of `s`, for quoting source in messages.
fn short(s: &str) -> String {
    if s.chars().count() <= 24 { s.to_string() } else { format!("{}...", s.chars().take(24).collect::<String>()) }
}

/// Parses a list of names with their values. A mistake in one name's part is pushed to
/// `errors` and the list goes on after the next `,`: the names that parsed, the broken one's
/// included (its value a placeholder), keep their fields in the fallback types, so that the
/// user's code that uses them adds no secondary errors (`no field named l`).
fn parse_decls(input: ParseStream, kind: DeclKind, errors: &mut Errors) -> syn::Result<Vec<Decl>> {
    let list = match kind {
        DeclKind::Params => "params a, b = 2.5;",
        DeclKind::Inputs => "input phi;` or `inputs th1, th2;",
        DeclKind::Unknowns => "unknowns psi = 0.3, x;",
    };
    // `input: phi;`, `inputs (th1, th2);`, `input: (phi);`: the names after punctuation of
    // another notation. Said once, and the names read all the same, so that they keep their
    // fields in the fallback types (without them, `m.solve(0.5)` had an error of its own at the
    // macro's call).
    let colon =
        if input.peek(Token![:]) && !input.peek(Token![::]) { Some(input.parse::<Token![:]>()?.span) } else { None };
    if let Some((_, _, span, after)) = input.cursor().any_group()
        && !input.peek(syn::token::Brace)
        && after.punct().is_some_and(|(p, _)| p.as_char() == ';')
    {
        errors.push(match colon {
            Some(colon) => SpanRange { start: colon, end: span.close() }
                .error(format!("no `:` and no brackets around the names: write them after the keyword, `{list}`")),
            None => SpanRange { start: span.open(), end: span.close() }
                .error(format!("no brackets around the names: write them after the keyword, `{list}`")),
        });
        let content;
        if input.peek(syn::token::Paren) {
            syn::parenthesized!(content in input);
        } else {
            syn::bracketed!(content in input);
        }
        let decls = parse_decls(&content, kind, errors)?;
        // What the list left inside (its error is said) is passed over with the brackets.
        skip_to_separator(&content);
        while content.parse::<Token![,]>().is_ok() || content.parse::<Token![;]>().is_ok() {
            skip_to_separator(&content);
        }
        return Ok(decls);
    }
    if let Some(colon) = colon {
        errors.push(syn::Error::new(colon, format!("no `:` after the keyword: write the names after it, `{list}`")));
    }
    let mut decls = Vec::new();
    loop {
        let mut name = None;
        match parse_decl(input, kind, &mut name) {
            Ok(decl) => decls.push(decl),
            Err(e) => {
                errors.push(e);
                if let Some(name) = name {
                    let value = Some(stand_in(&name));
                    decls.push(Decl { docs: Vec::new(), name, value });
                }
                skip_to_separator(input);
            }
        }
        if input.peek(Token![,]) && !comma_before_item(input) {
            input.parse::<Token![,]>()?;
            if input.peek(Token![;]) {
                break;
            }
        } else if let Ok(next) = input.fork().parse::<Ident>()
            && !starts_an_item(input)
        {
            // `params a b = 2.5`: the next name without its `,`, not the item's end.
            let list = match kind {
                DeclKind::Params => "params a, b = 2.5;",
                DeclKind::Inputs => "inputs th1, th2;",
                DeclKind::Unknowns => "unknowns psi = 0.3, x;",
            };
            errors.push(input.error(format!("expected `,` before `{next}`: names are separated by commas, `{list}`")));
        } else {
            break;
        }
    }
    Ok(decls)
}

/// One name of a list with its value; `name` is set as soon as the name parsed.
fn parse_decl(input: ParseStream, kind: DeclKind, name: &mut Option<Ident>) -> syn::Result<Decl> {
    if let Some(e) = inner_attribute(input)? {
        return Err(e);
    }
    let attrs = Attribute::parse_outer(input)?;
    if let Some(bad) = attrs.iter().find(|a| !a.path().is_ident("doc")) {
        // The name after it keeps its field in the fallback types.
        *name = input.fork().parse::<Ident>().ok();
        return Err(syn::Error::new_spanned(
            bad,
            "only doc comments (`///`) are accepted before a name; remove this attribute",
        ));
    }
    if let Some(e) = attrs.iter().find_map(not_a_doc_comment) {
        return Err(e);
    }
    if !input.peek(Ident) {
        // A keyword where a name belongs (`input self;`): the list keeps a stand-in, so that
        // the fallback types have as many inputs as written (`m.solve(0.5)` still converts).
        // Not a parameter's: the mechanism's struct literal (`SliderCrank { r: 1.0 }`), which
        // cannot name the keyword, would miss the stand-in's field. A keyword before the name
        // (`params pub r`) keeps that name's field.
        if let Some((_, _, after)) = modifier_before_name(input) {
            *name = Some(after);
        } else if kind != DeclKind::Params
            && let Ok(word) = input.fork().call(<Ident as syn::ext::IdentExt>::parse_any)
        {
            *name = Some(Ident::new(&format!("__kinloop_keyword_{word}"), word.span()));
        }
        let what = match kind {
            DeclKind::Params => "a parameter",
            DeclKind::Inputs => "an input",
            DeclKind::Unknowns => "an unknown",
        };
        if let Some(e) = keyword_as_name(input, what) {
            return Err(e);
        }
        return Err(input.error(match kind {
            DeclKind::Params => "expected a parameter name: `params a, b = 2.5;`",
            DeclKind::Inputs => "expected an input name: `input phi;` or `inputs th1, th2;`",
            DeclKind::Unknowns => "expected an unknown's name: `unknowns psi = 0.3, x;`",
        }));
    }
    let parsed: Ident = input.parse()?;
    *name = Some(parsed.clone());
    let name = parsed;
    // `x == 1` for `x = 1`: the `==` of an equation where a value is given.
    let double = input.peek(Token![==]);
    let value = if input.peek(Token![=]) {
        let eq = if double {
            let t = input.parse::<Token![==]>()?;
            SpanRange { start: t.spans[0], end: t.spans[1] }
        } else {
            SpanRange::single(input.parse::<Token![=]>()?.span)
        };
        if kind == DeclKind::Inputs {
            return Err(eq.error(format!(
                "an input takes no value here: write `{name}` alone; its value is given when \
                 the mechanism is solved (`m.solve({name})`)"
            )));
        }
        if double {
            let what = if kind == DeclKind::Params { "a default value" } else { "an initial guess" };
            return Err(eq.error(format!(
                "{what} is given with one `=`: write `{name} = ...` (`==` belongs in a `loop` or `eq`)"
            )));
        }
        Some(parse_expr(input)?)
    } else if input.peek(Token![:]) && input.peek2(Token![=]) {
        // `r := 1` is `:` then `=` to the tokenizer: an assignment of another language, not a
        // type.
        return Err(input.error(format!("a value is given with `=`, not `:=`: write `{name} = ...`")));
    } else if input.peek(Token![:]) && kind != DeclKind::Inputs && number_after_colon(input) {
        // `r: 1.5`, as a key and its value are written in YAML or Python: a value, not a type,
        // which "write `r` alone" would drop.
        return Err(input.error(format!("a value is given with `=`, not `:`: write `{name} = ...`")));
    } else if input.peek(Token![:]) {
        return Err(input.error(format!(
            "no type is needed: write `{name}` alone (every parameter, input and unknown is an `f64`)"
        )));
    } else {
        None
    };
    // Anything else after the value ends the list: the item's `;` check says what is missing.
    if let Some(e) = not_in_the_language(input) {
        return Err(e);
    }
    Ok(Decl { docs: attrs, name, value })
}

/// Whether `input`, at a `:`, goes on with a number (`r: 1.5`, `psi: -0.3`): a value, not a type.
fn number_after_colon(input: ParseStream) -> bool {
    let fork = input.fork();
    if fork.parse::<Token![:]>().is_err() {
        return false;
    }
    if fork.peek(Token![-]) {
        let _ = fork.parse::<Token![-]>();
    }
    fork.cursor().literal().is_some()
}

/// The error for a token after a complete value that is Rust but not kinloop, saying what to
/// write instead: `%`, comparisons, paths (`std::f64::consts::PI`), indexing, a second `==`.
/// Without it the item's own message ("expected `;` at the end of this item") points before
/// the token and names no replacement.
fn not_in_the_language(input: ParseStream) -> Option<syn::Error> {
    if input.peek(Token![==]) {
        return Some(second_equals(input));
    }
    let message = if input.peek(Token![%]) {
        "kinloop has no `%`: write `wrap(x, period)` for `x` reduced to `0 <= x < period`"
    } else if input.peek(Token![<]) || input.peek(Token![>]) || input.peek(Token![!=]) {
        "kinloop has no comparisons: a value that depends on one is written with `min`, `max`, \
         `clamp` or `abs`"
    } else if input.peek(Token![::]) {
        "kinloop has no paths: write `pi` for `PI`, and functions by their own names (`sin(x)`, \
         not `f64::sin(x)`)"
    } else if input.peek(Token![!]) && !input.peek(Token![!=]) && input.peek2(syn::token::Paren) {
        // `max!(a, b)`, `vec2!(x, y)`: the name before the `!` parsed as a value.
        "kinloop has no macros: call the function without `!`, as in `max(a, b)`, and write a \
         vector as `(x, y)`"
    } else if input.peek(syn::token::Bracket) {
        "kinloop has no indexing: name each value (`let`, `point`, `.x` and `.y` of a vector)"
    } else {
        return None;
    };
    Some(input.error(message))
}

/// The error for a second `==` after a complete equation, underlining both of its characters:
/// one with nothing after it (`loop c: a == b ==;`) is left over and only to be removed, one
/// with a value after it (`a == b == c`) chains two equalities.
fn second_equals(input: ParseStream) -> syn::Error {
    let fork = input.fork();
    let Ok(eq) = fork.parse::<Token![==]>() else {
        return input.error("an equation has one `==`");
    };
    let range = SpanRange { start: eq.spans[0], end: eq.spans[1] };
    if fork.is_empty() || fork.peek(Token![;]) {
        range.error("nothing follows this `==`; remove it (an equation is `lhs == rhs`, with one `==`)")
    } else {
        range.error("an equation has one `==`: write each equality as its own `eq` or `loop`")
    }
}

/// "a `loop`", "an `eq`": the item called `what`, for messages.
fn item_article(what: &str) -> String {
    let article = if what.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" };
    format!("{article} `{what}`")
}

/// Why no item or name takes a visibility, for the message that says to remove one.
const VISIBILITY: &str = "the items and names of a declaration take no visibility: the generated fields are all \
     public, and the generated types take the mechanism's (`pub struct Name`)";

/// A Rust keyword written before a name, as a modifier (`params pub r`, `params const r`): how
/// it is written, its tokens and the name after it. `None` where no name follows the keyword
/// (`params type;`, a keyword where the name belongs).
fn modifier_before_name(input: ParseStream) -> Option<(String, proc_macro2::TokenStream, Ident)> {
    use quote::ToTokens;
    let fork = input.fork();
    let tokens = if fork.peek(Token![pub]) {
        // `pub(crate) r`: the visibility as a whole.
        fork.parse::<Visibility>().ok()?.to_token_stream()
    } else {
        fork.call(<Ident as syn::ext::IdentExt>::parse_any).ok()?.to_token_stream()
    };
    let name: Ident = fork.parse().ok()?;
    Some((written(&tokens), tokens, name))
}

/// `tokens` as a message quotes them: `pub(crate)`, not the token stream's `pub (crate)`.
fn written(tokens: &proc_macro2::TokenStream) -> String {
    tokens.to_string().replace(" (", "(").replace("( ", "(").replace(" )", ")")
}

/// The error for a Rust keyword where a name belongs (`params in;`, `output type = ..;`),
/// saying what to write instead; `None` where no keyword stands.
fn keyword_as_name(input: ParseStream, what: &str) -> Option<syn::Error> {
    if input.peek(Ident) {
        return None;
    }
    let word = input.fork().call(<Ident as syn::ext::IdentExt>::parse_any).ok()?.to_string();
    if word == "mut" {
        return Some(input.error(format!("remove `mut`: {what} names one value, which is never reassigned")));
    }
    // `_` is no name at all, and `r#_` does not lex: neither the raw form nor `__` helps.
    if word == "_" {
        let unused = if what == "a parameter" {
            " (one that starts with `_`, such as `_spare`, keeps an unused parameter without a warning)"
        } else {
            ""
        };
        return Some(
            input.error(format!(
                "`_` is Rust's placeholder, not a name, and cannot name {what}: give it a name{unused}"
            )),
        );
    }
    if let Some((word, tokens, name)) = modifier_before_name(input) {
        // `params pub r` or `params const r`: a keyword before the name, not in its place;
        // another name for the keyword (`pub_`) would not help.
        let why = if input.peek(Token![pub]) {
            VISIBILITY.to_string()
        } else {
            format!("{what} is declared by its name alone")
        };
        return Some(syn::Error::new_spanned(tokens, format!("remove `{word}`: {why}; write `{name}`")));
    }
    // These four are keywords even as raw identifiers.
    let raw = if matches!(word.as_str(), "self" | "Self" | "super" | "crate") {
        String::new()
    } else {
        format!(", or write the raw identifier `r#{word}`")
    };
    Some(input.error(format!(
        "`{word}` is a Rust keyword and cannot name {what}: choose another name, such as `{word}_`{raw}"
    )))
}

/// Skips to the next top-level `,` or `;` of a list, leaving it (error recovery within a list).
fn skip_to_separator(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tt, next)) = rest.token_tree() {
            if let proc_macro2::TokenTree::Punct(p) = &tt
                && matches!(p.as_char(), ',' | ';')
            {
                break;
            }
            rest = next;
        }
        Ok(((), rest))
    });
}

/// A `point` or `output` item's name and value, as [`parse_binding`] parses them.
enum Named {
    /// Both parsed; the item's `;` follows.
    Parsed(Ident, Expr),
    /// The name parsed, the value did not: its error is pushed, the item is skipped to just
    /// after its `;`, and the value is a placeholder. The name keeps its column in the fallback
    /// types (`s.out.p`), so the user's code that reads it adds no secondary error.
    Broken(Ident, Expr),
}

/// The value that stands in for `name`'s where it did not parse. Never evaluated: a
/// declaration with a syntax error is not lowered; only its names make the fallback types.
fn stand_in(name: &Ident) -> Expr {
    Expr::Num { value: 0.0, integer: Some(0), span: name.span() }
}

fn named_value(input: ParseStream, what: &str, errors: &mut Errors) -> syn::Result<Named> {
    let name = input.fork().parse::<Ident>().ok();
    match (parse_binding(input, what), name) {
        (Ok((name, value)), _) => Ok(Named::Parsed(name, value)),
        (Err(e), Some(name)) => {
            errors.push(e);
            skip_item(input);
            let value = stand_in(&name);
            Ok(Named::Broken(name, value))
        }
        (Err(e), None) => Err(e),
    }
}

fn parse_binding(input: ParseStream, what: &str) -> syn::Result<(Ident, Expr)> {
    if let Some(e) = keyword_as_name(input, &item_article(what)) {
        return Err(e);
    }
    if let Some(e) = misplaced_doc_comment(input) {
        return Err(e);
    }
    if !input.peek(Ident) {
        return Err(input.error(format!("expected a name: `{what} name = expression;`")));
    }
    let name: Ident = input.parse()?;
    // `point p := ...` is `:` then `=` to the tokenizer: an assignment, not a type.
    if input.peek(Token![:]) && input.peek2(Token![=]) {
        return Err(input.error(format!("a value is given with `=`, not `:=`: write `{what} {name} = expression;`")));
    }
    if input.peek(Token![:]) {
        return Err(input.error(format!("no type is needed: write `{what} {name} = expression;`")));
    }
    if !input.peek(Token![=]) || input.peek(Token![==]) {
        return Err(input.error(format!("expected `=`: `{what} {name} = expression;`")));
    }
    input.parse::<Token![=]>()?;
    let value = parse_expr(input)?;
    Ok((name, value))
}

fn parse_equation(input: ParseStream, what: &str) -> syn::Result<(Ident, Expr, Expr, Span)> {
    if let Some(e) = keyword_as_name(input, &item_article(what)) {
        return Err(e);
    }
    if let Some(e) = misplaced_doc_comment(input) {
        return Err(e);
    }
    if !input.peek(Ident) {
        return Err(input.error(format!(
            "expected the equation's name: `{what} name: lhs == rhs;` (names appear in error messages)"
        )));
    }
    let name: Ident = input.parse()?;
    if !input.peek(Token![:]) || input.peek(Token![::]) {
        // `loop r @ phi == ...`: the name is missing, the equation starts right away.
        return Err(syn::Error::new(
            name.span(),
            format!(
                "expected the {what}'s name and `:` before its equation: `{what} name: lhs == rhs;` \
                 (the name appears in `EQUATIONS` and in error messages)"
            ),
        ));
    }
    input.parse::<Token![:]>()?;
    let lhs = parse_expr(input)?;
    if input.peek(Token![=]) && !input.peek(Token![==]) {
        return Err(input.error("expected `==`: an equation is written `lhs == rhs`"));
    }
    if !input.peek(Token![==]) {
        return Err(input.error(format!("expected `==`: `{what} {name}: lhs == rhs;`")));
    }
    if let Some(e) = triple_equals(input) {
        return Err(e);
    }
    let eq = input.parse::<Token![==]>()?.spans[0];
    let rhs = parse_expr(input)?;
    Ok((name, lhs, rhs, eq))
}

/// The error for `===` (the strict equality of JavaScript and PHP) where the `==` of an
/// equation belongs, underlining its three characters: it said "expected a value, found `=`" of
/// the third. `None` for anything else.
fn triple_equals(input: ParseStream) -> Option<syn::Error> {
    let joint = |p: &proc_macro2::Punct| p.as_char() == '=' && p.spacing() == proc_macro2::Spacing::Joint;
    let (first, rest) = input.cursor().punct().filter(|(p, _)| joint(p))?;
    let (_, rest) = rest.punct().filter(|(p, _)| joint(p))?;
    let (third, _) = rest.punct().filter(|(p, _)| p.as_char() == '=')?;
    let range = SpanRange { start: first.span(), end: third.span() };
    Some(range.error("`===` is not an operator: an equation is written with `==`, `lhs == rhs`"))
}

/// Skips to just after the next top-level `;` (error recovery).
pub(super) fn skip_item(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tt, next)) = rest.token_tree() {
            rest = next;
            if let proc_macro2::TokenTree::Punct(p) = &tt
                && p.as_char() == ';'
            {
                break;
            }
        }
        Ok(((), rest))
    });
}
