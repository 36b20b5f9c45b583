//! The interactive pages in a real browser: headless Chromium opens each page with the slider
//! moved to several poses (`page.html#probe=0,40,...`: the page's script moves the slider as a
//! user does and writes out what is then drawn), and the joints drawn, the readouts and the
//! charts' cursors are compared with closed-form positions of the mechanism at that input.
//! The drawn DOM itself (`--dump-dom`) is read back too, and a screenshot per mechanism is
//! written under `target/` for a person to look at.
//!
//! Without Chromium the browser tests print a note and pass locally; in CI (`CI` set) they
//! fail: `.ci/run` installs Debian's `chromium`. `KINLOOP_CHROMIUM` names another binary.
//!
//! The pages' SVG is also parsed as XML (no browser needed): no NaN, finite numbers, units on
//! every axis, a full turn ticked 0..360.

use kinloop::EventKind;
use kinloop_fixtures::{GALLERY_DRIVE, RhombicDrive};
use kinloop_viz::draw::{Drawing, HtmlConfig, Motion, Pt, Readout, html};
use std::f64::consts::{PI, TAU};
use std::path::Path;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::{FourBar, four_bar_joints};

mod browser_support;

use browser_support::{Expected, check_in_browser, chromium, read_page, root, run_chromium, url};

/// The gallery's four-bar (the same parameters as `CouplerFourBar` of the gallery, whose
/// `FourBar` twin the draw tests share): crank pin B, rocker pin C, coupler point P in closed
/// form; the page's readouts gamma, p.y, beta, p.x.
#[test]
fn gallery_four_bar_page_draws_the_closed_form_positions() {
    // The units the readouts state: angles in degrees, lengths in the (unnamed) unit.
    let page = read_page(&std::fs::read_to_string(root().join("docs/pages/four_bar_coupler.html")).unwrap());
    let units: Vec<(&str, &str)> = page.readouts.iter().map(|(l, u)| (l.as_str(), u.as_str())).collect();
    assert_eq!(units, [("phi", "°"), ("gamma", "°"), ("p.y", "length unit"), ("beta", "°"), ("p.x", "length unit")]);
    let Some(bin) = chromium() else { return };
    let m = FourBar::default();
    let phi = |i: usize| i as f64 * TAU / 360.0;
    check_in_browser(
        &bin,
        &root().join("docs/pages/four_bar_coupler.html"),
        "four_bar_coupler",
        &[0, 45, 137, 250, 360],
        |i| {
            let [b, c, p] = four_bar_joints(&m, phi(i));
            let gamma = (c[1]).atan2(c[0] - m.d);
            let beta = (c[1] - b[1]).atan2(c[0] - b[0]);
            // Angles as the readouts show them: continuous from the declared guesses (gamma near
            // 1.5 rad and beta near 0.5 rad over the whole turn: no wrap on this branch).
            Expected {
                chart_x: phi(i).to_degrees(),
                joints: vec![("-", [0.0, 0.0]), ("-", [m.d, 0.0]), ("b", b), ("c", c), ("p", p)],
                dots: vec![("p", p)],
                values: vec![
                    ("phi", phi(i).to_degrees()),
                    ("gamma", gamma.to_degrees()),
                    ("p.y", p[1]),
                    ("beta", beta.to_degrees()),
                    ("p.x", p[0]),
                ],
            }
        },
    );
}

/// The gallery's rhombic drive: crank arms AB and AD about A, pistons C (y = 0) and F
/// (y = de) in closed form from the loops (working rod to the left, displacer rod to the
/// right), and the rods' centres of mass S2, S4 (the traced points).
#[test]
fn gallery_rhombic_drive_page_draws_the_closed_form_positions() {
    let Some(bin) = chromium() else { return };
    let m: RhombicDrive = GALLERY_DRIVE;
    let phi = |i: usize| i as f64 * TAU / 360.0;
    check_in_browser(&bin, &root().join("docs/pages/rhombic_drive.html"), "rhombic_drive", &[0, 90, 200, 333], |i| {
        let a = [0.0, m.e_p];
        let b = [a[0] + m.r_p * phi(i).cos(), a[1] + m.r_p * phi(i).sin()];
        let d = [a[0] + m.r_b * (phi(i) + m.gamma).cos(), a[1] + m.r_b * (phi(i) + m.gamma).sin()];
        // B = C + l_p @ phi2 with cos phi2 > 0; D = F + l_b @ phi4 with cos phi4 < 0.
        let (s2, c2) = (b[1] / m.l_p, (1.0 - (b[1] / m.l_p).powi(2)).sqrt());
        let c = [b[0] - m.l_p * c2, 0.0];
        let (s4, c4) = ((d[1] - m.de) / m.l_b, -(1.0 - ((d[1] - m.de) / m.l_b).powi(2)).sqrt());
        let f = [d[0] - m.l_b * c4, m.de];
        let cs2 = [c[0] + m.l_cs2 * c2, c[1] + m.l_cs2 * s2];
        let fs4 = [f[0] + m.l_fs4 * c4, f[1] + m.l_fs4 * s4];
        let phi4 = s4.atan2(c4);
        Expected {
            chart_x: phi(i).to_degrees(),
            joints: vec![("-", a), ("-", b), ("-", c), ("-", d), ("-", f)],
            dots: vec![("s2", cs2), ("s4", fs4)],
            values: vec![
                ("phi1", phi(i).to_degrees()),
                ("x_c", c[0]),
                ("x_f", f[0]),
                ("phi2", s2.atan2(c2).to_degrees()),
                // phi4 continues from its guess pi: in (0, 2 pi) on this branch.
                ("phi4", phi4.rem_euclid(TAU).to_degrees()),
                ("gap", f[0] - c[0]),
            ],
        }
    });
}

/// Where the circles (`a`, `ra`) and (`b`, `rb`) meet, to the left of a->b (a tangency, at
/// a limit position, counts as meeting).
fn meet_left(a: [f64; 2], ra: f64, b: [f64; 2], rb: f64) -> [f64; 2] {
    let v = [b[0] - a[0], b[1] - a[1]];
    let dist = v[0].hypot(v[1]);
    let along = (ra * ra - rb * rb + dist * dist) / (2.0 * dist);
    let h = (ra * ra - along * along).max(0.0).sqrt();
    [a[0] + (along * v[0] - h * v[1]) / dist, a[1] + (along * v[1] + h * v[0]) / dist]
}

kinloop::mechanism! {
    /// A five-bar: two cranks (inputs) joined by two links meeting at `p`.
    pub struct FiveBar {
        params a = 1.0, b = 2.5, c = 2.5, d = 1.0, e = 2.0;
        inputs th1, th2;
        unknowns al = 1.2, be = 2.0;
        loop l: a @ th1 + b @ al == (e, 0) + d @ th2 + c @ be;
        point p = a @ th1 + b @ al;
    }
}

/// Several inputs: the slider moves along the straight path in input space (the first crank
/// half a turn, the second a quarter), every input has its readout and the charts are against
/// the fraction of the path; the joint P is where the links' circles meet.
#[test]
fn several_inputs_move_along_the_path() {
    let m = FiveBar::default();
    let (from, to) = ([0.0, 0.5 * PI], [PI, PI]);
    let samples = 61;
    let motion = Motion::record(&m, m.sweep(from, to, samples, &m.guess(from)).unwrap()).unwrap();
    let (a, c) = (
        |s: &kinloop_viz::draw::StateRef| [s.x[0].cos(), s.x[0].sin()],
        |s: &kinloop_viz::draw::StateRef| [2.0 + s.x[1].cos(), s.x[1].sin()],
    );
    let drawing = Drawing::new()
        .pivot(Pt::fixed(0.0, 0.0))
        .pivot(Pt::fixed(m.e, 0.0))
        .link([Pt::fixed(0.0, 0.0), Pt::expr(a), Pt::point("p"), Pt::expr(c), Pt::fixed(m.e, 0.0)])
        .trace("p");
    let config = HtmlConfig::new("Five-bar").show(FiveBar::COL.p.y).with_autoplay(false);
    let page = html(&m, &drawing, &motion, &config).unwrap();
    let read = read_page(&page);
    assert_eq!(read.readouts[..2], [("th1".to_string(), "°".to_string()), ("th2".to_string(), "°".to_string())]);
    assert!(read.charts[0].1.iter().all(|(v, _)| (0.0..=1.0).contains(v)), "charted against the path's fraction");
    let Some(bin) = chromium() else { return };
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("five_bar.html");
    std::fs::write(&path, &page).unwrap();
    check_in_browser(&bin, &path, "five_bar", &[0, 17, 60], |i| {
        let u = i as f64 / (samples - 1) as f64;
        let (th1, th2) = (from[0] + u * (to[0] - from[0]), from[1] + u * (to[1] - from[1]));
        let pa = [m.a * th1.cos(), m.a * th1.sin()];
        let pc = [m.e + m.d * th2.cos(), m.d * th2.sin()];
        let p = meet_left(pa, m.b, pc, m.c);
        Expected {
            chart_x: u,
            joints: vec![("-", pa), ("p", p), ("-", pc)],
            dots: vec![("p", p)],
            values: vec![("th1", th1.to_degrees()), ("th2", th2.to_degrees()), ("p.y", p[1])],
        }
    });
}

kinloop::mechanism! {
    /// A non-Grashof four-bar: the crank rocks between two limit positions.
    pub struct Rocking {
        params r = 3.0, l = 2.0, k = 2.5, d = 4.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop obcd: r @ phi + l @ beta == (d, 0) + k @ gamma;
        point b = r @ phi;
        point c = (d, 0) + k @ gamma;
    }
}

/// The limit position where the coupler and the rocker are collinear, |BD| = l + k (law of
/// cosines in triangle OBD).
fn rocking_limit(m: &Rocking) -> f64 {
    ((m.r * m.r + m.d * m.d - (m.l + m.k).powi(2)) / (2.0 * m.r * m.d)).acos()
}

fn rocking_page(m: &Rocking) -> (String, Motion) {
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let motion = Motion::record(m, m.sweep(0.0, PI, 91, &g).unwrap()).unwrap();
    let drawing = Drawing::new()
        .pivot(Pt::fixed(0.0, 0.0))
        .pivot(Pt::fixed(m.d, 0.0))
        .link([Pt::fixed(0.0, 0.0), Pt::point("b"), Pt::point("c"), Pt::fixed(m.d, 0.0)])
        .trace("c");
    let config =
        HtmlConfig::new("Rocking four-bar").show(Rocking::COL.gamma).with_back_and_forth(true).with_length_unit("mm");
    (html(m, &drawing, &motion, &config).unwrap(), motion)
}

/// A page written by the library here (not a committed file): the sweep stops at the limit
/// position, which is the slider's last pose, marked at the end of its track and labelled
/// with the closed-form input; the browser draws B and C there.
#[test]
fn a_sweep_stopped_at_a_limit_position_ends_the_slider_there() {
    let m = Rocking::default();
    let (page, motion) = rocking_page(&m);
    let limit = rocking_limit(&m);
    assert_eq!(motion.events.len(), 1);
    assert_eq!(motion.events[0].kind, EventKind::LimitPosition);
    let label = format!("limit position at phi = {:.2}°", limit.to_degrees());
    assert!(page.contains(&label), "the limit is labelled `{label}`");
    // Labelled in the list under the picture and as the ghost's title, never written over the
    // picture, where it would cover the mechanism.
    let drawing = page.split(r#"<svg xmlns="http://www.w3.org/2000/svg" id="kl-drawing""#).nth(1).unwrap();
    let drawing = drawing.split("</svg>").next().unwrap();
    assert!(!drawing.contains("<text"), "no text over the picture");
    assert!(drawing.contains(&format!(r#"<g class="kl-event"><title>{label}</title>"#)), "the ghost is titled");
    assert!(page.contains(&format!(r#"<span class="kl-key kl-limit-position"></span>{label}</li>"#)), "listed");
    // Samples every 2 degrees below the limit, then the limit itself: the last pose.
    let samples = motion.poses.len();
    assert!(page.contains(&format!(r#"max="{samples}""#)), "the slider ends at the limit position");
    assert!(page.contains("kl-mark kl-limit-position\" style=\"left:calc(8px + (100% - 16px) * 1)\""));
    assert!(page.contains(&format!(r#"data-at="{samples}""#)), "a click on the mark shows the limit position");
    let _ = read_page(&page);
    let Some(bin) = chromium() else { return };
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rocking.html");
    std::fs::write(&path, &page).unwrap();
    // Opened without a pose in its address, the page plays (its button then pauses); the
    // frames it reaches depend on the browser's clock, so only the state is checked.
    let dom = run_chromium(&bin, &url(&path, ""), &["--virtual-time-budget=500", "--dump-dom"]);
    assert!(dom.contains(r#"aria-pressed="true">Pause</button>"#), "the page plays when opened");
    check_in_browser(&bin, &path, "rocking_limit", &[0, 20, samples], |i| {
        let phi = if i == samples { limit } else { i as f64 * PI / 90.0 };
        let b = [m.r * phi.cos(), m.r * phi.sin()];
        // C where the circles (B, l) and (D, k) meet, left of B->D (the declared mode).
        let c = meet_left(b, m.l, [m.d, 0.0], m.k);
        let gamma = c[1].atan2(c[0] - m.d);
        Expected {
            chart_x: phi.to_degrees(),
            joints: vec![("b", b), ("c", c)],
            dots: vec![],
            values: vec![("phi", phi.to_degrees()), ("gamma", gamma.to_degrees())],
        }
    });
}

/// Every gallery page (no browser): one per animated mechanism, linked from the README, its
/// SVG well-formed without NaN, every chart axis titled with its unit, a full turn of the
/// input ticked 0 to 360, a readout per input (and a slider per input on a grid's page), and
/// no address outside the page.
#[test]
fn every_gallery_page_is_self_contained_and_finite() {
    let dir = root().join("docs/pages");
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let mut pages = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "html") {
            let text = std::fs::read_to_string(&path).unwrap();
            let link = format!("(docs/pages/{})", path.file_name().unwrap().to_string_lossy());
            assert!(readme.contains(&link), "the README links {link}");
            let svg = root().join("docs/animations").join(path.file_name().unwrap()).with_extension("svg");
            assert!(svg.is_file(), "{} has its animation", path.display());
            assert!(text.len() < 150_000, "{}: {} bytes", path.display(), text.len());
            let page = read_page(&text);
            assert!(!page.readouts.is_empty(), "{}", path.display());
            if text.contains(r#"id="kl-slider-0""#) {
                // A grid of several inputs: a slider and a readout for each, no chart.
                let sliders = text.matches(r#"class="kl-slider""#).count();
                assert!(sliders >= 2 && page.readouts.len() >= sliders, "{}", path.display());
                assert!(page.charts.is_empty() && text.contains(r#""grid":{"n":["#), "{}", path.display());
            } else {
                assert!(!page.charts.is_empty(), "{}", path.display());
            }
            for (title, xs, _) in &page.charts {
                let labels: Vec<f64> = xs.iter().map(|(v, _)| *v).collect();
                if labels.first() == Some(&0.0) && labels.last() == Some(&360.0) {
                    assert_eq!(labels, [0.0, 90.0, 180.0, 270.0, 360.0], "{title}: a turn ticked every 90 degrees");
                }
            }
            pages += 1;
        }
    }
    assert!(pages >= 9, "one page per gallery mechanism, found {pages}");
}

/// Bad data is a typed error, never NaN in the file: a readout that is NaN at some pose, a
/// column the mechanism does not have, a setting out of range; and the page is the same
/// bytes every time.
#[test]
fn bad_data_is_an_error_and_pages_are_deterministic() {
    use kinloop_viz::html::HtmlError;
    let m = Rocking::default();
    let (page, motion) = rocking_page(&m);
    assert_eq!(page, rocking_page(&m).0, "the same page every time");
    let drawing = Drawing::new().link([Pt::fixed(0.0, 0.0), Pt::point("b")]);
    let nan = HtmlConfig::new("x").with_readout(Readout::expr("bad", kinloop_viz::plot::Kind::Dimensionless, |s| {
        if s.x[0] > 0.5 { f64::NAN } else { 1.0 }
    }));
    let err = html(&m, &drawing, &motion, &nan).unwrap_err();
    assert!(matches!(err, HtmlError::NonFinite { .. }), "{err}");
    let huge = HtmlConfig::new("x").with_readout(Readout::expr("huge", kinloop_viz::plot::Kind::Dimensionless, |s| {
        if s.x[0] > 0.5 { f64::MAX } else { -f64::MAX }
    }));
    let err = html(&m, &drawing, &motion, &huge).unwrap_err();
    assert!(matches!(err, HtmlError::InvalidSetting(_)), "{err}");
    let err = html(&m, &drawing, &motion, &HtmlConfig::new("x").show("delta")).unwrap_err();
    assert!(matches!(&err, HtmlError::UnknownColumn { name, .. } if name == "delta"), "{err}");
    let err = html(&m, &drawing, &motion, &HtmlConfig::new("x").with_seconds(f64::NAN)).unwrap_err();
    assert!(matches!(err, HtmlError::InvalidSetting(_)), "{err}");
    let point_nan = Drawing::new().link([Pt::fixed(0.0, 0.0), Pt::expr(|s| [s.x[0], f64::NAN])]);
    let err = html(&m, &point_nan, &motion, &HtmlConfig::new("x")).unwrap_err();
    assert!(matches!(err, HtmlError::Draw(_)), "{err}");
    // Fewer frames than poses: at most ten, in equal steps of the samples (the page plays
    // them at one rate), the first and the last (the limit) kept.
    let few = HtmlConfig::new("x").with_max_frames(10);
    let page = html(&m, &drawing, &motion, &few).unwrap();
    let frames = page
        .split(r#"max=""#)
        .nth(1)
        .and_then(|r| r.split('"').next())
        .and_then(|v| v.parse::<usize>().ok())
        .expect("the slider's last frame")
        + 1;
    assert!((3..=10).contains(&frames), "{frames} frames");
    let inputs = page
        .split(r#""ch":[{"#)
        .nth(1)
        .and_then(|r| r.split(r#""v":["#).nth(1))
        .and_then(|r| r.split(']').next())
        .expect("the input's values");
    // Written as the readout shows them: to a hundredth of a degree.
    assert!(inputs.split(',').all(|t| browser_support::resolution(t) == 0.01), "{inputs}");
    let inputs: Vec<f64> = inputs.split(',').map(|v| v.parse().unwrap()).collect();
    assert_eq!(inputs.len(), frames);
    assert_eq!(inputs[0], 0.0);
    assert!(
        (inputs[frames - 1] - rocking_limit(&m).to_degrees()).abs() <= 0.005 + 1e-9,
        "the last frame is the limit: {inputs:?}"
    );
    assert!(inputs.windows(2).all(|w| w[1] > w[0]), "in order: {inputs:?}");
    // The samples are 2 degrees apart: every step but the one to the limit is the same.
    let steps: Vec<f64> = inputs[..frames - 1].windows(2).map(|w| w[1] - w[0]).collect();
    assert!(steps.iter().all(|d| (d - steps[0]).abs() <= 0.011), "equal steps: {inputs:?}");
    let label = format!("limit position at phi = {:.2}°", rocking_limit(&m).to_degrees());
    assert!(page.contains(&label));
    let err = html(&m, &drawing, &motion, &HtmlConfig::new("x").with_max_frames(1)).unwrap_err();
    assert!(matches!(err, HtmlError::InvalidSetting(_)), "{err}");
    // Through kinloop's one error type.
    let e: kinloop::Error = HtmlError::InvalidSetting("x".into()).into();
    assert!(matches!(e, kinloop::Error::Figure(_)));
}

/// A hostile number: NaN, infinities, the ends of the f64 range, subnormals, or an ordinary one.
fn hostile() -> impl proptest::strategy::Strategy<Value = f64> + Clone {
    use proptest::prelude::*;
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(-f64::MAX),
        Just(f64::MAX),
        Just(5e-324),
        Just(1e300),
        Just(-1e-300),
        Just(0.0),
        -10.0..10.0f64,
        any::<f64>(),
    ]
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 48, ..Default::default() })]
    /// Hostile readouts, points and angles: a typed error or a page without NaN or infinity
    /// (parsed as XML), never a panic.
    #[test]
    fn hostile_values_give_an_error_or_a_finite_page(
        values in proptest::collection::vec(hostile(), 1..6),
        points in proptest::collection::vec(hostile(), 2..6),
        angle in hostile(),
    ) {
        let m = Rocking::default();
        let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
        let motion = Motion::record(&m, m.sweep(0.0, 1.0, 9, &g).unwrap()).unwrap();
        let pick = |v: &[f64], s: &kinloop_viz::draw::StateRef| v[((s.x[0] * 8.0).round() as usize) % v.len()];
        let (vs, ps) = (values.clone(), points.clone());
        let drawing = Drawing::new()
            .link([Pt::fixed(0.0, 0.0), Pt::point("b")])
            .slider(Pt::expr(move |s| [pick(&ps, s), 1.0]), kinloop_viz::draw::Scalar::Const(angle))
            .trace("c");
        let config = HtmlConfig::new("hostile")
            .with_readout(Readout::expr("v", kinloop_viz::plot::Kind::length("mm"), move |s| pick(&vs, s)));
        if let Ok(page) = html(&m, &drawing, &motion, &config) {
            let _ = read_page(&page);
        }
    }
}

kinloop::mechanism! {
    /// A five-bar whose links are short: it cannot be assembled where the cranks' pins are
    /// farther apart than `b + c`.
    pub struct ShortFiveBar {
        params a = 1.0, b = 1.6, c = 1.6, d = 1.0, e = 2.0;
        inputs th1, th2;
        unknowns al = 1.2, be = 2.0;
        loop l: a @ th1 + b @ al == (e, 0) + d @ th2 + c @ be;
        point p = a @ th1 + b @ al;
    }
}

/// Several inputs over a grid: one slider per input. Headless Chromium moves both sliders to
/// several cells; the joints drawn there are the closed-form ones (the links' circles meet
/// left of A->C: one assembly mode carried over the whole grid), the readouts show both
/// inputs and p.y, and a cell where the pins are farther apart than `b + c` (closed form) says
/// "not reached on this assembly mode" with the mechanism hidden and no number for p.y.
#[test]
fn a_grid_of_two_inputs_has_a_slider_each_and_marks_what_cannot_be_assembled() {
    use kinloop::Mechanism;
    use kinloop_viz::draw::{Draw, GridMotion, html_grid};
    let m = ShortFiveBar::default();
    let (from, to, counts) = ([0.5, 0.0], [3.5, 3.0], [16, 13]);
    let grid = GridMotion::record(&m, from, to, counts, m.guess_flat(&from)).unwrap();
    let pins = |th1: f64, th2: f64| ([m.a * th1.cos(), m.a * th1.sin()], [m.e + m.d * th2.cos(), m.d * th2.sin()]);
    // The library's grid against the closed form, every cell: reachable ones on the carried
    // mode, the pins too far apart never reachable, and every cell reached whose straight
    // path from a reached neighbour stays within the links' reach.
    let (mut reachable, mut beyond) = (0, 0);
    for j in 0..counts[1] {
        for i in 0..counts[0] {
            let (th1, th2) = (grid.axes[0][i], grid.axes[1][j]);
            let (pa, pc) = pins(th1, th2);
            let apart = (pc[0] - pa[0]).hypot(pc[1] - pa[1]);
            match grid.cells[grid.cell(&[i, j]).unwrap()] {
                Some(k) => {
                    assert!(apart <= m.b + m.c, "cell {i}:{j}: pins {apart} apart");
                    let pose = &grid.motion.poses[k];
                    assert!((pose.x[0] - th1).abs() < 1e-12 && (pose.x[1] - th2).abs() < 1e-12);
                    let p = meet_left(pa, m.b, pc, m.c);
                    // Away from the limit (where the closed form's square root loses digits).
                    if apart < m.b + m.c - 1e-3 {
                        assert!(
                            (pose.out[0] - p[0]).hypot(pose.out[1] - p[1]) < 1e-9,
                            "cell {i}:{j}: {pose:?} vs {p:?}"
                        );
                    }
                    reachable += 1;
                }
                None => beyond += usize::from(apart > m.b + m.c),
            }
        }
    }
    assert!(reachable > 100 && beyond > 10, "{reachable} reachable, {beyond} beyond reach");
    // Within reach along the whole straight path from (i, j) to (i2, j2), by a margin: the
    // sweep between the two cells meets no limit position there.
    let clear = |(i, j): (usize, usize), (i2, j2): (usize, usize)| {
        (0..=64).all(|s| {
            let t = s as f64 / 64.0;
            let th1 = grid.axes[0][i] + t * (grid.axes[0][i2] - grid.axes[0][i]);
            let th2 = grid.axes[1][j] + t * (grid.axes[1][j2] - grid.axes[1][j]);
            let (pa, pc) = pins(th1, th2);
            (pc[0] - pa[0]).hypot(pc[1] - pa[1]) < m.b + m.c - 1e-3
        })
    };
    let reached = |i: usize, j: usize| grid.cells[grid.cell(&[i, j]).unwrap()].is_some();
    let mut around = 0;
    for j in 0..counts[1] {
        for i in 0..counts[0] {
            let from: [(usize, usize); 4] = [(i.wrapping_sub(1), j), (i + 1, j), (i, j.wrapping_sub(1)), (i, j + 1)];
            for (i2, j2) in from.into_iter().filter(|&(i2, j2)| i2 < counts[0] && j2 < counts[1]) {
                if reached(i2, j2) && clear((i2, j2), (i, j)) {
                    assert!(reached(i, j), "cell {i}:{j} not reached from its neighbour {i2}:{j2}");
                }
            }
            // A cell reached only around an unreachable stretch of its own row.
            let row_cut = (0..i).any(|k| !reached(k, j)) && reached(0, j);
            around += usize::from(reached(i, j) && row_cut);
        }
    }
    eprintln!("{around} cells reached past an unreachable stretch of their row");
    let config = HtmlConfig::new("Five-bar over a grid").show(ShortFiveBar::COL.p.y).with_autoplay(false);
    let drawing = m.drawing().into_drawing();
    let page = html_grid(&m, &drawing, &grid, &config).unwrap();
    assert_eq!(page, html_grid(&m, &drawing, &grid, &config).unwrap(), "deterministic");
    let read = read_page(&page);
    let units: Vec<(&str, &str)> = read.readouts.iter().map(|(l, u)| (l.as_str(), u.as_str())).collect();
    assert_eq!(units, [("th1", "°"), ("th2", "°"), ("p.y", "length unit")]);
    assert!(page.contains(r#"id="kl-slider-0" class="kl-slider" data-axis="0" type="range" min="0" max="15""#));
    assert!(page.contains(r#"id="kl-slider-1" class="kl-slider" data-axis="1" type="range" min="0" max="12""#));
    // Bounded: a grid of more cells than the page's poses is an error.
    let small = HtmlConfig::new("x").with_max_frames(100);
    assert!(matches!(html_grid(&m, &drawing, &grid, &small), Err(kinloop_viz::html::HtmlError::InvalidSetting(_))));
    let Some(bin) = chromium() else { return };
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("five_bar_grid.html");
    std::fs::write(&path, &page).unwrap();
    // Reachable cells, then the cell at th1 = 3.5, th2 = 0: pins 1 + 2 + 0.94 > 3.2 apart.
    let cells = [[0, 0], [5, 3], [15, 12], [9, 7], [15, 0], [2, 10]];
    let probe: Vec<String> = cells.iter().map(|[i, j]| format!("{i}:{j}")).collect();
    let dom = run_chromium(&bin, &url(&path, &format!("probe={}", probe.join(","))), &["--dump-dom"]);
    let lines = browser_support::probe_lines(&dom);
    let tol = browser_support::PX_TOL / read.scale;
    for [i, j] in cells {
        let c = grid.cell(&[i, j]).unwrap();
        let at: Vec<&browser_support::Line> = lines.iter().filter(|l| l.frame == c).collect();
        let state = at.iter().find(|l| l.what == "cell").expect("the cell's line");
        assert_eq!(state.get("at"), format!("{i}:{j}"), "both sliders moved");
        let (th1, th2) = (grid.axes[0][i], grid.axes[1][j]);
        let (pa, pc) = pins(th1, th2);
        let apart = (pc[0] - pa[0]).hypot(pc[1] - pa[1]);
        let text =
            |ch: usize| at.iter().find(|l| l.what == "value" && l.get("ch") == ch.to_string()).unwrap().get("text");
        // The inputs' readouts: the sliders' values to a hundredth of a degree, reachable or not.
        for (ch, th) in [(0, th1), (1, th2)] {
            let shown: f64 = text(ch).parse().unwrap();
            assert!((shown - th.to_degrees()).abs() <= 0.005 + 1e-9, "cell {i}:{j}: {} vs {th}", text(ch));
        }
        let status = at.iter().find(|l| l.what == "status").unwrap().get("text");
        if grid.cells[c].is_none() {
            assert_eq!(state.get("reachable"), "false");
            assert_eq!(status, "not reached on this assembly mode");
            assert_eq!(text(2), "\u{2013}", "no number where there is no mechanism");
            assert!(!at.iter().any(|l| l.what == "joint"));
            // The browser draws the frame's two pivots and nothing else of the mechanism.
            let shown = at.iter().find(|l| l.what == "shown").expect("what is drawn");
            assert_eq!(
                [shown.get("pivots"), shown.get("joints"), shown.get("shapes"), shown.get("dots")],
                ["2", "0", "0", "0"]
            );
            continue;
        }
        assert_eq!(state.get("reachable"), "true", "cell {i}:{j}");
        assert!(apart <= m.b + m.c);
        assert_eq!(status, "");
        let p = meet_left(pa, m.b, pc, m.c);
        let drawn: Vec<(&str, [f64; 2])> = at
            .iter()
            .filter(|l| l.what == "joint")
            .map(|l| (l.get("name"), read.world([l.num("x"), l.num("y")])))
            .collect();
        for (name, q) in [("-", pa), ("p", p), ("-", pc), ("-", [0.0, 0.0]), ("-", [m.e, 0.0])] {
            let near = |r: &[f64; 2]| (r[0] - q[0]).abs() <= tol && (r[1] - q[1]).abs() <= tol;
            assert!(
                drawn.iter().any(|(n, r)| (name == "-" || *n == name) && near(r)),
                "cell {i}:{j}: joint {name} at {q:?} not drawn: {drawn:?}"
            );
        }
        let dot = at.iter().find(|l| l.what == "dot" && l.get("name") == "p").expect("p's dot");
        let q = read.world([dot.num("x"), dot.num("y")]);
        assert!((q[0] - p[0]).abs() <= tol && (q[1] - p[1]).abs() <= tol, "cell {i}:{j}: dot {q:?} vs {p:?}");
        let shown: f64 = text(2).parse().unwrap();
        let half = 0.5 * browser_support::resolution(text(2));
        assert!((shown - p[1]).abs() <= half + 1e-12, "cell {i}:{j}: p.y {}", text(2));
    }
    let unreachable = cells.iter().filter(|[i, j]| grid.cells[grid.cell(&[*i, *j]).unwrap()].is_none()).count();
    assert_eq!(unreachable, 1, "one probed cell cannot be assembled");
    // In the DOM after the last move (a reachable cell): the mechanism shown, the status empty.
    let at = dom.find("<svg").unwrap();
    let svg = &dom[at..at + dom[at..].find('>').unwrap()];
    assert!(
        svg.contains(&format!(r#"data-cell="{}""#, grid.cell(&[2, 10]).unwrap()))
            && svg.contains(r#"data-reachable="true""#)
    );
    // Opened without a cell in its address, a page that plays starts playing (along the first
    // input's row; the frames it reaches depend on the browser's clock, so only the state and
    // the reachable first row are checked).
    let playing = Path::new(env!("CARGO_TARGET_TMPDIR")).join("five_bar_grid_playing.html");
    std::fs::write(&playing, html_grid(&m, &drawing, &grid, &config.clone().with_autoplay(true)).unwrap()).unwrap();
    let dom = run_chromium(&bin, &url(&playing, ""), &["--virtual-time-budget=800", "--dump-dom"]);
    assert!(dom.contains(r#"aria-pressed="true">Pause</button>"#), "the page plays when opened");
    let cell: usize = dom.split(r#"data-cell=""#).nth(1).and_then(|r| r.split('"').next()).unwrap().parse().unwrap();
    assert!(cell < counts[0], "on the first row: cell {cell}");
    let shot = Path::new(env!("CARGO_TARGET_TMPDIR")).join("browser").join("five_bar_grid.png");
    std::fs::create_dir_all(shot.parent().unwrap()).unwrap();
    run_chromium(&bin, &url(&path, "cell=15:0"), &[&format!("--screenshot={}", shot.display())]);
    assert!(std::fs::metadata(&shot).is_ok_and(|m| m.len() > 1000));
    eprintln!("five_bar_grid: screenshot {}", shot.display());
}
