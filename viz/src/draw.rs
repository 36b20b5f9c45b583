//! Drawings and animations of mechanisms (placeholder, being written).
