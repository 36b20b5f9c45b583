//! Fuzz target: any text the run-time reader accepts (`kinloop_model::Model::read`) goes
//! through what a program or the command line does with a mechanism: a sweep over its inputs'
//! range, the sampled analysis, the limit positions, the assembly modes, the reach, the traced
//! curve, the recorded motion and its drawing, where the mechanism assembles (nearest an input
//! angle and first along a path: the searches a designer runs when a point solve fails, so they
//! meet the inputs at which nothing solves) and, where declared, the sensitivities and the
//! dynamics. Their errors are answers; none may panic, overflow the stack or hang. Run with
//! `cargo +nightly fuzz run model_paths fuzz/corpus/model_paths cli/mechanisms -- -timeout=30`
//! from the repository root (see README.md, "Fuzzing").
#![no_main]

use kinloop_model::Model;
use kinloop_runtime::dynamics::{OdeConfig, RunConfig, SpeedLaw};
use kinloop_runtime::{QuantityKind, TraceConfig};
use libfuzzer_sys::fuzz_target;

/// Samples of every sweep: few, so that an input runs in milliseconds, yet steps that the
/// sweep's own bounds must subdivide.
const SAMPLES: usize = 9;

/// Samples of the searches for where the mechanism assembles: one each 10 degrees of a turn,
/// few enough that an input runs in milliseconds.
const ASSEMBLY_SAMPLES: usize = 36;

/// Inputs about which `assembly_near` searches: the origin, one near half a turn, and one a
/// million radians out, where the samples of the turn are coarser doubles.
const NEAR: [f64; 3] = [0.0, 3.0, 1e6];

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(mut model) = Model::read("fuzz.kl", text) {
            exercise(&mut model);
        }
    }
    // The reader keeps no span: the lexer's per-thread source map can be emptied, which bounds
    // the memory of a long run.
    kinloop_model::source::forget_spans();
});

fn exercise(m: &mut Model) {
    // Parameters without a default: a value each, as the command line's `--params` gives them.
    let unset: Vec<String> =
        m.params().iter().zip(m.param_values()).filter(|(_, v)| v.is_none()).map(|(p, _)| p.clone()).collect();
    for p in unset {
        m.set_param(&p, 1.5);
    }
    let ni = m.inputs().len();
    let n = m.unknowns().len();
    // A turn of every input (an angle's; a length's input moves by 2 pi of its unit).
    let from = vec![0.0; ni];
    let to = vec![std::f64::consts::TAU; ni];
    // Where it assembles: these searches solve from the declared guess at each sample, so they
    // need no guess of ours, and failing solves are what they go through.
    if m.input_kinds() == [QuantityKind::Angle] {
        for at in NEAR {
            let _ = m.assembly_near(&[at], ASSEMBLY_SAMPLES);
        }
    }
    let _ = m.assembly_along(&from, &to, ASSEMBLY_SAMPLES);
    let _ = m.assembly_along(&to, &from, ASSEMBLY_SAMPLES);
    let mut guess = vec![0.0; n];
    if m.guess(&from, &mut guess).is_err() {
        return;
    }
    if let Ok(sweep) = m.sweep(&from, &to, SAMPLES, &guess) {
        let _ = sweep.run();
    }
    let names = m.unknowns().to_vec();
    if let Ok(sampled) = m.sampled(&from, &to, SAMPLES, &guess) {
        for name in &names {
            let _ = sampled.range(name.as_str());
        }
    }
    if ni == 1 {
        let _ = m.limits(0.0, std::f64::consts::TAU, SAMPLES, &guess, &[]);
        let _ = m.trace_curve(&from, &to, &guess, &TraceConfig::default());
    }
    let _ = m.assembly_modes(&from);
    let _ = m.reachable(&from, &vec![1.0; ni], &guess, SAMPLES);
    if let Ok(motion) = m.motion(&from, &to, SAMPLES, &guess) {
        let _ = m.drawing().svg(&motion, 0);
    }
    if m.has_sensitivities() {
        let _ = m.sensitivities(&from, &guess, &Default::default());
    }
    if m.has_dynamics() && ni == 1 {
        let _ = m.inverse_cycle(SpeedLaw::Constant(1.0)).samples(8).guess(&guess).run();
        // A budget of steps: loads of absurd size (a torque of 1e89 on a crank that reaches a
        // limit position at once) make the integration crawl in steps of 1e-53 until a state
        // component stops registering its change (`CannotAdvance`), 445,000 steps and seconds
        // later; the default budget of 10 million steps is for real runs.
        let cfg = RunConfig::default().with_ode(OdeConfig::default().with_max_steps(20_000));
        let _ = m.simulation().start(0.0, 1.0).guess(&guess).config(cfg).run(0.5);
    }
}
