//! Shared by the browser tests: running headless Chromium on a page, reading back what the
//! page's probe wrote and what the page states about itself (its SVG parsed as XML), and the
//! comparison of a page's frames with a mechanism's expected positions and readouts.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Coordinates are written to a tenth of a pixel: a drawn point is within half of that of the
/// exact one, plus float noise far below it.
pub const PX_TOL: f64 = 0.05 + 1e-6;

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("viz sits in the workspace").to_path_buf()
}

/// The Chromium binary, or `None` (a note locally; a failure in CI, which installs it).
pub fn chromium() -> Option<PathBuf> {
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
pub fn run_chromium(bin: &Path, url: &str, args: &[&str]) -> String {
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

pub fn url(path: &Path, fragment: &str) -> String {
    format!("file://{}#{fragment}", path.canonicalize().expect("the page exists").display())
}

/// Unescapes the text of an HTML element.
pub fn unescape(s: &str) -> String {
    s.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&amp;", "&")
}

/// The place of the last digit a readout's text shows: `0.01` for `"12.34"`, `1e-10` for
/// `"-5.661e-7"`, `1e5` for `"1.5896e9"` (1 for `"0"`). The value it reads is within half
/// of it.
pub fn resolution(text: &str) -> f64 {
    let (mantissa, exp) = text.split_once('e').unwrap_or((text, "0"));
    let exp: i32 = exp.parse().unwrap_or_else(|_| panic!("readout {text:?}: power of ten"));
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    10f64.powi(exp - decimals)
}

/// One line the page's probe wrote: `frame=40 joint item=3 point=1 name=b x=1.5 y=2`.
pub struct Line {
    pub frame: usize,
    pub what: String,
    pub fields: Vec<(String, String)>,
}

impl Line {
    pub fn get(&self, key: &str) -> &str {
        self.fields.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str()).unwrap_or_else(|| panic!("no {key}"))
    }
    pub fn num(&self, key: &str) -> f64 {
        self.get(key).parse().unwrap_or_else(|_| panic!("{key}={} is a number", self.get(key)))
    }
}

pub fn probe_lines(dom: &str) -> Vec<Line> {
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
pub fn svgs(page: &str) -> Vec<String> {
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
pub type Ticks = Vec<(f64, f64)>;

/// What a page states about itself, read from its HTML (not from the browser).
pub struct Page {
    /// Pixels per unit and the pixel of the origin.
    pub scale: f64,
    pub origin: [f64; 2],
    /// Readout labels and units, by channel.
    pub readouts: Vec<(String, String)>,
    /// Each chart: its y title, and its x and y ticks as (value, pixel).
    pub charts: Vec<(String, Ticks, Ticks)>,
}

pub fn attr<'a>(node: &roxmltree::Node<'a, 'a>, name: &str) -> &'a str {
    node.attribute(name).unwrap_or_else(|| panic!("attribute {name}"))
}

pub fn read_page(page: &str) -> Page {
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
    pub fn world(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        [(x - self.origin[0]) / self.scale, (self.origin[1] - y) / self.scale]
    }

    pub fn channel(&self, label: &str) -> usize {
        self.readouts.iter().position(|(l, _)| l == label).unwrap_or_else(|| panic!("a readout {label}"))
    }
}

/// The pixel of value `v` on an axis from its ticks (first and last): the charts' own scale,
/// read off the labels.
pub fn on_ticks(ticks: &[(f64, f64)], v: f64) -> f64 {
    let ((v0, p0), (v1, p1)) = (ticks[0], ticks[ticks.len() - 1]);
    p0 + (v - v0) / (v1 - v0) * (p1 - p0)
}

/// A mechanism's expected state at a frame: points (name or `-` for unnamed joints that must
/// be among the drawn ones) and readout values (label, value in shown units).
pub struct Expected {
    /// Where the charts' cursors stand on their x axis (the input in degrees; the fraction
    /// of the path for several inputs).
    pub chart_x: f64,
    pub joints: Vec<(&'static str, [f64; 2])>,
    pub dots: Vec<(&'static str, [f64; 2])>,
    pub values: Vec<(&'static str, f64)>,
}

/// Opens `page` at `frames` in the browser and checks every frame against `expected`.
pub fn check_in_browser(
    bin: &Path,
    page_path: &Path,
    name: &str,
    frames: &[usize],
    expected: impl Fn(usize) -> Expected,
) {
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
            let shown: f64 = text.parse().expect("a number");
            let half = 0.5 * resolution(text);
            assert!(
                (shown - v).abs() <= half * (1.0 + 1e-9) + 1e-12 * v.abs().max(1.0),
                "{name} frame {f}: {label} shows {text}, exact {v}"
            );
            if page.readouts[ch].1 == "°" {
                assert_eq!(resolution(text), 0.01, "{name}: angles to a hundredth of a degree ({text})");
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
