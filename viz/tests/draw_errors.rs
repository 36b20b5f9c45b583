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
