//! The expression graph ([`dag`]: hash-consed nodes with local simplification), its symbolic
//! differentiation and substitution ([`diff`]), and how an expression depends on one leaf
//! through whole multiples ([`multiples`]), which sines and cosines of a sum are computed by
//! angle addition ([`angle_sums`]), the dimension of an expression ([`dims`]); an equation's residual is its sides' difference with
//! their common terms cancelled (`sides`).

pub mod angle_sums;
pub mod dag;
pub mod diff;
pub mod dims;
pub mod multiples;
mod sides;
