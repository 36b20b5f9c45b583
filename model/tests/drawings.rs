//! A run-time model's drawings against the compiled mechanism's of the same declaration: the
//! same description text (one function of the macro's pipeline writes both), and, over the
//! same states, the same SVG animations, exposures, poses and interactive pages byte for byte
//! (one drawing code over the runtime's `Drawable`). The states are the same bit for bit when
//! the compiled sweep takes libm's sines, as a run-time model's does (`sweeps.rs`). A drawn
//! joint is checked independently against the four-bar's closed form.

mod common;

use common::{Libm, read, set};
use kinloop::{Kin, Mechanism, Sweep};
use kinloop_fixtures as fx;
use kinloop_model::Model;
use kinloop_viz::draw::{Animation, DefaultDrawing, GridMotion, Motion};
use kinloop_viz::html::{HtmlConfig, html, html_grid, html_grid_of, html_of};
use std::f64::consts::TAU;

/// The `#[kinloop(dense)]` twin of a fixture's text, named `dense` (as `parity.rs` has it).
fn dense_text(text: &str, name: &str, dense: &str) -> String {
    format!("#[kinloop(dense)] {}", text.replacen(&format!("struct {name} "), &format!("struct {dense} "), 1))
}

/// Every fixture of the parity tests: the model's description is the compiled `DRAWING`,
/// character for character.
#[test]
fn descriptions_equal_the_compiled_ones() {
    let cases: Vec<(String, &str)> = vec![
        (fx::FOUR_BAR_TEXT.to_string(), fx::FourBar::DRAWING),
        (fx::RHOMBIC_DRIVE_TEXT.to_string(), fx::RhombicDrive::DRAWING),
        (dense_text(fx::RHOMBIC_DRIVE_TEXT, "RhombicDrive", "RhombicDriveDense"), fx::RhombicDriveDense::DRAWING),
        (fx::SLIDER_CRANK_TEXT.to_string(), fx::SliderCrank::DRAWING),
        (fx::FIVE_BAR_TEXT.to_string(), fx::FiveBar::DRAWING),
        (fx::SLOTTED_LEVER_TEXT.to_string(), fx::SlottedLever::DRAWING),
        (fx::CLASS_FOUR_TEXT.to_string(), fx::ClassFour::DRAWING),
        (dense_text(fx::CLASS_FOUR_TEXT, "ClassFour", "ClassFourDense"), fx::ClassFourDense::DRAWING),
        (fx::DISPLACER_ROD_DRIVE_TEXT.to_string(), fx::DisplacerRodDrive::DRAWING),
        (fx::WORKING_ROD_DRIVE_TEXT.to_string(), fx::WorkingRodDrive::DRAWING),
        (fx::gear_lever::GEAR_LEVER_TEXT.to_string(), fx::gear_lever::GearLever::DRAWING),
        (fx::roller_edger::ROLLER_EDGER_TEXT.to_string(), fx::roller_edger::RollerEdger::DRAWING),
        (fx::balancing::BALANCE_TEXT.to_string(), fx::balancing::Balance::DRAWING),
        (fx::CLASS_FOUR_CORE_TEXT.to_string(), fx::ClassFourCore::DRAWING),
        (kinloop_bench::ring::RING.to_string(), kinloop_bench::ring::Ring::DRAWING),
    ];
    for (text, compiled) in cases {
        let m = read(&text);
        assert!(compiled.starts_with("kinloop-drawing 1\n"), "{}: {compiled}", m.name());
        assert_eq!(m.drawing_text(), compiled, "{}", m.name());
    }
}

/// The compiled mechanism's figures and the model's over a sweep of input 0 from `from` to
/// `to`: the motions, the animation, the exposures, one pose and the interactive page, equal.
/// Returns the motion.
fn same_figures<M, const N: usize, const NI: usize, const NO: usize>(
    compiled: M,
    model: &mut Model,
    from: [f64; NI],
    to: [f64; NI],
    samples: usize,
    show: &str,
) -> Motion
where
    M: Mechanism<N, NI, NO>,
{
    let compiled = Libm(compiled);
    let guess = compiled.guess_flat(&from);
    let sweep = Sweep::<_, Kin<N, NI, NO>, N, NI, NO>::new(&compiled, from, to, samples, guess).unwrap();
    let c_motion = Motion::record(&compiled, sweep).unwrap();
    let r_motion = model.motion(&from, &to, samples, &guess).unwrap();
    assert_eq!(c_motion, r_motion, "{}: motions", M::NAME);
    let (c_draw, r_draw) = (DefaultDrawing::new(&compiled), model.drawing());
    assert_eq!(c_draw.notes(), r_draw.notes());
    assert_eq!(c_draw.joint_names(), r_draw.joint_names());
    let anim = Animation::default();
    let c_svg = c_draw.animate(&c_motion, &anim).unwrap();
    assert_eq!(c_svg, r_draw.animate(&r_motion, &anim).unwrap(), "{}: animations", M::NAME);
    assert!(c_svg.contains("<animate ") && !c_svg.contains("NaN"));
    assert_eq!(c_draw.exposures(&c_motion, 5).unwrap(), r_draw.exposures(&r_motion, 5).unwrap());
    let last = c_motion.poses.len() - 1;
    assert_eq!(c_draw.svg(&c_motion, last).unwrap(), r_draw.svg(&r_motion, last).unwrap());
    let config = HtmlConfig::new(M::NAME).show(show);
    let c_page = html(&compiled, &c_draw.into_drawing(), &c_motion, &config).unwrap();
    let r_page = html_of(model, &r_draw.into_drawing(), &r_motion, &config).unwrap();
    assert_eq!(c_page, r_page, "{}: pages", M::NAME);
    assert!(c_page.contains(r#"id="kl-slider""#));
    r_motion
}

#[test]
fn figures_equal_the_compiled_ones_byte_for_byte() {
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", 1.0), ("b", 3.0), ("c", 2.5), ("d", 3.2)]);
    let motion = same_figures(fx::FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 }, &mut m, [0.0], [TAU], 181, "gamma");
    assert_eq!((motion.poses.len(), motion.events.len(), motion.stopped), (181, 0, false));
    // A rocker input: the sweep stops at a limit position, drawn as a ghost on both sides.
    set(&mut m, &[("a", 1.5), ("b", 3.0), ("c", 1.0), ("d", 3.2)]);
    let motion = same_figures(fx::FourBar { a: 1.5, b: 3.0, c: 1.0, d: 3.2 }, &mut m, [1.2], [1.2 + TAU], 181, "pc.x");
    assert_eq!((motion.events.len(), motion.stopped), (1, true));
    // Plates, sliders and a frame of several pivots.
    let mut m = read(fx::RHOMBIC_DRIVE_TEXT);
    let motion = same_figures(fx::RhombicDrive::default(), &mut m, [0.0], [TAU], 91, "x_c");
    assert_eq!(motion.poses.len(), 91);
    // A turning guide, its length over the motion, and a point on its body.
    let mut m = read(fx::SLOTTED_LEVER_TEXT);
    let motion = same_figures(fx::SlottedLever::default(), &mut m, [0.0], [TAU], 61, "theta");
    assert_eq!(motion.poses.len(), 61);
}

/// The five-bar over a grid of its two inputs: the same cells reached, the same poses, the same
/// page with one slider per input.
#[test]
fn grid_pages_equal_the_compiled_ones_byte_for_byte() {
    let compiled = Libm(fx::FiveBar::default());
    let mut m = read(fx::FIVE_BAR_TEXT);
    let (from, to, counts) = ([0.0, 0.4], [3.0, 3.0], [9, 7]);
    let guess = compiled.guess_flat(&from);
    let c_grid = GridMotion::record(&compiled, from, to, counts, guess).unwrap();
    let r_grid = m.grid(&from, &to, &counts, &guess).unwrap();
    assert_eq!(c_grid, r_grid);
    assert_eq!(r_grid.cells.len(), 63);
    let config = HtmlConfig::new("Five-bar");
    let c_page = html_grid(&compiled, &DefaultDrawing::new(&compiled).into_drawing(), &c_grid, &config).unwrap();
    let r_drawing = m.drawing().into_drawing();
    let r_page = html_grid_of(&m, &r_drawing, &r_grid, &config).unwrap();
    assert_eq!(c_page, r_page);
    assert!(c_page.contains(r#"id="kl-slider-1""#));
}

/// The four-bar's joints C (`pc`, from the outputs) and B (`abcd.l1`, from the description's
/// tape) where the model's SVG draws them, against the closed form: B = a (cos phi, sin phi),
/// C the intersection of the circles of radius b about B and c about D = (d, 0) on the branch
/// of the declared guess (above the frame). The SVG's scale and origin are read from the two
/// frame pivots, O and D, fixed by the parameters alone.
#[test]
fn a_drawn_joint_is_where_the_closed_form_puts_it() {
    let (a, b, c, d) = (1.0, 3.0, 2.5, 3.2);
    let mut m = read(fx::FOUR_BAR_TEXT);
    set(&mut m, &[("a", a), ("b", b), ("c", c), ("d", d)]);
    let phi = 0.9;
    let motion = m.motion(&[0.0], &[phi], 7, &[0.5, 1.5]).unwrap();
    let pose = motion.poses.last().unwrap();
    assert_eq!(pose.x, [phi]);
    let pin = [a * phi.cos(), a * phi.sin()];
    let (ux, uy) = (d - pin[0], -pin[1]);
    let e = ux.hypot(uy);
    let along = (b * b - c * c + e * e) / (2.0 * e);
    let h = (b * b - along * along).sqrt();
    let (ux, uy) = (ux / e, uy / e);
    let foot = [pin[0] + along * ux, pin[1] + along * uy];
    let cands = [[foot[0] - h * uy, foot[1] + h * ux], [foot[0] + h * uy, foot[1] - h * ux]];
    let joint_c = if cands[0][1] > cands[1][1] { cands[0] } else { cands[1] };
    // The motion holds the point's columns: a few roundings of lengths of order 3.
    let pc = [pose.out[0], pose.out[1]];
    assert!((pc[0] - joint_c[0]).hypot(pc[1] - joint_c[1]) < 1e-12, "{pc:?} vs {joint_c:?}");
    // The SVG writes pixels to a tenth: the circles of the joints within rounding.
    let svg = m.drawing().svg(&motion, motion.poses.len() - 1).unwrap();
    let circles: Vec<[f64; 2]> = svg
        .split("<circle ")
        .skip(1)
        .filter_map(|c| {
            let t = c.split("transform=\"translate(").nth(1)?.split(')').next()?;
            let mut v = t.split(' ').map(|s| s.parse::<f64>().unwrap());
            Some([v.next()?, v.next()?])
        })
        .collect();
    // The frame pivots O and D (on the ground: the lowest circles, leftmost and rightmost).
    let lowest = circles.iter().fold(f64::MIN, |m, p| m.max(p[1]));
    let ground: Vec<&[f64; 2]> = circles.iter().filter(|p| (p[1] - lowest).abs() < 1e-9).collect();
    let o = ground.iter().fold([f64::MAX, 0.0], |m, p| if p[0] < m[0] { **p } else { m });
    let dd = ground.iter().fold([f64::MIN, 0.0], |m, p| if p[0] > m[0] { **p } else { m });
    let scale = (dd[0] - o[0]) / d;
    let px = |p: [f64; 2]| [o[0] + scale * p[0], o[1] - scale * p[1]];
    // Half a tenth of a pixel per coordinate written, and the scale read from two rounded
    // coordinates (0.1 px over |OD|, carried to points up to 1.2 |OD| away).
    let tol = 0.05 + 0.1 * 1.2 + 1e-9;
    for (name, at) in [("B", pin), ("C", joint_c)] {
        let want = px(at);
        let near = circles.iter().map(|p| (p[0] - want[0]).abs().max((p[1] - want[1]).abs())).fold(f64::MAX, f64::min);
        assert!(near <= tol, "joint {name}: no circle within {tol} px of {want:?} in {circles:?}");
    }
}

kinloop_fixtures::declare! {
    /// A four-bar stretched at input 0 (`a + |d| = b + c`: coupler and rocker in line, the
    /// analogs singular, the positions solved) with a coupler plate of four joints: B, C and
    /// the points `p` and `r` turning with the coupler.
    STRETCHED_TEXT => {
        pub struct Stretched {
            params a = 1, b = 1.75, c = 1.25, d = -2, e = 1.5, f = 0.8;
            input phi;
            unknowns beta = 3.0, gamma = 0.2;
            loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
            point p = a @ phi + e @ (beta + 0.6);
            point r = a @ phi + f @ (beta - 0.9);
        }
    }
}

/// The reference state of a mechanism whose analogs are singular at inputs 0 is its positions
/// there (`Model::positions`, as the compiled `position_flat`): its plate is drawn around its
/// centre, as the compiled one draws it, not in the declared order with a note. The drawing
/// and its SVG of a motion away from the limit equal the compiled ones byte for byte.
#[test]
fn a_mechanism_singular_at_zero_is_drawn_as_the_compiled_one() {
    let compiled = Libm(Stretched::default());
    let mut m = read(STRETCHED_TEXT);
    let cfg = kinloop::NewtonConfig::default();
    let guess = compiled.guess_flat(&[0.0]);
    // Singular at 0 for the full step, solved by positions alone: beta = pi, gamma = 0.
    assert!(compiled.kinematics_flat(&[0.0], &guess, &cfg).is_err());
    assert!(m.kinematics(&[0.0], &guess, &cfg).is_err());
    let q = m.positions(&[0.0], &guess, &cfg).unwrap().to_vec();
    assert!((q[0] - std::f64::consts::PI).abs() < 1e-7 && q[1].abs() < 1e-7, "{q:?}");
    let (c_draw, r_draw) = (DefaultDrawing::new(&compiled), m.drawing());
    assert_eq!(c_draw.notes(), r_draw.notes());
    assert!(r_draw.notes().iter().all(|n| !n.contains("does not assemble")), "{:?}", r_draw.notes());
    let motion = m.motion(&[0.3], &[2.0], 9, &compiled.guess_flat(&[0.3])).unwrap();
    let sweep =
        Sweep::<_, Kin<2, 1, 4>, 2, 1, 4>::new(&compiled, [0.3], [2.0], 9, compiled.guess_flat(&[0.3])).unwrap();
    assert_eq!(motion, Motion::record(&compiled, sweep).unwrap());
    for pose in [0, 4, 8] {
        assert_eq!(c_draw.svg(&motion, pose).unwrap(), r_draw.svg(&motion, pose).unwrap());
    }
    let anim = Animation::default();
    assert_eq!(c_draw.animate(&motion, &anim).unwrap(), r_draw.animate(&motion, &anim).unwrap());
}
