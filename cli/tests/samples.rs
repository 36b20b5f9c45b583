//! `--samples` is bounded: a count from the command line sizes what the sweeps allocate and how
//! long they run, so one past the limit is a usage error (exit 2) naming the limit, for every
//! command that samples, instead of an overflow, an aborted allocation or a run without end.

mod common;

use common::{kinloop, shipped};

/// The limit the help of each command states.
const MAX_SAMPLES: &str = "10000000";

/// `args` fails as a usage error naming `--samples` and the limit, writing nothing.
fn refused(args: &[&str]) {
    let out = kinloop(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains("--samples") && err.contains(MAX_SAMPLES), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}");
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
        refused(&args);
        assert!(!std::path::Path::new(&svg).exists(), "{n}: an animation was written");
        refused(&["dynamics", engine.as_str(), "--speed", "10", "--samples", n]);
    }
    // The limit itself is taken (checked without running a sweep that long: the request fails
    // afterwards on its empty range, a different usage error).
    let out = kinloop(&["sweep", &four_bar, "--from", "0", "--to", "0", "--samples", MAX_SAMPLES, "--params", params]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("`to` different from `from`") && !err.contains(MAX_SAMPLES), "{err}");
}

#[test]
fn the_help_states_the_limit() {
    for command in ["sweep", "extremes", "animate", "dynamics"] {
        let out = kinloop(&[command, "--help"]);
        let help = String::from_utf8_lossy(&out.stdout);
        assert!(help.contains(&format!("at most {MAX_SAMPLES}")), "{command}: {help}");
    }
}
