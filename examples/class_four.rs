//! A planar mechanism of class IV (`docs/papers.md`, paper 003): input crank OA, and an Assur group of
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
//! Run with `cargo run --release -p kinloop-examples --example class_four`.

use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop_fixtures::{ClassFour, ClassFourState};
use std::f64::consts::TAU;

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

    let states = turn(&m)?;
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

    let dir = draw(&m, &states)?;
    println!("\nwrote angles_and_analogs.svg, joint_paths.svg to {}", dir.display());
    Ok(())
}

/// The states over a crank turn from the declared assembly mode, 0.5 degrees apart (721, both
/// ends included): the example prints every 60th.
pub fn turn(m: &ClassFour) -> Result<Vec<ClassFourState>, kinloop::Error> {
    m.sweep(0.0, TAU, 721, &m.guess(0.0))?.collect()
}

/// Lengths are in units of the crank OA.
const UNIT: &str = "units of OA";

/// Link angles with their analogs, and the joints' paths with the linkage drawn at 30 degrees;
/// returns the folder they went to.
fn draw(m: &ClassFour, states: &[ClassFourState]) -> Result<std::path::PathBuf, Box<dyn std::error::Error>> {
    let dir = plot::figure_dir("class_four")?;
    // One panel per order: the four angles, their velocity analogs, their acceleration analogs.
    let panel = |axis: Axis, labels: [&str; 4], of: fn(&ClassFourState) -> [f64; 4]| {
        (0..4).fold(Panel::new(axis.clone()), |p, u| {
            let points = states.iter().map(|s| (s.input.phi, of(s)[u])).collect();
            p.with(Series::new(labels[u], axis.kind.clone(), points))
        })
    };
    plot::panels(
        &dir.join("angles_and_analogs.svg"),
        "Class IV mechanism: link angles and their velocity and acceleration analogs",
        &Axis::angle("crank angle φ"),
        &[
            panel(Axis::angle("link angle"), ["θ1 (AC)", "θ2 (BD)", "ψ1 (CD)", "ψ2 (EF)"], |s| s.q.into()),
            panel(
                Axis::new("velocity analog", Kind::AngleAnalog),
                ["dθ1/dφ", "dθ2/dφ", "dψ1/dφ", "dψ2/dφ"],
                |s| s.dq.into(),
            ),
            panel(
                Axis::new("acceleration analog", Kind::AngleAnalog2),
                ["d²θ1/dφ²", "d²θ2/dφ²", "d²ψ1/dφ²", "d²ψ2/dφ²"],
                |s| s.d2q.into(),
            ),
        ],
    )?;
    let length = Kind::length(UNIT);
    let path = |label: &str, f: fn(&ClassFourState) -> (f64, f64)| {
        Series::new(label, length.clone(), states.iter().map(f).collect())
    };
    // The linkage drawn at phi = 30 degrees: O-A, triangle A-C-E, C-D, triangle D-B-F, E-F.
    let s = &states[60];
    let (o, a, b) = ((0.0, 0.0), (s.input.phi.cos(), s.input.phi.sin()), (m.xb, m.yb));
    let [c, d, e, f] = [s.out.c, s.out.d, s.out.e, s.out.f].map(|p| (p.x, p.y));
    plot::xy_chart(
        &dir.join("joint_paths.svg"),
        "Class IV mechanism: paths of the joints over a crank turn (linkage at φ = 30°)",
        &Axis::length("x", UNIT),
        &Axis::length("y", UNIT),
        &[
            Series::new("linkage at φ = 30°", length.clone(), vec![o, a, c, e, a, c, d, b, f, d, f, e]),
            path("A (crank pin)", |s| (s.input.phi.cos(), s.input.phi.sin())),
            path("C", |s| (s.out.c.x, s.out.c.y)),
            path("E", |s| (s.out.e.x, s.out.e.y)),
            path("D (arc about B)", |s| (s.out.d.x, s.out.d.y)),
            path("F (arc about B)", |s| (s.out.f.x, s.out.f.y)),
        ],
        &[o, b],
    )?;
    Ok(dir)
}
