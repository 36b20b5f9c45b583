//! Mistakes in a drawing or its input are typed errors, never panics or NaN in the SVG.

use kinloop_viz::draw::{Animation, Canvas, DrawError, Drawing, Motion, Pt, Scalar};
use std::f64::consts::TAU;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::FourBar;

kinloop::mechanism! {
    /// A crank with no `point` outputs.
    pub struct Crank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oabo: r @ phi == (x, 0) + l @ psi;
    }
}

fn motion() -> (FourBar, Motion) {
    let m = FourBar::default();
    let mo = Motion::record(&m, m.sweep(0.0, TAU, 13, &m.guess(0.0)).unwrap()).unwrap();
    (m, mo)
}

#[test]
fn a_name_that_is_not_a_point_is_an_error_listing_the_points() {
    let (_, mo) = motion();
    for d in [
        Drawing::new().link(["b", "q"]),
        Drawing::new().trace("beta"),
        Drawing::new().slider("c.x", 0.0),
        Drawing::new().gear("", 1.0, 0.0),
    ] {
        let err = d.animate(&mo, &Animation::default()).unwrap_err();
        let DrawError::UnknownPoint { name, available } = &err else { panic!("{err}") };
        assert_eq!(available, &["b", "c", "p"], "{name}");
        assert!(err.to_string().contains("the mechanism's points are b, c, p"), "{err}");
        assert!(matches!(d.svg(&mo, 0), Err(DrawError::UnknownPoint { .. })));
        assert!(matches!(d.exposures(&mo, 4), Err(DrawError::UnknownPoint { .. })));
    }
    // A mechanism without points says so and what to use instead.
    let m = Crank::default();
    let mo = Motion::record(&m, m.sweep(0.0, TAU, 5, &m.guess(0.0)).unwrap()).unwrap();
    let err = Drawing::new().joint("b").svg(&mo, 0).unwrap_err();
    assert!(err.to_string().contains("declares no `point` outputs; use `Pt::fixed` or `Pt::expr`"), "{err}");
}

#[test]
fn an_empty_motion_is_an_error() {
    let empty = Motion::empty::<FourBar, 2, 1, 6>();
    let d = Drawing::new().joint("b");
    assert!(matches!(d.animate(&empty, &Animation::default()), Err(DrawError::EmptyMotion)));
    assert!(matches!(d.exposures(&empty, 3), Err(DrawError::EmptyMotion)));
    assert!(matches!(d.svg(&empty, 0), Err(DrawError::EmptyMotion)));
    assert!(d.svg(&empty, 0).unwrap_err().to_string().contains("empty sweep"));
}

#[test]
fn non_finite_geometry_is_an_error_naming_the_pose() {
    let (_, mo) = motion();
    let nan_at_pose_3 = Pt::expr(|s| [if s.x[0] > 1.5 && s.x[0] < 2.0 { f64::NAN } else { 0.0 }, 0.0]);
    let err = Drawing::new().joint(nan_at_pose_3).animate(&mo, &Animation::default()).unwrap_err();
    assert!(matches!(&err, DrawError::NonFinite { pose: 3, .. }), "{err}");
    let err = Drawing::new().slider("c", Scalar::expr(|_| f64::INFINITY)).svg(&mo, 0).unwrap_err();
    assert!(matches!(&err, DrawError::NonFinite { pose: 0, .. }), "{err}");
    let err = Drawing::new().gear(Pt::fixed(0.0, 0.0), f64::NAN, 0.0).svg(&mo, 0).unwrap_err();
    assert!(err.to_string().contains("radius"), "{err}");
}

#[test]
fn settings_out_of_range_are_errors() {
    let (_, mo) = motion();
    let d = Drawing::new().joint("b");
    let bad = |a: Animation| matches!(d.animate(&mo, &a), Err(DrawError::InvalidSetting(_)));
    assert!(bad(Animation { frames: 1, ..Animation::default() }));
    assert!(bad(Animation { seconds: 0.0, ..Animation::default() }));
    assert!(bad(Animation { seconds: f64::NAN, ..Animation::default() }));
    assert!(matches!(d.exposures(&mo, 0), Err(DrawError::InvalidSetting(_))));
    assert!(matches!(d.svg(&mo, 13), Err(DrawError::InvalidSetting(_))));
    for canvas in [
        Canvas { width: 0.0, ..Canvas::default() },
        Canvas { margin: 300.0, ..Canvas::default() },
        Canvas { window: Some([1.0, 0.0, 1.0, 2.0]), ..Canvas::default() },
        Canvas { window: Some([0.0, 0.0, f64::INFINITY, 2.0]), ..Canvas::default() },
    ] {
        let err = d.clone().with_canvas(canvas).svg(&mo, 0).unwrap_err();
        assert!(matches!(err, DrawError::InvalidSetting(_)), "{canvas:?}: {err}");
    }
    assert!(matches!(Drawing::new().svg(&mo, 0), Err(DrawError::InvalidSetting(_))));
}

#[test]
fn a_failed_sweep_is_an_error_and_a_lone_pose_still_draws() {
    // Links too short to close the loop: the sweep fails at its first pose.
    let m = FourBar { r: 1.0, l: 1.0, k: 1.0, d: 5.0, ..FourBar::default() };
    let err = Motion::record(&m, m.sweep(0.0, TAU, 13, &m.guess(0.0)).unwrap()).unwrap_err();
    assert!(matches!(err, DrawError::Sweep(kinloop::Error::NoAssembly { .. })), "{err}");
    // A one-sample motion is drawn (a lone point is shown at the scale of its distance from
    // the origin).
    let m = FourBar::default();
    let one = Motion::record(&m, m.sweep(0.0, 0.0, 1, &m.guess(0.0)).unwrap()).unwrap();
    let svg = Drawing::new().joint("p").animate(&one, &Animation::default()).unwrap();
    assert!(!svg.contains("NaN") && !svg.contains("inf") && !svg.contains("<animate"));
}

#[test]
fn a_hand_pushed_pose_shorter_than_the_mechanism_is_an_error() {
    let (m, mo) = motion();
    let d = Drawing::new().link(["b", "c", "p"]).trace("p");
    let full = kinloop_viz::draw::Pose::from(&m.solve(0.3).unwrap().flat);
    // Too few output columns (the drawing reads `p.x`, `p.y` from them), too few inputs, too
    // many unknowns: each is named with its counts, on a sample or on an event.
    let cases = [
        (kinloop_viz::draw::Pose { out: full.out[..2].to_vec(), ..full.clone() }, "output column", 2, 6),
        (kinloop_viz::draw::Pose { x: Vec::new(), ..full.clone() }, "input", 0, 1),
        (kinloop_viz::draw::Pose { q: vec![0.0; 3], ..full.clone() }, "unknown", 3, 2),
    ];
    for (pose, what, has, needs) in cases {
        let mut short = mo.clone();
        short.push(pose.clone());
        let at = short.poses.len() - 1;
        for err in [
            d.svg(&short, 0).unwrap_err(),
            d.animate(&short, &Animation::default()).unwrap_err(),
            d.exposures(&short, 3).unwrap_err(),
        ] {
            let DrawError::MalformedPose { pose, part, len, expected } = err else { panic!("{err}") };
            assert_eq!((pose, part, len, expected), (at, what, has, needs));
        }
        let mut event = mo.clone();
        event.events.push(kinloop_viz::draw::Marked { kind: kinloop::EventKind::LimitPosition, pose });
        let err = d.svg(&event, 0).unwrap_err();
        assert!(matches!(err, DrawError::MalformedPose { pose, .. } if pose == mo.poses.len()), "{err}");
        assert!(err.to_string().contains(&format!("{has} {what} values but the motion needs {needs}")), "{err}");
    }
    // An event's input is printed in its label: it must be finite.
    let mut event = mo.clone();
    event.events.push(kinloop_viz::draw::Marked {
        kind: kinloop::EventKind::LimitPosition,
        pose: kinloop_viz::draw::Pose { x: vec![f64::NAN], ..full },
    });
    assert!(matches!(d.svg(&event, 0), Err(DrawError::NonFinite { .. })));
}

/// Every number of `svg` (attribute values and text) is finite: no `NaN`, `inf` in it.
fn all_finite(svg: &str) -> bool {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    doc.descendants().all(|n| {
        let bad = |s: &str| s.contains("NaN") || s.contains("inf");
        !n.attributes().any(|a| bad(a.value())) && !n.text().is_some_and(bad)
    })
}

#[test]
fn extreme_coordinates_draw_finite_or_are_errors() {
    let (_, mo) = motion();
    // Points at the ends of the f64 range: the extent overflows a plain difference.
    let huge = Drawing::new().link([Pt::fixed(-1.7e308, -1.7e308), Pt::fixed(1.7e308, 1.7e308)]).joint("p");
    let svg = huge.svg(&mo, 0).unwrap();
    assert!(all_finite(&svg), "{svg}");
    // A mechanism of subnormal size: drawn when its extent can be scaled to pixels, a typed
    // error when the pixels per unit overflow.
    let tiny = Drawing::new().link([Pt::fixed(0.0, 0.0), Pt::fixed(1e-300, 1e-300)]);
    assert!(all_finite(&tiny.svg(&mo, 0).unwrap()));
    let subnormal = Drawing::new().link([Pt::fixed(0.0, 0.0), Pt::fixed(1e-320, 0.0)]);
    assert!(matches!(subnormal.svg(&mo, 0), Err(DrawError::Unscalable { .. })));
    let lone = Drawing::new().joint(Pt::fixed(1e-320, 0.0));
    assert!(all_finite(&lone.svg(&mo, 0).unwrap()));
    // A gear whose circle leaves the f64 plane, a negative radius.
    let gear = Drawing::new().gear(Pt::fixed(1e308, 0.0), 1e308, 0.0).svg(&mo, 0);
    assert!(matches!(gear, Err(DrawError::NonFinite { .. })), "{gear:?}");
    let gear = Drawing::new().gear(Pt::fixed(0.0, 0.0), -1.0, 0.0).svg(&mo, 0);
    assert!(matches!(gear, Err(DrawError::InvalidSetting(_))), "{gear:?}");
    // Huge angles (their degrees overflow), a far-off point through a tiny window.
    let turned = Drawing::new().slider("c", Scalar::expr(|s| if s.x[0] > 1.0 { 1.7e308 } else { -1.7e308 }));
    assert!(all_finite(&turned.animate(&mo, &Animation::default()).unwrap()));
    let window = Canvas { window: Some([0.0, 0.0, 1e-6, 1e-6]), ..Canvas::default() };
    let far = Drawing::new().with_canvas(window).joint("p").svg(&mo, 0);
    assert!(matches!(far, Err(DrawError::OffCanvas { .. })), "{far:?}");
    let window = Canvas { window: Some([0.0, 0.0, 1.0, 1e300]), ..Canvas::default() };
    assert!(matches!(Drawing::new().with_canvas(window).joint("p").svg(&mo, 0), Err(DrawError::InvalidSetting(_))));
    // A slider far along its guide through a window: the guide is cut to the picture (not a
    // billion hatch strokes).
    let window = Canvas { window: Some([-2.0, -2.0, 6.0, 5.0]), ..Canvas::default() };
    let far_slider = Drawing::new().with_canvas(window).slider(Pt::expr(|s| [1e6 * s.x[0], 0.0]), 0.0);
    let svg = far_slider.exposures(&mo, 3).unwrap();
    assert!(svg.len() < 100_000 && all_finite(&svg), "{} bytes", svg.len());
}

#[test]
fn style_sizes_and_colours_are_checked() {
    let (_, mo) = motion();
    let d = Drawing::new().link(["b", "c"]).slider("c", 0.0).trace("p");
    for style in [
        kinloop_viz::draw::Style { link_width: f64::NAN, ..Default::default() },
        kinloop_viz::draw::Style { joint_radius: -1.0, ..Default::default() },
        kinloop_viz::draw::Style { block: [f64::INFINITY, 1.0], ..Default::default() },
        kinloop_viz::draw::Style { ink: "red\" onload=\"x".into(), ..Default::default() },
        kinloop_viz::draw::Style { fill: "red\u{1}".into(), ..Default::default() },
        // Sizes larger than the picture: a block 1e7 pixels long drew a picture 1e7 pixels
        // wide with a guide of a million hatch strokes (and 1e300 never finished hatching);
        // a link 1e300 pixels wide, a picture 1e300 pixels wide.
        kinloop_viz::draw::Style { block: [1e7, 14.0], ..Default::default() },
        kinloop_viz::draw::Style { block: [26.0, 1e300], ..Default::default() },
        kinloop_viz::draw::Style { link_width: 1e300, ..Default::default() },
        kinloop_viz::draw::Style { joint_radius: 1e9, ..Default::default() },
        kinloop_viz::draw::Style { trace_width: 2e6, ..Default::default() },
    ] {
        match d.clone().with_style(style.clone()).svg(&mo, 0) {
            Err(DrawError::InvalidSetting(_)) => {}
            other => panic!("{style:?}: {:?}", other.map(|svg| svg.len())),
        }
    }
    let wide = Canvas { width: 1e300, ..Canvas::default() };
    assert!(matches!(d.clone().with_canvas(wide).svg(&mo, 0), Err(DrawError::InvalidSetting(_))));
}

/// A drawing's error goes through `?` into kinloop's one error type, whole: a failed sweep as
/// the sweep's error, anything else as `Error::Figure`, from which it comes back typed.
#[test]
fn draw_errors_convert_into_kinloops_error() {
    fn svg_of_empty() -> Result<String, kinloop_runtime::Error> {
        let empty = Motion::empty::<FourBar, 2, 1, 6>();
        Ok(Drawing::new().joint("b").svg(&empty, 0)?)
    }
    let e = svg_of_empty().unwrap_err();
    let kinloop_runtime::Error::Figure(source) = &e else { panic!("{e:?}") };
    assert!(matches!(source.downcast_ref::<DrawError>(), Some(DrawError::EmptyMotion)), "{e:?}");
    assert_eq!(e.to_string(), DrawError::EmptyMotion.to_string());
    let sweep = kinloop_runtime::Error::InvalidArgument("no samples".into());
    assert_eq!(kinloop_runtime::Error::from(DrawError::Sweep(sweep.clone())), sweep);
}
