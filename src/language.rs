//! # The declaration language of [`mechanism!`](crate::mechanism)
//!
//! The complete reference of what a `mechanism!` declaration may contain and what it generates;
//! the [crate documentation](crate) shows how the generated mechanisms are used.
//!
//! ```text
//! /// doc comment                            (kept on the generated struct)
//! #[kinloop(dense)]                          optional: solve all unknowns as one block
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
//!   `r @ (phi + gamma)`. The length comes first: a name that is an angle (it turns a link
//!   elsewhere, `l @ psi`, is the argument of a sine or cosine, is set to an angle by an `eq`, or
//!   has its value written in degrees) written as the length, `psi @ l`, is a compile error
//!   that says to write `l @ psi`; so is a length written in degrees itself, `deg(30) @ l`, and
//!   a length that is an angle by its expression, as a coordinate below is judged (`(2 * phi) @
//!   th`, a scalar `let` of an angle, `norm((phi, psi)) @ th`): the message gives a length to
//!   write (`(r * phi) @ th` compiles) and, unless the angle is a constant or an angle itself
//!   (`psi @ phi`, where swapping cannot help), the swap; the angle of a swapped term is the
//!   length it is everywhere else (`(x, l)` beside `psi @ l` is not refused too). A value in
//!   degrees may be scaled by a number or offset by one (`2 * deg(15)`, `deg(90) - pi / 6`),
//!   or named by a `let` (`let tilt = deg(5);`): it is an angle all the same. A name of no
//!   known kind cannot be told from a length, so a swap whose angle is an angle nowhere else
//!   compiles as written; nor can a name written as a length that a sine takes only as a
//!   fraction of itself (`x` in `sin(x / 2)`: the 2 may be a radius). For
//!   the same reason a loop, which adds lengths, refuses such an angle (or a value written in
//!   degrees) as a coordinate of one of its vectors, `(x, phi)`: write a length there,
//!   `(x, r * phi)`. So do the other positions: a `point`, a vector `let` that a loop or point
//!   uses, the point a force acts at and a centre of mass. A coordinate is judged by what its
//!   expression is, not by how it is written: an angle offset by a number or by another angle,
//!   a multiple of one by a number (`(x, 2 * phi)`), a scalar `let` of one, `dot` of an
//!   angle's vector and a direction, and an angle scaling a direction (`phi * (0, 1)`) are
//!   angles there too, and so is the magnitude of a vector of angles (`norm((phi, psi))`,
//!   `hypot(phi, 0.5)`); a length times an angle (`r * phi`, `l * dot((phi, 0), u)`) or a sine
//!   of one is not. The vectors `dot`, `cross`, `norm` and `angle` take are no positions
//!   themselves (`rot` gives its vector back turned, a position still). A force's value and
//!   gravity are no positions, and a vector scaled by a length, `r * (phi, 0)`, has lengths for
//!   coordinates. Nor does a scalar sum, difference or `eq` put such an angle beside a length (a
//!   name written elsewhere as a coordinate of a position or as the length of `@`): `eq e: s ==
//!   phi;` with `s` a slider's travel is a compile error that says to write `s == r * phi`, and
//!   so is `x + psi` in a `loop`, `let`, `point`, `output` or the law of a force or torque alike
//!   (a reported value or a load that mixes the two changes with the unit of length as much as an
//!   equation does), and `max(x, psi)`,
//!   which is a length or an angle by the input, and `atan2(x, psi)`, `hypot(x, psi)` and
//!   `wrap(x, psi)`, which change with the unit of length as the sum does. So does a vector of
//!   an angle and a length wherever it is built outside a position: `norm((x, psi))` (which is
//!   `sqrt(x^2 + psi^2)`), `dot((x, psi), u)`, `angle((x, 0) + (0, psi))` are compile errors at
//!   the vector, which "combines an angle and a length"; a sum of vectors one of whose
//!   coordinates adds the two, `norm((x, 0) + (psi, 0))` (which is `norm((x + psi, 0))`), is
//!   one at the sum, told once for the sum. The vectors these functions take need
//!   not be lengths, only of one kind: a vector of angles (`norm((phi, psi))`), or of a length
//!   and a constant or a number of no unit (`(x, 0.5)`, `(x, sin(psi))`), compiles as before.
//!   An unknown that an `eq` sets to an expression of angles (`eq e: y == 2 * psi;`, the column
//!   `y [rad]`) is an angle for these checks (`y + x` is refused), unless it is written as a
//!   length elsewhere (a coordinate of a position, the length of `@`): then the `eq` is told
//!   that it equates an angle and a length.
//! * Scalars: numbers, `+ - * /`, unary `-`, powers `x ^ 2` (an integer exponent becomes
//!   `powi`), `pi`, and the functions `sin cos tan asin acos atan atan2(y, x) sqrt exp ln abs
//!   pow(x, y) hypot(a, b) deg(degrees) min(a, b) max(a, b) clamp(x, lo, hi) floor
//!   wrap(x, period)`; for vectors `norm(v) dot(a, b) cross(a, b) angle(v) rot(v, theta)`.
//! * `min`, `max` and `clamp(x, lo, hi)` (= `min(max(x, lo), hi)`) return exactly one of their
//!   arguments, for piecewise laws such as a cam's rise-dwell-return-dwell
//!   (`let u = clamp((phi - phi0) / beta, 0, 1);`). A NaN argument gives NaN (unlike
//!   `f64::min`), so a bad value is still reported. Their analogs are those of the chosen
//!   argument; at a tie the first argument is chosen, so `clamp` at a bound takes the analogs
//!   of `x`. The arguments must be of one kind, as for `+`. Constant bounds with `lo > hi` are a
//!   compile error; bounds that vary are not checked, and where `lo > hi` the result is `hi`.
//! * `floor(x)` is the largest integer not above `x` (`floor(-0.5)` is `-1`; NaN and the
//!   infinities are their own floor); its analogs are zero, at the jumps too. It reduces an
//!   input by whole turns, so that a law written over one turn holds over every turn:
//!   `let u = phi - 2 * pi * floor(phi / (2 * pi));`, which `wrap(phi, 2 * pi)` writes for you.
//!   `wrap(x, period)` is `x - period * floor(x / period)`, in `[0, period)` but for rounding,
//!   with the analogs of `x` exactly (for a `period` that is a constant or a parameter). It is
//!   `x` itself for `0 <= x < period`; elsewhere it is computed as written, so just below a
//!   multiple of `period` it may come out as `period` itself, and it may miss `[0, period]` by
//!   a few units in the last place of `x`. A law of the wrapped value should therefore agree
//!   at `0` and at `period` (a cam's dwell at both ends does, and `clamp` keeps its argument
//!   in range). A constant `period` must be positive and finite (a compile error otherwise).
//! * A law through these functions may step (a `floor` of the input, a `clamp` whose width
//!   is zero: `clamp((phi - phi0) / 0, 0, 1)` jumps from 0 to 1 at `phi0`); a sweep then stops
//!   at the step, since no mechanism moves through it, and says that a piecewise function may
//!   step there. A corner (a velocity analog that jumps, as at the ends of a uniform-velocity
//!   ramp) is swept through and recorded as an event.
//! * **Angles are in radians** everywhere: in the declaration (`@`, `sin`, `rot`, initial
//!   guesses), in the inputs passed at run time, in every result (`s.q.phi2`, analogs per radian)
//!   and in tables and their CSV files (label the columns with [`Table::with_units`](crate::Table::with_units):
//!   `phi [rad]`). Write an angle in degrees as `deg(30)` in a declaration and as
//!   `kinloop::deg(30.0)` in Rust, and read one in degrees with [`to_deg`](crate::to_deg) or
//!   [`Table::column_deg`](crate::Table::column_deg); `30°` is not valid Rust and does not compile. A guess written in
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
//!   `(x, y)` of unknowns, outputs and constants (`com (x_c, 0)` for a slider; a point that
//!   moves with an input is declared, `point p = (s, 0);`, and named, `com p`), and `turns`
//!   names the input or angle unknown it rotates with (none for a slider). An angle there is
//!   what the unit checks above take for one: an input or unknown that enters a sine or cosine
//!   as a multiple of itself by a constant (`l @ q`, `l @ (q + gamma)`, `sin(2 * q)`,
//!   `l @ (q / 2)`; a length scaled into one, `sin(x / l)`, is not), an unknown that an `eq`
//!   sets to an angle (`eq e: th == atan2(y, x);`, or `asin`, `acos`, `atan`, `angle(v)`, plus
//!   a constant) or to an expression of angles (`eq gear: th == -2 * phi;`, a flywheel geared
//!   to the crank, which turns by so many radians), or one whose value is written in degrees.
//!   A name written as a length elsewhere (a coordinate of a position, the length of `@`) is
//!   an angle only by a whole multiple of it in a sine or an inverse trigonometric function in
//!   an `eq`. `force name at p = (fx, fy);` and
//!   `torque name on angle = scalar;` are loads: expressions of parameters,
//!   inputs and unknowns, evaluated by generated straight-line code. A law is judged by the unit
//!   check as an `output` is (`torque t on psi = x + psi;` and `force f at p = (x, psi);` are
//!   refused); whether it is a force or a torque at all is not: kinloop knows lengths and angles
//!   only, and a law's parameters (a pressure, an area, a stiffness) carry no declared unit, so
//!   a load is in the units its parameters are given in. `gravity (0, -g);` sets
//!   gravity. The macro then generates `m.mass_model()`, the runtime's
//!   [`dynamics::MassModel`](crate::dynamics::MassModel) for the reduced inertia, inverse
//!   dynamics, shaking forces, flywheel and simulation. A negative literal mass or inertia, a
//!   mass that changes with the state, `turns` or `on` a parameter or a length unknown, an
//!   `inertia` without `turns`, and a point with no analogs of its own are compile errors;
//!   negative or non-finite values given at run time are typed errors.
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
//! an equation without unknowns and an input that no equation or output depends on are errors; a
//! parameter that is never used is a warning (name it `_mass` to keep it on purpose). After an
//! error the macro still defines the parameter struct, the named types and the methods (never
//! run: the crate does not compile), so code using them adds no secondary errors.
//!
//! # What is generated
//!
//! For `pub struct Name { ... }`:
//!
//! * `Name`: the parameters as public `f64` fields (and `Default` when every parameter has a
//!   default value, or when there are no parameters), with `param_values()` and
//!   `from_param_values([...])` in declaration order;
//! * `NameInputs<T>`, `NameUnknowns<T>`, `NameOutputs<T>`: named fields (points are
//!   [`Vec2`](crate::Vec2)), convertible from and to arrays (and nalgebra vectors for the
//!   unknowns); with one input, a plain `f64` converts to `NameInputs`, so `m.solve(0.3)` works;
//! * `NameState`: the inputs `input`, positions `q`, velocity analogs `dq`, acceleration analogs
//!   `d2q`, outputs `out`, `dout`, `d2out`, the solver [`SolveReport`](crate::SolveReport), the
//!   blocks' [`Health`](crate::Health) and the same values as a flat [`Kin`](crate::Kin)
//!   (`flat`); `state.motion(omega, eps)` gives true velocities and accelerations (`NameMotion`);
//! * methods on `Name`: `solve(input)`, `kinematics(input, guess)`, `position(input, guess)`,
//!   `kinematics_at(input, q)`, `outputs`, `residual`, `guess`, `check`, `position_with` and
//!   `kinematics_with` taking a [`NewtonConfig`](crate::NewtonConfig), `sweep`, `sweep_at` and
//!   `assembly_modes` (see below), `sensitivities` when requested and `mass_model` when dynamics
//!   is declared;
//!   and the constants `NAME`, `PARAMS`, `INPUTS`, `UNKNOWNS`, `EQUATIONS`, `OUTPUTS`,
//!   `BLOCKS` (the block-triangular decomposition) and `DECOMPOSITION` (the same in words, see
//!   below); and `Mechanism::DRAWING`, what the declaration says about how the mechanism looks
//!   (see [`drawing`](crate::drawing): each loop's chain of points, the partial sums of its
//!   vectors; `l @ q` turning with an input or unknown is a link, a constant vector is the
//!   frame, a Cartesian vector with one moving coordinate a slider; links turning alike are one
//!   plate), which `m.drawing()` of `kinloop::draw` draws;
//! * implementations of [`Mechanism`](crate::Mechanism) (the flat, generated kernels) and
//!   [`Named`](crate::Named) (the same API by name) for generic code. The methods above are the
//!   same for every mechanism: they live once in [`Named`](crate::Named) and the generated ones
//!   only forward to it, so calling them needs no import.
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
//! `Name::BLOCKS` lists the blocks in solve order ([`BlockInfo`](crate::BlockInfo): unknowns,
//! equations, linear), and `Name::DECOMPOSITION` describes them in words: the counts and the
//! mobility, then one line per block with its index (the one error locations use), how it is
//! solved, and its unknowns `<-` its scalar equations (`loop.x`, `loop.y`, or an `eq` name). A
//! block that is a classical Assur group is solved in closed form, without iteration (`closed form,
//! angle equation`: one angle from `a cos q + b sin q = c`; `closed form, RRR dyad`: circle
//! intersection; `closed form, length and angle`: a slotted rocker; `closed form, angle and
//! slider`: an RRP group), on the assembly mode of the guess (the sign of the block's Jacobian
//! determinant there) and on the guess's turn. Where its links fall short of closing the loop it is
//! `NoAssembly`, as Newton; short by no more than the residual tolerance (a limit position rounded
//! past: `0.1 + 0.2 > 0.3` in metres) it is the limit position, in every unit. `linear, NxN` is one
//! linear solve; `Newton, NxN` iterates; `Newton, NxN sparse (K non-zeros)` iterates on a large
//! coupled block (16 unknowns or more, a sparse Jacobian) whose LU follows its sparsity: an
//! elimination order fixed at compile time, every pivot checked at run time, a dense LU where one
//! is weak. Newton ends on the guess's turn too: an angle that enters its block only through sines
//! and cosines of whole multiples of itself (`l @ q`, `l @ (q + gamma)`, `l @ (2 q)`) and that a
//! long step carried more than half a turn out is moved back to its guess's turn and corrected once
//! more there. A far guess can lead Newton into a fold of the residual (a local minimum where no
//! step decreases it, links lying folded against each other) though the loops close elsewhere:
//! there it restarts, with one such angle at a time turned by a quarter turn either way and by a
//! half turn, and returns the root nearest the guess; only when every restart stalls too is the
//! block `NoAssembly` ([`NewtonConfig::restarts`](crate::NewtonConfig::restarts); a sweep's steps
//! never restart). From a far guess Newton may end in either assembly mode; the closed forms keep
//! the guess's. A guess millions of turns out, where doubles are too far apart for an angle to meet
//! the tolerance, is [`Error::TooManyTurns`](crate::Error::TooManyTurns) on both paths.
//! `#[kinloop(dense)]` solves all unknowns as one block with dense LU instead (still in closed form
//! where that one block is an Assur group: add `newton` for Newton), `#[kinloop(newton)]` uses
//! Newton for every nonlinear block (the results are the same; both exist to compare and to debug).
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
//! assert_eq!(SliderCrank::BLOCKS[1].unknowns, &["x"][..]);
//! assert!(SliderCrank::BLOCKS[1].linear);
//! ```
//!
