//! The default drawing (`m.drawing()`) as SVG: parsed back as XML, its joint circles sit on the
//! closed-form joints of the four-bar and its pivots on the frame points, nothing is NaN, and a
//! declaration the drawing cannot show unambiguously carries notes in the picture, while every
//! gallery mechanism is drawn from its declaration without one.

use kinloop::Mechanism;
use kinloop_fixtures::cam_linkage::CamLinkage;
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::roller_edger::RollerEdger;
use kinloop_fixtures::{
    ClassFour, DisplacerRodDrive, EngineMachine, RhombicDrive, SlottedLever, StirlingEngine, WorkingRodDrive,
};
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
/// write each once, below the picture (within the picture's height, wrapped to its width),
/// escaped.
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
        let lines: Vec<(String, f64)> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text") && n.attribute("class") == Some("note"))
            .map(|n| (n.text().unwrap().to_string(), n.attribute("y").unwrap().parse().unwrap()))
            .collect();
        // Lines in order, inside the picture; a note wrapped to the picture's width goes on in
        // the lines after its first (`note: ...`), broken at spaces.
        assert!(lines.windows(2).all(|w| w[1].1 > w[0].1), "{lines:?}");
        assert!(lines.iter().all(|(_, y)| *y <= height), "{lines:?} within {height}");
        let mut notes: Vec<String> = Vec::new();
        for (line, _) in &lines {
            match notes.last_mut() {
                Some(note) if !line.starts_with("note: ") => *note = format!("{note} {line}"),
                _ => notes.push(line.clone()),
            }
        }
        assert_eq!(notes, expected);
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

/// A note is wrapped to the picture's width, not the picture widened to hold its text: a
/// drawing with a note of ten words and one of ten thousand characters (words, or a single
/// word with no space to break at) is as wide as with a note of one word, every line of a note
/// within the margins by the drawing's estimate of a text's width (0.6 of the font size a
/// character, the estimate that widens the picture for the readout); its words written in order,
/// a word too long for a line broken within it, and a note past eight lines cut, ending `…`.
/// The picture was as wide as its longest note's text (72 000 pixels for 10 000 characters).
#[test]
fn a_long_note_is_wrapped_to_the_pictures_width() {
    let m = FourBar::default();
    let motion = Motion::record(&m, m.sweep(0.0, 1.0, 5, &m.guess(0.0)).unwrap()).unwrap();
    let words = |n: usize| (0..n).map(|k| format!("w{k}")).collect::<Vec<_>>().join(" ");
    let drawn = |note: &str| {
        let d = m.drawing().into_drawing().note(note);
        [
            d.svg(&motion, 2).unwrap(),
            d.exposures(&motion, 3).unwrap(),
            d.animate(&motion, &Animation::default()).unwrap(),
        ]
    };
    let size = |doc: &roxmltree::Document| {
        let at = |a: &str| -> f64 { doc.root_element().attribute(a).unwrap().parse().unwrap() };
        (at("width"), at("height"))
    };
    let short: Vec<(f64, f64)> =
        drawn("short").iter().map(|svg| size(&roxmltree::Document::parse(svg).unwrap())).collect();
    // Each note, and whether it is cut.
    let long_word = "x".repeat(10_000);
    for (note, cut) in [(words(10), false), (words(60), false), (words(2500), true), (long_word.clone(), true)] {
        for (svg, (width, height)) in drawn(&note).iter().zip(&short) {
            let doc = roxmltree::Document::parse(svg).unwrap();
            let (w, h) = size(&doc);
            assert_eq!(w, *width, "{} characters", note.len());
            let lines: Vec<(&str, f64, f64)> = doc
                .descendants()
                .filter(|n| n.has_tag_name("text") && n.attribute("class") == Some("note"))
                .map(|n| {
                    let at = |a: &str| -> f64 { n.attribute(a).unwrap().parse().unwrap() };
                    (n.text().unwrap(), at("x"), at("y"))
                })
                .collect();
            assert!(lines.len() <= 8, "{} lines", lines.len());
            // The picture grows by the lines, each inside it.
            assert!(h > *height || lines.len() == 1, "{h} vs {height}");
            // The first line starts at the margin; none reaches into the margin on the right.
            let margin = lines[0].1;
            for (text, x, y) in &lines {
                assert!(x + 0.6 * 12.0 * text.chars().count() as f64 <= w - margin, "{text} at {x} in {w}");
                assert!(*y <= h, "{y} in {h}");
            }
            assert!(lines.windows(2).all(|p| p[1].2 > p[0].2), "{lines:?}");
            let text: Vec<&str> = lines.iter().map(|l| l.0).collect();
            assert!(text[0].starts_with("note: "), "{text:?}");
            if cut {
                assert_eq!(lines.len(), 8, "{text:?}");
                assert!(text[7].ends_with('\u{2026}'), "{text:?}");
            } else {
                // Every word, in order, none broken.
                let written: Vec<&str> = text.iter().flat_map(|l| l.split(' ')).filter(|w| !w.is_empty()).collect();
                assert_eq!(written[1..].join(" "), note);
                assert!(lines.len() > 1 || note.len() < 40, "{text:?}");
            }
            if note == long_word {
                // A word with nowhere to break: broken within it, each line full.
                let xs = text.concat().replace("note: ", "").replace('\u{2026}', "");
                assert!(xs.chars().all(|c| c == 'x') && xs.len() > 8 * 30, "{text:?}");
            }
        }
    }
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

kinloop::mechanism! {
    /// The slider-crank of [`TwicePinned`] with its frame at `(ox, oy)`: `t` is the crank pin
    /// a turn further round (the same point, another sum), `u` the pin turned on by `g` rad (a
    /// point `r g` from it, another joint however close).
    pub struct PinnedAway {
        params ox = 1e6, oy = -2e6, r = 1.0, l = 3.0, e = 0.2, g = 1e-5;
        input phi;
        unknowns psi = 3, x = 4;
        loop oabo: (ox, oy) + r @ phi == (ox + x, oy + e) + l @ psi;
        point b = (ox, oy) + r @ phi;
        point t = (ox, oy) + r @ (phi + 2 * pi);
        point u = (ox, oy) + r @ (phi + g);
    }
}

/// The note that two joints coincide is the same wherever the frame puts the mechanism and in
/// whatever unit of length it is declared: `t` coincides with the pin `b` (exactly, a turn
/// further round), `u` is `r g` = 1e-5 of the crank from it, 2.5e-6 of the mechanism's size,
/// far beyond rounding. The note was measured against 1e-9 of the joints' distance from the
/// origin: two million crank lengths away, `u` "coincided" with `b` (1e-5 below 2e-3).
#[test]
fn joints_coincide_relative_to_the_mechanism_not_to_the_origin() {
    for (at, unit) in [(0.0, 1.0), (1.0, 1.0), (1.0, 1e-6), (1.0, 1e6), (1e2, 1e-3)] {
        let m =
            PinnedAway { ox: 1e6 * at * unit, oy: -2e6 * at * unit, r: unit, l: 3.0 * unit, e: 0.2 * unit, g: 1e-5 };
        let notes = m.drawing().notes().join("\n");
        let ox = m.ox;
        assert!(notes.contains("`b` and `t` coincide"), "frame at {ox}, unit {unit}: {notes}");
        assert!(!notes.contains("`u`"), "frame at {ox}, unit {unit}: {notes}");
    }
}

/// `m`'s default drawing animated over a sweep from 0 to `to`: no note, well-formed, finite; and
/// at three poses of the sweep, every point the declaration names is drawn where its state puts
/// it (a joint circle, or a frame pivot for a fixed point, at the pixel the documented window
/// rule gives for the point's coordinates in the solved state). Returns how many points it checked.
fn draws_plainly<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(m: &M, to: f64) -> usize {
    let x0 = [0.0; NI];
    let sweep = kinloop::Sweep::<M, kinloop::Kin<N, NI, NO>, N, NI, NO>::new(m, x0, [to; NI], 61, m.guess_flat(&x0));
    let states: Vec<kinloop::Kin<N, NI, NO>> = sweep.unwrap().map(|s| s.unwrap()).collect();
    let sweep = kinloop::Sweep::<M, kinloop::Kin<N, NI, NO>, N, NI, NO>::new(m, x0, [to; NI], 61, m.guess_flat(&x0));
    let motion = Motion::record(m, sweep.unwrap()).unwrap();
    let d = m.drawing();
    assert!(d.notes().is_empty(), "{}: {:?}", M::NAME, d.notes());
    let svg = d.animate(&motion, &Animation::default()).unwrap();
    finite(&svg);
    assert!(!translated(&svg, "circle").is_empty(), "{}: no joint drawn", M::NAME);

    // The declared points: each pair of outputs `p.x`, `p.y`.
    let points: Vec<(&str, usize, usize)> = (0..NO)
        .filter_map(|o| {
            let p = M::OUTPUTS[o].strip_suffix(".x")?;
            let y = (0..NO).find(|&k| M::OUTPUTS[k].strip_suffix(".y") == Some(p))?;
            Some((p, o, y))
        })
        .collect();
    if points.is_empty() {
        return 0;
    }
    // A window around every point of the whole motion, with a margin: the pixels follow from it.
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for k in &states {
        for &(_, x, y) in &points {
            lo = [lo[0].min(k.out[x]), lo[1].min(k.out[y])];
            hi = [hi[0].max(k.out[x]), hi[1].max(k.out[y])];
        }
    }
    let pad = 0.25 * (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-3);
    let window = [lo[0] - pad, lo[1] - pad, hi[0] + pad, hi[1] + pad];
    let d = d.with_canvas(Canvas { width: WIDTH, window: Some(window), ..Canvas::default() });
    for pose in [0, 20, 40] {
        let svg = d.svg(&motion, pose).unwrap();
        let mut drawn = translated(&svg, "circle");
        drawn.extend(translated(&svg, "g"));
        for &(name, x, y) in &points {
            let at = window_px(window, WIDTH, [states[pose].out[x], states[pose].out[y]]);
            assert!(
                drawn.iter().any(|c| near(*c, at)),
                "{}: point `{name}` at {at:?} not drawn at pose {pose}",
                M::NAME
            );
        }
    }
    points.len()
}

#[test]
fn every_gallery_mechanism_is_drawn_from_its_declaration_without_a_note() {
    let tau = std::f64::consts::TAU;
    let checked = [
        draws_plainly(&RhombicDrive::default(), tau),
        draws_plainly(&StirlingEngine::default(), tau),
        draws_plainly(&DisplacerRodDrive::default(), tau),
        draws_plainly(&WorkingRodDrive::default(), tau),
        draws_plainly(&GearLever::default(), tau),
        draws_plainly(&RollerEdger::default(), 6.0),
        draws_plainly(&ClassFour::default(), tau),
        draws_plainly(&FourBar::default(), tau),
    ];
    // Sixteen points over the gallery; the roller edger declares none.
    assert!(checked.iter().sum::<usize>() >= 16, "{checked:?}");
}

/// `x,y` or `x y` as a point.
fn xy(t: &str) -> [f64; 2] {
    let v: Vec<f64> = t.split([',', ' ']).filter(|c| !c.is_empty()).map(|c| c.parse().expect("a number")).collect();
    [v[0], v[1]]
}

/// Every mechanism polyline of the SVG (traces left out) at each key frame: its points, read
/// from its `<animate>` when it moves.
fn polylines(svg: &str) -> Vec<Vec<Vec<[f64; 2]>>> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    let pts = |t: &str| t.split(' ').map(xy).collect::<Vec<_>>();
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline") && !n.attribute("class").is_some_and(|c| c.contains("trace")))
        .map(|n| match n.children().find(|c| c.has_tag_name("animate")) {
            Some(a) => a.attribute("values").unwrap().split(';').map(pts).collect(),
            None => vec![pts(n.attribute("points").unwrap())],
        })
        .collect()
}

/// Where each slider block is at each key frame (the translation of the group around it).
fn blocks(svg: &str) -> Vec<Vec<[f64; 2]>> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    doc.descendants()
        .filter(|n| n.has_tag_name("rect"))
        .filter_map(|r| r.parent()?.parent())
        .filter(|g| g.attribute("transform").is_some_and(|t| t.starts_with("translate(")))
        .map(|g| match g.children().find(|c| c.has_tag_name("animateTransform")) {
            Some(a) => a.attribute("values").unwrap().split(';').map(xy).collect(),
            None => vec![xy(g.attribute("transform").unwrap().trim_start_matches("translate(").trim_end_matches(')'))],
        })
        .collect()
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// A slotted lever's rocker is drawn as a designer draws it: one rigid bar through its pivot,
/// of one length over the whole turn, reaching past the block sliding on it at every pose and
/// out to the rocker's tip (`l = 4` from the pivot, the block `s` from 1 to 3), not a bar from
/// the pivot to the block that grows and shrinks. Lengths are compared in units of the crank
/// (`r = 1`), read from the same picture: no scale is assumed.
#[test]
fn a_slotted_levers_rocker_is_one_rigid_bar_past_its_block_and_out_to_its_tip() {
    let m = SlottedLever::default();
    let x0 = [0.0];
    let sweep = kinloop::Sweep::<SlottedLever, kinloop::Kin<2, 1, 2>, 2, 1, 2>::new(
        &m,
        x0,
        [std::f64::consts::TAU],
        61,
        m.guess_flat(&x0),
    );
    let motion = Motion::record(&m, sweep.unwrap()).unwrap();
    let d = m.drawing();
    assert!(d.notes().is_empty(), "{:?}", d.notes());
    let svg = d.animate(&motion, &Animation::default()).unwrap();
    finite(&svg);
    let bars: Vec<Vec<Vec<[f64; 2]>>> = polylines(&svg).into_iter().filter(|b| b[0].len() == 2).collect();
    // The bars from a frame pivot: their first point never moves. The crank's pivot (the
    // origin) is above the rocker's, at (0, -d).
    let fixed: Vec<&Vec<Vec<[f64; 2]>>> = bars.iter().filter(|b| b.iter().all(|f| f[0] == b[0][0])).collect();
    let top = fixed.iter().map(|b| b[0][0][1]).fold(f64::INFINITY, f64::min);
    let bottom = fixed.iter().map(|b| b[0][0][1]).fold(f64::NEG_INFINITY, f64::max);
    let crank: Vec<f64> = fixed.iter().find(|b| b[0][0][1] == top).unwrap().iter().map(|f| dist(f[0], f[1])).collect();
    let unit = crank[0];
    // Pixels are written to a tenth: a length within three halves of a tenth.
    let px = 0.15 + 1e-9;
    assert!(crank.iter().all(|c| (c - unit).abs() <= px), "the crank {crank:?}");
    let rocker: Vec<&Vec<Vec<[f64; 2]>>> = fixed.iter().copied().filter(|b| b[0][0][1] == bottom).collect();
    assert!(!rocker.is_empty(), "no bar from the rocker's pivot");
    for bar in &rocker {
        let len: Vec<f64> = bar.iter().map(|f| dist(f[0], f[1])).collect();
        assert!(len.iter().all(|l| (l - len[0]).abs() <= px), "a rocker bar changes its length: {len:?}");
    }
    let guide = rocker.iter().max_by(|a, b| dist(a[0][0], a[0][1]).total_cmp(&dist(b[0][0], b[0][1]))).unwrap();
    let length = dist(guide[0][0], guide[0][1]);
    assert!((length / unit - m.l / m.r).abs() <= 2.0 * px / unit, "the rocker is {} cranks long", length / unit);
    let block = blocks(&svg);
    assert_eq!(block.len(), 1);
    assert_eq!(block[0].len(), guide.len(), "key frames");
    for (at, bar) in block[0].iter().zip(guide.iter()) {
        let [o, e] = [bar[0], bar[1]];
        let u = [(e[0] - o[0]) / length, (e[1] - o[1]) / length];
        let along = (at[0] - o[0]) * u[0] + (at[1] - o[1]) * u[1];
        let off = ((at[0] - o[0]) * u[1] - (at[1] - o[1]) * u[0]).abs();
        assert!(off <= 2.0 * px, "the block {at:?} is off the rocker {bar:?}");
        assert!(along > 0.0 && along < 0.8 * length, "the block {at:?} is not well inside the rocker {bar:?}");
    }
}

/// The box `[x0, y0, x1, y1]` of every joint label of a static SVG (the text's width estimated
/// as the drawings estimate it, 0.6 em a character) with the point it labels.
fn label_boxes(svg: &str) -> Vec<(String, [f64; 4], [f64; 2])> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    doc.descendants()
        .filter(|n| n.attribute("class") == Some("joint-label"))
        .map(|g| {
            let at = xy(g.attribute("transform").unwrap().trim_start_matches("translate(").trim_end_matches(')'));
            let t = g.children().find(|c| c.has_tag_name("text")).unwrap();
            let text = t.text().unwrap().to_string();
            let num = |a: &str| t.attribute(a).unwrap().parse::<f64>().unwrap();
            let (font, w) = (num("font-size"), 0.6 * num("font-size") * text.chars().count() as f64);
            let left = at[0]
                + num("x")
                + match t.attribute("text-anchor") {
                    Some("end") => -w,
                    Some("middle") => -0.5 * w,
                    _ => 0.0,
                };
            let mid = at[1] + num("y") - 0.35 * font;
            (text, [left, mid - 0.5 * font, left + w, mid + 0.5 * font], at)
        })
        .collect()
}

fn box_distance(b: [f64; 4], q: [f64; 2]) -> f64 {
    (b[0] - q[0]).max(q[0] - b[2]).max(0.0).hypot((b[1] - q[1]).max(q[1] - b[3]).max(0.0))
}

/// Whether the segment from `a` to `b` comes within `w` pixels of the box `b`: sampled every
/// tenth of a pixel.
fn touches(a: [f64; 2], b: [f64; 2], bx: [f64; 4], w: f64) -> bool {
    let n = (dist(a, b) * 10.0).ceil().max(1.0) as usize;
    (0..=n).any(|k| {
        let t = k as f64 / n as f64;
        box_distance(bx, [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]) < w
    })
}

/// `m`'s default drawing at the start of a turn: each joint label off every link (the half
/// width of its stroke clear) and nearer its own joint than any other joint circle.
fn labels_by_their_joints<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(m: &M) {
    let x0 = [0.0; NI];
    let to = [std::f64::consts::TAU; NI];
    let sweep = kinloop::Sweep::<M, kinloop::Kin<N, NI, NO>, N, NI, NO>::new(m, x0, to, 37, m.guess_flat(&x0));
    let motion = Motion::record(m, sweep.unwrap()).unwrap();
    let svg = m.drawing().svg(&motion, 0).unwrap();
    let bars: Vec<[[f64; 2]; 2]> =
        polylines(&svg).iter().flat_map(|p| p[0].windows(2).map(|w| [w[0], w[1]]).collect::<Vec<_>>()).collect();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let polygons: Vec<Vec<[f64; 2]>> = doc
        .descendants()
        .filter(|n| n.has_tag_name("polygon"))
        .filter_map(|n| n.attribute("points"))
        .map(|t| t.split(' ').map(xy).collect())
        .collect();
    let edges = polygons.iter().flat_map(|p| (0..p.len()).map(|k| [p[k], p[(k + 1) % p.len()]]).collect::<Vec<_>>());
    let bars: Vec<[[f64; 2]; 2]> = bars.into_iter().chain(edges).collect();
    let dots = translated(&svg, "circle");
    let labels = label_boxes(&svg);
    assert!(!labels.is_empty(), "{}: no label", M::NAME);
    for (text, b, at) in labels {
        for [p, q] in &bars {
            assert!(!touches(*p, *q, b, 2.0), "{}: label {text} {b:?} on the link {p:?}-{q:?}", M::NAME);
        }
        let own = box_distance(b, at);
        for q in dots.iter().filter(|q| dist(**q, at) > 1.0) {
            assert!(box_distance(b, *q) > own, "{}: label {text} {b:?} nearer {q:?} than its joint {at:?}", M::NAME);
        }
    }
}

/// A joint's label sits beside its own joint, in a free direction: not on the crank of the
/// engine (where `s1`, its centre of mass, lies on it near the frame pivot, the label read as
/// the pivot's), nor against the frame pivot next to the cam's centre.
#[test]
fn joint_labels_sit_off_the_links_nearer_their_own_joints_than_any_other() {
    labels_by_their_joints(&EngineMachine::default());
    labels_by_their_joints(&CamLinkage::default());
    labels_by_their_joints(&SlottedLever::default());
    labels_by_their_joints(&RhombicDrive::default());
}
