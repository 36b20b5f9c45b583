//! Parameter sensitivities of positions, analogs and outputs against central finite differences
//! over random parameter sets (drawn from the fixtures' proptest strategies): rhombic drive,
//! gear-lever and class IV mechanism of the gallery, and a two-input five-bar.
//!
//! Reference: central differences with relative steps h and h/2 combined by Richardson
//! extrapolation, (4 D(h/2) - D(h)) / 3, whose truncation error is O(h^4); with h = 1e-4 that is
//! far below the rounding noise: positions (the reference solves converge to max|f| <= 1e-15)
//! give about 1e-15 / h = 1e-11, and analogs, whose rounding a Jacobian's condition amplifies to
//! ~1e-14, about 1e-10 (measured over these samples: 3e-11 for positions, 1.4e-11 for first and
//! 1.1e-10 for second analogs). `tol::FD_FIRST` (1e-9, relative, absolute near zero) keeps a
//! factor of about ten over the worst; the 1e-7 used before let a term off by 1e-8 pass.

use kinloop::{Kin, Mechanism, Sens, Sensitivities};
use kinloop_fixtures::strategies::{gear_lever, rhombic_drive, sample};
use kinloop_fixtures::{ClassFour, FiveBar, RhombicDrive};
use proptest::prelude::*;

use crate::support::{newton_to_residual_floor, tol};

/// Compares every sensitivity with Richardson-extrapolated central differences of the state.
fn check<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(m: &M, x: [f64; NI], guess: [f64; N])
where
    M: Sensitivities<N, NI, NO, NP>,
{
    let floor = newton_to_residual_floor();
    let (k, s): (Kin<N, NI, NO>, Sens<N, NI, NO, NP>) = m.sensitivities_flat(&x, &guess, &floor).unwrap();
    let base = m.params_flat();
    for p in 0..NP {
        let h = 1e-4 * base[p].abs().max(1.0);
        let at = |step: f64| {
            let mut v = base;
            v[p] += step;
            m.with_params_flat(v).kinematics_flat(&x, &k.q, &floor).unwrap()
        };
        let (hi, lo, hi2, lo2) = (at(h), at(-h), at(h / 2.0), at(-h / 2.0));
        let fd = |f: &dyn Fn(&Kin<N, NI, NO>) -> f64| {
            let d1 = (f(&hi) - f(&lo)) / (2.0 * h);
            let d2 = (f(&hi2) - f(&lo2)) / h;
            (4.0 * d2 - d1) / 3.0
        };
        let name = M::PARAMS[p];
        // Quantity v: the unknowns, then the outputs (flat order), in the state and in `s`.
        let of = |v: usize| if v < N { M::UNKNOWNS[v] } else { M::OUTPUTS[v - N] };
        let value = |k: &Kin<N, NI, NO>, v: usize| if v < N { k.q[v] } else { k.out[v - N] };
        let first = |k: &Kin<N, NI, NO>, v: usize, i: usize| if v < N { k.dq[v][i] } else { k.dout[v - N][i] };
        let second = |k: &Kin<N, NI, NO>, v: usize, i: usize, j: usize| {
            if v < N { k.d2q[v][i][j] } else { k.d2out[v - N][i][j] }
        };
        for v in 0..N + NO {
            let vn = of(v);
            let got = if v < N { s.q[v][p] } else { s.out[v - N][p] };
            let f = fd(&|k| value(k, v));
            assert_close!(got, f, rel = tol::FD_FIRST, "d{vn}/d{name}: {got} vs {f}");
            for i in 0..NI {
                let got = if v < N { s.dq[v][i][p] } else { s.dout[v - N][i][p] };
                let f = fd(&|k| first(k, v, i));
                assert_close!(got, f, rel = tol::FD_FIRST, "d(d{vn}/dx{i})/d{name}: {got} vs {f}");
                for j in 0..NI {
                    let got = if v < N { s.d2q[v][i][j][p] } else { s.d2out[v - N][i][j][p] };
                    let f = fd(&|k| second(k, v, i, j));
                    assert_close!(got, f, rel = tol::FD_FIRST, "d(d2{vn}/dx{i}dx{j})/d{name}: {got} vs {f}");
                }
            }
        }
    }
    // The kinematic part equals the plain solve.
    let plain = m.kinematics_flat(&x, &guess, &floor).unwrap();
    assert_eq!(plain.q, k.q);
    assert_eq!(plain.d2out, k.d2out);
}

#[test]
fn rhombic_drive_sensitivities_match_finite_differences() {
    for (m, phi) in sample((rhombic_drive(), 0.0..std::f64::consts::TAU), 25, 1) {
        let g = m.position(phi, &m.guess(phi)).unwrap().0;
        check(&m, [phi], g.into());
    }
}

#[test]
fn gear_lever_sensitivities_match_finite_differences() {
    for (m, a) in sample((gear_lever(), 0.0..std::f64::consts::TAU), 25, 2) {
        let g = m.position(a, &m.guess(a)).unwrap().0;
        check(&m, [a], g.into());
    }
}

#[test]
fn class_four_sensitivities_match_finite_differences() {
    let base = ClassFour::default();
    let mut q = base.position(0.0, &base.guess(0.0)).unwrap().0;
    let factors = sample(prop::array::uniform11(0.99f64..1.01), 12, 3);
    for (k, f) in factors.iter().enumerate() {
        let phi = 0.5 * k as f64;
        q = base.position(phi, &q).unwrap().0;
        let mut v = base.param_values();
        for (x, f) in v.iter_mut().zip(f) {
            *x *= f;
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
    let m = RhombicDrive::default();
    let (st, sens) = m.sensitivities(0.4, &m.guess(0.4)).unwrap();
    let (_, at) = m.sensitivities_at(0.4, &st.q).unwrap();
    // The closed-form solve hands its own sines and cosines of the rod angles to the analogs;
    // `sensitivities_at` takes them from the angles: equal to rounding.
    let all = |s: &kinloop::Sens<4, 1, 7, 11>| -> Vec<f64> {
        let f = |v: &[f64]| v.to_vec();
        [
            f(s.q.as_flattened()),
            f(s.dq.as_flattened().as_flattened()),
            f(s.d2q.as_flattened().as_flattened().as_flattened()),
            f(s.out.as_flattened()),
            f(s.dout.as_flattened().as_flattened()),
            f(s.d2out.as_flattened().as_flattened().as_flattened()),
        ]
        .concat()
    };
    for (x, y) in all(&sens.flat).iter().zip(all(&at.flat)) {
        assert_close!(*x, y, <= tol::ULPS * (1.0 + y.abs()), "{x} vs {y}");
    }
    assert_eq!(sens.q.x_c.l_p, sens.flat.q[2][2]);
    // X_C = R_P cos(phi1) - L_P cos(phi2): d X_C / d L_P = -cos(phi2) + L_P sin(phi2) dphi2/dL_P.
    let expected = -st.q.phi2.cos() + 3.0 * st.q.phi2.sin() * sens.q.phi2.l_p;
    assert_close!(sens.q.x_c.l_p, expected, tol::SOLVE);
    assert_eq!(sens.out.gap.l_b, sens.q.x_f.l_b - sens.q.x_c.l_b);
    // Flat, the outputs are the points' x and y (s1, s2, s4), then the scalar output: seven.
    assert_eq!(<RhombicDrive as Mechanism<4, 1, 7>>::NAME, "RhombicDrive");
    assert_eq!(sens.flat.out.len(), 7);
    assert_eq!(sens.out.gap.l_b, sens.flat.out[6][3]);
}
