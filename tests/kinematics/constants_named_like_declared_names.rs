//! Constants of the module around `mechanism!` named like the declaration's parameters,
//! input, unknowns, points and outputs: the generated code sets the parameter fields by name
//! (`Default`, `from_param_values`) instead of binding the names to locals, which such a
//! constant would turn into a pattern the compiler rejects.

#![allow(non_upper_case_globals, non_snake_case, dead_code)]

const R: f64 = 10.0;
const L: f64 = 30.0;
const PHI: f64 = 0.0;
const PSI: f64 = 0.0;
const X: f64 = 0.0;
const P: f64 = 0.0;
const W: f64 = 0.0;
const C: f64 = 0.0;

kinloop::mechanism! {
    #[kinloop(sensitivities)]
    pub struct SliderCrank {
        params R = 1.0, L = 3.0;
        input PHI;
        unknowns PSI = 0, X = 4;
        let C = R @ PHI;
        loop oabc: C + L @ PSI == (X, 0);
        point P = C;
        output W = X * 2;
        body rod: mass R, com P, turns PSI;
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
