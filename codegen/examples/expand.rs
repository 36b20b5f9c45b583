//! Prints what `mechanism!` expands to, formatted: for every `mechanism! { .. }` invocation in
//! a Rust file, or for a file that holds one declaration alone (`pub struct Name { .. }`).
//!
//! ```sh
//! cargo run -p kinloop-codegen --example expand -- examples/animations.rs
//! ```

use proc_macro2::{TokenStream, TokenTree};
use std::io::Write;
use std::process::ExitCode;

/// The bodies of the `mechanism!` invocations in `tokens`, at any depth, in order.
fn invocations(tokens: TokenStream, out: &mut Vec<TokenStream>) {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    for (k, tree) in trees.iter().enumerate() {
        if let TokenTree::Group(g) = tree {
            let named = matches!(&trees[..k], [.., TokenTree::Ident(m), TokenTree::Punct(p)] if m == "mechanism" && p.as_char() == '!');
            if named {
                out.push(g.stream());
            } else {
                invocations(g.stream(), out);
            }
        }
    }
}

fn main() -> ExitCode {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: expand FILE.rs (a file with `mechanism!` invocations, or one declaration)");
        return ExitCode::FAILURE;
    };
    let text = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(e) => {
            eprintln!("{path}: {e}");
            return ExitCode::FAILURE;
        }
    };
    let tokens: TokenStream = match text.parse() {
        Ok(tokens) => tokens,
        Err(e) => {
            eprintln!("{path}: not Rust tokens: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mut found = Vec::new();
    invocations(tokens.clone(), &mut found);
    if found.is_empty() {
        found.push(tokens);
    }
    let mut out = std::io::stdout().lock();
    for body in found {
        let expanded = kinloop_codegen::expand(body);
        let text = match syn::parse2::<syn::File>(expanded.clone()) {
            Ok(file) => prettyplease::unparse(&file),
            // Not expected (the expansion is always items); shown unformatted rather than lost.
            Err(_) => expanded.to_string(),
        };
        // Written, not printed: `println!` panics where the reader is gone (`| head`).
        if let Err(e) = writeln!(out, "{text}").and_then(|()| out.flush()) {
            return match e.kind() {
                std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
                _ => {
                    eprintln!("cannot write the expansion: {e}");
                    ExitCode::FAILURE
                }
            };
        }
    }
    ExitCode::SUCCESS
}
