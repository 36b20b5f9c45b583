//! Recognition on declarations parsed by [`crate::analyze`]: each pattern is found where it
//! holds, with coefficients checked numerically against the declared residuals at random
//! points (the residual evaluated directly, not through the recognition), and near-misses that
//! look alike but have no such closed form keep Newton.

use super::recognise::{ClosedForm, recognise};
use crate::graph::dag::{Graph, Leaf, NodeId};

/// The closed forms of the declaration's blocks, in solve order (`None`: Newton or linear).
fn forms(src: &str) -> (Graph, Vec<Option<ClosedForm>>, Vec<Vec<NodeId>>) {
    let a = crate::analyze(src.parse().expect("tokens")).unwrap_or_else(|e| panic!("{e}"));
    let mut g = a.model.graph.clone();
    let np = a.model.params.len();
    let mut out = Vec::new();
    let mut rows = Vec::new();
    for b in &a.blocks {
        let f: Vec<NodeId> = b.equations.iter().map(|&e| a.model.equations[e].residual).collect();
        out.push(recognise(&mut g, b, &f, np).map(|r| r.form));
        rows.push(f);
    }
    (g, out, rows)
}

/// A deterministic pseudo-random value in [-2, 2) per leaf and trial.
fn value(l: Leaf, trial: u64) -> f64 {
    let mut h = std::hash::DefaultHasher::new();
    std::hash::Hash::hash(&(l, trial), &mut h);
    let bits = std::hash::Hasher::finish(&h);
    (bits >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
}

/// Checks `form` reproduces the residuals `f` at random parameters, inputs and unknowns.
fn check_identity(g: &Graph, form: &ClosedForm, f: &[NodeId]) {
    for trial in 0..20 {
        let leaf = |l: Leaf| value(l, trial);
        let ev = |n: NodeId| g.eval(&[n], &leaf)[0];
        let cs = |u: usize| {
            let q = leaf(Leaf::Unknown(u as u16));
            [q.cos(), q.sin()]
        };
        let predicted: Vec<f64> = match form {
            ClosedForm::AngleEquation { angle, a, b, c } => {
                let [c_, s_] = cs(*angle);
                vec![ev(*a) * c_ + ev(*b) * s_ - ev(*c)]
            }
            ClosedForm::Dyad { angles, m, e, .. } => (0..2)
                .map(|r| {
                    let (c0, c1) = (cs(angles[0]), cs(angles[1]));
                    ev(m[0][r][0]) * c0[0]
                        + ev(m[0][r][1]) * c0[1]
                        + ev(m[1][r][0]) * c1[0]
                        + ev(m[1][r][1]) * c1[1]
                        + ev(e[r])
                })
                .collect(),
            ClosedForm::PolarLength { angle, length, w, e } => (0..2)
                .map(|r| {
                    let c = cs(*angle);
                    let s = leaf(Leaf::Unknown(*length as u16));
                    s * (ev(w[r][0]) * c[0] + ev(w[r][1]) * c[1]) + ev(e[r])
                })
                .collect(),
            ClosedForm::AngleSlider { angle, slider, m, d, e } => (0..2)
                .map(|r| {
                    let c = cs(*angle);
                    let s = leaf(Leaf::Unknown(*slider as u16));
                    ev(m[r][0]) * c[0] + ev(m[r][1]) * c[1] + ev(d[r]) * s + ev(e[r])
                })
                .collect(),
        };
        let actual = g.eval(f, &leaf);
        for (p, a) in predicted.iter().zip(&actual) {
            assert!((p - a).abs() <= 1e-12 * (1.0 + a.abs()), "trial {trial}: {p} vs residual {a} for {form:?}");
        }
    }
}

/// The recognised forms' kinds, each checked against its residuals.
fn kinds(src: &str) -> Vec<&'static str> {
    let (g, fs, rows) = forms(src);
    fs.iter()
        .zip(&rows)
        .map(|(f, r)| match f {
            Some(f) => {
                check_identity(&g, f, r);
                f.describe()
            }
            None => "none",
        })
        .collect()
}

const FOUR_BAR: &str = "pub struct F { params a, b, c, d; input phi; unknowns beta, gamma;
    loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma; }";

#[test]
fn rrr_dyad_of_a_four_bar() {
    assert_eq!(kinds(FOUR_BAR), ["closed form, RRR dyad"]);
    // Offsets in the angles, links written by components, the loop on either side.
    assert_eq!(
        kinds(
            "pub struct F { params a, b, c, d, k; input phi; unknowns beta, gamma;
             loop abcd: (d, 0) + (c * cos(gamma + k), c * sin(gamma + k)) == a @ phi + b @ (pi - beta); }"
        ),
        ["closed form, RRR dyad"]
    );
}

#[test]
fn angle_equations_of_the_slider_crank_and_rhombic_drive() {
    let sc = "pub struct S { params r, l, e; input phi; unknowns psi, x; loop o: r @ phi == (x, e) + l @ psi; }";
    assert_eq!(kinds(sc), ["closed form, angle equation", "none"]);
    let eq = "pub struct S { params l; input y; unknowns q; eq e: l * sin(q) == y; }";
    assert_eq!(kinds(eq), ["closed form, angle equation"]);
    let neg = "pub struct S { params l, k; input y; unknowns q; eq e: l * cos(k - q) + 2 * sin(-q) == y; }";
    assert_eq!(kinds(neg), ["closed form, angle equation"]);
}

#[test]
fn length_and_angle_and_angle_and_slider() {
    let rocker = "pub struct R { params r, h; input phi; unknowns s, th; loop o: (0, h) + r @ phi == s @ th; }";
    assert_eq!(kinds(rocker), ["closed form, length and angle"]);
    let lever = "pub struct G { params l; input a; unknowns s, phi;
        loop o: (l * sin(a), 1 + l * cos(a)) == s * (sin(phi), cos(phi)); }";
    assert_eq!(kinds(lever), ["closed form, length and angle"]);
    let tilted = "pub struct Trial { params r, l, t; input phi; unknowns psi, x; loop o: r @ phi == x @ t + l @ psi; }";
    assert_eq!(kinds(tilted), ["closed form, angle and slider"]);
}

#[test]
fn near_misses_keep_newton() {
    let cases = [
        // A double angle, a bare angle, a square of a sine.
        "pub struct S { params l; input y; unknowns q; eq e: l * sin(2 * q) == y; }",
        "pub struct S { params l; input y; unknowns q; eq e: l * sin(q) + q == y; }",
        "pub struct S { params l; input y; unknowns q; eq e: l * sin(q) * sin(q) + cos(q) == y; }",
        // An ellipse is not a rigid link: no circle intersection.
        "pub struct F { params a, b, c, d; input phi; unknowns beta, gamma;
         loop o: a @ phi + b @ beta == (d, 0) + (c * cos(gamma), 2 * c * sin(gamma)); }",
        // The two angles coupled inside one argument.
        "pub struct F { params a, b, c, d; input phi; unknowns beta, gamma;
         loop o: a @ phi + b @ beta == (d, 0) + c @ (gamma + beta); }",
        // A slotted rocker with an offset slot: quartic, not a closed form here.
        "pub struct R { params r, h, e; input phi; unknowns s, th;
         loop o: (0, h) + r @ phi == s @ th + e @ (th + pi / 2); }",
        // The slider inside an angle (scaled into one: a slider that is an angle too would
        // be a unit mix, refused); a slider squared with the angle.
        "pub struct Trial { params r, l; input phi; unknowns psi, x; loop o: r @ phi == (x, 0) + l @ (psi + x / l); }",
        "pub struct Trial { params r, l, t; input phi; unknowns psi, x; loop o: r @ phi == (x * x) @ t + l @ psi; }",
    ];
    for src in cases {
        let k = kinds(src);
        assert!(k.iter().all(|k| *k == "none"), "{src}: {k:?}");
    }
}

/// `min`, `max`, `clamp` of the block's unknowns keep Newton; of the input alone (a cam law, a
/// coefficient of the block) the block is still the four-bar's circle intersection.
#[test]
fn min_and_max_of_unknowns_keep_newton() {
    let newton = [
        "pub struct S { params l; input y; unknowns q; eq e: l * sin(min(q, 1)) == y; }",
        "pub struct S { params l; input y; unknowns q; eq e: l * sin(q) + max(q, 0) == y; }",
    ];
    for src in newton {
        let k = kinds(src);
        assert!(k.iter().all(|k| *k == "none"), "{src}: {k:?}");
    }
    // The Y projection alone gives the rod's angle in closed form; the slider, inside `clamp`,
    // keeps Newton.
    let clamped = "pub struct Trial { params r, l; input phi; unknowns psi, x;
        loop o: r @ phi == (clamp(x, 0, 5), 0) + l @ psi; }";
    assert_eq!(kinds(clamped), ["closed form, angle equation", "none"]);
    let law = "pub struct F { params a, b, c, d; input phi; unknowns beta, gamma;
        loop o: clamp(a * phi, 0, a) @ phi + b @ beta == (d, 0) + c @ gamma; }";
    assert_eq!(kinds(law), ["closed form, RRR dyad"]);
}

/// `floor` of the block's unknowns keeps Newton; `wrap` (by `floor`) of the input alone is a
/// coefficient: the four-bar driven by a law of the wrapped input is still a dyad.
#[test]
fn floor_of_unknowns_keeps_newton() {
    let newton = [
        "pub struct S { params l; input y; unknowns q; eq e: l * sin(q) + floor(q) == y; }",
        "pub struct S { params l; input y; unknowns q; eq e: l * floor(q) + q == y; }",
    ];
    for src in newton {
        let k = kinds(src);
        assert!(k.iter().all(|k| *k == "none"), "{src}: {k:?}");
    }
    let floored = "pub struct Trial { params r, l; input phi; unknowns psi, x;
        loop o: r @ phi == (floor(x), 0) + l @ psi; }";
    assert_eq!(kinds(floored), ["closed form, angle equation", "none"]);
    let law = "pub struct F { params a, b, c, d; input phi; unknowns beta, gamma;
        loop o: (a + floor(phi) + wrap(phi, 2 * pi)) @ phi + b @ beta == (d, 0) + c @ gamma; }";
    assert_eq!(kinds(law), ["closed form, RRR dyad"]);
}

#[test]
fn class_four_group_keeps_newton() {
    let src = "pub struct C { params oa, xb, yb, ac, ae, al, bd, bf, bl, cd, ef; input phi;
        unknowns th1, th2, psi1, psi2;
        loop acdb: oa @ phi + ac @ th1 + cd @ psi1 == (xb, yb) + bd @ th2;
        loop aefb: oa @ phi + ae @ (th1 + al) + ef @ psi2 == (xb, yb) + bf @ (th2 + bl); }";
    assert_eq!(kinds(src), ["none"]);
}

/// `constant_norm2` against `|w (cos q, sin q)|²` evaluated directly at a few angles: constant
/// (and returned) for a scaled rotation and a scaled reflection; `None` where the columns differ
/// in length, are not orthogonal, or an entry is not a constant.
#[test]
fn constant_norm2_is_the_norm_of_w_at_every_angle() {
    use super::constant_norm2;
    let norm2 = |w: [[f64; 2]; 2], q: f64| {
        let (c, s) = (q.cos(), q.sin());
        (w[0][0] * c + w[0][1] * s).powi(2) + (w[1][0] * c + w[1][1] * s).powi(2)
    };
    let known = |w: [[f64; 2]; 2]| w.map(|r| r.map(Some));
    // 3-4-5: the scaled rotation and reflection of length 5.
    for w in [[[3.0, -4.0], [4.0, 3.0]], [[3.0, 4.0], [4.0, -3.0]], [[0.0, 1.0], [1.0, 0.0]]] {
        let k2 = constant_norm2(known(w)).expect("a scaled rotation or reflection");
        for q in [0.0, 0.7, 2.0, -2.9] {
            assert!((norm2(w, q) - k2).abs() <= 4.0 * f64::EPSILON * k2, "{w:?} at {q}");
        }
    }
    assert_eq!(constant_norm2(known([[0.0, 1.0], [1.0, 0.0]])), Some(1.0));
    assert_eq!(constant_norm2(known([[2.0, 0.0], [0.0, 1.0]])), None, "unequal columns");
    assert_eq!(constant_norm2(known([[1.0, 1.0], [0.0, 0.0]])), None, "not orthogonal");
    assert_eq!(constant_norm2([[Some(1.0), Some(0.0)], [None, Some(1.0)]]), None, "not constant");
}
