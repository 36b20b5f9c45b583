//! # kinloop
//!
//! Kinematic analysis of planar mechanisms declared as **closed vector loops** (the method of
//! closed vector contours): each independent loop of the kinematic chain is one vector equation,
//! projected on X and Y. The [`mechanism!`] macro turns such a declaration, at compile time,
//! into straight-line numeric code for positions, velocity analogs `dq/dphi`, acceleration
//! analogs `d2q/dphi2`, true velocities and accelerations, and any named output (centres of
//! mass, coupler points). Every derivative comes from automatic differentiation of the declared
//! equations performed by the macro; nobody derives a derivative by hand.
//!
//! ```
//! kinloop::mechanism! {
//!     /// Offset slider-crank: crank `r` at the origin, rod `l`, slider on the line y = e.
//!     pub struct SliderCrank {
//!         params r = 1.0, l = 3.0, e = 0.2;
//!         input phi;
//!         unknowns psi = pi, x = r + l;   // rod from the slider back to the crank pin
//!         loop oabo: r @ phi == (x, e) + l @ psi;
//!         point mid = r @ phi + 0.5 * l @ psi;
//!     }
//! }
//!
//! let m = SliderCrank::default();
//! let s = m.solve(0.3)?;                       // positions, analogs, outputs
//! assert!((s.q.x - (0.3f64.cos() - 3.0 * s.q.psi.cos())).abs() < 1e-12);
//! let v = s.motion(10.0, 0.0)?;                // crank at 10 rad/s: true motion
//! assert!((v.qdot.x - 10.0 * s.dq.x).abs() < 1e-12);
//! # Ok::<(), kinloop::Error>(())
//! ```
//!
//! ## Declaring a mechanism
//!
//! A declaration names the parameters, the input(s) and the unknowns, then writes each loop of
//! the chain as one vector equation; `point` and `output` name what to compute besides, and
//! `body`, `force`, `torque`, `gravity` describe the dynamics. [`mechanism!`] gives the grammar
//! at a glance and [`language`] the complete reference: expressions and functions, angles and
//! units, several inputs, the generated types and methods, how the equations are ordered into
//! blocks and how each block is solved (closed form, linear, Newton), and the diagnostics.
//!
//! ## Sweeps, singular positions and assembly modes
//!
//! `m.sweep(from, to, samples, &guess)` is a lazy iterator over `samples` equally spaced inputs
//! (a straight path in input space for several inputs). Between samples it steps adaptively with
//! a second-order Taylor predictor from the generated analogs and a Newton corrector, and it
//! **never jumps branches**: a step is accepted only if every block keeps the sign of its
//! Jacobian determinant (its assembly mode), the corrected position lies near the prediction and
//! the velocity analogs near theirs. The samples are only the output grid: the steps between
//! them are bounded in the inputs' own scale (a quarter radian for an angle) and by how much the
//! predicted slopes change, so two samples per turn follow the same branch to the same first
//! limit as two thousand. A range of more than a million turns is refused before any step is
//! made: the sweep's first item is [`Error::RangeTooLong`]. When no step can be made it locates
//! why — a **limit position** of the input (found by pseudo-arclength continuation where the
//! input reverses) or a **singular crossing** (a change point where a determinant changes
//! sign) — records an [`Event`] with the input value, and stops with [`Error::SweepStopped`]
//! (or, with [`AtSingular::Continue`], passes a crossing). [`Sweep::run`] runs it to its end and returns a
//! [`SweepResult`]: the states up to where it ended, the [`SweepStop`] (completed, a limit position
//! or a singular crossing with its located [`Event`], or the error) and the events met.
//! [`Sweep::table`] collects a sweep into a CSV-ready [`Table`]; `m.reachable(at, delta, &guess,
//! samples)` finds the input range reachable on a branch, in input values ([`Reach`]);
//! `m.trace_curve(from, to, &guess, &TraceConfig::default())` follows the whole solution curve
//! through limit positions (e.g. the closed curve of a non-Grashof four-bar);
//! `m.assembly_modes(input)?` lists the distinct assembly modes so one can be picked by a readable
//! rule ("elbow up": `.into_iter().find(|s| s.out.c.y > 0.0)`); and `m.assembly_near(phi)?`, for
//! a mechanism of one input angle, where it assembles nearest `phi` (the stretch between its
//! limit positions, or a crank that turns fully: an [`Assembly`]), or `None` where its loops close
//! nowhere on the turn. Arclength continuation measures
//! angles in radians and lengths in units of the mechanism's size, so events are located at the
//! same inputs whatever the unit of length.
//!
//! Every state carries its [`Health`]: the determinant signs (the assembly mode) and the
//! smallest pivot ratio of its blocks, how far it is from a singular position whatever the unit
//! of length. That includes a slide passing near the pivot of its slotted link (or a cylinder
//! nearly collapsed onto its pivot), where the link's angle is undetermined: its pivot ratio
//! there is the slide's distance from the pivot over the loop's other lengths. A position-only
//! solve, which has no analogs, makes the same test itself (a slide, or a dyad's two centres,
//! closer than [`NewtonConfig::singular_tol`] of the links is [`Error::Singular`]), on the
//! closed-form path as on Newton's. A sweep does not accept a step below
//! [`SweepConfig::singular_pivot`] (`1e-6`); where it finds no limit position or crossing there
//! (the path only passes close to one) it stops with [`Error::NearSingular`] saying so, and a
//! lower value lets it pass; a sweep that starts at one (the end of a reachable range) stops
//! with [`Error::SingularStart`].
//!
//! Beside a singular position the results lose accuracy as the smallest pivot ratio `p` falls:
//! about `eps / p` in the positions, `eps / p^2` in the velocity analogs and `eps / p^3` in the
//! acceleration analogs (`eps` = 2.2e-16). That is the position's own conditioning (the rounding
//! of the data moves the solution by as much), not the solver's: a slider-crank of rod equal to
//! its crank, 1e-6 rad before its change point (`p` = 1e-6), has its rod's velocity analog off
//! by about 4e-5 and its acceleration analog by about 90, where the exact values are 1 and 0. A
//! point solve accepts states down to [`NewtonConfig::singular_tol`] (1e-10): where analogs
//! matter, read `state.health.min_pivot`.
//!
//! `m.with_config(cfg)` gives the mechanism its own solver configuration (a [`SweepConfig`] or
//! a [`NewtonConfig`], validated once): the [`Configured`] mechanism uses it in every solve,
//! sweep, sampled analysis, limit search, reachable range, assembly-mode search, trace, scan and
//! inverse-dynamics cycle (its methods are those of [`Named`]).
//!
//! ```
//! kinloop::mechanism! {
//!     pub struct FourBar {
//!         params a = 3.0, b = 2.0, c = 2.5, d = 4.0;   // non-Grashof: the input rocks
//!         input phi;
//!         unknowns beta = 0.5, gamma = 1.5;
//!         loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
//!     }
//! }
//! let m = FourBar::default();
//! let g = m.position(0.0, &m.guess(0.0))?.0;
//! let mut sweep = m.sweep(0.0, 3.14, 19, &g)?;
//! let last = sweep.by_ref().find_map(Result::err).expect("the input cannot reach 3.14");
//! assert!(matches!(last, kinloop::Error::SweepStopped { kind: kinloop::EventKind::LimitPosition, .. }));
//! let limit = sweep.events()[0].x[0];
//! // Law of cosines: coupler and rocker are collinear, |BD| = b + c.
//! let expected = ((9.0 + 16.0 - 4.5f64 * 4.5) / 24.0).acos();
//! assert!((limit - expected).abs() < 1e-9);
//!
//! // The whole run at once: the states before the limit position and where it is.
//! let run = m.sweep(0.0, 3.14, 19, &g)?.run();
//! assert_eq!(run.states.len(), 8); // 0, 10, ..., 70 degrees
//! let kinloop::SweepStop::LimitPosition(at) = &run.stop else { panic!("{:?}", run.stop) };
//! assert!((at.x[0] - expected).abs() < 1e-9);
//! // The reachable range on this assembly mode, in input values.
//! let reach = m.reachable(0.0, 3.14, &g, 19)?;
//! assert!((reach.to.phi - expected).abs() < 1e-9 && (reach.from.phi + expected).abs() < 1e-9);
//! // The closed curve through both limit positions.
//! let curve = m.trace_curve(0.0, 3.14, &g, &kinloop::TraceConfig::default().with_ds(0.05))?;
//! assert!(curve.closed && curve.folds.len() == 2);
//!
//! // A mechanism-wide configuration, validated once and used by every call.
//! use kinloop::{Named, NewtonConfig, SweepConfig};
//! let bad = m.with_config(NewtonConfig::default().with_residual_tol(-1.0)).unwrap_err();
//! assert!(bad.to_string().contains("newton.residual_tol"));
//! let fine = m.with_config(SweepConfig::default().with_max_step(0.25))?;
//! let run = fine.sweep(0.0, 3.14, 19, &g)?.run();
//! assert!((run.stop.event().unwrap().x[0] - expected).abs() < 1e-9);
//! # Ok::<(), kinloop::Error>(())
//! ```
//!
//! ## Analysis over a sweep: typed columns, one input or several
//!
//! `m.sampled(from, to, samples, &guess)` ([`analysis::Sampled`]) runs a branch-safe sweep once
//! and answers questions about any column: extremes located as roots of the velocity analog,
//! the global range (dead centres, stroke), dwells, Fourier coefficients, residual unbalance,
//! peaks. Columns are the typed handles that `mechanism!` generates in `Name::COL`, with the
//! state's paths (`FourBar::COL.beta`, `FourBar::COL.p.x`, an input `FourBar::COL.phi`): a
//! misspelled column or a column of another mechanism is a compile error, not a run-time one.
//! [`analysis::Column::named`] looks a column up by a name known only at run time (the dynamic
//! fallback).
//!
//! With several inputs, it samples the straight path from `from` to `to` in input space
//! ([`analysis::Sampled::path`]); every quantity is then a function of the path parameter (the
//! fraction of the path, or an input chosen with `.along(Name::COL.input)`), its derivatives
//! the analog tensors contracted with the path's direction.
//!
//! ```
//! use std::f64::consts::{PI, TAU};
//! kinloop::mechanism! {
//!     pub struct SliderCrank {
//!         params r = 1.0, l = 3.0;
//!         input phi;
//!         unknowns psi = 0, x = r + l;
//!         loop oabc: r @ phi + l @ psi == (x, 0);
//!     }
//! }
//! let m = SliderCrank::default();
//! let turn = m.sampled(-0.5, TAU - 0.5, 73, &m.guess(-0.5))?;    // or Sampled::sweep(&m, ...)
//! let x = turn.range(SliderCrank::COL.x)?;        // dead centres at 0 and pi
//! assert!((x.max.value - 4.0).abs() < 1e-12 && x.max.x.abs() < 1e-9);
//! assert!((x.min.value - 2.0).abs() < 1e-12 && (x.min.x - PI).abs() < 1e-9);
//! assert!((x.span() - 2.0).abs() < 1e-12);         // the stroke 2 r
//!
//! kinloop::mechanism! {
//!     /// A five-bar: two cranks (inputs) joined by two links meeting at `p`.
//!     pub struct FiveBar {
//!         params a = 1.0, b = 2.5, c = 2.5, d = 1.0, e = 2.0;
//!         inputs th1, th2;
//!         unknowns al = 1.2, be = 2.0;
//!         loop l: a @ th1 + b @ al == (e, 0) + d @ th2 + c @ be;
//!         point p = a @ th1 + b @ al;
//!     }
//! }
//! // Both cranks turn, the second half as fast as the first; parameter: th1.
//! let m = FiveBar::default();
//! let from = [0.0, 0.5 * PI];
//! let run = m.sampled(from, [PI, PI], 61, &m.guess(from))?.along(FiveBar::COL.th1)?;
//! let top = run.range(FiveBar::COL.p.y)?.max;       // d(p.y)/d(th1) along the path vanishes there
//! let k = run.at(top.x)?;
//! assert!((k.x[1] - (0.5 * PI + 0.5 * top.x)).abs() < 1e-12);
//! assert!((k.dout[1][0] + 0.5 * k.dout[1][1]).abs() < 1e-9);
//! # Ok::<(), kinloop::Error>(())
//! ```
//!
//! ```compile_fail
//! # use kinloop::analysis::Sampled;
//! # kinloop::mechanism! {
//! #     pub struct SliderCrank {
//! #         params r = 1.0, l = 3.0;
//! #         input phi;
//! #         unknowns psi = 0, x = r + l;
//! #         loop oabc: r @ phi + l @ psi == (x, 0);
//! #     }
//! # }
//! # let m = SliderCrank::default();
//! # let turn = m.sampled(0.0, 6.0, 73, &m.guess(0.0)).unwrap();
//! let x = turn.range(SliderCrank::COL.xc); // no column `xc`: a compile error
//! ```
//!
//! ## Parameter sensitivities
//!
//! Declared with `#[kinloop(sensitivities)]` (they are generated only on request: they are the
//! larger part of the generated code), a mechanism also has `m.sensitivities(input, &guess)`
//! (and `sensitivities_at(input, &q)` at a solved position), which returns the state and its
//! exact derivatives with respect to every parameter (`NameSensitivities`, whose innermost level
//! is a `NameParams`: one value per parameter) — of positions, velocity and acceleration analogs
//! and outputs — by the implicit function theorem on the same block factorisations
//! (`dq/dp = -J^-1 df/dp`; the analogs' sensitivities differentiate their own equations), all
//! differentiated at compile time. A parameter name appended to a state path reads as a
//! derivative: `sens.dq.x_c.l_p` is `d(dX_C/dphi1)/dL_P`. They cost nothing unless requested;
//! calling `sensitivities` on a mechanism declared without the attribute is a compile error that
//! says to add it. A sampled sweep's
//! [`extremum_with_gradient`](analysis::Sampled::extremum_with_gradient) and
//! [`integral_with_gradient`](analysis::Sampled::integral_with_gradient) give objectives over a
//! whole sweep with exact gradients (extremes by the envelope theorem, with the gradient of
//! their location), and [`LevenbergMarquardt`](analysis::optimize::LevenbergMarquardt) uses them.
//!
//! [`synthesis`] finds dimensions for a task with them: a point through given points (with
//! prescribed or free input values), a curve fitted with a free placement, a function, poses.
//! Its Levenberg–Marquardt runs on the exact Jacobian (sensitivities, velocity analogs) from
//! Halton starts, from the best members of a differential evolution, or from classical closed
//! forms given as seeds, every candidate verified by a branch-safe sweep through the targets in order
//! and rejected with its defect (branch, circuit, order) or a violated constraint (full
//! rotation, transmission angle, link ratio); see `docs/synthesis.md` and
//! `examples/synthesis.rs`.
//!
//! ## Design-space scans
//!
//! [`scan`] runs the same sweep over many parameter sets and folds each sweep into one value
//! (a stroke, the extreme of an output) without keeping its states; `par_scan` (cargo feature
//! `rayon`) does the same on all cores and returns bitwise the same results in the same order.
//! A set that fails (cannot be assembled, meets a limit position, non-finite parameters) gives
//! an [`Error`] in its slot; the others go on. [`ScanConfig`] says what every sweep does and
//! [`ScanStart`] how it starts (the declared guess by default).
//!
//! ```
//! kinloop::mechanism! {
//!     pub struct SliderCrank {
//!         params r, l, e;
//!         input phi;
//!         unknowns psi = pi, x = r + l;   // rod from the slider back to the crank pin
//!         loop oabo: r @ phi == (x, e) + l @ psi;
//!     }
//! }
//! use std::f64::consts::TAU;
//! use kinloop::{ScanConfig, scan};
//!
//! // Rod lengths 2.0, 2.5, ..., and one rod too short to reach the slider's line.
//! let mut designs: Vec<_> = (0..8).map(|i| SliderCrank { r: 1.0, l: 2.0 + 0.5 * i as f64, e: 0.3 }).collect();
//! designs.push(SliderCrank { r: 1.0, l: 0.2, e: 0.3 });
//! let spec = ScanConfig::new([0.0], [TAU], 361);
//! // Fold each turn into (min, max) of the slider position x (unknown 1).
//! let extent = |(lo, hi): (f64, f64), _: &SliderCrank, k: &kinloop::Kin<2, 1, 0>| (lo.min(k.q[1]), hi.max(k.q[1]));
//! let start = |_: &SliderCrank| (f64::INFINITY, f64::NEG_INFINITY);
//! let results = scan(&designs, &spec, start, extent);
//! for (m, r) in designs.iter().zip(&results).take(8) {
//!     let (lo, hi) = *r.as_ref().unwrap();
//!     let stroke = ((m.l + m.r).powi(2) - m.e * m.e).sqrt() - ((m.l - m.r).powi(2) - m.e * m.e).sqrt();
//!     assert!((hi - lo - stroke).abs() < 1e-3);   // sampled every degree
//! }
//! assert!(matches!(results[8], Err(kinloop::Error::NoAssembly { .. })));
//!
//! // The same on all cores (feature `rayon`): bitwise the same results.
//! #[cfg(feature = "rayon")]
//! assert_eq!(kinloop::par_scan(&designs, &spec, start, extent), results);
//! ```
//!
//! ## Given inputs, tables, CSV and interchange
//!
//! `m.sweep_at([0.1, 0.15, 0.9, 2.5], &guess)` follows the mechanism through a given list of
//! inputs (uneven, far apart or repeated) with the same branch guarantees as a sweep, and returns
//! a [`SweepResult`]: the states in order, why it stopped and the events met (`.into_result()?`
//! for the states alone). [`Table`] collects states under named columns with their units in the
//! CSV header, inferred by `mechanism!` (angles `phi [rad]`, lengths `x_c [length unit]`, the
//! analogs their quotients `d(x_c)/d(phi) [length unit/rad]`; an input whose kind cannot be
//! inferred, such as a time `t`, is in `unit of t` and the analogs by it per that unit,
//! `d(psi)/d(t) [rad/unit of t]`, while an unknown or output of a kind not inferred gets no
//! unit: see [`QuantityKind`]); `with_length_unit("mm")`
//! names the unit of length and `with_units(&[("t", "s")])` sets any; `Table::read_csv` reads
//! the table back.
//! [`Vec2`] adds, subtracts, scales and converts to `nalgebra::Vector2` (and, with the feature
//! `mint`, `mint::Vector2`). With the feature `serde`, parameter sets, named positions and
//! outputs, states, tables, events and configurations implement `Serialize` and `Deserialize`
//! (the generated structs name serde through `kinloop`, so no serde dependency is needed). A
//! generated struct or a state read with a field it does not have (a misspelt parameter) is an
//! error naming the field and those it has.
//! Through JSON, serde_json reads every number back to the bit with its feature
//! `float_roundtrip` (`serde_json = { version = "1", features = ["float_roundtrip"] }`);
//! without it, its faster parser may read the last bit of some numbers differently. JSON has
//! no NaN nor infinity: a state's, a parameter set's or other generated struct's (alone as
//! inside a state), a vector's, a table's, an event's, a report's or a configuration's are
//! written as the strings `"NaN"`, `"inf"` and `"-inf"` and read back as they were, a NaN with
//! its sign and payload (`"-NaN"`, `"NaN(0x..)"` with its bits; `null` reads as NaN).
//! Configurations ([`SweepConfig`], [`NewtonConfig`], the optimisers) are built from their
//! defaults with `with_*` methods: `SweepConfig::default().with_max_step(0.5)`.
//!
//! ## Analysis, metrics, dynamics and features
//!
//! [`analysis`] answers questions about a sweep by column (extremes, strokes, dwells,
//! harmonics, unbalance) and optimises designs; [`metrics`] gives the designer's figures
//! (transmission angle, Grashof class, time ratio, dead centres and limit positions);
//! [`dynamics`] works on the mass model of a machine (reduced inertia, inverse dynamics,
//! flywheel, simulation); [`drawing`] reads what a declaration says about how the mechanism
//! looks (its loops' chains of points, links, frame, sliders, plates). Cargo features add
//! `plot` (`kinloop::plot`, charts of sweep results as SVG), `draw` (`kinloop::draw`, drawings
//! and animations of the mechanism as SVG; `m.drawing()` draws it from its declaration; and
//! interactive HTML pages with a slider, readouts and linked charts: `draw::html`, or a slider
//! per input over a grid of several inputs: `draw::html_grid`; synthesis candidates over their
//! targets: `draw::candidates`), `png`
//! (`kinloop::draw::png`, drawings and charts rendered to PNG, text included), `rayon`
//! (`par_scan`), `mint` and `serde` (see above).
//!
//! ## Errors
//!
//! Bad input never panics and never yields a silent NaN: see [`Error`] (non-finite parameters or
//! inputs, no convergence, a mechanism that cannot be assembled, a singular position, an
//! expression outside its domain, an overflow, an angle too many turns out to be solved to the
//! tolerance, a sweep stopped at a singular position or unable to stay on its branch, a range of
//! more than a million turns, an invalid argument). Every error of a solve or a sweep carries a
//! [`Location`]: the mechanism, the input values and, where one is concerned, the block (an
//! invalid argument and the wrapped errors below carry none). [`Error`] is the one error type a
//! program of analyses needs: the errors of dynamics, charts, drawings and pages
//! (`DynamicsError`, `PlotError`, `DrawError`, `HtmlError`) convert into it through `?`, kept
//! whole in [`Error::Dynamics`] and [`Error::Figure`] ([`Source::downcast_ref`] gives them back
//! typed). A synthesis problem's [`synthesis::SynthesisError`] is the other way round: it wraps
//! an [`Error`] of the kinematics, and a program that builds problems returns it (or a boxed
//! error).
//!
//! ```
//! kinloop::mechanism! {
//!     pub struct FourBar {
//!         params a, b, c, d;
//!         input phi;
//!         unknowns beta = 0.5, gamma = 1.5;
//!         loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
//!     }
//! }
//! // Links too short to close the loop:
//! let m = FourBar { a: 1.0, b: 1.0, c: 1.0, d: 5.0 };
//! let err = m.solve(0.0).unwrap_err();
//! assert!(matches!(err, kinloop::Error::NoAssembly { .. }), "{err}");
//! let bad = FourBar { a: f64::NAN, ..m };
//! assert!(matches!(bad.solve(0.0), Err(kinloop::Error::NonFinite { .. })));
//! // Nowhere on the turn, from the declared guess:
//! assert!(m.assembly_near(0.0)?.is_none());
//! // Coupler and rocker (2.5 + 1.5) short of frame and crank in line (3.2 + 1): not at pi, but
//! // between the limit positions where they stretch out (the law of cosines).
//! let m = FourBar { a: 1.0, b: 2.5, c: 1.5, d: 3.2 };
//! assert!(matches!(m.solve(3.1), Err(kinloop::Error::NoAssembly { .. })));
//! let near = m.assembly_near(3.1)?.expect("it assembles");
//! let limit = ((1.0f64 + 3.2 * 3.2 - 16.0) / (2.0 * 3.2)).acos();
//! assert!((near.reach.to.phi - limit).abs() < 1e-9 && (near.reach.from.phi + limit).abs() < 1e-9);
//! # Ok::<(), kinloop::Error>(())
//! ```
#![warn(missing_docs)]

extern crate self as kinloop;

pub mod language;

/// Declares a planar mechanism by its closed vector loops and generates, at compile time, its
/// named types and straight-line kernels: positions, velocity and acceleration analogs, outputs,
/// their exact derivatives by automatic differentiation, and (on request) parameter
/// sensitivities and the mass model of its dynamics.
///
/// ```text
/// /// doc comment                            kept on the generated struct
/// #[kinloop(dense | newton | sensitivities)] optional solver and generation options
/// pub struct Name {
///     params a, b = 2.5, c;                  design parameters (f64 fields; optional defaults)
///     input phi;                             generalized coordinate(s): `inputs th1, th2;`
///     unknowns q1 = 0.3, s = a + b;          unknowns with initial guesses (they pick the branch)
///     let v = a @ phi + (0, c);              named intermediate (scalar or vector)
///     loop name: vector == vector;           one closed contour: two scalar equations
///     eq name: scalar == scalar;             one scalar equation
///     point p = vector;                      named output point and its analogs
///     output w = scalar;                     named scalar output and its analogs
///     body b: mass m, com p, inertia j, turns q1;   a rigid body of the dynamics
///     force f at p = vector;   torque t on q1 = scalar;   gravity (0, -g);
/// }
/// ```
///
/// `length @ angle` is a polar vector, `(x, y)` a Cartesian one; angles are in radians
/// (`deg(30)` converts). It generates `Name` (the parameters), `NameInputs`, `NameUnknowns`,
/// `NameOutputs`, `NameState`, `NameMotion`, `NameColumns` (`Name::COL`), the constants
/// `NAME`, `PARAMS`, `INPUTS`, `UNKNOWNS`, `EQUATIONS`, `OUTPUTS`, `BLOCKS`, `DECOMPOSITION`,
/// the methods of [`Named`] (`solve`, `kinematics`, `sweep`, `sampled`, `reachable`, ...) and
/// implementations of [`Mechanism`] and [`Named`]. Every mistake is a compile error at its
/// span saying what to write instead. The complete reference is [`language`].
///
/// ```
/// kinloop::mechanism! {
///     /// Four-bar: crank `a`, coupler `b`, rocker `c`, ground `d`.
///     pub struct FourBar {
///         params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
///         input phi;
///         unknowns beta = 0.5, gamma = 1.5;
///         loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
///         point coupler = a @ phi + 0.5 * b @ beta;
///     }
/// }
/// let m = FourBar::default();
/// let s = m.solve(0.3)?;
/// // The loop closes, and the velocity analog is the derivative of the position.
/// let closure = 1.0 * 0.3f64.cos() + 3.0 * s.q.beta.cos() - 3.2 - 2.5 * s.q.gamma.cos();
/// assert!(closure.abs() < 1e-12);
/// let h = 1e-6;
/// let (up, down) = (m.kinematics(0.3 + h, &s.q)?, m.kinematics(0.3 - h, &s.q)?);
/// assert!(((up.q.beta - down.q.beta) / (2.0 * h) - s.dq.beta).abs() < 1e-8);
/// # Ok::<(), kinloop::Error>(())
/// ```
///
/// The expansion names kinloop as this macro was reached: a crate that depends on kinloop under
/// another name (`kl = { package = "kinloop", ... }` in `Cargo.toml`), or through a crate that
/// re-exports it, calls `kl::mechanism!` and needs nothing else.
// A `macro_rules!` wrapper, not the procedural macro re-exported: `$crate` is the one name of
// kinloop that holds in the user's crate whatever it calls kinloop, and only a `macro_rules!`
// macro has it. The procedural macro receives it in the marker `#![crate = $crate]` and roots
// every path of the expansion there. The declaration's tokens pass through unchanged, with
// their spans: errors still point into the user's declaration.
#[macro_export]
macro_rules! mechanism {
    ($($declaration:tt)*) => {
        $crate::__gen::mechanism! { #![crate = $crate] $($declaration)* }
    };
}
// The runtime's public items, listed rather than glob-imported: a glob would also inline the
// whole of nalgebra into these pages (rustdoc documents a module re-exported through a glob).
/// nalgebra, the linear algebra of the runtime, under its own path so that users share its
/// version (`kinloop::nalgebra::Vector2`); its documentation is nalgebra's own.
#[doc(no_inline)]
pub use kinloop_runtime::nalgebra;
pub use kinloop_runtime::{
    Assembly, AtSingular, BlockInfo, BlockNames, ColumnKey, Compiled, CompiledSens, Computed, Configured, DetSigns,
    Error, Event, EventKind, Extreme, Extremum, ExtremumOf, FlatMotion, Health, Jac, Kernel, Kin, LENGTH_UNIT,
    Location, Mechanism, Named, NamedSensitivities, NewtonConfig, NewtonStop, Number, Quantity, QuantityKind, Reach,
    Sens, SensKernel, SensState, Sensitivities, SolveReport, Source, Sweep, SweepConfig, SweepOf, SweepResult,
    SweepStop, Table, TraceConfig, Traced, TracedOf, TracedPoint, TracedPointOf, Vec2, deg, to_deg,
};
pub use kinloop_runtime::{analysis, dims, drawing, dynamics, events, metrics, paths, synthesis};
// A glob of the scan module: it holds `par_scan` whenever the runtime is built with rayon,
// whichever crate's feature asked for it (features unify).
pub use kinloop_runtime::paths::scan::*;

/// What code expanded by [`mechanism!`] names (and nothing else); not for use by hand.
#[doc(hidden)]
pub mod __gen {
    pub use kinloop_macros::mechanism;
    pub use kinloop_runtime::generated::*;

    // The `Serialize` and `Deserialize` derives every generated struct names: with the feature
    // `serde`, kinloop's, which emit serde's impls with every number written and read as the
    // crate's other numbers are (serde's own wrote a non-finite one as JSON's `null`, which does
    // not read back); otherwise derives that implement nothing and accept the `serde`
    // attributes. The user's crate cannot test kinloop's features, so the expansion names these,
    // the same with and without the feature.
    #[cfg(feature = "serde")]
    pub use kinloop_macros::{FloatsDeserialize as Deserialize, FloatsSerialize as Serialize};
    #[cfg(not(feature = "serde"))]
    pub use kinloop_macros::{NoDeserialize as Deserialize, NoSerialize as Serialize};
}

/// Charts of sweep results as SVG (feature `plot`).
#[cfg(feature = "plot")]
pub use kinloop_viz::plot;

/// Drawings and animations of the mechanism as SVG (feature `draw`).
#[cfg(feature = "draw")]
pub use kinloop_viz::draw;
