//! `--samples` is bounded: a count from the command line sizes what the sweeps allocate and how
//! long they run, so one past the limit is a usage error (exit 2) naming the limit, for every
//! command that samples, instead of an overflow, an aborted allocation or a run without end.

mod common;

use common::{kinloop, shipped};

/// The limit the help of each command states.
const MAX_SAMPLES: &str = "10000000";

/// The limit of `animate`'s samples, each a pose recorded in full.
const MAX_ANIMATION_SAMPLES: &str = "100000";

/// `args` fails as a usage error naming `--samples` and the limit, writing nothing.
fn refused(args: &[&str]) {
    refused_beyond(args, MAX_SAMPLES);
}

/// `args` fails as a usage error naming `--samples` and the limit `max`, writing nothing.
fn refused_beyond(args: &[&str], max: &str) {
    let out = kinloop(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains("--samples") && states_limit(&err, max), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}");
}

/// Whether `text` says "at most `max`", the number whole (not the start of a larger one).
fn states_limit(text: &str, max: &str) -> bool {
    let said = format!("at most {max}");
    text.match_indices(&said).any(|(i, _)| !text[i + said.len()..].starts_with(|c: char| c.is_ascii_digit()))
}

#[test]
fn too_many_samples_are_usage_errors() {
    let four_bar = shipped("four_bar.kl");
    let engine = shipped("engine.kl");
    let params = "a=1,b=3,c=2.5,d=3.2";
    let svg = std::env::temp_dir().join(format!("kinloop-samples-{}.svg", std::process::id()));
    let svg = svg.display().to_string();
    // One past the limit, a count whose allocation aborts, and the largest `usize` (whose sum
    // with the columns overflowed in `extremes`).
    for n in ["10000001", "1000000000000000", &usize::MAX.to_string()] {
        let range = ["--from", "0", "--to", "1", "--samples", n, "--params", params];
        for command in ["sweep", "extremes"] {
            let mut args = vec![command, four_bar.as_str()];
            args.extend(range);
            refused(&args);
        }
        let mut args = vec!["animate", four_bar.as_str()];
        args.extend(range);
        args.extend(["--out", svg.as_str()]);
        refused_beyond(&args, MAX_ANIMATION_SAMPLES);
        assert!(!std::path::Path::new(&svg).exists(), "{n}: an animation was written");
        refused(&["dynamics", engine.as_str(), "--speed", "10", "--samples", n]);
    }
    // The limit itself is taken (checked without running a sweep that long: the request fails
    // afterwards on its empty range, a different usage error, which names the count given).
    let out = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "0", "--samples", MAX_SAMPLES, "--params", params]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("give --to different from --from") && !err.contains("too many"), "{err}");
}

#[test]
fn the_help_states_the_limit() {
    for (command, max) in [
        ("sweep", MAX_SAMPLES),
        ("extremes", MAX_SAMPLES),
        ("animate", MAX_ANIMATION_SAMPLES),
        ("dynamics", MAX_SAMPLES),
    ] {
        let out = kinloop(&[command, "--help"]);
        let help = String::from_utf8_lossy(&out.stdout);
        assert!(states_limit(&help, max), "{command}: {help}");
    }
}

/// The help of the commands whose samples are both ends of a range states the least count too:
/// it said "at most" alone, and 0 and 1 were refused with a bound the reader had not been told.
#[test]
fn the_help_states_the_least_count() {
    for (command, least) in [("sweep", "at least 2, or 1 where `--to` equals `--from`"), ("animate", "at least 2")] {
        let out = kinloop(&[command, "--help"]);
        let help = String::from_utf8_lossy(&out.stdout);
        // The option's own entry: from its name to the next option's.
        let entry = help.split("\n      --samples <").nth(1).and_then(|rest| rest.split("\n      --").next());
        assert!(entry.is_some_and(|entry| entry.contains(least)), "{command}: {help}");
    }
}

/// An animation records every sample's pose in full (a few kilobytes each, where a sweep's row
/// takes a hundred bytes): its samples are bounded lower, so that the largest count taken fits
/// in memory (ten million took some twenty gigabytes), one more is refused.
#[test]
fn an_animations_samples_are_bounded_by_its_poses() {
    let svg = std::env::temp_dir().join(format!("kinloop-samples-poses-{}.svg", std::process::id()));
    let svg = svg.display().to_string();
    let args = ["animate", &shipped("four_bar.kl"), "--from", "0", "--to", "1", "--params", "a=1,b=3,c=2.5,d=3.2"];
    refused_beyond(&[&args[..], &["--samples", "100001", "--out", &svg]].concat(), MAX_ANIMATION_SAMPLES);
    assert!(!std::path::Path::new(&svg).exists());
}
