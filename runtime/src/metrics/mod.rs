//! Design metrics of mechanisms (placeholder, being written).
