//! A Newton block whose iteration stalls in a fold of its residual restarts before it reports
//! "cannot be assembled" (`NewtonConfig::restarts`): the class IV group of paper 003
//! (`docs/papers.md`), solved from guesses up to a radian off in every angle.

use kinloop::{Error, Mechanism, NewtonConfig};
use kinloop_fixtures::{ClassFour, ClassFourUnknowns};
use std::f64::consts::PI;

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

/// Uniform numbers in `[-1, 1)` from a fixed seed (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        2.0 * ((self.0 >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }
}

#[test]
fn guesses_a_radian_off_assemble_where_the_iteration_alone_stalls() {
    let m = ClassFour::default();
    let cfg = NewtonConfig::default();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut stalls_alone, mut solved) = (0, 0);
    for phi in [0.001, 1.0, 2.0, 5.0] {
        // An assembly at this input, by a sweep from the declared guess.
        let states = m.sweep(0.0, phi, 40, &m.guess(0.0)).unwrap().collect::<Result<Vec<_>, _>>().unwrap();
        let q_ref: [f64; 4] = states[states.len() - 1].q.into();
        for _ in 0..250 {
            let g: [f64; 4] = core::array::from_fn(|u| q_ref[u] + rng.next());
            let alone = m.position_flat(&[phi], &g, &cfg.with_restarts(false));
            stalls_alone += usize::from(matches!(alone, Err(Error::NoAssembly { .. })));
            match m.position_flat(&[phi], &g, &cfg) {
                Ok((q, _)) => {
                    solved += 1;
                    let gap = loop_gaps(&m, phi, q).iter().fold(0.0f64, |w, v| w.max(v.abs()));
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
    // The guesses do lead the iteration alone into folds (about one in twenty), and the
    // restarts leave them.
    assert!(stalls_alone >= 20, "only {stalls_alone} stalls without restarts");
    assert!(solved >= 990, "{solved} of 1000 solved");
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
        assert!((q[u] - q_ref[u]).abs() < 1e-12, "{q:?} vs {q_ref:?}");
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
