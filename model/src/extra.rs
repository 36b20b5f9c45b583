//! The registers beyond the graph's: those of the closed forms' programs (their constants,
//! written once when the model is built, and their intermediate values) and the Newton blocks'
//! rotation slots, numbered after the graph's nodes in one register file.
//!
//! Apart from both users, below them: the closed forms (`crate::closed`) run their arithmetic
//! as the instruction tape's steps, and the tape runs the rotation slots (`crate::near`) of its
//! Newton evaluation segments, so the tape sits between the two, and the registers they share
//! sit under all three.

use std::collections::HashMap;

/// The registers beyond the graph's that the closed forms' programs use (their constants,
/// written once when the model is built, and their intermediate values), and the Newton
/// blocks' rotation slots (`crate::near`).
#[derive(Debug, Default)]
pub(crate) struct Extra {
    next: u32,
    /// The constants' registers and values.
    consts: Vec<(u32, f64)>,
    /// A constant's register by its bits.
    by_bits: HashMap<u64, u32>,
}

impl Extra {
    /// Registers from `first` on.
    pub(crate) fn new(first: u32) -> Extra {
        Extra { next: first, ..Extra::default() }
    }

    /// The size of the register file with these registers.
    pub(crate) fn len(&self) -> usize {
        self.next as usize
    }

    /// Writes the constants into the registers (`r.len() >= self.len()`).
    pub(crate) fn write_constants(&self, r: &mut [f64]) {
        for &(k, x) in &self.consts {
            r[k as usize] = x;
        }
    }

    /// A fresh register.
    pub(crate) fn fresh(&mut self) -> u32 {
        self.block(1)
    }

    /// The first of `n` consecutive fresh registers.
    pub(crate) fn block(&mut self, n: u32) -> u32 {
        let k = self.next;
        self.next += n;
        k
    }

    /// The register holding the constant `x`: one per value (by its bits), made the first time.
    pub(crate) fn constant(&mut self, x: f64) -> u32 {
        if let Some(&k) = self.by_bits.get(&x.to_bits()) {
            return k;
        }
        let k = self.fresh();
        self.consts.push((k, x));
        self.by_bits.insert(x.to_bits(), k);
        k
    }
}
