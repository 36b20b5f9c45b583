//! Regrouping of long runs of `let` statements, so that rustc can compile them with debug
//! information.
//!
//! Every `let` opens a scope nested in the previous one, and rustc's stack overflows (8 MiB)
//! building the debug information of a block with a few thousand of them: a coupled block of
//! a hundred unknowns emits that many temporaries in one kernel. Any block (a function's body, a
//! closure's, a nested block) with more than [`LETS_PER_GROUP`] `let`s at its top level is
//! therefore rewritten, on the tokens: its statements are cut into groups of that many `let`s,
//! each group becoming one
//! `let (a, mut b, ..) = { <the group's statements> (a, b, ..) };`
//! that hands on the bindings the later statements name. The values, their order of evaluation,
//! early returns and `?` are unchanged; the nesting is now bounded by the group size plus the
//! number of groups. Items (`static` tables) move to the top of their block, where they are
//! visible to every group. A group never ends while a closure it defines is named later (the
//! closure may borrow the group's locals). Smaller blocks are left exactly as emitted.

use proc_macro2::{Delimiter, Group, Ident, Spacing, TokenStream, TokenTree};
use quote::quote;
use std::collections::HashMap;

/// Most `let`s kept at the top level of one block (rustc overflowed beyond ~2,500 to 5,000).
pub(crate) const LETS_PER_GROUP: usize = 1024;

/// `tokens` with every over-long block regrouped (see the module documentation).
pub(crate) fn group_lets(tokens: TokenStream) -> TokenStream {
    regroup(&tokens).unwrap_or(tokens)
}

/// The regrouped stream, or `None` when nothing in it needed regrouping.
fn regroup(tokens: &TokenStream) -> Option<TokenStream> {
    let trees: Vec<TokenTree> = tokens.clone().into_iter().collect();
    let mut changed = false;
    let inner: Vec<TokenTree> = trees
        .iter()
        .map(|t| match t {
            TokenTree::Group(g) => match regroup(&g.stream()) {
                Some(s) => {
                    changed = true;
                    let mut n = Group::new(g.delimiter(), s);
                    n.set_span(g.span());
                    TokenTree::Group(n)
                }
                None => t.clone(),
            },
            _ => t.clone(),
        })
        .collect();
    let stmts = statements(&inner);
    if stmts.iter().filter(|s| s.is_let()).count() <= LETS_PER_GROUP {
        return changed.then(|| inner.into_iter().collect());
    }
    Some(grouped(stmts))
}

/// One top-level statement (or the block's tail expression) as its tokens.
struct Stmt {
    tokens: Vec<TokenTree>,
}

impl Stmt {
    fn first_ident(&self) -> Option<String> {
        match self.tokens.first() {
            Some(TokenTree::Ident(i)) => Some(i.to_string()),
            _ => None,
        }
    }
    fn is_let(&self) -> bool {
        self.first_ident().as_deref() == Some("let")
    }
    fn is_item(&self) -> bool {
        matches!(self.first_ident().as_deref(), Some("static" | "const" | "fn" | "struct" | "enum" | "use" | "impl"))
    }
    fn ends_with_semicolon(&self) -> bool {
        matches!(self.tokens.last(), Some(TokenTree::Punct(p)) if p.as_char() == ';')
    }
    /// The names a `let` binds, each with whether it is bound `mut` (the pattern is everything
    /// before the first top-level `:` or `=`; `_` binds nothing).
    fn bindings(&self) -> Vec<(Ident, bool)> {
        let mut out = Vec::new();
        let mut pattern = Vec::new();
        for t in self.tokens.iter().skip(1) {
            if let TokenTree::Punct(p) = t
                && (p.as_char() == '=' || (p.as_char() == ':' && p.spacing() == Spacing::Alone))
            {
                break;
            }
            pattern.push(t.clone());
        }
        collect_bindings(pattern, &mut out);
        out
    }
    /// Whether a `let` binds a closure (`let f = |..| ..` or `let f = move |..| ..`).
    fn binds_closure(&self) -> bool {
        let mut rest = self.tokens.iter().skip_while(|t| !matches!(t, TokenTree::Punct(p) if p.as_char() == '='));
        rest.next();
        match rest.next() {
            Some(TokenTree::Punct(p)) => p.as_char() == '|',
            Some(TokenTree::Ident(i)) => i == "move",
            _ => false,
        }
    }
}

fn collect_bindings(pattern: Vec<TokenTree>, out: &mut Vec<(Ident, bool)>) {
    let mut mutable = false;
    for t in pattern {
        match t {
            TokenTree::Ident(i) if i == "mut" => mutable = true,
            TokenTree::Ident(i) if i != "_" && i != "ref" => {
                out.push((i, mutable));
                mutable = false;
            }
            TokenTree::Group(g) => collect_bindings(g.stream().into_iter().collect(), out),
            _ => mutable = false,
        }
    }
}

/// The top-level statements of a block's tokens: each ends at a top-level `;`, or after the
/// braces of a statement that starts with `if`, `match`, `for`, `while`, `loop` or a block
/// (unless `else` follows).
fn statements(trees: &[TokenTree]) -> Vec<Stmt> {
    let mut out = Vec::new();
    let mut cur: Vec<TokenTree> = Vec::new();
    for (k, t) in trees.iter().enumerate() {
        cur.push(t.clone());
        let ends = match t {
            TokenTree::Punct(p) => p.as_char() == ';',
            TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
                let block_like = match &cur[0] {
                    TokenTree::Ident(i) => ["if", "match", "for", "while", "loop", "unsafe"].iter().any(|w| i == w),
                    TokenTree::Group(g0) => g0.delimiter() == Delimiter::Brace,
                    _ => false,
                };
                let else_follows = matches!(trees.get(k + 1), Some(TokenTree::Ident(i)) if i == "else");
                block_like && !else_follows
            }
            _ => false,
        };
        if ends {
            out.push(Stmt { tokens: std::mem::take(&mut cur) });
        }
    }
    if !cur.is_empty() {
        out.push(Stmt { tokens: cur });
    }
    out
}

/// Every identifier in `trees`, into `last` with statement index `k` (the last statement that
/// names each identifier).
fn note_names(trees: &[TokenTree], k: usize, last: &mut HashMap<String, usize>) {
    for t in trees {
        match t {
            TokenTree::Ident(i) => {
                last.insert(i.to_string(), k);
            }
            TokenTree::Group(g) => note_names(&g.stream().into_iter().collect::<Vec<_>>(), k, last),
            _ => {}
        }
    }
}

/// The block's statements regrouped: items first, then groups of [`LETS_PER_GROUP`] `let`s,
/// then the rest as it was.
fn grouped(stmts: Vec<Stmt>) -> TokenStream {
    let (items, stmts): (Vec<Stmt>, Vec<Stmt>) = stmts.into_iter().partition(Stmt::is_item);
    let mut last = HashMap::new();
    for (k, s) in stmts.iter().enumerate() {
        note_names(&s.tokens, k, &mut last);
    }
    let named_after = |name: &Ident, end: usize| last.get(&name.to_string()).is_some_and(|&k| k >= end);
    let mut out: TokenStream = items.iter().flat_map(|s| s.tokens.clone()).collect();
    let total_lets = stmts.iter().filter(|s| s.is_let()).count();
    let (mut start, mut lets_left) = (0, total_lets);
    let mut group = (0usize, Vec::<Ident>::new());
    for (k, s) in stmts.iter().enumerate() {
        if s.is_let() {
            group.0 += 1;
            if s.binds_closure() {
                group.1.extend(s.bindings().into_iter().map(|(i, _)| i));
            }
        }
        let end = k + 1;
        // A group closes after its share of `let`s, at a `;`, with no closure of it named later,
        // and only while enough `let`s follow to make another group worth it.
        let full = group.0 >= LETS_PER_GROUP && s.ends_with_semicolon();
        if full && !group.1.iter().any(|c| named_after(c, end)) && lets_left > LETS_PER_GROUP {
            out.extend(one_group(&stmts[start..end], |i| named_after(i, end)));
            lets_left -= group.0;
            start = end;
            group = (0, Vec::new());
        }
    }
    out.extend(stmts[start..].iter().flat_map(|s| s.tokens.clone()));
    out
}

/// `let (a, mut b, ..) = { stmts (a, b, ..) };` handing on the bindings named later (the last
/// binding of each name; `mut` as it was bound).
fn one_group(stmts: &[Stmt], named_later: impl Fn(&Ident) -> bool) -> TokenStream {
    let mut bound: Vec<(Ident, bool)> = Vec::new();
    for s in stmts.iter().filter(|s| s.is_let()) {
        for (name, mutable) in s.bindings() {
            bound.retain(|(n, _)| *n != name);
            bound.push((name, mutable));
        }
    }
    bound.retain(|(n, _)| named_later(n));
    let body: TokenStream = stmts.iter().flat_map(|s| s.tokens.clone()).collect();
    let names = bound.iter().map(|(n, _)| n);
    let pats = bound.iter().map(|(n, m)| if *m { quote!(mut #n) } else { quote!(#n) });
    quote! {
        #[allow(unused_mut)]
        let (#(#pats,)*) = { #body (#(#names,)*) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lets(n: usize, from: usize) -> String {
        (from..from + n).map(|k| format!("let t{k}: f64 = t{} * 1.5 + x;", k - 1)).collect()
    }

    /// Top-level `let`s of a block's tokens.
    fn top_lets(ts: &TokenStream) -> usize {
        let trees: Vec<TokenTree> = ts.clone().into_iter().collect();
        statements(&trees).iter().filter(|s| s.is_let()).count()
    }

    #[test]
    fn short_blocks_are_untouched() {
        let body: TokenStream = format!("let t0 = x; {} t9", lets(9, 1)).parse().unwrap();
        assert_eq!(group_lets(body.clone()).to_string(), body.to_string());
    }

    /// A long body: the groups hold at most `LETS_PER_GROUP` lets, bindings named later are handed
    /// on (the tail, a mutated `mut`, a closure used across the cut), items move to the top, and
    /// the result is still a block of Rust statements.
    #[test]
    fn long_blocks_are_cut_into_groups_that_hand_on_what_is_named_later() {
        let n = 3 * LETS_PER_GROUP + 10;
        let half = LETS_PER_GROUP - 3;
        let text = format!(
            "let t0 = x; let mut acc = 0.0; {first} let f = |z: f64| z * t1; {mid} let u = f(t5); \
             if t3 > 0.0 {{ return None; }} static TABLE: [u8; 1] = [0]; {rest} \
             acc += u; Some(acc + t{n} + TABLE[0] as f64)",
            first = lets(half, 1),
            mid = lets(10, half + 1),
            rest = lets(n - half - 10, half + 11),
        );
        let out = group_lets(text.parse().unwrap());
        let printed = out.to_string();
        let file: syn::Block = syn::parse2(quote!({ #out })).expect("a block of statements");
        assert!(printed.starts_with("static TABLE"), "items first: {}", &printed[..60]);
        assert!(top_lets(&out) < LETS_PER_GROUP + 8, "{} top-level lets", top_lets(&out));
        // Every group's own block is below the limit too (plus the 11 `let`s the group with the
        // closure runs on to the closure's last use).
        for stmt in &file.stmts {
            if let syn::Stmt::Local(l) = stmt
                && let Some(init) = &l.init
                && let syn::Expr::Block(b) = &*init.expr
            {
                let inner = b.block.stmts.iter().filter(|s| matches!(s, syn::Stmt::Local(_))).count();
                assert!(inner <= LETS_PER_GROUP + 11, "a group of {inner} lets");
            }
        }
        // The closure and what it borrows stay in one group; `acc` is handed on as `mut`.
        assert!(printed.contains("mut acc"));
        assert!(printed.contains("u ,"), "the closure's result is handed on");
        assert!(!printed.contains(", f ,") && !printed.contains("(f ,"), "the closure is not handed on");
    }
}
