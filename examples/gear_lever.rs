//! Intermittent-motion gear-lever drive (`docs/papers.md`, paper 001): a planet gear rolling inside a
//! fixed gear (`u = z1/z3 = 3`) carries a pin in the slot of a rocker pivoted at the centre. The
//! pin traces a prolate hypocycloid with three loops; in each loop the rocker swings back a
//! little: three stops per carrier turn.
//!
//! For `k = l/r = 1.1 ... 1.5` (carrier `L = 2r`, `r = 1`) it prints the dwell duration (carrier
//! angle during a stop), the dwell quality (rocker swing during the stop) and the peak
//! acceleration analog, and draws the paper's Fig. 2 (rocker angle, velocity and acceleration
//! analogs against the carrier angle, `k = 1.3`), Fig. 3 (the three against `k`) and the rocker
//! angle for every `k` (`rocker_k13.svg`, `dwell_vs_k.svg`, `rocker_angle.svg`, in
//! `out/gear_lever/` or `$KINLOOP_FIGURES/gear_lever/`).
//!
//! **Dwell** (see `kinloop::analysis::dwell`): in each loop the rocker reverses between a
//! local maximum and the following local minimum of its angle; the dwell is the carrier-angle
//! interval during which the rocker stays within that swing, from where it first reaches the
//! lower edge of the swing to where it passes the upper edge again. Its duration is given in
//! carrier degrees and as a share of the 120° stop cycle; its quality is the swing, in degrees
//! and as a share of the rocker's 120° travel per stop cycle.
//!
//! Run with `cargo run --release -p kinloop-examples --example gear_lever`.

use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop_fixtures::gear_lever::{GearLever, GearLeverState, stops};
use std::f64::consts::TAU;

/// What the paper's Fig. 3 shows for one `k`.
pub struct Stop {
    /// Dwell duration in carrier degrees.
    pub duration: f64,
    /// Rocker swing during the stop, degrees.
    pub swing: f64,
    /// Largest acceleration analog eps_r / omega^2 over a turn (by symmetry the smallest is its
    /// negative).
    pub peak_acc: f64,
    /// Where it occurs: carrier degrees modulo the 120° stop cycle.
    pub peak_at: f64,
}

/// The stop of the drive with the pin at `k` planet radii from the planet's centre.
pub fn stop(k: f64) -> Result<Stop, kinloop::Error> {
    let (dwells, (peak_at, peak_acc)) = stops(&GearLever { l_p: k, ..GearLever::default() })?;
    assert_eq!(dwells.len(), 3, "three stops per turn for k = {k}");
    let d = dwells[0];
    Ok(Stop {
        duration: d.duration().to_degrees(),
        swing: d.swing().to_degrees(),
        peak_acc,
        peak_at: peak_at.to_degrees().rem_euclid(120.0),
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("Gear-lever intermittent drive (paper 001): u = 3, L = 2, l = k (r = 1)\n");
    println!(
        "{:>4} {:>14} {:>10} {:>12} {:>10} {:>14} {:>10} {:>12}",
        "k", "dwell [deg]", "of 120°", "planet [deg]", "swing [°]", "of 120° travel", "max a_q", "at mod 120°"
    );
    let ks = [1.1, 1.2, 1.3, 1.4, 1.5];
    let mut marks = [Vec::new(), Vec::new(), Vec::new()];
    for k in ks {
        let s = stop(k)?;
        println!(
            "{k:>4.1} {:>14.6} {:>9.2}% {:>12.6} {:>10.6} {:>13.4}% {:>10.6} {:>12.6}",
            s.duration,
            100.0 * s.duration / 120.0,
            3.0 * s.duration,
            s.swing,
            100.0 * s.swing / 120.0,
            s.peak_acc,
            s.peak_at
        );
        marks[0].push((k, s.duration.to_radians()));
        marks[1].push((k, s.swing.to_radians()));
        marks[2].push((k, s.peak_acc));
    }
    println!("(planet: the dwell measured on a main shaft turning with the planet, u times the carrier dwell)");

    let dir = plot::figure_dir("gear_lever")?;
    draw_stops_against_k(&dir, marks)?;
    draw_rocker_motion(&dir, &ks)?;
    println!("\nwrote dwell_vs_k.svg, rocker_k13.svg, rocker_angle.svg to {}", dir.display());
    Ok(())
}

/// The paper's Fig. 3: the stop characteristics against `k` on a fine grid, with the table's `k`
/// marked (angles in radians, the plot shows degrees).
fn draw_stops_against_k(dir: &std::path::Path, marks: [Vec<(f64, f64)>; 3]) -> Result<(), Box<dyn std::error::Error>> {
    let mut curves = [Vec::new(), Vec::new(), Vec::new()];
    for i in 0..=50 {
        let k = 1.05 + 0.01 * i as f64;
        let s = stop(k)?;
        curves[0].push((k, s.duration.to_radians()));
        curves[1].push((k, s.swing.to_radians()));
        curves[2].push((k, s.peak_acc));
    }
    let [c0, c1, c2] = curves;
    let [m0, m1, m2] = marks;
    plot::panels(
        &dir.join("dwell_vs_k.svg"),
        "Gear-lever drive (u = 3): stops against k = l/r (dots: k = 1.1 ... 1.5)",
        &Axis::new("pin radius ratio k = l/r", Kind::Dimensionless),
        &[
            Panel::new(Axis::angle("dwell duration (carrier)"))
                .with(Series::new("dwell duration", Kind::Angle, c0))
                .with_marks(m0),
            Panel::new(Axis::angle("rocker swing in the stop"))
                .with(Series::new("rocker swing", Kind::Angle, c1))
                .with_marks(m1),
            Panel::new(Axis::new("peak ε_r/ω²", Kind::AngleAnalog2))
                .with(Series::new("peak acceleration analog", Kind::AngleAnalog2, c2))
                .with_marks(m2),
        ],
    )?;
    Ok(())
}

/// The paper's Fig. 2 for k = 1.3, and the rocker angle for every `k` of the table.
fn draw_rocker_motion(dir: &std::path::Path, ks: &[f64]) -> Result<(), Box<dyn std::error::Error>> {
    let m = GearLever { l_p: 1.3, ..GearLever::default() };
    let states: Vec<_> = m.sweep(0.0, TAU, 721, &m.guess(0.0))?.collect::<Result<_, _>>()?;
    let curve = |label: &str, kind: Kind, f: fn(&GearLeverState) -> f64| {
        Series::new(label, kind, states.iter().map(|s| (s.input.alpha, f(s))).collect())
    };
    let carrier = Axis::angle("carrier angle α");
    plot::panels(
        &dir.join("rocker_k13.svg"),
        "Gear-lever drive, k = 1.3: rocker angle, velocity and acceleration analogs",
        &carrier,
        &[
            Panel::new(Axis::angle("rocker angle φ")).with(curve("rocker angle", Kind::Angle, |s| s.q.phi)),
            Panel::new(Axis::new("ω_r/ω", Kind::AngleAnalog))
                .with(curve("velocity analog", Kind::AngleAnalog, |s| s.dq.phi)),
            Panel::new(Axis::new("ε_r/ω²", Kind::AngleAnalog2)).with(curve(
                "acceleration analog",
                Kind::AngleAnalog2,
                |s| s.d2q.phi,
            )),
        ],
    )?;
    let mut all = Vec::new();
    for &k in ks {
        let m = GearLever { l_p: k, ..GearLever::default() };
        let pts = m
            .sweep(0.0, TAU, 721, &m.guess(0.0))?
            .map(|s| s.map(|s| (s.input.alpha, s.q.phi)))
            .collect::<Result<Vec<_>, _>>()?;
        all.push(Series::new(&format!("k = {k}"), Kind::Angle, pts));
    }
    plot::line_chart(
        &dir.join("rocker_angle.svg"),
        "Gear-lever drive: rocker angle over a carrier turn",
        &carrier,
        &Axis::angle("rocker angle φ"),
        &all,
    )?;
    Ok(())
}
