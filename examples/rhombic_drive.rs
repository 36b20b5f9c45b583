//! Kinematic analysis of the asymmetric rhombic drive of a Stirling engine (`docs/papers.md`,
//! paper 000, Fig. 1): positions, velocity and acceleration analogs of the pistons and rods, and the
//! centres of mass, over a full turn of the crank.
//!
//! It also locates the extreme positions of the working piston and the displacer exactly (as
//! roots of their velocity analogs), compares them with the paper's closed forms
//! `X_F0 = sqrt((L_B + R_B)^2 - e_B^2)`, `X_Fmin = sqrt((L_B - R_B)^2 - e_B^2)` (and their
//! analogues for the piston, with `e_P`), and prints the strokes and the phase shift between the
//! piston's and the displacer's extremes.
//!
//! Run with `cargo run --release -p kinloop-examples --example rhombic_drive`. It prints a table every 10 degrees,
//! writes the full sweep as CSV and draws SVG charts into `out/rhombic_drive/` (the charts into
//! `$KINLOOP_FIGURES/rhombic_drive/` when that variable is set).

use kinloop::Table;
use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop_fixtures::{RhombicDrive, RhombicDriveState};
use std::f64::consts::TAU;

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn main() -> Result<()> {
    let drive = RhombicDrive::default();
    let states = full_turn(&drive)?;
    println!("Rhombic drive (paper 000, Fig. 1): {:?}\n", drive);
    print_table(&states);
    report_extremes(&drive)?;
    let s = states.iter().map(|s| s.report.iterations).sum::<u32>();
    println!("Newton iterations over the sweep: {s} ({} solves)", states.len());
    write_outputs(&states)
}

/// A full turn in steps of 0.1 degree.
fn full_turn(drive: &RhombicDrive) -> Result<Vec<RhombicDriveState>> {
    // A full turn in steps of 0.1 degree, each solve warm-started from the previous position
    // so the drive stays in the declared assembly mode.
    let mut guess = drive.guess(0.0);
    let mut states = Vec::with_capacity(3601);
    for k in 0..=3600 {
        let phi1 = (k as f64 / 10.0).to_radians();
        let state = drive.kinematics(phi1, &guess)?;
        guess = state.q;
        states.push(state);
    }
    Ok(states)
}

/// The table every 10 degrees.
fn print_table(states: &[RhombicDriveState]) {
    println!(
        "{:>6} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>8} {:>8}",
        "phi1", "X_C", "X_F", "V_qC", "V_qF", "a_qC", "a_qF", "U21", "U41"
    );
    for s in states.iter().step_by(100) {
        println!(
            "{:>5.0}° {:>9.5} {:>9.5} {:>9.5} {:>9.5} {:>9.5} {:>9.5} {:>8.5} {:>8.5}",
            s.input.phi1.to_degrees(),
            s.q.x_c,
            s.q.x_f,
            s.dq.x_c,
            s.dq.x_f,
            s.d2q.x_c,
            s.d2q.x_f,
            s.dq.phi2,
            s.dq.phi4,
        );
    }
}

/// Extreme positions, strokes and phase shifts against the closed forms.
fn report_extremes(drive: &RhombicDrive) -> Result<()> {
    // Extreme positions, located as roots of the velocity analogs (dX/dphi1 = 0) on a sweep of
    // one turn, against the closed forms: crank and rod stretched (outer) or folded (inner).
    let turn = drive.sampled(0.0, TAU, 361, &drive.guess(0.0))?;
    let xc = turn.range(RhombicDrive::COL.x_c)?;
    let xf = turn.range(RhombicDrive::COL.x_f)?;
    let e_b = drive.e_p - drive.de;
    let x_f0 = ((drive.l_b + drive.r_b).powi(2) - e_b * e_b).sqrt();
    let x_fmin = ((drive.l_b - drive.r_b).powi(2) - e_b * e_b).sqrt();
    let x_c_outer = -((drive.l_p + drive.r_p).powi(2) - drive.e_p * drive.e_p).sqrt();
    let x_c_inner = -((drive.l_p - drive.r_p).powi(2) - drive.e_p * drive.e_p).sqrt();
    // Crank angles there: arm AB points from A = (0, e_P) at C (outer) or away from it (inner);
    // arm AD likewise towards F = (X_F, de).
    let deg = |a: f64| a.to_degrees().rem_euclid(360.0);
    let at_c_outer = deg(f64::atan2(-drive.e_p, x_c_outer));
    let at_c_inner = deg(f64::atan2(drive.e_p, -x_c_inner));
    let at_f_outer = deg(f64::atan2(-e_b, x_f0) - drive.gamma);
    let at_f_inner = deg(f64::atan2(e_b, -x_fmin) - drive.gamma);
    println!("\nextreme positions (roots of the velocity analogs) vs closed forms:");
    let show = |name: &str, v: f64, at: f64, closed: f64, closed_at: f64| {
        println!(
            "  {name:<20} {v:>16.12} at phi1 = {:>9.5}°   closed form {closed:>16.12} at {closed_at:>9.5}°   (diff {:.1e})",
            deg(at),
            (v - closed).abs()
        )
    };
    show("X_C min (outer)", xc.min.value, xc.min.x, x_c_outer, at_c_outer);
    show("X_C max (inner)", xc.max.value, xc.max.x, x_c_inner, at_c_inner);
    show("X_F max = X_F0", xf.max.value, xf.max.x, x_f0, at_f_outer);
    show("X_F min = X_Fmin", xf.min.value, xf.min.x, x_fmin, at_f_inner);
    println!("piston stroke    {:.12} (closed form {:.12})", xc.span(), x_c_inner - x_c_outer);
    println!("displacer stroke {:.12} (closed form {:.12})", xf.span(), x_f0 - x_fmin);
    // Phase shift: crank angle from the piston's extreme to the displacer's corresponding one
    // (outer to outer, inner to inner: both pistons farthest from, or nearest to, the crank).
    let shift_outer = deg(xf.max.x - xc.min.x);
    let shift_inner = deg(xf.min.x - xc.max.x);
    println!(
        "phase shift of the extremes: outer {shift_outer:.6}° (closed form {:.6}°), inner {shift_inner:.6}° (closed form {:.6}°)",
        deg((at_f_outer - at_c_outer).to_radians()),
        deg((at_f_inner - at_c_inner).to_radians())
    );
    Ok(())
}

/// Lengths of the drive are in units of the working crank radius (`r_P = 1`).
const UNIT: &str = "units of r_P";

/// The sweep as CSV and its charts as SVG.
fn write_outputs(states: &[RhombicDriveState]) -> Result<()> {
    let data = plot::out_dir("rhombic_drive")?;
    // Units in the CSV header, inferred by the macro: angles in radians, lengths in the drive's
    // unit of length (which only we know).
    let table = Table::from_states::<RhombicDrive, _, _, _>(states.iter().map(|s| &s.flat)).with_length_unit(UNIT);
    table.save_csv(data.join("sweep.csv"))?;

    let dir = plot::figure_dir("rhombic_drive")?;
    let crank = Axis::angle("crank angle φ1");
    // A column of the sweep against the crank angle, with its legend label.
    let column = |name: &str, kind: Kind, label: &str| -> Result<Series> {
        Ok(Series { label: label.to_string(), ..Series::from_table(&table, "phi1", name, kind)? })
    };
    let length = Kind::length(UNIT);
    let (v_len, a_len) = (Kind::LengthAnalog(UNIT.into()), Kind::LengthAnalog2(UNIT.into()));
    plot::line_chart(
        &dir.join("positions.svg"),
        "Rhombic drive: piston and displacer positions",
        &crank,
        &Axis::length("position X", UNIT),
        &[column("x_c", length.clone(), "X_C (working piston)")?, column("x_f", length, "X_F (displacer)")?],
    )?;
    // Pistons (lengths) and rods (angles) have analogs of different kinds: one panel each.
    plot::panels(
        &dir.join("velocity_analogs.svg"),
        "Rhombic drive: velocity analogs",
        &crank,
        &[
            Panel::new(Axis::new("dX/dφ1", v_len.clone()))
                .with(column("d(x_c)/d(phi1)", v_len.clone(), "V_qC (working piston)")?)
                .with(column("d(x_f)/d(phi1)", v_len, "V_qF (displacer)")?),
            Panel::new(Axis::new("U = dφ/dφ1", Kind::AngleAnalog))
                .with(column("d(phi2)/d(phi1)", Kind::AngleAnalog, "U21 (working rod)")?)
                .with(column("d(phi4)/d(phi1)", Kind::AngleAnalog, "U41 (displacer rod)")?),
        ],
    )?;
    plot::panels(
        &dir.join("acceleration_analogs.svg"),
        "Rhombic drive: acceleration analogs",
        &crank,
        &[
            Panel::new(Axis::new("d²X/dφ1²", a_len.clone()))
                .with(column("d2(x_c)/d(phi1)^2", a_len.clone(), "a_qC (working piston)")?)
                .with(column("d2(x_f)/d(phi1)^2", a_len, "a_qF (displacer)")?),
            Panel::new(Axis::new("ε_q = d²φ/dφ1²", Kind::AngleAnalog2))
                .with(column("d2(phi2)/d(phi1)^2", Kind::AngleAnalog2, "ε_q2 (working rod)")?)
                .with(column("d2(phi4)/d(phi1)^2", Kind::AngleAnalog2, "ε_q4 (displacer rod)")?),
        ],
    )?;
    // Speed analog of a centre of mass: the length of its velocity analog vector.
    let speed = |label: &str, of: fn(&RhombicDriveState) -> f64| {
        Series::new(label, Kind::LengthAnalog(UNIT.into()), states.iter().map(|s| (s.input.phi1, of(s))).collect())
    };
    plot::line_chart(
        &dir.join("centres_of_mass_speed.svg"),
        "Rhombic drive: speed analogs of the centres of mass",
        &crank,
        &Axis::new("|dS/dφ1|", Kind::LengthAnalog(UNIT.into())),
        &[
            speed("S1 (crank)", |s| s.dout.s1.norm()),
            speed("S2 (working rod)", |s| s.dout.s2.norm()),
            speed("S4 (displacer rod)", |s| s.dout.s4.norm()),
        ],
    )?;
    println!("\nwrote {} and 4 charts to {}", data.join("sweep.csv").display(), dir.display());
    Ok(())
}
