//! The link angles and velocity analogs the `class_four` example prints every 30 degrees of the
//! crank, against the Assur group of class IV solved in this test (`docs/papers.md`, paper 003),
//! never by kinloop: the two loops' projections written out, with their derivatives by hand,
//! solved together by Newton's method with Gaussian elimination, followed from the declared
//! guess over the turn in the example's steps of 0.5 degrees, each solve from the last; the
//! analogs are central differences of that solution. (The group cannot be solved loop by loop,
//! nor by a search over one angle: over the turn the dyad C-D-B passes through its stretched
//! position, where a search on the direction of AC changes branch.)

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../class_four.rs"]
mod class_four;

use class_four::turn;
use kinloop_fixtures::ClassFour;
use std::f64::consts::{PI, TAU};

/// An angle difference in `(-pi, pi]`.
fn wrap(a: f64) -> f64 {
    let d = a.rem_euclid(TAU);
    if d > PI { d - TAU } else { d }
}

/// The loops ACDB and AEFB, x and y, at `q = [th1, th2, psi1, psi2]` and crank angle `phi`, and
/// their derivatives by `q`.
fn loops(m: &ClassFour, phi: f64, q: [f64; 4]) -> ([f64; 4], [[f64; 4]; 4]) {
    let [th1, th2, psi1, psi2] = q;
    let (ta, tb) = (th1 + m.alpha_a, th2 + m.alpha_b);
    let (ax, ay) = (m.oa * phi.cos(), m.oa * phi.sin());
    let f = [
        ax + m.ac * th1.cos() + m.cd * psi1.cos() - m.xb - m.bd * th2.cos(),
        ay + m.ac * th1.sin() + m.cd * psi1.sin() - m.yb - m.bd * th2.sin(),
        ax + m.ae * ta.cos() + m.ef * psi2.cos() - m.xb - m.bf * tb.cos(),
        ay + m.ae * ta.sin() + m.ef * psi2.sin() - m.yb - m.bf * tb.sin(),
    ];
    let j = [
        [-m.ac * th1.sin(), m.bd * th2.sin(), -m.cd * psi1.sin(), 0.0],
        [m.ac * th1.cos(), -m.bd * th2.cos(), m.cd * psi1.cos(), 0.0],
        [-m.ae * ta.sin(), m.bf * tb.sin(), 0.0, -m.ef * psi2.sin()],
        [m.ae * ta.cos(), -m.bf * tb.cos(), 0.0, m.ef * psi2.cos()],
    ];
    (f, j)
}

/// `x` with `a x = b`, by Gaussian elimination with partial pivoting.
fn solve(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> [f64; 4] {
    for c in 0..4 {
        let p = (c..4).max_by(|&i, &k| a[i][c].abs().total_cmp(&a[k][c].abs())).expect("rows");
        a.swap(c, p);
        b.swap(c, p);
        assert!(a[c][c].abs() > 1e-6, "a regular Jacobian (no singular position on the turn)");
        for r in c + 1..4 {
            let (f, pivot) = (a[r][c] / a[c][c], a[c]);
            for (x, p) in a[r][c..].iter_mut().zip(&pivot[c..]) {
                *x -= f * p;
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 4];
    for r in (0..4).rev() {
        x[r] = (b[r] - (r + 1..4).map(|k| a[r][k] * x[k]).sum::<f64>()) / a[r][r];
    }
    x
}

/// The group `[th1, th2, psi1, psi2]` at `phi`, by Newton's method from `q` until a step is
/// below 1e-15 rad (at most 50 steps).
fn group(m: &ClassFour, phi: f64, mut q: [f64; 4]) -> [f64; 4] {
    for _ in 0..50 {
        let (f, j) = loops(m, phi, q);
        let dq = solve(j, f.map(|v| -v));
        for u in 0..4 {
            q[u] += dq[u];
        }
        if dq.iter().all(|d| d.abs() < 1e-15) {
            return q;
        }
    }
    let (f, _) = loops(m, phi, q);
    assert!(f.iter().all(|v| v.abs() < 1e-13), "phi = {phi}: the loops close ({f:?})");
    q
}

/// Positions to 1e-10 rad: Newton's root is within a few ulps (its last step below 1e-15 rad,
/// the loops' terms of order 1), and kinloop's residual tolerance (1e-12 of the loops' terms) leaves them
/// within about 1e-12 (the example prints six decimals). Analogs to 1e-7: the central
/// difference's step of 1e-5 rad makes a truncation error of `h^2 / 6` times the third
/// derivative (below 1e-9 for third derivatives up to 60) and a rounding error of about
/// `1e-15 / h` = 1e-10 (the example prints five decimals).
#[test]
fn the_printed_angles_and_analogs_agree_with_the_group_solved_from_its_geometry() -> Result<(), kinloop::Error> {
    let m = ClassFour::default();
    let states = turn(&m)?;
    assert_eq!(states.len(), 721);
    let g = m.guess(0.0);
    let mut near = [g.th1, g.th2, g.psi1, g.psi2];
    let h = 1e-5;
    for (k, s) in states.iter().enumerate() {
        let phi = s.input.phi;
        assert!((phi - k as f64 * TAU / 720.0).abs() < 1e-12, "sample {k} at {phi}");
        near = group(&m, phi, near);
        if k % 60 != 0 {
            continue;
        }
        let q = [s.q.th1, s.q.th2, s.q.psi1, s.q.psi2];
        let dq = [s.dq.th1, s.dq.th2, s.dq.psi1, s.dq.psi2];
        let (ahead, behind) = (group(&m, phi + h, near), group(&m, phi - h, near));
        for u in 0..4 {
            assert!(wrap(q[u] - near[u]).abs() < 1e-10, "phi = {phi}, unknown {u}: {} vs {}", q[u], near[u]);
            let fd = wrap(ahead[u] - behind[u]) / (2.0 * h);
            assert!((dq[u] - fd).abs() < 1e-7, "phi = {phi}, unknown {u}: analog {} vs {fd}", dq[u]);
        }
    }
    Ok(())
}
