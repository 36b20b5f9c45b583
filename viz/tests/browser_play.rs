//! Playing a page in a real browser, on a clock the test sets: the page's script is given a
//! `performance.now` and a `requestAnimationFrame` that stand still between calls, so the
//! frames it reaches are the same on every run (no wall-clock time is measured).
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
