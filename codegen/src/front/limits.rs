//! Size limits checked on the raw tokens, before any parsing.
//!
//! syn's token buffer and the parsers behind it recurse into every bracket, so a deep enough
//! nesting (tens of thousands of `(`) overflows the compiler's stack before any depth guard of
//! the parser itself runs: the compiler aborts without a diagnostic. This walk visits the
//! groups with an explicit stack instead, so it handles any depth, and rejects the input with
//! one error at the first bracket beyond the limit. It also bounds the number of tokens, which
//! bounds the time every later stage takes.

use proc_macro2::{TokenStream, TokenTree, token_stream::IntoIter};

/// Deepest nesting of `(...)`, `[...]` and `{...}` accepted. Expressions have their own,
/// smaller limit ([`crate::front::expr::MAX_DEPTH`]) with a more specific message; this one only keeps
/// the recursive parsers safe.
pub const MAX_NESTING: usize = 256;

/// Most tokens one declaration may have. A large mechanism has a few thousand; parsing this
/// many takes about a second in an unoptimised build.
pub const MAX_TOKENS: usize = 100_000;

/// Checks the nesting depth and the size of `tokens` without recursion.
pub fn check(tokens: &TokenStream) -> Result<(), syn::Error> {
    let mut stack: Vec<IntoIter> = vec![tokens.clone().into_iter()];
    let mut count = 0usize;
    while let Some(top) = stack.last_mut() {
        let Some(tt) = top.next() else {
            stack.pop();
            continue;
        };
        count += 1;
        if count > MAX_TOKENS {
            return Err(syn::Error::new(
                tt.span(),
                format!(
                    "the declaration has more than {MAX_TOKENS} tokens, the most kinloop accepts; \
                     split the mechanism into smaller ones"
                ),
            ));
        }
        if let TokenTree::Group(g) = tt {
            // `stack.len()` is the depth of this group: 1 for a group at the top level.
            if stack.len() > MAX_NESTING {
                return Err(syn::Error::new(
                    g.span_open(),
                    format!(
                        "brackets nested more than {MAX_NESTING} levels deep, the most kinloop accepts; \
                         split the expression into named parts with `let`"
                    ),
                ));
            }
            stack.push(g.stream().into_iter());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proc_macro2::{Delimiter, Group};

    /// `n` nested groups around `x`, built without recursion (and without text).
    fn nested(n: usize, delimiter: Delimiter) -> TokenStream {
        let mut ts: TokenStream = "x".parse().expect("tokens");
        for _ in 0..n {
            ts = TokenTree::Group(Group::new(delimiter, ts)).into();
        }
        ts
    }

    #[test]
    fn depth_at_the_limit_passes_and_one_more_fails() {
        for d in [Delimiter::Parenthesis, Delimiter::Bracket, Delimiter::Brace, Delimiter::None] {
            assert!(check(&nested(MAX_NESTING, d)).is_ok(), "{d:?}");
            let e = check(&nested(MAX_NESTING + 1, d)).expect_err("too deep");
            assert!(e.to_string().contains("nested more than 256 levels"), "{e}");
        }
    }

    #[test]
    fn a_million_levels_are_rejected_without_recursion() {
        let deep = nested(1_000_000, Delimiter::Parenthesis);
        assert!(check(&deep).is_err());
    }

    #[test]
    fn token_count_is_bounded() {
        let at_limit: TokenStream = std::iter::repeat_n("x", MAX_TOKENS).collect::<Vec<_>>().join(" ").parse().unwrap();
        assert!(check(&at_limit).is_ok());
        let over: TokenStream = std::iter::repeat_n("x", MAX_TOKENS + 1).collect::<Vec<_>>().join(" ").parse().unwrap();
        let e = check(&over).expect_err("too many tokens");
        assert!(e.to_string().contains("more than 100000 tokens"), "{e}");
        // A group counts as one token, plus its contents.
        let groups = |n: usize| -> TokenStream { std::iter::repeat_n("(x)", n).collect::<String>().parse().unwrap() };
        assert!(check(&groups(MAX_TOKENS / 2)).is_ok());
        assert!(check(&groups(MAX_TOKENS / 2 + 1)).is_err());
    }
}
