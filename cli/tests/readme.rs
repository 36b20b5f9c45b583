//! The command lines README.md shows a reader ("Mechanisms at run time: the `kinloop` command")
//! run as written, each to success, in a scratch directory (the shipped files by their path
//! from the repository's root), so that the README cannot drift from the command line: a
//! renamed option or subcommand, a file moved, a default that no longer fits fails here. The
//! synthesis line's claim (it finds `a = 1.1, b = 2.8` again, to about 1e-4) is checked too.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's root (the command line's package is `cli/`).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the repository's root").to_path_buf()
}

/// The commands of the README's block that follows the section's title: one string a command,
/// its continuation lines (`\` at the end) joined.
fn readme_commands() -> Vec<String> {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let section = readme.split("### Mechanisms at run time").nth(1).expect("the README's section on the command line");
    let block = section.split("```sh\n").nth(1).and_then(|b| b.split("```").next()).expect("its shell block");
    let mut commands = Vec::new();
    let mut pending = String::new();
    for line in block.lines() {
        match line.strip_suffix('\\') {
            Some(head) => pending.push_str(head),
            None => commands.push(std::mem::take(&mut pending) + line),
        }
    }
    commands
}

/// A scratch directory of this test's own.
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("kinloop-readme-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    dir
}

/// `printf '%s\n' A B ... > FILE`: the lines `A`, `B`, ... written to `FILE` in `dir`.
fn printf_lines(command: &str, dir: &Path) {
    let (args, file) = command.split_once('>').expect("printf's output file");
    let lines: Vec<&str> = args.split_whitespace().skip(2).collect();
    std::fs::write(dir.join(file.trim()), lines.join("\n") + "\n").expect("the printf's file");
}

#[test]
fn the_readmes_command_lines_run_as_written() {
    let commands = readme_commands();
    let dir = scratch();
    let mechanisms = root().join("cli").join("mechanisms");
    let mut ran = 0;
    let mut synth = None;
    for command in &commands {
        let command = command.trim();
        if command.starts_with("cargo install") {
            continue;
        }
        if command.starts_with("printf") {
            printf_lines(command, &dir);
            continue;
        }
        let words: Vec<String> = command
            .split_whitespace()
            .map(|w| match w.strip_prefix("cli/mechanisms/") {
                Some(file) => mechanisms.join(file).display().to_string(),
                None => w.to_string(),
            })
            .collect();
        assert_eq!(words[0], "kinloop", "a README command line that is not `kinloop`: {command}");
        let out = Command::new(env!("CARGO_BIN_EXE_kinloop"))
            .args(&words[1..])
            .current_dir(&dir)
            .output()
            .expect("the kinloop binary runs");
        assert!(out.status.success(), "{command}\n{}", String::from_utf8_lossy(&out.stderr));
        if words[1] == "synth" {
            synth = Some(String::from_utf8(out.stdout).expect("utf-8"));
        }
        ran += 1;
    }
    // Every subcommand the README shows (check, solve, sweep, extremes, trace, cam, dynamics,
    // simulate, animate three times, synth).
    assert!(ran >= 12, "ran {ran} of {commands:?}");
    for file in ["rhombic.html", "cam.svg", "five_bar.html"] {
        assert!(dir.join(file).is_file(), "{file} not written");
    }
    // The best candidate, the table's first row after its header: rank, start, valid, a, b, ...
    let synth = synth.expect("the README shows a synthesis");
    let best: Vec<&str> = synth.lines().nth(1).expect("a candidate").split_whitespace().collect();
    let (a, b): (f64, f64) = (best[3].parse().expect("a"), best[4].parse().expect("b"));
    assert_eq!(best[2], "1", "the best candidate is valid: {synth}");
    assert!((a - 1.1).abs() < 3e-4 && (b - 2.8).abs() < 3e-4, "a = {a}, b = {b}: {synth}");
    std::fs::remove_dir_all(&dir).ok();
}
