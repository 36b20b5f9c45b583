//! Prints the code generated for a declaration read from a file (the body of `mechanism!`):
//! `cargo run -p kinloop-codegen --example expand -- path/to/decl.txt`
fn main() {
    let path = std::env::args().nth(1).expect("usage: expand <file>");
    let src = std::fs::read_to_string(&path).expect("readable file");
    let tokens: proc_macro2::TokenStream = src.parse().expect("tokens");
    let out = kinloop_codegen::expand(tokens);
    match syn::parse2::<syn::File>(out.clone()) {
        Ok(file) => print!("{}", prettyplease::unparse(&file)),
        Err(_) => print!("{out}"),
    }
}
