//! The literature's four-bar path-synthesis test cases (see `docs/synthesis-literature.md`):
//! five points with prescribed crank angles, six points on a straight line and ten points on an
//! ellipse without timing, eighteen points of a closed curve with timing. The four-bar is
//! declared in the literature's own variables (frame `r1`, crank `r2`, coupler `r3`, rocker
//! `r4`, coupler point `(rcx, rcy)` in the coupler's frame, crank pivot `(x0, y0)`, frame angle
//! `th0`, crank angle `th2` from the frame), so that the design variables and their bounds are
//! the published ones; the error is the published measure, the sum of the squared distances
//! from the coupler point to the targets.

use kinloop::synthesis::{
    Candidate, Constraints, Design, LocalConfig, Problem, Rejections, Search, SynthesisError, Task,
};
use std::f64::consts::{PI, TAU};

kinloop::mechanism! {
    /// The four-bar of the literature's path-synthesis cases: crank pivot at `(x0, y0)`, frame
    /// `r1` at the angle `th0`, crank `r2` at `th2` from the frame (plus a start angle `th2s`
    /// where the timing is given as increments), coupler `r3`, rocker `r4`; the coupler point at
    /// `rcx` along the coupler and `rcy` across it. `th3`, `th4` are measured from the frame.
    #[kinloop(sensitivities)]
    pub struct LiteratureFourBar {
        params r1 = 3.0, r2 = 1.0, r3 = 3.0, r4 = 2.5, rcx = 1.0, rcy = 1.0, x0 = 0.0, y0 = 0.0,
               th0 = 0.0, th2s = 0.0;
        input th2;
        unknowns th3 = 0.5, th4 = 1.5;
        loop abcd: r2 @ (th2 + th2s) + r3 @ th3 == (r1, 0) + r4 @ th4;
        point p = (x0, y0) + r2 @ (th2 + th2s + th0) + rcx @ (th3 + th0) + rcy @ (th3 + th0 + pi / 2);
    }
}

/// How the targets are timed.
#[derive(Clone, Debug, PartialEq)]
pub enum Timing {
    /// The crank angle `th2` of every target is given.
    Given(Vec<f64>),
    /// The crank angles are given as `th2s + t_i`, the start `th2s` a design variable.
    Increments(Vec<f64>),
    /// Every target's crank angle is free within one turn, the targets met in order.
    Free,
}

/// One of the literature's cases.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// Short name.
    pub name: &'static str,
    /// The targets, in order.
    pub targets: Vec<[f64; 2]>,
    /// Their timing.
    pub timing: Timing,
    /// Bounds of `r1..r4`.
    pub links: (f64, f64),
    /// Bounds of `rcx`, `rcy`, `x0`, `y0`.
    pub coords: (f64, f64),
    /// The ranges of the crank angle searched with free timing (within the published `[0, 2 pi]`):
    /// starts spread the targets' angles evenly over a range in order, so a range about as
    /// wide as the arc the targets take gives starts near the ordered solutions.
    pub windows: Vec<(f64, f64)>,
    /// Whether the crank must turn fully (a Grashof crank).
    pub full_rotation: bool,
    /// Whether the frame is fixed (crank pivot at the origin, frame along x): `x0`, `y0`, `th0`
    /// are no design variables.
    pub frame_fixed: bool,
}

/// (a) Five points with prescribed crank angles (as restated since Cabrera, Simon and Prado 2002).
pub fn case_a() -> Case {
    Case {
        name: "a: 5 points, timed",
        targets: vec![[3.0, 3.0], [2.759, 3.363], [2.372, 3.663], [1.890, 3.862], [1.355, 3.943]],
        timing: Timing::Given(vec![PI / 6.0, PI / 4.0, PI / 3.0, 5.0 * PI / 12.0, PI / 2.0]),
        links: (0.0, 5.0),
        coords: (-5.0, 5.0),
        windows: Vec::new(),
        full_rotation: true,
        frame_fixed: false,
    }
}

/// (b) with the frame free (crank pivot and frame angle design variables too), as the case is
/// stated in the literature: 15 unknowns for 12 equations, so the problem is declared
/// underdetermined.
pub fn case_b_free_frame() -> Case {
    Case { name: "b\u{2033}: 6 points on a line, untimed, frame free", frame_fixed: false, ..case_b() }
}

/// (b) Six points on a vertical straight line, untimed.
pub fn case_b() -> Case {
    Case {
        name: "b: 6 points on a line, untimed",
        targets: (0..6).map(|k| [20.0, 20.0 + 5.0 * k as f64]).collect(),
        timing: Timing::Free,
        links: (5.0, 60.0),
        coords: (-60.0, 60.0),
        windows: (0..8).map(|k| (k as f64 * PI / 4.0, k as f64 * PI / 4.0 + PI)).chain([(0.0, TAU)]).collect(),
        full_rotation: true,
        frame_fixed: true,
    }
}

/// (c) Ten points on an ellipse (centre (10, 10), semi-axes 10 and 8), untimed; the tenth
/// repeats the first, as published.
pub fn case_c() -> Case {
    Case {
        name: "c: 10 points on an ellipse, untimed",
        targets: vec![
            [20.0, 10.0],
            [17.66, 15.142],
            [11.736, 17.878],
            [5.0, 16.928],
            [0.60307, 12.736],
            [0.60307, 7.2638],
            [5.0, 3.0718],
            [11.736, 2.1215],
            [17.66, 4.8577],
            [20.0, 10.0],
        ],
        timing: Timing::Free,
        links: (5.0, 80.0),
        coords: (-80.0, 80.0),
        windows: vec![(0.0, TAU)],
        full_rotation: true,
        frame_fixed: false,
    }
}

/// (d) Eighteen points of a closed curve, the crank turning 20 degrees from each to the next.
pub fn case_d() -> Case {
    Case {
        name: "d: 18 points of a closed curve, timed",
        targets: vec![
            [0.5, 1.1],
            [0.4, 1.1],
            [0.3, 1.1],
            [0.2, 1.0],
            [0.1, 0.9],
            [0.005, 0.75],
            [0.02, 0.6],
            [0.0, 0.5],
            [0.0, 0.4],
            [0.03, 0.3],
            [0.1, 0.25],
            [0.15, 0.2],
            [0.2, 0.3],
            [0.3, 0.4],
            [0.4, 0.5],
            [0.5, 0.7],
            [0.6, 0.9],
            [0.6, 1.0],
        ],
        timing: Timing::Increments((0..18).map(|k| (20.0 * k as f64).to_radians()).collect()),
        links: (0.0, 50.0),
        coords: (-50.0, 50.0),
        windows: Vec::new(),
        full_rotation: true,
        frame_fixed: false,
    }
}

/// (b) without requiring the crank to turn fully: the targets met in order on one circuit.
pub fn case_b_rocking() -> Case {
    Case { name: "b': 6 points on a line, untimed, input not turning fully", full_rotation: false, ..case_b() }
}

/// All cases, in order.
pub fn cases() -> Vec<Case> {
    vec![case_a(), case_b(), case_b_rocking(), case_b_free_frame(), case_c(), case_d()]
}

/// The design variables' names, in the order of [`Candidate::values`].
pub fn variables(case: &Case) -> Vec<&'static str> {
    let mut v = vec!["r1", "r2", "r3", "r4", "rcx", "rcy"];
    if !case.frame_fixed {
        v.extend(["x0", "y0", "th0"]);
    }
    if matches!(case.timing, Timing::Increments(_)) {
        v.push("th2s");
    }
    v
}

/// The problem of a case: the published variables and bounds, the crank required to turn
/// fully where the case says so, on the assembly mode of a guess (`[th3, th4]` at the first
/// target; `None`: the declaration's).
pub type LiteratureProblem = Problem<LiteratureFourBar, 2, 1, 2, 10>;

/// Builds the problem of `case`, free crank angles within `window` (ignored with timing).
pub fn problem(case: &Case, guess: Option<[f64; 2]>, window: (f64, f64)) -> Result<LiteratureProblem, SynthesisError> {
    let (l0, l1) = case.links;
    let (c0, c1) = case.coords;
    let mut design = Design::new().var("r1", l0, l1).var("r2", l0, l1).var("r3", l0, l1).var("r4", l0, l1);
    design = design.var("rcx", c0, c1).var("rcy", c0, c1);
    if !case.frame_fixed {
        design = design.var("x0", c0, c1).var("y0", c0, c1).var("th0", 0.0, TAU);
    }
    if !case.frame_fixed && matches!(case.timing, Timing::Free) {
        // Untimed with the frame free: more unknowns than the targets' equations (a family of
        // designs meets them; the constraints choose).
        design = design.underdetermined();
    }
    let task = Task::path("p", case.targets.clone());
    let task = match &case.timing {
        Timing::Given(x) => task.timed(x.clone()),
        Timing::Increments(x) => {
            design = design.var("th2s", 0.0, TAU);
            task.timed(x.clone())
        }
        Timing::Free => task.untimed(window.0, window.1),
    };
    let p = Problem::new(LiteratureFourBar::default(), &design, &task)?.with_constraints(&if case.full_rotation {
        Constraints::default().with_full_rotation()
    } else {
        Constraints::default()
    })?;
    Ok(match guess {
        Some(g) => p.with_guess(g)?,
        None => p,
    })
}

/// The two assembly modes searched: the declared one (coupler joint on the left of the line
/// from crank pin to rocker pivot) and its mirror.
pub const MODES: [Option<[f64; 2]>; 2] = [None, Some([-0.5, -1.5])];

/// The sum of the squared distances of a candidate (the literature's error).
pub fn sum_of_squares(c: &Candidate) -> f64 {
    c.errors.iter().map(|e| e * e).sum()
}

/// What a search over a case found: every valid candidate's error, the best, and the work.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The best valid candidate (over both modes).
    pub best: Option<Candidate>,
    /// The assembly mode and crank-angle window it was found with.
    pub best_at: (Option<[f64; 2]>, (f64, f64)),
    /// The sum of squares of every valid local solution (one per start that gave one).
    pub valid: Vec<f64>,
    /// Starts run (over both modes).
    pub starts: usize,
    /// Evaluations over all starts.
    pub evaluations: usize,
    /// Starts that could not be assembled at every target.
    pub unassembled: usize,
    /// Local solutions rejected by the verification, by defect.
    pub rejected: Rejections,
    /// The smallest error of a rejected local solution (what the verification turned down).
    pub best_rejected: f64,
}

/// Runs `starts` starts with `seed` on each assembly mode of `case` and each of its windows of
/// the crank angle; local solves of up to `max_evaluations` evaluations.
pub fn search(case: &Case, starts: usize, seed: u64, max_evaluations: usize) -> Result<Outcome, SynthesisError> {
    let mut out = Outcome {
        best: None,
        best_at: (None, (0.0, TAU)),
        valid: Vec::new(),
        starts: 0,
        evaluations: 0,
        unassembled: 0,
        rejected: Rejections::default(),
        best_rejected: f64::INFINITY,
    };
    let windows = if case.windows.is_empty() { vec![(0.0, TAU)] } else { case.windows.clone() };
    for (mode, window) in MODES.into_iter().flat_map(|m| windows.iter().map(move |w| (m, *w))) {
        let p = problem(case, mode, window)?;
        let s = Search::default()
            .with_starts(0..starts)
            .with_seed(seed)
            .with_keep(starts)
            .with_distinct(0.0)
            .with_local(LocalConfig::default().with_max_evaluations(max_evaluations));
        let r = s.run(&p)?;
        out.starts += starts;
        out.evaluations += r.evaluations;
        out.unassembled += r.unassembled;
        out.rejected.add(&r.rejected);
        for c in r.candidates {
            let e = sum_of_squares(&c);
            if !c.is_valid() {
                out.best_rejected = out.best_rejected.min(e);
                continue;
            }
            out.valid.push(e);
            if out.best.as_ref().is_none_or(|b| e < sum_of_squares(b)) {
                out.best = Some(c);
                out.best_at = (mode, window);
            }
        }
    }
    Ok(out)
}

/// The error (sum of squares) a run must reach to count as a success in the comparison, per
/// case.
pub const THRESHOLDS: [f64; 6] = [1e-4, 1e-2, 1e-2, 1e-2, 1e-2, 2e-2];

/// The best candidate of `out` polished by a longer local solve (up to 5000 evaluations) from
/// where its start stopped, verified again.
pub fn polish(case: &Case, out: &Outcome) -> Result<Option<Candidate>, SynthesisError> {
    let Some(best) = &out.best else { return Ok(None) };
    let p = problem(case, out.best_at.0, out.best_at.1)?;
    let mut z = best.values.clone();
    if matches!(case.timing, Timing::Free) {
        z.extend(best.inputs.iter().map(|x| x[0]));
    }
    let local = LocalConfig::default().with_max_evaluations(5000);
    let c = Search::default().with_local(local).refine(&p, &z)?;
    Ok(Some(if c.is_valid() && sum_of_squares(&c) <= sum_of_squares(best) { c } else { best.clone() }))
}
