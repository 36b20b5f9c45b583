//! Hostile inputs to the interactive pages: what the drawings refuse or bound, the pages
//! refuse or bound too (a page's size follows its frames, not the reach of a window).

use kinloop_viz::draw::{Canvas, DefaultDrawing, Drawing, HtmlConfig, HtmlError, Motion, Pt, html};
use std::f64::consts::TAU;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::FourBar;

fn motion() -> (FourBar, Motion) {
    let m = FourBar::default();
    let mo = Motion::record(&m, m.sweep(0.0, TAU, 13, &m.guess(0.0)).unwrap()).unwrap();
    (m, mo)
}

/// The `d` attribute of every hatch path (`M x,y l dx,dy` repeated) of a page's drawing.
fn hatch_strokes(page: &str) -> usize {
    page.split("<path d=\"").skip(1).map(|p| p.split('"').next().unwrap().matches('l').count()).sum()
}

#[test]
fn a_fixed_sliders_guide_on_a_page_is_cut_to_the_picture() {
    let (m, mo) = motion();
    // A slider travelling about 6e7 pixels along its guide through a window 480 pixels wide:
    // the guide's ground line and hatching are drawn over the picture only, as the drawings
    // do, not as some ten million hatch strokes.
    let window = Canvas { window: Some([-2.0, -2.0, 6.0, 5.0]), ..Canvas::default() };
    let far = Drawing::new().with_canvas(window).slider(Pt::expr(|s| [1e6 * s.x[0], 0.0]), 0.0).joint("b");
    let page = html(&m, &far, &mo, &HtmlConfig::new("far slider")).unwrap();
    let view = far.view(&mo).unwrap();
    // One stroke every 6 pixels along the picture's diagonal at most, and a few more.
    let most = (view.width.hypot(view.height) / 6.0).ceil() as usize + 8;
    assert!(hatch_strokes(&page) <= most, "{} hatch strokes, {} bytes", hatch_strokes(&page), page.len());
    assert!(page.len() < 200_000, "{} bytes", page.len());
}

/// A link through no point (`Drawing::link` of an empty list) draws nothing, on a page as in
/// the drawings; last among the items, it made the page read past the frame's numbers.
#[test]
fn a_link_through_no_point_draws_nothing_on_a_page() {
    let (m, mo) = motion();
    let none: [Pt; 0] = [];
    for d in [
        Drawing::new().joint("b").link(none.clone()),
        Drawing::new().link(none.clone()).joint("b").body(none.clone()),
        Drawing::new().joint("b").body(none.clone()).trace("p"),
    ] {
        let svg = d.svg(&mo, 0).unwrap();
        let page = html(&m, &d, &mo, &HtmlConfig::new("empty links")).unwrap();
        assert_eq!(page.matches("class=\"kl-joint\"").count(), svg.matches("<circle r=\"3.5\"").count());
    }
}

/// A sweep far from the origin of its input (a crank after a hundred thousand turns): the
/// readouts keep the digits that tell the frames apart, and the charts against the input
/// spread over their width. Rounded to five significant digits of the largest value, a whole
/// turn read `5.7296e7` at every frame and each chart collapsed onto one vertical line.
#[test]
fn a_sweep_far_from_zero_keeps_the_digits_that_tell_its_frames_apart() {
    let m = FourBar::default();
    let start = 1e6;
    let mo = Motion::record(&m, m.sweep(start, start + TAU, 73, &m.guess(start)).unwrap()).unwrap();
    let d = Drawing::new().link(["b", "c", "p"]);
    let page = html(&m, &d, &mo, &HtmlConfig::new("far").show("gamma")).unwrap();
    // The readouts' values of the input at every frame: all different.
    let data = page.split("id=\"kl-data\">").nth(1).unwrap().split("</script>").next().unwrap();
    let phi: Vec<&str> =
        data.split("\"v\":[").nth(1).unwrap().split(']').next().unwrap().split(',').collect::<Vec<_>>();
    assert_eq!(phi.len(), 73);
    let mut distinct = phi.clone();
    distinct.dedup();
    assert_eq!(distinct.len(), 73, "{phi:?}");
    // The chart of gamma against phi: its curve spans most of the plot's width.
    let curve = page.split("class=\"kl-curve\" points=\"").nth(1).unwrap().split('"').next().unwrap();
    let xs: Vec<f64> = curve.split(' ').map(|p| p.split(',').next().unwrap().parse().unwrap()).collect();
    let (lo, hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(*x), b.max(*x)));
    assert!(hi - lo > 200.0, "the curve spans {lo}..{hi} px");
}

/// The x tick labels of a page's charts do not run into each other (widths estimated at 0.6 em
/// a character of the charts' 11 px text): on an input far from zero, labelled with many
/// digits (`5.729580e7`), every second tick (or n-th) is labelled.
#[test]
fn a_charts_x_labels_stand_apart() {
    let m = FourBar::default();
    let start = 1e6;
    let mo = Motion::record(&m, m.sweep(start, start + TAU, 73, &m.guess(start)).unwrap()).unwrap();
    let d = Drawing::new().link(["b", "c", "p"]);
    let page = html(&m, &d, &mo, &HtmlConfig::new("far").show("gamma")).unwrap();
    let labels: Vec<(f64, String)> = page
        .split("class=\"kl-tick-x\" x=\"")
        .skip(1)
        .map(|s| {
            let x: f64 = s.split('"').next().unwrap().parse().unwrap();
            let label = s.split('>').nth(1).unwrap().split('<').next().unwrap().to_string();
            (x, label)
        })
        .collect();
    assert!(labels.len() >= 2, "{labels:?}");
    let half = |l: &str| 0.5 * 0.6 * 11.0 * l.chars().count() as f64;
    for w in labels.windows(2) {
        assert!(w[0].0 + half(&w[0].1) < w[1].0 - half(&w[1].1), "{:?} and {:?} overlap", w[0], w[1]);
    }
}

#[test]
fn a_duration_a_page_cannot_play_is_refused_as_an_animations_is() {
    // A subnormal duration made the page's script divide the time played into infinity and
    // fail on every frame; a duration an animated SVG refuses is refused here too.
    let (m, motion) = motion();
    let drawing = DefaultDrawing::new(&m).into_drawing();
    for seconds in [5e-324, 1e-300, 1e-4, 0.0, -1.0, 1e10, f64::INFINITY, f64::NAN] {
        let page = html(&m, &drawing, &motion, &HtmlConfig::new("x").with_seconds(seconds));
        assert!(matches!(page, Err(HtmlError::InvalidSetting(_))), "{seconds:e}");
    }
    for seconds in [1e-3, 6.0, 1e9] {
        assert!(html(&m, &drawing, &motion, &HtmlConfig::new("x").with_seconds(seconds)).is_ok(), "{seconds:e}");
    }
}

/// A motion whose output columns are not the mechanism's (its fields set by hand, or recorded
/// from another mechanism of the same inputs) is refused naming the output columns: the
/// message said the inputs differed and printed the same inputs twice.
#[test]
fn a_motion_of_other_output_columns_is_refused_naming_them() {
    let (m, mut mo) = motion();
    let drawing = DefaultDrawing::new(&m).into_drawing();
    mo.outputs.truncate(1);
    let Err(HtmlError::InvalidSetting(e)) = html(&m, &drawing, &mo, &HtmlConfig::new("x")) else {
        panic!("a motion of other output columns made a page")
    };
    assert!(e.contains("output columns") && !e.contains("inputs"), "{e}");
    mo.inputs = vec!["theta".into()];
    let Err(HtmlError::InvalidSetting(e)) = html(&m, &drawing, &mo, &HtmlConfig::new("x")) else {
        panic!("a motion of other inputs made a page")
    };
    assert!(e.contains("inputs [\"theta\"]"), "{e}");
}

/// The opening tag of a page's picture: its size, scale and origin.
fn picture_tag(page: &str) -> &str {
    let start = page.find(r#"<svg xmlns="http://www.w3.org/2000/svg" id="kl-drawing""#).expect("the picture");
    &page[start..start + page[start..].find('>').unwrap()]
}

/// A page's picture is framed to what it draws: the mechanism and its traced paths. The
/// drawings' labels and the strip under an SVG drawing (scale bar, readout of the inputs,
/// notes) are not drawn over the page's picture (the page writes its readouts, events and
/// notes as text beside and under it), and left the picture a blank band under the mechanism
/// as high as that strip, and as wide and offset as a long label or readout made the drawing.
#[test]
fn a_pages_picture_is_framed_by_what_it_draws() {
    let (m, mo) = motion();
    let bare = Drawing::new()
        .with_annotate(kinloop_viz::draw::Annotate::none())
        .pivot(Pt::fixed(0.0, 0.0))
        .pivot(Pt::fixed(m.d, 0.0))
        .link([Pt::fixed(0.0, 0.0), Pt::point("b"), Pt::point("c"), Pt::fixed(m.d, 0.0)])
        .trace("p");
    let mut annotated = bare.clone();
    annotated.annotate = kinloop_viz::draw::Annotate::default();
    let annotated = annotated
        .label(Pt::point("c"), "the rocker's pin, where the coupler meets it")
        .note("a note long enough to take two lines of the strip under the drawing, so that its height shows");
    // The SVG drawings do hold the annotations: the annotated one is larger.
    let size = |svg: &str| {
        let doc = roxmltree::Document::parse(svg).unwrap();
        let attr = |a: &str| doc.root_element().attribute(a).unwrap().parse::<f64>().unwrap();
        [attr("width"), attr("height")]
    };
    let bare_svg = size(&bare.svg(&mo, 0).unwrap());
    let annotated_svg = size(&annotated.svg(&mo, 0).unwrap());
    assert!(annotated_svg[1] > bare_svg[1] + 40.0, "{annotated_svg:?} {bare_svg:?}");
    let config = HtmlConfig::new("framed");
    let bare_page = html(&m, &bare, &mo, &config).unwrap();
    let annotated_page = html(&m, &annotated, &mo, &config).unwrap();
    // The same picture, to the digit: the page draws the same items and paths of both.
    assert_eq!(picture_tag(&annotated_page), picture_tag(&bare_page));
    // The bare drawing has no strip (no annotation, event or note): its SVG is the mechanism
    // and its paths alone, which is what the page shows.
    let tag = picture_tag(&annotated_page);
    let field = |a: &str| tag.split(&format!(r#" {a}=""#)).nth(1).unwrap().split('"').next().unwrap().to_string();
    assert_eq!([field("width"), field("height")], bare_svg.map(|v| v.to_string()), "{tag}");
    assert!(annotated_page.contains("<p class=\"kl-drawing-note\">note: a note long enough"));
}

/// The page's Play button. Disabled where there is nothing to play: a page of one pose, or a
/// grid whose first input (the one Play moves) has one value; pressed, it did nothing.
fn play_disabled(page: &str) -> bool {
    let at = page.find(r#"<button id="kl-play""#).expect("the button");
    let tag = &page[at..at + page[at..].find('>').unwrap()];
    tag.contains(" disabled")
}

/// A page with nothing to play offers no Play that does nothing, and says "1 pose", not "1
/// poses"; a page with something to play keeps its button.
#[test]
fn a_page_with_nothing_to_play_disables_its_play_button() {
    use kinloop::Mechanism;
    use kinloop_fixtures::FiveBar;
    use kinloop_viz::draw::{Draw, GridMotion, html_grid};
    let m = FourBar::default();
    let d = Drawing::new().link([Pt::fixed(0.0, 0.0), Pt::point("b"), Pt::point("c")]);
    let one = Motion::record(&m, m.sweep(0.5, 0.5, 1, &m.guess(0.5)).unwrap()).unwrap();
    let page = html(&m, &d, &one, &HtmlConfig::new("one pose")).unwrap();
    assert!(play_disabled(&page));
    assert!(page.contains("1 pose of a branch-safe sweep"), "{page}");
    let (m, two) = motion();
    let page = html(&m, &d, &two, &HtmlConfig::new("poses")).unwrap();
    assert!(!play_disabled(&page));
    assert!(page.contains("13 poses of a branch-safe sweep"));
    // A grid: Play moves the first input.
    let five = FiveBar::default();
    let drawing = five.drawing().into_drawing();
    for (counts, to, disabled) in [([1, 3], [0.0, 0.2], true), ([3, 1], [0.2, 0.0], false)] {
        let from = [0.0, 0.0];
        let grid = GridMotion::record(&five, from, to, counts, five.guess_flat(&from)).unwrap();
        let page = html_grid(&five, &drawing, &grid, &HtmlConfig::new("grid")).unwrap();
        assert_eq!(play_disabled(&page), disabled, "{counts:?}");
    }
}
