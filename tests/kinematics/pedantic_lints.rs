//! `mechanism!` in a module that denies clippy's `pedantic` and `nursery` groups: a user who
//! turns them on in their crate sees no lint on code they did not write. CI's
//! `cargo clippy --all-targets -- -D warnings` checks this file, so a lint that the expansion
//! starts to trip fails the build; the test below only keeps the mechanisms in use.

/// The mechanisms, declared where every pedantic and nursery lint is an error.
mod pedantic {
    #![deny(clippy::pedantic, clippy::nursery)]

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
        /// A four-bar in closed form, with an `eq`, degrees and a piecewise law.
        pub struct FourBar {
            params a = 1.0, b = 3.0, c = 2.5, d = 3.2, tilt = deg(5);
            input phi;
            unknowns beta = 0.5, gamma = 1.5, y = 0.1;
            loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
            eq lift: y == c * sin(gamma + tilt) - a * floor(phi / (2 * pi));
            output rocker = gamma;
            output swing = min(abs(gamma - beta), pi);
        }
    }

    ::kinloop::mechanism! {
        /// Two four-bars that drive each other: one small coupled block, solved by Newton.
        pub struct Pair {
            params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
            input phi;
            unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9;
            loop l0: a @ (0.5 * (phi + v1)) + b @ u0 == (d, 0) + c @ v0;
            loop l1: a @ v0 + b @ u1 == (d, 0) + c @ v1;
            point tip = a @ v0 + 0.5 * b @ u1;
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

#[test]
fn mechanisms_declared_under_pedantic_lints_solve() {
    let m = pedantic::Engine::default();
    let s = m.solve(0.3).expect("assembles");
    let x = m.r * 0.3f64.cos() + (m.l * m.l - (m.r * 0.3f64.sin()).powi(2)).sqrt();
    assert!((s.q.x - x).abs() < 1e-12 * m.l, "{} against {x}", s.q.x);
    m.sensitivities(0.3, &m.guess(0.3)).expect("sensitivities");
    m.mass_model().expect("mass model");

    let five = pedantic::FiveBar::default();
    let s = five.solve([0.4, 2.0]).expect("five-bar assembles");
    assert!(five.residual(s.input, &s.q).iter().all(|e| e.abs() <= 1e-12 * five.l5), "{:?}", s.q);

    let four = pedantic::FourBar::default();
    let s = four.solve(0.3).expect("four-bar assembles");
    assert!(four.residual(s.input, &s.q).iter().all(|e| e.abs() <= 1e-12 * four.d), "{:?}", s.q);

    assert!(pedantic::Pair::default().solve(0.2).is_ok());
    assert!(pedantic::Ring::default().solve(0.2).is_ok());
}
