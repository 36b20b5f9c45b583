//! Prints the tables of `BENCHMARKS.md` from one run of the benchmarks: the medians criterion
//! measured (read from `<target>/criterion/<group>/<bench>/new/estimates.json`) with their ratios
//! to each group's reference, the Newton iterations per step of every variant, and the size of
//! the macro's expansions.
//!
//! `cargo run --release -p kinloop-bench --bin report [-- [--paired] [--callgrind FILE]
//! [CRITERION_DIR]]`. The criterion directory defaults to `$CARGO_TARGET_DIR/criterion`, else
//! `target/criterion` at the workspace root. `--paired` adds an interleaved measurement of the
//! same steps (see [`paired`]), a cross-check of criterion's sequential runs on a shared, noisy
//! machine. `--callgrind FILE` puts the instructions per step of the closed-form rows (the
//! output of `benches/callgrind.sh`, lines `VARIANT COUNT` naming variants of
//! `closed_form_step`, `VARIANT@TURN` for another turn than 720 steps) beside their criterion
//! times, and adds the table of the rows callgrind alone measures (the class IV predictor and
//! sweep, the turns of 10^6 steps, the rhombic drive by Newton, the ring of 64 loops).

use std::collections::HashMap;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use kinloop::Mechanism;
use kinloop_bench::class_four::{self, HandNewton};
use kinloop_bench::decls::paper_mechanisms;
use kinloop_bench::expansion::{four_bar_chain, four_bar_chain_dense, size};
use kinloop_bench::hand_sweep::HandSweep;
use kinloop_bench::kinloop_variants::{Kinloop, KinloopNamed, KinloopSweep, check_kinloop_sweep};
use kinloop_bench::lean::HandSweepCursor;
use kinloop_bench::rhombic::{self, ClosedForm, DenseFiniteDifference, DenseHandJacobian, DenseNumDual, TwoLoopNewton};
use kinloop_bench::rows::{RowVisitor, TURN_720, closed_form_rows};
use kinloop_bench::sweep::{Failed, STEPS, Stepper, Sweep, SweepCheck, WarmStart, check_sweep, check_turn};

const RHOMBIC: [&str; 8] = [
    "closed_form",
    "kinloop",
    "kinloop_named",
    SWEEP,
    "two_loop_newton",
    "dense_hand_jacobian",
    "dense_num_dual",
    "dense_finite_difference",
];
const CLASS_FOUR: [&str; 4] = ["hand_newton", "kinloop", "kinloop_named", SWEEP];

/// kinloop's own sweep: it has its own (Taylor) predictor, so it is measured in the taylor
/// groups only.
const SWEEP: &str = "kinloop_sweep";

/// The sweep recipe written by hand (`kinloop_bench::hand_sweep`): the floor of a sweep's
/// sample, without a general sweep's checks.
const HAND_SWEEP: &str = "hand_sweep";

fn measured_with(bench: &str, policy: WarmStart) -> bool {
    bench != SWEEP || policy == WarmStart::Taylor
}

/// Median and its 95% confidence interval, in nanoseconds.
#[derive(Clone, Copy, Debug)]
struct Estimate {
    median: f64,
    low: f64,
    high: f64,
}

fn estimate(dir: &Path, group: &str, bench: &str) -> Option<Estimate> {
    let path = dir.join(group).join(bench).join("new").join("estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    let m = &v["median"];
    Some(Estimate {
        median: m["point_estimate"].as_f64()?,
        low: m["confidence_interval"]["lower_bound"].as_f64()?,
        high: m["confidence_interval"]["upper_bound"].as_f64()?,
    })
}

/// The command line: `[--paired] [--callgrind FILE] [CRITERION_DIR]`.
struct Args {
    paired: bool,
    callgrind: Option<PathBuf>,
    dir: PathBuf,
}

fn args() -> Args {
    let mut a = Args { paired: false, callgrind: None, dir: default_criterion_dir() };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--paired" => a.paired = true,
            "--callgrind" => match it.next() {
                Some(f) => a.callgrind = Some(PathBuf::from(f)),
                None => exit_with("--callgrind needs a file (the output of benches/callgrind.sh)"),
            },
            other if other.starts_with("--") => exit_with(&format!("unknown option {other}")),
            dir => a.dir = PathBuf::from(dir),
        }
    }
    a
}

fn exit_with(why: &str) -> ! {
    eprintln!("report: {why}\nusage: report [--paired] [--callgrind FILE] [CRITERION_DIR]");
    std::process::exit(2)
}

fn default_criterion_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("target"));
    target.join("criterion")
}

fn fmt_ns(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.2} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.1} µs", ns / 1e3)
    } else {
        format!("{ns:.1} ns")
    }
}

fn timing_table(dir: &Path, prefix: &str, benches: &[&str], reference: &str) {
    println!("| variant | warm start | median per step | 95% CI of the median | ratio to `{reference}` |");
    println!("|---|---|---:|---:|---:|");
    for policy in WarmStart::ALL {
        let group = format!("{prefix}_{}", policy.name());
        let base = estimate(dir, &group, reference);
        for b in benches.iter().filter(|b| measured_with(b, policy)) {
            match estimate(dir, &group, b) {
                Some(e) => {
                    let ratio = base.map_or("?".to_string(), |r| format!("{:.2}", e.median / r.median));
                    println!(
                        "| `{b}` | {} | {} | {} – {} | {ratio} |",
                        policy.name(),
                        fmt_ns(e.median),
                        fmt_ns(e.low),
                        fmt_ns(e.high)
                    );
                }
                None => println!("| `{b}` | {} | not measured | | |", policy.name()),
            }
        }
    }
    println!();
}

fn speedups(dir: &Path) {
    println!(
        "| warm start | kinloop / closed form | kinloop / two-loop Newton | num-dual / kinloop | finite differences / kinloop | class IV: kinloop / hand-written | kinloop_sweep / closed form | class IV: kinloop_sweep / hand-written |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for policy in WarmStart::ALL {
        let g = format!("rhombic_{}", policy.name());
        let g4 = format!("class_four_{}", policy.name());
        let r = |a: Option<Estimate>, b: Option<Estimate>| match (a, b) {
            (Some(a), Some(b)) => format!("{:.2}", a.median / b.median),
            _ => "?".to_string(),
        };
        let sweep = |group: &str, reference: &str| {
            if measured_with(SWEEP, policy) {
                r(estimate(dir, group, SWEEP), estimate(dir, group, reference))
            } else {
                "–".to_string()
            }
        };
        let kl = estimate(dir, &g, "kinloop");
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            policy.name(),
            r(kl, estimate(dir, &g, "closed_form")),
            r(kl, estimate(dir, &g, "two_loop_newton")),
            r(estimate(dir, &g, "dense_num_dual"), kl),
            r(estimate(dir, &g, "dense_finite_difference"), kl),
            r(estimate(dir, &g4, "kinloop"), estimate(dir, &g4, "hand_newton")),
            sweep(&g, "closed_form"),
            sweep(&g4, "hand_newton"),
        );
    }
    println!();
}

/// A closed-form row: its criterion group, its mechanism, and each variant's bench id beside
/// the same variant of `closed_form_step` (the reference first).
struct Row {
    group: &'static str,
    mechanism: &'static str,
    variants: &'static [(&'static str, &'static str)],
}

const CLOSED_FORM_ROWS: [Row; 4] = [
    Row {
        group: "closed_form_rhombic",
        mechanism: "rhombic drive",
        variants: &[("closed_form", "hand"), ("kinloop", "point"), (SWEEP, "sweep"), (HAND_SWEEP, "hand-sweep")],
    },
    Row {
        group: "closed_form_four_bar",
        mechanism: "four-bar with its coupler point",
        variants: &[
            ("closed_form", "four-bar-hand"),
            ("kinloop", "four-bar-point"),
            (SWEEP, "four-bar-sweep"),
            (HAND_SWEEP, "four-bar-hand-sweep"),
        ],
    },
    Row {
        group: "closed_form_gear_lever",
        mechanism: "gear-lever rocker",
        variants: &[
            ("closed_form", "gear-lever-hand"),
            ("kinloop", "gear-lever-point"),
            (SWEEP, "gear-lever-sweep"),
            (HAND_SWEEP, "gear-lever-hand-sweep"),
        ],
    },
    Row {
        group: "class_four_720_previous",
        mechanism: "class IV block (Newton)",
        variants: &[("hand_newton", "class-four-hand"), ("kinloop", "class-four-point")],
    },
];

/// A row measured by callgrind only: a variant of `closed_form_step` (`VARIANT@TURN` when its
/// turn is not [`TURN_720`] steps) against its reference, and the target of their ratio if any.
struct CountRow {
    what: &'static str,
    variant: &'static str,
    reference: &'static str,
    target: Option<f64>,
}

const COUNT_ROWS: [CountRow; 34] = [
    CountRow {
        what: "rhombic drive, point step, against the hand closed form with libm's `sincos(phi1 + gamma)`",
        variant: "point",
        reference: "hand-libm-sum",
        target: None,
    },
    CountRow {
        what: "rhombic drive, kinloop's own `Sweep`, 20,000 steps a turn",
        variant: "sweep@20000",
        reference: "hand@20000",
        target: Some(0.6),
    },
    CountRow {
        what: "rhombic drive, the sweep recipe written by hand (no branch checks), 20,000 steps a turn",
        variant: "hand-sweep@20000",
        reference: "hand@20000",
        target: None,
    },
    CountRow {
        what: "rhombic drive, the sweep recipe written by hand with kinloop's per-sample branch checks",
        variant: "hand-sweep-checked",
        reference: "hand",
        target: None,
    },
    CountRow {
        what: "rhombic drive, the sweep recipe written by hand with kinloop's per-sample branch checks, 20,000 steps a turn",
        variant: "hand-sweep-checked@20000",
        reference: "hand@20000",
        target: None,
    },
    CountRow {
        what: "rhombic drive, point step, 20,000 steps a turn",
        variant: "point@20000",
        reference: "hand@20000",
        target: Some(1.3),
    },
    CountRow {
        what: "four-bar with its coupler point, kinloop's own `Sweep`, 20,000 steps a turn",
        variant: "four-bar-sweep@20000",
        reference: "four-bar-hand@20000",
        target: Some(0.6),
    },
    CountRow {
        what: "four-bar with its coupler point, the sweep recipe written by hand (no branch checks), 20,000 steps a turn",
        variant: "four-bar-hand-sweep@20000",
        reference: "four-bar-hand@20000",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, the sweep recipe written by hand with kinloop's per-sample branch checks",
        variant: "four-bar-hand-sweep-checked",
        reference: "four-bar-hand",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, the sweep recipe written by hand with kinloop's per-sample branch checks, 20,000 steps a turn",
        variant: "four-bar-hand-sweep-checked@20000",
        reference: "four-bar-hand@20000",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, point step, 20,000 steps a turn",
        variant: "four-bar-point@20000",
        reference: "four-bar-hand@20000",
        target: Some(1.3),
    },
    CountRow {
        what: "gear-lever rocker, kinloop's own `Sweep`, 20,000 steps a turn",
        variant: "gear-lever-sweep@20000",
        reference: "gear-lever-hand@20000",
        target: Some(0.6),
    },
    CountRow {
        what: "gear-lever rocker, the sweep recipe written by hand (no branch checks), 20,000 steps a turn",
        variant: "gear-lever-hand-sweep@20000",
        reference: "gear-lever-hand@20000",
        target: None,
    },
    CountRow {
        what: "gear-lever rocker, the sweep recipe written by hand with kinloop's per-sample branch checks",
        variant: "gear-lever-hand-sweep-checked",
        reference: "gear-lever-hand",
        target: None,
    },
    CountRow {
        what: "gear-lever rocker, the sweep recipe written by hand with kinloop's per-sample branch checks, 20,000 steps a turn",
        variant: "gear-lever-hand-sweep-checked@20000",
        reference: "gear-lever-hand@20000",
        target: None,
    },
    CountRow {
        what: "gear-lever rocker, point step, 20,000 steps a turn",
        variant: "gear-lever-point@20000",
        reference: "gear-lever-hand@20000",
        target: Some(1.3),
    },
    CountRow {
        what: "rhombic drive, kinloop's kernel driven by the hand sweep's trigonometry, no check and no judgment (the floor of a sweep that calls the kernel)",
        variant: "kernel-lane",
        reference: "hand",
        target: None,
    },
    CountRow {
        what: "rhombic drive, kinloop's kernel driven by the hand sweep's trigonometry, no check and no judgment (the floor of a sweep that calls the kernel), 20,000 steps a turn",
        variant: "kernel-lane@20000",
        reference: "hand@20000",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, kinloop's kernel driven by the hand sweep's trigonometry, no check and no judgment (the floor of a sweep that calls the kernel)",
        variant: "four-bar-kernel-lane",
        reference: "four-bar-hand",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, kinloop's kernel driven by the hand sweep's trigonometry, no check and no judgment (the floor of a sweep that calls the kernel), 20,000 steps a turn",
        variant: "four-bar-kernel-lane@20000",
        reference: "four-bar-hand@20000",
        target: None,
    },
    CountRow {
        what: "gear-lever rocker, kinloop's kernel driven by the hand sweep's trigonometry, no check and no judgment (the floor of a sweep that calls the kernel)",
        variant: "gear-lever-kernel-lane",
        reference: "gear-lever-hand",
        target: None,
    },
    CountRow {
        what: "gear-lever rocker, kinloop's kernel driven by the hand sweep's trigonometry, no check and no judgment (the floor of a sweep that calls the kernel), 20,000 steps a turn",
        variant: "gear-lever-kernel-lane@20000",
        reference: "gear-lever-hand@20000",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, its sweep loop sketched as the macro would emit it (the kernel's formulas and run-time pieces, the sweep's checks)",
        variant: "four-bar-lane-sketch",
        reference: "four-bar-hand",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, its sweep loop sketched as the macro would emit it (the kernel's formulas and run-time pieces, the sweep's checks), 20,000 steps a turn",
        variant: "four-bar-lane-sketch@20000",
        reference: "four-bar-hand@20000",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, the sketched sweep loop with the branch flag carried, the plain root formula and the analogs by the dyad's own determinant",
        variant: "four-bar-lane-lean",
        reference: "four-bar-hand",
        target: None,
    },
    CountRow {
        what: "four-bar with its coupler point, the sketched sweep loop with the branch flag carried, the plain root formula and the analogs by the dyad's own determinant, 20,000 steps a turn",
        variant: "four-bar-lane-lean@20000",
        reference: "four-bar-hand@20000",
        target: None,
    },
    CountRow {
        what: "class IV block, second-order predictor (hand Newton with the same predictor)",
        variant: "class-four-point-taylor",
        reference: "class-four-hand-taylor",
        target: Some(1.3),
    },
    CountRow {
        what: "class IV block, kinloop's own `Sweep` (against the predictor-driven hand Newton)",
        variant: "class-four-sweep",
        reference: "class-four-hand-taylor",
        target: None,
    },
    CountRow {
        what: "class IV block, previous position, 10^6 steps a turn",
        variant: "class-four-point@1000000",
        reference: "class-four-hand@1000000",
        target: Some(1.3),
    },
    CountRow {
        what: "class IV block, second-order predictor, 10^6 steps a turn",
        variant: "class-four-point-taylor@1000000",
        reference: "class-four-hand-taylor@1000000",
        target: Some(1.3),
    },
    CountRow {
        what: "rhombic drive, point step, 10^6 steps a turn: the 2000 steps measured cover only 0.7 degrees of the turn (libm's cost depends on the angle)",
        variant: "point@1000000",
        reference: "hand@1000000",
        target: None,
    },
    CountRow {
        what: "rhombic drive by Newton in every block (`#[kinloop(newton)]`) against its closed forms, point step",
        variant: "newton",
        reference: "point",
        target: None,
    },
    CountRow {
        what: "rhombic drive by Newton in every block against its closed forms, `Sweep` sample",
        variant: "newton-sweep",
        reference: "sweep",
        target: None,
    },
    CountRow {
        what: "ring of 64 four-bar loops, one sparse block of 128 unknowns, against the same loops in series",
        variant: "ring-point",
        reference: "series-point",
        target: Some(5.0),
    },
];

/// The rows measured by callgrind only (see [`COUNT_ROWS`]).
fn count_table(callgrind: &HashMap<String, f64>) {
    println!(
        "| row | `closed_form_step` variant | instructions per step | reference variant | reference | ratio | target |"
    );
    println!("|---|---|---:|---|---:|---:|---:|");
    let cell = |v: &str| callgrind.get(v).copied();
    let fmt = |n: Option<f64>| n.map_or("–".to_string(), |n| format!("{n:.0}"));
    for row in &COUNT_ROWS {
        let (count, reference) = (cell(row.variant), cell(row.reference));
        let ratio = match (count, reference) {
            (Some(n), Some(r)) => format!("{:.2}", n / r),
            _ => "–".to_string(),
        };
        let target = row.target.map_or("–".to_string(), |t| format!("{t}"));
        println!(
            "| {} | `{}` | {} | `{}` | {} | {ratio} | {target} |",
            row.what,
            row.variant,
            fmt(count),
            row.reference,
            fmt(reference)
        );
    }
    println!();
}

/// Instructions per step of the variants of `closed_form_step`: the lines `VARIANT COUNT` that
/// `benches/callgrind.sh` prints (blank lines and `#` comments are skipped).
fn read_callgrind(path: &Path) -> Result<HashMap<String, f64>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let mut counts = HashMap::new();
    for (i, line) in text.lines().enumerate().map(|(i, l)| (i, l.trim())) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut words = line.split_whitespace();
        match (words.next(), words.next().map(str::parse::<f64>), words.next()) {
            (Some(variant), Some(Ok(n)), None) if n.is_finite() && n > 0.0 => {
                counts.insert(variant.to_string(), n);
            }
            _ => return Err(format!("line {}: expected `VARIANT INSTRUCTIONS_PER_STEP`, got `{line}`", i + 1)),
        }
    }
    Ok(counts)
}

/// The closed-form rows: criterion's median with its ratio to the row's reference, beside the
/// callgrind instructions per step of the same variant with their ratio (when a file of counts
/// was given).
fn closed_form_table(dir: &Path, callgrind: Option<&HashMap<String, f64>>) {
    println!(
        "| mechanism | variant | `closed_form_step` variant | median per step | 95% CI of the median | ratio to the reference | instructions per step | ratio to the reference |"
    );
    println!("|---|---|---|---:|---:|---:|---:|---:|");
    let instr = |v: &str| callgrind.and_then(|c| c.get(v).copied());
    for row in &CLOSED_FORM_ROWS {
        let (reference, reference_cg) = row.variants[0];
        let base = estimate(dir, row.group, reference);
        for &(bench, cg) in row.variants {
            let time = match estimate(dir, row.group, bench) {
                Some(e) => {
                    let ratio = base.map_or("?".to_string(), |r| format!("{:.2}", e.median / r.median));
                    format!("{} | {} – {} | {ratio}", fmt_ns(e.median), fmt_ns(e.low), fmt_ns(e.high))
                }
                None => "not measured | | ".to_string(),
            };
            let count = match (instr(cg), instr(reference_cg)) {
                (Some(n), Some(r)) => format!("{n:.0} | {:.2}", n / r),
                (Some(n), None) => format!("{n:.0} | ?"),
                (None, _) => "– | –".to_string(),
            };
            println!("| {} | `{bench}` | `{cg}` | {time} | {count} |", row.mechanism);
        }
    }
    println!();
}

/// The iterations and deviations of one warm-start policy: two cells of the table.
fn iteration_cells(check: Result<SweepCheck, Failed>) -> String {
    match check {
        Ok(c) => format!(
            "{:.3} (max {}) | {:.0e} / {:.0e} / {:.0e}",
            c.mean_iterations, c.max_iterations, c.max_dev[0], c.max_dev[1], c.max_dev[2]
        ),
        Err(e) => format!("failed: {e} | "),
    }
}

fn iteration_row<S: Stepper<4>, R: Stepper<4>>(name: &str, s: &S, r: &R, guess0: [f64; 4]) {
    let cells: Vec<String> =
        WarmStart::ALL.iter().map(|&policy| iteration_cells(check_sweep(s, r, STEPS, policy, guess0))).collect();
    println!("| `{name}` | {} |", cells.join(" | "));
}

/// kinloop's sweep: the iterations of the accepted solve of each sample (its own predictor).
fn iteration_row_sweep<M: Mechanism<4, 1, 0>, R: Stepper<4>>(name: &str, m: &M, r: &R, guess0: [f64; 4]) {
    let taylor = iteration_cells(check_kinloop_sweep(m, r, STEPS, guess0));
    println!("| `{name}` | {taylor} | – | – |");
}

fn iterations() {
    println!(
        "| variant | Newton iterations per step, taylor | max deviation q / dq / d2q, taylor | iterations, previous | deviation, previous |"
    );
    println!("|---|---:|---:|---:|---:|");
    let p = rhombic::PARAMS;
    let g = rhombic::initial_guess(&p);
    let closed = ClosedForm::new(&p);
    iteration_row("rhombic: kinloop", &Kinloop::<_, 0>::new(p.kinloop()), &closed, g);
    iteration_row("rhombic: kinloop_named", &KinloopNamed::new(p.kinloop()), &closed, g);
    iteration_row_sweep("rhombic: kinloop_sweep", &p.kinloop(), &closed, g);
    iteration_row("rhombic: two_loop_newton", &TwoLoopNewton { p }, &closed, g);
    iteration_row("rhombic: dense_hand_jacobian", &DenseHandJacobian { p }, &closed, g);
    iteration_row("rhombic: dense_num_dual", &DenseNumDual { p }, &closed, g);
    iteration_row("rhombic: dense_finite_difference", &DenseFiniteDifference { p }, &closed, g);
    let p4 = class_four::PARAMS;
    let hand = HandNewton { p: p4 };
    let g4 = class_four::INITIAL_GUESS;
    iteration_row("class IV: hand_newton", &hand, &hand, g4);
    iteration_row("class IV: kinloop", &Kinloop::<_, 0>::new(p4.kinloop()), &hand, g4);
    iteration_row_sweep("class IV: kinloop_sweep", &p4.kinloop(), &hand, g4);
    println!();
}

fn sizes(dir: &Path) {
    println!(
        "| declaration | scalar equations | expansion time (median) | expanded lines | lines per equation | token trees |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    for d in paper_mechanisms() {
        let s = size(d.text);
        let t = estimate(dir, "expand", d.name).map_or("not measured".to_string(), |e| fmt_ns(e.median));
        println!(
            "| `{}` | {} | {t} | {} | {:.0} | {} |",
            d.name,
            d.equations,
            s.lines,
            s.lines as f64 / d.equations as f64,
            s.tokens
        );
    }
    println!();
    println!(
        "| four-bar chain of k loops | scalar equations | lines (blocks of 2) | lines per equation | lines, `#[kinloop(dense)]` (one block) | expansion time |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    for k in [1, 2, 4, 8, 16] {
        let s = size(&four_bar_chain(k));
        let dense = if k <= 8 { size(&four_bar_chain_dense(k)).lines.to_string() } else { "–".to_string() };
        let t = estimate(dir, "expand", &format!("FourBarChain{k}")).map_or("–".to_string(), |e| fmt_ns(e.median));
        println!("| k = {k} | {} | {} | {:.0} | {dense} | {t} |", 2 * k, s.lines, s.lines as f64 / (2 * k) as f64);
    }
    println!();
}

/// A variant timed by [`paired`]: runs `n` steps of its own sweep, returns ns per step.
type Timed<'a> = (&'static str, Box<dyn FnMut(usize) -> f64 + 'a>);

/// A variant that runs one step per call of `step`.
fn timed_steps<'a>(name: &'static str, mut step: impl FnMut() + 'a) -> Timed<'a> {
    let run = move |n: usize| {
        let t = Instant::now();
        for _ in 0..n {
            step();
        }
        t.elapsed().as_nanos() as f64 / n as f64
    };
    (name, Box::new(run))
}

/// `s` along turns of `steps` steps with `policy`.
fn timed_turn<'a, S: Stepper<N>, const N: usize>(
    name: &'static str,
    s: &'a S,
    policy: WarmStart,
    guess0: [f64; N],
    steps: usize,
) -> Timed<'a> {
    let mut sweep = Sweep::start(s, steps, policy, guess0).expect("the sweep starts");
    timed_steps(name, move || {
        black_box(sweep.advance(s).expect("the sweep goes on"));
    })
}

/// `s` along turns of [`STEPS`] steps with `policy`.
fn timed<'a, S: Stepper<4>>(name: &'static str, s: &'a S, policy: WarmStart, guess0: [f64; 4]) -> Timed<'a> {
    timed_turn(name, s, policy, guess0, STEPS)
}

/// kinloop's own sweep of `m` (see `KinloopSweep`) over turns of `steps` samples.
fn timed_sweep<'a, M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(
    m: &'a M,
    guess0: [f64; N],
    steps: usize,
) -> Timed<'a> {
    let mut sweep = KinloopSweep::start(m, steps, guess0).expect("the sweep starts");
    timed_steps(SWEEP, move || {
        black_box(sweep.advance().expect("the sweep goes on"));
    })
}

/// The sweep recipe written by hand, one sample per call (see `kinloop_bench::hand_sweep`).
fn timed_hand_sweep<'a, S: HandSweep<N, NP> + 'a, const N: usize, const NP: usize>(mut s: S) -> Timed<'a> {
    s.sync(0.0).expect("the sweep starts");
    let mut cursor = HandSweepCursor::new(&s);
    timed_steps(HAND_SWEEP, move || {
        black_box(cursor.next(&mut s).expect("the sweep goes on"));
    })
}

/// The sweep recipe written by hand over one turn against the hand closed form `reference`.
fn check_hand_sweep<S: HandSweep<N, NP>, R: Stepper<N>, const N: usize, const NP: usize>(
    mut s: S,
    reference: &R,
    guess0: [f64; N],
) -> Result<SweepCheck, Failed> {
    let (first, _) = s.sync(0.0)?;
    let mut cursor = HandSweepCursor::new(&s);
    check_turn(reference, s.turn(), WarmStart::Previous, guess0, (0.0, first), || {
        cursor.next(&mut s).map(|(x, step, _)| (x, step))
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Interleaved timing: in each round every variant runs `n` steps, in an order rotated from
/// round to round; ratios are taken within a round and their median reported. On a shared
/// machine this pairs each ratio's numerator and denominator in time, so load that comes and
/// goes cancels out of the ratio.
#[allow(clippy::needless_range_loop)] // t[variant][round], filled in a rotated order
fn paired(title: &str, mut variants: Vec<Timed<'_>>, n: usize, rounds: usize) {
    let k = variants.len();
    let mut t = vec![vec![0.0; rounds]; k];
    for (_, run) in variants.iter_mut() {
        run(n); // warm-up
    }
    for r in 0..rounds {
        for i in 0..k {
            let v = (i + r) % k;
            t[v][r] = (variants[v].1)(n);
        }
    }
    println!("| {title} | median per step | ratio to `{}` (median of per-round ratios) |", variants[0].0);
    println!("|---|---:|---:|");
    for v in 0..k {
        let ratio = median((0..rounds).map(|r| t[v][r] / t[0][r]).collect());
        println!("| `{}` | {} | {ratio:.2} |", variants[v].0, fmt_ns(median(t[v].clone())));
    }
    println!();
}

fn paired_all(rounds: usize) {
    let p = rhombic::PARAMS;
    let g = rhombic::initial_guess(&p);
    let closed = ClosedForm::new(&p);
    let kl = Kinloop::<_, 0>::new(p.kinloop());
    let named = KinloopNamed::new(p.kinloop());
    let two = TwoLoopNewton { p };
    let hand = DenseHandJacobian { p };
    let dual = DenseNumDual { p };
    let fd = DenseFiniteDifference { p };
    let p4 = class_four::PARAMS;
    let hand4 = HandNewton { p: p4 };
    let kl4 = Kinloop::<_, 0>::new(p4.kinloop());
    let named4 = KinloopNamed::new(p4.kinloop());
    let g4 = class_four::INITIAL_GUESS;
    for policy in WarmStart::ALL {
        let mut variants = vec![
            timed("closed_form", &closed, policy, g),
            timed("kinloop", &kl, policy, g),
            timed("kinloop_named", &named, policy, g),
            timed("two_loop_newton", &two, policy, g),
            timed("dense_hand_jacobian", &hand, policy, g),
            timed("dense_num_dual", &dual, policy, g),
            timed("dense_finite_difference", &fd, policy, g),
        ];
        let mut variants4 = vec![
            timed("hand_newton", &hand4, policy, g4),
            timed("kinloop", &kl4, policy, g4),
            timed("kinloop_named", &named4, policy, g4),
        ];
        if measured_with(SWEEP, policy) {
            variants.insert(3, timed_sweep(&kl.m, g, STEPS));
            variants4.push(timed_sweep(&kl4.m, g4, STEPS));
        }
        paired(&format!("rhombic drive, {} warm start", policy.name()), variants, 100_000, rounds);
        paired(&format!("class IV, {} warm start", policy.name()), variants4, 50_000, rounds);
    }
}

/// Times each closed-form row by [`paired`]: the hand closed form, kinloop's point step from
/// the previous position, kinloop's own sweep and the sweep recipe written by hand, along turns
/// of [`TURN_720`] steps.
struct PairedRows(usize);

impl RowVisitor for PairedRows {
    fn row<
        M: Mechanism<N, 1, NO>,
        H: Stepper<N>,
        S: HandSweep<N, NP>,
        const N: usize,
        const NO: usize,
        const NP: usize,
    >(
        &mut self,
        _name: &str,
        title: &str,
        m: M,
        hand: &H,
        sweep: S,
        guess0: [f64; N],
    ) {
        let policy = WarmStart::Previous;
        let kl = Kinloop::<M, NO>::new(m);
        let variants = vec![
            timed_turn("closed_form", hand, policy, guess0, TURN_720),
            timed_turn("kinloop", &kl, policy, guess0, TURN_720),
            timed_sweep(&kl.m, guess0, TURN_720),
            timed_hand_sweep(sweep),
        ];
        paired(&format!("{title}, {TURN_720} steps a turn"), variants, 100_000, self.0);
    }
}

/// Prints the iterations and deviations from the hand closed form of kinloop's point step
/// (previous position), of its own sweep and of the sweep recipe written by hand over one turn
/// of [`TURN_720`] steps.
struct CheckedRows;

impl RowVisitor for CheckedRows {
    fn row<
        M: Mechanism<N, 1, NO>,
        H: Stepper<N>,
        S: HandSweep<N, NP>,
        const N: usize,
        const NO: usize,
        const NP: usize,
    >(
        &mut self,
        _name: &str,
        title: &str,
        m: M,
        hand: &H,
        sweep: S,
        guess0: [f64; N],
    ) {
        let kl = Kinloop::<M, NO>::new(m);
        let point = check_sweep(&kl, hand, TURN_720, WarmStart::Previous, guess0);
        println!("| {title}: `kinloop` | {} |", iteration_cells(point));
        println!("| {title}: `{SWEEP}` | {} |", iteration_cells(check_kinloop_sweep(&kl.m, hand, TURN_720, guess0)));
        println!("| {title}: `{HAND_SWEEP}` | {} |", iteration_cells(check_hand_sweep(sweep, hand, guess0)));
    }
}

/// The closed-form rows and the class IV block at [`TURN_720`] steps a turn, checked against
/// their hand references over one turn.
fn iterations_720() {
    println!("| variant | Newton iterations per step | max deviation q / dq / d2q |");
    println!("|---|---:|---:|");
    closed_form_rows(&mut CheckedRows);
    let p4 = class_four::PARAMS;
    let (hand4, g4) = (HandNewton { p: p4 }, class_four::INITIAL_GUESS);
    let kl4 = Kinloop::<_, 0>::new(p4.kinloop());
    let check = check_sweep(&kl4, &hand4, TURN_720, WarmStart::Previous, g4);
    println!("| class IV block: `kinloop` | {} |", iteration_cells(check));
    let check = check_sweep(&hand4, &hand4, TURN_720, WarmStart::Previous, g4);
    println!("| class IV block: `hand_newton` | {} |", iteration_cells(check));
    println!();
}

/// The closed-form rows and the class IV block at [`TURN_720`] steps a turn (the mechanism
/// values of `closed_form_step` and of the criterion groups).
fn paired_closed_form(rounds: usize) {
    closed_form_rows(&mut PairedRows(rounds));
    let p4 = class_four::PARAMS;
    let (hand4, kl4, g4) = (HandNewton { p: p4 }, Kinloop::<_, 0>::new(p4.kinloop()), class_four::INITIAL_GUESS);
    let variants = vec![
        timed_turn("hand_newton", &hand4, WarmStart::Previous, g4, TURN_720),
        timed_turn("kinloop", &kl4, WarmStart::Previous, g4, TURN_720),
    ];
    paired(&format!("class IV, previous warm start, {TURN_720} steps a turn"), variants, 50_000, rounds);
}

fn main() {
    let args = args();
    let dir = args.dir.clone();
    let callgrind = args
        .callgrind
        .as_deref()
        .map(|f| read_callgrind(f).unwrap_or_else(|e| exit_with(&format!("cannot read {}: {e}", f.display()))));
    println!("<!-- generated by `cargo run --release -p kinloop-bench --bin report` from {} -->\n", dir.display());
    println!("### Rhombic drive (paper 000): one full kinematic step\n");
    timing_table(&dir, "rhombic", &RHOMBIC, "closed_form");
    println!("### Class IV mechanism (paper 003): one full kinematic step of the coupled 4x4 block\n");
    timing_table(&dir, "class_four", &CLASS_FOUR, "hand_newton");
    println!("### Closed-form rows: criterion time and callgrind instructions, {TURN_720} steps a turn\n");
    closed_form_table(&dir, callgrind.as_ref());
    if let Some(counts) = &callgrind {
        println!("### Instruction counts of the other rows (callgrind), {TURN_720} steps a turn unless said\n");
        count_table(counts);
    }
    println!("### The ratios of the targets\n");
    speedups(&dir);
    println!("### Newton iterations and accuracy over one turn of {STEPS} steps (release build)\n");
    iterations();
    println!("### Closed-form rows: iterations and accuracy over one turn of {TURN_720} steps (release build)\n");
    iterations_720();
    println!("### Macro expansion\n");
    sizes(&dir);
    if args.paired {
        println!("### Paired (interleaved) timing, 41 rounds\n");
        paired_all(41);
        paired_closed_form(41);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<HashMap<String, f64>, String> {
        // One file per call: the tests run in parallel threads of one process.
        static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!("kinloop-report-callgrind-{}-{call}.txt", std::process::id()));
        std::fs::write(&path, text).unwrap();
        let counts = read_callgrind(&path);
        std::fs::remove_file(&path).unwrap();
        counts
    }

    #[test]
    fn callgrind_counts_are_read_from_variant_lines() {
        let counts = parse("# a comment\n\nhand 575\n  four-bar-point   991  \n").unwrap();
        assert_eq!(counts.len(), 2);
        assert_eq!(counts["hand"], 575.0);
        assert_eq!(counts["four-bar-point"], 991.0);
    }

    #[test]
    fn malformed_callgrind_lines_are_errors_naming_the_line() {
        for bad in ["hand\n", "hand 575 extra\n", "hand many\n", "hand NaN\n", "hand -3\n"] {
            let e = parse(&format!("point 813\n{bad}")).unwrap_err();
            assert!(e.starts_with("line 2:"), "{bad:?}: {e}");
        }
    }

    /// `benches/callgrind.sh` measures by default every variant a table of the report names, so
    /// one run of it fills both tables.
    #[test]
    fn the_script_measures_every_variant_the_tables_name() {
        let script = include_str!("../../callgrind.sh");
        // The default list (the first `variants=(` takes the command line's).
        let start = script.rfind("variants=(").expect("the script's default list");
        let list: Vec<&str> = script[start + "variants=(".len()..]
            .split(')')
            .next()
            .expect("the list closes")
            .split_whitespace()
            .collect();
        let named = CLOSED_FORM_ROWS
            .iter()
            .flat_map(|r| r.variants.iter().map(|v| v.1))
            .chain(COUNT_ROWS.iter().flat_map(|r| [r.variant, r.reference]));
        for v in named {
            assert!(list.contains(&v), "callgrind.sh does not measure `{v}` by default");
        }
    }

    #[test]
    fn every_closed_form_row_starts_with_its_reference() {
        for row in &CLOSED_FORM_ROWS {
            assert!(["closed_form", "hand_newton"].contains(&row.variants[0].0), "{}", row.group);
            assert!(row.variants[1..].iter().all(|(b, _)| !["closed_form", "hand_newton"].contains(b)));
        }
    }
}
