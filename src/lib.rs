//! kinloop: kinematic analysis of planar mechanisms declared as closed vector loops.
extern crate self as kinloop;

pub use kinloop_macros::mechanism;
pub use kinloop_runtime::*;

#[doc(hidden)]
pub mod __private {
    pub use kinloop_runtime::*;
}
