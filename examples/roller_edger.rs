//! Roller edger (tilter) of a rolling mill, lever-turning mode (`docs/papers.md`, paper 002): a
//! hydraulic cylinder pivoted at O1 extends at constant speed, `S1 = V1 t`, so the input is time.
//! Contour O1 A O3 O1: cylinder 1 (length `S1 + l1`, angle `phi1`) and link 3 (`l3`, turning
//! about O3, angle `phi3`), frame O1O3 = `l5` at angle `alpha`. Contour O2 B A O3 O2: cylinder 2
//! (held at length `s2 + l2`, angle `phi2`) and link 4 from B to A (`l4`, angle `phi4`), frame
//! O2O3 = `l6` at angle `beta`.
//!
//! Dimensions (metres, seconds): `l1 = 0.9, l3 = 0.6, l5 = 1.2, alpha = 0.2 rad, V1 = 0.05 m/s,
//! l2 = 1.0, s2 = 0.1, l4 = 0.7, l6 = 1.4, beta = 0.9 rad`, for `t` from 0 to 6 s.
//!
//! It prints the angles, angular velocities and accelerations of all four links against time
//! (the analogs of a time input are the true angular velocities and accelerations) and their
//! largest deviations from the closed forms: the law of cosines for contour 1 (with the branch
//! pair `phi3 = alpha - acos(.)`, `phi1 = alpha + acos(.)`: the paper prints `phi1 = alpha -
//! acos(.)`, which belongs to the other assembly mode), and for contour 2 the triangle O2 B A
//! with velocities and accelerations from its differentiated loop equation.
//!
//! Run with `cargo run --release -p kinloop-examples --example roller_edger`.

use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop_fixtures::roller_edger::{RollerEdger, RollerEdgerState, closed, solved};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let m = RollerEdger::default();
    println!("Roller edger, lever-turning mode (paper 002): {m:?}\n");
    let states: Vec<_> = m.sweep(0.0, 6.0, 601, &m.guess(0.0))?.collect::<Result<_, _>>()?;
    println!(
        "{:>5} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "t [s]",
        "phi1 [°]",
        "phi3 [°]",
        "phi2 [°]",
        "phi4 [°]",
        "w1 [1/s]",
        "w3 [1/s]",
        "w2 [1/s]",
        "w4 [1/s]",
        "e1 [1/s2]",
        "e3 [1/s2]",
        "e2 [1/s2]",
        "e4 [1/s2]"
    );
    for s in states.iter().step_by(50) {
        println!(
            "{:>5.1} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>10.6} {:>10.6} {:>10.6} {:>10.6} \
             {:>10.3e} {:>10.3e} {:>10.3e} {:>10.3e}",
            s.input.t,
            s.q.phi1.to_degrees(),
            s.q.phi3.to_degrees(),
            s.q.phi2.to_degrees(),
            s.q.phi4.to_degrees(),
            s.dq.phi1,
            s.dq.phi3,
            s.dq.phi2,
            s.dq.phi4,
            s.d2q.phi1,
            s.d2q.phi3,
            s.d2q.phi2,
            s.d2q.phi4,
        );
    }

    // Largest deviations from the closed forms over the 601 instants, per order.
    let mut dev = [[0.0f64; 3]; 4];
    for s in &states {
        let (c, got) = (closed(&m, s.input.t), solved(s));
        for l in 0..4 {
            for o in 0..3 {
                dev[l][o] = dev[l][o].max((got[l][o] - c[l][o]).abs());
            }
        }
    }
    println!("\nlargest deviation from the closed forms over t = 0 .. 6 s (angle, angular velocity, acceleration):");
    for (name, d) in ["phi1", "phi3", "phi2", "phi4"].iter().zip(dev) {
        println!("  {name}: {:.1e} rad, {:.1e} rad/s, {:.1e} rad/s^2", d[0], d[1], d[2]);
    }

    let [t, closed_t, phi1] = turn_back(&m)?;
    println!("cylinder 1 turns back at t = {t:.6} s (closed form {closed_t:.6} s), phi1 = {:.6}°", phi1.to_degrees());

    let dir = draw(&states)?;
    println!("\nwrote angles_velocities_accelerations.svg to {}", dir.display());
    Ok(())
}

/// When cylinder 1 turns back: `[t, t by the closed form, phi1 there]`. It turns back when it
/// is perpendicular to link 3 (`s^2 = l5^2 - l3^2`), located along the stroke as the maximum of
/// `phi1`, a root of its angular velocity.
pub fn turn_back(m: &RollerEdger) -> Result<[f64; 3], kinloop::Error> {
    let run = m.sampled(0.0, 6.0, 61, &m.guess(0.0))?;
    let top = run.range(RollerEdger::COL.phi1)?.max;
    Ok([top.x, ((m.l5 * m.l5 - m.l3 * m.l3).sqrt() - m.l1) / m.v1, top.value])
}

/// The paper's figure: link angles, angular velocities and accelerations against time; returns
/// the folder it went to.
fn draw(states: &[RollerEdgerState]) -> Result<std::path::PathBuf, Box<dyn std::error::Error>> {
    let dir = plot::figure_dir("roller_edger")?;
    let velocity = Kind::AngularSpeed;
    let acceleration = Kind::Other { quantity: "angular acceleration".into(), unit: "rad/s²".into() };
    // One panel per order, each with the four links.
    let panel = |axis: Axis, of: [fn(&RollerEdgerState) -> f64; 4]| {
        let links = ["link 1 (cylinder 1)", "link 3", "link 2 (cylinder 2)", "link 4"];
        links.into_iter().zip(of).fold(Panel::new(axis.clone()), |p, (label, f)| {
            p.with(Series::new(label, axis.kind.clone(), states.iter().map(|s| (s.input.t, f(s))).collect()))
        })
    };
    plot::panels(
        &dir.join("angles_velocities_accelerations.svg"),
        "Roller edger (V1 = 0.05 m/s): link angles and their rates",
        &Axis::new("time t", Kind::time("s")),
        &[
            panel(Axis::angle("link angle"), [|s| s.q.phi1, |s| s.q.phi3, |s| s.q.phi2, |s| s.q.phi4]),
            panel(
                Axis::new("angular velocity", velocity),
                [|s| s.dq.phi1, |s| s.dq.phi3, |s| s.dq.phi2, |s| s.dq.phi4],
            ),
            panel(
                Axis::new("angular acceleration", acceleration),
                [|s| s.d2q.phi1, |s| s.d2q.phi3, |s| s.d2q.phi2, |s| s.d2q.phi4],
            ),
        ],
    )?;
    Ok(dir)
}
