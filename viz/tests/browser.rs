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
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::{FourBar, four_bar_joints};

/// Coordinates are written to a tenth of a pixel: a drawn point is within half of that of the
/// exact one, plus float noise far below it.
const PX_TOL: f64 = 0.05 + 1e-6;

/// The workspace root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("viz sits in the workspace").to_path_buf()
}

/// The Chromium binary, or `None` (a note locally; a failure in CI, which installs it).
fn chromium() -> Option<PathBuf> {
    let candidates: Vec<PathBuf> = match std::env::var_os("KINLOOP_CHROMIUM") {
        Some(p) => vec![PathBuf::from(p)],
        None => std::env::var_os("PATH")
            .map(|path| {
                std::env::split_paths(&path).flat_map(|d| ["chromium", "chromium-browser"].map(|n| d.join(n))).collect()
            })
            .unwrap_or_default(),
    };
    let found = candidates.into_iter().find(|p| p.is_file());
    if found.is_none() {
        let msg = "headless Chromium not found (Debian package `chromium`, or set KINLOOP_CHROMIUM)";
        let ci = std::env::var("CI").is_ok_and(|v| !["", "0", "false"].contains(&v.as_str()));
        assert!(!ci, "{msg}: CI must install it (.ci/run does)");
        // Straight to the process's stderr: the test harness captures `eprintln!` of a
        // passing test, and a skip must be seen.
        let _ = writeln!(std::io::stderr().lock(), "note: {msg}; the browser test is skipped");
    }
    found
}

/// Runs Chromium headless on `url` with `args`, returning its standard output. A browser
/// that has not finished after a minute is stopped and the test fails.
fn run_chromium(bin: &Path, url: &str, args: &[&str]) -> String {
    static COUNT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    // A profile per launch: parallel tests do not share (and lock) one.
    let profile = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("chromium-profile-{}-{n}", std::process::id()));
    let mut child = Command::new(bin)
        .args(["--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--no-first-run"])
        .args(["--disable-extensions", "--disable-background-networking", "--window-size=1280,900"])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(url)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("chromium starts");
    let mut out = child.stdout.take().expect("piped stdout");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut out, &mut s).map(|_| s)
    });
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        if let Some(status) = child.try_wait().expect("wait for chromium") {
            assert!(status.success(), "chromium failed on {url}: {status}");
            break;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("chromium did not finish within a minute on {url}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = std::fs::remove_dir_all(&profile);
    reader.join().expect("reader thread").expect("chromium's output is UTF-8")
}

fn url(path: &Path, fragment: &str) -> String {
    format!("file://{}#{fragment}", path.canonicalize().expect("the page exists").display())
}

/// Unescapes the text of an HTML element.
fn unescape(s: &str) -> String {
    s.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&amp;", "&")
}

/// One line the page's probe wrote: `frame=40 joint item=3 point=1 name=b x=1.5 y=2`.
struct Line {
    frame: usize,
    what: String,
    fields: Vec<(String, String)>,
}

impl Line {
    fn get(&self, key: &str) -> &str {
        self.fields.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str()).unwrap_or_else(|| panic!("no {key}"))
    }
    fn num(&self, key: &str) -> f64 {
        self.get(key).parse().unwrap_or_else(|_| panic!("{key}={} is a number", self.get(key)))
    }
}

fn probe_lines(dom: &str) -> Vec<Line> {
    let start = dom.find("<pre id=\"kl-probe\">").expect("the page wrote its probe") + "<pre id=\"kl-probe\">".len();
    let end = start + dom[start..].find("</pre>").expect("closed probe");
    unescape(&dom[start..end])
        .lines()
        .map(|l| {
            let mut words = l.split(' ');
            let frame = words.next().and_then(|w| w.strip_prefix("frame=")).expect("frame=").parse().expect("index");
            let what = words.next().expect("what").to_string();
            let mut fields = Vec::new();
            let rest: Vec<&str> = words.collect();
            let mut i = 0;
            while i < rest.len() {
                let (k, v) = rest[i].split_once('=').expect("key=value");
                if k == "text" {
                    // The readout's text runs to the end of the line.
                    fields.push((
                        k.to_string(),
                        std::iter::once(v).chain(rest[i + 1..].iter().copied()).collect::<Vec<_>>().join(" "),
                    ));
                    break;
                }
                fields.push((k.to_string(), v.to_string()));
                i += 1;
            }
            Line { frame, what, fields }
        })
        .collect()
}

/// The `<svg ...>...</svg>` elements of a page (not nested), parsed as XML, each checked: no
/// NaN or infinity anywhere, every number-valued attribute finite.
fn svgs(page: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = page;
    while let Some(i) = rest.find("<svg") {
        let end = i + rest[i..].find("</svg>").expect("closed svg") + "</svg>".len();
        let svg = rest[i..end].to_string();
        let doc = roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("the SVG parses: {e}"));
        for node in doc.descendants() {
            for a in node.attributes() {
                let v = a.value();
                assert!(!v.contains("NaN") && !v.contains("inf"), "{}={v:?}", a.name());
                if ["x", "y", "cx", "cy", "r", "width", "height", "x1", "x2", "y1", "y2"].contains(&a.name()) {
                    assert!(v.parse::<f64>().is_ok_and(f64::is_finite), "{}={v:?} is a finite number", a.name());
                }
                if a.name() == "points" {
                    for n in v.split([' ', ',']) {
                        assert!(n.parse::<f64>().is_ok_and(f64::is_finite), "point {n:?} is a finite number");
                    }
                }
            }
        }
        out.push(svg);
        rest = &rest[end..];
    }
    out
}

/// An axis's ticks: (value, pixel).
type Ticks = Vec<(f64, f64)>;

/// What a page states about itself, read from its HTML (not from the browser).
struct Page {
    /// Pixels per unit and the pixel of the origin.
    scale: f64,
    origin: [f64; 2],
    /// Readout labels and units, by channel.
    readouts: Vec<(String, String)>,
    /// Each chart: its y title, and its x and y ticks as (value, pixel).
    charts: Vec<(String, Ticks, Ticks)>,
}

fn attr<'a>(node: &roxmltree::Node<'a, 'a>, name: &str) -> &'a str {
    node.attribute(name).unwrap_or_else(|| panic!("attribute {name}"))
}

fn read_page(page: &str) -> Page {
    assert!(!page.contains("NaN") && !page.contains("Infinity"), "no NaN or infinity in the page");
    for l in page.match_indices("http").map(|(i, _)| &page[i..i + 34.min(page.len() - i)]) {
        assert!(l.starts_with("http://www.w3.org/2000/svg"), "no link out of the page: {l}");
    }
    let svgs = svgs(page);
    let drawing = roxmltree::Document::parse(&svgs[0]).expect("parsed");
    let d = drawing.root_element();
    assert_eq!(attr(&d, "id"), "kl-drawing");
    let scale: f64 = attr(&d, "data-scale").parse().expect("scale");
    let o: Vec<f64> = attr(&d, "data-origin").split(' ').map(|v| v.parse().expect("origin")).collect();
    let table_at = page.find("<table class=\"kl-readouts\">").expect("readouts");
    let table_end = table_at + page[table_at..].find("</table>").expect("closed table") + "</table>".len();
    let table = roxmltree::Document::parse(&page[table_at..table_end]).expect("the readouts parse as XML");
    let readouts = table
        .descendants()
        .filter(|n| n.has_tag_name("tr"))
        .map(|tr| {
            let cell = |tag: &str, class: Option<&str>| {
                tr.children()
                    .find(|c| c.has_tag_name(tag) && class.is_none_or(|k| c.attribute("class") == Some(k)))
                    .map(|c| c.text().unwrap_or("").to_string())
                    .expect("cell")
            };
            (cell("th", None), cell("td", Some("kl-unit")))
        })
        .collect();
    let charts = svgs[1..]
        .iter()
        .map(|svg| {
            let doc = roxmltree::Document::parse(svg).expect("parsed");
            let text = |class: &'static str| {
                doc.descendants().filter(move |n| n.attribute("class") == Some(class)).map(|n| {
                    (n.text().expect("label").to_string(), n.attribute("x").expect("x").parse::<f64>().expect("x"), n)
                })
            };
            let title = text("kl-axis-y").next().expect("a y title").0;
            let x_title = text("kl-axis-x").next().expect("an x title").0;
            for t in [&title, &x_title] {
                let unit = t.rsplit_once(" [").map(|(_, u)| u.trim_end_matches(']'));
                assert!(unit.is_some_and(|u| !u.is_empty()), "axis title {t:?} names its unit");
            }
            let xs = text("kl-tick-x").map(|(l, x, _)| (l.parse().expect("tick value"), x)).collect();
            let ys = text("kl-tick-y")
                .map(|(l, _, n)| {
                    (l.parse().expect("tick value"), n.attribute("y").unwrap().parse::<f64>().unwrap() - 4.0)
                })
                .collect();
            (title, xs, ys)
        })
        .collect();
    Page { scale, origin: [o[0], o[1]], readouts, charts }
}

impl Page {
    /// The mechanism point of a pixel.
    fn world(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [(x - self.origin[0]) / self.scale, (self.origin[1] - y) / self.scale]
    }

    fn channel(&self, label: &str) -> usize {
        self.readouts.iter().position(|(l, _)| l == label).unwrap_or_else(|| panic!("a readout {label}"))
    }
}

/// The pixel of value `v` on an axis from its ticks (first and last): the charts' own scale,
/// read off the labels.
fn on_ticks(ticks: &[(f64, f64)], v: f64) -> f64 {
    let ((v0, p0), (v1, p1)) = (ticks[0], ticks[ticks.len() - 1]);
    p0 + (v - v0) / (v1 - v0) * (p1 - p0)
}

/// A mechanism's expected state at a frame: points (name or `-` for unnamed joints that must
/// be among the drawn ones) and readout values (label, value in shown units).
struct Expected {
    /// Where the charts' cursors stand on their x axis (the input in degrees; the fraction
    /// of the path for several inputs).
    chart_x: f64,
    joints: Vec<(&'static str, [f64; 2])>,
    dots: Vec<(&'static str, [f64; 2])>,
    values: Vec<(&'static str, f64)>,
}

/// Opens `page` at `frames` in the browser and checks every frame against `expected`.
fn check_in_browser(bin: &Path, page_path: &Path, name: &str, frames: &[usize], expected: impl Fn(usize) -> Expected) {
    let text = std::fs::read_to_string(page_path).expect("the page");
    let page = read_page(&text);
    let list: Vec<String> = frames.iter().map(usize::to_string).collect();
    let dom = run_chromium(bin, &url(page_path, &format!("probe={}", list.join(","))), &["--dump-dom"]);
    let lines = probe_lines(&dom);
    let tol = PX_TOL / page.scale;
    for &f in frames {
        let at: Vec<&Line> = lines.iter().filter(|l| l.frame == f).collect();
        assert!(!at.is_empty(), "{name}: frame {f} probed");
        let e = expected(f);
        let drawn: Vec<(&str, [f64; 2])> = at
            .iter()
            .filter(|l| l.what == "joint")
            .map(|l| (l.get("name"), page.world([l.num("x"), l.num("y")])))
            .collect();
        for (n, p) in &e.joints {
            let near = |q: &[f64; 2]| (q[0] - p[0]).abs() <= tol && (q[1] - p[1]).abs() <= tol;
            let found = if *n == "-" {
                drawn.iter().any(|(_, q)| near(q))
            } else {
                drawn.iter().any(|(m, q)| m == n && near(q))
            };
            assert!(found, "{name} frame {f}: joint {n} at {p:?} not drawn (drawn: {drawn:?})");
        }
        for (n, p) in &e.dots {
            let dot = at.iter().find(|l| l.what == "dot" && l.get("name") == *n).expect("the traced dot");
            let q = page.world([dot.num("x"), dot.num("y")]);
            assert!(
                (q[0] - p[0]).abs() <= tol && (q[1] - p[1]).abs() <= tol,
                "{name} frame {f}: dot {n} {q:?} vs {p:?}"
            );
        }
        for (label, v) in &e.values {
            let ch = page.channel(label);
            let line = at.iter().find(|l| l.what == "value" && l.get("ch") == ch.to_string()).expect("readout");
            let text = line.get("text");
            let decimals = text.split_once('.').map_or(0, |(_, d)| d.len());
            let shown: f64 = text.parse().expect("a number");
            let half = 0.5 * 10f64.powi(-(decimals as i32));
            assert!(
                (shown - v).abs() <= half * (1.0 + 1e-9) + 1e-12,
                "{name} frame {f}: {label} shows {text}, exact {v}"
            );
            if page.readouts[ch].1 == "°" {
                assert_eq!(decimals, 2, "{name}: angles to a hundredth of a degree");
            }
            // The chart of this readout (if any): its cursor at the input and at the value,
            // on the chart's own tick labels, within the 0.1 px rounding and the value's.
            if let Some((k, (_, xs, ys))) =
                page.charts.iter().enumerate().find(|(_, c)| c.0.starts_with(&format!("{label} [")))
            {
                let cursor = at.iter().find(|l| l.what == "cursor" && l.get("chart") == k.to_string()).expect("cursor");
                let x_px = on_ticks(xs, e.chart_x);
                assert!(
                    (cursor.num("x") - x_px).abs() <= 0.1,
                    "{name} frame {f}: chart {k} cursor x {} vs {x_px}",
                    cursor.num("x")
                );
                let (y_px, y_slack) = (on_ticks(ys, *v), (on_ticks(ys, v + half) - on_ticks(ys, *v)).abs());
                assert!(
                    (cursor.num("y") - y_px).abs() <= 0.1 + y_slack,
                    "{name} frame {f}: chart {k} cursor y {} vs {y_px}",
                    cursor.num("y")
                );
            }
        }
    }
    // The DOM as the browser holds it after the last move: its joints are the probe's.
    let last = *frames.last().expect("frames");
    let at = dom.find("<svg").expect("the drawing in the DOM");
    let end = at + dom[at..].find("</svg>").expect("closed") + "</svg>".len();
    let svg = roxmltree::Document::parse(&dom[at..end]).expect("the drawn SVG parses as XML");
    assert_eq!(svg.root_element().attribute("data-frame"), Some(last.to_string().as_str()));
    let circles: Vec<[f64; 2]> = svg
        .descendants()
        .filter(|n| n.attribute("class") == Some("kl-joint"))
        .map(|n| [attr(&n, "cx").parse().unwrap(), attr(&n, "cy").parse().unwrap()])
        .collect();
    let probed: Vec<[f64; 2]> =
        lines.iter().filter(|l| l.frame == last && l.what == "joint").map(|l| [l.num("x"), l.num("y")]).collect();
    assert_eq!(circles, probed, "{name}: the DOM holds the drawn joints");
    // A screenshot for a person to look at (never committed).
    let shot = Path::new(env!("CARGO_TARGET_TMPDIR")).join("browser").join(format!("{name}.png"));
    std::fs::create_dir_all(shot.parent().unwrap()).unwrap();
    run_chromium(
        bin,
        &url(page_path, &format!("i={}", frames[frames.len() / 2])),
        &[&format!("--screenshot={}", shot.display())],
    );
    assert!(std::fs::metadata(&shot).is_ok_and(|m| m.len() > 1000), "{name}: a screenshot at {}", shot.display());
    eprintln!("{name}: screenshot {}", shot.display());
}

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
/// input ticked 0 to 360, a readout per input, and no address outside the page.
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
            assert!(!page.readouts.is_empty() && !page.charts.is_empty(), "{}", path.display());
            for (title, xs, _) in &page.charts {
                let labels: Vec<f64> = xs.iter().map(|(v, _)| *v).collect();
                if labels.first() == Some(&0.0) && labels.last() == Some(&360.0) {
                    assert_eq!(labels, [0.0, 90.0, 180.0, 270.0, 360.0], "{title}: a turn ticked every 90 degrees");
                }
            }
            pages += 1;
        }
    }
    assert!(pages >= 8, "one page per gallery mechanism, found {pages}");
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
    // Fewer frames than poses: evenly spread, the first and the last (the limit) kept.
    let few = HtmlConfig::new("x").with_max_frames(10);
    let page = html(&m, &drawing, &motion, &few).unwrap();
    assert!(page.contains(r#"max="9""#), "ten frames");
    let inputs =
        page.split(r#""ch":[{"dec":2,"v":["#).nth(1).and_then(|r| r.split(']').next()).expect("the input's values");
    let inputs: Vec<f64> = inputs.split(',').map(|v| v.parse().unwrap()).collect();
    assert_eq!(inputs.len(), 10);
    assert_eq!(inputs[0], 0.0);
    assert!(
        (inputs[9] - rocking_limit(&m).to_degrees()).abs() <= 0.005 + 1e-9,
        "the last frame is the limit: {inputs:?}"
    );
    assert!(inputs.windows(2).all(|w| w[1] > w[0]), "in order: {inputs:?}");
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
