//! What the command line's end-to-end tests share: running the built binary, the shipped
//! mechanisms' paths and a numeric CSV read back.
// Each test binary uses a part of it.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs the built `kinloop` binary with `args`.
pub fn kinloop(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_kinloop")).args(args).output().expect("the kinloop binary runs")
}

/// The path of the shipped mechanism file `name` (`cli/mechanisms/`).
pub fn shipped(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("mechanisms").join(name).display().to_string()
}

/// A successful run's CSV: its header and its rows of numbers.
pub fn csv(out: &Output) -> (Vec<String>, Vec<Vec<f64>>) {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout.clone()).expect("utf-8");
    let mut lines = text.lines();
    let header = lines.next().expect("header").split(',').map(str::to_string).collect();
    let rows = lines.map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect()).collect();
    (header, rows)
}
