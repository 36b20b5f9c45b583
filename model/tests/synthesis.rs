//! Synthesis on a run-time model: the runtime's one implementation over the model's kernel.
//! The same problem, seed and starts give the same report as the compiled mechanism's, bit for
//! bit (path generation and function generation, with Halton starts and with differential
//! evolution); and a four-bar whose coupler points are computed here in closed form from known
//! dimensions is recovered to rounding.

mod common;

use common::read;
use kinloop::synthesis::{DeConfig, Design, Global, Problem, Search, SynthesisError, Task};
use kinloop_fixtures::linkages::coupler_point;

/// `kinloop::mechanism! { decl }` and `const TEXT: &str` holding the same declaration's text:
/// the compiled mechanism and the run-time model of one declaration.
macro_rules! both {
    ($text:ident => { $($decl:tt)* }) => {
        kinloop::mechanism! { $($decl)* }
        const $text: &str = stringify!($($decl)*);
    };
}

both! { COUPLER_TEXT => {
    /// Four-bar with a coupler point: crank `a` at the origin, coupler `b`, rocker `c` at (d, 0);
    /// the point `p` at distance `e` from the crank pin, `alpha` off the coupler line.
    #[kinloop(sensitivities)]
    pub struct CouplerFourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.0, e = 1.5, alpha = 0.6;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point p = a @ phi + e @ (beta + alpha);
    }
}}

both! { PLAIN_TEXT => {
    /// The same four-bar without sensitivities: refused by synthesis.
    pub struct PlainFourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}}

/// The dimensions `[a, b, c, d, e, alpha]` the targets are made from.
const TRUTH: [f64; 6] = [1.1, 2.8, 2.3, 3.2, 1.7, 0.45];
const NAMES: [&str; 6] = ["a", "b", "c", "d", "e", "alpha"];

/// The rocker angle `gamma` of the four-bar `[a, b, c, d]` at crank angle `phi`, closed form.
fn rocker_angle([a, b, c, d]: [f64; 4], phi: f64) -> f64 {
    let [x, y] = coupler_point([a, b, c, d, b, 0.0], phi);
    y.atan2(x - d)
}

fn design(names: &[&str], values: &[f64], spread: f64) -> Design {
    names.iter().zip(values).fold(Design::new(), |d, (n, v)| d.var(*n, v * (1.0 - spread), v * (1.0 + spread)))
}

fn path_task() -> Task {
    let phis: Vec<f64> = (0..5).map(|k| 0.3 + 1.1 * k as f64).collect();
    Task::path("p", phis.iter().map(|&p| coupler_point(TRUTH, p))).timed(phis)
}

#[test]
fn path_generation_equals_the_compiled_search_bit_for_bit() {
    let (task, design) = (path_task(), design(&NAMES, &TRUTH, 0.3));
    let search = Search::default().with_starts(0..12).with_seed(3);
    let compiled = Problem::new(CouplerFourBar::default(), &design, &task).unwrap();
    let want = search.run(&compiled).unwrap();
    let mut model = read(COUPLER_TEXT);
    let problem = model.synthesis_problem(&design, &task).unwrap();
    let got = search.run(&problem).unwrap();
    assert!(want.valid >= 1, "{want:#?}");
    // `PartialEq` of the reports: every value of every candidate equal (f64 `==`), the counts too.
    assert_eq!(got, want);
    // Differential evolution: the residual norms (positions only) steer the populations.
    let de = search.with_global(Global::DifferentialEvolution(DeConfig::default().with_population(12)));
    let de = de.with_starts(0..1);
    assert_eq!(de.run(&problem).unwrap(), de.run(&compiled).unwrap());
}

#[test]
fn function_generation_equals_the_compiled_search_bit_for_bit() {
    let (a, b, c, d) = (TRUTH[0], TRUTH[1], TRUTH[2], TRUTH[3]);
    let phis: Vec<f64> = (0..6).map(|k| 0.5 + 0.8 * k as f64).collect();
    let task = Task::function("gamma", phis.iter().map(|&p| (p, rocker_angle([a, b, c, d], p))));
    let design = design(&["a", "b", "c"], &[a, b, c], 0.3);
    let search = Search::default().with_starts(0..10).with_seed(11);
    let compiled = Problem::new(CouplerFourBar { d, ..CouplerFourBar::default() }, &design, &task).unwrap();
    let want = search.run(&compiled).unwrap();
    let mut model = read(COUPLER_TEXT);
    assert!(model.set_param("d", d));
    let got = search.run(&model.synthesis_problem(&design, &task).unwrap()).unwrap();
    assert!(want.valid >= 1, "{want:#?}");
    assert_eq!(got, want);
    // The problem lends the model and puts its parameters back after every evaluation.
    assert_eq!(model.param_values()[0], Some(1.0));
}

#[test]
fn a_four_bar_from_closed_form_coupler_points_is_recovered() {
    let mut model = read(COUPLER_TEXT);
    let problem = model.synthesis_problem(&design(&NAMES, &TRUTH, 0.3), &path_task()).unwrap();
    let report = Search::default().with_starts(0..24).run(&problem).unwrap();
    let best = report.best().unwrap_or_else(|| panic!("no valid candidate: {report:#?}"));
    // Targets of size ~3 met to rounding: ten equations in six unknowns, a consistent system.
    assert!(best.max_error <= 1e-13, "max error {:e}", best.max_error);
    for (name, (got, want)) in NAMES.iter().zip(best.values.iter().zip(&TRUTH)) {
        // A zero residual fixes the dimensions to its conditioning: 1e-8 relative.
        assert!((got - want).abs() <= 1e-8 * want.abs(), "{name}: {got} vs {want}");
    }
}

#[test]
fn names_and_missing_sensitivities_are_typed_errors() {
    let mut model = read(COUPLER_TEXT);
    let bad = Design::new().var("length", 1.0, 2.0);
    let e = model.synthesis_problem(&bad, &path_task()).unwrap_err();
    assert!(
        matches!(&e, SynthesisError::UnknownVariable { name, mechanism, .. }
            if name == "length" && mechanism == "CouplerFourBar"),
        "{e}"
    );
    let e = model.synthesis_problem(&design(&NAMES, &TRUTH, 0.3), &Task::path("q", [[1.0, 2.0]; 6]).timed([0.0; 6]));
    assert!(matches!(&e, Err(SynthesisError::UnknownColumn { name, .. }) if name == "q.x"), "{e:?}");
    let mut plain = read(PLAIN_TEXT);
    let _ = PlainFourBar::default();
    let e = plain.synthesis_problem(&design(&["a"], &[1.0], 0.3), &path_task()).unwrap_err();
    assert!(matches!(&e, SynthesisError::Unsupported(m) if m.contains("#[kinloop(sensitivities)]")), "{e}");
}

#[test]
fn the_kernel_refuses_another_parameter_count_and_puts_the_parameters_back() {
    use kinloop::{Error, SensKernel, SweepConfig};
    use kinloop_model::Count;
    use std::panic::{AssertUnwindSafe, catch_unwind};
    let mut model = read(COUPLER_TEXT);
    let declared = model.param_values().to_vec();
    {
        let k = model.kernel(SweepConfig::default()).unwrap();
        let now = |k: &kinloop_model::ModelKernel<'_>| (0..6).map(|i| Some(k.param(i))).collect::<Vec<_>>();
        for p in [&[1.0][..], &[1.0; 7]] {
            let e = k.with_params(p, |_| unreachable!("not called with a wrong length")).unwrap_err();
            // One value is one: "1 parameter value".
            let says = format!("{} for the 6 parameters of `CouplerFourBar`", Count(p.len(), "parameter value"));
            assert!(matches!(&e, Error::InvalidArgument(m) if m.contains(&says)), "{e}");
            assert_eq!(now(&k), declared);
        }
        // Set for the evaluation, put back after it.
        let seen = k.with_params(&TRUTH, |m| (0..6).map(|i| m.param(i)).collect::<Vec<_>>()).unwrap();
        assert_eq!(seen, TRUTH);
        assert_eq!(now(&k), declared);
        // An evaluation that fails: put back too.
        let failed = k.with_params(&[f64::NAN; 6], |m| m.check_params()).unwrap();
        assert!(matches!(failed, Err(Error::NonFinite { .. })), "{failed:?}");
        assert_eq!(now(&k), declared);
        // An evaluation that panics: put back while unwinding.
        let unwound = catch_unwind(AssertUnwindSafe(|| k.with_params(&TRUTH, |_| panic!("an evaluation panics"))));
        assert!(unwound.is_err());
        assert_eq!(now(&k), declared);
    }
    assert_eq!(model.param_values(), declared);
}

/// `run` in a rayon pool of four threads (more than the machine may have: the jobs then share
/// its cores, and evaluations still overlap).
fn on_four_threads<R: Send>(run: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new().num_threads(4).build().unwrap().install(run)
}

#[test]
fn par_run_on_a_shared_model_equals_run_and_the_compiled_par_run_bit_for_bit() {
    use kinloop::synthesis::ProblemOf;
    let (task, design) = (path_task(), design(&NAMES, &TRUTH, 0.3));
    let search = Search::default().with_starts(0..16).with_seed(3);
    let compiled = Problem::new(CouplerFourBar::default(), &design, &task).unwrap();
    let want = on_four_threads(|| search.par_run(&compiled).unwrap());
    assert!(want.valid >= 1, "{want:#?}");
    let mut model = read(COUPLER_TEXT);
    let serial = search.run(&model.synthesis_problem(&design, &task).unwrap()).unwrap();
    // The pool seen from outside: the problem's kernel is a clone of `k` (one pool).
    let k = model.shared_kernel(kinloop::SweepConfig::default()).unwrap();
    let shared = ProblemOf::over(k.clone(), &design, &task).unwrap();
    let got = on_four_threads(|| search.par_run(&shared).unwrap());
    assert_eq!(got, serial);
    assert_eq!(got, want);
    // The evaluations ran on the pool's clones: at least one. How many overlapped is the
    // scheduler's (on a loaded host the four threads may take turns); that a clone is made
    // exactly when every one made before is checked out is pinned with a barrier below
    // (`concurrent_evaluations_each_run_on_their_own_clone_with_their_own_parameters`).
    assert!(k.clones() >= 1, "{} clones", k.clones());
    // `Model::shared_synthesis_problem` is that problem; serially it gives the same report.
    let shared = model.shared_synthesis_problem(&design, &task).unwrap();
    assert_eq!(search.run(&shared).unwrap(), want);
    // Differential evolution: each generation's trial vectors evaluated in parallel as well.
    let de = search.with_global(Global::DifferentialEvolution(DeConfig::default().with_population(12)));
    let de = de.with_starts(0..3);
    let want = on_four_threads(|| de.par_run(&compiled).unwrap());
    let got = on_four_threads(|| de.par_run(&shared).unwrap());
    assert_eq!(got, want);
    assert_eq!(got, de.run(&model.synthesis_problem(&design, &task).unwrap()).unwrap());
    // The model is not lent: its parameters are its own.
    assert_eq!(model.param_values()[0], Some(1.0));
}

#[test]
fn function_generation_on_a_shared_model_equals_the_compiled_par_run_bit_for_bit() {
    let (a, b, c, d) = (TRUTH[0], TRUTH[1], TRUTH[2], TRUTH[3]);
    let phis: Vec<f64> = (0..6).map(|k| 0.5 + 0.8 * k as f64).collect();
    let task = Task::function("gamma", phis.iter().map(|&p| (p, rocker_angle([a, b, c, d], p))));
    let design = design(&["a", "b", "c"], &[a, b, c], 0.3);
    let search = Search::default().with_starts(0..16).with_seed(11);
    let compiled = Problem::new(CouplerFourBar { d, ..CouplerFourBar::default() }, &design, &task).unwrap();
    let want = on_four_threads(|| search.par_run(&compiled).unwrap());
    assert!(want.valid >= 1, "{want:#?}");
    let mut model = read(COUPLER_TEXT);
    assert!(model.set_param("d", d));
    let shared = model.shared_synthesis_problem(&design, &task).unwrap();
    // The progress: every job counted once, whatever order they finish in.
    let done = std::sync::atomic::AtomicUsize::new(0);
    let got = on_four_threads(|| {
        search
            .par_run_with_progress(&shared, |_, total| {
                assert_eq!(total, 16);
                done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            })
            .unwrap()
    });
    assert_eq!(got, want);
    assert_eq!(done.into_inner(), 16);
    assert_eq!(got, search.run(&model.synthesis_problem(&design, &task).unwrap()).unwrap());
}

/// One evaluation's positions, outputs and outputs' sensitivities.
type Evaluated = (Vec<f64>, Vec<f64>, Vec<f64>);

/// The kinematics and sensitivities at one input, from the declared guess, on the kernel `k`
/// (in `with_params`: on the clone checked out with its parameters).
fn state_and_sens(k: &kinloop_model::SharedModelKernel) -> Result<Evaluated, kinloop::Error> {
    use kinloop::{Kernel, SensKernel};
    let x = kinloop::dims::Heap(vec![0.7].into());
    let mut kin = kinloop::dims::Dims::kin(k.dims());
    let mut sens = k.sens();
    k.sensitivities_into(&x, &k.guess(&x), &kinloop::NewtonConfig::default(), &mut kin, &mut sens)?;
    Ok((kin.q.to_vec(), kin.out.to_vec(), sens.out))
}

#[test]
fn a_failing_or_panicking_evaluation_leaves_the_pool_whole() {
    use kinloop::{Error, SensKernel, SweepConfig};
    use std::panic::{AssertUnwindSafe, catch_unwind};
    let model = read(COUPLER_TEXT);
    let declared: Vec<f64> = model.param_values().iter().map(|v| v.unwrap()).collect();
    let k = model.shared_kernel(SweepConfig::default()).unwrap();
    let params = |k: &kinloop_model::SharedModelKernel| (0..6).map(|i| k.param(i)).collect::<Vec<_>>();
    let want = k.with_params(&TRUTH, state_and_sens).unwrap().unwrap();
    // Independent of the pool: the coupler point in closed form.
    assert!(want.1.iter().zip(coupler_point(TRUTH, 0.7)).all(|(g, w)| (g - w).abs() <= 1e-12), "{want:?}");
    assert_eq!(k.clones(), 1);
    // A failing evaluation: the error, and its clone given back with its parameters...
    let failed = k.with_params(&[f64::NAN; 6], |m| (params(m), state_and_sens(m))).unwrap();
    assert!(failed.0.iter().all(|v| v.is_nan()));
    assert!(matches!(&failed.1, Err(Error::NonFinite { .. })), "{:?}", failed.1);
    // ... set anew by the next evaluation, on that very clone (no other was made).
    assert_eq!(k.with_params(&TRUTH, state_and_sens).unwrap().unwrap(), want);
    assert_eq!(k.clones(), 1);
    // Another design in between: the evaluation of the first unchanged by it.
    let other = [1.0, 3.0, 2.5, 3.0, 1.5, 0.6];
    let between = k.with_params(&other, state_and_sens).unwrap().unwrap();
    assert_ne!(between, want);
    assert_eq!(k.with_params(&TRUTH, state_and_sens).unwrap().unwrap(), want);
    // A panicking evaluation: its clone dropped, the pool usable, the next evaluation unchanged.
    let unwound = catch_unwind(AssertUnwindSafe(|| {
        k.with_params(&other, |m| {
            let _ = state_and_sens(m);
            panic!("an evaluation panics")
        })
    }));
    assert!(unwound.is_err());
    assert_eq!(k.with_params(&TRUTH, state_and_sens).unwrap().unwrap(), want);
    assert_eq!(k.clones(), 2);
    // A wrong parameter count: refused before a clone is checked out.
    let e = k.with_params(&[1.0; 7], |_| unreachable!("not called with a wrong length")).unwrap_err();
    assert!(matches!(&e, Error::InvalidArgument(m) if m.contains("7 parameter values")), "{e}");
    // The kernel's own parameters never changed, and its own evaluations use them (on the
    // clone in the pool, last checked out with other parameters: no new clone).
    assert_eq!(params(&k), declared);
    let own = state_and_sens(&k).unwrap();
    assert_eq!(k.clones(), 2);
    assert!(
        own.1.iter().zip(coupler_point(declared.clone().try_into().unwrap(), 0.7)).all(|(g, w)| (g - w).abs() <= 1e-12)
    );
}

#[test]
fn concurrent_evaluations_each_run_on_their_own_clone_with_their_own_parameters() {
    use kinloop::SensKernel;
    let model = read(COUPLER_TEXT);
    let k = model.shared_kernel(kinloop::SweepConfig::default()).unwrap();
    // Four designs around the truth, evaluated at once: each waits inside its evaluation until
    // all four are checked out.
    let designs: Vec<[f64; 6]> = (0..4).map(|j| TRUTH.map(|v| v * (1.0 + 0.02 * j as f64))).collect();
    let barrier = std::sync::Barrier::new(designs.len());
    let points: Vec<Vec<f64>> = std::thread::scope(|s| {
        let handles: Vec<_> = designs
            .iter()
            .map(|p| {
                let (k, barrier) = (&k, &barrier);
                s.spawn(move || {
                    k.with_params(p, |m| {
                        barrier.wait();
                        state_and_sens(m).unwrap().1
                    })
                    .unwrap()
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(k.clones(), 4);
    for (p, got) in designs.iter().zip(&points) {
        let want = coupler_point(*p, 0.7);
        // Coordinates of size ~3, one position solve to rounding: 1e-12.
        assert!(got.iter().zip(want).all(|(g, w)| (g - w).abs() <= 1e-12), "{p:?}: {got:?} vs {want:?}");
    }
}

#[test]
fn a_shared_kernel_sweeps_as_the_lent_model_does() {
    use kinloop_runtime::dims::Heap;
    use kinloop_runtime::paths::sweep::SweepOf;
    let mut model = read(COUPLER_TEXT);
    let k = model.shared_kernel(kinloop::SweepConfig::default()).unwrap();
    let v = |s: &[f64]| Heap(s.into());
    let (from, to, guess) = ([0.0], [std::f64::consts::TAU], [0.5, 1.5]);
    let sweep: SweepOf<_, kinloop_runtime::dims::KinBuf> =
        SweepOf::over(k.clone(), v(&from), v(&to), 73, v(&guess)).unwrap();
    let shared = sweep.table().unwrap();
    let lent = model.sweep(&from, &to, 73, &guess).unwrap().table().unwrap();
    // The same steps on the same operations: every column equal to the bit.
    assert_eq!(shared, lent);
    // Every step on the one clone, its parameters loaded once.
    assert_eq!(k.clones(), 1);
}
