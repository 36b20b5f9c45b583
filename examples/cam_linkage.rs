//! Kinematic analysis of a cam-linkage drive: an eccentric disc cam turns the bell-crank rocker
//! of a roller follower, which drives a slider through a connecting rod. Prints a table every
//! 30 degrees of the cam, the rocker's swing and the slider's stroke (extremes located as roots
//! of the velocity analogs) against the closed form of the equivalent four-bar's limit
//! positions, and the largest pressure angle of the cam.
//!
//! Run with `cargo run --release -p kinloop-examples --example cam_linkage`. It writes the sweep
//! as CSV and SVG charts into `out/cam_linkage/` (the charts into `$KINLOOP_FIGURES/cam_linkage/`
//! when that variable is set).

use kinloop::Table;
use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop_fixtures::cam_linkage::{CamLinkage, CamLinkageState};
use std::f64::consts::{PI, TAU};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The drive's lengths are in millimetres.
const UNIT: &str = "mm";

fn main() -> Result<()> {
    let drive = CamLinkage::default();
    println!("Cam-linkage drive: {drive:?}\n");
    // A full turn in steps of 1 degree, each solve warm-started from the previous position so
    // the drive stays in the declared assembly mode.
    let mut guess = drive.guess(0.0);
    let mut states: Vec<CamLinkageState> = Vec::with_capacity(361);
    for k in 0..=360 {
        let state = drive.kinematics(f64::from(k).to_radians(), &guess)?;
        guess = state.q;
        states.push(state);
    }
    println!(
        "{:>6} {:>9} {:>9} {:>9} {:>10} {:>10} {:>10} {:>9}",
        "phi", "psi [°]", "x [mm]", "dpsi/dphi", "dx/dphi", "d2psi", "d2x", "pressure"
    );
    for s in states.iter().step_by(30) {
        println!(
            "{:>5.0}° {:>9.4} {:>9.4} {:>9.5} {:>10.5} {:>10.5} {:>10.5} {:>8.3}°",
            s.input.phi.to_degrees(),
            s.q.psi.to_degrees(),
            s.q.x,
            s.dq.psi,
            s.dq.x,
            s.d2q.psi,
            s.d2q.x,
            s.out.pressure.to_degrees()
        );
    }
    report_extremes(&drive)?;
    let worst = states.iter().map(|s| s.out.pressure.abs()).fold(0.0, f64::max);
    println!("largest pressure angle of the cam: {:.3}°", worst.to_degrees());
    write_outputs(&states)
}

/// An extreme of the rocker's angle or of the slider's position over a turn: located along the
/// sweep as a root of its velocity analog, and at a limit position of the equivalent four-bar.
/// Angles in degrees (cam angles in `[0, 360)`), positions in millimetres.
#[derive(Clone, Copy, Debug)]
pub struct Limit {
    /// Which quantity and which extreme.
    pub name: &'static str,
    /// The unit of `value` and `closed`.
    pub unit: &'static str,
    /// The extreme located along the sweep.
    pub value: f64,
    /// The cam angle there.
    pub at: f64,
    /// The extreme at the four-bar's limit position.
    pub closed: f64,
    /// The cam angle of that limit position.
    pub closed_at: f64,
}

/// The rocker's largest and smallest angle and the slider's largest and smallest position, in
/// that order, against the limit positions of the equivalent four-bar.
pub fn extremes(m: &CamLinkage) -> Result<[Limit; 4]> {
    let turn = m.sampled(0.0, TAU, 361, &m.guess(0.0))?;
    let swing = turn.range(CamLinkage::COL.psi)?;
    let stroke = turn.range(CamLinkage::COL.x)?;
    // Limit positions: cam crank e and roller line r_cam + r_roller stretched or folded, so the
    // roller centre P is at b + e or b - e from the shaft and at l_arm from the pivot A.
    let b = m.r_cam + m.r_roller;
    let limit = |radius: f64| {
        let (ux, uy) = (-m.a_x, -m.a_y);
        let d = ux.hypot(uy);
        let along = (m.l_arm * m.l_arm - radius * radius + d * d) / (2.0 * d);
        let across = (m.l_arm * m.l_arm - along * along).sqrt();
        let (px, py) = (m.a_x + (along * ux - across * uy) / d, m.a_y + (along * uy + across * ux) / d);
        ((py - m.a_y).atan2(px - m.a_x), py.atan2(px))
    };
    let ((psi_out, at_out), (psi_in, at_in)) = (limit(b + m.e), limit(b - m.e));
    let slider = |psi: f64| {
        let (qx, qy) = (m.a_x + m.l_out * (psi + m.delta).cos(), m.a_y + m.l_out * (psi + m.delta).sin());
        qx + (m.l_rod * m.l_rod - (m.h - qy).powi(2)).sqrt()
    };
    let deg = |a: f64| a.to_degrees().rem_euclid(360.0);
    // (rocker angle, cam angle) at the stretched and the folded limit position, the larger first.
    let (out, inn) = ((psi_out, at_out), (psi_in, at_in + PI));
    let (hi, lo) = if psi_out > psi_in { (out, inn) } else { (inn, out) };
    let (x_hi, x_lo) = (slider(hi.0), slider(lo.0));
    let (x_max, x_min) = if x_hi > x_lo { ((x_hi, hi.1), (x_lo, lo.1)) } else { ((x_lo, lo.1), (x_hi, hi.1)) };
    let row = |name, unit, value: f64, at: f64, closed: f64, closed_at: f64| Limit {
        name,
        unit,
        value,
        at: deg(at),
        closed,
        closed_at: deg(closed_at),
    };
    Ok([
        row("rocker psi max", "°", swing.max.value.to_degrees(), swing.max.x, hi.0.to_degrees(), hi.1),
        row("rocker psi min", "°", swing.min.value.to_degrees(), swing.min.x, lo.0.to_degrees(), lo.1),
        row("slider x max", " mm", stroke.max.value, stroke.max.x, x_max.0, x_max.1),
        row("slider x min", " mm", stroke.min.value, stroke.min.x, x_min.0, x_min.1),
    ])
}

/// Prints the swing and the stroke from the sweep against the limit positions of the
/// equivalent four-bar.
fn report_extremes(m: &CamLinkage) -> Result<()> {
    let rows = extremes(m)?;
    println!("\nextremes (roots of the velocity analogs) vs the four-bar's limit positions:");
    for r in rows {
        println!(
            "  {:<15} {:>14.9}{} at {:>9.5}°   closed form {:>14.9}{} at {:>9.5}°",
            r.name, r.value, r.unit, r.at, r.closed, r.unit, r.closed_at
        );
    }
    let [psi_max, psi_min, x_max, x_min] = rows;
    println!(
        "rocker swing  {:.9}° (closed form {:.9}°)",
        psi_max.value - psi_min.value,
        psi_max.closed - psi_min.closed
    );
    println!("slider stroke {:.9} mm (closed form {:.9} mm)", x_max.value - x_min.value, x_max.closed - x_min.closed);
    Ok(())
}

/// The sweep as CSV and its charts as SVG.
fn write_outputs(states: &[CamLinkageState]) -> Result<()> {
    let data = plot::out_dir("cam_linkage")?;
    let table = Table::from_states::<CamLinkage, _, _, _>(states.iter().map(|s| &s.flat)).with_length_unit(UNIT);
    table.save_csv(data.join("sweep.csv"))?;
    let dir = plot::figure_dir("cam_linkage")?;
    let cam = Axis::angle("cam angle φ");
    let column = |name: &str, kind: Kind, label: &str| -> Result<Series> {
        Ok(Series { label: label.to_string(), ..Series::from_table(&table, "phi", name, kind)? })
    };
    let panel = |title: &str, psi: &str, x: &str, angle: Kind, length: Kind| -> Result<[Panel; 2]> {
        Ok([
            Panel::new(Axis::new(&format!("rocker {title}"), angle.clone())).with(column(psi, angle, "ψ (rocker)")?),
            Panel::new(Axis::new(&format!("slider {title}"), length.clone())).with(column(x, length, "x (slider)")?),
        ])
    };
    plot::panels(
        &dir.join("positions.svg"),
        "Cam-linkage drive: rocker and slider positions",
        &cam,
        &panel("position", "psi", "x", Kind::Angle, Kind::length(UNIT))?,
    )?;
    plot::panels(
        &dir.join("velocity_analogs.svg"),
        "Cam-linkage drive: velocity analogs",
        &cam,
        &panel("dq/dφ", "d(psi)/d(phi)", "d(x)/d(phi)", Kind::AngleAnalog, Kind::LengthAnalog(UNIT.into()))?,
    )?;
    plot::panels(
        &dir.join("acceleration_analogs.svg"),
        "Cam-linkage drive: acceleration analogs",
        &cam,
        &panel("d²q/dφ²", "d2(psi)/d(phi)^2", "d2(x)/d(phi)^2", Kind::AngleAnalog2, Kind::LengthAnalog2(UNIT.into()))?,
    )?;
    println!("\nwrote {} and 3 charts to {}", data.join("sweep.csv").display(), dir.display());
    Ok(())
}
