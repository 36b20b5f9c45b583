//! Parameter sensitivities of positions, analogs and outputs against central finite differences
//! over random parameter sets: rhombic drive, gear-lever and class IV mechanism (the last two as
//! declared in the examples), and a two-input five-bar.
//!
//! Reference: central differences with relative steps h and h/2 combined by Richardson
//! extrapolation, (4 D(h/2) - D(h)) / 3, whose truncation error is O(h^4); with h = 1e-4 that is
//! far below the rounding noise, about 1e-15 / h = 1e-11 (the reference solves converge to
//! max|f| <= 1e-15). The tolerance 1e-7 (relative, absolute near zero) leaves a wide margin
//! while any wrong term shows up at O(1).

use kinloop::{Kin, Mechanism, NewtonConfig, Sens, Sensitivities};

kinloop::mechanism! {
    #[kinloop(sensitivities)]
    pub struct RhombicDrive {
        params r_p, r_b, l_p, l_b, e_p, de, gamma, l_cs2, l_fs4;
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
        point s2 = (x_c, 0) + l_cs2 @ phi2;
        point s4 = (x_f, de) + l_fs4 @ phi4;
        output gap = x_f - x_c;
    }
}

#[allow(dead_code)]
#[path = "../examples/gear_lever.rs"]
mod gear_lever;

// Both examples load `examples/common/mod.rs` (their plotting helpers, unused here).
#[allow(dead_code, clippy::duplicate_mod)]
#[path = "../examples/class_four.rs"]
mod class_four;

use class_four::ClassFour;
use gear_lever::GearLever;

#[allow(dead_code)] // not every test uses every helper
mod support;

use support::close;

kinloop::mechanism! {
    #[kinloop(sensitivities)]
    pub struct FiveBar {
        params a, b, c, d, e;
        inputs th1, th2;
        unknowns phi2 = 1.2, phi3 = 1.9;
        loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3;
        point pc = a @ th1 + b @ phi2;
    }
}

/// A tiny deterministic generator (xorshift) for parameter perturbations.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Compares every sensitivity with Richardson-extrapolated central differences of the state.
fn check<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(m: &M, x: [f64; NI], guess: [f64; N])
where
    M: Sensitivities<N, NI, NO, NP>,
{
    let tight = NewtonConfig::default().with_residual_tol(1e-15);
    let (k, s): (Kin<N, NI, NO>, Sens<N, NI, NO, NP>) = m.sensitivities_flat(&x, &guess, &tight).unwrap();
    let base = m.params_flat();
    for p in 0..NP {
        let h = 1e-4 * base[p].abs().max(1.0);
        let at = |step: f64| {
            let mut v = base;
            v[p] += step;
            m.with_params_flat(v).kinematics_flat(&x, &k.q, &tight).unwrap()
        };
        let (hi, lo, hi2, lo2) = (at(h), at(-h), at(h / 2.0), at(-h / 2.0));
        let fd = |f: &dyn Fn(&Kin<N, NI, NO>) -> f64| {
            let d1 = (f(&hi) - f(&lo)) / (2.0 * h);
            let d2 = (f(&hi2) - f(&lo2)) / h;
            (4.0 * d2 - d1) / 3.0
        };
        let name = M::PARAMS[p];
        for u in 0..N {
            let un = M::UNKNOWNS[u];
            let f = fd(&|k| k.q[u]);
            assert!(close(s.q[u][p], f, 1e-7), "d{un}/d{name}: {} vs {f}", s.q[u][p]);
            for i in 0..NI {
                let f = fd(&|k| k.dq[u][i]);
                assert!(close(s.dq[u][i][p], f, 1e-7), "d(d{un}/dx{i})/d{name}: {} vs {f}", s.dq[u][i][p]);
                for j in 0..NI {
                    let f = fd(&|k| k.d2q[u][i][j]);
                    assert!(close(s.d2q[u][i][j][p], f, 1e-7), "d(d2{un})/d{name}: {} vs {f}", s.d2q[u][i][j][p]);
                }
            }
        }
        for o in 0..NO {
            let on = M::OUTPUTS[o];
            let f = fd(&|k| k.out[o]);
            assert!(close(s.out[o][p], f, 1e-7), "d{on}/d{name}: {} vs {f}", s.out[o][p]);
            for i in 0..NI {
                let f = fd(&|k| k.dout[o][i]);
                assert!(close(s.dout[o][i][p], f, 1e-7), "d(d{on})/d{name}: {} vs {f}", s.dout[o][i][p]);
                for j in 0..NI {
                    let f = fd(&|k| k.d2out[o][i][j]);
                    assert!(close(s.d2out[o][i][j][p], f, 1e-7), "d(d2{on})/d{name}: {} vs {f}", s.d2out[o][i][j][p]);
                }
            }
        }
    }
    // The kinematic part equals the plain solve.
    let plain = m.kinematics_flat(&x, &guess, &tight).unwrap();
    assert_eq!(plain.q, k.q);
    assert_eq!(plain.d2out, k.d2out);
}

#[test]
fn rhombic_drive_sensitivities_match_finite_differences() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for _ in 0..25 {
        let m = RhombicDrive {
            r_p: 0.8 + 0.4 * rng.next(),
            r_b: 1.0 + 0.4 * rng.next(),
            l_p: 2.5 + rng.next(),
            l_b: 3.0 + rng.next(),
            e_p: 0.2 + 0.5 * rng.next(),
            de: 0.6 + 0.5 * rng.next(),
            gamma: 0.3 + rng.next(),
            l_cs2: 0.5 + rng.next(),
            l_fs4: 0.5 + rng.next(),
        };
        let phi = std::f64::consts::TAU * rng.next();
        let g = m.position(phi, &m.guess(phi)).unwrap().0;
        check(&m, [phi], g.into());
    }
}

#[test]
fn gear_lever_sensitivities_match_finite_differences() {
    let mut rng = Rng(12345);
    for _ in 0..25 {
        let m = GearLever { l_c: 2.0, l_p: 1.1 + 0.4 * rng.next(), u: 2.5 + rng.next() };
        let a = std::f64::consts::TAU * rng.next();
        let g = m.position(a, &m.guess(a)).unwrap().0;
        check(&m, [a], g.into());
    }
}

#[test]
fn class_four_sensitivities_match_finite_differences() {
    let base = ClassFour::default();
    let mut rng = Rng(777);
    let mut q = base.position(0.0, &base.guess(0.0)).unwrap().0;
    for k in 0..12 {
        let phi = 0.5 * k as f64;
        q = base.position(phi, &q).unwrap().0;
        let mut v = base.param_values();
        for x in &mut v {
            *x *= 1.0 + 0.02 * (rng.next() - 0.5);
        }
        let m = ClassFour::from_param_values(v);
        let g = m.position(phi, &q).unwrap().0;
        check(&m, [phi], g.into());
    }
}

#[test]
fn five_bar_sensitivities_of_partial_analogs() {
    let m = FiveBar { a: 1.0, b: 2.5, c: 2.2, d: 1.5, e: 1.2 };
    for (t1, t2) in [(1.3, 0.9), (1.6, 1.2)] {
        let g = m.solve([t1, t2]).unwrap().q;
        check(&m, [t1, t2], g.into());
    }
    // The named API reads like the state with a parameter appended.
    let (st, sens) = m.sensitivities([1.3, 0.9], &m.solve([1.3, 0.9]).unwrap().q).unwrap();
    assert_eq!(st.q, m.solve([1.3, 0.9]).unwrap().q);
    // Flat indices: unknowns (phi2, phi3), inputs (th1, th2), outputs (pc.x, pc.y), params
    // (a, b, c, d, e).
    assert_eq!(sens.dq.phi2.th1.b, sens.flat.dq[0][0][1]);
    assert_eq!(sens.d2out.pc.y.th1.th2.e, sens.flat.d2out[1][0][1][4]);
}

#[test]
fn named_sensitivities_match_flat() {
    let m =
        RhombicDrive { r_p: 1.0, r_b: 1.2, l_p: 3.0, l_b: 3.5, e_p: 0.5, de: 0.9, gamma: 0.7, l_cs2: 1.2, l_fs4: 1.4 };
    let (st, sens) = m.sensitivities(0.4, &m.guess(0.4)).unwrap();
    let (_, at) = m.sensitivities_at(0.4, &st.q).unwrap();
    assert_eq!(sens.flat, at.flat);
    assert_eq!(sens.q.x_c.l_p, sens.flat.q[2][2]);
    // X_C = R_P cos(phi1) - L_P cos(phi2): d X_C / d L_P = -cos(phi2) + L_P sin(phi2) dphi2/dL_P.
    let expected = -st.q.phi2.cos() + 3.0 * st.q.phi2.sin() * sens.q.phi2.l_p;
    assert!((sens.q.x_c.l_p - expected).abs() < 1e-12);
    assert_eq!(sens.out.gap.l_b, sens.q.x_f.l_b - sens.q.x_c.l_b);
    // Flat, the outputs are the points' x and y, then the scalar output: five of them.
    assert_eq!(<RhombicDrive as Mechanism<4, 1, 5>>::NAME, "RhombicDrive");
    assert_eq!(sens.flat.out.len(), 5);
    assert_eq!(sens.out.gap.l_b, sens.flat.out[4][3]);
}
