//! The front of the pipeline: tokens to a syntax tree.
//!
//! [`limits`] first measures the raw tokens without recursion (nesting depth, size), so that no
//! input can overflow the stack in the recursive parsers behind it; [`declaration`] then parses
//! the declaration (one item at a time in `item`, the dynamics' items in `dynamics`) into the
//! tree of [`syntax`], with [`expr`] for expressions, and [`names`] rejects names the generated
//! code cannot use. [`suggest`] finds the did-you-mean of a misspelt word, for the front and the
//! stages after it.

pub mod declaration;
mod dynamics;
pub mod expr;
mod item;
pub mod limits;
pub mod names;
pub mod suggest;
pub mod syntax;
