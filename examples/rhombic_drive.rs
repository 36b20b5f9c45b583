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

/// An extreme position of a piston: located along the sweep as a root of its velocity analog,
/// and by the closed form (crank arm and rod stretched or folded). Angles in degrees, in
/// `[0, 360)`.
#[derive(Clone, Copy, Debug)]
pub struct DeadCentre {
    /// Which piston and which extreme.
    pub name: &'static str,
    /// The position located along the sweep.
    pub value: f64,
    /// The crank angle there.
    pub at: f64,
    /// The closed form's position.
    pub closed: f64,
    /// The closed form's crank angle.
    pub closed_at: f64,
}

/// The pistons' extremes and the phase shifts between them, located and in closed form.
#[derive(Clone, Copy, Debug)]
pub struct Extremes {
    /// X_C min (outer), X_C max (inner), X_F max (outer, the paper's X_F0), X_F min (inner,
    /// X_Fmin).
    pub rows: [DeadCentre; 4],
    /// Crank angle from the piston's outer extreme to the displacer's, and from the inner to
    /// the inner (degrees, in `[0, 360)`), located.
    pub shift: [f64; 2],
    /// The same from the closed forms' crank angles.
    pub closed_shift: [f64; 2],
}

/// Extreme positions, located as roots of the velocity analogs (dX/dphi1 = 0) on a sweep of one
/// turn, against the closed forms: crank and rod stretched (outer) or folded (inner).
pub fn extremes(drive: &RhombicDrive) -> Result<Extremes> {
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
    let at_c_outer = f64::atan2(-drive.e_p, x_c_outer);
    let at_c_inner = f64::atan2(drive.e_p, -x_c_inner);
    let at_f_outer = f64::atan2(-e_b, x_f0) - drive.gamma;
    let at_f_inner = f64::atan2(e_b, -x_fmin) - drive.gamma;
    let row = |name, e: kinloop::analysis::Jet, closed, closed_at| DeadCentre {
        name,
        value: e.value,
        at: deg(e.x),
        closed,
        closed_at: deg(closed_at),
    };
    Ok(Extremes {
        rows: [
            row("X_C min (outer)", xc.min, x_c_outer, at_c_outer),
            row("X_C max (inner)", xc.max, x_c_inner, at_c_inner),
            row("X_F max = X_F0", xf.max, x_f0, at_f_outer),
            row("X_F min = X_Fmin", xf.min, x_fmin, at_f_inner),
        ],
        // Phase shift: crank angle from the piston's extreme to the displacer's corresponding
        // one (outer to outer, inner to inner: both pistons farthest from, or nearest to, the
        // crank).
        shift: [deg(xf.max.x - xc.min.x), deg(xf.min.x - xc.max.x)],
        closed_shift: [deg(at_f_outer - at_c_outer), deg(at_f_inner - at_c_inner)],
    })
}

/// Prints the extremes, strokes and phase shifts against the closed forms.
fn report_extremes(drive: &RhombicDrive) -> Result<()> {
    let e = extremes(drive)?;
    println!("\nextreme positions (roots of the velocity analogs) vs closed forms:");
    for r in e.rows {
        println!(
            "  {:<20} {:>16.12} at phi1 = {:>9.5}°   closed form {:>16.12} at {:>9.5}°   (diff {:.1e})",
            r.name,
            r.value,
            r.at,
            r.closed,
            r.closed_at,
            (r.value - r.closed).abs()
        );
    }
    let [c_min, c_max, f_max, f_min] = e.rows;
    println!("piston stroke    {:.12} (closed form {:.12})", c_max.value - c_min.value, c_max.closed - c_min.closed);
    println!("displacer stroke {:.12} (closed form {:.12})", f_max.value - f_min.value, f_max.closed - f_min.closed);
    println!(
        "phase shift of the extremes: outer {:.6}° (closed form {:.6}°), inner {:.6}° (closed form {:.6}°)",
        e.shift[0], e.closed_shift[0], e.shift[1], e.closed_shift[1]
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
