//! A mechanism of many blocks beyond the closed forms' sizes solves, or fails, where and as it
//! does at size 1. At size 1 its blocks are solved one at a time, each from its guess with the
//! blocks before it solved; beyond `1e±144` the rescue solved the position by Newton over the
//! whole system at once (`runtime/src/mechanism/extreme_scale.rs`), which needs a guess close
//! enough for every block together. On the 108 chains of five four-bars below (each driven by
//! the last one's rocker, ten unknowns), at 12 inputs and 4 sizes, 2137 of the 5184 solves
//! differed from size 1: 66 failed where size 1 solves, 16 had an angle a whole turn off, one
//! solved where size 1 fails, and 2054 of the failures named another block or another error
//! (a chain whose crank cannot close its first loop was said to fail in its second to its
//! fifth loop, by size). The rescue now solves the blocks in turn, as size 1 does.

use kinloop::{Error, Mechanism, NewtonConfig};
use std::mem::discriminant;

use crate::extreme_scales::{FourBarChain, FourBarChainNewton};

/// 108 chains: crank `a`, coupler `b`, rocker `c`, frame `d` at size 1, every four-bar of a
/// chain alike. Some assemble at every crank angle, some only over part of a turn (the crank's
/// end must stay within `|b - c| .. b + c` of the rocker's pivot), and a later four-bar's crank
/// is the last one's rocker, which swings over part of a turn: a chain fails in its first loop
/// at some inputs and in a later one at others.
fn chains() -> Vec<[f64; 4]> {
    let mut all = Vec::new();
    for a in [0.5, 1.0, 2.0, 2.5] {
        for b in [2.0, 3.0, 4.5] {
            for c in [1.5, 2.5, 3.5] {
                for d in [2.0, 3.5, 5.0] {
                    all.push([a, b, c, d]);
                }
            }
        }
    }
    all
}

/// 12 inputs spread over a turn, none at a multiple of `pi / 12` (where a chain of these
/// lengths could sit on a limit position exactly).
fn inputs() -> impl Iterator<Item = f64> {
    (0..12).map(|i| -3.0 + 0.5 * i as f64 + 0.01)
}

/// The sizes beyond the closed forms' on both sides.
const SIZES: [f64; 4] = [1e-300, 1e-200, 1e200, 1e300];

/// How far the angles at another size may be from size 1's: each loop's residual is rounded to
/// a few `eps` of its magnitude (its four terms, its lengths times `k` rounded to half an ulp),
/// and a residual change moves the angles by the inverse Jacobian: at most `eps` times the
/// chain's [`condition`] `kappa` each way, 4 of them allowed. Near the limit positions of its
/// stages, a chain passes its first rockers' errors on amplified: over these chains at 24
/// inputs, `kappa` reached `1.6e4`, where the angles differed by `1.5e-12` (`0.44 eps kappa`),
/// and the largest difference was `1.5 eps kappa`, where `kappa` is below 10 and the angles
/// differ by an ulp or two.
fn tolerance(kappa: f64) -> f64 {
    4.0 * f64::EPSILON * kappa.max(1.0)
}

/// The chain of `lengths` at input `x` from its declared guess solved at size 1 by its Newton
/// twin: the generated Newton solver, block by block, in place of the closed forms.
fn twin(lengths: &[f64; 4], x: f64) -> Result<kinloop::Kin<10, 1, 2>, Error> {
    let [a, b, c, d] = *lengths;
    let m = FourBarChainNewton { a, b, c, d };
    m.kinematics_flat(&[x], &m.guess_flat(&[x]), &NewtonConfig::default())
}

/// An error as size 1's is compared: its variant and the block it names.
fn kind(e: &Error) -> (std::mem::Discriminant<Error>, Option<usize>) {
    (discriminant(e), e.location().and_then(|at| at.block.as_ref().map(|b| b.0)))
}

/// Every chain at every input solves at every size beyond the closed forms' where it solves at
/// size 1 (the same angles to their [`tolerance`]), and fails where it fails there with the
/// same error in the same block.
#[test]
fn a_chain_of_blocks_solves_and_fails_as_at_size_one() {
    let cfg = NewtonConfig::default();
    let mut differ = Vec::new();
    let (mut solved, mut failed) = (0, 0);
    let mut failing = std::collections::BTreeSet::new();
    for lengths in chains() {
        let at = |k: f64| {
            let [a, b, c, d] = lengths.map(|l| l * k);
            FourBarChain { a, b, c, d }
        };
        let one = at(1.0);
        for x in inputs() {
            let base = one.kinematics_flat(&[x], &one.guess_flat(&[x]), &cfg);
            match &base {
                Ok(_) => solved += 1,
                Err(e) => {
                    failed += 1;
                    failing.insert(kind(e).1);
                }
            }
            for k in SIZES {
                let m = at(k);
                let got = m.kinematics_flat(&[x], &m.guess_flat(&[x]), &cfg);
                let alike = match (&base, &got) {
                    (Ok(b), Ok(g)) => {
                        let tol = tolerance(condition(&one.jacobian_flat(&[x], &b.q)));
                        b.q.iter().zip(&g.q).all(|(b, g)| (b - g).abs() <= tol)
                    }
                    // Where Newton's iterations run out with the residual still falling, it
                    // cannot tell a chain that does not assemble from one it did not reach, and
                    // says so; the same chain's Newton twin says so at size 1.
                    (Err(b), Err(g)) => {
                        kind(b) == kind(g) || twin(&lengths, x).err().as_ref().map(kind) == Some(kind(g))
                    }
                    _ => false,
                };
                if !alike {
                    let show = |r: &Result<kinloop::Kin<10, 1, 2>, Error>| match r {
                        Ok(kin) => format!("{:?}", kin.q),
                        Err(e) => format!("{e}"),
                    };
                    differ.push(format!("{lengths:?} phi {x} size {k:e}: {} against {}", show(&got), show(&base)));
                }
            }
        }
    }
    eprintln!("chains at size 1: {solved} solved, {failed} failed in blocks {failing:?}; {} differ", differ.len());
    // Both kinds of case are met, failures in the first block and in later ones: the test is
    // not of chains that always solve, nor of a failure Newton over the whole system names
    // alike.
    assert!(solved > 500 && failed > 50, "{solved} solved, {failed} failed at size 1");
    assert!(failing.len() == 5, "failures at size 1 only in blocks {failing:?}");
    assert!(differ.is_empty(), "{} of {} differ:\n{}", differ.len(), 4 * (solved + failed), differ.join("\n"));
}

/// How far the angles of a solved chain can move for a rounding of its equations: the largest
/// over the unknowns of `sum_e |(J^-1)_ue| scale_e`, the change of an angle when each equation's
/// residual changes by its magnitude (`Jac::scale`), times `eps` the angles' error from
/// residuals rounded to `eps` of their terms. By Gauss-Jordan elimination with partial pivoting
/// of `J` beside `diag(scale)`.
fn condition(jac: &kinloop::Jac<10, 1>) -> f64 {
    const N: usize = 10;
    let mut a = jac.j;
    let mut b: [[f64; N]; N] =
        std::array::from_fn(|e| std::array::from_fn(|u| if u == e { jac.scale[e] } else { 0.0 }));
    for c in 0..N {
        let p = (c..N).max_by(|&i, &k| a[i][c].abs().total_cmp(&a[k][c].abs())).unwrap_or(c);
        a.swap(c, p);
        b.swap(c, p);
        let pivot = a[c][c];
        if pivot == 0.0 {
            return f64::INFINITY;
        }
        for r in 0..N {
            if r != c {
                let f = a[r][c] / pivot;
                for k in 0..N {
                    a[r][k] -= f * a[c][k];
                    b[r][k] -= f * b[c][k];
                }
            }
        }
    }
    (0..N).map(|u| b[u].iter().map(|v| v.abs()).sum::<f64>() / a[u][u].abs()).fold(0.0, f64::max)
}
