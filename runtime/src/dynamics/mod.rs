//! Machine dynamics (placeholder, being written).
