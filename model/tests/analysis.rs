//! The runtime's analyses of sampled sweeps (`SampledOf`: extremes, ranges, dwells, harmonics,
//! unbalance, time ratio, transmission angle) and its limit report on run-time models: the one
//! implementation over two kernels, against the compiled mechanisms of the same declarations
//! (the fixtures), and against closed forms that share nothing with either.
//!
//! With libm's sines and cosines in both sweeps the states are equal to the last bit
//! (`sweeps.rs`), and every analysis then performs the same operations on the same numbers:
//! its results must be equal bit for bit. With the compiled sweep's rotation cache they agree to
//! rounding.

mod common;

use common::{Libm, read, set};
use kinloop::Mechanism;
use kinloop::analysis::{Column, Extreme, Sampled};
use kinloop_fixtures as fx;
use kinloop_model::Model;
use kinloop_runtime::dims::KinState;
use std::f64::consts::{PI, TAU};
use std::fmt::Debug;

/// Both results equal (bit for bit: `f64` fields compared with `==`), or both errors.
fn same<T: PartialEq + Debug>(what: &str, c: Result<T, kinloop::Error>, r: Result<T, kinloop::Error>) -> bool {
    match (c, r) {
        (Ok(c), Ok(r)) => {
            assert_eq!(c, r, "{what}");
            true
        }
        (Err(_), Err(_)) => false,
        (c, r) => panic!("{what}: compiled {c:?}, run time {r:?}"),
    }
}

/// Every analysis of every unknown and output column over one sampled range of input 0 (the
/// other inputs moving along the straight path to `to`), compiled (with libm's sines) and run
/// time, equal bit for bit. Returns how many analyses gave a result (not an error).
fn same_analyses<M, const N: usize, const NI: usize, const NO: usize>(
    compiled: M,
    model: &mut Model,
    from: [f64; NI],
    to: [f64; NI],
    samples: usize,
) -> usize
where
    M: Mechanism<N, NI, NO>,
{
    let compiled = Libm(compiled);
    let guess = compiled.guess_flat(&from);
    let names: Vec<String> = model.unknowns().iter().chain(model.outputs()).cloned().collect();
    let input = model.inputs()[0].clone();
    let c = Sampled::<_, N, NO, NI>::path(&compiled, from, to, samples, guess).unwrap();
    let c = c.along(Column::<Libm<M>>::named(&input).unwrap()).unwrap();
    let r = model.sampled(&from, &to, samples, &guess).unwrap();
    let r = if NI == 1 { r } else { r.along(input.as_str()).unwrap() };
    assert_eq!(c.path_values(), r.path_values());
    for (a, b) in c.states().iter().zip(r.states()) {
        assert_eq!((&a.q[..], &a.out[..]), (b.q(), b.out()), "the samples at {:?}", a.x);
    }
    let mut results = 0;
    for name in &names {
        let col = Column::<Libm<M>>::named(name).unwrap();
        let n = name.as_str();
        results += usize::from(same(&format!("extremes of {n}"), c.extremes(col), r.extremes(n)));
        results += usize::from(same(&format!("range of {n}"), c.range(col), r.range(n)));
        results += usize::from(same(&format!("dwells of {n}"), c.dwells(col), r.dwells(n)));
        results += usize::from(same(&format!("harmonics of {n}"), c.fourier(col, 6), r.fourier(n, 6)));
        results += usize::from(same(&format!("unbalance of {n}"), c.unbalance(col, 1), r.unbalance(n, 1)));
        results += usize::from(same(&format!("time ratio of {n}"), c.time_ratio(col), r.time_ratio(n)));
        let peak = |j: kinloop::analysis::Jet| j.d2.abs();
        results += usize::from(same(&format!("peak of {n}"), c.peak_of(col, peak), r.peak_of(n, peak)));
        let s = 0.37 * c.path_values()[0] + 0.63 * c.path_values()[samples - 1];
        results += usize::from(same(&format!("{n} between samples"), c.jet_at(col, s), r.jet_at(n, s)));
    }
    results
}

#[test]
fn with_the_same_sines_the_analyses_are_equal_to_the_last_bit() {
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let n = same_analyses(fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 }, &mut m, [-1.0], [TAU - 1.0], 73);
    // Each column's extremes, range, harmonics, unbalance, peak and a jet at least.
    assert!(n >= 4 * 6, "{n} results");
    let mut m = read(fx::RHOMBIC_DRIVE_TEXT);
    assert!(same_analyses(fx::RhombicDrive::default(), &mut m, [0.0], [TAU], 145) >= 6 * 6);
    let mut m = read(fx::SLIDER_CRANK_TEXT);
    set(&mut m, &[("r", 1.0), ("l", 3.0), ("e", 0.4)]);
    assert!(same_analyses(fx::SliderCrank { r: 1.0, l: 3.0, e: 0.4 }, &mut m, [0.0], [TAU], 37) >= 2 * 6);
    // Two inputs moving together, the first as the path parameter.
    let mut m = read(fx::FIVE_BAR_TEXT);
    assert!(same_analyses(fx::FiveBar::default(), &mut m, [0.0, 1.0], [PI, 1.0 + PI / 2.0], 91) >= 3 * 3);
}

/// The transmission angle and the limit report, compiled (with libm's sines) and run time.
#[test]
fn with_the_same_sines_the_metrics_are_equal_to_the_last_bit() {
    let links = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let compiled = Libm(fx::FourBar { ..links });
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let guess = compiled.guess_flat(&[-1.0]);
    let c = Sampled::sweep(&compiled, -1.0, TAU - 1.0, 73, guess).unwrap();
    let col = |n: &str| Column::<Libm<fx::FourBar>>::named(n).unwrap();
    let ct = c.transmission(col("beta"), col("gamma")).unwrap();
    let r = m.sampled(&[-1.0], &[TAU - 1.0], 73, &guess).unwrap();
    assert_eq!(ct, r.transmission("beta", "gamma").unwrap());
    let columns = [col("gamma"), col("pc.x")];
    let cl = kinloop::metrics::Limits::new(&compiled, -1.0, TAU - 1.0)
        .samples(73)
        .guess(guess)
        .columns(&columns)
        .run()
        .unwrap();
    let rl = m.limits(-1.0, TAU - 1.0, 73, &guess, &["gamma", "pc.x"]).unwrap();
    assert_eq!((cl.reached, &cl.outputs), (rl.reached, &rl.outputs));
    assert_eq!(cl.outputs[0].extremes.len(), 2);
    assert!(cl.events.is_empty() && rl.events.is_empty());
}

/// Relative agreement with the compiled mechanism's own sweep (its sines from the rotation
/// cache, a few units in the last place off libm's): the states agree to 1e-13 of their scale
/// (`sweeps.rs`); an extreme's value is where the analog vanishes, so it moves only to second
/// order, and its location by the analog's error over the curvature (of order one here): 1e-10.
#[test]
fn analyses_agree_with_the_compiled_sweeps_to_rounding() {
    let links = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let guess = links.guess_flat(&[0.0]);
    let c = Sampled::sweep(&links, 0.0, TAU, 73, guess).unwrap();
    let r = m.sampled(&[0.0], &[TAU], 73, &guess).unwrap();
    for name in ["beta", "gamma", "pc.x", "pc.y"] {
        let (a, b) = (c.range(Column::named(name).unwrap()).unwrap(), r.range(name).unwrap());
        for (p, q) in [(a.min, b.min), (a.max, b.max)] {
            assert!((p.value - q.value).abs() <= 1e-13 * (1.0 + p.value.abs()), "{name}: {a:?} {b:?}");
            assert!((p.x - q.x).abs() <= 1e-10, "{name}: {a:?} {b:?}");
        }
        let (a, b) = (c.fourier(Column::named(name).unwrap(), 4).unwrap(), r.fourier(name, 4).unwrap());
        for k in 0..4 {
            assert!((a.a[k] - b.a[k]).abs() <= 1e-13 && (a.b[k] - b.b[k]).abs() <= 1e-13, "{name}: {a:?} {b:?}");
        }
    }
}

/// The offset slider-crank (`r @ phi == (x, e) + l @ psi`, the slider on the crank's -x side):
/// the slider is nearest the crank pivot with crank and rod folded, `|x| = sqrt((l - r)^2 - e^2)`,
/// the crank pointing away from it; farthest with them stretched, `|x| = sqrt((l + r)^2 - e^2)`,
/// the crank pointing at it. Located to the analog's rounding over the curvature (1e-10, as the
/// runtime's own tests), the values to second order (1e-12).
#[test]
fn slider_crank_stroke_and_dead_centres_from_the_closed_form() {
    let (r, l, e) = (1.0, 3.0, 0.4);
    let mut m = read(fx::SLIDER_CRANK_TEXT);
    set(&mut m, &[("r", r), ("l", l), ("e", e)]);
    let near = ((l - r) * (l - r) - e * e).sqrt();
    let far = ((l + r) * (l + r) - e * e).sqrt();
    let (phi_near, phi_far) = (f64::atan2(-e, near).rem_euclid(TAU), f64::atan2(e, -far).rem_euclid(TAU));
    let guess = [0.0, -(l * l - e * e).sqrt() + r];
    let turn = m.sampled(&[0.0], &[TAU], 73, &guess).unwrap();
    let x = turn.range("x").unwrap();
    assert!((x.max.value - -near).abs() < 1e-12 && (x.min.value - -far).abs() < 1e-12, "{x:?}");
    assert!((x.max.x - phi_near).abs() < 1e-10 && (x.min.x - phi_far).abs() < 1e-10, "{x:?}");
    assert!((x.span() - (far - near)).abs() < 1e-12, "the stroke: {x:?}");
    let e2 = turn.extremes("x").unwrap();
    assert_eq!(e2.iter().map(|e| e.kind).collect::<Vec<_>>(), [Extreme::Min, Extreme::Max], "{e2:?}");
    // The harmonics against the trapezoidal sums of the closed form x(phi) on the same grid.
    let x_of = |phi: f64| r * phi.cos() - (l * l - (r * phi.sin() - e).powi(2)).sqrt();
    let f = turn.fourier("x", 5).unwrap();
    let n = 72;
    for k in 1..=5 {
        let (mut a, mut b) = (0.0, 0.0);
        for j in 0..n {
            let phi = TAU * j as f64 / n as f64;
            a += x_of(phi) * (k as f64 * phi).cos() * 2.0 / n as f64;
            b += x_of(phi) * (k as f64 * phi).sin() * 2.0 / n as f64;
        }
        assert!((f.a[k - 1] - a).abs() < 1e-12 && (f.b[k - 1] - b).abs() < 1e-12, "harmonic {k}: {f:?}");
    }
    // A column the model does not have.
    assert!(matches!(turn.range("y"), Err(kinloop::Error::InvalidArgument(_))));
    // The limit report of the same range: no event, the same dead centres.
    let report = m.limits(0.0, TAU, 73, &guess, &["x"]).unwrap();
    assert!(report.events.is_empty(), "{report}");
    let d = &report.outputs[0].extremes;
    assert!((d[0].value() - -far).abs() < 1e-12 && (d[1].value() - -near).abs() < 1e-12, "{report}");
    assert!(matches!(m.limits(0.0, TAU, 73, &guess, &["y"]), Err(kinloop::Error::InvalidArgument(_))));
    // Inputs or a guess of the wrong size: typed errors, also straight from the runtime's
    // `SampledOf` over the model's kernel (an empty input used to be indexed before any check).
    let bad = |r: Result<_, kinloop::Error>| matches!(r, Err(kinloop::Error::InvalidArgument(_)));
    assert!(bad(m.sampled(&[], &[TAU], 73, &guess).map(|_| ())));
    assert!(bad(m.sampled(&[0.0], &[TAU], 73, &[]).map(|_| ())));
    assert!(bad(m.limits(0.0, TAU, 73, &[], &["x"]).map(|_| ())));
    let cfg = kinloop_runtime::SweepConfig::default();
    let k = m.kernel(cfg).unwrap();
    let (h, g) = (kinloop_runtime::dims::Heap(Box::new([])), kinloop_runtime::dims::Heap(guess.as_slice().into()));
    assert!(bad(kinloop_runtime::analysis::SampledOf::over(k, h.clone(), h, 73, g, cfg).map(|_| ())));
}

/// A crank-rocker (`a @ phi + b @ beta == (d, 0) + c @ gamma`, crank `a` shortest): the rocker's
/// limit positions are where crank and coupler line up, `|AC| = b + a` or `b - a`, and the
/// triangle A-D-C gives the rocker angle, `|AC|^2 = d^2 + c^2 + 2 d c cos gamma`, the crank
/// along A-C (stretched) or against it (folded). The time ratio is the crank angle between
/// them; the transmission angle is smallest with the crank along the frame, `cos mu = (b^2 +
/// c^2 - (d - a)^2) / (2 b c)`, and reaches 90 degrees.
#[test]
fn four_bar_rocker_limits_from_the_limit_position_geometry() {
    let (a, b, c, d) = (1.0, 3.0, 2.5, 3.2);
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", a), ("b", b), ("c", c), ("d", d)]);
    // The rocker angle and the crank angle at each limit position (upper assembly, gamma in (0, pi)).
    let limit = |ac: f64, stretched: bool| {
        let gamma = ((ac * ac - d * d - c * c) / (2.0 * d * c)).acos();
        let (cx, cy) = (d + c * gamma.cos(), c * gamma.sin());
        let phi = if stretched { cy.atan2(cx) } else { (-cy).atan2(-cx) };
        (gamma, phi.rem_euclid(TAU))
    };
    let (g1, p1) = limit(b + a, true);
    let (g2, p2) = limit(b - a, false);
    let ((g_min, p_min), (g_max, p_max)) = if g1 < g2 { ((g1, p1), (g2, p2)) } else { ((g2, p2), (g1, p1)) };
    let guess = [0.5, 1.5];
    let turn = m.sampled(&[0.0], &[TAU], 73, &guess).unwrap();
    let gamma = turn.range("gamma").unwrap();
    assert!((gamma.min.value - g_min).abs() < 1e-12 && (gamma.max.value - g_max).abs() < 1e-12, "{gamma:?}");
    assert!((gamma.min.x - p_min).abs() < 1e-10 && (gamma.max.x - p_max).abs() < 1e-10, "{gamma:?}");
    let t = turn.time_ratio("gamma").unwrap();
    let rising = (p_max - p_min).rem_euclid(TAU);
    assert!((t.rising - rising).abs() < 1e-10 && (t.falling - (TAU - rising)).abs() < 1e-10, "{t:?}");
    // The transmission angle over a turn with the crank along the frame inside the range.
    let turn = m.sampled(&[-1.0], &[TAU - 1.0], 73, &guess).unwrap();
    let mu = turn.transmission("beta", "gamma").unwrap();
    let mu_min = ((b * b + c * c - (d - a) * (d - a)) / (2.0 * b * c)).acos();
    assert!((mu.min.angle - mu_min).abs() < 1e-12 && mu.min.x.abs() < 1e-10, "{mu:?}");
    assert!((mu.max.angle - PI / 2.0).abs() < 1e-12 && mu.dead_points.is_empty(), "{mu:?}");
}

/// A Grashof-equal four-bar (`a + d = b + c`) read at run time, through its change point at
/// `phi = pi`: the limit report of every column succeeds, at the same numbers as the compiled
/// mechanism's (the one search over two kernels), with the crossing and, for the joint's `x`,
/// its minimum `d - c` at the crossing (the run-time report failed there as the compiled one
/// did: a stop at the crossing with 73 samples, a branch error with 10 and with 5 up to 3.5).
#[test]
// The range short of a full turn (6.28) is the one the failure was found with, not `TAU`.
#[allow(clippy::approx_constant)]
fn limits_of_a_run_time_four_bar_pass_its_change_point() {
    let (a, b, c, d) = (1.0, 2.0, 2.5, 3.5);
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", a), ("b", b), ("c", c), ("d", d)]);
    let compiled = fx::FourBar { a, b, c, d };
    let guess = compiled.guess_flat(&[0.0]);
    for (to, samples) in [(6.28, 73), (6.28, 10), (3.5, 5)] {
        for name in ["beta", "gamma", "pc.x", "pc.y"] {
            let what = format!("{name} to {to}, {samples} samples");
            let r = m.limits(0.0, to, samples, &guess, &[name]).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_eq!(r.events.len(), 1, "{what}: {r}");
            assert!((r.events[0].x[0] - PI).abs() < 1e-9, "{what}: {r}");
            let columns = [Column::<fx::FourBar>::named(name).unwrap()];
            let cl = kinloop::metrics::Limits::new(&compiled, 0.0, to).samples(samples).guess(guess).columns(&columns);
            let cl = cl.run().unwrap();
            assert_eq!(r.reached, cl.reached, "{what}");
            assert_eq!(r.outputs[0].extremes.len(), cl.outputs[0].extremes.len(), "{what}: {r} {cl}");
            for (p, q) in r.outputs[0].extremes.iter().zip(&cl.outputs[0].extremes) {
                assert!((p.x() - q.x()).abs() < 1e-9 && (p.value() - q.value()).abs() < 1e-12, "{what}: {r} {cl}");
            }
            if name == "pc.x" {
                let at: Vec<_> = r.outputs[0].extremes.iter().filter(|e| e.kind == Extreme::Min).collect();
                assert_eq!(at.len(), 1, "{what}: {r}");
                assert_eq!(at[0].x(), r.events[0].x[0], "{what}: {r}");
                assert!((at[0].value() - (d - c)).abs() < 1e-12, "{what}: {r}");
            }
        }
    }
}

/// A name that is no column is refused listing the columns by group, a group without any as
/// `none` (it read `outputs ` and stopped, as if cut off), and a point's name with its two
/// columns; the compiled mechanism and the run-time model of the same declaration alike.
#[test]
fn a_name_that_is_no_column_is_told_the_columns() {
    use kinloop::analysis::ColumnOf;
    let message = |e: kinloop::Error| e.to_string();
    let mut slider = read(fx::SLIDER_CRANK_TEXT);
    set(&mut slider, &[("r", 1.0), ("l", 3.0), ("e", 0.2)]);
    let slider_kernel = slider.kernel(kinloop::SweepConfig::default()).expect("a kernel");
    let compiled = message(Column::<fx::SliderCrank>::named("pc").unwrap_err());
    assert_eq!(
        compiled,
        "invalid argument: `pc` is no column of `SliderCrank`: inputs phi; unknowns psi, x; outputs none"
    );
    assert_eq!(message("pc".resolve(&slider_kernel).unwrap_err()).replace("fixture", "SliderCrank"), compiled);
    let mut four = read(fx::FOUR_BAR_TEXT);
    set(&mut four, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.5)]);
    let four_kernel = four.kernel(kinloop::SweepConfig::default()).expect("a kernel");
    let compiled = message(Column::<fx::FourBar>::named("pc").unwrap_err());
    assert_eq!(
        compiled,
        "invalid argument: `pc` is no column of `FourBar`: inputs phi; unknowns beta, gamma; outputs pc.x, pc.y \
         (`pc` is a point: its columns are `pc.x` and `pc.y`)"
    );
    assert_eq!(message("pc".resolve(&four_kernel).unwrap_err()).replace("fixture", "FourBar"), compiled);
}
