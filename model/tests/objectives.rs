//! The objectives with parameter gradients on run-time models (`extremum_with_gradient`,
//! `integral_with_gradient` on a `ModelSampled`): the runtime's one implementation over the
//! model's kernel. With libm's sines in both sweeps the states and the sensitivities at them are
//! equal to the last bit, so the results must be too; and the offset slider-crank's dead
//! centres, their locations and the gradients of all three are checked against closed forms and
//! central finite differences that share nothing with the library.

mod common;

use common::{Libm, read, set};
use kinloop::Mechanism;
use kinloop::analysis::{Column, ColumnIndex, Extreme, Sampled};
use kinloop_fixtures as fx;
use std::f64::consts::{PI, TAU};

/// The rhombic drive (declared with sensitivities), compiled and at run time: every extremum and
/// integral with its gradients equal bit for bit.
#[test]
fn rhombic_drive_objectives_equal_the_compiled_ones_bit_for_bit() {
    let compiled = Libm(fx::RhombicDrive::default());
    let mut m = read(fx::RHOMBIC_DRIVE_TEXT);
    let guess = compiled.guess_flat(&[0.0]);
    let c = Sampled::sweep(&compiled, 0.0, TAU, 73, guess).unwrap();
    let r = m.sampled(&[0.0], &[TAU], 73, &guess).unwrap();
    let col = |n: &str| Column::<Libm<fx::RhombicDrive>>::named(n).unwrap();
    let mut compared = 0;
    for name in ["x_f", "x_c", "gap", "phi2", "s2.y"] {
        for which in [Extreme::Max, Extreme::Min] {
            let ce = c.extremum_with_gradient(col(name), which).unwrap();
            let re = r.extremum_with_gradient(name, which).unwrap();
            assert_eq!((ce.x.to_bits(), ce.value.to_bits()), (re.x.to_bits(), re.value.to_bits()), "{name}");
            assert_eq!(ce.grad.as_slice(), re.grad.as_slice(), "{name} {which:?}");
            assert_eq!(ce.x_grad.as_slice(), re.x_grad.as_slice(), "{name} {which:?}");
            compared += 1;
        }
        let (cv, cg) = c.integral_with_gradient(col(name)).unwrap();
        let (rv, rg) = r.integral_with_gradient(name).unwrap();
        assert_eq!(cv.to_bits(), rv.to_bits(), "{name}");
        assert_eq!(cg.as_slice(), rg.as_slice(), "{name}");
    }
    assert_eq!(compared, 10, "{compared} extrema compared");
}

/// An offset slider-crank with sensitivities: crank `r`, rod `l`, the slider at (s, e).
const SLIDER: &str = "#[kinloop(sensitivities)]
pub struct OffsetSlider {
    params r = 1, l = 3, e = 0.4;
    input phi;
    unknowns beta = 0, s = 4;
    loop rod: r @ phi + l @ beta == (s, e);
}";

/// The dimensions of the closed forms below.
const R: f64 = 1.0;
const L: f64 = 3.0;
const E: f64 = 0.4;

/// Closed forms (crank and rod in line): the outer dead centre s = sqrt((l + r)^2 - e^2) at
/// phi = asin(e / (l + r)), the inner one s = sqrt((l - r)^2 - e^2) at phi = pi + asin(e / (l - r)).
/// Returns (phi, s, [d phi/d(r, l, e)], [d s/d(r, l, e)]) of one dead centre.
fn dead_centre(outer: bool) -> (f64, f64, [f64; 3], [f64; 3]) {
    // The reach k of the line crank + rod, and its derivatives by (r, l).
    let (k, dk) = if outer { (L + R, [1.0, 1.0]) } else { (L - R, [-1.0, 1.0]) };
    let s = (k * k - E * E).sqrt();
    let phi = if outer { (E / k).asin() } else { PI + (E / k).asin() };
    // d asin(e / k) = (de / k - e dk / k^2) / sqrt(1 - e^2 / k^2) = (de - e dk / k) / s.
    let dphi = [-E * dk[0] / (k * s), -E * dk[1] / (k * s), 1.0 / s];
    let ds = [k * dk[0] / s, k * dk[1] / s, -E / s];
    (phi, s, dphi, ds)
}

#[test]
fn slider_dead_centres_and_their_gradients_from_the_closed_form() {
    let mut m = read(SLIDER);
    // From -1 so that both dead centres are interior.
    let turn = m.sampled(&[-1.0], &[TAU - 1.0], 73, &[0.0, 4.0]).unwrap();
    for (which, outer) in [(Extreme::Max, true), (Extreme::Min, false)] {
        let got = turn.extremum_with_gradient("s", which).unwrap();
        let (phi, s, dphi, ds) = dead_centre(outer);
        // The extremum is a root of the velocity analog, located to rounding (measured: 3e-17
        // here); the value is second order in that error, its gradients and location first
        // order: 1e-11 leaves a hundredfold margin over a root finder stopping at 1e-13.
        assert!((got.value - s).abs() < 1e-14, "{which:?}: {} vs {s}", got.value);
        assert!((got.x - phi).abs() < 1e-11, "{which:?}: {} vs {phi}", got.x);
        for p in 0..3 {
            assert!((got.grad[p] - ds[p]).abs() < 1e-11, "{which:?} d s/d p{p}: {} vs {}", got.grad[p], ds[p]);
            assert!(
                (got.x_grad[p] - dphi[p]).abs() < 1e-11,
                "{which:?} d phi/d p{p}: {} vs {}",
                got.x_grad[p],
                dphi[p]
            );
        }
    }
}

#[test]
fn slider_dead_centre_gradients_against_finite_differences() {
    let mut m = read(SLIDER);
    let base =
        m.sampled(&[-1.0], &[TAU - 1.0], 73, &[0.0, 4.0]).unwrap().extremum_with_gradient("s", Extreme::Min).unwrap();
    let names = ["r", "l", "e"];
    for (p, name) in names.iter().enumerate() {
        let v = [R, L, E][p];
        let h = 1e-5;
        let mut at = |d: f64| {
            set(&mut m, &[(name, v + d)]);
            let t = m.sampled(&[-1.0], &[TAU - 1.0], 73, &[0.0, 4.0]).unwrap();
            let e = t.extremum_with_gradient("s", Extreme::Min).unwrap();
            (e.x, e.value)
        };
        let (a, b) = (at(h), at(-h));
        set(&mut m, &[(name, v)]);
        // Central differences: truncation h^2 |f'''| / 6 ~ 1e-10, and rounding of values near 3
        // (or of the root's location) divided by 2h ~ 2e-11 (measured: 2e-12 on the locations,
        // 2e-11 on the values): 1e-8 relative keeps a margin and still catches a wrong term.
        let (fd_x, fd_v) = ((a.0 - b.0) / (2.0 * h), (a.1 - b.1) / (2.0 * h));
        assert!((base.x_grad[p] - fd_x).abs() < 1e-8 * (1.0 + fd_x.abs()), "{name}: {} vs {fd_x}", base.x_grad[p]);
        assert!((base.grad[p] - fd_v).abs() < 1e-8 * (1.0 + fd_v.abs()), "{name}: {} vs {fd_v}", base.grad[p]);
    }
}

#[test]
fn slider_integral_and_gradient_from_the_closed_form_quadrature() {
    let mut m = read(SLIDER);
    let n = 181;
    let (v, g) = m.sampled(&[0.0], &[TAU], n, &[0.0, 4.0]).unwrap().integral_with_gradient("s").unwrap();
    // Independent: the trapezoid over s(phi) = r cos phi + sqrt(l^2 - (e - r sin phi)^2) and
    // its derivatives by (r, l, e) in closed form.
    let h = TAU / (n - 1) as f64;
    let (mut value, mut grad) = (0.0, [0.0; 3]);
    for k in 0..n {
        let phi = k as f64 * h;
        let w = if k == 0 || k == n - 1 { 0.5 * h } else { h };
        let y = E - R * phi.sin();
        let root = (L * L - y * y).sqrt();
        value += w * (R * phi.cos() + root);
        let d = [phi.cos() + y * phi.sin() / root, L / root, -y / root];
        for p in 0..3 {
            grad[p] += w * d[p];
        }
    }
    // Each sample equals its closed form to the solver's rounding (~1e-15 relative); the sums
    // of 181 of them to ~1e-13 (measured: 7e-15).
    assert!((v - value).abs() < 1e-12, "{v} vs {value}");
    for p in 0..3 {
        assert!((g[p] - grad[p]).abs() < 1e-12, "p{p}: {} vs {}", g[p], grad[p]);
    }
}

/// A mechanism of two inputs is refused with a typed error, not a panic.
#[test]
fn two_inputs_are_refused() {
    let mut m = read(fx::FIVE_BAR_TEXT);
    let guess = fx::FiveBar::default().guess_flat(&[0.0, 1.0]);
    let t = m.sampled(&[0.0, 1.0], &[PI, 1.0 + PI / 2.0], 31, &guess).unwrap();
    let refused = |r: Result<(), kinloop::Error>| matches!(r, Err(kinloop::Error::InvalidArgument(ref s)) if s.contains("one input"));
    assert!(refused(t.integral_with_gradient(ColumnIndex::Unknown(0)).map(drop)));
    assert!(refused(t.extremum_with_gradient(ColumnIndex::Unknown(0), Extreme::Max).map(drop)));
}

/// A model declared without sensitivities is refused with a typed error naming the attribute's
/// absence, not a panic.
#[test]
fn a_model_without_sensitivities_is_refused() {
    let mut m = read(&SLIDER.replace("#[kinloop(sensitivities)]\n", ""));
    let turn = m.sampled(&[-1.0], &[TAU - 1.0], 37, &[0.0, 4.0]).unwrap();
    let refused = |r: Result<(), kinloop::Error>| matches!(r, Err(kinloop::Error::InvalidArgument(ref s)) if s.contains("without parameter sensitivities"));
    assert!(refused(turn.extremum_with_gradient("s", Extreme::Max).map(drop)));
    assert!(refused(turn.integral_with_gradient("s").map(drop)));
}

/// Two curved laws meeting at a corner: `s = min(a sin phi, b cos phi)` has its maximum where
/// they cross, `tan phi = b / a`, and `s = max(..)` its minimum there.
fn corner_law(kind: &str) -> String {
    format!(
        "#[kinloop(sensitivities)]
pub struct Corner {{
    params a = 1, b = 2;
    input phi;
    unknowns s = 0;
    eq law: s == {kind}(a * sin(phi), b * cos(phi));
}}"
    )
}

/// The corner of `corner_law`'s branches in closed form: `(phi, s)` with `phi = atan2(b, a)`,
/// `s = a b / hypot(a, b)`.
fn corner_closed_form(a: f64, b: f64) -> (f64, f64) {
    (b.atan2(a), a * b / a.hypot(b))
}

/// An extremum at a corner of the motion (a kink) is not a root of the velocity analog, so the
/// envelope theorem does not give its gradient: one side's `d s / d p` and `x_grad = 0` came
/// back (here 0.89 and 0 by `a` where the corner's value and location move by 0.72 and -0.4).
/// Both now follow the corner (where the branches are equal) as central differences of the
/// closed form do; the cam law `h min(phi / p0, (2 pi - phi) / (2 pi - p0))` has its peak `h`
/// at `phi = p0` whatever `p0`.
#[test]
fn an_extremum_at_a_kink_has_the_corners_gradients() {
    let (a, b) = (1.0, 2.0);
    let (x, v) = corner_closed_form(a, b);
    // Central differences of the closed form: step 1e-5 leaves truncation ~1e-10 and
    // rounding ~1e-11 in the derivatives; the corner's are exact to the rounding of a step of
    // a few units of it beside the corner, so 1e-8 tells a right gradient from a side's.
    let h = 1e-5;
    let fd = |f: &dyn Fn(f64, f64) -> f64| {
        [(f(a + h, b) - f(a - h, b)) / (2.0 * h), (f(a, b + h) - f(a, b - h)) / (2.0 * h)]
    };
    let (dx, dv) = (fd(&|a, b| corner_closed_form(a, b).0), fd(&|a, b| corner_closed_form(a, b).1));
    for (kind, which) in [("min", Extreme::Max), ("max", Extreme::Min)] {
        let mut m = read(&corner_law(kind));
        for n in [16, 41, 100] {
            let run = m.sampled(&[0.1], &[1.5], n, &[0.1]).unwrap();
            let e = run.extremum_with_gradient("s", which).unwrap();
            assert!((e.x - x).abs() < 1e-14 && (e.value - v).abs() < 1e-14, "{kind}, {n}: {e:?}");
            for p in 0..2 {
                assert!((e.grad[p] - dv[p]).abs() < 1e-8, "{kind}, {n}: grad {:?} vs {dv:?}", e.grad);
                assert!((e.x_grad[p] - dx[p]).abs() < 1e-8, "{kind}, {n}: x_grad {:?} vs {dx:?}", e.x_grad);
            }
        }
    }
    let mut cam = read(
        "#[kinloop(sensitivities)]
pub struct CamLaw {
    params h = 1, p0 = 2;
    input phi;
    unknowns s = 0;
    eq law: s == h * min(phi / p0, (6.283185307179586 - phi) / (6.283185307179586 - p0));
}",
    );
    let run = cam.sampled(&[0.3], &[6.0], 73, &[0.0]).unwrap();
    let top = run.extremum_with_gradient("s", Extreme::Max).unwrap();
    // d h / d (h, p0) = (1, 0); the corner phi = p0 moves by (0, 1).
    assert!((top.grad[0] - 1.0).abs() < 1e-12 && top.grad[1].abs() < 1e-12, "{top:?}");
    assert!(top.x_grad[0].abs() < 1e-12 && (top.x_grad[1] - 1.0).abs() < 1e-12, "{top:?}");
}
