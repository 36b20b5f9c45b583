//! Constants of the module around `mechanism!` named like the declaration's parameters,
//! input, unknowns, `let`s, points and outputs: the generated code sets the parameter fields by
//! name (`Default`, `from_param_values`) and names a `let`'s local after it with `let_` before,
//! instead of binding the names to locals, which such a constant would turn into a pattern the
//! compiler rejects.

#![allow(non_upper_case_globals, non_snake_case, dead_code)]

const R: f64 = 10.0;
const L: f64 = 30.0;
const PHI: f64 = 0.0;
const PSI: f64 = 0.0;
const X: f64 = 0.0;
const P: f64 = 0.0;
const W: f64 = 0.0;
const C: f64 = 0.0;
const D: f64 = 0.0;

kinloop::mechanism! {
    #[kinloop(sensitivities)]
    pub struct SliderCrank {
        params R = 1.0, L = 3.0;
        input PHI;
        unknowns PSI = 0, X = 4;
        let C = R @ PHI;
        let D = X / 2;
        loop oabc: C + L @ PSI == (X, 0);
        point P = C;
        output W = 4 * D;
        body rod: mass R, com P, turns PSI;
        force push at P = (D, 0);
    }
}

#[test]
fn the_mechanism_is_built_from_its_own_values_not_the_constants() {
    let m = SliderCrank::default();
    assert_eq!((m.R, m.L), (1.0, 3.0));
    assert_eq!(SliderCrank::from_param_values([2.0, 5.0]), SliderCrank { R: 2.0, L: 5.0 });
    let s = m.solve(0.3).expect("assembles");
    assert!((s.q.X - (0.3f64.cos() + (9.0 - 0.3f64.sin().powi(2)).sqrt())).abs() < 1e-12);
    assert!((s.out.W - 2.0 * s.q.X).abs() < 1e-15);
    m.sensitivities(0.3, &m.guess(0.3)).expect("sensitivities");
    m.mass_model().expect("mass model");
}

/// Lower-case one-letter constants, as physics code writes them (`const g: f64 = 9.81`, a
/// spring's `k`, a mass `m`), beside every shape of generated code: a point, an output, a
/// body, sensitivities, two inputs, a large sparse block. The generated code binds no name
/// such a constant would turn into a pattern (its closures, conversions and factorisations
/// name their locals `__v`, `__k`, ...), and its macros are called by their full paths.
mod one_letter_constants {
    #![allow(non_upper_case_globals, dead_code)]

    const a: f64 = 1.0;
    const b: f64 = 2.0;
    const c: f64 = 3.0;
    const d: f64 = 4.0;
    const e: f64 = 5.0;
    const f: f64 = 6.0;
    const g: f64 = 7.0;
    const h: f64 = 8.0;
    const i: f64 = 9.0;
    const j: f64 = 10.0;
    const k: f64 = 11.0;
    const l: f64 = 12.0;
    const m: f64 = 13.0;
    const n: f64 = 14.0;
    const o: f64 = 15.0;
    const p: f64 = 16.0;
    const q: f64 = 17.0;
    const r: f64 = 18.0;
    const s: f64 = 19.0;
    const t: f64 = 20.0;
    const u: f64 = 21.0;
    const v: f64 = 22.0;
    const w: f64 = 23.0;
    const x: f64 = 24.0;
    const y: f64 = 25.0;
    const z: f64 = 26.0;

    kinloop::mechanism! {
        #[kinloop(sensitivities)]
        pub struct Crank {
            params rr = 1.0, ll = 3.0, mm = 2.0;
            input phi;
            unknowns psi = 3, xx = 4;
            loop oab: rr @ phi == (xx, 0) + ll @ psi;
            point pp = (xx, 0);
            output ww = xx * 2;
            body rod: mass mm, com pp, turns psi;
        }
    }

    kinloop::mechanism! {
        #[kinloop(sensitivities)]
        pub struct TwoInputs {
            params l1 = 1.0, l2 = 1.5, l3 = 1.5, l4 = 1.0, l5 = 1.2;
            input th1, th2;
            unknowns th3 = 1.2, th4 = 2.0;
            loop five: l1 @ th1 + l2 @ th3 == (l5, 0) + l4 @ th2 + l3 @ th4;
            point tip = l1 @ th1 + l2 @ th3;
        }
    }

    kinloop::mechanism! {
        pub struct Ring {
            params aa = 1.0, bb = 3.0, cc = 2.5, dd = 3.2;
            input phi;
            unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9, u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9, u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9;
            loop l0: aa @ (0.5 * (phi + v11)) + bb @ u0 == (dd, 0) + cc @ v0;
            loop l1: aa @ v0 + bb @ u1 == (dd, 0) + cc @ v1;
            loop l2: aa @ v1 + bb @ u2 == (dd, 0) + cc @ v2;
            loop l3: aa @ v2 + bb @ u3 == (dd, 0) + cc @ v3;
            loop l4: aa @ v3 + bb @ u4 == (dd, 0) + cc @ v4;
            loop l5: aa @ v4 + bb @ u5 == (dd, 0) + cc @ v5;
            loop l6: aa @ v5 + bb @ u6 == (dd, 0) + cc @ v6;
            loop l7: aa @ v6 + bb @ u7 == (dd, 0) + cc @ v7;
            loop l8: aa @ v7 + bb @ u8 == (dd, 0) + cc @ v8;
            loop l9: aa @ v8 + bb @ u9 == (dd, 0) + cc @ v9;
            loop l10: aa @ v9 + bb @ u10 == (dd, 0) + cc @ v10;
            loop l11: aa @ v10 + bb @ u11 == (dd, 0) + cc @ v11;
        }
    }

    /// The same ring where no constant is in scope.
    mod twin {
        kinloop::mechanism! {
        pub struct Ring {
            params aa = 1.0, bb = 3.0, cc = 2.5, dd = 3.2;
            input phi;
            unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9, u4 = 0.6, v4 = 1.9, u5 = 0.6, v5 = 1.9, u6 = 0.6, v6 = 1.9, u7 = 0.6, v7 = 1.9, u8 = 0.6, v8 = 1.9, u9 = 0.6, v9 = 1.9, u10 = 0.6, v10 = 1.9, u11 = 0.6, v11 = 1.9;
            loop l0: aa @ (0.5 * (phi + v11)) + bb @ u0 == (dd, 0) + cc @ v0;
            loop l1: aa @ v0 + bb @ u1 == (dd, 0) + cc @ v1;
            loop l2: aa @ v1 + bb @ u2 == (dd, 0) + cc @ v2;
            loop l3: aa @ v2 + bb @ u3 == (dd, 0) + cc @ v3;
            loop l4: aa @ v3 + bb @ u4 == (dd, 0) + cc @ v4;
            loop l5: aa @ v4 + bb @ u5 == (dd, 0) + cc @ v5;
            loop l6: aa @ v5 + bb @ u6 == (dd, 0) + cc @ v6;
            loop l7: aa @ v6 + bb @ u7 == (dd, 0) + cc @ v7;
            loop l8: aa @ v7 + bb @ u8 == (dd, 0) + cc @ v8;
            loop l9: aa @ v8 + bb @ u9 == (dd, 0) + cc @ v9;
            loop l10: aa @ v9 + bb @ u10 == (dd, 0) + cc @ v10;
            loop l11: aa @ v10 + bb @ u11 == (dd, 0) + cc @ v11;
        }
        }
    }

    #[test]
    fn generated_code_binds_no_name_a_constant_could_take() {
        // This test's own locals have names of two letters or more: `let m = ..` would be a
        // pattern against the constant `m` here too.
        let crank = Crank::default();
        let state = crank.solve(0.3).expect("assembles");
        let xx = 0.3f64.cos() + (9.0 - 0.3f64.sin().powi(2)).sqrt();
        assert!((state.q.xx - xx).abs() < 1e-12, "{}", state.q.xx);
        assert_eq!((state.out.pp.x, state.out.ww), (state.q.xx, 2.0 * state.q.xx));
        let (_, sens) = crank.sensitivities(0.3, &crank.guess(0.3)).expect("sensitivities");
        // x = r cos phi + sqrt(l^2 - r^2 sin^2 phi): dx/dl = l / sqrt(..).
        assert!((sens.q.xx.ll - 3.0 / (9.0 - 0.3f64.sin().powi(2)).sqrt()).abs() < 1e-12);
        crank.mass_model().expect("mass model");
        let five = TwoInputs::default();
        let state = five.solve([1.0, 2.0]).expect("assembles");
        assert!(five.residual([1.0, 2.0], &state.q).iter().all(|res| res.abs() < 1e-12));
        five.sensitivities([1.0, 2.0], &state.q).expect("sensitivities");
        let (ring, twin) = (Ring::default(), twin::Ring::default());
        let (st_ring, st_twin) = (ring.solve(0.4).expect("assembles"), twin.solve(0.4).expect("assembles"));
        assert_eq!(st_ring.flat.q, st_twin.flat.q);
        assert_eq!(st_ring.flat.d2q, st_twin.flat.d2q);
    }
}

kinloop::mechanism! {
    /// Outputs, points, loops and bodies named by raw identifiers (Rust keywords).
    pub struct RawNames {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 3, x = 4;
        loop r#loop: r @ phi == (x, 0) + l @ psi;
        point r#impl = (x, 0);
        output r#fn = x * 2;
        body r#move: mass 1.0, com r#impl, turns psi;
    }
}

/// A name written as a raw identifier is its column without `r#`, as Rust compares names: the
/// outputs as the inputs and unknowns (`SC::COL.r#fn` is the column `fn`), in a table's header
/// and in the drawing's named points.
#[test]
fn raw_identifiers_name_their_columns_without_r_hash() {
    assert_eq!(RawNames::OUTPUTS, ["impl.x", "impl.y", "fn"]);
    assert_eq!(RawNames::EQUATIONS, ["loop.x", "loop.y"]);
    assert_eq!(RawNames::COL.r#fn.name(), "fn");
    assert!(kinloop::analysis::Column::<RawNames>::named("fn").is_ok());
    assert!(kinloop::analysis::Column::<RawNames>::named("impl.x").is_ok());
    let m = RawNames::default();
    let table = m.sweep(0.0, 1.0, 3, &m.guess(0.0)).unwrap().table().unwrap();
    assert!(table.index("fn").is_some() && table.index("d(impl.x)/d(phi)").is_some(), "{:?}", table.columns);
    let d = kinloop::drawing::Description::of::<RawNames, 2, 1, 3>().unwrap();
    assert!(d.joint("impl").is_some(), "{:?}", d.joints);
    assert!(d.joints.iter().all(|j| !j.name.contains("r#")), "{:?}", d.joints);
    let masses = m.mass_model().unwrap();
    let bodies: Vec<&str> = masses.bodies().iter().map(|b| b.name.as_ref()).collect();
    assert_eq!(bodies, ["move"]);
}
