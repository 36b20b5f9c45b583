//! The block decomposition (maximum matching + Tarjan's BLT order) of the papers' mechanisms,
//! and its correctness: results with the decomposition equal results without it
//! (`#[kinloop(dense)]`, every unknown in one Newton block) to 1e-12 over full crank turns.

use kinloop::{Kin, Sensitivities};
use std::f64::consts::PI;

#[allow(dead_code)]
#[path = "../examples/class_four.rs"]
mod class_four;

use class_four::ClassFour;

#[allow(dead_code)] // not every test uses every helper
mod support;

use support::close;

kinloop::mechanism! {
    /// The class IV mechanism of `examples/class_four.rs` (SEEDS 003), solved as one dense block.
    #[kinloop(dense)]
    #[kinloop(sensitivities)]
    pub struct ClassFourDense {
        params oa = 1.0, xb = 4.4, yb = 0.6, ac = 2.3, ae = 2.4, alpha_a = 0.84,
               bd = 1.6, bf = 3.5, alpha_b = 0.62, cd = 2.0, ef = 3.4;
        input phi;
        unknowns th1 = 1.4, th2 = 3.0, psi1 = -0.8, psi2 = -1.0;
        let a = oa @ phi;
        let b = (xb, yb);
        loop acdb: a + ac @ th1 + cd @ psi1 == b + bd @ th2;
        loop aefb: a + ae @ (th1 + alpha_a) + ef @ psi2 == b + bf @ (th2 + alpha_b);
        point c = a + ac @ th1;
        point e = a + ae @ (th1 + alpha_a);
        point d = b + bd @ th2;
        point f = b + bf @ (th2 + alpha_b);
    }
}

/// Declares a mechanism twice from one body: as `$name`, decomposed into blocks, and as
/// `$dense` with `#[kinloop(dense)]`, so that the two cannot drift apart.
macro_rules! with_dense_twin {
    ($(#[doc = $doc:literal])* pub struct $name:ident, $dense:ident { $($body:tt)* }) => {
        kinloop::mechanism! {
            $(#[doc = $doc])*
            pub struct $name { $($body)* }
        }
        kinloop::mechanism! {
            $(#[doc = $doc])*
            #[kinloop(dense)]
            pub struct $dense { $($body)* }
        }
    };
}

with_dense_twin! {
    /// Asymmetric rhombic drive (SEEDS 000, Fig. 1) with a scalar output.
    pub struct Rhombic, RhombicDense {
        params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7, l_cs2 = 1.1, l_fs4 = 1.6;
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
        point s2 = (x_c, 0) + l_cs2 @ phi2;
        point s4 = (x_f, de) + l_fs4 @ phi4;
        output stroke_sum = x_c + x_f;
    }
}

#[test]
fn class_four_is_one_coupled_four_unknown_block() {
    // The crank is the input (computed directly); the Assur group of class IV cannot be split:
    // both loops are needed at once for all four angles.
    let blocks = ClassFour::BLOCKS;
    assert_eq!(blocks.len(), 1, "{}", ClassFour::DECOMPOSITION);
    assert_eq!(blocks[0].unknowns, &["th1", "th2", "psi1", "psi2"]);
    assert_eq!(blocks[0].equations, &["acdb.x", "acdb.y", "aefb.x", "aefb.y"]);
    assert!(!blocks[0].linear);
    assert_eq!(
        ClassFour::DECOMPOSITION,
        "ClassFour: 4 unknowns, 4 scalar equations, 1 input (mobility W = 1); 1 block in solve order\n  \
         block 0 (Newton, 4x4): th1, th2, psi1, psi2 <- acdb.x, acdb.y, aefb.x, aefb.y"
    );
    assert_eq!(ClassFourDense::BLOCKS.len(), 1);
    assert!(ClassFourDense::DECOMPOSITION.contains("dense: decomposition disabled"));
    // The dense twin is the example's mechanism: the same names and parameter values.
    assert_eq!(ClassFourDense::default().params_flat(), ClassFour::default().params_flat());
    assert_eq!(ClassFourDense::PARAMS, ClassFour::PARAMS);
    assert_eq!(ClassFourDense::EQUATIONS, ClassFour::EQUATIONS);
    assert_eq!(ClassFourDense::OUTPUTS, ClassFour::OUTPUTS);
}

#[test]
fn rhombic_drive_splits_into_its_groups_with_sliders_in_closed_form() {
    let blocks = Rhombic::BLOCKS;
    assert_eq!(blocks.len(), 4, "{}", Rhombic::DECOMPOSITION);
    // Each block is one unknown from one loop: the working group (oabco: phi2, x_c) and the
    // displacer group (oadff1o: phi4, x_f) never share a block.
    for b in blocks {
        assert_eq!(b.unknowns.len(), 1, "{b:?}");
        let group = if ["phi2", "x_c"].contains(&b.unknowns[0]) { "oabco." } else { "oadff1o." };
        assert!(b.equations.iter().all(|e| e.starts_with(group)), "{b:?}");
        // Slider coordinates appear linearly: one linear solve, no iteration.
        assert_eq!(b.linear, b.unknowns[0].starts_with("x_"), "{b:?}");
    }
    let at = |u: &str| blocks.iter().position(|b| b.unknowns[0] == u).unwrap();
    assert!(at("phi2") < at("x_c") && at("phi4") < at("x_f"));
    // The rod angle comes from the y projection (the slider is not in it), the slider from x.
    assert_eq!(blocks[at("phi2")].equations, &["oabco.y"]);
    assert_eq!(blocks[at("x_c")].equations, &["oabco.x"]);
    let text = Rhombic::DECOMPOSITION;
    assert!(text.starts_with("Rhombic: 4 unknowns, 4 scalar equations, 1 input (mobility W = 1); 4 blocks"), "{text}");
    assert!(text.contains("(Newton, 1x1): phi2 <- oabco.y"), "{text}");
    assert!(text.contains("(linear, 1x1): x_f <- oadff1o.x"), "{text}");
    assert_eq!(text.lines().count(), 5, "{text}");

    assert_eq!(RhombicDense::BLOCKS.len(), 1);
    assert_eq!(RhombicDense::BLOCKS[0].unknowns.len(), 4);
}

/// `|a - b| <= tol * max(1, |b|)`, with a message naming what differs.
fn assert_close(what: &str, a: &[f64], b: &[f64], tol: f64) {
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(close(*x, *y, tol), "{what}[{k}]: {x} vs {y} (difference {})", (x - y).abs());
    }
}

/// The decomposed and the dense solve agree to 1e-12: positions, analogs, outputs (flat: `x`, `y`
/// of each point, then the scalar outputs) and the outputs' analogs.
fn assert_same_as_dense<const N: usize, const NO: usize>(at: &str, a: &Kin<N, 1, NO>, b: &Kin<N, 1, NO>) {
    let first = |v: &[[f64; 1]]| v.iter().map(|d| d[0]).collect::<Vec<_>>();
    let second = |v: &[[[f64; 1]; 1]]| v.iter().map(|d| d[0][0]).collect::<Vec<_>>();
    assert_close(&format!("q {at}"), &a.q, &b.q, 1e-12);
    assert_close(&format!("dq {at}"), &first(&a.dq), &first(&b.dq), 1e-12);
    assert_close(&format!("d2q {at}"), &second(&a.d2q), &second(&b.d2q), 1e-12);
    assert_close(&format!("outputs {at}"), &a.out, &b.out, 1e-12);
    assert_close(&format!("output analogs {at}"), &first(&a.dout), &first(&b.dout), 1e-12);
    assert_close(&format!("output acceleration analogs {at}"), &second(&a.d2out), &second(&b.d2out), 1e-12);
}

#[test]
fn rhombic_drive_decomposed_equals_dense_over_a_turn() {
    let (m, d) = (Rhombic::default(), RhombicDense::default());
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
        assert!(m.residual(phi1, &a.q).iter().all(|r| r.abs() < 1e-12));
    }
}

#[test]
fn class_four_decomposed_equals_dense_and_assembles_over_a_turn() {
    let (m, d) = (ClassFour::default(), ClassFourDense::default());
    let first = m.solve(0.0).expect("assembles at phi = 0");
    let (mut gm, mut gd) = (first.q, d.solve(0.0).expect("dense assembles at phi = 0").q);
    let h = 1e-5;
    for k in 0..=720 {
        let phi = 2.0 * PI * k as f64 / 720.0;
        let a = m.kinematics(phi, &gm).unwrap_or_else(|e| panic!("decomposed at {phi}: {e}"));
        let b = d.kinematics(phi, &gd).unwrap_or_else(|e| panic!("dense at {phi}: {e}"));
        let at = format!("at phi = {phi}");
        assert_same_as_dense(&at, &a.flat, &b.flat);
        let (qa, va, aa): ([f64; 4], [f64; 4], [f64; 4]) = (a.q.into(), a.dq.into(), a.d2q.into());

        // Independent check of the analogs: central differences of the positions.
        let plus: [f64; 4] = m.kinematics(phi + h, &a.q).expect("phi + h").q.into();
        let minus: [f64; 4] = m.kinematics(phi - h, &a.q).expect("phi - h").q.into();
        let fd: Vec<f64> = plus.iter().zip(&minus).map(|(p, q)| (p - q) / (2.0 * h)).collect();
        assert_close(&format!("dq vs finite differences {at}"), &va, &fd, 1e-6);
        let fd2: Vec<f64> = plus.iter().zip(&minus).zip(&qa).map(|((p, q), c)| (p - 2.0 * c + q) / (h * h)).collect();
        assert_close(&format!("d2q vs finite differences {at}"), &aa, &fd2, 1e-3);
        // Continuity along the sweep: the same assembly mode all the way round.
        let prev: [f64; 4] = gm.into();
        assert!(qa.iter().zip(&prev).all(|(x, y)| (x - y).abs() < 0.2), "branch jump {at}: {qa:?} after {prev:?}");
        gm = a.q;
        gd = b.q;
    }
    // Back to the start after a full turn.
    let (end, start): ([f64; 4], [f64; 4]) = (gm.into(), first.q.into());
    assert_close("q after a full turn", &end, &start, 1e-9);
}
