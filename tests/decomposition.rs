//! The block decomposition (maximum matching + Tarjan's BLT order) of the papers' mechanisms,
//! and its correctness: results with the decomposition equal results without it
//! (`#[kinloop(dense)]`, every unknown in one Newton block) to 1e-12 over full crank turns.

use std::f64::consts::PI;

kinloop::mechanism! {
    /// Class IV mechanism (SEEDS 003): crank OA, ternary links CAE (at A) and DBF (at B), binary
    /// links CD, EF.
    pub struct ClassFour {
        params oa = 1.0, xb = 4.4, yb = 0.6, ac = 2.3, ae = 2.4, alpha_a = 0.84,
               bd = 1.6, bf = 3.5, alpha_b = 0.62, cd = 2.0, ef = 3.4;
        input phi;
        unknowns th1 = 1.4, th2 = 3.0, psi1 = -0.8, psi2 = -1.0;
        let a = oa @ phi;
        let b = (xb, yb);
        loop acdb: a + ac @ th1 + cd @ psi1 == b + bd @ th2;
        loop aefb: a + ae @ (th1 + alpha_a) + ef @ psi2 == b + bf @ (th2 + alpha_b);
        point c = a + ac @ th1;
        point f = b + bf @ (th2 + alpha_b);
    }
}

kinloop::mechanism! {
    /// The same class IV mechanism, solved as one dense block.
    #[kinloop(dense)]
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
        point f = b + bf @ (th2 + alpha_b);
    }
}

kinloop::mechanism! {
    /// Asymmetric rhombic drive (SEEDS 000, Fig. 1).
    pub struct Rhombic {
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

kinloop::mechanism! {
    /// The same rhombic drive, solved as one dense block.
    #[kinloop(dense)]
    pub struct RhombicDense {
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
        assert!((x - y).abs() <= tol * y.abs().max(1.0), "{what}[{k}]: {x} vs {y} (difference {})", (x - y).abs());
    }
}

fn flat2(v: &[kinloop::Vec2]) -> Vec<f64> {
    v.iter().flat_map(|p| [p.x, p.y]).collect()
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
        let at = format!("at phi1 = {phi1}");
        let (qa, qb): ([f64; 4], [f64; 4]) = (a.q.into(), b.q.into());
        assert_close(&format!("q {at}"), &qa, &qb, 1e-12);
        let (va, vb): ([f64; 4], [f64; 4]) = (a.dq.into(), b.dq.into());
        assert_close(&format!("dq {at}"), &va, &vb, 1e-12);
        let (aa, ab): ([f64; 4], [f64; 4]) = (a.d2q.into(), b.d2q.into());
        assert_close(&format!("d2q {at}"), &aa, &ab, 1e-12);
        let out = |s: &RhombicState| {
            let mut v = flat2(&[s.out.s2, s.out.s4]);
            v.push(s.out.stroke_sum);
            v.extend(flat2(&[s.dout.s2, s.dout.s4]));
            v.push(s.dout.stroke_sum);
            v.extend(flat2(&[s.d2out.s2, s.d2out.s4]));
            v.push(s.d2out.stroke_sum);
            v
        };
        let out_dense = |s: &RhombicDenseState| {
            let mut v = flat2(&[s.out.s2, s.out.s4]);
            v.push(s.out.stroke_sum);
            v.extend(flat2(&[s.dout.s2, s.dout.s4]));
            v.push(s.dout.stroke_sum);
            v.extend(flat2(&[s.d2out.s2, s.d2out.s4]));
            v.push(s.d2out.stroke_sum);
            v
        };
        assert_close(&format!("outputs {at}"), &out(&a), &out_dense(&b), 1e-12);
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
        let (qa, qb): ([f64; 4], [f64; 4]) = (a.q.into(), b.q.into());
        assert_close(&format!("q {at}"), &qa, &qb, 1e-12);
        let (va, vb): ([f64; 4], [f64; 4]) = (a.dq.into(), b.dq.into());
        assert_close(&format!("dq {at}"), &va, &vb, 1e-12);
        let (aa, ab): ([f64; 4], [f64; 4]) = (a.d2q.into(), b.d2q.into());
        assert_close(&format!("d2q {at}"), &aa, &ab, 1e-12);
        let (oa, ob) = (flat2(&[a.out.c, a.out.f]), flat2(&[b.out.c, b.out.f]));
        assert_close(&format!("outputs {at}"), &oa, &ob, 1e-12);
        let (oa, ob) = (flat2(&[a.dout.c, a.dout.f]), flat2(&[b.dout.c, b.dout.f]));
        assert_close(&format!("output analogs {at}"), &oa, &ob, 1e-12);
        let (oa, ob) = (flat2(&[a.d2out.c, a.d2out.f]), flat2(&[b.d2out.c, b.d2out.f]));
        assert_close(&format!("output acceleration analogs {at}"), &oa, &ob, 1e-12);

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
