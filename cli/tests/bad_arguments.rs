//! Every command's options given what they do not take: numbers out of range (0, negative,
//! 1e30, beyond `f64`, below its subnormals, NaN, infinities, text), ranges backwards or empty,
//! names of nothing, parameters misspelt or not finite, files missing or directories, outputs
//! that cannot be created. Each run ends (a hang shows as a test that does not end; no test reads the clock) with one of the
//! documented exit codes, never a panic (101) or a signal; a failure says why on standard
//! error, naming the option or the value given; a success writes no NaN or infinity.

mod common;

use common::shipped;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// What an option takes, and so which wrong values it is given.
#[derive(Clone, Copy, Debug)]
enum Takes {
    /// A number (`--speed`, `--roller`).
    Number,
    /// A count (`--samples`, `--starts`).
    Count,
    /// Numbers separated by commas (`--from`, `--at`, `--guide`).
    List,
    /// A name of the declaration (`--point`, `--columns`).
    Name,
    /// `name=value,...` (`--params`).
    Params,
    /// `name=lo..hi,...` (`--vary`) or `lo..hi` (`--range`).
    Ranges,
    /// A file read (the declaration, `--targets`).
    Input,
    /// A file written (`--events`, `--out`).
    Output,
}

/// Wrong numbers: zeros, negatives, beyond and below `f64`'s range, not numbers.
const NUMBERS: &[&str] = &["0", "-1", "1e30", "-1e308", "1e309", "1e-320", "1e-400", "NaN", "-inf", "", "abc", "1,2"];

/// Wrong counts: none, negative, fractional, written as floats, beyond the limits and any
/// integer type.
const COUNTS: &[&str] =
    &["0", "1", "-1", "1.5", "1e30", "NaN", "", "10000001", "18446744073709551615", "18446744073709551616"];

/// Wrong lists of numbers: empty, too many, not finite, not numbers, separated otherwise.
const LISTS: &[&str] = &[
    "", ",", "1,2,3", "nan", "inf", "-inf", "1e309", "1e-400", "a", "0;1", "1e308", "-1e308", "0,nan", "1e300", "1,,2",
];

/// Names of nothing, of what is not a point, and not names.
const NAMES: &[&str] = &["", "nope", "phi", "p.x", "😀", "a,a", "kind"];

/// Wrong parameter lists, `P` standing for a parameter of the declaration.
const PARAMS: &[&str] =
    &["P=", "=1", "P", "P=nan", "P=inf", "P=1e-400", "zz=1", "P=1,P=2", "P=0", "P=-1", "P=1e308", ",,,", "P=1=2"];

/// Wrong ranges.
const RANGES: &[&str] = &[
    "",
    "a=1..0",
    "a=1..1",
    "a=0..1e309",
    "a=nan..1",
    "a=..1",
    "a=1",
    "zz=0..1",
    "a=-inf..inf",
    "1..0",
    "0..0",
    "nan..1",
    "0..1e309",
    "a=0.8..1.4,a=2..3",
    "c=0..1e308",
];

/// One command line, and the options of it that are replaced by wrong values.
struct Base {
    args: Vec<String>,
    options: Vec<(&'static str, Takes)>,
}

fn base(args: &[&str], options: &[(&'static str, Takes)]) -> Base {
    Base { args: args.iter().map(|s| s.to_string()).collect(), options: options.to_vec() }
}

/// The files the runs read and write, in a directory of their own.
struct Scratch {
    dir: PathBuf,
}

impl Scratch {
    /// A directory of its own for the runs of `user` (a worker, a test): the tests of this file
    /// run at once in one process, and one's scratch removed at its end must not be another's.
    fn new(user: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("kinloop-bad-arguments-{}-{user}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a scratch directory");
        // Targets on the coupler curve of `a = 1.1, b = 2.8` (the README's).
        let targets = "0.9661,1.4940\n1.2330,2.2071\n0.6814,2.4363\n-0.0985,2.1152\n-0.6145,1.4192\n-0.6820,0.7191\n";
        std::fs::write(dir.join("points.csv"), targets).expect("targets");
        std::fs::write(dir.join("not_utf8.kl"), b"pub struct X { params a = 1\xff; }").expect("a binary file");
        std::fs::write(dir.join("empty.kl"), "").expect("an empty file");
        std::fs::create_dir_all(dir.join("a_directory.kl")).expect("a directory");
        Scratch { dir }
    }

    fn path(&self, name: &str) -> String {
        self.dir.join(name).display().to_string()
    }

    /// Files that cannot be read as a declaration or targets.
    fn inputs(&self) -> Vec<String> {
        vec![
            self.path("missing.kl"),
            self.path("a_directory.kl"),
            self.path("not_utf8.kl"),
            self.path("empty.kl"),
            "/dev/null".to_string(),
            "/dev/zero".to_string(),
            String::new(),
        ]
    }

    /// Files that cannot be written: a directory, in a directory that does not exist, where
    /// nothing may be created, a device full, the declaration itself, nothing.
    fn outputs(&self, declaration: &str) -> Vec<String> {
        vec![
            self.path("a_directory.kl"),
            self.path("no/such/dir/out.svg"),
            "/proc/kinloop-cannot-be-here.svg".to_string(),
            "/dev/full".to_string(),
            declaration.to_string(),
            String::new(),
            self.path("out.unknown"),
        ]
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The commands, each with a command line that succeeds and its options to make wrong.
fn bases(s: &Scratch) -> Vec<Base> {
    use Takes::*;
    let (four_bar, rhombic, slider) = (shipped("four_bar.kl"), shipped("rhombic_drive.kl"), shipped("slider_crank.kl"));
    let (engine, cam, five_bar, coupler) =
        (shipped("engine.kl"), shipped("dwell_cam.kl"), shipped("five_bar.kl"), shipped("coupler_four_bar.kl"));
    let (events, out_svg, out_html, plot, flywheel) =
        (s.path("events.csv"), s.path("anim.svg"), s.path("grid.html"), s.path("cam.svg"), s.path("flywheel.csv"));
    let targets = s.path("points.csv");
    let fb = "a=1,b=3,c=2.5,d=3.2";
    vec![
        base(&["check", &rhombic], &[("FILE", Input)]),
        base(
            &["solve", &four_bar, "--params", fb, "--at", "30", "--deg"],
            &[("FILE", Input), ("--params", Params), ("--at", List)],
        ),
        base(
            &[
                "sweep",
                &four_bar,
                "--params",
                fb,
                "--from",
                "0",
                "--to",
                "360",
                "--samples",
                "13",
                "--deg",
                "--events",
                &events,
            ],
            &[
                ("--from", List),
                ("--to", List),
                ("--samples", Count),
                ("--events", Output),
                ("--singular-pivot", Number),
                ("--params", Params),
            ],
        ),
        base(
            &[
                "trace",
                &four_bar,
                "--params",
                "a=3,b=2,c=2.5,d=4",
                "--from",
                "0",
                "--to",
                "180",
                "--deg",
                "--ds",
                "0.05",
                "--max-points",
                "200",
            ],
            &[("--from", List), ("--to", List), ("--ds", Number), ("--max-points", Count), ("--events", Output)],
        ),
        base(
            &[
                "extremes",
                &slider,
                "--params",
                "r=1,l=3,e=0.4",
                "--from",
                "0",
                "--to",
                "360",
                "--deg",
                "--samples",
                "13",
            ],
            &[("--from", List), ("--to", List), ("--samples", Count), ("--columns", Name), ("--params", Params)],
        ),
        base(
            &["dynamics", &engine, "--speed", "150", "--delta", "0.02", "--samples", "36", "--flywheel", &flywheel],
            &[
                ("--speed", Number),
                ("--start", Number),
                ("--samples", Count),
                ("--delta", Number),
                ("--about", List),
                ("--flywheel", Output),
                ("--params", Params),
            ],
        ),
        // A budget of 20,000 steps (the run takes about 35): the wrong values that ask for more
        // steps than any budget holds (`--speed 1e30`, `--torque 1e30`, `--time 1e30`) spend it
        // and are refused by the same message in a fiftieth of the time the default million
        // took (about 50 s each in a debug build, half this test's time).
        base(
            &[
                "simulate",
                &engine,
                "--speed",
                "150",
                "--torque",
                "2.5",
                "--flywheel",
                "0.05",
                "--time",
                "0.02",
                "--samples",
                "5",
                "--max-steps",
                "20000",
            ],
            &[
                ("--speed", Number),
                ("--start", Number),
                ("--time", Number),
                ("--torque", Number),
                ("--flywheel", Number),
                ("--samples", Count),
                ("--max-steps", Count),
                ("--params", Params),
            ],
        ),
        base(
            &[
                "cam",
                &cam,
                "--point",
                "follower",
                "--guide",
                "0,1",
                "--roller",
                "10",
                "--deg",
                "--samples",
                "37",
                "--plot",
                &plot,
            ],
            &[
                ("--point", Name),
                ("--guide", List),
                ("--rocker", List),
                ("--pivot", List),
                ("--roller", Number),
                ("--flat", Number),
                ("--face-offset", Number),
                ("--start", Number),
                ("--samples", Count),
                ("--plot", Output),
                ("--params", Params),
            ],
        ),
        base(
            &["animate", &rhombic, "--from", "0", "--to", "360", "--deg", "--samples", "13", "--out", &out_svg],
            &[
                ("--from", List),
                ("--to", List),
                ("--samples", Count),
                ("--out", Output),
                ("--show", Name),
                ("--frames", Count),
                ("--cam", Name),
            ],
        ),
        base(
            &["animate", &five_bar, "--grid", "--from", "0,0.4", "--to", "3,3", "--samples", "3,3", "--out", &out_html],
            &[("--from", List), ("--to", List), ("--samples", List), ("--out", Output), ("--show", Name)],
        ),
        base(
            &[
                "synth",
                &coupler,
                "--targets",
                &targets,
                "--path",
                "p",
                "--vary",
                "a=0.8..1.4,b=2..3.5",
                "--starts",
                "2",
                "--jobs",
                "1",
                "--keep",
                "2",
            ],
            &[
                ("FILE", Input),
                ("--targets", Input),
                ("--path", Name),
                ("--function", Name),
                ("--vary", Ranges),
                ("--range", Ranges),
                ("--starts", Count),
                ("--seed", Count),
                ("--keep", Count),
                ("--jobs", Count),
                ("--max-error", Number),
                ("--params", Params),
            ],
        ),
    ]
}

/// `args` with `option`'s value replaced by `value` (added where not given); `FILE`, the
/// declaration, is the second argument.
fn with(args: &[String], option: &str, value: &str) -> Vec<String> {
    let mut out = args.to_vec();
    if option == "FILE" {
        out[1] = value.to_string();
    } else if let Some(k) = out.iter().position(|a| a == option) {
        out[k + 1] = value.to_string();
    } else {
        out.extend([option.to_string(), value.to_string()]);
    }
    out
}

/// The wrong values of what an option takes.
fn values(takes: Takes, s: &Scratch, declaration: &str, param: &str) -> Vec<String> {
    let own = |v: &[&str]| v.iter().map(|s| s.replace('P', param)).collect();
    match takes {
        Takes::Number => own(NUMBERS),
        Takes::Count => own(COUNTS),
        Takes::List => own(LISTS),
        Takes::Name => own(NAMES),
        Takes::Params => own(PARAMS),
        Takes::Ranges => own(RANGES),
        Takes::Input => s.inputs(),
        Takes::Output => s.outputs(declaration),
    }
}

/// The exit codes `kinloop` documents.
const CODES: &[i32] = &[0, 1, 2, 65, 66, 69, 73, 74];

/// Runs `kinloop` with `args`: its exit code (`None` for a signal), standard output and
/// standard error.
fn run(args: &[String]) -> (Option<i32>, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_kinloop"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("kinloop runs");
    // Read on threads, so that a full pipe does not stall the child.
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            let _ = r.read_to_end(&mut v);
            String::from_utf8_lossy(&v).into_owned()
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("stdout")));
    let err = drain(Box::new(child.stderr.take().expect("stderr")));
    let status = child.wait().expect("wait");
    (status.code(), out.join().unwrap_or_default(), err.join().unwrap_or_default())
}

/// What is wrong with one run's outcome, if anything.
fn judge(option: &str, value: &str, code: Option<i32>, out: &str, err: &str) -> Option<String> {
    let Some(code) = code else { return Some(format!("killed by a signal; stderr: {err}")) };
    if err.contains("panicked") || !CODES.contains(&code) {
        return Some(format!("exit code {code}: {err}"));
    }
    if code != 0 && err.trim().is_empty() {
        return Some(format!("exit code {code} and nothing said"));
    }
    // A usage error names what was wrong: the option, the value given or a name in it, or
    // another option it does not go with.
    if code == 2 && option != "FILE" {
        let given = value.trim();
        let mut pieces = given.split([',', '=', '.']).map(str::trim).filter(|p| !p.is_empty());
        let named = err.contains(option)
            || (!given.is_empty() && err.contains(given))
            || pieces.any(|p| err.contains(&format!("`{p}`")))
            || err.contains(" --");
        if !named {
            return Some(format!("a usage error naming neither {option} nor `{value}`: {err}"));
        }
    }
    if code == 0 {
        let fields = out.split([',', '\n', ' ']).map(str::trim);
        if let Some(bad) = fields.clone().find(|f| matches!(f.to_ascii_lowercase().as_str(), "nan" | "inf" | "-inf")) {
            return Some(format!("succeeded writing `{bad}`"));
        }
    }
    None
}

#[test]
fn wrong_arguments_are_refused_in_words_never_a_panic_or_a_hang() {
    // The runs are independent processes, shared among workers (each with its own scratch
    // directory, so that no two runs write the same output file at once): each worker takes the
    // next run not yet taken, so that the slow commands (a synthesis, a simulation) do not fall
    // to one worker.
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get().min(4));
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results: Vec<(usize, Vec<String>)> = std::thread::scope(|scope| {
        let next = &next;
        let handles: Vec<_> = (0..workers).map(|w| scope.spawn(move || runs_of_worker(w, next))).collect();
        handles.into_iter().map(|h| h.join().expect("a worker")).collect()
    });
    let runs: usize = results.iter().map(|r| r.0).sum();
    let failures: Vec<String> = results.into_iter().flat_map(|r| r.1).collect();
    eprintln!("{runs} runs");
    assert!(failures.is_empty(), "{} runs failed:\n{}", failures.len(), failures.join("\n"));
}

/// One run of a command: its command line succeeding as given (`None`), or with one option's
/// wrong value.
struct Job {
    args: Vec<String>,
    wrong: Option<(&'static str, String)>,
}

/// Every run, in one order for every worker: each command as given, then with each wrong value.
fn jobs(s: &Scratch) -> Vec<Job> {
    let mut jobs = Vec::new();
    for b in bases(s) {
        let declaration = b.args[1].clone();
        let param = first_param(&declaration);
        for (option, takes) in &b.options {
            for value in values(*takes, s, &declaration, &param) {
                jobs.push(Job { args: with(&b.args, option, &value), wrong: Some((option, value)) });
            }
        }
        jobs.push(Job { args: b.args, wrong: None });
    }
    jobs
}

/// The runs the worker `worker` takes from `next` (the index of the next run not yet taken):
/// how many with a wrong value, and what was wrong with each that failed.
fn runs_of_worker(worker: usize, next: &std::sync::atomic::AtomicUsize) -> (usize, Vec<String>) {
    let s = Scratch::new(&format!("worker-{worker}"));
    let jobs = jobs(&s);
    let mut failures = Vec::new();
    let mut runs = 0;
    while let Some(job) = jobs.get(next.fetch_add(1, std::sync::atomic::Ordering::Relaxed)) {
        let (code, out, err) = run(&job.args);
        match &job.wrong {
            // The command line itself succeeds: the wrong values alone make its runs fail.
            None => assert_eq!(code, Some(0), "{:?}: {err}", job.args),
            Some((option, value)) => {
                runs += 1;
                if let Some(problem) = judge(option, value, code, &out, &err) {
                    failures.push(format!("kinloop {}: {problem}", shown(&job.args)));
                }
            }
        }
    }
    (runs, failures)
}

/// The first parameter the declaration `file` lists (what `P` stands for in [`PARAMS`]).
fn first_param(file: &str) -> String {
    let text = std::fs::read_to_string(file).expect("the declaration");
    let after = text.split_once("params").map_or("", |(_, rest)| rest);
    after.trim_start().split([' ', ',', '=', ';']).next().unwrap_or("a").to_string()
}

/// A command line as typed, quoted where needed.
fn shown(args: &[String]) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).display().to_string();
    args.iter()
        .map(|a| a.replace(&root, "cli"))
        .map(|a| if a.is_empty() || a.contains([' ', ',', ';']) { format!("'{a}'") } else { a })
        .collect::<Vec<_>>()
        .join(" ")
}

/// An item of `--params` without a name (`=1`, a name lost in editing) is refused naming the
/// option and the item, where it was "FourBar has no parameter ``" with its list of parameters.
#[test]
fn a_parameter_without_a_name_is_refused_naming_params() {
    let four_bar = shipped("four_bar.kl");
    for list in ["=1", "a=1,b=3, = 2.5,d=3.2"] {
        let out = common::kinloop(&["solve", &four_bar, "--at", "0", "--params", list]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{list}: {err}");
        assert!(err.contains("in --params has no name before `=`"), "{list}: {err}");
        assert!(!err.contains("parameter ``"), "{list}: {err}");
    }
}

/// A parameter typed with a Cyrillic letter that looks like a Latin one (`а`, U+0430, for `a`:
/// a keyboard left on another layout) is refused naming the letter, its code point and the
/// parameter meant, where it was "no parameter `а`" beside a list holding `a`, the two alike.
#[test]
fn a_parameter_typed_with_a_look_alike_letter_names_the_letter_and_the_parameter() {
    let four_bar = shipped("four_bar.kl");
    let out = common::kinloop(&["solve", &four_bar, "--at", "0", "--params", "\u{430}=1,b=3,c=2.5,d=3.2"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains(
            "no parameter `\u{430}`: `\u{430}` (U+0430) is a Cyrillic letter that looks like the Latin `a`; write `a`"
        ),
        "{err}"
    );
    assert!(err.contains("(its parameters: a, b, c, d)"), "{err}");
    // A name wrong in ASCII letters is told as before, without a word of scripts.
    let out = common::kinloop(&["solve", &four_bar, "--at", "0", "--params", "q=1,b=3,c=2.5,d=3.2"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("has no parameter `q` (its parameters: a, b, c, d)"), "{err}");
}

/// Every other option that takes a declared name says the same of a look-alike letter: a
/// column of `extremes` and of `animate --show`, a point of `--path` (as of `--point`), a design
/// variable of `--vary` and the output of `--function` (whose messages come from the library,
/// the note added after its list).
#[test]
fn every_declared_name_typed_with_a_look_alike_letter_names_the_letter() {
    let s = Scratch::new("look_alike");
    let (four_bar, coupler) = (shipped("four_bar.kl"), shipped("coupler_four_bar.kl"));
    let (points, values, page) = (s.path("points.csv"), s.path("values.csv"), s.path("page.html"));
    std::fs::write(&points, "0.5,2.0,1.0\n1.0,1.5,1.8\n1.5,0.8,2.2\n2.0,0.2,2.1\n").unwrap();
    std::fs::write(&values, "0,1\n1,1.2\n2,1.4\n3,1.5\n").unwrap();
    let params = "a=1,b=3,c=2.5,d=3.2";
    let synth = ["synth", &coupler, "--starts", "1", "--jobs", "1"];
    let cases: [(Vec<&str>, &str); 5] = [
        (
            vec!["extremes", &four_bar, "--params", params, "--from", "0", "--to", "1", "--columns", "b\u{435}ta"],
            "no unknown or output `b\u{435}ta`: `\u{435}` (U+0435) is a Cyrillic letter that looks like the Latin `e`; \
             write `beta` (they are:",
        ),
        (
            vec!["animate", &coupler, "--from", "0", "--to", "1", "--show", "g\u{430}mma", "--out", &page],
            "(`\u{430}` (U+0430) is a Cyrillic letter that looks like the Latin `a`; write `gamma`)",
        ),
        (
            [&synth[..], &["--targets", &points, "--path", "\u{440}", "--vary", "a=0.8..1.4"]].concat(),
            "no point of that name: `\u{440}` (U+0440) is a Cyrillic letter that looks like the Latin `p`; write `p`",
        ),
        (
            [&synth[..], &["--targets", &points, "--path", "p", "--vary", "\u{430}=0.8..1.4"]].concat(),
            "(`\u{430}` (U+0430) is a Cyrillic letter that looks like the Latin `a`; write `a`)",
        ),
        (
            [&synth[..], &["--targets", &values, "--function", "phi:g\u{430}mma", "--vary", "a=0.8..1.4"]].concat(),
            "(`\u{430}` (U+0430) is a Cyrillic letter that looks like the Latin `a`; write `gamma`)",
        ),
    ];
    for (args, said) in cases {
        let out = common::kinloop(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(said), "{args:?}: {err}");
    }
}

/// A design variable given twice in `--vary` is refused naming the option, where the library's
/// "the parameter `a` is named twice" named none.
#[test]
fn a_design_variable_given_twice_is_refused_naming_vary() {
    let s = Scratch::new("vary");
    let targets = s.path("points.csv");
    let coupler = shipped("coupler_four_bar.kl");
    let args = ["synth", &coupler, "--targets", &targets, "--path", "p", "--starts", "1", "--jobs", "1"];
    let out = common::kinloop(&[&args[..], &["--vary", "a=0.8..1.4, a=2..3"]].concat());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("`a` is given twice in --vary"), "{err}");
}

/// `--flat` takes an optional angle: a negative one that clap does not take for a number
/// (`-inf`, `-1e-400`) is its value all the same, refused by its own check, where clap called it
/// an unexpected argument `-i` and said to pass it after `--` (which makes it a file name).
#[test]
fn a_negative_flat_angle_is_the_options_value() {
    let cam = shipped("dwell_cam.kl");
    for (angle, says) in [("-inf", "--flat -inf"), ("-1e-400", "too small for a 64-bit float")] {
        let out = common::kinloop(&["cam", &cam, "--point", "follower", "--guide", "0,1", "--flat", angle]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{angle}: {err}");
        assert!(err.contains(says) && !err.contains("unexpected argument"), "{angle}: {err}");
    }
}

/// An angle parameter beyond the largest angle a solve takes precisely (`phi0=1e17` of the
/// dwell cam) is a usage error of every command that solves, naming the parameter and saying to
/// give it less whole turns with `--params`; `check` says the same of the motion it cannot
/// tell. It failed each solve with exit code 1 and the library's advice, `phi0.rem_euclid(TAU)`,
/// Rust a command line cannot follow.
#[test]
fn an_angle_parameter_too_large_to_solve_precisely_is_a_usage_error() {
    let cam = shipped("dwell_cam.kl");
    let runs: [&[&str]; 4] = [
        &["solve", &cam, "--at", "0"],
        &["sweep", &cam, "--from", "0", "--to", "1"],
        &["extremes", &cam, "--from", "0", "--to", "1"],
        &["cam", &cam, "--point", "follower", "--guide", "0,1"],
    ];
    for args in runs {
        let out = common::kinloop(&[args, &["--params", "phi0=1e17"]].concat());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("parameter `phi0` is an angle of 1e17 rad"), "{args:?}: {err}");
        assert!(err.contains("give it less whole turns") && err.contains("--params phi0=VALUE"), "{args:?}: {err}");
        assert!(!err.contains("rem_euclid") && out.stdout.is_empty(), "{args:?}: {err}");
    }
    let out = common::kinloop(&["check", &cam, "--params", "phi0=1e17"]);
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(report.contains("motion: not determined: parameter `phi0` is an angle of 1e17 rad"), "{report}");
    assert!(report.contains("--params phi0=VALUE") && !report.contains("rem_euclid"), "{report}");
    // Within the bound (a few turns out) it solves as before.
    let out = common::kinloop(&["solve", &cam, "--at", "0", "--params", "phi0=12.7"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}
