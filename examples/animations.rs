//! Animations of every mechanism of the gallery, with the curves their points trace: the
//! rhombic drive and its two variants, the gear-lever drive, the roller edger, the class IV
//! mechanism, four-bars (a coupler curve, and a rocker stopping at its limit position), the
//! five-bar, and the cam drives (the cam-linkage drive and the dwell cam).
//!
//! Run with `cargo run --release -p kinloop-examples --example animations -- docs/animations`
//! (the folder defaults to `out/animations`). Each mechanism gives `<name>.svg`, an animated
//! SVG that plays in a browser or a README; the roller edger, the class IV mechanism and the
//! four-bar coupler curve also give `<name>_exposures.svg`, a static multi-exposure for print.
//! Each mechanism also gives `<name>.html` in the folder `pages` beside that one (or the folder
//! given second), an interactive page (one file, no network): a slider and play/pause for the
//! input, live readouts with units, charts whose cursor follows the slider, and the sweep's
//! limit positions marked on the slider's track.
//!
//! `examples/tests/animations.rs` checks that the committed `docs/animations` and `docs/pages`
//! are what this example writes now: regenerate them after a change to a drawing.
//!
//! The five-bar's page has two inputs: it holds a grid of both cranks' angles, with one slider
//! per crank (`html_grid`).
//!
//! Each mechanism is drawn as its declaration describes it (`m.drawing()`: links, frame
//! pivots, sliders, rigid plates, the named points traced), with at most a trace removed or
//! added and, for the gear-lever drive, its gears, and for the cam drives, the disc, the roller
//! and the cam's profile, which no loop describes.

use kinloop::Mechanism;
use kinloop::draw::{
    Animation, DefaultDrawing, Draw, GridMotion, HtmlConfig, Motion, Readout, Scalar, html, html_grid,
};
use kinloop::plot::Kind;
use std::error::Error;
use std::f64::consts::{PI, TAU};
use std::path::{Path, PathBuf};

// The gallery's mechanisms, declared once in the fixtures crate.
use kinloop_fixtures::cam_linkage::{CamLinkage, DwellCamRocker};
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::roller_edger::RollerEdger;
use kinloop_fixtures::{ClassFour, DisplacerRodDrive, FiveBar, RhombicDrive, WorkingRodDrive};

kinloop::mechanism! {
    /// Four-bar: crank `r` at O = (0, 0), coupler BC of length `l` carrying the point P at
    /// `e` from B at angle `delta` to BC, rocker `k` pivoted at D = (d, 0).
    pub struct CouplerFourBar {
        params r = 1.0, l = 3.5, k = 3.0, d = 4.0, e = 2.5, delta = 0.7;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop obcd: r @ phi + l @ beta == (d, 0) + k @ gamma;
        point b = r @ phi;
        point c = (d, 0) + k @ gamma;
        point p = r @ phi + e @ (beta + delta);
    }
}

fn rhombic_drive() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = RhombicDrive::default();
    // The paths of the rods' centres of mass; the crank's is a circle.
    let drawing = m.drawing().untrace("s1")?;
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

fn displacer_rod_drive() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = DisplacerRodDrive::default();
    Ok((m.drawing(), Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

fn working_rod_drive() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = WorkingRodDrive::default();
    Ok((m.drawing(), Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// The gear-lever drive: the declaration has the carrier, the planet's arm to the pin and the
/// rocker the pin slides in; the gears are added to it. A planet of pitch radius
/// `l_c / (u - 1)` rolls inside a fixed ring of radius `u l_c / (u - 1)`, turning with its arm.
fn gear_lever() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = GearLever::default();
    let d = m.drawing();
    let centre = d.joint("oab.l1")?;
    let arm = d.angle("oab: (l_p * sin((1 - u) * alpha), l_p * cos((1 - u) * alpha))")?;
    let (ring, planet) = (m.u * m.l_c / (m.u - 1.0), m.l_c / (m.u - 1.0));
    let drawing = d.extend(|d| d.gear([0.0, 0.0], ring, 0.0).gear(centre, planet, arm));
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// The roller edger: cylinder O1-A extending at constant speed turns the lever O3-A; the
/// locked cylinder O2-B and the link B-A follow. B, a joint the declaration does not name, is
/// traced.
fn roller_edger() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = RollerEdger::default();
    let d = m.drawing();
    let b = d.joint("o2bao3.l1")?;
    Ok((d.extend(|d| d.trace(b)), Motion::record(&m, m.sweep(0.0, 6.0, 121, &m.guess(0.0))?)?))
}

fn class_four() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = ClassFour::default();
    let drawing = m.drawing().untrace("d")?.untrace("f")?;
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// The cam-linkage drive: the declaration closes the cam's contact as the equivalent four-bar
/// (the eccentric `e` as a crank, the line of centres `r_cam + r_roller`, the rocker's arm). The
/// disc and the roller, which no loop describes, are added as circles about their centres.
fn cam_linkage() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = CamLinkage::default();
    let drawing =
        m.drawing().extend(|d| d.length_unit("mm").circle("cam_centre", m.r_cam).circle("roller", m.r_roller));
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// The dwell cam: the declaration's follower pin on its guide, rod and rocker, the pin rising
/// and returning by the 3-4-5 law and resting in the dwells. Only the law enters the
/// kinematics; the cam that produces it is found by kinematic inversion
/// (`kinloop::analysis::cam`, as the `dwell_cam` example does) for a roller of 10 mm about the
/// pin, and drawn turning with the shaft. The cam angle meets no sine in the declaration; it is
/// an angle because the law compares it with angles written in degrees, so its readout is in
/// degrees.
fn dwell_cam() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = DwellCamRocker::default();
    let cam = kinloop_examples::dwell_cam::cam(&kinloop_examples::dwell_cam::turn(&m, 720)?)?;
    let roller = kinloop_examples::dwell_cam::ROLLER;
    let drawing = m.drawing().extend(|d| {
        d.length_unit("mm")
            .pivot([0.0, 0.0])
            .outline([0.0, 0.0], cam.profile.clone(), Scalar::expr(|s| s.x[0]))
            .circle("follower", roller)
            .note(format!("cam profile for a {roller} mm roller, by inversion of the follower's motion"))
    });
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// The five-bar with two cranks: both turned together (a one-to-one gearing), the coupler
/// point C tracing its path. (Its page is a grid of the two cranks: one slider each.)
fn five_bar() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = FiveBar::default();
    let (from, to) = ([0.0, 0.0], [TAU, TAU]);
    Ok((m.drawing(), Motion::record(&m, m.sweep(from, to, 361, &m.guess(from))?)?))
}

/// The four-bar with the coupler curve of P traced (the pins B and C move on circles).
fn four_bar(m: &CouplerFourBar) -> Result<DefaultDrawing, Box<dyn Error>> {
    Ok(m.drawing().untrace("b")?.untrace("c")?)
}

fn coupler_curve() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = CouplerFourBar::default();
    Ok((four_bar(&m)?, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// A non-Grashof four-bar: the input link cannot turn fully; the sweep stops at the located
/// limit position (coupler and rocker collinear), drawn and marked.
fn limit_position() -> Result<(DefaultDrawing, Motion), Box<dyn Error>> {
    let m = CouplerFourBar { r: 3.0, l: 2.0, k: 2.5, d: 4.0, e: 1.2, delta: 0.9 };
    let g = m.position(0.0, &m.guess(0.0))?.0;
    Ok((four_bar(&m)?, Motion::record(&m, m.sweep(0.0, PI, 181, &g)?)?))
}

/// Writes the file `name` (an animation or a page) into `dir`.
fn write(dir: &Path, name: &str, text: &str) -> Result<(), Box<dyn Error>> {
    let path = dir.join(name);
    std::fs::write(&path, text)?;
    println!("{:>7} bytes  {}", text.len(), path.display());
    Ok(())
}

type Scene = fn() -> Result<(DefaultDrawing, Motion), Box<dyn Error>>;

/// What to write of a mechanism.
struct Show {
    name: &'static str,
    scene: Scene,
    /// The motion is a full turn that ends where it began (else it plays forward and back).
    turn: bool,
    /// Also a static multi-exposure.
    exposures: bool,
}

/// The animated SVGs of the gallery, as `(file name, contents)`: one `<name>.svg` per mechanism,
/// and `<name>_exposures.svg` for those shown as a multi-exposure too.
pub fn animations() -> Result<Vec<(String, String)>, Box<dyn Error>> {
    let show = |name, scene: Scene, turn, exposures| Show { name, scene, turn, exposures };
    let shows = [
        show("rhombic_drive", rhombic_drive, true, false),
        show("displacer_rod_drive", displacer_rod_drive, true, false),
        show("working_rod_drive", working_rod_drive, true, false),
        show("gear_lever", gear_lever, true, false),
        show("roller_edger", roller_edger, false, true),
        show("class_four", class_four, true, true),
        show("four_bar_coupler", coupler_curve, true, true),
        show("four_bar_limit", limit_position, false, false),
        show("five_bar", five_bar, true, false),
        show("cam_linkage", cam_linkage, true, false),
        show("dwell_cam", dwell_cam, true, false),
    ];
    let mut files = Vec::new();
    for s in shows {
        let (drawing, motion) = (s.scene)()?;
        let anim = Animation { frames: 90, seconds: 6.0, back_and_forth: !s.turn };
        files.push((format!("{}.svg", s.name), drawing.animate(&motion, &anim)?));
        if s.exposures {
            files.push((format!("{}_exposures.svg", s.name), drawing.exposures(&motion, 8)?));
        }
    }
    Ok(files)
}

fn main() -> Result<(), Box<dyn Error>> {
    let dir = std::env::args_os().nth(1).map_or_else(|| PathBuf::from("out/animations"), PathBuf::from);
    // The pages go beside the animations' folder (`docs/animations` -> `docs/pages`), or
    // into the folder given second.
    let pages_dir =
        std::env::args_os().nth(2).map_or_else(|| dir.parent().unwrap_or(Path::new(".")).join("pages"), PathBuf::from);
    for (folder, files) in [(dir, animations()?), (pages_dir, pages()?)] {
        std::fs::create_dir_all(&folder)?;
        for (name, text) in files {
            write(&folder, &name, &text)?;
        }
    }
    Ok(())
}

/// The interactive pages: the same drawings and sweeps, with the readouts worth watching.
pub fn pages() -> Result<Vec<(String, String)>, Box<dyn Error>> {
    let mut files = Vec::new();
    let (d, motion) = rhombic_drive()?;
    let config = HtmlConfig::new("Rhombic drive (paper 000, Fig. 1)")
        .show(RhombicDrive::COL.x_c)
        .show(RhombicDrive::COL.x_f)
        .with_readout(Readout::column(RhombicDrive::COL.phi2).without_chart())
        .with_readout(Readout::column(RhombicDrive::COL.phi4).without_chart())
        .with_readout(Readout::column(RhombicDrive::COL.gap).without_chart());
    files.push((
        "rhombic_drive.html".into(),
        html(&RhombicDrive::default(), &d.clone().into_drawing(), &motion, &config)?,
    ));
    let (d, motion) = displacer_rod_drive()?;
    let config = HtmlConfig::new("Developed displacer rod (paper 000, Fig. 2)")
        .show(DisplacerRodDrive::COL.x_c)
        .show(DisplacerRodDrive::COL.x_f);
    files.push((
        "displacer_rod_drive.html".into(),
        html(&DisplacerRodDrive::default(), &d.clone().into_drawing(), &motion, &config)?,
    ));
    let (d, motion) = working_rod_drive()?;
    let config = HtmlConfig::new("Developed working rod (paper 000, Fig. 3)")
        .show(WorkingRodDrive::COL.x_c)
        .show(WorkingRodDrive::COL.x_f);
    files.push((
        "working_rod_drive.html".into(),
        html(&WorkingRodDrive::default(), &d.clone().into_drawing(), &motion, &config)?,
    ));
    let (d, motion) = gear_lever()?;
    let config = HtmlConfig::new("Gear-lever drive (paper 001)")
        .show(GearLever::COL.phi)
        .with_readout(Readout::column(GearLever::COL.s).without_chart());
    files.push(("gear_lever.html".into(), html(&GearLever::default(), &d.clone().into_drawing(), &motion, &config)?));
    let (d, motion) = roller_edger()?;
    let time = Kind::Other { quantity: "time".into(), unit: "s".into() };
    let config = HtmlConfig::new("Roller edger (paper 002)")
        .with_readout(Readout::column(RollerEdger::COL.t).kind(time))
        .show(RollerEdger::COL.phi3)
        .with_readout(Readout::column(RollerEdger::COL.phi1).without_chart())
        .with_readout(Readout::column(RollerEdger::COL.phi2).without_chart())
        .with_back_and_forth(true);
    files.push((
        "roller_edger.html".into(),
        html(&RollerEdger::default(), &d.clone().into_drawing(), &motion, &config)?,
    ));
    let (d, motion) = class_four()?;
    let config = HtmlConfig::new("Class IV mechanism (paper 003)").show(ClassFour::COL.th1).show(ClassFour::COL.th2);
    files.push(("class_four.html".into(), html(&ClassFour::default(), &d.clone().into_drawing(), &motion, &config)?));
    let (d, motion) = coupler_curve()?;
    let config = HtmlConfig::new("Crank-rocker four-bar: coupler curve of P")
        .show(CouplerFourBar::COL.gamma)
        .show(CouplerFourBar::COL.p.y)
        .with_readout(Readout::column(CouplerFourBar::COL.beta).without_chart())
        .with_readout(Readout::column(CouplerFourBar::COL.p.x).without_chart());
    files.push((
        "four_bar_coupler.html".into(),
        html(&CouplerFourBar::default(), &d.clone().into_drawing(), &motion, &config)?,
    ));
    let (d, motion) = limit_position()?;
    let m = CouplerFourBar { r: 3.0, l: 2.0, k: 2.5, d: 4.0, e: 1.2, delta: 0.9 };
    let config = HtmlConfig::new("Non-Grashof four-bar: the sweep stops at the limit position")
        .show(CouplerFourBar::COL.gamma)
        .with_readout(Readout::column(CouplerFourBar::COL.beta).without_chart())
        .with_back_and_forth(true);
    files.push(("four_bar_limit.html".into(), html(&m, &d.clone().into_drawing(), &motion, &config)?));
    let (d, motion) = cam_linkage()?;
    let config = HtmlConfig::new("Cam-linkage drive: disc cam, roller on a bell-crank rocker, rod and slider")
        .show(CamLinkage::COL.psi)
        .show(CamLinkage::COL.x)
        .show(CamLinkage::COL.pressure)
        .with_readout(Readout::column(CamLinkage::COL.beta).without_chart())
        .with_length_unit("mm");
    files.push(("cam_linkage.html".into(), html(&CamLinkage::default(), &d.clone().into_drawing(), &motion, &config)?));
    let (d, motion) = dwell_cam()?;
    let config = HtmlConfig::new("Dwell cam: 3-4-5 rise-dwell-return-dwell, follower swinging a rocker")
        .with_readout(Readout::column(DwellCamRocker::COL.phi).without_chart())
        .show(DwellCamRocker::COL.follower.y)
        .show(DwellCamRocker::COL.psi)
        .with_readout(Readout::column(DwellCamRocker::COL.gamma).without_chart())
        .with_length_unit("mm");
    files.push((
        "dwell_cam.html".into(),
        html(&DwellCamRocker::default(), &d.clone().into_drawing(), &motion, &config)?,
    ));
    // Two inputs: a grid of both cranks over a turn each (25 x 25 cells), one slider per crank;
    // where the links cannot reach each other the page says so.
    let m = FiveBar::default();
    let from = [0.0, 0.0];
    let grid = GridMotion::record(&m, from, [TAU, TAU], [25, 25], m.guess_flat(&from))?;
    let config = HtmlConfig::new("Five-bar: a slider for each crank")
        .show(FiveBar::COL.pc.x)
        .show(FiveBar::COL.pc.y)
        .show(FiveBar::COL.spread)
        .with_autoplay(false);
    files.push(("five_bar.html".into(), html_grid(&m, &m.drawing().into_drawing(), &grid, &config)?));
    Ok(files)
}
