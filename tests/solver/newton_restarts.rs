//! A Newton block whose iteration stalls in a fold of its residual restarts before it reports
//! "cannot be assembled" (`NewtonConfig::restarts`): the class IV group of paper 003
//! (`docs/papers.md`) and a class III group (a triad), solved from guesses up to a radian off in
//! every angle.

use kinloop::{Error, Mechanism, NewtonConfig};
use kinloop_fixtures::{ClassFour, ClassFourUnknowns};
use std::f64::consts::PI;

use crate::support::{Xorshift, tol};

/// The two loops of the group, written out here: `A + AC + CD - (B + BD)` and
/// `A + AE + EF - (B + BF)`, each projected on X and Y.
fn loop_gaps(m: &ClassFour, phi: f64, [th1, th2, psi1, psi2]: [f64; 4]) -> [f64; 4] {
    let at = |l: f64, a: f64| (l * a.cos(), l * a.sin());
    let (a, ac, cd, bd) = (at(m.oa, phi), at(m.ac, th1), at(m.cd, psi1), at(m.bd, th2));
    let (ae, ef, bf) = (at(m.ae, th1 + m.alpha_a), at(m.ef, psi2), at(m.bf, th2 + m.alpha_b));
    [
        a.0 + ac.0 + cd.0 - (m.xb + bd.0),
        a.1 + ac.1 + cd.1 - (m.yb + bd.1),
        a.0 + ae.0 + ef.0 - (m.xb + bf.0),
        a.1 + ae.1 + ef.1 - (m.yb + bf.1),
    ]
}

kinloop::mechanism! {
    /// A class III group driven by a crank: the ternary link P1-P2-P3 (angle `t`), joined to the
    /// crank pin A by the binary link P1 (angle `b1`) and to the frame at B and C by the binary
    /// links P2-B (`b2`) and P3-C (`b3`). The frame points are those of an assembly at
    /// `b1 = 1.2, t = 0.1, b2 = -1.3, b3 = 2.5` at phi = 0, to four places.
    pub struct Triad {
        params oa = 1.0, l1 = 2.0, p12 = 2.5, p13 = 1.8, gamma = 1.0, l2 = 2.2, l3 = 2.0,
               bx = 3.6235, by = 4.2339, cx = 4.1333, cy = 2.2711;
        input phi;
        unknowns b1 = 1.2, t = 0.1, b2 = -1.3, b3 = 2.5;
        let a = oa @ phi;
        loop one: a + l1 @ b1 + p12 @ t == (bx, by) + l2 @ b2;
        loop two: a + l1 @ b1 + p13 @ (t + gamma) == (cx, cy) + l3 @ b3;
    }
}

/// The triad's two loops written out, as [`loop_gaps`] for the class IV group.
fn triad_gaps(m: &Triad, phi: f64, [b1, t, b2, b3]: [f64; 4]) -> [f64; 4] {
    let at = |l: f64, a: f64| (l * a.cos(), l * a.sin());
    let (a, p1, p12, p13) = (at(m.oa, phi), at(m.l1, b1), at(m.p12, t), at(m.p13, t + m.gamma));
    let (b, c) = (at(m.l2, b2), at(m.l3, b3));
    [
        a.0 + p1.0 + p12.0 - (m.bx + b.0),
        a.1 + p1.1 + p12.1 - (m.by + b.1),
        a.0 + p1.0 + p13.0 - (m.cx + c.0),
        a.1 + p1.1 + p13.1 - (m.cy + c.1),
    ]
}

/// Uniform numbers in `[-1, 1)` from a fixed seed.
struct Rng(Xorshift);

impl Rng {
    fn next(&mut self) -> f64 {
        2.0 * self.0.unit() - 1.0
    }
}

/// Solves `m` at each input of `refs` (with an assembly there) from `per_input` guesses, each
/// angle up to a radian off the assembly's, with and without restarts. Every solve with
/// restarts closes the loops (`gaps`, written out by the test) on the guess's turns, or ends
/// `NoConvergence`; none is `NoAssembly`. Returns how many stalled without restarts and how many
/// were solved with them.
fn from_guesses_a_radian_off<M: Mechanism<4, 1, NO>, const NO: usize>(
    m: &M,
    refs: &[(f64, [f64; 4])],
    per_input: usize,
    rng: &mut Rng,
    gaps: impl Fn(f64, [f64; 4]) -> [f64; 4],
) -> (usize, usize) {
    let cfg = NewtonConfig::default();
    let (mut stalls_alone, mut solved) = (0, 0);
    for &(phi, q_ref) in refs {
        for _ in 0..per_input {
            let g: [f64; 4] = core::array::from_fn(|u| q_ref[u] + rng.next());
            let alone = m.position_flat(&[phi], &g, &cfg.with_restarts(false));
            stalls_alone += usize::from(matches!(alone, Err(Error::NoAssembly { .. })));
            match m.position_flat(&[phi], &g, &cfg) {
                Ok((q, _)) => {
                    solved += 1;
                    let gap = gaps(phi, q).iter().fold(0.0f64, |w, v| w.max(v.abs()));
                    // Residual tolerance 1e-12 of loops about 10 long, and a final correction.
                    assert!(gap < 1e-11, "phi = {phi}, guess {g:?}: {q:?} leaves the loops open by {gap:e}");
                    // Every angle on its guess's turn.
                    assert!((0..4).all(|u| (q[u] - g[u]).abs() <= PI), "phi = {phi}, guess {g:?}: {q:?}");
                }
                // A slow iteration is told apart from a stall (and says what to do); a false
                // "cannot be assembled" is not allowed.
                Err(Error::NoConvergence { .. }) => {}
                Err(e) => panic!("phi = {phi}, guess {g:?}: {e}"),
            }
        }
    }
    (stalls_alone, solved)
}

#[test]
fn guesses_a_radian_off_assemble_where_the_iteration_alone_stalls() {
    let m = ClassFour::default();
    // Assemblies by a sweep from the declared guess.
    let refs = [0.001, 1.0, 2.0, 5.0].map(|phi| {
        let states = m.sweep(0.0, phi, 40, &m.guess(0.0)).unwrap().collect::<Result<Vec<_>, _>>().unwrap();
        (phi, states[states.len() - 1].q.into())
    });
    let (stalls_alone, solved) =
        from_guesses_a_radian_off(&m, &refs, 250, &mut Rng(Xorshift(0x9e37_79b9_7f4a_7c15)), |phi, q| {
            loop_gaps(&m, phi, q)
        });
    // The guesses do lead the iteration alone into folds (45 of them, about one in twenty), and
    // the restarts leave them.
    assert!(stalls_alone >= 20, "only {stalls_alone} stalls without restarts");
    assert!(solved >= 990, "{solved} of 1000 solved");
}

#[test]
fn a_class_three_group_assembles_from_guesses_a_radian_off() {
    let m = Triad::default();
    assert!(Triad::DECOMPOSITION.contains("Newton, 4x4"), "{}", Triad::DECOMPOSITION);
    let refs = [0.3, -0.3].map(|phi| {
        let states = m.sweep(0.0, phi, 30, &m.guess(0.0)).unwrap().collect::<Result<Vec<_>, _>>().unwrap();
        (phi, states[states.len() - 1].q.into())
    });
    let (stalls_alone, solved) =
        from_guesses_a_radian_off(&m, &refs, 500, &mut Rng(Xorshift(0x2545_f491_4f6c_dd1d)), |phi, q| {
            triad_gaps(&m, phi, q)
        });
    // 55 of the guesses stall without restarts, one in twenty.
    assert!(stalls_alone >= 20, "only {stalls_alone} stalls without restarts");
    assert!(solved >= 985, "{solved} of 1000 solved");
}

#[test]
fn a_stalled_guess_assembles_in_its_own_mode_and_starts_a_sweep() {
    let m = ClassFour::default();
    let phi = 0.001;
    // A guess from which the iteration alone stalls in a fold.
    let g = [0.769_901_552_615_186, 2.469_494_962_272_225_5, -1.565_244_534_929_787_4, -0.072_132_133_502_123_44];
    let alone = m.position_flat(&[phi], &g, &NewtonConfig::default().with_restarts(false));
    assert!(matches!(alone, Err(Error::NoAssembly { .. })), "{alone:?}");
    let (q, report) = m.position_flat(&[phi], &g, &NewtonConfig::default()).unwrap();
    // The assembly of the declared guess (the nearest to this one), found by a sweep.
    let states = m.sweep(0.0, phi, 2, &m.guess(0.0)).unwrap().collect::<Result<Vec<_>, _>>().unwrap();
    let q_ref: [f64; 4] = states[1].q.into();
    for u in 0..4 {
        assert_close!(q[u], q_ref[u], tol::SOLVE, "{q:?} vs {q_ref:?}");
    }
    assert!(report.iterations > 10, "{report:?}");
    // A sweep from that guess starts (its first sample restarts) and closes the loops.
    let turn =
        m.sweep(phi, phi + 1.0, 11, &ClassFourUnknowns::from(g)).unwrap().collect::<Result<Vec<_>, _>>().unwrap();
    assert_eq!(turn.len(), 11);
    let first: [f64; 4] = turn[0].q.into();
    assert!((0..4).all(|u| (first[u] - q_ref[u]).abs() < 1e-12), "{first:?} vs {q_ref:?}");
}

#[test]
fn a_group_that_cannot_close_is_still_no_assembly() {
    // EF far longer than the group can span: no assembly at any input, from any restart.
    let m = ClassFour { ef: 20.0, ..ClassFour::default() };
    let e = m.position_flat(&[1.0], &m.guess_flat(&[1.0]), &NewtonConfig::default()).unwrap_err();
    assert!(matches!(e, Error::NoAssembly { .. }), "{e}");
}
