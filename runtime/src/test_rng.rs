//! A small deterministic generator for the unit tests of every layer (the solvers' among them),
//! so it sits at the bottom, apart from the modules it serves.

/// A small deterministic generator (xorshift64) for random designs without a dependency.
pub struct Rng(pub u64);

impl Rng {
    /// A uniform draw from `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        lo + (hi - lo) * (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}
