//! From syntax to a checked model: names resolved ([`scope`], over the table of [`symbols`]),
//! vector/scalar types checked and every expression lowered into one graph ([`lower`], with the
//! built-in functions of [`builtins`]), assembled by [`model`].

mod angles;
pub mod builtins;
mod calls;
pub mod drawing;
pub mod dynamics;
pub mod lower;
pub mod model;
mod polar;
mod scope;
mod symbols;
