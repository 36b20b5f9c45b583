//! Charts of sweep results (placeholder, being written).
