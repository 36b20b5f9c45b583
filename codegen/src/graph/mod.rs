//! The expression graph ([`dag`]: hash-consed nodes with local simplification), its symbolic
//! differentiation and substitution ([`diff`]), and how an expression depends on one leaf
//! through whole multiples ([`multiples`]); an equation's residual is its sides' difference with
//! their common terms cancelled (`sides`).

pub mod dag;
pub mod diff;
pub mod multiples;
mod sides;
