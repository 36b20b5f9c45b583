//! Limit positions and change points located along sweeps.
//!
//! * A non-Grashof four-bar driven by its input link cannot turn fully: the sweep stops at the
//!   limit position (coupler and rocker collinear) and reports the located input value, which is
//!   compared with the law of cosines; the reachable range is found both ways; pseudo-arclength
//!   continuation then traces the whole closed curve through both limits.
//! * A four-bar at a change point (s + l = p + q) reaches a position where its two assembly
//!   modes meet: the sweep reports the singular crossing instead of silently changing branch.
//!
//! Run with `cargo run --release -p kinloop-examples --example limit_positions`.

use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop::{AtSingular, SweepConfig};
use kinloop_fixtures::{FourBar, FourBarUnknowns};
use std::f64::consts::PI;

/// What the example finds of a four-bar whose input link cannot turn fully, swept from 0
/// towards pi on the assembly mode of its declared guess.
pub struct Limits {
    /// Why the sweep stopped, as it says.
    pub stopped: Option<String>,
    /// The last sample the sweep reached.
    pub last: f64,
    /// The sweep's events: kind, the located input, and the coupler and rocker angles there.
    pub events: Vec<(kinloop::EventKind, f64, [f64; 2])>,
    /// The limit position by the law of cosines: coupler and rocker stretched, `|BD| = b + c`.
    pub law: f64,
    /// The reachable input range on this assembly mode.
    pub reach: [f64; 2],
    /// The closed curve traced by continuation through both limits.
    pub traced: kinloop::Traced<2, 1>,
}

/// Sweeps `m` from 0 towards pi, finds its reachable range, and traces its whole curve.
pub fn limits(m: &FourBar) -> Result<Limits, Box<dyn std::error::Error>> {
    let g = m.position(0.0, &m.guess(0.0))?.0;
    let mut sweep = m.sweep(0.0, PI, 37, &g)?;
    let (mut stopped, mut last) = (None, 0.0);
    for state in &mut sweep {
        match state {
            Ok(s) => last = s.input.phi,
            Err(e) => stopped = Some(e.to_string()),
        }
    }
    let events = sweep.events().iter().map(|ev| (ev.kind, ev.x[0], [ev.q[0], ev.q[1]])).collect();
    let law = ((m.a * m.a + m.d * m.d - (m.b + m.c).powi(2)) / (2.0 * m.a * m.d)).acos();
    let reach = m.reachable(0.0, PI, &g, 91)?;
    let traced = m.trace_curve(0.0, PI, &g, &kinloop::TraceConfig::default())?;
    Ok(Limits { stopped, last, events, law, reach: [reach.from.phi, reach.to.phi], traced })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // s + l = 2 + 4 > p + q = 2.5 + 3: non-Grashof.
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    println!("Non-Grashof four-bar {m:?}");
    let found = limits(&m)?;
    if let Some(e) = &found.stopped {
        println!("  sweep 0 -> pi stopped: {e}");
    }
    let last = found.last;
    println!("  last sample reached: phi = {:.6} rad ({:.3} deg)", last, last.to_degrees());
    for &(kind, x, [beta, gamma]) in &found.events {
        let law = found.law;
        println!(
            "  event {kind:?} at phi = {x:.12} rad; law of cosines gives {law:.12} (difference {:.1e}); \
             beta = {beta:.6}, gamma = {gamma:.6}",
            (x - law).abs(),
        );
    }
    let [lo, hi] = found.reach;
    println!("  reachable input range on this assembly mode: [{lo:.12}, {hi:.12}] rad");
    let traced = &found.traced;
    println!(
        "  arclength continuation: {} points, closed = {}, limit positions at {:?}",
        traced.points.len(),
        traced.closed,
        traced.folds.iter().map(|f| format!("{:.12}", f.x[0])).collect::<Vec<_>>()
    );
    let dir = plot::figure_dir("limit_positions")?;
    let curve = |label: &str, u: usize| {
        let points: Vec<(f64, f64)> = traced.points.iter().map(|p| (p.x[0], p.q[u])).collect();
        Series::new(label, Kind::Angle, plot::decimate(&points, 600))
    };
    // The limit positions (dots) on both curves.
    let folds = traced.folds.iter().flat_map(|f| [(f.x[0], f.q[0]), (f.x[0], f.q[1])]);
    plot::panels(
        &dir.join("closed_curve.svg"),
        "Non-Grashof four-bar: closed curve by continuation (dots: limit positions)",
        &Axis::angle("input angle φ"),
        &[Panel::new(Axis::angle("link angle"))
            .with(curve("coupler β", 0))
            .with(curve("rocker γ", 1))
            .with_marks(folds)],
    )?;

    change_point()?;
    println!("\nwrote {}", dir.join("closed_curve.svg").display());
    Ok(())
}

/// A four-bar at a change point: the sweep stops at the singular crossing, or passes it when told
/// to and changes the assembly mode.
fn change_point() -> Result<(), Box<dyn std::error::Error>> {
    // Change point: s + l = 1 + 3 = p + q = 2 + 2.
    let cp = FourBar { a: 1.0, b: 3.0, c: 2.0, d: 2.0 };
    let g = cp.position(0.5, &FourBarUnknowns { beta: 0.6, gamma: 1.6 })?.0;
    println!("\nChange-point four-bar {cp:?}");
    let mut sweep = cp.sweep(0.5, 7.0, 66, &g)?;
    if let Some(Err(e)) = sweep.by_ref().find(|s| s.is_err()) {
        println!("  default sweep stopped: {e}");
    }
    for ev in sweep.events() {
        println!(
            "  event {:?} at phi = {:.12} (2 pi = {:.12}), block {:?}",
            ev.kind,
            ev.x[0],
            2.0 * PI,
            ev.block.as_ref().map(|b| b.0)
        );
    }
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let mut sweep = cp.sweep(0.5, 7.0, 66, &g)?.with_config(cfg);
    let states: Vec<_> = sweep.by_ref().collect::<Result<_, _>>()?;
    println!(
        "  with AtSingular::Continue: {} samples, {} event(s), assembly mode (det signs) {:#b} -> {:#b}",
        states.len(),
        sweep.events().len(),
        states[0].health.det_signs,
        states[states.len() - 1].health.det_signs
    );
    Ok(())
}
