//! Large sparse Newton blocks factorised by the straight-line code `mechanism!` emits for their
//! pattern (every slot a constant index): the same factor as the general table-driven sparse
//! LU (`Tables`, the runtime's loops over the pattern's index tables), bit for bit, on a ring
//! of loops and on a randomly coupled declaration; both checked against the dense
//! partial-pivoting LU and against the residual of the solved system, independent of either;
//! a weak static pivot (or a non-finite entry) takes the dense fallback, never a wrong answer.

use kinloop::__gen::{BlockJacobian, Lu, SparseJac, SparseLu, SparseSteps, Tables};
use kinloop::{Mechanism, NewtonConfig};

kinloop::mechanism! {
    /// 16 four-bar loops closed into a ring through a differential: one sparse block of 32.
    pub struct Ring16 {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns
            u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
            u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9,
            u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9,
            u12 = 0.6, v12 = 1.9, u13 = 0.6, v13 = 1.9, u14 = 0.6, v14 = 1.9, u15 = 0.6, v15 = 1.9;
        loop l0: a @ (0.5 * (phi + v15)) + b @ u0 == (d, 0) + c @ v0;
        loop l1: a @ v0 + b @ u1 == (d, 0) + c @ v1;
        loop l2: a @ v1 + b @ u2 == (d, 0) + c @ v2;
        loop l3: a @ v2 + b @ u3 == (d, 0) + c @ v3;
        loop l4: a @ v3 + b @ u4 == (d, 0) + c @ v4;
        loop l5: a @ v4 + b @ u5 == (d, 0) + c @ v5;
        loop l6: a @ v5 + b @ u6 == (d, 0) + c @ v6;
        loop l7: a @ v6 + b @ u7 == (d, 0) + c @ v7;
        loop l8: a @ v7 + b @ u8 == (d, 0) + c @ v8;
        loop l9: a @ v8 + b @ u9 == (d, 0) + c @ v9;
        loop l10: a @ v9 + b @ u10 == (d, 0) + c @ v10;
        loop l11: a @ v10 + b @ u11 == (d, 0) + c @ v11;
        loop l12: a @ v11 + b @ u12 == (d, 0) + c @ v12;
        loop l13: a @ v12 + b @ u13 == (d, 0) + c @ v13;
        loop l14: a @ v13 + b @ u14 == (d, 0) + c @ v14;
        loop l15: a @ v14 + b @ u15 == (d, 0) + c @ v15;
    }
}

// 16 four-bar loops, each driven by the mean of the rockers of two others drawn at random
// (Python's `random.seed(20261128)`, `random.sample` of two other loops): a coupling with
// more fill than the ring's, one sparse block of 28 (two loops drive others and are driven by
// none of the block).
kinloop::mechanism! {
    /// Randomly coupled four-bar loops.
    pub struct Coupled {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns
            u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
            u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9,
            u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9,
            u12 = 0.6, v12 = 1.9, u13 = 0.6, v13 = 1.9, u14 = 0.6, v14 = 1.9, u15 = 0.6, v15 = 1.9;
        loop l0: a @ (0.5 * (phi + v8)) + b @ u0 == (d, 0) + c @ v0;
        loop l1: a @ (0.5 * (v12 + v13)) + b @ u1 == (d, 0) + c @ v1;
        loop l2: a @ (0.5 * (v1 + v0)) + b @ u2 == (d, 0) + c @ v2;
        loop l3: a @ (0.5 * (v11 + v7)) + b @ u3 == (d, 0) + c @ v3;
        loop l4: a @ (0.5 * (v7 + v6)) + b @ u4 == (d, 0) + c @ v4;
        loop l5: a @ (0.5 * (v15 + v9)) + b @ u5 == (d, 0) + c @ v5;
        loop l6: a @ (0.5 * (v14 + v12)) + b @ u6 == (d, 0) + c @ v6;
        loop l7: a @ (0.5 * (v0 + v3)) + b @ u7 == (d, 0) + c @ v7;
        loop l8: a @ (0.5 * (v12 + v5)) + b @ u8 == (d, 0) + c @ v8;
        loop l9: a @ (0.5 * (v1 + v11)) + b @ u9 == (d, 0) + c @ v9;
        loop l10: a @ (0.5 * (v15 + v7)) + b @ u10 == (d, 0) + c @ v10;
        loop l11: a @ (0.5 * (v3 + v7)) + b @ u11 == (d, 0) + c @ v11;
        loop l12: a @ (0.5 * (v4 + v5)) + b @ u12 == (d, 0) + c @ v12;
        loop l13: a @ (0.5 * (v11 + v9)) + b @ u13 == (d, 0) + c @ v13;
        loop l14: a @ (0.5 * (v13 + v0)) + b @ u14 == (d, 0) + c @ v14;
        loop l15: a @ (0.5 * (v8 + v1)) + b @ u15 == (d, 0) + c @ v15;
    }
}

kinloop::mechanism! {
    /// `Coupled` solved as one dense block.
    #[kinloop(dense)]
    pub struct CoupledDense {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns
            u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
            u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9,
            u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9,
            u12 = 0.6, v12 = 1.9, u13 = 0.6, v13 = 1.9, u14 = 0.6, v14 = 1.9, u15 = 0.6, v15 = 1.9;
        loop l0: a @ (0.5 * (phi + v8)) + b @ u0 == (d, 0) + c @ v0;
        loop l1: a @ (0.5 * (v12 + v13)) + b @ u1 == (d, 0) + c @ v1;
        loop l2: a @ (0.5 * (v1 + v0)) + b @ u2 == (d, 0) + c @ v2;
        loop l3: a @ (0.5 * (v11 + v7)) + b @ u3 == (d, 0) + c @ v3;
        loop l4: a @ (0.5 * (v7 + v6)) + b @ u4 == (d, 0) + c @ v4;
        loop l5: a @ (0.5 * (v15 + v9)) + b @ u5 == (d, 0) + c @ v5;
        loop l6: a @ (0.5 * (v14 + v12)) + b @ u6 == (d, 0) + c @ v6;
        loop l7: a @ (0.5 * (v0 + v3)) + b @ u7 == (d, 0) + c @ v7;
        loop l8: a @ (0.5 * (v12 + v5)) + b @ u8 == (d, 0) + c @ v8;
        loop l9: a @ (0.5 * (v1 + v11)) + b @ u9 == (d, 0) + c @ v9;
        loop l10: a @ (0.5 * (v15 + v7)) + b @ u10 == (d, 0) + c @ v10;
        loop l11: a @ (0.5 * (v3 + v7)) + b @ u11 == (d, 0) + c @ v11;
        loop l12: a @ (0.5 * (v4 + v5)) + b @ u12 == (d, 0) + c @ v12;
        loop l13: a @ (0.5 * (v11 + v9)) + b @ u13 == (d, 0) + c @ v13;
        loop l14: a @ (0.5 * (v13 + v0)) + b @ u14 == (d, 0) + c @ v14;
        loop l15: a @ (0.5 * (v8 + v1)) + b @ u15 == (d, 0) + c @ v15;
    }
}

const N: usize = 32;

/// A deterministic stream of values in `[-1, 1)` (xorshift64*).
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        bits as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// Random values of the pattern's entries, the static pivots `pivot` times larger than the
/// rest (so that, unless `pivot` is small, the static order is accepted).
fn values<const M: usize, const NNZ: usize, const NLU: usize, E: SparseSteps<M, NLU>>(
    j: &SparseJac<M, NNZ, NLU, E>,
    s: &mut Stream,
    pivot: f64,
) -> [f64; NNZ] {
    let p = j.pattern;
    let mut v = [0.0; NNZ];
    for (e, ve) in v.iter_mut().enumerate() {
        // The entry's row: the last whose entries start at or before it.
        let r = p.row_ptr.partition_point(|&start| start as usize <= e) - 1;
        let c = p.col[e] as usize;
        let on_pivot = (0..M).any(|k| p.prow[k] as usize == r && p.pcol[k] as usize == c);
        *ve = if on_pivot { pivot * (1.5 + s.next()) } else { s.next() };
    }
    v
}

/// `max_r |(J x - b)_r| / (sum_c |J_rc x_c| + |b_r|)`: the residual of a solution relative to
/// the size of its terms (a backward error, independent of the factorisation that solved it).
fn backward_error<const M: usize>(j: &[[f64; M]; M], x: &[f64; M], b: &[f64; M]) -> f64 {
    (0..M)
        .map(|r| {
            let (mut sum, mut size) = (-b[r], b[r].abs());
            for c in 0..M {
                sum += j[r][c] * x[c];
                size += (j[r][c] * x[c]).abs();
            }
            sum.abs() / size
        })
        .fold(0.0, f64::max)
}

/// The emitted steps and the tables factorise `j` alike, bit for bit; the solution solves the
/// system to rounding and agrees with the dense LU's. Returns whether the static order was
/// rejected (the dense fallback taken).
fn same_factor<const M: usize, const NNZ: usize, const NLU: usize, E: SparseSteps<M, NLU>>(
    j: SparseJac<M, NNZ, NLU, E>,
    s: &mut Stream,
) -> bool {
    let tables: SparseJac<M, NNZ, NLU, Tables> = j.with_steps::<Tables>();
    let rows: [f64; M] = core::array::from_fn(|_| 2.0 + s.next());
    let cols: [f64; M] = core::array::from_fn(|_| 2.0 + s.next());
    let b: [f64; M] = core::array::from_fn(|_| s.next());
    let (emitted, general): (SparseLu<M, NLU, E>, SparseLu<M, NLU, Tables>) =
        (j.factor_scaled(rows, cols), tables.factor_scaled(rows, cols));
    assert_eq!(emitted.is_dense(), general.is_dense());
    assert_eq!(emitted.pivot_ratio().to_bits(), general.pivot_ratio().to_bits());
    assert_eq!(emitted.det().to_bits(), general.det().to_bits());
    assert_eq!(emitted.negative_det(), general.negative_det());
    let x = emitted.solve(b);
    assert_eq!(x.map(f64::to_bits), general.solve(b).map(f64::to_bits));
    // Independent of both: the residual of the system, and the dense partial-pivoting LU.
    let dense = j.to_dense();
    // The static order's pivots pass the threshold test (growth of at most 11 per
    // elimination), so the backward error stays at a few hundred ulps on 30-odd unknowns.
    let err = backward_error(&dense, &x, &b);
    assert!(err <= 1e-13, "backward error {err:e}");
    let lu = Lu::factor_scaled(&dense, rows, cols);
    assert_eq!(emitted.negative_det(), lu.negative_det());
    let xd = lu.solve(b);
    let size = xd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for c in 0..M {
        // Both solve the same system to a backward error of ~1e-15; their difference is that
        // times the system's condition number, which the dominant pivots keep below ~1e3.
        assert!((x[c] - xd[c]).abs() <= 1e-11 * size, "unknown {c}: {} vs {}", x[c], xd[c]);
    }
    emitted.is_dense()
}

#[test]
fn both_declarations_are_one_sparse_block() {
    assert!(Ring16::DECOMPOSITION.contains("block 0 (Newton, 32x32 sparse"), "{}", Ring16::DECOMPOSITION);
    // Some loops drive others without being driven back: the coupled block is 28 of the 32.
    assert!(Coupled::DECOMPOSITION.contains("block 0 (Newton, 28x28 sparse"), "{}", Coupled::DECOMPOSITION);
    // More fill than the ring: the random coupling is not a relabelled ring.
    assert!(__CoupledSparsePattern0.upd.len() > __Ring16SparsePattern0.upd.len());
}

#[test]
fn the_emitted_factorisation_is_the_tables_bit_for_bit() {
    let mut s = Stream(0x9e37_79b9_7f4a_7c15);
    for _ in 0..50 {
        let ring = __Ring16SparseJac0::new([0.0; _], &__Ring16SparsePattern0);
        let ring = __Ring16SparseJac0::new(values(&ring, &mut s, 10.0), &__Ring16SparsePattern0);
        assert!(!same_factor(ring, &mut s), "dominant static pivots are accepted");
        let coupled = __CoupledSparseJac0::new([0.0; _], &__CoupledSparsePattern0);
        let coupled = __CoupledSparseJac0::new(values(&coupled, &mut s, 10.0), &__CoupledSparsePattern0);
        assert!(!same_factor(coupled, &mut s), "dominant static pivots are accepted");
    }
}

/// A static pivot far below the other entries of its column: the elimination along the static
/// order would divide by it (and amplify rounding by its inverse), so both implementations
/// reject it and the dense partial-pivoting LU solves instead, to rounding.
#[test]
fn a_weak_static_pivot_takes_the_dense_fallback() {
    let mut s = Stream(0x2545_f491_4f6c_dd1d);
    let pattern = &__CoupledSparsePattern0;
    // Pivots with other entries in their column (the last has none: nothing to compare with)
    // that no earlier elimination updates (so that the value set is the value tested).
    let tested: Vec<usize> = (0..pattern.diag.len())
        .filter(|&k| pattern.l_ptr[k + 1] > pattern.l_ptr[k] && !pattern.upd.contains(&pattern.diag[k]))
        .collect();
    assert!(tested.len() >= 3, "{tested:?}");
    for k in [tested[0], tested[tested.len() / 2], tested[tested.len() - 1]] {
        let j = weak_pivot(pattern, k, &mut s);
        assert!(same_factor(j, &mut s), "pivot {k}: the static order was kept");
    }
    // A NaN entry: singular (pivot ratio 0), never a silent NaN solution reported regular.
    let j = __Ring16SparseJac0::new([0.0; _], &__Ring16SparsePattern0);
    let mut v = values(&j, &mut s, 10.0);
    v[7] = f64::NAN;
    let lu = __Ring16SparseJac0::new(v, &__Ring16SparsePattern0).factor_cols([1.0; _]);
    assert_eq!(lu.pivot_ratio(), 0.0);
}

/// Random values of the pattern's entries with static pivot `k` set to `1e-6`: weak against
/// the other entries of its column (dominant pivots of about 10, other entries below 1).
fn weak_pivot(pattern: &'static kinloop::__gen::SparsePattern, k: usize, s: &mut Stream) -> __CoupledSparseJac0 {
    let (r, c) = (pattern.prow[k] as usize, pattern.pcol[k] as usize);
    let mut v = values(&__CoupledSparseJac0::new([0.0; _], pattern), s, 10.0);
    let e = (pattern.row_ptr[r] as usize..pattern.row_ptr[r + 1] as usize)
        .find(|&e| pattern.col[e] as usize == c)
        .expect("a pivot is an entry");
    v[e] = 1e-6;
    __CoupledSparseJac0::new(v, pattern)
}

/// The solve through the emitted factorisation against the dense block: the same positions
/// and analogs along a turn of the input, to the Newton tolerance amplified by the block's
/// condition.
#[test]
fn the_coupled_loops_solve_like_their_dense_twin() {
    let cfg = NewtonConfig::default();
    let (m, twin) = (Coupled::default(), CoupledDense::default());
    let mut q = m.kinematics_flat(&[0.0], &m.guess(0.0).into(), &cfg).expect("assembles").q;
    let mut qd = q;
    for k in 0..24 {
        let phi = std::f64::consts::TAU * k as f64 / 24.0;
        let (a, b) = (
            m.kinematics_flat(&[phi], &q, &cfg).expect("sparse"),
            twin.kinematics_flat(&[phi], &qd, &cfg).expect("dense"),
        );
        for u in 0..N {
            assert!((a.q[u] - b.q[u]).abs() <= 1e-12, "{phi} q{u}: {} vs {}", a.q[u], b.q[u]);
            assert!((a.dq[u][0] - b.dq[u][0]).abs() <= 1e-11, "{phi} dq{u}");
            assert!((a.d2q[u][0][0] - b.d2q[u][0][0]).abs() <= 1e-10, "{phi} d2q{u}");
        }
        (q, qd) = (a.q, b.q);
    }
}
