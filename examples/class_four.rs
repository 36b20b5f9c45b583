//! A planar mechanism of class IV (SEEDS.md, paper 003): input crank OA, and an Assur group of
//! class IV made of two ternary links, C-A-E (pinned to the crank at A) and D-B-F (pinned to the
//! frame at B), joined by the binary links CD and EF. The closed contour C-D-F-E cannot be
//! solved loop by loop: both loops ACDB and AEFB must close together. The paper tracks the free
//! angle with a high-gain amplifier on an analog computer until both four-bars close; here the
//! macro finds the coupling at compile time and solves the four unknowns as one block by Newton.
//!
//! Dimensions (lengths in units of the crank OA = 1; they assemble over a full turn, well away
//! from singular positions): O = (0, 0), B = (4.4, 0.6); ternary link CAE: AC = 2.3, AE = 2.4,
//! angle CAE = 0.84 rad; ternary link DBF: BD = 1.6, BF = 3.5, angle DBF = 0.62 rad; CD = 2.0,
//! EF = 3.4. Unknowns: `th1` (direction of AC), `th2` (direction of BD), `psi1` (CD), `psi2`
//! (EF).
//!
//! Run with `cargo run --release --example class_four`.

#[allow(dead_code)] // not every example uses every helper
mod common;

use common::{Panel, Series, figure_dir, panels, xy_chart};
use std::f64::consts::TAU;

kinloop::mechanism! {
    /// Class IV mechanism: crank OA, ternary links CAE (at A) and DBF (at B), binary links CD, EF.
    #[kinloop(sensitivities)]
    pub struct ClassFour {
        params oa = 1.0, xb = 4.4, yb = 0.6, ac = 2.3, ae = 2.4, alpha_a = 0.84,
               bd = 1.6, bf = 3.5, alpha_b = 0.62, cd = 2.0, ef = 3.4;
        input phi;
        unknowns th1 = 1.4, th2 = 3.0, psi1 = -0.8, psi2 = -1.0;
        let a = oa @ phi;
        let b = (xb, yb);
        loop acdb: a + ac @ th1 + cd @ psi1 == b + bd @ th2;
        loop aefb: a + ae @ (th1 + alpha_a) + ef @ psi2 == b + bf @ (th2 + alpha_b);
        /// Joints of the group.
        point c = a + ac @ th1;
        point e = a + ae @ (th1 + alpha_a);
        point d = b + bd @ th2;
        point f = b + bf @ (th2 + alpha_b);
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let m = ClassFour::default();
    println!("Class IV mechanism (paper 003): {m:?}\n");
    for (i, b) in ClassFour::BLOCKS.iter().enumerate() {
        println!(
            "block {i}: unknowns {:?}, equations {:?}, {}",
            b.unknowns,
            b.equations,
            if b.linear { "linear" } else { "solved by Newton as one unit" }
        );
    }

    let states: Vec<_> = m.sweep(0.0, TAU, 721, &m.guess(0.0))?.collect::<Result<_, _>>()?;
    println!(
        "\n{:>6} {:>10} {:>10} {:>10} {:>10} {:>9} {:>9} {:>9} {:>9}",
        "phi", "th1", "th2", "psi1", "psi2", "dth1", "dth2", "dpsi1", "dpsi2"
    );
    for s in states.iter().step_by(60) {
        println!(
            "{:>5.0}° {:>10.6} {:>10.6} {:>10.6} {:>10.6} {:>9.5} {:>9.5} {:>9.5} {:>9.5}",
            s.input.phi.to_degrees(),
            s.q.th1,
            s.q.th2,
            s.q.psi1,
            s.q.psi2,
            s.dq.th1,
            s.dq.th2,
            s.dq.psi1,
            s.dq.psi2
        );
    }
    let iterations: u32 = states.iter().map(|s| s.report.iterations).sum();
    let worst = states.iter().map(|s| s.health.min_pivot).fold(f64::INFINITY, f64::min);
    let residual = states.iter().flat_map(|s| m.residual(s.input.phi, &s.q)).fold(0.0f64, |a, r| a.max(r.abs()));
    let (first, last) = (states[0].q, states[states.len() - 1].q);
    println!(
        "\n{} solves, {iterations} Newton iterations; largest loop residual {residual:.1e}; smallest pivot ratio {worst:.3} \
         (1 = perfectly conditioned)",
        states.len()
    );
    println!(
        "after a full crank turn the group returns to its start: th1 within {:.1e}, psi2 within {:.1e}",
        (last.th1 - first.th1).abs(),
        (last.psi2 - first.psi2).abs()
    );

    let dir = figure_dir("class_four");
    let curve = |f: &dyn Fn(&ClassFourState) -> f64| {
        states.iter().map(|s| (s.input.phi.to_degrees(), f(s))).collect::<Vec<_>>()
    };
    // One panel per order: the four angles, their velocity analogs, their acceleration analogs.
    let panel = |y_label: &'static str, labels: [&'static str; 4], of: fn(&ClassFourState) -> [f64; 4]| Panel {
        y_label,
        series: (0..4).map(|u| Series { label: labels[u], points: curve(&|s| of(s)[u]) }).collect(),
        marks: vec![],
    };
    panels(
        &dir.join("angles_and_analogs.svg"),
        "Class IV mechanism: link angles and their velocity analogs",
        "crank angle phi [deg]",
        &[
            panel("angle [rad]", ["th1 (AC)", "th2 (BD)", "psi1 (CD)", "psi2 (EF)"], |s| s.q.into()),
            panel("velocity analog", ["dth1/dphi", "dth2/dphi", "dpsi1/dphi", "dpsi2/dphi"], |s| s.dq.into()),
            panel("acceleration analog", ["d2th1/dphi2", "d2th2/dphi2", "d2psi1/dphi2", "d2psi2/dphi2"], |s| {
                s.d2q.into()
            }),
        ],
    )?;
    let path = |f: &dyn Fn(&ClassFourState) -> (f64, f64)| states.iter().map(f).collect::<Vec<_>>();
    // The linkage drawn at phi = 30 degrees: O-A, triangle A-C-E, C-D, triangle D-B-F, E-F.
    let s = &states[60];
    let (o, a, b) = ((0.0, 0.0), (s.input.phi.cos(), s.input.phi.sin()), (m.xb, m.yb));
    let [c, d, e, f] = [s.out.c, s.out.d, s.out.e, s.out.f].map(|p| (p.x, p.y));
    xy_chart(
        &dir.join("joint_paths.svg"),
        "Class IV mechanism: paths of the joints over a crank turn (linkage at phi = 30°)",
        &[
            Series { label: "linkage at phi = 30°", points: vec![o, a, c, e, a, c, d, b, f, d, f, e] },
            Series { label: "A (crank pin)", points: path(&|s| (s.input.phi.cos(), s.input.phi.sin())) },
            Series { label: "C", points: path(&|s| (s.out.c.x, s.out.c.y)) },
            Series { label: "E", points: path(&|s| (s.out.e.x, s.out.e.y)) },
            Series { label: "D (arc about B)", points: path(&|s| (s.out.d.x, s.out.d.y)) },
            Series { label: "F (arc about B)", points: path(&|s| (s.out.f.x, s.out.f.y)) },
        ],
        &[o, b],
    )?;
    println!("\nwrote angles_and_analogs.svg, joint_paths.svg to {}", dir.display());
    Ok(())
}
