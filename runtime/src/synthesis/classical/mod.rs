//! Closed-form four-bar synthesis from the classical theory.
