//! Playing a page in a real browser, on a clock the test sets: the page's script is given a
//! `performance.now` and a `requestAnimationFrame` that stand still between calls, so the
//! frames it reaches are the same on every run (no wall-clock time is measured).
//! Also a page laid out on a narrow screen (no part of it wider than the screen).
//!
//! Without Chromium the test prints a note and passes locally; in CI (`CI` set) it fails.

use kinloop_viz::draw::{Draw, HtmlConfig, Motion, html};
use std::f64::consts::TAU;
use std::path::Path;

#[allow(dead_code)] // not every test uses every helper
mod draw_support;

use draw_support::FourBar;

#[allow(dead_code)] // not every test uses every helper
mod browser_support;

use browser_support::{chromium, run_chromium, url};

/// Frames the stand-in for `requestAnimationFrame` runs before it stops asking for more.
const TICKS: usize = 40;

/// Milliseconds between two of those frames.
const STEP: f64 = 16.0;

/// Put before the page's script: a clock that reads 1000 ms and moves on by `STEP` at each
/// frame, whose frames are stamped with the time they began, `STEP` before the clock (as a
/// browser stamps a frame in which a click, or the page's first script, read the clock later);
/// an error thrown by the page is written on the root element.
fn clock() -> String {
    format!(
        "<script>(function () {{
  var clock = 1000, ticks = 0;
  window.performance.now = function () {{ return clock; }};
  window.requestAnimationFrame = function (cb) {{
    if (ticks++ >= {TICKS}) {{ return 0; }}
    var stamp = clock - {STEP};
    clock += {STEP};
    window.setTimeout(function () {{ cb(stamp); }}, 1);
    return ticks;
  }};
  window.addEventListener('error', function (e) {{
    document.documentElement.setAttribute('data-error', String(e.message));
  }});
}})();</script>"
    )
}

/// The value of attribute `name` of the page's drawing, as the browser left it.
fn drawing_attr<'a>(dom: &'a str, name: &str) -> Option<&'a str> {
    let at = dom.find("id=\"kl-drawing\"")?;
    let tag = &dom[at..at + dom[at..].find('>')?];
    tag.split(&format!(" {name}=\"")).nth(1)?.split('"').next()
}

/// A page of many frames opened without a pose plays from its first frame: the first frame the
/// browser runs began before `play` read the clock, and that moment before the start once
/// made the pose a negative frame, whose missing numbers threw and stopped the playing for
/// good (the button still saying Pause). Both ways of playing, a full turn and back and forth.
#[test]
fn a_page_plays_from_a_frame_stamped_before_play_started() {
    let m = FourBar::default();
    let motion = Motion::record(&m, m.sweep(0.0, TAU, 721, &m.guess(0.0)).unwrap()).unwrap();
    let drawing = m.drawing().into_drawing();
    let Some(bin) = chromium() else { return };
    for back_and_forth in [false, true] {
        let config = HtmlConfig::new("played").with_back_and_forth(back_and_forth);
        let page = html(&m, &drawing, &motion, &config).unwrap();
        let frames = motion.poses.len();
        assert!(page.contains(&format!(r#"max="{}""#, frames - 1)), "one frame per pose");
        let page = page.replacen("<script", &(clock() + "<script"), 1);
        let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("played_{back_and_forth}.html"));
        std::fs::write(&path, &page).unwrap();
        let dom = run_chromium(&bin, &url(&path, ""), &["--virtual-time-budget=2000", "--dump-dom"]);
        let error = dom.split(" data-error=\"").nth(1).and_then(|r| r.split('"').next());
        assert_eq!(error, None, "the page threw");
        assert!(dom.contains(r#"aria-pressed="true">Pause</button>"#), "the page plays");
        // The last frame run began (TICKS - 2) steps after play read the clock: the pose
        // shown is that time's share of a pass (6 s by default), forward in both ways.
        let played = (TICKS - 2) as f64 * STEP / (1000.0 * config.seconds);
        let want = (played * (frames - 1) as f64).round() as usize;
        assert_eq!(
            drawing_attr(&dom, "data-frame"),
            Some(want.to_string().as_str()),
            "back and forth: {back_and_forth}"
        );
    }
}

/// The value of attribute `name` of the page's root element, as the browser left it.
fn root_attr(dom: &str, name: &str) -> Option<f64> {
    dom.split(&format!(" {name}=\"")).nth(1)?.split('"').next()?.parse().ok()
}

/// On a screen narrower than a chart (a phone's, 390 pixels), the page does not scroll
/// sideways: the charts shrink with the picture. A chart kept its 380 pixels beside the page's
/// margins and ran off the screen, its last tick labels cut and the whole page scrolling.
/// Headless Chromium opens no window narrower than 500 pixels: the page's body is given the
/// phone's width instead.
#[test]
fn a_page_fits_a_narrow_screen() {
    let m = FourBar::default();
    let motion = Motion::record(&m, m.sweep(0.0, TAU, 37, &m.guess(0.0)).unwrap()).unwrap();
    let drawing = m.drawing().into_drawing();
    let Some(bin) = chromium() else { return };
    let config = HtmlConfig::new("narrow").show(FourBar::COL.gamma).with_autoplay(false);
    let page = html(&m, &drawing, &motion, &config).unwrap();
    let page = page.replacen("</head>", "<style>body{width:390px}</style></head>", 1);
    // Measured once the page is laid out: how wide its content is, how wide the body, where
    // each chart's right edge lies.
    let measure = "<script>window.addEventListener('load', function () {
  var d = document.documentElement, b = document.body;
  d.setAttribute('data-scroll-width', String(b.scrollWidth));
  d.setAttribute('data-body-width', String(b.clientWidth));
  var right = 0;
  document.querySelectorAll('svg.kl-chart').forEach(function (c) {
    right = Math.max(right, c.getBoundingClientRect().right);
  });
  d.setAttribute('data-chart-right', String(right));
});</script></body>";
    let page = page.replacen("</body>", measure, 1);
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("narrow.html");
    std::fs::write(&path, &page).unwrap();
    let dom = run_chromium(&bin, &url(&path, ""), &["--virtual-time-budget=1000", "--dump-dom"]);
    let [scroll, body, right] =
        ["data-scroll-width", "data-body-width", "data-chart-right"].map(|a| root_attr(&dom, a).expect(a));
    assert_eq!(body, 390.0, "the body is the phone's width");
    assert!(scroll <= body, "the page's content is {scroll} px wide in a body of {body} px");
    assert!(right > 0.0 && right <= body, "a chart ends at {right} px in a body of {body} px");
}
