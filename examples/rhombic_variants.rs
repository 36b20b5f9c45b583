//! The two structural variants of the rhombic drive whose equations paper 000 does "not give for
//! lack of space" (`docs/papers.md`, paper 000, Figs. 2 and 3), declared from their description only: one crank
//! AB (radius `r`, centre A = (0, e_p)), the working piston C on the X axis, the displacer F on
//! the line y = de.
//!
//! * Fig. 2, developed displacer rod: rod 4 is a rigid triangle F-B-D (FB = `l_b` at angle
//!   `phi4`, FD = `l_fd` at the fixed angle `gamma_b` from FB); the working rod 2 (`l_p`) joins
//!   D to the piston C. Contours OABFF1O and OCDFF1O.
//! * Fig. 3, developed working rod: rod 2 is a rigid triangle C-B-D (CB = `l_p` at angle
//!   `phi2`, CD = `l_cd` at the fixed angle `gamma_p` from CB); the displacer rod 4 (`l_b`)
//!   joins D to the displacer F. Contours OABCO and OF1FDCO.
//!
//! For each it prints the strokes, the extreme positions located as roots of the velocity
//! analogs, and the phase shift between the piston's and the displacer's extremes, and checks
//! that the third joint placed on the crank pin (D = B) gives back the drive of Fig. 1.
//!
//! Run with `cargo run --release -p kinloop-examples --example rhombic_variants`.

use kinloop::analysis::{Column, Sampled};
use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop_fixtures::{DisplacerRodDrive, WorkingRodDrive};
use std::f64::consts::TAU;

/// Strokes, extremes and phase shift of a drive with piston `x_c` and displacer `x_f`.
pub fn report<M, const N: usize, const NO: usize>(
    name: &str,
    turn: &Sampled<'_, M, N, NO>,
    [x_c, x_f]: [Column<M>; 2],
) -> Result<[f64; 4], Box<dyn std::error::Error>>
where
    M: kinloop::Mechanism<N, 1, NO>,
{
    let xc = turn.range(x_c)?;
    let xf = turn.range(x_f)?;
    let deg = |a: f64| a.to_degrees().rem_euclid(360.0);
    println!("{name}");
    for (what, r) in [("piston    X_C", &xc), ("displacer X_F", &xf)] {
        println!(
            "  {what} in [{:.12}, {:.12}] (at phi1 = {:.5}°, {:.5}°): stroke {:.12}",
            r.min.value,
            r.max.value,
            deg(r.min.x),
            deg(r.max.x),
            r.span()
        );
    }
    // Outer extremes: the piston farthest left (min X_C), the displacer farthest right (max X_F).
    let outer = deg(xf.max.x - xc.min.x);
    let inner = deg(xf.min.x - xc.max.x);
    println!("  phase shift of the extremes: outer {outer:.6}°, inner {inner:.6}°");
    Ok([xc.span(), xf.span(), outer, inner])
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let fig2 = DisplacerRodDrive::default();
    let fig3 = WorkingRodDrive::default();
    println!("Rhombic drive variants of paper 000 (lengths in crank radii)\n{fig2:?}\n{fig3:?}\n");
    let t2 = fig2.sampled(0.0, TAU, 361, &fig2.guess(0.0))?;
    let t3 = fig3.sampled(0.0, TAU, 361, &fig3.guess(0.0))?;
    report("Fig. 2, developed displacer rod:", &t2, [DisplacerRodDrive::COL.x_c, DisplacerRodDrive::COL.x_f])?;
    // The displacer group of Fig. 2 is the one of Fig. 1: the paper's X_F0 and X_Fmin hold.
    let e_b = fig2.e_p - fig2.de;
    let xf = t2.range(DisplacerRodDrive::COL.x_f)?;
    println!(
        "  paper: X_F0 = {:.12}, X_Fmin = {:.12}",
        ((fig2.l_b + fig2.r).powi(2) - e_b * e_b).sqrt(),
        ((fig2.l_b - fig2.r).powi(2) - e_b * e_b).sqrt()
    );
    assert!((xf.max.value - ((fig2.l_b + fig2.r).powi(2) - e_b * e_b).sqrt()).abs() < 1e-12);
    report("Fig. 3, developed working rod:", &t3, [WorkingRodDrive::COL.x_c, WorkingRodDrive::COL.x_f])?;
    let xc = t3.range(WorkingRodDrive::COL.x_c)?;
    println!(
        "  closed form of the piston group: X_C min = {:.12}, X_C max = {:.12}",
        -((fig3.l_p + fig3.r).powi(2) - fig3.e_p * fig3.e_p).sqrt(),
        -((fig3.l_p - fig3.r).powi(2) - fig3.e_p * fig3.e_p).sqrt()
    );
    assert!((xc.min.value + ((fig3.l_p + fig3.r).powi(2) - fig3.e_p * fig3.e_p).sqrt()).abs() < 1e-12);

    // Degenerate case: the third joint on the crank pin (D = B) is the drive of Fig. 1 with both
    // crank arms on one pin (r_p = r_b = r, gamma = 0). Compare with Fig. 1's closed form.
    let d2 = DisplacerRodDrive { l_fd: fig2.l_b, gamma_b: 0.0, ..fig2 };
    let d3 = WorkingRodDrive { l_cd: fig3.l_p, gamma_p: 0.0, ..fig3 };
    // Largest deviation of (phi1, X_C, X_F) samples from Fig. 1 with dimensions [r, l_p, l_b, e_p, de].
    let deviation = |[r, l_p, l_b, e_p, de]: [f64; 5], samples: Vec<(f64, f64, f64)>| {
        let dev = |(phi1, x_c, x_f): (f64, f64, f64)| {
            let c = fig1_closed(r, l_p, l_b, e_p, de, phi1);
            (x_c - c[0]).abs().max((x_f - c[1]).abs())
        };
        samples.into_iter().map(dev).fold(0.0f64, f64::max)
    };
    let s2 = d2.sweep(0.0, TAU, 361, &d2.guess(0.0))?.map(|s| s.map(|s| (s.input.phi1, s.q.x_c, s.q.x_f)));
    let dev2 = deviation([d2.r, d2.l_p, d2.l_b, d2.e_p, d2.de], s2.collect::<Result<_, _>>()?);
    let s3 = d3.sweep(0.0, TAU, 361, &d3.guess(0.0))?.map(|s| s.map(|s| (s.input.phi1, s.q.x_c, s.q.x_f)));
    let dev3 = deviation([d3.r, d3.l_p, d3.l_b, d3.e_p, d3.de], s3.collect::<Result<_, _>>()?);
    println!("\nthird joint on the crank pin = Fig. 1: largest deviation of X_C, X_F from Fig. 1's closed form");
    println!("  Fig. 2 with l_fd = l_b, gamma_b = 0: {dev2:.1e};  Fig. 3 with l_cd = l_p, gamma_p = 0: {dev3:.1e}");

    draw(&t2, &t3)?;
    Ok(())
}

/// Lengths of both variants are in units of the crank radius (`r = 1`).
const UNIT: &str = "units of r";

/// One variant's panel: X_C and X_F (order 0) or their velocity analogs (order 1), by column.
fn panel<M: kinloop::Mechanism<4, 1, 2>>(
    axis: Axis,
    turn: &Sampled<'_, M, 4, 2>,
    [(c_label, c), (f_label, f)]: [(&str, Column<M>); 2],
    order: usize,
) -> Result<Panel, kinloop::Error> {
    let kind = axis.kind.clone();
    let curve = |label: &str, col| -> Result<Series, kinloop::Error> {
        let points = turn.jets(col)?.iter().map(|j| (j.x, if order == 0 { j.value } else { j.d1 })).collect();
        Ok(Series::new(label, kind.clone(), points))
    };
    Ok(Panel::new(axis).with(curve(c_label, c)?).with(curve(f_label, f)?))
}

/// X_C and X_F (order 0) or their velocity analogs (order 1) of both variants, one panel per
/// variant.
fn draw(
    t2: &Sampled<'_, DisplacerRodDrive, 4, 2>,
    t3: &Sampled<'_, WorkingRodDrive, 4, 2>,
) -> Result<(), Box<dyn std::error::Error>> {
    let dir = plot::figure_dir("rhombic_variants")?;
    let figures = [
        (
            "positions.svg",
            "piston X_C and displacer X_F",
            "X",
            Kind::length(UNIT),
            ["X_C (working piston)", "X_F (displacer)"],
        ),
        (
            "velocity_analogs.svg",
            "velocity analogs dX/dφ1",
            "dX/dφ1",
            Kind::LengthAnalog(UNIT.into()),
            ["V_qC", "V_qF"],
        ),
    ];
    for (order, (file, what, y, kind, [c, f])) in figures.into_iter().enumerate() {
        let axis = |fig: &str| Axis::new(&format!("{fig}: {y}"), kind.clone());
        let (c2, f2) = (DisplacerRodDrive::COL.x_c, DisplacerRodDrive::COL.x_f);
        let (c3, f3) = (WorkingRodDrive::COL.x_c, WorkingRodDrive::COL.x_f);
        let both = [
            panel(axis("Fig. 2"), t2, [(c, c2), (f, f2)], order)?,
            panel(axis("Fig. 3"), t3, [(c, c3), (f, f3)], order)?,
        ];
        let title = format!("Rhombic drive variants: {what}");
        plot::panels(&dir.join(file), &title, &Axis::angle("crank angle φ1"), &both)?;
    }
    println!("\nwrote positions.svg, velocity_analogs.svg to {}", dir.display());
    Ok(())
}

/// Fig. 1's published closed form (paper 000) for one crank pin (`r_p = r_b = r`,
/// `gamma = 0`): `[X_C, X_F]`.
fn fig1_closed(r: f64, l_p: f64, l_b: f64, e_p: f64, de: f64, phi1: f64) -> [f64; 2] {
    let (lam_p, lam_b) = (r / l_p, r / l_b);
    let (k_p, k_b) = (e_p / r, (e_p - de) / r);
    let phi2 = (lam_p * (k_p + phi1.sin())).asin();
    let phi4 = std::f64::consts::PI - (lam_b * (k_b + phi1.sin())).asin();
    [l_p * (lam_p * phi1.cos() - phi2.cos()), l_b * (lam_b * phi1.cos() - phi4.cos())]
}
