//! The run-time model against the compiled mechanism of the same declaration: the fixtures'
//! mechanisms (declared with `kinloop::mechanism!`, their text kept beside them) read at run
//! time give the same positions, analogs and outputs along whole sweeps.
//!
//! The reference is independent of the tape: the compiled kernels are straight-line Rust that
//! the macro emitted and rustc optimised. Both evaluate the same plan with the same operations,
//! so the values agree to the last bits; the tolerance allows a relative 1e-15 of each array's
//! largest magnitude (a few rounding steps of 1.1e-16: an optimiser may contract or reorder
//! nothing in IEEE arithmetic, but libm calls may be inlined differently), and the test reports
//! the largest difference it saw.

#[macro_use]
mod common;

use kinloop::NewtonConfig;
use kinloop::{Mechanism, Sensitivities};
use kinloop_fixtures as fx;
use kinloop_model::Model;
use std::f64::consts::{FRAC_PI_2, TAU};

/// Relative agreement demanded, of each array's largest magnitude.
const REL: f64 = 1e-15;

/// Largest difference between `a` and `b` relative to the largest magnitude of either.
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    a.iter().zip(b).map(|(x, y)| (x - y).abs() / scale).fold(0.0, f64::max)
}

/// Sweeps input 0 over a full turn (the other inputs fixed), warm-started from the compiled
/// mechanism's previous position (both solvers get the same guess, bit for bit), and compares
/// every array of the state. Returns the largest relative difference seen and the number of
/// states compared.
fn sweep_parity<M, const N: usize, const NI: usize, const NO: usize>(
    compiled: &M,
    model: &mut Model,
    x0: [f64; NI],
    samples: usize,
) -> (f64, usize)
where
    M: Mechanism<N, NI, NO>,
{
    let cfg = NewtonConfig::default();
    let name = model.name().to_string();
    let mut guess = compiled.guess_flat(&x0);
    let mut worst = 0.0f64;
    let mut compared = 0;
    for k in 0..samples {
        let mut x = x0;
        x[0] = x0[0] + TAU * k as f64 / samples as f64;
        let c = compiled.kinematics_flat(&x, &guess, &cfg);
        let r = model.kinematics(&x, &guess, &cfg).cloned();
        match (c, r) {
            (Ok(c), Ok(r)) => {
                let flat3 = |v: &[[[f64; NI]; NI]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
                let flat2 = |v: &[[f64; NI]]| v.iter().flatten().copied().collect::<Vec<f64>>();
                let diffs = [
                    rel_diff(&c.q, &r.q),
                    rel_diff(&flat2(&c.dq), &r.dq),
                    rel_diff(&flat3(&c.d2q), &r.d2q),
                    rel_diff(&c.out, &r.out),
                    rel_diff(&flat2(&c.dout), &r.dout),
                    rel_diff(&flat3(&c.d2out), &r.d2out),
                ];
                for (what, d) in ["q", "dq", "d2q", "out", "dout", "d2out"].iter().zip(diffs) {
                    assert!(d <= REL, "{} at x = {x:?}: {what} differs by {d:e} (relative)", name);
                    worst = worst.max(d);
                }
                assert_eq!(c.report.iterations, r.report.iterations, "{} at {x:?}: iterations", name);
                assert_eq!(c.health.det_signs, r.health.det_signs, "{} at {x:?}: determinant signs", name);
                guess = c.q;
                compared += 1;
            }
            (Err(_), Err(_)) => guess = compiled.guess_flat(&x),
            (c, r) => panic!("{} at {x:?}: compiled {:?}, run time {:?}", name, c.map(|k| k.q), r.map(|s| s.q)),
        }
    }
    (worst, compared)
}

fn read(text: &str) -> Model {
    Model::read("fixture.kl", text).unwrap_or_else(|e| panic!("{e}"))
}

/// The `#[kinloop(dense)]` twin of a fixture's text, named `dense`.
fn dense_text(text: &str, name: &str, dense: &str) -> String {
    format!("#[kinloop(dense)] {}", text.replacen(&format!("struct {name} "), &format!("struct {dense} "), 1))
}

#[test]
fn four_bar_equals_the_compiled_one() {
    let compiled = fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let mut model = read(fx::FOUR_BAR_TEXT);
    for (p, v) in [("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)] {
        assert!(model.set_param(p, v));
    }
    let (worst, n) = sweep_parity(&compiled, &mut model, [0.0], 360);
    assert!(n >= 300, "only {n} states compared");
    eprintln!("four-bar: {n} states, largest relative difference {worst:e}");
}

#[test]
fn rhombic_drive_equals_the_compiled_one() {
    let mut model = read(fx::RHOMBIC_DRIVE_TEXT);
    let (worst, n) = sweep_parity(&fx::RhombicDrive::default(), &mut model, [0.0], 360);
    assert_eq!(n, 360);
    eprintln!("rhombic drive: {n} states, largest relative difference {worst:e}");
    // The same declaration as one dense Newton block.
    let mut dense = read(&dense_text(fx::RHOMBIC_DRIVE_TEXT, "RhombicDrive", "RhombicDriveDense"));
    let (worst, n) = sweep_parity(&fx::RhombicDriveDense::default(), &mut dense, [0.0], 360);
    assert_eq!(n, 360);
    eprintln!("rhombic drive (dense Newton): {n} states, largest relative difference {worst:e}");
    // At 1e20 and 1e-20 times its size: one Newton block of two angles and two positions,
    // whose pivots are measured in the unknowns' units, solves every state there too.
    for k in [1e20, 1e-20] {
        let d = fx::RhombicDriveDense::default();
        let mut p = d.params_flat();
        let names = <fx::RhombicDriveDense as Mechanism<4, 1, 7>>::PARAMS;
        for (name, v) in names.iter().zip(p.iter_mut()) {
            if !["gamma", "psi_s1"].contains(name) {
                *v *= k;
                assert!(dense.set_param(name, *v));
            }
        }
        let (worst, n) = sweep_parity(&d.with_params_flat(p), &mut dense, [0.0], 360);
        assert_eq!(n, 360, "at {k:e} times its size");
        eprintln!("rhombic drive (dense Newton) at {k:e} times its size: largest relative difference {worst:e}");
    }
}

#[test]
fn other_fixtures_equal_the_compiled_ones() {
    let mut m = read(fx::SLIDER_CRANK_TEXT);
    for (p, v) in [("r", 1.0), ("l", 3.0), ("e", 0.4)] {
        m.set_param(p, v);
    }
    let w = sweep_parity(&fx::SliderCrank { r: 1.0, l: 3.0, e: 0.4 }, &mut m, [0.0], 180);
    eprintln!("slider-crank: {w:?}");
    let w = sweep_parity(&fx::FiveBar::default(), &mut read(fx::FIVE_BAR_TEXT), [0.0, 0.4], 180);
    eprintln!("five-bar: {w:?}");
    let w = sweep_parity(&fx::ClassFour::default(), &mut read(fx::CLASS_FOUR_TEXT), [0.0], 180);
    eprintln!("class IV: {w:?}");
    let mut dense = read(&dense_text(fx::CLASS_FOUR_TEXT, "ClassFour", "ClassFourDense"));
    let w = sweep_parity(&fx::ClassFourDense::default(), &mut dense, [0.0], 180);
    eprintln!("class IV (dense): {w:?}");
    let w = sweep_parity(&fx::DisplacerRodDrive::default(), &mut read(fx::DISPLACER_ROD_DRIVE_TEXT), [0.0], 180);
    eprintln!("displacer-rod drive: {w:?}");
    let w = sweep_parity(&fx::WorkingRodDrive::default(), &mut read(fx::WORKING_ROD_DRIVE_TEXT), [0.0], 180);
    eprintln!("working-rod drive: {w:?}");
    let w = sweep_parity(&fx::gear_lever::GearLever::default(), &mut read(fx::gear_lever::GEAR_LEVER_TEXT), [0.0], 180);
    eprintln!("gear lever: {w:?}");
    // The roller edger's input is time: the same range, 0 to 2π, in seconds.
    let w = sweep_parity(
        &fx::roller_edger::RollerEdger::default(),
        &mut read(fx::roller_edger::ROLLER_EDGER_TEXT),
        [0.0],
        180,
    );
    eprintln!("roller edger: {w:?}");
    let w = sweep_parity(&fx::balancing::Balance::default(), &mut read(fx::balancing::BALANCE_TEXT), [0.0], 180);
    eprintln!("balance: {w:?}");
    let w = sweep_parity(&fx::ClassFourCore::default(), &mut read(fx::CLASS_FOUR_CORE_TEXT), [0.0], 180);
    eprintln!("class IV core: {w:?}");
    let w =
        sweep_parity(&fx::cam_linkage::CamLinkage::default(), &mut read(fx::cam_linkage::CAM_LINKAGE_TEXT), [0.0], 180);
    eprintln!("cam linkage: {w:?}");
    let w = sweep_parity(
        &fx::cam_linkage::HarmonicCamRocker::default(),
        &mut read(fx::cam_linkage::HARMONIC_CAM_ROCKER_TEXT),
        [0.0],
        180,
    );
    eprintln!("harmonic cam rocker: {w:?}");
    let w = sweep_parity(
        &fx::cam_linkage::DwellCamRocker::default(),
        &mut read(fx::cam_linkage::DWELL_CAM_ROCKER_TEXT),
        [0.0],
        180,
    );
    eprintln!("dwell cam rocker: {w:?}");
    let w = sweep_parity(
        &fx::cam_linkage::DwellCamRocker::default(),
        &mut read(fx::cam_linkage::DWELL_CAM_ROCKER_TEXT),
        [-3.0 * TAU - 0.1],
        180,
    );
    eprintln!("dwell cam rocker, three turns back: {w:?}");
}

/// The piecewise cam law (`clamp`, `min`, `max`, and `wrap` by `floor`) to the bit: every array
/// of the state at the segments' ends and beside them, where the comparisons of the law change
/// their choice, in four turns (where `floor` jumps at the turns' boundaries), and the
/// same error where the law is NaN (`fall = 0` at the return's start, 0 / 0).
#[test]
fn dwell_cam_equals_the_compiled_one_to_the_bit() {
    let compiled = fx::cam_linkage::DwellCamRocker::default();
    let mut model = read(fx::cam_linkage::DWELL_CAM_ROCKER_TEXT);
    let cfg = NewtonConfig::default();
    let m = &compiled;
    let mut compared = 0;
    // Over four turns: the law of the wrapped angle (`floor`) repeats every turn.
    let ends = [0.0, m.phi0, m.phi0 + m.rise, m.phi1, m.phi1 + m.fall, TAU];
    for end in [-TAU, 0.0, TAU, 2.0 * TAU].into_iter().flat_map(|turn| ends.map(|e| turn + e)) {
        for d in [0.0, -1e-12, 1e-12, -1e-6, 1e-6, -0.3, 0.3] {
            let x = [end + d];
            let guess = compiled.guess_flat(&x);
            let c = compiled.kinematics_flat(&x, &guess, &cfg).expect("compiled");
            let r = model.kinematics(&x, &guess, &cfg).expect("run time").clone();
            let bits = |v: &[f64]| v.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
            let flat = |v: &[[f64; 1]]| v.iter().flatten().copied().collect::<Vec<f64>>();
            let flat3 = |v: &[[[f64; 1]; 1]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
            assert_eq!(bits(&c.q), bits(&r.q), "q at {x:?}");
            assert_eq!(bits(&flat(&c.dq)), bits(&r.dq), "dq at {x:?}");
            assert_eq!(bits(&flat3(&c.d2q)), bits(&r.d2q), "d2q at {x:?}");
            assert_eq!(bits(&c.out), bits(&r.out), "out at {x:?}");
            assert_eq!(bits(&flat(&c.dout)), bits(&r.dout), "dout at {x:?}");
            assert_eq!(bits(&flat3(&c.d2out)), bits(&r.d2out), "d2out at {x:?}");
            compared += 1;
        }
    }
    assert_eq!(compared, 168);
    let nan = fx::cam_linkage::DwellCamRocker { fall: 0.0, ..Default::default() };
    assert!(model.set_param("fall", 0.0));
    let x = [nan.phi1];
    let guess = nan.guess_flat(&x);
    assert!(nan.kinematics_flat(&x, &guess, &cfg).is_err(), "compiled: a NaN law went unnoticed");
    assert!(model.kinematics(&x, &guess, &cfg).is_err(), "run time: a NaN law went unnoticed");
}

/// The comparison can fail: a run-time model with one parameter changed by one part in 10^12
/// differs from the compiled mechanism beyond the tolerance.
#[test]
fn a_changed_parameter_is_seen() {
    let mut model = read(fx::RHOMBIC_DRIVE_TEXT);
    model.set_param("l_p", 3.0 * (1.0 + 1e-12));
    let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        sweep_parity(&fx::RhombicDrive::default(), &mut model, [0.0], 8)
    }));
    assert!(caught.is_err(), "a parameter changed by 1e-12 went unnoticed");
}

/// Sensitivities of positions, analogs and outputs to every parameter along a turn, against the
/// compiled mechanism's `sensitivities_flat`.
fn sensitivity_parity<M, const N: usize, const NI: usize, const NO: usize, const NP: usize>(
    compiled: &M,
    model: &mut Model,
    x0: [f64; NI],
    samples: usize,
) -> f64
where
    M: kinloop::Sensitivities<N, NI, NO, NP>,
{
    let cfg = NewtonConfig::default();
    let mut guess = compiled.guess_flat(&x0);
    let mut worst = 0.0f64;
    for k in 0..samples {
        let mut x = x0;
        x[0] = x0[0] + TAU * k as f64 / samples as f64;
        let (ck, cs) = compiled.sensitivities_flat(&x, &guess, &cfg).expect("compiled");
        let (_, rs) = model.sensitivities(&x, &guess, &cfg).expect("run time");
        let rs = rs.expect("declared with sensitivities");
        let f = |v: &[f64]| v.to_vec();
        let pairs = [
            (cs.q.iter().flatten().copied().collect::<Vec<_>>(), f(&rs.q)),
            (cs.dq.iter().flatten().flatten().copied().collect(), f(&rs.dq)),
            (cs.d2q.iter().flatten().flatten().flatten().copied().collect(), f(&rs.d2q)),
            (cs.out.iter().flatten().copied().collect(), f(&rs.out)),
            (cs.dout.iter().flatten().flatten().copied().collect(), f(&rs.dout)),
            (cs.d2out.iter().flatten().flatten().flatten().copied().collect(), f(&rs.d2out)),
        ];
        for (c, r) in pairs {
            let d = rel_diff(&c, &r);
            assert!(d <= REL, "{} at {x:?}: sensitivities differ by {d:e}", model.name());
            worst = worst.max(d);
        }
        guess = ck.q;
    }
    worst
}

#[test]
fn sensitivities_equal_the_compiled_ones() {
    let w = sensitivity_parity(&fx::RhombicDrive::default(), &mut read(fx::RHOMBIC_DRIVE_TEXT), [0.0], 90);
    eprintln!("rhombic drive sensitivities: largest relative difference {w:e}");
    let w = sensitivity_parity(&fx::FiveBar::default(), &mut read(fx::FIVE_BAR_TEXT), [0.0, 0.4], 90);
    eprintln!("five-bar sensitivities: {w:e}");
    let w = sensitivity_parity(&fx::ClassFour::default(), &mut read(fx::CLASS_FOUR_TEXT), [0.0], 90);
    eprintln!("class IV sensitivities: {w:e}");
}

/// Residuals, outputs and the full Jacobian at given positions (near and away from the
/// solution), against the compiled `residual_flat`, `outputs_flat` and `jacobian_flat`.
fn at_parity<M, const N: usize, const NI: usize, const NO: usize>(compiled: &M, model: &mut Model, x0: [f64; NI])
where
    M: Mechanism<N, NI, NO>,
{
    let mut jac = kinloop_model::Jacobian::default();
    for k in 0..24 {
        let mut x = x0;
        x[0] += 0.27 * k as f64;
        let mut q = compiled.guess_flat(&x);
        for (u, v) in q.iter_mut().enumerate() {
            *v += 0.01 * (k * (u + 1)) as f64;
        }
        let (mut res, mut out) = (vec![0.0; N], vec![0.0; NO]);
        model.residual(&x, &q, &mut res).expect("residual");
        model.outputs_at(&x, &q, &mut out).expect("outputs");
        model.jacobian(&x, &q, &mut jac).expect("jacobian");
        let c = compiled.jacobian_flat(&x, &q);
        assert_eq!(rel_diff(&res, &compiled.residual_flat(&x, &q)), 0.0, "{}: residual", model.name());
        assert_eq!(rel_diff(&out, &compiled.outputs_flat(&x, &q)), 0.0, "{}: outputs", model.name());
        let flat = |m: &[[f64; N]]| m.iter().flatten().copied().collect::<Vec<f64>>();
        let flat_x = |m: &[[f64; NI]]| m.iter().flatten().copied().collect::<Vec<f64>>();
        for (what, a, b) in [
            ("f", jac.f.clone(), c.f.to_vec()),
            ("j", jac.j.clone(), flat(&c.j)),
            ("fx", jac.fx.clone(), flat_x(&c.fx)),
            ("scale", jac.scale.clone(), c.scale.to_vec()),
            ("unit", jac.unit.clone(), c.unit.to_vec()),
            ("input_unit", jac.input_unit.clone(), c.input_unit.to_vec()),
        ] {
            assert!(rel_diff(&a, &b) <= REL, "{}: jacobian {what}", model.name());
        }
    }
}

#[test]
fn evaluations_at_a_position_equal_the_compiled_ones() {
    at_parity(&fx::RhombicDrive::default(), &mut read(fx::RHOMBIC_DRIVE_TEXT), [0.0]);
    at_parity(&fx::ClassFour::default(), &mut read(fx::CLASS_FOUR_TEXT), [0.0]);
    at_parity(&fx::FiveBar::default(), &mut read(fx::FIVE_BAR_TEXT), [0.0, 0.4]);
}

/// Analogs and outputs at given positions (solved ones and perturbed ones), against the
/// compiled `kinematics_at_flat`, including the residual it reports.
fn kinematics_at_parity<M, const N: usize, const NI: usize, const NO: usize>(
    compiled: &M,
    model: &mut Model,
    x0: [f64; NI],
) where
    M: Mechanism<N, NI, NO>,
{
    let cfg = NewtonConfig::default();
    let name = model.name().to_string();
    let mut compared = 0;
    for k in 0..24 {
        let mut x = x0;
        x[0] += 0.27 * k as f64;
        let Ok(solved) = compiled.kinematics_flat(&x, &compiled.guess_flat(&x), &cfg) else { continue };
        for shift in [0.0, 1e-7] {
            let q = solved.q.map(|v| v + shift);
            let (c, r) = (compiled.kinematics_at_flat(&x, &q, &cfg), model.kinematics_at(&x, &q, &cfg));
            let (c, r) = match (c, r) {
                (Ok(c), Ok(r)) => (c, r),
                (Err(_), Err(_)) => continue,
                (c, r) => panic!("{name}: compiled {:?}, run time {:?}", c.is_ok(), r.is_ok()),
            };
            let flat2 = |v: &[[f64; NI]]| v.iter().flatten().copied().collect::<Vec<f64>>();
            let flat3 = |v: &[[[f64; NI]; NI]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
            assert_eq!(c.report.residual.to_bits(), r.report.residual.to_bits(), "{name}: residual");
            for (a, b) in [
                (flat2(&c.dq), r.dq.clone()),
                (flat3(&c.d2q), r.d2q.clone()),
                (c.out.to_vec(), r.out.clone()),
                (flat2(&c.dout), r.dout.clone()),
                (flat3(&c.d2out), r.d2out.clone()),
            ] {
                assert!(rel_diff(&a, &b) <= REL, "{name} at {x:?}: analogs at a position differ");
            }
            compared += 1;
        }
    }
    assert!(compared >= 24, "{name}: only {compared} positions compared");
}

#[test]
fn kinematics_at_a_position_equal_the_compiled_ones() {
    kinematics_at_parity(&fx::RhombicDrive::default(), &mut read(fx::RHOMBIC_DRIVE_TEXT), [0.0]);
    kinematics_at_parity(&fx::ClassFour::default(), &mut read(fx::CLASS_FOUR_TEXT), [0.0]);
    kinematics_at_parity(&fx::FiveBar::default(), &mut read(fx::FIVE_BAR_TEXT), [0.0, 0.4]);
    let mut m = read(fx::SLIDER_CRANK_TEXT);
    for (p, v) in [("r", 1.0), ("l", 3.0), ("e", 0.4)] {
        m.set_param(p, v);
    }
    kinematics_at_parity(&fx::SliderCrank { r: 1.0, l: 3.0, e: 0.4 }, &mut m, [0.0]);
}

declared! {
    DENSE_RING_TEXT =>
    /// A ring of five four-bar loops closed through the input: one coupled block of ten
    /// unknowns, declared dense (more unknowns than the sizes of the closed forms and the 2x2
    /// inverse: the runtime's `Lu<10>` and `newton::<10, _>`).
    #[kinloop(dense)]
    pub struct DenseRing {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
        input phi;
        unknowns u0 = 0.6, v0 = 1.9, u1 = 0.6, v1 = 1.9, u2 = 0.6, v2 = 1.9, u3 = 0.6, v3 = 1.9,
            u4 = 0.6, v4 = 1.9;
        loop l0: a @ (0.5 * (phi + v4)) + b @ u0 == (d, 0) + c @ v0;
        loop l1: a @ v0 + b @ u1 == (d, 0) + c @ v1;
        loop l2: a @ v1 + b @ u2 == (d, 0) + c @ v2;
        loop l3: a @ v2 + b @ u3 == (d, 0) + c @ v3;
        loop l4: a @ v3 + b @ u4 == (d, 0) + c @ v4;
    }
}

#[test]
fn a_dense_block_of_ten_unknowns_equals_the_compiled_one() {
    let mut model = read(DENSE_RING_TEXT);
    assert_eq!(model.block_count(), 1, "{}", model.decomposition());
    assert!(model.unknowns().len() > 8);
    let (worst, n) = sweep_parity(&DenseRing::default(), &mut model, [0.0], 360);
    assert!(n >= 300, "only {n} states compared");
    eprintln!("dense ring of ten unknowns: {n} states, largest relative difference {worst:e}");
}

/// The positions-only solve over a turn (warm-started as `sweep_parity`): where the full step
/// solves, the same positions bit for bit (the same block solves in the same order); and where
/// the compiled mechanism's `position_flat` solves, the model's too, to the kernels' agreement.
/// Returns the states compared.
fn positions_parity<M, const N: usize, const NI: usize, const NO: usize>(
    compiled: &M,
    model: &mut Model,
    x0: [f64; NI],
    samples: usize,
) -> usize
where
    M: Mechanism<N, NI, NO>,
{
    let cfg = NewtonConfig::default();
    let name = model.name().to_string();
    let mut guess = compiled.guess_flat(&x0);
    let mut compared = 0;
    for k in 0..samples {
        let mut x = x0;
        x[0] = x0[0] + TAU * k as f64 / samples as f64;
        let full = model.kinematics(&x, &guess, &cfg).map(|s| s.q.clone());
        let positions = model.positions(&x, &guess, &cfg).map(<[f64]>::to_vec);
        if let Ok(q) = &full {
            let p = positions.as_ref().unwrap_or_else(|e| panic!("{name} at {x:?}: {e}"));
            let bits = |v: &[f64]| v.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
            assert_eq!(bits(p), bits(q), "{name} at {x:?}: positions {p:?}, full step {q:?}");
            compared += 1;
        }
        match (compiled.position_flat(&x, &guess, &cfg), &positions) {
            (Ok((c, _)), Ok(r)) => {
                let d = rel_diff(&c, r);
                assert!(d <= REL, "{name} at {x:?}: positions differ from position_flat by {d:e}");
                guess = c;
            }
            (Err(_), Err(_)) => guess = compiled.guess_flat(&x),
            (c, r) => panic!("{name} at {x:?}: position_flat {c:?}, positions {r:?}"),
        }
    }
    compared
}

#[test]
fn positions_alone_equal_the_full_steps() {
    let mut m = read(fx::FOUR_BAR_TEXT);
    for (p, v) in [("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)] {
        m.set_param(p, v);
    }
    assert_eq!(positions_parity(&fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 }, &mut m, [0.0], 180), 180);
    let mut m = read(fx::SLIDER_CRANK_TEXT);
    for (p, v) in [("r", 1.0), ("l", 3.0), ("e", 0.4)] {
        m.set_param(p, v);
    }
    assert_eq!(positions_parity(&fx::SliderCrank { r: 1.0, l: 3.0, e: 0.4 }, &mut m, [0.0], 180), 180);
    let mut m = read(fx::RHOMBIC_DRIVE_TEXT);
    assert_eq!(positions_parity(&fx::RhombicDrive::default(), &mut m, [0.0], 180), 180);
    let mut dense = read(&dense_text(fx::RHOMBIC_DRIVE_TEXT, "RhombicDrive", "RhombicDriveDense"));
    assert_eq!(positions_parity(&fx::RhombicDriveDense::default(), &mut dense, [0.0], 180), 180);
    let n = positions_parity(&fx::FiveBar::default(), &mut read(fx::FIVE_BAR_TEXT), [0.0, 0.4], 180);
    assert!(n > 0);
    let n = positions_parity(&fx::ClassFour::default(), &mut read(fx::CLASS_FOUR_TEXT), [0.0], 180);
    assert!(n > 0);
    let mut dense = read(&dense_text(fx::CLASS_FOUR_TEXT, "ClassFour", "ClassFourDense"));
    assert!(positions_parity(&fx::ClassFourDense::default(), &mut dense, [0.0], 180) > 0);
    let gear = &mut read(fx::gear_lever::GEAR_LEVER_TEXT);
    assert!(positions_parity(&fx::gear_lever::GearLever::default(), gear, [0.0], 180) > 0);
    let edger = &mut read(fx::roller_edger::ROLLER_EDGER_TEXT);
    assert!(positions_parity(&fx::roller_edger::RollerEdger::default(), edger, [0.0], 180) > 0);
    let n = positions_parity(&fx::balancing::Balance::default(), &mut read(fx::balancing::BALANCE_TEXT), [0.0], 180);
    assert!(n > 0);
    // One sparse Newton block of 128 unknowns.
    let ring = &mut read(kinloop_bench::ring::RING);
    assert_eq!(positions_parity(&kinloop_bench::ring::Ring::default(), ring, [0.0], 24), 24);
}

/// A position the data do not determine fails the positions-only solve as the compiled
/// `position_flat` fails it: at phi = 0 the four-bar's joint B is 1e-11 from the rocker's pivot
/// D (`d = a + 1e-11`), equal links (`b = c`) about centres closer than `singular_tol` times a
/// link leave the dyad's orientation to the rounding. The dyad's solve finds a root there; the
/// test of its centres reports the block singular before it, with the same pivot ratio.
#[test]
fn positions_the_data_do_not_determine_fail_alike() {
    use kinloop_model::{StepError, StepFailure};
    use kinloop_runtime::generated::BlockFailure;
    let (a, b, c, d) = (1.0, 2.0, 2.0, 1.0 + 1e-11);
    let compiled = fx::FourBar { a, b, c, d };
    let mut m = read(fx::FOUR_BAR_TEXT);
    for (p, v) in [("a", a), ("b", b), ("c", c), ("d", d)] {
        m.set_param(p, v);
    }
    let cfg = NewtonConfig::default();
    let guess = compiled.guess_flat(&[0.0]);
    let c_err = compiled.position_flat(&[0.0], &guess, &cfg).unwrap_err();
    let kinloop::Error::Singular { pivot_ratio, .. } = c_err else { panic!("{c_err:?}") };
    let r_err = m.positions(&[0.0], &guess, &cfg).unwrap_err();
    let StepError::Block { block: 0, failure: StepFailure::Block(BlockFailure::Singular { pivot_ratio: r, .. }) } =
        r_err
    else {
        panic!("{r_err:?}")
    };
    assert_eq!(r.to_bits(), pivot_ratio.to_bits());
    // Away from it, both solve.
    assert!(m.positions(&[0.5], &guess, &cfg).is_ok() && compiled.position_flat(&[0.5], &guess, &cfg).is_ok());
}

/// A mechanism of extreme size, whose closed forms' squared lengths leave the range of `f64`
/// (beyond about `1e±144`): the compiled mechanism solves it again by Newton over the whole
/// system (`kinloop::__gen::rescue`), and so does the model, a step and a sweep. The four-bar
/// and the slider-crank at sizes `k` from `1e-300` to `1e300` against the compiled ones, to the
/// bit: both run the runtime's one whole-system solve (`whole_position`) on residuals and
/// Jacobians that are the same to the bit, and the analogs at the same position.
#[test]
fn a_mechanism_of_extreme_size_is_solved_as_the_compiled_one() {
    let cfg = NewtonConfig::default();
    for k in [1e-300, 1e-200, 1e-150, 1e150, 1e200, 1e300] {
        let four_bar = fx::FourBar { a: k, b: 3.0 * k, c: 2.5 * k, d: 3.2 * k };
        let mut model = common::read(fx::FOUR_BAR_TEXT);
        common::set(&mut model, &[("a", k), ("b", 3.0 * k), ("c", 2.5 * k), ("d", 3.2 * k)]);
        let slider = fx::SliderCrank { r: k, l: 3.0 * k, e: 0.4 * k };
        let mut slider_model = common::read(fx::SLIDER_CRANK_TEXT);
        common::set(&mut slider_model, &[("r", k), ("l", 3.0 * k), ("e", 0.4 * k)]);
        for x in [0.5, 2.0, 4.0] {
            let c = four_bar.kinematics_flat(&[x], &four_bar.guess_flat(&[x]), &cfg).expect("compiled four-bar");
            let m = model.solve(&[x]).unwrap_or_else(|e| panic!("four-bar at size {k:e}, phi {x}: {e}"));
            assert_eq!(
                (c.q.to_vec(), c.dq.concat(), c.out.to_vec()),
                (m.q.clone(), m.dq.clone(), m.out.clone()),
                "{k:e} {x}"
            );
            let c = slider.kinematics_flat(&[x], &slider.guess_flat(&[x]), &cfg).expect("compiled slider-crank");
            let m = slider_model.solve(&[x]).unwrap_or_else(|e| panic!("slider-crank at size {k:e}, phi {x}: {e}"));
            assert_eq!((c.q.to_vec(), c.dq.concat()), (m.q.clone(), m.dq.clone()), "{k:e} {x}");
        }
        let guess = four_bar.guess_flat(&[0.0]);
        let table = model.sweep(&[0.0], &[TAU], 37, &guess).expect("sweep").table().expect("a whole turn");
        assert_eq!(table.rows.len(), 37, "{k:e}");
    }
}

declared! {
    CHAIN_TEXT =>
    /// Five four-bars, each driven by the last one's rocker: five closed-form blocks in turn.
    pub struct Chain {
        params a = 1.0, b = 3.5, c = 3.0, d = 4.0;
        input phi;
        unknowns b1 = 0.5, g1 = 1.5, b2 = 0.5, g2 = 1.5, b3 = 0.5, g3 = 1.5, b4 = 0.5, g4 = 1.5,
            b5 = 0.5, g5 = 1.5;
        loop l1: a @ phi + b @ b1 == (d, 0) + c @ g1;
        loop l2: a @ g1 + b @ b2 == (d, 0) + c @ g2;
        loop l3: a @ g2 + b @ b3 == (d, 0) + c @ g3;
        loop l4: a @ g3 + b @ b4 == (d, 0) + c @ g4;
        loop l5: a @ g4 + b @ b5 == (d, 0) + c @ g5;
    }
}

/// A chain of five four-bars beyond the closed forms' sizes, where Newton over its ten unknowns
/// at once fails from the declared guess at most inputs and the blocks are solved in turn: the
/// model's position is the compiled one's to the bit where the compiled step solves, and where
/// it fails, the model fails in the same block. Two chains: one whose rockers all swing through
/// a whole turn of their cranks (crank 1, coupler 3.5, rocker 3, frame 4), one whose loops
/// (crank 2, coupler 3, rocker 1.5, frame 2) cannot close at some inputs, in one block or
/// another.
#[test]
fn a_chain_of_blocks_of_extreme_size_is_solved_in_turn_as_the_compiled_one() {
    use kinloop_model::StepError;
    let cfg = NewtonConfig::default();
    let (mut solved, mut failed_later) = (0, 0);
    for lengths in [[1.0, 3.5, 3.0, 4.0], [2.0, 3.0, 1.5, 2.0]] {
        for k in [1e-300, 1e-200, 1e200, 1e300] {
            let [a, b, c, d] = lengths.map(|l| l * k);
            let compiled = Chain { a, b, c, d };
            let mut model = read(CHAIN_TEXT);
            common::set(&mut model, &[("a", a), ("b", b), ("c", c), ("d", d)]);
            for i in 0..24 {
                let x = [-3.0 + 0.25 * f64::from(i) + 0.01];
                let guess = compiled.guess_flat(&x);
                let c = compiled.kinematics_flat(&x, &guess, &cfg);
                let m = model.kinematics(&x, &guess, &cfg);
                match (c, m) {
                    (Ok(c), Ok(m)) => {
                        assert_eq!(c.q.to_vec(), m.q, "{lengths:?} at size {k:e}, phi {}", x[0]);
                        solved += 1;
                    }
                    (Err(c), Err(StepError::Block { block, .. })) => {
                        let want = c.location().and_then(|at| at.block.as_ref().map(|b| b.0));
                        assert_eq!(want, Some(block), "{lengths:?} at size {k:e}, phi {}: {c}", x[0]);
                        failed_later += usize::from(block > 0);
                    }
                    (c, m) => panic!("{lengths:?} at size {k:e}, phi {}: {c:?} against {m:?}", x[0]),
                }
            }
        }
    }
    assert!(solved > 100 && failed_later > 20, "{solved} solved, {failed_later} failed after the first block");
}

/// The gear-lever's polar length beyond the closed forms' sizes, from guesses of either sign of
/// its length: the model's positions alone are the compiled ones to the bit (both normalise the
/// pin's direction with the runtime's `polar_norm`, which now refuses an overflowed square, and
/// keep the closed form's root of the guess's sign in the rescue), and the length has the
/// guess's sign as at size 1.
#[test]
fn a_polar_length_of_extreme_size_keeps_its_guess_s_sign_as_the_compiled_one() {
    let cfg = NewtonConfig::default();
    for k in [1e-300, 1e-200, 1e160, 1e200, 1e300] {
        let compiled = fx::gear_lever::GearLever { l_c: 2.0 * k, l_p: 1.3 * k, u: 3.0 };
        let mut model = read(fx::gear_lever::GEAR_LEVER_TEXT);
        common::set(&mut model, &[("l_c", 2.0 * k), ("l_p", 1.3 * k)]);
        for i in 0..12 {
            let x = [-3.0 + 0.5 * f64::from(i) + 0.01];
            for guess in [[3.3 * k, 0.0], [-3.3 * k, 0.0], [0.5 * k, 2.25], [-0.5 * k, -2.25]] {
                let (c, _) = compiled.position_flat(&x, &guess, &cfg).unwrap_or_else(|e| panic!("{k:e} {x:?}: {e}"));
                let m = model.positions(&x, &guess, &cfg).unwrap_or_else(|e| panic!("{k:e} {x:?}: {e:?}")).to_vec();
                assert_eq!(c.to_vec(), m, "size {k:e}, alpha {}, from {guess:?}", x[0]);
                assert_eq!(c[0] > 0.0, guess[0] > 0.0, "size {k:e}, alpha {}, from {guess:?}: {c:?}", x[0]);
            }
        }
    }
}

declared! {
    SCALED_POLAR_TEXT =>
    /// The gear-lever's pin as a ratio `s` of a rod of length `l` and its angle: a closed form
    /// whose squared direction is a product of four lengths.
    pub struct ScaledPolar {
        params l_c = 2.0, l_p = 1.3, u = 3.0, l = 2.5;
        input alpha;
        unknowns s = 1.0, phi = 0;
        let pin = (l_c * sin(alpha), l_c * cos(alpha))
                + (l_p * sin((1 - u) * alpha), l_p * cos((1 - u) * alpha));
        loop oab: pin == s * (l * sin(phi), l * cos(phi));
    }
}

/// Where that closed form's square overflows inside the closed forms' sizes (`1e80`, `1e100`)
/// and beyond them (`1e200`), the model solves the position again by Newton as the compiled
/// mechanism does: its positions alone and its kinematics the compiled ones, to the bit.
#[test]
fn a_closed_form_overflowed_inside_the_sizes_is_solved_as_the_compiled_one() {
    let cfg = NewtonConfig::default();
    for k in [1e80, 1e100, 1e200] {
        let compiled = ScaledPolar { l_c: 2.0 * k, l_p: 1.3 * k, u: 3.0, l: 2.5 * k };
        let mut model = read(SCALED_POLAR_TEXT);
        common::set(&mut model, &[("l_c", 2.0 * k), ("l_p", 1.3 * k), ("l", 2.5 * k)]);
        for i in 0..12 {
            let x = [-3.0 + 0.5 * f64::from(i) + 0.01];
            let guess = compiled.guess_flat(&x);
            let (c, _) = compiled.position_flat(&x, &guess, &cfg).unwrap_or_else(|e| panic!("{k:e} {x:?}: {e}"));
            let m = model.positions(&x, &guess, &cfg).unwrap_or_else(|e| panic!("{k:e} {x:?}: {e:?}")).to_vec();
            assert_eq!(c.to_vec(), m, "positions at size {k:e}, alpha {}", x[0]);
            let c = compiled.kinematics_flat(&x, &guess, &cfg).unwrap_or_else(|e| panic!("{k:e} {x:?}: {e}"));
            let m = model.kinematics(&x, &guess, &cfg).unwrap_or_else(|e| panic!("{k:e} {x:?}: {e:?}"));
            assert_eq!((c.q.to_vec(), c.dq.concat()), (m.q.clone(), m.dq.clone()), "size {k:e}, alpha {}", x[0]);
        }
    }
}

declared! {
    ROD_SQUARED_TEXT =>
    /// The offset slider-crank by its rod's length squared alone: a Newton block of one length
    /// whose equation's terms are squared lengths.
    #[kinloop(newton)]
    pub struct RodSquared {
        params r = 1.0, l = 3.2, e = 0.4;
        input phi;
        unknowns x = l;
        eq rod: (x - r * cos(phi)) ^ 2 + (r * sin(phi) - e) ^ 2 == l * l;
    }
}

/// An equation whose terms are too small for `f64` fails the model's solve as it fails the
/// compiled one: at sizes `1e-160` (a subnormal magnitude, `3e-319`), `1e-200` and `1e-300`
/// (underflowed to zero) both refuse it with the same error (`Error::Underflow`, the same
/// magnitude to the bit); at `1e-156` (a subnormal magnitude fine enough for the tolerance) and
/// at size 1 both solve it, to the bit (the runtime's Newton on residuals and Jacobians that
/// are the same to the bit). The compiled block accepted positions `4e-5` of the size off at
/// `1e-160`, the model too, each with the other's error.
#[test]
fn an_equation_too_small_for_f64_fails_as_the_compiled_one() {
    let cfg = NewtonConfig::default();
    for k in [1.0, 1e-156, 1e-160, 1e-200, 1e-300] {
        let compiled = RodSquared { r: k, l: 3.2 * k, e: 0.4 * k };
        let mut model = common::read(ROD_SQUARED_TEXT);
        common::set(&mut model, &[("r", k), ("l", 3.2 * k), ("e", 0.4 * k)]);
        for x in [0.3, 1.8, 3.3, 4.8] {
            let guess = compiled.guess_flat(&[x]);
            let c = compiled.kinematics_flat(&[x], &guess, &cfg);
            let m = model.kinematics(&[x], &guess, &cfg).map(|s| s.q.clone());
            match (c, m) {
                (Ok(c), Ok(m)) => {
                    assert!(k >= 1e-156, "size {k:e}, phi {x}: solved");
                    assert_eq!(c.q.map(f64::to_bits).to_vec(), m.iter().map(|v| v.to_bits()).collect::<Vec<_>>());
                }
                (Err(c), Err(m)) => {
                    let m = model.explain(&[x], &guess, &cfg, m);
                    assert!(matches!(c, kinloop::Error::Underflow { .. }), "size {k:e}, phi {x}: {c}");
                    assert_eq!(c, m, "size {k:e}, phi {x}");
                }
                (c, m) => panic!("size {k:e}, phi {x}: compiled {:?}, run time {m:?}", c.map(|k| k.q)),
            }
        }
    }
}

/// An equation whose terms are too large for `f64` fails the model's solve as it fails the
/// compiled one, its state and its positions alone, and a sweep at its first sample: at sizes
/// `3.5e153` (a magnitude beyond `f64::MAX`, where at some inputs the terms themselves are
/// not), `1e160`, `1e200` and `1e300` (terms beyond `f64::MAX`, the residual `inf - inf`) both
/// refuse it with the same error, `Error::Overflow` of the equation, whose step failure the
/// model's own record says is too large for `f64`; at size 1 and `2e153` (the largest
/// magnitude `1.6e308`) both solve it, to the bit. Both said the equation left its domain from
/// `1e160`, and at `3.5e153` that the loops could not close.
#[test]
fn an_equation_too_large_for_f64_fails_as_the_compiled_one() {
    let cfg = NewtonConfig::default();
    let bits = |q: &[f64]| q.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    for k in [1.0, 2e153, 3.5e153, 1e160, 1e200, 1e300] {
        let compiled = RodSquared { r: k, l: 3.2 * k, e: 0.4 * k };
        let mut model = common::read(ROD_SQUARED_TEXT);
        common::set(&mut model, &[("r", k), ("l", 3.2 * k), ("e", 0.4 * k)]);
        let refused = |c: &kinloop::Error, m: kinloop::Error, what: &str| {
            assert!(k > 2e153, "size {k:e}, {what}: {c}");
            assert!(
                matches!(c, kinloop::Error::Overflow { what: kinloop::Computed::Equation, name, .. } if name == "rod"),
                "{c}"
            );
            assert_eq!(*c, m, "size {k:e}, {what}");
        };
        for x in [0.3, 1.8, 3.3, 4.8] {
            let guess = compiled.guess_flat(&[x]);
            match (compiled.kinematics_flat(&[x], &guess, &cfg), model.kinematics(&[x], &guess, &cfg)) {
                (Ok(c), Ok(m)) => assert_eq!(bits(&c.q), bits(&m.q), "size {k:e}, phi {x}"),
                (Err(c), Err(m)) => {
                    assert!(m.to_string().contains("too large for f64"), "{m}");
                    refused(&c, model.explain(&[x], &guess, &cfg, m), "state");
                }
                (c, m) => panic!("size {k:e}, phi {x}: compiled {:?}, run time {m:?}", c.map(|k| k.q)),
            }
            match (compiled.position_flat(&[x], &guess, &cfg), model.positions(&[x], &guess, &cfg).map(bits)) {
                (Ok((c, _)), Ok(m)) => assert_eq!(bits(&c), m, "size {k:e}, phi {x}"),
                (Err(c), Err(m)) => refused(&c, model.explain(&[x], &guess, &cfg, m), "positions"),
                (c, m) => panic!("size {k:e}, phi {x}: compiled {:?}, run time {m:?}", c.map(|(q, _)| q)),
            }
        }
        if k >= 1e160 {
            let (from, to) = ([0.3], [0.3 + TAU]);
            let guess = compiled.guess_flat(&from);
            let c_sweep = kinloop::Sweep::<_, kinloop::Kin<1, 1, 0>, 1, 1, 0>::new(&compiled, from, to, 73, guess);
            let c_first = c_sweep.unwrap().next().expect("a sample").unwrap_err();
            let m_first = model.sweep(&from, &to, 73, &guess).unwrap().next().expect("a sample").unwrap_err();
            refused(&c_first, m_first, "sweep");
        }
    }
}

/// A four-bar driven by its rocker at the limit position of its input (crank 1 shortest, rocker
/// 3 the input, coupler 3.5, frame 4: coupler and crank in line at `acos(4.75 / 24)`), and one
/// and two units in the last place inside it, at sizes beyond the closed forms': the model's
/// positions alone are the compiled `position_flat`'s to the bit, and its kinematics the
/// compiled ones (the same state, or the same error: singular where the position is the
/// double root). Both solve it by the runtime's one whole-system Newton, which reaches a double
/// root only linearly: both failed as singular, where at size 1 the closed form gives the
/// position (`tests/kinematics/limit_positions_extreme_scales.rs` checks it there against the
/// construction and size 1).
#[test]
fn a_limit_position_of_extreme_size_is_solved_as_the_compiled_one() {
    let cfg = NewtonConfig::default();
    let [a, b, c, d] = [3.0f64, 3.5, 1.0, 4.0];
    let limit = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    for k in [1.0, 1e-300, 1e-200, 1e-160, 1e160, 1e200, 1e300] {
        let compiled = fx::FourBar { a: a * k, b: b * k, c: c * k, d: d * k };
        let mut model = common::read(fx::FOUR_BAR_TEXT);
        common::set(&mut model, &[("a", a * k), ("b", b * k), ("c", c * k), ("d", d * k)]);
        for x in [limit, limit.next_down(), limit.next_down().next_down()] {
            let guess = compiled.guess_flat(&[x]);
            let got = model.positions(&[x], &guess, &cfg).unwrap_or_else(|e| panic!("size {k:e}, phi {x}: {e:?}"));
            let got: Vec<u64> = got.iter().map(|v| v.to_bits()).collect();
            let (want, _) = compiled
                .position_flat(&[x], &guess, &cfg)
                .unwrap_or_else(|e| panic!("compiled at size {k:e}, phi {x}: {e}"));
            assert_eq!(got, want.map(f64::to_bits), "size {k:e}, phi {x}");
            let c = compiled.kinematics_flat(&[x], &guess, &cfg);
            let m = model.kinematics(&[x], &guess, &cfg).map(|s| (s.q.clone(), s.dq.clone()));
            match (c, m) {
                (Ok(c), Ok(m)) => assert_eq!((c.q.to_vec(), c.dq.concat()), m, "size {k:e}, phi {x}"),
                (Err(c), Err(m)) => {
                    let m = model.explain(&[x], &guess, &cfg, m);
                    assert!(matches!(c, kinloop::Error::Singular { .. }), "size {k:e}, phi {x}: {c}");
                    assert_eq!(c, m, "size {k:e}, phi {x}");
                }
                (c, m) => panic!("size {k:e}, phi {x}: compiled {:?}, run time {m:?}", c.map(|k| k.q)),
            }
        }
    }
}

/// The four-bar driven by its rocker above (rocker 3, coupler 3.5, crank 1, frame 4) at 12
/// inputs over each of its rocker's two ranges, `0.02` rad inside their limits, from its
/// declared guess and from that guess's mirror (the two assembly modes at size 1), at sizes
/// beyond the closed forms': the model's positions are the compiled ones to the bit (the same
/// whole-system solve, keeping the same closed-form blocks' modes), and both are size 1's
/// within `1e-12` rad (the lengths' rounding, `k` not a power of two, through a position at
/// least `0.02` rad from the fold: a few `1e-15`, the other mode over `0.2` rad away). Both
/// gave the other assembly mode than size 1 at 14 of the 24 inputs from one guess or the other.
#[test]
fn a_mechanism_of_extreme_size_keeps_its_assembly_mode_as_the_compiled_one() {
    let cfg = NewtonConfig::default();
    let [a, b, c, d] = [3.0f64, 3.5, 1.0, 4.0];
    let (lo, hi) = ((25.0f64 / 32.0).acos() + 0.02, (19.0f64 / 96.0).acos() - 0.02);
    let range: Vec<f64> = (0..12).map(|i| lo + (hi - lo) * f64::from(i) / 11.0).collect();
    let inputs: Vec<f64> = range.iter().map(|x| -x).chain(range.iter().copied()).collect();
    let one = fx::FourBar { a, b, c, d };
    let declared = one.guess_flat(&[0.0]);
    for k in [1e-300, 1e-200, 1e-160, 1e160, 1e200, 1e300] {
        let compiled = fx::FourBar { a: a * k, b: b * k, c: c * k, d: d * k };
        let mut model = common::read(fx::FOUR_BAR_TEXT);
        common::set(&mut model, &[("a", a * k), ("b", b * k), ("c", c * k), ("d", d * k)]);
        for &x in &inputs {
            for guess in [declared, declared.map(|q| -q)] {
                let (base, _) = one.position_flat(&[x], &guess, &cfg).expect("size 1");
                let (want, _) = compiled
                    .position_flat(&[x], &guess, &cfg)
                    .unwrap_or_else(|e| panic!("compiled at size {k:e}, phi {x}: {e}"));
                let got = model.positions(&[x], &guess, &cfg).unwrap_or_else(|e| panic!("size {k:e}, phi {x}: {e:?}"));
                assert_eq!(got.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), want.map(f64::to_bits), "{k:e} {x}");
                let off = (0..2).fold(0.0f64, |o, u| o.max((want[u] - base[u]).abs()));
                assert!(off <= 1e-12, "size {k:e}, phi {x} from {guess:?}: {want:?}, size 1 {base:?}");
            }
        }
    }
}

declared! {
    INCLINED_SLIDER_CRANK_TEXT =>
    /// A slider-crank on an inclined slide: crank `r` about `(0, h)`, rod `l` from the crank pin
    /// to the slider `x (u, v)` on the slide through the origin along the unit vector `(u, v)`
    /// (an angle and a slider in closed form, every coefficient an expression).
    pub struct InclinedSliderCrank {
        params r, l, h, u, v;
        input phi;
        unknowns psi = 2.0, x = 0;
        loop ocb: (0, h) + r @ phi == x * (u, v) + l @ psi;
    }
}

/// The model against the compiled mechanism at input `x` from `guess`: its positions alone the
/// compiled `position_flat`'s to the bit, its kinematics the compiled ones (the same state, or
/// the same error), or both the same error. Returns whether the positions were solved.
fn step_parity<M, const N: usize, const NI: usize, const NO: usize>(
    what: &str,
    compiled: &M,
    model: &mut Model,
    x: [f64; NI],
    guess: [f64; N],
    cfg: &NewtonConfig,
) -> bool
where
    M: Mechanism<N, NI, NO>,
{
    let solved = match (compiled.position_flat(&x, &guess, cfg), model.positions(&x, &guess, cfg).map(<[f64]>::to_vec))
    {
        (Ok((c, _)), Ok(m)) => {
            assert_eq!(c.map(f64::to_bits).to_vec(), m.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), "{what}");
            true
        }
        (Err(c), Err(m)) => {
            assert_eq!(c, model.explain(&x, &guess, cfg, m), "{what}");
            false
        }
        (c, m) => panic!("{what}: compiled {c:?}, run time {m:?}"),
    };
    match (compiled.kinematics_flat(&x, &guess, cfg), model.kinematics(&x, &guess, cfg).map(|s| s.q.clone())) {
        (Ok(c), Ok(m)) => assert_eq!(c.q.to_vec(), m, "{what}"),
        (Err(c), Err(m)) => assert_eq!(c, model.explain(&x, &guess, cfg, m), "{what}"),
        (c, m) => panic!("{what}: compiled kinematics {:?}, run time {m:?}", c.map(|k| k.q)),
    }
    solved
}

/// One-angle closed forms at their limit positions (`tests/errors/limit_of_one_angle.rs` checks
/// the compiled ones against the construction), closing exactly in decimal in metres,
/// millimetres and micrometres and missing by 500 times the tolerance, under the default
/// tolerance and at the rounding floor: the model's verdict is the compiled one's, and so are
/// its positions and errors (a miss judged in the magnitude of the equation's terms, which both
/// compute only where the root fails). The offset slider-crank's rod angle is an angle equation
/// with a folded coefficient (`l sin psi = r sin phi - e`: `r - e = l` at `phi = pi/2`); the
/// inclined one's an angle and a slider with no coefficient folded (the crank pin `(r, h)` at
/// `u h - v r = l` from the slide at `phi = 0`).
#[test]
fn a_one_angle_limit_is_judged_as_the_compiled_one() {
    let offset = [[0.406, 0.0003, 0.4057], [406.0, 0.3, 405.7], [406000.0, 300.0, 405700.0]];
    let inclined = [[0.3, 0.0000012, 0.400002], [300.0, 0.0012, 400.002], [300000.0, 1.2, 400002.0]];
    let mut solved = 0;
    for cfg in [NewtonConfig::default(), NewtonConfig::default().with_residual_tol(0.0)] {
        let tol = cfg.residual_tol.max(16.0 * f64::EPSILON);
        for (k, [r, l, e]) in offset.into_iter().enumerate() {
            for l in [l, l - 500.0 * tol * (r + e + l)] {
                let compiled = fx::SliderCrank { r, l, e };
                let mut model = common::read(fx::SLIDER_CRANK_TEXT);
                common::set(&mut model, &[("r", r), ("l", l), ("e", e)]);
                let what = format!("offset, unit {k}, rod {l}, tolerance {:e}", cfg.residual_tol);
                solved += step_parity(&what, &compiled, &mut model, [FRAC_PI_2], [1.5, 0.0], &cfg) as usize;
            }
        }
        for (k, [r, l, h]) in inclined.into_iter().enumerate() {
            let (u, v) = (0.6, 0.8);
            for l in [l, l - 500.0 * tol * (v * (r + l) + u * (h + r + l))] {
                let compiled = InclinedSliderCrank { r, l, h, u, v };
                let mut model = common::read(INCLINED_SLIDER_CRANK_TEXT);
                common::set(&mut model, &[("r", r), ("l", l), ("h", h), ("u", u), ("v", v)]);
                let what = format!("inclined, unit {k}, rod {l}, tolerance {:e}", cfg.residual_tol);
                solved += step_parity(&what, &compiled, &mut model, [0.0], [2.0, 0.0], &cfg) as usize;
            }
        }
    }
    // Every design closing at its limit, none missing it.
    assert_eq!(solved, 12);
}

declared! {
    FOUR_BAR_NEWTON_TEXT =>
    /// The fixtures' four-bar solved by Newton: one block of two angles.
    #[kinloop(newton)]
    pub struct FourBarNewton {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

/// A Newton block whose coupler of `1e-20` closes the loop at every angle (unit crank, rocker
/// and frame at `fl(π/3)`: `tests/solver/closed_form.rs` computes the loop in plain f64): the
/// iteration carries the coupler's angle turns away, and the block, probed with that angle
/// turned, is the singular position. The run-time model, on the runtime's Newton, fails with
/// the compiled block's error, at every size; both returned the coupler at `-5468` rad.
#[test]
fn a_newton_angle_every_value_closes_is_singular_read_and_compiled_alike() {
    let cfg = NewtonConfig::default();
    let phi = std::f64::consts::PI / 3.0;
    for k in [1.0, 1e-3, 1e3] {
        let compiled = FourBarNewton { a: k, b: 1e-20 * k, c: k, d: k };
        let mut model = common::read(FOUR_BAR_NEWTON_TEXT);
        common::set(&mut model, &[("a", k), ("b", 1e-20 * k), ("c", k), ("d", k)]);
        let guess = [0.5, 1.5];
        let c = compiled.kinematics_flat(&[phi], &guess, &cfg).map(|k| k.q).unwrap_err();
        assert!(matches!(c, kinloop::Error::Singular { .. }), "size {k:e}: {c}");
        let m = model.kinematics(&[phi], &guess, &cfg).map(|s| s.q.clone()).unwrap_err();
        assert_eq!(model.explain(&[phi], &guess, &cfg, m), c, "size {k:e}");
    }
}
