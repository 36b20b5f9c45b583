//! Animations of every mechanism of the gallery, with the curves their points trace: the
//! rhombic drive and its two variants, the gear-lever drive, the roller edger, the class IV
//! mechanism, and four-bars (a coupler curve, and a rocker stopping at its limit position).
//!
//! Run with `cargo run --release -p kinloop-examples --example animations -- docs/animations`
//! (the folder defaults to `out/animations`). Each mechanism gives `<name>.svg`, an animated
//! SVG that plays in a browser or a README; the roller edger, the class IV mechanism and the
//! four-bar coupler curve also give `<name>_exposures.svg`, a static multi-exposure for print.
//! Each mechanism also gives `<name>.html` in the folder `pages` beside that one (or the folder
//! given second), an interactive page (one file, no network): a slider and play/pause for the
//! input, live readouts with units, charts whose cursor follows the slider, and the sweep's
//! limit positions marked on the slider's track.

use kinloop::draw::{Animation, Drawing, HtmlConfig, Motion, Pt, Readout, Scalar, html};
use kinloop::plot::Kind;
use std::error::Error;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::path::{Path, PathBuf};

// The gallery's mechanisms, declared once in the fixtures crate.
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::roller_edger::RollerEdger;
use kinloop_fixtures::{ClassFour, DisplacerRodDrive, RhombicDrive, WorkingRodDrive};

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

/// The point at `r` from `o` in direction `angle`.
fn polar(o: [f64; 2], r: f64, angle: f64) -> [f64; 2] {
    [o[0] + r * angle.cos(), o[1] + r * angle.sin()]
}

/// Index of unknown `name` among `names` (drawings read unknowns by name, not position).
fn col(names: &[&str], name: &str) -> usize {
    names.iter().position(|n| *n == name).unwrap_or_else(|| panic!("no unknown `{name}`"))
}

/// A slider on the line `y = y0` whose abscissa is unknown `i`.
fn on_line(i: usize, y0: f64) -> Pt {
    Pt::expr(move |s| [s.q[i], y0])
}

fn rhombic_drive() -> Result<(Drawing, Motion), Box<dyn Error>> {
    let m = RhombicDrive::default();
    let u = RhombicDrive::UNKNOWNS;
    let a = [0.0, m.e_p];
    let (r_p, r_b, gamma) = (m.r_p, m.r_b, m.gamma);
    let b = Pt::expr(move |s| polar(a, r_p, s.x[0]));
    let d = Pt::expr(move |s| polar(a, r_b, s.x[0] + gamma));
    let (c, f) = (on_line(col(&u, "x_c"), 0.0), on_line(col(&u, "x_f"), m.de));
    let drawing = Drawing::new()
        .pivot(a)
        .slider(c.clone(), 0.0)
        .slider(f.clone(), 0.0)
        .body([b.clone(), Pt::from(a), d.clone()])
        .link([b, c])
        .link([d, f])
        .trace("s2")
        .trace("s4");
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

fn displacer_rod_drive() -> Result<(Drawing, Motion), Box<dyn Error>> {
    let m = DisplacerRodDrive::default();
    let drawing = developed_rod_drive(m.e_p, m.r, m.de, &DisplacerRodDrive::UNKNOWNS, false);
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

fn working_rod_drive() -> Result<(Drawing, Motion), Box<dyn Error>> {
    let m = WorkingRodDrive::default();
    let drawing = developed_rod_drive(m.e_p, m.r, m.de, &WorkingRodDrive::UNKNOWNS, true);
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// The two variants with a developed rod: crank `r` about A = (0, e_p), pistons C (on y = 0)
/// and F (on y = de); the developed rod is a triangle through the crank pin B, the third joint
/// D and the piston it drives (C for the working rod, F for the displacer rod), the other
/// piston hangs from D by a plain link.
fn developed_rod_drive(e_p: f64, r: f64, de: f64, u: &[&str], on_working_piston: bool) -> Drawing {
    let a = [0.0, e_p];
    let b = Pt::expr(move |s| polar(a, r, s.x[0]));
    let (c, f) = (on_line(col(u, "x_c"), 0.0), on_line(col(u, "x_f"), de));
    let (body_piston, linked_piston) = if on_working_piston { (c.clone(), f.clone()) } else { (f.clone(), c.clone()) };
    Drawing::new()
        .pivot(a)
        .slider(c, 0.0)
        .slider(f, 0.0)
        .link([Pt::from(a), b.clone()])
        .body([b, body_piston, Pt::point("d")])
        .link([Pt::point("d"), linked_piston])
        .trace("d")
}

/// The gear-lever drive: a planet of pitch radius `l_c / (u - 1)` rolls inside a fixed ring
/// of radius `u l_c / (u - 1)` (so it turns by `(1 - u) alpha` as its carrier turns by
/// `alpha`); its pin slides in the rocker pivoted at O. Angles of the declaration are from
/// the Y axis: direction `a` is `(sin a, cos a)`, i.e. `pi/2 - a` from the X axis.
fn gear_lever() -> Result<(Drawing, Motion), Box<dyn Error>> {
    let m = GearLever::default();
    let phi = col(&GearLever::UNKNOWNS, "phi");
    let (l_c, l_p, u) = (m.l_c, m.l_p, m.u);
    let o = [0.0, 0.0];
    let centre = Pt::expr(move |s| polar(o, l_c, FRAC_PI_2 - s.x[0]));
    let pin_angle = move |alpha: f64| FRAC_PI_2 - (1.0 - u) * alpha;
    let pin = Pt::expr(move |s| polar(polar(o, l_c, FRAC_PI_2 - s.x[0]), l_p, pin_angle(s.x[0])));
    let rocker_end = Pt::expr(move |s| polar(o, 1.1 * (l_c + l_p), FRAC_PI_2 - s.q[phi]));
    let drawing = Drawing::new()
        .gear(o, u * l_c / (u - 1.0), 0.0)
        .gear(centre.clone(), l_c / (u - 1.0), Scalar::expr(move |s| pin_angle(s.x[0])))
        .pivot(o)
        .link([Pt::from(o), rocker_end])
        .link([Pt::from(o), centre.clone()])
        .link([centre, pin.clone()])
        .slider(pin.clone(), Scalar::expr(move |s| FRAC_PI_2 - s.q[phi]))
        .trace(pin);
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// The roller edger: cylinder O1-A extending at constant speed turns the lever O3-A; the
/// locked cylinder O2-B and the link B-A follow. O1 is the origin, O3 = `l5 @ alpha`, and
/// O2 = O3 - `l6 @ beta`.
fn roller_edger() -> Result<(Drawing, Motion), Box<dyn Error>> {
    let m = RollerEdger::default();
    let u = RollerEdger::UNKNOWNS;
    let (phi1, phi2) = (col(&u, "phi1"), col(&u, "phi2"));
    let o1 = [0.0, 0.0];
    let o3 = polar(o1, m.l5, m.alpha);
    let o2 = polar(o3, -m.l6, m.beta);
    let (l1, v1, l2) = (m.l1, m.v1, m.s2 + m.l2);
    let a = Pt::expr(move |s| polar(o1, v1 * s.x[0] + l1, s.q[phi1]));
    let b = Pt::expr(move |s| polar(o2, l2, s.q[phi2]));
    let barrel1 = Pt::expr(move |s| polar(o1, 0.5 * l1, s.q[phi1]));
    let barrel2 = Pt::expr(move |s| polar(o2, 0.5 * l2, s.q[phi2]));
    let drawing = Drawing::new()
        .pivot(o1)
        .pivot(o2)
        .pivot(o3)
        .link([Pt::from(o1), a.clone()])
        .slider(barrel1, Scalar::expr(move |s| s.q[phi1]))
        .link([Pt::from(o2), b.clone()])
        .slider(barrel2, Scalar::expr(move |s| s.q[phi2]))
        .link([b.clone(), a.clone()])
        .link([a, Pt::from(o3)])
        .trace(b);
    Ok((drawing, Motion::record(&m, m.sweep(0.0, 6.0, 121, &m.guess(0.0))?)?))
}

fn class_four() -> Result<(Drawing, Motion), Box<dyn Error>> {
    let m = ClassFour::default();
    let (o, b, oa) = ([0.0, 0.0], [m.xb, m.yb], m.oa);
    let a = Pt::expr(move |s| polar(o, oa, s.x[0]));
    let drawing = Drawing::new()
        .pivot(o)
        .pivot(b)
        .link([Pt::from(o), a.clone()])
        .body([Pt::point("c"), a, Pt::point("e")])
        .body([Pt::point("d"), Pt::from(b), Pt::point("f")])
        .link(["c", "d"])
        .link(["e", "f"])
        .trace("c")
        .trace("e");
    Ok((drawing, Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

fn four_bar(m: &CouplerFourBar) -> Drawing {
    let (o, d) = ([0.0, 0.0], [m.d, 0.0]);
    Drawing::new()
        .pivot(o)
        .pivot(d)
        .link([Pt::from(o), Pt::point("b")])
        .body(["b", "c", "p"])
        .link([Pt::point("c"), Pt::from(d)])
        .trace("p")
}

fn coupler_curve() -> Result<(Drawing, Motion), Box<dyn Error>> {
    let m = CouplerFourBar::default();
    Ok((four_bar(&m), Motion::record(&m, m.sweep(0.0, TAU, 361, &m.guess(0.0))?)?))
}

/// A non-Grashof four-bar: the input link cannot turn fully; the sweep stops at the located
/// limit position (coupler and rocker collinear), drawn and marked.
fn limit_position() -> Result<(Drawing, Motion), Box<dyn Error>> {
    let m = CouplerFourBar { r: 3.0, l: 2.0, k: 2.5, d: 4.0, e: 1.2, delta: 0.9 };
    let g = m.position(0.0, &m.guess(0.0))?.0;
    Ok((four_bar(&m), Motion::record(&m, m.sweep(0.0, PI, 181, &g)?)?))
}

fn write(dir: &Path, name: &str, svg: &str) -> Result<(), Box<dyn Error>> {
    let path = dir.join(format!("{name}.svg"));
    std::fs::write(&path, svg)?;
    println!("{:>7} bytes  {}", svg.len(), path.display());
    Ok(())
}

type Scene = fn() -> Result<(Drawing, Motion), Box<dyn Error>>;

/// What to write of a mechanism.
struct Show {
    name: &'static str,
    scene: Scene,
    /// The motion is a full turn that ends where it began (else it plays forward and back).
    turn: bool,
    /// Also a static multi-exposure.
    exposures: bool,
}

fn main() -> Result<(), Box<dyn Error>> {
    let dir = std::env::args_os().nth(1).map_or_else(|| PathBuf::from("out/animations"), PathBuf::from);
    std::fs::create_dir_all(&dir)?;
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
    ];
    for s in shows {
        let (drawing, motion) = (s.scene)()?;
        let anim = Animation { frames: 90, seconds: 6.0, back_and_forth: !s.turn };
        write(&dir, s.name, &drawing.animate(&motion, &anim)?)?;
        if s.exposures {
            write(&dir, &format!("{}_exposures", s.name), &drawing.exposures(&motion, 8)?)?;
        }
    }
    // The pages go beside the animations' folder (`docs/animations` -> `docs/pages`), or
    // into the folder given second.
    let pages_dir =
        std::env::args_os().nth(2).map_or_else(|| dir.parent().unwrap_or(Path::new(".")).join("pages"), PathBuf::from);
    std::fs::create_dir_all(&pages_dir)?;
    pages(&pages_dir)
}

/// Writes `<name>.html`.
fn write_page(dir: &Path, name: &str, page: &str) -> Result<(), Box<dyn Error>> {
    let path = dir.join(format!("{name}.html"));
    std::fs::write(&path, page)?;
    println!("{:>7} bytes  {}", page.len(), path.display());
    Ok(())
}

/// The interactive pages: the same drawings and sweeps, with the readouts worth watching.
fn pages(dir: &Path) -> Result<(), Box<dyn Error>> {
    let (d, motion) = rhombic_drive()?;
    let config = HtmlConfig::new("Rhombic drive (paper 000, Fig. 1)")
        .show(RhombicDrive::COL.x_c)
        .show(RhombicDrive::COL.x_f)
        .with_readout(Readout::column(RhombicDrive::COL.phi2).without_chart())
        .with_readout(Readout::column(RhombicDrive::COL.phi4).without_chart())
        .with_readout(Readout::column(RhombicDrive::COL.gap).without_chart());
    write_page(dir, "rhombic_drive", &html(&RhombicDrive::default(), &d, &motion, &config)?)?;
    let (d, motion) = displacer_rod_drive()?;
    let config = HtmlConfig::new("Developed displacer rod (paper 000, Fig. 2)")
        .show(DisplacerRodDrive::COL.x_c)
        .show(DisplacerRodDrive::COL.x_f);
    write_page(dir, "displacer_rod_drive", &html(&DisplacerRodDrive::default(), &d, &motion, &config)?)?;
    let (d, motion) = working_rod_drive()?;
    let config = HtmlConfig::new("Developed working rod (paper 000, Fig. 3)")
        .show(WorkingRodDrive::COL.x_c)
        .show(WorkingRodDrive::COL.x_f);
    write_page(dir, "working_rod_drive", &html(&WorkingRodDrive::default(), &d, &motion, &config)?)?;
    let (d, motion) = gear_lever()?;
    let config = HtmlConfig::new("Gear-lever drive (paper 001)")
        .show(GearLever::COL.phi)
        .with_readout(Readout::column(GearLever::COL.s).without_chart());
    write_page(dir, "gear_lever", &html(&GearLever::default(), &d, &motion, &config)?)?;
    let (d, motion) = roller_edger()?;
    let time = Kind::Other { quantity: "time".into(), unit: "s".into() };
    let config = HtmlConfig::new("Roller edger (paper 002)")
        .with_readout(Readout::column(RollerEdger::COL.t).kind(time))
        .show(RollerEdger::COL.phi3)
        .with_readout(Readout::column(RollerEdger::COL.phi1).without_chart())
        .with_readout(Readout::column(RollerEdger::COL.phi2).without_chart())
        .with_back_and_forth(true);
    write_page(dir, "roller_edger", &html(&RollerEdger::default(), &d, &motion, &config)?)?;
    let (d, motion) = class_four()?;
    let config = HtmlConfig::new("Class IV mechanism (paper 003)").show(ClassFour::COL.th1).show(ClassFour::COL.th2);
    write_page(dir, "class_four", &html(&ClassFour::default(), &d, &motion, &config)?)?;
    let (d, motion) = coupler_curve()?;
    let config = HtmlConfig::new("Crank-rocker four-bar: coupler curve of P")
        .show(CouplerFourBar::COL.gamma)
        .show(CouplerFourBar::COL.p.y)
        .with_readout(Readout::column(CouplerFourBar::COL.beta).without_chart())
        .with_readout(Readout::column(CouplerFourBar::COL.p.x).without_chart());
    write_page(dir, "four_bar_coupler", &html(&CouplerFourBar::default(), &d, &motion, &config)?)?;
    let (d, motion) = limit_position()?;
    let m = CouplerFourBar { r: 3.0, l: 2.0, k: 2.5, d: 4.0, e: 1.2, delta: 0.9 };
    let config = HtmlConfig::new("Non-Grashof four-bar: the sweep stops at the limit position")
        .show(CouplerFourBar::COL.gamma)
        .with_readout(Readout::column(CouplerFourBar::COL.beta).without_chart())
        .with_back_and_forth(true);
    write_page(dir, "four_bar_limit", &html(&m, &d, &motion, &config)?)
}
