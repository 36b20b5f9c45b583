//! `kinloop animate` end to end: the built binary on the shipped `.kl` files, its SVG read back
//! as XML (frames counted, the crank's drawn angle against the input it was swept through, a
//! joint's drawn track and a limit position against their constructions), its HTML page's
//! structure, and its exit codes.

mod common;

use common::{kinloop, shipped};
use std::path::{Path, PathBuf};
use std::process::Output;

/// A file in a directory of this test's own under the target directory.
fn out(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("animate");
    std::fs::create_dir_all(&dir).expect("a directory for the outputs");
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

fn ok(o: &Output) {
    assert!(o.status.success(), "exit {:?}: {}", o.status.code(), String::from_utf8_lossy(&o.stderr));
}

const FOUR_BAR: &str = "a=1,b=3,c=2.5,d=3.2";

/// The `points` animations of the SVG: per element, the frames, each a list of pixels.
fn point_animations(svg: &str) -> Vec<Vec<Vec<[f64; 2]>>> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    doc.descendants()
        .filter(|n| n.has_tag_name("animate") && n.attribute("attributeName") == Some("points"))
        .map(|n| {
            let values = n.attribute("values").expect("values");
            values
                .split(';')
                .map(|frame| {
                    frame
                        .split(' ')
                        .map(|p| {
                            let (x, y) = p.split_once(',').expect("x,y");
                            [x.parse().expect("x"), y.parse().expect("y")]
                        })
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// Joint C of the four-bar `a, b, c, d` (crank `a` at the origin at `phi`, coupler `b`, rocker
/// `c` pivoted at `(d, 0)`) where the circles (B, b) and (D, c) meet, on the left of B -> D: the
/// assembly mode of the declaration's guess (C above the frame at `phi = 0`).
fn joint_c([a, b, c, d]: [f64; 4], phi: f64) -> [f64; 2] {
    let (bx, by) = (a * phi.cos(), a * phi.sin());
    let (ux, uy) = (d - bx, -by);
    let dist = ux.hypot(uy);
    let along = (b * b - c * c + dist * dist) / (2.0 * dist);
    let h = (b * b - along * along).sqrt();
    [bx + (along * ux - h * uy) / dist, by + (along * uy + h * ux) / dist]
}

/// A whole turn of the four-bar's crank in 37 samples: an SVG of 37 key frames, in which the
/// crank (a bar from a fixed pixel) turns through the swept angles: at frame k its angle from
/// the pivot is 10 k degrees, to the rounding of pixels written to a tenth. The coupler's and
/// rocker's joint C is drawn where the construction puts it ([`joint_c`]), mapped to pixels by
/// the picture's scale read from the crank's drawn length and its pivot's pixel.
#[test]
fn an_svg_animation_of_a_turn() {
    let path = out("four_bar.svg");
    let p = path.display().to_string();
    let o = kinloop(
        &["animate", &shipped("four_bar.kl"), "--from", "0", "--to", "360", "--deg", "--samples", "37"]
            .into_iter()
            .chain(["--params", FOUR_BAR, "--out", &p])
            .collect::<Vec<_>>(),
    );
    ok(&o);
    let svg = std::fs::read_to_string(&path).expect("the SVG is written");
    assert!(!svg.contains("NaN"));
    let anims = point_animations(&svg);
    assert!(!anims.is_empty());
    assert!(anims.iter().all(|a| a.len() == 37), "frames: {:?}", anims.iter().map(Vec::len).collect::<Vec<_>>());
    // The crank: two points, the first fixed, the second at a constant distance, turning with
    // the input. Its length is 1 of the mechanism's 4.2-wide span: tens of pixels, so a tenth
    // of a pixel at each end is under 0.01 rad.
    let crank = anims.iter().find(|a| {
        a.iter().all(|f| f.len() == 2 && f[0] == a[0][0])
            && a.iter().enumerate().all(|(k, f)| {
                let angle = (-(f[1][1] - f[0][1])).atan2(f[1][0] - f[0][0]);
                let want = (10.0 * k as f64).to_radians();
                let d = (angle - want).rem_euclid(std::f64::consts::TAU);
                d.min(std::f64::consts::TAU - d) < 0.01
            })
    });
    let crank = crank.unwrap_or_else(|| panic!("no bar turns with the input: {anims:?}"));
    // The picture's map: `px = o + s (x, -y)` (Y up in the mechanism, down in the picture), `o`
    // the crank's pivot's pixel and `s` pixels per unit, the crank's drawn length over `a = 1`.
    let o = crank[0][0];
    let s = crank.iter().map(|f| (f[1][0] - f[0][0]).hypot(f[1][1] - f[0][1])).sum::<f64>() / crank.len() as f64;
    assert!(s > 50.0, "{s} pixels per unit: the mechanism spans most of a picture 480 pixels wide");
    // Each coordinate is written to a tenth of a pixel (within 0.05): the crank's length within
    // 0.15 pixel, so `s` within 0.15 pixel per unit, which moves C (at most `a + b = 4` units
    // from the pivot) by 0.6 pixel; with the roundings of C's and the pivot's own pixels,
    // within 0.75 pixel. One frame's step of the crank moves C by tens of pixels, the other
    // assembly mode by hundreds.
    let tracks = |f: &[Vec<[f64; 2]>], j: usize| {
        f.iter().enumerate().all(|(k, frame)| {
            let [cx, cy] = joint_c([1.0, 3.0, 2.5, 3.2], (10.0 * k as f64).to_radians());
            let want = [o[0] + s * cx, o[1] - s * cy];
            frame.get(j).is_some_and(|p| (p[0] - want[0]).hypot(p[1] - want[1]) <= 0.75)
        })
    };
    let joint = anims.iter().filter(|a| (0..a[0].len()).any(|j| tracks(a, j))).count();
    // The coupler's bar B-C and the rocker's C-D.
    assert_eq!(joint, 2, "C drawn off its construction: {anims:?}");
}

/// The rhombic drive as an interactive page: one document, its figure well-formed SVG, a slider
/// over every sample, the readout asked for.
#[test]
fn an_interactive_page() {
    let path = out("rhombic.html");
    let p = path.display().to_string();
    let o = kinloop(&[
        "animate",
        &shipped("rhombic_drive.kl"),
        "--from",
        "0",
        "--to",
        "6.283185307179586",
        "--samples",
        "61",
        "--show",
        "x_c",
        "--out",
        &p,
    ]);
    ok(&o);
    let page = std::fs::read_to_string(&path).expect("the page is written");
    assert!(page.starts_with("<!DOCTYPE html>") && page.trim_end().ends_with("</html>"));
    assert_eq!(page.matches("<html").count(), 1);
    assert!(page.contains(r#"id="kl-slider" type="range" min="0" max="60""#), "61 poses");
    assert!(page.contains(r#"<th scope="row">x_c</th>"#));
    assert!(!page.contains("NaN"));
    let start = page.find("<svg").expect("a figure");
    let end = page[start..].find("</svg>").expect("closed") + start + "</svg>".len();
    let doc = roxmltree::Document::parse(&page[start..end]).expect("the figure is well-formed SVG");
    assert_eq!(doc.root_element().attribute("id"), Some("kl-drawing"));
}

/// `--format` names the format whatever the extension; a rocker stopping at its limit position
/// is drawn there and plays back and forth (2 k - 1 key frames for k poses), exit 0. The limit
/// is where the law of cosines puts it: the crank's tip B and the rocker's pivot D are
/// `|BD|^2 = a^2 + d^2 - 2 a d cos(phi)` apart, which grows with `phi` from `|d - a| = 1.7` at 0
/// to `d + a = 4.7` at 180 degrees, and the loop closes while `|b - c| = 2 <= |BD| <= b + c = 4`:
/// from 27.8 to 111.4 degrees. Swept up from 70 degrees, the crank stops where coupler and
/// rocker lie stretched in line, `|BD| = b + c`, at `acos((a^2 + d^2 - (b + c)^2) / (2 a d))`.
#[test]
fn format_option_and_a_stop_at_a_limit_position() {
    let path = out("rocker.drawing");
    let p = path.display().to_string();
    let params = "a=1.5,b=3,c=1,d=3.2";
    let args = ["animate", &shipped("four_bar.kl"), "--from", "70", "--to", "430", "--deg", "--samples", "19"];
    let o = kinloop(&args.into_iter().chain(["--params", params, "--out", &p, "--format", "svg"]).collect::<Vec<_>>());
    ok(&o);
    let stderr = String::from_utf8_lossy(&o.stderr);
    let at = stderr.split_once("stopped at a limit position at phi = ").and_then(|(_, rest)| rest.split_once(" deg"));
    let at: f64 = at.and_then(|(v, _)| v.parse().ok()).unwrap_or_else(|| panic!("no limit's input: {stderr}"));
    let (a, b, c, d): (f64, f64, f64, f64) = (1.5, 3.0, 1.0, 3.2);
    let limit = ((a * a + d * d - (b + c).powi(2)) / (2.0 * a * d)).acos().to_degrees();
    // An event is located to 1e-9 rad (the tests' `tol::LOCATED`): 5.7e-8 degrees.
    assert!((at - limit).abs() <= 1e-9f64.to_degrees(), "stopped at {at} deg, the limit is at {limit} deg");
    let anims = point_animations(&std::fs::read_to_string(&path).expect("written"));
    let k = anims[0].len();
    assert!(k % 2 == 1 && k > 3 && k < 2 * 19 - 1, "{k} key frames");
    assert!(anims.iter().all(|a| a.len() == k && a[0] == a[k - 1]), "back and forth");
}

fn fails_without_output(args: &[&str], out: &Path, code: i32, says: &str) {
    let o = kinloop(args);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(code), "{args:?}: {stderr}");
    assert!(stderr.contains(says), "{args:?}: {stderr}");
    assert!(!out.exists(), "{args:?} left {}", out.display());
}

#[test]
fn exit_codes() {
    let fb = shipped("four_bar.kl");
    let path = out("bad.svg");
    let p = path.display().to_string();
    let with = |extra: &[&'static str]| {
        let mut a = vec!["animate", fb.as_str(), "--from", "0", "--to", "1"];
        a.extend_from_slice(extra);
        a
    };
    let mut a = with(&["--params", FOUR_BAR, "--out"]);
    a.push(&p);
    // Usage: the format of an unknown extension, equal ends, a column that is not one.
    let txt = out("bad.txt");
    let t = txt.display().to_string();
    let mut b = with(&["--params", FOUR_BAR, "--out"]);
    b.push(&t);
    fails_without_output(&b, &txt, 2, "cannot tell the format");
    let mut c = vec!["animate", fb.as_str(), "--from", "1", "--to", "1", "--params", FOUR_BAR, "--out"];
    c.push(&p);
    fails_without_output(&c, &path, 2, "give --to different from --from");
    let mut d = a.clone();
    d.extend(["--format", "html", "--show", "delta"]);
    fails_without_output(&d, &path, 2, "delta");
    // A column shown twice would be two equal readouts and charts: named once, as
    // `extremes --columns` asks.
    let mut d = a.clone();
    d.extend(["--format", "html", "--show", "beta", "--show", "gamma", "--show", "beta"]);
    fails_without_output(&d, &path, 2, "--show beta is given twice");
    // Parameters without a value: a usage error (2).
    let mut e = with(&["--out"]);
    e.push(&p);
    fails_without_output(&e, &path, 2, "parameters `a`, `b`, `c`, `d` have no value");
    // No assembly at the start (|AD| shorter than |b - c|): 1.
    let mut f = with(&["--params", "a=1.5,b=3,c=1,d=3.2", "--out"]);
    f.push(&p);
    fails_without_output(&f, &path, 1, "FourBar");
    // The declaration cannot be read (66), the output cannot be created (73).
    let missing = out("missing.kl").display().to_string();
    fails_without_output(&["animate", &missing, "--from", "0", "--to", "1", "--out", &p], &path, 66, "cannot read");
    let nowhere = out("no-such-dir").join("x.svg");
    let n = nowhere.display().to_string();
    let mut g = with(&["--params", FOUR_BAR, "--out"]);
    g.push(&n);
    fails_without_output(&g, &nowhere, 73, "cannot create");
    // A grid of no value of an input says which and which option.
    let five = shipped("five_bar.kl");
    let page = out("bad.html");
    let h = page.display().to_string();
    for (samples, input) in [("0", "th1"), ("3,0", "th2")] {
        let args = ["animate", &five, "--grid", "--samples", samples, "--from", "0,0", "--to", "1,1", "--out", &h];
        fails_without_output(
            &args,
            &page,
            2,
            &format!("--samples: a grid needs at least one value of input `{input}`"),
        );
    }
    // And the same arguments with a good output succeed.
    ok(&kinloop(&a));
    assert!(path.exists());
}

/// `--grid`: the five-bar over a grid of its two inputs, 9 x 7 values, is the library's page of
/// the same model and grid (`Model::grid`, `html_grid_of`) byte for byte, with one slider per
/// input.
#[test]
fn a_grid_page_of_two_inputs_is_the_librarys() {
    let path = out("five_bar.html");
    let p = path.display().to_string();
    let file = shipped("five_bar.kl");
    let args = ["animate", &file, "--grid", "--from", "0,0.4", "--to", "3,3", "--samples", "9,7", "--show", "pc.x"];
    ok(&kinloop(&args.into_iter().chain(["--out", &p]).collect::<Vec<_>>()));
    let page = std::fs::read_to_string(&path).expect("the page is written");

    let text = std::fs::read_to_string(&file).expect("shipped file");
    let mut m = kinloop_model::Model::read("five_bar.kl", &text).expect("valid");
    let (from, to) = ([0.0, 0.4], [3.0, 3.0]);
    let mut guess = vec![0.0; 2];
    m.guess(&from, &mut guess).expect("guess");
    let grid = m.grid(&from, &to, &[9, 7], &guess).expect("grid");
    assert_eq!(grid.cells.len(), 63);
    let drawing = m.drawing().into_drawing();
    let config = kinloop_viz::html::HtmlConfig::new("FiveBar").show("pc.x");
    let library = kinloop_viz::html::html_grid_of(&m, &drawing, &grid, &config).expect("page");
    assert!(page == library, "the command's page differs from the library's");
    assert!(page.contains(r#"id="kl-slider-0""#) && page.contains(r#"id="kl-slider-1""#));
    assert!(page.contains(r#"<th scope="row">pc.x</th>"#) && !page.contains("NaN"));

    // One count for both inputs: 5 x 5 cells, a page of its own.
    let path5 = out("five_bar_5.html");
    let p5 = path5.display().to_string();
    let args = ["animate", &file, "--grid", "--from", "0,0.4", "--to", "3,3", "--samples", "5", "--out", &p5];
    ok(&kinloop(&args));
    let grid = m.grid(&from, &to, &[5, 5], &guess).expect("grid");
    let library = kinloop_viz::html::html_grid_of(&m, &drawing, &grid, &kinloop_viz::html::HtmlConfig::new("FiveBar"));
    assert!(std::fs::read_to_string(&path5).expect("written") == library.expect("page"));
}

/// `--grid` over a range no sweep follows is a usage error naming the input, whether a sweep
/// between two cells could follow it (a wide range: each cell a sweep of up to a million turns)
/// or not (each cell read as unreachable).
#[test]
fn a_grid_over_a_range_no_sweep_follows_is_a_usage_error() {
    let path = out("five_bar_far.html");
    let p = path.display().to_string();
    let file = shipped("five_bar.kl");
    for to in ["1e7,3", "1e12,3"] {
        let args = ["animate", &file, "--grid", "--from", "0,0.4", "--to", to, "--samples", "5", "--out", &p];
        fails_without_output(&args, &path, 2, "the grid sweeps input `th1` over its range 0 to");
    }
    // In degrees as given with --deg, not in the radians the grid is computed in.
    let args =
        ["animate", &file, "--grid", "--deg", "--from", "0,20", "--to", "2.5e8,170", "--samples", "5", "--out", &p];
    fails_without_output(&args, &path, 2, "the grid sweeps input `th1` over its range 0 to 250000000 (degrees)");
    // Farther, degrees no longer convert to radians to a solve's precision: refused as given.
    let args =
        ["animate", &file, "--grid", "--deg", "--from", "0,20", "--to", "1e14,170", "--samples", "5", "--out", &p];
    fails_without_output(
        &args,
        &path,
        2,
        "--to 1e14,170: 100000000000000 degrees are too many turns out to convert to radians",
    );
}

/// A grid input with equal ends and several values (the default count too), or one value and
/// different ends, is a usage error naming the input and the options that fix it; the grid
/// fixed in that input as the message says is drawn.
#[test]
fn a_grid_input_whose_ends_and_count_disagree_says_what_to_write() {
    let file = shipped("five_bar.kl");
    let path = out("grid_ends.html");
    let p = path.display().to_string();
    let head = ["animate", file.as_str(), "--grid", "--out", p.as_str()];
    let equal_ends = ["--from", "0,0", "--to", "0,1"];
    fails_without_output(
        &[&head[..], &equal_ends[..]].concat(),
        &path,
        2,
        "--from and --to give input `th1` the same value (0), where the grid takes 26 values of it: give --to \
         another value of `th1`, or --samples 1,26 for a grid fixed in `th1`",
    );
    fails_without_output(
        &[&head[..], &["--deg", "--samples", "4,5", "--from", "0,30", "--to", "90,30"]].concat(),
        &path,
        2,
        "the same value (30), where the grid takes 5 values of it: give --to another value of `th2`, or \
         --samples 4,1 for a grid fixed in `th2`",
    );
    fails_without_output(
        &[&head[..], &["--samples", "1,5", "--from", "0,0", "--to", "1,1"]].concat(),
        &path,
        2,
        "--samples 1,5 gives input `th1` one value, and --from and --to a range of it (0 to 1): give --samples \
         2,5 for values over the range, or --to 0 in `th1` for a grid fixed there",
    );
    ok(&kinloop(&[&head[..], &equal_ends[..], &["--samples", "1,5"]].concat()));
    assert!(path.exists());
}

/// A grid that cannot start (the five-bar's base, 5, longer than its other four links, 4 in all,
/// closes nowhere) says where in degrees with `--deg`, the inputs as given: it said `th1 =
/// 1.5707963267948966` of the 90 typed, where an animation's sweep says 90.
#[test]
fn a_grid_that_cannot_start_names_its_inputs_in_degrees() {
    let path = out("five_bar_apart.html");
    let p = path.display().to_string();
    let file = shipped("five_bar.kl");
    let apart = ["--params", "a=1,b=1,c=1,d=5,e=1", "--deg", "--from", "90,45", "--to", "200,200", "--samples", "3"];
    let args = [&["animate", file.as_str(), "--grid", "--out", p.as_str()][..], &apart[..]].concat();
    fails_without_output(&args, &path, 1, "cannot be assembled in `FiveBar` at th1 = 90, th2 = 45 (");
    let stderr = String::from_utf8_lossy(&kinloop(&args).stderr).to_string();
    assert!(!stderr.contains("1.5707963267948966"), "{stderr}");
}

/// A three-input mechanism for the default grid: a two-link arm on a slider, its tip `(x, y)`.
const ARM_ON_SLIDER: &str = "pub struct ArmOnSlider {
    params a = 1.0, b = 0.8;
    inputs s, th1, th2;
    unknowns x = 1.0, y = 0.5;
    loop tip: (s, 0) + a @ th1 + b @ th2 == (x, y);
    point p = (s, 0) + a @ th1;
}";

/// `kinloop animate --grid FILE --from .. --to .. [--frames F]` and the library's page of the
/// same model over the grid of `counts` values per input: byte for byte the same.
fn default_grid_is(file: &str, text: &str, from: &[f64], to: &[f64], frames: Option<&str>, counts: &[usize]) {
    let path = out(&format!("default_grid_{}_{}.html", counts.len(), frames.unwrap_or("all")));
    let p = path.display().to_string();
    let join = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    let (f, t) = (join(from), join(to));
    let mut args = vec!["animate", file, "--grid", "--from", &f, "--to", &t, "--out", &p];
    if let Some(frames) = frames {
        args.extend(["--frames", frames]);
    }
    ok(&kinloop(&args));
    let page = std::fs::read_to_string(&path).expect("the page is written");
    let mut m = kinloop_model::Model::read("grid.kl", text).expect("valid");
    let mut guess = vec![0.0; m.unknowns().len()];
    m.guess(from, &mut guess).expect("guess");
    let grid = m.grid(from, to, counts, &guess).expect("grid");
    let mut config = kinloop_viz::html::HtmlConfig::new(m.name());
    if let Some(frames) = frames {
        config = config.with_max_frames(frames.parse().expect("a count"));
    }
    let drawing = m.drawing().into_drawing();
    let library = kinloop_viz::html::html_grid_of(&m, &drawing, &grid, &config).expect("page");
    assert!(page == library, "the default grid of {} inputs is not {counts:?}", counts.len());
}

/// Without `--samples`, a grid has the most values per input that fit the page's poses
/// (`c^ni <= frames`, by hand: 26^2 = 676 <= 721 < 27^2; 10^2 = 100; 8^3 = 512 <= 721 < 9^3):
/// the plain command succeeds for two and three inputs and with `--frames 100`.
#[test]
fn the_default_grid_fits_the_page() {
    let five = shipped("five_bar.kl");
    let text = std::fs::read_to_string(&five).expect("shipped file");
    default_grid_is(&five, &text, &[0.0, 0.4], &[3.0, 3.0], None, &[26, 26]);
    default_grid_is(&five, &text, &[0.0, 0.4], &[3.0, 3.0], Some("100"), &[10, 10]);
    let arm = out("arm_on_slider.kl");
    std::fs::write(&arm, ARM_ON_SLIDER).expect("written");
    let arm = arm.display().to_string();
    default_grid_is(&arm, ARM_ON_SLIDER, &[0.0, 0.0, 0.5], &[1.0, 1.5, 2.0], None, &[8, 8, 8]);
}

/// Too many cells for the page is refused before any cell is solved: a five-bar that cannot be
/// assembled anywhere (links of 0.1 across a gap of more than 1) fails its solve (1) when the
/// grid fits, and is a usage error (2) about the cells when it does not.
#[test]
fn too_many_cells_is_refused_before_solving() {
    let path = out("too_many_cells.html");
    let p = path.display().to_string();
    let five = shipped("five_bar.kl");
    let args = |samples: &'static str| {
        let base = ["animate", five.as_str(), "--grid", "--from", "0,0.4", "--to", "3,3", "--params", "b=0.1,c=0.1"];
        base.into_iter().chain(["--samples", samples, "--out", p.as_str()]).collect::<Vec<&str>>()
    };
    fails_without_output(&args("5"), &path, 1, "FiveBar");
    fails_without_output(&args("30"), &path, 2, "a grid of 900 cells is more than the page's 721 poses");
    // Without --samples the default grid is the least, two values per input: the advice is
    // the frames it needs, not fewer --samples (which would be a grid of no range).
    let frames = ["animate", five.as_str(), "--grid", "--from", "0,0.4", "--to", "3,3", "--frames", "3", "--out", &p];
    fails_without_output(
        &frames,
        &path,
        2,
        "a grid of 4 cells is more than the page's 3 poses: give --frames 4 or more (the default grid has two values",
    );
}

/// The advice for too many cells works when followed: more `--frames` raise the page's bound,
/// never the 100,000 cells a grid holds, so past those the advice is fewer values (it said "more
/// --frames", and `--frames 160000` was then refused by the grid); within them it names the
/// frames that fit, and a grid given them is solved.
#[test]
fn too_many_cells_advice_works_when_followed() {
    let path = out("too_many_cells_advice.html");
    let p = path.display().to_string();
    let five = shipped("five_bar.kl");
    let args = |extra: &[&'static str]| {
        let base = ["animate", five.as_str(), "--grid", "--from", "0,0.4", "--to", "3,3", "--params", "b=0.1,c=0.1"];
        base.into_iter().chain(extra.iter().copied()).chain(["--out", p.as_str()]).collect::<Vec<&str>>()
    };
    let beyond = "a grid of 160000 cells is more than the 100000 cells a grid holds: give fewer values with --samples";
    fails_without_output(&args(&["--samples", "400"]), &path, 2, beyond);
    fails_without_output(&args(&["--samples", "400", "--frames", "160000"]), &path, 2, beyond);
    let within = "a grid of 900 cells is more than the page's 721 poses: fewer --samples, or --frames 900 or more";
    fails_without_output(&args(&["--samples", "30"]), &path, 2, within);
    // Followed, the grid fits: its cells are solved (and fail there, the five-bar's links
    // reaching nowhere: exit code 1, not a usage error).
    fails_without_output(&args(&["--samples", "30", "--frames", "900"]), &path, 1, "FiveBar");
}

/// `--grid` is for a mechanism of several inputs, drawn as a page; its counts are one per input
/// or one for all: anything else is a usage error (2) that writes nothing.
#[test]
fn grid_usage_errors() {
    let path = out("grid_bad.html");
    let p = path.display().to_string();
    let fb = shipped("four_bar.kl");
    let one_input = ["animate", &fb, "--grid", "--from", "0", "--to", "1", "--params", FOUR_BAR, "--out", &p];
    fails_without_output(&one_input, &path, 2, "--grid needs a mechanism of two inputs or more: `FourBar` has 1");
    let five = shipped("five_bar.kl");
    let svg = out("grid_bad.svg");
    let s = svg.display().to_string();
    let grid = |extra: &[&'static str], out: &str| {
        let mut a = vec!["animate", five.as_str(), "--grid", "--from", "0,0.4", "--to", "3,3"];
        a.extend_from_slice(extra);
        a.extend(["--out", out]);
        a.into_iter().map(str::to_string).collect::<Vec<String>>()
    };
    let run = |a: Vec<String>, file: &Path, says: &str| {
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        fails_without_output(&a, file, 2, says);
    };
    run(grid(&[], &s), &svg, "interactive page");
    run(grid(&["--samples", "9,7,5"], &p), &path, "one per input (2)");
    run(grid(&["--samples", "0"], &p), &path, "at least one value of input `th1`");
    // One value of an input from 0 to 3: the range would be ignored (the page showed `th1` at
    // 0 alone, with success).
    run(grid(&["--samples", "1,7"], &p), &path, "--samples 1,7 gives input `th1` one value, and --from and --to a");
    // More cells than the page's poses.
    run(grid(&["--samples", "30"], &p), &path, "--frames");
    // A count that is not one is named with what is wrong with it, not said to be one count too
    // many or too few (two were given for two inputs).
    run(grid(&["--samples", "9,-1"], &p), &path, "--samples 9,-1: `-1`: a count cannot be negative");
    run(grid(&["--samples", "9,2.5"], &p), &path, "--samples 9,2.5: `2.5`: a count is a whole number");
    run(
        grid(&["--samples", "99999999999999999999,2"], &p),
        &path,
        "`99999999999999999999`: 99999999999999999999 is beyond",
    );
    let huge = [
        "animate",
        &fb,
        "--from",
        "0",
        "--to",
        "1",
        "--samples",
        "99999999999999999999",
        "--params",
        FOUR_BAR,
        "--out",
        &p,
    ];
    fails_without_output(&huge, &path, 2, "--samples 99999999999999999999: 99999999999999999999 is beyond any count");
    // Without --grid, a list of counts is not a sample count.
    let list = ["animate", &fb, "--from", "0", "--to", "1", "--samples", "9,7", "--params", FOUR_BAR, "--out", &p];
    fails_without_output(&list, &path, 2, "--grid");
}

/// `--show` adds readouts and charts to the interactive page: with an SVG, which has neither,
/// it is a usage error saying to write a page, not ignored with success.
#[test]
fn show_with_an_svg_is_a_usage_error() {
    let fb = shipped("four_bar.kl");
    for (name, format) in [("show.svg", None), ("show.html", Some("svg"))] {
        let path = out(name);
        let p = path.display().to_string();
        let mut args = vec!["animate", fb.as_str(), "--from", "0", "--to", "1", "--params", FOUR_BAR, "--out", &p];
        if let Some(f) = format {
            args.extend(["--format", f]);
        }
        args.extend(["--show", "beta"]);
        fails_without_output(&args, &path, 2, "--show");
        fails_without_output(&args, &path, 2, ".html");
    }
}

/// Ten turns in the default 90 key frames are 40 degrees a frame: the crank would seem to jump
/// or turn backwards, and standard error says so; a turn says nothing.
#[test]
fn frames_far_apart_in_an_angle_are_noted() {
    let run = |to: &str, name: &str| {
        let path = out(name);
        let p = path.display().to_string();
        let args = ["animate", &shipped("four_bar.kl"), "--from", "0", "--to", to, "--deg", "--params", FOUR_BAR];
        let o = kinloop(&args.into_iter().chain(["--out", p.as_str()]).collect::<Vec<_>>());
        ok(&o);
        String::from_utf8_lossy(&o.stderr).to_string()
    };
    let stderr = run("3600", "ten_turns.svg");
    assert!(stderr.contains("note: the frames are 40.4 degrees of phi apart"), "{stderr}");
    assert!(!run("360", "one_turn.svg").contains("note:"));
}

/// A write that fails part way (here a file size limit of 10 KiB, its signal ignored so that the
/// write fails with `EFBIG`) leaves no SVG cut short behind: exit code 74 and no file.
#[cfg(target_os = "linux")]
#[test]
fn a_write_that_fails_part_way_leaves_no_file() {
    let svg = out("cut_short.svg");
    let path = svg.to_str().unwrap().to_string();
    let fb = shipped("four_bar.kl");
    let script = r#"trap '' XFSZ; ulimit -f 10; exec "$0" "$@""#;
    let o = std::process::Command::new("sh")
        .args(["-c", script, env!("CARGO_BIN_EXE_kinloop")])
        .args(["animate", &fb, "--from", "0", "--to", "360", "--deg", "--params", FOUR_BAR, "--out", &path])
        .output()
        .expect("sh runs");
    assert_eq!(o.status.code(), Some(74), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot write"));
    assert!(!svg.exists(), "a file of {:?} bytes was left", std::fs::metadata(&svg).map(|m| m.len()));
}

/// A sweep that stops at a limit position far out (a slider-driven linkage in units of 1e200)
/// names the input as `sweep` does, `2.9999999999999996e200`, not in 201 digits.
#[test]
fn a_stop_far_out_is_named_briefly() {
    let dir = out("far_out");
    std::fs::create_dir_all(&dir).expect("a directory");
    let file = dir.join("edger.kl");
    std::fs::write(
        &file,
        "pub struct Edger {\n    params l3 = 1e200, l5 = 2e200, alpha = 0.3;\n    input s;\n    unknowns phi1 = 0.5, phi3 = \
         2.0;\n    loop c: s @ phi1 + l3 @ phi3 == l5 @ alpha;\n}\n",
    )
    .expect("the declaration");
    let path = out("far_out.svg");
    let o = kinloop(&[
        "animate",
        file.to_str().unwrap(),
        "--from",
        "1.5e200",
        "--to",
        "3.5e200",
        "--out",
        path.to_str().unwrap(),
    ]);
    ok(&o);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("the sweep stopped at a limit position at s = 2.9999999999999996e200\n"), "{stderr}");
    assert!(!stderr.contains("0000000000"), "{stderr}");
}

/// A sweep that cannot start (the rhombus four-bar folded at 0, a change point) is the error
/// `sweep` writes with the notes `sweep` writes: its advice names the library's `trace_curve`,
/// the note `kinloop trace`, which animate left out.
#[test]
fn a_sweep_that_cannot_start_has_the_notes_of_sweep() {
    let path = out("singular_start.svg");
    let p = path.display().to_string();
    let common = ["--params", "a=1,b=1,c=1,d=1", "--from", "0", "--to", "1"];
    let file = shipped("four_bar.kl");
    let sweep = kinloop(&[&["sweep", file.as_str()][..], &common[..]].concat());
    let note = |o: &Output| {
        let stderr = String::from_utf8_lossy(&o.stderr).to_string();
        stderr.lines().filter(|l| l.starts_with("note: ")).map(str::to_string).collect::<Vec<_>>()
    };
    assert_eq!(sweep.status.code(), Some(1));
    assert!(note(&sweep).iter().any(|n| n.contains("`kinloop trace` traces the curve")), "{:?}", note(&sweep));
    let animate = kinloop(&[&["animate", file.as_str(), "--out", p.as_str()][..], &common[..]].concat());
    let stderr = String::from_utf8_lossy(&animate.stderr);
    assert_eq!(animate.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("error: the sweep failed: the sweep starts at a singular position"), "{stderr}");
    assert_eq!(note(&animate), note(&sweep), "{stderr}");
    assert!(!path.exists());
}

/// `--out -` writes the animation to standard output, the same bytes as to a file (it made a
/// file named `-`); without `--format` it says to give one.
#[test]
fn out_dash_is_standard_output() {
    let path = out("to_file.svg");
    let p = path.display().to_string();
    let fb = shipped("four_bar.kl");
    let args = |out: &str| -> Vec<String> {
        ["animate", &fb, "--params", FOUR_BAR, "--from", "0", "--to", "90", "--deg", "--samples", "7", "--out", out]
            .into_iter()
            .map(String::from)
            .chain(["--format".to_string(), "svg".to_string()])
            .collect()
    };
    let to_file = args(&p);
    ok(&kinloop(&to_file.iter().map(String::as_str).collect::<Vec<_>>()));
    let to_stdout = args("-");
    let o = kinloop(&to_stdout.iter().map(String::as_str).collect::<Vec<_>>());
    ok(&o);
    assert_eq!(o.stdout, std::fs::read(&path).expect("written"), "standard output against the file");
    assert!(!Path::new("-").exists(), "a file named `-` was made");
    let no_format = &to_stdout[..to_stdout.len() - 2];
    let o = kinloop(&no_format.iter().map(String::as_str).collect::<Vec<_>>());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--out - writes the animation to standard output: give its format"), "{stderr}");
    assert!(o.stdout.is_empty() && !Path::new("-").exists());
}

/// A declaration of no loop and no point has nothing to draw: a usage error that says to
/// declare a point, for a sweep and a grid, in either format, with no file written. It swept
/// first and then failed with exit code 1, "invalid drawing setting: the drawing has no item to
/// draw", naming a setting no one gave.
#[test]
fn nothing_to_draw_is_a_usage_error() {
    let decl = out("nothing_to_draw.kl");
    let text = "pub struct Outputs {\n    params a = 1;\n    inputs phi, psi;\n    output o = a * phi + psi;\n}\n";
    std::fs::write(&decl, text).expect("the declaration written");
    let d = decl.display().to_string();
    for (name, grid) in [("nothing.svg", false), ("nothing.html", false), ("nothing_grid.html", true)] {
        let path = out(name);
        let p = path.display().to_string();
        let mut args = vec!["animate", d.as_str(), "--from", "0,0", "--to", "1,1", "--out", p.as_str()];
        if grid {
            args.push("--grid");
        }
        let o = kinloop(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains("Outputs declares no loop and no point"), "{name}: {stderr}");
        assert!(stderr.contains("`point p = ...;`"), "{name}: {stderr}");
        assert!(!path.exists(), "{name} was written");
    }
}
