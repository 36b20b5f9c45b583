//! A hand-written LU with partial pivoting for small fixed-size systems, as an expert writes
//! it for a hand-coded Newton (fixed sizes, fully unrollable loops, no checks beyond a zero or
//! non-finite pivot).

/// `P A = L U` of an `N x N` matrix given by rows, with the reciprocals of the pivots kept so
/// that solves multiply instead of divide.
#[derive(Clone, Copy, Debug)]
pub struct Lu<const N: usize> {
    lu: [[f64; N]; N],
    inv_pivot: [f64; N],
    perm: [usize; N],
}

impl<const N: usize> Lu<N> {
    /// Factorises `a`; `None` when a pivot is zero or not finite.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // index loops read like the textbook elimination
    pub fn factor(mut a: [[f64; N]; N]) -> Option<Self> {
        let mut perm = [0usize; N];
        for (k, p) in perm.iter_mut().enumerate() {
            *p = k;
        }
        let mut inv_pivot = [0.0; N];
        for k in 0..N {
            let mut best = k;
            for r in k + 1..N {
                if a[r][k].abs() > a[best][k].abs() {
                    best = r;
                }
            }
            if best != k {
                a.swap(k, best);
                perm.swap(k, best);
            }
            let pivot = a[k][k];
            if pivot == 0.0 || !pivot.is_finite() {
                return None;
            }
            let inv = 1.0 / pivot;
            inv_pivot[k] = inv;
            for r in k + 1..N {
                let m = a[r][k] * inv;
                a[r][k] = m;
                for c in k + 1..N {
                    a[r][c] -= m * a[k][c];
                }
            }
        }
        Some(Lu { lu: a, inv_pivot, perm })
    }

    /// Solves `A x = b`.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)]
    pub fn solve(&self, b: [f64; N]) -> [f64; N] {
        let mut x = [0.0; N];
        for r in 0..N {
            let mut acc = b[self.perm[r]];
            for c in 0..r {
                acc -= self.lu[r][c] * x[c];
            }
            x[r] = acc;
        }
        for r in (0..N).rev() {
            let mut acc = x[r];
            for c in r + 1..N {
                acc -= self.lu[r][c] * x[c];
            }
            x[r] = acc * self.inv_pivot[r];
        }
        x
    }
}

/// Largest magnitude (NaN propagates, so a NaN residual never counts as converged).
#[inline(always)]
pub fn max_abs<const N: usize>(v: &[f64; N]) -> f64 {
    let mut m = 0.0f64;
    for x in v {
        let a = x.abs();
        m = if a > m || a.is_nan() { a } else { m };
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_with_pivoting() {
        let a = [[0.0, 2.0, 1.0, 0.0], [1.0, 1.0, 0.0, 3.0], [3.0, 0.0, 1.0, 1.0], [0.5, -1.0, 2.0, 0.0]];
        let x = [1.0, -2.0, 0.5, 0.25];
        let b: [f64; 4] = std::array::from_fn(|r| (0..4).map(|c| a[r][c] * x[c]).sum());
        let z = Lu::factor(a).unwrap().solve(b);
        for k in 0..4 {
            assert!((z[k] - x[k]).abs() < 1e-14, "{z:?}");
        }
        assert!(Lu::factor([[1.0, 2.0], [2.0, 4.0]]).is_none());
    }
}
