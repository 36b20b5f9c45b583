//! Intermittent-motion gear-lever drive (SEEDS.md, paper 001): a planet gear rolling inside a
//! fixed gear (`u = z1/z3 = 3`) carries a pin in the slot of a rocker pivoted at the centre. The
//! pin traces a prolate hypocycloid with three loops; in each loop the rocker swings back a
//! little: three stops per carrier turn.
//!
//! For `k = l/r = 1.1 ... 1.5` (carrier `L = 2r`, `r = 1`) it prints the dwell duration (carrier
//! angle during a stop), the dwell quality (rocker swing during the stop) and the peak
//! acceleration analog, and draws the paper's Fig. 2 (rocker angle, velocity and acceleration
//! analogs against the carrier angle, `k = 1.3`) and Fig. 3 (the three against `k`).
//!
//! **Dwell** (see `kinloop::analysis::dwell`): in each loop the rocker reverses between a
//! local maximum and the following local minimum of its angle; the dwell is the carrier-angle
//! interval during which the rocker stays within that swing, from where it first reaches the
//! lower edge of the swing to where it passes the upper edge again. Its duration is given in
//! carrier degrees and as a share of the 120° stop cycle; its quality is the swing, in degrees
//! and as a share of the rocker's 120° travel per stop cycle.
//!
//! Run with `cargo run --release --example gear_lever`.

mod common;

use common::{Panel, Series, figure_dir, line_chart, panels};
use kinloop::analysis::{Dwell, Sampled};
use std::f64::consts::{PI, TAU};

kinloop::mechanism! {
    /// Gear-lever drive: carrier `l_c` turning by `alpha`, planet pin at `l_p` from the planet
    /// centre turning by `(1 - u) alpha`, block sliding in a rocker pivoted at O (distance `s`
    /// from O, rocker angle `phi`). Angles from the Y axis as in the paper: direction `a` is
    /// `(sin a, cos a)`.
    #[kinloop(sensitivities)]
    pub struct GearLever {
        params l_c = 2.0, l_p = 1.3, u = 3.0;
        input alpha;
        unknowns s = l_c + l_p, phi = 0;
        let pin = (l_c * sin(alpha), l_c * cos(alpha))
                + (l_p * sin((1 - u) * alpha), l_p * cos((1 - u) * alpha));
        loop oab: pin == s * (sin(phi), cos(phi));
    }
}

/// What the paper's Fig. 3 shows for one `k`.
struct Stop {
    /// Dwell duration in carrier degrees.
    duration: f64,
    /// Rocker swing during the stop, degrees.
    swing: f64,
    /// Largest acceleration analog eps_r / omega^2 over a turn, and where it occurs (carrier
    /// degrees modulo the 120° stop cycle; by symmetry the smallest is its negative).
    peak_acc: f64,
    peak_at: f64,
}

/// The stops (dwells of the rocker) over one carrier turn, and the largest acceleration analog
/// with the carrier angle where it occurs.
pub fn stops(m: &GearLever) -> Result<(Vec<Dwell>, (f64, f64)), kinloop::Error> {
    // The turn starts at alpha = -60 degrees, where the pin is nearest the centre and the rocker
    // moves fastest, so the three stops of the turn (around 0, 120 and 240 degrees) lie inside.
    let from = -PI / 3.0;
    let turn = Sampled::sweep(m, from, from + TAU, 721, m.guess(from).into())?;
    Ok((turn.dwells("phi")?, turn.peak(|s| s.d2q[1][0][0])?))
}

fn stop(k: f64) -> Result<Stop, kinloop::Error> {
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
        marks[0].push((k, s.duration));
        marks[1].push((k, s.swing));
        marks[2].push((k, s.peak_acc));
    }
    println!("(planet: the dwell measured on a main shaft turning with the planet, u times the carrier dwell)");

    // Fig. 3: the same against k on a fine grid.
    let mut curves = [Vec::new(), Vec::new(), Vec::new()];
    for i in 0..=50 {
        let k = 1.05 + 0.01 * i as f64;
        let s = stop(k)?;
        curves[0].push((k, s.duration));
        curves[1].push((k, s.swing));
        curves[2].push((k, s.peak_acc));
    }
    let dir = figure_dir("gear_lever");
    let [c0, c1, c2] = curves;
    let [m0, m1, m2] = marks;
    panels(
        &dir.join("dwell_vs_k.svg"),
        "Gear-lever drive (u = 3): stop characteristics against k = l/r (dots: k = 1.1 ... 1.5)",
        "pin radius k = l/r",
        &[
            Panel {
                y_label: "dwell [carrier deg]",
                series: vec![Series { label: "dwell duration", points: c0 }],
                marks: m0,
            },
            Panel {
                y_label: "swing [deg]",
                series: vec![Series { label: "rocker swing in the stop", points: c1 }],
                marks: m1,
            },
            Panel {
                y_label: "max eps_r/omega^2",
                series: vec![Series { label: "peak acceleration analog", points: c2 }],
                marks: m2,
            },
        ],
    )?;

    // Fig. 2 for k = 1.3, and the rocker angle for every k.
    let m = GearLever { l_p: 1.3, ..GearLever::default() };
    let states: Vec<_> = m.sweep(0.0, TAU, 721, &m.guess(0.0))?.collect::<Result<_, _>>()?;
    let curve = |f: &dyn Fn(&GearLeverState) -> f64| -> Vec<(f64, f64)> {
        states.iter().map(|s| (s.input.alpha.to_degrees(), f(s))).collect()
    };
    panels(
        &dir.join("rocker_k13.svg"),
        "Gear-lever drive, k = 1.3: rocker angle, velocity and acceleration analogs",
        "carrier angle alpha [deg]",
        &[
            Panel {
                y_label: "phi [deg]",
                series: vec![Series { label: "rocker angle", points: curve(&|s| s.q.phi.to_degrees()) }],
                marks: vec![],
            },
            Panel {
                y_label: "omega_r / omega",
                series: vec![Series { label: "velocity analog", points: curve(&|s| s.dq.phi) }],
                marks: vec![],
            },
            Panel {
                y_label: "eps_r / omega^2",
                series: vec![Series { label: "acceleration analog", points: curve(&|s| s.d2q.phi) }],
                marks: vec![],
            },
        ],
    )?;
    let mut all = Vec::new();
    for k in ks {
        let m = GearLever { l_p: k, ..GearLever::default() };
        let pts = m
            .sweep(0.0, TAU, 721, &m.guess(0.0))?
            .map(|s| s.map(|s| (s.input.alpha.to_degrees(), s.q.phi.to_degrees())))
            .collect::<Result<Vec<_>, _>>()?;
        all.push((k, pts));
    }
    let labels: Vec<String> = ks.iter().map(|k| format!("k = {k}")).collect();
    line_chart(
        &dir.join("rocker_angle.svg"),
        "Gear-lever drive: rocker angle over a carrier turn",
        "carrier angle alpha [deg]",
        "rocker angle phi [deg]",
        &all.into_iter().zip(&labels).map(|((_, p), l)| Series { label: l, points: p }).collect::<Vec<_>>(),
    )?;
    println!("\nwrote dwell_vs_k.svg, rocker_k13.svg, rocker_angle.svg to {}", dir.display());
    Ok(())
}
