//! The runtime's sweep over a run-time model against the same sweep over the compiled
//! mechanism of the same declaration (the fixtures of `parity.rs`): one implementation of the
//! sweep, two kernels. The reference is the compiled kernels (straight-line Rust the macro
//! emitted); the states must agree to the kernels' own agreement (`parity.rs`: a relative 1e-15
//! of each array's largest magnitude) at every sample, the events must be the same events at
//! the same inputs.
//!
//! The compiled sweep's steps take the inputs' sines and cosines from a rotation cache (a few
//! units in the last place off libm's, see the runtime's `trig`), a run-time model's from libm:
//! so the sweeps agree to rounding, not bit for bit, and the step sequences (accepted, halved)
//! are the same where no judgement sits within rounding of its bound.

mod common;

use common::{Libm, read, set};
use kinloop::{Event, Kin, Mechanism, Sweep};
use kinloop_fixtures as fx;
use kinloop_model::Model;
use kinloop_runtime::dims::KinBuf;
use std::f64::consts::TAU;

/// Relative agreement demanded, of each array's largest magnitude (the kernels' own, see
/// `parity.rs`), with room for the rotation cache's few ulps amplified by a step's Newton
/// correction: 1e-13.
const REL: f64 = 1e-13;

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    a.iter().zip(b).map(|(x, y)| (x - y).abs() / scale).fold(0.0, f64::max)
}

/// One compiled state against one run-time state: every array.
fn state_diff<const N: usize, const NI: usize, const NO: usize>(c: &Kin<N, NI, NO>, r: &KinBuf) -> f64 {
    let f2 = |v: &[[f64; NI]]| v.iter().flatten().copied().collect::<Vec<f64>>();
    let f3 = |v: &[[[f64; NI]; NI]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
    [
        rel_diff(&c.x, &r.x),
        rel_diff(&c.q, &r.q),
        rel_diff(&f2(&c.dq), &r.dq),
        rel_diff(&f3(&c.d2q), &r.d2q),
        rel_diff(&c.out, &r.out),
        rel_diff(&f2(&c.dout), &r.dout),
        rel_diff(&f3(&c.d2out), &r.d2out),
    ]
    .into_iter()
    .fold(0.0, f64::max)
}

/// Both sweeps of input 0 over `[from, to]` (the other inputs at `from`'s), sample by sample;
/// returns the largest difference, the samples compared and the two sweeps' events and errors.
fn both<M, const N: usize, const NI: usize, const NO: usize>(
    compiled: &M,
    model: &mut Model,
    from: [f64; NI],
    to: [f64; NI],
    samples: usize,
) -> (f64, usize, Vec<Event>, Vec<Event>, Option<String>, Option<String>)
where
    M: Mechanism<N, NI, NO>,
{
    let guess = compiled.guess_flat(&from);
    let mut c = Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(compiled, from, to, samples, guess).unwrap();
    let mut r = model.sweep(&from, &to, samples, &guess).unwrap();
    let (mut worst, mut compared) = (0.0f64, 0);
    let (mut c_err, mut r_err) = (None, None);
    loop {
        match (c.next_ref(), r.next_ref()) {
            (Some(Ok(a)), Some(Ok(b))) => {
                assert_eq!(a.health.det_signs, b.health.det_signs, "determinant signs at {:?}", a.x);
                worst = worst.max(state_diff(a, b));
                compared += 1;
            }
            (None, None) => break,
            (Some(Err(a)), Some(Err(b))) => {
                (c_err, r_err) = (Some(a.to_string()), Some(b.to_string()));
                break;
            }
            (a, b) => panic!(
                "the sweeps part after {compared} samples: compiled {:?}, run time {:?}",
                a.map(|x| x.map(|k| k.q)),
                b.map(|x| x.map(|k| k.q.clone()))
            ),
        }
    }
    (worst, compared, c.events().to_vec(), r.events().to_vec(), c_err, r_err)
}

/// The same events: kind and block (its index and names), and input, fraction and positions to
/// the states' agreement.
fn same_events(c: &[Event], r: &[Event]) {
    assert_eq!(c.len(), r.len(), "compiled {c:?}\nrun time {r:?}");
    for (a, b) in c.iter().zip(r) {
        assert_eq!(a.kind, b.kind);
        assert_eq!(a.block, b.block, "{a:?}\n{b:?}");
        assert!(rel_diff(&a.x, &b.x) <= REL, "{a:?}\n{b:?}");
        assert!((a.tau - b.tau).abs() <= REL, "{a:?}\n{b:?}");
        assert!(rel_diff(&a.q, &b.q) <= REL, "{a:?}\n{b:?}");
    }
}

/// With libm's sines and cosines in both, the one sweep over the two kernels gives the same
/// states bit for bit, sample by sample, and the same events at the same inputs.
#[test]
fn with_the_same_sines_the_sweeps_are_equal_to_the_last_bit() {
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let (worst, n, ..) = both(&Libm(fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 }), &mut model, [0.0], [TAU], 721);
    assert_eq!((worst, n), (0.0, 721));
    set(&mut model, &[("a", 1.5), ("b", 3.0), ("c", 1.0), ("d", 3.2)]);
    let compiled = Libm(fx::FourBar { a: 1.5, b: 3.0, c: 1.0, d: 3.2 });
    let (worst, n, ce, re, ..) = both(&compiled, &mut model, [1.2], [1.2 + TAU], 361);
    assert_eq!(worst, 0.0, "after {n} samples");
    assert_eq!(ce.len(), 1);
    // The same event, bit for bit (a run-time model's carries no static block description).
    let strip = |e: &[Event]| e.iter().map(|e| (e.kind, e.x.clone(), e.tau, e.q.clone())).collect::<Vec<_>>();
    assert_eq!(strip(&ce), strip(&re));
    let mut m = read(fx::RHOMBIC_DRIVE_TEXT);
    let (worst, n, ..) = both(&Libm(fx::RhombicDrive::default()), &mut m, [0.0], [TAU], 361);
    assert_eq!((worst, n), (0.0, 361));
}

#[test]
fn four_bar_sweeps_equal_the_compiled_one() {
    let compiled = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let (worst, n, ce, re, cerr, rerr) = both(&compiled, &mut model, [0.0], [TAU], 721);
    assert_eq!(n, 721);
    assert!(worst <= REL, "largest relative difference {worst:e}");
    assert!(ce.is_empty() && re.is_empty() && cerr.is_none() && rerr.is_none());
    eprintln!("four-bar sweep: {n} samples, largest relative difference {worst:e}");
}

/// A rocker input (Grashof, shortest link the output): both sweeps stop at the same limit
/// position, located at the same input.
#[test]
fn a_limit_position_is_the_same_event() {
    let (a, b, c, d) = (1.5, 3.0, 1.0, 3.2);
    let compiled = fx::FourBar { a, b, c, d };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", a), ("b", b), ("c", c), ("d", d)]);
    // Start where the loop closes (|AD| = 3, between |b - c| = 2 and b + c = 4), going up
    // to where the coupler and the output stretch in line.
    let (worst, n, ce, re, cerr, rerr) = both(&compiled, &mut model, [1.2], [1.2 + TAU], 361);
    assert!(n > 10, "only {n} samples");
    assert!(worst <= REL, "largest relative difference {worst:e}");
    assert_eq!(ce.len(), 1, "{ce:?}");
    assert_eq!(ce[0].kind, kinloop::EventKind::LimitPosition);
    same_events(&ce, &re);
    assert!(cerr.is_some() && rerr.is_some(), "{cerr:?} {rerr:?}");
    // The limit position against the closed form: the coupler and the output in line,
    // |A - D| = b + c, i.e. a^2 + d^2 - 2 a d cos(phi) = (b + c)^2.
    let phi = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    assert!((re[0].x[0] - phi).abs() < 1e-9, "event at {}, closed form {phi}", re[0].x[0]);
    eprintln!("limit position at {} (closed form {phi}), {n} samples, {worst:e}", re[0].x[0]);
}

/// Both comparisons on one fixture over `[from, to]`: against the compiled sweep (to `REL`, the
/// same events at the same inputs, both stopping or neither) and against the compiled kernels
/// with libm's sines (bit for bit). Returns the samples compared and the events met.
fn fixture<M, const N: usize, const NI: usize, const NO: usize>(
    name: &str,
    compiled: M,
    model: &mut Model,
    from: [f64; NI],
    to: [f64; NI],
    samples: usize,
) -> (usize, usize)
where
    M: Mechanism<N, NI, NO>,
{
    let (worst, n, ce, re, cerr, rerr) = both(&compiled, model, from, to, samples);
    assert!(worst <= REL, "{name}: largest relative difference {worst:e}");
    same_events(&ce, &re);
    assert_eq!(cerr.is_some(), rerr.is_some(), "{name}: {cerr:?} {rerr:?}");
    // Every sample requested compared, or a stop that an event explains: two sweeps failing
    // alike at their first sample would otherwise agree.
    if ce.is_empty() {
        assert_eq!((n, &cerr), (samples, &None), "{name}: samples compared of {samples}");
    } else {
        assert!(n > 0, "{name}: stopped at the start after the events {ce:?}");
    }
    let (worst, n_libm, ce, re, ..) = both(&Libm(compiled), model, from, to, samples);
    assert_eq!(worst, 0.0, "{name}: with libm's sines");
    assert_eq!(n_libm, n, "{name}: samples compared with libm's sines");
    let strip = |e: &[Event]| e.iter().map(|e| (e.kind, e.x.clone(), e.tau, e.q.clone())).collect::<Vec<_>>();
    assert_eq!(strip(&ce), strip(&re), "{name}: events with libm's sines");
    eprintln!("{name}: {n} samples ({n_libm} with libm's sines), {} events", ce.len());
    (n, ce.len())
}

/// Every fixture of `parity.rs` over a whole turn of its first input.
#[test]
fn other_fixtures_sweep_as_the_compiled_ones() {
    let turn = [0.0];
    let end = [TAU];
    let n = fixture("rhombic drive", fx::RhombicDrive::default(), &mut read(fx::RHOMBIC_DRIVE_TEXT), turn, end, 361);
    assert_eq!(n.0, 361);
    let dense = |text: &str, name: &str, twin: &str| {
        read(&format!("#[kinloop(dense)] {}", text.replacen(&format!("struct {name} "), &format!("struct {twin} "), 1)))
    };
    let mut m = dense(fx::RHOMBIC_DRIVE_TEXT, "RhombicDrive", "RhombicDriveDense");
    assert_eq!(fixture("rhombic drive (dense)", fx::RhombicDriveDense::default(), &mut m, turn, end, 361).0, 361);
    let mut m = read(fx::SLIDER_CRANK_TEXT);
    set(&mut m, &[("r", 1.0), ("l", 3.0), ("e", 0.4)]);
    assert_eq!(fixture("slider-crank", fx::SliderCrank { r: 1.0, l: 3.0, e: 0.4 }, &mut m, turn, end, 181).0, 181);
    fixture("five-bar", fx::FiveBar::default(), &mut read(fx::FIVE_BAR_TEXT), [0.0, 0.4], [TAU, 0.4], 181);
    fixture("class IV", fx::ClassFour::default(), &mut read(fx::CLASS_FOUR_TEXT), turn, end, 181);
    let mut m = dense(fx::CLASS_FOUR_TEXT, "ClassFour", "ClassFourDense");
    fixture("class IV (dense)", fx::ClassFourDense::default(), &mut m, turn, end, 181);
    let mut m = read(fx::DISPLACER_ROD_DRIVE_TEXT);
    fixture("displacer-rod drive", fx::DisplacerRodDrive::default(), &mut m, turn, end, 181);
    let mut m = read(fx::WORKING_ROD_DRIVE_TEXT);
    fixture("working-rod drive", fx::WorkingRodDrive::default(), &mut m, turn, end, 181);
    let mut m = read(fx::gear_lever::GEAR_LEVER_TEXT);
    fixture("gear lever", fx::gear_lever::GearLever::default(), &mut m, turn, end, 181);
    let mut m = read(fx::roller_edger::ROLLER_EDGER_TEXT);
    fixture("roller edger", fx::roller_edger::RollerEdger::default(), &mut m, turn, end, 181);
    let mut m = read(fx::balancing::BALANCE_TEXT);
    fixture("balance", fx::balancing::Balance::default(), &mut m, turn, end, 181);
    let mut m = read(fx::CLASS_FOUR_CORE_TEXT);
    fixture("class IV core", fx::ClassFourCore::default(), &mut m, turn, end, 181);
}

/// The table of a run-time sweep: the compiled sweep's columns, units and rows.
#[test]
fn tables_equal_the_compiled_ones() {
    let compiled = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let g = compiled.guess_flat(&[0.0]);
    let c = Sweep::<_, Kin<2, 1, 2>, 2, 1, 2>::new(&compiled, [0.0], [TAU], 37, g).unwrap().table().unwrap();
    let r = model.sweep(&[0.0], &[TAU], 37, &g).unwrap().table().unwrap();
    let (mut a, mut b) = (Vec::new(), Vec::new());
    c.write_csv(&mut a).unwrap();
    r.write_csv(&mut b).unwrap();
    let (a, b) = (String::from_utf8(a).unwrap(), String::from_utf8(b).unwrap());
    assert_eq!(a.lines().next(), b.lines().next(), "headers");
    let (ta, tb) = (kinloop::Table::read_csv(a.as_bytes()).unwrap(), kinloop::Table::read_csv(b.as_bytes()).unwrap());
    for name in ["phi", "beta", "gamma", "d(beta)/d(phi)", "d2(gamma)/d(phi)^2", "pc.x"] {
        let (x, y) = (ta.column(name).unwrap(), tb.column(name).unwrap());
        assert!(rel_diff(&x, &y) <= REL, "{name}");
    }
}

/// A parallelogram four-bar (`a = c`, `b = d`) has change points where its links lie in line,
/// at `phi = 0` and `pi`: from `phi = 0.3` both sweeps stop at the same singular crossing, at
/// `pi`.
#[test]
fn a_singular_crossing_is_the_same_event() {
    let (a, b, c, d) = (1.0, 3.0, 1.0, 3.0);
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", a), ("b", b), ("c", c), ("d", d)]);
    // The parallelogram branch through the start (beta = 0, gamma = phi).
    let guess = [0.0, 0.3];
    let compiled = fx::FourBar { a, b, c, d };
    let mut cs = Sweep::<_, Kin<2, 1, 2>, 2, 1, 2>::new(&compiled, [0.3], [0.3 + TAU], 181, guess).unwrap();
    let mut rs = model.sweep(&[0.3], &[0.3 + TAU], 181, &guess).unwrap();
    let (c_states, r_states) = (cs.by_ref().count(), rs.by_ref().count());
    assert_eq!(c_states, r_states);
    let (ce, re) = (cs.events().to_vec(), rs.events().to_vec());
    assert_eq!(ce.len(), 1, "{ce:?}");
    assert_eq!(ce[0].kind, kinloop::EventKind::SingularCrossing);
    same_events(&ce, &re);
    // The singular block named alike: the compiled constants, the model's own names.
    let (Some((_, c_info)), Some((_, r_info))) = (&ce[0].block, &re[0].block) else { panic!("{ce:?}\n{re:?}") };
    assert!(matches!(c_info.equations, std::borrow::Cow::Borrowed(_)), "{c_info:?}");
    assert!(matches!(r_info.equations, std::borrow::Cow::Owned(_)), "{r_info:?}");
    assert_eq!(r_info.equations, &["abcd.x", "abcd.y"][..], "{r_info:?}");
    assert!((re[0].x[0] - std::f64::consts::PI).abs() < 1e-6, "crossing at {}", re[0].x[0]);
}

/// A sweep that cannot start names the run-time model and its input with the model's own
/// (owned) names, as the compiled mechanism's error names its constants.
#[test]
fn a_failed_start_names_the_model() {
    let (a, b, c, d) = (1.5, 3.0, 1.0, 3.2);
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", a), ("b", b), ("c", c), ("d", d)]);
    // At phi = 0, |AD| = 1.7 is shorter than |b - c| = 2: no assembly.
    let compiled = fx::FourBar { a, b, c, d };
    let g = compiled.guess_flat(&[0.0]);
    let c_err =
        Sweep::<_, Kin<2, 1, 2>, 2, 1, 2>::new(&compiled, [0.0], [1.0], 3, g).unwrap().next().unwrap().unwrap_err();
    let r_err = model.sweep(&[0.0], &[1.0], 3, &g).unwrap().next().unwrap().unwrap_err();
    let (c_at, r_at) = (c_err.location().expect("located"), r_err.location().expect("located"));
    assert_eq!((&c_at.mechanism, &c_at.inputs), (&r_at.mechanism, &r_at.inputs));
    assert!(matches!(r_at.mechanism, std::borrow::Cow::Owned(_)));
    assert!(r_err.to_string().contains("in `FourBar` at phi = 0"), "{r_err}");
    // The same failure is the same variant, the residual where the loop stalls the same.
    assert_eq!(std::mem::discriminant(&c_err), std::mem::discriminant(&r_err), "{c_err:?}\n{r_err:?}");
    let (kinloop::Error::NoAssembly { residual: c_res, .. }, kinloop::Error::NoAssembly { residual: r_res, .. }) =
        (&c_err, &r_err)
    else {
        panic!("no assembly expected: {c_err:?}\n{r_err:?}")
    };
    // The residual is the closed form's gap |b - c| - |AD| = 0.3 over the dyad's size
    // b + c + |AD| = 5.7: the same to a few rounding steps.
    assert!((c_res - r_res).abs() <= 1e-12 * c_res.abs().max(1.0), "{c_res:e} {r_res:e}");
    // Named alike, to the block: with the compiled residual, the run-time error reads as the
    // compiled one, character for character (the model's names owned, the compiled constants).
    let kinloop::Error::NoAssembly { equation, .. } = &r_err else { unreachable!() };
    assert!(matches!(equation, std::borrow::Cow::Owned(_)), "{r_err:?}");
    let r_named =
        kinloop::Error::NoAssembly { residual: *c_res, equation: equation.clone(), at: Box::new(r_at.clone()) };
    assert_eq!(c_err.to_string(), r_named.to_string());
    assert_eq!(c_at.block, r_at.block);
    assert!(c_at.block.is_some(), "{c_err:?}");
    eprintln!("compiled: {c_err}\nrun time: {r_err}");
}

/// Far out, where the input's doubles are a sixteenth of a radian apart (4e14) and more,
/// a run-time model's sweep fails saying so. With samples 277 rad apart its diagnosis of the
/// failed step followed the curve in steps the inputs' rounding kept rejecting and never ended
/// (the command line's `kinloop sweep` hung). From 1e12 to 1e16, samples 0.28 and 277 rad
/// apart, each sweep completes or says the input is too coarse.
#[test]
fn a_sweep_far_out_ends_and_says_the_input_is_coarse() {
    let mut model = read(fx::SLIDER_CRANK_TEXT);
    set(&mut model, &[("r", 1.0), ("l", 3.0), ("e", 0.4)]);
    for from in [1e12, 1e13, 1e14, 4e14, 1e15, 1e16] {
        for span in [1e2, 1e5] {
            let mut guess = vec![0.0; 2];
            model.guess(&[from], &mut guess).unwrap();
            let mut sweep = model.sweep(&[from], &[from + span], 361, &guess).unwrap();
            let mut failure = None;
            while let Some(item) = sweep.next_ref() {
                if let Err(e) = item {
                    failure = Some(e.to_string());
                    break;
                }
            }
            if let Some(message) = failure {
                let coarse = message.contains("input `phi` is a double") && message.contains("whole turns");
                assert!(coarse, "{from} + {span}: {message}");
            }
        }
    }
}

/// A model's own sweep configuration (`Model::set_sweep_config`) reaches the analyses that take
/// none, as a compiled `Configured` mechanism's does: a slotted rocker whose slide passes 1e-8
/// of the crank's radius from the rocker's pivot stops the default sweep (the smallest pivot
/// ratio below `singular_pivot`, 1e-6) with a message to lower it; lowered, the sweep, the
/// sampled analysis pass, on the rocker's closed form.
#[test]
fn a_model_s_sweep_configuration_reaches_its_sweeps_and_analyses() {
    let text = "pub struct SlottedRocker {
        params h, r;
        input phi;
        unknowns s = 1, theta = 0.5;
        loop slot: (0, h) + r @ phi == s @ theta;
    }";
    for scale in [1e-3, 1.0, 1e3] {
        let (h, r) = (scale * (1.0 + 1e-8), scale);
        let mut m = Model::read("rocker.kl", text).unwrap();
        assert!(m.set_param("h", h) && m.set_param("r", r));
        let exact = |phi: f64| (h + r * phi.sin()).atan2(r * phi.cos());
        let guess = [h + r, 0.5 * std::f64::consts::PI];
        let guess = m.kinematics(&[0.0], &guess, &Default::default()).unwrap().q.clone();
        let default = m.sweep(&[0.0], &[TAU], 73, &guess).unwrap().find_map(Result::err).expect("a stop");
        assert!(default.to_string().contains("singular_pivot"), "{default}");
        assert!(m.sampled(&[0.0], &[TAU], 73, &guess).is_err());
        let config = m.sweep_config().with_singular_pivot(1e-12);
        m.set_sweep_config(config).unwrap();
        let turned =
            |q: &[f64], phi: f64| (q[1] - exact(phi) + std::f64::consts::PI).rem_euclid(TAU) - std::f64::consts::PI;
        for state in m.sweep(&[0.0], &[TAU], 73, &guess).unwrap() {
            let state = state.unwrap();
            assert!(turned(&state.q, state.x[0]).abs() < 1e-9 && state.q[0] > 0.0, "scale {scale:e} at {}", state.x[0]);
        }
        assert!(m.sampled(&[0.0], &[TAU], 73, &guess).is_ok());
        // An invalid configuration is refused, and the model keeps its own.
        assert!(m.set_sweep_config(config.with_singular_pivot(f64::NAN)).is_err());
        assert_eq!(m.sweep_config().singular_pivot, 1e-12);
    }
}

/// A run-time model's sweep collects under the runtime's memory budget, its states counted
/// with the arrays they hold on the heap: a sweep whose states' own size fits the budget but
/// whose arrays do not is refused by `run` before any step (and one of the most samples by
/// `table`); iterated, it steps.
#[test]
fn collecting_a_model_sweep_counts_its_states_arrays() {
    use kinloop_runtime::dims::KinState;
    use kinloop_runtime::paths::collected::MAX_COLLECTED_BYTES;
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let g = [0.6, 1.9];
    let first = model.sweep(&[0.0], &[TAU], 2, &g).unwrap().next().unwrap().unwrap();
    let (own, heap) = (size_of::<KinBuf>(), first.heap_bytes());
    assert!(heap > 0);
    let samples = MAX_COLLECTED_BYTES / own;
    assert!(samples * (own + heap) > MAX_COLLECTED_BYTES);
    let run = model.sweep(&[0.0], &[TAU], samples, &g).unwrap().run();
    assert!(run.states.is_empty());
    let err = run.into_result().expect_err("beyond the budget");
    assert!(err.to_string().contains(&format!("{samples} states of {} bytes", own + heap)), "{err}");
    // A row is smaller than a state: the table is refused at the most samples a sweep takes.
    let most = kinloop::analysis::MAX_SAMPLES + 1;
    assert!(model.sweep(&[0.0], &[TAU], most, &g).unwrap().table().is_err());
    assert_eq!(model.sweep(&[0.0], &[TAU], samples, &g).unwrap().take(3).filter(Result::is_ok).count(), 3);
    assert_eq!(model.sweep(&[0.0], &[TAU], 37, &g).unwrap().table().unwrap().rows.len(), 37);
}

/// A run-time model whose unknowns are read by equations of two units (a loop's projections,
/// in lengths, and a gear's equation between angles) is as far from a singular position in every
/// unit of length, as the compiled mechanism is (`tests/kinematics/mixed_units_extreme_scales.rs`,
/// which says why it was not): the same smallest pivot ratio to the rounding of its entries, and
/// a sweep near size 1's that completes at every size. A four-bar whose rocker drives a gear
/// (the gear's row beyond the loop's block), a geared five-bar (the loop and the gear one block,
/// dense), and a ring of eight four-bars closed through a gear (one sparse block).
#[test]
fn mechanisms_with_gears_sweep_alike_in_every_unit() {
    let rocker = "pub struct GearedRocker {
        params a = 1, b = 3.5, c = 3, d = 4;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, th3 = 3.0;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        eq g: th3 == 2 * gamma;
    }";
    let five_bar = "pub struct GearedFiveBar {
        params a = 1, b = 2.5, c = 2.2, d = 1.5, e = 1.2;
        input th1;
        unknowns phi2 = 1.0, th2 = 0.8, phi3 = 1.6;
        loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3;
        eq gear: phi3 == 2 * th2;
    }";
    let loops: String = (1..8).map(|k| format!("loop l{k}: a @ v{} + b @ u{k} == (d, 0) + c @ v{k};", k - 1)).collect();
    let unknowns: String = (0..8).map(|k| format!("u{k} = 0.6, v{k} = 1.9, ")).collect();
    let ring = format!(
        "pub struct GearedRing {{ params a = 1, b = 3, c = 2.5, d = 3.2; input phi; unknowns {unknowns} w = 0.95;
            loop l0: a @ (0.5 * (phi + w)) + b @ u0 == (d, 0) + c @ v0; {loops} eq gear: w == 0.5 * v7; }}"
    );
    let mut ring_guess = [0.6, 1.9].repeat(8);
    ring_guess.push(0.95);
    // Each declaration, its lengths at size 1 and its guess.
    let cases = [
        (rocker, vec![("a", 1.0), ("b", 3.5), ("c", 3.0), ("d", 4.0)], vec![0.5, 1.5, 3.0]),
        (five_bar, vec![("a", 1.0), ("b", 2.5), ("c", 2.2), ("d", 1.5), ("e", 1.2)], vec![1.0, 0.8, 1.6]),
        (&ring, vec![("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)], ring_guess),
    ];
    let cfg = kinloop::NewtonConfig::default();
    for (text, lengths, guess) in cases {
        let pivot_at_one = read(text).kinematics(&[0.5], &guess, &cfg).expect("assembles").health.min_pivot;
        assert!(pivot_at_one > 0.01, "{pivot_at_one:e}");
        for k in [1e-9, 1e-6, 1e-3, 1e3, 1e6, 1e9] {
            let mut model = read(text);
            let scaled: Vec<(&str, f64)> = lengths.iter().map(|&(p, v)| (p, v * k)).collect();
            set(&mut model, &scaled);
            let pivot = model.kinematics(&[0.5], &guess, &cfg).expect("assembles").health.min_pivot;
            assert!((pivot - pivot_at_one).abs() <= 1e-13 * pivot_at_one, "{k:e}: {pivot:e}\n{text}");
            let mut sweep = model.sweep(&[0.5], &[0.6], 11, &guess).unwrap();
            while let Some(item) = sweep.next_ref() {
                assert!(item.is_ok(), "{k:e}: {:?}\n{text}", item.err());
            }
        }
    }
}
