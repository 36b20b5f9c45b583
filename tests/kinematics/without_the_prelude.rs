//! `mechanism!` where the standard prelude is not what the expansion expects: in a module
//! without it (`#![no_implicit_prelude]`), and beside a trait in scope for every type whose
//! methods are named like the prelude traits' (`into`, `from`, `default`, `clone`). The
//! generated code names `Some`, `Err`, the derived traits and the conversions by their paths in
//! `core` and calls trait methods through their traits, so it compiles in both places; every
//! shape of generated code is here: closed forms, a linear block, Newton, a large sparse block,
//! two inputs, outputs, sensitivities and dynamics.

/// The mechanisms, declared where nothing of the prelude is in scope.
mod bare {
    #![no_implicit_prelude]

    ::kinloop::mechanism! {
        /// A slider-crank with every kind of item.
        #[kinloop(sensitivities)]
        pub struct Engine {
            params r = 0.05, l = 0.2, m_rod = 2.0, j_rod = 0.01, m_p = 0.5, p = 300.0;
            input phi;
            unknowns beta = 0, x = 0.25;
            let v = r @ phi;
            loop abc: v + l @ beta == (x, 0);
            point s2 = v + 0.3 * l @ beta;
            output w = max(x, l) + l * clamp(x / l, 0, 1) + r * wrap(phi, 2 * pi);
            body rod: mass m_rod, com s2, inertia j_rod, turns beta;
            body piston: mass m_p, com (x, 0);
            force gas at (x, 0) = (p * (r + l) / x, 0);
            torque drive on phi = 1;
            gravity (0, -9.81);
        }
    }

    ::kinloop::mechanism! {
        /// Two inputs, solved by Newton as one block.
        #[kinloop(sensitivities, newton, dense)]
        pub struct FiveBar {
            params l1 = 1.0, l2 = 1.5, l3 = 1.5, l4 = 1.0, l5 = 1.2;
            inputs th1, th2;
            unknowns th3 = 1.2, th4 = 2.0;
            loop five: l1 @ th1 + l2 @ th3 == (l5, 0) + l4 @ th2 + l3 @ th4;
            point tip = l1 @ th1 + l2 @ th3;
        }
    }

    ::kinloop::mechanism! {
        /// A ring of four-bars: one coupled block of 16 unknowns, factorised as a sparse one.
        pub struct Ring {
            params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
            input phi;
            unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9, u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9;
            loop l0: a @ (0.5 * (phi + v7)) + b @ u0 == (d, 0) + c @ v0;
            loop l1: a @ v0 + b @ u1 == (d, 0) + c @ v1;
            loop l2: a @ v1 + b @ u2 == (d, 0) + c @ v2;
            loop l3: a @ v2 + b @ u3 == (d, 0) + c @ v3;
            loop l4: a @ v3 + b @ u4 == (d, 0) + c @ v4;
            loop l5: a @ v4 + b @ u5 == (d, 0) + c @ v5;
            loop l6: a @ v5 + b @ u6 == (d, 0) + c @ v6;
            loop l7: a @ v6 + b @ u7 == (d, 0) + c @ v7;
        }
    }
}

/// The same slider-crank beside a trait, implemented for every type, whose methods are named
/// like those of `Into`, `From`, `Default` and `Clone` (and of `f64`: those stay inherent).
mod lookalikes {
    #![allow(dead_code)]

    pub trait Lookalike: Sized {
        fn into(self) -> Self;
        fn from(self) -> Self;
        fn default() -> Self;
        fn clone(&self) -> Self;
        fn abs(self) -> Self;
        fn sin_cos(self) -> Self;
    }

    impl<T: Copy> Lookalike for T {
        fn into(self) -> Self {
            self
        }
        fn from(self) -> Self {
            self
        }
        fn default() -> Self {
            unreachable!("never called by the expansion")
        }
        fn clone(&self) -> Self {
            *self
        }
        fn abs(self) -> Self {
            self
        }
        fn sin_cos(self) -> Self {
            self
        }
    }

    kinloop::mechanism! {
        /// Two inputs, sensitivities and a body: the conversions of every named type.
        #[kinloop(sensitivities)]
        pub struct FiveBar {
            params l1 = 1.0, l2 = 1.5, l3 = 1.5, l4 = 1.0, l5 = 1.2, m = 1.0;
            inputs th1, th2;
            unknowns th3 = 1.2, th4 = 2.0;
            loop five: l1 @ th1 + l2 @ th3 == (l5, 0) + l4 @ th2 + l3 @ th4;
            point tip = l1 @ th1 + l2 @ th3;
            body link: mass m, com tip, turns th3;
        }
    }
}

#[test]
fn a_mechanism_declared_without_the_prelude_solves() {
    let m = bare::Engine::default();
    let s = m.solve(0.3).expect("assembles");
    let (r, l) = (m.r, m.l);
    let x = r * 0.3f64.cos() + (l * l - (r * 0.3f64.sin()).powi(2)).sqrt();
    assert!((s.q.x - x).abs() < 1e-12 * l, "{} against {x}", s.q.x);
    let motion = s.motion(10.0, 0.0).expect("motion");
    assert!((motion.qdot.x - 10.0 * s.dq.x).abs() <= 1e-12 * motion.qdot.x.abs());
    m.sensitivities(0.3, &m.guess(0.3)).expect("sensitivities");
    m.mass_model().expect("mass model");

    let five = bare::FiveBar::default();
    let s = five.solve([0.4, 2.0]).expect("five-bar assembles");
    assert!(five.residual(s.input, &s.q).iter().all(|e| e.abs() <= 1e-12 * five.l5), "{:?}", s.q);
    five.sensitivities([0.4, 2.0], &five.guess([0.4, 2.0])).expect("sensitivities");

    let ring = bare::Ring::default();
    assert!(ring.solve(0.2).is_ok());
}

#[test]
fn a_mechanism_beside_lookalike_trait_methods_solves() {
    let m = lookalikes::FiveBar::default();
    let s = m.solve([0.4, 2.0]).expect("assembles");
    assert!(m.residual(s.input, &s.q).iter().all(|e| e.abs() <= 1e-12 * m.l5), "{:?}", s.q);
    let motion = s.motion([1.0, 0.0], [0.0, 0.0]).expect("motion");
    assert_eq!(motion.qdot.th3, s.dq.th3.th1);
    m.sensitivities([0.4, 2.0], &m.guess([0.4, 2.0])).expect("sensitivities");
    m.mass_model().expect("mass model");
}
