//! Index and size literals.

use proc_macro2::Literal;

pub(crate) fn lit(n: usize) -> Literal {
    Literal::usize_unsuffixed(n)
}
