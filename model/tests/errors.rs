//! A run-time model's failed steps against the compiled mechanism's of the same declaration:
//! the same variant with the same fields (the model's names owned, the compiled ones constants,
//! equal as text), so the same message character for character. Each case also names the value
//! the test expects, written out here: the output that divides by zero, the angle guessed too
//! many turns out, the non-finite parameter, the equation whose linear block is not finite.

mod common;

use common::{Libm, read, set};
use kinloop::dims::Heap;
use kinloop::{Error, Kernel, Kin, Mechanism, NewtonConfig, Quantity, Sweep, SweepConfig};
use kinloop_codegen::graph::dag::NodeId;
use kinloop_codegen::plan::Plan;
use kinloop_codegen::plan::finite::{BUDGET, READ_BUDGET, Value, kept, state_terms};
use kinloop_fixtures as fx;
use kinloop_model::{Model, StepError};
use std::borrow::Cow;

/// The same four-bar with one output of its own (`$output`): the cases below differ in that
/// output alone, the value whose failure each names.
macro_rules! four_bar_with {
    ($(#[$doc:meta])* $text:ident => $name:ident { $($output:tt)* }) => {
        kinloop_fixtures::declare! {
            $(#[$doc])*
            $text => {
                pub struct $name {
                    params a = 1, b = 3, c = 2.5, d = 3.2;
                    input phi;
                    unknowns psi = 0.6, theta = 1.9;
                    loop abcd: a @ phi + b @ psi == (d, 0) + c @ theta;
                    $($output)*
                }
            }
        }
    };
}

four_bar_with! {
    /// A four-bar with an output that divides by the input: finite positions and analogs
    /// everywhere, a non-finite output at 0.
    RECIPROCAL_TEXT => Reciprocal { output k = c / phi; }
}

four_bar_with! {
    /// The four-bar with the square root of its input as an output: NaN below 0, and at 0 a
    /// finite output whose analog `1 / (2 sqrt(phi))` is not.
    ROOT_TEXT => Root { output root = sqrt(phi); }
}

four_bar_with! {
    /// The four-bar with an output beyond the range of `f64` at every input: `exp(800 + phi)`.
    GROWTH_TEXT => Growth { output growth = exp(800 + phi); }
}

/// The compiled step's error and the model's (through its `Kernel`, as every algorithm of the
/// runtime calls it) at `x` from `guess`: equal, and returned.
fn same_error<M, const N: usize, const NI: usize, const NO: usize>(
    compiled: &M,
    model: &mut Model,
    x: [f64; NI],
    guess: [f64; N],
) -> Error
where
    M: Mechanism<N, NI, NO>,
{
    let cfg = NewtonConfig::default();
    let c_err = compiled.kinematics_flat(&x, &guess, &cfg).unwrap_err();
    let k = model.kernel(SweepConfig::default()).unwrap();
    let r_err = k.kinematics(&Heap(x.into()), &Heap(guess.into()), &cfg).unwrap_err();
    same(&c_err, &r_err);
    r_err
}

/// Equal errors: every field (as `Debug` writes them, so that NaN values compare) and the
/// message.
fn same(c_err: &Error, r_err: &Error) {
    assert_eq!(format!("{c_err:?}"), format!("{r_err:?}"));
    assert_eq!(c_err.to_string(), r_err.to_string());
}

/// The name an error carries, owned (the model's) or not.
fn name_of(e: &Error) -> &Cow<'static, str> {
    match e {
        Error::Domain { name, .. } | Error::TooManyTurns { name, .. } | Error::NonFinite { name, .. } => name,
        other => panic!("unexpected variant: {other:?}"),
    }
}

#[test]
fn a_non_finite_output_is_named_as_the_compiled_one_names_it() {
    let compiled = Reciprocal::default();
    let mut model = read(RECIPROCAL_TEXT);
    let e = same_error(&compiled, &mut model, [0.0], compiled.guess_flat(&[0.0]));
    assert!(matches!(e, Error::Domain { what: kinloop::Computed::Output, .. }), "{e:?}");
    assert_eq!(name_of(&e), "k");
    assert!(matches!(name_of(&e), Cow::Owned(_)));
    eprintln!("{e}");

    let compiled = Root::default();
    let mut model = read(ROOT_TEXT);
    // At 0 the output is 0, its analog is not: the first bad value in the compiled order
    // (positions, their analogs, outputs, their analogs).
    let e = same_error(&compiled, &mut model, [0.0], compiled.guess_flat(&[0.0]));
    assert!(matches!(e, Error::Domain { what: kinloop::Computed::OutputVelocityAnalog, .. }), "{e:?}");
    assert_eq!(name_of(&e), "root");
    let e = same_error(&compiled, &mut model, [-0.5], compiled.guess_flat(&[-0.5]));
    assert!(matches!(e, Error::Domain { what: kinloop::Computed::Output, .. }), "{e:?}");
    assert_eq!(name_of(&e), "root");
}

/// An output that overflows (finite operands, an infinite result) is reported as the domain
/// errors are, and the message names the range of `f64` beside the domain.
#[test]
fn an_output_beyond_the_range_of_f64_is_named_with_its_cause() {
    let compiled = Growth::default();
    let mut model = read(GROWTH_TEXT);
    let e = same_error(&compiled, &mut model, [0.0], compiled.guess_flat(&[0.0]));
    assert!(matches!(e, Error::Domain { what: kinloop::Computed::Output, .. }), "{e:?}");
    assert_eq!(name_of(&e), "growth");
    let message = e.to_string();
    assert!(message.contains("the range of f64") && message.contains("exp of an argument above 709.78"), "{message}");
}

/// Whether the finiteness sum of `text`'s compiled kernel and of its run-time model (within
/// either budget) leaves out the value `node` picks among the plan's nodes.
fn left_out(text: &str, node: impl Fn(&Plan) -> NodeId) -> bool {
    let planned = kinloop_codegen::plan_declaration(text.parse().expect("tokens")).expect("plans");
    let plan = &planned.plan;
    let terms = state_terms(plan);
    let at = terms.iter().position(|(_, v)| *v == Value::Node(node(plan))).expect("a value of the state");
    let (compiled, read) = (kept(plan, &terms, BUDGET), kept(plan, &terms, READ_BUDGET));
    assert_eq!(compiled, read, "a small declaration is analysed within both budgets");
    !compiled[at]
}

/// A value the finiteness sum leaves out (its finiteness follows from a value kept) that is
/// not finite still fails the step: the square root's analog `1 / (2 sqrt(phi))`, infinite at
/// 0, is an operand of its second analog; the reciprocal `c / phi`, infinite at 0, of its
/// analogs. The model's step reports a non-finite state, and the error is the compiled one.
#[test]
fn a_value_left_out_of_the_finiteness_sum_still_fails_the_step() {
    let cfg = NewtonConfig::default();
    assert!(left_out(ROOT_TEXT, |p| p.out_d1[0][0]));
    let compiled = Root::default();
    let mut model = read(ROOT_TEXT);
    let guess = compiled.guess_flat(&[0.0]);
    assert!(matches!(model.kinematics(&[0.0], &guess, &cfg), Err(StepError::NonFinite)));
    let e = same_error(&compiled, &mut model, [0.0], guess);
    assert!(matches!(e, Error::Domain { what: kinloop::Computed::OutputVelocityAnalog, .. }), "{e:?}");

    assert!(left_out(RECIPROCAL_TEXT, |p| p.outputs[0]));
    let compiled = Reciprocal::default();
    let mut model = read(RECIPROCAL_TEXT);
    let guess = compiled.guess_flat(&[0.0]);
    assert!(matches!(model.kinematics(&[0.0], &guess, &cfg), Err(StepError::NonFinite)));
    let e = same_error(&compiled, &mut model, [0.0], guess);
    assert!(matches!(e, Error::Domain { what: kinloop::Computed::Output, .. }), "{e:?}");
}

/// A sweep through the input where an output divides by zero stops there with the same error
/// (the compiled sweep taking libm's sines, as the model's steps do).
#[test]
fn a_sweep_through_a_division_by_zero_fails_alike() {
    let compiled = Libm(Reciprocal::default());
    let mut model = read(RECIPROCAL_TEXT);
    let (from, to) = ([-1.0], [1.0]);
    let guess = compiled.guess_flat(&from);
    let c_sweep = Sweep::<_, Kin<2, 1, 1>, 2, 1, 1>::new(&compiled, from, to, 5, guess).unwrap();
    let c_err = c_sweep.filter_map(Result::err).next().expect("the compiled sweep fails");
    let r_err = model.sweep(&from, &to, 5, &guess).unwrap().filter_map(Result::err).next().expect("fails");
    same(&c_err, &r_err);
    let Error::Domain { what, name, at } = &r_err else { panic!("{r_err:?}") };
    assert_eq!(
        (*what, name.as_ref(), &at.inputs[..]),
        (kinloop::Computed::Output, "k", &[(Cow::Borrowed("phi"), 0.0)][..])
    );
}

/// An angle guessed a billion radians out: the closed form's root on the guess's turn is too
/// coarse (the four-bar's dyad), or Newton stalls at the angle's rounding (the class IV group).
/// Both name the block's angle with the largest guess.
#[test]
fn an_angle_too_many_turns_out_is_named() {
    let compiled = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let e = same_error(&compiled, &mut model, [0.3], [0.5, 1.5e9]);
    assert!(matches!(e, Error::TooManyTurns { .. }), "{e:?}");
    assert_eq!(name_of(&e), "gamma");

    let compiled = fx::ClassFour::default();
    let mut model = read(fx::CLASS_FOUR_TEXT);
    let mut guess = compiled.guess_flat(&[0.0]);
    let angle = (0..guess.len()).find(|&u| fx::ClassFour::UNKNOWN_KINDS[u] == kinloop::QuantityKind::Angle).unwrap();
    guess[angle] += 1e9;
    let e = same_error(&compiled, &mut model, [0.0], guess);
    assert!(matches!(e, Error::TooManyTurns { .. }), "{e:?}");
    assert_eq!(name_of(&e), fx::ClassFour::UNKNOWNS[angle]);
    eprintln!("{e}");
}

/// The slotted lever (size 3) from an angle's guess too many turns out and a length's far beyond
/// the mechanism's size (`1e150`), or two guesses whose sum overflows (`1e308` each): the
/// magnitudes at the guess are beyond the closed forms' sizes, and the solve again by Newton
/// over the whole system returned the far angle with a length of `0` or `1e168`, with no error.
/// The angle is named, as it is from a length's guess of the mechanism's size.
#[test]
fn an_angle_too_many_turns_out_is_named_beside_a_length_guessed_far_out() {
    let compiled = fx::SlottedLever::default();
    let mut model = read(fx::SLOTTED_LEVER_TEXT);
    for guess in [[3.0, 1e7], [1e150, 1e7], [1e308, 1e308]] {
        let e = same_error(&compiled, &mut model, [0.3], guess);
        assert!(matches!(e, Error::TooManyTurns { .. }), "{guess:?}: {e:?}");
        assert_eq!(name_of(&e), "theta");
    }
}

/// The slotted lever at its singular position (`r = d = 1`, `phi = -pi/2`: the crank pin on the
/// rocker's pivot) from a length's guess of `1e150`: the solve again by Newton over the whole
/// system, its residual judged in the magnitudes at that guess, returned a length of `1e118`
/// with no error. Singular, as from a guess of the mechanism's size.
#[test]
fn a_length_guessed_far_out_at_a_singular_position_is_singular() {
    let compiled = fx::SlottedLever { r: 1.0, d: 1.0, l: 4.0 };
    let mut model = read(fx::SLOTTED_LEVER_TEXT);
    set(&mut model, &[("r", 1.0), ("d", 1.0), ("l", 4.0)]);
    for guess in [[1.0, 0.3], [1e150, 0.3], [1e200, 0.3]] {
        let e = same_error(&compiled, &mut model, [-std::f64::consts::FRAC_PI_2], guess);
        assert!(matches!(e, Error::Singular { .. }), "{guess:?}: {e:?}");
    }
}

/// A sweep whose angle has turned a billion radians (its guess carried over that many turns)
/// fails at its first step, alike.
#[test]
fn a_sweep_turned_too_many_times_fails_alike() {
    let compiled = Libm(fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 });
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let guess = [0.5 + 2e8 * std::f64::consts::TAU, 1.5];
    let c_err = Sweep::<_, Kin<2, 1, 2>, 2, 1, 2>::new(&compiled, [0.0], [1.0], 5, guess)
        .map(|mut s| s.next().expect("a sample").unwrap_err())
        .unwrap_or_else(|e| e);
    let r_err = match model.sweep(&[0.0], &[1.0], 5, &guess) {
        Ok(mut s) => s.next().expect("a sample").unwrap_err(),
        Err(e) => e,
    };
    same(&c_err, &r_err);
    assert_eq!(name_of(&r_err), "beta");
}

/// A non-finite parameter explains a failure before the failure itself, as in the compiled
/// step.
#[test]
fn a_non_finite_parameter_is_named_first() {
    let compiled = fx::FourBar { a: 1.0, b: f64::NAN, c: 2.5, d: 3.2 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", f64::NAN), ("c", 2.5), ("d", 3.2)]);
    let e = same_error(&compiled, &mut model, [0.3], [0.5, 1.5]);
    assert!(matches!(e, Error::NonFinite { what: Quantity::Parameter, .. }), "{e:?}");
    assert_eq!(name_of(&e), "b");
}

/// `Model::solve` with a parameter or an input not finite names it, as the compiled `solve`
/// does (`Error::NonFinite`), parameters first: its error was the first block's, failing on the
/// value ("block 0: a value of the block's row 0 left its functions' domain", or "the terms of
/// the block's row 0 are too large for f64" for an infinite length), which names neither the
/// value nor what to mend. `Model::explain` of it is the compiled error.
#[test]
fn solve_names_a_parameter_or_input_not_finite_as_the_compiled_solve() {
    use kinloop::Mechanism as _;
    for (l, phi, what, name) in [
        (f64::NAN, 0.3, "parameter", "l"),
        (f64::INFINITY, f64::NAN, "parameter", "l"),
        (3.0, f64::NEG_INFINITY, "input", "phi"),
        (3.0, f64::NAN, "input", "phi"),
    ] {
        let compiled = fx::SliderCrank { r: 1.0, l, e: 0.4 };
        let mut model = read(fx::SLIDER_CRANK_TEXT);
        set(&mut model, &[("r", 1.0), ("l", l), ("e", 0.4)]);
        let step = model.solve(&[phi]).map(|_| ()).unwrap_err();
        let value = if what == "parameter" { l } else { phi };
        let StepError::NotFinite { what: w, name: n, value: v } = &step else { panic!("{l} {phi}: {step:?}") };
        assert_eq!((*w, n.as_str(), v.to_bits()), (what, name, value.to_bits()), "{step}");
        assert_eq!(step.to_string(), format!("{what} `{name}` is not finite ({value}): give it a finite value"));
        let solved = compiled.solve(phi).map(|_| ()).unwrap_err();
        let guess = compiled.guess_flat(&[phi]);
        let explained = model.explain(&[phi], &guess, &NewtonConfig::default(), step);
        same(&solved, &explained);
        assert!(matches!(explained, Error::NonFinite { .. }), "{explained:?}");
    }
}

/// A position given to `kinematics_at` with an unknown not finite: the model's own record
/// names the unknown (it said "singular position: pivot ratio 0"), `explain` calls it the
/// given position (it said "initial guess"), and the model's kernel and the compiled one give
/// the same error naming it.
#[test]
fn a_given_position_not_finite_is_named_alike() {
    let compiled = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let cfg = NewtonConfig::default();
    for (q, unknown) in [([f64::NAN, 1.5], "beta"), ([0.5, f64::INFINITY], "gamma")] {
        let e = model.kinematics_at(&[0.5], &q, &cfg).map(drop).unwrap_err();
        assert!(matches!(&e, StepError::NonFinitePosition { unknown: u, .. } if u == unknown), "{e:?}");
        assert!(e.to_string().starts_with(&format!("the given position of `{unknown}` is not finite")), "{e}");
        let explained = model.explain(&[0.5], &q, &cfg, e);
        assert!(matches!(&explained, Error::NonFinite { what: Quantity::Position, .. }), "{explained:?}");
        let c_err = kinloop_runtime::Compiled(&compiled).kinematics_at(&[0.5], &q, &cfg).unwrap_err();
        same(&c_err, &explained);
        let k = model.kernel(SweepConfig::default()).unwrap();
        same(&c_err, &k.kinematics_at(&Heap([0.5].into()), &Heap(q.into()), &cfg).unwrap_err());
        assert_eq!(name_of(&c_err), unknown);
    }
}

/// `Model::kinematics_at` with a parameter or an input not finite names it, as the compiled
/// `kinematics_at_flat` does, before the given position's unknowns: its error was "a value of
/// the state is not finite", the state computed from the value.
#[test]
fn kinematics_at_names_a_parameter_or_input_not_finite() {
    let cfg = NewtonConfig::default();
    let q = [0.5, 1.5];
    for (b, phi, what, name) in
        [(f64::NAN, 0.5, "parameter", "b"), (3.0, f64::NAN, "input", "phi"), (3.0, f64::INFINITY, "input", "phi")]
    {
        let compiled = fx::FourBar { a: 1.0, b, c: 2.5, d: 3.2 };
        let mut model = read(fx::FOUR_BAR_TEXT);
        set(&mut model, &[("a", 1.0), ("b", b), ("c", 2.5), ("d", 3.2)]);
        let e = model.kinematics_at(&[phi], &q, &cfg).map(drop).unwrap_err();
        let value = if what == "parameter" { b } else { phi };
        let StepError::NotFinite { what: w, name: n, value: v } = &e else { panic!("{b} {phi}: {e:?}") };
        assert_eq!((*w, n.as_str(), v.to_bits()), (what, name, value.to_bits()), "{e}");
        // Before the position: a value not finite there too is not the one named.
        let both = model.kinematics_at(&[phi], &[f64::NAN, 1.5], &cfg).map(drop).unwrap_err();
        assert_eq!(format!("{both:?}"), format!("{e:?}"));
        let c_err = kinloop_runtime::Compiled(&compiled).kinematics_at(&[phi], &q, &cfg).unwrap_err();
        same(&c_err, &model.explain(&[phi], &q, &cfg, e));
        let k = model.kernel(SweepConfig::default()).unwrap();
        same(&c_err, &k.kinematics_at(&Heap([phi].into()), &Heap(q.into()), &cfg).unwrap_err());
    }
}

/// `Model::kinematics_at` with a configuration out of range names its field, as the compiled
/// `kinematics_at_flat` does: the analogs read `singular_tol`, and a NaN one made a regular
/// position "singular" (a negative one was taken).
#[test]
fn kinematics_at_names_a_configuration_out_of_range() {
    let compiled = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let q = compiled.kinematics_flat(&[0.5], &[0.5, 1.5], &NewtonConfig::default()).unwrap().q;
    for tol in [f64::NAN, -1.0] {
        let cfg = NewtonConfig::default().with_singular_tol(tol);
        let e = model.kinematics_at(&[0.5], &q, &cfg).map(drop).unwrap_err();
        assert!(matches!(e, StepError::InvalidConfig("singular_tol")), "{tol}: {e:?}");
        let c_err = kinloop_runtime::Compiled(&compiled).kinematics_at(&[0.5], &q, &cfg).unwrap_err();
        let k = model.kernel(SweepConfig::default()).unwrap();
        let r_err = k.kinematics_at(&Heap([0.5].into()), &Heap(q.into()), &cfg).unwrap_err();
        for e in [c_err, r_err] {
            let Error::InvalidArgument(msg) = &e else { panic!("{tol}: {e:?}") };
            assert!(msg.contains("NewtonConfig::singular_tol is out of its valid range, [0, 1)"), "{msg}");
        }
    }
}

/// The evaluations at a given position write into the caller's buffer only when it has one
/// place per value: a short one was filled in part, a long one kept what its extra places held,
/// and both returned `Ok`.
#[test]
fn an_evaluation_into_a_buffer_of_the_wrong_length_is_refused() {
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let (x, q) = ([0.5], [0.5, 1.5]);
    for len in [1, 3] {
        let mut out = vec![7.0; len];
        let e = model.residual(&x, &q, &mut out).unwrap_err();
        assert_eq!(e, StepError::Size { what: "residual places", expected: 2, given: len });
        assert_eq!(e.to_string(), format!("{len} residual places given, 2 expected"));
        assert!(model.outputs_at(&x, &q, &mut out).is_err());
        assert_eq!(out, vec![7.0; len], "nothing written");
    }
    let (mut residuals, mut outputs) = ([0.0; 2], [0.0; 2]);
    model.residual(&x, &q, &mut residuals).unwrap();
    model.outputs_at(&x, &q, &mut outputs).unwrap();
    let compiled = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    assert_eq!(residuals, compiled.residual_flat(&x, &q));
    assert_eq!(outputs, compiled.outputs_flat(&x, &q));
}

kinloop_fixtures::declare! {
    /// A slider solved by one linear equation whose coefficient is `sqrt(phi)`: NaN below 0.
    LINEAR_TEXT => {
        pub struct Linear {
            params a = 1;
            input phi;
            unknowns s = 1;
            eq e: sqrt(phi) * s == a;
        }
    }
}

/// A linear block whose matrix is not finite (an input outside a coefficient's domain) is an
/// equation outside its domain, named, not a singular position: the compiled step's diagnosis
/// of a failed factorisation.
#[test]
fn a_non_finite_linear_block_names_its_equation() {
    let compiled = Linear::default();
    let mut model = read(LINEAR_TEXT);
    let e = same_error(&compiled, &mut model, [-1.0], [1.0]);
    assert!(matches!(e, Error::Domain { what: kinloop::Computed::Equation, .. }), "{e:?}");
    assert_eq!(name_of(&e), "e");
    // At 0 the coefficient is 0: singular.
    let e = same_error(&compiled, &mut model, [0.0], [1.0]);
    assert!(matches!(e, Error::Singular { .. }), "{e:?}");
}

/// A failed step of the model's own API (`Model::kinematics`, `solve`) reads as a sentence by
/// its block's row, and `Model::explain` gives the compiled mechanism's error for it, naming
/// the equation: a non-Grashof four-bar at an input it cannot reach. It printed `block 0:
/// Block(NoAssembly { row: 0, .. })`.
#[test]
fn a_step_error_reads_as_a_sentence_and_explains_as_the_compiled_error() {
    let compiled = fx::FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 3.0), ("b", 2.0), ("c", 2.5), ("d", 4.0)]);
    let (x, guess) = ([3.0], [0.5, 1.5]);
    let e = model.kinematics(&x, &guess, &NewtonConfig::default()).map(|_| ()).unwrap_err();
    let text = e.to_string();
    assert!(!text.contains('{') && !text.contains("Block("), "{text}");
    assert!(text.starts_with("block 0: ") && text.contains("`Model::explain`"), "{text}");
    let explained = model.explain(&x, &guess, &NewtonConfig::default(), e);
    let c_err = compiled.kinematics_flat(&x, &guess, &NewtonConfig::default()).unwrap_err();
    same(&c_err, &explained);
    assert!(explained.to_string().contains("cannot be assembled in `FourBar` at phi = 3"), "{explained}");
    // Values of the wrong count: the step's own error, not a panic.
    let e = model.kinematics(&[3.0, 1.0], &guess, &NewtonConfig::default()).map(|_| ()).unwrap_err();
    assert!(matches!(model.explain(&[3.0, 1.0], &guess, &NewtonConfig::default(), e), Error::InvalidArgument(_)));
}

/// A four-bar whose crank is too long to close the loop at `phi = 3` (frame 3, crank 2, coupler
/// 1.5, rocker 2, times `k`: the crank's end 4.98 from the rocker's pivot, beyond 3.5) fails as
/// at size 1 at every size: no assembly, in its loop's block. Beyond the closed forms' sizes
/// (`1e±144`) both the model and the compiled step solve the position again by Newton over the
/// whole system, whose failure is the error; they reported the closed form's instead,
/// distorted by its squares out of range (singular at `1e-300` and `1e-200`, an equation not
/// finite at `1e200` and `1e300`). The model's own record and, through its kernels, the
/// compiled mechanism's error field for field, for a step and a sensitivity solve.
#[test]
fn a_four_bar_whose_crank_cannot_close_fails_alike_at_every_scale() {
    use kinloop::dims::Dims;
    use kinloop::{SensKernel, Sensitivities};
    use kinloop_model::StepFailure;
    use kinloop_runtime::generated::BlockFailure;
    let cfg = NewtonConfig::default();
    let (x, guess) = ([3.0], [0.5, 1.5]);
    for k in [1.0, 1e-300, 1e-200, 1e-160, 1e200, 1e300] {
        let [a, b, c, d] = [2.0 * k, 1.5 * k, 2.0 * k, 3.0 * k];
        let compiled = fx::FourBarSens { a, b, c, d };
        let mut model = read(fx::FOUR_BAR_SENS_TEXT);
        set(&mut model, &[("a", a), ("b", b), ("c", c), ("d", d)]);
        let no_assembly = |e: &StepError| {
            matches!(e, StepError::Block { block: 0, failure: StepFailure::Block(BlockFailure::NoAssembly { .. }) })
        };
        let e = model.kinematics(&x, &guess, &cfg).map(drop).unwrap_err();
        assert!(no_assembly(&e), "size {k:e}: {e:?}");
        let explained = model.explain(&x, &guess, &cfg, e);
        assert!(matches!(explained, Error::NoAssembly { .. }), "size {k:e}: {explained:?}");
        let e = model.sensitivities(&x, &guess, &cfg).map(drop).unwrap_err();
        assert!(no_assembly(&e), "size {k:e}: {e:?}");
        let e = same_error(&compiled, &mut model, x, guess);
        same(&e, &explained);
        let c_err = compiled.sensitivities_flat(&x, &guess, &cfg).unwrap_err();
        let kernel = model.kernel(SweepConfig::default()).unwrap();
        let (mut kin, mut sens) = (kernel.dims().kin(), kernel.sens());
        let r_err = kernel.sensitivities_into(&Heap(x.into()), &Heap(guess.into()), &cfg, &mut kin, &mut sens);
        same(&c_err, &r_err.unwrap_err());
        same(&c_err, &e);
    }
}

/// Beyond the closed forms' sizes, where the rescue solves the position but a value there is
/// not finite, that value is the error, as at size 1: the four-bar whose output divides by its
/// input, at 0, names its output `k`, compiled and at run time alike. The closed form's error
/// stood instead (a singular position at `1e-300`, its equation not finite at `1e200`).
#[test]
fn a_non_finite_output_at_a_rescued_position_is_named_at_every_scale() {
    for k in [1.0, 1e-300, 1e-200, 1e200, 1e300] {
        let compiled = Reciprocal { a: k, b: 3.0 * k, c: 2.5 * k, d: 3.2 * k };
        let mut model = read(RECIPROCAL_TEXT);
        set(&mut model, &[("a", k), ("b", 3.0 * k), ("c", 2.5 * k), ("d", 3.2 * k)]);
        let e = same_error(&compiled, &mut model, [0.0], compiled.guess_flat(&[0.0]));
        assert!(matches!(e, Error::Domain { what: kinloop::Computed::Output, .. }), "size {k:e}: {e:?}");
        assert_eq!(name_of(&e), "k", "size {k:e}");
        assert_eq!(e.location().map(|at| at.inputs.clone()), Some(vec![("phi".into(), 0.0)]), "size {k:e}");
    }
}

/// The positions alone (`Model::positions`, the compiled `position_flat`) of the four-bar whose
/// crank cannot close its loop at `phi = 3`, at every size: no assembly in its loop's block
/// there, explained as the compiled error field for field, and at `phi = 0.3`, where it
/// assembles, the compiled positions to the bit. Beyond the closed forms' sizes both solve the
/// positions again by Newton over the whole system; neither did (singular at `1e-300` and
/// `1e-200`, an equation not finite at `1e200` and `1e300`, at both inputs).
#[test]
fn positions_alone_of_a_four_bar_whose_crank_cannot_close_fail_alike_at_every_scale() {
    use kinloop_model::StepFailure;
    use kinloop_runtime::generated::BlockFailure;
    let cfg = NewtonConfig::default();
    for k in [1.0, 1e-300, 1e-200, 1e200, 1e300] {
        let [a, b, c, d] = [2.0 * k, 1.5 * k, 2.0 * k, 3.0 * k];
        let compiled = fx::FourBarSens { a, b, c, d };
        let mut model = read(fx::FOUR_BAR_SENS_TEXT);
        set(&mut model, &[("a", a), ("b", b), ("c", c), ("d", d)]);
        let (x, guess) = ([3.0], [0.5, 1.5]);
        let e = model.positions(&x, &guess, &cfg).map(drop).unwrap_err();
        let no_assembly =
            matches!(e, StepError::Block { block: 0, failure: StepFailure::Block(BlockFailure::NoAssembly { .. }) });
        assert!(no_assembly, "size {k:e}: {e:?}");
        let explained = model.explain(&x, &guess, &cfg, e);
        same(&compiled.position_flat(&x, &guess, &cfg).unwrap_err(), &explained);
        let x = [0.3];
        let q = model.positions(&x, &guess, &cfg).unwrap_or_else(|e| panic!("size {k:e}: {e:?}")).to_vec();
        let (want, _) = compiled.position_flat(&x, &guess, &cfg).unwrap();
        assert_eq!(q.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), want.map(f64::to_bits), "size {k:e}");
    }
}

/// The sizes at which a singular position is tested: size 1, inside the closed forms' sizes near
/// their ends (`1e±140`), and beyond them (`1e±150` to `1e±300`, solved again by Newton over the
/// whole system).
const SINGULAR_SIZES: [f64; 9] = [1.0, 1e-140, 1e140, 1e-150, 1e150, 1e-160, 1e160, 1e-300, 1e300];

/// The positions alone at `x` from `guess` of a mechanism singular there: a singular failure of
/// its only block from the model and from the compiled mechanism, at the same location. (Their
/// pivot ratios may differ in the last digits at ordinary sizes: the slotted lever's closed form
/// takes the crank's cosine at `-pi/2`, a rounding residue of `6e-17`, from each one's own
/// trigonometry.)
fn singular_alike<M: Mechanism<2, 1, NO>, const NO: usize>(
    compiled: &M,
    model: &mut Model,
    x: [f64; 1],
    guess: [f64; 2],
    what: &str,
) {
    use kinloop_model::StepFailure;
    use kinloop_runtime::generated::BlockFailure;
    let cfg = NewtonConfig::default();
    let e = model.positions(&x, &guess, &cfg).map(|q| q.to_vec()).unwrap_err();
    let singular =
        matches!(e, StepError::Block { block: 0, failure: StepFailure::Block(BlockFailure::Singular { .. }) });
    assert!(singular, "{what}: {e:?}");
    let explained = model.explain(&x, &guess, &cfg, e);
    let c_err = compiled.position_flat(&x, &guess, &cfg).map(|(q, _)| q).unwrap_err();
    assert!(matches!(c_err, Error::Singular { .. }), "{what}: {c_err:?}");
    assert!(matches!(explained, Error::Singular { .. }), "{what}: {explained:?}");
    assert_eq!(format!("{:?}", c_err.location()), format!("{:?}", explained.location()), "{what}");
}

/// The positions alone of a four-bar whose dyad's centres are `1e-13` of its links apart at
/// `phi = 0` (`a = 1`, `b = c = 2`, `d = 1 + 1e-13`), and of the slotted lever whose lever is
/// `1e-13` of its loop (`r = 1`, `d = 1 + 1e-13` at `phi = -pi/2`): singular at every size,
/// compiled and at run time alike, as the closed forms find them at size 1 (a pivot ratio of
/// `5e-14`). Beyond the closed forms' sizes the rescue took Newton's singular failure there for a
/// limit position and returned a point of the family of near-roots about it, with no error and a
/// different one at each size: the four-bar at `beta = gamma = 1.0000000004` (`1e-150`) to
/// `1.0000000004083` (`1e160`), its loop open by `7e-14` of a link, where its root is
/// `(pi/2 - 2.5e-14, pi/2 + 2.5e-14)` (`cos beta = (d - a) / 4`, `gamma = pi - beta`, checked
/// with mpmath at 50 digits), `0.57` rad off; the lever at `theta` `1.2539` to `1.2552` where
/// its root is `1.5702` (the crank pin's direction from the pivot).
#[test]
fn positions_alone_at_a_singular_position_are_singular_at_every_scale() {
    for k in SINGULAR_SIZES {
        let [a, b, c, d] = [1.0, 2.0, 2.0, 1.0 + 1e-13].map(|v| v * k);
        let compiled = fx::FourBar { a, b, c, d };
        let mut model = read(fx::FOUR_BAR_TEXT);
        set(&mut model, &[("a", a), ("b", b), ("c", c), ("d", d)]);
        singular_alike(&compiled, &mut model, [0.0], [0.5, 1.5], &format!("four-bar at size {k:e}"));

        let [r, d, l] = [1.0, 1.0 + 1e-13, 4.0].map(|v| v * k);
        let compiled = fx::SlottedLever { r, d, l };
        let mut model = read(fx::SLOTTED_LEVER_TEXT);
        set(&mut model, &[("r", r), ("d", d), ("l", l)]);
        let phi = -std::f64::consts::FRAC_PI_2;
        singular_alike(&compiled, &mut model, [phi], [k, 0.3], &format!("slotted lever at size {k:e}"));
    }
}

kinloop_fixtures::declare! {
    /// A rocker driven by a cylinder whose length is the input: a dyad between two fixed pivots
    /// on the x axis, its second coefficient folded to zero.
    CYLINDER_TEXT => {
        pub struct Cylinder {
            params c = 1, d = 2;
            input s;
            unknowns th = 1.5, ph = 2.0;
            loop l: c @ th == (d, 0) + s @ ph;
        }
    }
}

/// A dyad with a coefficient folded that cannot be assembled reports its links' gap over its
/// size, compiled and at run time alike, at every size: the cylinder of rocker 1 on pivots 2
/// apart, stretched to 4, is 1 too long, 1/7 of the dyad (`1 + 2 + 4`). The model reported the
/// gap in its coefficients' units, products of two lengths (3.5 times the size squared), where
/// the compiled mechanism reports it so.
#[test]
fn a_folded_dyad_that_cannot_close_reports_its_gap_alike_at_every_scale() {
    for k in [1.0, 1e-100, 1e100] {
        let compiled = Cylinder { c: k, d: 2.0 * k };
        let mut model = read(CYLINDER_TEXT);
        set(&mut model, &[("c", k), ("d", 2.0 * k)]);
        let e = same_error(&compiled, &mut model, [4.0 * k], [1.5, 2.0]);
        let Error::NoAssembly { residual, .. } = e else { panic!("size {k:e}: {e:?}") };
        assert!((residual - 1.0 / 7.0).abs() <= 1e-15, "size {k:e}: {residual}");
    }
}

/// The class IV group with its angle parameter `alpha_b` set to `value`, compiled and read.
fn class_four_at(alpha_b: f64) -> (fx::ClassFour, Model) {
    let compiled = fx::ClassFour { alpha_b, ..fx::ClassFour::default() };
    let mut model = read(fx::CLASS_FOUR_TEXT);
    set(&mut model, &[("alpha_b", alpha_b)]);
    (compiled, model)
}

/// An angle parameter so large that an angle added to it is rounded beyond the tolerance
/// (`th2 + alpha_b`, where doubles are coarser than `largest_precise_angle` allows; at `1e80`
/// the sum is `alpha_b` itself): the equations are not the declared ones. A point solve at
/// `1e80` returned positions 4.5 length units off the declared loop `aefb` (checked in mpmath,
/// `imprecise_angle_param.py`), and a sweep ground through 100,000 steps a sample before it
/// failed. Both are refused before any solve, compiled and read alike, naming the parameter, its
/// value and the bound.
#[test]
fn an_angle_parameter_beyond_the_precise_angles_is_refused() {
    let bound = NewtonConfig::default().largest_precise_angle();
    // The next double beyond the bound, and far beyond it.
    for alpha_b in [f64::from_bits(bound.to_bits() + 1), 1e80, -1e80] {
        let (compiled, mut model) = class_four_at(alpha_b);
        let solved = compiled.solve(0.5).map(|_| ()).unwrap_err();
        let message = solved.to_string();
        assert!(matches!(solved, Error::InvalidArgument(_)), "{alpha_b:e}: {solved:?}");
        for part in ["`alpha_b`", &format!("{alpha_b:e} rad"), &format!("{bound:e} rad"), "whole turns"] {
            assert!(message.contains(part), "{part}: {message}");
        }
        let guess = compiled.guess(0.0);
        assert_eq!(compiled.kinematics(0.5, &guess).map(|_| ()).unwrap_err(), solved);
        assert_eq!(compiled.position(0.5, &guess).map(|_| ()).unwrap_err(), solved);
        assert_eq!(compiled.sweep(0.0, 1.0, 3, &guess).map(|_| ()).unwrap_err(), solved);
        assert_eq!(compiled.sampled(0.0, 1.0, 3, &guess).map(|_| ()).unwrap_err(), solved);
        assert_eq!(compiled.reachable(0.5, 0.1, &guess, 3).map(|_| ()).unwrap_err(), solved);
        assert_eq!(compiled.assembly_modes(0.5).map(|_| ()).unwrap_err(), solved);
        assert_eq!(compiled.trace_curve(0.0, 1.0, &guess, &Default::default()).map(|_| ()).unwrap_err(), solved);
        // The model's: its step's error, and the same error as the compiled one.
        let step = model.solve(&[0.5]).map(|_| ()).unwrap_err();
        assert!(
            matches!(&step, StepError::ImpreciseParam { param, value, .. } if param == "alpha_b" && *value == alpha_b)
        );
        let explained = model.explain(&[0.5], &<[f64; 4]>::from(guess), &NewtonConfig::default(), step);
        assert_eq!(explained, solved);
        let swept = model.sweep(&[0.0], &[1.0], 3, &<[f64; 4]>::from(guess)).map(|_| ()).unwrap_err();
        assert_eq!(swept, solved);
    }
}

/// An angle parameter just within the bound still solves, compiled and read, to the positions of
/// the declared mechanism with `alpha_b = 4.5e6` exactly, computed in mpmath at 50 digits
/// (`imprecise_angle_param.py`, whose output is below).
#[test]
fn an_angle_parameter_within_the_precise_angles_solves() {
    let alpha_b = 4.5e6;
    assert!(alpha_b <= NewtonConfig::default().largest_precise_angle());
    // mpmath: q at alpha_b = 4.5e6, phi = 0.5, from the declared guess.
    let reference = [1.1172053298592558, 1.932314203432634, -0.2270817766603773, -1.2387915261821983];
    // mpmath: dq/dalpha_b there, the largest magnitude 1.02264. `th2 + alpha_b` is rounded by
    // at most half the spacing of doubles at alpha_b (4.7e-10 rad): the positions are off by at
    // most that times dq/dalpha_b; twice it, for the other roundings of the solve.
    let spacing = f64::from_bits(alpha_b.to_bits() + 1) - alpha_b;
    let tol = 2.0 * 1.03 * spacing / 2.0;
    let (compiled, mut model) = class_four_at(alpha_b);
    let q: [f64; 4] = compiled.solve(0.5).unwrap_or_else(|e| panic!("{e}")).q.into();
    let read_q = model.solve(&[0.5]).unwrap_or_else(|e| panic!("{e}")).q.clone();
    for (u, r) in reference.iter().enumerate() {
        assert!((q[u] - r).abs() <= tol, "compiled {u}: {} against {r}, tol {tol:e}", q[u]);
        assert!((read_q[u] - r).abs() <= tol, "read {u}: {} against {r}, tol {tol:e}", read_q[u]);
    }
}

/// The entries the named solves do not go through, each refused once at its start at
/// `alpha_b = 1e80` (where `th2 + alpha_b == alpha_b`: the equations solved are not the declared
/// ones, `imprecise_angle_param.py`) with the error of `solve`, naming the parameter, its value
/// and the bound: a list of inputs (`sweep_at`), a sweep made directly (`Sweep::new`), each
/// design of a scan (the others go on), the free functions and builders over any compiled
/// mechanism, and the dynamics' simulation and inverse cycle. Before,
/// each ground through the wrong equations (a sweep about 1 s a sample before it failed).
#[test]
fn the_entries_beside_the_named_solves_refuse_an_angle_parameter_beyond_the_precise_angles() {
    use kinloop::analysis::Sampled;
    use kinloop::dynamics::{Body, Coord, DynamicsError, InverseCycle, MassModel, Rotation, Simulation, SpeedLaw};
    use kinloop::metrics::Limits;
    use kinloop::paths;
    let (compiled, _) = class_four_at(1e80);
    let solved = compiled.solve(0.5).map(|_| ()).unwrap_err();
    let guess = compiled.guess(0.0);
    let q: [f64; 4] = guess.into();

    let listed = compiled.sweep_at([0.0, 0.5, 1.0], &guess);
    assert!(listed.states.is_empty(), "{} states", listed.states.len());
    assert_eq!(listed.into_result().map(|_| ()).unwrap_err(), solved);
    let direct = Sweep::<_, Kin<4, 1, 8>, 4, 1, 8>::new(&compiled, [0.0], [1.0], 3, q);
    assert_eq!(direct.map(|_| ()).unwrap_err(), solved);
    // The free functions and builders over any compiled mechanism, beside the named methods.
    let (sampled, path) = (Sampled::sweep(&compiled, 0.0, 1.0, 3, q), Sampled::path(&compiled, [0.0], [1.0], 3, q));
    assert_eq!(sampled.map(|_| ()).unwrap_err(), solved);
    assert_eq!(path.map(|_| ()).unwrap_err(), solved);
    assert_eq!(paths::reach::reachable(&compiled, [0.5], [0.1], q, 3).map(|_| ()).unwrap_err(), solved);
    let traced = paths::trace::trace_curve(&compiled, [0.0], [1.0], q, &Default::default());
    assert_eq!(traced.map(|_| ()).unwrap_err(), solved);
    let modes = paths::modes::assembly_modes(&compiled, &[0.5], 8, &NewtonConfig::default());
    assert_eq!(modes.map(|_| ()).unwrap_err(), solved);
    assert_eq!(Limits::new(&compiled, 0.0, 1.0).run().map(|_| ()).unwrap_err(), solved);

    // A scan of a design within the bound and one beyond it: only the second is refused.
    let designs = [class_four_at(0.62).0, compiled];
    let spec = kinloop::ScanConfig::new([0.0], [1.0], 3);
    let count = |n: usize, _: &fx::ClassFour, _: &Kin<4, 1, 8>| n + 1;
    for results in [kinloop::scan(&designs, &spec, |_| 0, count), kinloop::par_scan(&designs, &spec, |_| 0, count)] {
        assert_eq!(results[0], Ok(3));
        assert_eq!(results[1].clone().unwrap_err(), solved);
    }

    // A body at the point `f` of the loop the parameter turns, turning with `th2`.
    let f = fx::ClassFour::OUTPUTS.iter().position(|o| *o == "f.x").expect("f.x");
    let body = Body {
        name: "dbf".into(),
        mass: 1.0,
        com: [Coord::Output(f), Coord::Output(f + 1)],
        inertia: 0.1,
        rotation: Rotation::Unknown(1),
    };
    let mass = MassModel::new().with_body(body).expect("a body");
    let kinematic = |e: DynamicsError| match e {
        DynamicsError::Kinematics { t: None, source } => source,
        e => panic!("{e}"),
    };
    let run = Simulation::new(&compiled, &mass).start(0.5, 1.0).drive(|_, _, _| 1.0).run(1.0);
    assert_eq!(kinematic(run.map(|_| ()).unwrap_err()), solved);
    let cycle = InverseCycle::new(&compiled, &mass, SpeedLaw::Constant(1.0)).run();
    assert_eq!(kinematic(cycle.map(|_| ()).unwrap_err()), solved);
}

/// Synthesis, compiled and read alike: a design whose angle parameter is beyond the bound of
/// the problem's Newton configuration is a refused candidate, as one that cannot be assembled
/// is (counted in `unassembled`), and the refinement from it and its residuals give the reason
/// (the parameter, its value, the bound). A problem none of whose designs is within the bound
/// (a parameter not varied at 1e80) is refused by the search with that reason. Before, every
/// start at `|alpha_b|` near 1e79 solved other equations than the declared ones and was
/// reported as a design.
#[test]
fn synthesis_refuses_a_design_whose_angle_parameter_is_beyond_the_precise_angles() {
    use kinloop::synthesis::{Design, Search, SynthesisError, Task};
    let phis = [0.0, 0.4, 0.8, 1.2];
    let reference = class_four_at(0.62).0;
    let f = |phi: f64| {
        let s = reference.solve(phi).unwrap_or_else(|e| panic!("{e}"));
        [s.out.f.x, s.out.f.y]
    };
    let task = Task::path("f", phis.map(f)).timed(phis);
    // The problem's Newton configuration: positions to rounding (residual 1e-14).
    let bound = NewtonConfig::default().with_residual_tol(1e-14).largest_precise_angle();
    let named_with = |e: &SynthesisError, value: &str, bound: f64| {
        let SynthesisError::Kinematics(Error::InvalidArgument(message)) = e else { panic!("{e:?}") };
        for part in ["`alpha_b`", &format!("{value} rad"), &format!("{bound:e} rad"), "whole turns"] {
            assert!(message.contains(part), "{part}: {message}");
        }
    };
    let names = |e: &SynthesisError, value: &str| named_with(e, value, bound);
    let search = Search::default().with_starts(0..4);

    // `alpha_b` varied over a box almost all beyond the bound: every start refused.
    let varied = Design::new().var("alpha_b", -1e80, 1e80);
    let mut model = read(fx::CLASS_FOUR_TEXT);
    let compiled = kinloop::synthesis::Problem::new(reference, &varied, &task).unwrap();
    let read_problem = model.synthesis_problem(&varied, &task).unwrap();
    let report = search.run(&compiled).unwrap();
    assert_eq!((report.valid, report.unassembled, report.candidates.len()), (0, 4, 0), "{report:#?}");
    assert_eq!(search.run(&read_problem).unwrap(), report);
    for e in [search.refine(&compiled, &[1e80]).unwrap_err(), search.refine(&read_problem, &[1e80]).unwrap_err()] {
        names(&e, "1e80");
    }
    names(&compiled.residual_norm(&[-1e80]).unwrap_err(), "-1e80");
    names(&compiled.residuals(&[1e80]).map(|_| ()).unwrap_err(), "1e80");
    drop(read_problem);

    // `alpha_b` not varied, at 1e80: no design can be solved, the search says why.
    let (beyond, mut model) = class_four_at(1e80);
    let lengths = Design::new().var("oa", 0.9, 1.1);
    let compiled = kinloop::synthesis::Problem::new(beyond, &lengths, &task).unwrap();
    names(&search.run(&compiled).unwrap_err(), "1e80");
    // The model read is refused as its kernel is made, against the default configuration.
    let default_bound = NewtonConfig::default().largest_precise_angle();
    named_with(&model.synthesis_problem(&lengths, &task).map(|_| ()).unwrap_err(), "1e80", default_bound);
}

/// The kernel-level functions, over a compiled mechanism lent as a kernel (`Compiled(&m)`): each
/// refuses `alpha_b = 1e80` (where `th2 + alpha_b == alpha_b`, so a solve answers for other
/// equations: residuals of 4.5 length units on the declared loop, `imprecise_angle_param.py`)
/// once at its start with the error of `solve`. Before, only the compiled wrappers checked: a
/// sweep made over the kernel and `sweep_at_of` gave a wrong first state, and the others
/// ground through the wrong equations.
#[test]
fn the_kernel_level_functions_refuse_an_angle_parameter_beyond_the_precise_angles() {
    use kinloop::dynamics::{Dynamics, RunConfig, each_turn_state, simulate_of, simulate_steps_of, turn_states};
    use kinloop::paths::{modes, reach, scan, sweep::SweepOf, sweep_at, trace};
    use kinloop::{Compiled, analysis::SampledOf, metrics::limits_of};
    let (compiled, _) = class_four_at(1e80);
    let solved = compiled.solve(0.5).map(|_| ()).unwrap_err();
    let q: [f64; 4] = compiled.guess(0.0).into();
    let k = Compiled(&compiled);

    let listed = sweep_at::sweep_at_of(&k, [[0.0], [0.5], [1.0]], q);
    assert!(listed.states.is_empty(), "{} states", listed.states.len());
    assert_eq!(listed.into_result().map(|_| ()).unwrap_err(), solved);
    let mut sweep = SweepOf::<_, Kin<4, 1, 8>>::over(k, [0.0], [1.0], 3, q).expect("the sweep is made");
    assert_eq!(sweep.next().map(|r| r.map(|_| ())), Some(Err(solved.clone())));
    assert!(sweep.next().is_none(), "the sweep stops at the refusal");
    let folded = scan::fold_sweep_of(k, [0.0], [1.0], 3, q, None, || 0, |n, _| n + 1);
    assert_eq!(folded.unwrap_err(), solved);
    let sampled = SampledOf::over(k, [0.0], [1.0], 3, q, SweepConfig::default());
    assert_eq!(sampled.map(|_| ()).unwrap_err(), solved);
    assert_eq!(limits_of(k, 0.0, 1.0, 3, q, &["th1"]).map(|_| ()).unwrap_err(), solved);
    assert_eq!(reach::reachable_of(&k, [0.5], [0.1], q, 3).map(|_| ()).unwrap_err(), solved);
    let traced = trace::trace_curve_of(&k, [0.0], [1.0], q, &Default::default());
    assert_eq!(traced.map(|_| ()).unwrap_err(), solved);
    let found = modes::assembly_modes_of(&k, &[0.5], 8, &NewtonConfig::default());
    assert_eq!(found.map(|_| ()).unwrap_err(), solved);

    // The dynamics over a kernel: the kinematic error before the first state or step.
    let kinematic = |e: kinloop::dynamics::DynamicsError| match e {
        kinloop::dynamics::DynamicsError::Kinematics { t: None, source } => source,
        e => panic!("{e}"),
    };
    assert_eq!(kinematic(turn_states(k, 0.0, 8, q).map(|_| ()).unwrap_err()), solved);
    let mut visited = 0;
    assert_eq!(kinematic(each_turn_state(k, 0.0, 8, q, |_| visited += 1).unwrap_err()), solved);
    assert_eq!(visited, 0);
    let reduced = |_: &Kin<4, 1, 8>, _: f64| Ok(Dynamics { mass: [[1.0]], gamma: [[[0.0]]], forces: [0.0] });
    let (run, drive) = (RunConfig::default(), |_: f64, _: f64, _: f64| 1.0);
    let simulated = simulate_of(k, reduced, drive, [0.5, 1.0], 1.0, q, &run, |_, _| false);
    assert_eq!(kinematic(simulated.map(|_| ()).unwrap_err()), solved);
    let stepped = simulate_steps_of(k, reduced, drive, [0.5, 1.0], 1.0, q, &run, |_, _| false);
    assert_eq!(kinematic(stepped.map(|_| ()).unwrap_err()), solved);
}

/// A four-bar whose rocker (the dyad's second link) is `1e-20` of its unit crank and coupler,
/// at the input where the coupler's end sits on the rocker's pivot (exactly: frame 2 at 0;
/// within rounding: frame 1 at `fl(π/3)`): every rocker angle closes the loop within the
/// rounding of its size (`tests/solver/closed_form.rs` computes the loop in plain f64), so the
/// read model's solve, on the runtime's closed-form dyad as the compiled one is, reports the
/// same singular position in block 0. Both returned a rocker angle of rounding noise.
#[test]
fn a_rocker_below_the_rounding_of_its_loop_is_singular_read_and_compiled_alike() {
    for (frame, phi) in [(2.0, 0.0), (1.0, std::f64::consts::PI / 3.0)] {
        let compiled = fx::FourBar { a: 1.0, b: 1.0, c: 1e-20, d: frame };
        let solved = compiled.solve(phi).map(|_| ()).unwrap_err();
        assert!(matches!(solved, Error::Singular { .. }), "frame {frame}: {solved:?}");
        let mut model = read(fx::FOUR_BAR_TEXT);
        set(&mut model, &[("a", 1.0), ("b", 1.0), ("c", 1e-20), ("d", frame)]);
        let step = model.solve(&[phi]).map(|_| ()).unwrap_err();
        let explained = model.explain(&[phi], &[0.5, 1.5], &NewtonConfig::default(), step);
        assert_eq!(explained, solved, "frame {frame}");
    }
}

kinloop_fixtures::declare! {
    /// Text of [`GammaFirstFourBar`].
    GAMMA_FIRST_TEXT => {
        /// The fixtures' four-bar with its unknowns declared rocker first: the closed form's
        /// dyad takes the coupler as its second link.
        pub struct GammaFirstFourBar {
            params a, b, c, d;
            input phi;
            unknowns gamma = 1.5, beta = 0.5;
            loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        }
    }
}

kinloop_fixtures::declare! {
    /// Text of [`SlideDyad`].
    SLIDE_DYAD_TEXT => {
        /// A dyad whose first centre `(s, 0)` slides along the frame: a coefficient of its
        /// equation folded to a constant.
        pub struct SlideDyad {
            params b, c, d;
            input s;
            unknowns beta = 0.1, gamma = 3.0;
            loop sbcd: (s, 0) + b @ beta == (d, 0) + c @ gamma;
        }
    }
}

/// A dyad's second link below the rounding of its loop, where every angle of it closes the
/// loop (`tests/solver/degenerate_dyad_links.rs` computes the loop in plain f64): the four-bar
/// declared rocker first with a coupler of `1e-20` or `1e-300` at `fl(π/3)` and `π/3 + 1e-12`,
/// and the sliding dyad (a coefficient folded) with a rocker of `1e-20` whose pivot the
/// coupler's end reaches. The read model's solve, on the runtime's closed-form dyad as the
/// compiled one is, reports the same singular position in block 0. Both returned an angle of
/// rounding noise, or a `Domain` error where the coupler's square underflowed.
#[test]
fn a_second_link_below_the_rounding_is_singular_read_and_compiled_alike() {
    let cfg = NewtonConfig::default();
    for coupler in [1e-20, 1e-300] {
        for phi in [std::f64::consts::PI / 3.0, std::f64::consts::PI / 3.0 + 1e-12] {
            let compiled = GammaFirstFourBar { a: 1.0, b: coupler, c: 1.0, d: 1.0 };
            let solved = compiled.solve(phi).map(|_| ()).unwrap_err();
            assert!(matches!(solved, Error::Singular { .. }), "coupler {coupler:e}, phi {phi}: {solved:?}");
            let mut model = read(GAMMA_FIRST_TEXT);
            set(&mut model, &[("a", 1.0), ("b", coupler), ("c", 1.0), ("d", 1.0)]);
            let step = model.solve(&[phi]).map(|_| ()).unwrap_err();
            let explained = model.explain(&[phi], &[1.5, 0.5], &cfg, step);
            assert_eq!(explained, solved, "coupler {coupler:e}, phi {phi}");
        }
    }
    let compiled = SlideDyad { b: 1.0, c: 1e-20, d: 2.0 };
    let solved = compiled.solve(1.0).map(|_| ()).unwrap_err();
    assert!(matches!(solved, Error::Singular { .. }), "{solved:?}");
    let mut model = read(SLIDE_DYAD_TEXT);
    set(&mut model, &[("b", 1.0), ("c", 1e-20), ("d", 2.0)]);
    let step = model.solve(&[1.0]).map(|_| ()).unwrap_err();
    assert_eq!(model.explain(&[1.0], &[0.1, 3.0], &cfg, step), solved);
}

/// The fixtures' four-bar with a link below the rounding of its loop, beyond the closed forms'
/// sizes (`1e±160`, `1e±200`), where a failed step is solved again by Newton over the whole
/// system: a rocker of `1e-20` of its unit crank and coupler on a frame of 2 at an input of 0
/// (the coupler's end exactly on the rocker's pivot), and a coupler of `1e-20` on a unit
/// crank, rocker and frame at `fl(π/3)` (the crank pin on the rocker's reach). Every angle of
/// the short link closes the loop within `4 eps` of its size
/// (`tests/solver/degenerate_dyad_links.rs` computes it in plain f64): the singular position of
/// block 0 as at size 1, for the analogs and for the positions alone, read and compiled alike.
/// The rocker's analogs were the rocker at its guess (`1.5` rad, a value the data do not
/// determine), in both.
#[test]
fn a_link_below_the_rounding_of_its_loop_is_singular_at_extreme_sizes_read_and_compiled_alike() {
    let cfg = NewtonConfig::default();
    let guess = [0.5, 1.5];
    let cases = [([1.0, 1.0, 1e-20, 2.0], 0.0), ([1.0, 1e-20, 1.0, 1.0], std::f64::consts::PI / 3.0)];
    for (links, phi) in cases {
        for k in [1e160, 1e-160, 1e200, 1e-200] {
            let at = format!("links {links:?} at {phi}, size {k:e}");
            let [a, b, c, d] = links.map(|l| l * k);
            let compiled = fx::FourBar { a, b, c, d };
            let mut model = read(fx::FOUR_BAR_TEXT);
            set(&mut model, &[("a", a), ("b", b), ("c", c), ("d", d)]);
            let solved = compiled.kinematics_flat(&[phi], &guess, &cfg).map(|_| ()).unwrap_err();
            assert!(matches!(solved, Error::Singular { .. }), "{at}: {solved:?}");
            assert_eq!(solved.location().and_then(|l| l.block.as_ref()).map(|b| b.0), Some(0), "{at}");
            let step = model.kinematics(&[phi], &guess, &cfg).map(|_| ()).unwrap_err();
            assert_eq!(model.explain(&[phi], &guess, &cfg, step), solved, "{at}");
            let positioned = compiled.position_flat(&[phi], &guess, &cfg).map(|_| ()).unwrap_err();
            assert!(matches!(positioned, Error::Singular { .. }), "{at}: {positioned:?}");
            let step = model.positions(&[phi], &guess, &cfg).map(|_| ()).unwrap_err();
            assert_eq!(model.explain(&[phi], &guess, &cfg, step), positioned, "{at}");
        }
    }
}

kinloop_fixtures::declare! {
    /// Text of [`SlideDyadNewton`].
    SLIDE_DYAD_NEWTON_TEXT => {
        /// [`SlideDyad`] solved by Newton.
        #[kinloop(newton)]
        pub struct SlideDyadNewton {
            params b, c, d;
            input s;
            unknowns beta = 0.1, gamma = 3.0;
            loop sbcd: (s, 0) + b @ beta == (d, 0) + c @ gamma;
        }
    }
}

kinloop_fixtures::declare! {
    /// Text of [`SlideDyadGammaFirst`].
    SLIDE_GAMMA_FIRST_TEXT => {
        /// [`SlideDyad`] declared rocker first: the closed form's dyad takes the rocker as its
        /// first link.
        pub struct SlideDyadGammaFirst {
            params b, c, d;
            input s;
            unknowns gamma = 3.0, beta = 0.1;
            loop sbcd: (s, 0) + b @ beta == (d, 0) + c @ gamma;
        }
    }
}

kinloop_fixtures::declare! {
    /// Text of [`FourBarNewton`].
    FOUR_BAR_NEWTON_TEXT => {
        /// The fixtures' four-bar solved by Newton.
        #[kinloop(newton)]
        pub struct FourBarNewton {
            params a, b, c, d;
            input phi;
            unknowns beta = 0.5, gamma = 1.5;
            loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        }
    }
}

/// The analogs' positions and the positions alone of `compiled` at `x` from `guess`, and the
/// read model's of `text` with the parameters `params`, alike: the same positions to the bit,
/// or the same error (the model's explained). Returns the compiled mechanism's two results.
fn solved_alike<M: Mechanism<2, 1, NO>, const NO: usize>(
    compiled: &M,
    text: &str,
    params: &[(&str, f64)],
    x: f64,
    guess: [f64; 2],
    at: &str,
) -> [Result<Vec<f64>, Error>; 2] {
    let cfg = NewtonConfig::default();
    let mut model = read(text);
    set(&mut model, params);
    let kin = compiled.kinematics_flat(&[x], &guess, &cfg).map(|k| k.q.to_vec());
    let model_kin = model.kinematics(&[x], &guess, &cfg).map(|k| k.q.clone());
    let pos = compiled.position_flat(&[x], &guess, &cfg).map(|(q, _)| q.to_vec());
    let model_pos = model.positions(&[x], &guess, &cfg).map(|q| q.to_vec());
    for (c, m, what) in [(&kin, model_kin, "analogs"), (&pos, model_pos, "positions")] {
        match (c, m) {
            (Ok(c), Ok(m)) => assert_eq!(c, &m, "{at}: {what}"),
            (Err(c), Err(m)) => assert_eq!(&model.explain(&[x], &guess, &cfg, m), c, "{at}: {what}"),
            (c, m) => panic!("{at}: {what}: compiled {c:?}, read {m:?}"),
        }
    }
    [kin, pos]
}

/// A dyad whose triangle closes exactly with a link `1e-20` of the others
/// (`tests/solver/degenerate_dyad_links.rs` computes the loop over 64 angles of it in plain
/// f64: every one closes it within `4 eps` of its size), the closed form's FIRST link (the
/// slide dyad at `s = 1` on a frame of 2 with a coupler, or declared rocker first a rocker, of
/// `1e-20`; the four-bar of unit crank on a frame of 2 at 0 the same), or with the Newton twin
/// either link: read and compiled alike, the singular position of block 0, at sizes `1e-3`, 1
/// and `1e3`, and beyond the closed forms' sizes (`1e±200`, the rescue's). Both solved the closed form's dyad to `[π/2, π]` (the short link at right angles
/// to nothing: its `d2` does not cancel), and Newton to the short link's angle near its guess
/// (the slide dyad's rocker at `2.95` rad). With a link of `1e-8` (far above the rounding) both
/// are positions, the same to the bit. With a link of `1e-10` each is a position or, where
/// Newton stalls with the slide dyad's rocker along its coupler (the loop open by the rocker's
/// length), the singular position of block 0: read and compiled alike.
#[test]
fn a_link_below_the_rounding_on_an_exact_triangle_is_singular_read_and_compiled_alike() {
    // The links of `1e-8` and `1e-10` at ordinary sizes only: at `1e-200` the slide dyad's
    // analogs fail, read and compiled alike, on the coupler's acceleration analog (a domain
    // error, outside this test).
    let cases = [1.0, 1e-3, 1e3, 1e200, 1e-200].into_iter().flat_map(|s| [(s, 1e-20), (s, 1e-10), (s, 1e-8)]);
    for (scale, short) in cases.filter(|&(s, short)| short < 1e-16 || (1e-3..=1e3).contains(&s)) {
        {
            let (long, short_len) = (scale, short * scale);
            let d = 2.0 * scale;
            let mut results = Vec::new();
            for short_coupler in [true, false] {
                let (b, c) = if short_coupler { (short_len, long) } else { (long, short_len) };
                let at = format!("short {short:e}, coupler short {short_coupler}, size {scale:e}");
                let slide = [("b", b), ("c", c), ("d", d)];
                let four = [("a", scale), ("b", b), ("c", c), ("d", d)];
                let (sg, fg) = ([0.1, 3.0], [0.5, 1.5]);
                // The closed forms with the short link first; Newton with it first and second.
                if short_coupler {
                    let m = SlideDyad { b, c, d };
                    results.push(solved_alike(&m, SLIDE_DYAD_TEXT, &slide, scale, sg, &format!("{at}, slide")));
                    let m = fx::FourBar { a: scale, b, c, d };
                    results.push(solved_alike(&m, fx::FOUR_BAR_TEXT, &four, 0.0, fg, &format!("{at}, four-bar")));
                } else {
                    let m = SlideDyadGammaFirst { b, c, d };
                    let at = format!("{at}, slide rocker first");
                    results.push(solved_alike(&m, SLIDE_GAMMA_FIRST_TEXT, &slide, scale, [3.0, 0.1], &at));
                    let m = GammaFirstFourBar { a: scale, b, c, d };
                    let at = format!("{at}, four-bar rocker first");
                    results.push(solved_alike(&m, GAMMA_FIRST_TEXT, &four, 0.0, [1.5, 0.5], &at));
                }
                let m = SlideDyadNewton { b, c, d };
                results.push(solved_alike(
                    &m,
                    SLIDE_DYAD_NEWTON_TEXT,
                    &slide,
                    scale,
                    sg,
                    &format!("{at}, slide Newton"),
                ));
                let m = FourBarNewton { a: scale, b, c, d };
                results.push(solved_alike(&m, FOUR_BAR_NEWTON_TEXT, &four, 0.0, fg, &format!("{at}, four-bar Newton")));
            }
            for r in results.into_iter().flatten() {
                match r {
                    Err(e @ Error::Singular { .. }) if short < 1e-9 => {
                        assert_eq!(e.location().and_then(|l| l.block.as_ref()).map(|b| b.0), Some(0), "{e}");
                    }
                    Ok(_) if short > 1e-16 => {}
                    other => panic!("short {short:e}, size {scale:e}: {other:?}"),
                }
            }
        }
    }
}

/// A loop whose lengths are all zero (parameters left at zero, as unset ones are) fails the
/// model's step as it fails the compiled one, field for field and in its message: an invalid
/// argument naming the loop, not the block's singular position that both reported (the
/// four-bar's closed form, and the class IV group's Newton block, decomposed and dense); for the
/// step, the positions alone, and a sweep's first sample (which both said starts at a singular
/// position). The model's own record of the step says the block's row holds at every position.
#[test]
fn a_loop_whose_lengths_are_all_zero_fails_alike() {
    let cfg = NewtonConfig::default();
    let zero_loop = |e: &Error, name: &str| match e {
        Error::InvalidArgument(m) => {
            assert!(m.contains(&format!("the links of loop `{name}` all have length zero")), "{m}")
        }
        other => panic!("{other:?}"),
    };
    let compiled = fx::FourBar { a: 0.0, b: 0.0, c: 0.0, d: 0.0 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    set(&mut model, &[("a", 0.0), ("b", 0.0), ("c", 0.0), ("d", 0.0)]);
    for (x, guess) in [([0.7], [0.5, 1.5]), ([-2.0], [-2.0, 3.0])] {
        let e = same_error(&compiled, &mut model, x, guess);
        zero_loop(&e, "abcd");
        let step = model.kinematics(&x, &guess, &cfg).map(drop).unwrap_err();
        assert!(step.to_string().contains("holds at every position"), "{step}");
        same(&e, &model.explain(&x, &guess, &cfg, step));
        let positions = model.positions(&x, &guess, &cfg).map(drop).unwrap_err();
        same(&compiled.position_flat(&x, &guess, &cfg).unwrap_err(), &model.explain(&x, &guess, &cfg, positions));
        let c_sweep = Sweep::<_, Kin<2, 1, 2>, 2, 1, 2>::new(&compiled, x, [x[0] + 1.0], 5, guess).unwrap();
        let c_err = c_sweep.filter_map(Result::err).next().expect("the compiled sweep fails");
        let r_err = model.sweep(&x, &[x[0] + 1.0], 5, &guess).unwrap().filter_map(Result::err).next().expect("fails");
        same(&c_err, &r_err);
        zero_loop(&r_err, "abcd");
    }
    let z = 0.0;
    let blocked = fx::ClassFour { oa: z, xb: z, yb: z, ac: z, ae: z, bd: z, bf: z, cd: z, ef: z, ..Default::default() };
    let dense =
        fx::ClassFourDense { oa: z, xb: z, yb: z, ac: z, ae: z, bd: z, bf: z, cd: z, ef: z, ..Default::default() };
    // The `#[kinloop(dense)]` twin's text (`stringify!` puts a line break after the name).
    let dense_text = format!(
        "#[kinloop(dense)] {}",
        fx::CLASS_FOUR_TEXT.replacen("pub struct ClassFour", "pub struct ClassFourDense", 1)
    );
    class_four_alike(&blocked, fx::CLASS_FOUR_TEXT, &zero_loop);
    class_four_alike(&dense, &dense_text, &zero_loop);
}

/// [`a_loop_whose_lengths_are_all_zero_fails_alike`] of the class IV group `compiled` (its
/// lengths zero) and the model of `text` with the same lengths: the step and the positions alone
/// fail alike, with the error `zero_loop` checks of its first loop, `acdb`.
fn class_four_alike<M: Mechanism<4, 1, NO>, const NO: usize>(
    compiled: &M,
    text: &str,
    zero_loop: &dyn Fn(&Error, &str),
) {
    let cfg = NewtonConfig::default();
    let mut model = read(text);
    set(&mut model, &["oa", "xb", "yb", "ac", "ae", "bd", "bf", "cd", "ef"].map(|p| (p, 0.0)));
    let x = [1.0];
    let guess = compiled.guess_flat(&x);
    zero_loop(&same_error(compiled, &mut model, x, guess), "acdb");
    let positions = model.positions(&x, &guess, &cfg).map(drop).unwrap_err();
    same(&compiled.position_flat(&x, &guess, &cfg).unwrap_err(), &model.explain(&x, &guess, &cfg, positions));
}
