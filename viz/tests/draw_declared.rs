//! The default drawing (`m.drawing()`) as SVG: parsed back as XML, its joint circles sit on the
//! closed-form joints of the four-bar and its pivots on the frame points, nothing is NaN, and a
//! declaration the drawing cannot show unambiguously carries notes in the picture, while every
//! gallery mechanism is drawn from its declaration without one.

use kinloop::Mechanism;
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::roller_edger::RollerEdger;
use kinloop_fixtures::{ClassFour, DisplacerRodDrive, RhombicDrive, StirlingEngine, WorkingRodDrive};
use kinloop_viz::draw::{Animation, Canvas, Draw, DrawError, Motion};

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::{FourBar, four_bar_joints, window_px};

const WINDOW: [f64; 4] = [-2.0, -2.0, 6.0, 5.0];
const WIDTH: f64 = 400.0;
/// Pixel coordinates are written with one decimal: half a tenth of a pixel of rounding.
const PX: f64 = 0.05 + 1e-9;

/// `(x, y)` of every `translate(x,y)` on elements named `tag` (at the first key frame).
fn translated(svg: &str, tag: &str) -> Vec<[f64; 2]> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    doc.descendants()
        .filter(|n| n.has_tag_name(tag))
        // A joint's label is placed by a translated group too: not a pivot.
        .filter(|n| n.attribute("class") != Some("joint-label"))
        .filter_map(|n| n.attribute("transform"))
        .filter_map(|t| t.strip_prefix("translate(")?.strip_suffix(')').map(str::to_string))
        .map(|xy| {
            let v: Vec<f64> = xy.split([',', ' ']).map(|c| c.parse().expect("a number")).collect();
            [v[0], v[1]]
        })
        .collect()
}

/// No attribute or text of the SVG holds a NaN or an infinity.
fn finite(svg: &str) {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    for n in doc.descendants() {
        for a in n.attributes() {
            assert!(!a.value().contains("NaN") && !a.value().contains("inf"), "{}={}", a.name(), a.value());
        }
    }
}

fn near(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() <= PX && (a[1] - b[1]).abs() <= PX
}

#[test]
fn the_four_bar_is_drawn_on_its_closed_form_joints() {
    let m = FourBar::default();
    for phi in [0.4, 2.0, 4.5] {
        let mut one = Motion::empty::<FourBar, 2, 1, 6>();
        one.push(&m.solve(phi).unwrap().flat);
        let d = m.drawing().with_canvas(Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() });
        assert!(d.notes().is_empty(), "{:?}", d.notes());
        let svg = d.svg(&one, 0).unwrap();
        finite(&svg);
        let [b, c, p] = four_bar_joints(&m, phi);
        let px = |w| window_px(WINDOW, WIDTH, w);
        let joints: Vec<[f64; 2]> = [b, c, p, [0.0, 0.0], [m.d, 0.0]].into_iter().map(px).collect();
        let circles = translated(&svg, "circle");
        // Every joint circle is on a joint of the closed form, and every moving joint has one.
        for at in &circles {
            assert!(joints.iter().any(|j| near(*j, *at)), "circle at {at:?}, joints at {joints:?}");
        }
        for j in &joints[..3] {
            assert!(circles.iter().any(|at| near(*j, *at)), "no circle at {j:?}");
        }
        // The two frame pivots, and no other.
        let mut pivots = translated(&svg, "g");
        pivots.sort_by(|a, b| a[0].total_cmp(&b[0]));
        assert_eq!(pivots.len(), 2, "{pivots:?}");
        assert!(near(pivots[0], joints[3]) && near(pivots[1], joints[4]), "{pivots:?}");
    }
}

kinloop::mechanism! {
    /// A pointer whose tip is `(x, y)`, both unknown, with a scalar equation beside the loop:
    /// the drawing cannot tell what `(x, y)` is, and does not show the equation.
    pub struct Pointer {
        params l = 2.0;
        input phi;
        unknowns x = 1, y = 1, s = 0;
        loop tip: l @ phi == (x, y);
        eq sum: s == x + y;
    }
}

#[test]
fn an_ambiguous_declaration_is_drawn_with_notes_saying_so() {
    let m = Pointer::default();
    let d = m.drawing();
    let notes = d.notes().join("\n");
    assert!(notes.contains("`tip: (x, y)`") && notes.contains("construction"), "{notes}");
    assert!(notes.contains("`sum`"), "{notes}");
    let motion = Motion::record(&m, m.sweep(0.0, 1.0, 5, &m.guess(0.0)).unwrap()).unwrap();
    let svg = d.animate(&motion, &Animation::default()).unwrap();
    finite(&svg);
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts: Vec<&str> = doc.descendants().filter(|n| n.has_tag_name("text")).filter_map(|n| n.text()).collect();
    assert_eq!(texts.iter().filter(|t| t.starts_with("note: ")).count(), 2, "{texts:?}");
}

/// The notes survive `into_drawing()`: the `Drawing` carries the declaration's notes and any
/// added with `.note(..)`, and its SVGs (pose, exposures, animation) and its interactive page
/// write each once, below the picture (within the picture's height), escaped.
#[test]
fn notes_survive_into_the_drawing_its_svg_and_its_page() {
    let m = Pointer::default();
    let declared = m.drawing().notes().to_vec();
    assert_eq!(declared.len(), 2, "{declared:?}");
    let d = m.drawing().extend(|d| d.note("pin <A> & rod")).into_drawing().note("second note");
    let mut expected: Vec<String> = declared.iter().map(|n| format!("note: {n}")).collect();
    expected.push("note: pin <A> & rod".into());
    expected.push("note: second note".into());
    assert_eq!(d.notes().len(), 4);
    let motion = Motion::record(&m, m.sweep(0.0, 1.0, 5, &m.guess(0.0)).unwrap()).unwrap();
    for svg in [
        d.svg(&motion, 2).unwrap(),
        d.exposures(&motion, 3).unwrap(),
        d.animate(&motion, &Animation::default()).unwrap(),
    ] {
        finite(&svg);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let height: f64 = doc.root_element().attribute("height").unwrap().parse().unwrap();
        let notes: Vec<(String, f64)> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text") && n.attribute("class") == Some("note"))
            .map(|n| (n.text().unwrap().to_string(), n.attribute("y").unwrap().parse().unwrap()))
            .collect();
        assert_eq!(notes.iter().map(|(t, _)| t.clone()).collect::<Vec<_>>(), expected);
        // One line each, in order, inside the picture.
        assert!(notes.windows(2).all(|w| w[1].1 > w[0].1), "{notes:?}");
        assert!(notes.iter().all(|(_, y)| *y <= height), "{notes:?} within {height}");
    }
    let page = kinloop_viz::draw::html(&m, &d, &motion, &kinloop_viz::draw::HtmlConfig::new("notes")).unwrap();
    let written: Vec<&str> =
        page.split("<p class=\"kl-drawing-note\">").skip(1).map(|s| s.split("</p>").next().unwrap()).collect();
    let escaped: Vec<String> =
        expected.iter().map(|n| n.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")).collect();
    assert_eq!(written, escaped);
    // Without notes, none is written.
    let plain = FourBar::default();
    let motion = Motion::record(&plain, plain.sweep(0.0, 1.0, 5, &plain.guess(0.0)).unwrap()).unwrap();
    let svg = plain.drawing().into_drawing().svg(&motion, 0).unwrap();
    assert!(!svg.contains("class=\"note\""));
}

#[test]
fn joints_are_renamed_and_hidden_by_name_and_a_wrong_name_is_an_error() {
    let m = FourBar::default();
    let d = m.drawing();
    assert_eq!(d.joint_names(), ["origin", "b", "c", "obcd.r1", "p"]);
    let d = d.rename("obcd.r1", "D").unwrap().hide("p").unwrap().hide("obcd: (d, 0)").unwrap();
    assert!(d.joint("D").is_ok());
    assert!(matches!(d.joint("obcd.r1"), Err(DrawError::UnknownPoint { .. })));
    assert!(matches!(d.clone().hide("nothing"), Err(DrawError::UnknownPoint { .. })));
    assert!(d.angle("obcd: (d, 0)").is_err(), "a fixed vector has no turning angle");
    // P hidden: not traced (B and C still are) and not a corner of the coupler.
    let drawing = d.into_drawing().with_canvas(Canvas { width: WIDTH, window: Some(WINDOW), ..Canvas::default() });
    assert_eq!(drawing.traces.len(), 2);
    let mut one = Motion::empty::<FourBar, 2, 1, 6>();
    one.push(&m.solve(1.0).unwrap().flat);
    let svg = drawing.svg(&one, 0).unwrap();
    finite(&svg);
    let p = window_px(WINDOW, WIDTH, four_bar_joints(&m, 1.0)[2]);
    let circles = translated(&svg, "circle");
    assert!(!circles.is_empty() && circles.iter().all(|c| !near(*c, p)), "{circles:?}");
    // The crank hidden by its term: its bar goes, and the pivot O that only it stood on; the
    // coupler, the rocker and the pivot D stay.
    let without_crank = m.drawing().hide("obcd: r @ phi").unwrap().into_drawing();
    assert_eq!(without_crank.items.len(), m.drawing().into_drawing().items.len() - 2);
}

kinloop::mechanism! {
    /// A crank pin declared thrice: `b` and `pin` as the loop's `r @ phi` (one joint), `t` a
    /// turn further round, which is the same point but not the same sum of vectors.
    pub struct TwicePinned {
        params r = 1.0, l = 3.0, e = 0.2;
        input phi;
        unknowns psi = 3, x = 4;
        loop oabo: r @ phi == (x, e) + l @ psi;
        point b = r @ phi;
        point pin = r @ phi;
        point t = r @ (phi + 2 * pi);
    }
}

#[test]
fn joints_that_coincide_only_numerically_are_two_joints_and_points_of_one_sum_one_joint_with_notes() {
    let d = TwicePinned::default().drawing();
    assert_eq!(d.joint_names(), ["origin", "b", "oabo.r1", "t"]);
    let notes = d.notes().join("\n");
    assert!(notes.contains("`b` and `t` coincide"), "{notes}");
    assert!(notes.contains("points `b` and `pin` are one joint"), "{notes}");
}

/// `m`'s default drawing animated over a sweep from 0 to `to`: no note, well-formed, finite.
fn draws_plainly<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(m: &M, to: f64) {
    let x0 = [0.0; NI];
    let sweep = kinloop::Sweep::<M, kinloop::Kin<N, NI, NO>, N, NI, NO>::new(m, x0, [to; NI], 61, m.guess_flat(&x0));
    let motion = Motion::record(m, sweep.unwrap()).unwrap();
    let d = m.drawing();
    assert!(d.notes().is_empty(), "{}: {:?}", M::NAME, d.notes());
    let svg = d.animate(&motion, &Animation::default()).unwrap();
    finite(&svg);
    assert!(!translated(&svg, "circle").is_empty(), "{}: no joint drawn", M::NAME);
}

#[test]
fn every_gallery_mechanism_is_drawn_from_its_declaration_without_a_note() {
    let tau = std::f64::consts::TAU;
    draws_plainly(&RhombicDrive::default(), tau);
    draws_plainly(&StirlingEngine::default(), tau);
    draws_plainly(&DisplacerRodDrive::default(), tau);
    draws_plainly(&WorkingRodDrive::default(), tau);
    draws_plainly(&GearLever::default(), tau);
    draws_plainly(&RollerEdger::default(), 6.0);
    draws_plainly(&ClassFour::default(), tau);
    draws_plainly(&FourBar::default(), tau);
}
