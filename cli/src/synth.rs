//! `kinloop synth`: dimensional synthesis of a declaration read at run time, the library's
//! synthesis (`kinloop_runtime::synthesis`: Levenberg–Marquardt from Halton starts on the exact
//! Jacobian, every candidate verified by a branch-safe sweep through the targets) over the
//! model (`Model::shared_synthesis_problem`), on all cores (`Search::par_run`, each
//! evaluation on a clone of the model; the same candidates as one start after another,
//! `--jobs 1`). The targets come from a CSV file: points of a path (`x,y`, or `input,x,y` at
//! given inputs) or pairs of a function (`input,output`). The ranked candidates are written as
//! a table or as CSV, each with its defects.

use crate::csv_rows::unsigned_zero;
use crate::numbers::number;
use crate::own_columns::{self, Own};
use crate::{Failed, exit, params, progress};
use kinloop_model::{Count, Model};
use kinloop_runtime::paths::sweep::MAX_TURNS;
use kinloop_runtime::synthesis::{
    Candidate, Constraints, Defect, Design, Origin, Refused, Search, SynthesisError, SynthesisReport, Task,
    default_newton,
};
use kinloop_runtime::{Number, QuantityKind};
use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::path::Path;

/// The most threads `--jobs` starts: more than machines have cores. The pool starts every
/// thread before the first start is searched, and tens of thousands (a count typed with zeros
/// too many) take minutes to start.
pub const MAX_JOBS: usize = 1024;

/// The most starts a search takes: each is a local solve and a verifying sweep, milliseconds,
/// so a million take many minutes. The search lays out every start's job first: a count typed
/// with zeros too many would abort on that allocation.
pub const MAX_STARTS: usize = 1_000_000;

/// The columns `kinloop synth` writes of its own, around the design variables' (`max_error` and
/// `rms_error` with their unit in the header, `max_error [mm]`, read back as `max_error`).
const COLUMNS: [&str; 7] = ["rank", "start", "valid", "max_error", "rms_error", "evaluations", "defects"];

/// What `kinloop synth` was asked.
pub struct Request<'a> {
    /// The CSV file of the targets.
    pub targets: &'a Path,
    /// The point whose path is synthesised (`--path`).
    pub path: Option<&'a str>,
    /// `input:output` of a function generator (`--function`).
    pub function: Option<&'a str>,
    /// The design variables, `name=lo..hi` separated by commas.
    pub vary: &'a str,
    /// The input range of a path whose targets have no inputs, `lo..hi`.
    pub range: Option<&'a str>,
    /// Halton starts.
    pub starts: usize,
    /// The seed of the starts.
    pub seed: u64,
    /// The most candidates written (fewer where the starts reached fewer distinct designs).
    pub keep: usize,
    /// Threads of the search (`None`: all cores; 1: one start after another).
    pub jobs: Option<usize>,
    /// Angles in degrees (inputs, angle outputs, the range); otherwise radians.
    pub deg: bool,
    /// CSV instead of a table.
    pub csv: bool,
    /// The parameters given with `--params` (`name=value` separated by commas), already set in
    /// the model: read here for the names, none of which may be a design variable.
    pub params: Option<&'a str>,
    /// The largest error accepted at a target (`--max-error`), in the unit the errors are
    /// written.
    pub max_error: Option<f64>,
}

/// Runs the search and writes its ranked candidates: success when one is valid, exit code 1
/// when none is.
pub fn run(model: &mut Model, req: &Request) -> Result<(), Failed> {
    if req.keep == 0 {
        return Err(exit::usage("--keep 0 would write no candidate: keep at least 1"));
    }
    if req.starts == 0 {
        return Err(exit::usage("--starts 0 would search from no start: give at least 1 (e.g. --starts 64)"));
    }
    if req.starts > MAX_STARTS {
        return Err(exit::usage(format!("--starts {} is too many: at most {MAX_STARTS}", req.starts)));
    }
    if req.jobs == Some(0) {
        return Err(exit::usage("--jobs 0 would run no start: give at least 1"));
    }
    if let Some(n) = req.jobs.filter(|&n| n > MAX_JOBS) {
        return Err(exit::usage(format!(
            "--jobs {n} is too many threads: at most {MAX_JOBS} (without --jobs the search runs on every core)"
        )));
    }
    let design = design(req.vary)?;
    not_given_twice(&design, req.params)?;
    not_a_column(&design, model.name())?;
    // The search sets the design variables at every evaluation, so one without a value needs
    // none of its own; the model's kernel, built before, needs one for every parameter: any
    // within the bounds does.
    for v in design.variables() {
        if let Some(k) = model.params().iter().position(|p| *p == v.name)
            && model.param_values()[k].is_none()
        {
            model.set_param(&v.name, 0.5 * v.lo + 0.5 * v.hi);
        }
    }
    params::require_values(model)?;
    precise_angles(model, &design, default_newton().largest_precise_angle())?;
    let crate::targets::Targets { rows, lines, header } = crate::targets::read(req.targets)?;
    if let Some((line, (column, field, unit))) =
        header.as_ref().and_then(|(n, text)| Some((n, crate::targets::angle_unit(text, req.deg)?)))
    {
        let (given, instead) = match unit {
            "deg" => ("degrees", "give --deg (without it angles are read in radians)"),
            _ => ("radians", "leave out --deg (with it angles are read in degrees)"),
        };
        return Err(exit::usage(format!(
            "{} line {line}, column {column}: the header gives `{field}` in {given}: {instead}",
            req.targets.display()
        )));
    }
    let task = task(model, req, &rows)?;
    let name = model.name().to_string();
    let problem = model.shared_synthesis_problem(&design, &task).map_err(|e| problem_error(&name, e, req))?;
    let problem = match req.max_error {
        Some(max) => {
            if !(max.is_finite() && max > 0.0) {
                return Err(exit::usage(format!("--max-error {max} must be a finite number above 0")));
            }
            // In the library's units: an angle's error in radians. A bound so small that it is
            // 0 there is said in the unit typed (the library would name its 0).
            let max_typed = max;
            let max = max / Units::of(model, req).error;
            if max == 0.0 {
                return Err(exit::usage(format!(
                    "--max-error {} is 0 in radians: give a larger bound (in degrees with --deg)",
                    Number(max_typed)
                )));
            }
            let c = Constraints::default().with_max_error(max);
            problem.with_constraints(&c).map_err(|e| problem_error(&name, e, req))?
        }
        None => problem,
    };
    let search = Search::default().with_starts(0..req.starts).with_seed(req.seed).with_keep(req.keep);
    let bar = progress::bar_if(req.starts >= progress::MIN_STARTS, &format!("{name}: searching"), req.starts);
    let tick = |_: usize, _: usize| bar.inc(1);
    let report = match req.jobs {
        Some(1) => search.run_with_progress(&problem, tick),
        // A pool of its own: `--jobs N` threads.
        Some(n) => match rayon::ThreadPoolBuilder::new().num_threads(n).build() {
            Ok(pool) => pool.install(|| search.par_run_with_progress(&problem, tick)),
            Err(e) => return Err(exit::usage(format!("--jobs {n}: cannot start the threads: {e}"))),
        },
        // Rayon's global pool: all cores.
        None => search.par_run_with_progress(&problem, tick),
    };
    bar.finish_and_clear();
    let report = report.map_err(|e| problem_error(&name, e, req))?;
    let units = Units { lines, ..Units::of(model, req) };
    let text = if req.csv { csv(&report, &units) } else { table(&report, &units) };
    crate::output::text(&text, "the candidates")?;
    eprintln!("{}", summary(&report));
    for r in &report.refused {
        // The error again, from the refused start, for its inputs in the units written (the
        // report's message has them in radians).
        let message = match search.refine(&problem, &r.point) {
            Err(SynthesisError::Kinematics(e)) => crate::solve::in_units(e, model.input_kinds(), req.deg).to_string(),
            _ => r.message.clone(),
        };
        eprintln!("{}", refusal(&report.variables, r, &message));
    }
    if let Some(note) = out_of_reach(&report, &rows, &units, req.path.is_some()) {
        eprintln!("{note}");
    }
    if report.best().is_some() {
        Ok(())
    } else {
        eprintln!("error: {name}: no valid candidate");
        Err(Failed(exit::SOLVE_FAILED))
    }
}

/// A problem the library refuses: a usage error (names, bounds, targets), or a failed solve.
/// Too few targets is said in the command's terms (the library's message offers its Rust API).
fn problem_error(name: &str, e: SynthesisError, req: &Request) -> Failed {
    match e {
        SynthesisError::Kinematics(_) => {
            eprintln!("error: {name}: {e}");
            Failed(exit::SOLVE_FAILED)
        }
        SynthesisError::TooFewTargets { residuals, variables } => exit::usage(format!(
            "{name}: the targets in {} give {} for {} (the design variables of --vary, and an input per \
             target of a path without inputs): the design is not determined; give more targets, or vary fewer \
             parameters in --vary",
            req.targets.display(),
            Count(residuals, "equation"),
            Count(variables, "unknown")
        )),
        // A name refused for a look-alike letter of another script says so (the library's
        // message lists the names, which then read the same as the one refused).
        SynthesisError::UnknownVariable { name: ref given, ref params, .. }
        | SynthesisError::UnknownColumn { name: ref given, columns: ref params, .. } => {
            let known: Vec<&str> = params.split(", ").collect();
            exit::usage(format!("{name}: {e}{}", crate::names::look_alike_after(given, &known)))
        }
        e => exit::usage(format!("{name}: {e}")),
    }
}

/// Refuses an angle parameter beyond `bound`, the largest angle the search's solves take
/// precisely (its default Newton configuration's, tighter than a sweep's: about 4.5e4 rad), as the
/// other commands refuse one beyond theirs: a usage error naming the parameter, the bound and
/// the option that gives it. The search refused it as a failed synthesis (exit code 1) with the
/// library's advice, `phi0.rem_euclid(TAU)`, which a command line cannot follow. A design
/// variable is checked at its value nearest 0, as the search checks it: refused only where its
/// whole range lies beyond (a design within it is refused at its evaluation alone).
fn precise_angles(model: &Model, design: &Design, bound: f64) -> Result<(), Failed> {
    // The fixed parameters first, every design variable at 0 (no angle beyond any bound).
    let mut fixed = model.clone();
    for v in design.variables() {
        fixed.set_param(&v.name, 0.0);
    }
    if let Some(why) = params::imprecise_angle_within(&fixed, bound) {
        return Err(exit::usage(format!(
            "{}: {why}; the search solves to a tighter tolerance than the other commands, so its bound is smaller",
            model.name()
        )));
    }
    for v in design.variables() {
        fixed.set_param(&v.name, 0.0f64.clamp(v.lo, v.hi));
        if fixed.angle_param_beyond(bound).is_some() {
            return Err(exit::usage(format!(
                "{}: --vary {}={}..{}: every value is an angle beyond {} rad, the largest angle the search solves \
                 precisely, so an angle added to it is lost to rounding; give a range with less whole turns, within \
                 {} rad (in radians)",
                model.name(),
                v.name,
                Number(v.lo),
                Number(v.hi),
                Number(bound),
                Number(bound)
            )));
        }
        fixed.set_param(&v.name, 0.0);
    }
    Ok(())
}

/// Refuses a design variable also given a value with `--params`: the search sets it, so the
/// value would be dropped without a word.
fn not_given_twice(design: &Design, params: Option<&str>) -> Result<(), Failed> {
    let given = params.into_iter().flat_map(|p| p.split(',')).filter_map(|item| item.split_once('='));
    for (name, value) in given.map(|(n, v)| (n.trim(), v.trim())) {
        if let Some(v) = design.variables().iter().find(|v| v.name == name) {
            return Err(exit::usage(format!(
                "`{name}` is given in --params ({name}={value}) and varied in --vary ({name}={}..{}): the search \
                 sets a design variable, so its value would be ignored; leave it out of --params, or out of --vary \
                 to keep it fixed",
                v.lo, v.hi
            )));
        }
    }
    Ok(())
}

/// Refuses a design variable named as one of the columns the candidates are written with
/// beside it, before the run.
fn not_a_column(design: &Design, mechanism: &str) -> Result<(), Failed> {
    let own = Own {
        command: "kinloop synth",
        columns: &COLUMNS,
        beside: "design variables'",
        rename_to: " to vary it",
        written: "the candidates",
    };
    own_columns::check(&own, mechanism, design.variables().iter().map(|v| ("parameter", v.name.as_str())))
}

/// `lo..hi` as two finite numbers, lower first (`lo <= hi`; strictly lower where `strict`, as a
/// range of inputs needs, whose refusal says so: `2..1` was told `lo <= hi`, and then `1..1`
/// that it is empty).
fn bounds(spec: &str, what: &str, strict: bool) -> Result<(f64, f64), Failed> {
    let order = if strict { "<" } else { "<=" };
    let not_bounds = format!("{what} `{spec}` is not `lo..hi` with finite lo {order} hi");
    let Some((lo, hi)) = spec.split_once("..") else {
        return Err(exit::usage(not_bounds));
    };
    // Three dots (`0...5`) split as `0` and `.5`: read as 0..0.5 without a word, where 0..5 may
    // be meant.
    if hi.trim_start().starts_with('.') {
        return Err(exit::usage(format!(
            "{not_bounds}: it has three dots or more between the bounds; write two (`0..5`, or `0..0.5` for a bound of .5)"
        )));
    }
    match (number(lo), number(hi)) {
        (Ok(lo), Ok(hi)) if lo.is_finite() && hi.is_finite() && (lo < hi || (!strict && lo == hi)) => Ok((lo, hi)),
        (Err(e), _) | (_, Err(e)) => Err(exit::usage(format!("{not_bounds}: {e}"))),
        _ => Err(exit::usage(not_bounds)),
    }
}

/// `--vary a=0.5..3,b=1..4`.
fn design(vary: &str) -> Result<Design, Failed> {
    let mut d = Design::new();
    for item in vary.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let Some((name, range)) = item.split_once('=') else {
            return Err(exit::usage(format!("`{item}` in --vary is not `name=lo..hi`")));
        };
        let name = name.trim();
        // Said here, naming the option: the library's "named twice" named none.
        if d.variables().iter().any(|v| v.name == name) {
            return Err(exit::usage(format!("`{name}` is given twice in --vary: give each design variable once")));
        }
        let (lo, hi) = bounds(range, &format!("the range of `{name}` in --vary"), false)?;
        d = d.var(name, lo, hi);
    }
    if d.variables().is_empty() {
        return Err(exit::usage("--vary names no design variable"));
    }
    Ok(d)
}

/// An angle given in degrees with `--deg` in radians; any other value as it is. An angle so
/// many turns out that its radians round by more than a solve's precision is refused as the
/// other commands refuse it, naming the value as typed (`given` says where): converted without
/// a word, targets at 1e17 degrees were rejected as "no assembly".
fn angle_in(kind: QuantityKind, deg: bool, v: f64, given: impl FnOnce() -> String) -> Result<f64, Failed> {
    if deg && kind == QuantityKind::Angle { crate::solve::radians_of(v, &given()) } else { Ok(v) }
}

/// Where target `k` of the file `targets` gives `what` (`the input`), for [`angle_in`].
fn target_value(targets: &Path, k: usize, what: &str) -> String {
    format!("{}: target {k}'s {what}", targets.display())
}

/// The task of `--path` or `--function` over the rows.
fn task(model: &Model, req: &Request, rows: &[Vec<f64>]) -> Result<Task, Failed> {
    let (ni, input_kind) = (model.inputs().len(), model.input_kinds().first().copied());
    let width = rows[0].len();
    // Only targets without inputs move along a range: given with targets that carry their
    // inputs, it was ignored without a word.
    if let Some(r) = req.range
        && !(req.path.is_some() && width == 2)
    {
        return Err(exit::usage(format!(
            "--range {r} applies to --path targets without inputs (rows `x,y`); {} gives the inputs in its rows: \
             remove --range",
            req.targets.display()
        )));
    }
    match (req.path, req.function) {
        (Some(point), None) => {
            // Named here: the library would say that `POINT.x` is no column.
            crate::cam::point_columns(model, point, "--path")?;
            let xy = |r: &Vec<f64>| [r[width - 2], r[width - 1]];
            match width {
                2 => {
                    if ni != 1 {
                        return Err(exit::usage(format!(
                            "targets without inputs move one input along --range; `{}` has {ni}",
                            model.name()
                        )));
                    }
                    let kind = input_kind.unwrap_or(QuantityKind::Other);
                    let (lo, hi) = match req.range {
                        Some(r) => range_in(r, kind, req.deg)?,
                        None if kind == QuantityKind::Angle => (0.0, TAU),
                        None => return Err(exit::usage("targets without inputs need --range lo..hi")),
                    };
                    one_point_untimed(rows, req.targets)?;
                    Ok(Task::path(point, rows.iter().map(xy)).untimed(lo, hi))
                }
                w if w == ni + 2 => {
                    let (kinds, names) = (model.input_kinds(), model.inputs());
                    let input = |t: usize, i: usize| {
                        let what = if ni == 1 { "input".to_string() } else { format!("input `{}`", names[i]) };
                        angle_in(kinds[i], req.deg, rows[t][i], || target_value(req.targets, t, &what))
                    };
                    let inputs = (0..rows.len())
                        .map(|t| (0..ni).map(|i| input(t, i)).collect::<Result<Vec<f64>, Failed>>())
                        .collect::<Result<Vec<_>, Failed>>()?;
                    Ok(Task::path(point, rows.iter().map(xy)).timed_inputs(inputs))
                }
                _ => Err(exit::usage(format!(
                    "--path targets are rows `x,y` or `{}x,y`: {} has {} per row",
                    "input,".repeat(ni),
                    req.targets.display(),
                    Count(width, "value")
                ))),
            }
        }
        (None, Some(spec)) => {
            let Some((input, output)) = spec.split_once(':').map(|(a, b)| (a.trim(), b.trim())) else {
                return Err(exit::usage(format!("--function `{spec}` is not `input:output`")));
            };
            // A function generator moves one input: a mechanism of several was told its input
            // `th1` "is not the one input", as if misspelt.
            if ni != 1 {
                return Err(exit::usage(format!(
                    "--function generates a function of one input, and `{}` has {ni} ({}): synthesize the path of a \
                     point at given inputs instead (--path POINT, targets `{}x,y`)",
                    model.name(),
                    model.inputs().join(", "),
                    "input,".repeat(ni)
                )));
            }
            if model.inputs()[0] != input {
                return Err(exit::usage(format!(
                    "--function: `{input}` is not the input of `{}` (its input: {}); write --function {}:OUTPUT",
                    model.name(),
                    model.inputs()[0],
                    model.inputs()[0]
                )));
            }
            if width != 2 {
                return Err(exit::usage(format!(
                    "--function targets are rows `input,output`: {} has {} per row",
                    req.targets.display(),
                    Count(width, "value")
                )));
            }
            let out_kind = column_kind(model, output).unwrap_or(QuantityKind::Other);
            let kind = input_kind.unwrap_or(QuantityKind::Other);
            let mut pairs = Vec::with_capacity(rows.len());
            for (t, r) in rows.iter().enumerate() {
                let x = angle_in(kind, req.deg, r[0], || target_value(req.targets, t, "input"))?;
                let y = angle_in(out_kind, req.deg, r[1], || target_value(req.targets, t, &format!("`{output}`")))?;
                pairs.push((x, y));
            }
            Ok(Task::function(output, pairs))
        }
        _ => Err(exit::usage("give the channel: --path POINT or --function INPUT:OUTPUT")),
    }
}

/// Refuses rows `x,y` without inputs that are all one point (two or more): they ask only that
/// the path pass through it, and a design that does meets them all at one input, no motion (the
/// library refuses them so, in its own terms: `timed`). Said in the command's: give points
/// along the path, or the inputs.
fn one_point_untimed(rows: &[Vec<f64>], targets: &Path) -> Result<(), Failed> {
    if rows.len() < 2 || rows.iter().any(|r| *r != rows[0]) {
        return Ok(());
    }
    Err(exit::usage(format!(
        "{}: all {} targets are one point ({}, {}): without inputs they ask only that the path pass through it, and \
         a design that does meets them all at one input, no motion; give points along the path, or the input of \
         each (rows `input,x,y`) to hold the point there while the input moves",
        targets.display(),
        rows.len(),
        Number(rows[0][0]),
        Number(rows[0][1])
    )))
}

/// `--range lo..hi` of an input of kind `kind` in the library's units (an angle's in radians,
/// given in degrees with `deg`).
fn range_in(r: &str, kind: QuantityKind, deg: bool) -> Result<(f64, f64), Failed> {
    // Targets along no range at all (`1..1`): every candidate would be rejected.
    let (lo, hi) = bounds(r, "--range", true)?;
    // Candidates are verified by sweeps between the targets' inputs, which refuse a range of
    // more turns than they follow: every candidate would be rejected for "no assembly" instead.
    // Counted in the unit typed, before the conversion (which refuses ends beyond a solve's
    // precision, a shorter reach), so that the range is told how long it may be. Each end over
    // a turn first: `hi - lo` of ends near the largest f64 overflows.
    let turn = if deg { 360.0 } else { TAU };
    let turns = hi / turn - lo / turn;
    if kind == QuantityKind::Angle && turns > MAX_TURNS {
        let span = match deg {
            true => format!("{:.0} deg", 360.0 * MAX_TURNS),
            false => format!("{:.1} rad", TAU * MAX_TURNS),
        };
        return Err(exit::usage(format!(
            "--range {r} spans {turns:.3e} turns of the input, more than the {MAX_TURNS:e} turns a sweep follows: \
             give a range at most {MAX_TURNS:e} turns long ({span})"
        )));
    }
    let given = || format!("--range {r}");
    let (lo, hi) = (angle_in(kind, deg, lo, given)?, angle_in(kind, deg, hi, given)?);
    // Ends apart in degrees can be one number in radians (subnormals that round to 0): the
    // library would name the radians, not these.
    if lo == hi {
        return Err(exit::usage(format!(
            "--range `{r}` is empty in radians: both ends are {} rad; give ends further apart",
            Number(lo)
        )));
    }
    Ok((lo, hi))
}

/// The kind of the unknown or output `name` (the library names a missing one).
fn column_kind(model: &Model, name: &str) -> Option<QuantityKind> {
    let unknowns = model.unknowns().iter().zip(model.unknown_kinds());
    let outputs = model.outputs().iter().zip(model.output_kinds());
    unknowns.chain(outputs).find(|(n, _)| *n == name).map(|(_, k)| *k)
}

/// How the candidates' numbers are written: the errors in the unit of the targets (an angle
/// output's in degrees with `--deg`, as its targets are given), the angles of the defects (an
/// angle input's limit position, a transmission angle) in degrees with `--deg`.
struct Units {
    /// The factor from the library's errors (radians for an angle) to those written.
    error: f64,
    /// The unit of the errors, written in the header.
    error_unit: &'static str,
    /// The factor from the radians of an angle input to the value written (1 for an input of
    /// another kind).
    input: f64,
    /// The factor from radians to the unit of angles written.
    angle: f64,
    /// That unit.
    angle_unit: &'static str,
    /// A turn in the unit of the errors where they are an angle's (a function of an angle
    /// output), whose errors the library takes modulo a turn; `None` otherwise.
    turn: Option<f64>,
    /// Per parameter of the model (by name): the unit its values are written in, the
    /// declaration's (an angle's in radians, with or without `--deg`), for the header.
    params: Vec<(String, &'static str)>,
    /// Each target's line in the targets file (from 1), where its defects are said to be: the
    /// library counts targets from 0, and a header, blank lines and comments move the rows
    /// further from their count.
    lines: Vec<usize>,
}

impl Units {
    /// The units of the request's channel and `--deg`.
    fn of(model: &Model, req: &Request) -> Units {
        let (angle, angle_unit) = if req.deg { (180.0 / std::f64::consts::PI, "deg") } else { (1.0, "rad") };
        let of = |kind: QuantityKind| if kind == QuantityKind::Angle { angle } else { 1.0 };
        // A path's error is a distance; a function's is in the unit of its output.
        let kind = match req.function {
            Some(spec) => spec.split_once(':').and_then(|(_, o)| column_kind(model, o.trim())),
            None => Some(QuantityKind::Length),
        };
        let kind = kind.unwrap_or(QuantityKind::Other);
        let error_unit = if kind == QuantityKind::Angle { angle_unit } else { kind.unit() };
        let input = model.input_kinds().first().map_or(1.0, |&k| of(k));
        let turn = (kind == QuantityKind::Angle).then_some(TAU * angle);
        let params = model.params().iter().cloned().zip(model.param_kinds().iter().map(|k| k.unit())).collect();
        Units { error: of(kind), error_unit, input, angle, angle_unit, turn, params, lines: Vec::new() }
    }
}

/// A defect in words, with where it happened (its angles in the units written, its target by
/// its line in the targets file).
fn defect(d: &Defect, u: &Units) -> String {
    let target = |k: &usize| match u.lines.get(*k) {
        Some(line) => format!("the target of line {line}"),
        None => format!("target {k}"),
    };
    match d {
        Defect::Order => "order".into(),
        Defect::Branch { target: k } => format!("branch at {}", target(k)),
        Defect::Circuit { target: k, at } => format!("circuit before {} (limit at {:.6})", target(k), at * u.input),
        Defect::NoAssembly { target: k } => format!("no assembly before {}", target(k)),
        Defect::NoFullRotation => "no full rotation".into(),
        Defect::Transmission { min } => format!("transmission angle {:.6} {}", min * u.angle, u.angle_unit),
        Defect::LinkRatio { ratio } => format!("link ratio {ratio:.6}"),
        Defect::Miss { target: k, error } => format!("miss at {} (error {})", target(k), Number(error * u.error)),
        _ => format!("{d:?}"),
    }
}

/// The defects of a candidate, `;`-separated (empty for a valid one).
fn defects(c: &Candidate, u: &Units) -> String {
    c.defects.iter().map(|d| defect(d, u)).collect::<Vec<_>>().join("; ")
}

/// The columns: rank, start, valid, the design variables, the errors (with their unit, as the
/// other commands write units: `max_error [deg]`), evaluations, defects.
fn header(report: &SynthesisReport, u: &Units) -> Vec<String> {
    let [rank, start, valid, max_error, rms_error, evaluations, defects] = COLUMNS;
    let mut h: Vec<String> = [rank, start, valid].map(String::from).to_vec();
    // Each design variable with its unit, as every other column has one: an angle's is radians
    // whatever `--deg` says (the variables are parameters, in the declaration's units), which a
    // bare `alpha` beside `max_error [deg]` left to be guessed.
    let variable = |v: &String| match u.params.iter().find(|(p, _)| p == v) {
        Some((_, unit)) if !unit.is_empty() => format!("{v} [{unit}]"),
        _ => v.clone(),
    };
    h.extend(report.variables.iter().map(variable));
    let unit = if u.error_unit.is_empty() { String::new() } else { format!(" [{}]", u.error_unit) };
    h.extend([format!("{max_error}{unit}"), format!("{rms_error}{unit}")]);
    h.extend([evaluations, defects].map(String::from));
    h
}

/// One candidate's cells, each number written by `number` (in full precision: it reads back to
/// the same bits; an error converted to degrees is within a rounding of the radians').
fn cells(rank: usize, c: &Candidate, u: &Units, number: fn(f64) -> String) -> Vec<String> {
    let mut r = vec![rank.to_string(), c.start.to_string(), u8::from(c.is_valid()).to_string()];
    r.extend(c.values.iter().map(|&v| number(v)));
    let (max, rms) = (c.max_error * u.error, c.rms_error * u.error);
    r.extend([number(max), number(rms), c.local.evaluations.to_string()]);
    r.push(defects(c, u));
    r
}

/// A number of the table as text: in full precision, as `Debug` writes it.
fn shown(v: f64) -> String {
    format!("{v:?}")
}

/// A number of the CSV as every CSV of the command line writes it (`crate::csv_rows`): in full
/// precision, a zero without a sign.
fn csv_number(v: f64) -> String {
    Number(unsigned_zero(v)).to_string()
}

/// A field of text in the CSV: quoted, a quote within doubled (RFC 4180), so that a comma, a
/// quote or a line break within reads back as written.
fn csv_text(text: &str) -> String {
    format!("\"{}\"", text.replace('"', "\"\""))
}

/// The candidates as CSV (the defects quoted).
fn csv(report: &SynthesisReport, u: &Units) -> String {
    let mut s = header(report, u).join(",");
    s.push('\n');
    for (k, c) in report.candidates.iter().enumerate() {
        let mut r = cells(k + 1, c, u, csv_number);
        let last = r.len() - 1;
        r[last] = csv_text(&r[last]);
        let _ = writeln!(s, "{}", r.join(","));
    }
    s
}

/// The candidates as a table aligned in columns.
fn table(report: &SynthesisReport, u: &Units) -> String {
    let head = header(report, u);
    let rows: Vec<Vec<String>> = report.candidates.iter().enumerate().map(|(k, c)| cells(k + 1, c, u, shown)).collect();
    let widths: Vec<usize> =
        (0..head.len()).map(|j| rows.iter().map(|r| r[j].len()).chain([head[j].len()]).max().unwrap_or(0)).collect();
    let mut s = String::new();
    for r in std::iter::once(&head).chain(&rows) {
        let line: Vec<String> = r.iter().zip(&widths).map(|(v, w)| format!("{v:<w$}")).collect();
        let _ = writeln!(s, "{}", line.join("  ").trim_end());
    }
    s
}

/// A note where the best valid candidate misses its targets by as much as they lie from their
/// centre (the mean of a path's points, the middle of a function's values) or more: no better
/// than a point that does not move (an output that does not change, for a function: its targets
/// are values, and no point of the mechanism is fitted), the optimum within the bounds of
/// `--vary` of targets those designs cannot reach. `path`: the targets are points (their last two columns), otherwise
/// values (their last column), in the unit the errors are written. Targets that are all one
/// point or one value (or one target) lie 0 from their centre, which every miss passes: their
/// note says what they ask and gives the miss ([`one_target`]).
fn out_of_reach(report: &SynthesisReport, rows: &[Vec<f64>], units: &Units, path: bool) -> Option<String> {
    let best = report.best()?;
    let width = rows.first()?.len();
    let reach = match path {
        true => path_reach(rows.iter().map(|r| [r[width - 2], r[width - 1]])),
        false => value_reach(rows.iter().map(|r| r[width - 1]), units.turn),
    };
    let error = best.max_error * units.error;
    // Targets all at one point (or one value, or one target) lie 0 from their centre (or a
    // rounding of it): every miss is "as much or more", and the note below said nothing of a
    // miss by 1000, or that such a miss is all a point held still can be judged by.
    let columns = if path { width - 2 } else { width - 1 };
    if reach == 0.0 || rows.iter().all(|r| r[columns..] == rows[0][columns..]) {
        return Some(one_target(rows, path, error));
    }
    let still = if path { "a point that does not move" } else { "an output that does not change" };
    (error >= reach).then(|| {
        format!(
            "note: the best candidate misses its targets by {}, as much as they lie from their centre ({}) or \
             more: no better than {still}; the targets are likely out of reach of the designs --vary allows \
             (widen its bounds, or vary more parameters)",
            Number(error),
            Number(reach)
        )
    })
}

/// The note where the targets `rows` are all one point of a path (`path`) or one value of a
/// function (their last two columns, or their last), or there is one target: what they ask (a
/// point or an output held still while the input moves), and how far the best candidate misses
/// (`error`, in the unit written), all there is to judge whether the designs `--vary` allows
/// hold it there.
fn one_target(rows: &[Vec<f64>], path: bool, error: f64) -> String {
    let (row, width) = (&rows[0], rows[0].len());
    let (what, hold) = match path {
        true => (
            format!("one point ({}, {})", Number(row[width - 2]), Number(row[width - 1])),
            "the point must stay there while the input moves",
        ),
        false => {
            (format!("one value ({})", Number(row[width - 1])), "the output must stay at it while the input moves")
        }
    };
    let targets = match rows.len() {
        1 => format!("the only target is {what}"),
        n => format!("all {n} targets are {what}: {hold}"),
    };
    format!(
        "note: {targets}; the best candidate misses it by {} (where that is more than rounding, the designs --vary \
         allows do not reach it: widen its bounds, or vary more parameters)",
        Number(error)
    )
}

/// How far the points `points` lie from their mean at most.
fn path_reach(points: impl Iterator<Item = [f64; 2]> + Clone) -> f64 {
    let n = points.clone().count() as f64;
    // Each term divided first: sums of targets near the largest f64 stay finite.
    let centre = points.clone().fold([0.0, 0.0], |[x, y], [px, py]| [x + px / n, y + py / n]);
    points.map(|[x, y]| (x - centre[0]).hypot(y - centre[1])).fold(0.0f64, f64::max)
}

/// How far the values `values` lie from their middle at most: half their spread; for an angle
/// (`turn`: a turn in their unit), whose errors the library takes modulo a turn, half the
/// shortest arc of the circle that holds them all (179 and -179 degrees are 2 degrees apart,
/// 1 from their middle at 180, not 179 from 0). The value nearest all of them sits opposite the
/// middle of the widest gap between them: every value is then at most half a turn less half
/// that gap away, and elsewhere the value at one end of the gap is farther.
fn value_reach(values: impl Iterator<Item = f64> + Clone, turn: Option<f64>) -> f64 {
    let Some(turn) = turn else {
        let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
        // Halves first: the spread of values near the largest f64 stays finite.
        let centre = 0.5 * lo + 0.5 * hi;
        return (hi - centre).max(centre - lo);
    };
    let mut on_turn: Vec<f64> = values.map(|v| v.rem_euclid(turn)).collect();
    on_turn.sort_by(f64::total_cmp);
    let (Some(&first), Some(&last)) = (on_turn.first(), on_turn.last()) else { return 0.0 };
    let widest = on_turn.windows(2).map(|w| w[1] - w[0]).fold(turn - (last - first), f64::max);
    0.5 * (turn - widest)
}

/// What happened to the starts, in one line.
fn summary(r: &SynthesisReport) -> String {
    format!(
        "{}: {} valid, {} converged, {} stopped by the step tolerance, {} could not be assembled, {} rejected (order \
         {}, branch {}, circuit {}, no assembly {}, miss {}), {}",
        Count(r.starts.len() + r.seeds, "start"),
        r.valid,
        r.converged,
        r.step_tolerance,
        r.unassembled,
        r.rejected.total(),
        r.rejected.order,
        r.rejected.branch,
        r.rejected.circuit,
        r.rejected.no_assembly,
        r.rejected.miss,
        Count(r.evaluations, "evaluation")
    )
}

/// The starts of one kind refused before their local solve, in one line: how many, why, and
/// the first with its design variables by name and the error's `message`.
fn refusal(variables: &[String], r: &Refused, message: &str) -> String {
    let values: Vec<String> = variables.iter().zip(&r.point).map(|(n, v)| format!("{n}={}", Number(*v))).collect();
    let origin = if r.origin == Origin::Seed { "seed" } else { "start" };
    format!(
        "  {} ({}), the first {origin} {} at {}: {}",
        Count(r.count, "start"),
        r.kind.describe(),
        r.start,
        values.join(", "),
        message
    )
}

#[cfg(test)]
mod tests {
    use super::{Units, csv_number, csv_text, defect, refusal, value_reach};
    use kinloop_runtime::synthesis::{Defect, Origin, RefusalKind, Refused};

    /// A defect's target is named by its line in the targets file, not by the library's count
    /// from 0 ("miss at target 0" was the row on line 1, or on line 4 below a header, a comment
    /// and a blank line); a target beyond the lines known keeps its count.
    #[test]
    fn a_defect_names_its_target_by_its_line() {
        let u = Units {
            error: 1.0,
            error_unit: "length unit",
            input: 1.0,
            angle: 1.0,
            angle_unit: "rad",
            turn: None,
            params: Vec::new(),
            lines: vec![4, 5, 7],
        };
        assert_eq!(defect(&Defect::Miss { target: 0, error: 0.25 }, &u), "miss at the target of line 4 (error 0.25)");
        assert_eq!(defect(&Defect::Branch { target: 2 }, &u), "branch at the target of line 7");
        assert_eq!(defect(&Defect::NoAssembly { target: 1 }, &u), "no assembly before the target of line 5");
        assert_eq!(
            defect(&Defect::Circuit { target: 1, at: 0.5 }, &u),
            "circuit before the target of line 5 (limit at 0.500000)"
        );
        assert_eq!(defect(&Defect::Branch { target: 3 }, &u), "branch at target 3");
    }

    /// A kind of refusal is written with its count, its first start's design variables by name
    /// and its message: before, the summary said only how many could not be assembled.
    #[test]
    fn a_refusal_names_its_first_design_and_its_message() {
        let r = Refused {
            kind: RefusalKind::NoAssembly,
            count: 3,
            origin: Origin::Halton,
            start: 7,
            point: vec![55.0, 0.25],
            message: "the mechanism cannot be assembled".into(),
        };
        let variables = ["a".to_string(), "e".to_string()];
        assert_eq!(
            refusal(&variables, &r, &r.message),
            "  3 starts (cannot be assembled), the first start 7 at a=55, e=0.25: the mechanism cannot be assembled"
        );
    }

    /// The CSV's numbers are written as the command line's other CSVs write them: a negative
    /// zero as `0` (it was `-0.0`, where the sweeps' and the tables' CSVs write `0`), every
    /// other value to the same bits (read back by Rust's parser, independent of the writer),
    /// NaN and infinities as `Table::read_csv` reads them.
    #[test]
    fn the_csv_numbers_are_written_as_every_csv_of_the_command_line() {
        assert_eq!(csv_number(-0.0), "0");
        assert_eq!(csv_number(0.0), "0");
        for v in [1.5, -2.25e-7, 0.1 + 0.2, f64::MAX, -f64::MIN_POSITIVE, 5e-324, f64::INFINITY, f64::NEG_INFINITY] {
            let back: f64 = csv_number(v).parse().unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{v:e} written {}", csv_number(v));
        }
        assert!(csv_number(f64::NAN).parse::<f64>().unwrap().is_nan());
    }

    /// A field of text is quoted with any quote within doubled, as RFC 4180 reads it: a quote
    /// in a defect's words would have ended the field early.
    #[test]
    fn a_csv_text_field_doubles_its_quotes() {
        assert_eq!(csv_text(""), "\"\"");
        assert_eq!(csv_text("order; circuit at 2.36"), "\"order; circuit at 2.36\"");
        assert_eq!(csv_text("a \"b\", c"), "\"a \"\"b\"\", c\"");
    }

    /// The reach of angles against the brute force: the best of a thousandth of a degree's
    /// grid of constants, each's largest error modulo a turn (a grid point lies within 0.0005
    /// of the best constant, so the two agree to that).
    #[test]
    fn the_reach_of_angles_is_the_best_constant_s_largest_error() {
        let wrapped = |d: f64| (d - 360.0 * (d / 360.0).round()).abs();
        for values in [
            &[179.0, -179.0][..],
            &[0.0, 180.0],
            &[0.0, 120.0, 240.0],
            &[10.0, 20.0, -350.0, 730.0],
            &[-90.0, 90.0, 100.0],
            &[42.0],
        ] {
            let brute = (0..360_000)
                .map(|k| {
                    let c = k as f64 / 1000.0;
                    values.iter().map(|v| wrapped(v - c)).fold(0.0, f64::max)
                })
                .fold(f64::INFINITY, f64::min);
            let reach = value_reach(values.iter().copied(), Some(360.0));
            assert!((reach - brute).abs() <= 5e-4 + 1e-12, "{values:?}: {reach} against {brute}");
        }
        // Not an angle: half the spread.
        assert_eq!(value_reach([179.0, -179.0].into_iter(), None), 179.0);
    }
}
