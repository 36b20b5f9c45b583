//! `kinloop animate --cam` end to end: the shipped dwell cam's animation read back as SVG, and
//! the cam drawn checked against what a cam must do in every frame, independently of how it was
//! found: a roller follower's roller touches the turning profile (the distance from the roller's
//! centre to the profile is the roller's radius) without cutting into it, and a flat face
//! touches it with the whole cam on one side. A cam drawn turning the wrong way, from the wrong
//! start or about the wrong point fails both by tens of pixels.
//!
//! Tolerances, in pixels: the SVG writes positions and angles to a tenth (a tenth of a degree at
//! the profile's 160 pixels is 0.28 px; a tenth of a pixel at each end of a distance), and the
//! profile's 721 corners lie on the curve, so that a chord runs inside it by under 0.01 px here:
//! 0.5 px, against a roller of 24 px.

mod common;

use common::{kinloop, shipped};
use std::path::PathBuf;

/// A file in a directory of this test's own under the target directory.
fn out(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("animate_cam");
    std::fs::create_dir_all(&dir).expect("a directory for the outputs");
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

/// A rigid outline of the SVG: its corners in its own frame, and per frame where its frame is
/// (translation) and how far it has turned (degrees, SVG's sense: clockwise on the screen).
struct Outline {
    corners: Vec<[f64; 2]>,
    at: Vec<[f64; 2]>,
    turned: Vec<f64>,
}

impl Outline {
    /// The corners in the picture at frame `k`: SVG's `translate(at) rotate(turned)`.
    fn placed(&self, k: usize) -> Vec<[f64; 2]> {
        let (s, c) = self.turned[k].to_radians().sin_cos();
        let [x0, y0] = self.at[k];
        self.corners.iter().map(|&[x, y]| [x0 + c * x - s * y, y0 + s * x + c * y]).collect()
    }
}

/// A transform's values per frame: its `animateTransform`'s, or its own (one frame) repeated.
fn values(g: roxmltree::Node, frames: usize) -> Vec<Vec<f64>> {
    let numbers =
        |v: &str| v.split([' ', ',']).filter(|t| !t.is_empty()).map(|t| t.parse().expect("a number")).collect();
    match g.children().find(|n| n.has_tag_name("animateTransform")) {
        Some(a) => a.attribute("values").expect("values").split(';').map(numbers).collect(),
        None => {
            let t = g.attribute("transform").expect("a transform");
            let inner = &t[t.find('(').expect("(") + 1..t.find(')').expect(")")];
            vec![numbers(inner); frames]
        }
    }
}

/// The SVG's outlines (`<polygon>` in a translated, then turned group) over `frames` frames.
fn outlines(svg: &str, frames: usize) -> Vec<Outline> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    doc.descendants()
        .filter(|n| n.has_tag_name("polygon"))
        .filter_map(|p| {
            let turn = p.parent_element()?;
            let shift = turn.parent_element()?;
            let corners = p
                .attribute("points")?
                .split(' ')
                .map(|c| {
                    let (x, y) = c.split_once(',').expect("x,y");
                    [x.parse().expect("x"), y.parse().expect("y")]
                })
                .collect();
            let at = values(shift, frames).into_iter().map(|v| [v[0], v[1]]).collect();
            let turned = values(turn, frames).into_iter().map(|v| v[0]).collect();
            Some(Outline { corners, at, turned })
        })
        .collect()
}

/// The distance from `p` to the closed polygon `corners`, negative inside it.
fn signed_distance(p: [f64; 2], corners: &[[f64; 2]]) -> f64 {
    let mut d = f64::INFINITY;
    let mut inside = false;
    for k in 0..corners.len() {
        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
        let (ab, ap) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
        let t = ((ap[0] * ab[0] + ap[1] * ab[1]) / (ab[0] * ab[0] + ab[1] * ab[1])).clamp(0.0, 1.0);
        d = d.min((ap[0] - t * ab[0]).hypot(ap[1] - t * ab[1]));
        if (a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) {
            inside = !inside;
        }
    }
    if inside { -d } else { d }
}

/// Runs `animate` on the dwell cam over a turn in 91 samples and frames, with `extra`.
fn dwell_cam_svg(name: &str, extra: &[&str]) -> (String, String) {
    let path = out(name);
    let p = path.display().to_string();
    let file = shipped("dwell_cam.kl");
    let args = ["animate", &file, "--from", "0", "--to", "360", "--deg", "--samples", "91", "--frames", "91"];
    let o = kinloop(&args.into_iter().chain(extra.iter().copied()).chain(["--out", &p]).collect::<Vec<_>>());
    let stderr = String::from_utf8_lossy(&o.stderr).to_string();
    assert!(o.status.success(), "exit {:?}: {stderr}", o.status.code());
    (std::fs::read_to_string(&path).expect("the SVG is written"), stderr)
}

#[test]
fn the_roller_touches_the_turning_cam_in_every_frame() {
    for (sense, turn) in [(None, -360.0), (Some("--clockwise"), 360.0)] {
        let name = format!("roller{}.svg", sense.unwrap_or(""));
        let args: Vec<&str> =
            ["--cam", "follower", "--guide", "0,1", "--roller", "10"].into_iter().chain(sense).collect();
        let (svg, stderr) = dwell_cam_svg(&name, &args);
        assert!(stderr.contains("no undercut with a roller of radius 10"), "the cam's checks: {stderr}");
        let outlines = outlines(&svg, 91);
        // The cam: about a fixed pivot, turning a whole turn; the roller: a circle, moving.
        let cam = outlines.iter().find(|o| o.at.iter().all(|a| *a == o.at[0])).expect("the cam's outline");
        let roller = outlines.iter().find(|o| o.at.iter().any(|a| *a != o.at[0])).expect("the roller's outline");
        assert_eq!((cam.at.len(), cam.turned.len(), roller.at.len()), (91, 91, 91));
        // Counter-clockwise on the page is negative in SVG's y-down rotation.
        assert_eq!((cam.turned[0], cam.turned[90]), (0.0, turn), "{sense:?}");
        let radius = roller.corners.iter().map(|c| c[0].hypot(c[1])).sum::<f64>() / roller.corners.len() as f64;
        assert!(radius > 20.0, "the roller is {radius} px: too small to judge a tenth of a pixel by");
        for k in 0..91 {
            let gap = signed_distance(roller.at[k], &cam.placed(k)) - radius;
            assert!(gap.abs() <= 0.5, "{sense:?}, frame {k}: the roller is {gap} px off the cam");
        }
    }
}

/// A flat face, translating with the follower pin or rocking with the rocker's pin about the
/// rocker's pivot (at a distance from it): in every frame the cam lies on one side of the face's
/// line and reaches it.
#[test]
fn the_flat_face_touches_the_turning_cam_in_every_frame() {
    let cases: [&[&str]; 2] = [
        &["--cam", "follower", "--guide", "0,1", "--flat"],
        &["--cam", "rocker_pin", "--rocker", "-40,140", "--flat", "--face-offset", "5"],
    ];
    for (k, extra) in cases.into_iter().enumerate() {
        let (svg, stderr) = dwell_cam_svg(&format!("flat{k}.svg"), extra);
        assert!(stderr.contains("the profile is convex at every sample"), "the cam's checks: {stderr}");
        let outlines = outlines(&svg, 91);
        // The cam about its fixed pivot; the face's plate moving with the follower.
        let cam = outlines.iter().find(|o| o.at.iter().all(|a| *a == o.at[0])).expect("the cam's outline");
        let plate = outlines.iter().find(|o| o.at.iter().any(|a| *a != o.at[0])).expect("the face's plate");
        assert_eq!((outlines.len(), plate.corners.len()), (2, 4), "the cam and the plate, no roller");
        for f in 0..91 {
            // The face: the plate's first edge.
            let [a, b] = [plate.placed(f)[0], plate.placed(f)[1]];
            let length = (b[0] - a[0]).hypot(b[1] - a[1]);
            assert!(length > 50.0, "{extra:?}, frame {f}: the face from {a:?} to {b:?} is {length} px long");
            let side = |c: &[f64; 2]| ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / length;
            let d: Vec<f64> = cam.placed(f).iter().map(side).collect();
            let (lo, hi) = d.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
            // One side: the extreme corner of that side on the line (so none beyond it), and the
            // plate on the other.
            assert!(lo.abs().min(hi.abs()) <= 0.5, "{extra:?}, frame {f}: the cam from {lo} to {hi} px");
            let plate_side: f64 = plate.placed(f)[2..].iter().map(side).sum();
            assert!(plate_side * (lo + hi) < 0.0, "{extra:?}, frame {f}: the plate on the cam's side");
        }
    }
}

#[test]
fn follower_options_without_a_cam_and_a_cam_of_no_one_input_are_usage_errors() {
    let path = out("refused.svg");
    let p = path.display().to_string();
    let (cam, five_bar) = (shipped("dwell_cam.kl"), shipped("five_bar.kl"));
    let cases: [(&[&str], &str); 6] = [
        (&["animate", &cam, "--from", "0", "--to", "6", "--roller", "10"], "--roller describes the follower of a cam"),
        (
            &["animate", &cam, "--from", "0", "--to", "6", "--cam", "follower", "--guide", "1,0"],
            "does not move along this guide: it leaves the guide's line by 20 over a stroke of 20",
        ),
        (
            &["animate", &cam, "--from", "0", "--to", "6", "--cam", "follower", "--rocker", "0,60"],
            "--rocker 0,60 is at the follower's point `follower` at sample 0",
        ),
        (
            &["animate", &cam, "--from", "0", "--to", "6", "--cam", "rod"],
            "--cam rod: DwellCamRocker has no point of that name",
        ),
        (
            &["animate", &five_bar, "--from", "0,0", "--to", "1,1", "--cam", "p", "--guide", "0,1"],
            "must have one input, an angle",
        ),
        (
            &["animate", &five_bar, "--grid", "--from", "0,0", "--to", "1,1", "--cam", "p", "--guide", "0,1"],
            "not a --grid",
        ),
    ];
    for (args, says) in cases {
        let o = kinloop(&args.iter().copied().chain(["--out", &p]).collect::<Vec<_>>());
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        assert!(!path.exists(), "{args:?} left {}", path.display());
    }
}

/// A cam whose drawing reaches beyond the largest `f64` (a pivot, or a rocking face's pivot,
/// near it: huge but finite) is a usage error naming the options and the bound, before the
/// cam's report; it was the drawing's internal "extent of item 5 (outline) is not finite at
/// pose 0", exit code 1. A pivot far out but within the bound is drawn.
#[test]
fn a_cam_too_far_out_to_draw_is_a_usage_error_naming_the_bound() {
    let path = out("too_far.svg");
    let p = path.display().to_string();
    let cam = shipped("dwell_cam.kl");
    let base = ["animate", &cam, "--from", "0", "--to", "360", "--deg", "--cam", "follower", "--out", &p];
    let refused: [(&[&str], &str); 3] = [
        (&["--guide", "0,1", "--roller", "10", "--pivot", "1e308,0"], "--guide 0,1, --roller 10, --pivot 1e308,0"),
        (&["--guide", "0,1", "--flat", "0", "--pivot", "0,-9e307"], "--guide 0,1, --flat 0, --pivot 0,-9e307"),
        (&["--rocker", "1e308,0", "--flat", "0"], "--rocker 1e308,0, --flat 0, the cam's pivot 0,0"),
    ];
    for (extra, options) in refused {
        let o = kinloop(&[&base[..], extra].concat());
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {stderr}");
        let says = format!("the cam of the follower given ({options}) cannot be drawn");
        assert!(stderr.contains(&says) && stderr.contains("1.7976931348623157e308"), "{extra:?}: {stderr}");
        assert!(!stderr.contains("extent") && !stderr.contains("cam: "), "{extra:?}: {stderr}");
        assert!(!path.exists(), "{extra:?} left {}", path.display());
    }
    let o = kinloop(&[&base[..], &["--guide", "0,1", "--roller", "10", "--pivot", "1e200,0"]].concat());
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::remove_file(&path).ok();
}

/// A range the animation refuses is refused before the cam is found: the cam's report (its
/// largest pressure angle, its sharpest point, its undercut) was written first, then the error,
/// as though the animation had gone ahead.
#[test]
fn a_refused_range_is_refused_before_the_cams_report() {
    let path = out("refused_range.svg");
    let p = path.display().to_string();
    let cam = shipped("dwell_cam.kl");
    let args =
        ["animate", &cam, "--from", "0", "--to", "0", "--deg", "--cam", "follower", "--guide", "0,1", "--out", &p];
    let o = kinloop(&args);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("give --to different from --from"), "{stderr}");
    assert!(!stderr.contains("cam:"), "{stderr}");
    assert!(!path.exists());
}

/// The notes written under an SVG's picture (`note: ...`), each read across the lines it is
/// wrapped in to the picture's width (broken at spaces).
fn notes(svg: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    let mut notes: Vec<String> = Vec::new();
    for line in doc.descendants().filter(|n| n.attribute("class") == Some("note")).filter_map(|n| n.text()) {
        match notes.last_mut() {
            Some(note) if !line.starts_with("note: ") => *note = format!("{note} {line}"),
            _ => notes.push(line.to_string()),
        }
    }
    notes
}

/// A roller larger than the pitch curve's curvature: the profile drawn crosses itself, and the
/// drawing says so in its notes, as standard error does; a roller that fits has no such note.
#[test]
fn an_undercut_cam_is_marked_in_the_drawing() {
    let (svg, stderr) = dwell_cam_svg("undercut.svg", &["--cam", "follower", "--guide", "0,1", "--roller", "100"]);
    assert!(stderr.contains("cam: UNDERCUT at"), "{stderr}");
    let written = notes(&svg);
    assert!(
        written.iter().any(|n| n.starts_with("note: UNDERCUT at ") && n.contains("the profile crosses itself")),
        "{written:?}"
    );
    let (svg, _) = dwell_cam_svg("fits.svg", &["--cam", "follower", "--guide", "0,1", "--roller", "10"]);
    let written = notes(&svg);
    assert!(written.iter().all(|n| !n.contains("UNDERCUT")) && !written.is_empty(), "{written:?}");
}

/// A rise of half a degree, no sample of the drawn cam in its undercut: the drawing's note says
/// so, located between the samples (at 30.4885 degrees, as `cam_extremes` and the summary on
/// standard error put it; `cli/tests/cam.rs` checks the place against the law by hand), where
/// the drawing showed the cam as if it worked.
#[test]
fn an_undercut_between_the_samples_is_marked_in_the_drawing() {
    let args = ["--cam", "follower", "--guide", "0,1", "--roller", "10", "--params", "rise=0.00872665"];
    let (svg, stderr) = dwell_cam_svg("undercut_between.svg", &args);
    assert!(stderr.contains("cam: UNDERCUT between the samples, at 30.4885"), "{stderr}");
    let written = notes(&svg);
    let between = "note: UNDERCUT between the samples, at 30.4885";
    assert!(written.iter().any(|n| n.starts_with(between) && n.contains("the profile crosses itself")), "{written:?}");
}

/// A three-lobed cam (`s = h / 2 (1 - cos 3 phi)`) under a roller of 30: the pitch curve's
/// radius of curvature is 24 at 60, 180 and 300 degrees and about 46 between (polar formula
/// `(r^2 + r'^2)^(3/2) / (r^2 + 2 r'^2 - r r'')`, `r = 40 + s`), so it is undercut in three
/// stretches apart, and the drawing's note lists each (it said "44° to 316°", the whole turn
/// but the ends). The roller's radius is written short in any unit (`1e-200` was written with
/// all its 200 digits, widening the picture to hold them).
#[test]
fn an_undercut_in_stretches_is_noted_stretch_by_stretch_in_any_unit() {
    let decl = out("three_lobes.kl");
    std::fs::write(
        &decl,
        "pub struct ThreeLobes {\n    params rb = 40, h = 20, e = 0;\n    input phi;\n    \
         let s = h / 2 * (1 - cos(3 * phi));\n    point follower = (e, rb + s);\n}\n",
    )
    .expect("the declaration is written");
    let decl = decl.display().to_string();
    let svg = |name: &str, extra: &[&str]| {
        let path = out(name);
        let p = path.display().to_string();
        let args = ["animate", &decl, "--from", "0", "--to", "360", "--deg", "--cam", "follower", "--guide", "0,1"];
        let o = kinloop(&args.into_iter().chain(extra.iter().copied()).chain(["--out", &p]).collect::<Vec<_>>());
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(&path).expect("the SVG is written")
    };
    let written = notes(&svg("three_lobes.svg", &["--roller", "30"]));
    assert!(
        written.iter().any(|n| n.starts_with("note: UNDERCUT at 195 samples (44° to 76°, 164° to 196°, 284° to 316°)")),
        "{written:?}"
    );
    let tiny = svg("three_lobes_tiny.svg", &["--roller", "1e-200", "--params", "rb=4e-200,h=2e-200,e=0"]);
    let written = notes(&tiny);
    assert!(written.iter().any(|n| n.contains("roller of radius 1e-200,")), "{written:?}");
    let width =
        |s: &str| roxmltree::Document::parse(s).expect("SVG").root_element().attribute("width").map(str::to_string);
    assert_eq!(width(&tiny), width(&svg("three_lobes_mm.svg", &["--roller", "10"])));
}
