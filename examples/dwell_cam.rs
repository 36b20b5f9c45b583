//! The rise-dwell-return-dwell cam as a cam designer reads it: a disc cam lifts a translating
//! follower by the 3-4-5 polynomial law, and the follower swings a rocker through a rod. Prints a
//! table every 15 degrees of the cam (follower lift, rocker angle, their analogs), checks that
//! the follower and the rocker stand exactly still in each dwell (velocity and acceleration
//! analogs zero), and sets the peak velocity and acceleration analogs of the rise and of the
//! return, located along the sweep, beside the law's closed-form peaks. Then the cam itself: its
//! pitch curve and profile for a 10 mm roller by kinematic inversion of the follower's motion,
//! the largest pressure angle of the rise and of the return, and the sharpest point of the
//! profile against the roller (undercut or not).
//!
//! Run with `cargo run --release -p kinloop-examples --example dwell_cam`. It writes the sweep
//! and the cam's profile as CSV into `out/dwell_cam/` and the follower's, the rocker's and the
//! cam's charts as SVG into the figure folder (`KINLOOP_FIGURES=docs/figures` for the
//! README's).

use kinloop::Table;
use kinloop::analysis::Sampled;
use kinloop::analysis::cam::CamProfile;
use kinloop::plot::{self, Axis, Kind, Panel, Series};
pub use kinloop_examples::dwell_cam::{ROLLER, cam, peak_pressure, turn};
use kinloop_fixtures::cam_linkage::{DwellCamRocker, DwellCamRockerState};
use std::f64::consts::TAU;

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// The drive's lengths are in millimetres.
const UNIT: &str = "mm";

/// Peak velocity analog of the 3-4-5 law, in units of `h / beta`: `30 u^2 (1 - u)^2` at `u = 1/2`.
pub const PEAK_VELOCITY: f64 = 1.875;

/// A located peak: the cam angle (radians) and the value there.
#[derive(Clone, Copy, Debug)]
pub struct Peak {
    pub at: f64,
    pub value: f64,
}

/// The peaks of the follower's analogs over one moving segment of the law: the velocity
/// analog of largest magnitude, and the largest and the smallest acceleration analog.
#[derive(Clone, Copy, Debug)]
pub struct SegmentPeaks {
    pub velocity: Peak,
    pub acceleration_max: Peak,
    pub acceleration_min: Peak,
}

/// A moving segment of the law: it starts at cam angle `start` and lasts `span`; `sign` is
/// `1` for the rise, `-1` for the return.
#[derive(Clone, Copy, Debug)]
pub struct Segment {
    pub name: &'static str,
    pub start: f64,
    pub span: f64,
    pub sign: f64,
}

/// A dwell of the law, from cam angle `from` to `to`.
#[derive(Clone, Copy, Debug)]
pub struct Dwell {
    pub name: &'static str,
    pub from: f64,
    pub to: f64,
}

/// The follower and rocker over a dwell: where they stand, and the largest magnitudes of
/// their analogs (all zero when they stand exactly still).
#[derive(Clone, Copy, Debug)]
pub struct DwellCheck {
    pub samples: usize,
    pub lift: f64,
    pub psi: f64,
    /// Largest `|ds/dphi|`, `|d2s/dphi2|`, `|dpsi/dphi|`, `|d2psi/dphi2|`.
    pub analogs: [f64; 4],
    /// The follower and rocker did not move between the samples (their positions all equal).
    pub still: bool,
}

/// The rise and the return of `m`.
pub fn segments(m: &DwellCamRocker) -> [Segment; 2] {
    [
        Segment { name: "rise", start: m.phi0, span: m.rise, sign: 1.0 },
        Segment { name: "return", start: m.phi1, span: m.fall, sign: -1.0 },
    ]
}

/// The dwells of `m` over one turn: at the bottom before the rise, at the top, at the bottom
/// after the return.
pub fn dwells(m: &DwellCamRocker) -> [Dwell; 3] {
    [
        Dwell { name: "bottom", from: 0.0, to: m.phi0 },
        Dwell { name: "top", from: m.phi0 + m.rise, to: m.phi1 },
        Dwell { name: "bottom", from: m.phi1 + m.fall, to: TAU },
    ]
}

/// The follower and the rocker over a dwell, solved at every tenth of a degree strictly
/// inside it and at 1e-9 rad inside each end. The ends themselves are left out: there a
/// segment's polynomial meets the dwell, and its analogs vanish only up to rounding.
pub fn check_dwell(m: &DwellCamRocker, d: &Dwell) -> Result<DwellCheck> {
    let mut phis = vec![d.from + 1e-9, d.to - 1e-9];
    phis.extend((0..3600).map(|k| f64::from(k).to_radians() / 10.0).filter(|&p| p > d.from && p < d.to));
    let first = m.solve(phis[0])?;
    let (lift, psi) = (first.out.follower.y - m.y0, first.q.psi);
    let (mut analogs, mut still) = ([0.0f64; 4], true);
    for &phi in &phis {
        let s = m.solve(phi)?;
        let now = [s.dout.follower.y, s.d2out.follower.y, s.dq.psi, s.d2q.psi];
        for (worst, v) in analogs.iter_mut().zip(now) {
            *worst = worst.max(v.abs());
        }
        still &= s.out.follower.y - m.y0 == lift && s.q.psi == psi;
    }
    Ok(DwellCheck { samples: phis.len(), lift, psi, analogs, still })
}

/// The peaks of the follower's analogs over a segment: the segment swept at 121 cam angles,
/// each peak refined between its best sample's neighbours by Brent's search.
pub fn segment_peaks(m: &DwellCamRocker, seg: &Segment) -> Result<SegmentPeaks> {
    let sweep = m.sampled(seg.start, seg.start + seg.span, 121, &m.guess(seg.start))?;
    let col = DwellCamRocker::COL.follower.y;
    let peak = |(at, value): (f64, f64)| Peak { at, value };
    let (at, v) = sweep.peak_of(col, |j| seg.sign * j.d1)?;
    let (at_min, v_min) = sweep.peak_of(col, |j| -j.d2)?;
    Ok(SegmentPeaks {
        velocity: peak((at, seg.sign * v)),
        acceleration_max: peak(sweep.peak_of(col, |j| j.d2)?),
        acceleration_min: peak((at_min, -v_min)),
    })
}

fn main() -> Result<()> {
    let m = DwellCamRocker::default();
    println!("Dwell cam rocker: {m:?}\n");
    let deg = f64::to_degrees;
    println!(
        "3-4-5 law: lift h = {} mm; dwell 0°-{:.0}°, rise over {:.0}° ({:.0}°-{:.0}°), dwell to {:.0}°, return over {:.0}° \
         ({:.0}°-{:.0}°), dwell to 360°\n",
        m.lift,
        deg(m.phi0),
        deg(m.rise),
        deg(m.phi0),
        deg(m.phi0 + m.rise),
        deg(m.phi1),
        deg(m.fall),
        deg(m.phi1),
        deg(m.phi1 + m.fall)
    );
    let states = turn(&m, 360)?;
    println!(
        "{:>5} {:>9} {:>10} {:>11} {:>9} {:>10} {:>11}",
        "phi", "s [mm]", "ds/dphi", "d2s/dphi2", "psi [°]", "dpsi/dphi", "d2psi/dphi2"
    );
    for s in states.iter().step_by(15) {
        println!(
            "{:>4.0}° {:>9.5} {:>10.5} {:>11.5} {:>9.4} {:>10.5} {:>11.5}",
            deg(s.input.phi),
            s.out.follower.y - m.y0,
            s.dout.follower.y,
            s.d2out.follower.y,
            deg(s.q.psi),
            s.dq.psi,
            s.d2q.psi
        );
    }
    report_dwells(&m)?;
    report_peaks(&m)?;
    let cam = cam(&states)?;
    report_cam(&m, &states, &cam)?;
    write_outputs(&m, &states, &cam)
}

/// What a cam designer checks of the cam: its size, the pressure angle on the rise and the
/// return, and the sharpest point of the profile against the roller.
fn report_cam(m: &DwellCamRocker, states: &[DwellCamRockerState], cam: &CamProfile) -> Result<()> {
    let deg = f64::to_degrees;
    println!(
        "\ncam, by inversion of the follower's motion (roller radius {ROLLER} mm, the follower's line through the \
         cam's centre): pitch curve from {} to {} mm from the centre, profile from {} mm",
        m.y0,
        m.y0 + m.lift,
        m.y0 - ROLLER
    );
    for seg in segments(m) {
        let (at, alpha) = peak_pressure(m, states, cam, seg.start, seg.start + seg.span)?;
        println!(
            "  {:<6} largest pressure angle {:.6}° at {:.5}° (located between the samples)",
            seg.name,
            deg(alpha),
            deg(at)
        );
    }
    if let Some((k, radius)) = cam.min_convex_radius() {
        println!(
            "  sharpest convex point of the pitch curve: radius of curvature {radius:.4} mm at {:.0}°; of the profile \
             {:.4} mm: {}",
            deg(states[k].input.phi),
            cam.profile_radius(k),
            if cam.undercut().is_empty() {
                "no undercut".to_string()
            } else {
                format!("UNDERCUT at {} samples", cam.undercut().len())
            }
        );
    }
    Ok(())
}

/// Each dwell: where follower and rocker stand, and that they stand exactly still.
fn report_dwells(m: &DwellCamRocker) -> Result<()> {
    println!("\ndwells (every 0.1° inside, and 1e-9 rad inside each end): where they stand, and the largest |analog|");
    println!("{:>23} {:>9} {:>9} {:>8} {:>9} {:>9} {:>9}", "", "s [mm]", "psi [°]", "ds/dphi", "d2s", "dpsi", "d2psi");
    for d in dwells(m) {
        let c = check_dwell(m, &d)?;
        let [v, a, w, e] = c.analogs;
        println!(
            "  {:<6} {:>6.1}°-{:>6.1}° {:>9.5} {:>9.4} {v:>8} {a:>9} {w:>9} {e:>9}  {}",
            d.name,
            d.from.to_degrees(),
            d.to.to_degrees(),
            c.lift,
            c.psi.to_degrees(),
            if c.still { format!("still ({} solves)", c.samples) } else { "MOVING".into() }
        );
        assert!(c.still && c.analogs == [0.0; 4], "the {} dwell is not exactly still: {c:?}", d.name);
    }
    // The same dwells found from the motion alone: the follower's rests over a turn from the
    // middle of the rise (where it moves), each end located between 73 samples to where the
    // law switches (within 1e-8 rad: the 3-4-5 law's velocity rounds to zero that close).
    let from = m.phi0 + 0.5 * m.rise;
    let sampled = Sampled::sweep(m, from, from + TAU, 73, m.guess(from))?;
    let rests = sampled.rests(DwellCamRocker::COL.follower.y)?;
    let found: Vec<String> =
        rests.iter().map(|r| format!("{:.6}°-{:.6}°", r.start.x.to_degrees(), r.end.x.to_degrees())).collect();
    println!("  located from the motion (Sampled::rests, 73 samples): {}", found.join(", "));
    let law = [(m.phi0 + m.rise, m.phi1), (m.phi1 + m.fall, TAU + m.phi0)];
    assert!(
        rests.len() == 2
            && rests.iter().zip(law).all(|(r, (a, b))| (r.start.x - a).abs() < 1e-7 && (r.end.x - b).abs() < 1e-7),
        "the rests found are not the law's dwells: {rests:?}"
    );
    Ok(())
}

/// The located peaks of the rise and of the return against the 3-4-5 law's closed form:
/// `ds/dphi = 1.875 h / beta` at `u = 1/2`, `d2s/dphi2 = ±(10 / sqrt 3) h / beta^2` at
/// `u = 1/2 ∓ sqrt(3) / 6` (the return's mirrored: its acceleration analog is the rise's negated).
fn report_peaks(m: &DwellCamRocker) -> Result<()> {
    let (accel, u_accel) = (10.0 / 3f64.sqrt(), 0.5 - 3f64.sqrt() / 6.0);
    for seg in segments(m) {
        let p = segment_peaks(m, &seg)?;
        let (h, beta) = (m.lift, seg.span);
        println!(
            "\n{}: h = {h} mm over beta = {:.0}°, peaks located along the sweep vs the 3-4-5 law's closed form",
            seg.name,
            beta.to_degrees()
        );
        // Where the largest and the smallest acceleration analog fall in the segment.
        let (u_max, u_min) = if seg.sign > 0.0 { (u_accel, 1.0 - u_accel) } else { (1.0 - u_accel, u_accel) };
        let velocity_law = if seg.sign > 0.0 { "1.875 h/beta" } else { "-1.875 h/beta" };
        let rows = [
            ("ds/dphi [mm/rad]", p.velocity, seg.sign * PEAK_VELOCITY * h / beta, 0.5, velocity_law),
            ("max d2s/dphi2 [mm/rad²]", p.acceleration_max, accel * h / (beta * beta), u_max, "5.7735 h/beta²"),
            ("min d2s/dphi2 [mm/rad²]", p.acceleration_min, -accel * h / (beta * beta), u_min, "-5.7735 h/beta²"),
        ];
        println!(
            "  {:<23} {:>16} {:>13}   {:<15} {:>16} {:>13} {:>10}   difference",
            "", "located", "at", "closed form", "", "at", "u"
        );
        for (name, got, closed, u, law) in rows {
            let closed_at = seg.start + u * beta;
            println!(
                "  {name:<23} {:>16.12} {:>12.8}°   {law:<15} {closed:>16.12} {:>12.8}° {u:>10.8}   {:>8.1e}, {:>8.1e}°",
                got.value,
                got.at.to_degrees(),
                closed_at.to_degrees(),
                got.value - closed,
                (got.at - closed_at).to_degrees()
            );
        }
    }
    // The rocker's peaks: no closed form (they depend on the rod and rocker too), but what the
    // rocker's bearings and the spring keeping the follower on the cam must take.
    let turn = m.sampled(0.0, TAU, 721, &m.guess(0.0))?;
    let (at_v, v) = turn.peak_of(DwellCamRocker::COL.psi, |j| j.d1.abs())?;
    let (at_a, a) = turn.peak_of(DwellCamRocker::COL.psi, |j| j.d2.abs())?;
    let swing = turn.range(DwellCamRocker::COL.psi)?;
    println!(
        "\nrocker: swings {:.6}° (from {:.6}° to {:.6}°); peak |dpsi/dphi| {v:.6} at {:.3}°, peak |d2psi/dphi2| {a:.6} at {:.3}°",
        swing.span().to_degrees(),
        swing.min.value.to_degrees(),
        swing.max.value.to_degrees(),
        at_v.to_degrees(),
        at_a.to_degrees()
    );
    Ok(())
}

/// The sweep as CSV and the follower's and the rocker's charts as SVG, the located peaks of the
/// follower's analogs marked.
fn write_outputs(m: &DwellCamRocker, states: &[DwellCamRockerState], disc: &CamProfile) -> Result<()> {
    let data = plot::out_dir("dwell_cam")?;
    let table = Table::from_states::<DwellCamRocker, _, _, _>(states.iter().map(|s| &s.flat)).with_length_unit(UNIT);
    table.save_csv(data.join("sweep.csv"))?;
    let columns = ["phi", "pitch.x", "pitch.y", "profile.x", "profile.y", "pitch_radius", "pressure_angle"];
    let mut profile = Table::new(columns.iter().map(|c| c.to_string()).collect());
    for (k, s) in states.iter().enumerate() {
        let ([px, py], [cx, cy]) = (disc.pitch[k], disc.profile[k]);
        profile.push(vec![s.input.phi, px, py, cx, cy, disc.pitch_radius[k], disc.pressure_angle[k]]);
    }
    let units = [("phi", "rad"), ("pitch", UNIT), ("profile", UNIT), ("pitch_radius", UNIT), ("pressure_angle", "rad")];
    profile.with_units(&units).save_csv(data.join("cam.csv"))?;
    let dir = plot::figure_dir("dwell_cam")?;
    let cam = Axis::angle("cam angle φ");
    let phi: Vec<f64> = states.iter().map(|s| s.input.phi).collect();
    let series = |label: &str, kind: Kind, f: &dyn Fn(&DwellCamRockerState) -> f64| {
        Series::columns(label, kind, &phi, &states.iter().map(f).collect::<Vec<_>>())
    };
    let mut peaks = [Vec::new(), Vec::new()];
    for seg in segments(m) {
        let p = segment_peaks(m, &seg)?;
        peaks[0].push((p.velocity.at, p.velocity.value));
        peaks[1].extend([p.acceleration_max, p.acceleration_min].map(|p| (p.at, p.value)));
    }
    let [velocity_peaks, acceleration_peaks] = peaks;
    let (length, v, a) = (Kind::length(UNIT), Kind::LengthAnalog(UNIT.into()), Kind::LengthAnalog2(UNIT.into()));
    plot::panels(
        &dir.join("follower.svg"),
        "Dwell cam: follower lift and its analogs (3-4-5 law), peaks marked",
        &cam,
        &[
            Panel::new(Axis::new("lift s", length.clone()))
                .with(series("s (follower)", length, &|s| s.out.follower.y - m.y0)),
            Panel::new(Axis::new("ds/dφ", v.clone()))
                .with(series("ds/dφ", v, &|s| s.dout.follower.y))
                .with_marks(velocity_peaks),
            Panel::new(Axis::new("d²s/dφ²", a.clone()))
                .with(series("d²s/dφ²", a, &|s| s.d2out.follower.y))
                .with_marks(acceleration_peaks),
        ],
    )?;
    plot::panels(
        &dir.join("rocker.svg"),
        "Dwell cam: rocker angle and its analogs",
        &cam,
        &[
            Panel::new(Axis::angle("rocker angle ψ")).with(series("ψ (rocker)", Kind::Angle, &|s| s.q.psi)),
            Panel::new(Axis::new("dψ/dφ", Kind::AngleAnalog)).with(series("dψ/dφ", Kind::AngleAnalog, &|s| s.dq.psi)),
            Panel::new(Axis::new("d²ψ/dφ²", Kind::AngleAnalog2)).with(series(
                "d²ψ/dφ²",
                Kind::AngleAnalog2,
                &|s| s.d2q.psi,
            )),
        ],
    )?;
    let length = Kind::length(UNIT);
    let curve = |points: &[[f64; 2]]| points.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>();
    plot::xy_chart(
        &dir.join("cam.svg"),
        &format!("Dwell cam: its profile for a {ROLLER} mm roller, by inversion"),
        &Axis::new("x", length.clone()),
        &Axis::new("y", length.clone()),
        &[
            Series::new("pitch curve (roller centre)", length.clone(), curve(&disc.pitch)),
            Series::new("cam profile", length, curve(&disc.profile)),
        ],
        &[(0.0, 0.0)],
    )?;
    println!(
        "\nwrote {} and {} and 3 charts to {}",
        data.join("sweep.csv").display(),
        data.join("cam.csv").display(),
        dir.display()
    );
    Ok(())
}
