//! A randomly shifted Halton sequence: the starts of a global search, spread evenly over the
//! box of the design variables, deterministic for a seed and addressable by index (point `i`
//! does not depend on any other), so that a search can be split by index range.
//!
//! Point `i` in dimension `d` is the radical inverse of `i + 1` in the `d`-th prime, shifted
//! modulo 1 by a value drawn from the seed (a Cranley–Patterson rotation: the same low
//! discrepancy, another sequence for another seed).

/// The Halton sequence in `dims` dimensions with the shifts of `seed`.
#[derive(Clone, Debug, PartialEq)]
pub struct Halton {
    primes: Vec<u64>,
    shifts: Vec<f64>,
}

impl Halton {
    /// The sequence in `dims` dimensions, shifted by `seed`'s values.
    pub fn new(dims: usize, seed: u64) -> Self {
        let primes = first_primes(dims);
        let mut state = seed;
        let shifts = (0..dims).map(|_| unit(splitmix64(&mut state))).collect();
        Halton { primes, shifts }
    }

    /// Point `index`, each coordinate in `[0, 1)`.
    pub fn point(&self, index: u64) -> Vec<f64> {
        self.primes
            .iter()
            .zip(&self.shifts)
            .map(|(&p, &s)| {
                let v = radical_inverse(index.wrapping_add(1), p) + s;
                if v >= 1.0 { v - 1.0 } else { v }
            })
            .collect()
    }
}

/// The digits of `i` in base `b` mirrored about the radix point.
fn radical_inverse(mut i: u64, b: u64) -> f64 {
    let (mut v, mut f) = (0.0, 1.0 / b as f64);
    while i > 0 {
        v += (i % b) as f64 * f;
        i /= b;
        f /= b as f64;
    }
    v
}

/// The first `n` primes.
fn first_primes(n: usize) -> Vec<u64> {
    let mut primes: Vec<u64> = Vec::with_capacity(n);
    let mut k = 2u64;
    while primes.len() < n {
        if primes.iter().take_while(|&&p| p * p <= k).all(|&p| !k.is_multiple_of(p)) {
            primes.push(k);
        }
        k += 1;
    }
    primes
}

/// SplitMix64 (Steele, Lea and Flood 2014): a well-mixed 64-bit value per call.
pub(crate) fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The top 53 bits as a double in `[0, 1)`.
pub(crate) fn unit(v: u64) -> f64 {
    (v >> 11) as f64 / (1u64 << 53) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radical_inverses_are_the_textbook_values() {
        // Base 2: 1/2, 1/4, 3/4, 1/8; base 3: 1/3, 2/3, 1/9 (exact binary fractions or one rounding).
        let b2: Vec<f64> = (1..=4).map(|i| radical_inverse(i, 2)).collect();
        assert_eq!(b2, [0.5, 0.25, 0.75, 0.125]);
        assert!((radical_inverse(3, 3) - 1.0 / 9.0).abs() < 1e-16);
        assert_eq!(first_primes(6), [2, 3, 5, 7, 11, 13]);
    }

    #[test]
    fn points_are_addressable_and_fill_the_cube() {
        let h = Halton::new(3, 7);
        let all: Vec<Vec<f64>> = (0..512).map(|i| h.point(i)).collect();
        assert_eq!(h.point(300), all[300], "a point depends on its index only");
        // Low discrepancy: each of the 8 octants holds 512/8 = 64 points within a few.
        let mut counts = [0usize; 8];
        for p in &all {
            assert!(p.iter().all(|v| (0.0..1.0).contains(v)));
            counts[(p[0] >= 0.5) as usize + 2 * (p[1] >= 0.5) as usize + 4 * (p[2] >= 0.5) as usize] += 1;
        }
        assert!(counts.iter().all(|&c| (58..=70).contains(&c)), "{counts:?}");
        assert_ne!(Halton::new(3, 8).point(0), h.point(0), "another seed, another shift");
    }
}
