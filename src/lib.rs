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
//! ## The declaration language
//!
//! ```text
//! /// doc comment                            (kept on the generated struct)
//! #[kinloop(dense)]                          optional: solve all unknowns as one dense block
//! #[kinloop(newton)]                         optional: Newton even where a closed form exists
//! #[kinloop(sensitivities)]                  optional: also generate parameter sensitivities
//! pub struct Name {
//!     params a, b = 2.5, c;                  design parameters (f64 fields; optional defaults)
//!     input phi;                             generalized coordinate(s): `inputs th1, th2;`
//!     unknowns q1 = 0.3, s = a + b;          unknowns, with initial guesses (default 0)
//!     let v = a @ phi + (0, c);              named intermediate (scalar or vector)
//!     loop name: vector == vector;           a closed contour: two scalar equations
//!     eq name: scalar == scalar;             one scalar equation
//!     point p = vector;                      named output point (x, y) and its analogs
//!     output w = scalar;                     named scalar output and its analogs
//!     body b: mass m, com p, inertia j, turns q1;   dynamics: a rigid body (see below)
//!     force f at p = vector;                 a force at a point, an expression of the state
//!     torque t on q1 = scalar;               a torque on an input or an angle unknown
//!     gravity vector;                        the gravitational acceleration, e.g. `(0, -g)`
//! }
//! ```
//!
//! * `length @ angle` is a polar vector (`(length cos angle, length sin angle)`), `(x, y)` a
//!   Cartesian one; `+` and `-` chain vectors, a scalar scales a vector (`k * v`, `v / k`),
//!   `v.x` and `v.y` take components. `@` binds tighter than `+` and looser than `*`, so
//!   `a + 2 * r @ phi` is `a + ((2 r) @ phi)`, and an angle that is a sum needs parentheses:
//!   `r @ (phi + gamma)`.
//! * Scalars: numbers, `+ - * /`, unary `-`, powers `x ^ 2` (an integer exponent becomes
//!   `powi`), `pi`, and the functions `sin cos tan asin acos atan atan2(y, x) sqrt exp ln abs
//!   pow(x, y) hypot(a, b) deg(degrees)`; for vectors `norm(v) dot(a, b) cross(a, b) angle(v)
//!   rot(v, theta)`.
//! * **Angles are in radians** everywhere: in the declaration (`@`, `sin`, `rot`, initial
//!   guesses), in the inputs passed at run time, in every result (`s.q.phi2`, analogs per radian)
//!   and in tables and their CSV files (label the columns with [`Table::with_units`]:
//!   `phi [rad]`). Write an angle in degrees as `deg(30)` in a declaration and as
//!   `kinloop::deg(30.0)` in Rust, and read one in degrees with [`to_deg`] or
//!   [`Table::column_deg`]; `30°` is not valid Rust and does not compile. A guess written in
//!   degrees by mistake (`phi2 = 30`) is a guess of 30 rad.
//! * A loop's right side may be `0` (the zero vector): `loop c: a + b - c == 0;`.
//! * Time can be the input: `input t; let s1 = v1 * t;` (the analogs are then time derivatives).
//! * Several inputs make a multi-degree-of-freedom mechanism; the analogs are partial
//!   derivatives (`state.dq.phi2.th1` is `d phi2 / d th1`, `state.d2q.phi2.th1.th2` the mixed
//!   second derivative).
//! * The initial guesses choose the assembly mode (branch); pass another guess at run time to
//!   pick another branch, or warm-start each solve from the previous position along a sweep.
//!
//! * Machine dynamics: `body name: mass m, com p, inertia j, turns angle;` declares a rigid
//!   body — its mass and moment of inertia about the centre of mass are expressions of the
//!   parameters (`inertia` defaults to 0), its centre of mass `com` a declared `point` or
//!   `(x, y)` of unknowns, outputs and constants (`com (x_c, 0)` for a slider), and `turns`
//!   names the input or angle unknown it rotates with (none for a slider). `force name at p =
//!   (fx, fy);` and `torque name on angle = scalar;` are loads: expressions of parameters,
//!   inputs and unknowns, evaluated by generated straight-line code; `gravity (0, -g);` sets
//!   gravity. The macro then generates `m.mass_model()`, the runtime's
//!   [`dynamics::MassModel`] for the reduced inertia, inverse dynamics, shaking forces, flywheel
//!   and simulation. A negative literal mass or inertia, a mass that changes with the state,
//!   `turns` or `on` a parameter or a length unknown, and a point with no analogs of its own
//!   are compile errors; negative or non-finite values given at run time are typed errors.
//!
//! ```
//! kinloop::mechanism! {
//!     /// A slider-crank with its rod and piston, a gas force and gravity.
//!     pub struct Engine {
//!         params r = 0.05, l = 0.2, m_rod = 2.0, j_rod = 0.01, m_p = 0.5, p = 300.0;
//!         input phi;
//!         unknowns beta = 0, x = 0.25;
//!         loop abc: r @ phi + l @ beta == (x, 0);
//!         point s2 = r @ phi + 0.3 * l @ beta;
//!         body rod: mass m_rod, com s2, inertia j_rod, turns beta;
//!         body piston: mass m_p, com (x, 0);
//!         force gas at (x, 0) = (p * (r + l) / x, 0);
//!         gravity (0, -9.81);
//!     }
//! }
//! use kinloop::Mechanism;
//! let engine = Engine::default();
//! let model = engine.mass_model()?;
//! let k = engine.kinematics_flat(&[0.5], &engine.guess_flat(&[0.5]), &Default::default())?;
//! let d = model.dynamics(&k, &[100.0])?; // at 100 rad/s
//! let torque = d.drive(&[100.0], &[0.0])[0]; // J eps + 1/2 J' omega^2 - Q at constant speed
//! assert!(d.reduced_inertia() > 0.0 && torque.is_finite());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Mistakes are compile errors at the exact place, with what to write instead: unknown names
//! (with a suggestion), vector/scalar mix-ups, unsupported functions, and structural problems
//! (equation and unknown counts with the resulting mobility, over- and under-determined parts).
//! All mistakes of a declaration are reported together. A structural problem is one error at the
//! mechanism's name — counts, mobility `W = unknowns + inputs - equations`, the over- and
//! under-determined parts (Dulmage–Mendelsohn) with their equations and unknowns, and what to add
//! or remove — plus a short error at each loop and unknown involved. An unknown in no equation,
//! an equation without unknowns and an input that is never used are errors; a parameter that is
//! never used is a warning (name it `_mass` to keep it on purpose). After an error the macro
//! still defines the parameter struct and the named types, so code using them adds no
//! secondary errors.
//!
//! ## What is generated
//!
//! For `pub struct Name { ... }`:
//!
//! * `Name`: the parameters as public `f64` fields (and `Default` when every parameter has a
//!   default value, or when there are no parameters), with `param_values()` and
//!   `from_param_values([...])` in declaration order;
//! * `NameInputs<T>`, `NameUnknowns<T>`, `NameOutputs<T>`: named fields (points are
//!   [`Vec2`]), convertible from and to arrays (and nalgebra vectors for the unknowns); with
//!   one input, a plain `f64` converts to `NameInputs`, so `m.solve(0.3)` works;
//! * `NameState`: the inputs `input`, positions `q`, velocity analogs `dq`, acceleration analogs
//!   `d2q`, outputs `out`, `dout`, `d2out`, the solver [`SolveReport`], the blocks' [`Health`]
//!   and the same values as a flat [`Kin`] (`flat`); `state.motion(omega, eps)` gives true
//!   velocities and accelerations (`NameMotion`);
//! * methods on `Name`: `solve(input)`, `kinematics(input, guess)`, `position(input, guess)`,
//!   `kinematics_at(input, q)`, `outputs`, `residual`, `guess`, `check`, `position_with` and
//!   `kinematics_with` taking a [`NewtonConfig`], `sweep`, `sweep_at` and `assembly_modes`
//!   (see below), `sensitivities` when requested and `mass_model` when dynamics is declared;
//!   and the constants `NAME`, `PARAMS`, `INPUTS`, `UNKNOWNS`, `EQUATIONS`, `OUTPUTS`,
//!   `BLOCKS` (the block-triangular decomposition) and `DECOMPOSITION` (the same in words, see
//!   below);
//! * implementations of [`Mechanism`] (the flat, generated kernels) and [`Named`] (the same
//!   API by name) for generic code. The methods above are the same for every mechanism: they
//!   live once in [`Named`] and the generated ones only forward to it, so calling them needs no
//!   import.
//!
//! ```
//! kinloop::mechanism! {
//!     /// A slider driven through a fixed cam profile: no parameters, and still `Default`.
//!     pub struct Cam {
//!         input phi;
//!         unknowns x = 1;
//!         eq follower: x == 2 + 0.5 * sin(phi);
//!     }
//! }
//! let s = Cam::default().solve(0.3)?;
//! assert!((s.dq.x - 0.5 * 0.3f64.cos()).abs() < 1e-12);
//! # Ok::<(), kinloop::Error>(())
//! ```
//!
//! The equations are ordered into blocks (maximum matching and Tarjan's strongly connected
//! components, i.e. the block-lower-triangular form): each block is solved by its own small
//! Newton with a fixed-size Jacobian, blocks whose unknowns appear linearly (slider coordinates)
//! by one linear solve, and blocks that are classical Assur groups (a rod angle, an RRR dyad, a
//! slotted rocker, an RRP group) in closed form. Velocity analogs solve `J q' = -df/dphi` and acceleration analogs
//! `J q'' = -D2f[(q', 1), (q', 1)]` with one factorisation per block shared by both.
//!
//! `Name::BLOCKS` lists the blocks in solve order ([`BlockInfo`]: unknowns, equations, linear),
//! and `Name::DECOMPOSITION` describes them in words: the counts and the mobility, then one line
//! per block with its index (the one error locations use), how it is solved, and its unknowns
//! `<-` its scalar equations (`loop.x`, `loop.y`, or an `eq` name). A block that is a classical
//! Assur group is solved in closed form, without iteration (`closed form, angle equation`: one
//! angle from `a cos q + b sin q = c`; `closed form, RRR dyad`: circle intersection; `closed
//! form, length and angle`: a slotted rocker; `closed form, angle and slider`: an RRP group),
//! on the assembly mode of the guess (the sign of the block's Jacobian determinant there) and
//! on the guess's turn. Where its links fall short of closing the loop it is `NoAssembly`, as
//! Newton; short by no more than the residual tolerance (a limit position rounded past: `0.1 +
//! 0.2 > 0.3` in metres) it is the limit position, in every unit. `linear, NxN` is one linear solve; `Newton, NxN` iterates;
//! `Newton, NxN sparse (K non-zeros)` iterates on a large coupled block (16 unknowns or more,
//! a sparse Jacobian) whose LU follows its sparsity: an elimination order fixed at compile time,
//! every pivot checked at run time, a dense LU where one is weak. Newton ends on the guess's turn
//! too: an angle that enters its block only through sines and cosines of whole multiples of
//! itself (`l @ q`, `l @ (q + gamma)`, `l @ (2 q)`) and that a long step carried more than half a
//! turn out is moved back to its guess's turn and corrected once more there. A far guess can
//! lead Newton into a fold of the residual (a local minimum where no step decreases it, links
//! lying folded against each other) though the loops close elsewhere: there it restarts, with
//! one such angle at a time turned by a quarter turn either way and by a half turn, and returns
//! the root nearest the guess; only when every restart stalls too is the block `NoAssembly`
//! ([`NewtonConfig::restarts`]; a sweep's steps never restart). From a far guess Newton may end
//! in either assembly mode; the closed forms keep the guess's. A guess millions
//! of turns out, where doubles are too far apart for an angle to meet the tolerance, is
//! [`Error::TooManyTurns`] on both paths.
//! `#[kinloop(dense)]` solves all unknowns as one block with dense LU instead, `#[kinloop(newton)]` uses
//! Newton for every nonlinear block (the results are the same; both exist to compare and to
//! debug).
//!
//! ```
//! kinloop::mechanism! {
//!     pub struct SliderCrank {
//!         params r = 1.0, l = 3.0, e = 0.2;
//!         input phi;
//!         unknowns psi = pi, x = r + l;   // rod from the slider back to the crank pin
//!         loop oabo: r @ phi == (x, e) + l @ psi;
//!     }
//! }
//!
//! // The rod angle comes from the loop's y projection (the slider is not in it), then the
//! // slider coordinate, which appears linearly, from its x projection in closed form.
//! assert_eq!(
//!     SliderCrank::DECOMPOSITION,
//!     "SliderCrank: 2 unknowns, 2 scalar equations, 1 input (mobility W = 1); 2 blocks in solve order
//!   block 0 (closed form, angle equation): psi <- oabo.y
//!   block 1 (linear, 1x1): x <- oabo.x"
//! );
//! assert_eq!(SliderCrank::BLOCKS[1].unknowns, ["x"]);
//! assert!(SliderCrank::BLOCKS[1].linear);
//! ```
//!
//! ## Sweeps, singular positions and assembly modes
//!
//! `m.sweep(from, to, samples, &guess)` is a lazy iterator over `samples` equally spaced inputs
//! (a straight path in input space for several inputs). Between samples it steps adaptively with
//! a second-order Taylor predictor from the generated analogs and a Newton corrector, and it
//! **never jumps branches**: a step is accepted only if every block keeps the sign of its
//! Jacobian determinant (its assembly mode), the corrected position lies near the prediction and
//! the velocity analogs near theirs. When no step can be made it locates why — a **limit
//! position** of the input (found by pseudo-arclength continuation where the input reverses) or
//! a **singular crossing** (a change point where a determinant changes sign) — records an
//! [`Event`] with the input value, and stops with [`Error::SweepStopped`] (or, with
//! [`AtSingular::Continue`], passes a crossing). [`Sweep::run`] runs it to its end and returns a
//! [`SweepResult`]: the states up to where it ended, the [`Stop`] (completed, a limit position
//! or a singular crossing with its located [`Event`], or the error) and the events met.
//! [`Sweep::table`] collects a sweep into a CSV-ready [`Table`]; `m.reachable(at, delta, &guess,
//! samples)` finds the input range reachable on a branch, in input values ([`Reach`]);
//! `m.trace_curve(from, to, &guess, &TraceOptions::default())` follows the whole solution curve
//! through limit positions (e.g. the closed curve of a non-Grashof four-bar);
//! `m.assembly_modes(input)` lists the distinct assembly modes so one can be picked by a readable
//! rule ("elbow up": `.into_iter().find(|s| s.out.c.y > 0.0)`). Arclength continuation measures
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
//! (the path only passes close to one) it stops with [`Error::Branch`] saying so, and a lower
//! value lets it pass.
//!
//! `m.with_config(cfg)` gives the mechanism its own solver configuration (a [`SweepConfig`] or
//! a [`NewtonConfig`], validated once): the [`Configured`] mechanism uses it in every solve,
//! sweep, reachable range, assembly-mode search and trace (its methods are those of [`Named`]).
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
//! let kinloop::Stop::LimitPosition(at) = &run.stop else { panic!("{:?}", run.stop) };
//! assert!((at.x[0] - expected).abs() < 1e-9);
//! // The reachable range on this assembly mode, in input values.
//! let reach = m.reachable(0.0, 3.14, &g, 19)?;
//! assert!((reach.to.phi - expected).abs() < 1e-9 && (reach.from.phi + expected).abs() < 1e-9);
//! // The closed curve through both limit positions.
//! let curve = m.trace_curve(0.0, 3.14, &g, &kinloop::TraceOptions::default().with_ds(0.05))?;
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
//! # let turn = Sampled::sweep(&m, 0.0, 6.0, 73, m.guess(0.0).into()).unwrap();
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
//! says to add it. [`extremum`] and [`integral`] give objectives over a whole sweep with exact
//! gradients (extremes by the envelope theorem, with the gradient of their location), and
//! [`LevenbergMarquardt`](analysis::optimize::LevenbergMarquardt) uses them for synthesis
//! (`examples/synthesis.rs`).
//!
//! ## Design-space scans
//!
//! [`scan`] runs the same sweep over many parameter sets and folds each sweep into one value
//! (a stroke, the extreme of an output) without keeping its states; `par_scan` (cargo feature
//! `rayon`) does the same on all cores and returns bitwise the same results in the same order.
//! A set that fails (cannot be assembled, meets a limit position, non-finite parameters) gives
//! an [`Error`] in its slot; the others go on. [`ScanSpec`] says what every sweep does and
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
//! use kinloop::{ScanSpec, scan};
//!
//! // Rod lengths 2.0, 2.5, ..., and one rod too short to reach the slider's line.
//! let mut designs: Vec<_> = (0..8).map(|i| SliderCrank { r: 1.0, l: 2.0 + 0.5 * i as f64, e: 0.3 }).collect();
//! designs.push(SliderCrank { r: 1.0, l: 0.2, e: 0.3 });
//! let spec = ScanSpec::new([0.0], [TAU], 361);
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
//! analogs their quotients `d(x_c)/d(phi) [length unit/rad]`; a column whose kind cannot be
//! inferred, such as a time input, gets none: see [`QuantityKind`]); `with_length_unit("mm")`
//! names the unit of length and `with_units(&[("t", "s")])` sets any; `Table::read_csv` reads
//! the table back.
//! [`Vec2`] adds, subtracts, scales and converts to `nalgebra::Vector2` (and, with the feature
//! `mint`, `mint::Vector2`). With the feature `serde`, parameter sets, named positions and
//! outputs, states, tables, events and configurations implement `Serialize` and `Deserialize`
//! (the generated structs name serde through `kinloop`, so no serde dependency is needed).
//! Configurations ([`SweepConfig`], [`NewtonConfig`], the optimisers) are built from their
//! defaults with `with_*` methods: `SweepConfig::default().with_max_step(0.5)`.
//!
//! ## Analysis, metrics, dynamics and features
//!
//! [`analysis`] answers questions about a sweep by column (extremes, strokes, dwells,
//! harmonics, unbalance) and optimises designs; [`metrics`] gives the designer's figures
//! (transmission angle, Grashof class, time ratio, dead centres and limit positions);
//! [`dynamics`] works on the mass model of a machine (reduced inertia, inverse dynamics,
//! flywheel, simulation). Cargo features add `plot` (`kinloop::plot`, charts of sweep results
//! as SVG), `draw` (`kinloop::draw`, drawings and animations of the mechanism as SVG), `rayon`
//! (`par_scan`), `mint` and `serde` (see above).
//!
//! ## Errors
//!
//! Bad input never panics and never yields a silent NaN: see [`Error`] (non-finite parameters or
//! inputs, no convergence, a mechanism that cannot be assembled, a singular position, an
//! expression outside its domain, an overflow, an angle too many turns out to be solved to the
//! tolerance, a sweep stopped at a singular position or unable to stay on its branch, an invalid
//! argument). Every error but an invalid argument carries a [`Location`]: the mechanism,
//! the input values and, where one is concerned, the block.
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
//! ```
#![warn(missing_docs)]

extern crate self as kinloop;

pub use kinloop_macros::mechanism;
pub use kinloop_runtime::*;

/// What code expanded by [`mechanism!`] names (and nothing else); not for use by hand.
#[doc(hidden)]
pub mod __gen {
    pub use kinloop_runtime::generated::*;

    // The `Serialize` and `Deserialize` derives every generated struct names: serde's with the
    // feature `serde`, otherwise derives that implement nothing and accept the `serde`
    // attributes. The user's crate cannot test kinloop's features, so the expansion names these,
    // the same with and without the feature.
    #[cfg(not(feature = "serde"))]
    pub use kinloop_macros::{NoDeserialize as Deserialize, NoSerialize as Serialize};
    #[cfg(feature = "serde")]
    pub use kinloop_runtime::generated::serde::{Deserialize, Serialize};
}

/// Charts of sweep results as SVG (feature `plot`).
#[cfg(feature = "plot")]
pub use kinloop_viz::plot;

/// Drawings and animations of the mechanism as SVG (feature `draw`).
#[cfg(feature = "draw")]
pub use kinloop_viz::draw;
