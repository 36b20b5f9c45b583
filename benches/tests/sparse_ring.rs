//! The ring of 64 four-bar loops closed through a differential (`kinloop_bench::ring`): one
//! Newton block of 128 unknowns, factorised along its sparsity. Checked against three
//! independent computations: its `#[kinloop(dense)]` twin (dense partial-pivoting LU), the same
//! loops in series (64 closed-form RRR dyads, driven by the ring's differential carrier) and
//! central finite differences of its positions.

use kinloop::{Kin, Mechanism, NewtonConfig};
use kinloop_bench::expansion::four_bar_ring;
use kinloop_bench::ring::{RING, Ring, RingDense, Series};

const N: usize = 128;
type State = Kin<N, 1, 0>;

/// `samples` states of `m` along one turn of the input, each solved from the previous one.
fn turn<M: Mechanism<N, 1, 0>>(m: &M, samples: usize) -> Vec<State> {
    let cfg = NewtonConfig::default();
    let mut q = m.kinematics_flat(&[0.0], &Ring::default().guess(0.0).into(), &cfg).expect("assembles").q;
    (0..samples)
        .map(|k| {
            let phi = std::f64::consts::TAU * k as f64 / samples as f64;
            let s = m.kinematics_flat(&[phi], &q, &cfg).expect("assembles");
            q = s.q;
            s
        })
        .collect()
}

/// `|a - b| / max(1, |a|, |b|)`: absolute for values of order one (angles in radians, analogs
/// of links of comparable lengths), relative beyond.
fn diff(a: f64, b: f64) -> f64 {
    (a - b).abs() / 1f64.max(a.abs()).max(b.abs())
}

fn worst(a: &State, b: &State) -> [f64; 3] {
    let mut w = [0.0f64; 3];
    for u in 0..N {
        w[0] = w[0].max(diff(a.q[u], b.q[u]));
        w[1] = w[1].max(diff(a.dq[u][0], b.dq[u][0]));
        w[2] = w[2].max(diff(a.d2q[u][0][0], b.d2q[u][0][0]));
    }
    w
}

#[test]
fn the_ring_is_one_sparse_block_and_its_twin_dense() {
    println!("{}", Ring::DECOMPOSITION.lines().take(2).collect::<Vec<_>>().join("\n"));
    assert!(Ring::DECOMPOSITION.contains("1 block in solve order"), "{}", Ring::DECOMPOSITION);
    assert!(Ring::DECOMPOSITION.contains("block 0 (Newton, 128x128 sparse (384 non-zeros))"));
    assert!(RingDense::DECOMPOSITION.contains("block 0 (Newton, 128x128)"), "{}", RingDense::DECOMPOSITION);
    assert_eq!(Series::BLOCKS.len(), 64);
}

/// The written-out declaration is the generator's (the expansion-size test measures the
/// generator's rings of other sizes).
#[test]
fn the_written_out_ring_is_the_generated_one() {
    let strip = |s: &str| s.chars().filter(|c| !c.is_whitespace()).collect::<String>();
    assert!(strip(RING).ends_with(&strip(&four_bar_ring(64))), "{RING}");
}

/// Sparse and dense factorisations of the same Newton block: the same positions and analogs
/// to rounding (1e-12: both converge to the 1e-12 scaled residual and then apply one more
/// correction, leaving differences of a few ulps amplified by the block's condition), the same
/// determinant sign (assembly mode) and pivot ratios that agree on regularity.
#[test]
fn the_ring_matches_its_dense_twin_along_a_turn() {
    // The dense twin's 128x128 Jacobian and LU (128 KiB each, copied freely by an
    // unoptimised build) need more than a test thread's 2 MiB of stack.
    let dense = std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(|| turn(&RingDense::default(), 48))
        .expect("a thread")
        .join()
        .expect("the dense twin solves");
    let sparse = turn(&Ring::default(), 48);
    let mut w = [0.0f64; 3];
    for (s, d) in sparse.iter().zip(&dense) {
        for (k, v) in worst(s, d).into_iter().enumerate() {
            w[k] = w[k].max(v);
        }
        assert_eq!(s.health.det_signs, d.health.det_signs, "assembly mode at {:?}", s.x);
        assert!(
            s.health.min_pivot > 1e-3 && d.health.min_pivot > 1e-3,
            "{} {}",
            s.health.min_pivot,
            d.health.min_pivot
        );
    }
    let ratios = |v: &[State]| {
        v.iter().map(|s| s.health.min_pivot).fold((f64::INFINITY, 0.0f64), |(a, b), p| (a.min(p), b.max(p)))
    };
    println!("pivot ratios along the turn: sparse {:?}, dense {:?}", ratios(&sparse), ratios(&dense));
    println!("worst differences sparse - dense: q {:.1e}, dq {:.1e}, d2q {:.1e}", w[0], w[1], w[2]);
    assert!(w.iter().all(|&v| v <= 1e-12), "{w:?}");
}

/// The ring's differential carrier `c = (phi + v63) / 2` drives the series' first loop: the
/// series solved in closed form at `c` must give every unknown of the ring, and the ring's
/// analogs are the series' times `dc/dphi = (1 + v63') / 2` (and for the second analogs
/// `s'' c'^2 + s' c''` with `c'' = v63'' / 2`).
#[test]
fn the_ring_closes_the_series_in_closed_form() {
    let (ring, series, cfg) = (Ring::default(), Series::default(), NewtonConfig::default());
    let mut w = [0.0f64; 3];
    for s in turn(&ring, 48) {
        let last = N - 1;
        let c = 0.5 * (s.x[0] + s.q[last]);
        let (c1, c2) = (0.5 * (1.0 + s.dq[last][0]), 0.5 * s.d2q[last][0][0]);
        let t = series.kinematics_flat(&[c], &s.q, &cfg).expect("the series assembles");
        for u in 0..N {
            w[0] = w[0].max(diff(s.q[u], t.q[u]));
            w[1] = w[1].max(diff(s.dq[u][0], t.dq[u][0] * c1));
            w[2] = w[2].max(diff(s.d2q[u][0][0], t.d2q[u][0][0] * c1 * c1 + t.dq[u][0] * c2));
        }
    }
    println!("worst differences ring - series: q {:.1e}, dq {:.1e}, d2q {:.1e}", w[0], w[1], w[2]);
    assert!(w.iter().all(|&v| v <= 1e-12), "{w:?}");
}

/// Central differences with step `h = 1e-4`: truncation `h^2 q''' / 6` (~1e-9 for third
/// derivatives of order one) above rounding `eps / h` (~1e-12); 1e-8 leaves room for the
/// largest third analogs of the chain.
#[test]
fn the_rings_analogs_are_central_differences_of_its_positions() {
    let (m, cfg, h) = (Ring::default(), NewtonConfig::default(), 1e-4);
    let mut w = [0.0f64; 2];
    for s in turn(&m, 12) {
        let at = |phi: f64| m.kinematics_flat(&[phi], &s.q, &cfg).expect("assembles");
        let (p, n) = (at(s.x[0] + h), at(s.x[0] - h));
        for u in 0..N {
            w[0] = w[0].max(diff(s.dq[u][0], (p.q[u] - n.q[u]) / (2.0 * h)));
            w[1] = w[1].max(diff(s.d2q[u][0][0], (p.dq[u][0] - n.dq[u][0]) / (2.0 * h)));
        }
    }
    // The analogs at a given position (their own factorisation of the sparse block) are the
    // same numbers.
    for s in turn(&m, 4) {
        let at = m.kinematics_at_flat(&s.x, &s.q, &cfg).expect("regular");
        assert!(worst(&s, &at).iter().all(|&v| v <= 1e-12), "{:?}", worst(&s, &at));
        assert_eq!(at.health.det_signs, s.health.det_signs);
    }
    println!("worst differences against central differences: dq {:.1e}, d2q {:.1e}", w[0], w[1]);
    assert!(w.iter().all(|&v| v <= 1e-8), "{w:?}");
}
