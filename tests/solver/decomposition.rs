//! The block decomposition (maximum matching + Tarjan's BLT order) of the papers' mechanisms,
//! and its correctness: results with the decomposition equal results without it
//! (`#[kinloop(dense)]`, every unknown in one Newton block) to 1e-12 over full crank turns, and
//! both agree with independent references: the acceleration analogs with Richardson-extrapolated
//! central differences of the velocity analogs, the velocity analogs with differences of the
//! positions.

use kinloop::{Kin, Sensitivities};
use std::f64::consts::PI;

use kinloop_fixtures::{ClassFour, ClassFourDense, RhombicDrive, RhombicDriveDense};

use crate::support::{newton_to_fine_step, richardson_first, tol};

#[test]
fn class_four_is_one_coupled_four_unknown_block() {
    // The crank is the input (computed directly); the Assur group of class IV cannot be split:
    // both loops are needed at once for all four angles.
    let blocks = ClassFour::BLOCKS;
    assert_eq!(blocks.len(), 1, "{}", ClassFour::DECOMPOSITION);
    assert_eq!(blocks[0].unknowns, &["th1", "th2", "psi1", "psi2"][..]);
    assert_eq!(blocks[0].equations, &["acdb.x", "acdb.y", "aefb.x", "aefb.y"][..]);
    assert!(!blocks[0].linear);
    assert_eq!(
        ClassFour::DECOMPOSITION,
        "ClassFour: 4 unknowns, 4 scalar equations, 1 input (mobility W = 1); 1 block in solve order\n  \
         block 0 (Newton, 4x4): th1, th2, psi1, psi2 <- acdb.x, acdb.y, aefb.x, aefb.y"
    );
    assert_eq!(ClassFourDense::BLOCKS.len(), 1);
    assert!(ClassFourDense::DECOMPOSITION.contains("dense: decomposition disabled"));
    // The dense twin is the gallery's mechanism: the same names and parameter values.
    assert_eq!(ClassFourDense::default().params_flat(), ClassFour::default().params_flat());
    assert_eq!(ClassFourDense::PARAMS, ClassFour::PARAMS);
    assert_eq!(ClassFourDense::EQUATIONS, ClassFour::EQUATIONS);
    assert_eq!(ClassFourDense::OUTPUTS, ClassFour::OUTPUTS);
}

#[test]
fn rhombic_drive_splits_into_its_groups_with_sliders_in_closed_form() {
    let blocks = RhombicDrive::BLOCKS;
    assert_eq!(blocks.len(), 4, "{}", RhombicDrive::DECOMPOSITION);
    // Each block is one unknown from one loop: the working group (oabco: phi2, x_c) and the
    // displacer group (oadff1o: phi4, x_f) never share a block.
    for b in blocks {
        assert_eq!(b.unknowns.len(), 1, "{b:?}");
        let group = if ["phi2", "x_c"].contains(&&*b.unknowns[0]) { "oabco." } else { "oadff1o." };
        assert!(b.equations.iter().all(|e| e.starts_with(group)), "{b:?}");
        // Slider coordinates appear linearly: one linear solve, no iteration.
        assert_eq!(b.linear, b.unknowns[0].starts_with("x_"), "{b:?}");
    }
    let at = |u: &str| blocks.iter().position(|b| b.unknowns[0] == u).unwrap();
    assert!(at("phi2") < at("x_c") && at("phi4") < at("x_f"));
    // The rod angle comes from the y projection (the slider is not in it), the slider from x.
    assert_eq!(blocks[at("phi2")].equations, &["oabco.y"][..]);
    assert_eq!(blocks[at("x_c")].equations, &["oabco.x"][..]);
    let text = RhombicDrive::DECOMPOSITION;
    assert!(
        text.starts_with("RhombicDrive: 4 unknowns, 4 scalar equations, 1 input (mobility W = 1); 4 blocks"),
        "{text}"
    );
    assert!(text.contains("(closed form, angle equation): phi2 <- oabco.y"), "{text}");
    assert!(text.contains("(linear, 1x1): x_f <- oadff1o.x"), "{text}");
    assert_eq!(text.lines().count(), 5, "{text}");

    assert_eq!(RhombicDriveDense::BLOCKS.len(), 1);
    assert_eq!(RhombicDriveDense::BLOCKS[0].unknowns.len(), 4);
}

/// `|a - b| <= tol * max(1, |b|)`, with a message naming what differs.
fn assert_all_close(what: &str, a: &[f64], b: &[f64], tol: f64) {
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        assert_close!(*x, *y, rel = tol, "{what}[{k}]");
    }
}

/// The decomposed and the dense solve agree to 1e-12: positions, analogs, outputs (flat: `x`, `y`
/// of each point, then the scalar outputs) and the outputs' analogs.
fn assert_same_as_dense<const N: usize, const NO: usize>(at: &str, a: &Kin<N, 1, NO>, b: &Kin<N, 1, NO>) {
    let first = |v: &[[f64; 1]]| v.iter().map(|d| d[0]).collect::<Vec<_>>();
    let second = |v: &[[[f64; 1]; 1]]| v.iter().map(|d| d[0][0]).collect::<Vec<_>>();
    assert_all_close(&format!("q {at}"), &a.q, &b.q, tol::SOLVE);
    assert_all_close(&format!("dq {at}"), &first(&a.dq), &first(&b.dq), tol::SOLVE);
    assert_all_close(&format!("d2q {at}"), &second(&a.d2q), &second(&b.d2q), tol::SOLVE);
    assert_all_close(&format!("outputs {at}"), &a.out, &b.out, tol::SOLVE);
    assert_all_close(&format!("output analogs {at}"), &first(&a.dout), &first(&b.dout), tol::SOLVE);
    assert_all_close(&format!("output acceleration analogs {at}"), &second(&a.d2out), &second(&b.d2out), tol::SOLVE);
}

#[test]
fn rhombic_drive_decomposed_equals_dense_over_a_turn() {
    let (m, d) = (RhombicDrive::default(), RhombicDriveDense::default());
    let (mut gm, mut gd) = (m.guess(0.0), d.guess(0.0));
    for k in 0..=720 {
        let phi1 = 2.0 * PI * k as f64 / 720.0;
        let a = m.kinematics(phi1, &gm).unwrap_or_else(|e| panic!("decomposed at {phi1}: {e}"));
        let b = d.kinematics(phi1, &gd).unwrap_or_else(|e| panic!("dense at {phi1}: {e}"));
        gm = a.q;
        gd = b.q;
        assert_same_as_dense(&format!("at phi1 = {phi1}"), &a.flat, &b.flat);
        // The decomposition is not a different answer to the same question only by accident:
        // both satisfy the loops.
        assert!(m.residual(phi1, &a.q).iter().all(|r| r.abs() < tol::SOLVE));
    }
}

#[test]
fn class_four_decomposed_equals_dense_and_assembles_over_a_turn() {
    let (m, d) = (ClassFour::default(), ClassFourDense::default());
    let first = m.solve(0.0).expect("assembles at phi = 0");
    let (mut gm, mut gd) = (first.q, d.solve(0.0).expect("dense assembles at phi = 0").q);
    let fine = newton_to_fine_step();
    for k in 0..=720 {
        let phi = 2.0 * PI * k as f64 / 720.0;
        let a = m.kinematics(phi, &gm).unwrap_or_else(|e| panic!("decomposed at {phi}: {e}"));
        let b = d.kinematics(phi, &gd).unwrap_or_else(|e| panic!("dense at {phi}: {e}"));
        let at = format!("at phi = {phi}");
        assert_same_as_dense(&at, &a.flat, &b.flat);
        let (qa, va): ([f64; 4], [f64; 4]) = (a.q.into(), a.dq.into());

        // Independent check of the velocity analogs: Richardson-extrapolated central
        // differences of positions solved to rounding (h = 1e-3: see `tol::FD_FIRST`). The
        // acceleration analogs are checked against differences of these (exact) velocity analogs
        // in `acceleration_analogs_are_differences_of_the_velocity_analogs`, and against the
        // 50-digit reference in `tests/kinematics/reference_mpmath.rs`.
        let position = |x: f64| -> [f64; 4] { m.position_with(x, &a.q, &fine).expect("phi +- h").0.into() };
        let fd: Vec<f64> = (0..4).map(|u| richardson_first(|x| position(x)[u], phi, 1e-3)).collect();
        assert_all_close(&format!("dq vs finite differences {at}"), &va, &fd, tol::FD_FIRST);
        // Continuity along the sweep: the same assembly mode all the way round.
        let prev: [f64; 4] = gm.into();
        assert!(qa.iter().zip(&prev).all(|(x, y)| (x - y).abs() < 0.2), "branch jump {at}: {qa:?} after {prev:?}");
        gm = a.q;
        gd = b.q;
    }
    // Back to the start after a full turn.
    let (end, start): ([f64; 4], [f64; 4]) = (gm.into(), first.q.into());
    assert_all_close("q after a full turn", &end, &start, 1e-9);
}

/// Richardson-extrapolated central differences of the velocity analogs (of the unknowns and of
/// the outputs) against the acceleration analogs, at `samples` inputs over a turn. The velocity
/// analogs are exact to rounding (~1e-15), so with h = 1e-2 the truncation (~h^4/30 |q^(5)| ~
/// 1e-10 here) dominates and the reference is good to ~1e-9, relative (absolute near zero).
fn assert_second_analogs_match_differences<M, const N: usize, const NO: usize>(m: &M, guess: [f64; N], samples: usize)
where
    M: kinloop::Mechanism<N, 1, NO>,
{
    let h = 1e-2;
    let mut q = guess;
    for k in 0..samples {
        let x = 0.05 + 2.0 * PI * k as f64 / samples as f64;
        let s = m.kinematics_flat(&[x], &q, &Default::default()).unwrap();
        q = s.q;
        let at = |x: f64| m.kinematics_flat(&[x], &s.q, &Default::default()).unwrap();
        for u in 0..N {
            let fd = richardson_first(|x| at(x).dq[u][0], x, h);
            assert_close!(s.d2q[u][0][0], fd, rel = 1e-8, "d2{} at {x}: {} vs {fd}", M::UNKNOWNS[u], s.d2q[u][0][0]);
        }
        for o in 0..NO {
            let fd = richardson_first(|x| at(x).dout[o][0], x, h);
            assert_close!(s.d2out[o][0][0], fd, rel = 1e-8, "d2 output {o} at {x}: {} vs {fd}", s.d2out[o][0][0]);
        }
    }
}

#[test]
fn acceleration_analogs_are_differences_of_the_velocity_analogs() {
    let (r, rd) = (RhombicDrive::default(), RhombicDriveDense::default());
    assert_second_analogs_match_differences(&r, r.guess(0.05).into(), 48);
    assert_second_analogs_match_differences(&rd, rd.guess(0.05).into(), 48);
    let (c, cd) = (ClassFour::default(), ClassFourDense::default());
    assert_second_analogs_match_differences(&c, c.solve(0.05).unwrap().q.into(), 48);
    assert_second_analogs_match_differences(&cd, cd.solve(0.05).unwrap().q.into(), 48);
}
